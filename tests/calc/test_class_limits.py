"""Class-society crankshaft TV limits (checker.calc.class_limits) against the rule text worked
by hand: Korean Register, Rules for the Classification of Steel Ships, Pt 5 Ch 4, 2025,
201.1-201.4 (tau_1, tau_2, tau_3, f_m), 203 (generator engines), 206.1(1) (barred speed
range). Every expected number below is the rule's formula evaluated on paper; the tolerance
is float round-off (1e-12 relative)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import class_limits as cl

RTOL = 1e-12


@pytest.mark.parametrize(("lam", "group", "expected"), [
    (0.0, "A", 45.0), (0.5, "A", 45.0 - 24.0 * 0.25), (0.8, "A", 45.0 - 24.0 * 0.64),
    (1.0, "A", 21.0), (0.5, "B", 45.0 - 29.0 * 0.25), (1.0, "B", 16.0),
])
def test_tau1_propulsion_by_hand(lam, group, expected):
    """KR 201.1: tau_1 = 45 - 24 lambda^2 (group A), 45 - 29 lambda^2 (group B) N/mm^2."""
    assert cl.propulsion_continuous(lam, group) == pytest.approx(expected * 1e6, rel=RTOL)


def test_tau1_material_factor_by_hand():
    """KR 201.4(1): f_m = 1 + 2/3 (T_s/440 - 1); T_s = 500: 1.090909..., tau_1(0.5, A) =
    39 x 1.0909 = 42.5454 N/mm^2; T_s above the 590 cap is credited as 590."""
    f1, f2 = cl.material_factors(500e6, None)
    assert f1 == pytest.approx(1.0 + 2.0 / 3.0 * (500.0 / 440.0 - 1.0), rel=RTOL)
    assert f2 == 1.0
    assert cl.propulsion_continuous(0.5, "A", f1) == pytest.approx(39.0 * f1 * 1e6, rel=RTOL)
    assert cl.material_factors(950e6, None)[0] == pytest.approx(
        1.0 + 2.0 / 3.0 * (590.0 / 440.0 - 1.0), rel=RTOL)
    assert cl.material_factors(950e6, None, cl.TS_CAP_LOW_ALLOY)[0] == pytest.approx(
        1.0 + 2.0 / 3.0 * (835.0 / 440.0 - 1.0), rel=RTOL)
    # below the reference strengths the rule gives no factor (no reduction either)
    assert cl.material_factors(400e6, 200e6) == (1.0, 1.0)


@pytest.mark.parametrize(("lam", "group", "yield_mpa", "expected"), [
    (0.0, "A", None, 90.0), (0.6, "A", None, 2.0 * (45.0 - 24.0 * 0.36)),
    (0.8, "B", None, 2.0 * (45.0 - 29.0 * 0.64)),
    (0.6, "A", 450.0, 2.0 * (45.0 - 24.0 * 0.36) * 450.0 / 225.0),
])
def test_tau2_propulsion_by_hand(lam, group, yield_mpa, expected):
    """KR 201.2: tau_2 = 2 tau_1 for lambda <= 0.8; 201.4(2): times Y/225."""
    f2 = cl.material_factors(None, None if yield_mpa is None else yield_mpa * 1e6)[1]
    assert cl.propulsion_transient(lam, group, f2) == pytest.approx(expected * 1e6, rel=RTOL)


def test_tau3_overspeed_by_hand():
    """KR 201.3: tau_3 = 21 + 237 (lambda - 0.8) sqrt(lambda - 1) (A), 16 + ... (B); equal to
    tau_1 at lambda = 1 (continuous)."""
    assert cl.propulsion_overspeed(1.1, "A") == pytest.approx(
        (21.0 + 237.0 * 0.3 * np.sqrt(0.1)) * 1e6, rel=RTOL)
    assert cl.propulsion_overspeed(1.15, "B") == pytest.approx(
        (16.0 + 237.0 * 0.35 * np.sqrt(0.15)) * 1e6, rel=RTOL)
    for g in cl.GROUPS:
        assert cl.propulsion_overspeed(1.0, g) == pytest.approx(
            cl.propulsion_continuous(1.0, g), rel=RTOL)


def test_generator_limits_by_hand():
    """KR 203.1: tau_1 = 21 (A) / 16 (B) N/mm^2 in 0.9..1.1; tau_2 = 90 N/mm^2 below 0.9;
    203.3: times f_m."""
    assert cl.generator_continuous("A") == 21e6
    assert cl.generator_continuous("B") == 16e6
    assert cl.generator_transient() == 90e6
    f1, f2 = cl.material_factors(590e6, 300e6)
    assert cl.generator_continuous("A", f1) == pytest.approx(21e6 * f1, rel=RTOL)
    assert cl.generator_transient(f2) == pytest.approx(90e6 * 300.0 / 225.0, rel=RTOL)


@pytest.mark.parametrize(("lam", "lower", "upper"), [
    # N_c = lam x 1000 rpm, N_MCR = 1000 rpm: 16 N_c/(18 - lam) .. (18 - lam) N_c/16
    (0.5, 16.0 * 500.0 / 17.5, 17.5 * 500.0 / 16.0),   # 457.143 .. 546.875 rpm
    (0.8, 16.0 * 800.0 / 17.2, 17.2 * 800.0 / 16.0),   # 744.186 .. 860.000 rpm
    (1.0, 16.0 * 1000.0 / 17.0, 17.0 * 1000.0 / 16.0),  # 941.176 .. 1062.500 rpm
])
def test_barred_speed_range_by_hand(lam, lower, upper):
    """KR 206.1(1) at three speed ratios of the critical."""
    rpm = 2.0 * np.pi / 60.0
    r = cl.barred_speed_range(lam * 1000.0 * rpm, 1000.0 * rpm)
    assert float(r.lower) / rpm == pytest.approx(lower, rel=RTOL)
    assert float(r.upper) / rpm == pytest.approx(upper, rel=RTOL)
    assert float(r.lower) < lam * 1000.0 * rpm < float(r.upper)


def test_validity_is_checked():
    with pytest.raises(ValueError):
        cl.propulsion_continuous(1.05, "A")
    with pytest.raises(ValueError):
        cl.propulsion_transient(0.85, "A")
    with pytest.raises(ValueError):
        cl.propulsion_overspeed(0.95, "A")
    with pytest.raises(ValueError):
        cl.propulsion_continuous(0.5, "C")
    with pytest.raises(ValueError):
        cl.barred_speed_range(-1.0, 100.0)


def test_engine_group():
    """201.1: in-line engines and V engines firing every 45 or 60 deg are group A."""
    i6 = np.radians([0, 480, 240, 600, 120, 360])
    assert cl.engine_group(i6, np.zeros(6)) == "A"
    v16 = np.radians(np.arange(16) * 45.0)
    assert cl.engine_group(v16, np.radians([0, 45] * 8)) == "A"
    v6 = np.radians(np.arange(6) * 120.0)
    assert cl.engine_group(v6, np.radians([0, 60] * 3)) == "B"


def test_band_clearance():
    """204: signed distance from the band, in units of the rated speed."""
    assert cl.band_clearance([0.79, 0.95, 1.2], (0.8, 1.1)) == pytest.approx(
        [0.01, -0.15, 0.1], rel=1e-12)
