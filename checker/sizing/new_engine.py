"""Size a first crank-train layout from a brief and write it as a complete workbook.

Every derived value carries a note ``ESTIMATE (checker new): <rule>; <source>``; the rules and
their sources are those of :mod:`checker.calc.first_layout` (docs/new-engine.md). The
estimates are made consistent with each other by running the checker's own models on the
layout (:func:`size`): the flywheel is sized for a 1 % irregularity at the rated speed by the
flywheel module, the damper ring tuned to Den Hartog's optimum by the damper-tuning module, and
the bolted joints sized for the torsional model's joint torques with the recommended preload.

The crank is written as its geometry (sheets Crank and CrankEnds, issue 33): the crank
module derives its CrankMass rows and the crank stations' TVModel inertias, and Bearings and
Fatigue take its dimensions. The counterweights are sized with the crank-geometry module's
mass properties (:func:`checker.calc.crank_geometry.throw_mass_properties`); the crank
stations' inertias and stiffnesses are left blank in TVModel and derived by the crank module
(its throw stiffness fitted to a 3D FE, :mod:`checker.calc.throw_stiffness`).
"""

from __future__ import annotations

import itertools
import math
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..calc import first_layout as fl
from ..calc.bolted_joint import PRELOAD_FRACTIONS, effective_friction_diameter, tensile_stress_area
from ..calc.crank_geometry import cylinder, throw_mass_properties
from .brief import Brief
from .firing import inline_firing_order

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
    out = "" if 18 <= p <= 25 else ", outside Agostini's 18-25 MPa"
    return f" [p_adm = {p:g} MPa given in the brief{out}: the brief's value, not the rule's]"


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
    force: float  # resultant along the piston axis at the rated speed (bearing lengths)
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


def _throws_and_firing(b: Brief) -> tuple[list[float], list[int], list[float], list[float],
                                          str, str]:
    n = b.cylinders
    if b.layout == "inline":
        order, tabled = inline_firing_order(n)
        step = 720.0 / n
        firing = [0.0] * n
        for k, c in enumerate(order):
            firing[c - 1] = k * step
        throws = [(-f) % 360.0 for f in firing]
        return (throws, list(range(1, n + 1)), [0.0] * n, firing, "-".join(map(str, order)),
                f"{'the usual' if tabled else 'a derived'} in-line firing order"
                f"{'' if tabled else ' (the smallest free moments, Taylor 1985 vol. 2 ch. 8)'},"
                f" even firing every {step:g} deg; throw angle = -firing angle (mod 360)")
    half = n // 2
    if half == 4:
        pins = [0.0, 90.0, 270.0, 180.0]
        how = "cross-plane crank (pins 0/90/270/180 deg)"
    else:
        f = [0.0] * half
        for k, c in enumerate(inline_firing_order(half)[0]):
            f[c - 1] = k * 720.0 / half
        pins = [(-x) % 360.0 for x in f]
        how = f"pins as an in-line {half}"
    alpha = math.degrees(b.bank_angle)
    banks = [alpha / 2 if c % 2 == 0 else -alpha / 2 for c in range(n)]  # odd cyl left (+)
    cyl_pin = [c // 2 + 1 for c in range(n)]
    tdc = [((banks[c] - banks[0]) - pins[cyl_pin[c] - 1]) % 360.0 for c in range(n)]
    groups: dict[float, list[int]] = {}
    for c in range(n):
        groups.setdefault(round(tdc[c], 6), []).append(c)
    free = [g for g in groups.values() if len(g) == 2 and 0 not in g]
    best: tuple | None = None
    for pick in itertools.product((0, 1), repeat=len(free)):  # which of a pair fires first
        firing = [tdc[c] for c in range(n)]
        for g in groups.values():
            if len(g) == 2 and 0 in g:
                firing[g[1] if g[0] == 0 else g[0]] += 360.0
        for g, k in zip(free, pick):
            firing[g[1 - k]] += 360.0
        order = sorted(range(n), key=lambda c: firing[c])
        alternations = sum(banks[order[i]] != banks[order[(i + 1) % n]] for i in range(n))
        key = (-alternations, tuple(order))
        if best is None or key < best[0]:
            best = (key, firing, order)
    _key, firing, order = best
    gaps = np.diff(sorted(firing) + [720.0])
    even = bool(np.allclose(gaps, 720.0 / n))
    fire = (f"even firing every {720.0 / n:g} deg" if even else
            "the layout does not allow even firing (firing intervals "
            + "/".join(f"{g:g}" for g in gaps) + " deg)")
    note = (f"V{n}, {alpha:g} deg bank angle, two rods per pin, {how}; each pair of cylinders"
            " reaching TDC at the same crank position fires 360 deg apart, the order chosen to"
            " alternate the banks most often (then the lowest cylinder numbers first); " + fire)
    return (pins, cyl_pin, banks, firing, "-".join(str(c + 1) for c in order), note)


def _cw_for_target(b: Brief, geo: dict, target_unbalance: float, mat: dict, ro_max: float,
                   t_max: float) -> tuple[float, float, float]:
    """Outer radius, angle and axial thickness of the two counterweights of a throw whose
    unbalance (kg m, opposite the pin) is ``target_unbalance`` (crank geometry of the crank
    branch): 150 deg at the web thickness first, then 180 deg, then thicker (up to
    ``t_max``); none reaches it: the largest that fits if it balances at least half the
    target (the low end of industrial practice), else :class:`NoRule`."""
    ri = geo["journal_diameter"] / 2.0
    tw = geo["web_thickness"]

    def u(ro: float, ang: float, tc: float) -> float:
        p = throw_mass_properties(**geo, density=mat["density"], cw_inner_radius=ri,
                                  cw_outer_radius=ro, cw_angle=ang, cw_thickness=tc)
        return float(-(p.mass[0, 2] * p.y[0, 2] + p.mass[0, 5] * p.y[0, 5]))

    tries = [(150.0, tw), (180.0, tw)] + [(180.0, min(f * tw, t_max)) for f in (1.25, 1.5, 2.0)
                                          if f * tw <= t_max]
    for ang_deg, tc in tries:
        ang = math.radians(ang_deg)
        if u(ro_max, ang, tc) >= target_unbalance:
            lo, hi = ri * 1.0001, ro_max
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if u(mid, ang, tc) < target_unbalance:
                    lo = mid
                else:
                    hi = mid
            return hi, ang, tc
    ang, tc = math.radians(tries[-1][0]), tries[-1][1]
    if u(ro_max, ang, tc) >= 0.5 * target_unbalance:  # the largest that fits, >= 50 %
        return ro_max, ang, tc
    raise NoRule("counterweight: no annular counterweight up to 180 deg, the swing radius"
                 f" {ro_max * 1e3:.0f} mm (rod length - crank radius - 0.25 bore) and"
                 f" {t_max * 1e3:.0f} mm thickness balances half the target"
                 f" ({target_unbalance * 1e3:.0f} kg mm); the counterweight rule has no data for"
                 " this geometry")


def layout(b: Brief) -> Layout:
    """Size every dimension by its rule (:mod:`checker.calc.first_layout`)."""
    throws, cyl_throw, banks, firing, order, fnote = _throws_and_firing(b)
    n_thr = max(cyl_throw)
    rods_per_pin = b.cylinders // n_thr
    gas = fl.peak_gas_force(b.bore, b.peak_pressure)
    dp = fl.pin_diameter(b.bore)
    dj = fl.main_diameter(dp)
    rf_p, rf_j = fl.fillet_radius(dp), fl.fillet_radius(dj)
    rod_len = fl.rod_length(b.stroke, b.fuel)
    wp = fl.wrist_pin(b.bore)
    piston = fl.piston_mass(b.bore, b.fuel) + wp.mass
    force, rod_land = gas, fl.land_length(gas, dp, b.bearing_pressure)
    for _ in range(20):  # the rod's big eye is as wide as the land the resultant needs
        rod = fl.con_rod(force=gas, length=rod_len, pin_d=dp, pin_land=rod_land, wrist=wp)
        m_rot = rod.mass * (rod_len - rod.centre_from_big_end) / rod_len
        force = fl.resultant_force(gas, piston + rod.mass - m_rot, b.stroke / 2.0, rod_len,
                                   b.rated_speed)
        land = fl.land_length(force, dp, b.bearing_pressure)
        if abs(land - rod_land) < 1e-7:
            break
        rod_land = land
    rod_land = land
    main_land = fl.land_length(force, dj, b.bearing_pressure, share=0.5)
    pin_len = rods_per_pin * rod_land + 2 * (rf_p + 1e-3) + (rods_per_pin - 1) * 1e-3
    main_len = main_land + 2 * (rf_j + 1e-3)
    tw = fl.web_thickness(b.bore)
    bw = fl.web_width(dp)
    spacing = main_len + 2 * tw + pin_len
    mat = MATERIALS[b.crank_material]
    R = b.stroke / 2.0
    geo = dict(journal_diameter=dj, journal_bore=0.0, journal_length=main_len, pin_diameter=dp,
               pin_bore=0.0, pin_length=pin_len, web_thickness=tw, web_width_journal=bw,
               web_width_pin=bw, crank_radius=R)
    bare = throw_mass_properties(**geo, density=mat["density"])
    u_crank = float(bare.mass[0, 1] * bare.y[0, 1] * 2 + bare.mass[0, 3] * bare.y[0, 3])
    m_rot = rod.mass * (rod_len - rod.centre_from_big_end) / rod_len
    m_rec = piston + rod.mass - m_rot
    target = u_crank + rods_per_pin * m_rot * R
    if b.layout == "V" and abs(math.degrees(b.bank_angle) - 90.0) < 1e-6:
        target += m_rec * R
    ro_max = rod_len - R - 0.25 * b.bore
    ro, ang, tc = _cw_for_target(b, geo, target, mat, ro_max, tw + 0.9 * min(pin_len, main_len))
    return Layout(b, n_thr, throws, cyl_throw, banks, firing, order, fnote, force, gas, dp,
                  dj, rod_land, pin_len, main_land, main_len, rf_p, rf_j, tw, bw, rod_len,
                  spacing, wp, piston, rod, dj / 2.0, ro, ang, tc, target, 5e-4 * dj,
                  5e-4 * dp)


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
               + "); oil holes 0.1 x pin diameter [not confirmed]; material: " + mat["source"])
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
    note = est(None, "crank nose 0.75 x and 0.6 x the main journal diameter, flywheel flange 1.0"
               " x and 0.5 x [ratios not confirmed in a public source]")
    return [("Crank nose diameter", _mm(NOSE[0] * L.dj), "mm", note),
            ("Crank nose length", _mm(NOSE[1] * L.dj + L.main_len / 2), "mm", note),
            ("Flywheel flange diameter", _mm(FLANGE[0] * L.dj), "mm", note),
            ("Flywheel flange length", _mm(FLANGE[1] * L.dj + L.main_len / 2), "mm", note)]


def _tv_rows(L: Layout, mat: dict, tune: Tuning) -> list:
    """TVModel: damper ring, crank nose, one station per throw, flywheel. The crank stations'
    inertias and every stiffness along the crank are left blank: the crank module derives them
    from sheets Crank and CrankEnds."""
    b = L.brief
    nose_d, nose_l = NOSE[0] * L.dj, NOSE[1] * L.dj
    _m, jn, _ = cylinder(diameter=nose_d, bore=0.0, length=nose_l, density=mat["density"])
    hub = 4.0 * float(jn)  # pulley hub, timing sprocket and damper hub on the nose
    derived = "derived from sheets Crank and CrankEnds (crank module)"
    rows = [["Damper ring", "damper ring", None, round(tune.ring, 6), None,
             round(tune.ring_stiffness), None,
             est(None, "Den Hartog tuned absorber: ring inertia 0.25 x the first crank mode's"
                 " modal inertia at the nose [ratio not confirmed in a public source];"
                 " rubber stiffness at the optimum tuning of the damper-tuning module (Den"
                 " Hartog, Mechanical Vibrations, 1956)")],
            ["Crank nose", "crank nose", None, round(float(jn) + hub, 7), None, None, None,
             est(None, "inertia of the nose shaft (sheet CrankEnds) plus hubs 4 x its inertia"
                 f" [not confirmed]; stiffness {derived}")]]
    rods = b.cylinders // L.throws
    for t in range(L.throws):
        cyl = [c + 1 for c in range(b.cylinders) if L.cyl_throw[c] == t + 1]
        rows.append([f"Throw {t + 1}" if rods > 1 else f"Cylinder {cyl[0]}", "cylinder",
                     ", ".join(map(str, cyl)) if rods > 1 else cyl[0], None, None, None, None,
                     f"inertia and stiffness {derived}"])
    rows.append(["Flywheel", "flywheel", None, round(tune.flywheel, 5), None, None, None,
                 est(None, "smallest flywheel meeting a cyclic irregularity of 1 % (Agostini"
                     " 2019: 'kinematic irregularity <= 1 %') at the rated speed, full load,"
                     " with the engine's inertias only (flywheel module, +5 %)")])
    return rows


def _joint_design(location: str, torque: float, face_od: float, face_id: float) -> dict:
    """Smallest bolt set (ISO metric, class 10.9, yield-controlled tightening at the
    recommended 75 % of R_p0.2, Bell 2013) whose slip capacity covers ``torque`` with a cover
    factor of 1.8 x 1.1 (friction 0.2, Bell 2013); the bolt no larger than the face allows
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
            cap = 0.2 * n * frac * rp02 * a * r_eff
            f = frac * rp02 * a
            head_id = round(1.1 * d_mm, 1)
            head_od = math.ceil(2 * 1e3 * math.sqrt(4 * f / (math.pi * 450e6)
                                                    + (head_id * 1e-3)**2)) / 2
            best = {"bolts": n, "d": d_mm, "p": p_mm, "capacity": cap, "head_od": head_od,
                    "head_id": head_id, "id": fid}
            if cap >= 1.8 * 1.1 * torque:
                return best
    return best


def content(L: Layout, tune: Tuning) -> dict[str, Any]:
    """The workbook's sheets (format of :func:`checker.workbook.example.write_workbook`)."""
    b = L.brief
    mat = MATERIALS[b.crank_material]
    R = b.stroke / 2.0
    rated_torque = b.rated_power / b.rated_speed
    vd = math.pi / 4 * b.bore**2 * b.stroke
    bmep = rated_torque * 4 * math.pi / (vd * b.cylinders)
    brief_note = "brief (checker new)"

    def dflt(key: str) -> str:
        return (f"{TAG}: default of checker new ({b.defaults[key]})" if key in b.defaults
                else brief_note)

    if b.fuel == "gasoline":
        cls = "passenger car"
    else:
        cls = "marine" if b.bore >= 0.2 else ("commercial vehicle" if b.bore >= 0.095
                                             else "passenger car")
    cr = 10.5 if b.fuel == "gasoline" else 17.0
    bmep_na = 12e5 if b.fuel == "gasoline" else 9e5
    p_int = max(1.0, round(bmep / bmep_na, 2))
    step = max(25, int(round((b.max_speed - b.min_speed) * RPM / 60 / 25.0)) * 25)
    m_rot = L.rod.mass * (L.rod_len - L.rod.centre_from_big_end) / L.rod_len
    engine = [
        ("Engine name", b.name, "-", brief_note),
        ("Number of cylinders", b.cylinders, "-", brief_note),
        ("Engine class", cls, "-", est(None, "by fuel and bore (gasoline: passenger car;"
                                       " diesel: below 95 mm passenger car, to 200 mm"
                                       " commercial vehicle, above marine)")),
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
        ("Target cyclic irregularity", 1 if tune.sizing else None, "%",
         "the project's target at the lowest speed (FLY-001): not estimated by checker new"
         " (the flywheel is sized for 1 % at the rated speed, see TVModel)"),
        ("Project", "checker new: first layout", "-", brief_note),
        ("Revision", "0", "-", brief_note),
    ]
    cyl_cols = [("cylinder", "-"), ("throw angle", "deg"), ("firing angle", "deg"),
                ("bank angle", "deg"), ("crank pin", "-"), ("note", "")]
    cyl_rows = [[c + 1, round(L.throw_angle[L.cyl_throw[c] - 1], 6), round(L.cyl_firing[c], 6),
                 round(L.cyl_bank[c], 6), L.cyl_throw[c], est(None, L.firing_note)]
                for c in range(b.cylinders)]
    # peak pressure and brake torque: the brief's peak at every speed; torque from rated power
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
    # full-load peak pressure: the brief's peak where the torque peaks, the firing part of it
    # scaled with the torque elsewhere (IMEP ~ torque)
    p_mot = p_int * cr**1.3  # bar: polytropic compression, n = 1.3
    pk = b.peak_pressure / 1e5
    src = ("the brief's peak pressure" if "peak_pressure" not in b.defaults
           else "the typical peak pressure (" + fl.RULES["peak_pressure"]["rule"] + "; "
           + fl.RULES["peak_pressure"]["source"] + ")")
    pp_note = est(None, f"{src} at the peak-torque speed; elsewhere the motored peak"
                  f" ({p_mot:.0f} bar = intake pressure x CR^1.3) plus the firing part scaled"
                  " with the brake torque (IMEP ~ torque) [not confirmed]")
    pp_rows = [["full", s_, round(p_mot + (pk - p_mot) * t / t_max, 1), pp_note]
               for s_, t, _n in bt_rows]
    pp_rows.append(["no", round(b.max_speed * RPM), round(1.5 * cr ** 1.3, 1),
                    est(None, "motored peak ~ 1 bar x CR^1.3 x 1.5 (polytropic compression,"
                        " n = 1.3, with throttled/no-load combustion) [not confirmed]")])
    lining = b.bearing_lining
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
                 + f"; lining from the brief ({dflt('bearing_lining')})")
    brows = []
    groove_w = round(0.15 * L.main_land * 1e3, 1)
    for k in range(L.throws + 1):
        brows.append([f"M{k + 1}", "main", None, None, _mm(L.main_land - groove_w * 1e-3),
                      round(L.clearance_main * 1e3, 4), "partial", groove_w, 270, 90, "bearing",
                      0, None, None, None, lining, m_note])
    p_note = est("journal_length", "per rod" + padm_text(b) + "; journal diameter, length and"
                 " oil hole diameter from sheet Crank; " + clr
                 + "; oil hole 45 deg leading [not confirmed]")
    for c in range(b.cylinders):
        brows.append([f"BE{c + 1}", "big end", None, None, _mm(L.rod_land),
                      round(L.clearance_pin * 1e3, 4), "none", None, None, None, "crank", 1,
                      "leading", None, 45, lining, p_note])
    oil = [("Oil grade", "5W30" if b.fuel == "gasoline" else "10W40", "-",
            est(None, "a usual grade for the fuel")),
           ("Oil supply pressure", 4.0, "bar(g)", est(None, "usual gallery pressure at speed")),
           ("Oil supply temperature", 120 if b.fuel == "gasoline" else 110, "°C",
            est(None, "usual gallery temperature at full load")),
           ("Film temperature rise", 10, "K", est(None, "moderate film heating")),
           ("Mobility model", "finite length", "-",
            est(None, "the finite-length Reynolds film (the short bearing is optimistic at"
                " engine L/D)"))]
    tv_cols = [("station", "-"), ("role", "-"), ("cylinder", "-"), ("inertia", "kg m^2"),
               ("absolute damping", "N m s/rad"), ("stiffness to next", "N m/rad"),
               ("damping to next", "N m s/rad"), ("note", "")]
    tv_rows = _tv_rows(L, mat, tune)
    damper = [("Rubber loss factor", round(tune.loss_factor, 3), "-",
               est(None, "Den Hartog's optimum loss factor for the ring/crank inertia ratio"
                   " (damper-tuning module)")),
              ("Tuning ratio, minimum", round(0.9 * tune.tuning, 3), "-",
               est(None, "Den Hartog's optimum tuning ratio for this ring/crank inertia ratio"
                   " (damper-tuning module) -10 % [band not confirmed]")),
              ("Tuning ratio, maximum", round(1.1 * tune.tuning, 3), "-",
               est(None, "Den Hartog's optimum tuning ratio +10 % [band not confirmed]"))]
    src = f"{TAG}: {mat['source']}"
    fatigue = [  # the web, fillet, oil-hole and bore dimensions come from sheet Crank
        ("Web offset", 0, "mm", est(None, "symmetric web")),
        ("Pin journal oil hole height", _mm(L.dp / 2 * math.sin(math.radians(45))), "mm",
         est(None, "pin radius x sin 45 deg (hole 45 deg leading)")),
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
    ]
    jcols = [("name", "-"), ("location", "-"), ("bolts", "-"), ("nominal diameter", "mm"),
             ("thread pitch", "mm"), ("property class", "-"), ("tightening", "-"),
             ("head bearing outer diameter", "mm"), ("head bearing inner diameter", "mm"),
             ("clamped material", "-"), ("face outer diameter", "mm"),
             ("face inner diameter", "mm"), ("friction coefficient", "-"), ("note", "")]
    jrows = []
    for j in tune.joints:
        jrows.append([j["name"], j["name"], j["bolts"], j["d"], j["p"], "10.9",
                      "yield controlled", j["head_od"], j["head_id"],
                      "steel", _mm(j["od"]), _mm(j["id"]), 0.2,
                      est(None, f"smallest bolt set whose slip capacity covers the torsional"
                          f" model's largest joint torque {j['torque']:.0f} N m with a cover"
                          " factor of 1.8 (+10 %), yield-controlled tightening at 75 % of"
                          " R_p0.2 and friction 0.2 (Bell, Ricardo 2013); head bearing"
                          " diameter for 90 % of the 500 N/mm^2 contact limit on steel (Bell,"
                          " Ricardo 2013) from a 1.1 d clearance hole; face diameters [ratios"
                          " not confirmed]")])
    return {
        "Engine": engine,
        "Cylinders": (cyl_cols, cyl_rows),
        "PeakPressure": ([("load case", "-"), ("speed", "rpm"), ("peak pressure", "bar"),
                          ("note", "")], pp_rows),
        "BrakeTorque": ([("speed", "rpm"), ("brake torque", "N m"), ("note", "")], bt_rows),
        "Bearings": (bcols, brows),
        "Crank": _crank_sheet(L, mat),
        "CrankEnds": _crank_ends(L),
        "CrankMass": ([("location", "-"), ("throw", "-"), ("kind", "-"), ("mass", "kg"),
                       ("X", "mm"), ("Y", "mm"), ("Z", "mm"), ("axial position", "mm"),
                       ("relative to", "-"), ("note", "")], []),
        "Oil": oil,
        "TVModel": (tv_cols, tv_rows),
        "Damper": damper,
        "Fatigue": fatigue,
        "Joints": (jcols, jrows),
        "JointTorques": ([("joint", "-"), ("operating point", "-"), ("speed", "rpm"),
                          ("applied torque", "N m"), ("note", "")], []),
        "RuleOverrides": ([("rule", "-"), ("limit", "-"), ("unit", "-"), ("reason", "-")], []),
        "Tolerances": ([("sheet", "-"), ("row", "-"), ("column", "-"), ("min", "-"),
                        ("max", "-"), ("unit", "-"), ("source", "")], []),
        "Notes": [f"First layout written by checker new from a brief: {b.name}.",
                  "Values marked ESTIMATE are sized by a stated design rule (see each note and"
                  " docs/new-engine.md), not data of this engine.",
                  "Replace each estimate with the design's value as it becomes known.",
                  f"Peak gas force {L.gas / 1e3:.1f} kN, resultant at TDC and the rated"
                  f" speed {L.force / 1e3:.1f} kN, rated torque {rated_torque:.0f} N m,"
                  f" rated BMEP {bmep / 1e5:.1f} bar; rotating share of the rod"
                  f" {m_rot:.3f} kg, crank radius {R * 1e3:g} mm.",
                  "See docs/workbook.md for every sheet, parameter and column."],
    }


def _evaluate(cont: dict[str, Any], select: list[str]):
    from .. import api
    from ..workbook.example import write_workbook

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "pass.xlsx"
        write_workbook(path, cont)
        res = api.check(str(path), select=select)
    return res


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


def size(b: Brief) -> tuple[Layout, dict[str, Any]]:
    """The layout and the workbook content, its flywheel, damper and joints made consistent
    with the checker's own models (three evaluation passes)."""
    L = layout(b)
    mat = MATERIALS[b.crank_material]
    crank_j = L.throws * float(_throw_props(L, mat).inertia_total[0])
    od = 1.6 * L.dj
    joints0 = [{"name": "crank nose", "bolts": 1, "d": 12, "p": 1.25, "torque": 0.0,
                "od": 0.75 * L.dj, "id": 0.0, "head_od": 24.0, "head_id": 13.2},
               {"name": "flywheel", "bolts": 8, "d": 10, "p": 1.25, "torque": 0.0, "od": od,
                "id": L.dj * 0.8, "head_od": 20.0, "head_id": 11.0}]
    tune = Tuning(flywheel=20 * crank_j, ring=0.25 * crank_j,
                  ring_stiffness=0.25 * crank_j * (2 * math.pi * 300.0)**2, loss_factor=0.2,
                  joints=joints0)
    for _ in range(4):  # flywheel and damper tuning settle in 2-3 passes
        res = _evaluate(content(L, tune), ["FLY", "DMP"])
        j_min = _rated(res, "flywheel.minimum_inertia", b.rated_speed)
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
        new = Tuning(fw, ring, k, min(max(loss, 0.05), 1.0), joints0, tuning=tr)
        done = (abs(new.flywheel / tune.flywheel - 1) < 0.01
                and abs(new.ring / tune.ring - 1) < 0.01
                and abs(new.ring_stiffness / tune.ring_stiffness - 1) < 0.01)
        tune = new
        if done:
            break
    res = _evaluate(content(L, tune), ["TV", "JNT"])  # the joint torques of the tuned model
    tq = _q(res, "tv.joint_torque")
    joints = []
    for i, j in enumerate(joints0):
        t = float(np.nanmax(tq[i])) if tq is not None else float("nan")
        if not np.isfinite(t) or t <= 0:
            raise NoRule(f"{j['name']} joint: the torsional model gave no joint torque")
        joints.append({**j, **_joint_design(j["name"], t, j["od"], j["id"]), "torque": t})
    tune = replace(tune, joints=joints)
    return L, content(L, replace(tune, sizing=False))

