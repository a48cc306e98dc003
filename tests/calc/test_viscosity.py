"""Tests for checker.calc.viscosity (each test names its oracle and the tolerance it supports)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import viscosity as vs

C = 273.15


@pytest.mark.parametrize(
    ("grade", "t_c", "mu_mpas"),
    [("30", 100.0, 8.16), ("30", 150.0, 2.99), ("40", 100.0, 10.16), ("40", 150.0, 3.42),
     ("10", 100.0, 4.73), ("60", 150.0, 6.63)],
)
def test_seireg_dandage_against_notes_table(grade, t_c, mu_mpas):
    # notes bearings.md 5.2 (Celsius form of the Shigley/Seireg-Dandage reyn fits, values
    # printed to 3 significant digits -> tolerance 0.1 %)
    assert vs.seireg_dandage_viscosity(t_c + C, grade) * 1e3 == pytest.approx(mu_mpas, rel=1e-3)


def test_seireg_dandage_reyn_form_by_hand():
    # mu = mu0 exp(b / (T_F + 95)) reyn, SAE 30 at 212 F: 0.0141e-6 * exp(1360/307) reyn
    reyn = 0.0141e-6 * np.exp(1360.0 / 307.0)
    assert vs.seireg_dandage_viscosity(100.0 + C, "SAE 30") == pytest.approx(
        reyn * 6894.757293168361, rel=1e-12)


def test_three_point_vogel_round_trip():
    # exact interpolation: points generated from a known Vogel curve are fitted back (rounding)
    a, b, c = 7.0e-5, 950.0, 165.0
    t = np.array([313.15, 373.15, 423.15])
    oil = vs.fit_vogel(t, vs.vogel_viscosity(t, a, b, c))
    assert (oil.a, oil.b, oil.c) == pytest.approx((a, b, c), rel=1e-9)
    assert oil.viscosity(403.15) == pytest.approx(vs.vogel_viscosity(403.15, a, b, c), rel=1e-12)


def test_datasheet_vogel_passes_through_anchors():
    # construction: KV40 rho(40 C), KV100 rho(100 C), HTHS(150 C) are reproduced (rounding)
    oil = vs.vogel_from_datasheet(kv40=62e-6, kv100=10.5e-6, density_15=852.0, hths150=3.1e-3)
    rho = vs.oil_density(np.array([vs.T_40C, vs.T_100C]), 852.0)
    expected = [62e-6 * rho[0], 10.5e-6 * rho[1], 3.1e-3]
    got = oil.viscosity([vs.T_40C, vs.T_100C, vs.T_150C])
    assert np.allclose(got, expected, rtol=1e-12)
    assert oil.is_extrapolated([300.0, 400.0, 430.0]).tolist() == [True, False, True]


def test_walther_round_trip():
    # ASTM D341 line through two points generated from a known line reproduces a third point
    a_w, b_w = 9.0, 3.5
    t = np.array([313.15, 373.15, 423.15])
    nu = (10 ** (10 ** (a_w - b_w * np.log10(t))) - 0.7) * 1e-6
    got = vs.walther_kinematic_viscosity(t[2], t[0], nu[0], t[1], nu[1])
    assert got == pytest.approx(nu[2], rel=1e-10)


def test_datasheet_without_hths_uses_walther_at_150c():
    # third anchor = ASTM D341 extrapolation times density (construction, rounding)
    oil = vs.vogel_from_datasheet(kv40=62e-6, kv100=10.5e-6)
    nu150 = vs.walther_kinematic_viscosity(vs.T_150C, vs.T_40C, 62e-6, vs.T_100C, 10.5e-6)
    assert oil.viscosity(vs.T_150C) == pytest.approx(nu150 * vs.oil_density(vs.T_150C), rel=1e-12)
    assert "low shear" in oil.source


def test_j300_minimum_default_anchors():
    # J300 (2015) 5W-30: KV100 min 9.3 mm^2/s, HTHS min 2.9 mPa s (notes 5.1); the default curve
    # passes through KV100_min * rho(100 C) and HTHS_min (construction, rounding)
    oil = vs.vogel_from_j300("5W-30")
    rho100 = vs.oil_density(vs.T_100C)
    assert oil.viscosity(vs.T_100C) == pytest.approx(9.3e-6 * rho100, rel=1e-12)
    assert oil.viscosity(vs.T_150C) == pytest.approx(2.9e-3, rel=1e-12)
    assert oil.c == pytest.approx(vs.VOGEL_C_DEFAULT)
    assert "ASSUMPTION" in oil.source and "J300 minimum" in oil.source
    mid = vs.vogel_from_j300("5W30", basis="mid_band")
    assert mid.viscosity(vs.T_100C) == pytest.approx(10.9e-6 * rho100, rel=1e-12)


def test_j300_default_is_plausible_against_monograde_fits():
    # a 30 grade at the J300 minimum lies between the Seireg-Dandage SAE 20 and SAE 30 curves at
    # 130 C (the SD 30 curve has KV100 ~ 9.6 mm^2/s, just above the J300 minimum)
    t = 130.0 + C
    mu = vs.j300_viscosity(t, "5W-30")
    assert vs.seireg_dandage_viscosity(t, "20") < mu < vs.seireg_dandage_viscosity(t, "30")


@pytest.mark.parametrize(
    ("grade", "hths"),
    [("0W-40", 3.5e-3), ("10w40", 3.7e-3 - 0.2e-3), ("15W-40", 3.7e-3), ("40", 3.7e-3),
     ("SAE 0W-20", 2.6e-3), ("16", 2.3e-3)],
)
def test_j300_grade_parsing(grade, hths):
    # J300 (2015) HTHS minima (notes 5.1): 0W/5W/10W-40 3.5, 15W/20W/25W-40 and 40 3.7 mPa s
    assert vs.j300_grade(grade).hths150_min == pytest.approx(hths)


def test_table_interpolation_and_extrapolation_flag():
    # ln(mu) linear in T is exact for mu = A exp(-B T) (rounding); outside -> flagged
    t_tab = np.array([353.15, 373.15, 393.15, 413.15])
    mu_tab = 0.05 * np.exp(-0.02 * (t_tab - 300.0))
    t = np.array([340.0, 363.15, 400.0, 420.0])
    mu, extra = vs.table_viscosity(t, t_tab, mu_tab)
    assert np.allclose(mu, 0.05 * np.exp(-0.02 * (t - 300.0)), rtol=1e-12)
    assert extra.tolist() == [True, False, False, True]


@pytest.mark.parametrize(("spacing", "tol"), [(20.0, 0.027), (10.0, 0.0075)])
def test_table_against_vogel_oil_between_points(spacing, tol):
    # documented accuracy (table_viscosity Notes) for 60..160 C against a Vogel oil
    oil = vs.vogel_from_j300("5W-30")
    t_tab = np.arange(333.15, 434.0, spacing)
    t = t_tab[:-1] + spacing / 2
    mu, _ = vs.table_viscosity(t, t_tab, oil.viscosity(t_tab))
    assert np.allclose(mu, oil.viscosity(t), rtol=tol)


def test_validation():
    with pytest.raises(ValueError):
        vs.vogel_viscosity(-5.0, 1e-4, 900.0, 170.0)
    with pytest.raises(ValueError):
        vs.vogel_viscosity(160.0, 1e-4, 900.0, 170.0)  # T <= c
    with pytest.raises(ValueError):
        vs.j300_grade("5W-35")
    with pytest.raises(ValueError):
        vs.table_viscosity(400.0, [380.0, 370.0], [0.01, 0.008])
    with pytest.raises(ValueError):
        vs.table_viscosity(400.0, [370.0, 380.0], [0.01, -0.008])
    with pytest.raises(ValueError):
        vs.vogel_from_datasheet(kv40=10e-6, kv100=12e-6)
    with pytest.raises(ValueError):
        vs.fit_vogel([313.15, 373.15, 423.15], [0.01, 0.02, 0.005])  # not monotonic
