"""The fast paths of the orbit kernel give the same numbers as the plain arithmetic they
replace (bit for bit): map lookups through the interleaved table, loads resampled straight
into the node-major layout, the closed-form rate on real parts."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import orbit as ob
from checker.calc import reynolds_map as rm


def _plain_map(w: np.ndarray, lod: np.ndarray) -> np.ndarray:
    """Map mobility times (L/D)^2: the lookup coordinates (:func:`rm._lookup_t`, rows in
    ``ln(1 - eps)``) and :func:`rm._bilinear`, unfused."""
    mob, _, _, off = rm.stack_tables(lod)
    e = np.abs(w)
    d = np.maximum(1.0 - e, rm._S_MIN)
    d2 = d * d
    ld2 = np.log(d2)
    q = (e - w.real) / (e + rm._TINY)
    ft = (np.log(d2 + q) - ld2 + rm._LIN_Q * q) / (np.log(d2 + 2.0) - ld2 + 2.0 * rm._LIN_Q)
    ft = ft * rm._CT
    fx = ld2 * (0.5 * rm._CX)
    ix, it = fx.astype(np.intp), ft.astype(np.intp)
    a = rm._bilinear(mob, ix * rm._SX + it + off, fx - ix, ft - it)
    g = np.sqrt(d) * d
    return a.real * g + 1j * (a.imag * (g * w.imag))


@pytest.mark.parametrize("size", [1, 2, 7, 300])
def test_map_kernel_equals_plain_lookup(size):
    rng = np.random.default_rng(size)
    r = 1.0 - np.exp(rng.uniform(np.log(2e-7), 0.0, size))  # clustered at the wall
    r[: size // 3] *= 1.0 + 1e-6  # RK stages slightly outside the disk: floored
    w = r * np.exp(1j * rng.uniform(-np.pi, np.pi, size))
    lod = rng.choice([0.1, 0.25, 0.3717, 0.6], size)
    expect = _plain_map(w, lod)
    tab, off = rm.stack_kernel_tables(lod)
    got = rm.map_kernel(w, None, off, tab)
    assert np.array_equal(got, expect)
    mob, _, _, off2 = rm.stack_tables(lod)
    assert np.array_equal(rm.map_kernel(w, mob, off2), expect)  # table built on the fly
    one = np.full(size, 0.25)
    tab1, off1 = rm.stack_kernel_tables(one)
    assert not off1.any()
    assert np.array_equal(rm.map_kernel(w, None, None, tab1), _plain_map(w, one))


def test_kernel_table_pairs():
    flat = np.arange(6) + 1j * np.arange(6) ** 2
    pairs = rm.kernel_table(flat).reshape(-1, 2)
    assert np.array_equal(pairs[:, 0], flat)
    assert np.array_equal(pairs[:-1, 1], np.diff(flat))
    assert pairs[-1, 1] == 0.0


@pytest.mark.parametrize("n_in,n_out", [(720, 480), (720, 720), (720, 360), (1, 480),
                                        (720, 346), (100, 480)])
def test_resample_nodes_equals_resample_periodic(n_in, n_out):
    rng = np.random.default_rng(n_in + n_out)
    a = rng.normal(size=(5, n_in)) * 1e4
    out = np.empty((n_out, 5))
    ob._resample_nodes(a, n_out, out)
    assert np.array_equal(out, ob._resample_periodic(a, n_out).T)
    c = np.empty((n_out, 5), dtype=complex)  # as the kernel uses it: into complex parts
    ob._resample_nodes(a, n_out, c.real)
    ob._resample_nodes(-a, n_out, c.imag)
    assert np.array_equal(c, ob._resample_periodic(a - 1j * a, n_out).T)


def test_closed_form_rate_equals_complex_formula():
    rng = np.random.default_rng(3)
    n = 5000
    z = 0.999 * np.sqrt(rng.random(n)) * np.exp(2j * np.pi * rng.random(n))
    uc = np.exp(2j * np.pi * rng.random(n))
    fk = rng.normal(size=n) * 1e3 + 1j * rng.normal(size=n) * 1e3
    iwb = 1j * rng.normal(size=n) * 0.5
    rate = ob._make_rate("closed_form", {}, {})
    for k in (n, 1, 2, 3):
        w = z[:k] * uc[:k]
        s = np.maximum(1.0 - w.real, ob._S_MIN)
        expect = fk[:k] * (s * np.sqrt(s) * (s - 1j * ob._C4PI * w.imag)) + iwb[:k] * z[:k]
        assert np.array_equal(rate(z[:k], fk[:k], uc[:k], iwb[:k]), expect)
