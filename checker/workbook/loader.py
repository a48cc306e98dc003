"""Read an engine workbook defensively: every problem found, each with its sheet and cell.

The cells are streamed by :mod:`checker.workbook.xlsx` (standard library, one expat
pass per sheet): stored values, number formats, formulas (a formula cell without a stored
result, which pandas/openpyxl would silently read as empty, is an error) and merged ranges.
Only cells that hold something are kept, so a sheet whose used range reaches row 1,048,576
through empty formatted cells costs no more than its data, and the cost is linear in the cells
and the problems (problem cells are looked up in a set). Everything zipfile, openpyxl or the XML
parser raise while opening or reading is a file-level input error naming the file (a damaged,
encrypted or non-workbook file), never an internal error. Values are converted to SI through
:func:`checker.workbook.units.to_si`, choices through
:func:`checker.workbook.schema.resolve_choice`,
and checked against the fields' declared ranges (``valid``: error, ``usual``: warning).
Nothing is written and the file is never modified.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError, InputErrors
from .schema import SHEETS, ChoiceProblem, Field, Sheet, expected_choices, resolve_choice
from .units import KINDS, UnitProblem, from_si, kind_words, to_si
from .xlsx import LAST_COLUMN, PackageProblem, SheetCells, open_package

_PARAM_HEADER = ("parameter", "value", "unit")
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
    sheets_present: tuple[str, ...] = ()  # the schema's names of the sheets in the file
    errors: list[InputError] = field(default_factory=list)
    warnings: list[InputError] = field(default_factory=list)
    assumptions: list[str] = field(default_factory=list)
    estimates: list[str] = field(default_factory=list)
    """Inputs whose note says ESTIMATE (sized by a stated rule, e.g. by ``checker new``), in
    the format of :attr:`assumptions`."""
    refused: set[str] = field(default_factory=set)
    """Value cells left unread because of an error reported at another cell (a column's unit
    cell): the builders' checks treat them as cells with an error, not as blank cells."""

    def cell(self, sheet: str, attr: str, row: int | None = None) -> str:
        """The ``Sheet!A1`` address of a parameter (or of a table cell in data row ``row``)."""
        key = (sheet, attr) if row is None else (sheet, row, attr)
        return self.where.get(key, f"{sheet}")


def _norm(s: Any) -> str:
    return re.sub(r"\s+", " ", str(s)).strip().lower()


def _addr(sheet: str, row: int, col: int) -> str:
    """``Sheet!B4`` for 1-based row and column numbers."""
    return f"{sheet}!{_letter(col)}{row}"


_LETTERS: dict[int, str] = {}


def _letter(col: int) -> str:
    """Column letters of a 1-based column number (1 -> A, 27 -> AA), as
    ``openpyxl.utils.get_column_letter`` (without importing openpyxl)."""
    got = _LETTERS.get(col)
    if got is None:
        if not 1 <= col <= LAST_COLUMN:
            raise ValueError(f"invalid column index {col}")
        n, text = col, ""
        while n:
            n, r = divmod(n - 1, 26)
            text = chr(65 + r) + text
        got = _LETTERS[col] = text
    return got


def _describe(v: Any) -> str:
    if isinstance(v, str):
        return f"text '{v}'"
    if isinstance(v, (_dt.datetime, _dt.date, _dt.time, _dt.timedelta)):
        # Excel turned the entry into a date or time (e.g. "1-5" -> 1 May): say so in words
        if isinstance(v, _dt.datetime):
            text = (v.date().isoformat() if (v.hour, v.minute, v.second) == (0, 0, 0)
                    else v.isoformat(sep=" ", timespec="seconds"))
        else:
            text = v.isoformat() if not isinstance(v, _dt.timedelta) else str(v)
        what = "time" if isinstance(v, (_dt.time, _dt.timedelta)) else "date"
        return (f"the {what} {text} (the cell holds a {what}, not a number: type the number"
                " and format the cell as a number)")
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
    if f.expected:
        return f.expected
    if f.kind == "int":
        return "a whole number"
    if f.kind == "int_list":
        return "a whole number, or whole numbers separated by commas (e.g. 1, 5)"
    if f.kind == "text":
        return "text"
    if f.kind == "choice":
        return expected_choices(f)
    k = KINDS[f.kind]
    if f.kind in ("dimensionless", "ratio"):
        return "a number (dimensionless)"
    return f"{kind_words(k.name)} with a unit (e.g. {k.example})"


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


def _int_list(f: Field, raw: Any) -> tuple[tuple[int, ...] | None, str | None, list[str]]:
    """A cell of whole numbers (kind ``int_list``): one number, or several separated by
    commas or semicolons (``1, 5``; ``1;5``), each checked like an ``int`` field against the
    field's sign check and ``valid``/``usual`` ranges. Returns (tuple without repeats or None,
    error text or None, warning texts)."""
    parts = re.split(r"[,;]", raw.strip()) if isinstance(raw, str) else [raw]
    out: list[int] = []
    warnings: list[str] = []
    for part in parts:
        num = _number(part.strip() if isinstance(part, str) else part)
        if num is None or not math.isfinite(num) or not float(num).is_integer():
            hint = ""
            if isinstance(raw, float) and not float(raw).is_integer():
                hint = (" (a cell typed as 1,5 in a decimal-comma locale is stored as the"
                        " number 1.5: write '1; 5' or format the cell as text)")
            return None, f"{f.label}: expected {_expected(f)}, found {_describe(raw)}{hint}", []
        n = int(num)
        problem = _check(f, n)
        if problem:
            return None, f"{f.label} {problem}, found {n}", []
        if f.valid is not None and not f.valid.contains(n, f.kind):
            return None, (f"{f.label} {n} is outside {f.valid.text()}, the range the"
                          " calculations can handle; check the value"), []
        if f.usual is not None and not f.usual.contains(n, f.kind):
            warnings.append(f"{f.label} {n} is outside the usual range {f.usual.text()} of"
                            " crank-train engines; check the value")
        if n in out:
            return None, f"{f.label}: {n} is listed twice in '{raw}'", []
        out.append(n)
    return tuple(out), None, warnings


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


_BOUNDS: dict[int, tuple[float, float, float, float]] = {}


def _bounds(f: Field) -> tuple[float, float, float, float]:
    """SI ends of the field's valid and usual ranges (open ends infinite), cached per field."""
    got = _BOUNDS.get(id(f))
    if got is None:
        inf = float("inf")
        vlo, vhi = f.valid.si(f.kind) if f.valid is not None else (-inf, inf)
        ulo, uhi = f.usual.si(f.kind) if f.usual is not None else (-inf, inf)
        got = _BOUNDS[id(f)] = (vlo, vhi, ulo, uhi)
    return got


def _range_problem(f: Field, num: float, si: float, unit: str | None
                   ) -> tuple[str | None, str | None]:
    """(error, warning) texts for a value outside the field's ``valid`` / ``usual`` range."""
    vlo, vhi, ulo, uhi = _bounds(f)
    valid = vlo <= si <= vhi
    usual = ulo <= si <= uhi
    if valid and usual:
        return None, None
    shown = _shown(f, num, unit, si)
    hint = f"; check the value and its unit ('{unit}')" if unit and unit != "-" else \
        "; check the value"
    if not valid:
        return (f"{f.label} {shown} is outside {f.valid.text()}, the range the calculations"
                f" can handle{hint}"), None
    return None, (f"{f.label} {shown} is outside the usual range {f.usual.text()} of"
                  f" crank-train engines{hint}")


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
        self._choices: dict[tuple, str | ChoiceProblem] = {}  # resolved spellings per field

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
        if f.kind == "int_list":
            got, error, warnings = _int_list(f, raw)
            if error:
                self.err(where, error)
            for w in warnings:
                self.warn(where, w)
            return got
        if f.kind == "text":
            return str(raw).strip() if not isinstance(raw, float) else f"{raw:g}"
        if f.kind == "choice":
            ck = (id(f), type(raw), raw if isinstance(raw, (str, float, int)) else repr(raw))
            got = self._choices.get(ck)
            if got is None:
                try:
                    got = self._choices[ck] = resolve_choice(f, raw)
                except ChoiceProblem as exc:
                    got = self._choices[ck] = ChoiceProblem(f"{f.label}: {exc}")
            if isinstance(got, ChoiceProblem):
                self.err(where, str(got))
                return None
            return got
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
            error, warning = _range_problem(f, num, num, None)
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
        error, warning = _range_problem(f, num, si, unit)
        if error:
            self.err(where, error)
            return None
        if warning:
            self.warn(where, warning)
        data.units[key] = unit or ""
        return si

    def merged(self, sheet: str, raw: SheetCells) -> None:
        for ref in raw.merged:
            self.err(f"{sheet}!{ref}", "merged cells are not allowed in the input area;"
                     " unmerge them and fill every cell")

    def parameters(self, spec: Sheet, raw: SheetCells, data: WorkbookData) -> None:
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
        def cells(r: int) -> list[tuple[Any, str | None]]:
            row = raw.rows.get(r, {})
            return [row.get(j, (None, None)) for j in range(1, _PARAM_COLUMNS + 1)]

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
            elif note and "ESTIMATE" in str(note) and not _blank(value_raw):
                data.estimates.append(f"{vwhere} {f.label}: {note}")
            if params[f.attr] is None and f.required and not self.has_error(vwhere):
                self.err(vwhere, f"{f.label} is required: expected {_expected(f)}, found an"
                         " empty cell")
        for f in spec.fields:
            if f.required and f.attr not in seen:
                self.err(name, f"required parameter '{f.label}' is missing: add a row with"
                         f" {_expected(f)}")

    def table(self, spec: Sheet, raw: SheetCells, data: WorkbookData) -> None:
        name = spec.name
        out: list[dict[str, Any]] = []
        data.tables[name] = out
        if not raw.rows and not raw.formulas:
            self.err(name, "sheet is empty; expected column names in row 1 and units in row 2")
            return
        header = raw.rows.get(1, {})
        units_row = raw.rows.get(2, {})
        col_of: dict[str, int] = {}  # attr -> 1-based column
        by_label = {_norm(f.label): f for f in spec.fields}
        by_label.update({_norm(f.attr): f for f in spec.fields})
        note_col = None
        for j, (v, _) in sorted(header.items()):
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
            u = units_row.get(j, (None, None))[0]
            unit_of[attr] = None if u is None else str(u).strip()
        fields = {f.attr: f for f in spec.fields}
        unit_bad = {attr: problem for attr in col_of
                    if (problem := _unit_problem(fields[attr], unit_of[attr])) is not None}
        keys_seen: dict[Any, str] = {}
        notes: dict[str, list[int]] = {}
        est_rows: dict[str, list[int]] = {}
        last_note = None
        formula_rows = {r for r, _ in raw.formulas}
        for r in sorted(set(raw.rows) | formula_rows):
            if r <= 2:
                continue
            row = raw.rows.get(r, {})
            if r not in formula_rows and all(_blank(v) for v, _ in row.values()):
                continue
            rec: dict[str, Any] = {"_row": r}
            idx = len(out)
            for f in spec.fields:
                j = col_of.get(f.attr)
                if j is None:
                    rec[f.attr] = None
                    continue
                v, fmt = row.get(j, (None, None))
                where = _addr(name, r, j)
                if f.attr in unit_bad and not _blank(v):
                    # the column's unit is wrong: one error at its unit cell (row 2), the
                    # column's values unread
                    at = _addr(name, 2, j)
                    if not self.has_error(at):
                        self.err(at, unit_bad[f.attr])
                    data.where[(name, idx, f.attr)] = where
                    data.refused.add(where)
                    rec[f.attr] = None
                    continue
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
            if note_col is not None:
                note = row.get(note_col, (None, None))[0]
                if note is not None and _norm(note) in DITTO:
                    note = last_note  # "as above": the note of the row above applies
                last_note = note
                if note and "assumption" in str(note).lower():
                    notes.setdefault(str(note), []).append(r)
                elif note and "ESTIMATE" in str(note):
                    est_rows.setdefault(str(note), []).append(r)
        if spec.max_rows is not None and len(out) > spec.max_rows:
            self.err(name, f"{len(out)} data rows; at most {spec.max_rows} are accepted (the"
                     " calculation time grows with them)")
        elif spec.dense_rows is not None and len(out) > spec.dense_rows:
            self.warn(name, f"{len(out)} data rows, unusually dense (more than"
                      f" {spec.dense_rows}); accepted and interpolated, but check that the"
                      " sheet holds what you meant")
        for text, rws in notes.items():
            rr = f"row {rws[0]}" if len(rws) == 1 else f"rows {', '.join(map(str, rws))}"
            data.assumptions.append(f"{name} {rr}: {text}")
        for text, rws in est_rows.items():
            rr = f"row {rws[0]}" if len(rws) == 1 else f"rows {', '.join(map(str, rws))}"
            data.estimates.append(f"{name} {rr}: {text}")


def _unit_problem(f: Field, unit: str | None) -> str | None:
    """What is wrong with a table column's unit cell for field ``f`` (None: nothing, or a
    field without a unit)."""
    if f.kind in ("int", "int_list", "text", "choice"):
        return None
    try:
        to_si(1.0, unit, f.kind)
    except UnitProblem as exc:
        return f"{f.label}: {exc} (the unit of the column, row 2)"
    return None


DITTO = ("as above", "ditto", "〃", '"')
"""A table row's note that repeats the note of the row above (the template writes a long
note once per run of rows)."""


@dataclass(frozen=True)
class RawWorkbook:
    """The cells of a workbook that hold something, read once (plain values; picklable).

    :func:`convert_raw` turns it into :class:`WorkbookData`; a parametric study changes cells
    in memory with :meth:`with_values` and converts again, without touching the file."""

    path: str
    sha256: str
    sheetnames: tuple[str, ...]
    sheets: dict[str, SheetCells]  # schema sheet name -> its cells
    problems: tuple[InputError, ...] = ()  # sheet-level problems (unknown, duplicate...)
    present: tuple[str, ...] = ()  # schema sheet names found in the file

    def with_values(self, changes: dict[tuple[str, int, int], Any]) -> RawWorkbook:
        """A copy with cell values replaced: ``{(sheet, row, column): value}`` (1-based);
        only the changed rows are copied, number formats are kept. The sha256 of the copy
        identifies the base and the changes."""
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
                row = dict(rows.get(r, {}))
                row[c] = (v, row.get(c, (None, None))[1])
                rows[r] = row
            sheets[sh] = SheetCells(rows, {k: f for k, f in raw.formulas.items()
                                           if k not in cells}, list(raw.merged))
        h = hashlib.sha256(self.sha256.encode())
        h.update(repr(sorted(changes.items())).encode())
        return RawWorkbook(self.path, h.hexdigest(), self.sheetnames, sheets, self.problems,
                           self.present)


def read_raw_workbook(path: str | Path) -> RawWorkbook:
    """Read the cells of an engine workbook (one pass over the file, nothing converted).

    A file that is not a readable workbook raises :class:`InputErrors` at once, with one
    file-level error naming the file.
    """
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
    raws: dict[str, SheetCells] = {}
    present: dict[str, str] = {}
    try:
        # everything that touches the file: open the package, stream the sheets
        pkg = open_package(p)
        try:
            sheetnames = tuple(name for name, _, _ in pkg.sheets)
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
            parts = {name: (part, kind) for name, part, kind in pkg.sheets}
            for name, spec in SHEETS.items():
                if name not in present or spec.shape == "notes":
                    continue
                part, kind = parts[present[name]]
                if kind != "worksheet":
                    reader.err(name, f"sheet '{present[name]}' is a chart sheet; expected a"
                               " worksheet")
                    continue
                ncols = _PARAM_COLUMNS if spec.shape == "parameters" else LAST_COLUMN
                raws[name] = pkg.cells(part, ncols)
        finally:
            pkg.close()
    except PackageProblem as exc:
        raise _unreadable(p, str(exc)) from None
    except Exception as exc:  # noqa: BLE001 - any failure of the file is a file-level error
        raise _unreadable(p, _short(exc)) from None
    return RawWorkbook(str(p), sha, sheetnames, raws, tuple(reader.errors), tuple(present))


def _convert_sheet(reader: _Reader, name: str, spec: Sheet, sheet: SheetCells,
                   data: WorkbookData) -> None:
    reader.merged(name, sheet)
    if spec.shape == "parameters":
        reader.parameters(spec, sheet, data)
    else:
        reader.table(spec, sheet, data)


@dataclass
class _SheetPart:
    """One sheet converted on its own: what it adds to a :class:`WorkbookData` and to the
    reader's problems (in the order a whole-workbook conversion adds them)."""

    cells: SheetCells  # kept: the memo's key is its identity
    data: WorkbookData
    errors: list[InputError]
    warnings: list[InputError]

    def copy_to(self, reader: _Reader, data: WorkbookData) -> None:
        part = self.data
        for name, params in part.params.items():
            data.params[name] = dict(params)
        for name, rows in part.tables.items():
            data.tables[name] = [{k: list(v) if isinstance(v, list) else v
                                  for k, v in rec.items()} for rec in rows]
        data.where.update(part.where)
        data.units.update(part.units)
        data.assumptions.extend(part.assumptions)
        data.estimates.extend(part.estimates)
        data.refused.update(part.refused)
        for e in self.errors:
            reader.err(e.where, e.message)
        reader.warnings.extend(self.warnings)


_SHEET_MEMO: dict[tuple[str, str, int], _SheetPart] = {}
_SHEET_MEMO_SIZE = 64
"""Sheets kept converted (:func:`_converted_sheet`): a study's or the remedies' variants change
one sheet of the workbook (:meth:`RawWorkbook.with_values` keeps the others as they are)."""


def _converted_sheet(path: str, name: str, spec: Sheet, sheet: SheetCells) -> _SheetPart:
    """The conversion of one sheet, from the memo when the same cells (the same object) were
    converted before; a fresh conversion otherwise."""
    key = (path, name, id(sheet))
    got = _SHEET_MEMO.get(key)
    if got is not None and got.cells is sheet:
        _SHEET_MEMO[key] = _SHEET_MEMO.pop(key)  # most recently used last
        return got
    reader = _Reader(Path(path))
    part = WorkbookData(path=path, sha256="")
    _convert_sheet(reader, name, spec, sheet, part)
    got = _SheetPart(sheet, part, reader.errors, reader.warnings)
    _SHEET_MEMO[key] = got
    while len(_SHEET_MEMO) > _SHEET_MEMO_SIZE:
        del _SHEET_MEMO[next(iter(_SHEET_MEMO))]
    return got


def convert_raw(raw: RawWorkbook, raise_errors: bool = True) -> WorkbookData:
    """Convert the cells of a :class:`RawWorkbook` to SI (every problem with its cell)."""
    reader = _Reader(Path(raw.path))
    for e in raw.problems:
        reader.err(e.where, e.message)
    data = WorkbookData(path=raw.path, sha256=raw.sha256, sheets_present=raw.present)
    for name, spec in SHEETS.items():
        if name not in raw.present:
            if spec.required:
                reader.err(name, f"required sheet '{name}' is missing")
            continue
        sheet = raw.sheets.get(name)
        if sheet is None:
            continue
        if raw.problems:  # (a sheet's conversion asks whether a cell has an error already)
            _convert_sheet(reader, name, spec, sheet, data)
        else:
            _converted_sheet(raw.path, name, spec, sheet).copy_to(reader, data)
    for name, spec in SHEETS.items():
        if spec.shape == "parameters" and name not in data.params:
            data.params[name] = {f.attr: None for f in spec.fields}
        if spec.shape == "table" and name not in data.tables:
            data.tables[name] = []
    data.errors = list(reader.errors)
    data.warnings = list(reader.warnings)
    if raise_errors and reader.errors:
        raise InputErrors(reader.errors, reader.warnings)
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
