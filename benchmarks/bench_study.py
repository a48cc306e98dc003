"""Study throughput and memory (issue 25): the whole ``checker study`` command on the example I4.

    python benchmarks/bench_study.py [--variants 100] [--repeat 1] [--workers 2]
                                     [--before /path/to/old/checker/tree] [--only a,b,c,d]

Cases (each the whole process: start-up, the variants, results.parquet/xlsx and the study PDF):

* (a) ``clearance``: 100-variant Latin hypercube of the main bearings' radial clearance,
  BRG-001..006 (specific load and film thickness; the heat balance BRG-007..009 is not
  selected), 2 local workers. Target <= 30 s.
* (b) ``geometry``: 100-variant Latin hypercube over bore, stroke, connecting-rod length, piston
  mass and main-bearing width, every rule, 2 local workers. Target <= 90 s.
* (c) ``geometry, Dask``: the same on a 2-worker Dask ``LocalCluster``. Target <= 1.3 x (b).
* (d) ``joints 200 / 1000``: a cheap study (JNT rules, nose torque and friction) at 200 and
  1000 variants: the peak resident memory of the whole process tree (sampled every 0.2 s)
  must not grow with the number of variants (results are streamed to disk).

Each line gives the wall time, the CPU time of the process and its workers (user + system,
summed over processes: the better measure while other jobs share the machine; on an idle
machine wall ~ CPU / workers + the serial parts) and the 1-minute load average before and
after. ``--before`` runs the same cases with an earlier source tree first on ``PYTHONPATH``.
The study-phase time (``... variants in N s``) is taken from the command's own last line.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

FILM_AND_LOAD = ["BRG-001", "BRG-002", "BRG-003", "BRG-004", "BRG-005", "BRG-006"]
"""Specific load and film thickness (the bearing flow/temperature rules BRG-007..009 add the
heat balance)."""

CLEARANCE = """
[study]
name = "bench: clearance"
design = "latin-hypercube"
samples = {n}
seed = 1
select = ["BRG-001", "BRG-002", "BRG-003", "BRG-004", "BRG-005", "BRG-006"]

[[parameter]]
name = "main clearance"
sheet = "Bearings"
where = {{ type = "main" }}
column = "radial clearance"
unit = "um"
range = [16, 40]
"""

LHS = """
[study]
name = "bench: geometry"
design = "latin-hypercube"
samples = {n}
seed = 2

[[parameter]]
sheet = "Engine"
row = "Bore"
unit = "mm"
range = [78, 84]

[[parameter]]
sheet = "Engine"
row = "Stroke"
unit = "mm"
range = [84, 90]

[[parameter]]
sheet = "Engine"
row = "Connecting rod length"
unit = "mm"
range = [135, 150]

[[parameter]]
sheet = "Engine"
row = "Piston assembly mass"
unit = "g"
range = [300, 420]

[[parameter]]
name = "main bearing width"
sheet = "Bearings"
where = {{ type = "main" }}
column = "effective length"
unit = "mm"
range = [16, 21]
"""

JOINTS = """
[study]
name = "bench: joints"
design = "latin-hypercube"
samples = {n}
seed = 3
select = ["JNT"]

[[parameter]]
name = "nose torque"
sheet = "Joints"
row = "crank nose"
column = "tightening torque"
unit = "N m"
range = [250, 400]

[[parameter]]
name = "nose friction"
sheet = "Joints"
row = "crank nose"
column = "friction coefficient"
unit = "-"
range = [0.08, 0.16]
"""


def _tree_rss_kb(pid: int) -> int:
    """Summed VmRSS of ``pid`` and its descendants (Linux /proc)."""
    kids: dict[int, list[int]] = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
                kids.setdefault(ppid, []).append(int(d))
            except (OSError, ValueError, IndexError):
                pass
    total, stack = 0, [pid]
    while stack:
        p = stack.pop()
        stack.extend(kids.get(p, []))
        try:
            with open(f"/proc/{p}/status") as f:
                total += next((int(line.split()[1]) for line in f
                               if line.startswith("VmRSS:")), 0)
        except OSError:
            pass
    return total


def run_case(code: Path, wb: Path, study: Path, out: Path, extra: list[str]) -> dict:
    """One whole ``checker study`` process: wall, CPU (process + workers), peak tree RSS,
    load before/after, the study phase's own seconds."""
    shutil.rmtree(out, ignore_errors=True)
    env = {**os.environ, "PYTHONPATH": str(code)}
    cmd = [sys.executable, "-m", "checker", "study", str(wb), str(study), "-o", str(out),
           "--no-progress", *extra]
    load0 = os.getloadavg()[0]
    r0 = os.times()
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=code, env=env, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True)
    peak = 0
    linux = sys.platform.startswith("linux")
    while p.poll() is None:
        if linux:
            peak = max(peak, _tree_rss_kb(p.pid))
        time.sleep(0.2)
    err = p.stderr.read() if p.stderr else ""
    wall = time.perf_counter() - t0
    r1 = os.times()
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{err}")
    m = re.search(r"variants \(.*\) in ([0-9.]+) s", err)
    return {"wall": wall, "cpu": (r1.children_user - r0.children_user)
            + (r1.children_system - r0.children_system), "peak_mb": peak / 1024,
            "load": (load0, os.getloadavg()[0]), "study_s": float(m.group(1)) if m else None}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--variants", type=int, default=100)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=1, help="runs per case (median)")
    ap.add_argument("--before", type=Path, default=None,
                    help="earlier checker source tree (its folder holding 'checker/')")
    ap.add_argument("--only", default="a,b,c,d", help="cases to run, e.g. 'a,d'")
    a = ap.parse_args()
    sys.path.insert(0, str(ROOT))
    from checker.workbook.example import example_content, write_workbook

    tmp = Path(tempfile.mkdtemp(prefix="bench-study-"))
    wb = tmp / "engine.xlsx"
    write_workbook(wb, example_content())
    w = ["--workers", str(a.workers)]
    n = a.variants
    cases = [("a", f"clearance, BRG-001..006, {n} variants, local", CLEARANCE, n, w),
             ("b", f"geometry LHS, every rule, {n} variants, local", LHS, n, w),
             ("c", f"geometry LHS, every rule, {n} variants, Dask LocalCluster", LHS, n,
              [*w, "--dask", "local"]),
             ("d", "joints (JNT), 200 variants, local", JOINTS, 200, w),
             ("d", "joints (JNT), 1000 variants, local", JOINTS, 1000, w)]
    only = set(a.only.split(","))
    trees = ([("before", a.before.resolve())] if a.before else []) + [("now", ROOT)]
    print(f"{os.cpu_count()} cores; whole `checker study` process, median of {a.repeat}\n")
    print("| case | tree | wall [s] | variants [s] | CPU [s] | peak RSS [MB] | load before"
          " -> after |")
    print("|---|---|---|---|---|---|---|")
    for key, label, text, size, extra in cases:
        if key not in only:
            continue
        study = tmp / f"{key}-{size}.toml"
        study.write_text(text.format(n=size), encoding="utf-8")
        for tree, code in trees:
            runs = [run_case(code, wb, study, tmp / "out", extra) for _ in range(a.repeat)]
            med = {k: statistics.median(r[k] for r in runs)
                   for k in ("wall", "cpu", "peak_mb")}
            st = [r["study_s"] for r in runs if r["study_s"] is not None]
            print(f"| ({key}) {label} | {tree} | {med['wall']:.1f} |"
                  f" {statistics.median(st) if st else float('nan'):.1f} | {med['cpu']:.1f} |"
                  f" {med['peak_mb']:.0f} | {runs[0]['load'][0]:.1f} -> {runs[-1]['load'][1]:.1f}"
                  " |", flush=True)
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
