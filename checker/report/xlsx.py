"""A minimal, fast and deterministic .xlsx writer (numbers, text, a bold header style).

openpyxl needs about a second for the ~20 000 values of a report's results workbook and
stamps the current time into the file; this writer builds the few XML parts directly (inline
strings, no shared-string table) in a few tens of milliseconds, byte-identical for the same
content. Office Open XML SpreadsheetML, ECMA-376 Part 1, sec. 18.
"""

from __future__ import annotations

import io
import math
import zipfile
from xml.sax.saxutils import escape

_CT = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
       '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
       '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.'
       'relationships+xml"/><Default Extension="xml" ContentType="application/xml"/>'
       '<Override PartName="/xl/workbook.xml" ContentType="application/vnd.openxmlformats-'
       'officedocument.spreadsheetml.sheet.main+xml"/>'
       '<Override PartName="/xl/styles.xml" ContentType="application/vnd.openxmlformats-'
       'officedocument.spreadsheetml.styles+xml"/>{sheets}</Types>')
_SHEET_CT = ('<Override PartName="/xl/worksheets/sheet{n}.xml" ContentType="application/'
             'vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/>')
_RELS = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
         '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
         '<Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/'
         'relationships/officeDocument" Target="xl/workbook.xml"/></Relationships>')
_WB = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
       '<workbook xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" '
       'xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships">'
       '<sheets>{sheets}</sheets></workbook>')
_WB_RELS = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
            '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/'
            'relationships">{rels}<Relationship Id="rIdS" Type="http://schemas.openxmlformats'
            '.org/officeDocument/2006/relationships/styles" Target="styles.xml"/>'
            '</Relationships>')
_STYLES = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
           '<styleSheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main">'
           '<fonts count="2"><font><sz val="11"/><name val="Calibri"/></font>'
           '<font><b/><sz val="11"/><name val="Calibri"/></font></fonts>'
           '<fills count="2"><fill><patternFill patternType="none"/></fill>'
           '<fill><patternFill patternType="gray125"/></fill></fills>'
           '<borders count="1"><border><left/><right/><top/><bottom/><diagonal/></border>'
           '</borders><cellStyleXfs count="1"><xf numFmtId="0" fontId="0" fillId="0" '
           'borderId="0"/></cellStyleXfs><cellXfs count="2"><xf numFmtId="0" fontId="0" '
           'fillId="0" borderId="0" xfId="0"/><xf numFmtId="0" fontId="1" fillId="0" '
           'borderId="0" xfId="0" applyFont="1"/></cellXfs><cellStyles count="1">'
           '<cellStyle name="Normal" xfId="0" builtinId="0"/></cellStyles></styleSheet>')
_DATE = (1980, 1, 1, 0, 0, 0)


def _col(i: int) -> str:
    s = ""
    i += 1
    while i:
        i, r = divmod(i - 1, 26)
        s = chr(65 + r) + s
    return s


_COLS = [_col(i) for i in range(400)]


def sheet_xml(rows: list[list], bold_rows: set[int] | tuple[int, ...] = (),
              widths: list[float] | None = None) -> str:
    """The XML of one sheet (``rows``, ``bold_rows``, ``widths``: see :func:`write`), for a
    sheet written ahead of the workbook (``{"name", "xml"}`` in :func:`write`)."""
    bold_rows = set(bold_rows)
    out = ['<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<worksheet xmlns="'
           'http://schemas.openxmlformats.org/spreadsheetml/2006/main">']
    if widths:
        out.append("<cols>" + "".join(
            f'<col min="{i + 1}" max="{i + 1}" width="{w:g}" customWidth="1"/>'
            for i, w in enumerate(widths)) + "</cols>")
    out.append("<sheetData>")
    for r, row in enumerate(rows, start=1):
        s = ' s="1"' if r - 1 in bold_rows else ""
        cells = []
        for c, v in enumerate(row):
            if v is None or v == "":
                continue
            ref = (_COLS[c] if c < len(_COLS) else _col(c)) + str(r)
            if isinstance(v, bool):
                cells.append(f'<c r="{ref}"{s} t="b"><v>{int(v)}</v></c>')
            elif isinstance(v, (int, float)):
                if isinstance(v, float) and not math.isfinite(v):
                    continue
                cells.append(f'<c r="{ref}"{s}><v>{v:.12g}</v></c>' if isinstance(v, float)
                             else f'<c r="{ref}"{s}><v>{v}</v></c>')
            else:
                cells.append(f'<c r="{ref}"{s} t="inlineStr"><is><t xml:space="preserve">'
                             f"{escape(str(v))}</t></is></c>")
        out.append(f'<row r="{r}">' + "".join(cells) + "</row>")
    out.append("</sheetData></worksheet>")
    return "".join(out)


def write(sheets: list[dict]) -> bytes:
    """An .xlsx file from ``[{"name", "rows", "bold_rows" (row indices, optional),
    "widths" (column widths in characters, optional)}]``; values are str, int, float, bool
    or None (an empty cell). A sheet may come as ``{"name", "xml"}``, its XML written
    beforehand by :func:`sheet_xml`."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED, compresslevel=6) as z:
        def put(name: str, text: str) -> None:
            z.writestr(zipfile.ZipInfo(name, date_time=_DATE), text.encode("utf-8"),
                       compress_type=zipfile.ZIP_DEFLATED)

        n = len(sheets)
        put("[Content_Types].xml", _CT.format(sheets="".join(
            _SHEET_CT.format(n=i + 1) for i in range(n))))
        put("_rels/.rels", _RELS)
        put("xl/workbook.xml", _WB.format(sheets="".join(
            f'<sheet name="{escape(s["name"], {chr(34): "&quot;"})}" sheetId="{i + 1}" '
            f'r:id="rId{i + 1}"/>' for i, s in enumerate(sheets))))
        put("xl/_rels/workbook.xml.rels", _WB_RELS.format(rels="".join(
            f'<Relationship Id="rId{i + 1}" Type="http://schemas.openxmlformats.org/'
            f'officeDocument/2006/relationships/worksheet" Target="worksheets/sheet{i + 1}'
            '.xml"/>' for i in range(n))))
        put("xl/styles.xml", _STYLES)
        for i, s in enumerate(sheets):
            put(f"xl/worksheets/sheet{i + 1}.xml", s["xml"] if "xml" in s else
                sheet_xml(s["rows"], s.get("bold_rows", ()), s.get("widths")))
    return buf.getvalue()
