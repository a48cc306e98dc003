"""Cylinder pressure over the 4-stroke cycle: user traces, synthesis for concept studies, IMEP.

Angles: the cycle angle of a cylinder is measured from **its own firing TDC**, ``0 <= theta <
4*pi`` (``theta = 0`` firing TDC, ``2*pi`` gas-exchange TDC); the crank-angle reference is the
geometric one of :mod:`checker.calc.kinematics`. Pressures are absolute [Pa].

Contents
--------
* :func:`interpolate_trace` - validate a user trace (crank angle vs pressure) and interpolate it
  periodically onto a cycle grid.
* :func:`synthesize_trace` - single-zone polytropic compression/expansion with a Wiebe heat
  release, calibrated so that the trace peaks at a given peak pressure (exactly, by a closed-form
  solve, see its Notes); :func:`cylinder_volume`, :func:`swept_volume`.
* :func:`indicated_mean_effective_pressure` - ``oint p dV / V_d``.
* :func:`fmep_barnes_moss`, :func:`fmep_chen_flynn`, :func:`bmep_from_torque`,
  :func:`implied_imep` - friction estimate and the brake-torque consistency check.
* :func:`calibrate_combustion_start` - optional secondary calibration: combustion phasing that
  also matches a target IMEP at the given peak pressure.
* :func:`peak_pressure_at_speed` - linear interpolation of a peak-pressure table over speed with an
  explicit extrapolation mask.

References
----------
.. [1] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, secs. 2.4, 2.7,
   7.6, ch. 9 sec. 9.2 (Wiebe function), ch. 13 (Barnes-Moss friction correlation).
.. [2] S. K. Chen, P. F. Flynn, SAE Technical Paper 650733, 1965 (friction mean effective pressure
   form).
.. [3] F. N. Fritsch, R. E. Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal.
   17(2), 1980.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from checker.calc.kinematics import FOUR_STROKE_CYCLE, dead_centres, slider_kinematics

__all__ = [
    "MAX_TRACE_GAP",
    "SynthesizedTrace",
    "bmep_from_torque",
    "calibrate_combustion_start",
    "cylinder_volume",
    "fmep_barnes_moss",
    "fmep_chen_flynn",
    "implied_imep",
    "indicated_mean_effective_pressure",
    "interpolate_trace",
    "peak_pressure_at_speed",
    "swept_volume",
    "synthesize_trace",
]

_CYCLE = FOUR_STROKE_CYCLE
_DEG = np.pi / 180.0
MAX_TRACE_GAP = 10.0 * _DEG
"""Largest accepted spacing of a pressure trace [rad] (10 deg, documented in the workbook)."""
_GAP_RTOL = 1e-9  # a spacing of exactly max_gap passes despite degree-to-radian round-off


# ---------------------------------------------------------------------------------------------
# (a) user traces
# ---------------------------------------------------------------------------------------------
def _periodic_linear(xp: np.ndarray, fp: np.ndarray, x: np.ndarray, period: float) -> np.ndarray:
    """Vectorized periodic linear interpolation along the last axis of ``fp``."""
    xp_ext = np.concatenate([xp[-1:] - period, xp, xp[:1] + period])
    fp_ext = np.concatenate([fp[..., -1:], fp, fp[..., :1]], axis=-1)
    xm = np.mod(x, period)
    i1 = np.clip(np.searchsorted(xp_ext, xm, side="right"), 1, xp_ext.size - 1)
    i0 = i1 - 1
    w = (xm - xp_ext[i0]) / (xp_ext[i1] - xp_ext[i0])
    return fp_ext[..., i0] * (1.0 - w) + fp_ext[..., i1] * w


def interpolate_trace(
    theta_data: ArrayLike,
    pressure_data: ArrayLike,
    theta: ArrayLike,
    *,
    firing_tdc: float = 0.0,
    max_gap: float = MAX_TRACE_GAP,
    method: str = "linear",
    endpoint_tolerance: float = 0.02,
) -> np.ndarray:
    """Validate a user pressure trace and interpolate it periodically onto cycle angles.

    Parameters
    ----------
    theta_data : array_like, shape (M,) [rad]
        Crank angles of the trace, strictly increasing, in the data's own scale (e.g. -2*pi..2*pi
        or 0..4*pi). They must span the cycle: no gap (including the wrap-around from the last to
        the first point) larger than ``max_gap`` and a total span of at most ``4*pi`` (a
        duplicated end point at exactly ``first + 4*pi`` is accepted and dropped).
    pressure_data : array_like, shape (..., M) [Pa]
        Absolute cylinder pressure; finite and > 0. Leading axes (e.g. load case, speed) are kept.
    theta : array_like, shape (N,) [rad]
        Cycle angles (from firing TDC) to interpolate at, e.g. :func:`~checker.calc.kinematics.
        cycle_grid`; any values, taken modulo ``4*pi``.
    firing_tdc : float [rad]
        Angle of firing TDC in the data's scale (``0`` for a -360..360 deg trace, ``2*pi`` for a
        0..720 deg trace with firing TDC at 360 deg).
    max_gap : float [rad]
        Largest accepted spacing between data points (default 10 deg; a spacing equal to it
        passes, within a relative round-off of 1e-9).
    method : {"linear", "pchip"}
        Periodic piecewise-linear (no overshoot, slightly cuts a coarse peak) or periodic
        monotone cubic (PCHIP, Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17(2); no overshoot
        either, better peak for coarse data).
    endpoint_tolerance : float [-]
        When the data include the duplicated end point, the two values may differ by at most this
        fraction of the trace maximum (otherwise the trace is not periodic: ``ValueError``).

    Returns
    -------
    numpy.ndarray, shape (..., N) [Pa]

    Notes
    -----
    Interpolation cannot create information: sample the source at <= 1 deg around the combustion
    peak (the interpolated peak of a linear interpolation is never above the data's maximum).
    """
    xp = np.asarray(theta_data, dtype=float)
    fp = np.asarray(pressure_data, dtype=float)
    th = np.asarray(theta, dtype=float)
    if xp.ndim != 1 or xp.size < 8:
        raise ValueError("theta_data must be 1-D with at least 8 points")
    if fp.shape[-1:] != xp.shape:
        raise ValueError(
            f"pressure_data last axis ({fp.shape[-1:]}) must match theta_data ({xp.shape})"
        )
    if not (np.all(np.isfinite(xp)) and np.all(np.isfinite(fp)) and np.all(np.isfinite(th))):
        raise ValueError("pressure trace and angles must be finite (no NaN/inf)")
    if np.any(fp <= 0):
        raise ValueError("pressure trace must be > 0 Pa (absolute pressure)")
    if np.any(np.diff(xp) <= 0):
        raise ValueError("theta_data must be strictly increasing")
    span = xp[-1] - xp[0]
    tol = 1e-9 * _CYCLE
    if span > _CYCLE + tol:
        raise ValueError(
            f"trace spans {np.rad2deg(span):.3f} deg, more than one 720 deg cycle; pass one cycle"
        )
    if span > _CYCLE - tol:  # duplicated end point
        mismatch = np.max(np.abs(fp[..., -1] - fp[..., 0]) / np.max(fp, axis=-1))
        if mismatch > endpoint_tolerance:
            raise ValueError(
                f"trace is not periodic: start and end values differ by {100 * mismatch:.1f} % of "
                "the peak pressure"
            )
        xp, fp = xp[:-1], fp[..., :-1]
    gaps = np.append(np.diff(xp), xp[0] + _CYCLE - xp[-1])
    k = int(np.argmax(gaps))
    if gaps[k] > max_gap * (1.0 + _GAP_RTOL):
        start = xp[k]
        raise ValueError(
            f"trace does not cover the 720 deg cycle: gap of {np.rad2deg(gaps[k]):.2f} deg after "
            f"{np.rad2deg(start):.2f} deg (max_gap {np.rad2deg(max_gap):.2f} deg)"
        )
    xm = np.mod(xp - firing_tdc, _CYCLE)
    order = np.argsort(xm, kind="stable")
    xm, fp = xm[order], fp[..., order]
    if np.any(np.diff(xm) <= 0):
        raise ValueError("theta_data maps two points onto the same cycle angle")
    if method == "linear":
        return _periodic_linear(xm, fp, th, _CYCLE)
    if method == "pchip":
        from scipy.interpolate import PchipInterpolator

        pad = 3
        xe = np.concatenate([xm[-pad:] - _CYCLE, xm, xm[:pad] + _CYCLE])
        fe = np.concatenate([fp[..., -pad:], fp, fp[..., :pad]], axis=-1)
        return PchipInterpolator(xe, fe, axis=-1)(np.mod(th, _CYCLE))
    raise ValueError(f"method must be 'linear' or 'pchip', got {method!r}")


# ---------------------------------------------------------------------------------------------
# (b) synthesis
# ---------------------------------------------------------------------------------------------
def swept_volume(
    bore: float,
    crank_radius: float,
    rod_length: float,
    cylinder_offset: float = 0.0,
    pin_offset: float = 0.0,
) -> float:
    """Swept volume of one cylinder, ``V_d = pi/4 B^2 * stroke`` (exact stroke with offset).

    Parameters
    ----------
    bore : float [m]
    crank_radius, rod_length : float [m]
    cylinder_offset, pin_offset : float [m]
        As in :func:`checker.calc.kinematics.slider_kinematics`.

    Returns
    -------
    float [m^3]

    Notes
    -----
    Stroke from :func:`checker.calc.kinematics.dead_centres` (``2 r`` for zero offset).
    """
    if not bore > 0:
        raise ValueError(f"bore must be > 0 m, got {bore!r}")
    _, _, stroke = dead_centres(crank_radius, rod_length, cylinder_offset, pin_offset)
    return float(np.pi / 4.0 * bore**2 * stroke)


def cylinder_volume(
    theta: ArrayLike,
    bore: float,
    crank_radius: float,
    rod_length: float,
    compression_ratio: float,
    cylinder_offset: float = 0.0,
    pin_offset: float = 0.0,
) -> np.ndarray:
    """Cylinder volume ``V = V_c + (pi/4) B^2 x(theta)``, ``V_c = V_d/(CR - 1)``.

    Parameters
    ----------
    theta : array_like [rad]
        Cycle (crank) angle from TDC.
    bore : float [m]
    crank_radius, rod_length : float [m]
    compression_ratio : float [-]
        Geometric ``CR = (V_c + V_d)/V_c`` (> 1).
    cylinder_offset, pin_offset : float [m]
        As in :func:`checker.calc.kinematics.slider_kinematics`.

    Returns
    -------
    numpy.ndarray [m^3], shape of ``theta``.

    Notes
    -----
    Heywood (1988), *Internal Combustion Engine Fundamentals*, eq. 2.4, with the piston
    displacement ``x`` of :func:`~checker.calc.kinematics.slider_kinematics` (exact with offset).
    """
    if not compression_ratio > 1:
        raise ValueError(f"compression_ratio must be > 1, got {compression_ratio!r}")
    vd = swept_volume(bore, crank_radius, rod_length, cylinder_offset, pin_offset)
    kin = slider_kinematics(theta, crank_radius, rod_length, 0.0, cylinder_offset, pin_offset)
    return vd / (compression_ratio - 1.0) + np.pi / 4.0 * bore**2 * kin.x


class SynthesizedTrace(NamedTuple):
    """Result of :func:`synthesize_trace` (leading shape ``S`` = broadcast of the case inputs).

    Attributes
    ----------
    pressure : numpy.ndarray, shape S + (N,) [Pa]
        Absolute cylinder pressure at the requested cycle angles.
    heat_release : numpy.ndarray, shape S [J]
        Calibrated total apparent heat release ``Q`` (0 for motored traces).
    intake_pressure : numpy.ndarray, shape S [Pa]
        Pressure at inlet valve closing actually used (lowered for motored traces).
    motored : numpy.ndarray of bool, shape S
        True where the requested peak was at or below the motored (no-combustion) peak and the
        trace was throttled instead (see ``below_motored``).
    peak_pressure : numpy.ndarray, shape S [Pa]
        Maximum of the trace on the internal fine grid (equals the requested peak).
    peak_angle : numpy.ndarray, shape S [rad]
        Cycle angle of that maximum (in ``(-2*pi, 2*pi]``, i.e. negative before firing TDC).
    """

    pressure: np.ndarray
    heat_release: np.ndarray
    intake_pressure: np.ndarray
    motored: np.ndarray
    peak_pressure: np.ndarray
    peak_angle: np.ndarray


def _wiebe(psi: np.ndarray, start: np.ndarray, duration: np.ndarray, a: float, m: float):
    """Wiebe burned fraction ``1 - exp(-a z^(m+1))``, ``z = max((psi - start)/duration, 0)``;
    the power and exponential only where ``z > 0`` (before the start the fraction is 0, as the
    formula gives: ``1 - exp(-0) = 0``), about half the grid of the closed cycle."""
    z = (psi - start) / duration
    out = np.zeros(z.shape)
    burn = z > 0.0
    zb = z[burn]
    out[burn] = 1.0 - np.exp(-a * zb ** (m + 1.0))
    return out


def synthesize_trace(
    theta: ArrayLike,
    peak_pressure: ArrayLike,
    *,
    bore: float,
    crank_radius: float,
    rod_length: float,
    compression_ratio: float,
    cylinder_offset: float = 0.0,
    pin_offset: float = 0.0,
    intake_pressure: ArrayLike = 1.0e5,
    exhaust_pressure: ArrayLike = 1.1e5,
    polytropic_exponent: ArrayLike = 1.32,
    combustion_start: ArrayLike = -15.0 * _DEG,
    combustion_duration: ArrayLike = 50.0 * _DEG,
    wiebe_a: float = 5.0,
    wiebe_m: float = 2.0,
    intake_closing: float = -140.0 * _DEG,
    exhaust_opening: float = 130.0 * _DEG,
    blowdown: float = 60.0 * _DEG,
    overlap: float = 20.0 * _DEG,
    below_motored: str = "throttle",
    resolution: float = 0.05 * _DEG,
) -> SynthesizedTrace:
    """Synthetic cylinder pressure calibrated to a given peak pressure (concept studies).

    Closed cycle (inlet closing ``IVC`` to exhaust opening ``EVO``): single-zone first law with a
    constant polytropic exponent ``k`` and an apparent heat release ``Q x_b(theta)``::

        dp/dtheta = [(k - 1) Q dx_b/dtheta - k p dV/dtheta] / V
        x_b = 1 - exp(-a ((theta - theta_s)/dtheta_b)^(m+1)),  theta >= theta_s   (Wiebe)

    (Heywood 1988, *Internal Combustion Engine Fundamentals*, ch. 9, sec. 9.2: single-zone
    apparent heat-release equation with constant ratio of specific heats, and the Wiebe
    mass-fraction-burned function with a = 5, m = 2; equation numbers not verified here),

    which integrates exactly (integrating factor ``V^k``) to::

        p(theta) V^k = p_IVC V_IVC^k + (k - 1) Q J(theta),  J = int_IVC^theta V^(k-1) dx_b

    so ``p = A(theta) + Q B(theta)`` is *linear* in ``Q``. The peak ``max_theta(A + Q B)`` is
    a continuous increasing function of ``Q`` and the ``Q`` that makes it equal the target ``p*``
    is ``min_theta (p* - A)/B`` over the points with ``B > 0`` (no iteration; evaluated on an
    internal grid of step ``resolution``, so the fine-grid peak equals ``p*`` to rounding).

    Gas exchange (documented simplification; hardly affects bearing loads): from ``EVO`` a
    cosine blow-down to ``exhaust_pressure`` over ``blowdown``; exhaust stroke at
    ``exhaust_pressure``; a cosine change-over to ``intake_pressure`` over ``overlap`` centred on
    gas-exchange TDC; intake at ``intake_pressure`` up to ``IVC``. The trace is continuous.

    Motored case: if ``p*`` is at or below the motored peak (``Q = 0``) and ``below_motored`` is
    ``"throttle"`` (default), the intake pressure is lowered (throttled) so that the motored trace
    peaks exactly at ``p*``; ``motored`` flags these cases. ``"raise"`` raises ``ValueError``
    instead.

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Cycle angles from firing TDC at which the trace is returned (taken modulo ``4*pi``).
    peak_pressure : array_like, shape S [Pa]
        Target peak (absolute) pressure per case, e.g. per load case x speed.
    bore, crank_radius, rod_length : float [m]
        Engine geometry.
    compression_ratio : float [-]
        Geometric compression ratio (> 1).
    cylinder_offset, pin_offset : float [m]
        Offsets as in :func:`checker.calc.kinematics.slider_kinematics`.
    intake_pressure : array_like, broadcast to S [Pa]
        Pressure at IVC and during the intake stroke (default 1.0e5).
    exhaust_pressure : array_like, broadcast to S [Pa]
        Exhaust-stroke pressure (default 1.1e5).
    polytropic_exponent : array_like, broadcast to S [-]
        ``k``, 1.1..1.5 (default 1.32, a typical value of the apparent-heat-release ratio of
        specific heats for SI engines, Heywood ch. 9).
    combustion_start : array_like, broadcast to S [rad]
        Wiebe start ``theta_s`` (default -15 deg, i.e. 15 deg before firing TDC).
    combustion_duration : array_like, broadcast to S [rad]
        Wiebe duration ``dtheta_b`` (default 50 deg; with a = 5, m = 2 the 50 % burn point is
        ~11 deg after TDC and the peak pressure ~15-20 deg after TDC).
    wiebe_a, wiebe_m : float [-]
        Wiebe efficiency and form factors (Heywood: a = 5, m = 2).
    intake_closing : float [rad]
        IVC = start of the closed cycle, in ``[-pi - 60 deg, -60 deg]`` (default -140 deg = 40 deg
        after BDC).
    exhaust_opening : float [rad]
        EVO = end of the closed cycle, in ``[60 deg, pi + 60 deg]`` (default 130 deg = 50 deg
        before BDC).
    blowdown, overlap : float [rad]
        Blow-down duration after EVO (default 60 deg) and intake/exhaust change-over width at
        gas-exchange TDC (default 20 deg).
    below_motored : {"throttle", "raise"}
        Treatment of targets at or below the motored peak (see above).
    resolution : float [rad]
        Step of the internal closed-cycle grid (default 0.05 deg).

    Returns
    -------
    SynthesizedTrace

    Notes
    -----
    A concept-level trace: single zone, no wall heat transfer model (absorbed in ``k`` and in the
    apparent heat release), no valve flow, no cycle-to-cycle variation. The peak pressure is
    matched exactly; the IMEP follows from the assumed phasing and should be compared with the
    brake torque (:func:`implied_imep`) or calibrated (:func:`calibrate_combustion_start`).
    """
    th = np.asarray(theta, dtype=float)
    if th.ndim != 1 or not np.all(np.isfinite(th)):
        raise ValueError("theta must be a finite 1-D array of cycle angles")
    p_star = np.asarray(peak_pressure, dtype=float)
    p_in = np.asarray(intake_pressure, dtype=float)
    p_ex = np.asarray(exhaust_pressure, dtype=float)
    k = np.asarray(polytropic_exponent, dtype=float)
    t_s = np.asarray(combustion_start, dtype=float)
    d_b = np.asarray(combustion_duration, dtype=float)
    for name, val in (
        ("peak_pressure", p_star),
        ("intake_pressure", p_in),
        ("exhaust_pressure", p_ex),
    ):
        if not np.all(np.isfinite(val)) or np.any(val <= 0):
            raise ValueError(f"{name} must be finite and > 0 Pa")
    if not np.all(np.isfinite(k)) or np.any((k < 1.1) | (k > 1.5)):
        raise ValueError(f"polytropic_exponent must be in [1.1, 1.5], got {polytropic_exponent!r}")
    if not np.all(np.isfinite(d_b)) or np.any(d_b <= 0):
        raise ValueError("combustion_duration must be > 0 rad")
    if not np.all(np.isfinite(t_s)):
        raise ValueError("combustion_start must be finite")
    if not (wiebe_a > 0 and wiebe_m >= 0):
        raise ValueError("wiebe_a must be > 0 and wiebe_m >= 0")
    if not -np.pi - 60 * _DEG <= intake_closing <= -60 * _DEG:
        raise ValueError("intake_closing must be within [-240, -60] deg (before firing TDC)")
    if not 60 * _DEG <= exhaust_opening <= np.pi + 60 * _DEG:
        raise ValueError("exhaust_opening must be within [60, 240] deg (after firing TDC)")
    if not (blowdown > 0 and overlap > 0):
        raise ValueError("blowdown and overlap must be > 0 rad")
    if exhaust_opening + blowdown > 2 * np.pi - overlap / 2:
        raise ValueError("exhaust_opening + blowdown must end before the valve overlap")
    if intake_closing < -2 * np.pi + overlap / 2:
        raise ValueError("intake_closing must lie after the valve overlap")
    if np.any(t_s <= intake_closing) or np.any(t_s >= exhaust_opening):
        raise ValueError("combustion_start must lie between intake_closing and exhaust_opening")
    if below_motored not in ("throttle", "raise"):
        raise ValueError(f"below_motored must be 'throttle' or 'raise', got {below_motored!r}")
    if not resolution > 0:
        raise ValueError("resolution must be > 0 rad")

    shape = np.broadcast_shapes(p_star.shape, p_in.shape, p_ex.shape, k.shape, t_s.shape, d_b.shape)
    p_star, p_in, p_ex = (np.broadcast_to(a, shape) for a in (p_star, p_in, p_ex))
    geo = dict(
        bore=bore,
        crank_radius=crank_radius,
        rod_length=rod_length,
        compression_ratio=compression_ratio,
        cylinder_offset=cylinder_offset,
        pin_offset=pin_offset,
    )

    # closed cycle on a fine uniform grid
    n_f = int(np.ceil((exhaust_opening - intake_closing) / resolution)) + 1
    psi = np.linspace(intake_closing, exhaust_opening, n_f)
    h_f = psi[1] - psi[0]
    vol = cylinder_volume(psi, **geo)  # (M,)
    # parameters keep their own (often scalar) shapes here so that the (M,)-long work is done
    # only once per distinct value; full S + (M,) arrays appear only where unavoidable
    kk = k[..., None]
    xb = _wiebe(psi, t_s[..., None], d_b[..., None], wiebe_a, wiebe_m)
    vk1 = vol ** (kk - 1.0)
    dj = 0.5 * (vk1[..., 1:] + vk1[..., :-1]) * np.diff(xb, axis=-1)
    jj = np.concatenate([np.zeros(dj.shape[:-1] + (1,)), np.cumsum(dj, axis=-1)], axis=-1)
    vk = vol**kk
    a_mot = p_in[..., None] * ((vol[0] / vol) ** kk)  # motored trace, S + (M,)
    b_q = np.broadcast_to((kk - 1.0) * jj / vk, shape + (n_f,))
    motored_peak = a_mot.max(axis=-1)
    motored = p_star <= motored_peak
    if np.any(motored) and below_motored == "raise":
        raise ValueError(
            "requested peak pressure is at or below the motored (no-combustion) peak "
            f"(min ratio {np.min(p_star / motored_peak):.3f}); lower intake_pressure or use "
            "below_motored='throttle'"
        )
    with np.errstate(divide="ignore", invalid="ignore"):
        q_cand = np.where(b_q > 0, (p_star[..., None] - a_mot) / b_q, np.inf)
    q = np.where(motored, 0.0, q_cand.min(axis=-1))
    if np.any(~np.isfinite(q)):
        raise ValueError("no heat release inside the closed cycle; check combustion_start")
    p_ivc = np.where(motored, p_in * p_star / motored_peak, p_in)
    p_fine = a_mot * (p_ivc / p_in)[..., None] + q[..., None] * b_q
    i_pk = np.argmax(p_fine, axis=-1)
    peak = np.take_along_axis(p_fine, i_pk[..., None], axis=-1)[..., 0]
    peak_angle = psi[i_pk]

    # assemble the full cycle at the requested angles (psi in [-2 pi, 2 pi))
    ps = np.mod(th + 2 * np.pi, _CYCLE) - 2 * np.pi
    out = np.empty(shape + th.shape)
    closed = (ps >= intake_closing) & (ps <= exhaust_opening)
    u = np.clip((ps[closed] - intake_closing) / h_f, 0.0, n_f - 1.0)
    i0 = np.minimum(np.floor(u).astype(int), n_f - 2)
    w = u - i0
    out[..., closed] = p_fine[..., i0] * (1.0 - w) + p_fine[..., i0 + 1] * w
    p_evo = p_fine[..., -1:]
    pin_, pex_ = p_ivc[..., None], p_ex[..., None]

    def blend(s):  # 1 -> 0 smoothly for s in [0, 1]
        return 0.5 * (1.0 + np.cos(np.pi * np.clip(s, 0.0, 1.0)))

    after = ps > exhaust_opening  # blow-down and exhaust stroke up to gas-exchange TDC
    s_bd = (ps[after] - exhaust_opening) / blowdown
    s_ov = (ps[after] - (2 * np.pi - overlap / 2)) / overlap
    base = pex_ + (p_evo - pex_) * blend(s_bd)
    out[..., after] = base + (pin_ - pex_) * (1.0 - blend(s_ov))
    before = ps < intake_closing  # from gas-exchange TDC (psi = -2 pi) to IVC
    s_ov = (ps[before] + 2 * np.pi + overlap / 2) / overlap
    out[..., before] = pex_ + (pin_ - pex_) * (1.0 - blend(s_ov))
    return SynthesizedTrace(
        pressure=out,
        heat_release=q,
        intake_pressure=p_ivc,
        motored=motored,
        peak_pressure=peak,
        peak_angle=peak_angle,
    )


def indicated_mean_effective_pressure(
    pressure: ArrayLike, volume: ArrayLike, swept_volume: float
) -> np.ndarray:
    """Net indicated mean effective pressure over one closed 720 deg cycle.

    ``IMEP = (oint p dV) / V_d`` with the periodic trapezoidal rule in ``V``::

        oint p dV ~= sum_k (p_k + p_{k+1})/2 (V_{k+1} - V_k),   index k+1 wraps to 0

    Parameters
    ----------
    pressure : array_like, shape (..., N) [Pa]
        Cylinder pressure on a uniform cycle grid without the end point.
    volume : array_like, shape (N,) or (..., N) [m^3]
        Cylinder volume at the same angles (:func:`cylinder_volume`).
    swept_volume : float [m^3]
        ``V_d`` of one cylinder (:func:`swept_volume`).

    Returns
    -------
    numpy.ndarray, shape (...) [Pa]

    Notes
    -----
    Heywood (1988), sec. 2.4 (net indicated work per cycle over all four strokes) and sec. 2.7
    (mep = work per cycle / V_d). Second-order accurate in the grid step; use <= 1 deg.
    """
    p = np.asarray(pressure, dtype=float)
    v = np.asarray(volume, dtype=float)
    if not swept_volume > 0:
        raise ValueError("swept_volume must be > 0 m^3")
    if p.shape[-1] != v.shape[-1] or p.shape[-1] < 8:
        raise ValueError("pressure and volume must share the crank-angle axis (>= 8 points)")
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(v))):
        raise ValueError("pressure and volume must be finite")
    dv = np.roll(v, -1, axis=-1) - v
    work = np.sum(0.5 * (p + np.roll(p, -1, axis=-1)) * dv, axis=-1)
    return work / swept_volume


def fmep_barnes_moss(omega: ArrayLike) -> np.ndarray:
    """Friction estimate: total motored FMEP of 4-cylinder SI engines vs speed.

    ``FMEP [bar] = 0.97 + 0.15 (N/1000) + 0.05 (N/1000)^2``, ``N`` in rev/min.

    Parameters
    ----------
    omega : array_like [rad/s]
        Crank speed.

    Returns
    -------
    numpy.ndarray [Pa]

    Notes
    -----
    Correlation of Barnes-Moss (1975) motored-engine data as given by Heywood (1988), *Internal
    Combustion Engine Fundamentals*, ch. 13 (equation number not verified here): 4-cylinder SI
    engines of 845-2000 cm^3, motored at wide-open throttle, so it includes the pumping loss of a
    motored engine. Indicative only (+-30 % for a modern engine); valid 1000-6000 rev/min
    (values outside are extrapolated; no flag, the estimate is only used for a consistency
    check).
    """
    w = np.asarray(omega, dtype=float)
    if not np.all(np.isfinite(w)) or np.any(w < 0):
        raise ValueError("omega must be finite and >= 0 rad/s")
    n_k = w * 60.0 / (2.0 * np.pi) / 1000.0
    return (0.97 + 0.15 * n_k + 0.05 * n_k**2) * 1.0e5


def fmep_chen_flynn(
    peak_pressure: ArrayLike,
    mean_piston_speed: ArrayLike,
    *,
    constant: float,
    peak_pressure_factor: float,
    speed_factor: float,
    speed_squared_factor: float,
) -> np.ndarray:
    """Chen-Flynn form of the friction mean effective pressure (coefficients from the user).

    ``FMEP = C + F_p p_max + F_s c_m + F_ss c_m^2``

    Parameters
    ----------
    peak_pressure : array_like [Pa]
        Peak cylinder pressure ``p_max``.
    mean_piston_speed : array_like [m/s]
        ``c_m = 2 * stroke * n`` (``n`` in rev/s).
    constant : float [Pa]
    peak_pressure_factor : float [-]
    speed_factor : float [Pa*s/m]
    speed_squared_factor : float [Pa*s^2/m^2]

    Returns
    -------
    numpy.ndarray [Pa]

    Notes
    -----
    Functional form of Chen & Flynn (1965), SAE 650733, as used in 1-D engine simulation codes
    (GT-Power, WAVE). No default coefficients are given here because none could be verified
    from a citable source; take them from the performance model of the engine. Use
    :func:`fmep_barnes_moss` for a stated default estimate.
    """
    pm = np.asarray(peak_pressure, dtype=float)
    cm = np.asarray(mean_piston_speed, dtype=float)
    if np.any(pm < 0) or np.any(cm < 0):
        raise ValueError("peak_pressure and mean_piston_speed must be >= 0")
    return constant + peak_pressure_factor * pm + speed_factor * cm + speed_squared_factor * cm**2


def bmep_from_torque(brake_torque: ArrayLike, total_displacement: float) -> np.ndarray:
    """Brake mean effective pressure of a 4-stroke engine, ``BMEP = 4 pi T_b / V_D``.

    Parameters
    ----------
    brake_torque : array_like [N*m]
    total_displacement : float [m^3]
        Swept volume of all cylinders.

    Returns
    -------
    numpy.ndarray [Pa]

    Notes
    -----
    Heywood (1988), sec. 2.7 (``bmep = 2 pi n_R T / V_d``, ``n_R = 2`` revolutions per cycle).
    """
    if not total_displacement > 0:
        raise ValueError("total_displacement must be > 0 m^3")
    return 4.0 * np.pi * np.asarray(brake_torque, dtype=float) / total_displacement


def implied_imep(brake_torque: ArrayLike, total_displacement: float, fmep: ArrayLike) -> np.ndarray:
    """IMEP implied by a brake torque and a friction estimate, ``BMEP + FMEP``.

    Compare with :func:`indicated_mean_effective_pressure` of the (synthesized) trace as a
    consistency check, or use it as the target of :func:`calibrate_combustion_start`.

    Parameters
    ----------
    brake_torque : array_like [N*m]
    total_displacement : float [m^3]
    fmep : array_like [Pa]
        E.g. :func:`fmep_barnes_moss`.

    Returns
    -------
    numpy.ndarray [Pa]

    Notes
    -----
    Heywood (1988), sec. 2.7: ``imep = bmep + fmep`` (fmep here including pumping, consistent
    with a net IMEP over 720 deg and a motored friction correlation).
    """
    return bmep_from_torque(brake_torque, total_displacement) + np.asarray(fmep, dtype=float)


INTAKE_FLOOR = 0.3e5
"""Lowest intake pressure [Pa] for the low-load calibration of
:func:`calibrate_combustion_start` (about the closed-throttle manifold pressure of a gasoline
engine at idle; Heywood 1988, sec. 7.6)."""
INTAKE_TOLERANCE = 1e-4
"""Relative width of the intake-pressure bisection (2^-14 of the bracket; the IMEP then within
about 0.2 %, 10 x inside the 2 % the check asks)."""
LOW_LOAD_START = -15.0 * _DEG
"""Combustion start of the low-load calibration (the default phasing of
:func:`synthesize_trace`)."""


def calibrate_combustion_start(
    theta: ArrayLike,
    peak_pressure: ArrayLike,
    target_imep: ArrayLike,
    *,
    bounds: tuple[float, float] = (-45.0 * _DEG, 15.0 * _DEG),
    tolerance: float = 0.01 * _DEG,
    intake_floor: float | None = None,
    **synthesis_kwargs,
) -> tuple[SynthesizedTrace, np.ndarray, np.ndarray]:
    """Secondary calibration: Wiebe start angle so that the trace also matches a target IMEP.

    For each case the peak pressure is matched exactly by :func:`synthesize_trace`; the start
    of combustion ``theta_s`` is then found by vectorized bisection on
    ``IMEP(theta_s) - IMEP_target`` within ``bounds``. At fixed peak pressure the IMEP rises as
    combustion is retarded (more heat is needed to reach the same peak), which makes the
    bisection well posed inside the bracket; cases whose target is not bracketed are returned at
    the nearer bound and flagged.

    Low load (with ``intake_floor``): where the target IMEP lies *above* every IMEP the phasing
    can reach (typically a no-load point whose peak pressure is at or below the motored peak at
    the given intake pressure: the trace is then throttled, carries no heat release and its IMEP
    is the pumping loop only, e.g. 0.45 bar against a 1.2-1.8 bar friction target on a boosted
    diesel whose one intake pressure is the full-load boost), the intake pressure is lowered
    instead, with the combustion start at :data:`LOW_LOAD_START`: below the motored-peak value,
    reaching the same peak needs heat release, and the IMEP rises continuously and
    monotonically as the intake pressure falls (more heat for the same peak). The intake
    pressure is found by bisection in ``[intake_floor, intake_pressure]`` to
    :data:`INTAKE_TOLERANCE` (relative); ``trace.intake_pressure`` reports it.

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Uniform cycle grid (without end point) used for the trace and its IMEP.
    peak_pressure : array_like, shape S [Pa]
    target_imep : array_like, broadcast to S [Pa]
        E.g. :func:`implied_imep`.
    bounds : (float, float) [rad]
        Bracket for ``theta_s`` (default -45..+15 deg).
    tolerance : float [rad]
        Bisection stops when the bracket is narrower (default 0.01 deg).
    **synthesis_kwargs
        Geometry and remaining keywords of :func:`synthesize_trace` (not ``combustion_start``).

    Returns
    -------
    trace : SynthesizedTrace
        Trace at the calibrated start angle.
    combustion_start : numpy.ndarray, shape S [rad]
    not_matched : numpy.ndarray of bool, shape S
        True where the target IMEP lies outside the IMEP range reachable within ``bounds`` (or
        the case is motored); the trace there is the closest bound's.

    Notes
    -----
    Models as :func:`synthesize_trace`; whether the resulting phasing is physical must be judged
    by the user (reported ``combustion_start`` and ``trace.peak_angle``).
    """
    if "combustion_start" in synthesis_kwargs:
        raise ValueError("combustion_start is the calibrated quantity; do not pass it")
    missing = {"bore", "crank_radius", "rod_length", "compression_ratio"} - synthesis_kwargs.keys()
    if missing:
        raise TypeError(f"calibrate_combustion_start needs the geometry keywords {sorted(missing)}")
    th = np.asarray(theta, dtype=float)
    geo = {
        key: synthesis_kwargs[key]
        for key in (
            "bore",
            "crank_radius",
            "rod_length",
            "compression_ratio",
            "cylinder_offset",
            "pin_offset",
        )
        if key in synthesis_kwargs
    }
    vol = cylinder_volume(th, **geo)
    vd = swept_volume(
        geo["bore"],
        geo["crank_radius"],
        geo["rod_length"],
        geo.get("cylinder_offset", 0.0),
        geo.get("pin_offset", 0.0),
    )
    p_star = np.asarray(peak_pressure, dtype=float)
    target = np.broadcast_to(np.asarray(target_imep, dtype=float), p_star.shape)
    lo = np.full(p_star.shape, float(bounds[0]))
    hi = np.full(p_star.shape, float(bounds[1]))

    def imep_at(start):
        tr = synthesize_trace(th, p_star, combustion_start=start, **synthesis_kwargs)
        return tr, indicated_mean_effective_pressure(tr.pressure, vol, vd)

    _, f_lo = imep_at(lo)
    _, f_hi = imep_at(hi)
    f_lo, f_hi = f_lo - target, f_hi - target
    increasing = f_hi >= f_lo
    bracketed = (np.sign(f_lo) != np.sign(f_hi)) | (f_lo == 0) | (f_hi == 0)
    n_iter = int(np.ceil(np.log2(max((bounds[1] - bounds[0]) / tolerance, 2.0))))
    for _ in range(n_iter):
        mid = 0.5 * (lo + hi)
        _, f_mid = imep_at(mid)
        f_mid = f_mid - target
        go_up = (f_mid < 0) == increasing  # root above mid
        lo = np.where(go_up, mid, lo)
        hi = np.where(go_up, hi, mid)
    start = 0.5 * (lo + hi)
    # unbracketed cases: nearer bound (smaller |IMEP - target|)
    start = np.where(
        bracketed, start, np.where(np.abs(f_lo) <= np.abs(f_hi), bounds[0], bounds[1])
    )
    # low load: the target above every reachable IMEP -> lower the intake pressure instead
    too_low = ~bracketed & (np.maximum(f_lo, f_hi) < 0)
    if intake_floor is None or not np.any(too_low):
        trace, _ = imep_at(start)
        return trace, start, ~bracketed | trace.motored
    start = np.where(too_low, LOW_LOAD_START, start)
    trace, _ = imep_at(start)
    p_in = np.broadcast_to(np.asarray(synthesis_kwargs.get("intake_pressure", 1.0e5),
                                      dtype=float), p_star.shape)
    sub = {k: v for k, v in synthesis_kwargs.items() if k != "intake_pressure"}
    idx = too_low  # boolean mask (also for 0-d inputs)
    ps, tg, st = p_star[idx], target[idx], start[idx]
    hi_p = np.array(p_in[idx], dtype=float)  # IMEP too low here
    lo_p = np.full(ps.shape, float(intake_floor))

    def imep_in(pi):
        tr = synthesize_trace(th, ps, combustion_start=st, intake_pressure=pi, **sub)
        return tr, indicated_mean_effective_pressure(tr.pressure, vol, vd)

    _, f_floor = imep_in(lo_p)
    ok = f_floor >= tg  # reachable within [floor, given intake]
    for _ in range(int(np.ceil(np.log2(1.0 / INTAKE_TOLERANCE)))):
        mid = 0.5 * (lo_p + hi_p)
        _, f_mid = imep_in(mid)
        up = f_mid >= tg  # the IMEP falls as the intake pressure rises: root above mid
        lo_p = np.where(up, mid, lo_p)
        hi_p = np.where(up, hi_p, mid)
    tr_low, _ = imep_in(np.where(ok, 0.5 * (lo_p + hi_p), float(intake_floor)))
    fields = {f: np.array(getattr(trace, f), copy=True) for f in SynthesizedTrace._fields}
    for f in fields:
        fields[f][idx] = getattr(tr_low, f)
    trace = SynthesizedTrace(**fields)
    matched = np.zeros(p_star.shape, dtype=bool)
    matched[idx] = ok
    return trace, start, (~bracketed | trace.motored) & ~matched


# ---------------------------------------------------------------------------------------------
# (c) peak pressure vs speed
# ---------------------------------------------------------------------------------------------
def peak_pressure_at_speed(
    table_speed: ArrayLike,
    table_peak_pressure: ArrayLike,
    omega: ArrayLike,
    extrapolation: str = "constant",
) -> tuple[np.ndarray, np.ndarray]:
    """Peak cylinder pressure at the requested speeds by linear interpolation of a table.

    Parameters
    ----------
    table_speed : array_like, shape (K,) [rad/s]
        Strictly increasing table speeds (K >= 1).
    table_peak_pressure : array_like, shape (K,) [Pa]
        Peak pressures at those speeds (> 0).
    omega : array_like [rad/s]
        Speeds to evaluate (any shape).
    extrapolation : {"constant", "linear", "raise"}
        Outside the table: hold the end value (default; the only option for a single-point
        table), extend the end segment linearly (``ValueError`` if that reaches <= 0 Pa), or
        raise ``ValueError``.

    Returns
    -------
    peak : numpy.ndarray, shape of ``omega`` [Pa]
    extrapolated : numpy.ndarray of bool, shape of ``omega``
        True where ``omega`` lies outside ``[table_speed[0], table_speed[-1]]`` (relative
        tolerance 1e-9): these values are not backed by the table and must be reported as such.

    Notes
    -----
    Piecewise-linear interpolation (``numpy.interp``); no smoothing.
    """
    xs = np.asarray(table_speed, dtype=float)
    ys = np.asarray(table_peak_pressure, dtype=float)
    w = np.asarray(omega, dtype=float)
    if xs.ndim != 1 or xs.shape != ys.shape or xs.size < 1:
        raise ValueError("table_speed and table_peak_pressure must be 1-D of equal length >= 1")
    if not (np.all(np.isfinite(xs)) and np.all(np.isfinite(ys)) and np.all(np.isfinite(w))):
        raise ValueError("speeds and pressures must be finite")
    if np.any(ys <= 0):
        raise ValueError("table_peak_pressure must be > 0 Pa")
    if np.any(np.diff(xs) <= 0):
        raise ValueError("table_speed must be strictly increasing")
    if extrapolation not in ("constant", "linear", "raise"):
        raise ValueError(f"unknown extrapolation {extrapolation!r}")
    tol = 1e-9 * max(abs(xs[-1]), 1.0)
    below, above = w < xs[0] - tol, w > xs[-1] + tol
    extrapolated = below | above
    if extrapolation == "raise" and np.any(extrapolated):
        raise ValueError(
            "speed outside the peak-pressure table "
            f"[{xs[0]:.6g}, {xs[-1]:.6g}] rad/s: {np.unique(w[extrapolated])}"
        )
    peak = np.interp(w, xs, ys)
    if extrapolation == "linear" and np.any(extrapolated):
        if xs.size < 2:
            raise ValueError("linear extrapolation needs at least two table points")
        s0 = (ys[1] - ys[0]) / (xs[1] - xs[0])
        s1 = (ys[-1] - ys[-2]) / (xs[-1] - xs[-2])
        peak = np.where(below, ys[0] + s0 * (w - xs[0]), peak)
        peak = np.where(above, ys[-1] + s1 * (w - xs[-1]), peak)
        if np.any(peak <= 0):
            raise ValueError("linear extrapolation of the peak pressure reaches <= 0 Pa")
    return peak, extrapolated
