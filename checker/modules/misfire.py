"""Graph calculation of the misfire case (module ``misfire``, "Misfire"): the torsional
response at full load with one cylinder not firing, every cylinder in turn, the worst case
judged (rules MIS-).

Model (:mod:`checker.calc.misfire`): the misfiring cylinder gets no fuel but keeps its
compression (Korean Register, Rules for Steel Ships, Pt 5 Ch 4, 102.1: "no injection but with
compression"): its gas pressure is the motored trace, the polytrope fitted to the full-load
trace's own compression line; its inertia torque is unchanged. The excitation of every other
cylinder and the torsional model are those of the torsion module (``tv.nose_amplitude``'s
model, the cylinder torques of :func:`checker.calc.crank_forces.cylinder_loads` from the
loads module's full-load traces); the response is superposed on normal firing per misfiring
cylinder (one factorisation per speed and order). All orders 0.5..24 are kept: a misfire
excites the lower and half orders that cancel in normal firing.

Judged at full load within its operating envelope (the full-load data range), the worst
misfiring cylinder at each speed: the damper (rubber: heat per volume against the supplier's
limit, sheet Damper) and the flexible couplings (vibratory torque and heat against T_KW and
P_KV, DIN 740-2 conventions, sheet Coupling). The class rules found (Korean Register Pt 5 Ch
4, 102.1 and 206) ask for the misfire case but give no limit of their own for the crankshaft;
the element torques under misfire are reported beside normal firing.
"""

from __future__ import annotations

import numpy as np

from ..calc import class_limits as cl
from ..calc import coupling as cp
from ..calc import crank_forces as cf
from ..calc import damper as dmp
from ..calc import excitation as exc
from ..calc import misfire as mf
from ..calc import pressure as pr
from ..calc import torsion_post as tp
from ..calc import torsional as tv
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.misfire import MisfireDetail, MisfireStressDetail
from . import coupling as cpl
from . import damper_inputs as dinp
from .torsion_stress import TENSILE_CAP

CASE = "full"
MAX_ORDER = exc.DEFAULT_MAX_ORDER

M_TORQUE = quantity(QuantitySpec(
    "misfire.element_torque", "N*m", ("item", "speed"),
    "Vibratory torque in each element of the TV model with one cylinder misfiring (no"
    " injection, compression kept), the worst cylinder, full load (half peak-to-peak)", "N*m",
    ("kind",), detail=MisfireDetail))
M_TORQUE_RATIO = quantity(QuantitySpec(
    "misfire.element_torque_increase", "", ("item", "speed"),
    "Misfire vibratory torque over normal firing's, each element, full load", "",
    ("kind",), detail=MisfireDetail))
M_DAMPER_POWER = quantity(QuantitySpec(
    "misfire.damper_power", "W", ("speed",),
    "Power dissipated in the TV damper with one cylinder misfiring, the worst cylinder, full"
    " load", "W", detail=MisfireDetail))
M_DAMPER_HEAT = quantity(QuantitySpec(
    "misfire.damper_heat_density", "W/m**3", ("speed",),
    "Mean heat per unit rubber volume of the TV damper with one cylinder misfiring, the worst"
    " cylinder, full load", "W/cm**3", filters=("damper_type",), detail=MisfireDetail))
M_DAMPER_FLUX = quantity(QuantitySpec(
    "misfire.damper_heat_flux", "W/m**2", ("speed",),
    "Power dissipated per wetted ring area of a viscous TV damper with one cylinder"
    " misfiring, the worst cylinder, full load", "W/cm**2", filters=("damper_type",),
    detail=MisfireDetail))
M_COUPLING_TORQUE = quantity(QuantitySpec(
    "misfire.coupling_torque_ratio", "", ("item", "speed"),
    "Flexible coupling vibratory torque x S_t x S_f over T_KW with one cylinder misfiring, the"
    " worst cylinder, full load", "", detail=MisfireDetail))
M_COUPLING_HEAT = quantity(QuantitySpec(
    "misfire.coupling_heat_ratio", "", ("item", "speed"),
    "Flexible coupling damping power x S_t over P_KV with one cylinder misfiring, the worst"
    " cylinder, full load", "", detail=MisfireDetail))
M_STRESS = quantity(QuantitySpec(
    "misfire.crank_stress_ratio", "", ("item", "speed"),
    "Crank vibratory shear stress with one cylinder misfiring (the worst cylinder, full load)"
    " over the class's transient limit tau_2 (the class gives no misfire limit of its own)",
    "", ("engine_class",), detail=MisfireStressDetail))
PROVIDES = ("misfire.element_torque", "misfire.element_torque_increase",
            "misfire.damper_power", "misfire.damper_heat_density", "misfire.damper_heat_flux",
            "misfire.coupling_torque_ratio", "misfire.coupling_heat_ratio")

ENVELOPE_TEXT = ("judged at full load within its operating envelope (the full-load data"
                 " range), the worst misfiring cylinder at each speed")


def _traces(engine: Engine, cyc) -> tuple[np.ndarray, mf.MotoredTrace]:
    """Full-load firing traces (S, N) and their motored traces."""
    p = engine.params
    if p.get("compression_ratio") is None:
        raise MissingInputs([engine.describe_missing(
            "Engine", "compression_ratio", what="the engine (needed for the cylinder volume of"
            " the misfiring cylinder's motored trace)")])
    ci = list(cyc.cases).index(CASE)
    off = engine.offsets
    vol = pr.cylinder_volume(cyc.theta, p["bore"], p["stroke"] / 2.0, p["rod_length"],
                             p["compression_ratio"], off["cylinder_offset"], off["pin_offset"])
    fire = cyc.pressure[ci]
    try:
        mot = mf.motored_trace(cyc.theta, fire, vol)
    except ValueError as err:
        raise MissingInputs([f"PressureTraces/PeakPressure: full-load trace: {err}"]) from None
    return fire, mot


def _coefficients(engine: Engine, cyc, fire: np.ndarray, motored: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Order coefficients (2, S, O) of one cylinder's crank torque, firing and motored."""
    p = engine.params
    loads = cf.cylinder_loads(
        cyc.theta, cyc.speeds[None, :], np.stack([fire, motored])[:, :, None, :],
        bore=p["bore"], crank_radius=p["stroke"] / 2.0, rod_length=p["rod_length"],
        piston_mass=p["piston_mass"], rod_mass=p["rod_mass"], rod_cg_from_big_end=p["rod_com"],
        rod_inertia=p["rod_inertia"], firing_angle=np.zeros(1), **engine.offsets)
    return exc.torque_harmonics(loads.torque[:, :, 0, :], MAX_ORDER)


def _worst(values: np.ndarray, axis: int) -> tuple[np.ndarray, np.ndarray]:
    k = np.argmax(values, axis=axis)
    return np.take_along_axis(values, np.expand_dims(k, axis), axis).squeeze(axis), k


CLASSES = ("industrial", "marine")
"""Engine classes the misfire case is judged for: the class societies ask for it for
propulsion and generator engines (Korean Register Pt 5 Ch 4, 101.1 and 102.1)."""


def _applies(engine: Engine) -> bool:
    return str(engine.params.get("engine_class") or "").lower() in CLASSES


def _why_not(engine: Engine) -> str:
    cls = engine.params.get("engine_class") or "passenger car (the default)"
    return (f"the misfire case is a class-society requirement for marine propulsion and"
            f" generator (industrial) engines (Korean Register, Rules for Steel Ships, Pt 5"
            f" Ch 4, 101.1 and 102.1); this engine's class is {cls} (Engine sheet, 'Engine"
            " class')")


@calculation("misfire_response", "misfire", provides=PROVIDES,
             needs=("loads.cycle", "tv.nose_amplitude"),
             reads=("params", "cylinders", "tv_model", "damper", "coupling", "driven"),
             applies=_applies, applies_why=_why_not)
def misfire_response(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Full-load response with each cylinder misfiring in turn; the worst case per speed."""
    cyc = inputs["loads.cycle"].detail.cycle
    nose = inputs["tv.nose_amplitude"].detail
    model: tv.TorsionalModel = nose.model
    data = nose.model_data
    speeds = np.asarray(cyc.speeds, dtype=float)
    fire, mot = _traces(engine, cyc)
    orders, coeffs = _coefficients(engine, cyc, fire, mot.pressure)
    firing = np.array([c.firing_angle for c in engine.cylinders])
    force = exc.phase_cylinders(coeffs[0], orders, firing)  # (S, Z, O)
    delta = mf.misfire_excitation(coeffs[0], coeffs[1], orders, firing)
    try:
        res = mf.misfire_response(model, speeds, orders, force, delta, data.cyl_station,
                                  cpl.station_damping(engine, speeds))
    except np.linalg.LinAlgError:
        raise MissingInputs(["TVModel: the torsional model is singular at a swept speed and"
                             " order (an undamped resonance, see the torsion section): add"
                             " damping"]) from None
    names = [s.station for s in engine.tv_model]
    n_el = model.n_elements
    el_names = [f"{names[e]} -> {names[e + 1]}" for e in range(n_el)]
    cyl = tuple(c.number for c in engine.cylinders)

    # element torques: half range of all orders, each misfiring cylinder and normal firing
    both = np.concatenate([res.torque, res.torque_normal[:, None]], axis=1)  # (S, Z+1, E, O)
    hi, lo = tp.synthesized_extremes(orders, both)
    amp = 0.5 * (hi - lo)  # (S, Z+1, E)
    mis, normal = amp[:, :-1], amp[:, -1]
    worst_t, k_t = _worst(mis, axis=1)  # (S, E)
    worst_orders = np.abs(np.take_along_axis(res.torque, k_t[:, None, :, None], 1)[:, 0])

    # the damper element (ring -> hub) and the couplings: any element's heat 1/2 W Im z |dphi|^2
    z = tv.element_impedance(model, res.omega)  # (S, O, E)
    twist = res.theta[:, :, :-1] - res.theta[:, :, 1:]  # (S, Z, E, O)
    twist0 = res.theta_normal[:, :-1] - res.theta_normal[:, 1:]  # (S, E, O)
    zt = np.moveaxis(z, 1, 2)  # (S, E, O)
    power_el = 0.5 * res.omega[:, None, None, :] * zt.imag[:, None] * np.abs(twist) ** 2
    power_el0 = 0.5 * res.omega[:, None, :] * zt.imag * np.abs(twist0) ** 2
    ring = data.ring
    damper_p = damper_p0 = None
    if ring is not None:
        damper_p = power_el[:, :, ring].sum(-1).T  # (Z, S)
        damper_p0 = power_el0[:, ring].sum(-1)

    couplings = cpl.coupling_elements(engine)
    c_torque = c_power = None
    c_ratio_t = c_ratio_p = None
    c_missing: list[str] = []
    if couplings:
        try:
            state = cpl.coupling_state(engine)
        except MissingInputs as err:
            c_missing = err.reasons
        else:
            c_torque = np.moveaxis(mis[:, :, couplings], -1, 0).transpose(0, 2, 1)  # (K, Z, S)
            tw = np.moveaxis(twist[:, :, couplings], 2, 0)  # (K, S, Z, O)
            po = cp.damping_power(tw, res.omega[:, None, :], state.stiffness,
                                  state.relative_damping).sum(-1)
            c_power = np.moveaxis(po, 1, 2)  # (K, Z, S)
            t_ord = np.abs(np.moveaxis(res.torque[:, :, couplings], 2, 0))  # (K, S, Z, O)
            ratio, _f = cp.vibratory_torque_ratio(
                np.moveaxis(c_torque, 1, 2), t_ord, res.omega[:, None, :] / (2 * np.pi),
                state.vibratory_torque, state.temperature_factor)  # (K, S, Z)
            c_ratio_t = ratio.max(-1)
            c_ratio_p = c_power.max(1) * state.temperature_factor / state.damping_power

    detail = MisfireDetail(
        speeds=speeds, orders=orders, cylinders=cyl, elements=tuple(el_names),
        element_torque=np.transpose(mis, (1, 2, 0)), element_torque_normal=normal.T,
        worst_cylinder=k_t.T, worst_torque_orders=np.moveaxis(worst_orders, 0, 1),
        motored_exponent=np.broadcast_to(mot.exponent, speeds.shape).copy(),
        motored_peak=np.broadcast_to(mot.peak, speeds.shape).copy(),
        firing_peak=fire.max(-1), damper_power=damper_p, damper_power_normal=damper_p0,
        couplings=tuple(el_names[e] for e in couplings),
        coupling_torque=c_torque, coupling_power=c_power,
        assumptions=(
            "Misfire: one cylinder at a time gets no fuel but keeps its compression (Korean"
            " Register, Rules for Steel Ships, Pt 5 Ch 4, 102.1); its gas pressure is the"
            " polytrope fitted to the full-load trace's compression line between -110 and -50"
            f" deg (exponent {float(np.min(mot.exponent)):.3g}..{float(np.max(mot.exponent)):.3g};"
            " Heywood 1988 sec. 9.2), its inertia torque unchanged; full load; orders 0.5 to"
            f" {MAX_ORDER:g}, the lower and half orders the misfire excites included.",))
    env = cyc.envelope
    judged = None if env is None else env[list(cyc.cases).index(CASE)]  # (S,)
    kinds = {el_names[e]: {"kind": "damper rubber" if e == ring else
                           cpl.COUPLING if e in couplings else "shaft"} for e in range(n_el)}
    e_coords = {"item": el_names, "speed": list(speeds)}
    out = {
        "misfire.element_torque": Quantity(
            M_TORQUE, worst_t.T, e_coords, kinds, detail=detail, applies=judged,
            applies_text=ENVELOPE_TEXT),
        "misfire.element_torque_increase": Quantity(
            M_TORQUE_RATIO, worst_t.T / np.where(normal.T > 0, normal.T, np.inf), e_coords,
            kinds, detail=detail, applies=judged, applies_text=ENVELOPE_TEXT),
    }
    out.update(_damper(engine, ring, damper_p, speeds, detail, judged))
    k_coords = {"item": list(detail.couplings), "speed": list(speeds)}
    for name, spec, vals in (("misfire.coupling_torque_ratio", M_COUPLING_TORQUE, c_ratio_t),
                             ("misfire.coupling_heat_ratio", M_COUPLING_HEAT, c_ratio_p)):
        if vals is None:
            vals = np.full((len(couplings), speeds.size), np.nan)
        miss = {(i,): list(c_missing) for i in range(len(couplings))} if c_missing else {}
        out[name] = Quantity(spec, vals, k_coords, missing=miss, detail=detail,
                             applies=judged, applies_text=ENVELOPE_TEXT)
    return out


def _limit_attrs(engine: Engine, kind: str, attr: str) -> dict:
    """Item attributes with the supplier's limit of sheet Damper (SI), or its blank cell."""
    lim = engine.damper.get(attr)
    if lim is None:
        return {"all": {"damper_type": kind, "limit_missing": [engine.describe_missing(
            "Damper", attr, what="the damper supplier")]}}
    return {"all": {"damper_type": kind, "limit": (float(lim),),
                    "limit_cell": engine.cell("Damper", attr)}}


def _damper(engine: Engine, ring: int | None, power: np.ndarray | None, speeds: np.ndarray,
            detail: MisfireDetail, judged: np.ndarray | None) -> dict[str, Quantity]:
    """The damper's power under misfire (worst cylinder), a rubber's heat per volume and a
    viscous damper's heat per wetted area."""
    coords = {"speed": list(speeds)}
    nan = np.full(speeds.size, np.nan)
    kind = dinp.damper_type(engine)
    attrs = {"all": {"damper_type": kind}}
    specs = (("misfire.damper_power", M_DAMPER_POWER),
             ("misfire.damper_heat_density", M_DAMPER_HEAT),
             ("misfire.damper_heat_flux", M_DAMPER_FLUX))

    def blank(spec: QuantitySpec, why: list[str], at: dict = attrs) -> Quantity:
        return Quantity(spec, nan, coords, at, {(si,): why for si in range(speeds.size)},
                        detail=detail)

    if ring is None or power is None:
        why = ["TVModel: no station with role 'damper ring' (engine without a TV damper)"]
        return {n: blank(s, why) for n, s in specs}
    worst = power.max(0)
    out = {"misfire.damper_power": Quantity(M_DAMPER_POWER, worst, coords, attrs, detail=detail,
                                            applies=judged, applies_text=ENVELOPE_TEXT)}
    d = engine.damper
    if kind == "viscous":
        out["misfire.damper_heat_density"] = blank(M_DAMPER_HEAT, [
            "Damper: a viscous damper has no rubber (Damper type 'viscous')"])
        flux_attrs = _limit_attrs(engine, kind, "heat_flux_limit")
        try:
            area = dinp.viscous_coupling(engine).wetted_area
        except MissingInputs as err:
            out["misfire.damper_heat_flux"] = blank(M_DAMPER_FLUX, err.reasons, flux_attrs)
            return out
        if area is None:
            out["misfire.damper_heat_flux"] = blank(M_DAMPER_FLUX, [
                engine.describe_missing("Damper", a, what="the viscous damper (its wetted"
                                        " area)")
                for a in ("ring_inner_radius", "ring_outer_radius", "ring_width",
                          "gap_radial", "gap_axial") if d.get(a) is None], flux_attrs)
            return out
        out["misfire.damper_heat_flux"] = Quantity(
            M_DAMPER_FLUX, worst / area, coords, flux_attrs, detail=detail, applies=judged,
            applies_text=ENVELOPE_TEXT)
        return out
    out["misfire.damper_heat_flux"] = blank(M_DAMPER_FLUX, [
        "Damper: a rubber damper has no silicone film (Damper type 'rubber')"])
    heat_attrs = _limit_attrs(engine, kind, "heat_limit")
    geo = [engine.describe_missing("Damper", a, what="the damper rubber")
           for a in ("inner_radius", "outer_radius", "axial_length") if d.get(a) is None]
    if geo:
        out["misfire.damper_heat_density"] = blank(M_DAMPER_HEAT, geo, heat_attrs)
        return out
    q_mean, _q_peak = dmp.annulus_heat_density(worst, d["inner_radius"], d["outer_radius"],
                                               d["axial_length"])
    out["misfire.damper_heat_density"] = Quantity(M_DAMPER_HEAT, q_mean, coords, heat_attrs,
                                                  detail=detail, applies=judged,
                                                  applies_text=ENVELOPE_TEXT)
    return out


LIMIT_TEXT = {
    "marine": ("the class gives no misfire limit: its transient limit tau_2 = 2 tau_1 f_m2"
               " (Korean Register Pt 5 Ch 4 201.2, 201.4; defined up to 0.8 of the rated"
               " speed) is used up to the rated speed, the formula extended above 0.8 (a"
               " misfiring engine keeps running at its speed); above the rated speed not"
               " judged"),
    "industrial": ("the class gives no misfire limit: the generator engine's transient limit"
                   " tau_2 = 90 N/mm^2 f_m2 (Korean Register Pt 5 Ch 4 203.1(2), 203.3;"
                   " defined below 0.9 of the rated speed) is used at every speed"),
}


def _misfire_limit(cls: str, lam: np.ndarray, group: str, f2: float) -> np.ndarray:
    """The transient limit used for the misfire case [Pa] (:data:`LIMIT_TEXT`), NaN where
    not judged."""
    if cls == "industrial":
        return np.full(lam.shape, cl.generator_transient(f2))
    ok = lam <= 1.0 + 1e-9
    out = np.full(lam.shape, np.nan)
    out[ok] = 2.0 * f2 * cl.propulsion_continuous(np.minimum(lam[ok], 1.0), group, 1.0)
    return out


@calculation("misfire_crank_stress", "misfire", provides=("misfire.crank_stress_ratio",),
             needs=("misfire.element_torque", "tv.crank_shear_stress"),
             reads=("params", "cylinders", "fatigue.uts", "fatigue.yield_strength"),
             applies=_applies, applies_why=_why_not)
def misfire_crank_stress(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """The crank sections' stress under misfire against the class's transient limit."""
    mt: Quantity = inputs["misfire.element_torque"]
    st: Quantity = inputs["tv.crank_shear_stress"]
    rated = engine.params.get("rated_speed")
    if rated is None:
        raise MissingInputs([engine.describe_missing(
            "Engine", "rated_speed", what="the engine (the speed ratio of the class limit)")])
    cls = str(engine.params.get("engine_class") or "").lower()
    if cls not in LIMIT_TEXT:
        raise MissingInputs([f"{engine.cell('Engine', 'engine_class')}: the misfire case's"
                             " crank stress is judged for marine and industrial engines"])
    idx = np.asarray(st.detail.element_index, dtype=int)
    w = np.asarray(st.detail.polar_modulus, dtype=float)
    speeds = np.asarray(mt.coords["speed"], dtype=float)
    tau = mt.values[idx] / w[:, None]  # (Ec, S)
    tau0 = mt.detail.element_torque_normal[idx] / w[:, None]
    lam = cl.speed_ratio(speeds, float(rated))
    firing = np.array([c.firing_angle for c in engine.cylinders])
    bank = np.array([c.bank_angle for c in engine.cylinders])
    group = cl.engine_group(firing, bank)
    fa = engine.fatigue
    _f1, f2 = cl.material_factors(fa.get("uts"), fa.get("yield_strength"), TENSILE_CAP)
    lim = _misfire_limit(cls, lam, group, f2)
    judged = np.isfinite(lim) if mt.applies is None else (mt.applies[idx] & np.isfinite(lim))
    with np.errstate(invalid="ignore"):
        ratio = np.where(np.isfinite(lim), tau / np.where(np.isfinite(lim), lim, 1.0), 0.0)
    names = [mt.coords["item"][e] for e in idx]
    detail = MisfireStressDetail(
        speeds=speeds, sections=tuple(names), stress=tau, stress_normal=tau0, limit=lim,
        speed_ratio=lam, engine_class=cls, limit_text=LIMIT_TEXT[cls],
        assumptions=("Misfire crank stress: the crank sections' nominal shear stress (IACS UR"
                     " M53 2.2, the polar modulus of tv.crank_shear_stress) with the worst"
                     " misfiring cylinder; " + LIMIT_TEXT[cls] + f" (f_m2 = {f2:.3f}).",))
    return {"misfire.crank_stress_ratio": Quantity(
        M_STRESS, ratio, {"item": names, "speed": list(speeds)},
        {n: {"engine_class": cls} for n in names}, detail=detail, applies=judged,
        applies_text=ENVELOPE_TEXT + "; " + LIMIT_TEXT[cls])}

