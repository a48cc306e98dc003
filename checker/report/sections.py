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
    out = []
    for m in res.outcome.modules_run:
        f = SECTIONS.get(m)
        if f is not None:
            out.append(f(res))
    return out
