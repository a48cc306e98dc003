"""Detail type of the crank-nose fatigue check (node ``crank_nose_fatigue`` in
:mod:`checker.modules.crank_nose`, quantity ``fatigue.nose_goodman_sf``).

Axes: ``C`` load cases, ``S`` swept speeds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class CrankNoseDetail(Detail):
    """Stresses and torques behind the crank-nose Goodman safety factor."""

    sigma_eq_a: np.ndarray  # (C, S) equivalent alternating stress [Pa]
    sigma_eq_m: np.ndarray  # (C, S) equivalent mean stress [Pa]
    torque_max: np.ndarray  # (C, S) max torque over the cycle, mean + vibratory [N m]
    torque_min: np.ndarray  # (C, S) min torque over the cycle [N m]
    element: str  # the TV element whose torque is used
