"""Rules whose limit is the engine's own workbook value (``limit_from = "workbook"``)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.errors import RuleFileError
from checker.evaluation.graph import Quantity, QuantitySpec
from checker.evaluation.ruletable import Rule, evaluate_rule, load_rules

RULE = '''
[[rule]]
id = "BAL-901"
name = "x"
quantity = "balance.free_force"
where = { order = "2" }
check = "<="
limit_from = "workbook"
unit = "N"
severity = "warning"
source = "test"
rationale = "test"
'''


def _q(values, attrs):
    spec = QuantitySpec("balance.free_force", "N", ("item",), "test", filters=("order",))
    items = [f"order {i + 1}" for i in range(len(values))]
    return Quantity(spec, np.array(values, float), {"item": items},
                    {it: dict(a) for it, a in zip(items, attrs)})


def test_rule_file_with_workbook_limit_loads(tmp_path):
    p = tmp_path / "r.toml"
    p.write_text(RULE)
    [r] = load_rules(p).rules
    assert r.limit_from == "workbook" and r.limit is None and r.limit_text() == "≤ workbook limit"
    p.write_text(RULE.replace('limit_from = "workbook"', 'limit_from = "workbook"\nlimit = 3'))
    with pytest.raises(RuleFileError, match="not both"):
        load_rules(p)
    p.write_text(RULE.replace('limit_from = "workbook"', 'limit_from = "table"'))
    with pytest.raises(RuleFileError, match="limit_from must be"):
        load_rules(p)


def test_workbook_limit_is_used_per_item_and_missing_is_not_evaluated():
    rule = Rule("BAL-901", "x", "balance.free_force", "<=", "kN", "warning", "s", "r",
                where={"order": ("1", "2")}, limit_from="workbook")
    q = _q([1500.0, 900.0], [
        {"order": "1", "limit_missing": ["Engine!B31: Free force limit, 1st order"]},
        {"order": "2", "limit": (1000.0,), "limit_cell": "Engine!B32"}])
    first, second = evaluate_rule(rule, q, None)
    assert first.status == "not_evaluated" and first.missing == [
        "Engine!B31: Free force limit, 1st order"]
    assert first.limit_missing == first.missing  # not evaluated for its blank limit
    assert second.status == "pass" and second.value == pytest.approx(0.9)  # kN
    assert second.limit_values == [pytest.approx(1.0)] and "Engine!B32" in second.message
    assert second.margin == pytest.approx(0.1) and second.limit_missing == []
    q.item_attrs["order 2"]["limit"] = (800.0,)
    [_, second] = evaluate_rule(rule, q, None)
    assert second.status == "fail"


def test_workbook_range():
    rule = Rule("DMP-901", "x", "balance.free_force", "between", "N", "warning", "s", "r",
                limit_from="workbook")
    q = _q([0.95], [{"limit": (0.9, 1.0)}])
    [res] = evaluate_rule(rule, q, None)
    assert res.status == "pass" and res.limit.startswith("0.9..1")
    q.item_attrs["order 1"]["limit"] = (1.0,)  # wrong arity: treated as not given
    [res] = evaluate_rule(rule, q, None)
    assert res.status == "not_evaluated"
