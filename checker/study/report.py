"""The study PDF: feasibility per rule family, margin-vs-parameter plots, a 2-D feasibility
map for two-parameter studies, the sensitivity ranking and the best variant. Formatting only:
every number comes from :mod:`checker.study.results`."""

from __future__ import annotations

import base64
import datetime as _dt
from typing import Any

import numpy as np

from .. import __version__
from ..resources import templates_dir
from .results import STATUS_ORDER, best_variant, sensitivity, variant_table
from .run import StudyRun

_COLOURS = {"pass": "#27ae60", "warning": "#d68910", "fail": "#c0392b",
            "not_evaluated": "#7f8c8d", "input error": "#34495e", "-": "#bdc3c7"}


def _label(text: str) -> str:
    """Workbook/study text as literal plot text (no mathtext)."""
    return str(text).replace("\\", "\\\\").replace("$", r"\$")


def _img(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")


def _item_margins(df, items: tuple[str, ...], fam: str) -> dict[int, float]:
    """Smallest error-severity margin per variant over the results of ``items``."""
    sel = df[(df["rule"].map(lambda r: r.split("-")[0]) == fam) & df["item"].isin(items)
             & (df["severity"] == "error")]
    return {int(k): float(g["margin"].min()) for k, g in sel.groupby("variant")
            if g["margin"].notna().any()}


def _margin_figures(vt, run: StudyRun, fams: list[str], df=None) -> list[dict[str, Any]]:
    from ..report.plots import figure, legend_below, to_svg

    params = [q for q in run.study.parameters if q.numeric]
    if not params:
        return []
    items_of = {t.param.name: t.items for t in run.targets}
    figs = []
    ok = vt[~vt["input_error"]]
    for f in fams:
        if not np.isfinite(ok[f"{f} margin"].to_numpy(dtype=float)).any():
            continue  # warnings only (no error-severity margin): nothing to plot
        n = len(params)
        cols = min(n, 3)
        rows = (n + cols - 1) // cols
        fig, axes = figure(170, 55 * rows, nrows=rows, ncols=cols, squeeze=False)
        for k, q in enumerate(params):
            ax = axes[k // cols][k % cols]
            x = ok[q.name].to_numpy(dtype=float)
            y = ok[f"{f} margin"].to_numpy(dtype=float) * 100
            st = ok[f"{f} status"].tolist()
            own = _item_margins(df, items_of.get(q.name, ()), f) if df is not None and \
                items_of.get(q.name) else {}
            if own:
                ys = np.array([own.get(int(v), np.nan) for v in ok["variant"]]) * 100
                gy = np.isfinite(x) & np.isfinite(ys)
                ax.scatter(x[gy], ys[gy], s=22, facecolors="none", edgecolors="#2c3e50",
                           label=_label("its own items"), zorder=4)
            good = np.isfinite(x) & np.isfinite(y)
            order = np.argsort(x[good], kind="stable")
            if run.study.design == "one-at-a-time":
                sel = ok["variant_name"].str.startswith(q.name + " =").to_numpy()
                xs, ys = x[sel & good], y[sel & good]
                o = np.argsort(xs, kind="stable")
                ax.plot(xs[o], ys[o], color="#2c3e50", linewidth=1.0)
            for s in STATUS_ORDER:
                m = good & np.array([t == s for t in st])
                if m.any():
                    ax.scatter(x[m], y[m], s=12, color=_COLOURS.get(s, "#000"),
                               label=s.replace("_", " "), zorder=3)
            del order
            ax.axhline(0.0, color="#c0392b", linestyle="--", linewidth=1.0)
            ax.set_xlabel(_label(f"{q.name} [{q.unit or '-'}]"))
            if k % cols == 0:
                ax.set_ylabel(_label(f"{f}: smallest margin [%]"))
        for k in range(n, rows * cols):
            axes[k // cols][k % cols].set_visible(False)
        fig.tight_layout()
        legend_below(fig, axes=[axes[0][0]])  # below the axes: never cut off, never on data
        figs.append({"family": f, "src": _img(to_svg(fig)),
                     "caption": f"{f} rules: smallest margin of each variant (error-severity"
                     " results) against each parameter; below 0 % a rule fails. Colour: the"
                     " family's worst status in that variant. Open circles: the smallest"
                     " margin of the items the parameter changes (e.g. the bearings whose"
                     " clearance varies)."})
    return figs


def _map_figure(vt, run: StudyRun, fams: list[str]) -> dict[str, Any] | None:
    from ..report.plots import figure, legend_below, to_svg

    params = [q for q in run.study.parameters if q.numeric]
    if len(params) != 2:
        return None
    a, b = params
    ok = vt[~vt["input_error"]]
    fig, ax = figure(120, 90)
    x = ok[a.name].to_numpy(dtype=float)
    y = ok[b.name].to_numpy(dtype=float)
    feas = ok["feasible"].to_numpy(dtype=bool)
    ax.scatter(x[feas], y[feas], s=40, marker="s", color=_COLOURS["pass"], label="feasible")
    ax.scatter(x[~feas], y[~feas], s=40, marker="s", color=_COLOURS["fail"],
               label="not feasible")
    bad = vt[vt["input_error"]]
    if not bad.empty:
        ax.scatter(bad[a.name].to_numpy(dtype=float), bad[b.name].to_numpy(dtype=float),
                   s=40, marker="x", color=_COLOURS["input error"], label="input error")
    ax.set_xlabel(_label(f"{a.name} [{a.unit or '-'}]"))
    ax.set_ylabel(_label(f"{b.name} [{b.unit or '-'}]"))
    legend_below(fig)
    return {"src": _img(to_svg(fig)),
            "caption": "Feasibility map: a variant is feasible when no error-severity rule of"
            " the selected families fails (" + ", ".join(fams) + ")."}


def context(run: StudyRun, df) -> dict[str, Any]:
    vt, fams = variant_table(df, run)
    pnames = [q.name for q in run.study.parameters]
    rows = []
    for _, r in vt.iterrows():
        cells = []
        for f in fams:
            st = r[f"{f} status"]
            m = r[f"{f} margin"]
            cells.append({"status": st, "css": st.replace(" ", "-").replace("_", "-"),
                          "margin": "-" if m is None or not np.isfinite(m) else
                          f"{m * 100:+.1f} %"})
        rows.append({"variant": int(r["variant"]), "name": r["variant_name"],
                     "values": [_fmt(r[p]) for p in pnames], "cells": cells,
                     "feasible": bool(r["feasible"]), "input_error": bool(r["input_error"])})
    errors = [{"variant": rec["index"], "name": rec["name"], "errors": rec["errors"]}
              for rec in run.records if rec["status"] == "input error"]
    sens = sensitivity(vt, run, fams)
    for s in sens:
        for e in s["ranking"]:
            e["text"] = "-" if e["measure"] is None or not np.isfinite(e["measure"]) else (
                f"{e['measure']:+.3f}" if s["r2"] is not None else f"{e['measure'] * 100:.1f} %")
    params = [{"name": q.name, "cells": ", ".join(t.labels[:6]) + (
        f" (+{len(t.labels) - 6} more)" if len(t.labels) > 6 else ""),
        "unit": q.unit or "-", "levels": _levels(q, run)}
        for q, t in zip(run.study.parameters, run.targets)]
    return {
        "title": f"Parametric study: {run.study.name}",
        "study": run.study, "date": _dt.date.today().isoformat(), "version": __version__,
        "base_file": run.base_path.replace("\\", "/").split("/")[-1],
        "sha256": run.base_sha256, "n_variants": len(run.records),
        "n_errors": len(errors), "errors": errors, "params": params, "pnames": pnames,
        "fams": fams, "rows": rows, "n_feasible": int(vt["feasible"].sum()),
        "sensitivity": sens, "best": best_variant(vt),
        "figures": _margin_figures(vt, run, fams, df), "map": _map_figure(vt, run, fams),
        "select": ", ".join(run.study.select or ["all rules"]),
        "css": (templates_dir() / "report.css").read_text(encoding="utf-8"),
    }


def _levels(q, run: StudyRun) -> str:
    """The levels of a parameter as the design gives them (a table design: the values its
    variants name, "workbook" where a variant keeps the workbook's value)."""
    if run.study.design == "table":
        given = [dict(vals).get(q.name) for _, vals in run.study.table]
        seen = list(dict.fromkeys("workbook" if v is None else _fmt(v) for v in given))
        return ", ".join(seen) or "workbook"
    if q.values:
        return ", ".join(_fmt(v) for v in q.values)
    if q.low is None or q.high is None:
        return "-"
    return f"{q.low:g}..{q.high:g}" + ("" if run.study.design == "latin-hypercube"
                                        else f" in {q.steps} steps")


def _fmt(v: Any) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def render(run: StudyRun, df) -> tuple[str, bytes]:
    """(HTML, PDF bytes) of the study report."""
    from jinja2 import Environment, FileSystemLoader, StrictUndefined, select_autoescape
    from weasyprint import HTML

    env = Environment(loader=FileSystemLoader(str(templates_dir())),
                      autoescape=select_autoescape(["html"]), undefined=StrictUndefined)
    import hashlib

    html = env.get_template("study.html").render(**context(run, df))
    ident = hashlib.sha256(html.encode("utf-8")).hexdigest()[:32].encode()
    pdf = HTML(string=html, base_url=str(templates_dir())).write_pdf(pdf_identifier=ident)
    return html, pdf
