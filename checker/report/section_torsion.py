"""Report section: crankshaft torsional vibration, TV damper rubber and joint torques (module
``torsion``, :mod:`checker.modules.torsion`; detail types :mod:`checker.results.torsion`). The
damper's tuning against Den Hartog's optimum is the damper section."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..results import display
from ..results.display import case_text
from . import judged as jd
from .plots import figure, later, legend_below, limit_line, literal, to_image
from .sections import display_values, fmt, in_unit, rpm, section


def _deg(rad):
    """Angle(s) in rad as degrees."""
    return in_unit(rad, "rad", "deg")


def _limit(res: CheckResult, quantity: str, unit: str) -> float | None:
    """Display limit of the rule (after overrides) on ``quantity`` if its unit is ``unit``: the
    limit its results used (a limit by engine class), else the rule table's."""
    rules = {r.id: r for r in res.table.rules}
    for rr in res.results:
        r = rules.get(rr.rule)
        if r is not None and r.quantity == quantity and rr.limit_values and rr.unit == unit:
            return rr.limit_values[0]
    for r in res.table.rules:
        if r.quantity == quantity and r.limit and r.unit == unit:
            return r.limit[0]
    return None


def _inputs(res: CheckResult) -> list[dict]:
    eng = res.engine
    rows = []
    for s in eng.tv_model:
        rows.append([s.station, s.role, ", ".join(map(str, s.cylinders)) or "-",
                     fmt(in_unit(s.inertia, "kg*m**2", "g*m**2")), fmt(s.absolute_damping),
                     "-" if s.stiffness is None else fmt(in_unit(s.stiffness, "N*m/rad",
                                                                 "kN*m/rad")),
                     fmt(s.relative_damping)])
    blocks = [{"type": "table", "caption": "Torsional model (sheet TVModel), front to rear",
               "columns": ["station", "role", "cylinder", "J [g·m²]", "d_abs [N·m·s/rad]",
                           "k to next [kN·m/rad]", "c to next [N·m·s/rad]"], "rows": rows,
               "widths": [18, 14, 10, 12, 15, 16, 15]}]
    d = eng.damper
    rows = []
    for key, label, si, u in (("loss_factor", "Rubber loss factor η", "", ""),
                              ("inner_radius", "Rubber inner radius", "m", "mm"),
                              ("outer_radius", "Rubber outer radius", "m", "mm"),
                              ("axial_length", "Rubber axial length", "m", "mm"),
                              ("shear_stress_limit", "Shear stress limit (supplier)", "Pa",
                               "MPa"),
                              ("heat_limit", "Heat per unit volume limit (supplier)", "W/m**3",
                               "W/cm**3")):
        v = d.get(key)
        shown = "-" if v is None else (f"{fmt(in_unit(v, si, u) if u else v)}"
                                       f" {display.unit_text(u)}").strip()
        rows.append([label, shown, eng.cell("Damper", key)])
    fead = eng.params.get("fead_torque")
    rows.append(["Accessory drive torque at the crank nose",
                 "-" if fead is None else f"{fmt(fead)} N·m", eng.cell("Engine", "fead_torque")])
    blocks.append({"type": "table", "caption": "Damper rubber and accessory drive (sheets"
                   " Damper, Engine)", "columns": ["parameter", "value", "cell"],
                   "rows": rows, "widths": [50, 25, 25]})
    return blocks


def _modes(res: CheckResult, nf, sp: np.ndarray) -> list[dict]:
    ex = nf.detail
    f = nf.values
    orders = ex.orders
    n_cyl = len(res.engine.cylinders)
    major = [o for o in orders if abs((o / (n_cyl / 2)) - round(o / (n_cyl / 2))) < 1e-9
             and o <= 4 * n_cyl]
    rows = []
    lo, hi = sp.min(), sp.max()  # [rad/s]
    for i, lab in enumerate(nf.coords["mode"]):
        crit = ex.critical_speed[i]
        inside = [f"{o:g}: {rpm(c):.0f}" for o, c in zip(orders, crit)
                  if o in major and lo <= c <= hi]
        rows.append([lab, fmt(f[i]), fmt(in_unit(ex.damping_ratio[i], "", "percent")),
                     ", ".join(inside) or "-"])
    blocks: list[dict] = [{"type": "table", "caption": "Undamped natural frequencies (flexible"
                           " modes), modal damping ratio and critical speeds of the major"
                           " orders inside the speed range",
                           "columns": ["mode", "f [Hz]", "ζ [%]",
                                       "major order: critical speed [rpm]"], "rows": rows,
                           "widths": [12, 12, 10, 66]}]
    n_show = min(3, f.size)
    if n_show:
        blocks.append({"type": "figure", "png": later((170, 58), _draw_mode_shapes, ex.modes,
                                                      ex.stations, f, n_show),
                       "data": [nf.name],
                       "caption": "Mode shapes of the first flexible modes, normalised to the"
                                  " largest station amplitude."})
    # Campbell diagram
    lo_rpm, hi_rpm = rpm(lo), rpm(hi)
    drawn, f_show, above, y_max = _campbell_range(f, orders, n_cyl, hi_rpm)
    barred, band = _class_marks(res)
    png = later((170, 78), _draw_campbell, orders, major, ex.critical_speed, drawn, f_show,
                y_max, lo_rpm, hi_rpm, barred, band)
    note = ""
    if above.size:
        note = (" Modes above the frequency axis (no drawn order reaches them inside the speed"
                " range): " + ", ".join(f"mode {int(np.flatnonzero(f == x)[0]) + 1}"
                                        f" {x:.0f} Hz" for x in above) + ".")
    blocks.append({"type": "figure", "png": png, "data": [nf.name],
                   "caption": "Campbell diagram: engine orders (numbered at the ends of the"
                              " lines; half orders dotted) against the natural frequencies;"
                              " filled dots: major-order resonances inside the speed range,"
                              " open dots: resonances of the other orders drawn."
                              + (" Red bands: barred speed ranges of the criticals whose"
                                 " crank stress exceeds the class's continuous limit (KR Pt 5"
                                 " Ch 4 206.1(1))." if barred else "")
                              + (f" Hatched: {band[0]:.0f}..{band[1]:.0f} rpm, the band of"
                                 " the rated speed the class keeps free of major criticals"
                                 " (KR Pt 5 Ch 4 204)." if band else "") + note})
    return blocks


def _class_marks(res: CheckResult) -> tuple[list[tuple[float, float]], tuple | None]:
    """Barred speed ranges [rpm] and the band free of major criticals [rpm] (None) of the
    class rules, for the Campbell diagram."""
    q = res.outcome.quantities
    b, m = q.get("tv.barred_speed_range"), q.get("tv.major_critical_clearance")
    barred = ([(rpm(lo), rpm(hi)) for lo, hi in zip(b.detail.lower, b.detail.upper,
                                                     strict=True)] if b is not None else [])
    band = None
    if m is not None and np.isfinite(m.detail.band).all():
        n = rpm(m.detail.rated_speed)
        band = (m.detail.band[0] * n, m.detail.band[1] * n)
    return barred, band


def _draw_mode_shapes(modes: np.ndarray, stations: list[str], f: np.ndarray, n_show: int):
    """The first ``n_show`` mode shapes (columns of ``modes``, natural frequencies ``f``) over
    the ``stations``, drawn."""
    fig, ax = figure(170, 58, bottom=17, legend_rows=1)
    x = np.arange(len(stations))
    for i in range(n_show):
        phi = modes[:, i] / np.max(np.abs(modes[:, i]))
        ax.plot(x, phi, marker="o", ms=3, label=f"mode {i + 1}: {f[i]:.0f} Hz")
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xticks(x, [literal(s) for s in stations], rotation=15, ha="right")
    ax.set_ylabel("Relative amplitude [-]")
    ax.set_xlabel("Station of the torsional model (front to rear)", labelpad=1)
    legend_below(fig, ncols=3)
    return to_image(fig)


def _campbell_range(f: np.ndarray, orders, n_cyl: int, hi_rpm: float
                    ) -> tuple[list, np.ndarray, np.ndarray, float]:
    """What the Campbell diagram shows: the orders drawn, the natural frequencies on its
    frequency axis, those above it and the top of the axis [Hz]."""
    drawn = [o for o in orders if o <= 2 * n_cyl + 4 and (float(o).is_integer()
                                                         or float(o * 2).is_integer())]
    o_top = max(drawn) if drawn else max(orders)
    # the frequency axis ends above the highest mode that a drawn order crosses inside the
    # speed range: higher modes would crowd the crossings into the bottom of the plot
    crossed = f[f <= o_top * hi_rpm / 60]
    f_show = crossed if crossed.size else f[:1]
    above = f[f > (f_show.max() if f_show.size else 0)]
    y_max = (f_show.max() if f_show.size else f.min()) * 1.15
    return drawn, f_show, above, y_max


def _draw_campbell(orders, major: list, critical_speed: np.ndarray, drawn: list,
                   f_show: np.ndarray, y_max: float, lo_rpm: float, hi_rpm: float,
                   barred: list | None = None, band: tuple | None = None):
    """The Campbell diagram of :func:`_modes` (``drawn``, ``f_show``, ``y_max`` of
    :func:`_campbell_range`; speed range ``lo_rpm`` to ``hi_rpm``; the class rules' barred
    ranges and band free of major criticals [rpm]), drawn."""
    fig, ax = figure(170, 78, right=12, legend_rows=2 if (barred or band) else 1)
    x_max = max(hi_rpm, band[1] if band else 0.0) * 1.1
    ax.axvspan(lo_rpm, hi_rpm, color="#3498db", alpha=0.08, label="speed range")
    for k, (lo, hi) in enumerate(barred or []):
        ax.axvspan(lo, hi, color="#e74c3c", alpha=0.25,
                   label="barred speed range" if k == 0 else None)
    if band:
        ax.axvspan(*band, fill=False, hatch="//", ec="#bdc3c7", lw=0,
                   label="band free of major criticals")
    seen: set[str] = set()
    placed: list[tuple[str, float]] = []  # order labels already placed (edge, position)
    for o in drawn:
        is_major = o in major
        half = not float(o).is_integer()
        kind = "major orders" if is_major else "half orders" if half else "other orders"
        ax.plot([0, x_max], [0, o * x_max / 60],
                color="#2c3e50" if is_major else "#b3b6b7" if half else "#95a5a6",
                lw=1.0 if is_major else 0.6, ls=":" if half else "-",
                label=kind if kind not in seen else None)
        seen.add(kind)
        y_end = o * x_max / 60
        # the order number where its line leaves the axes; labels too close to a placed one
        # are left out (the lines are in order, every other one is enough to read them)
        edge, pos = ("top", y_max * 60 / o / x_max) if y_end > y_max else (
            "right", y_end / y_max)
        if any(e == edge and abs(pos - p) < 0.035 for e, p in placed):
            continue
        placed.append((edge, pos))
        if edge == "top":
            ax.annotate(f"{o:g}", (y_max * 60 / o, y_max), xytext=(0, 2),
                        textcoords="offset points", fontsize=6 if not half else 5,
                        ha="center", va="bottom", annotation_clip=False)
        else:
            ax.annotate(f"{o:g}", (x_max, y_end), xytext=(2, 0), textcoords="offset points",
                        fontsize=6 if not half else 5, va="center", annotation_clip=False)
    for i, fi in enumerate(f_show):
        ax.axhline(fi, color="#c0392b", lw=0.8, ls="--",
                   label="natural frequencies" if i == 0 else None)
        # a label above its line, or below it when the next mode's line is close above
        close = i + 1 < f_show.size and f_show[i + 1] - fi < 0.07 * y_max
        ax.annotate(f"mode {i + 1}: {fi:.0f} Hz", (0, fi), xytext=(2, -1.5 if close else 1.5),
                    textcoords="offset points", fontsize=5.5, va="top" if close else "bottom",
                    color="#c0392b",
                    bbox={"boxstyle": "square,pad=0.1", "fc": "white", "ec": "none",
                          "alpha": 0.85})
        crit = rpm(critical_speed[i])
        pick = [(c, o) for o, c in zip(orders, crit) if o in major and lo_rpm <= c <= hi_rpm]
        other = [(c, o) for o, c in zip(orders, crit) if o in drawn and o not in major
                 and lo_rpm <= c <= hi_rpm]
        if pick:
            ax.plot([c for c, _ in pick], [fi] * len(pick), "o", color="#c0392b", ms=3,
                    label="major-order resonance in the speed range" if i == 0 else None)
        if other:
            ax.plot([c for c, _ in other], [fi] * len(other), "o", mfc="white",
                    color="#7f8c8d", ms=2.6, label="other-order resonance in the speed range"
                    if "other res" not in seen else None)
            seen.add("other res")
    ax.set_xlim(0, x_max)
    ax.set_ylim(0, y_max)
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Frequency [Hz]")
    legend_below(fig, ncols=4)
    return to_image(fig)


def _judged_rows(res: CheckResult, items: list[tuple[str, object, list[tuple], str]],
                 cells) -> tuple[list[list[str]], list[str]]:
    """Rows of a 'largest value' table. ``items``: (content, quantity, leads, how) with one
    lead per load case; per content the judged worst points first, most severe first (so the
    first equals the rule result over all cases), then the worse points the rules do not
    judge, marked. ``cells(content, q, point)`` gives a row without the 'judged by' cell."""
    rows, css = [], []
    for content, qq, leads, how in items:
        found = [jd.worst(qq, lead, how) for lead in leads]
        sign = 1.0 if how == "max" else -1.0
        judged = sorted((j for j, _ in found if j is not None), key=lambda p: -sign * p.value)
        for p in judged + [u for _, u in found if u is not None]:
            case = qq.coords["case"][p.index[qq.spec.dims.index("case")]]
            rows.append(cells(content, qq, p) + [jd.judged_text(res, qq, p, None, case)])
            css.append(jd.row_css(p))
    return rows, css


def _nose(res: CheckResult, q: dict) -> list[dict]:
    tot, per = q["tv.nose_amplitude"], q["tv.nose_order_amplitude"]
    cyl = q.get("tv.nose_cylinder_order_amplitude")
    hi_q = q.get("tv.nose_higher_order_amplitude")
    sp = rpm(np.array(tot.coords["speed"]))
    labels = per.coords["order"]
    orders = per.detail.orders
    cases = tot.coords["case"]
    n_cyl = len(res.engine.cylinders)
    lim_cyl = _limit(res, "tv.nose_cylinder_order_amplitude", "deg")
    lim_hi = _limit(res, "tv.nose_higher_order_amplitude", "deg")
    tot_j = jd.mask(tot)
    hi_labels = list(hi_q.coords["order"]) if hi_q is not None else []
    k_cyl = int(np.argmin(np.abs(orders - n_cyl)))
    # the same orders in both panels (one legend): the cylinder-count order and the five
    # largest others over both load cases
    peak = per.values.max(axis=(1, 2))
    top = [k for k in np.argsort(-peak) if k != k_cyl][:5]
    show = [k_cyl] + sorted(top, key=lambda k: orders[k])
    # per case and shown order: the points the rules judge (None: no rule on the order)
    marks = []
    for ci in range(len(cases)):
        marks.append([])
        for k in show:
            jm = None
            if k == k_cyl and cyl is not None:
                jm = jd.mask(cyl)[ci]
            elif labels[k] in hi_labels:
                jm = jd.mask(hi_q)[hi_labels.index(labels[k]), ci]
            marks[-1].append(jm)
    marked = any(jm is not None and jm.any() for row in marks for jm in row)
    shaded = any(_shades(sp, tot_j[ci]) for ci in range(len(cases)))
    png = later((170, 82), _draw_nose, sp, cases, tot, per, labels, show, k_cyl, marks, marked,
                tot_j, n_cyl, lim_cyl, lim_hi)
    why = [jd.reason(x) for x in (cyl, hi_q) if x is not None]
    caption = (
        "Crank-nose TV amplitude against speed (relative to a node rotating at the mean speed,"
        " not twist): total = half peak-to-peak of all orders; orders 0-to-peak (the"
        f" cylinder-count order {n_cyl} and the five largest others)."
        + (" Circles: the points the rules judge; the rest of each order curve is computed"
           " but not judged (" + "; ".join(dict.fromkeys(why)) + ")." if marked else "")
        + (jd.shade_caption([jd.reason(tot)]) if shaded else ""))
    blocks: list[dict] = [{"type": "figure", "png": png, "caption": caption,
                           "data": [x.name for x in (tot, per, cyl, hi_q) if x is not None]}]

    low_q = q.get("tv.nose_lower_order_elastic_amplitude")
    lim_low = _limit(res, "tv.nose_lower_order_elastic_amplitude", "deg")

    def cells(content, qq, p):
        ci, si = p.index[-2], p.index[-1]
        if qq is hi_q:
            content = f"higher: {hi_q.coords['order'][p.index[0]]}"
        if qq is low_q:
            content = f"lower, elastic: {low_q.coords['order'][p.index[0]]}"
        lim = (lim_cyl if qq is cyl else lim_hi if qq is hi_q else lim_low if qq is low_q
               else None)
        return [content, case_text(cases[ci]), fmt(_deg(p.value)),
                f"{sp[si]:.0f}", "-" if lim is None else f"< {lim:g}"]

    items = []
    if cyl is not None:
        items.append((f"order {n_cyl}", cyl, [(ci,) for ci in range(len(cases))], "max"))
    if hi_q is not None and hi_q.values.size:
        items.append(("higher orders", hi_q,
                      [(slice(None), ci) for ci in range(len(cases))], "max"))
    if low_q is not None and low_q.values.size and jd.mask(low_q).any():
        items.append(("lower orders, elastic part (TV-003)", low_q,
                      [(slice(None), ci) for ci in range(len(cases))], "max"))
    items.append(("total (half peak-to-peak)", tot, [(ci,) for ci in range(len(cases))],
                  "max"))
    rows, css = _judged_rows(res, items, cells)
    blocks.append({"type": "table", "caption": "Largest crank-nose amplitudes: per content the"
                   " judged worst first (the value of the rule result), then, marked, larger"
                   " amplitudes at points the rules do not judge",
                   "columns": ["content", "case", "amplitude [°]", "speed [rpm]",
                               "limit [°]", "judged by"], "rows": rows, "row_css": css,
                   "widths": [17, 10, 12, 10, 9, 42]})
    return blocks


def _shades(x, judged_1d: np.ndarray) -> bool:
    """Whether :func:`judged.shade` shades anything of ``x`` (points not judged)."""
    return np.asarray(x).size >= 2 and bool(jd.runs(judged_1d))


def _draw_nose(sp: np.ndarray, cases: list[str], tot, per, labels: list[str], show: list[int],
               k_cyl: int, marks: list[list], marked: bool, tot_j: np.ndarray, n_cyl: int,
               lim_cyl: float | None, lim_hi: float | None):
    """The crank-nose amplitude figure of :func:`_nose`: the total and the orders ``show``
    (``k_cyl`` the cylinder-count order) per load case, circles at the judged points
    ``marks`` (per case and shown order; ``marked``: any), drawn."""
    fig, axes = figure(170, 82, ncols=len(cases), sharey=True, squeeze=False, wgap=8,
                       legend_rows=2)
    colors = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#17becf"]
    for ci, c in enumerate(cases):
        ax = axes[0, ci]
        jd.shade(ax, sp, tot_j[ci])
        ax.plot(sp, _deg(tot.values[ci]), color="k", lw=1.6, label="total (synthesis)")
        for n, k in enumerate(show):
            (ln,) = ax.plot(sp, _deg(per.values[k, ci]), lw=1.4 if k == k_cyl else 0.9,
                            color=colors[n % len(colors)], label=literal(labels[k]))
            jm = marks[ci][n]
            if jm is not None and jm.any():
                ax.plot(sp[jm], _deg(per.values[k, ci, jm]), "o", ms=3.5, mfc="none",
                        color=ln.get_color())
        if lim_cyl is not None:
            limit_line(ax, lim_cyl, f"limit, order {n_cyl}: {lim_cyl:g}°")
        if lim_hi is not None:
            limit_line(ax, lim_hi, f"limit, higher orders: {lim_hi:g}°", ls=":")
        ax.set_yscale("log")
        ax.set_ylim(1e-3, None)
        ax.set_title(case_text(c))
        ax.set_xlabel("Engine speed [rpm]")
    if marked:
        axes[0, 0].plot([], [], "o", ms=3.5, mfc="none", color="0.3",
                        label="points the rules judge")
    axes[0, 0].set_ylabel("Crank-nose amplitude [°]")
    legend_below(fig, ncols=6)
    return to_image(fig)


def _elements(res: CheckResult, q: dict) -> list[dict]:
    et = q["tv.element_torque"]
    tw = q.get("tv.crank_twist")
    ex = et.detail
    sp = rpm(np.array(et.coords["speed"]))
    cases = et.coords["case"]
    names = et.coords["item"]
    et_j = jd.mask(et)
    png = later((170, 70), _draw_elements, sp, cases, names, tw, et, et_j)
    dotted = not et_j.all() or (tw is not None and not jd.mask(tw).all())
    blocks: list[dict] = [{"type": "figure", "png": png, "caption": (
        "Crankshaft twist (crank nose to flywheel) and vibratory torque in every element of"
        " the TV model against speed"
        + (f"; dotted: computed but not judged ({jd.reason(et)})" if dotted else "") + "."),
        "data": [x.name for x in (tw, et) if x is not None]}]
    rows, css = [], []
    for e, n in enumerate(names):
        for ci, c in enumerate(cases):
            for p in jd.worst(et, (e, ci), "max"):
                if p is None:
                    continue
                k = p.index[-1]
                rows.append([n, case_text(c), fmt(p.value), f"{sp[k]:.0f}",
                             fmt(ex.mean[e, ci, k]), fmt(ex.vib_min[e, ci, k]),
                             fmt(ex.vib_max[e, ci, k]),
                             fmt(_deg(ex.twist[e, ci, k])),
                             jd.judged_text(res, et, p, n, c)])
                css.append(jd.row_css(p))
    blocks.append({"type": "table", "caption": (
        "Largest vibratory torque per element (sign: torque of the front part on the rear"
        " part, positive in the direction of rotation; mean = cylinder mean torques from the"
        " front minus the accessory drive, friction not subtracted); a larger value at a point"
        " the rules do not judge follows, marked"),
        "columns": ["element", "case", "T half range [N·m]", "speed [rpm]", "T mean [N·m]",
                    "T vib min [N·m]", "T vib max [N·m]", "twist [°]", "judged by"],
        "rows": rows, "row_css": css, "widths": [20, 9, 11, 9, 10, 10, 10, 8, 13],
        "detail": True, "sheet": "element torque maxima"})
    return blocks


def _draw_elements(sp: np.ndarray, cases: list[str], names: list[str], tw, et,
                   et_j: np.ndarray):
    """The figure of :func:`_elements`: crank twist ``tw`` (or None) per load case and the
    vibratory torque of every element (``et``, judged points ``et_j``) at full load, drawn."""
    fig, axes = figure(170, 70, ncols=2, squeeze=False, legend_rows=2)
    ax = axes[0, 0]
    for ci, c in enumerate(cases):
        if tw is not None:
            jd.line(ax, sp, _deg(tw.values[ci]), jd.mask(tw)[ci], color=("k", "0.5")[ci % 2],
                    label=f"twist, {case_text(c)}")
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Twist, nose to flywheel [°]")
    ax.set_title("crank twist, half peak-to-peak")
    ax = axes[0, 1]
    ci = cases.index("full") if "full" in cases else 0
    colors = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#e377c2",
              "#7f7f7f", "#bcbd22"]
    for e, n in enumerate(names):
        jd.line(ax, sp, et.values[e, ci], et_j[e, ci], label=literal(n), lw=0.9,
                color=colors[e % len(colors)])
    ax.set_xlabel("Engine speed [rpm]")
    ax.set_ylabel("Vibratory torque [N·m]")
    ax.set_title("element torque, half peak-to-peak, full load")
    legend_below(fig, ncols=5)
    return to_image(fig)


_LIMITS = (("continuous", "τ₁ continuous", "-"), ("transient", "τ₂ transient", "--"),
           ("overspeed", "τ₃ above rated speed", ":"))


def _crank_stress(res: CheckResult, q: dict) -> list[dict]:
    """The crank's nominal vibratory shear stress against speed with the class limits, the
    worst section marked; its largest values, barred speed ranges and major criticals."""
    st = q.get("tv.crank_shear_stress")
    if st is None:
        return []
    d = st.detail
    cls = next((q[n].detail for n in ("tv.crank_stress_ratio_continuous",
                                      "tv.crank_stress_ratio_transient") if n in q), None)
    sp = rpm(np.array(st.coords["speed"]))
    cases = st.coords["case"]
    names = st.coords["item"]
    b = q.get("tv.barred_speed_range")
    barred = [] if b is None else [(rpm(lo), rpm(hi)) for lo, hi in
                                   zip(b.detail.lower, b.detail.upper, strict=True)]
    limits = [] if cls is None else [
        (lab, ls, in_unit(getattr(cls, key), "Pa", "MPa")) for key, lab, ls in _LIMITS
        if np.isfinite(getattr(cls, key)).any()]
    env = np.ones((len(cases), sp.size), bool) if d.envelope is None else d.envelope
    png = later((170, 78), _draw_crank_stress, sp, cases, names, in_unit(st.values, "Pa", "MPa"),
                d.worst, env, limits, barred)
    where = (f" Limits: {cls.source} (engine group {cls.group}, f_m = {cls.f_m_tensile:.3f}"
             f" for τ₁/τ₃, {cls.f_m_yield:.3f} for τ₂; rated speed"
             f" {rpm(cls.rated_speed):.0f} rpm)." if cls is not None else
             " No class limit applies to this engine class (the crank-nose targets judge it).")
    blocks: list[dict] = [{"type": "figure", "png": png, "data": [st.name], "caption": (
        "Nominal vibratory shear stress in every crank section (half range of the"
        " synthesised torque over the polar modulus of the"
        f" {d.section[0]}, the smaller of pin and journal), against speed; bold: the worst"
        f" section ({literal(names[d.worst])}); dotted outside each load case's operating"
        " envelope" + ("; red bands: barred speed ranges" if barred else "") + "." + where)}]
    rows = []
    for e, n in enumerate(names):
        for ci, c in enumerate(cases):
            v = np.where(env[ci], st.values[e, ci], -np.inf)
            k = int(np.argmax(v))
            if not np.isfinite(v[k]):
                continue
            lim = "-" if cls is None else next(
                (fmt(in_unit(getattr(cls, key)[k], "Pa", "MPa")) for key, _, _ in _LIMITS
                 if np.isfinite(getattr(cls, key)[k])), "-")
            rows.append([n, case_text(c), fmt(in_unit(st.values[e, ci, k], "Pa", "MPa")),
                         f"{sp[k]:.0f}", lim])
    blocks.append({"type": "table", "caption": "Largest nominal vibratory shear stress per"
                   " crank section and load case within the operating envelope, with the"
                   " class's permissible stress at that speed (rules TV-004..TV-006, TV-009)",
                   "columns": ["crank section", "case", "τ [MPa]", "speed [rpm]",
                               "limit [MPa]"], "rows": rows, "widths": [34, 14, 16, 16, 20]})
    if b is not None and b.values.size:
        bd = b.detail
        blocks.append({"type": "table", "caption": "Barred speed ranges (KR Pt 5 Ch 4"
                       " 206.1(1): 16 N_c/(18 − λ) ≤ N ≤ (18 − λ) N_c/16, λ = N_c/N_rated,"
                       " widened to every speed of the run above τ₁; rule TV-007: none above"
                       " 0.8 of the rated speed)",
                       "columns": ["critical", "N_c [rpm]", "λ", "barred [rpm]",
                                   "peak τ / τ₁ [MPa]"],
                       "rows": [[lab, f"{rpm(bd.critical_speed[i]):.0f}",
                                 f"{bd.critical_speed[i] / bd.rated_speed:.3f}",
                                 f"{rpm(bd.lower[i]):.0f}..{rpm(bd.upper[i]):.0f}",
                                 f"{fmt(in_unit(bd.peak_stress[i], 'Pa', 'MPa'))} /"
                                 f" {fmt(in_unit(bd.peak_limit[i], 'Pa', 'MPa'))}"]
                                for i, lab in enumerate(b.coords["item"])],
                       "widths": [26, 14, 10, 24, 26]})
    m = q.get("tv.major_critical_clearance")
    if m is not None and m.values.size:
        md = m.detail
        blocks.append({"type": "table", "caption": "Major criticals of the one-node mode"
                       f" ({md.natural_frequency:.1f} Hz) against the band"
                       f" {md.band[0]:g}..{md.band[1]:g} of the rated speed (KR Pt 5 Ch 4 204,"
                       " rule TV-008)",
                       "columns": ["order", "N_c [rpm]", "λ = N_c/N_rated", "outside the band"],
                       "rows": [[f"{md.order[i]:g}", f"{rpm(md.critical_speed[i]):.0f}",
                                 f"{md.speed_ratio[i]:.3f}",
                                 "yes" if m.values[i] > 0 else "NO"]
                                for i in range(m.values.size)],
                       "widths": [15, 20, 25, 25]})
    return blocks


def _draw_crank_stress(sp: np.ndarray, cases: list[str], names: list[str], tau: np.ndarray,
                       worst: int, env: np.ndarray, limits: list, barred: list):
    """The figure of :func:`_crank_stress`: per load case the stress of every section
    (``tau`` [MPa], (E, C, S)), the ``worst`` one bold, the limit curves ``limits`` (label,
    line style, (S,) [MPa]) and the barred ranges [rpm], drawn."""
    fig, axes = figure(170, 78, ncols=len(cases), sharey=True, squeeze=False, wgap=8,
                       legend_rows=2)
    for ci, c in enumerate(cases):
        ax = axes[0, ci]
        for k, (lo, hi) in enumerate(barred):
            ax.axvspan(lo, hi, color="#e74c3c", alpha=0.2,
                       label="barred speed range" if k == 0 else None)
        for e, n in enumerate(names):
            is_worst = e == worst
            jd.line(ax, sp, tau[e, ci], env[ci], color="k" if is_worst else "0.6",
                    lw=1.6 if is_worst else 0.7,
                    label=f"worst section: {literal(n)}" if is_worst else
                    ("other crank sections" if e == (1 if worst == 0 else 0) else None))
        if env[ci].any():  # the worst section's largest stress in the envelope, marked
            k = int(np.argmax(np.where(env[ci], tau[worst, ci], -np.inf)))
            ax.plot(sp[k], tau[worst, ci, k], "o", ms=4, mfc="none", color="k",
                    label="largest in the operating envelope")
        for lab, ls, curve in limits:
            ax.plot(sp, curve, color="#c0392b", ls=ls, lw=1.0, label=lab)
        ax.set_title(case_text(c))
        ax.set_xlabel("Engine speed [rpm]")
        ax.set_ylim(0, None)
    axes[0, 0].set_ylabel("Nominal shear stress [MPa]")
    legend_below(fig, ncols=4)
    return to_image(fig)


def _damper(res: CheckResult, q: dict) -> list[dict]:
    pw = q.get("damper.power")
    if pw is None or not np.isfinite(pw.values).any():
        reasons = [] if pw is None else sorted({r for v in pw.missing.values() for r in v})
        return [{"type": "text", "text": "Damper rubber: not computed"
                 + (" (" + "; ".join(reasons) + ")" if reasons else "") + "."}]
    sp = rpm(np.array(pw.coords["speed"]))
    cases = pw.coords["case"]
    d = res.engine.damper
    heat, heat_pk, tau = (q.get(n) for n in ("damper.heat_density", "damper.heat_density_peak",
                                             "damper.shear_stress"))
    geo = heat is not None and np.isfinite(heat.values).any()
    png = later((170, 62), _draw_damper, sp, cases, geo, pw, heat, heat_pk, tau,
                d.get("heat_limit"), d.get("shear_stress_limit"))
    faint = not jd.mask(pw).all()
    blocks: list[dict] = [{"type": "figure", "png": png, "caption": (
        ("TV damper silicone (viscous damper): dissipated power (sum of orders)"
         if d.get("damper_type") == "viscous" else
         "TV damper rubber: dissipated power (sum of orders), heat per unit rubber volume (mean"
        " P/V and peak at the inner radius) and shear-stress amplitude at the inner radius")
        + (f"; faint dotted: computed but not judged ({jd.reason(pw)})" if faint else "")
        + "."), "data": [x.name for x in (pw, heat, heat_pk, tau) if x is not None]}]
    tw, tq = q.get("damper.relative_twist"), q.get("damper.torque")
    # each in its quantity's display unit: W, deg, N m, W/cm³, W/cm³, MPa (the column heads)
    cols = [pw, tw, tq] + ([heat, heat_pk, tau] if geo else [])
    rows, css = [], []
    for ci, c in enumerate(cases):
        found = [jd.worst(x, (ci,), "max") if x is not None else (None, None) for x in cols]
        for which in (0, 1):
            pts = [f[which] for f in found]
            if which == 1 and all(p is None for p in pts):
                continue
            p0 = pts[0]
            row = [case_text(c), "-" if p0 is None else f"{sp[p0.index[-1]]:.0f}"]
            row += ["-" if p is None else fmt(display_values(x, p.value)[0])
                    for p, x in zip(pts, cols)]
            row += ["-"] * (3 - (len(cols) - 3))
            row.append("judged points" if which == 0 else "not judged: " + jd.reason(pw))
            rows.append(row)
            css.append("" if which == 0 else jd.NOT_JUDGED_CSS)
    blocks.append({"type": "table", "caption": "Damper rubber maxima over the judged points"
                   " per load case, then, marked, larger values at points the rules do not"
                   " judge",
                   "columns": ["case", "speed of max power [rpm]", "P max [W]",
                               "twist [°]", "torque [N·m]", "q mean [W/cm³]",
                               "q peak [W/cm³]", "τ max [MPa]", "points"],
                   "rows": rows, "row_css": css, "widths": [9, 11, 9, 8, 9, 10, 10, 9, 25],
                   "detail": True, "sheet": "damper maxima"})
    judged_q = [(n, q.get(n)) for n in ("damper.shear_stress", "damper.heat_density",
                                        "damper.heat_density_peak")]
    items = [(qq.spec.description, qq, [(ci,) for ci in range(len(cases))],
              jd.direction(res, n, "max"))
             for n, qq in judged_q if qq is not None and np.isfinite(qq.values).all()
             and (qq.item_attrs.get("all") or {}).get("limit") is not None]
    if items:
        def cells(content, qq, p):  # in the quantity's display unit (MPa, W/cm³)
            ci, si = p.index
            lim = qq.item_attrs["all"]["limit"][0]
            (val, u), lim_shown = display_values(qq, p.value), display_values(qq, lim)[0]
            return [content, case_text(cases[ci]), f"{fmt(val)} {u}", f"{fmt(lim_shown)} {u}",
                    f"{sp[si]:.0f}"]

        rows, css = _judged_rows(res, items, cells)
        blocks.append({"type": "table", "caption": "Damper rubber against the supplier's limits"
                       " (rules DMP-001..003): the judged worst first (the value of the rule"
                       " result), then, marked, larger values at points the rules do not judge",
                       "columns": ["quantity", "case", "value", "supplier limit",
                                   "speed [rpm]", "judged by"], "rows": rows, "row_css": css})
    if geo:
        ex = heat.detail
        blocks.append({"type": "list", "items": [
            f"Rubber volume {in_unit(ex.volume, 'm**3', 'cm**3'):.4g} cm³; storage shear"
            " modulus implied by the element stiffness and the geometry G' ="
            f" {in_unit(ex.shear_modulus, 'Pa', 'MPa'):.3g} MPa"
            f" (k' = {ex.stiffness:.5g} N m/rad, η = {ex.loss_factor:g}).",
            "The rubber's shear stress and heat per volume are judged against the supplier's"
            " limits (Damper sheet; rules DMP-001..003).",
        ]})
    return blocks


def _draw_damper(sp: np.ndarray, cases: list[str], geo: bool, pw, heat, heat_pk, tau,
                 heat_limit: float | None, shear_stress_limit: float | None):
    """The figure of :func:`_damper`: dissipated power and, with the rubber's geometry
    (``geo``), heat per unit volume and shear stress against the supplier's limits (SI),
    drawn."""
    fig, axes = figure(170, 62, ncols=3 if geo else 1, squeeze=False, wgap=16, legend_rows=1)
    case_color = {c: ("#1f77b4", "#ff7f0e", "#2ca02c")[i % 3] for i, c in enumerate(cases)}
    ax = axes[0, 0]
    for ci, c in enumerate(cases):
        jd.line(ax, sp, pw.values[ci], jd.mask(pw)[ci], color=case_color[c],
                label=case_text(c))
    ax.set_ylabel("Dissipated power [W]")
    ax.set_title("dissipated power")
    ax.set_xlabel("Engine speed [rpm]")
    if geo:
        ax = axes[0, 1]
        for ci, c in enumerate(cases):
            jd.line(ax, sp, display_values(heat, heat.values[ci])[0], jd.mask(heat)[ci],
                    color=case_color[c])
            jd.line(ax, sp, display_values(heat_pk, heat_pk.values[ci])[0],
                    jd.mask(heat_pk)[ci], ls="--",
                    lw=0.8, color=case_color[c])
        ax.plot([], [], color="0.3", label="mean (solid)")
        ax.plot([], [], color="0.3", ls="--", lw=0.8, label="peak at the inner radius")
        if heat_limit is not None:
            limit_line(ax, in_unit(heat_limit, "W/m**3", "W/cm**3"), "supplier limit")
        ax.set_ylabel("Heat per rubber volume [W/cm³]")
        ax.set_title("heat per unit volume")
        ax.set_xlabel("Engine speed [rpm]")
        ax = axes[0, 2]
        for ci, c in enumerate(cases):
            jd.line(ax, sp, display_values(tau, tau.values[ci])[0], jd.mask(tau)[ci],
                    color=case_color[c])
        if shear_stress_limit is not None:
            limit_line(ax, in_unit(shear_stress_limit, "Pa", "MPa"), "supplier limit")
        ax.set_ylabel("Shear stress amplitude [MPa]")
        ax.set_title("shear stress at the inner radius")
        ax.set_xlabel("Engine speed [rpm]")
    legend_below(fig, ncols=6)
    return to_image(fig)


def _joints(res: CheckResult, q: dict) -> list[dict]:
    jt = q.get("tv.joint_torque")
    if jt is None:
        return []
    app = q.get("joint.applied_torque")
    src = None if app is None else app.detail.source
    given = {(t.joint, t.point): t for t in res.engine.joint_torques}
    rows = []
    for i, n in enumerate(jt.coords["item"]):
        for k, p in enumerate(jt.coords["point"]):
            s = "" if src is None else str(src[i, k])
            used = ("workbook (JointTorques)" if s.startswith("workbook") else
                    "torsional model" if s else "-")
            g = fmt(given[(n, p)].torque) if (n, p) in given else "-"
            if np.isfinite(jt.values[i, k]):
                c = jt.detail.case[i, k]
                rows.append([n, p, case_text(c) if c else "-",
                             f"{rpm(jt.detail.speed[i, k]):.0f}", fmt(jt.values[i, k]),
                             g, used])
            else:
                rows.append([n, p, "-", "-", "-", g, used if s else "not available: "
                             + "; ".join(jt.missing.get((i, k), []))])
    blocks: list[dict] = [{"type": "table", "caption": (
        "Peak torque through the bolted joints from the TV model (max over the cycle of"
        " |mean + vibratory|), the workbook's value and the one the joint check uses (both"
        " cover factors are in the bolted-joints section)"),
        "columns": ["joint", "operating point", "case", "speed [rpm]", "TV torque [N·m]",
                    "workbook [N·m]", "used"], "rows": rows,
        "widths": [12, 13, 10, 10, 12, 12, 31]}]
    how = jt.detail.how
    items = [f"{n} at '{p}': {how[i, k]}"
             for i, n in enumerate(jt.coords["item"]) for k, p in enumerate(jt.coords["point"])
             if how[i, k]]
    mp, ov = jt.detail.max_power_speed, jt.detail.overspeed
    items.append("Operating points: 'tv peak' = speed of the largest joint torque over the"
                 " full-load sweep; 'max power' = speed of the maximum brake power of the"
                 " BrakeTorque sheet"
                 + (f" ({rpm(mp):.0f} rpm)" if mp is not None else "")
                 + ", full load; 'overspeed' = Engine 'Overspeed'"
                 + (f" ({rpm(ov):.0f} rpm)" if ov is not None else "") + ", no load; each at"
                 " the nearest swept speed. Crank nose: damper rubber element torque plus the"
                 " accessory drive torque (the hub's own inertia torque is neglected);"
                 " flywheel: torque of the element ending at the flywheel plus the brake torque"
                 " (0 at no load).")
    blocks.append({"type": "list", "items": items})
    return blocks


@section("torsion", label="torsional vibration")
def torsion_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    blocks: list[dict] = _inputs(res)
    blocks.append({"type": "equations", "items": [
        ("Forced response per order n", "[K(1 + jη) + jΩC − Ω²M]·Θₙ = Fₙ,  Ω = n·ω",
         "Friswell, Penny, Garvey and Lees, Dynamics of Rotating Machines, 2010, ch. 9;"
         " linear, frequency domain as in Bell, Ricardo 2013, 'Crankshaft analysis (15)'"),
        ("Cylinder excitation", "Fᵢₙ = cₙ·e^(−j n φᵢ),  T(θ) = c₀/2 + Σ Re{cₙ e^(jnθ)}",
         "Ker Wilson, Practical Solution of Torsional Vibration Problems, vol. 2, ch. 19;"
         " Drápal and Novotný, J. Vibroengineering 19, 2017, eq. 1-2"),
        ("Total amplitude", "A = (max θ(t) − min θ(t))/2 over 720°, all orders synthesised",
         "half peak-to-peak: Bell, Ricardo 2013, 'Crankshaft analysis (15)'; Lloyd's"
         " Register rules, 'half-range' amplitudes"),
        ("Element torque", "Tₑ = zₑ·(Θ_front − Θ_rear),  zₑ = k(1 + jη) + jΩc",
         "Friswell et al. 2010, ch. 9"),
        ("Damper power", "P = Σₙ ½·Ωₙ·η·k'·|Δφₙ|²", "Den Hartog, Mechanical Vibrations, 1956,"
         " §2.8; Nashif, Jones and Henderson, Vibration Damping, 1985"),
        ("Rubber shear stress", "τ = T / (2π·rᵢ²·L)", "Gent, Engineering with Rubber, 2012,"
         " ch. 8"),
        ("Rubber heat per volume", "q_mean = P / (π(rₒ² − rᵢ²)L),  q_peak = q_mean·(rₒ/rᵢ)²",
         "Nashif, Jones and Henderson 1985 (local heat ∝ 1/r⁴ in a bonded ring)"),
        ("Joint torque", "T = max_t |T_mean + T_vib(t)|", "Bell, Ricardo 2013, 'Crankshaft"
         " analysis (23)-(24)' (TV torque + accessory drive / + brake torque)"),
        ("Crank vibratory stress", "τ = M_TN / W_P,  W_P = π(D⁴ − D_B⁴)/(16 D)",
         "IACS UR M53, Rev. 4, 2019, 2.2(A)(e): M_TN the half range of the synthesised torque;"
         " the smaller of crank pin and journal"),
        ("Class limits", "τ₁ = f_m(45 − 24λ²),  τ₂ = 2τ₁·Y/225 (λ ≤ 0.8),  τ₃ = f_m(21 +"
         " 237(λ − 0.8)√(λ − 1))", "Korean Register, Rules for the Classification of Steel"
         " Ships, Pt 5 Ch 4, 2025, 201 (4-stroke in-line; 45 − 29λ², 16 + ... other V"
         " engines); generator engines 203: τ₁ = 21 (16), τ₂ = 90 MPa"),
        ("Barred speed range", "16 N_c/(18 − λ) ≤ N ≤ (18 − λ) N_c/16",
         "Korean Register, Rules for the Classification of Steel Ships, Pt 5 Ch 4, 2025,"
         " 206.1(1)"),
    ]})
    nf = q.get("tv.natural_frequency")
    tot = q.get("tv.nose_amplitude")
    if nf is not None and tot is not None:
        sp = np.array(tot.coords["speed"])
        # judged worst cases first (the values of the rule results), then the plots
        modes, nose, elements, damper = (_modes(res, nf, sp), _nose(res, q),
                                         _elements(res, q), _damper(res, q))
        stress = _crank_stress(res, q)

        def tables(bs):
            return [b for b in bs if b["type"] != "figure"]

        def figures(bs):
            return [b for b in bs if b["type"] == "figure"]

        blocks.append({"type": "heading", "text": "Crank-nose amplitude: judged worst cases"})
        blocks += tables(nose)
        blocks.append({"type": "heading", "text": "TV damper silicone: dissipated power"
                       if res.engine.damper.get("damper_type") == "viscous" else
                       "TV damper rubber: judged worst cases"})
        blocks += tables(damper)
        if stress:
            blocks.append({"type": "heading", "text": "Crankshaft vibratory stress and the"
                           " class rules"})
            blocks += tables(stress)
        blocks.append({"type": "heading", "text": "Torques at the bolted joints"})
        blocks += _joints(res, q)
        blocks.append({"type": "heading", "text": "Natural frequencies"})
        blocks += tables(modes) + tables(elements)
        blocks.append({"type": "heading", "text": "Plots"})
        blocks += (figures(modes) + figures(nose) + figures(elements) + figures(stress)
                   + figures(damper))
        found = sorted({f for v in tot.findings.values() for f in v})
        if found:
            blocks.append({"type": "heading", "text": "Numerical findings"})
            blocks.append({"type": "list", "items": found[:20] + (
                [f"... and {len(found) - 20} more"] if len(found) > 20 else [])})
    else:
        reasons = sorted({r for n, v in res.outcome.unavailable.items()
                          if n.startswith(("tv.", "damper.")) for r in v})
        jt = q.get("tv.joint_torque")
        if jt is not None:
            reasons += sorted({r for v in jt.missing.values() for r in v} - set(reasons))
        if jt is not None and np.isfinite(jt.values).any():
            blocks.append({"type": "text", "text": "Only the joint torques of the TV model were"
                           " needed by the selected rules; select the TV and DMP rules for the"
                           " full torsional results."})
            blocks += _joints(res, q)
        else:
            blocks.append({"type": "text", "text": "Torsional vibration not computed: "
                           + ("; ".join(reasons) or "no torsional quantity was requested")
                           + "."})
    return {"id": "torsion", "title": "Torsional vibration and TV damper",
            "intro": "Lumped-mass torsional model of the crank train (damper ring, crank nose,"
                     " cylinders, flywheel) excited by the gas and inertia torque of every"
                     " cylinder, solved per order in the frequency domain at full and no load"
                     " across the speed range (the concept-level practice of Bell, Ricardo"
                     " 2013): natural frequencies, crank-nose amplitude with its order"
                     " content, crankshaft twist and element torques, damper rubber power,"
                     " heat and stress, and the TV torques at the bolted joints.",
            "blocks": blocks}
