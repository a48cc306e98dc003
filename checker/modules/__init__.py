"""The calculation modules, one per analysis family, and their registry.

:data:`REGISTRY` lists the analysis modules in the order of listings and of the report (each
builds on the ones before): name, title and the Python module holding its calculations.
Importing this package registers them with :mod:`checker.evaluation.graph` in that order, then
imports
the Python modules, which register their quantities and calculations. The graph imports no
module (``tests/test_import_cycles.py``): whoever runs it imports this package
(:mod:`checker.evaluation.ruletable`, and through it :mod:`checker.api`).
"""

from ..evaluation import graph

REGISTRY: tuple[tuple[str, str, str], ...] = (
    ("loads", "Crank-train loads", "loads"),
    ("bearings", "Bearing oil film (MOFT)", "bearings"),
    ("bearing_performance", "Bearing oil flow, friction and temperature", "bearing_performance"),
    ("torsion", "Torsional vibration", "torsion"),
    ("coupling", "Flexible coupling", "coupling"),
    ("misfire", "Misfire", "misfire"),
    ("joints", "Bolted joints", "joints"),
    ("fatigue", "Crankshaft fatigue", "fatigue"),
    ("balance", "Crankshaft balancing", "balance"),
    ("flywheel", "Flywheel and cyclic irregularity", "flywheel"),
    ("damper", "TV damper tuning", "damper_tuning"),
    ("crank", "Crank geometry", "crank"),
)
"""(module name, title, Python module) in report order; ``crank_nose`` adds calculations to
the ``fatigue`` module."""

ORDER = tuple(name for name, _title, _file in REGISTRY)
"""Order of the modules in listings and in the report."""

QUIET = ("crank",)
"""Modules run only when their sheet is given (``crank``: sheet Crank), listed only then."""

for _name, _title, _file in REGISTRY:
    graph.register_module(_name, _title, quiet=_name in QUIET)

from . import (  # noqa: E402, F401  (after the registry: their calculations name its modules)
    balance,
    bearing_performance,
    bearings,
    coupling,
    crank,
    crank_nose,
    damper_thermal,
    damper_tuning,
    fatigue,
    flywheel,
    joints,
    loads,
    misfire,
    torsion,
    torsion_stress,
)
