"""Rule-table validation, selection, overrides and evaluation."""

from __future__ import annotations

import numpy as np
import pytest

from checker import api
from checker.errors import InputErrors, RuleFileError
from checker.evaluation.graph import Quantity
from checker.evaluation.ruletable import Rule, evaluate_rule, load_rules, select_rules
from tests.helpers import analyses_run, edited, example_path

GOOD = '''
[[rule]]
id = "JNT-101"
name = "x"
quantity = "joint.cover_factor"
where = { location = "flywheel", point = "tv peak" }
check = ">="
limit = 1.8
unit = "-"
severity = "error"
source = "test"
rationale = "test"
'''


def write(tmp_path, text, name="r.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_default_table_is_valid_and_sourced():
    t = load_rules()
    ids = [r.id for r in t.rules]
    assert len(ids) == len(set(ids))
    for r in t.rules:
        assert r.source.strip() and r.rationale.strip()


def test_good_file_loads(tmp_path):
    t = load_rules(write(tmp_path, GOOD))
    assert t.rules[0].limit == (1.8,)


@pytest.mark.parametrize("change,match", [
    (('id = "JNT-101"', 'id = "J-1"'), "id must look like"),
    (('quantity = "joint.cover_factor"', 'quantity = "joint.nothing"'), "unknown quantity"),
    (('check = ">="', 'check = "=>"'), "check must be one of"),
    (('severity = "error"', 'severity = "fatal"'), "severity must be"),
    (('limit = 1.8', 'limit = "high"'), "limit must be"),
    (('unit = "-"', 'unit = "mm"'), "does not fit quantity"),
    (('location = "flywheel"', 'colour = "red"'), "where-key 'colour'"),
    (('point = "tv peak"', 'point = "idle"'), "is not one of"),
    (('source = "test"\n', ''), "missing 'source'"),
    (('rationale = "test"', 'rationale = "test"\nlimt = 2'), "unknown key 'limt'"),
])
def test_malformed_rules_refused(tmp_path, change, match):
    with pytest.raises(RuleFileError, match=match):
        load_rules(write(tmp_path, GOOD.replace(*change)))


def test_duplicate_ids_and_bad_toml(tmp_path):
    with pytest.raises(RuleFileError, match="duplicate rule id"):
        load_rules(write(tmp_path, GOOD + GOOD))
    with pytest.raises(RuleFileError, match="not valid TOML"):
        load_rules(write(tmp_path, "[[rule]\nid=", "b.toml"))


def test_between_needs_range(tmp_path):
    with pytest.raises(RuleFileError, match=r"\[low, high\]"):
        load_rules(write(tmp_path, GOOD.replace('check = ">="', 'check = "between"')))


def test_select_and_ignore_prefixes():
    t = load_rules()
    assert {r.id for r in select_rules(t, ["JNT-00"], ["JNT-004"])} == {
        "JNT-001", "JNT-002", "JNT-003", "JNT-005", "JNT-006", "JNT-007", "JNT-008"}
    with pytest.raises(ValueError):
        select_rules(t, ["NOPE"], None)


def _q(values, coords=None):
    from checker.evaluation.graph import QUANTITIES
    spec = QUANTITIES["joint.cover_factor"]
    coords = coords or {"item": ["a"], "point": ["tv peak", "max power", "overspeed"]}
    return Quantity(spec, np.array(values, float), coords,
                    {"a": {"location": "flywheel"}})


def test_evaluation_worst_case_margin_and_tolerance():
    rule = Rule("JNT-101", "x", "joint.cover_factor", ">=", "", "error", "s", "r", (1.8,))
    [res] = evaluate_rule(rule, _q([[1.9, 1.7, 2.5]]), None)
    assert res.status == "fail" and res.value == pytest.approx(1.7) and res.case == "max power"
    assert res.margin == pytest.approx((1.7 - 1.8) / 1.8)
    # a value equal to the limit up to float noise passes
    [res] = evaluate_rule(rule, _q([[1.8 * (1 - 1e-12), 2, 2]]), None)
    assert res.status == "pass"


def test_missing_values_are_not_evaluated_never_pass():
    rule = Rule("JNT-101", "x", "joint.cover_factor", ">=", "", "error", "s", "r", (1.8,))
    q = _q([[2.0, np.nan, 2.0]])
    q.missing[(0, 1)] = ["JointTorques: torque at max power"]
    [res] = evaluate_rule(rule, q, None)
    assert res.status == "not_evaluated" and "max power" in res.missing[0]
    [res] = evaluate_rule(rule, None, ["Joints: no joints"])
    assert res.status == "not_evaluated" and res.missing == ["Joints: no joints"]


def test_override_from_workbook_is_applied_and_listed(tmp_path):
    def edit(wb):
        ws = wb["RuleOverrides"]
        ws.append(["JNT-005", 1.75, "-", "OEM guideline for this flywheel (DMF)"])

    res = api.check(edited(tmp_path, edit), select=["JNT-005"])
    [r] = res.results
    assert r.status == "pass" and r.limit == "≥ 1.75"  # 1.771 >= 1.75
    [o] = res.table.overrides
    assert o.rule == "JNT-005" and o.old == "≥ 1.8" and "OEM" in o.reason and o.where


def test_override_of_unknown_rule_is_input_error(tmp_path):
    def edit(wb):
        wb["RuleOverrides"].append(["JNT-999", 2, "-", "why"])

    with pytest.raises(InputErrors, match="unknown rule 'JNT-999'"):
        api.check(edited(tmp_path, edit))


def test_api_returns_dataframe_without_files(tmp_path):
    p = example_path(tmp_path)
    before = set(tmp_path.iterdir())
    res = api.check(p, select=["JNT"])
    df = res.to_frame()
    assert set(tmp_path.iterdir()) == before
    assert {"rule", "item", "status", "value", "unit", "limit"} <= set(df.columns)
    assert res.verdict == "fail" and res.exit_code == 1
    # in-memory engine: the same result without a workbook
    res2 = api.check(res.engine, select=["JNT"])
    assert res2.to_dict(timings=False)["results"] == res.to_dict(timings=False)["results"]


def test_selection_skips_modules(tmp_path):
    def edit(wb):  # every joint torque given: the TV module (and loads) are needed only to
        # compare the given torques with the torsional model's (JNT-008)
        ws = wb["JointTorques"]
        for j in ("crank nose", "flywheel"):
            for point, speed, torque in (("max power", 5500, 300), ("overspeed", 7000, 280)):
                ws.append([j, point, speed, torque * (4 if j == "flywheel" else 1)])

    res = api.check(edited(tmp_path, edit), select=["JNT"], ignore=["JNT-008"])
    assert analyses_run(res.outcome) == ["joints"]
    assert set(res.outcome.modules_skipped) == set(
        m for m in __import__("checker.evaluation.graph", fromlist=["MODULES"]).MODULES
        if m not in ("joints", "crank"))  # crank: runs whenever sheet Crank is given


def test_resonant_peak_mask_and_applies():
    from checker.evaluation.graph import resonant_peaks

    a = np.array([5.0, 4.0, 3.0, 3.5, 2.0, 1.0, 1.5])
    # rolling-mode fall from the lowest speed is not a peak; interior maximum and rising end are
    assert resonant_peaks(a).tolist() == [False, False, False, True, False, False, True]
    rule = Rule("JNT-101", "x", "joint.cover_factor", ">=", "", "error", "s", "r", (1.8,))
    q = _q([[1.0, 2.0, 2.5]])
    q.applies = np.array([[False, True, True]])
    [res] = evaluate_rule(rule, q, None)  # the 1.0 point is not judged
    assert res.status == "pass" and res.value == pytest.approx(2.0)
    q.applies = np.zeros((1, 3), bool)
    q.applies_text = "judged at resonant peaks only"
    # nothing to judge: not applicable, with the reason (never a pass without a value)
    [na] = evaluate_rule(rule, q, None)
    assert na.status == "not_applicable" and na.value is None and na.margin is None
    assert na.message.startswith("not applicable: the rule judges no point of")
    assert "judged at resonant peaks only" in na.message


def test_joints_only_workbook_uses_given_torques(tmp_path):
    """Only Engine, Joints and JointTorques: the given TV-peak torques are used although the
    torsional module cannot run; the other points say why they are not evaluated."""
    from checker.workbook.example import example_content, write_workbook

    c = example_content()
    p = tmp_path / "joints_only.xlsx"
    write_workbook(p, {k: c[k] for k in ("Engine", "Joints", "JointTorques")})
    res = api.check(p, select=["JNT"])
    by = {(r.rule, r.item): r for r in res.results}
    assert by[("JNT-003", "crank nose")].status == "fail"
    assert by[("JNT-005", "flywheel")].value == pytest.approx(1.771, abs=5e-4)
    r6 = by[("JNT-006", "flywheel")]
    assert r6.status == "not_evaluated" and "torsional module could not run" in r6.missing[0]
    assert "Cylinders" in r6.missing[0]


def test_findings_of_the_judged_point_come_first():
    """A note shown beside a result describes its judged point (I6: the JNT-008 row at 'max
    power' carried the note of 'tv peak')."""
    from checker.evaluation.graph import ensure_registered

    ensure_registered()
    rule = Rule("JNT-101", "x", "joint.cover_factor", ">=", "", "error", "s", "r", (1.8,))
    q = _q([[1.9, 1.7, 2.5]])
    q.findings = {(0, 0): ["at tv peak"], (0, 1): ["at max power"]}
    [res] = evaluate_rule(rule, q, None)
    assert res.case == "max power"
    assert res.findings == ["at max power", "at tv peak"]


# --- not-evaluated reasons read as sentences (issue 37, item 2) -------------------------------
@pytest.mark.parametrize(("reasons", "message"), [
    (["Bearings!Q3: max film temperature of M1 (the shell supplier's limit)"],
     "not evaluated: missing Bearings!Q3: max film temperature of M1 (the shell supplier's"
     " limit)"),
    (["no limit for the engine is given in the workbook",
      "Damper!B3: Rubber inner radius of the damper rubber (length, e.g. mm)"],
     "not evaluated: no limit for the engine is given in the workbook; missing Damper!B3: Rubber"
     " inner radius of the damper rubber (length, e.g. mm)"),
    (["Joints: no bolted joints are given (sheet Joints)"],
     "not evaluated: Joints: no bolted joints are given (sheet Joints)"),
    (["Engine (parameter 'Free force limit, 1st order'): Free force limit, 1st order of the"
      " project (needed to judge the 1st-order free force; blank = not judged) (force)"],
     "not evaluated: missing Engine (parameter 'Free force limit, 1st order'): Free force"
     " limit, 1st order of the project (needed to judge the 1st-order free force; blank = not"
     " judged) (force)"),
    (["M53 formula gives no valid SCF for this geometry",
      "or give the factor: Fatigue!B20: alpha_B (a number, no unit)"],
     "not evaluated: M53 formula gives no valid SCF for this geometry; or give the factor:"
     " Fatigue!B20: alpha_B (a number, no unit)"),
])
def test_not_evaluated_reasons_compose_into_sentences(reasons, message):
    from checker.evaluation.ruletable import not_evaluated_message

    assert not_evaluated_message(reasons) == message


def _damper_blank(*labels):
    def edit(wb):
        from tests.helpers import param_row

        ws = wb["Damper"]
        for label in labels:
            ws.cell(param_row(ws, label), 2).value = None
    return edit


@pytest.mark.parametrize("blank", [
    ("Rubber inner radius", "Rubber shear stress limit"),  # both: each named once
    ("Rubber inner radius",),  # the limit given: the geometry is what is missing
    ("Rubber shear stress limit",),
])
def test_damper_rule_without_geometry_or_limit_names_what_is_missing(tmp_path, blank):
    """DMP-001 read "missing no limit for 'all' given in the workbook" when the damper's
    geometry was blank: its limit was not looked up at all. Every blank cell is named, in a
    sentence, and the whole engine is not called 'all'."""
    res = api.check(edited(tmp_path, _damper_blank(*blank)), select=["DMP-001"])
    (r,) = res.results
    assert r.status == "not_evaluated"
    assert "missing no " not in r.message and "'all'" not in r.message, r.message
    assert r.message.startswith("not evaluated: missing Damper!B"), r.message
    for label in blank:
        assert label in r.message, (label, r.message)
    for label in {"Rubber inner radius", "Rubber shear stress limit"} - set(blank):
        assert label not in r.message, (label, r.message)
