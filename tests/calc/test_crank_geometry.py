"""Mass properties of crank throws (checker.calc.crank_geometry) against closed forms and an
independent grid integration written here.

The grid: midpoint rule on a square grid of spacing h with a membership test of its own (the
web as the union of the discs interpolated between the journal-side and pin-side circles,
c(t) = (0, t R), r(t) = a + t (b - a), t in [0, 1], which is the convex hull of the two
circles; the counterweight by its polar description). Tolerance 0.1 % (issue 33); the grid's
own error at h = outline / 2500 is about 1e-5.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from checker.calc import crank_geometry as cg

RHO = 7850.0


def _in_web(x, y, a, b, rr):
    """Inside the union of the discs c(t) = (0, tR), r(t) = a + t (b - a), 0 <= t <= 1: the
    t minimising |p - c(t)| - r(t) has (p_y - tR)/|p - c| = (a - b)/R (convex in t)."""
    s = np.clip((a - b) / rr, -1 + 1e-15, 1 - 1e-15)
    t = np.clip((y - np.abs(x) * s / math.sqrt(1 - s * s)) / rr, 0.0, 1.0)
    return np.hypot(x, y - t * rr) <= a + t * (b - a)


def _in_cw(x, y, ri, ro, alpha):
    r = np.hypot(x, y)
    off = np.abs(np.arctan2(x, -y))  # angle from -y
    return (r >= ri) & (r <= ro) & (off <= alpha / 2)


def _grid_moments(thickness, extent, n=2500):
    """sum over a grid of t(x, y) * (1, y, x^2 + y^2) dA, in chunks of rows."""
    (x0, x1), (y0, y1) = extent
    h = max(x1 - x0, y1 - y0) / n
    xs = np.arange(x0 + h / 2, x1, h)
    ys = np.arange(y0 + h / 2, y1, h)
    out = np.zeros(3)
    for k in range(0, ys.size, 200):
        yy, xx = np.meshgrid(ys[k:k + 200], xs, indexing="ij")
        t = thickness(xx, yy)
        out += [t.sum(), (t * yy).sum(), (t * (xx**2 + yy**2)).sum()]
    return out * h * h


GEOMS = [
    # a, b, R, ri, ro, alpha [deg], tw, tc  (m); a spread of webs and counterweights
    (0.0379, 0.0379, 0.0473, 0.030, 0.066, 150, 0.0223, 0.0223),  # I4-like, equal widths
    (0.045, 0.032, 0.0473, 0.028, 0.070, 180, 0.020, 0.020),  # wider at the journal
    (0.030, 0.036, 0.050, 0.020, 0.060, 220, 0.025, 0.025),  # wider at the pin, wide cw
    (0.040, 0.030, 0.045, 0.045, 0.075, 120, 0.020, 0.030),  # cw beyond the web, thicker
    (0.050, 0.020, 0.040, 0.010, 0.065, 100, 0.024, 0.018),  # pin centre inside disc A
    (0.035, 0.030, 0.060, 0.000, 0.050, 200, 0.022, 0.022),  # solid sector from the axis
]


@pytest.mark.parametrize("a, b, rr, ri, ro, alpha, tw, tc", GEOMS)
def test_web_and_counterweight_against_grid(a, b, rr, ri, ro, alpha, tw, tc):
    al = math.radians(alpha)
    web = cg.web_outline(width_journal=2 * a, width_pin=2 * b, crank_radius=rr)
    cw = cg.annular_sector(inner_radius=ri, outer_radius=ro, angle=al)
    ov = cg.counterweight_web_overlap(inner_radius=ri, outer_radius=ro, angle=al,
                                      width_journal=2 * a, width_pin=2 * b, crank_radius=rr)
    ext = ((-max(a, b, ro), max(a, b, ro)), (-max(a, ro), rr + b))
    g_web = _grid_moments(lambda x, y: _in_web(x, y, a, b, rr).astype(float), ext)
    assert np.allclose([web.area, web.first_y, web.polar], g_web, rtol=1e-3, atol=0)

    def union(x, y):
        return np.maximum(tw * _in_web(x, y, a, b, rr), tc * _in_cw(x, y, ri, ro, al))

    g_union = _grid_moments(union, ext)
    tmin = min(tw, tc)
    ours = np.array([tw * web.area + tc * cw.area - tmin * ov.area[0],
                     tw * web.first_y + tc * cw.first_y - tmin * ov.first_y[0],
                     tw * web.polar + tc * cw.polar - tmin * ov.polar[0]])
    assert np.allclose(ours, g_union, rtol=1e-3, atol=0)
    # the counterweight's own part (union minus web) too
    g_cw = g_union - tw * g_web
    own = ours - tw * np.array([web.area, web.first_y, web.polar])
    assert np.allclose(own, g_cw, rtol=1e-3, atol=1e-12)


def test_web_closed_forms():
    # equal circles: a stadium, pi a^2 + 2 a R; J = pi a^4/2 + (sector B shifted) + rectangle
    a, rr = 0.04, 0.05
    w = cg.web_outline(width_journal=2 * a, width_pin=2 * a, crank_radius=rr)
    assert w.area == pytest.approx(math.pi * a * a + 2 * a * rr, rel=1e-14)
    # first moment: half disc B at R (+4a/3pi), rectangle at R/2, half disc A at -4a/3pi
    sy = (math.pi * a * a / 2) * (rr + 4 * a / (3 * math.pi)) + 2 * a * rr * rr / 2 \
        - (math.pi * a * a / 2) * 4 * a / (3 * math.pi)
    assert w.first_y == pytest.approx(sy, rel=1e-14)
    # one circle containing the other: a disc
    d = cg.web_outline(width_journal=0.2, width_pin=0.02, crank_radius=0.03)
    assert d.area == pytest.approx(math.pi * 0.01, rel=1e-14)
    assert d.polar == pytest.approx(math.pi * 0.1**4 / 2, rel=1e-14)


def test_overlap_is_the_annular_sector_where_the_span_lies_on_the_journal_arc():
    # journal-side arc spans pi + 2 beta about -y; a 150 deg counterweight lies within it, so
    # the common part is the annular sector ri..min(ro, a), closed form
    a, b, rr, ri, ro, al = 0.045, 0.03, 0.05, 0.02, 0.07, math.radians(150)
    ov = cg.counterweight_web_overlap(inner_radius=ri, outer_radius=ro, angle=al,
                                      width_journal=2 * a, width_pin=2 * b, crank_radius=rr)
    ref = cg.annular_sector(inner_radius=ri, outer_radius=a, angle=al)
    for k in ("area", "first_y", "polar"):
        assert getattr(ov, k)[0] == pytest.approx(float(getattr(ref, k)), rel=1e-13)


def test_overlap_quadrature_converged():
    # the Gauss-Legendre rule on the split intervals: doubling the nodes changes nothing
    kw = dict(inner_radius=0.02, outer_radius=0.06, angle=math.radians(230),
              width_journal=0.06, width_pin=0.072, crank_radius=0.05)
    ov = cg.counterweight_web_overlap(**kw)
    nodes, weights = cg._GAUSS_NODES, cg._GAUSS_WEIGHTS
    try:
        cg._GAUSS_NODES, cg._GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(128)
        fine = cg.counterweight_web_overlap(**kw)
    finally:
        cg._GAUSS_NODES, cg._GAUSS_WEIGHTS = nodes, weights
    for k in ("area", "first_y", "polar"):
        assert getattr(ov, k)[0] == pytest.approx(getattr(fine, k)[0], rel=1e-12)


def test_cylinder_closed_forms():
    m, j_own, j_main = cg.cylinder(diameter=0.048, bore=0.02, length=0.0244, density=RHO,
                                   offset=0.0473)
    m_ref = RHO * math.pi / 4 * (0.048**2 - 0.02**2) * 0.0244
    assert m == pytest.approx(m_ref, rel=1e-14)
    assert j_own == pytest.approx(m_ref * (0.048**2 + 0.02**2) / 8, rel=1e-14)
    assert j_main == pytest.approx(m_ref * (0.048**2 + 0.02**2) / 8 + m_ref * 0.0473**2,
                                   rel=1e-14)
    with pytest.raises(ValueError, match="bore"):
        cg.cylinder(diameter=0.04, bore=0.04, length=0.01, density=RHO)


def test_throw_totals_against_grid_and_parts_consistent():
    kw = dict(journal_diameter=0.055, journal_bore=0.0, journal_length=0.027,
              pin_diameter=0.048, pin_bore=0.018, pin_length=0.0244, web_thickness=0.0223,
              web_width_journal=0.090, web_width_pin=0.0757, crank_radius=0.0473,
              density=RHO, cw_inner_radius=0.032, cw_outer_radius=0.068,
              cw_angle=math.radians(160), cw_thickness=0.0)
    p = cg.throw_mass_properties(**kw)
    a, b, rr = 0.045, 0.03785, 0.0473
    ext = ((-0.07, 0.07), (-0.07, rr + b))
    g = _grid_moments(lambda x, y: 0.0223 * (_in_web(x, y, a, b, rr)
                                             | _in_cw(x, y, 0.032, 0.068,
                                                      math.radians(160))), ext) * RHO
    # two webs with their counterweights, the journals and the hollow pin by closed forms
    mj = RHO * math.pi / 4 * 0.055**2 * 0.027
    mp = RHO * math.pi / 4 * (0.048**2 - 0.018**2) * 0.0244
    jp = mp * (0.048**2 + 0.018**2) / 8 + mp * rr**2
    assert p.mass_total[0] == pytest.approx(2 * g[0] + mj + mp, rel=1e-3)
    assert p.inertia_total[0] == pytest.approx(2 * g[2] + mj * 0.055**2 / 8 + jp, rel=1e-3)
    assert p.unbalance_y[0] == pytest.approx(2 * g[1] + mp * rr, rel=1e-3, abs=1e-6)
    # parts: own-centre inertia by the parallel-axis theorem, symmetric webs, z in order
    assert np.allclose(p.inertia_own, p.inertia_main - p.mass * p.y**2)
    assert p.mass[0, 1] == p.mass[0, 4] and p.mass[0, 2] == p.mass[0, 5]
    assert np.all(np.diff(p.z[0, [0, 1, 3, 4, 6]]) > 0)
    assert p.z[0, 3] == pytest.approx((0.027 + 2 * 0.0223 + 0.0244) / 2)
    assert p.y[0, 2] < 0 < p.y[0, 1] < rr


def test_vectorised_over_throws_matches_one_by_one():
    kw = dict(journal_diameter=[0.055, 0.06], journal_bore=0.0, journal_length=0.027,
              pin_diameter=0.048, pin_bore=[0.0, 0.02], pin_length=0.0244,
              web_thickness=0.0223, web_width_journal=0.0757, web_width_pin=0.0757,
              crank_radius=0.0473, density=RHO, cw_inner_radius=[0.0, 0.03],
              cw_outer_radius=[0.0, 0.065], cw_angle=[0.0, 2.5], cw_thickness=0.0)
    p = cg.throw_mass_properties(**kw)
    for i in range(2):
        one = cg.throw_mass_properties(**{k: (v[i] if isinstance(v, list) else v)
                                          for k, v in kw.items()})
        assert np.allclose(p.mass[i], one.mass[0]) and np.allclose(p.inertia_main[i],
                                                                    one.inertia_main[0])
    assert p.mass[0, 2] == 0.0 and p.mass[1, 2] > 0.0


def test_plain_shaft_and_shear_modulus():
    g = cg.shear_modulus(210e9, 0.3)
    assert g == pytest.approx(210e9 / 2.6)
    k = cg.plain_shaft_stiffness(diameter=0.04, bore=0.01, length=0.05, shear_modulus=g)
    assert k == pytest.approx(g * math.pi * (0.04**4 - 0.01**4) / 32 / 0.05, rel=1e-14)


def test_web_width_at_pin_centre():
    # equal circles: the width across the pin centre is the pin-side circle's diameter
    assert cg.web_width_at_pin_centre(width_journal=0.08, width_pin=0.08,
                                      crank_radius=0.05) == pytest.approx(0.08)
    # wider at the journal: the tangent lines, checked by the membership test at y = R
    a, b, rr = 0.045, 0.03, 0.05
    w = cg.web_width_at_pin_centre(width_journal=2 * a, width_pin=2 * b, crank_radius=rr)
    xs = np.linspace(0, 0.06, 600001)
    inside = xs[_in_web(xs, np.full_like(xs, rr), a, b, rr)]
    assert w == pytest.approx(2 * inside.max(), abs=2e-7)
