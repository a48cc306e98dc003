"""Read an engine workbook defensively: every problem found, each with its sheet and cell.

The workbook is opened read-only twice with openpyxl: once for formulas (to find formula cells
that have no stored result, which pandas/openpyxl would silently read as empty) and once for the
stored values. Values are converted to SI through :func:`checker.units.to_si`. Nothing is
written and the file is never modified.
"""

from __future__ import annotations

import hashlib
import math
import re
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError, InputErrors
from ..units import KINDS, UnitProblem, to_si
from .schema import SHEETS, Field, Sheet

_PARAM_HEADER = ("parameter", "value", "unit")


@dataclass
class WorkbookData:
    """Everything read from a workbook, in SI, with the cell each value came from."""

    path: str
    sha256: str
    params: dict[str, dict[str, Any]] = field(default_factory=dict)
    tables: dict[str, list[dict[str, Any]]] = field(default_factory=dict)
    where: dict[tuple, str] = field(default_factory=dict)
    units: dict[tuple, str] = field(default_factory=dict)
    sheets_present: tuple[str, ...] = ()
    errors: list[InputError] = field(default_factory=list)
    assumptions: list[str] = field(default_factory=list)

    def cell(self, sheet: str, attr: str, row: int | None = None) -> str:
        """The ``Sheet!A1`` address of a parameter (or of a table cell in data row ``row``)."""
        key = (sheet, attr) if row is None else (sheet, row, attr)
        return self.where.get(key, f"{sheet}")


def _norm(s: Any) -> str:
    return re.sub(r"\s+", " ", str(s)).strip().lower()


def _addr(sheet: str, cell) -> str:
    return f"{sheet}!{cell.coordinate}"


def _describe(v: Any) -> str:
    if isinstance(v, str):
        return f"text '{v}'"
    return repr(v)


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
        return "one of " + ", ".join(f"'{c}'" for c in f.choices)
    k = KINDS[f.kind]
    if f.kind in ("dimensionless", "ratio"):
        return "a number (dimensionless)"
    return f"a {k.name.replace('_', ' ')} with a unit (e.g. {k.example})"


def _check(f: Field, v: float) -> str | None:
    """Physical range check; returns a problem text or None."""
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


class _Reader:
    def __init__(self, path: Path):
        self.path = path
        self.errors: list[InputError] = []

    def err(self, where: str, msg: str) -> None:
        self.errors.append(InputError(where, msg))

    def value(self, sheet: str, f: Field, vcell, fcell, ucell, data: WorkbookData, key: tuple):
        """Convert one value cell (with unit cell text) according to field ``f``."""
        where = _addr(sheet, vcell)
        raw = vcell.value
        if fcell is not None and fcell.data_type == "f" and raw is None:
            self.err(where, f"{f.label} is a formula ({fcell.value}) with no stored result;"
                     " open and save the workbook in Excel or LibreOffice so the value is"
                     " stored")
            return None
        data.where[key] = where
        if raw is None or (isinstance(raw, str) and raw.strip() == ""):
            return None
        unit = None if ucell is None else ucell
        if f.kind == "text":
            return str(raw).strip() if not isinstance(raw, float) else f"{raw:g}"
        if f.kind == "choice":
            text = _norm(raw if not isinstance(raw, float) else f"{raw:g}")
            text = {"big-end": "big end", "bigend": "big end", "v-engine": "v",
                    "counter weight": "counterweight", "c/w": "counterweight",
                    "yield": "yield controlled", "angle": "angle controlled"}.get(text, text)
            if text not in f.choices:
                self.err(where, f"{f.label}: expected {_expected(f)}, found {_describe(raw)}")
                return None
            return text
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
            v = int(num)
            problem = _check(f, v)
            if problem:
                self.err(where, f"{f.label} {problem}, found {v}")
                return None
            return v
        percent = "%" in str(vcell.number_format or "")
        try:
            si = to_si(num, unit, f.kind, percent_formatted=percent)
        except UnitProblem as exc:
            uw = where if ucell is None else where
            self.err(uw, f"{f.label}: {exc}")
            return None
        problem = _check(f, si)
        if problem:
            shown = f"{num:g}" + (f" {unit}" if unit else "")
            self.err(where, f"{f.label} {problem}, found {shown}")
            return None
        data.units[key] = unit or ""
        return si

    def merged(self, sheet: str, ws) -> None:
        for rng in getattr(ws, "merged_cells", None) and ws.merged_cells.ranges or []:
            self.err(f"{sheet}!{rng.coord}", "merged cells are not allowed in the input area;"
                     " unmerge them and fill every cell")

    def parameters(self, spec: Sheet, ws, wsf, data: WorkbookData) -> None:
        name = spec.name
        rows = list(ws.iter_rows())
        frows = list(wsf.iter_rows()) if wsf is not None else [None] * len(rows)
        by_label = {_norm(f.label): f for f in spec.fields}
        by_label.update({_norm(f.attr): f for f in spec.fields})
        params: dict[str, Any] = {f.attr: None for f in spec.fields}
        seen: dict[str, str] = {}
        if not rows:
            self.err(name, "sheet is empty; expected the header 'parameter | value | unit |"
                     " note' in row 1")
            data.params[name] = params
            return
        header = tuple(_norm(c.value) if c.value is not None else "" for c in rows[0][:3])
        if header != _PARAM_HEADER:
            self.err(f"{name}!A1", "expected the header 'parameter | value | unit | note' in"
                     f" row 1, found {' | '.join(h or '(blank)' for h in header)}")
        for r, row in enumerate(rows[1:], start=1):
            cells = list(row) + [None] * 4
            label_cell, vcell, ucell = cells[0], cells[1], cells[2]
            if label_cell is None or str(label_cell.value or "").strip() == "":
                if vcell is not None and vcell.value not in (None, ""):
                    self.err(_addr(name, vcell), "value without a parameter name in column A")
                continue
            label = _norm(label_cell.value)
            f = by_label.get(label)
            if f is None:
                self.err(_addr(name, label_cell), f"unknown parameter '{label_cell.value}'"
                         f" (see docs/workbook.md for the parameters of sheet {name})")
                continue
            if f.attr in seen:
                self.err(_addr(name, label_cell), f"duplicate parameter '{label_cell.value}'"
                         f" (already given in {seen[f.attr]})")
                continue
            seen[f.attr] = _addr(name, label_cell)
            frow = frows[r] if r < len(frows) and frows[r] is not None else None
            fcell = list(frow)[1] if frow is not None and len(list(frow)) > 1 else None
            if vcell is None:
                continue
            unit_text = None
            if ucell is not None and ucell.value is not None:
                unit_text = str(ucell.value).strip()
            params[f.attr] = self.value(name, f, vcell, fcell, unit_text, data, (name, f.attr))
            note = cells[3].value if cells[3] is not None else None
            if note and "assumption" in str(note).lower():
                shown = f"{vcell.value}" + (f" {unit_text}" if unit_text not in (None, "-") else "")
                data.assumptions.append(f"{_addr(name, vcell)} {f.label} = {shown}: {note}")
            if params[f.attr] is None and f.required and (name, f.attr) in data.where and not any(
                e.where == _addr(name, vcell) for e in self.errors
            ):
                self.err(_addr(name, vcell), f"{f.label} is required: expected {_expected(f)},"
                         " found an empty cell")
        for f in spec.fields:
            if f.required and f.attr not in seen:
                self.err(name, f"required parameter '{f.label}' is missing: add a row with"
                         f" {_expected(f)}")
        data.params[name] = params

    def table(self, spec: Sheet, ws, wsf, data: WorkbookData) -> None:
        name = spec.name
        rows = list(ws.iter_rows())
        frows = list(wsf.iter_rows()) if wsf is not None else []
        out: list[dict[str, Any]] = []
        data.tables[name] = out
        if not rows:
            self.err(name, "sheet is empty; expected column names in row 1 and units in row 2")
            return
        header = rows[0]
        units_row = rows[1] if len(rows) > 1 else []
        col_of: dict[str, int] = {}
        by_label = {_norm(f.label): f for f in spec.fields}
        by_label.update({_norm(f.attr): f for f in spec.fields})
        for j, c in enumerate(header):
            if c.value is None or str(c.value).strip() == "":
                continue
            label = _norm(c.value)
            if label in spec.extra_columns:
                continue
            f = by_label.get(label)
            if f is None:
                self.err(_addr(name, c), f"unknown column '{c.value}'; expected one of "
                         + ", ".join(f"'{x.label}'" for x in spec.fields))
                continue
            if f.attr in col_of:
                self.err(_addr(name, c), f"duplicate column '{c.value}'")
                continue
            col_of[f.attr] = j
        for f in spec.fields:
            if f.required and f.attr not in col_of:
                self.err(f"{name}!1:1", f"required column '{f.label}' is missing")
        unit_of: dict[str, str | None] = {}
        for attr, j in col_of.items():
            u = units_row[j].value if j < len(units_row) else None
            unit_of[attr] = None if u is None else str(u).strip()
        keys_seen: dict[Any, str] = {}
        note_col = next((j for j, c in enumerate(header)
                         if c.value is not None and _norm(c.value) in ("note", "notes")), None)
        notes: dict[str, list[int]] = {}
        for r in range(2, len(rows)):
            row = rows[r]
            if all(c.value is None or (isinstance(c.value, str) and not c.value.strip())
                   for c in row):
                continue
            frow = frows[r] if r < len(frows) else None
            rec: dict[str, Any] = {"_row": r + 1}
            idx = len(out)
            for f in spec.fields:
                j = col_of.get(f.attr)
                if j is None:
                    rec[f.attr] = None
                    continue
                vcell = row[j] if j < len(row) else None
                fcell = frow[j] if frow is not None and j < len(frow) else None
                if vcell is None:
                    rec[f.attr] = None
                    continue
                v = self.value(name, f, vcell, fcell, unit_of.get(f.attr), data,
                               (name, idx, f.attr))
                rec[f.attr] = v
                if v is None and f.required and not any(
                    e.where == _addr(name, vcell) for e in self.errors
                ):
                    self.err(_addr(name, vcell), f"{f.label} is required: expected"
                             f" {_expected(f)}, found an empty cell")
            if spec.key and rec.get(spec.key) is not None:
                k = rec[spec.key]
                kk = _norm(k) if isinstance(k, str) else k
                j = col_of[spec.key]
                where = _addr(name, row[j])
                if kk in keys_seen:
                    self.err(where, f"duplicate {spec.key} '{k}' (already in {keys_seen[kk]})")
                else:
                    keys_seen[kk] = where
            out.append(rec)
            if note_col is not None and note_col < len(row) and row[note_col].value and \
                    "assumption" in str(row[note_col].value).lower():
                notes.setdefault(str(row[note_col].value), []).append(r + 1)
        for text, rws in notes.items():
            rr = f"row {rws[0]}" if len(rws) == 1 else f"rows {', '.join(map(str, rws))}"
            data.assumptions.append(f"{name} {rr}: {text}")


def read_workbook(path: str | Path, raise_errors: bool = True) -> WorkbookData:
    """Read and convert an engine workbook; raise :class:`InputErrors` with every problem.

    With ``raise_errors=False`` the cell-level problems are returned in ``data.errors`` so the
    caller can add cross-sheet problems and report all of them together (a file that is not a
    workbook still raises at once).

    Parameters
    ----------
    path : str or Path
        An ``.xlsx`` file laid out as described in ``docs/workbook.md``.
    """
    import openpyxl
    from openpyxl.utils.exceptions import InvalidFileException

    p = Path(path)
    if not p.is_file():
        raise InputErrors([InputError(str(p), "file not found")])
    blob = p.read_bytes()
    sha = hashlib.sha256(blob).hexdigest()
    reader = _Reader(p)
    try:
        wb_values = openpyxl.load_workbook(p, data_only=True, read_only=False)
        wb_formulas = openpyxl.load_workbook(p, data_only=False, read_only=False)
    except (zipfile.BadZipFile, InvalidFileException, KeyError, OSError, ValueError) as exc:
        raise InputErrors([InputError(p.name, "is not an Excel .xlsx workbook"
                                      f" ({type(exc).__name__}); save it as .xlsx")]) from None
    data = WorkbookData(path=str(p), sha256=sha, sheets_present=tuple(wb_values.sheetnames))
    known = {_norm(s): s for s in SHEETS}
    present: dict[str, str] = {}
    for sn in wb_values.sheetnames:
        key = known.get(_norm(sn))
        if key is None:
            reader.err(sn, f"unknown sheet '{sn}'; known sheets: {', '.join(SHEETS)}")
            continue
        if key in present:
            reader.err(sn, f"duplicate sheet '{sn}'")
            continue
        present[key] = sn
    for name, spec in SHEETS.items():
        if name not in present:
            if spec.required:
                reader.err(name, f"required sheet '{name}' is missing")
            continue
        if spec.shape == "notes":
            continue
        ws = wb_values[present[name]]
        wsf = wb_formulas[present[name]]
        reader.merged(name, ws)
        if spec.shape == "parameters":
            reader.parameters(spec, ws, wsf, data)
        else:
            reader.table(spec, ws, wsf, data)
    for name, spec in SHEETS.items():
        if spec.shape == "parameters" and name not in data.params:
            data.params[name] = {f.attr: None for f in spec.fields}
        if spec.shape == "table" and name not in data.tables:
            data.tables[name] = []
    wb_values.close()
    wb_formulas.close()
    data.errors = list(reader.errors)
    if raise_errors and reader.errors:
        raise InputErrors(reader.errors)
    return data
