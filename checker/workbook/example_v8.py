"""A third example workbook: a 90-degree cross-plane V8 built from public service data.

``checker template --engine v8`` writes it. It exercises what only a V engine has: two rods on
each crank pin (pin, main-bearing and fillet loads from both rods, big-end loads per rod in its
own rod frame), one torsional station per throw carrying both cylinders of the pin, bank
angles in the balancing, and the counterweights of a cross-plane crank. Same sheets and column
headers as :func:`checker.workbook.example.example_content`.

Sources
-------
[GM] GM Service Manual, "Engine Mechanical Specifications", 5.7 L V8 RPO LS1 (1997-2004
    Corvette and F-car): bore 99.0-99.018 mm, stroke 92.0 mm, firing order 1-8-7-2-6-5-4-3,
    compression ratio 10.1:1, oil 5W-30, connecting rod journal diameter 53.318-53.338 mm,
    connecting rod bearing clearance (production) 0.023-0.065 mm, crankshaft (main) bearing
    clearance (production) 0.020-0.052 mm; 90-degree V, five main bearings, cast nodular iron
    crankshaft with undercut and rolled journal fillets (GM's LS1 engine description).

Everything else is assumed for a 5.7 L two-valve passenger-car V8 and marked ``ASSUMPTION`` in
the note column with a one-line reason; :data:`ASSUMED` lists them.

Layout and conventions
----------------------
* GM numbering: odd cylinders 1-3-5-7 on the left bank, even 2-4-6-8 on the right bank,
  cylinders ``2k - 1`` and ``2k`` on crank pin ``k`` (the left bank is the forward one). With the
  crank turning clockwise seen from the front, the left bank lies at +45 deg from the vertical
  in the direction of rotation and the right bank at -45 deg (sheet Cylinders, bank angle).
* Firing angles from the firing order at 90-degree intervals: 1: 0, 8: 90, 7: 180, 2: 270,
  6: 360, 5: 450, 4: 540, 3: 630 deg. Throws (workbook convention, :func:`checker.calc.
  crank_forces.throw_angles`: gamma = bank - firing, relative to throw 1): pins 1-4 at 0, 90,
  270, 180 deg, the cross-plane crank. Both cylinders of a pin give the same throw.
* Crank masses in the throw-1 frame (Y along throw 1, Z +90 deg in the direction of rotation,
  X the axial offset from the component's plane).

Counterweights (:func:`counterweights`)
---------------------------------------
A 90-degree V8 throw carries an equivalent first-order rotating unbalance ``U = U_crank + 2 m_b r
+ m_rec r`` (webs and pin, both rods' big ends, and the primary forces of the two reciprocating
masses, which for a 90-degree V add up to a force of constant magnitude ``m_rec r omega^2``
turning with the throw; Taylor 1985, vol. 2, ch. 8). The four throws cancel as forces but leave
a rotating couple ``C = U sum z_j e_j`` of magnitude ``sqrt(10) U L`` (``L`` the throw pitch),
which counterweights must cancel. As cross-plane cranks are built, every web carries a
counterweight opposite its own throw balancing half of that web's share (``U / 4`` per web),
and the two end webs carry in addition the counterweights ``+-(C / 2) / (z_web8 - z_web1)``
that cancel the rest of the couple: the end counterweights are the heaviest and are turned
away from their own throws. The crank then leaves no first-order free force or moment.
"""

from __future__ import annotations

import math
from typing import Any

from .example import (
    _NO_SUPPLIER_LIMITS,
    BEARING_COLUMNS,
    BRAKE_TORQUE_COLUMNS,
    CRANK_MASS_COLUMNS,
    CYLINDER_COLUMNS,
    JOINT_COLUMNS,
    JOINT_TORQUE_COLUMNS,
    NOSE_ROWS,
    RULE_OVERRIDE_COLUMNS,
    TOLERANCE_COLUMNS,
    TV_MODEL_COLUMNS,
)

GM = "GM Service Manual, LS1 5.7 L Engine Mechanical Specifications"
GM_DESC = "GM LS1 engine description"
ASSUMPTION = "ASSUMPTION"

# ---------------------------------------------------------------- published data [GM]
BORE, STROKE = 99.0, 92.0  # mm
FIRING_ORDER = (1, 8, 7, 2, 6, 5, 4, 3)
PIN_DIAMETER = 53.32  # mm, 53.318-53.338
ROD_CLEARANCE_DIAMETRAL = (0.023, 0.065)  # mm, production
MAIN_CLEARANCE_DIAMETRAL = (0.020, 0.052)  # mm, production

# ---------------------------------------------------------------- assumed geometry and masses
ROD_LENGTH = 154.9  # mm
SPACING = 111.76  # mm, bore spacing = main journal spacing
MAIN_D, MAIN_L, MAIN_EFF = 64.99, 26.0, 18.0  # mm
PIN_L, PIN_EFF = 48.0, 19.0  # mm: whole pin (two rods); effective land per rod bearing
WEB_T = round((SPACING - MAIN_L - PIN_L) / 2, 2)  # 18.88 mm: main + pin + two webs = spacing
ROD_MASS, ROD_COM = 0.640, 45.0  # kg, mm from the big end
PISTON_MASS = 0.580  # kg
ROD_INERTIA = 2850  # kg mm^2: 0.9 x m a b (the Ricardo example rod's ratio)
CRANK_R = STROKE / 2
M_REC = PISTON_MASS + ROD_MASS * ROD_COM / ROD_LENGTH  # two-mass rod: small-end share
M_BIG = ROD_MASS - ROD_MASS * ROD_COM / ROD_LENGTH

_W_MASS, _W_R = 1.00, 23.0  # web arm: ~95 x 80 x 18.9 mm nodular iron, centre 0.5 r
_PIN_MASS = round(math.pi / 4 * PIN_DIAMETER**2 * PIN_L * 7.1e-6, 3)  # solid, 7100 kg/m^3
_CW_R = 52.0  # counterweight centre of mass radius [mm]
_CW_LOCAL_FRACTION = 0.5  # of each throw's equivalent unbalance, in its own two webs
_W_FRONT = MAIN_L / 2 + WEB_T / 2  # web centre from its bay's front main [mm]
_W_REAR = SPACING - _W_FRONT


def _deg_mod(a: float) -> float:
    return a % 360.0


# ---------------------------------------------------------------- cylinders
#: Firing angle after cylinder 1 [deg] (90-degree intervals, order 1-8-7-2-6-5-4-3).
FIRING_ANGLES = {c: 90 * k for k, c in enumerate(FIRING_ORDER)}
#: Bank angle [deg]: left bank (odd) +45, right bank (even) -45 (clockwise crank, from the
#: vertical in the direction of rotation).
BANK_ANGLES = {c: (45 if c % 2 else -45) for c in range(1, 9)}
#: Crank pin of each cylinder (GM: 1-2, 3-4, 5-6, 7-8).
PINS = {c: (c + 1) // 2 for c in range(1, 9)}
_GAMMA = {c: _deg_mod(BANK_ANGLES[c] - FIRING_ANGLES[c]) for c in range(1, 9)}
#: Throw angle from throw 1 in the direction of rotation [deg] (0, 90, 270, 180 for pins 1-4).
THROW_ANGLES = {c: _deg_mod(_GAMMA[c] - _GAMMA[1]) for c in range(1, 9)}
PIN_THROW = {PINS[c]: THROW_ANGLES[c] for c in range(1, 9)}


def _e(deg: float) -> tuple[float, float]:
    """Unit vector (Z, Y) of a direction ``deg`` from throw 1 in the direction of rotation."""
    g = math.radians(deg)
    return math.sin(g), math.cos(g)


def throw_unbalance() -> dict[str, float]:
    """Equivalent first-order rotating unbalance of one throw [kg m] and its parts."""
    crank = (2 * _W_MASS * _W_R + _PIN_MASS * CRANK_R) * 1e-3
    rods = 2 * M_BIG * CRANK_R * 1e-3
    recip = M_REC * CRANK_R * 1e-3
    return {"crank": crank, "rods": rods, "reciprocating": recip, "total": crank + rods + recip}


def counterweights() -> dict[int, tuple[float, float]]:
    """Counterweight unbalance vector (Z, Y) [kg m] of webs 1..8 (module docstring)."""
    u = throw_unbalance()["total"]
    local = _CW_LOCAL_FRACTION * u / 2
    z_pin = {j: (j - 0.5) * SPACING * 1e-3 for j in range(1, 5)}
    cz = sum(z_pin[j] * u * _e(PIN_THROW[j])[0] for j in range(1, 5))
    cy = sum(z_pin[j] * u * _e(PIN_THROW[j])[1] for j in range(1, 5))
    z1 = _W_FRONT * 1e-3
    z8 = (3 * SPACING + _W_REAR) * 1e-3
    rest = 1.0 - _CW_LOCAL_FRACTION
    e_rear = (-rest * cz / (z8 - z1), -rest * cy / (z8 - z1))
    out = {}
    for web in range(1, 9):
        j = (web + 1) // 2
        ez, ey = _e(PIN_THROW[j])
        vz, vy = -local * ez, -local * ey
        if web == 1:
            vz, vy = vz - e_rear[0], vy - e_rear[1]
        elif web == 8:
            vz, vy = vz + e_rear[0], vy + e_rear[1]
        out[web] = (vz, vy)
    return out


# ---------------------------------------------------------------- parameter sheets
ENGINE_ROWS: list[tuple[str, Any, str, str]] = [
    ("Engine name", "Example V8 gasoline (GM LS1 5.7 L, public service data)", "-", GM),
    ("Number of cylinders", 8, "-", GM),
    ("Layout", "V", "-", GM + ": 90-degree V8"),
    ("Bore", BORE, "mm", GM + ": 99.0-99.018 mm"),
    ("Stroke", STROKE, "mm", GM),
    ("Connecting rod length", ROD_LENGTH, "mm", ASSUMPTION + ": 154.9 mm (6.098 in), the"
     " commonly quoted LS rod length"),
    ("Cylinder offset", 0.0, "mm", ASSUMPTION + ": none"),
    ("Pin offset", 0.0, "mm", ASSUMPTION + ": none (the balancing of the cross-plane crank is"
     " exact without offsets)"),
    ("Crankshaft rotation", "clockwise", "-", ASSUMPTION + ": clockwise seen from the front,"
     " the SAE standard rotation"),
    ("Firing order", "1-8-7-2-6-5-4-3", "-", GM),
    ("Cylinder spacing", SPACING, "mm", ASSUMPTION + ": 4.40 in, the commonly quoted LS bore"
     " spacing"),
    ("Main journal spacing", SPACING, "mm", ASSUMPTION + ": one main between each pair of"
     " cylinders (five mains, " + GM_DESC + ")"),
    ("Connecting rod mass", ROD_MASS, "kg", ASSUMPTION + ": powder-metal rod of a 99 mm bore,"
     " with bolts and shells"),
    ("Rod centre of mass from big end", ROD_COM, "mm", ASSUMPTION + ": 0.29 x rod length"
     " (typical)"),
    ("Rod moment of inertia about centre of mass", ROD_INERTIA, "kg mm^2",
     ASSUMPTION + ": 0.9 x two-mass value m a b (the ratio of the Ricardo example rod)"),
    ("Piston assembly mass", PISTON_MASS, "kg", ASSUMPTION + ": cast hypereutectic piston,"
     " rings, pin and clips for a 99 mm bore"),
    ("Compression ratio", 10.1, "-", ASSUMPTION + ": 10.1, the value of the " + GM + " table"),
    ("Intake manifold pressure at full load", 1.0, "bar", ASSUMPTION + ": naturally aspirated"),
    ("Rated speed", 5600, "rpm", ASSUMPTION + ": maximum power speed of the assumed brake"
     " torque curve"),
    ("Minimum speed", 1000, "rpm", ASSUMPTION + ": lowest full-load speed swept"),
    ("Maximum speed", 6000, "rpm", ASSUMPTION + ": rev limit of a two-valve pushrod V8"),
    ("Speed step", 100, "rpm", ASSUMPTION + ": as Bell 2013 I4 (100 rpm intervals)"),
    ("Overspeed", 6500, "rpm", ASSUMPTION + ": about 1.08 x the rev limit"),
    ("Accessory drive torque at crank nose", 25, "N m", ASSUMPTION + ": alternator, water pump,"
     " power steering and A/C on one belt"),
    ("Free force limit, 1st order", 500, "N", ASSUMPTION + ": ILLUSTRATIVE project limit at"
     " rated speed (no published limit), replace with the project's value"),
    ("Free force limit, 2nd order", 500, "N", ASSUMPTION + ": ILLUSTRATIVE project limit (a"
     " cross-plane V8 has no 2nd-order free force)"),
    ("Free moment limit, 1st order", 100, "N m", ASSUMPTION + ": ILLUSTRATIVE project limit"
     " (the counterweights cancel the cross-plane V8's rotating primary couple)"),
    ("Free moment limit, 2nd order", 100, "N m", ASSUMPTION + ": ILLUSTRATIVE project limit"),
    ("Balance ratio, minimum", 50, "%", ASSUMPTION + ": ILLUSTRATIVE band for the"
     " counterweight balance ratio per throw"),
    ("Balance ratio, maximum", 150, "%", ASSUMPTION + ": ILLUSTRATIVE band (the end throws of a"
     " cross-plane crank carry more than their own unbalance)"),
    ("Target cyclic irregularity", 10, "%", ASSUMPTION + ": ILLUSTRATIVE target at the lowest"
     " speed, as the I4 example"),
]

OIL_ROWS = [
    ("Oil grade", "5W30", "-", ASSUMPTION + ": 5W-30, the oil of the " + GM + " table"),
    ("Oil supply pressure", 3.5, "bar(g)", ASSUMPTION + ": gallery pressure at speed (the " + GM
     + " table's hot minimum is 1.65 bar at 4000 rpm)"),
    ("Oil supply temperature", 110, "°C", ASSUMPTION + ": sump/gallery at full load"),
    ("Film temperature rise", 10, "K", ASSUMPTION + ": moderate film heating"),
    ("Film temperature", "supply plus rise", "-", ASSUMPTION + ": supply plus rise (the"
     " default); 'heat balance' runs the film thickness at each bearing's balance temperature"),
    ("Heat fraction carried by the oil", 1.0, "-", ASSUMPTION + ": all bearing friction heat"
     " leaves with the oil (conservative; the default when blank)"),
]

DAMPER_ROWS = [
    ("Rubber loss factor", 0.15, "-", ASSUMPTION + ": typical EPDM/NR loss factor tan(delta)"),
    ("Rubber inner radius", 70, "mm", ASSUMPTION + ": ILLUSTRATIVE geometry of the balancer"
     " ring"),
    ("Rubber outer radius", 74, "mm", ASSUMPTION + ": ILLUSTRATIVE geometry"),
    ("Rubber axial length", 32, "mm", ASSUMPTION + ": ILLUSTRATIVE geometry"),
    ("Rubber shear stress limit", 0.5, "MPa", ASSUMPTION + ": ILLUSTRATIVE limit, replace with"
     " the damper supplier's value"),
    ("Rubber heat per unit volume limit", 0.5, "W/cm^3", ASSUMPTION + ": ILLUSTRATIVE limit,"
     " replace with the damper supplier's value"),
    ("Tuning ratio, minimum", 0.80, "-", ASSUMPTION + ": ILLUSTRATIVE band, about -10 % around"
     " Den Hartog's optimum for this ring/crank inertia ratio"),
    ("Tuning ratio, maximum", 0.98, "-", ASSUMPTION + ": ILLUSTRATIVE band, about +10 % around"
     " Den Hartog's optimum"),
]

_IRON = ASSUMPTION + ": cast nodular iron crank (" + GM_DESC + "), GJS-800-2 class"
FATIGUE_ROWS = [
    ("Web reduced thickness", WEB_T - 1.0, "mm", ASSUMPTION + ": full thickness - 2 x 0.5 mm"
     " lands"),
    ("Web full thickness", WEB_T, "mm", ASSUMPTION + ": (111.76 spacing - 26 main - 48 pin)/2"),
    ("Web minimum width", 90.0, "mm", ASSUMPTION + ": 1.7 x pin diameter"),
    ("Web maximum width", 110.0, "mm", ASSUMPTION + ": 2 x pin diameter"),
    ("Web offset", 0, "mm", ASSUMPTION + ": symmetric web"),
    ("Crank pin fillet radius", 2.5, "mm", ASSUMPTION + ": undercut rolled fillet (" + GM_DESC
     + "), 0.047 x pin diameter"),
    ("Crank pin fillet undercut", 0.5, "mm", ASSUMPTION + ": undercut fillet"),
    ("Crank pin fillet web undercut", 0, "mm", ASSUMPTION + ": none"),
    ("Main journal fillet radius", 2.5, "mm", ASSUMPTION + ": undercut rolled fillet"),
    ("Main journal fillet undercut", 0.5, "mm", ASSUMPTION + ": undercut fillet"),
    ("Main journal web undercut", 0, "mm", ASSUMPTION + ": none"),
    ("Pin journal oil hole diameter", 6.0, "mm", ASSUMPTION + ": 0.11 x pin diameter"),
    ("Pin journal oil hole height", round(PIN_DIAMETER / 2 * math.sin(math.radians(45)), 2),
     "mm", ASSUMPTION + ": pin radius x sin(45 deg), hole 45 deg leading (Bearings sheet)"),
    ("Main journal oil hole diameter", 6.0, "mm", ASSUMPTION + ": as the pin oil hole"),
    ("Main journal oil hole height", round(MAIN_D / 2 * math.sin(math.radians(20)), 2), "mm",
     ASSUMPTION + ": journal radius x sin(20 deg)"),
    ("Pin journal land diameter", 66.0, "mm", ASSUMPTION + ": pin diameter + 12.7 mm"),
    ("Pin journal land thickness", 0.5, "mm", ASSUMPTION + ": as the Ricardo example"),
    ("Main journal land diameter", 78.0, "mm", ASSUMPTION + ": journal diameter + 13 mm"),
    ("Main journal land thickness", 0.5, "mm", ASSUMPTION + ": as the Ricardo example"),
    ("Pin bore diameter", 0, "mm", ASSUMPTION + ": solid pin"),
    ("Main journal bore diameter", 0, "mm", ASSUMPTION + ": solid journal"),
    ("Base material UTS", 800, "N/mm^2", _IRON),
    ("Fillet UTS", 800, "N/mm^2", _IRON + " (rolling credited in the fatigue strengths)"),
    ("Base tensile yield strength", 480, "N/mm^2", _IRON),
    ("Base compressive yield strength", 480, "N/mm^2", _IRON),
    ("Base infinite life fatigue strength", 300, "N/mm^2", ASSUMPTION + ": 0.375 x UTS, smooth"
     " nodular iron"),
    ("Base hydrostatic fatigue strength", 435, "N/mm^2", ASSUMPTION + ": 2.5 x 174 (Ricardo"
     " example rule)"),
    ("Base torsional fatigue strength", 174, "N/mm^2", ASSUMPTION + ": 0.58 x 300"),
    ("Fillet tensile and compressive yield", 600, "N/mm^2", ASSUMPTION + ": rolled fillet"
     " layer"),
    ("Pin fillet fatigue strength", 470, "N/mm^2", ASSUMPTION + ": 300 x 0.87 (size) x 1.8"
     " (rolled fillet, as Bell, Ricardo 2013: x 1.9 for steel)"),
    ("Pin oil hole fatigue strength", 261, "N/mm^2", ASSUMPTION + ": 300 x 0.87 x 1.0"),
    ("Main fillet fatigue strength", 465, "N/mm^2", ASSUMPTION + ": 300 x 0.86 x 1.8 (rolled)"),
    ("Main oil hole fatigue strength", 258, "N/mm^2", ASSUMPTION + ": 300 x 0.86 x 1.0"),
]

# ---------------------------------------------------------------- table sheets
CYLINDERS = (
    CYLINDER_COLUMNS,
    [[c, THROW_ANGLES[c], FIRING_ANGLES[c], BANK_ANGLES[c], PINS[c],
      GM + ": firing order 1-8-7-2-6-5-4-3 at 90 deg; " + ASSUMPTION + ": GM numbering (odd"
      " left bank at +45 deg, even right bank at -45 deg, cylinders 2k-1 and 2k on pin k);"
      " throw = bank - firing angle, relative to throw 1"] for c in range(1, 9)],
)

_FULL = [(1000, 55.0), (1500, 60.0), (2000, 66.0), (2500, 71.0), (3000, 75.0), (3500, 78.0),
         (4000, 80.0), (4500, 82.0), (5000, 82.0), (5500, 80.0), (6000, 76.0)]
PEAK_PRESSURE = (
    [("load case", "-"), ("speed", "rpm"), ("peak pressure", "bar"), ("note", "")],
    [["full", n, p, ASSUMPTION + ": absolute peak pressure of a naturally aspirated 10:1"
      " two-valve gasoline engine (as Bell 2013 I4, 53-84 bar)"] for n, p in _FULL]
    + [["no", 6500, 29.0, ASSUMPTION + ": no-load overspeed point as Bell 2013 I4 (29.1 bar"
        " at 7000 rpm)"]],
)

_BRAKE = [(1000, 400), (1500, 420), (2000, 440), (2500, 450), (3000, 460), (3500, 467),
          (4000, 472), (4400, 475), (5000, 462), (5600, 438), (6000, 395)]
BRAKE_TORQUE = (
    BRAKE_TORQUE_COLUMNS,
    [[n, t, ASSUMPTION + ": curve of a 5.7 L two-valve V8, 475 N m at 4400 rpm and 257 kW at"
      " 5600 rpm (the 1997 Corvette rating as commonly quoted)"] for n, t in _BRAKE],
)

_MAIN_C = round(sum(MAIN_CLEARANCE_DIAMETRAL) / 4, 4)
_PIN_C = round(sum(ROD_CLEARANCE_DIAMETRAL) / 4, 4)
_MAIN = ["main", MAIN_D, MAIN_L, MAIN_EFF, _MAIN_C, "partial", 4.0, 270, 90, "bearing", 0,
         None, None, None, "aluminium bimetal"]
_PIN = ["big end", PIN_DIAMETER, PIN_L, PIN_EFF, _PIN_C, "none", None, None, None, "crank", 1,
        "leading", 6.0, 45, "aluminium bimetal"]
_MAIN_NOTE = (GM + ": radial clearance (0.020 + 0.052)/4 = 0.018 mm (production, diametral);"
              " " + ASSUMPTION + ": journal 64.99 mm (2.558 in, as commonly quoted), length 26"
              " mm, effective 26 - 4 groove - 2 x 2 chamfers, upper shell grooved, aluminium"
              " bimetal lining")
_PIN_NOTE = (GM + ": pin 53.32 mm (53.318-53.338), radial clearance (0.023 + 0.065)/4 ="
             " 0.022 mm (production, diametral); " + ASSUMPTION + ": journal length = the"
             " whole pin, 48 mm for two rods; effective 19 mm per rod bearing; aluminium"
             " bimetal lining; oil hole 6 mm at 45 deg leading")
BEARINGS = (
    BEARING_COLUMNS,
    [[f"M{i}", *_MAIN, *_NO_SUPPLIER_LIMITS, _MAIN_NOTE] for i in range(1, 6)]
    + [[f"BE{i}", *_PIN, *_NO_SUPPLIER_LIMITS, _PIN_NOTE + f" (rod of cylinder {i}, pin {PINS[i]})"]
       for i in range(1, 9)],
)

_AX_NOTE = (f"web centre at half main journal + half web ({MAIN_L / 2:g} + {WEB_T / 2:g} mm)"
            " from its main, pin at mid-bay")


def _zy(vec: tuple[float, float], radius: float) -> tuple[float, float, float]:
    """(mass [kg], Z [mm], Y [mm]) of a counterweight of unbalance ``vec`` [kg m]."""
    u = math.hypot(*vec)
    return (round(u / (radius * 1e-3), 4), round(radius * vec[0] / u, 3) + 0.0,
            round(radius * vec[1] / u, 3) + 0.0)


def _crank_mass_rows() -> list[list[Any]]:
    rows: list[list[Any]] = []
    cws = counterweights()
    for j in range(1, 5):
        g = PIN_THROW[j]
        ez, ey = _e(g)
        wz, wy = round(_W_R * ez, 3) + 0.0, round(_W_R * ey, 3) + 0.0
        web_note = (ASSUMPTION + f": {_W_MASS:g} kg nodular iron web arm, centre of mass"
                    f" {_W_R:g} mm along throw {j} ({g:g} deg from throw 1); {_AX_NOTE}")
        for web, ax in ((2 * j - 1, _W_FRONT), (2 * j, _W_REAR)):
            rows.append([f"Web{web}", j, "web", _W_MASS, 0, wy, wz, round(ax, 2), "main axis",
                         web_note])
            m, cz, cy = _zy(cws[web], _CW_R)
            d = math.degrees(math.atan2(cz, cy)) % 360
            what = ("end counterweight: half of the throw's share plus the share of the"
                    " cross-plane couple, turned away from the throw" if web in (1, 8)
                    else "opposite the throw, half of the web's share of the throw's"
                    " equivalent unbalance")
            rows.append([f"Web{web} c/w", j, "counterweight", m, 0, cy, cz, round(ax, 2),
                         "main axis", ASSUMPTION + f": 8-counterweight cross-plane crank,"
                         f" centre of mass at {_CW_R:g} mm, {d:.1f} deg from throw 1; {what};"
                         f" crank free of 1st-order force and moment; {_AX_NOTE}"])
            if web % 2:
                rows.append([f"Crankpin{j}", j, "pin", _PIN_MASS, 0, 0, 0, SPACING / 2,
                             "pin axis", ASSUMPTION + f": solid {PIN_DIAMETER} x {PIN_L:g} mm"
                             f" nodular iron pin; {_AX_NOTE}"])
    return rows


CRANK_MASS = (CRANK_MASS_COLUMNS, _crank_mass_rows())

# ---------------------------------------------------------------- torsional model
#: Throw station inertias [kg m^2]: the point-mass estimate of each throw's CrankMass rows
#: (sum m rho^2) x 1.227 for the parts' own inertia and the journals (the ratio of the seed
#: I4's station inertia, less its rod, to the point-mass estimate of its CrankMass rows), plus
#: both rods, m_b r^2 + m_rec r^2/2 each (the mean inertia of the reciprocating parts, Ker
#: Wilson); recomputed in tests/workbook/test_example_v8.py. The end throws carry the heavy
#: end counterweights.
THROW_INERTIA = {1: 0.0162, 2: 0.0119, 3: 0.0119, 4: 0.0162}
SHAFT_STIFFNESS = 480e3  # N m/rad between throws
NOSE_STIFFNESS = 300e3  # N m/rad, crank nose -> throw 1
REAR_STIFFNESS = 800e3  # N m/rad, throw 4 -> flywheel
NOSE_INERTIA = 0.0030  # kg m^2, balancer hub, sprocket and nose
FLYWHEEL_INERTIA = 0.200  # kg m^2, flywheel and clutch
RING_INERTIA = 0.0065  # kg m^2
#: Rubber stiffness [N m/rad], Den Hartog tuned to the first mode of the chain without the
#: ring (372.3 Hz): J_eq = 0.0317 kg m^2 (modal inertia at the nose), mu = 0.0065/0.0317 =
#: 0.205, f_ring = 372.3/(1 + mu) = 308.9 Hz, k = J_ring (2 pi f_ring)^2.
RUBBER_STIFFNESS = 24500.0
STATION_DAMPING = 3.0  # N m s/rad per throw station: 1.5 per cylinder (Bell, Ricardo 2013)

_K_NOTE = (ASSUMPTION + ": seed I4 crank (403 kN m/rad per throw) scaled by journal and pin"
           " diameters^4, the 111.76 mm pitch and nodular iron's shear modulus (0.8 x steel)")


def _tv_rows(split: bool = False, link: float = 1e13) -> list[list[Any]]:
    """TVModel rows: one station per throw carrying both cylinders of its pin (``split``:
    two stations per throw, one per cylinder, joined by a ``link`` stiffness, half the
    inertia and damping each; the equivalent model used in the tests)."""
    rows: list[list[Any]] = [
        ["Damper ring", "damper ring", None, RING_INERTIA, None, RUBBER_STIFFNESS, None,
         ASSUMPTION + ": balancer inertia ring 0.0065 kg m^2, rubber Den Hartog tuned to"
         " 309 Hz = 372.3 Hz/(1 + 0.205); rubber damping from Damper loss factor"],
        ["Crank nose", "crank nose", None, NOSE_INERTIA, None, NOSE_STIFFNESS, None,
         ASSUMPTION + ": balancer hub, timing sprocket and nose; stiffness to throw 1 " + _K_NOTE
         [len(ASSUMPTION) + 2:]],
    ]
    for j in range(1, 5):
        a, b = 2 * j - 1, 2 * j
        k_next = SHAFT_STIFFNESS if j < 4 else REAR_STIFFNESS
        note = (ASSUMPTION + f": throw {j} with the rods of cylinders {a} and {b} (inertia from"
                " the CrankMass rows and both rods); absolute damping 1.5 N m s/rad per"
                " cylinder (Bell, Ricardo 2013); " + ("stiffness to the next throw " + _K_NOTE
                                           [len(ASSUMPTION) + 2:] if j < 4 else
                                           "stiffness to the flywheel: short rear flange"))
        if split:
            rows.append([f"Throw {j} cylinder {a}", "cylinder", a, THROW_INERTIA[j] / 2,
                         STATION_DAMPING / 2, link, None, note + "; split station"])
            rows.append([f"Throw {j} cylinder {b}", "cylinder", b, THROW_INERTIA[j] / 2,
                         STATION_DAMPING / 2, k_next, None, note + "; split station"])
        else:
            rows.append([f"Throw {j}", "cylinder", f"{a}, {b}", THROW_INERTIA[j],
                         STATION_DAMPING, k_next, None, note])
    rows.append(["Flywheel", "flywheel", None, FLYWHEEL_INERTIA, None, None, None,
                 ASSUMPTION + ": flywheel and clutch of a manual-transmission V8"])
    return rows


JOINTS = (
    JOINT_COLUMNS,
    [
        ["crank nose", "crank nose", 1, 16, 2.0, None, "10.9", "angle controlled", None, None,
         None, None, None, 30, 17, "steel", 46, 17, 0.15,
         ASSUMPTION + ": one M16x2 10.9 centre bolt, angle controlled (preload from the"
         " method table), clamping the balancer hub (face 46/17 mm, mu 0.15); the hub's"
         " press fit on the nose is not credited (bolt clamp friction only, the method of Bell,"
         " Ricardo 2013)"],
        ["flywheel", "flywheel", 6, 11, 1.5, None, "10.9", "torque", 110, 0.2, None, None, None,
         17, 11.5, "steel", 76, 45, 0.2,
         ASSUMPTION + ": 6 x M11x1.5 10.9 at 110 N m into the rear flange (76/45 mm face),"
         " steel flywheel; mu 0.2"],
    ],
)

JOINT_TORQUES = (JOINT_TORQUE_COLUMNS, [])
RULE_OVERRIDES = (RULE_OVERRIDE_COLUMNS, [])

NOTES = [
    "Example V8 gasoline workbook for checker: a 90-degree cross-plane V8 (GM LS1 5.7 L).",
    "Public data: GM Service Manual, Engine Mechanical Specifications, 5.7 L V8 RPO LS1: bore"
    " 99.0 mm, stroke 92.0 mm, firing order 1-8-7-2-6-5-4-3, crank-pin diameter 53.32 mm, rod"
    " and main bearing clearances (production).",
    "Two rods per crank pin (Cylinders 'crank pin'); one TVModel station per throw carrying"
    " both cylinders ('1, 2').",
    "Counterweights of a cross-plane crank: each web opposite its throw plus heavy end"
    " counterweights that cancel the rotating primary couple.",
    "Values marked ASSUMPTION are not in the sources and are stated in the report.",
    "See docs/workbook.md for every sheet, parameter and column.",
]

ASSUMED = {
    "Engine": [r[0] for r in ENGINE_ROWS if str(r[3]).startswith(ASSUMPTION)],
    "Oil": [r[0] for r in OIL_ROWS],
    "Damper": [r[0] for r in DAMPER_ROWS],
    "Fatigue": [r[0] for r in FATIGUE_ROWS],
    "Cylinders": ["cylinder numbering per bank and pin"],
    "PeakPressure": ["whole curve"],
    "BrakeTorque": ["whole curve"],
    "Bearings": ["main journal diameter and lengths, big-end lengths, linings, oil holes"],
    "CrankMass": ["all mass properties and axial positions"],
    "TVModel": ["all inertias, stiffnesses and damping"],
    "Joints": ["all joint data"],
}


TOLERANCES = (
    TOLERANCE_COLUMNS,
    [
        ["Bearings", "all", "radial clearance", -20, 20, "% of nominal",
         ASSUMPTION + ": production range of the radial clearance (journal and bore"
         " tolerances), +-20 % of the nominal clearance"],
        ["Oil", "", "Oil supply temperature", 100, 120, "°C",
         ASSUMPTION + ": gallery temperature range at full load"],
        ["Joints", "flywheel", "tightening factor", None, 1.6, "-",
         ASSUMPTION + ": tightening by torque wrench with estimated friction; VDI 2230"
         " Part 1 (2015), Table A8: alpha_A = 1.4..1.6, 1.6 taken"],
        ["PeakPressure", "all", "peak pressure", -3, 3, "% of nominal",
         ASSUMPTION + ": cycle-to-cycle and cylinder-to-cylinder scatter of the peak pressure"],
    ],
)


def v8_content(split_stations: bool = False, link: float = 1e13) -> dict[str, Any]:
    """The V8 workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``.

    ``split_stations=True`` models every throw by two TV stations (one per cylinder) joined by
    a stiffness ``link`` instead of one station carrying both cylinders.
    """
    return {
        "Engine": ENGINE_ROWS,
        "Cylinders": CYLINDERS,
        "PeakPressure": PEAK_PRESSURE,
        "BrakeTorque": BRAKE_TORQUE,
        "Bearings": BEARINGS,
        "CrankMass": CRANK_MASS,
        "Oil": OIL_ROWS,
        "TVModel": (TV_MODEL_COLUMNS, _tv_rows(split_stations, link)),
        "Damper": DAMPER_ROWS,
        "Fatigue": FATIGUE_ROWS + NOSE_ROWS,
        "Joints": JOINTS,
        "JointTorques": JOINT_TORQUES,
        "RuleOverrides": RULE_OVERRIDES,
        "Tolerances": TOLERANCES,
        "Notes": NOTES,
    }


__all__ = ["ASSUMED", "v8_content", "counterweights", "throw_unbalance"]
