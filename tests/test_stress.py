"""Numerical stress tests (issue 7): extreme speeds and L/D, every module finite or flagged,
never NaN or a hang. Film collapse and undamped resonance are in the module tests
(tests/modules/test_moft_module.py, test_torsion_module.py)."""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from checker import api
from checker.description.engine import Params, load_engine
from checker.evaluation import graph
from tests.helpers import example_path

RPM = np.pi / 30


@pytest.fixture(scope="module")
def engine(tmp_path_factory):
    return load_engine(example_path(tmp_path_factory.mktemp("stress")))


def _speeds(e, lo, hi, step):
    new = copy.copy(e)
    new.params = Params({**e.params, "speed_min": lo * RPM, "speed_max": hi * RPM,
                         "speed_step": step * RPM, "overspeed": None})
    return new


def _finite_or_flagged(res):
    for name, q in res.outcome.quantities.items():
        bad = ~np.isfinite(q.values)
        # a non-finite entry must be an explained missing value, never a silent NaN/inf
        for idx in zip(*np.nonzero(bad)):
            idx = tuple(int(i) for i in idx)
            assert any(idx[:n] in q.missing for n in range(len(idx), 0, -1)), (name, idx)


@pytest.mark.parametrize("lo,hi,step", [(300, 900, 300), (9000, 12000, 1500)])
def test_very_low_and_very_high_speeds(engine, lo, hi, step):
    res = api.check(_speeds(engine, lo, hi, step))
    _finite_or_flagged(res)
    for name in ("bearing.moft_finite", "bearing.moft_short"):  # BRG-003..006
        moft = res.outcome.quantities[name]
        assert np.isfinite(moft.values).all() and (moft.values > 0).all()
    text = " ".join(res.assumptions)
    assert "extrapolation" in text  # outside the pressure data: said, not silent


@pytest.mark.parametrize("ld", [0.12, 1.0])
def test_extreme_length_to_diameter(engine, ld):
    e = _speeds(engine, 1000, 7000, 1500)
    e.bearings = tuple(dataclasses.replace(b, length=ld * b.diameter) for b in engine.bearings)
    q = graph.run(e, ["bearing.moft"]).quantities["bearing.moft"]
    assert np.isfinite(q.values).all() and (q.values > 0).all()
    assert (q.values < np.array([b.clearance for b in e.bearings])[:, None, None]).all()


@pytest.fixture(scope="module")
def loads_4000(engine):
    base = _speeds(engine, 4000, 4000, 1000)
    return base, graph.run(base, ["loads.bearing_load"]).quantities["loads.bearing_load"]


def _scaled(q, k):
    detail = dataclasses.replace(q.detail, fx=q.detail.fx * k, fy=q.detail.fy * k)
    return dataclasses.replace(q, values=q.values * k, detail=detail)


@settings(max_examples=10, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(c=st.floats(0.015e-3, 0.05e-3), factor=st.floats(1.1, 1.6),
       scale=st.floats(1.1, 2.0))
def test_moft_trends_random(loads_4000, c, factor, scale):
    """More clearance at fixed load -> more eccentricity; more load -> less MOFT (every
    bearing, full and no load, 4000 rpm)."""
    from checker.modules.bearings import moft

    base, q = loads_4000

    def run(e, k=1.0):
        return moft(e, {"loads.bearing_load": _scaled(q, k)})["bearing.moft"]

    e1 = copy.copy(base)
    e1.bearings = tuple(dataclasses.replace(b, clearance=c) for b in base.bearings)
    e2 = copy.copy(base)
    e2.bearings = tuple(dataclasses.replace(b, clearance=c * factor) for b in base.bearings)
    q1, q2, q3 = run(e1), run(e2), run(e1, scale)
    assert (q2.detail.eps_max > q1.detail.eps_max).all()
    assert (q3.values < q1.values).all()
