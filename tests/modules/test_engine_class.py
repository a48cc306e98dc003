"""Limits by engine class: the crank-nose TV targets (TV-001..003) are Bell 2013's for a
refined passenger-car engine; another class has no published target, so those rules are not
evaluated until the project enters its limits (RuleOverrides), and every row says which class
its limit is for."""

from __future__ import annotations

import openpyxl
import pytest

from checker import api
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content
from tests.helpers import edited, example_path, param_row, set_param

TV = ("TV-001", "TV-002", "TV-003")


def _tv(res):
    return {r.rule: r for r in res.results if r.rule in TV}


def _blank_class(wb):
    ws = wb["Engine"]
    ws.cell(param_row(ws, "Engine class"), 2).value = None


def test_every_example_gives_its_class(tmp_path):
    """The template's Engine sheet has the row the docs list (issue 37 item 12): the I4 and
    V8 are passenger-car engines (the I4's an assumption, stated), the I6 a truck diesel."""
    from checker.workbook.example_data import load_example

    for engine, cls, assumed in (("i4", "passenger car", True), ("i6", "commercial vehicle",
                                                                  False),
                                 ("v8", "passenger car", False)):
        row = next(r for r in load_example(engine)["Engine"] if r[0] == "Engine class")
        assert row[1] == cls and ("ASSUMPTION" in row[3]) == assumed, row
    res = api.check(example_path(tmp_path), select=["TV"])
    assert not any("Engine class not given" in a for a in res.assumptions)
    assert any("Engine class = passenger car: ASSUMPTION" in a for a in res.assumptions)
    assert not any(c["kind"] == "assumption" and "TV-001" in c["rules"] for c in res.caveats)
    rows = _tv(res)  # the same verdicts as with the class blank (passenger car assumed)
    assert rows["TV-001"].status == "fail" and rows["TV-002"].status == "fail"
    assert all(r.name.endswith("(passenger car limit)") for r in rows.values())


def test_blank_class_is_a_passenger_car_stated_as_an_assumption(tmp_path):
    res = api.check(edited(tmp_path, _blank_class), select=["TV"])
    rows = _tv(res)
    assert rows["TV-001"].status == "fail" and rows["TV-002"].status == "fail"
    for r in rows.values():
        assert r.name.endswith("(passenger car limit)"), r.name
    assert any("Engine class not given" in a for a in res.assumptions)
    assert any(c["kind"] == "assumption" and "TV-001" in c["rules"] for c in res.caveats)


def test_a_truck_needs_project_limits(tmp_path):
    p = tmp_path / "i6.xlsx"
    write_workbook(p, i6_content(damper_ring=True))
    assert openpyxl.load_workbook(p)["Engine"]["A4"].value == "Engine class"
    res = api.check(p, select=["TV"])
    rows = _tv(res)
    assert set(rows) == set(TV)
    for r in rows.values():
        assert r.status == "not_evaluated"
        assert "commercial vehicle" in r.message and "passenger car" in r.message
        assert "RuleOverrides" in r.message and "Engine!B4" in r.message
        if r.rule == "TV-003":
            # the I6's untuned viscous damper adds no spring mode: no low order meets a crank
            # mode inside the speed range (3 x 2800 rpm < 216.6 Hz), nothing to show
            continue
        assert r.value is not None and r.value > 0  # computed, shown, not judged
        assert "computed, not judged" in r.message
    assert not any(c["kind"] == "assumption" for c in res.caveats)


def test_a_project_limit_makes_the_rule_evaluated(tmp_path):
    def edit(wb):
        set_param(wb, "Engine", "Engine class", "truck")  # an alias of commercial vehicle
        ws = wb["RuleOverrides"]
        ws.cell(3, 1).value, ws.cell(3, 2).value = "TV-001", "0.2"
        ws.cell(3, 3).value, ws.cell(3, 4).value = "deg", "engine maker's truck target"

    res = api.check(edited(tmp_path, edit), select=["TV"])
    rows = _tv(res)
    assert rows["TV-001"].status in ("pass", "fail")
    assert rows["TV-001"].limit == "< 0.2°" and "overridden" in rows["TV-001"].override
    assert rows["TV-001"].status == ("fail" if rows["TV-001"].value >= 0.2 else "pass")
    assert rows["TV-002"].status == "not_evaluated"


@pytest.mark.parametrize("bad", ["lorry-ish"])
def test_unknown_class_is_an_input_error(tmp_path, bad):
    from checker.errors import InputErrors

    def edit(wb):
        set_param(wb, "Engine", "Engine class", bad)

    with pytest.raises(InputErrors, match="Engine class"):
        api.check(edited(tmp_path, edit), select=["TV"])


# --- the layout the targets were given for (issue 37, item 7) ---------------------------------
def _layout_caveats(res):
    return [c for c in res.caveats if "a layout they were not given for" in c["text"]]


def test_the_targets_extrapolated_to_another_layout_are_a_caveat():
    """Bell 2013 gives the crank-nose targets for an I4 (4th order) and a V6 (6th): judging an
    in-line three's 3rd order or a V8's 8th with them is an extrapolation, stated."""
    import tempfile
    from dataclasses import replace
    from pathlib import Path

    from checker.description.engine import load_engine
    from checker.modules.torsion import layout_caveats
    from checker.workbook.example import example_content
    from checker.workbook.example_v8 import v8_content

    with tempfile.TemporaryDirectory() as d:
        i4, v8 = Path(d) / "i4.xlsx", Path(d) / "v8.xlsx"
        write_workbook(i4, example_content())
        write_workbook(v8, v8_content())
        e4, e8 = load_engine(i4), load_engine(v8)
    assert layout_caveats(e4) == ()  # the layout the I4 target is given for
    (c3,) = layout_caveats(replace(e4, cylinders=e4.cylinders[:3]))
    assert "this engine is an in-line three" in c3["text"]
    assert "cylinder-count order (3rd)" in c3["text"] and "Bell 2013" in c3["text"]
    assert c3["kind"] == "limit outside its class" and c3["rules"] == list(TV)
    (c8,) = layout_caveats(e8)
    assert "this engine is a V8" in c8["text"] and "(8th)" in c8["text"]


def test_the_layout_caveat_is_in_every_output_and_not_for_an_i4(tmp_path):
    import json
    import xml.etree.ElementTree as ET

    from checker.outputs.formats import to_json, to_junit, to_text
    from checker.report import review
    from checker.workbook.example_v8 import v8_content

    p = tmp_path / "v8.xlsx"
    write_workbook(p, v8_content())
    res = api.check(p, select=["TV"])
    (c,) = _layout_caveats(res)
    assert c in json.loads(to_json(res, timings=False))["caveats"]
    assert f"limit outside its class: {c['text']}" in to_text(res)
    props = [x.get("value") for x in ET.fromstring(to_junit(res)).iter("property")
             if x.get("name") == "caveat"]
    assert f"limit outside its class: {c['text']}" in props
    page1 = {x["title"]: " ".join(x["items"]) for x in review.caveats(res)}
    assert "this engine is a V8" in page1["Limits outside their engine class"]
    assert not _layout_caveats(api.check(example_path(tmp_path), select=["TV"]))


def test_no_layout_caveat_when_the_project_gives_its_limits(tmp_path):
    """The caveat qualifies the published targets; with the project's own limits for every
    TV rule (RuleOverrides) it has nothing left to qualify."""
    from checker.workbook.example_v8 import v8_content

    p = tmp_path / "v8.xlsx"
    write_workbook(p, v8_content())
    wb = openpyxl.load_workbook(p)
    ws = wb["RuleOverrides"]
    for k, rule in enumerate(TV):
        for j, v in enumerate((rule, "0.1", "deg", "engine maker's V8 target"), start=1):
            ws.cell(3 + k, j).value = v
    wb.save(p)
    res = api.check(p, select=list(TV))  # (TV-004..009, the class rules, do not apply)
    assert all(r.override for r in res.results)
    assert not _layout_caveats(res)
