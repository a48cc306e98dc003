"""Project limits of a first layout (issue 47, item 3): a rule the project declares not
applicable (RuleOverrides limit 'not applicable' with its reason), the free-force defaults."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from checker.description.engine import RuleOverride
from checker.evaluation.ruletable import evaluate_rule, load_rules, override_problems
from checker.sizing.project_limits import SUPPLIER_RULES, free_limits, override_rows


def test_not_applicable_override_gives_the_reason_and_needs_one():
    table = load_rules()
    rules, applied, errs = override_problems(table, [
        RuleOverride("BRG-007", "not applicable", "-", "no shell supplier yet", "RuleOverrides!B3"),
        RuleOverride("BRG-008", "N/A", None, "", "RuleOverrides!B4")])
    assert [a.new for a in applied] == ["not applicable"]
    assert len(errs) == 1 and "BRG-008 declared not applicable: expected the reason" in str(
        errs[0])
    r = next(x for x in rules if x.id == "BRG-007")
    [res] = evaluate_rule(r, None, None)
    assert res.status == "not_applicable"
    assert "no shell supplier yet" in res.message and "RuleOverrides" in res.message


def test_supplier_rules_rows():
    rows = override_rows()
    assert [r[0] for r in rows] == list(SUPPLIER_RULES)
    assert all(r[1] == "not applicable" and "supplier" in r[3] for r in rows)


def test_free_limits_take_the_crank_type_and_a_floor():
    q = SimpleNamespace(coords={"item": ["order 1", "order 2", "order 4"]},
                        values=np.array([0.0, 20000.0, 5.0]))
    res = SimpleNamespace(outcome=SimpleNamespace(quantities={"balance.free_force": q,
                                                              "balance.free_moment": q}))
    lim = free_limits(res, m_rec=0.5, crank_radius=0.05, speed=600.0, pitch=0.1)
    floor = 0.01 * 0.5 * 0.05 * 600.0**2  # 1 % of one cylinder's primary force: 90 N
    assert lim["force_1"] == pytest.approx(floor)
    assert lim["force_2"] == 21000  # +5 %
    assert lim["moment_1"] == pytest.approx(floor * 0.1)
