"""Graph calculation: minimum oil film thickness (MOFT) at every bearing by the mobility
method, at full and no load across the speed range."""

from __future__ import annotations

import numpy as np

from ..calc import orbit as ob
from ..calc import viscosity as vs
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.bearings import FilmDetail, FilmOrbit
from .loads import CASES

MODELS = {"short bearing": "closed_form", "exact short bearing": "exact_table",
          "finite length": "reynolds_map", "Butenschoen fits": "butenschoen"}
MODEL_TEXT = {
    "closed_form": "Booker's closed-form short-bearing mobility (Booker 1965; as in Bell,"
                   " Ricardo 2013:"
                   " 'short bearing assumption normally used')",
    "exact_table": "exact short-bearing mobility (numerical pi-film integral, tabulated)",
    "reynolds_map": "finite-length mobility of the Reynolds equation (Swift-Stieber"
                    " cavitation), tabulated from checker's finite-difference solution"
                    " (Booker 1965 mobility method; map as in Goenka 1984)",
    "butenschoen": "Butenschoen (1976) finite-length curve fits (rotation + squeeze"
                   " superposed)",
}
METHOD_QUANTITY = {"closed_form": "bearing.moft_short", "reynolds_map": "bearing.moft_finite"}
"""Model -> the method-tagged quantity that always uses that model."""

STEPS_PER_CYCLE = ob.DEFAULT_STEPS_PER_CYCLE
"""RK steps per 720 deg cycle (benchmarks/bench_moft.py; halving the step changes the example's
MOFT by far less than 0.5 %, tests/modules/test_bearings_module.py)."""

STEPS_PER_CYCLE_FINITE = 240
"""RK steps per cycle for the finite-length map (benchmarks/bench_finite_length.py: MOFT within
4e-4 of 1440 steps on the example I4)."""

MAX_BATCH_ORBITS = 4096
"""Largest number of orbits of one kernel call when several variants are solved together
(:func:`solve_many`; benchmarks/bench_speed.py)."""

METHODS = {"short-bearing guideline": "bearing.moft_short",
           "physical criterion": "bearing.moft_finite"}
"""MOFT limits are method-tagged (rule key ``method``): a guideline calibrated to the
short-bearing mobility method (Bell, Ricardo 2013: "Ricardo limiting values should only be
applied when using Ricardo calculation methods") is judged on the short-bearing film, a
physical criterion (film over composite roughness) on the finite-length film."""
COMPARE = (("short bearing", "bearing.moft_short"), ("finite length", "bearing.moft_finite"))
"""Every MOFT result carries both values at its judged point."""

MOFT = quantity(QuantitySpec(
    "bearing.moft", "m", ("item", "case", "speed"),
    "Minimum oil film thickness over the cycle (periodic journal orbit), by the mobility model"
    " chosen in the workbook (Oil sheet 'Mobility model'; default short bearing)", "um",
    ("type", "lining"), coords={"case": CASES}, methods=METHODS, compare=COMPARE,
    detail=FilmDetail))
MOFT_SHORT = quantity(QuantitySpec(
    "bearing.moft_short", "m", ("item", "case", "speed"),
    "Minimum oil film thickness by the short-bearing mobility (Booker's closed form), whatever"
    " the workbook's model", "um", ("type", "lining"), coords={"case": CASES},
    methods=METHODS, compare=COMPARE, detail=FilmDetail))
MOFT_FINITE = quantity(QuantitySpec(
    "bearing.moft_finite", "m", ("item", "case", "speed"),
    "Minimum oil film thickness by the finite-length Reynolds mobility map, whatever the"
    " workbook's model", "um", ("type", "lining"), coords={"case": CASES},
    methods=METHODS, compare=COMPARE, detail=FilmDetail))
SPECS = {"bearing.moft": MOFT, "bearing.moft_short": MOFT_SHORT,
         "bearing.moft_finite": MOFT_FINITE}


def oil_fit(engine: Engine) -> tuple[vs.VogelOil, list[str]]:
    """Viscosity-temperature law of the workbook's oil and the assumptions used."""
    oil = engine.oil
    notes: list[str] = []
    if oil.get("kv40") is not None and oil.get("kv100") is not None:
        dens = oil.get("density")
        fit = vs.vogel_from_datasheet(oil["kv40"], oil["kv100"],
                                      dens if dens is not None else vs.DENSITY_15C_DEFAULT,
                                      oil.get("hths"))
    elif oil.get("grade"):
        try:
            fit = vs.vogel_from_j300(str(oil["grade"]), basis="minimum")
        except (ValueError, KeyError) as exc:
            raise MissingInputs([f"{engine.cell('Oil', 'grade')}: oil grade"
                                 f" '{oil['grade']}' is not an SAE J300 grade ({exc}); give"
                                 " KV40 and KV100"]) from None
        notes.append(f"Oil viscosity from the SAE J300 grade minimums (no datasheet): "
                     f"{fit.source}.")
    else:
        raise MissingInputs([engine.describe_missing("Oil", "grade")
                             + " (or KV40 and KV100)"])
    return fit, notes


def oil_viscosity(engine: Engine) -> tuple[float, float, list[str]]:
    """Film temperature [K], dynamic viscosity [Pa s] and the assumptions used."""
    oil = engine.oil
    notes: list[str] = []
    t_supply = oil.get("supply_temperature")
    if t_supply is None:
        raise MissingInputs([engine.describe_missing("Oil", "supply_temperature")])
    rise = oil.get("temperature_rise")
    if rise is None:
        rise = 0.0
        notes.append("Film temperature rise not given: film at the oil supply temperature.")
    t_film = t_supply + rise
    fit, fit_notes = oil_fit(engine)
    notes += fit_notes
    mu = float(fit.viscosity(t_film))
    if bool(fit.is_extrapolated(t_film)):
        notes.append(f"Viscosity at the film temperature {t_film - 273.15:.0f} °C extrapolates"
                     " the Vogel fit beyond its anchor points.")
    return t_film, mu, notes


def heat_balance_asked(engine: Engine) -> bool:
    """The workbook asks for the film at the heat-balance temperature (Oil 'Film
    temperature' = heat balance)."""
    return engine.oil.get("film_temperature_method") == "heat balance"


def chosen_model(engine: Engine) -> str:
    """Mobility model of the workbook (Oil sheet 'Mobility model'), as a model key."""
    return MODELS[engine.oil.get("mobility_model") or "short bearing"]


def _film_needs(engine: Engine) -> tuple[str, ...]:
    return ("loads.bearing_load",) + (("bearing.film_temperature",)
                                      if heat_balance_asked(engine) else ())


def _moft_needs(engine: Engine) -> tuple[str, ...]:
    alias = METHOD_QUANTITY.get(chosen_model(engine))
    return _film_needs(engine) + ((alias,) if alias else ())


@calculation("moft", "bearings", provides=("bearing.moft",), needs=_moft_needs,
             reads=("bearings", "oil"))
def moft(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """MOFT by the workbook's model (reuses the method-tagged quantity of that model)."""
    model = chosen_model(engine)
    alias = METHOD_QUANTITY.get(model)
    if alias is not None and alias in inputs:
        q = inputs[alias]
        return {"bearing.moft": Quantity(MOFT, q.values, q.coords, q.item_attrs,
                                         dict(q.missing), q.findings, detail=q.detail)}
    return {"bearing.moft": _solve(engine, inputs, model, "bearing.moft")}


@calculation("moft_short", "bearings", provides=("bearing.moft_short",),
             needs=_film_needs, reads=("bearings", "oil"))
def moft_short(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """MOFT by the short-bearing mobility (Booker's closed form), for method-tagged limits."""
    return {"bearing.moft_short": _solve(engine, inputs, "closed_form", "bearing.moft_short")}


@calculation("moft_finite", "bearings", provides=("bearing.moft_finite",),
             needs=_film_needs, reads=("bearings", "oil"))
def moft_finite(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """MOFT by the finite-length Reynolds mobility map, for physical film criteria."""
    return {"bearing.moft_finite": _solve(engine, inputs, "reynolds_map",
                                          "bearing.moft_finite")}


def _solve(engine: Engine, inputs: dict, model: str, name: str) -> Quantity:
    """Periodic journal orbits of all bearings x load cases x speeds in one batch."""
    out = solve_many([(engine, inputs)], model, name)[0]
    if isinstance(out, MissingInputs):
        raise out
    return out


def solve_many(items: list[tuple[Engine, dict]], model: str,
               name: str) -> list[Quantity | MissingInputs]:
    """The film-thickness quantity ``name`` of several engines (variants) with one orbit
    kernel call per load-grid length: the orbits of all variants form one batch (each
    variant's own orbits are shared only within the variant, so every variant's numbers are
    those of its own evaluation, :func:`checker.calc.orbit.solve_orbit` ``group``). Returns,
    per item, the quantity or the :class:`MissingInputs` it raised."""
    preps: list = []
    for engine, inputs in items:
        try:
            preps.append(_prepare(engine, inputs, model))
        except MissingInputs as exc:
            preps.append(exc)
    live = [i for i, p in enumerate(preps) if not isinstance(p, MissingInputs)
            and p["sel"].size]
    by_len: dict[int, list[int]] = {}
    for i in live:
        by_len.setdefault(preps[i]["n_pts"], []).append(i)
    for idx in by_len.values():
        # kernel calls of at most MAX_BATCH_ORBITS orbits (beyond a few thousand the cost
        # per orbit no longer falls and memory grows; results do not depend on the split)
        chunk: list[int] = []
        size = 0
        for i in idx:
            m = preps[i]["arg"]["speed"].size
            if chunk and size + m > MAX_BATCH_ORBITS:
                _orbits([preps[j] for j in chunk], model)
                chunk, size = [], 0
            chunk.append(i)
            size += m
        _orbits([preps[j] for j in chunk], model)
    return [p if isinstance(p, MissingInputs) else _finish(p, model, name) for p in preps]


def _prepare(engine: Engine, inputs: dict, model: str) -> dict:
    """Inputs of one engine's orbits (rows with complete data) and what the quantity needs."""
    bl = inputs["loads.bearing_load"]
    if not bl.coords["item"]:
        raise MissingInputs(["Bearings: no bearings given (sheet Bearings)"])
    ex = bl.detail
    names = bl.coords["item"]
    ft = inputs.get("bearing.film_temperature") if heat_balance_asked(engine) else None
    if ft is None:
        t_film, mu, notes = oil_viscosity(engine)
    else:
        fit, notes = oil_fit(engine)
        t_film = ft.values
        mu = fit.viscosity(np.where(np.isfinite(t_film), t_film, engine.oil[
            "supply_temperature"]))
    bearings = {b.name: b for b in engine.bearings}
    speeds = np.array(bl.coords["speed"])
    nb, nc, ns = bl.values.shape
    ok = np.isfinite(bl.values).all(axis=(1, 2))
    missing = dict(bl.missing)
    if ft is not None:
        ok &= np.isfinite(ft.values).all(axis=(1, 2))
        for k, v in ft.missing.items():
            missing.setdefault(k[:1], []).extend(f"film temperature: {t}" for t in v)
    lo_hi = _model_l_over_d_range(model)
    if lo_hi is not None:
        lo, hi = lo_hi
        for i, n in enumerate(names):
            b = bearings[n]
            lod = (0.5 if b.groove == "full" else 1.0) * b.length / b.diameter
            if ok[i] and not lo - 1e-12 <= lod <= hi + 1e-12:
                ok[i] = False
                missing[(i,)] = [
                    f"{engine.cell('Bearings', 'length', b.row)}: land length / diameter"
                    f" {lod:.3g} outside the range {lo:.3g}..{hi:.3g} of the"
                    f" {MODEL_TEXT[model].split(' (')[0]}"]
    ok_rows = np.where(ok)[0]
    sel = ok_rows
    nsel = sel.size
    n_pts = ex.fx.shape[-1]
    shp = (nsel, nc, ns)
    arg = {}
    if nsel:
        col = (slice(None), None, None)
        arg = {
            "fy": np.broadcast_to(ex.fy[sel], shp + (n_pts,)).reshape(-1, n_pts),
            "fx": np.broadcast_to(ex.fx[sel], shp + (n_pts,)).reshape(-1, n_pts),
            "wj": np.broadcast_to(ex.omega_journal[sel], shp + (n_pts,)).reshape(-1, n_pts),
            "wb": np.broadcast_to(ex.omega_bearing[sel], shp + (n_pts,)).reshape(-1, n_pts),
            "speed": np.broadcast_to(speeds[None, None, :], shp).reshape(-1),
            "d": np.broadcast_to(np.array([bearings[names[i]].diameter for i in sel])[col],
                                 shp).reshape(-1),
            "length": np.broadcast_to(np.array([bearings[names[i]].length for i in sel])[col],
                                      shp).reshape(-1),
            "c": np.broadcast_to(np.array([bearings[names[i]].clearance for i in sel])[col],
                                 shp).reshape(-1),
            "mu": np.broadcast_to(mu if np.ndim(mu) == 0 else mu[sel], shp).reshape(-1),
            "full": np.broadcast_to(np.array([bearings[names[i]].groove == "full"
                                              for i in sel])[col], shp).reshape(-1),
        }
    return {"engine": engine, "bl": bl, "names": names, "bearings": bearings, "speeds": speeds,
            "shape": (nb, nc, ns), "sel": sel, "n_pts": n_pts, "arg": arg, "res": None,
            "missing": missing, "notes": notes, "t_film": t_film, "mu": mu}


def _orbits(preps: list[dict], model: str) -> None:
    """The orbits of the prepared engines; bearing rows solved before are reused
    (:mod:`checker.modules.film_memo`), the others solved by :func:`_orbit_kernel`."""
    from . import film_memo

    film_memo.orbits(preps, model, _orbit_kernel, tag=repr(sorted(_steps(model).items())))


def _orbit_kernel(preps: list[dict], model: str) -> None:
    """One orbit kernel call for the prepared engines (same load-grid length); the result of
    each is stored in its ``res`` (arrays over its rows x cases x speeds)."""
    # one engine: its arrays as they are (solve_orbit does not modify its inputs)
    cat = ({k: np.concatenate([p["arg"][k] for p in preps]) for k in preps[0]["arg"]}
           if len(preps) > 1 else dict(preps[0]["arg"]))
    group = np.concatenate([np.full(p["arg"]["speed"].size, g) for g, p in enumerate(preps)])
    # orbit frame: X along the loads' y axis, Y along their x axis, so that angles are
    # positive in the direction of crank rotation in both (checker.calc.crank_forces)
    res = ob.solve_orbit(cat["fy"], cat["fx"], cat["wj"], cat["wb"], cat["speed"], cat["d"],
                         cat["length"], cat["c"], cat["mu"], model=model,
                         full_groove=cat["full"], peak_pressure=model == "closed_form",
                         group=group, **_steps(model))
    start = 0
    for p in preps:
        m = p["arg"]["speed"].size
        shp = (p["sel"].size,) + p["shape"][1:]
        part = slice(start, start + m)
        start += m
        p["res"] = {
            "h_min": res.h_min[part].reshape(shp), "eps_max": res.eps_max[part].reshape(shp),
            "theta_h_min": res.theta_h_min[part].reshape(shp),
            "p_max": None if res.p_max is None else res.p_max[part].reshape(shp),
            "theta_p_max": None if res.theta_p_max is None
            else res.theta_p_max[part].reshape(shp),
            "collapse": res.collapse[part].reshape(shp),
            "converged": res.converged[part].reshape(shp),
            "n_cycles": res.n_cycles[part].reshape(shp),
            "message": res.message[part].reshape(shp), "theta": res.theta,
            "eps_x": res.eps_x[part].reshape(shp + (-1,)),
            "eps_y": res.eps_y[part].reshape(shp + (-1,)),
        }


def _finish(p: dict, model: str, name: str) -> Quantity:
    """The quantity of one prepared engine from its orbits."""
    bl, names, bearings, speeds = p["bl"], p["names"], p["bearings"], p["speeds"]
    nb, nc, ns = p["shape"]
    missing, notes, t_film, mu = p["missing"], p["notes"], p["t_film"], p["mu"]
    h = np.full((nb, nc, ns), np.nan)
    eps = np.full((nb, nc, ns), np.nan)
    th_min = np.full((nb, nc, ns), np.nan)
    p_max = np.full((nb, nc, ns), np.nan) if model == "closed_form" else None
    th_p = np.full((nb, nc, ns), np.nan) if model == "closed_form" else None
    findings: dict[tuple, list[str]] = {}
    orbit = None
    res = p["res"]
    if res is not None:
        sel = p["sel"]
        if p_max is not None:
            p_max[sel] = res["p_max"]
            th_p[sel] = res["theta_p_max"]
        h[sel] = res["h_min"]
        eps[sel] = res["eps_max"]
        th_min[sel] = res["theta_h_min"]
        collapse, converged = res["collapse"], res["converged"]
        # only the flagged points (film collapse, not periodic) are visited
        for a, ci, si in np.argwhere(collapse | ~converged):
            rpm = speeds[si] * 30 / np.pi
            if collapse[a, ci, si]:
                text = (f"film collapse at {rpm:.0f} rpm ({CASES[ci]} load): eccentricity"
                        f" {res['eps_max'][a, ci, si]:.4f}; {res['message'][a, ci, si]}")
            else:
                text = (f"orbit not periodic after {res['n_cycles'][a, ci, si]} cycles at"
                        f" {rpm:.0f} rpm ({CASES[ci]} load)")
            findings.setdefault((int(sel[a]), int(ci), int(si)), []).append(text)
        orbit = FilmOrbit(rows=sel, theta=res["theta"], eps_x=res["eps_x"],
                          eps_y=res["eps_y"], converged=converged, collapse=collapse,
                          n_cycles=res["n_cycles"])
    assumptions = [
        f"MOFT by the mobility method: {MODEL_TEXT[model]}; rigid journal and housing,"
        " statically determinate loads, mean cold radial clearance (Bell, Ricardo 2013 concept"
        " assumptions); " + _film_text(t_film, mu),
    ] + notes
    partial = [n for n in names if bearings[n].groove == "partial"]
    if partial:
        assumptions.append(
            "Partial grooves (" + ", ".join(partial) + ") are not modelled: the bearing is"
            " treated as ungrooved with its effective length (approximation; Booker 2014"
            " notes the method applies approximately when the loaded region is symmetric)."
            " Checked with checker's finite-length Reynolds solution on Bell 2013 I4 mains"
            " (groove as an ambient-pressure strip in the upper shell): the effective-width"
            " film is 25 % thinner than the grooved one where the thinnest film lies in the"
            " plain shell (full load, 1000 rpm) but 48 % thicker where it lies under the"
            " groove (no load, 7000 rpm).")
    holes = [n for n in names if (bearings[n].oil_holes or 0) > 0]
    if holes:
        assumptions.append("Journal oil holes (" + ", ".join(holes) + ") are recorded but"
                           " their effect on the film is not modelled (no documented method"
                           " in the mobility method used).")
    if model in ("closed_form", "exact_table"):
        ld = ", ".join(f"{n} {bearings[n].length / bearings[n].diameter:.2f}" for n in names)
        assumptions.append("Short-bearing theory is optimistic at engine L/D (reference notes"
                           f" 1.5: +28 % h_min at L/D 1/3, eps 0.9); L/D: {ld}.")
    detail = FilmDetail(
        model=model, model_text=MODEL_TEXT[model], eps_max=eps, theta_h_min=th_min,
        viscosity=mu, film_temperature=t_film, p_max=p_max, theta_p_max=th_p, orbit=orbit,
        l_over_d={n: bearings[n].length / bearings[n].diameter for n in names},
        assumptions=tuple(assumptions))
    return Quantity(SPECS[name], h, bl.coords, bl.item_attrs, missing, findings,
                    detail=detail)


def _film_text(t_film, mu) -> str:
    if np.ndim(t_film) == 0:
        return (f"isoviscous film at {float(t_film) - 273.15:.0f} °C, viscosity"
                f" {float(mu) * 1e3:.2f} mPa s.")
    t = np.asarray(t_film)[np.isfinite(t_film)] - 273.15
    m = np.asarray(mu)[np.isfinite(t_film)] * 1e3
    if not t.size:
        return "film temperature of the heat balance (not available)."
    return (f"isoviscous film at the effective temperature of each bearing's heat balance"
            f" ({t.min():.0f}..{t.max():.0f} °C, viscosity {m.min():.2f}..{m.max():.2f}"
            " mPa s; Oil 'Film temperature' = heat balance).")


def _steps(model: str) -> dict:
    if model == "reynolds_map":
        return {"steps_per_cycle": STEPS_PER_CYCLE_FINITE}
    return {"steps_per_cycle": STEPS_PER_CYCLE}


def _model_l_over_d_range(model: str) -> tuple[float, float] | None:
    if model in ("reynolds_map", "reynolds"):
        from ..calc import reynolds_map as rm

        return rm.MAP_L_OVER_D[0], rm.MAP_L_OVER_D[-1]
    if model == "butenschoen":
        from ..calc import mobility as mb

        return mb.BUTENSCHOEN_B_OVER_D_RANGE
    return None
