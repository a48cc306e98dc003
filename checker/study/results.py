"""The study's results: a tidy table, feasibility per rule family, sensitivity, best variant.

The tidy table has one row per variant, rule and item (variant, its parameter values, rule,
item, case, value, unit, limit, margin, status; the variant numbered from 1, as the terminal,
the PDF and the default names number it); a variant whose input is invalid has one
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

STATUS_ORDER = ("fail", "input error", "not_evaluated", "warning", "pass", "not_applicable")


def family(rule: str) -> str:
    return rule.split("-")[0]


_TAIL = ["rule", "name", "item", "case", "value", "unit", "limit", "margin", "status",
         "severity", "message"]
_FLOAT = {"value", "margin"}


def _columns(run: StudyRun) -> list[str]:
    return ["variant", "variant_name", "variant_id",
            *[q.name for q in run.study.parameters], *_TAIL]


def _rows(rec: dict, pnames: list[str]) -> list[dict[str, Any]]:
    """The tidy rows of one variant's record."""
    vals = dict((k, v) for k, v in rec["values"])
    base = {"variant": rec["index"] + 1, "variant_name": rec["name"], "variant_id": rec["id"]}
    for p in pnames:
        v = vals.get(p)
        base[p] = np.nan if v is None else v
    if rec["status"] == "input error":
        return [{**base, "rule": "", "name": "", "item": "", "case": "",
                 "value": np.nan, "unit": "", "limit": "", "margin": np.nan,
                 "status": "input error", "severity": "error",
                 "message": "; ".join(rec["errors"])}]
    rows = []
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
    return rows


def _frame(rows: list[dict], run: StudyRun):
    import pandas as pd

    df = pd.DataFrame(rows, columns=_columns(run))
    for q in run.study.parameters:  # baseline values (None) shown as NaN; numbers stay float
        if q.numeric:
            df[q.name] = df[q.name].astype(float)
    for c in _FLOAT:
        df[c] = df[c].astype(float)
    for c in _TAIL:  # text columns hold text (or None): one type for every parquet piece
        if c not in _FLOAT:
            df[c] = df[c].map(lambda x: x if x is None or isinstance(x, str) else str(x))
    df["variant"] = df["variant"].astype("int64")
    return df


def tidy_chunks(run: StudyRun, variants_per_chunk: int = 100):
    """The tidy table in pieces of ``variants_per_chunk`` variants (records are read from
    disk one at a time; memory does not grow with the size of the study)."""
    pnames = [q.name for q in run.study.parameters]
    rows: list[dict] = []
    n = 0
    for rec in run.records:
        rows.extend(_rows(rec, pnames))
        n += 1
        if n % variants_per_chunk == 0:
            yield _frame(rows, run)
            rows = []
    if rows or n == 0:
        yield _frame(rows, run)


def tidy(run: StudyRun):
    """The results as a pandas DataFrame (deterministic order and types)."""
    import pandas as pd

    parts = list(tidy_chunks(run))
    return parts[0] if len(parts) == 1 else pd.concat(parts, ignore_index=True)


def baseline_values(run: StudyRun) -> dict[str, float | None]:
    """The workbook's own value of each parameter (first cell), in the study's unit."""
    from ..workbook.units import to_si

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
            row[f"{f} status"] in ("pass", "warning", "-", "not_applicable") for f in fams)
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


#: Rows an Excel sheet holds (with the header row).
EXCEL_ROWS = 1_048_576


def _schema(run: StudyRun):
    import pyarrow as pa

    fields = [pa.field("variant", pa.int64()), pa.field("variant_name", pa.string()),
              pa.field("variant_id", pa.string())]
    fields += [pa.field(q.name, pa.float64() if q.numeric else pa.string())
               for q in run.study.parameters]
    fields += [pa.field(c, pa.float64() if c in _FLOAT else pa.string()) for c in _TAIL]
    return pa.schema(fields)


def _tmp(out, name: str) -> str:
    import os
    import tempfile

    from ..outputs.files import file_mode

    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=out)
    os.fchmod(fd, file_mode())
    os.close(fd)
    return tmp


def _write_xlsx(parquet_path, names: list[str], tmp: str) -> None:
    """results.xlsx (to ``tmp``) from results.parquet, in pieces (openpyxl write-only rows)."""
    import pyarrow.parquet as pq
    from openpyxl import Workbook

    pf = pq.ParquetFile(parquet_path)
    wb = Workbook(write_only=True)
    ws = wb.create_sheet("results")
    ws.append(names)
    for batch in pf.iter_batches(batch_size=20_000):
        cols = [batch.column(i).to_pylist() for i in range(batch.num_columns)]
        for row in zip(*cols):
            ws.append([None if isinstance(v, float) and v != v else v for v in row])
    wb.save(tmp)


def _xlsx_child(parquet_path, names: list[str], tmp: str, conn) -> None:
    """Body of the process that writes results.xlsx beside other work: "" or the error."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent ends it on an interruption
    try:
        _write_xlsx(parquet_path, names, tmp)
        conn.send("")
    except BaseException as exc:  # noqa: BLE001 - reported by the parent
        conn.send(f"{type(exc).__name__}: {exc}")
    finally:
        conn.close()


def _xlsx_alongside(parquet_path, names: list[str], tmp: str,
                    alongside) -> Exception | None:
    """Write results.xlsx in a forked process while ``alongside()`` runs here (the study PDF):
    the two take about the same time, and a study's workers are idle by now. Without fork
    (not Linux) one after the other. An error of ``alongside`` is returned once results.xlsx
    is written (the tables are kept, as when they were written first); an interruption
    ends the other process at once."""
    import multiprocessing as mp
    import sys

    if not sys.platform.startswith("linux"):
        _write_xlsx(parquet_path, names, tmp)
        try:
            alongside()
        except Exception as exc:  # noqa: BLE001 - raised by the caller after the tables
            return exc
        return None
    ctx = mp.get_context("fork")
    here, there = ctx.Pipe(duplex=False)
    child = ctx.Process(target=_xlsx_child, args=(parquet_path, names, tmp, there),
                        daemon=True)
    child.start()
    there.close()
    failed: Exception | None = None
    try:
        try:
            alongside()
        except Exception as exc:  # noqa: BLE001 - raised by the caller after the tables
            failed = exc
        error = here.recv() if here.poll(None) else "no answer"
        child.join()
    except BaseException:
        if child.is_alive():
            child.terminate()
        child.join(timeout=3)
        if child.is_alive():
            child.kill()
            child.join()
        raise
    finally:
        here.close()
    if error:
        raise RuntimeError(f"results.xlsx could not be written ({error})")
    return failed


def write_tables(run: StudyRun, out_dir, say=None, alongside=None) -> list[str]:
    """results.parquet and results.xlsx (atomic, unique temporary names); returns the paths
    written. Both are written in pieces (parquet row groups, openpyxl write-only rows), so
    a large study's table is never all in memory. A table longer than an Excel sheet is
    kept in results.parquet only (``say`` tells why).

    ``alongside``: work to do once results.parquet is written (the study PDF, which reads
    it), done while another process writes results.xlsx; it runs exactly once, also when no
    results.xlsx is written."""
    import os
    from pathlib import Path

    import pyarrow as pa
    import pyarrow.parquet as pq

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    schema = _schema(run)
    tmp = _tmp(out, "results.parquet")
    try:
        with pq.ParquetWriter(tmp, schema) as w:
            for df in tidy_chunks(run):
                w.write_table(pa.Table.from_pandas(df, schema=schema, preserve_index=False))
        os.replace(tmp, out / "results.parquet")
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    written.append(str(out / "results.parquet"))
    pf = pq.ParquetFile(out / "results.parquet")
    if pf.metadata.num_rows + 1 > EXCEL_ROWS:
        old = out / "results.xlsx"
        if old.exists():
            old.unlink()  # never leave a table of an earlier run beside the new one
        if say:
            say(f"results.xlsx not written: {pf.metadata.num_rows:,} rows exceed an Excel"
                f" sheet ({EXCEL_ROWS:,}); results.parquet holds them all")
        if alongside is not None:
            alongside()
        return written
    tmp = _tmp(out, "results.xlsx")
    failed = None
    try:
        if alongside is None:
            _write_xlsx(out / "results.parquet", schema.names, tmp)
        else:
            failed = _xlsx_alongside(out / "results.parquet", schema.names, tmp, alongside)
        os.replace(tmp, out / "results.xlsx")
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    written.append(str(out / "results.xlsx"))
    if failed is not None:
        raise failed
    return written


def report_frame(out_dir, run: StudyRun):
    """The tidy table for the study report, read back from results.parquet (the same
    table :func:`tidy` builds)."""
    from pathlib import Path

    import pandas as pd

    df = pd.read_parquet(Path(out_dir) / "results.parquet")
    for c in df.columns:  # None (not NaN) in text columns, as tidy() gives
        if df[c].dtype == object:
            df[c] = df[c].where(df[c].notna(), None)
    return df
