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


@dataclass(frozen=True)
class _Table:
    """The CSV part of a file: column names (lower case), units, data rows with their lines."""

    name_line: int
    unit_line: int
    names: list[str]
    units: list[str]
    data: list[tuple[int, list[str]]]

    @property
    def lines(self) -> list[int]:
        return [ln for ln, _ in self.data]

    def unit(self, j: int) -> str:
        return self.units[j].strip() if j < len(self.units) else ""


@dataclass(frozen=True)
class _Run:
    """One steady run of a signal: its rows and its whole cycles."""

    row: int  # first data row of the run
    start: int  # row of its first cycle start
    count: int  # samples in its whole cycles
    per_cycle: int  # samples per 720 deg cycle
    step: float  # crank-angle step [rad]
    rows: int  # rows of the run


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
        raise InputErrors([InputError(p.name, f"cannot be read as a UTF-8 CSV file"
                                      f" ({type(exc).__name__}: {exc})")], source=p.name
                          ) from None
    meta, rows = _rows(text)
    station, load, temperature, lines = _metadata(meta, probs)
    table = _table(rows, probs)
    notes = tuple(f"{k}: {v}" for k, (v, _) in sorted(meta.items())
                  if k not in ("station", "load", "damper temperature"))
    common = dict(source=p.name, station=station or "", load=load or "",
                  temperature=temperature, notes=notes)
    if "crank angle" in table.names:
        m = _read_signal(table, probs, orders, common, lines)
    else:
        m = _read_tracks(table, probs, orders, common, lines)
    probs.raise_if_any()
    return m


def _table(rows: list[tuple[int, list[str]]], probs: _Problems) -> _Table:
    """Names in the first row, units in the second, data from the third (raises with the
    problems so far when the file has no such table)."""
    if len(rows) < 2:
        probs.add(rows[0][0] if rows else None,
                  "expected the column names in the first row, their units in the second and"
                  " data from the third; found "
                  + ("no rows" if not rows else "only one row (no unit row: missing units)"))
        probs.raise_if_any()
    (hline, header), (uline, units) = rows[0], rows[1]
    if len(header) == 1 and ";" in header[0]:
        probs.add(hline, "expected columns separated by commas (CSV), found semicolons (a"
                  " spreadsheet's export with a decimal comma: export with '.' and ',')")
        probs.raise_if_any()
    names = [h.strip().lower() for h in header]
    units = units + [""] * (len(names) - len(units))
    given = [u for u in units[: len(names)] if u]
    if given and all(_number(u) is not None for u in given):
        probs.add(uline, "expected the units of the columns in the second row (as the"
                  " workbook's table sheets: e.g. rpm, deg), found numbers: missing units")
        probs.raise_if_any()
    if len(rows) < 3:
        probs.add(uline, "no data rows after the unit row")
        probs.raise_if_any()
    return _Table(hline, uline, names, units, rows[2:])


def _metadata(meta: dict[str, tuple[str, int]], probs: _Problems
              ) -> tuple[str | None, str | None, float | None, dict[str, int]]:
    """Station, load case, damper temperature [K] and the line of each."""
    lines: dict[str, int] = {}
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


def _unit(t: _Table, j: int, kinds: tuple[str, ...], expected: str, probs: _Problems
          ) -> tuple[str, float] | None:
    """(kind, SI factor) of column ``j``'s unit, or None with the problem reported."""
    u = t.unit(j)
    if not u and "dimensionless" not in kinds:
        probs.add(t.unit_line, f"column '{t.names[j]}' has no unit (missing units: expected"
                  f" {expected})")
        return None
    k = _unit_kind(u, kinds)
    if k is None:
        probs.add(t.unit_line, f"column '{t.names[j]}': unit '{u}' is not {expected}")
    return k


def _cells(t: _Table, cols: list[int], probs: _Problems) -> np.ndarray:
    """The numbers of columns ``cols`` (rows, cols); a bad cell is reported (NaN kept)."""
    out = np.full((len(t.data), len(cols)), np.nan)
    for r, (line, cells) in enumerate(t.data):
        for j, c in enumerate(cols):
            text = cells[c] if c < len(cells) else ""
            v = _number(text)
            if v is None:
                probs.add(line, f"column '{t.names[c]}': expected a number, found {_found(text)}"
                          + (" (NaN samples are not accepted: leave the point out)"
                             if text.lower() in ("nan", "inf", "-inf") else ""))
            else:
                out[r, j] = v
    return out


_ANGLE = ("angle",), "an angle (e.g. deg)"
_SPEED = ("speed",), "a speed (e.g. rpm)"


def _track_columns(t: _Table, probs: _Problems) -> dict:
    """The columns of an order-track file: ``speed``, ``total``, ``irregularity`` (index or
    None) and ``amp``/``phase`` ({order: index})."""
    cols: dict = {"speed": None, "total": None, "irregularity": None, "amp": {}, "phase": {}}
    for j, nm in enumerate(t.names):
        if nm in ("speed", "total", "irregularity"):
            cols[nm] = j
        elif (mo := _ORDER.match(nm)) is not None:
            cols["amp"][float(mo.group(1))] = j
        elif (mp := _PHASE.match(nm)) is not None:
            cols["phase"][float(mp.group(1))] = j
        else:
            probs.add(t.name_line, f"unknown column '{nm}': expected speed, order N, order N"
                      " phase, total, irregularity (order tracks) or run speed, crank angle,"
                      " instantaneous speed / vibratory angle (a signal)")
    if cols["speed"] is None:
        probs.add(t.name_line, "no 'speed' column (the engine speed of each row)")
    if not cols["amp"]:
        probs.add(t.name_line, "no 'order N' column (the amplitude of an order)")
    for o in sorted(cols["phase"]):
        if o not in cols["amp"]:
            probs.add(t.name_line, f"column 'order {o:g} phase' without 'order {o:g}'")
    for o in sorted(cols["amp"]):
        if abs(2 * o - round(2 * o)) > 1e-9 or o <= 0:
            probs.add(t.name_line, f"column 'order {o:g}': orders are positive multiples of"
                      " 0.5 (4-stroke half orders)")
    return cols


def _read_tracks(t: _Table, probs: _Problems, asked: list[float] | None, common: dict,
                 lines: dict[str, int]) -> Measurement:
    cols = _track_columns(t, probs)
    amp_cols, phase_cols = cols["amp"], cols["phase"]
    conv: dict[int, tuple[str, float] | None] = {}
    if cols["speed"] is not None:
        conv[cols["speed"]] = _unit(t, cols["speed"], *_SPEED, probs)
    for j in amp_cols.values():
        conv[j] = _unit(t, j, ("angle", "speed"),
                        "an angle (e.g. deg) or a speed amplitude (e.g. rpm)", probs)
    for j in [*phase_cols.values(), cols["total"]]:
        if j is not None:
            conv[j] = _unit(t, j, *_ANGLE, probs)
    if cols["irregularity"] is not None:
        conv[cols["irregularity"]] = _unit(t, cols["irregularity"], ("dimensionless",),
                                           "% or - (a ratio)", probs)
    probs.raise_if_any()
    orders = sorted(amp_cols)
    if asked:
        for o in asked:
            if o not in amp_cols:
                probs.add(t.name_line, f"order {o:g} asked (--orders) has no column"
                          f" 'order {o:g}'")
        orders = sorted(set(asked) & set(amp_cols))
    lines.update({f"order {o:g}": t.name_line for o in orders})
    vals = _cells(t, [cols["speed"]] + [amp_cols[o] for o in orders], probs)
    speed = vals[:, 0] * conv[cols["speed"]][1]
    _check_speeds(t, vals[:, 0], speed, cols["speed"], probs)
    amp = np.empty((len(t.data), len(orders)))
    for i, o in enumerate(orders):
        j = amp_cols[o]
        a = vals[:, 1 + i]
        for r in np.nonzero(np.isfinite(a) & (a < 0))[0]:
            probs.add(t.lines[r], f"column '{t.names[j]}': an amplitude is >= 0, found"
                      f" {a[r]:g}")
        kind, f = conv[j]
        amp[:, i] = a * f if kind == "angle" else a * f / (o * speed)
    probs.raise_if_any()
    notes = list(common.pop("notes"))
    coeffs = None
    with_phase = [o for o in orders if o in phase_cols]
    if orders and len(with_phase) == len(orders):
        pc = [phase_cols[o] for o in orders]
        ph = _cells(t, pc, probs) * np.array([conv[c][1] for c in pc])
        # a speed amplitude's phase leads the angle's by 90 deg: Theta = W / (j n w)
        shift = np.array([0.0 if conv[amp_cols[o]][0] == "angle" else -np.pi / 2
                          for o in orders])
        coeffs = amp * np.exp(1j * (ph + shift))
    elif with_phase:
        notes.append(f"phases given for {len(with_phase)} of {len(orders)} orders: not used"
                     " (the synthesis needs every order's phase)")
    total = irr = None
    if cols["total"] is not None:
        total = _cells(t, [cols["total"]], probs)[:, 0] * conv[cols["total"]][1]
    if cols["irregularity"] is not None:
        c = cols["irregularity"]
        irr = _cells(t, [c], probs)[:, 0] * conv[c][1]
    return Measurement(kind=TRACKS, speeds=speed, orders=np.array(orders, dtype=float),
                       amplitude=amp, coeffs=coeffs, total=total, irregularity=irr,
                       lines=lines, speed_lines=tuple(t.lines), notes=tuple(notes), **common)


def _check_speeds(t: _Table, raw: np.ndarray, speed: np.ndarray, col: int,
                  probs: _Problems) -> None:
    """Speeds > 0 and strictly increasing, each problem at its line."""
    u = t.unit(col)
    for r in range(len(t.data)):
        if not np.isfinite(speed[r]):
            continue
        if speed[r] <= 0:
            probs.add(t.lines[r], f"speed: expected > 0, found {raw[r]:g}")
        elif r and np.isfinite(speed[r - 1]) and speed[r] <= speed[r - 1]:
            probs.add(t.lines[r], f"speed {raw[r]:g} {u} is not above the previous row's"
                      f" {raw[r - 1]:g}: the speeds must increase (non-monotone speed)")


_SIGNAL_COLUMNS = {"run speed": _SPEED, "crank angle": _ANGLE, "instantaneous speed": _SPEED,
                   "vibratory angle": _ANGLE}


def _signal_columns(t: _Table, probs: _Problems) -> tuple[dict[str, int], dict[str, float]]:
    """{column: index} and {column: SI factor} of a signal file."""
    col: dict[str, int] = {}
    for j, nm in enumerate(t.names):
        if nm in _SIGNAL_COLUMNS:
            col[nm] = j
        else:
            probs.add(t.name_line, f"unknown column '{nm}' in a signal file: expected run"
                      " speed, crank angle and instantaneous speed or vibratory angle")
    for need in ("run speed", "crank angle"):
        if need not in col:
            probs.add(t.name_line, f"no '{need}' column")
    sig = [k for k in ("instantaneous speed", "vibratory angle") if k in col]
    if len(sig) != 1:
        probs.add(t.name_line, "expected one signal column, 'instantaneous speed' or"
                  f" 'vibratory angle'; found {len(sig) or 'none'}")
    factor = {}
    for k, j in col.items():
        got = _unit(t, j, *_SIGNAL_COLUMNS[k], probs)
        if got is not None:
            factor[k] = got[1]
    probs.raise_if_any()
    return col, factor


def _signal_run(t: _Table, a: int, b: int, speed_text: str, run_speed: float,
                angle: np.ndarray, probs: _Problems) -> _Run | None:
    """Rows ``a:b`` as one run: equal crank-angle steps dividing 720 deg, a cycle start, at
    least :data:`~checker.correlation.order_analysis.MIN_CYCLES` whole cycles (or None with
    the problem reported)."""
    line = t.lines[a]
    if run_speed <= 0:
        probs.add(line, f"run speed: expected > 0, found {speed_text}")
        return None
    th = angle[a:b]
    if th.size < 2:
        probs.add(line, f"run at {speed_text}: one sample; too few cycles for any order")
        return None
    steps = np.diff(th)
    step = float(np.median(steps))
    if step <= 0 or np.any(np.abs(steps - step) > 1e-6 * abs(step) + 1e-12):
        r = int(np.argmax(np.abs(steps - step))) + 1
        probs.add(t.lines[a + r], f"run at {speed_text}: crank angle must increase in equal"
                  f" steps ({np.degrees(step):g} deg), found {np.degrees(steps[r - 1]):g} deg")
        return None
    per = oa.CYCLE / step
    n = int(round(per))
    if abs(per - n) > 1e-6 * per:
        probs.add(line, f"run at {speed_text}: the crank-angle step {np.degrees(step):g} deg"
                  " does not divide the 720 deg cycle")
        return None
    off = (-th[0]) % oa.CYCLE  # to the first cycle start (a multiple of 720 deg)
    first = int(round(off / step))
    if abs(off - first * step) > 1e-6 * step and abs(off - oa.CYCLE) > 1e-6 * step:
        probs.add(line, f"run at {speed_text}: no sample at a cycle start (crank angle a"
                  " multiple of 720 deg, cylinder 1 firing TDC)")
        return None
    first %= n
    cycles = (th.size - first) // n
    if cycles < oa.MIN_CYCLES:
        probs.add(line, f"run at {speed_text}: {cycles} whole 720 deg cycle"
                  f"{'s' if cycles != 1 else ''} ({np.degrees(th[-1] - th[0] + step):g} deg of"
                  " crank angle); too few cycles for the half orders: the order analysis"
                  f" needs at least {oa.MIN_CYCLES} whole cycles per run")
        return None
    return _Run(row=a, start=a + first, count=cycles * n, per_cycle=n, step=step, rows=b - a)


def _signal_runs(t: _Table, raw_speed: np.ndarray, run_speed: np.ndarray, angle: np.ndarray,
                 unit: str, probs: _Problems) -> list[_Run]:
    """Contiguous rows of one run speed, the run speeds increasing; each run checked."""
    n = len(t.data)
    starts = [0] + [r for r in range(1, n) if run_speed[r] != run_speed[r - 1]]
    runs = []
    for a, b in zip(starts, starts[1:] + [n]):
        if a and run_speed[a] <= run_speed[a - 1]:
            probs.add(t.lines[a], f"run speed {raw_speed[a]:g} {unit} after a run at"
                      f" {raw_speed[a - 1]:g}: the runs must follow each other at increasing"
                      " speeds (non-monotone speed)")
        run = _signal_run(t, a, b, f"{raw_speed[a]:g} {unit}", float(run_speed[a]), angle,
                          probs)
        if run is not None:
            runs.append(run)
    probs.raise_if_any()
    return runs


def _signal_orders(t: _Table, runs: list[_Run], raw_speed: np.ndarray, unit: str,
                   asked: list[float] | None, probs: _Problems) -> np.ndarray:
    """The orders asked (each resolved by every run), or every half order up to the lowest
    highest order of the runs and :data:`DEFAULT_MAX_ORDER`."""
    top = min(oa.highest_order(r.per_cycle) for r in runs)
    if not asked:
        return 0.5 * np.arange(1, int(2 * min(top, DEFAULT_MAX_ORDER)) + 1)
    orders = np.array(sorted(asked), dtype=float)
    for r in runs:
        h = oa.highest_order(r.per_cycle)
        if orders.max() > h + 1e-9:
            probs.add(t.lines[r.row], f"run at {raw_speed[r.row]:g} {unit}: order"
                      f" {orders.max():g} asked but {r.per_cycle} samples per cycle resolve"
                      f" orders up to {h:g}")
    probs.raise_if_any()
    return orders


def _read_signal(t: _Table, probs: _Problems, asked: list[float] | None, common: dict,
                 lines: dict[str, int]) -> Measurement:
    col, factor = _signal_columns(t, probs)
    signal = "instantaneous speed" if "instantaneous speed" in col else "vibratory angle"
    keys = ["run speed", "crank angle", signal]
    vals = _cells(t, [col[k] for k in keys], probs)
    probs.raise_if_any()
    run_speed = vals[:, 0] * factor["run speed"]
    x = vals[:, 2] * factor[signal]
    unit = t.unit(col["run speed"])
    runs = _signal_runs(t, vals[:, 0], run_speed, vals[:, 1] * factor["crank angle"], unit,
                        probs)
    orders = _signal_orders(t, runs, vals[:, 0], unit, asked, probs)
    speeds, coeffs, analyses, irr = [], [], [], []
    for r in runs:
        seg = x[r.start:r.start + r.count]
        spec = oa.order_spectrum(seg, r.per_cycle, orders)
        if signal == "instantaneous speed":
            w = spec.mean
            theta = oa.angle_from_speed(spec.coeffs, orders, w)
            scale = 1.0 / (orders * w)
            avg = seg.reshape(-1, r.per_cycle).mean(axis=0)  # the cycle-averaged speed
            irr.append(float((avg.max() - avg.min()) / w))
        else:
            w = float(run_speed[r.row])
            theta, scale = spec.coeffs, np.ones_like(orders)
        speeds.append(w)
        coeffs.append(theta)
        analyses.append(RunAnalysis(
            speed=w, cycles=spec.cycles, samples_per_cycle=r.per_cycle, step=r.step,
            highest_order=oa.highest_order(r.per_cycle), dropped=r.rows - r.count,
            scatter=spec.scatter * scale, leakage=spec.leakage * scale, line=t.lines[r.row]))
    c = np.array(coeffs)
    return Measurement(kind=SIGNAL, speeds=np.array(speeds), orders=orders,
                       amplitude=np.abs(c), coeffs=c, total=None,
                       irregularity=np.array(irr) if irr else None,
                       lines=dict(lines, **{f"order {o:g}": t.name_line for o in orders}),
                       speed_lines=tuple(a.line for a in analyses), runs=tuple(analyses),
                       **common)
