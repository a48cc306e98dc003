"""Torsional response of a crank train with one cylinder misfiring (pure NumPy).

A misfiring cylinder gets no fuel but keeps its compression: its gas pressure is the motored
(compression-only) trace, its inertia torque is unchanged. Class societies ask for this case
(Korean Register, Rules for the Classification of Steel Ships, Pt 5 Ch 4, 102.1: "any one
cylinder misfiring, i.e. no injection but with compression"; IACS UR M53, Annex, "unfavourable
conditions such as one cylinder misfiring").

Model (the conventions of :mod:`checker.calc.torsional` and :mod:`checker.calc.excitation`)
---------------------------------------------------------------------------------------------
* Motored trace: in the compression and expansion strokes (cycle angle ``-pi <= psi <= pi``
  from the cylinder's firing TDC) the polytrope ``p V^k = C`` fitted to the firing trace's own
  compression line (least squares of ``ln p`` against ``ln V`` over :data:`FIT_WINDOW`, before
  any combustion); in the exhaust and intake strokes the firing trace (gas exchange at the
  same charge and exhaust pressures). The fitted ``k`` is the polytropic exponent of the
  compression (Heywood 1988, *Internal Combustion Engine Fundamentals*, sec. 9.2: the
  compression line of the log p - log V diagram is close to a polytrope, ``k`` about 1.3).
  At the joins (bottom dead centre) the crank torque of the gas force is zero
  (``dx/dtheta = 0``), so the joins do not enter the torque.
* Excitation difference of cylinder ``i`` misfiring: ``dF_{i,n} = (c^mot_n - c_n)
  exp(-j n phi_i)``, with ``c_n``, ``c^mot_n`` the order coefficients of one cylinder's crank
  torque (firing, motored; the inertia torque cancels) and ``phi_i`` its firing angle. A
  misfire breaks the symmetry of the firing order: every order 0.5, 1, 1.5, ... is excited,
  the lower and half orders that cancel in normal firing included.
* Response (linear, steady state): with the receptance ``H(Omega) = D(Omega)^-1`` (the dynamic
  stiffness of :func:`checker.calc.torsional.dynamic_stiffness_matrix`),
  ``Theta^(i) = Theta^(0) + H[:, s_i] dF_i`` (``s_i`` the station of cylinder ``i``):
  one factorisation per speed and order serves normal firing and every misfiring cylinder.

References
----------
.. [1] Korean Register of Shipping, "Rules for the Classification of Steel Ships", Pt 5 Ch 4
   "Torsional Vibration of Shaftings", 2025, 102.1 (misfire case: no injection but with
   compression).
.. [2] IACS Unified Requirement M53, "Calculation of crankshafts for I.C. engines", Annex
   (harmonic synthesis of the complete dynamic system; unfavourable conditions such as one
   cylinder misfiring).
.. [3] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, sec. 9.2.
.. [4] W. Ker Wilson, "Practical Solution of Torsional Vibration Problems", Vol. 2, ch. 19
   (phasing of the cylinder excitation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .torsional import (
    TorsionalModel,
    dynamic_stiffness_matrix,
    element_impedance,
    speeds_and_orders,
)

__all__ = [
    "FIT_WINDOW",
    "MisfireResponse",
    "MotoredTrace",
    "misfire_excitation",
    "misfire_response",
    "motored_trace",
]

FIT_WINDOW = (np.radians(-110.0), np.radians(-50.0))
"""Cycle angles [rad] from firing TDC of the compression line fitted by the motored polytrope:
after inlet valve closing (at most about 60 deg after bottom dead centre, -120 deg, on
four-stroke engines; Heywood 1988 sec. 6.3) and before the start of injection or ignition
(at most about 45 deg before TDC, the earliest combustion start of
:func:`checker.calc.pressure.calibrate_combustion_start`)."""

EXPONENT_RANGE = (1.05, 1.6)
"""Range of a plausible polytropic exponent of compression [-] (Heywood 1988 sec. 9.2: about
1.3 +- 0.05); a fit outside it means the trace has no clean compression line in
:data:`FIT_WINDOW` (combustion in the window, a trace of another angle reference)."""


@dataclass(frozen=True)
class MotoredTrace:
    """Motored (no injection, compression kept) cylinder pressure.

    Attributes
    ----------
    pressure : numpy.ndarray, shape (..., N) [Pa]
    exponent : numpy.ndarray, shape (...) [-]
        Fitted polytropic exponent ``k`` of the compression line.
    peak : numpy.ndarray, shape (...) [Pa]
        Motored peak pressure (at TDC).
    """

    pressure: np.ndarray
    exponent: np.ndarray
    peak: np.ndarray


def motored_trace(theta: ArrayLike, pressure: ArrayLike, volume: ArrayLike,
                  window: tuple[float, float] = FIT_WINDOW) -> MotoredTrace:
    """Motored trace of a cylinder from its firing trace (module docstring).

    ``p_mot = C V^-k`` for ``|psi| <= pi`` with ``ln C - k ln V`` the least-squares line of
    ``ln p`` over the samples in ``window``; the firing trace elsewhere.

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Cycle angles from the cylinder's firing TDC (any, taken modulo ``4 pi``).
    pressure : array_like, shape (..., N) [Pa]
        Absolute firing pressure at ``theta`` (> 0).
    volume : array_like, shape (N,) [m^3]
        Cylinder volume at ``theta`` (:func:`checker.calc.pressure.cylinder_volume`).
    window : (float, float) [rad]
        Fitted part of the compression stroke (default :data:`FIT_WINDOW`); at least three
        samples, volumes not all equal.

    Returns
    -------
    MotoredTrace

    Notes
    -----
    Valid for four-stroke cycles whose compression line in ``window`` is free of combustion;
    raises ``ValueError`` when the fitted exponent lies outside :data:`EXPONENT_RANGE`.
    A purely polytropic compression (the synthesized traces of
    :func:`checker.calc.pressure.synthesize_trace` below their heat release) is reproduced to
    round-off.
    """
    th = np.asarray(theta, dtype=float)
    p = np.asarray(pressure, dtype=float)
    vol = np.asarray(volume, dtype=float)
    if th.ndim != 1 or vol.shape != th.shape or p.shape[-1:] != th.shape:
        raise ValueError("theta, volume and the last axis of pressure must have the same length")
    if np.any(~np.isfinite(p)) or np.any(p <= 0) or np.any(vol <= 0):
        raise ValueError("pressure and volume must be finite and > 0")
    psi = np.mod(th + 2.0 * np.pi, 4.0 * np.pi) - 2.0 * np.pi  # (-2 pi, 2 pi]
    fit = (psi >= window[0]) & (psi <= window[1])
    x = np.log(vol[fit])
    if fit.sum() < 3 or np.ptp(x) <= 0:
        raise ValueError("the fit window must hold at least three samples of changing volume")
    y = np.log(p[..., fit])
    xm = x.mean()
    slope = ((y - y.mean(-1, keepdims=True)) @ (x - xm)) / np.sum((x - xm) ** 2)
    k = -slope
    lnc = y.mean(-1) + k * xm
    if np.any((k < EXPONENT_RANGE[0]) | (k > EXPONENT_RANGE[1])):
        raise ValueError(
            f"compression exponent {np.min(k):.3g}..{np.max(k):.3g} fitted to the trace between"
            f" {np.degrees(window[0]):.0f} and {np.degrees(window[1]):.0f} deg is outside"
            f" {EXPONENT_RANGE[0]:g}..{EXPONENT_RANGE[1]:g}: no clean compression line there")
    closed = np.abs(psi) <= np.pi
    poly = np.exp(lnc[..., None] - k[..., None] * np.log(vol))
    out = np.where(closed, poly, p)
    return MotoredTrace(pressure=out, exponent=k,
                        peak=np.exp(lnc - k * np.log(vol.min())))


def misfire_excitation(firing_coeffs: ArrayLike, motored_coeffs: ArrayLike, orders: ArrayLike,
                       firing_angles: ArrayLike) -> np.ndarray:
    """Change of each cylinder's order excitation when it misfires.

    ``dF_{i,n} = (c^mot_n - c_n) exp(-j n phi_i)`` (module docstring).

    Parameters
    ----------
    firing_coeffs, motored_coeffs : array_like, shape (..., O), complex [N m]
        Order coefficients of one cylinder's crank torque at firing angle 0, firing and
        misfiring (:func:`checker.calc.excitation.torque_harmonics`).
    orders : array_like, shape (O,) [-]
    firing_angles : array_like, shape (n_cyl,) [rad]

    Returns
    -------
    numpy.ndarray, shape (..., n_cyl, O), complex [N m]
    """
    c0 = np.asarray(firing_coeffs, dtype=complex)
    c1 = np.asarray(motored_coeffs, dtype=complex)
    n = np.asarray(orders, dtype=float).ravel()
    phi = np.asarray(firing_angles, dtype=float).ravel()
    if c0.shape != c1.shape or c0.shape[-1:] != n.shape:
        raise ValueError("firing and motored coefficients must match, order axis last")
    return (c1 - c0)[..., None, :] * np.exp(-1j * phi[:, None] * n)


@dataclass(frozen=True)
class MisfireResponse:
    """Steady-state response in normal firing and with each cylinder misfiring in turn.

    Attributes
    ----------
    speeds : numpy.ndarray, shape (S,) [rad/s]
    orders : numpy.ndarray, shape (O,) [-]
    omega : numpy.ndarray, shape (S, O) [rad/s]
    theta_normal : numpy.ndarray, shape (S, n, O), complex [rad]
        Station angles in normal firing.
    theta : numpy.ndarray, shape (S, n_cyl, n, O), complex [rad]
        Station angles with cylinder ``i`` (axis 1) misfiring.
    torque_normal : numpy.ndarray, shape (S, n_e, O), complex [N m]
    torque : numpy.ndarray, shape (S, n_cyl, n_e, O), complex [N m]
        Element torques ``z_e (Theta_a - Theta_b)``.
    """

    speeds: np.ndarray
    orders: np.ndarray
    omega: np.ndarray
    theta_normal: np.ndarray
    theta: np.ndarray
    torque_normal: np.ndarray
    torque: np.ndarray


def misfire_response(model: TorsionalModel, speeds: ArrayLike, orders: ArrayLike,
                     cylinder_force: ArrayLike, delta: ArrayLike, stations: ArrayLike,
                     station_damping: ArrayLike | None = None) -> MisfireResponse:
    """Forced response in normal firing and with each cylinder misfiring (module docstring).

    Parameters
    ----------
    model : TorsionalModel
    speeds : array_like, shape (S,) [rad/s]
        Mean crank speeds (> 0).
    orders : array_like, shape (O,) [-]
        Harmonic orders (> 0).
    cylinder_force : array_like, shape (S, n_cyl, O), complex [N m]
        Phased order excitation of every cylinder in normal firing
        (:func:`checker.calc.excitation.phase_cylinders`).
    delta : array_like, shape (S, n_cyl, O), complex [N m]
        Its change when that cylinder misfires (:func:`misfire_excitation`).
    stations : array_like of int, shape (n_cyl,)
        Station of each cylinder (several cylinders may share one).
    station_damping : array_like, shape (S, n), optional [N m s/rad]
        Absolute viscous damping added per speed (as
        :func:`checker.calc.torsional.forced_response`).

    Returns
    -------
    MisfireResponse

    Notes
    -----
    One LU factorisation of ``D`` per speed and order with one right-hand side per station
    carrying a cylinder (``numpy.linalg.solve``); the misfire cases are superposed (linear
    model, exact). An undamped resonance (singular ``D``) raises ``numpy.linalg.LinAlgError``;
    the caller flags those points with :func:`checker.calc.torsional.forced_response`.
    """
    w, n_ord = speeds_and_orders(speeds, orders)
    st = np.asarray(stations, dtype=int).ravel()
    n_cyl, n = st.size, model.n_stations
    f = np.asarray(cylinder_force, dtype=complex)
    d = np.asarray(delta, dtype=complex)
    shape = (w.size, n_cyl, n_ord.size)
    if f.shape != shape or d.shape != shape:
        raise ValueError(f"cylinder_force and delta must have shape (S, n_cyl, O) = {shape}")
    if np.any(st < 0) or np.any(st >= n):
        raise ValueError(f"stations must be in 0..{n - 1}")
    used = sorted(set(st.tolist()))
    col = np.array([used.index(s) for s in st])
    om = w[:, None] * n_ord  # (S, O)
    dmat = dynamic_stiffness_matrix(model, om)  # (S, O, n, n)
    if station_damping is not None:
        extra = np.broadcast_to(np.asarray(station_damping, dtype=float), (w.size, n))
        if np.any(~np.isfinite(extra)) or np.any(extra < 0):
            raise ValueError("station_damping must be finite and >= 0 N m s/rad")
        dmat[..., np.arange(n), np.arange(n)] += 1j * om[..., None] * extra[:, None, :]
    rhs = np.zeros((n, len(used)))
    rhs[used, np.arange(len(used))] = 1.0
    h = np.linalg.solve(dmat, rhs)  # (S, O, n, m): receptance columns of the cylinder stations
    f_st = np.zeros((w.size, n_ord.size, len(used)), dtype=complex)
    np.add.at(f_st, (slice(None), slice(None), col), np.moveaxis(f, 1, 2))
    theta0 = (h @ f_st[..., None])[..., 0]  # (S, O, n)
    dtheta = h[..., col] * np.moveaxis(d, 1, 2)[:, :, None, :]  # (S, O, n, n_cyl)
    theta = theta0[..., None] + dtheta
    z = element_impedance(model, om)  # (S, O, E)
    bmat = model.incidence
    t0 = z * (theta0 @ bmat.T)
    t1 = z[..., None] * (bmat @ theta)  # (S, O, E, n_cyl)
    return MisfireResponse(
        speeds=w, orders=n_ord, omega=om,
        theta_normal=np.moveaxis(theta0, 1, 2),
        theta=np.transpose(theta, (0, 3, 2, 1)),
        torque_normal=np.moveaxis(t0, 1, 2),
        torque=np.transpose(t1, (0, 3, 2, 1)))
