"""Benchmark of `checker report` and `checker check`: whole-process times and time per stage.

    python benchmarks/bench_report.py [--runs 3] [--engines i4,i6]

For each example engine (the I4 of Bell, Ricardo 2013 and the I6 of Mendes et al. 2008,
written by ``checker template``) it measures, each in a fresh process, ``--runs`` times:

* ``checker check`` whole process (process start to exit, output to a file);
* ``checker report`` whole process (process start to PDF written);
* a stage-timing run of the same report: imports, analysis, PDF engine import (overlapping
  the figure drawing in worker processes), figures, HTML, PDF layout, results workbook (written
  by a forked process during the layout: its wall time is the wait after the layout, its
  processor time the child's), PDF write: wall time and processor time per stage.

It prints the medians, the page count and the targets of issue 25 (I4 report <= 8 s, stretch
5 s; check <= 1.5 s). On a machine shared with other work, compare processor times: the wall
time of a stage grows with the load, its processor time much less. Run it once, not in a loop.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TARGETS = {"i4": 8.0, "i6": 8.0}
STRETCH = {"i4": 5.0}
CHECK_TARGET = 1.5

DRIVER = r"""
import json, sys, time
t0 = time.perf_counter(); c0 = time.process_time()
from checker import api
from checker.report import render
t1 = time.perf_counter(); c1 = time.process_time()
res = api.check(sys.argv[1])
t2 = time.perf_counter(); c2 = time.process_time()
rep = render.build_report(res, want_html=False)
with open(sys.argv[2], "wb") as f:
    f.write(rep.pdf)
t3 = time.perf_counter()
wall = {"imports": t1 - t0, "analysis": t2 - t1, **rep.stages}
cpu = {"imports": c1 - c0, "analysis": c2 - c1, **rep.cpu}
print(json.dumps({"wall": wall, "cpu": cpu, "pages": rep.pages, "total": t3 - t0}))
"""


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return env


CPU: list[float] = []
"""Processor time (user + system) of each timed process with its children [s]."""


def _children_cpu() -> float:
    import resource

    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _timed(cmd: list[str]) -> float:
    t, c = time.perf_counter(), _children_cpu()
    r = subprocess.run(cmd, env=_env(), capture_output=True, text=True)
    dt = time.perf_counter() - t
    CPU.append(_children_cpu() - c)
    if r.returncode not in (0, 1):
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}): {r.stderr[-2000:]}")
    return dt


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--engines", default="i4,i6")
    args = ap.parse_args()
    py = sys.executable
    load0 = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    out: dict[str, dict] = {}
    with tempfile.TemporaryDirectory() as d:
        for eng in args.engines.split(","):
            wb = Path(d) / f"engine-{eng}.xlsx"
            subprocess.run([py, "-m", "checker.cli", "template", str(wb), "--engine", eng,
                            "--force"], env=_env(), check=True, capture_output=True)
            pdf = Path(d) / f"{eng}.pdf"
            check, report, stage_runs, report_cpu, check_cpu = [], [], [], [], []
            for _ in range(args.runs):
                check.append(_timed([py, "-m", "checker.cli", "check", str(wb), "-o",
                                     str(Path(d) / "out.txt")]))
                check_cpu.append(CPU[-1])
                report.append(_timed([py, "-m", "checker.cli", "report", str(wb), "-o",
                                      str(pdf), "--quiet"]))
                report_cpu.append(CPU[-1])
                r = subprocess.run([py, "-c", DRIVER, str(wb), str(pdf)], env=_env(),
                                   capture_output=True, text=True, check=True)
                stage_runs.append(json.loads(r.stdout.strip().splitlines()[-1]))
            stages = list(stage_runs[0]["wall"])
            out[eng] = {
                "check": statistics.median(check), "report": statistics.median(report),
                "report_cpu": statistics.median(report_cpu),
                "check_cpu": statistics.median(check_cpu),
                "pages": stage_runs[0]["pages"],
                "wall": {s: statistics.median(x["wall"][s] for x in stage_runs) for s in stages},
                "cpu": {s: statistics.median(x["cpu"][s] for x in stage_runs) for s in stages},
            }
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"median of {args.runs} runs; load average {load0:.1f} at the start, {load:.1f} at"
          f" the end, on {os.cpu_count()} cores. cpu: processor time (user + system) of the"
          " process and its child processes (figure workers, results workbook), the number"
          " to compare on a shared machine\n")
    print("| stage | " + " | ".join(f"{e} wall [s] | {e} cpu [s]" for e in out) + " |")
    # processor time is the number to compare on a shared machine (the wall time of a stage
    # grows with the load); the sum of the stages' processor times is the report's work
    print("|---|" + "---|---|" * len(out))
    for s in next(iter(out.values()))["wall"]:
        print(f"| {s} | " + " | ".join(f"{v['wall'][s]:.2f} | {v['cpu'][s]:.2f}"
                                       for v in out.values()) + " |")
    print("| whole process (`checker report`) | " + " | ".join(
        f"{v['report']:.2f} | {v['report_cpu']:.2f}" for v in out.values()) + " |")
    print("| whole process (`checker check`) | " + " | ".join(
        f"{v['check']:.2f} | {v['check_cpu']:.2f}" for v in out.values()) + " |")
    print()
    for e, v in out.items():
        tgt = TARGETS.get(e)
        st = STRETCH.get(e)
        print(f"{e}: report whole process {v['report']:.2f} s (target {tgt} s"
              f" {'met' if tgt and v['report'] <= tgt else 'NOT met'}"
              + (f", stretch {st} s {'met' if v['report'] <= st else 'not met'}" if st else "")
              + f"), processor time {v['report_cpu']:.2f} s, {v['pages']} pages;"
              f" check whole process {v['check']:.2f} s (target {CHECK_TARGET} s"
              f" {'met' if v['check'] <= CHECK_TARGET else 'NOT met'})")


if __name__ == "__main__":
    main()
