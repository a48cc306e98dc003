"""One meaning per status (issue 43, item 9; docs/verdicts.md, docs/workbook.md): a blank
lining leaves the lining rules not evaluated, naming the cell (not "not applicable"); a rubber
table that covers neither end of the operating range leaves every rule judging the ends not
evaluated, DMP-005 (judged at the largest power) as DMP-006/007."""

from __future__ import annotations

from checker import api
from tests.helpers import column, edited


def _by(res, rule):
    return {r.item: r for r in res.results if r.rule == rule}


def test_blank_linings_leave_the_sputter_rules_not_evaluated_at_their_cells(tmp_path):
    cells = {}

    def edit(wb):
        ws = wb["Bearings"]
        lin, name = column(ws, "lining"), column(ws, "name")
        for r in range(3, ws.max_row + 1):
            ws.cell(r, lin).value = None
            cells[ws.cell(r, name).value] = f"Bearings!{ws.cell(r, lin).coordinate}"

    res = api.check(edited(tmp_path, edit), select=["BRG-001", "BRG-005", "BRG-006"])
    for rule in ("BRG-001", "BRG-005", "BRG-006"):
        got = _by(res, rule)
        assert set(got) == set(cells), rule
        for item, r in got.items():
            assert r.status == "not_evaluated", (rule, item, r.message)
            assert r.message.startswith(f"not evaluated: missing {cells[item]}: lining of"
                                        f" {item}"), r.message


def test_another_lining_stays_not_applicable(tmp_path):
    # the example's linings (AS15/AS16) are given: the sputter guideline does not apply
    def edit(wb):
        ws = wb["Bearings"]
        ws.cell(3, column(ws, "lining")).value = None  # M1 blank, the others given

    res = api.check(edited(tmp_path, edit), select=["BRG-005"])
    got = _by(res, "BRG-005")
    assert got["M1"].status == "not_evaluated"
    assert {r.status for i, r in got.items() if i != "M1"} == {"not_applicable"}


def test_a_one_row_rubber_table_leaves_dmp_005_not_evaluated_as_006_and_007(tmp_path):
    def edit(wb):
        ws = wb["DamperRubber"]
        for r in range(4, ws.max_row + 1):
            for c in range(1, ws.max_column + 1):
                ws.cell(r, c).value = None

    res = api.check(edited(tmp_path, edit), select=["DMP-005", "DMP-006", "DMP-007"])
    for rule in ("DMP-005", "DMP-006", "DMP-007"):
        (r,) = _by(res, rule).values()
        assert r.status == "not_evaluated", (rule, r.message)
        assert "lies outside the rubber table" in r.message, r.message
