"""The summary a reviewer reads first: failures, warnings, not evaluated, passes, in that
order; one row for a finding shared by several items; overrides shown on the rows, in the text
output and in the JSON; values, units and distances to the limit in one style."""

from __future__ import annotations

import json

import pytest

from checker import api
from checker.outputs import formats as outputs
from checker.report import summary
from checker.results import display
from tests.helpers import edited, example_path


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return api.check(example_path(tmp_path_factory.mktemp("summary")),
                     select=["BRG", "JNT"])


def test_groups_in_reader_order_and_counts_add_up(result):
    groups = summary.groups(result)
    kinds = [g["kind"] for g in groups]
    assert kinds == [k for k, _, _ in summary.GROUPS if k in kinds]
    c = result.counts()
    by = {g["kind"]: g["count"] for g in groups}
    assert by.get("fail", 0) == c["fail"] and by.get("pass", 0) == c["pass"]
    assert by.get("warning", 0) == c["warning"]
    assert by.get("not_evaluated", 0) == c["not_evaluated"]
    assert sum(len(r.results) for g in groups for r in g["rows"]) == len(result.results)


def test_identical_findings_share_one_row(result):
    # the four big ends of the example are identical: BRG-003 (judged on the finite-length
    # film) fails on all four with 0.3683 µm, shown once
    rows = [r for r in summary.rows(result) if r.rule == "BRG-003" and r.kind == "fail"
            and "BE1" in r.items]
    assert len(rows) == 1 and rows[0].items == ["BE1", "BE2", "BE3", "BE4"]
    assert rows[0].value == "0.3683 µm" and rows[0].limit == "≥ 1.2 µm"
    assert rows[0].margin == "69 % below the minimum"
    # different values stay apart
    mains = [r for r in summary.rows(result) if r.rule == "BRG-001" and r.kind == "pass"]
    assert len(mains) > 1 and all(len(r.results) == len(r.items) for r in mains)


def test_look_first_lists_the_smallest_passing_margins(result):
    first = summary.look_first(result)
    margins = [r.margin_value for r in first]
    assert margins == sorted(margins) and all(r.kind == "pass" for r in first)
    smallest = min(r.margin for r in result.results if r.status == "pass" and r.margin is not None)
    assert margins[0] == pytest.approx(smallest)


def test_override_is_shown_on_the_row_in_text_and_json(tmp_path):
    def edit(wb):
        wb["RuleOverrides"].append(["JNT-005", 1.75, "-", "OEM guideline for this flywheel"])

    res = api.check(edited(tmp_path, edit), select=["JNT-005"])
    [r] = res.results
    assert "≥ 1.8 → ≥ 1.75" in r.override and "OEM guideline" in r.override
    [row] = summary.rows(res)
    assert row.override == r.override
    assert r.override in outputs.to_text(res)
    [j] = json.loads(outputs.to_json(res))["results"]
    assert j["override"] == r.override and j["margin_text"] == r.margin_text


@pytest.mark.parametrize(("value", "limit", "shown"), [
    (0.87129, None, "0.8713"), (45.2634, None, "45.26"), (1512.3, None, "1512"),
    (12345.6, None, "12346"), (1.79996, 1.8, "1.79996"), (1.80049, 1.8, "1.8005"),
    (0.000123456, None, "1.235e-4"), (-3.5, None, "−3.5"), (0.0, None, "0"),
])
def test_numbers_have_four_digits_unless_they_would_read_as_the_limit(value, limit, shown):
    assert display.number(value, distinct_from=limit) == shown


@pytest.mark.parametrize(("unit", "shown"), [
    ("um", "µm"), ("N/mm^2", "MPa"), ("N m", "N·m"), ("N*m", "N·m"), ("deg", "°"),
    ("W/cm^3", "W/cm³"), ("kg m^2", "kg·m²"), ("-", ""), ("%", "%"), ("MPa", "MPa"),
])
def test_one_unit_style(unit, shown):
    assert display.unit_text(unit) == shown


@pytest.mark.parametrize(("check", "value", "limit", "margin", "passed", "words"), [
    ("<=", 554.5, [500], -0.109, False, "limit exceeded by 11 %"),
    ("<=", 12.37, [1], -11.37, False, "12.4 × the limit"),
    (">=", 0.8713, [1.2], -0.274, False, "27 % below the minimum"),
    (">=", 1.575, [1.5], 0.05, True, "5.0 % above the minimum"),
    ("<=", 45.26, [48], 0.057, True, "5.7 % below the limit"),
    ("between", 79.51, [70, 75], -0.06, False, "6.0 % above the range"),
])
def test_margins_read_in_words(check, value, limit, margin, passed, words):
    assert display.margin_words(check, value, limit, margin, passed) == words
