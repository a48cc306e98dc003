"""Typed engine description in SI units, built from a workbook or directly in Python.

This is the boundary between the workbook (cells, units, text) and the calculations (SI
floats). Cross-sheet consistency is checked here; every problem names its cell.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..errors import InputError, InputErrors
from ..workbook.loader import WorkbookData
from ..workbook.schema import SHEETS
from .crank_input import CrankGeometry


class Params(dict):
    """Read-only mapping of one parameter sheet (SI values, ``None`` when blank)."""

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError as exc:  # pragma: no cover - programming error
            raise AttributeError(name) from exc


@dataclass(frozen=True)
class Cylinder:
    number: int
    throw_angle: float  # [rad]
    firing_angle: float  # [rad] after cylinder 1 fires, 0..4 pi
    bank_angle: float = 0.0  # [rad]
    pin: int = 0  # crank pin (throw) number, 1-based


@dataclass(frozen=True)
class Bearing:
    name: str
    type: str  # "main" | "big end"
    diameter: float  # [m]
    length: float  # effective length [m]
    clearance: float  # radial [m]
    journal_length: float | None = None
    groove: str = "none"
    groove_width: float | None = None
    groove_start: float | None = None
    groove_end: float | None = None
    oil_feed: str | None = None
    oil_holes: int = 0
    oil_hole_type: str | None = None
    oil_hole_diameter: float | None = None
    oil_hole_angle: float | None = None
    lining: str | None = None
    max_film_temperature: float | None = None  # [K], supplier limit
    max_film_pressure: float | None = None  # [Pa], supplier limit
    min_oil_flow: float | None = None  # [m^3/s], supplier limit
    support_stiffness: float | None = None  # [N/m] main bearings, continuous beam
    support_offset: float | None = None  # [m] main bearings, continuous beam (block y)
    index: int = 0  # main number (1..) or big-end number (1..)
    row: int = -1  # data-row index in sheet Bearings


@dataclass(frozen=True)
class MassItem:
    location: str
    throw: int
    kind: str
    mass: float
    x: float
    y: float
    z: float
    axial: float
    reference: str  # "main axis" | "pin axis"


@dataclass(frozen=True)
class TVStation:
    """One station of the torsional chain; ``cylinders`` are the cylinders whose excitation
    acts on it (one for an in-line engine, both of a crank pin in the usual V model)."""

    station: str
    role: str
    inertia: float
    cylinders: tuple[int, ...] = ()
    absolute_damping: float = 0.0
    stiffness: float | None = None
    relative_damping: float = 0.0
    element: str = "shaft"  # what joins it to the next station: "shaft" | "flexible coupling"

    @property
    def cylinder(self) -> int | None:
        """The first cylinder on the station (``None`` without one)."""
        return self.cylinders[0] if self.cylinders else None


@dataclass(frozen=True)
class Joint:
    name: str
    location: str
    bolts: int
    diameter: float
    pitch: float
    property_class: str
    tightening: str
    face_outer: float
    face_inner: float
    stress_area_coefficient: float | None = None
    tightening_torque: float | None = None
    nut_factor: float | None = None
    preload_fraction: float | None = None
    rp02: float | None = None
    proof_load_stress: float | None = None
    head_outer: float | None = None
    head_inner: float | None = None
    clamped_material: str | None = None
    friction: float | None = None
    row: int = -1  # data-row index in sheet Joints (for cell addresses)


@dataclass(frozen=True)
class JointTorque:
    joint: str
    point: str  # "tv peak" | "max power" | "overspeed"
    torque: float  # [N m]
    speed: float | None = None  # [rad/s]


@dataclass(frozen=True)
class RuleOverride:
    rule: str
    limit: str
    unit: str | None
    reason: str
    where: str = ""


@dataclass
class Engine:
    """The whole engine description (SI). Optional parts are empty when not given."""

    params: Params
    cylinders: tuple[Cylinder, ...] = ()
    bearings: tuple[Bearing, ...] = ()
    crank_mass: tuple[MassItem, ...] = ()
    tv_model: tuple[TVStation, ...] = ()
    joints: tuple[Joint, ...] = ()
    joint_torques: tuple[JointTorque, ...] = ()
    peak_pressure: tuple[tuple[str, float, float], ...] = ()  # (case, speed rad/s, p Pa)
    pressure_traces: tuple[tuple[str, float, float, float], ...] = ()  # case, speed, angle, p
    brake_torque: tuple[tuple[float, float], ...] = ()  # (speed rad/s, torque N m)
    oil: Params = field(default_factory=Params)
    damper: Params = field(default_factory=Params)
    #: Sheet Coupling (and CouplingTemperature as ``temperature_table``, ((T [K], stiffness
    #: factor, damping factor, temperature factor), ...)), empty when not given.
    coupling: Params = field(default_factory=Params)
    #: Sheet Driven: the driven machine (generator, propeller), empty when not given.
    driven: Params = field(default_factory=Params)
    fatigue: Params = field(default_factory=Params)
    overrides: tuple[RuleOverride, ...] = ()
    source: str = "<in memory>"
    sha256: str = ""
    where: dict[tuple, str] = field(default_factory=dict)
    assumptions: tuple[str, ...] = ()  # workbook values marked as assumptions (with cells)
    estimates: tuple[str, ...] = ()  # workbook values marked ESTIMATE (sized by a rule)
    #: The crank's geometry (sheets Crank, CrankEnds), None without a Crank sheet.
    crank: CrankGeometry | None = None
    #: Values of the crank model derived from the geometry or typed over it, with their
    #: origins (:class:`checker.description.crank_derive.ModelValue`); empty without a Crank sheet.
    crank_model: tuple = ()
    #: Inputs that can be computed with but are unusual for a crank-train engine (value
    #: outside a field's usual range, a very fine speed grid...), each with its cell.
    warnings: tuple[InputError, ...] = ()

    @property
    def name(self) -> str:
        return str(self.params.get("name") or "engine")

    @property
    def offsets(self) -> dict[str, float]:
        """Cylinder and pin offsets [m] as the kinematics take them: the cylinder offset
        along ``+t`` and the pin offset towards the major thrust side positive (the
        workbook's documented convention; :mod:`checker.calc.kinematics`)."""
        p = self.params
        return {"cylinder_offset": float(p.get("cylinder_offset") or 0.0),
                "pin_offset": float(p.get("pin_offset") or 0.0)}

    def cell(self, sheet: str, attr: str, row: int | None = None) -> str:
        """Cell address of an input (for messages), or the sheet name when unknown."""
        key = (sheet, attr) if row is None else (sheet, row, attr)
        return self.where.get(key, sheet)

    def describe_missing(self, sheet: str, attr: str, row: int | None = None,
                         what: str = "") -> str:
        """A 'missing input' text naming the cell (or sheet and column) to fill in."""
        spec = SHEETS[sheet]
        f = next((x for x in spec.fields if x.attr == attr), None)
        label = f.label if f else attr
        where = self.cell(sheet, attr, row)
        if where == sheet:
            where = f"{sheet} ({'column' if spec.shape == 'table' else 'parameter'} '{label}')"
        return f"{where}: {label}{' of ' + what if what else ''}{_unit_words(f)}"


def _unit_words(f) -> str:
    """What to type in a missing input cell: " (a length, e.g. mm)", " (a number, no unit)"."""
    from ..workbook.units import KINDS

    if f is None or f.kind not in KINDS:
        return ""
    if f.kind in ("dimensionless", "ratio"):
        return " (a number, no unit)"
    k = KINDS[f.kind]
    return f" ({k.name.replace('_', ' ')}, e.g. {k.example})"


def _rows(data: WorkbookData, sheet: str) -> list[dict[str, Any]]:
    return data.tables.get(sheet, [])


def _firing_order(text: str) -> list[int] | None:
    parts = [p for p in str(text).replace(",", "-").replace(" ", "-").split("-") if p]
    try:
        return [int(p) for p in parts]
    except ValueError:
        return None


_LD_VALID = (0.02, 5.0)  # bearing effective length / diameter: error outside
_LD_USUAL = (0.1, 1.5)  # warning outside (engine bearings are about 0.2..0.6)
_PIN_TOL = 1e-6  # [rad] cylinders on one pin: as checker.calc.crank_forces.throw_angles
_THROW_TOL = math.radians(0.05)  # [rad] throw angle vs firing/bank angles (rounded entries)
_TWO_PI = 2.0 * math.pi


def _angle_diff(a: float, b: float) -> float:
    """Smallest absolute difference of two angles [rad] (modulo 2 pi)."""
    d = (a - b) % _TWO_PI
    return min(d, _TWO_PI - d)


def _rpm(omega: float) -> str:
    """A speed [rad/s] as the workbook's users read it."""
    return f"{omega * 30.0 / math.pi:.6g} rpm"


def _mm(length: float) -> str:
    """A length [m] in mm."""
    return f"{length * 1e3:.6g} mm"


def _celsius(t: float) -> str:
    """A temperature [K] in °C."""
    return f"{t - 273.15:.6g} °C"


def _deg(a: float) -> str:
    return f"{math.degrees(a):.6g} deg"


def _even_firing(angles: list[float]) -> bool:
    """True when the firing angles [rad] are evenly spaced over the 720 deg cycle."""
    n = len(angles)
    if n < 2:
        return True
    a = sorted(x % (2 * _TWO_PI) for x in angles)
    gaps = [b - c for b, c in zip(a[1:] + [a[0] + 2 * _TWO_PI], a)]
    return all(abs(g - 2 * _TWO_PI / n) <= _THROW_TOL for g in gaps)


def check_cylinders(cylinders: list[Cylinder], row_of: dict[int, int],
                    err: Callable[[str, str, int | None, str], None],
                    cell: Callable[[str, int], str] | None = None) -> None:
    """Cross-check the Cylinders sheet: crank pins, shared pins and throw angles.

    Convention of the calculations (:func:`checker.calc.crank_forces.throw_angles`, module
    docstring of :mod:`checker.calc.crank_forces`): crank angle 0 is the firing TDC of
    cylinder 1, and the throw of cylinder ``i`` (bank angle ``alpha_i``, firing angle
    ``phi_i``) points at crank-frame angle ``gamma_i = alpha_i - phi_i`` (mod 360 deg),
    measured in the direction of rotation: at crank angle ``phi_i`` that throw lies on the
    cylinder's axis (4-stroke: firing TDC every 720 deg, throw direction modulo 360 deg).
    The workbook's throw angle is measured from throw 1 in the direction of rotation, so it must
    equal ``gamma_i - gamma_(throw 1)`` (mod 360 deg); cylinders sharing a crank pin (V engines)
    must give the same ``gamma``. ``row_of`` maps the cylinder number to its data row index;
    ``cell(attr, row)`` names a cell (``Cylinders!C4``) for messages that name two.

    A throw angle that contradicts its firing angle names both cells and says which to change:
    the firing angle when the others fire at even intervals and this one breaks them while the
    value the throw implies keeps them (cell of the error: the firing angle); the throw angle
    when the firing angles are evenly spaced (the error at the throw angle); otherwise either,
    with both values.
    """
    def gamma(c: Cylinder) -> float:
        return (c.bank_angle - c.firing_angle) % _TWO_PI

    by_pin: dict[int, list[Cylinder]] = {}
    for c in sorted(cylinders, key=lambda c: c.number):
        by_pin.setdefault(c.pin, []).append(c)
    first = next((c for c in cylinders if c.number == 1), None)
    if first is not None and _angle_diff(first.firing_angle, 0.0) > 1e-9:
        err("Cylinders", "firing_angle", row_of[1], "cylinder 1 fires at 0 deg by definition"
            " (firing angles are crank angles after cylinder 1 fires), found"
            f" {_deg(first.firing_angle)}")
    n_pins = max(by_pin, default=0)
    empty = [j for j in range(1, n_pins + 1) if j not in by_pin]
    if empty:
        c = next(c for c in cylinders if c.pin == n_pins)
        err("Cylinders", "pin", row_of[c.number], f"crank pins must be numbered 1..{n_pins}"
            f" without gaps: pin {', '.join(map(str, empty))} carries no cylinder")
    shared_ok = True
    for pin, cs in by_pin.items():
        g0 = gamma(cs[0])
        for c in cs[1:]:
            if _angle_diff(gamma(c), g0) > _PIN_TOL:
                shared_ok = False
                want = (cs[0].firing_angle + c.bank_angle - cs[0].bank_angle) % _TWO_PI
                err("Cylinders", "firing_angle", row_of[c.number],
                    f"cylinders {cs[0].number} and {c.number} share crank pin {pin}, so their"
                    " firing angles must differ by the difference of their bank angles"
                    f" ({_deg(c.bank_angle - cs[0].bank_angle)}): expected {_deg(want)} or"
                    f" {_deg(want + _TWO_PI)}, found {_deg(c.firing_angle)}")
    if not shared_ok or 1 not in by_pin:
        return
    ref = gamma(by_pin[1][0])
    firing = {c.number: c.firing_angle for c in cylinders}
    even_now = _even_firing(list(firing.values()))
    for c in sorted(cylinders, key=lambda c: c.number):
        expected = (gamma(c) - ref) % _TWO_PI
        if _angle_diff(c.throw_angle, expected) <= _THROW_TOL:
            continue
        row = row_of[c.number]
        # the firing angles the throw angle implies (4-stroke: two, 360 deg apart)
        f0 = (c.bank_angle - ref - c.throw_angle) % _TWO_PI
        keeps_even = [f for f in (f0, f0 + _TWO_PI)
                      if _even_firing([*(v for k, v in firing.items() if k != c.number), f])]
        why = (f"cylinder {c.number} (crank pin {c.pin}, bank {_deg(c.bank_angle)}) fires"
               f" {_deg(c.firing_angle)} after cylinder 1, so its throw is at"
               f" {_deg(expected)} from throw 1 in the direction of rotation (throw = bank"
               " angle - firing angle, relative to throw 1, modulo 360 deg)")
        if cell is None:
            b_ref, c_ref = "the throw angle", "the firing angle"
        else:
            b_ref, c_ref = cell("throw_angle", row), cell("firing_angle", row)
        if not even_now and keeps_even:
            err("Cylinders", "firing_angle", row,
                f"firing angle {_deg(c.firing_angle)} contradicts the throw angle"
                f" {_deg(c.throw_angle)} ({b_ref}): {why}. The firing angles are not evenly spaced"
                f" and would be with this one at {_deg(keeps_even[0])}: change this firing angle"
                f" to {_deg(keeps_even[0])} (or {b_ref} to {_deg(expected)} if the crank"
                " changed)")
        elif even_now:
            err("Cylinders", "throw_angle", row,
                f"throw angle {_deg(c.throw_angle)} contradicts the firing and bank angles"
                f" ({c_ref}): {why}. The firing angles are evenly spaced: change this throw"
                f" angle to {_deg(expected)} (or {c_ref} if the firing order changed)")
        else:
            err("Cylinders", "throw_angle", row,
                f"throw angle {_deg(c.throw_angle)} contradicts the firing and bank angles"
                f" ({c_ref}): {why}. Change one of the two: this throw angle to"
                f" {_deg(expected)}, or {c_ref} to {_deg(f0)} or {_deg(f0 + _TWO_PI)}")


def check_traces(rows: list[dict[str, Any]], err: Callable[[str, str, int | None, str], None]
                 ) -> None:
    """Check every pressure trace (one per load case and speed) as the calculation will use it.

    The same conditions as :func:`checker.calc.pressure.interpolate_trace`, with the cells:
    at least 8 points, distinct crank angles, at most one 720 deg cycle (a duplicated end point
    at first + 720 deg must repeat the first pressure within 2 % of the peak), and no gap
    above :data:`checker.calc.pressure.MAX_TRACE_GAP` (10 deg; exactly 10 deg passes) between
    neighbouring points, including the wrap-around from the last point to the first.
    """
    from ..calc.pressure import MAX_TRACE_GAP

    groups: dict[tuple[str, float], list[tuple[float, float, int]]] = {}
    for i, r in enumerate(rows):
        if None in (r["case"], r["speed"], r["crank_angle"], r["pressure"]):
            continue
        groups.setdefault((r["case"], round(r["speed"], 9)), []).append(
            (r["crank_angle"], r["pressure"], i))
    cycle = 2 * _TWO_PI
    tol = 1e-9 * cycle
    for (case, speed), pts in groups.items():
        what = f"{case} load trace at {speed * 60 / _TWO_PI:.6g} rpm"
        pts.sort()
        if len(pts) < 8:
            err("PressureTraces", "crank_angle", pts[0][2], f"the {what} has {len(pts)} points;"
                " at least 8 are needed (one 720 deg cycle, at most 10 deg apart)")
            continue
        dup = next((k for k in range(1, len(pts)) if pts[k][0] - pts[k - 1][0] <= 0), None)
        if dup is not None:
            err("PressureTraces", "crank_angle", pts[dup][2], f"the {what} has two points at"
                f" crank angle {_deg(pts[dup][0])}")
            continue
        span = pts[-1][0] - pts[0][0]
        if span > cycle + tol:
            err("PressureTraces", "crank_angle", pts[-1][2], f"the {what} spans {_deg(span)},"
                " more than one 720 deg cycle; give one cycle")
            continue
        if span > cycle - tol:  # duplicated end point
            peak = max(p for _, p, _ in pts)
            if abs(pts[-1][1] - pts[0][1]) > 0.02 * peak:
                err("PressureTraces", "pressure", pts[-1][2], f"the {what} is not periodic: the"
                    f" end point at {_deg(pts[-1][0])} repeats the start but its pressure"
                    " differs from the first by more than 2 % of the peak")
                continue
            pts = pts[:-1]
        for k in range(len(pts)):
            a0 = pts[k - 1][0] if k else pts[-1][0] - cycle
            gap = pts[k][0] - a0
            if gap > MAX_TRACE_GAP * (1.0 + 1e-9):
                before = pts[k - 1] if k else pts[-1]
                err("PressureTraces", "crank_angle", pts[k][2], f"the {what} has a gap of"
                    f" {_deg(gap)} between crank angles {_deg(before[0])} and"
                    f" {_deg(pts[k][0])} (wrapped over the 720 deg cycle where needed); at most"
                    " 10 deg between points")
                break


def check_speed_grid(p: Params, peak_pressure: list[tuple[str, float, float]],
                     err: Callable[[str, str, int | None, str], None],
                     warn: Callable[[str, str, int | None, str], None]) -> None:
    """Number of swept speeds (as :func:`checker.modules.loads.speed_sweep` builds them)."""
    from ..workbook.schema import DEFAULT_SPEED_STEP_RPM, MAX_SPEEDS, USUAL_SPEEDS

    full = sorted(s for c, s, _ in peak_pressure if c == "full")
    lo = p.get("speed_min") or (full[0] if full else None)
    hi = p.get("speed_max") or (full[-1] if full else None)
    step = p.get("speed_step") or DEFAULT_SPEED_STEP_RPM * _TWO_PI / 60.0
    if lo is None or hi is None or hi <= lo:
        return
    n = math.floor((hi - lo) / step + 1e-9) + 3  # grid, maximum speed, overspeed
    rpm = 60.0 / _TWO_PI
    text = (f"the speed grid {lo * rpm:.6g}..{hi * rpm:.6g} rpm in steps of"
            f" {step * rpm:.6g} rpm has {n if n < 1e15 else float(n):.6g} speeds")
    if n > MAX_SPEEDS:
        err("Engine", "speed_step", None, f"{text}; at most {MAX_SPEEDS} can be computed (the"
            " run time grows with every speed): use a larger speed step")
    elif n > USUAL_SPEEDS:
        warn("Engine", "speed_step", None, f"{text}, more than the usual {USUAL_SPEEDS}: the"
             " check takes correspondingly longer")


MASS_PLANE_FRACTION = 0.15
"""Without a web thickness (sheet Fatigue), a web's or counterweight's centre of mass more than
15 % of the main journal spacing from its plane is taken as outside it: half the thickest
usual web (webs are 15-30 % of the spacing; the examples: 22.3/96 and 25/130 mm)."""


def check_mass_planes(rows: list[dict[str, Any]], p: Params, fatigue: Params,
                      bearings: list[Bearing], where: dict[tuple, str],
                      warn: Callable[[str, str, int | None, str], None]) -> None:
    """Warn where a CrankMass centre of mass lies axially outside its component.

    ``X`` is the axial offset of the centre of mass from the component's plane (a web's
    mid-plane); a web or counterweight cannot have it beyond half its thickness (Fatigue 'Web
    full thickness', else 'Web reduced thickness', else :data:`MASS_PLANE_FRACTION` of the main
    journal spacing), a crank pin not beyond half the pin length (the big-end journal length,
    the whole pin also when it carries two rods; else a quarter of the spacing). A lateral
    coordinate entered in X instead of Z is the usual cause: the centrifugal force then acts in
    the wrong direction and off its plane.
    """
    spacing = p.get("main_spacing")
    t = fatigue.get("web_full_thickness") or fatigue.get("web_thickness")
    t_attr = "web_full_thickness" if fatigue.get("web_full_thickness") else "web_thickness"
    if t is not None:
        web_bound = t / 2.0
        web_why = (f"half the web thickness {t * 1e3:.4g} mm"
                   f" ({where.get(('Fatigue', t_attr), 'Fatigue')})")
    elif spacing is not None:
        web_bound = MASS_PLANE_FRACTION * spacing
        web_why = (f"{MASS_PLANE_FRACTION * 100:.0f} % of the main journal spacing, half the"
                   " thickest usual web (no web thickness on sheet Fatigue)")
    else:
        web_bound, web_why = None, ""
    lengths = [b.journal_length for b in bearings if b.type == "big end" and b.journal_length]
    for i, r in enumerate(rows):
        x, kind = r.get("x"), r.get("kind")
        if x is None or kind is None:
            continue
        if kind == "pin":
            if lengths:
                bound = 0.5 * max(lengths)
                why = f"half the crank pin (big-end journal) length {max(lengths) * 1e3:.4g} mm"
            elif spacing is not None:
                bound, why = 0.25 * spacing, "a quarter of the main journal spacing"
            else:
                continue
        else:
            if web_bound is None:
                continue
            bound, why = web_bound, web_why
        if abs(x) > bound * (1.0 + 1e-9):
            what = {"web": "web", "counterweight": "counterweight", "pin": "crank pin"}[kind]
            warn("CrankMass", "x", i, f"X = {x * 1e3:.4g} mm puts the centre of mass of"
                 f" '{r.get('location')}' axially outside the {what} (|X| above {why}); X is"
                 " the axial offset of the centre of mass from the component's plane: a"
                 " lateral position in the crank frame belongs in Z")


def check_oil(oil: Params, err: Callable[[str, str, int | None, str], None]) -> None:
    """The oil data must give a viscosity curve that holds at the film temperature."""
    from ..calc import viscosity as vs

    fit, what = None, ""
    if oil.get("kv40") is not None and oil.get("kv100") is not None:
        dens = oil.get("density")
        try:
            fit = vs.vogel_from_datasheet(oil["kv40"], oil["kv100"],
                                          dens if dens is not None else vs.DENSITY_15C_DEFAULT,
                                          oil.get("hths"))
        except (ValueError, ArithmeticError) as exc:
            err("Oil", "kv40", None, "the datasheet values (kinematic viscosities at 40 and"
                " 100 °C, density, HTHS) do not give a Vogel viscosity curve: " + str(exc))
            return
        what = "the datasheet"
    elif oil.get("grade"):
        try:
            fit = vs.vogel_from_j300(str(oil["grade"]), basis="minimum")
        except (ValueError, KeyError):
            err("Oil", "grade", None, f"'{oil['grade']}' is not an SAE J300 grade (e.g. 0W20,"
                " 5W30, 15W40, 40); give it, or the kinematic viscosities at 40 and 100 °C")
            return
        what = f"grade {oil['grade']}"
    t = oil.get("supply_temperature")
    if fit is None or t is None:
        return
    t_film = t + (oil.get("temperature_rise") or 0.0)
    if not t_film > fit.c + 1.0:
        err("Oil", "supply_temperature", None, f"the film temperature {t_film - 273.15:.4g} °C"
            f" is at or below the Vogel temperature {fit.c - 273.15:.4g} °C of the oil"
            f" ({what}), where its viscosity curve has no value")


class _Problems:
    """The errors and warnings of one workbook, collected across every sheet's builder (all
    problems are reported in one pass), each located by its cell.

    Causes, not their consequences: a cell the loader rejected (a value out of range, a wrong
    unit, a text where a number belongs) leaves its row out of the sheet's data. A cross-check
    that counts or matches that sheet's rows (``needs``: the crank pins of ``Cylinders`` for
    the throws of ``CrankMass``) would then report problems that exist only because the row is
    missing ("throw 3 does not exist (the engine has 2 crank pins)"). An error whose ``needs``
    name a sheet with a rejected cell is therefore held back (counted in ``follow_on``, said
    in one line): the cause is reported once, and the cross-check runs again on the corrected
    workbook."""

    def __init__(self, data: WorkbookData):
        self.where = data.where
        self.errors: list[InputError] = list(data.errors)
        self.warnings: list[InputError] = list(data.warnings)
        self.rejected = {e.where.split("!", 1)[0] for e in data.errors}
        self.follow_on = 0
        self._error_cells: set[str] = set(data.refused)
        self._indexed = 0

    def _at(self, sheet: str, attr: str, row: int | None) -> str:
        key = (sheet, attr) if row is None else (sheet, row, attr)
        return self.where.get(key, sheet)

    def _follows(self, needs: tuple[str, ...]) -> bool:
        if any(n in self.rejected for n in needs):
            self.follow_on += 1
            return True
        return False

    def err(self, sheet: str, attr: str, row: int | None, msg: str,
            needs: tuple[str, ...] = ()) -> None:
        """An error at a cell; ``needs``: the sheets whose every row the check relies on."""
        if not self._follows(needs):
            self.errors.append(InputError(self._at(sheet, attr, row), msg))

    def blank_required(self, sheet: str, attr: str, row: int | None, msg: str) -> None:
        """A required cell left blank (unless its cell already has an error: a value the
        loader refused is blank here)."""
        where = self._at(sheet, attr, row)
        for e in self.errors[self._indexed:]:  # errors added since the last call
            self._error_cells.add(e.where)
        self._indexed = len(self.errors)
        if where not in self._error_cells:
            self.errors.append(InputError(where, msg))

    def cell(self, sheet: str, attr: str, row: int | None = None) -> str:
        """The ``Sheet!A1`` address of a value (the sheet's name when it has none)."""
        return self._at(sheet, attr, row)

    def refused(self, sheet: str, attr: str, row: int | None) -> bool:
        """Whether the loader refused the cell's value (an error at the cell or at its
        column's unit cell): the cell is blank to the builders, its problem reported."""
        where = self._at(sheet, attr, row)
        return where in self._error_cells or any(e.where == where for e in self.errors)

    def warn(self, sheet: str, attr: str, row: int | None, msg: str) -> None:
        self.warnings.append(InputError(self._at(sheet, attr, row), msg))

    def sheet_error(self, sheet: str, msg: str, needs: tuple[str, ...] = ()) -> None:
        """A problem of a whole sheet (no single cell)."""
        if not self._follows(needs):
            self.errors.append(InputError(sheet, msg))


def build_engine(data: WorkbookData,
                 check_overrides: Callable[[list[RuleOverride]], list[InputError]] | None = None
                 ) -> Engine:
    """Build and cross-check the typed engine from converted workbook data: one builder per
    sheet (``_cylinders``, ``_bearings``...), each adding its problems to one list, so every
    problem of the workbook is reported at once.

    ``check_overrides`` validates the RuleOverrides rows against the rule table in use; its
    problems are reported together with every other problem of the workbook.
    """
    pr = _Problems(data)
    p = Params(data.params["Engine"])
    cylinders, complete = _cylinders(data, p, pr)
    _engine_geometry(p, pr)
    crank = _crank(data, p, cylinders, pr)
    rows = _crank_rows(data, crank, cylinders, pr)
    has_crank = "Crank" in data.sheets_present  # its problems are reported on sheet Crank
    bearings = _bearings(rows["Bearings"], pr, has_crank)
    fatigue = rows["Fatigue"]
    crank_mass = _crank_mass(data, p, cylinders, complete, bearings, pr, rows["CrankMass"],
                             fatigue, rows["where"])
    tv = _tv_model(rows["TVModel"], p, pr, has_crank,
                   data.params.get("Damper", {}).get("damper_type") == "viscous")
    joints = _joints(data, pr)
    jt = _joint_torques(data, joints, pr)
    pk = _peak_pressure(data, pr)
    check_traces(_rows(data, "PressureTraces"), pr.err)
    check_speed_grid(p, pk, pr.err, pr.warn)
    traces = tuple((r["case"], r["speed"], r["crank_angle"], r["pressure"])
                   for r in _rows(data, "PressureTraces")
                   if None not in (r["case"], r["speed"], r["crank_angle"], r["pressure"]))
    bt = _brake_torque(data, pr)
    _support_scheme(p, bearings, crank, pr)
    check_oil(Params(data.params.get("Oil", {})), pr.err)
    damper = _damper(data, pr)
    coupling = _coupling(data, tv, pr)
    driven = _driven(data, tv, pr)
    overrides = _overrides(data, pr)
    if check_overrides is not None:
        pr.errors += check_overrides(overrides)
    if pr.errors:
        raise InputErrors(pr.errors, pr.warnings, follow_on=pr.follow_on)
    return Engine(
        params=p, cylinders=tuple(sorted(cylinders, key=lambda c: c.number)),
        bearings=tuple(bearings), crank_mass=crank_mass, tv_model=tuple(tv),
        joints=tuple(joints), joint_torques=tuple(jt), peak_pressure=tuple(pk),
        pressure_traces=traces, brake_torque=tuple(sorted(bt)),
        oil=Params(data.params.get("Oil", {})), damper=damper, coupling=coupling,
        driven=driven, fatigue=fatigue, overrides=tuple(overrides),
        source=data.path, sha256=data.sha256, where=dict(data.where),
        assumptions=tuple(data.assumptions), estimates=tuple(data.estimates),
        warnings=tuple(pr.warnings), crank=crank, crank_model=tuple(rows["model"]),
    )


def _support_scheme(p: Params, bearings: list[Bearing], crank: CrankGeometry | None,
                    pr: _Problems) -> None:
    """Engine 'Main bearing supports' against what it needs: a continuous beam needs the crank's
    geometry (sheet Crank); elastic supports a stiffness for every main; support values on a
    big end or under the determinate scheme are refused (they would be ignored)."""
    scheme = p.get("support_scheme") or "determinate"
    continuous = scheme.startswith("continuous beam")
    if continuous and crank is None:
        pr.err("Engine", "support_scheme", None, f"'{scheme}' needs the crank's dimensions"
               " (sheet Crank: each throw's bending stiffness follows from them); give sheet"
               " Crank or choose 'determinate'")
    for b in bearings:
        for attr in ("support_stiffness", "support_offset"):
            if getattr(b, attr) is None:
                continue
            if b.type != "main":
                pr.err("Bearings", attr, b.row, "a support value applies to main bearings"
                       " only (the crank's supports); leave it blank on a big end")
            elif not continuous:
                pr.err("Bearings", attr, b.row, f"{attr.replace('_', ' ')} is used by the"
                       " continuous-beam schemes only; Engine 'Main bearing supports' is"
                       f" '{scheme}': choose a continuous beam or leave this cell blank")
            elif attr == "support_stiffness" and scheme != "continuous beam, elastic supports":
                pr.err("Bearings", attr, b.row, "support stiffness is used by 'continuous"
                       " beam, elastic supports' only (rigid supports have none)")
    if p.get("support_stiffness") is not None and scheme != "continuous beam, elastic supports":
        pr.err("Engine", "support_stiffness", None, "support stiffness is used by 'continuous"
               f" beam, elastic supports' only; 'Main bearing supports' is '{scheme}'")
    mains = [b for b in bearings if b.type == "main"]
    if scheme == "continuous beam, elastic supports" and p.get("support_stiffness") is None:
        if all(b.support_stiffness is None for b in mains):
            pr.err("Engine", "support_scheme", None, f"'{scheme}' needs the radial stiffness of"
                   " the main bearings' supports: give Engine 'Main bearing support stiffness'"
                   " (all mains, e.g. 1e6 N/mm) or Bearings 'support stiffness' per main",
                   needs=("Engine",))
            mains = []
        for b in mains:
            if b.support_stiffness is None:
                pr.err("Bearings", "support_stiffness", b.row, "'continuous beam, elastic"
                       " supports' needs a radial support stiffness for every main: give"
                       " Engine 'Main bearing support stiffness' (all mains) or this cell,"
                       " e.g. 1e6 N/mm", needs=("Engine",))


SPACING_SLIP = 0.05
"""A throw's length (main journal + 2 webs + pin) more than 5 % from the main journal spacing
is a warning (a slip: recesses, thrust faces and rounding explain a few percent)."""


def _crank(data: WorkbookData, p: Params, cylinders: list[Cylinder], pr: _Problems
           ) -> CrankGeometry | None:
    """Sheets Crank and CrankEnds: the crank's geometry, checked (None without sheet Crank)."""
    from .crank_input import build_crank

    rows = _rows(data, "Crank")
    n_pins = max((c.pin for c in cylinders), default=0)
    if not rows and "Crank" in data.sheets_present:
        pr.sheet_error("Crank", "the sheet has no data row: expected a row 'all' (column"
                       " 'throw', from row 3) with the dimensions every throw shares, or one"
                       " row per throw" + (f" (1..{n_pins}: the engine has {n_pins} throws)"
                                           if n_pins else "") + "; or remove sheets Crank"
                       " and CrankEnds and type the crank's values in Bearings, Fatigue and"
                       " TVModel", needs=("Crank",))  # (not after the loader's 'empty sheet')
        return None
    if not rows:
        for attr, v in data.params.get("CrankEnds", {}).items():
            if v is not None:
                pr.err("CrankEnds", attr, None, "sheet CrankEnds needs sheet Crank (the"
                       " crank's throws)")
                break
        return None
    crank = build_crank(rows, dict(data.params.get("CrankEnds", {})), n_pins, p.get("stroke"),
                        data.where, pr.err, pr.sheet_error, pr.blank_required,
                        lambda i, attr: pr.refused("Crank", attr, i))
    if crank is not None and p.get("main_spacing") is not None:
        for t in crank.throws:
            if abs(t.length - p["main_spacing"]) > SPACING_SLIP * p["main_spacing"]:
                pr.warn("Engine", "main_spacing", None, f"main journal spacing"
                        f" {p['main_spacing'] * 1e3:.6g} mm differs from throw {t.number}'s"
                        f" length {t.length * 1e3:.6g} mm (main journal + 2 webs + pin,"
                        f" {crank.cell('journal_length', t.number)},"
                        f" {crank.cell('web_thickness', t.number)},"
                        f" {crank.cell('pin_length', t.number)})")
                break
    return crank


def _crank_rows(data: WorkbookData, crank: CrankGeometry | None, cylinders: list[Cylinder],
                pr: _Problems) -> dict[str, Any]:
    """The rows of Bearings, Fatigue, CrankMass and TVModel as the analyses use them: without
    a crank the workbook's own (unchanged); with one, completed from its geometry
    (:mod:`checker.description.crank_derive`), a typed value winning, and the model values'
    origins."""
    out: dict[str, Any] = {
        "Bearings": _rows(data, "Bearings"), "CrankMass": _rows(data, "CrankMass"),
        "TVModel": _rows(data, "TVModel"),
        "Fatigue": Params(data.params.get("Fatigue", {})), "model": [], "where": data.where}
    if crank is None:
        return out
    from . import crank_derive as cd

    pin_of = {c.number: c.pin for c in cylinders}
    bearings = [dict(r) for r in out["Bearings"]]
    model = cd.bearings_from_crank(bearings, crank, pin_of, data.where, pr.err)
    filled: dict[tuple, str] = {}
    fatigue, fatigue_model = cd.fatigue_from_crank(dict(out["Fatigue"]), crank, pr.err,
                                                   data.where, filled)
    model += fatigue_model
    typed_throws = {r["throw"] for r in out["CrankMass"] if r.get("throw") is not None}
    gamma = {}
    for c in sorted(cylinders, key=lambda c: c.number):
        gamma.setdefault(c.pin, c.throw_angle)
    crank_mass = list(out["CrankMass"]) + cd.crank_mass_rows(crank, gamma, typed_throws)
    tv = [dict(r) for r in out["TVModel"]]
    stiff = cd.throw_stiffness(crank, gamma)
    model += cd.tv_from_crank(
        tv, crank, data.params["Engine"], pin_of, data.where, pr.blank_required, stiff,
        pr.warn, data.params.get("Damper", {}).get("damper_type") == "viscous")
    out.update(Bearings=bearings, Fatigue=Params(fatigue), CrankMass=crank_mass, TVModel=tv,
               model=model, stiffness=stiff, where={**data.where, **filled})
    return out


def _cylinders(data: WorkbookData, p: Params, pr: _Problems) -> tuple[list[Cylinder], bool]:
    """Sheet Cylinders (with the Engine sheet's cylinder count and firing order): the
    cylinders, and whether every row was complete."""
    err = pr.err
    n_cyl = p.get("cylinders")
    cyl_rows = _rows(data, "Cylinders")
    cylinders = []
    row_of: dict[int, int] = {}
    complete = True
    for i, r in enumerate(cyl_rows):
        if r["cylinder"] is None or r["throw_angle"] is None or r["firing_angle"] is None:
            complete = False
            continue
        fa = r["firing_angle"]
        if not (0 <= fa < 4 * math.pi + 1e-12):
            err("Cylinders", "firing_angle", i, "firing angle must be in 0..720 deg, found"
                f" {math.degrees(fa):g} deg")
        row_of.setdefault(r["cylinder"], i)
        cylinders.append(Cylinder(r["cylinder"], r["throw_angle"], fa % (4 * math.pi),
                                  r["bank_angle"] or 0.0, r["pin"] or r["cylinder"]))
    if complete and cylinders and len(row_of) == len(cylinders):
        check_cylinders(cylinders, row_of, err,
                        lambda attr, row: pr._at("Cylinders", attr, row))
    if n_cyl is not None and cyl_rows and len(cyl_rows) != n_cyl:
        pr.sheet_error("Cylinders", f"{len(cyl_rows)} cylinder rows but Engine says"
                       f" {n_cyl} cylinders ({data.where.get(('Engine', 'cylinders'))})")
    numbers = sorted(c.number for c in cylinders)
    if n_cyl is not None and cylinders and numbers != list(range(1, len(cylinders) + 1)):
        pr.sheet_error("Cylinders", f"cylinders must be numbered 1..{len(cylinders)},"
                       f" found {numbers}", needs=("Cylinders",))
    fo_text = p.get("firing_order")
    if fo_text is not None:
        fo = _firing_order(fo_text)
        if fo is None or (n_cyl is not None and sorted(fo) != list(range(1, n_cyl + 1))):
            err("Engine", "firing_order", None, f"firing order '{fo_text}' must list each of"
                f" cylinders 1..{n_cyl} once, e.g. 1-3-4-2")
        elif cylinders and len(cylinders) == len(fo):
            by_angle = [c.number for c in sorted(cylinders, key=lambda c: c.firing_angle)]
            if by_angle != fo:
                pr.sheet_error(
                    "Cylinders", f"firing angles give the firing order"
                    f" {'-'.join(map(str, by_angle))}, but Engine says '{fo_text}'"
                    f" ({data.where.get(('Engine', 'firing_order'))})", needs=("Cylinders",))
    return cylinders, complete


def _engine_geometry(p: Params, pr: _Problems) -> None:
    """Sheet Engine: the speed range and the slider-crank geometry are consistent."""
    err = pr.err
    smin, smax = p.get("speed_min"), p.get("speed_max")
    if smin is not None and smax is not None and smin >= smax:
        err("Engine", "speed_max", None, f"maximum speed {_rpm(smax)} must be above the"
            f" minimum speed {_rpm(smin)} ({pr.cell('Engine', 'speed_min', None)})")
    if p.get("stroke") is not None and p.get("rod_length") is not None:
        offsets = abs(p.get("cylinder_offset") or 0.0) + abs(p.get("pin_offset") or 0.0)
        if p["rod_length"] <= p["stroke"] / 2:
            err("Engine", "rod_length", None, "connecting rod length must exceed half the"
                " stroke (crank radius)")
        elif p["stroke"] / 2 + offsets >= p["rod_length"]:
            # the slider geometry (checker.calc.kinematics) needs r + |offsets| < l
            worst = "cylinder_offset" if abs(p.get("cylinder_offset") or 0.0) >= abs(
                p.get("pin_offset") or 0.0) else "pin_offset"
            err("Engine", worst, None, f"crank radius {p['stroke'] / 2 * 1e3:g} mm plus the"
                f" cylinder and pin offsets ({offsets * 1e3:g} mm together) must be less than"
                f" the connecting rod length {p['rod_length'] * 1e3:g} mm, or the rod cannot"
                " reach the piston pin at every crank angle")
    if p.get("rod_com") is not None and p.get("rod_length") is not None:
        if p["rod_com"] >= p["rod_length"]:
            err("Engine", "rod_com", None, "rod centre of mass must lie between big end and"
                " small end")


def _bearings(rows: list[dict[str, Any]], pr: _Problems, has_crank: bool) -> list[Bearing]:
    """Sheet Bearings (completed from sheet Crank where given): the complete rows, with their
    geometry checked."""
    err, warn = pr.err, pr.warn
    bearings = []
    counts = {"main": 0, "big end": 0}
    for i, r in enumerate(rows):
        if r["diameter"] is None and not has_crank:
            pr.blank_required("Bearings", "diameter", i, "journal diameter is required:"
                              " expected a length with a unit (e.g. mm)"
                              + ", found an empty cell (or give sheet Crank)")
        if None in (r["name"], r["type"], r["diameter"], r["length"], r["clearance"]):
            continue
        counts[r["type"]] += 1
        if r["journal_length"] is not None and r["length"] > r["journal_length"]:
            err("Bearings", "length", i, "effective length exceeds the journal length")
        ld = r["length"] / r["diameter"]
        if not _LD_VALID[0] <= ld <= _LD_VALID[1]:
            err("Bearings", "length", i, f"effective length / diameter = {ld:.3g} is outside"
                f" {_LD_VALID[0]:g}..{_LD_VALID[1]:g}, where the film calculation is"
                " meaningful (a narrower bearing also takes minutes to solve): check the"
                " length, the diameter and their units")
        elif not _LD_USUAL[0] <= ld <= _LD_USUAL[1]:
            warn("Bearings", "length", i, f"effective length / diameter = {ld:.3g} is outside"
                 f" the usual {_LD_USUAL[0]:g}..{_LD_USUAL[1]:g} of crank-train bearings")
        if r["clearance"] >= 0.01 * r["diameter"]:
            err("Bearings", "clearance", i, f"radial clearance {r['clearance'] * 1e3:g} mm is"
                " 1 % of the diameter or more: check the unit (radial clearance in mm or um)")
        bearings.append(Bearing(
            name=r["name"], type=r["type"], diameter=r["diameter"], length=r["length"],
            clearance=r["clearance"], journal_length=r["journal_length"],
            groove=r["groove"] or "none", groove_width=r["groove_width"],
            groove_start=r["groove_start"], groove_end=r["groove_end"], oil_feed=r["oil_feed"],
            oil_holes=r["oil_holes"] or 0, oil_hole_type=r["oil_hole_type"],
            oil_hole_diameter=r["oil_hole_diameter"], oil_hole_angle=r["oil_hole_angle"],
            lining=r["lining"], max_film_temperature=r["max_film_temperature"],
            max_film_pressure=r["max_film_pressure"], min_oil_flow=r["min_oil_flow"],
            support_stiffness=r.get("support_stiffness"),
            support_offset=r.get("support_offset"),
            index=counts[r["type"]], row=i))
    return bearings


def _crank_mass(data: WorkbookData, p: Params, cylinders: list[Cylinder], complete: bool,
                bearings: list[Bearing], pr: _Problems, rows: list[dict[str, Any]],
                fatigue: Params, where: dict[tuple, str]) -> tuple[MassItem, ...]:
    """Sheet CrankMass (and the rows derived from sheet Crank for throws it does not give),
    with the crank's bearing count (a main on each side of every throw, a big end per rod) and
    the mass planes checked against the crank."""
    err = pr.err
    crank_mass = tuple(
        MassItem(r["location"], r["throw"], r["kind"], r["mass"], r["x"], r["y"], r["z"] or 0.0,
                 r["axial"], r["reference"])
        for r in rows
        if None not in (r["location"], r["throw"], r["kind"], r["mass"], r["x"], r["y"],
                        r["axial"], r["reference"])
    )
    n_pins = max((c.pin for c in cylinders), default=0)
    bearing_rows = [r for r in _rows(data, "Bearings") if r["type"] is not None]
    if complete and cylinders and bearing_rows:
        # the crank needs a main bearing on each side of every throw and a big end per rod:
        # a missing row is an input error, like a missing cylinder row (not "not evaluated")
        for kind, need, why in (
                ("main", n_pins + 1, f"a crank with {n_pins} throws needs {n_pins + 1}, one on"
                 f" each side of every throw (M1..M{n_pins + 1}, front to rear)"),
                ("big-end", len(cylinders), f"{len(cylinders)} cylinders need"
                 f" {len(cylinders)}, one per connecting rod (BE1..BE{len(cylinders)})")):
            names = [str(r["name"]) for r in bearing_rows
                     if r["type"] == kind.replace("-", " ")]
            if names and len(names) != need:
                fix = (f"add the missing {kind} bearing row" if len(names) < need
                       else "remove the extra rows")
                pr.sheet_error("Bearings", f"{len(names)} {kind} bearing"
                               f"{'s' if len(names) != 1 else ''} given"
                               f" ({', '.join(names)}), but {why}; {fix}")
    for i, r in enumerate(_rows(data, "CrankMass")):
        if r["throw"] is not None and n_pins and r["throw"] > n_pins:
            err("CrankMass", "throw", i, f"throw {r['throw']} does not exist (the engine has"
                f" {n_pins} crank pins)", needs=("Cylinders",))
        spacing = p.get("main_spacing")
        if r["axial"] is not None and spacing is not None and r["axial"] > spacing:
            err("CrankMass", "axial", i, "axial position lies beyond the next main bearing"
                " (main journal spacing)")
    check_mass_planes(_rows(data, "CrankMass"), p, fatigue, bearings, where, pr.warn)
    return crank_mass


def _tv_model(tv_rows: list[dict[str, Any]], p: Params, pr: _Problems, has_crank: bool,
              viscous: bool = False) -> list[TVStation]:
    """Sheet TVModel (completed from sheet Crank where given): the stations front to rear,
    each cylinder on one station; ``viscous``: the damper is a viscous one (its ring row has
    no stiffness or damping to the next station)."""
    err = pr.err
    n_cyl = p.get("cylinders")
    tv = []
    station_of_cyl: dict[int, int] = {}
    for i, r in enumerate(tv_rows):
        if r["inertia"] is None and not has_crank:
            pr.blank_required("TVModel", "inertia", i, "inertia is required: expected an"
                              " inertia with a unit (e.g. kg m^2), found an empty cell")
        if r["station"] is None or r["inertia"] is None or r["role"] is None:
            continue
        last = i == len(tv_rows) - 1
        element = r.get("element") or "shaft"
        if element == "flexible coupling":  # the catalogue's stiffness and damping
            if last:
                err("TVModel", "element", i, "the last station has no next station; a flexible"
                    " coupling joins a station to the next one")
            for col, what in (("stiffness", "stiffness"), ("relative_damping", "damping")):
                if r[col] is not None:
                    err("TVModel", col, i, f"a flexible coupling's {what} is the maker's"
                        " catalogue value (sheet Coupling, at the rubber's temperature); leave"
                        " it blank")
        elif viscous and r["role"] == "damper ring":  # the silicone couples the ring
            for col, what in (("stiffness", "stiffness"), ("relative_damping", "damping")):
                if r[col] is not None:
                    err("TVModel", col, i, f"a viscous damper's ring has no {what} to next"
                        " here: its coupling is the silicone's (sheet Damper); leave it blank")
        elif not last and r["stiffness"] is None and not has_crank:
            err("TVModel", "stiffness", i, "stiffness to the next station is required for"
                " every station but the last (expected a torsional stiffness, e.g. N m/rad)")
        if last and r["stiffness"] is not None:
            err("TVModel", "stiffness", i, "the last station has no next station; leave its"
                " stiffness blank")
        cyls_here = tuple(r["cylinder"] or ())
        if r["role"] == "cylinder" and not cyls_here:
            err("TVModel", "cylinder", i, "a cylinder station needs its cylinder number(s)"
                " (e.g. 3, or 1, 2 for both cylinders of a V-engine crank pin)")
        for c in cyls_here:
            if n_cyl is not None and c > n_cyl:
                err("TVModel", "cylinder", i, f"cylinder {c} does not exist (the engine has"
                    f" {n_cyl} cylinders)")
            elif c in station_of_cyl:
                first = tv_rows[station_of_cyl[c]]["station"]
                err("TVModel", "cylinder", i, f"cylinder {c} is already on station '{first}';"
                    " each cylinder's excitation acts on one station")
            else:
                station_of_cyl[c] = i
        tv.append(TVStation(r["station"], r["role"], r["inertia"], cyls_here,
                            r["absolute_damping"] or 0.0, r["stiffness"],
                            r["relative_damping"] or 0.0, element))
        shares = _rod_piston_inertia(p)
        if shares is not None and cyls_here and r["inertia"] < len(cyls_here) * shares:
            pr.warn("TVModel", "inertia", i, f"inertia {r['inertia']:.4g} kg m^2 is less than"
                    f" the con-rod and piston shares of its {len(cyls_here)} cylinder(s)"
                    f" alone ({len(cyls_here) * shares:.4g} kg m^2: m_rot r^2 + 1/2 m_rec r^2"
                    " from the Engine sheet's masses); the torsional model uses a station's"
                    " inertia as given, so a cylinder station includes those shares (the"
                    " throw's own inertia plus them)")
    return tv


def _rod_piston_inertia(p: Params) -> float | None:
    """Con-rod and piston shares of one cylinder's station inertia [kg m^2]: the rod's rotating
    share ``m_rod (1 - a/l) r^2`` plus the mean inertia of the reciprocating masses
    ``1/2 (m_piston + m_rod a/l) r^2`` (``a`` rod centre of mass from the big end; the
    two-mass rod of the loads; terms in (r/l)^2 neglected); None without the masses."""
    m_p, m_r, a = p.get("piston_mass"), p.get("rod_mass"), p.get("rod_com")
    stroke, rod = p.get("stroke"), p.get("rod_length")
    if None in (m_p, m_r, a, stroke, rod) or not 0 < a < rod:
        return None
    r2 = (stroke / 2) ** 2
    return (m_r * (1 - a / rod) + 0.5 * (m_p + m_r * a / rod)) * r2


def _joints(data: WorkbookData, pr: _Problems) -> list[Joint]:
    """Sheet Joints: the complete joint rows, with their geometry checked."""
    err = pr.err
    joints = []
    for i, r in enumerate(_rows(data, "Joints")):
        if r["head_outer"] is not None and r["head_inner"] is not None and \
                r["head_inner"] >= r["head_outer"]:
            err("Joints", "head_inner", i, f"head bearing inner diameter"
                f" {_mm(r['head_inner'])} must be smaller than the outer diameter"
                f" {_mm(r['head_outer'])} ({pr.cell('Joints', 'head_outer', i)})")
        if r["face_outer"] is not None and r["face_inner"] is not None and \
                r["face_inner"] >= r["face_outer"]:
            err("Joints", "face_inner", i, f"face inner diameter {_mm(r['face_inner'])} must be"
                f" smaller than the outer diameter {_mm(r['face_outer'])}"
                f" ({pr.cell('Joints', 'face_outer', i)})")
        if r["diameter"] is not None and r["pitch"] is not None and r["pitch"] >= 0.5 * r[
                "diameter"]:
            err("Joints", "pitch", i, "thread pitch must be well below the nominal diameter")
        if r["tightening"] == "torque" and r["tightening_torque"] is None and r["name"]:
            err("Joints", "tightening_torque", i, "tightening 'torque' needs the tightening"
                " torque (expected a torque, e.g. N m)")
        if None in (r["name"], r["location"], r["bolts"], r["diameter"], r["pitch"],
                    r["property_class"], r["tightening"], r["face_outer"], r["face_inner"]):
            continue
        joints.append(Joint(**{k: v for k, v in r.items() if not k.startswith("_")}, row=i))
    return joints


def _joint_torques(data: WorkbookData, joints: list[Joint], pr: _Problems
                   ) -> list[JointTorque]:
    """Sheet JointTorques: one torque per joint and operating point, of a known joint."""
    err = pr.err
    names = {j.name.lower(): j.name for j in joints}
    jt = []
    seen = {}
    for i, r in enumerate(_rows(data, "JointTorques")):
        if r["joint"] is None or r["point"] is None or r["torque"] is None:
            continue
        if r["joint"].lower() not in names:
            err("JointTorques", "joint", i, f"joint '{r['joint']}' is not in sheet Joints")
            continue
        key = (r["joint"].lower(), r["point"])
        if key in seen:
            err("JointTorques", "point", i, f"duplicate operating point '{r['point']}' for"
                f" joint '{r['joint']}' (also at {pr.cell('JointTorques', 'point', seen[key])})")
            continue
        seen[key] = i
        name = names[r["joint"].lower()]
        jt.append(JointTorque(name, r["point"], r["torque"], r["speed"]))
    return jt


def _peak_pressure(data: WorkbookData, pr: _Problems) -> list[tuple[str, float, float]]:
    """Sheet PeakPressure: (case, speed, peak pressure), one per case and speed."""
    pk = []
    seen_pk: dict[tuple, int] = {}
    for i, r in enumerate(_rows(data, "PeakPressure")):
        if None in (r["case"], r["speed"], r["peak_pressure"]):
            continue
        key = (r["case"], round(r["speed"], 6))
        if key in seen_pk:
            first = pr.cell("PeakPressure", "speed", seen_pk[key])
            pr.err("PeakPressure", "speed", i, f"duplicate speed {_rpm(r['speed'])} for load"
                   f" case '{r['case']}' (also at {first})")
        seen_pk.setdefault(key, i)
        pk.append((r["case"], r["speed"], r["peak_pressure"]))
    return pk


def _brake_torque(data: WorkbookData, pr: _Problems) -> list[tuple[float, float]]:
    """Sheet BrakeTorque: (speed, brake torque), one per speed."""
    bt = []
    seen_bt: dict[float, int] = {}
    for i, r in enumerate(_rows(data, "BrakeTorque")):
        if r["speed"] is None or r["brake_torque"] is None:
            continue
        key = round(r["speed"], 6)
        if key in seen_bt:
            pr.err("BrakeTorque", "speed", i, f"duplicate speed {_rpm(r['speed'])} (also at"
                   f" {pr.cell('BrakeTorque', 'speed', seen_bt[key])})")
        seen_bt.setdefault(key, i)
        bt.append((r["speed"], r["brake_torque"]))
    return bt


def _damper(data: WorkbookData, pr: _Problems) -> Params:
    """Sheet Damper (and DamperRubber): the rubber ring's radii are consistent; a viscous
    damper's coupling is given once; the rubber table (sorted by temperature, no repeats) is
    kept as ``damper["rubber_table"]``, ``((T [K], G' [Pa], eta), ...)``, only when given."""
    damper = Params(data.params.get("Damper", {}))
    if damper.get("inner_radius") is not None and damper.get("outer_radius") is not None and \
            damper["inner_radius"] >= damper["outer_radius"]:
        pr.err("Damper", "inner_radius", None, f"rubber inner radius"
               f" {_mm(damper['inner_radius'])} must be smaller than the outer radius"
               f" {_mm(damper['outer_radius'])} ({pr.cell('Damper', 'outer_radius', None)})")
    if damper.get("ring_inner_radius") is not None and \
            damper.get("ring_outer_radius") is not None and \
            damper["ring_inner_radius"] >= damper["ring_outer_radius"]:
        pr.err("Damper", "ring_inner_radius", None, f"ring inner radius"
               f" {_mm(damper['ring_inner_radius'])} must be smaller than the ring outer radius"
               f" {_mm(damper['ring_outer_radius'])}"
               f" ({pr.cell('Damper', 'ring_outer_radius', None)})")
    lo, hi = damper.get("operating_temperature_min"), damper.get("operating_temperature_max")
    if lo is not None and hi is not None and lo > hi:
        pr.err("Damper", "operating_temperature_min", None, f"the minimum operating"
               f" temperature {_celsius(lo)} is above the maximum {_celsius(hi)}"
               f" ({pr.cell('Damper', 'operating_temperature_max', None)})")
    if damper.get("damper_type") == "viscous" and damper.get("viscous_damping") is not None \
            and damper.get("silicone_viscosity") is not None:
        pr.err("Damper", "viscous_damping", None, "give the damping coefficient or the"
               " silicone's viscosity (with the gap geometry), not both: one source per value")
    rows = [r for r in _rows(data, "DamperRubber")
            if None not in (r["temperature"], r["storage_modulus"], r["loss_factor"])]
    seen: dict[float, int] = {}
    for i, r in enumerate(_rows(data, "DamperRubber")):
        t = r["temperature"]
        if t is None:
            continue
        if round(t, 9) in seen:
            pr.err("DamperRubber", "temperature", i, f"duplicate temperature {_celsius(t)}"
                   f" (also at {pr.cell('DamperRubber', 'temperature', seen[round(t, 9)])}):"
                   " one row per temperature")
        seen.setdefault(round(t, 9), i)
    if rows:
        if damper.get("damper_type") == "viscous":
            pr.err("DamperRubber", "temperature", 0, "a rubber table with a viscous damper"
                   " (Damper type): remove the table or set the type to rubber")
        table = tuple(sorted((r["temperature"], r["storage_modulus"], r["loss_factor"])
                             for r in rows))
        damper = Params(dict(damper, rubber_table=table))
    return damper


def _coupling(data: WorkbookData, tv: list[TVStation], pr: _Problems) -> Params:
    """Sheet Coupling (and CouplingTemperature): the table (sorted by temperature, no
    repeats) is kept as ``coupling["temperature_table"]``, ``((T [K], stiffness factor,
    damping factor, temperature factor), ...)``, only when given; catalogue values without a
    flexible coupling in TVModel are refused (they would be ignored)."""
    coupling = Params(data.params.get("Coupling", {}))
    rows = _rows(data, "CouplingTemperature")
    seen: set[float] = set()
    table = []
    for i, r in enumerate(rows):
        t = r["temperature"]
        if t is None:
            continue
        if round(t, 9) in seen:
            pr.err("CouplingTemperature", "temperature", i, "duplicate temperature")
        seen.add(round(t, 9))
        vals = (r["stiffness_factor"], r["damping_factor"], r["temperature_factor"])
        if None in vals:
            col = ("stiffness_factor", "damping_factor", "temperature_factor")[vals.index(None)]
            pr.err("CouplingTemperature", col, i, "each row needs its three factors (expected"
                   " a number, found an empty cell)")
            continue
        table.append((t, *vals))
    given = any(v is not None for k, v in coupling.items()) or bool(table)
    if given and not any(s.element == "flexible coupling" for s in tv):
        pr.err("Coupling", "nominal_torque", None, "coupling data are given but no TVModel"
               " element is a flexible coupling (column 'element to next'): mark the"
               " coupling's row, or remove the Coupling sheet's values")
    if table:
        coupling = Params(dict(coupling, temperature_table=tuple(sorted(table))))
    return coupling


def _driven(data: WorkbookData, tv: list[TVStation], pr: _Problems) -> Params:
    """Sheet Driven: a propeller's entrained water and torque need a 'propeller' station."""
    driven = Params(data.params.get("Driven", {}))
    has_prop = any(s.role == "propeller" for s in tv)
    for attr in ("entrained_water", "propeller_torque"):
        if driven.get(attr) is not None and not has_prop:
            pr.err("Driven", attr, None, "no TVModel station has the role 'propeller' (its"
                   " inertia and damping are the propeller's)")
    if driven.get("propeller_torque") is not None and data.params["Engine"].get(
            "rated_speed") is None:
        pr.err("Driven", "propeller_torque", None, "the propeller law needs the Engine"
               " sheet's rated speed (the speed of this torque)")
    return driven


def _overrides(data: WorkbookData, pr: _Problems) -> list[RuleOverride]:
    """Sheet RuleOverrides: each override with its limit and reason."""
    overrides = []
    for i, r in enumerate(_rows(data, "RuleOverrides")):
        if r["rule"] is None:
            continue
        if r["limit"] is None:
            pr.err("RuleOverrides", "rule", i, "an override needs a limit")
            continue
        if r["reason"] is None:
            pr.err("RuleOverrides", "rule", i, "an override needs a reason (it is listed in"
                   " the report)")
            continue
        overrides.append(RuleOverride(r["rule"].strip(), str(r["limit"]).strip(),
                                      r["unit"], r["reason"],
                                      data.where.get(("RuleOverrides", i, "limit"), "")))
    return overrides


def load_engine(path, check_overrides: Callable[[list[RuleOverride]], list[InputError]]
                | None = None) -> Engine:
    """Read, convert and check a workbook (raises :class:`InputErrors` with every problem)."""
    from ..workbook.loader import read_workbook

    return build_engine(read_workbook(path, raise_errors=False), check_overrides)


__all__ = ["Engine", "Cylinder", "Bearing", "MassItem", "TVStation", "Joint", "JointTorque",
           "RuleOverride", "Params", "build_engine", "load_engine", "SHEETS"]
