"""Benchmark of what it takes to pass (``--remedies``) and the tolerance corners
(``--corners``) on the I4 example: whole-process ``checker check`` and ``checker report`` with
and without them.

    python benchmarks/bench_remedies.py [--runs 1] [--select JNT] [--report]

With ``--report`` the plain report and the report with remedies and corners run one after the
other ``--runs`` times (pairs), each pair's ratio printed with their median.

Each run is a fresh process; the wall time and the children's processor time (user + system,
``os.wait4``) are reported, with the number of variant evaluations and their share. Target
(issue 23): the report with remedies and corners within 2x the report without them. On a
machine shared with other work compare the processor times. Run it once, not in a loop.
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


def _run(cmd: list[str]) -> tuple[float, float]:
    """Wall time and processor time (user + sys) of a process and its children."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    t = time.perf_counter()
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t
    code = os.waitstatus_to_exitcode(status)
    if code not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} exited {code}")
    return wall, ru.ru_utime + ru.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--select", default=None, help="rule prefixes, e.g. JNT (default: all)")
    ap.add_argument("--report", action="store_true", help="also time checker report")
    args = ap.parse_args()
    exe = [sys.executable, "-m", "checker"]
    sel = ["--select", args.select] if args.select else []
    with tempfile.TemporaryDirectory() as d:
        wb = Path(d) / "engine.xlsx"
        subprocess.run(exe + ["template", str(wb)], check=True, capture_output=True,
                       env={**os.environ, "PYTHONPATH": str(ROOT)})
        rows = []
        cases = [("check", []), ("check --remedies", ["--remedies"]),
                 ("check --corners", ["--corners"]),
                 ("check --remedies --corners", ["--remedies", "--corners"])]
        for name, extra in cases:
            cmd = exe + ["check", str(wb), "--format", "json", "-o",
                         str(Path(d) / "r.json")] + sel + extra
            times = [_run(cmd) for _ in range(args.runs)]
            wall = statistics.median(t[0] for t in times)
            cpu = statistics.median(t[1] for t in times)
            evals = ""
            if not name.startswith("report") and extra:
                doc = json.loads((Path(d) / "r.json").read_text(encoding="utf-8"))
                n = sum(doc.get(k, {}).get("evaluations", 0) for k in ("remedies", "corners"))
                evals = str(n)
            rows.append((name, wall, cpu, evals))
            print(f"{name:32s} wall {wall:7.2f} s   cpu {cpu:7.2f} s   evaluations {evals}",
                  flush=True)
        if args.report:
            # the two reports one after the other, pair by pair: the machine's drift (here
            # the plain report alone varies by 30 % from run to run) then moves both
            plain = exe + ["report", str(wb), "-o", str(Path(d) / "r.pdf"), "-q"] + sel
            pairs = []
            for k in range(args.runs):
                pairs.append((_run(plain), _run(plain + ["--remedies", "--corners"])))
                (pw, _), (ww, _) = pairs[-1]
                print(f"pair {k + 1}: report {pw:6.2f} s, with remedies and corners"
                      f" {ww:6.2f} s: {ww / pw:.2f}x", flush=True)
            for i, name in enumerate(("report", "report --remedies --corners")):
                wall = statistics.median(p[i][0] for p in pairs)
                cpu = statistics.median(p[i][1] for p in pairs)
                rows.append((name, wall, cpu, ""))
                print(f"{name:32s} wall {wall:7.2f} s   cpu {cpu:7.2f} s   (median of"
                      f" {len(pairs)})", flush=True)
            ratios = [p[1][0] / p[0][0] for p in pairs]
            print(f"report ratio per pair: median {statistics.median(ratios):.2f}x,"
                  f" range {min(ratios):.2f}-{max(ratios):.2f}x")
        base = {r[0]: r for r in rows}
        for a, b in (("check --remedies --corners", "check"),
                     ("report --remedies --corners", "report")):
            if a in base and b in base:
                print(f"{a} / {b}: wall {base[a][1] / base[b][1]:.2f}x,"
                      f" cpu {base[a][2] / base[b][2]:.2f}x (target <= 2x for the report)")
    load = os.getloadavg()
    print(f"load average {load[0]:.1f} {load[1]:.1f} {load[2]:.1f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
