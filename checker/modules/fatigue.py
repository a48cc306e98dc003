"""Graph calculation for classical crankshaft fatigue: Goodman safety factors at the crank-pin
fillets, main-journal fillets and oil holes across the speed range, and the IACS UR M53
acceptability factor from the same stresses.

Method (Bell, Ricardo 2013, 'Crankshaft analysis (25)-(28)': "classical stress analysis"; M53)
----------------------------------------------------------------------------------------------
* **Loads** (quantity ``loads.bearing_load``): the force of the con-rod(s) on each crank pin in
  the crank frame, ``F_pin = -big_end_crank`` summed over the rods of the pin
  (:func:`checker.calc.crank_forces.crankpin_force`: a big-end load is the force of the journal
  on the rod's bearing), turned into the throw frame (radial ``F_R`` + outward, tangential
  ``F_T`` + in the direction of rotation;
  :func:`checker.calc.crank_stress.pin_force_in_throw_frame`).
  Gas + reciprocating and con-rod inertia at constant speed, full and no load, every speed.
  The crank's own centrifugal forces (pin, webs, counterweights) are not part of the M53
  loading and are not included; being constant at a given speed they would shift only the
  mean stress.
* **Bending**: each throw is a beam simply supported at the centres of its two main journals
  (statically determinate, Bell, Ricardo 2013 "load sharing between main bearings not included");
  the
  web bending stress at the web centre ``sigma_BF = (F_R (L3 - L2)/L3) L1 / (B W^2/6)`` and the
  direct stress ``sigma_QF`` (:func:`checker.calc.crank_stress.throw_nominal_stresses`), the
  oil-bore bending from the moments of ``F_R`` and ``F_T`` at the pin centre.
* **Torsion** (quantity ``tv.element_torque``): the element torques of the torsional model,
  synthesised over the cycle on the loads module's crank-angle grid from the per-order complex
  torques (``T_e(theta) = T_mean,e + sum_n Re{T_en exp(j n theta)}``, the same theta origin:
  firing TDC of cylinder 1), so bending and torsion are combined at the same crank angle.
  Mapping of TV elements to the crank (chain front to rear):

  - a **main journal** between cylinder stations ``i`` and ``i + 1`` carries the torque of the
    element between them; main 1 carries the element ending at the first cylinder station
    (crank nose -> cylinder 1), the last main the element from the last cylinder station
    (cylinder n -> flywheel);
  - a **crank pin** carries one torque along its length, ``T_f + (L_3 - L_2)/L_3 (T_r -
    T_f)`` of its front and rear elements (the mean for a centred pin;
    :func:`checker.calc.throw_fatigue.pin_torque`): the rod's tangential force passes through
    the pin axis, and the main bearings' reactions to it, acting on the crank axis a crank
    radius away, twist the pin. Both pin fillets and the **pin oil hole** use it;
  - a throw whose cylinder station is the first/last station of the chain has zero torque on
    that side (free end).
* **Stress concentration**: factors from sheet Fatigue where given (``scf_*``), otherwise the
  IACS UR M53 empirical formulae (:func:`checker.calc.scf.m53_scf`); every M53 validity flag of
  a factor that is used becomes a finding of the locations that use it (never silent). M53
  has no factor for the direct stress at the journal fillet other than ``beta_Q`` and none for
  a journal oil hole: ``beta_Q`` is always from M53; the main oil hole uses M53's ``gamma_T``
  with ``d_O = D_O / D_G`` (an extension, flagged in the assumptions).
* **Criterion** (:mod:`checker.calc.fatigue`): amplitude and mean of each local stress history
  over the cycle (half range, mid value); equivalent alternating stress = von Mises of the
  amplitudes ``sqrt(sigma_a^2 + 3 tau_a^2)`` (in phase, M53 §5); equivalent mean = signed von
  Mises ``sign(sigma_m) sqrt(sigma_m^2 + 3 tau_m^2)``, compressive means not credited; oil
  holes: M53's maximum-principal combination; Goodman ``SF = 1 / (sigma_eq,a / S_e +
  sigma_eq,m / S_u)`` with the Fatigue sheet strengths (fillets: fillet UTS; oil holes: base
  UTS).
* **M53 acceptability** ``Q = sigma_DW / sigma_V`` (alternating only, ``sigma_add`` = 10 MPa
  for trunk-piston engines, ``sigma_DW`` from M53 §6 with the base UTS, K = 1.05 for drop-forged
  fillets, 1.0 at the oil bore; radius below 2 mm raised to 2 mm and flagged). Rolled or
  hardened fillets are not credited (M53 accepts surface-treatment gains only from tests).

Locations (items): ``pin j fillet`` (worst of the two fillets of pin j), ``main k fillet``
(worst of the fillets of main k next to a crank web), ``pin j oil hole`` (if the big-end rows
or the Fatigue sheet give a crank-pin oil hole), ``main k oil hole`` (Goodman only, if the
Fatigue sheet gives a main journal oil hole diameter: torsion only, since the statically
determinate bending moment is zero at the main journal centre). Item attribute ``location``
is one of :data:`LOCATIONS`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..calc import crank_forces as cf
from ..calc import crank_stress as cs
from ..calc import fatigue as fat
from ..calc import scf as scf_mod
from ..calc import throw_fatigue as tf
from ..description.engine import Engine
from ..evaluation.graph import (
    UNAVAILABLE,
    MissingInputs,
    Quantity,
    QuantitySpec,
    calculation,
    quantity,
)
from ..results.fatigue import (
    FilletRatioDetail,
    GoodmanDetail,
    LocationStrength,
    M53Detail,
    PinOilHole,
    ScfInfo,
    ThrowGeometry,
    ThrowNominal,
)
from ..workbook.units import RPM
from . import joints, loads, support_beam, torsion  # noqa: F401  (registered first: report order)
from . import torsion_stress as tvs
from .loads import CASES

LOCATIONS = ("pin fillet", "main fillet", "pin oil hole", "main oil hole")
M53_K_FILLET = 1.05
"""M53 §6 factor K of the fillets: continuous grain flow / drop forged (automotive forged
crank); 1.0 at the oil bore."""
M53_K_OIL = 1.0
SIGMA_ADD = fat.SIGMA_ADD_TRUNK_PISTON
"""M53 §4 additional alternating bending stress of a trunk-piston engine [Pa] (Q only)."""
WEB_WIDTH_CHOICE = "min"
"""Web width B of the reference section: the minimum width (smallest section, conservative)."""
MEAN_CRITERION = "signed_von_mises"

GOODMAN = quantity(QuantitySpec(
    "fatigue.goodman_sf", "", ("item", "case", "speed"),
    "Goodman fatigue safety factor per crankshaft location (crank-pin and main-journal fillets,"
    " oil holes), load case and speed", "", ("location",), coords={"case": CASES},
    detail=GoodmanDetail))
FILLET_RATIO = quantity(QuantitySpec(
    "fatigue.fillet_bending_ratio", "", ("item",),
    "Fillet bending moment of the crank as a continuous beam over that of the statically"
    " determinate scheme (amplitudes over the cycle, con-rod forces on the pins) per throw and"
    " fillet, at the operating point of the largest determinate amplitude", "",
    detail=FilletRatioDetail))
M53Q = quantity(QuantitySpec(
    "fatigue.m53_q", "", ("item", "case", "speed"),
    "IACS UR M53 acceptability factor Q = sigma_DW / sigma_V per location, load case and speed",
    "", ("location",), coords={"case": CASES}, detail=M53Detail))

SCF_FIELDS = {  # factor -> (Fatigue attribute, symbol, description)
    "alpha_b": ("scf_pin_bending", "α_B", "pin fillet, bending"),
    "alpha_t": ("scf_pin_torsion", "α_T", "pin fillet, torsion"),
    "beta_b": ("scf_main_bending", "β_B", "main fillet, bending"),
    "beta_q": (None, "β_Q", "main fillet, direct (radial) force"),
    "beta_t": ("scf_main_torsion", "β_T", "main fillet, torsion"),
    "gamma_b": ("scf_oil_bending", "γ_B", "pin oil hole, bending"),
    "gamma_t": ("scf_oil_torsion", "γ_T", "pin oil hole, torsion"),
    "gamma_t_main": ("scf_oil_torsion", "γ_T", "main oil hole, torsion (d_O = D_O/D_G)"),
}
FACTORS_OF = {"pin fillet": ("alpha_b", "alpha_t"),
              "main fillet": ("beta_b", "beta_q", "beta_t"),
              "pin oil hole": ("gamma_b", "gamma_t"),
              "main oil hole": ("gamma_t_main",)}
_RATIOS_OF = {  # M53 related dimensions each factor depends on (validity, M53 §3.1)
    "alpha_b": ("r_pin", "s", "w", "b", "d_G", "d_H"),
    "alpha_t": ("r_pin", "s", "w", "b"),
    "beta_b": ("r_journal", "s", "w", "b", "d_G", "d_H"),
    "beta_q": ("r_journal", "s", "w", "b", "d_H"),
    "beta_t": ("r_journal_torsion", "s", "w", "b"),
    "gamma_b": ("d_O",), "gamma_t": ("d_O",), "gamma_t_main": ("d_O",),
}
_M53_FLAGS = {  # non-range M53 flags per factor -> text
    "alpha_b": (("s_clipped", "s < -0.5: f(s,w) evaluated at s = -0.5 (M53 §3.1 extension)"),
                ("recess_clipped", "f(recess) < 1 set to 1 (M53 §3.1 extension)")),
    "alpha_t": (("s_clipped", "s < -0.5: f(r,s) evaluated at s = -0.5 (M53 §3.1 extension)"),),
    "beta_b": (("journal_s_extrapolated", "s < -0.5: f_B(s,w) evaluated at s = -0.5, an"
                " extrapolation M53 does not state"),
               ("recess_clipped", "f(recess) < 1 set to 1 (M53 §3.1 extension)")),
    "beta_q": (("journal_s_extrapolated", "s < -0.5: f_Q(s) evaluated at s = -0.5, an"
                " extrapolation M53 does not state"),
               ("recess_clipped", "f(recess) < 1 set to 1 (M53 §3.1 extension)")),
    "beta_t": (("s_clipped", "s < -0.5: f(r,s) evaluated at s = -0.5 (M53 §3.1 extension)"),),
}


# ------------------------------------------------------------------------------------ inputs
def _geometry(engine: Engine) -> tuple[ThrowGeometry, dict, list[str]]:
    """Throw geometry (SI) and the cells it came from; raises MissingInputs naming cells."""
    p, fa = engine.params, engine.fatigue
    missing: list[str] = []
    notes: list[str] = []
    mains = [b for b in engine.bearings if b.type == "main"]
    bigs = [b for b in engine.bearings if b.type == "big end"]
    if not mains:
        missing.append("Bearings: no main bearing rows (journal diameter and length of the main"
                       " journals)")
    if not bigs:
        missing.append("Bearings: no big-end bearing rows (crank-pin diameter and length)")
    for b in mains + bigs:
        if b.journal_length is None:
            missing.append(engine.describe_missing("Bearings", "journal_length", b.row,
                                                   f"bearing {b.name}"))
    for attr in ("stroke", "main_spacing"):
        if p.get(attr) is None:
            missing.append(engine.describe_missing("Engine", attr))
    for attr in ("web_thickness", "web_min_width"):
        if fa.get(attr) is None:
            missing.append(engine.describe_missing("Fatigue", attr, what="the crank web"))
    if missing:
        raise MissingInputs(missing)
    D = min(b.diameter for b in bigs)
    DG = min(b.diameter for b in mains)
    LG = max(b.journal_length for b in mains)
    LH = min(b.journal_length for b in bigs)
    if len({b.diameter for b in bigs}) > 1 or len({b.diameter for b in mains}) > 1 or len(
            {b.journal_length for b in mains}) > 1 or len({b.journal_length for b in bigs}) > 1:
        notes.append("Journal and pin sizes differ between bearing rows: the smallest diameters,"
                     " the longest main journal and the shortest crank pin are used for every"
                     " throw (conservative).")
    g = ThrowGeometry(
        pin_diameter=D, journal_diameter=DG, throw=p["stroke"] / 2.0,
        main_spacing=p["main_spacing"], main_journal_length=LG, pin_journal_length=LH,
        web_thickness=fa["web_thickness"],
        web_width=cs.web_width(fa["web_min_width"], fa.get("web_max_width"), WEB_WIDTH_CHOICE),
        web_offset=fa.get("web_offset") or 0.0, pin_bore=fa.get("pin_bore") or 0.0,
        journal_bore=fa.get("main_bore") or 0.0)
    return g, {"bigs": bigs, "mains": mains}, notes


def _pin_oil_hole(engine: Engine, bigs: list) -> tuple[PinOilHole | None, list[str]]:
    """Crank-pin oil hole (diameter, angle) or None when the crank has none; missing texts."""
    fa = engine.fatigue
    with_holes = [b for b in bigs if (b.oil_holes or 0) > 0]
    d = fa.get("pin_oil_hole_diameter")
    if d is None and with_holes:
        d = next((b.oil_hole_diameter for b in with_holes if b.oil_hole_diameter), None)
    if d is None and not with_holes:
        return None, []
    missing = []
    if d is None:
        missing.append(engine.describe_missing("Fatigue", "pin_oil_hole_diameter",
                                               what="the crank pin"))
    ref = with_holes[0] if with_holes else bigs[0]
    angle = ref.oil_hole_angle
    if angle is None:
        missing.append(engine.describe_missing("Bearings", "oil_hole_angle", ref.row,
                                               f"bearing {ref.name} (crank-pin oil hole)"))
    elif "trail" in (ref.oil_hole_type or "").lower() and angle > 0:
        angle = -angle
    return PinOilHole(diameter=d, angle=angle, row=ref), missing


def _station_elements(engine: Engine, n_pins: int, n_el: int) -> tuple[np.ndarray, list[str]]:
    """Front and rear TV element of each throw, shape (n_pins, 2); ``n_el`` = none (free end)."""
    station_of = {c: i for i, s in enumerate(engine.tv_model) for c in s.cylinders}
    out = np.full((n_pins, 2), n_el, dtype=int)
    missing = []
    for j in range(n_pins):
        st = [station_of.get(c.number) for c in engine.cylinders if c.pin - 1 == j]
        if not st or None in st:
            missing.append(f"TVModel: no station for the cylinder(s) of crank pin {j + 1}"
                           " (column 'cylinder')")
            continue
        front, rear = min(st) - 1, max(st)
        out[j, 0] = front if front >= 0 else n_el
        out[j, 1] = rear if rear < n_el else n_el
    return out, missing


def _scfs(engine: Engine, g: ThrowGeometry, oil: PinOilHole | None, main_oil_d: float | None
          ) -> tuple[ScfInfo, dict, dict]:
    """Factors used with their sources and M53 values; missing texts and findings per factor."""
    fa = engine.fatigue
    m53 = None
    m53_missing: list[str] = []
    for attr in ("pin_fillet_radius", "main_fillet_radius"):
        if fa.get(attr) is None:
            m53_missing.append(engine.describe_missing("Fatigue", attr,
                                                       what="the crankshaft (M53 SCF)"))
    kw = dict(pin_diameter=g.pin_diameter, journal_diameter=g.journal_diameter,
              throw=g.throw, web_thickness=g.web_thickness, web_width=g.web_width,
              pin_fillet_radius=fa.get("pin_fillet_radius"),
              journal_fillet_radius=fa.get("main_fillet_radius"),
              pin_recess=fa.get("pin_fillet_web_undercut") or 0.0,
              journal_recess=fa.get("main_fillet_web_undercut") or 0.0,
              pin_bore=g.pin_bore, journal_bore=g.journal_bore)
    m53_main_oil = None
    if not m53_missing:
        try:
            m53 = scf_mod.m53_scf(**kw, oil_hole_diameter=(oil.diameter if oil is not None
                                                            else None) or 0.0)
            if main_oil_d is not None:
                # journal oil hole: M53's pin formula with d_O = D_O / D_G
                m53_main_oil = scf_mod.m53_scf(
                    **kw, oil_hole_diameter=main_oil_d * g.pin_diameter
                    / g.journal_diameter)
        except ValueError as exc:
            m53_missing.append(f"Fatigue: M53 stress concentration factors: {exc}")
    used: dict[str, float | None] = {}
    source: dict[str, str] = {}
    m53_val: dict[str, float | None] = {}
    findings: dict[str, list[str]] = {}
    missing: dict[str, list[str]] = {}
    for key, (attr, sym, what) in SCF_FIELDS.items():
        base = m53_main_oil if key == "gamma_t_main" else m53
        fkey = "gamma_t" if key == "gamma_t_main" else key
        v53 = None if base is None else float(getattr(base, fkey))
        m53_val[key] = v53 if v53 is not None and np.isfinite(v53) else None
        given = fa.get(attr) if attr else None
        if given is not None:
            used[key], source[key] = float(given), f"workbook {engine.cell('Fatigue', attr)}"
            continue
        if m53_val[key] is None:
            used[key], source[key] = None, "missing"
            why = list(m53_missing) or [f"M53 formula gives no valid {sym} ({what}) for this"
                                        " geometry (far outside its validity range)"]
            if attr:
                why.append("or give the factor: " + engine.describe_missing(
                    "Fatigue", attr, what=f"{sym} ({what})"))
            missing[key] = why
            continue
        used[key], source[key] = m53_val[key], "IACS UR M53 §3"
        texts = []
        ratios = base.ratios
        for name in _RATIOS_OF[key]:
            if base.flags[f"{name}_out_of_range"].any():
                lo, hi = scf_mod.VALIDITY[name]
                val = float(getattr(ratios, "r_pin" if (name == "r_journal_torsion" and bool(
                    base.flags["beta_t_equal_to_alpha_t"])) else name))
                texts.append(f"M53 {sym} ({what}): {name} = {val:.4g} outside"
                             f" [{'-inf' if lo is None else f'{lo:g}'},"
                             f" {'+inf' if hi is None else f'{hi:g}'}] (M53 §3.1); factor"
                             " used, confirm by FEM or give it in the Fatigue sheet")
        for flag, text in _M53_FLAGS.get(key, ()):
            if base.flags[flag].any():
                texts.append(f"M53 {sym} ({what}): {text}")
        if texts:
            findings[key] = texts
    info = ScfInfo(used=used, source=source, m53=m53_val,
                   ratios=None if m53 is None else m53.ratios,
                   ratios_main_oil=None if m53_main_oil is None else m53_main_oil.ratios,
                   m53_missing=m53_missing)
    return info, missing, findings


def _strengths(engine: Engine, has: dict) -> tuple[dict, dict]:
    """(S_e, S_u) per location type [Pa] and the missing cells per location type."""
    fa = engine.fatigue
    spec = {"pin fillet": ("pin_fillet_fatigue", "fillet_uts"),
            "main fillet": ("main_fillet_fatigue", "fillet_uts"),
            "pin oil hole": ("pin_oil_hole_fatigue", "uts"),
            "main oil hole": ("main_oil_hole_fatigue", "uts")}
    out, missing = {}, {}
    for loc, (se, su) in spec.items():
        if not has.get(loc):
            continue
        miss = [engine.describe_missing("Fatigue", a, what=f"the {loc}s") for a in (se, su)
                if fa.get(a) is None]
        if miss:
            missing[loc] = miss
        out[loc] = LocationStrength(fa.get(se), fa.get(su), engine.cell("Fatigue", se),
                                    engine.cell("Fatigue", su))
    return out, missing


@dataclass
class _Locations:
    """Which location types are evaluated and what each lacks (inputs of the node)."""

    oil: PinOilHole | None  # the crank-pin oil hole (None: none)
    main_oil_d: float | None  # main journal oil hole diameter [m] (None: none)
    has: dict[str, bool]  # location type -> evaluated
    strengths: dict[str, LocationStrength]
    scf: ScfInfo
    scf_find: dict[str, list[str]]  # factor -> M53 validity texts
    stress_missing: dict[str, list[str]]  # location type -> local stresses not available
    loc_missing: dict[str, list[str]]  # location type -> Goodman not available

    def strength(self, loc: str) -> tuple[float, float]:
        """(S_e, S_u) [Pa] of a location type, 1.0 where missing (then not judged)."""
        se, su = self.strengths.get(loc, (None, None, "", ""))[:2]
        return (se or 1.0), (su or 1.0)

    def factors(self) -> dict[str, float]:
        """Stress concentration factors used, 1.0 where missing (then not judged)."""
        return {key: (v if v is not None else 1.0) for key, v in self.scf.used.items()}


def _locations(engine: Engine, g: ThrowGeometry, bigs: list, notes: list[str]) -> _Locations:
    """The locations to evaluate, their strengths and factors, and what each lacks."""
    oil, oil_missing = _pin_oil_hole(engine, bigs)
    main_oil_d = engine.fatigue.get("main_oil_hole_diameter")
    has = {"pin fillet": True, "main fillet": True, "pin oil hole": oil is not None,
           "main oil hole": main_oil_d is not None}
    if oil is None:
        notes.append("No crank-pin oil hole (Bearings big-end 'oil holes' 0 and no Fatigue"
                     " 'Pin journal oil hole diameter'): pin oil holes not evaluated.")
    if main_oil_d is None:
        notes.append("No main journal oil hole diameter (Fatigue sheet): main oil holes not"
                     " evaluated.")
    strengths, s_missing = _strengths(engine, has)
    scf, scf_missing, scf_find = _scfs(engine, g, oil, main_oil_d)
    stress_missing: dict[str, list[str]] = {}
    loc_missing: dict[str, list[str]] = {}
    for loc in LOCATIONS:
        if not has[loc]:
            continue
        why = list(oil_missing) if loc == "pin oil hole" else []
        for fkey in FACTORS_OF[loc]:
            why += [w for w in scf_missing.get(fkey, []) if w not in why]
        if why:
            stress_missing[loc] = why
        why = list(s_missing.get(loc, [])) + why
        if why:
            loc_missing[loc] = why
    return _Locations(oil, main_oil_d, has, strengths, scf, scf_find, stress_missing,
                      loc_missing)


def _pin_forces(engine: Engine, bl: Quantity, pins: np.ndarray, n_pins: int
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Con-rod force on each crank pin in the throw frame: F_R, F_T (C, S, T, N) [N], and the
    throw angles (T,) [rad]."""
    cyls = engine.cylinders
    firing = np.array([c.firing_angle for c in cyls])
    bank = np.array([c.bank_angle for c in cyls])
    f_pin = cf.crankpin_force(bl.detail.big_end_crank, pins, n_pins)  # (C, S, T, N)
    try:
        gamma = cf.throw_angles(firing, bank, pins, n_pins)
    except ValueError as exc:
        raise MissingInputs([f"Cylinders: {exc}"]) from None
    f_r, f_t = cs.pin_force_in_throw_frame(f_pin.x, f_pin.y, gamma[:, None])
    return f_r, f_t, gamma


def _items(n_pins: int, n_mains: int, has: dict[str, bool], results: dict[str, object]
           ) -> list[tuple[str, str, object, list[tuple[int, int]]]]:
    """(item, location type, result, its two candidates) of every location.

    Candidates index the last two axes of the result: (throw, web) of a fillet, (throw,
    torque side: both the pin's torque) of a pin oil hole, (main, element candidate) of a
    main oil hole."""
    sel = []
    for j in range(n_pins):
        sel.append((f"pin {j + 1} fillet", "pin fillet", results["pin fillet"],
                    [(j, 0), (j, 1)]))
    for m in range(n_mains):
        adj = ([(m, 0)] if m < n_pins else []) + ([(m - 1, 1)] if m > 0 else [])
        sel.append((f"main {m + 1} fillet", "main fillet", results["main fillet"], adj))
    for loc, n in (("pin oil hole", n_pins), ("main oil hole", n_mains)):
        if has[loc]:
            word = loc.split()[0]
            for j in range(n):
                sel.append((f"{word} {j + 1} oil hole", loc, results[loc], [(j, 0), (j, 1)]))
    return sel


def _findings(location: list[str], where: _Locations, et: Quantity) -> dict[tuple, list[str]]:
    """M53 validity of the factors a location uses; undamped TV resonance at (case, speed)."""
    findings: dict[tuple, list[str]] = {}
    for i, lname in enumerate(location):
        texts = [t for key in FACTORS_OF[lname] for t in where.scf_find.get(key, [])]
        if texts and lname not in where.loc_missing:
            findings[(i,)] = list(dict.fromkeys(texts))
    tv_find: dict[tuple[int, int], list[str]] = {}
    for (_, ci, si), v in et.findings.items():
        lst = tv_find.setdefault((ci, si), [])
        lst += [x for x in v if x not in lst]
    for (ci, si), v in tv_find.items():
        for i in range(len(location)):
            findings[(i, ci, si)] = list(v)
    return findings


def _m53(engine: Engine, g: ThrowGeometry, where: _Locations, location: list[str],
         cand, findings: dict[tuple, list[str]], shape: tuple[int, int],
         tau_system: dict[str, float] | None = None) -> dict:
    """M53 Q of every location but the main oil holes: values, sigma_V, sigma_DW, missing
    inputs and findings (indices into the M53 items). ``tau_system``: the local alternating
    shear stress of each location type from the whole dynamic system's largest nominal
    stress (:func:`_m53_torsion`); ``None``: the stress at each speed (``cand.tau_a``)."""
    fa = engine.fatigue
    m53_items = [i for i, lname in enumerate(location) if lname != "main oil hole"]
    uts = fa.get("uts")
    q_vals = np.full((len(m53_items), *shape), np.nan)
    sv_pick = np.full((len(m53_items), *shape), np.nan)
    q_missing: dict[tuple, list[str]] = {}
    q_find: dict[tuple, list[str]] = {}
    dw_of: dict[str, float] = {}
    m53_base_missing = []
    if uts is None:
        m53_base_missing.append(engine.describe_missing("Fatigue", "uts",
                                                        what="the crankshaft (M53 sigma_B)"))
    oil = where.oil
    radius = {"pin fillet": ("pin_fillet_radius", g.pin_diameter, M53_K_FILLET),
              "main fillet": ("main_fillet_radius", g.journal_diameter, M53_K_FILLET),
              "pin oil hole": (None, g.pin_diameter, M53_K_OIL)}
    clip_text = {}
    for lname, (rattr, dia, kk) in radius.items():
        if not where.has[lname]:
            continue
        if lname == "pin oil hole":
            rx = None if oil is None or oil.diameter is None else oil.diameter / 2.0
        else:
            rx = fa.get(rattr)
        if uts is None or rx is None:
            continue
        dw = fat.m53_fatigue_strength(uts, dia, rx, kk)
        dw_of[lname] = float(dw.value)
        if bool(dw.radius_clipped):
            clip_text[lname] = (f"M53 sigma_DW ({lname}): radius {rx * 1e3:.3g} mm below 2 mm,"
                                " taken as 2 mm (IACS UR M53 §6)")
    for qi, i in enumerate(m53_items):
        lname = location[i]
        why = list(m53_base_missing) + where.stress_missing.get(lname, [])
        if lname != "pin oil hole" and fa.get(radius[lname][0]) is None:
            why.append(engine.describe_missing("Fatigue", radius[lname][0],
                                               what="the crankshaft (M53 sigma_DW)"))
        if why:
            q_missing[(qi,)] = list(dict.fromkeys(why))
            continue
        # (C, S): worst fillet / torque variant
        tau = cand.tau_a[:, :, i, :]
        if tau_system is not None:  # M53 2.2(A)(f): the highest value over the speed range
            tau = np.full_like(tau, tau_system[lname])
        sv_pick[qi], q_vals[qi] = tf.m53_q(cand.sigma_a[:, :, i, :], tau,
                                           dw_of[lname], lname == "pin oil hole", SIGMA_ADD)
        texts = list(findings.get((i,), []))
        if lname in clip_text:
            texts.append(clip_text[lname])
        if texts:
            q_find[(qi,)] = texts
    for (i, ci, si), v in ((k_, v_) for k_, v_ in findings.items() if len(k_) == 3):
        if i in m53_items:
            q_find[(m53_items.index(i), ci, si)] = v
    return {"items": m53_items, "values": q_vals, "sigma_v": sv_pick, "sigma_dw": dw_of,
            "missing": q_missing, "findings": q_find}


@calculation("fillet_bending_ratio", "fatigue", provides=("fatigue.fillet_bending_ratio",),
             needs=("loads.bearing_load",),
             reads=("fatigue", "params", "cylinders", "crank", "bearings.name", "bearings.type",
                    "bearings.index", "bearings.diameter", "bearings.journal_length",
                    "bearings.support_stiffness", "bearings.support_offset"))
def fillet_bending_ratio(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Continuous-beam over determinate fillet bending moment per throw and fillet.

    The workbook's continuous scheme, or under the determinate scheme the beam on rigid
    supports (what choosing it would change); con-rod forces on the pins only, as IACS UR M53
    counts them, so the two schemes differ in their supports alone (the figure of Piraner,
    Pflueger and Bouthier, Cummins crankshaft and bearing analysis process, 2002, Fig. 1).
    """
    if engine.crank is None:
        raise MissingInputs(["Crank: the continuous beam needs the crank's geometry (sheet"
                             " Crank)"])
    bl: Quantity = inputs["loads.bearing_load"]
    g, _, _ = _geometry(engine)
    pins = np.array([c.pin - 1 for c in engine.cylinders])
    n_pins = int(pins.max()) + 1
    f_r, f_t, gamma = _pin_forces(engine, bl, pins, n_pins)
    scheme = support_beam.scheme_of(engine)
    if scheme == "determinate":
        scheme = "continuous beam, rigid supports"
    beam = support_beam.build_beam(engine, gamma, scheme)
    theta = np.asarray(bl.detail.theta)
    cont, det = support_beam.throw_sections(beam, f_r, f_t, gamma, g.as_kwargs(), theta)
    items, a_c, a_d, case, speed = [], [], [], [], []
    cases, speeds = list(bl.coords["case"]), np.asarray(bl.coords["speed"], dtype=float)
    for fillet, key in (("pin fillet", "moment_pin_fillet"),
                        ("main fillet", "moment_journal_fillet")):
        mc, md = getattr(cont, key), getattr(det, key)  # (C, S, T, 2, N)
        amp_c = (mc.max(axis=-1) - mc.min(axis=-1)) / 2.0
        amp_d = (md.max(axis=-1) - md.min(axis=-1)) / 2.0
        for t in range(n_pins):
            for side, web in enumerate(("front", "rear")):
                ad = amp_d[:, :, t, side]
                ci, si = np.unravel_index(int(np.argmax(ad)), ad.shape)
                items.append(f"throw {t + 1} {fillet}, {web} web")
                a_c.append(amp_c[ci, si, t, side])
                a_d.append(ad[ci, si])
                case.append(cases[ci])
                speed.append(speeds[si])
    a_c, a_d = np.array(a_c), np.array(a_d)
    if np.any(a_d <= 0.0):
        raise MissingInputs(["a fillet without determinate bending (no pin force): the ratio"
                             " is undefined"])
    detail = FilletRatioDetail(
        scheme=scheme, amplitude_continuous=a_c, amplitude_determinate=a_d, case=tuple(case),
        speed=np.array(speed),
        assumptions=(f"Fillet bending ratio: the crank as a continuous beam ({scheme}) against"
                     " the statically determinate scheme, under the con-rod forces on the pins"
                     " (IACS UR M53's loads), bending moment amplitudes at the operating point"
                     " of each fillet's largest determinate amplitude.",))
    return {"fatigue.fillet_bending_ratio": Quantity(FILLET_RATIO, a_c / a_d, {"item": items},
                                                     detail=detail)}


def _assumptions(engine: Engine, has: dict[str, bool], notes: list[str]) -> list[str]:
    """The method's assumptions, then the notes of this run."""
    assumptions = [
        "Crankshaft fatigue (classical, Bell, Ricardo 2013, 'Crankshaft analysis (25)-(28)';"
        " IACS UR M53 §2-5): each throw"
        " simply supported at its main journal centres (statically determinate, no load"
        " sharing, no bending vibration); con-rod gas and inertia forces on the pin; web width"
        " B = minimum web width; K_e = 1 (4-stroke). The crank's own centrifugal forces (pin,"
        " webs, counterweights) are not included (M53 loading; they shift only the mean).",
        "Crankshaft torsion from the TV model, synthesised over the cycle (mean + all orders,"
        " same crank angle as the bending): a main journal carries the element torque between"
        " the cylinder stations on either side; the crank pin (its fillets and oil hole) the"
        " torque of a throw simply supported at its mains, between its two elements' torques"
        " in the ratio of the main bearings' shares of the rod force (their mean for a"
        " centred pin). Mean torque = sum of the mean"
        " cylinder (indicated) torques from the front minus the FEAD torque (friction not"
        " subtracted, conservative).",
        "Goodman safety factor: von Mises of the amplitudes (half range over the cycle), signed"
        " von Mises mean (compressive means not credited), SF = 1/(σa/Se + σm/Su); oil holes:"
        " M53 maximum-principal combination of bending and torsion.",
        f"M53 acceptability Q: σ_add = {SIGMA_ADD / 1e6:g} MPa (trunk piston), σ_DW from M53 §6"
        f" with the base UTS, K = {M53_K_FILLET:g} at fillets (drop forged, assumed) and"
        f" {M53_K_OIL:g} at the oil bore; fillet rolling/induction hardening not credited"
        " (M53 accepts surface-treatment gains only from tests).",
    ]
    if support_beam.scheme_of(engine) != "determinate":
        assumptions[0] = (
            "Crankshaft fatigue (IACS UR M53 §2-5 stresses and factors) with the bending moments"
            f" and web forces of the crank as a {support_beam.scheme_of(engine)} (Piraner,"
            " Pflueger and Bouthier, Cummins crankshaft and bearing analysis process, 2002):"
            " con-rod gas and inertia forces on the pins, carried to every main by the beam;"
            " web width B = minimum web width; K_e = 1 (4-stroke). The crank's own"
            " centrifugal forces are not included (M53 loading; they shift only the mean).")
    if has["main oil hole"]:
        assumptions.append("Main journal oil holes: torsion only (the statically determinate"
                           " bending moment is zero at the journal centre), γ_T of M53's"
                           " crank-pin oil bore with d_O = D_O/D_G (M53 has no journal oil-bore"
                           " factor); evaluated at every main journal.")
    return assumptions + notes + loads.shared_pins_text(engine)


def _candidate_names(sel: list, main_el: np.ndarray, element_names: list[str]
                     ) -> list[tuple[str, ...]]:
    """The two candidates of each item in words (web, torque side or TV element)."""
    n_el = len(element_names)
    side_text = {"pin fillet": ("front web", "rear web"),
                 "pin oil hole": ("pin torque", "pin torque")}
    out = []
    for _, lname, _, adj in sel:
        if lname == "main fillet":
            out.append(tuple(f"throw {t + 1} {'front' if s == 0 else 'rear'} web"
                             for t, s in (adj * 2)[:2]))
        elif lname == "main oil hole":
            out.append(tuple(element_names[e] if e < n_el else "free end"
                             for e in main_el[int(adj[0][0])]))
        else:
            out.append(side_text[lname])
    return out


def _m53_torsion(engine: Engine, inputs: dict, g: ThrowGeometry, k: dict[str, float],
                 speeds: np.ndarray) -> tuple[dict[str, float] | None, str]:
    """M53's alternating torsional stress of each location type, and which torque it is from.

    IACS UR M53 2.2(A)(a), (f): the nominal alternating torsional stress is the highest value,
    over the speed range, of the harmonic synthesis of the *complete dynamic system* at its
    most torsionally loaded mass point of the crankshaft, stresses inside barred speed ranges
    left out. Where the TV model is that system (stations behind the crank: coupling and
    driven machine), ``M_TN`` is the largest half range of the crank sections' torque
    (``tv.crank_shear_stress``) over the load cases' operating envelopes outside the barred
    ranges, ``tau_N = M_TN / W_P`` of the crank pin (pin fillet, oil bore) or the journal
    (journal fillet), times alpha_T, beta_T, gamma_T. Otherwise (the engine's own TV model: no
    driven machinery) ``None``: each speed's own torque, combined with that speed's bending.
    """
    if not tvs.whole_system(engine):
        return None, (
            "M53 torsion (FAT-002): the TV model is the engine's own (no driven machinery"
            " behind the crank in sheet TVModel), so each speed's synthesised torque is"
            " combined with that speed's bending; IACS UR M53 2.2(A)(a),(f) takes the highest"
            " nominal torsional stress of the complete dynamic system (engine, couplings,"
            " driven machine) over the speed range, which needs that system in TVModel.")
    stress = inputs.get("tv.crank_shear_stress")
    if stress is None:
        why = "; ".join(inputs.get(UNAVAILABLE, {}).get("tv.crank_shear_stress", []))
        return None, ("M53 torsion (FAT-002): the crank's nominal TV stress of the whole"
                      f" dynamic system is not available ({why or 'not computed'}); each"
                      " speed's own torque is used.")
    d = stress.detail
    torque = stress.values * d.polar_modulus[:, None, None]  # (E, C, S) M_TN per section
    judged = np.ones(torque.shape[1:], bool) if d.envelope is None else d.envelope.copy()
    barred = inputs.get("tv.barred_speed_range")
    ranges = []
    if barred is not None:
        for lo, hi in zip(barred.detail.lower, barred.detail.upper, strict=True):
            judged &= ~((speeds >= lo) & (speeds <= hi))[None, :]
            ranges.append(f"{lo / RPM:.0f}..{hi / RPM:.0f} rpm")
    if not judged.any():
        return None, ("M53 torsion (FAT-002): no speed of the operating range lies outside"
                      " the barred speed ranges; each speed's own torque is used.")
    e, ci, si = np.unravel_index(int(np.argmax(np.where(judged[None], torque, -np.inf))),
                                 torque.shape)
    m_tn = float(torque[e, ci, si])
    _, w_pin = cs.shaft_section_moduli(g.pin_diameter, g.pin_bore)
    _, w_jnl = cs.shaft_section_moduli(g.journal_diameter, g.journal_bore)
    tau_pin, tau_jnl = m_tn / float(w_pin), m_tn / float(w_jnl)
    text = (f"M53 torsion (FAT-002): the whole dynamic system of sheet TVModel (stations behind"
            f" the crank), largest synthesised half range M_TN = {m_tn:.0f} N m in"
            f" {stress.coords['item'][e]} at {speeds[si] / RPM:.0f} rpm"
            f" ({stress.coords['case'][ci]} load) over the operating range"
            + (f" outside the barred speed ranges {', '.join(ranges)}" if ranges else "")
            + f": tau_N = {tau_pin / 1e6:.1f} MPa (crank pin), {tau_jnl / 1e6:.1f} MPa"
              " (journal), at every speed (IACS UR M53 2.2(A)(f)).")
    return {"pin fillet": k["alpha_t"] * tau_pin, "main fillet": k["beta_t"] * tau_jnl,
            "pin oil hole": k["gamma_t"] * tau_pin}, text


# ------------------------------------------------------------------------------- calculation
def _needs(engine: Engine) -> tuple[str, ...]:
    """The loads and element torques; the crank's nominal TV stress (M53's whole-system
    torsional stress, and the report's stress plot) and, for an engine whose class rules bar
    speed ranges, those ranges (left out of M53's speed range)."""
    out = ("loads.bearing_load", "tv.element_torque", "tv.crank_shear_stress")
    if tvs.whole_system(engine) and tvs.bars_speed_ranges(engine):
        out += ("tv.barred_speed_range",)
    return out


@calculation("crank_fatigue", "fatigue", provides=("fatigue.goodman_sf", "fatigue.m53_q"),
             needs=_needs, optional=("tv.crank_shear_stress", "tv.barred_speed_range"),
             reads=("fatigue", "params", "cylinders", "tv_model", "crank",
                    "bearings.support_stiffness", "bearings.support_offset",
                    "bearings.name", "bearings.type",
                    "bearings.diameter", "bearings.journal_length", "bearings.row",
                    "bearings.oil_holes", "bearings.oil_hole_diameter",
                    "bearings.oil_hole_angle", "bearings.oil_hole_type"))
def crank_fatigue(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Goodman safety factor and M53 Q at every fillet and oil hole, full/no load, all speeds.

    Gathers the inputs (geometry, factors, strengths, pin forces, element torques), calls
    :mod:`checker.calc.throw_fatigue` and wraps the results (:mod:`checker.results.fatigue`).
    """
    bl: Quantity = inputs["loads.bearing_load"]
    et: Quantity = inputs["tv.element_torque"]
    g, rows, notes = _geometry(engine)
    pins = np.array([c.pin - 1 for c in engine.cylinders])
    n_pins = int(pins.max()) + 1
    n_mains = n_pins + 1
    theta = np.asarray(bl.detail.theta)
    cases, speeds = list(bl.coords["case"]), np.asarray(bl.coords["speed"], dtype=float)
    C, S = len(cases), speeds.size
    if list(et.coords["case"]) != cases or not np.allclose(et.coords["speed"], speeds):
        raise MissingInputs(["tv.element_torque and loads.bearing_load disagree on the load"
                             " cases or speeds (internal)"])
    where = _locations(engine, g, rows["bigs"], notes)
    f_r, f_t, gamma = _pin_forces(engine, bl, pins, n_pins)
    sections = None
    if support_beam.scheme_of(engine) != "determinate":
        beam = support_beam.build_beam(engine, gamma)
        sections, _ = support_beam.throw_sections(beam, f_r, f_t, gamma, g.as_kwargs(), theta)
    n_el = len(et.coords["item"])
    sides, st_missing = _station_elements(engine, n_pins, n_el)
    if st_missing:
        raise MissingInputs(st_missing)
    # (C, S, E + 1, N): + a zero "element" for a free end
    torque = tf.element_torque_cycle(et.detail.orders, et.detail.coeffs, et.detail.mean,
                                     theta.size)
    t_side = torque[:, :, sides, :]  # (C, S, T, 2, N): front / rear element of each throw
    main_el = tf.main_journal_elements(sides, n_mains)

    # ------------------------------------------------------------- stresses and Goodman
    oil = where.oil
    phi = 0.0 if oil is None or oil.angle is None else float(oil.angle)
    k = where.factors()
    # one load case at a time: halves the peak memory (fresh pages are the main cost here)
    try:
        parts = [tf.throw_goodman(f_r[ci], f_t[ci], t_side[ci], g.as_kwargs(), phi, k,
                                  {n: where.strength(n) for n in LOCATIONS},
                                  where.has["pin oil hole"], MEAN_CRITERION,
                                  None if sections is None else
                                  cs.SectionLoads(*(x[ci] for x in sections)))
                 for ci in range(C)]
    except ValueError as exc:
        raise MissingInputs([f"Fatigue/Bearings/Engine geometry of the crank throw: {exc}"]
                            ) from None
    results: dict[str, object] = {  # (C, S, T, 2): per web or torque side
        loc: None if parts[0][n] is None else type(parts[0][n])(
            *(np.stack(x) for x in zip(*(p[n] for p in parts), strict=True)))
        for n, loc in enumerate(("pin fillet", "main fillet", "pin oil hole"))}
    if where.has["main oil hole"]:
        # torsion only, once per TV element, then per main journal and candidate element
        per_el = tf.main_oil_hole_goodman(torque, g.journal_diameter, g.journal_bore,
                                          k["gamma_t_main"], *where.strength("main oil hole"))
        results["main oil hole"] = type(per_el)(*(x[:, :, main_el] for x in per_el))

    # ------------------------------------------------------------- items: governing candidate
    sel = _items(n_pins, n_mains, where.has, results)
    items = [s[0] for s in sel]
    location = [s[1] for s in sel]
    cand = tf.gather_candidates([s[2] for s in sel], [(s[3] * 2)[:2] for s in sel])
    picked, governing = tf.governing_candidate(cand)  # (C, S, I)
    pick = {f: np.moveaxis(v, 2, 0) for f, v in picked._asdict().items()}  # (I, C, S)
    sf = pick["safety_factor"].copy()
    attrs = {n: {"location": lname} for n, lname in zip(items, location, strict=True)}
    missing: dict[tuple, list[str]] = {}
    for i, lname in enumerate(location):
        if lname in where.loc_missing:
            sf[i] = np.nan
            missing[(i,)] = where.loc_missing[lname]
    findings = _findings(location, where, et)
    tau_system, basis = _m53_torsion(engine, inputs, g, where.factors(), speeds)
    m53 = _m53(engine, g, where, location, cand, findings, (C, S), tau_system)

    # ------------------------------------------------------------- details
    loc_arr = np.array(location)
    sf_by_loc = np.full((len(LOCATIONS), C, S), np.nan)
    for li, lname in enumerate(LOCATIONS):
        rows_i = np.nonzero(loc_arr == lname)[0]
        if rows_i.size and lname not in where.loc_missing:
            sf_by_loc[li] = sf[rows_i].min(axis=0)
    s_e = np.array([where.strengths.get(n, (None,))[0] or np.nan for n in location],
                   dtype=float)
    s_u = np.array([(where.strengths.get(n, (None, None))[1] or np.nan) for n in location],
                   dtype=float)
    element_names = list(et.coords["item"]) + ["free end"]
    common = dict(
        geometry=g, scf=where.scf, scf_findings=where.scf_find, strengths=where.strengths,
        oil_hole=oil, main_oil_hole_diameter=where.main_oil_d, theta=theta, speeds=speeds,
        locations=location, sf_by_location=sf_by_loc,
        assumptions=tuple(_assumptions(engine, where.has, notes)))
    caveats = ()
    if sections is not None and where.has["main oil hole"]:
        caveats = ({"kind": "model validity", "severity": "medium", "rules": ["FAT-001"],
                    "text": "Main-journal oil holes are checked in torsion only, as in the"
                    " statically determinate scheme; on the continuous beam chosen here the"
                    " main journals also carry the support bending moments, which that check"
                    " does not include: their safety factors are not conservative."},)
    detail = GoodmanDetail(
        **common, caveats=caveats,
        sigma_eq_a=pick["sigma_eq_a"], sigma_eq_m=pick["sigma_eq_m"],
        sigma_a=pick["sigma_a"], sigma_m=pick["sigma_m"], tau_a=pick["tau_a"],
        tau_m=pick["tau_m"], governing=np.moveaxis(governing, 2, 0),
        candidates=_candidate_names(sel, main_el, element_names[:-1]),
        sigma_eq_max=pick["sigma_eq_m"] + pick["sigma_eq_a"],
        sigma_eq_min=pick["sigma_eq_m"] - pick["sigma_eq_a"],
        endurance_limit=s_e, ultimate_strength=s_u,
        haigh_x=pick["sigma_eq_m"] / s_u[:, None, None],
        haigh_y=pick["sigma_eq_a"] / s_e[:, None, None],
        candidate_sf=np.moveaxis(cand.safety_factor, 2, 0),
        pin_force_radial=f_r, pin_force_tangential=f_t,
        throw_angle=gamma, throw_elements=sides, main_elements=main_el,
        nominal=ThrowNominal(
            sigma_web_bending=np.stack([p.nominal.sigma_web_bending for p in parts]),
            sigma_web_direct=np.stack([p.nominal.sigma_web_direct for p in parts]),
            web_centre_distance=parts[0].nominal.web_centre_distance,
            overlap=parts[0].nominal.overlap),
        element_names=element_names, element_torque=torque, mean_criterion=MEAN_CRITERION)
    coords = {"item": items, "case": cases, "speed": list(speeds)}
    q_items = [items[i] for i in m53["items"]]
    return {
        "fatigue.goodman_sf": Quantity(GOODMAN, sf, coords, attrs, missing, findings,
                                       detail=detail),
        "fatigue.m53_q": Quantity(
            M53Q, m53["values"], {"item": q_items, "case": cases, "speed": list(speeds)},
            {n: attrs[n] for n in q_items}, m53["missing"], m53["findings"],
            detail=M53Detail(**dict(common, assumptions=common["assumptions"] + (basis,)),
                             torsion_basis=basis, sigma_v=m53["sigma_v"],
                             sigma_dw=m53["sigma_dw"],
                             sigma_add=SIGMA_ADD, k_fillet=M53_K_FILLET, k_oil=M53_K_OIL)),
    }
