"""Read an engine workbook defensively: every problem found, each with its sheet and cell.

The workbook is streamed read-only twice with openpyxl: once for the stored values and once
for formulas (to find formula cells that have no stored result, which pandas/openpyxl would
silently read as empty). Only rows that hold something are kept, so a sheet whose used range
reaches row 1,048,576 through empty formatted cells costs no more than its data. Everything
openpyxl, zipfile or the XML parser raises while opening or reading is a file-level input
error naming the file (a damaged, encrypted or non-workbook file), never an internal error.
Values are converted to SI through :func:`checker.units.to_si`, choices through
:func:`checker.workbook.schema.resolve_choice`, and checked against the fields' declared
ranges (``valid``: error, ``usual``: warning). Nothing is written and the file is never
modified.
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from openpyxl.utils import get_column_letter

from ..errors import InputError, InputErrors
from ..units import KINDS, UnitProblem, from_si, to_si
from .schema import SHEETS, ChoiceProblem, Field, Sheet, expected_choices, resolve_choice

_PARAM_HEADER = ("parameter", "value", "unit")
_LAST_ROW = 1_048_576  # last row of an .xlsx sheet
_PARAM_COLUMNS = 4  # parameter | value | unit | note
_OLE_MAGIC = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"  # encrypted .xlsx and old .xls files


@dataclass
class WorkbookData:
    """Everything read from a workbook, in SI, with the cell each value came from.

    ``errors`` are input errors (the check cannot run); ``warnings`` are values that parse
    and can be computed with but lie outside the usual range of crank-train engines (each
    with its cell), to be shown with the results.
    """

    path: str
    sha256: str
    params: dict[str, dict[str, Any]] = field(default_factory=dict)
    tables: dict[str, list[dict[str, Any]]] = field(default_factory=dict)
    where: dict[tuple, str] = field(default_factory=dict)
    units: dict[tuple, str] = field(default_factory=dict)
    sheets_present: tuple[str, ...] = ()
    errors: list[InputError] = field(default_factory=list)
    warnings: list[InputError] = field(default_factory=list)
    assumptions: list[str] = field(default_factory=list)

    def cell(self, sheet: str, attr: str, row: int | None = None) -> str:
        """The ``Sheet!A1`` address of a parameter (or of a table cell in data row ``row``)."""
        key = (sheet, attr) if row is None else (sheet, row, attr)
        return self.where.get(key, f"{sheet}")


@dataclass
class _RawSheet:
    """The cells of one sheet that hold something: plain values, no openpyxl objects.

    ``rows`` maps a 1-based row number to ``(value, number_format)`` per column (1-based
    column ``j`` at index ``j - 1``); ``formulas`` maps ``(row, column)`` to the formula text
    of formula cells.
    """

    rows: dict[int, tuple[tuple[Any, str | None], ...]]
    formulas: dict[tuple[int, int], str]
    merged: list[str]
    ncols: int


def _norm(s: Any) -> str:
    return re.sub(r"\s+", " ", str(s)).strip().lower()


def _addr(sheet: str, row: int, col: int) -> str:
    """``Sheet!B4`` for 1-based row and column numbers."""
    return f"{sheet}!{get_column_letter(col)}{row}"


def _describe(v: Any) -> str:
    if isinstance(v, str):
        return f"text '{v}'"
    return repr(v)


def _blank(v: Any) -> bool:
    return v is None or (isinstance(v, str) and not v.strip())


_NUMBER_TEXT = re.compile(r"^[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?$")


def _number(value: Any) -> float | None:
    """A cell value as float, or None if it is not a number (bools are not numbers)."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str) and _NUMBER_TEXT.match(value.strip()):
        return float(value.strip())
    return None


def _expected(f: Field) -> str:
    if f.kind == "int":
        return "a whole number"
    if f.kind == "text":
        return "text"
    if f.kind == "choice":
        return expected_choices(f)
    k = KINDS[f.kind]
    if f.kind in ("dimensionless", "ratio"):
        return "a number (dimensionless)"
    return f"a {k.name.replace('_', ' ')} with a unit (e.g. {k.example})"


def _check(f: Field, v: float) -> str | None:
    """Sign check; returns a problem text or None."""
    c = f.check
    if c is None:
        return None
    if c == ">0" and not v > 0:
        return "must be greater than zero"
    if c == ">=0" and not v >= 0:
        return "must not be negative"
    if c == ">1" and not v > 1:
        return "must be greater than 1"
    if c == ">=1" and not v >= 1:
        return "must be at least 1"
    if c == "0..1" and not 0 < v <= 1:
        return "must be between 0 and 1"
    return None


def _shown(f: Field, num: float, unit: str | None, si: float) -> str:
    """The value as entered, plus its value in the unit of the field's ranges when different."""
    text = f"{num:g}" + (f" {unit}" if unit and unit != "-" else "")
    span = f.valid or f.usual
    if f.kind == "int" or span is None or span.unit in ("", "-") or span.unit == (unit or ""):
        return text
    try:
        conv = float(from_si(si, KINDS[f.kind].si, span.unit))
    except Exception:  # pragma: no cover - display only
        return text
    return f"{text} (= {conv:.4g} {span.unit})"


def _range_problem(f: Field, si: float, shown: str, unit: str | None
                   ) -> tuple[str | None, str | None]:
    """(error, warning) texts for a value outside the field's ``valid`` / ``usual`` range."""
    hint = f"; check the value and its unit ('{unit}')" if unit and unit != "-" else \
        "; check the value"
    if f.valid is not None and not f.valid.contains(si, f.kind):
        return (f"{f.label} {shown} is outside {f.valid.text()}, the range the calculations"
                f" can handle{hint}"), None
    if f.usual is not None and not f.usual.contains(si, f.kind):
        return None, (f"{f.label} {shown} is outside the usual range {f.usual.text()} of"
                      f" crank-train engines{hint}")
    return None, None


def _short(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    text = text if len(text) <= 160 else text[:157] + "..."
    return type(exc).__name__ + (f": {text}" if text else "")


def _unreadable(p: Path, detail: str) -> InputErrors:
    return InputErrors([InputError(
        p.name, f"cannot be read: not an Excel .xlsx workbook, or a damaged one ({detail});"
        " open it in Excel or LibreOffice and save it again as an unencrypted .xlsx")])


class _Reader:
    def __init__(self, path: Path):
        self.path = path
        self.errors: list[InputError] = []
        self.warnings: list[InputError] = []
        self._error_cells: set[str] = set()

    def err(self, where: str, msg: str) -> None:
        self.errors.append(InputError(where, msg))
        self._error_cells.add(where)

    def warn(self, where: str, msg: str) -> None:
        self.warnings.append(InputError(where, msg))

    def has_error(self, where: str) -> bool:
        return where in self._error_cells

    def value(self, where: str, f: Field, raw: Any, number_format: str | None,
              formula: str | None, unit: str | None, data: WorkbookData, key: tuple):
        """Convert one value cell (with its unit cell text) according to field ``f``."""
        if formula is not None and raw is None:
            self.err(where, f"{f.label} is a formula ({formula}) with no stored result;"
                     " open and save the workbook in Excel or LibreOffice so the value is"
                     " stored")
            return None
        data.where[key] = where
        if _blank(raw):
            return None
        if f.kind == "text":
            return str(raw).strip() if not isinstance(raw, float) else f"{raw:g}"
        if f.kind == "choice":
            try:
                return resolve_choice(f, raw)
            except ChoiceProblem as exc:
                self.err(where, f"{f.label}: {exc}")
                return None
        num = _number(raw)
        if num is None:
            hint = " (use a decimal point, not a comma)" if isinstance(raw, str) and re.match(
                r"^[+-]?\d+,\d+$", raw.strip()) else ""
            self.err(where, f"{f.label}: expected {_expected(f)}, found {_describe(raw)}{hint}")
            return None
        if not math.isfinite(num):
            self.err(where, f"{f.label}: expected a finite number, found {raw!r}")
            return None
        if f.kind == "int":
            if not float(num).is_integer():
                self.err(where, f"{f.label}: expected a whole number, found {raw!r}")
                return None
            problem = _check(f, num)
            if problem:
                self.err(where, f"{f.label} {problem}, found {num:g}")
                return None
            error, warning = _range_problem(f, num, f"{num:g}", None)
            if error:
                self.err(where, error)
                return None
            if warning:
                self.warn(where, warning)
            return int(num)
        percent = "%" in str(number_format or "")
        try:
            si = to_si(num, unit, f.kind, percent_formatted=percent)
        except UnitProblem as exc:
            self.err(where, f"{f.label}: {exc}")
            return None
        problem = _check(f, si)
        if problem:
            shown = f"{num:g}" + (f" {unit}" if unit else "")
            self.err(where, f"{f.label} {problem}, found {shown}")
            return None
        error, warning = _range_problem(f, si, _shown(f, num, unit, si), unit)
        if error:
            self.err(where, error)
            return None
        if warning:
            self.warn(where, warning)
        data.units[key] = unit or ""
        return si

    def merged(self, sheet: str, raw: _RawSheet) -> None:
        for ref in raw.merged:
            self.err(f"{sheet}!{ref}", "merged cells are not allowed in the input area;"
                     " unmerge them and fill every cell")

    def parameters(self, spec: Sheet, raw: _RawSheet, data: WorkbookData) -> None:
        name = spec.name
        by_label = {_norm(f.label): f for f in spec.fields}
        by_label.update({_norm(f.attr): f for f in spec.fields})
        params: dict[str, Any] = {f.attr: None for f in spec.fields}
        seen: dict[str, str] = {}
        data.params[name] = params
        row_numbers = sorted(set(raw.rows) | {r for r, _ in raw.formulas})
        if not row_numbers:
            self.err(name, "sheet is empty; expected the header 'parameter | value | unit |"
                     " note' in row 1")
            return
        empty = ((None, None),) * _PARAM_COLUMNS

        def cells(r: int) -> tuple[tuple[Any, str | None], ...]:
            return (raw.rows.get(r, empty) + empty)[:_PARAM_COLUMNS]

        header = tuple(_norm(v) if v is not None else "" for v, _ in cells(1)[:3])
        if header != _PARAM_HEADER:
            self.err(f"{name}!A1", "expected the header 'parameter | value | unit | note' in"
                     f" row 1, found {' | '.join(h or '(blank)' for h in header)}")
        for r in row_numbers:
            if r == 1:
                continue
            (label_raw, _), (value_raw, value_fmt), (unit_raw, _), (note, _) = cells(r)
            vwhere = _addr(name, r, 2)
            formula = raw.formulas.get((r, 2))
            if _blank(label_raw):
                if not _blank(value_raw) or formula is not None:
                    self.err(vwhere, "value without a parameter name in column A")
                continue
            f = by_label.get(_norm(label_raw))
            if f is None:
                self.err(_addr(name, r, 1), f"unknown parameter '{label_raw}' (see"
                         f" docs/workbook.md for the parameters of sheet {name})")
                continue
            if f.attr in seen:
                self.err(_addr(name, r, 1), f"duplicate parameter '{label_raw}' (already given"
                         f" in {seen[f.attr]})")
                continue
            seen[f.attr] = _addr(name, r, 1)
            unit_text = None if unit_raw is None else str(unit_raw).strip()
            params[f.attr] = self.value(vwhere, f, value_raw, value_fmt, formula, unit_text,
                                        data, (name, f.attr))
            if note and "assumption" in str(note).lower():
                shown = f"{value_raw}" + (f" {unit_text}" if unit_text not in (None, "-")
                                          else "")
                data.assumptions.append(f"{vwhere} {f.label} = {shown}: {note}")
            if params[f.attr] is None and f.required and not self.has_error(vwhere):
                self.err(vwhere, f"{f.label} is required: expected {_expected(f)}, found an"
                         " empty cell")
        for f in spec.fields:
            if f.required and f.attr not in seen:
                self.err(name, f"required parameter '{f.label}' is missing: add a row with"
                         f" {_expected(f)}")

    def table(self, spec: Sheet, raw: _RawSheet, data: WorkbookData) -> None:
        name = spec.name
        out: list[dict[str, Any]] = []
        data.tables[name] = out
        if not raw.rows and not raw.formulas:
            self.err(name, "sheet is empty; expected column names in row 1 and units in row 2")
            return
        header = raw.rows.get(1, ())
        units_row = raw.rows.get(2, ())
        col_of: dict[str, int] = {}  # attr -> 1-based column
        by_label = {_norm(f.label): f for f in spec.fields}
        by_label.update({_norm(f.attr): f for f in spec.fields})
        note_col = None
        for j, (v, _) in enumerate(header, start=1):
            if _blank(v):
                continue
            label = _norm(v)
            if label in spec.extra_columns:
                if label in ("note", "notes") and note_col is None:
                    note_col = j
                continue
            f = by_label.get(label)
            if f is None:
                self.err(_addr(name, 1, j), f"unknown column '{v}'; expected one of "
                         + ", ".join(f"'{x.label}'" for x in spec.fields))
                continue
            if f.attr in col_of:
                self.err(_addr(name, 1, j), f"duplicate column '{v}'")
                continue
            col_of[f.attr] = j
        for f in spec.fields:
            if f.required and f.attr not in col_of:
                self.err(f"{name}!1:1", f"required column '{f.label}' is missing")
        unit_of: dict[str, str | None] = {}
        for attr, j in col_of.items():
            u = units_row[j - 1][0] if j <= len(units_row) else None
            unit_of[attr] = None if u is None else str(u).strip()
        keys_seen: dict[Any, str] = {}
        notes: dict[str, list[int]] = {}
        last_note = None
        formula_rows = {r for r, _ in raw.formulas}
        for r in sorted(set(raw.rows) | formula_rows):
            if r <= 2:
                continue
            row = raw.rows.get(r, ())
            if r not in formula_rows and all(_blank(v) for v, _ in row):
                continue
            rec: dict[str, Any] = {"_row": r}
            idx = len(out)
            for f in spec.fields:
                j = col_of.get(f.attr)
                if j is None:
                    rec[f.attr] = None
                    continue
                v, fmt = row[j - 1] if j <= len(row) else (None, None)
                where = _addr(name, r, j)
                val = self.value(where, f, v, fmt, raw.formulas.get((r, j)), unit_of.get(f.attr),
                                 data, (name, idx, f.attr))
                rec[f.attr] = val
                if val is None and f.required and not self.has_error(where):
                    self.err(where, f"{f.label} is required: expected {_expected(f)}, found an"
                             " empty cell")
            if spec.key and rec.get(spec.key) is not None:
                k = rec[spec.key]
                kk = _norm(k) if isinstance(k, str) else k
                where = _addr(name, r, col_of[spec.key])
                if kk in keys_seen:
                    self.err(where, f"duplicate {spec.key} '{k}' (already in {keys_seen[kk]})")
                else:
                    keys_seen[kk] = where
            out.append(rec)
            if note_col is not None and note_col <= len(row):
                note = row[note_col - 1][0]
                if note is not None and _norm(note) in DITTO:
                    note = last_note  # "as above": the note of the row above applies
                last_note = note
                if note and "assumption" in str(note).lower():
                    notes.setdefault(str(note), []).append(r)
        if spec.max_rows is not None and len(out) > spec.max_rows:
            self.err(name, f"{len(out)} data rows; at most {spec.max_rows} are accepted (the"
                     " calculation time grows with them)")
        for text, rws in notes.items():
            rr = f"row {rws[0]}" if len(rws) == 1 else f"rows {', '.join(map(str, rws))}"
            data.assumptions.append(f"{name} {rr}: {text}")


DITTO = ("as above", "ditto", "〃", '"')
"""A table row's note that repeats the note of the row above (the template writes a long
note once per run of rows)."""


def _merged_ranges(ws) -> list[str]:
    """``A3:A4`` refs of the merged ranges of a read-only sheet (streamed, rows discarded)."""
    import xml.etree.ElementTree as ET

    refs: list[str] = []
    sheet_data = None
    source = getattr(ws, "_get_source", None)  # openpyxl's read-only sheet XML stream
    if source is None:  # pragma: no cover - other openpyxl versions
        return refs
    with source() as src:
        for event, el in ET.iterparse(src, events=("start", "end")):
            tag = el.tag.rsplit("}", 1)[-1]
            if event == "start":
                if tag == "sheetData":
                    sheet_data = el
                continue
            if tag == "mergeCell":
                refs.append(str(el.get("ref", "?")))
            elif tag == "row" and sheet_data is not None:
                try:
                    sheet_data.remove(el)
                except ValueError:  # pragma: no cover - a row outside sheetData
                    el.clear()
    return refs


def _declared_sheets(p: Path) -> list[str]:
    """Sheet names the workbook part declares (openpyxl silently drops a sheet whose part is
    missing from the archive; a damaged file must not lose a sheet unnoticed)."""
    import xml.etree.ElementTree as ET
    import zipfile

    with zipfile.ZipFile(p) as z:
        types = ET.fromstring(z.read("[Content_Types].xml"))
        part = next((el.get("PartName", "") for el in types
                     if el.tag.rsplit("}", 1)[-1] == "Override"
                     and el.get("ContentType", "").endswith(".main+xml")), "")
        book = ET.fromstring(z.read(part.lstrip("/")))
    return [str(el.get("name")) for el in book.iter() if el.tag.rsplit("}", 1)[-1] == "sheet"]


def _sheet_width(ws) -> int:
    """Last column of row 1 that holds a value (the table's width)."""
    for row in ws.iter_rows(min_row=1, max_row=1):
        return max((j for j, c in enumerate(row, start=1) if not _blank(c.value)), default=0)
    return 0


def _read_raw(ws_values, ws_formulas, ncols: int) -> _RawSheet:
    """Stream both passes of one sheet, keeping only the rows that hold something."""
    rows: dict[int, tuple[tuple[Any, str | None], ...]] = {}
    formulas: dict[tuple[int, int], str] = {}
    if ncols > 0:
        last_empty = None
        for r, row in enumerate(ws_values.iter_rows(min_row=1, max_row=_LAST_ROW,
                                                    max_col=ncols), start=1):
            if row is last_empty:  # openpyxl repeats one tuple for missing rows
                continue
            if all(c.value is None for c in row):
                last_empty = row
                continue
            rows[r] = tuple((c.value, c.number_format if c.value is not None else None)
                            for c in row)
        last_empty = None
        for r, row in enumerate(ws_formulas.iter_rows(min_row=1, max_row=_LAST_ROW,
                                                      max_col=ncols), start=1):
            if row is last_empty:
                continue
            found = False
            for j, c in enumerate(row, start=1):
                if c.data_type == "f" and c.value is not None:
                    formulas[(r, j)] = str(c.value)
                    found = True
            if not found and all(c.value is None for c in row):
                last_empty = row
    return _RawSheet(rows, formulas, _merged_ranges(ws_values), ncols)


@dataclass(frozen=True)
class RawWorkbook:
    """The cells of a workbook that hold something, read once (plain values, no openpyxl
    objects; picklable). :func:`convert_raw` turns it into :class:`WorkbookData`; a
    parametric study changes cells in memory with :meth:`with_values` and converts again,
    without touching the file."""

    path: str
    sha256: str
    sheetnames: tuple[str, ...]
    sheets: dict[str, _RawSheet]  # schema sheet name -> its cells
    problems: tuple[InputError, ...] = ()  # sheet-level problems (unknown, duplicate...)
    present: tuple[str, ...] = ()  # schema sheet names found in the file

    def with_values(self, changes: dict[tuple[str, int, int], Any]) -> RawWorkbook:
        """A copy with cell values replaced: ``{(sheet, row, column): value}`` (1-based);
        only the changed rows are copied, the number formats are kept. The sha256 of the
        copy identifies the base and the changes."""
        if not changes:
            return self
        sheets = dict(self.sheets)
        by_sheet: dict[str, dict[tuple[int, int], Any]] = {}
        for (sh, r, c), v in changes.items():
            by_sheet.setdefault(sh, {})[(r, c)] = v
        for sh, cells in by_sheet.items():
            raw = sheets[sh]
            rows = dict(raw.rows)
            for (r, c), v in cells.items():
                row = list(rows.get(r, ()))
                row += [(None, None)] * (c - len(row))
                row[c - 1] = (v, row[c - 1][1])
                rows[r] = tuple(row)
            sheets[sh] = _RawSheet(rows, {k: f for k, f in raw.formulas.items()
                                          if k not in cells}, raw.merged, raw.ncols)
        h = hashlib.sha256(self.sha256.encode())
        h.update(repr(sorted(changes.items())).encode())
        return RawWorkbook(self.path, h.hexdigest(), self.sheetnames, sheets, self.problems,
                           self.present)


def read_raw_workbook(path: str | Path) -> RawWorkbook:
    """Read the cells of an engine workbook (one pass over the file, nothing converted).

    A file that is not a readable workbook raises :class:`InputErrors` at once, with one
    file-level error naming the file.
    """
    import openpyxl

    p = Path(path)
    if not p.is_file():
        raise InputErrors([InputError(str(p), "file not found")])
    try:
        blob = p.read_bytes()
    except OSError as exc:
        raise InputErrors([InputError(p.name, f"cannot be read ({_short(exc)})")]) from None
    sha = hashlib.sha256(blob).hexdigest()
    if blob.startswith(_OLE_MAGIC):
        raise _unreadable(p, "it is an encrypted (password-protected) workbook or an old .xls"
                          " file")
    reader = _Reader(p)
    raws: dict[str, _RawSheet] = {}
    wbs = []
    present: dict[str, str] = {}
    try:
        # everything that touches the file: open, stream the sheets, scan merged cells
        wb_values = openpyxl.load_workbook(p, data_only=True, read_only=True)
        wbs.append(wb_values)
        wb_formulas = openpyxl.load_workbook(p, data_only=False, read_only=True)
        wbs.append(wb_formulas)
        sheetnames = tuple(wb_values.sheetnames)
        lost = [n for n in _declared_sheets(p) if n not in sheetnames]
        if lost:
            raise _unreadable(p, f"the content of sheet '{lost[0]}' is missing")
        known = {_norm(s): s for s in SHEETS}
        for sn in sheetnames:
            key = known.get(_norm(sn))
            if key is None:
                reader.err(sn, f"unknown sheet '{sn}'; known sheets: {', '.join(SHEETS)}")
                continue
            if key in present:
                reader.err(sn, f"duplicate sheet '{sn}'")
                continue
            present[key] = sn
        for name, spec in SHEETS.items():
            if name not in present or spec.shape == "notes":
                continue
            ws, wsf = wb_values[present[name]], wb_formulas[present[name]]
            if not hasattr(ws, "iter_rows") or not hasattr(wsf, "iter_rows"):
                reader.err(name, f"sheet '{present[name]}' is a chart sheet; expected a"
                           " worksheet")
                continue
            ncols = _PARAM_COLUMNS if spec.shape == "parameters" else _sheet_width(ws)
            raws[name] = _read_raw(ws, wsf, ncols)
    except InputErrors:
        raise
    except Exception as exc:  # noqa: BLE001 - any failure of the file is a file-level error
        raise _unreadable(p, _short(exc)) from None
    finally:
        for wb in wbs:
            try:
                wb.close()
            except Exception:  # noqa: BLE001, S110 - closing a damaged archive
                pass
    return RawWorkbook(str(p), sha, sheetnames, raws, tuple(reader.errors), tuple(present))


def convert_raw(raw: RawWorkbook, raise_errors: bool = True) -> WorkbookData:
    """Convert the cells of a :class:`RawWorkbook` to SI (every problem with its cell)."""
    reader = _Reader(Path(raw.path))
    for e in raw.problems:
        reader.err(e.where, e.message)
    data = WorkbookData(path=raw.path, sha256=raw.sha256, sheets_present=raw.sheetnames)
    for name, spec in SHEETS.items():
        if name not in raw.present:
            if spec.required:
                reader.err(name, f"required sheet '{name}' is missing")
            continue
        sheet = raw.sheets.get(name)
        if sheet is None:
            continue
        reader.merged(name, sheet)
        if spec.shape == "parameters":
            reader.parameters(spec, sheet, data)
        else:
            reader.table(spec, sheet, data)
    for name, spec in SHEETS.items():
        if spec.shape == "parameters" and name not in data.params:
            data.params[name] = {f.attr: None for f in spec.fields}
        if spec.shape == "table" and name not in data.tables:
            data.tables[name] = []
    data.errors = list(reader.errors)
    data.warnings = list(reader.warnings)
    if raise_errors and reader.errors:
        raise InputErrors(reader.errors)
    return data


def read_workbook(path: str | Path, raise_errors: bool = True) -> WorkbookData:
    """Read and convert an engine workbook; raise :class:`InputErrors` with every problem.

    With ``raise_errors=False`` the cell-level problems are returned in ``data.errors`` so the
    caller can add cross-sheet problems and report all of them together (a file that is not a
    readable workbook still raises at once, with one file-level error naming the file).
    Values outside a field's usual range are returned in ``data.warnings``.

    Parameters
    ----------
    path : str or Path
        An ``.xlsx`` file laid out as described in ``docs/workbook.md``.
    """
    return convert_raw(read_raw_workbook(path), raise_errors)
