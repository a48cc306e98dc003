"""Crank-nose stresses against hand calculations (Shigley 10th ed. eq. 3-24, 3-37, 7-7/7-8)."""

import numpy as np
import pytest

from checker.calc.crank_nose import crank_nose_safety_factor, crank_nose_stresses


def test_hand_calculation():
    # d = 30 mm solid: W_b = pi d^3/32 = 2650.7 mm^3, W_p = 5301.4 mm^3
    # belt 3 kN at 40 mm: M = 120 N m -> sigma_a = 1.8 x 120e3/2650.7 = 81.49 MPa
    # torque -20..+300 N m: tau_a = 1.3 x 160e3/5301.4 = 39.23 MPa, tau_m = 1.3 x 140e3/5301.4
    # = 34.33 MPa; eq_a = sqrt(81.49^2 + 3 x 39.23^2) = 106.10 MPa; eq_m = sqrt(3) 34.33
    # = 59.46 MPa; Goodman SF = 1/(106.10/400 + 59.46/750) = 2.9025
    a, m = crank_nose_stresses(300.0, -20.0, 3000.0, 0.040, 0.030, 0.0, 1.8, 1.3)
    assert a / 1e6 == pytest.approx(106.10, abs=0.01)
    assert m / 1e6 == pytest.approx(59.46, abs=0.01)
    sf = crank_nose_safety_factor(a, m, 400e6, 750e6)
    assert sf == pytest.approx(2.9025, abs=0.0005)


def test_pure_reversed_bending_gives_endurance_ratio():
    a, m = crank_nose_stresses(0.0, 0.0, 1000.0, 0.05, 0.04, 0.0)
    sigma = 1000 * 0.05 / (np.pi * 0.04**3 / 32)
    assert a == pytest.approx(sigma, rel=1e-12) and m == 0
    assert crank_nose_safety_factor(a, m, 300e6, 800e6) == pytest.approx(300e6 / sigma)


def test_reversed_torque_direction_does_not_relieve():
    a1, m1 = crank_nose_stresses(100.0, 50.0, 0.0, 0.0, 0.03)
    a2, m2 = crank_nose_stresses(-50.0, -100.0, 0.0, 0.0, 0.03)
    assert a1 == pytest.approx(a2) and m1 == pytest.approx(-m2)
    assert crank_nose_safety_factor(a1, m1, 300e6, 800e6) == pytest.approx(
        crank_nose_safety_factor(a2, m2, 300e6, 800e6))


@pytest.mark.parametrize("kw", [dict(diameter=0.03, bore=0.03), dict(diameter=0.03, bore=0.0,
                                                                      kt_bending=0.9)])
def test_invalid(kw):
    with pytest.raises(ValueError):
        crank_nose_stresses(1.0, 0.0, 0.0, 0.0, **kw)
