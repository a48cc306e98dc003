"""Finite-length (Reynolds map) MOFT against the short-bearing default: run time and error.

    python benchmarks/bench_finite_length.py [--direct]

1. Whole ``checker check`` (a fresh process per run, as a user runs it; min of 3 alternating
   runs, CPU time of the child) on the example I4 and the I6 truck diesel, with the workbook's
   default short-bearing mobility and with ``Mobility model = finite length``. Issue 16 asks
   for at most 1.5 times the short-bearing default.
2. Step convergence of the finite-length orbit: worst MOFT per bearing and load case at the
   module default (:data:`checker.modules.bearings.STEPS_PER_CYCLE_FINITE`) and at 360 steps,
   against 1440 steps per cycle.
3. ``--direct`` (slow, ~15 minutes): the map-based orbit against a direct orbit that solves
   the Reynolds equation at every step (:func:`checker.calc.reynolds.mobility_reynolds`), at
   the worst point of each bearing type and load case of both engines (issue 16: within 2 %).
4. ``--groove`` (slow, ~10 minutes): what the effective-width model of a partially grooved
   main bearing costs: direct orbits with the groove as a zero-pressure strip fixed in the
   housing (total width = effective width + groove width) against the map at the effective
   width, at the worst main-bearing points of the I4.

Run it once (the machine is shared); it prints the tables for the README.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker.calc import orbit as ob  # noqa: E402
from checker.description.engine import load_engine  # noqa: E402
from checker.evaluation import graph  # noqa: E402
from checker.modules import bearings as m_bearings  # noqa: E402
from checker.workbook.example import example_content, write_workbook  # noqa: E402
from checker.workbook.example_i6 import i6_content  # noqa: E402

ENGINES = {"I4": example_content, "I6": i6_content}
FINITE_ROW = ("Mobility model", "finite length", "-", "finite-length Reynolds mobility map")


def workbooks(tmp: Path) -> dict[tuple[str, str], Path]:
    out = {}
    for name, make in ENGINES.items():
        content = make()
        p = tmp / f"{name}_short.xlsx"
        write_workbook(p, content)
        out[(name, "short bearing")] = p
        fin = dict(content)
        fin["Oil"] = list(content["Oil"]) + [FINITE_ROW]
        p = tmp / f"{name}_finite.xlsx"
        write_workbook(p, fin)
        out[(name, "finite length")] = p
    return out


def cli_cpu(path: Path) -> tuple[float, float]:
    """CPU and wall time of one ``checker check`` in a fresh process."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "checker.cli", "check", str(path), "--no-timings",
                    "--format", "json", "-o", str(path.with_suffix(".json"))], env=env, check=False,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall


def worst(q) -> np.ndarray:
    return np.nanmin(q.values, axis=-1)  # (item, case)


def step_convergence(path: Path) -> list[tuple[str, float, float]]:
    engine = load_engine(path)
    bl = graph.run(engine, ["loads.bearing_load"]).quantities
    rows = []
    old = m_bearings.STEPS_PER_CYCLE_FINITE
    try:
        m_bearings.STEPS_PER_CYCLE_FINITE = 1440
        ref = worst(m_bearings._solve(engine, dict(bl), "reynolds_map", "bearing.moft_finite"))
        for n in sorted({old, 360}):
            m_bearings.STEPS_PER_CYCLE_FINITE = n
            t0 = time.process_time()
            q = m_bearings._solve(engine, dict(bl), "reynolds_map", "bearing.moft_finite")
            t = time.process_time() - t0
            rows.append((f"{n} steps/cycle", t, float(np.nanmax(np.abs(worst(q) / ref - 1)))))
    finally:
        m_bearings.STEPS_PER_CYCLE_FINITE = old
    return rows


def direct_comparison(path: Path, grid=None) -> list[tuple]:
    """Map orbit vs direct Reynolds orbit at the worst point of each bearing type and case."""
    engine = load_engine(path)
    bl = graph.run(engine, ["loads.bearing_load"]).quantities["loads.bearing_load"]
    qs = graph.run(engine, ["bearing.moft_short", "bearing.moft_finite"]).quantities
    short, fin = qs["bearing.moft_short"], qs["bearing.moft_finite"]
    names = fin.coords["item"]
    bearings = {b.name: b for b in engine.bearings}
    speeds = np.array(fin.coords["speed"])
    _, mu, _ = m_bearings.oil_viscosity(engine)
    ex = bl.detail
    rows = []
    for typ in dict.fromkeys(bearings[n].type for n in names):
        idx = [i for i, n in enumerate(names) if bearings[n].type == typ]
        for ci, case in enumerate(fin.coords["case"]):
            sub = fin.values[idx, ci]
            ii, k = np.unravel_index(int(np.nanargmin(sub)), sub.shape)
            i = idx[ii]
            n = names[i]
            b = bearings[n]
            args = (ex.fy[i, ci, k], ex.fx[i, ci, k], ex.omega_journal[i, ci, k],
                    ex.omega_bearing[i, ci, k], speeds[k], b.diameter, b.length,
                    b.clearance, mu)
            kw = {"steps_per_cycle": m_bearings.STEPS_PER_CYCLE_FINITE,
                  "full_groove": b.groove == "full"}
            t0 = time.perf_counter()
            res_map = ob.solve_orbit(*args, model="reynolds_map", **kw)
            t_map = time.perf_counter() - t0
            t0 = time.perf_counter()
            res_dir = ob.solve_orbit(*args, model="reynolds", solver_grid=grid,
                                     eps0_x=res_map.eps_x[..., 0], eps0_y=res_map.eps_y[..., 0],
                                     **kw)
            t_dir = time.perf_counter() - t0
            rows.append((n, b.type, case, speeds[k] * 30 / np.pi, short.values[i, ci, k],
                         float(res_map.h_min), float(res_dir.h_min), t_map, t_dir))
    return rows


def groove_comparison(path: Path) -> list[tuple]:
    """Mains of the I4 at their worst points: effective-width map vs direct grooved film.

    Angles of the workbook's groove (start, end) are taken in the loads' convention (0 along
    the cylinder axis towards the piston, positive with the rotation), which is the orbit
    frame of :mod:`checker.modules.bearings`. The grooved film spans the effective length plus the
    groove width (lands and groove; chamfers excluded).
    """
    engine = load_engine(path)
    bl = graph.run(engine, ["loads.bearing_load"]).quantities["loads.bearing_load"]
    fin = graph.run(engine, ["bearing.moft_finite"]).quantities["bearing.moft_finite"]
    names = fin.coords["item"]
    bearings = {b.name: b for b in engine.bearings}
    speeds = np.array(fin.coords["speed"])
    _, mu, _ = m_bearings.oil_viscosity(engine)
    ex = bl.detail
    rows = []
    mains = [i for i, n in enumerate(names) if bearings[n].type == "main"]
    for ci, case in enumerate(fin.coords["case"]):
        sub = fin.values[mains, ci]
        ii, k = np.unravel_index(int(np.nanargmin(sub)), sub.shape)
        i = mains[ii]
        b = bearings[names[i]]
        width = b.length + b.groove_width
        groove = (b.groove_start, b.groove_end + (2 * np.pi if b.groove_end <= b.groove_start
                                                   else 0.0), b.groove_width / b.diameter)
        args = (ex.fy[i, ci, k], ex.fx[i, ci, k], ex.omega_journal[i, ci, k],
                ex.omega_bearing[i, ci, k], speeds[k], b.diameter)
        kw = {"steps_per_cycle": m_bearings.STEPS_PER_CYCLE_FINITE}
        eff = ob.solve_orbit(*args, b.length, b.clearance, mu, model="reynolds_map", **kw)
        wide = ob.solve_orbit(*args, width, b.clearance, mu, model="reynolds_map", **kw)
        t0 = time.perf_counter()
        grooved = ob.solve_orbit(*args, width, b.clearance, mu, model="reynolds",
                                 solver_groove=groove, eps0_x=eff.eps_x[..., 0],
                                 eps0_y=eff.eps_y[..., 0], **kw)
        rows.append((names[i], case, speeds[k] * 30 / np.pi, float(eff.h_min),
                     float(wide.h_min), float(grooved.h_min),
                     float(np.degrees(grooved.phi_h_min)), time.perf_counter() - t0))
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--direct", action="store_true", help="also run the direct-Reynolds orbits")
    ap.add_argument("--groove", action="store_true", help="also run the grooved-main study")
    ap.add_argument("--no-timing", action="store_true", help="skip the run-time measurements")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        wbs = workbooks(Path(tmp))
        if not args.no_timing:
            timing(wbs)
        if args.direct:
            print()
            print("| engine | bearing (worst of its type) | case | rpm | short bearing [um] |"
                  " map [um] | direct Reynolds [um] | map/direct - 1 | short/direct |"
                  " time map / direct [s] |")
            print("|---|---|---|---|---|---|---|---|---|---|")
            for eng in ENGINES:
                for row in direct_comparison(wbs[(eng, "short bearing")]):
                    n, typ, case, rpm, hs, hm, hd, tm, td = row
                    print(f"| {eng} | {n} ({typ}) | {case} | {rpm:.0f} | {hs * 1e6:.3f} |"
                          f" {hm * 1e6:.3f} | {hd * 1e6:.3f} | {hm / hd - 1:+.2%} |"
                          f" {hs / hd:.2f} | {tm:.2f} / {td:.0f} |", flush=True)
        if args.groove:
            print()
            print("| main | case | rpm | map, effective width [um] | map, full width, no groove"
                  " [um] | direct, grooved [um] | effective/grooved - 1 | angle of h_min"
                  " [deg] | time [s] |")
            print("|---|---|---|---|---|---|---|---|---|")
            for n, case, rpm, he, hw, hg, ang, t in groove_comparison(
                    wbs[("I4", "short bearing")]):
                print(f"| {n} | {case} | {rpm:.0f} | {he * 1e6:.3f} | {hw * 1e6:.3f} |"
                      f" {hg * 1e6:.3f} | {he / hg - 1:+.1%} | {ang:.0f} | {t:.0f} |",
                      flush=True)
    return 0


def timing(wbs) -> None:
    """Whole-check run time (fresh processes) and the orbit step convergence."""
    print("| engine | model | whole check CPU [s] (min of 3) | wall [s] | ratio |")
    print("|---|---|---|---|---|")
    for eng in ENGINES:
        times = {}
        for _ in range(3):
            for model in ("short bearing", "finite length"):
                cpu, wall = cli_cpu(wbs[(eng, model)])
                old = times.get(model, (np.inf, np.inf))
                times[model] = (min(old[0], cpu), min(old[1], wall))
        base = times["short bearing"][0]
        for model, (cpu, wall) in times.items():
            print(f"| {eng} | {model} | {cpu:.2f} | {wall:.2f} | {cpu / base:.2f} |",
                  flush=True)
    print()
    print("| engine | finite-length orbit | CPU [s] | worst-MOFT error vs 1440 steps |")
    print("|---|---|---|---|")
    for eng in ENGINES:
        for label, t, err in step_convergence(wbs[(eng, "short bearing")]):
            print(f"| {eng} | {label} | {t:.2f} | {err:.1e} |", flush=True)


if __name__ == "__main__":
    raise SystemExit(main())
