"""Every page of both example reports is clean: no text outside the page or outside its table
cell, no word broken inside a table, no heading left as the last block of a page, no
near-empty page, and every figure says where its data are.

One PDF per example engine (shared by the tests). Cell boxes and line breaks come from the
laid-out document (the PDF is drawn from it); positions on the page are checked in the PDF
itself with pypdf.
"""

from __future__ import annotations

import io
import re

import pytest

from checker import api
from checker.report.render import build_report
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content

EPS = 0.6  # CSS px (0.16 mm): rounding of glyph advances
WORD = re.compile(r"\w", re.UNICODE)


@pytest.fixture(scope="module", params=["i4", "i6"])
def report(request, tmp_path_factory):
    p = tmp_path_factory.mktemp("layout") / f"{request.param}.xlsx"
    write_workbook(p, example_content() if request.param == "i4"
                   else i6_content(damper_ring=True))
    res = api.check(p)
    rep = build_report(res, want_html=False)
    return request.param, rep


def _boxes(box):
    yield box
    for child in getattr(box, "children", ()) or ():
        yield from _boxes(child)


def _page_boxes(rep):
    for n, page in enumerate(rep.document.pages, start=1):
        yield n, page._page_box


def _cls(name: str):
    from weasyprint.formatting_structure import boxes

    return getattr(boxes, name)


def text_outside_the_page(pdf: bytes) -> list[tuple]:
    """(page, text, x, y) of every text drawn outside the page."""
    from pypdf import PdfReader

    bad = []
    for n, page in enumerate(PdfReader(io.BytesIO(pdf)).pages, start=1):
        w, h = float(page.mediabox.width), float(page.mediabox.height)

        def visit(text, cm, tm, font, size, n=n, w=w, h=h):
            if not text.strip():
                return
            x = cm[0] * tm[4] + cm[2] * tm[5] + cm[4]
            y = cm[1] * tm[4] + cm[3] * tm[5] + cm[5]
            if not (-1 <= x <= w + 1 and -1 <= y <= h + 1):
                bad.append((n, text[:40], round(x), round(y)))

        page.extract_text(visitor_text=visit)
    return bad


def test_no_program_internals_on_any_page(report):
    """No page shows a dict or list repr, None, nan or a class name (issue 37)."""
    from tests.helpers import pdf_internals

    name, rep = report
    bad = pdf_internals(rep.pdf)
    assert not bad, f"{name}: program internals on the page: {bad[:5]}"


def test_no_text_outside_the_page(report):
    name, rep = report
    bad = text_outside_the_page(rep.pdf)
    assert not bad, f"{name}: text outside the page: {bad[:5]}"


def cell_overflows(document) -> list[tuple]:
    """(page, text, overflow px) of text that runs beyond its table cell."""
    cell_cls, text_cls = _cls("TableCellBox"), _cls("TextBox")
    bad = []
    for n, page in enumerate(document.pages, start=1):
        for cell in _boxes(page._page_box):
            if not isinstance(cell, cell_cls):
                continue
            x0 = cell.border_box_x()
            x1 = x0 + cell.border_width()
            for t in _boxes(cell):
                if isinstance(t, text_cls) and t.text.strip():
                    if t.position_x < x0 - EPS or t.position_x + t.width > x1 + EPS:
                        bad.append((n, t.text[:30], round(t.position_x + t.width - x1, 1)))
    return bad


def test_no_text_outside_its_table_cell(report):
    name, rep = report
    bad = cell_overflows(rep.document)
    assert not bad, f"{name}: text beyond its cell (page, text, overflow px): {bad[:8]}"


def _text(element) -> str:
    """The text of an HTML element as read (a line break element counts as a space)."""
    parts = []

    def walk(el):
        if el.tag == "br":
            parts.append(" ")
        parts.append(el.text or "")
        for ch in el:
            walk(ch)
            parts.append(ch.tail or "")

    walk(element)
    return " ".join("".join(parts).split())


def _lines(cell, line_cls, text_cls):
    out = []
    for b in _boxes(cell):
        if isinstance(b, line_cls):
            out.append("".join(t.text for t in _boxes(b) if isinstance(t, text_cls)))
    return out


def broken_words(document) -> list[tuple]:
    """(page, "end of line|start of next") where a table cell breaks a word between lines."""
    cell_cls, line_cls, text_cls = _cls("TableCellBox"), _cls("LineBox"), _cls("TextBox")
    bad = []
    for n, page in enumerate(document.pages, start=1):
        for cell in _boxes(page._page_box):
            if not isinstance(cell, cell_cls):
                continue
            lines = [x for x in _lines(cell, line_cls, text_cls) if x.strip()]
            source = _text(cell.element) if getattr(cell, "element", None) is not None else ""
            for a, b in zip(lines, lines[1:]):
                a, b = a.rstrip(), b.lstrip()
                if a and b and WORD.match(a[-1]) and WORD.match(b[0]) and (a + b) in source \
                        and (a + " " + b) not in source:
                    bad.append((n, a[-15:] + "|" + b[:15]))
    return bad


def test_no_word_broken_inside_a_table(report):
    name, rep = report
    bad = broken_words(rep.document)
    assert not bad, f"{name}: words broken across lines in table cells: {bad[:8]}"


def premature_breaks(document) -> list[tuple]:
    """(page, "line|next") where a rule's name in a table breaks a line early: the next
    line's first word would have fitted on it (issue 37: "Contact / stress under the bolt
    head" wrapped after one word). Cells that name a rule (a ``rule-id`` span), widths from
    the laid-out boxes (a word's width estimated by its share of its line's characters)."""
    cell_cls, line_cls, text_cls = _cls("TableCellBox"), _cls("LineBox"), _cls("TextBox")
    bad = []
    for n, page in enumerate(document.pages, start=1):
        for cell in _boxes(page._page_box):
            el = getattr(cell, "element", None)
            if not isinstance(cell, cell_cls) or el is None or el.find(
                    ".//span[@class='rule-id']") is None:
                continue
            lines = []
            for b in _boxes(cell):
                if isinstance(b, line_cls):
                    ts = [t for t in _boxes(b) if isinstance(t, text_cls)]
                    text = "".join(t.text for t in ts)
                    if text.strip():
                        lines.append((text, sum(t.width for t in ts)))
            room = cell.width
            end = el.find(".//span[@class='name-end']")  # kept on one line on purpose
            tail = _text(end) if end is not None else ""
            for (a, wa), (b, wb) in zip(lines, lines[1:]):
                word = tail if tail and b.strip().startswith(tail) else b.split()[0]
                w_word = wb * (len(word) + 1) / max(len(b), 1)
                if wa + w_word < room - 2 * EPS:
                    bad.append((n, f"{a.strip()}|{b.strip()[:20]}"))
    return bad


def test_no_rule_name_breaks_early_in_a_table(report):
    name, rep = report
    bad = premature_breaks(rep.document)
    assert not bad, f"{name}: a line of a rule's name broken early: {bad[:8]}"


def _lines_with_owner(box, owner=None):
    """(line box, tag of the element that holds it) of the page body, in document order."""
    line_cls, margin_cls = _cls("LineBox"), _cls("MarginBox")
    if isinstance(box, margin_cls):
        return
    tag = getattr(box, "element_tag", None)
    if isinstance(box, line_cls):
        yield box, owner
        return
    for child in getattr(box, "children", ()) or ():
        yield from _lines_with_owner(child, tag if tag in ("h2", "h3") else owner
                                     if tag is None or tag in ("span", "b", "i", "a") else tag)


def stranded_headings(document) -> list[tuple]:
    """(page, heading) of headings that are the lowest text of a page (last page excepted)."""
    bad = []
    pages = document.pages
    for n, page in enumerate(pages, start=1):
        if n == len(pages):
            continue
        root = page._page_box
        lines = [(b.position_y + b.height, tag, b) for b, tag in _lines_with_owner(root)]
        figures = [(b.position_y + b.height, "figure", b) for b in _boxes(root)
                   if getattr(b, "element_tag", None) == "img"]
        if not lines:
            continue
        bottom, tag, box = max(lines + figures, key=lambda x: x[0])
        if tag in ("h2", "h3"):
            bad.append((n, "".join(t.text for t in _boxes(box) if hasattr(t, "text"))[:40]))
    return bad


def test_no_heading_at_the_bottom_of_a_page(report):
    name, rep = report
    bad = stranded_headings(rep.document)
    assert not bad, f"{name}: heading left at the bottom of a page: {bad}"


def _flow(box, in_h2=None):
    """("h2", text) for a section heading, ("content", "") for any other line or image of
    the page body, in document order (margin boxes left out)."""
    if isinstance(box, _cls("MarginBox")):
        return
    el = getattr(box, "element", None)
    tag = getattr(box, "element_tag", None)
    if tag == "h2" and in_h2 is None and "toc-title" not in (el.get("class") or ""):
        yield "h2", " ".join(_text(el).split())
        return
    if isinstance(box, _cls("LineBox")) or tag == "img":
        yield "content", ""
        return
    for child in getattr(box, "children", ()) or ():
        yield from _flow(child, in_h2)


def header_mismatches(document, first: str = "Verdict") -> list[tuple]:
    """(page, running header, section the page starts in) where they differ: the header
    must name the section whose text the page starts with (the heading at the top of the
    page, else the section running on from the pages before), as printed reference works
    do; not a section that starts lower down the page (issue 37)."""
    bad = []
    running = first
    for n, page in enumerate(document.pages, start=1):
        items = list(_flow(page._page_box))
        header = ""
        for m in _boxes(page._page_box):
            if isinstance(m, _cls("MarginBox")) and m.at_keyword == "@top-right":
                header = " ".join("".join(t.text for t in _boxes(m)
                                          if isinstance(t, _cls("TextBox"))).split())
        starts = items[0][1] if items and items[0][0] == "h2" else running
        if n > 1 and header != starts:
            bad.append((n, header, starts))
        for kind, text in items:
            if kind == "h2":
                running = text
    return bad


def test_the_running_header_names_the_section_the_page_starts_in(report):
    name, rep = report
    bad = header_mismatches(rep.document)
    assert not bad, f"{name}: running header (page, header, section at its top): {bad}"


def test_the_checks_find_bad_layouts():
    # the helpers above are not vacuous: a page built with each defect is caught
    from weasyprint import HTML

    html = """<html><head><style>
      @page { size: A6; margin: 10mm }
      table { table-layout: fixed; width: 30mm; border-collapse: collapse }
      td { width: 10mm; overflow-wrap: anywhere }
      td.nowrap { white-space: nowrap; overflow-wrap: normal }
      .filler { height: 95mm }
    </style></head><body>
      <table><tr><td>Severity warning</td><td class="nowrap">NOT EVALUATED AT ALL</td></tr></table>
      <div class="filler"></div>
      <h3>Stranded heading</h3>
      <div style="height: 120mm">next page</div>
    </body></html>"""
    doc = HTML(string=html).render()
    assert broken_words(doc), "a word broken inside a narrow cell is found"
    assert cell_overflows(doc), "text running past its cell is found"
    assert [t for _, t in stranded_headings(doc)] == ["Stranded heading"]


def test_no_near_empty_page(report):
    name, rep = report
    pages = rep.document.pages
    for n, root in _page_boxes(rep):
        if n == len(pages):
            continue
        body = [b for b in _boxes(root) if getattr(b, "element_tag", None) == "body"]
        content = [b for b in _boxes(body[0]) if getattr(b, "element_tag", None) in (
            "p", "li", "tr", "figure", "h2", "h3")] if body else []
        bottom = max((b.position_y + b.margin_height() for b in content), default=0)
        top = root.children[0].content_box_y() if root.children else 0
        usable = root.height - top
        used = (bottom - top) / usable if usable else 1
        assert used > 0.3, f"{name}: page {n} is {used:.0%} full"


def test_every_figure_names_its_data(report):
    name, rep = report
    html = rep.document.pages  # noqa: F841 - the figures are in the laid-out document
    fig_cls = _cls("BlockBox")
    missing = []
    for n, root in _page_boxes(rep):
        for b in _boxes(root):
            if isinstance(b, fig_cls) and getattr(b, "element_tag", None) == "figcaption":
                text = " ".join("".join(b.element.itertext()).split())
                if "results.xlsx" not in text:
                    missing.append((n, text[:60]))
    assert not missing, f"{name}: figures without a data reference: {missing}"
