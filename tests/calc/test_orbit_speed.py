"""The orbit kernel's speed devices give the numbers of the plain computation: shared
(shifted) orbits, the closure criterion, batch independence."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import orbit as ob
from tests.calc.test_orbit import PIN, THETA, N, i4_like_loads

RPM = 3000.0
W = RPM * np.pi / 30


def _shifted_big_ends(shifts_deg=(0, 180, 540, 360)):
    """Big-end loads of four throws of an in-line engine: one sequence shifted in crank angle
    (1 deg grid, so a shift of k deg is k/2 steps of the default 360-step orbit)."""
    fx, fy, w_rod, _, _ = i4_like_loads(RPM)
    fx = fx + 400.0 * np.cos(0.5 * THETA)  # a half-order part: loads 720 deg periodic only
    lx = np.stack([np.roll(fx, s) for s in shifts_deg])
    ly = np.stack([np.roll(fy, s) for s in shifts_deg])
    wb = np.stack([np.roll(w_rod, s) for s in shifts_deg])
    return lx, ly, wb


def test_shared_orbits_equal_the_independently_solved_ones():
    lx, ly, wb = _shifted_big_ends()
    shared = ob.solve_orbit(lx, ly, W, wb, W, **PIN, peak_pressure=True)
    alone = ob.solve_orbit(lx, ly, W, wb, W, **PIN, peak_pressure=True, share_orbits=False)
    # the same periodic orbit: equal to the periodicity tolerance (different start phase)
    assert np.allclose(shared.h_min, alone.h_min, rtol=1e-5, atol=0)
    assert np.allclose(shared.p_max, alone.p_max, rtol=1e-4, atol=0)
    assert np.allclose(shared.eps_x, alone.eps_x, rtol=0, atol=1e-4)
    assert np.allclose(shared.eps_y, alone.eps_y, rtol=0, atol=1e-4)
    # the shared orbits are exactly the first one shifted by whole steps, and so is the
    # crank angle of the thinnest film
    for i, s_deg in enumerate((0, 180, 540, 360)):
        k = s_deg // 2
        assert np.array_equal(shared.eps_x[i], np.roll(shared.eps_x[0], k))
        assert shared.h_min[i] == shared.h_min[0]
        th = (shared.theta_h_min[0] + np.radians(s_deg)) % (4 * np.pi)
        assert shared.theta_h_min[i] == pytest.approx(th, abs=1e-9)


def test_orbits_not_shifted_copies_are_not_shared():
    lx, ly, wb = _shifted_big_ends((0, 180))
    ly = ly.copy()
    ly[1] *= 1.0 + 1e-6  # a slightly different load: solved on its own
    a = ob.solve_orbit(lx, ly, W, wb, W, **PIN)
    b = ob.solve_orbit(lx, ly, W, wb, W, **PIN, share_orbits=False)
    assert np.array_equal(a.h_min, b.h_min)
    # a shift that is not a whole step (1 deg on 2-deg steps) is not shared either
    lx2, ly2, wb2 = _shifted_big_ends((0, 1))
    c = ob.solve_orbit(lx2, ly2, W, wb2, W, **PIN)
    d = ob.solve_orbit(lx2, ly2, W, wb2, W, **PIN, share_orbits=False)
    assert np.array_equal(c.h_min, d.h_min)


def test_bearing_results_do_not_depend_on_the_rest_of_the_batch():
    # per-bearing sub-step counts: a bearing's numbers are bit-identical alone or in a batch
    # with much stiffer bearings (heavier loads need many more sub-steps)
    fx, fy, w_rod, mx, my = i4_like_loads(RPM)
    lx = np.stack([fx, 6.0 * fx, mx])
    ly = np.stack([fy, 6.0 * fy, my])
    wb = np.stack([w_rod, w_rod, np.zeros(N)])
    batch = ob.solve_orbit(lx, ly, W, wb, W, **PIN, peak_pressure=True)
    for i in range(3):
        one = ob.solve_orbit(lx[i], ly[i], W, wb[i], W, **PIN, peak_pressure=True)
        assert float(one.h_min) == batch.h_min[i]
        assert float(one.p_max) == batch.p_max[i]
        assert np.array_equal(one.eps_x, batch.eps_x[i])


@pytest.mark.parametrize("model", ["closed_form", "reynolds_map"])
def test_closure_criterion_matches_the_converged_orbit(model):
    # the default tolerance against an orbit converged to round-off
    lx, ly, wb = _shifted_big_ends((0,))
    r = ob.solve_orbit(lx, ly, W, wb, W, **PIN, model=model)
    ref = ob.solve_orbit(lx, ly, W, wb, W, **PIN, model=model, tol=1e-12)
    assert r.converged.all() and int(r.n_cycles.max()) <= int(ref.n_cycles.max())
    assert np.allclose(r.h_min, ref.h_min, rtol=2e-5, atol=0)
    assert np.all(r.periodic_error < ob.DEFAULT_PERIODIC_TOL)
