"""Graph calculation for the TV damper's tuning: the ring's natural frequency relative to the
crank's first mode and its damping, compared with Den Hartog's optimum for its inertia ratio,
and the crank-nose amplitude the same torsional model would have with the optimum rubber
(:mod:`checker.calc.damper_tuning`).

Which node computes what: this module ("damper", node ``damper_tuning``) gives
``damper.tuning_ratio`` (rule DMP-004), the optimum (``damper.optimum_*``,
``damper.crank_mode_frequency``, ``damper.modal_inertia``, ``damper.mass_ratio``,
``damper.ring_frequency``, ``damper.damping_ratio``) and the peaks ``damper.peak_*``. The
rubber's response (``damper.relative_twist``, ``damper.torque``, ``damper.power``,
``damper.shear_stress``, ``damper.heat_density*`` and the ratios, rules DMP-001..003) comes from
the torsional solve, module ``torsion`` (:mod:`checker.modules.torsion`). Detail type:
:class:`checker.results.damper.DamperTuningDetail`.

It reuses the torsional module's solution (model, station excitation and crank-nose amplitude
of ``tv.nose_amplitude``) and re-solves the forced response once with the rubber element at
the optimum stiffness and loss factor; every other input is unchanged. The tuning ratio is
judged against the project's band (sheet ``Damper``, rule DMP-004, a warning).
"""

from __future__ import annotations

import numpy as np

from ..calc import damper_tuning as dt
from ..calc import torsional as tv
from ..description.engine import Engine
from ..evaluation.graph import (
    MissingInputs,
    Quantity,
    QuantitySpec,
    calculation,
    quantity,
    resonant_peaks,
)
from ..results.damper import DamperTuningDetail
from . import damper_inputs as dinp

CASES = ("full", "no")

TUNING = quantity(QuantitySpec(
    "damper.tuning_ratio", "", ("item",),
    "Damper tuning ratio: ring natural frequency sqrt(k/J_ring) / crank first-mode frequency"
    " without the ring", "", detail=DamperTuningDetail))
OPT_NOSE = quantity(QuantitySpec(
    "damper.optimum_nose_amplitude", "rad", ("case", "speed"),
    "Crank-nose TV amplitude (all orders, half peak-to-peak) with the damper rubber at Den"
    " Hartog's optimum tuning and damping (same model otherwise)", "deg",
    coords={"case": CASES}, detail=DamperTuningDetail))


def _item_spec(name: str, unit: str, description: str, display: str) -> QuantitySpec:
    return quantity(QuantitySpec(name, unit, ("item",), description, display,
                                 detail=DamperTuningDetail))


# Den Hartog's optimum and the primary system, per damper ring (item): every number the
# report's damper section prints, so that the JSON and the results workbook carry them too.
TUNING_VALUES = (
    _item_spec("damper.crank_mode_frequency", "Hz",
               "First flexible mode of the crank train without the damper ring (primary"
               " system of the absorber)", "Hz"),
    _item_spec("damper.modal_inertia", "kg*m**2",
               "Modal inertia of that mode at the damper hub, J_eq = sum J_i (phi_i/phi_hub)^2"
               " (Drapal & Novotny 2017, eq. 3)", "kg*m**2"),
    _item_spec("damper.mass_ratio", "",
               "Inertia ratio mu = J_ring / J_eq of the damper", ""),
    _item_spec("damper.ring_frequency", "Hz",
               "Damper ring natural frequency sqrt(k/J_ring)", "Hz"),
    _item_spec("damper.optimum_tuning_ratio", "",
               "Den Hartog's optimum tuning ratio f_opt = 1/(1 + mu)", ""),
    _item_spec("damper.optimum_ring_frequency", "Hz",
               "Ring natural frequency at Den Hartog's optimum tuning, f_opt times the crank"
               " mode", "Hz"),
    _item_spec("damper.damping_ratio", "",
               "Damper damping ratio (equivalent viscous, zeta = eta f/2 + c/(2 J_ring w_n))",
               ""),
    _item_spec("damper.optimum_damping_ratio", "",
               "Den Hartog's optimum damping ratio zeta_opt = sqrt(3 mu / (8 (1 + mu)^3))", ""),
    _item_spec("damper.optimum_loss_factor", "",
               "Rubber loss factor at Den Hartog's optimum, eta_opt = 2 zeta_opt / f_opt", ""),
    _item_spec("damper.optimum_stiffness", "N*m/rad",
               "Rubber storage stiffness at Den Hartog's optimum, k_opt = J_ring (f_opt w_n)^2",
               "N*m/rad"),
)
PEAK_DESIGNS = ("actual", "optimum")
PEAK_GROUPS = ("cylinder order", "higher orders")
PEAK_AMP = quantity(QuantitySpec(
    "damper.peak_nose_amplitude", "rad", ("design", "orders"),
    "Largest crank-nose order amplitude at the resonant peaks (as TV-001/TV-002 judge them)"
    " with the actual damper and with the optimum rubber (same model)", "deg",
    coords={"design": PEAK_DESIGNS, "orders": PEAK_GROUPS}, detail=DamperTuningDetail))
PEAK_SPEED = quantity(QuantitySpec(
    "damper.peak_speed", "rad/s", ("design", "orders"),
    "Engine speed of that largest peak", "rpm",
    coords={"design": PEAK_DESIGNS, "orders": PEAK_GROUPS}, detail=DamperTuningDetail))
PEAK_ORDER = quantity(QuantitySpec(
    "damper.peak_order", "", ("design", "orders"), "Order of that largest peak", "",
    coords={"design": PEAK_DESIGNS, "orders": PEAK_GROUPS}, detail=DamperTuningDetail))

PROVIDES = ("damper.tuning_ratio", "damper.optimum_nose_amplitude",
            *(s.name for s in TUNING_VALUES), PEAK_AMP.name, PEAK_SPEED.name, PEAK_ORDER.name)


def peak_summary(orders: np.ndarray, theta: np.ndarray, n_cyl: int, speeds: np.ndarray,
                 cases: list[str]) -> dict:
    """Largest crank-nose order amplitude at the resonant peaks (as rules TV-001/TV-002 judge
    them): the cylinder-count order and the worst order above it.

    ``theta``: complex nose amplitudes (C, S, O). Returns values [rad] with their order, case
    and speed (None where no order has a peak).
    """
    amp = np.abs(theta)
    out = {}
    k = int(np.argmin(np.abs(orders - n_cyl)))
    groups = {"cylinder order": np.array([k]), "higher orders": np.nonzero(orders > n_cyl
                                                                            + 1e-9)[0]}
    for name, idx in groups.items():
        if idx.size == 0:
            out[name] = None
            continue
        a = np.moveaxis(amp[..., idx], -1, 0)  # (o, C, S)
        v = np.where(resonant_peaks(a, axis=-1), a, -np.inf)
        if not np.isfinite(v).any():
            out[name] = None
            continue
        o, c, s_ = np.unravel_index(int(np.argmax(v)), v.shape)
        out[name] = {"value": float(a[o, c, s_]), "order": float(orders[idx[o]]),
                     "case": cases[c], "speed": float(speeds[s_])}
    return out


@calculation("damper_tuning", "damper", provides=PROVIDES, needs=("tv.nose_amplitude",),
             reads=("damper", "tv_model", "cylinders", "params"),
             applies=lambda engine: not dinp.is_viscous(engine),
             applies_why=dinp.why_not_rubber)
def damper_tuning(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Actual vs optimum damper tuning and the crank-nose amplitude at the optimum."""
    nose_q = inputs["tv.nose_amplitude"]
    ex = nose_q.detail
    model: tv.TorsionalModel = ex.model
    data = ex.model_data
    ring, nose = data.ring, data.nose
    if ring is None:
        raise MissingInputs(["TVModel: no station with role 'damper ring' (engine without a TV"
                             " damper: nothing to tune)"])
    try:
        pm = dt.primary_mode(model, ring)
    except ValueError as exc:
        raise MissingInputs([f"TVModel: {exc}"]) from None
    if ring + 1 != nose:
        raise MissingInputs(["TVModel: the damper ring must hang on the crank nose (the"
                             " 'crank nose' station must follow the 'damper ring' station)"])
    eta = float(model.loss_factor[ring])
    c = float(model.damping_rel[ring])
    t = dt.absorber_tuning(float(model.inertia[ring]), float(model.stiffness[ring]), eta, c,
                           pm.omega, pm.equivalent_inertia)
    opt = dt.optimum_model(model, ring, t)
    force = ex.excitation  # (C, S, n, O)
    orders = np.asarray(ex.orders, dtype=float)
    speeds = np.asarray(ex.speeds, dtype=float)
    C, S, n_st, O = force.shape
    resp = tv.forced_response(opt, np.tile(speeds, C), orders, force.reshape(C * S, n_st, O))
    theta_nose = resp.theta[:, nose, :].reshape(C, S, O)
    amp_opt = tv.half_peak_to_peak(orders, theta_nose)
    reson = resp.resonance.reshape(C, S, O)
    findings = {}
    for ci, si in zip(*np.nonzero(reson.any(-1))):
        findings[(int(ci), int(si))] = [
            f"undamped resonance in the optimum-damper model at {speeds[si] * 30 / np.pi:.0f}"
            " rpm; the amplitude there is not physical"]
    d = engine.damper
    lo, hi = d.get("tuning_ratio_min"), d.get("tuning_ratio_max")
    miss = [engine.describe_missing("Damper", n, what="the project (needed to judge the"
                                    " tuning ratio)")
            for n, v in (("tuning_ratio_min", lo), ("tuning_ratio_max", hi)) if v is None]
    if miss:
        lim = {"limit_missing": miss}
    elif lo > hi:
        lim = {"limit_missing": [
            f"{engine.cell('Damper', 'tuning_ratio_min')} /"
            f" {engine.cell('Damper', 'tuning_ratio_max')}: the minimum ({lo:g}) is above the"
            f" maximum ({hi:g})"]}
    else:
        lim = {"limit": (float(lo), float(hi)),
               "limit_cell": f"{engine.cell('Damper', 'tuning_ratio_min')},"
                             f" {engine.cell('Damper', 'tuning_ratio_max')}"}
    item = engine.tv_model[ring].station
    k_cyl = int(np.argmin(np.abs(orders - len(engine.cylinders))))
    assumptions = [
        "Damper tuning: the crank's first flexible mode without the damper ring is the primary"
        " system (modal inertia at the crank nose, Drapal & Novotny 2017); Den Hartog's"
        " optimum (Mechanical Vibrations, 1956) for the inertia ratio; a hysteretic rubber is"
        " compared through its viscous equivalent at the ring frequency; the nose amplitude at"
        " the optimum re-solves the same model with the optimum rubber stiffness and loss"
        " factor (no viscous rubber damping)."]
    peaks = {"actual": peak_summary(orders, ex.theta, len(engine.cylinders), speeds,
                                    list(nose_q.coords["case"])),
             "optimum": peak_summary(orders, theta_nose, len(engine.cylinders), speeds,
                                     list(nose_q.coords["case"]))}
    detail = DamperTuningDetail(
        tuning=t, primary_omega=pm.omega, primary_inertia=pm.equivalent_inertia,
        primary_mode=pm.mode, ring_inertia=float(model.inertia[ring]),
        stiffness=float(model.stiffness[ring]), loss_factor=eta, relative_damping=c,
        ring=engine.tv_model[ring].station, hub=engine.tv_model[nose].station, orders=orders,
        speeds=speeds, actual_nose_amplitude=nose_q.values, optimum_theta=theta_nose,
        actual_theta=ex.theta, cylinder_order=float(orders[k_cyl]), cylinder_order_index=k_cyl,
        peaks=peaks, assumptions=tuple(assumptions))
    two_pi = 2.0 * np.pi
    values = {"damper.crank_mode_frequency": pm.omega / two_pi,
              "damper.modal_inertia": pm.equivalent_inertia,
              "damper.mass_ratio": t.mass_ratio,
              "damper.ring_frequency": t.ring_frequency / two_pi,
              "damper.optimum_tuning_ratio": t.tuning_optimum,
              "damper.optimum_ring_frequency": t.tuning_optimum * pm.omega / two_pi,
              "damper.damping_ratio": t.damping_ratio,
              "damper.optimum_damping_ratio": t.damping_optimum,
              "damper.optimum_loss_factor": t.loss_factor_optimum,
              "damper.optimum_stiffness": t.stiffness_optimum}
    out = {spec.name: Quantity(spec, np.array([values[spec.name]]), {"item": [item]},
                               detail=detail) for spec in TUNING_VALUES}
    pk = {k: np.full((len(PEAK_DESIGNS), len(PEAK_GROUPS)), np.nan)
          for k in ("value", "speed", "order")}
    pk_missing: dict[tuple, list[str]] = {}
    for a, design in enumerate(PEAK_DESIGNS):
        for b, group in enumerate(PEAK_GROUPS):
            p = peaks[design].get(group)
            if p is None:
                pk_missing[(a, b)] = [f"no resonant peak of the {group} in the speed range"]
                continue
            for k in pk:
                pk[k][a, b] = p[k]
    pc = {"design": list(PEAK_DESIGNS), "orders": list(PEAK_GROUPS)}
    for spec, k in ((PEAK_AMP, "value"), (PEAK_SPEED, "speed"), (PEAK_ORDER, "order")):
        out[spec.name] = Quantity(spec, pk[k], pc, missing=dict(pk_missing), detail=detail)
    return {
        **out,
        "damper.tuning_ratio": Quantity(TUNING, np.array([t.tuning]), {"item": [item]},
                                        {item: lim}, detail=detail),
        "damper.optimum_nose_amplitude": Quantity(OPT_NOSE, amp_opt, dict(nose_q.coords),
                                                  findings=findings, detail=detail),
    }
