"""Per-bearing reuse of the bearing heat balance across variants (remedies, tolerance corners,
studies).

A variant that moves one bearing's inputs (its clearance, its width) leaves the heat balance of
the other bearings unchanged; the heat balance is nevertheless one node of the calculation
graph (:func:`checker.modules.bearing_performance.bearing_heat_balance`), so without this memo
every such variant solves the short-bearing orbits of all bearings again, two or three times
(one per film-temperature iterate). :func:`balance` wraps the solution of the balance: each
bearing row gets a key, and rows whose key was solved before are taken from the memo; the
others are solved together in one call, as before.

Exactness. The balance of each load case and speed of a bearing is iterated on its own
(:func:`checker.calc.bearing_performance.solve_heat_balance` with ``partial``: a point is
evaluated again only while it changes, with its own temperature, viscosity and warm start),
and the orbit kernel chooses its sub-steps and cycles per orbit. A row's numbers therefore
depend on its own inputs (loads, whirl, speeds, diameter, length, clearance, groove, oil feed;
oil, supply temperature and pressure; tolerance and steps), and, through orbit sharing
(:func:`checker.calc.orbit.solve_orbit` ``share_orbits``: an orbit that is another's shifted
by whole steps is that orbit shifted, with its initial state), on the earlier rows whose orbits
may be its shifted copies. The key of a row covers its own inputs and the keys of every earlier
row *linked* to it (same geometry and the same shift-invariant load features, compared with a
tolerance far wider than the kernel's sharing test and whatever the viscosity, so every pair the
kernel could share at any iterate is linked). Rows solved again are solved together with every
earlier row linked to them, so the kernel sees the same sharing as in a cold evaluation. What
is aggregated over the bearings (number of evaluations, largest change, temperature range,
findings, engine friction) is computed by the caller from the assembled rows: the number of
evaluations of the whole balance is the largest number of evaluations of any point. Results
are therefore bitwise those of a cold evaluation (tests/modules/test_heat_memo.py). When the
partial solution fails (an input error), the whole balance is solved cold for its own message.

The memo holds copies of the per-row results (a few kB per bearing), at most :data:`MAX_BYTES`
(least recently used first out). :func:`clear` empties it.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable

import numpy as np

from . import film_memo

MAX_BYTES = 32 * 2**20
"""Memory held by the memo (the balance of one bearing at every case and speed of the I4
template, 2 x 61 points, is about 20 kB)."""

_LINK_RTOL = 1e-6
"""Relative tolerance of the link test (the kernel shares orbits equal to about 1e-10)."""

def _size(entry: dict) -> int:
    n = 0
    for v in entry.values():
        n += v.nbytes
        if v.dtype == object:
            n += sum(len(s) + 64 for s in v.flat)
    return n


_memo = film_memo.RowMemo(MAX_BYTES, _size)
stats = _memo.stats
"""Bearing rows taken from the memo and rows solved since the last :func:`clear`."""


def clear() -> None:
    """Empty the memo."""
    _memo.reset()


def _links(rows: np.ndarray, scalars: np.ndarray, feats: np.ndarray) -> list[list[int]]:
    """Per row (position in ``rows``), the earlier rows whose orbits the kernel might share
    with its own at some speed (same geometry, close shift-invariant load and whirl features
    at that speed in some load cases; the viscosity is not compared: it moves with the
    iterated temperature)."""
    n_rows = rows.size
    f = feats[rows]  # (rows, cases, speeds, features)
    nc, ns = f.shape[1:3]
    f = np.moveaxis(f, 2, 0).reshape(ns, n_rows * nc, -1)

    def close(a: np.ndarray) -> np.ndarray:
        tol = _LINK_RTOL * np.maximum(np.abs(a)[..., :, None], np.abs(a)[..., None, :]) + 1e-300
        return np.abs(a[..., :, None] - a[..., None, :]) <= tol

    near = np.ones((ns, n_rows * nc, n_rows * nc), dtype=bool)
    for j in range(f.shape[-1]):
        near &= close(f[..., j])
    row_near = near.reshape(ns, n_rows, nc, n_rows, nc).any(axis=(0, 2, 4))
    s = np.asarray(scalars, dtype=float).reshape(n_rows, -1)
    for j in range(s.shape[1]):
        row_near &= close(s[:, j])
    return [[b for b in range(a) if row_near[a, b]] for a in range(n_rows)]


def balance(rows: np.ndarray, facts: list[bytes], scalars: np.ndarray, loads: dict,
            solve: Callable[[np.ndarray], dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """The heat balance of the bearing rows ``rows`` as ``solve(rows)`` gives it, solving only
    the rows not in the memo (and the earlier rows linked to them).

    Parameters
    ----------
    rows : numpy.ndarray of int
        Bearing indices (into the load arrays) of the balance.
    facts : list of bytes
        Per row, every input of its balance besides its loads, exactly (geometry, feed, oil,
        settings).
    scalars : numpy.ndarray, shape (rows, k)
        Per row, the orbit kernel's bearing scalars besides the viscosity (diameter, length,
        clearance, full groove) for the link test.
    loads : dict
        The load quantity's ``fx``, ``fy``, ``omega_journal``, ``omega_bearing`` arrays
        (bearings first).
    solve : callable
        ``solve(sub) -> {name: array (len(sub), ...)}``: the balance of the bearing rows
        ``sub`` (a subset of ``rows``, in order) solved together; may raise ValueError.

    Returns
    -------
    dict
        ``solve(rows)``'s arrays, bitwise.
    """
    load_digests, feats = film_memo._load_facts({k: loads[k] for k in film_memo._LOADS})
    n_rows = rows.size
    links = _links(rows, scalars, feats)
    keys: list[str] = []
    for a in range(n_rows):
        h = hashlib.sha256(facts[a])
        h.update(load_digests[int(rows[a])])
        for b in links[a]:
            h.update(keys[b].encode())
        keys.append(h.hexdigest())
    todo = _memo.to_solve(keys, links)
    order = sorted(todo)
    got = {a: _memo[keys[a]] for a in range(n_rows) if a not in todo}
    if not got:  # nothing to reuse: the cold solution
        fresh = solve(rows)
        for a in range(n_rows):
            _memo.store(keys[a], {k: v[a].copy() for k, v in fresh.items()})
        stats["solved"] += n_rows
        return fresh
    fresh = {}
    if order:
        try:
            fresh = solve(rows[order])
        except ValueError:
            return solve(rows)  # the cold solution's own error (or its numbers)
    stats["hits"] += len(got)
    stats["solved"] += len(order)
    pos = {a: k for k, a in enumerate(order)}
    entries = []
    for a in range(n_rows):
        if a in pos:
            e = {k: v[pos[a]].copy() for k, v in fresh.items()}
            _memo.store(keys[a], e)
        else:
            e = got[a]
            if keys[a] in _memo:
                _memo.move_to_end(keys[a])
        entries.append(e)
    return {k: np.stack([e[k] for e in entries]) for k in entries[0]}
