"""Tests for checker.calc.crank_stress (nominal stresses, statically determinate throw).

Sources: IACS UR M53 §2 (KR RA-05-E 2025 Pt 5 Annex 5-3 §2; standards.md §1.2) for the
equations; the hand calculations below use the example engine of seed 000 (pin 48, journal 55,
stroke 94.6, main spacing 96, main journal length 27, pin length 24.4, web reduced thickness
21.3, web minimum width 71.4, oil hole angle 45 deg; all mm). Hand values are written out to
5 significant digits in the comments and compared at rtol 1e-4 (the rounding of the written
values); exact identities (symmetry, cyclic shifts, M53's psi form) at rtol 1e-12.
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.crank_stress import (
    bay_bending_moment,
    local_stresses,
    oil_hole_bending_stress,
    pin_force_in_throw_frame,
    shaft_section_moduli,
    throw_nominal_stresses,
    torsional_stress,
    web_centre_distance,
    web_overlap,
    web_section_properties,
    web_width,
)
from checker.calc.fatigue import fillet_goodman, oil_hole_goodman
from checker.calc.scf import m53_scf

MM = 1e-3
GEOM = dict(
    pin_diameter=48 * MM,
    journal_diameter=55 * MM,
    throw=47.3 * MM,
    main_spacing=96 * MM,
    main_journal_length=27 * MM,
    pin_journal_length=24.4 * MM,
    web_thickness=21.3 * MM,
    web_width=71.4 * MM,
    oil_hole_angle=np.deg2rad(45.0),
)


def test_overlap_and_web_geometry_hand_calc():
    # S = (48 + 55)/2 - 47.3 = 4.2 mm (M53 §3.1)
    assert float(web_overlap(48 * MM, 55 * MM, 47.3 * MM)) == pytest.approx(4.2 * MM, rel=1e-12)
    # W_full = (96 - 27 - 24.4)/2 = 22.3 mm (seed: "full width 22.3"); L1 = 13.5 + 11.15
    assert web_centre_distance(96 * MM, 27 * MM, 24.4 * MM) == pytest.approx(24.65 * MM)
    assert web_centre_distance(96 * MM, 27 * MM, 24.4 * MM, 0.5 * MM) == pytest.approx(25.15 * MM)
    # F = 71.4 * 21.3 = 1520.8 mm^2, W_eqw = 71.4 * 21.3^2 / 6 = 5398.9 mm^3
    area, modulus = web_section_properties(21.3 * MM, 71.4 * MM)
    assert float(area) == pytest.approx(1520.82e-6, rel=1e-4)
    assert float(modulus) == pytest.approx(5398.9e-9, rel=1e-4)
    assert web_width(71.4 * MM, 80 * MM) == 71.4 * MM
    assert web_width(71.4 * MM, 80 * MM, "max") == 80 * MM
    assert web_width(71.4 * MM, 80 * MM, "mean") == pytest.approx(75.7 * MM)


def test_simple_throw_hand_calc():
    # Constant load: F_R = -20 kN (towards the crank axis, gas-like), F_T = +8 kN,
    # pin torque 300 N m, journal torque 300 N m; pin centred (L2 = 48 mm).
    # Web force (each web): Q_RF = -20/2 = -10 kN; M_BRF = -10e3 * 0.02465 = -246.5 N m
    # sigma_BF = -246.5 / 5.3989e-6 = -45.657 MPa (journal-side face; pin side +45.657)
    # sigma_QF = -10e3 / 1.5208e-3 = -6.5754 MPa
    # journal fillet moment: -10e3 * 0.0135 = -135 N m; pin fillet: -10e3 * 0.0358 = -358 N m
    # W_p,pin = pi/16 * 0.048^3 = 2.1715e-5 m^3 -> tau_pin = 13.816 MPa
    # W_p,jnl = pi/16 * 0.055^3 = 3.2668e-5 m^3 -> tau_jnl = 9.1834 MPa
    # oil hole at the pin centre (x = 48 mm): M_BRO = -10e3 * 0.048 = -480 N m,
    # M_BTO = +4e3 * 0.048 = +192 N m, W_e = pi/32 * 0.048^3 = 1.0857e-5 m^3,
    # sigma_BO = (-480 cos45 + 192 sin45) / W_e = -18.757 MPa
    n = 8
    res = throw_nominal_stresses(
        np.full(n, -20e3), np.full(n, 8e3), np.full(n, 300.0), np.full((2, n), 300.0), **GEOM
    )
    assert res.overlap == pytest.approx(4.2 * MM)
    assert res.web_centre_distance == pytest.approx(24.65 * MM)
    assert res.web_force.shape == (2, n)
    np.testing.assert_allclose(res.web_force, -10e3, rtol=1e-12)
    np.testing.assert_allclose(res.moment_web, -246.5, rtol=1e-12)
    np.testing.assert_allclose(res.moment_web_tangential, 4e3 * 0.02465, rtol=1e-12)
    np.testing.assert_allclose(res.moment_journal_fillet, -135.0, rtol=1e-12)
    np.testing.assert_allclose(res.moment_pin_fillet, -358.0, rtol=1e-12)
    np.testing.assert_allclose(res.sigma_web_bending, -45.657e6, rtol=1e-4)
    np.testing.assert_allclose(res.sigma_web_direct, -6.5754e6, rtol=1e-4)
    np.testing.assert_allclose(res.tau_pin, 13.816e6, rtol=1e-4)
    np.testing.assert_allclose(res.tau_journal, 9.1834e6, rtol=1e-4)
    np.testing.assert_allclose(res.moment_oil_radial, -480.0, rtol=1e-12)
    np.testing.assert_allclose(res.moment_oil_tangential, 192.0, rtol=1e-12)
    np.testing.assert_allclose(res.sigma_oil_bending, -18.757e6, rtol=1e-4)
    # K_e = 0.8 (2-stroke, M53 §2.1.2.1) scales both web stresses
    res2 = throw_nominal_stresses(-20e3 * np.ones(n), 0 * np.ones(n), 0.0, 0.0, k_e=0.8, **GEOM)
    np.testing.assert_allclose(res2.sigma_web_bending, 0.8 * res.sigma_web_bending, rtol=1e-12)
    np.testing.assert_allclose(res2.sigma_web_direct, 0.8 * res.sigma_web_direct, rtol=1e-12)


def test_local_stress_signs_under_gas_load():
    # Free body of the web: an inward (gas) force puts the crankpin-side face in tension and
    # the journal-side face in compression (bending + direct compression add there).
    res = throw_nominal_stresses(np.array([-20e3, 0.0]), np.zeros(2), 0.0, 0.0, **GEOM)
    loc = local_stresses(
        res, alpha_b=3.0, alpha_t=2.0, beta_b=4.0, beta_q=3.0, beta_t=2.0, gamma_b=3.0,
        gamma_t=4.0,
    )  # fmt: skip
    # pin fillet: 3.0 * 45.657 = 136.97 MPa; journal fillet: 4 * -45.657 + 3 * -6.5754
    # = -202.35 MPa
    np.testing.assert_allclose(loc.sigma_pin_fillet[:, 0], 136.97e6, rtol=1e-4)
    np.testing.assert_allclose(loc.sigma_journal_fillet[:, 0], -202.35e6, rtol=1e-4)
    np.testing.assert_allclose(loc.sigma_pin_fillet[:, 1], 0.0, atol=1e-9)
    assert loc.tau_pin_fillet.shape == (2, 2)


def test_pin_force_in_throw_frame_rotation():
    # Throw pointing along crank-frame x (gamma = 90 deg): a force along +x is radial outward,
    # a force along +y (= -e_t there) is tangential negative. gamma = 0: identity mapping.
    fr, ft = pin_force_in_throw_frame(np.array([1.0, 0.0]), np.array([0.0, 1.0]), np.pi / 2)
    np.testing.assert_allclose(fr, [1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(ft, [0.0, -1.0], atol=1e-15)
    fr, ft = pin_force_in_throw_frame(3.0, -2.0, 0.0)
    assert (float(fr), float(ft)) == (-2.0, 3.0)
    # magnitude preserved (rotation)
    rng = np.random.default_rng(3)
    fx, fy, g = rng.normal(size=(3, 20))
    fr, ft = pin_force_in_throw_frame(fx, fy, g)
    np.testing.assert_allclose(np.hypot(fr, ft), np.hypot(fx, fy), rtol=1e-12)


def test_bay_bending_moment_triangular_diagram():
    # F = 1000 N, L3 = 0.1 m, L2 = 0.04 m: M(0.02) = 1000 * 0.06 * 0.02 / 0.1 = 12 N m,
    # M(0.04) = 1000 * 0.06 * 0.04 / 0.1 = 24 N m, M(0.07) = 1000 * 0.04 * 0.03 / 0.1 = 12 N m
    m = bay_bending_moment(1000.0, np.array([0.0, 0.02, 0.04, 0.07, 0.1]), 0.1, 0.04)
    np.testing.assert_allclose(m, [0.0, 12.0, 24.0, 12.0, 0.0], rtol=1e-12, atol=1e-12)


def test_off_centre_pin_shares_the_force_by_lever_rule():
    # L2 = 44 mm: front web carries (96 - 44)/96, rear web 44/96 of F_R (static equilibrium)
    res = throw_nominal_stresses(
        np.full(3, 9.6e3), np.zeros(3), 0.0, 0.0, pin_position=44 * MM, **GEOM
    )
    np.testing.assert_allclose(res.web_force[0], 5.2e3, rtol=1e-12)
    np.testing.assert_allclose(res.web_force[1], 4.4e3, rtol=1e-12)
    np.testing.assert_allclose(res.web_force.sum(axis=0), 9.6e3, rtol=1e-12)


def test_oil_hole_matches_m53_psi_form():
    # M53 §2.1.2.2: M_BO = M_BTO cos(psi) + M_BRO sin(psi); here psi = pi/2 - phi
    rng = np.random.default_rng(1)
    mr, mt = rng.normal(size=(2, 50)) * 500.0
    for phi in (0.0, 0.3, np.pi / 4, 2.0, -1.0):
        psi = np.pi / 2 - phi
        we, _ = shaft_section_moduli(48 * MM)
        want = (mt * np.cos(psi) + mr * np.sin(psi)) / we
        np.testing.assert_allclose(oil_hole_bending_stress(mr, mt, phi, 48 * MM), want, rtol=1e-12)


def test_hollow_pin_torsion_hand_calc():
    # W_p = pi/16 (48^4 - 20^4)/48 = 21060 mm^3 -> 300 N m gives 14.245 MPa
    assert float(torsional_stress(300.0, 48 * MM, 20 * MM)) == pytest.approx(14.245e6, rel=1e-4)
    # bending modulus is half the polar one for a round section
    we, wp = shaft_section_moduli(48 * MM, 20 * MM)
    assert float(wp) == pytest.approx(2 * float(we), rel=1e-12)


def _cylinder_forces(theta_local, throw=47.3 * MM, rod=145.7 * MM, omega=600.0):
    """Simple slider-crank pin force (gas pulse + reciprocating inertia) for the tests."""
    lam = throw / rod
    area = np.pi / 4 * 0.086**2
    ang = np.mod(theta_local + np.pi, 4 * np.pi) - np.pi  # -pi .. 3pi, firing TDC at 0
    p = 1e5 + 75e5 * np.exp(-(((ang - np.deg2rad(12)) / np.deg2rad(25)) ** 2))
    acc = throw * omega**2 * (np.cos(theta_local) + lam * np.cos(2 * theta_local))
    fp = (p - 1e5) * area - 0.64 * acc  # along the cylinder axis, + towards the crank
    beta = np.arcsin(lam * np.sin(theta_local))
    f_r = -fp * np.cos(theta_local + beta) / np.cos(beta) + 0.38 * throw * omega**2
    f_t = fp * np.sin(theta_local + beta) / np.cos(beta)
    return f_r, f_t


def test_i4_mirror_symmetric_loads_give_matching_throws():
    # I4, firing order 1-3-4-2, phases 0/540/180/360 deg (seed 000 VALDYN table). Throws 1 and
    # 4 (and 2 and 3) see the same load history shifted by 360 deg; journal torques are built
    # mirror-symmetric (front of throw 1 <-> rear of throw 4). Then the per-cycle results must
    # coincide (exact identity up to round-off, rtol 1e-12), on a 2 case x 3 speed grid.
    n = 720
    theta = np.arange(n) * 4 * np.pi / n
    phase = np.deg2rad([0.0, 540.0, 180.0, 360.0])
    omega = np.array([300.0, 450.0, 600.0])[:, None, None]  # (speed, throw, angle)
    loc_theta = theta - phase[:, None]  # (throw, angle)
    f_r, f_t = _cylinder_forces(loc_theta[None], omega=omega)
    load = np.array([1.0, 0.3])[:, None, None, None]  # full / part load scaling (case)
    f_r, f_t = f_r[None] * load, f_t[None] * load  # (2, 3, 4, n)
    pin_t = 200.0 + 150.0 * np.sin(2 * loc_theta)
    a = 100.0 + 80.0 * np.sin(2 * loc_theta + 0.3)
    b = 300.0 + 60.0 * np.sin(4 * loc_theta)
    jt = np.stack([a, b], axis=-2)  # (throw, 2, n)
    jt[2:] = jt[2:, ::-1]  # mirror: throws 3, 4 swap front and rear
    jt *= np.array([1.0, 1.3, 1.3, 1.0])[:, None, None]  # outer/inner throws differ
    res = throw_nominal_stresses(f_r, f_t, pin_t, jt, **GEOM)
    assert res.sigma_web_bending.shape == (2, 3, 4, 2, n)
    assert res.sigma_oil_bending.shape == (2, 3, 4, n)
    # histories of throw 4 are those of throw 1 shifted by 360 deg (n/2 samples)
    np.testing.assert_allclose(
        res.sigma_web_bending[:, :, 3], np.roll(res.sigma_web_bending[:, :, 0], n // 2, -1),
        rtol=1e-12, atol=1e-6,
    )  # fmt: skip
    # centred pin -> front and rear web bending identical
    np.testing.assert_array_equal(
        res.sigma_web_bending[..., 0, :], res.sigma_web_bending[..., 1, :]
    )

    k = m53_scf(
        pin_diameter=48 * MM, journal_diameter=55 * MM, throw=47.3 * MM, web_thickness=21.3 * MM,
        web_width=71.4 * MM, pin_fillet_radius=1.6 * MM, journal_fillet_radius=1.6 * MM,
        oil_hole_diameter=5.4 * MM,
    )  # fmt: skip
    loc = local_stresses(
        res, alpha_b=k.alpha_b, alpha_t=k.alpha_t, beta_b=k.beta_b, beta_q=k.beta_q,
        beta_t=k.beta_t, gamma_b=k.gamma_b, gamma_t=k.gamma_t,
    )  # fmt: skip
    pin = fillet_goodman(
        loc.sigma_pin_fillet, loc.tau_pin_fillet, endurance_limit=619e6, ultimate_strength=920e6
    )
    jnl = fillet_goodman(
        loc.sigma_journal_fillet, loc.tau_journal_fillet, endurance_limit=611e6,
        ultimate_strength=920e6,
    )  # fmt: skip
    oil = oil_hole_goodman(
        loc.sigma_oil_bending, loc.sigma_oil_torsion, endurance_limit=326e6,
        ultimate_strength=750e6,
    )  # fmt: skip
    assert pin.safety_factor.shape == (2, 3, 4, 2)
    assert oil.safety_factor.shape == (2, 3, 4)
    for i, j in ((0, 3), (1, 2)):
        np.testing.assert_allclose(
            pin.safety_factor[:, :, i], pin.safety_factor[:, :, j], rtol=1e-12
        )
        np.testing.assert_allclose(
            jnl.safety_factor[:, :, i], jnl.safety_factor[:, :, j, ::-1], rtol=1e-12
        )
        np.testing.assert_allclose(
            oil.safety_factor[:, :, i], oil.safety_factor[:, :, j], rtol=1e-12
        )
    # the comparison is not vacuous: outer and inner throws differ, and without the mirror
    # (front of throw 1 vs front of throw 4) the journal results differ
    assert not np.allclose(jnl.safety_factor[:, :, 0], jnl.safety_factor[:, :, 1], rtol=1e-6)
    assert not np.allclose(jnl.safety_factor[:, :, 0], jnl.safety_factor[:, :, 3], rtol=1e-6)


@pytest.mark.parametrize(
    ("override", "match"),
    [
        (dict(pin_position=100 * MM), "pin_position"),
        (dict(pin_position=30 * MM), "web centre"),
        (dict(oil_hole_position=20 * MM), "oil_hole_position"),
        (dict(pin_bore=48 * MM), "bore"),
        (dict(main_spacing=50 * MM), "leaves no web"),
        (dict(web_offset=12 * MM), "web_offset"),
        (dict(web_thickness=-1.0), "web_thickness"),
        (dict(k_e=0.0), "k_e"),
    ],
)
def test_invalid_inputs_raise(override, match):
    with pytest.raises(ValueError, match=match):
        throw_nominal_stresses(np.zeros(4), np.zeros(4), 0.0, 0.0, **dict(GEOM, **override))


def test_non_finite_loads_raise():
    f = np.array([0.0, np.nan, 1.0])
    with pytest.raises(ValueError, match="force_radial"):
        throw_nominal_stresses(f, np.zeros(3), 0.0, 0.0, **GEOM)
    with pytest.raises(ValueError, match="journal_torque"):
        throw_nominal_stresses(np.zeros(3), np.zeros(3), 0.0, np.array([np.inf]), **GEOM)
