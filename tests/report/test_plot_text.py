"""Text from the workbook is data in every figure: names with matplotlib math markup ($...$,
^, _, backslashes) are drawn literally and never crash the rendering."""

from __future__ import annotations

import html
import re

import pytest

from checker import api
from checker.report.sections import SECTIONS, build_sections
from tests.helpers import edited, set_cell

BEARING = "M$1$"
STATION = r"BE_1^2 $\alpha$"
JOINT = r"nose $\foo$"  # unknown math symbol: matplotlib's parser raised on it
ELEMENT = "ring $x_$"  # a math syntax error


def _hostile(wb) -> None:
    set_cell(wb, "Bearings", "name", "M1", "name", BEARING)
    set_cell(wb, "Bearings", "name", "BE1", "name", STATION)
    set_cell(wb, "TVModel", "station", "Cylinder 1", "station", STATION)
    set_cell(wb, "TVModel", "station", "Damper ring", "station", ELEMENT)
    ws = wb["JointTorques"]
    for r in range(3, ws.max_row + 1):
        if ws.cell(r, 1).value == "crank nose":
            ws.cell(r, 1).value = JOINT
    set_cell(wb, "Joints", "name", "crank nose", "name", JOINT)


@pytest.fixture(scope="module")
def sections(tmp_path_factory):
    path = edited(tmp_path_factory.mktemp("markup"), _hostile)
    res = api.check(path, select=["BRG", "TV", "JNT"])  # fatigue names are not workbook text
    build_sections(res)  # registers the sections
    return {m: SECTIONS[m](res) for m in res.outcome.modules_run if m in SECTIONS}


def _svg_texts(sec: dict) -> list[str]:
    """The drawn text of every figure: the strings the renderer drew into a PNG figure, the
    <text> elements (tspans joined; comments ignored) of an SVG figure."""
    out = []
    for b in sec["blocks"]:
        if b["type"] == "figure" and "png" in b:
            out += list(b["png"].texts)
        elif b["type"] == "figure":
            svg = re.sub(r"<!--.*?-->", "", b["svg"], flags=re.S)
            for t in re.findall(r"<text\b[^>]*>(.*?)</text>", svg, flags=re.S):
                out.append(html.unescape(re.sub(r"<[^>]+>|\n\s*", "", t)))
    return out


@pytest.mark.parametrize(("module", "names"), [
    ("loads", [BEARING, STATION]),
    ("bearings", [BEARING, STATION]),
    ("torsion", [STATION, ELEMENT + " -> Crank nose"]),
    ("joints", [JOINT]),
])
def test_names_are_drawn_literally(sections, module, names):
    texts = _svg_texts(sections[module])
    for n in names:
        assert any(n in t for t in texts), (module, n)


@pytest.mark.parametrize("text", [
    "M$1$", r"BE_1^2 $\alpha$", r"$\foo$", "a$^$b", "$x_$", r"a\$b$", "$$", "cost: 5$",
    "100 %", r"C:\path\$x"])
def test_literal_round_trips_through_matplotlib(text):
    from checker.report.plots import figure, literal, to_svg

    fig, ax = figure(60, 30)
    ax.plot([0, 1], [0, 1], label=literal(text))
    ax.set_title(literal(text))
    ax.set_xticks([0.5], [literal(text)])
    ax.legend()
    svg = to_svg(fig)
    texts = _svg_texts({"blocks": [{"type": "figure", "svg": svg}]})
    assert texts.count(text) == 3, texts


@pytest.mark.parametrize("text", ["M$1$", r"BE_1^2 $\alpha$", "$x_$", "cost: 5$"])
def test_literal_text_in_the_report_png(text):
    """The report's raster figures draw the same literal text (the renderer's strings)."""
    from checker.report.plots import figure, literal, to_image

    fig, ax = figure(60, 30)
    ax.plot([0, 1], [0, 1], label=literal(text))
    ax.set_title(literal(text))
    ax.legend()
    png = to_image(fig)
    assert png[:3] == b"\xff\xd8\xff"  # JPEG
    assert png.texts.count(text) == 2, png.texts
