"""Benchmark of the heat memo (:mod:`checker.modules.heat_memo`) on the I4 example: the bearing
heat balance of a variant that moves one bearing (its clearance), cold and with the memo
holding the nominal engine's bearings; and a variant whose bearings were all solved before.

    python benchmarks/bench_heat_memo.py [--runs 5]

Medians of the processor time (the machine may be shared); the rows solved and reused.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import tempfile
import time
from pathlib import Path

from checker.description.engine import load_engine
from checker.evaluation import graph
from checker.modules import bearing_performance, heat_memo
from checker.workbook.example import example_content, write_workbook


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "engine.xlsx"
        write_workbook(p, example_content())
        engine = load_engine(p)
    graph.ensure_registered()
    loads = {"loads.bearing_load": graph.run(engine, ["loads.bearing_load"], cache={})
             .quantities["loads.bearing_load"]}

    def moved(name: str, factor: float):
        rows = tuple(dataclasses.replace(b, clearance=b.clearance * factor)
                     if b.name == name else b for b in engine.bearings)
        return dataclasses.replace(engine, bearings=rows)

    def timed(e, warm: bool) -> float:
        heat_memo.clear()
        if warm:
            bearing_performance.bearing_heat_balance(engine, loads)
        t = time.process_time()
        bearing_performance.bearing_heat_balance(e, loads)
        return time.process_time() - t

    cases = [("nominal again (all 9 rows reused)", engine),
             ("M3 clearance x 1.1 (1 row solved)", moved("M3", 1.1)),
             ("BE2 clearance x 1.1 (big ends solved)", moved("BE2", 1.1))]
    for label, e in cases:
        cold = statistics.median(timed(e, False) for _ in range(args.runs))
        warm = statistics.median(timed(e, True) for _ in range(args.runs))
        print(f"{label:40s} cold {cold:6.3f} s   memo {warm:6.3f} s   "
              f"(rows solved {heat_memo.stats['solved'] - 9}, reused {heat_memo.stats['hits']})")


if __name__ == "__main__":
    main()
