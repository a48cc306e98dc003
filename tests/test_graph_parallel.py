"""checker.evaluation.graph.run with ``parallel``: the calculations marked ``separate`` (the
bearings'
heat balance) computed in a forked process give the outcome of a run in one process, value
for value and in the same order (the outputs list quantities and assumptions in it)."""

from __future__ import annotations

import os

import numpy as np
import pytest

from checker import api
from checker.evaluation import graph
from checker.workbook.example import example_content, write_workbook


@pytest.fixture(scope="module")
def engine(tmp_path_factory):
    p = tmp_path_factory.mktemp("par") / "engine.xlsx"
    write_workbook(p, example_content())
    return api.check(p).engine


def _same(a, b) -> None:
    assert list(a.quantities) == list(b.quantities)
    assert list(a.unavailable.items()) == list(b.unavailable.items())
    assert a.ran == b.ran and a.modules_run == b.modules_run
    for name, q in a.quantities.items():
        np.testing.assert_array_equal(np.asarray(q.values), np.asarray(b.quantities[name].values))


def test_heat_balance_is_marked_separate():
    assert graph.CALCULATIONS["bearing_heat_balance"].separate


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: nothing is forked")
def test_parallel_run_gives_the_outcome_of_one_process(engine, monkeypatch):
    wanted = sorted(graph.PROVIDER)  # every quantity of the graph
    one = graph.run(engine, wanted)
    from checker.plumbing import forked

    started = []
    real = forked.ForkedCall.__init__

    def spy(self, fn, *args):
        real(self, fn, *args)
        started.append(self.forked)

    monkeypatch.setattr(forked.ForkedCall, "__init__", spy)
    two = graph.run(engine, wanted, parallel=True)
    assert started == [True]  # the heat balance went to a forked process
    _same(two, one)
    assert "bearing_performance" in two.timings


def test_parallel_run_with_a_cache_fills_it_as_one_process_does(engine):
    wanted = ["bearing.film_temperature", "bearing.moft"]
    c1: dict = {}
    c2: dict = {}
    graph.run(engine, wanted, cache=c1)
    graph.run(engine, wanted, cache=c2, parallel=True)
    assert set(c1) == set(c2)
    again = graph.run(engine, wanted, cache=c2, parallel=True)
    assert "bearing_heat_balance" in again.reused
