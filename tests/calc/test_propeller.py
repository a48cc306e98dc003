"""Propeller law, its damping and the inertia in water (checker.calc.propeller).

Independent numbers: the propeller law's torque at 80 % speed is 64 % of the rated torque
(Q ~ n^2); its damping is the slope dQ/domega, checked against a central difference of the
law itself (tolerance of the difference, 1e-8 relative); the wet inertia by hand.
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import propeller as prop

Q_R, W_R = 10313.0, 1000 * np.pi / 30


def test_propeller_law():
    w = np.array([0.0, 0.5, 0.8, 1.0, 1.15]) * W_R
    np.testing.assert_allclose(prop.propeller_torque(w, Q_R, W_R),
                               Q_R * np.array([0.0, 0.25, 0.64, 1.0, 1.3225]), rtol=1e-12)


def test_damping_is_the_slope_of_the_law():
    w = np.linspace(0.3, 1.1, 9) * W_R
    h = 1e-4
    slope = (prop.propeller_torque(w + h, Q_R, W_R) - prop.propeller_torque(w - h, Q_R, W_R)
             ) / (2 * h)
    np.testing.assert_allclose(prop.propeller_damping(w, Q_R, W_R), slope, rtol=1e-8)
    # 2 Q / omega at the rated point: 2 x 10313 / 104.72 = 196.96 N m s/rad
    assert float(prop.propeller_damping(W_R, Q_R, W_R)) == pytest.approx(196.96, abs=0.01)


def test_wet_inertia_and_bad_input():
    assert float(prop.wet_inertia(400.0, 0.25)) == pytest.approx(500.0)
    with pytest.raises(ValueError):
        prop.wet_inertia(400.0, -0.1)
    with pytest.raises(ValueError):
        prop.propeller_torque(-1.0, Q_R, W_R)
