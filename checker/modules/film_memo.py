"""Per-bearing reuse of journal orbits across variants (remedies, tolerance corners, studies).

A variant that moves one bearing's inputs (its clearance, its width) leaves the orbits of the
other bearings unchanged; the film calculation is nevertheless one node of the calculation
graph (:mod:`checker.modules.bearings`), so without this memo every such variant solves the orbits
of all bearings again. :func:`orbits` wraps the orbit kernel call of
:func:`checker.modules.bearings._orbits`: each bearing row of each prepared engine gets a key, and
rows whose key was solved before are taken from the memo; the others are solved in one kernel
call, as before.

Exactness. The orbit of a bearing depends on its own kernel inputs (loads, whirl, speed,
diameter, length, clearance, viscosity, groove; model and steps) and, through orbit sharing
(:func:`checker.calc.orbit.solve_orbit` ``share_orbits``: an orbit that is another's shifted
by whole steps is that orbit shifted, with its initial state), on the bearing rows before it
whose orbits may be its shifted copies. The key of a row therefore covers its own inputs and
those of every earlier row *linked* to it (same scalars and the same shift-invariant load
features, compared with a tolerance far wider than the kernel's sharing test, so every pair the
kernel could share is linked). Rows solved again are solved together with every earlier row
linked to them, so the kernel sees the same sharing as in a cold evaluation. Results are
therefore bitwise those of a cold evaluation (tests/test_film_memo.py).

The memo holds copies of the per-row results, at most :data:`MAX_BYTES` (least recently used
first out). :func:`clear` empties it.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Callable

import numpy as np

MAX_BYTES = 128 * 2**20
"""Memory held by the memo (the orbits of one bearing at every case and speed are about 1 MB)."""

_SCALARS = ("speed", "d", "length", "c", "mu", "full")
_LINK_RTOL = 1e-6
"""Relative tolerance of the link test (the kernel shares orbits equal to about 1e-10)."""

class RowMemo(OrderedDict):
    """Per-row results by key, least recently used first out beyond ``max_bytes`` (``size``
    gives an entry's bytes); ``stats`` counts rows taken from it and rows solved. Used by this
    module and :mod:`checker.modules.heat_memo`."""

    def __init__(self, max_bytes: int, size: Callable[[dict], int]):
        super().__init__()
        self.max_bytes, self.size, self.bytes = max_bytes, size, 0
        self.stats = {"hits": 0, "solved": 0}

    def reset(self) -> None:
        """Empty it and its counts."""
        self.clear()
        self.bytes = 0
        self.stats.update(hits=0, solved=0)

    def to_solve(self, keys: list[str], links: list[list[int]]) -> set[int]:
        """The rows whose key is not kept, with every earlier row linked to one of them
        (``links[a]``: the rows before ``a`` whose orbits the kernel might share with its
        own), so that the kernel sees the same sharing as in a cold evaluation."""
        todo = {a for a, k in enumerate(keys) if k not in self}
        grow = list(todo)
        while grow:
            a = grow.pop()
            for b in links[a]:
                if b not in todo:
                    todo.add(b)
                    grow.append(b)
        return todo

    def store(self, key: str, entry: dict) -> None:
        """Keep ``entry`` (unless already there or larger than the bound), dropping the
        oldest entries beyond the bound."""
        size = self.size(entry)
        if key in self or size > self.max_bytes:
            return
        self[key] = entry
        self.bytes += size
        while self.bytes > self.max_bytes and self:
            _, old = self.popitem(last=False)
            self.bytes -= self.size(old)


def _array_bytes(entry: dict) -> int:
    return sum(v.nbytes for v in entry.values() if isinstance(v, np.ndarray))


_memo = RowMemo(MAX_BYTES, _array_bytes)
stats = _memo.stats
"""Rows taken from the memo and rows solved by the kernel since the last :func:`clear`."""


def clear() -> None:
    """Empty the memo."""
    _memo.reset()


_LOADS = ("fy", "fx", "omega_journal", "omega_bearing")
_per_loads: dict[int, tuple] = {}  # id of a load array -> (weakref, digests, features)


def _load_facts(ex: dict) -> tuple[list[bytes], np.ndarray]:
    """Per bearing of a load quantity's arrays: a digest of its loads and whirl, and the
    shift-invariant features of each (case, speed) orbit (largest and mean load and whirl).
    Computed once per load array (the calculation cache shares it between variants)."""
    import weakref

    key = id(ex["fx"])
    hit = _per_loads.get(key)
    if hit is not None and hit[0]() is ex["fx"] and all(
            r() is ex[k] for r, k in zip(hit[3], _LOADS)):
        return hit[1], hit[2]
    arrs = [np.ascontiguousarray(ex[k]) for k in _LOADS]
    nb = arrs[0].shape[0]
    digests = []
    for i in range(nb):
        h = hashlib.sha256()
        for k, a in zip(_LOADS, arrs):
            h.update(k.encode() + str(a.dtype).encode() + str(a[i].shape).encode())
            h.update(a[i].tobytes())
        digests.append(h.digest())
    fy, fx, wj, wb = np.broadcast_arrays(*arrs)
    mag = np.hypot(fx, fy)
    w = np.abs(wj + wb)
    feats = np.stack([mag.max(axis=-1), mag.mean(axis=-1), w.max(axis=-1), w.mean(axis=-1)],
                     axis=-1)  # (bearings, cases, speeds, 4)
    for k in [k for k, v in _per_loads.items() if v[0]() is None]:
        del _per_loads[k]
    _per_loads[key] = (weakref.ref(ex["fx"]), digests, feats,
                       [weakref.ref(ex[k]) for k in _LOADS])
    return digests, feats


def _links(p: dict, feats: np.ndarray) -> list[list[int]]:
    """Per row, the earlier rows whose orbits the kernel might share with its own (orbits at
    the same speed with the same scalars and shift-invariant load and whirl features)."""
    arg, sel = p["arg"], p["sel"]
    n_rows = sel.size
    nc, ns = p["shape"][1:]
    f = np.broadcast_to(feats[sel], (n_rows, nc, ns, feats.shape[-1]))
    scal = [np.asarray(arg[k], dtype=float).reshape(n_rows, nc, ns) for k in _SCALARS]
    f = np.concatenate([f, np.stack(scal, axis=-1)], axis=-1)
    f = np.moveaxis(f, 2, 0).reshape(ns, n_rows * nc, -1)
    close = np.ones((ns, n_rows * nc, n_rows * nc), dtype=bool)
    for j in range(f.shape[-1]):
        a = f[..., j]
        tol = _LINK_RTOL * np.maximum(np.abs(a)[:, :, None], np.abs(a)[:, None, :]) + 1e-300
        close &= np.abs(a[:, :, None] - a[:, None, :]) <= tol
    row_close = close.reshape(ns, n_rows, nc, n_rows, nc).any(axis=(0, 2, 4))
    return [[b for b in range(a) if row_close[a, b]] for a in range(n_rows)]


def _row_digests(p: dict, load_digests: list[bytes], tag: str) -> list[bytes]:
    """Per row: its loads (digest) and its kernel scalars, exactly."""
    arg, sel = p["arg"], p["sel"]
    n_rows = sel.size
    per = int(np.prod(p["shape"][1:]))
    n_pts = arg["fx"].shape[-1]
    out = []
    for a in range(n_rows):
        h = hashlib.sha256(tag.encode() + str((per, n_pts)).encode())
        h.update(load_digests[int(sel[a])])
        part = slice(a * per, (a + 1) * per)
        for k in _SCALARS:
            x = np.ascontiguousarray(arg[k][part])
            h.update(k.encode() + str(x.dtype).encode() + str(x.shape).encode())
            h.update(x.tobytes())
        out.append(h.digest())
    return out


def _take(arg: dict, rows: list[int], per: int) -> dict:
    idx = np.concatenate([np.arange(r * per, (r + 1) * per) for r in rows])
    return {k: v[idx] for k, v in arg.items()}


_FIELDS = ("h_min", "eps_max", "theta_h_min", "p_max", "theta_p_max", "collapse", "converged",
           "n_cycles", "message", "eps_x", "eps_y")


def orbits(preps: list[dict], model: str, kernel: Callable[[list[dict], str], None],
           tag: str = "") -> None:
    """Fill ``p["res"]`` of every prepared engine like ``kernel(preps, model)`` does, solving
    only the bearing rows not in the memo (and the earlier rows linked to them).

    ``tag`` names the kernel settings besides ``model`` (steps per cycle...): part of the key.
    """
    plan = []  # per prep: (keys, rows to solve)
    for p in preps:
        n_rows = p["sel"].size
        per = int(np.prod(p["shape"][1:]))
        load_digests, feats = _load_facts({k: getattr(p["bl"].detail, k) for k in _LOADS})
        digests = _row_digests(p, load_digests, f"{model}|{tag}")
        links = _links(p, feats)
        keys = []
        for a in range(n_rows):
            h = hashlib.sha256(digests[a])
            for b in links[a]:
                h.update(digests[b])
            keys.append(h.hexdigest())
        todo = _memo.to_solve(keys, links)
        plan.append((keys, sorted(todo), per))
    # the memo's entries this call uses, taken before storing new ones (which may evict)
    hits = [{a: _memo[k] for a, k in enumerate(keys) if a not in set(todo)}
            for keys, todo, _ in plan]
    stats["hits"] += sum(len(h) for h in hits)
    sub = []
    for p, (_keys, todo, per) in zip(preps, plan):
        if todo:
            # every row to solve (an oil variant, a new peak pressure): the arrays as they are
            whole = len(todo) == p["sel"].size
            sub.append({"arg": p["arg"] if whole else _take(p["arg"], todo, per),
                        "sel": p["sel"] if whole else p["sel"][todo],
                        "shape": p["shape"], "res": None})
    if sub:
        kernel(sub, model)
    it = iter(sub)
    for p, (keys, todo, _per), got in zip(preps, plan, hits):
        fresh = next(it)["res"] if todo else None
        pos = {a: k for k, a in enumerate(todo)}
        rows = []
        for a, key in enumerate(keys):
            if a in pos:
                e = {f: (None if fresh[f] is None else fresh[f][pos[a]].copy()) for f in _FIELDS}
                e["theta"] = fresh["theta"]
                _memo.store(key, e)
                stats["solved"] += 1
            else:
                e = got[a]
                if key in _memo:
                    _memo.move_to_end(key)
            rows.append(e)
        res = {f: (None if rows[0][f] is None else np.stack([e[f] for e in rows]))
               for f in _FIELDS}
        res["theta"] = rows[0]["theta"]
        p["res"] = res
