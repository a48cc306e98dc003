"""Regenerate the finite-length mobility map ``checker/calc/data/reynolds_map.npz``.

    python scripts/make_reynolds_map.py [--out PATH] [--derive-only]

Solves the finite-length Reynolds LCP (:mod:`checker.calc.reynolds`, default grid) on the
map's nodes (:mod:`checker.calc.reynolds_map`: 13 width ratios x 18 eccentricities x 33
directions; about 5 minutes on one core of the project machine) and stores the solver output
together with the rows derived from it for the lookup tables (:func:`derive_rows`, about a
second). ``--derive-only`` keeps the stored solver output and re-derives the rows (after a
change of the lookup grid). ``tests/calc/test_reynolds_map.py`` regenerates a slice and
compares it with the stored file.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker.calc import reynolds_map as rm  # noqa: E402

RAW_KEYS = ("l_over_d", "eps", "alpha", "w", "p_max", "q_side", "grid")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=rm.MAP_FILE)
    ap.add_argument("--derive-only", action="store_true",
                    help="re-derive the lookup rows from the solver output already in --out")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if args.derive_only:
        with np.load(args.out) as f:
            data = {k: f[k] for k in RAW_KEYS}
    else:
        data = rm.generate_map(progress=True)
    data.update(rm.derive_rows(data))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(args.out, **data)
    print(f"wrote {args.out} in {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
