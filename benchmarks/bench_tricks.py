"""What each trick that patches a dependency or the interpreter saves, alone.

    python benchmarks/bench_tricks.py [--pairs 5] [--engine i4] [--only NAME,...]

Every trick lives in ``checker/plumbing`` (docs/architecture.md). For each one this runs
`checker report` on the example workbook (``checker template --engine``) as a whole process,
alternately with every trick in place and with that one trick undone (the module attribute
the command calls replaced by the plain way, before the command starts: its forked processes
inherit it), ``--pairs`` times, and prints per trick the median wall time and processor time
(the command and every process it started: ``RUSAGE_CHILDREN``) of both, and the median of
the pairs' ratios without/with. On a machine shared with other work, the processor time and
the pairs' ratios hold when the absolute wall times drift; the saving quoted in
docs/benchmarks.md is ``1 - with/without`` of the median processor-time ratio. A trick that
saves less than :data:`KEEP_ABOVE` of the command is dropped (issue 44).

Byte code is cached (``PYTHONPYCACHEPREFIX`` in a temporary folder), as after an install.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KEEP_ABOVE = 0.03
"""A trick is kept when it saves at least this share of the command's time."""

UNDO = {
    "frame_stack": "from checker.plumbing import frame_stack as m; m._OUTER = None",
    "gc_tuning": "from checker.plumbing import gc_tuning as m; "
                 "m.fewer_collections = lambda *a, **k: None",
    "pdf_compression": "import contextlib; from checker.plumbing import pdf_compression as m; "
                       "m.flate_level = lambda level: contextlib.nullcontext()",
    "pdf_engine_import": "from checker.plumbing import pdf_engine_import as m\n"
                         "def plain():\n    import weasyprint\n    return weasyprint\n"
                         "m.import_weasyprint = plain",
    "matplotlib_patches": "import contextlib; from checker.plumbing import matplotlib_patches"
                          " as m; m.property_lists_unwritten = contextlib.nullcontext",
}
"""Per trick: the code that undoes it before the command starts (the plain way)."""

DRIVER = "import sys\n{undo}\nfrom checker.cli import run\nsys.argv = {argv!r}\nrun()\n"


def _run(code: str, env: dict) -> tuple[float, float, int]:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if p.returncode not in (0, 1):
        raise RuntimeError(p.stderr.decode(errors="replace")[-2000:])
    return wall, cpu, p.returncode


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--engine", default="i4")
    ap.add_argument("--only", default=",".join(UNDO))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, PYTHONPYCACHEPREFIX=str(Path(tmp) / "pycache"),
                   PYTHONPATH=str(ROOT))
        book = Path(tmp) / "engine.xlsx"
        subprocess.run([sys.executable, "-m", "checker", "template", "--engine", args.engine,
                        str(book)], env=env, check=True, capture_output=True)
        argv = ["checker", "report", str(book), "-o", str(Path(tmp) / "engine.pdf"), "-q"]
        with_all = DRIVER.format(undo="", argv=argv)
        _run(with_all, env)  # warm-up: byte code, font cache
        print(f"`checker report` on the {args.engine.upper()}, {args.pairs} pairs"
              " (with every trick / with the trick undone):")
        print(f"{'trick':20s} {'wall with':>9s} {'without':>8s} {'cpu with':>9s} {'without':>8s}"
              f" {'wall saved':>10s} {'cpu saved':>9s}  verdict")
        for name in args.only.split(","):
            without = DRIVER.format(undo=UNDO[name], argv=argv)
            w, wo = [], []
            for _ in range(args.pairs):
                w.append(_run(with_all, env))
                wo.append(_run(without, env))
            wall_saved = 1 - statistics.median(a[0] / b[0] for a, b in zip(w, wo))
            cpu_saved = 1 - statistics.median(a[1] / b[1] for a, b in zip(w, wo))
            verdict = "keep" if max(wall_saved, cpu_saved) >= KEEP_ABOVE else "drop"
            print(f"{name:20s} {statistics.median(a[0] for a in w):9.2f}"
                  f" {statistics.median(b[0] for b in wo):8.2f}"
                  f" {statistics.median(a[1] for a in w):9.2f}"
                  f" {statistics.median(b[1] for b in wo):8.2f}"
                  f" {wall_saved:10.1%} {cpu_saved:9.1%}  {verdict}", flush=True)


if __name__ == "__main__":
    main()
