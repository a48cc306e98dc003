"""Report section: classical crankshaft fatigue (Goodman safety factors, IACS UR M53 Q)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..calc.fatigue import goodman_line
from ..calc.scf import VALIDITY
from ..evaluation.ruletable import not_evaluated_message
from ..modules.fatigue import FACTORS_OF, LOCATIONS, SCF_FIELDS
from ..results.display import case_text
from ..results.fatigue import FatigueDetail, GoodmanDetail
from . import judged as jd
from .plots import LIMIT_STYLE, figure, later, legend_below, limit_line, literal, to_image
from .sections import fmt, in_unit, rpm, section

COLORS = {"pin fillet": "#1f77b4", "main fillet": "#2ca02c", "pin oil hole": "#d62728",
          "main oil hole": "#9467bd"}
SF_PLOT_MAX = 6.0
"""Upper end of the safety-factor axis (factors above it are clipped in the plot only)."""


def _limit(res: CheckResult, quantity: str) -> float | None:
    """Display limit of the rule (after overrides) on ``quantity``."""
    for r in res.table.rules:
        if r.quantity == quantity and r.limit:
            return r.limit[0]
    return None


def mpa(v):
    """Stress(es) in Pa as MPa."""
    return in_unit(v, "Pa", "MPa")


def _inputs(res: CheckResult, ex: FatigueDetail, m53q) -> list[dict]:
    eng = res.engine
    fa = eng.fatigue
    g = ex.geometry
    oil = ex.oil_hole

    def cell(sheet: str, attr: str) -> str:
        c = eng.cell(sheet, attr)
        return f"{sheet} (blank)" if c == sheet else c

    def mm(v) -> str:
        return "-" if v is None else fmt(in_unit(v, "m", "mm"))

    rows = [
        ["Crank-pin diameter", "D", mm(g.pin_diameter), "mm", "Bearings (big end)"],
        ["Main journal diameter", "D_G", mm(g.journal_diameter), "mm", "Bearings (main)"],
        ["Crank radius (stroke/2)", "E", mm(g.throw), "mm", cell("Engine", "stroke")],
        ["Main journal spacing", "L3", mm(g.main_spacing), "mm",
         cell("Engine", "main_spacing")],
        ["Main journal length", "L_G", mm(g.main_journal_length), "mm", "Bearings (main)"],
        ["Crank-pin length", "L_H", mm(g.pin_journal_length), "mm",
         "Bearings (big end)"],
        ["Web reduced thickness", "W", mm(g.web_thickness), "mm",
         cell("Fatigue", "web_thickness")],
        ["Web width (minimum)", "B", mm(g.web_width), "mm", cell("Fatigue", "web_min_width")],
        ["Web offset", "-", mm(g.web_offset), "mm", cell("Fatigue", "web_offset")],
        ["Pin / journal axial bore", "D_BH / D_BG",
         f"{mm(g.pin_bore)} / {mm(g.journal_bore)}", "mm",
         f"{cell('Fatigue', 'pin_bore')}, {cell('Fatigue', 'main_bore')}"],
        ["Pin fillet radius", "R_H", mm(fa.get("pin_fillet_radius")), "mm",
         cell("Fatigue", "pin_fillet_radius")],
        ["Main fillet radius", "R_G", mm(fa.get("main_fillet_radius")), "mm",
         cell("Fatigue", "main_fillet_radius")],
        ["Pin / main fillet recess into the web", "T_H / T_G",
         f"{mm(fa.get('pin_fillet_web_undercut') or 0.0)} /"
         f" {mm(fa.get('main_fillet_web_undercut') or 0.0)}", "mm",
         f"{cell('Fatigue', 'pin_fillet_web_undercut')},"
         f" {cell('Fatigue', 'main_fillet_web_undercut')}"],
        ["Pin / main radial fillet undercut (not an M53 parameter, not used)", "-",
         f"{mm(fa.get('pin_fillet_undercut'))} / {mm(fa.get('main_fillet_undercut'))}", "mm",
         f"{cell('Fatigue', 'pin_fillet_undercut')}, {cell('Fatigue', 'main_fillet_undercut')}"],
    ]
    if oil is not None:
        rows.append(["Crank-pin oil hole diameter", "D_O", mm(oil.diameter), "mm",
                     cell("Fatigue", "pin_oil_hole_diameter")])
        ang = oil.angle
        rows.append(["Crank-pin oil hole angle from the throw axis (+ leading)", "φ",
                     "-" if ang is None else fmt(in_unit(ang, "rad", "deg")), "deg",
                     f"Bearings {oil.row.name}"])
    if ex.main_oil_hole_diameter is not None:
        rows.append(["Main journal oil hole diameter", "D_O,G",
                     mm(ex.main_oil_hole_diameter), "mm",
                     cell("Fatigue", "main_oil_hole_diameter")])
    blocks: list[dict] = [{"type": "table", "caption": "Geometry of the crank throw (SI inputs"
                           " shown in mm; sizes of the first/smallest bearing rows)",
                           "columns": ["parameter", "symbol", "value", "unit", "source"],
                           "rows": rows, "widths": [37, 12, 12, 6, 33]}]
    rows = []
    dw = {} if m53q is None else m53q.detail.sigma_dw
    for loc in LOCATIONS:
        st = ex.strengths.get(loc)
        if st is None:
            continue
        se, su, c_se, c_su = st
        rows.append([loc, "-" if se is None else fmt(mpa(se)), c_se,
                     "-" if su is None else fmt(mpa(su)), c_su,
                     fmt(mpa(dw[loc])) if loc in dw else "-"])
    blocks.append({"type": "table", "caption": "Material strengths (sheet Fatigue) and the IACS"
                   " UR M53 §6 fatigue strength σ_DW (base UTS, no surface-treatment credit)",
                   "columns": ["location", "S_e [MPa]", "cell", "S_u [MPa]", "cell",
                               "M53 σ_DW [MPa]"], "rows": rows,
                   "widths": [18, 11, 20, 11, 20, 20]})
    return blocks


def _scf(ex: FatigueDetail) -> list[dict]:
    scf = ex.scf
    find = ex.scf_findings
    rows = []
    for key, (_, sym, what) in SCF_FIELDS.items():
        if not any(key in FACTORS_OF[loc] for loc in LOCATIONS if loc in ex.strengths):
            continue
        used = scf.used[key]
        status = "; ".join(t.split("): ", 1)[-1] for t in find.get(key, [])) or (
            "within M53 validity" if scf.source[key].startswith("IACS") else "-")
        rows.append([sym, what, fmt(used), scf.source[key], fmt(scf.m53[key]),
                     status])
    blocks: list[dict] = [{"type": "table", "caption": "Stress concentration factors: workbook"
                           " value where given, otherwise IACS UR M53 §3 (validity flags"
                           " reported, never silent)",
                           "columns": ["factor", "location and load", "used", "source",
                                       "M53 value", "M53 validity"], "rows": rows,
                           "widths": [8, 27, 8, 19, 9, 29]}]
    ratios = scf.ratios
    if ratios is not None:
        rows = []
        for name in ("r_pin", "r_journal", "r_journal_torsion", "s", "w", "b", "d_O", "d_G",
                     "d_H"):
            lo, hi = VALIDITY[name]
            v = float(getattr(ratios, name))
            inside = (lo is None or v >= lo) and (hi is None or v <= hi)
            rows.append([name, fmt(v), f"{'-∞' if lo is None else f'{lo:g}'} .."
                         f" {'∞' if hi is None else f'{hi:g}'}", "yes" if inside else "NO"])
        blocks.append({"type": "table", "caption": "M53 related dimensions (§3.1): r = R/D, s ="
                       " S/D with the overlap S = (D + D_G)/2 − E, w = W/D, b = B/D, d_O = D_O/D,"
                       " d_G = D_BG/D, d_H = D_BH/D (r_journal_torsion = R_G/D_G is used only"
                       " when D ≠ D_G or R_H ≠ R_G)",
                       "columns": ["ratio", "value", "validity range", "inside"],
                       "rows": rows, "detail": True, "sheet": "M53 dimensions"})
    return blocks


def _equations() -> list[dict]:
    return [{"type": "equations", "items": [
        ("Pin force in the throw frame", "F_R = F·e_r (+ outward),  F_T = F·e_t (+ rotation),"
         "  F = −Σ big-end load of the rods on the pin", "IACS UR M53 §2.1"),
        ("Web bending (web centre)", "σ_BF = K_e·Q_RF·L1 / (B·W²/6),  Q_RF = F_R·(L3 − L2)/L3,"
         "  K_e = 1", "M53 §2.1; statically determinate: Bell, Ricardo 2013, 'Crankshaft"
         " analysis (25)'"),
        ("Web direct stress", "σ_QF = K_e·Q_RF / (B·W)", "M53 §2.1"),
        ("Oil-bore bending", "σ_BO = (M_BRO·cos φ + M_BTO·sin φ) / W_e,  W_e = π/32·(D⁴ − D_BH⁴)/D",
         "M53 §2.1.2"),
        ("Torsion", "τ = T_e(θ) / W_P,  W_P = π/16·(D⁴ − D_B⁴)/D,  T_e(θ) = T_mean,e + Σ"
         " Re{T_en·e^(jnθ)}", "M53 §2.2; TV element torques (torsion section)"),
        ("Local stresses", "σ_H = −α_B·σ_BF,  τ_H = α_T·τ_pin,  σ_G = β_B·σ_BF + β_Q·σ_QF,"
         "  τ_G = β_T·τ_journal,  σ_BO·γ_B,  σ_TO = γ_T·τ_pin", "M53 §2.1.3, §2.2.3, §3"),
        ("Amplitude and mean", "X_a = (X_max − X_min)/2,  X_m = (X_max + X_min)/2 over 720°",
         "M53 §2.1.2"),
        ("Equivalent alternating (fillet)", "σ_eq,a = √(σ_a² + 3·τ_a²)  (von Mises of the"
         " amplitudes, in phase)", "M53 §5"),
        ("Equivalent mean (fillet)", "σ_eq,m = sign(σ_m)·√(σ_m² + 3·τ_m²),  compressive"
         " σ_eq,m not credited (taken as 0)", "signed von Mises of the means (Budynas and"
         " Nisbett, Shigley's Mechanical Engineering Design, 10th ed., 2015, §6-14)"),
        ("Oil hole (amplitude and mean)", "σ_eq = (σ_BO + 2·√(σ_BO² + 9/4·σ_TO²))/3",
         "M53 §5(4), maximum principal stress"),
        ("Goodman safety factor", "SF = 1 / (σ_eq,a/S_e + σ_eq,m/S_u) ≥ 1.5",
         "Shigley eq. 6-46; limit: Bell, Ricardo 2013, 'Crankshaft analysis (28)'"),
        ("M53 acceptability", "Q = σ_DW / σ_V ≥ 1.15,  σ_V = √((σ_a + σ_add)² + 3·τ_a²),"
         "  σ_add = 10 MPa", "M53 §4-7"),
        ("M53 fatigue strength", "σ_DW = K(0.42σ_B + 39.3)[0.264 + 1.073·D^−0.2 + (785 − σ_B)/4900"
         " + 196/σ_B·√(1/R_X)]", "M53 §6 (N/mm², mm; R_X ≥ 2 mm)"),
    ]}]


def _governing(q) -> dict[str, int]:
    """Index of the item with the lowest judged factor per location type."""
    out = {}
    for loc in LOCATIONS:
        worst = {}
        for i, n in enumerate(q.coords["item"]):
            if q.item_attrs[n]["location"] == loc and np.isfinite(q.values[i]).all():
                p = jd.worst(q, (i,), "min")[0]
                if p is not None:
                    worst[i] = p.value
        if worst:
            out[loc] = min(worst, key=lambda i: worst[i])
    return out


def _plots(res: CheckResult, q) -> list[dict]:
    ex: GoodmanDetail = q.detail
    sp = rpm(np.array(q.coords["speed"]))
    cases = q.coords["case"]
    gov = _governing(q)
    judged = jd.mask(q)
    blocks: list[dict] = []
    if not gov:
        return blocks
    note = jd.shade_caption([] if judged[list(gov.values())].all() else [jd.reason(q)])
    # Goodman SF vs speed with the limit
    lim = _limit(res, "fatigue.goodman_sf")
    blocks.append({"type": "figure", "png": later((170, 66), _draw_goodman, q, sp, gov, judged,
                                                  lim), "data": [q.name], "caption": (
        f"Lowest Goodman safety factor of each location type against speed (axis clipped at"
        f" {SF_PLOT_MAX:g}).{note}")})
    # normalised Haigh (Goodman) diagram
    grey = False
    cols: dict[str, list] = {}
    for i in gov.values():
        for ci, c in enumerate(cases):
            grey = grey or bool((~judged[i, ci]).any())
            name = f"{q.coords['item'][i]}, {case_text(c)}"
            cols[f"{name}: mean / S_u"] = list(ex.haigh_x[i, ci])
            cols[f"{name}: alternating / S_e"] = list(ex.haigh_y[i, ci])
    names = list(cols)
    data = {"sheet": "Haigh diagram", "title": "Normalised Haigh diagram points per speed",
            "columns": ["speed [rpm]", *names],
            "rows": [[float(sp[k]), *[float(cols[n][k]) for n in names]]
                     for k in range(sp.size)]}
    blocks.append({"type": "figure", "png": later((170, 80), _draw_haigh, q, gov, judged, lim),
                   "data": [data], "caption": (
        "Normalised Haigh (Goodman) diagram: the operating points over the speed range of the"
        " location of each type with the lowest safety factor (solid: full load, dashed: no"
        " load; marker: the judged lowest factor). Compressive means are not credited: the"
        " line is flat for σ_m < 0."
        + ("" if not grey else f" Grey dotted: computed but not judged ({jd.reason(q)}).")
        )})
    return blocks


def _draw_goodman(q, sp, gov: dict[str, int], judged, lim: float | None) -> bytes:
    """Lowest Goodman safety factor of each location type against speed, per load case."""
    ex: GoodmanDetail = q.detail
    cases = q.coords["case"]
    fig, axes = figure(170, 66, ncols=len(cases), squeeze=False, sharey=True, wgap=8,
                       legend_rows=1)
    by_loc = ex.sf_by_location
    for ci, c in enumerate(cases):
        ax = axes[0, ci]
        jd.shade(ax, sp, judged[list(gov.values()), ci].any(axis=0))
        for li, loc in enumerate(LOCATIONS):
            if loc in gov:
                ax.plot(sp, np.minimum(by_loc[li, ci], SF_PLOT_MAX), color=COLORS[loc],
                        label=f"{loc}s (lowest)")
        if lim is not None:
            limit_line(ax, lim, f"limit {lim:g} (FAT-001)")
        ax.set_ylim(0, SF_PLOT_MAX)
        ax.set_title(case_text(c))
        ax.set_xlabel("Engine speed [rpm]")
    axes[0, 0].set_ylabel("Goodman safety factor [-]")
    legend_below(fig, ncols=6)
    return to_image(fig)


def _draw_haigh(q, gov: dict[str, int], judged, lim: float | None) -> bytes:
    """Normalised Haigh (Goodman) diagram of the governing location of each type."""
    ex: GoodmanDetail = q.detail
    cases = q.coords["case"]
    fig, ax = figure(170, 80, legend_rows=2)
    x_max = max(1.05, float(np.nanmax(ex.haigh_x[list(gov.values())])) * 1.1)
    xs = np.linspace(min(-0.5, float(np.nanmin(ex.haigh_x[list(gov.values())])) * 1.1),
                     x_max, 200)
    ax.plot(xs, goodman_line(xs, 1.0, 1.0, 1.0), color="k", lw=1.0, label="Goodman, SF = 1")
    if lim is not None:
        ax.plot(xs, goodman_line(xs, 1.0, 1.0, lim), **LIMIT_STYLE,
                label=f"SF = {lim:g} (FAT-001)")
    grey = False
    for loc, i in gov.items():
        for ci, c in enumerate(cases):
            j = judged[i, ci]
            hx, hy = ex.haigh_x[i, ci], ex.haigh_y[i, ci]
            # the operating points as a path over speed (one line per location and case),
            # the judged lowest safety factor marked
            ax.plot(np.where(j, hx, np.nan), np.where(j, hy, np.nan), color=COLORS[loc],
                    ls="-" if c == "full" else "--", lw=0.9,
                    label=literal(f"{q.coords['item'][i]}, {case_text(c)}"))
            if (~j).any():
                ax.plot(np.where(j, np.nan, hx), np.where(j, np.nan, hy), color="0.55",
                        ls=":", lw=0.9, label=None if grey else "not judged")
                grey = True
            p = jd.worst(q, (i, ci), "min")[0]
            if p is not None:
                k = p.index[-1]
                ax.plot([hx[k]], [hy[k]], "o" if c == "full" else "^", ms=4,
                        color=COLORS[loc], mfc=COLORS[loc] if c == "full" else "white")
    ax.axvline(0, color="k", lw=0.5)
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(0, max(1.1, float(np.nanmax(ex.haigh_y[list(gov.values())])) * 1.1))
    ax.set_xlabel("Equivalent mean stress / S_u [-]")
    ax.set_ylabel("Equivalent alternating stress / S_e [-]")
    legend_below(fig, ncols=4)
    return to_image(fig)


def _worst(res: CheckResult, q, m53q) -> list[dict]:
    """Lowest Goodman SF and M53 Q per location: the judged worst first (the values of the
    rule results), then, marked, lower values at points the rules do not judge."""
    ex: GoodmanDetail = q.detail
    sp = rpm(np.array(q.coords["speed"]))
    cases = q.coords["case"]

    def sf_cells(p):
        if p is None:
            return ["-"] * 6
        i, ci, si = p.index
        side = ex.candidates[i][int(ex.governing[i, ci, si])]
        return [fmt(p.value), case_text(cases[ci]), f"{sp[si]:.0f}",
                fmt(mpa(ex.sigma_eq_a[i, ci, si])),
                fmt(mpa(ex.sigma_eq_m[i, ci, si])), side]

    def q_cells(p):
        if p is None:
            return ["-", "-"]
        _, cq, sq = p.index
        return [fmt(p.value), f"{case_text(cases[cq])}, {sp[sq]:.0f}"]

    rows, css = [], []
    for i, n in enumerate(q.coords["item"]):
        qj = qu = None
        if m53q is not None and n in m53q.coords["item"]:
            k = m53q.coords["item"].index(n)
            if np.isfinite(m53q.values[k]).all():
                qj, qu = jd.worst(m53q, (k,), "min")
        if not np.isfinite(q.values[i]).all():
            rows.append([n, "not evaluated: " + "; ".join(jd.missing_reasons(q, (i,))),
                         *["-"] * 5, *q_cells(qj), "-"])
            css.append("")
            continue
        sj, su = jd.worst(q, (i,), "min")
        ids = (jd.rule_ids(res, q.name, n) if sj is not None else []) + (
            jd.rule_ids(res, m53q.name, n) if qj is not None else [])
        rows.append([n, *sf_cells(sj), *q_cells(qj), ", ".join(ids) or "no rule on it"])
        css.append("")
        if su is not None or qu is not None:
            why = [jd.reason(x) for x, p in ((q, su), (m53q, qu)) if p is not None]
            rows.append([n, *sf_cells(su), *q_cells(qu),
                         "not judged: " + "; ".join(dict.fromkeys(why))])
            css.append(jd.NOT_JUDGED_CSS)
    return [{"type": "table", "caption": (
        "Lowest Goodman safety factor per location with its operating point and governing"
        " fillet/torque (rule FAT-001), and the lowest M53 Q (FAT-002): the judged worst first"
        " (the values of the rule results), then, marked, lower values at points the rules do"
        " not judge"),
        "columns": ["location", "SF min", "case", "speed [rpm]", "σ_eq,a [MPa]",
                    "σ_eq,m [MPa]", "governing", "M53 Q min", "Q at", "judged by"],
        "rows": rows, "row_css": css, "widths": [12, 7, 8, 7, 8, 8, 11, 8, 11, 20]}]


@section("fatigue", label="crankshaft fatigue")
def fatigue_section(res: CheckResult) -> dict:
    qs = res.outcome.quantities
    q = qs.get("fatigue.goodman_sf")
    m53q = qs.get("fatigue.m53_q")
    title = "Crankshaft fatigue (classical stress analysis)"
    intro = ("Classical (statically determinate) stresses at the crank-pin fillets, main-journal"
             " fillets and oil holes over the 720° cycle at full and no load across the speed"
             " range (Bell, Ricardo 2013, 'Crankshaft analysis (25)-(28)'; IACS UR M53 §2-5):"
             " bending of each throw from the"
             " con-rod forces of the loads module, torsion from the TV module's element torques"
             " synthesised at the same crank angle, stress concentration factors from the"
             " workbook or IACS UR M53, Goodman safety factor against the workbook's fatigue"
             " strengths (FAT-001) and the M53 acceptability factor (FAT-002).")
    if q is None:
        q = m53q
    if q is None:
        reasons = sorted({r for n, v in res.outcome.unavailable.items()
                          if n.startswith("fatigue.") for r in v})
        return {"id": "fatigue", "title": title, "intro": intro, "blocks": [
            {"type": "text", "text": "Crankshaft fatigue not computed: "
             + ("; ".join(reasons) or "no fatigue quantity was requested") + "."}]}
    ex: FatigueDetail = q.detail
    blocks: list[dict] = [{"type": "heading", "text": "Inputs"}]
    blocks += _inputs(res, ex, m53q)
    blocks += _scf(ex)
    blocks.append({"type": "heading", "text": "Equations and criteria"})
    blocks += _equations()
    blocks.append({"type": "list", "items": [
        "Stress criterion (Goodman, FAT-001): von Mises of the component amplitudes (bending and"
        " torsion assumed in phase, as M53 §5) against S_e; signed von Mises of the means against"
        " S_u (keeps the mean shear of the drive torque; a compressive mean is not credited);"
        " oil holes: M53's maximum-principal combination for both. The two criteria FAT-001 and"
        " FAT-002 are not equivalent: M53 neglects means and uses its own σ_DW.",
        "Mapping of TV elements (sign: torque of the front part on the rear part, + in the"
        " direction of rotation): a main journal carries the element torque between the"
        " cylinder stations on either side; the front pin fillet of a throw the element in"
        " front of its cylinder station, the rear pin fillet the element behind it; the pin"
        " oil hole (at the pin centre) is evaluated with both and the lower factor kept.",
        "Main journal fillets: each main journal's fillets next to a crank web (main 1 and the"
        " last main have one); bending of the adjacent throw plus the journal's torque. Main"
        " oil holes: torsion only (zero bending moment at the journal centre in the statically"
        " determinate scheme).",
        "The loading assumptions (statically determinate throw, TV torque, M53 constants) are"
        " listed under 'Assumptions and run'.",
    ]})
    if q.name == "fatigue.goodman_sf":
        blocks.append({"type": "heading", "text": "Judged worst cases"})
        blocks += _worst(res, q, m53q)
        blocks.append({"type": "heading", "text": "Plots"})
        blocks += _plots(res, q)
    found = sorted({f for v in q.findings.values() for f in v}
                   | ({f for v in m53q.findings.values() for f in v} if m53q else set()))
    if found:
        blocks.append({"type": "heading", "text": "Findings"})
        blocks.append({"type": "list", "items": found[:20] + (
            [f"... and {len(found) - 20} more"] if len(found) > 20 else [])})
    blocks += _nose(res)
    return {"id": "fatigue", "title": title, "intro": intro, "blocks": blocks}


def _nose(res: CheckResult) -> list[dict]:
    """Crank-nose check (FAT-003): the worst point per load case, or why it did not run."""
    nq = res.outcome.quantities.get("fatigue.nose_goodman_sf")
    out: list[dict] = [{"type": "heading", "text": "Crank nose (FAT-003)"}]
    if nq is None:
        why = res.outcome.unavailable.get("fatigue.nose_goodman_sf")
        if why is None:
            return []
        return out + [{"type": "text", "text": "N" + not_evaluated_message(why)[1:]}]
    ex = nq.detail
    sp = rpm(np.array(nq.coords["speed"]))
    rows, css = [], []
    found = [jd.worst(nq, (ci,), "min") for ci in range(len(nq.coords["case"]))]
    judged = sorted((j for j, _ in found if j is not None), key=lambda p: p.value)
    for p in judged + [u for _, u in found if u is not None]:
        ci, k = p.index
        c = nq.coords["case"][ci]
        rows.append([f"{c} load", f"{sp[k]:.0f}", f"{nq.values[ci, k]:.4g}",
                     f"{ex.torque_min[ci, k]:.0f} / {ex.torque_max[ci, k]:.0f}",
                     f"{mpa(ex.sigma_eq_a[ci, k]):.1f}",
                     f"{mpa(ex.sigma_eq_m[ci, k]):.1f}",
                     jd.judged_text(res, nq, p, None, c)])
        css.append(jd.row_css(p))
    return out + [{"type": "table", "caption": f"Worst crank-nose point per load case (torque"
                   f" of TV element '{ex.element}'): the judged points, lowest first (the"
                   " value of the rule result), then, marked, lower factors at points the"
                   " rules do not judge",
                   "columns": ["case", "speed [rpm]", "Goodman SF", "T min / max [N·m]",
                               "σ_eq,a [MPa]", "σ_eq,m [MPa]", "judged by"],
                   "rows": rows, "row_css": css, "widths": [11, 10, 10, 17, 11, 11, 30]}]
