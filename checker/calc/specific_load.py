"""Peak specific (projected-area) bearing load.

``p_spec = max_theta |F(theta)| / (D L_eff)`` per bearing, with the crank angle (and, for the
envelope over an operating-point axis, the speed) at which the maximum occurs. ``L_eff`` is the
effective shell length, excluding grooves and chamfers (the usual convention). Bell, Ricardo
2013, lists e.g. main bearings D = 55 mm, L_eff = 18.2 mm and big ends D = 48 mm, L_eff = 17.8 mm.

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013
   (projected-area specific loads, limiting values).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["PeakSpecificLoad", "WorstCase", "peak_specific_load", "worst_case"]


class PeakSpecificLoad(NamedTuple):
    """Maximum over the crank-angle axis; all arrays have the leading shape ``S`` of the loads.

    Attributes
    ----------
    specific_load : numpy.ndarray [Pa]
        ``max |F| / (D L_eff)``.
    force : numpy.ndarray [N]
        ``max |F|``.
    theta : numpy.ndarray [rad]
        Crank angle at the maximum (first one if several are equal).
    index : numpy.ndarray of int
        Index of that angle on the crank-angle axis.
    """

    specific_load: np.ndarray
    force: np.ndarray
    theta: np.ndarray
    index: np.ndarray


class WorstCase(NamedTuple):
    """Maximum of a :class:`PeakSpecificLoad` over one more axis (e.g. speed).

    Attributes
    ----------
    specific_load : numpy.ndarray [Pa]
    force : numpy.ndarray [N]
    theta : numpy.ndarray [rad]
        Crank angle of the maximum at the worst point.
    coordinate : numpy.ndarray
        Value of the reduced axis' coordinate (e.g. speed [rad/s]) at the maximum.
    index : numpy.ndarray of int
        Index along the reduced axis.
    """

    specific_load: np.ndarray
    force: np.ndarray
    theta: np.ndarray
    coordinate: np.ndarray
    index: np.ndarray


def peak_specific_load(
    force_x: ArrayLike,
    force_y: ArrayLike,
    theta: ArrayLike,
    diameter: ArrayLike,
    effective_length: ArrayLike,
) -> PeakSpecificLoad:
    """Peak specific load of each bearing over the crank-angle (last) axis.

    ``p_spec = max_k sqrt(F_x,k^2 + F_y,k^2) / (D L_eff)``

    Parameters
    ----------
    force_x, force_y : array_like, shape S + (N,) [N]
        Load components in any one frame (the magnitude does not depend on it), e.g.
        ``loads.big_end_block.x`` and ``.y`` of :func:`checker.calc.crank_forces.cylinder_loads`,
        with axes such as (load case, speed, bearing, crank angle).
    theta : array_like, shape (N,) [rad]
        Crank angles of the last axis.
    diameter : array_like, broadcast to S [m]
        Journal diameter ``D`` (> 0), e.g. shape (n_bearing,).
    effective_length : array_like, broadcast to S [m]
        Effective bearing length ``L_eff`` (> 0).

    Returns
    -------
    PeakSpecificLoad

    Notes
    -----
    Projected-area specific load, the usual lining-capacity measure (limits
    are indicative and method-dependent, Bell, Ricardo 2013: "Ricardo limiting values should
    only be
    applied when using Ricardo calculation methods"). The maximum is taken on the grid: its
    discretisation error is quantified in ``benchmarks/bench_loads.py``.
    """
    fx = np.asarray(force_x, dtype=float)
    fy = np.asarray(force_y, dtype=float)
    th = np.asarray(theta, dtype=float)
    if fx.shape != fy.shape or fx.ndim < 1 or th.shape != fx.shape[-1:]:
        raise ValueError("force_x and force_y must share a shape whose last axis matches theta")
    if not (np.all(np.isfinite(fx)) and np.all(np.isfinite(fy))):
        raise ValueError("bearing loads contain non-finite values")
    d = np.asarray(diameter, dtype=float)
    le = np.asarray(effective_length, dtype=float)
    if not (np.all(np.isfinite(d)) and np.all(d > 0)):
        raise ValueError("diameter must be finite and > 0 m")
    if not (np.all(np.isfinite(le)) and np.all(le > 0)):
        raise ValueError("effective_length must be finite and > 0 m")
    mag = np.hypot(fx, fy)
    idx = np.argmax(mag, axis=-1)
    fmax = np.take_along_axis(mag, idx[..., None], axis=-1)[..., 0]
    spec = fmax / (d * le)
    shape = spec.shape
    return PeakSpecificLoad(
        specific_load=spec,
        force=np.broadcast_to(fmax, shape),
        theta=np.broadcast_to(th[idx], shape),
        index=np.broadcast_to(idx, shape),
    )


def worst_case(peak: PeakSpecificLoad, coordinate: ArrayLike, axis: int) -> WorstCase:
    """Envelope of peak specific loads over one axis (e.g. the speed axis).

    Parameters
    ----------
    peak : PeakSpecificLoad
        Result of :func:`peak_specific_load`, leading shape ``S``.
    coordinate : array_like, shape (S[axis],)
        Coordinate values along ``axis`` (e.g. speeds [rad/s]).
    axis : int
        Axis of ``S`` to reduce (negative values count from the end of ``S``).

    Returns
    -------
    WorstCase
        Arrays of shape ``S`` without ``axis``.
    """
    spec = np.asarray(peak.specific_load)
    ax = axis % spec.ndim if spec.ndim else 0
    coord = np.asarray(coordinate)
    if spec.ndim == 0 or coord.shape != (spec.shape[ax],):
        raise ValueError("coordinate must have one value per element of the reduced axis")
    idx = np.expand_dims(np.argmax(spec, axis=ax), ax)

    def pick(a):
        return np.take_along_axis(np.broadcast_to(a, spec.shape), idx, axis=ax).squeeze(ax)

    return WorstCase(
        specific_load=pick(spec),
        force=pick(peak.force),
        theta=pick(peak.theta),
        coordinate=coord[idx.squeeze(ax)],
        index=idx.squeeze(ax),
    )
