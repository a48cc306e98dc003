"""Benchmark of the throw FE (mesh convergence) and of the fast model (not a test).

Run: ``.venv/bin/python benchmarks/bench_throw_fe.py`` (needs the extra ``fe``; about 2
minutes on one core; ``--quick`` stops at size 0.08).

Throw: the I4 of Bell (2013), idealised (Dj 55, Dp 48, Lj 27, Lp 24.4, tw 22.3, R 47.3 mm,
web width 75.7 mm at both circles, solid, no counterweight; G 80.8 GPa, E 210 GPa); the
stiffness definition of ``scripts/throw_fe.py`` (faces free axially). Printed:

* validation: plain and hollow shafts against G Jp / L, a 2:1 rectangular bar against
  Saint-Venant (Timoshenko & Goodier 1970, eq. 163);
* mesh convergence: element size far from the junctions (fraction of Dj; a quarter of it at
  the re-entrant journal-web and pin-web edges), degrees of freedom, run time (mesh + assembly
  + solve, one core), stiffness, change from the previous size, and the difference from the
  Richardson extrapolation of the three finest sizes;
* the boundary-condition variants (faces free / rigid but free to tilt / held axially) and
  quarter against whole throw;
* the samples' mesh against a finer one on six samples (the worst fitted, most of them
  extreme corners);
* the fast model (checker.calc.throw_stiffness), Carter and Ker Wilson as usually quoted, the
  published FE-based 403.3 kN m/rad of the real crank (Bell 2013, with lightening and fillets);
  the fast model's run time for 10,000 throws.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
_spec = importlib.util.spec_from_file_location("throw_fe", ROOT / "scripts" / "throw_fe.py")
fe = importlib.util.module_from_spec(_spec)
sys.modules["throw_fe"] = fe
_spec.loader.exec_module(fe)

from checker.calc import throw_stiffness as ts  # noqa: E402

SIZES = (0.3, 0.2, 0.15, 0.12, 0.1, 0.08, 0.065, 0.05)


def validation() -> None:
    E, nu = 210e9, 0.3
    G = E / (2 * (1 + nu))
    print("validation against closed forms (quarter model, faces free axially)")
    for D, d, size in ((0.05, 0.0, 0.3), (0.05, 0.025, 0.3), (0.06, 0.045, 0.3),
                       (0.05, 0.025, 0.15)):
        k = fe.shaft(D, d, 0.1, E=E, nu=nu, size=size)
        ref = G * math.pi * (D**4 - d**4) / (32 * 0.1)
        print(f"  shaft D {D * 1e3:.0f} d {d * 1e3:.0f} L 100 mm, size {size} D: "
              f"{100 * (k / ref - 1):+.3f} % vs G Jp / L")
    a, b, L = 0.04, 0.02, 0.12
    ref = G * fe.rect_torsion_constant(a, b) / L
    for size in (0.25, 0.15):
        k = fe.rect_bar(a, b, L, E=E, nu=nu, size=size)
        kh = fe.rect_bar(a, b, L, E=E, nu=nu, size=size, variant="held")
        print(f"  bar 40 x 20 x 120 mm, size {size} b: {100 * (k / ref - 1):+.3f} % vs "
              f"Saint-Venant (faces held axially: {100 * (kh / ref - 1):+.2f} %)")


def convergence(sizes) -> float:
    th = fe.I4_THROW
    print("\nmesh convergence, I4 throw (quarter model)")
    print(f"{'size/Dj':>8} {'dofs':>8} {'tets':>7} {'time s':>7} {'k kN m/rad':>11} "
          f"{'change %':>9} {'vs extrap. %':>13}")
    rows = []
    for s in sizes:
        r = fe.solve_throw(th, s)
        rows.append((s, r.n_dofs, r.n_elements, r.seconds, r.stiffness))
    k = np.array([r[4] for r in rows])
    n = np.array([r[1] for r in rows], dtype=float)
    # Richardson on the three finest: k = k_inf + c h^p, h = dofs^(-1/3) (solve for p)
    from scipy.optimize import brentq

    (k1, k2, k3), (h1, h2, h3) = k[-3:], n[-3:] ** (-1 / 3)
    q = (k1 - k2) / (k2 - k3)
    p = brentq(lambda p: (h1**p - h2**p) / (h2**p - h3**p) - q, 0.2, 8.0)
    c = (k2 - k3) / (h2**p - h3**p)
    k_inf = k3 - c * h3**p
    for i, (s, nd, ne, t, kk) in enumerate(rows):
        ch = "" if i == 0 else f"{100 * (kk / rows[i - 1][4] - 1):+9.3f}"
        print(f"{s:8.3f} {nd:8d} {ne:7d} {t:7.1f} {kk / 1e3:11.2f} {ch:>9} "
              f"{100 * (kk / k_inf - 1):+13.3f}")
    print(f"extrapolated: {k_inf / 1e3:.2f} kN m/rad (observed order in h = dofs^-1/3: {p:.2f})")
    return k_inf


def variants() -> float:
    th = fe.I4_THROW
    print("\nboundary conditions, I4 throw, size 0.12")
    free = fe.solve_throw(th, 0.12).stiffness
    for v in ("free", "rigid", "held"):
        k = free if v == "free" else fe.solve_throw(th, 0.12, variant=v).stiffness
        print(f"  {v:6s} {k / 1e3:8.2f} kN m/rad ({100 * (k / free - 1):+.1f} %)")
    full = fe.solve_throw(th, 0.15, full=True)
    quarter = fe.solve_throw(th, 0.15)
    print(f"  whole throw (size 0.15) {full.stiffness / 1e3:.2f} vs quarter "
          f"{quarter.stiffness / 1e3:.2f} kN m/rad ({full.n_dofs} vs {quarter.n_dofs} dofs, "
          f"{full.seconds:.1f} vs {quarter.seconds:.1f} s)")
    return free


def fast_model(k_fe: float, k_inf: float) -> None:
    th = fe.I4_THROW
    args = dict(journal_diameter=th.Dj, journal_bore=0.0, journal_length=th.Lj,
                pin_diameter=th.Dp, pin_bore=0.0, pin_length=th.Lp, web_thickness=th.tw,
                web_width_journal=th.Bj, web_width_pin=th.Bp, crank_radius=th.R,
                youngs_modulus=th.E, poisson_ratio=th.nu)
    k = float(ts.throw_torsional_stiffness(**args).stiffness[0])
    G = th.G
    cl = dict(Dj=th.Dj, Lj=th.Lj, Dp=th.Dp, Lp=th.Lp, tw=th.tw, B=th.Bj, R=th.R, G=G)
    carter = float(ts.carter_stiffness(**cl))
    kw = float(ts.ker_wilson_stiffness(dj=0.0, dp=0.0, **cl))
    print("\nI4 throw, kN m/rad")
    print(f"  FE size 0.12 (the samples' setting) {k_fe / 1e3:.1f}; extrapolated "
          f"{k_inf / 1e3:.1f}")
    print(f"  fast model {k / 1e3:.1f} ({100 * (k / k_fe - 1):+.1f} % vs FE)")
    print(f"  Carter {carter / 1e3:.1f} ({100 * (carter / k_fe - 1):+.1f} %), Ker Wilson "
          f"{kw / 1e3:.1f} ({100 * (kw / k_fe - 1):+.1f} %)")
    print(f"  published FE-based, real crank (Bell 2013): 403.3 "
          f"({100 * (403.3e3 / k_fe - 1):+.1f} % vs the idealised FE)")
    many = {kk: np.full(10_000, v) for kk, v in args.items()}
    ts.throw_torsional_stiffness(**args)
    t0 = time.perf_counter()
    for _ in range(20):
        ts.throw_torsional_stiffness(**many)
    print(f"  fast model: {(time.perf_counter() - t0) / 20 * 1e3:.2f} ms for 10,000 throws")
    t0 = time.perf_counter()
    for _ in range(200):
        ts.throw_torsional_stiffness(**args)
    print(f"  fast model: {(time.perf_counter() - t0) / 200 * 1e6:.0f} us for one throw")


def sample_sensitivity(names=("corner4", "corner3", "corner5", "corner2", "fit08", "corner7")):
    """The samples' mesh (0.12) against a finer one (0.08) on the worst-fitted samples and
    extreme corners: the FE's discretisation error across geometries, not only the I4."""
    import csv

    with ts.SAMPLES_FILE.open() as f:
        rows = {r["name"]: r for r in csv.DictReader(f)}
    fields = list(fe.Throw.__dataclass_fields__)
    print("\nsamples: size 0.12 (stored) against 0.08")
    for name in names:
        if name not in rows:
            continue
        r = rows[name]
        th = fe.Throw(**{k: float(r[k]) for k in fields})
        fine = fe.solve_throw(th, 0.08)
        print(f"  {name:8s} {float(r['k_fe']) / 1e3:8.2f} -> {fine.stiffness / 1e3:8.2f} kN m/rad "
              f"({100 * (float(r['k_fe']) / fine.stiffness - 1):+.3f} %, {fine.n_dofs} dofs, "
              f"{fine.seconds:.0f} s)")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    validation()
    k_inf = convergence([s for s in SIZES if not args.quick or s >= 0.08])
    k_fe = variants()
    fast_model(k_fe, k_inf)
    sample_sensitivity()


if __name__ == "__main__":
    main()
