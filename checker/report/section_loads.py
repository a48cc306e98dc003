"""Report section: crank-train loads (pressure traces, bearing loads, peak specific load)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from . import judged as jd
from .plots import LIMIT_STYLE, figure, literal, to_svg
from .sections import fmt, section

RPM = 2 * np.pi / 60


def _rule_limits(res: CheckResult, quantity: str, case: str) -> dict[str, float]:
    """Display limits per lining from the selected rule on ``quantity`` for ``case``."""
    for r in res.rules:
        if r.quantity == quantity and case in r.where.get("case", (case,)):
            if r.limits:
                return {k: v[0] for k, v in r.limits.items()}
            if r.limit:
                return {"*": r.limit[0]}
    return {}


def bearing_speed_figure(res: CheckResult, q, scale: float, ylabel: str, unit: str) -> str:
    """Per-bearing curves (values x ``scale``) against speed, mains / big ends x load cases,
    with the rule limit of each lining; ``q`` has dims (item, case, speed) and item attributes
    type and lining."""
    names = q.coords["item"]
    sp = np.array(q.coords["speed"]) / RPM
    judged = jd.mask(q)
    fig, axes = figure(170, 110, nrows=2, ncols=2, sharex=True)
    for ci, c in enumerate(q.coords["case"]):
        lim = _rule_limits(res, q.name, c)
        for row, typ in enumerate(("main", "big end")):
            ax = axes[row, ci]
            linings = set()
            rows = [i for i, n in enumerate(names) if q.item_attrs[n]["type"] == typ
                    and np.isfinite(q.values[i, ci]).all()]
            if rows:
                jd.shade(ax, sp, judged[rows, ci].any(axis=0))
            for i in rows:
                n = names[i]
                ax.plot(sp, q.values[i, ci] * scale, label=literal(n))
                linings.add(q.item_attrs[n]["lining"])
            for ln in sorted(x for x in linings if x):
                v = lim.get(ln, lim.get("*"))
                if v is not None:
                    ax.axhline(v, **LIMIT_STYLE)
                    ax.text(sp[0], v, literal(f" limit {ln} {v:g} {unit}"), va="bottom", fontsize=6,
                            color=LIMIT_STYLE["color"])
            ax.set_title(f"{typ} bearings, {c} load", fontsize=8)
            ax.set_ylabel(ylabel)
            ax.set_ylim(bottom=0)
            ax.legend(fontsize=6, ncols=3)
    for ax in axes[-1]:
        ax.set_xlabel("Engine speed [rpm]")
    return to_svg(fig)


def shade_caption(q) -> str:
    """Caption text for the grey ranges of :func:`bearing_speed_figure` (empty if none)."""
    return jd.shade_caption([] if jd.mask(q).all() else [jd.reason(q)])


def worst_table(res: CheckResult, q, value, extra_cols, caption: str, columns: list[str]
                ) -> dict:
    """Worst value per item and load case of an (item, case, speed) quantity: the judged worst
    first (the point the rule names), then, marked, a worse point the rules do not judge.
    ``value(v)`` formats a value; ``extra_cols(i, ci, k)`` gives the row's further cells."""
    how = jd.direction(res, q.name, "max")
    sp = np.array(q.coords["speed"]) / RPM
    rows, css = [], []
    for i, n in enumerate(q.coords["item"]):
        for ci, c in enumerate(q.coords["case"]):
            if not np.isfinite(q.values[i, ci]).all():
                rows.append([n, f"{c} load", "-", "-", *["-"] * len(extra_cols(None)),
                             "not evaluated: " + "; ".join(jd.missing_reasons(q, (i, ci)))])
                css.append("")
                continue
            for p in jd.worst(q, (i, ci), how):
                if p is None:
                    continue
                k = p.index[-1]
                rows.append([n, f"{c} load", value(p.value), f"{sp[k]:.0f}",
                             *extra_cols((i, ci, k)), jd.judged_text(res, q, p, n, c)])
                css.append(jd.row_css(p))
    return {"type": "table", "caption": caption, "columns": columns + ["judged by"],
            "rows": rows, "row_css": css}


@section("loads")
def loads_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    p = res.engine.params
    blocks: list[dict] = []
    rows = [["Bore", fmt(p["bore"] * 1e3), "mm"], ["Stroke", fmt(p["stroke"] * 1e3), "mm"],
            ["Connecting rod length", fmt(p["rod_length"] * 1e3), "mm"],
            ["Cylinder offset", fmt((p.get("cylinder_offset") or 0) * 1e3), "mm"],
            ["Pin offset", fmt((p.get("pin_offset") or 0) * 1e3), "mm"]]
    for key, label, f, u in (("piston_mass", "Piston assembly mass", 1, "kg"),
                             ("rod_mass", "Con-rod mass", 1, "kg"),
                             ("rod_com", "Rod centre of mass from big end", 1e3, "mm"),
                             ("rod_inertia", "Rod inertia about centre of mass", 1e6, "kg mm²"),
                             ("compression_ratio", "Compression ratio", 1, "-"),
                             ("main_spacing", "Main journal spacing", 1e3, "mm")):
        if p.get(key) is not None:
            rows.append([label, fmt(p[key] * f), u])
    rows.append(["Firing order", str(p.get("firing_order")), ""])
    blocks.append({"type": "table", "caption": "Inputs (sheet Engine)",
                   "columns": ["parameter", "value", "unit"], "rows": rows})
    blocks.append({"type": "equations", "items": [
        ("Gas force", "F_g = (p − p_cc)·π/4·B²", "Heywood 1988 ch. 2"),
        ("Reciprocating inertia", "F_i = −m_rec·ω²·x''(θ),  m_rec = m_piston + m_rod·l_g/l",
         "two-mass con-rod, seed 004"),
        ("Rod inertia correction", "C = (I − m_rod·l_g·(l − l_g))·α_rod",
         "restores the true rod inertia; rigid-body dynamics"),
        ("Main bearing load", "F_j = Σ_bay F·(1 − z/L) + F·z/L (lever rule)",
         "statically determinate, seed 000 slide 'bearing analysis assumptions'"),
        ("Peak specific load", "p = max_θ |F| / (D·L_eff)", "bearings.md sec. 3.1"),
    ]})
    cyc_q = q.get("loads.cycle")
    if cyc_q is not None:
        cyc = cyc_q.extra["cycle"]
        sp = cyc.speeds / RPM
        pick = [i for i, s in enumerate(sp) if abs(s % 500) < 1e-6 or i == sp.size - 1]
        # judged (case, speed) points: those the load rules judge (any bearing)
        ref = q.get("bearing.peak_specific_load")
        cs_judged = (np.ones((len(cyc.cases), sp.size), bool) if ref is None
                     or list(ref.coords["case"]) != list(cyc.cases)
                     or len(ref.coords["speed"]) != sp.size else jd.mask(ref).any(axis=0))
        rows, css = [], []
        for ci, c in enumerate(cyc.cases):
            for i in pick:
                rows.append([f"{c} load", f"{sp[i]:.0f}", fmt(cyc.pressure[ci, i].max() / 1e5, 4),
                             "synthesized" if cyc.synthesized[ci, i] else "workbook trace",
                             "yes" if cyc.extrapolated[ci, i] else "",
                             fmt(cyc.imep[ci, i] / 1e5, 4),
                             fmt(cyc.target_imep[ci, i] / 1e5, 4),
                             "yes" if cs_judged[ci, i] else "not judged: " + jd.reason(ref)])
                css.append("" if cs_judged[ci, i] else jd.NOT_JUDGED_CSS)
        blocks.append({"type": "table", "caption": "Cylinder pressure per load case (every"
                       " 500 rpm); 'judged': whether the rules judge results at this point",
                       "columns": ["case", "speed [rpm]", "peak [bar]", "trace",
                                   "extrapolated", "IMEP [bar]", "target IMEP [bar]",
                                   "judged"], "rows": rows, "row_css": css})
        fig, axes = figure(170, 70, ncols=2)
        deg = np.degrees(cyc.theta)
        for ci, (ax, c) in enumerate(zip(axes, cyc.cases)):
            for i in pick[:: max(1, len(pick) // 5)]:
                ax.plot(deg, cyc.pressure[ci, i] / 1e5, ls="-" if cs_judged[ci, i] else ":",
                        label=f"{sp[i]:.0f} rpm" + ("" if cs_judged[ci, i] else
                                                    " (not judged)"))
            ax.set_xlim(-0.5 + 0, 720)
            ax.set_xlabel("Crank angle from firing TDC [deg]")
            ax.set_ylabel("Cylinder pressure [bar]")
            ax.set_title(f"{c} load")
            ax.legend(fontsize=6)
        blocks.append({"type": "figure", "svg": to_svg(fig),
                       "caption": "Cylinder pressure traces used (own cycle angle)"
                       + ("" if cs_judged.all() else
                          f"; dotted: not judged by the rules ({jd.reason(ref)})")})
    sl = q.get("bearing.peak_specific_load")
    bl = q.get("loads.bearing_load")
    if sl is not None and bl is not None:
        names = sl.coords["item"]
        sp = np.array(sl.coords["speed"]) / RPM
        cases = sl.coords["case"]
        blocks.append({"type": "figure", "svg": bearing_speed_figure(
            res, sl, 1e-6, "Peak specific load [MPa]", "MPa"),
            "caption": "Peak specific load against speed, full and no load."
                       + shade_caption(sl)})
        th = sl.extra["theta_at_max"]

        def more(idx):
            if idx is None:
                return ["-", "-"]
            return [fmt(np.degrees(th[idx]), 4), fmt(bl.values[idx] / 1e3, 4)]

        blocks.append(worst_table(
            res, sl, lambda v: fmt(v / 1e6, 4), more,
            "Worst peak specific load per bearing and load case: the judged worst first (the"
            " value of the rule result), then a worse point the rules do not judge, marked",
            ["bearing", "case", "p [MPa]", "speed [rpm]", "crank angle [deg]", "load [kN]"]))
        ex = bl.extra
        sl_judged = jd.mask(sl)
        how = jd.direction(res, sl.name, "max")
        choose = [n for n in names if sl.item_attrs[n]["type"] == "big end"][:1] + \
                 [n for n in names if sl.item_attrs[n]["type"] == "main"][len(
                     [n for n in names if sl.item_attrs[n]["type"] == "main"]) // 2:][:1]
        speeds_pick = sorted({int(np.argmin(abs(sp - s))) for s in
                              ((res.engine.params.get("rated_speed") or sp[-1] * RPM) / RPM,
                               sp[-1])})
        if choose:
            fig, axes = figure(170, 85, ncols=len(choose),
                               subplot_kw={"projection": "polar"}, squeeze=False)
            for a, n in enumerate(choose):
                i = names.index(n)
                ax = axes[0, a]
                for ci, c in enumerate(cases):
                    for k in speeds_pick:
                        fx, fy = ex["fx"][i, ci, k], ex["fy"][i, ci, k]
                        ax.plot(np.arctan2(fx, fy), np.hypot(fx, fy) / 1e3,
                                label=f"{c} load {sp[k]:.0f} rpm"
                                + jd.point_label(sl, (i, ci, k)), lw=0.8,
                                ls="-" if sl_judged[i, ci, k] else ":")
                ax.set_theta_zero_location("N")
                ax.set_theta_direction(-1)
                ax.set_title(literal(f"{n} ({ex['frames'][n]}), kN"), fontsize=8)
                ax.legend(fontsize=5, loc="lower left", bbox_to_anchor=(-0.15, -0.25))
            shown = [sl_judged[names.index(n), ci, k] for n in choose
                     for ci in range(len(cases)) for k in speeds_pick]
            blocks.append({"type": "figure", "svg": to_svg(fig),
                           "caption": "Polar load diagrams (force of the journal on the"
                                      " bearing; 0 deg = frame y axis, angle in the direction"
                                      " of rotation)" + ("" if all(shown) else
                                                         "; dotted: computed but not judged"
                                                         f" ({jd.reason(sl)})")})
            fig, axes = figure(170, 60, ncols=len(choose), squeeze=False)
            deg = np.degrees(ex["theta"])
            for a, n in enumerate(choose):
                i = names.index(n)
                ax = axes[0, a]
                for ci, c in enumerate(cases):
                    p = jd.worst(sl, (i, ci), how)[0]
                    if p is None:
                        continue
                    k = p.index[-1]
                    ax.plot(deg, np.hypot(ex["fx"][i, ci, k], ex["fy"][i, ci, k]) / 1e3,
                            label=f"{c} load {sp[k]:.0f} rpm (judged worst)")
                ax.set_xlabel("Crank angle [deg]")
                ax.set_ylabel("|F| [kN]")
                ax.set_title(literal(n), fontsize=8)
                ax.legend(fontsize=6)
            blocks.append({"type": "figure", "svg": to_svg(fig),
                           "caption": "Bearing load against crank angle at the judged worst"
                                      " speed (the point of the rule result)"})
    return {"id": "loads", "title": "Crank-train loads and peak specific load",
            "intro": "Cylinder pressure, gas and inertia forces, big-end loads (con-rod frame)"
                     " and main bearing loads (statically determinate) at full and no load"
                     " across the speed range; peak specific load per bearing against the"
                     " lining limits.", "blocks": blocks}
