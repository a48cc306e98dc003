"""A missing main-bearing or big-end row is an input error (exit code 2) naming the sheet and
what is expected, like a missing cylinder row, never 14 "not evaluated" results (issue 21,
item 12)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.description.engine import load_engine
from checker.errors import InputErrors
from tests.helpers import edited, table_row


def _delete(name: str):
    def edit(wb):
        ws = wb["Bearings"]
        ws.delete_rows(table_row(ws, "name", name))
    return edit


def test_missing_main_bearing_is_an_input_error(tmp_path):
    p = edited(tmp_path, _delete("M3"))
    with pytest.raises(InputErrors) as info:
        load_engine(p)
    (e,) = info.value.errors
    assert e.where == "Bearings"
    assert "4 main bearings given (M1, M2, M4, M5)" in e.message
    assert "a crank with 4 throws needs 5" in e.message and "M1..M5" in e.message
    r = CliRunner().invoke(main, ["check", str(p)])
    assert r.exit_code == 2
    assert "Bearings: 4 main bearings given" in r.stderr and "Traceback" not in r.output


def test_missing_big_end_is_an_input_error(tmp_path):
    p = edited(tmp_path, _delete("BE2"))
    with pytest.raises(InputErrors) as info:
        load_engine(p)
    (e,) = info.value.errors
    assert e.where == "Bearings"
    assert "3 big-end bearings given (BE1, BE3, BE4)" in e.message
    assert "4 cylinders need 4" in e.message


def test_same_treatment_as_a_missing_cylinder_row(tmp_path):
    def no_cyl(wb):
        ws = wb["Cylinders"]
        ws.delete_rows(ws.max_row)
    for p in (edited(tmp_path, no_cyl, "c.xlsx"), edited(tmp_path, _delete("M5"), "m.xlsx")):
        r = CliRunner().invoke(main, ["check", str(p)])
        assert r.exit_code == 2, r.output


def test_no_bearing_rows_at_all_is_not_evaluated_not_an_error(tmp_path):
    """An empty Bearings table is an unfinished workbook: its rules are not evaluated."""
    def empty(wb):
        ws = wb["Bearings"]
        ws.delete_rows(3, ws.max_row)
    e = load_engine(edited(tmp_path, empty))
    assert e.bearings == ()
