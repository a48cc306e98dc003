"""The verdict at the tolerance corners (checker.remedies.corners): worst corners known by hand
(VDI 2230 preload scatter of the crank-nose joint; the film thickness at maximum clearance
and hottest oil) and a response that is not monotonic (worst point inside the box)."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from checker import api
from checker.errors import InputErrors
from checker.evaluation.ruletable import load_rules
from checker.remedies.corners import Tolerance, evaluate_corners, read_tolerances
from checker.remedies.variants import Evaluator
from checker.workbook.loader import read_raw_workbook


def _workbook(path, tolerances, speed_step=None):
    from checker.workbook import example

    content = example.example_content()
    if speed_step is not None:
        content["Engine"] = [(p, speed_step, u, n) if p == "Speed step" else (p, v, u, n)
                             for p, v, u, n in content["Engine"]]
    cols, _ = content["Tolerances"]
    content["Tolerances"] = (cols, tolerances)
    example.write_workbook(path, content)
    return path


def _run(path, select, ignore=None):
    table = load_rules()
    ev = Evaluator(read_raw_workbook(path), table, select=select, ignore=ignore)
    nom = api.check(path, select=select, ignore=ignore, cache=ev.cache)
    tols = read_tolerances(ev.base)
    return nom, {(c.rule, c.item): c for c in evaluate_corners(nom, ev, tols)}, tols


def test_joint_preload_scatter_worst_corners_by_hand(tmp_path):
    alpha = 1.6  # VDI 2230 tightening factor, torque wrench
    p = _workbook(tmp_path / "j.xlsx", [
        ["Joints", "crank nose", "tightening factor", None, alpha, "-", "VDI 2230"],
        ["Joints", "crank nose", "friction coefficient", 0.15, 0.25, "-", "test"]])
    nom, c, tols = _run(p, ["JNT-001", "JNT-002", "JNT-003"])
    t_max = 400 * 2 * alpha / (1 + alpha)  # F_max / F_min = alpha around today's preload
    t_min = 400 * 2 / (1 + alpha)
    assert tols[0].high == pytest.approx(t_max) and tols[0].low == pytest.approx(t_min)
    v = {r.rule: r.value for r in nom.results if r.item == "crank nose"}
    # proof stress and head contact at maximum preload; friction does not enter
    assert c[("JNT-001", "crank nose")].worst_value == pytest.approx(
        v["JNT-001"] * t_max / 400, rel=1e-9)
    assert c[("JNT-001", "crank nose")].corner == [tols[0].end_text(1.0)]
    assert c[("JNT-002", "crank nose")].worst_value == pytest.approx(
        v["JNT-002"] * t_max / 400, rel=1e-9)
    # slip (cover factor) at minimum preload and minimum friction
    cf = c[("JNT-003", "crank nose")]
    assert cf.worst_value == pytest.approx(v["JNT-003"] * t_min / 400 * 0.15 / 0.2, rel=1e-9)
    assert cf.corner == [tols[0].end_text(0.0), tols[1].end_text(0.0)]
    assert cf.worst_status == "fail" and not cf.inside
    assert cf.design == "all 4 corners of 2 tolerances"


def test_film_thickness_worst_at_max_clearance_and_hottest_oil(tmp_path):
    p = _workbook(tmp_path / "b.xlsx", [
        ["Bearings", "M1", "radial clearance", 17, 27, "um", "test"],
        ["Oil", "", "Oil supply temperature", 120, 140, "°C", "test"]], speed_step=3000)
    nom, c, tols = _run(p, ["BRG-003"])
    m1 = c[("BRG-003", "M1")]
    assert m1.corner == [tols[0].end_text(1.0), tols[1].end_text(1.0)]
    assert m1.worst_value < m1.nominal_value
    assert not m1.inside
    # the other bearings see the oil temperature only: hottest oil
    m2 = c[("BRG-003", "M2")]
    assert m2.corner == [tols[1].end_text(1.0)]
    assert m2.design == "all 2 corners of 1 tolerances"


def test_bad_tolerance_rows_name_their_cells(tmp_path):
    p = _workbook(tmp_path / "bad.xlsx", [
        ["Bearings", "M9", "radial clearance", 17, 27, "um", ""],
        ["Oil", "", "Oil supply temperature", 150, 120, "°C", ""],
        ["Nowhere", "", "x", 1, 2, "-", ""]])
    with pytest.raises(InputErrors) as exc:
        read_tolerances(read_raw_workbook(p))
    text = str(exc.value)
    assert "Tolerances!B3" in text and "M9" in text
    assert "Tolerances!D4" in text
    assert "Tolerances!A5" in text


def test_a_text_range_names_the_rows_unit(tmp_path):
    """min and max take their unit from the row's unit column: the message says so (not
    'dimensionless'); the command exits 2 with no report."""
    from click.testing import CliRunner

    from checker.cli import main

    p = _workbook(tmp_path / "text.xlsx", [
        ["Bearings", "M1", "radial clearance", "abc", 27, "um", ""]])
    out = tmp_path / "r.pdf"
    r = CliRunner().invoke(main, ["report", str(p), "--corners", "-o", str(out)])
    assert r.exit_code == 2
    assert "Tolerances!D3" in r.output
    assert "expected a number in the row's unit (column 'unit'), found text 'abc'" in r.output
    assert "dimensionless" not in r.output
    assert not out.exists()


# ------------------------------------------------- a response that is not monotonic (closed form)
@dataclass
class _R:
    rule: str
    item: str
    value: float
    margin: float
    status: str
    unit: str = ""
    severity: str = "error"


class _Res:
    def __init__(self, results):
        self.results = results


class _Bind:
    def __init__(self, k):
        self.k = k
        self.labels = (f"X{k}",)

    def changes(self, v):
        return {("S", self.k, 1): v}


class _Ev:
    """Margin m(x, y) = (x - 0.4)^2 + 0.01 (y - 1) on the box [0, 1]^2 (nominal 0.5, 0.5):
    its worst point is inside the box at x = 0.4, y = 0 (m = -0.01), while the worst corner
    is x = 0 or 1 ... at y = 0 with m = 0.15."""

    def __init__(self):
        self.evaluations = 0

    def evaluate_variants(self, changes, select=None):
        out = []
        for ch in changes:
            x = ch.get(("S", 0, 1), 0.5)
            y = ch.get(("S", 1, 1), 0.5)
            m = (x - 0.4) ** 2 + 0.01 * (y - 1.0)
            out.append(_Res([_R("TST-001", "all", m, m, "pass" if m >= 0 else "fail")]))
            self.evaluations += 1
        return out


def test_worst_point_inside_the_box_is_found():
    tols = [Tolerance("x", "T!A3", _Bind(0), 0.0, 1.0, 0.5),
            Tolerance("y", "T!A4", _Bind(1), 0.0, 1.0, 0.5)]
    ev = _Ev()
    nominal = ev.evaluate_variants([{}])[0]
    c = evaluate_corners(nominal, ev, tols)[0]
    assert c.inside
    assert c.worst_margin == pytest.approx(-0.01, abs=2e-3)
    assert c.worst_status == "fail"  # passes at nominal and at every corner, fails inside
    assert nominal.results[0].status == "pass"
    u = c._u
    assert u[0] == pytest.approx(0.4, abs=0.05) and u[1] == 0.0
    # every corner passes: the corners alone would have missed it
    corners = ev.evaluate_variants([{("S", 0, 1): a, ("S", 1, 1): b}
                                    for a in (0.0, 1.0) for b in (0.0, 1.0)])
    assert all(r.results[0].status == "pass" for r in corners)
