"""Report section: bolted joints."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..results.display import case_text
from .plots import STATUS_COLORS, figure, later, legend_below, literal, to_image
from .sections import display_values, fmt, in_unit, rpm, section

BELL = "Bell, Cranktrain Analysis Using ENGDYN and VALDYN, Ricardo, 2013"


def _by_joint(caption: str, names: list[str], rows: list[tuple[str, list[str]]]) -> dict:
    """A table with one column per joint (parameters as rows): readable for the usual two
    joints, and no narrow columns."""
    w = max(12.0, min(30.0, 60.0 / max(1, len(names))))
    return {"type": "table", "caption": caption, "columns": ["", *names],
            "rows": [[label, *vals] for label, vals in rows],
            "widths": [100 - w * len(names), *[w] * len(names)]}


@section("joints", label="bolted joint")
def joints_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    eng = res.engine
    blocks: list[dict] = []
    js = list(eng.joints)
    mm = lambda v: fmt(in_unit(v, "m", "mm"))  # noqa: E731
    blocks.append(_by_joint("Joint inputs (sheet Joints)", [j.name for j in js], [
        ("Location", [j.location for j in js]),
        ("Bolts", [str(j.bolts) for j in js]),
        ("Thread diameter d x pitch p [mm]", [f"{mm(j.diameter)} x {mm(j.pitch)}" for j in js]),
        ("Property class", [j.property_class for j in js]),
        ("Tightening", [j.tightening for j in js]),
        ("Tightening torque [N·m]", [fmt(j.tightening_torque)
                                     if j.tightening_torque is not None else "-" for j in js]),
        ("Clamped face inner / outer diameter [mm]",
         [f"{mm(j.face_inner)} / {mm(j.face_outer)}" for j in js]),
        ("Head bearing inner / outer diameter [mm]",
         ["-" if j.head_outer is None or j.head_inner is None
          else f"{mm(j.head_inner)} / {mm(j.head_outer)}" for j in js]),
        ("Clamped material", [j.clamped_material or "-" for j in js]),
        ("Friction coefficient μ of the face", [fmt(j.friction) if j.friction is not None
                                                else "0.2 (default)" for j in js]),
    ]))
    blocks.append({"type": "equations", "items": [
        ("Tensile stress area", "A_s = π/4 · (d − c·p)²,  c = 0.9382", "ISO 898-1:2013 §9.1.6.1"
         f" ({BELL}, crank-nose worksheet: c = 0.938)"),
        ("Preload, torque tightening", "F = T / (K·d),  K = 0.2",
         f"{BELL}, 'Crankshaft analysis (23)': F = 5 T / D"),
        ("Preload, yield/angle/torque-wrench", "F = k·σ_ref·A_s,  k = 0.75 / 0.85 R_p0.2,"
         " 0.70 S_p", f"{BELL}, 'Crankshaft analysis (24)', table"),
        ("Proof-stress percentage", "100 · F / (P·A_s),  P = R_p0.2",
         f"{BELL}, 'Crankshaft analysis (23)': 70-75 % recommended"),
        ("Contact stress under the head", "σ = F / (π/4 · (d_o² − d_i²))",
         f"{BELL}, 'Crankshaft analysis (23)'; VDI 2230 Part 1, 2015, R10"),
        ("Slip torque capacity", "T_cap = μ·n·F·(2/3)(R³ − r³)/(R² − r²) = μ·n·F·D_eff/2",
         f"{BELL}, 'Crankshaft analysis (23)-(24)'"),
        ("Cover factor", "CF = T_cap / T_applied", f"{BELL}: crank nose ≥ 1.8 (2.0"
         " preferred); flywheel ≥ 1.8 at the TV peak, ≥ 2.0 at max power, ≥ 1.7 at"
         " overspeed"),
    ]})
    area = q.get("joint.stress_area")
    if area is not None:
        names = area.coords["item"]
        n = range(len(names))
        rows = []
        for label, name in (("Stress area A_s", "joint.stress_area"),
                            ("Preload per bolt F", "joint.preload"),
                            ("Clamp force, all bolts", "joint.clamp_force"),
                            ("Bolt stress / proof stress", "joint.proof_stress_ratio"),
                            ("Contact stress under the head", "joint.head_contact_stress"),
                            ("Effective friction diameter D_eff", "joint.effective_diameter"),
                            ("Slip torque capacity T_cap", "joint.slip_capacity")):
            vals, unit = display_values(q[name])
            rows.append((f"{label} [{unit}]", [fmt(vals[i]) for i in n]))
        blocks.append({"type": "heading", "text": "Bolt and face results"})
        blocks.append(_by_joint("Bolt and face results (rules JNT-001, JNT-002; the slip"
                                " capacity enters the cover factors)", list(names), rows))
        how = area.detail.how
        items = [f"{n}: " + "; ".join(f"{k}: {v}" for k, v in how.get(n, {}).items())
                 for n in names]
        blocks.append({"type": "list", "items": items})
    cf = q.get("joint.cover_factor")
    tq = q.get("joint.applied_torque")
    if cf is not None and tq is not None:
        blocks += _torques(res, cf, tq, q.get("joint.computed_torque"),
                           q.get("joint.computed_cover_factor"))
    return {"id": "joints", "title": "Bolted joints",
            "intro": "Crank-nose and flywheel bolted joints: bolt preload and proof-stress"
                     " percentage, contact stress under the bolt head, and the cover factor of"
                     " the clamped face (slip torque capacity over the peak applied torque),"
                     f" after the worked calculations of {BELL}, 'Crankshaft analysis"
                     " (23)-(24)'.",
            "blocks": blocks}


def _rpm(w) -> str:
    return "-" if w is None or not np.isfinite(w) else fmt(rpm(w))


def _torques(res: CheckResult, cf, tq, comp, comp_cf) -> list[dict]:
    """Given and computed torque per joint and operating point, which one each rule used, the
    cover factor at both; a bar chart of the cover factors the rules judged."""
    by_rule = {r.id: r for r in res.rules}
    used_by: dict[tuple[str, str], list[str]] = {}
    for r in res.results:
        rule = by_rule.get(r.rule)
        if rule is not None and rule.quantity == "joint.cover_factor" and r.case:
            used_by.setdefault((r.item, r.case), []).append(r.rule)
    src = tq.detail.source
    spd = tq.detail.speed
    given = {(t.joint, t.point): t for t in res.engine.joint_torques}
    rows = []
    for i, n in enumerate(cf.coords["item"]):
        for k, p in enumerate(cf.coords["point"]):
            t = given.get((n, p))
            g = "-" if t is None else f"{fmt(t.torque)} ({_rpm(t.speed)} rpm)"
            if comp is None:
                c = "not computed (the torsional module was not needed by the selected rules)"
                c_cf = "-"
            elif np.isfinite(comp.values[i, k]):
                case = case_text(str(comp.detail.case[i, k]))
                c = (f"{fmt(comp.values[i, k])} ({case}, {_rpm(comp.detail.speed[i, k])}"
                     " rpm)")
                c_cf = "-" if comp_cf is None else fmt(comp_cf.values[i, k])
            else:
                c = "not computed: " + "; ".join(comp.missing.get((i, k), []))
                c_cf = "-"
            s = src[i, k] if src is not None and src[i, k] else ""
            used = ("given" if s.startswith("workbook") else "computed" if s else
                    "not available: " + "; ".join(tq.missing.get((i, k), [])))
            if s:
                used += f": {fmt(tq.values[i, k])} N·m at {_rpm(spd[i, k])} rpm"
            rules = ", ".join(used_by.get((n, p), [])) or "none (not judged)"
            rows.append([n, p, g, c, used, rules, fmt(cf.values[i, k]), c_cf])
    blocks: list[dict] = [{"type": "heading", "text": "Cover factors"}, {
        "type": "table",
        "caption": "Applied torque per operating point: the value given in sheet JointTorques,"
                   " the torsional model's value at the same operating point ('tv peak': the"
                   " model's own peak speed), the one the cover-factor rules used, and the"
                   " cover factor at each (JNT-008 warns when the computed torque exceeds the"
                   " given one)",
        "columns": ["joint", "operating point", "given T [N·m]", "computed T [N·m]",
                    "used by the rules", "rules", "cover factor (used T)",
                    "cover factor (computed T)"],
        "rows": rows, "widths": [10, 10, 13, 18, 16, 11, 11, 11]}]
    status = {}
    limits: dict[tuple[str, str], list[float]] = {}
    for r in res.results:
        rule = by_rule.get(r.rule)
        if rule is None or rule.quantity != "joint.cover_factor" or not r.case:
            continue
        key = (r.item, r.case)
        st = ("FAIL" if r.status == "fail" and r.severity == "error" else
              "WARN" if r.status == "fail" else "PASS" if r.status == "pass" else
              "NOT EVALUATED")
        rank = ["PASS", "NOT EVALUATED", "WARN", "FAIL"]
        if rank.index(st) > rank.index(status.get(key, "PASS")) or key not in status:
            status[key] = st
        if r.limit_values:
            limits.setdefault(key, []).append(r.limit_values[0])
    labels, vals, alt, colors, lims = [], [], [], [], []
    for i, n in enumerate(cf.coords["item"]):
        for k, p in enumerate(cf.coords["point"]):
            if np.isfinite(cf.values[i, k]):
                labels.append(f"{n}, {p}")
                vals.append(cf.values[i, k])
                st = status.get((n, p), "NOT JUDGED")
                colors.append(STATUS_COLORS[st])
                lims.append(limits.get((n, p), []))
                differs = (comp_cf is not None and src is not None
                           and str(src[i, k]).startswith("workbook")
                           and np.isfinite(comp_cf.values[i, k]))
                alt.append(comp_cf.values[i, k] if differs else np.nan)
    if vals:
        blocks.append({"type": "figure", "png": later(
            (170, 22 + 8 * len(vals)), _draw_cover_factors, vals, labels, colors, lims, alt),
                       "data": ["joint.cover_factor", "joint.computed_cover_factor"],
                       "caption": "Joint cover factors coloured by the result of their rules,"
                                  " with each rule's limit (red mark); diamonds: at the"
                                  " torsional model's torque where a given torque was used."})
    return blocks


def _draw_cover_factors(vals, labels, colors, lims, alt) -> bytes:
    """Bars of the joints' cover factors ``vals`` (``labels``; ``colors`` by the status of
    their rules; ``lims``: each bar's rule limits; ``alt``: at the torsional model's torque)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    fig, ax = figure(170, 22 + 8 * len(vals), left=34, bottom=10, legend_rows=2)
    y = np.arange(len(vals))
    ax.barh(y, vals, color=colors, height=0.55)
    for yi, ls in zip(y, lims):
        for v in ls:
            ax.plot([v, v], [yi - 0.42, yi + 0.42], color="#c0392b", lw=1.4)
    if np.isfinite(alt).any():
        ax.plot(alt, y, "D", color="#34495e", ms=3.5, ls="none")
    ax.set_yticks(y, [literal(x) for x in labels])
    ax.set_xlabel("Cover factor (slip torque capacity / applied torque)")
    ax.set_ylim(len(vals) - 0.5, -0.5)
    ax.grid(axis="x", alpha=0.3)
    ax.grid(axis="y", visible=False)
    used = dict.fromkeys(c for c in colors)
    names = {v: k.lower() for k, v in STATUS_COLORS.items()}
    handles = [Patch(color=c, label=f"{names[c]} (at the torque the rules used)"
                     if names[c] != "not judged" else "no rule at this point")
               for c in used]
    handles.append(Line2D([], [], color="#c0392b", lw=1.4, label="limit of the rule"))
    if np.isfinite(alt).any():
        handles.append(Line2D([], [], marker="D", color="#34495e", ms=3.5, ls="none",
                              label="at the torsional model's torque"))
    legend_below(fig, handles=handles, labels=[h.get_label() for h in handles], ncols=3)
    return to_image(fig)
