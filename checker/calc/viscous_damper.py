"""Untuned viscous (Houdaille) torsional-vibration damper: silicone coupling, optimum, heat.

An inertia ring (``J_d``) turns in a closed housing bolted to the crank nose; the silicone in
the gaps couples it to the housing. With a Newtonian fluid the coupling is a pure viscous
torque ``T = c (Omega_hub - Omega_ring)``; with the fluid's shear elasticity (a Maxwell fluid:
spring and dashpot in series) the coupling is the complex impedance

    z(Omega) = j Omega c k_s / (k_s + j Omega c)

(Andre & Spurk 1982). Per order the power dissipated is ``P_n = 1/2 Omega_n Im z |dphi_n|^2``
(``= 1/2 c Omega_n^2 |dphi_n|^2`` for the Newtonian coupling).

References
----------
.. [1] J. P. Den Hartog, "Mechanical Vibrations", 4th ed., McGraw-Hill, 1956, ch. 3 (the
   damped vibration absorber; the untuned viscous "Lanchester" damper: both response curves
   pass through one fixed point, the optimum damping makes it the maximum).
.. [2] W. Andre, J. H. Spurk, "Torsional damper for maximum energy absorption with
   equilibrated polydimethylsiloxanes as damping fluids", J. Sound Vib. 82(4), 465-472, 1982
   (Newtonian c = viscosity x geometry factor; the fluid's shear modulus in series).
.. [3] F. M. White, "Viscous Fluid Flow", 3rd ed., McGraw-Hill, 2006, sec. 3-2 (Couette flow
   between parallel walls: linear velocity profile, wall shear stress mu U / h).
.. [4] E. N. da C. Andrade, "The viscosity of liquids", Nature 125, 309-310, 1930
   (ln nu = A + B / T).
.. [5] F. P. Incropera, D. P. DeWitt, T. L. Bergman, A. S. Lavine, "Fundamentals of Heat and
   Mass Transfer", 6th ed., Wiley, 2007, eq. 1.3a (Newton's law of cooling q = h A dT).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from checker.calc._checks import non_negative, positive

__all__ = [
    "GapGeometry",
    "andrade_slope",
    "andrade_viscosity",
    "couette_factor",
    "impedance_power",
    "maxwell_impedance",
    "steady_temperature",
    "untuned_magnification",
    "untuned_optimum",
    "wetted_area",
]

#: Largest gap / radius for which the thin-gap (plane Couette) shear is used: the linear
#: velocity profile of a narrow annular gap differs from the exact cylindrical Couette flow by
#: about h / r (a few % at 0.05); beyond 0.1 the geometry is not a thin film.
MAX_GAP_RATIO = 0.1


class GapGeometry(NamedTuple):
    """Inertia ring of a viscous damper in its housing (all [m]).

    Attributes
    ----------
    r_inner, r_outer : ring inner and outer radius
    width : axial width of the ring
    gap_radial : silicone film at the ring's inner and outer cylindrical faces
    gap_axial : silicone film at each of the ring's two side faces
    """

    r_inner: float
    r_outer: float
    width: float
    gap_radial: float
    gap_axial: float


def _geometry(g: GapGeometry) -> tuple[float, ...]:
    ri, ro, b, hr, ha = (float(positive(n, v)) for n, v in zip(g._fields, g))
    if ro <= ri:
        raise ValueError("ring outer radius must exceed the inner radius")
    if hr > MAX_GAP_RATIO * ri or ha > MAX_GAP_RATIO * ri:
        raise ValueError(f"gaps must be thin films: gap <= {MAX_GAP_RATIO:g} x ring inner"
                         " radius (plane Couette shear)")
    return ri, ro, b, hr, ha


def couette_factor(g: GapGeometry) -> float:
    """Geometry factor ``Phi`` [m^3] of the silicone coupling: ``c = mu Phi``.

    Couette shear on every wetted face (thin film, linear velocity profile, wall shear stress
    ``tau = mu r Omega / h`` at radius ``r``):

    * cylindrical face of radius ``R`` and width ``b`` (gap ``h_r``): torque
      ``tau 2 pi R b R`` -> ``2 pi b R^3 / h_r`` for the inner and for the outer face;
    * each flat side face (``r_i..r_o``, gap ``h_a``): ``int mu r Omega / h_a r 2 pi r dr``
      -> ``pi (r_o^4 - r_i^4) / (2 h_a)``, two faces.

    ``Phi = 2 pi b (r_o^3 + r_i^3) / h_r + pi (r_o^4 - r_i^4) / h_a``.

    The fluid's shear modulus gives the series stiffness with the same factor,
    ``k_s = G Phi`` (Andre & Spurk 1982).

    Parameters
    ----------
    g : GapGeometry

    Returns
    -------
    float [m^3]

    Notes
    -----
    Couette flow: White, *Viscous Fluid Flow*, 3rd ed. 2006, sec. 3-2. Validity: thin gaps
    (``h <= 0.1 r_i``, checked), centred ring, laminar Newtonian film, no end effects at the
    corners of the ring.

    Examples
    --------
    A ring r_i = 100 mm, r_o = 150 mm, b = 40 mm in 1 mm gaps:

    2 pi 0.04 (0.15^3 + 0.1^3) / 0.001 + pi (0.15^4 - 0.1^4) / 0.001 = 1.099557 + 1.276272:

    >>> round(couette_factor(GapGeometry(0.1, 0.15, 0.04, 0.001, 0.001)), 6)
    2.375829
    """
    ri, ro, b, hr, ha = _geometry(g)
    return 2.0 * np.pi * b * (ro**3 + ri**3) / hr + np.pi * (ro**4 - ri**4) / ha


def wetted_area(g: GapGeometry) -> float:
    """Silicone-wetted area of the ring ``2 pi b (r_o + r_i) + 2 pi (r_o^2 - r_i^2)`` [m^2]."""
    ri, ro, b, _, _ = _geometry(g)
    return 2.0 * np.pi * b * (ro + ri) + 2.0 * np.pi * (ro**2 - ri**2)


#: Temperatures of the viscosity temperature coefficient of silicone-fluid datasheets,
#: ``VTC = 1 - nu(210 F) / nu(100 F)`` [K].
VTC_TEMPERATURES = (310.928, 372.039)


def andrade_slope(vtc: float) -> float:
    """Slope ``B`` [K] of ``ln nu = A + B / T`` from a viscosity temperature coefficient.

    ``VTC = 1 - nu(98.9 C) / nu(37.8 C)`` (210 and 100 F, as silicone-fluid datasheets give
    it): ``B = ln(1 / (1 - VTC)) / (1/T_37.8 - 1/T_98.9)``.

    Examples
    --------
    >>> round(andrade_slope(0.6), 1)
    1734.5
    """
    v = float(positive("vtc", vtc))
    if v >= 1.0:
        raise ValueError("vtc must be below 1")
    t1, t2 = VTC_TEMPERATURES
    return float(np.log(1.0 / (1.0 - v)) / (1.0 / t1 - 1.0 / t2))


def andrade_viscosity(temperature: ArrayLike, nu_ref: float, t_ref: float,
                      slope: float) -> np.ndarray:
    """Kinematic viscosity against temperature, ``nu = nu_ref exp(B (1/T - 1/T_ref))``.

    Parameters
    ----------
    temperature : array_like [K]
    nu_ref, t_ref : float [m^2/s], [K]
        Viscosity at the reference temperature (the grade).
    slope : float [K]
        ``B`` of ``ln nu = A + B / T`` (:func:`andrade_slope`).

    Returns
    -------
    numpy.ndarray [m^2/s]

    Notes
    -----
    Andrade, Nature 125, 1930. Valid for a liquid well above its pour point (silicone fluids:
    about -50 C); the datasheet's VTC fixes ``B`` between 37.8 and 98.9 C, beyond them it is
    the law's own trend.

    Examples
    --------
    >>> round(float(andrade_viscosity(372.039, 1.0, 310.928, andrade_slope(0.6))), 6)
    0.4
    """
    t = positive("temperature", temperature)
    nu1, t1 = float(positive("nu_ref", nu_ref)), float(positive("t_ref", t_ref))
    return nu1 * np.exp(float(slope) * (1.0 / t - 1.0 / t1))


def maxwell_impedance(omega: ArrayLike, damping: ArrayLike,
                      shear_stiffness: float | None = None) -> np.ndarray:
    """Complex impedance of the silicone coupling [N m/rad].

    ``z = j Omega c`` (Newtonian), or with the fluid's shear stiffness in series (Maxwell)
    ``z = j Omega c k_s / (k_s + j Omega c)`` (Andre & Spurk 1982).

    Parameters
    ----------
    omega : array_like [rad/s]
    damping : array_like [N m s/rad]
        ``c``, broadcast to ``omega``.
    shear_stiffness : float, optional [N m/rad]
        ``k_s = G Phi`` (:func:`couette_factor`); ``None``: Newtonian.

    Returns
    -------
    numpy.ndarray, complex [N m/rad]
    """
    w = non_negative("omega", omega)
    jwc = 1j * w * non_negative("damping", damping)
    if shear_stiffness is None:
        return jwc
    ks = float(positive("shear_stiffness", shear_stiffness))
    return jwc * ks / (ks + jwc)


def impedance_power(dphi: ArrayLike, omega: ArrayLike, impedance: ArrayLike) -> np.ndarray:
    """Mean power dissipated by a coupling per order ``P_n = 1/2 Omega_n Im z |dphi_n|^2`` [W].

    For ``z = j Omega c`` this is ``1/2 c Omega^2 |dphi|^2`` (Den Hartog 1956, sec. 2.8: work
    of a viscous force per cycle ``pi c Omega |dphi|^2``, times ``Omega / 2 pi``).

    Parameters
    ----------
    dphi : array_like, complex [rad]
        Relative twist hub - ring per order (0-to-peak).
    omega : array_like [rad/s]
    impedance : array_like, complex [N m/rad]
    """
    z = np.asarray(impedance, dtype=complex)
    return 0.5 * np.asarray(omega, dtype=float) * z.imag * np.abs(
        np.asarray(dphi, dtype=complex)) ** 2


def untuned_optimum(mass_ratio: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Den Hartog's optimum untuned viscous damper on an undamped primary system.

    With ``g = c / (2 J_d omega_n)`` (``J_d`` the ring, ``omega_n`` and ``J = J_d / mu`` the
    primary system) every response curve passes through one fixed point at the frequency ratio
    ``r_P = sqrt(2 / (2 + mu))`` with magnification ``1 + 2/mu``; the optimum damping puts the
    curve's maximum there:

    ``g_opt = 1 / sqrt(2 (1 + mu) (2 + mu))`` (damping ratio of the primary system
    ``zeta = c/(2 J omega_n) = mu g_opt = mu / sqrt(2 (1 + mu)(2 + mu))``).

    Parameters
    ----------
    mass_ratio : array_like [-]
        ``mu = J_d / J > 0``.

    Returns
    -------
    g_opt, peak_ratio, peak_magnification : numpy.ndarray [-]
        Optimum ``c / (2 J_d omega_n)``, frequency ratio of the peak, peak magnification.

    Notes
    -----
    Den Hartog, *Mechanical Vibrations*, 4th ed. 1956, ch. 3 (untuned viscous damper). The
    fixed point follows from :func:`untuned_magnification` being independent of ``g`` where
    ``(1 - r^2 - mu r^2)^2 = (1 - r^2)^2``; ``g_opt`` from a zero slope there.

    Examples
    --------
    >>> [round(float(x), 4) for x in untuned_optimum(1.0)]
    [0.2887, 0.8165, 3.0]
    """
    mu = positive("mass_ratio", mass_ratio)
    return (1.0 / np.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)), np.sqrt(2.0 / (2.0 + mu)),
            1.0 + 2.0 / mu)


def untuned_magnification(frequency_ratio: ArrayLike, mass_ratio: ArrayLike,
                          damping_ratio: ArrayLike) -> np.ndarray:
    """Magnification of an undamped primary system with an untuned viscous damper (2-DOF).

    ``xi = sqrt((4 g^2 r^2 + r^4) / (4 g^2 r^2 (1 - r^2 - mu r^2)^2 + r^4 (r^2 - 1)^2))``

    (the tuned absorber's expression with no absorber spring, Den Hartog 1956, ch. 3).

    Parameters
    ----------
    frequency_ratio : array_like [-]
        ``r = Omega / omega_n``, ``omega_n = sqrt(k / J)``.
    mass_ratio : array_like [-]
        ``mu = J_d / J``.
    damping_ratio : array_like [-]
        ``g = c / (2 J_d omega_n)``.

    Returns
    -------
    numpy.ndarray [-]
        ``|Theta_primary| / (T / k)``.
    """
    r2 = non_negative("frequency_ratio", frequency_ratio) ** 2
    mu = positive("mass_ratio", mass_ratio)
    g2 = non_negative("damping_ratio", damping_ratio) ** 2
    num = 4 * g2 * r2 + r2**2
    den = 4 * g2 * r2 * (1 - r2 - mu * r2) ** 2 + r2**2 * (r2 - 1) ** 2
    return np.sqrt(num / den)


def steady_temperature(ambient: ArrayLike, power: ArrayLike, heat_transfer: float,
                       area: float) -> np.ndarray:
    """Steady temperature of a damper whose heat leaves through its cooled surface [K].

    ``T = T_ambient + P / (h A)``: all the dissipated power crosses the cooled surface ``A``
    with the heat-transfer coefficient ``h`` to the surrounding air (Newton's law of cooling,
    Incropera et al. 2007, eq. 1.3a); the damper is one body at one temperature (no gradient
    from the film or rubber to the surface: the result is the mean temperature).

    Parameters
    ----------
    ambient : array_like [K]
    power : array_like [W]
    heat_transfer : float [W/(m^2 K)]
    area : float [m^2]
    """
    return np.asarray(ambient, float) + non_negative("power", power) / (
        float(positive("heat_transfer", heat_transfer)) * float(positive("area", area)))
