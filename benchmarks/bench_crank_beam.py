"""Benchmark of the crank as a continuous beam (issue 34; not a test).

Run: ``.venv/bin/python benchmarks/bench_crank_beam.py``

The example I4 with its crank described by sheet Crank, under each support scheme. Printed:

* the beam's own cost inside a check: building and factorising the frame, the main-bearing
  loads of every crank angle, speed and load case (one product), and the fatigue's section
  loads (minimum of 20 repeats each);
* the whole check per scheme (minimum of 3), the difference being what the scheme costs;
* the error: the frame is exact for Euler-Bernoulli elements under nodal loads (no
  discretisation to converge); what is printed is the equilibrium residual of the main loads
  (sum over the mains of the continuous beam against the determinate scheme's, which carry the
  same forces) relative to the largest main load.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "workbook"))

from test_crank_sheet import i4_with_crank  # noqa: E402

from checker import api  # noqa: E402
from checker.calc import crank_forces as cf  # noqa: E402
from checker.description.engine import load_engine  # noqa: E402
from checker.modules import support_beam  # noqa: E402
from checker.workbook.example import write_workbook  # noqa: E402

SCHEMES = (("determinate", None), ("continuous beam, rigid supports", None),
           ("continuous beam, elastic supports", 1e6))


def _workbook(folder: Path, scheme: str, k: float | None) -> Path:
    def edit(c):
        c["Engine"].append(["Main bearing supports", scheme, "-", "benchmark"])
        if k is not None:
            c["Engine"].append(["Main bearing support stiffness", k, "N/mm", "benchmark"])
    p = folder / f"{scheme.replace(',', '').replace(' ', '_')}.xlsx"
    write_workbook(p, i4_with_crank(edit=edit))
    return p


def best(f, n: int) -> float:
    t = []
    for _ in range(n):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        paths = {s: _workbook(Path(tmp), s, k) for s, k in SCHEMES}
        res = api.check(paths["continuous beam, rigid supports"])
        det = api.check(paths["determinate"])
        engine = load_engine(paths["continuous beam, rigid supports"])
        bl = res.outcome.quantities["loads.bearing_load"]
        cyc = res.outcome.quantities["loads.cycle"].detail.cycle
        cyls = engine.cylinders
        pins = np.array([c.pin - 1 for c in cyls])
        gamma = cf.throw_angles(np.array([c.firing_angle for c in cyls]),
                                np.array([c.bank_angle for c in cyls]), pins, pins.max() + 1)
        r = engine.params["stroke"] / 2
        t_build = best(lambda: support_beam.build_beam(engine, gamma), 20)
        beam = support_beam.build_beam(engine, gamma)
        t_loads = best(lambda: support_beam.continuous_main_loads(
            beam, engine, cyc.theta, cyc.speeds, bl.detail.big_end_crank, pins, gamma, r,
            list(cyc.cases)), 20)
        g = res.outcome.quantities["fatigue.goodman_sf"].detail
        from checker.modules.fatigue import _geometry
        geo = _geometry(engine)[0].as_kwargs()
        t_sec = best(lambda: support_beam.throw_sections(
            beam, g.pin_force_radial, g.pin_force_tangential, gamma, geo, cyc.theta), 20)
        n_pts = cyc.theta.size * cyc.speeds.size * len(cyc.cases)
        print(f"I4, {len(cyc.cases)} cases x {cyc.speeds.size} speeds x {cyc.theta.size}"
              f" angles = {n_pts} load sets; frame {beam.crank.frame.nodes.shape[0]} nodes")
        print(f"  build + factorise the frame      {t_build * 1e3:7.2f} ms")
        print(f"  main-bearing loads, whole sweep  {t_loads * 1e3:7.2f} ms")
        print(f"  fatigue section loads, sweep     {t_sec * 1e3:7.2f} ms")
        print(f"  beam total per check (x2 build)  {(2 * t_build + t_loads + t_sec) * 1e3:7.2f}"
              " ms")
        names = bl.coords["item"]
        rows = [i for i, n in enumerate(names) if bl.item_attrs[n]["type"] == "main"]
        dq = det.outcome.quantities["loads.bearing_load"].detail
        resid = max(np.abs(bl.detail.fx[rows].sum(0) - dq.fx[rows].sum(0)).max(),
                    np.abs(bl.detail.fy[rows].sum(0) - dq.fy[rows].sum(0)).max())
        print(f"  equilibrium residual / largest main load: "
              f"{resid / np.abs(dq.fx[rows]).max():.1e}")
        for s, _ in SCHEMES:
            t = best(lambda s=s: api.check(paths[s]), 3)
            print(f"check, {s:36s} {t:6.2f} s (min of 3)")


if __name__ == "__main__":
    main()
