"""A digest of a written workbook, cell by cell, to compare ``checker template`` outputs.

Every sheet in order with its freeze panes, column widths and data validations, and every
cell that holds a value or a style: value (as read back: the file writes 86.0 as 86), number
format, fill colour, font (bold, italic, colour), wrap and the comment text; and the workbook's
creator and creation date (openpyxl sets "modified" to the save time). Used by
``tests/workbook/test_example_data.py`` against the digests in ``tests/workbook/data/``
(written by ``scripts/examples_to_data.py``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any


def _color(c: Any) -> str | None:
    if c is None:
        return None
    rgb = getattr(c, "rgb", None)
    return rgb if isinstance(rgb, str) else None


def workbook_digest(path: str | Path) -> dict[str, Any]:
    """The digest of the workbook at ``path`` (a JSON-ready dict)."""
    import openpyxl

    wb = openpyxl.load_workbook(path)
    props = wb.properties
    out: dict[str, Any] = {
        "properties": [props.creator, str(props.created)],  # openpyxl stamps "modified"
        "sheets": [],
    }
    for ws in wb.worksheets:
        cells = []
        for row in ws.iter_rows():
            for c in row:
                fill = _color(c.fill.fgColor) if c.fill.fill_type else None
                font = [bool(c.font.b), bool(c.font.i), _color(c.font.color)]
                wrap = bool(c.alignment.wrap_text)
                vertical = c.alignment.vertical
                comment = c.comment.text if c.comment is not None else None
                styled = (fill is not None or font != [False, False, None] or wrap
                          or vertical is not None or comment is not None
                          or c.number_format != "General")
                if c.value is None and not styled:
                    continue
                cells.append([c.coordinate, c.value, c.number_format, fill, font, wrap,
                              vertical, comment])
        validations = sorted(
            [str(dv.sqref), dv.type, dv.formula1, bool(dv.allow_blank),
             bool(dv.showErrorMessage)] for dv in ws.data_validations.dataValidation)
        widths = {k: d.width for k, d in sorted(ws.column_dimensions.items())
                  if d.customWidth or d.width not in (None, 13.0)}
        out["sheets"].append({"name": ws.title, "freeze": ws.freeze_panes, "widths": widths,
                              "validations": validations, "cells": cells})
    return out
