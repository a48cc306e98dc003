"""Graph calculation: minimum oil film thickness (MOFT) at every bearing by the mobility
method, at full and no load across the speed range."""

from __future__ import annotations

import numpy as np

from ..calc import orbit as ob
from ..calc import viscosity as vs
from ..engine import Engine
from ..graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity, register_module
from .loads import CASES

register_module("bearings", "Bearing oil film (MOFT)")

MODELS = {"short bearing": "closed_form", "exact short bearing": "exact_table",
          "finite length": "butenschoen"}
MODEL_TEXT = {
    "closed_form": "Booker's closed-form short-bearing mobility (Booker 1965; as in Bell,"
                   " Ricardo 2013:"
                   " 'short bearing assumption normally used')",
    "exact_table": "exact short-bearing mobility (numerical pi-film integral, tabulated)",
    "butenschoen": "Butenschoen (1976) finite-length curve fits (rotation + squeeze"
                   " superposed)",
}

STEPS_PER_CYCLE = ob.DEFAULT_STEPS_PER_CYCLE
"""RK steps per 720 deg cycle (benchmarks/bench_moft.py; halving the step changes the example's
MOFT by far less than 0.5 %, tests/modules/test_moft_module.py)."""

MOFT = quantity(QuantitySpec(
    "bearing.moft", "m", ("item", "case", "speed"),
    "Minimum oil film thickness over the cycle (periodic journal orbit)", "um",
    ("type", "lining"), coords={"case": CASES}))


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
    mu = float(fit.viscosity(t_film))
    if bool(fit.is_extrapolated(t_film)):
        notes.append(f"Viscosity at the film temperature {t_film - 273.15:.0f} °C extrapolates"
                     " the Vogel fit beyond its anchor points.")
    return t_film, mu, notes


@calculation("moft", "bearings", provides=("bearing.moft",), needs=("loads.bearing_load",),
             reads=("bearings", "oil"))
def moft(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Periodic journal orbits of all bearings x load cases x speeds in one batch."""
    bl = inputs["loads.bearing_load"]
    if not bl.coords["item"]:
        raise MissingInputs(["Bearings: no bearings given (sheet Bearings)"])
    ex = bl.extra
    t_film, mu, notes = oil_viscosity(engine)
    choice = engine.oil.get("mobility_model") or "short bearing"
    model = MODELS[choice]
    names = bl.coords["item"]
    bearings = {b.name: b for b in engine.bearings}
    speeds = np.array(bl.coords["speed"])
    nb, nc, ns = bl.values.shape
    ok_rows = np.where(np.isfinite(bl.values).all(axis=(1, 2)))[0]
    h = np.full((nb, nc, ns), np.nan)
    eps = np.full((nb, nc, ns), np.nan)
    th_min = np.full((nb, nc, ns), np.nan)
    findings: dict[tuple, list[str]] = {}
    orbit_store = {}
    if ok_rows.size:
        sel = ok_rows
        d = np.array([bearings[names[i]].diameter for i in sel])[:, None, None]
        length = np.array([bearings[names[i]].length for i in sel])[:, None, None]
        c = np.array([bearings[names[i]].clearance for i in sel])[:, None, None]
        full = np.array([bearings[names[i]].groove == "full" for i in sel])[:, None, None]
        # orbit frame: X along the loads' y axis, Y along their x axis, so that angles are
        # positive in the direction of crank rotation in both (checker.calc.crank_forces)
        res = ob.solve_orbit(
            ex["fy"][sel], ex["fx"][sel], ex["omega_journal"][sel], ex["omega_bearing"][sel],
            speeds[None, None, :], np.broadcast_to(d, (sel.size, nc, ns)),
            np.broadcast_to(length, (sel.size, nc, ns)), np.broadcast_to(c, (sel.size, nc, ns)),
            mu, model=model, full_groove=np.broadcast_to(full, (sel.size, nc, ns)),
            steps_per_cycle=STEPS_PER_CYCLE)
        h[sel] = res.h_min
        eps[sel] = res.eps_max
        th_min[sel] = res.theta_h_min
        # only the flagged points (film collapse, not periodic) are visited
        for a, ci, si in np.argwhere(res.collapse | ~res.converged):
            rpm = speeds[si] * 30 / np.pi
            if res.collapse[a, ci, si]:
                text = (f"film collapse at {rpm:.0f} rpm ({CASES[ci]} load): eccentricity"
                        f" {res.eps_max[a, ci, si]:.4f}; {res.message[a, ci, si]}")
            else:
                text = (f"orbit not periodic after {res.n_cycles[a, ci, si]} cycles at"
                        f" {rpm:.0f} rpm ({CASES[ci]} load)")
            findings.setdefault((int(sel[a]), int(ci), int(si)), []).append(text)
        orbit_store = {"rows": sel, "theta": res.theta, "eps_x": res.eps_x,
                       "eps_y": res.eps_y, "converged": res.converged,
                       "collapse": res.collapse, "n_cycles": res.n_cycles}
    assumptions = [
        f"MOFT by the mobility method: {MODEL_TEXT[model]}; rigid journal and housing,"
        " statically determinate loads, mean cold radial clearance (Bell, Ricardo 2013 concept"
        " assumptions); isoviscous film at "
        f"{t_film - 273.15:.0f} °C, viscosity {mu * 1e3:.2f} mPa s.",
    ] + notes
    partial = [n for n in names if bearings[n].groove == "partial"]
    if partial:
        assumptions.append(
            "Partial grooves (" + ", ".join(partial) + ") are not modelled: the bearing is"
            " treated as ungrooved with its effective length (approximation; Booker 2014"
            " notes the method applies approximately when the loaded region is symmetric).")
    holes = [n for n in names if (bearings[n].oil_holes or 0) > 0]
    if holes:
        assumptions.append("Journal oil holes (" + ", ".join(holes) + ") are recorded but"
                           " their effect on the film is not modelled (no documented method"
                           " in the mobility method used).")
    if model != "butenschoen":
        ld = ", ".join(f"{n} {bearings[n].length / bearings[n].diameter:.2f}" for n in names)
        assumptions.append("Short-bearing theory is optimistic at engine L/D (reference notes"
                           f" 1.5: +28 % h_min at L/D 1/3, eps 0.9); L/D: {ld}.")
    extra = {"eps_max": eps, "theta_h_min": th_min, "viscosity": mu, "film_temperature": t_film,
             "model": model, "model_text": MODEL_TEXT[model], "orbit": orbit_store,
             "assumptions": assumptions,
             "l_over_d": {n: bearings[n].length / bearings[n].diameter for n in names}}
    return {"bearing.moft": Quantity(MOFT, h, bl.coords, bl.item_attrs, dict(bl.missing),
                                     findings, extra)}
