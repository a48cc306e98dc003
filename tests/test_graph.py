"""The calculation graph's shared helpers: the resonant-peak mask within an operating envelope."""

from __future__ import annotations

import numpy as np

from checker.evaluation.graph import resonant_peaks


def _resonance(speed: np.ndarray, critical: float, zeta: float) -> np.ndarray:
    """Amplitude of a single-degree-of-freedom resonance, |1 / (1 - r^2 + 2 j zeta r)| with
    r = speed / critical (closed form, e.g. Den Hartog, Mechanical Vibrations, 1956, ch. 2)."""
    r = speed / critical
    return np.abs(1.0 / (1.0 - r ** 2 + 2j * zeta * r))


def test_flank_rising_into_the_envelope_top_is_judged_there():
    # resonance at 6800 rpm, envelope (data range) up to 6500 rpm, sweep to 7000 rpm: the only
    # resonant point inside the envelope is its top speed, where the flank still rises
    speed = np.arange(1000.0, 7001.0, 100.0)
    amp = _resonance(speed, 6800.0, 0.05)
    env = speed <= 6500.0
    m = resonant_peaks(amp, envelope=env)
    assert speed[m].tolist() == [6500.0]
    assert amp[m].max() == amp[env].max()  # the true maximum within the envelope
    # without the envelope the sweep's interior peak at 6800 rpm is the peak (outside the data)
    assert speed[resonant_peaks(amp)].tolist() == [6800.0]


def test_peak_outside_the_envelope_is_not_judged_and_interior_peak_inside_is():
    a = np.array([5.0, 4.0, 3.0, 3.5, 2.0, 1.0, 1.5, 1.2])
    env = np.array([True, True, True, True, True, True, False, False])
    # interior maximum at index 3 inside; the peak at index 6 lies outside; the envelope top
    # (index 5) is reached falling, so it is not a peak
    assert resonant_peaks(a, envelope=env).tolist() == [False, False, False, True,
                                                       False, False, False, False]
    # rolling-mode fall from the lowest speed: never judged, with or without an envelope
    fall = np.array([9.0, 8.0, 7.0, 6.0, 5.0])
    assert not resonant_peaks(fall).any()
    assert not resonant_peaks(fall, envelope=np.array([False, False, True, True, True])).any()


def test_falling_flank_at_the_envelope_bottom_is_judged_when_a_resonance_lies_below():
    # a resonance below the envelope (peak at index 3) falls through the envelope's first speed
    a = np.array([5.0, 4.0, 6.0, 8.0, 7.0, 6.0, 5.0])
    env = np.array([False, False, False, False, True, True, True])
    assert resonant_peaks(a, envelope=env).tolist() == [False] * 4 + [True, False, False]
    # two envelope ranges in one curve: each has its own top
    b = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    env2 = np.array([True, True, False, True, True, False])
    assert resonant_peaks(b, envelope=env2).tolist() == [False, True, False, False, True, False]


def test_envelope_broadcasts_over_orders_and_cases():
    # (order, case, speed) values with a (case, speed) envelope: full load to index 3, no load
    # everywhere; both cases rise to the end of the sweep
    v = np.tile(np.arange(1.0, 7.0), (2, 2, 1))
    env = np.array([[True] * 4 + [False] * 2, [True] * 6])
    m = resonant_peaks(v, axis=-1, envelope=env)
    assert m.shape == v.shape
    for o in range(2):
        assert np.flatnonzero(m[o, 0]).tolist() == [3]
        assert np.flatnonzero(m[o, 1]).tolist() == [5]
