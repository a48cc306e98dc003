"""checker.workbook.xlsx reads the same values as openpyxl (read-only, stored results of
formulas) for every kind of cell, and finds formulas and merged ranges."""

from __future__ import annotations

import datetime as dt
import zipfile

import openpyxl
from openpyxl.styles import PatternFill

from checker.workbook.xlsx import open_package
from tests.helpers import example_path


def _openpyxl_values(path) -> dict[str, dict[tuple[int, int], object]]:
    wb = openpyxl.load_workbook(path, read_only=True, data_only=True)
    out = {}
    for ws in wb.worksheets:
        ws.reset_dimensions()  # read every cell, not only the declared used range
        cells = {}
        for r, row in enumerate(ws.iter_rows(), start=1):
            for c, cell in enumerate(row, start=1):
                if cell.value is not None:
                    cells[(r, c)] = (cell.value, cell.number_format)
        out[ws.title] = cells
    wb.close()
    return out


def _ours(path) -> dict[str, dict[tuple[int, int], object]]:
    pkg = open_package(path)
    try:
        out = {}
        for name, part, _kind in pkg.sheets:
            cells = pkg.cells(part)
            out[name] = {(r, c): v for r, row in cells.rows.items() for c, v in row.items()}
        return out
    finally:
        pkg.close()


def _kinds_workbook(tmp_path):
    p = tmp_path / "kinds.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Kinds"
    ws["A1"] = 42
    ws["B1"] = 42.5
    ws["C1"] = -1.25e-7
    ws["D1"] = "shared text"
    ws["E1"] = True
    ws["F1"] = False
    ws["G1"] = dt.datetime(2024, 3, 1, 12, 30)
    ws["H1"] = 0.75
    ws["H1"].number_format = "0%"
    ws["I1"] = "=2*47.3"  # cached value added below
    ws["J1"] = "=1/0"  # no cached value
    ws["A3"] = "after an empty row"
    ws["C5"] = 3
    ws["C5"].fill = PatternFill("solid", fgColor="FFFF00")
    ws.cell(40, 2).fill = PatternFill("solid", fgColor="FFFF00")  # formatted, empty
    ws.merge_cells("A7:B8")
    ws["A7"] = "merged"
    ws2 = wb.create_sheet("Second")
    ws2["B2"] = "x"
    wb.save(p)
    # store a result for I1 as Excel would, and an error code cell
    with zipfile.ZipFile(p) as z:
        items = {i.filename: z.read(i.filename) for i in z.infolist()}
    sheet = items["xl/worksheets/sheet1.xml"].decode()
    sheet = sheet.replace("<f>2*47.3</f><v></v>", "<f>2*47.3</f><v>94.6</v>")
    sheet = sheet.replace("<f>2*47.3</f><v />", "<f>2*47.3</f><v>94.6</v>")
    assert "<v>94.6</v>" in sheet, sheet[:2000]
    sheet = sheet.replace("</row>", '<c r="K1" t="e"><v>#DIV/0!</v></c></row>', 1)
    items["xl/worksheets/sheet1.xml"] = sheet.encode()
    with zipfile.ZipFile(p, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in items.items():
            z.writestr(name, data)
    return p


def test_same_values_as_openpyxl(tmp_path):
    for p in (example_path(tmp_path), _kinds_workbook(tmp_path)):
        theirs, ours = _openpyxl_values(p), _ours(p)
        assert theirs.keys() == ours.keys()
        for name in theirs:
            assert ours[name] == theirs[name], name


def test_kinds_formulas_and_merged(tmp_path):
    p = _kinds_workbook(tmp_path)
    pkg = open_package(p)
    try:
        cells = pkg.cells(pkg.sheets[0][1])
    finally:
        pkg.close()
    row1 = cells.rows[1]
    assert row1[1][0] == 42 and isinstance(row1[1][0], int)
    assert row1[7][0] == dt.datetime(2024, 3, 1, 12, 30)
    assert row1[8] == (0.75, "0%")
    assert row1[9][0] == 94.6 and 10 not in row1  # J1: formula without a stored result
    assert row1[11][0] == "#DIV/0!"
    assert cells.formulas == {(1, 9): "=2*47.3", (1, 10): "=1/0"}
    assert cells.merged == ["A7:B8"]
    assert 40 not in cells.rows and sorted(cells.rows) == [1, 3, 5, 7]
