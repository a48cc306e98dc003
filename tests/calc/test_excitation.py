"""Tests of checker.calc.excitation against closed forms and published values."""

import numpy as np
import pytest

from checker.calc import excitation as exc
from checker.calc.kinematics import cycle_grid


def _grid(n_points):
    return cycle_grid(4 * np.pi / n_points)


# torsion.md section 3.1: exact inertia-torque sine coefficients for lambda = 0.3, orders 1..6,
# in units of m_rec r^2 omega^2, rounded to 5 decimals (so atol 5e-6 + FFT round-off).
EXACT_LAMBDA_03 = np.array([0.07676, -0.50028, -0.23300, -0.02356, 0.00460, 0.00083])


def _unit_inertia_coeffs(lam, n_points=720, max_order=12.0):
    theta = _grid(n_points)
    torque = exc.reciprocating_inertia_torque(theta, 1.0, lam, 1.0, 1.0) / lam**2
    return exc.torque_harmonics(torque, max_order)


def test_harmonics_convention_roundtrip():
    # Definition T = c0/2 + sum Re{c_n e^{j n theta}}: a known two-order signal is recovered.
    theta = _grid(256)
    torque = 3.0 + 2.0 * np.cos(0.5 * theta + 0.3) - 1.5 * np.sin(4.0 * theta)
    orders, c = exc.torque_harmonics(torque, 8.0)
    assert orders[0] == 0.5 and orders[-1] == 8.0 and orders.size == 16
    np.testing.assert_allclose(c[0], 2.0 * np.exp(0.3j), atol=1e-12)
    np.testing.assert_allclose(c[7], 1.5j, atol=1e-12)  # -1.5 sin x = Re{1.5j e^{jx}}
    c_others = np.delete(c, [0, 7])
    np.testing.assert_allclose(c_others, 0.0, atol=1e-12)


def test_harmonics_reject_nyquist_and_bad_order():
    with pytest.raises(ValueError):
        exc.torque_harmonics(np.zeros(32), 8.0)  # bin 16 = Nyquist of 32 points
    with pytest.raises(ValueError):
        exc.torque_harmonics(np.zeros(64), 1.25)


def test_inertia_torque_fft_matches_published_exact_values():
    # Source: torsion.md 3.1 exact values for lambda = 0.3 (5 decimals -> atol 5e-6).
    _, c = _unit_inertia_coeffs(0.3)
    b = -c.imag  # complex coefficient of b sin(n theta) is -j b
    np.testing.assert_allclose(b[1::2][:6], EXACT_LAMBDA_03, atol=5.1e-6)
    # only integer orders and only sine terms (torque odd in theta)
    np.testing.assert_allclose(c[0::2], 0.0, atol=1e-14)
    np.testing.assert_allclose(c.real, 0.0, atol=1e-14)


def test_inertia_torque_series_matches_fft_to_truncation_order():
    # Closed-form series correct to O(lambda^5): at lambda = 0.3 the error is below
    # lambda^6 / 10 (= 7.3e-5), and halving lambda divides the error by at least 2^5.
    errs = []
    for lam in (0.3, 0.15):
        _, c = _unit_inertia_coeffs(lam)
        _, b_series = exc.inertia_torque_series_coefficients(lam)
        errs.append(np.max(np.abs(b_series - (-c.imag[1::2]))))
    assert errs[0] < 0.3**6 / 10
    assert errs[0] / errs[1] > 2**5
    # leading closed-form terms of torsion.md 3.1
    lam = 0.3
    _, b = exc.inertia_torque_series_coefficients(lam)
    np.testing.assert_allclose(b[0], lam / 4 + lam**3 / 16, atol=lam**5)
    np.testing.assert_allclose(b[1], -(0.5 + lam**4 / 32), atol=lam**6)
    np.testing.assert_allclose(b[4], 5 * lam**3 / 32, atol=lam**5)


def test_inertia_torque_series_time_signal():
    theta = _grid(360)
    exact = exc.reciprocating_inertia_torque(theta, 0.6419, 0.0473, 0.1457, 600.0)
    series = exc.inertia_torque_series(theta, 0.6419, 0.0473, 0.1457, 600.0)
    scale = 0.6419 * 0.0473**2 * 600.0**2
    lam = 0.0473 / 0.1457
    assert np.max(np.abs(exact - series)) < scale * lam**6


def test_gas_torque_sign_and_work():
    # Positive torque after firing TDC; cycle work of a constant pressure on the piston is zero.
    theta = _grid(720)
    t = exc.gas_torque(theta, 5e6, 0.08, 0.0473, 0.1457, crankcase_pressure=1e5)
    assert t[10] > 0 and t[190] < 0  # 10 deg after TDC, 10 deg after BDC
    assert abs(t.mean()) < 1e-9 * np.max(np.abs(t))
    # Work of a pressure acting only in the expansion stroke = p * A * stroke (energy balance)
    p = np.where(theta < np.pi, 4e6, 0.0)
    work = np.sum(exc.gas_torque(theta, p, 0.08, 0.0473, 0.1457)) * (4 * np.pi / 720)
    # p A stroke; rtol 1e-4 covers the O(h^2) rectangle-rule error (2.5e-5)
    np.testing.assert_allclose(work, 4e6 * np.pi * 0.08**2 / 4 * 2 * 0.0473, rtol=1e-4)


def test_phasing_shifts_time_signal():
    # F_{i,n} = c_n exp(-j n phi_i) represents T_1(theta - phi_i) (torsion.md 3.3).
    theta = _grid(720)
    t1 = np.exp(np.cos(theta / 2)) + np.sin(3 * theta)
    orders, c = exc.torque_harmonics(t1, 24.0)
    phi = np.deg2rad([0.0, 540.0, 180.0, 360.0])
    ci = exc.phase_cylinders(c, orders, phi)
    for i, p in enumerate(phi):
        shift = int(round(p / (4 * np.pi) * 720))
        _, ref = exc.torque_harmonics(np.roll(t1, shift), 24.0)  # T1(theta - phi)
        np.testing.assert_allclose(ci[i], ref, atol=1e-12)


def test_rigid_body_vector_sums_i4_and_i6():
    # torsion.md 3.3: I4 (phi = 0/540/180/360 for cyl 1..4) non-zero only at 2, 4, 6, ... (sum 4);
    # even-firing 6-cyl (1-5-3-6-2-4) only at 3, 6, 9, ... (sum 6). Exact, atol 1e-12.
    orders = np.arange(1, 49) / 2
    i4 = np.deg2rad([0, 540, 180, 360])
    s4 = exc.vector_sum(orders, i4)
    major4 = np.isclose(orders % 2, 0)
    np.testing.assert_allclose(s4[major4], 4.0, atol=1e-12)
    np.testing.assert_allclose(s4[~major4], 0.0, atol=1e-12)
    np.testing.assert_array_equal(exc.major_order_mask(orders, i4), major4)
    # 1-5-3-6-2-4: firing positions of cylinders 1..6
    firing_sequence = [1, 5, 3, 6, 2, 4]
    i6 = np.deg2rad([120.0 * firing_sequence.index(cyl) for cyl in range(1, 7)])
    s6 = exc.vector_sum(orders, i6)
    major6 = np.isclose(orders % 3, 0)
    np.testing.assert_allclose(s6[major6], 6.0, atol=1e-12)
    np.testing.assert_allclose(s6[~major6], 0.0, atol=1e-12)


def test_vector_sum_with_mode_shape():
    # Weighted sum equals the explicit complex sum.
    orders = np.array([0.5, 1.5, 4.0])
    phi = np.deg2rad([0, 540, 180, 360])
    beta = np.array([1.0, 0.8, 0.5, 0.1])
    ref = [
        abs(sum(b * np.exp(-1j * n * p) for b, p in zip(beta, phi, strict=True))) for n in orders
    ]
    np.testing.assert_allclose(exc.vector_sum(orders, phi, beta), ref, rtol=1e-13)


def test_input_validation():
    with pytest.raises(ValueError):
        exc.reciprocating_inertia_torque(0.0, 1.0, 0.1, 0.05, 100.0)
    with pytest.raises(ValueError):
        exc.gas_torque(0.0, -1.0, 0.08, 0.04, 0.14)
    with pytest.raises(ValueError):
        exc.inertia_torque_series_coefficients(1.2)
