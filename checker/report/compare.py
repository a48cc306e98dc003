"""The design-review pack of ``checker compare``: input changes, result changes (status
changes first), side-by-side worst cases and the key curves of baseline and variants
overlaid. Formatting only: every number comes from the checks and :mod:`checker.compare`."""

from __future__ import annotations

import base64
import datetime as _dt
import hashlib
from pathlib import Path
from typing import Any

import numpy as np

from .. import __version__
from ..compare import Comparison
from ..display import with_unit
from ..resources import templates_dir
from ..units import from_si

# (quantity, case, title, y label, display unit, reduce over items)
CURVES = (
    ("bearing.peak_specific_load", "full", "Peak specific load, full load",
     "specific load [MPa]", "MPa", None),
    ("bearing.moft", "full", "Minimum oil film thickness, full load", "MOFT [µm]", "um",
     None),
    ("tv.nose_amplitude", "full", "Crank-nose amplitude (all orders), full load",
     "amplitude [deg]", "deg", None),
    ("fatigue.goodman_sf", "full", "Smallest Goodman safety factor, full load",
     "Goodman SF [-]", "", "min"),
)
_STYLES = ("-", "--", ":", "-.")
_NOT_STATUS = ("margin changed", "value changed (not evaluated)")


def _label(text: str) -> str:
    return str(text).replace("\\", "\\\\").replace("$", r"\$")


def _series(res, qname: str, case: str, unit: str, reduce: str | None):
    q = res.outcome.quantities.get(qname)
    if q is None or "speed" not in q.spec.dims or case not in [str(c) for c in
                                                                  q.coords.get("case", [])]:
        return None
    ci = [str(c) for c in q.coords["case"]].index(case)
    rpm = np.array([from_si(float(s), "rad/s", "rpm") for s in q.coords["speed"]])
    vals = np.take(q.values, ci, axis=q.spec.dims.index("case"))
    if unit:  # affine where the unit is (K -> °C), never a factor
        vals = np.asarray(from_si(np.asarray(vals, dtype=float), q.spec.unit or "", unit))
    if "item" in q.spec.dims:
        if reduce == "min":
            with np.errstate(all="ignore"):
                return {"all": (rpm, np.nanmin(vals, axis=0))}
        return {it: (rpm, vals[i]) for i, it in enumerate(q.coords["item"])}
    return {"": (rpm, vals)}


def _figures(comps: list[Comparison]) -> list[dict[str, Any]]:
    from .plots import figure, legend_below, to_svg

    runs = [comps[0].baseline] + [c.variant for c in comps]
    names = [Path(r.engine.source).name for r in runs]
    out = []
    for qname, case, title, ylabel, unit, reduce in CURVES:
        series = [_series(r, qname, case, unit, reduce) for r in runs]
        if series[0] is None:
            continue
        items = list(series[0])
        n = len(items)
        cols = 1 if n == 1 else min(n, 3)
        rows = (n + cols - 1) // cols
        fig, axes = figure(170, 45 * rows if n > 1 else 70, nrows=rows, ncols=cols,
                           squeeze=False)
        for k, it in enumerate(items):
            ax = axes[k // cols][k % cols]
            for j, s in enumerate(series):
                if s is None or it not in s:
                    continue
                x, y = s[it]
                ax.plot(x, y, _STYLES[j % len(_STYLES)], color=f"C{j}",
                        label=_label(names[j]) if k == 0 else None)
            if it and it != "all":
                ax.set_title(_label(it), fontsize=8)
            if k % cols == 0:
                ax.set_ylabel(ylabel)
            if k // cols == rows - 1:
                ax.set_xlabel("speed [rpm]")
        for k in range(n, rows * cols):
            axes[k // cols][k % cols].set_visible(False)
        fig.tight_layout()
        legend_below(fig, axes=[axes[0][0]])  # below the axes: never cut off, never on data
        svg = to_svg(fig)
        out.append({"title": title, "src": "data:image/svg+xml;base64," + base64.b64encode(
            svg.encode()).decode("ascii"),
            "caption": f"{title}: baseline (solid) and variants overlaid; per-speed values"
            " are in each workbook's own check."})
    return out


def _fmt_side(s: dict | None) -> str:
    if s is None:
        return "-"
    v = with_unit(s["value"], s["unit"], sig=4)
    m = "" if s["margin"] is None else f" ({s['margin'] * 100:+.1f} %)"
    return f"{s['status'].replace('_', ' ').upper()}: {v}{m}"


def render(comps: list[Comparison]) -> tuple[str, bytes]:
    """(HTML, PDF bytes) of the pack."""
    from jinja2 import Environment, FileSystemLoader, StrictUndefined, select_autoescape
    from weasyprint import HTML

    base = comps[0].baseline
    ctx = {
        "title": "Design-review comparison", "date": _dt.date.today().isoformat(),
        "version": __version__, "baseline": Path(base.engine.source).name,
        "sha256": base.engine.sha256,
        "css": (templates_dir() / "report.css").read_text(encoding="utf-8"),
        "comparisons": [{
            "variant": Path(c.variant.engine.source).name,
            "verdicts": (c.baseline.verdict_text, c.variant.verdict_text),
            "inputs": c.inputs,
            "inputs_text": c.inputs_text(),
            "status_changes": [dict(r, b=_fmt_side(r["baseline"]), v=_fmt_side(r["variant"]))
                               for r in c.results if r["change"] not in _NOT_STATUS],
            # a margin change needs a margin on both sides; a not-evaluated result whose
            # computed value moved is listed as such, never as a margin change
            "margin_changes": [dict(r, b=_fmt_side(r["baseline"]), v=_fmt_side(r["variant"]))
                               for r in c.results if r["change"] == "margin changed"
                               and r["margin_change"] is not None][:40],
            "n_margin": sum(1 for r in c.results if r["change"] == "margin changed"
                            and r["margin_change"] is not None),
            "value_changes": [dict(r, b=_fmt_side(r["baseline"]), v=_fmt_side(r["variant"]))
                              for r in c.results
                              if r["change"] == "value changed (not evaluated)"][:40],
        } for c in comps],
        "figures": _figures(comps),
    }
    env = Environment(loader=FileSystemLoader(str(templates_dir())),
                      autoescape=select_autoescape(["html"]), undefined=StrictUndefined)
    html = env.get_template("compare.html").render(**ctx)
    ident = hashlib.sha256(html.encode("utf-8")).hexdigest()[:32].encode()
    return html, HTML(string=html, base_url=str(templates_dir())).write_pdf(
        pdf_identifier=ident)
