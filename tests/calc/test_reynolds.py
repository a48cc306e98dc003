"""Tests for checker.calc.reynolds, the finite-length Reynolds LCP solver (each test names its
oracle and the tolerance it supports)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import mobility as mb
from checker.calc import reynolds as ry
from tests.calc.butenschoen_tables import (  # Butenschoen (1976) tables
    B_OVER_D,
    BETA_ROT_T,
    EPS_ROT,
    EPS_SQ,
    Q_ROT_T,
    Q_SQ_T,
    SO_ROT_T,
    SO_SQ_T,
)

# squeeze-table entries that the solver shows to be typing errors (every other entry of both
# tables agrees within 1 %); (row of EPS_SQ, column of B_OVER_D): table value, solver value
SQ_TYPOS = {
    (15, 1): (0.9814, 0.931),  # B/D 1/2, eps 0.1: probably 0.9314
    (22, 2): (15.94, 19.94),  # B/D 1/2.5, eps 0.8: probably 19.94 (breaks the B/D order)
    (25, 2): (492.49, 483.1),  # B/D 1/2.5, eps 0.96: probably 482.49
    (28, 6): (2331.0, 3339.0),  # B/D 1/6, eps 0.99: probably 3331 (breaks the B/D order)
    (4, 7): (0.0085, 0.00885),  # B/D 1/8, eps -0.95: probably 0.0088 (breaks the eps order)
}


def rounding(table: np.ndarray) -> np.ndarray:
    """Half a unit in the last printed digit of the 4-decimal tables (B/D 1/8 at small eps:
    0.0025 is +-2 %)."""
    return np.where(table < 10.0, 0.5e-4, 0.0)


@pytest.fixture(scope="module")
def rotation():
    """Solver Sommerfeld number, attitude angle and side flow on Butenschoen's rotation grid,
    with his set-up (ambient pressure along the thickest film, where the oil is supplied)."""
    so = np.empty(SO_ROT_T.shape)
    beta = np.empty(SO_ROT_T.shape)
    q = np.empty(SO_ROT_T.shape)
    for j, x in enumerate(B_OVER_D):
        for i, e in enumerate(EPS_ROT):
            s = ry.solve_film(e, -np.pi / 2, x, supply_angle=np.pi)
            w = np.hypot(s.w_r, s.w_t)
            so[i, j] = e * w / (8 * x)
            beta[i, j] = np.arctan2(-s.w_t, s.w_r)
            q[i, j] = s.q_side * e / 2  # Qbar = Q/(c R^2 |v|), |v| = eps omega / 2
    return so, beta, q


@pytest.fixture(scope="module")
def squeeze():
    so = np.empty(SO_SQ_T.shape)
    q = np.empty(SO_SQ_T.shape)
    for j, x in enumerate(B_OVER_D):
        for i, e in enumerate(EPS_SQ):
            s = ry.solve_film(abs(e), 0.0 if e >= 0 else np.pi, x)
            so[i, j] = np.hypot(s.w_r, s.w_t) / (4 * x)
            q[i, j] = s.q_side
    return so, q


# ------------------------------------------------------------------------------------------
# Butenschoen's tables
# ------------------------------------------------------------------------------------------
def test_rotation_sommerfeld_and_attitude_match_butenschoen(rotation):
    # whole table: So within 1 % (+ half a unit of the last printed digit), beta within 1 %
    # (measured: So 0.57 %, beta 0.83 % = 0.10 deg)
    so, beta, _ = rotation
    assert np.all(np.abs(so - SO_ROT_T) <= 0.01 * SO_ROT_T + rounding(SO_ROT_T))
    assert np.max(np.abs(beta / BETA_ROT_T - 1)) < 0.01


def test_rotation_side_flow_matches_butenschoen(rotation):
    # Q = Q_side / (R^3 psi omega) within 1 % everywhere (measured 0.5 %)
    _, _, q = rotation
    assert np.max(np.abs(q / Q_ROT_T - 1)) < 0.01


def test_squeeze_sommerfeld_matches_butenschoen_and_finds_the_typing_errors(squeeze):
    # every entry within 1 % except five, which differ by 2..43 %: those are typing errors
    # (each one digit off; three also break the monotone order of the table)
    so, _ = squeeze
    rel = so / SO_SQ_T - 1
    tol = 0.01 + rounding(SO_SQ_T) / SO_SQ_T
    off = {(int(i), int(j)) for i, j in np.argwhere(np.abs(rel) > tol)}
    assert off == set(SQ_TYPOS)
    for (i, j), (table, solver) in SQ_TYPOS.items():
        assert SO_SQ_T[i, j] == table
        assert so[i, j] == pytest.approx(solver, rel=0.005)
        assert abs(rel[i, j]) > 0.015


def test_squeeze_side_flow_matches_butenschoen(squeeze):
    # within 1 % for B/D <= 1/2 (measured 0.86 %); B/D = 1 differs by up to 2.1 % at eps >= 0.6
    _, q = squeeze
    rel = np.abs(q / Q_SQ_T - 1)
    assert rel[:, 1:].max() < 0.01
    assert rel[:, 0].max() < 0.025


def test_free_cavitation_condition_differs_from_the_supplied_set_up_only_for_wide_bearings():
    # the map uses the free Swift-Stieber condition all round (no supply position in the
    # mobility method); Butenschoen's supply along the thickest film matters only for wide,
    # lightly loaded bearings (notes: up to 4 deg at B/D = 1, < 0.02 deg at eps >= 0.9)
    _, b_free = ry.sommerfeld_rotation(0.1, 1.0)
    _, b_sup = ry.sommerfeld_rotation(0.1, 1.0, supply_at_max_gap=True)
    assert abs(np.degrees(b_sup - b_free)) > 3.0  # measured 4.4 deg
    _, b_free = ry.sommerfeld_rotation(0.95, 1 / 3)
    _, b_sup = ry.sommerfeld_rotation(0.95, 1 / 3, supply_at_max_gap=True)
    assert abs(np.degrees(b_sup - b_free)) < 0.02


# ------------------------------------------------------------------------------------------
# short-bearing limit (Ocvirk) and closed forms
# ------------------------------------------------------------------------------------------
def ocvirk_sommerfeld(eps, l_over_d):
    """Ocvirk (1952, NACA TN 2808): S = F psi^2 / (mu L D omega)."""
    return l_over_d**2 * eps * np.sqrt(np.pi**2 * (1 - eps**2) + 16 * eps**2) / (
        2 * (1 - eps**2) ** 2)


def ocvirk_attitude(eps):
    return np.arctan2(np.pi * np.sqrt(1 - eps**2), 4 * eps)


@pytest.mark.parametrize("eps", [0.3, 0.6, 0.8])
def test_ocvirk_limit_at_small_width_ratio(eps):
    # finite-length So -> Ocvirk's as L/D -> 0 with an error ~ (L/D)^2: within 0.4 % at
    # L/D = 1/32 (measured 0.35 % at eps 0.8), at least 2.5 times smaller than at L/D = 1/16;
    # attitude within 0.02 deg
    e16 = abs(ry.sommerfeld_rotation(eps, 1 / 16)[0] / ocvirk_sommerfeld(eps, 1 / 16) - 1)
    so, beta = ry.sommerfeld_rotation(eps, 1 / 32)
    e32 = abs(so / ocvirk_sommerfeld(eps, 1 / 32) - 1)
    assert e32 < 0.004
    assert e16 > 2.5 * e32
    assert abs(np.degrees(beta - ocvirk_attitude(eps))) < 0.02


def test_ocvirk_steady_case():
    # the steady case of the notes (bearings.md 1.4, steady check): the load for which Ocvirk
    # gives eps = 0.78605; at L/D = 1/64 the finite-length film carries it at the same
    # eccentricity within 2e-4 (the short-bearing limit; measured 3.3e-4 at 1/32), at
    # L/D = 1/3 at a larger one (a thinner film: short-bearing theory is optimistic)
    from scipy.optimize import brentq

    eps_ocv = 0.78605

    def eps_for(l_over_d):
        target = ocvirk_sommerfeld(eps_ocv, l_over_d)
        return brentq(lambda e: ry.sommerfeld_rotation(e, l_over_d)[0] - target, 0.5, 0.95,
                      xtol=1e-7)

    assert eps_for(1 / 64) == pytest.approx(eps_ocv, abs=2e-4)
    assert eps_for(1 / 3) > eps_ocv + 0.02


def test_side_flow_short_bearing_limits():
    # short bearing (L/D -> 0): squeeze Qbar = 4 L/D at any eps (the squeezed volume leaves by
    # the edges), rotation Q = 2 eps L/D (Couette inflow difference); within 0.2 % at 1/32
    x = 1 / 32
    for e in (0.0, 0.5, 0.9):
        assert ry.solve_film(e, 0.0, x).q_side == pytest.approx(4 * x, rel=0.002)
    for e in (0.5, 0.9):
        q = ry.solve_film(e, -np.pi / 2, x).q_side * e / 2
        assert q == pytest.approx(2 * e * x, rel=0.002)


@pytest.mark.parametrize("eps", [0.4, 0.8])
def test_peak_pressure_short_bearing_limit(eps):
    # Ocvirk's peak pressure (checker.calc.mobility.short_bearing_peak_pressure, itself tested
    # against Ocvirk's closed form) within 1 % at L/D = 1/32, steady rotation
    d, c, mu, w = 0.05, 25e-6, 0.01, 300.0
    length = d / 32
    vs = eps * w / 2  # |V_s| / c, tangential
    p_ref, _ = mb.short_bearing_peak_pressure(eps, 0.0, 0.0, -vs, length, c, mu)
    st = ry.film_force(eps, 0.0, 0.0, -vs, d, length, c, mu)
    assert float(st.p_max) == pytest.approx(float(p_ref), rel=0.01)


def test_mobility_tends_to_exact_short_bearing():
    # direct finite-length mobility -> exact short-bearing mobility (root found, 1e-12) as
    # L/D -> 0, error ~ (L/D)^2 (measured 3.3 % -> 0.8 % at eps 0.92 from 1/16 to 1/32)
    w = 0.9 - 0.2j
    errs = []
    for x in (1 / 16, 1 / 32):
        m = complex(*(float(v) for v in ry.mobility_reynolds(w.real, w.imag, x)))
        ref = complex(*(float(v) for v in mb.mobility_exact(w.real, w.imag, x)))
        errs.append(abs(m / ref - 1))
    assert errs[1] < 0.012
    assert errs[0] > 3.0 * errs[1]


def test_full_groove_is_two_lands():
    # a full circumferential zero-pressure groove of half width g splits the film into two
    # lands of width (L/D - g) / 2 each: identity of the Reynolds problem, within the
    # discretisation (0.3 %)
    x, g = 0.4, 0.08
    for e, a in ((0.6, -np.pi / 2), (0.9, 0.0)):
        s = ry.solve_film(e, a, x, groove=(0.0, 2 * np.pi, g))
        s1 = ry.solve_film(e, a, (x - g) / 2)
        assert complex(s.w_r, s.w_t) == pytest.approx(2 * complex(s1.w_r, s1.w_t), rel=0.005)
        # and the groove nodes carry no pressure
        on_groove = s.zeta[:-1] <= g + 1e-12
        assert np.all(s.pressure[:, :-1][:, on_groove] == 0.0)


def test_partial_groove_reduces_the_load_where_it_sits():
    # a half-circumference groove on the loaded side costs load; on the unloaded side nothing
    e, a, x, g = 0.9, 0.0, 0.4, 0.07
    full = ry.solve_film(e, a, x).w_r
    loaded = ry.solve_film(e, a, x, groove=(-np.pi / 2, np.pi / 2, g)).w_r
    unloaded = ry.solve_film(e, a, x, groove=(np.pi / 2 + 0.3, 3 * np.pi / 2 - 0.3, g)).w_r
    assert loaded < 0.7 * full
    assert unloaded == pytest.approx(full, rel=1e-3)


# ------------------------------------------------------------------------------------------
# friction and losses
# ------------------------------------------------------------------------------------------
def test_petroff_at_zero_eccentricity():
    # T = 2 pi mu R^3 L (omega_J - omega_B) / c, power T (omega_J - omega_B) (Petroff)
    d, ln, c, mu, wj, wb = 0.06, 0.02, 30e-6, 0.008, 400.0, -50.0
    t, p = ry.film_losses(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, wj, wb, d, ln, c, mu)
    ref = 2 * np.pi * mu * (d / 2) ** 3 * ln * (wj - wb) / c
    assert float(t) == pytest.approx(-ref, rel=1e-12)
    assert float(p) == pytest.approx(ref * (wj - wb), rel=1e-12)


@pytest.mark.parametrize("eps", [0.5, 0.9])
def test_friction_pressure_term_equals_integral_over_the_film(eps):
    # the pressure-flow shear int (h/2) dp/dx dA on the journal, integrated numerically over
    # the solver's pressure field, equals the closed form (c eps / 2) F_t used by film_losses
    # (integration by parts); within 1 % (discretisation)
    d, c, mu, w = 0.05, 25e-6, 0.01, 300.0
    x = 1 / 3
    ln = x * d
    r = d / 2
    vs = eps * w / 2
    s = ry.solve_film(eps, -np.pi / 2, x, grid=ry.FINE_GRID)
    scale = mu * vs / (c / r) ** 2
    th = s.theta
    p = s.pressure * scale
    dpdth = (np.roll(p, -1, axis=0) - np.roll(p, 1, axis=0)) / (
        (np.roll(th, -1) - np.roll(th, 1)) % (2 * np.pi))[:, None]
    h = c * (1 - eps * np.cos(th))[:, None]
    integrand = h / 2 * dpdth / r  # (h/2) dp/dx
    dth = 0.5 * ((np.roll(th, -1) - np.roll(th, 1)) % (2 * np.pi))
    z = s.zeta * r
    inner = np.trapezoid(integrand, z, axis=1) * 2  # both halves
    t_num = -r * np.sum(inner * dth) * r  # torque of -(h/2) dp/dx over R dtheta dz
    f = ry.film_force(eps, 0.0, 0.0, -vs, d, ln, c, mu, grid=ry.FINE_GRID)
    t_closed = 0.5 * c * (eps * float(f.force_y))
    assert t_num == pytest.approx(t_closed, rel=0.01)


def test_butenschoen_friction_coefficient_form():
    # mu_f / psi = pi / (sqrt(1 - eps^2) So) + eps sin(beta) / 2 for steady rotation
    # (Butenschoen's relation, as in the mboct-mbdyn-pkg test): film_losses with the solver's
    # force reproduces it (identity check of signs and scales)
    eps, x = 0.8, 1 / 3
    d, c, mu, w = 0.05, 25e-6, 0.01, 300.0
    ln, r = x * d, d / 2
    so, beta = ry.sommerfeld_rotation(eps, x)
    f = ry.film_force(eps, 0.0, 0.0, -eps * w / 2, d, ln, c, mu)
    t, _ = ry.film_losses(eps, 0.0, f.force_x, f.force_y, 0.0, -eps * w / 2, w, 0.0, d, ln,
                          c, mu)
    fabs = np.hypot(f.force_x, f.force_y)
    mu_f = abs(float(t)) / (float(fabs) * r)
    psi = c / r
    assert mu_f / psi == pytest.approx(np.pi / (np.sqrt(1 - eps**2) * so)
                                       + eps * np.sin(beta) / 2, rel=1e-9)


# ------------------------------------------------------------------------------------------
# numerics
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("eps,alpha_deg", [(0.9, -90.0), (0.99, 0.0), (0.9999, -90.0)])
def test_grid_convergence(eps, alpha_deg):
    # loaded states (rotation, approach): second order, halving the grid spacing divides the
    # change by about 4 (>= 2.8 here); the default grid is within 0.2 % of the Richardson
    # extrapolate (measured 0.03-0.17 %)
    a = np.radians(alpha_deg)
    w = [complex(s.w_r, s.w_t) for s in (ry.solve_film(eps, a, 1 / 3, grid=g) for g in
                                         (ry.Grid(72, 12), ry.DEFAULT_GRID, ry.FINE_GRID))]
    order = abs(w[0] - w[1]) / abs(w[1] - w[2])
    assert order > 2.8
    extrap = w[2] + (w[2] - w[1]) / 3
    assert abs(w[1] / extrap - 1) < 0.002


def test_grid_convergence_receding_near_the_wall():
    # receding states near the wall converge more slowly (the free boundary crosses the
    # clustered nodes): default grid within 1 % of the 2x finer one (measured 0.6 % at
    # eps = 0.999, 150 deg; against a 4x finer grid 0.7 %)
    w = [complex(s.w_r, s.w_t) for s in (ry.solve_film(0.999, np.radians(150.0), 1 / 3, grid=g)
                                         for g in (ry.DEFAULT_GRID, ry.FINE_GRID))]
    assert abs(w[0] / w[1] - 1) < 0.01


def test_lcp_solution_is_complementary():
    # P >= 0; A P = f where P > 0; A P - f >= 0 where P = 0 (to rounding)
    s = ry._system_cached(0.95, 0.35, ry.DEFAULT_GRID, None, None)
    f = ry._source(s, np.radians(120.0))
    p, active, _ = ry._solve_lcp(s, f, None)
    lam = s.apply(p) - f
    scale = np.abs(f).max()
    assert p.min() >= 0.0 and np.any(active) and np.any(~active)
    assert np.abs(lam[~active]).max() < 1e-10 * scale
    assert lam[active].min() > -1e-10 * scale


def test_mirror_symmetry_and_homogeneity():
    # reflecting the squeeze direction mirrors the load: W(eps, -alpha) = conj W(eps, alpha)
    a = ry.solve_film(0.7, 0.8, 0.3)
    b = ry.solve_film(0.7, -0.8, 0.3)
    assert complex(a.w_r, a.w_t) == pytest.approx(complex(b.w_r, -b.w_t), rel=1e-9)
    # SI: the force is linear in the squeeze speed (positive homogeneity of the LCP)
    f1 = ry.film_force(0.6, 0.1, 3.0, -20.0, 0.05, 0.016, 25e-6, 0.01)
    f2 = ry.film_force(0.6, 0.1, 6.0, -40.0, 0.05, 0.016, 25e-6, 0.01)
    assert float(f2.force_x) == pytest.approx(2 * float(f1.force_x), rel=1e-9)
    assert float(f2.side_flow) == pytest.approx(2 * float(f1.side_flow), rel=1e-9)


def test_validation():
    with pytest.raises(ValueError, match="eccentricity"):
        ry.solve_film(1.0, 0.0, 0.3)
    with pytest.raises(ValueError, match="L/D"):
        ry.solve_film(0.5, 0.0, 3.0)
    with pytest.raises(ValueError, match="alpha"):
        ry.solve_film(0.5, np.nan, 0.3)
    with pytest.raises(ValueError, match="groove"):
        ry.solve_film(0.5, 0.0, 0.3, groove=(0.0, 1.0, 0.4))
    with pytest.raises(ValueError, match="diameter"):
        ry.film_force(0.5, 0.0, 1.0, 0.0, -0.05, 0.01, 20e-6, 0.01)
    with pytest.raises(ValueError, match="eccentricity"):
        ry.film_losses(0.8, 0.7, 0, 0, 0, 0, 1, 0, 0.05, 0.01, 20e-6, 0.01)
