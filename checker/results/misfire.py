"""Detail types of the misfire case (module ``misfire``, node ``misfire_response`` in
:mod:`checker.modules.misfire`): the ``misfire.*`` quantities.

Axes: ``S`` swept speeds (full load), ``O`` harmonic orders, ``E`` elements of the torsional
model (front to rear), ``Z`` cylinders (Cylinders row order), ``K`` flexible couplings.
Angles [rad], torques [N m], speeds [rad/s], powers [W].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class MisfireDetail(Detail):
    """What every ``misfire.*`` quantity carries: the response with each cylinder misfiring
    and normal firing beside it (full load)."""

    speeds: np.ndarray  # (S,) swept speeds [rad/s]
    orders: np.ndarray  # (O,) harmonic orders [-], 0.5 .. 24
    cylinders: tuple[int, ...]  # (Z,) cylinder numbers, Cylinders row order
    elements: tuple[str, ...]  # (E,) element names "front -> rear"
    element_torque: np.ndarray  # (Z, E, S) half peak-to-peak vibratory torque, misfire [N m]
    element_torque_normal: np.ndarray  # (E, S) the same in normal firing [N m]
    worst_cylinder: np.ndarray  # (E, S) int: index into ``cylinders`` of the worst misfire
    worst_torque_orders: np.ndarray  # (E, S, O) order amplitudes of the worst case [N m]
    motored_exponent: np.ndarray  # (S,) polytropic exponent of the motored trace [-]
    motored_peak: np.ndarray  # (S,) motored peak pressure [Pa]
    firing_peak: np.ndarray  # (S,) firing peak pressure, full load [Pa]
    damper_power: np.ndarray | None = None  # (Z, S) damper power per misfiring cylinder [W]
    damper_power_normal: np.ndarray | None = None  # (S,) damper power, normal firing [W]
    couplings: tuple[str, ...] = ()  # (K,) names of the flexible-coupling elements
    coupling_torque: np.ndarray | None = None  # (K, Z, S) vibratory torque, misfire [N m]
    coupling_power: np.ndarray | None = None  # (K, Z, S) damping power, misfire [W]


@dataclass(frozen=True, kw_only=True)
class MisfireStressDetail(Detail):
    """``misfire.crank_stress_ratio``: the crank sections' vibratory shear stress with one
    cylinder misfiring against the class's transient limit."""

    speeds: np.ndarray  # (S,) swept speeds [rad/s]
    sections: tuple[str, ...]  # (Ec,) crank-section elements "front -> rear"
    stress: np.ndarray  # (Ec, S) misfire stress, worst cylinder [Pa]
    stress_normal: np.ndarray  # (Ec, S) normal firing's stress [Pa]
    limit: np.ndarray  # (S,) the limit used [Pa] (NaN where not judged)
    speed_ratio: np.ndarray  # (S,) lambda = n / n_rated [-]
    engine_class: str  # "marine" or "industrial"
    limit_text: str  # which limit, in words, with its source


__all__ = ["MisfireDetail", "MisfireStressDetail"]
