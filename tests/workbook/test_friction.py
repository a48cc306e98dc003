"""Messages for mistakes users make (issue 21, friction): a unit in the wrong letter case, a
date where a number belongs, FAT-003's inputs named with cell and unit and present (blank) in
every template."""

from __future__ import annotations

import datetime as dt

import openpyxl
import pytest

from checker import api
from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content
from checker.workbook.example_v8 import v8_content
from checker.workbook.units import UnitProblem, to_si
from tests.helpers import column, edited, param_row, table_row


@pytest.mark.parametrize("unit, kind, hint", [("MM", "length", "mm"), ("Mpa", "stress", "MPa"),
                                              ("KN", "force", "kN"), ("KG", "mass", "kg")])
def test_unit_in_the_wrong_case_gets_did_you_mean(unit, kind, hint):
    with pytest.raises(UnitProblem, match=f"did you mean '{hint}'"):
        to_si(1.0, unit, kind)


def test_megamolar_clearance_names_the_cell_and_the_fix(tmp_path):
    def edit(wb):
        ws = wb["Bearings"]
        ws.cell(2, column(ws, "radial clearance")).value = "MM"
    with pytest.raises(InputErrors) as info:
        load_engine(edited(tmp_path, edit))
    msgs = [str(e) for e in info.value.errors]
    assert msgs and all("did you mean 'mm'" in m for m in msgs)
    assert "molar concentration" in msgs[0] and msgs[0].startswith("Bearings!F")


def test_a_date_in_a_number_cell_is_shown_as_a_date(tmp_path):
    def edit(wb):
        ws = wb["Engine"]
        ws.cell(param_row(ws, "Bore"), 2).value = dt.datetime(2024, 5, 1)
        ws = wb["Bearings"]
        ws.cell(table_row(ws, "name", "M2"), column(ws, "radial clearance")).value = \
            dt.datetime(2024, 1, 22, 0, 0)
    with pytest.raises(InputErrors) as info:
        load_engine(edited(tmp_path, edit))
    text = str(info.value)
    assert "datetime" not in text
    assert "found the date 2024-05-01" in text and "found the date 2024-01-22" in text
    assert "expected a length with a unit (e.g. mm)" in text


@pytest.mark.parametrize("content", [example_content, lambda: i6_content(damper_ring=True),
                                     v8_content], ids=["i4", "i6", "v8"])
def test_fat003_inputs_are_in_every_template_and_named_with_cell_and_unit(tmp_path, content):
    p = tmp_path / "e.xlsx"
    write_workbook(p, content())
    ws = openpyxl.load_workbook(p)["Fatigue"]
    rows = {label: param_row(ws, label) for label in (
        "Crank nose diameter", "Crank nose stress concentration bending",
        "Crank nose stress concentration torsion", "Crank nose fatigue strength")}
    assert all(ws.cell(r, 2).value is None for r in rows.values())  # blank: user types it
    res = api.check(p, select=["FAT-003"])
    (r,) = res.results
    assert r.status == "not_evaluated"
    assert r.missing == [
        f"Fatigue!B{rows['Crank nose diameter']}: Crank nose diameter (length, e.g. mm)",
        f"Fatigue!B{rows['Crank nose stress concentration bending']}: Crank nose stress"
        " concentration bending (a number, no unit)",
        f"Fatigue!B{rows['Crank nose stress concentration torsion']}: Crank nose stress"
        " concentration torsion (a number, no unit)",
        f"Fatigue!B{rows['Crank nose fatigue strength']}: Crank nose fatigue strength"
        " (stress, e.g. MPa)"]
