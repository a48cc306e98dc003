"""Report section: bearing oil film (MOFT by the mobility method)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from . import judged as jd
from .plots import figure, literal, to_svg
from .section_loads import bearing_speed_figure, shade_caption, worst_table
from .sections import fmt, section

RPM = 2 * np.pi / 60


@section("bearings")
def bearings_section(res: CheckResult) -> dict:
    q = res.outcome.quantities.get("bearing.moft")
    blocks: list[dict] = []
    if q is None:
        return {"id": "bearings", "title": "Bearing oil film (MOFT)", "intro": "Not computed.",
                "blocks": []}
    ex = q.extra
    eng = res.engine
    bearings = {b.name: b for b in eng.bearings}
    names = q.coords["item"]
    rows = []
    for n in names:
        b = bearings[n]
        rows.append([n, b.type, fmt(b.diameter * 1e3), fmt(b.length * 1e3),
                     fmt(b.clearance * 1e6), fmt(ex["l_over_d"][n], 3), b.groove,
                     str(b.oil_holes or 0), b.lining or "-"])
    blocks.append({"type": "table", "caption": "Bearings (sheet Bearings)",
                   "columns": ["bearing", "type", "D [mm]", "L_eff [mm]", "c [µm]", "L/D",
                               "groove", "oil holes", "lining"], "rows": rows})
    blocks.append({"type": "text", "text": f"Model: {ex['model_text']}. Film temperature"
                   f" {ex['film_temperature'] - 273.15:.0f} °C, dynamic viscosity"
                   f" {ex['viscosity'] * 1e3:.3f} mPa s."})
    blocks.append({"type": "equations", "items": [
        ("Journal motion", "dε/dt = |F| ψ² /(μ L D) · M(ε, F̂) + ω̄ ẑ × ε,  ψ = c/R",
         "Booker 1965 mobility method; bearings.md 1.2"),
        ("Mean angular velocity", "ω̄ = (ω_J + ω_B)/2: main ω/2; big end (ω − ω_rod)/2 in the"
         " con-rod frame", "bearings.md 1.1"),
        ("Short-bearing mobility", "M_ζ = (1 − ζ)^2.5 / (π (L/D)²),  M_κ = −4κ(1 − ζ)^1.5 /"
         " (π² (L/D)²)", "Booker's closed form (Flores et al. 2006); bearings.md 1.3"),
        ("MOFT", "h_min = c (1 − max ε) over the periodic cycle", "bearings.md 1.6"),
    ]})
    sp = np.array(q.coords["speed"]) / RPM
    cases = q.coords["case"]
    blocks.append({"type": "figure", "svg": bearing_speed_figure(res, q, 1e6, "MOFT [µm]", "µm"),
                   "caption": "Minimum oil film thickness against speed, full and no load."
                              + shade_caption(q)})

    def more(idx):
        if idx is None:
            return ["-", "-"]
        return [fmt(np.degrees(ex["theta_h_min"][idx]), 4), fmt(ex["eps_max"][idx], 4)]

    blocks.append(worst_table(
        res, q, lambda v: fmt(v * 1e6, 4), more,
        "Worst MOFT per bearing and load case: the judged worst first (the value of the rule"
        " result), then a thinner film at a point the rules do not judge, marked",
        ["bearing", "case", "MOFT [µm]", "speed [rpm]", "crank angle [deg]",
         "max eccentricity"]))
    orb = ex.get("orbit") or {}
    judged_worst = jd.worst(q, (), jd.direction(res, q.name, "min"))[0]
    if orb and judged_worst is not None:
        i, ci, k = judged_worst.index
        a = int(np.where(orb["rows"] == i)[0][0])
        exx, eyy = orb["eps_x"][a, ci, k], orb["eps_y"][a, ci, k]
        th = np.degrees(orb["theta"])
        fig = figure(170, 75, ncols=2)[0]
        fig.clf()
        ax0 = fig.add_subplot(1, 2, 1, aspect="equal")
        t = np.linspace(0, 2 * np.pi, 181)
        ax0.plot(np.cos(t), np.sin(t), color="0.5", lw=0.8)
        ax0.plot(exx, eyy, lw=1.0)
        ax0.set_xlim(-1.05, 1.05)
        ax0.set_ylim(-1.05, 1.05)
        ax0.set_title(literal(f"Journal orbit ε, {names[i]}, {cases[ci]} load, {sp[k]:.0f} rpm"),
                      fontsize=7)
        ax1 = fig.add_subplot(1, 2, 2)
        c_ = bearings[names[i]].clearance
        ax1.plot(th, c_ * (1 - np.hypot(exx, eyy)) * 1e6, label="film thickness h [µm]")
        bl = res.outcome.quantities.get("loads.bearing_load")
        if bl is not None:
            le = bl.extra
            f = np.hypot(le["fx"][i, ci, k], le["fy"][i, ci, k]) / 1e3
            ax2 = ax1.twinx()
            ax2.plot(np.degrees(le["theta"]), f, color="#c0392b", lw=0.8, label="|F| [kN]")
            ax2.set_ylabel("|F| [kN]", color="#c0392b")
        ax1.set_xlabel("Crank angle [deg]")
        ax1.set_ylabel("h [µm]")
        ax1.set_title("Film thickness and load over the cycle", fontsize=7)
        blocks.append({"type": "figure", "svg": to_svg(fig),
                       "caption": "Judged worst case (the thinnest film the rules judge):"
                                  " journal orbit (eccentricity ratio, in the bearing's frame)"
                                  " and film thickness with the load"})
    return {"id": "bearings", "title": "Bearing oil film (MOFT)",
            "intro": "Minimum oil film thickness at every main and big-end bearing by Booker's"
                     " mobility method (short bearing, rigid journal, statically determinate"
                     " loads, mean cold clearance: the seed's concept assumptions), at full and"
                     " no load across the speed range.", "blocks": blocks}
