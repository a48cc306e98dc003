"""Typed results of the bolted-joint analysis (module ``joints``, quantities ``joint.*``, rules
``JNT-``): what the report section and the results workbook show beside the numbers."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class JointBoltsDetail(Detail):
    """Bolt and face results (stress area, preload, proof stress, head contact stress, slip
    capacity): how each value was obtained, in words for the report."""

    how: dict[str, dict[str, str]] = field(default_factory=dict)
    """Joint name -> {"stress area" | "preload" | "proof stress" | "friction": equation and the
    values used (with their source)}."""


@dataclass(frozen=True, kw_only=True)
class AppliedTorqueDetail(Detail):
    """Peak applied torque per joint and operating point (``joint.applied_torque``, and the
    cover factor computed from it): where each torque came from."""

    source: np.ndarray
    """(item, point) str: ``"workbook (JointTorques)"``, ``"torsional vibration module"`` or
    ``""`` (not available)."""
    speed: np.ndarray
    """(item, point) [rad/s] engine speed of the torque (NaN: not given)."""


@dataclass(frozen=True, kw_only=True)
class ComputedTorqueDetail(Detail):
    """The torsional model's torque at each joint and operating point next to the design torque
    (``joint.computed_torque``, ``joint.computed_cover_factor``,
    ``joint.computed_torque_ratio``)."""

    speed: np.ndarray
    """(item, point) [rad/s] speed of the torsional model's torque (NaN: not computed)."""
    case: np.ndarray
    """(item, point) str load case label of the torsional model's torque (``""``: none)."""
    how: np.ndarray | None = None
    """(item, point) str how the torsional module obtained the torque (None: it did not run)."""
    given: np.ndarray
    """(item, point) bool: the design torque is given in sheet JointTorques."""
    design: np.ndarray
    """(item, point) [N m] design torque the cover-factor rules use (NaN: none)."""
    given_speed: np.ndarray
    """(item, point) [rad/s] speed of the design torque (NaN: not given)."""
