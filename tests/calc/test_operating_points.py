"""Pressure traces carried across the speed sweep and the full-load data range
(checker.calc.operating_points)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.operating_points import data_envelope, traces_at_speeds


def test_traces_equal_numpy_interp_at_every_crank_angle():
    # reference: numpy.interp column by column (same arithmetic: results bit for bit)
    rng = np.random.default_rng(3)
    table = np.array([104.7, 209.4, 314.2, 523.6])
    traces = rng.uniform(1e5, 9e6, (4, 720))
    speeds = np.array([50.0, 104.7, 150.0, 209.4, 400.0, 523.6, 600.0])
    out, ex = traces_at_speeds(table, traces, speeds)
    want = np.stack([np.interp(speeds, table, traces[:, k]) for k in range(720)], axis=1)
    np.testing.assert_array_equal(out, want)
    assert ex.tolist() == [True, False, False, False, False, False, True]


def test_hand_values_midway_and_held_outside():
    # halfway between 1000 and 2000 rpm: the mean of the two traces; outside: held
    out, ex = traces_at_speeds([1000.0, 2000.0], [[10.0, 20.0], [30.0, 60.0]],
                               [500.0, 1500.0, 1750.0, 2500.0])
    np.testing.assert_allclose(out, [[10, 20], [20, 40], [25, 50], [30, 60]], rtol=1e-15)
    assert ex.tolist() == [True, False, False, True]


def test_single_trace_is_held_everywhere():
    out, ex = traces_at_speeds([300.0], [[1.0, 2.0, 3.0]], [100.0, 300.0, 500.0])
    np.testing.assert_array_equal(out, [[1, 2, 3]] * 3)
    assert ex.tolist() == [True, False, True]


def test_bad_tables_are_refused():
    with pytest.raises(ValueError, match="increase"):
        traces_at_speeds([2.0, 1.0], [[1.0], [2.0]], [1.5])
    with pytest.raises(ValueError, match="must be"):
        traces_at_speeds([1.0, 2.0], [1.0, 2.0], [1.5])
    with pytest.raises(ValueError, match="finite"):
        traces_at_speeds([1.0, 2.0], [[1.0], [2.0]], [np.nan])


def test_envelope_is_the_data_range_with_tolerance():
    s = np.array([100.0, 150.0, 200.0, 250.0])
    assert data_envelope(s, [150.0 + 5e-10, 200.0]).tolist() == [False, True, True, False]
    assert data_envelope(s, [90.0, 300.0]).all()
    with pytest.raises(ValueError):
        data_envelope(s, [])
