"""Class-society limits of crankshaft torsional vibration: permissible vibratory shear stress
against the speed ratio, the material factor, barred speed ranges and major criticals.

Source (the only class text with crankshaft limits read for this module): Korean Register of
Shipping, *Rules for the Classification of Steel Ships*, Part 5 *Machinery Installations*,
Chapter 4 *Torsional Vibration of Shaftings*, 2025 (RA-05-E), Section 2 (201 crankshafts of
main engines, 203 generator engines, 204 major criticals, 206 barred speed ranges). The
nominal stress these limits judge is the half range of the synthesised vibratory torque over
the polar section modulus of the crank pin or journal, ``tau = M_TN / W_P`` (IACS UR M53,
Rev. 4, 2019, 2.2(A)(e), as carried in KR Part 5 Annex 5-3).

All stresses in Pa (the rules' N/mm^2 times 1e6), speeds in rad/s, the speed ratio
``lambda = n / n_MCR`` dimensionless (``n_MCR``: maximum continuous, rated, speed).

References
----------
.. [1] Korean Register of Shipping, "Rules for the Classification of Steel Ships", Part 5
   "Machinery Installations", Chapter 4 "Torsional Vibration of Shaftings", 2025 (RA-05-E),
   Section 2: 201, 203, 204, 206.
.. [2] IACS, "Calculation of Crankshafts for I.C. Engines", Unified Requirement M53, Rev. 4,
   2019, 2.2(A)(e).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._checks import finite, positive

MPA = 1e6
TS_REFERENCE = 440e6
"""Tensile strength above which KR Pt 5 Ch 4 201.4 lets tau_1 and tau_3 grow [Pa]."""
YIELD_REFERENCE = 225e6
"""Yield strength above which KR Pt 5 Ch 4 201.4 lets tau_2 grow [Pa]."""
TS_CAP_CARBON = 590e6
"""KR Pt 5 Ch 4 201.4: a tensile strength above 590 N/mm^2 (carbon-steel forgings) or 835
N/mm^2 (low-alloy forgings) enters f_m only "as deemed appropriate by the Society" [Pa]."""
TS_CAP_LOW_ALLOY = 835e6
GROUPS = ("A", "B")
"""Engine groups of KR Pt 5 Ch 4 201.1: A = 4-stroke in-line engines and 4-stroke V engines
with firing intervals of 45 or 60 deg; B = 2-stroke engines and the other 4-stroke V
engines."""
_PROPULSION_SLOPE = {"A": 24.0, "B": 29.0}  # tau_1 = 45 - c lambda^2 [N/mm^2]
_OVERSPEED_BASE = {"A": 21.0, "B": 16.0}  # tau_3 = b + 237 (lambda - 0.8) sqrt(lambda - 1)
_GENERATOR_CONTINUOUS = {"A": 21.0, "B": 16.0}  # 203.1(1), 0.9 <= lambda <= 1.1
GENERATOR_TRANSIENT = 90e6
"""KR Pt 5 Ch 4 203.1(2): transient limit of a generator engine's crankshaft, lambda <= 0.9
[Pa]."""
PROPULSION_TRANSIENT_TOP = 0.8
"""KR Pt 5 Ch 4 201.2: tau_2 = 2 tau_1 applies up to and at 80 % of the MCR speed."""
OVERSPEED_TOP = 1.15
"""KR Pt 5 Ch 4 201.3: tau_3 applies from the MCR speed to 115 % of it."""
GENERATOR_BAND = (0.9, 1.1)
"""KR Pt 5 Ch 4 203.1(1): the continuous range of a generator engine (and 204: the band free
of major criticals)."""
PROPULSION_CRITICAL_BAND = (0.8, 1.1)
"""KR Pt 5 Ch 4 204: no major critical of the one-node mode in 0.8 <= lambda <= 1.1 for
main propulsion shafting."""
BARRED_RANGE_TOP = 0.8
"""IACS UR M53 2.2(A)(d) (KR Pt 5 Annex 5-3 2(2)(A)(d)): no barred speed range above a speed
ratio of 0.8 for normal firing."""
_LAMBDA_TOL = 1e-9


def engine_group(firing_angles: ArrayLike, bank_angles: ArrayLike) -> str:
    """KR Pt 5 Ch 4 201.1 engine group of a 4-stroke engine: ``"A"`` or ``"B"``.

    ``A``: an in-line engine (one bank angle), or a V engine whose firing intervals are all
    45 or 60 deg; ``B``: any other V engine (or more than two banks).

    Parameters
    ----------
    firing_angles : array_like, shape (n_cyl,) [rad]
        Crank angle at which each cylinder fires, from firing TDC of cylinder 1.
    bank_angles : array_like, shape (n_cyl,) [rad]
        Bank angle of each cylinder.

    Returns
    -------
    str

    Examples
    --------
    >>> import numpy as np
    >>> engine_group(np.radians([0, 540, 180, 360]), [0, 0, 0, 0])
    'A'
    >>> v12 = np.radians(np.arange(12) * 60.0)
    >>> engine_group(v12, np.radians([0, 60] * 6))
    'A'
    >>> v8 = np.radians(np.arange(8) * 90.0)
    >>> engine_group(v8, np.radians([0, 90] * 4))
    'B'
    """
    phi = finite("firing_angles", firing_angles).ravel()
    banks = finite("bank_angles", bank_angles).ravel()
    if phi.size == 0 or phi.size != banks.size:
        raise ValueError("firing_angles and bank_angles need one entry per cylinder")
    if np.unique(np.round(np.degrees(banks), 6)).size <= 1:
        return "A"
    deg = np.sort(np.mod(np.degrees(phi), 720.0))
    steps = np.diff(np.append(deg, deg[0] + 720.0))
    for interval in (45.0, 60.0):
        if np.allclose(steps, interval, atol=1e-6):
            return "A"
    return "B"


def speed_ratio(speed: ArrayLike, rated_speed: float) -> np.ndarray:
    """Speed ratio ``lambda = n / n_MCR`` [-] (KR Pt 5 Ch 4 201.1).

    Parameters
    ----------
    speed : array_like [rad/s]
        Engine speeds, >= 0.
    rated_speed : float [rad/s]
        Maximum continuous (rated) speed, > 0.
    """
    n = finite("speed", speed)
    if np.any(n < 0):
        raise ValueError(f"speed must be >= 0, got {speed!r}")
    return n / float(positive("rated_speed", rated_speed))


def material_factors(tensile_strength: float | None, yield_strength: float | None,
                     tensile_cap: float = TS_CAP_CARBON) -> tuple[float, float]:
    """Material factors ``(f_m1, f_m2)`` of KR Pt 5 Ch 4 201.4 [-].

    ``f_m1 = 1 + 2/3 (T_s/440 - 1)`` multiplies tau_1 and tau_3 when ``T_s > 440 N/mm^2``;
    ``f_m2 = Y / 225`` multiplies tau_2 when ``Y > 225 N/mm^2``; 1 otherwise, or when the
    strength is not given (the rule *permits* the increase). ``T_s`` enters at most as
    ``tensile_cap``: the rule leaves higher strengths (above 590 N/mm^2 for carbon-steel and
    835 N/mm^2 for low-alloy forgings) to the Society.

    Parameters
    ----------
    tensile_strength : float or None [Pa]
        Specified minimum tensile strength of the crank material.
    yield_strength : float or None [Pa]
        Specified minimum yield strength.
    tensile_cap : float [Pa]
        Largest ``T_s`` credited (default the carbon-steel 590 N/mm^2).

    Examples
    --------
    T_s = 590 N/mm^2, Y = 350 N/mm^2: f_m1 = 1 + 2/3 (590/440 - 1) = 1.2273, f_m2 = 1.5556

    >>> [round(x, 4) for x in material_factors(590e6, 350e6)]
    [1.2273, 1.5556]
    """
    f1 = f2 = 1.0
    if tensile_strength is not None:
        ts = min(float(positive("tensile_strength", tensile_strength)),
                 float(positive("tensile_cap", tensile_cap)))
        f1 = max(1.0, 1.0 + 2.0 / 3.0 * (ts / TS_REFERENCE - 1.0))
    if yield_strength is not None:
        f2 = max(1.0, float(positive("yield_strength", yield_strength)) / YIELD_REFERENCE)
    return f1, f2


def _group(group: str) -> str:
    if group not in GROUPS:
        raise ValueError(f"group must be one of {GROUPS}, got {group!r}")
    return group


def _ratio_in(name: str, lam: ArrayLike, lo: float, hi: float) -> np.ndarray:
    x = finite(name, lam)
    if np.any(x < lo - _LAMBDA_TOL) or np.any(x > hi + _LAMBDA_TOL):
        raise ValueError(f"{name} must lie in [{lo:g}, {hi:g}], got {lam!r}")
    return x


def propulsion_continuous(lam: ArrayLike, group: str, f_m: float = 1.0) -> np.ndarray:
    """Permissible vibratory stress of a main engine's crankshaft in continuous operation,
    ``tau_1 = f_m (45 - 24 lambda^2)`` (group A) or ``f_m (45 - 29 lambda^2)`` (group B)
    N/mm^2, ``0 <= lambda <= 1`` (KR Pt 5 Ch 4 201.1, 201.4) [Pa].

    Examples
    --------
    Group A at lambda = 0.5, 0.8, 1.0: 39.0, 29.64, 21.0 N/mm^2

    >>> (propulsion_continuous([0.5, 0.8, 1.0], "A") / 1e6).round(2).tolist()
    [39.0, 29.64, 21.0]
    """
    x = _ratio_in("lambda", lam, 0.0, 1.0)
    return f_m * (45.0 - _PROPULSION_SLOPE[_group(group)] * x**2) * MPA


def propulsion_transient(lam: ArrayLike, group: str, f_m: float = 1.0) -> np.ndarray:
    """Permissible stress for transient operation (passing a barred range rapidly),
    ``tau_2 = 2 tau_1`` with ``tau_1`` of :func:`propulsion_continuous` *without* its factor,
    times the yield factor ``f_m = Y/225`` (the second of :func:`material_factors`),
    ``0 <= lambda <= 0.8`` (KR Pt 5 Ch 4 201.2, 201.4(2)) [Pa].

    Examples
    --------
    Group B at lambda = 0.6: 2 (45 - 29 x 0.36) = 69.12 N/mm^2

    >>> round(float(propulsion_transient(0.6, "B")) / 1e6, 2)
    69.12
    """
    x = _ratio_in("lambda", lam, 0.0, PROPULSION_TRANSIENT_TOP)
    return f_m * 2.0 * (45.0 - _PROPULSION_SLOPE[_group(group)] * x**2) * MPA


def propulsion_overspeed(lam: ArrayLike, group: str, f_m: float = 1.0) -> np.ndarray:
    """Permissible stress between the MCR speed and 115 % of it,
    ``tau_3 = f_m (21 + 237 (lambda - 0.8) sqrt(lambda - 1))`` (group A; 16 + ... group B)
    N/mm^2, ``1 <= lambda <= 1.15`` (KR Pt 5 Ch 4 201.3, 201.4) [Pa]. At ``lambda = 1`` it
    equals tau_1 (21 = 45 - 24, 16 = 45 - 29).

    Examples
    --------
    Group A at lambda = 1.1: 21 + 237 x 0.3 x sqrt(0.1) = 43.48 N/mm^2

    >>> round(float(propulsion_overspeed(1.1, "A")) / 1e6, 2)
    43.48
    """
    x = _ratio_in("lambda", lam, 1.0, OVERSPEED_TOP)
    base = _OVERSPEED_BASE[_group(group)]
    return f_m * (base + 237.0 * (x - 0.8) * np.sqrt(np.maximum(x - 1.0, 0.0))) * MPA


def generator_continuous(group: str, f_m: float = 1.0) -> float:
    """Permissible stress of a generator engine's crankshaft in continuous operation, 0.9 <=
    lambda <= 1.1: ``tau_1 = 21`` (group A) or ``16`` N/mm^2 (group B), times ``f_m``
    (KR Pt 5 Ch 4 203.1(1), 203.3) [Pa].

    >>> generator_continuous("B") / 1e6
    16.0
    """
    return f_m * _GENERATOR_CONTINUOUS[_group(group)] * MPA


def generator_transient(f_m2: float = 1.0) -> float:
    """Permissible stress of a generator engine's crankshaft below and at 0.9 of the MCR
    speed for transient operation: ``tau_2 = 90 N/mm^2`` times ``f_m2 = Y/225`` (KR Pt 5 Ch 4
    203.1(2), 203.3) [Pa].

    >>> generator_transient() / 1e6
    90.0
    """
    return f_m2 * GENERATOR_TRANSIENT


class BarredRange(NamedTuple):
    """A barred speed range (KR Pt 5 Ch 4 206.1(1))."""

    lower: np.ndarray  #: lowest barred speed [rad/s]
    upper: np.ndarray  #: highest barred speed [rad/s]


def barred_speed_range(critical_speed: ArrayLike, rated_speed: float) -> BarredRange:
    """Barred speed range around a critical whose stress exceeds tau_1 (KR Pt 5 Ch 4
    206.1(1)):

    ``16 N_c / (18 - lambda) <= N <= (18 - lambda) N_c / 16``, ``lambda = N_c / N_MCR``.

    Parameters
    ----------
    critical_speed : array_like [rad/s]
        Speed of the resonant critical ``N_c`` (> 0).
    rated_speed : float [rad/s]
        MCR (rated) speed ``N_MCR``.

    Returns
    -------
    BarredRange

    Examples
    --------
    A critical at the MCR speed (lambda = 1): 16/17 = 0.9412 .. 17/16 = 1.0625 of it

    >>> r = barred_speed_range(100.0, 100.0)
    >>> round(float(r.lower), 4), round(float(r.upper), 4)
    (94.1176, 106.25)

    Notes
    -----
    Valid for ``0 < lambda < 18`` (the formula's own range; critical speeds far above the
    rated speed have no barred range in the rules).
    """
    nc = positive("critical_speed", critical_speed)
    lam = nc / float(positive("rated_speed", rated_speed))
    if np.any(lam >= 18.0):
        raise ValueError("critical_speed / rated_speed must be below 18")
    return BarredRange(16.0 * nc / (18.0 - lam), (18.0 - lam) * nc / 16.0)


def band_clearance(lam: ArrayLike, band: tuple[float, float]) -> np.ndarray:
    """Signed distance of speed ratios from a band, in units of the rated speed [-]:
    ``max(lo - lambda, lambda - hi)``, positive outside the band, negative inside (KR Pt 5
    Ch 4 204: major criticals must lie outside 0.8..1.1, generators 0.9..1.1).

    >>> band_clearance([0.5, 1.0, 1.3], (0.8, 1.1)).round(3).tolist()
    [0.3, -0.1, 0.2]
    """
    x = finite("lambda", lam)
    lo, hi = band
    if not lo < hi:
        raise ValueError(f"band must be (low, high) with low < high, got {band!r}")
    return np.maximum(lo - x, x - hi)
