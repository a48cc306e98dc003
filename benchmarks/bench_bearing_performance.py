"""Bearing oil flow, friction and film temperature: run time against error, and the cost of
the module in the whole check.

    python benchmarks/bench_bearing_performance.py [--no-check]

1. Heat-balance orbit resolution (RK steps per cycle of the short-bearing orbits that the heat
   balance iterates on): effective film temperature, cycle-mean friction power and oil flow of
   every bearing, load case and speed against 720 steps; time of the heat-balance calculation;
   orbit evaluations to converge (tolerance 0.1 K).
2. Whole ``checker check`` (wall time of the process, median of 3) of each example engine with
   every rule, and with the bearing-performance rules BRG-007..009 ignored (the module is then
   skipped), to show the work a case does not need is not done.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker.description.engine import load_engine  # noqa: E402
from checker.evaluation import graph  # noqa: E402
from checker.modules import bearing_performance as bpm  # noqa: E402
from checker.workbook.example import example_content, write_workbook  # noqa: E402
from checker.workbook.example_i6 import i6_content  # noqa: E402

WANTED = ("bearing.film_temperature", "bearing.friction_power", "bearing.oil_flow")


def _run(engine, steps: int) -> tuple[dict, float, int]:
    bpm.STEPS_PER_CYCLE = steps
    cache: dict = {}
    out = graph.run(engine, ["loads.bearing_load"], cache=cache)
    t0 = time.perf_counter()
    out = graph.run(engine, list(WANTED), cache=cache)
    dt = time.perf_counter() - t0
    q = out.quantities
    return ({k: q[k].values for k in WANTED}, dt,
            q["bearing.film_temperature"].detail.evaluations or 0)


def resolution(path: Path, label: str) -> None:
    engine = load_engine(path)
    default = bpm.STEPS_PER_CYCLE
    ref, t_ref, _ = _run(engine, 720)
    print(f"\n{label}: heat-balance orbit steps per cycle vs 720 steps ({t_ref:.2f} s)")
    print("| steps | time [s] | evaluations | max |dT_eff| [K] | max rel. friction power |"
          " max rel. oil flow |")
    print("|---|---|---|---|---|---|")
    for steps in (90, 180, 360):
        vals, dt, ev = _run(engine, steps)
        dtemp = np.nanmax(np.abs(vals[WANTED[0]] - ref[WANTED[0]]))
        dp = np.nanmax(np.abs(vals[WANTED[1]] / ref[WANTED[1]] - 1))
        dq = np.nanmax(np.abs(vals[WANTED[2]] / ref[WANTED[2]] - 1))
        mark = " (default)" if steps == default else ""
        print(f"| {steps}{mark} | {dt:.2f} | {ev} | {dtemp:.3f} | {dp:.2e} | {dq:.2e} |")
    bpm.STEPS_PER_CYCLE = default


def whole_check(path: Path, label: str) -> None:
    exe = [sys.executable, "-m", "checker.cli", "check", str(path), "--format", "json",
           "--no-timings", "-o", str(path.with_suffix(".json"))]
    rows = []
    for name, extra in (("all rules", []),
                        ("without BRG-007..009", ["--ignore", "BRG-007", "--ignore", "BRG-008",
                                                  "--ignore", "BRG-009"])):
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            subprocess.run(exe + extra, check=False, capture_output=True)
            times.append(time.perf_counter() - t0)
        rows.append((name, statistics.median(times)))
    print(f"\n{label}: whole check (process wall time, median of 3)")
    print("| rules | time [s] |")
    print("|---|---|")
    for name, t in rows:
        print(f"| {name} | {t:.2f} |")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-check", action="store_true", help="skip the whole-check timing")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        wbs = {"I4": Path(tmp) / "i4.xlsx", "I6": Path(tmp) / "i6.xlsx"}
        write_workbook(wbs["I4"], example_content())
        write_workbook(wbs["I6"], i6_content())
        for label, p in wbs.items():
            resolution(p, label)
        if not args.no_check:
            for label, p in wbs.items():
                whole_check(p, label)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
