"""Typed results of the crank geometry (:mod:`checker.modules.crank`): each throw's mass
properties and stiffness derived from sheet Crank, and the origin of every value of the crank
model the analyses use. Axes: T throws, P parts of a throw
(:data:`checker.calc.crank_geometry.PARTS`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class CrankDetail(Detail):
    """Detail shared by the ``crank.*`` quantities."""

    parts: tuple[str, ...]  # names of the P parts, front to rear
    part_mass: np.ndarray  # [kg] (T, P)
    part_y: np.ndarray  # [m] (T, P) mass centre towards the pin
    part_z: np.ndarray  # [m] (T, P) mass centre from the front journal mid-plane
    part_inertia: np.ndarray  # [kg m^2] (T, P) polar, about the main axis
    part_inertia_own: np.ndarray  # [kg m^2] (T, P) polar, about the part's mass centre
    stiffness_in_range: np.ndarray  # [-] (T,) bool: inside the stiffness model's fitted range
    stiffness_method: str  # how the throw stiffness is computed ("" when not available)
    stiffness_error: float | None  # stated relative error of the stiffness model
    model: tuple[dict, ...]  # ModelValue.as_dict() of every typed or derived model value
