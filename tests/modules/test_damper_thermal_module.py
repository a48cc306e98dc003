"""The damper at its own temperature (checker.modules.damper_thermal): the I6's untuned
viscous damper against Den Hartog's optimum and its heat balance, the I4's rubber at the cold
and hot ends, and workbooks with today's rubber damper unchanged."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import openpyxl
import pytest

from checker import api
from checker.calc import damper as dmp
from checker.calc import damper_tuning as dt
from checker.calc import viscous_damper as vd
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content
from tests.helpers import edited, param_row

ROOT = Path(__file__).resolve().parents[2]
NEW_DAMPER_ROWS = ("Operating temperature, minimum", "Operating temperature, maximum",
                   "Damper heat transfer coefficient", "Damper cooled surface area")


@pytest.fixture(scope="module")
def i6(tmp_path_factory):
    p = tmp_path_factory.mktemp("i6") / "i6.xlsx"
    write_workbook(p, i6_content(damper_ring=True))
    return api.check(p, select=["TV", "DMP"])


def test_viscous_damper_rules_replace_the_rubber_rules(i6):
    status = {r.rule: r.status for r in i6.results}
    assert {"DMP-008", "DMP-009", "DMP-010"} <= set(status)
    assert all(status[r] != "not_applicable" for r in ("DMP-008", "DMP-009", "DMP-010"))
    # the rubber's rules are listed as not applicable with the reason (issue 37 item 6)
    rubber = [r for r in i6.results if r.rule in {"DMP-001", "DMP-002", "DMP-003", "DMP-004",
                                                  "DMP-005", "DMP-006", "DMP-007"}]
    assert {r.rule for r in rubber} == {f"DMP-00{k}" for k in range(1, 8)}
    assert all(r.status == "not_applicable" and "viscous" in r.message for r in rubber)
    assert "damper.tuning_ratio" not in i6.outcome.quantities
    assert any("do not apply" in a for a in i6.assumptions)


def test_optimum_is_den_hartogs_for_the_crank_mode(i6):
    q = i6.outcome.quantities
    d = q["damper.optimum_damping"].detail
    model = q["tv.nose_amplitude"].detail.model
    pm = dt.primary_mode(model, 0)
    mu = model.inertia[0] / pm.equivalent_inertia
    # c_opt = 2 J_d w_n / sqrt(2 (1 + mu)(2 + mu)) (Den Hartog 1956 ch. 3)
    c_opt = 2 * model.inertia[0] * pm.omega / np.sqrt(2 * (1 + mu) * (2 + mu))
    assert q["damper.optimum_damping"].values[0] == pytest.approx(c_opt, rel=1e-12)
    assert d.mass_ratio == pytest.approx(0.751, abs=5e-4)  # 0.1085 / 0.1444
    assert d.peak_magnification == pytest.approx(1 + 2 / mu, rel=1e-12)
    # the example's grade is sized so that c is at the optimum at the hot end's resonance
    opt = q["damper.damping_to_optimum"]
    hot_full = opt.values[1, 0][opt.applies[1, 0]]
    assert hot_full.size == 1 and hot_full[0] == pytest.approx(1.0, abs=0.03)


def test_heat_balance_power_and_flux(i6):
    q = i6.outcome.quantities
    d = q["damper.optimum_damping"].detail
    t, p = d.temperature, d.power
    ok = np.isfinite(t)
    # T = T_air + P R at every point, R = 1/(h A) of the Damper sheet (80 W/(m^2 K), 0.25 m^2)
    assert d.heat_resistance == pytest.approx(1 / (80 * 0.25), rel=1e-12)
    t_air = np.array(d.air_temperature)[:, None, None]
    np.testing.assert_allclose((t - t_air - p * d.heat_resistance)[ok], 0.0, atol=2e-3)
    g = vd.GapGeometry(0.09, 0.13, 0.04, 0.0005, 0.0006)
    np.testing.assert_allclose(q["damper.heat_flux"].values, p / vd.wetted_area(g), rtol=1e-12)
    # c at the silicone temperature: rho nu(T) Phi (Andrade through the datasheet's VTC)
    nu = vd.andrade_viscosity(t, 0.16, 298.15, vd.andrade_slope(0.6))
    np.testing.assert_allclose(d.damping, 970 * nu * vd.couette_factor(g), rtol=1e-12)


def test_nominal_power_is_c_omega2_twist2_over_2(i6):
    # the TV solve's damper power with the silicone at its reference temperature: Newtonian
    # coupling, P = sum_n c Omega_n^2 |dphi_n|^2 / 2
    q = i6.outcome.quantities
    pw = q["damper.power"]
    c = q["damper.optimum_damping"].detail.damping_nominal
    omega = pw.detail.orders * np.array(pw.coords["speed"])[:, None]
    ref = (0.5 * c * omega**2 * np.abs(pw.detail.dphi) ** 2).sum(-1)
    np.testing.assert_allclose(pw.values, ref, rtol=1e-12)


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    p = edited(tmp_path_factory.mktemp("i4"), lambda wb: None)
    return api.check(p, select=["DMP"])


def test_rubber_ends_from_the_table(i4):
    q = i4.outcome.quantities
    d = q["damper.end_tuning_ratio"].detail
    phi = float(dmp.annulus_stiffness(1.0, 0.055, 0.059, 0.028))
    t = d.temperature
    ok = np.isfinite(t)
    assert ok.all()
    # k' = Phi_r G'(T) from the table, the tuning ratio sqrt(k'/J_ring) / w_n
    tab = dict((round(x[0], 6), x[1]) for x in d.table)
    g60 = tab[round(333.15, 6)]
    assert g60 * phi == pytest.approx(25500, rel=2e-4)  # the TVModel stiffness at 60 C
    np.testing.assert_allclose(q["damper.end_tuning_ratio"].values,
                               np.sqrt(d.stiffness / d.ring_inertia) / d.crank_mode_omega,
                               rtol=1e-12)
    # the rubber heats itself: T >= T_air, the cold end stiffer (higher tuning) than the hot
    t_air = np.array(d.air_temperature)[:, None, None]
    assert np.all(t >= t_air - 1e-9)
    assert np.all(d.stiffness[0] > d.stiffness[1])
    rules = {r.rule: r for r in i4.results}
    assert rules["DMP-005"].status == "fail" and "cold" in rules["DMP-005"].case


def test_table_at_the_nominal_properties_reproduces_the_nominal_damper(tmp_path):
    # a table with the nominal G' and loss factor at 60 (and 61) C, both ends at 60 C and a
    # heat path so good that the rubber stays at the air temperature (1e-7 K/W, the largest
    # h and A the workbook accepts): the ends
    # reproduce the TV section's damper (the rubber's properties are the same)
    phi = float(dmp.annulus_stiffness(1.0, 0.055, 0.059, 0.028))

    def edit(wb):
        ws = wb["DamperRubber"]
        for r in range(3, ws.max_row + 1):
            for c in range(1, 5):
                ws.cell(r, c).value = None
        for r, t in ((3, 60), (4, 61)):  # the same properties at 60 and 61 C
            ws.cell(r, 1).value, ws.cell(r, 2).value = t, 25500 / phi / 1e6
            ws.cell(r, 3).value = 0.15
        wd = wb["Damper"]
        for label, v in zip(NEW_DAMPER_ROWS, (60, 60, 1e5, 100)):
            wd.cell(param_row(wd, label), 2).value = v
        wd.cell(param_row(wd, "Damper cooled surface area"), 3).value = "m^2"

    res = api.check(edited(tmp_path, edit), select=["DMP"])
    q = res.outcome.quantities
    for e in range(2):
        np.testing.assert_allclose(q["damper.end_shear_stress"].values[e],
                                   q["damper.shear_stress"].values, rtol=1e-9)
        np.testing.assert_allclose(q["damper.end_heat_density"].values[e],
                                   q["damper.heat_density"].values, rtol=1e-9)
        np.testing.assert_allclose(q["damper.end_tuning_ratio"].values[e],
                                   q["damper.tuning_ratio"].values[0], rtol=1e-9)


def _legacy_rubber(wb):
    """Today's rubber damper: no temperature table, no temperature range, no heat path."""
    del wb["DamperRubber"]
    ws = wb["Damper"]
    for label in NEW_DAMPER_ROWS:
        ws.delete_rows(param_row(ws, label))


def test_todays_rubber_damper_gives_the_same_json_without_the_new_rules(tmp_path):
    # byte-identical JSON: a workbook with today's rubber damper, checked with the full rule
    # table and with the rule table without this change's rule file (DMP-005..010)
    p = edited(tmp_path, _legacy_rubber)
    rules = tmp_path / "rules"
    shutil.copytree(ROOT / "rules", rules)
    (rules / "damper_thermal.toml").unlink()
    levers = (rules / "levers.toml").read_text(encoding="utf-8")  # their levers go too
    blocks = levers.split("[[lever]]")
    levers = "[[lever]]".join(b for b in blocks if '"DMP-008"' not in b)
    (rules / "levers.toml").write_text(levers.replace(', "DMP-006", "DMP-007"', ""),
                                       encoding="utf-8")
    new_rules = {"DMP-005", "DMP-006", "DMP-007", "DMP-008", "DMP-009", "DMP-010"}
    full = api.check(p).to_dict(timings=False)
    old = api.check(p, rules=rules).to_dict(timings=False)
    # the new rules are listed as not applicable (issue 37 item 6), with their reason; every
    # other byte of the JSON is today's
    added = [r for r in full["results"] if r["rule"] in new_rules]
    assert {r["rule"] for r in added} == new_rules
    assert all(r["status"] == "not_applicable" for r in added)
    full["results"] = [r for r in full["results"] if r["rule"] not in new_rules]
    full["counts"]["not_applicable"] -= len(added)
    assert json.dumps(full, sort_keys=True) == json.dumps(old, sort_keys=True)
    assert not [n for n in full["quantities"] if n.startswith(("damper.end_",
                                                                 "damper.silicone"))]


def test_viscous_workbook_errors_name_the_cells(tmp_path):
    # a viscous damper keeps no rubber spring on its ring row, and one source for c
    def edit(wb):
        ws = wb["Damper"]
        r = ws.max_row + 1
        for label, v, u in (("Damper type", "viscous", "-"),
                            ("Viscous damping coefficient", 50, "N m s/rad"),
                            ("Silicone kinematic viscosity", 1e5, "mm^2/s")):
            ws.cell(r, 1).value, ws.cell(r, 2).value, ws.cell(r, 3).value = label, v, u
            r += 1

    from checker.errors import InputErrors

    with pytest.raises(InputErrors) as exc:
        api.check(edited(tmp_path, edit))
    text = str(exc.value)
    assert "TVModel" in text and "viscous damper's ring has no stiffness" in text
    assert "not both" in text


def test_cold_end_below_the_table_is_not_evaluated(tmp_path):
    def edit(wb):
        ws = wb["Damper"]
        ws.cell(param_row(ws, "Operating temperature, minimum"), 2).value = -60

    res = api.check(edited(tmp_path, edit), select=["DMP-006"])
    [r] = res.results
    assert r.status == "not_evaluated" and "outside the rubber table" in r.message
    q = res.outcome.quantities["damper.end_shear_stress"]
    assert np.isnan(q.values[0]).all() and np.isfinite(q.values[1]).all()
    assert any("outside the rubber table" in m for m in q.missing[(0,)])


def test_workbook_keeps_its_data(tmp_path):
    # the loader reads the DamperRubber table sorted by temperature, in SI
    p = edited(tmp_path, lambda wb: None)
    wb = openpyxl.load_workbook(p)
    assert wb["DamperRubber"].cell(3, 1).value == -40
    from checker.description.engine import load_engine

    e = load_engine(p)
    t = [x[0] for x in e.damper["rubber_table"]]
    assert t == sorted(t) and t[0] == pytest.approx(233.15)


def test_maxwell_silicone_in_the_torsional_solve(tmp_path):
    # the I6 with the silicone's shear modulus: k_s = G Phi in series with c (Andre & Spurk
    # 1982); the TV solve's damper power is sum 1/2 Omega Im z |dphi|^2 with that z
    content = i6_content(damper_ring=True)
    content["Damper"] = list(content["Damper"]) + [
        ("Silicone shear modulus", 2000, "Pa", "test")]
    p = tmp_path / "i6_maxwell.xlsx"
    write_workbook(p, content)
    res = api.check(p, select=["DMP"])
    q = res.outcome.quantities
    g = vd.GapGeometry(0.09, 0.13, 0.04, 0.0005, 0.0006)
    d = q["damper.optimum_damping"].detail
    assert d.shear_stiffness == pytest.approx(2000 * vd.couette_factor(g), rel=1e-12)
    pw = q["damper.power"]
    omega = pw.detail.orders * np.array(pw.coords["speed"])[:, None]
    z = vd.maxwell_impedance(omega, d.damping_nominal, d.shear_stiffness)
    np.testing.assert_allclose(pw.values, vd.impedance_power(pw.detail.dphi, omega, z).sum(-1),
                               rtol=1e-12)
    judged = [r for r in res.results if r.status != "not_applicable"]
    assert {r.rule for r in judged} == {"DMP-008", "DMP-009", "DMP-010"}
    assert all(r.value is not None for r in judged)


def _blank_heat_path(wb, labels=NEW_DAMPER_ROWS[2:]):
    ws = wb["Damper"]
    for label in labels:
        ws.cell(param_row(ws, label), 2).value = None


def test_blank_heat_path_means_no_self_heating(tmp_path):
    """Issue 43, item 4: blank 'Damper heat transfer coefficient' and 'Damper cooled surface
    area' mean no self-heating (docs/workbook.md), stated as an assumption: the rubber at
    the air temperature of each end, DMP-005..007 judged (they were not evaluated)."""
    res = api.check(edited(tmp_path, _blank_heat_path), select=["DMP"])
    status = {r.rule: r.status for r in res.results}
    assert all(status[r] not in ("not_evaluated", "not_applicable")
               for r in ("DMP-005", "DMP-006", "DMP-007")), status
    d = res.outcome.quantities["damper.end_tuning_ratio"].detail
    assert d.heat_resistance is None
    t_air = np.array(d.air_temperature)[:, None, None]
    np.testing.assert_array_equal(d.temperature, np.broadcast_to(t_air, d.temperature.shape))
    assert any("no self-heating" in a and "Damper!B" in a for a in res.assumptions)


def test_blank_heat_path_viscous_damper_at_the_air_temperature(tmp_path):
    content = i6_content(damper_ring=True)
    content["Damper"] = [r for r in content["Damper"] if r[0] not in NEW_DAMPER_ROWS[2:]]
    p = tmp_path / "i6-no-heat-path.xlsx"
    write_workbook(p, content)
    res = api.check(p, select=["DMP"])
    status = {r.rule: r.status for r in res.results}
    assert all(status[r] not in ("not_evaluated", "not_applicable")
               for r in ("DMP-008", "DMP-009", "DMP-010")), status
    q = res.outcome.quantities["damper.silicone_temperature"]
    t_air = np.array(q.detail.air_temperature)[:, None, None]
    np.testing.assert_array_equal(q.values, np.broadcast_to(t_air, q.values.shape))
    assert any("no self-heating" in a for a in res.assumptions)


def test_coefficient_without_its_area_is_not_evaluated_naming_the_area(tmp_path):
    res = api.check(edited(tmp_path, lambda wb: _blank_heat_path(
        wb, ("Damper cooled surface area",))), select=["DMP-006"])
    [r] = res.results
    assert r.status == "not_evaluated" and "Damper cooled surface area" in r.message


def test_blank_coefficient_alone_means_no_self_heating(tmp_path):
    """docs/workbook.md: a blank heat transfer coefficient is no self-heating (the area alone
    is no heat path)."""
    res = api.check(edited(tmp_path, lambda wb: _blank_heat_path(
        wb, ("Damper heat transfer coefficient",))), select=["DMP-006"])
    [r] = res.results
    assert r.status not in ("not_evaluated", "not_applicable"), r.message
    assert any("no self-heating" in a for a in res.assumptions)
