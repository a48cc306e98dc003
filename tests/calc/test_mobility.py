"""Tests for checker.calc.mobility (each test names its oracle and the tolerance it supports)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import mobility as mb
from tests.calc.butenschoen_tables import (  # Butenschoen (1976) tables
    B_OVER_D,
    BETA_ROT_T,
    EPS_ROT,
    EPS_SQ,
    SO_ROT_T,
    SO_SQ_T,
)

# squeeze-table entries that break the monotonic trend of their row/column (typing errors in the
# source): B/D = 1/2.5 at eps = 0.8 (15.94 < 15.282 of B/D = 1/3), B/D = 1/6 at eps = 0.99
# (2331 < 2560.1 of B/D = 1/8), B/D = 1/2 at eps = 0.1 (0.9814, off the row trend by 7 %)
SQ_TYPOS = {(22, 2), (28, 6), (15, 1)}


# ------------------------------------------------------------------------------------------
# independent oracles
# ------------------------------------------------------------------------------------------
def ocvirk_sommerfeld(eps, l_over_d):
    """Ocvirk (1952, NACA TN 2808) short bearing: S = F psi^2 / (mu L D omega)."""
    return l_over_d**2 * eps * np.sqrt(np.pi**2 * (1 - eps**2) + 16 * eps**2) / (
        2 * (1 - eps**2) ** 2
    )


def ocvirk_attitude(eps):
    """Ocvirk attitude angle: tan(phi) = pi sqrt(1 - eps^2) / (4 eps)."""
    return np.arctan2(np.pi * np.sqrt(1 - eps**2), 4 * eps)


def brute_force_g(eps, alpha, n=400001):
    """Trapezoidal quadrature of the pi-film load integral G(eps, alpha) (notes 1.4)."""
    th = np.linspace(alpha - np.pi / 2, alpha + np.pi / 2, n)
    w = np.cos(th - alpha) / (1 - eps * np.cos(th)) ** 3
    return np.trapezoid(w * np.cos(th), th), np.trapezoid(w * np.sin(th), th)


# ------------------------------------------------------------------------------------------
# exact short-bearing mobility
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("eps", [0.0, 0.3, 0.8, 0.95])
@pytest.mark.parametrize("alpha", [-2.5, -1.0, 0.0, 0.7, 2.0, 3.1])
def test_load_integral_against_brute_force_quadrature(eps, alpha):
    # oracle: trapezoid rule with 4e5 intervals; its error < 1e-7 relative here
    g_r, g_t = mb.squeeze_load_integral(eps, alpha)
    bx, by = brute_force_g(eps, alpha)
    scale = np.hypot(bx, by)
    assert abs(g_r - bx) < 1e-7 * scale
    assert abs(g_t - by) < 1e-7 * scale


@pytest.mark.parametrize("eps", [-0.9, -0.3, 0.0, 0.4, 0.9, 0.99])
def test_pure_approach_equals_closed_form_g_rad(eps):
    # notes 1.4: G(eps, 0) = G_rad(eps); negative eps = receding (alpha = pi); rounding only
    if eps >= 0:
        g_r, g_t = mb.squeeze_load_integral(eps, 0.0)
    else:
        g_r, g_t = mb.squeeze_load_integral(-eps, np.pi)
        g_r = -g_r
    assert g_r == pytest.approx(mb.squeeze_load_radial(eps), rel=1e-11)
    assert abs(g_t) < 1e-11 * abs(g_r)


@pytest.mark.parametrize("eps", [0.05, 0.3, 0.6, 0.786, 0.9, 0.99, 0.999])
def test_exact_mobility_reproduces_ocvirk_steady_state(eps):
    # Ocvirk: journal rotating at omega, fixed bearing (omega_bar = omega/2), load S(eps) at
    # attitude phi: the eccentricity must not move. Exact short-bearing theory -> rounding only.
    d, length, c, mu, w = 0.05, 0.016, 25e-6, 0.005, 400.0
    load = ocvirk_sommerfeld(eps, length / d) * mu * length * d * w / (2 * c / d) ** 2
    ang = -np.pi / 2 + ocvirk_attitude(eps)  # load along -y, e leads by phi
    rx, ry = mb.eccentricity_rate(0.0, -load, eps * np.cos(ang), eps * np.sin(ang), w, 0.0,
                                  d, length, c, mu, model="exact")
    assert np.hypot(rx, ry) < 1e-10 * (w / 2 * eps)


def test_exact_equals_closed_form_at_centre():
    # Booker's closed form is exact at eps = 0 (notes 1.4): M = (D/L)^2 / pi along the load
    mz, mk = mb.mobility_exact(0.0, 0.0, 0.4)
    assert mz == pytest.approx(1 / (np.pi * 0.16), rel=1e-12)
    assert abs(mk) < 1e-14


def test_closed_form_vs_exact_bound():
    # documented bound (mobility_closed_form Notes; notes 1.4 found M ratios 0.94..1.13 on
    # eps <= 0.99): |M_exact| / |M_closed| in [0.942, 1.132], direction within 4.5 deg
    eps = np.concatenate([np.linspace(0.0, 0.99, 34), [0.995, 0.999]])
    psi = np.linspace(-np.pi, np.pi, 73)
    e, p = np.meshgrid(eps, psi, indexing="ij")
    z, k = e * np.cos(p), e * np.sin(p)
    ez, ek = mb.mobility_exact(z, k, 0.3)
    cz, ck = mb.mobility_closed_form(z, k, 0.3)
    r = (ez + 1j * ek) / (cz + 1j * ck)
    assert 0.942 <= np.abs(r).min() and np.abs(r).max() <= 1.132
    assert np.degrees(np.abs(np.angle(r))).max() <= 4.5
    # the along-load component alone: notes quote 0.94..1.13 (eps <= 0.99)
    sel = e <= 0.99
    ratio_z = ez[sel] / cz[sel]
    assert 0.94 <= ratio_z.min() and ratio_z.max() <= 1.135


def test_exact_table_interpolation_error():
    # documented interpolation bound EXACT_TABLE_MAX_REL_ERROR vs the root-finding "exact"
    rng = np.random.default_rng(12)
    n = 3000
    eps = 1 - 10 ** rng.uniform(-7, 0, n)
    psi = rng.uniform(-np.pi, np.pi, n)
    z, k = eps * np.cos(psi), eps * np.sin(psi)
    tz, tk = mb.mobility_exact_table(z, k, 0.35)
    ez, ek = mb.mobility_exact(z, k, 0.35)
    err = np.abs((tz + 1j * tk) / (ez + 1j * ek) - 1)
    assert err.max() <= mb.EXACT_TABLE_MAX_REL_ERROR


def test_closed_form_formula():
    # Booker / Flores et al. 2006 closed form, evaluated by hand at one point
    mz, mk = mb.mobility_closed_form(0.5, -0.3, 0.25)
    assert mz == pytest.approx(0.5**2.5 / (np.pi * 0.0625), rel=1e-14)
    assert mk == pytest.approx(4 * 0.3 * 0.5**1.5 / (np.pi**2 * 0.0625), rel=1e-14)


# ------------------------------------------------------------------------------------------
# Butenschoen fits against Butenschoen's tables
# ------------------------------------------------------------------------------------------
def test_butenschoen_rotation_sommerfeld_against_table():
    # fit error at the tabulated points: -3.3 % .. +6.8 % (computed here); tolerance 7 %
    e, x = np.meshgrid(EPS_ROT, B_OVER_D, indexing="ij")
    rel = mb.butenschoen_sommerfeld_rotation(e, x) / SO_ROT_T - 1
    assert np.abs(rel).max() < 0.07
    # sample values quoted in the notes: B/D = 1/3, eps 0.5 -> 0.1522; eps 0.9 -> 3.2201
    assert mb.butenschoen_sommerfeld_rotation(0.5, 1 / 3) == pytest.approx(0.1522, rel=0.03)
    assert mb.butenschoen_sommerfeld_rotation(0.9, 1 / 3) == pytest.approx(3.2201, rel=0.05)


def test_butenschoen_attitude_against_table():
    # fit error at the tabulated points within 2.4 deg (computed here); tolerance 2.5 deg
    e, x = np.meshgrid(EPS_ROT, B_OVER_D, indexing="ij")
    err = np.degrees(mb.butenschoen_attitude_angle(e, x) - BETA_ROT_T)
    assert np.abs(err).max() < 2.5


def test_butenschoen_squeeze_sommerfeld_against_table():
    # fit error within 5.5 % except three entries that are typing errors in the source table
    e, x = np.meshgrid(EPS_SQ, B_OVER_D, indexing="ij")
    rel = mb.butenschoen_sommerfeld_squeeze(e, x) / SO_SQ_T - 1
    mask = np.ones(rel.shape, dtype=bool)
    for i, j in SQ_TYPOS:
        mask[i, j] = False
    assert np.abs(rel[mask]).max() < 0.055
    assert all(abs(rel[i, j]) > 0.06 for i, j in SQ_TYPOS)  # they really are outliers


def test_butenschoen_short_limit_of_squeeze_bracket():
    # notes 1.4/1.5: So_V without the fit factor = 2 (B/D)^2 G_rad
    e = np.linspace(-0.95, 0.95, 11)
    x = 0.3
    a = mb._butenschoen_coefficients(np.asarray(x))
    fit_factor = a[7] * (1 - e) / (-a[8] - e)
    so_v = mb.butenschoen_sommerfeld_squeeze(e, x) / fit_factor
    assert np.allclose(so_v, 2 * x**2 * mb.squeeze_load_radial(e), rtol=1e-12)


@pytest.mark.parametrize("i_eps", [1, 4, 8, 10, 13])
@pytest.mark.parametrize("j_bd", [0, 3, 7])
def test_butenschoen_mobility_steady_rotation_is_fit_equilibrium(i_eps, j_bd):
    # the mobility inversion (notes 1.5) must have Butenschoen's rotation solution as its
    # steady state: load So_D(eps) at attitude beta(eps), omega_J = omega, omega_B = 0 ->
    # no motion (rounding). The table comparison of the resulting h_min is in test_orbit.
    eps, x = EPS_ROT[i_eps], B_OVER_D[j_bd]
    d, c, mu, w = 0.05, 25e-6, 0.005, 300.0
    length = x * d
    so = mb.butenschoen_sommerfeld_rotation(eps, x)
    beta = mb.butenschoen_attitude_angle(eps, x)
    load = so * mu * length * d * w / (2 * c / d) ** 2
    ang = -np.pi / 2 + beta
    rx, ry = mb.eccentricity_rate(0.0, -load, eps * np.cos(ang), eps * np.sin(ang), w, 0.0,
                                  d, length, c, mu, model="butenschoen")
    assert np.hypot(rx, ry) < 1e-9 * (w / 2 * eps)


@pytest.mark.parametrize("i_eps", [3, 9, 14, 19, 23, 26])
def test_butenschoen_mobility_pure_squeeze_matches_table(i_eps):
    # pure squeeze (omega_bar = 0, load along e): eps_dot = F psi^2 / (So_V eta B D);
    # So_V from the squeeze table within the fit tolerance (5.5 %)
    eps, x = EPS_SQ[i_eps], B_OVER_D[3]
    d, c, mu = 0.05, 25e-6, 0.005
    length = x * d
    load = 1000.0 * np.sign(eps) if eps != 0 else 1000.0
    e_abs = abs(eps)
    rx, ry = mb.eccentricity_rate(load, 0.0, e_abs, 0.0, 0.0, 0.0, d, length, c, mu,
                                  model="butenschoen")
    so_v = abs(load) * (2 * c / d) ** 2 / (abs(rx) * mu * length * d)
    assert abs(ry) < 1e-12 * abs(rx)
    assert so_v == pytest.approx(SO_SQ_T[i_eps, 3], rel=0.055)


# ------------------------------------------------------------------------------------------
# Butenschoen and squeeze kernels near the wall (eps -> 1): finite, continuous, monotone
# ------------------------------------------------------------------------------------------
WALL = 1.0 - np.logspace(-1, -15, 57)  # 1 - eps from 0.1 down to 1e-15, 4 points a decade


def test_squeeze_bracket_without_cancellation():
    # g(phi) = phi/2 (1 + 2 cos^2 phi) - 3/2 cos(phi) sin(phi) with es = -cos(phi). Oracles:
    # (a) the direct formula where it does not cancel (phi >= 0.5: terms within a factor 30 of
    # g, rounding < 1e-14), tolerance 1e-13; (b) the two-term expansion derived by hand from
    # the sine and cosine series, g = 2/15 phi^5 - 8/315 phi^7 + O(phi^9), for phi <= 1e-3
    # (neglected term < 1e-12 relative), tolerance 1e-12.
    phi = np.linspace(0.5, 3.1, 200)
    direct = 0.5 * phi * (1 + 2 * np.cos(phi) ** 2) - 1.5 * np.cos(phi) * np.sin(phi)
    assert np.allclose(mb._bracket_of_angle(phi), direct, rtol=1e-13, atol=0)
    phi = np.logspace(-7, -3, 30)
    assert np.allclose(mb._bracket_of_angle(phi),
                       2 / 15 * phi**5 - 8 / 315 * phi**7, rtol=1e-12, atol=0)
    # g' = 2 sin(phi) (sin(phi) - phi cos(phi)) > 0 on (0, pi): increasing in es everywhere
    es = np.concatenate([-WALL[::-1], np.linspace(-0.89, 0.89, 179), WALL])
    g = mb._squeeze_bracket(es)
    assert np.all(np.isfinite(g)) and np.all(g > 0) and np.all(np.diff(g) > 0)


@pytest.mark.parametrize("x", [0.125, 1 / 3, 1.0])
def test_butenschoen_squeeze_finite_and_monotone_up_to_the_wall(x):
    # So_V(es) grows monotonically from recession (es -> -1) to approach (es -> +1) and stays
    # finite. Receding limit by hand: (1 - es^2)^(5/2) -> phi^5 and the bracket -> 2/15 phi^5,
    # so So_V(-1) = 16 x^2 a8 / (15 (1 - a9)); tolerance 1e-9 at 1 - |es| = 1e-15.
    # Before the fix the bracket cancelled: NaN, 0 or the wrong sign beyond 1 - |es| ~ 1e-8.
    es = np.concatenate([-WALL[::-1], np.linspace(-0.89, 0.89, 179), WALL])
    so = mb.butenschoen_sommerfeld_squeeze(es, x)
    assert np.all(np.isfinite(so)) and np.all(so > 0) and np.all(np.diff(so) > 0)
    a = mb._butenschoen_coefficients(np.asarray(x))
    assert so[0] == pytest.approx(16 * x**2 * a[7] / (15 * (1 - a[8])), rel=1e-9)
    # the shared inverse pair of the mobility agrees with 1/So_V on both branches
    inv_p, inv_m = mb._bt_inv_so_sq_pair(WALL, np.full(WALL.shape, x), a[:, None])
    assert np.allclose(inv_p * mb.butenschoen_sommerfeld_squeeze(WALL, x), 1, rtol=1e-12)
    assert np.allclose(inv_m * mb.butenschoen_sommerfeld_squeeze(-WALL, x), 1, rtol=1e-12)
    # rotation: So_D finite and increasing towards the wall
    so_d = mb.butenschoen_sommerfeld_rotation(WALL, x)
    assert np.all(np.isfinite(so_d)) and np.all(np.diff(so_d) > 0)


@pytest.mark.parametrize("angle", [0.0, 0.3, np.pi / 2, 2.5, np.pi])
def test_butenschoen_mobility_finite_and_continuous_near_the_wall(angle):
    # the orbit solver's contract: never NaN. Mobility at eccentricity angle `angle` from the
    # load, 1 - eps = 0.1 .. 1e-12 (below the orbit's clamp 1e-7 and beyond): finite, and a
    # relative step of 1e-3 in (1 - eps) changes M by less than 1 % (continuity; the largest
    # growth rate of M is (1 - eps)^(-1/2), i.e. 0.05 % per such step).
    x = 0.35
    gap = np.logspace(-1, -12, 45)
    e = 1.0 - gap
    m = np.array(mb.mobility_butenschoen(e * np.cos(angle), e * np.sin(angle), x))
    e2 = 1.0 - gap * (1 + 1e-3)
    m2 = np.array(mb.mobility_butenschoen(e2 * np.cos(angle), e2 * np.sin(angle), x))
    assert np.all(np.isfinite(m)) and np.all(np.isfinite(m2))
    mag = np.hypot(*m)
    assert np.all(np.hypot(*(m - m2)) < 1e-2 * mag)
    if angle == 0.0:  # pure approach: M = 1 / So_V(+eps) > 0, falls monotonically to 0
        assert np.all(m[0] > 0) and np.all(np.diff(m[0]) < 0) and np.allclose(m[1], 0)
    if angle == np.pi:  # load towards the centre: M = 1/So_V(-eps) grows to 1/So_V(-1)
        assert np.all(m[0] > 0) and np.all(np.diff(m[0]) >= 0)
        a = mb._butenschoen_coefficients(np.asarray(x))
        assert m[0, -1] == pytest.approx(15 * (1 - a[8]) / (16 * x**2 * a[7]), rel=1e-6)


# ------------------------------------------------------------------------------------------
# peak pressure, symmetry, validation
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("eps", [0.2, 0.6, 0.9, 0.98])
def test_peak_pressure_ocvirk(eps):
    # Ocvirk steady pressure p = 3 mu omega eps sin(t) (L^2/4 - z^2) / (c^2 (1 + eps cos t)^3),
    # maximum at cos(t) = (1 - sqrt(1 + 24 eps^2)) / (4 eps) (t from the maximum film);
    # squeeze velocity of steady rotation V_s/c = -omega_bar z x eps. Tolerance 1e-9.
    length, c, mu, w = 0.02, 30e-6, 0.006, 500.0
    ex, ey = eps * np.cos(0.4), eps * np.sin(0.4)
    vx, vy = w / 2 * ey, -w / 2 * ex
    p, ang = mb.short_bearing_peak_pressure(ex, ey, vx, vy, length, c, mu)
    ct = (1 - np.sqrt(1 + 24 * eps**2)) / (4 * eps)
    st = np.sqrt(1 - ct**2)
    p_ref = 3 * mu * w * eps * st * length**2 / 4 / (c**2 * (1 + eps * ct) ** 3)
    assert p == pytest.approx(p_ref, rel=1e-9)
    # location: t measured from the maximum film (direction -e), against the rotation
    t_loc = np.arccos(ct)
    expected = 0.4 + np.pi + t_loc
    assert np.cos(ang - expected) == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("model", mb.MOBILITY_MODELS)
def test_rate_is_frame_invariant(model):
    # rotating all vectors by an angle rotates the rate (isotropy); rounding / root-find level
    args = dict(omega_journal=300.0, omega_bearing=-40.0, diameter=0.05, length=0.017,
                clearance=25e-6, viscosity=0.005, model=model)
    f = 4000.0 * np.exp(0.3j)
    e = 0.7 * np.exp(1.1j)
    r0 = complex(*mb.eccentricity_rate(f.real, f.imag, e.real, e.imag, **args))
    rot = np.exp(0.9j)
    f2, e2 = f * rot, e * rot
    r1 = complex(*mb.eccentricity_rate(f2.real, f2.imag, e2.real, e2.imag, **args))
    assert abs(r1 - r0 * rot) < 1e-9 * abs(r0)


def test_full_groove_equals_half_bearing_with_half_load():
    # notes 1.6: full circumferential groove = two lands of L/2 each carrying F/2 (identity)
    common = dict(omega_journal=300.0, omega_bearing=0.0, diameter=0.05, clearance=25e-6,
                  viscosity=0.005)
    a = mb.eccentricity_rate(0.0, -8000.0, 0.2, -0.5, length=0.02, full_groove=True, **common)
    b = mb.eccentricity_rate(0.0, -4000.0, 0.2, -0.5, length=0.01, **common)
    assert np.allclose(a, b, rtol=1e-14, atol=0.0)


def test_validation():
    with pytest.raises(ValueError):
        mb.mobility_closed_form(0.8, 0.6, 0.3)  # eps = 1
    with pytest.raises(ValueError):
        mb.mobility_closed_form(0.1, 0.1, -0.3)
    with pytest.raises(ValueError):
        mb.mobility(0.1, 0.1, 0.3, model="long_bearing")
    with pytest.raises(ValueError):
        mb.mobility_butenschoen(0.1, 0.1, 0.1)  # B/D below 1/8
    with pytest.raises(ValueError):
        mb.eccentricity_rate(0, 1, 0, 0, 1, 0, 0.05, 0.02, -1e-6, 0.005)
    with pytest.raises(ValueError):
        mb.squeeze_load_radial(1.0)
