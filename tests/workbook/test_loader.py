"""Bad workbooks: every case gives exit 2, names sheet and cell, writes nothing, and leaves the
input untouched; all problems of one workbook are reported together."""

from __future__ import annotations

import hashlib

import openpyxl
import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.description.engine import load_engine
from checker.errors import InputErrors
from tests.helpers import edited, example_path, param_row, set_cell, set_param


def _run_bad(path, tmp_path, *extra):
    """Run report and check on a bad workbook; return the stderr text of the report run."""
    before = hashlib.sha256(path.read_bytes()).hexdigest()
    out_pdf = tmp_path / "out.pdf"
    runner = CliRunner()
    r = runner.invoke(main, ["report", str(path), "-o", str(out_pdf), "--html",
                             str(tmp_path / "out.html"), *extra])
    assert r.exit_code == 2, r.output
    assert "Traceback" not in r.output
    assert not out_pdf.exists() and not (tmp_path / "out.html").exists()
    assert not list(tmp_path.glob(".checker-*"))
    r2 = runner.invoke(main, ["check", str(path), "--format", "json"])
    assert r2.exit_code == 2
    assert r2.stdout == ""  # nothing on stdout for a JSON consumer
    assert hashlib.sha256(path.read_bytes()).hexdigest() == before
    return r.stderr


def test_example_reads_cleanly(tmp_path):
    e = load_engine(example_path(tmp_path))
    assert e.params["bore"] == pytest.approx(0.086)
    assert e.params["rod_inertia"] == pytest.approx(0.002128)
    assert e.oil["supply_temperature"] == pytest.approx(403.15)
    assert e.oil["supply_pressure"] == pytest.approx(4e5)  # gauge parameter, bar(g)
    assert len(e.bearings) == 9 and len(e.cylinders) == 4 and len(e.crank_mass) == 20
    assert [c.number for c in sorted(e.cylinders, key=lambda c: c.firing_angle)] == [1, 3, 4, 2]
    assert len(e.tv_model) == 7 and e.tv_model[-1].role == "flywheel"
    assert {(t.joint, t.point) for t in e.joint_torques} == {("crank nose", "tv peak"),
                                                              ("flywheel", "tv peak")}
    assert any("Compression ratio" in a for a in e.assumptions)


def test_missing_required_value(tmp_path):
    p = edited(tmp_path, lambda wb: set_param(wb, "Engine", "Bore", value=""))
    r = p  # noqa
    ws = openpyxl.load_workbook(p)["Engine"]
    cell = f"Engine!B{param_row(ws, 'Bore')}"
    err = _run_bad(p, tmp_path)
    assert cell in err and "Bore is required" in err and "length" in err


def test_text_in_number_cell(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_param(wb, "Engine", "Stroke",
                                                                     value="ninety")))
    err = _run_bad(p, tmp_path)
    assert cell["c"] in err and "text 'ninety'" in err and "length" in err


def test_decimal_comma_hint(tmp_path):
    p = edited(tmp_path, lambda wb: set_param(wb, "Engine", "Stroke", value="94,6"))
    assert "decimal point" in _run_bad(p, tmp_path)


def test_wrong_unit(tmp_path):
    cell = {}

    def edit(wb):
        ws = wb["PeakPressure"]
        ws.cell(2, 3).value = "mm"  # peak pressure column unit
        cell["c"] = "PeakPressure!C2"  # the unit cell, once (issue 43, item 10)

    p = edited(tmp_path, edit)
    err = _run_bad(p, tmp_path)
    assert cell["c"] in err and "expected a pressure" in err and "'mm'" in err
    assert err.count("'mm'") == 1 and "PeakPressure!C3" not in err


def test_unknown_unit(tmp_path):
    p = edited(tmp_path, lambda wb: set_param(wb, "Engine", "Bore", unit="smoots"))
    err = _run_bad(p, tmp_path)
    assert "unknown unit 'smoots'" in err


def test_formula_without_cached_value(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault(
        "c", set_param(wb, "Engine", "Stroke", value="=2*47.3")))
    err = _run_bad(p, tmp_path)
    assert cell["c"] in err and "formula" in err and "no stored result" in err


def test_negative_clearance(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault(
        "c", set_cell(wb, "Bearings", "name", "M3", "radial clearance", -0.022)))
    err = _run_bad(p, tmp_path)
    assert cell["c"] in err and "greater than zero" in err


def test_inner_radius_not_below_outer(tmp_path):
    def edit(wb):
        set_param(wb, "Damper", "Rubber inner radius", value=60)
        set_cell(wb, "Joints", "name", "crank nose", "head bearing inner diameter", 30)

    p = edited(tmp_path, edit)
    err = _run_bad(p, tmp_path)
    assert "inner radius 60 mm must be smaller" in err and "Damper!B" in err
    assert "inner diameter 30 mm must be smaller" in err and "Joints!O3" in err


def test_duplicate_names(tmp_path):
    p = edited(tmp_path, lambda wb: set_cell(wb, "Bearings", "name", "M2", "name", "M1"))
    err = _run_bad(p, tmp_path)
    assert "duplicate name 'M1'" in err and "Bearings!A4" in err


def test_missing_and_unknown_sheet(tmp_path):
    def edit(wb):
        del wb["Engine"]
        wb.create_sheet("Foo")

    p = edited(tmp_path, edit)
    err = _run_bad(p, tmp_path)
    assert "required sheet 'Engine' is missing" in err
    assert "unknown sheet 'Foo'" in err


def test_not_a_workbook(tmp_path):
    p = tmp_path / "engine.xlsx"
    p.write_text("this is not a spreadsheet")
    err = _run_bad(p, tmp_path)
    assert "not an Excel .xlsx workbook" in err


def test_percent_formatted_cell(tmp_path):
    def edit(wb):
        ws = wb["Joints"]
        c = ws["K4"]  # preload fraction of the flywheel
        c.value = 0.75
        c.number_format = "0%"
        ws["K2"].value = "%"

    p = edited(tmp_path, edit)
    e = load_engine(p)  # a cell shown as 75 % with unit % is the fraction 0.75
    assert e.joints[1].preload_fraction == pytest.approx(0.75)

    def edit_bad(wb):
        ws = wb["Engine"]
        r = param_row(ws, "Bore")
        ws.cell(r, 2).number_format = "0%"

    p2 = edited(tmp_path, edit_bad, "bad.xlsx")
    assert "percent-formatted" in _run_bad(p2, tmp_path)


def test_all_problems_reported_together(tmp_path):
    def edit(wb):
        set_param(wb, "Engine", "Bore", value="x")
        set_param(wb, "Engine", "Stroke", unit="bar")
        set_cell(wb, "Bearings", "name", "BE1", "radial clearance", 0)
        set_cell(wb, "Joints", "name", "flywheel", "face inner diameter", 90)
        wb.create_sheet("Scratch")

    p = edited(tmp_path, edit)
    with pytest.raises(InputErrors) as info:
        load_engine(p)
    assert len(info.value.errors) == 5
    err = _run_bad(p, tmp_path)
    assert "5 problems in the input" in err


def test_merged_cells_refused(tmp_path):
    p = edited(tmp_path, lambda wb: wb["Bearings"].merge_cells("A3:A4"))
    assert "merged cells" in _run_bad(p, tmp_path)


def test_unknown_parameter_and_column(tmp_path):
    def edit(wb):
        ws = wb["Engine"]
        ws.cell(ws.max_row + 1, 1).value = "Number of turbos"
        wb["Joints"].cell(1, 30).value = "thread angle"

    err = _run_bad(edited(tmp_path, edit), tmp_path)
    assert "unknown parameter 'Number of turbos'" in err and "unknown column 'thread angle'" in err


def test_firing_order_inconsistent(tmp_path):
    p = edited(tmp_path, lambda wb: set_param(wb, "Engine", "Firing order", value="1-2-4-3"))
    err = _run_bad(p, tmp_path)
    assert "firing order" in err and "1-3-4-2" in err


def test_unknown_joint_in_torques(tmp_path):
    def edit(wb):
        wb["JointTorques"]["A3"].value = "pulley"

    assert "joint 'pulley' is not in sheet Joints" in _run_bad(edited(tmp_path, edit), tmp_path)


def test_workbook_docs_are_current():
    from pathlib import Path

    from checker.workbook.docs import workbook_markdown

    doc = Path(__file__).resolve().parents[2] / "docs" / "workbook.md"
    assert doc.read_text() == workbook_markdown(), "run: python -m checker.workbook.docs"
