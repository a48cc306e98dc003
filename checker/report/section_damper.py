"""Report section: TV damper tuning against Den Hartog's optimum (module ``damper``,
:mod:`checker.modules.damper_tuning`; detail :class:`checker.results.damper.DamperTuningDetail`).
The damper rubber's stress and heat are in the torsion section."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..display import case_text
from .plots import figure, legend_below, to_image
from .sections import fmt, in_unit, rpm, section


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


@section("damper")
def damper_section(res: CheckResult) -> dict:
    q = res.outcome.quantities
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
        k = ex.cylinder_order_index
        fig, axes = figure(170, 64, ncols=2, legend_rows=1)
        for c_i, c in enumerate(on.coords["case"]):
            for ax, act, opt in ((axes[0], np.abs(ex.actual_theta[c_i, :, k]),
                                  np.abs(ex.optimum_theta[c_i, :, k])),
                                 (axes[1], ex.actual_nose_amplitude[c_i],
                                  on.values[c_i])):
                line = ax.plot(sp, _deg(act), label=f"actual, {case_text(c)}")[0]
                ax.plot(sp, _deg(opt), ls="--", color=line.get_color(),
                        label=f"optimum, {case_text(c)}")
        axes[0].set_ylabel(f"Nose amplitude, order {ex.cylinder_order:g} [deg]")
        axes[1].set_ylabel("Nose amplitude, all orders [deg]")
        axes[1].set_yscale("log")
        for ax in axes:
            ax.set_xlabel("Engine speed [rpm]")
        legend_below(fig, axes=[axes[0]], ncols=4)
        blocks.append({"type": "figure", "png": to_image(fig),
                       "data": ["tv.nose_amplitude", "damper.optimum_nose_amplitude"],
                       "caption": "Crank-nose amplitude, actual damper (solid) and optimum"
                                  " rubber (dashed): the cylinder-count order and all orders"
                                  " synthesised (the low-speed part is the rigid-body"
                                  " rolling motion, which the damper does not change)"})
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
