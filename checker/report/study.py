"""The study PDF: feasibility per rule family, margin-vs-parameter plots, a 2-D feasibility
map for two-parameter studies, the sensitivity ranking and the best variant. Formatting only:
every number comes from :mod:`checker.study.results`."""

from __future__ import annotations

import base64
import datetime as _dt
from typing import Any

import numpy as np

from .. import __version__
from ..plumbing.resources import templates_dir
from ..results.display import item_label
from ..study.results import STATUS_ORDER, baseline_values, best_variant, sensitivity, variant_table
from ..study.run import StudyRun

_COLOURS = {"pass": "#27ae60", "warning": "#d68910", "fail": "#c0392b",
            "not_evaluated": "#7f8c8d", "input error": "#34495e", "-": "#bdc3c7",
            "not_applicable": "#bdc3c7"}


def _label(text: str) -> str:
    """Workbook/study text as literal plot text (no mathtext)."""
    return str(text).replace("\\", "\\\\").replace("$", r"\$")


def _img(fig) -> str:
    """A figure as a JPEG data URI (raster: the PDF engine copies it instead of drawing)."""
    from .plots import to_image

    return "data:image/jpeg;base64," + base64.b64encode(bytes(to_image(fig))).decode("ascii")


def _item_margins(df, items: tuple[str, ...], fam: str) -> dict[int, float]:
    """Smallest error-severity margin per variant over the results of ``items``."""
    sel = df[(df["rule"].map(lambda r: r.split("-")[0]) == fam) & df["item"].isin(items)
             & (df["severity"] == "error")]
    return {int(k): float(g["margin"].min()) for k, g in sel.groupby("variant")
            if g["margin"].notna().any()}


def _margin_figures(vt, run: StudyRun, fams: list[str], df=None) -> list[dict[str, Any]]:
    from .plots import figure, legend_below

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
        legend_below(fig, axes=[axes[0][0]])  # below the axes: never cut off, never on data
        figs.append({"family": f, "src": _img(fig),
                     "caption": f"{f} rules: smallest margin of each variant (error-severity"
                     " results) against each parameter; below 0 % a rule fails. Colour: the"
                     " family's worst status in that variant. Open circles: the smallest"
                     " margin of the items the parameter changes (e.g. the bearings whose"
                     " clearance varies)."})
    return figs


def _map_figure(vt, run: StudyRun, fams: list[str]) -> dict[str, Any] | None:
    """Feasibility maps of a two-parameter study, one panel per rule family (the family's
    worst status in each variant), so that one failing family does not paint every map red."""
    from .plots import figure, legend_below

    params = [q for q in run.study.parameters if q.numeric]
    if len(params) != 2 or not fams:
        return None
    a, b = params
    ok = vt[~vt["input_error"]]
    n = len(fams)
    cols = min(n, 3)
    rows = -(-n // cols)
    width = 170 if cols > 1 else 100
    fig, axes = figure(width, 52 * rows + 8, nrows=rows, ncols=cols, squeeze=False,
                       legend_rows=1, wgap=16, hgap=16)
    x = ok[a.name].to_numpy(dtype=float)
    y = ok[b.name].to_numpy(dtype=float)
    bad = vt[vt["input_error"]]
    for k, f in enumerate(fams):
        ax = axes[k // cols][k % cols]
        st = ok[f"{f} status"].tolist()
        for status in STATUS_ORDER:
            m = np.array([t == status for t in st])
            if m.any():
                ax.scatter(x[m], y[m], s=36, marker="s", color=_COLOURS.get(status, "#000"),
                           label=status.replace("_", " "))
        if not bad.empty:
            ax.scatter(bad[a.name].to_numpy(dtype=float), bad[b.name].to_numpy(dtype=float),
                       s=36, marker="x", color=_COLOURS["input error"], label="input error")
        ax.set_title(_label(f"{f} rules"))
        ax.set_xlabel(_label(f"{a.name} [{a.unit or '-'}]"))
        if k % cols == 0:
            ax.set_ylabel(_label(f"{b.name} [{b.unit or '-'}]"))
    for k in range(n, rows * cols):
        axes[k // cols][k % cols].set_visible(False)
    legend_below(fig)
    return {"src": _img(fig), "width_mm": width,
            "caption": "Feasibility map per rule family: each square is a variant, coloured by"
            " the family's worst status in it (error-severity failures make a variant"
            " infeasible; warnings do not)."}


def _baseline(run: StudyRun) -> dict[str, float | None]:
    """The base workbook's own value of each parameter (its first cell, in the study's
    unit), read from the base workbook."""
    if "base_cells" not in run.extra:
        cells: dict[tuple, Any] = {}
        try:
            from openpyxl import load_workbook

            wb = load_workbook(run.base_path, read_only=True, data_only=True)
            for t in run.targets:
                if t.cells and t.param.sheet in wb.sheetnames:
                    r, c, _ = t.cells[0]
                    v = wb[t.param.sheet].cell(r, c).value
                    if isinstance(v, (int, float)) and not isinstance(v, bool):
                        cells[(t.param.sheet, r, c)] = v
            wb.close()
        except (OSError, KeyError, ValueError):
            cells = {}
        run.extra["base_cells"] = cells
    try:
        return baseline_values(run)
    except (KeyError, ValueError, TypeError):
        return {q.name: None for q in run.study.parameters}


def _governing(df) -> dict[int, dict[str, Any]]:
    """Per variant: the error-severity result with the smallest margin (rule, item, case,
    margin), the one that decides whether the variant passes."""
    out: dict[int, dict[str, Any]] = {}
    sel = df[(df["severity"] == "error") & df["margin"].notna()]
    for v, g in sel.groupby("variant", sort=True):
        r = g.loc[g["margin"].idxmin()]
        out[int(v)] = {"rule": r["rule"], "item": r["item"], "case": r["case"],
                       "margin": float(r["margin"])}
    return out


def _range_words(levels: list[float], ok: list[bool], name: str, unit: str) -> str:
    """Where along sorted ``levels`` the items pass, in words."""
    u = f" {unit}" if unit and unit != "-" else ""
    if all(ok):
        return f"at every {name}"
    if not any(ok):
        return f"at no {name}"
    idx = [k for k, v in enumerate(ok) if v]
    if idx == list(range(idx[0], idx[-1] + 1)):
        if idx[0] == 0:
            return f"at {name} ≤ {levels[idx[-1]]:g}{u}"
        if idx[-1] == len(levels) - 1:
            return f"at {name} ≥ {levels[idx[0]]:g}{u}"
        return f"at {name} {levels[idx[0]]:g}..{levels[idx[-1]]:g}{u}"
    return f"at {name} = " + ", ".join(f"{levels[k]:g}" for k in idx) + u


def _answer(vt, df, run: StudyRun, fams: list[str], gov: dict[int, dict]) -> list[str]:
    """The study's answer in words: what governs, and where each family (and the items each
    parameter changes) passes."""
    from collections import Counter

    out: list[str] = []
    ok = vt[~vt["input_error"]]
    if ok.empty:
        return ["No variant could be evaluated."]
    cnt = Counter((g["rule"], g["item"]) for g in gov.values())
    if cnt:
        (rule, item), k = cnt.most_common(1)[0]
        every = "every" if k == len(gov) else f"{k} of {len(gov)}"
        out.append(f"{item_label(item)} ({rule}) governs {every}"
                   f" variant{'s' if k != 1 else ''}: its"
                   " margin is the smallest of all error-severity results.")
    params = [q for q in run.study.parameters if q.numeric]
    items_of = {t.param.name: t.items for t in run.targets}
    fact2 = run.study.design == "full-factorial" and len(params) == 2
    for f in fams:
        n_pass = int(ok[f"{f} status"].isin(["pass", "warning"]).sum())
        line = f"{f} rules: {n_pass} of {len(ok)} variants pass."
        if fact2:
            for a, b in (params, params[::-1]):
                own = items_of.get(a.name)
                if not own:
                    continue
                m = _item_margins(df, own, f)
                if not m:
                    continue
                parts = []
                for lb in sorted(ok[b.name].dropna().unique()):
                    sub = ok[ok[b.name] == lb].sort_values(a.name)
                    lev = sub[a.name].to_numpy(dtype=float).tolist()
                    passed = [m.get(int(v), -1.0) >= 0 for v in sub["variant"]]
                    parts.append(_range_words(lev, passed, a.name, a.unit or "")
                                 + f" at {lb:g} {b.unit or ''}".rstrip())
                who = ", ".join(own[:5]) + (" ..." if len(own) > 5 else "")
                line += (f" The items {a.name} changes ({who}) pass " + "; ".join(parts)
                         + ".")
        out.append(line)
    return out


def _ties(vt, best: dict | None, tol: float = 5e-4) -> list[int]:
    """Variants (1-based) whose smallest margin equals the best one's (within 0.05 points)."""
    if not best:
        return []
    pool = vt[~vt["input_error"] & vt["smallest margin"].notna()]
    if best.get("feasible"):
        pool = pool[pool["feasible"]]
    m = best["smallest_margin"]
    return [int(v) for v, x in zip(pool["variant"], pool["smallest margin"])
            if abs(float(x) - m) <= tol]


def _own_sensitivity(vt, df, run: StudyRun, fams: list[str]) -> dict[tuple[str, str], str]:
    """Per (family, parameter): the change of the smallest margin of the items the parameter
    changes across its range (points; least-squares slope with the other parameters as
    further regressors); missing where the parameter has no items of its own."""
    out: dict[tuple[str, str], str] = {}
    ok = vt[~vt["input_error"]]
    pnames = [q.name for q in run.study.parameters if q.numeric]
    for t in run.targets:
        if not t.items or not t.param.numeric:
            continue
        for f in fams:
            m = _item_margins(df, t.items, f)
            if not m:
                continue
            y = np.array([m.get(int(v), np.nan) for v in ok["variant"]]) * 100
            X = ok[pnames].to_numpy(dtype=float)
            good = np.isfinite(y) & np.isfinite(X).all(axis=1)
            if good.sum() < len(pnames) + 1:
                continue
            A = np.column_stack([X[good], np.ones(good.sum())])
            coef, *_ = np.linalg.lstsq(A, y[good], rcond=None)
            j = pnames.index(t.param.name)
            span = float(np.ptp(X[good, j]))
            out[(f, t.param.name)] = f"{coef[j] * span:+.1f} points"
    return out


def context(run: StudyRun, df) -> dict[str, Any]:
    vt, fams = variant_table(df, run)
    pnames = [q.name for q in run.study.parameters]
    base = _baseline(run)
    gov = _governing(df)
    rows = []
    for _, r in vt.iterrows():
        cells = []
        for f in fams:
            st = r[f"{f} status"]
            m = r[f"{f} margin"]
            cells.append({"status": st, "css": st.replace(" ", "-").replace("_", "-"),
                          "margin": "-" if m is None or not np.isfinite(m) else
                          f"{m * 100:+.1f} %"})
        values = []
        for p in pnames:
            v, b0 = r[p], base.get(p)
            change = ""
            if isinstance(v, (int, float)) and isinstance(b0, (int, float)) and np.isfinite(v) \
                    and abs(v - b0) > 1e-9 * max(1.0, abs(b0)):
                change = f" ({v - b0:+.4g})"
            values.append(_fmt(v) + change)
        g = gov.get(int(r["variant"]))
        rows.append({"variant": int(r["variant"]), "name": r["variant_name"],
                     "values": values, "cells": cells,
                     "governing": "-" if g is None else
                     f"{g['rule']} {item_label(g['item'])}, {g['case']}",
                     "feasible": bool(r["feasible"]), "input_error": bool(r["input_error"])})
    errors = [{"variant": rec["index"] + 1, "name": rec["name"], "errors": rec["errors"]}
              for rec in run.records if rec["status"] == "input error"]
    sens = sensitivity(vt, run, fams)
    own = _own_sensitivity(vt, df, run, fams)
    for s in sens:
        for e in s["ranking"]:
            e["text"] = "-" if e["measure"] is None or not np.isfinite(e["measure"]) else (
                f"{e['measure']:+.3f}" if s["r2"] is not None else f"{e['measure'] * 100:.1f} %")
            e["own"] = own.get((s["family"], e["parameter"]), "-")
    params = []
    for q, t in zip(run.study.parameters, run.targets):
        levels = _levels(q, run)
        params.append({"name": q.name, "cells": ", ".join(t.labels[:6]) + (
            f" (+{len(t.labels) - 6} more)" if len(t.labels) > 6 else ""),
            "unit": q.unit or "-", "levels": levels, "baseline": _fmt(base.get(q.name)),
            "items": ", ".join(t.items) if t.items else "-"})
    widths = _feas_widths(pnames, fams, rows)
    best = best_variant(vt)
    if best:
        g = gov.get(best["variant"])
        best = dict(best, variant=best["variant"], ties=_ties(vt, best),
                    governing="" if g is None else
                    f"{g['rule']} at {item_label(g['item'])} ({g['case']})")
    return {
        "title": f"Parametric study: {run.study.name}",
        "study": run.study, "date": _dt.date.today().isoformat(), "version": __version__,
        "base_file": run.base_path.replace("\\", "/").split("/")[-1],
        "sha256": run.base_sha256, "n_variants": len(run.records),
        "n_errors": len(errors), "errors": errors, "params": params, "pnames": pnames,
        "baseline": [_fmt(base.get(p)) for p in pnames], "widths": widths,
        "fams": fams, "rows": rows, "n_feasible": int(vt["feasible"].sum()),
        "sensitivity": sens, "best": best, "answer": _answer(vt, df, run, fams, gov),
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


CHAR_MM = 1.3
"""Width of a character of the feasibility table (6.5 pt DejaVu Sans) [mm], padding aside."""


def _feas_widths(pnames: list[str], fams: list[str], rows: list[dict]) -> list[float]:
    """Column widths [% of the text width] of the feasibility table: each column at least as
    wide as its longest word (header or cell; words never break), the rest shared out."""
    def word(texts) -> int:
        return max((len(w) for t in texts for w in str(t).split()), default=1)

    mins = [3 * CHAR_MM, word(["Variant"] + [r["name"] for r in rows]) * CHAR_MM]
    for k, p in enumerate(pnames):
        mins.append(word([p] + [r["values"][k] for r in rows]) * CHAR_MM)
    for k, f in enumerate(fams):
        mins.append(max(word([f]), max((len(r["cells"][k]["status"].replace("_", " "))
                                        for r in rows), default=4), 7) * CHAR_MM)
    mins.append(word(["governing result"] + [r["governing"] for r in rows]) * CHAR_MM)
    mins = [m + 2.8 for m in mins]  # cell padding
    total = 180.0
    spare = max(total - sum(mins), 0.0)
    weights = [0.2, 1.5] + [1.0] * len(pnames) + [0.6] * len(fams) + [2.0]
    w = [m + spare * x / sum(weights) for m, x in zip(mins, weights)]
    return [round(100 * x / sum(w), 1) for x in w]


def _fmt(v: Any) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def html(run: StudyRun, df) -> str:
    """The study report as HTML (what :func:`render` lays out)."""
    from jinja2 import Environment, FileSystemLoader, StrictUndefined, select_autoescape

    env = Environment(loader=FileSystemLoader(str(templates_dir())),
                      autoescape=select_autoescape(["html"]), undefined=StrictUndefined)
    return env.get_template("study.html").render(**context(run, df))


def render(run: StudyRun, df) -> tuple[str, bytes]:
    """(HTML, PDF bytes) of the study report."""
    import hashlib

    from weasyprint import HTML

    text = html(run, df)
    ident = hashlib.sha256(text.encode("utf-8")).hexdigest()[:32].encode()
    pdf = HTML(string=text, base_url=str(templates_dir())).write_pdf(pdf_identifier=ident)
    return text, pdf
