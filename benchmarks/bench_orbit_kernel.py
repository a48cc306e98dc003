"""Benchmark of the journal-orbit kernel :func:`checker.calc.orbit.solve_orbit` per call.

    python benchmarks/bench_orbit_kernel.py [--runs 7] [--workbook engine.xlsx]

The batches are those of a check of the I4 example (``checker template``; or the given
workbook): the calls of ``checker.api.check`` to ``solve_orbit`` are recorded once, then
replayed ``--runs`` times each, and the median and minimum processor time per call are
printed. Batches:

* ``reynolds_map 1098``: the finite-length film of the check (9 bearings x 2 load cases x 61
  speeds, 488 distinct orbits after sharing);
* ``reynolds_map 1586``: the same with 488 more rows at 2 % larger clearance in another
  ``group`` (like the variants of a ``--remedies`` batch);
* ``reynolds_map 122``: one bearing's rows;
* ``closed_form 1098``: the short-bearing film of the check (with the peak pressure);
* ``closed_form heat 1098`` / ``61``: the heat-balance calls (squeeze velocity; all rows, one
  bearing and load case).

Report the machine load (``uptime``) with the numbers: the machine may be shared.
"""

from __future__ import annotations

import argparse
import ctypes
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker import api  # noqa: E402
from checker.calc import orbit as ob  # noqa: E402


def _keep_freed_memory() -> None:
    """As the command line does (checker.cli): keep freed memory in the process."""
    try:
        libc = ctypes.CDLL(None)
        libc.mallopt(-3, 32 * 2**20)
        libc.mallopt(-1, 128 * 2**20)
    except (OSError, AttributeError):
        pass


def _record(workbook: Path) -> list[tuple[tuple, dict]]:
    calls = []
    orig = ob.solve_orbit

    def rec(*a, **k):
        calls.append((a, k))
        return orig(*a, **k)

    ob.solve_orbit = rec
    try:
        api.check(workbook)
    finally:
        ob.solve_orbit = orig
    return calls


def _rows(call: tuple[tuple, dict], rows: np.ndarray) -> tuple[tuple, dict]:
    """The call restricted to some rows of its batch (flattened)."""
    a, k = call
    size = np.shape(a[0])[:-1]

    def take(v):
        if v is None or np.ndim(v) == 0:
            return v
        if np.ndim(v) == len(size) + 1:
            return np.broadcast_to(v, size + (np.shape(v)[-1],)).reshape(-1, np.shape(v)[-1])[rows]
        return np.broadcast_to(v, size).reshape(-1)[rows]

    return (tuple(take(v) for v in a),
            {key: take(v) if isinstance(v, np.ndarray) else v for key, v in k.items()})


def _variants(call: tuple[tuple, dict], extra: int) -> tuple[tuple, dict]:
    """The call and ``extra`` more rows at 2 % more clearance in their own group."""
    base_a, base_k = _rows(call, np.arange(np.prod(np.shape(call[0][0])[:-1])))
    more_a, more_k = _rows(call, np.arange(extra))
    more_a = more_a[:7] + (more_a[7] * 1.02,) + more_a[8:]
    a = tuple(np.concatenate([x, y]) for x, y in zip(base_a, more_a))
    k = dict(base_k)
    for key, v in base_k.items():
        if isinstance(v, np.ndarray):
            k[key] = np.concatenate([v, more_k[key]])
    k["group"] = np.concatenate([np.zeros(len(base_a[0]), np.int64), np.ones(extra, np.int64)])
    return a, k


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--workbook", type=Path, default=None)
    args = ap.parse_args()
    _keep_freed_memory()
    with tempfile.TemporaryDirectory() as d:
        wb = args.workbook
        if wb is None:
            wb = Path(d) / "engine.xlsx"
            subprocess.run([sys.executable, "-m", "checker", "template", str(wb)], check=True,
                           capture_output=True, env={**os.environ, "PYTHONPATH": str(ROOT)})
        calls = _record(wb)
    heat = [c for c in calls if c[1].get("squeeze_velocity")]
    film = {c[1]["model"]: c for c in calls if not c[1].get("squeeze_velocity")}
    rm = film["reynolds_map"]
    cases = [
        ("reynolds_map 1098", rm),
        ("reynolds_map 1586", _variants(rm, 488)),
        ("reynolds_map 122", _rows(rm, np.arange(122))),
        ("closed_form 1098", film["closed_form"]),
        ("closed_form heat 1098", heat[0]),
        ("closed_form heat 61", _rows(heat[0], np.arange(61))),
    ]
    print(f"load: {os.getloadavg()[0]:.2f} (1 min), numpy {np.__version__}")
    print(f"{'batch':24s} {'median':>9s} {'min':>9s}   (processor time per call, {args.runs} runs)")
    for name, (a, k) in cases:
        ob.solve_orbit(*a, **k)  # tables built, memory touched
        times = []
        for _ in range(args.runs):
            t = time.process_time()
            ob.solve_orbit(*a, **k)
            times.append(time.process_time() - t)
        print(f"{name:24s} {statistics.median(times):8.3f}s {min(times):8.3f}s")


if __name__ == "__main__":
    main()
