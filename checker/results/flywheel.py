"""Typed results of the flywheel analysis (:mod:`checker.modules.flywheel`): the rigid
engine's angular speed over the cycle, its inertias and the project's target. Axes: C load
cases, S speeds, N crank angles of the cycle grid."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class FlywheelDetail(Detail):
    """Detail shared by the ``flywheel.*`` quantities (one object for all four; the minimum
    inertia's own carries ``total_needed`` and ``inertia_rest`` besides)."""

    theta: np.ndarray  # [rad] (N,) cycle angle from firing TDC
    omega: np.ndarray  # [rad/s] (C, S, N) angular speed of the rigid engine over the cycle
    omega_max: np.ndarray  # [rad/s] (C, S) highest speed over the cycle
    omega_min: np.ndarray  # [rad/s] (C, S) lowest speed over the cycle
    theta_max: np.ndarray  # [rad] (C, S) cycle angle of the highest speed
    theta_min: np.ndarray  # [rad] (C, S) cycle angle of the lowest speed
    linear: np.ndarray  # [-] (C, S) classical estimate of the irregularity dE / (J w^2)
    inertia_total: float  # [kg m^2] every station of the torsional model
    inertia_flywheel: float  # [kg m^2] the flywheel stations
    flywheel_stations: list[str]  # names of the flywheel stations (sheet TVModel)
    target: float | None  # [-] target cyclic irregularity (None: not given)
    lowest_speed: float  # [rad/s] lowest swept speed (the judged one)
    torque: np.ndarray  # [N m] (C, S, N) engine torque, all cylinders
    total_needed: np.ndarray | None = None  # [kg m^2] (C, S) total inertia for the target
    inertia_rest: float | None = None  # [kg m^2] total minus the flywheel stations
