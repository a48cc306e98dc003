"""Untuned viscous damper (checker.calc.viscous_damper) and self-heating
(checker.calc.damper_temperature) against closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import damper as dmp
from checker.calc import damper_temperature as dtemp
from checker.calc import torsional as tv
from checker.calc import viscous_damper as vd


def _sdof_with_viscous_damper(mu: float, g: float, j: float = 2.0, k: float = 8.0e4):
    """Grounded primary J, k (undamped) and a ring mu J coupled by c = 2 g J_d w_n only."""
    wn = np.sqrt(k / j)
    jd = mu * j
    c = 2.0 * g * jd * wn
    model = tv.TorsionalModel([jd, j], [0.0], damping_rel=[c], stiffness_ground=[0.0, k])
    return model, wn, c


@pytest.mark.parametrize(("mu", "peak", "ratio"),
                         [(1.0, 3.000, 0.8165), (0.25, 9.0, 0.9428), (0.1, 21.0, 0.9759)])
def test_den_hartog_optimum_peak_in_the_torsional_model(mu, peak, ratio):
    # Den Hartog 1956 ch. 3 (untuned viscous damper): at the optimum damping the peak
    # magnification is 1 + 2/mu at r = sqrt(2/(2 + mu)); e.g. mu = 1: 3.000 at 0.8165.
    g_opt, r_p, m_p = (float(x) for x in vd.untuned_optimum(mu))
    assert m_p == pytest.approx(peak, rel=1e-12)
    assert r_p == pytest.approx(ratio, abs=5e-5)
    model, wn, c = _sdof_with_viscous_damper(mu, g_opt)
    k = 8.0e4
    # forced response of the chain (the checker's solver) on a fine frequency grid
    r = np.linspace(0.5, 1.5, 20001)
    resp = tv.forced_response(model, r * wn, [1.0], np.array([0.0, k])[None, :, None])
    mag = np.abs(resp.theta[:, 1, 0])  # |Theta| / (T / k) with T = k
    i = int(np.argmax(mag))
    assert mag[i] == pytest.approx(1.0 + 2.0 / mu, rel=1e-7)  # grid step 5e-5 at a flat top
    assert r[i] == pytest.approx(np.sqrt(2.0 / (2.0 + mu)), abs=2e-3)
    # the closed-form curve agrees with the solver at every point
    np.testing.assert_allclose(mag, vd.untuned_magnification(r, mu, g_opt), rtol=1e-10)
    # any other damping gives a higher peak (the optimum is a minimum of the peak)
    for g in (0.7 * g_opt, 1.4 * g_opt):
        assert vd.untuned_magnification(r, mu, g).max() > 1.0 + 2.0 / mu


def test_fixed_point_is_independent_of_damping():
    mu = 0.3
    rp = np.sqrt(2.0 / (2.0 + mu))
    vals = vd.untuned_magnification(rp, mu, np.array([0.01, 0.1, 1.0, 10.0]))
    np.testing.assert_allclose(vals, 1.0 + 2.0 / mu, rtol=1e-12)


def test_dissipated_power_equals_c_omega2_twist2_over_2():
    # P = c Omega^2 |dphi|^2 / 2 (Den Hartog 1956 sec. 2.8), and the same as the time mean
    # of the instantaneous power c dphi_dot^2 over one period
    model, wn, c = _sdof_with_viscous_damper(0.2, 0.3)
    w = np.array([0.9, 1.0, 1.1]) * wn
    resp = tv.forced_response(model, w, [1.0], np.array([0.0, 1.0e3])[None, :, None])
    dphi = resp.theta[:, 1, 0] - resp.theta[:, 0, 0]
    z = vd.maxwell_impedance(w, c)
    p = vd.impedance_power(dphi, w, z)
    np.testing.assert_allclose(p, 0.5 * c * w**2 * np.abs(dphi) ** 2, rtol=1e-14)
    np.testing.assert_allclose(p, dmp.dissipated_power(dphi, w, damping=c), rtol=1e-14)
    t = np.linspace(0.0, 2 * np.pi, 4096, endpoint=False)
    rate = np.real(1j * w[:, None] * dphi[:, None] * np.exp(1j * t))  # d(dphi)/dt
    np.testing.assert_allclose(p, c * np.mean(rate**2, axis=1), rtol=1e-12)


def test_maxwell_coupling_limits_and_power():
    w = np.array([10.0, 100.0, 1000.0])
    c, ks = 50.0, 2.0e4
    z = vd.maxwell_impedance(w, c, ks)
    # series spring and dashpot: 1/z = 1/k_s + 1/(j w c)
    np.testing.assert_allclose(1.0 / z, 1.0 / ks + 1.0 / (1j * w * c), rtol=1e-14)
    assert np.all(z.real > 0) and np.all(z.imag > 0)
    # stiff fluid -> Newtonian
    np.testing.assert_allclose(vd.maxwell_impedance(w, c, 1e15), 1j * w * c, rtol=1e-9)


def test_couette_factor_sum_of_faces():
    g = vd.GapGeometry(0.1, 0.15, 0.04, 0.001, 0.0005)
    # faces one by one: outer cylinder, inner cylinder, two flat sides (numerical integral)
    cyl = 2 * np.pi * 0.04 * (0.15**3 + 0.1**3) / 0.001
    r = np.linspace(0.1, 0.15, 200001)
    side = np.trapezoid(r / 0.0005 * r * 2 * np.pi * r, r)
    assert vd.couette_factor(g) == pytest.approx(cyl + 2 * side, rel=1e-9)
    assert vd.wetted_area(g) == pytest.approx(
        2 * np.pi * 0.04 * 0.25 + 2 * np.pi * (0.15**2 - 0.1**2), rel=1e-14)
    with pytest.raises(ValueError, match="thin films"):
        vd.couette_factor(vd.GapGeometry(0.01, 0.15, 0.04, 0.002, 0.0005))


def test_andrade_law_reproduces_the_vtc():
    b = vd.andrade_slope(0.6)
    t1, t2 = vd.VTC_TEMPERATURES
    nu = vd.andrade_viscosity(np.array([t1, t2]), 0.1, t1, b)
    assert 1.0 - nu[1] / nu[0] == pytest.approx(0.6, rel=1e-12)
    # ln nu linear in 1/T, through the reference point
    t = np.array([250.0, 300.0, 350.0, 400.0])
    ln = np.log(vd.andrade_viscosity(t, 0.1, 298.15, b))
    np.testing.assert_allclose(np.diff(ln) / np.diff(1 / t), b, rtol=1e-9)
    assert float(vd.andrade_viscosity(298.15, 0.1, 298.15, b)) == 0.1


def test_rubber_table_at_its_points_reproduces_constant_properties_exactly():
    # a table evaluated at its own temperatures gives the table's values bit for bit, so the
    # forced response with the table equals the constant-property response exactly
    t = np.array([243.15, 293.15, 333.15, 393.15])
    g = np.array([9.5e6, 2.1e6, 1.3e6, 0.95e6])
    eta = np.array([0.30, 0.18, 0.15, 0.12])
    tab = dtemp.RubberTable(t, g, eta)
    gi, ei = tab(t)
    assert np.array_equal(gi, g) and np.array_equal(ei, eta)
    assert np.isnan(tab(t[0] - 1.0)[0]) and np.isnan(tab(t[-1] + 1.0)[1])
    phi = float(dmp.annulus_stiffness(1.0, 0.055, 0.059, 0.028))
    speeds = np.linspace(100.0, 700.0, 13)
    orders = np.array([1.0, 2.0, 4.0])
    force = np.zeros((speeds.size, 3, orders.size), complex)
    force[:, 2, :] = 100.0
    base = tv.TorsionalModel([0.0055, 0.02, 0.3], [1.0e4, 3.0e5], damping_abs=[0, 0, 1.0])
    for ti, gg, ee in zip(t, g, eta):
        ks = phi * gg
        const = tv.forced_response(
            tv.TorsionalModel([0.0055, 0.02, 0.3], [ks, 3.0e5], damping_abs=[0, 0, 1.0],
                              loss_factor=[ee, 0.0]), speeds, orders, force)
        gt, et = tab(np.full(speeds.size, ti))
        z = (phi * gt * (1.0 + 1j * et))[:, None] * np.ones(orders.size)
        table = tv.forced_response(base, speeds, orders, force, impedance={0: z})
        assert np.array_equal(table.theta, const.theta)
        assert np.array_equal(table.element_torque, const.element_torque)


def test_log_interpolation_between_points():
    tab = dtemp.RubberTable([250.0, 350.0], [1e7, 1e6], [0.3, 0.1])
    g, e = tab(300.0)
    assert float(g) == pytest.approx(np.sqrt(1e7 * 1e6), rel=1e-14)
    assert float(e) == pytest.approx(0.2, rel=1e-14)


def test_self_heated_temperature_solves_the_heat_balance():
    # P(T) = P0 exp(-(T - T0)/s): T = T_a + R P(T) by bisection, checked by substitution
    p0, t0, s = 400.0, 300.0, 40.0

    def power_at(temp):
        return p0 * np.exp(-(temp - t0) / s)

    ta = np.array([250.0, 300.0, 330.0])
    temp, p = dtemp.self_heated_temperature(power_at, ta, 0.1, 500.0)
    np.testing.assert_allclose(temp, ta + 0.1 * power_at(temp), atol=2e-3)
    np.testing.assert_allclose(p, power_at(temp), rtol=1e-12)
    # no heat path: the ambient
    t2, _ = dtemp.self_heated_temperature(power_at, ta, None, 500.0)
    assert np.array_equal(t2, ta)
    # hotter than the properties are known: NaN, never a clipped value
    t3, p3 = dtemp.self_heated_temperature(power_at, ta, 0.1, 320.0)
    assert np.isnan(t3[1]) and np.isnan(p3[1]) and np.isfinite(t3[0])


def test_steady_temperature_newton_cooling():
    assert float(vd.steady_temperature(300.0, 500.0, 50.0, 0.2)) == pytest.approx(350.0)
