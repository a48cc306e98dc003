"""Sheet Crank at its edges (issue 43, items 8, 10 and 12): a sheet without data rows is one
error at the sheet, a problem of the ``all`` row is reported once, a refused cell is not
reported again as missing, and every typed or derived crank value is listed in the model."""

from __future__ import annotations

import pytest

from checker import api
from checker.description.engine import load_engine
from checker.errors import InputErrors
from tests.helpers import column, edited, stub_section_images


def _errors(path) -> list:
    with pytest.raises(InputErrors) as exc:
        load_engine(path)
    return exc.value.errors


def _crank_cell(wb, col: str, value, row: int = 3) -> str:
    ws = wb["Crank"]
    c = ws.cell(row, column(ws, col))
    c.value = value
    return f"Crank!{c.coordinate}"


def test_a_crank_sheet_with_headers_only_is_one_error_at_the_sheet(tmp_path):
    def edit(wb):
        ws = wb["Crank"]
        ws.delete_rows(3, ws.max_row)

    errs = _errors(edited(tmp_path, edit))
    assert [e.where for e in errs] == ["Crank"]
    msg = errs[0].message
    # what is expected: a row 'all' or one row per throw of the engine's four
    assert "no data row" in msg and "'all'" in msg and "1..4" in msg
    assert "give sheet Crank" not in msg


def test_an_empty_crank_sheet_is_one_error_at_the_sheet(tmp_path):
    def edit(wb):
        ws = wb["Crank"]
        ws.delete_rows(1, ws.max_row)

    errs = _errors(edited(tmp_path, edit))
    assert [(e.where, e.message.split(";")[0]) for e in errs] == [("Crank", "sheet is empty")]


def test_a_problem_of_the_all_row_is_reported_once_for_every_throw(tmp_path):
    where = {}

    def edit(wb):
        where["cell"] = _crank_cell(wb, "web width at journal", 30)

    errs = _errors(edited(tmp_path, edit))
    assert [e.where for e in errs] == [where["cell"]]
    assert errs[0].message.startswith("every throw: the web (30 mm wide at the journal) is"
                                      " narrower than its main journal (55 mm)")


def test_a_throw_row_problem_names_its_throw(tmp_path):
    where = {}

    def edit(wb):
        ws = wb["Crank"]
        ws.cell(4, column(ws, "throw")).value = 3
        where["cell"] = _crank_cell(wb, "web width at journal", 30, row=4)

    errs = _errors(edited(tmp_path, edit))
    assert [(e.where, e.message.split(":")[0]) for e in errs] == [(where["cell"], "throw 3")]


def test_a_refused_counterweight_angle_is_not_reported_again_as_missing(tmp_path):
    where = {}

    def edit(wb):
        where["cell"] = _crank_cell(wb, "counterweight angle", 400)

    errs = _errors(edited(tmp_path, edit))
    assert [e.where for e in errs] == [where["cell"]]
    assert "400 deg" in errs[0].message and "0..360 deg" in errs[0].message


def test_a_refused_material_and_a_blank_length_each_once(tmp_path):
    where = {}

    def edit(wb):
        where["density"] = _crank_cell(wb, "density", 1e9)
        where["pin"] = _crank_cell(wb, "pin length", None)

    errs = _errors(edited(tmp_path, edit))
    assert sorted(e.where for e in errs) == sorted(where.values())
    pin = next(e for e in errs if e.where == where["pin"])
    assert pin.message.startswith("pin length of every throw is missing")


def test_typed_bearing_dimensions_are_listed_in_the_crank_model(tmp_path, monkeypatch):
    cells = {}

    def edit(wb):
        ws = wb["Bearings"]
        jd, name = column(ws, "journal diameter"), column(ws, "name")
        for r in range(3, ws.max_row + 1):
            if ws.cell(r, name).value == "M2":
                ws.cell(r, jd).value = 55  # typed, as the crank's main journal
                cells["M2"] = f"Bearings!{ws.cell(r, jd).coordinate}"

    res = api.check(edited(tmp_path, edit), select=["BRG-001"])
    model = {(m["sheet"], m["item"], m["attr"]): m
             for m in res.to_dict(timings=False)["crank_model"]}
    typed = model[("Bearings", "M2", "diameter")]
    assert (typed["origin"], typed["cell"], typed["value"], typed["derived"]) == (
        "typed", cells["M2"], 0.055, 0.055)
    derived = model[("Bearings", "M1", "diameter")]
    assert (derived["origin"], derived["cell"], derived["value"]) == ("derived", "Crank!B3",
                                                                       0.055)
    # every bearing's diameter and journal length, and the Fatigue sheet's crank dimensions
    for name in ("M1", "M2", "M3", "M4", "M5", "BE1", "BE2", "BE3", "BE4"):
        for attr in ("diameter", "journal_length"):
            assert ("Bearings", name, attr) in model
    assert model[("Fatigue", "crank", "web_full_thickness")]["origin"] == "derived"
    # the report's crank model table lists them too
    from checker.report.section_crank import crank_section

    stub_section_images(monkeypatch, ["crank"])
    sec = crank_section(res)
    table = next(b for b in sec["blocks"] if b.get("caption", "").startswith(
        "The crank model the analyses use"))
    rows = {(r[0], r[1].split(" [")[0]): r for r in table["rows"]}
    assert rows[("Bearings: M2", "diameter")][3] == f"typed ({cells['M2']})"
    assert rows[("Bearings: M1", "diameter")][3] == "derived (Crank!B3)"
