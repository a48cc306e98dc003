"""A damper whose properties depend on its own temperature: rubber tables and self-heating.

Rubber: the storage shear modulus ``G'(T)`` and loss factor ``eta(T)`` of the damper
elastomer, given as a table against temperature (supplier data), make the rubber element

    k*(T) = Phi_r G'(T) (1 + j eta(T)),   Phi_r = 4 pi L r_i^2 r_o^2 / (r_o^2 - r_i^2)

(bonded annulus, :func:`checker.calc.damper.annulus_stiffness`). The storage modulus of an
elastomer changes by an order of magnitude between -30 and 120 C (US 11,136,448: E'(-30 C) /
E'(60 C) up to 21), roughly exponentially in temperature away from the glass transition
(WLF / Arrhenius shift, Moreira et al., Shock and Vibration 17, 2010): ``G'`` is interpolated
linearly in ``ln G'`` between the table's points, ``eta`` linearly; a table point is returned
exactly.

Self-heating: at each operating point the damper settles where the heat it dissipates leaves
through its cooled surface, ``T = T_ambient + P(T) R_th`` with ``R_th = 1 / (h A)``
(:func:`checker.calc.viscous_damper.steady_temperature`); ``P(T)`` is the forced response's
dissipated power with the properties at ``T``. :func:`self_heated_temperature` solves this
per point by bisection.

References
----------
.. [1] US Patent 11,136,448 B2 (torsional vibration damper elastomer: tan delta >= 0.14 from
   -30 to 120 C, E'(-30 C)/E'(60 C) up to 21).
.. [2] E. Moreira, J. Dias Rodrigues, A. Ferreira, "Frequency and temperature dependent
   viscoelastic properties of a damping material", Shock and Vibration 17, 2010 (WLF shift).
.. [3] F. P. Incropera, D. P. DeWitt, "Fundamentals of Heat and Mass Transfer", Wiley, 2002,
   ch. 3 (thermal resistance of a cooled surface, R = 1/(h A)).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["RubberTable", "self_heated_temperature"]


class RubberTable:
    """Storage shear modulus and loss factor of a damper elastomer against temperature.

    Parameters
    ----------
    temperature : array_like, shape (m,) [K]
        Strictly increasing.
    storage_modulus : array_like, shape (m,) [Pa]
        ``G' > 0``.
    loss_factor : array_like, shape (m,) [-]
        ``eta >= 0``.

    Notes
    -----
    ``G'`` is interpolated linearly in ``ln G'`` (module docstring), ``eta`` linearly; outside
    the table the properties are unknown: :meth:`__call__` returns NaN there (never a held end
    value) and :meth:`inside` says where.
    """

    def __init__(self, temperature: ArrayLike, storage_modulus: ArrayLike,
                 loss_factor: ArrayLike) -> None:
        t = np.asarray(temperature, dtype=float).ravel()
        g = np.asarray(storage_modulus, dtype=float).ravel()
        eta = np.asarray(loss_factor, dtype=float).ravel()
        if t.size < 1 or g.shape != t.shape or eta.shape != t.shape:
            raise ValueError("temperature, storage_modulus and loss_factor: 1-D, same length")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(g)) and np.all(np.isfinite(eta))):
            raise ValueError("the rubber table must be finite")
        if np.any(np.diff(t) <= 0):
            raise ValueError("temperature must be strictly increasing")
        if np.any(g <= 0) or np.any(eta < 0):
            raise ValueError("storage_modulus must be > 0 and loss_factor >= 0")
        self.temperature, self.storage_modulus, self.loss_factor = t, g, eta

    @property
    def t_min(self) -> float:
        return float(self.temperature[0])

    @property
    def t_max(self) -> float:
        return float(self.temperature[-1])

    def inside(self, temperature: ArrayLike) -> np.ndarray:
        """Whether each temperature [K] lies within the table."""
        t = np.asarray(temperature, dtype=float)
        return (t >= self.t_min) & (t <= self.t_max)

    def __call__(self, temperature: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """``(G' [Pa], eta [-])`` at ``temperature`` [K] (any shape; NaN outside the table)."""
        t = np.asarray(temperature, dtype=float)
        tt, g, eta = self.temperature, self.storage_modulus, self.loss_factor
        if tt.size == 1:
            on = t == tt[0]
            return np.where(on, g[0], np.nan), np.where(on, eta[0], np.nan)
        i = np.clip(np.searchsorted(tt, t, side="right") - 1, 0, tt.size - 2)
        s = (t - tt[i]) / (tt[i + 1] - tt[i])
        gi = g[i] * (g[i + 1] / g[i]) ** s  # s = 0: exactly g[i]
        ei = eta[i] + s * (eta[i + 1] - eta[i])
        last = t == tt[-1]
        gi = np.where(last, g[-1], gi)
        ei = np.where(last, eta[-1], ei)
        ok = self.inside(t)
        return np.where(ok, gi, np.nan), np.where(ok, ei, np.nan)


#: The heat balance is solved when ``|T - T_a - R P(T)|`` is below this at every point [K].
TEMPERATURE_TOLERANCE = 1e-3
#: Most evaluations of ``P(T)`` (bracketing iterations; the Illinois method takes about 5-10).
MAX_ITERATIONS = 200


def self_heated_temperature(power_at: Callable[[np.ndarray], np.ndarray], ambient: ArrayLike,
                            resistance: float | None, t_max: float
                            ) -> tuple[np.ndarray, np.ndarray]:
    """Steady damper temperature ``T = T_a + R P(T)`` at each operating point.

    Parameters
    ----------
    power_at : callable
        ``P(T)``: dissipated power [W] at the points for temperatures ``T`` [K] of the same
        shape (one forced response with the properties at each point's temperature).
    ambient : array_like [K]
        Air temperature at the damper, per point.
    resistance : float or None [K/W]
        ``R = 1 / (h A)``; ``None`` or 0: no self-heating (``T = T_a``).
    t_max : float [K]
        Highest temperature the properties are known at (top of the rubber table; for a
        viscous damper a bound far above the fluid's limit).

    Returns
    -------
    temperature : numpy.ndarray [K]
        NaN where the balance has no solution below ``t_max`` (the damper would be hotter
        than its properties are known).
    power : numpy.ndarray [W]
        ``P(T)`` at that temperature (NaN where the temperature is).

    Notes
    -----
    ``g(T) = T - T_a - R P(T)`` is ``<= 0`` at ``T_a``; where ``g(t_max) >= 0`` a root lies in
    ``[T_a, t_max]`` and the Illinois variant of the false-position method (Dowell and
    Jarratt, BIT 11, 1971) keeps it bracketed until ``|g| <`` :data:`TEMPERATURE_TOLERANCE`
    (the lowest-lying root when ``P`` falls with ``T``, as for a damper detuning as it heats;
    with several roots, one of them). Deterministic: a fixed sequence of vectorised
    evaluations. ``RuntimeError`` if :data:`MAX_ITERATIONS` do not suffice (never a silent
    partial result).
    """
    ta = np.asarray(ambient, dtype=float)
    if not resistance:
        return ta.copy(), np.asarray(power_at(ta), dtype=float)
    r = float(resistance)
    if r < 0:
        raise ValueError("resistance must be >= 0 K/W")

    def g(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        p = np.asarray(power_at(t), dtype=float)
        return t - ta - r * p, p

    lo, (g_lo, p_lo) = ta.copy(), g(ta)
    hi = np.maximum(np.full(ta.shape, float(t_max)), ta)
    g_hi, _ = g(hi)
    ok = g_hi >= 0
    t, gt, pt = lo.copy(), g_lo, p_lo
    done = ~ok | (np.abs(g_lo) < TEMPERATURE_TOLERANCE)
    side = np.zeros(ta.shape, dtype=int)
    for _ in range(MAX_ITERATIONS):
        if done.all():
            break
        den = np.where(g_hi - g_lo > 0, g_hi - g_lo, 1.0)
        cand = np.clip(hi - g_hi * (hi - lo) / den, lo, hi)
        cand = np.where(done, t, cand)
        gc, pc = g(cand)
        t, gt, pt = (np.where(done, t, cand), np.where(done, gt, gc),
                     np.where(done, pt, pc))
        below = ~done & (gc < 0)
        above = ~done & (gc >= 0)
        lo, g_lo = np.where(below, cand, lo), np.where(below, gc, g_lo)
        hi, g_hi = np.where(above, cand, hi), np.where(above, gc, g_hi)
        g_hi = np.where(below & (side == -1), 0.5 * g_hi, g_hi)  # Illinois step
        g_lo = np.where(above & (side == 1), 0.5 * g_lo, g_lo)
        side = np.where(below, -1, np.where(above, 1, side))
        done |= (np.abs(gc) < TEMPERATURE_TOLERANCE) | (hi - lo < TEMPERATURE_TOLERANCE)
    else:
        if not done.all():
            raise RuntimeError("the damper's heat balance did not converge in"
                               f" {MAX_ITERATIONS} iterations")
    return np.where(ok, t, np.nan), np.where(ok, pt, np.nan)
