"""Typed results of the loads, flywheel and balance analyses (issue 24): every quantity carries
its declared detail type (no extras), the report sections render from those types alone, and a
hand-off with a missing field fails where the detail is made."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from checker import api
from checker.report.sections import fmt
from checker.results.balance import BalanceDetail, FreeOrderDetail
from checker.results.flywheel import FlywheelDetail
from checker.results.loads import BearingLoadDetail, CycleDetail, SpecificLoadDetail
from tests.helpers import example_path, stub_section_images

SECTIONS = ("loads", "flywheel", "balance")
FAMILY = ("loads.", "bearing.peak_specific_load", "flywheel.", "balance.")


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    return api.check(example_path(tmp_path_factory.mktemp("i4")))


def _render(res, monkeypatch) -> dict[str, dict]:
    import importlib

    stub_section_images(monkeypatch, SECTIONS)
    out = {}
    for m in SECTIONS:
        mod = importlib.import_module(f"checker.report.section_{m}")
        out[m] = getattr(mod, f"{m}_section")(res)
    return out


def test_family_quantities_carry_their_declared_types_and_no_extras(i4):
    q = i4.outcome.quantities
    mine = {n: x for n, x in q.items() if n.startswith(FAMILY)}
    assert {"loads.cycle", "loads.bearing_load", "bearing.peak_specific_load",
            "flywheel.cyclic_irregularity", "balance.free_force"} <= set(mine)
    for name, x in mine.items():
        assert x.spec.detail is not None and type(x.detail) is x.spec.detail, name
        assert not hasattr(x, "extra"), name
    assert isinstance(q["loads.cycle"].detail, CycleDetail)
    assert isinstance(q["loads.bearing_load"].detail, BearingLoadDetail)
    assert isinstance(q["bearing.peak_specific_load"].detail, SpecificLoadDetail)
    assert isinstance(q["flywheel.minimum_inertia"].detail, FlywheelDetail)
    assert isinstance(q["balance.free_moment"].detail, FreeOrderDetail)
    # applies_text moved from the extras to the quantity
    assert "lowest swept speed" in q["flywheel.cyclic_irregularity"].applies_text


def test_sections_render_from_the_typed_details(i4, monkeypatch):
    secs = _render(i4, monkeypatch)
    for m in SECTIONS:
        assert secs[m]["blocks"], m
    fly = secs["flywheel"]
    target = i4.outcome.quantities["flywheel.cyclic_irregularity"].detail.target
    assert f"δ ≤ {target * 100:g} %" in fly["intro"]
    inputs = fly["blocks"][0]["rows"]
    lowest = i4.outcome.quantities["flywheel.cyclic_irregularity"].detail.lowest_speed
    assert inputs[3][1] == fmt(lowest * 60 / (2 * np.pi), 5)


def test_a_changed_detail_changes_the_section(i4, monkeypatch):
    # the section reads the detail's fields, not a copy kept elsewhere
    q = i4.outcome.quantities["flywheel.cyclic_irregularity"]
    new = dataclasses.replace(q.detail, target=0.5)
    monkeypatch.setitem(i4.outcome.quantities, "flywheel.cyclic_irregularity",
                        dataclasses.replace(q, detail=new))
    assert "δ ≤ 50 %" in _render(i4, monkeypatch)["flywheel"]["intro"]


def test_a_missing_field_fails_where_the_detail_is_made():
    with pytest.raises(TypeError, match="fx"):
        BearingLoadDetail(theta=np.zeros(3), fy=np.zeros(3), omega_journal=np.zeros(3),
                          omega_bearing=np.zeros(3), frames={}, torque=np.zeros(3),
                          big_end_crank=None)
    with pytest.raises(TypeError):
        BalanceDetail(orders=np.arange(1, 3), omega=1.0)  # the masses missing
