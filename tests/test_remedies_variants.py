"""Variant evaluation (checker.remedies.variants): batched film orbits, the per-bearing film
memo and the calculation cache give the numbers of a cold check of each variant."""

from __future__ import annotations

import pytest

from checker import api
from checker.description.engine import build_engine
from checker.errors import InputErrors
from checker.evaluation.ruletable import load_rules
from checker.modules import film_memo
from checker.outputs.formats import to_json
from checker.remedies.variants import Evaluator, bind
from checker.workbook.loader import convert_raw, read_raw_workbook
from checker.workbook.schema import SHEETS


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    from checker.workbook.example import example_content, write_workbook

    p = tmp_path_factory.mktemp("var") / "engine.xlsx"
    write_workbook(p, example_content())
    return p


def _field(sheet: str, attr: str):
    return next(f for f in SHEETS[sheet].fields if f.attr == attr)


def test_batched_variants_equal_cold_checks(i4):
    base = read_raw_workbook(i4)
    table = load_rules()
    clear = bind(base, "Bearings", (_field("Bearings", "clearance"),), "um", ("M3",), ())
    clear_b = bind(base, "Bearings", (_field("Bearings", "clearance"),), "um", ("BE2",), ())
    assert not isinstance(clear, str) and not isinstance(clear_b, str)
    c0, cb0 = clear.nominal[0], clear_b.nominal[0]
    changes = [clear.changes(c0 * 1.15), clear.changes(c0 * 0.9),
               {**clear.changes(c0 * 1.1), **clear_b.changes(cb0 * 1.2)},
               clear.changes(-5.0)]  # a negative clearance: an input error
    ev = Evaluator(base, table, select=["BRG-003", "BRG-004"])
    api.check(i4, select=["BRG-003", "BRG-004"], cache=ev.cache)  # the check's own cache
    got = ev.evaluate_variants(changes)
    assert ev.evaluations == len(changes)
    assert isinstance(got[-1], InputErrors)
    for ch, res in zip(changes[:-1], got[:-1]):
        film_memo.clear()
        engine = build_engine(convert_raw(base.with_values(ch), raise_errors=False))
        cold = api.check(engine, select=["BRG-003", "BRG-004"], compare=False)
        assert to_json(res, timings=False) == to_json(cold, timings=False)
        # without the compared film: the same values, statuses and margins
        full = api.check(engine, select=["BRG-003", "BRG-004"])
        assert [(r.rule, r.item, r.status, r.value, r.margin) for r in res.results] == [
            (r.rule, r.item, r.status, r.value, r.margin) for r in full.results]
        assert sum(len(r.compare) for r in res.results) < sum(len(r.compare)
                                                              for r in full.results)
    # one by one (batch of 1) gives the same results
    ev1 = Evaluator(base, table, select=["BRG-003", "BRG-004"], batch=1)
    for a, b in zip(got[:-1], ev1.evaluate_variants(changes[:-1])):
        assert to_json(a, timings=False) == to_json(b, timings=False)


def test_helper_processes_give_the_same_results(i4):
    """Variants shared with a forked helper process: the rule results of each are those of
    this process alone (the helper returns them without the calculated quantities)."""
    base = read_raw_workbook(i4)
    table = load_rules()
    sel = ["BRG-003", "BRG-004", "JNT"]
    clear = bind(base, "Bearings", (_field("Bearings", "clearance"),), "um", ("M2",), ())
    assert not isinstance(clear, str)
    c0 = clear.nominal[0]
    changes = [clear.changes(c0 * f) for f in (0.8, 0.9, 1.1, 1.2)] + [clear.changes(-1.0)]
    alone = Evaluator(base, table, select=sel)
    api.check(i4, select=sel, cache=alone.cache)
    want = alone.evaluate_variants(changes)
    shared = Evaluator(base, table, select=sel)
    api.check(i4, select=sel, cache=shared.cache)
    shared.start_workers(2)
    try:
        assert shared.workers == 2
        got = shared.evaluate_variants(changes)
        again = shared.evaluate_variants(changes[:2])  # the same helper meets them again
    finally:
        shared.release()
    assert shared.workers == 1 and shared.evaluations == len(changes) + 2
    assert isinstance(got[-1], InputErrors)
    for a, b in zip(want[:-1] + want[:2], got[:-1] + again):
        assert [r.as_dict() for r in a.results] == [r.as_dict() for r in b.results]


def test_groups_shared_with_a_helper_equal_one_process(i4):
    """Groups of variants (each on its own rules) spread over a helper process: the same rule
    results as one process, in the order asked."""
    base = read_raw_workbook(i4)
    table = load_rules()
    clear = bind(base, "Bearings", (_field("Bearings", "clearance"),), "um", ("M3",), ())
    torque = bind(base, "Joints", (_field("Joints", "tightening_torque"),), "N m",
                  ("crank nose",), ())
    assert not isinstance(clear, str) and not isinstance(torque, str)
    groups = [([clear.changes(clear.nominal[0] * f) for f in (0.9, 1.1)], ["BRG-003"]),
              ([torque.changes(torque.nominal[0] * f) for f in (0.8, 0.9, 1.1)], ["JNT"]),
              ([clear.changes(clear.nominal[0] * 0.8)], ["BRG-004"])]
    alone = Evaluator(base, table)
    want = alone.evaluate_groups(groups)
    shared = Evaluator(base, table)
    shared.start_workers(2)
    try:
        got = shared.evaluate_groups(groups)
    finally:
        shared.release()
    assert shared.evaluations == alone.evaluations == 6
    assert [len(g) for g in got] == [2, 3, 1]
    for a, b in zip(want, got):
        for x, y in zip(a, b):
            assert [r.as_dict() for r in x.results] == [r.as_dict() for r in y.results]


def test_input_errors_of_a_variant_without_calculating(i4):
    """A width beyond its journal is an invalid workbook, known from the cells alone (the
    root finding then does not pack that trial value with other items' values)."""
    base = read_raw_workbook(i4)
    width = bind(base, "Bearings", (_field("Bearings", "length"),), "mm", ("BE1",), ())
    assert not isinstance(width, str)
    ev = Evaluator(base, load_rules())
    assert ev.input_errors(width.changes(width.nominal[0] * 1.05)) is None
    err = ev.input_errors(width.changes(width.nominal[0] * 10.0))
    assert isinstance(err, InputErrors)
    assert any(e.where.startswith("Bearings!") for e in err.errors)
    assert ev.evaluations == 0 and not ev.cache


def test_corners_in_their_own_process_equal_one_process(i4):
    """With remedies and more than one process the corners are checked in a forked process
    of their own: the same corners as in one process."""
    from checker.remedies import attach

    out = []
    for workers in (1, 2):
        cache: dict = {}
        res = api.check(i4, select=["JNT"], cache=cache)
        attach(res, remedies=True, corners=True, cache=cache, select=["JNT"],
               workers=workers)
        out.append(([c.as_dict() for c in res.corners["results"]],
                    res.corners["evaluations"],
                    [x.as_dict() for x in res.remedies["results"]]))
    assert out[0] == out[1]
    assert out[0][1] > 0 and any(c["worst"] for c in out[0][0])
