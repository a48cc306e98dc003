"""Graph calculations for crank-train loads: speed sweep, cylinder pressure, gas and inertia
forces, big-end and main bearing loads, peak specific load per bearing."""

from __future__ import annotations

import numpy as np

from ..calc import crank_forces as cf
from ..calc import operating_points as op
from ..calc import pressure as pr
from ..calc.kinematics import DEFAULT_STEP, cycle_grid
from ..calc.specific_load import peak_specific_load
from ..description.engine import Bearing, Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.loads import BearingLoadDetail, Cycle, CycleDetail, SpecificLoadDetail
from ..workbook.units import RPM
from . import support_beam

CASES = ("full", "no")
"""Load cases swept: full load and no load (Bell, Ricardo 2013: 'at full load and no load across the
speed range'). Part-load data are read and shown but not swept."""
DEFAULT_SPEED_STEP = 100 * RPM
DEFAULT_INTAKE = 1.0e5
SYNTHESIS_RESOLUTION = np.radians(0.2)
"""Internal crank-angle grid of the trace synthesis [rad]; 0.2 deg changes pressures by < 0.1 %
of the peak and IMEP by < 0.2 % against 0.05 deg, at a quarter of the cost
(benchmarks/bench_loads_module.py)."""
CRANK_STEP = DEFAULT_STEP
"""Crank-angle step of the cycle grid [rad] (1 deg: benchmarks/run_all.py, bench_loads.py)."""
CALIBRATION_TOLERANCE = np.radians(0.1)
"""Bisection tolerance on the combustion start when calibrating IMEP [rad]."""

CYCLE = quantity(QuantitySpec(
    "loads.cycle", "Pa", ("case", "speed"),
    "Peak cylinder pressure of the trace used per load case and speed", "bar",
    coords={"case": CASES}, detail=CycleDetail))
BEARING_LOAD = quantity(QuantitySpec(
    "loads.bearing_load", "N", ("item", "case", "speed"),
    "Peak bearing load per bearing, load case and speed", "kN", ("type", "lining"),
    coords={"case": CASES}, detail=BearingLoadDetail))
SPECIFIC = quantity(QuantitySpec(
    "bearing.peak_specific_load", "Pa", ("item", "case", "speed"),
    "Peak specific load max|F|/(D L_eff) per bearing, load case and speed", "MPa",
    ("type", "lining"), coords={"case": CASES}, detail=SpecificLoadDetail))


def speed_sweep(engine: Engine) -> tuple[np.ndarray, list[str]]:
    """Speeds [rad/s]: minimum..maximum in steps (default 100 rpm) plus the overspeed."""
    p = engine.params
    notes = []
    if p.get("speed_points"):
        # explicit speeds (checker correlate: the measured speeds and a grid between them)
        return np.array(sorted(p["speed_points"]), dtype=float), notes
    full = sorted(s for c, s, _ in engine.peak_pressure if c == "full")
    lo = p.get("speed_min") or (full[0] if full else None)
    hi = p.get("speed_max") or (full[-1] if full else None)
    if lo is None or hi is None:
        raise MissingInputs([engine.describe_missing("Engine", "speed_min"),
                             engine.describe_missing("Engine", "speed_max")])
    step = p.get("speed_step") or DEFAULT_SPEED_STEP
    if p.get("speed_step") is None:
        notes.append("Speed step not given: 100 rpm (the practice of Bell, Ricardo 2013).")
    n = int(np.floor((hi - lo) / step + 1e-9)) + 1
    speeds = lo + step * np.arange(n)
    if hi - speeds[-1] > 1e-9:
        speeds = np.append(speeds, hi)
    ov = p.get("overspeed")
    if ov is not None and ov > speeds[-1] + 1e-9:
        speeds = np.append(speeds, ov)
    sub = p.get("speed_subset")
    if sub:
        # screening speeds of a remedy search (checker.remedies.screening): the swept
        # speeds among them (the whole sweep when none is)
        keep = np.isin(np.round(speeds, 6), np.round(np.asarray(sub, dtype=float), 6))
        if keep.any():
            speeds = speeds[keep]
    return speeds, notes


def _trace_from_table(engine: Engine, case: str, theta: np.ndarray, speeds: np.ndarray):
    rows = [r for r in engine.pressure_traces if r[0] == case]
    if not rows:
        return None
    by_speed: dict[float, list[tuple[float, float]]] = {}
    for _, s, a, p in rows:
        by_speed.setdefault(round(s, 9), []).append((a, p))
    sp = np.array(sorted(by_speed))
    traces = []
    for s in sp:
        pts = sorted(by_speed[s])
        a = np.array([x[0] for x in pts])
        pv = np.array([x[1] for x in pts])
        try:
            traces.append(pr.interpolate_trace(a, pv, theta))
        except ValueError as exc:
            raise MissingInputs([f"PressureTraces: {case} load at {s / RPM:.0f} rpm: {exc}"]
                                ) from None
    return op.traces_at_speeds(sp, np.array(traces), speeds)


def build_cycle(engine: Engine, step: float | None = None) -> Cycle:
    """Pressure traces for every swept case and speed (given traces or synthesized)."""
    step = CRANK_STEP if step is None else step
    p = engine.params
    speeds, notes = speed_sweep(engine)
    theta = cycle_grid(step)
    C, S, N = len(CASES), speeds.size, theta.size
    pressure = np.zeros((C, S, N))
    synth = np.zeros((C, S), bool)
    extrap = np.zeros((C, S), bool)
    motored = np.zeros((C, S), bool)
    target = np.full((C, S), np.nan)
    missing = []
    r = p["stroke"] / 2.0
    for ci, case in enumerate(CASES):
        table = _trace_from_table(engine, case, theta, speeds)
        if table is not None:
            pressure[ci], extrap[ci] = table
            continue
        pts = sorted((s, pk) for c, s, pk in engine.peak_pressure if c == case)
        if not pts:
            missing.append(f"PeakPressure: no peak pressures for {case} load (or PressureTraces)")
            continue
        if p.get("compression_ratio") is None:
            missing.append(engine.describe_missing("Engine", "compression_ratio",
                                                   what="the engine (needed to synthesize"
                                                   " pressure traces)"))
            continue
        peak, ex = pr.peak_pressure_at_speed(np.array([x[0] for x in pts]),
                                             np.array([x[1] for x in pts]), speeds,
                                             extrapolation="constant")
        extrap[ci] = ex
        synth[ci] = True
        intake = p.get("intake_pressure") or DEFAULT_INTAKE
        kw = dict(bore=p["bore"], crank_radius=r, rod_length=p["rod_length"],
                  compression_ratio=p["compression_ratio"],
                  **engine.offsets, intake_pressure=intake,
                  resolution=SYNTHESIS_RESOLUTION)
        tgt = None
        if case == "full" and engine.brake_torque:
            bt = np.array(engine.brake_torque)
            vd = pr.swept_volume(p["bore"], r, p["rod_length"], kw["cylinder_offset"],
                                 kw["pin_offset"]) * len(engine.cylinders)
            # outside the BrakeTorque range the target IMEP is held at its value at the
            # nearest BrakeTorque speed (never above it): evaluated at the clipped speed
            tgt, held = op.full_load_target_imep(speeds, bt[:, 0], bt[:, 1], vd)
            out = np.abs(held - speeds) > 1e-9
            if out.any():
                sides = [f"{tgt[out & (held == s_)][0] / 1e5:.1f} bar at {s_ / RPM:.0f} rpm"
                         for s_ in (bt[0, 0], bt[-1, 0]) if np.any(out & (held == s_))]
                notes.append(
                    "Full load outside the BrakeTorque speeds (at"
                    f" {_speeds_text(speeds[out] / RPM)}): IMEP held at its value at the nearest"
                    f" BrakeTorque speed ({'; '.join(sides)}), never above it, and the peak"
                    " pressure held at the nearest PeakPressure speed: the synthesized trace"
                    " there is the trace of that speed (above the range the brake torque then"
                    " falls with the rising friction) instead of an uncalibrated, more severe"
                    " one.")
        elif case == "no":
            # no load: brake torque zero, the indicated work only overcomes friction
            tgt = np.asarray(pr.fmep_barnes_moss(speeds), dtype=float)
        if tgt is not None and np.isfinite(tgt).any():
            ok = np.isfinite(tgt)
            tr, _, not_matched = pr.calibrate_combustion_start(
                theta, peak[ok], tgt[ok], tolerance=CALIBRATION_TOLERANCE,
                intake_floor=pr.INTAKE_FLOOR if case == "no" else None, **kw)
            low = ok.copy()
            low[ok] = np.abs(tr.intake_pressure / intake - 1) > 1e-9
            if case == "no" and low.any():
                pin = tr.intake_pressure[low[ok]] / 1e5
                notes.append(f"No-load target IMEP (friction) above what combustion phasing"
                             f" reaches at the intake pressure {intake / 1e5:.3g} bar and the"
                             f" no-load peak pressure, at {_speeds_text(speeds[low] / RPM)}:"
                             f" intake pressure lowered to {pin.min():.3g}-{pin.max():.3g} bar"
                             " (combustion start 15 deg before TDC) so that the trace meets"
                             " both.")
            pressure[ci, ok] = tr.pressure
            motored[ci, ok] = tr.motored
            target[ci, ok] = tgt[ok]
            if np.any(not_matched):
                bad = speeds[ok][not_matched] / RPM
                notes.append(f"{case.capitalize()}-load target IMEP could not be matched by"
                             f" combustion phasing at {_speeds_text(bad)}; nearest phasing"
                             " used.")
            if np.any(~ok):
                tr2 = pr.synthesize_trace(theta, peak[~ok], **kw)
                pressure[ci, ~ok] = tr2.pressure
                motored[ci, ~ok] = tr2.motored
        else:
            tr = pr.synthesize_trace(theta, peak, **kw)
            pressure[ci] = tr.pressure
            motored[ci] = tr.motored
    if missing:
        raise MissingInputs(missing)
    off = engine.offsets
    vol = pr.cylinder_volume(theta, p["bore"], r, p["rod_length"],
                             p.get("compression_ratio") or 10.0,
                             off["cylinder_offset"], off["pin_offset"])
    vd1 = pr.swept_volume(p["bore"], r, p["rod_length"], off["cylinder_offset"],
                          off["pin_offset"])
    imep = pr.indicated_mean_effective_pressure(pressure, vol, vd1)
    for ci, case in enumerate(CASES):
        if extrap[ci].any():
            notes.append(f"{case.capitalize()}-load pressure held at the nearest given speed"
                         f" (explicit extrapolation) at {_speeds_text(speeds[extrap[ci]] / RPM)}.")
    envelope = np.ones((C, S), bool)
    if "full" in CASES:
        # full load exists only where the engine has full-load data: above (below) the last
        # (first) given full-load speed the points are computed and plotted but not judged
        ci = CASES.index("full")
        data_speeds = [s for c, s, _ in engine.peak_pressure if c == "full"] + [
            r[1] for r in engine.pressure_traces if r[0] == "full"]
        if data_speeds:
            envelope[ci] = op.data_envelope(speeds, data_speeds)
            if not envelope[ci].all():
                notes.append("Full-load rules are judged within the full-load data range"
                             f" ({min(data_speeds) / RPM:.0f}-{max(data_speeds) / RPM:.0f} rpm);"
                             " full-load points outside it rest on extrapolated pressure and are"
                             " shown, not judged. No load is judged at every speed including"
                             " overspeed.")
    return Cycle(theta, speeds, CASES, pressure, synth, extrap, motored, imep, target, notes,
                 envelope)


def _speeds_text(rpm: np.ndarray) -> str:
    rpm = np.round(rpm).astype(int)
    if rpm.size > 3 and np.all(np.diff(rpm) == rpm[1] - rpm[0]):
        return f"{rpm[0]}-{rpm[-1]} rpm"
    return ", ".join(str(x) for x in rpm) + " rpm"


def _required(engine: Engine, names: tuple[str, ...]) -> None:
    miss = [engine.describe_missing("Engine", n) for n in names if engine.params.get(n) is None]
    if miss:
        raise MissingInputs(miss)


@calculation("pressure_traces", "loads", provides=("loads.cycle",),
             reads=("params", "cylinders", "peak_pressure", "pressure_traces", "brake_torque"))
def pressure_traces(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Cylinder pressure over the 720 deg cycle for every load case and speed."""
    if not engine.cylinders:
        raise MissingInputs(["Cylinders: no cylinders given (sheet Cylinders)"])
    cyc = build_cycle(engine)
    peak = cyc.pressure.max(axis=-1)
    assumptions = []
    if cyc.synthesized.any():
        assumptions.append(
            "Cylinder pressure traces synthesized (polytropic compression/expansion with a Wiebe"
            " heat release calibrated to the peak pressure; Heywood 1988 ch. 9) for "
            + ", ".join(f"{c} load" for ci, c in enumerate(cyc.cases)
                        if cyc.synthesized[ci].any()) + ".")
        if np.isfinite(cyc.target_imep).any():
            assumptions.append(
                "Combustion phasing calibrated so the IMEP equals the brake torque (full load;"
                " zero at no load) plus a friction estimate (FMEP = 0.97 + 0.15 N/1000 + 0.05"
                " (N/1000)^2 bar, Barnes-Moss, in Heywood 1988 ch. 13).")
        if engine.params.get("intake_pressure") is None:
            assumptions.append("Intake pressure not given: 1.0 bar absolute.")
    if cyc.motored.any():
        assumptions.append("Cases whose peak pressure is below the motored peak use a motored"
                           " (no-combustion) trace with throttled intake pressure.")
    assumptions += cyc.notes
    return {"loads.cycle": Quantity(CYCLE, peak, {"case": list(cyc.cases),
                                                  "speed": list(cyc.speeds)},
                                    detail=CycleDetail(cycle=cyc,
                                                       assumptions=tuple(assumptions)))}


def _bearing_sets(engine: Engine, n_pins: int, n_cyl: int) -> tuple[list[Bearing], list[Bearing]]:
    mains = [b for b in engine.bearings if b.type == "main"]
    bigs = [b for b in engine.bearings if b.type == "big end"]
    problems = []
    if mains and len(mains) != n_pins + 1:
        problems.append(f"Bearings: {len(mains)} main bearings given; a crank with {n_pins}"
                        f" throws has {n_pins + 1}")
    if bigs and len(bigs) != n_cyl:
        problems.append(f"Bearings: {len(bigs)} big-end bearings given for {n_cyl} cylinders")
    if problems:
        raise MissingInputs(problems)
    return mains, bigs


def shared_pins_text(engine: Engine) -> list[str]:
    """One line naming the cylinders that share a crank pin (V engines), or nothing."""
    by_pin: dict[int, list[int]] = {}
    for c in engine.cylinders:
        by_pin.setdefault(c.pin, []).append(c.number)
    shared = {j: cs for j, cs in sorted(by_pin.items()) if len(cs) > 1}
    if not shared:
        return []
    pins = "; ".join(f"pin {j}: cylinders {', '.join(map(str, cs))}" for j, cs in shared.items())
    return [f"Crank pins carrying two or more rods ({pins}): each pin's load, the main bearing"
            " loads and the pin fillet bending use the vector sum of the forces of the rods on"
            " the pin, both at the pin's mid-plane; big-end loads stay per rod, each in its own"
            " rod frame."]


@calculation("bearing_loads", "loads", provides=("loads.bearing_load",),
             needs=("loads.cycle",),
             reads=("params", "cylinders", "crank_mass", "crank", "bearings.name",
                    "bearings.type", "bearings.index", "bearings.lining",
                    "bearings.support_stiffness", "bearings.support_offset"))
def bearing_loads(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Big-end loads (rod frame) and main bearing loads (block frame, statically determinate)."""
    _required(engine, ("piston_mass", "rod_mass", "rod_com", "rod_inertia"))
    cyc: Cycle = inputs["loads.cycle"].detail.cycle
    p = engine.params
    cyls = engine.cylinders
    n_cyl = len(cyls)
    pins = np.array([c.pin - 1 for c in cyls])
    n_pins = int(pins.max()) + 1
    mains, bigs = _bearing_sets(engine, n_pins, n_cyl)
    firing = np.array([c.firing_angle for c in cyls])
    bank = np.array([c.bank_angle for c in cyls])
    r = p["stroke"] / 2.0
    omega = cyc.speeds[None, :]  # (1, S) against pressure (C, S, 1, N)
    loads = cf.cylinder_loads(
        cyc.theta, omega, cyc.pressure[:, :, None, :], bore=p["bore"], crank_radius=r,
        rod_length=p["rod_length"], piston_mass=p["piston_mass"], rod_mass=p["rod_mass"],
        rod_cg_from_big_end=p["rod_com"], rod_inertia=p["rod_inertia"], firing_angle=firing,
        bank_angle=bank, **engine.offsets)
    names, fx, fy, wj, wb = [], [], [], [], []
    beam_detail = main_determinate = None
    missing: dict[tuple, list[str]] = {}
    attrs = {}
    C, S, N = cyc.pressure.shape
    # big ends: load of the pin on the rod's bearing in the rod frame; journal turns at
    # omega - omega_rod relative to the rod, the bearing (rod) is the frame
    for b in bigs:
        i = b.index - 1
        names.append(b.name)
        fx.append(loads.big_end_rod.x[:, :, i, :])
        fy.append(loads.big_end_rod.y[:, :, i, :])
        wj.append(np.broadcast_to(cyc.speeds[None, :, None] - loads.rod_omega[..., i, :],
                                  (C, S, N)))
        wb.append(np.zeros((C, S, N)))
    if mains:
        if not engine.crank_mass:
            for b in mains:
                missing[(len(names),)] = ["CrankMass: crank mass properties are needed for"
                                          " the main bearing loads (sheet CrankMass)"]
                names.append(b.name)
                fx.append(np.full((C, S, N), np.nan))
                fy.append(np.full((C, S, N), np.nan))
                wj.append(np.broadcast_to(cyc.speeds[None, :, None], (C, S, N)))
                wb.append(np.zeros((C, S, N)))
        else:
            if p.get("main_spacing") is None:
                raise MissingInputs([engine.describe_missing("Engine", "main_spacing")])
            gamma = cf.throw_angles(firing, bank, pins, n_pins)
            m = engine.crank_mass
            pos = cf.mass_positions([it.z for it in m], [it.y for it in m],
                                    [it.throw - 1 for it in m],
                                    [it.reference == "pin axis" for it in m], gamma, r)
            mains_load = cf.main_bearing_loads(
                cyc.theta, omega, loads.big_end_block, pin_index=pins,
                rod_axial_position=p["main_spacing"] / 2.0,
                bay_length=np.full(n_pins, p["main_spacing"]),
                mass=np.array([it.mass for it in m]),
                mass_bay=np.array([it.throw - 1 for it in m]), mass_position=pos,
                mass_axial_position=np.array([it.axial + it.x for it in m]))
            if support_beam.scheme_of(engine) != "determinate":
                beam = support_beam.build_beam(engine, gamma)
                main_determinate = mains_load
                mains_load, beam_detail = support_beam.continuous_main_loads(
                    beam, engine, cyc.theta, cyc.speeds, loads.big_end_crank, pins, gamma, r,
                    list(cyc.cases))
            for b in mains:
                k = b.index - 1
                names.append(b.name)
                fx.append(mains_load.x[:, :, k, :])
                fy.append(mains_load.y[:, :, k, :])
                wj.append(np.broadcast_to(cyc.speeds[None, :, None], (C, S, N)))
                wb.append(np.zeros((C, S, N)))
    order = [b.name for b in engine.bearings]
    idx = [names.index(n) for n in order]
    bearings = {b.name: b for b in engine.bearings}
    empty = np.zeros((0, C, S, N))  # no Bearings sheet: crank forces only (fatigue, TV)

    def stacked(arrays: list) -> np.ndarray:
        return np.stack([arrays[i] for i in idx]) if idx else empty

    fx, fy = stacked(fx), stacked(fy)
    missing = {(order.index(names[k[0]]),): v for k, v in missing.items()}
    mag = np.hypot(fx, fy)
    peak = np.where(np.isnan(mag).any(axis=-1), np.nan, np.nanmax(
        np.where(np.isnan(mag), -np.inf, mag), axis=-1))
    for n in order:
        b = bearings[n]
        attrs[n] = {"type": b.type, "lining": (b.lining or "").lower() or None}
        if attrs[n]["lining"] is None:  # the lining rules cannot tell: not evaluated
            attrs[n]["lining_missing"] = [engine.describe_missing("Bearings", "lining", b.row, n)]
    detail = BearingLoadDetail(
        theta=cyc.theta, fx=fx, fy=fy, omega_journal=stacked(wj), omega_bearing=stacked(wb),
        frames={n: ("con-rod frame" if bearings[n].type == "big end" else "block frame")
                for n in order},
        torque=loads.torque, big_end_crank=loads.big_end_crank,
        scheme=support_beam.scheme_of(engine), beam=beam_detail,
        main_determinate=main_determinate,
        assumptions=(
            ("Main bearing loads by the statically determinate method: rigid crank pinned"
             " at each main, each main carries only the adjacent throws (Bell, Ricardo 2013)."
             if beam_detail is None else beam_detail.assumptions[0]),
            "Con-rod as two masses plus an inertia-correction couple (exact rigid-body"
            " dynamics of the slider crank); constant crank speed; gravity neglected.",
            *shared_pins_text(engine)))
    q = Quantity(BEARING_LOAD, peak, {"item": order, "case": list(cyc.cases),
                                      "speed": list(cyc.speeds)}, attrs, missing, detail=detail)
    return {"loads.bearing_load": q}


@calculation("specific_load", "loads", provides=("bearing.peak_specific_load",),
             needs=("loads.bearing_load",), reads=("bearings",))
def specific_load(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Peak specific load = max|F| / (D L_eff) per bearing, load case and speed."""
    bl = inputs["loads.bearing_load"]
    if not bl.coords["item"]:
        raise MissingInputs(["Bearings: no bearings given (sheet Bearings)"])
    ex: BearingLoadDetail = bl.detail
    # diameter and width from the engine, not from the loads: a width variant (remedies,
    # tolerance corners, studies) then leaves the bearing loads and what needs them cached
    bearings = {b.name: b for b in engine.bearings}
    names = bl.coords["item"]
    dia = np.array([bearings[n].diameter for n in names])
    length = np.array([bearings[n].length for n in names])
    ok = np.isfinite(bl.values)
    val = np.full(bl.values.shape, np.nan)
    theta_max = np.full(bl.values.shape, np.nan)
    rows = np.where(ok.all(axis=(1, 2)))[0]
    if rows.size:
        psl = peak_specific_load(ex.fx[rows], ex.fy[rows], ex.theta,
                                 dia[rows, None, None], length[rows, None, None])
        val[rows] = psl.specific_load
        theta_max[rows] = psl.theta
    return {"bearing.peak_specific_load": Quantity(
        SPECIFIC, val, bl.coords, bl.item_attrs, dict(bl.missing),
        detail=SpecificLoadDetail(theta_at_max=theta_max))}
