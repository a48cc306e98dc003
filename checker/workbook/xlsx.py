"""Stream the cells of an .xlsx workbook: plain values, number formats, formulas, merged ranges.

The package (content types, workbook part and its relationships, shared strings, number
formats) is read with the standard library the way openpyxl reads it (openpyxl itself costs
about 0.15 s of CPU to import; it is imported only for a date cell or a number format with
date letters, to apply its rules); the sheet XML is parsed in one expat pass per sheet that
keeps only the cells holding something. Neither openpyxl mode fits a defensive loader on its
own: the normal mode creates every cell of the used range (a formatted cell at row 1,048,576
costs gigabytes), and the read-only mode scans a sheet without a ``<dimension>`` element once
just to open it and then costs about 40 us per cell on each of the two passes needed for
stored values and formulas. Cell values follow openpyxl's rules
(``openpyxl.worksheet._reader.WorkSheetParser``): numbers as int or float, shared and inline
strings, booleans, error codes as text, ISO dates, and numbers with a date format as
``datetime``. Every failure (zip, XML, a missing part) raises; the loader turns it into one
file-level input error.
"""

from __future__ import annotations

import re
import xml.parsers.expat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

LAST_ROW = 1_048_576  # the last row of an .xlsx sheet
LAST_COLUMN = 16_384  # XFD

_REF = re.compile(r"^\$?([A-Za-z]{1,3})\$?(\d+)$")


class PackageProblem(Exception):
    """The package is readable as a zip but not as a workbook (a declared part is missing)."""


@dataclass
class SheetCells:
    """The cells of one sheet that hold something.

    ``rows`` maps a 1-based row number to ``{column: (value, number_format)}`` (1-based
    columns); ``formulas`` maps ``(row, column)`` to the formula text (``=...``);
    ``merged`` lists merged ranges (``A3:A4``).
    """

    rows: dict[int, dict[int, tuple[Any, str | None]]] = field(default_factory=dict)
    formulas: dict[tuple[int, int], str] = field(default_factory=dict)
    merged: list[str] = field(default_factory=list)


# ECMA-376 Part 1, 18.8.30 numFmt: the built-in number formats (as openpyxl lists them,
# openpyxl.styles.numbers.BUILTIN_FORMATS; a test compares the two)
BUILTIN_FORMATS: dict[int, str] = {
    0: "General", 1: "0", 2: "0.00", 3: "#,##0", 4: "#,##0.00",
    5: '"$"#,##0_);("$"#,##0)', 6: '"$"#,##0_);[Red]("$"#,##0)',
    7: '"$"#,##0.00_);("$"#,##0.00)', 8: '"$"#,##0.00_);[Red]("$"#,##0.00)',
    9: "0%", 10: "0.00%", 11: "0.00E+00", 12: "# ?/?", 13: "# ??/??",
    14: "mm-dd-yy", 15: "d-mmm-yy", 16: "d-mmm", 17: "mmm-yy", 18: "h:mm AM/PM",
    19: "h:mm:ss AM/PM", 20: "h:mm", 21: "h:mm:ss", 22: "m/d/yy h:mm",
    37: "#,##0_);(#,##0)", 38: "#,##0_);[Red](#,##0)", 39: "#,##0.00_);(#,##0.00)",
    40: "#,##0.00_);[Red](#,##0.00)",
    41: r'_(* #,##0_);_(* \(#,##0\);_(* "-"_);_(@_)',
    42: r'_("$"* #,##0_);_("$"* \(#,##0\);_("$"* "-"_);_(@_)',
    43: r'_(* #,##0.00_);_(* \(#,##0.00\);_(* "-"??_);_(@_)',
    44: r'_("$"* #,##0.00_)_("$"* \(#,##0.00\)_("$"* "-"??_)_(@_)',
    45: "mm:ss", 46: "[h]:mm:ss", 47: "mmss.0", 48: "##0.0E+0", 49: "@",
}

# content types of the package parts (ECMA-376 Part 1, 12.3; openpyxl.xml.constants)
_WORKBOOK_TYPES = (  # openpyxl's order of preference
    "application/vnd.ms-excel.template.macroEnabled.main+xml",
    "application/vnd.openxmlformats-officedocument.spreadsheetml.template.main+xml",
    "application/vnd.ms-excel.sheet.macroEnabled.main+xml",
    "application/vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml",
)
_SHARED_STRINGS = "application/vnd.openxmlformats-officedocument.spreadsheetml.sharedStrings+xml"
_STYLES = "xl/styles.xml"  # where openpyxl looks for the stylesheet
_DATE_LETTERS = re.compile(r"[dmhysDMHYS]")


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _parse(data: bytes):
    import xml.etree.ElementTree as ET

    return ET.fromstring(data)


@dataclass
class Package:
    """An opened workbook: its sheets (name, part, kind) and what their cells need."""

    sheets: list[tuple[str, str, str]]  # (name, part path in the zip, "worksheet"|"chartsheet")
    archive: Any
    strings: list[str] = field(default_factory=list)
    date1904: bool = False
    _xf_formats: list[int] = field(default_factory=lambda: [0])  # numFmtId per cell style
    _custom: dict[int, str] = field(default_factory=dict)  # numFmtId -> format code
    _formats: dict[int, tuple[str, bool, bool]] = field(default_factory=dict)

    def close(self) -> None:
        self.archive.close()

    def cells(self, part: str, max_col: int = LAST_COLUMN) -> SheetCells:
        """Parse one worksheet part, keeping cells in columns ``1..max_col``."""
        return _SheetParser(self, max_col).parse(part)

    def number_format(self, style_id: int) -> tuple[str, bool, bool]:
        """(number format, is a date format, is a time-delta format) of a cell style (as
        openpyxl: a custom format of the style's id, else the built-in one, else General)."""
        got = self._formats.get(style_id)
        if got is None:
            xf = self._xf_formats
            fmt_id = xf[style_id] if 0 <= style_id < len(xf) else 0
            fmt = self._custom.get(fmt_id)
            if fmt is None:
                fmt = BUILTIN_FORMATS.get(fmt_id, "General")
            if _DATE_LETTERS.search(fmt) is None:  # no date or time letter at all
                got = (fmt, False, False)
            else:  # openpyxl's rules for the rest (literals, locales, [h]...)
                from openpyxl.styles.numbers import is_date_format, is_timedelta_format

                got = (fmt, is_date_format(fmt), is_timedelta_format(fmt))
            self._formats[style_id] = got
        return got

    def epoch(self):
        from openpyxl.utils.datetime import CALENDAR_MAC_1904, CALENDAR_WINDOWS_1900

        return CALENDAR_MAC_1904 if self.date1904 else CALENDAR_WINDOWS_1900


def _rels(archive, part: str) -> dict[str, tuple[str, str]]:
    """Relationships of ``part``: id -> (target path in the zip, type), targets made absolute
    as openpyxl does (``openpyxl.packaging.relationship.get_dependents``)."""
    import posixpath

    folder, name = posixpath.split(part)
    path = posixpath.join(folder, "_rels", f"{name}.rels")
    root = _parse(archive.read(path))
    parent = posixpath.split(posixpath.dirname(path))[0]
    out = {}
    for r in root:
        if _local(r.tag) != "Relationship":
            continue
        target = r.get("Target", "")
        if r.get("TargetMode") != "External":
            target = target[1:] if target.startswith("/") else posixpath.normpath(
                posixpath.join(parent, target))
        out[r.get("Id", "")] = (target, r.get("Type", ""))
    return out


def _shared_strings(src) -> list[str]:
    """The shared-string table as openpyxl reads it (``read_string_table``): per ``si`` its
    plain text and the text of its runs (phonetic runs left out), ``x005F_`` removed."""
    import xml.etree.ElementTree as ET

    out = []
    for _, node in ET.iterparse(src):
        if _local(node.tag) != "si":
            continue
        plain = ""
        runs = []
        for child in node:
            tag = _local(child.tag)
            if tag == "t":
                plain = child.text or ""
            elif tag == "r":
                for t in child:
                    if _local(t.tag) == "t" and t.text is not None:
                        runs.append(t.text)
        out.append((plain + "".join(runs)).replace("x005F_", ""))
        node.clear()
    return out


def open_package(path: Path) -> Package:
    """Open the package (content types, workbook part and its relationships, shared strings,
    number formats) with the standard library, as openpyxl's reader does; no worksheet is
    parsed here (tests compare every value with openpyxl's).

    Raises whatever zipfile and the XML parser raise for a file that is not a workbook
    (``KeyError`` for a missing part, ``OSError`` for a package without a workbook part),
    and :class:`PackageProblem` when a sheet's part is missing (openpyxl would drop that
    sheet silently).
    """
    import zipfile

    archive = zipfile.ZipFile(str(path))
    try:
        manifest = _parse(archive.read("[Content_Types].xml"))
        overrides = [(n.get("PartName", ""), n.get("ContentType", "")) for n in manifest
                     if _local(n.tag) == "Override"]
        defaults = {n.get("ContentType", "") for n in manifest if _local(n.tag) == "Default"}
        strings: list[str] = []
        ss = next((name for name, ct in overrides if ct == _SHARED_STRINGS), None)
        if ss is not None:
            with archive.open(ss[1:]) as src:
                strings = _shared_strings(src)
        wb_part = next((name[1:] for ct in _WORKBOOK_TYPES for name, c in overrides
                        if c == ct), None)
        if wb_part is None:
            if not defaults & set(_WORKBOOK_TYPES):
                raise OSError("File contains no valid workbook part")
            wb_part = "xl/workbook.xml"
        wb = _parse(archive.read(wb_part))
        date1904 = False
        sheet_nodes = []
        for node in wb:
            tag = _local(node.tag)
            if tag == "workbookPr":
                date1904 = node.get("date1904", "").strip().lower() in ("1", "true")
            elif tag == "sheets":
                sheet_nodes = [s for s in node if _local(s.tag) == "sheet"]
        xf_formats, custom = [0], {}
        if _STYLES in archive.namelist():
            for node in _parse(archive.read(_STYLES)):
                tag = _local(node.tag)
                if tag == "numFmts":
                    custom = {int(n.get("numFmtId")): n.get("formatCode", "") for n in node
                              if _local(n.tag) == "numFmt"}
                elif tag == "cellXfs":
                    xfs = [int(x.get("numFmtId", "0")) for x in node if _local(x.tag) == "xf"]
                    xf_formats = xfs or xf_formats
        valid = set(archive.namelist())
        rels = None
        sheets = []
        for node in sheet_nodes:
            rid = next((v for k, v in node.attrib.items() if k.startswith("{")
                        and _local(k) == "id"), None)
            if not rid:  # openpyxl drops such a sheet with a warning
                continue
            if rels is None:
                rels = _rels(archive, wb_part)
            target, rtype = rels[rid]
            name = node.get("name", "")
            if target not in valid:
                raise PackageProblem(f"the content of sheet '{name}' is missing")
            kind = "chartsheet" if "chartsheet" in rtype else "worksheet"
            sheets.append((name, target, kind))
    except BaseException:
        archive.close()
        raise
    return Package(sheets, archive, strings, date1904, xf_formats, custom)


def _cast_number(text: str) -> int | float:
    """As openpyxl: ``int`` unless the text has a decimal point or an exponent."""
    if "." in text or "E" in text or "e" in text:
        return float(text)
    return int(text)


def _column_number(letters: str) -> int:
    n = 0
    for ch in letters.upper():
        n = n * 26 + ord(ch) - 64
    return n


class _SheetParser:
    """expat handlers: one pass, constant memory per row, only non-empty cells kept."""

    def __init__(self, package: Package, max_col: int):
        self.pkg = package
        self.max_col = max_col
        self.out = SheetCells()
        self.strings = package.strings
        self.row = 0
        self.col = 0
        self.cell_row = 0
        self.ctype = "n"
        self.style = 0
        self.text: list[str] | None = None  # collecting character data
        self.v: str | None = None
        self.f: str | None = None
        self.has_f = False
        self.inline: list[str] | None = None
        self.in_cell = False

    def parse(self, part: str) -> SheetCells:
        p = xml.parsers.expat.ParserCreate()  # names as written: "c" or "x:c"
        p.buffer_text = True
        p.StartElementHandler = self.start
        p.EndElementHandler = self.end
        p.CharacterDataHandler = self.chars
        with self.pkg.archive.open(part) as src:
            p.ParseFile(src)
        return self.out

    def chars(self, data: str) -> None:
        if self.text is not None:
            self.text.append(data)

    def start(self, name: str, attrs: dict[str, str]) -> None:
        tag = name if ":" not in name else name.split(":", 1)[1]
        if tag == "c":
            ref = _REF.match(attrs.get("r", ""))
            if ref:
                self.col, self.cell_row = _column_number(ref.group(1)), int(ref.group(2))
            else:
                self.col, self.cell_row = self.col + 1, self.row
            self.ctype = attrs.get("t", "n")
            s = attrs.get("s")
            self.style = int(s) if s else 0
            self.v = self.f = None
            self.has_f = False
            self.inline = None
            self.in_cell = True
        elif tag == "row":
            r = attrs.get("r")
            self.row = int(float(r)) if r else self.row + 1
            self.col = 0
        elif not self.in_cell:
            if tag == "mergeCell":
                self.out.merged.append(str(attrs.get("ref", "?")))
        elif tag in ("v", "f"):
            self.text = []
            if tag == "f":
                self.has_f = True
        elif tag == "is":
            self.inline = []
        elif tag == "t" and self.inline is not None:
            self.text = []

    def end(self, name: str) -> None:
        tag = name if ":" not in name else name.split(":", 1)[1]
        if tag == "c":
            self.in_cell = False
            if self.col <= self.max_col:
                self.finish_cell()
        elif not self.in_cell:
            return
        elif tag == "v":
            self.v = "".join(self.text or ())
            self.text = None
        elif tag == "f":
            self.f = "".join(self.text or ())
            self.text = None
        elif tag == "t" and self.inline is not None:
            self.inline.append("".join(self.text or ()))
            self.text = None

    def finish_cell(self) -> None:
        r, c = self.cell_row, self.col
        if self.has_f:
            self.out.formulas[(r, c)] = "=" + self.f if self.f else "a shared formula"
        value: Any = None
        t = self.ctype
        if t == "inlineStr":
            value = "".join(self.inline) if self.inline is not None else None
        elif self.v:  # openpyxl: an empty <v/> is no value
            v = self.v
            if t == "n":
                value = _cast_number(v)
                fmt, is_date, is_delta = self.pkg.number_format(self.style)
                if is_date:
                    from openpyxl.utils.datetime import from_excel

                    try:
                        value = from_excel(value, self.pkg.epoch(), timedelta=is_delta)
                    except (OverflowError, ValueError):
                        value = "#VALUE!"  # as openpyxl: a date outside the calendar
            elif t == "s":
                value = self.strings[int(v)]
            elif t == "b":
                value = bool(int(v))
            elif t == "d":
                from openpyxl.utils.datetime import from_ISO8601

                value = from_ISO8601(v)
            else:  # "str" (formula text result), "e" (error code)
                value = v
        if value is None:
            return
        fmt = self.pkg.number_format(self.style)[0] if self.style else "General"
        self.out.rows.setdefault(r, {})[c] = (value, fmt)
