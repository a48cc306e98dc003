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


@dataclass(frozen=True, kw_only=True)
class DamperEndsDetail(Detail):
    """The damper at the cold and hot ends of its operating temperature range (module
    ``damper``, :mod:`checker.modules.damper_thermal`): a rubber damper with its temperature
    table (node ``damper_rubber_ends``) or an untuned viscous damper (node
    ``viscous_damper``), each at its own temperature from its heat.

    Axes: ``E`` ends (cold, hot), ``C`` load cases, ``S`` swept speeds.
    """

    damper_type: str  # "rubber" | "viscous"
    ends: tuple[str, ...]  # ("cold", "hot")
    air_temperature: tuple[float, ...]  # (E,) air temperature at the damper [K]
    heat_resistance: float | None  # 1/(h A) of the cooled surface [K/W]; None: not heated
    speeds: np.ndarray  # (S,) [rad/s]
    cases: tuple[str, ...]  # (C,)
    temperature: np.ndarray  # (E, C, S) damper (rubber / silicone) temperature [K]
    power: np.ndarray  # (E, C, S) dissipated power [W]
    nose_amplitude: np.ndarray  # (E, C, S) crank-nose half range [rad]
    nominal_nose_amplitude: np.ndarray  # (C, S) crank nose with the nominal damper [rad]
    judged: np.ndarray  # (E, C, S) bool: the speed of the largest power per end and case
    crank_mode_omega: float  # crank's first mode without the ring [rad/s]
    modal_inertia: float  # its modal inertia at the hub [kg m^2]
    ring_inertia: float  # [kg m^2]
    ring: str  # ring station
    stiffness: np.ndarray | None = None  # (E, C, S) rubber storage stiffness [N m/rad]
    loss_factor: np.ndarray | None = None  # (E, C, S) rubber loss factor [-]
    table: tuple[tuple[float, float, float], ...] = ()  # rubber (T [K], G' [Pa], eta)
    damping: np.ndarray | None = None  # (E, C, S) viscous c at the silicone temperature
    damping_optimum: float | None = None  # Den Hartog's c_opt [N m s/rad]
    damping_nominal: float | None = None  # c at the reference temperature / typed
    mass_ratio: float | None = None  # mu = J_ring / J_eq [-]
    peak_magnification: float | None = None  # 1 + 2/mu at the optimum [-]
    wetted_area: float | None = None  # [m^2]
    coupling: str = ""  # how the viscous coupling was obtained
    shear_stiffness: float | None = None  # Maxwell k_s [N m/rad]
