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
  traces); the report says so under the plot. ``png`` comes from
  :func:`checker.report.plots.later` with a module-level function that makes the figure from
  its arguments and returns :func:`~checker.report.plots.to_image` of it: a drawing process
  of the report sends its sections before it builds a figure, and builds and draws them
  while the PDF is laid out (each argument is used then: pass values that do not change).
* ``{"type": "equations", "items": [(name, equation, source)]}``, ``{"type": "text",
  "text"}``, ``{"type": "list", "items"}``, ``{"type": "heading", "text"}``.

Sections only format numbers that the calculations produced; they never compute physics.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..api import CheckResult
from ..results import display

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
    :func:`checker.workbook.units.from_si` (offset units converted affinely: K -> °C subtracts
    273.15).
    Every unit conversion of a section goes through here or :func:`display_values`."""
    from ..workbook.units import from_si

    return from_si(np.asarray(values, dtype=float) if not np.isscalar(values) else values,
                   si_unit, unit)


def rpm(speed):
    """Shaft speed(s) in rad/s as rpm."""
    return in_unit(speed, "rad/s", "rpm")


def display_values(q, values=None):
    """A quantity's SI values (or ``values`` of it) in its declared display unit
    (:attr:`checker.evaluation.graph.QuantitySpec.display_unit`), with that unit as displayed."""
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


SLOW_FIRST = ("torsion", "loads", "fatigue", "bearings")
"""Sections with the most figures, started first so that the workers stay busy."""


def _drawer(worker: int, tasks, conn, nice: int, defer: bool) -> None:
    """A drawing process: builds the sections of the modules it takes from ``tasks`` (None:
    no more) and sends each to the parent, ``("section", module, dict)``; with ``defer`` its
    figures are placeholders (:class:`checker.report.plots.Deferred`) and it builds and draws
    them after the last section, ``("images", None, {(worker, index): image})``; then
    ``("done", None, None)``. An exception of a section is sent as ``("error", module,
    exception)``."""
    from ..plumbing.forked import child_start
    from ..plumbing.gc_tuning import fewer_collections
    from . import plots

    child_start(nice)  # Ctrl-C and SIGTERM: the parent handles them
    fewer_collections()  # a short-lived process building many objects (see there)
    plots.DEFERRED = [] if defer else None
    plots.DRAWER = worker
    try:
        while (module := tasks.get()) is not None:
            # progress is told by the parent (it owns stderr)
            conn.send(("section", module, _one(module, None)))
        if defer:
            images = {}
            for i in range(len(plots.DEFERRED)):  # sizes checked where they replace
                images[(worker, i)] = plots.draw_deferred(i)  # their placeholders
            conn.send(("images", None, images))
        conn.send(("done", None, None))
    except BaseException as exc:  # noqa: BLE001 - every failure goes to the parent
        try:
            conn.send(("error", None, exc))
        except Exception:  # noqa: BLE001 - an exception that does not pickle
            conn.send(("error", None, RuntimeError(f"{type(exc).__name__}: {exc}")))
    finally:
        conn.close()


class SectionJob:
    """Sections being built in forked drawing processes (matplotlib is single-threaded and
    drawing dominates a section's time) while the caller does other work; :meth:`result`
    waits for the sections. Sequential where fork is unavailable or with one core.

    With ``defer`` the figures of the sections are placeholders of their exact pixel size
    (:class:`checker.report.plots.Deferred`, key ``png.key``): the sections arrive when their
    content is known (a figure made by :func:`checker.report.plots.later` is not even built
    yet), and the processes build and draw the figures while the caller lays the PDF out;
    :meth:`images` waits for them."""

    def __init__(self, res: CheckResult, progress: Callable[[str], None] | None = None,
                 workers: int | None = None, modules: list[str] | None = None,
                 nice: int = 0, defer: bool = False):
        """``modules``: the sections to build (default: every section of ``res``);
        ``nice``: the workers' scheduling priority increment (``os.nice``): drawing started
        before other work of the command (the remedies' search) takes only the processor time
        that work leaves idle; ``defer``: figures drawn after every section is built (see the
        class)."""
        import multiprocessing as mp
        import os

        from ..plumbing.forked import hold_signals, release_signals

        global _RESULT
        self.res = res
        load_sections()
        self.mods = modules_with_sections(res) if modules is None else list(modules)
        self.progress = progress
        self.defer = False
        self.procs: list = []
        self.conns: list = []
        self._open: dict[int, object] = {}
        self._sections: dict[str, dict] = {}
        self._images: dict[tuple[int, int], bytes] = {}
        self._done: set[int] = set()
        cores = os.cpu_count() or 1
        if not self.mods or cores < 2 or "fork" not in mp.get_all_start_methods():
            return
        n = max(1, min(len(self.mods), workers or cores))
        ctx = mp.get_context("fork")
        order = sorted(self.mods, key=lambda m: (m not in SLOW_FIRST,
                                                 SLOW_FIRST.index(m) if m in SLOW_FIRST
                                                 else 0))
        tasks = ctx.SimpleQueue()
        for m in order + [None] * n:  # a few short items: they fit the pipe's buffer
            tasks.put(m)
        self.defer = defer
        # pyplot imported once here, before the fork, rather than by each drawing process
        # (about 0.3 s of processor time each; the processes start drawing at once)
        from . import plots

        plots.pyplot()
        _RESULT = res
        # SIGINT and SIGTERM held back while the processes are forked: a signal that reached
        # a child between its fork and its own handlers (in _drawer) would raise the parent's
        # exception there, with a traceback; each child takes them once its handlers are set
        blocked = hold_signals()
        try:
            for w in range(n):
                recv, send = ctx.Pipe(duplex=False)
                p = ctx.Process(target=_drawer, args=(w, tasks, send, nice, defer),
                                daemon=True)
                p.start()
                send.close()  # the child's copy only: its end of file says it ended
                self.procs.append(p)
                self.conns.append(recv)
                self._open[w] = recv
        except BaseException:
            self.close()
            raise
        finally:
            _RESULT = None
            release_signals(blocked)
        if progress is not None:  # drawn in parallel from now on; told here (stderr is ours)
            for m in order:
                progress(f"Drawing the {LABELS.get(m, m)} figures")

    def _receive(self, until, also: tuple | None = None) -> None:
        """Messages of the drawing processes until ``until()`` holds; ``also``: ``(connection,
        handler)`` of another process whose messages are handled meanwhile (the PDF
        engine's progress)."""
        from multiprocessing.connection import wait

        while not until():
            if not self._open:
                raise RuntimeError("the drawing processes ended without every figure")
            extra = [also[0]] if also is not None else []
            for conn in wait(list(self._open.values()) + extra):
                if extra and conn is extra[0]:
                    also[1]()
                    continue
                w = next(k for k, c in self._open.items() if c is conn)
                try:
                    kind, module, value = conn.recv()
                except EOFError:
                    del self._open[w]
                    if w not in self._done:
                        self.procs[w].join(timeout=10)  # its end of file: it is ending
                        code = self.procs[w].exitcode
                        self.close()
                        raise RuntimeError(f"a drawing process ended (exit code {code})"
                                           " before its figures were drawn") from None
                    continue
                if kind == "section":
                    self._sections[module] = value
                elif kind == "images":
                    self._images.update(value)
                elif kind == "done":
                    self._done.add(w)
                else:
                    self.close()
                    raise value

    def result(self) -> list[dict]:
        global _ARG
        if not self.procs:
            _ARG = self.res
            try:
                return [_one(m, self.progress) for m in self.mods]
            finally:
                _ARG = None
        self._receive(lambda: len(self._sections) == len(self.mods))
        if not self.defer:
            self.images()
        return [self._sections[m] for m in self.mods]

    def images(self, also: tuple | None = None) -> dict[tuple[int, int], bytes]:
        """The drawn figures of the placeholders, by ``png.key`` (waits for them; empty
        without ``defer``). The drawing processes have ended when it returns. ``also``: see
        :meth:`_receive`."""
        if self.procs:
            self._receive(lambda: len(self._done) == len(self.procs), also)
            for p in self.procs:
                p.join()
            for c in self.conns:
                c.close()
            self.procs, self._open = [], {}
        return self._images

    def close(self) -> None:
        """End the drawing processes without waiting for the sections (the command failed
        before it needed them)."""
        procs, self.procs, self._open = self.procs, [], {}
        for p in procs:
            if p.is_alive():
                p.terminate()
        for p in procs:
            p.join()
        for c in self.conns:
            c.close()


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
