"""Bearing performance module on the example engine: heat balance closed on its own numbers,
flows and friction that add up, peak pressure bounds, supplier limits with °C conversion,
the film thickness at the heat-balance temperature, and the module skipped when not needed."""

from __future__ import annotations

import numpy as np
import pytest

from checker import api
from checker.calc import bearing_performance as bp
from checker.calc import orbit as ob
from checker.calc import viscosity as vs
from checker.modules.bearings import oil_fit
from checker.results.bearings import FilmDetail, FilmOrbit, FilmPressureDetail, HeatBalanceDetail
from tests.helpers import edited, example_path, set_cell, set_param

RPM = 2 * np.pi / 60


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return api.check(example_path(tmp_path_factory.mktemp("perf")),
                     select=["BRG-007", "BRG-008", "BRG-009"])


def test_results_are_typed(result):
    """Every bearing quantity carries its declared detail type (issue 24), with the orbits of
    the film-thickness calculation and the heat balance's record."""
    q = result.outcome.quantities
    for name, want in (("bearing.moft_short", FilmDetail), ("bearing.moft_finite", FilmDetail),
                       ("bearing.film_temperature", HeatBalanceDetail),
                       ("bearing.oil_flow", HeatBalanceDetail),
                       ("engine.bearing_friction_power", HeatBalanceDetail),
                       ("bearing.peak_film_pressure", FilmPressureDetail),
                       ("bearing.peak_film_pressure_short", FilmPressureDetail)):
        assert type(q[name].detail) is want, name
        assert q[name].spec.detail is want, name
        assert not hasattr(q[name], "extra"), name
    fin = q["bearing.moft_finite"].detail
    assert isinstance(fin.orbit, FilmOrbit)
    shape = q["bearing.moft_finite"].values.shape
    assert fin.orbit.eps_x.shape[:3] == (fin.orbit.rows.size,) + shape[1:]
    hb = q["bearing.film_temperature"].detail
    assert hb.evaluations >= 1 and hb.t_range[0] <= hb.t_range[1]
    assert set(hb.feeds) == set(q["bearing.film_temperature"].coords["item"])


def test_quantities_finite_and_consistent(result):
    q = result.outcome.quantities
    t = q["bearing.film_temperature"]
    for name in ("bearing.film_temperature", "bearing.friction_power", "bearing.side_flow",
                 "bearing.feed_flow", "bearing.oil_flow", "bearing.friction_torque",
                 "bearing.peak_film_pressure", "bearing.peak_film_pressure_short",
                 "engine.bearing_friction_power"):
        assert np.isfinite(q[name].values).all(), name
    # flows add up, engine friction is the sum of the bearings (definitions, to rounding)
    np.testing.assert_allclose(q["bearing.oil_flow"].values, q["bearing.side_flow"].values
                               + q["bearing.feed_flow"].values, rtol=1e-14)
    np.testing.assert_allclose(q["engine.bearing_friction_power"].values,
                               q["bearing.friction_power"].values.sum(axis=0), rtol=1e-12)
    # the film is warmer than the supply and friction grows with speed
    assert (t.values > t.detail.t_supply).all()
    p = q["engine.bearing_friction_power"].values
    assert (np.diff(p, axis=-1) > 0).all()
    # friction power = torque x relative speed on average for the mains (omega_bar = omega/2:
    # journal at omega, shell fixed): mean power >= mean torque x omega (squeeze adds power)
    names = t.coords["item"]
    sp = np.array(t.coords["speed"])
    mains = [i for i, n in enumerate(names) if t.item_attrs[n]["type"] == "main"]
    pw = q["bearing.friction_power"].values[mains]
    tq = q["bearing.friction_torque"].values[mains]
    assert (pw >= tq * sp * (1 - 1e-9)).all()


def test_heat_balance_closes_on_its_own_numbers(result):
    """Energy: T_eff - T_s = 0.5 f P / (rho c_p Q) with the reported P and Q, within the
    solver's convergence band (0.1 K tolerance; residual up to ~2.3 x tol, calc tests)."""
    q = result.outcome.quantities
    t = q["bearing.film_temperature"].values
    p = q["bearing.friction_power"].values
    flow = q["bearing.oil_flow"].values
    ts = q["bearing.film_temperature"].detail.t_supply
    rho_cp = vs.oil_density(t, vs.DENSITY_15C_DEFAULT) * bp.oil_specific_heat(
        t, vs.DENSITY_15C_DEFAULT)
    balance = ts + 0.5 * p / (rho_cp * flow)
    np.testing.assert_allclose(t, balance, atol=0.25)


def test_peak_pressure_at_least_the_specific_load(result):
    """Physics bound: the peak film pressure of a bearing carrying F over its projected area
    L D is at least F / (L D) (the film force is the integral of the pressure)."""
    q = result.outcome.quantities
    bl = q["loads.bearing_load"]
    eng = result.engine
    bearings = {b.name: b for b in eng.bearings}
    for name in ("bearing.peak_film_pressure", "bearing.peak_film_pressure_short"):
        pm = q[name].values
        for i, n in enumerate(bl.coords["item"]):
            b = bearings[n]
            bound = bl.values[i] / (b.length * b.diameter)
            assert (pm[i] >= bound * 0.999).all(), (name, n)


def test_peak_pressure_short_equals_orbit_solver(result):
    """The short-bearing peak pressure is the orbit solver's, at the film temperature used for
    the film thickness (one main, full load, 3000 rpm)."""
    q = result.outcome.quantities
    bl = q["loads.bearing_load"]
    eng = result.engine
    b = eng.bearings[0]
    k = int(np.argmin(np.abs(np.array(bl.coords["speed"]) - 3000 * RPM)))
    t_film = eng.oil["supply_temperature"] + (eng.oil.get("temperature_rise") or 0.0)
    mu = float(oil_fit(eng)[0].viscosity(t_film))
    ex = bl.detail
    res = ob.solve_orbit(ex.fy[0, 0, k], ex.fx[0, 0, k], ex.omega_journal[0, 0, k],
                         ex.omega_bearing[0, 0, k], bl.coords["speed"][k], b.diameter,
                         b.length, b.clearance, mu, peak_pressure=True)
    assert q["bearing.peak_film_pressure_short"].values[0, 0, k] == pytest.approx(
        float(res.p_max), rel=1e-9)


def test_not_evaluated_names_the_supplier_cells(result):
    ne = [r for r in result.results if r.status == "not_evaluated"]
    assert {r.rule for r in ne} == {"BRG-007", "BRG-008", "BRG-009"}
    assert all("Bearings!" in r.missing[0] and "supplier" in r.missing[0] for r in ne)


def test_supplier_limits_in_celsius_judged(tmp_path, result):
    """A max film temperature of 135 °C on M3 fails where the film is hotter (°C is an offset
    unit: the rule layer converts affinely) and a min flow above the computed one fails."""
    t = result.outcome.quantities["bearing.film_temperature"]
    i = t.coords["item"].index("M3")
    hottest = float(np.max(t.values[i])) - 273.15
    flow = result.outcome.quantities["bearing.oil_flow"]
    least = float(np.min(flow.values[i])) * 6e4

    def edit(wb):
        set_cell(wb, "Bearings", "name", "M3", "max film temperature", 135)
        set_cell(wb, "Bearings", "name", "M2", "max film temperature", 200)
        set_cell(wb, "Bearings", "name", "M3", "min oil flow", round(least * 1.5, 4))

    res = api.check(edited(tmp_path, edit), select=["BRG-007", "BRG-009"])
    by = {(r.rule, r.item): r for r in res.results}
    r7 = by[("BRG-007", "M3")]
    # judged worst: the hottest judged point (full load beyond the data is not judged)
    judged = t.values[i][t.applies[i]] if t.applies is not None else t.values[i]
    assert r7.status == "fail" and r7.value == pytest.approx(
        float(judged.max()) - 273.15, abs=0.05)
    assert 135 < r7.value <= hottest + 1e-9
    assert r7.limit_values == [pytest.approx(135.0)]
    assert by[("BRG-007", "M2")].status == "pass"
    r9 = by[("BRG-009", "M3")]
    assert r9.status == "fail" and r9.value == pytest.approx(least, rel=1e-3)


def test_film_thickness_at_heat_balance_temperature(tmp_path, result):
    """Oil 'Film temperature' = heat balance: the film-thickness orbits run at each point's
    effective temperature (hotter, thinner oil: thinner film), equal to a direct orbit."""
    def edit(wb):
        set_param(wb, "Oil", "Film temperature", "heat balance")

    res = api.check(edited(tmp_path, edit), select=["BRG-003", "BRG-005"])
    base = api.check(example_path(tmp_path, "base.xlsx"), select=["BRG-003", "BRG-005"])
    h_hb = res.outcome.quantities["bearing.moft_short"].values
    h_0 = base.outcome.quantities["bearing.moft_short"].values
    assert (h_hb < h_0).all()
    assert "bearing_performance" in res.outcome.modules_run
    assert "bearing_performance" not in base.outcome.modules_run
    t = res.outcome.quantities["bearing.film_temperature"].values
    bl = res.outcome.quantities["loads.bearing_load"]
    eng = res.engine
    b = eng.bearings[5]
    k = 10
    mu = float(oil_fit(eng)[0].viscosity(t[5, 0, k]))
    ex = bl.detail
    direct = ob.solve_orbit(ex.fy[5, 0, k], ex.fx[5, 0, k], ex.omega_journal[5, 0, k],
                            ex.omega_bearing[5, 0, k], bl.coords["speed"][k], b.diameter,
                            b.length, b.clearance, mu)
    assert h_hb[5, 0, k] == pytest.approx(float(direct.h_min), rel=1e-9)


def test_heat_balance_not_converged_is_reported(tmp_path, monkeypatch):
    """A balance stopped before it converges is a finding and the film temperature is not
    evaluated there (never a silent value)."""
    from checker.modules import bearing_performance as bpm

    monkeypatch.setattr(bpm, "HEAT_BALANCE_MAX_EVALUATIONS", 1)

    def edit(wb):
        set_cell(wb, "Bearings", "name", "M1", "max film temperature", 150)

    res = api.check(edited(tmp_path, edit), select=["BRG-007"])
    t = res.outcome.quantities["bearing.film_temperature"]
    bad = np.argwhere(np.isnan(t.values))
    assert len(bad) > 0
    for idx in bad:  # every point left out carries the finding
        assert any("heat balance not converged" in f for f in t.findings[tuple(int(x)
                                                                            for x in idx)])
    assert sum("heat balance not converged" in f for v in t.findings.values()
               for f in v) == len(bad)
    m1 = next(r for r in res.results if r.item == "M1")
    assert np.isnan(t.values[0]).any()
    assert m1.status == "not_evaluated" and m1.value is None
    assert any("heat balance not converged" in m for m in m1.missing)


def test_feed_hole_outside_formula_validity_is_named(tmp_path):
    """A feed hole too large for the strip-source formula (a / b > 0.5) leaves that bearing's
    flow and temperature not evaluated, naming the cell; the other bearings are computed."""
    cell = {}

    def edit(wb):
        cell["c"] = set_cell(wb, "Bearings", "name", "BE1", "oil hole diameter", 12)

    res = api.check(edited(tmp_path, edit), select=["BRG-007", "BRG-009"])
    t = res.outcome.quantities["bearing.film_temperature"]
    i = t.coords["item"].index("BE1")
    assert np.isnan(t.values[i]).all() and np.isfinite(np.delete(t.values, i, axis=0)).all()
    be1 = [r for r in res.results if r.item == "BE1"]
    assert be1 and all(any(cell["c"] in m and "validity" in m for m in r.missing) for r in be1)
