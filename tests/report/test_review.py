"""Page 1 of the report: failures ranked by severity (predicted failures first, then by the
distance to the limit), a mechanism line for every rule, the caveats box and the
document-control block."""

from __future__ import annotations

import pytest

from checker import api
from checker.evaluation.ruletable import RuleResult
from checker.report import review, summary
from tests.helpers import edited, example_path, param_row, program_internals


def _result(rule: str, value: float, margin: float, status: str = "fail") -> RuleResult:
    return RuleResult(rule=rule, name=rule, item="x", status=status, severity="error",
                      value=value, unit="", limit="", limit_values=[1.5], margin=margin,
                      case="full", message="", source="")


def _row(r: RuleResult) -> summary.Row:
    return summary.Row("fail", r.rule, r.name, [r.item], r.case, str(r.value), "", "", "", "",
                       r.margin, [r])


def test_predicted_failures_come_first_then_the_furthest_from_the_limit():
    rows = [_row(_result("DMP-002", 12.4, -11.4)),  # far over its limit, but a design margin
            _row(_result("JNT-005", 0.75, -0.58)),  # cover factor < 1: the joint slips
            _row(_result("BRG-003", 0.37, -0.69)),
            _row(_result("FAT-001", 0.88, -0.41)),  # Goodman SF < 1: a crack is expected
            _row(_result("FAT-001", 1.27, -0.16))]  # below target, not below 1
    ranked = review.rank_failures(rows)
    assert [(x.rule, x.results[0].value) for x in ranked] == [
        ("JNT-005", 0.75), ("FAT-001", 0.88), ("DMP-002", 12.4), ("BRG-003", 0.37),
        ("FAT-001", 1.27)]
    assert "slips" in ranked[0].predicted and "crack" in ranked[1].predicted
    assert not ranked[2].predicted and not ranked[4].predicted
    # one mechanism line per failure; a repeated mechanism points back to its first row
    assert ranked[1].mechanism_text.startswith("Goodman")
    assert ranked[4].mechanism_text == "Mechanism as #2."


def test_every_rule_has_a_mechanism_that_cites_a_publication():
    from checker.evaluation.ruletable import load_rules

    for r in load_rules().rules:
        text = review.mechanism(r.id)
        assert text, r.id
        assert any(ch.isdigit() for ch in text), (r.id, text)  # a year or a section


@pytest.fixture(scope="module")
def checked(tmp_path_factory):
    def doc_control(wb):
        ws = wb["Engine"]
        # the engine class left blank: its assumption is a caveat (a dict with kind, severity,
        # rules and text, issue 37 item 1)
        ws.cell(param_row(ws, "Engine class"), 2).value = None
        row = ws.max_row + 1
        for k, (label, value) in enumerate((("Author", "A. Engineer"),
                                            ("Reviewer", "B. Chief"))):
            ws.cell(row + k, 1).value = label
            ws.cell(row + k, 2).value = value
            ws.cell(row + k, 3).value = "-"

    p = edited(tmp_path_factory.mktemp("review"), doc_control)
    return api.check(p, select=["FAT", "TV", "JNT-001"])


def test_the_caveats_name_validity_flags_class_limits_and_assumptions(checked):
    cav = {c["title"]: " ".join(c["items"]) for c in review.caveats(checked)}
    assert "M53" in cav["Model validity"]  # the example's main-fillet ratio is outside M53
    assert "TV-001" in cav["Limits outside their engine class"]
    assert "passenger-car" in cav["Limits outside their engine class"]
    assert "marked as assumptions" in cav["Inputs that are assumptions"]


def test_the_caveats_are_sentences_not_program_data(checked):
    """Issue 37: the engine-class caveat the torsion states (a dict with kind, severity,
    rules and text) was printed as the dict's repr on page 2; its sentence is shown, under
    the heading of its kind."""
    cav = {c["title"]: " ".join(c["items"]) for c in review.caveats(checked)}
    for title, text in cav.items():
        assert not program_internals(f"{title}. {text}"), (title, text)
    assert cav["Assumptions behind the limits"].startswith("Engine class not given (")
    assert "'kind'" not in " ".join(cav.values())


def test_assumptions_become_rows_with_sheet_cell_value_and_source(checked):
    rows = review.assumption_rows(checked)
    engine = [r for r in rows if r["sheet"] == "Engine"]
    assert engine and all(r["cell"] and r["value"] and r["source"] for r in engine)
    assert not any(r["source"].startswith("ASSUMPTION") for r in rows)


def test_document_control_comes_from_the_engine_sheet(checked):
    dc = dict(review.document_control(checked))
    assert dc["Project"].startswith("Example review")  # the example workbook's own
    assert dc["Revision"] == "A"
    assert dc["Author"] == "A. Engineer" and dc["Reviewer"] == "B. Chief"
    assert dc["Date"] != "-"  # the run date when the workbook gives none


def test_blank_document_control_shows_dashes(tmp_path):
    res = api.check(example_path(tmp_path), select=["JNT-001"])
    dc = dict(review.document_control(res))
    assert dc["Author"] == "-" and dc["Reviewer"] == "-"
