"""Report section: crank-train loads (pressure traces, bearing loads, peak specific load)."""

from __future__ import annotations

import re

import numpy as np

from ..api import CheckResult
from ..results.display import unit_text
from . import judged as jd
from .plots import every, figure, later, legend_below, limit_line, literal, to_image
from .sections import fmt, in_unit, merge_items, param_table, rpm, section


def _rule_limits(res: CheckResult, quantity: str, case: str) -> dict[str, float]:
    """Display limits per lining from the selected rule on ``quantity`` for ``case``."""
    for r in res.rules:
        if r.quantity == quantity and case in r.where.get("case", (case,)):
            if r.limits:
                return {k: v[0] for k, v in r.limits.items()}
            if r.limit:
                return {"*": r.limit[0]}
    return {}


def lining_text(name: str) -> str:
    """A lining material as a reader knows it: supplier grade codes (``as15``) in capitals."""
    return name.upper() if re.fullmatch(r"[a-z]{1,3}\d+", name) else name


def _identical(q, rows: list[int]) -> list[list[int]]:
    """``rows`` (item indices) grouped by identical curves over every case and speed (equal
    bearings of a symmetric engine): each group is drawn once, named by all its items."""
    groups: list[list[int]] = []
    for i in rows:
        for g in groups:
            a, b = q.values[g[0]], q.values[i]
            if a.shape == b.shape and np.allclose(a, b, rtol=1e-9, atol=0, equal_nan=True):
                g.append(i)
                break
        else:
            groups.append([i])
    return groups


def bearing_speed_figure(res: CheckResult, q, scale: float, ylabel: str, unit: str,
                         from_zero: bool = True) -> str:
    """Per-bearing curves (values x ``scale``) against speed, mains / big ends x load cases,
    with the rule limit of each lining (named in the legend below the panels); ``q`` has dims
    (item, case, speed) and item attributes type and lining. The y axis starts at 0 unless
    ``from_zero`` is false (then just below the lowest curve). Built and drawn by
    :func:`_draw_bearing_speed` through :func:`plots.later` (deferred while the sections are
    built)."""
    return later((170, 100), _draw_bearing_speed, res, q, scale, ylabel, unit, from_zero)


def _draw_bearing_speed(res: CheckResult, q, scale: float, ylabel: str, unit: str,
                        from_zero: bool):
    """The figure of :func:`bearing_speed_figure`, drawn."""
    names = q.coords["item"]
    sp = rpm(np.array(q.coords["speed"]))
    judged = jd.mask(q)
    fig, axes = figure(170, 100, nrows=2, ncols=2, sharex=True, sharey="row", wgap=8,
                       legend_rows=2)
    u = unit_text(unit)
    for ci, c in enumerate(q.coords["case"]):
        lim = _rule_limits(res, q.name, c)
        for row, typ in enumerate(("main", "big end")):
            ax = axes[row, ci]
            linings = set()
            rows = [i for i, n in enumerate(names) if q.item_attrs[n]["type"] == typ
                    and np.isfinite(q.values[i, ci]).all()]
            if rows:
                jd.shade(ax, sp, judged[rows, ci].any(axis=0))
            for k, same in enumerate(_identical(q, rows)):
                label = " = ".join(names[i] for i in same) if len(same) <= 3 else (
                    f"{names[same[0]]} .. {names[same[-1]]} ({len(same)} identical)")
                ax.plot(sp, q.values[same[0], ci] * scale, label=literal(label),
                        color=CURVE_COLORS[k % len(CURVE_COLORS)],
                        ls="-" if typ == "main" else "--")
                linings.update(q.item_attrs[names[i]]["lining"] for i in same)
            by_value: dict[float, list[str]] = {}
            for ln in sorted(x for x in linings if x):
                v = lim.get(ln, lim.get("*"))
                if v is not None:
                    by_value.setdefault(v, []).append(lining_text(ln))
            for v, lns in by_value.items():
                limit_line(ax, v, f"limit, {' and '.join(lns)} lining{'s' if len(lns) > 1 else ''}"
                           f": {v:g} {u}")
            ax.set_title(f"{typ} bearings, {c} load")
            if ci == 0:
                ax.set_ylabel(ylabel)
    for row in axes:  # shared y per row: from 0 to the highest curve or limit of the row
        top = max(max((float(np.nanmax(np.asarray(ln.get_ydata(), float)))
                       for ln in ax.get_lines() if np.isfinite(
                           np.asarray(ln.get_ydata(), float)).any()), default=1.0)
                  for ax in row)
        if from_zero:
            row[0].set_ylim(0, top * 1.08)
        else:
            low = min(min((float(np.nanmin(np.asarray(ln.get_ydata(), float)))
                           for ln in ax.get_lines() if np.isfinite(
                               np.asarray(ln.get_ydata(), float)).any()), default=0.0)
                      for ax in row)
            pad = 0.08 * max(top - low, 1e-9)
            row[0].set_ylim(low - pad, top + pad)
    for ax in axes[-1]:
        ax.set_xlabel("Engine speed [rpm]")
    legend_below(fig, ncols=7)
    return to_image(fig)


CURVE_COLORS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf",
                "#7f7f7f", "#bcbd22")
"""Curve colours (the red of limit lines is kept for limits)."""


def shade_caption(q) -> str:
    """Caption text for the grey ranges of :func:`bearing_speed_figure` (empty if none)."""
    return jd.shade_caption([] if jd.mask(q).all() else [jd.reason(q)])


def worst_table(res: CheckResult, q, value, extra_cols, caption: str, columns: list[str]
                ) -> dict:
    """Worst value per item and load case of an (item, case, speed) quantity: the judged worst
    first (the point the rule names), then, marked, a worse point the rules do not judge.
    ``value(v)`` formats a value; ``extra_cols(i, ci, k)`` gives the row's further cells.
    Items with identical rows (symmetric bearings) share one row."""
    how = jd.direction(res, q.name, "max")
    sp = rpm(np.array(q.coords["speed"]))
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
    rows, css = merge_items(rows, css)
    return {"type": "table", "caption": caption, "columns": columns + ["judged by"],
            "rows": rows, "row_css": css}


def _inputs(res: CheckResult) -> dict:
    p = res.engine.params
    def mm(v: float) -> str:
        return f"{fmt(in_unit(v, 'm', 'mm'))} mm"

    items = [("Bore", mm(p["bore"])), ("Stroke", mm(p["stroke"])),
             ("Connecting rod length", mm(p["rod_length"])),
             ("Cylinder offset", mm(p.get("cylinder_offset") or 0)),
             ("Pin offset", mm(p.get("pin_offset") or 0))]
    for key, label, si, u in (("piston_mass", "Piston assembly mass", "kg", "kg"),
                              ("rod_mass", "Con-rod mass", "kg", "kg"),
                              ("rod_com", "Rod centre of mass from big end", "m", "mm"),
                              ("rod_inertia", "Rod inertia about centre of mass", "kg*m**2",
                               "kg*mm**2"),
                              ("compression_ratio", "Compression ratio", "", ""),
                              ("main_spacing", "Main journal spacing", "m", "mm")):
        if p.get(key) is not None:
            items.append((label, f"{fmt(in_unit(p[key], si, u))} {unit_text(u)}".strip()))
    items.append(("Firing order", str(p.get("firing_order"))))
    return param_table("Inputs (sheet Engine)", items)


EQUATIONS = {"type": "equations", "items": [
    ("Gas force", "F_g = (p − p_cc)·π/4·B²",
     "Heywood, Internal Combustion Engine Fundamentals, 1988, ch. 2"),
    ("Reciprocating inertia", "F_i = −m_rec·ω²·x''(θ),  m_rec = m_piston + m_rod·l_g/l",
     "two-mass con-rod: Agostini, Powertrain Components Design, Politecnico di Torino,"
     " 2019, ch. 1"),
    ("Rod inertia correction", "C = (I − m_rod·l_g·(l − l_g))·α_rod",
     "restores the true rod inertia (rigid-body dynamics of the con-rod)"),
    ("Main bearing load", "F_j = Σ_bay F·(1 − z/L) + F·z/L (lever rule)",
     "statically determinate: Bell, Cranktrain Analysis Using ENGDYN and VALDYN, Ricardo,"
     " 2013, 'Bearing analysis assumptions'"),
    ("Peak specific load", "p = max_θ |F| / (D·L_eff)",
     "load over the projected bearing area, L_eff without grooves and chamfers (the usual"
     " convention; lining limits in the rule table)"),
]}


@section("loads", label="crank-train load")
def loads_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    blocks: list[dict] = [_inputs(res), EQUATIONS]
    cyc_q = q.get("loads.cycle")
    ref = q.get("bearing.peak_specific_load")
    cs_judged = None
    if cyc_q is not None:
        cyc = cyc_q.detail.cycle
        sp = rpm(cyc.speeds)
        # judged (case, speed) points: those the load rules judge (any bearing)
        cs_judged = (np.ones((len(cyc.cases), sp.size), bool) if ref is None
                     or list(ref.coords["case"]) != list(cyc.cases)
                     or len(ref.coords["speed"]) != sp.size else jd.mask(ref).any(axis=0))
        blocks.append(_pressure_text(cyc, sp, cs_judged, ref))
    sl = q.get("bearing.peak_specific_load")
    bl = q.get("loads.bearing_load")
    if sl is not None and bl is not None:
        th = sl.detail.theta_at_max

        def more(idx):
            if idx is None:
                return ["-", "-"]
            return [fmt(in_unit(th[idx], "rad", "deg")), fmt(in_unit(bl.values[idx], "N", "kN"))]

        blocks.append({"type": "heading", "text": "Judged worst cases"})
        blocks.append(worst_table(
            res, sl, lambda v: fmt(in_unit(v, "Pa", "MPa")), more,
            "Highest peak specific load per bearing and load case: the judged worst first (the"
            " value of the rule result), then, marked, a higher value at a point the rules do"
            " not judge",
            ["bearing", "case", "p [MPa]", "speed [rpm]", "crank angle [°]", "load [kN]"]))
        blocks.append({"type": "heading", "text": "Plots"})
        blocks.append({"type": "figure", "png": bearing_speed_figure(
            res, sl, 1e-6, "Peak specific load [MPa]", "MPa"),
            "caption": "Peak specific load against speed, full and no load." + shade_caption(sl),
            "data": [sl.name]})
    if cyc_q is not None:
        blocks.append(_pressure_figure(cyc, sp, cs_judged, ref))
    if sl is not None and bl is not None:
        blocks += _polar(res, sl, bl)
    if bl is not None and bl.detail.beam is not None:
        blocks += _support_scheme(res, bl)
    scheme = "statically determinate" if bl is None or bl.detail.beam is None else (
        f"the crank as a {bl.detail.scheme}")
    return {"id": "loads", "title": "Crank-train loads and peak specific load",
            "intro": "Cylinder pressure, gas and inertia forces, big-end loads (con-rod frame)"
                     f" and main bearing loads ({scheme}) at full and no load"
                     " across the speed range; peak specific load per bearing against the"
                     " lining limits.", "blocks": blocks}


def _pressure_text(cyc, sp, cs_judged, ref) -> dict:
    """The cylinder pressure used, in words (the per-speed values are in the workbook)."""
    parts = []
    for ci, c in enumerate(cyc.cases):
        pk = in_unit(cyc.pressure[ci].max(axis=-1), "Pa", "bar")
        kind = ("synthesized" if cyc.synthesized[ci].all() else "workbook traces"
                if not cyc.synthesized[ci].any() else "workbook traces and synthesized")
        txt = (f"{c} load: peak {fmt(pk.min())} to {fmt(pk.max())} bar over"
               f" {sp[0]:.0f} to {sp[-1]:.0f} rpm ({kind}")
        ok = np.isfinite(cyc.target_imep[ci]) & (cs_judged[ci] if cs_judged is not None
                                                 else True)
        if ok.any():
            dev = np.abs(cyc.imep[ci, ok] / cyc.target_imep[ci, ok] - 1).max() * 100
            txt += (f"; IMEP within {fmt(dev, 2)} % of the brake-torque target at the judged"
                    " speeds")
        if cyc.extrapolated[ci].any():
            ex = sp[cyc.extrapolated[ci]]
            txt += (f"; peak pressure extrapolated at {ex.size} speed{'s' if ex.size > 1 else ''}"
                    f" ({ex.min():.0f} to {ex.max():.0f} rpm)")
        parts.append(txt + ")")
    note = "" if cs_judged.all() else (f" Points not judged by the rules: {jd.reason(ref)}.")
    return {"type": "text", "text": "Cylinder pressure: " + "; ".join(parts) + "." + note
            + f" Per speed (peak, IMEP, target, trace): {ATTACHMENT}, sheet loads.cycle."}


ATTACHMENT = "results.xlsx"


def _pressure_figure(cyc, sp, cs_judged, ref) -> dict:
    deg = in_unit(cyc.theta, "rad", "deg")
    pick = sorted({0, int(np.argmin(abs(sp - 0.5 * (sp[0] + sp[-1])))), sp.size - 1})
    cols = {"crank angle [°]": deg}
    for ci, c in enumerate(cyc.cases):
        for i in pick:
            cols[f"{c} load, {sp[i]:.0f} rpm [bar]"] = in_unit(cyc.pressure[ci, i], "Pa", "bar")
    png = later((170, 62), _draw_pressure, cyc, sp, cs_judged, deg, pick)
    names = list(cols)
    data = {"sheet": "pressure traces", "title": "Cylinder pressure traces of the report's"
            " plot", "columns": names,
            "rows": [[float(cols[k][j]) for k in names] for j in range(deg.size)]}
    return {"type": "figure", "png": png, "data": ["loads.cycle", data],
            "caption": "Cylinder pressure at the lowest, middle and highest speed (own cycle"
                       " angle)" + ("" if cs_judged.all() else
                                    f"; dotted: not judged by the rules ({jd.reason(ref)})")
                       + "."}


def _draw_pressure(cyc, sp, cs_judged, deg, pick: list[int]):
    """The cylinder pressure figure of :func:`_pressure_figure` (traces at the speeds
    ``pick``, crank angle ``deg``), drawn."""
    fig, axes = figure(170, 62, ncols=len(cyc.cases), wgap=14, legend_rows=1)
    th = every(deg.size)
    for ci, (ax, c) in enumerate(zip(np.atleast_1d(axes), cyc.cases)):
        for n, i in enumerate(pick):
            lab = f"{sp[i]:.0f} rpm" + ("" if cs_judged[ci, i] else " (not judged)")
            ax.plot(deg[th], in_unit(cyc.pressure[ci, i, th], "Pa", "bar"),
                    ls="-" if cs_judged[ci, i] else ":",
                    color=CURVE_COLORS[n], label=lab)
        ax.set_xlim(0, 720)
        ax.set_xticks(np.arange(0, 721, 180))
        ax.set_xlabel("Crank angle from firing TDC [°]")
        ax.set_ylabel("Cylinder pressure [bar]")
        ax.set_title(f"{c} load")
    legend_below(fig, axes=[np.atleast_1d(axes)[0]], ncols=6)
    return to_image(fig)


def _polar(res: CheckResult, sl, bl) -> list[dict]:
    """Polar load diagrams of one big end and the centre main at the worst judged speed of
    each load case (the speed of the highest peak specific load the rules judge): closed
    traces with dots every 90° of crank angle, radial labels where the curves leave room."""
    ex = bl.detail
    names = sl.coords["item"]
    sp = rpm(np.array(sl.coords["speed"]))
    bes = [n for n in names if sl.item_attrs[n]["type"] == "big end"]
    mains = [n for n in names if sl.item_attrs[n]["type"] == "main"]
    choose = bes[:1] + mains[len(mains) // 2:][:1]
    if not choose:
        return []
    curves = _polar_curves(sl, ex, choose)
    cols: dict[str, np.ndarray] = {"crank angle [°]": in_unit(ex.theta, "rad", "deg")}
    for n, per_case in zip(choose, curves):
        for c, k, fx, fy, _ in per_case:
            cols[f"{n} {c} load {sp[k]:.0f} rpm Fx [kN]"] = in_unit(fx, "N", "kN")
            cols[f"{n} {c} load {sp[k]:.0f} rpm Fy [kN]"] = in_unit(fy, "N", "kN")
    png = later((170, 96), _draw_polar, choose, curves, sp, ex.theta,
                [ex.frames[n] for n in choose])
    names_ = list(cols)
    data = {"sheet": "polar loads", "title": "Bearing load components of the polar diagrams",
            "columns": names_, "rows": [[float(cols[k][j]) for k in names_]
                                        for j in range(cols["crank angle [°]"].size)]}
    return [{"type": "figure", "png": png, "data": [data],
             "caption": "Polar load diagrams: force of the journal on the bearing in kN (0° ="
                        " frame y axis, angle in the direction of rotation), each load case at"
                        " the speed of its highest judged peak specific load; dots every 90° of"
                        " crank angle over the 720° cycle (the first labelled 0°); dotted: not"
                        f" judged ({jd.reason(sl)})."}]


def _polar_curves(sl, ex, choose: list[str]) -> list[list[tuple]]:
    """Per bearing of ``choose``, per load case: ``(case, speed index, fx, fy, judged)``, the
    bearing load over the cycle at the speed of the highest judged peak specific load (the
    highest of all if none is judged)."""
    names = sl.coords["item"]
    sl_judged = jd.mask(sl)
    out = []
    for n in choose:
        i = names.index(n)
        per_case = []
        for ci, c in enumerate(sl.coords["case"]):
            vals = np.where(sl_judged[i, ci], sl.values[i, ci], -np.inf)
            if not np.isfinite(vals).any():
                vals = sl.values[i, ci]
            k = int(np.nanargmax(vals))
            per_case.append((c, k, ex.fx[i, ci, k], ex.fy[i, ci, k], sl_judged[i, ci, k]))
        out.append(per_case)
    return out


def _draw_polar(choose: list[str], curves: list[list[tuple]], sp, theta, frames: list[str]):
    """The polar load diagrams of :func:`_polar` (``curves`` of :func:`_polar_curves`, crank
    angle ``theta`` [rad], ``frames``: the frame of each bearing), drawn."""
    fig, axes = figure(170, 96, ncols=len(choose), subplot_kw={"projection": "polar"},
                       squeeze=False, left=10, right=10, top=12, bottom=20, wgap=34)
    deg = in_unit(theta, "rad", "deg") % 720
    marks = np.array([int(np.argmin(np.abs(deg - a))) for a in range(0, 720, 90)])
    for a, (n, per_case, frame) in enumerate(zip(choose, curves, frames)):
        ax = axes[0, a]
        k_col = 0
        angles, radii = [], []
        for c, k, fx, fy, judged in per_case:
            th = every(fx.size)
            ang = np.append(np.arctan2(fx, fy)[th], np.arctan2(fx[0], fy[0]))  # closed
            rad = in_unit(np.append(np.hypot(fx, fy)[th], np.hypot(fx[0], fy[0])), "N", "kN")
            color = CURVE_COLORS[k_col]
            ax.plot(ang, rad, lw=0.9, color=color, ls="-" if judged else ":",
                    label=f"{c} load, {sp[k]:.0f} rpm (its worst)" + ("" if judged else
                                                                      ", not judged"))
            ax.plot(np.arctan2(fx[marks], fy[marks]), in_unit(np.hypot(fx[marks], fy[marks]),
                                                              "N", "kN"),
                    "o", ms=2.6, color=color)
            ax.annotate("0°", (np.arctan2(fx[marks[0]], fy[marks[0]]),
                               in_unit(np.hypot(fx[marks[0]], fy[marks[0]]), "N", "kN")),
                        fontsize=5.5, color=color, xytext=(3, 2), textcoords="offset points")
            angles.append(ang)
            radii.append(rad)
            k_col += 1
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_thetagrids(np.arange(0, 360, 45))
        ax.set_rlabel_position(_free_direction(np.concatenate(angles), np.concatenate(radii)))
        ax.yaxis.set_major_locator(_max_ticks(4))
        ax.tick_params(axis="y", labelsize=5.5)
        for t in ax.get_yticklabels():
            t.set_bbox({"facecolor": "white", "edgecolor": "none", "pad": 0.3, "alpha": 0.8})
        ax.grid(True, alpha=0.3)
        ax.set_title(literal(f"{n} ({frame}), load [kN]"), pad=10)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncols=1, frameon=False,
                  fontsize=6)
    return to_image(fig)


def _free_direction(ang: np.ndarray, rad: np.ndarray) -> float:
    """The direction [deg, clockwise from the top] of a 45° grid line where the curves stay
    closest to the centre: the radial tick labels go there, off the curves."""
    best, low = 22.5, np.inf
    for d in np.arange(22.5, 360, 45):
        a = np.radians(d)
        near = np.abs(np.angle(np.exp(1j * (ang - a)))) < np.radians(15)
        r = float(rad[near].max()) if near.any() else 0.0
        if r < low:
            best, low = float(d), r
    return best


def _max_ticks(n: int):
    from matplotlib.ticker import MaxNLocator

    return MaxNLocator(n)


def main_load_scheme(res: CheckResult) -> str:
    """Where the main-bearing loads come from, in words (the films and heat balances name it)."""
    bl = res.outcome.quantities.get("loads.bearing_load")
    if bl is None or bl.detail.beam is None:
        return "statically determinate loads"
    return f"main loads of the crank as a {bl.detail.scheme}"


def _support_scheme(res: CheckResult, bl) -> list[dict]:
    """The continuous beam beside the determinate scheme: both schemes' main loads (polar
    diagrams overlaid, peaks per main), the fillet bending ratio per throw, and the verdicts
    that change with the scheme."""
    ex = bl.detail
    beam = ex.beam
    names = bl.coords["item"]
    mains = [i for i, n in enumerate(names) if bl.item_attrs[n]["type"] == "main"]
    cases = list(bl.coords["case"])
    blocks: list[dict] = [{"type": "heading", "text": "The crank as a continuous beam"}]
    k = beam.support_stiffness
    sup = ("rigid supports" if not np.isfinite(k).any() else
           "elastic supports of " + ", ".join(f"{fmt(float(v) * 1e-3)}" for v in k)
           + " N/mm")
    off = ("" if not np.any(beam.support_offset) else "; support offsets " + ", ".join(
        fmt(in_unit(v, "m", "mm")) for v in beam.support_offset) + " mm")
    blocks.append({"type": "text", "text":
                   f"Main bearing loads of the crank as a continuous beam on {sup}{off}:"
                   f" {beam.nodes.shape[0]} nodes, {beam.elements.shape[0]} beam elements"
                   " through the journal and pin centre lines (every node, element stiffness,"
                   " support and the nodal loads and main loads at the case and speed of the"
                   f" largest main load, {beam.case} load, {rpm(beam.speed):.0f} rpm, are in"
                   f" the JSON output and {ATTACHMENT}, sheets crank beam nodes, elements and"
                   " loads). The statically"
                   " determinate loads are shown beside them: both carry the same forces, the"
                   " beam shares them between the mains by its stiffness."})
    # peaks per main and case, both schemes
    det = ex.main_determinate
    rows = []
    for j, i in enumerate(mains):
        for ci, c in enumerate(cases):
            pc = np.hypot(ex.fx[i, ci], ex.fy[i, ci]).max()
            pd = np.hypot(det.x[ci, :, j], det.y[ci, :, j]).max()
            rows.append([names[i], f"{c} load", fmt(in_unit(pd, "N", "kN")),
                         fmt(in_unit(pc, "N", "kN")), fmt(pc / pd, 3)])
    blocks.append({"type": "table", "caption": "Peak main-bearing load over the speed range,"
                   " both schemes", "columns": ["main", "case", "determinate [kN]",
                                                "continuous beam [kN]", "ratio"],
                   "rows": rows})
    # polar diagrams of every main at the recorded operating point, both schemes
    ci = cases.index(beam.case)
    si = int(np.argmin(np.abs(np.array(bl.coords["speed"]) - beam.speed)))
    ncols = min(len(mains), 4)
    nrows = -(-len(mains) // ncols)
    height = 62 * nrows
    curves = [(names[i], (
        ("determinate", det.x[ci, si, j], det.y[ci, si, j], CURVE_COLORS[1], "--"),
        ("continuous beam", ex.fx[i, ci, si], ex.fy[i, ci, si], CURVE_COLORS[0], "-")))
        for j, i in enumerate(mains)]
    cols: dict[str, np.ndarray] = {"crank angle [°]": in_unit(ex.theta, "rad", "deg")}
    for name, both in curves:
        for label, fx, fy, _, _ in both:
            cols[f"{name} {label} Fx [kN]"] = in_unit(fx, "N", "kN")
            cols[f"{name} {label} Fy [kN]"] = in_unit(fy, "N", "kN")
    png = later((170, height), _draw_main_loads, height, nrows, ncols, curves, ex.theta.size)
    names_ = list(cols)
    data = {"sheet": "main loads both schemes", "title": "Main-bearing loads of both schemes"
            f" at {beam.case} load, {rpm(beam.speed):.0f} rpm", "columns": names_,
            "rows": [[float(cols[n][r]) for n in names_] for r in range(ex.theta.size)]}
    blocks.append({"type": "figure", "png": png, "data": [data, *_beam_sheets(beam)],
                   "caption": f"Main-bearing loads at {beam.case} load, {rpm(beam.speed):.0f}"
                              " rpm (the operating point of the largest main load): the"
                              " continuous beam (solid) over the statically determinate scheme"
                              " (dashed); force of the journal on the bearing, block frame,"
                              " 0° = cylinder axis, angle in the direction of rotation."})
    fr = res.outcome.quantities.get("fatigue.fillet_bending_ratio")
    if fr is not None:
        d = fr.detail
        rows = [[n, fmt(a), fmt(b), fmt(v, 3),
                 f"{c} load, {rpm(w):.0f} rpm"]
                for n, a, b, v, c, w in zip(fr.coords["item"], d.amplitude_determinate,
                                            d.amplitude_continuous, fr.values, d.case, d.speed,
                                            strict=True)]
        blocks.append({"type": "table", "caption": "Fillet bending moment amplitude of the"
                       " continuous beam over the determinate scheme (con-rod forces on the"
                       " pins, IACS UR M53's loads), each at the operating point of its largest"
                       " determinate amplitude. Piraner, Pflueger and Bouthier (Cummins, 2002,"
                       " Fig. 1) report 80 % on rigid and 87 % on elastic supports for the"
                       " fillet bending stress.",
                       "columns": ["fillet", "determinate [N m]", "continuous [N m]", "ratio",
                                   "operating point"], "rows": rows})
    changes = res.scheme_changes
    if changes is not None:
        if changes:
            rows = [[c["rule"], literal(c["item"]), c["determinate_case"],
                     c["determinate"].replace("_", " "), fmt(c["determinate_value"]),
                     c["case"], c["continuous"].replace("_", " "), fmt(c["continuous_value"])]
                    for c in changes]
            blocks.append({"type": "table", "caption": "Verdicts that change with the support"
                           " scheme (this report's continuous beam against the determinate"
                           " scheme, every other input the same)",
                           "columns": ["rule", "item", "determinate: case", "status", "value",
                                       "continuous: case", "status", "value"], "rows": rows})
        else:
            blocks.append({"type": "text", "text": "No verdict changes with the support"
                           " scheme: the determinate scheme gives every rule the status of"
                           " the continuous beam."})
    return blocks


def _draw_main_loads(height: float, nrows: int, ncols: int, curves: list[tuple],
                     n_theta: int):
    """The polar diagrams of every main of :func:`_support_scheme`, both schemes (``curves``:
    per main its name and its (label, fx, fy, colour, line style) per scheme; ``n_theta``
    crank angles), drawn."""
    fig, axes = figure(170, height, nrows=nrows, ncols=ncols, squeeze=False,
                       subplot_kw={"projection": "polar"}, left=8, right=8, top=10,
                       bottom=14, wgap=18)
    th = every(n_theta)
    for j, (name, both) in enumerate(curves):
        ax = axes[j // ncols, j % ncols]
        for label, fx, fy, color, ls in both:
            ang = np.append(np.arctan2(fx, fy)[th], np.arctan2(fx[0], fy[0]))
            rad = in_unit(np.append(np.hypot(fx, fy)[th], np.hypot(fx[0], fy[0])), "N", "kN")
            ax.plot(ang, rad, lw=0.8, color=color, ls=ls, label=label)
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_thetagrids(np.arange(0, 360, 90))
        ax.yaxis.set_major_locator(_max_ticks(3))
        ax.tick_params(labelsize=5.5)
        ax.grid(True, alpha=0.3)
        ax.set_title(literal(f"{name} [kN]"), pad=6, fontsize=7)
    for j in range(len(curves), nrows * ncols):
        axes[j // ncols, j % ncols].set_visible(False)
    legend_below(fig, axes=[axes[0, 0]], ncols=2)
    return to_image(fig)


def _beam_sheets(beam) -> list[dict]:
    """The beam model as results-workbook sheets: nodes (with supports), elements, and the
    nodal loads and main loads per crank angle at the recorded operating point (SI)."""
    sup = {int(n): (k, o) for n, k, o in zip(beam.support_nodes, beam.support_stiffness,
                                             beam.support_offset, strict=True)}
    nodes = [[i, *map(float, p), "main" if i in sup else "", (
        "rigid" if i in sup and not np.isfinite(sup[i][0]) else float(sup[i][0]) if i in sup
        else ""), float(sup[i][1]) if i in sup else ""] for i, p in enumerate(beam.nodes)]
    elements = [[e, int(i), int(j), float(ea), float(gj), float(ei[0]), float(ei[1]),
                 *map(float, ax)] for e, ((i, j), ea, gj, ei, ax) in enumerate(zip(
                     beam.elements, beam.axial_stiffness, beam.torsional_stiffness,
                     beam.bending_stiffness, beam.first_axis, strict=True))]
    load_cols = ["crank angle [deg]"] + [f"node {n} {c}" for n in beam.load_nodes
                                          for c in ("Fx [N]", "Fy [N]", "Fz [N]", "Mx [N m]",
                                                    "My [N m]", "Mz [N m]")]
    load_cols += [f"main {m + 1} {c} [N]" for m in range(beam.support_nodes.size)
                  for c in ("x", "y")]
    loads = [[float(np.rad2deg(a)), *map(float, beam.node_loads[k].ravel()),
              *map(float, beam.main_loads[k].ravel())] for k, a in enumerate(beam.angles)]
    return [
        {"sheet": "crank beam nodes", "title": f"Crank beam ({beam.scheme}): nodes, crank"
         " frame (z = crank axis); supports at the mains (radial stiffness, block-frame y"
         f" offset); rotation about z held at node {beam.torsion_node} (it reacts nothing:"
         " the Mz loads balance the rods' torque)",
         "columns": ["node", "x [m]", "y [m]", "z [m]", "support", "stiffness [N/m]",
                     "offset [m]"], "rows": nodes},
        {"sheet": "crank beam elements", "title": "Crank beam: Euler-Bernoulli elements (EI"
         " about axis 1 and about axis 2 = element axis x axis 1)",
         "columns": ["element", "node i", "node j", "EA [N]", "GJ [N m^2]",
                     "EI axis 1 [N m^2]", "EI axis 2 [N m^2]", "axis 1 x", "axis 1 y",
                     "axis 1 z"], "rows": elements},
        {"sheet": "crank beam loads", "title": f"Crank beam loads at {beam.case} load,"
         f" {rpm(beam.speed):.0f} rpm: force and moment on the crank at each load node and the"
         " force of each main journal on its bearing, crank frame", "columns": load_cols,
         "rows": loads},
    ]
