"""Benchmark: classical crank stress + Goodman safety factor over the speed range.

Evaluates nominal stresses (:mod:`checker.calc.crank_stress`), M53 SCFs (:mod:`checker.calc.scf`)
and Goodman safety factors (:mod:`checker.calc.fatigue`) for the example I4 of seed 000 over
61 speeds (1000..7000 rpm) x 2 cases (full load, no load) x 4 throws x N crank angles, for
several crank-angle steps, and prints the run time and the error of the minimum SF against the
finest grid.

Loads: pin forces from :mod:`checker.calc.crank_forces` (gas + reciprocating/rotating inertia,
two-mass rod) driven by a synthetic cylinder pressure (polytropic compression/expansion plus a
combustion bump scaled to the seed's peak pressures); element torques = quasi-static
cumulative crank torque (front end free) + a synthetic TV torque with 4th/6th-order
resonances at the seed's 6150/4100 rpm and the seed's brake torque as the mean. With
``--synthetic-loads`` a self-contained slider-crank force model is used instead.
The loads are generated once on the finest grid; coarser grids are exact sub-samples, so the
error shown is purely the crank-angle sampling error of the max/min picking.

Run: ``/work/venv/bin/python benchmarks/bench_fatigue.py [--repeat 5] [--synthetic-loads]``
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from checker.calc.crank_stress import (
    local_stresses,
    pin_force_in_throw_frame,
    throw_nominal_stresses,
    web_width,
)
from checker.calc.fatigue import fillet_goodman, oil_hole_goodman
from checker.calc.scf import m53_scf

MM = 1e-3
# --- example engine (seed 000) ---------------------------------------------------------------
BORE, RADIUS, ROD = 86.0 * MM, 47.3 * MM, 145.7 * MM
PISTON_MASS, ROD_MASS, ROD_CG, ROD_INERTIA = 0.4955, 0.597, 35.73 * MM, 2128e-9
FIRING = np.deg2rad([0.0, 540.0, 180.0, 360.0])  # 1-3-4-2
GEOM = dict(
    pin_diameter=48 * MM,
    journal_diameter=55 * MM,
    throw=RADIUS,
    main_spacing=96 * MM,
    main_journal_length=27 * MM,
    pin_journal_length=24.4 * MM,
    web_thickness=21.3 * MM,
    web_width=web_width(71.4 * MM, 80.0 * MM, "min"),
    oil_hole_angle=np.deg2rad(45.0),
)
SPEEDS_RPM = np.linspace(1000.0, 7000.0, 61)
PEAK_FULL_BAR = (  # seed 000 table, full-load peak pressure vs speed
    [1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500, 5000, 5500, 6000, 6500, 7000],
    [53.4, 59.0, 68.1, 73.6, 77.1, 77.5, 80.0, 83.8, 84.4, 82.7, 79.8, 73.3, 70.0],
)
BRAKE_TORQUE = (  # seed 000 table [N m]; 7000 rpm extrapolated
    [1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500, 5000, 5500, 6000, 6500, 7000],
    [175, 200, 245, 255, 265, 265, 265, 265, 265, 255, 220, 190, 160],
)
NO_LOAD_PEAK_BAR = 29.1  # seed: no-load peak pressure (7000 rpm); used at all speeds
# strengths (seed 000 slide 26)
SE_PIN, SE_MAIN, SE_OIL = 619e6, 611e6, 326e6
SU_FILLET, SU_BASE = 920e6, 750e6


def pressure_trace(theta: np.ndarray, peak_bar: np.ndarray) -> np.ndarray:
    """Synthetic absolute cylinder pressure (..., N) vs. own cycle angle, peak ~ ``peak_bar``."""
    cr, gamma, p_in = 10.5, 1.32, 1.0e5
    lam = RADIUS / ROD
    x = RADIUS * (1 - np.cos(theta) + (1 - np.sqrt(1 - (lam * np.sin(theta)) ** 2)) / lam)
    v_rel = 1.0 + (cr - 1.0) * x / (2 * RADIUS)  # V / V_c
    ang = np.mod(theta + np.pi, 4 * np.pi) - np.pi  # -pi .. 3pi, firing TDC at 0
    motored = np.where(np.abs(ang) < np.pi, p_in * (cr / v_rel) ** gamma, p_in)
    bump = np.exp(-(((ang - np.deg2rad(14.0)) / np.deg2rad(22.0)) ** 2))
    p_mot_peak = p_in * cr**gamma
    extra = np.maximum(np.asarray(peak_bar)[..., None] * 1e5 - p_mot_peak, 0.0)
    return motored + extra * bump


def loads_crank_forces(theta, omega, peak_bar):
    """Pin forces (..., 4, N) in the throw frame and crank torques via checker.calc.crank_forces."""
    from checker.calc import crank_forces as cf

    p = pressure_trace(theta, peak_bar)[..., None, :]  # (case, speed, 1, N)
    cl = cf.cylinder_loads(
        theta,
        omega,
        p,
        bore=BORE,
        crank_radius=RADIUS,
        rod_length=ROD,
        piston_mass=PISTON_MASS,
        rod_mass=ROD_MASS,
        rod_cg_from_big_end=ROD_CG,
        rod_inertia=ROD_INERTIA,
        firing_angle=FIRING,
    )
    pins = np.arange(4)
    f = cf.crankpin_force(cl.big_end_crank, pins, 4)
    gam = cf.throw_angles(FIRING, 0.0, pins, 4)
    f_r, f_t = pin_force_in_throw_frame(f.x, f.y, gam[:, None])
    return f_r, f_t, cl.torque


def loads_synthetic(theta, omega, peak_bar):
    """Self-contained slider-crank (no rod inertia couple) for when crank_forces is unavailable."""
    lam = RADIUS / ROD
    loc = theta - FIRING[:, None]  # (4, N)
    p = pressure_trace(loc, np.asarray(peak_bar)[..., None])  # (case, speed, 4, N)
    m_rec = PISTON_MASS + ROD_MASS * ROD_CG / ROD
    m_rot = ROD_MASS * (1 - ROD_CG / ROD)
    w2 = (omega**2)[..., None, None]
    acc = RADIUS * w2 * (np.cos(loc) + lam * np.cos(2 * loc))
    fp = (p - 1e5) * np.pi / 4 * BORE**2 - m_rec * acc
    beta = np.arcsin(lam * np.sin(loc))
    f_r = -fp * np.cos(loc + beta) / np.cos(beta) + m_rot * RADIUS * w2
    f_t = fp * np.sin(loc + beta) / np.cos(beta)
    return f_r, f_t, f_t * RADIUS


def element_torques(theta, rpm, cyl_torque, brake):
    """Main-journal torques (..., 5, N): cumulative crank torque + synthetic TV + brake mean."""
    cum = np.concatenate([np.zeros_like(cyl_torque[..., :1, :]), np.cumsum(cyl_torque, -2)], -2)
    # shift so that the mean torque leaving the crank equals the brake torque
    cum = cum - cum[..., -1:, :].mean(-1, keepdims=True) * np.linspace(0, 1, 5)[:, None]
    cum = cum + brake[..., None, None] * np.linspace(0, 1, 5)[:, None]
    tv = np.zeros_like(cum)
    # first-mode torque shape: 0 at the free front end, largest at the flywheel end (seed:
    # "TV torque is generally highest at locations close to the flywheel")
    shape = np.sin(0.5 * np.pi * np.arange(5) / 4)[:, None]
    # peak TV torque ~ amp / 0.15: 4th order ~900 N m at 6150 rpm (seed: flywheel TV max 951)
    for order, res_rpm, amp in ((4.0, 6150.0, 135.0), (6.0, 4100.0, 60.0)):
        r = rpm / res_rpm
        mag = amp * r**2 / np.sqrt((1 - r**2) ** 2 + (0.15 * r) ** 2)
        tv = tv + mag * shape * np.sin(order * theta / 2)
    return cum + tv


def evaluate(f_r, f_t, pin_t, jnl_t, k):
    """Stress + SF evaluation being timed; returns the minimum SF per location kind."""
    nom = throw_nominal_stresses(f_r, f_t, pin_t, jnl_t, **GEOM)
    loc = local_stresses(
        nom,
        alpha_b=k.alpha_b,
        alpha_t=k.alpha_t,
        beta_b=k.beta_b,
        beta_q=k.beta_q,
        beta_t=k.beta_t,
        gamma_b=k.gamma_b,
        gamma_t=k.gamma_t,
    )
    pin = fillet_goodman(
        loc.sigma_pin_fillet,
        loc.tau_pin_fillet,
        endurance_limit=SE_PIN,
        ultimate_strength=SU_FILLET,
    )
    jnl = fillet_goodman(
        loc.sigma_journal_fillet,
        loc.tau_journal_fillet,
        endurance_limit=SE_MAIN,
        ultimate_strength=SU_FILLET,
    )
    oil = oil_hole_goodman(
        loc.sigma_oil_bending,
        loc.sigma_oil_torsion,
        endurance_limit=SE_OIL,
        ultimate_strength=SU_BASE,
    )
    return np.array([pin.safety_factor.min(), jnl.safety_factor.min(), oil.safety_factor.min()])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--synthetic-loads", action="store_true")
    args = ap.parse_args()

    n_fine = 2880  # 0.25 deg
    theta = np.arange(n_fine) * 4 * np.pi / n_fine
    rpm = SPEEDS_RPM[None, :]
    omega = np.broadcast_to(rpm * np.pi / 30.0, (2, SPEEDS_RPM.size))
    peak = np.stack(
        [np.interp(SPEEDS_RPM, *PEAK_FULL_BAR), np.full(SPEEDS_RPM.size, NO_LOAD_PEAK_BAR)]
    )
    brake = np.stack([np.interp(SPEEDS_RPM, *BRAKE_TORQUE), np.zeros(SPEEDS_RPM.size)])

    t0 = time.perf_counter()
    gen = loads_synthetic if args.synthetic_loads else loads_crank_forces
    f_r, f_t, cyl_t = gen(theta, omega, peak)
    mains = element_torques(theta, np.broadcast_to(rpm, omega.shape)[..., None, None], cyl_t, brake)
    jnl_t = np.stack([mains[..., :-1, :], mains[..., 1:, :]], axis=-2)  # (2, 61, 4, 2, N)
    pin_t = 0.5 * (mains[..., :-1, :] + mains[..., 1:, :])  # (2, 61, 4, N)
    t_gen = time.perf_counter() - t0

    k = m53_scf(
        pin_diameter=GEOM["pin_diameter"],
        journal_diameter=GEOM["journal_diameter"],
        throw=RADIUS,
        web_thickness=GEOM["web_thickness"],
        web_width=GEOM["web_width"],
        pin_fillet_radius=1.6 * MM,
        journal_fillet_radius=1.6 * MM,
        oil_hole_diameter=5.4 * MM,
    )
    print(f"loads: {gen.__name__}, grid {f_r.shape} generated in {t_gen:.2f} s")
    print("M53 SCF: " + ", ".join(f"{n}={float(getattr(k, n)):.3f}" for n in k._fields[:7]))
    for m in k.messages:
        print("  flag:", m)
    print(
        f"{'step deg':>8} {'N':>5} {'time ms':>9} {'min SF pin':>11} {'jnl':>7} {'oil':>7}"
        f" {'|err| pin':>10} {'jnl':>8} {'oil':>8}"
    )
    rows = []
    for stride in (1, 2, 4, 8, 16, 32):
        sl = np.s_[..., ::stride]
        args_ = (f_r[sl], f_t[sl], pin_t[sl], jnl_t[sl])
        times = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            sf = evaluate(*args_, k)
            times.append(time.perf_counter() - t0)
        rows.append((720.0 / (n_fine // stride), n_fine // stride, 1e3 * np.median(times), sf))
    ref = rows[0][3]
    for step, n, ms, sf in rows:
        err = np.abs(sf - ref) / ref
        print(
            f"{step:8.2f} {n:5d} {ms:9.1f} {sf[0]:11.4f} {sf[1]:7.4f} {sf[2]:7.4f}"
            f" {err[0]:10.2e} {err[1]:8.2e} {err[2]:8.2e}"
        )


if __name__ == "__main__":
    main()
