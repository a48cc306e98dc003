"""Detail types of the torsional-vibration analysis (module ``torsion``, node ``tv_response``
and ``tv_joint_torque`` in :mod:`checker.modules.torsion`): the ``tv.*`` quantities and the
damper-rubber quantities ``damper.relative_twist`` ... ``damper.heat_peak_ratio`` that the same
forced-response solve gives. (The damper *tuning* quantities, ``damper.tuning_ratio`` and the
Den Hartog optimum, are :mod:`checker.results.damper`.)

Axes: ``C`` load cases (``("full", "no")``), ``S`` swept speeds, ``O`` harmonic orders, ``n``
stations of the torsional model (front to rear), ``E = n - 1`` elements, ``I`` joints, ``P``
operating points of a joint. Angles [rad], torques [N m], speeds [rad/s].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..calc.torsional import TorsionalModel
from . import Detail


@dataclass(frozen=True, kw_only=True)
class TVModelData:
    """The torsional model of the TVModel/Damper sheets and where its named stations are."""

    model: TorsionalModel  # lumped-mass chain (SI)
    ring: int | None  # station index of the damper ring (None: no damper)
    nose: int  # station index of the crank nose
    flywheel: int | None  # station index of the flywheel (None: none given)
    cyl_station: np.ndarray  # (n_cyl,) int: station of each cylinder (Cylinders row order)
    eta: float  # rubber loss factor of the Damper sheet [-] (0 when not given)


@dataclass(frozen=True, kw_only=True)
class TorsionDetail(Detail):
    """What every forced-response quantity of the TV solve carries."""

    orders: np.ndarray  # (O,) harmonic orders [-], 0.5 .. 24
    speeds: np.ndarray  # (S,) swept engine speeds [rad/s]
    resonance: np.ndarray  # (C, S, O) bool: an order exactly on an undamped mode
    near_resonance: np.ndarray  # (S, O) bool: an order near an undamped mode (band/crossing)


@dataclass(frozen=True, kw_only=True)
class NaturalFrequencyDetail(Detail):
    """``tv.natural_frequency``: the flexible modes of the torsional model."""

    modes: np.ndarray  # (n, M) mode shapes of the flexible modes [-]
    stations: list[str]  # (n,) station names, front to rear
    roles: list[str]  # (n,) station roles (TVModel column 'role')
    damping_ratio: np.ndarray  # (M,) modal damping ratio [-]
    omega: np.ndarray  # (M,) undamped natural angular frequencies [rad/s]
    critical_speed: np.ndarray  # (M, O) engine speed where order O meets mode M [rad/s]
    orders: np.ndarray  # (O,) harmonic orders [-]
    rigid_body_mode: bool  # the model has a free rigid-body mode (left out of ``modes``)


@dataclass(frozen=True, kw_only=True)
class NoseDetail(TorsionDetail):
    """``tv.nose_amplitude``: the crank-nose response and what a re-solve needs (damper
    tuning re-solves the same model with the optimum rubber)."""

    theta: np.ndarray  # (C, S, O) complex crank-nose angle per order, 0-to-peak [rad]
    station: str  # name of the crank-nose station
    model: TorsionalModel  # the model solved
    model_data: TVModelData  # the model and its named stations
    excitation: np.ndarray  # (C, S, n, O) complex station excitation torques [N m]


@dataclass(frozen=True, kw_only=True)
class CylinderOrderDetail(TorsionDetail):
    """``tv.nose_cylinder_order_amplitude``."""

    order: float  # the order equal to the cylinder count [-]


@dataclass(frozen=True, kw_only=True)
class OrdersCheckedDetail(TorsionDetail):
    """``tv.nose_higher_order_amplitude``: the orders on the quantity's order axis."""

    orders_checked: np.ndarray  # (o,) orders of the quantity's order axis [-]


@dataclass(frozen=True, kw_only=True)
class LowerOrdersDetail(OrdersCheckedDetail):
    """``tv.nose_lower_order_elastic_amplitude``: the elastic/rigid-body split (rule TV-003)."""

    rigid_body: np.ndarray  # (o, C, S) rigid-body (inertia-weighted mean) amplitude [rad]
    nose_total: np.ndarray  # (o, C, S) crank-nose amplitude, rigid + elastic [rad]
    mode_band: float  # relative band around a natural frequency judged a resonance [-]


@dataclass(frozen=True, kw_only=True)
class TwistDetail(TorsionDetail):
    """``tv.crank_twist``."""

    stations: tuple[str, str]  # (front, rear) stations the twist is taken between


@dataclass(frozen=True, kw_only=True)
class ElementTorqueDetail(TorsionDetail):
    """``tv.element_torque``: the torque through every element (read by the fatigue and
    crank-nose checks)."""

    coeffs: np.ndarray  # (E, C, S, O) complex vibratory torque per order [N m]
    vib_max: np.ndarray  # (E, C, S) max over the cycle of the vibratory torque [N m]
    vib_min: np.ndarray  # (E, C, S) min over the cycle of the vibratory torque [N m]
    mean: np.ndarray  # (E, C, S) mean torque [N m]
    twist: np.ndarray  # (E, C, S) element twist, half peak-to-peak [rad]
    twist_coeffs: np.ndarray  # (E, C, S, O) complex element twist per order [rad]
    cylinder_mean_torque: np.ndarray  # (C, S) mean crank torque of one cylinder [N m]
    sign: str  # the sign convention in words
    mean_definition: str  # what the mean torque contains, in words


@dataclass(frozen=True, kw_only=True)
class DamperDetail(TorsionDetail):
    """``damper.relative_twist`` .. ``damper.heat_peak_ratio`` (the rubber element of the TV
    solve). Fields are None where the quantity was not computed: no damper ring (all), no
    rubber geometry (``volume``, ``shear_modulus``, ``shear_orders``), no supplier limit
    (``limit``, ``limit_cell``, only on the ratios)."""

    dphi: np.ndarray | None = None  # (C, S, O) complex relative twist hub - ring [rad]
    torque_orders: np.ndarray | None = None  # (C, S, O) complex rubber torque [N m]
    power_orders: np.ndarray | None = None  # (C, S, O) dissipated power per order [W]
    stiffness: float | None = None  # rubber storage stiffness k' [N m/rad]
    loss_factor: float | None = None  # rubber loss factor eta [-]
    relative_damping: float | None = None  # viscous damping of the element [N m s/rad]
    hub: str | None = None  # name of the hub station
    ring: str | None = None  # name of the damper-ring station
    volume: float | None = None  # rubber volume [m^3]
    shear_modulus: float | None = None  # storage shear modulus G' from k' and geometry [Pa]
    shear_orders: np.ndarray | None = None  # (C, S, O) shear stress amplitude per order [Pa]
    limit: float | None = None  # supplier limit of a ratio (SI: Pa or W/m^3)
    limit_cell: str | None = None  # workbook cell of that limit


@dataclass(frozen=True, kw_only=True)
class JointTorqueDetail(Detail):
    """``tv.joint_torque`` (read by the joints module): where each joint torque was taken."""

    speed: np.ndarray  # (I, P) swept speed used [rad/s] (NaN: not computed)
    case: np.ndarray  # (I, P) object: load case used ("" : not computed)
    how: np.ndarray  # (I, P) object: the torque's composition in words ("" : none)
    max_power_speed: float | None = None  # speed of maximum brake power [rad/s]
    overspeed: float | None = None  # Engine 'Overspeed' [rad/s]


__all__ = ["CylinderOrderDetail", "DamperDetail", "ElementTorqueDetail", "JointTorqueDetail",
           "LowerOrdersDetail", "NaturalFrequencyDetail", "NoseDetail", "OrdersCheckedDetail",
           "TVModelData", "TorsionDetail", "TwistDetail"]
