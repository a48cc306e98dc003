"""The template workbook explains itself: a description per parameter (schema), comments on
table columns, drop-down lists for choices, ASSUMPTION values highlighted, a long table note
written once per run of rows ("as above") and still applied to every row it covers."""

from __future__ import annotations

from pathlib import Path

import openpyxl
import pytest

from checker.description.engine import load_engine
from checker.workbook.example import example_content, write_workbook
from checker.workbook.loader import DITTO
from checker.workbook.schema import SHEETS


@pytest.fixture(scope="module")
def template(tmp_path_factory):
    p = tmp_path_factory.mktemp("tpl") / "engine.xlsx"
    write_workbook(p, example_content())
    return p


def test_parameter_sheets_have_descriptions_and_choice_lists(template):
    wb = openpyxl.load_workbook(template)
    ws = wb["Engine"]
    assert ws["E1"].value == "description"
    labels = {f.label.lower(): f for f in SHEETS["Engine"].fields}
    described = 0
    for r in range(2, ws.max_row + 1):
        f = labels.get(str(ws.cell(r, 1).value).lower())
        if f is not None:
            desc = ws.cell(r, 5).value
            assert desc and ("required" in desc or "optional" in desc), (r, desc)
            described += 1
    assert described == ws.max_row - 1
    # a choice parameter offers its choices in a drop-down that allows other spellings
    lists = [dv for dv in ws.data_validations.dataValidation if dv.type == "list"]
    assert any("clockwise" in dv.formula1 and not dv.showErrorMessage for dv in lists)


def test_table_columns_have_comments_and_choice_lists(template):
    wb = openpyxl.load_workbook(template)
    ws = wb["Bearings"]
    header = {ws.cell(1, j).value: ws.cell(1, j) for j in range(1, ws.max_column + 1)}
    assert "main" in header["type"].comment.text and "big end" in header["type"].comment.text
    lists = [dv.formula1 for dv in ws.data_validations.dataValidation if dv.type == "list"]
    assert any("partial" in f for f in lists) and any("as16" in f for f in lists)


def test_assumptions_highlighted_and_notes_not_repeated(template):
    wb = openpyxl.load_workbook(template)
    ws = wb["Engine"]
    for r in range(2, ws.max_row + 1):
        note = str(ws.cell(r, 4).value or "")
        filled = ws.cell(r, 2).fill.fgColor.rgb not in (None, "00000000")
        assert filled == ("assumption" in note.lower()), (r, note)
    ws = wb["Bearings"]
    note_col = next(j for j in range(1, ws.max_column + 1) if ws.cell(1, j).value == "note")
    notes = [ws.cell(r, note_col).value for r in range(3, ws.max_row + 1)]
    assert notes.count(DITTO[0]) >= 5  # 9 bearings, 2 distinct notes
    # the loader applies a note to every row it covers: the report lists all rows
    eng = load_engine(template)
    rows = [a for a in eng.assumptions if a.startswith("Bearings rows")]
    assert any("3, 4, 5, 6, 7" in a for a in rows) and any("8, 9, 10, 11" in a for a in rows)


def test_template_says_what_ambiguous_inputs_mean(template):
    """Issue 37 item 12: the Engine sheet has the 'Engine class' row the docs list; the oil
    hole heights say what they are measured from; the TVModel inertia says whether a cylinder
    station includes the con-rod and piston shares (it does: the model adds nothing)."""
    wb = openpyxl.load_workbook(template)
    ws = wb["Engine"]
    rows = {str(ws.cell(r, 1).value): r for r in range(2, ws.max_row + 1)}
    assert "Engine class" in rows
    r = rows["Engine class"]
    assert ws.cell(r, 2).value == "passenger car" and "ASSUMPTION" in ws.cell(r, 4).value
    fa = wb["Fatigue"]
    desc = {str(fa.cell(r, 1).value): fa.cell(r, 5).value for r in range(2, fa.max_row + 1)}
    for name in ("Pin journal oil hole height", "Main journal oil hole height"):
        assert "throw plane" in desc[name] and "crank axis" in desc[name], desc[name]
    tv = wb["TVModel"]
    header = {tv.cell(1, j).value: tv.cell(1, j) for j in range(1, tv.max_column + 1)}
    text = header["inertia"].comment.text
    assert "con-rod and piston shares" in text and "used as given" in text
    assert "1/2 m_rec r^2" in text
    doc = (Path(__file__).resolve().parents[2] / "docs" / "workbook.md").read_text()
    assert "con-rod and piston shares" in doc and "throw plane" in doc
