"""Input messages (issue 43, item 10): each problem once, at its cell, with the values: a
wrong unit in a table's unit row at that row, a duplicate or a minimum above its maximum
naming both values and the other cell, and the article before a unit kind."""

from __future__ import annotations

import pytest

from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.workbook.units import UnitProblem, to_si
from tests.helpers import column, edited, set_param


def _errors(path) -> list:
    with pytest.raises(InputErrors) as exc:
        load_engine(path)
    return exc.value.errors


def test_a_wrong_unit_in_the_unit_row_is_reported_once_at_row_2(tmp_path):
    where = {}

    def edit(wb):
        ws = wb["Crank"]
        c = ws.cell(2, column(ws, "web thickness"))
        c.value = "MM"
        where["unit"] = f"Crank!{c.coordinate}"
        ws = wb["PeakPressure"]  # a table of many rows: its values unread, one error
        c = ws.cell(2, column(ws, "speed"))
        c.value = "kg"
        where["speed"] = f"PeakPressure!{c.coordinate}"

    errs = _errors(edited(tmp_path, edit))
    assert sorted(e.where for e in errs) == sorted(where.values())
    web = next(e for e in errs if e.where == where["unit"])
    assert "found unit 'MM'" in web.message and "did you mean 'mm'" in web.message
    assert "row 2" in web.message


def test_duplicate_temperature_names_the_value_and_the_other_cell(tmp_path):
    cells = {}

    def edit(wb):
        ws = wb["DamperRubber"]
        t = column(ws, "temperature")
        ws.cell(4, t).value = ws.cell(3, t).value
        cells["first"] = f"DamperRubber!{ws.cell(3, t).coordinate}"
        cells["second"] = f"DamperRubber!{ws.cell(4, t).coordinate}"
        cells["value"] = ws.cell(3, t).value

    errs = _errors(edited(tmp_path, edit))
    assert [e.where for e in errs] == [cells["second"]]
    assert f"duplicate temperature {cells['value']:g} °C" in errs[0].message
    assert f"also at {cells['first']}" in errs[0].message


def test_minimum_above_maximum_names_both_values_and_the_other_cell(tmp_path):
    cells = {}

    def edit(wb):
        cells["min"] = set_param(wb, "Damper", "Operating temperature, minimum", 95)
        cells["max"] = set_param(wb, "Damper", "Operating temperature, maximum", 20)
        cells["smin"] = set_param(wb, "Engine", "Minimum speed", 6000)
        cells["smax"] = set_param(wb, "Engine", "Maximum speed", 2000)

    errs = {e.where: e.message for e in _errors(edited(tmp_path, edit))}
    assert "95 °C" in errs[cells["min"]] and "20 °C" in errs[cells["min"]]
    assert cells["max"] in errs[cells["min"]]
    assert "2000 rpm" in errs[cells["smax"]] and "6000 rpm" in errs[cells["smax"]]
    assert cells["smin"] in errs[cells["smax"]]


def test_an_angle_is_expected_with_an():
    from checker.workbook.units import kind_words

    assert kind_words("angle") == "an angle"
    assert kind_words("inertia") == "an inertia"
    assert kind_words("length") == "a length"
    assert kind_words("heat_flux") == "a heat flux"
    with pytest.raises(UnitProblem) as exc:
        to_si(1.0, "mm", "angle")
    assert "expected an angle" in str(exc.value)


def test_the_brief_expects_an_angle():
    from checker.sizing.brief import parse_brief

    with pytest.raises(InputErrors) as exc:
        parse_brief({"bank_angle": "3 kg"})
    assert any("expected an angle" in e.message for e in exc.value.errors)
