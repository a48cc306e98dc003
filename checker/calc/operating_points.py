"""Operating points of the speed sweep: cylinder-pressure traces given at a few speeds carried to
every swept speed, and the speed range the full-load data cover.

Both follow the practice of Bell (*Cranktrain Analysis Using ENGDYN and VALDYN*, Ricardo,
2013, 'Bearing analysis assumptions'): loads are evaluated at full and no load across the speed
range from the measured or given cylinder pressure, interpolated between the given speeds and
held (never extrapolated linearly) outside them, with the held points flagged.

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013, 'Bearing
   analysis assumptions'.
.. [2] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, sec. 2.7 (mean
   effective pressures).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

SPEED_TOLERANCE = 1e-9
"""Speeds closer than this [rad/s] are the same speed (tables round-trip through units)."""


def traces_at_speeds(table_speeds: ArrayLike, traces: ArrayLike, speeds: ArrayLike
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Pressure traces given at ``table_speeds`` carried to ``speeds``.

    Linear in speed between two given speeds, point by point along the crank angle::

        p(w, theta) = p_j(theta) + (p_{j+1}(theta) - p_j(theta)) (w - w_j) / (w_{j+1} - w_j)

    for ``w_j <= w < w_{j+1}``, and held at the nearest given trace outside the given range
    (explicit extrapolation, flagged). The arithmetic is that of :func:`numpy.interp`, applied
    to every crank angle at once.

    Parameters
    ----------
    table_speeds : array_like, shape (K,) [rad/s]
        Speeds of the given traces, strictly increasing, finite.
    traces : array_like, shape (K, N) [Pa]
        Given traces (any quantity over the crank angle), one row per table speed.
    speeds : array_like, shape (S,) [rad/s]
        Speeds wanted.

    Returns
    -------
    out : numpy.ndarray, shape (S, N)
        The traces at ``speeds``.
    extrapolated : numpy.ndarray of bool, shape (S,)
        Speeds outside ``[table_speeds[0], table_speeds[-1]]`` (by more than
        :data:`SPEED_TOLERANCE`): held at the nearest given trace.

    Examples
    --------
    >>> out, ex = traces_at_speeds([100.0, 200.0], [[1.0, 2.0], [3.0, 6.0]], [50.0, 150.0])
    >>> out.tolist(), ex.tolist()
    ([[1.0, 2.0], [2.0, 4.0]], [True, False])
    """
    xp = np.asarray(table_speeds, dtype=float)
    fp = np.asarray(traces, dtype=float)
    x = np.asarray(speeds, dtype=float)
    if xp.ndim != 1 or xp.size == 0 or fp.ndim != 2 or fp.shape[0] != xp.size:
        raise ValueError(f"traces_at_speeds: traces {fp.shape} must be (K, N) for {xp.size}"
                         " table speeds")
    if not (np.isfinite(xp).all() and np.isfinite(x).all()):
        raise ValueError("traces_at_speeds: speeds must be finite")
    if np.any(np.diff(xp) <= 0):
        raise ValueError("traces_at_speeds: table speeds must increase strictly")
    extrapolated = (x < xp[0] - SPEED_TOLERANCE) | (x > xp[-1] + SPEED_TOLERANCE)
    if xp.size == 1:
        return np.broadcast_to(fp[0], (x.size, fp.shape[1])).copy(), extrapolated
    j = np.clip(np.searchsorted(xp, x, side="right") - 1, 0, xp.size - 2)  # w_j <= w < w_j+1
    slope = (fp[1:] - fp[:-1]) / (xp[1:] - xp[:-1])[:, None]  # (K - 1, N)
    out = slope[j] * (x - xp[j])[:, None] + fp[j]
    out[x < xp[0]] = fp[0]
    out[x >= xp[-1]] = fp[-1]
    return out, extrapolated


def data_envelope(speeds: ArrayLike, data_speeds: ArrayLike) -> np.ndarray:
    """Swept ``speeds`` within the range of the speeds that have data (``data_speeds``).

    Bell (Ricardo 2013) evaluates full load where the engine has full-load data; beyond the
    first and last given full-load speed the points rest on held pressure and are not judged.

    Parameters
    ----------
    speeds : array_like, shape (S,) [rad/s]
    data_speeds : array_like, shape (D,) [rad/s], D >= 1

    Returns
    -------
    numpy.ndarray of bool, shape (S,)
        ``min(data) - tol <= speed <= max(data) + tol`` (:data:`SPEED_TOLERANCE`).

    Examples
    --------
    >>> data_envelope([100.0, 200.0, 300.0], [150.0, 200.0]).tolist()
    [False, True, False]
    """
    s = np.asarray(speeds, dtype=float)
    d = np.asarray(data_speeds, dtype=float)
    if d.size == 0:
        raise ValueError("data_envelope: no data speeds")
    return (s >= d.min() - SPEED_TOLERANCE) & (s <= d.max() + SPEED_TOLERANCE)


def full_load_target_imep(speeds: ArrayLike, torque_speeds: ArrayLike, brake_torque: ArrayLike,
                          total_displacement: float) -> tuple[np.ndarray, np.ndarray]:
    """Full-load IMEP target at the swept speeds: brake torque plus friction.

    ``imep = 4 pi T_b / V_D + FMEP`` (Heywood 1988, sec. 2.7; FMEP of Barnes-Moss,
    :func:`checker.calc.pressure.fmep_barnes_moss`), with ``T_b`` interpolated linearly in the
    BrakeTorque table. Outside the table's speed range the target is the one at the nearest
    table speed (torque **and** friction evaluated there): the trace there is that speed's trace
    instead of an uncalibrated, more severe one (the brake torque above the range then falls
    with the rising friction).

    Parameters
    ----------
    speeds : array_like, shape (S,) [rad/s]
        Swept speeds.
    torque_speeds : array_like, shape (K,) [rad/s]
        Speeds of the brake-torque table, in increasing order.
    brake_torque : array_like, shape (K,) [N m]
        Full-load brake torque of the whole engine at ``torque_speeds``.
    total_displacement : float [m^3]
        Swept volume of all cylinders.

    Returns
    -------
    target : numpy.ndarray, shape (S,) [Pa]
    held : numpy.ndarray, shape (S,) [rad/s]
        The speed each target is evaluated at (``speeds`` clipped to the table's range).

    Examples
    --------
    >>> import numpy as np
    >>> w = 2000 * np.pi / 30  # 2000 rpm: FMEP 0.97 + 0.3 + 0.2 = 1.47 bar
    >>> t, h = full_load_target_imep([w], [w / 2, 2 * w], [100.0, 100.0], 4 * np.pi * 1e-3)
    >>> round(float(t[0]) / 1e5, 6)  # BMEP = 4 pi 100 / (4 pi 1e-3) Pa = 1 bar
    2.47
    """
    from .pressure import fmep_barnes_moss, implied_imep

    s = np.asarray(speeds, dtype=float)
    ws = np.asarray(torque_speeds, dtype=float)
    tb = np.asarray(brake_torque, dtype=float)
    if ws.ndim != 1 or ws.size == 0 or tb.shape != ws.shape:
        raise ValueError("full_load_target_imep: torque_speeds and brake_torque must be (K,)")
    if np.any(np.diff(ws) < 0):
        raise ValueError("full_load_target_imep: torque speeds must increase")
    held = np.clip(s, ws[0], ws[-1])
    torque = np.interp(held, ws, tb)
    return implied_imep(torque, total_displacement, fmep_barnes_moss(held)), held
