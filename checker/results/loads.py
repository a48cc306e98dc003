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
    scheme: str = "determinate"  # Engine 'Main bearing supports' the main loads come from
    beam: CrankBeamDetail | None = None  # the continuous beam (None: determinate scheme)
    main_determinate: Vector2 | None = None  # [N] (M, C, S, N) determinate main loads, block
    #   frame, beside a continuous beam's (None: the scheme is determinate)


@dataclass(frozen=True, kw_only=True)
class SpecificLoadDetail(Detail):
    """Detail of ``bearing.peak_specific_load``."""

    theta_at_max: np.ndarray  # [rad] (B, C, S) cycle angle of the peak load (nan: missing)


@dataclass(frozen=True, kw_only=True)
class CrankBeamDetail(Detail):
    """The crank as a continuous beam (Engine 'Main bearing supports'), as the outputs show it:
    enough to recompute the main-bearing loads with another beam solver. Crank frame
    (:mod:`checker.calc.crank_beam`): ``z`` the crank axis, throw 1's pin at angle
    ``gamma_1``; the loads and reactions at one operating point (``case``, ``speed``)."""

    scheme: str
    nodes: np.ndarray  # [m] (n_node, 3)
    elements: np.ndarray  # (n_el, 2) node indices
    axial_stiffness: np.ndarray  # [N] (n_el,) E A
    torsional_stiffness: np.ndarray  # [N m^2] (n_el,) G J
    bending_stiffness: np.ndarray  # [N m^2] (n_el, 2) E I about axis 1 and axis 2
    first_axis: np.ndarray  # (n_el, 3) vector giving each element's axis 1
    support_nodes: np.ndarray  # (n_main,)
    support_stiffness: np.ndarray  # [N/m] (n_main,), inf = rigid
    support_offset: np.ndarray  # [m] (n_main,) block-frame y offset (misalignment)
    torsion_node: int  # node whose rotation about z is held
    load_nodes: np.ndarray  # (n_load,)
    case: str  # load case of the recorded loads
    speed: float  # [rad/s] speed of the recorded loads
    angles: np.ndarray  # [rad] (n_angle,) crank angles of the recorded loads
    node_loads: np.ndarray  # [N, N m] (n_angle, n_load, 6): force and moment, crank frame
    main_loads: np.ndarray  # [N] (n_angle, n_main, 2): force of each journal on its bearing

    def as_dict(self) -> dict:
        """JSON-ready (SI; ``null`` for a rigid support's stiffness)."""
        def num(a: np.ndarray) -> list:
            return [num(x) for x in a] if np.ndim(a) else float(f"{float(a):.6g}")

        return {
            "scheme": self.scheme, "frame": "crank (z = crank axis, throw angles as in"
            " loads)", "nodes_m": num(self.nodes),
            "elements": [{"nodes": [int(i), int(j)], "EA_N": num(ea), "GJ_N_m2": num(gj),
                          "EI_axis1_N_m2": num(ei[0]), "EI_axis2_N_m2": num(ei[1]),
                          "axis1": num(ax)}
                         for (i, j), ea, gj, ei, ax in zip(
                             self.elements, self.axial_stiffness, self.torsional_stiffness,
                             self.bending_stiffness, self.first_axis, strict=True)],
            "supports": [{"node": int(n), "stiffness_N_per_m": (None if not np.isfinite(k)
                                                                else num(k)),
                          "offset_m": num(o)}
                         for n, k, o in zip(self.support_nodes, self.support_stiffness,
                                            self.support_offset, strict=True)],
            "torsion_held_at_node": self.torsion_node,
            "load_nodes": [int(n) for n in self.load_nodes],
            "operating_point": {"case": self.case,
                                "speed_rpm": float(f"{self.speed * 30.0 / np.pi:.6g}")},
            "angles_deg": num(np.rad2deg(self.angles)),
            "node_loads_N_Nm": num(self.node_loads),
            "main_loads_N": num(self.main_loads),
        }
