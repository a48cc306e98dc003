"""Cost of ``checker new`` with its sizing loop (issue 47): the I4 brief of the tests.

    python benchmarks/bench_new.py [--brief FILE] [--repeat 1]

Runs ``checker new`` as a user does (a separate process), once open loop (``--no-iterate``)
and once with the loop, and prints per run the wall time and the process's processor time
(user + system of the command and its children: on a shared machine the wall time also
counts the other processes' turns), and the loop's rounds, evaluations and results failed
before and after it (the command's own console line). Budget (issue 47): the I4 with its
loop in at most 30 s on the project's 2-core machine.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

I4 = ('cylinders = 4\nlayout = "inline"\nbore = "86 mm"\nstroke = "94.6 mm"\n'
      'rated_power = "110 kW"\nrated_speed = "6000 rpm"\nmax_speed = "7000 rpm"\n'
      'peak_pressure = "85 bar"\nfuel = "gasoline"\n')


def run(brief: Path, out: Path, *extra: str) -> tuple[float, float, str]:
    """Wall and processor time [s] of one ``checker new``, and its console output."""
    t0, c0 = time.perf_counter(), os.times()
    r = subprocess.run([sys.executable, "-m", "checker", "new", str(out), "--brief",
                        str(brief), "--force", *extra], capture_output=True, text=True,
                       cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
    c1 = os.times()
    if r.returncode != 0:
        raise SystemExit(r.stderr)
    cpu = (c1.children_user - c0.children_user) + (c1.children_system - c0.children_system)
    return time.perf_counter() - t0, cpu, r.stderr


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--brief", type=Path, default=None)
    ap.add_argument("--repeat", type=int, default=1)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        brief = a.brief or Path(d) / "i4.toml"
        if a.brief is None:
            brief.write_text(I4)
        for label, extra in (("open loop (--no-iterate)", ("--no-iterate",)),
                             ("with the sizing loop", ())):
            for _ in range(a.repeat):
                wall, cpu, err = run(brief, Path(d) / "new.xlsx", *extra)
                m = re.search(r"sizing loop: .*", err)
                print(f"{label}: {wall:.1f} s wall, {cpu:.1f} s processor"
                      + (f"; {m.group(0)}" if m else ""))


if __name__ == "__main__":
    main()
