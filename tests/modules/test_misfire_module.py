"""The misfire case in a check (module ``misfire``, rules MIS-).

The I6 example checked as an ``industrial`` engine: normal firing of the misfire node is the
torsion module's full-load response (the same model and excitation, solved anew: round-off);
a misfire adds the half orders the firing order cancels (Ker Wilson, vol. 2, ch. 19); the
worst cylinder is the one whose misfire gives the largest torque; the rules MIS- give results
for the classes the misfire case is judged for and are not applicable for the others.
"""

from __future__ import annotations

import numpy as np
import pytest

from checker import api
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content


def _content(cls: str):
    c = i6_content(damper_ring=True)
    c["Engine"] = [(r[0], cls, r[2], r[3]) if r[0] == "Engine class" else r
                   for r in c["Engine"]]
    return c


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    p = tmp_path_factory.mktemp("mis") / "i6.xlsx"
    write_workbook(p, _content("industrial"))
    return api.check(p)


def test_normal_firing_is_the_torsion_modules_full_load(result):
    q = result.outcome.quantities
    mis = q["misfire.element_torque"].detail
    el = q["tv.element_torque"]
    full = list(el.coords["case"]).index("full")
    np.testing.assert_allclose(mis.element_torque_normal, el.values[:, full], rtol=1e-9,
                               atol=1e-9 * el.values.max())


def test_misfire_excites_the_half_orders(result):
    q = result.outcome.quantities
    mis = q["misfire.element_torque"].detail
    el = q["tv.element_torque"].detail
    full = 0
    half = int(np.nonzero(mis.orders == 0.5)[0][0])
    e = len(mis.elements) - 1  # the element to the flywheel
    normal = np.abs(el.coeffs[e, full, :, half])
    worst = mis.worst_torque_orders[e, :, half]
    assert np.all(worst > 10 * normal)


def test_worst_cylinder_is_the_largest(result):
    q = result.outcome.quantities["misfire.element_torque"]
    d = q.detail
    np.testing.assert_array_equal(q.values, d.element_torque.max(axis=0))
    np.testing.assert_array_equal(d.worst_cylinder, d.element_torque.argmax(axis=0))
    inc = result.outcome.quantities["misfire.element_torque_increase"].values
    np.testing.assert_allclose(inc, q.values / d.element_torque_normal, rtol=1e-12)


def test_misfire_rules_by_class(result, tmp_path):
    got = {r.rule: r.status for r in result.results if r.rule.startswith("MIS-")}
    assert got["MIS-004"] in ("pass", "fail")  # the I6's viscous damper
    assert got["MIS-001"] == "not_applicable"  # no rubber damper
    p = tmp_path / "cv.xlsx"
    write_workbook(p, _content("commercial vehicle"))
    res = api.check(p)
    other = [r for r in res.results if r.rule.startswith("MIS-")]
    assert other and all(r.status == "not_applicable" for r in other)
    assert "misfire.element_torque" not in res.outcome.quantities


def test_motored_exponent_is_the_synthesis_exponent(result):
    d = result.outcome.quantities["misfire.element_torque"].detail
    # the I6's full-load traces are synthesized with the polytropic exponent 1.32
    np.testing.assert_allclose(d.motored_exponent, 1.32, rtol=1e-9)
    assert np.all(d.motored_peak < d.firing_peak)


def test_misfire_crank_stress_against_the_transient_limit_by_hand(result):
    q = result.outcome.quantities["misfire.crank_stress_ratio"]
    d = q.detail
    st = result.outcome.quantities["tv.crank_shear_stress"].detail
    mt = result.outcome.quantities["misfire.element_torque"]
    e = int(st.element_index[0])
    w = float(st.polar_modulus[0])
    # industrial (generator engine): 90 N/mm^2 x Y/225 at every speed (KR Pt 5 Ch 4 203.1(2))
    y = result.engine.fatigue.get("yield_strength")
    f2 = max(1.0, y / 225e6) if y is not None else 1.0
    hand = mt.values[e] / w / (90e6 * f2)
    np.testing.assert_allclose(q.values[0], hand, rtol=1e-12)
    assert d.engine_class == "industrial"
    rules = {r.status for r in result.results if r.rule == "MIS-005"}
    assert rules and rules <= {"pass", "fail"}
