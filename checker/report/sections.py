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
  its arguments and returns :func:`~checker.report.plots.to_image` of it: the report builds its
  sections without matplotlib and draws the figures in other processes while the PDF is laid
  out (each argument is used then: pass values, not something changed afterwards).
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
    """Sections of the modules that ran, in module order, their figures drawn."""
    return SectionJob(res, progress).result()


def _one(module: str, res: CheckResult, progress: Callable[[str], None] | None = None
         ) -> dict:
    if progress is not None:
        progress(f"Drawing the {LABELS.get(module, module)} figures")
    return SECTIONS[module](res)


def _drawer(tasks, conn, nice: int) -> None:
    """A drawing process: draws the deferred figures (:data:`checker.report.plots.DEFERRED`,
    inherited by fork) whose places it takes from ``tasks`` (None: no more) and sends each
    to the parent, ``("image", key, image)``; then ``("done", None, None)``. An exception is
    sent as ``("error", None, exception)``."""
    from ..forked import child_start
    from ..gc_tuning import fewer_collections
    from . import plots

    child_start(nice)  # Ctrl-C and SIGTERM: the parent handles them
    fewer_collections()  # a short-lived process building many objects (see there)
    try:
        while (i := tasks.get()) is not None:
            conn.send(("image", (plots.DRAWER, i), plots.draw_deferred(i)))
        conn.send(("done", None, None))
    except BaseException as exc:  # noqa: BLE001 - every failure goes to the parent
        try:
            conn.send(("error", None, exc))
        except Exception:  # noqa: BLE001 - an exception that does not pickle
            conn.send(("error", None, RuntimeError(f"{type(exc).__name__}: {exc}")))
    finally:
        conn.close()


class SectionJob:
    """The report's sections, built in this process when the job is made.

    With ``defer`` (where the platform can fork and has two cores or more) their figures are
    placeholders of their exact pixel size (:class:`checker.report.plots.Deferred`, key
    ``png.key``): the sections need no matplotlib and are ready at once, the PDF can be laid
    out from them, and the figures are built and drawn by forked drawing processes from
    :meth:`start` on (matplotlib is single-threaded); :meth:`images` waits for them. Without
    ``defer`` the figures are drawn here while the sections are built."""

    def __init__(self, res: CheckResult, progress: Callable[[str], None] | None = None,
                 workers: int | None = None, modules: list[str] | None = None,
                 nice: int = 0, defer: bool = False):
        """``modules``: the sections to build (default: every section of ``res``);
        ``workers``: drawing processes (default: one per core); ``nice``: their scheduling
        priority increment (``os.nice``): drawing started before other work of the command
        (the remedies' search) takes only the processor time that work leaves idle;
        ``defer``: figures drawn later, in other processes (see the class)."""
        import multiprocessing as mp
        import os

        from . import plots

        self.res = res
        load_sections()
        self.mods = modules_with_sections(res) if modules is None else list(modules)
        self.progress = progress
        self.nice = nice
        cores = os.cpu_count() or 1
        self.workers = max(1, workers or cores)
        self.defer = defer and cores >= 2 and "fork" in mp.get_all_start_methods()
        self.procs: list = []
        self.conns: list = []
        self._open: dict[int, object] = {}
        self._images: dict[tuple[int, int], bytes] = {}
        self._done: set[int] = set()
        self._started = False
        self.figures: list = []
        if self.defer:
            plots.DEFERRED, plots.DRAWER = [], 0
        try:
            self._sections = [_one(m, res, None if self.defer else progress)
                              for m in self.mods]
        finally:
            if self.defer:
                self.figures, plots.DEFERRED = plots.DEFERRED, None

    def start(self) -> None:
        """Start drawing the deferred figures in forked processes (once)."""
        if self._started or not self.figures:
            self._started = True
            return
        import multiprocessing as mp

        from ..forked import hold_signals, release_signals
        from . import plots

        self._started = True
        # pyplot imported once here, before the fork, rather than by each drawing process
        # (about 0.3 s of processor time each)
        plots.pyplot()
        n = min(len(self.figures), self.workers)
        ctx = mp.get_context("fork")
        tasks = ctx.SimpleQueue()
        for i in list(range(len(self.figures))) + [None] * n:  # short items: the pipe holds them
            tasks.put(i)
        plots.DEFERRED = self.figures  # inherited by the drawing processes
        # SIGINT and SIGTERM held back while the processes are forked: a signal that reached
        # a child between its fork and its own handlers (in _drawer) would raise the parent's
        # exception there, with a traceback; each child takes them once its handlers are set
        blocked = hold_signals()
        try:
            for w in range(n):
                recv, send = ctx.Pipe(duplex=False)
                p = ctx.Process(target=_drawer, args=(tasks, send, self.nice), daemon=True)
                p.start()
                send.close()  # the child's copy only: its end of file says it ended
                self.procs.append(p)
                self.conns.append(recv)
                self._open[w] = recv
        except BaseException:
            self.close()
            raise
        finally:
            plots.DEFERRED = None
            release_signals(blocked)
        if self.progress is not None:  # drawn in parallel from now on (stderr is ours)
            for m in self.mods:
                self.progress(f"Drawing the {LABELS.get(m, m)} figures")

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
                    kind, key, value = conn.recv()
                except EOFError:
                    del self._open[w]
                    if w not in self._done:
                        self.procs[w].join(timeout=10)  # its end of file: it is ending
                        code = self.procs[w].exitcode
                        self.close()
                        raise RuntimeError(f"a drawing process ended (exit code {code})"
                                           " before its figures were drawn") from None
                    continue
                if kind == "image":
                    self._images[key] = value
                elif kind == "done":
                    self._done.add(w)
                else:
                    self.close()
                    raise value

    def result(self) -> list[dict]:
        """The sections (with ``defer``: their figures placeholders, see :meth:`images`)."""
        return self._sections

    def images(self, also: tuple | None = None) -> dict[tuple[int, int], bytes]:
        """The drawn figures of the placeholders, by ``png.key`` (starts the drawing if not
        started and waits for it; empty without ``defer``). The drawing processes have ended
        when it returns. ``also``: see :meth:`_receive`."""
        self.start()
        if self.procs:
            self._receive(lambda: len(self._done) == len(self.procs), also)
            for p in self.procs:
                p.join()
            for c in self.conns:
                c.close()
            self.procs, self._open = [], {}
        return self._images

    def close(self) -> None:
        """End the drawing processes without waiting for the figures (the command failed
        before it needed them)."""
        procs, self.procs, self._open = self.procs, [], {}
        self.figures = []
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
