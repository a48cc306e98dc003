"""Tests for checker.calc.throw_fatigue (the steps of the crankshaft-fatigue node).

Independent numbers:
* element torques: the order sum evaluated directly, T_mean + sum Re{T_n exp(j n theta)} at
  theta_k = 4 pi k / N (rtol 1e-12);
* throw Goodman: hand evaluation of M53 §2.1-2.2 for a fully reversed radial force (bending
  only, L1 = L_G/2 + (L3 - L_G - L_H)/4, section modulus B W^2/6) and for a torque with a mean
  (torsion only, W_P = pi D^3/16), Goodman 1/SF = sigma_a/S_e + sigma_m/S_u (Shigley eq.
  6-46), rtol 1e-9;
* main oil hole and M53 Q: closed forms of M53 §5(4) and §5-7 (rtol 1e-12);
* the pin's torque: statics of a throw simply supported at its mains, checked by summing the
  moments about the pin axis of the front free body (rtol 1e-12).
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.fatigue import CycleFatigue
from checker.calc.throw_fatigue import (
    element_torque_cycle,
    gather_candidates,
    governing_candidate,
    m53_q,
    main_journal_elements,
    main_oil_hole_goodman,
    pin_torque,
    throw_goodman,
)

N = 72
THETA = 4 * np.pi * np.arange(N) / N  # 720 deg cycle
# a throw of the Bell (Ricardo 2013) example engine's proportions [m]
GEOM = dict(pin_diameter=0.048, journal_diameter=0.052, throw=0.043, main_spacing=0.096,
            main_journal_length=0.027, pin_journal_length=0.0244, web_thickness=0.0213,
            web_width=0.0714)
SCF = dict(alpha_b=2.5, alpha_t=1.8, beta_b=2.7, beta_q=1.4, beta_t=1.6, gamma_b=1.3,
           gamma_t=2.2)
STRENGTHS = {"pin fillet": (300e6, 800e6), "main fillet": (280e6, 800e6),
             "pin oil hole": (320e6, 900e6)}
L1 = 0.027 / 2 + (0.096 - 0.027 - 0.0244) / 4  # web centre from the main centre [m]
W_BEND = 0.0714 * 0.0213**2 / 6  # B W^2 / 6 [m^3]


def test_element_torque_cycle_is_the_order_sum():
    orders = [0.5, 1.0, 2.5]
    rng = np.random.default_rng(0)
    coeffs = rng.normal(size=(3, 2, 4, 3)) + 1j * rng.normal(size=(3, 2, 4, 3))  # (E, C, S, n)
    mean = rng.normal(size=(3, 2, 4)) * 100
    t = element_torque_cycle(orders, coeffs, mean, N)
    assert t.shape == (2, 4, 4, N)
    direct = mean[..., None] + sum(
        np.real(coeffs[..., n, None] * np.exp(1j * o * THETA)) for n, o in enumerate(orders))
    np.testing.assert_allclose(t[:, :, :3], np.moveaxis(direct, 0, 2), rtol=1e-12, atol=1e-12)
    assert not t[:, :, 3].any()  # the free-end "element" carries no torque


def test_main_journal_elements_of_an_i4_and_a_free_end():
    # I4: nose -> c1 (0), c1 -> c2 (1) ... c4 -> flywheel (4); main k between throws k-1, k
    sides = [[0, 1], [1, 2], [2, 3], [3, 4]]
    assert main_journal_elements(sides, 5).tolist() == [[0, 0], [1, 1], [2, 2], [3, 3],
                                                        [4, 4]]
    # a station without neighbour on one side (free end = element index E = 2): both
    # candidates of a middle journal differ when the throws disagree
    assert main_journal_elements([[2, 0], [1, 2]], 3).tolist() == [[2, 2], [1, 0], [2, 2]]


def test_throw_goodman_bending_only_by_hand():
    f0 = 20e3
    fr = (f0 * np.cos(THETA))[None, :]  # (T = 1, N)
    out = throw_goodman(fr, np.zeros_like(fr), np.zeros((1, 2, N)), GEOM, 0.0, SCF, STRENGTHS,
                        pin_oil_hole=False)
    assert out.pin_oil is None
    sigma_bf = f0 / 2 * L1 / W_BEND  # amplitude at either web (pin at mid-bay)
    np.testing.assert_allclose(out.nominal.web_centre_distance, L1, rtol=1e-12)
    np.testing.assert_allclose(out.pin.sigma_a, 2.5 * sigma_bf, rtol=1e-9)
    np.testing.assert_allclose(out.pin.safety_factor, 300e6 / (2.5 * sigma_bf), rtol=1e-9)
    sigma_g = f0 / 2 * (2.7 * L1 / W_BEND + 1.4 / (0.0714 * 0.0213))
    np.testing.assert_allclose(out.journal.safety_factor, 280e6 / sigma_g, rtol=1e-9)


def test_throw_goodman_torsion_only_by_hand():
    t0, ta = 300.0, 200.0
    side = np.zeros((1, 2, N))
    side[0, 0] = t0 + ta * np.cos(THETA)  # front element; rear: a free end
    side[0, 1] = t0 + ta * np.cos(THETA)
    zero = np.zeros((1, N))
    out = throw_goodman(zero, zero, side, GEOM, 0.3, SCF, STRENGTHS, pin_oil_hole=True)
    wp_pin, wp_jnl = np.pi * 0.048**3 / 16, np.pi * 0.052**3 / 16
    # fillets: von Mises of pure shear, sqrt(3) tau (signed von Mises mean, positive)
    for r, k, wp, (se, su) in ((out.pin, 1.8, wp_pin, STRENGTHS["pin fillet"]),
                               (out.journal, 1.6, wp_jnl, STRENGTHS["main fillet"])):
        sa, sm = np.sqrt(3) * k * ta / wp, np.sqrt(3) * k * t0 / wp
        np.testing.assert_allclose(r.safety_factor[0], 1 / (sa / se + sm / su), rtol=1e-9)
    # oil hole, no bending: M53 §5(4) (0 + 2 sqrt(9/4 s^2))/3 = s, s = gamma_T tau
    se, su = STRENGTHS["pin oil hole"]
    sa, sm = 2.2 * ta / wp_pin, 2.2 * t0 / wp_pin
    np.testing.assert_allclose(out.pin_oil.safety_factor[0], 1 / (sa / se + sm / su), rtol=1e-9)


def test_pin_torque_is_the_moment_of_the_front_free_body_about_the_pin_axis():
    # front journal torque T_f, tangential rod force F_T at the pin (radius R, L2 from the front
    # main of a bay L3): T_r = T_f + R F_T; the front main's reaction -F_T (L3 - L2)/L3 acts
    # on the crank axis, -R e_r from the pin axis: its moment about the pin axis is
    # + R F_T (L3 - L2)/L3 (r x F with r = -R e_r, F = -F_T (L3 - L2)/L3 e_t)
    tf, ft, r, l3 = 150.0, 4000.0, 0.043, 0.096
    for l2 in (0.048, 0.03, 0.07):
        reaction = -ft * (l3 - l2) / l3
        moment = -r * reaction  # (-R e_r) x (reaction e_t) = -R reaction e_x
        side = np.array([[[tf], [tf + r * ft]]])  # (T = 1, 2, N = 1)
        np.testing.assert_allclose(pin_torque(side, l3, l2)[0, 0], tf + moment, rtol=1e-12)
    with pytest.raises(ValueError, match="inside the bay"):
        pin_torque(side, l3, l3)


def test_pin_oil_hole_and_fillets_carry_the_pins_torque_not_the_larger_side():
    # a throw whose rear element carries 3x the front's alternating torque: the pin (centred)
    # carries their mean at both fillets and the oil hole
    side = np.zeros((1, 2, N))
    side[0, 0] = 100.0 * np.cos(THETA)
    side[0, 1] = 300.0 * np.cos(THETA)
    zero = np.zeros((1, N))
    out = throw_goodman(zero, zero, side, GEOM, 0.3, SCF, STRENGTHS, pin_oil_hole=True)
    wp_pin = np.pi * 0.048**3 / 16
    se = STRENGTHS["pin oil hole"][0]
    np.testing.assert_allclose(out.pin_oil.safety_factor[0], se / (2.2 * 200.0 / wp_pin),
                               rtol=1e-9)
    se = STRENGTHS["pin fillet"][0]
    np.testing.assert_allclose(out.pin.safety_factor[0],
                               se / (np.sqrt(3) * 1.8 * 200.0 / wp_pin), rtol=1e-9)
    np.testing.assert_allclose(out.nominal.tau_pin[0], 200.0 * np.cos(THETA) / wp_pin,
                               rtol=1e-9, atol=1e-3)


def test_throw_goodman_rejects_a_web_thicker_than_the_bay():
    bad = dict(GEOM, main_spacing=0.05)
    with pytest.raises(ValueError):
        throw_goodman(np.ones((1, N)), np.ones((1, N)), np.zeros((1, 2, N)), bad, 0.0, SCF,
                      STRENGTHS)


def test_main_oil_hole_goodman_with_a_mean_torque():
    t = 400.0 + 150.0 * np.cos(THETA)
    r = main_oil_hole_goodman(t, 0.052, 0.02, 2.0, 300e6, 850e6)
    wp = np.pi / 16 * (0.052**4 - 0.02**4) / 0.052
    sa, sm = 2.0 * 150.0 / wp, 2.0 * 400.0 / wp
    assert float(r.safety_factor) == pytest.approx(1 / (sa / 300e6 + sm / 850e6), rel=1e-9)


def test_m53_q_fillet_and_oil_bore():
    sa = np.array([[50e6, 30e6]])
    ta = np.array([[20e6, 40e6]])
    sv, q = m53_q(sa, ta, 300e6, oil_bore=False, sigma_add=10e6)
    # candidates: sqrt(60^2 + 3 20^2) = 69.28, sqrt(40^2 + 3 40^2) = 80 MPa -> the second
    assert float(sv[0]) == pytest.approx(80e6, rel=1e-12)
    assert float(q[0]) == pytest.approx(300 / 80, rel=1e-12)
    sv, q = m53_q(sa, ta, 300e6, oil_bore=True)
    # (s + 2 sqrt(s^2 + 9/4 t^2))/3: 50, 20 MPa -> (50 + 2 sqrt(3400))/3 = 55.54 MPa, above
    # 30, 40 MPa -> (30 + 2 sqrt(4500))/3 = 54.72 MPa; no sigma_add at the oil bore
    want = (50 + 2 * np.sqrt(50**2 + 2.25 * 20**2)) / 3
    assert want == pytest.approx(55.54, abs=0.005)
    assert float(sv[0]) == pytest.approx(want * 1e6, rel=1e-12)
    assert float(q[0]) == pytest.approx(300 / want, rel=1e-12)


def test_governing_candidate_is_the_lowest_safety_factor_of_the_gathered_pairs():
    # two results over (case = 1, speed = 2, throw = 2, web = 2); each field a distinct ramp
    base = np.arange(8.0).reshape(1, 2, 2, 2)
    r = CycleFatigue(*(base + 100 * k for k in range(7)))  # safety_factor = base + 600
    cand = gather_candidates([r, r], [[(0, 0), (1, 1)], [(1, 0), (1, 0)]])
    assert cand.safety_factor.shape == (1, 2, 2, 2)
    np.testing.assert_array_equal(cand.safety_factor[0, 1], [[604.0, 607.0], [606.0, 606.0]])
    picked, k = governing_candidate(cand)
    np.testing.assert_array_equal(k, [[[0, 0], [0, 0]]])
    np.testing.assert_array_equal(picked.safety_factor, [[[600.0, 602.0], [604.0, 606.0]]])
    # the other fields follow the governing candidate (sigma_a = base + 0)
    np.testing.assert_array_equal(picked.sigma_a, picked.safety_factor - 600)
    # a lower factor at the second candidate governs
    sf = cand.safety_factor.copy()
    sf[0, 0, 0, 1] = 1.0
    picked, k = governing_candidate(cand._replace(safety_factor=sf))
    assert k[0, 0, 0] == 1 and picked.safety_factor[0, 0, 0] == 1.0
    assert picked.sigma_a[0, 0, 0] == cand.sigma_a[0, 0, 0, 1]
