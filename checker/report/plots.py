"""Matplotlib helpers: vector SVG with real text, deterministic bytes.

Text from the workbook (bearing, station, element, joint and lining names) is data: matplotlib
reads ``$...$`` in any label as math markup (and raises on markup it cannot parse). Every such
text goes through :func:`literal` before it reaches a label, title, legend entry, tick label
or annotation. Math parsing itself stays on: matplotlib's own log-axis tick labels use it.
"""

from __future__ import annotations

import io
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({
    "svg.fonttype": "none",  # text stays text in the PDF (searchable, report fonts)
    "svg.hashsalt": "checker",  # deterministic ids
    "font.family": "DejaVu Sans",
    "font.size": 8,
    "axes.grid": True,
    "axes.grid.axis": "y",  # y grid only: each grid line is an SVG path WeasyPrint lays out
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "lines.linewidth": 1.2,
    "figure.dpi": 100,
    "text.usetex": False,
})

LIMIT_STYLE = {"color": "#c0392b", "linestyle": "--", "linewidth": 1.2}


def figure(width_mm: float = 170, height_mm: float = 80, **kw):
    """A new figure sized in millimetres (fits an A4 text column at 170 mm)."""
    return plt.subplots(figsize=(width_mm / 25.4, height_mm / 25.4), **kw)


def literal(text: object) -> str:
    """``text`` (workbook data) as matplotlib draws it literally: every ``$`` escaped as
    ``\\$``, so no pair of dollar signs opens math markup. Matplotlib turns ``\\$`` back
    into ``$`` in text without math (``matplotlib.text.Text._preprocess_math``), so the drawn
    text equals ``text`` character for character, backslashes, ``^`` and ``_`` included."""
    return str(text).replace("$", "\\$")


def to_svg(fig) -> str:
    """Serialize and close a figure; returns inline SVG markup without the XML prolog."""
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None})
    plt.close(fig)
    svg = buf.getvalue()
    svg = svg[svg.find("<svg"):]
    # make the SVG scale to the column width
    svg = re.sub(r'width="[\d.]+pt" height="[\d.]+pt"', 'width="100%"', svg, count=1)
    return svg
