"""Bolted-joint formulas against the worked calculations of Ricardo 2013 (seed 000, slides
23-24). Tolerance: half a unit in the last digit the seed prints."""

import numpy as np
import pytest

from checker.calc import bolted_joint as bj


def test_crank_nose_worked_example():
    # slide 23: D = 16 mm, p = 1.5 mm, csa with 0.938 p; T_bolt = 400 N m; P = 940 N/mm^2;
    # head annulus 24/17 mm; R1 = 18, r1 = 10 mm; mu = 0.2; TTV = 226 + 19 = 245 N m
    csa = bj.tensile_stress_area(0.016, 0.0015, 0.938)
    assert csa * 1e6 == pytest.approx(167.255, abs=0.0005)
    f = bj.preload_from_torque(400.0, 0.016, 0.2)
    assert f == pytest.approx(1.25e5, abs=0.005e5)
    percent = 100 * bj.proof_stress_ratio(f, 940e6, csa)
    assert percent == pytest.approx(79.507, abs=0.0005)
    sigma = bj.head_contact_stress(f, 0.024, 0.017)
    assert sigma / 1e6 == pytest.approx(554.547, abs=0.0005)
    cap = bj.slip_torque_capacity(0.2, f, 0.036, 0.020)
    assert cap == pytest.approx(359.524, abs=0.0005)
    assert bj.cover_factor(cap, 245.0) == pytest.approx(1.467, abs=0.0005)


def test_flywheel_worked_example():
    # slide 24: 6 x M10x1.0 grade 12.9 yield controlled, k = 0.75, sigma_b = 1100 MPa;
    # face d = 47, D = 84.4 mm; mu = 0.2; T_max = 265 + 951 = 1216 N m
    tsa = bj.tensile_stress_area(0.010, 0.001)  # ISO coefficient 0.9382
    assert tsa * 1e6 == pytest.approx(64.494, abs=0.0005)
    fb = bj.preload_from_stress(0.75, 1100e6, tsa)
    assert fb / 1e3 == pytest.approx(53.207, abs=0.0005)
    assert 6 * fb / 1e3 == pytest.approx(319.245, abs=0.0005)
    deff = bj.effective_friction_diameter(0.0844, 0.047)
    assert deff * 1e3 == pytest.approx(67.474, abs=0.0005)
    tcap = bj.slip_torque_capacity(0.2, 6 * fb, 0.0844, 0.047)
    assert tcap / 1e3 == pytest.approx(2.154, abs=0.0005)
    assert bj.cover_factor(tcap, 1216.0) == pytest.approx(1.771, abs=0.0005)


def test_property_class_table_matches_seed():
    # slide 24 table: Rp0.2 940/1020/1100, stress under proofing load 830/900/970 MPa
    for cls, (rp, sp) in {"10.9": (940, 830), "11.9": (1020, 900), "12.9": (1100, 970)}.items():
        assert bj.PROPERTY_CLASSES[cls] == (rp * 1e6, sp * 1e6)
    assert bj.PRELOAD_FRACTIONS["yield controlled"] == (0.75, "rp02")
    assert bj.PRELOAD_FRACTIONS["angle controlled"] == (0.85, "rp02")
    assert bj.PRELOAD_FRACTIONS["torque wrench"] == (0.70, "proof_load_stress")


def test_effective_diameter_limits():
    # closed form: a thin ring (d -> D) has D_eff -> D; a full disc has D_eff = 2/3 D
    assert bj.effective_friction_diameter(0.1, 0.0) == pytest.approx(2 / 3 * 0.1, rel=1e-12)
    assert bj.effective_friction_diameter(0.1, 0.0999999) == pytest.approx(0.1, rel=1e-6)


def test_vectorized_over_joints():
    d = np.array([0.016, 0.010])
    p = np.array([0.0015, 0.001])
    a = bj.tensile_stress_area(d, p)
    assert a.shape == (2,)
    assert a[1] == pytest.approx(bj.tensile_stress_area(0.010, 0.001))


@pytest.mark.parametrize("call", [
    lambda: bj.tensile_stress_area(-0.01, 0.001),
    lambda: bj.tensile_stress_area(0.01, 0.006),
    lambda: bj.head_contact_stress(1e4, 0.017, 0.024),
    lambda: bj.effective_friction_diameter(0.04, 0.05),
    lambda: bj.preload_from_torque(0.0, 0.016),
    lambda: bj.preload_from_stress(1.2, 1e9, 1e-4),
    lambda: bj.cover_factor(100.0, 0.0),
])
def test_invalid_inputs_raise(call):
    with pytest.raises(ValueError):
        call()
