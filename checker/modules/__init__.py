"""Graph calculations, one module per analysis family. Importing registers them."""

from .. import graph
from . import (  # noqa: F401
    balance,
    bearing_performance,
    crank_nose,
    damper_tuning,
    fatigue,
    flywheel,
    joints,
    loads,
    moft,
    torsion,
)

ORDER = ("loads", "bearings", "bearing_performance", "torsion", "joints", "fatigue", "balance",
         "flywheel", "damper")
"""Order of the modules in listings and in the report (each builds on the ones before)."""

_registered = dict(graph.MODULES)
graph.MODULES.clear()
graph.MODULES.update({m: _registered[m] for m in ORDER if m in _registered})
graph.MODULES.update({m: t for m, t in _registered.items() if m not in ORDER})
