"""Crank-nose fatigue check (FAT-003) on the example engine with nose data added."""

from __future__ import annotations

import numpy as np
import pytest

from checker import api
from checker.results.crank_nose import CrankNoseDetail
from tests.helpers import edited, example_path


def _add_nose(wb, belt=True):
    ws = wb["Fatigue"]
    rows = [("Crank nose diameter", 32, "mm"), ("Crank nose stress concentration bending", 1.9,
            "-"), ("Crank nose stress concentration torsion", 1.4, "-"),
            ("Crank nose fatigue strength", 420, "MPa")]
    if belt:
        rows += [("Belt load on crank nose", 2.5, "kN"), ("Belt load overhang", 35, "mm")]
    labels = {str(c.value).strip().lower(): c.row for c in ws["A"] if c.value}
    for r in rows:  # the template has the nose rows blank: fill them, append the others
        if r[0].lower() in labels:
            for j, v in enumerate([*r, "test data"], start=1):
                ws.cell(labels[r[0].lower()], j).value = v
        else:
            ws.append([*r, "test data"])


def test_not_evaluated_without_nose_data(tmp_path):
    res = api.check(example_path(tmp_path), select=["FAT-003"])
    [r] = res.results
    assert r.status == "not_evaluated" and any("Crank nose diameter" in m for m in r.missing)


def test_nose_safety_factor_hand_check(tmp_path):
    res = api.check(edited(tmp_path, _add_nose), select=["FAT-003"])
    [r] = res.results
    assert r.status in ("pass", "fail") and r.case
    q = res.outcome.quantities["fatigue.nose_goodman_sf"]
    ex = q.detail
    assert isinstance(ex, CrankNoseDetail)
    ci, si = 0, 30
    d = 0.032
    wb_, wp = np.pi * d**3 / 32, np.pi * d**3 / 16
    tmax, tmin = ex.torque_max[ci, si], ex.torque_min[ci, si]
    sa = 1.9 * 2500 * 0.035 / wb_
    ta, tm = 1.4 * (tmax - tmin) / 2 / wp, 1.4 * (tmax + tmin) / 2 / wp
    sf = 1 / (np.sqrt(sa**2 + 3 * ta**2) / 420e6 + np.sqrt(3) * abs(tm) / 750e6)
    assert q.values[ci, si] == pytest.approx(sf, rel=1e-9)
    # the nose carries the accessory drive torque: the mean torque is about -19 N m (seed FEAD)
    tv = res.outcome.quantities["tv.element_torque"]
    k = tv.coords["item"].index(ex.element)
    assert tv.detail.mean[k] == pytest.approx(-19.0, abs=1e-6)


def test_without_belt_load_torsion_only_is_stated(tmp_path):
    res = api.check(edited(tmp_path, lambda wb: _add_nose(wb, belt=False)), select=["FAT-003"])
    assert any("torsion only" in a for a in res.assumptions)
