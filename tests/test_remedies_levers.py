"""Which levers a result is offered (checker.description.levers, rules/levers.toml): the oil
grade's choices
cover every SAE J300 high-temperature grade in the order of their J300 viscosity, and a thin
grade (5W-20, 0W-20) is offered a thicker one."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from checker import api
from checker.calc.viscosity import SAE_J300_2015, j300_grade, j300_order
from checker.description.levers import load_levers
from checker.evaluation.ruletable import load_rules
from checker.remedies.solve import _discrete_candidates, find_remedies
from checker.remedies.variants import Evaluator
from checker.workbook.loader import read_raw_workbook


def _grade_lever():
    return next(lv for lv in load_levers() if lv.id == "oil-grade")


def _candidates(today: str, sign: int = 1) -> list[str]:
    job = SimpleNamespace(lever=_grade_lever(), binding=SimpleNamespace(nominal=[today]),
                          sign=sign)
    return _discrete_candidates(job)


def test_oil_grade_choices_cover_every_j300_grade_in_viscosity_order():
    choices = [str(c) for c in _grade_lever().choices]
    # every high-temperature grade of SAE J300 (2015-01) Table 1, with both 40 HTHS minima
    limits = {(hths, lo) for lo, _, hths in SAE_J300_2015.values()}
    assert {j300_order(c) for c in choices} == limits
    assert {"5W-20", "0W-20", "5W-30", "15W-40"} <= set(choices)
    # the file lists them in their J300 order: HTHS at 150 C, then KV100 (both minima)
    keys = [j300_order(c) for c in choices]
    assert keys == sorted(keys)
    g = {c: j300_grade(c) for c in ("0W-40", "15W-40", "20W-50")}
    assert g["0W-40"].hths150_min == pytest.approx(3.5e-3)  # below 15W-40's 3.7 mPa s
    assert j300_order("0W-40") < j300_order("15W-40") < j300_order("20W-50")


@pytest.mark.parametrize("today", ["5W-20", "0W-20", "5W20", "SAE 0W-20"])
def test_a_thin_grade_is_offered_a_thicker_one(today):
    up = _candidates(today)
    assert up, f"no thicker grade offered from {today}"
    winter = today.replace("SAE ", "")[:2]
    assert up[0] == f"{winter}-30"  # the next J300 grade, today's winter grade kept
    assert all(j300_order(c) > j300_order(today) for c in up)
    # one grade per J300 viscosity, nearest first
    keys = [j300_order(c) for c in up]
    assert keys == sorted(set(keys))
    down = _candidates(today, sign=-1)
    assert [j300_order(c) for c in down] == sorted({j300_order(c) for c in down}, reverse=True)
    assert down[0] == "0W-16"


def test_the_thickest_grade_has_no_further_choice_and_unknown_text_none():
    assert _candidates("20W-60") == []
    assert _candidates("castor oil") == []


def test_lever_file_refuses_a_grade_j300_does_not_know(tmp_path):
    from checker.errors import RuleFileError

    p = tmp_path / "l.toml"
    p.write_text('[[lever]]\nid = "g"\nrules = ["BRG-003"]\nsheet = "Oil"\nrow = "Oil grade"\n'
                 'direction = "increase"\nchoices = ["5W-30", "5W-35"]\n', encoding="utf-8")
    with pytest.raises(RuleFileError, match="5W-35"):
        load_levers(p)


def test_i4_with_5w20_oil_gets_a_thicker_grade_remedy(tmp_path):
    from checker.workbook.example import example_content, write_workbook

    content = example_content()
    content["Oil"] = [("Oil grade", "5W-20", "-", "test") if r[0] == "Oil grade" else r
                      for r in content["Oil"]]
    wb = tmp_path / "engine.xlsx"
    write_workbook(wb, content)
    table = load_rules()
    sel = ["BRG-003"]
    ev = Evaluator(read_raw_workbook(wb), table, select=sel)
    nom = api.check(wb, select=sel, cache=ev.cache)
    lever = [lv for lv in table.levers if lv.id == "oil-grade"]
    out = find_remedies(nom, ev, lever)
    grade = [rm for rr in out for rm in rr.remedies]
    assert grade, "no oil-grade remedy for a failing film"
    for rm in grade:
        assert rm.reason != "no further choice in that direction"
        assert rm.evaluations > 0  # thicker grades were tried
        if rm.found:
            assert j300_order(str(rm.value)) > j300_order("5W-20")


@pytest.fixture(scope="module")
def v8_joints(tmp_path_factory):
    from checker.workbook.example import write_workbook
    from checker.workbook.example_data import load_example

    wb = tmp_path_factory.mktemp("v8") / "engine-v8.xlsx"
    write_workbook(wb, load_example("v8"))
    table = load_rules()
    sel, ign = ["JNT-00"], ["JNT-008"]
    ev = Evaluator(read_raw_workbook(wb), table, select=sel, ignore=ign)
    nom = api.check(wb, select=sel, ignore=ign, cache=ev.cache)
    return {(rr.rule, rr.item): rr for rr in find_remedies(nom, ev, table.levers)}


def test_joint_levers_follow_the_tightening_method(v8_joints):
    # the V8's crank-nose bolt is angle controlled (preload fraction blank: the method's 0.85),
    # its flywheel bolts torque controlled (examples/templates: example_v8.toml)
    nose = [rr for (rule, item), rr in v8_joints.items() if item == "crank nose"]
    fly = [rr for (rule, item), rr in v8_joints.items() if item == "flywheel"]
    assert nose and fly
    for rr in nose:
        ids = {rm.lever.id for rm in rr.remedies}
        assert "joint-tightening-torque" not in ids
        assert "joint-preload-fraction" in ids and "joint-bolt-size" in ids
        frac = next(rm for rm in rr.remedies if rm.lever.id == "joint-preload-fraction")
        assert frac.nominal == pytest.approx(0.85)  # Bell 2013: snug + angle, 0.85 R_p0.2
        assert "blank" not in frac.reason
    for rr in fly:
        ids = {rm.lever.id for rm in rr.remedies}
        assert "joint-tightening-torque" in ids and "joint-preload-fraction" not in ids
    for rr in nose + fly:
        assert all("today's value is blank" not in rm.reason for rm in rr.remedies)


def test_when_is_validated_and_resolves_spellings(tmp_path):
    from checker.errors import RuleFileError

    base = ('[[lever]]\nid = "t"\nrules = ["JNT-001"]\nsheet = "Joints"\nrow = "{item}"\n'
            'column = "tightening torque"\nunit = "N m"\ndirection = "either"\n'
            'bounds = [0.5, 1.5]\n')
    p = tmp_path / "l.toml"
    p.write_text(base + 'when = { tightening = ["torque", "angle"] }\n', encoding="utf-8")
    (lv,) = load_levers(p)
    assert lv.holds_for({"tightening": "Angle-controlled"})
    assert lv.holds_for({"tightening": "torque"})
    assert not lv.holds_for({"tightening": "yield controlled"})
    assert not lv.holds_for({"tightening": None})
    for bad in ('when = { tightening = ["by hand"] }\n', 'when = { bolts = [1] }\n'):
        p.write_text(base + bad, encoding="utf-8")
        with pytest.raises(RuleFileError, match="when"):
            load_levers(p)
