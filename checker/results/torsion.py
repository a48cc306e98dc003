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


@dataclass(frozen=True, kw_only=True)
class CrankStressDetail(TorsionDetail):
    """``tv.crank_shear_stress``: the nominal vibratory shear stress of every crank section
    of the TV model (the elements from the crank nose to the flywheel), the torque over the
    polar section modulus of the crank pin or main journal, the smaller governing."""

    order_stress: np.ndarray  # (E, C, S, O) stress amplitude per order, 0-to-peak [Pa]
    element_index: np.ndarray  # (E,) int: index of each section in ``tv.element_torque``
    polar_modulus: np.ndarray  # (E,) polar section modulus used [m^3]
    section: tuple[str, ...]  # (E,) "crank pin" or "main journal": the smaller modulus
    pin_modulus: float  # W_P of the crank pin [m^3]
    journal_modulus: float  # W_P of the main journal [m^3]
    pin_diameter: float  # [m]
    pin_bore: float  # [m]
    journal_diameter: float  # [m]
    journal_bore: float  # [m]
    worst: int  # index of the section with the largest stress in the operating envelope
    envelope: np.ndarray | None  # (C, S) bool: each load case's operating envelope


@dataclass(frozen=True, kw_only=True)
class ClassLimitDetail(Detail):
    """The class-society limits of the crank's vibratory stress against speed (quantities
    ``tv.crank_stress_ratio_*``): the limit curves over the whole sweep (NaN outside the
    speed range where a limit is defined) and what they were built from."""

    engine_class: str  # "marine", "industrial" or "commercial vehicle"
    group: str  # KR Pt 5 Ch 4 201.1 engine group "A" or "B"
    rated_speed: float  # MCR (rated) speed [rad/s]
    speed_ratio: np.ndarray  # (S,) lambda = n / n_rated of every swept speed [-]
    continuous: np.ndarray  # (S,) permissible stress, continuous operation [Pa] (NaN: none)
    transient: np.ndarray  # (S,) permissible stress, transient operation [Pa] (NaN: none)
    overspeed: np.ndarray  # (S,) permissible stress above the rated speed [Pa] (NaN: none)
    judged_band: tuple[float, float]  # lambda band the quantity judges [-]
    f_m_tensile: float  # material factor of tau_1, tau_3 [-]
    f_m_yield: float  # material factor of tau_2 [-]
    speeds: np.ndarray  # (s,) the speeds on the quantity's speed axis [rad/s]
    stress: np.ndarray  # (E, C, s) the stresses judged [Pa]
    limit: np.ndarray  # (s,) the limit at those speeds [Pa]
    source: str  # the rule text behind the limit, in words
    default: bool  # an engineering default (no published limit for the class)


@dataclass(frozen=True, kw_only=True)
class BarredRangeDetail(Detail):
    """``tv.barred_speed_range``: the barred speed range of every critical whose stress
    exceeds the continuous limit (KR Pt 5 Ch 4 206.1(1)); item axis R."""

    critical_speed: np.ndarray  # (R,) N_c [rad/s]
    lower: np.ndarray  # (R,) lowest barred speed: min(rule_lower, run_lower) [rad/s]
    upper: np.ndarray  # (R,) highest barred speed: max(rule_upper, run_upper) [rad/s]
    rule_lower: np.ndarray  # (R,) 16 N_c / (18 - lambda) [rad/s]
    rule_upper: np.ndarray  # (R,) (18 - lambda) N_c / 16 [rad/s]
    run_lower: np.ndarray  # (R,) lowest swept speed of the run above tau_1 [rad/s]
    run_upper: np.ndarray  # (R,) highest swept speed of the run above tau_1 [rad/s]
    order: np.ndarray  # (R,) order of the critical [-] (NaN: a peak without a critical)
    mode: np.ndarray  # (R,) int: flexible mode of the critical, 0-based (-1: none)
    peak_speed: np.ndarray  # (R,) swept speed of the largest stress / tau_1 [rad/s]
    peak_stress: np.ndarray  # (R,) synthesised stress there [Pa]
    peak_limit: np.ndarray  # (R,) tau_1 there [Pa]
    section: tuple[str, ...]  # (R,) crank section of the peak
    case: tuple[str, ...]  # (R,) load case of the peak
    rated_speed: float  # [rad/s]


@dataclass(frozen=True, kw_only=True)
class MajorCriticalDetail(Detail):
    """``tv.major_critical_clearance``: the critical speeds of the major orders of the
    one-node (first flexible) mode against the band KR Pt 5 Ch 4 204 keeps free."""

    order: np.ndarray  # (K,) major orders [-]
    critical_speed: np.ndarray  # (K,) [rad/s]
    speed_ratio: np.ndarray  # (K,) N_c / N_rated [-]
    band: tuple[float, float]  # the band to keep free [-]
    natural_frequency: float  # of the one-node mode [Hz]
    rated_speed: float  # [rad/s]


__all__ = ["BarredRangeDetail", "ClassLimitDetail", "CrankStressDetail", "CylinderOrderDetail",
           "DamperDetail", "ElementTorqueDetail", "JointTorqueDetail",
           "LowerOrdersDetail", "MajorCriticalDetail",
           "NaturalFrequencyDetail", "NoseDetail", "OrdersCheckedDetail",
           "TVModelData", "TorsionDetail", "TwistDetail"]
