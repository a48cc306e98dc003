"""``checker compare`` (issue 21, item 1 and the compare friction): a not-evaluated result whose
computed value moved is listed as such, never as a margin change without margins (the PDF used
to crash on it); messages name inputs as the user typed them, with the file name; two different
engines are called so."""

from __future__ import annotations

import json

import pypdf
import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.outputs.compare import compare, input_changes
from checker.report.compare import render
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content
from checker.workbook.loader import read_raw_workbook
from tests import variants
from tests.helpers import edited, example_path, param_row


@pytest.fixture(scope="module")
def clearance_pair(tmp_path_factory):
    d = tmp_path_factory.mktemp("cmp")
    base = example_path(d)
    return base, variants.clearance(base, d / "v.xlsx")


def test_clearance_variant_renders_with_not_evaluated_value_changes(clearance_pair, tmp_path):
    base, var = clearance_pair
    (c,) = compare(base, [var])
    assert c.inputs == [{"sheet": "Bearings", "cell": "Bearings!F5",
                         "what": "M3: radial clearance", "baseline": "0.022 mm",
                         "variant": "0.03 mm"}]
    margin = [r for r in c.results if r["change"] == "margin changed"]
    moved = [r for r in c.results if r["change"] == "value changed (not evaluated)"]
    assert margin and all(r["margin_change"] is not None for r in margin)
    assert {r["rule"] for r in margin} >= {"BRG-003", "BRG-004"}
    # the oil-film temperature rule has no limit in the example: its value moved
    assert any(r["rule"] == "BRG-007" and r["item"] == "M3" for r in moved)
    for r in moved:
        assert r["baseline"]["status"] == r["variant"]["status"] == "not_evaluated"
        assert r["margin_change"] is None
    html, pdf = render([c])
    assert "Not evaluated, computed value moved" in html
    path = tmp_path / "pack.pdf"
    path.write_bytes(pdf)
    text = "".join(p.extract_text() for p in pypdf.PdfReader(path).pages)
    assert "M3: radial clearance" in text and "NOT EVALUATED" in text


def test_cli_writes_the_pdf_and_counts_changes_in_words(clearance_pair, tmp_path):
    base, var = clearance_pair
    out = tmp_path / "c.pdf"
    r = CliRunner().invoke(main, ["compare", str(base), str(var), "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert out.stat().st_size > 10_000
    assert "v.xlsx: " in r.stderr and "(1 input change;" in r.stderr


def test_input_names_as_typed_and_no_unit_dash(tmp_path):
    base = example_path(tmp_path)

    def edit(wb):
        ws = wb["Engine"]
        ws.cell(param_row(ws, "Compression ratio"), 2).value = 11
        ws = wb["RuleOverrides"]
        ws.cell(3, 1).value, ws.cell(3, 2).value = "TV-001", 0.2
        ws.cell(3, 3).value, ws.cell(3, 4).value = "deg", "a reason"
    var = edited(tmp_path, edit, "v.xlsx")
    ch = input_changes(read_raw_workbook(base), read_raw_workbook(var))
    cr = next(c for c in ch if c["what"] == "Compression ratio")
    assert (cr["baseline"], cr["variant"]) == ("10.5", "11")  # no trailing "-"
    assert any(c["what"] == "row 'TV-001'" for c in ch), ch  # as typed, not 'tv-001'


def test_different_engines_are_called_so(tmp_path):
    base = example_path(tmp_path)
    other = tmp_path / "i6.xlsx"
    write_workbook(other, i6_content(damper_ring=True))
    r = CliRunner().invoke(main, ["compare", str(base), str(other), "--format", "json",
                                  "--select", "BAL"])
    d = json.loads(r.stdout)["comparisons"][0]
    assert d["different_engines"] is True
    n, m = len(d["input_changes"]), d["inputs_compared"]
    assert f"these look like different engines ({n} of {m} inputs differ)" in r.stderr


def test_input_error_in_a_variant_names_the_file(tmp_path):
    base = example_path(tmp_path)

    def edit(wb):
        ws = wb["Engine"]
        ws.cell(param_row(ws, "Bore"), 2).value = "wide"
    var = edited(tmp_path, edit, "broken.xlsx")
    r = CliRunner().invoke(main, ["compare", str(base), str(var), "--format", "json"])
    assert r.exit_code == 2
    assert "1 problem in the input broken.xlsx:" in r.stderr
