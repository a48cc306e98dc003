"""Report section: bearing oil film (MOFT by the mobility method)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from . import judged as jd
from .film_methods import film_method_blocks
from .plots import every, figure, later, to_image
from .section_loads import (
    bearing_speed_figure,
    lining_text,
    main_load_scheme,
    shade_caption,
    worst_table,
)
from .sections import fmt, in_unit, merge_items, rpm, section


@section("bearings", label="bearing oil film")
def bearings_section(res: CheckResult) -> dict:
    qs = res.outcome.quantities
    q = qs.get("bearing.moft") or qs.get("bearing.moft_finite") or qs.get("bearing.moft_short")
    blocks: list[dict] = []
    if q is None:
        return {"id": "bearings", "title": "Bearing oil film (MOFT)", "intro": "Not computed.",
                "blocks": []}
    d = q.detail
    eng = res.engine
    bearings = {b.name: b for b in eng.bearings}
    names = q.coords["item"]
    rows = []
    for n in names:
        b = bearings[n]
        rows.append([n, b.type, fmt(in_unit(b.diameter, "m", "mm")),
                     fmt(in_unit(b.length, "m", "mm")), fmt(in_unit(b.clearance, "m", "um")),
                     fmt(d.l_over_d[n]), b.groove,
                     str(b.oil_holes or 0), lining_text(b.lining) if b.lining else "-"])
    rows, _ = merge_items(rows, [""] * len(rows))
    blocks.append({"type": "table", "caption": "Bearings (sheet Bearings; bearings with equal"
                   " data share a row)",
                   "columns": ["bearing", "type", "D [mm]", "L_eff [mm]", "c [µm]", "L/D",
                               "groove", "oil holes", "lining"], "rows": rows,
                   "widths": [22, 9, 9, 10, 8, 8, 12, 10, 12]})
    tf = in_unit(np.asarray(d.film_temperature, float), "K", "°C")
    mu = in_unit(np.asarray(d.viscosity, float), "Pa*s", "mPa*s")
    if tf.ndim == 0:
        film = (f"Film temperature {float(tf):.0f} °C, dynamic viscosity"
                f" {float(mu):.3f} mPa·s.")
    else:
        ok = np.isfinite(tf)
        film = ("Film temperature from each bearing's heat balance (section 'Bearing oil flow,"
                f" friction and temperature'): {tf[ok].min():.0f}.."
                f"{tf[ok].max():.0f} °C, dynamic viscosity"
                f" {mu[ok].min():.3f}..{mu[ok].max():.3f} mPa·s.") if ok.any() \
            else "Film temperature of the heat balance: not available."
    blocks.append({"type": "text", "text": f"Model: {d.model_text}. {film}"})
    blocks.append({"type": "equations", "items": [
        ("Journal motion", "dε/dt = |F| ψ² /(μ L D) · M(ε, F̂) + ω̄ ẑ × ε,  ψ = c/R",
         "Booker, Dynamically loaded journal bearings: mobility method of solution, J. Basic"
         " Eng. 87, 1965"),
        ("Mean angular velocity", "ω̄ = (ω_J + ω_B)/2: main ω/2; big end (ω − ω_rod)/2 in the"
         " con-rod frame", "Booker 1965"),
        ("Short-bearing mobility", "M_ζ = (1 − ζ)^2.5 / (π (L/D)²),  M_κ = −4κ(1 − ζ)^1.5 /"
         " (π² (L/D)²)", "Booker 1965 closed form, as given by Flores et al., Nonlinear"
         " Dynamics 2006"),
        ("MOFT", "h_min = c (1 − max ε) over the periodic cycle", "Booker 1965"),
    ]})
    sp = rpm(np.array(q.coords["speed"]))
    cases = q.coords["case"]

    blocks.append({"type": "heading", "text": "Judged worst cases"})
    judged_qs = [x for x in (res.outcome.quantities.get(n) for n in
                             ("bearing.moft_finite", "bearing.moft_short", "bearing.moft"))
                 if x is not None and any(
                     r.quantity == x.name and any(rr.rule == r.id for rr in res.results)
                     for r in res.rules)]
    for jq in judged_qs or [q]:
        jx = jq.detail

        def more_j(idx, jx=jx):
            if idx is None:
                return ["-", "-"]
            return [fmt(np.degrees(jx.theta_h_min[idx])), fmt(jx.eps_max[idx])]

        blocks.append(worst_table(
            res, jq, lambda v: fmt(in_unit(v, "m", "um")), more_j,
            f"Thinnest film per bearing and load case, {jx.model_text}: the judged worst"
            " first (the value of the rule result), then, marked, a thinner film at a point the"
            " rules do not judge",
            ["bearing", "case", "MOFT [µm]", "speed [rpm]", "crank angle [°]",
             "max eccentricity"]))
    blocks += film_method_blocks(res)
    blocks.append({"type": "heading", "text": "Plots"})
    blocks.append({"type": "figure", "png": bearing_speed_figure(res, q, 1e6, "MOFT [µm]", "µm"),
                   "caption": "Minimum oil film thickness against speed, full and no load."
                              + shade_caption(q), "data": [q.name]})
    orb = d.orbit
    judged_worst = jd.worst(q, (), jd.direction(res, q.name, "min"))[0]
    if orb is not None and judged_worst is not None:
        i, ci, k = judged_worst.index
        a = int(np.where(orb.rows == i)[0][0])
        exx, eyy = orb.eps_x[a, ci, k], orb.eps_y[a, ci, k]
        th = np.degrees(orb.theta)
        c_ = bearings[names[i]].clearance
        h = in_unit(c_ * (1 - np.hypot(exx, eyy)), "m", "um")
        bl = res.outcome.quantities.get("loads.bearing_load")
        cols = {"crank angle [°]": th, "eps_x [-]": exx, "eps_y [-]": eyy, "h [µm]": h}
        load = None
        if bl is not None:
            le = bl.detail
            f = in_unit(np.hypot(le.fx[i, ci, k], le.fy[i, ci, k]), "N", "kN")
            load = (np.degrees(le.theta), f)
            if len(le.theta) == th.size:
                cols["|F| [kN]"] = f
        names_ = list(cols)
        data = {"sheet": "orbit of the worst case",
                "title": f"Journal orbit and film of {names[i]}, {cases[ci]} load,"
                         f" {sp[k]:.0f} rpm", "columns": names_,
                "rows": [[float(cols[n][j]) for n in names_] for j in range(th.size)]}
        blocks.append({"type": "figure", "png": later((170, 72), _draw_orbit, exx, eyy, th, h,
                                                      load),
                       "data": [data],
                       "caption": f"Judged worst case (the thinnest film the rules judge):"
                                  f" {names[i]}, {cases[ci]} load, {sp[k]:.0f} rpm; journal"
                                  " orbit (eccentricity ratio in the bearing's frame) and film"
                                  " thickness with the load over the cycle."})
    return {"id": "bearings", "title": "Bearing oil film (MOFT)",
            "intro": "Minimum oil film thickness at every main and big-end bearing by Booker's"
                     f" mobility method (short bearing, rigid journal, {main_load_scheme(res)},"
                     " mean cold clearance: the concept-stage assumptions of Bell,"
                     " Ricardo 2013), at full and no load across the speed range.",
            "blocks": blocks}


def _draw_orbit(exx, eyy, th, h, load) -> bytes:
    """The worst case's journal orbit (eccentricity ratios ``exx``, ``eyy``) and its film
    thickness ``h`` [µm] over the crank angle ``th`` [°], with the bearing load ``load``
    ((crank angle [°], |F| [kN]) or None) on a second axis."""
    fig = figure(170, 72, ncols=2)[0]
    fig.clf()
    ax0 = fig.add_axes((0.11, 0.16, 0.28, 0.72), aspect="equal")
    t = np.linspace(0, 2 * np.pi, 181)
    ax0.plot(np.cos(t), np.sin(t), color="0.5", lw=0.8, label="clearance circle")
    ev = every(exx.size, 2)
    ax0.plot(exx[ev], eyy[ev], lw=1.0, color="#1f77b4", label="journal centre")
    ax0.set_xlim(-1.05, 1.05)
    ax0.set_ylim(-1.05, 1.05)
    ax0.set_xlabel("ε_x (eccentricity / clearance) [-]")
    ax0.set_ylabel("ε_y [-]")
    ax0.set_title("Journal orbit")
    ax1 = fig.add_axes((0.52, 0.16, 0.38, 0.72))
    ax1.plot(th[ev], h[ev], color="#1f77b4", label="film thickness h")
    ax1.set_xlim(0, 720)
    ax1.set_xticks(np.arange(0, 721, 180))
    if load is not None:
        lth, f = load
        ax2 = ax1.twinx()
        fv = every(f.size)
        ax2.plot(lth[fv], f[fv], color="#c0392b", lw=0.8)
        ax2.set_ylabel("Bearing load |F| [kN]", color="#c0392b")
        ax2.tick_params(axis="y", colors="#c0392b")
        ax2.spines["right"].set_visible(True)
        ax2.grid(False)
    ax1.set_xlabel("Crank angle [°]")
    ax1.set_ylabel("Film thickness h [µm]", color="#1f77b4")
    ax1.set_title("Film thickness (blue) and load (red) over the cycle")
    return to_image(fig)
