"""The PDF engine in a process of its own, started before the analysis.

Importing WeasyPrint and setting it up (Pango, fonts, its stylesheets) takes about half a
second of processor time, and laying out and writing the report's PDF is the longest piece of
``checker report`` that cannot be split. :class:`PdfEngine` forks a process at the start of
the command that imports and warms WeasyPrint while the analysis runs in the command's own
process (the machine's other core); when the HTML is ready, the process lays it out (the
figures are placeholders of their exact pixel size, :mod:`checker.report.plots`), then takes
the results workbook and the drawn figures and writes the PDF. The command's process relays
the drawn figures and prints the engine's progress; a failure in the engine process comes back
as its exception.

Messages (each a tuple, pickled through one duplex pipe):

* command -> engine: ``("layout", html, figures, pending)`` (figure URL -> image bytes of the
  placeholders; URL -> drawing key of those still being drawn), then ``("book", bytes)`` and
  ``("images", {key: bytes})``; ``None`` ends an engine that is not needed.
* engine -> command: ``("progress", text)``, ``("pdf", bytes, pages, timings)`` or
  ``("error", exception)``.

Where the platform cannot fork, or with one core, :func:`start` returns None and the report is
laid out in the command's process (:func:`checker.report.render.build_report`).
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable

Progress = Callable[[str], None]

WARM_UP = ("<html><body><h2>Warm-up</h2><p>Text <b>bold</b> <i>italic</i> <span class=\"mono\">"
           "mono</span> 0.123</p><table class=\"data\"><thead><tr><th>a</th></tr></thead>"
           "<tbody><tr><td>1</td></tr></tbody></table></body></html>")
"""A page with the report's fonts and elements, laid out once in the engine process before the
report arrives (font loading and the first-use setup of the layout code)."""


class _ProgressToParent(logging.Handler):
    """WeasyPrint's page progress sent to the command's process."""

    def __init__(self, conn):
        super().__init__(logging.INFO)
        self.conn = conn

    def emit(self, record: logging.LogRecord) -> None:
        from .pdf_engine import PageProgress

        m = PageProgress.PAGE.search(record.getMessage())
        if m:
            self.conn.send(("progress", f"Laying out the PDF, page {m.group(1)}"))


def _serve(conn) -> None:
    """The engine process: import and warm WeasyPrint, then lay out and write one report."""
    from ..plumbing.forked import child_start
    from ..plumbing.gc_tuning import fewer_collections

    child_start()  # Ctrl-C and SIGTERM: the command handles them
    try:
        from ..plumbing.resources import templates_dir
        from . import pdf_engine

        wp = pdf_engine.load_weasyprint()
        html_class = pdf_engine.html_class(wp)
        html_class(string=WARM_UP, base_url=str(templates_dir())).render()
        fewer_collections()  # a short-lived process building many objects (see there)
        failed: BaseException | None = None
    except BaseException as exc:  # noqa: BLE001 - told when the report arrives
        failed = exc
    try:
        msg = conn.recv()
        if msg is None:
            return
        if failed is not None:
            raise failed
        _, html, figures, pending = msg
        conn.send(("pdf", *_lay_out_and_write(conn, wp, html_class, html, figures,
                                               pending)))
    except EOFError:  # the command ended
        return
    except BaseException as exc:  # noqa: BLE001 - every failure goes to the command
        try:
            conn.send(("error", exc))
        except Exception:  # noqa: BLE001 - an exception that does not pickle
            conn.send(("error", RuntimeError(f"{type(exc).__name__}: {exc}")))
    finally:
        conn.close()


def _lay_out_and_write(conn, wp, html_class, html: str, figures: dict[str, bytes],
                       pending: dict[str, tuple[int, int]]):
    """The PDF of ``html`` (figures served from ``figures``; those in ``pending`` replaced by
    the drawn ones the command sends): ``(pdf, pages, wall and processor times)``."""
    from ..plumbing.resources import templates_dir
    from . import pdf_engine

    t, c = time.perf_counter(), time.process_time()
    images = pdf_engine.FigureCache()
    logger = logging.getLogger("weasyprint.progress")
    logger.addHandler(_ProgressToParent(conn))
    logger.setLevel(logging.INFO)
    doc = html_class(string=html, base_url=str(templates_dir()),
                     url_fetcher=pdf_engine.fetcher(wp, figures)).render(cache=images)
    times = {"layout": (time.perf_counter() - t, time.process_time() - c)}
    t, c = time.perf_counter(), time.process_time()
    kind, book = conn.recv()
    if kind != "book":
        raise RuntimeError(f"the PDF engine expected the results workbook, got {kind!r}")
    conn.send(("progress", f"Writing the PDF ({len(doc.pages)} pages)"))

    def drawn() -> dict[tuple[int, int], bytes]:
        kind, value = conn.recv()
        if kind != "images":
            raise RuntimeError(f"the PDF engine expected the drawn figures, got {kind!r}")
        return value

    pdf = pdf_engine.write_with_figures(wp, doc, html, book, images, figures, pending, drawn)
    times["write"] = (time.perf_counter() - t, time.process_time() - c)
    times["wait"] = (images.wait, 0.0)
    return pdf, len(doc.pages), times


class PdfEngine:
    """WeasyPrint in a forked process (see the module); :meth:`close` ends it."""

    def __init__(self, process, conn):
        self.process = process
        self.conn = conn

    def lay_out(self, html: str, figures: dict[str, bytes],
                pending: dict[str, tuple[int, int]]) -> None:
        """Send the report's HTML: the engine lays it out from now on."""
        self._send(("layout", html, {k: bytes(v) for k, v in figures.items()},
                    dict(pending)))

    def send(self, kind: str, value) -> None:
        """Send the results workbook (``"book"``) or the drawn figures (``"images"``)."""
        self._send((kind, value))

    def _send(self, msg: tuple) -> None:
        try:
            self.conn.send(msg)
        except OSError:  # the engine failed and ended: its last message says why
            while True:
                self.handle(lambda _text: None)

    def handle(self, say: Progress) -> tuple | None:
        """One message of the engine: a progress line is told (None returned), the PDF
        returned as ``(pdf, pages, times)``, an error raised."""
        try:
            msg = self.conn.recv()
        except EOFError:
            self.process.join(timeout=10)
            raise RuntimeError(f"the PDF engine process ended (exit code"
                               f" {self.process.exitcode}) before the PDF was written"
                               ) from None
        if msg[0] == "progress":
            say(msg[1])
            return None
        if msg[0] == "error":
            raise msg[1]
        return msg[1:]

    def result(self, say: Progress) -> tuple[bytes, int, dict]:
        """Wait for the PDF (telling the engine's progress): ``(pdf, pages, times)``."""
        while (got := self.handle(say)) is None:
            pass
        self.process.join()
        self.close()
        return got

    def close(self) -> None:
        """End the engine process (at once if it is still working)."""
        p, self.process = self.process, None
        if p is None:
            return
        if p.is_alive():
            try:
                self.conn.send(None)
            except OSError:
                pass
            p.join(timeout=0.05)
        if p.is_alive():
            p.terminate()
        p.join()
        self.conn.close()


def start() -> PdfEngine | None:
    """The PDF engine started in a forked process (None where the platform cannot fork or
    has one core: the report is then laid out in this process)."""
    import multiprocessing as mp
    import os

    from ..plumbing.forked import hold_signals, release_signals

    if (os.cpu_count() or 1) < 2 or "fork" not in mp.get_all_start_methods():
        return None
    ctx = mp.get_context("fork")
    mine, theirs = ctx.Pipe(duplex=True)
    blocked = hold_signals()  # until the child has its own handlers
    try:
        p = ctx.Process(target=_serve, args=(theirs,), daemon=True)
        p.start()
    finally:
        release_signals(blocked)
    theirs.close()
    return PdfEngine(p, mine)
