"""Tests of checker.calc.torsion_post: extremes of synthesised signals, mean element torques,
the rigid-body split and the torque-cut peak, against closed forms and hand values."""

import numpy as np
import pytest

from checker.calc import torsion_post as tp
from checker.calc import torsional as tv


def test_extremes_of_two_orders_closed_form():
    # x = A cos(u) + B cos(2 u), u = theta + a: max A + B at u = 0; with B = A/2,
    # dx/du = -sin u (A + 4 B cos u) = 0 at cos u = -A/(4B) = -1/2, x = -A/2 + B cos(240 deg)
    # = -A/2 - B/2 (the minimum); phase shifts move the extremes between the samples
    a_amp, b_amp = 3.0, 1.5
    for ph in np.linspace(0.0, 0.4, 9):
        c = np.array([a_amp * np.exp(1j * ph), b_amp * np.exp(2j * ph)])
        hi, lo = tp.synthesized_extremes([1.0, 2.0], c)
        tol = 1e-3 * (a_amp + b_amp)  # the documented accuracy
        assert hi == pytest.approx(a_amp + b_amp, abs=tol)
        assert lo == pytest.approx(-a_amp / 2 - b_amp / 2, abs=tol)
    # the refinement is needed (control): the raw samples miss the peak by far more
    c = np.array([a_amp * np.exp(0.1j), b_amp * np.exp(0.2j)])
    hi, _ = tp.synthesized_extremes([1.0, 2.0], c)
    _, x = tv.synthesize([1.0, 2.0], c, 64)
    assert a_amp + b_amp - x.max() > 10 * abs(hi - (a_amp + b_amp))


def test_extremes_agree_with_the_exact_half_range():
    rng = np.random.default_rng(3)
    orders = np.arange(1, 25) * 0.5
    c = (rng.normal(size=(5, orders.size)) + 1j * rng.normal(size=(5, orders.size))) / orders
    hi, lo = tp.synthesized_extremes(orders, c)
    exact = tv.half_peak_to_peak(orders, c)
    np.testing.assert_allclose(0.5 * (hi - lo), exact, atol=1e-3 * np.abs(c).sum(-1).max())


def test_mean_element_torque_by_hand():
    # I4 chain: ring, nose, 4 cylinder stations, flywheel; 19 N m FEAD taken off at the nose;
    # full and no load means 25 and -3 N m per cylinder
    cm = np.array([[25.0], [-3.0]])  # (C, S)
    t = tp.mean_element_torque(cm, [2, 3, 4, 5], 7, 1, 19.0)
    np.testing.assert_allclose(t[0, 0], [0, -19, 6, 31, 56, 81])
    np.testing.assert_allclose(t[1, 0], [0, -19, -22, -25, -28, -31])
    # two cylinders on one station (V engine) add
    t2 = tp.mean_element_torque(10.0, [1, 1], 3, 0, 0.0)
    np.testing.assert_allclose(t2, [0.0, 20.0])
    with pytest.raises(ValueError):
        tp.mean_element_torque(1.0, [3], 3, 0, 0.0)


def test_rigid_body_angle_is_mass_orthogonal_to_flexible_modes():
    j = np.array([0.0055, 0.001155, 0.0065732, 0.0065732, 0.0065732, 0.0065732, 0.174743])
    k = np.array([25500.0, 171035.0, 403300.0, 416625.0, 403300.0, 661013.0])
    w, modes = tv.natural_frequencies(tv.TorsionalModel(inertia=j, stiffness=k))
    flex = modes[:, w > 1.0]
    np.testing.assert_allclose(tp.rigid_body_angle(flex, j, axis=0), 0.0,
                               atol=1e-12 * np.abs(flex).max())
    # a rigid rotation is all rigid body
    theta = np.full((2, 7, 3), 0.01 + 0.02j)
    np.testing.assert_allclose(tp.rigid_body_angle(theta, j, axis=1), 0.01 + 0.02j)
    with pytest.raises(ValueError):
        tp.rigid_body_angle(theta, -j, axis=1)


def test_peak_cut_torque():
    # crank nose: FEAD 19 N m against a rubber torque swinging -40..+30 N m -> |19 - 40| = 21 or
    # |19 + 30| = 49 (the cut's sign folded into the vibratory extremes)
    np.testing.assert_allclose(tp.peak_cut_torque(19.0, 30.0, -40.0), 49.0)
    np.testing.assert_allclose(tp.peak_cut_torque([100.0, -5.0], [20.0, 1.0], [-150.0, -2.0]),
                               [120.0, 7.0])
