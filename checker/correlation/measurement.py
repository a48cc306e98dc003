"""Reading a measurement file for ``checker correlate`` (units at the edge, SI inside).

Two formats, both CSV with ``# key: value`` lines for what the measurement is, then the column
names in the first row and their units in the second (as the workbook's table sheets), data
from the third (docs/correlation.md):

* **order tracks**: ``speed`` and per order ``order N`` (the 0-to-peak amplitude of the
  station's angle, or of its speed: ``rpm``), optionally ``order N phase``, ``total`` (the
  synthesis, half peak-to-peak) and ``irregularity``;
* **angle-domain signal**: ``run speed``, ``crank angle`` and ``instantaneous speed`` or
  ``vibratory angle`` sampled at equal crank-angle steps at several steady speeds; the order
  analysis is done here (:mod:`checker.correlation.order_analysis`).

Every problem of the file is reported at once, each at ``file:line`` with what was expected and
what was found (:class:`checker.errors.InputErrors`); nothing is computed from a bad file.
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, InputErrors
from ..workbook.units import UnitProblem, to_si
from . import order_analysis as oa

LOADS = ("full", "no")
"""Load cases a measurement can be at (the torsion module's cases)."""
STATION_WORDS = ("crank nose", "damper ring", "flywheel")
"""The named stations (TVModel roles) a measurement is usually taken at; a TVModel station
name is accepted too."""
TRACKS = "order tracks"
SIGNAL = "angle-domain signal"
DEFAULT_MAX_ORDER = 24.0
"""Highest order analysed from a signal by default (the torsion module's highest order)."""

_ORDER = re.compile(r"^order\s+([0-9]+(?:\.[0-9]*)?)$")
_PHASE = re.compile(r"^order\s+([0-9]+(?:\.[0-9]*)?)\s+phase$")
_QUANTITY = re.compile(r"^\s*([-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)\s*(.*?)\s*$")


@dataclass(frozen=True)
class RunAnalysis:
    """How one steady run of a signal was analysed (for the report)."""

    speed: float  # mean speed of the run [rad/s]
    cycles: int  # whole 720 deg cycles averaged
    samples_per_cycle: int
    step: float  # crank-angle step [rad]
    highest_order: float  # highest order below the Nyquist bin [-]
    dropped: int  # samples before the first and after the last whole cycle, left out
    scatter: np.ndarray  # (O,) cycle-to-cycle std of the angle amplitude [rad]
    leakage: np.ndarray  # (O,) leakage bound of the drift [rad]
    line: int  # first data line of the run


@dataclass(frozen=True)
class Measurement:
    """A measurement at one station and load case, as order amplitudes of the station's angle.

    ``amplitude`` is the 0-to-peak amplitude of the station's angle relative to a node turning
    at the mean speed, per order, the quantity of :mod:`checker.calc.torsional`; ``coeffs``
    the complex coefficients where phases are known (an analysed signal, or ``order N phase``
    columns for every order).
    """

    source: str  # file name
    kind: str  # TRACKS or SIGNAL
    station: str
    load: str
    speeds: np.ndarray  # (S,) [rad/s], strictly increasing
    orders: np.ndarray  # (O,) [-]
    amplitude: np.ndarray  # (S, O) [rad]
    coeffs: np.ndarray | None  # (S, O) complex [rad]
    total: np.ndarray | None  # (S,) measured synthesis, half peak-to-peak [rad]
    irregularity: np.ndarray | None  # (S,) (w_max - w_min) / w_mean [-]
    temperature: float | None  # damper temperature [K]
    lines: dict = field(default_factory=dict)  # where: "station", "load", "order" -> line
    speed_lines: tuple[int, ...] = ()  # (S,) line of each speed (first line of a run)
    runs: tuple[RunAnalysis, ...] = ()  # signal: the order analysis of each run
    notes: tuple[str, ...] = ()  # other '# key: value' lines, as written

    def where(self, what: str) -> str:
        """``file:line`` of a header item (``station``, ``load``, ``order 4``...)."""
        line = self.lines.get(what)
        return f"{self.source}:{line}" if line else self.source


class _Problems:
    def __init__(self, name: str):
        self.name = name
        self.errors: list[InputError] = []

    def add(self, line: int | None, message: str) -> None:
        where = f"{self.name}:{line}" if line else self.name
        self.errors.append(InputError(where, message))

    def raise_if_any(self) -> None:
        if self.errors:
            raise InputErrors(self.errors, source=self.name)


def _rows(text: str) -> tuple[dict[str, tuple[str, int]], list[tuple[int, list[str]]]]:
    """Metadata ``{key: (value, line)}`` and the CSV rows with their line numbers."""
    meta: dict[str, tuple[str, int]] = {}
    rows: list[tuple[int, list[str]]] = []
    for i, raw in enumerate(text.splitlines(), start=1):
        s = raw.strip()
        if not s:
            continue
        if s.startswith("#"):
            body = s.lstrip("#").strip()
            if ":" in body:
                k, v = body.split(":", 1)
                meta[k.strip().lower()] = (v.strip(), i)
            continue
        rows.append((i, [c.strip() for c in next(csv.reader(io.StringIO(raw)))]))
    return meta, rows


def _number(text: str) -> float | None:
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def _found(text: str) -> str:
    return "an empty cell" if not text else f"'{text}'"


def read_measurement(path: str | Path, orders: list[float] | None = None) -> Measurement:
    """Read and check a measurement file (raises :class:`InputErrors` with every problem).

    ``orders``: the orders asked (``--orders``); default: the file's order columns (tracks) or
    every half order up to :data:`DEFAULT_MAX_ORDER` and the signal's highest order (signal).
    """
    p = Path(path)
    probs = _Problems(p.name)
    try:
        text = p.read_bytes().decode("utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        probs.add(None, f"cannot be read as a UTF-8 CSV file ({type(exc).__name__}: {exc})")
        probs.raise_if_any()
        raise AssertionError from None  # pragma: no cover
    meta, rows = _rows(text)
    station, load, temperature, lines = _metadata(meta, probs)
    if len(rows) < 2:
        probs.add(rows[0][0] if rows else None,
                  "expected the column names in the first row, their units in the second and"
                  " data from the third; found "
                  + ("no rows" if not rows else "only one row (no unit row: missing units)"))
        probs.raise_if_any()
    (hline, header), (uline, units) = rows[0], rows[1]
    names = [h.strip().lower() for h in header]
    units = units + [""] * (len(names) - len(units))
    if names and all(_number(u) is not None for u in units[: len(names)] if u):
        if any(units[: len(names)]):
            probs.add(uline, "expected the units of the columns in the second row (as the"
                      " workbook's table sheets: e.g. rpm, deg), found numbers: missing units")
            probs.raise_if_any()
    data = rows[2:]
    if not data:
        probs.add(uline, "no data rows after the unit row")
        probs.raise_if_any()
    notes = tuple(f"{k}: {v}" for k, (v, _) in sorted(meta.items())
                  if k not in ("station", "load", "damper temperature"))
    common = dict(source=p.name, station=station or "", load=load or "",
                  temperature=temperature, notes=notes)
    if "crank angle" in names:
        m = _read_signal(names, units, uline, data, probs, orders, common, lines)
    else:
        m = _read_tracks(names, units, hline, uline, data, probs, orders, common, lines)
    probs.raise_if_any()
    return m


def _metadata(meta: dict[str, tuple[str, int]], probs: _Problems
              ) -> tuple[str | None, str | None, float | None, dict]:
    lines = {}
    station = None
    if "station" not in meta or not meta["station"][0]:
        probs.add(meta.get("station", ("", None))[1],
                  "missing '# station: ...' line: the station measured (crank nose, damper"
                  " ring, flywheel or a TVModel station name)")
    else:
        station, lines["station"] = meta["station"]
    load = None
    if "load" not in meta:
        probs.add(None, "missing '# load: full' or '# load: no' line (the load case measured)")
    else:
        v, line = meta["load"]
        lines["load"] = line
        v = v.strip().lower().removesuffix(" load").strip()
        if v not in LOADS:
            probs.add(line, f"load: expected 'full' or 'no', found '{meta['load'][0]}'")
        else:
            load = v
    temperature = None
    if "damper temperature" in meta:
        v, line = meta["damper temperature"]
        lines["damper temperature"] = line
        mm = _QUANTITY.match(v)
        if not mm:
            probs.add(line, f"damper temperature: expected a number and a unit (e.g. 80 °C),"
                      f" found '{v}'")
        elif not mm.group(2):
            probs.add(line, f"damper temperature: '{v}' has no unit (missing units: e.g. °C)")
        else:
            try:
                temperature = to_si(float(mm.group(1)), mm.group(2), "temperature")
            except UnitProblem as exc:
                probs.add(line, f"damper temperature: {exc}")
    return station, load, temperature, lines


def _unit_kind(unit: str, kinds: tuple[str, ...]) -> tuple[str, float] | None:
    """(kind, SI factor) of the first of ``kinds`` the unit converts to."""
    for k in kinds:
        try:
            return k, to_si(1.0, unit, k)
        except UnitProblem:
            continue
    return None


def _cells(data, cols: list[int], labels: list[str], probs: _Problems) -> np.ndarray:
    """The numbers of columns ``cols`` (rows, cols); a bad cell is reported (NaN kept)."""
    out = np.full((len(data), len(cols)), np.nan)
    for r, (line, cells) in enumerate(data):
        for j, c in enumerate(cols):
            t = cells[c] if c < len(cells) else ""
            v = _number(t)
            if v is None:
                probs.add(line, f"column '{labels[j]}': expected a number, found {_found(t)}"
                          + (" (NaN samples are not accepted: leave the point out)"
                             if t.lower() in ("nan", "inf", "-inf") else ""))
            else:
                out[r, j] = v
    return out


def _read_tracks(names, units, hline, uline, data, probs: _Problems, asked, common, lines
                 ) -> Measurement:
    amp_cols: dict[float, int] = {}
    phase_cols: dict[float, int] = {}
    speed_col = total_col = irr_col = None
    for j, nm in enumerate(names):
        if nm == "speed":
            speed_col = j
        elif nm == "total":
            total_col = j
        elif nm == "irregularity":
            irr_col = j
        elif (mo := _ORDER.match(nm)) is not None:
            amp_cols[float(mo.group(1))] = j
        elif (mp := _PHASE.match(nm)) is not None:
            phase_cols[float(mp.group(1))] = j
        else:
            probs.add(hline, f"unknown column '{names[j]}': expected speed, order N, order N"
                      " phase, total, irregularity (order tracks) or run speed, crank angle,"
                      " instantaneous speed / vibratory angle (a signal)")
    if speed_col is None:
        probs.add(hline, "no 'speed' column (the engine speed of each row)")
    if not amp_cols:
        probs.add(hline, "no 'order N' column (the amplitude of an order)")
    for o in sorted(phase_cols):
        if o not in amp_cols:
            probs.add(hline, f"column 'order {o:g} phase' without 'order {o:g}'")
    for o in sorted(amp_cols):
        if abs(2 * o - round(2 * o)) > 1e-9 or o <= 0:
            probs.add(hline, f"column 'order {o:g}': orders are positive multiples of 0.5"
                      " (4-stroke half orders)")
        lines[f"order {o:g}"] = hline
    # units
    conv: dict[int, tuple[str, float]] = {}

    def unit_of(j: int, kinds: tuple[str, ...], expected: str) -> None:
        u = units[j].strip() if j < len(units) else ""
        if not u and "dimensionless" not in kinds:
            probs.add(uline, f"column '{names[j]}' has no unit (missing units: expected"
                      f" {expected})")
            return
        k = _unit_kind(u, kinds)
        if k is None:
            probs.add(uline, f"column '{names[j]}': unit '{u}' is not {expected}")
        else:
            conv[j] = k

    if speed_col is not None:
        unit_of(speed_col, ("speed",), "a speed (e.g. rpm)")
    for j in amp_cols.values():
        unit_of(j, ("angle", "speed"), "an angle (e.g. deg) or a speed amplitude (e.g. rpm)")
    for j in phase_cols.values():
        unit_of(j, ("angle",), "an angle (e.g. deg)")
    if total_col is not None:
        unit_of(total_col, ("angle",), "an angle (e.g. deg)")
    if irr_col is not None:
        unit_of(irr_col, ("dimensionless",), "% or - (a ratio)")
    if probs.errors:
        probs.raise_if_any()
    file_orders = np.array(sorted(amp_cols), dtype=float)
    if asked:
        missing = [o for o in asked if o not in amp_cols]
        for o in missing:
            probs.add(hline, f"order {o:g} asked (--orders) has no column 'order {o:g}'")
        file_orders = np.array(sorted(set(asked) & set(amp_cols)), dtype=float)
    cols = [speed_col] + [amp_cols[o] for o in file_orders]
    vals = _cells(data, cols, [names[c] for c in cols], probs)
    speed = vals[:, 0] * conv[speed_col][1]
    data_lines = [ln for ln, _ in data]
    for r in range(1, len(data)):
        if np.isfinite(speed[r]) and np.isfinite(speed[r - 1]) and speed[r] <= speed[r - 1]:
            probs.add(data_lines[r], f"speed {vals[r, 0]:g} {units[speed_col]} is not above the"
                      f" previous row's {vals[r - 1, 0]:g}: the speeds must increase"
                      " (non-monotone speed)")
    for r in range(len(data)):
        if np.isfinite(speed[r]) and speed[r] <= 0:
            probs.add(data_lines[r], f"speed: expected > 0, found {vals[r, 0]:g}")
    amp = np.empty((len(data), file_orders.size))
    for i, o in enumerate(file_orders):
        j = amp_cols[o]
        a = vals[:, 1 + i]
        bad = np.isfinite(a) & (a < 0)
        for r in np.nonzero(bad)[0]:
            probs.add(data_lines[r], f"column '{names[j]}': an amplitude is >= 0, found"
                      f" {a[r]:g}")
        kind, f = conv[j]
        amp[:, i] = a * f if kind == "angle" else a * f / (o * speed)
    if probs.errors:
        probs.raise_if_any()
    coeffs = None
    if file_orders.size and all(o in phase_cols for o in file_orders):
        pc = [phase_cols[o] for o in file_orders]
        ph = _cells(data, pc, [names[c] for c in pc], probs)
        ph = ph * np.array([conv[c][1] for c in pc])
        # a speed amplitude's phase leads the angle's by 90 deg: Theta = W / (j n w)
        shift = np.array([0.0 if conv[amp_cols[o]][0] == "angle" else -np.pi / 2
                          for o in file_orders])
        coeffs = amp * np.exp(1j * (ph + shift))
    total = None
    if total_col is not None:
        total = _cells(data, [total_col], ["total"], probs)[:, 0] * conv[total_col][1]
    irr = None
    if irr_col is not None:
        irr = _cells(data, [irr_col], ["irregularity"], probs)[:, 0] * conv[irr_col][1]
    return Measurement(kind=TRACKS, speeds=speed, orders=file_orders, amplitude=amp,
                       coeffs=coeffs, total=total, irregularity=irr, lines=lines,
                       speed_lines=tuple(data_lines), **common)


def _read_signal(names, units, uline, data, probs: _Problems, asked, common, lines
                 ) -> Measurement:
    hline = uline - 1
    want = {"run speed": ("speed", "a speed (e.g. rpm)"),
            "crank angle": ("angle", "an angle (e.g. deg)"),
            "instantaneous speed": ("speed", "a speed (e.g. rpm)"),
            "vibratory angle": ("angle", "an angle (e.g. deg)")}
    col: dict[str, int] = {}
    for j, nm in enumerate(names):
        if nm in want:
            col[nm] = j
        else:
            probs.add(hline, f"unknown column '{nm}' in a signal file: expected run speed, crank"
                      " angle and instantaneous speed or vibratory angle")
    for need in ("run speed", "crank angle"):
        if need not in col:
            probs.add(hline, f"no '{need}' column")
    sig = [k for k in ("instantaneous speed", "vibratory angle") if k in col]
    if len(sig) != 1:
        probs.add(hline, "expected one signal column, 'instantaneous speed' or 'vibratory"
                  f" angle'; found {len(sig) or 'none'}")
    factor: dict[str, float] = {}
    for k, j in col.items():
        kind, expected = want[k]
        u = units[j].strip() if j < len(units) else ""
        if not u:
            probs.add(uline, f"column '{k}' has no unit (missing units: expected {expected})")
            continue
        try:
            factor[k] = to_si(1.0, u, kind)
        except UnitProblem:
            probs.add(uline, f"column '{k}': unit '{u}' is not {expected}")
    probs.raise_if_any()
    signal = sig[0]
    keys = ["run speed", "crank angle", signal]
    vals = _cells(data, [col[k] for k in keys], keys, probs)
    probs.raise_if_any()
    run_speed = vals[:, 0] * factor["run speed"]
    angle = vals[:, 1] * factor["crank angle"]
    x = vals[:, 2] * factor[signal]
    data_lines = [ln for ln, _ in data]
    # runs: contiguous rows of one run speed, the run speeds increasing
    starts = [0] + [r for r in range(1, len(data)) if run_speed[r] != run_speed[r - 1]]
    bounds = list(zip(starts, starts[1:] + [len(data)]))
    for a, _ in bounds[1:]:
        if run_speed[a] <= run_speed[a - 1]:
            probs.add(data_lines[a], f"run speed {vals[a, 0]:g} {units[col['run speed']]}"
                      f" after a run at {vals[a - 1, 0]:g}: the runs must follow each other"
                      " at increasing speeds (non-monotone speed)")
    runs: list[tuple[int, int, int, float, int]] = []  # (first, count, N, step, rows)
    for a, b in bounds:
        line = data_lines[a]
        rpm_text = f"{vals[a, 0]:g} {units[col['run speed']]}"
        if run_speed[a] <= 0:
            probs.add(line, f"run speed: expected > 0, found {vals[a, 0]:g}")
            continue
        th = angle[a:b]
        if th.size < 2:
            probs.add(line, f"run at {rpm_text}: one sample; too few cycles for any order")
            continue
        steps = np.diff(th)
        step = float(np.median(steps))
        if step <= 0 or np.any(np.abs(steps - step) > 1e-6 * abs(step) + 1e-12):
            r = int(np.argmax(np.abs(steps - step))) + 1
            probs.add(data_lines[a + r], f"run at {rpm_text}: crank angle must increase in"
                      f" equal steps ({np.degrees(step):g} deg), found"
                      f" {np.degrees(steps[r - 1]):g} deg")
            continue
        per = oa.CYCLE / step
        n = int(round(per))
        if abs(per - n) > 1e-6 * per:
            probs.add(line, f"run at {rpm_text}: the crank-angle step {np.degrees(step):g} deg"
                      " does not divide the 720 deg cycle")
            continue
        # first sample of a cycle: crank angle a multiple of 720 deg
        off = (-th[0]) % oa.CYCLE
        first = int(round(off / step))
        if abs(off - first * step) > 1e-6 * step and abs(off - oa.CYCLE) > 1e-6 * step:
            probs.add(line, f"run at {rpm_text}: no sample at a cycle start (crank angle a"
                      " multiple of 720 deg, cylinder 1 firing TDC)")
            continue
        first = first % n
        cycles = (th.size - first) // n
        if cycles < oa.MIN_CYCLES:
            probs.add(line, f"run at {rpm_text}: {cycles} whole 720 deg cycle"
                      f"{'s' if cycles != 1 else ''} ({np.degrees(th[-1] - th[0] + step):g}"
                      f" deg of crank angle); too few cycles for the half orders: the order"
                      f" analysis needs at least {oa.MIN_CYCLES} whole cycles per run")
            continue
        runs.append((a + first, cycles * n, n, step, b - a))
    probs.raise_if_any()
    top = min(oa.highest_order(r[2]) for r in runs)
    if asked:
        orders = np.array(sorted(asked), dtype=float)
        for (_first, _count, n, _step, _rows), (ra, _) in zip(runs, bounds):
            h = oa.highest_order(n)
            if orders.max() > h + 1e-9:
                probs.add(data_lines[ra], f"run at {vals[ra, 0]:g}"
                          f" {units[col['run speed']]}: order {orders.max():g} asked but"
                          f" {n} samples per cycle resolve orders up to {h:g}")
        bad = [o for o in orders if o <= 0 or abs(2 * o - round(2 * o)) > 1e-9]
        for o in bad:
            probs.add(None, f"order {o:g} asked: orders are positive multiples of 0.5")
        probs.raise_if_any()
    else:
        orders = 0.5 * np.arange(1, int(2 * min(top, DEFAULT_MAX_ORDER)) + 1)
    speeds, coeffs, analyses, irr = [], [], [], []
    for a, count, n, step, rows in runs:
        seg = x[a:a + count]
        spec = oa.order_spectrum(seg, n, orders)
        if signal == "instantaneous speed":
            w = spec.mean
            theta = oa.angle_from_speed(spec.coeffs, orders, w)
            scale = 1.0 / (orders * w)
            irr.append(float((seg.reshape(-1, n).mean(0).max()
                              - seg.reshape(-1, n).mean(0).min()) / w))
        else:
            w = float(run_speed[a])
            theta = spec.coeffs
            scale = np.ones_like(orders)
            irr.append(np.nan)
        speeds.append(w)
        coeffs.append(theta)
        analyses.append(RunAnalysis(
            speed=w, cycles=spec.cycles, samples_per_cycle=n, step=step,
            highest_order=oa.highest_order(n), dropped=rows - count, scatter=spec.scatter * scale,
            leakage=spec.leakage * scale, line=data_lines[a]))
    c = np.array(coeffs)
    irregularity = np.array(irr) if signal == "instantaneous speed" else None
    return Measurement(kind=SIGNAL, speeds=np.array(speeds), orders=orders,
                       amplitude=np.abs(c), coeffs=c, total=None, irregularity=irregularity,
                       lines=dict(lines, **{f"order {o:g}": hline for o in orders}),
                       speed_lines=tuple(r.line for r in analyses), runs=tuple(analyses),
                       **common)
