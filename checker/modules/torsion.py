"""Graph calculations for crankshaft torsional vibration (TV), the rubber TV damper and the
TV torques at the bolted joints (module ``torsion``, "Torsional vibration").

Which node computes what: ``tv_response`` gives every ``tv.*`` quantity but the joint torques
and the damper rubber's response ``damper.relative_twist``, ``damper.torque``,
``damper.power``, ``damper.shear_stress``, ``damper.heat_density``,
``damper.heat_density_peak`` and their ratios to the supplier's limits (rules DMP-001..003);
``tv_joint_torque`` gives ``tv.joint_torque``. The damper's *tuning* (``damper.tuning_ratio``,
Den Hartog's optimum, rule DMP-004) is module ``damper``, :mod:`checker.modules.damper_tuning`.
Detail types: :mod:`checker.results.torsion`.

Model (the concept-level VALDYN practice of Bell, Ricardo 2013)
---------------------------------------------------------
* Lumped-mass chain from sheet ``TVModel``, front to rear in row order: station ``i`` has the
  inertia ``J_i`` and absolute viscous damping ``d_i`` to a node rotating at the mean speed;
  element ``e`` joins station ``e`` to station ``e + 1`` with the stiffness and relative damping
  of row ``e`` ("stiffness to next", "damping to next"). The damper element is the element from
  the ``damper ring`` station to the next one; it gets the rubber's hysteretic loss factor from
  sheet ``Damper`` (``k* = k (1 + j eta)``). The variable inertia of pistons and rods is
  represented by the constant inertia lumped at the cylinder stations (Bell, Ricardo 2013).
* Excitation: the crank torque of one cylinder (gas pressure + reciprocating and con-rod
  inertia at constant speed, :func:`checker.calc.crank_forces.cylinder_loads`, offsets
  included) from the loads module's pressure traces (quantity ``loads.cycle``), its harmonics
  (:func:`checker.calc.excitation.torque_harmonics`, orders 0.5..24), phased by the firing
  angles (sheet ``Cylinders``) and applied at the cylinder stations (``TVModel`` column
  ``cylinder``; a station may carry several cylinders, e.g. both of a V-engine crank pin, and
  then takes the sum of their phased torques). All cylinders have the same geometry, so
  cylinder ``i`` is cylinder 1 shifted by its firing angle (exact in the frequency domain); the
  bank angle does not enter, since a cylinder's crank torque depends only on its own kinematic
  crank angle ``theta - phi_i``.
* Steady-state forced response per order and speed at full and no load in one batched solve
  (:func:`checker.calc.torsional.forced_response`); totals are synthesised over 720 deg and
  given as half peak-to-peak ("half range").

Sign conventions
----------------
* Angles: ``theta_i(t) = sum_n Re{Theta_in exp(j n w t)}``, station angle relative to a node
  rotating at the mean speed, positive in the direction of rotation (so the crank-nose motion is
  *not* twist; Bell, Ricardo 2013). Amplitudes are 0-to-peak per order, half peak-to-peak for
  totals.
* Element torque ``T_e`` (quantity ``tv.element_torque``, detail fields ``coeffs``,
  ``vib_max``, ``vib_min``, ``mean``): the torque the front part of the chain exerts on the
  rear part through element ``e``, positive in the direction of rotation; equivalently
  positive when the front station leads the rear one. A crankshaft transmitting drive torque
  to the flywheel carries a positive mean torque.
* Mean element torque: the mean cylinder (indicated, gas) torques applied at the cylinder
  stations and the accessory-drive torque taken off at the crank-nose station, summed from the
  front: ``T_mean,e = sum_{cylinder stations in front of e} mean(T_cyl) - T_FEAD [nose in
  front of e]``. Friction is not subtracted, so the flywheel element carries brake torque plus
  friction torque (conservative toward the flywheel); the flywheel station takes the remainder.
* Damper rubber (``damper.*``): relative twist ``dphi = Theta_hub - Theta_ring`` and torque hub
  -> ring ``(k' + j k'') dphi`` (:mod:`checker.calc.damper`).
* Joint torque (``tv.joint_torque``): the peak over the cycle of the magnitude of the total
  torque (mean + vibratory) through the joint: crank nose ``|T_FEAD - T_rubber(t)|`` (the
  crank drives the pulley and the damper ring), flywheel ``|T_brake + T_e,flywheel(t)|``.

Findings (undamped modes): an order exactly on the natural frequency of a mode without damping
(regularised solve, :data:`checker.calc.torsional.RESONANCE_TOLERANCE`), and an order near one:
undamped amplification >= 10 or a crossing between two swept speeds, where the response is
unbounded although every swept amplitude is finite
(:func:`checker.calc.torsional.undamped_resonance_band`).

Damper limits: the supplier's limits are per engine (sheet ``Damper``): the rules compare the
shear stress [MPa] and heat per volume [W/cm^3] with the limit carried by the quantity
(``limit_from = "workbook"``); without the limit the rule is ``not evaluated`` naming the Damper
cell. The ratios value / limit (``damper.*_ratio``) are reported beside.

Calculations: ``tv_response`` (all ``tv.*`` and ``damper.*`` quantities but the joint torques)
and ``tv_joint_torque`` (``tv.joint_torque``, needed by the joints module when JointTorques
does not give every joint and operating point) share one solve per run. ``tv_joint_torque``
never fails on missing TV inputs: its entries are missing with the reasons, so the joints
module still uses the torques the workbook gives.
"""

from __future__ import annotations

import weakref

import numpy as np

from ..calc import crank_forces as cf
from ..calc import damper as dmp
from ..calc import excitation as exc
from ..calc import torsion_post as tp
from ..calc import torsional as tv
from ..calc import viscous_damper as vd
from ..description.engine import Engine
from ..evaluation.graph import (
    MissingInputs,
    Quantity,
    QuantitySpec,
    calculation,
    quantity,
    resonant_peaks,
)
from ..results.torsion import (
    CylinderOrderDetail,
    DamperDetail,
    ElementTorqueDetail,
    JointTorqueDetail,
    LowerOrdersDetail,
    NaturalFrequencyDetail,
    NoseDetail,
    OrdersCheckedDetail,
    TorsionDetail,
    TVModelData,
    TwistDetail,
)
from ..workbook.units import RPM
from . import coupling as cpl
from . import damper_inputs as dinp
from .joints import POINTS

CASES = ("full", "no")
MAX_ORDER = exc.DEFAULT_MAX_ORDER
"""Highest harmonic order (24; benchmarks/bench_tv.py: <= 0.03 % on the nose amplitude)."""
EXTREMES_SAMPLES_PER_PERIOD = tp.EXTREMES_SAMPLES_PER_PERIOD
"""Samples per period of the highest order for the max/min of synthesised torques (refined by a
parabola through the largest sample and its neighbours)."""

NATURAL = quantity(QuantitySpec(
    "tv.natural_frequency", "Hz", ("mode",),
    "Undamped natural frequencies of the torsional model (flexible modes)", "Hz",
    detail=NaturalFrequencyDetail))
NOSE = quantity(QuantitySpec(
    "tv.nose_amplitude", "rad", ("case", "speed"),
    "Crank-nose TV amplitude, all orders synthesised (half peak-to-peak)", "deg",
    coords={"case": CASES}, detail=NoseDetail))
NOSE_ORDER = quantity(QuantitySpec(
    "tv.nose_order_amplitude", "rad", ("order", "case", "speed"),
    "Crank-nose TV amplitude per order (0-to-peak)", "deg", coords={"case": CASES},
    detail=TorsionDetail))
NOSE_CYL = quantity(QuantitySpec(
    "tv.nose_cylinder_order_amplitude", "rad", ("case", "speed"),
    "Crank-nose TV amplitude of the order equal to the cylinder count (4th for an I4, 6th for"
    " a V6/I6)", "deg", ("engine_class",), coords={"case": CASES},
    detail=CylinderOrderDetail))
NOSE_HIGH = quantity(QuantitySpec(
    "tv.nose_higher_order_amplitude", "rad", ("order", "case", "speed"),
    "Crank-nose TV amplitude of each order above the cylinder count", "deg",
    ("engine_class",), coords={"case": CASES}, detail=OrdersCheckedDetail))
NOSE_LOW = quantity(QuantitySpec(
    "tv.nose_lower_order_elastic_amplitude", "rad", ("order", "case", "speed"),
    "Elastic crank-nose TV amplitude (nose motion less the rigid-body motion) of each order"
    " below the cylinder count, 0-to-peak", "deg", ("engine_class",), coords={"case": CASES},
    detail=LowerOrdersDetail))
TWIST = quantity(QuantitySpec(
    "tv.crank_twist", "rad", ("case", "speed"),
    "Crankshaft twist crank nose to flywheel, all orders synthesised (half peak-to-peak)", "deg",
    coords={"case": CASES}, detail=TwistDetail))
ELEMENT = quantity(QuantitySpec(
    "tv.element_torque", "N*m", ("item", "case", "speed"),
    "Vibratory torque in each element of the TV model (half peak-to-peak; mean, max/min and"
    " per-order torques in the report section)", "N*m", ("kind",), coords={"case": CASES},
    detail=ElementTorqueDetail))
JOINT = quantity(QuantitySpec(
    "tv.joint_torque", "N*m", ("item", "point"),
    "Peak torque through a bolted joint from the TV model (mean + vibratory)", "N*m",
    ("location",), coords={"point": POINTS}, detail=JointTorqueDetail))
D_TWIST = quantity(QuantitySpec(
    "damper.relative_twist", "rad", ("case", "speed"),
    "Damper rubber relative twist hub - ring (half peak-to-peak)", "deg",
    coords={"case": CASES}, detail=DamperDetail))
D_TORQUE = quantity(QuantitySpec(
    "damper.torque", "N*m", ("case", "speed"),
    "Damper rubber torque (half peak-to-peak)", "N*m", coords={"case": CASES},
    detail=DamperDetail))
D_POWER = quantity(QuantitySpec(
    "damper.power", "W", ("case", "speed"),
    "Power dissipated in the damper rubber (sum of orders)", "W", coords={"case": CASES},
    detail=DamperDetail))
D_SHEAR = quantity(QuantitySpec(
    "damper.shear_stress", "Pa", ("case", "speed"),
    "Damper rubber shear stress amplitude at the inner (bonded) radius", "MPa",
    filters=("damper_type",), coords={"case": CASES},
    detail=DamperDetail))
D_HEAT = quantity(QuantitySpec(
    "damper.heat_density", "W/m**3", ("case", "speed"),
    "Mean heat generated per unit rubber volume (P/V)", "W/cm**3", filters=("damper_type",),
    coords={"case": CASES}, detail=DamperDetail))
D_HEAT_PEAK = quantity(QuantitySpec(
    "damper.heat_density_peak", "W/m**3", ("case", "speed"),
    "Peak local heat per unit rubber volume (inner radius, q_mean (r_o/r_i)^2)", "W/cm**3",
    filters=("damper_type",), coords={"case": CASES},
    detail=DamperDetail))
D_SHEAR_RATIO = quantity(QuantitySpec(
    "damper.shear_stress_ratio", "", ("case", "speed"),
    "Damper rubber shear stress / supplier limit (Damper sheet)", "", coords={"case": CASES},
    detail=DamperDetail))
D_HEAT_RATIO = quantity(QuantitySpec(
    "damper.heat_ratio", "", ("case", "speed"),
    "Mean rubber heat per unit volume / supplier limit (Damper sheet)", "",
    coords={"case": CASES}, detail=DamperDetail))
D_HEAT_PEAK_RATIO = quantity(QuantitySpec(
    "damper.heat_peak_ratio", "", ("case", "speed"),
    "Peak local rubber heat per unit volume / supplier limit (Damper sheet)", "",
    coords={"case": CASES}, detail=DamperDetail))

_DAMPER_QUANTITIES = ("damper.relative_twist", "damper.torque", "damper.power",
                      "damper.shear_stress", "damper.heat_density", "damper.heat_density_peak",
                      "damper.shear_stress_ratio", "damper.heat_ratio", "damper.heat_peak_ratio")
PROVIDES = ("tv.natural_frequency", "tv.nose_amplitude", "tv.nose_order_amplitude",
            "tv.nose_cylinder_order_amplitude", "tv.nose_higher_order_amplitude",
            "tv.nose_lower_order_elastic_amplitude", "tv.crank_twist",
            "tv.element_torque") + _DAMPER_QUANTITIES


def _rpm_text(w: float) -> str:
    return f"{w / RPM:.0f} rpm"


def _speeds_text(w: np.ndarray) -> str:
    return ", ".join(f"{x / RPM:.0f}" for x in np.sort(w)) + " rpm"


def _tv_inputs(engine: Engine) -> TVModelData:
    """Model data from TVModel/Damper/Cylinders; raises MissingInputs naming the cells."""
    st = engine.tv_model
    problems: list[str] = []
    if len(st) < 2:
        raise MissingInputs(["TVModel: a torsional model of at least two stations (damper"
                             " ring, crank nose, cylinders, flywheel) is needed (sheet TVModel)"])
    roles = [s.role for s in st]
    if "crank nose" not in roles:
        problems.append("TVModel: no station with role 'crank nose' (column 'role')")
    p = engine.params
    for name in ("piston_mass", "rod_mass", "rod_com", "rod_inertia"):
        if p.get(name) is None:
            problems.append(engine.describe_missing("Engine", name, what="the engine (needed"
                                                    " for the inertia torque of the TV"
                                                    " excitation)"))
    station_of = {c: i for i, s in enumerate(st) for c in s.cylinders}
    for c in engine.cylinders:
        if c.number not in station_of:
            problems.append(f"TVModel: no station for cylinder {c.number} (column 'cylinder')")
    ring = roles.index("damper ring") if "damper ring" in roles else None
    if ring is not None and ring == len(st) - 1:
        problems.append("TVModel: the 'damper ring' station is the last one; its rubber element"
                        " is the element to the next station")
        ring = None
    viscous = dinp.is_viscous(engine)
    couplings = cpl.coupling_elements(engine)
    stiffness = np.array([0.0 if (viscous and i == ring) or i in couplings else s.stiffness
                          for i, s in enumerate(st[:-1])], dtype=float)
    rel = np.array([s.relative_damping for s in st[:-1]], dtype=float)
    loss = np.zeros(len(st) - 1)
    if couplings:  # flexible couplings: the catalogue's stiffness and damping (sheet Coupling)
        try:
            state = cpl.coupling_state(engine)
        except MissingInputs as err:
            problems += err.reasons
        else:
            stiffness[couplings] = state.stiffness
            loss[couplings] = cpl.cp.loss_factor(state.relative_damping)
    eta = engine.damper.get("loss_factor")
    dyn = {}
    if ring is not None and viscous:
        # untuned viscous damper: the silicone couples ring and hub (no spring)
        eta = None
        try:
            coupling = dinp.viscous_coupling(engine)
        except MissingInputs as exc:
            problems += exc.reasons
        else:
            if coupling.shear_stiffness is None:
                rel[ring] = coupling.damping
            else:
                dyn[ring] = coupling.impedance
    elif ring is not None:
        if eta is None and rel[ring] == 0:
            problems.append(engine.describe_missing("Damper", "loss_factor",
                                                    what="the damper rubber"))
        loss[ring] = eta or 0.0
    if viscous and ring is None:
        problems.append("TVModel: Damper type 'viscous' needs a station with role 'damper"
                        " ring' (the inertia ring; its hub is the next station)")
    if problems:
        raise MissingInputs(problems)
    model = tv.TorsionalModel(
        inertia=cpl.station_inertia(engine), stiffness=stiffness,
        damping_abs=[s.absolute_damping for s in st], damping_rel=rel, loss_factor=loss,
        dynamic_stiffness=dyn)
    return TVModelData(
        model=model, ring=ring, nose=roles.index("crank nose"),
        flywheel=roles.index("flywheel") if "flywheel" in roles else None,
        cyl_station=np.array([station_of[c.number] for c in engine.cylinders]),
        eta=float(eta or 0.0))


def _excitation(engine: Engine, cyc) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Order coefficients per case, speed, cylinder (C, S, n_cyl, O) and mean cylinder torque.

    One cylinder's torque (firing angle 0) from :func:`cylinder_loads`, its harmonics, phased
    by each cylinder's firing angle: ``F_in = c_n exp(-j n phi_i)``.
    """
    p = engine.params
    loads = cf.cylinder_loads(
        cyc.theta, cyc.speeds[None, :], cyc.pressure[:, :, None, :], bore=p["bore"],
        crank_radius=p["stroke"] / 2.0, rod_length=p["rod_length"],
        piston_mass=p["piston_mass"], rod_mass=p["rod_mass"], rod_cg_from_big_end=p["rod_com"],
        rod_inertia=p["rod_inertia"], firing_angle=np.zeros(1),
        **engine.offsets)
    torque = loads.torque[:, :, 0, :]  # (C, S, N)
    orders, coeffs = exc.torque_harmonics(torque, MAX_ORDER)
    firing = np.array([c.firing_angle for c in engine.cylinders])
    return orders, exc.phase_cylinders(coeffs, orders, firing), torque.mean(axis=-1)


_SOLUTIONS: list[tuple[weakref.ref, weakref.ref, dict]] = []
"""Solutions of the current runs, keyed by (engine, loads.cycle quantity) identity, so that the
two calculations below share one solve within a run (weak references; a few entries)."""


def _solution(engine: Engine, cycle: Quantity) -> dict:
    """The TV solution for this engine and cycle (solved once per run, then reused)."""
    for e_ref, c_ref, sol in _SOLUTIONS:
        if e_ref() is engine and c_ref() is cycle:
            return sol
    sol = _solve(engine, cycle)
    _SOLUTIONS[:] = [x for x in _SOLUTIONS if x[0]() is not None and x[1]() is not None][-3:]
    _SOLUTIONS.append((weakref.ref(engine), weakref.ref(cycle), sol))
    return sol


@calculation("tv_response", "torsion", provides=PROVIDES, needs=("loads.cycle",),
             reads=("params", "cylinders", "tv_model", "damper", "brake_torque", "coupling",
                    "driven"))
def tv_response(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Natural frequencies, forced response at full and no load, element and damper results."""
    return dict(_solution(engine, inputs["loads.cycle"])["quantities"])


@calculation("tv_joint_torque", "torsion", provides=("tv.joint_torque",), needs=("loads.cycle",),
             reads=("params", "cylinders", "tv_model", "damper", "brake_torque",
                    "joint_torques", "joints.name", "joints.location", "coupling", "driven"))
def tv_joint_torque(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Peak TV torque through each bolted joint at the three operating points.

    Never raises for missing TV inputs: the entries are missing with the reasons, so that the
    joints module still uses the torques the workbook gives (JointTorques).
    """
    try:
        sol = _solution(engine, inputs["loads.cycle"])
    except MissingInputs as exc:
        n = len(engine.joints)
        missing = {(i, k): list(exc.reasons) for i in range(n) for k in range(len(POINTS))}
        return {"tv.joint_torque": Quantity(
            JOINT, np.full((n, len(POINTS)), np.nan),
            {"item": [j.name for j in engine.joints], "point": list(POINTS)},
            {j.name: {"location": j.location} for j in engine.joints}, missing,
            detail=JointTorqueDetail(speed=np.full((n, len(POINTS)), np.nan),
                                     case=np.full((n, len(POINTS)), "", dtype=object),
                                     how=np.full((n, len(POINTS)), "", dtype=object)))}
    return {"tv.joint_torque": _joints(engine, **sol["joint_inputs"])}


def _solve(engine: Engine, cycle: Quantity) -> dict:
    """Natural frequencies, forced response at full and no load, element and damper results."""
    if not engine.cylinders:
        raise MissingInputs(["Cylinders: no cylinders given (sheet Cylinders)"])
    data = _tv_inputs(engine)
    model: tv.TorsionalModel = data.model
    cyc = cycle.detail.cycle
    cases = list(cyc.cases)
    speeds = np.asarray(cyc.speeds, dtype=float)
    C, S = len(cases), speeds.size
    n_st, n_el = model.n_stations, model.n_elements
    names = [s.station for s in engine.tv_model]
    roles = [s.role for s in engine.tv_model]
    nose, ring, fw = data.nose, data.ring, data.flywheel
    assumptions = [
        "TV excitation: crank torque of gas pressure plus reciprocating and con-rod inertia at"
        " constant speed (the same cylinder loads as the loads module), orders 0.5 to"
        f" {MAX_ORDER:g}, phased by the firing angles; the variable inertia of pistons and rods"
        " is the constant inertia lumped at the cylinder stations (Bell, Ricardo 2013).",
        "TV response: linear, steady state, frequency domain (Bell, Ricardo 2013: 'analysis in"
        " frequency"
        " domain'); amplitudes relative to a node rotating at the mean speed; totals are the"
        " half peak-to-peak of all orders synthesised over 720 deg.",
    ]

    # ---------------------------------------------------------------- natural frequencies
    w_n, modes = tv.natural_frequencies(model)
    flex = w_n > 1e-6 * max(w_n.max(), 1.0)
    zeta = tv.modal_damping_ratios(model, w_n, modes)
    w_flex, m_flex, z_flex = w_n[flex], modes[:, flex], zeta[flex]
    mode_labels = [f"mode {i + 1}" for i in range(w_flex.size)]

    # ---------------------------------------------------------------- forced response
    orders, cyl_coeffs, cyl_mean = _excitation(engine, cyc)
    O = orders.size
    force = tv.station_excitation(cyl_coeffs, data.cyl_station, n_st)  # (C, S, n, O)
    extra = cpl.station_damping(engine, speeds)  # a propeller's damping per speed
    resp = tv.forced_response(model, np.tile(speeds, C), orders, force.reshape(C * S, n_st, O),
                              station_damping=None if extra is None else np.tile(extra, (C, 1)))
    assumptions += cpl.driven_text(engine)
    couplings = cpl.coupling_elements(engine)
    if couplings:
        assumptions.append(cpl.state_text(cpl.coupling_state(engine)))
    theta = resp.theta.reshape(C, S, n_st, O)
    et = resp.element_torque.reshape(C, S, n_el, O)
    omega = resp.omega.reshape(C, S, O)
    reson = resp.resonance.reshape(C, S, O)

    twist_e = theta[:, :, :-1] - theta[:, :, 1:]  # (C, S, E, O) chain: front - rear
    rear = fw if fw is not None else n_st - 1
    # rule quantities: exact half range (Newton-polished extremes)
    nose_amp, crank_twist = tv.half_peak_to_peak(
        orders, np.stack([theta[:, :, nose], theta[:, :, nose] - theta[:, :, rear]]))  # (C, S)
    nose_ord = np.abs(theta[:, :, nose])  # (C, S, O)
    # element torques and twists (report, joints, fatigue): parabola-refined sampled extremes
    emax, emin = tp.synthesized_extremes(orders, np.concatenate([et, twist_e], axis=2),
                                         EXTREMES_SAMPLES_PER_PERIOD)  # (C, S, 2E)
    vmax, vmin = emax[..., :n_el], emin[..., :n_el]
    el_amp = 0.5 * (vmax - vmin)
    tw_amp = 0.5 * (emax[..., n_el:] - emin[..., n_el:])

    # mean torque per element: cylinder mean torques applied at their stations, FEAD taken off
    # at the crank nose, summed from the front
    fead = engine.params.get("fead_torque")
    if fead is None:
        assumptions.append("Accessory drive (FEAD) torque at the crank nose not given"
                           f" ({engine.cell('Engine', 'fead_torque')}): 0 N m used.")
    mean_el = tp.mean_element_torque(cyl_mean, data.cyl_station, n_st, nose,
                                     fead or 0.0)  # (C, S, E)

    # ---------------------------------------------------------------- findings (resonance)
    res_text: dict[tuple[int, int], list[str]] = {}  # (case, speed) -> texts
    find_ocs: dict[tuple[int, int, int], list[str]] = {}  # (order, case, speed) -> text
    for ci, si, oi in zip(*np.nonzero(reson)):
        ci, si, oi = int(ci), int(si), int(oi)
        om = omega[ci, si, oi]
        near = w_flex[np.argmin(np.abs(w_flex - om))] if w_flex.size else om
        text = (f"undamped resonance: order {orders[oi]:g} at {_rpm_text(speeds[si])}"
                f" ({cases[ci]} load) hits the natural frequency {near / (2 * np.pi):.1f} Hz;"
                " the model has no damping for this mode, the amplitude there comes from a"
                " regularised solve and is not physical - add damping (TVModel absolute or"
                " relative damping, Damper loss factor)")
        res_text.setdefault((ci, si), []).append(text)
        find_ocs[(oi, ci, si)] = [text]
    # near (not exactly on) a resonance of an undamped mode: amplification band or a crossing
    # between two swept speeds (checker.calc.torsional.undamped_resonance_band)
    band = tv.undamped_resonance_band(model, speeds, orders)
    groups: dict[tuple[int, str], list[int]] = {}  # (order, natural frequency) -> speeds
    for si, oi in zip(*np.nonzero(band.near)):
        key = (int(oi), f"{band.natural_frequency[si, oi]:.6g}")  # same mode, rounding aside
        groups.setdefault(key, []).append(int(si))
    for (oi, _), sis in groups.items():
        w_r = float(np.mean(band.natural_frequency[sis, oi]))
        crit = band.critical_speed[sis, oi]
        crossed = bool(np.isfinite(crit).any())
        w_c = float(np.nanmean(crit)) if crossed else w_r / orders[oi]
        where = (" between two swept speeds" if crossed else
                 " (outside the swept speeds)" if not speeds[0] <= w_c <= speeds[-1] else "")
        text = (f"undamped resonance near the sweep: order {orders[oi]:g} meets the natural"
                f" frequency {w_r / (2 * np.pi):.1f} Hz of a mode without damping at"
                f" {_rpm_text(w_c)}{where}; swept speeds next to it or within the band of"
                f" undamped amplification >= {tv.NEAR_RESONANCE_AMPLIFICATION:g} (about"
                f" +-5 %): {_speeds_text(speeds[sis])}. The response at that speed is unbounded"
                " while the swept amplitudes stay finite - add damping (TVModel absolute or"
                " relative damping, Damper loss factor)")
        for si in sis:
            for ci in range(C):
                if not reson[ci, si, oi]:  # exactly on it: the finding above
                    res_text.setdefault((ci, si), []).append(text)
                    find_ocs.setdefault((oi, ci, si), []).append(text)
    find_cs = dict(res_text)

    # ---------------------------------------------------------------- quantities
    cs_coords = {"case": cases, "speed": list(speeds)}
    order_labels = [f"order {n:g}" for n in orders]
    n_cyl = len(engine.cylinders)
    k_cyl = int(np.argmin(np.abs(orders - n_cyl)))
    higher = np.nonzero(orders > n_cyl + 1e-9)[0]
    # engine class (Engine sheet): selects the published TV targets (rules TV-001..003)
    cls = engine.params.get("engine_class")
    cls_cell = engine.cell("Engine", "engine_class")
    if cls_cell == "Engine":  # no such row in the workbook
        cls_cell = "sheet Engine, parameter 'Engine class'"
    cls_attrs = {"all": {"engine_class": cls or DEFAULT_ENGINE_CLASS,
                         "engine_class_cell": cls_cell}}
    cls_caveats: tuple[dict, ...] = ()
    if not cls:
        assumptions.append(
            f"Engine class not given ({cls_cell}):"
            f" {DEFAULT_ENGINE_CLASS} assumed, the class of the crank-nose TV targets of Bell"
            " 2013 (rules TV-001..003).")
        cls_caveats = ({
            "kind": "assumption", "severity": "medium", "rules": ["TV-001", "TV-002", "TV-003"],
            "text": f"Engine class not given ({cls_cell}): the"
                    " crank-nose TV targets of a refined passenger-car engine with a rubber"
                    " damper (Bell 2013) are applied; set the class, or enter the project's"
                    " limits (RuleOverrides), for any other engine."},)
    if (cls or DEFAULT_ENGINE_CLASS).lower() == DEFAULT_ENGINE_CLASS:
        cls_caveats += layout_caveats(engine)
    common = {"orders": orders, "speeds": speeds, "resonance": reson,
              "near_resonance": band.near, "assumptions": tuple(assumptions)}
    out: dict[str, Quantity] = {}
    out["tv.natural_frequency"] = Quantity(
        NATURAL, w_flex / (2 * np.pi), {"mode": mode_labels},
        detail=NaturalFrequencyDetail(
            modes=m_flex, stations=names, roles=roles, damping_ratio=z_flex, omega=w_flex,
            critical_speed=w_flex[:, None] / orders[None, :], orders=orders,
            rigid_body_mode=bool((~flex).any()), assumptions=tuple(assumptions)))
    # model and station excitation (C, S, n, O) for re-solves (damper tuning)
    out["tv.nose_amplitude"] = Quantity(
        NOSE, nose_amp, cs_coords, findings=find_cs,
        detail=NoseDetail(**common, theta=theta[:, :, nose], station=names[nose], model=model,
                          model_data=data, excitation=force))
    out["tv.nose_order_amplitude"] = Quantity(
        NOSE_ORDER, np.moveaxis(nose_ord, -1, 0), {"order": order_labels, **cs_coords},
        findings=find_ocs, detail=TorsionDetail(**common))
    cyl_find = {(ci, si): v for (oi, ci, si), v in find_ocs.items() if oi == k_cyl}
    env = cyc.envelope  # (C, S) operating envelope of each load case (None = every speed)
    peaks_text = ("judged at resonant peaks within each load case's operating envelope only"
                  " (full load: the full-load data range; no load: every speed up to the"
                  " overspeed): interior local maxima of the amplitude against speed, and the"
                  " envelope's top speed when the curve still rises into it; the rolling-mode"
                  " motion that falls from the lowest speed and points outside the envelope"
                  " are shown, not judged")
    out["tv.nose_cylinder_order_amplitude"] = Quantity(
        NOSE_CYL, nose_ord[:, :, k_cyl], cs_coords, dict(cls_attrs), findings=cyl_find,
        detail=CylinderOrderDetail(**dict(common, caveats=cls_caveats),
                                   order=float(orders[k_cyl])),
        applies_text=peaks_text,
        applies=resonant_peaks(nose_ord[:, :, k_cyl], axis=-1, envelope=env))
    pos = {int(o): i for i, o in enumerate(higher)}
    hi_find = {(pos[oi], ci, si): v for (oi, ci, si), v in find_ocs.items() if oi in pos}
    hi_vals = np.moveaxis(nose_ord[:, :, higher], -1, 0)
    out["tv.nose_higher_order_amplitude"] = Quantity(
        NOSE_HIGH, hi_vals,
        {"order": [order_labels[i] for i in higher], **cs_coords}, dict(cls_attrs),
        findings=hi_find, detail=OrdersCheckedDetail(**common, orders_checked=orders[higher]),
        applies_text=peaks_text, applies=resonant_peaks(hi_vals, axis=-1, envelope=env))
    low_q = _lower_orders(
        model, theta, nose, orders, speeds, omega, w_flex, n_cyl, order_labels, cs_coords, find_ocs,
        env, common)
    low_q.item_attrs = dict(cls_attrs)
    out["tv.nose_lower_order_elastic_amplitude"] = low_q
    out["tv.crank_twist"] = Quantity(TWIST, crank_twist, cs_coords, findings=find_cs,
                                     detail=TwistDetail(**common,
                                                        stations=(names[nose], names[rear])))

    el_names = [f"{names[e]} -> {names[e + 1]}" for e in range(n_el)]
    el_attrs = {el_names[e]: {"kind": "damper rubber" if e == ring else
                              cpl.COUPLING if e in couplings else "shaft",
                              "front": names[e], "rear": names[e + 1]} for e in range(n_el)}
    el_find = {(e, ci, si): v for (ci, si), v in res_text.items() for e in range(n_el)}
    out["tv.element_torque"] = Quantity(
        ELEMENT, np.moveaxis(el_amp, -1, 0), {"item": el_names, **cs_coords}, el_attrs,
        findings=el_find,
        detail=ElementTorqueDetail(
            **common,
            coeffs=np.moveaxis(et, 2, 0),  # (E, C, S, O) complex [N m]
            vib_max=np.moveaxis(vmax, -1, 0), vib_min=np.moveaxis(vmin, -1, 0),
            mean=np.moveaxis(mean_el, -1, 0),  # (E, C, S) [N m]
            twist=np.moveaxis(tw_amp, -1, 0),  # (E, C, S) [rad]
            twist_coeffs=np.moveaxis(twist_e, 2, 0),
            cylinder_mean_torque=cyl_mean,  # (C, S) one cylinder [N m]
            sign=("torque the front part exerts on the rear part through the element,"
                  " positive in the direction of rotation (front station leads)"),
            mean_definition=("sum from the front of the mean cylinder torques at the"
                             " cylinder stations minus the FEAD torque at the crank"
                             " nose; friction not subtracted")))

    out.update(_damper(engine, data, model, orders, theta, omega, cs_coords, find_cs, common))
    return {"quantities": out,
            "joint_inputs": dict(data=data, speeds=speeds, cases=cases, vmax=vmax, vmin=vmin,
                                 el_names=el_names, res_text=res_text, fead=fead or 0.0,
                                 assumptions=assumptions,
                                 envelope=getattr(cyc, "envelope", None))}


DEFAULT_ENGINE_CLASS = "passenger car"
"""Engine class when the Engine sheet gives none (stated as an assumption): the class of the
crank-nose TV targets of Bell 2013."""
TARGET_LAYOUTS = (("in-line", 4), ("V", 6))
"""The layouts the crank-nose TV targets of Bell 2013 are given for ('Crankshaft analysis
(15)': '4th order for I4 or 6th order for V6 <0.06 deg', 'higher orders <0.05 deg')."""
_COUNT_WORDS = {1: "single", 2: "two", 3: "three", 4: "four", 5: "five", 6: "six",
                8: "eight", 10: "ten", 12: "twelve"}


def engine_layout(engine: Engine) -> tuple[str, int]:
    """(``in-line`` | ``V`` | ``N-bank``, cylinder count) from the Cylinders sheet's bank
    angles (one bank angle: in-line; two: a V)."""
    banks = {round(float(c.bank_angle), 6) for c in engine.cylinders}
    kind = "in-line" if len(banks) <= 1 else "V" if len(banks) == 2 else f"{len(banks)}-bank"
    return kind, len(engine.cylinders)


def layout_text(kind: str, n: int) -> str:
    """An engine layout in words: "an in-line three", "a V8", "a 3-bank 12-cylinder"."""
    if kind == "in-line":
        return f"an in-line {_COUNT_WORDS.get(n, f'{n}-cylinder')}"
    if kind == "V":
        return f"a V{n}"
    return f"a {kind} {n}-cylinder engine"


def _ordinal(n: int) -> str:
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def layout_caveats(engine: Engine) -> tuple[dict, ...]:
    """The caveat that the passenger-car TV targets (TV-001..003) judge a layout they were not
    given for (:data:`TARGET_LAYOUTS`): an in-line three's 3rd order held to the target of
    an I4's 4th or a V6's 6th is an extrapolation. Empty for an I4 or a V6."""
    kind, n = engine_layout(engine)
    if (kind, n) in TARGET_LAYOUTS or n == 0:
        return ()
    return ({
        "kind": "limit outside its class", "severity": "medium",
        "rules": ["TV-001", "TV-002", "TV-003"],
        "text": f"The crank-nose TV targets of TV-001..003 are given for an in-line four and"
                " a V6 (Bell 2013, 'Crankshaft analysis (15)': 4th order of an I4 or 6th"
                f" order of a V6 < 0.06 deg, higher orders < 0.05 deg); this engine is"
                f" {layout_text(kind, n)}, so its cylinder-count order ({_ordinal(n)}) and the"
                " orders above and below it are judged by targets extrapolated to a layout"
                " they were not given for; enter the project's limits (RuleOverrides) where"
                " they are known."},)
ROUND_OFF_FLOOR = 1e-9
"""Amplitudes below this fraction of the largest are round-off (an order the firing order
cancels): never a resonant peak."""
MODE_BAND = 0.2
"""Relative distance of an order's frequency from an undamped natural frequency of the model
within which a peak of its elastic amplitude is a resonance with that mode (TV-003): the
damped peak of a rubber-damped crank lies between the two coupled modes of ring and crank,
within about +-20 % of one of them (Den Hartog's optimum split for inertia ratios up to 0.4:
f = 1/(1+mu) +- sqrt(mu/2), i.e. +-20 to 45 % between the fixed points; +-20 % of the nearer
mode)."""


def _lower_orders(model: tv.TorsionalModel, theta: np.ndarray, nose: int, orders: np.ndarray,
                  speeds: np.ndarray, omega: np.ndarray, w_flex: np.ndarray, n_cyl: int,
                  order_labels: list[str], cs_coords: dict, find_ocs: dict, env: np.ndarray | None,
                  common: dict) -> Quantity:
    """Elastic crank-nose amplitude of the orders below the cylinder count (rule TV-003).

    The motion of every station splits into the rigid-body mode, the inertia-weighted mean
    angle ``theta_rb = sum J_i theta_i / sum J_i`` (the modal coordinate of the rigid-body
    mode, mass-orthogonal to every flexible mode), and the elastic rest. At low speed the low
    orders move the whole engine as one body (the rolling motion of cyclic irregularity,
    FLY-001, which Bell 2013's targets leave out); where such an order meets a crank torsional
    mode inside the speed range the crank twists as at any other resonance. Judged: the
    resonant peaks (:func:`checker.evaluation.graph.resonant_peaks`, within each case's envelope)
    whose
    order frequency lies within :data:`MODE_BAND` of an undamped natural frequency whose
    critical speed for that order (natural frequency / order) lies inside the swept speeds.
    ``common``: the fields of :class:`~checker.results.torsion.TorsionDetail`.
    """
    low = np.nonzero(orders < n_cyl - 1e-9)[0]
    rigid = tp.rigid_body_angle(theta, model.inertia, axis=2)  # (C, S, O)
    elastic = np.abs(theta[:, :, nose, :] - rigid)[:, :, low]  # (C, S, o)
    vals = np.moveaxis(elastic, -1, 0)  # (o, C, S)
    om = np.moveaxis(omega[:, :, low], -1, 0)  # (o, C, S) order frequency [rad/s]
    if w_flex.size:
        # the nearest mode, and its critical speed for the order inside the sweep
        k = np.argmin(np.abs(om[..., None] - w_flex) / w_flex, axis=-1)
        w_k = w_flex[k]
        crit = w_k / orders[low][:, None, None]
        near = ((np.abs(om - w_k) <= MODE_BAND * w_k)
                & (crit >= speeds.min() * (1 - 1e-9)) & (crit <= speeds.max() * (1 + 1e-9)))
    else:
        near = np.zeros(vals.shape, dtype=bool)
    applies = resonant_peaks(vals, axis=-1, envelope=env) & near if vals.size else near
    if vals.size:  # orders cancelled by the layout (a V8's 6th): round-off wiggles, no peaks
        applies &= vals > ROUND_OFF_FLOOR * vals.max()
    pos = {int(o): i for i, o in enumerate(low)}
    finds = {(pos[oi], ci, si): v for (oi, ci, si), v in find_ocs.items() if oi in pos}
    text = ("judged at the resonant peaks of each order below the cylinder count whose"
            f" frequency lies within {MODE_BAND * 100:.0f} % of a natural frequency of the"
            " torsional model whose critical speed for the order lies inside the swept speeds"
            " (a resonance with a crank mode), within each load case's"
            " operating envelope; elsewhere the low orders are the rigid-body rolling motion"
            " (cyclic irregularity), not judged")
    return Quantity(NOSE_LOW, vals, {"order": [order_labels[i] for i in low], **cs_coords},
                    findings=finds,
                    detail=LowerOrdersDetail(
                        **common, orders_checked=orders[low],
                        rigid_body=np.moveaxis(np.abs(rigid[:, :, low]), -1, 0),
                        nose_total=np.moveaxis(np.abs(theta[:, :, nose, low]), -1, 0),
                        mode_band=MODE_BAND),
                    applies_text=text, applies=applies)


def _damper(engine: Engine, data: TVModelData, model: tv.TorsionalModel, orders: np.ndarray,
            theta: np.ndarray, omega: np.ndarray, cs_coords: dict, findings: dict,
            common: dict) -> dict[str, Quantity]:
    """Damper rubber twist, torque, power, shear stress and heat (and the limit ratios).

    ``common``: the fields of :class:`~checker.results.torsion.TorsionDetail`.
    """
    ring = data.ring
    shape = theta.shape[:2]
    nan = np.full(shape, np.nan)

    kind = dinp.damper_type(engine)

    def q(spec, values, missing=(), fields=None):
        miss = {(ci,): list(missing) for ci in range(shape[0])} if missing else {}
        return Quantity(spec, values, cs_coords, {"all": {"damper_type": kind}}, missing=miss,
                        findings=findings, detail=DamperDetail(**common, **(fields or {})))

    if ring is None:
        why = ["TVModel: no station with role 'damper ring' (engine without a TV damper)"]
        return {n: q(_SPECS[n], nan, why) for n in _DAMPER_QUANTITIES}
    hub = ring + 1
    ks = float(model.stiffness[ring])
    eta = float(model.loss_factor[ring])
    c_rel = float(model.damping_rel[ring])
    dphi = dmp.relative_twist(theta[:, :, hub], theta[:, :, ring])  # (C, S, O)
    if dinp.is_viscous(engine):
        return _viscous_damper(engine, model, ring, hub, orders, dphi, omega, q)
    torque = dmp.damper_torque(dphi, omega, ks, eta, c_rel)
    power_o = dmp.dissipated_power(dphi, omega, ks, eta, c_rel)
    power = power_o.sum(-1)
    twist_amp = dmp.synthesized_amplitude(orders, dphi)
    torque_amp = dmp.synthesized_amplitude(orders, torque)
    base = {"dphi": dphi, "torque_orders": torque, "power_orders": power_o,
            "stiffness": ks, "loss_factor": eta, "relative_damping": c_rel,
            "hub": engine.tv_model[hub].station, "ring": engine.tv_model[ring].station}
    out = {"damper.relative_twist": q(D_TWIST, twist_amp, fields=base),
           "damper.torque": q(D_TORQUE, torque_amp, fields=base),
           "damper.power": q(D_POWER, power, fields=base)}
    d = engine.damper

    def limit_attrs(lim_attr: str) -> dict:
        """The supplier's limit of the rules DMP-001..003 (SI, judged in physical units)."""
        lim = d.get(lim_attr)
        if lim is None:
            return {"all": {"limit_missing": [engine.describe_missing(
                "Damper", lim_attr, what="the damper supplier")], "damper_type": kind}}
        return {"all": {"limit": (float(lim),), "limit_cell": engine.cell("Damper", lim_attr),
                        "damper_type": kind}}

    geo_missing = [engine.describe_missing("Damper", a, what="the damper rubber")
                   for a in ("inner_radius", "outer_radius", "axial_length") if d.get(a) is None]
    if geo_missing:
        for n in ("damper.shear_stress", "damper.heat_density", "damper.heat_density_peak",
                  "damper.shear_stress_ratio", "damper.heat_ratio", "damper.heat_peak_ratio"):
            out[n] = q(_SPECS[n], nan, geo_missing)
        # the supplier's limits as without the geometry: a result names each missing input
        for n, lim_attr in (("damper.shear_stress", "shear_stress_limit"),
                            ("damper.heat_density", "heat_limit"),
                            ("damper.heat_density_peak", "heat_limit")):
            out[n].item_attrs = limit_attrs(lim_attr)
        return out
    ri, ro, ln = d["inner_radius"], d["outer_radius"], d["axial_length"]
    tau = dmp.annulus_shear_stress(torque_amp, ri, ln)
    q_mean, q_peak = dmp.annulus_heat_density(power, ri, ro, ln)
    geom = dict(base, volume=float(dmp.annulus_volume(ri, ro, ln)),
                shear_modulus=float(dmp.annulus_shear_modulus(ks, ri, ro, ln)),
                shear_orders=dmp.annulus_shear_stress(np.abs(torque), ri, ln))
    for name, spec, val, lim_attr in (
            ("damper.shear_stress", D_SHEAR, tau, "shear_stress_limit"),
            ("damper.heat_density", D_HEAT, q_mean, "heat_limit"),
            ("damper.heat_density_peak", D_HEAT_PEAK, q_peak, "heat_limit")):
        out[name] = q(spec, val, fields=geom)
        out[name].item_attrs = limit_attrs(lim_attr)
    for name, spec, val, lim_attr in (
            ("damper.shear_stress_ratio", D_SHEAR_RATIO, tau, "shear_stress_limit"),
            ("damper.heat_ratio", D_HEAT_RATIO, q_mean, "heat_limit"),
            ("damper.heat_peak_ratio", D_HEAT_PEAK_RATIO, q_peak, "heat_limit")):
        lim = d.get(lim_attr)
        if lim is None:
            out[name] = q(spec, nan, [engine.describe_missing(
                "Damper", lim_attr, what="the damper supplier (needed for the ratio)")])
        else:
            out[name] = q(spec, val / lim, fields=dict(
                geom, limit=lim, limit_cell=engine.cell("Damper", lim_attr)))
    return out


def _viscous_damper(engine: Engine, model: tv.TorsionalModel, ring: int, hub: int,
                    orders: np.ndarray, dphi: np.ndarray, omega: np.ndarray, q
                    ) -> dict[str, Quantity]:
    """Twist, torque and power of an untuned viscous damper's silicone coupling (nominal:
    the silicone at its reference temperature, or the typed coefficient); the rubber's
    stress and heat do not apply (rules DMP-001..003 select rubber dampers only)."""
    z = tv.element_impedance(model, omega)[..., ring]  # (C, S, O)
    torque = z * dphi
    power_o = vd.impedance_power(dphi, omega, z)
    base = {"dphi": dphi, "torque_orders": torque, "power_orders": power_o,
            "stiffness": 0.0, "loss_factor": 0.0,
            "relative_damping": float(model.damping_rel[ring]),
            "hub": engine.tv_model[hub].station, "ring": engine.tv_model[ring].station}
    out = {"damper.relative_twist": q(D_TWIST, dmp.synthesized_amplitude(orders, dphi),
                                      fields=base),
           "damper.torque": q(D_TORQUE, dmp.synthesized_amplitude(orders, torque), fields=base),
           "damper.power": q(D_POWER, power_o.sum(-1), fields=base)}
    nan = np.full(dphi.shape[:2], np.nan)
    why = ["Damper: a viscous damper has no rubber (Damper type 'viscous'); its silicone's"
           " heat and temperature are judged by DMP-008..010"]
    for n in _DAMPER_QUANTITIES[3:]:
        out[n] = q(_SPECS[n], nan, why)
    return out


def _joints(engine: Engine, data: TVModelData, speeds: np.ndarray, cases: list[str],
            vmax: np.ndarray, vmin: np.ndarray, el_names: list[str], res_text: dict, fead: float,
            assumptions: list[str], envelope: np.ndarray | None = None) -> Quantity:
    """Peak TV torque through each bolted joint at 'tv peak', 'max power' and 'overspeed'.

    * crank nose: the element ending at the crank-nose station (the damper rubber in the usual
      layout) plus the accessory drive torque: ``max_t |T_FEAD - T_e(t)|``;
    * flywheel: the element ending at the flywheel station plus the brake torque (full load,
      BrakeTorque sheet; 0 at no load): ``max_t |T_brake + T_e(t)|``.
    Points: 'tv peak' = speed of the largest such torque over the full-load sweep; 'max power'
    = speed of the maximum brake power of the BrakeTorque sheet, full load; 'overspeed' =
    Engine 'Overspeed', no load. Each uses the nearest swept speed (recorded in the detail).
    """
    joints = engine.joints
    nj, npt = len(joints), len(POINTS)
    vals = np.full((nj, npt), np.nan)
    speed_used = np.full((nj, npt), np.nan)
    case_used = np.full((nj, npt), "", dtype=object)
    how = np.full((nj, npt), "", dtype=object)
    missing: dict[tuple, list[str]] = {}
    findings: dict[tuple, list[str]] = {}
    ci_full, ci_no = cases.index("full"), cases.index("no")
    bt = np.array(engine.brake_torque, dtype=float).reshape(-1, 2)
    p = engine.params
    # operating-point speeds
    mp_speed = None
    if bt.size:
        mp_speed = float(bt[np.argmax(bt[:, 0] * bt[:, 1]), 0])
    ov_speed = p.get("overspeed")
    brake_missing = "BrakeTorque: full-load brake torque vs speed (sheet BrakeTorque)"
    given = {(t.joint, t.point) for t in engine.joint_torques}
    notes = []
    for i, j in enumerate(joints):
        if j.location == "crank nose":
            e = data.nose - 1
            if e < 0:
                for k in range(npt):
                    missing[(i, k)] = ["TVModel: no station in front of the crank nose (damper"
                                       " ring); the crank-nose joint torque needs its element"]
                continue
            sign, mean = -1.0, np.full((len(cases), speeds.size), fead)
            src = f"{el_names[e]} (damper rubber) + FEAD {fead:g} N m"
        elif j.location == "flywheel":
            fw = data.flywheel
            if fw is None or fw == 0:
                for k in range(npt):
                    missing[(i, k)] = ["TVModel: no station with role 'flywheel' (the flywheel"
                                       " joint torque is the torque of the element ending"
                                       " there)"]
                continue
            e = fw - 1
            sign = 1.0
            mean = np.zeros((len(cases), speeds.size))
            if bt.size:
                mean[ci_full] = np.interp(speeds, bt[:, 0], bt[:, 1])
            src = f"{el_names[e]} + brake torque"
        else:
            for k in range(npt):
                missing[(i, k)] = [f"TVModel: no torque cut is defined for a joint at location"
                                   f" '{j.location}' (give its torque in JointTorques)"]
            continue
        hi, lo = sign * vmax[:, :, e], sign * vmin[:, :, e]
        if sign < 0:
            hi, lo = lo, hi
        peak = tp.peak_cut_torque(mean, hi, lo)  # (C, S)
        points: list[tuple[int, int | None, str]] = []
        if j.location == "flywheel" and not bt.size:
            points.append((0, None, brake_missing))
        else:
            inside = np.ones(speeds.size, bool) if envelope is None else envelope[ci_full]
            points.append((ci_full, int(np.argmax(np.where(inside, peak[ci_full], -np.inf))),
                           ""))
        if mp_speed is None:
            points.append((ci_full, None, brake_missing + " (maximum power speed)"))
        else:
            points.append((ci_full, int(np.argmin(np.abs(speeds - mp_speed))), ""))
        if ov_speed is None:
            points.append((ci_no, None, engine.describe_missing("Engine", "overspeed")))
        else:
            points.append((ci_no, int(np.argmin(np.abs(speeds - ov_speed))), ""))
        for k, (ci, si, why) in enumerate(points):
            if si is None:
                missing[(i, k)] = [why]
                continue
            vals[i, k] = peak[ci, si]
            speed_used[i, k] = speeds[si]
            case_used[i, k] = cases[ci]
            how[i, k] = (f"{src}: {cases[ci]} load at {_rpm_text(speeds[si])}, mean"
                         f" {mean[ci, si]:.0f} N m, vibratory {lo[ci, si]:+.0f}..{hi[ci, si]:+.0f}"
                         f" N m, peak |T| {peak[ci, si]:.0f} N m")
            if (ci, si) in res_text:
                findings[(i, k)] = res_text[(ci, si)]
            if (j.name, POINTS[k]) in given:
                continue
            notes.append(f"{j.name} at '{POINTS[k]}': {vals[i, k]:.0f} N m ({how[i, k]})")
            if j.location == "flywheel" and ci == ci_full and (
                    speeds[si] < bt[0, 0] - 1e-9 or speeds[si] > bt[-1, 0] + 1e-9):
                notes[-1] = (notes[-1][:-1] + "; brake torque held at the end of the"
                             " BrakeTorque table)")
    assumptions = list(assumptions)
    if notes:
        assumptions.append("Joint torques not given in JointTorques are taken from the TV"
                           " module (peak |mean + vibratory| over the cycle): "
                           + "; ".join(notes))
    attrs = {j.name: {"location": j.location} for j in joints}
    return Quantity(JOINT, vals, {"item": [j.name for j in joints], "point": list(POINTS)},
                    attrs, missing, findings,
                    detail=JointTorqueDetail(speed=speed_used, case=case_used, how=how,
                                             max_power_speed=mp_speed, overspeed=ov_speed,
                                             assumptions=tuple(assumptions)))


_SPECS = {s.name: s for s in (D_TWIST, D_TORQUE, D_POWER, D_SHEAR, D_HEAT, D_HEAT_PEAK,
                              D_SHEAR_RATIO, D_HEAT_RATIO, D_HEAT_PEAK_RATIO)}
