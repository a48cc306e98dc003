"""Graph calculations for the crankshaft's vibratory torsional stress and the class-society
rules on it (module ``torsion``; detail types :mod:`checker.results.torsion`).

* ``tv_crank_stress`` gives ``tv.crank_shear_stress`` (per order
  ``tv.crank_order_shear_stress``): the nominal shear stress amplitude of every crank
  section of the TV model, ``tau = M_TN / W_P`` (IACS UR M53, Rev. 4, 2019,
  2.2(A)(e)): ``M_TN`` the half range of the element torque synthesised over the cycle
  (quantity ``tv.element_torque``), ``W_P = pi/16 (D^4 - D_B^4)/D`` of the crank pin and of
  the main journal (diameters from sheet Bearings, axial bores from sheet Fatigue), the
  smaller modulus (the larger stress) governing, since every crank section's torque passes
  a main journal and half a crank pin. Crank sections: the elements from the crank-nose
  station to the flywheel (to the last cylinder station without a flywheel). Per order the
  0-to-peak stress ``|T_en| / W_P``.
* ``tv_class_rules`` judges that stress by the rules of a classification society for the
  engine classes ``marine`` (a main propulsion engine: Korean Register, Rules for the
  Classification of Steel Ships, Pt 5 Ch 4, 2025, 201), ``industrial`` (a generator engine:
  the same rules, 203) and ``commercial vehicle`` (no published limit: the propulsion
  limit of 201.1/201.3 as a stated engineering default): the stress over the permissible
  stress at each speed (``tv.crank_stress_ratio_continuous``, ``_transient``,
  ``_overspeed``), the barred speed range of every critical above the continuous limit
  (``tv.barred_speed_range``, 206.1(1)) and the critical speeds of the major orders of the
  one-node mode against the band 204 keeps free (``tv.major_critical_clearance``). The
  passenger-car class keeps the crank-nose targets of Bell 2013 (TV-001..003): these rules
  do not apply to it.
"""

from __future__ import annotations

import numpy as np

from ..calc import class_limits as cl
from ..calc import crank_stress as cs
from ..calc import excitation as exc
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.torsion import (
    BarredRangeDetail,
    ClassLimitDetail,
    CrankStressDetail,
    MajorCriticalDetail,
)
from ..workbook.units import RPM
from .torsion import CASES

CLASS_RULE_CLASSES = ("marine", "industrial", "commercial vehicle")
"""Engine classes judged by class-society limits of the crank's vibratory stress."""
TENSILE_CAP = cl.TS_CAP_CARBON
"""Largest tensile strength credited in the material factor (KR Pt 5 Ch 4 201.4 leaves
strengths above 590 N/mm^2 for carbon-steel forgings, 835 N/mm^2 for low-alloy forgings, to
the Society; the steel's kind is not an input, so the lower cap is taken)."""
CRITICAL_MATCH = 0.1
"""Relative distance of a critical speed from the speed of an exceedance's peak within which
that critical is taken as its cause (else the peak speed is the critical, stated)."""

STRESS = quantity(QuantitySpec(
    "tv.crank_shear_stress", "Pa", ("item", "case", "speed"),
    "Nominal vibratory shear stress in each crank section of the TV model (element torque half"
    " range over the smaller polar section modulus of crank pin and main journal)", "MPa",
    ("section",), coords={"case": CASES}, detail=CrankStressDetail))
STRESS_ORDER = quantity(QuantitySpec(
    "tv.crank_order_shear_stress", "Pa", ("order", "item", "case", "speed"),
    "Nominal vibratory shear stress in each crank section per harmonic order (0-to-peak)",
    "MPa", ("section",), coords={"case": CASES}, detail=CrankStressDetail))
_RATIO_FILTERS = ("engine_class",)
CONTINUOUS = quantity(QuantitySpec(
    "tv.crank_stress_ratio_continuous", "", ("item", "case", "speed"),
    "Crank vibratory shear stress over the class's permissible stress for continuous"
    " operation (tau_1; for commercial vehicles an engineering default), in the speed range"
    " judged", "", _RATIO_FILTERS, coords={"case": CASES}, detail=ClassLimitDetail))
TRANSIENT = quantity(QuantitySpec(
    "tv.crank_stress_ratio_transient", "", ("item", "case", "speed"),
    "Crank vibratory shear stress over the class's permissible stress for transient"
    " operation (tau_2), below 0.8 (generators 0.9) of the rated speed", "", _RATIO_FILTERS,
    coords={"case": CASES}, detail=ClassLimitDetail))
OVERSPEED = quantity(QuantitySpec(
    "tv.crank_stress_ratio_overspeed", "", ("item", "case", "speed"),
    "Crank vibratory shear stress over the class's permissible stress from the rated speed to"
    " 115 % of it (tau_3)", "", _RATIO_FILTERS, coords={"case": CASES},
    detail=ClassLimitDetail))
BARRED = quantity(QuantitySpec(
    "tv.barred_speed_range", "", ("item",),
    "Upper end of the barred speed range of each critical whose stress exceeds tau_1, as a"
    " fraction of the rated speed", "", _RATIO_FILTERS, detail=BarredRangeDetail))
MAJOR = quantity(QuantitySpec(
    "tv.major_critical_clearance", "", ("item",),
    "Distance of the critical speed of each major order of the one-node mode from the band"
    " of the rated speed the class keeps free (positive: outside), as a fraction of the rated"
    " speed", "%", _RATIO_FILTERS, detail=MajorCriticalDetail))


# ------------------------------------------------------------------------ crank stress
def crank_sections(engine: Engine) -> list[int]:
    """Indices of the TV elements that are crank sections: from the crank-nose station to
    the flywheel station (to the last cylinder station when the flywheel is not behind it)."""
    roles = [s.role for s in engine.tv_model]
    if "crank nose" not in roles:
        return []
    rear = _crank_rear(engine)
    return [] if rear is None else list(range(roles.index("crank nose"), rear))


def _crank_rear(engine: Engine) -> int | None:
    """Station index where the crank ends: the flywheel behind the last cylinder station,
    else the last cylinder station (None: no cylinder station)."""
    roles = [s.role for s in engine.tv_model]
    cyl = [i for i, s in enumerate(engine.tv_model) if s.cylinders]
    if not cyl:
        return None
    rear = max(cyl)
    if "flywheel" in roles and roles.index("flywheel") > rear:
        rear = roles.index("flywheel")
    return rear


def whole_system(engine: Engine) -> bool:
    """Whether the TV model is the complete dynamic system (IACS UR M53 2.2(A)(a)): stations
    behind the crank (a coupling, a generator, a propeller), not the engine alone."""
    rear = _crank_rear(engine)
    return rear is not None and rear < len(engine.tv_model) - 1


def bars_speed_ranges(engine: Engine) -> bool:
    """Whether the engine's class rules impose barred speed ranges (marine propulsion)."""
    return engine_class(engine) == "marine"


def _section_moduli(engine: Engine) -> dict:
    """Diameters, bores and polar moduli of the crank pin and main journal (the smallest
    diameters of the Bearings rows); raises MissingInputs naming the cells."""
    mains = [b for b in engine.bearings if b.type == "main"]
    bigs = [b for b in engine.bearings if b.type == "big end"]
    missing = []
    if not mains:
        missing.append("Bearings: no main bearing rows (the main journal diameter)")
    if not bigs:
        missing.append("Bearings: no big-end bearing rows (the crank-pin diameter)")
    if missing:
        raise MissingInputs(missing)
    fa = engine.fatigue
    d_pin, d_jnl = min(b.diameter for b in bigs), min(b.diameter for b in mains)
    b_pin, b_jnl = fa.get("pin_bore") or 0.0, fa.get("main_bore") or 0.0
    try:
        _, w_pin = cs.shaft_section_moduli(d_pin, b_pin)
        _, w_jnl = cs.shaft_section_moduli(d_jnl, b_jnl)
    except ValueError as err:
        raise MissingInputs([f"Fatigue/Bearings: crank pin or journal section: {err}"]) from None
    return {"pin_diameter": float(d_pin), "pin_bore": float(b_pin),
            "journal_diameter": float(d_jnl), "journal_bore": float(b_jnl),
            "pin_modulus": float(w_pin), "journal_modulus": float(w_jnl)}


@calculation("tv_crank_stress", "torsion",
             provides=("tv.crank_shear_stress", "tv.crank_order_shear_stress"),
             needs=("tv.element_torque", "loads.cycle"),
             reads=("tv_model", "bearings.type", "bearings.diameter", "fatigue.pin_bore",
                    "fatigue.main_bore"))
def tv_crank_stress(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Nominal vibratory shear stress in every crank section, synthesised and per order."""
    et: Quantity = inputs["tv.element_torque"]
    env = getattr(inputs["loads.cycle"].detail.cycle, "envelope", None)
    elems = crank_sections(engine)
    if not elems:
        raise MissingInputs(["TVModel: no crank section (no element from the 'crank nose'"
                             " station to a cylinder station or the flywheel)"])
    geo = _section_moduli(engine)
    w = min(geo["pin_modulus"], geo["journal_modulus"])
    section = "crank pin" if geo["pin_modulus"] <= geo["journal_modulus"] else "main journal"
    names = [et.coords["item"][e] for e in elems]
    vals = et.values[elems] / w  # (E, C, S)
    per_order = np.abs(et.detail.coeffs[elems]) / w  # (E, C, S, O)
    judged = np.ones(vals.shape[1:], bool) if env is None else np.asarray(env, bool)
    worst = int(np.argmax(np.where(judged[None], vals, -np.inf).max(axis=(1, 2))))
    ex = et.detail
    detail = CrankStressDetail(
        orders=ex.orders, speeds=ex.speeds, resonance=ex.resonance,
        near_resonance=ex.near_resonance, assumptions=(
            "Crank vibratory shear stress: tau = M_TN / W_P (IACS UR M53 2.2), M_TN the half"
            " range of the element torque synthesised over 720 deg, W_P = pi/16 (D^4 - D_B^4)/D"
            f" of the crank pin (D = {geo['pin_diameter'] * 1e3:g} mm) and the main journal"
            f" (D_G = {geo['journal_diameter'] * 1e3:g} mm), the smaller ({section}) for every"
            " crank section; the nominal stress of the plain section, no stress raisers.",),
        order_stress=per_order, element_index=np.array(elems),
        polar_modulus=np.full(len(elems), w), section=tuple([section] * len(elems)),
        worst=worst, envelope=None if env is None else np.asarray(env, bool), **geo)
    attrs = {n: {"section": section} for n in names}
    findings = {(i, ci, si): v for (e, ci, si), v in et.findings.items() if e in elems
                for i in [elems.index(e)]}
    coords = {"item": names, "case": list(et.coords["case"]), "speed": list(et.coords["speed"])}
    return {"tv.crank_shear_stress": Quantity(STRESS, vals, coords, attrs, findings=findings,
                                              detail=detail),
            "tv.crank_order_shear_stress": Quantity(
                STRESS_ORDER, np.moveaxis(per_order, -1, 0),
                {"order": [f"order {n:g}" for n in ex.orders], **coords}, attrs,
                detail=detail)}


# ------------------------------------------------------------------------ class rules
def engine_class(engine: Engine) -> str:
    """The engine class in lower case ('passenger car' when not given)."""
    return str(engine.params.get("engine_class") or "passenger car").lower()


def _applies(engine: Engine) -> bool:
    return engine_class(engine) in CLASS_RULE_CLASSES


def _why_not(engine: Engine) -> str:
    return (f"the class-society limits of the crank's vibratory stress are judged for"
            f" {', '.join(CLASS_RULE_CLASSES)} engines; this engine is a"
            f" {engine_class(engine)} engine (judged by the crank-nose targets of Bell 2013,"
            " TV-001..003)")


def _limit_curves(cls: str, group: str, lam: np.ndarray, f1: float, f2: float
                  ) -> dict[str, np.ndarray]:
    """Permissible stresses over the sweep [Pa], NaN where the class defines none."""
    nan = np.full(lam.shape, np.nan)
    cont, trans, over = nan.copy(), nan.copy(), nan.copy()
    if cls == "industrial":
        lo, hi = cl.GENERATOR_BAND
        m = (lam >= lo - 1e-9) & (lam <= hi + 1e-9)
        cont[m] = cl.generator_continuous(group, f1)
        trans[lam <= lo + 1e-9] = cl.generator_transient(f2)
        return {"continuous": cont, "transient": trans, "overspeed": over}
    m = lam <= 1.0 + 1e-9
    cont[m] = cl.propulsion_continuous(np.minimum(lam[m], 1.0), group, f1)
    m = lam <= cl.PROPULSION_TRANSIENT_TOP + 1e-9
    trans[m] = cl.propulsion_transient(np.minimum(lam[m], cl.PROPULSION_TRANSIENT_TOP),
                                       group, f2)
    m = (lam > 1.0 + 1e-9) & (lam <= cl.OVERSPEED_TOP + 1e-9)
    over[m] = cl.propulsion_overspeed(np.minimum(lam[m], cl.OVERSPEED_TOP), group, f1)
    if cls == "commercial vehicle":  # one continuous curve: tau_1 to the rated speed, tau_3
        cont = np.where(np.isnan(cont), over, cont)
        trans[:] = np.nan
        over[:] = np.nan
    return {"continuous": cont, "transient": trans, "overspeed": over}


_BANDS = {  # (class, limit) -> (lambda band judged, text)
    ("marine", "continuous"): ((cl.BARRED_RANGE_TOP, 1.0),
                               "speeds from 0.8 to 1.0 of the rated speed, where no barred"
                               " speed range may lie (IACS UR M53 2.2(A)(d); KR Pt 5 Ch 4"
                               " 201.1); below 0.8 a stress above tau_1 is judged by its"
                               " barred range (TV-007) and tau_2 (TV-005)"),
    ("marine", "transient"): ((0.0, cl.PROPULSION_TRANSIENT_TOP),
                              "speeds up to 0.8 of the rated speed (KR Pt 5 Ch 4 201.2)"),
    ("marine", "overspeed"): ((1.0, cl.OVERSPEED_TOP),
                              "speeds above the rated speed up to 1.15 of it (KR Pt 5 Ch 4"
                              " 201.3)"),
    ("industrial", "continuous"): (cl.GENERATOR_BAND,
                                   "speeds from 0.9 to 1.1 of the rated speed (generator"
                                   " engine, KR Pt 5 Ch 4 203.1(1))"),
    ("industrial", "transient"): ((0.0, cl.GENERATOR_BAND[0]),
                                  "speeds up to 0.9 of the rated speed (generator engine, KR"
                                  " Pt 5 Ch 4 203.1(2))"),
    ("commercial vehicle", "continuous"): ((0.0, cl.OVERSPEED_TOP),
                                           "speeds up to 1.15 of the rated speed (engineering"
                                           " default: KR Pt 5 Ch 4 201.1 and 201.3); above,"
                                           " no limit is defined"),
}
_SOURCES = {
    "marine": "KR Pt 5 Ch 4 201 (main engine crankshafts)",
    "industrial": "KR Pt 5 Ch 4 203.1 (crankshafts of generator engines)",
    "commercial vehicle": "ENGINEERING DEFAULT: no published limit for a commercial-vehicle"
                          " crankshaft; KR Pt 5 Ch 4 201.1/201.3 (main engine crankshafts)",
}


def _ratio(spec: QuantitySpec, kind: str, cls: str, stress: Quantity, lam: np.ndarray,
           curves: dict, common: dict) -> Quantity:
    """Stress over the permissible stress ``kind`` on the speeds of the class's band."""
    band, text = _BANDS.get((cls, kind), ((np.inf, -np.inf), f"no {kind} limit for a {cls}"
                                           " engine"))
    lim = curves[kind]
    cols = np.flatnonzero((lam >= band[0] - 1e-9) & (lam <= band[1] + 1e-9)
                          & np.isfinite(lim))
    tau = stress.values[:, :, cols]
    env = stress.detail.envelope
    applies = (np.ones(tau.shape, bool) if env is None
               else np.broadcast_to(env[:, cols], tau.shape))
    items = list(stress.coords["item"])
    attrs = {n: {"engine_class": cls, "section": stress.item_attrs[n]["section"]}
             for n in items}
    sp = np.asarray(stress.coords["speed"], float)
    ratio = tau / lim[cols] if cols.size else tau
    findings = {}
    for e, n in enumerate(items):  # the stress and the limit at each item's worst point
        if not applies[e].any():
            continue
        ci, k = np.unravel_index(int(np.argmax(np.where(applies[e], ratio[e], -np.inf))),
                                 ratio.shape[1:])
        si = cols[k]
        findings[(e, int(ci), int(k))] = [
            f"{n}: tau = {tau[e, ci, k] / 1e6:.3g} MPa against the {kind} limit"
            f" {lim[si] / 1e6:.3g} MPa at lambda = {lam[si]:.3f} ({sp[si] / RPM:.0f} rpm)"]
    detail = ClassLimitDetail(
        **common, judged_band=tuple(band), speeds=sp[cols], stress=tau, limit=lim[cols],
        source=_SOURCES[cls], default=cls == "commercial vehicle")
    return Quantity(spec, ratio,
                    {"item": items, "case": list(stress.coords["case"]),
                     "speed": list(sp[cols])}, attrs, findings=findings, applies=applies,
                    applies_text=f"judged at {text}, within each load case's operating"
                                 " envelope", detail=detail)


def _criticals(nf: Quantity) -> tuple[np.ndarray, np.ndarray]:
    """Critical speeds (M, O) [rad/s] and orders (O,) of the flexible modes."""
    return np.asarray(nf.detail.critical_speed, float), np.asarray(nf.detail.orders, float)


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) index of every run of True in a 1-D boolean mask."""
    edges = np.diff(np.concatenate([[0], np.asarray(mask, int), [0]]))
    return [(int(a), int(b) - 1) for a, b in zip(np.flatnonzero(edges == 1),
                                                 np.flatnonzero(edges == -1), strict=True)]


def _critical_at(order_stress: np.ndarray, crit: np.ndarray, orders: np.ndarray,
                 speed: float) -> tuple[float, str, float, int]:
    """The critical behind a stress peak at ``speed`` [rad/s]: (N_c [rad/s], label, order,
    mode (0-based; -1 none)). The order with the largest stress there (``order_stress``, (O,))
    and the mode whose critical speed for it is nearest, if within :data:`CRITICAL_MATCH`;
    else the peak's own speed."""
    oi = int(np.argmax(order_stress))
    if crit.size:
        m = int(np.argmin(np.abs(crit[:, oi] - speed)))
        if abs(crit[m, oi] - speed) <= CRITICAL_MATCH * speed:
            return float(crit[m, oi]), f"order {orders[oi]:g}, mode {m + 1}", orders[oi], m
    return float(speed), f"peak at {speed / RPM:.0f} rpm", float("nan"), -1


def _barred(cls: str, stress: Quantity, nf: Quantity, lam: np.ndarray, curves: dict,
            rated: float) -> Quantity:
    """Barred speed ranges of the criticals whose synthesised stress exceeds tau_1: one per
    run of swept speeds above tau_1 (either load case, within its envelope), the rule's
    range around the run's critical (:func:`_critical_at`) widened to the whole run."""
    sp = np.asarray(stress.coords["speed"], float)
    tau = stress.values  # (E, C, S)
    env = stress.detail.envelope
    judged = np.ones(tau.shape[1:], bool) if env is None else env
    tau1 = curves["continuous"] if cls == "marine" else np.full(sp.shape, np.nan)
    with np.errstate(invalid="ignore"):
        r = np.where(judged[None] & np.isfinite(tau1), tau / tau1, 0.0)  # (E, C, S)
    crit, orders = _criticals(nf)
    rows: dict[str, dict] = {}
    for s, t in _runs((r > 1.0).any(axis=(0, 1))):
        e, ci, si = np.unravel_index(int(np.argmax(r[:, :, s:t + 1])),
                                     (r.shape[0], r.shape[1], t + 1 - s))
        si += s
        nc, label, order, mode = _critical_at(stress.detail.order_stress[e, ci, si], crit,
                                              orders, sp[si])
        if label in rows and rows[label]["ratio"] >= r[e, ci, si]:
            continue
        rng = cl.barred_speed_range(nc, rated)
        rows[label] = {"ratio": r[e, ci, si], "nc": nc,
                       "lo": min(float(rng.lower), sp[s]), "hi": max(float(rng.upper), sp[t]),
                       "rule_lo": float(rng.lower), "rule_hi": float(rng.upper),
                       "run_lo": sp[s], "run_hi": sp[t], "order": order, "mode": mode,
                       "peak_speed": sp[si], "peak_stress": tau[e, ci, si],
                       "peak_limit": tau1[si], "section": stress.coords["item"][e],
                       "case": stress.coords["case"][ci]}
    labels = sorted(rows, key=lambda x: rows[x]["nc"])

    def get(field: str) -> np.ndarray:
        return np.array([rows[x][field] for x in labels], dtype=float)

    vals = get("hi") / rated
    detail = BarredRangeDetail(
        critical_speed=get("nc"), lower=get("lo"), upper=get("hi"),
        rule_lower=get("rule_lo"), rule_upper=get("rule_hi"), run_lower=get("run_lo"),
        run_upper=get("run_hi"), order=get("order"),
        mode=get("mode").astype(int), peak_speed=get("peak_speed"),
        peak_stress=get("peak_stress"), peak_limit=get("peak_limit"),
        section=tuple(rows[x]["section"] for x in labels),
        case=tuple(rows[x]["case"] for x in labels), rated_speed=rated)
    findings = {(i,): [
        f"barred speed range {rows[x]['lo'] / RPM:.0f}..{rows[x]['hi'] / RPM:.0f} rpm around"
        f" the critical at {rows[x]['nc'] / RPM:.0f} rpm (lambda = {rows[x]['nc'] / rated:.3f}):"
        f" stress {rows[x]['peak_stress'] / 1e6:.3g} MPa above tau_1"
        f" {rows[x]['peak_limit'] / 1e6:.3g} MPa at {rows[x]['peak_speed'] / RPM:.0f} rpm"
        f" ({rows[x]['section']}, {rows[x]['case']} load)"] for i, x in enumerate(labels)}
    why = ("no critical's synthesised stress exceeds the continuous limit tau_1 below the"
           " rated speed: no barred speed range is needed" if cls == "marine" else
           f"barred speed ranges are judged for marine propulsion engines (this {cls} engine"
           " runs continuously only where tau_1 is defined)")
    return Quantity(BARRED, vals, {"item": labels},
                    {x: {"engine_class": cls} for x in labels}, findings=findings,
                    applies_text=why, detail=detail)


def _major(cls: str, engine: Engine, nf: Quantity, rated: float) -> Quantity:
    """Critical speeds of the major orders of the one-node mode against the class's band."""
    band = {"marine": cl.PROPULSION_CRITICAL_BAND, "industrial": cl.GENERATOR_BAND}.get(cls)
    crit, orders = _criticals(nf)
    firing = np.array([c.firing_angle for c in engine.cylinders])
    major = exc.major_order_mask(orders, firing) if crit.size and band else \
        np.zeros(orders.size, bool)
    idx = np.flatnonzero(major)
    nc = crit[0, idx] if idx.size else np.zeros(0)
    lam_c = nc / rated
    labels = [f"order {orders[i]:g}, mode 1" for i in idx]
    vals = cl.band_clearance(lam_c, band) if band else lam_c
    f1 = float(nf.values[0]) if nf.values.size else float("nan")
    findings = {(k,): [f"order {orders[i]:g} meets mode 1 ({f1:.1f} Hz) at"
                       f" {nc[k] / RPM:.0f} rpm, lambda = {lam_c[k]:.3f}; band kept free:"
                       f" {band[0]:g}..{band[1]:g}"] for k, i in enumerate(idx)}
    why = ("no flexible mode" if not crit.size else
           f"major criticals are judged for marine and industrial engines (not a {cls} engine)")
    return Quantity(MAJOR, vals, {"item": labels}, {x: {"engine_class": cls} for x in labels},
                    findings=findings, applies_text=why,
                    detail=MajorCriticalDetail(
                        order=orders[idx], critical_speed=nc, speed_ratio=lam_c,
                        band=tuple(band) if band else (np.nan, np.nan),
                        natural_frequency=f1, rated_speed=rated))


@calculation("tv_class_rules", "torsion",
             provides=("tv.crank_stress_ratio_continuous", "tv.crank_stress_ratio_transient",
                       "tv.crank_stress_ratio_overspeed", "tv.barred_speed_range",
                       "tv.major_critical_clearance"),
             needs=("tv.crank_shear_stress", "tv.natural_frequency"),
             reads=("params.engine_class", "params.rated_speed", "fatigue.uts",
                    "fatigue.yield_strength", "cylinders"),
             applies=_applies, applies_why=_why_not)
def tv_class_rules(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """The crank's vibratory stress against the class rules, barred ranges, major criticals."""
    stress: Quantity = inputs["tv.crank_shear_stress"]
    nf: Quantity = inputs["tv.natural_frequency"]
    cls = engine_class(engine)
    if cls not in CLASS_RULE_CLASSES:  # (the rules are not applicable: the graph says why)
        raise MissingInputs([_why_not(engine)])
    rated = engine.params.get("rated_speed")
    if rated is None:
        raise MissingInputs([engine.describe_missing(
            "Engine", "rated_speed", what="the engine (the speed ratio of the class rules)")])
    firing = np.array([c.firing_angle for c in engine.cylinders])
    bank = np.array([c.bank_angle for c in engine.cylinders])
    group = cl.engine_group(firing, bank)
    fa = engine.fatigue
    f1, f2 = cl.material_factors(fa.get("uts"), fa.get("yield_strength"), TENSILE_CAP)
    sp = np.asarray(stress.coords["speed"], float)
    lam = cl.speed_ratio(sp, rated)
    curves = _limit_curves(cls, group, lam, f1, f2)
    kind = ("in-line, or V firing every 45 or 60 deg" if group == "A"
            else "V with other firing intervals")
    notes = [f"Class limits of the crank's vibratory stress: {_SOURCES[cls]}; engine group"
             f" {group} of KR Pt 5 Ch 4 201.1 ({kind});"
             f" material factor f_m = {f1:.3f} (tau_1, tau_3) and {f2:.3f} (tau_2) from"
             f" {engine.cell('Fatigue', 'uts')} and {engine.cell('Fatigue', 'yield_strength')}"
             f" (tensile strength credited up to {TENSILE_CAP / 1e6:.0f} MPa)."]
    if fa.get("uts") is None or fa.get("yield_strength") is None:
        notes.append("Material strength not given: f_m = 1 where missing (the rules permit,"
                     " not require, the increase).")
    common = dict(engine_class=cls, group=group, rated_speed=float(rated), speed_ratio=lam,
                  continuous=curves["continuous"], transient=curves["transient"],
                  overspeed=curves["overspeed"], f_m_tensile=f1, f_m_yield=f2,
                  assumptions=tuple(notes))
    return {
        "tv.crank_stress_ratio_continuous": _ratio(CONTINUOUS, "continuous", cls, stress, lam,
                                                   curves, common),
        "tv.crank_stress_ratio_transient": _ratio(TRANSIENT, "transient", cls, stress, lam,
                                                  curves, common),
        "tv.crank_stress_ratio_overspeed": _ratio(OVERSPEED, "overspeed", cls, stress, lam,
                                                  curves, common),
        "tv.barred_speed_range": _barred(cls, stress, nf, lam, curves, float(rated)),
        "tv.major_critical_clearance": _major(cls, engine, nf, float(rated)),
    }
