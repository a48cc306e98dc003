"""Crankshaft fatigue module on the example engine (seed 000): every location and operating
point, I4 symmetry, the nominal bending stress against a hand calculation, workbook SCFs,
missing inputs, the Goodman point of the reported worst case, and the report section.

The Goodman, M53 and stress functions are tested on their own in tests/calc; these tests check
the integration (loads + TV torque -> stresses -> SF) and the module's mappings.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from checker import api
from checker.calc.fatigue import goodman_line
from checker.modules import fatigue as m_fatigue
from tests.helpers import edited, example_path, param_row, set_param, without_crank

RPM = 2 * np.pi / 60
PINS = [f"pin {j} fillet" for j in range(1, 5)]
MAINS = [f"main {k} fillet" for k in range(1, 6)]
PIN_OIL = [f"pin {j} oil hole" for j in range(1, 5)]
MAIN_OIL = [f"main {k} oil hole" for k in range(1, 6)]


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("fat"))


@pytest.fixture(scope="module")
def result(example):
    return api.check(example, select=["FAT-001", "FAT-002"])


def _q(res, name="fatigue.goodman_sf"):
    return res.outcome.quantities[name]


def _row(q, item):
    return q.values[q.coords["item"].index(item)]


def _append_param(wb, sheet: str, label: str, value, unit: str = "-") -> str:
    ws = wb[sheet]
    ws.append([label, value, unit, "test"])
    return f"{sheet}!B{ws.max_row}"


# ---------------------------------------------------------------------------------- coverage
def test_every_location_full_and_no_load_across_speeds(result):
    q = _q(result)
    sp = np.array(q.coords["speed"]) / RPM
    assert sp.size == 61 and sp[0] == pytest.approx(1000) and sp[-1] == pytest.approx(7000)
    assert q.coords["case"] == ["full", "no"]
    assert q.coords["item"] == PINS + MAINS + PIN_OIL + MAIN_OIL
    assert np.isfinite(q.values).all() and (q.values > 0).all()
    locs = {n: q.item_attrs[n]["location"] for n in q.coords["item"]}
    assert {locs[n] for n in PINS} == {"pin fillet"} and {locs[n] for n in MAIN_OIL} == {
        "main oil hole"}
    by = {(r.rule, r.item): r for r in result.results}
    for item in q.coords["item"]:
        r = by[("FAT-001", item)]
        assert r.status in ("pass", "fail") and r.source and r.value is not None
        assert r.case.endswith("rpm") and ("full load" in r.case or "no load" in r.case)
    m53 = _q(result, "fatigue.m53_q")
    assert m53.coords["item"] == PINS + MAINS + PIN_OIL  # M53 has no journal oil bore
    for item in m53.coords["item"]:
        r = by[("FAT-002", item)]
        assert r.status in ("pass", "fail") and r.severity == "warning"
    # the worst location is the rule result with the lowest value, at a named speed
    worst = min((r for r in result.results if r.rule == "FAT-001"), key=lambda r: r.value)
    judged = q.values if q.applies is None else np.where(q.applies, q.values, np.inf)
    assert worst.value == pytest.approx(np.nanmin(judged), rel=1e-12)


def test_m53_validity_flags_are_findings(result):
    by = {(r.rule, r.item): r for r in result.results}
    # example: R_G/D_G = 1.6/55 = 0.029 < 0.03 (beta_T uses R_G/D_G because D != D_G)
    for item in MAINS:
        assert any("β_T" in f and "r_journal_torsion" in f for f in by[("FAT-001", item)].findings)
    for item in PINS + PIN_OIL:
        assert not any("β_T" in f for f in by[("FAT-001", item)].findings)
    # M53 sigma_DW: fillet radius 1.6 mm raised to 2 mm (M53 §6) is stated
    assert any("taken as 2 mm" in f for f in by[("FAT-002", "pin 1 fillet")].findings)


# ---------------------------------------------------------------------------------- physics
def test_i4_throw_symmetry(result, example):
    q = _q(result)
    nom = q.detail.nominal.sigma_web_bending  # (C, S, T, 2, N)
    rng, mid = np.ptp(nom, axis=-1), nom.max(-1) + nom.min(-1)
    # throws 1/4 (0 deg) and 2/3 (180 deg) see the same bending, shifted by their firing angles
    for a, b in ((0, 3), (1, 2)):
        np.testing.assert_allclose(rng[:, :, a], rng[:, :, b], rtol=0.01)
        np.testing.assert_allclose(mid[:, :, a], mid[:, :, b], rtol=0.01, atol=1e3)
    # with the same torque in every journal (none), every safety factor is symmetric ...
    res_tv = result.outcome.quantities
    et = res_tv["tv.element_torque"]
    zero = dataclasses.replace(et, detail=dataclasses.replace(
        et.detail, coeffs=np.zeros_like(et.detail.coeffs), mean=np.zeros_like(et.detail.mean)))
    out = m_fatigue.crank_fatigue(result.engine,
                                  {"loads.bearing_load": res_tv["loads.bearing_load"],
                                   "tv.element_torque": zero})["fatigue.goodman_sf"]
    for a, b in (("pin 1 fillet", "pin 4 fillet"), ("pin 2 fillet", "pin 3 fillet"),
                 ("main 1 fillet", "main 5 fillet"), ("main 2 fillet", "main 4 fillet"),
                 ("pin 1 oil hole", "pin 4 oil hole"), ("pin 2 oil hole", "pin 3 oil hole")):
        np.testing.assert_allclose(_row(out, a), _row(out, b), rtol=0.01)
    # ... while the TV torque, which builds up towards the flywheel, breaks it (control)
    assert _row(q, "pin 4 fillet").min() < 0.95 * _row(q, "pin 1 fillet").min()
    assert _row(q, "main 5 fillet").min() < 0.95 * _row(q, "main 1 fillet").min()


def test_nominal_bending_of_throw_1_by_hand(result):
    q = _q(result)
    ex = q.detail
    ci, si = 0, list(np.round(np.array(q.coords["speed"]) / RPM)).index(4000)
    f_r = ex.pin_force_radial[ci, si, 0]  # (N,) module's own pin force, throw 1 [N]
    # example geometry (seed 000): L3 = 96, L_G = 27, L_H = 24.4, W = 21.3, B = 71.4 mm
    r_main = f_r * 48.0 / 96.0  # reaction at the front main (pin at mid-bay)
    lever = 27.0 / 2 + (96.0 - 27.0 - 24.4) / 4  # L1 = L_G/2 + W_full/2 = 24.65 mm
    w_b = 71.4 * 21.3**2 / 6  # B W^2 / 6 [mm^3]
    sigma = r_main * lever / w_b * 1e6  # N mm / mm^3 -> Pa
    np.testing.assert_allclose(ex.nominal.sigma_web_bending[ci, si, 0, 0], sigma,
                               rtol=1e-9)
    np.testing.assert_allclose(ex.nominal.sigma_web_bending[ci, si, 0, 1], sigma,
                               rtol=1e-9)  # rear web: same share with the pin at mid-bay
    # the pin force itself: at 1000 rpm full load the gas force pushes the pin inward,
    # F_R,min ~ -(p_max - p_cc) pi/4 B^2 cos(theta + beta)/cos(beta) near TDC (inertia small)
    f_gas = (53.4e5 - 1e5) * np.pi / 4 * 0.086**2
    f_min = ex.pin_force_radial[0, 0, 0].min()
    assert -1.0 * f_gas < f_min < -0.85 * f_gas
    # the pin fillet (crank-pin-side web face) is in tension under the gas load
    i = q.coords["item"].index("pin 1 fillet")
    assert ex.sigma_m[i, 0, 0] > 0


def test_tv_torque_signal_on_the_loads_crank_angle(result):
    qs = result.outcome.quantities
    ex = qs["fatigue.goodman_sf"].detail
    t = ex.element_torque  # (C, S, E + 1, N)
    et = qs["tv.element_torque"]
    # synthesised signal: mean as given, extremes as the TV module's (1 deg sampling)
    np.testing.assert_allclose(t[..., :-1, :].mean(-1), np.moveaxis(et.detail.mean, 0, -1),
                               atol=1e-9)
    vib_max = np.moveaxis(et.detail.vib_max + et.detail.mean, 0, -1)
    np.testing.assert_allclose(t[..., :-1, :].max(-1), vib_max, rtol=2e-3, atol=2.0)
    # same theta origin as the loads: at 1000 rpm the torque that cylinder 1's station adds to
    # the chain follows cylinder 1's own crank torque (loads module) without a phase shift
    cyl1 = qs["loads.bearing_load"].detail.torque[0, 0, 0]
    added = t[0, 0, 2] - t[0, 0, 1]  # (cylinder 1 -> 2) - (nose -> cylinder 1)
    corr = [np.corrcoef(np.roll(added, k), cyl1)[0, 1] for k in (-10, 0, 10)]
    assert corr[1] > 0.99 and corr[1] > max(corr[0], corr[2])
    # mapping: throw 1 front/rear = elements nose -> cyl 1, cyl 1 -> cyl 2; main 5 = cyl 4 -> fw
    names = ex.element_names
    assert [names[e] for e in ex.throw_elements[0]] == ["Crank nose -> Cylinder 1",
                                                           "Cylinder 1 -> Cylinder 2"]
    assert names[ex.main_elements[4][0]] == "Cylinder 4 -> Flywheel"


def test_goodman_point_of_the_reported_worst_case(result):
    q = _q(result)
    ex = q.detail
    r = min((r for r in result.results if r.rule == "FAT-001"), key=lambda r: r.value)
    i = q.coords["item"].index(r.item)
    judged = q.values[i] if q.applies is None else np.where(q.applies[i], q.values[i], np.inf)
    ci, si = np.unravel_index(int(np.argmin(judged)), judged.shape)
    se, su = ex.endurance_limit[i], ex.ultimate_strength[i]
    sa, sm = ex.sigma_eq_a[i, ci, si], ex.sigma_eq_m[i, ci, si]
    assert se == pytest.approx(326e6) and su == pytest.approx(750e6)  # pin oil hole, seed 000
    assert r.value == pytest.approx(1 / (sa / se + max(sm, 0.0) / su), rel=1e-9)
    # the operating point lies on the Goodman line shrunk by its safety factor
    assert float(goodman_line(sm, se, su, r.value)) == pytest.approx(sa, rel=1e-9)
    # normalised Haigh coordinates of the report
    assert ex.haigh_y[i, ci, si] + max(ex.haigh_x[i, ci, si], 0) == pytest.approx(
        1 / r.value, rel=1e-9)


# ---------------------------------------------------------------------------------- inputs
def test_workbook_scfs_override_m53(tmp_path, result):
    base = _q(result)
    a_b53 = base.detail.scf.m53["alpha_b"]
    cells = {}

    def edit(wb):
        cells["ab"] = _append_param(wb, "Fatigue", "Pin fillet stress concentration bending", 3.0)
        cells["bt"] = _append_param(wb, "Fatigue", "Main fillet stress concentration torsion",
                                    2.0)

    res = api.check(edited(tmp_path, edit), select=["FAT-001", "FAT-002"])
    q = _q(res)
    scf = q.detail.scf
    assert scf.used["alpha_b"] == 3.0 and cells["ab"] in scf.source["alpha_b"]
    assert scf.used["beta_t"] == 2.0 and cells["bt"] in scf.source["beta_t"]
    assert scf.source["alpha_t"].startswith("IACS")
    # the pin-fillet bending amplitude scales with the factor used
    i = [q.coords["item"].index(n) for n in PINS]
    np.testing.assert_allclose(q.detail.sigma_a[i], base.detail.sigma_a[i] * 3.0 / a_b53,
                               rtol=1e-9)
    # the beta_T validity flag no longer applies: the user's factor replaced the formula
    by = {(r.rule, r.item): r for r in res.results}
    assert not any("β_T" in f for f in by[("FAT-001", "main 1 fillet")].findings)
    assert by[("FAT-001", "pin 4 fillet")].value != pytest.approx(
        next(r.value for r in result.results if (r.rule, r.item) == ("FAT-001", "pin 4 fillet")))


def test_not_evaluated_without_tv_model(tmp_path):
    def edit(wb):
        ws = wb["TVModel"]
        ws.delete_rows(3, ws.max_row)

    res = api.check(edited(tmp_path, edit), select=["FAT-001", "FAT-002"])
    assert {r.rule for r in res.results} == {"FAT-001", "FAT-002"}
    for r in res.results:
        assert r.status == "not_evaluated"
        assert any("TVModel" in m for m in r.missing), r.missing
    assert "fatigue" not in res.outcome.modules_run  # blocked: never run without the torque


def test_missing_fatigue_cells_are_named(tmp_path):
    cell = {}

    def edit(wb):
        cell["se"] = set_param(wb, "Fatigue", "Pin fillet fatigue strength")
        wb["Fatigue"].cell(param_row(wb["Fatigue"], "Pin fillet fatigue strength"), 2).value = None

    res = api.check(edited(tmp_path, edit), select=["FAT-001", "FAT-002"])
    by = {(r.rule, r.item): r for r in res.results}
    for item in PINS:
        r = by[("FAT-001", item)]
        assert r.status == "not_evaluated"
        assert any(cell["se"] in m and "Pin fillet fatigue strength" in m for m in r.missing)
        assert by[("FAT-002", item)].status in ("pass", "fail")  # M53 uses its own sigma_DW
    for item in MAINS + PIN_OIL + MAIN_OIL:
        assert by[("FAT-001", item)].status in ("pass", "fail")

    def edit2(wb):
        without_crank(wb)  # sheet Crank would derive the reduced thickness
        cell["w"] = set_param(wb, "Fatigue", "Web reduced thickness")
        wb["Fatigue"].cell(param_row(wb["Fatigue"], "Web reduced thickness"), 2).value = None

    res = api.check(edited(tmp_path, edit2, "web.xlsx"), select=["FAT-001", "FAT-002"])
    for r in res.results:
        assert r.status == "not_evaluated"
        assert any(cell["w"] in m and "Web reduced thickness" in m for m in r.missing)


def test_report_section(result):
    from checker.report.sections import build_sections
    from checker.results.fatigue import GoodmanDetail, M53Detail

    assert isinstance(_q(result).detail, GoodmanDetail)
    assert isinstance(_q(result, "fatigue.m53_q").detail, M53Detail)
    sec = {s["id"]: s for s in build_sections(result)}["fatigue"]
    types = [b["type"] for b in sec["blocks"]]
    assert types.count("figure") == 2 and "equations" in types  # SF against speed, Haigh
    tables = {b["caption"].split(" (")[0].split(":")[0]: b for b in sec["blocks"]
              if b["type"] == "table"}
    worst = next(b for c, b in tables.items() if c.startswith("Lowest Goodman"))
    judged = [r[0] for r, css in zip(worst["rows"], worst["row_css"]) if not css]
    assert judged == PINS + MAINS + PIN_OIL + MAIN_OIL  # then, marked, points not judged
    scf = next(b for c, b in tables.items() if c.startswith("Stress concentration"))
    beta_t = next(r for r in scf["rows"] if r[0] == "β_T")
    assert "r_journal_torsion" in beta_t[-1]
    text = " ".join(str(i) for b in sec["blocks"] if b["type"] == "list" for i in b["items"])
    assert "von Mises" in text and "signed von Mises" in text
