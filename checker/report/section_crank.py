"""Report section: the crank as the tool understood it (sheet Crank): a to-scale drawing of each
distinct throw, its derived mass properties and stiffness, and the model the analyses use with
each value's origin (typed or derived) and method."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from .plots import figure, later, to_image
from .sections import fmt, section


def _outline(t, radius: float, n: int = 721) -> tuple[np.ndarray, np.ndarray]:
    """End-view outline of a throw's web (x, y) [mm], by its radial function."""
    from ..calc.crank_geometry import web_radius

    th = np.linspace(0.0, 2.0 * np.pi, n)
    r = web_radius(th, width_journal=t.web_width_journal, width_pin=t.web_width_pin,
                   crank_radius=radius)
    return r * np.sin(th) * 1e3, r * np.cos(th) * 1e3


def _sector(t) -> tuple[np.ndarray, np.ndarray]:
    """End-view outline of the counterweight's annular sector (x, y) [mm]."""
    h = t.cw_angle / 2.0
    a = np.linspace(np.pi - h, np.pi + h, 121)
    x = np.concatenate([t.cw_outer_radius * np.sin(a), t.cw_inner_radius * np.sin(a[::-1])])
    y = np.concatenate([t.cw_outer_radius * np.cos(a), t.cw_inner_radius * np.cos(a[::-1])])
    return np.append(x, x[0]) * 1e3, np.append(y, y[0]) * 1e3


def _circle(d: float, yc: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    a = np.linspace(0.0, 2.0 * np.pi, 181)
    return d / 2 * np.sin(a) * 1e3, (yc + d / 2 * np.cos(a)) * 1e3


def _drawing(crank, throws) -> bytes:
    """End view and side view, to scale (equal axes), of each distinct throw."""
    import matplotlib.patches as mp

    fig, axes = figure(170, 62 * len(throws), nrows=len(throws), ncols=2)
    axes = np.atleast_2d(axes)
    r = crank.crank_radius
    for row, (numbers, t) in enumerate(throws):
        ax = axes[row, 0]
        if t.has_counterweight:
            ax.fill(*_sector(t), color="0.75", lw=0.6, ec="0.3", label="counterweight")
        ax.fill(*_outline(t, r), color="0.88", lw=0.8, ec="0.2", label="web")
        ax.plot(*_circle(t.journal_diameter), color="C0", lw=1.0, label="main journal")
        ax.plot(*_circle(t.pin_diameter, r), color="C3", lw=1.0, label="crank pin")
        for d, yc, c in ((t.journal_bore, 0.0, "C0"), (t.pin_bore, r, "C3")):
            if d > 0:
                ax.plot(*_circle(d, yc), color=c, lw=0.6, ls="--")
        ax.plot([0], [0], "+", color="C0")
        ax.plot([0], [r * 1e3], "+", color="C3")
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_title(f"throw {numbers}: end view", fontsize=8)
        ax = axes[row, 1]
        z = 0.0
        tc = (t.cw_thickness or t.web_thickness) if t.has_counterweight else 0.0
        parts = [(t.journal_length / 2, -t.journal_diameter / 2, t.journal_diameter, "C0"),
                 (t.web_thickness, None, None, "0.5"),
                 (t.pin_length, r - t.pin_diameter / 2, t.pin_diameter, "C3"),
                 (t.web_thickness, None, None, "0.5"),
                 (t.journal_length / 2, -t.journal_diameter / 2, t.journal_diameter, "C0")]
        top = r + t.web_width_pin / 2
        bottom = -max(t.web_width_journal / 2, t.cw_outer_radius if tc else 0.0)
        for length, y0, h, c in parts:
            if y0 is None:  # web: its outline's extent in y; the counterweight below
                ax.add_patch(mp.Rectangle((z * 1e3, -t.web_width_journal / 2 * 1e3),
                                          length * 1e3, (top + t.web_width_journal / 2) * 1e3,
                                          fc="0.88", ec="0.2", lw=0.8))
                if tc:
                    zc = z + length / 2 - tc / 2
                    ax.add_patch(mp.Rectangle((zc * 1e3, -t.cw_outer_radius * 1e3), tc * 1e3,
                                              (t.cw_outer_radius - t.cw_inner_radius) * 1e3,
                                              fc="0.75", ec="0.3", lw=0.6))
            else:
                ax.add_patch(mp.Rectangle((z * 1e3, y0 * 1e3), length * 1e3, h * 1e3,
                                          fc="none", ec=c, lw=1.0))
            z += length
        ax.axhline(0.0, color="C0", lw=0.5, ls="-.")
        ax.axhline(r * 1e3, color="C3", lw=0.5, ls="-.")
        ax.set_xlim(-5, z * 1e3 + 5)
        ax.set_ylim(bottom * 1e3 - 5, top * 1e3 + 5)
        ax.set_aspect("equal")
        ax.set_xlabel("z from the front journal mid-plane [mm]")
        ax.set_title(f"throw {numbers}: side view", fontsize=8)
    return to_image(fig)


@section("crank", "crank geometry")
def crank_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    qm, qj, qk = (q.get(f"crank.throw_{n}") for n in ("mass", "inertia", "stiffness"))
    title = "Crank geometry"
    crank = res.engine.crank
    if qm is None or crank is None:
        why = "; ".join(res.outcome.unavailable.get("crank.throw_mass", ["not computed"]))
        return {"id": "crank", "title": title, "intro": f"Not computed: {why}.", "blocks": []}
    ex = qm.detail
    distinct: list[tuple[str, object]] = []
    for t in crank.throws:
        key = {k: v for k, v in t.__dict__.items() if k != "number"}
        for i, (nums, u) in enumerate(distinct):
            if {k: v for k, v in u.__dict__.items() if k != "number"} == key:
                distinct[i] = (f"{nums}, {t.number}", u)
                break
        else:
            distinct.append((str(t.number), t))
    drawing = later((170, 62 * len(distinct)), _drawing, crank, list(distinct))
    blocks: list[dict] = [{"type": "figure", "png": drawing,
                           "data": ["crank.throw_mass"],
                           "caption": "Each distinct throw to scale as the check models it:"
                                      " webs (convex hull of the two web circles),"
                                      " counterweights (annular sectors opposite the pin),"
                                      " journals and pin (dashed: bores); fillets, undercuts,"
                                      " oil holes and lightening are not part of the solid"}]
    qa = q.get("crank.assembled_stiffness")
    rows = []
    for i, item in enumerate(qm.coords["item"]):
        k = qk.values[i]
        ka = qa.values[i] if qa is not None else np.nan
        rows.append([item, fmt(qm.values[i], 4), fmt(qj.values[i], 4),
                     fmt(k / 1e3, 4) if np.isfinite(k) else "-",
                     fmt(ka / 1e3, 4) if np.isfinite(ka) else "-",
                     "yes" if ex.stiffness_in_range[i] else "no"])
    err = ("" if ex.stiffness_error is None
           else f"; stated model error ±{ex.stiffness_error * 100:.1f} %")
    blocks.append({"type": "table", "caption": "Each throw between its journal mid-planes, from"
                   " its geometry (crank alone; also where typed values win). Stiffness: "
                   + (ex.stiffness_method or "not available") + err + ". In the assembled"
                   " crank: each throw's stiffness on its main bearings, which the torsional"
                   " model uses (its neighbours and bearings hold the journals' tilt)",
                   "columns": ["throw", "mass [kg]", "inertia about the main axis [kg m²]",
                               "torsional stiffness [kN m/rad]",
                               "in the assembled crank [kN m/rad]", "in fitted range"],
                   "rows": rows})
    parts = []
    for nums, t in distinct:
        j = t.number - 1
        for p, name in enumerate(ex.parts):
            if ex.part_mass[j, p] <= 0:
                continue
            parts.append([nums, name, fmt(ex.part_mass[j, p], 4),
                          fmt(ex.part_y[j, p] * 1e3, 4), fmt(ex.part_z[j, p] * 1e3, 4),
                          fmt(ex.part_inertia[j, p], 4), fmt(ex.part_inertia_own[j, p], 4)])
    blocks.append({"type": "table", "caption": "Mass properties of every part (exact for the"
                   " stated geometry: closed forms and Green's theorem on the web outline);"
                   " y towards the pin, z from the front journal mid-plane",
                   "columns": ["throw", "part", "mass [kg]", "y [mm]", "z [mm]",
                               "J main axis [kg m²]", "J own centre [kg m²]"],
                   "rows": parts, "detail": True, "sheet": "Crank parts"})
    model, methods = [], []
    for m in ex.model:
        unit = {"inertia": "kg m²", "stiffness": "N m/rad"}.get(m["attr"], "mm")
        scale = 1e3 if unit == "mm" else 1.0
        if m["method"] not in methods:  # one note per distinct method, below the table
            methods.append(m["method"])
        diff = ("" if m["derived"] in (None, 0) or m["origin"] != "typed"
                else f"{(m['value'] / m['derived'] - 1) * 100:+.1f} %")
        model.append([f"{m['sheet']}: {m['item']}",
                      f"{m['attr'].replace('_', ' ')} [{unit}]",
                      fmt(m["value"] * scale, 5), f"{m['origin']} ({m['cell']})",
                      fmt(None if m["derived"] is None else m["derived"] * scale, 5), diff,
                      f"[{methods.index(m['method']) + 1}]"])
    blocks.append({"type": "table", "caption": "The crank model the analyses use: each value"
                   " typed in the workbook (it wins) or derived from sheet Crank, with the"
                   " derived value beside a typed one, the typed value's difference from it"
                   " and how it is derived (the methods below)",
                   "columns": ["station / element", "quantity", "used", "origin (cell)",
                               "derived", "typed vs derived", "method"], "rows": model})
    if methods:
        blocks.append({"type": "text", "text": "Methods: " + "; ".join(
            f"[{k + 1}] {m or 'not derivable from the geometry'}"
            for k, m in enumerate(methods)) + "."})
    return {"id": "crank", "title": title,
            "intro": "The crank described once, by its main dimensions (sheet Crank): crank"
                     " axis z, main axis at x = y = 0, pin axis at (0, stroke/2); a throw runs"
                     " between the mid-planes of its two main journals (half journal, web,"
                     " pin, web, half journal). From it the check derives the bearings'"
                     " journal sizes, the fatigue web geometry, the crank masses for the"
                     " balance and the torsional model's throw inertias and stiffnesses; a"
                     " value typed in TVModel, CrankMass, Bearings or Fatigue wins (or, for the"
                     " same dimension, must agree). The idealised geometry has no lightening,"
                     " chamfers or the real web outline: against a published model of the real"
                     " crank its inertias and stiffnesses differ by far more than the"
                     f" stiffness model's own error{err.replace('; stated model error', '')}.",
            "blocks": blocks}
