"""Graph calculation for crankshaft balancing: free forces and moments by order, counterweight
balance ratio per throw and the internal bending moment of the rotating masses.

Inputs: sheet ``Cylinders`` (firing and bank angles, crank pins), ``Engine`` (stroke, rod,
piston and rod masses, offsets, main journal spacing, rated speed, the project's balancing
limits) and ``CrankMass`` (webs, counterweights, pins). No load calculation is needed: the
free forces are inertia forces of the moving parts (:mod:`checker.calc.balance`).

Geometry: crank pin ``j`` (bay ``j``) lies at mid-bay, axial position ``(j - 1/2) L`` from the
front main (``L`` = main journal spacing, as in the loads module); rods sharing a pin sit at
its mid-plane. Crank masses are at ``(throw - 1) L + axial position + X`` with their crank-frame
position (the sheet's Z, Y are in the throw-1 frame, turned by throw 1's angle; ``pin axis``
rows shifted by the pin position: :func:`checker.calc.crank_forces.mass_positions`). Free
moments are taken about the crank's mid-plane ``z = n_pins L / 2``.

Values are at the reference speed: the rated speed (Engine 'Rated speed'), else the maximum
speed; forces scale with the speed squared. The rules compare them with the project's own
limits from the Engine sheet (``limit_from = "workbook"``); without a limit a rule is not
evaluated.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..calc import balance as bal
from ..calc import crank_forces as cf
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.balance import (
    BalanceDetail,
    BalanceRatioDetail,
    CrankUnbalanceDetail,
    FreeOrderDetail,
    InternalMomentDetail,
)
from ..workbook.units import RPM

MAX_ORDER = bal.DEFAULT_MAX_ORDER
ORDERS = tuple(str(n) for n in range(1, MAX_ORDER + 1))

FREE_FORCE = quantity(QuantitySpec(
    "balance.free_force", "N", ("item",),
    "Free (shaking) force per order at the reference speed: largest magnitude over the crank"
    " angle (rotating and reciprocating masses)", "N", ("order",), detail=FreeOrderDetail))
FREE_MOMENT = quantity(QuantitySpec(
    "balance.free_moment", "N*m", ("item",),
    "Free moment per order about the crank's mid-plane at the reference speed: largest"
    " magnitude over the crank angle", "N*m", ("order",), detail=FreeOrderDetail))
BALANCE_RATIO = quantity(QuantitySpec(
    "balance.balance_ratio", "", ("item",),
    "Counterweight balance ratio: counterweight unbalance / rotating unbalance (webs, pin, rod"
    " big ends) along the throw, per throw and for the whole crank", "%", ("kind",),
    detail=BalanceRatioDetail))
INTERNAL_MOMENT = quantity(QuantitySpec(
    "balance.internal_moment", "N*m", ("item",),
    "Bending moment of the rotating masses' centrifugal forces in the crank at each main"
    " bearing, at the reference speed", "N*m", detail=InternalMomentDetail))

CRANK_UNBALANCE = quantity(QuantitySpec(
    "balance.crank_unbalance", "", ("item",),
    "Resultant unbalance of the crank's rotating masses (CrankMass rows and the rods' big"
    " ends) in a layout whose throws balance each other: static = |sum m rho| / one throw's"
    " rotating unbalance U; dynamic = |sum m rho z| / (U x main journal spacing)", "%",
    ("kind",), detail=CrankUnbalanceDetail))

PROVIDES = ("balance.free_force", "balance.free_moment", "balance.balance_ratio",
            "balance.internal_moment", "balance.crank_unbalance")

UNBALANCE_FRACTION = 0.05
"""Unbalance of the crank's rotating masses, as a fraction of one throw's rotating unbalance
(static) or of that unbalance times the main journal spacing (dynamic), above which a layout
that is inherently balanced gets a finding (rule BAL-006 uses the same 5 % as its limit).
Rounding of entered coordinates leaves far less (~1e-5), a misplaced counterweight or a
coordinate in the wrong column far more (one web's counterweight is ~40 % of a throw)."""

_LIMITS = {("force", "1"): "free_force_limit_1", ("force", "2"): "free_force_limit_2",
           ("moment", "1"): "free_moment_limit_1", ("moment", "2"): "free_moment_limit_2"}


def _ordinal(n: int) -> str:
    return {1: "1st", 2: "2nd", 3: "3rd"}.get(n, f"{n}th")


def _limit_attrs(engine: Engine, attr: str, what: str) -> dict:
    v = engine.params.get(attr)
    if v is None:
        return {"limit_missing": [engine.describe_missing(
            "Engine", attr, what=f"the project (needed to judge the {what}; blank = not"
            " judged)")]}
    return {"limit": (float(v),), "limit_cell": engine.cell("Engine", attr)}


def _band_attrs(engine: Engine, sheet: str, lo: str, hi: str, what: str) -> dict:
    params = engine.params if sheet == "Engine" else getattr(engine, sheet.lower())
    a, b = params.get(lo), params.get(hi)
    miss = [engine.describe_missing(sheet, n, what=f"the project (needed to judge the {what})")
            for n, v in ((lo, a), (hi, b)) if v is None]
    if miss:
        return {"limit_missing": miss}
    if a > b:
        return {"limit_missing": [f"{engine.cell(sheet, lo)} / {engine.cell(sheet, hi)}: the"
                                  f" minimum ({a:g}) is above the maximum ({b:g})"]}
    return {"limit": (float(a), float(b)),
            "limit_cell": f"{engine.cell(sheet, lo)}, {engine.cell(sheet, hi)}"}


def reference_speed(engine: Engine) -> tuple[float, str]:
    """Reference speed [rad/s] and how it was chosen (rated, else maximum speed)."""
    p = engine.params
    if p.get("rated_speed") is not None:
        return float(p["rated_speed"]), f"rated speed ({engine.cell('Engine', 'rated_speed')})"
    if p.get("speed_max") is not None:
        return float(p["speed_max"]), (f"maximum speed ({engine.cell('Engine', 'speed_max')});"
                                       " no rated speed given")
    raise MissingInputs([engine.describe_missing("Engine", "rated_speed",
                                                 what="the engine (reference speed of the"
                                                 " free forces)")])


@calculation("balance", "balance", provides=PROVIDES,
             reads=("params", "cylinders", "crank_mass", "bearings.name", "bearings.type"))
def balance(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Free forces and moments by order, balance ratio per throw, internal bending moment."""
    with np.errstate(over="ignore", invalid="ignore"):  # overflow becomes a missing reason
        return _overflow_checked(_balance(engine), engine)


def _balance(engine: Engine) -> dict[str, Quantity]:
    p = engine.params
    if not engine.cylinders:
        raise MissingInputs(["Cylinders: no cylinders given (sheet Cylinders)"])
    need = [n for n in ("stroke", "rod_length", "piston_mass", "rod_mass", "rod_com")
            if p.get(n) is None]
    if need:
        raise MissingInputs([engine.describe_missing("Engine", n, what="the engine (needed for"
                                                     " the inertia forces)") for n in need])
    omega, speed_text = reference_speed(engine)
    w2 = omega * omega
    r = p["stroke"] / 2.0
    cyls = engine.cylinders
    firing = np.array([c.firing_angle for c in cyls])
    bank = np.array([c.bank_angle for c in cyls])
    pins = np.array([c.pin - 1 for c in cyls])
    n_pins = int(pins.max()) + 1
    try:
        gamma = cf.throw_angles(firing, bank, pins, n_pins)
    except ValueError as exc:
        raise MissingInputs([f"Cylinders: {exc}"]) from None
    # the rods' inertia-correction couple is a roll torque: no free force or moment
    m_small, m_big, _ = cf.rod_mass_split(p["rod_mass"], p["rod_length"], p["rod_com"],
                                          p["rod_mass"] * p["rod_com"]
                                          * (p["rod_length"] - p["rod_com"]))
    m_rec = p["piston_mass"] + float(m_small)
    m_big = float(m_big)
    off = engine.offsets  # total offset of the slider line (checker.calc.kinematics)
    offset = off["cylinder_offset"] - off["pin_offset"]
    try:
        harm = bal.piston_acceleration_harmonics(r, p["rod_length"], offset, MAX_ORDER)
    except ValueError as exc:
        raise MissingInputs([f"{engine.cell('Engine', 'rod_length')}: {exc}"]) from None

    spacing = p.get("main_spacing")
    assumptions = [
        "Balancing: rigid crank train at constant speed; con-rod as its two-mass equivalent"
        " (reciprocating small-end share with the piston, rotating big-end share at the pin);"
        " free forces and moments are the inertia forces on the engine structure (Taylor 1985,"
        f" vol. 2, ch. 8), orders 1..{MAX_ORDER} from the exact piston kinematics, at the"
        f" {speed_text}, {omega / RPM:.0f} rpm."]
    e_pin = np.stack([np.sin(gamma), np.cos(gamma)], axis=-1)  # (n_pins, 2)
    crank = engine.crank_mass
    no_crank = ["CrankMass: crank mass properties are needed for the crank's rotating unbalance"
                " (sheet CrankMass)"]
    no_spacing = [engine.describe_missing("Engine", "main_spacing", what="the crank (axial"
                                          " positions of throws and mains)")]
    # rotating masses: crank items + rods' big ends at their pins
    cm = np.array([it.mass for it in crank], dtype=float)
    cthrow = np.array([it.throw - 1 for it in crank], dtype=int)
    cpos = cf.mass_positions([it.z for it in crank], [it.y for it in crank], cthrow,
                             [it.reference == "pin axis" for it in crank], gamma, r)
    cw = np.array([it.kind == "counterweight" for it in crank], dtype=bool)
    rod_pos = r * e_pin[pins]
    L = spacing if spacing is not None else 0.0
    zc = L * n_pins / 2.0
    cax = np.array([(it.throw - 1) * L + it.axial + it.x for it in crank], dtype=float) - zc
    zcyl = (pins + 0.5) * L - zc
    rm = np.concatenate([cm, np.full(len(cyls), m_big)])
    rpos = np.concatenate([cpos, rod_pos]) if crank else rod_pos
    rax = np.concatenate([cax, zcyl])
    res = bal.shaking_phasors(firing_angle=firing, bank_angle=bank, cylinder_axial=zcyl,
                              reciprocating_mass=m_rec, acceleration_harmonics=harm,
                              rotating_mass=rm, rotating_position=rpos, rotating_axial=rax)
    orders = res.orders
    f_big, f_small, f_theta, f_dir = bal.order_vector_extremes(res.force, orders)
    m_big_, m_small_, m_theta, m_dir = bal.order_vector_extremes(res.moment, orders)
    fr_big = bal.order_vector_extremes(res.force_reciprocating, orders)[0]
    mr_big = bal.order_vector_extremes(res.moment_reciprocating, orders)[0]

    items = [f"order {n}" for n in orders]
    f_attrs, m_attrs = {}, {}
    f_missing, m_missing = {}, {}
    for i, n in enumerate(orders):
        lab = str(n)
        f_attrs[items[i]] = {"order": lab}
        m_attrs[items[i]] = {"order": lab}
        if ("force", lab) in _LIMITS:
            f_attrs[items[i]].update(_limit_attrs(engine, _LIMITS[("force", lab)],
                                                  f"{_ordinal(n)}-order free force"))
            m_attrs[items[i]].update(_limit_attrs(engine, _LIMITS[("moment", lab)],
                                                  f"{_ordinal(n)}-order free moment"))
    f_vals = f_big * w2
    m_vals = m_big_ * w2
    if not crank:
        f_vals[0] = np.nan
        m_vals[0] = np.nan
        f_missing[(0,)] = list(no_crank)
        m_missing[(0,)] = list(no_crank)
    if spacing is None:
        m_vals[:] = np.nan
        for i in range(orders.size):
            m_missing[(i,)] = list(no_spacing) + m_missing.get((i,), [])
    common = BalanceDetail(orders=orders, omega=omega, speed_text=speed_text,
                           reciprocating_mass=m_rec, rotating_rod_mass=m_big, crank_radius=r,
                           harmonics=harm, reference_plane=zc, assumptions=tuple(assumptions))
    out: dict[str, Quantity] = {}
    out["balance.free_force"] = Quantity(
        FREE_FORCE, f_vals, {"item": items}, f_attrs, f_missing,
        detail=_as(FreeOrderDetail, common, phasors=res.force * w2, smallest=f_small * w2,
                   theta=f_theta, direction=f_dir, reciprocating=fr_big * w2,
                   rotating=bal.order_vector_extremes(res.force_rotating, orders)[0] * w2))
    out["balance.free_moment"] = Quantity(
        FREE_MOMENT, m_vals, {"item": items}, m_attrs, m_missing,
        detail=_as(FreeOrderDetail, common, phasors=res.moment * w2, smallest=m_small_ * w2,
                   theta=m_theta, direction=m_dir, reciprocating=mr_big * w2,
                   rotating=bal.order_vector_extremes(res.moment_rotating, orders)[0] * w2))

    # balance ratio per throw and for the whole crank
    b_items = [f"throw {j + 1}" for j in range(n_pins)] + ["crank"]
    band = _band_attrs(engine, "Engine", "balance_ratio_min", "balance_ratio_max",
                       "balance ratio")
    b_attrs = {it: dict(band, kind="crank" if it == "crank" else "throw") for it in b_items}
    if not crank:
        out["balance.balance_ratio"] = Quantity(
            BALANCE_RATIO, np.full(len(b_items), np.nan), {"item": b_items}, b_attrs,
            {(i,): list(no_crank) for i in range(len(b_items))},
            detail=_as(BalanceRatioDetail, common))
    else:
        n_on = np.bincount(pins, minlength=n_pins).astype(float)
        # unbalances off the crank (pulley, flywheel: sheet CrankEnds) belong to no throw
        on = np.array([it.kind != "unbalance" for it in crank], dtype=bool)
        try:
            tb = bal.throw_balance(throw_angle=gamma, mass=cm[on], position=cpos[on],
                                   throw_of_mass=cthrow[on], is_counterweight=cw[on],
                                   pin_rotating_mass=m_big * n_on,
                                   pin_reciprocating_mass=m_rec * n_on, crank_radius=r)
        except ValueError as exc:
            tb = None
            out["balance.balance_ratio"] = Quantity(
                BALANCE_RATIO, np.full(len(b_items), np.nan), {"item": b_items}, b_attrs,
                {(i,): [f"CrankMass: {exc}"] for i in range(len(b_items))},
                detail=_as(BalanceRatioDetail, common))
    if crank and tb is not None:
        out["balance.balance_ratio"] = Quantity(
            BALANCE_RATIO, np.append(tb.balance_ratio, tb.crank_ratio), {"item": b_items},
            b_attrs, detail=_as(BalanceRatioDetail, common, rotating=tb.rotating,
                                counterweight=tb.counterweight,
                                rotating_along=tb.rotating_along,
                                counterweight_along=tb.counterweight_along,
                                reciprocating_factor=tb.reciprocating_factor,
                                static_unbalance=np.hypot(*rm @ rpos),
                                couple_unbalance=np.hypot(*((rm * rax) @ rpos)),
                                throw_angle=gamma))

    out["balance.crank_unbalance"] = _crank_unbalance(
        engine, common, crank=bool(crank), spacing=spacing, gamma=gamma, pins=pins,
        rm=rm, rpos=rpos, rax=rax, is_cw=np.concatenate([cw, np.zeros(len(cyls), bool)]),
        throw_of=np.concatenate([cthrow, pins]), w2=w2, speed_text=speed_text, omega=omega,
        force=out["balance.free_force"], moment=out["balance.free_moment"])

    # internal bending moment at the mains
    mains = [b.name for b in engine.bearings if b.type == "main"]
    if len(mains) != n_pins + 1:
        mains = [f"main {k + 1}" for k in range(n_pins + 1)]
    why = (no_crank if not crank else []) + (no_spacing if spacing is None else [])
    if why:
        out["balance.internal_moment"] = Quantity(
            INTERNAL_MOMENT, np.full(n_pins + 1, np.nan), {"item": mains},
            missing={(k,): list(why) for k in range(n_pins + 1)},
            detail=_as(InternalMomentDetail, common))
    else:
        stations = L * np.arange(n_pins + 1) - zc
        b = bal.internal_bending_moment(stations, rm, rpos, rax)
        keep = ~np.concatenate([cw, np.zeros(len(cyls), bool)])
        b0 = bal.internal_bending_moment(stations, rm[keep], rpos[keep], rax[keep])
        out["balance.internal_moment"] = Quantity(
            INTERNAL_MOMENT, np.hypot(b[:, 0], b[:, 1]) * w2, {"item": mains},
            detail=_as(InternalMomentDetail, common, vector=b * w2,
                       without_counterweights=np.hypot(b0[:, 0], b0[:, 1]) * w2,
                       stations=stations + zc))
    return out


def _as(kind: type, common: BalanceDetail, **fields):
    """A detail of type ``kind`` holding the common fields of ``common`` and ``fields``."""
    return kind(**{f.name: getattr(common, f.name) for f in dataclasses.fields(common)},
                **fields)


def _crank_unbalance(engine: Engine, common: BalanceDetail, *, crank: bool, spacing: float | None,
                     gamma: np.ndarray, pins: np.ndarray, rm: np.ndarray, rpos: np.ndarray,
                     rax: np.ndarray, is_cw: np.ndarray, throw_of: np.ndarray, w2: float,
                     speed_text: str, omega: float, force: Quantity, moment: Quantity
                     ) -> Quantity:
    """Static and dynamic unbalance of the crank's rotating masses where the layout is
    inherently balanced (findings on this quantity and on the 1st-order free force/moment).

    A layout is inherently balanced statically when equal throws cancel, ``sum_j e_j = 0``
    (``e_j`` the unit vector of throw ``j``, each pin carrying the same number of rods), and
    dynamically when also ``sum_j z_j e_j = 0`` (Taylor 1985, vol. 2, ch. 8: in-line four and
    six, flat-plane V8; not the in-line three or the cross-plane V8, whose rotating couple the
    counterweights cancel by design). There, any resultant of the rotating masses comes from
    the crank data (a counterweight missing or misplaced, a coordinate in the wrong column).
    """
    static_ok, dynamic_ok = bal.inherent_balance(gamma, pins)
    items = ["static", "dynamic"]
    attrs = {it: {"kind": it} for it in items}
    vals = np.full(2, np.nan)
    missing: dict[tuple, list[str]] = {}
    findings: dict[tuple, list[str]] = {}
    applies = np.array([static_ok, dynamic_ok])
    if dynamic_ok:
        why = "the layout is inherently balanced (equal throws cancel, forces and couples)"
    elif static_ok:
        why = ("judged statically only: equal throws of this layout cancel as forces but leave"
               " a rotating couple, which the counterweights cancel by design (cross-plane V8,"
               " in-line three)")
    else:
        why = ("not judged: equal throws of this layout do not cancel (single throw, uneven"
               " layouts), so the counterweights balance the crank by design, not by symmetry")
    flags = dict(static_inherent=static_ok, dynamic_inherent=dynamic_ok,
                 fraction=UNBALANCE_FRACTION)
    if not crank:
        reason = ["CrankMass: crank mass properties are needed for the crank's rotating"
                  " unbalance (sheet CrankMass)"]
        return Quantity(CRANK_UNBALANCE, vals, {"item": items}, attrs,
                        {(0,): list(reason), (1,): list(reason)}, applies=applies,
                        applies_text=why, detail=_as(CrankUnbalanceDetail, common, **flags))
    keep = ~is_cw
    u_throw = bal.mean_throw_unbalance(rm[keep], rpos[keep], throw_of[keep], gamma.size)
    s_vec = rm @ rpos
    c_vec = (rm * rax) @ rpos
    flags.update(throw_unbalance=u_throw, static_vector=s_vec, couple_vector=c_vec)
    if not u_throw > 0:
        reason = ["CrankMass: the throws have no rotating unbalance without counterweights (webs,"
                  " pin and rods); check the crank masses and positions"]
        return Quantity(CRANK_UNBALANCE, vals, {"item": items}, attrs,
                        {(0,): list(reason), (1,): list(reason)}, applies=applies,
                        applies_text=why, detail=_as(CrankUnbalanceDetail, common, **flags))
    vals[0] = np.hypot(*s_vec) / u_throw
    if spacing is None:
        missing[(1,)] = [engine.describe_missing("Engine", "main_spacing", what="the crank"
                                                 " (lever of the rotating couple)")]
    else:
        vals[1] = np.hypot(*c_vec) / (u_throw * spacing)
    rpm = omega / RPM
    check = (" Check the CrankMass rows: the lateral position belongs in Z (X is the axial"
             " offset of the centre of mass), and the counterweights must balance the crank as"
             " a whole.")
    if static_ok and vals[0] > UNBALANCE_FRACTION:
        text = (f"the crank's rotating masses leave a static unbalance of"
                f" {np.hypot(*s_vec):.4g} kg m ({np.hypot(*s_vec) * w2 / 1e3:.3g} kN at"
                f" {rpm:.0f} rpm), {100 * vals[0]:.0f} % of one throw's rotating unbalance"
                f" {u_throw:.4g} kg m, in a layout whose equal throws cancel." + check)
        findings[(0,)] = [text]
        force.findings.setdefault((0,), []).append(text)
    if dynamic_ok and np.isfinite(vals[1]) and vals[1] > UNBALANCE_FRACTION:
        text = (f"the crank's rotating masses leave a rotating couple of"
                f" {np.hypot(*c_vec):.4g} kg m^2 ({np.hypot(*c_vec) * w2:.4g} N m at"
                f" {rpm:.0f} rpm), {100 * vals[1]:.0f} % of one throw's rotating unbalance x"
                f" the main journal spacing, in a layout whose equal throws cancel dynamically."
                + check)
        findings[(1,)] = [text]
        moment.findings.setdefault((0,), []).append(text)
    return Quantity(CRANK_UNBALANCE, vals, {"item": items}, attrs, missing, findings,
                    applies=applies, applies_text=why,
                    detail=_as(CrankUnbalanceDetail, common, **flags))


def _overflow_checked(out: dict[str, Quantity], engine: Engine) -> dict[str, Quantity]:
    """Entries that overflowed (absurd speed or masses) become missing with the reason, never
    NaN/inf for a rule to meet."""
    why = (f"{engine.cell('Engine', 'rated_speed')}: the balancing numbers overflow with these"
           " inputs (check the rated speed, masses and lengths)")
    for q in out.values():
        bad = ~np.isfinite(q.values)
        for idx in zip(*np.nonzero(bad)):
            key = tuple(int(i) for i in idx)
            if not any(q.missing.get(key[:n]) for n in range(len(key), 0, -1)):
                q.missing[key] = [why]
    return out
