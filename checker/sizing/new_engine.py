"""Size a first crank-train layout from a brief and write it as a complete workbook.

Every derived value carries a note ``ESTIMATE (checker new): <rule>; <source>``; the rules and
their sources are those of :mod:`checker.calc.first_layout` (docs/new-engine.md). The
estimates are made consistent with each other by running the checker's own models on the
layout (:func:`size`): the flywheel is sized for the class's irregularity target at the lowest
speed by the flywheel module, the damper ring tuned to Den Hartog's optimum by the damper-tuning
module, the bolted joints sized for the torsional model's joint torques with the recommended
preload, and the project limits the rules need are set by class
(:mod:`checker.sizing.project_limits`). The crank type and firing come from
:mod:`checker.sizing.crank_types`; dimensions outside the band of real engines are listed
(:func:`plausibility`) for the console and the report.

The crank is written as its geometry (sheets Crank and CrankEnds, issue 33): the crank
module derives its CrankMass rows and the crank stations' TVModel inertias, and Bearings and
Fatigue take its dimensions. The counterweights are sized with the crank-geometry module's
mass properties (:func:`checker.calc.crank_geometry.throw_mass_properties`); the crank
stations' inertias and stiffnesses are left blank in TVModel and derived by the crank module
(its throw stiffness fitted to a 3D FE, :mod:`checker.calc.throw_stiffness`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..calc import first_layout as fl
from ..calc.bolted_joint import PRELOAD_FRACTIONS, effective_friction_diameter, tensile_stress_area
from ..calc.crank_geometry import cylinder, throw_mass_properties
from ..results.caveats import PLAUSIBILITY_MARK
from . import crank_types, project_limits
from .bench import Bench
from .brief import Brief

TAG = "ESTIMATE (checker new)"
RPM = 30.0 / math.pi


def est(rule_key: str | None, text: str = "") -> str:
    """A note: ESTIMATE, the rule and its source (from :data:`first_layout.RULES`)."""
    if rule_key is None:
        return f"{TAG}: {text}"
    r = fl.RULES[rule_key]
    conf = "" if r["confirmed"] else " [ratio not confirmed in a public source]"
    return f"{TAG}: {text + '; ' if text else ''}{r['rule']}; {r['source']}{conf}"


MATERIALS = {  # density, E, nu, strengths [MPa] (Bell 2013 data for the steel)
    "forged steel": {
        "density": 7850.0, "E": 210e9, "nu": 0.3, "uts": 750, "fillet_uts": 920, "yield": 450,
        "fatigue": 375, "hydro": 543.75, "torsion": 217.5, "fillet_yield": 750,
        "pin_fillet": 619, "pin_hole": 326, "main_fillet": 611, "main_hole": 326,
        "source": "C38+N2BY forged steel, rolled fillets, induction-hardened oil holes: the"
                  " strengths of Bell, Ricardo 2013; steel density 7850 kg/m^3, E 210 GPa,"
                  " nu 0.3"},
    "42CrMo4": {
        "density": 7850.0, "E": 210e9, "nu": 0.3, "uts": 900, "fillet_uts": 1104, "yield": 650,
        "fatigue": 450, "hydro": 652.5, "torsion": 261, "fillet_yield": 1083,
        "pin_fillet": 742, "pin_hole": 391, "main_fillet": 734, "main_hole": 386,
        "source": "42CrMo4 +QT forged alloy steel (EN 10083-3:2006, 40-100 mm: R_m 900-1100,"
                  " R_e >= 650 MPa; the minima), rolled fillets, induction-hardened oil holes:"
                  " strengths derived as Bell, Ricardo 2013 derives C38+N2BY's (fatigue 0.5 x"
                  " UTS, torsion 0.58 x, hydrostatic 2.5 x torsion, the same size and treatment"
                  " factors; fillet UTS and yield scaled by Bell's ratios [not confirmed]);"
                  " steel density 7850 kg/m^3, E 210 GPa, nu 0.3"},
    "nodular iron": {
        "density": 7100.0, "E": 174e9, "nu": 0.275, "uts": 800, "fillet_uts": 800, "yield": 480,
        "fatigue": 300, "hydro": 435, "torsion": 174, "fillet_yield": 600,
        "pin_fillet": 470, "pin_hole": 261, "main_fillet": 465, "main_hole": 258,
        "source": "EN-GJS-800-2 nodular iron (EN 1563 minimum UTS 800, yield 480 MPa); density,"
                  " E 174 GPa, nu 0.275, fatigue 0.375 UTS, rolled fillets x 1.8 [not confirmed"
                  " in a public source]"},
}

def padm_text(b: Brief) -> str:
    """What the notes say of the admissible bearing pressure when the brief sets it."""
    if "bearing_pressure" in b.defaults:
        return ""
    p = b.bearing_pressure / 1e6
    out = "" if 41 <= p <= 83 else ", outside the published 41-83 MPa of engine linings"
    return f" [p_s = {p:g} MPa given in the brief{out}: the brief's value, not the rule's]"


FLY_SOURCE = ("a four-cylinder at 800 rpm idle turns between about 710 and 860 rpm, 19 %"
              " (J. Venter, 'Doing the twist', CAR magazine) [one measurement, not a"
              " standard]")


class NoRule(ValueError):
    """The brief needs a rule that has no data (the message says which)."""


@dataclass(frozen=True)
class Layout:
    brief: Brief
    throws: int
    throw_angle: list[float]  # deg, per throw
    cyl_throw: list[int]  # per cylinder (1-based)
    cyl_bank: list[float]  # deg
    cyl_firing: list[float]  # deg
    firing_order: str
    firing_note: str
    force: float  # worst crank-pin force over the speed range (journal sizing)
    gas: float  # peak gas force (rod stem)
    dp: float
    dj: float
    rod_land: float
    pin_len: float
    main_land: float
    main_len: float
    fillet_p: float
    fillet_j: float
    tw: float
    bw: float
    rod_len: float
    spacing: float
    wrist: fl.WristPin
    piston: float
    rod: fl.Rod
    cw_ri: float
    cw_ro: float
    cw_angle: float
    cw_thickness: float
    balance_target: float
    clearance_main: float
    clearance_pin: float
    engine_class: str = "passenger car"
    crank_type: str = "in-line"
    even_firing: bool = True
    intervals: tuple[float, ...] = ()
    f_pin: float = 0.0  # worst crank-pin force over the speed range [N]
    f_main: float = 0.0  # worst main-bearing force [N]
    cw_achieved: float = 1.0  # counterweight unbalance / target
    balance_rec: float = 0.0  # the target's reciprocating part (kg m; 90-degree V, in-throw)
    plausibility: tuple[str, ...] = ()  # sized dimensions outside the band of real engines
    oil_hole_angle: float = 45.0  # deg, crank-pin oil hole from the throw axis, + leading
    material: str = "forged steel"  # the crank's material (MATERIALS; the brief's, or moved)
    nose_ratio: float = 0.75  # crank nose diameter / main journal diameter (NOSE; or moved)
    lining_main: str = ""  # the mains' lining ("": the brief's; or moved by the loop)
    lining_pin: str = ""  # the big ends' lining ("": the brief's; or moved by the loop)


def _throws_and_firing(b: Brief) -> crank_types.Arrangement:
    try:
        return crank_types.arrange(b.cylinders, b.layout, b.bank_angle, b.crank_type,
                              b.firing_order)
    except crank_types.NoArrangement as exc:
        raise NoRule(str(exc)) from None


WEB_MIN = 0.22
"""Thinnest web a crank that is longer than its cylinder pitch is given, per bore: the low end of
Khurmi & Gupta's 0.22-0.32 x bore (A Textbook of Machine Design, §32.19)."""

CW_BULKHEAD = 0.80
"""Radius of the main bearing's housing (bulkhead) as a fraction of the journal diameter: a
counterweight thicker than its web overhangs the web axially and must clear it (inner radius at
least 0.8 x the journal diameter: shell, housing wall) [ratio not confirmed]."""


def _cw_for_target(b: Brief, geo: dict, target_unbalance: float, mat: dict, ro_max: float,
                   t_max: float) -> tuple[float, float, float, float, float]:
    """Inner and outer radius, angle and axial thickness of the two counterweights of a throw
    whose unbalance (kg m, opposite the pin) is ``target_unbalance`` (crank geometry of the
    crank branch), and the fraction of the target they reach: 150 deg at the web thickness
    first, then 180 deg, then thicker (up to ``t_max``), a thicker counterweight starting
    clear of the main bearing (:data:`CW_BULKHEAD`); none reaches it: the largest that fits
    (the caller states the fraction)."""
    rj = geo["journal_diameter"] / 2.0
    tw = geo["web_thickness"]

    def u(ri: float, ro: float, ang: float, tc: float) -> float:
        p = throw_mass_properties(**geo, density=mat["density"], cw_inner_radius=ri,
                                  cw_outer_radius=ro, cw_angle=ang, cw_thickness=tc)
        return float(-(p.mass[0, 2] * p.y[0, 2] + p.mass[0, 5] * p.y[0, 5]))

    rb = CW_BULKHEAD * geo["journal_diameter"]
    tries = [(150.0, tw, rj), (180.0, tw, rj)]
    if rb < 0.9 * ro_max:
        tries += [(180.0, min(f * tw, t_max), rb) for f in (1.25, 1.5, 2.0) if f * tw <= t_max]
    best = None
    for ang_deg, tc, ri in tries:
        ang = math.radians(ang_deg)
        ri = math.ceil(ri * 1e5) / 1e5  # written in mm to 2 decimals: never inside the journal
        if ro_max <= ri * 1.01:
            continue
        full = u(ri, ro_max, ang, tc)
        if full >= target_unbalance:
            lo, hi = ri * 1.0001, ro_max
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if u(ri, mid, ang, tc) < target_unbalance:
                    lo = mid
                else:
                    hi = mid
            return ri, hi, ang, tc, 1.0
        if best is None or full > best[4] * target_unbalance:
            best = (ri, ro_max, ang, tc, full / target_unbalance)
    if best is None or best[4] <= 0.0:
        raise NoRule("counterweight: the swing radius (rod length - crank radius - 0.25 bore,"
                     f" {ro_max * 1e3:.0f} mm) leaves no room outside the main journal; the"
                     " counterweight rule has no data for this geometry")
    return best


def _rod_and_forces(b: Brief, cls: dict, dp: float, land: float, rod_len: float,
                    wp: fl.WristPin, piston: float, gas: float, rods: int
                    ) -> tuple[fl.Rod, float, float, float, float]:
    """The con-rod for a big end of ``land`` on a pin ``dp``, its reciprocating and rotating
    masses and the worst pin and main forces over the speed range."""
    rod = fl.con_rod(force=gas, length=rod_len, pin_d=dp, pin_land=land, wrist=wp)
    m_rot = rod.mass * (rod_len - rod.centre_from_big_end) / rod_len
    m_rec = piston + rod.mass - m_rot
    f_pin, f_main = fl.sizing_forces(gas=gas, m_rec=m_rec, m_rot=m_rot,
                                     crank_radius=b.stroke / 2.0, rod_length=rod_len,
                                     min_speed=b.min_speed, max_speed=b.max_speed, rods=rods,
                                     bank_angle=b.bank_angle if rods > 1 else 0.0)
    return rod, m_rot, m_rec, f_pin, f_main


def layout(b: Brief) -> Layout:
    """Size every dimension by its rule (:mod:`checker.calc.first_layout`)."""
    arr = _throws_and_firing(b)
    n_thr = max(arr.cyl_throw)
    rods_per_pin = b.cylinders // n_thr
    cls = fl.CLASSES[b.engine_class]
    gas = fl.peak_gas_force(b.bore, b.peak_pressure)
    rod_len = fl.rod_length(b.stroke, b.engine_class)
    wp = fl.wrist_pin(b.bore, b.fuel)
    piston = fl.piston_mass(b.bore, b.fuel) + wp.mass
    p_s = b.bearing_pressure
    ld = cls["pin_ld"]
    land_ld = ld if rods_per_pin == 1 else cls["shared_ld"]
    dp = fl.pin_diameter(gas, p_s, ld)
    for _ in range(30):  # the rod's big eye and masses follow the pin; the pin the forces
        rod, m_rot, m_rec, f_pin, f_main = _rod_and_forces(
            b, cls, dp, land_ld * dp, rod_len, wp, piston, gas, rods_per_pin)
        new = fl.pin_diameter(f_pin, p_s, ld)
        if abs(new - dp) < 1e-8:
            break
        dp = new
    rod_land = land_ld * dp
    dj = fl.main_diameter(dp, f_main, p_s, cls["main_ld"])
    rf_p, rf_j = fl.fillet_radius(dp), fl.fillet_radius(dj)
    main_land = fl.main_land(f_main, dj, p_s, cls["main_ld_band"])
    pin_len = rods_per_pin * rod_land + 2 * (rf_p + 1e-3) + (rods_per_pin - 1) * 1e-3
    main_len = main_land + 2 * (rf_j + 1e-3)
    tw = fl.web_thickness(b.bore)
    split = arr.crank_type == "split pins"
    bore_pitch = fl.cylinder_pitch(b.bore, 0.0, cls["pitch_wall"])
    throw_pitch = bore_pitch / 2.0 if split else bore_pitch  # split: two throws per pitch
    stack = main_len + 2 * tw + pin_len
    if stack > throw_pitch:  # thinner webs, down to Khurmi & Gupta's 0.22 x bore
        tw = max(WEB_MIN * b.bore, (throw_pitch - main_len - pin_len) / 2.0, 0.0)
    else:  # the crank fills the pitch: longer mains (to the L/D band), then thicker webs
        extra = throw_pitch - stack
        grow = max(min(extra, cls["main_ld_band"][1] * dj - main_land), 0.0)
        main_land += grow
        main_len += grow
        extra -= grow
        dt = min(extra / 2.0, max(cls["web_band"][1] * b.bore * 0.95 - tw, 0.0))
        tw += dt
        extra -= 2 * dt
        main_land += extra
        main_len += extra
    spacing = main_len + 2 * tw + pin_len
    bw = max(fl.web_width(dp), 1.25 * dj)
    mat = MATERIALS[b.crank_material]
    R = b.stroke / 2.0
    geo = dict(journal_diameter=dj, journal_bore=0.0, journal_length=main_len, pin_diameter=dp,
               pin_bore=0.0, pin_length=pin_len, web_thickness=tw, web_width_journal=bw,
               web_width_pin=bw, crank_radius=R)
    bare = throw_mass_properties(**geo, density=mat["density"])
    u_crank = float(bare.mass[0, 1] * bare.y[0, 1] * 2 + bare.mass[0, 3] * bare.y[0, 3])
    target = u_crank + rods_per_pin * m_rot * R
    rec = 0.0  # a 90-degree V pair's primary force is a constant rotating vector (in-throw)
    if (b.layout == "V" and abs(math.degrees(b.bank_angle) - 90.0) < 1e-6 and not split
            and arr.crank_type != "flat-plane"):
        rec = m_rec * R
    target += rec
    ro_max = rod_len - R - 0.25 * b.bore
    ri, ro, ang, tc, got = _cw_for_target(b, geo, target, mat, ro_max,
                                          tw + 0.9 * min(pin_len, main_len))
    L = Layout(b, n_thr, arr.throw_angle, arr.cyl_throw, arr.cyl_bank, arr.cyl_firing,
               arr.firing_order, arr.note, f_pin, gas, dp, dj, rod_land, pin_len, main_land,
               main_len, rf_p, rf_j, tw, bw, rod_len, spacing, wp, piston, rod, ri, ro, ang, tc,
               target, 5e-4 * dj, 5e-4 * dp, engine_class=b.engine_class,
               crank_type=arr.crank_type, even_firing=arr.even,
               intervals=tuple(arr.intervals), f_pin=f_pin, f_main=f_main, cw_achieved=got,
               balance_rec=rec, material=b.crank_material)
    return replace(L, plausibility=tuple(plausibility(L)))


def plausibility(L: Layout) -> list[str]:
    """Sized dimensions outside the band of real engines of the class (:data:`first_layout.
    CLASSES`), each a sentence; the balance the counterweights reach when short of target."""
    b = L.brief
    cls = fl.CLASSES[L.engine_class]
    out = []
    rods = b.cylinders // L.throws

    def band(what: str, x: float, lo_hi: tuple[float, float], unit: str = "") -> None:
        lo, hi = lo_hi
        if not lo * 0.999 <= x <= hi * 1.001:
            out.append(f"{what} {x:.3g}{unit} is outside the band of real {L.engine_class}"
                       f" engines ({lo:g}-{hi:g}{unit})")

    band("crank-pin land L/D", L.rod_land / L.dp, cls["pin_ld_band"])
    band("main land L/D", L.main_land / L.dj, cls["main_ld_band"])
    pitch = L.spacing * (2 if L.crank_type == "split pins" else 1)
    band("cylinder pitch per bore", pitch / b.bore, cls["pitch_band"])
    band("web thickness per bore", L.tw / b.bore, cls["web_band"])
    if rods == 1 and L.pin_len / L.dp > 1.0:
        out.append(f"crank-pin length {L.pin_len * 1e3:.0f} mm is longer than its diameter")
    if L.cw_achieved < 0.999:
        out.append(f"the counterweights reach only {100 * L.cw_achieved:.0f} % of their target"
                   f" ({L.balance_target * 1e3:.0f} kg mm per throw): the swing radius"
                   f" (piston skirt at BDC) leaves no room for more")
    return out


def warnings(L: Layout) -> list[str]:
    """What ``checker new`` prints as warnings: the values outside the band of real engines
    and firing that cannot be even (both also page-1 caveats of the report)."""
    out = [f"{w} (docs/new-engine.md)" for w in L.plausibility]
    if not L.even_firing:
        where = "on this crank" if L.brief.layout == "inline" else "at this bank angle"
        out.append(f"{L.crank_type}: even firing is impossible {where}; firing"
                   f" order {L.firing_order}, intervals "
                   + "/".join(f"{g:g}" for g in L.intervals) + " deg")
    return out


@dataclass
class Tuning:
    """What the second pass sets from the checker's own models."""

    flywheel: float
    ring: float
    ring_stiffness: float
    loss_factor: float
    joints: list[dict]
    tuning: float = 1.0  # Den Hartog's optimum ring / crank-mode frequency ratio
    sizing: bool = True  # a sizing pass (the irregularity target typed for the flywheel module)
    limits: dict | None = None  # project limits (sizing.project_limits.free_limits)
    oil_grade: str | None = None  # chosen by the loop (None: the fuel's usual grade)
    oil_cooling: float = 0.0  # K below the usual gallery temperature (an oil cooler, the loop)
    detune: float = 1.0  # rubber stiffness / Den Hartog's optimum (the loop's damper tuning)


def _mm(x: float) -> float:
    return round(x * 1e3, 2)


NOSE = (0.75, 0.6)
"""Crank nose shaft diameter and length (damper hub mid-plane to the first journal's face) as
fractions of the main journal diameter [not confirmed in a public source]; sheet CrankEnds
measures the length to the journal's mid-plane (half the journal added)."""
FLANGE = (1.0, 0.5)
"""Flywheel flange shaft diameter and length (last journal's face to the flywheel) as fractions
of the main journal diameter [not confirmed]; CrankEnds adds half the journal."""


def _throw_props(L: Layout, mat: dict) -> Any:
    """The sized throw's mass properties (crank-geometry module of the crank branch)."""
    return throw_mass_properties(journal_diameter=L.dj, journal_bore=0.0,
                                 journal_length=L.main_len, pin_diameter=L.dp, pin_bore=0.0,
                                 pin_length=L.pin_len, web_thickness=L.tw,
                                 web_width_journal=L.bw, web_width_pin=L.bw,
                                 crank_radius=L.brief.stroke / 2.0, density=mat["density"],
                                 cw_inner_radius=L.cw_ri, cw_outer_radius=L.cw_ro,
                                 cw_angle=L.cw_angle, cw_thickness=L.cw_thickness)


def _crank_sheet(L: Layout, mat: dict) -> tuple[list, list]:
    """Sheet Crank: one row 'all' (every throw alike)."""
    p = _throw_props(L, mat)
    cw_u = float(-(p.mass[0, 2] * p.y[0, 2] + p.mass[0, 5] * p.y[0, 5]))
    hole = 0.1 * L.dp
    note = est(None, "diameters: " + fl.RULES["pin_diameter"]["rule"] + " ("
               + fl.RULES["pin_diameter"]["source"] + "), "
               + fl.RULES["main_diameter"]["rule"] + " (" + fl.RULES["main_diameter"]["source"]
               + "); lengths: " + fl.RULES["journal_length"]["rule"] + padm_text(L.brief) + " ("
               + fl.RULES["journal_length"]["source"] + "); web thickness: "
               + fl.RULES["web_thickness"]["rule"] + " (" + fl.RULES["web_thickness"]["source"]
               + "); web widths: " + fl.RULES["web_width"]["rule"] + " ("
               + fl.RULES["web_width"]["source"] + ", not confirmed); counterweights: "
               + fl.RULES["counterweight"]["rule"]
               + f", achieved {100 * cw_u / L.balance_target:.0f} % of the target"
               f" {L.balance_target * 1e3:.0f} kg mm per throw; fillets: "
               + fl.RULES["fillet_radius"]["rule"] + " (" + fl.RULES["fillet_radius"]["source"]
               + "); oil holes 0.1 x pin diameter [not confirmed]; material: " + mat["source"]
               + (f" [{PLAUSIBILITY_MARK}: " + "; ".join(L.plausibility) + "]"
                  if L.plausibility else ""))
    cols = [("throw", "-"), ("main journal diameter", "mm"), ("main journal bore", "mm"),
            ("main journal length", "mm"), ("pin diameter", "mm"), ("pin bore", "mm"),
            ("pin length", "mm"), ("web thickness", "mm"), ("web width at journal", "mm"),
            ("web width at pin", "mm"), ("counterweight inner radius", "mm"),
            ("counterweight outer radius", "mm"), ("counterweight angle", "deg"),
            ("counterweight thickness", "mm"), ("pin fillet radius", "mm"),
            ("pin fillet undercut", "mm"), ("pin fillet web undercut", "mm"),
            ("main fillet radius", "mm"), ("main fillet undercut", "mm"),
            ("main fillet web undercut", "mm"), ("pin oil hole diameter", "mm"),
            ("main oil hole diameter", "mm"), ("density", "kg/m^3"), ("Young's modulus", "GPa"),
            ("Poisson's ratio", "-"), ("note", "")]
    row = ["all", _mm(L.dj), 0, _mm(L.main_len), _mm(L.dp), 0, _mm(L.pin_len), _mm(L.tw),
           _mm(L.bw), _mm(L.bw), _mm(L.cw_ri), _mm(L.cw_ro), round(math.degrees(L.cw_angle), 3),
           _mm(L.cw_thickness), _mm(L.fillet_p), 0, 0, _mm(L.fillet_j), 0, 0, _mm(hole),
           _mm(hole), mat["density"], mat["E"] / 1e9, mat["nu"], note]
    return cols, [row]


def _crank_ends(L: Layout) -> list:
    note = est(None, f"crank nose {L.nose_ratio:.3g} x and 0.6 x the main journal diameter,"
               " flywheel flange 1.0 x and 0.5 x [ratios not confirmed in a public source]"
               + ("" if L.nose_ratio == NOSE[0] else "; the nose's diameter moved by the"
                  " sizing loop for its joint (Notes)"))
    return [("Crank nose diameter", _mm(L.nose_ratio * L.dj), "mm", note),
            ("Crank nose length", _mm(NOSE[1] * L.dj + L.main_len / 2), "mm", note),
            ("Flywheel flange diameter", _mm(FLANGE[0] * L.dj), "mm", note),
            ("Flywheel flange length", _mm(FLANGE[1] * L.dj + L.main_len / 2), "mm", note)]


def _tv_rows(L: Layout, mat: dict, tune: Tuning) -> list:
    """TVModel: damper ring, crank nose, one station per throw, flywheel. The crank stations'
    inertias and every stiffness along the crank are left blank: the crank module derives them
    from sheets Crank and CrankEnds."""
    b = L.brief
    nose_d, nose_l = L.nose_ratio * L.dj, NOSE[1] * L.dj
    _m, jn, _ = cylinder(diameter=nose_d, bore=0.0, length=nose_l, density=mat["density"])
    hub = 4.0 * float(jn)  # pulley hub, timing sprocket and damper hub on the nose
    derived = "derived from sheets Crank and CrankEnds (crank module)"
    rows = [["Damper ring", "damper ring", None, round(tune.ring, 6), None,
             round(tune.ring_stiffness), None,
             est(None, "Den Hartog tuned absorber: ring inertia 0.25 x the first crank mode's"
                 " modal inertia at the nose [ratio not confirmed in a public source];"
                 " rubber stiffness at the optimum tuning of the damper-tuning module (Den"
                 " Hartog, Mechanical Vibrations, 1956)"
                 + ("" if tune.detune == 1.0 else f", x {tune.detune:.3g} (tuned by the"
                    " sizing loop to the crank's response)"))],
            ["Crank nose", "crank nose", None, round(float(jn) + hub, 7), None, None, None,
             est(None, "inertia of the nose shaft (sheet CrankEnds) plus hubs 4 x its inertia"
                 f" [not confirmed]; stiffness {derived}")]]
    rods = b.cylinders // L.throws
    c_cyl = fl.cylinder_damping(b.bore, L.engine_class)
    for t in range(L.throws):
        cyl = [c + 1 for c in range(b.cylinders) if L.cyl_throw[c] == t + 1]
        rows.append([f"Throw {t + 1}" if rods > 1 else f"Cylinder {cyl[0]}", "cylinder",
                     ", ".join(map(str, cyl)) if rods > 1 else cyl[0], None,
                     round(c_cyl * len(cyl), 4), None, None,
                     f"inertia and stiffness {derived}; absolute damping: "
                     + est("cylinder_damping")])
    rows.append(["Flywheel", "flywheel", None, round(tune.flywheel, 5), None, None, None,
                 est(None, "smallest flywheel meeting the class's cyclic irregularity target"
                     f" ({fl.CLASSES[L.engine_class]['irregularity'] * 100:g} %) at the lowest"
                     " speed, full load,"
                     " with the engine's inertias only (flywheel module, +5 %)")])
    return rows


def _mode_plausibility(L: Layout, res: Any) -> list[str]:
    """The first torsional mode of the sized crank train against the class's band."""
    f = _q(res, "tv.natural_frequency")
    if f is None:
        return []
    f = f[np.isfinite(f) & (f > 1.0)]
    if not f.size:
        return []
    lo, hi = fl.CLASSES[L.engine_class]["mode_band"]
    x = float(f.min())
    if lo <= x <= hi:
        return []
    return [f"first torsional mode {x:.0f} Hz is outside the band of real {L.engine_class}"
            f" engines ({lo:g}-{hi:g} Hz)"]


def _limit_rows(L: Layout, tune: Tuning) -> list[tuple]:
    """Engine-sheet project limits (free forces and moments, balance-ratio band); blank in a
    sizing pass before the balance module has run."""
    if tune.limits is None:
        return []
    return project_limits.engine_rows(tune.limits, L.balance_target / max(
        L.balance_target - L.balance_rec, 1e-12))


def _joint_design(location: str, torque: float, face_od: float, face_id: float,
                  friction: float = 0.2) -> dict:
    """Smallest bolt set (ISO metric, class 10.9, yield-controlled tightening at the
    recommended 75 % of R_p0.2, Bell 2013) whose slip capacity covers ``torque`` with a cover
    factor of 1.8 x 1.1 (friction 0.2, or 0.3 with a diamond washer, Bell 2013); the bolt
    no larger than the face allows
    (crank nose: 0.45 x face diameter; flywheel: 0.6 x the face's radial width, at most 16
    bolts). None fits: the largest that does, its cover factor below 1.8 a design finding."""
    frac = PRELOAD_FRACTIONS["yield controlled"][0]
    rp02 = 940e6
    sizes = [(8, 1.0), (10, 1.25), (12, 1.25), (14, 1.5), (16, 1.5), (18, 1.5), (20, 1.5),
             (24, 2.0), (27, 2.0), (30, 2.0), (36, 3.0)]
    if location == "crank nose":
        d_max, counts = 0.45 * face_od * 1e3, [1]
    else:
        d_max, counts = 0.6 * (face_od - face_id) / 2.0 * 1e3, [6, 8, 10, 12, 16]
    fits = [s for s in sizes if s[0] <= d_max] or sizes[:1]
    best = None
    for d_mm, p_mm in fits:
        for n in counts:
            a = float(tensile_stress_area(d_mm * 1e-3, p_mm * 1e-3))
            fid = max(face_id, 1.1 * d_mm * 1e-3) if location == "crank nose" else face_id
            r_eff = float(effective_friction_diameter(face_od, fid)) / 2.0
            cap = friction * n * frac * rp02 * a * r_eff
            f = frac * rp02 * a
            head_id = round(1.1 * d_mm, 1)
            head_od = math.ceil(2 * 1e3 * math.sqrt(4 * f / (math.pi * 450e6)
                                                    + (head_id * 1e-3)**2)) / 2
            best = {"bolts": n, "d": d_mm, "p": p_mm, "capacity": cap, "head_od": head_od,
                    "head_id": head_id, "id": fid, "friction": friction}
            if cap >= 1.8 * 1.1 * torque:
                return best
    return best


BRIEF_NOTE = "brief (checker new)"


def _from_brief(b: Brief, key: str) -> str:
    """The note of a brief value: the brief's, or the default of checker new it took."""
    return (f"{TAG}: default of checker new ({b.defaults[key]})" if key in b.defaults
            else BRIEF_NOTE)


@dataclass(frozen=True)
class Rating:
    """The rated operating point that the Engine, BrakeTorque and PeakPressure sheets share."""

    torque: float  # N m, rated power / rated speed
    bmep: float  # Pa, at the rated torque
    cr: float  # compression ratio (by fuel)
    bmep_na: float  # Pa, a naturally aspirated engine's BMEP (by fuel)
    p_int: float  # bar, intake manifold pressure at full load


def rating(b: Brief) -> Rating:
    """Rated torque and BMEP from the brief; compression ratio and intake pressure by fuel."""
    rated_torque = b.rated_power / b.rated_speed
    vd = math.pi / 4 * b.bore**2 * b.stroke
    bmep = rated_torque * 4 * math.pi / (vd * b.cylinders)
    cr = 10.5 if b.fuel == "gasoline" else 17.0
    bmep_na = 12e5 if b.fuel == "gasoline" else 9e5
    return Rating(rated_torque, bmep, cr, bmep_na, max(1.0, round(bmep / bmep_na, 2)))


def _rod_rotating_mass(L: Layout) -> float:
    """The con-rod's rotating share [kg]: its mass times the centre of mass's distance from
    the small end over the rod length."""
    return L.rod.mass * (L.rod_len - L.rod.centre_from_big_end) / L.rod_len


def content(L: Layout, tune: Tuning) -> dict[str, Any]:
    """The workbook's sheets (format of :func:`checker.workbook.example.write_workbook`)."""
    b = L.brief
    mat = MATERIALS[L.material]
    rt = rating(b)
    bt_rows = _brake_torque_rows(b, rt)
    return {
        "Engine": _engine_sheet(L, rt, tune),
        "Cylinders": _cylinders_sheet(L),
        "PeakPressure": ([("load case", "-"), ("speed", "rpm"), ("peak pressure", "bar"),
                          ("note", "")], _peak_pressure_rows(b, rt, bt_rows)),
        "BrakeTorque": ([("speed", "rpm"), ("brake torque", "N m"), ("note", "")], bt_rows),
        "Bearings": _bearings_sheet(L),
        "Crank": _crank_sheet(L, mat),
        "CrankEnds": _crank_ends(L),
        "CrankMass": ([("location", "-"), ("throw", "-"), ("kind", "-"), ("mass", "kg"),
                       ("X", "mm"), ("Y", "mm"), ("Z", "mm"), ("axial position", "mm"),
                       ("relative to", "-"), ("note", "")], []),
        "Oil": _oil_sheet(L.brief, tune),
        "TVModel": ([("station", "-"), ("role", "-"), ("cylinder", "-"),
                     ("inertia", "kg m^2"), ("absolute damping", "N m s/rad"),
                     ("stiffness to next", "N m/rad"), ("damping to next", "N m s/rad"),
                     ("note", "")], _tv_rows(L, mat, tune)),
        "Damper": _damper_sheet(tune),
        "Fatigue": _fatigue_sheet(L, mat),
        "Joints": _joints_sheet(tune),
        "JointTorques": ([("joint", "-"), ("operating point", "-"), ("speed", "rpm"),
                          ("applied torque", "N m"), ("note", "")], []),
        "RuleOverrides": ([("rule", "-"), ("limit", "-"), ("unit", "-"), ("reason", "-")],
                          project_limits.override_rows(b.engine_class)),
        "Tolerances": ([("sheet", "-"), ("row", "-"), ("column", "-"), ("min", "-"),
                        ("max", "-"), ("unit", "-"), ("source", "")], []),
        "Notes": _notes(L, rt),
    }


def _engine_sheet(L: Layout, rt: Rating, tune: Tuning) -> list[tuple]:
    """Sheet Engine: the brief's values, the rod and piston by their rules, the speeds."""
    b = L.brief
    brief_note = BRIEF_NOTE

    def dflt(key: str) -> str:
        return _from_brief(b, key)

    cls = L.engine_class
    cr, p_int, bmep, bmep_na = rt.cr, rt.p_int, rt.bmep, rt.bmep_na
    step = max(25, int(round((b.max_speed - b.min_speed) * RPM / 60 / 25.0)) * 25)
    engine = [
        ("Engine name", b.name, "-", brief_note),
        ("Number of cylinders", b.cylinders, "-", brief_note),
        ("Engine class", cls, "-", dflt("engine_class")),
        ("Layout", "inline" if b.layout == "inline" else "V", "-", dflt("layout")),
        ("Bore", round(b.bore * 1e3, 3), "mm", brief_note),
        ("Stroke", round(b.stroke * 1e3, 3), "mm", brief_note),
        ("Connecting rod length", _mm(L.rod_len), "mm", est("rod_length")),
        ("Cylinder offset", 0.0, "mm", est(None, "none (the usual layout)")),
        ("Pin offset", 0.0, "mm", est(None, "none (the usual layout)")),
        ("Crankshaft rotation", "clockwise", "-", est(None, "clockwise seen from the front,"
                                                     " the SAE standard rotation")),
        ("Firing order", L.firing_order, "-", est(None, L.firing_note)),
        ("Cylinder spacing", _mm(L.spacing), "mm",
         est(None, "main journal + 2 webs + pin lengths (one main between each throw)")),
        ("Main journal spacing", _mm(L.spacing), "mm", est(None, "one main between each throw")),
        ("Connecting rod mass", round(L.rod.mass, 4), "kg", est("rod_mass")),
        ("Rod centre of mass from big end", _mm(L.rod.centre_from_big_end), "mm",
         est("rod_centre")),
        ("Rod moment of inertia about centre of mass", round(L.rod.inertia * 1e6, 1),
         "kg mm^2", est("rod_centre")),
        ("Piston assembly mass", round(L.piston, 4), "kg",
         est("piston_mass", f"wrist pin {L.wrist.mass:.3f} kg ({fl.RULES['wrist_pin']['rule']};"
             f" {fl.RULES['wrist_pin']['source']})")),
        ("Compression ratio", cr, "-", est(None, "typical: gasoline 10.5, diesel 17 [not"
                                           " confirmed in a public source]; used to"
                                           " synthesize pressure traces")),
        ("Intake manifold pressure at full load", p_int, "bar",
         est(None, f"rated BMEP {bmep / 1e5:.1f} bar / {bmep_na / 1e5:g} bar (a naturally"
             " aspirated engine's BMEP) [not confirmed in a public source], at least 1 bar")),
        ("Rated speed", round(b.rated_speed * RPM), "rpm", brief_note),
        ("Minimum speed", round(b.min_speed * RPM), "rpm", dflt("min_speed")),
        ("Maximum speed", round(b.max_speed * RPM), "rpm", dflt("max_speed")),
        ("Speed step", step, "rpm", est(None, "about 60 speeds from minimum to maximum")),
        ("Overspeed", round(b.max_speed * RPM), "rpm", est(None, "the maximum speed of the"
                                                           " brief")),
        ("Target cyclic irregularity", round(fl.CLASSES[cls]["irregularity"] * 100, 3), "%",
         est(None, "the class's target at the lowest speed, full load (FLY-001; the flywheel"
             " in TVModel is sized for it): " + FLY_SOURCE)),
        *_limit_rows(L, tune),
        ("Project", "checker new: first layout", "-", brief_note),
        ("Revision", "0", "-", brief_note),
    ]
    return engine


def _cylinders_sheet(L: Layout) -> tuple[list, list]:
    """Sheet Cylinders: each cylinder's throw, firing and bank angle and its crank pin."""
    b = L.brief
    cyl_cols = [("cylinder", "-"), ("throw angle", "deg"), ("firing angle", "deg"),
                ("bank angle", "deg"), ("crank pin", "-"), ("note", "")]
    cyl_rows = [[c + 1, round(L.throw_angle[L.cyl_throw[c] - 1], 6), round(L.cyl_firing[c], 6),
                 round(L.cyl_bank[c], 6), L.cyl_throw[c], est(None, L.firing_note)]
                for c in range(b.cylinders)]
    return cyl_cols, cyl_rows


BELL_CURVE = ("the full-load curve of the production gasoline I4 of Bell, Ricardo 2013 made"
              " dimensionless (speed / rated speed) and scaled to")


def _gasoline_speeds(b: Brief) -> list[float]:
    """Speeds [rad/s] of a gasoline engine's full-load rows: the minimum, the points of
    :data:`first_layout.GASOLINE_FULL_LOAD` inside the speed range, the rated and maximum."""
    pts = [b.min_speed, b.rated_speed, b.max_speed]
    pts += [r[0] * b.rated_speed for r in fl.GASOLINE_FULL_LOAD
            if b.min_speed * 1.02 < r[0] * b.rated_speed < b.max_speed / 1.02
            and abs(r[0] - 1.0) > 0.02]
    return sorted({round(s * RPM) / RPM for s in pts})


def _brake_torque_rows(b: Brief, rt: Rating) -> list[list]:
    """Sheet BrakeTorque: the torque from the rated power; a gasoline engine's curve has the
    shape of :data:`first_layout.GASOLINE_FULL_LOAD` (its peak torque 1.2 x the rated);
    other fuels: the peak torque 1.2 x the rated between the minimum and the rated speed,
    less at the ends."""
    rated_torque = rt.torque
    if b.fuel == "gasoline":
        t_peak = rated_torque / fl.full_load_shape(1.0)[0]
        return [[round(s * RPM), round(t_peak * fl.full_load_shape(s / b.rated_speed)[0], 1),
                 "as above" if k else est(None, f"{BELL_CURVE} the brief's rated torque"
                                          " (rated power / rated speed; outside the curve's"
                                          " speed range its end values)")]
                for k, s in enumerate(_gasoline_speeds(b))]
    t_max = rated_torque * 1.2
    bt_rows = [[round(b.min_speed * RPM), round(0.8 * t_max, 1),
                est(None, "80 % of the peak torque at the minimum speed [shape not"
                    " confirmed]")],
               [round(0.5 * (b.min_speed + b.rated_speed) * RPM), round(t_max, 1),
                est(None, "peak torque = 1.2 x rated torque [not confirmed]")],
               [round(b.rated_speed * RPM), round(rated_torque, 1),
                est(None, "rated power / rated speed (brief)")]]
    if b.max_speed > b.rated_speed * 1.001:
        bt_rows.append([round(b.max_speed * RPM), round(0.8 * rated_torque, 1),
                        est(None, "80 % of the rated torque at the maximum speed [not"
                            " confirmed]")])
    return bt_rows


def _peak_pressure_rows(b: Brief, rt: Rating, bt_rows: list[list]) -> list[list]:
    """Sheet PeakPressure: at full load the brief's peak where the torque peaks, the firing
    part of it scaled with the torque elsewhere (IMEP ~ torque); a motored peak at no load."""
    cr, p_int = rt.cr, rt.p_int
    t_max = rt.torque * 1.2
    p_mot = p_int * cr**1.3  # bar: polytropic compression, n = 1.3
    pk = b.peak_pressure / 1e5
    src = ("the brief's peak pressure" if "peak_pressure" not in b.defaults
           else "the typical peak pressure (" + fl.RULES["peak_pressure"]["rule"] + "; "
           + fl.RULES["peak_pressure"]["source"] + ")")
    pp_note = est(None, f"{src} at the peak-torque speed; elsewhere the motored peak"
                  f" ({p_mot:.0f} bar = intake pressure x CR^1.3) plus the firing part scaled"
                  " with the brake torque (IMEP ~ torque) [not confirmed]")
    if b.fuel == "gasoline":
        pp_rows = [["full", s_, round(pk * fl.full_load_shape(s_ / RPM / b.rated_speed)[1], 1),
                    "as above" if k else est(None, f"{BELL_CURVE} {src} as its maximum"
                                             " (knock-limited at low speed: the peak pressure"
                                             " falls faster than the torque)")]
                   for k, (s_, _t, _n) in enumerate(bt_rows)]
    else:
        pp_rows = [["full", s_, round(p_mot + (pk - p_mot) * t / t_max, 1), pp_note]
                   for s_, t, _n in bt_rows]
    pp_rows.append(["no", round(b.max_speed * RPM), round(1.5 * cr ** 1.3, 1),
                    est(None, "motored peak ~ 1 bar x CR^1.3 x 1.5 (polytropic compression,"
                        " n = 1.3, with throttled/no-load combustion) [not confirmed]")])
    return pp_rows


def _bearings_sheet(L: Layout) -> tuple[list, list]:
    """Sheet Bearings: the mains (partial groove) and one big end per rod, their widths and
    clearances by rule, the diameters from sheet Crank."""
    b = L.brief

    def dflt(key: str) -> str:
        return _from_brief(b, key)

    lining_m = L.lining_main or b.bearing_lining
    lining_p = L.lining_pin or b.bearing_lining
    bcols = [("name", "-"), ("type", "-"), ("journal diameter", "mm"), ("journal length", "mm"),
             ("effective length", "mm"), ("radial clearance", "mm"), ("groove", "-"),
             ("groove width", "mm"), ("groove start", "deg"), ("groove end", "deg"),
             ("oil feed", "-"), ("oil holes", "-"), ("oil hole type", "-"),
             ("oil hole diameter", "mm"), ("oil hole angle", "deg"), ("lining", "-"),
             ("note", "")]
    clr = est(None, "radial clearance 0.0005 x diameter (diametral 0.001 in per inch, the"
              " usual rule of thumb) [not confirmed in a public source]")
    m_note = est("journal_length", "journal diameter and length from sheet Crank"
                 + padm_text(b) + "; groove 0.15 x land [not confirmed]; " + clr
                 + (f"; lining from the brief ({dflt('bearing_lining')})" if not L.lining_main
                    else f"; lining {lining_m}, chosen by the sizing loop for the specific"
                    " load (Notes)"))
    brows = []
    groove_w = round(0.15 * L.main_land * 1e3, 1)
    for k in range(L.throws + 1):
        brows.append([f"M{k + 1}", "main", None, None, _mm(L.main_land - groove_w * 1e-3),
                      round(L.clearance_main * 1e3, 4), "partial", groove_w, 270, 90, "bearing",
                      0, None, None, None, lining_m, m_note])
    p_note = est("journal_length", "per rod" + padm_text(b) + "; journal diameter, length and"
                 " oil hole diameter from sheet Crank; " + clr
                 + f"; oil hole {L.oil_hole_angle:g} deg leading"
                 + (" [not confirmed]" if L.oil_hole_angle == 45.0 else
                    " (moved by the sizing loop)")
                 + (f"; lining from the brief ({dflt('bearing_lining')})" if not L.lining_pin
                    else f"; lining {lining_p}, chosen by the sizing loop for the specific"
                    " load (Notes)"))
    for c in range(b.cylinders):
        brows.append([f"BE{c + 1}", "big end", None, None, _mm(L.rod_land),
                      round(L.clearance_pin * 1e3, 4), "none", None, None, None, "crank", 1,
                      "leading", None, L.oil_hole_angle, lining_p, p_note])
    return bcols, brows


def oil_grade(b: Brief, tune: Tuning) -> str:
    """The oil grade of the layout: the loop's choice, else a usual grade for the fuel."""
    return tune.oil_grade or ("5W30" if b.fuel == "gasoline" else "10W40")


def _oil_sheet(b: Brief, tune: Tuning) -> list[tuple]:
    """Sheet Oil: a usual grade and gallery conditions for the fuel (the grade the loop chose
    where it moved it)."""
    grade_note = (est(None, "a usual grade for the fuel") if tune.oil_grade is None
                  else est(None, "the grade the sizing loop chose for the bearing films"
                           " (Notes)"))
    return [("Oil grade", oil_grade(b, tune), "-", grade_note),
            ("Oil supply pressure", 4.0, "bar(g)", est(None, "usual gallery pressure at speed")),
            ("Oil supply temperature", (120 if b.fuel == "gasoline" else 110)
             - tune.oil_cooling, "°C",
             est(None, "usual gallery temperature at full load") if not tune.oil_cooling
             else est(None, f"an oil cooler holding the gallery {tune.oil_cooling:g} K below"
                      " the usual temperature at full load (the sizing loop, for the bearing"
                      " films; Notes)")),
            ("Film temperature rise", 10, "K", est(None, "moderate film heating")),
            ("Mobility model", "finite length", "-",
             est(None, "the finite-length Reynolds film (the short bearing is optimistic at"
                 " engine L/D)"))]


def _damper_sheet(tune: Tuning) -> list[tuple]:
    """Sheet Damper: Den Hartog's optimum loss factor and tuning band of the second pass."""
    return [("Rubber loss factor", round(tune.loss_factor, 3), "-",
             est(None, "Den Hartog's optimum loss factor for the ring/crank inertia ratio"
                 " (damper-tuning module)")),
            ("Tuning ratio, minimum", round(0.9 * tune.tuning, 3), "-",
             est(None, "Den Hartog's optimum tuning ratio for this ring/crank inertia ratio"
                 " (damper-tuning module) -10 % [band not confirmed]")),
            ("Tuning ratio, maximum", round(1.1 * tune.tuning, 3), "-",
             est(None, "Den Hartog's optimum tuning ratio +10 % [band not confirmed]"))]


def _fatigue_sheet(L: Layout, mat: dict) -> list[tuple]:
    """Sheet Fatigue: oil-hole heights and the material's strengths (the web, fillet,
    oil-hole and bore dimensions come from sheet Crank)."""
    src = f"{TAG}: {mat['source']}"
    fatigue = [  # the web, fillet, oil-hole and bore dimensions come from sheet Crank
        ("Web offset", 0, "mm", est(None, "symmetric web")),
        ("Pin journal oil hole height", _mm(L.dp / 2 * math.sin(math.radians(
            L.oil_hole_angle))), "mm", est(None, f"pin radius x sin {L.oil_hole_angle:g} deg"
                                          f" (hole {L.oil_hole_angle:g} deg leading)")),
        ("Main journal oil hole height", _mm(L.dj / 2 * math.sin(math.radians(20))), "mm",
         est(None, "journal radius x sin 20 deg [not confirmed]")),
        ("Base material UTS", mat["uts"], "N/mm^2", src),
        ("Fillet UTS", mat["fillet_uts"], "N/mm^2", src),
        ("Base tensile yield strength", mat["yield"], "N/mm^2", src),
        ("Base compressive yield strength", mat["yield"], "N/mm^2", src),
        ("Base infinite life fatigue strength", mat["fatigue"], "N/mm^2", src),
        ("Base hydrostatic fatigue strength", mat["hydro"], "N/mm^2", src),
        ("Base torsional fatigue strength", mat["torsion"], "N/mm^2", src),
        ("Fillet tensile and compressive yield", mat["fillet_yield"], "N/mm^2", src),
        ("Pin fillet fatigue strength", mat["pin_fillet"], "N/mm^2", src),
        ("Pin oil hole fatigue strength", mat["pin_hole"], "N/mm^2", src),
        ("Main fillet fatigue strength", mat["main_fillet"], "N/mm^2", src),
        ("Main oil hole fatigue strength", mat["main_hole"], "N/mm^2", src),
        *project_limits.nose_rows(L.dj, L.nose_ratio * L.dj, L.fillet_j, mat["fatigue"],
                                  L.material),
    ]
    return fatigue


def _joints_sheet(tune: Tuning) -> tuple[list, list]:
    """Sheet Joints: the bolt sets of the second pass, yield-controlled class 10.9."""
    jcols = [("name", "-"), ("location", "-"), ("bolts", "-"), ("nominal diameter", "mm"),
             ("thread pitch", "mm"), ("property class", "-"), ("tightening", "-"),
             ("head bearing outer diameter", "mm"), ("head bearing inner diameter", "mm"),
             ("clamped material", "-"), ("face outer diameter", "mm"),
             ("face inner diameter", "mm"), ("friction coefficient", "-"), ("note", "")]
    jrows = []
    for j in tune.joints:
        jrows.append([j["name"], j["name"], j["bolts"], j["d"], j["p"], "10.9",
                      "yield controlled", j["head_od"], j["head_id"],
                      "steel", _mm(j["od"]), _mm(j["id"]), j.get("friction", 0.2),
                      est(None, f"smallest bolt set whose slip capacity covers the torsional"
                          f" model's largest joint torque {j['torque']:.0f} N m with a cover"
                          " factor of 1.8 (+10 %), yield-controlled tightening at 75 % of"
                          " R_p0.2 and friction "
                          + ("0.3 with a friction-enhancing (diamond) washer"
                             if j.get("friction", 0.2) > 0.2 else "0.2")
                          + " (Bell, Ricardo 2013); head bearing"
                          " diameter for 90 % of the 500 N/mm^2 contact limit on steel (Bell,"
                          " Ricardo 2013) from a 1.1 d clearance hole; face diameters [ratios"
                          " not confirmed]")])
    return jcols, jrows


def _notes(L: Layout, rt: Rating) -> list[str]:
    """Sheet Notes: what the workbook is and the layout's sizing loads."""
    b = L.brief
    m_rot = _rod_rotating_mass(L)
    R = b.stroke / 2.0
    rated_torque, bmep = rt.torque, rt.bmep
    return [f"First layout written by checker new from a brief: {b.name}.",
            "Values marked ESTIMATE are sized by a stated design rule (see each note and"
            " docs/new-engine.md), not data of this engine.",
            "Replace each estimate with the design's value as it becomes known.",
            f"Peak gas force {L.gas / 1e3:.1f} kN; worst pin force over the speed range"
            f" {L.f_pin / 1e3:.1f} kN, worst main force {L.f_main / 1e3:.1f} kN;"
            f" rated torque {rated_torque:.0f} N m,"
            f" rated BMEP {bmep / 1e5:.1f} bar; rotating share of the rod"
            f" {m_rot:.3f} kg, crank radius {R * 1e3:g} mm.",
            "See docs/workbook.md for every sheet, parameter and column."]


def _q(res, name: str) -> np.ndarray | None:
    q = res.outcome.quantities.get(name)
    return None if q is None else np.asarray(q.values, dtype=float)


def _rated(res, name: str, speed: float) -> np.ndarray | None:
    """A (case, speed) quantity at the swept speed nearest ``speed``, full load only."""
    q = res.outcome.quantities.get(name)
    if q is None:
        return None
    sp = np.asarray(q.coords.get("speed"), dtype=float)
    cases = list(q.coords.get("case", []))
    v = np.asarray(q.values, dtype=float)
    k = int(np.argmin(np.abs(sp - speed)))
    ci = cases.index("full") if "full" in cases else 0
    return v[ci, k:k + 1]


def _first_tuning(L: Layout, crank_j: float) -> Tuning:
    """The tuning passes' start: flywheel 20 and ring 0.25 x the crank's inertia, the ring
    tuned to 300 Hz, a single crank-nose bolt and eight flywheel bolts."""
    od = 1.6 * L.dj
    joints0 = [{"name": "crank nose", "bolts": 1, "d": 12, "p": 1.25, "torque": 0.0,
                "od": L.nose_ratio * L.dj, "id": 0.0, "head_od": 24.0, "head_id": 13.2},
               {"name": "flywheel", "bolts": 8, "d": 10, "p": 1.25, "torque": 0.0, "od": od,
                "id": L.dj * 0.8, "head_od": 20.0, "head_id": 11.0}]
    return Tuning(flywheel=20 * crank_j, ring=0.25 * crank_j,
                  ring_stiffness=0.25 * crank_j * (2 * math.pi * 300.0)**2, loss_factor=0.2,
                  joints=joints0)


def _next_tuning(res: Any, tune: Tuning, crank_j: float, min_speed: float) -> Tuning:
    """One pass: the smallest flywheel for the irregularity target at the lowest speed (+5 %,
    at least twice the crank), the ring 0.25 x the first mode's modal inertia with Den
    Hartog's optimum stiffness, loss factor and tuning ratio."""
    j_min = _rated(res, "flywheel.minimum_inertia", min_speed)
    modal = _q(res, "damper.modal_inertia")
    k_opt = _q(res, "damper.optimum_stiffness")
    eta = _q(res, "damper.optimum_loss_factor")
    fw = tune.flywheel
    if j_min is not None and np.isfinite(j_min).any():
        fw = max(float(np.nanmax(j_min)) * 1.05, 2 * crank_j)
    ring = tune.ring
    if modal is not None and np.isfinite(modal).any():
        ring = 0.25 * float(np.nanmax(modal))
    k = tune.ring_stiffness * ring / tune.ring
    if k_opt is not None and np.isfinite(k_opt).any():
        k = float(np.nanmax(k_opt)) * ring / tune.ring
    loss = float(np.nanmax(eta)) if eta is not None and np.isfinite(eta).any() else 0.2
    opt = _q(res, "damper.optimum_tuning_ratio")
    tr = float(np.nanmax(opt)) if opt is not None and np.isfinite(opt).any() else 1.0
    return Tuning(fw, ring, k, min(max(loss, 0.05), 1.0), tune.joints, tuning=tr)


def _sized_joints(res: Any, joints0: list[dict]) -> list[dict]:
    """The bolt sets for the tuned torsional model's largest joint torques."""
    tq = _q(res, "tv.joint_torque")
    joints = []
    for i, j in enumerate(joints0):
        t = float(np.nanmax(tq[i])) if tq is not None else float("nan")
        if not np.isfinite(t) or t <= 0:
            raise NoRule(f"{j['name']} joint: the torsional model gave no joint torque")
        joints.append({**j, **_joint_design(j["name"], t, j["od"], j["id"]), "torque": t})
    return joints


def tune_layout(L: Layout) -> tuple[Layout, Tuning, Bench]:
    """The flywheel, damper and joints of layout ``L`` made consistent with the checker's own
    models, the crank modes' plausibility and the free-force limits set (evaluation passes in
    memory on the first layout's workbook, :class:`Bench`)."""
    b = L.brief
    mat = MATERIALS[L.material]
    crank_j = L.throws * float(_throw_props(L, mat).inertia_total[0])
    tune = _first_tuning(L, crank_j)
    bench = Bench(content(L, tune))
    for _ in range(4):  # flywheel and damper tuning settle in 2-3 passes
        res = bench.check(content(L, tune), ["FLY", "DMP"])
        new = _next_tuning(res, tune, crank_j, b.min_speed)
        done = (abs(new.flywheel / tune.flywheel - 1) < 0.01
                and abs(new.ring / tune.ring - 1) < 0.01
                and abs(new.ring_stiffness / tune.ring_stiffness - 1) < 0.01)
        tune = new
        if done:
            break
    res = bench.check(content(L, tune), ["TV", "JNT", "BAL"])  # joint torques, free forces
    L = replace(L, plausibility=L.plausibility + tuple(_mode_plausibility(L, res)))
    m_rot = L.rod.mass * (L.rod_len - L.rod.centre_from_big_end) / L.rod_len
    tune = replace(tune, limits=project_limits.free_limits(
        res, L.piston + L.rod.mass - m_rot, b.stroke / 2.0, b.rated_speed, L.spacing))
    return L, replace(tune, joints=_sized_joints(res, tune.joints), sizing=False), bench


def size(b: Brief) -> tuple[Layout, dict[str, Any]]:
    """The open-loop layout and its workbook content (``checker new --no-iterate``): every
    dimension by its rule, the flywheel, damper and joints tuned."""
    L, tune, _bench = tune_layout(layout(b))
    return L, content(L, tune)
