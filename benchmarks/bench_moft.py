"""Benchmark of the batched MOFT solver (:mod:`checker.calc.orbit`). Not a test.

Batch: 61 speeds (1000..7000 rpm) x 2 load cases (full load, no load) x 9 bearings (5 mains,
4 big ends) of the example I4 engine (seed 000: bore 86, stroke 94.6, rod 145.7 mm; mains
D 55 / L_eff 18.2 / c 0.022 mm; pins D 48 / L_eff 17.8 / c 0.024 mm; 5W-30 at 130 C), loads
from a synthetic but engine-like model (centred slider crank, two-mass rod, polytropic
compression + Gaussian combustion spike scaled to the seed's full-load peak pressures,
statically determinate mains: half of each adjacent throw). If
``checker/calc/crank_forces.py`` is importable, its big-end loads for the same synthetic
pressure are also solved (frame mapping check: its ``(x, y)`` have ``x`` at +90 deg from ``y``
in the direction of rotation, so ``load_x = v.y``, ``load_y = v.x``).

Prints run time and MOFT error against a converged reference (0.25 deg steps, periodicity
tolerance 1e-7) for several step / tolerance settings, closed-form vs exact (tabulated) and
Butenschoen finite-length mobility, and the Butenschoen model's own step convergence.

Run:  python benchmarks/bench_moft.py [--quick]
"""

from __future__ import annotations

import sys
import time

import numpy as np

from checker.calc import orbit
from checker.calc.viscosity import j300_viscosity

N_THETA = 720  # 1 deg load grid over 720 deg
RPM = np.arange(1000.0, 7001.0, 100.0)  # 61 speeds

# example engine (seed 000)
BORE = 0.086
CRANK_R = 0.0946 / 2
ROD_L = 0.1457
M_ROD = 0.597
ROD_CG_FROM_BIG_END = 0.03573
M_PISTON = 0.4955
COMPRESSION_RATIO = 10.5  # assumption (not in the seed)
# crank throw unbalance per throw [kg m]: 2 webs, 2 counterweights, pin (seed mass table)
THROW_MR = 2 * 0.659 * 0.026763 - 2 * 0.794 * 0.037611 + 0.341 * CRANK_R
FIRING_OFFSET = {1: 0.0, 3: np.pi, 4: 2 * np.pi, 2: 3 * np.pi}  # firing order 1-3-4-2
PEAK_RPM = np.array([1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500, 5000, 5500, 6000, 6500.0])
PEAK_BAR = np.array([53.4, 59.0, 68.1, 73.6, 77.1, 77.5, 80.0, 83.8, 84.4, 82.7, 79.8, 73.3])
NO_LOAD_PEAK_BAR = 25.0  # assumption

MAIN = dict(diameter=0.055, length=0.0182, clearance=0.022e-3)
PIN = dict(diameter=0.048, length=0.0178, clearance=0.024e-3)


def cylinder_pressure(theta_local: np.ndarray, peak_bar: np.ndarray) -> np.ndarray:
    """Synthetic cylinder pressure [Pa] vs local cycle angle (0 = firing TDC); (S, N)."""
    lam = CRANK_R / ROD_L
    th = np.mod(theta_local + np.pi, 4 * np.pi) - np.pi  # -pi .. 3pi, firing TDC at 0
    s = np.sin(th)
    x = CRANK_R * (1 - np.cos(th)) + ROD_L * (1 - np.sqrt(1 - lam**2 * s**2))  # from TDC
    vd = np.pi / 4 * BORE**2 * 2 * CRANK_R
    vc = vd / (COMPRESSION_RATIO - 1)
    v = vc + np.pi / 4 * BORE**2 * x
    closed = (th > -np.pi) & (th < np.pi)
    p_mot = np.where(closed, 1e5 * ((vc + vd) / v) ** 1.35, 1e5)
    spike = np.exp(-0.5 * ((th - np.radians(12.0)) / np.radians(15.0)) ** 2)
    p_mot_max = 1e5 * ((vc + vd) / vc) ** 1.35
    dp = np.maximum(np.asarray(peak_bar)[..., None] * 1e5 - p_mot_max, 0.0)
    return p_mot + dp * spike


def engine_loads(rpm: np.ndarray, peak_bar: np.ndarray):
    """Loads for 5 mains + 4 big ends, engine frame (y up the cylinder axis, crank turning
    counter-clockwise = positive). Returns fx, fy (S, 9, N), omega_j, omega_b (S, 9, N)."""
    theta = np.arange(N_THETA) * 4 * np.pi / N_THETA
    w = np.asarray(rpm, dtype=float)[:, None] * np.pi / 30.0  # (S, 1)
    lam = CRANK_R / ROD_L
    m_rot = M_ROD * (1 - ROD_CG_FROM_BIG_END / ROD_L)
    m_rec = M_PISTON + M_ROD * ROD_CG_FROM_BIG_END / ROD_L
    area = np.pi / 4 * BORE**2
    be_fx, be_fy, w_rod = [], [], []
    throw_fx, throw_fy = [], []
    for cyl in (1, 2, 3, 4):
        th = theta - FIRING_OFFSET[cyl]
        s, c = np.sin(th), np.cos(th)
        sq = np.sqrt(1 - lam**2 * s**2)
        ypp = -CRANK_R * c - ROD_L * lam**2 * (np.cos(2 * th) / sq + lam**2 * s**2 * c**2 / sq**3)
        a_p = w**2 * ypp  # piston acceleration (S, N)
        f_gas = (cylinder_pressure(th, peak_bar) - 1e5) * area
        ur_x, ur_y = CRANK_R * s / ROD_L, sq
        tension = (m_rec * a_p + f_gas) / ur_y  # rod thrust (compression positive)
        px, py = -CRANK_R * s, CRANK_R * c  # pin position
        fpe_x = m_rot * (-(w**2) * px) + tension * ur_x  # pin on rod eye
        fpe_y = m_rot * (-(w**2) * py) + tension * ur_y
        be_fx.append(fpe_x)
        be_fy.append(fpe_y)
        w_rod.append(-w * lam * c / sq)
        cf = THROW_MR * w**2 / CRANK_R
        throw_fx.append(-fpe_x + cf * px)
        throw_fy.append(-fpe_y + cf * py)
    zero = np.zeros_like(be_fx[0])
    mains_x = [0.5 * (a + b) for a, b in zip([zero] + throw_fx, throw_fx + [zero], strict=True)]
    mains_y = [0.5 * (a + b) for a, b in zip([zero] + throw_fy, throw_fy + [zero], strict=True)]
    fx = np.stack(mains_x + be_fx, axis=1)
    fy = np.stack(mains_y + be_fy, axis=1)
    wj = np.broadcast_to(w[:, None, :], fx.shape)
    wb = np.concatenate([np.zeros((len(w), 5, N_THETA)), np.stack(w_rod, axis=1)], axis=1)
    return fx, fy, wj, wb


def batch():
    """Arrays for the (2, 61, 9) batch: load case x speed x bearing."""
    full = np.interp(RPM, PEAK_RPM, PEAK_BAR)
    parts = [engine_loads(RPM, full), engine_loads(RPM, np.full(RPM.shape, NO_LOAD_PEAK_BAR))]
    fx = np.stack([p[0] for p in parts])
    fy = np.stack([p[1] for p in parts])
    wj = np.stack([p[2] for p in parts])
    wb = np.stack([p[3] for p in parts])
    speed = np.broadcast_to((RPM * np.pi / 30.0)[None, :, None], fx.shape[:-1])
    geo = {k: np.array([MAIN[k]] * 5 + [PIN[k]] * 4) for k in MAIN}
    mu = float(j300_viscosity(130.0 + 273.15, "5W-30"))
    return fx, fy, wj, wb, speed, geo, mu


def run(args, **kw):
    fx, fy, wj, wb, speed, geo, mu = args
    t0 = time.perf_counter()
    res = orbit.solve_orbit(fx, fy, wj, wb, speed, geo["diameter"], geo["length"],
                            geo["clearance"], mu, **kw)
    return res, time.perf_counter() - t0


def crank_forces_check(mu: float) -> None:
    """Big ends with checker.calc.crank_forces loads (optional module, API of Nov 2026)."""
    try:
        from checker.calc import crank_forces as cf

        theta = np.arange(N_THETA) * 4 * np.pi / N_THETA
        rpm = np.array([2000.0, 4000.0, 6000.0])
        w = rpm * np.pi / 30
        peak = np.interp(rpm, PEAK_RPM, PEAK_BAR)
        p = cylinder_pressure(theta[None, :], peak)
        cl = cf.cylinder_loads(
            theta, w, p[:, None, :], bore=BORE, crank_radius=CRANK_R, rod_length=ROD_L,
            piston_mass=M_PISTON, rod_mass=M_ROD, rod_cg_from_big_end=ROD_CG_FROM_BIG_END,
            rod_inertia=2128e-9, firing_angle=np.array([0, 3 * np.pi, np.pi, 2 * np.pi]))
    except Exception as exc:  # optional cross-check only
        print(f"crank_forces check skipped: {exc!r}")
        return
    be = cl.big_end_block
    r_cf = orbit.solve_orbit(be.y, be.x, w[:, None, None], cl.rod_omega, w[:, None],
                             PIN["diameter"], PIN["length"], PIN["clearance"], mu)
    fx, fy, wj, wb = engine_loads(rpm, peak)
    r_own = orbit.solve_orbit(fx[:, 5:], fy[:, 5:], wj[:, 5:], wb[:, 5:], w[:, None],
                              PIN["diameter"], PIN["length"], PIN["clearance"], mu)
    print("big-end 1 MOFT [um], crank_forces loads vs this script's loads at "
          + ", ".join(f"{r:.0f}" for r in rpm) + " rpm: "
          + " / ".join(f"{a * 1e6:.3f} vs {b * 1e6:.3f}"
                       for a, b in zip(r_cf.h_min[:, 0], r_own.h_min[:, 0], strict=True)))


def main(quick: bool = False) -> None:
    args = batch()
    print(f"batch shape {args[0].shape[:-1]} (load case x speed x bearing), "
          f"viscosity {args[-1] * 1e3:.2f} mPa s")
    orbit.solve_orbit(*(a[:1, :1, :1] for a in args[:5]), 0.05, 0.02, 2e-5, 5e-3)  # warm up
    ref, t_ref = run(args, steps_per_cycle=1440 if quick else 2880, tol=1e-7, max_cycles=80)
    print(f"reference: {ref.steps_per_cycle} steps/cycle, tol 1e-7: {t_ref:.2f} s, "
          f"h_min {ref.h_min.min() * 1e6:.3f}..{ref.h_min.max() * 1e6:.3f} um, "
          f"collapse {ref.collapse.sum()}, not converged {(~ref.converged).sum()}")
    print()
    print("model        steps  tol     time[s]  cycles(mean/max)  max|dMOFT|/MOFT  "
          "p99        not conv.")
    settings = [
        ("closed_form", 90, 1e-4), ("closed_form", 180, 1e-4), ("closed_form", 360, 1e-3),
        ("closed_form", 360, 1e-4), ("closed_form", 360, 1e-5), ("closed_form", 720, 1e-4),
        ("exact_table", 360, 1e-4), ("butenschoen", 360, 1e-4),  # butenschoen: >= 720 steps
    ]
    default = (orbit.DEFAULT_STEPS_PER_CYCLE, orbit.DEFAULT_PERIODIC_TOL)
    for model, steps, tol in settings:
        best = np.inf
        for _ in range(1 if quick else 3):
            res, t = run(args, model=model, steps_per_cycle=steps, tol=tol)
            best = min(best, t)
        if model == "closed_form":
            err = np.abs(res.h_min / ref.h_min - 1)
            e_txt = f"{err.max():.2e}         {np.quantile(err, 0.99):.2e}"
        else:
            err = np.abs(res.h_min / ref.h_min - 1)
            e_txt = f"vs closed form: max {err.max():.3f}, median {np.median(err):.3f}"
        mark = " (default)" if (model == "closed_form" and (steps, tol) == default) else ""
        print(f"{model:12s} {steps:5d}  {tol:.0e}  {best:7.3f}  "
              f"{res.n_cycles.mean():5.2f}/{res.n_cycles.max():3d}         {e_txt}  "
              f"{(~res.converged).sum()}{mark}")
    if not quick:  # Butenschoen against its own converged solution, every 6th speed
        sub = [a[:, ::6] for a in args[:5]] + list(args[5:])
        bref, t_b = run(sub, model="butenschoen", steps_per_cycle=2880, tol=1e-7)
        for steps in (720, 1440):  # "butenschoen" uses at least 720 steps (1 deg)
            res, t = run(sub, model="butenschoen", steps_per_cycle=steps)
            err = np.abs(res.h_min / bref.h_min - 1)
            print(f"butenschoen self-convergence ({bref.h_min.size} bearings, ref 2880 steps "
                  f"{t_b:.0f} s): {steps} steps {t:.2f} s, max |dMOFT|/MOFT {err.max():.2e}, "
                  f"median {np.median(err):.1e}")
    crank_forces_check(args[-1])
    res, t = run(args, peak_pressure=True)
    print(f"\nclosed_form default + peak_pressure: {t:.3f} s; "
          f"p_max {res.p_max.min() / 1e6:.0f}..{res.p_max.max() / 1e6:.0f} MPa")
    i = np.unravel_index(np.argmin(ref.h_min), ref.h_min.shape)
    print(f"lowest MOFT (reference): {ref.h_min[i] * 1e6:.3f} um at load case {i[0]}, "
          f"{RPM[i[1]]:.0f} rpm, bearing {i[2]} "
          f"({'main ' + str(i[2] + 1) if i[2] < 5 else 'big end ' + str(i[2] - 4)})")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
