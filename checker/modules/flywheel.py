"""Graph calculation for flywheel sizing: speed fluctuation, fluctuation energy and coefficient
of cyclic irregularity at every swept speed and load case, and the minimum inertia for the
project's target irregularity (:mod:`checker.calc.flywheel`).

Inputs: the engine torque over the cycle already computed by the loads module (every
cylinder's gas + inertia torque at constant speed, firing phased; detail ``torque`` of
``loads.bearing_load``) and the inertias of the torsional model (sheet ``TVModel``: the whole
chain turns as one rigid body for this low-frequency motion). The load torque is constant and
equal to the cycle mean (steady state); clutch, gearbox and vehicle inertias are not included
(idle, declutched).

Rule FLY-001 judges the lowest swept speed (full and no load) against the target from the
Engine sheet ('Target cyclic irregularity').
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..calc import flywheel as fw
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.flywheel import FlywheelDetail

CASES = ("full", "no")

IRREG = quantity(QuantitySpec(
    "flywheel.cyclic_irregularity", "", ("case", "speed"),
    "Coefficient of cyclic irregularity (w_max - w_min)/w_mean of the rigid engine (w_mean the"
    " time-mean speed over the cycle)", "%",
    coords={"case": CASES}, detail=FlywheelDetail))
ENERGY = quantity(QuantitySpec(
    "flywheel.fluctuation_energy", "J", ("case", "speed"),
    "Fluctuation energy W_max - W_min of the engine torque over the cycle", "J",
    coords={"case": CASES}, detail=FlywheelDetail))
SPEED_FLUCT = quantity(QuantitySpec(
    "flywheel.speed_fluctuation", "rad/s", ("case", "speed"),
    "Speed fluctuation w_max - w_min over the cycle", "rpm", coords={"case": CASES},
    detail=FlywheelDetail))
MIN_INERTIA = quantity(QuantitySpec(
    "flywheel.minimum_inertia", "kg*m**2", ("case", "speed"),
    "Minimum flywheel inertia for the target irregularity (total needed minus the rest of"
    " the torsional model; <= 0: the rest already suffices)", "kg*m**2",
    coords={"case": CASES}, detail=FlywheelDetail))

PROVIDES = ("flywheel.cyclic_irregularity", "flywheel.fluctuation_energy",
            "flywheel.speed_fluctuation", "flywheel.minimum_inertia")


@calculation("flywheel", "flywheel", provides=PROVIDES, needs=("loads.bearing_load",),
             reads=("tv_model", "params.target_irregularity"))
def flywheel(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Cyclic irregularity, fluctuation energy and minimum flywheel inertia."""
    st = engine.tv_model
    if not st:
        raise MissingInputs(["TVModel: the rotating inertias (damper ring, crank, flywheel) are"
                             " needed for the cyclic irregularity (sheet TVModel)"])
    bl = inputs["loads.bearing_load"]
    theta = bl.detail.theta
    torque = bl.detail.torque.sum(axis=-2)  # (C, S, N): all cylinders
    speeds = np.asarray(bl.coords["speed"], dtype=float)
    cases = list(bl.coords["case"])
    j_total = float(sum(s.inertia for s in st))
    fws = [s for s in st if s.role == "flywheel"]
    j_fw = float(sum(s.inertia for s in fws))
    j_rest = j_total - j_fw
    res = fw.cyclic_irregularity(theta, torque, j_total, speeds[None, :])
    coords = {"case": cases, "speed": list(speeds)}
    lowest = np.zeros(res.irregularity.shape, bool)
    lowest[:, int(np.argmin(speeds))] = True
    target = engine.params.get("target_irregularity")
    if target is None:
        attrs = {"all": {"limit_missing": [engine.describe_missing(
            "Engine", "target_irregularity", what="the project (by application; blank = not"
            " judged)")]}}
    else:
        attrs = {"all": {"limit": (float(target),),
                         "limit_cell": engine.cell("Engine", "target_irregularity")}}
    assumptions = [
        "Cyclic irregularity: the whole torsional model turns as one rigid inertia"
        f" ({j_total:.4g} kg m^2, sheet TVModel) driven by the engine torque of the loads"
        " module (gas + inertia at constant speed) against a constant load torque equal to its"
        " mean; clutch, gearbox and vehicle inertias not included (Agostini 2019, Politecnico"
        " di Torino, 'Engine degree of irregularity')."]
    detail = FlywheelDetail(
        theta=theta, omega=res.omega, omega_max=res.omega_max, omega_min=res.omega_min,
        theta_max=res.theta_max, theta_min=res.theta_min, linear=res.irregularity_linear,
        inertia_total=j_total, inertia_flywheel=j_fw,
        flywheel_stations=[s.station for s in fws], target=target,
        lowest_speed=float(speeds.min()), torque=torque, assumptions=tuple(assumptions))
    out = {
        "flywheel.cyclic_irregularity": Quantity(
            IRREG, res.irregularity, coords, attrs, detail=detail, applies=lowest,
            applies_text="the lowest swept speed only (idle / lowest speed)"),
        "flywheel.fluctuation_energy": Quantity(ENERGY, res.energy, coords, detail=detail),
        "flywheel.speed_fluctuation": Quantity(SPEED_FLUCT, res.omega_max - res.omega_min,
                                               coords, detail=detail),
    }
    if target is None:
        miss = attrs["all"]["limit_missing"]
        out["flywheel.minimum_inertia"] = Quantity(
            MIN_INERTIA, np.full(res.energy.shape, np.nan), coords,
            missing={(ci,): list(miss) for ci in range(len(cases))}, detail=detail)
    else:
        j_min = fw.minimum_inertia(theta, torque, speeds[None, :], float(target))
        out["flywheel.minimum_inertia"] = Quantity(
            MIN_INERTIA, j_min - j_rest, coords,
            detail=replace(detail, total_needed=j_min, inertia_rest=j_rest))
    return out
