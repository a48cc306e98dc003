"""The PDF engine's side of the report: WeasyPrint loaded (with the report's user-agent
stylesheet), the figures served from memory, the drawn figures put in place of their
placeholders when the file is written, and the file written with its attachments.

Both the command's process (:mod:`checker.report.render`) and the forked PDF engine
(:mod:`checker.report.pdf_process`) use it; it imports neither of them.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import logging
import re
import time
from collections.abc import Callable

from ..plumbing import pdf_compression
from . import results_book

Progress = Callable[[str], None]


WEASYPRINT_HELP = (
    "WeasyPrint could not load its system libraries (Pango). Install them, e.g. on Debian/"
    "Ubuntu: apt-get install libpango-1.0-0 libpangoft2-1.0-0 fonts-dejavu-core"
)


FIGURE_SCHEME = "checker-figure:"


def fetcher(wp, figures: dict[str, bytes]):
    """A WeasyPrint URL fetcher that serves the report's figures from memory."""

    class Fetcher(wp.urls.URLFetcher):
        def fetch(self, url, headers=None):
            if url.startswith(FIGURE_SCHEME):
                return wp.urls.URLFetcherResponse(url, body=figures[url],
                                                  headers={"Content-Type": "image/jpeg"})
            return super().fetch(url, headers)

    return Fetcher()


def load_weasyprint():
    from ..plumbing.pdf_engine_import import import_weasyprint

    try:
        weasyprint = import_weasyprint()
    except OSError as exc:  # missing Pango
        raise RuntimeError(WEASYPRINT_HELP + f" ({exc})") from None
    return weasyprint


def html_class(wp):
    """WeasyPrint's ``HTML`` class, which the report is laid out with (below WeasyPrint's own
    user-agent stylesheet: a shorter one of the report's own saved less than 3 % of
    `checker report` and was dropped, docs/benchmarks.md, "What each trick saves")."""
    return wp.HTML


def write_pdf(wp, doc, html: str, attachments) -> bytes:
    import io

    day = _dt.datetime.combine(_dt.date.today(), _dt.time())
    files = [wp.Attachment(file_obj=io.BytesIO(data), name=name, description=desc,
                           created=day, modified=day) for name, data, desc in attachments]
    ident = hashlib.sha256(html.encode("utf-8")).hexdigest()[:32].encode()
    with pdf_compression.flate_level(pdf_compression.FLATE_LEVEL):
        return doc.write_pdf(pdf_identifier=ident, attachments=files)


def write_with_figures(wp, doc, html: str, book: bytes, images: FigureCache,
                       figures: dict[str, bytes], pending: dict[str, tuple[int, int]],
                       drawn: Callable[[], dict[tuple[int, int], bytes]]) -> bytes:
    """The laid-out report's PDF with the results workbook ``book`` attached; the figures
    still being drawn (``pending``) are fetched from ``drawn()`` when the writer first reads
    one (:meth:`FigureCache.arm`). Never written with a placeholder."""
    images.arm(figures, pending, drawn)
    pdf = write_pdf(wp, doc, html, [(results_book.ATTACHMENT_NAME, book,
                                  "Every computed quantity, the rule results and the plot"
                                  " data of this report")])
    if not images.filled:
        raise RuntimeError("the PDF was written without its drawn figures")
    return pdf


class PageProgress(logging.Handler):
    """WeasyPrint's progress log ("Step 5 - Creating layout - Page 12") as progress lines."""

    PAGE = re.compile(r"Creating layout - Page (\d+)$")

    def __init__(self, progress: Progress):
        super().__init__(logging.INFO)
        self.progress = progress

    def emit(self, record: logging.LogRecord) -> None:
        m = self.PAGE.search(record.getMessage())
        if m:
            self.progress(f"Laying out the PDF, page {m.group(1)}")


class FigureCache(dict):
    """WeasyPrint's image cache (a dict: URL -> image, data key -> image bytes) that puts the
    drawn figures in place of their placeholders when the PDF writer first reads the data of
    one (:meth:`arm`): the figures are drawn while the PDF is laid out and its pages are
    drawn, and are needed only when the file is serialised. An image keeps its placeholder's
    size (checked), so the layout is that of the drawn figure."""

    def __init__(self):
        super().__init__()
        self._armed: tuple | None = None
        self._keys: set[str] = set()
        self.filled = True
        self.wait = 0.0
        """Time waited for the drawing processes [s]."""
        self.children_cpu = 0.0
        """Processor time of the drawing processes, counted when they ended [s]."""

    def arm(self, figures: dict[str, bytes], pending: dict[str, tuple[int, int]],
            drawn: Callable[[], dict[tuple[int, int], bytes]]) -> None:
        """Fill the placeholders ``pending`` (URL -> key) with ``drawn()[key]`` (and
        ``figures[URL]``) when the data of one is first read."""
        if not pending:
            return
        keys = set()
        for url in pending:
            img = dict.get(self, url)
            if img is None or not hasattr(img, "image_data"):
                raise RuntimeError(f"figure {url}: not found in the laid-out document")
            keys.add(img.image_data._key)
        self._armed, self._keys, self.filled = (figures, pending, drawn), keys, False

    def __getitem__(self, key):
        if self._armed is not None and key in self._keys:
            self._fill()
        return super().__getitem__(key)

    def _fill(self) -> None:
        from .plots import image_size

        figures, pending, drawn = self._armed
        self._armed = None
        t, c = time.perf_counter(), children_cpu()
        images = drawn()
        self.wait = time.perf_counter() - t
        self.children_cpu = children_cpu() - c
        for url, key in pending.items():
            data = bytes(images[key])
            img = dict.__getitem__(self, url)
            if (img.width, img.height) != image_size(data):
                raise RuntimeError(f"figure {url}: drawn at another size than its"
                                   " placeholder")
            img.image_data = img.cache_image_data(data)
            figures[url] = data
        self.filled = True


def children_cpu() -> float:
    """Processor time of the finished child processes [s] (0 where unknown)."""
    try:
        import resource

        r = resource.getrusage(resource.RUSAGE_CHILDREN)
        return r.ru_utime + r.ru_stime
    except (ImportError, OSError):
        return 0.0
