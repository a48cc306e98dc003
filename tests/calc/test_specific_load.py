"""Tests for checker.calc.specific_load."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.crank_forces import cylinder_loads, rod_mass_split
from checker.calc.kinematics import cycle_grid
from checker.calc.specific_load import peak_specific_load, worst_case

MM, DEG, RPM = 1e-3, np.pi / 180, np.pi / 30


def test_peak_of_known_vectors():
    # Hand calculation: loads (3, 4) N at one angle -> |F| = 5 N; D = 0.05 m, L = 0.02 m ->
    # 5 / 1e-3 = 5000 Pa. Exact.
    th = cycle_grid(90 * DEG)  # 8 points
    fx = np.zeros((2, 8))
    fy = np.ones((2, 8))
    fx[0, 3], fy[0, 3] = 3.0, 4.0
    fx[1, 6], fy[1, 6] = -6.0, 8.0  # 10 N
    res = peak_specific_load(fx, fy, th, np.array([0.05, 0.05]), 0.02)
    np.testing.assert_allclose(res.force, [5.0, 10.0])
    np.testing.assert_allclose(res.specific_load, [5000.0, 10000.0])
    np.testing.assert_allclose(res.theta, th[[3, 6]])
    np.testing.assert_array_equal(res.index, [3, 6])


def test_worst_case_over_speed():
    # Envelope over the speed axis picks the speed and crank angle of the largest peak (exact).
    th = cycle_grid(90 * DEG)
    speeds = np.array([100.0, 200.0, 300.0])
    # (case, speed, bearing, angle)
    fx = np.zeros((2, 3, 4, 8))
    fy = np.zeros((2, 3, 4, 8))
    fy[1, 2, 3, 5] = 7.0
    fy[1, 0, 3, 1] = 6.0
    fy[0, 1, :, 2] = 1.0
    peak = peak_specific_load(fx, fy, th, 0.05, 0.02)
    wc = worst_case(peak, speeds, axis=1)
    assert wc.specific_load.shape == (2, 4)
    np.testing.assert_allclose(wc.force[1, 3], 7.0)
    np.testing.assert_allclose(wc.coordinate[1, 3], 300.0)
    np.testing.assert_allclose(wc.theta[1, 3], th[5])
    np.testing.assert_allclose(wc.coordinate[0, 0], 200.0)


def test_motored_big_end_specific_load_closed_form():
    # Example engine (seed 000) big end, D = 48 mm, L_eff = 17.8 mm, no gas force, zero offsets:
    # the maximum over the cycle is at TDC (0 or 360 deg) and equals
    # (m_rec (1 + lam) + m_b) r w^2 / (D L_eff) (closed form of seed 004 / brief). Exact (1e-12).
    th = cycle_grid(1.0 * DEG)
    w = np.array([3000.0, 7000.0]) * RPM
    r, l = 47.3 * MM, 145.7 * MM
    loads = cylinder_loads(
        th, w, np.full((2, 1, th.size), 1e5), bore=86 * MM, crank_radius=r, rod_length=l,
        piston_mass=0.4955, rod_mass=0.597, rod_cg_from_big_end=35.73 * MM, rod_inertia=2128e-9,
        firing_angle=np.array([0.0]), crankcase_pressure=1e5,
    )
    m_a, m_b, _ = rod_mass_split(0.597, l, 35.73 * MM, 2128e-9)
    ref = ((0.4955 + m_a) * (1 + r / l) + m_b) * r * w**2 / (48 * MM * 17.8 * MM)
    be = loads.big_end_block
    peak = peak_specific_load(be.x, be.y, th, 48 * MM, 17.8 * MM)
    np.testing.assert_allclose(peak.specific_load[:, 0], ref, rtol=1e-12)
    assert np.all(np.isin(np.round(np.rad2deg(peak.theta[:, 0])), [0.0, 360.0]))


def test_invalid_inputs_raise():
    th = cycle_grid(90 * DEG)
    f = np.ones(8)
    with pytest.raises(ValueError, match="diameter"):
        peak_specific_load(f, f, th, 0.0, 0.02)
    with pytest.raises(ValueError, match="effective_length"):
        peak_specific_load(f, f, th, 0.05, -1.0)
    with pytest.raises(ValueError, match="non-finite"):
        peak_specific_load(np.where(np.arange(8) == 2, np.nan, f), f, th, 0.05, 0.02)
    with pytest.raises(ValueError, match="last axis"):
        peak_specific_load(f, f, th[:4], 0.05, 0.02)
    with pytest.raises(ValueError, match="coordinate"):
        worst_case(peak_specific_load(f[None], f[None], th, 0.05, 0.02), [1.0, 2.0], axis=0)
