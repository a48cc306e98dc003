"""Typed results of the bearing analyses: the oil film (``bearing.moft*``, module
``bearings``) and the bearing performance (heat balance, oil flow, friction, peak film
pressure; module ``bearing_performance``).

Array axes: ``item`` = bearing (the rows of ``loads.bearing_load``), ``case`` = load case
(full, no), ``speed`` = engine speed; orbits add ``angle`` (crank angle over the 720° cycle,
the orbit's time steps). All values SI.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import Detail


@dataclass(frozen=True, kw_only=True)
class FilmOrbit:
    """Periodic journal orbits of the bearings that could be solved (rows of complete data)."""

    rows: np.ndarray  # int, (row,): index of each solved row into the item axis
    theta: np.ndarray  # rad, (angle,): crank angle of the orbit steps
    eps_x: np.ndarray  # -, (row, case, speed, angle): eccentricity ratio, orbit frame X
    eps_y: np.ndarray  # -, (row, case, speed, angle): eccentricity ratio, orbit frame Y
    converged: np.ndarray  # bool, (row, case, speed): orbit periodic
    collapse: np.ndarray  # bool, (row, case, speed): film collapse (eccentricity -> 1)
    n_cycles: np.ndarray  # int, (row, case, speed): cycles integrated


@dataclass(frozen=True, kw_only=True)
class FilmDetail(Detail):
    """Minimum oil film thickness by the mobility method (``bearing.moft``,
    ``bearing.moft_short``, ``bearing.moft_finite``)."""

    model: str  # mobility model key: closed_form, exact_table, reynolds_map, butenschoen
    model_text: str  # the model in words, with its source
    eps_max: np.ndarray  # -, (item, case, speed): largest eccentricity ratio of the cycle
    theta_h_min: np.ndarray  # rad, (item, case, speed): crank angle of the thinnest film
    viscosity: float | np.ndarray  # Pa s: scalar, or (item, case, speed) (heat balance)
    film_temperature: float | np.ndarray  # K: scalar, or (item, case, speed) (heat balance)
    p_max: np.ndarray | None = None  # Pa, (item, case, speed): peak short-bearing pressure
    # (closed-form model only, else None)
    theta_p_max: np.ndarray | None = None  # rad, (item, case, speed): crank angle of p_max
    orbit: FilmOrbit | None = None  # the orbits (None: no bearing could be solved)
    l_over_d: dict[str, float]  # -, per bearing name: effective length / diameter


@dataclass(frozen=True, kw_only=True)
class HeatBalanceDetail(Detail):
    """Heat balance of the bearings (film temperature, friction, oil flows; and the engine's
    bearing friction power, which shares it)."""

    feeds: dict[str, str]  # per bearing name: oil feed kind (full, partial, hole, '+'-joined,
    # or none)
    heat_to_oil: float  # -: fraction of the friction heat carried away by the oil
    t_supply: float  # K: oil supply temperature
    p_supply: float | None  # Pa (gauge): oil supply pressure (None: not given)
    evaluations: int | None = None  # orbit evaluations of the balance (None: nothing solved)
    change_max: float | None = None  # K: largest last temperature change of the iteration
    extrapolated: bool | None = None  # a film temperature beyond the viscosity data
    t_range: tuple[float, float] | None = None  # K: lowest and highest film temperature


@dataclass(frozen=True, kw_only=True)
class FilmPressureDetail(Detail):
    """Peak oil-film pressure over the cycle (``bearing.peak_film_pressure``, finite length;
    ``bearing.peak_film_pressure_short``, short bearing)."""

    theta_p_max: np.ndarray  # rad, (item, case, speed): crank angle of the peak (NaN: none)
    film_temperature: float | np.ndarray | None  # K: of the film-thickness orbits used
    model_text: str  # the pressure model in words
