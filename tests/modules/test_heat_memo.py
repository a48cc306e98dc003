"""Per-bearing reuse of the bearing heat balance: a variant's check equals its cold evaluation
(no memo, no calculation cache), bit for bit."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from checker import api
from checker.description.engine import build_engine
from checker.evaluation.ruletable import load_rules
from checker.modules import film_memo, heat_memo
from checker.outputs.formats import to_json
from checker.remedies.variants import Evaluator, bind
from checker.workbook.loader import convert_raw, read_raw_workbook
from checker.workbook.schema import SHEETS

HEAT = ("bearing.film_temperature", "bearing.friction_power", "bearing.friction_power_peak",
        "bearing.friction_torque", "bearing.friction_torque_peak", "bearing.side_flow",
        "bearing.feed_flow", "bearing.oil_flow", "engine.bearing_friction_power")


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    from checker.workbook.example import example_content, write_workbook

    p = tmp_path_factory.mktemp("heat") / "engine.xlsx"
    write_workbook(p, example_content())  # the I4 template (checker template --engine i4)
    return read_raw_workbook(p)


def _field(sheet: str, attr: str):
    return next(f for f in SHEETS[sheet].fields if f.attr == attr)


def _changes(base, sheet: str, attr: str, unit: str, rows, factor: float) -> dict:
    b = bind(base, sheet, (_field(sheet, attr),), unit, rows, ())
    assert not isinstance(b, str), b
    return b.changes(b.nominal[0] * factor)


def _same(a, b) -> bool:
    """Equal values, bit for bit (arrays, dataclasses, containers)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype != b.dtype or a.shape != b.shape:
            return False
        if a.dtype.kind == "f":
            return bool(np.array_equal(a.view(np.int64 if a.itemsize == 8 else np.int32),
                                       b.view(np.int64 if b.itemsize == 8 else np.int32)))
        return bool(np.array_equal(a, b))
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(
            _same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
    if isinstance(a, dict):
        return (isinstance(b, dict) and list(a) == list(b)
                and all(_same(a[k], b[k]) for k in a))
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(map(_same, a, b))
    if isinstance(a, float) and isinstance(b, float):
        return np.float64(a).tobytes() == np.float64(b).tobytes()
    return a == b


def _assert_identical(warm, cold) -> None:
    assert to_json(warm, timings=False) == to_json(cold, timings=False)
    qw, qc = warm.outcome.quantities, cold.outcome.quantities
    assert list(qw) == list(qc)
    assert all(q in qw for q in HEAT)
    for name in qw:
        assert _same(qw[name], qc[name]), name  # values, findings, missing, detail...


def _engine(base, changes: dict):
    return build_engine(convert_raw(base.with_values(changes), raise_errors=False))


def _cold(engine):
    film_memo.clear()
    heat_memo.clear()
    res = api.check(engine)
    assert heat_memo.stats["hits"] == 0
    return res


@pytest.fixture(scope="module")
def nominal(i4):
    return _engine(i4, {})


def _variants(base) -> dict[str, dict]:
    return {
        "main clearance": _changes(base, "Bearings", "clearance", "um", ("M3",), 1.2),
        "big-end width": _changes(base, "Bearings", "length", "mm", ("BE2",), 0.9),
        "supply temperature": _changes(base, "Oil", "supply_temperature", "degC", None, 1.1),
    }


@pytest.mark.parametrize("what", ["main clearance", "big-end width", "supply temperature"])
def test_variant_with_memo_equals_cold(i4, nominal, what):
    changes = _variants(i4)[what]
    film_memo.clear()
    heat_memo.clear()
    api.check(nominal)  # fills the memos with the nominal engine's bearings
    n_rows = heat_memo.stats["solved"]
    assert n_rows == 9 and heat_memo.stats["hits"] == 0  # I4: 5 mains, 4 big ends
    variant = _engine(i4, changes)
    warm = api.check(variant)
    hits, solved = heat_memo.stats["hits"], heat_memo.stats["solved"] - n_rows
    assert hits + solved == n_rows
    _assert_identical(warm, _cold(variant))
    if what == "main clearance":
        assert solved < n_rows  # the other bearings come from the memo
    if what == "big-end width":
        assert 1 <= solved < n_rows
    if what == "supply temperature":
        assert hits == 0  # every bearing's balance moves


def test_variant_then_back_to_nominal(i4, nominal):
    film_memo.clear()
    heat_memo.clear()
    cold = api.check(nominal)
    api.check(_engine(i4, _variants(i4)["main clearance"]))
    before = heat_memo.stats["solved"]
    again = api.check(nominal)
    assert heat_memo.stats["solved"] == before  # every bearing from the memo
    _assert_identical(again, cold)


def test_evaluator_variants_equal_cold_checks(i4):
    """The remedies' variant evaluation (calculation cache, batched films, both memos)."""
    v = _variants(i4)
    changes = [v["main clearance"], v["big-end width"],
               {**v["main clearance"], **v["big-end width"]}, {}]
    film_memo.clear()
    heat_memo.clear()
    ev = Evaluator(i4, load_rules(), select=["BRG"])
    got = ev.evaluate_variants(changes)
    assert heat_memo.stats["hits"] > 0
    for ch, res in zip(changes, got):
        film_memo.clear()
        heat_memo.clear()
        cold = api.check(_engine(i4, ch), select=["BRG"], compare=False)
        assert to_json(res, timings=False) == to_json(cold, timings=False)
        for name in HEAT:
            assert _same(res.outcome.quantities[name], cold.outcome.quantities[name]), name


def test_clear_and_memory_bound(i4, nominal):
    film_memo.clear()
    heat_memo.clear()
    api.check(nominal)
    assert heat_memo.stats["solved"] == 9 and 0 < heat_memo._memo.bytes <= heat_memo.MAX_BYTES
    heat_memo.clear()
    assert heat_memo._memo.bytes == 0 and not heat_memo._memo
    assert heat_memo.stats == {"hits": 0, "solved": 0}
