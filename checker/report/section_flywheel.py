"""Report section: flywheel sizing and cyclic irregularity."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..results.display import case_text
from . import judged as jd
from .plots import figure, later, legend_below, limit_line, to_image
from .sections import display_values, fmt, in_unit, rpm, section


@section("flywheel")
def flywheel_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    ci = q.get("flywheel.cyclic_irregularity")
    title = "Flywheel and cyclic irregularity"
    if ci is None:
        why = "; ".join(res.outcome.unavailable.get("flywheel.cyclic_irregularity",
                                                    ["not computed"]))
        return {"id": "flywheel", "title": title, "intro": f"Not computed: {why}.",
                "blocks": []}
    ex = ci.detail
    eng = res.engine
    sp = np.array(ci.coords["speed"])
    cases = list(ci.coords["case"])
    target = ex.target
    j_tot, j_fw = ex.inertia_total, ex.inertia_flywheel
    blocks: list[dict] = [{"type": "table", "caption": "Inputs (sheets TVModel, Engine)",
                           "columns": ["parameter", "value", "unit", "cell"], "rows": [
        ["Total rotating inertia (all stations of sheet TVModel)", fmt(j_tot, 5), "kg m²",
         "TVModel"],
        ["Flywheel station inertia (" + (", ".join(ex.flywheel_stations) or "none") + ")",
         fmt(j_fw, 5), "kg m²", "TVModel"],
        ["Target cyclic irregularity", "-" if target is None else fmt(_pct(target), 4), "%",
         eng.cell("Engine", "target_irregularity")],
        ["Lowest speed (judged)", fmt(rpm(ex.lowest_speed), 5), "rpm",
         eng.cell("Engine", "speed_min")]]}]
    blocks.append({"type": "equations", "items": [
        ("Equation of motion", "J ω dω/dθ = T(θ) − T_mean  ⇒  J/2 (ω² − ω_min²) = W(θ) − W_min",
         "Agostini 2019, Politecnico di Torino, 'Engine degree of irregularity' (shaft dynamic"
         " equilibrium)"),
        ("Fluctuation energy", "ΔE = W_max − W_min,  W(θ) = ∫ (T − T_mean) dθ", "ibid."),
        ("Cyclic irregularity", "δ = (ω_max − ω_min) / ω_avg,  ω_avg = (ω_max + ω_min)/2;"
         " classical estimate δ ≈ ΔE / (J ω²)", "ibid.; ω_min solved so that the time-mean"
         " speed is the engine speed"),
        ("Flywheel sizing", "J_min: δ(J_min) = δ_target (≈ ΔE / (δ_target ω²)); flywheel ="
         " J_min − J_rest", "ibid. ('flywheel dimensioning')"),
    ]})
    # judged worst first (equal to FLY-001), then worse points the rule does not judge
    judged_rows, other_rows, css_j, css_o = [], [], [], []
    for c_i, c in enumerate(cases):
        for p in jd.worst(ci, (c_i,), "max"):
            if p is None:
                continue
            row = ["cyclic irregularity", case_text(c), fmt(_pct(p.value), 4),
                   case_text(c), f"{rpm(sp[p.index[1]]):.0f}",
                   jd.judged_text(res, ci, p, case=c)]
            (judged_rows if p.judged else other_rows).append((p.value, row))
            (css_j if p.judged else css_o).append(jd.row_css(p))
    order = sorted(range(len(judged_rows)), key=lambda i: -judged_rows[i][0])
    blocks.append({"type": "table", "caption": "Judged worst cyclic irregularity per load case"
                   " (first row: the value FLY-001 judges); greyed rows are computed but not"
                   " judged, with the reason",
                   "columns": ["quantity", "load", "δ [%]", "case", "speed [rpm]",
                               "judged by"],
                   "rows": [judged_rows[i][1] for i in order] + [r for _, r in other_rows],
                   "row_css": [css_j[i] for i in order] + css_o})
    k0 = int(np.argmin(sp))
    jm = q.get("flywheel.minimum_inertia")
    en = q.get("flywheel.fluctuation_energy")
    dw = q.get("flywheel.speed_fluctuation")
    step = max(1, int(round(1000 / np.median(np.diff(rpm(sp)))))) if sp.size > 1 else 1
    picks = sorted(set([k0] + list(range(0, sp.size, step))))
    rows = []
    ci_pct, _ = display_values(ci)
    dw_rpm, _ = display_values(dw)
    for c_i, c in enumerate(cases):
        for k in picks:
            need = "-" if jm is None or not np.isfinite(jm.values[c_i, k]) else fmt(
                jm.values[c_i, k], 4)
            rows.append([case_text(c), f"{rpm(sp[k]):.0f}",
                         fmt(en.values[c_i, k], 4), fmt(dw_rpm[c_i, k], 4),
                         fmt(ci_pct[c_i, k], 4), fmt(_pct(ex.linear[c_i, k]), 4),
                         need])
    blocks.append({"type": "table", "caption": "Fluctuation energy, speed fluctuation, cyclic"
                   " irregularity (exact and classical estimate) and the minimum flywheel"
                   " inertia for the target (negative: the rest of the engine suffices)",
                   "columns": ["case", "speed [rpm]", "ΔE [J]", "Δω [rpm]", "δ [%]",
                               "ΔE/(Jω²) [%]", "min. flywheel [kg m²]"], "rows": rows,
                   "detail": True, "sheet": "Flywheel per speed"})
    blocks.append({"type": "figure", "png": later(
        (170, 65), _draw_irregularity, sp, cases, ci_pct, target, ex.theta, ex.omega, k0),
                   "data": ["flywheel.cyclic_irregularity"],
                   "caption": "Left: cyclic irregularity against speed (dashed: target)."
                              f" Right: speed over the cycle at {rpm(sp[k0]):.0f} rpm"})
    tgt = ("the target is not given (Engine 'Target cyclic irregularity'): FLY-001 is not"
           " evaluated" if target is None else
           f"target used: δ ≤ {_pct(target):g} % ({eng.cell('Engine', 'target_irregularity')})")
    return {"id": "flywheel", "title": title,
            "intro": "Rigid-body speed fluctuation of the engine over the cycle from its total"
                     " gas + inertia torque (load analysis) and the inertias of the torsional"
                     " model; coefficient of cyclic irregularity at every speed and load case"
                     f" and the flywheel inertia needed for the target; {tgt}.",
            "blocks": blocks}


def _pct(v):
    """A dimensionless fraction in percent."""
    return in_unit(v, "", "%")


def _draw_irregularity(sp, cases, ci_pct, target, theta, omega, k0) -> bytes:
    """Cyclic irregularity ``ci_pct`` [%] against the speeds ``sp`` [rad/s] per load case
    (dashed: ``target``), and the speed ``omega`` over the cycle ``theta`` at speed ``k0``."""
    fig, axes = figure(170, 65, ncols=2, legend_rows=1)
    ax = axes[0]
    for c_i, c in enumerate(cases):
        ax.plot(rpm(sp), ci_pct[c_i], label=case_text(c), color=f"C{c_i}")
    if target is not None:
        limit_line(ax, _pct(target), f"target δ ≤ {_pct(target):g} %")
    ax.set_yscale("log")
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Cyclic irregularity δ [%]")
    ax = axes[1]
    th = in_unit(theta, "rad", "deg")
    for c_i in range(len(cases)):
        ax.plot(th, rpm(omega[c_i, k0]), color=f"C{c_i}")
    ax.axhline(rpm(sp[k0]), color="0.5", lw=0.6, label="mean speed")
    ax.set_xlabel("Crank angle [deg]")
    ax.set_ylabel("Speed [rpm]")
    ax.set_xticks(np.arange(0, 721, 180))
    ax.set_xlim(0, 720)
    legend_below(fig, ncols=4)
    return to_image(fig)
