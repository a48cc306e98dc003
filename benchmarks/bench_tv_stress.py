"""Benchmark of the crank vibratory stress and the class rules on the I6 example (not a test).

Run: ``PYTHONPATH=. .venv/bin/python benchmarks/bench_tv_stress.py``

The I6 template (Mendes et al. 2008, 6 cylinders, 9 TV elements, 2 load cases x 73 speeds x 48
orders) as a commercial vehicle (its own class) and as a marine engine (every class rule:
ratios, barred ranges, major criticals). Printed: the median run time of the two calculations
this adds to a check, ``tv_crank_stress`` (stress per crank section, synthesised and per
order) and ``tv_class_rules`` (limits, ratios, barred ranges, major criticals), called on the
same inputs 50 times; and the median wall time of ``checker check`` of the I6 (5 runs, in
this process after a warm-up) with and without the new rules (``--ignore TV-004,...``: the
stress is computed anyway, FAT-002 needs it).
"""

from __future__ import annotations

import statistics
import tempfile
import time
from pathlib import Path

import openpyxl

from checker import api
from checker.evaluation import graph
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content

NEW = ["TV-004", "TV-005", "TV-006", "TV-007", "TV-008", "TV-009"]


def _workbook(folder: Path, cls: str) -> Path:
    p = folder / f"i6_{cls.replace(' ', '_')}.xlsx"
    write_workbook(p, i6_content(damper_ring=True))
    wb = openpyxl.load_workbook(p)
    ws = wb["Engine"]
    row = next(r for r in range(1, ws.max_row + 1) if ws.cell(r, 1).value == "Engine class")
    ws.cell(row, 2).value = cls
    wb.save(p)
    return p


def _median(f, n: int) -> float:
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        for cls in ("commercial vehicle", "marine"):
            p = _workbook(Path(tmp), cls)
            res = api.check(p)
            q = res.outcome.quantities
            eng = res.engine
            stress = graph.CALCULATIONS["tv_crank_stress"]
            rules = graph.CALCULATIONS["tv_class_rules"]
            ins = {n: q[n] for n in stress.needs(eng)}
            t_stress = _median(lambda s=stress, e=eng, i=ins: s.func(e, i), 50)
            ins2 = {n: q[n] for n in rules.needs(eng)}
            t_rules = _median(lambda r=rules, e=eng, i=ins2: r.func(e, i), 50)
            full = _median(lambda p=p: api.check(p), 5)
            without = _median(lambda p=p: api.check(p, ignore=NEW), 5)
            print(f"I6 as {cls}: tv_crank_stress {t_stress * 1e3:.2f} ms, tv_class_rules"
                  f" {t_rules * 1e3:.2f} ms; check {full:.3f} s, without TV-004..009"
                  f" {without:.3f} s (difference {1e3 * (full - without):+.0f} ms)")


if __name__ == "__main__":
    main()
