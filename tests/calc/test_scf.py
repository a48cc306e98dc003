"""Tests for checker.calc.scf (IACS UR M53 empirical stress concentration factors).

Sources:
* IACS UR M53 §3 formulae as transcribed in KR RA-05-E 2025 Pt 5 Annex 5-3 and in
  /work/shared/reference/standards.md §1.3-1.4;
* the notes' worked numbers, standards.md §1.12 ([CALC] by the notes' author, printed to 3
  decimals for the marine throw and 2 decimals for the automotive throw -> tolerances of half
  the last printed digit);
* hand evaluation of the published formulae with literal numbers for the example engine
  (seed 000: D 48, D_G 55, E 47.3, W 21.3, B 71.4, R 1.6, D_O 5.4 mm) -> rtol 1e-12 (same
  arithmetic, different code path).
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.scf import m53_scf

MM = 1e-3

# Example engine (seed 000 slide 26 + engine table)
SEED = dict(
    pin_diameter=48 * MM,
    journal_diameter=55 * MM,
    throw=47.3 * MM,
    web_thickness=21.3 * MM,
    web_width=71.4 * MM,
    pin_fillet_radius=1.6 * MM,
    journal_fillet_radius=1.6 * MM,
    oil_hole_diameter=5.4 * MM,
)

# Marine throw of standards.md §1.12: D 300, D_G 320, R 15, S 60 (E = 250), W 100, B 440, D_O 30
MARINE = dict(
    pin_diameter=300 * MM,
    journal_diameter=320 * MM,
    throw=250 * MM,
    web_thickness=100 * MM,
    web_width=440 * MM,
    pin_fillet_radius=15 * MM,
    journal_fillet_radius=15 * MM,
    oil_hole_diameter=30 * MM,
)


def test_marine_worked_numbers_notes_1_12():
    # standards.md §1.12: alpha_B 2.183, alpha_T 2.066 (with 0.857 b^3), beta_B 2.429,
    # beta_Q 3.006, beta_T 2.098, gamma_B 2.758, gamma_T 3.700 (3 decimals -> atol 5e-4)
    k = m53_scf(**MARINE)
    got = [k.alpha_b, k.alpha_t, k.beta_b, k.beta_q, k.beta_t, k.gamma_b, k.gamma_t]
    want = [2.183, 2.066, 2.429, 3.006, 2.098, 2.758, 3.700]
    np.testing.assert_allclose(np.array(got, dtype=float), want, rtol=0, atol=5e-4)
    assert bool(k.in_range)
    assert k.messages == []


def test_automotive_worked_numbers_notes_1_12():
    # standards.md §1.12: D 50, D_G 55, R 2.5, S 9.5 (E = 43.0), W 20, B 80, D_O 6:
    # alpha_B 2.67, alpha_T 1.93, beta_B 2.99, beta_Q 3.51, gamma_B 2.79, gamma_T 3.71
    # (2 decimals -> atol 5e-3)
    k = m53_scf(
        pin_diameter=50 * MM,
        journal_diameter=55 * MM,
        throw=43.0 * MM,
        web_thickness=20 * MM,
        web_width=80 * MM,
        pin_fillet_radius=2.5 * MM,
        journal_fillet_radius=2.5 * MM,
        oil_hole_diameter=6 * MM,
    )
    got = [k.alpha_b, k.alpha_t, k.beta_b, k.beta_q, k.gamma_b, k.gamma_t]
    np.testing.assert_allclose(
        np.array(got, dtype=float), [2.67, 1.93, 2.99, 3.51, 2.79, 3.71], rtol=0, atol=5e-3
    )


def test_overlap_trend_notes_1_12():
    # standards.md §1.12, same marine throw: s = -0.3 -> alpha_B 2.81; 0 -> 2.53; 0.2 -> 2.18;
    # 0.4 -> 1.72 (2 decimals -> atol 5e-3); alpha_T rises with s (1.78 -> 2.20 quoted).
    s = np.array([-0.3, 0.0, 0.2, 0.4])
    geo = dict(MARINE, throw=(300 + 320) / 2 * MM - s * 300 * MM)
    k = m53_scf(**geo)
    np.testing.assert_allclose(k.alpha_b, [2.81, 2.53, 2.18, 1.72], rtol=0, atol=5e-3)
    assert np.all(np.diff(k.alpha_t) > 0)
    np.testing.assert_allclose(k.alpha_t[-1], 2.20, atol=5e-3)
    assert k.alpha_b.shape == (4,)


def test_seed_geometry_against_hand_evaluation():
    # Ratios: s = ((48+55)/2 - 47.3)/48 = 4.2/48 = 0.0875; w = 21.3/48 = 0.44375;
    # b = 71.4/48 = 1.4875; r = 1.6/48; r_G,torsion = 1.6/55; d_O = 5.4/48 = 0.1125;
    # no bores, no recess (seed "web undercut" 0) -> f(d_G) = 0.9993, f(d_H) = 0.9978,
    # f_B(d_G) = 1.0012, f_B(d_H) = 1.0022, f_Q(d_H) = 0.9937, f(recess) = 1.
    s, w, b, r, u = 0.0875, 0.44375, 1.4875, 1.6 / 48, 1 - 0.0875
    f_sw = (
        -4.1883 + 29.2004 * w - 77.5925 * w**2 + 91.9454 * w**3 - 40.0416 * w**4
        + u * (9.5440 - 58.3480 * w + 159.3415 * w**2 - 192.5846 * w**3 + 85.2916 * w**4)
        + u**2 * (-3.8399 + 25.0444 * w - 70.5571 * w**2 + 87.0328 * w**3 - 39.1832 * w**4)
    )  # fmt: skip
    alpha_b = (
        2.6914 * f_sw * (2.1790 * w**0.7171) * (0.6840 - 0.0077 * b + 0.1473 * b**2)
        * (0.2081 * r**-0.5231) * 0.9993 * 0.9978
    )  # fmt: skip
    f_b_t = 7.8955 - 10.654 * b + 5.3482 * b**2 - 0.857 * b**3
    alpha_t = 0.8 * r ** (-0.322 + 0.1015 * u) * f_b_t * w**-0.145
    beta_t = 0.8 * (1.6 / 55) ** (-0.322 + 0.1015 * u) * f_b_t * w**-0.145
    fb_sw = (
        -1.7625 + 2.9821 * w - 1.5276 * w**2
        + u * (5.1169 - 5.8089 * w + 3.1391 * w**2)
        + u**2 * (-2.1567 + 2.3297 * w - 1.2952 * w**2)
    )  # fmt: skip
    beta_b = (
        2.7146 * fb_sw * (2.2422 * w**0.7548) * (0.5616 + 0.1197 * b + 0.1176 * b**2)
        * (0.1908 * r**-0.5568) * 1.0012 * 1.0022
    )  # fmt: skip
    beta_q = (
        3.0128 * (0.4368 + 2.1630 * u - 1.5212 * u**2) * (w / (0.0637 + 0.9369 * w))
        * (b - 0.5) * (0.5331 * r**-0.2038) * 0.9937
    )  # fmt: skip
    gamma_b = 3 - 5.88 * 0.1125 + 34.6 * 0.1125**2
    gamma_t = 4 - 6 * 0.1125 + 30 * 0.1125**2
    k = m53_scf(**SEED)
    got = [k.alpha_b, k.alpha_t, k.beta_b, k.beta_q, k.beta_t, k.gamma_b, k.gamma_t]
    want = [alpha_b, alpha_t, beta_b, beta_q, beta_t, gamma_b, gamma_t]
    np.testing.assert_allclose(np.array(got, dtype=float), want, rtol=1e-12)
    np.testing.assert_allclose(k.ratios.s, s, rtol=1e-12)
    # rounded values for the report reader: alpha_B 3.63, alpha_T 2.08, beta_B 4.17,
    # beta_Q 3.34, beta_T 2.15, gamma_B 2.78, gamma_T 3.70
    np.testing.assert_allclose(
        np.array(got, dtype=float), [3.63, 2.08, 4.17, 3.34, 2.15, 2.78, 3.70], atol=5e-3
    )


def test_seed_geometry_flags_journal_torsion_radius():
    # r = R_G/D_G = 1.6/55 = 0.0291 < 0.03 (M53 §3.1) -> flagged; everything else in range:
    # r = 1.6/48 = 0.0333, s = 0.0875, w = 0.444, b = 1.49, d_O = 0.1125.
    k = m53_scf(**SEED)
    fired = sorted(name for name, f in k.flags.items() if f.any())
    assert fired == ["r_journal_torsion_out_of_range"]
    assert not bool(k.in_range)
    assert len(k.messages) == 1 and "r_journal_torsion" in k.messages[0]
    assert "0.02909" in k.messages[0]


def test_beta_t_equals_alpha_t_for_equal_pin_and_journal():
    # M53 §3.3(C)(a): same diameters and radii -> beta_T = alpha_T (exactly)
    k = m53_scf(**dict(MARINE, journal_diameter=300 * MM, throw=240 * MM))
    assert float(k.beta_t) == float(k.alpha_t)
    assert bool(k.flags["beta_t_equal_to_alpha_t"])


@pytest.mark.parametrize(
    ("override", "flag"),
    [
        (dict(pin_fillet_radius=6 * MM), "r_pin_out_of_range"),  # r = 0.02 < 0.03
        (dict(pin_fillet_radius=42 * MM), "r_pin_out_of_range"),  # r = 0.14 > 0.13
        (dict(journal_fillet_radius=6 * MM), "r_journal_out_of_range"),  # R_G/D = 0.02
        (dict(throw=100 * MM), "s_out_of_range"),  # S = 210 mm, s = 0.7 > 0.5
        (dict(web_thickness=50 * MM), "w_out_of_range"),  # w = 0.167 < 0.2
        (dict(web_thickness=250 * MM), "w_out_of_range"),  # w = 0.833 > 0.8
        (dict(web_width=300 * MM), "b_out_of_range"),  # b = 1.0 < 1.1
        (dict(web_width=700 * MM), "b_out_of_range"),  # b = 2.33 > 2.2
        (dict(oil_hole_diameter=75 * MM), "d_O_out_of_range"),  # d_O = 0.25 > 0.2
        (dict(pin_bore=250 * MM), "d_H_out_of_range"),  # d_H = 0.833 > 0.8
        (dict(journal_bore=270 * MM), "d_G_out_of_range"),  # d_G = 0.9 > 0.8
    ],
)
def test_validity_flags_trigger(override, flag):
    # Validity ranges: IACS UR M53 §3.1 table (standards.md §1.3); base = in-range marine throw
    k = m53_scf(**dict(MARINE, **override))
    assert bool(k.flags[flag]), k.flags
    assert not bool(k.in_range)
    assert any(flag.removesuffix("_out_of_range") in m for m in k.messages)
    # the factor is still computed (M53: "to be used with care" / FEM), finite and positive
    assert np.isfinite(float(k.alpha_b)) and float(k.alpha_b) > 0


def test_nonpositive_factor_far_outside_range_is_nan_and_flagged():
    # s = 0.7 (> 0.5): the journal quadratic f_B(s, w) turns negative -> beta_B <= 0 is
    # physically meaningless; returned as NaN with a flag and message, never silently.
    k = m53_scf(**dict(MARINE, throw=100 * MM))
    assert np.isnan(float(k.beta_b))
    assert bool(k.flags["beta_b_invalid"]) and bool(k.flags["s_out_of_range"])
    assert any("non-positive beta_b" in m for m in k.messages)
    assert float(k.alpha_b) > 0 and not bool(k.flags["alpha_b_invalid"])


def test_flags_are_elementwise_for_arrays():
    k = m53_scf(**dict(MARINE, web_width=np.array([440, 700]) * MM))
    np.testing.assert_array_equal(k.flags["b_out_of_range"], [False, True])
    np.testing.assert_array_equal(k.in_range, [True, False])
    assert k.flags["r_pin_out_of_range"].shape == (2,)


def test_s_below_minus_half_evaluated_at_minus_half():
    # M53 §3.1: for s < -0.5, f(s,w) and f(r,s) use s = -0.5; without recess f(recess) = 1, so
    # alpha_B and alpha_T at s = -0.8 and s = -1.2 are equal (both evaluated at -0.5) and
    # differ from s = -0.4 (not clipped).
    at = {s: m53_scf(**dict(MARINE, throw=(310 - s * 300) * MM)) for s in (-0.4, -0.8, -1.2)}
    assert float(at[-0.8].alpha_b) == pytest.approx(float(at[-1.2].alpha_b), rel=1e-12)
    assert float(at[-0.8].alpha_t) == pytest.approx(float(at[-1.2].alpha_t), rel=1e-12)
    assert float(at[-0.8].alpha_t) != pytest.approx(float(at[-0.4].alpha_t), rel=1e-3)
    assert bool(at[-0.8].flags["s_clipped"]) and not bool(at[-0.4].flags["s_clipped"])
    assert bool(at[-0.8].flags["journal_s_extrapolated"])
    assert float(at[-1.2].beta_q) > 0
    assert bool(at[-1.2].in_range) is False


def test_recess_factor_and_its_clipping():
    # f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s); marine throw s = 0.2, T_H = T_G = 3 mm:
    # t = 0.01 each -> 1 + 0.02 * 2.44 = 1.0488 multiplies alpha_B, beta_B, beta_Q only.
    base = m53_scf(**MARINE)
    rec = m53_scf(**MARINE, pin_recess=3 * MM, journal_recess=3 * MM)
    for name in ("alpha_b", "beta_b", "beta_q"):
        assert float(getattr(rec, name)) / float(getattr(base, name)) == pytest.approx(1.0488)
    assert float(rec.alpha_t) == float(base.alpha_t)
    # s = -0.7: 1.8 + 3.2 s = -0.44 < 0 -> f(recess) < 1 -> set to 1 (M53 §3.1), flagged
    neg = dict(MARINE, throw=(310 + 0.7 * 300) * MM)
    k0 = m53_scf(**neg)
    k1 = m53_scf(**neg, pin_recess=3 * MM, journal_recess=3 * MM)
    assert float(k1.alpha_b) == pytest.approx(float(k0.alpha_b), rel=1e-12)
    assert bool(k1.flags["recess_clipped"]) and not bool(k0.flags["recess_clipped"])


def test_reduced_web_thickness_without_overlap():
    # M53 §3.1: no overlap (S <= 0) -> w = W_red/D, W_red = W - (T_H - R_H) if T_H > R_H.
    # D 300, D_G 320, E 330 -> S = -20 mm; W 100, T_H 25, R_H 15 -> W_red 90 -> w = 0.3
    k = m53_scf(**dict(MARINE, throw=330 * MM), pin_recess=25 * MM)
    assert float(k.ratios.w) == pytest.approx(0.3)
    k2 = m53_scf(**dict(MARINE, throw=240 * MM), pin_recess=25 * MM)  # S = +70 mm, overlap
    assert float(k2.ratios.w) == pytest.approx(100 / 300)


@pytest.mark.parametrize(
    ("override", "match"),
    [
        (dict(pin_diameter=-0.048), "pin_diameter"),
        (dict(pin_fillet_radius=0.0), "pin_fillet_radius"),
        (dict(pin_bore=0.05), "pin_bore"),
        (dict(journal_bore=0.06), "journal_bore"),
        (dict(oil_hole_diameter=0.05), "oil_hole_diameter"),
        (dict(web_width=float("nan")), "web_width"),
    ],
)
def test_invalid_geometry_raises(override, match):
    with pytest.raises(ValueError, match=match):
        m53_scf(**dict(SEED, **override))
