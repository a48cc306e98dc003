"""The study PDFs and the compare pack pass the same layout checks as the engine reports: no
text outside the page or its table cell, no word broken inside a table, no heading left at
the bottom of a page; and they say what a reviewer asks first (the answer, ties, the net
trade).

Studies: the two example study designs on cheap rules (peak specific load and bolt preload:
no orbits, no torsional model): a two-parameter full-factorial on the I4 and a
five-parameter Latin hypercube on the I6 (the wide feasibility table that overlapped
itself). The pack: the I4 against a copy with a cooler oil supply.
"""

from __future__ import annotations

import openpyxl
import pytest

from checker.plumbing.resources import templates_dir
from checker.study.results import tidy
from checker.study.run import run_study
from checker.study.spec import load_study
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content
from tests.report.test_layout import (
    broken_words,
    cell_overflows,
    stranded_headings,
    text_outside_the_page,
)

RULES = '["BRG-001", "BRG-002", "JNT-001", "JNT-002"]'

I4_STUDY = f"""
[study]
name = "I4 main-bearing clearance and oil supply temperature"
design = "full-factorial"
select = {RULES}

[[parameter]]
name = "main clearance"
sheet = "Bearings"
where = {{ type = "main" }}
column = "radial clearance"
unit = "um"
range = [16, 40]
steps = 3

[[parameter]]
name = "oil supply temperature"
sheet = "Oil"
row = "Oil supply temperature"
unit = "°C"
values = [90, 130]
"""

I6_STUDY = f"""
[study]
name = "I6 geometry and mass, Latin hypercube"
design = "latin-hypercube"
samples = 10
seed = 2026
select = {RULES}

[[parameter]]
sheet = "Engine"
row = "Bore"
unit = "mm"
range = [100, 110]

[[parameter]]
sheet = "Engine"
row = "Stroke"
unit = "mm"
range = [130, 145]

[[parameter]]
sheet = "Engine"
row = "Connecting rod length"
unit = "mm"
range = [200, 215]

[[parameter]]
sheet = "Engine"
row = "Piston assembly mass"
unit = "kg"
range = [1.5, 1.9]

[[parameter]]
name = "main bearing width"
sheet = "Bearings"
where = {{ type = "main" }}
column = "length"
unit = "mm"
range = [26, 34]
"""


def _layout(html: str):
    from weasyprint import HTML

    return HTML(string=html, base_url=str(templates_dir())).render()


def _study(kind: str, d):
    from checker.report.study import html

    wb = d / "engine.xlsx"
    eng, text = ("i4", I4_STUDY) if kind == "i4-factorial" else ("i6", I6_STUDY)
    write_workbook(wb, example_content() if eng == "i4" else i6_content(damper_ring=True))
    st = d / "study.toml"
    st.write_text(text, encoding="utf-8")
    run = run_study(load_study(st), wb, d / "out", workers=1)
    page = html(run, tidy(run))
    return kind, page, _layout(page)


def _pack(d):
    from checker.outputs.compare import compare
    from checker.report.compare import pack_html

    base = d / "engine.xlsx"
    write_workbook(base, example_content())
    book = openpyxl.load_workbook(base)
    for row in book["Oil"].iter_rows():
        if row[0].value == "Oil supply temperature":
            row[1].value = 100
    var = d / "engine-cool-oil.xlsx"
    book.save(var)
    comps = compare(base, [var], select=["BRG-001", "BRG-003", "BRG-004", "JNT-001"])
    page = pack_html(comps)
    return "pack", page, _layout(page)


@pytest.fixture(scope="module", params=["i4-factorial", "i6-lhs", "pack"])
def document(request, tmp_path_factory):
    d = tmp_path_factory.mktemp(request.param)
    return _pack(d) if request.param == "pack" else _study(request.param, d)


def test_no_text_outside_its_table_cell(document):
    name, _, doc = document
    bad = cell_overflows(doc)
    assert not bad, f"{name}: text beyond its cell (page, text, overflow px): {bad[:8]}"


def test_no_word_broken_inside_a_table(document):
    name, _, doc = document
    bad = broken_words(doc)
    assert not bad, f"{name}: words broken across lines in table cells: {bad[:8]}"


def test_no_heading_at_the_bottom_of_a_page(document):
    name, _, doc = document
    bad = stranded_headings(doc)
    assert not bad, f"{name}: heading left at the bottom of a page: {bad}"


_PDFS: dict[str, bytes] = {}


def _pdf(document) -> bytes:
    """The document's PDF, written once per document for the tests that read it."""
    name, _, doc = document
    if name not in _PDFS:
        _PDFS[name] = doc.write_pdf()
    return _PDFS[name]


def test_notext_outside_the_page(document):
    name, _, _ = document
    bad = text_outside_the_page(_pdf(document))
    assert not bad, f"{name}: text outside the page: {bad[:5]}"


def test_no_program_internals_on_any_page(document):
    """No page of a study PDF or compare pack shows a dict or list repr, None, nan or a class
    name (issue 37)."""
    from tests.helpers import pdf_internals

    name, _, _ = document
    bad = pdf_internals(_pdf(document))
    assert not bad, f"{name}: program internals on the page: {bad[:5]}"


def test_the_study_answers_in_words(document):
    name, page, _ = document
    if name == "pack":
        pytest.skip("a study check")
    assert "The answer" in page and "governs" in page, name
    # variant numbers are 1-based, as the variants' names ("sample 1" is variant 1)
    assert '<td>0</td>' not in page, name
    if name == "i4-factorial":
        # the clearance changes only the mains: the answer speaks of their items
        assert "The items main clearance changes (M1, M2, M3, M4, M5) pass" in page


def test_the_pack_states_the_net_trade(document):
    name, page, _ = document
    if name != "pack":
        pytest.skip("a pack check")
    for words in ("Newly passing (", "Newly failing (", "Worse (", "Better ("):
        assert words in page
    assert "N/mm" not in page
    assert "points" in page  # margin changes in points, not as a percentage of a percentage
