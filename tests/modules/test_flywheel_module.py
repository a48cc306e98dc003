"""Flywheel module on the example engine: cyclic irregularity from the loads module's torque,
the rule at the lowest speed, the minimum flywheel inertia and the target from the workbook."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from checker import api
from checker.calc.kinematics import FOUR_STROKE_CYCLE
from checker.workbook.example import TV_MODEL
from tests.helpers import analyses_run, edited, example_path, set_param

RPM = 2 * np.pi / 60


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return api.check(example_path(tmp_path_factory.mktemp("fly")), select=["FLY"])


def test_inertia_is_the_whole_torsional_model(result):
    q = result.outcome.quantities["flywheel.cyclic_irregularity"]
    j = sum(r[3] for r in TV_MODEL[1])  # seed 000 chain: ring, nose, 4 cylinders, flywheel
    assert q.detail.inertia_total == pytest.approx(j, rel=1e-12)
    assert q.detail.inertia_flywheel == pytest.approx(0.174743, rel=1e-12)
    assert analyses_run(result.outcome) == ["loads", "flywheel"]


def test_lowest_speed_against_direct_integration(result):
    # Independent: integrate J dw/dt = T(theta) - T_mean over one cycle (DOP853) with the
    # loads module's total torque at 1000 rpm full load (periodic linear interpolation of its
    # 1 deg samples), starting from the speed the module gives at theta = 0; the time-mean
    # speed must be 1000 rpm and (w_max - w_min)/w_avg the module's delta (tolerance 3e-4:
    # linear vs spectral interpolation of the 1 deg torque samples; measured 3e-5).
    q = result.outcome.quantities["flywheel.cyclic_irregularity"]
    ex = q.detail
    th, tq = ex.theta, ex.torque[0, 0]
    j = ex.inertia_total
    t_mean = tq.mean()
    period = FOUR_STROKE_CYCLE
    step = th[1] - th[0]

    def rhs(_t, y):  # periodic linear interpolation of the 1 deg torque samples
        x = (y[0] % period) / step
        k = int(x)
        f = x - k
        t = tq[k % tq.size] * (1 - f) + tq[(k + 1) % tq.size] * f
        return [y[1], (t - t_mean) / j]

    def done(_t, y):
        return y[0] - period

    done.terminal = True
    sol = solve_ivp(rhs, (0, 1.0), [0.0, ex.omega[0, 0, 0]], method="DOP853", rtol=1e-7,
                    atol=1e-7, events=done, dense_output=True)
    t_cyc = sol.t_events[0][0]
    w = sol.sol(np.linspace(0, t_cyc, 100_001))[1]
    assert period / t_cyc == pytest.approx(1000 * RPM, rel=1e-4)
    delta = (w.max() - w.min()) / (period / t_cyc)  # over the time-mean speed
    assert q.values[0, 0] == pytest.approx(delta, rel=3e-4)
    # the midrange speed (w_max + w_min)/2 would give a measurably different value
    assert abs(delta / ((w.max() - w.min()) / ((w.max() + w.min()) / 2)) - 1) > 3e-3
    assert 0.10 < q.values[0, 0] < 0.20  # seed I4, 0.2077 kg m^2, full load at 1000 rpm


def test_rule_judges_the_lowest_speed_only(result):
    q = result.outcome.quantities["flywheel.cyclic_irregularity"]
    [r] = [x for x in result.results if x.rule == "FLY-001"]
    assert r.value == pytest.approx(100 * q.values[:, 0].max(), rel=1e-9)
    assert "1000 rpm" in r.case and r.limit_values == [pytest.approx(10.0)]
    assert r.status == "fail"  # 14.8 % > 10 % (illustrative target of the example)


def test_minimum_flywheel_meets_the_target(result, tmp_path):
    q = result.outcome.quantities["flywheel.minimum_inertia"]
    need = q.values[0, 0] + q.detail.inertia_rest  # total inertia at 1000 rpm full load

    def edit(wb):
        ws = wb["TVModel"]
        for row in ws.iter_rows(min_row=3):
            if row[1].value == "flywheel":
                row[3].value = float(q.values[0, 0])

    res = api.check(edited(tmp_path, edit), select=["FLY"])
    ci = res.outcome.quantities["flywheel.cyclic_irregularity"]
    assert ci.detail.inertia_total == pytest.approx(need, rel=1e-12)
    assert ci.values[0, 0] == pytest.approx(0.10, rel=1e-6)


def test_without_target_not_evaluated(tmp_path):
    cell = {}

    def edit(wb):
        cell["c"] = set_param(wb, "Engine", "Target cyclic irregularity")
        ws = wb["Engine"]
        ws[cell["c"].split("!")[1]].value = None

    res = api.check(edited(tmp_path, edit), select=["FLY"])
    [r] = res.results
    assert r.status == "not_evaluated" and cell["c"] in r.missing[0]


def test_report_section_states_the_target(result):
    from checker.report.section_flywheel import flywheel_section

    sec = flywheel_section(result)
    assert "δ ≤ 10 %" in sec["intro"] and "Engine!B" in sec["intro"]
    types = [b["type"] for b in sec["blocks"]]
    assert types.count("figure") == 1 and "equations" in types
    table = next(b for b in sec["blocks"] if b["type"] == "table"
                 and b["caption"].startswith("Fluctuation energy"))
    assert table["rows"][0][:2] == ["full load", "1000"]
