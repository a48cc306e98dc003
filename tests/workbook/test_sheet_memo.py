"""The per-sheet conversion memo of checker.workbook.loader: a variant's conversion (cells
changed in memory, the unchanged sheets taken from the memo) equals a cold conversion, errors
and warnings included, in the same order; the memo's copies are not shared."""

from __future__ import annotations

import dataclasses

import pytest

from checker.workbook import loader
from checker.workbook.loader import convert_raw, read_raw_workbook


def _cold(raw):
    loader._SHEET_MEMO.clear()
    return convert_raw(raw, raise_errors=False)


def _same(a, b) -> None:
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        assert x == y, f.name
        if isinstance(x, dict):
            assert list(x) == list(y), f.name  # same order


@pytest.fixture(scope="module")
def raw(tmp_path_factory):
    from click.testing import CliRunner

    from checker.cli import main

    p = tmp_path_factory.mktemp("memo") / "i4.xlsx"
    assert CliRunner().invoke(main, ["template", "--engine", "i4", str(p)]).exit_code == 0
    return read_raw_workbook(p)


def _cell(raw, sheet: str, label: str) -> tuple[str, int, int]:
    for r, row in raw.sheets[sheet].rows.items():
        if row.get(1, (None,))[0] == label:
            return (sheet, r, 2)
    raise AssertionError(label)


def test_variants_equal_a_cold_conversion(raw):
    warm = convert_raw(raw, raise_errors=False)
    _same(warm, _cold(raw))
    convert_raw(raw, raise_errors=False)  # every sheet in the memo
    variants = [
        {("Bearings", 5, 6): 0.05},  # a clearance (mm)
        {("Bearings", 5, 6): -1.0},  # an error in one sheet
        {("Bearings", 5, 6): "abc", ("Bearings", 6, 6): 0.05},  # an error and a value
        {("Oil", 4, 2): 95.0},
    ]
    for ch in variants:
        v = raw.with_values(ch)
        memo = convert_raw(v, raise_errors=False)
        assert any(e.where.startswith("Bearings!F5") for e in memo.errors) == (
            ch.get(("Bearings", 5, 6)) in (-1.0, "abc"))
        _same(memo, _cold(v))
        convert_raw(raw, raise_errors=False)


def test_memo_copies_are_not_shared(raw):
    a = convert_raw(raw, raise_errors=False)
    a.tables["Bearings"][0]["clearance"] = 1.0
    a.params["Oil"]["supply_temperature"] = 1.0
    b = convert_raw(raw, raise_errors=False)
    assert b.tables["Bearings"][0]["clearance"] != 1.0
    assert b.params["Oil"]["supply_temperature"] != 1.0
