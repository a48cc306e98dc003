"""Large inputs: the loader's cost stays linear in the number of problems and cells. 50,000 bad
rows used to take minutes (every new error was compared with all earlier ones); a sheet whose
used range reaches row 1,048,576 through an empty formatted cell used to take a minute and
gigabytes (every cell of the used range was materialized)."""

from __future__ import annotations

import time
import tracemalloc

import openpyxl
import pytest
from openpyxl.styles import PatternFill

from checker.description.engine import load_engine
from checker.errors import InputErrors
from tests.helpers import example_path

N_BAD = 50_000


def _copy_write_only(src, dst, extra_rows=None):
    """The workbook ``src`` rewritten with openpyxl write-only mode, plus ``extra_rows[sheet]``."""
    wb = openpyxl.load_workbook(src)
    out = openpyxl.Workbook(write_only=True)
    for ws in wb.worksheets:
        new = out.create_sheet(ws.title)
        for row in ws.iter_rows(values_only=True):
            new.append(list(row))
        for row in (extra_rows or {}).get(ws.title, ()):
            new.append(row)
    out.save(dst)
    return dst


def test_50000_bad_rows_are_all_reported_in_linear_time(tmp_path):
    src = example_path(tmp_path)
    wb = openpyxl.load_workbook(src)
    ws = wb["Bearings"]
    template = [c.value for c in ws[3]]  # M1
    names = [c.value for c in ws[1]]
    d = names.index("journal diameter")
    rows = []
    for i in range(N_BAD):
        r = list(template)
        r[0] = f"X{i}"
        r[d] = "fifty-five"  # text in a number cell: one error per row
        rows.append(r)
    path = _copy_write_only(src, tmp_path / "bad_rows.xlsx", {"Bearings": rows})
    load_engine(example_path(tmp_path, "warm.xlsx"))  # imports outside the measurement
    t0 = time.process_time()  # CPU time of this process: not inflated by other load
    with pytest.raises(InputErrors) as info:
        load_engine(path)
    elapsed = time.process_time() - t0
    errs = info.value.errors
    text_errors = [e for e in errs if "text 'fifty-five'" in e.message]
    assert len(text_errors) == N_BAD  # every problem, each once
    assert len({e.where for e in text_errors}) == N_BAD
    assert any("at most 500 are accepted" in e.message for e in errs)  # Bearings max_rows
    # a quadratic loader needs minutes here (1.25e9 comparisons); linear takes about 15 s of
    # CPU for these 850,000 cells on a slow machine
    assert elapsed < 30.0, elapsed


def _formatted_far_away(tmp_path):
    def style(ws, row, col):
        c = ws.cell(row, col)
        c.fill = PatternFill("solid", fgColor="FFFF00")
        c.number_format = "0.00"

    p = example_path(tmp_path)
    wb = openpyxl.load_workbook(p)
    style(wb["Bearings"], 1_048_576, 1)  # used range A1:Q1048576
    style(wb["Engine"], 1_048_576, 16_384)  # used range A1:XFD1048576
    style(wb["Joints"], 500_000, 3)
    wb.save(p)
    check = openpyxl.load_workbook(p, read_only=True)
    assert check["Bearings"].max_row == 1_048_576
    assert check["Engine"].max_column == 16_384
    check.close()
    return p


def test_used_range_to_the_last_row_loads_with_modest_time_and_memory(tmp_path):
    p = _formatted_far_away(tmp_path)
    load_engine(example_path(tmp_path, "warm.xlsx"))  # imports and caches outside the timing
    t0 = time.process_time()
    e = load_engine(p)
    elapsed = time.process_time() - t0
    assert len(e.bearings) == 9 and e.params["bore"] == pytest.approx(0.086)
    assert e.warnings == ()
    assert elapsed < 5.0, elapsed  # was about a minute (every cell of the used range)
    tracemalloc.start()
    try:
        load_engine(p)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 200e6, f"peak {peak / 1e6:.0f} MB"  # was gigabytes


def test_formula_without_stored_value_in_an_otherwise_empty_row_is_reported(tmp_path):
    """Rows are kept when either pass (values or formulas) holds something."""
    p = example_path(tmp_path)
    wb = openpyxl.load_workbook(p)
    ws = wb["BrakeTorque"]
    r = ws.max_row + 1
    ws.cell(r, 1).value = "=1000+7000"
    ws.cell(r, 2).value = "=2*100"
    wb.save(p)
    with pytest.raises(InputErrors) as info:
        load_engine(p)
    where = sorted(e.where for e in info.value.errors)
    assert where == [f"BrakeTorque!A{r}", f"BrakeTorque!B{r}"]
    assert all("no stored result" in e.message for e in info.value.errors)


N_DENSE = 50_000


def test_dense_brake_torque_table_is_accepted_with_a_warning(tmp_path):
    """A logged dyno curve of 50,000 rows is normal input (issue 21, item 14): accepted (it is
    only interpolated), with a warning that it is unusually dense, and the loads computed from
    it equal those of the sparse curve it samples (linear interpolation of a piecewise-linear
    curve reproduces it)."""
    import numpy as np

    from checker import api

    src = example_path(tmp_path)
    wb = openpyxl.load_workbook(src)
    ws = wb["BrakeTorque"]
    pts = [(ws.cell(r, 1).value, ws.cell(r, 2).value) for r in range(3, ws.max_row + 1)
           if ws.cell(r, 1).value is not None]
    rpm = np.linspace(pts[0][0], pts[-1][0], N_DENSE)
    torque = np.interp(rpm, [p[0] for p in pts], [p[1] for p in pts])
    ws.delete_rows(3, ws.max_row)
    wb.save(src)
    dense = _copy_write_only(src, tmp_path / "dense.xlsx",
                             {"BrakeTorque": [[float(n), float(t)] for n, t in
                                              zip(rpm, torque)]})
    load_engine(example_path(tmp_path, "warm.xlsx"))  # imports outside the measurement
    t0 = time.process_time()
    e = load_engine(dense)
    elapsed = time.process_time() - t0
    assert len(e.brake_torque) == N_DENSE
    assert any("BrakeTorque" in str(w) and "50000 data rows" in str(w) for w in e.warnings)
    assert elapsed < 30.0, elapsed  # linear: a few seconds of CPU for 100,000 cells

    base = api.check(example_path(tmp_path, "base.xlsx"), select=["JNT"])
    res = api.check(dense, select=["JNT"])
    a = {(r.rule, r.item): r.value for r in base.results}
    b = {(r.rule, r.item): r.value for r in res.results}
    assert a.keys() == b.keys()
    for k, v in a.items():
        if v is not None:
            assert b[k] == pytest.approx(v, rel=1e-6), k
