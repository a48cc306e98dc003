"""Two example workbooks for the class rules: a constant-speed generating set and a marine
propulsion engine, both an in-line six medium-speed diesel of the Wärtsilä 20 class.

:func:`genset_content` reads ``templates/example_genset.toml`` (engine class ``industrial``):
the engine drives a generator through a flexible coupling at a constant 1000 rpm (50 Hz); full
load is given at the rated speed only, no load over the run-up to the overspeed.
:func:`marine_content` reads ``templates/example_marine.toml`` (engine class ``marine``): the
engine drives a fixed-pitch propeller through the same coupling and a 4:1 reduction gear
(gearbox, shafting and propeller referred to the engine speed); full load follows the
propeller law, the propeller's inertia includes the entrained water and its damping is the
slope of the propeller law (sheet Driven).

Sources
-------
[W20-2003] Wärtsilä Corporation, trade press release "2000th Wärtsilä 20 engine", 28 January
    2003: up to 180 kW/cylinder at up to 1000 rev/min, four to nine cylinders in-line.
[W20-2017] Wärtsilä, "Wärtsilä 20 - Small changes, big results" (Twentyfour7): the upgraded
    engine runs up to 1200 rpm, from 1000 rpm (mechanical propulsion) and 900 rpm (60 Hz
    generating sets).
[RATO] VULKAN RATO-DS series 2200, rubber quality 5, data sheet: T_KN 50 kNm, T_KW 15 kNm,
    P_KV50 0.62 kW, C_Tdyn 262.5 kNm/rad nominal / 183.75 warm, psi 1.13 nominal / 0.79 warm.
[MAN] MAN Energy Solutions, "Basic principles of ship propulsion", "Slip ratio and propeller
    law" (torque ~ n^2 along the propeller curve).

What the sources do not give is marked ``ASSUMPTION``: the bore and stroke as commonly quoted
(200 x 280 mm; the project guide could not be read), and the whole crank train (bearings,
crank, masses, torsional model, damper, joints), which is the I6 example's
(:mod:`checker.workbook.example_i6`) scaled by geometric similarity (factor 1.97 =
sqrt(200/105 x 280/137): lengths x 1.97, masses x 1.97^3, inertias x 1.97^5, torsional
stiffness x 1.97^3, damping x 1.97^4). The generator's and the propeller's inertias, the
gear ratio and the shafting are assumptions of their size. The files were derived once from
the I6's data file; since then they are data (``scripts/make_example_derived.py`` keeps
their derived cells current).
"""

from __future__ import annotations

from typing import Any

from .example_data import load_example


def genset_content() -> dict[str, Any]:
    """The genset workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``."""
    return load_example("genset")


def marine_content() -> dict[str, Any]:
    """The marine propulsion workbook, as :func:`genset_content`."""
    return load_example("marine")


__all__ = ["genset_content", "marine_content"]
