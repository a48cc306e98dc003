"""Typed results of the crankshaft fatigue analysis (module ``fatigue``, quantities
``fatigue.*``, rules ``FAT-``): the inputs, factors, stresses and Haigh-diagram points the
report section shows beside the safety factors.

Axes: ``item`` = location (``pin 1 fillet`` ...), ``case`` = load case, ``speed``, ``throw``
(T, crank pins), ``side`` (front/rear web of a throw, or front/rear element torque), ``angle``
(N, crank angle of the loads module), ``element`` (E + 1 torsional elements, the last a zero
"free end"), ``location type`` (:data:`checker.modules.fatigue.LOCATIONS`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class ThrowGeometry:
    """Geometry of a crank throw [m] (the keyword arguments of
    :func:`checker.calc.crank_stress.throw_nominal_stresses`)."""

    pin_diameter: float  # D [m]
    journal_diameter: float  # D_G [m]
    throw: float  # E = stroke / 2 [m]
    main_spacing: float  # L3 [m]
    main_journal_length: float  # L_G [m]
    pin_journal_length: float  # L_H [m]
    web_thickness: float  # W [m]
    web_width: float  # B [m]
    web_offset: float = 0.0  # [m]
    pin_bore: float = 0.0  # D_BH [m]
    journal_bore: float = 0.0  # D_BG [m]

    def as_kwargs(self) -> dict[str, float]:
        """The fields as keyword arguments of the calc functions."""
        return dataclasses.asdict(self)


@dataclass(frozen=True, kw_only=True)
class PinOilHole:
    """The crank-pin oil hole."""

    diameter: float | None  # D_O [m] (None: missing)
    angle: float | None  # phi [rad] from the throw axis, + leading (None: missing)
    row: Any  # the Bearings row (checker.description.engine.Bearing) it was read from


class LocationStrength(NamedTuple):
    """Goodman strengths of one location type [Pa] (None: missing) and their cells."""

    endurance_limit: float | None
    ultimate_strength: float | None
    endurance_cell: str
    ultimate_cell: str


@dataclass(frozen=True, kw_only=True)
class ScfInfo:
    """Stress concentration factors per factor key (``alpha_b`` ... ``gamma_t_main``, see
    :data:`checker.modules.fatigue.SCF_FIELDS`)."""

    used: dict[str, float | None]  # factor used [-] (None: missing)
    source: dict[str, str]  # "workbook Fatigue!B12", "IACS UR M53 §3" or "missing"
    m53: dict[str, float | None]  # M53 formula value [-] (None: not available)
    ratios: Any = None  # checker.calc.scf.M53Ratios of the throw (None: M53 not evaluated)
    ratios_main_oil: Any = None  # M53Ratios with d_O = D_O/D_G (main oil hole), or None
    m53_missing: list[str] = field(default_factory=list)  # inputs M53 lacks (texts)


@dataclass(frozen=True, kw_only=True)
class ThrowNominal:
    """Nominal web stresses of the throws (M53 §2.1)."""

    sigma_web_bending: np.ndarray  # (case, speed, throw, side, angle) [Pa] sigma_BF
    sigma_web_direct: np.ndarray  # (case, speed, throw, side, angle) [Pa] sigma_QF
    web_centre_distance: Any  # L1 [m] (float or per side)
    overlap: Any  # S [m] pin/journal overlap


@dataclass(frozen=True, kw_only=True)
class FatigueDetail(Detail):
    """What the Goodman and the M53 quantities share: inputs, factors, the sweep."""

    geometry: ThrowGeometry
    scf: ScfInfo
    scf_findings: dict[str, list[str]]  # factor key -> M53 validity texts
    strengths: dict[str, LocationStrength]  # location type -> strengths
    oil_hole: PinOilHole | None  # None: the crank has no pin oil hole
    main_oil_hole_diameter: float | None  # [m] None: no main oil hole
    theta: np.ndarray  # (angle,) [rad] crank angle, 0 = firing TDC of cylinder 1
    speeds: np.ndarray  # (speed,) [rad/s]
    locations: list[str]  # (item,) location type of each Goodman item
    sf_by_location: np.ndarray  # (location type, case, speed) [-] lowest Goodman SF (NaN: none)


@dataclass(frozen=True, kw_only=True)
class GoodmanDetail(FatigueDetail):
    """Goodman safety factor (``fatigue.goodman_sf``): the governing stresses of each item."""

    sigma_eq_a: np.ndarray  # (item, case, speed) [Pa] equivalent alternating stress
    sigma_eq_m: np.ndarray  # (item, case, speed) [Pa] equivalent mean stress
    sigma_a: np.ndarray  # (item, case, speed) [Pa] local normal stress amplitude
    sigma_m: np.ndarray  # (item, case, speed) [Pa] local normal mean stress
    tau_a: np.ndarray  # (item, case, speed) [Pa] local shear stress amplitude
    tau_m: np.ndarray  # (item, case, speed) [Pa] local shear mean stress
    governing: np.ndarray  # (item, case, speed) int index into ``candidates[item]``
    candidates: list[tuple[str, ...]]  # (item,) the two candidates' names (web / torque)
    sigma_eq_max: np.ndarray  # (item, case, speed) [Pa] mean + amplitude
    sigma_eq_min: np.ndarray  # (item, case, speed) [Pa] mean - amplitude
    endurance_limit: np.ndarray  # (item,) [Pa] S_e (NaN: missing)
    ultimate_strength: np.ndarray  # (item,) [Pa] S_u (NaN: missing)
    haigh_x: np.ndarray  # (item, case, speed) [-] sigma_eq,m / S_u
    haigh_y: np.ndarray  # (item, case, speed) [-] sigma_eq,a / S_e
    candidate_sf: np.ndarray  # (item, case, speed, 2) [-] SF of both candidates
    pin_force_radial: np.ndarray  # (case, speed, throw, angle) [N] F_R, + outward
    pin_force_tangential: np.ndarray  # (case, speed, throw, angle) [N] F_T, + rotation
    throw_angle: np.ndarray  # (throw,) [rad] angle of each throw
    throw_elements: np.ndarray  # (throw, side) int torsional element index (E: free end)
    main_elements: np.ndarray  # (main, 2) int candidate element index of each main journal
    nominal: ThrowNominal
    element_names: list[str]  # (element,) TV element names + "free end"
    element_torque: np.ndarray  # (case, speed, element, angle) [N m], last = 0 (free end)
    mean_criterion: str  # mean-stress criterion of the fillets ("signed_von_mises")


@dataclass(frozen=True, kw_only=True)
class M53Detail(FatigueDetail):
    """IACS UR M53 acceptability factor (``fatigue.m53_q``)."""

    sigma_v: np.ndarray  # (item, case, speed) [Pa] M53 equivalent alternating stress
    sigma_dw: dict[str, float]  # location type -> M53 §6 fatigue strength [Pa]
    sigma_add: float  # [Pa] additional bending stress (trunk piston)
    k_fillet: float  # [-] M53 §6 factor K at the fillets
    k_oil: float  # [-] M53 §6 factor K at the oil bore
    torsion_basis: str = ""  # which torsional stress M53 used (whole system or each speed)


@dataclass(frozen=True, kw_only=True)
class FilletRatioDetail(Detail):
    """Detail of ``fatigue.fillet_bending_ratio``: the bending moment amplitude at each fillet
    on the continuous beam and by the determinate scheme, at the operating point the ratio is
    taken at (items in the quantity's order)."""

    scheme: str  # the continuous scheme compared (the workbook's, or rigid supports)
    amplitude_continuous: np.ndarray  # [N m] (I,) half range over the cycle
    amplitude_determinate: np.ndarray  # [N m] (I,)
    case: tuple[str, ...]  # (I,) load case of the governing operating point
    speed: np.ndarray  # [rad/s] (I,) its speed
