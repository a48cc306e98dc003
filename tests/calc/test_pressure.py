"""Tests for checker.calc.pressure (traces, synthesis, IMEP, friction, peak-pressure table)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from checker.calc.kinematics import cycle_grid, slider_kinematics
from checker.calc.pressure import (
    bmep_from_torque,
    calibrate_combustion_start,
    cylinder_volume,
    fmep_barnes_moss,
    fmep_chen_flynn,
    implied_imep,
    indicated_mean_effective_pressure,
    interpolate_trace,
    peak_pressure_at_speed,
    swept_volume,
    synthesize_trace,
)

MM, BAR, DEG = 1e-3, 1e5, np.pi / 180
RPM = np.pi / 30
GEO = dict(
    bore=86 * MM, crank_radius=47.3 * MM, rod_length=145.7 * MM, compression_ratio=10.5,
    pin_offset=0.8 * MM,
)  # seed 000 example engine; compression ratio assumed (not in the seed)
VD = swept_volume(86 * MM, 47.3 * MM, 145.7 * MM, 0.0, 0.8 * MM)


def _smooth_trace(theta):
    """Analytic positive periodic test function (period 4 pi) with a sharp-ish peak at 15 deg."""
    return (1.0 + 60.0 * np.exp(-(((np.mod(theta + 2 * np.pi, 4 * np.pi) - 2 * np.pi
                                    - 15 * DEG) / (25 * DEG)) ** 2))) * BAR


# ------------------------------------------------------------------------------- traces
def test_interpolate_trace_linear_error_bound_and_nodes():
    # Linear interpolation error <= h^2/8 max|f''| (standard bound); data at 0.5 deg, grid
    # 0.1 deg; f'' of the test function <= 2 * 60 bar / (25 deg)^2 -> bound ~0.33 bar... use the
    # numerically evaluated max|f''|. Data nodes are reproduced exactly.
    xd = np.arange(-360.0, 360.0, 0.5) * DEG
    fd = _smooth_trace(xd)
    th = cycle_grid(0.1 * DEG)
    out = interpolate_trace(xd, fd, th)
    h = 0.5 * DEG
    fine = np.linspace(-60, 90, 150001) * DEG
    f2 = np.abs(np.gradient(np.gradient(_smooth_trace(fine), fine), fine)).max()
    assert np.max(np.abs(out - _smooth_trace(th))) <= h**2 / 8 * f2 * 1.001
    on_nodes = np.isclose(np.mod(np.rad2deg(th), 0.5), 0.0) | np.isclose(
        np.mod(np.rad2deg(th), 0.5), 0.5
    )
    np.testing.assert_allclose(out[on_nodes], _smooth_trace(th[on_nodes]), rtol=1e-12)


def test_interpolate_trace_conventions_and_leading_axes():
    # Duplicated end point (-360..360 inclusive) is dropped; a 0..720 trace with firing TDC at
    # 360 deg gives the same result; leading axes (case, speed) are kept. Exact identity.
    xd = np.arange(-360.0, 360.01, 1.0) * DEG
    fd = np.stack([_smooth_trace(xd), 2 * _smooth_trace(xd)])
    th = cycle_grid(0.25 * DEG)
    a = interpolate_trace(xd, fd, th)
    b = interpolate_trace(xd + 2 * np.pi, fd, th, firing_tdc=2 * np.pi)
    assert a.shape == (2, th.size)
    np.testing.assert_allclose(a, b, rtol=1e-12)
    np.testing.assert_allclose(a[1], 2 * a[0], rtol=1e-12)
    # PCHIP: nodes exact, no overshoot above the data maximum (Fritsch & Carlson 1980)
    c = interpolate_trace(xd, fd, th, method="pchip")
    assert c.max() <= fd.max() * (1 + 1e-12)
    np.testing.assert_allclose(c[:, ::4], a[:, ::4], rtol=1e-12)


@pytest.mark.parametrize(
    ("xd", "fd_mod", "match"),
    [
        (np.arange(-360.0, 360.0, 1.0), lambda f: np.where(np.arange(f.size) == 5, np.nan, f),
         "finite"),
        (np.arange(-360.0, 360.0, 1.0), lambda f: -f, "> 0"),
        (np.arange(-300.0, 360.0, 1.0), lambda f: f, "gap"),
        (np.arange(-360.0, 400.0, 1.0), lambda f: f, "more than one"),
        (np.arange(-360.0, 360.1, 1.0), lambda f: np.where(np.arange(f.size) == f.size - 1,
                                                           3 * f, f), "not periodic"),
        (np.arange(-360.0, 360.0, 1.0)[::-1], lambda f: f, "increasing"),
    ],
)
def test_interpolate_trace_rejects_bad_traces(xd, fd_mod, match):
    fd = fd_mod(_smooth_trace(np.asarray(xd) * DEG))
    with pytest.raises(ValueError, match=match):
        interpolate_trace(np.asarray(xd) * DEG, fd, cycle_grid(1 * DEG))


# ------------------------------------------------------------------------------- synthesis
def test_synthesized_trace_reaches_peak_pressure():
    # Brief requirement: peak of the synthesized trace within 0.5 % of the target. Checked on an
    # independent 0.1 deg output grid (sampling can only lower the peak) and on the internal
    # grid (closed-form calibration, rounding level 1e-9).
    targets = np.array([[53.4, 84.4, 73.3], [29.1, 120.0, 40.0]]) * BAR
    th = cycle_grid(0.1 * DEG)
    tr = synthesize_trace(th, targets, **GEO)
    np.testing.assert_allclose(tr.pressure.max(axis=-1), targets, rtol=5e-3)
    np.testing.assert_allclose(tr.peak_pressure, targets, rtol=1e-9)
    assert not tr.motored.any()
    assert np.all(tr.heat_release > 0)
    # physically placed peak: after TDC, before 40 deg ATDC
    assert np.all((tr.peak_angle > 0) & (tr.peak_angle < 40 * DEG))


def test_synthesis_matches_ode_integration():
    # Independent check of the integrating-factor solution: integrate the single-zone equation
    # dp/dtheta = [(k-1) Q dx_b/dtheta - k p dV/dtheta]/V (Heywood 1988 ch. 9) with
    # scipy's RK45 (rtol 1e-10) for the calibrated Q; agreement 1e-4 relative (trapezoidal
    # cumulative heat-release integral on the 0.05 deg internal grid).
    th = cycle_grid(1.0 * DEG)
    k, ts, db = 1.3, -12 * DEG, 45 * DEG
    tr = synthesize_trace(
        th, 80 * BAR, polytropic_exponent=k, combustion_start=ts, combustion_duration=db, **GEO
    )
    q = float(tr.heat_release)
    area = np.pi / 4 * GEO["bore"] ** 2

    def rhs(t, p):
        vol = cylinder_volume(t, **GEO)
        dv = area * slider_kinematics(t, 47.3 * MM, 145.7 * MM, 1.0, 0.0, 0.8 * MM).dx_dtheta
        z = max((t - ts) / db, 0.0)
        dxb = 5.0 * 3.0 * z**2 * np.exp(-5.0 * z**3) / db
        return [((k - 1) * q * dxb - k * p[0] * dv) / vol]

    ivc, evo = -140 * DEG, 130 * DEG
    psi = np.mod(th + 2 * np.pi, 4 * np.pi) - 2 * np.pi
    sel = (psi >= ivc) & (psi <= evo)
    order = np.argsort(psi[sel])
    t_eval = psi[sel][order]
    sol = solve_ivp(rhs, (ivc, evo), [1.0e5], t_eval=t_eval, rtol=1e-10, atol=1e-3, max_step=0.02)
    np.testing.assert_allclose(tr.pressure[sel][order], sol.y[0], rtol=1e-4)


def test_motored_trace_is_polytropic_and_throttled():
    # Closed form: with Q = 0, p = p_IVC (V_IVC/V)^k (polytropic law). A target below the motored
    # peak throttles the intake so that the motored peak equals the target (documented choice).
    th = cycle_grid(0.25 * DEG)
    tr = synthesize_trace(th, 10 * BAR, **GEO)
    assert tr.motored and tr.heat_release == 0.0
    assert tr.intake_pressure < 1.0e5
    psi = np.mod(th + 2 * np.pi, 4 * np.pi) - 2 * np.pi
    sel = (psi >= -140 * DEG) & (psi <= 130 * DEG)
    v = cylinder_volume(th[sel], **GEO)
    v_ivc = cylinder_volume(-140 * DEG, **GEO)
    np.testing.assert_allclose(tr.pressure[sel], tr.intake_pressure * (v_ivc / v) ** 1.32,
                               rtol=1e-6)
    np.testing.assert_allclose(tr.peak_pressure, 10 * BAR, rtol=1e-9)
    with pytest.raises(ValueError, match="motored"):
        synthesize_trace(th, 10 * BAR, below_motored="raise", **GEO)


def test_synthesized_trace_is_continuous_and_positive():
    # Continuity of the assembled cycle (gas exchange blends): no jump between 0.1 deg points
    # larger than the steepest combustion rise (< 1 % of the peak per 0.1 deg here).
    th = cycle_grid(0.1 * DEG)
    tr = synthesize_trace(th, 84.4 * BAR, **GEO)
    p = tr.pressure
    jumps = np.abs(np.diff(np.append(p, p[0])))
    assert jumps.max() < 0.01 * p.max()
    assert p.min() > 0.5 * BAR


def test_synthesis_input_validation():
    th = cycle_grid(1 * DEG)
    with pytest.raises(ValueError, match="peak_pressure"):
        synthesize_trace(th, -1.0, **GEO)
    with pytest.raises(ValueError, match="polytropic"):
        synthesize_trace(th, 80 * BAR, polytropic_exponent=1.8, **GEO)
    with pytest.raises(ValueError, match="combustion_start"):
        synthesize_trace(th, 80 * BAR, combustion_start=150 * DEG, **GEO)
    with pytest.raises(ValueError, match="compression_ratio"):
        synthesize_trace(th, 80 * BAR, **{**GEO, "compression_ratio": 0.9})


# ------------------------------------------------------------------------------- IMEP, friction
def test_imep_of_known_integrals():
    # (1) p = const -> oint p dV = 0 exactly (closed cycle). (2) p = p0 + c dV/dtheta ->
    # oint p dV = c int (dV/dtheta)^2 dtheta, reference by scipy-free fine midpoint quadrature
    # of the analytic derivative (kinematics); tolerance 1e-4 (trapezoid in V on a 0.25 deg grid).
    th = cycle_grid(0.25 * DEG)
    v = cylinder_volume(th, **GEO)
    np.testing.assert_allclose(indicated_mean_effective_pressure(np.full(th.size, 3e5), v, VD),
                               0.0, atol=1e-6)
    area = np.pi / 4 * GEO["bore"] ** 2
    c = 1e8
    dv = area * slider_kinematics(th, 47.3 * MM, 145.7 * MM, 1.0, 0.0, 0.8 * MM).dx_dtheta
    fine = (np.arange(720000) + 0.5) * (4 * np.pi / 720000)
    dvf = area * slider_kinematics(fine, 47.3 * MM, 145.7 * MM, 1.0, 0.0, 0.8 * MM).dx_dtheta
    ref = c * np.sum(dvf**2) * (4 * np.pi / 720000) / VD
    np.testing.assert_allclose(indicated_mean_effective_pressure(2e5 + c * dv, v, VD), ref,
                               rtol=1e-4)


def test_friction_and_brake_torque_consistency():
    # Barnes-Moss / Heywood (1988) ch. 13: 0.97 + 0.15 N/1000 + 0.05 (N/1000)^2 bar (exact
    # arithmetic). BMEP = 4 pi T / V_D (Heywood sec. 2.7): seed 000, 265 N m at 5000 rpm,
    # V_D = 4 * pi/4 * 86^2 * 94.6 mm^3 = 2.198 L -> 15.15 bar (hand calculation, 0.1 %).
    np.testing.assert_allclose(fmep_barnes_moss(np.array([1000, 6000]) * RPM),
                               [1.17e5, 3.67e5], rtol=1e-12)
    vd_tot = 4 * np.pi / 4 * (86 * MM) ** 2 * 94.6 * MM
    np.testing.assert_allclose(bmep_from_torque(265.0, vd_tot), 15.15e5, rtol=1e-3)
    imp = implied_imep(265.0, vd_tot, fmep_barnes_moss(5000 * RPM))
    np.testing.assert_allclose(imp, 15.15e5 + 2.97e5, rtol=1e-3)
    np.testing.assert_allclose(
        fmep_chen_flynn(80e5, 15.0, constant=0.4e5, peak_pressure_factor=0.005,
                        speed_factor=0.09e5, speed_squared_factor=0.0009e5),
        0.4e5 + 0.4e5 + 1.35e5 + 0.2025e5, rtol=1e-12,
    )


def test_calibrate_combustion_start_matches_imep_and_peak():
    # Secondary calibration: the trace keeps the peak (< 1e-9 internal, 0.5 % on a 0.5 deg grid)
    # and reaches the brake-torque implied IMEP of seed 000 at 5000 rpm to 0.2 % (bisection to
    # 0.01 deg; IMEP sensitivity ~0.7 bar/deg -> < 0.01 bar).
    th = cycle_grid(0.5 * DEG)
    vd_tot = 4 * VD
    target = implied_imep(np.array([265.0, 255.0]), vd_tot,
                          fmep_barnes_moss(np.array([5000, 5500]) * RPM))
    peaks = np.array([84.4, 82.7]) * BAR
    tr, start, bad = calibrate_combustion_start(th, peaks, target, **GEO)
    assert not bad.any()
    imep = indicated_mean_effective_pressure(tr.pressure, cylinder_volume(th, **GEO), VD)
    np.testing.assert_allclose(imep, target, rtol=2e-3)
    np.testing.assert_allclose(tr.peak_pressure, peaks, rtol=1e-9)
    assert np.all((start > -45 * DEG) & (start < 15 * DEG))
    # an unreachable target is flagged, not silently accepted
    _, _, bad2 = calibrate_combustion_start(th, 84.4 * BAR, 60 * BAR, **GEO)
    assert bad2



def test_low_load_calibration_lowers_the_intake_pressure():
    """A boosted diesel at no load (the I6 example: CR 17, 2.67 bar intake = the full-load
    boost, no-load peak 58.8 bar): the motored peak at 2.67 bar (~113 bar) is above the given
    peak, so the trace is throttled with no heat release and its IMEP is the pumping loop only
    (0.45 bar) against a friction target of 1.2-1.8 bar (Barnes-Moss). With ``intake_floor``
    the intake pressure is lowered until the same peak needs heat release and the IMEP meets
    the target: checked independently by the IMEP of a trace synthesized at the returned
    intake pressure and phasing, and by the peak."""
    geo = dict(bore=0.105, crank_radius=0.0685, rod_length=0.2165, compression_ratio=17.0)
    vd = swept_volume(0.105, 0.0685, 0.2165)
    th = cycle_grid(0.5 * DEG)
    vol = cylinder_volume(th, **geo)
    speeds = np.array([1000.0, 1800.0, 2800.0]) * RPM
    target = fmep_barnes_moss(speeds)
    peaks = np.full(3, 58.8 * BAR)
    tr0, _, bad0 = calibrate_combustion_start(th, peaks, target, intake_pressure=2.67 * BAR,
                                              **geo)
    imep0 = indicated_mean_effective_pressure(tr0.pressure, vol, vd)
    assert bad0.all() and tr0.motored.all()
    assert np.all(imep0 < 0.6 * BAR) and np.all(target > 1.1 * BAR)  # the miss
    tr, start, bad = calibrate_combustion_start(th, peaks, target, intake_pressure=2.67 * BAR,
                                                intake_floor=0.3 * BAR, **geo)
    assert not bad.any() and not tr.motored.any()
    imep = indicated_mean_effective_pressure(tr.pressure, vol, vd)
    np.testing.assert_allclose(imep, target, rtol=0.02)  # the 2 % of the issue
    np.testing.assert_allclose(imep, target, rtol=2e-3)  # the bisection (INTAKE_TOLERANCE)
    np.testing.assert_allclose(tr.peak_pressure, peaks, rtol=1e-9)
    assert np.all((tr.intake_pressure > 0.3 * BAR) & (tr.intake_pressure < 2.67 * BAR))
    again = synthesize_trace(th, peaks, intake_pressure=tr.intake_pressure,
                             combustion_start=start, **geo)
    np.testing.assert_allclose(indicated_mean_effective_pressure(again.pressure, vol, vd),
                               imep, rtol=1e-12)
    # a target out of reach even at the floor stays flagged
    _, _, bad2 = calibrate_combustion_start(th, 58.8 * BAR, 40 * BAR, intake_pressure=2.67 * BAR,
                                            intake_floor=0.3 * BAR, **geo)
    assert bad2


# ------------------------------------------------------------------------------- peak vs speed
def test_peak_pressure_interpolation_and_extrapolation_flags():
    # Seed 000 full-load table; linear interpolation between 6000 (79.8) and 6500 (73.3) gives
    # 76.55 bar at 6250 (hand calculation, exact). 7000 rpm is outside -> flagged.
    rpm = np.arange(1000, 6501, 500) * RPM
    pk = np.array([53.4, 59.0, 68.1, 73.6, 77.1, 77.5, 80.0, 83.8, 84.4, 82.7, 79.8, 73.3]) * BAR
    w = np.array([1000, 6250, 7000, 500]) * RPM
    p, ext = peak_pressure_at_speed(rpm, pk, w)
    np.testing.assert_allclose(p, [53.4e5, 76.55e5, 73.3e5, 53.4e5], rtol=1e-12)
    np.testing.assert_array_equal(ext, [False, False, True, True])
    p_lin, _ = peak_pressure_at_speed(rpm, pk, w, extrapolation="linear")
    np.testing.assert_allclose(p_lin[2], 73.3e5 + (73.3e5 - 79.8e5), rtol=1e-12)
    with pytest.raises(ValueError, match="outside"):
        peak_pressure_at_speed(rpm, pk, w, extrapolation="raise")
    # single-point table (no-load 29.1 bar @ 7000 rpm): constant, flagged elsewhere
    p1, e1 = peak_pressure_at_speed([7000 * RPM], [29.1 * BAR], w)
    np.testing.assert_allclose(p1, 29.1 * BAR)
    np.testing.assert_array_equal(e1, [True, True, False, True])
    with pytest.raises(ValueError, match="increasing"):
        peak_pressure_at_speed(rpm[::-1], pk, w)
