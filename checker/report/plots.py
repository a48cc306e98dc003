"""Matplotlib helpers: vector SVG with real text, deterministic bytes, fixed layout.

Matplotlib is imported on the first figure only (``checker check`` never pays for it); the
report imports it once before it forks its drawing processes, which then share it.

Layout rules for every figure (the report's pages are reviewed as images): margins are fixed
in millimetres (no ``bbox_inches="tight"`` or constrained layout, which draw the figure once
more: about 60 % of a figure's cost); a legend sits below the axes, never over the data
(:func:`legend_below`); limit lines are named in the legend, not by text over the curves
(:func:`limit_line`); every axis has a label.

Text from the workbook (bearing, station, element, joint and lining names) is data: matplotlib
reads ``$...$`` in any label as math markup (and raises on markup it cannot parse). Every such
text goes through :func:`literal` before it reaches a label, title, legend entry, tick label
or annotation. Math parsing itself stays on: matplotlib's own log-axis tick labels use it.
"""

from __future__ import annotations

import io
import re
from collections.abc import Callable

from ..plumbing import matplotlib_patches

LIMIT_STYLE = {"color": "#c0392b", "linestyle": "--", "linewidth": 1.1}
STATUS_COLORS = {"PASS": "#1e8449", "FAIL": "#c0392b", "WARN": "#d68910",
                 "NOT EVALUATED": "#95a5a6", "NOT JUDGED": "#bdc3c7"}
"""Colours of results by status (bars, markers), as in the report's tables."""
MM = 1 / 25.4

_RC = {
    "svg.fonttype": "none",  # text stays text in the PDF (searchable, report fonts)
    "svg.hashsalt": "checker",  # deterministic ids
    "font.family": "DejaVu Sans",
    "font.size": 7.5,
    "axes.titlesize": 7.5,
    # a fixed title height: matplotlib otherwise measures every tick label of the axes to
    # lift the title over top-side tick labels (none but a polar plot's 0°: :func:`to_image`
    # gives polar axes the automatic height back): about 15 % of the drawing time
    "axes.titley": 1.0,
    "axes.labelsize": 7.5,
    "xtick.labelsize": 6.5,
    "ytick.labelsize": 6.5,
    "legend.fontsize": 6.5,
    "axes.grid": True,
    "axes.grid.axis": "y",  # y grid only: each grid line is an SVG path WeasyPrint lays out
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "lines.linewidth": 1.1,
    "figure.dpi": 100,
    "text.usetex": False,
    "path.simplify_threshold": 0.3,
    # the report's sections may hold their built figures until they are drawn (DEFERRED)
    "figure.max_open_warning": 0,
}
_PLT = None


def pyplot():
    """``matplotlib.pyplot``, imported and configured on first use."""
    global _PLT
    if _PLT is None:
        import matplotlib

        matplotlib.use("Agg")
        with matplotlib_patches.property_lists_unwritten():
            import matplotlib.pyplot as mpl_pyplot

        mpl_pyplot.rcParams.update(_RC)
        _PLT = mpl_pyplot
    return _PLT


class _LazyPyplot:
    """``plots.plt``: pyplot, imported on first attribute access."""

    def __getattr__(self, name: str):
        return getattr(pyplot(), name)


plt = _LazyPyplot()


def figure(width_mm: float = 170, height_mm: float = 80, *, left: float = 17,
           right: float = 4, top: float = 7, bottom: float = 11, wgap: float = 18,
           hgap: float = 13, legend_rows: int = 0, **kw):
    """A new figure sized in millimetres (fits an A4 text column at 170 mm) with fixed
    margins in mm: ``left`` (tick labels and y label), ``bottom`` (x label; plus 3.6 mm per
    ``legend_rows`` of a legend below the axes), ``wgap``/``hgap`` between panels.
    Other keywords go to ``plt.subplots`` (nrows, ncols, sharex, subplot_kw...)."""
    fig, axes = pyplot().subplots(figsize=(width_mm * MM, height_mm * MM), **kw)
    nrows, ncols = kw.get("nrows", 1), kw.get("ncols", 1)
    fig._checker_margins = (width_mm, height_mm, bottom, legend_rows)
    bottom = bottom + LEGEND_ROW_MM * legend_rows
    aw = (width_mm - left - right - (ncols - 1) * wgap) / ncols
    ah = (height_mm - top - bottom - (nrows - 1) * hgap) / nrows
    fig.subplots_adjust(left=left / width_mm, right=1 - right / width_mm,
                        top=1 - top / height_mm, bottom=bottom / height_mm,
                        wspace=wgap / aw if ncols > 1 else 0.2,
                        hspace=hgap / ah if nrows > 1 else 0.2)
    return fig, axes


LEGEND_ROW_MM = 3.6
"""Height of one legend row below the axes [mm] (legend font 6.5 pt)."""


def literal(text: object) -> str:
    """``text`` (workbook data) as matplotlib draws it literally: every ``$`` escaped as
    ``\\$``, so no pair of dollar signs opens math markup. Matplotlib turns ``\\$`` back
    into ``$`` in text without math (``matplotlib.text.Text._preprocess_math``), so the drawn
    text equals ``text`` character for character, backslashes, ``^`` and ``_`` included."""
    return str(text).replace("$", "\\$")


def limit_line(ax, value: float, label: str | None, vertical: bool = False, **style):
    """A limit drawn as a dashed red line and named in the legend (no text over the data)."""
    st = {**LIMIT_STYLE, **style}
    f = ax.axvline if vertical else ax.axhline
    return f(value, label=None if label is None else literal(label), **st)


def legend_below(fig, axes=None, ncols: int = 6, handles=None, labels=None) -> None:
    """One legend for the figure, centred below the axes; entries of all ``axes`` (default:
    every axes), duplicates once. The number of columns is reduced until the entries fit
    the figure's width, and the bottom margin grows to the legend's rows (the axes shrink:
    the legend never covers an axis label)."""
    if handles is None:
        handles, labels = [], []
        for ax in (fig.axes if axes is None else axes):
            for h, lab in zip(*ax.get_legend_handles_labels()):
                if lab not in labels and not lab.startswith("_"):
                    handles.append(h)
                    labels.append(lab)
    if not handles:
        return
    width_mm, height_mm, bottom, reserved = getattr(
        fig, "_checker_margins", (fig.get_figwidth() / MM, fig.get_figheight() / MM, 11, 0))
    # entry width: handle + gap + text (6.5 pt DejaVu Sans: about 1.25 mm per character)
    entry = 9.0 + 1.25 * max(len(str(x)) for x in labels)
    n = max(1, min(ncols, len(handles), int((width_mm - 6) // entry)))
    rows = -(-len(handles) // n)
    if rows != reserved:
        fig.subplots_adjust(bottom=(bottom + LEGEND_ROW_MM * rows) / height_mm)
    fig.legend(handles, labels, loc="lower center", bbox_to_anchor=(0.5, 0.0),
               ncols=n, frameon=False, handlelength=1.8, columnspacing=1.2,
               borderaxespad=0.2)


def every(n_points: int, step: int = 4) -> slice:
    """Slice that thins a crank-angle curve for plotting (a 1° grid drawn every ``step``°
    looks the same at report size and costs a quarter of the PDF drawing)."""
    return slice(None, None, step if n_points > 200 else 1)


PNG_DPI = 150
"""Resolution of the report's figures [dots per inch]: at the 170 mm column width 1000 px,
sharp in print and on screen. Raster figures, because the PDF engine draws vector (SVG)
figures in pure Python (about 2.5 s of a 13-figure report) while a PNG is copied."""



JPEG_QUALITY = 92
"""JPEG quality of the report's figures: lines and text stay sharp at 150 dpi."""


class Png(bytes):
    """Image bytes of a figure (JPEG); ``texts``: every string drawn into it, after matplotlib's own
    processing (what the reader sees), for tests of the figures' text."""

    texts: list[str]
    width_mm: float


DEFERRED: list | None = None
"""While the report's sections are built for drawing in other processes
(:class:`checker.report.sections.SectionJob` with ``defer``): the figures deferred so far,
each a call ``(function, args)`` that builds and draws it (:func:`later`) or a built figure
(:func:`to_image`), in order; None (the default): figures are drawn at once."""

DRAWER = 0
"""The first part of a :class:`Deferred` key (the process that deferred the figure)."""

_PLACEHOLDERS: dict[tuple[int, int], bytes] = {}


class Deferred(Png):
    """A figure not drawn yet (:data:`DEFERRED`): a white JPEG of the figure's exact pixel
    size, so that the PDF can be laid out before the figure is drawn; ``key``: (:data:`DRAWER`,
    place in :data:`DEFERRED`), ``size``: (width, height) [px]."""

    key: tuple[int, int]
    size: tuple[int, int]


def pixel_size(fig) -> tuple[int, int]:
    """Width and height [px] of the image :func:`to_image` draws of ``fig`` at the figure's
    dpi (Agg's canvas: the figure's size in pixels, truncated)."""
    w, h = fig.bbox.size
    return int(w), int(h)


def planned_size(width_mm: float, height_mm: float, dpi: float = PNG_DPI) -> tuple[int, int]:
    """:func:`pixel_size` of a figure :func:`figure` makes ``width_mm`` x ``height_mm`` (the
    same arithmetic as matplotlib's: inches times dpi, truncated), without matplotlib."""
    return int(width_mm * MM * dpi), int(height_mm * MM * dpi)


def image_size(data: bytes) -> tuple[int, int]:
    """Width and height [px] of an image (JPEG or PNG bytes)."""
    from PIL import Image

    with Image.open(io.BytesIO(data)) as img:
        return img.size


def _prepare(fig, dpi: float) -> None:
    for ax in fig.axes:
        if ax.name == "polar" and hasattr(ax, "_autotitlepos"):
            ax._autotitlepos = True  # the title lifted over the 0° label (see _RC titley)
    fig.set_dpi(dpi)
    fig.patch.set_facecolor("white")


def _placeholder(size: tuple[int, int], width_mm: float) -> Deferred:
    """A :class:`Deferred` of ``size`` [px] for the next place in :data:`DEFERRED`."""
    from PIL import Image

    if size not in _PLACEHOLDERS:
        buf = io.BytesIO()
        Image.new("RGB", size, "white").save(buf, format="JPEG", quality=JPEG_QUALITY,
                                             subsampling=0, optimize=False)
        _PLACEHOLDERS[size] = buf.getvalue()
    png = Deferred(_PLACEHOLDERS[size])
    png.texts = []
    png.width_mm = width_mm
    png.key = (DRAWER, len(DEFERRED))
    png.size = size
    return png


def to_image(fig, dpi: float = PNG_DPI) -> Png:
    """Draw and close a figure; returns its image (RGB JPEG; deterministic: no metadata).
    Raster, because the PDF engine draws vector (SVG) figures in pure Python. While figures
    are deferred (:data:`DEFERRED`), a :class:`Deferred` placeholder of the same size instead;
    :func:`draw_deferred` draws it later."""
    _prepare(fig, dpi)
    if DEFERRED is None:
        return _draw(fig)
    png = _placeholder(pixel_size(fig), fig.get_figwidth() * 25.4)
    DEFERRED.append(fig)
    return png


def later(size_mm: tuple[float, float], draw: Callable[..., Png], *args) -> Png:
    """The image ``draw(*args)`` returns (a function that makes a figure of ``size_mm``
    (width, height) with :func:`figure` and returns :func:`to_image` of it). While figures are
    deferred (:data:`DEFERRED`) the call is kept and a :class:`Deferred` placeholder of the
    figure's size returned: matplotlib is then not needed to build a report's sections, and
    the figure is built where it is drawn (:func:`draw_deferred`). ``args`` are used when it
    is drawn: values that do not change after this call."""
    if DEFERRED is None:
        return draw(*args)
    png = _placeholder(planned_size(*size_mm), size_mm[0] * MM * 25.4)  # as figwidth * 25.4
    DEFERRED.append((draw, args))
    return png


def draw_deferred(index: int) -> Png:
    """The image of the figure ``DEFERRED[index]`` (built if it was deferred as a call, drawn
    and closed now; the entry freed)."""
    global DEFERRED
    item = DEFERRED[index]
    DEFERRED[index] = None
    if not isinstance(item, tuple):
        return _draw(item)
    draw, args = item
    kept, DEFERRED = DEFERRED, None  # the call's own to_image draws at once
    try:
        return draw(*args)
    finally:
        DEFERRED = kept


def _draw(fig) -> Png:
    """Draw and close a prepared figure (:func:`_prepare`)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    drawn: list[str] = []
    canvas = FigureCanvasAgg(fig)
    with matplotlib_patches.agg_text_recorded(drawn):
        canvas.draw()
    rgba = canvas.buffer_rgba()
    img = Image.frombuffer("RGBA", (rgba.shape[1], rgba.shape[0]), rgba, "raw", "RGBA", 0,
                           1).convert("RGB")
    pyplot().close(fig)
    buf = io.BytesIO()
    # JPEG at high quality without chroma subsampling: the PDF engine embeds its bytes as
    # they are (a PNG it decodes and compresses again: about 35 ms a figure)
    img.save(buf, format="JPEG", quality=JPEG_QUALITY, subsampling=0, optimize=False)
    png = Png(buf.getvalue())
    png.texts = drawn
    png.width_mm = fig.get_figwidth() * 25.4
    return png


def to_svg(fig) -> str:
    """Serialize and close a figure; returns inline SVG markup without the XML prolog."""
    buf = io.StringIO()
    fig.savefig(buf, format="svg", metadata={"Date": None})
    pyplot().close(fig)
    svg = lean_svg(buf.getvalue())
    # make the SVG scale to the column width
    svg = re.sub(r'width="[\d.]+pt" height="[\d.]+pt"', 'width="100%"', svg, count=1)
    return svg


_SVG_NS = "http://www.w3.org/2000/svg"
_XLINK = "http://www.w3.org/1999/xlink"


def lean_svg(svg: str) -> str:
    """The same drawing in an SVG that WeasyPrint draws faster (about half the time of the
    report's PDF output goes into its SVG interpreter, which is pure Python): ``style``
    attributes become presentation attributes (no CSS parsing per element), the global
    ``<style>`` becomes root attributes, ``<metadata>`` goes, and groups that only carry an
    unreferenced id are dissolved into their parent."""
    import xml.etree.ElementTree as ET

    ET.register_namespace("", _SVG_NS)
    ET.register_namespace("xlink", _XLINK)
    root = ET.fromstring(svg)
    q = f"{{{_SVG_NS}}}"
    href = f"{{{_XLINK}}}href"
    referenced: set[str] = set()
    for el in root.iter():
        h = el.get(href)
        if h and h.startswith("#"):
            referenced.add(h[1:])
        for v in el.attrib.values():
            for m in re.finditer(r"url\(#([^)]+)\)", v):
                referenced.add(m.group(1))
    for el in list(root):
        if el.tag == q + "metadata":
            root.remove(el)
    for defs in root.iter(q + "defs"):
        for st in list(defs):
            if st.tag == q + "style":
                for k, v in _declarations(re.sub(r"^[^{]*\{|\}.*$", "", (st.text or "").strip(),
                                                 flags=re.S)):
                    root.set(k, v)
                defs.remove(st)
    for el in root.iter():
        st = el.attrib.pop("style", None)
        if st:
            for k, v in _declarations(st):
                el.set(k, v)

    def flatten(parent) -> None:
        out = []
        for ch in list(parent):
            flatten(ch)
            if ch.tag == q + "g" and set(ch.attrib) <= {"id"} and \
                    ch.get("id") not in referenced:
                out.extend(list(ch))
            else:
                out.append(ch)
        if len(out) != len(parent) or any(a is not b for a, b in zip(out, parent)):
            parent[:] = out

    flatten(root)
    for el in root.iter():
        i = el.get("id")
        if i is not None and i not in referenced:
            del el.attrib["id"]
    return ET.tostring(root, encoding="unicode")


def _declarations(text: str) -> list[tuple[str, str]]:
    out = []
    for part in text.split(";"):
        if ":" in part:
            k, v = part.split(":", 1)
            out.append((k.strip(), v.strip()))
    return out
