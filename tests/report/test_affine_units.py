"""Every quantity shown in an offset (affine) unit, °C, reads right in every output: JSON, text,
results workbook and the compare JSON. A temperature converted by a factor (403.6 K x
-272.15 = -109,846 °C) instead of by an offset must fail here.

Independent reference: pint's own conversion of each SI value (kelvin -> degree Celsius).
"""

from __future__ import annotations

import io
import json

import numpy as np
import openpyxl
import pytest
from click.testing import CliRunner

from checker import api
from checker.cli import main
from checker.evaluation import graph
from checker.outputs.formats import to_json, to_text
from checker.report import results_book
from checker.workbook.units import Q_
from tests.helpers import edited, set_param

RULE = "BRG-007"  # the effective film temperature, judged in °C


def _is_affine(si: str, unit: str) -> bool:
    """True when converting ``si`` to ``unit`` needs an offset (K -> °C)."""
    if not unit or unit in ("-", "%") or si == unit:
        return False
    try:
        return float(Q_(0.0, si or "").to(unit).magnitude) != 0.0
    except Exception:  # noqa: BLE001 - incompatible: not this test's concern
        return False


def _celsius(kelvin):
    return np.asarray(Q_(np.asarray(kelvin, dtype=float), "kelvin").to("degC").magnitude)


def _with_limit(limit: float, supply: float):
    def edit(wb):
        ws = wb["RuleOverrides"]
        ws.cell(3, 1).value, ws.cell(3, 2).value = RULE, str(limit)
        ws.cell(3, 3).value, ws.cell(3, 4).value = "°C", "test limit"
        set_param(wb, "Oil", "Oil supply temperature", supply, "°C")
    return edit


@pytest.fixture(scope="module")
def books(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("affine")
    base = edited(tmp, _with_limit(150.0, 130.0), "base.xlsx")
    var = edited(tmp, _with_limit(150.0, 110.0), "var.xlsx")
    return base, var


@pytest.fixture(scope="module")
def result(books):
    return api.check(books[0], select=[RULE])


def _affine_quantities(res) -> dict[str, str]:
    """Quantity -> display unit, for every computed quantity shown in an offset unit (by a
    rule's unit or its declared display unit)."""
    out = {}
    for q in res.outcome.quantities.values():
        disp = results_book.display_unit(res, q)
        if _is_affine(q.spec.unit, disp) or _is_affine(q.spec.unit, q.spec.display_unit or ""):
            out[q.name] = disp
    return out


def test_the_example_has_affine_quantities(result):
    aff = _affine_quantities(result)
    assert "bearing.film_temperature" in aff
    # every declared quantity in K is found by the helper above (so none escapes the test)
    graph.ensure_registered()
    declared = {n for n, s in graph.QUANTITIES.items() if s.unit == "K"
                and _is_affine("K", s.display_unit or "")}
    assert declared <= set(aff) | (declared - set(result.outcome.quantities))


def test_rule_results_json_and_text(result):
    q = result.outcome.quantities["bearing.film_temperature"]
    d = json.loads(to_json(result, timings=False))
    text = to_text(result)
    rows = [r for r in d["results"] if r["rule"] == RULE]
    assert rows and all(r["unit"] == "°C" for r in rows)
    items = list(q.coords["item"])
    for r, rr in zip(rows, [x for x in result.results if x.rule == RULE], strict=True):
        i = items.index(r["item"])
        vals = np.where(np.asarray(q.applies)[i] if q.applies is not None else True,
                        q.values[i], -np.inf)
        expected = float(_celsius(np.max(vals)))
        assert 20.0 < r["value"] < 300.0, r
        assert r["value"] == pytest.approx(expected, rel=1e-5)
        assert r["limit"] == [150.0]
        assert rr.value_text in text and rr.value_text.endswith("°C")
    # the quantity itself is given in SI (K), absolute
    jq = d["quantities"]["bearing.film_temperature"]
    assert jq["unit"] == "K"
    tops = [x["max"] for x in jq["over_speed"] if x]
    assert tops and all(300.0 < t < 600.0 for t in tops)
    np.testing.assert_allclose(max(tops), np.nanmax(q.values), rtol=1e-5)


def test_results_workbook(result):
    wb = openpyxl.load_workbook(io.BytesIO(results_book.build(result)), read_only=True)
    aff = _affine_quantities(result)
    for name in aff:
        q = result.outcome.quantities[name]
        rows = list(wb[results_book.sheet_name(name)].iter_rows(values_only=True))
        assert rows[1][0] == "unit: °C", (name, rows[1])
        lead = len(q.spec.dims) - 1
        got = np.array([r[lead:lead + q.values.shape[-1]] for r in rows[3:3 + int(
            np.prod(q.values.shape[:-1]))]], dtype=float)
        want = _celsius(q.values).reshape(got.shape)
        np.testing.assert_allclose(got, want, rtol=1e-9, equal_nan=True)
        assert np.nanmin(got) > 0.0 and np.nanmax(got) < 300.0
    res_rows = list(wb["Rule results"].iter_rows(values_only=True))
    hdr = res_rows[0]
    for row in res_rows[1:]:
        if row[0] == RULE:
            assert row[hdr.index("unit")] == "°C"
            assert 20.0 < row[hdr.index("value")] < 300.0


def test_compare_json(books, result):
    r = CliRunner().invoke(main, ["compare", str(books[0]), str(books[1]), "--select", RULE,
                                  "--format", "json"])
    assert r.exit_code in (0, 1), r.output
    doc = json.loads(r.stdout)
    comps = doc if isinstance(doc, list) else doc.get("comparisons", [doc])
    changes = [c for comp in comps for c in comp["result_changes"] if c["rule"] == RULE]
    assert changes
    base = {x.item: x for x in result.results if x.rule == RULE}
    for c in changes:
        b, v = c["baseline"], c["variant"]
        assert b["unit"] == v["unit"] == "°C"
        assert b["value"] == pytest.approx(base[c["item"]].value, rel=1e-5)
        # 20 K colder oil: a colder film, but an absolute temperature in °C
        assert 20.0 < v["value"] < b["value"] < 300.0
