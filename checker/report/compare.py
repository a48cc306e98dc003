"""The design-review pack of ``checker compare``: input changes, result changes (status
changes first), side-by-side worst cases and the key curves of baseline and variants
overlaid. Formatting only: every number comes from the checks and :mod:`checker.outputs.compare`."""

from __future__ import annotations

import base64
import datetime as _dt
import hashlib
from pathlib import Path
from typing import Any

import numpy as np

from .. import __version__
from ..outputs.compare import Comparison
from ..plumbing.resources import templates_dir
from ..results.display import item_label, with_unit
from ..workbook.units import from_si

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


_METHOD_QUANTITY = {"finite length": "bearing.moft_finite", "short bearing": "bearing.moft_short"}


def _quantity(res, qname: str):
    """The quantity ``qname``, or for the film thickness the method the rules judged (the
    film is computed by two methods: ``bearing.moft_finite`` / ``bearing.moft_short``)."""
    q = res.outcome.quantities.get(qname)
    if q is not None or qname != "bearing.moft":
        return q
    on = next((r.judged_on for r in res.results if r.rule.startswith("BRG") and r.judged_on),
              "")
    names = [_METHOD_QUANTITY[on]] if on in _METHOD_QUANTITY else []
    for n in names + list(_METHOD_QUANTITY.values()):
        if n in res.outcome.quantities:
            return res.outcome.quantities[n]
    return None


def _series(res, qname: str, case: str, unit: str, reduce: str | None):
    q = _quantity(res, qname)
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


def _moved(series: list[dict | None], it: str) -> bool:
    """Whether any variant's curve of ``it`` differs from the baseline's."""
    b = series[0].get(it) if series[0] else None
    if b is None:
        return False
    for s in series[1:]:
        v = None if s is None else s.get(it)
        if v is None:
            return True
        x, y = np.asarray(b[1], float), np.asarray(v[1], float)
        if x.shape != y.shape or not np.allclose(x, y, rtol=1e-6, atol=0, equal_nan=True):
            return True
    return False


def _figures(comps: list[Comparison]) -> list[dict[str, Any]]:
    """Overlays of the key curves that the change moved (an unchanged curve is named in a
    line instead of drawn)."""
    from .plots import figure, legend_below, to_image

    runs = [comps[0].baseline] + [c.variant for c in comps]
    names = [Path(r.engine.source).name for r in runs]
    out = []
    for qname, case, title, ylabel, unit, reduce in CURVES:
        series = [_series(r, qname, case, unit, reduce) for r in runs]
        if series[0] is None:
            continue
        items = [it for it in series[0] if _moved(series, it)]
        same = [it for it in series[0] if it not in items]
        if not items:
            out.append({"title": title, "src": None, "caption": f"{title}: unchanged by the"
                        " variants (not drawn)."})
            continue
        groups: list[list[str]] = []  # items with identical curves in every run: one panel
        for it in items:
            for g in groups:
                if all(sr is not None and it in sr and g[0] in sr and np.allclose(
                        np.asarray(sr[g[0]][1], float), np.asarray(sr[it][1], float),
                        rtol=1e-9, atol=0, equal_nan=True) for sr in series):
                    g.append(it)
                    break
            else:
                groups.append([it])
        title_of = {g[0]: " = ".join(g) for g in groups}
        items = [g[0] for g in groups]
        n = len(items)
        cols = 1 if n == 1 else min(n, 3)
        rows = (n + cols - 1) // cols
        fig, axes = figure(170, 45 * rows + 10 if n > 1 else 70, nrows=rows, ncols=cols,
                           squeeze=False, legend_rows=1)
        for k, it in enumerate(items):
            ax = axes[k // cols][k % cols]
            for j, s in enumerate(series):
                if s is None or it not in s:
                    continue
                x, y = s[it]
                ax.plot(x, y, _STYLES[j % len(_STYLES)], color=f"C{j}",
                        label=_label(names[j]) if k == 0 else None)
            if it and it != "all":
                ax.set_title(_label(title_of[it]), fontsize=8)
            if k % cols == 0:
                ax.set_ylabel(ylabel)
            if k // cols == rows - 1:
                ax.set_xlabel("speed [rpm]")
        for k in range(n, rows * cols):
            axes[k // cols][k % cols].set_visible(False)
        legend_below(fig, axes=[axes[0][0]])  # below the axes: never cut off, never on data
        png = to_image(fig)
        note = ("" if not same or same == [""] else
                " Unchanged, not drawn: " + ", ".join(x for x in same if x) + ".")
        out.append({"title": title, "src": "data:image/jpeg;base64,"
                    + base64.b64encode(bytes(png)).decode("ascii"),
                    "caption": f"{title}: baseline (solid) and variants overlaid, only the"
                    " curves the change moved." + note})
    return out


_UNITS = {"N/mm^2": "MPa", "N/mm²": "MPa", "N/mm2": "MPa", "N mm^-2": "MPa"}


def _unit(u: str | None) -> str:
    return _UNITS.get(u or "", u or "")


def _fmt_side(s: dict | None) -> str:
    if s is None:
        return "-"
    v = "-" if s.get("value") is None else with_unit(s["value"], s.get("unit"), sig=4)
    m = "" if s.get("margin") is None else f" (margin {s['margin'] * 100:+.1f} %)"
    return f"{str(s.get('status') or '-').replace('_', ' ').upper()}: {v}{m}"


def _points(dm: float | None) -> str:
    """A margin change in points of the relative margin ('+12.3 points')."""
    return "-" if dm is None else f"{dm * 100:+.1f} points"


def _trade(c: Comparison) -> dict[str, Any]:
    """The net trade of a variant: what newly passes, what newly fails, what got worse and
    better (by how much, in points of the relative margin)."""
    def line(r: dict) -> str:
        where = item_label(r["item"])
        return (f"{r['rule']} {r['name']}, {where}: {_fmt_side(r['baseline'])} → "
                f"{_fmt_side(r['variant'])}")
    worse = [r for r in c.results if r["change"] == "margin changed"
             and (r["margin_change"] or 0) < 0]
    better = [r for r in c.results if r["change"] == "margin changed"
              and (r["margin_change"] or 0) > 0]
    worse.sort(key=lambda r: r["margin_change"])
    better.sort(key=lambda r: -r["margin_change"])

    def moved(rs: list[dict]) -> list[str]:
        return [f"{r['rule']} {r['name']}, {item_label(r['item'])}:"
                f" {_points(r['margin_change'])}" for r in rs[:5]]
    return {
        "newly_passing": [line(r) for r in c.results if r["change"] == "newly passing"],
        "newly_failing": [line(r) + f" ({_points(r['margin_change'])})"
                          for r in c.results if r["change"] == "newly failing"],
        "worse": moved(worse), "n_worse": len(worse),
        "better": moved(better), "n_better": len(better),
    }


def render(comps: list[Comparison]) -> tuple[str, bytes]:
    """(HTML, PDF bytes) of the pack."""
    from weasyprint import HTML

    html = pack_html(comps)
    ident = hashlib.sha256(html.encode("utf-8")).hexdigest()[:32].encode()
    return html, HTML(string=html, base_url=str(templates_dir())).write_pdf(
        pdf_identifier=ident)


def pack_html(comps: list[Comparison]) -> str:
    """The pack as HTML (what :func:`render` lays out)."""
    from jinja2 import Environment, FileSystemLoader, StrictUndefined, select_autoescape

    base = comps[0].baseline

    def rows(c: Comparison, keep) -> list[dict]:
        return [dict(r, b=_fmt_side(r["baseline"]), v=_fmt_side(r["variant"]),
                     dm=_points(r["margin_change"]))
                for r in c.results if keep(r)]

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
            "trade": _trade(c),
            "status_changes": rows(c, lambda r: r["change"] not in _NOT_STATUS),
            # a margin change needs a margin on both sides; a not-evaluated result whose
            # computed value moved is listed as such, never as a margin change
            "margin_changes": rows(c, lambda r: r["change"] == "margin changed"
                                   and r["margin_change"] is not None)[:40],
            "n_margin": sum(1 for r in c.results if r["change"] == "margin changed"
                            and r["margin_change"] is not None),
            "value_changes": rows(c, lambda r: r["change"]
                                  == "value changed (not evaluated)")[:40],
        } for c in comps],
        "figures": _figures(comps),
    }
    env = Environment(loader=FileSystemLoader(str(templates_dir())),
                      autoescape=select_autoescape(["html"]), undefined=StrictUndefined)
    env.filters["item_label"] = item_label
    return env.get_template("compare.html").render(**ctx)
