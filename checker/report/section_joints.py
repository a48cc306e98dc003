"""Report section: bolted joints."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..units import from_si
from .plots import LIMIT_STYLE, figure, to_svg
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
        rows = []
        src = tq.extra.get("source")
        spd = tq.extra.get("speed")
        for i, n in enumerate(cf.coords["item"]):
            for k, p in enumerate(cf.coords["point"]):
                s = "-" if spd is None or not np.isfinite(spd[i, k]) else fmt(
                    from_si(spd[i, k], "rad/s", "rpm"), 5)
                rows.append([n, p, s, fmt(tq.values[i, k], 5),
                             (src[i, k] if src is not None and src[i, k] else "not available"),
                             fmt(cf.values[i, k], 4)])
        blocks.append({"type": "table", "caption": "Applied torque and cover factor per"
                       " operating point", "columns": ["joint", "operating point",
                                                       "speed [rpm]", "T_applied [N m]",
                                                       "source", "cover factor"],
                       "rows": rows})
        labels, vals = [], []
        for i, n in enumerate(cf.coords["item"]):
            for k, p in enumerate(cf.coords["point"]):
                if np.isfinite(cf.values[i, k]):
                    labels.append(f"{n}\n{p}")
                    vals.append(cf.values[i, k])
        if vals:
            fig, ax = figure(170, 25 + 12 * len(vals))
            y = np.arange(len(vals))
            ax.barh(y, vals, color="#34495e", height=0.5)
            ax.set_yticks(y, labels)
            for lim, lab in ((1.7, "1.7 overspeed"), (1.8, "1.8 minimum"),
                             (2.0, "2.0 preferred / max power")):
                ax.axvline(lim, **LIMIT_STYLE)
                ax.text(lim, len(vals) - 0.4, lab, rotation=90, va="top", ha="right",
                        fontsize=6, color=LIMIT_STYLE["color"])
            ax.set_xlabel("Cover factor (slip torque capacity / applied torque)")
            ax.invert_yaxis()
            blocks.append({"type": "figure", "svg": to_svg(fig),
                           "caption": "Joint cover factors against the seed's limits"})
    return {"id": "joints", "title": "Bolted joints",
            "intro": "Crank-nose and flywheel bolted joints: bolt preload and proof-stress"
                     " percentage, contact stress under the bolt head, and the cover factor of"
                     " the clamped face (slip torque capacity over the peak applied torque),"
                     " after the worked calculations of Ricardo 2013 (seed 000).",
            "blocks": blocks}
