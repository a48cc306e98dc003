"""Per-bearing reuse of journal orbits: a variant's films equal its cold evaluation."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from checker import api
from checker.description.engine import Engine, load_engine
from checker.modules import film_memo
from checker.outputs.formats import to_json
from tests.helpers import example_path


@pytest.fixture(scope="module")
def engine(tmp_path_factory) -> Engine:
    return load_engine(example_path(tmp_path_factory.mktemp("memo")))


def _scaled(engine: Engine, names: set[str], **factors: float) -> Engine:
    assert names <= {b.name for b in engine.bearings}
    rows = tuple(dataclasses.replace(b, **{k: getattr(b, k) * f for k, f in factors.items()})
                 if b.name in names else b for b in engine.bearings)
    return dataclasses.replace(engine, bearings=rows)


def _films(res) -> list[np.ndarray]:
    out = []
    for q in ("bearing.moft", "bearing.moft_short", "bearing.moft_finite"):
        if q in res.outcome.quantities:
            x = res.outcome.quantities[q]
            out += [x.values, x.detail.eps_max,
                    x.detail.orbit.eps_x if x.detail.orbit is not None else np.zeros(0)]
    return out


@pytest.mark.parametrize("names", [{"M3"}, {"BE1"}, {"M1", "BE2"}, {"M1", "M5"}])
def test_variant_with_memo_equals_cold(engine, names):
    film_memo.clear()
    api.check(engine, select=["BRG-003"])  # fills the memo with today's orbits
    base_hits, base_solved = film_memo.stats["hits"], film_memo.stats["solved"]
    variant = _scaled(engine, names, clearance=1.2)
    warm = api.check(variant, select=["BRG-003"])
    hits = film_memo.stats["hits"] - base_hits
    solved = film_memo.stats["solved"] - base_solved
    film_memo.clear()
    cold = api.check(variant, select=["BRG-003"])
    assert film_memo.stats["hits"] == 0
    assert to_json(warm, timings=False) == to_json(cold, timings=False)
    for a, b in zip(_films(warm), _films(cold), strict=True):
        assert np.array_equal(a, b, equal_nan=True)
    models = base_solved // len(engine.bearings)  # film models solved (short, finite)
    assert models >= 1 and solved + hits == base_solved
    if names == {"M3"}:
        # only M3 is solved again: the other bearings come from the memo
        assert solved == models
    if names == {"BE1"}:
        # the big ends' orbits are one orbit shifted: all four are solved again together
        assert solved == 4 * models


def test_memo_does_not_change_the_baseline(engine):
    film_memo.clear()
    cold = api.check(engine, select=["BRG-003"])
    again = api.check(engine, select=["BRG-003"])
    assert film_memo.stats["hits"] > 0
    assert to_json(again, timings=False) == to_json(cold, timings=False)
