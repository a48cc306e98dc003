"""Close the loop of ``checker new``: check the first layout and move its sizing levers until
every rule passes, or say which brief value prevents it.

The layout is evaluated in memory: the first layout's workbook is read once
(:class:`Bench`), every later layout is the cell changes that turn it into the new one,
checked by the evaluator of the remedies (:class:`checker.remedies.variants.Evaluator`, with
its calculation cache: a flywheel move recomputes only what the flywheel feeds).

The sizing levers (:data:`MOVES`) move layout dimensions, not cells: a move scales one or
several dimensions together (a journal's diameter and its land width; the web's thickness and
width) and the layout's dependent dimensions follow (the journal lengths, the cylinder pitch,
the counterweight's bore), so every layout written is consistent. Each round takes the failing
results; for each, the first move in the order of :data:`MOVES` (the order of design
preference) that applies and has not yet failed for it; the remedies' root finding
(:func:`checker.remedies.solve.find_remedies`) gives the smallest factor that passes it, and
every move takes the largest factor its results need. A result that no move passes within its
bounds stops the loop with the brief value that drives it (:data:`DRIVERS`), the rule and its
margin.
"""

from __future__ import annotations

import dataclasses
import fnmatch
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..calc import first_layout as fl
from ..calc import throw_stiffness as ts
from ..workbook.schema import SHEETS
from .bench import Bench
from .brief import Brief
from .new_engine import (
    Layout,
    Tuning,
    _joint_design,
    _mode_plausibility,
    content,
    layout,
    plausibility,
    tune_layout,
)

MAX_ROUNDS = 16
"""Rounds of the loop at most (each: one check, one root finding per move in use)."""
SIZING_TOL = 0.05
"""A sizing step's answer passes its result with a margin of 0 to 5 %: it need not reach the
limit to a thousandth (the remedies' window, :data:`checker.remedies.solve.TOL`)."""


# ------------------------------------------------------------------ the sizing levers
@dataclass(frozen=True)
class Design:
    """A layout and what the tuning passes set (the state the loop moves)."""

    layout: Layout
    tune: Tuning


@dataclass(frozen=True)
class Move:
    """One sizing lever of the loop: the layout dimensions it moves together by one factor
    (or, for a discrete lever, its choices)."""

    id: str
    name: str
    rules: tuple[str, ...]  # rule ids or family prefixes it answers
    items: tuple[str, ...]  # glob patterns on the result's item ("" = every item)
    moves: str  # what it changes, for the history
    apply: Callable[[Design, Any], Design]
    today: Callable[[Design], Any]
    bounds: tuple[float, float] = (1.0, 1.5)  # factors on today's value
    direction: str = "increase"
    choices: tuple[Any, ...] = ()
    to_end: bool = False
    """A discrete move whose choices improve its results in their order: when none passes
    but the last improves, the last is taken and its results go on to the next move."""
    cap: Callable[[Design], float] | None = None
    """The largest factor from the design that stays within the band of real engines
    (:data:`BANDS`); a geometric move that cannot pass its results within a round's bounds
    but improves them goes to its bound and on next round, until this cap."""

    def bounds_for(self, d: Design) -> tuple[float, float]:
        """This round's factor bounds: :attr:`bounds`, the upper one within the cap."""
        lo, hi = self.bounds
        return (lo, hi) if self.cap is None else (lo, max(min(hi, self.cap(d)), lo))

    def applies(self, rule: str, item: str) -> bool:
        if not any(rule.startswith(r) for r in self.rules):
            return False
        return not self.items or any(fnmatch.fnmatchcase(item.lower(), p.lower())
                                     for p in self.items)


def relayout(L: Layout, **dims: float) -> Layout:
    """The layout with ``dims`` changed and what follows from them: the rod's big eye and
    mass (:func:`first_layout.con_rod`), the pin and main journal lengths (lands and fillets,
    as :func:`checker.sizing.new_engine.layout`), the cylinder pitch at least the crank's
    axial stack, the counterweight's bore and the clearances in proportion to the diameters
    they belong to."""
    new = replace(L, **dims)
    rods = new.brief.cylinders // new.throws
    pin_len = rods * new.rod_land + 2 * (new.fillet_p + 1e-3) + (rods - 1) * 1e-3
    main_len = new.main_land + 2 * (new.fillet_j + 1e-3)
    stack = main_len + 2 * new.tw + pin_len
    rod = new.rod
    if new.dp != L.dp or new.rod_land != L.rod_land:
        rod = fl.con_rod(force=new.gas, length=new.rod_len, pin_d=new.dp,
                         pin_land=new.rod_land, wrist=new.wrist)
    return replace(new, rod=rod, pin_len=pin_len, main_len=main_len,
                   spacing=max(L.spacing - (L.main_len + 2 * L.tw + L.pin_len) + stack, stack),
                   cw_ri=L.cw_ri * new.dj / L.dj,
                   clearance_main=dims.get("clearance_main", L.clearance_main * new.dj / L.dj),
                   clearance_pin=dims.get("clearance_pin", L.clearance_pin * new.dp / L.dp))


def _scaled(*names: str) -> Callable[[Design, Any], Design]:
    def apply(d: Design, x: Any) -> Design:
        L0 = d.layout
        return replace(d, layout=relayout(L0, **{n: getattr(L0, n) * float(x)
                                                 for n in names}))
    return apply


def _tuned(name: str, also: tuple[str, ...] = ()) -> Callable[[Design, Any], Design]:
    def apply(d: Design, x: Any) -> Design:
        t = d.tune
        return replace(d, tune=replace(t, **{n: getattr(t, n) * float(x)
                                             for n in (name,) + also}))
    return apply


def _bolts(d: Design, x: Any) -> Design:
    """Bolt sets sized for ``x`` times their joint's torque (bigger or more bolts)."""
    joints = [{**j, **_joint_design(j["name"], j["torque"] * float(x), j["od"], j["id"],
                                    j.get("friction", 0.2))}
              for j in d.tune.joints]
    return replace(d, tune=replace(d.tune, joints=joints))


def _damper(d: Design, x: Any) -> Design:
    """The damper ring ``x`` times heavier, its rubber at Den Hartog's optimum for the new
    inertia ratio (J. P. Den Hartog, Mechanical Vibrations, 1956, sec. 3.3: ``f_opt = 1/(1 +
    mu)``, ``zeta_opt = sqrt(3 mu / (8 (1 + mu)^3))``, the damper-tuning module): the ratio
    ``mu`` of today's ring follows from today's optimum tuning, the crank mode's frequency from
    today's stiffness; a heavier ring at today's tuning would be detuned."""
    t = d.tune
    x = float(x)
    mu0 = max(1.0 / t.tuning - 1.0, 1e-6)
    w_n = math.sqrt(t.ring_stiffness / (t.detune * t.ring)) / t.tuning
    mu = x * mu0
    f = 1.0 / (1.0 + mu)
    zeta = math.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3))
    ring = x * t.ring
    return replace(d, tune=replace(t, ring=ring,
                                   ring_stiffness=t.detune * ring * (f * w_n) ** 2,
                                   loss_factor=min(max(2.0 * zeta / f, 0.05), 1.0), tuning=f))


DETUNE = (0.85, 1.2)
"""How far the loop may tune the damper's rubber stiffness from Den Hartog's optimum (a
single-mode optimum; the crank's response to several orders and modes may want another): the
ring's frequency within about -8/+10 % of the optimum, inside the Damper sheet's tuning band
(DMP-004: +-10 %) [the band not confirmed in a public source]."""


def _detuned(d: Design, x: Any) -> Design:
    """The damper's rubber ``x`` times stiffer, its total ratio to Den Hartog's optimum held
    within :data:`DETUNE` (the ring and loss factor kept)."""
    t = d.tune
    new = min(max(t.detune * float(x), DETUNE[0]), DETUNE[1])
    return replace(d, tune=replace(t, detune=new,
                                   ring_stiffness=t.ring_stiffness * new / t.detune))


def _washer(name: str) -> Callable[[Design, Any], Design]:
    """The joint ``name`` with a clamped-face friction coefficient ``x`` (0.3: a
    friction-enhancing diamond washer, Bell 2013), its bolt set kept."""
    def apply(d: Design, x: Any) -> Design:
        joints = []
        for j in d.tune.joints:
            if j["name"] == name:
                f = float(x)
                j = {**j, "friction": f, "capacity": j["capacity"] * f / j.get("friction", 0.2)}
            joints.append(j)
        return replace(d, tune=replace(d.tune, joints=joints))
    return apply


NOSE_MAX = 0.9
"""Largest crank nose diameter the loop gives, per main journal diameter (the nose steps down
from the front main journal through the seal) [not confirmed in a public source]."""


def _nose(d: Design, x: Any) -> Design:
    """The crank nose (and its joint's clamped face) ``x`` times larger in diameter, the
    joint's bolt the largest the wider face allows (or the smallest that covers four times
    its torque: the bolts move, before it, reaches that bound)."""
    x = float(x)
    L = replace(d.layout, nose_ratio=d.layout.nose_ratio * x)
    joints = []
    for j in d.tune.joints:
        if j["name"] == "crank nose":
            od = j["od"] * x
            j = {**j, **_joint_design("crank nose", j["torque"] * 4.0, od, 0.0,
                                      j.get("friction", 0.2)), "od": od}
        joints.append(j)
    return replace(d, layout=L, tune=replace(d.tune, joints=joints))


def _cap_nose(d: Design) -> float:
    return NOSE_MAX / d.layout.nose_ratio


def _friction(name: str) -> Callable[[Design], float]:
    def today(d: Design) -> float:
        return next(float(j.get("friction", 0.2)) for j in d.tune.joints if j["name"] == name)
    return today


def _chosen(part: str, attr: str, kind: type = str) -> Callable[[Design, Any], Design]:
    """A discrete move's choice ``x`` written to one field of the design's ``part``
    (``"layout"`` or ``"tune"``) as ``kind(x)``."""
    def apply(d: Design, x: Any) -> Design:
        return replace(d, **{part: replace(getattr(d, part), **{attr: kind(x)})})
    return apply


def _lining_today(attr: str) -> Callable[[Design], str]:
    def today(d: Design) -> str:
        return getattr(d.layout, attr) or d.layout.brief.bearing_lining
    return today


def _pin_and_main(d: Design, x: Any) -> Design:
    """The crank pin and its big-end land scaled by ``x``; the main journal (and its land)
    grown with it where needed to stay :data:`first_layout.MAIN_PIN_MIN` x the pin, as in
    real cranks."""
    L0 = d.layout
    dp = L0.dp * float(x)
    grow = max(fl.MAIN_PIN_MIN * dp / L0.dj, 1.0)
    return replace(d, layout=relayout(L0, dp=dp, rod_land=L0.rod_land * float(x),
                                      dj=L0.dj * grow, main_land=L0.main_land * grow))


WEB_WIDTH_MAX = min(ts.RANGE["Bp/Dp"][1], ts.RANGE["Bj/Dj"][1])
"""Largest web width per journal diameter the web move reaches (the top of the throw-stiffness
model's fitted range, 1.8: wider webs would leave the crank's derived stiffness extrapolated;
Bell 2013's I4 has 1.49-1.67 x its pin)."""


def _web(d: Design, x: Any) -> Design:
    """The web ``x`` times thicker and as much wider, its width at most
    :data:`WEB_WIDTH_MAX` x the smaller journal (never narrower than today)."""
    L0 = d.layout
    x = float(x)
    bw = max(min(L0.bw * x, WEB_WIDTH_MAX * min(L0.dp, L0.dj)), L0.bw)
    return replace(d, layout=relayout(L0, tw=L0.tw * x, bw=bw))


def _one(d: Design) -> float:
    return 1.0


BANDS = {"land_per_diameter": 0.6, "fillet_per_diameter": 0.08}
"""Upper ends of the sizing loop's bearing-land and fillet moves (bearing L/D 0.3-0.5,
fillets 0.05-0.07 x the journal) with a margin [the margin not confirmed in a public source].
The journal diameters and the web stay inside the class's bands of real engines
(:data:`checker.calc.first_layout.CLASSES`: ``pin_bore_band``, ``main_bore_band``,
``web_band``; the service data of docs/new-engine.md and Khurmi & Gupta, A Textbook of
Machine Design, §32.19)."""


def _cap_main_land(d: Design) -> float:
    return BANDS["land_per_diameter"] * d.layout.dj / d.layout.main_land


def _cap_pin_land(d: Design) -> float:
    return BANDS["land_per_diameter"] * d.layout.dp / d.layout.rod_land


def _cap_fillets(d: Design) -> float:
    L = d.layout
    return BANDS["fillet_per_diameter"] * min(L.dp / L.fillet_p, L.dj / L.fillet_j)


def _band_top(d: Design, key: str) -> float:
    return fl.CLASSES[d.layout.engine_class][key][1] * d.layout.brief.bore


def _cap_main(d: Design) -> float:
    return _band_top(d, "main_bore_band") / d.layout.dj


def _cap_pin(d: Design) -> float:
    """The pin's cap: its band, and the main's band over the smallest main/pin ratio (the
    main grows with the pin, :func:`_pin_and_main`)."""
    L = d.layout
    return min(_band_top(d, "pin_bore_band"),
               _band_top(d, "main_bore_band") / fl.MAIN_PIN_MIN) / L.dp


def _cap_web(d: Design) -> float:
    return _band_top(d, "web_band") / d.layout.tw


GRADES = ("5W-30", "10W-30", "5W-40", "10W-40", "15W-40", "15W-50", "20W-50")
"""Oil grades the loop may choose (SAE J300 engine grades of road engines, ranked by their
J300 viscosity by the remedies' oil-grade ranking)."""

HOLE_ANGLES = (45.0, 60.0, 75.0, 90.0)
"""Crank-pin oil hole angles the loop may choose [deg from the throw axis, leading]: from the
45 deg of the workbook's example engine (Bell, Ricardo 2013) towards 90 deg, where the gas
load's bending of the pin (IACS UR M53 §2.1.2.2: M_BRO cos(phi) + M_BTO sin(phi)) leaves only
its tangential part."""

STEELS = ("nodular iron", "forged steel", "42CrMo4")
"""Crank materials the loop may choose, weakest first (their strengths: the sizing's
MATERIALS, Bell 2013's C38+N2BY and EN 10083-3's 42CrMo4 +QT): a stronger steel before larger
journals, as Bell 2013 names alternative materials and fatigue-strength improvements first
among the parametric studies of the classical stress analysis."""

LININGS = ("AS15", "AS16", "aluminium bimetal", "tri-metal", "polymer", "sputter")
"""Bearing linings the loop may choose for a specific load, weakest first (their load
capacities: checker.calc.first_layout.LINING_CAPACITY and the BRG-001 limits, Clevite 2000,
MTU/Detroit Diesel, MAHLE 2012); after the bearing widths, before larger journals (Bell 2013:
'with sputtered con-rod' bearings)."""

COOLING = (0.0, 10.0, 20.0)
"""How far an oil cooler may hold the gallery below the usual full-load temperature (120 °C
gasoline, 110 °C diesel) [K]: to 100 / 90 °C, the cooler oil more viscous (the remedies' oil
supply temperature lever) [the temperatures not confirmed in a public source]."""

WASHER = (0.2, 0.3)
"""Friction coefficients of a bolted joint's clamped face the loop may choose: 0.2 typical,
0.3 with a friction-enhancing diamond washer (Bell, Ricardo 2013)."""

MOVES: tuple[Move, ...] = (
    # bearing films first through what keeps the crank like real ones
    Move("oil-grade", "Oil grade (SAE J300)", ("BRG-003", "BRG-004"), (), "oil grade",
         _chosen("tune", "oil_grade"), lambda d: d.tune.oil_grade or "", choices=GRADES,
         to_end=True),
    Move("main-clearance", "Main bearing clearance", ("BRG-003", "BRG-004"), ("M*",),
         "main bearing radial clearance", _scaled("clearance_main"), _one, (0.6, 1.6),
         "either"),
    Move("pin-clearance", "Big-end clearance", ("BRG-003", "BRG-004"), ("BE*",),
         "big-end radial clearance", _scaled("clearance_pin"), _one, (0.6, 1.6), "either"),
    Move("main-land", "Main bearing width", ("BRG-",), ("M*",), "main land width",
         _scaled("main_land"), _one, (1.0, 1.4), cap=_cap_main_land),
    Move("pin-land", "Big-end width", ("BRG-",), ("BE*",), "big-end land width",
         _scaled("rod_land"), _one, (1.0, 1.4), cap=_cap_pin_land),
    # then the crank's dimensions, several together where one rule needs it
    Move("pin-lining", "Big-end lining", ("BRG-001", "BRG-002"), ("BE*",),
         "big-end lining (a stronger one for the specific load)", _chosen("layout", "lining_pin"),
         _lining_today("lining_pin"), choices=LININGS),
    Move("main-lining", "Main bearing lining", ("BRG-001", "BRG-002"), ("M*",),
         "main bearing lining (a stronger one for the specific load)",
         _chosen("layout", "lining_main"),
         _lining_today("lining_main"), choices=LININGS),
    Move("oil-cooler", "Oil cooler (gallery temperature)", ("BRG-003", "BRG-004"), (),
         "oil supply temperature (an oil cooler)",
         _chosen("tune", "oil_cooling", float), lambda d: d.tune.oil_cooling,
         choices=COOLING, to_end=True),
    Move("oil-hole", "Crank-pin oil hole angle", ("FAT-",), ("pin*oil hole",),
         "crank-pin oil hole angle (towards the neutral axis of the gas load's bending)",
         _chosen("layout", "oil_hole_angle", float), lambda d: d.layout.oil_hole_angle,
         choices=HOLE_ANGLES, to_end=True),
    Move("fillets", "Fillet radii", ("FAT-",), (), "pin and main fillet radii",
         _scaled("fillet_p", "fillet_j"), _one, (1.0, 2.0), cap=_cap_fillets),
    Move("material", "Crank material", ("FAT-",), (), "crank material (a stronger forged"
         " steel: the fatigue strengths of its fillets and oil holes)",
         _chosen("layout", "material"),
         lambda d: d.layout.material, choices=STEELS, to_end=True),
    Move("main-journal", "Main journal (diameter and land width)", ("BRG-", "FAT-"),
         ("M*", "main*"), "main journal diameter and land width",
         _scaled("dj", "main_land"), _one, (1.0, 1.4), cap=_cap_main),
    Move("crank-pin", "Crank pin (diameter and land width)", ("BRG-", "FAT-"),
         ("BE*", "pin*"), "pin diameter and big-end land width (the main journal at least"
         f" {fl.MAIN_PIN_MIN:g} x the pin)", _pin_and_main, _one, (1.0, 1.4), cap=_cap_pin),
    Move("damper-tuning", "Damper tuning (rubber stiffness about Den Hartog's optimum)",
         ("TV-", "DMP-", "FAT-"), (), "damper rubber stiffness (its tuning to the crank's"
         " response, about Den Hartog's optimum)", _detuned, _one, DETUNE, "either"),
    Move("main-stiffness", "Main journal (diameter and land width, for the crank's"
         " torsional stiffness)", ("TV-",), (), "main journal diameter and land width (the"
         " crank's torsional stiffness)", _scaled("dj", "main_land"), _one, (1.0, 1.1),
         cap=_cap_main),
    Move("web", "Web (thickness and width)", ("FAT-", "TV-"), (),
         "web thickness and web width", _web, _one, (1.0, 1.6), cap=_cap_web),
    Move("counterweight", "Counterweight outer radius", ("BAL-",), (),
         "counterweight outer radius", _scaled("cw_ro"), _one, (0.8, 1.2), "either"),
    Move("flywheel", "Flywheel inertia", ("FLY-",), (), "flywheel inertia",
         _tuned("flywheel"), _one, (1.0, 4.0)),
    Move("damper", "Damper size (ring inertia, rubber at Den Hartog's optimum)",
         ("TV-", "DMP-", "FAT-"), (), "damper ring inertia (rubber stiffness and loss factor at"
         " Den Hartog's optimum)", _damper, _one, (1.0, 4.0)),
    Move("bolts", "Bolt size and number (yield-controlled preload)", ("JNT-",), (),
         "bolt size and number", _bolts, _one, (1.0, 4.0)),
    Move("nose-washer", "Diamond washer at the crank nose", ("JNT-",), ("crank nose",),
         "crank-nose joint's friction coefficient (a friction-enhancing diamond washer)",
         _washer("crank nose"), _friction("crank nose"), choices=WASHER, to_end=True),
    Move("nose", "Crank nose diameter (its joint's face and bolt)", ("JNT-",), ("crank nose",),
         "crank nose diameter (the damper joint's clamped face and the bolt it allows)", _nose,
         _one, (1.0, 1.2), cap=_cap_nose),
    Move("flywheel-washer", "Diamond washer at the flywheel", ("JNT-",), ("flywheel",),
         "flywheel joint's friction coefficient (a friction-enhancing diamond washer)",
         _washer("flywheel"), _friction("flywheel"), choices=WASHER, to_end=True),
)
"""The sizing levers in the order of design preference: the oil and the bearing clearances
and widths first (what keeps the crank like real ones), then fillets, journals and webs, then
the counterweights, the flywheel, the damper and the bolts."""

DRIVERS = {
    "BRG": "the brief's peak pressure {peak} at bore {bore} and speed range {speeds}",
    "FAT": "the brief's peak pressure {peak} at bore {bore}",
    "TV": "the brief's cylinders ({cyl}) and speed range {speeds}",
    "DMP": "the brief's cylinders ({cyl}) and speed range {speeds}",
    "JNT": "the brief's rated power {power}",
    "FLY": "the brief's minimum speed {min}",
    "BAL": "the brief's layout ({cyl} cylinders)",
}
"""The brief values that drive each rule family (what the stop message names)."""


# ------------------------------------------------------------------ history and verdict
@dataclass
class Step:
    """One move of the loop: which rule drove which dimensions, before and after."""

    round: int
    move: str
    moves: str
    rules: list[str]  # "FAT-001 pin 1 fillet" ...
    before: str
    after: str

    def text(self) -> str:
        rules = ", ".join(self.rules[:4]) + (f" and {len(self.rules) - 4} more"
                                             if len(self.rules) > 4 else "")
        return (f"round {self.round}: {rules} drove the {self.moves}: {self.before} ->"
                f" {self.after}")


@dataclass
class LoopOutcome:
    design: Design
    steps: list[Step]
    failed_before: int
    failed_after: int
    evaluations: int
    rounds: int
    seconds: float
    stop: list[str] = field(default_factory=list)  # why the loop stopped short of a pass

    @property
    def passed(self) -> bool:
        return self.failed_after == 0

    def summary(self) -> list[str]:
        """The console lines of ``checker new``: results failed before and after the loop,
        its rounds, evaluations and time, and why it stopped short of a pass."""
        verdict = ("every rule passes" if self.passed
                   else f"{self.failed_after} results still fail")
        return ([f"sizing loop: {self.failed_before} failed results in the first layout,"
                 f" {verdict} after {self.rounds} rounds ({self.evaluations} evaluations,"
                 f" {self.seconds:.1f} s)"] + [f"  {s.text()}" for s in self.steps]
                + [f"  stopped: {t}" for t in self.stop])

    def notes(self) -> list[str]:
        """The workbook's Notes lines: the sizing history."""
        head = (f"How this layout was sized: the first layout failed {self.failed_before}"
                f" results; checker new moved its sizing levers in {self.rounds} rounds"
                f" ({self.evaluations} evaluations, {self.seconds:.1f} s): "
                + (f"{self.failed_after} results still fail." if self.failed_after
                   else "every rule passes."))
        return ([head] + [f"Sizing {s.text()}." for s in self.steps]
                + [f"Sizing stopped: {t}" for t in self.stop])


HISTORY_MARK = "sizing loop:"
"""The words that open the sizing history in a moved value's note (the report's section
"How this layout was sized" collects them)."""

NOTE_ROWS = {  # move -> (sheet, how to find its rows)
    "oil-grade": ("Oil", "Oil grade"), "main-clearance": ("Bearings", "main"),
    "main-land": ("Bearings", "main"), "pin-clearance": ("Bearings", "big end"),
    "pin-land": ("Bearings", "big end"), "fillets": ("Crank", "all"),
    "main-journal": ("Crank", "all"), "main-stiffness": ("Crank", "all"),
    "crank-pin": ("Crank", "all"), "web": ("Crank", "all"),
    "counterweight": ("Crank", "all"), "flywheel": ("TVModel", "flywheel"),
    "damper": ("TVModel", "damper ring"), "damper-tuning": ("TVModel", "damper ring"),
    "bolts": ("Joints", None),
    "nose-washer": ("Joints", None), "flywheel-washer": ("Joints", None),
    "oil-hole": ("Bearings", "big end"), "material": ("Crank", "all"),
    "oil-cooler": ("Oil", "Oil supply temperature"), "nose": ("Joints", "crank nose"),
    "pin-lining": ("Bearings", "big end"), "main-lining": ("Bearings", "main"),
}
"""Where each move's history is noted: the note of the moved value's row."""


def annotate(cont: dict[str, Any], steps: list[Step]) -> dict[str, Any]:
    """``cont`` with each step's text added to the note of the rows it moved (after
    :data:`HISTORY_MARK`), so that the check and the report read the history with the
    estimates it changed."""
    out = dict(cont)
    for st in steps:
        sheet, key = NOTE_ROWS[st.move]
        add = f" [{HISTORY_MARK} {st.text()}]"
        body = out[sheet]
        if isinstance(body, list):  # a parameter sheet: (parameter, value, unit, note)
            out[sheet] = [(r[0], r[1], r[2], r[3] + add) if r[0] == key else r for r in body]
            continue
        cols, rows = body
        nj = [h for h, _u in cols].index("note")
        kj = 1 if sheet in ("Bearings", "TVModel") else 0  # type / role; Crank's throw
        out[sheet] = (cols, [row[:nj] + [(row[nj] or "") + add] + row[nj + 1:]
                             if key is None or str(row[kj]).lower() == key else row
                             for row in rows])
    return out


def _failing(res: Any) -> list[Any]:
    return [r for r in res.results if r.status == "fail" and r.severity == "error"]


def _dims_text(d: Design, m: Move) -> str:
    L, t = d.layout, d.tune
    mm = {"dp": L.dp, "dj": L.dj, "rod_land": L.rod_land, "main_land": L.main_land,
          "tw": L.tw, "bw": L.bw, "fillet_p": L.fillet_p, "fillet_j": L.fillet_j,
          "cw_ro": L.cw_ro}
    label = {"dp": "pin", "dj": "main", "rod_land": "big-end land", "main_land": "main land",
             "tw": "web", "bw": "web width", "fillet_p": "pin fillet",
             "fillet_j": "main fillet", "cw_ro": "counterweight radius"}
    if m.id == "oil-grade":
        return t.oil_grade or "the fuel's usual grade"
    if m.id.endswith("clearance"):
        c = L.clearance_main if m.id.startswith("main") else L.clearance_pin
        return f"{c * 1e6:.1f} µm"
    if m.id == "flywheel":
        return f"{t.flywheel:.4g} kg m^2"
    if m.id == "damper":
        return f"ring {t.ring:.4g} kg m^2"
    if m.id == "damper-tuning":
        return f"rubber {t.ring_stiffness:.4g} N m/rad ({t.detune:.3g} x Den Hartog's optimum)"
    if m.id == "bolts":
        return ", ".join(f"{j['name']} {j['bolts']} x M{j['d']}" for j in t.joints)
    if m.id.endswith("washer"):
        return "friction " + ", ".join(f"{j.get('friction', 0.2):g}" for j in t.joints
                                       if m.id.startswith(j["name"].split()[-1]))
    if m.id == "oil-hole":
        return f"{L.oil_hole_angle:g} deg leading"
    if m.id == "material":
        return L.material
    if m.id.endswith("lining"):
        return m.today(d)
    if m.id == "nose":
        nose = next(j for j in t.joints if j["name"] == "crank nose")
        return (f"nose {L.nose_ratio * L.dj * 1e3:.1f} mm, 1 x M{nose['d']}")
    if m.id == "oil-cooler":
        return f"{t.oil_cooling:g} K below the usual gallery temperature"
    keys = {"fillets": ("fillet_p", "fillet_j"), "main-journal": ("dj", "main_land"),
            "main-stiffness": ("dj", "main_land"),
            "crank-pin": ("dp", "rod_land", "dj"), "web": ("tw", "bw"), "main-land": ("main_land",),
            "pin-land": ("rod_land",), "counterweight": ("cw_ro",)}[m.id]
    return ", ".join(f"{label[k]} {mm[k] * 1e3:.1f} mm" for k in keys)


# ------------------------------------------------------------------ the solver's view of a move
@dataclass
class MoveBinding:
    """A move as the remedies' solver sees a lever's cells (the interface of
    :class:`checker.remedies.variants.Binding`): today's value (factor 1, or today's oil
    grade) and the cell changes of the layout at a trial value."""

    bench: Bench
    design: Design
    move: Move
    fields: tuple = ()
    retune: bool = False
    """Tune the damper to each trial layout (:func:`_retuned`): a crank move judged by the
    crank's vibration is judged with the damper a supplier would tune to the moved crank, not
    with today's damper detuned by it."""

    @property
    def nominal(self) -> list[Any]:
        return [self.move.today(self.design)]

    @property
    def labels(self) -> tuple[str, ...]:
        return (self.move.moves,)

    @property
    def cells(self) -> set[tuple[str, int, int]]:
        return {(f"move:{self.move.id}", 0, 0)}  # one identity per move: its jobs share

    def changes(self, value: Any) -> dict[tuple[str, int, int], Any]:
        d = self.move.apply(self.design, value)
        if self.retune:
            d = _retuned(self.bench, d)
        return self.bench.changes(content(d.layout, d.tune))


def lever_of(m: Move, d: Design) -> Any:
    """The remedies' lever of a move on design ``d`` (its rules, items, direction, this
    round's bounds or its choices)."""
    from ..description.levers import Lever

    # the oil grade's choices ranked by SAE J300 viscosity (the Oil sheet's lever); others
    # in the order given
    sheet, label = ("Oil", "oil grade") if m.id == "oil-grade" else ("Crank", "pin diameter")
    col = next(f for f in SHEETS[sheet].fields if f.label.lower() == label)
    return Lever(m.id, m.name, m.rules, sheet, (col,), items=m.items, unit="",
                 direction=m.direction, bounds=None if m.choices else m.bounds_for(d),
                 choices=m.choices, separable=False)


# ------------------------------------------------------------------ the loop
def close_loop(bench: Bench, design: Design, max_rounds: int = MAX_ROUNDS) -> LoopOutcome:
    """Move the sizing levers of ``design`` until every error-severity rule passes (see the
    module's docstring); the outcome holds the final design and its history."""
    t0 = time.perf_counter()
    n0 = bench.evaluations
    res = bench.check(content(design.layout, design.tune))
    first = len(_failing(res))
    tried: dict[tuple[str, str], set[str]] = {}
    steps: list[Step] = []
    rounds = 0
    stop: list[str] = []
    moved_since = False  # a move since the levers were last all tried
    ever: dict[tuple[str, str], set[str]] = {}  # every lever tried, over the passes
    while _failing(res) and rounds < max_rounds:
        rounds += 1
        plan = _plan(_failing(res), tried)
        if not plan and moved_since:  # the layout moved: each lever again, in the order
            ever = _union(ever, tried)
            tried.clear()
            moved_since = False
            plan = _plan(_failing(res), tried)
        if not plan:
            stop = _why_not(design, _failing(res), _union(ever, tried))
            break
        design, moved = _round(bench, design, res, plan, tried, rounds)
        steps += moved
        moved_since = moved_since or bool(moved)
        if not moved:
            continue  # every planned move failed: the next ones in the order next round
        if any(s.move in CRANK_MOVES or s.move in DAMPER_MOVES for s in moved):
            design = _retuned(bench, design)
        res = bench.check(content(design.layout, design.tune))
        if not hasattr(res, "results"):
            raise RuntimeError(f"a sized layout is not a valid workbook: {res}")
    if _failing(res) and not stop:
        stop = _why_not(design, _failing(res), _union(ever, tried))
    return LoopOutcome(design, steps, first, len(_failing(res)), bench.evaluations - n0,
                       rounds, time.perf_counter() - t0, stop)


BAND_MOVES = frozenset({"main-journal", "main-stiffness", "crank-pin", "web"})
"""Moves capped by the class's band of real engines (the stop message says so)."""

def _union(*tried: dict[tuple[str, str], set[str]]) -> dict[tuple[str, str], set[str]]:
    out: dict[tuple[str, str], set[str]] = {}
    for t in tried:
        for k, v in t.items():
            out.setdefault(k, set()).update(v)
    return out


CRANK_MOVES = frozenset({"main-land", "pin-land", "fillets", "main-journal", "main-stiffness",
                         "crank-pin", "nose", "web", "counterweight"})
"""Moves of the crank's geometry: its torsional modes move, and the damper is tuned again."""


DAMPER_MOVES = frozenset({"damper", "damper-tuning"})
"""Moves of the damper: its rubber is tuned again to the crank after them."""

TUNED_RULES = ("TV-", "DMP-")
"""Rules of the crank's vibration: a crank move answering one is tried with the damper tuned
to each trial layout (:class:`MoveBinding`)."""


def _retuned(bench: Bench, d: Design) -> Design:
    """The damper's rubber tuned again to the moved crank at the same ring (Den Hartog's
    optimum stiffness, loss factor and tuning ratio, the damper-tuning module)."""
    from .new_engine import _q

    res = bench.check(content(d.layout, replace(d.tune, sizing=True)), ["DMP"])
    if not hasattr(res, "results"):
        return d
    t = d.tune
    got = {n: _q(res, f"damper.{n}") for n in ("optimum_stiffness", "optimum_loss_factor",
                                               "optimum_tuning_ratio")}
    ok = {n: float(np.nanmax(v)) for n, v in got.items()
          if v is not None and np.isfinite(v).any()}
    return replace(d, tune=replace(
        t, ring_stiffness=ok["optimum_stiffness"] * t.detune if "optimum_stiffness" in ok
        else t.ring_stiffness,
        loss_factor=min(max(ok.get("optimum_loss_factor", t.loss_factor), 0.05), 1.0),
        tuning=ok.get("optimum_tuning_ratio", t.tuning)))


def _plan(failing: list[Any], tried: dict[tuple[str, str], set[str]]
          ) -> dict[str, list[Any]]:
    """Per move, the failing results it is tried on this round: for each result the first
    move of :data:`MOVES` that applies and has not failed for it yet."""
    plan: dict[str, list[Any]] = {}
    for r in failing:
        done = tried.setdefault((r.rule, r.item), set())
        m = next((m for m in MOVES if m.applies(r.rule, r.item) and m.id not in done), None)
        if m is not None:
            plan.setdefault(m.id, []).append(r)
    return plan


def _round(bench: Bench, design: Design, res: Any, plan: dict[str, list[Any]],
           tried: dict[tuple[str, str], set[str]], k: int) -> tuple[Design, list[Step]]:
    """One round: per planned move the remedies' answer for each of its results; the move
    takes the most demanding answer. A result it cannot pass within the round's bounds goes
    on to the next move next round, unless the move is geometric and improves it: then the
    move goes to its bound and is tried again next round, until its cap (the band of real
    engines, :data:`BANDS`)."""
    from ..remedies.solve import find_remedies

    steps = []
    for mid, results in plan.items():
        m = next(x for x in MOVES if x.id == mid)
        binding = MoveBinding(bench, design, m, retune=m.id in CRANK_MOVES and any(
            r.rule.startswith(TUNED_RULES) for r in results))
        sub = dataclasses.replace(res, results=_worst_per_rule(results))
        lo, hi = m.bounds_for(design)
        if not m.choices and m.direction == "increase" and hi <= 1.0 + 1e-6:
            for r in results:  # at the band's end already
                tried[(r.rule, r.item)].add(mid)
            continue
        out = find_remedies(sub, bench.ev, [lever_of(m, design)], near=0.0,
                            bind_lever=lambda lv, item, b=binding: b, side_effects=False,
                            tol=SIZING_TOL)
        found, better, last = [], [], []
        for rr in out:
            rm = rr.remedies[0] if rr.remedies else None
            if rm is not None and rm.found:
                found.append((rr, rm.value))
            elif (m.to_end and rm is not None and rm.best_margin is not None
                  and rr.margin is not None and rm.best_margin > rr.margin + 0.01):
                last.append(rr)  # improves at its last choice: taken, on to the next move
                for r in results:
                    if r.rule == rr.rule:
                        tried[(r.rule, r.item)].add(mid)
            elif (m.cap is not None and rm is not None and rm.best_margin is not None
                  and rr.margin is not None and rm.best_margin > rr.margin + 0.01):
                better.append(rr)  # improves, does not pass: to the bound, on next round
            else:  # the worst of its rule: the rule's other results go on with it
                for r in results:
                    if r.rule == rr.rule:
                        tried[(r.rule, r.item)].add(mid)
        if found:
            value, drove, how = _most_demanding(m, found), [rr for rr, _ in found], ""
            if last:
                value, drove = m.choices[-1], drove + last
        elif last:
            value, drove, how = m.choices[-1], last, " (its last choice: none passes yet)"
        elif better and bench.ev.input_errors(binding.changes(hi)) is None:
            value, drove, how = hi, better, " (to its bound this round: no value passes yet)"
        else:
            for r in results:  # its bound is not a valid layout: the next move next round
                if any(r.rule == rr.rule for rr in better):
                    tried[(r.rule, r.item)].add(mid)
            continue
        before = _dims_text(design, m)
        moved = m.apply(design, value)
        if _dims_text(moved, m) == before:  # at its cap within the written precision
            for r in results:
                tried[(r.rule, r.item)].add(mid)
            continue
        design = moved
        steps.append(Step(k, m.id, m.moves + how, [f"{rr.rule} {rr.item}" for rr in drove],
                          before, _dims_text(design, m)))
    return design, steps


def _worst_per_rule(results: list[Any]) -> list[Any]:
    """Of a move's failing results, the worst of each rule (the most negative margin): its
    answer is the one the others need too, as a rule's items differ by their loads, not by
    how the move acts on them (the check after the round shows any that still fail)."""
    worst: dict[str, Any] = {}
    for r in results:
        w = worst.get(r.rule)
        if w is None or (r.margin if r.margin is not None else 0.0) < (
                w.margin if w.margin is not None else 0.0):
            worst[r.rule] = r
    return list(worst.values())


def _most_demanding(m: Move, found: list[tuple[Any, Any]]) -> Any:
    """The answer that passes every result of the move: the largest factor (the last
    choice) of an increasing lever; of an 'either' lever that of the worst result."""
    if m.choices:
        order = [c for c in m.choices]
        return max((v for _, v in found), key=lambda v: order.index(v) if v in order else -1)
    if m.direction == "increase":
        return max(float(v) for _, v in found)
    return min(found, key=lambda p: p[0].margin)[1]


def _why_not(design: Design, failing: list[Any], tried: dict) -> list[str]:
    """For each rule still failing: its worst result and margin, the moves that could not
    pass it within their bounds, and the brief values that drive it."""
    b = design.layout.brief
    rpm = 30.0 / math.pi
    vals = {"peak": f"{b.peak_pressure / 1e5:.0f} bar", "bore": f"{b.bore * 1e3:g} mm",
            "speeds": f"{b.min_speed * rpm:.0f}-{b.max_speed * rpm:.0f} rpm",
            "cyl": b.cylinders, "power": f"{b.rated_power / 1e3:.0f} kW",
            "min": f"{b.min_speed * rpm:.0f} rpm"}
    worst: dict[str, Any] = {}
    for r in failing:
        if r.margin is not None and (r.rule not in worst or r.margin < worst[r.rule].margin):
            worst[r.rule] = r
    out = []
    for rule, r in sorted(worst.items()):
        used = [m for m in MOVES if m.id in tried.get((r.rule, r.item), set())]
        moves = [m.name.lower() for m in used]
        capped = [m.name.lower() for m in used
                  if m.cap is not None and m.id in BAND_MOVES and m.cap(design) <= 1.0 + 1e-6]
        fam = rule.split("-")[0]
        drive = DRIVERS.get(fam, "the brief").format(**vals)
        out.append(f"{rule} {r.item}: {r.value_text} against {r.limit} (margin"
                   f" {100 * r.margin:+.0f} %)"
                   + (f" with {', '.join(moves)} at their bounds" if moves else "")
                   + (f" ({', '.join(capped)} at the top of the band of real"
                      f" {design.layout.engine_class} engines)" if capped else "")
                   + f"; {drive} prevents it.")
    return out


@dataclass
class Sized:
    """A sized layout: its workbook content and, when the loop ran, its outcome."""

    layout: Layout
    content: dict[str, Any]
    loop: Any = None  # checker.sizing.loop.LoopOutcome


def _plausible(bench: Bench, d: Design) -> Layout:
    """The looped layout's own plausibility (:func:`checker.sizing.new_engine.plausibility`,
    the crank modes of its TV model): the loop moves dimensions past the open-loop layout's
    (a main land wider than real ones, a crank mode moved), and what ``checker new`` and the
    report's caveats say must be of the layout written."""
    res = bench.check(content(d.layout, d.tune), ["TV-001"])
    modes = _mode_plausibility(d.layout, res) if hasattr(res, "results") else []
    return replace(d.layout, plausibility=tuple(plausibility(d.layout)) + tuple(modes))


def sized(b: Brief, iterate: bool = True) -> Sized:
    """The first layout by its rules, tuned (:func:`tune_layout`); with ``iterate`` checked
    and moved by the sizing loop (:func:`checker.sizing.loop.close_loop`) until every rule
    passes or a brief value prevents it, the history in its Notes."""
    L, tune, bench = tune_layout(layout(b))
    if not iterate:
        return Sized(L, content(L, tune))
    out = close_loop(bench, Design(L, tune))
    d = replace(out.design, layout=_plausible(bench, out.design))
    cont = annotate(content(d.layout, d.tune), out.steps)
    cont["Notes"] = cont["Notes"] + out.notes()
    return Sized(d.layout, cont, out)
