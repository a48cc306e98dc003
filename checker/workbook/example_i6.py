"""A second example workbook: an inline six-cylinder truck diesel built from published data.

For benchmarks and stress tests, independent of the I4 gasoline example
(:mod:`checker.workbook.example`). :func:`i6_content` returns the same structure as
:func:`~checker.workbook.example.example_content` (same sheets and column headers) and is
written with :func:`~checker.workbook.example.write_workbook`.

Sources
-------
[MENDES] A. S. Mendes, P. S. Meirelles, D. E. Zampieri, "Analysis of torsional vibration in
    internal combustion engines: modelling and experimental validation", Proc. IMechE Part K,
    J. Multi-body Dynamics 222(2):155-178, 2008, doi:10.1243/14644193JMBD126. An MWM
    International six-cylinder diesel; the torsional model of its Fig. 4 and its measured and
    calculated vibratory torques (Figs 31 and 32).
[OT] Aalto-Arotor/openTorsion, ``examples/ICE_example.py`` with ``ICE_data/peak_data.csv`` and
    ``pressure_data.csv`` (MIT). It reproduces [MENDES]: inertias J2..J10 and stiffnesses
    k2..k9 of Fig. 4 **without** the damper inertia ring J1 and the rubber k1 (the code's own
    words: "crankshaft without torsional vibration damper"); J2 = crankshaft pulley, J3 = gear
    train, J4..J9 = cylinders 1..6, J10 = flywheel. Also bore 105 mm, stroke 137 mm, con-rod
    207 mm, reciprocating mass 2.521 kg, absolute damping 2 N m s/rad per cylinder, structural
    loss factor 0.035, the digitised peak-pressure curve (MPa against rpm), the digitised pressure
    trace, and, in ``opentorsion/examples/torsional_vibration_data_fig31.csv`` / ``fig32.csv``,
    the curves of [MENDES] Figs 31 and 32.
[MANUAL] "Workshop Manual MaxxForce 4.8/7.2 - Mechanical Injection", Group 08 (the MWM-built
    7.2 L family; that it is the engine of [MENDES] is inferred from 6 x 105 x 137 mm = 7.12 L
    and is itself an assumption): big-end bore with shells 63.015-63.031 mm and big-end
    clearance 0.026-0.081 mm.
[TORSION] free-free natural frequencies of the [OT] chain (an independent eigen-solution of
    the published J and k): 216.6 / 592.7 / 984.9 / 1171.0 / 1416.0 / 1660.0 / 1794.4 /
    2993.5 Hz.

What the sources do not give (bearings, crank mass properties, fillets, joints, oil, damper
rubber, brake torque...) is entered as a physically sound value for a ~7 L truck diesel, and its
note says ``ASSUMPTION`` with a one-line reason; :data:`ASSUMED` lists them.

Two deliberate choices
----------------------
* The TVModel chain is the published one (pulley, gear train, 6 cylinders, flywheel): there is
  no damper ring, since [MENDES]'s J1/k1 are not available. ``i6_content(damper_ring=True)``
  adds an ASSUMED rubber damper ring (Den Hartog tuning to the first mode) for damper checks.
* Throw angles follow the workbook convention ("from throw 1, in the direction of rotation",
  :func:`checker.calc.crank_forces.throw_angles`: gamma = -phi): with firing angles
  0/480/240/600/120/360 deg for cylinders 1..6 (order 1-5-3-6-2-4) the throws are
  0/240/120/120/240/0 deg (pairs 1&6, 2&5, 3&4). Measured against the rotation they are
  0/120/240/240/120/0 deg.
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

MENDES = "Mendes et al. 2008 (doi 10.1243/14644193JMBD126)"
OT = "openTorsion examples/ICE_example.py (reproduces Mendes et al. 2008)"
OT_PEAK = "Mendes et al. 2008 peak-pressure curve, digitised in openTorsion ICE_data/peak_data.csv"
MANUAL = "MaxxForce 4.8/7.2 Workshop Manual, Group 08"
ASSUMPTION = "ASSUMPTION"

# ---------------------------------------------------------------- published data
#: Reciprocating mass per cylinder [kg] ([OT] ``m_a``): piston assembly + rod small-end share.
RECIPROCATING_MASS = 2.521

#: Torsional chain of [MENDES] Fig. 4 without the damper ring, as in [OT]:
#: (station, role, cylinder, inertia [kg m^2], stiffness to next [N m/rad], [OT] name).
PUBLISHED_TV: list[tuple[str, str, int | None, float, float | None, str]] = [
    ("Pulley", "crank nose", None, 0.0170, 1.106e6, "J2, k2"),
    ("Gear train", "other", None, 0.0090, 1.631e6, "J3, k3"),
    ("Cylinder 1", "cylinder", 1, 0.0467, 1.253e6, "J4, k4"),
    ("Cylinder 2", "cylinder", 2, 0.0327, 1.253e6, "J5, k5"),
    ("Cylinder 3", "cylinder", 3, 0.0467, 1.678e6, "J6, k6"),
    ("Cylinder 4", "cylinder", 4, 0.0467, 1.253e6, "J7, k7"),
    ("Cylinder 5", "cylinder", 5, 0.0327, 1.253e6, "J8, k8"),
    ("Cylinder 6", "cylinder", 6, 0.0487, 1.976e6, "J9, k9"),
    ("Flywheel", "flywheel", None, 2.0750, None, "J10"),
]
#: Absolute damping at each cylinder station [N m s/rad] ([OT] ``c_a = 2``).
CYLINDER_ABSOLUTE_DAMPING = 2.0
#: Structural loss factor of the shaft elements ([OT] ``relative_damping_coefficient``).
SHAFT_LOSS_FACTOR = 0.035
#: First free-free natural frequency of the published chain [Hz] ([TORSION]).
FIRST_MODE_HZ = 216.6

#: Full-load peak cylinder pressure [MENDES] as digitised in [OT] ``peak_data.csv``
#: (digitised speeds 997.8, 1097.2, ... rounded to the nearest 100 rpm; MPa -> bar).
PEAK_PRESSURE_FULL: list[tuple[int, float]] = [
    (1000, 142.8), (1100, 142.8), (1200, 142.7), (1300, 140.6), (1400, 148.3), (1500, 148.3),
    (1600, 148.3), (1700, 149.6), (1800, 147.7), (1900, 147.7), (2000, 149.1), (2100, 149.0),
    (2200, 151.5), (2300, 134.8), (2400, 118.1),
]
#: End point of the same curve (digitised 2550.6 rpm, 5.88 MPa): high idle on the governor line.
PEAK_PRESSURE_END = (2550, 58.8)

#: Peaks of [MENDES] Fig. 31 (vibratory torque cylinder 6 - flywheel) and Fig. 32 (pulley - gear
#: train), digitised in [OT] torsional_vibration_data_fig31/32.csv: (speed [rpm], torque [N m]).
FIG31_PEAK = (2149.3, 9476.7)
FIG32_PEAK = (2148.1, 840.8)
#: The same curves at the rated speed 2200 rpm (linear between the digitised points).
FIG31_AT_2200 = 8530.5
FIG32_AT_2200 = 765.7

# ---------------------------------------------------------------- assumed values
RATED_SPEED = 2200  # rpm, ASSUMPTION: governor break point of the published curve
FEAD_TORQUE = 40.0  # N m, ASSUMPTION
_BRAKE = [(1000, 760), (1100, 820), (1200, 880), (1300, 900), (1400, 900), (1500, 900),
          (1600, 900), (1700, 895), (1800, 880), (1900, 865), (2000, 850), (2100, 830),
          (2200, 800), (2300, 655), (2400, 510), (2550, 0)]


def _brake_at(rpm: float) -> float:
    """Assumed brake torque [N m] at ``rpm`` (linear between the table points)."""
    for (n0, t0), (n1, t1) in zip(_BRAKE, _BRAKE[1:]):
        if n0 <= rpm <= n1:
            return t0 + (t1 - t0) * (rpm - n0) / (n1 - n0)
    raise ValueError(rpm)


# Crank geometry (ASSUMPTIONS, chosen so that the throw reproduces the published inertias)
_MAIN_D, _MAIN_L, _MAIN_EFF = 85.0, 38.0, 30.0
_PIN_D, _PIN_L, _PIN_EFF = 62.97, 40.0, 36.0
_SPACING = 130.0
_WEB_T = 25.0
_CRANK_R = 137.0 / 2

# ---------------------------------------------------------------- parameter sheets
ENGINE_ROWS: list[tuple[str, Any, str, str]] = [
    ("Engine name", "Example I6 truck diesel (MWM 6-cyl, Mendes et al. 2008)", "-", MENDES),
    ("Number of cylinders", 6, "-", MENDES),
    ("Engine class", "commercial vehicle", "-",
     MENDES + ": a truck diesel (the passenger-car TV targets of Bell 2013 do not apply)"),
    ("Layout", "inline", "-", MENDES),
    ("Bore", 105.0, "mm", OT + ": d_piston = 0.105 m"),
    ("Stroke", 137.0, "mm", OT + ": r = 0.137/2 m"),
    ("Connecting rod length", 207.0, "mm", OT + ": l_rod = 0.207 m"),
    ("Cylinder offset", 0.0, "mm", ASSUMPTION + ": no cylinder offset (usual for in-line diesels)"),
    ("Pin offset", 0.0, "mm", ASSUMPTION + ": no piston pin offset (usual for diesel pistons)"),
    ("Crankshaft rotation", "clockwise", "-",
     ASSUMPTION + ": clockwise seen from the front, the SAE standard rotation"),
    ("Firing order", "1-5-3-6-2-4", "-", OT + ": firing order index [0, 4, 2, 5, 1, 3]"),
    ("Cylinder spacing", _SPACING, "mm", ASSUMPTION + ": bore + 25 mm, room for"
     " a 38 mm main, two 25 mm webs and a 40 mm pin"),
    ("Main journal spacing", _SPACING, "mm", ASSUMPTION + ": one main between each cylinder"),
    ("Connecting rod mass", 2.9, "kg", ASSUMPTION + ": forged rod for a 105 mm bore; with piston"
     " mass and rod centre of mass it reproduces the published reciprocating mass 2.521 kg ("
     + OT + ")"),
    ("Rod centre of mass from big end", 58.0, "mm", ASSUMPTION + ": 0.28 x rod length (typical)"),
    ("Rod moment of inertia about centre of mass", 22600, "kg mm^2",
     ASSUMPTION + ": 0.9 x two-mass value m a b (the ratio of the Ricardo example rod)"),
    ("Piston assembly mass", 1.708, "kg", ASSUMPTION + ": published reciprocating mass 2.521 kg ("
     + OT + ") minus the rod small-end share 2.9 kg x 58/207"),
    ("Compression ratio", 17.0, "-", ASSUMPTION + ": typical turbocharged DI truck diesel"),
    ("Intake manifold pressure at full load", 2.67, "bar",
     MENDES + " pressure trace (openTorsion ICE_data/pressure_data.csv): 0.267 MPa absolute in"
     " the intake stroke; ASSUMPTION: read as the manifold pressure"),
    ("Rated speed", RATED_SPEED, "rpm", ASSUMPTION + ": governor break point of the published"
     " peak-pressure curve (peak pressure falls above 2200 rpm)"),
    ("Minimum speed", 1000, "rpm", OT + ": speed sweep 1000-2550 rpm (Mendes et al. 2008 range)"),
    ("Maximum speed", 2550, "rpm", OT_PEAK + ": last point 2550 rpm (high idle)"),
    ("Speed step", 25, "rpm", OT + ": np.arange(1000, 2575, 25)"),
    ("Overspeed", 2800, "rpm", ASSUMPTION + ": about 1.1 x high idle 2550 rpm"),
    ("Accessory drive torque at crank nose", FEAD_TORQUE, "N m",
     ASSUMPTION + ": truck FEAD (alternator, water pump, belt-driven fan drive)"),
]

OIL_ROWS = [
    ("Oil grade", "15W40", "-", ASSUMPTION + ": usual heavy-duty diesel grade (API CI-4)"),
    ("Kinematic viscosity at 40 °C", 105, "mm^2/s", ASSUMPTION + ": typical 15W-40 datasheet"),
    ("Kinematic viscosity at 100 °C", 14.5, "mm^2/s",
     ASSUMPTION + ": typical 15W-40 (SAE J300 band 12.5-16.3)"),
    ("Density at 15 °C", 880, "kg/m^3", ASSUMPTION + ": typical 15W-40 datasheet"),
    ("HTHS viscosity at 150 °C", 4.1, "mPa s", ASSUMPTION + ": typical 15W-40 (J300 min 3.7)"),
    ("Oil supply pressure", 4.5, "bar(g)", ASSUMPTION + ": gallery pressure of a truck diesel at"
     " rated speed (gauge)"),
    ("Oil supply temperature", 110, "°C", ASSUMPTION + ": gallery temperature at full load"),
    ("Film temperature rise", 10, "K", ASSUMPTION + ": moderate film heating at 63-85 mm"
     " journals"),
    ("Film temperature", "supply plus rise", "-", ASSUMPTION + ": supply plus rise (the"
     " default); 'heat balance' runs the film thickness at each bearing's balance temperature"),
    ("Heat fraction carried by the oil", 1.0, "-", ASSUMPTION + ": all bearing friction heat"
     " leaves with the oil (conservative; the default when blank)"),
]

DAMPER_ROWS = [
    ("Rubber loss factor", 0.4, "-", ASSUMPTION + ": high-damping damper elastomer"
     " tan(delta) (Den Hartog's optimum for mu = 0.42 would be about 0.6)"),
    ("Rubber inner radius", 110, "mm", ASSUMPTION + ": ILLUSTRATIVE heavy-duty ring geometry;"
     " with G' = 1.65 MPa it gives the assumed rubber stiffness 55.5 kN m/rad"),
    ("Rubber outer radius", 125, "mm", ASSUMPTION + ": ILLUSTRATIVE ring geometry"),
    ("Rubber axial length", 50, "mm", ASSUMPTION + ": ILLUSTRATIVE ring geometry"),
    ("Rubber shear stress limit", 0.5, "MPa", ASSUMPTION + ": ILLUSTRATIVE limit, replace with"
     " the damper supplier's value"),
    ("Rubber heat per unit volume limit", 0.5, "W/cm^3", ASSUMPTION + ": ILLUSTRATIVE limit,"
     " replace with the damper supplier's value"),
]

_STEEL = ASSUMPTION + ": 42CrMo4 +QT forging, induction-hardened fillets"
FATIGUE_ROWS = [
    ("Web reduced thickness", _WEB_T - 1.0, "mm", ASSUMPTION + ": full thickness - 2 x 0.5 mm"
     " lands"),
    ("Web full thickness", _WEB_T, "mm", ASSUMPTION + ": fits the 130 mm cylinder spacing"),
    ("Web minimum width", 105.0, "mm", ASSUMPTION + ": 1.67 x pin diameter (Ricardo example"
     " ratio)"),
    ("Web maximum width", 125.0, "mm", ASSUMPTION + ": 2 x pin diameter"),
    ("Web offset", 0, "mm", ASSUMPTION + ": symmetric web"),
    ("Crank pin fillet radius", 4.5, "mm", ASSUMPTION + ": 0.07 x pin diameter (M53 range"
     " 0.03-0.13)"),
    ("Crank pin fillet undercut", 0.5, "mm", ASSUMPTION + ": recessed fillet"),
    ("Crank pin fillet web undercut", 0, "mm", ASSUMPTION + ": none"),
    ("Main journal fillet radius", 4.5, "mm", ASSUMPTION + ": 0.053 x journal diameter"),
    ("Main journal fillet undercut", 0.5, "mm", ASSUMPTION + ": recessed fillet"),
    ("Main journal web undercut", 0, "mm", ASSUMPTION + ": none"),
    ("Pin journal oil hole diameter", 7.0, "mm", ASSUMPTION + ": 0.11 x pin diameter"),
    ("Pin journal oil hole height", round(_PIN_D / 2 * math.sin(math.radians(45)), 2), "mm",
     ASSUMPTION + ": pin radius x sin(45 deg), hole 45 deg leading (Bearings sheet)"),
    ("Main journal oil hole diameter", 7.0, "mm", ASSUMPTION + ": as the pin oil hole"),
    ("Main journal oil hole height", round(_MAIN_D / 2 * math.sin(math.radians(20)), 2), "mm",
     ASSUMPTION + ": journal radius x sin(20 deg)"),
    ("Pin journal land diameter", 78.0, "mm", ASSUMPTION + ": pin diameter + 15 mm"),
    ("Pin journal land thickness", 0.5, "mm", ASSUMPTION + ": as the Ricardo example"),
    ("Main journal land diameter", 100.0, "mm", ASSUMPTION + ": journal diameter + 15 mm"),
    ("Main journal land thickness", 0.5, "mm", ASSUMPTION + ": as the Ricardo example"),
    ("Pin bore diameter", 0, "mm", ASSUMPTION + ": solid pin"),
    ("Main journal bore diameter", 0, "mm", ASSUMPTION + ": solid journal"),
    ("Base material UTS", 950, "N/mm^2", _STEEL),
    ("Fillet UTS", 950, "N/mm^2", _STEEL + " (base value, hardening credited in the fatigue"
     " strengths)"),
    ("Base tensile yield strength", 700, "N/mm^2", _STEEL),
    ("Base compressive yield strength", 700, "N/mm^2", _STEEL),
    ("Base infinite life fatigue strength", 475, "N/mm^2", ASSUMPTION + ": 0.5 x base UTS"),
    ("Base hydrostatic fatigue strength", 688.75, "N/mm^2", ASSUMPTION + ": 2.5 x 275.5"
     " (Ricardo example rule)"),
    ("Base torsional fatigue strength", 275.5, "N/mm^2", ASSUMPTION + ": 0.58 x 475"),
    ("Fillet tensile and compressive yield", 1100, "N/mm^2", ASSUMPTION + ": induction-hardened"
     " fillet layer"),
    ("Pin fillet fatigue strength", 686, "N/mm^2", ASSUMPTION + ": 475 x 0.85 (size, 63 mm) x"
     " 1.7 (induction-hardened fillet)"),
    ("Pin oil hole fatigue strength", 404, "N/mm^2", ASSUMPTION + ": 475 x 0.85 x 1.0"),
    ("Main fillet fatigue strength", 670, "N/mm^2", ASSUMPTION + ": 475 x 0.83 (size, 85 mm) x"
     " 1.7 (induction-hardened fillet)"),
    ("Main oil hole fatigue strength", 394, "N/mm^2", ASSUMPTION + ": 475 x 0.83 x 1.0"),
]

# ---------------------------------------------------------------- table sheets
#: Firing angle after cylinder 1 [deg] (order 1-5-3-6-2-4, 120 deg apart).
FIRING_ANGLES = {1: 0, 2: 480, 3: 240, 4: 600, 5: 120, 6: 360}
#: Throw angle from throw 1 in the direction of rotation [deg]: gamma = -phi (mod 360).
THROW_ANGLES = {c: (-phi) % 360 for c, phi in FIRING_ANGLES.items()}

CYLINDERS = (
    CYLINDER_COLUMNS,
    [[c, THROW_ANGLES[c], FIRING_ANGLES[c], 0, c,
      OT + ": firing order 1-5-3-6-2-4 at 120 deg intervals; throw = -firing angle (mod 360)"]
     for c in range(1, 7)],
)

PEAK_PRESSURE = (
    [("load case", "-"), ("speed", "rpm"), ("peak pressure", "bar"), ("note", "")],
    [["full", n, p, OT_PEAK + " (absolute; speed rounded to 100 rpm)"]
     for n, p in PEAK_PRESSURE_FULL]
    + [["no", PEAK_PRESSURE_END[0], PEAK_PRESSURE_END[1],
        OT_PEAK + ": end point at high idle; ASSUMPTION: read as the no-load case"]],
)

BRAKE_TORQUE = (
    BRAKE_TORQUE_COLUMNS,
    [[n, t, ASSUMPTION + ": typical 7.2 L truck diesel curve (900 N m, 184 kW at 2200 rpm),"
      " IMEP ~19 bar of the published trace; 2300-2550 rpm scaled by the published"
      " peak-pressure drop to zero at high idle"] for n, t in _BRAKE],
)

_MAIN = ["main", _MAIN_D, _MAIN_L, _MAIN_EFF, 0.040, "partial", 5.0, 270, 90, "bearing", 0, None,
         None, None, "tri-metal"]
_PIN = ["big end", _PIN_D, _PIN_L, _PIN_EFF, 0.027, "none", None, None, None, "crank", 1,
        "leading", 7.0, 45, "sputter"]
_MAIN_NOTE = (ASSUMPTION + ": journal 85 mm (0.81 x bore, as 105-110 mm-bore truck diesels),"
              " effective length = 38 - 5 groove - 2 x 1.5 chamfers; radial clearance 0.040 mm"
              " (diametral 0.00094 x D); upper shell grooved; CuPb tri-metal lining")
_PIN_NOTE = (MANUAL + ": pin 62.950-62.989 mm (shell bore 63.015-63.031 minus clearance"
             " 0.026-0.081), radial clearance (0.026 + 0.081)/4 = 0.027 mm; ASSUMPTION: that the"
             " manual's 7.2 L engine is Mendes' engine, journal length 40 mm, 2 x 2 mm chamfers,"
             " sputter lining (usual for ~150 bar truck diesels), oil hole 7 mm at 45 deg leading")
BEARINGS = (
    BEARING_COLUMNS,
    [[f"M{i}", *_MAIN, *_NO_SUPPLIER_LIMITS, _MAIN_NOTE] for i in range(1, 8)]
    + [[f"BE{i}", *_PIN, *_NO_SUPPLIER_LIMITS, _PIN_NOTE] for i in range(1, 7)],
)

# Crank mass properties per throw (ASSUMPTIONS). Cylinders 2 and 5 carry 0.0140 kg m^2 less
# inertia than 1, 3, 4 in the published model: an 8-counterweight crank with no counterweights
# on throws 2 and 5 (2 x 1.65 kg x (58^2 + 30^2) mm^2 = 0.0141 kg m^2). With webs, pin, journal,
# rod and piston the point-mass estimate of a throw's inertia is ~0.048 (0.034 without
# counterweights) kg m^2 against the published 0.0467 (0.0327).
#
# Crank frame: Y along throw 1, Z +90 deg from Y in the direction of rotation (the lateral
# coordinate), X the axial offset of the centre of mass from the component's plane (0 for
# these symmetric webs). Each throw's own unbalance without counterweights (two webs and the
# pin) is U = 2 x 2.2 kg x 37.7 mm + 1.0 kg x 68.5 mm = 0.234 kg m along the throw.
#
# Counterweights: an in-line six's rotating masses are balanced (forces and couples) only when
# every throw carries the same unbalance (Taylor 1985, vol. 2, ch. 8); with counterweights on
# throws 1, 3, 4 and 6 only, counterweights directly opposite their own throws would leave
# 4 x 1.65 kg x 58 mm x |e(0) + e(120)| = 0.38 kg m of static unbalance. So, as the
# counterweights of a crank with counterweights on some throws only are laid out, the
# counterweight on each web next to an uncounterweighted throw (webs 2, 5, 8, 11, next to
# throws 2 and 5) also balances half of that neighbour throw: its unbalance vector is
# -c (e_own + e_neighbour) with c = 1.65 kg x 58 mm (the same magnitude, since the two throws
# are 120 deg apart: |e_own + e_neighbour| = 1), i.e. it is turned 60 deg toward the opposite
# of the neighbour throw. Each throw j then sees -c e_j from the two counterweights
# symmetric about its own plane (webs 2 and 5 about throw 2, 8 and 11 about throw 5), so every
# throw is balanced to the same fraction 2c/U = 82 % of its own unbalance, and the whole crank
# is statically and dynamically balanced.
_W_MASS, _W_R = 2.2, 37.7  # web arm: 110 x 100 x 25 mm steel, centre of mass 0.55 r
_CW_MASS, _CW_R = 1.65, 58.0  # counterweight: centre of mass 0.85 r
_PIN_MASS = 1.00  # pi/4 x 62.97^2 x 41 mm x 7850 kg/m^3
_CW_THROWS = (1, 3, 4, 6)
#: Web -> uncounterweighted neighbour throw whose half its counterweight also balances.
_CW_SHARED = {2: 2, 5: 2, 8: 5, 11: 5}
_W_FRONT = _MAIN_L / 2 + _WEB_T / 2
_W_REAR = _SPACING - _W_FRONT
_AX_NOTE = (ASSUMPTION + ": web centre at half main journal + half web (19 + 12.5 mm) from its"
            " main, pin at mid-bay")


def _zy(rho: float, gamma_deg: float) -> tuple[float, float]:
    """Crank-frame lateral and radial coordinates (Z, Y) of a point at radius ``rho`` along
    the direction ``gamma`` (from Y, in the direction of rotation)."""
    g = math.radians(gamma_deg)
    return round(rho * math.sin(g), 3) + 0.0, round(rho * math.cos(g), 3) + 0.0


def _cw_direction(web: int, throw: int) -> float:
    """Direction [deg] of a counterweight's centre of mass: opposite its throw, or opposite
    the bisector of its throw and the uncounterweighted neighbour throw (webs 2, 5, 8, 11)."""
    g = math.radians(THROW_ANGLES[throw])
    ex, ey = math.sin(g), math.cos(g)
    if web in _CW_SHARED:
        h = math.radians(THROW_ANGLES[_CW_SHARED[web]])
        ex, ey = ex + math.sin(h), ey + math.cos(h)
    return (math.degrees(math.atan2(-ex, -ey))) % 360


CRANK_MASS_ROWS: list[list[Any]] = []
for _t in range(1, 7):
    _g = THROW_ANGLES[_t]
    _wz, _wy = _zy(_W_R, _g)
    _wn = ASSUMPTION + f": 2.2 kg web arm, centre of mass {_W_R} mm along throw {_t}" \
                       f" ({_g} deg): Z = r sin, Y = r cos of the throw angle; {_AX_NOTE}"
    for _web, _ax in ((2 * _t - 1, _W_FRONT), (2 * _t, _W_REAR)):
        CRANK_MASS_ROWS.append([f"Web{_web}", _t, "web", _W_MASS, 0, _wy, _wz, _ax,
                                "main axis", _wn])
        if _t in _CW_THROWS:
            _d = _cw_direction(_web, _t)
            _cz, _cy = _zy(_CW_R, _d)
            _why = (f"turned to {_d:.0f} deg so that it also balances half of the"
                    f" uncounterweighted throw {_CW_SHARED[_web]}" if _web in _CW_SHARED
                    else f"opposite throw {_t} ({_d:.0f} deg)")
            CRANK_MASS_ROWS.append([
                f"Web{_web} c/w", _t, "counterweight", _CW_MASS, 0, _cy, _cz, _ax, "main axis",
                ASSUMPTION + ": 8-counterweight crank (published inertias of throws 2 and 5"
                f" are 0.014 kg m^2 lower); 1.65 kg at {_CW_R} mm, {_why}; the whole crank"
                f" statically and dynamically balanced; {_AX_NOTE}"])
        if _web % 2:
            CRANK_MASS_ROWS.append([f"Crankpin{_t}", _t, "pin", _PIN_MASS, 0, 0, 0,
                                    _SPACING / 2, "pin axis",
                                    ASSUMPTION + ": solid 62.97 x 41 mm steel pin; " + _AX_NOTE])
CRANK_MASS = (
    CRANK_MASS_COLUMNS,
    CRANK_MASS_ROWS,
)

#: Assumed rubber damper for ``damper_ring=True`` (the ``checker template --engine i6``
#: example): ring inertia [kg m^2] and rubber stiffness [N m/rad]. Mendes et al. 2008 fitted
#: their engine with a rubber and, alternatively, a viscous damper, but give the damper only as
#: J1/k1 of their Fig. 4 (k1 from a finite-element model of the rubber), values not in the
#: sources available here (the public re-implementation omits J1/k1). Sized instead as a
#: heavy-duty rubber damper by Den Hartog's rule: mu = J_d / J_eq = 0.06 / 0.1444 = 0.42
#: (J_eq = modal inertia of the first mode at the pulley), f_d = 216.6 / (1 + mu) = 153 Hz,
#: k_d = J_d (2 pi f_d)^2 = 55.5 kN m/rad (Den Hartog, Mechanical Vibrations, 1956, §3.3).
DAMPER_RING_INERTIA = 0.060
DAMPER_RUBBER_STIFFNESS = 55500.0


def _equivalent_viscous(k: float) -> float:
    """Viscous equivalent of the published loss factor at the first mode: c = eta k / omega_1."""
    return round(SHAFT_LOSS_FACTOR * k / (2 * math.pi * FIRST_MODE_HZ), 1)


_C_NOTE = ("; damping to next is an ASSUMPTION: viscous equivalent of the loss factor 0.035 ("
           + OT + ") at the first mode, c = 0.035 k / (2 pi 216.6 Hz)")


def _tv_rows(damper_ring: bool) -> list[list[Any]]:
    rows = []
    if damper_ring:
        rows.append(["Damper ring", "damper ring", None, DAMPER_RING_INERTIA, None,
                     DAMPER_RUBBER_STIFFNESS, None,
                     ASSUMPTION + ": Mendes et al. 2008 used a rubber (or viscous) damper but"
                     " its J1/k1 are not available; heavy-duty rubber damper, 0.060 kg m^2 ring"
                     " tuned to 153 Hz = 216.6/(1 + 0.42) (Den Hartog); rubber damping from the"
                     " Damper loss factor"])
    for station, role, cyl, j, k, name in PUBLISHED_TV:
        what = {"Pulley": "crankshaft pulley", "Gear train": "timing gear train",
                "Flywheel": "flywheel"}.get(station, station.lower())
        note = f"{OT}: {name} ({what})"
        absd = CYLINDER_ABSOLUTE_DAMPING if role == "cylinder" else None
        if absd is not None:
            note += "; absolute damping c_a = 2 N m s/rad (" + OT + ")"
        c = _equivalent_viscous(k) if k is not None else None
        if c is not None:
            note += _C_NOTE
        rows.append([station, role, cyl, j, absd, k, c, note])
    return rows


def _tv_model(damper_ring: bool) -> tuple[list, list]:
    return (
        TV_MODEL_COLUMNS,
        _tv_rows(damper_ring),
    )


JOINTS = (
    JOINT_COLUMNS,
    [
        ["crank nose", "crank nose", 6, 12, 1.5, None, "10.9", "torque", 145, 0.2, None, None,
         None, 19, 13, "steel", 110, 64, 0.2,
         ASSUMPTION + ": pulley hub on the crank-nose flange with 6 x M12x1.5 10.9 at 145 N m"
         " (F = T/(0.2 d) = 60 kN = 73 % of R_p0.2 A_s); face 110/64 mm; mu 0.2"],
        ["flywheel", "flywheel", 12, 16, 1.5, None, "12.9", "yield controlled", None, None,
         0.75, None, None, 24, 17, "grey cast iron", 160, 100, 0.2,
         ASSUMPTION + ": 12 x M16x1.5 12.9 yield-controlled into the rear flange (160/100 mm"
         " face), heads on the GJL flywheel; mu 0.2"],
    ],
)

_T_FW_PEAK = round(FIG31_PEAK[1] + _brake_at(FIG31_PEAK[0]))
_T_FW_RATED = round(FIG31_AT_2200 + _brake_at(RATED_SPEED))
_T_NOSE_PEAK = round(FIG32_PEAK[1] + FEAD_TORQUE)
_T_NOSE_RATED = round(FIG32_AT_2200 + FEAD_TORQUE)
JOINT_TORQUES = (
    JOINT_TORQUE_COLUMNS,
    [
        ["crank nose", "tv peak", round(FIG32_PEAK[0]), _T_NOSE_PEAK,
         MENDES + " Fig. 32 (pulley - gear train), digitised in openTorsion: 841 N m at 2148 rpm;"
         " + FEAD 40 N m (ASSUMPTION)"],
        ["crank nose", "max power", RATED_SPEED, _T_NOSE_RATED,
         MENDES + " Fig. 32 at 2200 rpm: 766 N m; + FEAD 40 N m (ASSUMPTION)"],
        ["flywheel", "tv peak", round(FIG31_PEAK[0]), _T_FW_PEAK,
         MENDES + " Fig. 31 (cylinder 6 - flywheel), digitised in openTorsion: 9477 N m at"
         f" 2149 rpm; + brake torque {_brake_at(FIG31_PEAK[0]):.0f} N m (ASSUMPTION)"],
        ["flywheel", "max power", RATED_SPEED, _T_FW_RATED,
         MENDES + " Fig. 31 at 2200 rpm: 8530 N m; + brake torque 800 N m (ASSUMPTION)"],
    ],
)

RULE_OVERRIDES = (
    RULE_OVERRIDE_COLUMNS,
    [],
)

NOTES = [
    "Example I6 truck diesel workbook for checker (benchmarks and stress tests).",
    "Source: A. S. Mendes, P. S. Meirelles, D. E. Zampieri, 'Analysis of torsional vibration in"
    " internal combustion engines: modelling and experimental validation', Proc. IMechE Part K"
    " 222(2):155-178, 2008, doi 10.1243/14644193JMBD126 (MWM International 6-cylinder diesel).",
    "Published numbers as reproduced by openTorsion (github.com/Aalto-Arotor/openTorsion,"
    " examples/ICE_example.py and its data files).",
    "Torsional chain: the published model; the damper ring (Mendes' J1, k1 are not"
    " available) is an ASSUMPTION when present (checker template --engine i6).",
    "Values marked ASSUMPTION are not in the sources and are stated in the report.",
    "See docs/workbook.md for every sheet, parameter and column.",
]

ASSUMED = {
    "Engine": ["Cylinder offset", "Pin offset", "Crankshaft rotation", "Cylinder spacing",
               "Main journal spacing", "Connecting rod mass", "Rod centre of mass from big end",
               "Rod moment of inertia about centre of mass", "Piston assembly mass",
               "Compression ratio", "Rated speed", "Overspeed",
               "Accessory drive torque at crank nose"],
    "Oil": [r[0] for r in OIL_ROWS],
    "Damper": [r[0] for r in DAMPER_ROWS],
    "Fatigue": [r[0] for r in FATIGUE_ROWS],
    "Bearings": ["main bearing geometry, clearance, groove", "big-end length, lining, oil hole",
                 "lining"],
    "CrankMass": ["all mass properties and axial positions"],
    "TVModel": ["damping to next (viscous equivalent of the loss factor)",
                "damper ring (only with damper_ring=True)"],
    "PeakPressure": ["2550 rpm end point read as the no-load case"],
    "BrakeTorque": ["whole curve"],
    "Joints": ["all joint data"],
    "JointTorques": ["FEAD torque and brake torque added to the published vibratory torques"],
}


TOLERANCES = (
    TOLERANCE_COLUMNS,
    [
        ["Bearings", "all", "radial clearance", -20, 20, "% of nominal",
         ASSUMPTION + ": production range of the radial clearance (journal and bore"
         " tolerances), +-20 % of the nominal clearance"],
        ["Oil", "", "Oil supply temperature", 100, 120, "°C",
         ASSUMPTION + ": gallery temperature range at full load"],
        ["Joints", "crank nose", "tightening factor", None, 1.6, "-",
         ASSUMPTION + ": tightening by torque wrench with estimated friction; VDI 2230"
         " Part 1 (2015), Table A8: alpha_A = 1.4..1.6, 1.6 taken"],
        ["PeakPressure", "all", "peak pressure", -3, 3, "% of nominal",
         ASSUMPTION + ": cycle-to-cycle and cylinder-to-cylinder scatter of the peak pressure"],
    ],
)


def i6_content(damper_ring: bool = False) -> dict[str, Any]:
    """The I6 diesel workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``.

    ``damper_ring=True`` puts an assumed rubber damper ring in front of the published chain.
    """
    return {
        "Engine": ENGINE_ROWS,
        "Cylinders": CYLINDERS,
        "PeakPressure": PEAK_PRESSURE,
        "BrakeTorque": BRAKE_TORQUE,
        "Bearings": BEARINGS,
        "CrankMass": CRANK_MASS,
        "Oil": OIL_ROWS,
        "TVModel": _tv_model(damper_ring),
        "Damper": DAMPER_ROWS,
        "Fatigue": FATIGUE_ROWS + NOSE_ROWS,
        "Joints": JOINTS,
        "JointTorques": JOINT_TORQUES,
        "RuleOverrides": RULE_OVERRIDES,
        "Tolerances": TOLERANCES,
        "Notes": NOTES,
    }


__all__ = ["ASSUMED", "i6_content"]
