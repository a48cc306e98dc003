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


def test_builtin_formats_are_openpyxls():
    from openpyxl.styles.numbers import BUILTIN_FORMATS

    from checker.workbook.xlsx import BUILTIN_FORMATS as OURS

    assert OURS == BUILTIN_FORMATS


def _restyled(tmp_path, src, name, edit):
    """A copy of ``src`` with ``edit(member name, bytes) -> bytes`` applied to each member."""
    p = tmp_path / name
    with zipfile.ZipFile(src) as z:
        items = {i.filename: z.read(i.filename) for i in z.infolist()}
    with zipfile.ZipFile(p, "w", zipfile.ZIP_DEFLATED) as z:
        for n, data in items.items():
            z.writestr(n, edit(n, data))
    return p


def test_package_details_as_openpyxl(tmp_path):
    """Custom and built-in number formats, date formats, rich-text and phonetic shared
    strings, the 1904 date system: the same values and formats as openpyxl."""
    p = tmp_path / "fmt.xlsx"
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Fmt"
    for col, (value, fmt) in enumerate([
            (0.25, "0.0%"), (1234.5, "#,##0.00"), (3.5, '0.0 "mm"'), (45000.5, "dd/mm/yyyy"),
            (0.75, "[h]:mm:ss"), (12.0, "0.00E+00"), (7, '"days" 0'), (45000, "mm-dd-yy"),
            (2.0, "General"), ("text", "@")], start=1):
        ws.cell(1, col, value).number_format = fmt
    ws["A2"] = "plain"
    wb.save(p)

    sst = (b'<sst xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"'
           b' count="2" uniqueCount="2"><si><t>first</t></si><si><r><t>ri</t></r>'
           b'<r><rPr><b/></rPr><t>ch x005F_y</t></r><rPh sb="0" eb="1"><t>PH</t></rPh>'
           b"</si></sst>")

    def edit(name, data):
        # a shared-string table (openpyxl writes inline strings) with a rich-text string
        # and a phonetic run, and the 1904 date system
        if name == "[Content_Types].xml":
            data = data.replace(b"</Types>", b'<Override PartName="/xl/sharedStrings.xml"'
                                b' ContentType="application/vnd.openxmlformats-officedocument'
                                b'.spreadsheetml.sharedStrings+xml"/></Types>')
        elif name == "xl/_rels/workbook.xml.rels":
            data = data.replace(b"</Relationships>", b'<Relationship Id="rIdS" Type="http://'
                                b"schemas.openxmlformats.org/officeDocument/2006/relationships"
                                b'/sharedStrings" Target="sharedStrings.xml"/></Relationships>')
        elif name == "xl/worksheets/sheet1.xml":
            cell = b'<c r="A2" t="inlineStr"><is><t>plain</t></is></c>'
            assert cell in data, data
            data = data.replace(cell, b'<c r="A2" t="s"><v>1</v></c><c r="B2" t="s">'
                                b"<v>0</v></c>")
        elif name == "xl/workbook.xml":
            assert b"<workbookPr" in data, data
            data = data.replace(b"<workbookPr", b'<workbookPr date1904="1"', 1)
        return data

    def add(path):
        with zipfile.ZipFile(path, "a") as z:
            z.writestr("xl/sharedStrings.xml", sst)
        return path

    q = add(_restyled(tmp_path, p, "fmt1904.xlsx", edit))
    for path in (p, q):
        theirs, ours = _openpyxl_values(path), _ours(path)
        assert ours == theirs
    got = _ours(q)["Fmt"]
    assert got[(2, 1)][0] == "rich y" and got[(2, 2)][0] == "first"
    assert got[(1, 4)][0].year == 2027  # day 45000 of the 1904 system (2023 in 1900)
