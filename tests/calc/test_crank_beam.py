"""The crank as a continuous beam (checker.calc.crank_beam) against closed forms.

Sources of the reference numbers:
- two equal spans, load at mid-span of the first: Clapeyron's three-moment equation (e.g.
  Timoshenko and Young, "Theory of Structures", 2nd ed., 1965, sec. 9.2), R1 = 13P/32,
  R2 = 11P/16, R3 = -3P/32, moment under the load 13PL/64: exact to rounding (1e-9);
- n spans: the three-moment equations solved here independently of the frame code;
- elastic supports: compatibility of the middle deflection with the spring deflections
  (flexibility method, derived in ``_two_span_springs``), exact;
- equilibrium of forces and moments: exact for any linear frame (1e-9 relative).
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.crank_beam import (
    Frame,
    crank_frame,
    element_stiffness,
    rectangle_torsion_constant,
    section_moment,
    solve_frame,
)
from checker.calc.crank_forces import Vector2, main_bearing_loads

EI = 2.0e5  # N m^2
SPAN = 0.09  # m


def _straight(z: np.ndarray, supports: list[int], k: float | np.ndarray = np.inf) -> Frame:
    n_el = z.size - 1
    return Frame(
        nodes=np.column_stack([np.zeros_like(z), np.zeros_like(z), z]),
        elements=np.column_stack([np.arange(n_el), np.arange(1, n_el + 1)]),
        axial_stiffness=np.full(n_el, 1e9),
        torsional_stiffness=np.full(n_el, 1e5),
        bending_stiffness=np.full((n_el, 2), EI),
        first_axis=np.tile([1.0, 0.0, 0.0], (n_el, 1)),
        support_nodes=np.array(supports),
        support_stiffness=np.broadcast_to(np.asarray(k, dtype=float), (len(supports),)).copy(),
        torsion_node=supports[-1],
    )


def _three_moment(n_span: int, span: float, load_span: int, a: float) -> np.ndarray:
    """Reactions of n equal spans on rigid supports, unit load at distance a in one span."""
    n_sup = n_span + 1
    # unknown support moments M_1..M_{n-1} (M_0 = M_n = 0)
    m = n_sup - 2
    mat = np.zeros((m, m))
    rhs = np.zeros(m)
    b = span - a
    for i in range(1, n_sup - 1):
        r = i - 1
        mat[r, r] = 4.0 * span
        if r > 0:
            mat[r, r - 1] = span
        if r < m - 1:
            mat[r, r + 1] = span
        # load term: 6 A x / L of the simply supported moment diagram of adjacent spans
        if load_span == i - 1:  # span left of support i, load at a from its left end
            rhs[r] -= a * (span**2 - a**2) / span
        if load_span == i:  # span right of support i
            rhs[r] -= b * (span**2 - b**2) / span
    mom = np.zeros(n_sup)
    mom[1:-1] = np.linalg.solve(mat, rhs)
    # share of the unit load at each support (sagging moments positive)
    reac = np.zeros(n_sup)
    for s in range(n_span):
        shear = (mom[s + 1] - mom[s]) / span  # M(x) = M_s + V_L x - P <x - a>
        reac[s] += shear
        reac[s + 1] -= shear
        if s == load_span:
            reac[s] += b / span
            reac[s + 1] += a / span
    return reac


def test_two_equal_spans_rigid_supports():
    z = np.array([0.0, 0.5, 1.0, 1.5, 2.0]) * SPAN
    sol = solve_frame(_straight(z, [0, 2, 4]), load_nodes=np.array([1]))
    p = -1000.0
    b = sol.bearing_loads(np.array([[0.0, p, 0.0]]))
    np.testing.assert_allclose(b[:, 1], [13 * p / 32, 11 * p / 16, -3 * p / 32], rtol=1e-9)
    np.testing.assert_allclose(b[:, 0], 0.0, atol=1e-9)
    # moment under the load from statics: 13 P L / 64
    forces = np.array([[0.0, p], *(-b)])
    zf = np.array([z[1], z[0], z[2], z[4]])
    m = section_moment([z[1] + 1e-12], forces, zf)
    assert m[0, 0] == pytest.approx(-13 * p * SPAN / 64, rel=1e-9)  # sagging, M_x = (z_c - z) F_y


@pytest.mark.parametrize("n_span", [2, 3, 4])
@pytest.mark.parametrize("where", [0.3, 0.5])
def test_n_spans_against_three_moment_equation(n_span, where):
    per = 4
    z = np.linspace(0.0, n_span * SPAN, n_span * per + 1)
    load_node = int(round(where * per))
    sol = solve_frame(_straight(z, list(range(0, z.size, per))), load_nodes=np.array([load_node]))
    b = sol.bearing_loads(np.array([[0.0, 1.0, 0.0]]))[:, 1]
    ref = _three_moment(n_span, SPAN, 0, z[load_node])
    np.testing.assert_allclose(b, ref, rtol=1e-9, atol=1e-12)


def _two_span_springs(kappa: float) -> np.ndarray:
    """R1, R2, R3 of two spans L on equal springs k, load P = 1 at L/2 (kappa = k L^3/EI).

    Middle deflection of the simply supported 2L beam under P at L/2: 11 P L^3/(96 EI); under
    the middle reaction R2: R2 (2L)^3/(48 EI) = R2 L^3/(6 EI); the end springs move the chord
    by (R1 + R3)/(2k) with R1 + R3 = P - R2; the middle spring by R2/k.
    """
    r2 = (11.0 / 96.0 + 0.5 / kappa) / (1.0 / 6.0 + 1.5 / kappa)
    return np.array([0.75 - r2 / 2, r2, 0.25 - r2 / 2])


@pytest.mark.parametrize("kappa", [1000.0, 100.0, 48.0, 10.0])
def test_two_spans_elastic_supports(kappa):
    z = np.array([0.0, 0.5, 1.0, 1.5, 2.0]) * SPAN
    k = kappa * EI / SPAN**3
    sol = solve_frame(_straight(z, [0, 2, 4], k), load_nodes=np.array([1]))
    b = sol.bearing_loads(np.array([[0.0, 1.0, 0.0]]))[:, 1]
    np.testing.assert_allclose(b, _two_span_springs(kappa), rtol=1e-9)


def test_very_stiff_springs_give_the_rigid_result():
    z = np.linspace(0.0, 4 * SPAN, 17)
    rigid = solve_frame(_straight(z, [0, 4, 8, 12, 16]), load_nodes=np.array([3, 9]))
    stiff = solve_frame(_straight(z, [0, 4, 8, 12, 16], 1e8 * EI / SPAN**3),
                        load_nodes=np.array([3, 9]))
    f = np.array([[300.0, -1000.0, 0.0], [-200.0, 500.0, 0.0]])
    np.testing.assert_allclose(stiff.bearing_loads(f), rigid.bearing_loads(f), rtol=1e-5,
                               atol=1e-5 * 1000)


def test_rigid_support_offset():
    """Middle support of two spans raised by d: R2 = 48 EI d/(2L)^3, ends -R2/2 each."""
    z = np.array([0.0, 0.5, 1.0, 1.5, 2.0]) * SPAN
    d = 1e-5
    off = np.zeros((3, 2))
    off[1, 1] = d
    for k in (np.inf, 1e4 * EI / SPAN**3):
        sol = solve_frame(_straight(z, [0, 2, 4], k), load_nodes=np.array([1]))
        b = sol.bearing_loads(np.zeros((1, 3)), offset=off)[:, 1]
        r2 = 48 * EI * d / (2 * SPAN) ** 3
        # the bearing pushed up by the crank's reaction is loaded downward by the journal
        np.testing.assert_allclose(b, [r2 / 2, -r2, r2 / 2], rtol=2e-3 if np.isfinite(k) else 1e-9)


def _i4_frame(k=np.inf) -> object:
    lj, tw, lp = 0.027, 0.0223, 0.0244
    bay = lj + 2 * tw + lp
    main_z = np.arange(5) * bay
    web_z = np.column_stack([main_z[:-1] + lj / 2 + tw / 2, main_z[1:] - lj / 2 - tw / 2])
    pin_z = [[m + bay / 2] for m in main_z[:-1]]
    return crank_frame(
        main_z=main_z, web_z=web_z, pin_load_z=pin_z,
        throw_angle=np.radians([0.0, 180.0, 180.0, 0.0]), crank_radius=0.0473,
        journal_diameter=0.055, journal_bore=0.0, pin_diameter=0.048, pin_bore=0.0,
        web_thickness=tw, web_width=0.0757, youngs_modulus=2.1e11, poisson_ratio=0.3,
        support_stiffness=k,
    )


@pytest.mark.parametrize("k", [np.inf, 5e8])
def test_crank_frame_equilibrium_at_every_angle(k):
    cf = _i4_frame(k)
    sol = solve_frame(cf.frame, cf.load_nodes)
    rng = np.random.default_rng(1)
    n_ang = 36
    f = rng.normal(0.0, 1e4, (n_ang, sol.load_nodes.size, 3))
    f[..., 2] = 0.0
    pts = sol.load_positions + rng.normal(0.0, 0.01, (n_ang, sol.load_nodes.size, 3))
    pts[..., 2] = sol.load_positions[:, 2]  # off-node radially (web and counterweight masses)
    b = sol.bearing_loads(f, point=pts)
    scale = np.abs(f).sum(axis=(-1, -2))
    np.testing.assert_allclose(b.sum(axis=-2), f[..., :2].sum(axis=-2), atol=1e-9 * scale.max())
    # moments about the origin, x and y components: sum over bearings equals sum over loads
    zb = sol.support_z
    mb = np.stack([-zb * b[..., 1], zb * b[..., 0]], axis=-1).sum(axis=-2)
    mf = np.cross(pts, f)[..., :2].sum(axis=-2)
    np.testing.assert_allclose(mb, mf, atol=1e-9 * (scale * zb.max()).max())


def test_single_throw_is_the_determinate_lever_rule():
    cf = crank_frame(
        main_z=[0.0, 0.1], web_z=[[0.025, 0.075]], pin_load_z=[[0.04, 0.06]],
        throw_angle=[0.3], crank_radius=0.045, journal_diameter=0.06, journal_bore=0.0,
        pin_diameter=0.05, pin_bore=0.02, web_thickness=0.02, web_width=0.08,
        youngs_modulus=2.1e11, poisson_ratio=0.3, support_stiffness=np.inf,
    )
    sol = solve_frame(cf.frame, cf.pin_nodes[0])
    f = np.array([[[1000.0, -5000.0, 0.0], [-300.0, 200.0, 0.0]]])
    b = sol.bearing_loads(f)[0]
    big_end = Vector2(-f[..., 0][..., None].T.reshape(2, 1), -f[..., 1][..., None].T.reshape(2, 1))
    ref = main_bearing_loads(
        [0.0], 0.0, big_end, pin_index=np.array([0, 0]), rod_axial_position=[0.04, 0.06],
        bay_length=[0.1], mass=np.zeros(0), mass_bay=np.zeros(0, dtype=int),
        mass_position=np.zeros((0, 2)), mass_axial_position=np.zeros(0),
    )
    np.testing.assert_allclose(b[:, 0], ref.x[:, 0], rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(b[:, 1], ref.y[:, 0], rtol=1e-9, atol=1e-6)


def test_element_stiffness_is_symmetric_and_has_six_rigid_modes():
    k = element_stiffness([0.0, 0.0, 0.0], [0.01, 0.03, 0.05], 1e8, 1e3, 2e3, 5e3,
                          [1.0, 0.0, 0.0])
    np.testing.assert_allclose(k, k.T, atol=1e-6 * np.abs(k).max())
    ev = np.linalg.eigvalsh(k)
    assert np.sum(np.abs(ev) < 1e-8 * ev.max()) == 6


def test_cantilever_tip_deflection():
    """Cantilever under a tip load, along a skew axis: P L^3 / (3 EI) (Euler-Bernoulli)."""
    d = np.array([1.0, 2.0, 2.0]) / 3.0
    length = 0.2
    k = element_stiffness(np.zeros(3), length * d, 1e9, 1e4, EI, 3 * EI, [0.0, 0.0, 1.0])
    e1 = np.array([0.0, 0.0, 1.0]) - d[2] * d
    e1 /= np.linalg.norm(e1)
    kf = k[6:, 6:]
    u = np.linalg.solve(kf, np.r_[e1, 0.0, 0.0, 0.0])
    # displacement along e1 bends about e2: stiffness EI_2 = 3 EI
    assert u[:3] @ e1 == pytest.approx(length**3 / (3 * 3 * EI), rel=1e-12)


def test_rectangle_torsion_constant_against_exact_series():
    """Exact J of a rectangle (Timoshenko and Goodier 1951, sec. 109): b/t = 1 -> 0.1406 b t^3,
    b/t = 2 -> 0.229, b/t = 10 -> 0.312 (Roark Table 10.7 quotes the same, 4 % band)."""
    for ratio, beta in ((1.0, 0.1406), (2.0, 0.229), (10.0, 0.312)):
        j = rectangle_torsion_constant(ratio, 1.0)
        assert j / ratio == pytest.approx(beta, rel=0.04)


def test_unheld_frame_is_reported():
    """Two separate elements, one support each: a mechanism, reported, never solved to NaN."""
    z = np.array([0.0, 0.1, 0.2, 0.3])
    fr = _straight(z, [0, 3])
    broken = Frame(**{**fr.__dict__, "elements": np.array([[0, 1], [2, 3]]),
                      "axial_stiffness": np.full(2, 1e9), "torsional_stiffness": np.full(2, 1e5),
                      "bending_stiffness": np.full((2, 2), EI),
                      "first_axis": np.tile([1.0, 0.0, 0.0], (2, 1))})
    with pytest.raises(ValueError, match="not held"):
        solve_frame(broken, np.array([1]))
    with pytest.raises(ValueError, match="at least two"):
        _straight(z, [0])
