"""Report section: the flexible coupling between engine and driven machine."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..results.display import case_text
from .plots import figure, later, legend_below, limit_line, to_image
from .sections import fmt, rpm, section


@section("coupling")
def coupling_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    title = "Flexible coupling"
    tq = q.get("coupling.vibratory_torque_ratio")
    if tq is None:
        why = "; ".join(res.outcome.unavailable.get("coupling.vibratory_torque_ratio",
                                                    ["not computed"]))
        return {"id": "coupling", "title": title, "intro": f"Not computed: {why}.",
                "blocks": []}
    d = tq.detail
    st = d.state
    eng = res.engine
    temp = "-" if st.temperature is None else fmt(st.temperature - 273.15, 4)
    blocks: list[dict] = [{"type": "table", "caption": "Catalogue values (sheet Coupling) and"
                           " their state at the rubber's temperature (sheet"
                           " CouplingTemperature)",
                           "columns": ["parameter", "value", "unit", "cell"], "rows": [
        ["Nominal torque T_KN", fmt(st.nominal_torque / 1e3, 4), "kN m",
         eng.cell("Coupling", "nominal_torque")],
        ["Permissible vibratory torque T_KW", fmt(st.vibratory_torque / 1e3, 4), "kN m",
         eng.cell("Coupling", "vibratory_torque")],
        ["Permissible damping power P_KV", fmt(st.damping_power / 1e3, 4), "kW",
         eng.cell("Coupling", "damping_power")],
        ["Dynamic torsional stiffness C_Tdyn (catalogue)", fmt(st.stiffness_catalogue / 1e3, 4),
         "kN m/rad", eng.cell("Coupling", "stiffness")],
        ["Relative damping psi (catalogue)", fmt(st.relative_damping_catalogue, 4), "-",
         eng.cell("Coupling", "relative_damping")],
        ["Rubber temperature", temp, "°C", eng.cell("Coupling", "temperature")],
        ["C_Tdyn at temperature", fmt(st.stiffness / 1e3, 4), "kN m/rad", "factor"
         f" {fmt(st.stiffness_factor, 3)}"],
        ["psi at temperature", fmt(st.relative_damping, 4), "-",
         f"factor {fmt(st.damping_factor, 3)}"],
        ["Temperature factor S_t", fmt(st.temperature_factor, 3), "-", "CouplingTemperature"],
    ]}, {"type": "equations", "items": [
        ("Element", "k* = C_Tdyn(T) (1 + j psi(T)/(2 pi))", "DIN 740-2 (psi = damping work /"
         " elastic work of a cycle)"),
        ("Vibratory torque", "T_W S_t S_f <= T_KW, S_f = sqrt(f/10 Hz) above 10 Hz (at the"
         " largest order's frequency)", "DIN 740-2; KTR, 'Coupling selection according to"
         " DIN 740 part 2'"),
        ("Heat", "P_W = sum_n psi f_n T_n^2 / (2 C_Tdyn);  P_W S_t <= P_KV", "DIN 740-2"),
    ]}]
    rows = []
    for k, name in enumerate(d.elements):
        for c_i, c in enumerate(tq.coords["case"]):
            for qn, label in (("coupling.vibratory_torque_ratio", "T_W S_t S_f / T_KW"),
                              ("coupling.heat_ratio", "P_W S_t / P_KV"),
                              ("coupling.mean_torque_ratio", "T_mean / T_KN")):
                v = q[qn].values[k, c_i]
                s = int(np.argmax(v))
                rows.append([name, case_text(c), label, f"{rpm(d.speeds[s]):.0f}",
                             fmt(v[s], 4)])
    blocks.append({"type": "table", "caption": "Largest ratio to the rating per load case"
                   " (the rules CPL-001..003 judge them within each case's envelope)",
                   "columns": ["coupling", "load", "ratio", "speed [rpm]", "value [-]"],
                   "rows": rows})
    blocks.append({"type": "figure", "png": later(
        (170, 65), _draw, d.speeds, list(tq.coords["case"]), tq.values,
        q["coupling.heat_ratio"].values), "data": ["coupling.vibratory_torque_ratio",
                                                   "coupling.heat_ratio"],
                   "caption": "Left: vibratory torque over its rating; right: damping heat over"
                              " its rating (dashed: 1, the rating)"})
    return {"id": "coupling", "title": title,
            "intro": "The flexible coupling as an element of the torsional model, from the"
                     " maker's catalogue values at the rubber's temperature; its vibratory"
                     " torque, damping heat and mean torque against its ratings (DIN 740-2"
                     " conventions).",
            "blocks": blocks}


def _draw(sp, cases, torque_ratio, heat_ratio) -> bytes:
    """Ratios to the ratings against speed per load case (first coupling)."""
    fig, axes = figure(170, 65, ncols=2, legend_rows=1)
    for ax, vals, label in ((axes[0], torque_ratio, "T_W S_t S_f / T_KW [-]"),
                            (axes[1], heat_ratio, "P_W S_t / P_KV [-]")):
        for c_i, c in enumerate(cases):
            ax.plot(rpm(sp), vals[0, c_i], color=f"C{c_i}", label=case_text(c))
        limit_line(ax, 1.0, "rating")
        ax.set_xlabel("Engine speed [rpm]")
        ax.set_ylabel(label)
    legend_below(fig, ncols=4)
    return to_image(fig)
