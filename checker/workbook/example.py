"""The example workbooks and the workbook writer.

The examples are data: ``templates/example_<engine>.toml`` (:mod:`checker.workbook.
example_data`), one file per engine with every cell of its workbook; what they derive (throw
angles, counterweight phasing, oil-hole heights) is computed by
:mod:`checker.workbook.example_derived`. :func:`example_content` is the I4 gasoline engine of
D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo workshop, 4 Feb 2013 (engine and
bearing data, peak cylinder pressures, crankshaft mass properties, torsional model data,
classical stress inputs, brake torque, the crank-nose and flywheel bolted-joint worked
calculations); values a later analysis needs that the workshop slides do not give are
labelled ASSUMPTION in the note column and listed in the data file's ``[about.assumed]``.
:mod:`checker.workbook.example_i6` and :mod:`checker.workbook.example_v8` give the other two.
:func:`write_workbook` writes any of them.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import Any

from .example_data import about, load_example


def example_content() -> dict[str, Any]:
    """The example workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``."""
    return load_example("i4")


def __getattr__(name: str) -> Any:
    """``TV_MODEL`` (the I4's TVModel sheet) and ``ASSUMED`` (what it assumes), read from
    the data file when asked for."""
    if name == "TV_MODEL":
        return example_content()["TVModel"]
    if name == "ASSUMED":
        return about("i4").get("assumed", {})
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def write_workbook(path: str | Path, content: dict[str, Any]) -> None:
    """Write a workbook from ``content`` (see :func:`example_content`) with openpyxl.

    Parameter sheets are lists of ``(parameter, value, unit, note)``; table sheets are
    ``(columns, rows)`` with ``columns`` a list of ``(name, unit)``; ``Notes`` is a list of lines.
    """
    import openpyxl
    from openpyxl.comments import Comment
    from openpyxl.styles import Alignment, Font, PatternFill
    from openpyxl.worksheet.datavalidation import DataValidation

    from .docs import field_description
    from .loader import DITTO
    from .schema import SHEETS

    wb = openpyxl.Workbook()
    wb.remove(wb.active)
    bold = Font(bold=True)
    grey = Font(italic=True, color="666666")
    unit_fill = PatternFill("solid", fgColor="EEEEEE")
    assumed = PatternFill("solid", fgColor="FFF2CC")  # ASSUMPTION values stand out
    wrap = Alignment(wrap_text=True, vertical="top")

    def choice_list(ws, f, ref: str) -> None:
        """A drop-down of the field's choices (other accepted spellings still allowed)."""
        if not f.choices:
            return
        dv = DataValidation(type="list", formula1='"' + ",".join(f.choices) + '"',
                            allow_blank=True, showErrorMessage=False)
        dv.add(ref)
        ws.add_data_validation(dv)

    for name, body in content.items():
        ws = wb.create_sheet(name)
        spec = SHEETS.get(name)
        fields = {} if spec is None else {f.label.lower(): f for f in spec.fields}
        if name == "Notes":
            for i, line in enumerate(body, start=1):
                ws.cell(row=i, column=1, value=line)
            ws.column_dimensions["A"].width = 100
            continue
        if isinstance(body, list):
            for j, h in enumerate(("parameter", "value", "unit", "note", "description"),
                                  start=1):
                ws.cell(row=1, column=j, value=h).font = bold
            for i, row in enumerate(body, start=2):
                for j, v in enumerate(row, start=1):
                    ws.cell(row=i, column=j, value=v)
                f = fields.get(str(row[0]).lower())
                if f is not None:
                    d = ws.cell(row=i, column=5, value=field_description(f))
                    d.font = grey
                    choice_list(ws, f, f"B{i}")
                if len(row) > 3 and row[3] and "assumption" in str(row[3]).lower():
                    ws.cell(row=i, column=2).fill = assumed
                    ws.cell(row=i, column=4).fill = assumed
            for col, w in zip("ABCDE", (40, 24, 10, 70, 70)):
                ws.column_dimensions[col].width = w
        else:
            cols, rows = body
            note_j = next((j for j, (h, _u) in enumerate(cols, start=1) if h == "note"), None)
            for j, (h, u) in enumerate(cols, start=1):
                c = ws.cell(row=1, column=j, value=h)
                c.font = bold
                f = fields.get(str(h).lower())
                if f is not None:
                    c.comment = Comment(field_description(f), "checker", width=320,
                                        height=120)
                    choice_list(ws, f, f"{openpyxl.utils.get_column_letter(j)}3:"
                                       f"{openpyxl.utils.get_column_letter(j)}"
                                       f"{max(50, len(rows) + 30)}")
                c = ws.cell(row=2, column=j, value=u)
                c.fill = unit_fill
            last = None
            for i, row in enumerate(rows, start=3):
                for j, v in enumerate(row, start=1):
                    if j == note_j and v and v == last:
                        v = DITTO[0]  # a long note once per run of rows
                    elif j == note_j:
                        last = row[j - 1]
                    ws.cell(row=i, column=j, value=v)
                note = row[note_j - 1] if note_j and note_j <= len(row) else None
                if note and "assumption" in str(note).lower():
                    for j in range(1, len(row) + 1):
                        ws.cell(row=i, column=j).fill = assumed
                if note_j:
                    ws.cell(row=i, column=note_j).alignment = wrap
            for j, (h, _u) in enumerate(cols, start=1):
                ws.column_dimensions[openpyxl.utils.get_column_letter(j)].width = max(
                    10, min(60, len(h) + 4)) if h != "note" else 80
        ws.freeze_panes = "A2" if isinstance(body, list) else "A3"
    fixed = _dt.datetime(2013, 2, 4)
    wb.properties.created = fixed
    wb.properties.modified = fixed
    wb.properties.creator = "checker"
    wb.save(path)
