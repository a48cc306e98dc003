"""Put a variant's values into the cells of the base workbook (in memory, never on disk).

A study parameter names a sheet, rows and a column; :func:`resolve` finds their cells in the
base workbook once, :func:`apply_variant` writes a variant's values into a copy of the raw
cells, converting each value from the study's unit into the unit of the cell (so a study in
um changes a clearance column kept in mm correctly, including offset units such as °C).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..workbook.loader import RawWorkbook
from ..workbook.schema import SHEETS, choice_key
from .spec import Parameter, Study, StudyFileError, did_you_mean


@dataclass(frozen=True)
class Target:
    """The cells of one parameter: (row, column) of each value cell and its unit text."""

    param: Parameter
    cells: tuple[tuple[int, int, str | None], ...]  # (row, col, unit) 1-based
    labels: tuple[str, ...]  # Sheet!A1 addresses, for messages and the report
    items: tuple[str, ...] = ()  # row keys (bearing, joint... names) of a table parameter


def _text(v: Any) -> str:
    return "" if v is None else (f"{v:g}" if isinstance(v, float) else str(v)).strip()


def _cell(raw, r: int, c: int) -> Any:
    """Value of cell (row, column) of a sheet's cells (None when empty)."""
    return raw.rows.get(r, {}).get(c, (None, None))[0]


def _label(spec, attr: str | None) -> str:
    """The column heading a user sees for the field ``attr``."""
    return next((f.label for f in spec.fields if f.attr == attr), str(attr))


def _header(raw, spec) -> dict[str, int]:
    hdr = raw.rows.get(1, {})
    out = {}
    for j, (v, _) in sorted(hdr.items()):
        t = _text(v).lower()
        for f in spec.fields:
            if t in (f.label.lower(), f.attr.lower()):
                out[f.attr] = j
    return out


def resolve(study: Study, base: RawWorkbook) -> list[Target]:
    """The cells of every parameter in the base workbook (StudyFileError naming the study line
    and the sheet when a row or column is not there)."""
    from openpyxl.utils import get_column_letter

    problems: list[str] = []
    out: list[Target] = []
    for q in study.parameters:
        raw = base.sheets.get(q.sheet)
        spec = SHEETS[q.sheet]
        pre = f"line {q.line}: parameter '{q.name}'"
        if raw is None:
            problems.append(f"{pre}: the workbook has no sheet {q.sheet}")
            continue
        cells: list[tuple[int, int, str | None]] = []
        items: list[str] = []
        if spec.shape == "parameters":
            for r in sorted(raw.rows):
                if r > 1 and _text(_cell(raw, r, 1)).lower() in (q.field.label.lower(),
                                                                 q.field.attr.lower()):
                    unit = _text(_cell(raw, r, 3))
                    cells.append((r, 2, unit or None))
                    break
            if not cells:
                problems.append(f"{pre}: sheet {q.sheet} has no row '{q.field.label}'; add it"
                                " to the workbook first (the study changes existing values)")
                continue
        else:
            cols = _header(raw, spec)
            j = cols.get(q.field.attr)
            if j is None:
                problems.append(f"{pre}: sheet {q.sheet} has no column '{q.field.label}'")
                continue
            unit = _text(_cell(raw, 2, j))
            kj = cols.get(spec.key) if spec.key else None
            wanted = {choice_key(x) for x in q.rows} if q.rows else None
            found: set[str] = set()
            keys: list[str] = []
            for r in sorted(raw.rows):
                if r < 3:
                    continue
                key = _text(_cell(raw, r, kj)) if kj else str(r)
                if key:
                    keys.append(key)
                if wanted is not None and choice_key(key) not in wanted:
                    continue
                ok = True
                for attr, val in q.where:
                    wj = cols.get(attr)
                    cell = _text(_cell(raw, r, wj)) if wj else ""
                    ok &= choice_key(cell) == choice_key(val)
                if ok:
                    found.add(choice_key(key))
                    cells.append((r, j, unit or None))
                    items.append(key)
            if wanted is not None and wanted - found:
                miss = [x for x in q.rows if choice_key(x) not in found]
                hints = "".join(did_you_mean(x, keys) for x in miss)
                problems.append(f"{pre}: sheet {q.sheet} has no row {', '.join(miss)} in"
                                f" column '{_label(spec, spec.key)}'" + (
                                    hints or f" (rows: {', '.join(keys[:20])}"
                                    + (", ..." if len(keys) > 20 else "") + ")"))
                continue
            if not cells:
                problems.append(f"{pre}: no row of sheet {q.sheet} matches "
                                + ", ".join(f"{a} = {v}" for a, v in q.where))
                continue
        labels = tuple(f"{q.sheet}!{get_column_letter(c)}{r}" for r, c, _ in cells)
        out.append(Target(q, tuple(cells), labels, tuple(items)))
    if problems:
        raise StudyFileError(study.path, problems)
    return out


def cell_value(target: Target, unit: str | None, value: Any, number_format: str | None = None
               ) -> Any:
    """``value`` (in the study's unit) expressed in the cell's ``unit``.

    Conversions go through the workbook's own unit reading (:func:`checker.workbook.units.to_si`),
    so
    every spreadsheet spelling it accepts works; the map is affine (offset units), solved
    from two points.
    """
    from ..workbook.units import to_si

    q = target.param
    if not q.numeric or value is None:
        return value
    if q.field.kind == "int":
        return int(round(value))
    pct = "%" in (number_format or "")
    want = to_si(float(value), q.unit or None, q.field.kind)
    b = to_si(0.0, unit, q.field.kind, percent_formatted=pct)
    a = to_si(1.0, unit, q.field.kind, percent_formatted=pct) - b
    return (want - b) / a


def apply_variant(base: RawWorkbook, targets: list[Target], values: dict[str, Any]
                  ) -> RawWorkbook:
    """A copy of ``base`` with the variant's values in the targeted cells (None = unchanged).

    Only the changed rows are copied; the base is never modified.
    """
    changes: dict[tuple[str, int, int], Any] = {}
    for t in targets:
        v = values.get(t.param.name)
        if v is None:
            continue
        raw = base.sheets[t.param.sheet]
        for r, c, unit in t.cells:
            fmt = raw.rows.get(r, {}).get(c, (None, None))[1]
            changes[(t.param.sheet, r, c)] = cell_value(t, unit, v, fmt)
    return base.with_values(changes)
