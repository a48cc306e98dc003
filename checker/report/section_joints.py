"""Report section: bolted joints."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..units import from_si
from .plots import LIMIT_STYLE, figure, literal, to_svg
from .sections import fmt, section


@section("joints")
def joints_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    eng = res.engine
    blocks: list[dict] = []
    rows = []
    for j in eng.joints:
        rows.append([
            j.name, j.location, str(j.bolts), fmt(j.diameter * 1e3), fmt(j.pitch * 1e3),
            j.property_class, j.tightening,
            fmt(j.tightening_torque) if j.tightening_torque is not None else "-",
            f"{fmt(j.face_inner * 1e3)} / {fmt(j.face_outer * 1e3)}",
            "-" if j.head_outer is None or j.head_inner is None
            else f"{fmt(j.head_inner * 1e3)} / {fmt(j.head_outer * 1e3)}",
            j.clamped_material or "-",
            fmt(j.friction) if j.friction is not None else "0.2 (default)",
        ])
    blocks.append({"type": "table", "caption": "Joint inputs (sheet Joints)",
                   "columns": ["joint", "location", "bolts", "d [mm]", "p [mm]", "class",
                               "tightening", "T [N m]", "face d/D [mm]", "head d/D [mm]",
                               "clamped", "μ"],
                   "rows": rows})
    blocks.append({"type": "equations", "items": [
        ("Tensile stress area", "A_s = π/4 · (d − c·p)²,  c = 0.9382", "ISO 898-1:2013 §9.1.6.1;"
         " the seed's crank-nose worksheet uses c = 0.938"),
        ("Preload, torque tightening", "F = T / (K·d),  K = 0.2", "Ricardo 2013 (seed 000),"
         " slide 23: F = 5 T / D"),
        ("Preload, yield/angle/torque-wrench", "F = k·σ_ref·A_s,  k = 0.75 / 0.85 R_p0.2,"
         " 0.70 S_p", "Ricardo 2013 (seed 000), slide 24 table"),
        ("Proof-stress percentage", "100 · F / (P·A_s),  P = R_p0.2", "Ricardo 2013 (seed 000)"
         " slide 23; 70–75 % recommended"),
        ("Contact stress under the head", "σ = F / (π/4 · (d_o² − d_i²))", "Ricardo 2013"
         " (seed 000) slide 23; VDI 2230-1 R10"),
        ("Slip torque capacity", "T_cap = μ·n·F·(2/3)(R³ − r³)/(R² − r²) = μ·n·F·D_eff/2",
         "Ricardo 2013 (seed 000) slides 23–24"),
        ("Cover factor", "CF = T_cap / T_applied", "Ricardo 2013 (seed 000): crank nose ≥ 1.8"
         " (2.0 preferred); flywheel ≥ 1.8 TV peak, ≥ 2.0 max power, ≥ 1.7 overspeed"),
    ]})
    area = q.get("joint.stress_area")
    if area is not None:
        names = area.coords["item"]
        pre, clamp = q["joint.preload"].values, q["joint.clamp_force"].values
        proof, head = q["joint.proof_stress_ratio"].values, q["joint.head_contact_stress"].values
        deff, cap = q["joint.effective_diameter"].values, q["joint.slip_capacity"].values
        rows = []
        for i, n in enumerate(names):
            rows.append([n, fmt(area.values[i] * 1e6, 6), fmt(pre[i] / 1e3, 6),
                         fmt(clamp[i] / 1e3, 6), fmt(proof[i] * 100, 5),
                         fmt(head[i] / 1e6, 6), fmt(deff[i] * 1e3, 5), fmt(cap[i], 6)])
        blocks.append({"type": "table", "caption": "Bolt and face results",
                       "columns": ["joint", "A_s [mm²]", "F per bolt [kN]", "clamp [kN]",
                                   "proof stress [%]", "head stress [MPa]", "D_eff [mm]",
                                   "T_cap [N m]"],
                       "rows": rows})
        how = area.extra.get("how", {})
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
                     " after the worked calculations of Ricardo 2013 (seed 000).",
            "blocks": blocks}


def _rpm(w) -> str:
    return "-" if w is None or not np.isfinite(w) else fmt(from_si(w, "rad/s", "rpm"), 5)


def _torques(res: CheckResult, cf, tq, comp, comp_cf) -> list[dict]:
    """Given and computed torque per joint and operating point, which one each rule used, the
    cover factor at both; a bar chart of the cover factors the rules judged."""
    by_rule = {r.id: r for r in res.rules}
    used_by: dict[tuple[str, str], list[str]] = {}
    for r in res.results:
        rule = by_rule.get(r.rule)
        if rule is not None and rule.quantity == "joint.cover_factor" and r.case:
            used_by.setdefault((r.item, r.case), []).append(r.rule)
    src = tq.extra.get("source")
    spd = tq.extra.get("speed")
    given = {(t.joint, t.point): t for t in res.engine.joint_torques}
    rows = []
    for i, n in enumerate(cf.coords["item"]):
        for k, p in enumerate(cf.coords["point"]):
            t = given.get((n, p))
            g = "-" if t is None else f"{fmt(t.torque, 5)} ({_rpm(t.speed)} rpm)"
            if comp is None:
                c = "not computed (the torsional module was not needed by the selected rules)"
                c_cf = "-"
            elif np.isfinite(comp.values[i, k]):
                case = {"full": "full load", "no": "no load"}.get(
                    str(comp.extra["case"][i, k]), str(comp.extra["case"][i, k]))
                c = (f"{fmt(comp.values[i, k], 5)} ({case}, {_rpm(comp.extra['speed'][i, k])}"
                     " rpm)")
                c_cf = "-" if comp_cf is None else fmt(comp_cf.values[i, k], 4)
            else:
                c = "not computed: " + "; ".join(comp.missing.get((i, k), []))
                c_cf = "-"
            s = src[i, k] if src is not None and src[i, k] else ""
            used = ("given" if s.startswith("workbook") else "computed" if s else
                    "not available: " + "; ".join(tq.missing.get((i, k), [])))
            if s:
                used += f": {fmt(tq.values[i, k], 5)} N m at {_rpm(spd[i, k])} rpm"
            rules = ", ".join(used_by.get((n, p), [])) or "none (not judged)"
            rows.append([n, p, g, c, used, rules, fmt(cf.values[i, k], 4), c_cf])
    blocks: list[dict] = [{
        "type": "table",
        "caption": "Applied torque per operating point: the value given in sheet JointTorques,"
                   " the torsional model's value at the same operating point ('tv peak': the"
                   " model's own peak speed), the one the cover-factor rules used, and the"
                   " cover factor at each (JNT-008 warns when the computed torque exceeds the"
                   " given one)",
        "columns": ["joint", "operating point", "given T [N m]", "computed T [N m]",
                    "used by the rules", "rules", "cover factor (used T)",
                    "cover factor (computed T)"],
        "rows": rows}]
    labels, vals, alt = [], [], []
    judged = []
    for i, n in enumerate(cf.coords["item"]):
        for k, p in enumerate(cf.coords["point"]):
            if np.isfinite(cf.values[i, k]):
                labels.append(f"{n}\n{p}")
                vals.append(cf.values[i, k])
                judged.append(bool(used_by.get((n, p))))
                differs = (comp_cf is not None and src is not None
                           and str(src[i, k]).startswith("workbook")
                           and np.isfinite(comp_cf.values[i, k]))
                alt.append(comp_cf.values[i, k] if differs else np.nan)
    if vals:
        fig, ax = figure(170, 30 + 12 * len(vals))
        y = np.arange(len(vals))
        jb = np.array(judged)
        ax.barh(y[jb], np.array(vals)[jb], color="#34495e", height=0.5,
                label="at the torque the rules used")
        if (~jb).any():
            ax.barh(y[~jb], np.array(vals)[~jb], color="#bdc3c7", height=0.5,
                    label="no rule at this operating point (not judged)")
        if np.isfinite(alt).any():
            ax.plot(alt, y, "D", color="#e67e22", ms=4, ls="none",
                    label="at the torsional model's torque (given torque used)")
        ax.set_yticks(y, [literal(x) for x in labels])
        for lim, lab in ((1.7, "1.7 overspeed"), (1.8, "1.8 minimum"),
                         (2.0, "2.0 preferred / max power")):
            ax.axvline(lim, **LIMIT_STYLE)
            ax.text(lim, -0.45, lab, rotation=90, va="top", ha="right",
                    fontsize=6, color=LIMIT_STYLE["color"])
        ax.set_xlabel("Cover factor (slip torque capacity / applied torque)")
        ax.set_ylim(len(vals) - 0.5, -0.5)
        ax.legend(fontsize=6, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=2,
                  frameon=False)
        blocks.append({"type": "figure", "svg": to_svg(fig),
                       "caption": "Joint cover factors against the seed's limits (dark bars: at"
                                  " the torque the rules used; grey bars: operating points no"
                                  " rule judges; diamonds: at the torsional model's torque"
                                  " where a given torque was used)"})
    return blocks
