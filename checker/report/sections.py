"""Report sections: each calculation module contributes a section built from its quantities.

Adding a section: a module ``checker/report/section_<name>.py`` with a function decorated
``@section("<module name>", label="<words for the progress line>")`` that takes the
:class:`~checker.api.CheckResult` and returns a dict ``{"id", "title", "intro", "blocks"}``.
It is found automatically and shown when its calculation module ran, in module order.

Blocks (in the order a reader needs them: inputs, method and assumptions, judged worst cases,
plots):

* ``{"type": "table", "caption", "columns", "rows", "row_css"?}``: a table in the body. Keep
  it short (inputs, judged worst cases); per-speed results belong in the results workbook,
  which holds every quantity anyway. ``"detail": True`` moves a table out of the body into
  the results workbook (sheet named by ``"sheet"``).
* ``{"type": "figure", "png", "caption", "data"?}`` (``png``: the image bytes, the
  texts drawn on it in ``png.texts``): ``data`` names where the numbers behind
  the plot are: quantity names (their sheets in the results workbook) and/or extra sheets
  ``{"sheet", "title", "columns", "rows"}`` for curves that are not quantities (crank-angle
  traces); the report says so under the plot.
* ``{"type": "equations", "items": [(name, equation, source)]}``, ``{"type": "text",
  "text"}``, ``{"type": "list", "items"}``, ``{"type": "heading", "text"}``.

Sections only format numbers that the calculations produced; they never compute physics.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import display
from ..api import CheckResult

SECTIONS: dict[str, Callable[[CheckResult], dict]] = {}
LABELS: dict[str, str] = {}
"""Words for the progress line "Drawing <label> figures", per module."""


def section(module: str, label: str | None = None):
    def deco(f):
        SECTIONS[module] = f
        LABELS[module] = label or module
        return f

    return deco


def fmt(v, digits: int = display.SIG) -> str:
    """A number as the report shows it (``digits`` significant digits, ``-`` for none)."""
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    if isinstance(v, str):
        return v
    return display.number(float(v), digits)


def in_unit(values, si_unit: str, unit: str):
    """SI ``values`` (float or array) in a display ``unit``, through
    :func:`checker.units.from_si` (offset units converted affinely: K -> °C subtracts 273.15).
    Every unit conversion of a section goes through here or :func:`display_values`."""
    from ..units import from_si

    return from_si(np.asarray(values, dtype=float) if not np.isscalar(values) else values,
                   si_unit, unit)


def rpm(speed):
    """Shaft speed(s) in rad/s as rpm."""
    return in_unit(speed, "rad/s", "rpm")


def display_values(q, values=None):
    """A quantity's SI values (or ``values`` of it) in its declared display unit
    (:attr:`checker.graph.QuantitySpec.display_unit`), with that unit as displayed."""
    unit = q.spec.display_unit or q.spec.unit
    v = q.values if values is None else values
    return in_unit(v, q.spec.unit or "", unit) if unit else v, display.unit_text(unit)


def load_sections() -> None:
    """Import every ``section_*`` module so that it registers itself."""
    import importlib
    import pkgutil

    from .. import report

    for m in pkgutil.iter_modules(report.__path__):
        if m.name.startswith("section_"):
            importlib.import_module(f"{report.__name__}.{m.name}")


def modules_with_sections(res: CheckResult) -> list[str]:
    load_sections()
    extra = ["remedies"] if res.remedies is not None or res.corners is not None else []
    return [m for m in res.outcome.modules_run if m in SECTIONS] + extra


def build_sections(res: CheckResult, progress: Callable[[str], None] | None = None
                   ) -> list[dict]:
    """Sections of the modules that ran, in module order (figures drawn in worker processes
    where the platform can fork)."""
    return SectionJob(res, progress).result()


def _one(module: str, progress: Callable[[str], None] | None = None) -> dict:
    if progress is not None:
        progress(f"Drawing the {LABELS.get(module, module)} figures")
    return SECTIONS[module](_RESULT if _RESULT is not None else _ARG)


_RESULT: CheckResult | None = None
_ARG: CheckResult | None = None
_PROGRESS: Callable[[str], None] | None = None


def _worker(module: str) -> dict:
    return _one(module, None)  # progress is told by the parent (it owns stderr)


def _worker_start(nice: int) -> None:
    """In a drawing process: lower its priority by ``nice``."""
    import os

    if nice:
        try:
            os.nice(nice)
        except OSError:
            pass


SLOW_FIRST = ("torsion", "loads", "fatigue", "bearings")
"""Sections with the most figures, started first so that the workers stay busy."""


class SectionJob:
    """Sections being built: in forked worker processes (matplotlib is single-threaded and
    drawing dominates a section's time) while the caller does other work; call
    :meth:`result` to wait. Sequential where fork is unavailable or with one core."""

    def __init__(self, res: CheckResult, progress: Callable[[str], None] | None = None,
                 workers: int | None = None, modules: list[str] | None = None,
                 nice: int = 0):
        """``modules``: the sections to build (default: every section of ``res``);
        ``nice``: the workers' scheduling priority increment (``os.nice``): drawing started
        before other work of the command (the remedies' search) takes only the processor time
        that work leaves idle."""
        import multiprocessing as mp
        import os

        global _RESULT, _PROGRESS
        self.res = res
        self.mods = modules_with_sections(res) if modules is None else list(modules)
        self.progress = progress
        self.pool = None
        self.futures: dict[str, object] = {}
        cores = os.cpu_count() or 1
        if not self.mods or cores < 2 or "fork" not in mp.get_all_start_methods():
            return
        n = max(1, min(len(self.mods), workers or cores))
        from concurrent.futures import ProcessPoolExecutor

        _RESULT, _PROGRESS = res, progress
        try:
            self.pool = ProcessPoolExecutor(n, mp_context=mp.get_context("fork"),
                                            initializer=_worker_start, initargs=(nice,))
            order = sorted(self.mods, key=lambda m: (m not in SLOW_FIRST,
                                                     SLOW_FIRST.index(m) if m in SLOW_FIRST
                                                     else 0))
            for m in order:
                self.futures[m] = self.pool.submit(_worker, m)
        finally:
            _RESULT, _PROGRESS = None, None
        if progress is not None:  # drawn in parallel from now on; told here (stderr is ours)
            for m in order:
                progress(f"Drawing the {LABELS.get(m, m)} figures")

    def result(self) -> list[dict]:
        global _ARG
        if self.pool is None:
            _ARG = self.res
            try:
                return [_one(m, self.progress) for m in self.mods]
            finally:
                _ARG = None
        try:
            return [self.futures[m].result() for m in self.mods]
        finally:
            self.pool.shutdown()

    def close(self) -> None:
        """End the drawing processes without waiting for the sections (the command failed
        before it needed them)."""
        if self.pool is None:
            return
        from ..forked import end_pool

        pool, self.pool = self.pool, None
        end_pool(pool)


def param_table(caption: str, items: list[tuple[str, str]], pairs: int = 2) -> dict:
    """A compact inputs table: ``(parameter, value with unit)`` pairs, ``pairs`` per row
    (filled column by column)."""
    n = max(1, (len(items) + pairs - 1) // pairs)
    rows = []
    for r in range(n):
        row: list[str] = []
        for p in range(pairs):
            k = p * n + r
            row += list(items[k]) if k < len(items) else ["", ""]
        rows.append(row)
    share = 100 / pairs
    return {"type": "table", "caption": caption, "columns": ["parameter", "value"] * pairs,
            "rows": rows, "widths": [round(share * 0.62, 1), round(share * 0.38, 1)] * pairs}


def merge_items(rows: list[list[str]], css: list[str]) -> tuple[list[list[str]], list[str]]:
    """Rows equal in every cell but the first (the item) merged into one row naming every
    item ("BE1, BE2, BE3, BE4"), in the order of first appearance."""
    out: dict[tuple, list] = {}
    for row, c in zip(rows, css):
        key = (tuple(row[1:]), c)
        if key in out:
            out[key][0][0] += ", " + row[0]
        else:
            out[key] = [list(row), c]
    return [v[0] for v in out.values()], [v[1] for v in out.values()]
