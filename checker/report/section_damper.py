"""Report section: TV damper tuning against Den Hartog's optimum (module ``damper``,
:mod:`checker.modules.damper_tuning`; detail :class:`checker.results.damper.DamperTuningDetail`).
The damper rubber's stress and heat are in the torsion section."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..results.display import case_text
from . import judged as jd
from .plots import figure, later, legend_below, to_image
from .sections import display_values, fmt, in_unit, rpm, section


def _deg(rad):
    """Angle(s) in rad as degrees."""
    return in_unit(rad, "rad", "deg")


def _peak_text(q: dict, design: int, group: int, case: str | None) -> list[str]:
    """The peak of quantity ``damper.peak_nose_amplitude`` with its order and speed."""
    v = q["damper.peak_nose_amplitude"].values[design, group]
    if not np.isfinite(v):
        return ["-", "-"]
    order = q["damper.peak_order"].values[design, group]
    speed = q["damper.peak_speed"].values[design, group]
    where = f"order {order:g}, " + (f"{case_text(case)}, " if case else "")
    return [fmt(_deg(v), 4), f"{where}{rpm(speed):.0f} rpm"]


_SHORT = {"damper.end_tuning_ratio": "tuning ratio", "damper.end_shear_stress": "shear stress",
          "damper.end_heat_density": "heat per volume", "damper.heat_flux": "heat per area",
          "damper.silicone_temperature": "silicone temperature",
          "damper.damping_to_optimum": "c / c_opt"}


def _judged_table(res: CheckResult, names: tuple[str, ...], caption: str) -> dict | None:
    """The damper's judged worst points at the cold and hot ends (quantities over end, case,
    speed): per quantity the judged worst of each end and load case, most severe first (the
    rule result's value and point; a range rule shows the point of its result only), then,
    marked, worse points the rules do not judge."""
    q = res.outcome.quantities
    rows, css = [], []
    for name in names:
        qq = q.get(name)
        rr = [r for r in res.results if r.value is not None and r.status != "not_evaluated"
              and any(x.id == r.rule and x.quantity == name for x in res.rules)]
        if qq is None or not rr:
            continue
        ends, cases = qq.coords["end"], qq.coords["case"]
        sp = rpm(np.array(qq.coords["speed"], dtype=float))
        lim = (qq.item_attrs.get("all") or {}).get("limit")
        lim_txt = "-" if lim is None else " .. ".join(
            f"{fmt(display_values(qq, x)[0])}" for x in lim) + f" {display_values(qq, 0)[1]}"
        how = jd.direction(res, name, "max")
        found = [jd.worst(qq, (e, c), how) for e in range(len(ends)) for c in range(len(cases))]
        sign = 1.0 if how == "max" else -1.0
        judged = sorted((j for j, _ in found if j is not None), key=lambda p: -sign * p.value)
        unjudged = [u for _, u in found if u is not None]
        if lim is not None and len(lim) == 2:  # a range: the point of the rule's result only
            shown = display_values(qq, np.array([p.value for p in judged]))[0]
            judged = [judged[int(np.argmin(np.abs(shown - rr[0].value)))]] if judged else []
            unjudged = []  # (larger is not worse for a range)
        for p in judged + unjudged:
            e, c, k = p.index
            val, unit = display_values(qq, p.value)
            rows.append([_SHORT.get(name, name), case_text(cases[c]),
                         f"{fmt(val)} {unit}".strip(), lim_txt, f"{sp[k]:.0f}", ends[e],
                         jd.judged_text(res, qq, p, None, cases[c])])
            css.append(jd.row_css(p))
    if not rows:
        return None
    return {"type": "table", "caption": caption,
            "columns": ["quantity", "case", "value", "limit", "speed [rpm]", "end",
                        "judged by"], "rows": rows, "row_css": css}


def _ends_rows(d, q, cols) -> list[list[str]]:
    """One row per end and load case at the speed of the largest dissipated power."""
    rows = []
    for e, end in enumerate(d.ends):
        for c, case in enumerate(d.cases):
            p = d.power[e, c]
            if not np.isfinite(p).any():
                rows.append([end, case_text(case), fmt(in_unit(d.air_temperature[e], "K",
                                                               "degC"), 3)]
                            + ["-"] * (len(cols) - 3))
                continue
            k = int(np.nanargmax(p))
            rows.append([end, case_text(case),
                         fmt(in_unit(d.air_temperature[e], "K", "degC"), 3),
                         f"{rpm(d.speeds[k]):.0f}", fmt(p[k], 3),
                         fmt(in_unit(d.temperature[e, c, k], "K", "degC"), 3)]
                        + [f(e, c, k) for _, f in cols[6:]])
    return rows


def _ends_figure(d, caption: str, what: str, data: list[str]) -> dict:
    """Damper temperature and crank-nose amplitude against speed, cold and hot end."""
    return {"type": "figure", "png": later((170, 64), _draw_ends, d, what), "caption": caption,
            "data": data}


def _draw_ends(d, what: str) -> bytes:
    """The figure of :func:`_ends_figure`."""
    sp = rpm(d.speeds)
    fig, axes = figure(170, 64, ncols=2, legend_rows=1)
    for c, case in enumerate(d.cases):
        axes[1].plot(sp, _deg(d.nominal_nose_amplitude[c]), color="0.5",
                     ls="--" if c else "-")
        for e, end in enumerate(d.ends):
            color = "tab:blue" if end == "cold" else "tab:red"
            ls = "--" if c else "-"
            axes[0].plot(sp, in_unit(d.temperature[e, c], "K", "degC"), color=color, ls=ls,
                         label=f"{end}, {case_text(case)}")
            axes[1].plot(sp, _deg(d.nose_amplitude[e, c]), color=color, ls=ls)
    axes[0].set_ylabel(f"{what} temperature [°C]")
    axes[1].set_ylabel("Nose amplitude, all orders [deg]")
    for ax in axes:
        ax.set_xlabel("Engine speed [rpm]")
    legend_below(fig, axes=[axes[0]], ncols=4)
    return to_image(fig)


def _rubber_ends_blocks(res: CheckResult, q: dict) -> list[dict]:
    """The rubber at the cold and hot ends (DMP-005..007)."""
    tq = q["damper.end_tuning_ratio"]
    d = tq.detail
    tau, heat = q["damper.end_shear_stress"], q["damper.end_heat_density"]
    cols = [("end", None), ("load", None), ("air [°C]", None), ("speed [rpm]", None),
            ("power [W]", None), ("rubber [°C]", None),
            ("k' [kN m/rad]", lambda e, c, k: fmt(in_unit(d.stiffness[e, c, k], "N*m/rad",
                                                           "kN*m/rad"), 4)),
            ("η", lambda e, c, k: fmt(d.loss_factor[e, c, k], 3)),
            ("tuning f", lambda e, c, k: fmt(tq.values[e, c, k], 4)),
            ("τ max [MPa]", lambda e, c, k: fmt(in_unit(np.nanmax(tau.values[e, c]), "Pa",
                                                         "MPa"), 3)),
            ("q max [W/cm³]", lambda e, c, k: fmt(in_unit(np.nanmax(heat.values[e, c]),
                                                           "W/m**3", "W/cm**3"), 3)),
            ("nose max [deg]", lambda e, c, k: fmt(_deg(np.nanmax(d.nose_amplitude[e, c])),
                                                   3))]
    table = [(t, fmt(in_unit(t, "K", "degC"), 3), fmt(in_unit(g, "Pa", "MPa"), 4),
              fmt(eta, 3)) for t, g, eta in d.table]
    return [
        {"type": "heading", "text": "Rubber at the cold and hot ends of the operating range"},
        {"type": "equations", "items": [
            ("Rubber at its temperature", "k*(T) = Φ_r G'(T) (1 + j η(T)),  Φ_r = 4π L r_i²"
             " r_o² / (r_o² − r_i²)", "Gent 2012, ch. 8; table sheet DamperRubber"),
            ("Own temperature", "T = T_air + P(T) / (h A)  (per speed and load case)",
             "Incropera et al. 2007, eq. 1.3a"),
            ("Tuning at T", "f = √(k'(T) / J_ring) / ω_n", "Den Hartog 1956, sec. 3.3")]},
        {"type": "table", "caption": "DamperRubber table (ln G' and η interpolated linearly"
         " in temperature)", "columns": ["temperature [°C]", "G' [MPa]", "η"],
         "rows": [[r[1], r[2], r[3]] for r in table]},
        {"type": "table", "caption": "Rubber at the speed of its largest dissipated power per"
         " end and load case (rules DMP-005..007; maxima over every speed)",
         "columns": [c for c, _ in cols], "rows": _ends_rows(d, q, cols)},
        *([t] if (t := _judged_table(res, ("damper.end_tuning_ratio",
                                           "damper.end_shear_stress",
                                           "damper.end_heat_density"),
                                     "Rubber at the cold and hot ends against the limits (rules"
                                     " DMP-005..007): the judged worst first (the value of the"
                                     " rule result), then, marked, worse values at points the"
                                     " rules do not judge")) else []),
        _ends_figure(d, "Rubber temperature from its own heat (left) and crank-nose"
                     " amplitude (right) at the cold (blue) and hot (red) end; grey: the"
                     " nominal rubber of the TV section", "Rubber",
                     ["damper.end_rubber_temperature", "damper.end_nose_amplitude",
                      "tv.nose_amplitude"]),
    ]


def _viscous_section(res: CheckResult) -> dict:
    """The untuned viscous damper: coupling, Den Hartog's optimum, heat at both ends."""
    q = res.outcome.quantities
    title = "TV damper (viscous)"
    co = q.get("damper.optimum_damping")
    if co is None:
        why = "; ".join(res.outcome.unavailable.get("damper.optimum_damping",
                                                    ["not computed"]))
        return {"id": "damper", "title": title, "intro": f"Not computed: {why}.",
                "blocks": []}
    d = co.detail
    opt = q["damper.damping_to_optimum"]
    flux = q["damper.heat_flux"]
    blocks: list[dict] = [{"type": "equations", "items": [
        ("Silicone coupling", "c = ρ ν(T) Φ,  Φ = 2π b (r_o³ + r_i³)/h_r + π (r_o⁴ − r_i⁴)/h_a",
         "Couette shear on every wetted face (White 2006, sec. 3-2)"),
        ("Viscosity", "ν(T) = ν_ref exp(B (1/T − 1/T_ref)),  B from the datasheet's VTC",
         "Andrade 1930"),
        ("Maxwell fluid", "z = jΩc k_s / (k_s + jΩc),  k_s = G Φ",
         "Andre & Spurk 1982, J. Sound Vib. 82(4)"),
        ("Optimum", "c_opt = 2 J_ring ω_n / √(2 (1 + μ)(2 + μ));  peak 1 + 2/μ at"
         " Ω/ω_n = √(2/(2 + μ))", "Den Hartog 1956, ch. 3 (untuned viscous damper)"),
        ("Heat", "P = Σ ½ Ω Im z |Δφ|²,  T = T_air + P / (h A)",
         "Den Hartog 1956, sec. 2.8; Incropera et al. 2007, eq. 1.3a"),
    ]}]
    rows = [
        ["Ring inertia J_ring (" + d.ring + ")", fmt(d.ring_inertia, 4), "kg m²"],
        ["Crank first mode without the ring", fmt(d.crank_mode_omega / (2 * np.pi), 4), "Hz"],
        ["Modal inertia at the hub J_eq", fmt(d.modal_inertia, 4), "kg m²"],
        ["Inertia ratio μ", fmt(d.mass_ratio, 3), "-"],
        ["Optimum damping c_opt", fmt(d.damping_optimum, 4), "N m s/rad"],
        ["Damping at the reference temperature / typed c", fmt(d.damping_nominal, 4),
         "N m s/rad"],
        ["Coupling", d.coupling + ("" if d.shear_stiffness is None else
                                   f"; Maxwell k_s = {fmt(d.shear_stiffness, 4)} N m/rad"), ""],
        ["Peak magnification at the optimum 1 + 2/μ", fmt(d.peak_magnification, 4), "-"],
        ["Wetted ring area", fmt(None if d.wetted_area is None else
                                 in_unit(d.wetted_area, "m**2", "cm**2"), 4), "cm²"],
        ["Heat path 1/(h A)", "not given: no self-heating" if d.heat_resistance is None
         else fmt(d.heat_resistance, 3), "" if d.heat_resistance is None else "K/W"],
    ]
    blocks.append({"type": "table", "caption": "Untuned viscous damper and Den Hartog's"
                   " optimum for this crank", "columns": ["quantity", "value", "unit"],
                   "rows": rows})
    cols = [("end", None), ("load", None), ("air [°C]", None), ("speed [rpm]", None),
            ("power [W]", None), ("silicone [°C]", None),
            ("c [N m s/rad]", lambda e, c, k: fmt(d.damping[e, c, k], 4)),
            ("c / c_opt", lambda e, c, k: fmt(opt.values[e, c, k], 3)),
            ("P/A max [W/cm²]", lambda e, c, k: fmt(in_unit(np.nanmax(flux.values[e, c]),
                                                             "W/m**2", "W/cm**2"), 3)),
            ("silicone max [°C]", lambda e, c, k: fmt(in_unit(np.nanmax(d.temperature[e, c]),
                                                              "K", "degC"), 3)),
            ("nose max [deg]", lambda e, c, k: fmt(_deg(np.nanmax(d.nose_amplitude[e, c])),
                                                   3))]
    blocks.append({"type": "table", "caption": "Viscous damper at the speed of its largest"
                   " dissipated power per end and load case (rules DMP-008..010; maxima over"
                   " every speed)", "columns": [c for c, _ in cols],
                   "rows": _ends_rows(d, q, cols)})
    t = _judged_table(res, ("damper.heat_flux", "damper.silicone_temperature",
                            "damper.damping_to_optimum"),
                      "Viscous damper against the limits (rules DMP-008..010): the judged worst"
                      " first (the value of the rule result), then, marked, worse values at"
                      " points the rules do not judge")
    if t is not None:
        blocks.append(t)
    blocks.append(_ends_figure(d, "Silicone temperature from the housing's heat balance"
                               " (left) and crank-nose amplitude (right) at the cold (blue)"
                               " and hot (red) end; grey: the TV section's nominal damper (the"
                               " silicone at its reference temperature)", "Silicone",
                               ["damper.silicone_temperature", "damper.viscous_nose_amplitude",
                                "tv.nose_amplitude"]))
    parts = []
    for e, end in enumerate(d.ends):
        v = np.where(opt.applies[e] if opt.applies is not None else True, opt.values[e],
                     np.nan)
        if np.isfinite(v).any():
            parts.append(f"{fmt(np.nanmin(v), 3)}..{fmt(np.nanmax(v), 3)} × c_opt at the"
                         f" {end} end")
    intro = (f"An untuned viscous damper: ring {fmt(d.ring_inertia, 3)} kg m², μ ="
             f" {fmt(d.mass_ratio, 3)}; Den Hartog's optimum damping for this crank is"
             f" {fmt(d.damping_optimum, 3)} N m s/rad. At the crank resonance the silicone's"
             f" damping is {'; '.join(parts) or '-'} (its viscosity follows its own"
             " temperature). The rubber damper's rules (DMP-001..007) do not apply.")
    return {"id": "damper", "title": title, "intro": intro, "blocks": blocks}


@section("damper")
def damper_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
    if res.engine.damper.get("damper_type") == "viscous":
        return _viscous_section(res)
    tr = q.get("damper.tuning_ratio")
    title = "TV damper tuning"
    if tr is None:
        why = "; ".join(res.outcome.unavailable.get("damper.tuning_ratio", ["not computed"]))
        return {"id": "damper", "title": title, "intro": f"Not computed: {why}.", "blocks": []}
    ex = tr.detail

    def v(name: str) -> float:  # a damper-tuning quantity (SI), one damper ring
        return float(q[name].values[0])
    eng = res.engine
    lim = tr.item_attrs.get(tr.coords["item"][0], {}).get("limit")
    blocks: list[dict] = [{"type": "equations", "items": [
        ("Primary system", "ω_n, J_eq = Σ J_i (φ_i/φ_hub)²: first flexible mode of the chain"
         " without the ring", "Drapal & Novotny 2017, J. Vibroeng. 19(7), eq. 3"),
        ("Tuning ratio", "f = ω_d / ω_n,  ω_d = √(k / J_ring)", "Den Hartog 1956, sec. 3.3"),
        ("Optimum", "f_opt = 1/(1 + μ),  ζ_opt = √(3μ / (8 (1 + μ)³)),  μ = J_ring / J_eq",
         "Den Hartog 1956, eqs. 3.19, 3.23"),
        ("Rubber damping", "ζ = η f / 2 + c / (2 J_ring ω_n);  η_opt = 2 ζ_opt / f_opt",
         "viscous equivalent of the hysteretic rubber at the ring frequency"),
    ]}]
    rows = [
        ["Ring inertia J_ring (" + ex.ring + ")",
         fmt(in_unit(ex.ring_inertia, "kg*m**2", "g*m**2"), 5), "g m²", "-"],
        ["Rubber stiffness k", fmt(in_unit(ex.stiffness, "N*m/rad", "kN*m/rad"), 5),
         "kN m/rad", fmt(in_unit(v("damper.optimum_stiffness"), "N*m/rad", "kN*m/rad"), 5)],
        ["Rubber loss factor η", fmt(ex.loss_factor, 4), "-",
         fmt(v("damper.optimum_loss_factor"), 4)],
        ["Rubber viscous damping c", fmt(ex.relative_damping, 4), "N m s/rad", "0"],
        ["Crank first mode without the ring", fmt(v("damper.crank_mode_frequency"), 5), "Hz",
         "-"],
        ["Modal inertia at the hub (" + ex.hub + ")",
         fmt(in_unit(v("damper.modal_inertia"), "kg*m**2", "g*m**2"), 5), "g m²", "-"],
        ["Inertia ratio μ", fmt(v("damper.mass_ratio"), 4), "-", "-"],
        ["Ring natural frequency", fmt(v("damper.ring_frequency"), 5), "Hz",
         fmt(v("damper.optimum_ring_frequency"), 5)],
        ["Tuning ratio f", fmt(v("damper.tuning_ratio"), 4), "-",
         fmt(v("damper.optimum_tuning_ratio"), 4)],
        ["Damping ratio ζ (equivalent viscous)", fmt(v("damper.damping_ratio"), 4), "-",
         fmt(v("damper.optimum_damping_ratio"), 4)],
        ["Project tuning band", "-" if lim is None else f"{lim[0]:g} .. {lim[1]:g}", "-",
         eng.cell("Damper", "tuning_ratio_min")],
    ]
    blocks.append({"type": "table", "caption": "Actual damper and Den Hartog's optimum for its"
                   " inertia ratio", "columns": ["quantity", "actual", "unit", "optimum"],
                   "rows": rows})
    pk = ex.peaks
    rows = []
    for g, name in enumerate(("cylinder order", "higher orders")):
        cases = [(pk[d].get(name) or {}).get("case") for d in ("actual", "optimum")]
        rows.append([name] + _peak_text(q, 0, g, cases[0]) + _peak_text(q, 1, g, cases[1]))
    blocks.append({"type": "table", "caption": "Crank-nose amplitude at the resonant peaks"
                   " (as rules TV-001/TV-002 judge them): actual damper and the same model with"
                   " the optimum rubber",
                   "columns": ["orders", "actual [deg]", "where", "optimum [deg]", "where"],
                   "rows": rows})
    on = q.get("damper.optimum_nose_amplitude")
    if on is not None:
        sp = rpm(np.array(on.coords["speed"]))
        png = later((170, 64), _draw_optimum, sp, list(on.coords["case"]), ex, on.values)
        blocks.append({"type": "figure", "png": png,
                       "data": ["tv.nose_amplitude", "damper.optimum_nose_amplitude"],
                       "caption": "Crank-nose amplitude, actual damper (solid) and optimum"
                                  " rubber (dashed): the cylinder-count order and all orders"
                                  " synthesised (the low-speed part is the rigid-body"
                                  " rolling motion, which the damper does not change)"})
    if "damper.end_tuning_ratio" in q:
        blocks += _rubber_ends_blocks(res, q)
    f, f_opt = v("damper.tuning_ratio"), v("damper.optimum_tuning_ratio")
    dev = (f / f_opt - 1.0) * 100
    return {"id": "damper", "title": title,
            "intro": f"The damper ring is tuned to {f:.3f} of the crank's first mode;"
                     f" Den Hartog's optimum for its inertia ratio μ ="
                     f" {v('damper.mass_ratio'):.3f} is"
                     f" {f_opt:.3f} ({dev:+.1f} % off) with a damping ratio of"
                     f" {v('damper.optimum_damping_ratio'):.3f} (actual"
                     f" {v('damper.damping_ratio'):.3f}). The"
                     " crank-nose amplitude with the optimum rubber comes from the same"
                     " torsional model with only the rubber changed.",
            "blocks": blocks}


def _draw_optimum(sp, cases: list[str], ex, optimum_nose) -> bytes:
    """Crank-nose amplitude against speed, actual damper and optimum rubber: the
    cylinder-count order (left) and all orders (right)."""
    k = ex.cylinder_order_index
    fig, axes = figure(170, 64, ncols=2, legend_rows=1)
    for c_i, c in enumerate(cases):
        for ax, act, opt in ((axes[0], np.abs(ex.actual_theta[c_i, :, k]),
                              np.abs(ex.optimum_theta[c_i, :, k])),
                             (axes[1], ex.actual_nose_amplitude[c_i],
                              optimum_nose[c_i])):
            line = ax.plot(sp, _deg(act), label=f"actual, {case_text(c)}")[0]
            ax.plot(sp, _deg(opt), ls="--", color=line.get_color(),
                    label=f"optimum, {case_text(c)}")
    axes[0].set_ylabel(f"Nose amplitude, order {ex.cylinder_order:g} [deg]")
    axes[1].set_ylabel("Nose amplitude, all orders [deg]")
    axes[1].set_yscale("log")
    for ax in axes:
        ax.set_xlabel("Engine speed [rpm]")
    legend_below(fig, axes=[axes[0]], ncols=4)
    return to_image(fig)
