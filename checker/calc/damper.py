"""Rubber torsional-vibration damper: twist, torque, dissipated power, rubber stress and heat.

Per-order quantities use the complex-amplitude convention of :mod:`checker.calc.excitation`
(``x(t) = sum_n Re{X_n exp(j n w t)}``, ``|X_n|`` 0-to-peak) with the order axis last. The rubber
element between hub and inertia ring has the complex stiffness

    k*(Omega) = k' + j (k'' + Omega c),   k'' = eta k'

(hysteretic loss factor ``eta`` and/or viscous ``c``). Sources of the formulas: References.

References
----------
.. [1] J. P. Den Hartog, "Mechanical Vibrations", 4th ed., 1956, sec. 2.8 (work per cycle), eqs.
   3.12, 3.19, 3.23, 3.24 (optimum tuned absorber).
.. [2] A. N. Gent (ed.), "Engineering with Rubber", 3rd ed., Hanser, 2012, ch. 8 (rubber in shear).
.. [3] L. Drapal, P. Novotny, "Torsional vibration analysis of crank train with low friction
   losses", J. Vibroeng. 19(7), 2017, doi:10.21595/jve.2017.17876, eq. 9.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from checker.calc.torsional import half_peak_to_peak

__all__ = [
    "absorber_magnification",
    "annulus_heat_density",
    "annulus_local_heat_density",
    "annulus_shear_stress",
    "annulus_stiffness",
    "annulus_volume",
    "damper_torque",
    "den_hartog_optimum",
    "dissipated_power",
    "relative_twist",
    "synthesized_amplitude",
]


def relative_twist(theta_hub: ArrayLike, theta_ring: ArrayLike) -> np.ndarray:
    """Complex relative twist of the rubber per order, ``dphi_n = Theta_hub - Theta_ring``.

    Parameters
    ----------
    theta_hub, theta_ring : array_like, shape (..., n_order), complex [rad]
        Order amplitudes of the hub (crank nose) and inertia-ring stations.

    Returns
    -------
    numpy.ndarray, shape (..., n_order), complex [rad]
    """
    return np.asarray(theta_hub, dtype=complex) - np.asarray(theta_ring, dtype=complex)


def _loss_stiffness(
    omega: np.ndarray, storage_stiffness: ArrayLike, loss_factor: ArrayLike, damping: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    ks = np.asarray(storage_stiffness, dtype=float)
    eta = np.asarray(loss_factor, dtype=float)
    c = np.asarray(damping, dtype=float)
    if np.any(ks < 0) or np.any(eta < 0) or np.any(c < 0):
        raise ValueError("storage_stiffness, loss_factor and damping must be >= 0")
    if np.any(omega < 0):
        raise ValueError("omega must be >= 0 rad/s")
    return ks, eta * ks + omega * c


def damper_torque(
    dphi: ArrayLike,
    omega: ArrayLike,
    storage_stiffness: ArrayLike,
    loss_factor: ArrayLike = 0.0,
    damping: ArrayLike = 0.0,
) -> np.ndarray:
    """Rubber torque per order ``T_n = (k' + j (eta k' + Omega_n c)) dphi_n``.

    Parameters
    ----------
    dphi : array_like, shape (..., n_order), complex [rad]
        Relative twist hub - ring (:func:`relative_twist`).
    omega : array_like, broadcast to dphi [rad/s]
        Vibration frequency of each order ``Omega_n = n w``.
    storage_stiffness : array_like [N m/rad]
        ``k'`` (may depend on frequency: pass an array broadcast to ``dphi``).
    loss_factor : array_like [-]
        ``eta`` (hysteretic).
    damping : array_like [N m s/rad]
        Viscous ``c``.

    Returns
    -------
    numpy.ndarray, complex [N m]
        Torque transmitted from hub to ring; ``|T_n| = k' |dphi_n| sqrt(1 + eta^2)`` for pure
        hysteretic damping.
    """
    w = np.asarray(omega, dtype=float)
    ks, kpp = _loss_stiffness(w, storage_stiffness, loss_factor, damping)
    return (ks + 1j * kpp) * np.asarray(dphi, dtype=complex)


def dissipated_power(
    dphi: ArrayLike,
    omega: ArrayLike,
    storage_stiffness: ArrayLike = 0.0,
    loss_factor: ArrayLike = 0.0,
    damping: ArrayLike = 0.0,
) -> np.ndarray:
    """Mean power dissipated in the rubber, per order.

    ``P_n = 1/2 Omega_n (eta k' + Omega_n c) |dphi_n|^2`` (energy per cycle ``pi k''|dphi|^2``,
    times ``Omega/(2 pi)``). The total is the plain sum over orders ``P = sum_n P_n`` (orders
    are orthogonal over the 720 deg cycle): ``dissipated_power(...).sum(-1)``.

    Parameters
    ----------
    dphi : array_like, shape (..., n_order), complex [rad]
    omega : array_like [rad/s]
    storage_stiffness : array_like [N m/rad]
        ``k'`` (only needed with ``loss_factor``).
    loss_factor : array_like [-]
    damping : array_like [N m s/rad]

    Returns
    -------
    numpy.ndarray, shape (..., n_order) [W]

    Notes
    -----
    Den Hartog, *Mechanical Vibrations*, 4th ed. 1956, sec. 2.8 (work of a viscous / hysteretic
    force per cycle).
    """
    w = np.asarray(omega, dtype=float)
    _, kpp = _loss_stiffness(w, storage_stiffness, loss_factor, damping)
    return 0.5 * w * kpp * np.abs(np.asarray(dphi, dtype=complex)) ** 2


def synthesized_amplitude(orders: ArrayLike, coeffs: ArrayLike) -> np.ndarray:
    """Half peak-to-peak of the synthesised signal of all orders (e.g. damper torque or twist).

    Thin wrapper of :func:`checker.calc.torsional.half_peak_to_peak`.

    Parameters
    ----------
    orders : array_like, shape (n_order,) [-]
    coeffs : array_like, shape (..., n_order), complex [any unit]

    Returns
    -------
    numpy.ndarray, shape (...) [unit of coeffs]
    """
    return half_peak_to_peak(orders, coeffs)


def _check_annulus(r_inner: ArrayLike, r_outer: ArrayLike, length: ArrayLike) -> tuple:
    ri = np.asarray(r_inner, dtype=float)
    ro = np.asarray(r_outer, dtype=float)
    ln = np.asarray(length, dtype=float)
    if np.any(ri <= 0) or np.any(ro <= ri) or np.any(ln <= 0):
        raise ValueError("annulus needs 0 < r_inner < r_outer and length > 0 (m)")
    return ri, ro, ln


def annulus_volume(r_inner: ArrayLike, r_outer: ArrayLike, length: ArrayLike) -> np.ndarray:
    """Rubber volume ``V = pi (r_o^2 - r_i^2) L`` [m^3] (radii and length in [m])."""
    ri, ro, ln = _check_annulus(r_inner, r_outer, length)
    return np.pi * (ro**2 - ri**2) * ln


def annulus_stiffness(
    shear_modulus: ArrayLike, r_inner: ArrayLike, r_outer: ArrayLike, length: ArrayLike
) -> np.ndarray:
    """Torsional stiffness of a bonded annular rubber ring twisted about its axis.

    ``k* = G* 4 pi L r_i^2 r_o^2 / (r_o^2 - r_i^2)`` (thin layer ``h``: ``~ 2 pi G R^3 L / h``).

    Parameters
    ----------
    shear_modulus : array_like [Pa]
        ``G'`` or complex ``G* = G' (1 + j eta)``.
    r_inner, r_outer : array_like [m]
        Bonded radii (hub side, ring side).
    length : array_like [m]
        Axial length of the rubber.

    Returns
    -------
    numpy.ndarray [N m/rad] (complex if ``shear_modulus`` is)

    Notes
    -----
    Torque equilibrium ``T = 2 pi r^2 L tau(r)`` with ``tau = G r dphi/dr`` integrated from
    ``r_i`` to ``r_o`` (Gent, *Engineering with Rubber*, 3rd ed. 2012, ch. 8).
    Linear (small-strain) rubber, bonded faces, no end effects.
    """
    ri, ro, ln = _check_annulus(r_inner, r_outer, length)
    g = np.asarray(shear_modulus)
    if np.any(np.real(g) <= 0) or np.any(np.imag(g) < 0):
        raise ValueError("shear_modulus must have Re > 0 and Im >= 0 Pa")
    return g * 4.0 * np.pi * ln * ri**2 * ro**2 / (ro**2 - ri**2)



def annulus_shear_modulus(
    stiffness: ArrayLike, r_inner: ArrayLike, r_outer: ArrayLike, length: ArrayLike
) -> np.ndarray:
    """Storage shear modulus of a bonded annular rubber ring from its torsional stiffness.

    ``G' = k' (r_o^2 - r_i^2) / (4 pi L r_i^2 r_o^2)``: :func:`annulus_stiffness` solved for
    the modulus (Gent, *Engineering with Rubber*, 3rd ed. 2012, ch. 8).

    Parameters
    ----------
    stiffness : array_like [N m/rad]
        Storage (real) torsional stiffness ``k'``, positive.
    r_inner, r_outer : array_like [m]
        Bonded radii (hub side, ring side).
    length : array_like [m]
        Axial length of the rubber.

    Returns
    -------
    numpy.ndarray [Pa]

    Examples
    --------
    A ring of r_i = 50 mm, r_o = 60 mm, L = 20 mm has k'/G' = 4 pi 0.02 0.05^2 0.06^2 / 0.0011
    = 2.0563152e-3 m^3, so k' = 2056.3152 N m/rad means G' = 1 MPa:

    >>> round(float(annulus_shear_modulus(2056.3152, 0.05, 0.06, 0.02)) / 1e6, 6)
    1.0
    """
    k = np.asarray(stiffness, dtype=float)
    if np.any(k <= 0):
        raise ValueError("stiffness must be positive N m/rad")
    return k / annulus_stiffness(1.0, r_inner, r_outer, length)

def annulus_shear_stress(
    torque: ArrayLike, r_inner: ArrayLike, length: ArrayLike, radius: ArrayLike | None = None
) -> np.ndarray:
    """Shear stress in a bonded annular rubber ring, ``tau(r) = T / (2 pi r^2 L)``.

    Parameters
    ----------
    torque : array_like [N m]
        Torque amplitude (per order, or the synthesised half peak-to-peak for the total).
    r_inner : array_like [m]
        Inner radius: the maximum stress is at ``r = r_inner`` (default).
    length : array_like [m]
    radius : array_like, optional [m]
        Radius where the stress is wanted (``>= r_inner``).

    Returns
    -------
    numpy.ndarray [Pa] (same kind, real or complex, as ``torque``)
    """
    ri = np.asarray(r_inner, dtype=float)
    ln = np.asarray(length, dtype=float)
    if np.any(ri <= 0) or np.any(ln <= 0):
        raise ValueError("r_inner and length must be > 0 m")
    r = ri if radius is None else np.asarray(radius, dtype=float)
    if np.any(r < ri * (1 - 1e-12)):
        raise ValueError("radius must be >= r_inner")
    return np.asarray(torque) / (2.0 * np.pi * r**2 * ln)


def annulus_local_heat_density(
    torque: ArrayLike,
    omega: ArrayLike,
    shear_modulus: ArrayLike,
    radius: ArrayLike,
    length: ArrayLike,
) -> np.ndarray:
    """Local mean heat generation per unit volume of one order at radius ``r``.

    ``q(r) = 1/2 Omega G'' |gamma(r)|^2``, ``gamma(r) = tau(r) / |G*|``, ``tau = |T|/(2 pi r^2 L)``.

    Parameters
    ----------
    torque : array_like [N m]
        Torque amplitude of the order (complex allowed, its modulus is used).
    omega : array_like [rad/s]
    shear_modulus : array_like, complex [Pa]
        ``G* = G' + j G''``.
    radius, length : array_like [m]

    Returns
    -------
    numpy.ndarray [W/m^3]
    """
    g = np.asarray(shear_modulus, dtype=complex)
    tau = np.abs(np.asarray(torque)) / (2.0 * np.pi * np.asarray(radius, float) ** 2 * length)
    return 0.5 * np.asarray(omega, dtype=float) * g.imag * (tau / np.abs(g)) ** 2


def annulus_heat_density(
    power: ArrayLike, r_inner: ArrayLike, r_outer: ArrayLike, length: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Mean and peak heat generation per unit rubber volume of a bonded annulus.

    ``q_mean = P / V``; since ``q(r) ~ 1/r^4`` the peak at the inner radius is
    ``q_peak = q_mean (r_o / r_i)^2``.

    Parameters
    ----------
    power : array_like [W]
        Dissipated power (per order or the total ``sum_n P_n``).
    r_inner, r_outer, length : array_like [m]

    Returns
    -------
    q_mean, q_peak : numpy.ndarray [W/m^3]
    """
    ri, ro, ln = _check_annulus(r_inner, r_outer, length)
    p = np.asarray(power, dtype=float)
    if np.any(p < 0):
        raise ValueError("power must be >= 0 W")
    q_mean = p / (np.pi * (ro**2 - ri**2) * ln)
    return q_mean, q_mean * (ro / ri) ** 2


def den_hartog_optimum(mass_ratio: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Den Hartog's optimum tuned viscous absorber on an undamped primary system.

    ``f_opt = 1/(1+mu)``, ``zeta_opt = sqrt(3 mu / (8 (1+mu)^3))`` (``zeta = c_d/(2 J_d
    omega_n)``), peak magnification ``sqrt(1 + 2/mu)``.

    Parameters
    ----------
    mass_ratio : array_like [-]
        ``mu = J_d / J_eq > 0`` (absorber inertia over the equivalent inertia of the mode,
        :func:`checker.calc.torsional.equivalent_inertia`).

    Returns
    -------
    tuning, damping_ratio, peak_magnification : numpy.ndarray [-]

    Notes
    -----
    Den Hartog, *Mechanical Vibrations*, 4th ed. 1956, eqs. (3.19), (3.23), (3.24) (equal-height
    fixed points; the damping is the average of the two values that put the maximum at either
    fixed point, so the true maximum slightly exceeds ``sqrt(1+2/mu)``: +0.1 % at mu = 0.05-0.2).
    """
    mu = np.asarray(mass_ratio, dtype=float)
    if np.any(mu <= 0):
        raise ValueError("mass_ratio must be > 0")
    return 1.0 / (1.0 + mu), np.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3)), np.sqrt(1.0 + 2.0 / mu)


def absorber_magnification(
    frequency_ratio: ArrayLike, mass_ratio: ArrayLike, tuning: ArrayLike, damping_ratio: ArrayLike
) -> np.ndarray:
    """Dynamic magnification of a primary system with a viscous tuned absorber (2-DOF).

    ``xi = sqrt((4 g^2 r^2 + (r^2 - f^2)^2) / (4 g^2 r^2 (1 - r^2 - mu r^2)^2 + (mu f^2 r^2 -
    (r^2 - 1)(r^2 - f^2))^2))``

    Parameters
    ----------
    frequency_ratio : array_like [-]
        ``r = Omega / omega_n`` (``omega_n = sqrt(k/J)`` of the primary system).
    mass_ratio : array_like [-]
        ``mu = J_d / J``.
    tuning : array_like [-]
        ``f = omega_d / omega_n`` with ``omega_d = sqrt(k_d / J_d)``.
    damping_ratio : array_like [-]
        ``g = c_d / (2 J_d omega_n)``.

    Returns
    -------
    numpy.ndarray [-]
        ``|Theta_primary| / (T / k)``; ``inf`` only for ``damping_ratio = 0`` exactly at a
        natural frequency of the undamped 2-DOF system (closed-form check function).

    Notes
    -----
    Den Hartog 1956, eq. (3.12); Drapal & Novotny 2017, J. Vibroeng. 19(7), eq. (9).
    """
    r2 = np.asarray(frequency_ratio, dtype=float) ** 2
    mu = np.asarray(mass_ratio, dtype=float)
    f2 = np.asarray(tuning, dtype=float) ** 2
    g2 = np.asarray(damping_ratio, dtype=float) ** 2
    if np.any(mu <= 0) or np.any(f2 <= 0) or np.any(g2 < 0):
        raise ValueError("mass_ratio and tuning must be > 0 and damping_ratio >= 0")
    num = 4 * g2 * r2 + (r2 - f2) ** 2
    den = 4 * g2 * r2 * (1 - r2 - mu * r2) ** 2 + (mu * f2 * r2 - (r2 - 1) * (r2 - f2)) ** 2
    return np.sqrt(num / den)
