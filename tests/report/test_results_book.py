"""The results workbook: every computed quantity with items, load cases, speeds and units,
equal to the quantities; attached to the PDF and written on request; byte-identical reruns."""

from __future__ import annotations

import io

import numpy as np
import openpyxl
import pytest
from click.testing import CliRunner

from checker import api
from checker.cli import main
from checker.report import results_book
from tests.helpers import example_path


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("book"))


@pytest.fixture(scope="module")
def result(example):
    return api.check(example, select=["BRG", "TV"])


def test_every_quantity_has_a_sheet_with_its_values(result):
    data = results_book.build(result)
    assert data == results_book.build(result)  # deterministic
    wb = openpyxl.load_workbook(io.BytesIO(data), read_only=True)
    names = set(wb.sheetnames)
    for q in result.outcome.quantities.values():
        if np.size(q.values):
            assert results_book.sheet_name(q.name) in names, q.name
    # MOFT in µm, one row per bearing and load case, one column per speed (rpm)
    q = result.outcome.quantities["bearing.moft_finite"]
    rows = list(wb["bearing.moft_finite"].iter_rows(values_only=True))
    assert rows[1][0] == "unit: µm"
    header = rows[2]
    assert header[:2] == ("item", "case") and header[2] == "1000 rpm"
    be1 = next(r for r in rows[3:] if r[0] == "BE1" and r[1] == "full load")
    i, ci = q.coords["item"].index("BE1"), q.coords["case"].index("full")
    np.testing.assert_allclose(np.array(be1[2:2 + q.values.shape[-1]], float),
                               q.values[i, ci] * 1e6, rtol=1e-9)
    res_rows = list(wb["Rule results"].iter_rows(values_only=True))
    assert len(res_rows) - 1 == len(result.results)


def test_pdf_carries_the_workbook_and_results_option_writes_it(example, tmp_path):
    from pypdf import PdfReader

    pdf, book = tmp_path / "r.pdf", tmp_path / "results.xlsx"
    r = CliRunner().invoke(main, ["report", str(example), "-o", str(pdf), "--results", str(book),
                                  "--select", "JNT", "--quiet"])
    assert r.exit_code == 1, r.output
    assert f"wrote {pdf}, {book}" in r.stderr  # the final line names every file written
    attached = PdfReader(pdf).attachments
    assert list(attached) == [results_book.ATTACHMENT_NAME]
    assert attached[results_book.ATTACHMENT_NAME][0] == book.read_bytes()
    wb = openpyxl.load_workbook(book, read_only=True)
    assert "joint.cover_factor" in wb.sheetnames
