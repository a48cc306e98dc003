"""Typed results of the crank-train loads (:mod:`checker.modules.loads`): the swept operating
points with their cylinder-pressure traces, the bearing loads over the cycle and the crank
angle of each peak specific load."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import Detail

if TYPE_CHECKING:
    from ..calc.crank_forces import Vector2


@dataclass
class Cycle:
    """The swept operating points and their pressure traces (SI). Axes: C load cases, S
    speeds, N crank angles of the cycle grid."""

    theta: np.ndarray  # [rad] (N,) cycle angle from firing TDC
    speeds: np.ndarray  # [rad/s] (S,)
    cases: tuple[str, ...]  # (C,) load case labels ("full", "no")
    pressure: np.ndarray  # [Pa] (C, S, N) cylinder pressure vs own cycle angle
    synthesized: np.ndarray  # [-] (C, S) bool: trace synthesized (not from the workbook)
    extrapolated: np.ndarray  # [-] (C, S) bool: peak pressure held beyond the given speeds
    motored: np.ndarray  # [-] (C, S) bool: motored (no-combustion) trace
    imep: np.ndarray  # [Pa] (C, S) IMEP of the trace used
    target_imep: np.ndarray  # [Pa] (C, S) brake torque + FMEP (nan: not calibrated)
    notes: list[str]  # sentences for the assumptions list
    envelope: np.ndarray | None = None  # [-] (C, S) bool: operating points the rules judge


@dataclass(frozen=True, kw_only=True)
class CycleDetail(Detail):
    """Detail of ``loads.cycle``: the cycle the peak pressures come from."""

    cycle: Cycle  # the swept operating points and pressure traces


def cycle_of(quantities: dict) -> Cycle | None:
    """The cycle of a run's ``loads.cycle`` quantity (``quantities``: name -> Quantity), or
    None when the loads did not run."""
    q = quantities.get("loads.cycle")
    return None if q is None or q.detail is None else q.detail.cycle


@dataclass(frozen=True, kw_only=True)
class BearingLoadDetail(Detail):
    """Detail of ``loads.bearing_load``: load components and speeds over the cycle of every
    bearing (B bearings in the Bearings sheet order), and the crank forces (T cylinders) the
    torsion, fatigue and flywheel analyses start from."""

    theta: np.ndarray  # [rad] (N,) cycle angle from firing TDC
    fx: np.ndarray  # [N] (B, C, S, N) force of the journal on the bearing, frame x
    fy: np.ndarray  # [N] (B, C, S, N) force of the journal on the bearing, frame y
    omega_journal: np.ndarray  # [rad/s] (B, C, S, N) journal speed in the bearing's frame
    omega_bearing: np.ndarray  # [rad/s] (B, C, S, N) bearing speed in its frame (0)
    frames: dict[str, str]  # bearing name -> its frame in words ("con-rod frame", ...)
    torque: np.ndarray  # [N m] (C, S, T, N) gas + inertia torque of each cylinder
    big_end_crank: Vector2  # [N] (C, S, T, N) force of each rod on its pin, crank frame


@dataclass(frozen=True, kw_only=True)
class SpecificLoadDetail(Detail):
    """Detail of ``bearing.peak_specific_load``."""

    theta_at_max: np.ndarray  # [rad] (B, C, S) cycle angle of the peak load (nan: missing)
