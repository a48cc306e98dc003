"""Cyclic speed fluctuation of a rigid engine, coefficient of cyclic irregularity and the
flywheel inertia for a target irregularity.

Model (Agostini 2019, *Powertrain Components Design*, Politecnico di Torino, "Engine degree of
irregularity"; Taylor 1985, vol. 2, ch. 8 "flywheel"): the engine, flywheel and everything
rigidly attached turn as one inertia ``J`` driven by the engine torque ``T(theta)`` (gas +
inertia of every cylinder, a function of the crank angle) against a constant load torque equal
to its cycle mean (steady state)::

    J omega domega/dtheta = T(theta) - T_mean   =>   J/2 (omega^2 - omega_0^2) = W(theta),
    W(theta) = int_0^theta (T - T_mean) dtheta

so the speed over the cycle is ``omega(theta) = sqrt(omega_min^2 + 2 (W - W_min)/J)``. The
fluctuation energy is ``dE = W_max - W_min`` and the coefficient of cyclic irregularity

    delta = (omega_max - omega_min) / w,   w = time-mean speed = 4 pi / t_cycle

(the "kinematic irregularity" of the source, whose ``omega_avg = (omega_max + omega_min)/2``
is the midrange approximation of the mean speed; the time-mean speed is the engine speed the
check is run at, and the two differ by O(delta^2): for ``omega = w0 (1 + a sin theta)`` the
time mean is ``w0 sqrt(1 - a^2)``). ``omega_min`` is solved so that the time-mean speed of the
cycle equals the given engine speed, which is exact for the model. The classical estimate
``delta ~ dE/(J w^2)`` is returned too.

References
----------
.. [1] M. Agostini, "Powertrain Components Design - Engine", course notes, Master Degree in
   Automotive Engineering, Politecnico di Torino, 2019 (A.Y. 2018-2019), "Engine degree of
   irregularity", "flywheel dimensioning".
.. [2] C. F. Taylor, "The Internal-Combustion Engine in Theory and Practice", Vol. 2, 1985, ch. 8
   "flywheel".
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from checker.calc._checks import finite, positive

__all__ = ["Irregularity", "cycle_work", "cyclic_irregularity", "minimum_inertia"]

SPEED_TOLERANCE = 1e-12
"""Relative tolerance on ``omega_min`` of the time-mean-speed condition (safeguarded Newton)."""


def _grid_period(theta: np.ndarray) -> float:
    n = theta.size
    if theta.ndim != 1 or n < 8:
        raise ValueError("theta must be a 1-D uniform periodic grid with at least 8 points")
    step = theta[1] - theta[0]
    if step <= 0 or not np.allclose(np.diff(theta), step, rtol=1e-9, atol=1e-12):
        raise ValueError("theta must be uniform and increasing (periodic grid without its end"
                         " point)")
    return step * n


def cycle_work(theta: ArrayLike, torque: ArrayLike) -> np.ndarray:
    """Work of the torque in excess of its mean from the start of the cycle.

    ``W(theta_k) = int_{theta_0}^{theta_k} (T - T_mean) dtheta``, integrated spectrally (exact
    for the trigonometric interpolant of the samples; the Nyquist term, whose integral vanishes
    on the grid, is dropped).

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Uniform periodic grid without its end point (period ``N * step``, e.g. 4 pi).
    torque : array_like, shape (..., N) [N m]

    Returns
    -------
    numpy.ndarray, shape (..., N) [J]
        ``W(theta_0) = 0``.
    """
    th = finite("theta", theta)
    period = _grid_period(th)
    t = finite("torque", torque)
    if t.shape[-1] != th.size:
        raise ValueError("torque must have the crank-angle axis last, matching theta")
    n = th.size
    c = np.fft.rfft(t, axis=-1)
    k = np.arange(c.shape[-1])
    c[..., 0] = 0.0
    if n % 2 == 0:
        c[..., -1] = 0.0
    wk = 2.0 * np.pi * k / period
    wk[0] = 1.0
    w = np.fft.irfft(c / (1j * wk), n=n, axis=-1)
    return w - w[..., :1]


class Irregularity(NamedTuple):
    """Speed fluctuation over the cycle (arrays over the leading axes of the torque).

    Attributes
    ----------
    energy : numpy.ndarray [J]
        Fluctuation energy ``dE = W_max - W_min``.
    irregularity : numpy.ndarray [-]
        ``(omega_max - omega_min) / w`` with ``w`` the time-mean speed.
    irregularity_linear : numpy.ndarray [-]
        Classical estimate ``dE / (J w^2)`` with ``w`` the mean speed.
    omega_max, omega_min : numpy.ndarray [rad/s]
    theta_max, theta_min : numpy.ndarray [rad]
        Crank angles (grid points) of the highest and lowest speed.
    omega : numpy.ndarray, shape (..., N) [rad/s]
        Speed over the cycle.
    """

    energy: np.ndarray
    irregularity: np.ndarray
    irregularity_linear: np.ndarray
    omega_max: np.ndarray
    omega_min: np.ndarray
    theta_max: np.ndarray
    theta_min: np.ndarray
    omega: np.ndarray


def cyclic_irregularity(theta: ArrayLike, torque: ArrayLike, inertia: ArrayLike,
                        mean_speed: ArrayLike) -> Irregularity:
    """Speed fluctuation and cyclic irregularity of a rigid engine (module docstring).

    ``omega_min`` solves ``(1/N) sum_k 1/sqrt(omega_min^2 + 2 (W_k - W_min)/J) = 1/w`` (the
    cycle time at the time-mean speed ``w``; the rectangle rule is spectrally accurate for a
    periodic integrand) by Newton's method safeguarded by bisection on ``(0, w]``, to
    :data:`SPEED_TOLERANCE`.

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Uniform periodic grid (:func:`cycle_work`).
    torque : array_like, shape (..., N) [N m]
        Total engine torque (all cylinders, gas + inertia) over the cycle.
    inertia : array_like, broadcast to ``torque.shape[:-1]`` [kg m^2]
        Total rotating inertia ``J > 0`` turning with the crank.
    mean_speed : array_like, broadcast to ``torque.shape[:-1]`` [rad/s]
        Time-mean engine speed ``w > 0``.

    Returns
    -------
    Irregularity

    Notes
    -----
    Valid for a rigid engine at steady state: the torsional flexibility of the crank is
    ignored (the rigid-body "rolling" motion only) and the inertia torque is the one at the
    mean speed (its change with the fluctuating speed is of order ``delta``). Agostini (2019)
    quotes ``delta <= 1 %`` as a typical bound; the target depends on the application.
    """
    th = finite("theta", theta)
    w_cyc = cycle_work(th, torque)
    shape = w_cyc.shape[:-1]
    j = np.broadcast_to(positive("inertia", inertia), shape)
    wm = np.broadcast_to(positive("mean_speed", mean_speed), shape)
    w_min = w_cyc.min(axis=-1)
    w_max = w_cyc.max(axis=-1)
    q = 2.0 * (w_cyc - w_min[..., None]) / j[..., None]  # omega^2 - omega_min^2 >= 0
    target = 1.0 / wm

    lo = np.zeros(shape)
    hi = np.array(wm, dtype=float)  # g(hi) <= 0 since every term <= 1/w there
    # start: one step of s = w mean((1 + q/s^2)^-1/2) from s = w (error of order delta^2)
    s = wm * np.mean(1.0 / np.sqrt(1.0 + q / (wm * wm)[..., None]), axis=-1)
    for _ in range(100):
        inv = 1.0 / np.sqrt(s[..., None] ** 2 + q)
        g = np.mean(inv, axis=-1) - target
        dg = -s * np.mean(inv * inv * inv, axis=-1)
        lo = np.where(g > 0, s, lo)
        hi = np.where(g <= 0, s, hi)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(dg < 0, g / dg, np.inf)
        s_new = s - step
        bad = ~np.isfinite(s_new) | (s_new <= lo) | (s_new >= hi)
        s_new = np.where(bad, 0.5 * (lo + hi), s_new)
        done = np.abs(s_new - s) <= SPEED_TOLERANCE * wm
        s = s_new
        if np.all(done):
            break
    omega = np.sqrt(s[..., None] ** 2 + q)
    o_max = np.sqrt(s * s + 2.0 * (w_max - w_min) / j)
    delta = (o_max - s) / wm  # time-mean speed (module docstring)
    energy = w_max - w_min
    return Irregularity(energy, delta, energy / (j * wm * wm), o_max, s,
                        th[np.argmax(w_cyc, axis=-1)], th[np.argmin(w_cyc, axis=-1)], omega)


def minimum_inertia(theta: ArrayLike, torque: ArrayLike, mean_speed: ArrayLike,
                    target: ArrayLike) -> np.ndarray:
    """Smallest rotating inertia that keeps the cyclic irregularity at ``target``.

    The module's model: with ``rho = omega_max / omega_min`` and ``u_k = (W_k - W_min)/dE`` in
    ``[0, 1]``, the speed over the cycle is ``omega_k = omega_min sqrt(1 + (rho^2 - 1) u_k)``;
    the time-mean speed condition gives ``omega_min = w m(rho)``, ``m(rho) = mean_k (1 +
    (rho^2 - 1) u_k)^(-1/2)``, so ``delta = (rho - 1) m(rho)``, increasing in ``rho``, solved
    for ``rho`` by Newton's method safeguarded by bisection (to round-off); the energy
    equation gives ``J = 2 dE / (omega_min^2 (rho^2 - 1))``. For small ``delta`` this is the
    classical flywheel sizing ``J = dE / (delta w^2)`` (Agostini 2019, "flywheel dimensioning").

    Parameters
    ----------
    theta, torque, mean_speed
        As in :func:`cyclic_irregularity`.
    target : array_like, broadcast to ``torque.shape[:-1]`` [-]
        Target irregularity, ``0 < target < 2``.

    Returns
    -------
    numpy.ndarray [kg m^2]
        Total inertia needed (subtract the engine's own to size the flywheel); 0 where the
        torque does not fluctuate (fluctuation energy at round-off level, 1e-12 of the cycle's
        torque times angle).
    """
    th = finite("theta", theta)
    tq = finite("torque", torque)
    shape = tq.shape[:-1]
    tgt = np.broadcast_to(positive("target", target), shape)
    if np.any(tgt >= 2.0):
        raise ValueError("target irregularity must be below 2")
    wm = np.broadcast_to(positive("mean_speed", mean_speed), shape)
    w = cycle_work(th, tq)
    w = w - w.min(axis=-1, keepdims=True)
    energy = w.max(axis=-1)
    flat = energy <= 1e-12 * np.abs(tq).max(axis=-1) * _grid_period(th)  # round-off level
    e_safe = np.where(flat, 1.0, energy)
    u = w / e_safe[..., None]

    def delta_of(r: np.ndarray) -> np.ndarray:  # (rho - 1) m(rho), r = rho - 1
        r2 = r * (r + 2.0)  # rho^2 - 1 without cancellation
        return r * np.mean((1.0 + r2[..., None] * u) ** -0.5, axis=-1)

    lo = np.zeros(shape)
    hi = np.ones(shape)
    for _ in range(200):  # bracket: delta_of grows without bound (u = 0 at the minimum)
        short = delta_of(hi) < tgt
        if not short.any():
            break
        hi = np.where(short, 2.0 * hi, hi)
    # Newton on f(r) = r m(r) - target inside the bracket (bisection where a step leaves it):
    # f' = m + r m',  m' = -(r + 1) mean(u (1 + r2 u)^(-3/2)); a few steps instead of ~45
    # bisection halvings, the same root to round-off
    r = np.clip(np.asarray(tgt, dtype=float), lo, hi)
    for _ in range(200):
        sk = (1.0 + (r * (r + 2.0))[..., None] * u) ** -0.5
        m = np.mean(sk, axis=-1)
        f = r * m - tgt
        below = f < 0.0
        lo = np.where(below, r, lo)
        hi = np.where(below, hi, r)
        fp = m - r * (r + 1.0) * np.mean(u * sk * sk * sk, axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            r_new = r - f / fp
        bad = ~np.isfinite(r_new) | (r_new <= lo) | (r_new >= hi)
        r_new = np.where(bad, 0.5 * (lo + hi), r_new)
        done = (np.abs(r_new - r) <= 1e-14 * r_new) | (f == 0.0) | (hi - lo <= 1e-13 * hi)
        r = np.where(f == 0.0, r, r_new)
        if np.all(done):
            break
    rho2m1 = r * (r + 2.0)
    s = wm * np.mean((1.0 + rho2m1[..., None] * u) ** -0.5, axis=-1)
    return np.where(flat, 0.0, 2.0 * energy / (s * s * rho2m1))
