"""Tests for checker.calc.reynolds_map: the stored finite-length mobility map is the solver's
output (a slice is regenerated), and its interpolant matches the solver."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import mobility as mb
from checker.calc import reynolds as ry
from checker.calc import reynolds_map as rm


def _random_states(n, seed, eps_max=0.999):
    """Load-frame eccentricities: uniform in ln((1-eps)/(1+eps)) up to eps_max, directions
    uniform in the map's direction coordinate (clustered at the load line near the wall)."""
    rng = np.random.default_rng(seed)
    x = rng.uniform(np.log((1 - eps_max) / (1 + eps_max)), 0.0, n)
    eps = -np.tanh(x / 2)
    u = rng.uniform(0.0, 1.0, n)
    th = (1 - eps) * np.sinh(u * np.arcsinh(np.pi / (1 - eps)))
    return eps * np.exp(1j * th * np.where(rng.uniform(size=n) < 0.5, 1, -1))


def test_stored_map_is_the_solver_output():
    # regenerate two rows of one width ratio (eps ~ 0.83 and ~ 0.9996) with the solver and
    # compare with the stored file: identical to rounding (same code, same grid)
    data = rm.load_map()
    assert tuple(data["grid"]) == (ry.DEFAULT_GRID.n_theta, ry.DEFAULT_GRID.n_z)
    assert np.allclose(data["l_over_d"], rm.MAP_L_OVER_D)
    k = int(np.argmin(np.abs(data["l_over_d"] - 0.35)))
    rows = [4, 15]
    fresh = rm.generate_map(l_over_d=[data["l_over_d"][k]], rows=rows)
    for key in ("alpha", "w", "p_max", "q_side"):
        assert np.allclose(fresh[key][0, rows], data[key][k, rows], rtol=1e-9, atol=0.0), key


def test_stored_lookup_rows_derive_from_the_stored_solver_output():
    data = rm.load_map()
    k = 3
    one = {key: data[key][k:k + 1] for key in ("l_over_d", "alpha", "w", "p_max", "q_side")}
    one["eps"] = data["eps"]
    rows = rm.derive_rows(one)
    for key in ("rows_log_r", "rows_log_pi", "rows_log_gamma"):
        assert np.allclose(rows[key][0], data[key][k], rtol=0.0, atol=1e-5), key


@pytest.mark.parametrize("l_over_d,seed", [(18.2 / 55, 1), (0.45, 2)])
def test_map_mobility_matches_the_solver(l_over_d, seed):
    # between the map's width ratios and rows: |M_map / M_solver - 1| < MAP_MAX_REL_ERROR
    # (1 %; measured 0.62 % max on 360 points, 0.13 % at the 95th percentile)
    w = _random_states(10, seed)
    mz, mk = rm.mobility_map(w.real, w.imag, l_over_d)
    rz, rk = ry.mobility_reynolds(w.real, w.imag, l_over_d)
    err = np.abs((mz + 1j * mk) / (rz + 1j * rk) - 1)
    assert err.max() < rm.MAP_MAX_REL_ERROR
    assert np.median(err) < 1e-3


def test_map_at_the_wall_scales_like_a_long_film():
    # towards the wall the finite film is locally long: along the load the mobility falls
    # like (1 - eps)^1.5 (long bearing), not (1 - eps)^2.5 (short); measured exponent between
    # 1.5 and 2.0 at L/D = 1/3 for 1 - eps = 1e-3 .. 1e-5 (beyond the last row: extrapolated)
    e = 1.0 - np.array([1e-3, 1e-4, 1e-5])
    m, _ = rm.mobility_map(e, 0.0, 1 / 3)
    slope = np.diff(np.log(m)) / np.diff(np.log(1 - e))
    assert np.all((slope > 1.45) & (slope < 2.0))


def test_map_tends_to_the_short_bearing_at_small_width():
    # L/D = 1/16 (the smallest node): exact short-bearing mobility within 4 % for eps <= 0.9
    # (the (L/D)^2 effect, notes: 3.3 % at eps 0.92)
    w = _random_states(20, 5, eps_max=0.9)
    mz, mk = rm.mobility_map(w.real, w.imag, 1 / 16)
    ez, ek = mb.mobility_exact(w.real, w.imag, 1 / 16)
    assert np.abs((mz + 1j * mk) / (ez + 1j * ek) - 1).max() < 0.04


def test_film_kernels_match_the_solver():
    # peak pressure and side flow per unit load at the mobility-method state, against the
    # solver at the root-found squeeze direction: within 1 %
    x = 0.37
    d, c, mu = 0.048, 24e-6, 0.004
    ln = x * d
    load = 12e3 * np.exp(0.4j)
    for w in _random_states(4, 9, eps_max=0.995):
        e = w * load / abs(load)  # eccentricity in the frame of the load
        p_map, q_map = rm.film_state_map(load.real, load.imag, e.real, e.imag, d, ln, c, mu)
        mz, mk = ry.mobility_reynolds(w.real, w.imag, x)
        m = complex(float(mz), float(mk)) * load / abs(load)  # mobility in the load's frame
        psi = 2 * c / d
        vs = abs(load) * psi**2 / (mu * ln * d) * m  # V_s / c
        st = ry.film_force(e.real, e.imag, vs.real, vs.imag, d, ln, c, mu)
        assert complex(float(st.force_x), float(st.force_y)) == pytest.approx(load, rel=1e-6)
        assert float(p_map) == pytest.approx(float(st.p_max), rel=0.01)
        assert float(q_map) == pytest.approx(float(st.side_flow), rel=0.01)


def test_table_is_built_quickly_and_cached():
    import time

    rm.table_for.cache_clear()
    t0 = time.perf_counter()
    a = rm.table_for(0.3141)
    assert time.perf_counter() - t0 < 1.0  # about 30 ms on one core
    assert rm.table_for(0.3141) is a


def test_validation():
    with pytest.raises(ValueError, match="L/D"):
        rm.mobility_map(0.5, 0.1, 1.5)
    with pytest.raises(ValueError, match="L/D"):
        rm.mobility_map(0.5, 0.1, 0.05)
    with pytest.raises(ValueError):
        rm.mobility_map(0.9, 0.5, 0.3)  # outside the unit disk
    with pytest.raises(ValueError, match="length"):
        rm.film_state_map(1e3, 0.0, 0.5, 0.0, 0.05, -0.01, 20e-6, 0.01)
