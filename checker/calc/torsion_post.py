"""Post-processing of a torsional forced response (pure NumPy): extremes of synthesised
signals, mean element torques of a lumped-mass chain, the rigid-body / elastic split of the
station motion, and the peak torque through a torque cut.

Conventions as :mod:`checker.calc.torsional`: ``x(theta) = sum_n Re{X_n exp(j n theta)}`` over
one 720 deg cycle, order axis last; elements of a chain join station ``e`` to ``e + 1``; element
torque positive when the front station leads (the torque the front part exerts on the rear
part, positive in the direction of rotation).

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013
   (concept-level torsional vibration analysis with VALDYN).
.. [2] M. I. Friswell, J. E. T. Penny, S. D. Garvey, A. W. Lees, "Dynamics of Rotating Machines",
   Cambridge University Press, 2010, ch. 3 (free-free rotor modes, mass orthogonality).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .torsional import synthesize

EXTREMES_SAMPLES_PER_PERIOD = 16
"""Samples per period of the highest order for :func:`synthesized_extremes`."""


def synthesized_extremes(orders: ArrayLike, coeffs: ArrayLike,
                         samples_per_period: int = EXTREMES_SAMPLES_PER_PERIOD
                         ) -> tuple[np.ndarray, np.ndarray]:
    """Max and min over 720 deg of ``x(theta) = sum_n Re{c_n exp(j n theta)}``.

    The signal is sampled by :func:`checker.calc.torsional.synthesize` with
    ``samples_per_period`` samples per period of the highest order (at least 64 per cycle);
    the extreme sample is refined by the vertex of the parabola through it and its two
    neighbours (error O(h^4) of the signal's smooth part; at the default sampling within
    1e-3 of ``sum |c_n|``, tests/calc/test_torsion_post.py). For the exact half range use
    :func:`checker.calc.torsional.half_peak_to_peak`.

    Parameters
    ----------
    orders : array_like, shape (O,) [-]
        Positive multiples of 0.5, no duplicates.
    coeffs : array_like, shape (..., O), complex [any unit]
        Order axis last.
    samples_per_period : int
        Samples per period of the highest order.

    Returns
    -------
    x_max, x_min : numpy.ndarray, shape (...) [unit of coeffs]

    Examples
    --------
    ``cos(theta) + 0.5 cos(2 theta)`` has its maximum 1.5 at 0 and its minimum -0.75 where
    ``cos(theta) = -1/2``:

    >>> import numpy as np
    >>> hi, lo = synthesized_extremes([1.0, 2.0], np.array([1.0, 0.5]))
    >>> round(float(hi), 3), round(float(lo), 2)
    (1.5, -0.75)
    """
    orders = np.asarray(orders, dtype=float).ravel()
    if samples_per_period < 4:
        raise ValueError("samples_per_period must be at least 4")
    m = int(round(2 * orders.max()))  # FFT bin of the highest order (2 periods per cycle)
    n_pts = max(64, samples_per_period * m)
    _, x = synthesize(orders, coeffs, n_pts)

    def top(y: np.ndarray) -> np.ndarray:
        k = np.argmax(y, axis=-1)[..., None]
        y0 = np.take_along_axis(y, k, -1)[..., 0]
        ym = np.take_along_axis(y, (k - 1) % n_pts, -1)[..., 0]
        yp = np.take_along_axis(y, (k + 1) % n_pts, -1)[..., 0]
        a = 0.5 * (ym + yp - 2.0 * y0)
        b = 0.5 * (yp - ym)
        return np.where(a < 0, y0 - b * b / (4.0 * np.where(a < 0, a, -1.0)), y0)

    return top(x), -top(-x)


def mean_element_torque(cylinder_mean: ArrayLike, cylinder_station: ArrayLike,
                        n_stations: int, nose: int, fead_torque: float) -> np.ndarray:
    """Mean torque in every element of a chain from the mean cylinder torques.

    ``T_mean,e = sum_{cylinder stations i <= e} mean(T_cyl) - T_FEAD [nose <= e]``: the mean
    (indicated) torque of every cylinder applied at its station, the accessory-drive torque
    taken off at the crank-nose station, summed from the front (static equilibrium of the
    chain's front part; Bell, Ricardo 2013). Friction is not subtracted, so the flywheel
    element carries brake torque plus friction torque.

    Parameters
    ----------
    cylinder_mean : array_like, shape (...) [N m]
        Mean crank torque of one cylinder (all cylinders alike).
    cylinder_station : array_like of int, shape (n_cyl,)
        Station of each cylinder (several cylinders may share one).
    n_stations : int
        Stations of the chain (``n_stations - 1`` elements).
    nose : int
        Station index of the crank nose.
    fead_torque : float [N m]
        Accessory-drive torque taken off at the crank nose (0: none).

    Returns
    -------
    numpy.ndarray, shape (..., n_stations - 1) [N m]

    Examples
    --------
    Four cylinders of 10 N m at stations 2..5 of a 7-station chain, 19 N m FEAD at station 1:

    >>> mean_element_torque(10.0, [2, 3, 4, 5], 7, 1, 19.0).tolist()
    [0.0, -19.0, -9.0, 1.0, 11.0, 21.0]
    """
    cm = np.asarray(cylinder_mean, dtype=float)
    st = np.asarray(cylinder_station, dtype=int)
    if n_stations < 2:
        raise ValueError("a chain needs at least two stations")
    if st.size and (st.min() < 0 or st.max() >= n_stations):
        raise ValueError("cylinder_station must index the stations")
    if not 0 <= nose < n_stations:
        raise ValueError("nose must index a station")
    applied = np.zeros(cm.shape + (n_stations,))
    np.add.at(applied, (..., st), np.broadcast_to(cm[..., None], cm.shape + (st.size,)))
    applied[..., nose] -= fead_torque
    return np.cumsum(applied, axis=-1)[..., :n_stations - 1]


def rigid_body_angle(theta: ArrayLike, inertia: ArrayLike, axis: int = -2) -> np.ndarray:
    """Rigid-body angle of a lumped-mass rotor: the inertia-weighted mean station angle.

    ``theta_rb = sum_i J_i theta_i / sum_i J_i``: the modal coordinate of the free rotor's
    rigid-body mode, which is mass-orthogonal to every flexible mode (``sum J_i phi_i = 0``;
    Friswell et al. 2010, ch. 3), so ``theta - theta_rb`` is the elastic motion.

    Parameters
    ----------
    theta : array_like, shape (..., n, ...) [rad] (real or complex)
        Station angles, station axis ``axis``.
    inertia : array_like, shape (n,) [kg m^2]
        Station inertias, positive.
    axis : int
        The station axis of ``theta``.

    Returns
    -------
    numpy.ndarray, ``theta`` without the station axis [rad]

    Examples
    --------
    >>> rigid_body_angle([[1.0], [3.0]], [1.0, 3.0], axis=0).tolist()
    [2.5]
    """
    j = np.asarray(inertia, dtype=float)
    if j.ndim != 1 or np.any(j <= 0):
        raise ValueError("inertia must be a 1-D array of positive values")
    th = np.moveaxis(np.asarray(theta), axis, -1)
    return np.tensordot(th, j, axes=([-1], [0])) / j.sum()


def peak_cut_torque(mean: ArrayLike, vib_max: ArrayLike, vib_min: ArrayLike) -> np.ndarray:
    """Peak over the cycle of the magnitude of the total torque through a cut.

    ``max_t |T_mean + T_vib(t)| = max(|T_mean + max T_vib|, |T_mean + min T_vib|)`` (the
    magnitude of a signal is largest at its maximum or its minimum).

    Parameters
    ----------
    mean, vib_max, vib_min : array_like (broadcast) [N m]
        Mean torque and the max/min of the vibratory torque over the cycle.

    Returns
    -------
    numpy.ndarray [N m]

    Examples
    --------
    >>> float(peak_cut_torque(-19.0, 30.0, -40.0))
    59.0
    """
    m = np.asarray(mean, dtype=float)
    return np.maximum(np.abs(m + np.asarray(vib_max, dtype=float)),
                      np.abs(m + np.asarray(vib_min, dtype=float)))
