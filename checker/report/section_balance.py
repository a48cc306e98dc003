"""Report section: crankshaft balancing (free forces and moments, balance ratio, internal
bending moment)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from .plots import LIMIT_STYLE, figure, later, to_image
from .sections import fmt, in_unit, rpm, section

ROUND_OFF = 1e-9
"""Magnitudes below this fraction of n_cyl m_rec r w^2 (N m for moments: times the crank
length) are zero to round-off and shown as 0."""


def _value(v: float, scale: float, digits: int = 5) -> str:
    if not np.isfinite(v):
        return "-"
    return "0" if abs(v) < ROUND_OFF * scale else fmt(v, digits)


@section("balance")
def balance_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    ff, fm = q.get("balance.free_force"), q.get("balance.free_moment")
    title = "Crankshaft balancing"
    if ff is None:
        why = "; ".join(res.outcome.unavailable.get("balance.free_force", ["not computed"]))
        return {"id": "balance", "title": title, "intro": f"Not computed: {why}.", "blocks": []}
    ex = ff.detail
    eng = res.engine
    n_cyl = len(eng.cylinders)
    w = ex.omega
    r = ex.crank_radius
    f_scale = n_cyl * ex.reciprocating_mass * r * w * w
    spacing = eng.params.get("main_spacing") or 0.0
    m_scale = f_scale * max(spacing * n_cyl, 1e-3)
    blocks: list[dict] = []
    lam = r / eng.params["rod_length"]
    blocks.append({"type": "table", "caption": "Inputs (sheets Engine, Cylinders, CrankMass)",
                   "columns": ["parameter", "value", "unit"], "rows": [
                       ["Reciprocating mass per cylinder (piston + rod small end)",
                        fmt(ex.reciprocating_mass, 4), "kg"],
                       ["Rotating rod mass per cylinder (big end)",
                        fmt(ex.rotating_rod_mass, 4), "kg"],
                       ["Crank radius r", fmt(_mm(r), 4), "mm"],
                       ["λ = r / l", fmt(lam, 4), "-"],
                       ["Reference speed: " + ex.speed_text, fmt(rpm(w), 5), "rpm"],
                       ["Main journal spacing (axial positions)",
                        fmt(_mm(spacing), 4) if spacing else "-", "mm"]]})
    blocks.append({"type": "equations", "items": [
        ("Free force, order n", "F_n = ω² Σ_i m_rec A_n e^(−j n φ_i) c_i + [n = 1] ω² Σ_k m_k ρ_k",
         "Taylor 1985, vol. 2, ch. 8 (phase-diagram summation); c_i = bore axis, A_n = piston"
         " acceleration harmonics of the exact kinematics"),
        ("Piston acceleration", "ẍ/(r ω²) = cos θ + (λ + λ³/4) cos 2θ − (λ³/4) cos 4θ + …",
         "Heywood 1988, eq. 2.5 expanded in λ = r/l"),
        ("Free moment, order n", "M_n = Σ z_i F_n,i  about the crank's mid-plane",
         "Taylor 1985, vol. 2, ch. 8"),
        ("Balance ratio", "BR_j = −U_cw,j · e_j / U_rot,j · e_j,  U = Σ m ρ",
         "counterweight / rotating unbalance of throw j (webs, pin, rod big end)"),
        ("Internal bending moment", "B(Z) = ω² Σ_(z_k < Z) m_k ρ_k (Z − z_k)",
         "moment of the centrifugal forces in front of main Z (rigid crank)"),
    ]})
    orders = ex.orders

    def angle(v: float, a: float, scale: float) -> str:
        if not np.isfinite(v) or v < ROUND_OFF * scale:
            return "-"
        return f"{round(float(in_unit(a, 'rad', 'deg')), 1) % 360 + 0.0:.1f}"

    rows = []
    for i, n in enumerate(orders):
        rows.append([str(n), _value(ff.values[i], f_scale),
                     _value(ex.smallest[i], f_scale),
                     angle(ff.values[i], ex.theta[i], f_scale),
                     angle(ff.values[i], ex.direction[i], f_scale),
                     _value(fm.values[i], m_scale),
                     angle(fm.values[i], fm.detail.theta[i], m_scale)])
    blocks.append({"type": "table", "caption": f"Free forces and moments at {rpm(w):.0f} rpm"
                   " (largest and smallest magnitude over the crank angle: equal for a force"
                   " rotating with the crank, smallest 0 for a force along a fixed line)",
                   "columns": ["order", "F max [N]", "F min [N]", "crank angle at max [deg]",
                               "direction [deg from cylinder axis]", "M max [N m]",
                               "crank angle at max [deg]"], "rows": rows})
    # bar chart, log scale, with the project's limits
    blocks.append({"type": "figure",
                   "png": later((170, 60), _draw_free, orders, ff, fm, f_scale, m_scale),
                   "data": ["balance.free_force", "balance.free_moment"],
                   "caption": f"Free forces and moments per order at {rpm(w):.0f} rpm (log"
                              " scale; '0' = zero to round-off; dashed: project limits)"})

    br = q.get("balance.balance_ratio")
    if br is not None and np.isfinite(br.values).all() and br.detail.rotating is not None:
        bx = br.detail
        ratio = in_unit(br.values, "", "%")
        rows = []
        for j in range(len(bx.rotating_along)):
            rows.append([f"throw {j + 1}",
                         fmt(in_unit(bx.throw_angle[j], "rad", "deg") % 360, 4),
                         fmt(_kg_mm(bx.rotating_along[j]), 5),
                         fmt(_kg_mm(bx.counterweight_along[j]), 5),
                         fmt(ratio[j], 4), fmt(in_unit(bx.reciprocating_factor[j], "", "%"), 4)])
        rows.append(["crank", "-", fmt(_kg_mm(bx.rotating_along.sum()), 5),
                     fmt(_kg_mm(bx.counterweight_along.sum()), 5), fmt(ratio[-1], 4), "-"])
        blocks.append({"type": "table", "caption": "Counterweight balance per throw (unbalance"
                       " along the throw direction)",
                       "columns": ["throw", "angle [deg]", "U rotating [kg mm]",
                                   "U counterweights [kg mm]", "balance ratio [%]",
                                   "reciprocating factor [%]"], "rows": rows})
        blocks.append({"type": "text", "text":
                       "Rotating unbalance of the whole crank with the rods' big ends: static"
                       f" {_value(_kg_mm(bx.static_unbalance), _kg_mm(r))} kg mm, couple"
                       f" {_value(_kg_mm2(bx.couple_unbalance), _kg_mm2(r * max(spacing, 1e-3)))}"
                       " kg mm². The reciprocating factor is the share of the reciprocating"
                       " unbalance m_rec·r the counterweights balance beyond the rotating"
                       " unbalance (negative: the rotating unbalance itself is not fully"
                       " balanced)."})
        # polar plot: per-throw unbalance in the crank frame (seen from the front)
        blocks.append({"type": "figure", "png": later((130, 72), _draw_polar, bx),
                       "data": ["balance.balance_ratio", "balance.internal_moment"],
                       "caption": "Polar diagram of each throw's unbalance seen from the front:"
                                  " net (arrows), without counterweights (circles) and of the"
                                  " counterweights alone (crosses)"})

    im = q.get("balance.internal_moment")
    if im is not None and np.isfinite(im.values).all() and (
            im.detail.without_counterweights is not None):
        wo = im.detail.without_counterweights
        top = max(float(wo.max()), float(im.values.max()))
        rows = [[n, fmt(_mm(im.detail.stations[k]), 4), _value(im.values[k], top),
                 _value(wo[k], top)]
                for k, n in enumerate(im.coords["item"])]
        blocks.append({"type": "table", "caption": f"Internal bending moment of the rotating"
                       f" masses at the mains, {rpm(w):.0f} rpm (rotates with the crank)",
                       "columns": ["main", "axial position [mm]", "with counterweights [N m]",
                                   "without counterweights [N m]"], "rows": rows})
    return {"id": "balance", "title": title,
            "intro": "Free (shaking) forces and moments of the crank train by order, from the"
                     " cylinders' firing and bank angles, the exact piston kinematics and the"
                     " crank masses; counterweight balance ratio per throw and the internal"
                     " bending moment that loads the mains (Taylor 1985, vol. 2, ch. 8). Free"
                     " forces and moments are judged only against the project's own limits"
                     " (warnings).",
            "blocks": blocks}


def _draw_free(orders, ff, fm, f_scale: float, m_scale: float) -> bytes:
    """Free forces and moments per order (bars, log scale) with the project's limits."""
    fig, axes = figure(170, 60, ncols=2)
    for ax, qq, scale, unit, lim_key in ((axes[0], ff, f_scale, "N", "force"),
                                         (axes[1], fm, m_scale, "N m", "moment")):
        v = np.where(np.isfinite(qq.values), qq.values, 0.0)
        shown = np.where(v < ROUND_OFF * scale, np.nan, v)
        lims = [qq.item_attrs.get(it, {}).get("limit") for it in qq.coords["item"]]
        if np.isfinite(shown).any():
            ax.bar(orders, np.nan_to_num(shown, nan=0.0), color="#34495e", width=0.6)
            ax.set_yscale("log")
            floor = max(np.nanmin(shown), 1e-3) / 3
            ax.set_ylim(bottom=floor)
        else:
            floor = 0.0
            ax.set_ylim(0, max([x[0] for x in lims if x is not None] + [1.0]) * 1.2)
        for i, n in enumerate(orders):
            if not np.isfinite(shown[i]):
                ax.text(n, floor * 1.3, "0", ha="center", fontsize=6)
        for n, lim in zip(orders, lims):
            if lim is not None:
                ax.plot([n - 0.4, n + 0.4], [lim[0]] * 2, **LIMIT_STYLE)
        ax.set_xticks(orders)
        ax.set_xlabel("Order")
        ax.set_ylabel(f"Free {lim_key} [{unit}]")
    fig.subplots_adjust(wspace=0.35)
    return to_image(fig)


def _polar(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unbalance vectors (x, y) [kg m] as polar angle from throw 1 [rad] and magnitude
    [kg mm]."""
    return np.arctan2(v[..., 0], v[..., 1]), _kg_mm(np.hypot(v[..., 0], v[..., 1]))


def _draw_polar(bx) -> bytes:
    """Polar diagram of each throw's unbalance in the crank frame, seen from the front."""
    fig = figure(130, 72)[0]
    fig.clf()
    ax = fig.add_axes((0.04, 0.1, 0.47, 0.8), projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    net = bx.rotating + bx.counterweight
    for vec in net:
        ang, mag = _polar(vec)
        ax.annotate("", xy=(ang, mag), xytext=(0, 0),
                    arrowprops={"arrowstyle": "->", "color": "#c0392b", "lw": 1.4})
    ax.plot([], [], color="#c0392b", label="net (with counterweights)")
    ax.plot(*_polar(bx.rotating), "o", mfc="none", color="#7f8c8d",
            label="rotating, without counterweights")
    ax.plot(*_polar(bx.counterweight), "x", color="#2c3e50", label="counterweights")
    groups: dict[float, list[str]] = {}  # throws sharing a direction share a label
    for j, vec in enumerate(bx.rotating):
        groups.setdefault(round(float(_polar(vec)[0]), 6), []).append(str(j + 1))
    top = max(_polar(bx.rotating)[1].max(), _polar(bx.counterweight)[1].max())
    for ang, labs in groups.items():
        ax.text(ang, top * 1.12, "throw " + ", ".join(labs), fontsize=6, ha="center",
                bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.5})
    ax.set_rmax(top * 1.25)
    ax.set_rlabel_position(22.5)
    ax.tick_params(axis="y", labelsize=5.5)
    ax.tick_params(axis="x", labelsize=6, pad=1)
    fig.legend(*ax.get_legend_handles_labels(), loc="center left",
               bbox_to_anchor=(0.58, 0.55), frameon=False, fontsize=6.5,
               title="radius: unbalance [kg mm]\ncrank frame, seen from the front,"
                     "\nthrow 1 up", title_fontsize=6.5, alignment="left")
    return to_image(fig)


def _mm(v):
    return in_unit(v, "m", "mm")


def _kg_mm(v):
    """An unbalance [kg m] in kg mm."""
    return in_unit(v, "kg*m", "kg*mm")


def _kg_mm2(v):
    """A couple unbalance [kg m^2] in kg mm^2."""
    return in_unit(v, "kg*m**2", "kg*mm**2")
