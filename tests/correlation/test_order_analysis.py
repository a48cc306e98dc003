"""Order analysis of angle-domain signals against signals of known orders (closed forms)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.correlation import order_analysis as oa
from checker.correlation.measurement import read_measurement

from .synth import signal_csv

# known orders: amplitude [deg] and phase [rad] (4-stroke half orders and integer orders)
KNOWN = {0.5: (0.020, 0.3), 1.0: (0.050, -1.2), 2.0: (0.110, 2.0), 3.5: (0.008, 0.7),
         4.0: (0.070, -0.4), 6.0: (0.015, 1.1)}


def _angle(theta: np.ndarray) -> np.ndarray:
    return sum(a * np.cos(n * theta + p) for n, (a, p) in KNOWN.items())


def test_known_orders_exact():
    """A sum of half orders sampled per crank angle: every amplitude and phase back to
    round-off (each half order lies on a bin of a whole 720 deg cycle: no leakage)."""
    n = 360
    th = np.arange(8 * n) * (4 * np.pi / n)
    spec = oa.order_spectrum(_angle(th) + 0.3, n, sorted(KNOWN))
    for o, c in zip(spec.orders, spec.coeffs):
        a, p = KNOWN[o]
        assert abs(c) == pytest.approx(a, rel=1e-10)
        assert np.angle(c) == pytest.approx(p, abs=1e-9)
    assert spec.mean == pytest.approx(0.3, rel=1e-12)
    assert spec.cycles == 8 and spec.resolution == 0.5
    assert np.all(spec.leakage < 1e-12)


def test_noisy_signal_within_one_percent():
    """3 % (of the largest order) white noise on every sample, 32 cycles averaged: the known
    amplitudes within 1 % (Brandt 2011: the averaged coefficient's error falls as 1/sqrt(cycles
    x samples))."""
    n = 360
    th = np.arange(32 * n) * (4 * np.pi / n)
    rng = np.random.default_rng(7)
    x = _angle(th) + 0.03 * 0.11 * rng.standard_normal(th.size)
    spec = oa.order_spectrum(x, n, sorted(KNOWN))
    for o, c in zip(spec.orders, spec.coeffs):
        assert abs(c) == pytest.approx(KNOWN[o][0], rel=0.01)
    assert np.all(spec.scatter > 0)


def test_drift_leakage_bound_is_the_sawtooth():
    """A mean that drifts by d per cycle (a ramp) leaks exactly d / (2 pi n) into order n:
    the bound stated equals what the transform finds for a pure ramp."""
    n, d = 720, 0.4
    th = np.arange(6 * n) * (4 * np.pi / n)
    x = d * th / (4 * np.pi)
    spec = oa.order_spectrum(x, n, [0.5, 1.0, 2.0, 5.5])
    assert spec.leakage == pytest.approx(d / (2 * np.pi * spec.orders), rel=1e-12)
    assert np.abs(spec.coeffs) == pytest.approx(spec.leakage, rel=2e-3)


def test_speed_to_angle():
    """Speed fluctuation W cos(n theta) integrates to an angle W / (n w) sin(n theta)."""
    c = oa.angle_from_speed(np.array([2.0 + 0j]), np.array([3.0]), 100.0)
    assert c[0] == pytest.approx(2.0 / (1j * 3.0 * 100.0))


def test_limits():
    with pytest.raises(ValueError, match="above the highest order"):
        oa.order_spectrum(np.zeros(80), 40, [10.0])
    with pytest.raises(ValueError, match="multiples of 0.5"):
        oa.order_spectrum(np.zeros(80), 40, [1.25])
    assert oa.highest_order(40) == 9.5


def test_signal_file_known_orders(tmp_path):
    """A signal file (two runs, vibratory angle in deg, 2 deg steps, a run starting mid-cycle
    and a partial cycle at its end) read and analysed: the known amplitudes within 1 %."""
    p = signal_csv(tmp_path / "sig.csv", "crank nose", [
        {"rpm": 1500, "cycles": 6, "signal": _angle},
        {"rpm": 2500, "cycles": 5, "start": 360.0, "extra": 100, "signal": _angle}])
    m = read_measurement(p, [0.5, 1, 2, 3.5, 4, 6])
    assert m.kind == "angle-domain signal"
    assert m.speeds == pytest.approx(np.array([1500, 2500]) * np.pi / 30)
    for j, o in enumerate(m.orders):
        assert np.degrees(m.amplitude[:, j]) == pytest.approx(KNOWN[o][0], rel=0.01)
    assert [r.cycles for r in m.runs] == [6, 4]


def test_speed_signal_file(tmp_path):
    """An instantaneous-speed signal (rpm): the angle amplitudes W / (n w) and the
    irregularity (w_max - w_min) / w_mean of the cycle."""
    w_rpm, amp_rpm = 1200.0, 24.0

    def speed(theta):
        return w_rpm + amp_rpm * np.cos(2 * theta)

    p = signal_csv(tmp_path / "speed.csv", "flywheel", [{"rpm": 1200, "cycles": 4,
                                                        "signal": speed}],
                   column="instantaneous speed", unit="rpm")
    m = read_measurement(p, [1.0, 2.0])
    assert m.amplitude[0, 1] == pytest.approx(amp_rpm / (2 * w_rpm), rel=1e-7)  # CSV: 9 digits
    assert m.amplitude[0, 0] == pytest.approx(0.0, abs=1e-12)
    assert m.irregularity[0] == pytest.approx(2 * amp_rpm / w_rpm, rel=1e-4)


def test_track_of_a_speed_amplitude(tmp_path):
    """An order track given as a speed amplitude (rpm) is the angle amplitude W / (n w); its
    phase 90 deg behind the speed's; percent irregularity read as a ratio."""
    p = tmp_path / "t.csv"
    p.write_text("# station: flywheel\n# load: no\nspeed,order 2,order 2 phase,irregularity\n"
                 "rpm,rpm,deg,%\n1000,10,30,2\n2000,4,30,0.4\n", encoding="utf-8")
    m = read_measurement(p)
    assert m.load == "no" and m.orders.tolist() == [2.0]
    assert m.amplitude[:, 0] == pytest.approx([10 / (2 * 1000), 4 / (2 * 2000)], rel=1e-12)
    assert np.degrees(np.angle(m.coeffs[0, 0])) == pytest.approx(30 - 90, abs=1e-9)
    assert m.irregularity == pytest.approx([0.02, 0.004], rel=1e-12)
