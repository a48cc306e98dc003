"""Balancing module on the example engines: free forces and moments, balance ratio, internal
bending moment, workbook limits and skipping."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from checker import api
from checker.description.engine import MassItem, load_engine
from checker.evaluation import graph
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content
from tests.helpers import analyses_run, edited, example_path, set_param

RPM = 2 * np.pi / 60


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("bal"))


@pytest.fixture(scope="module")
def result(example):
    return api.check(example, select=["BAL"])


def test_only_the_balance_module_runs(result):
    # no load calculation is needed: free forces are inertia forces of the moving parts
    assert analyses_run(result.outcome) == ["balance"]


def test_example_i4_free_forces_closed_form(result):
    # Taylor 1985 vol. 2 ch. 8: flat I4 1-3-4-2 with a mirror-symmetric crank: no 1st-order
    # force, secondary 4 m_rec r w^2 (lam + lam^3/4 + 15 lam^5/128) from the seed's masses
    # (m_rec = 0.4955 + 0.597 x 35.73/145.7 kg, r = 47.3 mm, l = 145.7 mm) at 6000 rpm; the
    # 0.8 mm pin offset changes it by O((e/l)^2) ~ 3e-5 and the series truncation by ~5e-5.
    q = result.outcome.quantities["balance.free_force"]
    m_rec = 0.4955 + 0.597 * 35.73 / 145.7
    r, lam, w = 0.0473, 47.3 / 145.7, 6000 * RPM
    f2 = 4 * m_rec * r * w * w * (lam + lam**3 / 4 + 15 * lam**5 / 128)
    scale = 4 * m_rec * r * w * w
    assert q.values[0] < 1e-12 * scale and q.values[2] < 1e-9 * scale
    assert q.values[1] == pytest.approx(f2, rel=2e-4)
    assert q.values[1] == pytest.approx(15998, rel=1e-3)
    m = result.outcome.quantities["balance.free_moment"]
    assert np.all(m.values < 1e-12 * scale)


def test_example_balance_ratio_and_internal_moment_from_the_sheet(result):
    # Ricardo 2013 crank masses per throw: webs 2 x 0.659 kg at 26.763 mm, pin 0.341 kg at
    # r - 0.1 mm, rod big end 0.597 (1 - 35.73/145.7) kg at r; counterweights 2 x 0.794 kg at
    # 37.611 mm opposite. Every throw is symmetric about its mid-bay, so the bending moment at
    # the centre main is the net throw unbalance x one bay (96 mm) x w^2.
    r = 0.0473
    u_rot = 2 * 0.659 * 0.026763 + 0.341 * (r - 0.0001) + 0.597 * (1 - 35.73 / 145.7) * r
    u_cw = 2 * 0.794 * 0.037611
    q = result.outcome.quantities["balance.balance_ratio"]
    np.testing.assert_allclose(q.values, u_cw / u_rot, rtol=1e-9)
    assert q.coords["item"][-1] == "crank"
    im = result.outcome.quantities["balance.internal_moment"]
    w2 = (6000 * RPM) ** 2
    assert im.values[2] == pytest.approx((u_rot - u_cw) * 0.096 * w2, rel=1e-9)
    assert im.values[0] < 1e-9 and im.values[-1] < 1e-6 * im.values[2]
    assert im.detail.without_counterweights[2] == pytest.approx(u_rot * 0.096 * w2, rel=1e-9)


def test_rules_use_the_workbook_limits(result):
    by = {(r.rule, r.item): r for r in result.results}
    r2 = by[("BAL-002", "order 2")]
    assert r2.status == "fail" and r2.severity == "warning"  # 16.0 kN > 10 kN (illustrative)
    assert r2.limit_values == [pytest.approx(10000.0)] and "Engine!" in r2.message
    assert by[("BAL-001", "order 1")].status == "pass"
    assert {r.status for r in result.results if r.rule == "BAL-005"} == {"pass"}


def test_missing_limit_is_not_evaluated_and_names_the_cell(tmp_path):
    cells = {}

    def edit(wb):
        cells["f"] = set_param(wb, "Engine", "Free force limit, 2nd order")
        ws = wb["Engine"]
        for row in ws.iter_rows(min_col=1, max_col=2):
            if str(row[0].value).startswith(("Free force limit, 2nd", "Balance ratio, max")):
                row[1].value = None

    res = api.check(edited(tmp_path, edit), select=["BAL-002", "BAL-005"])
    by = {(r.rule, r.item): r for r in res.results}
    r2 = by[("BAL-002", "order 2")]
    assert r2.status == "not_evaluated" and cells["f"] in r2.missing[0]
    assert all(r.status == "not_evaluated" and "Balance ratio, maximum" in r.missing[0]
               for r in res.results if r.rule == "BAL-005")


def test_inline_six_with_a_symmetric_crank_has_no_free_forces_or_moments(tmp_path):
    # The I6 example (Mendes et al. 2008) with its 8-counterweight crank made mirror- and
    # rotation-symmetric (counterweights on every throw): every free force and moment of the
    # orders 1-5, 7, 8 is zero to round-off (Taylor 1985 vol. 2 ch. 8); the 6th-order force
    # 6 m_rec r w^2 A_6 remains (all cylinders in phase), ~ lam^5.
    p = tmp_path / "i6.xlsx"
    write_workbook(p, i6_content())
    eng = load_engine(p)
    items = []
    for t in range(1, 7):
        g = -float(eng.cylinders[t - 1].firing_angle)  # throw angle [rad]
        e = np.array([np.sin(g), np.cos(g)])
        for kind, m, rad, ax in (("web", 2.2, 0.0377, 0.0315), ("web", 2.2, 0.0377, 0.0985),
                                 ("counterweight", 1.65, -0.058, 0.0315),
                                 ("counterweight", 1.65, -0.058, 0.0985)):
            items.append(MassItem(f"{kind}{t}{ax}", t, kind, m, 0.0, rad * e[1], rad * e[0],
                                  ax, "main axis"))
        items.append(MassItem(f"pin{t}", t, "pin", 1.0, 0.0, 0.0, 0.0, 0.065, "pin axis"))
    eng = dataclasses.replace(eng, crank_mass=tuple(items))
    out = graph.run(eng, ["balance.free_force", "balance.free_moment"])
    f = out.quantities["balance.free_force"]
    m = out.quantities["balance.free_moment"]
    p6 = eng.params
    m_rec = p6["piston_mass"] + p6["rod_mass"] * p6["rod_com"] / p6["rod_length"]
    w = f.detail.omega
    scale = 6 * m_rec * p6["stroke"] / 2 * w * w
    keep = f.detail.orders != 6
    assert np.all(f.values[keep] < 1e-12 * scale)
    assert np.all(m.values < 1e-12 * scale)
    assert f.values[5] == pytest.approx(6 * m_rec * abs(f.detail.harmonics[6]) * w * w,
                                        rel=1e-9)


def test_skipped_when_no_rule_needs_it(example):
    res = api.check(example, select=["JNT"])
    assert {"balance", "flywheel", "damper"} <= set(res.outcome.modules_skipped)


def test_report_section(result):
    from checker.report.section_balance import balance_section

    sec = balance_section(result)
    types = [b["type"] for b in sec["blocks"]]
    assert types.count("figure") == 2 and "equations" in types  # bar chart + polar diagram
    forces = next(b for b in sec["blocks"] if b["type"] == "table"
                  and b["caption"].startswith("Free forces"))
    assert [r[1] for r in forces["rows"]][:4] == ["0", "15998", "0", "445.34"]  # N, 6000 rpm
    drawn = " ".join(t for b in sec["blocks"] if b["type"] == "figure" for t in b["png"].texts)
    assert "Order" in drawn and "without counterweights" in drawn  # bar chart + polar
