"""Report section: bearing oil flow, friction power, effective film temperature and peak film
pressure."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..api import CheckResult
from .plots import figure, later, legend_below, literal, to_image
from .section_loads import (
    CURVE_COLORS,
    bearing_speed_figure,
    main_load_scheme,
    shade_caption,
    worst_table,
)
from .sections import fmt, in_unit, merge_items, rpm, section

FEED_WORDS = {"full": "full groove", "partial": "partial groove", "hole": "feed hole(s)",
              "none": "none given"}


def _feed_text(kind: str) -> str:
    return " + ".join(FEED_WORDS.get(k, k) for k in kind.split("+"))


def _widths(table: dict, widths: list[int]) -> dict:
    """A table block with column widths [%] (the 'judged by' texts get room for one line)."""
    return {**table, "widths": widths}


def _lpm(v):
    """A flow [m^3/s] in l/min."""
    return in_unit(v, "m**3/s", "l/min")


def _celsius(q):
    """The same quantity in °C for plotting (display unit of the report)."""
    return replace(q, values=in_unit(q.values, "K", "°C"))


@section("bearing_performance", label="bearing flow, friction and temperature")
def bearing_performance_section(res: CheckResult) -> dict:
    qs = res.outcome.quantities
    title = "Bearing oil flow, friction and temperature"
    t = qs.get("bearing.film_temperature")
    pp = qs.get("bearing.peak_film_pressure")
    if t is None and pp is None:
        why = "; ".join(res.outcome.unavailable.get("bearing.film_temperature",
                                                    ["not computed"]))
        return {"id": "bearing_performance", "title": title, "intro": f"Not computed: {why}.",
                "blocks": []}
    eng = res.engine
    bearings = {b.name: b for b in eng.bearings}
    blocks: list[dict] = []
    ref = t if t is not None else pp
    names = ref.coords["item"]
    if t is not None:
        ex = t.detail
        oil = eng.oil
        blocks.append({"type": "table", "caption": "Oil supply and heat balance (sheet Oil)",
                       "columns": ["parameter", "value", "unit", "cell"], "rows": [
            ["Oil supply pressure", fmt(None if ex.p_supply is None else
                                        in_unit(ex.p_supply, "Pa", "bar")), "bar(g)",
             eng.cell("Oil", "supply_pressure")],
            ["Oil supply temperature", fmt(in_unit(ex.t_supply, "K", "°C")), "°C",
             eng.cell("Oil", "supply_temperature")],
            ["Heat fraction carried by the oil", fmt(ex.heat_to_oil), "-",
             eng.cell("Oil", "heat_to_oil")],
            ["Film temperature of the film thickness",
             oil.get("film_temperature_method") or "supply plus rise", "-",
             eng.cell("Oil", "film_temperature_method")]],
            "widths": [44, 22, 12, 22]})
        rows = []
        for n in names:
            b = bearings[n]
            rows.append([n, _feed_text(ex.feeds[n]),
                         fmt(None if b.max_film_temperature is None
                             else in_unit(b.max_film_temperature, "K", "°C")),
                         fmt(None if b.max_film_pressure is None
                             else in_unit(b.max_film_pressure, "Pa", "MPa")),
                         fmt(None if b.min_oil_flow is None else _lpm(b.min_oil_flow))])
        rows, _ = merge_items(rows, [""] * len(rows))
        blocks.append({"type": "table", "caption": "Oil feed and the supplier's limits per"
                       " bearing (sheet Bearings; '-': not given, the rule is not evaluated)",
                       "columns": ["bearing", "oil feed", "max film temperature [°C]",
                                   "max film pressure [MPa]", "min oil flow [l/min]"],
                       "rows": rows, "widths": [24, 22, 18, 18, 18]})
    blocks.append({"type": "equations", "items": [
        ("Side leakage", "Q_side = D c L |V_s/c|  (steady: U c L ε)",
         "Ocvirk, Short-bearing approximation for full journal bearings, NACA TN 2808, 1952;"
         " squeeze form after Booker 1965"),
        ("Groove feed", "Q = p_s R/(6 μ b) ∫ h³ dθ over the groove arc; full groove"
         " π p_s D c³ (1 + 1.5 ε²)/(6 μ b)",
         "Budynas and Nisbett, Shigley's Mechanical Engineering Design, 9th ed., 2011,"
         " sec. 12-10"),
        ("Hole feed", "Q = h³/(12 μ) · 2π p / ln(4b/(π a)),  p = p_s + ρω²(r_h² − R_m²)/2 for"
         " a crank-fed pin hole", "Line source in a strip (conformal mapping); rotating oil"
         " column"),
        ("Friction", "T = 2π μ R³ L Δω /(c √(1−ε²)) + (c/2) ε × F;  P = T_C Δω + F · V_s",
         "Petroff (concentric limit); Hirani, Athre and Biswas, J. Tribol. 121, 1999"),
        ("Heat balance", "T_eff = T_s + ½ f P /(ρ c_p Q),  μ = μ(T_eff) (Vogel)",
         "ISO 7902-1:2020; Budynas and Nisbett 2011, sec. 12-9; c_p: Cragoe 1929"),
        ("Peak film pressure", "max over θ, z and the cycle of the film pressure: short"
         " bearing (Ocvirk) and finite length (Reynolds equation map)",
         "Ocvirk 1952; Booker 1965; finite-length solution as in the film-thickness section"),
    ]})
    blocks.append({"type": "heading", "text": "Judged worst cases"})
    if t is not None:
        flow = qs.get("bearing.oil_flow")
        powq = qs.get("bearing.friction_power")

        peak = qs.get("bearing.friction_power_peak")

        def more_t(idx):
            if idx is None:
                return ["-", "-", "-"]
            return [fmt(_lpm(flow.values[idx])), fmt(powq.values[idx]),
                    fmt(None if peak is None else peak.values[idx])]

        blocks.append(_widths(worst_table(
            res, t, lambda v: fmt(in_unit(v, "K", "°C")), more_t,
            "Hottest film per bearing and load case (effective temperature of the heat"
            " balance): the judged worst first, then, marked, a hotter film at a point the"
            " rules do not judge",
            ["bearing", "case", "T_eff [°C]", "speed [rpm]", "oil flow [l/min]",
             "friction mean [W]", "friction peak [W]"]), [15, 9, 9, 9, 12, 11, 11, 24]))

        def more_q(idx):
            if idx is None:
                return ["-", "-"]
            return [fmt(_lpm(qs["bearing.side_flow"].values[idx])),
                    fmt(_lpm(qs["bearing.feed_flow"].values[idx]))]

        blocks.append(_widths(worst_table(
            res, flow, lambda v: fmt(_lpm(v)), more_q,
            "Smallest oil flow per bearing and load case (side leakage + pressure-fed flow,"
            " cycle mean)",
            ["bearing", "case", "oil flow [l/min]", "speed [rpm]", "side leakage [l/min]",
             "feed [l/min]"]), [15, 9, 12, 10, 14, 12, 28]))
    if pp is not None:
        ps = qs.get("bearing.peak_film_pressure_short")

        def more_p(idx):
            if idx is None:
                return ["-", "-"]
            return [fmt(None if ps is None else in_unit(ps.values[idx], "Pa", "MPa")),
                    fmt(np.degrees(pp.detail.theta_p_max[idx]))]

        blocks.append(_widths(worst_table(
            res, pp, lambda v: fmt(in_unit(v, "Pa", "MPa")), more_p,
            "Highest oil-film pressure per bearing and load case: finite-length film (judged),"
            " the short-bearing value at the same point beside it",
            ["bearing", "case", "p_max finite [MPa]", "speed [rpm]", "p_max short [MPa]",
             "crank angle [°]"]), [13, 9, 12, 10, 12, 10, 34]))
    blocks.append({"type": "heading", "text": "Plots"})
    ef = qs.get("engine.bearing_friction_power")
    powq = qs.get("bearing.friction_power")
    if ef is not None and powq is not None:
        sp = rpm(np.array(ef.coords["speed"]))
        blocks.append({"type": "figure", "png": later((170, 70), _draw_friction, ef, powq, sp),
                       "data": ["engine.bearing_friction_power", "bearing.friction_power"],
                       "caption": "Friction power of the bearing oil films against speed"
                                  " (cycle means; hydrodynamic films only, no piston, valve"
                                  " train or seal friction)"})
    if t is not None:
        blocks.append({"type": "figure", "png": bearing_speed_figure(
            res, _celsius(t), 1.0, "Effective film temperature [°C]", "°C", from_zero=False),
            "caption": "Effective film temperature of the heat balance against speed."
                       + shade_caption(t), "data": [t.name]})
        flow = qs.get("bearing.oil_flow")
        blocks.append({"type": "figure", "png": bearing_speed_figure(
            res, flow, float(_lpm(1.0)), "Oil flow [l/min]", "l/min"),
            "caption": "Oil flow through each bearing (side leakage + pressure-fed flow)"
                       " against speed." + shade_caption(flow), "data": [flow.name]})
    if pp is not None:
        blocks.append({"type": "figure", "png": bearing_speed_figure(
            res, pp, 1e-6, "Peak film pressure [MPa]", "MPa"),
            "caption": "Peak oil-film pressure (finite-length film) against speed."
                       + shade_caption(pp), "data": [pp.name]})
    intro = ("Oil flow, friction power and effective film temperature of every main and big-end"
             " bearing from a heat balance iterated with the oil's viscosity law (short-bearing"
             " orbits at the balance temperature), and the peak oil-film pressure along the"
             " orbits of the film-thickness section (finite length judged, short bearing"
             f" beside it). Main bearings under {main_load_scheme(res)}.")
    if t is not None:
        ex = t.detail
        if ex.t_range is not None:
            lo, hi = in_unit(np.asarray(ex.t_range), "K", "°C")
            intro += (f" Effective film temperatures {lo:.1f}..{hi:.1f} °C (supply"
                      f" {in_unit(ex.t_supply, 'K', '°C'):.0f} °C), converged to"
                      f" {ex.change_max:.2g} K in {ex.evaluations} orbit evaluations.")
    return {"id": "bearing_performance", "title": title, "intro": intro, "blocks": blocks}


def _draw_friction(ef, powq, sp) -> bytes:
    """Bearing friction power of the engine (``ef``) and per bearing (``powq``, first load
    case) against the speeds ``sp`` [rpm]."""
    fig, axes = figure(170, 70, ncols=2, legend_rows=2)
    ax = axes[0]
    for ci, c in enumerate(ef.coords["case"]):
        ax.plot(sp, in_unit(ef.values[ci], "W", "kW"), label=f"{c} load",
                color=CURVE_COLORS[ci], ls="-" if ci == 0 else "--")
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Bearing friction power [kW]")
    ax.set_title("All main and big-end bearings")
    ax.legend(fontsize=6, loc="upper left")
    ax = axes[1]
    k = 0
    for i, n in enumerate(powq.coords["item"]):
        typ = powq.item_attrs[n]["type"]
        v = powq.values[i, 0]
        if not np.isfinite(v).all():
            continue
        ax.plot(sp, v, label=literal(n), color=CURVE_COLORS[k % len(CURVE_COLORS)],
                ls="-" if typ == "main" else "--")
        k += 1
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Friction power [W]")
    ax.set_title(f"Per bearing, {powq.coords['case'][0]} load")
    legend_below(fig, ncols=9)
    return to_image(fig)
