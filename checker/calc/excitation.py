"""Torsional excitation of a crank train: cylinder torque harmonics, phasing and vector sums.

Complex amplitude convention (used by every function here and in :mod:`checker.calc.torsional`)
-------------------------------------------------------------------------------------------------
A periodic quantity of the crank angle ``theta`` [rad] (4-stroke cycle ``0 <= theta < 4*pi``) is

    T(theta) = c_0/2 + sum_n Re{ c_n * exp(+j * n * theta) },     n = 0.5, 1, 1.5, ...

so ``|c_n|`` is the 0-to-peak amplitude of order ``n`` and ``arg(c_n)`` its phase: order ``n``
is ``|c_n| cos(n theta + arg c_n)``. ``theta`` is measured from firing TDC of cylinder 1 in the
direction of rotation (see ``docs/calc-conventions.md``); with the crank at constant speed
``omega``, ``theta = omega t`` and order ``n`` oscillates at ``n * omega`` [rad/s].

Sign of torque: positive torque drives the crankshaft in its direction of rotation (gas torque is
positive during the expansion stroke).

Phasing: cylinder ``i`` fires ``phi_i`` [rad] of crank angle after cylinder 1, so its torque is
``T_i(theta) = T_1(theta - phi_i)`` and its complex order-``n`` amplitude is
``F_{i,n} = c_n exp(-j n phi_i)`` (Ker Wilson, *Practical Solution of Torsional Vibration
Problems*, Vol. 2, ch. 19).

References
----------
.. [1] W. Ker Wilson, "Practical Solution of Torsional Vibration Problems", Vol. 2, ch. 19 (phasing
   of cylinder excitation, vector sums).
.. [2] L. Drapal, P. Novotny, "Torsional vibration analysis of crank train with low friction
   losses", J. Vibroeng. 19(7), 2017, doi:10.21595/jve.2017.17876, eq. 1 (discrete Fourier series).
.. [3] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, sec. 2.2.
.. [4] C. F. Taylor, "The Internal-Combustion Engine in Theory and Practice", Vol. 2, 1985, ch. 8
   (inertia torque harmonics).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from checker.calc.kinematics import FOUR_STROKE_CYCLE, slider_kinematics

__all__ = [
    "DEFAULT_MAX_ORDER",
    "gas_torque",
    "inertia_torque_series",
    "inertia_torque_series_coefficients",
    "major_order_mask",
    "phase_cylinders",
    "reciprocating_inertia_torque",
    "torque_harmonics",
    "vector_sum",
]

#: Highest harmonic order kept by default [-]. benchmarks/bench_tv.py (example I4 with rubber
#: damper, full load, 61 speeds 1000-7000 rpm, reference: orders to 48 on a 0.25 deg grid):
#: truncation at 24 changes the synthesised crank-nose amplitude by <= 0.03 % (1e-4 deg) and the
#: synthesised flywheel-side element torque by <= 0.15 %; at 16 by 0.45 % / 1.4 %, at 12 by
#: 2.2 % / 7.9 %. Orders kept are unaffected by truncation (linear model). The TV sweep takes
#: 35-50 ms at 24 orders (70 ms at 48) on the shared 2-core development machine. Order 24 also
#: covers the 18-24 orders commonly used for V6 crank-nose checks.
DEFAULT_MAX_ORDER = 24.0


def torque_harmonics(
    torque: ArrayLike,
    max_order: float = DEFAULT_MAX_ORDER,
    cycle: float = FOUR_STROKE_CYCLE,
) -> tuple[np.ndarray, np.ndarray]:
    """Complex harmonic coefficients of a periodic torque sampled over one cycle.

    ``c = rfft(T) * 2/N``; FFT bin ``m`` is order ``n = m * 2*pi/cycle`` (``m/2`` for a 4-stroke
    cycle), so that ``T(theta) = c_0/2 + sum_n Re{c_n exp(j n theta)}`` (module docstring).

    Parameters
    ----------
    torque : array_like, shape (..., N) [N*m]
        Torque at ``theta_k = k * cycle / N`` (no duplicated end point), crank angle last.
    max_order : float [-]
        Highest order returned; requires ``N > 2 * m_max`` with ``m_max = max_order*cycle/(2 pi)``
        (strictly below the Nyquist bin, where the factor 2 would be wrong).
    cycle : float [rad]
        Cycle length (``4*pi`` default).

    Returns
    -------
    orders : numpy.ndarray, shape (n_order,) [-]
        ``0.5, 1, 1.5, ..., max_order`` for a 4-stroke cycle (the mean, order 0, is excluded; it
        is ``torque.mean(-1)``).
    coeffs : numpy.ndarray, shape (..., n_order), complex [N*m]
        ``c_n``.

    Notes
    -----
    Discrete Fourier series (e.g. Drapal & Novotny 2017, J. Vibroeng. 19(7), eq. 1, whose sign
    of the exponent is the complex conjugate of the one used here). Exact for a band-limited
    signal; otherwise the coefficients contain aliasing from orders above ``N/2 * 2pi/cycle``.
    """
    t = np.asarray(torque, dtype=float)
    if t.ndim < 1:
        raise ValueError("torque must have a crank-angle axis (last axis)")
    n_pts = t.shape[-1]
    if not np.all(np.isfinite(t)):
        raise ValueError("torque contains non-finite values")
    step = 2.0 * np.pi / cycle  # order per FFT bin
    m_max = int(round(max_order / step))
    if m_max < 1 or abs(m_max * step - max_order) > 1e-9 * max(1.0, max_order):
        raise ValueError(
            f"max_order must be a positive multiple of {step:g} for this cycle, got {max_order!r}"
        )
    if 2 * m_max >= n_pts:
        raise ValueError(
            f"{n_pts} points per cycle resolve orders below {n_pts / 2 * step:g} only; "
            f"max_order={max_order:g} needs more than {2 * m_max} points"
        )
    spec = np.fft.rfft(t, axis=-1)[..., 1 : m_max + 1] * (2.0 / n_pts)
    orders = np.arange(1, m_max + 1) * step
    return orders, spec


def gas_torque(
    theta: ArrayLike,
    pressure: ArrayLike,
    bore: float,
    crank_radius: float,
    rod_length: float,
    crankcase_pressure: float = 0.0,
) -> np.ndarray:
    """Crankshaft torque of the gas force of one cylinder (zero offsets; helper for tests).

    ``T_g = (p - p_cc) A_p dx/dtheta = (p - p_cc) A_p r sin(theta) [1 + lam cos(theta)/
    sqrt(1 - lam^2 sin^2 theta)]`` with ``x`` the piston displacement from TDC toward the crank
    (:func:`checker.calc.kinematics.slider_kinematics`; Heywood 1988,
    sec. 2.2). The full per-cylinder torque with offsets and con-rod dynamics is
    :func:`checker.calc.crank_forces.cylinder_loads` (``.torque``).

    Parameters
    ----------
    theta : array_like [rad]
        Crank angle from firing TDC.
    pressure : array_like [Pa]
        Absolute cylinder pressure at ``theta`` (broadcast with it).
    bore : float [m]
        Cylinder bore.
    crank_radius, rod_length : float [m]
        Crank throw and connecting-rod length.
    crankcase_pressure : float [Pa]
        Pressure under the piston (0: absolute pressure on the crown only).

    Returns
    -------
    numpy.ndarray [N*m]
        Positive when driving the crank.
    """
    if not bore > 0:
        raise ValueError(f"bore must be > 0 m, got {bore!r}")
    p = np.asarray(pressure, dtype=float)
    if np.any(p < 0):
        raise ValueError("pressure must be >= 0 Pa (absolute)")
    kin = slider_kinematics(theta, crank_radius, rod_length)
    return (p - crankcase_pressure) * (np.pi * bore**2 / 4.0) * kin.dx_dtheta


def reciprocating_inertia_torque(
    theta: ArrayLike,
    reciprocating_mass: float,
    crank_radius: float,
    rod_length: float,
    omega: ArrayLike,
) -> np.ndarray:
    """Exact crank torque of the reciprocating mass at constant crank speed (zero offsets).

    ``T_i = -m_rec omega^2 x''(theta) x'(theta)`` (``x`` from
    :func:`checker.calc.kinematics.slider_kinematics`).

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Crank angle from TDC (last axis of the result).
    reciprocating_mass : float [kg]
        Piston assembly plus reciprocating share of the connecting rod.
    crank_radius, rod_length : float [m]
    omega : array_like, shape (...) [rad/s]
        Mean crank speed; leading axes of the result.

    Returns
    -------
    numpy.ndarray, shape (..., N) [N*m]
    """
    if reciprocating_mass < 0:
        raise ValueError("reciprocating_mass must be >= 0 kg")
    kin = slider_kinematics(theta, crank_radius, rod_length)
    w = np.asarray(omega, dtype=float)[..., np.newaxis]
    return -reciprocating_mass * w**2 * kin.d2x_dtheta2 * kin.dx_dtheta


def inertia_torque_series_coefficients(lam: float) -> tuple[np.ndarray, np.ndarray]:
    """Closed-form series of the reciprocating inertia torque, correct to ``O(lam^5)``.

    ``T_i / (m_rec r^2 omega^2) = sum_n b_n sin(n theta)``, n = 1..12 (terms above 6 are
    products of truncated series and are ``O(lam^6)``).

    Derivation: ``x''/r = -(cos t + A2 cos 2t - A4 cos 4t + A6 cos 6t)``, ``x'/r = -(sin t +
    A2/2 sin 2t - A4/4 sin 4t + A6/6 sin 6t)`` with ``A2 = lam + lam^3/4 + 15 lam^5/128``,
    ``A4 = lam^3/4 + 3 lam^5/16``, ``A6 = 9 lam^5/128`` (binomial series of the rod root; e.g.
    Taylor, *The Internal-Combustion Engine in Theory and Practice*, Vol. 2, ch. 8), and
    ``T_i = -m omega^2 x'' x'``. Leading terms: ``b1 = lam/4 + lam^3/16``, ``b2 = -(1/2 +
    lam^4/32)``, ``b3 = -(3 lam/4 + 9 lam^3/32)``, ``b4 = -(lam^2/4 + lam^4/8)``, ``b5 =
    5 lam^3/32``.

    Parameters
    ----------
    lam : float [-]
        Crank ratio ``r/l``, ``0 <= lam < 1`` (series meaningful for ``lam <~ 0.4``).

    Returns
    -------
    orders : numpy.ndarray, shape (12,) [-]
        1, 2, ..., 12.
    b : numpy.ndarray, shape (12,) [-]
        Sine coefficients; the complex coefficient of the module convention is ``-j b_n``.
    """
    if not 0 <= lam < 1:
        raise ValueError(f"crank ratio lam must be in [0, 1), got {lam!r}")
    a2 = lam + lam**3 / 4 + 15 * lam**5 / 128
    a4 = lam**3 / 4 + 3 * lam**5 / 16
    a6 = 9 * lam**5 / 128
    cos_c = {1: 1.0, 2: a2, 4: -a4, 6: a6}  # -x''/r  = sum cos_c[a] cos(a t)
    sin_c = {1: 1.0, 2: a2 / 2, 4: -a4 / 4, 6: a6 / 6}  # -x'/r = sum sin_c[b] sin(b t)
    b = np.zeros(13)
    # T/(m r^2 w^2) = -(x''/r)(x'/r) = -(sum C cos a t)(sum S sin b t);
    # cos(a t) sin(b t) = [sin((a+b) t) + sin((b-a) t)] / 2
    for a, ca in cos_c.items():
        for bb, sb in sin_c.items():
            b[a + bb] -= 0.5 * ca * sb
            d = bb - a
            if d > 0:
                b[d] -= 0.5 * ca * sb
            elif d < 0:
                b[-d] += 0.5 * ca * sb
    return np.arange(1, 13, dtype=float), b[1:]


def inertia_torque_series(
    theta: ArrayLike,
    reciprocating_mass: float,
    crank_radius: float,
    rod_length: float,
    omega: ArrayLike,
) -> np.ndarray:
    """Reciprocating inertia torque from the closed-form series (for checking).

    Parameters and result as :func:`reciprocating_inertia_torque`; see
    :func:`inertia_torque_series_coefficients` for the series and its truncation error.
    """
    r, lam = _check_crank(crank_radius, rod_length)
    if reciprocating_mass < 0:
        raise ValueError("reciprocating_mass must be >= 0 kg")
    orders, b = inertia_torque_series_coefficients(lam)
    th = np.asarray(theta, dtype=float)
    w = np.asarray(omega, dtype=float)[..., np.newaxis]
    shape = np.sin(th[..., np.newaxis] * orders) @ b
    return reciprocating_mass * r**2 * w**2 * shape


def phase_cylinders(coeffs: ArrayLike, orders: ArrayLike, firing_angles: ArrayLike) -> np.ndarray:
    """Order coefficients of each cylinder from those of cylinder 1 and the firing angles.

    ``F_{i,n} = c_n exp(-j n phi_i)`` (cylinder ``i`` fires ``phi_i`` after cylinder 1, so
    ``T_i(theta) = T_1(theta - phi_i)``).

    Parameters
    ----------
    coeffs : array_like, shape (..., n_order), complex [N*m]
        Coefficients of cylinder 1 (:func:`torque_harmonics`).
    orders : array_like, shape (n_order,) [-]
    firing_angles : array_like, shape (n_cyl,) [rad]
        Crank angle at which each cylinder fires, counted from firing TDC of cylinder 1
        (example I4, cylinders 1..4: 0, 3*pi, pi, 2*pi for firing order 1-3-4-2).

    Returns
    -------
    numpy.ndarray, shape (..., n_cyl, n_order), complex [N*m]
    """
    c = np.asarray(coeffs)
    n = np.asarray(orders, dtype=float)
    phi = np.asarray(firing_angles, dtype=float)
    if phi.ndim != 1 or n.ndim != 1:
        raise ValueError("orders and firing_angles must be 1-D")
    if c.shape[-1] != n.size:
        raise ValueError(f"coeffs has {c.shape[-1]} orders on its last axis, orders has {n.size}")
    rot = np.exp(-1j * phi[:, np.newaxis] * n)  # (n_cyl, n_order)
    return c[..., np.newaxis, :] * rot


def vector_sum(
    orders: ArrayLike, firing_angles: ArrayLike, weights: ArrayLike | None = None
) -> np.ndarray:
    """Vector ("phase") sum of the cylinder excitations for each order.

    ``S_n = |sum_i beta_i exp(-j n phi_i)|`` (Ker Wilson vol. 2). With
    ``beta`` = relative mode-shape amplitudes at the cylinders it measures how strongly order ``n``
    excites that mode; with ``beta = 1`` (rigid body) it identifies the major orders.

    Parameters
    ----------
    orders : array_like, shape (n_order,) [-]
    firing_angles : array_like, shape (n_cyl,) [rad]
    weights : array_like, shape (..., n_cyl), optional [-]
        Relative amplitudes ``beta_i`` (default 1).

    Returns
    -------
    numpy.ndarray, shape (..., n_order) [-]
    """
    n = np.asarray(orders, dtype=float)
    phi = np.asarray(firing_angles, dtype=float)
    beta = np.ones_like(phi) if weights is None else np.asarray(weights, dtype=float)
    if beta.shape[-1] != phi.size:
        raise ValueError("weights must have one entry per cylinder (last axis)")
    rot = np.exp(-1j * phi[:, np.newaxis] * n)  # (n_cyl, n_order)
    return np.abs(beta @ rot)


def major_order_mask(orders: ArrayLike, firing_angles: ArrayLike, rtol: float = 1e-9) -> np.ndarray:
    """Major orders: all cylinder excitations in phase (rigid-body vector sum = cylinder count).

    Parameters
    ----------
    orders : array_like, shape (n_order,) [-]
    firing_angles : array_like, shape (n_cyl,) [rad]
    rtol : float [-]
        Relative tolerance on the vector sum.

    Returns
    -------
    numpy.ndarray of bool, shape (n_order,)
        True for a major order (``n = k z/2`` for an evenly firing ``z``-cylinder 4-stroke engine).
    """
    phi = np.asarray(firing_angles, dtype=float)
    return vector_sum(orders, phi) >= phi.size * (1.0 - rtol)


def _check_crank(crank_radius: float, rod_length: float) -> tuple[float, float]:
    if not crank_radius > 0:
        raise ValueError(f"crank_radius must be > 0 m, got {crank_radius!r}")
    if not rod_length > crank_radius:
        raise ValueError(
            f"rod_length ({rod_length!r} m) must exceed crank_radius ({crank_radius!r} m)"
        )
    return float(crank_radius), float(crank_radius) / float(rod_length)
