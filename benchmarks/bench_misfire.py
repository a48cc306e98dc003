"""What the misfire case adds to a check of the I6 example (issue 46: <= 0.2 s; not a test).

Run: ``python benchmarks/bench_misfire.py [--repeat 7]``

The I6 example (``checker template --engine i6``) is checked as an ``industrial`` engine, the
class the misfire case is judged for, with the misfire calculations (nodes
``misfire_response``: the motored trace, the cylinder torques of the firing and motored
traces, one factorisation per speed and order for every misfiring cylinder, the synthesis of
every element's torque; ``misfire_crank_stress``) timed inside the check
(``time.process_time`` around each node, the median over ``--repeat`` checks in one process
after a warm-up check). Printed: the nodes' processor time, the whole check's, and the
misfire's share. Measured (shared 2-core machine): 47 ms of an 884 ms check (5.3 %).
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import openpyxl

from checker import api
from checker.evaluation import graph
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content


def _industrial_i6(folder: Path) -> Path:
    path = folder / "i6.xlsx"
    write_workbook(path, i6_content(damper_ring=True))
    wb = openpyxl.load_workbook(path)
    ws = wb["Engine"]
    for row in ws.iter_rows(min_row=1):
        if str(row[0].value).strip().lower() == "engine class":
            row[1].value = "industrial"
    wb.save(path)
    return path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    calcs = [c for c in graph.CALCULATIONS.values() if c.module == "misfire"]
    spent: list[float] = []

    def timed(inner):
        def run(engine, inputs):
            t0 = time.process_time()
            try:
                return inner(engine, inputs)
            finally:
                spent.append(time.process_time() - t0)
        return run

    for calc in calcs:
        object.__setattr__(calc, "func", timed(calc.func))
    with tempfile.TemporaryDirectory() as tmp:
        path = _industrial_i6(Path(tmp))
        api.check(path)  # warm-up (imports, caches)
        spent.clear()
        whole = []
        for _ in range(args.repeat):
            t0 = time.process_time()
            api.check(path)
            whole.append(time.process_time() - t0)
    per_check = [sum(spent[i:i + len(calcs)]) for i in range(0, len(spent), len(calcs))]
    node = statistics.median(per_check)
    total = statistics.median(whole)
    print(f"misfire nodes ({', '.join(c.name for c in calcs)}): {node * 1e3:.1f} ms processor"
          f" time (median of {len(per_check)} checks)")
    print(f"whole check:  {total * 1e3:.0f} ms processor time; misfire share"
          f" {100 * node / total:.1f} %")


if __name__ == "__main__":
    main()
