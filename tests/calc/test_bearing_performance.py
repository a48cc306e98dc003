"""Independent accuracy tests for checker.calc.bearing_performance, the friction kernel
checker.calc.reynolds.film_losses and the orbit solver checker.calc.orbit.solve_orbit.

Each test names its oracle (a publication, a closed form derived here, or an own numerical
solution) and the tolerance it supports.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import lambertw

from checker.calc import bearing_performance as bp
from checker.calc import mobility as mb
from checker.calc import orbit as ob
from checker.calc import reynolds as ry

# main bearing of the example I4 (notes), a thicker oil to get moderate eccentricities
D, L, C, MU, W = 0.055, 0.0182, 22e-6, 0.01, 300.0
R = 0.5 * D
U = W * R


def petroff_torque(mu, r, length, omega, c):
    """Petroff N.P. (1883): concentric journal, T = 2 pi mu R^3 L omega / c (Shigley 9th ed.,
    eq. 12-6)."""
    return 2.0 * np.pi * mu * r**3 * length * omega / c


# ------------------------------------------------------------------------------------------
# 1. Petroff
# ------------------------------------------------------------------------------------------
def test_film_losses_petroff_concentric():
    """Petroff (Shigley eq. 12-6): eps = 0, no load -> T = 2 pi mu R^3 L (wJ - wB) / c opposing
    the relative rotation, P = |T| (wJ - wB). Rel 1e-12 (rounding)."""
    wj = np.array([100.0, 300.0, 733.0, 300.0])
    wb = np.array([0.0, 0.0, 0.0, -120.0])  # last: a rotating bearing (big end)
    t, p = ry.film_losses(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, wj, wb, D, L, C, MU)
    ref = petroff_torque(MU, R, L, wj - wb, C)
    np.testing.assert_allclose(-t, ref, rtol=1e-12)
    np.testing.assert_allclose(p, ref * (wj - wb), rtol=1e-12)


def test_orbit_zero_load_stays_centred_and_gives_petroff():
    """Zero load: Booker's equation has eps = 0 as its solution (d eps/dt = omega_bar z x eps);
    the orbit stays centred (1e-15) and film_losses along it is Petroff at every crank angle
    (rel 1e-12), here with an oscillating bearing speed like a big end."""
    n = 720
    theta = np.arange(n) * 4.0 * np.pi / n
    wb = -0.3 * W * np.cos(theta)
    res = ob.solve_orbit(np.zeros(n), np.zeros(n), W, wb, W, D, L, C, MU, model="closed_form")
    assert bool(res.converged)
    assert np.max(np.hypot(res.eps_x, res.eps_y)) < 1e-15
    np.testing.assert_allclose(res.h_min, C, rtol=1e-15)
    wb = -0.3 * W * np.cos(res.theta)  # on the stored orbit's grid (360 steps)
    rx, ryy = mb.eccentricity_rate(0.0, 0.0, res.eps_x, res.eps_y, W, wb, D, L, C, MU)
    wbar = 0.5 * (W + wb)
    vx, vy = rx + wbar * res.eps_y, ryy - wbar * res.eps_x
    t, p = ry.film_losses(res.eps_x, res.eps_y, 0.0, 0.0, vx, vy, W, wb, D, L, C, MU)
    ref = petroff_torque(MU, R, L, W - wb, C)
    np.testing.assert_allclose(-t, ref, rtol=1e-12)
    np.testing.assert_allclose(p, ref * (W - wb), rtol=1e-12)


# ------------------------------------------------------------------------------------------
# 2. Ocvirk steady short bearing
# ------------------------------------------------------------------------------------------
def ocvirk_load(eps):
    """Ocvirk F.W. (1952), NACA TN 2808: F = mu U L^3 / (4 c^2) eps / (1 - eps^2)^2
    sqrt(pi^2 (1 - eps^2) + 16 eps^2)."""
    return (MU * U * L**3 / (4.0 * C**2) * eps / (1.0 - eps**2) ** 2
            * np.sqrt(np.pi**2 * (1.0 - eps**2) + 16.0 * eps**2))


def ocvirk_point(force):
    """Ocvirk's steady eps (brentq on the load relation), attitude tan(phi) = pi sqrt(1-eps^2)
    / (4 eps), peak pressure and journal friction torque."""
    eps = brentq(lambda e: ocvirk_load(e) - force, 1e-12, 1.0 - 1e-12, xtol=1e-15, rtol=1e-15)
    phi = np.arctan2(np.pi * np.sqrt(1.0 - eps**2), 4.0 * eps)
    # p(theta, 0) = 3 mu U / (R c^2) (L^2/4) eps sin(theta) / (1 + eps cos(theta))^3, theta
    # from the thickest film; dp/dtheta = 0 -> 2 eps cos^2 - cos - 3 eps = 0
    ct = (1.0 - np.sqrt(1.0 + 24.0 * eps**2)) / (4.0 * eps)
    st = np.sqrt(1.0 - ct**2)
    p_max = 3.0 * MU * U / (R * C**2) * L**2 / 4.0 * eps * st / (1.0 + eps * ct) ** 3
    torque = (2.0 * np.pi * MU * R**3 * L * W / (C * np.sqrt(1.0 - eps**2))
              + 0.5 * C * eps * force * np.sin(phi))
    return eps, phi, p_max, torque


FORCES = np.array([2000.0, 8000.0, 30000.0])  # Ocvirk eps 0.669, 0.827, 0.909


def _steady(model, steps, eps0=None, peak_pressure=True):
    """Main bearing (journal turns, shell fixed) under a constant downward load."""
    n = 72
    fy = -FORCES[:, None] * np.ones(n)
    kw = {}
    if eps0 is not None:
        kw = {"eps0_x": eps0.real, "eps0_y": eps0.imag}
    res = ob.solve_orbit(np.zeros_like(fy), fy, W, 0.0, W, D, L, C, MU, model=model,
                         steps_per_cycle=steps, tol=1e-8, max_cycles=100,
                         peak_pressure=peak_pressure, **kw)
    assert res.converged.all()
    z = res.eps_x[:, -1] + 1j * res.eps_y[:, -1]
    rx, ryy = mb.eccentricity_rate(0.0, -FORCES, z.real, z.imag, W, 0.0, D, L, C, MU,
                                   model=model)
    vs = (rx + 1j * ryy) - 0.5j * W * z  # V_s / c = d eps/dt - omega_bar z x eps
    return res, z, vs


def _refs():
    return [np.array(v) for v in zip(*(ocvirk_point(f) for f in FORCES))]


def test_ocvirk_steady_exact_mobility():
    """Exact short-bearing pi-film mobility against Ocvirk (NACA TN 2808), which is the same
    film in closed form: eps, attitude, side flow U c L eps, peak pressure and journal torque.
    Started 10 % off the steady point. Measured: <= 1e-14; tolerance 1e-9 (rel)."""
    eps, phi, p_max, torque = _refs()
    start = 0.9 * eps * np.exp(1j * (phi - 0.5 * np.pi))  # load along -y, eps rotated +phi
    res, z, vs = _steady("exact", 32, eps0=start)
    np.testing.assert_allclose(np.abs(z), eps, rtol=1e-9)
    att = np.angle(z / -1j)  # angle from the load direction, in the direction of rotation
    np.testing.assert_allclose(att, phi, rtol=1e-9)
    q = bp.short_bearing_side_flow(vs.real, vs.imag, D, L, C)
    np.testing.assert_allclose(q, U * C * L * eps, rtol=1e-9)
    np.testing.assert_allclose(res.p_max, p_max, rtol=1e-9)
    t, p = ry.film_losses(z.real, z.imag, 0.0, -FORCES, vs.real, vs.imag, W, 0.0, D, L, C, MU)
    np.testing.assert_allclose(-t, torque, rtol=1e-9)
    # steady state: all the work on the journal is dissipated, P = -T omega (rounding)
    np.testing.assert_allclose(p, -t * W, rtol=1e-12)


def test_ocvirk_steady_exact_table_from_centre():
    """Tabulated exact mobility (documented max error 2.5e-4 in M), orbit from the centred
    journal, 720 steps, tol 1e-8, against Ocvirk. Measured: eps and side flow 3.6e-5, torque
    3.0e-5, peak pressure 2.0e-4; tolerances 1e-4 (eps, flow, torque), 5e-4 (pressure)."""
    eps, phi, p_max, torque = _refs()
    res, z, vs = _steady("exact_table", 720)
    np.testing.assert_allclose(np.abs(z), eps, rtol=1e-4)
    np.testing.assert_allclose(np.angle(z / -1j), phi, atol=1e-4)
    q = bp.short_bearing_side_flow(vs.real, vs.imag, D, L, C)
    np.testing.assert_allclose(q, U * C * L * eps, rtol=1e-4)
    np.testing.assert_allclose(res.p_max, p_max, rtol=5e-4)
    t, _ = ry.film_losses(z.real, z.imag, 0.0, -FORCES, vs.real, vs.imag, W, 0.0, D, L, C, MU)
    np.testing.assert_allclose(-t, torque, rtol=1e-4)


def test_ocvirk_steady_closed_form():
    """Booker's closed-form mobility (the default) against Ocvirk: it is an approximation of the
    same film, documented 'h_min 0..+1.4 % optimistic, attitude within 0.7 deg'. Measured eps
    -0.12..-0.39 %, h_min +0.8..+1.2 %, attitude +0.51..+0.60 deg, peak pressure -2.2..-3.0 %,
    torque -0.23..-0.36 %. The side flow from the orbit's own state is Ocvirk's U c L eps with
    that eps (rel 1e-9: steady state, V_s = -omega_bar z x eps)."""
    eps, phi, p_max, torque = _refs()
    res, z, vs = _steady("closed_form", 720)
    np.testing.assert_allclose(np.abs(z), eps, rtol=5e-3)
    ratio = res.h_min / (C * (1.0 - eps))
    assert np.all((ratio >= 1.0) & (ratio <= 1.014)), ratio
    assert np.all(np.abs(np.angle(z / -1j) - phi) <= np.radians(0.7))
    q = bp.short_bearing_side_flow(vs.real, vs.imag, D, L, C)
    np.testing.assert_allclose(q, U * C * L * np.abs(z), rtol=1e-9)
    np.testing.assert_allclose(res.p_max, p_max, rtol=0.035)
    t, _ = ry.film_losses(z.real, z.imag, 0.0, -FORCES, vs.real, vs.imag, W, 0.0, D, L, C, MU)
    np.testing.assert_allclose(-t, torque, rtol=5e-3)


# ------------------------------------------------------------------------------------------
# 3. Heat balance
# ------------------------------------------------------------------------------------------
T0 = 373.15


def _visc(mu0, beta):
    return lambda t: mu0 * np.exp(-beta * (t - T0))


def lambert_temperature(ts, k, a, mu0, beta, rho_cp, q):
    """T = Ts + k a mu0 exp(-beta (T - T0)) / (rho_cp Q). With x = T - Ts and
    K = k a mu(Ts) / (rho_cp Q): x = K exp(-beta x) -> beta x exp(beta x) = beta K ->
    x = W0(beta K) / beta (derived here; principal branch, beta K > 0)."""
    kk = k * a * mu0 * np.exp(-beta * (ts - T0)) / (rho_cp * q)
    return ts + np.real(lambertw(beta * kk)) / beta


def test_heat_balance_lambert_closed_form():
    """Petroff power, constant flow: solve_heat_balance equals the Lambert-W fixed point to
    1e-6 K (the local model is exact, so one update lands on the root and the second
    evaluation confirms it: 2 evaluations; measured error 6e-14 K for a 20.4 K rise)."""
    a = 2.0 * np.pi * R**3 * L * 600.0**2 / C  # P = a mu (Petroff)
    mu0, beta, ts, q, rho_cp = 0.01, 0.03, 363.15, 4e-6, 870.0 * 2000.0
    visc = _visc(mu0, beta)

    def evaluate(t):
        return a * visc(t), np.full(np.shape(t), q), np.zeros(np.shape(t)), rho_cp, None

    hb = bp.solve_heat_balance(evaluate, ts, visc, tol=1e-6)
    ref = lambert_temperature(ts, 0.5, a, mu0, beta, rho_cp, q)
    assert bool(hb.converged)
    assert hb.evaluations <= 3
    assert abs(float(hb.temperature) - ref) <= 1e-6
    assert ref - ts > 5.0  # a real temperature rise, not a trivial fixed point


def test_heat_balance_lambert_batch():
    """50 random parameter sets (vectorised), weight and heat-to-oil fraction varied: all equal
    the Lambert-W fixed point to 1e-6 K within 3 evaluations."""
    rng = np.random.default_rng(7)
    n = 50
    a = rng.uniform(1e3, 1e5, n)
    mu0 = rng.uniform(0.004, 0.03, n)
    beta = rng.uniform(0.01, 0.05, n)
    ts = rng.uniform(330.0, 400.0, n)
    q = rng.uniform(1e-6, 2e-5, n)
    rho_cp = rng.uniform(1.5e6, 1.9e6, n)

    def visc(t):
        return mu0 * np.exp(-beta * (t - T0))

    def evaluate(t):
        return a * visc(t), q, 0.0, rho_cp, t

    hb = bp.solve_heat_balance(evaluate, ts, visc, weight=1.0, heat_to_oil=0.8, tol=1e-6)
    ref = lambert_temperature(ts, 0.8, a, mu0, beta, rho_cp, q)
    assert hb.temperature.shape == (n,)
    assert hb.converged.all()
    assert hb.evaluations <= 3
    np.testing.assert_allclose(hb.temperature, ref, rtol=0.0, atol=1e-6)
    assert np.ptp(ref - ts) > 10.0


def test_heat_balance_model_mismatch_brentq():
    """P = a mu^0.7 and Q_feed = d / mu (the solver's local model assumes P ~ mu): the result
    equals a brentq root of the scalar balance to within the solver's tol (1e-3 K). Measured:
    6 evaluations, error 0.92e-3 K (the result is the last evaluated T_k, whose error is about
    the last change / (1 - contraction), so it can approach or exceed tol)."""
    a, d, qs, rho_cp, ts, mu0, beta = 2.0e4, 2.0e-8, 2e-6, 1.7e6, 353.15, 0.012, 0.028
    visc = _visc(mu0, beta)

    def evaluate(t):
        mu = visc(t)
        return a * mu**0.7, qs, d / mu, rho_cp, None

    tol = 1e-3
    hb = bp.solve_heat_balance(evaluate, ts, visc, tol=tol, max_evaluations=20)

    def g(t):
        mu = visc(t)
        return ts + 0.5 * a * mu**0.7 / (rho_cp * (qs + d / mu)) - t

    ref = brentq(g, ts, ts + 500.0, xtol=1e-12)
    assert bool(hb.converged)
    assert ref - ts > 5.0
    assert abs(float(hb.temperature) - ref) <= tol


def test_heat_balance_partial_evaluation_equals_full():
    """``partial=True``: the converged points are not evaluated again (each later evaluation
    sees only the points still iterating) and every point ends with the temperature, change
    and evaluation state of the full iteration (points of P ~ mu^0.4..1, so they converge after
    different numbers of evaluations)."""
    n = 40
    rng = np.random.default_rng(3)
    a = rng.uniform(1e4, 5e4, n)
    expo = np.linspace(0.4, 1.0, n)  # 1.0: the local model is exact (2 evaluations)
    d, qs, rho_cp, ts, mu0, beta = 2.0e-8, 2e-6, 1.7e6, 353.15, 0.012, 0.028
    visc = _visc(mu0, beta)
    seen = []

    def evaluate(t, active=None):
        seen.append(n if active is None else int(active.sum()))
        mu = visc(t)
        return a * mu**expo, qs, d / mu, rho_cp, t.copy()

    def evaluate_all(t):
        mu = visc(t)
        return a * mu**expo, qs, d / mu, rho_cp, t.copy()

    full = bp.solve_heat_balance(evaluate_all, np.full(n, ts), visc, tol=1e-3,
                                 max_evaluations=20)
    part = bp.solve_heat_balance(evaluate, np.full(n, ts), visc, tol=1e-3, max_evaluations=20,
                                 partial=True)
    assert full.converged.all() and part.converged.all()
    assert part.evaluations == full.evaluations >= 4
    assert seen[0] == n and seen[-1] < n and seen == sorted(seen, reverse=True)
    np.testing.assert_array_equal(part.temperature, full.temperature)
    np.testing.assert_array_equal(part.state, full.temperature)
    np.testing.assert_allclose(part.change, full.change, rtol=0.0, atol=1e-3)


def test_heat_balance_not_converged_is_reported():
    """One evaluation from the supply temperature, far from the balance (~25 K): reported as
    not converged with its change, never a silent answer."""
    a, mu0, beta, ts, q, rho_cp = 3e4, 0.01, 0.03, 353.15, 3e-6, 1.7e6
    visc = _visc(mu0, beta)

    def evaluate(t):
        return a * visc(t) ** 0.7, q, 0.0, rho_cp, None

    hb = bp.solve_heat_balance(evaluate, ts, visc, tol=0.1, max_evaluations=1)
    assert hb.evaluations == 1
    assert not bool(hb.converged)
    assert float(hb.change) > 5.0
    assert float(hb.temperature) == ts  # the last evaluated temperature, as documented


# ------------------------------------------------------------------------------------------
# 4. Groove feed
# ------------------------------------------------------------------------------------------
GROOVE = dict(supply_pressure=3e5, viscosity=0.008, diameter=D, land_width=0.008,
              clearance=C)


def test_groove_full_equals_shigley():
    """Full groove: Q = pi p_s D c^3 (1 + 1.5 eps^2) / (6 mu b), Budynas & Nisbett, Shigley's
    MED 9th ed. 2011, sec. 12-10 (Q_s = pi p_s r c^3 (1 + 1.5 eps^2) / (3 mu l')). Rel 1e-10."""
    eps = np.array([0.0, 0.3, 0.7, 0.95])
    phi = np.array([0.0, 1.0, -2.0, 3.0])
    start = np.array([0.0, 0.4, -1.0, 2.5])
    q = bp.groove_feed_flow(eps * np.cos(phi), eps * np.sin(phi), arc_start=start,
                            arc_end=start + 2.0 * np.pi, **GROOVE)
    g = GROOVE
    ref = (np.pi * g["supply_pressure"] * D * C**3 * (1.0 + 1.5 * eps**2)
           / (6.0 * g["viscosity"] * g["land_width"]))
    np.testing.assert_allclose(q, ref, rtol=1e-10)


def test_groove_partial_arc_quad():
    """Partial arc: Q = p_s R / (6 mu b) int h^3 dtheta against scipy quad. Rel 1e-10."""
    g = GROOVE
    cases = [(0.6, 0.3, -0.5, 1.7), (0.9, 2.0, 1.0, 4.0), (0.2, -1.0, 3.0, 3.3)]
    for eps, phi, t1, t2 in cases:
        q = bp.groove_feed_flow(eps * np.cos(phi), eps * np.sin(phi), arc_start=t1,
                                arc_end=t2, **g)
        integral, _ = quad(lambda t, e=eps, f=phi: (C * (1.0 - e * np.cos(t - f))) ** 3, t1, t2,
                           epsabs=0.0, epsrel=1e-13)
        ref = g["supply_pressure"] * R * integral / (6.0 * g["viscosity"] * g["land_width"])
        assert abs(float(q) / ref - 1.0) < 1e-10


def test_groove_half_arc_concentric_is_half():
    """eps = 0: any half arc carries half the full groove's flow (rel 1e-12)."""
    full = bp.groove_feed_flow(0.0, 0.0, arc_start=0.0, arc_end=2.0 * np.pi, **GROOVE)
    half = bp.groove_feed_flow(0.0, 0.0, arc_start=1.1, arc_end=1.1 + np.pi, **GROOVE)
    assert abs(float(half) / float(full) - 0.5) < 1e-12


# ------------------------------------------------------------------------------------------
# 5. Hole feed against an own finite-difference solution of Laplace's equation
# ------------------------------------------------------------------------------------------
def _stretched(n, length, h0):
    """n+1 nodes on [0, length], x = length sinh(k s) / sinh(k), first spacing h0 (uniform
    if that is finer)."""
    s = np.linspace(0.0, 1.0, n + 1)
    if length / n <= h0:
        return length * s
    k = brentq(lambda k: length * np.sinh(k / n) / np.sinh(k) - h0, 1e-9, 60.0)
    return length * np.sinh(k * s) / np.sinh(k)


def hole_flux_fd(a, b=1.0, xlen=8.0, nx=240, ny=120, far="dirichlet"):
    """Flux out of both edges of a strip |y| <= b with p = 0 there, from a hole r <= a held at
    p = 1 (uniform film: the feed's Reynolds equation is Laplace's). Returns the flux divided
    by h^3 / (12 mu) p_s, i.e. int |grad p| over both edges.

    Quarter domain 0 <= x <= xlen b, 0 <= y <= b, symmetry (mirror) at x = 0 and y = 0;
    far end x = xlen b: p = 0 ("dirichlet") or dp/dx = 0 ("neumann"). Second-order
    finite differences on a sinh-stretched tensor grid (first spacing a/25 at the hole) with
    Shortley-Weller stencils where a grid line is cut by the circle (Shortley G.H., Weller R.,
    J. Appl. Phys. 9:334, 1938); edge flux by a second-order one-sided derivative and the
    trapezoidal rule."""
    x = _stretched(nx, xlen * b, a / 25.0)
    y = _stretched(ny, b, a / 25.0)
    nX, nY = x.size, y.size
    X, Y = np.meshgrid(x, y, indexing="ij")
    idx = np.arange(nX * nY).reshape(nX, nY)
    inside = X**2 + Y**2 <= a * a
    fixed = inside.copy()
    fixed[:, -1] = True  # edge y = b
    if far == "dirichlet":
        fixed[-1, :] = True
    rows, cols, vals = [idx[fixed]], [idx[fixed]], [np.ones(fixed.sum())]
    rhs = np.where(inside, 1.0, 0.0).ravel()
    free = ~fixed
    diag = np.zeros((nX, nY))
    for axis in (0, 1):
        g = x if axis == 0 else y
        other = Y if axis == 0 else X
        pos = np.arange(g.size)
        # spacings to the +/- neighbours along this axis (mirror at the first node and, for a
        # zero-flux far end, at the last node)
        hp = np.empty(g.size)
        hm = np.empty(g.size)
        hp[:-1] = np.diff(g)
        hm[1:] = np.diff(g)
        hm[0] = hp[0]
        hp[-1] = hm[-1]
        ip = np.where(pos < g.size - 1, pos + 1, pos - 1)
        im = np.where(pos > 0, pos - 1, pos + 1)
        shape = [1, 1]
        shape[axis] = g.size
        hp_, hm_ = np.broadcast_to(hp.reshape(shape), X.shape), hm.reshape(shape)
        hm_ = np.broadcast_to(hm_, X.shape).copy()
        coord = np.broadcast_to(g.reshape(shape), X.shape)
        if axis == 0:
            nb_p, nb_m = idx[ip, :], idx[im, :]
            in_m = inside[im, :]
        else:
            nb_p, nb_m = idx[:, ip], idx[:, im]
            in_m = inside[:, im]
        # Shortley-Weller: a minus neighbour inside the hole is replaced by the circle
        cut = free & in_m & (pos.reshape(shape) > 0)
        hm_[cut] = coord[cut] - np.sqrt(a * a - other[cut] ** 2)
        cp = 2.0 / (hp_ * (hp_ + hm_))
        cm = 2.0 / (hm_ * (hp_ + hm_))
        diag -= cp + cm
        rows += [idx[free], idx[free & ~cut]]
        cols += [nb_p[free], nb_m[free & ~cut]]
        vals += [cp[free], cm[free & ~cut]]
        np.subtract.at(rhs, idx[cut], cm[cut] * 1.0)
    rows.append(idx[free])
    cols.append(idx[free])
    vals.append(diag[free])
    a_mat = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(nX * nY, nX * nY))
    p = spl.spsolve(a_mat, rhs).reshape(nX, nY)
    h1, h2 = y[-1] - y[-2], y[-2] - y[-3]
    dpdy = (-p[:, -2] * (h1 + h2) / (h1 * h2) + p[:, -3] * h1 / (h2 * (h1 + h2)))  # p_edge = 0
    return 4.0 * -np.trapezoid(dpdy, x)


def _hole_formula(ratio):
    return float(bp.hole_feed_flow(1.0, 1.0, 1.0 / 12.0, 2.0 * ratio, 1.0))


def test_hole_fd_far_end_does_not_matter():
    """Own check of the FD oracle: p = 0 or zero flux at x = +-8 b changes the edge flux by
    < 5e-5 (measured 9e-6; the strip's slowest mode decays as exp(-pi x / 2b))."""
    q_d = hole_flux_fd(0.3, nx=160, ny=80, far="dirichlet")
    q_n = hole_flux_fd(0.3, nx=160, ny=80, far="neumann")
    assert abs(q_n / q_d - 1.0) < 5e-5


@pytest.mark.parametrize(("ratio", "bound"), [(0.1, 3e-4), (0.3, 1e-3), (0.5, 8e-3)])
def test_hole_feed_against_fd(ratio, bound):
    """hole_feed_flow (strip line-source formula) against the own FD solution. FD
    discretisation error (240x120 vs 480x240): 4.2e-5 at a/b = 0.1, 1.1e-5 at 0.3, 8e-6 at 0.5.
    Measured FD / formula - 1: +4.0e-5 (0.1), +4.8e-4 (0.3), +5.8e-3 (0.5): the formula is
    low by at most 0.6 %, inside the docstring's 2 % (asserted), bound per ratio as given."""
    q_fd = hole_flux_fd(ratio)
    diff = q_fd / _hole_formula(ratio) - 1.0
    assert abs(diff) < 0.02
    assert abs(diff) < bound, diff


# ------------------------------------------------------------------------------------------
# 6. Small helpers
# ------------------------------------------------------------------------------------------
def test_rotating_hole_film_factor_quad():
    """Mean of (1 - eps cos u)^3 over a turn by scipy quad, rel 1e-12."""
    eps = np.array([0.0, 0.25, 0.6, 0.9, 0.999])
    got = bp.rotating_hole_film_factor(eps)
    for e, g in zip(eps, got):
        ref = quad(lambda u, e=e: (1.0 - e * np.cos(u)) ** 3, 0.0, 2.0 * np.pi,
                   epsabs=0.0, epsrel=1e-13)[0] / (2.0 * np.pi)
        assert abs(g / ref - 1.0) < 1e-12


def test_centrifugal_pressure_rise_hand_number():
    """Hand number: rho 850 kg/m^3, omega 600 rad/s, r 25 -> 60 mm: 0.5 * 850 * 600^2 *
    (0.06^2 - 0.025^2) = 425 * 360000 * 0.002975 = 455 175 Pa (rel 1e-12)."""
    got = bp.centrifugal_pressure_rise(850.0, 600.0, 0.06, 0.025)
    assert abs(float(got) / 455175.0 - 1.0) < 1e-12


@pytest.mark.parametrize("t_c", [20.0, 100.0, 300.0])
@pytest.mark.parametrize("rho15", [860.0, 900.0])
def test_oil_specific_heat_cragoe_original_units(t_c, rho15):
    """Cragoe C.S. (1929), NBS Misc. Publ. 97: c = (0.388 + 0.00045 t_F) / sqrt(s) Btu/(lb F),
    1 Btu_IT/(lb F) = 4186.8 J/(kg K) exactly. Rel 1e-3 (the SI constants 1684 and 3.39 are
    rounded; measured 4.6e-4 at 20 C)."""
    t_f = t_c * 1.8 + 32.0
    s = rho15 / 999.0
    ref = (0.388 + 0.00045 * t_f) / np.sqrt(s) * 4186.8
    got = float(bp.oil_specific_heat(t_c + 273.15, rho15))
    assert abs(got / ref - 1.0) < 1e-3


def test_oil_specific_heat_outside_validity():
    with pytest.raises(ValueError, match="0..400"):
        bp.oil_specific_heat(273.15 - 10.0, 870.0)
    with pytest.raises(ValueError, match="0..400"):
        bp.oil_specific_heat(273.15 + 450.0, 870.0)
    with pytest.raises(ValueError, match="specific gravity"):
        bp.oil_specific_heat(350.0, 600.0)


# ------------------------------------------------------------------------------------------
# 7. Bad inputs
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("call", "name"), [
    (lambda: bp.short_bearing_side_flow(np.nan, 0.0, D, L, C), "vs_x"),
    (lambda: bp.short_bearing_side_flow(0.0, 0.0, D, -L, C), "length"),
    (lambda: bp.groove_feed_flow(0.1, 0.0, 3e5, 0.0, D, 0.008, C, 0.0, 1.0), "viscosity"),
    (lambda: bp.groove_feed_flow(0.1, 0.0, -1.0, 0.01, D, 0.008, C, 0.0, 1.0),
     "supply_pressure"),
    (lambda: bp.hole_feed_flow(-1e-6, 3e5, 0.01, 0.004, 0.009), "film"),
    (lambda: bp.hole_feed_flow(1e-6, 3e5, 0.01, 0.004, 0.0), "edge_distance"),
    (lambda: bp.centrifugal_pressure_rise(0.0, 600.0, 0.06, 0.025), "density"),
    (lambda: bp.oil_specific_heat(350.0, np.inf), "density_15"),
    (lambda: ry.film_losses(0, 0, 0, 0, 0, 0, W, 0, D, L, 0.0, MU), "clearance"),
    (lambda: ry.film_losses(0, 0, 0, 0, 0, 0, np.nan, 0, D, L, C, MU), "omega_journal"),
    (lambda: bp.solve_heat_balance(lambda t: (1.0, 1e-6, 0.0, 1.7e6, None), -300.0,
                                   lambda t: 0.01 + 0 * t), "t_supply"),
    (lambda: bp.solve_heat_balance(lambda t: (1.0, 1e-6, 0.0, 1.7e6, None), 300.0,
                                   lambda t: 0.01 + 0 * t, heat_to_oil=0.0), "heat_to_oil"),
])
def test_bad_inputs_name_the_argument(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_bad_inputs_outside_validity():
    with pytest.raises(ValueError, match="hole radius"):
        bp.hole_feed_flow(1e-6, 3e5, 0.01, 2 * 0.51 * 0.009, 0.009)
    with pytest.raises(ValueError, match="groove arc"):
        bp.groove_feed_flow(0.1, 0.0, 3e5, 0.01, D, 0.008, C, 1.0, 1.0)
    with pytest.raises(ValueError, match="eccentricity"):
        bp.groove_feed_flow(0.8, 0.6, 3e5, 0.01, D, 0.008, C, 0.0, 1.0)
    with pytest.raises(ValueError, match="eccentricity"):
        bp.rotating_hole_film_factor(1.0)
    with pytest.raises(ValueError, match="eccentricity"):
        ry.film_losses(0.8, 0.6, 0, 0, 0, 0, W, 0, D, L, C, MU)
    with pytest.raises(ValueError, match="oil flow"):
        bp.solve_heat_balance(lambda t: (1.0, 0.0, 0.0, 1.7e6, None), 330.0,
                              lambda t: 0.01 + 0 * t)


# ------------------------------------------------------------------------------------------
# Feed flow of one bearing over its orbit, crank drilling geometry, start temperature
# (physics moved out of the bearing-performance graph node, issue 24)
# ------------------------------------------------------------------------------------------
def _orbit(eps, n=720):
    """A whirling orbit of constant eccentricity ``eps``: the direction turns once per cycle,
    shape (1, n) (one point of the batch, n steps)."""
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return (eps * np.cos(t))[None, :], (eps * np.sin(t))[None, :]


def test_fixed_hole_film_factor_hand_values_and_whirl_mean():
    """(h/c)^3 at a shell hole: hand values; averaged over a whirling orbit it is the film
    seen by a turning hole, 1 + 1.5 eps^2 (closed form of the mean of (1 - eps cos u)^3)."""
    assert float(bp.fixed_hole_film_factor(0.3, 0.4, 0.5 * np.pi)) == pytest.approx(0.6**3)
    assert float(bp.fixed_hole_film_factor(0.3, 0.4, np.pi)) == pytest.approx(1.3**3)
    ex, ey = _orbit(0.7)
    mean = bp.fixed_hole_film_factor(ex, ey, 1.234).mean(axis=-1)
    assert float(mean[0]) == pytest.approx(1.0 + 1.5 * 0.49, rel=1e-12)
    with pytest.raises(ValueError, match="eccentricity"):
        bp.fixed_hole_film_factor(0.8, 0.8, 0.0)


def test_crank_hole_radius_hand_values():
    """Law of cosines: r = 45 mm, R_p = 24 mm; hole outward r + R_p = 69 mm, sideways
    sqrt(45^2 + 24^2) = 51 mm, inward r - R_p = 21 mm."""
    r = bp.crank_hole_radius(0.045, 0.024, np.array([0.0, 0.5 * np.pi, np.pi]))
    np.testing.assert_allclose(r, [0.069, 0.051, 0.021], rtol=1e-12)


FEED = {"supply_pressure": 3e5, "diameter": D, "length": 2 * 0.009, "clearance": C}


def test_cycle_mean_feed_full_groove_is_shigley():
    """Full groove, orbit at |eps| = 0.5: Shigley's pi p_s D c^3 (1 + 1.5 eps^2) / (6 mu b),
    b = L/2 (Budynas and Nisbett 2011, sec. 12-10)."""
    ex, ey = _orbit(0.5)
    q = bp.cycle_mean_feed_flow(ex, ey, np.array([MU]), full_groove=True, **FEED)
    ref = np.pi * 3e5 * D * C**3 * (1.0 + 1.5 * 0.25) / (6.0 * MU * 0.009)
    assert float(q[0]) == pytest.approx(ref, rel=1e-12)


def test_cycle_mean_feed_partial_arc_wraps_and_halves():
    """A half arc given with its end below its start (270 deg .. 90 deg) wraps by 2 pi; in a
    concentric film it carries half the full groove's flow."""
    z = np.zeros((1, 4))
    full = bp.cycle_mean_feed_flow(z, z, np.array([MU]), full_groove=True, **FEED)
    half = bp.cycle_mean_feed_flow(z, z, np.array([MU]), groove_arc=(1.5 * np.pi, 0.5 * np.pi),
                                   **FEED)
    assert float(half[0]) == pytest.approx(0.5 * float(full[0]), rel=1e-12)
    both = bp.cycle_mean_feed_flow(z, z, np.array([MU]), full_groove=True,
                                   groove_arc=(1.5 * np.pi, 0.5 * np.pi), **FEED)
    assert float(both[0]) == pytest.approx(1.5 * float(full[0]), rel=1e-12)


def test_cycle_mean_feed_holes_hand_formula():
    """Two holes of 5 mm, edge distance 9 mm: Q = n h^3/(12 mu) 2 pi p / ln(4b/(pi a));
    a shell hole in a concentric film sees h = c, a turning hole in a whirling film at
    eps 0.6 sees h^3 = (1 + 1.5 * 0.36) c^3; a centrifugal rise adds to the supply pressure
    and a net negative pressure feeds nothing."""
    def ref(h3, p):
        return 2 * h3 / (12.0 * MU) * 2.0 * np.pi * p / np.log(4.0 * 0.009 / (np.pi * 0.0025))

    z = np.zeros((1, 8))
    holes = {"holes": 2, "hole_diameter": 0.005}
    q = bp.cycle_mean_feed_flow(z, z, np.array([MU]), hole_angle=0.3, **holes, **FEED)
    assert float(q[0]) == pytest.approx(ref(C**3, 3e5), rel=1e-12)
    ex, ey = _orbit(0.6)
    q = bp.cycle_mean_feed_flow(ex, ey, np.array([MU]), **holes, **FEED)
    assert float(q[0]) == pytest.approx(ref(1.54 * C**3, 3e5), rel=1e-12)
    q = bp.cycle_mean_feed_flow(z, z, np.array([MU, MU]), hole_angle=0.0,
                                hole_pressure_rise=np.array([1e5, -5e5]), **holes, **FEED)
    assert float(q[0]) == pytest.approx(ref(C**3, 4e5), rel=1e-12)
    assert float(q[1]) == 0.0


def test_start_temperature_closed_form_at_constant_viscosity():
    """Constant viscosity, no feed: T = T_s + 0.5 f P / (rho c_p Q) with the Petroff power at
    eps 0.6, P = T_Petroff omega / sqrt(1 - 0.36), and the short-bearing side leakage
    Q = D c L 0.6 omega/2 (shell fixed: mean angular velocity omega/2; Ocvirk 1952)."""
    ts = np.array([373.15])
    wj = np.full((1, 16), W)
    wb = np.zeros((1, 16))
    rho_cp = 1.6e6
    t = bp.start_temperature(ts, wj, wb, D, L, C, 0.0, rho_cp, 0.8, lambda x: MU + 0.0 * x)
    power = petroff_torque(MU, R, L, W, C) * W / 0.8
    flow = D * C * L * 0.6 * 0.5 * W
    assert float(t[0]) == pytest.approx(373.15 + 0.5 * 0.8 * power / (rho_cp * flow), abs=1e-9)
    with pytest.raises(ValueError, match="eps"):
        bp.start_temperature(ts, wj, wb, D, L, C, 0.0, rho_cp, 0.8, lambda x: MU + 0.0 * x,
                             eps=1.0)



def test_groove_arc_integral_without_trigonometry_of_eps():
    """The partial-groove integral in polynomial form (groove ends' sines only) against the
    trigonometric primitive of the expanded cubic and against 200-point Gauss-Legendre
    quadrature, random eccentricities up to 0.999, arcs 1e-3..2 pi: rel 1e-11, abs 1e-14
    (the primitives' rounding, about 1e-15 of terms of order 10, where a short arc in the
    thin film integrates to 1e-5)."""
    rng = np.random.default_rng(37)
    n = 4000
    eps = rng.uniform(0.0, 0.999, n)
    phi = rng.uniform(-np.pi, np.pi, n)
    t1 = rng.uniform(-np.pi, 2.0 * np.pi, n)
    span = rng.uniform(1e-3, 2.0 * np.pi, n)
    ex, ey = eps * np.cos(phi), eps * np.sin(phi)
    got = bp._cubed_film_integral(ex, ey, ex * ex + ey * ey, t1, t1 + span, span)

    def prim(u):
        su = np.sin(u)
        return (u - 3.0 * eps * su + 3.0 * eps**2 * (0.5 * u + 0.25 * np.sin(2.0 * u))
                - eps**3 * (su - su**3 / 3.0))

    trig = prim(t1 - phi + span) - prim(t1 - phi)
    x, w = np.polynomial.legendre.leggauss(200)
    t = t1[:, None] + 0.5 * span[:, None] * (x + 1.0)
    quad_ref = (0.5 * span[:, None] * w * (1.0 - eps[:, None] * np.cos(t - phi[:, None])) ** 3
                ).sum(axis=1)
    np.testing.assert_allclose(got, trig, rtol=1e-11, atol=1e-14)
    np.testing.assert_allclose(got, quad_ref, rtol=1e-11, atol=1e-14)
