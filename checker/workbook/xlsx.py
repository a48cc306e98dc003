"""Stream the cells of an .xlsx workbook: plain values, number formats, formulas, merged ranges.

openpyxl reads the package (content types, workbook part, shared strings, styles); the sheet
XML is then parsed here in one expat pass per sheet that keeps only the cells holding
something. Neither openpyxl mode fits a defensive loader on its own: the normal mode creates
every cell of the used range (a formatted cell at row 1,048,576 costs gigabytes), and the
read-only mode scans a sheet without a ``<dimension>`` element once just to open it and then
costs about 40 us per cell on each of the two passes needed for stored values and formulas.
Cell values follow openpyxl's rules (``openpyxl.worksheet._reader.WorkSheetParser``): numbers
as int or float, shared and inline strings, booleans, error codes as text, ISO dates, and
numbers with a date format as ``datetime``. Every failure (zip, XML, a missing part) raises;
the loader turns it into one file-level input error.
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


@dataclass
class Package:
    """An opened workbook: its sheets (name, part, kind) and what their cells need."""

    sheets: list[tuple[str, str, str]]  # (name, part path in the zip, "worksheet"|"chartsheet")
    _reader: Any
    _formats: dict[int, tuple[str, bool, bool]] = field(default_factory=dict)

    def close(self) -> None:
        self._reader.archive.close()

    def cells(self, part: str, max_col: int = LAST_COLUMN) -> SheetCells:
        """Parse one worksheet part, keeping cells in columns ``1..max_col``."""
        return _SheetParser(self, max_col).parse(part)

    def number_format(self, style_id: int) -> tuple[str, bool, bool]:
        """(number format, is a date format, is a time-delta format) of a cell style."""
        got = self._formats.get(style_id)
        if got is None:
            from openpyxl.styles.numbers import (
                BUILTIN_FORMATS,
                BUILTIN_FORMATS_MAX_SIZE,
                is_date_format,
                is_timedelta_format,
            )

            wb = self._reader.wb
            styles = wb._cell_styles
            fmt_id = styles[style_id].numFmtId if 0 <= style_id < len(styles) else 0
            if fmt_id < BUILTIN_FORMATS_MAX_SIZE:
                fmt = BUILTIN_FORMATS.get(fmt_id, "General")
            else:
                fmt = wb._number_formats[fmt_id - BUILTIN_FORMATS_MAX_SIZE]
            got = (fmt, is_date_format(fmt), is_timedelta_format(fmt))
            self._formats[style_id] = got
        return got


def open_package(path: Path) -> Package:
    """Open the package with openpyxl's reader (no worksheet is parsed here).

    Raises whatever zipfile/openpyxl/XML parsing raise for a file that is not a workbook, and
    :class:`PackageProblem` when a sheet's part is missing (openpyxl would drop that sheet
    silently).
    """
    from openpyxl.reader.excel import ExcelReader
    from openpyxl.styles.stylesheet import apply_stylesheet

    reader = ExcelReader(str(path), read_only=True, data_only=True, keep_links=False)
    try:
        reader.read_manifest()
        reader.read_strings()
        reader.read_workbook()
        apply_stylesheet(reader.archive, reader.wb)
        sheets = []
        for sheet, rel in reader.parser.find_sheets():
            if rel.target not in reader.valid_files:
                raise PackageProblem(f"the content of sheet '{sheet.name}' is missing")
            kind = "chartsheet" if "chartsheet" in str(rel.Type) else "worksheet"
            sheets.append((str(sheet.name), rel.target, kind))
    except BaseException:
        reader.archive.close()
        raise
    return Package(sheets, reader)


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
        self.strings = package._reader.shared_strings
        self.epoch = package._reader.wb.epoch
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
        with self.pkg._reader.archive.open(part) as src:
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
                        value = from_excel(value, self.epoch, timedelta=is_delta)
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
