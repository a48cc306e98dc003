"""Graph calculations for the TV damper at its own temperature (module ``damper``): a rubber
damper at the cold and hot ends of the operating temperature range (node
``damper_rubber_ends``, rules DMP-005..007) and an untuned viscous (Houdaille) damper (node
``viscous_damper``, rules DMP-008..010).

Both re-solve the torsional model of module ``torsion`` (the same stations, excitation and
speeds, quantity ``tv.nose_amplitude``) with the damper element's impedance per operating
point at the damper's own temperature: at each speed and load case the damper settles where
the heat it dissipates leaves its cooled surface, ``T = T_air + P(T) / (h A)``
(:func:`checker.calc.damper_temperature.self_heated_temperature`), with ``T_air`` the cold or
the hot end of the range on sheet Damper.

* rubber: ``k*(T) = Phi_r G'(T) (1 + j eta(T))`` from the DamperRubber table and the bonded
  annulus (:mod:`checker.calc.damper_temperature`); judged: the tuning ratio
  ``sqrt(k'(T) / J_ring) / omega_n`` (DMP-005, at the speed where the rubber dissipates most,
  i.e. at the crank resonance), the shear stress at the inner bond (DMP-006) and the heat per
  volume (DMP-007), against the same workbook limits as DMP-004, DMP-001 and DMP-002;
* viscous: ``z = j Omega c(T)`` (with the silicone's shear stiffness in series when given),
  ``c(T)`` from the silicone's viscosity at its temperature (Andrade) or typed; judged: the
  dissipated power per wetted ring area (DMP-008), the silicone temperature (DMP-009) and the
  damping against Den Hartog's optimum untuned viscous damper for this crank,
  ``c_opt = 2 J_ring omega_n / sqrt(2 (1 + mu)(2 + mu))`` (DMP-010, at the speed of the
  largest power). ``omega_n`` and ``mu = J_ring / J_eq``: the crank's first flexible mode
  without the ring and its modal inertia at the hub (:func:`checker.calc.damper_tuning.
  primary_mode`).

Detail type: :class:`checker.results.damper.DamperEndsDetail`.
"""

from __future__ import annotations

import numpy as np

from ..calc import damper as dmp
from ..calc import damper_temperature as dtemp
from ..calc import damper_tuning as dt
from ..calc import torsional as tv
from ..calc import viscous_damper as vd
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.damper import DamperEndsDetail
from . import damper_inputs as dinp

CASES = ("full", "no")
ENDS = dinp.ENDS
_DIMS = ("end", "case", "speed")
_COORDS = {"end": ENDS, "case": CASES}

VISCOUS_SEARCH = 500.0
"""Span above the air temperature [K] within which the viscous damper's heat balance is
solved; no solution within it is reported (thermal runaway), never clipped."""


def _spec(name: str, unit: str, description: str, display: str) -> QuantitySpec:
    return quantity(QuantitySpec(name, unit, _DIMS, description, display, coords=_COORDS,
                                 detail=DamperEndsDetail))


R_TEMP = _spec("damper.end_rubber_temperature", "K",
               "Damper rubber temperature at the cold and hot ends of the operating range"
               " (air temperature + own heat / (h A))", "°C")
R_TUNING = _spec("damper.end_tuning_ratio", "",
                 "Damper tuning ratio sqrt(k'(T)/J_ring) / crank first mode with the rubber at"
                 " its own temperature, cold and hot end", "")
R_SHEAR = _spec("damper.end_shear_stress", "Pa",
                "Damper rubber shear stress amplitude at the inner bond, cold and hot end",
                "MPa")
R_HEAT = _spec("damper.end_heat_density", "W/m**3",
               "Mean heat per unit rubber volume (P/V), cold and hot end", "W/cm**3")
R_NOSE = _spec("damper.end_nose_amplitude", "rad",
               "Crank-nose TV amplitude (all orders, half peak-to-peak) with the rubber at its"
               " own temperature, cold and hot end", "deg")
V_TEMP = _spec("damper.silicone_temperature", "K",
               "Viscous damper silicone temperature (air temperature + heat / (h A)), cold and"
               " hot end", "°C")
V_FLUX = _spec("damper.heat_flux", "W/m**2",
               "Viscous damper dissipated power per wetted ring area, cold and hot end",
               "W/cm**2")
V_OPT = _spec("damper.damping_to_optimum", "",
              "Viscous damper damping c(T) / Den Hartog's optimum c_opt of an untuned viscous"
              " damper for this crank, cold and hot end", "")
V_POWER = _spec("damper.viscous_power", "W",
                "Power dissipated in the viscous damper's silicone, cold and hot end", "W")
V_NOSE = _spec("damper.viscous_nose_amplitude", "rad",
               "Crank-nose TV amplitude (all orders, half peak-to-peak) with the viscous damper"
               " at its silicone temperature, cold and hot end", "deg")
V_COPT = quantity(QuantitySpec(
    "damper.optimum_damping", "N*m*s/rad", ("item",),
    "Den Hartog's optimum damping of an untuned viscous damper for this crank,"
    " c_opt = 2 J_ring w_n / sqrt(2 (1 + mu)(2 + mu))", "N*m*s/rad",
    detail=DamperEndsDetail))

RUBBER_PROVIDES = tuple(s.name for s in (R_TEMP, R_TUNING, R_SHEAR, R_HEAT, R_NOSE))
VISCOUS_PROVIDES = tuple(s.name for s in (V_TEMP, V_FLUX, V_OPT, V_POWER, V_NOSE, V_COPT))


def _limit(engine: Engine, attr: str, what: str, lo_hi: tuple[str, str] | None = None) -> dict:
    """Item attributes with the workbook limit (SI) of a rule, or the cells that are blank."""
    d = engine.damper
    if lo_hi is not None:
        lo, hi = d.get(lo_hi[0]), d.get(lo_hi[1])
        miss = [engine.describe_missing("Damper", a, what=what)
                for a, v in zip(lo_hi, (lo, hi)) if v is None]
        if miss:
            return {"all": {"limit_missing": miss}}
        if lo > hi:
            return {"all": {"limit_missing": [
                f"{engine.cell('Damper', lo_hi[0])} / {engine.cell('Damper', lo_hi[1])}: the"
                f" minimum ({lo:g}) is above the maximum ({hi:g})"]}}
        return {"all": {"limit": (float(lo), float(hi)),
                        "limit_cell": f"{engine.cell('Damper', lo_hi[0])},"
                                      f" {engine.cell('Damper', lo_hi[1])}"}}
    lim = d.get(attr)
    if lim is None:
        return {"all": {"limit_missing": [engine.describe_missing("Damper", attr, what=what)]}}
    return {"all": {"limit": (float(lim),), "limit_cell": engine.cell("Damper", attr)}}


def _envelope(inputs: dict) -> np.ndarray | None:
    """(C, S) operating envelope of the load cases (module loads), None = every speed."""
    cyc = getattr(inputs["loads.cycle"].detail, "cycle", None)
    return getattr(cyc, "envelope", None)


class _Resolver:
    """Re-solves of the torsional model with the damper element's impedance per point."""

    def __init__(self, nose_q: Quantity):
        ex = nose_q.detail
        self.model: tv.TorsionalModel = ex.model
        data = ex.model_data
        self.ring, self.nose = data.ring, data.nose
        if self.ring is None:
            raise MissingInputs(["TVModel: no station with role 'damper ring' (engine without"
                                 " a TV damper)"])
        if self.ring + 1 != self.nose:
            raise MissingInputs(["TVModel: the damper ring must hang on the crank nose (the"
                                 " 'crank nose' station must follow the 'damper ring'"
                                 " station)"])
        self.hub = self.ring + 1
        self.orders = np.asarray(ex.orders, dtype=float)
        self.speeds = np.asarray(ex.speeds, dtype=float)
        force = ex.excitation  # (C, S, n, O)
        self.C, self.S, n, o = force.shape
        self.force = force.reshape(self.C * self.S, n, o)
        self.sp = np.tile(self.speeds, self.C)
        self.omega = self.sp[:, None] * self.orders  # (P, O)
        self.cases = tuple(nose_q.coords["case"])
        if self.cases != CASES:
            raise MissingInputs([f"the load cases {self.cases} differ from {CASES}"])
        self.nominal_nose = np.asarray(nose_q.values, dtype=float)
        try:
            self.primary = dt.primary_mode(self.model, self.ring)
        except ValueError as exc:
            raise MissingInputs([f"TVModel: {exc}"]) from None
        # the damper element's contribution to D is z b b^T (b: +1 ring, -1 hub), so with
        # another z the relative twist is dphi0 / (1 + (z - z0) s), s = b^T D0^-1 b
        # (Sherman-Morrison): the heat balance's iterations need no new solve
        r0 = tv.forced_response(self.model, self.sp, self.orders, self.force)
        self.z0 = tv.element_impedance(self.model, self.omega)[..., self.ring]
        self.dphi0 = r0.theta[:, self.hub] - r0.theta[:, self.ring]
        unit = np.zeros_like(self.force)
        unit[:, self.ring, :], unit[:, self.hub, :] = 1.0, -1.0
        rb = tv.forced_response(self.model, self.sp, self.orders, unit)
        self.s = rb.theta[:, self.ring] - rb.theta[:, self.hub]

    def solve(self, z: np.ndarray) -> tuple[tv.ForcedResponse, np.ndarray]:
        """Response with the damper impedance ``z`` (P, O) and the relative twist (P, O)."""
        r = tv.forced_response(self.model, self.sp, self.orders, self.force,
                               impedance={self.ring: z})
        return r, r.theta[:, self.hub] - r.theta[:, self.ring]

    def power(self, z: np.ndarray) -> np.ndarray:
        """Dissipated power (P,) with the damper impedance ``z`` (P, O), by the rank-one
        update of the nominal solve (exact up to rounding; the reported results come from a
        full solve at the converged temperature)."""
        dphi = self.dphi0 / (1.0 + (z - self.z0) * self.s)
        return vd.impedance_power(dphi, self.omega, z).sum(-1)

    def shape(self, x: np.ndarray) -> np.ndarray:
        """(P, ...) -> (C, S, ...)."""
        return x.reshape((self.C, self.S) + x.shape[1:])


def _judged_at_peak_power(power: np.ndarray, envelope: np.ndarray | None) -> np.ndarray:
    """(E, C, S) mask: the speed of the largest dissipated power of each end and case within
    the case's operating envelope ((C, S), None = every speed). An end and case without a
    computed power there (the rubber's properties unknown at that end) keeps every speed of
    the envelope: its values are missing, and the rule says which inputs (not evaluated),
    as the rules judging every speed do."""
    inside = np.ones(power.shape, dtype=bool)
    if envelope is not None:
        inside = inside & np.broadcast_to(envelope, power.shape)
    ok = np.isfinite(power) & inside
    p = np.where(ok, power, -np.inf)
    k = np.argmax(p, axis=-1)
    e_i, c_i = np.indices(power.shape[:2])
    mask = np.zeros(power.shape, dtype=bool)
    mask[e_i, c_i, k] = ok.any(-1)
    unknown = ~ok.any(-1)
    mask[unknown] = inside[unknown]
    return mask


@calculation("damper_rubber_ends", "damper", provides=RUBBER_PROVIDES,
             needs=("tv.nose_amplitude", "loads.cycle"),
             reads=("damper", "tv_model", "cylinders", "params"),
             applies=dinp.has_rubber_ends, applies_why=dinp.why_no_rubber_ends)
def damper_rubber_ends(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """The rubber damper at the cold and hot ends of the operating temperature range."""
    what = "the damper rubber at the ends of its operating temperature range"
    problems: list[str] = []
    for f in (lambda: dinp.temperature_range(engine, what), lambda: dinp.rubber_table(engine),
              lambda: dinp.rubber_factor(engine), lambda: dinp.heat_resistance(engine, what)):
        try:
            f()
        except MissingInputs as exc:
            problems += exc.reasons
    if problems:
        raise MissingInputs(problems)
    t_air = dinp.temperature_range(engine, what)
    table = dinp.rubber_table(engine)
    phi = dinp.rubber_factor(engine)
    res_th = dinp.heat_resistance(engine, what)
    rs = _Resolver(inputs["tv.nose_amplitude"])
    c_rel = float(rs.model.damping_rel[rs.ring])
    d = engine.damper
    ri, ro, ln = d["inner_radius"], d["outer_radius"], d["axial_length"]
    volume = float(dmp.annulus_volume(ri, ro, ln))
    j_ring = float(rs.model.inertia[rs.ring])

    def z_at(temp: np.ndarray) -> np.ndarray:
        g, eta = table(temp)
        return (phi * g * (1.0 + 1j * eta))[:, None] + 1j * rs.omega * c_rel

    E, P = len(ENDS), rs.C * rs.S
    temp = np.full((E, P), np.nan)
    power = np.full((E, P), np.nan)
    tau = np.full((E, P), np.nan)
    nose = np.full((E, P), np.nan)
    k_st = np.full((E, P), np.nan)
    eta_t = np.full((E, P), np.nan)
    missing: dict[tuple, list[str]] = {}
    for e, ta in enumerate(t_air):
        if not table.inside(ta):
            cell = engine.cell("Damper", ("operating_temperature_min",
                                          "operating_temperature_max")[e])
            missing[(e,)] = [
                f"DamperRubber: the {ENDS[e]} end of the operating range"
                f" ({ta - 273.15:.0f} °C, {cell})"
                f" lies outside the rubber table ({table.t_min - 273.15:.0f} to"
                f" {table.t_max - 273.15:.0f} °C): the rubber's properties there are unknown"]
            continue
        t, _ = dtemp.self_heated_temperature(lambda x: rs.power(z_at(x)), np.full(P, ta),
                                             res_th, table.t_max)
        ok = np.isfinite(t)
        if not ok.all():
            missing.setdefault((e,), []).append(
                f"DamperRubber: at the {ENDS[e]} end the rubber's heat balance has no solution"
                f" within the table (up to {table.t_max - 273.15:.0f} °C) at some speeds: the"
                " rubber would be hotter than its properties are known")
        z = z_at(np.where(ok, t, ta))
        r, dphi = rs.solve(z)
        p = vd.impedance_power(dphi, rs.omega, z).sum(-1)
        torque_amp = dmp.synthesized_amplitude(rs.orders, z * dphi)
        g, eta = table(np.where(ok, t, ta))
        temp[e] = t
        power[e] = np.where(ok, p, np.nan)
        tau[e] = np.where(ok, dmp.annulus_shear_stress(torque_amp, ri, ln), np.nan)
        nose[e] = np.where(ok, tv.half_peak_to_peak(rs.orders, r.theta[:, rs.nose]), np.nan)
        k_st[e] = np.where(ok, phi * g, np.nan)
        eta_t[e] = np.where(ok, eta, np.nan)
    sh = lambda x: x.reshape(E, rs.C, rs.S)  # noqa: E731
    temp, power, tau, nose, k_st, eta_t = map(sh, (temp, power, tau, nose, k_st, eta_t))
    tuning = np.sqrt(k_st / j_ring) / rs.primary.omega
    judged = _judged_at_peak_power(power, _envelope(inputs))
    detail = DamperEndsDetail(
        damper_type="rubber", ends=ENDS, air_temperature=tuple(t_air), heat_resistance=res_th,
        speeds=rs.speeds, cases=rs.cases, temperature=temp, power=power, nose_amplitude=nose,
        nominal_nose_amplitude=rs.nominal_nose, judged=judged, crank_mode_omega=rs.primary.omega,
        modal_inertia=rs.primary.equivalent_inertia, ring_inertia=j_ring,
        ring=engine.tv_model[rs.ring].station, stiffness=k_st, loss_factor=eta_t,
        table=tuple(d["rubber_table"]),
        assumptions=(
            "Damper rubber at the ends of the operating temperature range: the rubber's"
            " temperature at each speed and load case from its own heat, T = T_air + P/(h A)"
            " (steady state, one temperature for the whole rubber); G' and the loss factor"
            " from the DamperRubber table at that temperature (ln G' and the loss factor"
            " interpolated linearly in temperature); the tuning ratio is judged at the speed"
            " of the largest dissipated power of each end and load case (the crank"
            " resonance).",) + dinp.heat_path_assumption(engine, res_th))
    coords = {"end": list(ENDS), "case": list(rs.cases), "speed": list(rs.speeds)}
    judged_text = ("judged at the speed of the largest dissipated power of each end and load"
                   " case (the crank resonance the damper works at)")
    out = {
        R_TEMP.name: Quantity(R_TEMP, temp, coords, missing=dict(missing), detail=detail),
        R_TUNING.name: Quantity(
            R_TUNING, tuning, coords,
            _limit(engine, "", "the project (needed to judge the tuning ratio)",
                   ("tuning_ratio_min", "tuning_ratio_max")), dict(missing), detail=detail,
            applies=judged, applies_text=judged_text),
        R_SHEAR.name: Quantity(R_SHEAR, tau, coords,
                               _limit(engine, "shear_stress_limit", "the damper supplier"),
                               dict(missing), detail=detail),
        R_HEAT.name: Quantity(R_HEAT, power / volume, coords,
                              _limit(engine, "heat_limit", "the damper supplier"),
                              dict(missing), detail=detail),
        R_NOSE.name: Quantity(R_NOSE, nose, coords, missing=dict(missing), detail=detail),
    }
    return out


@calculation("viscous_damper", "damper", provides=VISCOUS_PROVIDES,
             needs=("tv.nose_amplitude", "loads.cycle"),
             reads=("damper", "tv_model", "cylinders", "params"),
             applies=dinp.is_viscous, applies_why=dinp.why_not_viscous)
def viscous_damper(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """The untuned viscous damper at the cold and hot ends: heat, silicone temperature and
    damping against Den Hartog's optimum."""
    what = "the viscous damper's silicone temperature"
    problems: list[str] = []
    for f in (lambda: dinp.temperature_range(engine, what),
              lambda: dinp.heat_resistance(engine, what), lambda: dinp.viscous_coupling(engine)):
        try:
            f()
        except MissingInputs as exc:
            problems += exc.reasons
    if problems:
        raise MissingInputs(problems)
    t_air = dinp.temperature_range(engine, what)
    res_th = dinp.heat_resistance(engine, what)
    cp = dinp.viscous_coupling(engine)
    rs = _Resolver(inputs["tv.nose_amplitude"])
    j_ring = float(rs.model.inertia[rs.ring])
    mu = j_ring / rs.primary.equivalent_inertia
    g_opt, _, peak = (float(x) for x in vd.untuned_optimum(mu))
    c_opt = 2.0 * g_opt * j_ring * rs.primary.omega

    def z_at(temp: np.ndarray) -> np.ndarray:
        return cp.impedance(rs.omega, cp.damping_at(temp)[:, None])

    E, P = len(ENDS), rs.C * rs.S
    temp = np.full((E, P), np.nan)
    power = np.full((E, P), np.nan)
    nose = np.full((E, P), np.nan)
    damping = np.full((E, P), np.nan)
    missing: dict[tuple, list[str]] = {}
    for e, ta in enumerate(t_air):
        t, _ = dtemp.self_heated_temperature(lambda x: rs.power(z_at(x)), np.full(P, ta),
                                             res_th, ta + VISCOUS_SEARCH)
        ok = np.isfinite(t)
        if not ok.all():
            missing[(e,)] = [f"Damper: at the {ENDS[e]} end the silicone's heat balance has"
                             f" no solution within {VISCOUS_SEARCH:.0f} K of the air"
                             " temperature at some speeds (thermal runaway)"]
        tt = np.where(ok, t, ta)
        z = z_at(tt)
        r, dphi = rs.solve(z)
        temp[e] = t
        power[e] = np.where(ok, vd.impedance_power(dphi, rs.omega, z).sum(-1), np.nan)
        nose[e] = np.where(ok, tv.half_peak_to_peak(rs.orders, r.theta[:, rs.nose]), np.nan)
        damping[e] = np.where(ok, cp.damping_at(tt), np.nan)
    sh = lambda x: x.reshape(E, rs.C, rs.S)  # noqa: E731
    temp, power, nose, damping = map(sh, (temp, power, nose, damping))
    judged = _judged_at_peak_power(power, _envelope(inputs))
    law = ("the silicone's viscosity at its temperature (Andrade, from the datasheet's VTC)"
           if cp.slope is not None else
           "a damping coefficient independent of temperature (typed, or no viscosity"
           " temperature coefficient given)")
    detail = DamperEndsDetail(
        damper_type="viscous", ends=ENDS, air_temperature=tuple(t_air), heat_resistance=res_th,
        speeds=rs.speeds, cases=rs.cases, temperature=temp, power=power, nose_amplitude=nose,
        nominal_nose_amplitude=rs.nominal_nose, judged=judged, crank_mode_omega=rs.primary.omega,
        modal_inertia=rs.primary.equivalent_inertia, ring_inertia=j_ring,
        ring=engine.tv_model[rs.ring].station, damping=damping, damping_optimum=c_opt,
        damping_nominal=cp.damping, mass_ratio=mu, peak_magnification=peak,
        wetted_area=cp.wetted_area, coupling=cp.source, shear_stiffness=cp.shear_stiffness,
        assumptions=(
            "Viscous damper: the silicone's temperature at each speed and load case from the"
            " housing's heat balance T = T_air + P/(h A) (steady state, one temperature for"
            f" the whole fluid); the coupling from {law}"
            + (", with the fluid's shear stiffness in series (Maxwell)"
               if cp.shear_stiffness is not None else ", Newtonian")
            + "; the TV response of module torsion uses the silicone at its reference"
            " temperature (or the typed coefficient); Den Hartog's optimum for an undamped"
            " crank mode, compared at the speed of the largest dissipated power.",
            "Damper type viscous: the rubber damper's rules (DMP-001..007) do not apply.",)
        + dinp.heat_path_assumption(engine, res_th))
    coords = {"end": list(ENDS), "case": list(rs.cases), "speed": list(rs.speeds)}
    flux_missing = dict(missing)
    if cp.wetted_area is None:
        why = [engine.describe_missing("Damper", a, what="the viscous damper (its wetted area)")
               for a in ("ring_inner_radius", "ring_outer_radius", "ring_width", "gap_radial",
                         "gap_axial") if engine.damper.get(a) is None]
        flux = np.full(temp.shape, np.nan)
        flux_missing = {(e,): why for e in range(E)}
    else:
        flux = power / cp.wetted_area
    judged_text = ("judged at the speed of the largest dissipated power of each end and load"
                   " case (the crank resonance the damper works at)")
    return {
        V_TEMP.name: Quantity(V_TEMP, temp, coords,
                              _limit(engine, "silicone_temperature_limit", "the silicone"
                                     " fluid's supplier"), dict(missing), detail=detail),
        V_FLUX.name: Quantity(V_FLUX, flux, coords,
                              _limit(engine, "heat_flux_limit", "the damper supplier"),
                              flux_missing, detail=detail),
        V_OPT.name: Quantity(V_OPT, damping / c_opt, coords,
                             _limit(engine, "", "the project (needed to judge the damping)",
                                    ("damping_ratio_min", "damping_ratio_max")),
                             dict(missing), detail=detail, applies=judged,
                             applies_text=judged_text),
        V_POWER.name: Quantity(V_POWER, power, coords, missing=dict(missing), detail=detail),
        V_NOSE.name: Quantity(V_NOSE, nose, coords, missing=dict(missing), detail=detail),
        V_COPT.name: Quantity(V_COPT, np.array([c_opt]),
                              {"item": [engine.tv_model[rs.ring].station]}, detail=detail),
    }
