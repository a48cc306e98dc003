"""Batched variant evaluation (:func:`checker.api.check_batch`) gives exactly the numbers of
checking each variant on its own."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from checker import api
from checker.description.engine import Engine, load_engine
from checker.outputs.formats import to_json
from tests.helpers import example_path


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Engine:
    return load_engine(example_path(tmp_path_factory.mktemp("batch")))


def _variant(engine: Engine, main_clearance: float | None = None,
             supply_c: float | None = None, main_length: float | None = None) -> Engine:
    bearings = []
    for b in engine.bearings:
        if b.type == "main":
            if main_clearance is not None:
                b = replace(b, clearance=main_clearance)
            if main_length is not None:
                b = replace(b, length=main_length)
        bearings.append(b)
    oil = type(engine.oil)(engine.oil)
    if supply_c is not None:
        oil["supply_temperature"] = supply_c + 273.15
    return replace(engine, bearings=tuple(bearings), oil=oil)


def test_batched_and_one_by_one_give_identical_results(base):
    mains = [b for b in base.bearings if b.type == "main"]
    c0, l0 = mains[0].clearance, mains[0].length
    engines = [
        base,
        _variant(base, main_clearance=0.8 * c0),
        _variant(base, main_clearance=1.3 * c0, supply_c=110.0),
        _variant(base, main_length=0.9 * l0),
        _variant(base, supply_c=90.0),
    ]
    select = ["BRG"]
    batched = api.check_batch(engines, select=select)
    single = [api.check(e, select=select) for e in engines]
    assert len(batched) == len(engines)
    for b, s in zip(batched, single):
        # byte-identical JSON of the results and the quantities (run times left out)
        assert to_json(b, timings=False) == to_json(s, timings=False)
        for name, q in s.outcome.quantities.items():
            assert np.array_equal(b.outcome.quantities[name].values, q.values, equal_nan=True)
    # the variants differ (the batch did not return one variant's numbers for all)
    h = [r.outcome.quantities["bearing.moft_short"].values for r in batched]
    assert not np.allclose(h[0], h[1], equal_nan=True)


def _count_kernel_calls(monkeypatch) -> list[str]:
    """The mobility model of every orbit-kernel call from now on (in the list returned)."""
    from checker.calc import orbit

    calls: list[str] = []
    real = orbit.solve_orbit

    def counting(*a, **k):
        calls.append(k.get("model", "closed_form"))
        return real(*a, **k)

    monkeypatch.setattr(orbit, "solve_orbit", counting)
    return calls


def test_batched_film_orbits_are_one_kernel_call(base, monkeypatch):
    calls = _count_kernel_calls(monkeypatch)
    mains = [b for b in base.bearings if b.type == "main"]
    engines = [_variant(base, main_clearance=f * mains[0].clearance) for f in (0.9, 1.0, 1.1)]
    api.check_batch(engines, select=["BRG-003", "BRG-004", "BRG-005", "BRG-006"])
    # film thickness (no heat balance selected): one short-bearing and one finite-length
    # orbit call for the three variants
    assert sorted(calls) == ["closed_form", "reynolds_map"]


def test_each_engine_on_its_own_selection(base, monkeypatch):
    """``selects``: variants checked on different rules in one batch give the results of
    checking each on its own rules, and their film orbits are still one kernel call."""
    mains = [b for b in base.bearings if b.type == "main"]
    engines = [_variant(base, main_clearance=0.9 * mains[0].clearance),
               _variant(base, supply_c=95.0), base]
    selects = [["BRG-003"], ["BRG-004", "JNT-001"], ["FAT"]]
    with monkeypatch.context() as m:
        calls = _count_kernel_calls(m)
        batched = api.check_batch(engines, selects=selects, compare=False)
    assert calls == ["reynolds_map"]
    for b, e, sel in zip(batched, engines, selects):
        s = api.check(e, select=sel, compare=False)
        assert to_json(b, timings=False) == to_json(s, timings=False)
        assert b.results and all(any(r.rule.startswith(x) for x in sel) for r in b.results)
    with pytest.raises(ValueError, match="one selection per engine"):
        api.check_batch(engines, selects=[["BRG"]])
