"""Detail type of the TV damper's tuning (module ``damper``, node ``damper_tuning`` in
:mod:`checker.modules.damper_tuning`): ``damper.tuning_ratio``, Den Hartog's optimum
(``damper.optimum_*``, ``damper.crank_mode_frequency`` ...) and the crank-nose amplitude with
the optimum rubber. (The rubber's twist, torque, power, shear stress and heat come from the
torsional solve: :class:`checker.results.torsion.DamperDetail`.)

Axes: ``C`` load cases, ``S`` swept speeds, ``O`` harmonic orders, ``n`` stations.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..calc.damper_tuning import DamperTuning
from . import Detail


@dataclass(frozen=True, kw_only=True)
class DamperTuningDetail(Detail):
    """Actual damper against Den Hartog's optimum for its inertia ratio."""

    tuning: DamperTuning  # actual and optimum tuning and damping (SI, see the calc type)
    primary_omega: float  # crank's first flexible mode without the ring [rad/s]
    primary_inertia: float  # modal inertia of that mode at the hub [kg m^2]
    primary_mode: np.ndarray  # (n - 1,) that mode's shape without the ring [-]
    ring_inertia: float  # damper ring inertia [kg m^2]
    stiffness: float  # rubber storage stiffness [N m/rad]
    loss_factor: float  # rubber loss factor [-]
    relative_damping: float  # rubber viscous damping [N m s/rad]
    ring: str  # name of the damper-ring station
    hub: str  # name of the hub (crank-nose) station
    orders: np.ndarray  # (O,) harmonic orders [-]
    speeds: np.ndarray  # (S,) swept speeds [rad/s]
    actual_nose_amplitude: np.ndarray  # (C, S) crank-nose half range, actual damper [rad]
    optimum_theta: np.ndarray  # (C, S, O) complex nose angle per order, optimum rubber [rad]
    actual_theta: np.ndarray  # (C, S, O) complex nose angle per order, actual damper [rad]
    cylinder_order: float  # the order equal to the cylinder count [-]
    cylinder_order_index: int  # its index on the order axis
    peaks: dict[str, dict[str, dict[str, Any] | None]]
    """Largest resonant peak per design ("actual", "optimum") and order group ("cylinder
    order", "higher orders"): ``{"value" [rad], "order", "case", "speed" [rad/s]}`` or None."""
