"""Crank mass data that contradict themselves are caught for every user: a centre of mass
axially outside its component (a lateral coordinate entered in X instead of Z) is a warning
with its cell; a resultant unbalance of the rotating masses in a layout that is balanced by
its symmetry is a finding and fails BAL-006 (checker.description.engine.check_mass_planes,
checker.modules.balance)."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from checker import api
from checker.description.engine import load_engine
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import THROW_ANGLES, i6_content
from tests.helpers import edited, example_path

RPM = 2 * math.pi / 60


def _i6_as_first_shipped() -> dict:
    """The I6 workbook with the crank-mass data of its first version: lateral coordinates in
    the axial offset X (Z = 0) and every counterweight directly opposite its own throw."""
    content = copy.deepcopy(i6_content())
    cols, rows = content["CrankMass"]
    for r in rows:
        _loc, throw, kind, _m, _x, y, z = r[:7]
        if kind == "counterweight":
            g = math.radians(THROW_ANGLES[throw])
            z, y = round(-58.0 * math.sin(g), 3) + 0.0, round(-58.0 * math.cos(g), 3) + 0.0
        r[4], r[5], r[6] = z, y, 0
    return content


@pytest.fixture(scope="module")
def bad_i6(tmp_path_factory):
    p = tmp_path_factory.mktemp("badi6") / "i6-old.xlsx"
    write_workbook(p, _i6_as_first_shipped())
    return p


@pytest.fixture(scope="module")
def good_i6(tmp_path_factory):
    p = tmp_path_factory.mktemp("goodi6") / "i6.xlsx"
    write_workbook(p, i6_content())
    return p


def test_centre_of_mass_outside_the_web_is_a_warning_with_cell(bad_i6):
    e = load_engine(bad_i6)
    warns = [w for w in e.warnings if w.where.startswith("CrankMass!E")]
    # the 8 webs of throws 2-5 (|X| = 37.7 sin 120 = 32.649 mm) and the 4 counterweights of
    # throws 3 and 4 (58 sin 120 = 50.229 mm) lie beyond 12.5 mm (half the 25 mm web, Fatigue
    # sheet); throws 1 and 6 and the counterweight-free throws 2 and 5 have none there
    by_cell = {w.where: w.message for w in warns}
    assert len(warns) == 8 + 4
    assert "CrankMass!E8" in by_cell  # Web3 (throw 2, first row of throw 2)
    msg = by_cell["CrankMass!E8"]
    assert "X = -32.65 mm puts the centre of mass of 'Web3' axially outside the web" in msg
    assert "half the web thickness 25 mm (Crank!F3)" in msg
    assert "belongs in Z" in msg


def test_consistent_data_give_no_warning(good_i6, tmp_path):
    assert not [w for w in load_engine(good_i6).warnings if w.where.startswith("CrankMass")]
    # the seed's I4: X = +-1.46 / 0.541 mm inside its 22.3 mm webs
    assert not [w for w in load_engine(example_path(tmp_path)).warnings
                if w.where.startswith("CrankMass")]


def test_bound_without_web_thickness_is_a_fraction_of_the_spacing(tmp_path):
    # I4 example without web thicknesses (nor sheet Crank, which gives the web's): the bound
    # is 15 % of the 96 mm main spacing = 14.4 mm
    def edit(x):
        def apply(wb):
            del wb["Crank"]
            for row in wb["Bearings"].iter_rows(min_row=3):
                row[2].value = 55.0 if row[1].value == "main" else 48.0
            for row in wb["Fatigue"].iter_rows(min_row=2):
                if row[0].value in ("Web reduced thickness", "Web full thickness"):
                    row[1].value = None
            wb["CrankMass"]["E3"].value = x  # Web1 X
        return apply

    e = load_engine(edited(tmp_path, edit(15.0)))
    w = [x for x in e.warnings if x.where == "CrankMass!E3"]
    assert len(w) == 1 and "15 % of the main journal spacing" in w[0].message
    e2 = load_engine(edited(tmp_path, edit(14.0), name="inside.xlsx"))
    assert not [x for x in e2.warnings if x.where == "CrankMass!E3"]


def test_unbalanced_crank_in_a_balanced_layout_fails_bal006_with_a_finding(bad_i6):
    res = api.check(bad_i6, select=["BAL"])
    by = {(r.rule, r.item): r for r in res.results}
    q = res.outcome.quantities["balance.crank_unbalance"]
    # by hand: with the lateral coordinates in X only the Y components act; webs: 2 x 2.2 kg
    # x 37.7 mm x (1 + 1 - 1/2 x 4) = 0 over the six throws, pins and rods cancel, and the
    # counterweights on throws 1, 3, 4, 6 leave 2 x 1.65 kg x 58 mm x (-2 + 1/2 x 2) =
    # -0.1914 kg m along Y (as the issue states: about 0.19 kg m, 10 kN at 2200 rpm)
    u = q.detail.throw_unbalance
    static = np.hypot(*q.detail.static_vector)
    assert static == pytest.approx(0.1914, abs=5e-4)
    assert q.values[0] == pytest.approx(static / u)
    r = by[("BAL-006", "static")]
    assert r.status == "fail" and r.severity == "warning"
    assert r.findings and "static unbalance of 0.1914 kg m (10.2 kN at 2200 rpm)" in \
        r.findings[0]
    assert by[("BAL-006", "dynamic")].status == "fail"
    # the same finding is on the 1st-order free force
    f1 = res.outcome.quantities["balance.free_force"]
    assert any("static unbalance" in t for t in f1.findings[(0,)])


def test_balanced_crank_passes_bal006(good_i6):
    res = api.check(good_i6, select=["BAL-006"])
    assert {(r.item, r.status) for r in res.results} == {("static", "pass"), ("dynamic", "pass")}
    q = res.outcome.quantities["balance.crank_unbalance"]
    assert np.all(q.values < 1e-5) and not q.findings
