"""A rule that does not apply is listed as *not applicable* with the reason in every output,
never a pass and never counted as not evaluated (issue 37, item 6): the preload band JNT-001
on a yield- or angle-controlled joint, TV-003 when no order below the cylinder count meets a
crank mode in the speed range, the sputter-lining film guideline on an engine without one."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from checker import api
from checker.evaluation.graph import QUANTITIES, Quantity, ensure_registered
from checker.evaluation.ruletable import evaluate_rule, load_rules
from checker.outputs.formats import to_json, to_junit, to_text
from checker.report import summary
from tests.helpers import edited, example_path, set_cell


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    """The I4 on its joint rules and the sputter guideline: the flywheel bolt is
    yield-controlled (no preload band), no bearing has a sputtered lining."""
    return api.check(example_path(tmp_path_factory.mktemp("na")),
                     select=["JNT-001", "JNT-002", "BRG-005"])


def _by(res):
    return {(r.rule, r.item): r for r in res.results}


def test_a_joint_the_rule_does_not_apply_to_is_listed_with_the_reason(i4):
    by = _by(i4)
    na = by[("JNT-001", "flywheel")]
    assert na.status == "not_applicable" and na.value is None and na.margin is None
    assert na.message == ("not applicable: its tightening is 'yield controlled'; JNT-001"
                          " applies to each torque-tightened joint (preload from tightening"
                          " torque)")
    assert by[("JNT-001", "crank nose")].status == "fail"  # the torque-tightened one
    # a rule on another kind of item (JNT-003: the crank-nose joint) has no line for it
    assert ("JNT-002", "flywheel") in by  # applies to both joints


def test_a_rule_that_applies_to_nothing_here_has_one_line(i4):
    (r,) = [r for r in i4.results if r.rule == "BRG-005"]
    assert r.status == "not_applicable" and r.item == "all"
    assert "sputtered lining" in r.message and "none of this engine's items does" in r.message
    assert "'as16' (M1, M2, M3, M4, M5)" in r.message


def test_not_applicable_is_neither_a_pass_nor_incomplete_in_every_output(i4):
    c = i4.counts()
    assert c["not_applicable"] == 2
    assert c["not_evaluated"] == len([r for r in i4.results if r.status == "not_evaluated"])
    assert all(r.status != "not_applicable" for r in i4.not_evaluated)
    text = to_text(i4)
    assert "JNT-001  NOT APPLICABLE  flywheel" in text
    assert "-> not applicable: its tightening is 'yield controlled'" in text
    assert ", 2 not applicable" in text.splitlines()[-1]
    d = json.loads(to_json(i4, timings=False))
    assert d["counts"]["not_applicable"] == 2
    na = [r for r in d["results"] if r["status"] == "not_applicable"]
    assert {(r["rule"], r["item"]) for r in na} == {("JNT-001", "flywheel"), ("BRG-005", "all")}
    assert all(r["margin_text"] == "" and r["value"] is None for r in na)
    root = ET.fromstring(to_junit(i4))
    case = next(c for c in root.iter("testcase") if c.get("name").startswith("JNT-001")
                and c.get("name").endswith("[flywheel]"))
    assert case.find("skipped").get("message").startswith("not applicable: its tightening")
    assert case.find("failure") is None
    props = {p.get("name"): p.get("value") for p in root.iter("property")}
    assert props["not_applicable"] == "2"
    groups = {g["kind"]: g for g in summary.groups(i4)}
    assert groups["not_applicable"]["count"] == 2
    assert all(x.note.startswith("not applicable: ") for x in groups["not_applicable"]["rows"])


def test_exit_codes_do_not_change(tmp_path):
    """A not-applicable result neither fails nor completes a check: with the crank-nose bolt
    in its preload band JNT-001 passes (exit 0, complete) beside the flywheel's line; with no
    torque-tightened joint at all nothing was checked (exit 2, as when the rule gave no
    result), also with --fail-on not-evaluated."""
    def in_band(wb):
        set_cell(wb, "Joints", "name", "crank nose", "tightening torque", 355)

    res = api.check(edited(tmp_path, in_band), select=["JNT-001"],
                    fail_on="warning,not-evaluated")
    assert [r.status for r in res.results] == ["pass", "not_applicable"]
    assert res.complete and res.verdict_text == "PASS" and res.exit_code == 0

    def all_yield(wb):
        set_cell(wb, "Joints", "name", "crank nose", "tightening", "yield controlled")

    res = api.check(edited(tmp_path, all_yield, "yield.xlsx"), select=["JNT-001"])
    assert {r.status for r in res.results} == {"not_applicable"}
    assert res.nothing_checked and res.exit_code == 2
    assert "not applicable" in res.nothing_checked_reason()


def test_no_lower_order_at_a_crank_mode_is_not_applicable():
    """TV-003 judges the lower orders only at a resonance with a crank mode inside the speed
    range: where there is none it applies to nothing, and says so (it vanished before)."""
    ensure_registered()
    rule = next(r for r in load_rules().rules if r.id == "TV-003")
    spec = QUANTITIES[rule.quantity]
    coords = {"order": ["order 0.5", "order 1"], "case": ["full", "no"],
              "speed": [100.0, 200.0, 300.0]}
    q = Quantity(spec, np.full((2, 2, 3), 0.01), coords,
                 {"all": {"engine_class": "passenger car"}},
                 applies=np.zeros((2, 2, 3), bool),
                 applies_text="judged at the resonant peaks of each order below the cylinder"
                              " count near a crank mode")
    (r,) = evaluate_rule(rule, q, None)
    assert r.status == "not_applicable" and r.item == "all"
    assert r.message == ("not applicable: the rule judges no point of this engine: judged at"
                         " the resonant peaks of each order below the cylinder count near a"
                         " crank mode")
