"""First layout of a crank train from the concept brief: design rules with their sources (SI).

Each rule is a small pure function of the brief's numbers (bore, stroke, peak pressure...) and
states where it comes from in :data:`RULES` (``rule``: the formula in words, ``source``: the
publication, ``scatter``: the published range of the ratio, ``confirmed``: whether the ratio was
found stated in a public source; an unconfirmed ratio is a round value chosen here and says so).
The rules are tuned on published design ratios, never on the example engines; the docs
(docs/new-engine.md) table the sized dimensions against three real engines.

Main sources:

* Agostini, M., "Powertrain Components Design: Engine", course notes, Politecnico di Torino,
  A.Y. 2018-2019 ("Agostini 2019"): crankshaft "Design Guidelines" (main and pin diameters
  equal as a first approximation; journal lengths from the peak force and an admissible bearing
  pressure of about 18-25 MPa, ``L_pin = F/(d p_adm)``, ``L_main = F/(2 d p_adm)``), wrist pin
  "first attempt design" (length = bore, wall half the pin's bore: used where no service
  data was found), con-rod stem
  ``A = F S / R_p0.2`` (S = 1.5);
* Khurmi, R.S., Gupta, J.K., "A Textbook of Machine Design", S. Chand, §32.19 "Design
  procedure for crankshaft": web thickness 0.22-0.32 x bore (or 0.4-0.6 x shaft diameter);
* the machine-design textbook rule for a centre crankshaft at TDC, web width 1.14 x pin
  diameter (found stated only by public online design calculators; the textbook page, e.g.
  Bhandari, "Design of Machine Elements", not seen: marked unconfirmed);
* van Basshuysen, R., Schaefer, F., "Internal Combustion Engine Handbook" (2004/2010):
  crank radius / rod length 0.28-0.33 for car engines, diesels lower (as quoted by the German
  Wikipedia article "Pleuelstangenverhaeltnis"; the page was not seen);
* IACS UR M53 (Rev. 3, 2017): validity range of the fillet radius, r/d 0.03-0.13.

References
----------
.. [1] M. Agostini, "Powertrain Components Design - Engine", course notes, Politecnico di
   Torino, 2019, "Design Guidelines" (crankshaft): journal lengths from the peak force and an
   admissible bearing pressure of 18-25 MPa, equal pin and main diameters, the wrist pin.
.. [2] R. S. Khurmi, J. K. Gupta, "A Textbook of Machine Design", S. Chand, 2005, sec. 32.19
   (crank web thickness).
.. [3] R. van Basshuysen, F. Schaefer, "Internal Combustion Engine Handbook", SAE, 2004 (rod
   length ratio of car engines).
.. [4] J. P. Den Hartog, "Mechanical Vibrations", 4th ed., McGraw-Hill, 1956, sec. 3.3 (damper
   tuning).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

RULES: dict[str, dict] = {
    "peak_pressure": {
        "rule": "typical peak cylinder pressure by fuel: gasoline 85 bar, diesel 180 bar",
        "source": "no public source confirmed: round values of current production engines",
        "scatter": "gasoline 60-120 bar (turbocharged high), diesel 140-220 bar",
        "confirmed": False},
    "pin_diameter": {
        "rule": "crank-pin diameter from the rod bearing's specific load: d = sqrt(F / ((L/D)"
                " p_s)), F the worst pin force over the speed range (the peak gas force less"
                " the reciprocating inertia at the lowest speed, or the inertia of the"
                " reciprocating and rotating rod masses at TDC of gas exchange at the maximum"
                " speed), L/D the land's ratio by engine class (passenger car 0.45, heavier"
                " classes 0.50), p_s the lining's specific-load capacity (aluminium bimetal"
                " 44.5 MPa, tri-metal 66.5 MPa: the middle of the published ranges)",
        "source": "specific load p = F/(d L) (bearing load capacity: the lining ranges of"
                  " Clevite/CARS Magazine 2000, aluminium bimetal 41-48 MPa, cast CuPb tri-metal"
                  " > 83 MPa, and MTU/Detroit Diesel S1600 training, tri-metal 50 MPa); L/D"
                  " band of real crank pins from makers' service data (Ford, GM, Chrysler,"
                  " Toyota, Honda, Cummins and others, as reproduced by repair-manual sites)",
        "scatter": "pin diameter against 34 real engines' service data: 4.6 % median, 17 %"
                   " largest error", "confirmed": True},
    "main_diameter": {
        "rule": "main journal diameter = the larger of 1.20 x the crank-pin diameter and the"
                " main bearing's own specific-load diameter (the main's worst force: one"
                " cylinder's net gas force, or the inertia of every rod on the neighbouring pin"
                " at the maximum speed: both rods of a V engine's pin), L/D 0.35 (passenger"
                " car) or 0.40",
        "source": "main larger than the pin as in real engines (Agostini 2019's equal diameters"
                  " are a first approximation only); the ratio 1.20 is the median of the"
                  " makers' service data of 32 engines (1.04-1.33; Ford, GM, Chrysler, Toyota,"
                  " Honda, Cummins and others, as reproduced by repair-manual sites)",
        "scatter": "main/pin 1.04-1.33 in the service data", "confirmed": True},
    "journal_length": {
        "rule": "bearing land widths from the specific load p_s and the L/D band of real"
                " bearings: crank pin L = F_pin/(d p_s) per rod (= (L/D) d), main L ="
                " F_main/(d p_s) held within L/D 0.30-0.45 (passenger car) or 0.30-0.55;"
                " journal length = land + 2 (fillet radius + 1 mm chamfer)",
        "source": "specific load p = F/(d L) with the lining capacities above; L/D bands of"
                  " real car mains about 0.3-0.45 (makers' service data); the"
                  " land-to-journal allowance is not from a source",
        "scatter": "L/D of real pins 0.35-0.60, mains 0.30-0.55", "confirmed": True},
    "fillet_radius": {
        "rule": "fillet radius = 0.04 x journal diameter",
        "source": "inside the validity range of IACS UR M53 (r/d 0.03-0.13); the value itself"
                  " is not from a source",
        "scatter": "0.03-0.13 x d (M53 validity range)", "confirmed": False},
    "web_thickness": {
        "rule": "web thickness = 0.27 x bore (middle of 0.22-0.32)",
        "source": "Khurmi & Gupta, A Textbook of Machine Design, §32.19",
        "scatter": "0.22-0.32 x bore (+-19 %)", "confirmed": True},
    "web_width": {
        "rule": "web width = 1.14 x crank-pin diameter (at the pin and at the journal)",
        "source": "the machine-design textbook rule for a centre crankshaft at TDC (w = 1.14"
                  " d_c, t = 0.7 d_c), found stated only by public online design calculators;"
                  " the textbook page (e.g. Bhandari, Design of Machine Elements) not seen",
        "scatter": "not stated", "confirmed": False},
    "rod_length": {
        "rule": "rod length = crank radius / lambda, lambda = 0.30 (passenger car, inside"
                " 0.28-0.33) or 0.31 (commercial vehicle, industrial, marine)",
        "source": "van Basshuysen & Schaefer, Internal Combustion Engine Handbook (as quoted by"
                  " Wikipedia 'Pleuelstangenverhaeltnis'; page not seen)",
        "scatter": "lambda 0.28-0.33 (+-8 %)", "confirmed": True},
    "wrist_pin": {
        "rule": "wrist pin outer diameter 0.243 x bore (gasoline) or 0.356 x bore (diesel),"
                " length 0.685 x bore (gasoline) or = bore (diesel), bore 0.5 x its outer"
                " diameter (wall half the bore); steel",
        "source": "outer diameter and gasoline length: medians of makers' service data as"
                  " reproduced by repair-manual sites (18 gasoline engines: Ford, Chrysler,"
                  " Nissan, GM, Cadillac, Mazda, Suzuki; 7 diesels: Cummins, GM Duramax,"
                  " Isuzu, Caterpillar, Detroit Diesel; 5 published gasoline pin lengths);"
                  " diesel length and the wall: Agostini 2019, wrist pin 'First attempt"
                  " design' (length = bore, thickness 50 % of the inner diameter)",
        "scatter": "outer/bore 0.229-0.264 (gasoline), 0.333-0.438 (diesel); length/bore"
                   " 0.648-0.785 (gasoline); no published inner diameter or diesel length",
        "confirmed": True},
    "piston_mass": {
        "rule": "piston (with rings, without pin) = K D^3, apparent density K = 0.5 g/cm^3"
                " (gasoline) or 1.0 g/cm^3 (diesel); plus the wrist pin",
        "source": "method: Agostini 2019, piston 'Design Guidelines' (K = W/D^3); gasoline K:"
                  " the published piston weights of three Chrysler engines (2.4 I4, 3.5 V6,"
                  " 4.7 V8 service data) give 0.46-0.58 g/cm^3; the diesel K is not from a"
                  " source",
        "scatter": "gasoline 0.46-0.58 g/cm^3 (3 engines); diesel unknown",
        "confirmed": False},
    "rod_mass": {
        "rule": "steel rod: stem of section A = F S / R_p0.2 (S = 1.5, R_p0.2 = 600 MPa) over"
                " the eye-to-eye length, big and small eyes as rings of wall 0.15 x their bore"
                " and the bearing's width, all x 1.30 for bolts, shells, bushes and bosses",
        "source": "stem: Agostini 2019, con-rod 'Design Guidelines - Stem'; the 1.30: the"
                  " median ratio of two published rod weights (Chrysler 2.4 I4 565.8 g and"
                  " 4.7 V8 555 g less bearing, service data) to the bare rule; the eye walls"
                  " are not from a source",
        "scatter": "+-3 % on the two rods it was set on; Bell 2013's I4 rod (597 g with bolts"
                   " and shells) -14 %",
        "confirmed": False},
    "rod_centre": {
        "rule": "rod centre of mass from the big end: the centroid of the stem and eye masses;"
                " inertia about it: the two-mass equivalent m a b (no inertia correction)",
        "source": "two-mass con-rod model (Agostini 2019, 'Forces on the Connecting Rod')",
        "scatter": "the real inertia is 5-15 % below m a b", "confirmed": True},
    "counterweight": {
        "rule": "each throw balanced within itself: the two counterweights (annular sectors of"
                " 150 deg from the journal radius, web thickness; 180 deg, then up to 2 x the web"
                " thickness, thicker by at most 0.9 x the pin or journal length, where needed)"
                " balance 100 % of the throw's"
                " rotating unbalance (pin, webs, rods' rotating share); a 90-degree V also"
                " its cylinder pair's primary reciprocating force m_rec R w^2 (a constant"
                " rotating vector)",
        "source": "target chosen here (full in-throw balance: no rotating couple, least"
                  " internal bending); the 90-degree V result is classical balancing theory;"
                  " swing radius limit rod length - crank radius - 0.25 bore [not confirmed]",
        "scatter": "industrial practice 50-100 % of the rotating unbalance", "confirmed": False},
    "cylinder_damping": {
        "rule": "absolute viscous damping at each cylinder (piston, rings and bearings, to a"
                " node turning at the mean speed): passenger cars 1.5 N m s/rad at an 86 mm"
                " bore, heavier classes 2.0 N m s/rad at a 105 mm bore, scaled by (bore /"
                " that bore)^4 (the modal damping ratio of a geometrically similar engine);"
                " a V engine's throw carries two",
        "source": "Bell, D., 'Cranktrain Analysis Using ENGDYN and VALDYN', Ricardo workshop,"
                  " 2013 (the 2.0 l I4: 1.5 N m s/rad at each cylinder); Mendes, Meirelles and"
                  " Zampieri, 'Analysis of torsional vibration in internal combustion engines',"
                  " Proc. IMechE Part K 222, 2008 (6-cylinder 105 mm truck diesel, 2 N m s/rad,"
                  " validated against measured torque); the bore scaling is not from a source",
        "scatter": "the two published values, scaled to one bore, differ by 1.7 x (the lower,"
                   " diesel value for the heavier classes: less damping, higher resonances)",
        "confirmed": False},
}


def peak_pressure(fuel: str) -> float:
    """Typical peak cylinder pressure [Pa] by fuel (:data:`RULES` ``peak_pressure``)."""
    return {"gasoline": 85e5, "diesel": 180e5}[fuel]


def peak_gas_force(bore: float, p_max: float) -> float:
    """Peak gas force on the piston [N]: ``F = p_max pi D^2 / 4`` (gauge pressure taken as
    absolute: conservative by 0.1 MPa)."""
    return p_max * math.pi * bore**2 / 4.0


def resultant_force(gas: float, m_rec: float, crank_radius: float, rod_length: float,
                    speed: float) -> float:
    """Resultant force along the piston axis at TDC [N] (Agostini 2019's ``F`` for the
    journal lengths): the peak gas force less the reciprocating inertia force
    ``m_rec R w^2 (1 + R/l)`` at ``speed`` (the gas peak taken at TDC: conservative by the
    few degrees after TDC where it occurs); at least half the gas force.

    >>> round(resultant_force(49.4e3, 0.9, 0.0473, 0.155, 628.3) / 1e3, 1)
    27.5
    """
    inertia = m_rec * crank_radius * speed**2 * (1.0 + crank_radius / rod_length)
    return max(gas - inertia, 0.5 * gas)


CLASSES: dict[str, dict[str, Any]] = {
    "passenger car": {"pin_ld": 0.45, "shared_ld": 0.40, "main_ld": 0.35,
                      "main_ld_band": (0.30, 0.45),
                      "pin_ld_band": (0.30, 0.60), "lambda": 0.30, "pitch_wall": 0.06,
                      "pitch_band": (1.05, 1.35), "web_band": (0.18, 0.34),
                      "pin_bore_band": (0.50, 0.64), "main_bore_band": (0.55, 0.83),
                      "mode_band": (250.0, 1500.0), "irregularity": 0.20},
    "commercial vehicle": {"pin_ld": 0.50, "shared_ld": 0.45, "main_ld": 0.40,
                           "main_ld_band": (0.30, 0.55),
                           "pin_ld_band": (0.35, 0.70), "lambda": 0.31, "pitch_wall": 0.11,
                           "pitch_band": (1.10, 1.45), "web_band": (0.18, 0.36),
                           "pin_bore_band": (0.53, 0.75), "main_bore_band": (0.71, 0.87),
                           "mode_band": (120.0, 900.0), "irregularity": 0.20},
}
CLASSES["industrial"] = CLASSES["commercial vehicle"]
CLASSES["marine"] = CLASSES["commercial vehicle"]
"""Sizing ratios and plausibility bands by engine class (the Engine sheet's classes):

* ``pin_ld``, ``main_ld``: land L/D the diameters are sized with; ``shared_ld``: each rod's land
  on a pin shared by two rods (V engines), narrower as in the service data (the Cadillac 4.4
  V8: two rods on 43.9 mm of a 54 mm pin), its specific load that much higher;
  ``*_ld_band``: the band of real bearings (service data, docs/new-engine.md) the lands are
  held in;
* ``lambda``: crank radius / rod length (van Basshuysen & Schaefer: 0.28-0.33 for cars);
* ``pitch_wall``: the cylinder wall and water jacket between two bores, per side, as a fraction
  of the bore (pitch >= bore (1 + 2 wall)) [not confirmed in a public source];
* ``pitch_band``, ``web_band``: cylinder pitch and web thickness per bore of real engines
  (plausibility; web: Khurmi & Gupta's 0.22-0.32 widened by the service data);
* ``pin_bore_band``, ``main_bore_band``: crank-pin and main journal diameters per bore of
  real engines (the service data of docs/new-engine.md, 34 engines: gasoline pins
  0.525-0.618 and mains 0.568-0.809 x bore, diesel pins 0.555-0.727 and mains 0.733-0.853 x
  bore), widened by about 0.02 at each end; the sizing loop keeps its journals inside them;
* ``mode_band``: first crank torsional mode [Hz] plausible for the class [not confirmed];
* ``irregularity``: the cyclic irregularity the flywheel is sized for at the lowest speed,
  full load (a four-cylinder at 800 rpm idle turns between about 710 and 860 rpm, 19 %: J.
  Venter, "Doing the twist", CAR magazine) [one measurement, not a standard]."""

LINING_CAPACITY = {"aluminium bimetal": 44.5e6, "AS15": 44.5e6, "AS16": 44.5e6,
                   "tri-metal": 66.5e6, "polymer": 95e6, "sputter": 110e6}
"""Specific-load capacity of bearing linings [Pa], the middle of the published ranges:
aluminium bimetal 41-48 MPa and cast CuPb tri-metal > 83 MPa (Clevite, CARS Magazine 2000),
tri-metal 50 MPa (MTU/Detroit Diesel S1600 training); polymer up to 95 MPa (MAHLE 2012);
sputter 100-120 MPa (substech.com)."""

SIZING_LOAD = {"gasoline": 44.5e6, "diesel": 66.5e6}
"""The specific load the journal diameters are sized for [Pa]: the capacity of the usual lining
of the fuel (aluminium bimetal for gasoline, tri-metal for diesel engines, LINING_CAPACITY);
a stronger lining chosen in the brief is margin, not a smaller journal."""

GASOLINE_FULL_LOAD = (
    # speed / rated speed, brake torque / peak torque, peak pressure / its maximum
    (1000 / 6000, 175 / 265, 53.4 / 84.4), (1500 / 6000, 200 / 265, 59.0 / 84.4),
    (2000 / 6000, 245 / 265, 68.1 / 84.4), (2500 / 6000, 255 / 265, 73.6 / 84.4),
    (3000 / 6000, 265 / 265, 77.1 / 84.4), (4000 / 6000, 265 / 265, 80.0 / 84.4),
    (5000 / 6000, 265 / 265, 84.4 / 84.4), (6000 / 6000, 220 / 265, 79.8 / 84.4),
    (6500 / 6000, 190 / 265, 73.3 / 84.4))
"""Full-load curves of a gasoline engine made dimensionless: brake torque and peak cylinder
pressure against speed of the production gasoline I4 of Bell, D., "Cranktrain Analysis Using
ENGDYN and VALDYN", Ricardo workshop, 2013 (rated at 6000 rpm; peak pressure 84.4 bar at
5000 rpm, 53.4 bar at 1000 rpm: knock-limited at low speed, the peak pressure falls faster
than the torque). ``checker new`` scales them to a gasoline brief's rated point and peak
pressure; outside their speed range the end values hold (stated in the sheet's notes)."""


def full_load_shape(speed_ratio: float) -> tuple[float, float]:
    """Brake torque / peak torque and peak pressure / its maximum at ``speed_ratio`` = speed /
    rated speed (:data:`GASOLINE_FULL_LOAD`, linear between its points, its end values
    outside them).

    >>> [round(x, 3) for x in full_load_shape(1000 / 6000)]
    [0.66, 0.633]
    """
    x = [r[0] for r in GASOLINE_FULL_LOAD]
    t = [r[1] for r in GASOLINE_FULL_LOAD]
    p = [r[2] for r in GASOLINE_FULL_LOAD]

    def interp(ys: list[float]) -> float:
        if speed_ratio <= x[0]:
            return ys[0]
        if speed_ratio >= x[-1]:
            return ys[-1]
        k = next(i for i in range(1, len(x)) if x[i] >= speed_ratio)
        w = (speed_ratio - x[k - 1]) / (x[k] - x[k - 1])
        return ys[k - 1] + w * (ys[k] - ys[k - 1])

    return interp(t), interp(p)


MAIN_PIN_MIN = 1.04
"""Smallest main journal / crank-pin diameter ratio the sizing loop keeps: the low end of
the service data tabled in docs/new-engine.md (1.04, the Ford 2.3 Duratec I4)."""

MAIN_PIN_RATIO = 1.20
"""Main journal / crank-pin diameter: median of the service data tabled in docs/new-engine.md
(32 engines, 1.04-1.33; median 1.20)."""


def engine_class(fuel: str, bore: float) -> str:
    """The engine class when the brief gives none: gasoline a passenger car; diesel below 95 mm
    bore a passenger car, to 200 mm a commercial vehicle, above marine [boundaries not
    confirmed]."""
    if fuel == "gasoline":
        return "passenger car"
    return "marine" if bore >= 0.2 else ("commercial vehicle" if bore >= 0.095
                                         else "passenger car")


def sizing_forces(*, gas: float, m_rec: float, m_rot: float, crank_radius: float,
                  rod_length: float, min_speed: float, max_speed: float, rods: int = 1,
                  bank_angle: float = 0.0) -> tuple[float, float]:
    """Worst crank-pin and main-bearing forces over the speed range [N].

    Pin: the larger of the peak gas force less the reciprocating inertia
    ``m_rec R w^2 (1 + R/l)`` at the lowest speed and the inertia at TDC of gas exchange at the
    maximum speed, ``(m_rec (1 + R/l) + m_rot) R w^2`` (the big end carries the rod's rotating
    share too). Main: the larger of the same net gas force (one cylinder fires at a time) and
    the inertia of every rod on the neighbouring pin at the maximum speed: ``rods m_rot R w^2
    + m_rec R w^2 (1 + R/l) (1 + (rods - 1) |cos bank|)`` (both rods of a V engine's pin;
    counterweights neglected: conservative). Crank-slider inertia (Agostini 2019).

    >>> [round(f / 1e3, 1) for f in sizing_forces(gas=49.4e3, m_rec=0.9, m_rot=0.45,
    ...     crank_radius=0.0473, rod_length=0.155, min_speed=104.7, max_speed=733.0)]
    [48.8, 48.8]
    """
    lam = crank_radius / rod_length
    gas_net = gas - m_rec * crank_radius * min_speed**2 * (1.0 + lam)
    w2r = crank_radius * max_speed**2
    pin_in = (m_rec * (1.0 + lam) + m_rot) * w2r
    main_in = rods * m_rot * w2r + m_rec * w2r * (1.0 + lam) * (
        1.0 + (rods - 1) * abs(math.cos(bank_angle)))
    return max(gas_net, pin_in), max(gas_net, main_in)


def pin_diameter(force: float, p_s: float, ld: float) -> float:
    """Crank-pin diameter [m] from the specific load ``p = F/(d L)`` with ``L = ld d``:
    ``d = sqrt(F / (ld p_s))`` (:data:`RULES` ``pin_diameter``).

    >>> round(pin_diameter(65.4e3, 44.5e6, 0.45) * 1e3, 1)
    57.1
    """
    if not (force > 0 and p_s > 0 and ld > 0):
        raise ValueError("force, p_s and ld must be > 0")
    return math.sqrt(force / (ld * p_s))


def main_diameter(pin_d: float, force: float, p_s: float, ld: float) -> float:
    """Main journal diameter [m]: the larger of :data:`MAIN_PIN_RATIO` x the pin and the main's
    own specific-load diameter ``sqrt(F / (ld p_s))`` (:data:`RULES` ``main_diameter``)."""
    return max(MAIN_PIN_RATIO * pin_d, pin_diameter(force, p_s, ld))


def main_land(force: float, diameter: float, p_s: float, band: tuple[float, float]) -> float:
    """Main bearing land [m]: ``F/(d p_s)`` held within the class's L/D band."""
    return min(max(force / (diameter * p_s), band[0] * diameter), band[1] * diameter)


def cylinder_pitch(bore: float, stack: float, wall: float) -> float:
    """Cylinder pitch [m]: the larger of the bore's (bore + two walls and water jackets,
    ``bore (1 + 2 wall)``) and the crank's axial stack (main journal + two webs + pin);
    the caller widens the crank to fill the pitch."""
    return max(bore * (1.0 + 2.0 * wall), stack)


def land_length(force: float, diameter: float, p_adm: float = 21.5e6,
                share: float = 1.0) -> float:
    """Loaded land length [m] ``L = share F / (d p_adm)`` (Agostini 2019; ``share`` = 1 for a
    rod bearing, 0.5 for a main bearing). Agostini's admissible pressure is about 18-25 MPa;
    another value (a brief's ``bearing_pressure``) is the user's, stated by the caller."""
    if not p_adm > 0:
        raise ValueError("p_adm must be > 0")
    return share * force / (diameter * p_adm)


def fillet_radius(diameter: float) -> float:
    """Fillet radius [m] = 0.04 d (inside IACS UR M53's r/d 0.03-0.13)."""
    return 0.04 * diameter


def web_thickness(bore: float) -> float:
    """Web thickness [m] = 0.27 x bore (Khurmi & Gupta §32.19: 0.22-0.32 x bore)."""
    return 0.27 * bore


def web_width(pin_d: float) -> float:
    """Web width [m] = 1.14 x pin diameter (Bhandari)."""
    return 1.14 * pin_d


def rod_length(stroke: float, cls: str) -> float:
    """Rod length [m] = (stroke / 2) / lambda, lambda by engine class (:data:`CLASSES`)."""
    return stroke / 2.0 / CLASSES[cls]["lambda"]


CYLINDER_DAMPING = {"passenger car": (1.5, 0.086), "commercial vehicle": (2.0, 0.105)}
"""Published absolute damping per cylinder [N m s/rad] and the bore it was given for [m]
(:data:`RULES` ``cylinder_damping``)."""


def cylinder_damping(bore: float, cls: str) -> float:
    """Absolute viscous damping of one cylinder [N m s/rad] for a bore [m].

    ``c = c_0 (B / B_0)^4``, ``(c_0, B_0)`` the published value of the class (Bell, Ricardo
    2013: 1.5 N m s/rad at 86 mm, passenger car; Mendes et al. 2008: 2.0 N m s/rad at 105 mm,
    truck diesel, for the heavier classes); the fourth power keeps the modal damping ratio
    ``c / (2 omega J)`` of a geometrically similar engine (inertia ~ length^5, natural
    frequency ~ 1/length), as the genset example scales the I6's damping [not from a source].

    >>> round(cylinder_damping(0.086, "passenger car"), 3)
    1.5
    >>> round(cylinder_damping(0.21, "marine"), 1)
    32.0
    """
    c0, b0 = CYLINDER_DAMPING.get(cls, CYLINDER_DAMPING["commercial vehicle"])
    if bore <= 0.0:
        raise ValueError(f"bore must be positive, got {bore!r} m")
    return c0 * (bore / b0) ** 4


STEEL_DENSITY = 7850.0


@dataclass(frozen=True)
class WristPin:
    outer: float
    inner: float
    length: float
    mass: float


#: Wrist pin outer diameter / bore by fuel: medians of makers' service data (RULES["wrist_pin"]).
WRIST_PIN_OUTER = {"gasoline": 0.243, "diesel": 0.356}
#: Wrist pin length / bore by fuel: gasoline the median of five published pins, diesel
#: Agostini 2019's first attempt (no published diesel length found).
WRIST_PIN_LENGTH = {"gasoline": 0.685, "diesel": 1.0}


def wrist_pin(bore: float, fuel: str = "gasoline") -> WristPin:
    """Wrist pin from the bore and fuel (:data:`RULES` ``wrist_pin``).

    Outer diameter ``0.243 D`` (gasoline) or ``0.356 D`` (diesel), the medians of makers'
    service data; length ``0.685 D`` (gasoline, median of five published pins) or ``D``
    (diesel: Agostini 2019's first attempt); bore half the outer diameter (Agostini 2019:
    wall thickness 50 % of the inner diameter); steel.

    >>> round(wrist_pin(0.086).mass, 3)  # an 86 mm gasoline bore: 20.9 x 10.4 x 58.9 mm
    0.119
    """
    do = WRIST_PIN_OUTER[fuel] * bore
    di = 0.5 * do
    length = WRIST_PIN_LENGTH[fuel] * bore
    m = STEEL_DENSITY * math.pi / 4.0 * (do**2 - di**2) * length
    return WristPin(do, di, length, m)


def piston_mass(bore: float, fuel: str) -> float:
    """Piston with rings, without pin [kg] = K D^3, K 500 (gasoline) or 1000 kg/m^3 (diesel)."""
    return (500.0 if fuel == "gasoline" else 1000.0) * bore**3


@dataclass(frozen=True)
class Rod:
    mass: float
    centre_from_big_end: float
    inertia: float
    stem_area: float


#: Con-rod mass over the bare stem and eyes: bolts, shells, bushes, the big end's bolt bosses
#: and the stem's flanges, set so the rule meets the published weights of two production rods
#: (RULES["rod_mass"]).
ROD_ALLOWANCE = 1.30


def con_rod(*, force: float, length: float, pin_d: float, pin_land: float,
            wrist: WristPin, rp02: float = 600e6, safety: float = 1.5) -> Rod:
    """Steel con-rod (:data:`RULES` ``rod_mass``/``rod_centre``): stem ``A = F S / R_p0.2``
    (Agostini 2019), eyes as rings of wall 0.15 x their bore, all x :data:`ROD_ALLOWANCE`
    (bolts, shells, bushes, bosses); centre of mass the centroid; inertia m a b (two-mass
    equivalent)."""
    area = force * safety / rp02
    r_be, r_se = pin_d / 2.0, wrist.outer / 2.0
    t_be, t_se = 0.15 * pin_d, 0.15 * wrist.outer
    w_se = 0.5 * wrist.length  # small eye between the piston bosses: half the pin length
    k = ROD_ALLOWANCE
    m_be = k * STEEL_DENSITY * math.pi * ((r_be + t_be)**2 - r_be**2) * pin_land
    m_se = k * STEEL_DENSITY * math.pi * ((r_se + t_se)**2 - r_se**2) * w_se
    stem_len = max(length - (r_be + t_be) - (r_se + t_se), 0.2 * length)
    m_st = k * STEEL_DENSITY * area * stem_len
    m = m_be + m_se + m_st
    z_st = r_be + t_be + stem_len / 2.0
    a = (m_se * length + m_st * z_st) / m
    return Rod(m, a, m * a * (length - a), area)
