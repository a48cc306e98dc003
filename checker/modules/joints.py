"""Graph calculations for the bolted joints (crank nose, flywheel, any number of joints)."""

from __future__ import annotations

import numpy as np

from ..calc import bolted_joint as bj
from ..description.engine import Engine, Joint
from ..evaluation.graph import (
    UNAVAILABLE,
    MissingInputs,
    Quantity,
    QuantitySpec,
    calculation,
    quantity,
)
from ..results.display import case_text
from ..results.joints import AppliedTorqueDetail, ComputedTorqueDetail, JointBoltsDetail

POINTS = ("tv peak", "max power", "overspeed")
_FILTERS = ("location", "tightening", "clamped_material", "property_class")

STRESS_AREA = quantity(QuantitySpec(
    "joint.stress_area", "m**2", ("item",), "Bolt tensile stress area A_s", "mm**2", _FILTERS,
    detail=JointBoltsDetail))
PRELOAD = quantity(QuantitySpec(
    "joint.preload", "N", ("item",), "Preload of one bolt", "kN", _FILTERS,
    detail=JointBoltsDetail))
CLAMP = quantity(QuantitySpec(
    "joint.clamp_force", "N", ("item",), "Clamp force of all bolts of the joint", "kN",
    _FILTERS, detail=JointBoltsDetail))
PROOF = quantity(QuantitySpec(
    "joint.proof_stress_ratio", "", ("item",), "Bolt stress as a percentage of proof stress",
    "%", _FILTERS, detail=JointBoltsDetail))
HEAD = quantity(QuantitySpec(
    "joint.head_contact_stress", "Pa", ("item",), "Contact stress under the bolt head", "MPa",
    _FILTERS, detail=JointBoltsDetail))
DEFF = quantity(QuantitySpec(
    "joint.effective_diameter", "m", ("item",), "Effective friction diameter of the face", "mm",
    _FILTERS, detail=JointBoltsDetail))
CAPACITY = quantity(QuantitySpec(
    "joint.slip_capacity", "N*m", ("item",), "Slip torque capacity of the clamped face", "N*m",
    _FILTERS, detail=JointBoltsDetail))
APPLIED = quantity(QuantitySpec(
    "joint.applied_torque", "N*m", ("item", "point"), "Peak applied torque at the joint", "N*m",
    _FILTERS, coords={"point": POINTS}, detail=AppliedTorqueDetail))
COVER = quantity(QuantitySpec(
    "joint.cover_factor", "", ("item", "point"),
    "Joint cover factor (slip capacity / peak applied torque)", "", _FILTERS,
    coords={"point": POINTS}, detail=AppliedTorqueDetail))
COMPUTED = quantity(QuantitySpec(
    "joint.computed_torque", "N*m", ("item", "point"),
    "Peak torque through the joint from the torsional model at the same operating point"
    " (for comparison with a torque given in JointTorques)", "N*m", _FILTERS,
    coords={"point": POINTS}, detail=ComputedTorqueDetail))
COMPUTED_COVER = quantity(QuantitySpec(
    "joint.computed_cover_factor", "", ("item", "point"),
    "Joint cover factor at the torsional model's torque (slip capacity / computed torque)", "",
    _FILTERS, coords={"point": POINTS}, detail=ComputedTorqueDetail))
TORQUE_RATIO = quantity(QuantitySpec(
    "joint.computed_torque_ratio", "", ("item", "point"),
    "Torsional model's joint torque / the design torque the cover-factor rules use (judged"
    " where the design torque is given in JointTorques)", "", _FILTERS,
    coords={"point": POINTS}, detail=ComputedTorqueDetail))

GIVEN_SOURCE = "workbook (JointTorques)"
COMPUTED_SOURCE = "torsional vibration module"


def _attrs(j: Joint) -> dict:
    return {"location": j.location, "tightening": j.tightening,
            "clamped_material": (j.clamped_material or "").lower() or None,
            "property_class": j.property_class}


def _preload(engine: Engine, j: Joint, area: float) -> tuple[float | None, list[str], str]:
    """Preload of one bolt, the missing inputs, and a text saying how it was obtained."""
    rp02_iso, sp_iso = bj.PROPERTY_CLASSES[j.property_class]
    if j.tightening == "torque":
        if j.tightening_torque is None:
            return None, [engine.describe_missing("Joints", "tightening_torque", j.row, j.name)], ""
        k = j.nut_factor if j.nut_factor is not None else bj.DEFAULT_NUT_FACTOR
        f = float(bj.preload_from_torque(j.tightening_torque, j.diameter, k))
        how = (f"F = T/(K d) with T = {j.tightening_torque:g} N m, K = {k:g}"
               + (" (default, Bell, Ricardo 2013)" if j.nut_factor is None else ""))
        return f, [], how
    frac_default, ref = bj.PRELOAD_FRACTIONS[j.tightening]
    frac = j.preload_fraction if j.preload_fraction is not None else frac_default
    if ref == "rp02":
        stress = j.rp02 if j.rp02 is not None else rp02_iso
        name = "R_p0.2"
    else:
        stress = j.proof_load_stress if j.proof_load_stress is not None else sp_iso
        name = "S_p"
    f = float(bj.preload_from_stress(frac, stress, area))
    how = f"F = {frac:g} x {name} x A_s ({j.tightening}) with {name} = {stress / 1e6:g} MPa"
    return f, [], how


@calculation("joint_bolts", "joints",
             provides=("joint.stress_area", "joint.preload", "joint.clamp_force",
                       "joint.proof_stress_ratio", "joint.head_contact_stress",
                       "joint.effective_diameter", "joint.slip_capacity"),
             reads=("joints",))
def joint_bolts(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Stress area, preload, proof-stress percentage, head contact stress and slip capacity."""
    joints = engine.joints
    if not joints:
        raise MissingInputs(["Joints: no bolted joints are given (sheet Joints)"])
    names = [j.name for j in joints]
    attrs = {j.name: _attrs(j) for j in joints}
    n = len(joints)
    area = np.full(n, np.nan)
    pre = np.full(n, np.nan)
    clamp = np.full(n, np.nan)
    proof = np.full(n, np.nan)
    head = np.full(n, np.nan)
    deff = np.full(n, np.nan)
    cap = np.full(n, np.nan)
    miss_pre: dict[tuple, list[str]] = {}
    miss_head: dict[tuple, list[str]] = {}
    how: dict[str, dict[str, str]] = {}
    for i, j in enumerate(joints):
        coef = (j.stress_area_coefficient if j.stress_area_coefficient is not None
                else bj.ISO_STRESS_AREA_COEFFICIENT)
        area[i] = bj.tensile_stress_area(j.diameter, j.pitch, coef)
        f, missing, text = _preload(engine, j, area[i])
        rp02 = j.rp02 if j.rp02 is not None else bj.PROPERTY_CLASSES[j.property_class][0]
        mu = j.friction if j.friction is not None else bj.DEFAULT_FRICTION
        deff[i] = bj.effective_friction_diameter(j.face_outer, j.face_inner)
        how[j.name] = {
            "stress area": f"A_s = pi/4 (d - {coef:g} p)^2"
                           + (" (ISO 898-1)" if j.stress_area_coefficient is None else ""),
            "preload": text,
            "proof stress": f"P = R_p0.2 = {rp02 / 1e6:g} MPa"
                            + (" (ISO 898-1 minimum for class " + j.property_class + ")"
                               if j.rp02 is None else ""),
            "friction": f"mu = {mu:g}" + (" (default, Bell, Ricardo 2013)"
                                          if j.friction is None else ""),
        }
        if f is None:
            miss_pre[(i,)] = missing
            miss_head[(i,)] = missing
            continue
        pre[i] = f
        clamp[i] = f * j.bolts
        proof[i] = bj.proof_stress_ratio(f, rp02, area[i])
        cap[i] = bj.slip_torque_capacity(mu, clamp[i], j.face_outer, j.face_inner)
        if j.head_outer is None or j.head_inner is None:
            miss_head[(i,)] = [engine.describe_missing("Joints", a, j.row, j.name)
                               for a in ("head_outer", "head_inner")
                               if getattr(j, a) is None]
        else:
            head[i] = bj.head_contact_stress(f, j.head_outer, j.head_inner)
    coords = {"item": names}
    detail = JointBoltsDetail(how=how)

    def q(spec, values, missing=None):
        return Quantity(spec, values, coords, attrs, dict(missing or {}), detail=detail)

    return {
        "joint.stress_area": q(STRESS_AREA, area),
        "joint.preload": q(PRELOAD, pre, miss_pre),
        "joint.clamp_force": q(CLAMP, clamp, miss_pre),
        "joint.proof_stress_ratio": q(PROOF, proof, miss_pre),
        "joint.head_contact_stress": q(HEAD, head, miss_head),
        "joint.effective_diameter": q(DEFF, deff),
        "joint.slip_capacity": q(CAPACITY, cap, miss_pre),
    }


def _applied_needs(engine: Engine) -> tuple[str, ...]:
    """Upstream quantities the applied torque needs: none when the workbook gives them all."""
    from ..evaluation.graph import PROVIDER

    given = {(t.joint, t.point) for t in engine.joint_torques}
    complete = all((j.name, p) in given for j in engine.joints for p in POINTS)
    if complete or "tv.joint_torque" not in PROVIDER:
        return ()
    return ("tv.joint_torque",)


@calculation("joint_applied_torque", "joints", provides=("joint.applied_torque",),
             needs=_applied_needs, optional=("tv.joint_torque",),
             reads=("joints", "joint_torques"))
def joint_applied_torque(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Peak applied torque per joint and operating point: the workbook's value where given,
    otherwise from the torsional-vibration module (when it runs)."""
    joints = engine.joints
    if not joints:
        raise MissingInputs(["Joints: no bolted joints are given (sheet Joints)"])
    names = [j.name for j in joints]
    vals = np.full((len(joints), len(POINTS)), np.nan)
    source = np.full((len(joints), len(POINTS)), "", dtype=object)
    speed = np.full((len(joints), len(POINTS)), np.nan)
    missing: dict[tuple, list[str]] = {}
    given = {(t.joint, t.point): t for t in engine.joint_torques}
    tv = inputs.get("tv.joint_torque")
    tv_gone = inputs.get(UNAVAILABLE, {}).get("tv.joint_torque")
    for i, j in enumerate(joints):
        for k, p in enumerate(POINTS):
            t = given.get((j.name, p))
            if t is not None:
                vals[i, k] = t.torque
                speed[i, k] = np.nan if t.speed is None else t.speed
                source[i, k] = GIVEN_SOURCE
            elif tv is not None and np.isfinite(tv.values[i, k]):
                vals[i, k] = tv.values[i, k]
                speed[i, k] = tv.detail.speed[i, k]
                source[i, k] = COMPUTED_SOURCE
            else:
                reason = (f"JointTorques: peak applied torque of joint '{j.name}' at '{p}'"
                          " (not given in the workbook")
                if tv is not None:
                    reason += " and not computed: " + "; ".join(tv.missing.get((i, k), [])) + ")"
                elif tv_gone:
                    reason += "; the torsional module could not run: " + "; ".join(tv_gone) + ")"
                else:
                    reason += "; the torsional module did not run)"
                missing[(i, k)] = [reason]
    coords = {"item": names, "point": list(POINTS)}
    attrs = {j.name: _attrs(j) for j in joints}
    return {"joint.applied_torque": Quantity(
        APPLIED, vals, coords, attrs, missing,
        detail=AppliedTorqueDetail(source=source, speed=speed))}


@calculation("joint_cover_factor", "joints", provides=("joint.cover_factor",),
             needs=("joint.slip_capacity", "joint.applied_torque"), reads=())
def joint_cover_factor(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Cover factor = slip torque capacity / peak applied torque, per operating point."""
    cap = inputs["joint.slip_capacity"]
    tq = inputs["joint.applied_torque"]
    vals = np.full(tq.values.shape, np.nan)
    ok = np.isfinite(tq.values) & np.isfinite(cap.values)[:, None]
    capb = np.broadcast_to(cap.values[:, None], tq.values.shape)
    vals[ok] = bj.cover_factor(capb[ok], tq.values[ok])
    missing = dict(tq.missing)
    for (i,), reasons in cap.missing.items():
        for k in range(len(POINTS)):
            missing[(i, k)] = list(dict.fromkeys(missing.get((i, k), []) + reasons))
    return {"joint.cover_factor": Quantity(COVER, vals, tq.coords, tq.item_attrs, missing,
                                           detail=tq.detail)}


RATIO_APPLIES = ("only torques given in JointTorques are compared with the torsional model;"
                 " where none is given the cover-factor rules use the computed torque itself")


def _computed_needs(engine: Engine) -> tuple[str, ...]:
    from ..evaluation.graph import PROVIDER

    tv = ("tv.joint_torque",) if "tv.joint_torque" in PROVIDER else ()
    return ("joint.applied_torque", "joint.slip_capacity") + tv


def _rpm(w: float | None) -> str:
    return "" if w is None or not np.isfinite(w) else f"{w * 30.0 / np.pi:.0f} rpm"


@calculation("joint_computed_torque", "joints",
             provides=("joint.computed_torque", "joint.computed_cover_factor",
                       "joint.computed_torque_ratio"),
             needs=_computed_needs, optional=("tv.joint_torque",),
             reads=("joints", "joint_torques"))
def joint_computed_torque(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """The torsional model's torque at each joint and operating point next to the design torque.

    The cover-factor rules (JNT-003..007) use the design torque: the value given in sheet
    JointTorques where there is one (the practice of Ricardo 2013, slides 23-24, where the
    torque comes from a separate VALDYN run), otherwise the torsional module's. This
    calculation reports the torsional module's torque at the same named operating point
    (``joint.computed_torque``; 'tv peak' = the model's own peak speed), the cover factor at
    that torque (``joint.computed_cover_factor``) and their ratio
    ``joint.computed_torque_ratio = T_computed / T_design``, judged only where the design
    torque is given (elsewhere it is 1 by definition). A ratio above 1 means the given torque
    is below what the model of this engine predicts, so the cover factor it gives is optimistic.
    """
    app = inputs["joint.applied_torque"]
    cap = inputs["joint.slip_capacity"]
    tv = inputs.get("tv.joint_torque")
    tv_gone = inputs.get(UNAVAILABLE, {}).get("tv.joint_torque")
    shape = app.values.shape
    names = app.coords["item"]
    comp = np.full(shape, np.nan) if tv is None else np.array(tv.values, dtype=float)
    if tv is None:
        why = ["the torsional module could not run: " + "; ".join(tv_gone)] if tv_gone else [
            "the torsional module did not run"]
        comp_missing = {(i, k): list(why) for i in range(shape[0]) for k in range(shape[1])}
        comp_speed = np.full(shape, np.nan)
        comp_case = np.full(shape, "", dtype=object)
        comp_findings: dict[tuple, list[str]] = {}
    else:
        comp_missing = {key: list(v) for key, v in tv.missing.items()}
        comp_speed = np.asarray(tv.detail.speed, dtype=float)
        comp_case = tv.detail.case
        comp_findings = {key: list(v) for key, v in tv.findings.items()}
    given = np.asarray(app.detail.source == GIVEN_SOURCE, dtype=bool)
    capv = np.broadcast_to(np.asarray(cap.values, dtype=float)[:, None], shape)
    ok_cf = np.isfinite(capv) & np.isfinite(comp) & (comp > 0)
    comp_cf = np.full(shape, np.nan)
    comp_cf[ok_cf] = bj.cover_factor(capv[ok_cf], comp[ok_cf])
    cf_missing = {key: list(v) for key, v in comp_missing.items()}
    for (i,), reasons in cap.missing.items():
        for k in range(shape[1]):
            cf_missing[(i, k)] = list(dict.fromkeys(cf_missing.get((i, k), []) + reasons))
    design = np.asarray(app.values, dtype=float)
    ratio = np.ones(shape)
    ratio_missing: dict[tuple, list[str]] = {}
    ratio_findings: dict[tuple, list[str]] = {}
    given_speed = np.asarray(app.detail.speed, dtype=float)
    for i, n in enumerate(names):
        for k, p in enumerate(POINTS):
            if not given[i, k]:
                continue
            if not np.isfinite(comp[i, k]):
                ratio[i, k] = np.nan
                ratio_missing[(i, k)] = [
                    f"the torsional model's torque of joint '{n}' at '{p}' (to compare with the"
                    " torque given in JointTorques): "
                    + "; ".join(comp_missing.get((i, k), ["not computed"]))]
                continue
            ratio[i, k] = comp[i, k] / design[i, k]
            if ratio[i, k] <= 1.0:
                continue
            case = case_text(str(comp_case[i, k]))
            where = ", ".join(x for x in (case, _rpm(comp_speed[i, k])) if x)
            at_given = _rpm(given_speed[i, k])
            text = (f"{n} at '{p}': the torsional model gives {comp[i, k]:.0f} N m"
                    + (f" ({where})" if where else "")
                    + f", {(ratio[i, k] - 1) * 100:.0f} % above the {design[i, k]:.0f} N m given"
                    " in JointTorques" + (f" (at {at_given})" if at_given else "")
                    + " that the cover-factor rules use")
            if np.isfinite(comp_cf[i, k]):
                text += (f"; cover factor {comp_cf[i, k]:.4g} at the computed torque instead of"
                         f" {capv[i, k] / design[i, k]:.4g}")
            ratio_findings[(i, k)] = [text]
    coords = {"item": list(names), "point": list(POINTS)}
    attrs = dict(app.item_attrs)
    detail = ComputedTorqueDetail(
        speed=comp_speed, case=comp_case, how=(tv.detail.how if tv is not None else None),
        given=given, design=design, given_speed=given_speed)
    return {
        "joint.computed_torque": Quantity(COMPUTED, comp, coords, attrs, comp_missing,
                                          comp_findings, detail=detail),
        "joint.computed_cover_factor": Quantity(COMPUTED_COVER, comp_cf, coords, attrs,
                                                cf_missing, detail=detail),
        "joint.computed_torque_ratio": Quantity(
            TORQUE_RATIO, ratio, coords, attrs, ratio_missing, ratio_findings, detail=detail,
            applies=given, applies_text=RATIO_APPLIES),
    }
