"""Detail types of the flexible couplings (module ``coupling``, node ``coupling_load`` in
:mod:`checker.modules.coupling`): the ``coupling.*`` quantities.

Axes: ``K`` flexible-coupling elements of the torsional model (front to rear), ``C`` load
cases, ``S`` swept speeds, ``O`` harmonic orders. Torques [N m], powers [W], stiffness
[N m/rad], temperatures [K].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class CouplingState:
    """A flexible coupling's catalogue values and its state at the rubber's temperature."""

    nominal_torque: float  # T_KN [N m]
    vibratory_torque: float  # T_KW, permissible vibratory torque at 10 Hz [N m]
    damping_power: float  # P_KV, permissible damping power [W]
    stiffness_catalogue: float  # C_Tdyn of the catalogue [N m/rad]
    relative_damping_catalogue: float  # psi of the catalogue [-]
    temperature: float | None  # rubber temperature [K] (None: the catalogue's state)
    stiffness_factor: float  # C_Tdyn(T) / C_Tdyn [-]
    damping_factor: float  # psi(T) / psi [-]
    temperature_factor: float  # S_t(T) >= 1 on the load [-]

    @property
    def stiffness(self) -> float:
        """Dynamic torsional stiffness at the rubber's temperature [N m/rad]."""
        return self.stiffness_catalogue * self.stiffness_factor

    @property
    def relative_damping(self) -> float:
        """Relative damping psi at the rubber's temperature [-]."""
        return self.relative_damping_catalogue * self.damping_factor


@dataclass(frozen=True, kw_only=True)
class CouplingDetail(Detail):
    """What every ``coupling.*`` quantity carries."""

    state: CouplingState  # the catalogue values and their state at temperature
    elements: tuple[str, ...]  # (K,) coupling element names "front -> rear"
    speeds: np.ndarray  # (S,) [rad/s]
    orders: np.ndarray  # (O,) [-]
    torque_orders: np.ndarray  # (K, C, S, O) complex vibratory torque per order [N m]
    power_orders: np.ndarray  # (K, C, S, O) damping power per order [W]
    vibratory_torque: np.ndarray  # (K, C, S) synthesised half range [N m]
    mean_torque: np.ndarray  # (K, C, S) mean torque through the coupling [N m]
    power: np.ndarray  # (K, C, S) damping power, all orders [W]
    frequency_factor: np.ndarray  # (K, C, S) S_f at the largest order's frequency [-]
    frequency: np.ndarray  # (K, C, S) frequency of the largest order [Hz]


__all__ = ["CouplingDetail", "CouplingState"]
