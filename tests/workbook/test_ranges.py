"""Plausibility: values that parse but lie far outside crank-train engines are caught at the
loader with their cell, an error outside a field's declared ``valid`` range (the calculation
cannot run), a warning outside its ``usual`` range; one mechanism declared in the schema."""

from __future__ import annotations

import math

import pytest

from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.workbook.schema import SHEETS, Span
from checker.workbook.units import KINDS, to_si
from tests.helpers import edited, set_cell, set_param


def _errors(path) -> list[str]:
    with pytest.raises(InputErrors) as info:
        load_engine(path)
    return [str(e) for e in info.value.errors]


def test_bore_in_inches_is_a_warning_with_cell(tmp_path):
    """86 'in' = 2.18 m: computable, but no crank-train engine has it (a unit slip)."""
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_param(wb, "Engine", "Bore",
                                                                     unit="in")))
    e = load_engine(p)
    assert e.params["bore"] == pytest.approx(86 * 0.0254)
    assert len(e.warnings) == 1
    w = e.warnings[0]
    assert w.where == cell["c"]
    assert "Bore 86 in (= 2184 mm) is outside the usual range 25..1000 mm" in w.message
    assert "check the value and its unit ('in')" in w.message


@pytest.mark.parametrize("sheet,label,value,unit,expect", [
    ("Engine", "Speed step", 1e-300, None, "Speed step 1e-300 rpm"),
    ("Engine", "Number of cylinders", 1e300, None, "Number of cylinders 1e+300 is outside 1..64"),
    ("Engine", "Bore", 1e300, None, "is outside 1..5000 mm"),
    ("Engine", "Stroke", 1e-300, None, "is outside 1..10000 mm"),
    ("Oil", "Oil supply temperature", -273, None, "is outside -40..250 °C"),
    ("Oil", "Oil supply temperature", 2000, "K", "(= 1727 °C) is outside -40..250 °C"),
    ("Engine", "Maximum speed", 1e12, None, "is outside 1..100000 rpm"),
])
def test_values_the_calculation_cannot_take_are_errors_with_cell(tmp_path, sheet, label,
                                                                 value, unit, expect):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_param(wb, sheet, label,
                                                                     value=value, unit=unit)))
    errs = _errors(p)
    mine = [e for e in errs if e.startswith(cell["c"] + ":")]
    assert mine and expect in mine[0], errs
    assert "the range the calculations can handle" in mine[0]


def test_table_cells_and_all_problems_together(tmp_path):
    def edit(wb):
        set_cell(wb, "Bearings", "name", "M2", "radial clearance", 22)  # 22 mm: error
        set_cell(wb, "TVModel", "station", "Flywheel", "inertia", 1e30)  # error
        set_cell(wb, "Joints", "name", "flywheel", "friction coefficient", 0.9)  # warning
        set_param(wb, "Engine", "Speed step", value=1e-300)  # error

    p = edited(tmp_path, edit)
    errs = _errors(p)
    assert len(errs) == 3, errs
    assert any(e.startswith("Bearings!F4:") and "22 mm" in e for e in errs)
    assert any(e.startswith("TVModel!D9:") for e in errs)


def test_usual_warning_from_table(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(
        wb, "Joints", "name", "flywheel", "friction coefficient", 0.9)))
    e = load_engine(p)
    assert [w.where for w in e.warnings] == [cell["c"]]
    assert "usual range 0.05..0.6" in e.warnings[0].message


def _numeric_fields():
    for sheet in SHEETS.values():
        if sheet.name == "Tolerances":
            continue  # min/max in each row's own unit: a bound is checked as the input it moves
        for f in sheet.fields:
            if f.kind not in ("text", "choice"):
                yield sheet.name, f


def test_every_number_has_a_valid_range_and_usual_lies_inside():
    """So no number of any magnitude (1e-300..1e300) reaches the calculations unchecked."""
    for sheet, f in _numeric_fields():
        assert isinstance(f.valid, Span), (sheet, f.label)
        assert f.valid.lo is not None and f.valid.hi is not None, (sheet, f.label)
        lo, hi = f.valid.si(f.kind)
        assert math.isfinite(lo) and math.isfinite(hi) and lo <= hi, (sheet, f.label)
        if f.check in (">0", ">=0", ">1", ">=1", "0..1"):
            assert lo >= 0, (sheet, f.label)
        if f.usual is not None:
            ulo, uhi = f.usual.si(f.kind)
            assert lo <= ulo <= uhi <= hi, (sheet, f.label)
        if f.kind not in ("int", "int_list", "dimensionless", "ratio"):
            assert f.valid.unit, (sheet, f.label)
            # the range's unit is one a user would write for this kind (it converts)
            to_si(1.0, f.valid.unit, f.kind)
            assert f.kind in KINDS


def test_span_text():
    assert Span(25, 1000, "mm").text() == "25..1000 mm"
    assert Span(None, 5, "bar").text() == "at most 5 bar"
    assert Span(0.3, None).text() == "at least 0.3"
    assert Span(-40, 250, "°C").si("temperature") == pytest.approx((233.15, 523.15))


def test_warnings_are_reported_with_the_errors(tmp_path):
    """A workbook with an error and an unusual value: one pass reports both (the warning is
    not lost behind the error)."""
    def edit(wb):
        set_param(wb, "Engine", "Bore", -5)
        set_param(wb, "Oil", "Oil supply temperature", 170)

    with pytest.raises(InputErrors) as exc:
        load_engine(edited(tmp_path, edit))
    text = str(exc.value)
    assert "1 problem in the input" in text and "Bore must be greater than zero" in text
    assert "and 1 warning:" in text and "Oil supply temperature 170 °C" in text
    assert [w.where for w in exc.value.warnings] == ["Oil!B4"]
