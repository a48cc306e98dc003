"""A fixed-pitch propeller as the load of a torsional model (pure NumPy): the propeller law,
the damping it gives, and its inertia in water.

* Propeller law: at a constant advance ratio the torque coefficient ``K_Q`` is constant and
  ``Q = K_Q rho n^2 D^5``: along the propeller curve the torque grows with the square of the
  speed, ``Q = Q_r (omega / omega_r)^2`` (MAN Energy Solutions, "Basic principles of ship
  propulsion", section "Slip ratio and propeller law").
* Damping: a small speed fluctuation ``d omega`` about the mean speed changes the absorbed
  torque by ``dQ = (dQ/domega) d omega``, a viscous damping to the stationary water of
  ``c = dQ/domega = 2 Q / omega`` on the propeller curve (the quasi-static slope of the
  propeller law; a lower estimate: the empirical propeller damping formulas used in marine
  torsional calculations give more).
* Inertia in water: the water the blades carry along adds to the propeller's dry inertia,
  ``J_w = J_dry (1 + f)``; ``f`` is typically 0.2..0.3 (MacPherson, Puleo, Packard,
  "Estimation of entrained water added mass properties for vibration analysis", SNAME New
  England Section, 2007, survey of the methods).

References
----------
.. [1] MAN Energy Solutions, "Basic principles of ship propulsion", section "Slip ratio and
   propeller law".
.. [2] MacPherson, D. M., Puleo, V. R., Packard, M. B., "Estimation of entrained water added
   mass properties for vibration analysis", SNAME New England Section, 2007.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["propeller_damping", "propeller_torque", "wet_inertia"]


def _check(rated_torque: float, rated_speed: float) -> None:
    if not (np.isfinite(rated_torque) and rated_torque > 0):
        raise ValueError("rated propeller torque must be finite and > 0 N m")
    if not (np.isfinite(rated_speed) and rated_speed > 0):
        raise ValueError("rated speed must be finite and > 0 rad/s")


def propeller_torque(speed: ArrayLike, rated_torque: float, rated_speed: float) -> np.ndarray:
    """Propeller law ``Q = Q_r (omega / omega_r)^2``.

    Parameters
    ----------
    speed : array_like [rad/s]
        Shaft speed (>= 0).
    rated_torque : float [N m]
        Torque at the rated speed.
    rated_speed : float [rad/s]

    Returns
    -------
    numpy.ndarray [N m]

    Examples
    --------
    >>> round(float(propeller_torque(0.8, 100.0, 1.0)), 6)  # 80 % speed: 64 % torque
    64.0
    """
    _check(rated_torque, rated_speed)
    w = np.asarray(speed, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0):
        raise ValueError("speed must be finite and >= 0 rad/s")
    return rated_torque * (w / rated_speed) ** 2


def propeller_damping(speed: ArrayLike, rated_torque: float, rated_speed: float) -> np.ndarray:
    """Propeller damping ``c = dQ/domega = 2 Q_r omega / omega_r^2`` on the propeller curve.

    Parameters and units as :func:`propeller_torque`; returns [N m s/rad].

    Examples
    --------
    >>> round(float(propeller_damping(10.0, 1000.0, 10.0)), 6)  # 2 Q / omega at rated speed
    200.0
    """
    _check(rated_torque, rated_speed)
    w = np.asarray(speed, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0):
        raise ValueError("speed must be finite and >= 0 rad/s")
    return 2.0 * rated_torque * w / rated_speed**2


def wet_inertia(dry_inertia: ArrayLike, entrained_fraction: float) -> np.ndarray:
    """Propeller inertia in water ``J_dry (1 + f)``.

    Parameters
    ----------
    dry_inertia : array_like [kg m^2]
        > 0.
    entrained_fraction : float [-]
        Entrained water inertia over the dry inertia (>= 0).

    Returns
    -------
    numpy.ndarray [kg m^2]
    """
    j = np.asarray(dry_inertia, dtype=float)
    if np.any(~np.isfinite(j)) or np.any(j <= 0):
        raise ValueError("dry inertia must be finite and > 0 kg m^2")
    if not (np.isfinite(entrained_fraction) and entrained_fraction >= 0):
        raise ValueError("entrained water fraction must be finite and >= 0")
    return j * (1.0 + entrained_fraction)
