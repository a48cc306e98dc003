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


def test_sheet_names_readable_unique_and_an_index():
    """Every quantity's sheet name fits Excel's 31 characters, is unique, and is shortened
    word by word, never cut mid-word (``tv.nose_cylinder_order_amplitud`` was)."""
    from checker.evaluation import graph

    graph.ensure_registered()
    names = {n: results_book.sheet_name(n) for n in graph.QUANTITIES}
    assert len(set(names.values())) == len(names)
    for q, s in names.items():
        assert len(s) <= results_book.SHEET_CHARS and not set(s) & set("[]:*?/\\"), s
        if len(q) <= results_book.SHEET_CHARS:
            assert s == q
        else:  # every word of the sheet name is a word, or an abbreviation, of the quantity's
            short = dict(results_book.ABBREVIATIONS)
            words = q.replace(".", "_").split("_")
            allowed = set(words) | {short.get(w, w).strip("_.") for w in words} | {"low", "brg"}
            assert set(s.replace(".", "_").split("_")) <= allowed, (q, s)
    assert names["tv.nose_cylinder_order_amplitude"] == "tv.nose_cylinder_order_ampl"


def test_index_sheet_and_cylinder_pressure_data(result):
    """The Index lists sheet, quantity, description and unit; the cylinder-pressure sheet the
    report points to holds the peak, the IMEP, its target and the traces."""
    wb = openpyxl.load_workbook(io.BytesIO(results_book.build(result)), read_only=True)
    assert wb.sheetnames[:2] == ["Index", "Rule results"]
    idx = list(wb["Index"].iter_rows(values_only=True))
    assert idx[4][:4] == ("sheet", "quantity", "description", "unit")
    listed = {r[0]: r[1] for r in idx[5:] if r and r[1]}
    for q in result.outcome.quantities.values():
        if np.size(q.values):
            assert listed[results_book.sheet_name(q.name)] == q.name
    cyc = result.outcome.quantities["loads.cycle"].detail.cycle
    rows = list(wb[results_book.sheet_name("loads.cycle")].iter_rows(values_only=True))
    titles = [r[0] for r in rows if r and isinstance(r[0], str)]
    for t in ("IMEP of the trace used [bar]", "IMEP target (brake torque + friction) [bar];"
              " blank: not calibrated to a target", "trace used"):
        assert t in titles
    k = titles.index("IMEP of the trace used [bar]")
    at = next(i for i, r in enumerate(rows) if r and r[0] == titles[k])
    full = rows[at + 2]
    assert full[0] == "full load"
    np.testing.assert_allclose(np.array(full[1:1 + cyc.speeds.size], float),
                               cyc.imep[0] / 1e5, rtol=1e-9)
    tr = next(i for i, r in enumerate(rows) if r and r[0] == "crank angle [deg]")
    first = rows[tr + 1]
    np.testing.assert_allclose(np.array(first[1:1 + cyc.speeds.size], float),
                               cyc.pressure[0, :, 0] / 1e5, rtol=1e-9)


def test_every_temperature_in_celsius(tmp_path):
    """Issue 43, item 5: the film temperature was in °C (its rule's unit) and the damper
    rubber's temperature at the ends of its range in K; every temperature in °C, as the
    report gives them (reference: pint's kelvin -> degree Celsius)."""
    from checker.workbook.units import Q_

    res = api.check(example_path(tmp_path), select=["BRG-007", "DMP"])
    wb = openpyxl.load_workbook(io.BytesIO(results_book.build(res)), read_only=True)
    temps = [q for q in res.outcome.quantities.values() if q.spec.unit == "K"]
    assert {"bearing.film_temperature", "damper.end_rubber_temperature"} <= {
        q.name for q in temps}
    for q in temps:
        rows = list(wb[results_book.sheet_name(q.name)].iter_rows(values_only=True))
        assert rows[1][0] == "unit: °C", (q.name, rows[1])
        lead = len(q.spec.dims) - 1
        n = int(np.prod(q.values.shape[:-1]))
        got = np.array([r[lead:lead + q.values.shape[-1]] for r in rows[3:3 + n]], float)
        want = Q_(q.values, "kelvin").to("degC").magnitude.reshape(got.shape)
        np.testing.assert_allclose(got, want, rtol=1e-9, equal_nan=True)
