"""Typed results of the crankshaft balancing (:mod:`checker.modules.balance`), at the reference
speed (rated, else maximum). Axes: K orders (1..max), P crank pins (throws), M mains."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class BalanceDetail(Detail):
    """What every ``balance.*`` quantity carries: the reference speed and the masses."""

    orders: np.ndarray  # [-] (K,) orders 1..max
    omega: float  # [rad/s] reference speed
    speed_text: str  # how the reference speed was chosen, with its cell
    reciprocating_mass: float  # [kg] per cylinder: piston + rod small-end share
    rotating_rod_mass: float  # [kg] per cylinder: rod big-end share
    crank_radius: float  # [m]
    harmonics: np.ndarray  # [m/rad^2] (K + 1,) complex piston-acceleration harmonics A_0..A_K
    reference_plane: float  # [m] axial position of the crank's mid-plane from the front main


@dataclass(frozen=True, kw_only=True)
class FreeOrderDetail(BalanceDetail):
    """Detail of ``balance.free_force`` [N] and ``balance.free_moment`` [N m] (unit U)."""

    phasors: np.ndarray  # [U] (K, 2) complex phasor of each order (x, y of the block frame)
    smallest: np.ndarray  # [U] (K,) smallest magnitude over the crank angle
    theta: np.ndarray  # [rad] (K,) crank angle of the largest magnitude
    direction: np.ndarray  # [rad] (K,) direction there, from the cylinder axis (block y)
    reciprocating: np.ndarray  # [U] (K,) largest magnitude of the reciprocating masses' part
    rotating: np.ndarray  # [U] (K,) largest magnitude of the rotating masses' part


@dataclass(frozen=True, kw_only=True)
class BalanceRatioDetail(BalanceDetail):
    """Detail of ``balance.balance_ratio``; the unbalances are None when not computed (no
    CrankMass sheet, or its data refused)."""

    rotating: np.ndarray | None = None  # [kg m] (P, 2) throw unbalance without counterweights
    counterweight: np.ndarray | None = None  # [kg m] (P, 2) unbalance of the counterweights
    rotating_along: np.ndarray | None = None  # [kg m] (P,) rotating, along the throw
    counterweight_along: np.ndarray | None = None  # [kg m] (P,) counterweights, against it
    reciprocating_factor: np.ndarray | None = None  # [-] (P,) share of m_rec r balanced
    static_unbalance: float | None = None  # [kg m] |sum m rho| of the crank with big ends
    couple_unbalance: float | None = None  # [kg m^2] |sum m rho z| about the mid-plane
    throw_angle: np.ndarray | None = None  # [rad] (P,) angle of each throw (crank frame)


@dataclass(frozen=True, kw_only=True)
class InternalMomentDetail(BalanceDetail):
    """Detail of ``balance.internal_moment``; None when not computed (no CrankMass sheet or no
    main journal spacing)."""

    vector: np.ndarray | None = None  # [N m] (M, 2) bending moment at each main (crank frame)
    without_counterweights: np.ndarray | None = None  # [N m] (M,) magnitude without them
    stations: np.ndarray | None = None  # [m] (M,) axial position of each main from the front


@dataclass(frozen=True, kw_only=True)
class CrankUnbalanceDetail(BalanceDetail):
    """Detail of ``balance.crank_unbalance``."""

    static_inherent: bool  # equal throws cancel as forces (judged statically)
    dynamic_inherent: bool  # and as couples (judged dynamically too)
    fraction: float  # [-] unbalance fraction above which a finding is raised
    throw_unbalance: float | None = None  # [kg m] mean rotating unbalance of one throw
    static_vector: np.ndarray | None = None  # [kg m] (2,) sum m rho (crank frame)
    couple_vector: np.ndarray | None = None  # [kg m^2] (2,) sum m rho z about the mid-plane
