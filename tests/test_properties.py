"""Property-based tests over physically valid random engines (hypothesis): no crash, all
outputs finite, known monotonic trends hold (issue 7)."""

from __future__ import annotations

import copy

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from checker import api
from checker.description.engine import Engine, Params, load_engine
from tests.helpers import example_path

SETTINGS = settings(max_examples=12, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture,
                                           HealthCheck.too_slow])


@pytest.fixture(scope="module")
def base_engine(tmp_path_factory) -> Engine:
    return load_engine(example_path(tmp_path_factory.mktemp("prop")))


def variant(e: Engine, **params) -> Engine:
    new = copy.copy(e)
    p = dict(e.params)
    p.update(params)
    new.params = Params(p)
    return new


engines = st.fixed_dictionaries({
    "bore": st.floats(0.06, 0.13),
    "stroke": st.floats(0.06, 0.14),
    "lam": st.floats(0.22, 0.36),  # crank radius / rod length
    "piston_mass": st.floats(0.2, 2.0),
    "rod_mass": st.floats(0.3, 2.5),
    "com": st.floats(0.2, 0.35),  # rod CoM / rod length from the big end
    "compression_ratio": st.floats(8.0, 20.0),
    "pin_offset": st.floats(-0.002, 0.002),
})


@SETTINGS
@given(engines)
def test_random_engines_give_finite_results(base_engine, g):
    rod = g["stroke"] / 2 / g["lam"]
    e = variant(base_engine, bore=g["bore"], stroke=g["stroke"], rod_length=rod,
                piston_mass=g["piston_mass"], rod_mass=g["rod_mass"], rod_com=g["com"] * rod,
                rod_inertia=g["rod_mass"] * rod**2 * 0.08,
                compression_ratio=g["compression_ratio"], pin_offset=g["pin_offset"])
    res = api.check(e, select=["BRG", "JNT"])
    for q in res.outcome.quantities.values():
        v = q.values[np.isfinite(q.values) | ~np.isnan(q.values)]
        assert np.all(np.isfinite(v)), q.name
    spec = res.outcome.quantities["bearing.peak_specific_load"].values
    assert np.all(np.isfinite(spec)) and np.all(spec > 0)
    assert {r.status for r in res.results} <= {"pass", "fail", "not_evaluated", "not_applicable"}


@SETTINGS
@given(st.floats(0.3, 1.5), st.floats(1.05, 1.5))
def test_heavier_piston_raises_no_load_big_end_peak(base_engine, m, factor):
    # inertia dominates at no load and maximum speed: more reciprocating mass, more load
    a = api.check(variant(base_engine, piston_mass=m), select=["BRG-002"])
    b = api.check(variant(base_engine, piston_mass=m * factor), select=["BRG-002"])
    qa = a.outcome.quantities["bearing.peak_specific_load"]
    qb = b.outcome.quantities["bearing.peak_specific_load"]
    i = qa.coords["item"].index("BE1")
    assert qb.values[i, 1, -1] > qa.values[i, 1, -1]
