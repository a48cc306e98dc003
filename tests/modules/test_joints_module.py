"""Joints module: the torsional model's torque next to a torque given in JointTorques
(quantities joint.computed_torque, joint.computed_cover_factor, joint.computed_torque_ratio and
the warning rule JNT-008), and which calculations each joint rule needs."""

from __future__ import annotations

import numpy as np
import pytest

from checker import api
from tests.helpers import analyses_run, edited, example_path, set_cell

# Ricardo 2013 (ENGDYN/VALDYN workshop) slide 23: crank-nose slip capacity 359.524 N m and the
# given peak torque 245 N m (cover factor 1.467); slide 24: flywheel capacity 2154.08 N m and
# 1216 N m (1.771).
SEED_CAPACITY = {"crank nose": 359.524, "flywheel": 2154.08}
SEED_GIVEN = {"crank nose": 245.0, "flywheel": 1216.0}




@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("joints"))


@pytest.fixture(scope="module")
def jnt(example):
    return api.check(example, select=["JNT"])


def _by(res):
    return {(r.rule, r.item): r for r in res.results}


def test_given_torque_stays_the_design_value(jnt):
    r = _by(jnt)
    # the cover-factor rules keep the seed's worked example (given torques)
    assert r[("JNT-003", "crank nose")].value == pytest.approx(359.524 / 245, abs=5e-4)
    assert r[("JNT-005", "flywheel")].value == pytest.approx(2154.08 / 1216, abs=5e-4)
    app = jnt.outcome.quantities["joint.applied_torque"]
    k = app.coords["point"].index("tv peak")
    assert list(app.values[:, k]) == [245.0, 1216.0]


def test_computed_torque_is_the_torsional_models(jnt):
    q = jnt.outcome.quantities
    comp, tv = q["joint.computed_torque"], q["tv.joint_torque"]
    # one source: the same numbers and operating-point speeds as the torsional module
    np.testing.assert_array_equal(comp.values, tv.values)
    np.testing.assert_array_equal(comp.detail.speed, tv.detail.speed)
    k = comp.coords["point"].index("tv peak")
    # the measurement on the example: about 317 N m at the crank nose (TV peak)
    assert comp.values[0, k] == pytest.approx(317.4, abs=0.5)
    # cover factor at the computed torque = capacity / computed torque (closed form, seed
    # capacities to their printed 6 digits)
    cf = q["joint.computed_cover_factor"]
    for i, n in enumerate(cf.coords["item"]):
        assert cf.values[i, k] == pytest.approx(SEED_CAPACITY[n] / comp.values[i, k], rel=2e-6)
    assert cf.values[0, k] == pytest.approx(1.132, abs=5e-4)


def test_jnt008_warns_with_the_cover_factor_at_the_computed_torque(jnt):
    r = _by(jnt)
    q = jnt.outcome.quantities
    comp = q["joint.computed_torque"]
    k = comp.coords["point"].index("tv peak")
    for i, n in enumerate(comp.coords["item"]):
        res = r[("JNT-008", n)]
        assert res.status == "fail" and res.severity == "warning"
        assert res.case == "tv peak"  # the only point the workbook gives
        assert res.value == pytest.approx(comp.values[i, k] / SEED_GIVEN[n], rel=1e-9)
        cf = q["joint.computed_cover_factor"].values[i, k]
        assert len(res.findings) == 1 and f"{cf:.4g}" in res.findings[0]
        assert f"{SEED_GIVEN[n]:.0f} N m given" in res.findings[0]
    # the points the workbook does not give are not judged (the rules use the computed torque)
    ratio = q["joint.computed_torque_ratio"]
    assert ratio.applies is not None
    assert list(ratio.applies[:, k]) == [True, True] and not ratio.applies[:, k + 1:].any()
    assert "JointTorques" in ratio.applies_text


def test_jnt008_passes_when_the_given_torque_is_not_below(tmp_path):
    def edit(wb):
        set_cell(wb, "JointTorques", "joint", "crank nose", "applied torque", 400)

    r = _by(api.check(edited(tmp_path, edit), select=["JNT-008"]))
    assert r[("JNT-008", "crank nose")].status == "pass"
    assert r[("JNT-008", "crank nose")].findings == []
    assert r[("JNT-008", "flywheel")].status == "fail"


def test_torsion_is_planned_only_for_jnt008_when_all_torques_are_given(tmp_path):
    def edit(wb):
        ws = wb["JointTorques"]
        for joint, point, speed, torque in (("crank nose", "max power", 5500, 250),
                                            ("crank nose", "overspeed", 7000, 240),
                                            ("flywheel", "max power", 5500, 1200),
                                            ("flywheel", "overspeed", 7000, 1100)):
            ws.append([joint, point, speed, torque, "test"])

    path = edited(tmp_path, edit)
    for sel in (["JNT-001"], ["JNT-003"], ["JNT-007"]):
        assert analyses_run(api.check(path, select=sel).outcome) == ["joints"], sel
    assert analyses_run(api.check(path, select=["JNT"], ignore=["JNT-008"]).outcome) == [
        "joints"]
    res = api.check(path, select=["JNT"])
    assert analyses_run(res.outcome) == ["loads", "torsion", "joints"]
    # every point is given now: all of them are judged
    assert _by(res)[("JNT-008", "flywheel")].status == "fail"
    assert res.outcome.quantities["joint.computed_torque_ratio"].applies.all()


def test_jnt008_not_evaluated_without_a_torsional_model(tmp_path):
    def edit(wb):
        ws = wb["TVModel"]
        ws.delete_rows(3, ws.max_row)

    r = _by(api.check(edited(tmp_path, edit), select=["JNT"]))
    assert r[("JNT-003", "crank nose")].value == pytest.approx(1.467, abs=5e-4)
    res = r[("JNT-008", "crank nose")]
    assert res.status == "not_evaluated" and any("TVModel" in m for m in res.missing)


def test_typed_details_and_the_report_section(jnt):
    """The joint quantities carry their declared detail types and the report section renders
    from them (display units of the quantities, how each value was obtained)."""
    from checker.report.sections import build_sections, fmt
    from checker.results.joints import (
        AppliedTorqueDetail,
        ComputedTorqueDetail,
        JointBoltsDetail,
    )

    q = jnt.outcome.quantities
    assert isinstance(q["joint.preload"].detail, JointBoltsDetail)
    assert q["joint.stress_area"].detail is q["joint.slip_capacity"].detail  # one per node
    assert isinstance(q["joint.applied_torque"].detail, AppliedTorqueDetail)
    assert isinstance(q["joint.cover_factor"].detail, AppliedTorqueDetail)
    for name in ("joint.computed_torque", "joint.computed_cover_factor",
                 "joint.computed_torque_ratio"):
        assert isinstance(q[name].detail, ComputedTorqueDetail)
    sec = {s["id"]: s for s in build_sections(jnt)}["joints"]
    table = next(b for b in sec["blocks"] if b["type"] == "table"
                 and b["caption"].startswith("Bolt and face"))
    rows = {r[0]: r[1:] for r in table["rows"]}
    area = q["joint.stress_area"].values
    assert rows["Stress area A_s [mm²]"] == [fmt(a * 1e6) for a in area]
    assert rows["Slip torque capacity T_cap [N·m]"][0] == fmt(SEED_CAPACITY["crank nose"])
    assert rows["Bolt stress / proof stress [%]"] == [
        fmt(v * 100) for v in q["joint.proof_stress_ratio"].values]
    how = next(b for b in sec["blocks"] if b["type"] == "list")["items"]
    assert how[0].startswith("crank nose: stress area: A_s = pi/4")
