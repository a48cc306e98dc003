"""Benchmark of the torsional-vibration (TV) sweep of the example I4 engine (not a test).

Run: ``/work/venv/bin/python benchmarks/bench_tv.py``

Model (seeds/000, workbook example): damper ring 0.0055, crank nose 0.001155, 4 x cylinder
0.0065732, flywheel (AUTO) 0.174743 kg m^2; stiffnesses 25500 (rubber), 171035, 403300, 416625,
403300, 661013 N m/rad; crankshaft damping 1.5 N m s/rad to a constant-speed node at each
cylinder; rubber loss factor 0.15 (workbook assumption). Excitation: full-load peak pressure vs
speed of seeds/000 (held constant above 6500 rpm), synthetic Wiebe traces
(:func:`checker.calc.pressure.synthesize_trace`, compression ratio 10.5), full per-cylinder
torque with con-rod dynamics and the 0.8 mm pin offset
(:func:`checker.calc.crank_forces.cylinder_loads`), firing 1-3-4-2 (0, 540, 180, 360 deg).
61 speeds, 1000..7000 rpm.

Printed: run time of the TV part (harmonic analysis + batched solve + synthesis of all stations,
element torques and damper quantities) and of the excitation preparation, and the error versus a
converged reference (orders up to 48, 2880 points = 0.25 deg) of
* the synthesised crank-nose amplitude (half peak-to-peak, deg), worst speed;
* the per-order crank-nose amplitudes (deg), worst order and speed;
* the synthesised torque of the cylinder-4 -> flywheel element (N m), worst speed;
for max orders 6..48 and excitation resolutions 720, 360, 180 points per cycle.
"""

from __future__ import annotations

import time

import numpy as np

from checker.calc import crank_forces, damper, excitation, pressure, torsional
from checker.calc.kinematics import cycle_grid

RPM = np.pi / 30.0
SPEEDS = np.linspace(1000.0, 7000.0, 61) * RPM
PEAK_TABLE_RPM = np.arange(1000.0, 6501.0, 500.0)
PEAK_TABLE_BAR = [53.4, 59.0, 68.1, 73.6, 77.1, 77.5, 80.0, 83.8, 84.4, 82.7, 79.8, 73.3]
FIRING = np.deg2rad([0.0, 540.0, 180.0, 360.0])
CYL_STATIONS = [2, 3, 4, 5]
NOSE, RING = 1, 0
GEOMETRY = dict(bore=0.086, crank_radius=0.0473, rod_length=0.1457)
MODEL = torsional.TorsionalModel(
    inertia=[0.0055, 0.001155, 0.0065732, 0.0065732, 0.0065732, 0.0065732, 0.174743],
    stiffness=[25500.0, 171035.0, 403300.0, 416625.0, 403300.0, 661013.0],
    damping_abs=[0.0, 0.0, 1.5, 1.5, 1.5, 1.5, 0.0],
    loss_factor=[0.15, 0.0, 0.0, 0.0, 0.0, 0.0],
)


def cylinder_torque(n_points: int) -> np.ndarray:
    """Per-cylinder crank torque, shape (n_speed, 4, n_points) [N m]."""
    theta = cycle_grid(4 * np.pi / n_points)
    peak, _ = pressure.peak_pressure_at_speed(
        PEAK_TABLE_RPM * RPM, np.multiply(PEAK_TABLE_BAR, 1e5), SPEEDS
    )
    trace = pressure.synthesize_trace(
        theta, peak, compression_ratio=10.5, pin_offset=0.0008, **GEOMETRY
    )
    loads = crank_forces.cylinder_loads(
        theta,
        SPEEDS,
        trace.pressure[:, None, :],
        piston_mass=0.4955,
        rod_mass=0.597,
        rod_cg_from_big_end=0.03573,
        rod_inertia=2128e-9,
        firing_angle=FIRING,
        pin_offset=0.0008,
        **GEOMETRY,
    )
    return loads.torque


def tv_sweep(torque: np.ndarray, max_order: float) -> dict[str, np.ndarray]:
    """The TV part: harmonics, batched solve, synthesis of stations, elements and damper."""
    orders, coeffs = excitation.torque_harmonics(torque, max_order)  # (S, 4, O)
    forces = torsional.station_excitation(coeffs, CYL_STATIONS, MODEL.n_stations)
    resp = torsional.forced_response(MODEL, SPEEDS, orders, forces)
    dphi = damper.relative_twist(resp.theta[:, NOSE], resp.theta[:, RING])
    power = damper.dissipated_power(dphi, resp.omega, MODEL.stiffness[0], 0.15).sum(-1)
    return {
        "orders": orders,
        "theta": resp.theta,
        "station_amp": resp.station_amplitude(),
        "torque_amp": resp.element_torque_amplitude(),
        "twist_amp": damper.synthesized_amplitude(orders, dphi),
        "damper_power": power,
        "resonance": resp.resonance,
    }


def timed(fn, *args, repeat: int = 7) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args)
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    ref_torque = cylinder_torque(2880)
    ref = tv_sweep(ref_torque, 48.0)
    ref_nose = np.rad2deg(ref["station_amp"][:, NOSE])
    ref_order = np.rad2deg(np.abs(ref["theta"][:, NOSE]))  # (S, 96)
    ref_fw = ref["torque_amp"][:, 5]
    print(
        f"reference: max order 48, 2880 points/cycle; nose amplitude max "
        f"{ref_nose.max():.4f} deg at {SPEEDS[ref_nose.argmax()] / RPM:.0f} rpm; "
        f"flywheel-element torque max {ref_fw.max():.0f} N m; damper power max "
        f"{ref['damper_power'].max():.1f} W; undamped resonances flagged: "
        f"{int(ref['resonance'].sum())}"
    )
    for order in (2.0, 4.0, 6.0, 8.0):
        amp = ref_order[:, int(round(2 * order)) - 1]
        print(
            f"  crank-nose order {order:g}: max {amp.max():.4f} deg at "
            f"{SPEEDS[amp.argmax()] / RPM:.0f} rpm"
        )
    print()
    header = (
        f"{'points':>6} {'max ord':>7} {'TV time ms':>10} {'exc. ms':>8} "
        f"{'nose tot err %':>14} {'nose tot err deg':>16} {'order err deg':>13} "
        f"{'fw torque err %':>15}"
    )
    print(header)
    print("-" * len(header))
    cases = [(720, m) for m in (6.0, 8.0, 12.0, 16.0, 24.0, 48.0)]
    cases += [(360, 24.0), (180, 24.0), (360, 48.0)]
    for n_points, max_order in cases:
        t_exc, torque = timed(cylinder_torque, n_points, repeat=3)
        t_tv, out = timed(tv_sweep, torque, max_order)
        nose = np.rad2deg(out["station_amp"][:, NOSE])
        n_o = out["orders"].size
        err_tot = np.abs(nose - ref_nose)
        err_ord = np.abs(np.rad2deg(np.abs(out["theta"][:, NOSE])) - ref_order[:, :n_o]).max()
        err_fw = np.max(np.abs(out["torque_amp"][:, 5] - ref_fw) / ref_fw)
        print(
            f"{n_points:>6} {max_order:>7.0f} {1e3 * t_tv:>10.1f} {1e3 * t_exc:>8.1f} "
            f"{100 * np.max(err_tot / ref_nose):>14.3f} {err_tot.max():>16.5f} "
            f"{err_ord:>13.2e} {100 * err_fw:>15.3f}"
        )


if __name__ == "__main__":
    main()
