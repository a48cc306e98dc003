"""Pin offset convention: the workbook's "towards the major thrust side positive" reaches the
kinematics with the right sign (a case whose side-force direction is known by hand)."""

from __future__ import annotations

import dataclasses

import numpy as np

from checker.calc.crank_forces import cylinder_loads
from checker.description.engine import Params, load_engine
from tests.helpers import example_path


def test_workbook_pin_offset_towards_major_thrust_side(tmp_path):
    """By hand: during expansion (crank angle 0..180 deg after firing TDC) the crank pin is on
    the +t side of the cylinder frame, the rod is in compression and pushes the piston towards
    -t: the piston presses on the liner's major thrust side, -t (negative side force). Moving
    the pin towards that side (workbook value > 0) moves the small end further from the crank
    pin, so the rod leans more (sin(beta) = (r sin(phi) - e)/l with e < 0) and the side force
    on the major thrust side grows; a pin moved the other way (workbook value < 0) reduces it.
    """
    base = load_engine(example_path(tmp_path))
    p = base.params
    theta = np.radians(np.arange(0.0, 720.0, 1.0))
    pressure = np.where((theta > 0) & (theta < np.pi), 60e5 * np.sin(theta), 1e5)

    def side(pin_mm: float) -> np.ndarray:
        eng = dataclasses.replace(base, params=Params({**p, "pin_offset": pin_mm * 1e-3,
                                                       "cylinder_offset": 0.0}))
        loads = cylinder_loads(theta, 0.0, pressure[None, :], bore=p["bore"],
                               crank_radius=p["stroke"] / 2, rod_length=p["rod_length"],
                               piston_mass=p["piston_mass"], rod_mass=p["rod_mass"],
                               rod_cg_from_big_end=p["rod_com"], rod_inertia=p["rod_inertia"],
                               firing_angle=np.zeros(1), **eng.offsets)
        return np.asarray(loads.side_force).reshape(-1, theta.size)[0]

    expansion = (theta > np.radians(10)) & (theta < np.radians(170))
    s0, s_thrust, s_anti = side(0.0), side(1.0), side(-1.0)
    assert np.all(s0[expansion] < 0)  # the major thrust side is -t
    assert np.all(s_thrust[expansion] < s0[expansion])  # more load on the thrust side
    assert np.all(s_anti[expansion] > s0[expansion])
    # every calculation takes the offsets from one place, in the documented convention
    eng = dataclasses.replace(base, params=Params({**p, "pin_offset": 0.8e-3}))
    assert eng.offsets["pin_offset"] == 0.8e-3
