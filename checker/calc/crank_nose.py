"""Classical fatigue check of the crank nose: belt bending plus mean and TV torsion.

The crank nose carries the torque to the damper and the front-end accessory drive (TV torque of
the nose section plus the FEAD/timing torque) and, where a belt or chain pulls on it, a bending
moment that is stationary in space and therefore fully reversed in the rotating shaft (Bell,
Ricardo 2013,
"Classical stress analysis of crank nose": TV torque, FEAD and timing drive torque, bending
loads due to FEAD belts and timing drive).

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 2013, slide 29.
.. [2] R.G. Budynas, J.K. Nisbett, "Shigley's Mechanical Engineering Design", 10th ed.,
   McGraw-Hill, 2015: eq. 3-24 (round shaft bending, sigma = 32 M / (pi d^3)), eq. 3-37 (torsion,
   tau = 16 T / (pi d^3)), eq. 7-7/7-8 (von Mises alternating and mean stresses of a rotating
   shaft under fully reversed bending and fluctuating torsion).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .crank_stress import shaft_section_moduli
from .fatigue import goodman_safety_factor


def crank_nose_stresses(torque_max: ArrayLike, torque_min: ArrayLike, belt_load: ArrayLike,
                        overhang: ArrayLike, diameter: float, bore: float = 0.0,
                        kt_bending: float = 1.0, kt_torsion: float = 1.0
                        ) -> tuple[np.ndarray, np.ndarray]:
    r"""Equivalent alternating and mean stresses at the crank-nose fillet.

    .. math::

        \sigma_a = K_b \frac{F a}{W_b},\quad \tau_a = K_t \frac{T_{max} - T_{min}}{2 W_p},\quad
        \tau_m = K_t \frac{T_{max} + T_{min}}{2 W_p}

        \sigma_{eq,a} = \sqrt{\sigma_a^2 + 3\tau_a^2},\quad
        \sigma_{eq,m} = \sqrt{3}\,\tau_m \;(\text{signed})

    The belt load is stationary while the shaft turns, so its bending is fully reversed (no
    mean); the bending and torsion amplitudes are combined as if in phase (conservative) [2].

    Parameters
    ----------
    torque_max, torque_min : array_like [N m]
        Largest and smallest torque over the cycle in the nose section (mean + vibratory).
    belt_load : array_like [N]
        Resultant belt/chain pull on the nose (0 if none).
    overhang : array_like [m]
        Lever of the belt load to the critical section.
    diameter, bore : float [m]
        Nose section diameter and bore.
    kt_bending, kt_torsion : float [-]
        Stress concentration factors of the nose fillet (>= 1).

    Returns
    -------
    sigma_eq_a, sigma_eq_m : numpy.ndarray [Pa]
    """
    if diameter <= 0 or bore < 0 or bore >= diameter:
        raise ValueError("crank nose needs 0 <= bore < diameter")
    if kt_bending < 1 or kt_torsion < 1:
        raise ValueError("stress concentration factors must be >= 1")
    w_b, w_p = shaft_section_moduli(diameter, bore)
    tmax, tmin = np.asarray(torque_max, float), np.asarray(torque_min, float)
    if np.any(tmax < tmin):
        raise ValueError("torque_max must not be below torque_min")
    sig_a = kt_bending * np.asarray(belt_load, float) * np.asarray(overhang, float) / w_b
    tau_a = kt_torsion * (tmax - tmin) / (2.0 * w_p)
    tau_m = kt_torsion * (tmax + tmin) / (2.0 * w_p)
    eq_a = np.sqrt(sig_a**2 + 3.0 * tau_a**2)
    eq_m = np.sign(tau_m) * np.sqrt(3.0) * np.abs(tau_m)
    return eq_a, eq_m


def crank_nose_safety_factor(sigma_eq_a: ArrayLike, sigma_eq_m: ArrayLike,
                             fatigue_strength: float, uts: float) -> np.ndarray:
    """Goodman safety factor of the nose fillet (torsional mean counted by its magnitude:
    a reversed torque direction does not relieve the fillet)."""
    return goodman_safety_factor(sigma_eq_a, np.abs(sigma_eq_m), fatigue_strength, uts)
