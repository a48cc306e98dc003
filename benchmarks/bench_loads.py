"""Benchmark of the crank-train load sweep of the example I4 engine (not a test).

Run: ``/work/venv/bin/python benchmarks/bench_loads.py``

Engine (seed 000, literal data): bore 86, stroke 94.6, rod 145.7 mm, pin offset 0.8 mm, rod
0.597 kg with CoM 35.73 mm from the big end and I_G = 2128 kg mm^2, piston assembly 0.4955 kg,
throws 0/180/180/0 deg, firing 1-3-4-2 (cylinders 1..4 at 0, 540, 180, 360 deg); crank mass
table of seed 000 (webs and counterweights relative to the main axis, crank pins relative to the
pin axis), web CoM 24.65 mm from the nearest main, pins at mid-bay, main spacing 96 mm; big end
D 48 / L_eff 17.8 mm, mains D 55 / L_eff 18.2 mm. Compression ratio 10.5 (assumed, not in the
seed). Load cases: full load (peak-pressure table of seed 000, held constant above 6500 rpm and
flagged as extrapolated) and no load (29.1 bar at all speeds, the seed's single point at
7000 rpm); traces synthesized by :func:`checker.calc.pressure.synthesize_trace` (its internal
0.05 deg grid makes the trace the same function for every output step, so the comparison below
isolates the sampling error of the load maxima). 61 speeds 1000..7000 rpm.

Printed per crank-angle step: time of the trace synthesis, time of the force sweep (cylinder
loads + main bearing loads + peak specific loads of all 4 big ends and 5 mains), and the error of
the peak specific loads against the finest step (0.1 deg): worst over all (case, speed, bearing)
and worst for the envelope over speed per bearing.
"""

from __future__ import annotations

import time

import numpy as np

from checker.calc.crank_forces import cylinder_loads, main_bearing_loads, throw_angles
from checker.calc.kinematics import DEFAULT_STEP_DEG, cycle_grid
from checker.calc.pressure import peak_pressure_at_speed, synthesize_trace
from checker.calc.specific_load import peak_specific_load, worst_case

MM, BAR, RPM, DEG = 1e-3, 1e5, np.pi / 30.0, np.pi / 180.0
SPEEDS = np.linspace(1000.0, 7000.0, 61) * RPM
FULL_LOAD_RPM = np.arange(1000.0, 6501.0, 500.0)
FULL_LOAD_BAR = [53.4, 59.0, 68.1, 73.6, 77.1, 77.5, 80.0, 83.8, 84.4, 82.7, 79.8, 73.3]
NO_LOAD_BAR = 29.1
FIRING = np.array([0.0, 540.0, 180.0, 360.0]) * DEG
GEOMETRY = dict(bore=86.0 * MM, crank_radius=47.3 * MM, rod_length=145.7 * MM, pin_offset=0.8 * MM)
ROD = dict(piston_mass=0.4955, rod_mass=0.597, rod_cg_from_big_end=35.73 * MM, rod_inertia=2128e-9)
# seed 000 crank mass table, per bay: web (front), web c/w, crank pin, web (rear), web c/w
MASS = np.tile([0.659, 0.794, 0.341, 0.659, 0.794], 4)
Y_TABLE = np.array(
    [26.763, -37.611, -0.1, 26.763, -37.611, -26.763, 37.611, 0.1, -26.763, 37.611,
     -26.763, 37.611, 0.1, -26.763, 37.611, 26.763, -37.611, -0.1, 26.763, -37.611]
) * MM
BAY = np.repeat(np.arange(4), 5)
Z_AXIAL = np.tile([24.65, 24.65, 48.0, 71.35, 71.35], 4) * MM
STEPS_DEG = [4.0, 2.0, 1.0, 0.5, 0.25, 0.1]


def crank_masses() -> np.ndarray:
    """Crank-frame CoM positions (n_m, 2): crank pins are offset by the throw radius."""
    gam = throw_angles(FIRING, 0.0, np.arange(4), 4)
    is_pin = np.tile([False, False, True, False, False], 4)
    r = GEOMETRY["crank_radius"]
    x = is_pin * r * np.sin(gam[BAY])
    y = Y_TABLE + is_pin * r * np.cos(gam[BAY])
    return np.stack([x, y], axis=1)


def traces(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pressure (case, speed, 1, N) and the extrapolation mask of the full-load table."""
    full, extrap = peak_pressure_at_speed(
        FULL_LOAD_RPM * RPM, np.multiply(FULL_LOAD_BAR, BAR), SPEEDS
    )
    peaks = np.stack([full, np.full_like(full, NO_LOAD_BAR * BAR)])
    tr = synthesize_trace(theta, peaks, compression_ratio=10.5, **GEOMETRY)
    return tr.pressure[:, :, None, :], extrap


def force_sweep(theta: np.ndarray, p: np.ndarray, positions: np.ndarray):
    """Big-end and main peak specific loads, shapes (case, speed, 4) and (case, speed, 5)."""
    loads = cylinder_loads(theta, SPEEDS, p, firing_angle=FIRING, **GEOMETRY, **ROD)
    mains = main_bearing_loads(
        theta, SPEEDS, loads.big_end_block, pin_index=np.arange(4),
        rod_axial_position=48.0 * MM, bay_length=np.full(4, 96.0 * MM), mass=MASS,
        mass_bay=BAY, mass_position=positions, mass_axial_position=Z_AXIAL,
    )
    be = loads.big_end_rod
    pk_be = peak_specific_load(be.x, be.y, theta, 48.0 * MM, 17.8 * MM)
    pk_mb = peak_specific_load(mains.x, mains.y, theta, 55.0 * MM, 18.2 * MM)
    return pk_be, pk_mb


def main() -> None:
    positions = crank_masses()
    results = {}
    t_total = time.perf_counter()
    for step in STEPS_DEG:
        theta = cycle_grid(step * DEG)
        t0 = time.perf_counter()
        p, extrap = traces(theta)
        t1 = time.perf_counter()
        n_rep = 3 if step >= 0.5 else 1
        t_force = np.inf
        for _ in range(n_rep):
            t2 = time.perf_counter()
            pk_be, pk_mb = force_sweep(theta, p, positions)
            t_force = min(t_force, time.perf_counter() - t2)
        results[step] = (t1 - t0, t_force, pk_be, pk_mb)
        del p

    ref_be, ref_mb = results[STEPS_DEG[-1]][2:]
    print("Example I4, 61 speeds x 2 load cases x 4 cylinders; peak specific loads vs 0.1 deg")
    print(f"(full-load peak pressure extrapolated at {int(extrap.sum())} speed(s) > 6500 rpm)")
    header = (
        f"{'step':>6} {'N':>6} {'synth s':>8} {'forces s':>9} "
        f"{'BE max err':>11} {'main max err':>13} {'BE env err':>11} {'main env err':>13}"
    )
    print(header)
    for step in STEPS_DEG:
        t_syn, t_force, pk_be, pk_mb = results[step]
        e_be = np.abs(pk_be.specific_load / ref_be.specific_load - 1).max()
        e_mb = np.abs(pk_mb.specific_load / ref_mb.specific_load - 1).max()
        env = [
            np.abs(
                worst_case(a, SPEEDS, 1).specific_load / worst_case(b, SPEEDS, 1).specific_load
                - 1
            ).max()
            for a, b in ((pk_be, ref_be), (pk_mb, ref_mb))
        ]
        print(
            f"{step:6.2f} {round(720 / step):6d} {t_syn:8.3f} {t_force:9.3f} "
            f"{100 * e_be:10.3f}% {100 * e_mb:12.3f}% {100 * env[0]:10.3f}% {100 * env[1]:12.3f}%"
        )
    wc = worst_case(ref_mb, SPEEDS, 1)
    print("\nReference (0.1 deg) worst peak specific loads over speed [MPa] / speed [rpm]:")
    for case, name in enumerate(("full load", "no load")):
        be = worst_case(ref_be, SPEEDS, 1)
        print(
            f"  {name:9s} big ends {be.specific_load[case].max() / 1e6:6.2f} @ "
            f"{be.coordinate[case].max() / RPM:5.0f};  mains "
            + ", ".join(
                f"{v / 1e6:5.2f} @ {c / RPM:4.0f}"
                for v, c in zip(wc.specific_load[case], wc.coordinate[case], strict=True)
            )
        )
    print(f"\nDEFAULT_STEP_DEG = {DEFAULT_STEP_DEG}; total run time "
          f"{time.perf_counter() - t_total:.1f} s")


if __name__ == "__main__":
    main()
