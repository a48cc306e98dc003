"""The study's results: a tidy table, feasibility per rule family, sensitivity, best variant.

The tidy table has one row per variant, rule and item (variant, its parameter values, rule,
item, case, value, unit, limit, margin, status); a variant whose input is invalid has one
row with status ``input error`` and the message.

Sensitivity: for each rule family the response of a variant is its smallest margin over the
family's evaluated results. On a Latin-hypercube or factorial sample the parameters are
ranked by standardized regression coefficients (SRC: least squares on the standardized
parameters and response; Saltelli et al., Global Sensitivity Analysis: The Primer, 2008,
sec. 1.2.5), reported with the model's R^2 (SRCs rank reliably when R^2 is near 1). A
one-at-a-time study ranks by the spread of the response over each parameter's levels.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .run import StudyRun

STATUS_ORDER = ("fail", "input error", "not_evaluated", "warning", "pass")


def family(rule: str) -> str:
    return rule.split("-")[0]


def tidy(run: StudyRun):
    """The results as a pandas DataFrame (deterministic order and types)."""
    import pandas as pd

    pnames = [q.name for q in run.study.parameters]
    rows: list[dict[str, Any]] = []
    for rec in run.records:
        vals = dict((k, v) for k, v in rec["values"])
        base = {"variant": rec["index"], "variant_name": rec["name"], "variant_id": rec["id"]}
        for p in pnames:
            v = vals.get(p)
            base[p] = np.nan if v is None else v
        if rec["status"] == "input error":
            rows.append({**base, "rule": "", "name": "", "item": "", "case": "",
                         "value": np.nan, "unit": "", "limit": "", "margin": np.nan,
                         "status": "input error", "severity": "error",
                         "message": "; ".join(rec["errors"])})
            continue
        for r in rec["results"]:
            st = r["status"]
            if st == "fail" and r["severity"] == "warning" and not r.get("internal_error"):
                st = "warning"
            rows.append({**base, "rule": r["rule"], "name": r["name"], "item": r["item"],
                         "case": r["case"],
                         "value": np.nan if r["value"] is None else r["value"],
                         "unit": r["unit"], "limit": r["limit_text"],
                         "margin": np.nan if r["margin"] is None else r["margin"],
                         "status": st, "severity": r["severity"], "message": r["message"]})
    cols = ["variant", "variant_name", "variant_id", *pnames, "rule", "name", "item", "case",
            "value", "unit", "limit", "margin", "status", "severity", "message"]
    df = pd.DataFrame(rows, columns=cols)
    for p in pnames:  # baseline values (None) shown as NaN; numeric columns stay numeric
        if all(isinstance(x, (int, float)) for x in df[p].dropna()):
            df[p] = df[p].astype(float)
    return df


def baseline_values(run: StudyRun) -> dict[str, float | None]:
    """The workbook's own value of each parameter (first cell), in the study's unit."""
    from ..units import to_si

    out: dict[str, float | None] = {}
    for t in run.targets:
        q = t.param
        if not q.numeric:
            out[q.name] = None
            continue
        r, c, unit = t.cells[0]
        v = run.extra.get("base_cells", {}).get((q.sheet, r, c))
        if v is None:
            out[q.name] = None
            continue
        si = to_si(float(v), unit, q.field.kind)
        b = to_si(0.0, q.unit or None, q.field.kind)
        a = to_si(1.0, q.unit or None, q.field.kind) - b
        out[q.name] = (si - b) / a
    return out


def variant_table(df, run: StudyRun):
    """One row per variant: parameter values, min margin and status per rule family."""
    import pandas as pd

    # families with at least one evaluated result (a family whose rules all lack inputs,
    # e.g. balancing without project limits, has nothing to show)
    ev = df[df["status"].isin(["pass", "fail", "warning"])]
    fams = sorted({family(r) for r in ev["rule"] if r})
    pnames = [q.name for q in run.study.parameters]
    base = baseline_values(run)
    out = []
    for idx, g in df.groupby("variant", sort=True):
        row: dict[str, Any] = {"variant": idx, "variant_name": g["variant_name"].iloc[0]}
        for p in pnames:
            v = g[p].iloc[0]
            row[p] = base.get(p) if (v is None or (isinstance(v, float) and np.isnan(v))) \
                else v
        err = (g["status"] == "input error").any()
        row["input_error"] = bool(err)
        worst = np.inf
        for f in fams:
            gf = g[g["rule"].map(family) == f]
            if err or gf.empty:
                row[f"{f} status"] = "input error" if err else "-"
                row[f"{f} margin"] = np.nan
                continue
            st = set(gf["status"])
            row[f"{f} status"] = next(s for s in STATUS_ORDER if s in st)
            m = gf.loc[gf["severity"] == "error", "margin"].dropna()
            mm = float(m.min()) if len(m) else np.nan
            row[f"{f} margin"] = mm
            if np.isfinite(mm):
                worst = min(worst, mm)
        row["smallest margin"] = worst if np.isfinite(worst) else np.nan
        row["feasible"] = (not err) and all(
            row[f"{f} status"] in ("pass", "warning", "-") for f in fams)
        out.append(row)
    return pd.DataFrame(out), fams


def sensitivity(vt, run: StudyRun, fams: list[str]) -> list[dict[str, Any]]:
    """Per family: parameters ranked by |SRC| (sampled designs) or by the spread of the
    response over a parameter's levels (one-at-a-time)."""
    pnames = [q.name for q in run.study.parameters if q.numeric]
    ok = vt[~vt["input_error"]]
    out = []
    for f in fams:
        y = ok[f"{f} margin"].to_numpy(dtype=float)
        if run.study.design == "one-at-a-time":
            ranks = []
            for p in pnames:
                lev = ok[~ok["variant_name"].str.startswith("baseline")]
                sel = lev[lev["variant_name"].str.startswith(p + " =")]
                yy = sel[f"{f} margin"].to_numpy(dtype=float)
                yy = yy[np.isfinite(yy)]
                ranks.append((p, float(yy.max() - yy.min()) if yy.size else np.nan))
            ranks.sort(key=lambda t: -np.nan_to_num(t[1], nan=-1))
            out.append({"family": f, "method": "spread of the smallest margin over the"
                        " levels (one at a time)", "r2": None,
                        "ranking": [{"parameter": p, "measure": v} for p, v in ranks]})
            continue
        X = ok[pnames].to_numpy(dtype=float)
        good = np.isfinite(y) & np.isfinite(X).all(axis=1)
        if good.sum() < len(pnames) + 2:
            out.append({"family": f, "method": "standardized regression coefficients",
                        "r2": None, "ranking": [], "note": "too few evaluated variants"})
            continue
        X, yv = X[good], y[good]
        sx, sy = X.std(axis=0), yv.std()
        keep = sx > 0
        if sy == 0 or not keep.any():
            out.append({"family": f, "method": "standardized regression coefficients",
                        "r2": None, "ranking": [{"parameter": p, "measure": 0.0}
                                                for p in pnames],
                        "note": "the response does not vary"})
            continue
        Z = (X[:, keep] - X[:, keep].mean(axis=0)) / sx[keep]
        zy = (yv - yv.mean()) / sy
        beta, *_ = np.linalg.lstsq(Z, zy, rcond=None)
        r2 = float(1 - np.sum((zy - Z @ beta) ** 2) / np.sum(zy ** 2))
        names = [p for p, k in zip(pnames, keep) if k]
        ranks = sorted(zip(names, beta.tolist()), key=lambda t: -abs(t[1]))
        out.append({"family": f, "method": "standardized regression coefficients (SRC)",
                    "r2": r2, "ranking": [{"parameter": p, "measure": float(b)}
                                          for p, b in ranks]})
    return out


def best_variant(vt) -> dict[str, Any] | None:
    """The variant with the largest smallest margin among the feasible ones (else among all
    evaluated ones), with why."""
    ok = vt[~vt["input_error"] & vt["smallest margin"].notna()]
    if ok.empty:
        return None
    feas = ok[ok["feasible"]]
    pool = feas if not feas.empty else ok
    row = pool.loc[pool["smallest margin"].idxmax()]
    return {"variant": int(row["variant"]), "name": row["variant_name"],
            "smallest_margin": float(row["smallest margin"]), "feasible": bool(row["feasible"]),
            "of": "feasible variants" if not feas.empty else "all variants (none feasible)"}


def write_tables(df, out_dir) -> list[str]:
    """results.parquet and results.xlsx (atomic); returns the paths written."""
    import os
    from pathlib import Path

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    tmp = out / ".results.parquet.tmp"
    df.to_parquet(tmp, index=False)
    os.replace(tmp, out / "results.parquet")
    written.append(str(out / "results.parquet"))
    tmp = out / ".results.xlsx.tmp"
    with __import__("pandas").ExcelWriter(tmp, engine="openpyxl") as xw:
        df.to_excel(xw, sheet_name="results", index=False)
    os.replace(tmp, out / "results.xlsx")
    written.append(str(out / "results.xlsx"))
    return written
