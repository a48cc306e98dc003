"""Order analysis of a signal sampled per crank angle (pure NumPy, SI).

A station's instantaneous speed or vibratory angle sampled at equal crank-angle steps (an
encoder or a zebra tape read out per tooth: synchronous, "computed order tracking" sampling)
is cut into whole 4-stroke cycles of 720 deg, each cycle transformed by a discrete Fourier
transform, and the complex order coefficients averaged over the cycles:

    X_m^(k) = (2 / N) sum_{i=0}^{N-1} x_{kN+i} exp(-j 2 pi i m / N)     (m >= 1)
    X_n = mean_k X_{2n}^(k),   n = m / 2 (orders 0.5, 1, 1.5, ...)

so that ``x(theta) = X_0 + sum_n Re{X_n exp(j n theta)}`` with ``theta`` the crank angle from
cylinder 1's firing top dead centre, the convention of :mod:`checker.calc.torsional`
(Brandt 2011, ch. 12, order tracking by synchronous sampling; Fyfe & Munck 1997).

* **Resolution** 0.5 order (one 720 deg cycle per transform: the 4-stroke half orders).
* **Leakage**: every half order falls exactly on a frequency bin of a whole cycle with a
  rectangular window, so a steady periodic signal has none. A drift of the signal's mean from
  one cycle to the next (a speed still changing) is a ramp within each cycle, whose Fourier
  series spreads ``|d| / (pi m)`` into bin ``m``, i.e. ``|d| / (2 pi n)`` into order ``n``
  (the sawtooth series); that bound, from the measured cycle-to-cycle drift ``d``, is stated
  per order.
* **Averaging** of the complex coefficients (synchronous averaging) keeps the phase referred
  to the cycle start; the scatter of the cycles' amplitudes is returned beside the mean.
* **Highest order**: ``N / 4 - 1/2`` for ``N`` samples per cycle (below the Nyquist bin).

References
----------
.. [1] A. Brandt, "Noise and Vibration Analysis: Signal Analysis and Experimental
   Procedures", Wiley, 2011, ch. 9 (DFT, leakage) and ch. 12 (rotating machinery, order
   tracking).
.. [2] K. R. Fyfe, E. D. S. Munck, "Analysis of computed order tracking", Mechanical Systems
   and Signal Processing 11(2), 1997, 187-205.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["CYCLE", "MIN_CYCLES", "OrderSpectrum", "angle_from_speed", "highest_order",
           "order_spectrum"]

CYCLE = 4.0 * np.pi
"""One 4-stroke cycle [rad] (720 deg): the transform length, for half orders."""

MIN_CYCLES = 4
"""Fewest whole cycles a run must hold: the half orders resolve only over whole 720 deg cycles,
and the average of 4 halves the cycle-to-cycle scatter of one."""


@dataclass(frozen=True)
class OrderSpectrum:
    """Averaged order coefficients of one steady run.

    Attributes
    ----------
    orders : numpy.ndarray, shape (O,) [-]
    coeffs : numpy.ndarray, shape (O,), complex [unit of the signal]
        Mean over the cycles of the 0-to-peak complex coefficients.
    scatter : numpy.ndarray, shape (O,) [unit of the signal]
        Standard deviation over the cycles of the amplitude ``|X_n^(k)|`` (0 for one cycle).
    leakage : numpy.ndarray, shape (O,) [unit of the signal]
        Bound of the amplitude a cycle-to-cycle drift of the mean spreads into each order,
        ``rms(d) / (2 pi n)``.
    mean : float [unit of the signal]
        Mean of the signal over the whole cycles.
    cycles : int
        Whole cycles averaged.
    samples_per_cycle : int
    """

    orders: np.ndarray
    coeffs: np.ndarray
    scatter: np.ndarray
    leakage: np.ndarray
    mean: float
    cycles: int
    samples_per_cycle: int

    @property
    def resolution(self) -> float:
        """Order resolution [-]: 0.5 (one transform per 720 deg cycle)."""
        return 0.5


def highest_order(samples_per_cycle: int) -> float:
    """Highest half order below the Nyquist bin for ``samples_per_cycle`` samples per 720 deg
    cycle: ``(N/2 - 1) / 2``."""
    return (samples_per_cycle // 2 - 1) / 2.0


def order_spectrum(samples: ArrayLike, samples_per_cycle: int, orders: ArrayLike
                   ) -> OrderSpectrum:
    """Averaged order coefficients of a signal sampled at equal crank-angle steps.

    Parameters
    ----------
    samples : array_like, shape (M,) [any unit]
        The signal, first sample at the start of a cycle (cylinder 1 firing TDC), equal crank
        angle steps of ``4 pi / samples_per_cycle``; samples past the last whole cycle are
        left out.
    samples_per_cycle : int
        ``N`` samples per 720 deg cycle (>= 4).
    orders : array_like, shape (O,) [-]
        Positive multiples of 0.5, at most :func:`highest_order` ``(N)``.

    Returns
    -------
    OrderSpectrum

    Raises
    ------
    ValueError
        Fewer than one whole cycle, non-finite samples, or an order that is no half order or
        above the highest order.

    Notes
    -----
    Exact (to round-off) for a signal that is a sum of half orders up to the highest order;
    content above it aliases (sample at least 4 points per period of the highest order
    present). Validity: a steady run (the leakage bound states the effect of a drift).
    """
    x = np.asarray(samples, dtype=float).ravel()
    n = int(samples_per_cycle)
    o = np.asarray(orders, dtype=float).ravel()
    if n < 4:
        raise ValueError("at least 4 samples per cycle are needed")
    if np.any(~np.isfinite(x)):
        raise ValueError("the samples must be finite")
    k = x.size // n
    if k < 1:
        raise ValueError(f"{x.size} samples hold no whole cycle of {n}")
    m = np.rint(2.0 * o)
    if o.size == 0 or np.any(m < 1) or np.any(np.abs(2.0 * o - m) > 1e-9):
        raise ValueError("orders must be positive multiples of 0.5")
    top = highest_order(n)
    if np.any(o > top + 1e-9):
        raise ValueError(f"order {o.max():g} is above the highest order {top:g} of"
                         f" {n} samples per cycle")
    cyc = x[: k * n].reshape(k, n)
    spec = np.fft.rfft(cyc, axis=-1) * (2.0 / n)  # (k, N/2+1)
    c = spec[:, m.astype(int)]  # (k, O)
    means = cyc.mean(axis=-1)
    drift = np.diff(means)
    d_rms = float(np.sqrt(np.mean(drift**2))) if drift.size else 0.0
    return OrderSpectrum(
        orders=o, coeffs=c.mean(axis=0), scatter=np.abs(c).std(axis=0),
        leakage=d_rms / (2.0 * np.pi * o), mean=float(means.mean()), cycles=k,
        samples_per_cycle=n)


def angle_from_speed(speed_coeffs: ArrayLike, orders: ArrayLike, mean_speed: float
                     ) -> np.ndarray:
    """Vibratory angle coefficients from the order coefficients of the instantaneous speed.

    ``Theta_n = W_n / (j n w)``: the angle's time derivative is the speed fluctuation, with
    ``theta = w t`` along the cycle (first order in the cyclic irregularity ``W / w``;
    Brandt 2011, ch. 12).

    Parameters
    ----------
    speed_coeffs : array_like, shape (..., O), complex [rad/s]
    orders : array_like, shape (O,) [-]
    mean_speed : float [rad/s]
        ``w > 0``.

    Returns
    -------
    numpy.ndarray, shape (..., O), complex [rad]
    """
    if not (np.isfinite(mean_speed) and mean_speed > 0):
        raise ValueError("mean_speed must be finite and > 0 rad/s")
    o = np.asarray(orders, dtype=float)
    return np.asarray(speed_coeffs, dtype=complex) / (1j * o * mean_speed)
