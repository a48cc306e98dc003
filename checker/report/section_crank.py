"""Report section: the crank as the tool understood it (sheet Crank).

To-scale drawings of each distinct throw (end view and side view, with counterweights), each
throw's mass, inertia and stiffness from its geometry with the stated model error, and every
value of the crank model the analyses use: typed (the workbook's cell wins) or derived (with its
method), the derived value beside a typed one.
"""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from .plots import figure, to_image
from .sections import fmt, section

UNITS = {"inertia": ("kg m²", 1.0), "stiffness": ("N m/rad", 1.0), "mass": ("kg", 1.0)}
"""Display unit and factor from SI of the crank model's attributes; lengths in mm."""


def _value(attr: str, v: float | None) -> tuple[str, str]:
    if v is None:
        return "-", ""
    unit, k = UNITS.get(attr, ("mm", 1e3))
    return fmt(float(v) * k), unit


def _hull(bj: float, bp: float, r: float, n: int = 180) -> np.ndarray:
    """Outline of the convex hull of the two web circles (journal circle at the origin, pin
    circle at (0, r)), counter-clockwise, for drawing."""
    from scipy.spatial import ConvexHull

    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    pts = np.concatenate([np.column_stack([bj / 2 * np.sin(t), bj / 2 * np.cos(t)]),
                          np.column_stack([bp / 2 * np.sin(t), r + bp / 2 * np.cos(t)])])
    h = ConvexHull(pts)
    loop = pts[h.vertices]
    return np.vstack([loop, loop[:1]])


def _sector(ri: float, ro: float, alpha: float, n: int = 60) -> np.ndarray:
    """Annular sector about the main axis bisected by -y."""
    t = np.linspace(np.pi - alpha / 2, np.pi + alpha / 2, n)
    outer = np.column_stack([ro * np.sin(t), ro * np.cos(t)])
    inner = np.column_stack([ri * np.sin(t[::-1]), ri * np.cos(t[::-1])])
    loop = np.vstack([outer, inner])
    return np.vstack([loop, loop[:1]])


def _circle(ax, cx: float, cy: float, d: float, **kw) -> None:
    t = np.linspace(0, 2 * np.pi, 120)
    ax.plot(cx + d / 2 * np.sin(t), cy + d / 2 * np.cos(t), **kw)


def throw_figure(t, r: float) -> str:
    """End view (along the crank axis, pin up) and side view (the plane of the pin) of one
    throw, to scale in mm."""
    mm = 1e3
    fig, (end, side) = figure(170, 78, ncols=2, wgap=14, left=14, bottom=12)
    web = "#c9d6e3"
    cw = "#e3d3b8"
    line = {"color": "#333333", "lw": 0.7}
    if t.has_counterweight:
        sec = _sector(t.cw_inner_radius, t.cw_outer_radius, t.cw_angle) * mm
        end.fill(sec[:, 0], sec[:, 1], color=cw, zorder=1)
        end.plot(sec[:, 0], sec[:, 1], **line)
    hull = _hull(t.web_width_journal, t.web_width_pin, r) * mm
    end.fill(hull[:, 0], hull[:, 1], color=web, zorder=2)
    end.plot(hull[:, 0], hull[:, 1], **line)
    for cy, d, b in ((0.0, t.journal_diameter, t.journal_bore),
                     (r, t.pin_diameter, t.pin_bore)):
        _circle(end, 0.0, cy * mm, d * mm, **line)
        if b > 0:
            _circle(end, 0.0, cy * mm, b * mm, color="#333333", lw=0.5, ls="--")
    end.plot([0], [0], "+", color="k", ms=5)
    end.plot([0], [r * mm], "+", color="k", ms=5)
    end.set_aspect("equal")
    end.set_title("end view (pin up)", fontsize=7)
    end.set_xlabel("x [mm]")
    end.set_ylabel("y [mm]")
    # side view: z along the crank axis, y towards the pin
    lj, tw, lp = t.journal_length, t.web_thickness, t.pin_length
    z = np.cumsum([0.0, lj / 2, tw, lp, tw, lj / 2])
    y_web_lo = -t.web_width_journal / 2
    y_web_hi = r + t.web_width_pin / 2

    def box(z0, z1, y0, y1, color, zo=2):
        zz = np.array([z0, z1, z1, z0, z0]) * mm
        yy = np.array([y0, y0, y1, y1, y0]) * mm
        side.fill(zz, yy, color=color, zorder=zo)
        side.plot(zz, yy, **line, zorder=zo + 1)

    shaft = "#d9d9d9"
    for z0, z1 in ((z[0], z[1]), (z[4], z[5])):
        box(z0, z1, -t.journal_diameter / 2, t.journal_diameter / 2, shaft)
    box(z[2], z[3], r - t.pin_diameter / 2, r + t.pin_diameter / 2, shaft)
    for z0 in (z[1], z[3]):
        if t.has_counterweight:
            tc = t.cw_thickness or tw
            zc = z0 + tw / 2
            y_in = -t.cw_inner_radius * np.cos(min(t.cw_angle, np.pi) / 2)
            box(zc - tc / 2, zc + tc / 2, -t.cw_outer_radius, min(y_in, 0.0), cw, 1)
        box(z0, z0 + tw, y_web_lo, y_web_hi, web)
    side.axhline(0.0, color="k", lw=0.5, ls="-.")
    side.axhline(r * mm, color="k", lw=0.5, ls="-.")
    side.set_aspect("equal")
    side.set_title("side view (plane of the pin)", fontsize=7)
    side.set_xlabel("z from the front journal mid-plane [mm]")
    return to_image(fig)


def _distinct(throws) -> list[list]:
    """Throws grouped by identical dimensions (each group drawn once)."""
    groups: list[list] = []
    for t in throws:
        key = {k: v for k, v in vars(t).items() if k != "number"}
        for g in groups:
            if {k: v for k, v in vars(g[0]).items() if k != "number"} == key:
                g.append(t)
                break
        else:
            groups.append([t])
    return groups


@section("crank", "crank geometry")
def crank_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    title = "Crank geometry and its model"
    crank = res.engine.crank
    mass = q.get("crank.throw_mass")
    if crank is None or mass is None:
        why = "; ".join(res.outcome.unavailable.get("crank.throw_mass", ["not computed"]))
        return {"id": "crank", "title": title, "intro": f"Not computed: {why}.", "blocks": []}
    inertia, stiff = q["crank.throw_inertia"], q.get("crank.throw_stiffness")
    d = mass.detail
    blocks: list[dict] = []
    for group in _distinct(crank.throws):
        t = group[0]
        nums = ", ".join(str(g.number) for g in group)
        blocks.append({"type": "figure", "png": throw_figure(t, crank.crank_radius),
                       "caption": f"Throw{'s' if len(group) > 1 else ''} {nums} to scale:"
                                  " webs (blue) as the convex hull of their two circles,"
                                  " counterweights (sand) as annular sectors opposite the pin,"
                                  " journal and pin (grey) with their bores dashed; the main"
                                  " and pin axes dash-dotted (the geometry of the documentation,"
                                  " crank geometry). Fillets, undercuts and lightening are not"
                                  " drawn: they are not part of the mass and stiffness solid."})
    rows = []
    for i, item in enumerate(mass.coords["item"]):
        k = "-" if stiff is None else fmt(float(stiff.values[i]) * 1e-3)
        rng = ("" if stiff is None or d.stiffness_in_range[i] else " (outside the fitted"
               " range: extrapolated)")
        rows.append([item, fmt(float(mass.values[i])), fmt(float(inertia.values[i])), k + rng])
    err = ("" if d.stiffness_error is None else f" Stated error of the stiffness model: within"
           f" {d.stiffness_error * 100:.1f} % of a linear-elastic 3D FE of the same geometry"
           " over its fitted range.")
    blocks.append({"type": "table", "caption": "Each throw between its journal mid-planes,"
                   " crank alone, from its geometry (also where typed values win in the"
                   f" analyses). Stiffness: {d.stiffness_method}.{err}",
                   "columns": ["throw", "mass [kg]", "inertia [kg m²]",
                               "stiffness [kN m/rad]"], "rows": rows})
    model = d.model
    if model:
        rows, methods = [], []
        for m in model:
            v, unit = _value(m["attr"], m["value"])
            dv, _ = _value(m["attr"], m["derived"])
            diff = ("" if m["derived"] in (None, 0) or m["origin"] != "typed" else
                    f"{(m['value'] / m['derived'] - 1) * 100:+.1f} %")
            # one line per distinct method (the per-throw numbers in it stripped of the throw)
            key = m["method"]
            if key not in methods:
                methods.append(key)
            rows.append([m["sheet"], m["item"], m["attr"].replace("_", " "), f"{v} {unit}",
                         m["origin"], dv, diff, f"[{methods.index(key) + 1}]", m["cell"]])
        blocks.append({"type": "table", "caption": "The crank model the analyses use: each value"
                       " typed (its cell wins) or derived from the geometry, the derived value"
                       " beside a typed one and the typed value's difference from it (methods"
                       " below)",
                       "columns": ["sheet", "item", "value of", "used", "origin", "derived",
                                   "typed vs derived", "method", "cell"], "rows": rows})
        blocks.append({"type": "text", "text": "Methods: " + "; ".join(
            f"[{k + 1}] {m}" for k, m in enumerate(methods)) + "."})
    return {"id": "crank", "title": title,
            "intro": "The crank as sheet Crank describes it and as the analyses use it: the"
                     " geometry drawn to scale, each throw's mass properties (exact for the"
                     " stated geometry) and torsional stiffness, and every value of the"
                     " torsional, balance and fatigue model with its origin.",
            "blocks": blocks}
