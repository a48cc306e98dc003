"""Damper tuning against Den Hartog's optimum (checker.calc.damper_tuning)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import damper as dmp
from checker.calc import damper_tuning as dt
from checker.calc import torsional as tv


def test_primary_mode_of_a_two_inertia_crank_closed_form():
    # ring + free-free J1 -k- J2: w_n^2 = k (J1 + J2)/(J1 J2), mode (1, -J1/J2),
    # J_eq at J1 = J1 + J2 (J1/J2)^2 = J1 (J1 + J2)/J2 (Drapal & Novotny 2017 eq. 3)
    j1, j2, k = 0.03, 0.2, 4.0e5
    model = tv.TorsionalModel([0.005, j1, j2], [2.0e4, k], loss_factor=[0.2, 0.0])
    pm = dt.primary_mode(model, 0)
    assert pm.omega == pytest.approx(np.sqrt(k * (j1 + j2) / (j1 * j2)), rel=1e-12)
    assert pm.equivalent_inertia == pytest.approx(j1 * (j1 + j2) / j2, rel=1e-12)
    np.testing.assert_allclose(pm.mode, [1.0, -j1 / j2], rtol=1e-12)


@pytest.mark.parametrize(
    ("mu", "f_ref", "zeta_ref"),
    [(0.05, 0.9524, 0.1273), (0.1, 0.9091, 0.1679), (0.2, 0.8333, 0.2083)],
)
def test_optimum_matches_the_den_hartog_test_values(mu, f_ref, zeta_ref):
    # the reference values of tests/calc/test_damper.py (torsion notes 3.4, Den Hartog 1956)
    # reached through the engine path: grounded primary J, k; ring J_d = mu J on k_d
    j, k = 2.0, 8.0e4
    wn = np.sqrt(k / j)
    jd = mu * j
    kd = jd * (0.8 * wn) ** 2  # a mistuned damper: f = 0.8
    model = tv.TorsionalModel([jd, j], [kd], loss_factor=[0.1], stiffness_ground=[0.0, k])
    pm = dt.primary_mode(model, 0)
    assert pm.omega == pytest.approx(wn, rel=1e-12) and pm.equivalent_inertia == pytest.approx(j)
    t = dt.absorber_tuning(jd, kd, 0.1, 0.0, pm.omega, pm.equivalent_inertia)
    assert t.mass_ratio == pytest.approx(mu, rel=1e-12)
    assert t.tuning == pytest.approx(0.8, rel=1e-12)
    np.testing.assert_allclose([t.tuning_optimum, t.damping_optimum], [f_ref, zeta_ref],
                               atol=5e-5)
    assert t.tuning_deviation == pytest.approx(0.8 / t.tuning_optimum - 1, rel=1e-12)
    assert t.damping_ratio == pytest.approx(0.1 * 0.8 / 2, rel=1e-12)  # eta f / 2
    assert t.peak_magnification == pytest.approx(np.sqrt(1 + 2 / mu), rel=1e-12)


def test_optimum_model_response_is_near_den_hartog_and_beats_mistuning():
    # Same model with the optimum rubber (k_opt, eta_opt hysteretic): the primary's peak
    # magnification |Theta| k / T over a frequency sweep is within 6 % of Den Hartog's
    # sqrt(1 + 2/mu) (viscous theory; the hysteretic equivalent is exact only at the ring
    # frequency: 4.81 vs 4.58 at mu = 0.1), within 3 % of the best hysteretic damper found by
    # a grid search over tuning and loss factor (4.70 at f = 0.91, eta = 0.39), and well below
    # the mistuned damper's peak.
    mu, j, k = 0.1, 2.0, 8.0e4
    wn = np.sqrt(k / j)
    jd = mu * j
    model = tv.TorsionalModel([jd, j], [jd * (0.8 * wn) ** 2], loss_factor=[0.1],
                              stiffness_ground=[0.0, k])
    pm = dt.primary_mode(model, 0)
    t = dt.absorber_tuning(jd, model.stiffness[0], 0.1, 0.0, pm.omega, pm.equivalent_inertia)
    opt = dt.optimum_model(model, 0, t)
    assert opt.stiffness[0] == pytest.approx(jd * (wn / (1 + mu)) ** 2, rel=1e-12)
    assert opt.loss_factor[0] == pytest.approx(2 * t.damping_optimum * (1 + mu), rel=1e-12)
    r = np.linspace(0.5, 1.5, 4001)
    f = np.array([[0.0], [1.0]])
    peak_opt = np.abs(tv.forced_response(opt, r * wn, [1.0], f).theta[:, 1, 0]).max() * k
    peak_mis = np.abs(tv.forced_response(model, r * wn, [1.0], f).theta[:, 1, 0]).max() * k
    assert peak_opt == pytest.approx(np.sqrt(1 + 2 / mu), rel=0.06)
    assert peak_mis > 1.5 * peak_opt

    def peak(tuning, eta):
        m = tv.TorsionalModel([jd, j], [jd * (tuning * wn) ** 2], loss_factor=[eta],
                              stiffness_ground=[0.0, k])
        return np.abs(tv.forced_response(m, r[::4] * wn, [1.0], f).theta[:, 1, 0]).max() * k

    best = min(peak(a, b) for a in np.linspace(0.86, 0.96, 11) for b in np.linspace(
        0.3, 0.48, 10))
    assert best <= peak_opt < 1.03 * best


def test_validation():
    model = tv.TorsionalModel([0.005, 0.03, 0.2], [2.0e4, 4.0e5])
    with pytest.raises(ValueError, match="first station"):
        dt.primary_mode(model, 1)
    with pytest.raises(ValueError):
        dt.absorber_tuning(0.0, 1e4, 0.1, 0.0, 100.0, 0.1)
    with pytest.raises(ValueError):
        dt.absorber_tuning(0.005, 1e4, -0.1, 0.0, 100.0, 0.1)
    # the damper module's optimum is the one used
    assert dt.absorber_tuning(0.01, 1e4, 0.1, 0.0, 100.0, 0.1).tuning_optimum == pytest.approx(
        float(dmp.den_hartog_optimum(0.1)[0]))
