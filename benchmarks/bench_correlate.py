"""Benchmark of ``checker correlate``'s calibration on the I6 example (not a test).

Run: ``.venv/bin/python benchmarks/bench_correlate.py``

Case: the I6 example (Mendes et al. 2008 chain, assumed viscous damper) with its silicone
given a shear modulus of 150 kPa (Maxwell coupling, so the damper has a stiffness); a
measurement at the crank nose, full load, 10 speeds 1000..2800 rpm, 12 orders 3..8.5,
synthesised from the model with the damper damping -30 % and the damper stiffness +8 % and a
relative Gaussian error of 0, 1, 3 and 10 % on every amplitude (seed 1). The fit moves the
damper damping, the damper stiffness and the crank damping.

Printed per noise level: wall time of the whole calibration in this process (reading both
files, the model at the measured speeds through the check's graph, the bounded least-squares
fit, the comparison), of the fit alone, the forced-response solves, and the error of each
recovered factor against the true one. Then the command end to end (``checker correlate``
in a fresh process with the PDF, the JSON and the calibrated copy). Target (issue 45):
<= 10 s for the 10-speed, 12-order calibration.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

TRUE = {"damper_damping": 0.70, "damper_stiffness": 1.08, "crank_damping": 1.0}
SPEEDS_RPM = np.linspace(1000.0, 2800.0, 10)
ORDERS = [3.0 + 0.5 * k for k in range(12)]


def _workbook(folder: Path) -> Path:
    from checker.workbook.example import write_workbook
    from checker.workbook.example_i6 import i6_content

    content = i6_content(damper_ring=True)
    content["Damper"].append(("Silicone shear modulus", 150, "kPa", "benchmark"))
    p = folder / "i6.xlsx"
    write_workbook(p, content)
    return p


def _measurement(folder: Path, wb: Path, noise: float) -> Path:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from tests.correlation.synth import perturbed_tracks

    sub = folder / f"noise{noise:g}"
    sub.mkdir(exist_ok=True)
    m, _ = perturbed_tracks(sub, wb, "crank nose", SPEEDS_RPM, ORDERS,
                            {k: v for k, v in TRUE.items() if v != 1.0}, noise)
    return m


def main() -> None:
    from checker import correlation as cr
    from checker.correlation import fit as ft

    with tempfile.TemporaryDirectory() as d:
        folder = Path(d)
        wb = _workbook(folder)
        print(f"I6, crank nose, {SPEEDS_RPM.size} speeds x {len(ORDERS)} orders; true factors"
              f" {TRUE}")
        print(f"{'noise':>6} {'total s':>8} {'fit s':>6} {'solves':>6} {'points':>6}  "
              + "  ".join(f"{k} err" for k in TRUE))
        for noise in (0.0, 0.01, 0.03, 0.10):
            m = _measurement(folder, wb, noise)
            t0 = time.perf_counter()
            c = cr.run(wb, m, fit=False)
            t1 = time.perf_counter()
            fit = ft.calibrate(c.setup, c.measurement)
            t2 = time.perf_counter()
            cr.compare.correlate(c.setup, c.measurement, fit)
            t3 = time.perf_counter()
            got = fit.factors()
            errs = "  ".join(f"{(got[k] / v - 1) * 100:+14.2f} %" for k, v in TRUE.items())
            print(f"{noise * 100:5.0f}% {t3 - t0:8.2f} {t2 - t1:6.2f} {fit.evaluations:6d}"
                  f" {fit.points:6d}  {errs}")
        m = _measurement(folder, wb, 0.03)
        t = time.perf_counter()
        r = subprocess.run([sys.executable, "-m", "checker", "correlate", str(wb), str(m),
                            "-o", str(folder / "c.pdf"), "--json", str(folder / "c.json"),
                            "--calibrated", str(folder / "cal.xlsx")],
                           capture_output=True, text=True)
        wall = time.perf_counter() - t
        print(f"checker correlate (fresh process, PDF + JSON + calibrated copy), 3 % noise:"
              f" {wall:.2f} s, exit {r.returncode}")
        print(r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "")


if __name__ == "__main__":
    main()
