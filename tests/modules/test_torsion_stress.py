"""Crank vibratory stress (tv.crank_shear_stress) and the class rules on it (TV-004..TV-009),
worked by hand from the quantities they are built of, on the I6 example (Mendes et al. 2008)
with its engine class set to each class; FAT-002's torsional stress from the whole dynamic
system (IACS UR M53 2.2(A)(f)).

Independent numbers: W_P = pi D^3/16 of the I6's crank pin (Bearings, D = 62.97 mm), the
Korean Register's formulas (Pt 5 Ch 4 201.1, 201.4, 203.1, 204, 206.1(1)) evaluated here
directly, the critical speed n_c = 60 f / q of the first natural frequency. Tolerances:
float round-off (1e-9 relative) unless stated."""

from __future__ import annotations

import numpy as np
import openpyxl
import pytest

from checker import api
from checker.modules import torsion_stress as tvs
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content
from tests.helpers import column, set_param, table_row

RPM = 2 * np.pi / 60
NEW = ("TV-004", "TV-005", "TV-006", "TV-007", "TV-008", "TV-009")
F_M = 1.0 + 2.0 / 3.0 * (590.0 / 440.0 - 1.0)  # KR 201.4(1), the I6's 950 MPa capped at 590


def _i6(tmp_path, name, edit=None):
    p = tmp_path / f"{name}.xlsx"
    write_workbook(p, i6_content(damper_ring=True))
    if edit is not None:
        wb = openpyxl.load_workbook(p)
        edit(wb)
        wb.save(p)
    return p


def _class(cls):
    def edit(wb):
        set_param(wb, "Engine", "Engine class", cls)
    return edit


def _with_generator(wb):
    """A flexible coupling (200 kN m/rad) and a generator rotor (3 kg m^2) behind the
    flywheel: the complete dynamic system of a genset."""
    ws = wb["TVModel"]
    r = table_row(ws, "station", "Flywheel")
    ws.cell(r, column(ws, "stiffness to next")).value = 2.0e5
    ws.cell(r, column(ws, "damping to next")).value = 100.0
    new = ws.max_row + 1
    for name, value in (("station", "Generator"), ("role", "other"), ("inertia", 3.0)):
        ws.cell(new, column(ws, name)).value = value


@pytest.fixture(scope="module")
def marine(tmp_path_factory):
    p = _i6(tmp_path_factory.mktemp("cls"), "marine", _class("marine"))
    return api.check(p, select=["TV", "FAT-002"])


@pytest.fixture(scope="module")
def genset(tmp_path_factory):
    p = _i6(tmp_path_factory.mktemp("cls"), "genset", _class("industrial"))
    return api.check(p, select=["TV"])


def test_stress_is_element_torque_over_the_pin_modulus(marine):
    q = marine.outcome.quantities
    st, et = q["tv.crank_shear_stress"], q["tv.element_torque"]
    # the crank sections: crank nose (Pulley) to Flywheel; the damper's element is not one
    assert st.coords["item"] == [n for n in et.coords["item"] if not n.startswith("Damper")]
    w = np.pi * 0.06297**3 / 16.0  # the pin (62.97 mm) is smaller than the journal (85 mm)
    rows = [list(et.coords["item"]).index(n) for n in st.coords["item"]]
    np.testing.assert_allclose(st.values, et.values[rows] / w, rtol=1e-9)
    np.testing.assert_allclose(st.detail.order_stress, np.abs(et.detail.coeffs[rows]) / w,
                               rtol=1e-9)
    per_q = q["tv.crank_order_shear_stress"]
    np.testing.assert_allclose(per_q.values, np.moveaxis(np.abs(et.detail.coeffs[rows]) / w,
                                                         -1, 0), rtol=1e-9)
    assert set(st.detail.section) == {"crank pin"}
    # synthesis bounds: the half range lies between the largest order and the sum of orders
    per = st.detail.order_stress
    assert np.all(st.values <= per.sum(-1) * (1 + 1e-6))
    assert np.all(st.values >= per.max(-1) * (1 - 1e-2))


def test_marine_ratios_by_hand(marine):
    q = marine.outcome.quantities
    st = q["tv.crank_shear_stress"]
    sp = np.asarray(st.coords["speed"])
    lam = sp / (2200 * RPM)
    cont = q["tv.crank_stress_ratio_continuous"]
    cols = np.flatnonzero((lam >= 0.8 - 1e-9) & (lam <= 1.0 + 1e-9))
    assert np.allclose(cont.coords["speed"], sp[cols])
    tau1 = F_M * (45.0 - 24.0 * lam[cols] ** 2) * 1e6  # in-line four-stroke: group A
    np.testing.assert_allclose(cont.values, st.values[:, :, cols] / tau1, rtol=1e-9)
    tr = q["tv.crank_stress_ratio_transient"]
    cols = np.flatnonzero(lam <= 0.8 + 1e-9)
    tau2 = 2.0 * (45.0 - 24.0 * lam[cols] ** 2) * 700.0 / 225.0 * 1e6  # Y = 700 MPa
    np.testing.assert_allclose(tr.values, st.values[:, :, cols] / tau2, rtol=1e-9)
    ov = q["tv.crank_stress_ratio_overspeed"]
    cols = np.flatnonzero((lam > 1.0 + 1e-9) & (lam <= 1.15 + 1e-9))
    x = lam[cols]
    tau3 = F_M * (21.0 + 237.0 * (x - 0.8) * np.sqrt(x - 1.0)) * 1e6
    np.testing.assert_allclose(ov.values, st.values[:, :, cols] / tau3, rtol=1e-9)
    by = {(r.rule, r.item): r for r in marine.results}
    worst = max(cont.values[0][np.asarray(cont.applies[0])])
    assert by[("TV-004", "Pulley -> Gear train")].value == pytest.approx(worst, rel=1e-6)
    assert by[("TV-009", "all")].status == "not_applicable"


def test_barred_ranges_follow_the_rule(marine):
    q = marine.outcome.quantities
    b = q["tv.barred_speed_range"]
    d = b.detail
    rated = 2200 * RPM
    assert b.values.size >= 1  # the I6 exceeds tau_1 near its rated speed
    lam = d.critical_speed / rated
    np.testing.assert_allclose(d.rule_lower, 16 * d.critical_speed / (18 - lam), rtol=1e-12)
    np.testing.assert_allclose(d.rule_upper, (18 - lam) * d.critical_speed / 16, rtol=1e-12)
    # widened to the whole run of speeds above tau_1: the I6 exceeds it from the lowest
    # full-load speed (1000 rpm) on
    np.testing.assert_allclose(d.lower, np.minimum(d.rule_lower, d.run_lower), rtol=1e-12)
    np.testing.assert_allclose(d.upper, np.maximum(d.rule_upper, d.run_upper), rtol=1e-12)
    assert d.lower.min() == pytest.approx(1000 * RPM)
    np.testing.assert_allclose(b.values, d.upper / rated, rtol=1e-12)
    assert np.all(d.peak_stress > d.peak_limit)
    r = next(r for r in marine.results if r.rule == "TV-007")
    assert r.status == "fail" and r.value > 0.8


def test_major_criticals_by_hand(marine, genset):
    for res, band in ((marine, (0.8, 1.1)), (genset, (0.9, 1.1))):
        q = res.outcome.quantities
        f1 = q["tv.natural_frequency"].values[0]
        m = q["tv.major_critical_clearance"]
        orders = [float(x.split()[1].rstrip(",")) for x in m.coords["item"]]
        assert orders[:3] == [3.0, 6.0, 9.0]  # a six-cylinder four-stroke: k n/2
        lam = 60 * f1 / np.array(orders) / 2200
        np.testing.assert_allclose(m.values, np.maximum(band[0] - lam, lam - band[1]),
                                   rtol=1e-9)


def test_generator_engine_limits(genset):
    q = genset.outcome.quantities
    st, cont = q["tv.crank_shear_stress"], q["tv.crank_stress_ratio_continuous"]
    sp = np.asarray(st.coords["speed"])
    cols = np.flatnonzero((sp / (2200 * RPM) >= 0.9 - 1e-9) & (sp / (2200 * RPM) <= 1.1 + 1e-9))
    np.testing.assert_allclose(cont.values, st.values[:, :, cols] / (21e6 * F_M), rtol=1e-9)
    tr = q["tv.crank_stress_ratio_transient"]
    assert np.allclose(tr.detail.limit, 90e6 * 700.0 / 225.0)
    by = {r.rule: r for r in genset.results}
    assert by["TV-006"].status == "not_applicable" and by["TV-007"].status == "not_applicable"
    assert by["TV-009"].status == "not_applicable"


def test_passenger_car_keeps_bells_targets(tmp_path):
    from tests.helpers import example_path

    res = api.check(example_path(tmp_path), select=["TV"])
    rows = {r.rule: r for r in res.results if r.rule in NEW}
    assert set(rows) == set(NEW)
    for r in rows.values():
        assert r.status == "not_applicable" and r.item == "all"
        assert "passenger car" in r.message and "Bell 2013" in r.message
    assert any(r.rule == "TV-001" and r.status == "fail" for r in res.results)


def test_commercial_vehicle_default_is_a_marked_warning(tmp_path):
    res = api.check(_i6(tmp_path, "truck"), select=["TV"])
    rows = [r for r in res.results if r.rule == "TV-009"]
    assert len(rows) == 8 and all(r.severity == "warning" for r in rows)
    assert all("ENGINEERING DEFAULT" in r.source for r in rows)
    assert all(r.status == "not_applicable" for r in res.results if r.rule in NEW[:5])
    d = res.outcome.quantities["tv.crank_stress_ratio_continuous"].detail
    assert d.default and d.judged_band == (0.0, 1.15)


def test_missing_rated_speed_names_the_cell(tmp_path):
    def edit(wb):
        _class("marine")(wb)
        ws = wb["Engine"]
        from tests.helpers import param_row

        ws.cell(param_row(ws, "Rated speed"), 2).value = None

    res = api.check(_i6(tmp_path, "norated", edit), select=["TV-004"])
    (r,) = [r for r in res.results if r.rule == "TV-004"]
    assert r.status == "not_evaluated" and "Rated speed" in r.message


def test_m53_torsion_from_the_whole_dynamic_system(tmp_path, monkeypatch):
    def edit(wb):
        _class("industrial")(wb)
        _with_generator(wb)

    p = _i6(tmp_path, "genset_system", edit)
    whole = api.check(p, select=["FAT-002"])
    q = whole.outcome.quantities
    m53, st = q["fatigue.m53_q"], q["tv.crank_shear_stress"]
    assert "whole dynamic system" in m53.detail.torsion_basis
    # M_TN by hand: the largest crank-section torque half range in the operating envelope
    et = q["tv.element_torque"]
    rows = [list(et.coords["item"]).index(n) for n in st.coords["item"]]
    env = st.detail.envelope
    m_tn = np.where(env[None], et.values[rows], -np.inf).max()
    assert f"M_TN = {m_tn:.0f} N m" in m53.detail.torsion_basis
    # the same engine, each speed's own torque: Q is never lower, and equal where M_TN is
    monkeypatch.setattr(tvs, "whole_system", lambda engine: False)
    each = api.check(p, select=["FAT-002"]).outcome.quantities["fatigue.m53_q"]
    assert "engine's own" in each.detail.torsion_basis
    assert np.all(m53.values <= each.values * (1 + 1e-12))
    assert np.any(m53.values < each.values * (1 - 1e-3))
    e, ci, si = np.unravel_index(int(np.argmax(np.where(env[None], et.values[rows], -np.inf))),
                                 (len(rows), *env.shape))
    # (1e-4: the per-speed stress is the torque's half range on the loads module's
    # crank-angle grid, M_TN the parabola-refined half range of tv.element_torque)
    assert np.isclose(m53.values[:, ci, si], each.values[:, ci, si], rtol=1e-4).any()


def test_examples_keep_the_engine_torque_basis(tmp_path):
    """No driven machinery in the I6's TVModel: FAT-002 as before, and it says so."""
    res = api.check(_i6(tmp_path, "truck"), select=["FAT-002"])
    d = res.outcome.quantities["fatigue.m53_q"].detail
    assert "engine's own" in d.torsion_basis and d.torsion_basis in d.assumptions
