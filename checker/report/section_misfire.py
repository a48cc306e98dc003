"""Report section: the misfire case (one cylinder not firing, every cylinder in turn)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from .plots import figure, later, legend_below, to_image
from .sections import fmt, in_unit, rpm, section


@section("misfire")
def misfire_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    title = "Misfire"
    mt = q.get("misfire.element_torque")
    if mt is None:
        why = "; ".join(res.outcome.unavailable.get("misfire.element_torque",
                                                    ["not computed"]))
        return {"id": "misfire", "title": title, "intro": f"Not computed: {why}.",
                "blocks": []}
    d = mt.detail
    sp = d.speeds
    cyl = d.cylinders
    blocks: list[dict] = [{"type": "equations", "items": [
        ("Misfiring cylinder", "no injection, compression kept: p_mot = C V^-k on the"
         " compression and expansion strokes, C and k fitted to the firing trace's compression"
         " line (-110..-50 deg)", "Korean Register, Rules for Steel Ships, Pt 5 Ch 4, 102.1;"
         " Heywood 1988 sec. 9.2"),
        ("Excitation change", "dF_i,n = (c_n^mot - c_n) exp(-j n phi_i), all orders 0.5..24",
         "Ker Wilson, Practical Solution of Torsional Vibration Problems, vol. 2, ch. 19"),
        ("Response", "Theta^(i) = Theta^(0) + D(n omega)^-1 e_s(i) dF_i (superposed per"
         " misfiring cylinder, one factorisation per speed and order)",
         "Friswell et al. 2010, ch. 9 (linear steady-state forced response)"),
    ]}]
    # the worst misfire case per element: speed, cylinder, torque against normal firing
    judged = np.ones(mt.values.shape, bool) if mt.applies is None else mt.applies
    rows = []
    for e, name in enumerate(d.elements):
        if not judged[e].any():
            continue
        k = int(np.argmax(np.where(judged[e], mt.values[e], -np.inf)))
        c = int(d.worst_cylinder[e, k])
        normal = d.element_torque_normal[e, k]
        rows.append([name, f"{rpm(sp[k]):.0f}", str(cyl[c]), fmt(mt.values[e, k], 4),
                     fmt(normal, 4), fmt(mt.values[e, k] / normal if normal > 0 else np.inf,
                                         3)])
    blocks.append({"type": "table", "caption": "The misfire case per element of the torsional"
                   " model, full load within its envelope: the speed of the largest vibratory"
                   " torque with any one"
                   " cylinder misfiring, the cylinder whose misfire gives it, and normal"
                   " firing at that speed (half peak-to-peak, all orders synthesised)",
                   "columns": ["element", "speed [rpm]", "misfiring cylinder",
                               "misfire [N m]", "normal [N m]", "ratio [-]"],
                   "rows": rows, "sheet": "Misfire per element"})
    e_max = int(np.argmax(np.where(judged, mt.values, -np.inf).max(axis=1)))
    per_cyl = d.element_torque[:, e_max]  # (Z, S)
    blocks.append({"type": "figure", "png": later(
        (170, 70), _draw_elements, sp, per_cyl, d.element_torque_normal[e_max],
        d.elements[e_max], cyl), "data": ["misfire.element_torque"],
                   "caption": f"Vibratory torque of {d.elements[e_max]} (the element with the"
                              " largest misfire torque), full load: each cylinder misfiring"
                              " (thin lines), the worst case (bold) and normal firing"
                              " (dashed)"})
    if d.damper_power is not None:
        blocks.append({"type": "figure", "png": later(
            (170, 60), _draw_damper, sp, d.damper_power, d.damper_power_normal),
                       "data": ["misfire.damper_power"],
                       "caption": "Power dissipated in the TV damper, full load: the worst"
                                  " misfiring cylinder and normal firing"})
    for k_i, name in enumerate(d.couplings):
        for qn, label in (("misfire.coupling_torque_ratio", "T_W S_t S_f / T_KW"),
                          ("misfire.coupling_heat_ratio", "P_W S_t / P_KV")):
            qq = q.get(qn)
            if qq is None or not np.isfinite(qq.values[k_i]).any():
                continue
            k = int(np.nanargmax(qq.values[k_i]))
            rows = [[name, label, f"{rpm(sp[k]):.0f}", fmt(qq.values[k_i, k], 4)]]
            blocks.append({"type": "table", "caption": f"Flexible coupling under misfire"
                           f" ({label}), worst speed", "columns": [
                               "coupling", "quantity", "speed [rpm]", "value [-]"],
                           "rows": rows})
    ms = q.get("misfire.crank_stress_ratio")
    if ms is not None and ms.detail is not None and ms.values.size:
        md = ms.detail
        ok = np.ones(ms.values.shape, bool) if ms.applies is None else ms.applies
        rows = []
        for e, name in enumerate(md.sections):
            if not ok[e].any():
                continue
            k = int(np.argmax(np.where(ok[e], ms.values[e], -np.inf)))
            rows.append([name, f"{rpm(sp[k]):.0f}", fmt(md.stress[e, k] / 1e6, 4),
                         fmt(md.stress_normal[e, k] / 1e6, 4), fmt(md.limit[k] / 1e6, 4),
                         fmt(ms.values[e, k], 3)])
        blocks.append({"type": "table", "caption": "Crank vibratory shear stress under misfire"
                       " (worst cylinder, full load) against the class's transient limit (rule"
                       f" MIS-005): {md.limit_text}",
                       "columns": ["crank section", "speed [rpm]", "misfire [MPa]",
                                   "normal [MPa]", "limit [MPa]", "ratio [-]"], "rows": rows})
    peak = in_unit(d.motored_peak, "Pa", "bar")
    fire = in_unit(d.firing_peak, "Pa", "bar")
    return {"id": "misfire", "title": title,
            "intro": "The torsional response at full load with one cylinder not firing (no"
                     " injection, compression kept), every cylinder in turn; the worst case"
                     " at each speed is judged against the damper and coupling limits (rules"
                     f" MIS-). Motored peak pressure {fmt(float(np.min(peak)), 3)}.."
                     f"{fmt(float(np.max(peak)), 3)} bar against the firing peak"
                     f" {fmt(float(np.min(fire)), 3)}..{fmt(float(np.max(fire)), 3)} bar;"
                     " polytropic exponent of compression"
                     f" {fmt(float(np.min(d.motored_exponent)), 4)}. A misfire excites the"
                     " lower and half orders that cancel in normal firing.",
            "blocks": blocks}


def _draw_elements(sp, per_cyl, normal, name, cyl) -> bytes:
    """Element torque against speed for each misfiring cylinder, the worst and normal."""
    fig, ax = figure(170, 70, legend_rows=1)
    x = rpm(sp)
    for c in range(per_cyl.shape[0]):
        ax.plot(x, per_cyl[c] / 1e3, lw=0.6, color=f"C{c % 10}", label=f"cyl. {cyl[c]}")
    ax.plot(x, per_cyl.max(axis=0) / 1e3, lw=1.8, color="k", label="worst misfire")
    ax.plot(x, normal / 1e3, lw=1.2, ls="--", color="0.4", label="normal firing")
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel(f"Vibratory torque [kN m]\n{name}")
    legend_below(fig, ncols=6)
    return to_image(fig)


def _draw_damper(sp, power, normal) -> bytes:
    """Damper power against speed, worst misfire and normal firing."""
    fig, ax = figure(170, 60, legend_rows=1)
    x = rpm(sp)
    ax.plot(x, power.max(axis=0), lw=1.6, color="k", label="worst misfire")
    ax.plot(x, normal, lw=1.2, ls="--", color="0.4", label="normal firing")
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Damper power [W]")
    legend_below(fig, ncols=4)
    return to_image(fig)
