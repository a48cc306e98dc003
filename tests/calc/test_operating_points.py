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


def test_full_load_target_by_hand_and_held_outside_the_table():
    from checker.calc.operating_points import full_load_target_imep

    rpm = np.pi / 30
    vd = 2.0e-3  # 2 l
    ws = np.array([1000.0, 3000.0]) * rpm
    tb = np.array([150.0, 190.0])
    speeds = np.array([800.0, 2000.0, 3000.0, 3500.0]) * rpm
    t, held = full_load_target_imep(speeds, ws, tb, vd)
    # by hand at 2000 rpm: T = 170 N m, BMEP = 4 pi 170 / 2e-3, FMEP = 0.97 + 0.3 + 0.2 bar
    assert t[1] == pytest.approx(4 * np.pi * 170 / vd + 1.47e5, rel=1e-12)
    # 3000 rpm: FMEP = 0.97 + 0.45 + 0.45 bar
    assert t[2] == pytest.approx(4 * np.pi * 190 / vd + 1.87e5, rel=1e-12)
    # held: below at the 1000 rpm value (FMEP 1.17 bar), above at the 3000 rpm value
    assert t[0] == pytest.approx(4 * np.pi * 150 / vd + 1.17e5, rel=1e-12)
    assert t[3] == t[2]
    np.testing.assert_allclose(held / rpm, [1000, 2000, 3000, 3000], rtol=1e-12)
    with pytest.raises(ValueError):
        full_load_target_imep(speeds, ws[::-1], tb, vd)
