"""Bearing performance from the journal orbit: side leakage, pressure-fed flow, and the film
temperature of a heat balance.

Friction torque and power of the film: :func:`film_losses` (Couette shear over the full film
plus the load term, any pressure field: short bearing or finite length); peak film pressures are
:func:`checker.calc.mobility.short_bearing_peak_pressure` and
:func:`checker.calc.reynolds_map.film_state_map` (over an orbit:
:func:`checker.calc.film_pressure.peak_film_pressure_finite`). This module adds the flows
and the heat balance. All inputs SI; vectorised over any batch shape (bearing x load case x
speed x crank angle).

Frames: eccentricity vectors and angles in one frame fixed to the bearing shell (the orbit
frame of :mod:`checker.calc.orbit`); the film is thinnest in the direction of the
eccentricity vector, ``h(theta) = c (1 - eps cos(theta - phi))``.

References
----------
.. [1] F. W. Ocvirk, "Short-bearing approximation for full journal bearings", NACA TN 2808, 1952.
.. [2] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [3] R. G. Budynas, J. K. Nisbett, "Shigley's Mechanical Engineering Design", 9th ed.,
   McGraw-Hill, 2011, secs. 12-6, 12-9, 12-10 (film geometry, average film temperature, pressure-fed
   bearings).
.. [4] ISO 7902-1:2020 (DIN 31652-1:1983), "Hydrodynamic plain journal bearings under steady-state
   conditions - Circular cylindrical bearings - Part 1: Calculation procedure".
.. [5] B. J. Hamrock, S. R. Schmid, B. O. Jacobson, "Fundamentals of Fluid Film Lubrication", 2nd
   ed., 2004, ch. 10 (Petroff friction of the full film).
.. [6] H.-J. Butenschoen, "Das hydrodynamische, zylindrische Gleitlager endlicher Breite unter
   instationaerer Belastung", Dissertation, Universitaet Karlsruhe, 1976 (friction coefficient).
.. [7] P. M. Morse, H. Feshbach, "Methods of Theoretical Physics", 1953, ch. 7 (Green's functions by
   images; feed-hole flow).
.. [8] C. S. Cragoe, "Thermal properties of petroleum products", U.S. Bureau of Standards
   Miscellaneous Publication 97, 1929 (specific heat of oil).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from checker.calc import _checks

__all__ = [
    "film_losses",
    "short_bearing_side_flow",
    "groove_feed_flow",
    "hole_feed_flow",
    "rotating_hole_film_factor",
    "centrifugal_pressure_rise",
    "fixed_hole_film_factor",
    "crank_hole_radius",
    "cycle_mean_feed_flow",
    "start_temperature",
    "oil_specific_heat",
    "HeatBalance",
    "solve_heat_balance",
    "model_temperature",
    "HOLE_RATIO_MAX",
    "EFFECTIVE_TEMPERATURE_WEIGHT",
]

HOLE_RATIO_MAX = 0.5
"""Largest hole radius over its distance to the bearing edge for :func:`hole_feed_flow`
(the strip-source formula is within 2 % of a numerical solution up to this ratio, tests)."""

EFFECTIVE_TEMPERATURE_WEIGHT = 0.5
"""Effective film temperature = inlet + this fraction of the oil's temperature rise (mean of
inlet and outlet: ISO 7902-1 / DIN 31652-1 for pressure-fed bearings; Shigley's average film
temperature ``T1 + dT/2``)."""


def film_losses(
    eps_x: ArrayLike,
    eps_y: ArrayLike,
    force_x: ArrayLike,
    force_y: ArrayLike,
    vs_x: ArrayLike,
    vs_y: ArrayLike,
    omega_journal: ArrayLike,
    omega_bearing: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Friction torque on the journal and power dissipated in the film.

    .. math::

        T_J = -\\frac{2\\pi \\mu R^3 L (\\omega_J - \\omega_B)}{c\\sqrt{1-\\varepsilon^2}}
        + \\frac{c}{2}\\,(\\boldsymbol\\varepsilon \\times \\mathbf F)_z, \\qquad
        P = \\frac{2\\pi \\mu R^3 L (\\omega_J - \\omega_B)^2}{c\\sqrt{1-\\varepsilon^2}}
        + \\mathbf F\\cdot\\mathbf V_s

    (shear of the Couette flow over the full circumference, as in Butenschoen's friction
    coefficient ``mu/psi = pi/(sqrt(1 - eps^2) So) + eps sin(beta)/2`` for pure rotation;
    pressure-flow shear by integration by parts of ``int h/2 dp/dx``; its dissipation
    ``int h^3 |grad p|^2 / (12 mu) = F . V_s`` by the Reynolds equation).

    Parameters
    ----------
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector.
    force_x, force_y : array_like [N]
        Load carried by the film (:func:`film_force` or the mobility method's applied load).
    vs_x, vs_y : array_like [1/s]
        Squeeze velocity over clearance (as in :func:`film_force`).
    omega_journal, omega_bearing : array_like [rad/s]
        Angular velocities of journal and bearing (same frame).
    diameter, length, clearance, viscosity : array_like [m, m, m, Pa s]
        Geometry and viscosity.

    Returns
    -------
    torque : numpy.ndarray [N m]
        Friction torque the film exerts on the journal (about z; opposes ``omega_J -
        omega_B``).
    power : numpy.ndarray [W]
        Power dissipated in the film (>= 0).

    Notes
    -----
    Petroff limit at ``eps = 0``: ``T = 2 pi mu R^3 L (omega_J - omega_B) / c``. Assumption:
    the cavitated region transmits Couette shear as a full film (usual; a striated film
    transmits less, so the torque is an upper bound there). Validity: ``|eps| < 1``.
    """
    ex, ey, fx, fy, vx, vy, wj, wb = (_checks.finite(n, a) for n, a in (
        ("eps_x", eps_x), ("eps_y", eps_y), ("force_x", force_x), ("force_y", force_y),
        ("vs_x", vs_x), ("vs_y", vs_y), ("omega_journal", omega_journal),
        ("omega_bearing", omega_bearing)))
    dia, ln, cl, mu = (_checks.positive(n, a) for n, a in (
        ("diameter", diameter), ("length", length), ("clearance", clearance),
        ("viscosity", viscosity)))
    e2 = ex * ex + ey * ey
    if np.any(e2 >= 1.0):
        raise ValueError("eccentricity ratio must be < 1")
    r = 0.5 * dia
    dw = wj - wb
    couette = 2.0 * np.pi * mu * r**3 * ln * dw / (cl * np.sqrt(1.0 - e2))
    torque = -couette + 0.5 * cl * (ex * fy - ey * fx)
    power = couette * dw + cl * (fx * vx + fy * vy)
    return torque, power


def short_bearing_side_flow(
    vs_x: ArrayLike, vs_y: ArrayLike, diameter: ArrayLike, length: ArrayLike,
    clearance: ArrayLike,
) -> np.ndarray:
    """Hydrodynamic side leakage of a short (Ocvirk) pi-film bearing.

    .. math::

        Q = D\\,c\\,L\\,\\frac{|\\mathbf V_s|}{c}
          = D\\,c\\,L\\sqrt{\\dot\\varepsilon^2 + \\varepsilon^2(\\dot\\phi - \\bar\\omega)^2}

    The short-bearing Reynolds equation ``d/dz(h^3 dp/dz) = -12 mu V_s . n`` discharges the
    whole source of the pressurised half of the film (where the film closes) through the two
    edges: ``Q = R L int c |v| max(cos, 0) dtheta = D L c |v|``. Steady rotation with a fixed
    bearing (``|v| = eps omega / 2``) gives Ocvirk's ``Q = U c L eps`` with ``U = omega R``.

    Parameters
    ----------
    vs_x, vs_y : array_like [1/s]
        Squeeze velocity over clearance, ``V_s / c = d eps/dt - omega_bar z_hat x eps``.
    diameter : array_like [m]
        Journal diameter ``D``.
    length : array_like [m]
        Land length ``L`` (sum of both lands of a grooved bearing: each land leaks
        ``D c L_land |v|``).
    clearance : array_like [m]
        Radial clearance ``c``.

    Returns
    -------
    numpy.ndarray [m^3/s]
        Flow out of both edges (>= 0).

    Notes
    -----
    Ocvirk F.W. (1952), "Short-bearing approximation for full journal bearings", NACA TN 2808
    (steady side flow ``U c L eps``); squeeze form after Booker (1965), J. Basic Eng.
    87:537-546. Half-Sommerfeld (pi) film: the cavitated half is not mass-conserving, so the
    value is the leakage of the pressurised film only (as in the mobility method).
    """
    vx, vy = (_checks.finite(n, a) for n, a in (("vs_x", vs_x), ("vs_y", vs_y)))
    dia, ln, cl = (_checks.positive(n, a) for n, a in (
        ("diameter", diameter), ("length", length), ("clearance", clearance)))
    return dia * cl * ln * np.hypot(vx, vy)


def groove_feed_flow(
    eps_x: ArrayLike, eps_y: ArrayLike, supply_pressure: ArrayLike, viscosity: ArrayLike,
    diameter: ArrayLike, land_width: ArrayLike, clearance: ArrayLike, arc_start: ArrayLike,
    arc_end: ArrayLike,
) -> np.ndarray:
    """Pressure-driven flow out of a circumferential groove (full or partial) at supply pressure.

    .. math::

        Q = \\frac{p_s R}{6 \\mu b}\\int_{\\theta_1}^{\\theta_2} h^3\\,d\\theta, \\qquad
        h = c\\,(1 - \\varepsilon\\cos(\\theta - \\phi))

    Axial Poiseuille flow from the groove to both edges across lands of width ``b``. A full
    groove (``theta_2 = theta_1 + 2 pi``) gives Shigley's pressure-fed bearing flow
    ``Q = pi p_s D c^3 (1 + 1.5 eps^2) / (6 mu b)``.

    Parameters
    ----------
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector (``|eps| < 1``) in the bearing frame.
    supply_pressure : array_like [Pa]
        Oil pressure in the groove above the edge (ambient) pressure (>= 0).
    viscosity : array_like [Pa s]
        Dynamic viscosity.
    diameter : array_like [m]
        Journal diameter.
    land_width : array_like [m]
        Axial width ``b`` of one land, groove edge to bearing edge (centred groove: half the
        effective length).
    clearance : array_like [m]
        Radial clearance.
    arc_start, arc_end : array_like [rad]
        Groove arc in the bearing frame, counter-clockwise from start to end
        (``end - start`` in ``(0, 2 pi]``).
    Returns
    -------
    numpy.ndarray [m^3/s]

    Notes
    -----
    Budynas R.G., Nisbett J.K., Shigley's Mechanical Engineering Design, 9th ed., McGraw-Hill,
    2011, sec. 12-10 "Pressure-fed bearings" (full groove). For a partial groove only the flow
    axially out of the groove arc is counted (flow spreading beyond the groove ends is
    neglected): a lower bound of the feed flow, conservative for the film temperature. The
    pressure field of the rotating film is not superposed (the two flows are added by the
    caller). Validity: ``|eps| < 1``, ``b > 0``.
    """
    ex, ey = (_checks.finite(n, a) for n, a in (("eps_x", eps_x), ("eps_y", eps_y)))
    ps = _checks.non_negative("supply_pressure", supply_pressure)
    mu, dia, b, cl = (_checks.positive(n, a) for n, a in (
        ("viscosity", viscosity), ("diameter", diameter), ("land_width", land_width),
        ("clearance", clearance)))
    t1, t2 = (_checks.finite(n, a) for n, a in (("arc_start", arc_start), ("arc_end", arc_end)))
    span = np.asarray(t2 - t1, dtype=float)
    if np.any(span <= 0.0) or np.any(span > 2.0 * np.pi + 1e-9):
        raise ValueError("groove arc must satisfy 0 < arc_end - arc_start <= 2 pi")
    eps2 = ex * ex + ey * ey
    if np.any(eps2 >= 1.0):
        raise ValueError("eccentricity ratio must be < 1")
    if np.all(span == 2.0 * np.pi):  # full groove: 2 pi (1 + 1.5 eps^2), no trigonometry
        integral = (2.0 * np.pi) * (1.0 + 1.5 * eps2)
    else:
        integral = _cubed_film_integral(ex, ey, eps2, np.asarray(t1, dtype=float),
                                        np.asarray(t2, dtype=float), span)
    return ps * 0.5 * dia * cl**3 * integral / (6.0 * mu * b)


def _cubed_film_integral(ex: np.ndarray, ey: np.ndarray, eps2: np.ndarray, t1: np.ndarray,
                         t2: np.ndarray, span: np.ndarray) -> np.ndarray:
    """``int_{t1}^{t2} (1 - eps cos(t - phi))^3 dt`` (``eps (cos phi, sin phi) = (ex, ey)``,
    ``span = t2 - t1``) in closed form without trigonometry of the eccentricity.

    With ``u = t - phi`` the expanded cubic integrates to ``P(u) = u (1 + 1.5 eps^2) -
    3 eps sin u + 0.75 eps^2 sin 2u - eps^3 (sin u - sin^3 u / 3)`` (``int cos^2 = u/2 +
    sin 2u / 4``, ``int cos^3 = sin u - sin^3 u / 3``); with ``a = eps sin u = ex sin t -
    ey cos t`` and ``c = eps cos u = ex cos t + ey sin t`` (the groove ends ``t`` are
    scalars per bearing, so the only trigonometry is of them) it is the polynomial
    ``u (1 + 1.5 eps^2) - 3 a + 1.5 a c - eps^2 a + a^3 / 3``."""

    def ends(t):
        st, ct = np.sin(t), np.cos(t)
        a = ex * st - ey * ct
        c = ex * ct + ey * st
        return a * (1.5 * c - 3.0 - eps2) + a * a * a / 3.0

    return span * (1.0 + 1.5 * eps2) + ends(t2) - ends(t1)


def hole_feed_flow(
    film: ArrayLike, supply_pressure: ArrayLike, viscosity: ArrayLike, hole_diameter: ArrayLike,
    edge_distance: ArrayLike,
) -> np.ndarray:
    """Pressure-driven flow out of one circular feed hole into a film of uniform thickness.

    .. math::

        Q = \\frac{h^3}{12\\mu}\\,\\frac{2\\pi\\,p_s}{\\ln\\left(\\frac{4 b}{\\pi a}\\right)}

    Potential flow of a source at the middle of a strip of half width ``b`` with zero pressure
    on both edges (the strip's Green's function ``(1/2pi) ln|coth(pi w / 4b)|`` near the source
    is ``(1/2pi) ln(4b / (pi r))``), the hole of radius ``a`` held at ``p_s``.

    Parameters
    ----------
    film : array_like [m]
        Film thickness at the hole (> 0).
    supply_pressure : array_like [Pa]
        Pressure in the hole above ambient (>= 0).
    viscosity : array_like [Pa s]
    hole_diameter : array_like [m]
        ``2 a``.
    edge_distance : array_like [m]
        Axial distance ``b`` from the hole centre to either bearing edge (centred hole: half
        the effective length).

    Returns
    -------
    numpy.ndarray [m^3/s]

    Raises
    ------
    ValueError
        ``a / b`` above :data:`HOLE_RATIO_MAX` (outside the formula's validity).

    Notes
    -----
    Conformal-mapping solution of Laplace's equation for a line source in a strip (e.g.
    Morse P.M., Feshbach H., Methods of Theoretical Physics, 1953, ch. 7, Green's functions
    by images); tested against a finite-difference solution of the Reynolds equation of the
    feed (uniform film): within 2 % for ``a / b <= 0.5``. The film's wedge and squeeze flows
    are not superposed (the caller adds the hydrodynamic side leakage).
    """
    h = _checks.positive("film", film)
    ps = _checks.non_negative("supply_pressure", supply_pressure)
    mu, dh, b = (_checks.positive(n, a) for n, a in (
        ("viscosity", viscosity), ("hole_diameter", hole_diameter),
        ("edge_distance", edge_distance)))
    a = 0.5 * dh
    if np.any(a / b > HOLE_RATIO_MAX + 1e-12):
        raise ValueError(f"hole radius / edge distance must be <= {HOLE_RATIO_MAX}"
                         f" (found {float(np.max(a / b)):.3g})")
    return h**3 / (12.0 * mu) * 2.0 * np.pi * ps / np.log(4.0 * b / (np.pi * a))


def rotating_hole_film_factor(eps: ArrayLike) -> np.ndarray:
    """Mean of ``(h / c)^3`` seen by a hole that turns relative to the film.

    .. math::

        \\frac{1}{2\\pi}\\int_0^{2\\pi} (1 - \\varepsilon\\cos u)^3\\,du = 1 + 1.5\\,\\varepsilon^2

    (a journal hole sweeps every angle of the film each revolution relative to the shell).

    Parameters
    ----------
    eps : array_like [-]
        Eccentricity ratio, ``0 <= eps < 1``.

    Returns
    -------
    numpy.ndarray [-]
    """
    e = _checks.non_negative("eps", eps)
    if np.any(e >= 1.0):
        raise ValueError("eccentricity ratio must be < 1")
    return 1.0 + 1.5 * e * e


def centrifugal_pressure_rise(
    density: ArrayLike, omega: ArrayLike, r_outer: ArrayLike, r_inner: ArrayLike,
) -> np.ndarray:
    """Pressure rise of oil in a crank drilling turning with the crank.

    .. math:: \\Delta p = \\tfrac12 \\rho\\,\\omega^2 (r_2^2 - r_1^2)

    (hydrostatics of a liquid in rigid-body rotation, no flow losses).

    Parameters
    ----------
    density : array_like [kg/m^3]
    omega : array_like [rad/s]
        Crank angular velocity.
    r_outer, r_inner : array_like [m]
        Radii from the crank axis of the outlet (pin hole) and the inlet (main journal
        surface).

    Returns
    -------
    numpy.ndarray [Pa]
    """
    rho = _checks.positive("density", density)
    w = _checks.finite("omega", omega)
    r2, r1 = (_checks.non_negative(n, a) for n, a in (("r_outer", r_outer),
                                                      ("r_inner", r_inner)))
    return 0.5 * rho * w * w * (r2 * r2 - r1 * r1)


def oil_specific_heat(temperature: ArrayLike, density_15: ArrayLike) -> np.ndarray:
    """Specific heat of a petroleum oil (Cragoe's correlation).

    .. math::

        c_p = \\frac{1684 + 3.39\\,(T - 273.15)}{\\sqrt{s}}\\ \\mathrm{J/(kg\\,K)},
        \\qquad s = \\rho_{15} / 999\\ \\mathrm{kg/m^3}

    Parameters
    ----------
    temperature : array_like [K]
        Oil temperature (accepted 0..400 °C).
    density_15 : array_like [kg/m^3]
        Density at 15 °C (accepted specific gravity ``s`` 0.7..1.0).

    Returns
    -------
    numpy.ndarray [J/(kg K)]

    Notes
    -----
    Cragoe C.S. (1929), "Thermal properties of petroleum products", U.S. Bureau of Standards
    Miscellaneous Publication 97: ``c = (0.388 + 0.00045 t) / sqrt(s)`` Btu/(lb °F) with ``t``
    in °F, converted to SI.
    """
    t = _checks.positive("temperature", temperature)
    rho = _checks.positive("density_15", density_15)
    tc = t - 273.15
    if np.any(tc < -1e-9) or np.any(tc > 400.0):
        raise ValueError("temperature outside 0..400 °C (Cragoe's correlation)")
    s = rho / 999.0
    if np.any(s < 0.7) or np.any(s > 1.0):
        raise ValueError("specific gravity outside 0.7..1.0 (Cragoe's correlation)")
    return (1684.0 + 3.39 * tc) / np.sqrt(s)


@dataclass(frozen=True)
class HeatBalance:
    """Result of :func:`solve_heat_balance` (arrays with the batch shape).

    Attributes
    ----------
    temperature : numpy.ndarray [K]
        Effective film temperature (the last evaluated temperature).
    converged : numpy.ndarray of bool
        ``|T_next - T| <= tol`` at the last evaluation.
    change : numpy.ndarray [K]
        Last change ``|T_next - T|``.
    evaluations : int
        Calls of ``evaluate``.
    state : object
        What ``evaluate`` returned at ``temperature`` (its full result).
    """

    temperature: np.ndarray
    converged: np.ndarray
    change: np.ndarray
    evaluations: int
    state: object


def model_temperature(t_supply, a, qs, d, rho_cp, k, viscosity_of, t_hi=None):
    """Fixed point of the local heat-balance model ``T = T_s + k a mu(T) / (rho_cp (qs + d /
    mu(T)))`` (friction power ``a mu`` [W], flow ``qs + d / mu`` [m^3/s]) by bisection: the
    right-hand side decreases in ``T``, so the root lies in ``[T_s, T_s + k a mu(T_s) /
    (rho_cp (qs + d / mu(T_s)))]``."""
    if t_hi is None:
        mu_s = viscosity_of(t_supply)
        t_hi = t_supply + k * a * mu_s / (rho_cp * (qs + d / mu_s))
    lo = np.array(t_supply, dtype=float)
    hi = np.array(t_hi, dtype=float)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        mu = viscosity_of(mid)
        g = t_supply + k * a * mu / (rho_cp * (qs + d / mu)) - mid
        up = g > 0.0
        lo = np.where(up, mid, lo)
        hi = np.where(up, hi, mid)
    return 0.5 * (lo + hi)


def solve_heat_balance(
    evaluate: Callable[[np.ndarray], tuple],
    t_supply: ArrayLike,
    viscosity_of: Callable[[np.ndarray], np.ndarray],
    *,
    heat_to_oil: float = 1.0,
    weight: float = EFFECTIVE_TEMPERATURE_WEIGHT,
    tol: float = 0.1,
    max_evaluations: int = 8,
    t_start: ArrayLike | None = None,
    partial: bool = False,
) -> HeatBalance:
    """Effective film temperature of a bearing whose friction heat leaves with its oil flow.

    .. math::

        T = T_s + w\\,\\frac{f\\,P(T)}{\\rho c_p\\,Q(T)}, \\qquad Q = Q_{side} + Q_{feed}

    ``P`` friction power, ``Q`` oil flow, ``f`` fraction of the heat carried by the oil,
    ``w`` the weight of the outlet rise in the effective temperature (0.5: mean of inlet and
    outlet). Viscosity couples ``P`` and ``Q`` to ``T``.

    Iteration: each evaluation at ``T_k`` gives ``P``, ``Q_side``, ``Q_feed`` and ``rho c_p``;
    the local model ``P = a mu(T)``, ``Q = Q_side + d / mu(T)`` (Petroff shear, Poiseuille
    feed) with ``a, d`` from that evaluation is solved exactly for ``T_{k+1}`` (bisection on a
    monotone function, so no oscillation); the iteration stops when ``|T_{k+1} - T_k| <=
    tol``. The returned ``T_k`` is the evaluated state (its ``P`` and ``Q`` belong to it); its
    distance to the true fixed point is about ``tol / (1 - slope)`` of the balance (tests: at
    most 2.3 ``tol`` in the balance residual), 0.2 K at the default 0.1 K.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(T) -> (P [W], Q_side [m^3/s], Q_feed [m^3/s], rho_cp [J/(m^3 K)], state)``,
        arrays of the batch shape, for film temperatures ``T`` [K] of that shape.
    t_supply : array_like [K]
        Oil supply (inlet) temperature, batch shape.
    viscosity_of : callable
        ``mu(T)`` [Pa s], vectorised, decreasing in ``T``.
    heat_to_oil : float [-]
        Fraction ``f`` of the friction heat carried away by the oil (0..1; 1: no heat
        conducted to journal and housing, the conservative usual assumption).
    weight : float [-]
        ``w``; default :data:`EFFECTIVE_TEMPERATURE_WEIGHT`.
    tol : float [K]
        Convergence tolerance on the temperature.
    max_evaluations : int
        Evaluations before the points still changing are reported as not converged.
    t_start : array_like [K], optional
        First temperature evaluated (default ``t_supply``); a close estimate saves an
        evaluation, the result does not depend on it beyond ``tol``.
    partial : bool
        Evaluate again only the points still iterating: ``evaluate(T, active)`` with
        ``active`` None (every point) or a boolean mask of the batch shape; the points outside
        the mask must be returned as at their last evaluation (they are converged and keep
        their temperature, change and state). Saves the orbits of the converged points when
        a few need one more evaluation.

    Returns
    -------
    HeatBalance

    Notes
    -----
    Heat balance of a pressure-fed bearing with the effective temperature as the mean of inlet
    and outlet: ISO 7902-1:2020 (DIN 31652-1:1983), "Hydrodynamic plain journal bearings
    under steady-state conditions - Circular cylindrical bearings - Part 1: Calculation
    procedure"; Budynas and Nisbett, Shigley's Mechanical Engineering Design, 9th ed., 2011,
    sec. 12-9 (``T_av = T_1 + dT/2``). A bearing with no oil flow has no balance (``Q > 0``
    required). With a Petroff power and a constant flow the fixed point is
    ``T = T_s + W(...)/beta`` in closed form (Lambert W; tests).
    """
    if not 0.0 < heat_to_oil <= 1.0:
        raise ValueError("heat_to_oil must be in (0, 1]")
    if not 0.0 < weight <= 1.0:
        raise ValueError("weight must be in (0, 1]")
    ts = _checks.positive("t_supply", t_supply)
    k = weight * heat_to_oil
    t = np.array(ts if t_start is None else np.broadcast_to(
        _checks.positive("t_start", t_start), ts.shape), dtype=float)
    change = np.full(t.shape, np.inf)
    conv = np.zeros(t.shape, dtype=bool)
    state = None
    n = 0
    active = None
    for n in range(1, int(max_evaluations) + 1):
        p, qs, qf, rho_cp, state = evaluate(t, active) if partial else evaluate(t)
        p, qs, qf, rho_cp = (np.broadcast_to(np.asarray(x, dtype=float), t.shape)
                             for x in (p, qs, qf, rho_cp))
        q = qs + qf
        if np.any(q <= 0.0) or np.any(p < 0.0):
            raise ValueError("heat balance needs an oil flow > 0 and a friction power >= 0")
        mu = viscosity_of(t)
        a = p / mu
        d = qf * mu
        t_hi = ts + k * a * viscosity_of(ts) / (rho_cp * (qs + d / viscosity_of(ts)))
        t_next = model_temperature(ts, a, qs, d, rho_cp, k, viscosity_of, t_hi)
        new_change = np.abs(t_next - t)
        if active is None:
            change = new_change
            conv = change <= tol
        else:  # converged points were not evaluated again: they keep their change
            change = np.where(active, new_change, change)
            conv = np.where(active, new_change <= tol, conv)
        if conv.all() or n == int(max_evaluations):
            break
        t = np.where(conv, t, t_next)
        if partial:
            active = ~conv
    return HeatBalance(t, conv, change, n, state)


def fixed_hole_film_factor(eps_x: ArrayLike, eps_y: ArrayLike, hole_angle: float) -> np.ndarray:
    """``(h / c)^3`` at a feed hole fixed in the bearing shell.

    .. math:: \\left(\\frac{h}{c}\\right)^3 = (1 - \\varepsilon_x\\cos\\varphi
              - \\varepsilon_y\\sin\\varphi)^3

    (film ``h = c (1 - eps cos(theta - phi_eps))`` at the hole angle ``theta = phi``).

    Parameters
    ----------
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector in the bearing frame (``|eps| <= 1``), any shape.
    hole_angle : float [rad]
        Angle of the hole in the bearing frame (from the frame's X axis, counter-clockwise).

    Returns
    -------
    numpy.ndarray [-]
        Shape of ``eps_x``.

    Notes
    -----
    Film geometry of the plain journal bearing (Budynas and Nisbett, Shigley's Mechanical
    Engineering Design, 9th ed., 2011, sec. 12-6). Validity: ``|eps| <= 1`` (a touching film,
    ``|eps| = 1`` at the hole, has no hole flow).

    Examples
    --------
    >>> float(fixed_hole_film_factor(0.5, 0.0, 0.0))  # hole at the thinnest film
    0.125
    """
    ex, ey = (_checks.finite(n, a) for n, a in (("eps_x", eps_x), ("eps_y", eps_y)))
    if np.any(ex * ex + ey * ey > 1.0 + 1e-12):
        raise ValueError("eccentricity ratio must be <= 1")
    phi = float(hole_angle)
    return (1.0 - ex * np.cos(phi) - ey * np.sin(phi))**3


def crank_hole_radius(crank_radius: ArrayLike, pin_radius: ArrayLike,
                      hole_angle: ArrayLike) -> np.ndarray:
    """Distance from the crank axis of the outlet of an oil hole on a crank pin's surface.

    .. math:: r_h = \\sqrt{r^2 + R_p^2 + 2\\,r R_p \\cos\\varphi}

    (law of cosines in the crank throw's plane).

    Parameters
    ----------
    crank_radius : array_like [m]
        ``r``: half the stroke (crank axis to pin centre).
    pin_radius : array_like [m]
        ``R_p``: half the pin diameter.
    hole_angle : array_like [rad]
        ``phi``: angle of the hole on the pin, measured at the pin centre from the crank
        radius pointing away from the crank axis (0: the pin's outermost point).

    Returns
    -------
    numpy.ndarray [m]

    Examples
    --------
    >>> round(float(crank_hole_radius(0.04, 0.02, 0.0)), 12)  # outermost point: r + R_p
    0.06
    """
    r = _checks.non_negative("crank_radius", crank_radius)
    rp = _checks.non_negative("pin_radius", pin_radius)
    phi = _checks.finite("hole_angle", hole_angle)
    return np.sqrt(r * r + rp * rp + 2 * r * rp * np.cos(phi))


def cycle_mean_feed_flow(
    eps_x: ArrayLike, eps_y: ArrayLike, viscosity: ArrayLike, supply_pressure: float,
    diameter: float, length: float, clearance: float, *, full_groove: bool = False,
    groove_arc: tuple[float, float] | None = None, holes: int = 0,
    hole_diameter: float | None = None, hole_angle: float | None = None,
    hole_pressure_rise: ArrayLike | None = None,
) -> np.ndarray:
    """Cycle-mean pressure-fed oil flow of one bearing: full groove, partial groove and feed
    holes superposed.

    .. math::

        \\bar Q = \\overline{Q_{groove}(\\varepsilon(t))}
        + n_h\\,Q_{hole}\\!\\left(c\\,\\sqrt[3]{\\overline{(h/c)^3}},\\ p_s + \\Delta p\\right)

    * full groove: :func:`groove_feed_flow` over ``0..2 pi`` across both lands (land width
      ``L/2``), averaged over the orbit;
    * partial groove: :func:`groove_feed_flow` over the groove arc (an end below the start
      wraps by ``2 pi``), averaged over the orbit;
    * holes: :func:`hole_feed_flow` (``n_h`` holes, edge distance ``L/2``) in the film whose
      cube is the orbit's mean ``(h/c)^3`` at the hole: :func:`fixed_hole_film_factor` for a
      hole fixed in the shell (``hole_angle`` given), :func:`rotating_hole_film_factor` for a
      hole turning relative to the film (journal hole; ``hole_angle`` None); hole pressure
      ``p_s`` plus ``hole_pressure_rise`` (the centrifugal rise of a crank drilling,
      :func:`centrifugal_pressure_rise`), negative pressures taken as zero.

    Parameters
    ----------
    eps_x, eps_y : array_like [-]
        Eccentricity ratio along the orbit in the bearing frame, shape ``(..., angle)``.
    viscosity : array_like [Pa s]
        Dynamic viscosity, shape ``(...)``.
    supply_pressure : float [Pa]
        Oil supply pressure (gauge, >= 0).
    diameter, length, clearance : float [m]
        Journal diameter, effective bearing length, radial clearance.
    full_groove : bool
        A full circumferential groove in the middle of the bearing.
    groove_arc : (float, float) [rad], optional
        Start and end of a partial groove in the bearing frame.
    holes : int
        Number of feed holes (0: none).
    hole_diameter : float [m]
        Diameter of each hole (required with ``holes > 0``).
    hole_angle : float [rad], optional
        Angle of a hole fixed in the shell; None: the hole turns relative to the film.
    hole_pressure_rise : array_like [Pa], optional
        Pressure added to the supply pressure in the hole, broadcast to ``(...)``.

    Returns
    -------
    numpy.ndarray [m^3/s]
        Shape ``(...)`` (the viscosity's shape).

    Notes
    -----
    Groove flow: Budynas and Nisbett, Shigley's Mechanical Engineering Design, 9th ed., 2011,
    sec. 12-10; hole flow: line source in a strip (see :func:`hole_feed_flow`). The feeds and
    the hydrodynamic film are superposed (they interact through the film's boundary
    conditions: an approximation of concept level). Validity: that of the functions used
    (``|eps| < 1``; hole radius / edge distance <= :data:`HOLE_RATIO_MAX`).
    """
    ex = np.asarray(eps_x, dtype=float)
    ey = np.asarray(eps_y, dtype=float)
    mu = np.asarray(viscosity, dtype=float)
    mu4 = mu[..., None]
    q = np.zeros(mu.shape)
    if full_groove:
        q += groove_feed_flow(ex, ey, supply_pressure, mu4, diameter, 0.5 * length, clearance,
                              0.0, 2.0 * np.pi).mean(axis=-1)
    if groove_arc is not None:
        t1, t2 = groove_arc
        t2 = t2 if t2 > t1 else t2 + 2.0 * np.pi
        q += groove_feed_flow(ex, ey, supply_pressure, mu4, diameter, 0.5 * length, clearance,
                              t1, t2).mean(axis=-1)
    if holes:
        if hole_diameter is None:
            raise ValueError("hole_diameter is required with holes > 0")
        p_hole = np.full(mu.shape, float(supply_pressure))
        if hole_angle is None:
            h3 = rotating_hole_film_factor(np.sqrt(ex**2 + ey**2)).mean(axis=-1)
        else:
            h3 = fixed_hole_film_factor(ex, ey, hole_angle).mean(axis=-1)
        if hole_pressure_rise is not None:
            p_hole = p_hole + hole_pressure_rise
        q += holes * hole_feed_flow(clearance * np.cbrt(h3), np.maximum(p_hole, 0.0), mu,
                                    hole_diameter, 0.5 * length)
    return q


def start_temperature(
    t_supply: ArrayLike, omega_journal: ArrayLike, omega_bearing: ArrayLike,
    diameter: ArrayLike, length: ArrayLike, clearance: ArrayLike, feed_coefficient: ArrayLike,
    rho_cp: ArrayLike, heat_to_oil: float, viscosity_of: Callable[[np.ndarray], np.ndarray],
    eps: float = 0.6,
) -> np.ndarray:
    """First estimate of the effective film temperature for :func:`solve_heat_balance`:
    the balance of a film at a fixed eccentricity, solved exactly.

    .. math::

        P = \\frac{2\\pi R^3 L\\,\\mu}{c\\sqrt{1-\\varepsilon^2}}\\,\\overline{\\Delta\\omega^2},
        \\qquad Q = D c L\\,\\varepsilon\\,\\overline{|\\bar\\omega|} + d / \\mu,
        \\qquad T = T_s + \\tfrac12 f\\,\\frac{P(T)}{\\rho c_p Q(T)}

    Couette (Petroff) friction of the full film at eccentricity ``eps``, steady short-bearing
    side leakage ``U c L eps`` (``U = R (omega_J + omega_B)``), the feed flow at unit viscosity
    ``d`` (``Q_feed mu``, concentric); solved by :func:`model_temperature`. Usually a few
    kelvin from the balance: saves an orbit evaluation; the balance does not depend on it
    beyond its tolerance.

    Parameters
    ----------
    t_supply : array_like [K]
        Oil supply temperature, batch shape ``(...)``.
    omega_journal, omega_bearing : array_like [rad/s]
        Angular velocities of journal and shell over the cycle, shape ``(..., angle)``.
    diameter, length, clearance : array_like [m]
        Broadcastable to ``(...)``.
    feed_coefficient : array_like [m^3 Pa]
        ``d = Q_feed mu`` of the concentric film (0 without feed).
    rho_cp : array_like [J/(m^3 K)]
        Volumetric heat capacity of the oil at ``t_supply``.
    heat_to_oil : float [-]
        Fraction ``f`` of the heat carried away by the oil.
    viscosity_of : callable
        ``mu(T)`` [Pa s], decreasing.
    eps : float [-]
        Eccentricity ratio of the estimate (0 <= eps < 1).

    Returns
    -------
    numpy.ndarray [K]

    Notes
    -----
    Petroff N.P. (1883) friction with the ``1/sqrt(1 - eps^2)`` factor of the full film
    (Hamrock, Schmid and Jacobson, Fundamentals of Fluid Film Lubrication, 2nd ed., 2004,
    ch. 10); side leakage: Ocvirk 1952; heat balance: ISO 7902-1:2020.
    """
    if not 0.0 <= eps < 1.0:
        raise ValueError("eps must be in [0, 1)")
    dia = _checks.positive("diameter", diameter)
    ln = _checks.positive("length", length)
    cl = _checks.positive("clearance", clearance)
    wj = _checks.finite("omega_journal", omega_journal)
    wb = _checks.finite("omega_bearing", omega_bearing)
    a = (2.0 * np.pi * (0.5 * dia) ** 3 * ln / cl / np.sqrt(1.0 - eps**2)
         * ((wj - wb) ** 2).mean(axis=-1))
    qs = dia * cl * ln * eps * np.abs(0.5 * (wj + wb)).mean(axis=-1)
    return model_temperature(t_supply, a, qs, feed_coefficient, rho_cp,
                             EFFECTIVE_TEMPERATURE_WEIGHT * heat_to_oil, viscosity_of)

