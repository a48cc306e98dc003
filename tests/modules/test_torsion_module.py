"""Torsional-vibration module on the example engine: natural frequencies, order structure,
synthesis bounds, undamped resonance findings, damper limits and the joint torques it provides.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.linalg

from checker import api
from checker.calc import torsional as tv
from checker.description.engine import load_engine
from checker.workbook.example import TV_MODEL
from tests.helpers import (
    analyses_run,
    column,
    edited,
    example_path,
    param_row,
    set_param,
    table_row,
)

RPM = 2 * np.pi / 60




def _workbook_chain() -> tuple[np.ndarray, np.ndarray]:
    """M and K of the example's TVModel rows, assembled by hand (kg m^2, N m/rad)."""
    rows = TV_MODEL[1]
    j = np.array([r[3] for r in rows], dtype=float)
    k = np.array([r[5] for r in rows[:-1]], dtype=float)
    n = j.size
    kmat = np.zeros((n, n))
    for e, ke in enumerate(k):
        kmat[np.ix_([e, e + 1], [e, e + 1])] += ke * np.array([[1, -1], [-1, 1]])
    return np.diag(j), kmat


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("tv"))


@pytest.fixture(scope="module")
def tv_result(example):
    return api.check(example, select=["TV", "DMP"])


def test_natural_frequencies_equal_direct_eigensolve(tv_result):
    # independent: generalized symmetric eigenproblem K phi = w^2 M phi of the workbook numbers
    mmat, kmat = _workbook_chain()
    lam = scipy.linalg.eigh(kmat, mmat, eigvals_only=True)
    f_ref = np.sqrt(lam[1:]) / (2 * np.pi)  # drop the free-free rigid-body mode
    nf = tv_result.outcome.quantities["tv.natural_frequency"]
    np.testing.assert_allclose(nf.values, f_ref, rtol=1e-9)
    assert nf.detail.rigid_body_mode
    assert 280 < nf.values[0] < 300  # damper mode below the first crank mode (543 Hz)


def test_minor_orders_small_against_major_orders(tv_result, example):
    # I4 firing 1-3-4-2: orders 0.5, 1, 1.5 cancel for rigid-body motion (vector sum 0), so at
    # the nose they are only the (small) crank twist; orders 2 and 4 (major) are not.
    q = tv_result.outcome.quantities["tv.nose_order_amplitude"]
    amp = {lab: q.values[i] for i, lab in enumerate(q.coords["order"])}
    minor = np.array([amp[f"order {n}"] for n in ("0.5", "1", "1.5")])  # (3, C, S)
    assert minor.max() < 0.05 * amp["order 2"].max()
    low = minor[:, 0, 0]  # full load, lowest speed: rolling-mode regime
    assert np.all(low < 0.05 * amp["order 2"][0, 0]) and np.all(low < 0.25 * amp["order 4"][0, 0])
    # control (the check can fail): every cylinder firing together makes orders 0.5..1.5 major
    eng = load_engine(example)
    same = dataclasses.replace(eng, cylinders=tuple(dataclasses.replace(c, firing_angle=0.0)
                                                    for c in eng.cylinders))
    q2 = api.check(same, select=["TV-001"]).outcome.quantities["tv.nose_order_amplitude"]
    amp2 = {lab: q2.values[i] for i, lab in enumerate(q2.coords["order"])}
    assert amp2["order 0.5"][0, 0] > amp["order 4"][0, 0]


def test_synthesised_total_between_largest_order_and_sum(tv_result):
    qs = tv_result.outcome.quantities
    total = qs["tv.nose_amplitude"].values  # (C, S)
    orders = qs["tv.nose_order_amplitude"].values  # (O, C, S)
    assert np.all(np.isfinite(total)) and np.all(total > 0)
    # sum |Theta_n| bounds the half range from above (triangle inequality); on this engine one
    # order dominates at every speed, so the total also exceeds each single order
    assert np.all(total <= orders.sum(axis=0) * (1 + 1e-9))
    assert np.all(total >= orders.max(axis=0) * (1 - 1e-9))


def test_rules_evaluated_with_sources(tv_result):
    by_rule = {r.rule: r for r in tv_result.results if r.status != "not_applicable"}
    # the I4 example's rubber has a temperature table: DMP-005..007 judge its ends
    assert set(by_rule) == {"TV-001", "TV-002", "TV-003", "DMP-001", "DMP-002", "DMP-003",
                            "DMP-004", "DMP-005", "DMP-006", "DMP-007"}
    for r in by_rule.values():
        assert r.status in ("pass", "fail") and r.value is not None and r.source
    # seed 000 model: the 6th order crank-mode resonance near 5400 rpm (543 Hz / 6) exceeds
    # the 0.05 deg target for higher orders
    assert by_rule["TV-002"].status == "fail" and "order 6" in by_rule["TV-002"].case
    nose = tv_result.outcome.quantities["tv.nose_cylinder_order_amplitude"]
    assert nose.detail.order == 4.0


def test_element_torque_conventions(tv_result):
    qs = tv_result.outcome.quantities
    et = qs["tv.element_torque"]
    ex = et.detail
    fead = 19.0  # Engine 'Accessory drive torque at crank nose' of the example
    cyl = ex.cylinder_mean_torque  # (C, S) one cylinder
    # mean torque summed from the front: rubber 0, nose element -FEAD, flywheel element 4 T - FEAD
    np.testing.assert_allclose(ex.mean[0], 0.0, atol=1e-9)
    np.testing.assert_allclose(ex.mean[1], -fead, atol=1e-9)
    np.testing.assert_allclose(ex.mean[-1], 4 * cyl - fead, rtol=1e-12)
    assert np.all(ex.mean[-1, 0] > 0)  # full load: the crank drives the flywheel
    # half range of the sampled extremes agrees with the exact half range
    exact = tv.half_peak_to_peak(ex.orders, ex.coeffs)
    np.testing.assert_allclose(et.values, exact, rtol=1e-3)
    np.testing.assert_allclose(0.5 * (ex.vib_max - ex.vib_min), et.values, rtol=1e-12)
    # the damper rubber torque is the torque of the damper element (opposite sign convention)
    np.testing.assert_allclose(qs["damper.torque"].values, et.values[0], rtol=1e-3)
    # dissipated power = sum over orders of 1/2 Omega eta k' |dphi|^2 (torsion.md 3.5)
    dphi = qs["damper.power"].detail.dphi
    omega = ex.orders * np.array(et.coords["speed"])[:, None]
    p_ref = (0.5 * omega * 0.15 * 25500 * np.abs(dphi) ** 2).sum(-1)
    np.testing.assert_allclose(qs["damper.power"].values, p_ref, rtol=1e-12)


def test_undamped_resonance_is_a_finding_not_nan(tmp_path):
    mmat, kmat = _workbook_chain()
    w1 = np.sqrt(scipy.linalg.eigh(kmat, mmat, eigvals_only=True)[1])
    rpm = w1 / 6 / RPM  # the 6th order hits mode 1 exactly at the first swept speed

    def edit(wb):
        set_param(wb, "Damper", "Rubber loss factor", 0)
        del wb["DamperRubber"]  # the rubber's table against temperature would damp the ring
        ws = wb["TVModel"]
        for r in range(3, ws.max_row + 1):
            ws.cell(r, column(ws, "absolute damping")).value = None
        ws = wb["Engine"]
        ws.cell(param_row(ws, "Minimum speed"), 2).value = float(rpm)

    res = api.check(edited(tmp_path, edit), select=["TV", "DMP"])
    qs = res.outcome.quantities
    for name, q in qs.items():
        if name.startswith(("tv.", "damper.")):
            assert not np.isnan(q.values).any() and not np.isinf(q.values).any(), name
    nose = qs["tv.nose_amplitude"]
    assert nose.coords["speed"][0] == pytest.approx(w1 / 6, rel=1e-12)
    found = nose.findings[(0, 0)]
    assert any("undamped resonance" in f and "order 6" in f for f in found)
    tv2 = next(r for r in res.results if r.rule == "TV-002")
    assert tv2.status == "fail" and any("undamped resonance" in f for f in tv2.findings)
    assert qs["damper.power"].values.max() == 0.0  # no loss in the rubber


def test_undamped_resonance_between_swept_speeds_is_a_finding(tmp_path, tv_result):
    """No damping at all and the sweep (every 100 rpm from 1000 rpm) does not hit the 4th-order
    resonance of mode 1 exactly: the critical speed w1 / 4 (hand eigensolve of the workbook
    chain) lies between two swept speeds. The swept amplitudes are finite there, so without a
    finding the unbounded response would go unnoticed; the damped example has none."""
    mmat, kmat = _workbook_chain()
    w1 = np.sqrt(scipy.linalg.eigh(kmat, mmat, eigvals_only=True)[1])
    crit_rpm = w1 / 4 / RPM
    assert abs(crit_rpm / 100 - round(crit_rpm / 100)) > 0.1  # not on a swept speed

    def edit(wb):
        set_param(wb, "Damper", "Rubber loss factor", 0)
        ws = wb["TVModel"]
        for r in range(3, ws.max_row + 1):
            ws.cell(r, column(ws, "absolute damping")).value = None

    res = api.check(edited(tmp_path, edit), select=["TV-001"])
    q = res.outcome.quantities["tv.nose_cylinder_order_amplitude"]
    assert not q.detail.resonance.any()  # not exactly on it: no exact-resonance flag
    assert np.isfinite(q.values).all()
    [r] = res.results
    text = f"order 4 meets the natural frequency {w1 / (2 * np.pi):.1f} Hz"
    found = [f for f in r.findings if text in f]
    assert len(found) == 1 and f"at {crit_rpm:.0f} rpm between two swept speeds" in found[0]
    lo, hi = int(crit_rpm // 100 * 100), int(crit_rpm // 100 * 100 + 100)
    assert f"{lo}, {hi}" in found[0]  # the bracketing speeds are named
    # the finding sits on the bracketing points of both load cases
    speeds = np.array(q.coords["speed"]) / RPM
    for ci in range(2):
        for rpm in (lo, hi):
            si = int(np.flatnonzero(np.isclose(speeds, rpm))[0])
            assert found[0] in q.findings[(ci, si)]
    assert not any("undamped" in f for r0 in tv_result.results for f in r0.findings)


def test_damper_rule_not_evaluated_without_supplier_limit(tmp_path):
    def edit(wb):
        ws = wb["Damper"]
        ws.cell(param_row(ws, "Rubber shear stress limit"), 2).value = None

    res = api.check(edited(tmp_path, edit), select=["DMP"])
    by_rule = {r.rule: r for r in res.results}
    assert by_rule["DMP-001"].status == "not_evaluated"
    assert any("Damper!B6" in m and "shear stress limit" in m.lower()
               for m in by_rule["DMP-001"].missing)
    assert by_rule["DMP-002"].status in ("pass", "fail")


def test_joint_rules_from_tv_torques_when_rows_removed(tmp_path):
    def edit(wb):
        ws = wb["JointTorques"]
        ws.delete_rows(3, ws.max_row)

    path = edited(tmp_path, edit)
    res = api.check(path, select=["JNT"])
    assert analyses_run(res.outcome) == ["loads", "torsion", "joints"]
    app = res.outcome.quantities["joint.applied_torque"]
    tq = res.outcome.quantities["tv.joint_torque"]
    assert np.all(app.detail.source == "torsional vibration module")
    np.testing.assert_array_equal(app.values, tq.values)
    # operating points: max power 5500 rpm (BrakeTorque: 255 N m x 5500 rpm), overspeed 7000
    k_mp, k_ov = app.coords["point"].index("max power"), app.coords["point"].index("overspeed")
    np.testing.assert_allclose(app.detail.speed[:, k_mp] / RPM, 5500)
    np.testing.assert_allclose(app.detail.speed[:, k_ov] / RPM, 7000)
    assert list(tq.detail.case[:, k_ov]) == ["no", "no"]
    # flywheel at overspeed: no load, no brake torque: the peak of the vibratory torque
    et = api.check(path, select=["TV-001"]).outcome.quantities["tv.element_torque"]
    i_fw, s_ov = app.coords["item"].index("flywheel"), et.coords["speed"].index(7000 * RPM)
    peak = max(abs(et.detail.vib_max[-1, 1, s_ov]), abs(et.detail.vib_min[-1, 1, s_ov]))
    assert app.values[i_fw, k_ov] == pytest.approx(peak, rel=1e-12)
    results = {(r.rule, r.item): r for r in res.results}
    for rule, item in (("JNT-003", "crank nose"), ("JNT-005", "flywheel"),
                       ("JNT-006", "flywheel"), ("JNT-007", "flywheel")):
        assert results[(rule, item)].status in ("pass", "fail")
    # the JSON and the report say where the torques come from
    assumptions = " ".join(res.to_dict(timings=False)["assumptions"])
    assert "taken from the TV module" in assumptions and "flywheel at 'overspeed'" in assumptions
    from checker.report.sections import build_sections

    sec = {s["id"]: s for s in build_sections(res)}
    joint_rows = [r for b in sec["joints"]["blocks"] if b["type"] == "table"
                  for r in b["rows"]]
    assert sum(1 for r in joint_rows if len(r) > 4 and r[4].startswith("computed:")) == 6
    tv_rows = [r for b in sec["torsion"]["blocks"] if b["type"] == "table" for r in b["rows"]]
    assert any(r[:2] == ["flywheel", "overspeed"] and r[-1] == "torsional model" for r in tv_rows)


def test_tv_module_skipped_when_joint_torques_given(tmp_path):
    def edit(wb):
        ws = wb["JointTorques"]
        for joint, point, speed, torque in (("crank nose", "max power", 5500, 250),
                                            ("crank nose", "overspeed", 7000, 240),
                                            ("flywheel", "max power", 5500, 1200),
                                            ("flywheel", "overspeed", 7000, 1100)):
            ws.append([joint, point, speed, torque, "test"])

    # the torsional module only runs for JNT-008 (the given torques against the model's)
    res = api.check(edited(tmp_path, edit), select=["JNT"], ignore=["JNT-008"])
    assert analyses_run(res.outcome) == ["joints"]
    app = res.outcome.quantities["joint.applied_torque"]
    assert np.all(app.detail.source == "workbook (JointTorques)")


def test_workbook_joint_torques_still_used_without_tv_model(tmp_path):
    def edit(wb):
        ws = wb["TVModel"]
        ws.delete_rows(3, ws.max_row)

    res = api.check(edited(tmp_path, edit), select=["JNT", "TV"])
    results = {(r.rule, r.item): r for r in res.results}
    # the 'tv peak' torques the workbook gives are used (seed 000: 245 and 1216 N m) ...
    assert results[("JNT-003", "crank nose")].value == pytest.approx(1.467, abs=5e-4)
    assert results[("JNT-005", "flywheel")].status == "fail"
    # ... and the points it does not give name the missing TV model
    for rule in ("JNT-006", "JNT-007"):
        r = results[(rule, "flywheel")]
        assert r.status == "not_evaluated" and any("TVModel" in m for m in r.missing)
    assert results[("TV-001", "all")].status == "not_evaluated"


@pytest.fixture(scope="module")
def v8_models(tmp_path_factory):
    """The V8 example with one TV station per throw (cylinders '1, 2' ...) and the same V8
    with every throw split into two stations, one per cylinder, joined by a 1e13 N m/rad link
    (half the inertia and damping each)."""
    from checker.workbook.example import write_workbook
    from checker.workbook.example_v8 import v8_content

    d = tmp_path_factory.mktemp("v8tv")
    out = []
    for split in (False, True):
        p = d / f"v8-{'split' if split else 'paired'}.xlsx"
        write_workbook(p, v8_content(split_stations=split, link=1e13))
        out.append(api.check(p, select=["TV"]))
    return out


def test_v8_paired_stations_equal_split_stations_with_a_stiff_link(v8_models):
    # A station carrying both cylinders of a V-engine pin is the limit of two stations joined
    # by an infinitely stiff link: with 1e13 N m/rad the model error is J w^2 / k ~ 1e-7, so
    # natural frequencies and crank-nose amplitudes agree to 1e-6 (issue 17).
    paired, split = (r.outcome.quantities for r in v8_models)
    f_p = paired["tv.natural_frequency"].values
    f_s = split["tv.natural_frequency"].values
    assert f_s.size == f_p.size + 4  # one link mode per split throw
    np.testing.assert_allclose(f_s[:f_p.size], f_p, rtol=1e-6)
    assert f_s[f_p.size] > 50 * f_p[-1]  # the link modes lie far above
    n_p, n_s = paired["tv.nose_amplitude"].values, split["tv.nose_amplitude"].values
    assert np.all(n_p > 0)
    np.testing.assert_allclose(n_s, n_p, rtol=1e-6)
    # per order too, where the amplitude matters (above 1e-9 of the largest); 2e-5 here: the
    # stiff link conditions the per-order solve at the lowest orders and speeds (k_link /
    # (w^2 J) ~ 1e10, so ~1e-6 of round-off, up to 1.1e-5 with the V8's station inertias
    # derived from its crank geometry, 3e-5 with its stiffnesses of the assembled crank,
    # issue 43, on amplitudes 1e-5 of the largest), which the synthesis averages out
    o_p = paired["tv.nose_order_amplitude"].values
    o_s = split["tv.nose_order_amplitude"].values
    big = o_p > 1e-9 * o_p.max()
    np.testing.assert_allclose(o_s[big], o_p[big], rtol=6e-5)


def test_v8_station_takes_both_cylinders_phased_by_their_own_firing_angles(v8_models):
    # throw 1 carries cylinders 1 and 2 (firing 0 and 270 deg), throw 2 cylinders 3 and 4 (630
    # and 540 deg): with one cylinder's harmonic c_n, F_n,throw = c_n sum exp(-j n phi_i)
    # (torsion.md sec. 3.3), so the ratio of the two stations' excitations is
    # (e^{-j n 630} + e^{-j n 540}) / (1 + e^{-j n 270}) whatever c_n is; at order 2 the two
    # cylinders of a pin cancel (1 + e^{-j 540 deg} = 0), at order 4 (a V8's major order) add.
    ex = v8_models[0].outcome.quantities["tv.nose_amplitude"].detail
    force = ex.excitation  # (C, S, n_st, O)
    orders = ex.orders
    assert list(ex.model_data.cyl_station) == [2, 2, 3, 3, 4, 4, 5, 5]

    def phase(n, *deg):
        return sum(np.exp(-1j * n * np.radians(d)) for d in deg)

    top = np.abs(force).max()
    for oi, n in enumerate(orders):
        den = phase(n, 0, 270)
        f2, f3 = force[:, :, 2, oi], force[:, :, 3, oi]
        if abs(den) < 1e-9:  # orders 2, 6, 10...: the pin's two cylinders cancel
            assert np.abs(f2).max() < 1e-12 * top
            continue
        np.testing.assert_allclose(f3, f2 * phase(n, 630, 540) / den, atol=1e-12 * top)
    o2, o4 = (int(np.argmin(np.abs(orders - n))) for n in (2.0, 4.0))
    assert np.abs(force[:, :, 2, o2]).max() < 1e-9 * np.abs(force[:, :, 2, o4]).max()


def _remove_damper_ring(wb, stiffness_factor: float = 1.0) -> None:
    """The example without its damper ring (TVModel row removed), crank stiffness scaled."""
    ws = wb["TVModel"]
    k = column(ws, "stiffness to next")
    for r in range(3, ws.max_row + 1):
        if isinstance(ws.cell(r, k).value, (int, float)):
            ws.cell(r, k).value *= stiffness_factor
    ws.delete_rows(table_row(ws, "role", "damper ring"))


def _judged_maximum(values: np.ndarray, envelope: np.ndarray) -> float:
    """Independent reference: the largest amplitude inside the envelope once the rolling-mode
    fall from the lowest swept speed has ended (from the first local minimum of the curve on)."""
    rise = np.flatnonzero(np.diff(values) > 0)
    start = rise[0] if rise.size else values.size - 1
    inside = envelope.copy()
    inside[:start] = False
    return float(values[inside].max()) if inside.any() else -np.inf


@pytest.mark.parametrize("factor, speed_rpm", [(1.0, 6500), (1.1, 6500)])
def test_tv001_judges_each_load_case_within_its_own_envelope(tmp_path, factor, speed_rpm):
    """Without the damper ring the 4th-order crank-mode resonance lies above the full-load
    data range (1000-6500 rpm): the full-load curve still rises at 6500 rpm, the last speed
    judged at full load, while no load is judged up to the 7000 rpm overspeed. Each case must
    be judged at its own top speed: TV-001 reports the full-load 6500 rpm amplitude (before
    this was fixed it reported the smaller no-load 7000 rpm value: 0.103 deg instead of
    0.161 deg without the ring; with the crank 10 % stiffer 0.051 deg, a PASS, instead of
    0.106 deg > 0.06 deg)."""
    res = api.check(edited(tmp_path, lambda wb: _remove_damper_ring(wb, factor)),
                    select=["TV-001"])
    q = res.outcome.quantities["tv.nose_cylinder_order_amplitude"]
    env = res.outcome.quantities["loads.cycle"].detail.cycle.envelope
    speeds = np.array(q.coords["speed"]) / RPM
    full, no = q.coords["case"].index("full"), q.coords["case"].index("no")
    top = int(np.flatnonzero(speeds == speed_rpm)[0])
    assert env[full, top] and not env[full, top + 1:].any() and env[no].all()
    assert q.values[full, top] > q.values[full, top - 1]  # the flank still rises into the top
    # judged points: never outside the envelope; the top speed of each rising case is judged
    assert not (q.applies & ~env).any()
    assert q.applies[full, top] and q.applies[no, -1]
    assert "envelope" in q.applies_text
    # per case: the judged maximum is the true maximum within the envelope (rolling mode aside)
    for ci in (full, no):
        assert q.values[ci][q.applies[ci]].max() == pytest.approx(
            _judged_maximum(q.values[ci], env[ci]), rel=1e-12)
    [r] = res.results
    assert r.case == f"full load, {speed_rpm} rpm"
    assert r.value == pytest.approx(np.degrees(q.values[full, top]), rel=1e-9)
    assert np.degrees(q.values[no, -1]) < r.value
    assert r.status == "fail" and r.value > 0.06
    if factor == 1.1:  # the no-load top alone would pass: the variant discriminates
        assert np.degrees(q.values[no, -1]) < 0.06
