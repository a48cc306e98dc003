"""Report sections: each calculation module contributes a section built from its quantities.

A section is a dict ``{"id", "title", "intro", "blocks"}``; blocks are
``{"type": "table", "caption", "columns", "rows"}``, ``{"type": "equations", "items":
[(name, equation, source)]}``, ``{"type": "figure", "svg", "caption"}``,
``{"type": "text", "text"}`` or ``{"type": "list", "items"}``. Sections only format numbers
that the calculations produced; they never compute physics.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..api import CheckResult

SECTIONS: dict[str, Callable[[CheckResult], dict]] = {}


def section(module: str):
    def deco(f):
        SECTIONS[module] = f
        return f

    return deco


def fmt(v, digits: int = 4) -> str:
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    if isinstance(v, str):
        return v
    return f"{v:.{digits}g}"


def build_sections(res: CheckResult) -> list[dict]:
    """Sections of the modules that ran, in module order."""
    import importlib
    import pkgutil

    from .. import report

    for m in pkgutil.iter_modules(report.__path__):
        if m.name.startswith("section_"):
            importlib.import_module(f"{report.__name__}.{m.name}")
    mods = [m for m in res.outcome.modules_run if m in SECTIONS]
    return _build_parallel(res, mods) if len(mods) > 1 else [SECTIONS[m](res) for m in mods]


_RESULT: CheckResult | None = None


def _one(module: str) -> dict:
    assert _RESULT is not None
    return SECTIONS[module](_RESULT)


def _build_parallel(res: CheckResult, mods: list[str]) -> list[dict]:
    """Draw the sections' figures in forked worker processes (matplotlib is single-threaded
    and drawing dominates the report's time); sequential where fork is unavailable."""
    import multiprocessing as mp
    import os
    from concurrent.futures import ProcessPoolExecutor

    global _RESULT
    workers = min(len(mods), os.cpu_count() or 1)
    if workers < 2 or "fork" not in mp.get_all_start_methods():
        return [SECTIONS[m](res) for m in mods]
    _RESULT = res
    try:
        with ProcessPoolExecutor(workers, mp_context=mp.get_context("fork")) as pool:
            # the slowest sections first, so the pool stays busy
            order = sorted(mods, key=lambda m: m not in ("torsion", "loads", "fatigue"))
            done = dict(zip(order, pool.map(_one, order)))
        return [done[m] for m in mods]
    finally:
        _RESULT = None
