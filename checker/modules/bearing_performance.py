"""Graph calculations: bearing oil flow, friction power, effective film temperature (heat
balance) and peak oil-film pressure, from the journal orbits of the mobility method."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..calc import bearing_performance as bp
from ..calc import film_pressure as fp
from ..calc import orbit as ob
from ..calc import viscosity as vs
from ..description.engine import Bearing, Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.bearings import FilmPressureDetail, HeatBalanceDetail
from . import heat_memo
from .bearings import oil_fit
from .loads import CASES

_F = ("type", "lining")
FILM_TEMPERATURE = quantity(QuantitySpec(
    "bearing.film_temperature", "K", ("item", "case", "speed"),
    "Effective oil-film temperature of the heat balance (friction power carried away by the"
    " bearing's oil flow; mean of inlet and outlet, ISO 7902-1)", "°C", _F,
    coords={"case": CASES}, detail=HeatBalanceDetail))
FRICTION_POWER = quantity(QuantitySpec(
    "bearing.friction_power", "W", ("item", "case", "speed"),
    "Friction power of the oil film, cycle mean (Couette shear over the full film + squeeze"
    " term), at the effective film temperature", "W", _F, coords={"case": CASES},
    detail=HeatBalanceDetail))
FRICTION_POWER_PEAK = quantity(QuantitySpec(
    "bearing.friction_power_peak", "W", ("item", "case", "speed"),
    "Friction power of the oil film, largest value over the cycle", "W", _F,
    coords={"case": CASES}, detail=HeatBalanceDetail))
FRICTION_TORQUE = quantity(QuantitySpec(
    "bearing.friction_torque", "N*m", ("item", "case", "speed"),
    "Friction torque of the oil film resisting the journal's rotation relative to the shell,"
    " cycle mean", "N m", _F, coords={"case": CASES},
    detail=HeatBalanceDetail))
FRICTION_TORQUE_PEAK = quantity(QuantitySpec(
    "bearing.friction_torque_peak", "N*m", ("item", "case", "speed"),
    "Friction torque of the oil film resisting the journal's rotation, largest value over the"
    " cycle", "N m", _F, coords={"case": CASES},
    detail=HeatBalanceDetail))
SIDE_FLOW = quantity(QuantitySpec(
    "bearing.side_flow", "m**3/s", ("item", "case", "speed"),
    "Hydrodynamic side leakage of the short-bearing film, cycle mean", "l/min", _F,
    coords={"case": CASES}, detail=HeatBalanceDetail))
FEED_FLOW = quantity(QuantitySpec(
    "bearing.feed_flow", "m**3/s", ("item", "case", "speed"),
    "Pressure-driven flow from the oil feed (groove or holes) at the supply pressure, cycle"
    " mean", "l/min", _F, coords={"case": CASES},
    detail=HeatBalanceDetail))
OIL_FLOW = quantity(QuantitySpec(
    "bearing.oil_flow", "m**3/s", ("item", "case", "speed"),
    "Oil flow through the bearing: side leakage + pressure-fed flow, cycle mean", "l/min", _F,
    coords={"case": CASES}, detail=HeatBalanceDetail))
ENGINE_FRICTION = quantity(QuantitySpec(
    "engine.bearing_friction_power", "W", ("case", "speed"),
    "Friction power of all main and big-end bearings (hydrodynamic films only)", "W",
    coords={"case": CASES}, detail=HeatBalanceDetail))
PRESSURE_COMPARE = (("finite length", "bearing.peak_film_pressure"),
                    ("short bearing", "bearing.peak_film_pressure_short"))
PEAK_PRESSURE = quantity(QuantitySpec(
    "bearing.peak_film_pressure", "Pa", ("item", "case", "speed"),
    "Peak oil-film pressure over the cycle, finite-length film (Reynolds equation, along the"
    " finite-length orbit of the film-thickness calculation)", "MPa", _F,
    coords={"case": CASES}, compare=PRESSURE_COMPARE, detail=FilmPressureDetail))
PEAK_PRESSURE_SHORT = quantity(QuantitySpec(
    "bearing.peak_film_pressure_short", "Pa", ("item", "case", "speed"),
    "Peak oil-film pressure over the cycle, short-bearing (Ocvirk) pressure field along the"
    " short-bearing orbit", "MPa", _F, coords={"case": CASES}, compare=PRESSURE_COMPARE,
    detail=FilmPressureDetail))

HEAT_BALANCE_TOL = 0.1
"""[K] Convergence tolerance of the film temperature (benchmarks/bench_bearing_performance.py:
two or three orbit evaluations on the examples)."""
HEAT_BALANCE_MAX_EVALUATIONS = 8
STEPS_PER_CYCLE = ob.DEFAULT_STEPS_PER_CYCLE
"""RK steps per cycle of the heat-balance orbits (360, as the film thickness).
benchmarks/bench_bearing_performance.py against 720 steps, I4 / I6: 360 steps 0.04 / 0.001 K,
friction power 9e-4 / 7e-5, oil flow 6e-3 / 3e-4 (relative, worst point); 180 steps 0.35 K,
1.6e-2 and 5.8e-2 on the I4 (the side leakage follows the squeeze velocity's peaks)."""


FEED_TEXT = {
    "groove": "full circumferential groove: axial Poiseuille flow across both lands with the"
              " film's (1 + 1.5 eps^2) (Budynas and Nisbett, Shigley's Mechanical Engineering"
              " Design, 9th ed., 2011, sec. 12-10)",
    "partial": "partial groove: axial flow out of the groove arc only, h^3 integrated over the"
               " arc along the orbit (spreading beyond the groove ends neglected: a lower bound,"
               " conservative for the film temperature)",
    "hole": "feed hole: source in a strip between the two edges, Q = h^3/(12 mu) 2 pi p /"
            " ln(4b / (pi a)) (conformal solution of the feed's Reynolds equation); a journal"
            " hole sees the film averaged over a turn, (1 + 1.5 eps^2) c^3, and the"
            " centrifugal pressure of the crank drilling, rho omega^2 (r_hole^2 - R_main^2)/2",
}


def _merge_orbits(full: ob.OrbitResult, part: ob.OrbitResult,
                  active: np.ndarray) -> ob.OrbitResult:
    """``full`` with the points ``active`` (boolean, batch shape) replaced by ``part``."""
    changes = {}
    for f in dataclasses.fields(full):
        a, b = getattr(full, f.name), getattr(part, f.name)
        if isinstance(a, np.ndarray) and a.shape[:active.ndim] == active.shape:
            a = a.copy()
            a[active] = b
            changes[f.name] = a
    return dataclasses.replace(full, **changes)


def _resample(a: np.ndarray, n: int) -> np.ndarray:
    return ob._resample_periodic(np.asarray(a, dtype=float), n)


def _limit_attrs(engine: Engine, bl: Quantity, limit_attr: str | None) -> dict:
    """Item attributes of the bearing quantities with the supplier's limit of one Bearings
    column (``limit`` SI + ``limit_cell``, or ``limit_missing`` naming the cell)."""
    bearings = {b.name: b for b in engine.bearings}
    out = {}
    for n in bl.coords["item"]:
        b = bearings[n]
        a = dict(bl.item_attrs.get(n, {}))
        if limit_attr is not None:
            v = getattr(b, limit_attr)
            if v is None:
                a["limit_missing"] = [engine.describe_missing(
                    "Bearings", limit_attr, b.row, f"{n} (the shell supplier's limit)")]
            else:
                a["limit"] = (float(v),)
                a["limit_cell"] = engine.cell("Bearings", limit_attr, b.row)
        out[n] = a
    return out


def _feed(engine: Engine, b: Bearing) -> tuple[str, list[str]]:
    """Feed kind of a bearing (``full``, ``partial``, ``hole``, combinations joined by '+',
    or ``none``) and the inputs missing for it."""
    kinds, missing = [], []
    if b.groove == "full":
        kinds.append("full")
    elif b.groove == "partial":
        kinds.append("partial")
        for f in ("groove_start", "groove_end"):
            if getattr(b, f) is None:
                missing.append(engine.describe_missing("Bearings", f, b.row,
                                                       f"partial groove arc of {b.name}"))
    if (b.oil_holes or 0) > 0:
        kinds.append("hole")
        if b.oil_hole_diameter is None:
            missing.append(engine.describe_missing("Bearings", "oil_hole_diameter", b.row,
                                                   f"feed hole of {b.name}"))
        elif b.oil_hole_diameter / b.length > bp.HOLE_RATIO_MAX:
            missing.append(
                f"{engine.cell('Bearings', 'oil_hole_diameter', b.row)}: feed hole"
                f" {b.oil_hole_diameter * 1e3:g} mm of {b.name} is outside the validity of the"
                f" hole-feed formula (hole radius / distance to the edge"
                f" {b.oil_hole_diameter / b.length:.2f} > {bp.HOLE_RATIO_MAX}): its flow is not"
                " computed")
    return "+".join(kinds) or "none", missing


@calculation("bearing_heat_balance", "bearing_performance",
             provides=("bearing.film_temperature", "bearing.friction_power",
                       "bearing.friction_power_peak", "bearing.friction_torque",
                       "bearing.friction_torque_peak",
                       "bearing.side_flow", "bearing.feed_flow", "bearing.oil_flow",
                       "engine.bearing_friction_power"),
             needs=("loads.bearing_load",), reads=("bearings", "oil", "params.stroke"),
             separate=True)  # its orbit sets beside the film calculations (both long)
def bearing_heat_balance(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Oil flow, friction and effective film temperature of every bearing by a heat balance
    iterated with the viscosity-temperature law (short-bearing orbits at each iterate).
    Bearings whose balance was solved before with the same inputs (variants moving other
    bearings) are taken from :mod:`checker.modules.heat_memo`, bit for bit."""
    bl = inputs["loads.bearing_load"]
    names = bl.coords["item"]
    if not names:
        raise MissingInputs(["Bearings: no bearings given (sheet Bearings)"])
    oil = engine.oil
    t_supply = oil.get("supply_temperature")
    if t_supply is None:
        raise MissingInputs([engine.describe_missing("Oil", "supply_temperature")])
    fit, notes = oil_fit(engine)
    bearings = {b.name: b for b in engine.bearings}
    ex = bl.detail
    speeds = np.array(bl.coords["speed"])
    nb, nc, ns = bl.values.shape
    missing: dict[tuple, list[str]] = {k: list(v) for k, v in bl.missing.items()}
    ok = np.isfinite(bl.values).all(axis=(1, 2))
    feed_missing: dict[int, list[str]] = {}
    feeds = {}
    p_supply = oil.get("supply_pressure")
    for i, n in enumerate(names):
        kind, miss = _feed(engine, bearings[n])
        if kind != "none" and p_supply is None:
            miss.append(engine.describe_missing("Oil", "supply_pressure",
                                                what=f"oil feed of {n}"))
        feeds[n] = kind
        if miss:
            feed_missing[i] = miss
    dens15 = oil.get("density") or vs.DENSITY_15C_DEFAULT
    heat_to_oil = oil.get("heat_to_oil") or 1.0
    mains = [b for b in engine.bearings if b.type == "main"]
    r_main = 0.5 * min(b.diameter for b in mains) if mains else None
    stroke = engine.params.get("stroke")

    rows = np.where(ok)[0]
    out = {k: np.full((nb, nc, ns), np.nan) for k in (
        "t", "p", "p_peak", "torque", "torque_peak", "qs", "qf")}
    findings: dict[tuple, list[str]] = {}
    info: dict = {}
    if rows.size:
        n_steps = STEPS_PER_CYCLE

        def feed_kwargs(b: Bearing) -> dict:
            """The feed of one bearing as arguments of :func:`bp.cycle_mean_feed_flow`."""
            kind = feeds[b.name].split("+")
            kw: dict = {"full_groove": "full" in kind}
            if "partial" in kind:
                kw["groove_arc"] = (b.groove_start, b.groove_end)
            if "hole" in kind:
                crank_fed = (b.oil_feed or "").strip().lower() == "crank"
                kw.update(holes=b.oil_holes or 0, hole_diameter=b.oil_hole_diameter,
                          hole_angle=None if crank_fed else b.oil_hole_angle)
                if (crank_fed and b.type == "big end" and b.oil_hole_angle is not None
                        and r_main is not None and stroke is not None):
                    r_out = bp.crank_hole_radius(0.5 * stroke, 0.5 * b.diameter,
                                                 b.oil_hole_angle)
                    rho = float(vs.oil_density(float(t_supply), dens15))
                    kw["hole_pressure_rise"] = bp.centrifugal_pressure_rise(
                        rho, speeds[None, :], r_out, r_main)
            return kw

        # feed of each fed bearing (by index into names)
        kws = {int(i): feed_kwargs(bearings[names[i]]) for i in rows
               if feeds[names[i]] != "none" and int(i) not in feed_missing}

        def solve(sub: np.ndarray) -> dict[str, np.ndarray]:
            """The heat balance of the bearing rows ``sub`` (indices into ``names``) solved
            together: per row, case and speed."""
            sel = [bearings[names[i]] for i in sub]
            shape = (sub.size, nc, ns)
            col = (slice(None), None, None)
            dia = np.array([b.diameter for b in sel])[col]
            length = np.array([b.length for b in sel])[col]
            clear = np.array([b.clearance for b in sel])[col]
            full = np.array([b.groove == "full" for b in sel])[col]
            fx_s = _resample(ex.fx[sub], n_steps)
            fy_s = _resample(ex.fy[sub], n_steps)
            wj_full = np.broadcast_to(ex.omega_journal[sub], ex.fx[sub].shape)
            wb_full = np.broadcast_to(ex.omega_bearing[sub], ex.fx[sub].shape)
            wj_s, wb_s = _resample(wj_full, n_steps), _resample(wb_full, n_steps)
            bdim = tuple(np.broadcast_to(a, shape) for a in (dia, length, clear, full))
            warm: dict = {}
            count = np.zeros(shape, dtype=np.int64)  # evaluations of each point
            fed = [(a, b, kws[int(sub[a])]) for a, b in enumerate(sel) if int(sub[a]) in kws]

            def feed_flow(eps_x, eps_y, mu):
                """Cycle-mean pressure-fed flow [m^3/s] of every selected bearing, (B, C, S)."""
                q = np.zeros(shape)
                for a, b, kw in fed:
                    q[a] = bp.cycle_mean_feed_flow(eps_x[a], eps_y[a], mu[a], p_supply,
                                                   b.diameter, b.length, b.clearance, **kw)
                return q

            def start_estimate(ts):
                """First film temperature (:func:`bp.start_temperature`), feed at eps 0."""
                mu0 = fit.viscosity(ts)
                z0 = np.zeros(shape + (1,))
                rho_cp = vs.oil_density(ts, dens15) * bp.oil_specific_heat(ts, dens15)
                return bp.start_temperature(ts, wj_s, wb_s, dia, length, clear,
                                            feed_flow(z0, z0, mu0) * mu0, rho_cp, heat_to_oil,
                                            fit.viscosity)

            load_shape = ex.fx[sub].shape

            def evaluate(t, active=None):
                """Every point (``active`` None) or only the points still iterating: their
                orbits are solved again, the others keep the orbit of their last evaluation."""
                mu = fit.viscosity(t)
                if active is None:
                    count[...] += 1
                    res = ob.solve_orbit(
                        ex.fy[sub], ex.fx[sub], ex.omega_journal[sub],
                        ex.omega_bearing[sub], speeds[None, None, :], *bdim[:3], mu,
                        model="closed_form", full_groove=bdim[3], steps_per_cycle=n_steps,
                        eps0_x=warm.get("x"),
                        eps0_y=warm.get("y"), squeeze_velocity=True)
                else:
                    count[active] += 1

                    def part_of(a):
                        return np.broadcast_to(a, load_shape)[active]

                    part = ob.solve_orbit(
                        part_of(ex.fy[sub]), part_of(ex.fx[sub]),
                        part_of(ex.omega_journal[sub]), part_of(ex.omega_bearing[sub]),
                        np.broadcast_to(speeds, shape)[active],
                        *(a[active] for a in bdim[:3]), mu[active], model="closed_form",
                        full_groove=bdim[3][active], steps_per_cycle=n_steps,
                        eps0_x=warm["x"][active], eps0_y=warm["y"][active],
                        squeeze_velocity=True)
                    res = _merge_orbits(warm["res"], part, active)
                warm["x"], warm["y"], warm["res"] = res.eps_x[..., 0], res.eps_y[..., 0], res
                mu4 = mu[..., None]
                lx, ly = fy_s, fx_s  # orbit frame: X along the loads' y axis
                vx, vy = res.vs_x, res.vs_y  # mobility.squeeze_velocity along the orbit
                torque, power = bp.film_losses(res.eps_x, res.eps_y, lx, ly, vx, vy, wj_s,
                                               wb_s, dia[..., None], length[..., None],
                                               clear[..., None], mu4)
                qs = bp.short_bearing_side_flow(vx, vy, dia[..., None], length[..., None],
                                                clear[..., None]).mean(axis=-1)
                qf = feed_flow(res.eps_x, res.eps_y, mu)
                rho_cp = vs.oil_density(t, dens15) * bp.oil_specific_heat(t, dens15)
                state = {"orbit": res, "torque": -torque.mean(axis=-1),
                         "torque_peak": (-torque).max(axis=-1), "power": power.mean(axis=-1),
                         "power_peak": power.max(axis=-1), "qs": qs, "qf": qf}
                return power.mean(axis=-1), qs, qf, rho_cp, state

            ts = np.full(shape, float(t_supply))
            hb = bp.solve_heat_balance(evaluate, ts, fit.viscosity, heat_to_oil=heat_to_oil,
                                       tol=HEAT_BALANCE_TOL,
                                       max_evaluations=HEAT_BALANCE_MAX_EVALUATIONS,
                                       t_start=start_estimate(ts), partial=True)
            st = hb.state
            res = st["orbit"]
            return {"t": hb.temperature, "converged": hb.converged, "change": hb.change,
                    "evaluations": count, "p": st["power"], "p_peak": st["power_peak"],
                    "torque": st["torque"], "torque_peak": st["torque_peak"], "qs": st["qs"],
                    "qf": st["qf"], "collapse": res.collapse, "orbit_converged": res.converged,
                    "message": res.message}

        # every input of a row's balance besides its loads (heat_memo's key)
        common = repr((HEAT_BALANCE_TOL, HEAT_BALANCE_MAX_EVALUATIONS, n_steps, fit,
                       float(t_supply), p_supply, dens15, heat_to_oil, (nc, ns),
                       speeds.tolist())).encode()
        facts, scalars = [], []
        for i in rows:
            b = bearings[names[i]]
            geo = (float(b.diameter), float(b.length), float(b.clearance), b.groove == "full")
            kw = kws.get(int(i))
            fb = [common, repr(geo).encode(), repr(kw is not None).encode()]
            for k, v in sorted((kw or {}).items()):
                if isinstance(v, np.ndarray):
                    fb.append(f"{k}|{v.dtype}|{v.shape}|".encode() + v.tobytes())
                else:
                    fb.append(f"{k}|{v!r}".encode())
            facts.append(b"\x00".join(fb))
            scalars.append(geo)
        try:
            hb = heat_memo.balance(rows, facts, np.array(scalars, dtype=float),
                                   {k: getattr(ex, k) for k in
                                    ("fx", "fy", "omega_journal", "omega_bearing")}, solve)
        except ValueError as exc:
            raise MissingInputs([f"bearing heat balance: {exc}"]) from None
        evaluations = int(hb["evaluations"].max())
        for k in ("t", "p", "p_peak", "torque", "torque_peak", "qs", "qf"):
            out[k][rows] = hb[k]
        for a, ci, si in np.argwhere(~hb["converged"]):
            rpm = speeds[si] * 30 / np.pi
            findings.setdefault((int(rows[a]), int(ci), int(si)), []).append(
                f"heat balance not converged at {rpm:.0f} rpm ({CASES[ci]} load) after"
                f" {evaluations} orbit evaluations: last change"
                f" {hb['change'][a, ci, si]:.2g} K > {HEAT_BALANCE_TOL} K")
        for a, ci, si in np.argwhere(hb["collapse"] | ~hb["orbit_converged"]):
            rpm = speeds[si] * 30 / np.pi
            findings.setdefault((int(rows[a]), int(ci), int(si)), []).append(
                f"short-bearing orbit at the film temperature: {hb['message'][a, ci, si]}"
                f" at {rpm:.0f} rpm ({CASES[ci]} load)")
        extrap = fit.is_extrapolated(hb["t"])
        info = {"evaluations": evaluations, "change_max": float(np.max(hb["change"])),
                "extrapolated": bool(np.any(extrap)),
                "t_range": (float(np.min(hb["t"])), float(np.max(hb["t"])))}
    # not converged, not periodic or collapsed: the balance cannot be trusted there
    bad_t = np.zeros((nb, nc, ns), dtype=bool)
    for (i, ci, si), texts in findings.items():
        bad_t[i, ci, si] = any("not converged" in t for t in texts)
    for i, miss in feed_missing.items():
        for k in ("t", "qf"):
            out[k][i] = np.nan
        missing.setdefault((i,), []).extend(miss)
    out["t"][bad_t] = np.nan
    for i, ci, si in np.argwhere(bad_t):
        missing.setdefault((int(i), int(ci), int(si)), []).append(
            "heat balance not converged (see findings)")
    qtot = out["qs"] + out["qf"]

    def attrs(limit_attr: str | None, _label: str = "") -> dict:
        return _limit_attrs(engine, bl, limit_attr)

    assumptions = [
        "Bearing oil flow, friction and film temperature from the short-bearing journal orbit"
        " (Booker's closed-form mobility) at the effective film temperature of each bearing,"
        " load case and speed.",
        "Friction: Couette shear of the full film over the whole circumference (the cavitated"
        " region is taken as full film: an upper bound of the shear, usual at concept level)"
        " plus the load term (c/2) eps x F; power = Couette + squeeze term F . V_s (Hirani,"
        " Athre and Biswas, 'Dynamically loaded finite length journal bearings: analytical"
        " method of solution', J. Tribol. 121, 1999, for the same split).",
        "Side leakage of the short-bearing pi-film Q = D c L |V_s/c| (Ocvirk 1952, steady"
        " U c L eps); oil flow = side leakage + pressure-fed flow (superposed; the two interact"
        " through the film boundary conditions, an approximation).",
        f"Heat balance: T_eff = T_supply + 0.5 f P / (rho c_p Q), fraction of the heat"
        f" carried by the oil f = {heat_to_oil:g}"
        + ("" if oil.get("heat_to_oil") is not None else " (ASSUMPTION: not given, all heat"
           " leaves with the oil, conservative)")
        + "; rho(T) by thermal expansion, c_p by Cragoe (1929); iterated with the Vogel"
        f" viscosity law to {HEAT_BALANCE_TOL} K (ISO 7902-1; Budynas and Nisbett 2011,"
        " sec. 12-9).",
    ] + [f"Oil feed of {', '.join(n for n in names if feeds[n] == k) or '-'}: {FEED_TEXT[t]}"
         for k, t in (("full", "groove"), ("partial", "partial"))
         if any(feeds[n] == k or k in feeds[n].split("+") for n in names)] + notes
    holes = [n for n in names if "hole" in feeds[n].split("+")]
    if holes:
        assumptions.append(f"Oil feed of {', '.join(holes)}: {FEED_TEXT['hole']}; the pressure"
                           " drop in the drillings is neglected.")
    none_fed = [n for n in names if feeds[n] == "none"]
    if none_fed:
        assumptions.append(f"No oil feed given for {', '.join(none_fed)}: only the side"
                           " leakage carries the heat (conservative).")
    if info.get("extrapolated"):
        assumptions.append("The effective film temperature lies beyond the viscosity data"
                           " (Vogel fit extrapolated).")
    detail = HeatBalanceDetail(feeds=feeds, heat_to_oil=heat_to_oil, t_supply=float(t_supply),
                               p_supply=p_supply, assumptions=tuple(assumptions), **info)
    coords = bl.coords
    miss_tq = {k: v for k, v in missing.items()}

    def q(spec, values, limit_attr=None, label=""):
        return Quantity(spec, values, coords, attrs(limit_attr, label), dict(miss_tq),
                        findings, detail=detail)

    eng = np.sum(out["p"], axis=0) if nb else np.full((nc, ns), np.nan)
    eng_missing = {}
    if nb and not np.isfinite(eng).all():
        eng_missing[()] = ["friction power of " + ", ".join(
            n for i, n in enumerate(names) if not np.isfinite(out["p"][i]).all())
            + " could not be computed"]
    return {
        "bearing.film_temperature": q(FILM_TEMPERATURE, out["t"], "max_film_temperature",
                                      "maximum film temperature"),
        "bearing.friction_power": q(FRICTION_POWER, out["p"]),
        "bearing.friction_power_peak": q(FRICTION_POWER_PEAK, out["p_peak"]),
        "bearing.friction_torque": q(FRICTION_TORQUE, out["torque"]),
        "bearing.friction_torque_peak": q(FRICTION_TORQUE_PEAK, out["torque_peak"]),
        "bearing.side_flow": q(SIDE_FLOW, out["qs"]),
        "bearing.feed_flow": q(FEED_FLOW, out["qf"]),
        "bearing.oil_flow": q(OIL_FLOW, qtot, "min_oil_flow", "minimum oil flow"),
        "engine.bearing_friction_power": Quantity(
            ENGINE_FRICTION, eng, {"case": coords["case"], "speed": coords["speed"]}, {},
            eng_missing, {}, detail=detail),
    }


@calculation("film_pressure", "bearing_performance",
             provides=("bearing.peak_film_pressure",),
             needs=("loads.bearing_load", "bearing.moft_finite"), reads=("bearings",))
def film_pressure(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Peak oil-film pressure of the finite-length film (Reynolds map) along the orbits of the
    finite-length film-thickness calculation."""
    bl = inputs["loads.bearing_load"]
    fin = inputs["bearing.moft_finite"]
    names = bl.coords["item"]
    bearings = {b.name: b for b in engine.bearings}
    nb, nc, ns = bl.values.shape
    p_fin = np.full((nb, nc, ns), np.nan)
    th_fin = np.full((nb, nc, ns), np.nan)
    orb = fin.detail.orbit
    if orb is not None:
        rows = orb.rows
        n = orb.eps_x.shape[-1]
        ex = bl.detail
        lx = _resample(ex.fy[rows], n)
        ly = _resample(ex.fx[rows], n)
        col = (slice(None), None, None, None)
        sel = [bearings[names[i]] for i in rows]
        dia = np.array([b.diameter for b in sel])[col]
        length = np.array([b.length for b in sel])[col]
        clear = np.array([b.clearance for b in sel])[col]
        full = np.array([b.groove == "full" for b in sel])[col]
        mu = np.asarray(fin.detail.viscosity, dtype=float)
        mu = mu[rows][..., None] if mu.ndim == 3 else mu
        p_fin[rows], th_fin[rows] = fp.peak_film_pressure_finite(
            lx, ly, orb.eps_x, orb.eps_y, orb.theta, dia, length, clear, mu, full)
    detail_f = FilmPressureDetail(
        theta_p_max=th_fin, film_temperature=fin.detail.film_temperature,
        model_text="finite-length Reynolds film (mobility map) along the finite-length orbit")
    return {"bearing.peak_film_pressure": Quantity(
        PEAK_PRESSURE, p_fin, bl.coords, _limit_attrs(engine, bl, "max_film_pressure"),
        dict(fin.missing), dict(fin.findings), detail=detail_f)}


@calculation("film_pressure_short", "bearing_performance",
             provides=("bearing.peak_film_pressure_short",),
             needs=("loads.bearing_load", "bearing.moft_short"), reads=("bearings",))
def film_pressure_short(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Peak oil-film pressure of the short-bearing (Ocvirk) pressure field along the orbits of
    the short-bearing film-thickness calculation (shown beside the finite-length value; a
    variant judged on margins alone does not compute it)."""
    bl = inputs["loads.bearing_load"]
    short = inputs["bearing.moft_short"]
    nb, nc, ns = bl.values.shape
    p_short = np.full((nb, nc, ns), np.nan)
    th_short = np.full((nb, nc, ns), np.nan)
    sx = short.detail
    if sx.p_max is not None:
        p_short[:] = sx.p_max
        th_short[:] = sx.theta_p_max
    detail_s = FilmPressureDetail(
        theta_p_max=th_short, film_temperature=short.detail.film_temperature,
        model_text="short-bearing (Ocvirk) pressure along the short-bearing orbit")
    return {"bearing.peak_film_pressure_short": Quantity(
        PEAK_PRESSURE_SHORT, p_short, bl.coords, _limit_attrs(engine, bl, "max_film_pressure"),
        dict(short.missing), dict(short.findings), detail=detail_s)}
