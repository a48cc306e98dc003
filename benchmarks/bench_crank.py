"""Cost of describing the crank by its geometry (issue 33): what sheet Crank adds to a check.

    python benchmarks/bench_crank.py [--repeat 20]

Per example (I4, I6, V8): the engine builder with the example's sheet Crank against the same
workbook typed without it (sheets Crank and CrankEnds removed, the journal sizes and web
thickness typed where they were before), the derivations alone (mass properties of every part
and the throw stiffness), and the crank module's node; medians of ``--repeat`` runs, wall time
in one process. The derivations are closed forms and a 32-point quadrature per interval
(:mod:`checker.calc.crank_geometry`), so their error is rounding: nothing to trade here.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import openpyxl

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker import api  # noqa: E402
from checker.description import crank_derive as cd  # noqa: E402
from checker.description.engine import build_engine  # noqa: E402
from checker.workbook.example import write_workbook  # noqa: E402
from checker.workbook.example_data import load_example  # noqa: E402
from checker.workbook.loader import read_workbook  # noqa: E402
from tests.helpers import without_crank  # noqa: E402


def _median(f, repeat: int) -> float:
    f()
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=20)
    args = ap.parse_args(argv)
    print("| example | build engine with Crank [ms] | without [ms] | derivations [ms] |"
          " crank node [ms] |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for e in ("i4", "i6", "v8"):
            p = Path(tmp) / f"{e}.xlsx"
            write_workbook(p, load_example(e))
            q = Path(tmp) / f"{e}-plain.xlsx"
            wb = openpyxl.load_workbook(p)
            without_crank(wb)
            if e == "v8":  # its torsional model is derived: type it as the derived one
                eng = build_engine(read_workbook(p, raise_errors=False))
                ws = wb["TVModel"]
                head = [c.value for c in ws[1]]
                ji, ki = head.index("inertia") + 1, head.index("stiffness to next") + 1
                for r, s in enumerate(eng.tv_model, start=3):
                    ws.cell(r, ji).value = s.inertia
                    ws.cell(r, ki).value = s.stiffness
            wb.save(q)
            with_crank = read_workbook(p, raise_errors=False)
            plain = read_workbook(q, raise_errors=False)
            t_with = _median(lambda d=with_crank: build_engine(d), args.repeat)
            t_plain = _median(lambda d=plain: build_engine(d), args.repeat)
            eng = build_engine(with_crank)

            def derive(c=eng.crank):
                c.__dict__.pop("mass_properties", None)
                _ = c.mass_properties
                cd.throw_stiffness(c)

            t_derive = _median(derive, args.repeat)
            node = api.check(eng).outcome.timings.get("crank", float("nan"))
            print(f"| {e.upper()} | {t_with * 1e3:.2f} | {t_plain * 1e3:.2f} |"
                  f" {t_derive * 1e3:.2f} | {node * 1e3:.2f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
