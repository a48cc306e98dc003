"""Study throughput: 100-variant clearance study (BRG-001..006, loads reused) and a 100-variant
Latin hypercube over bore, stroke, rod length, piston mass and a bearing width (all rules),
local worker processes vs a 2-worker Dask LocalCluster; per-variant cost vs a single check.

    python benchmarks/bench_study.py [--variants 100] [--skip-dask]

Prints one line per case: variants, wall time, time per variant, ratio to one whole check.
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
import time
from pathlib import Path

from checker import api
from checker.study.run import run_study
from checker.study.spec import load_study
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content

FILM_AND_LOAD = ["BRG-001", "BRG-002", "BRG-003", "BRG-004", "BRG-005", "BRG-006"]
"""Specific load and film thickness (the bearing flow/temperature rules BRG-007..009 add the
heat balance, about 2 s per variant on this machine)."""

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


def _time_study(text: str, wb: Path, tmp: Path, name: str, **kw) -> tuple[float, int]:
    st = tmp / f"{name}.toml"
    st.write_text(text, encoding="utf-8")
    out = tmp / f"out-{name}"
    shutil.rmtree(out, ignore_errors=True)
    t0 = time.perf_counter()
    run = run_study(load_study(st), wb, out, **kw)
    return time.perf_counter() - t0, len(run.records)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--variants", type=int, default=100)
    ap.add_argument("--skip-dask", action="store_true")
    a = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="bench-study-"))
    wb = tmp / "engine.xlsx"
    write_workbook(wb, example_content())
    write_workbook(tmp / "engine-i6.xlsx", i6_content())
    t0 = time.perf_counter()
    api.check(wb)
    single_all = time.perf_counter() - t0
    t0 = time.perf_counter()
    api.check(wb, select=FILM_AND_LOAD)
    single_brg = time.perf_counter() - t0
    print(f"single check (in process): all rules {single_all:.2f} s, BRG-001..006"
          f" {single_brg:.2f} s")
    rows = []
    for label, text, single, kw in [
        ("clearance study, BRG-001..006, local", CLEARANCE, single_brg, {}),
        ("LHS 5 parameters, all rules, local", LHS, single_all, {}),
        *([] if a.skip_dask else [("LHS 5 parameters, all rules, Dask LocalCluster(2)", LHS,
                                   single_all, {"dask": "local", "workers": 2})]),
    ]:
        sec, n = _time_study(text.format(n=a.variants), wb, tmp, label.split(",")[0][:3]
                             + str(len(rows)), **kw)
        rows.append((label, n, sec, sec / n, sec / n / single))
        print(f"{label:<52} {n:4d} variants {sec:7.1f} s  {sec / n * 1e3:6.0f} ms/variant"
              f"  {sec / n / single:5.2f} x single check", flush=True)
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
