"""The calibrated copy of the workbook: the fitted parameters written into their cells.

Each fitted parameter is a factor on the value the workbook gives (at the measured
temperature); the copy scales every cell that carries the parameter by that factor (so the
cell keeps its unit, and a rubber table keeps its shape against temperature), replaces the
row's note with a ``FITTED`` note naming the measurement file, the previous value and the
confidence, and adds a line to sheet Notes. The input workbook is never modified: the copy
is returned as bytes for the command to write.
"""

from __future__ import annotations

import io
from pathlib import Path

from .fit import FitResult

_SKIP = ("excitation_scale",)  # no workbook cell


def _split(addr: str) -> tuple[str, str]:
    sheet, cell = addr.split("!", 1)
    return sheet, cell


def _note_column(ws) -> int | None:
    for c in ws[1]:
        if str(c.value or "").strip().lower() == "note":
            return c.column
    return None


def calibrated_workbook(workbook: str | Path, fit: FitResult, measurement: str,
                        where: str) -> tuple[bytes, list[dict]]:
    """The calibrated copy (xlsx bytes) and the cells written [{cell, old, new, parameter}].

    ``measurement``: the measurement file's name; ``where``: the station, load and temperature
    in words (for the notes).
    """
    import openpyxl
    from openpyxl.comments import Comment

    src = Path(workbook)
    wb = openpyxl.load_workbook(src)
    values = openpyxl.load_workbook(src, data_only=True)
    written: list[dict] = []
    for p in fit.parameters:
        if p.key in _SKIP or not p.cells or p.factor == 1.0:
            continue
        ci = (f"95 % interval x{p.low95 / p.start:.3g} to x{p.high95 / p.start:.3g}"
              if p.determined else "not determined by the measurement")
        for addr in p.cells:
            sheet, cell = _split(addr)
            old = values[sheet][cell].value
            try:
                old_f = float(old)
            except (TypeError, ValueError):
                continue
            new = old_f * p.factor
            ws = wb[sheet]
            ws[cell].value = float(f"{new:.6g}")
            text = (f"FITTED by checker correlate to {measurement} ({where}): {p.label} x"
                    f"{p.factor:.4g} ({ci}); previous value {old_f:g}")
            ws[cell].comment = Comment(text, "checker correlate")
            nc = _note_column(ws)
            if nc is not None:
                row = ws[cell].row
                prev = str(ws.cell(row=row, column=nc).value or "").strip()
                # the previous note kept for its source, no longer an ASSUMPTION
                prev = prev.replace("ASSUMPTION", "assumed before").replace(
                    "assumption", "assumed before")
                ws.cell(row=row, column=nc).value = text + (f"; was: {prev}" if prev else "")
            written.append({"cell": addr, "parameter": p.key, "old": old_f,
                            "new": float(f"{new:.6g}")})
    if "Notes" in wb.sheetnames:
        ws = wb["Notes"]
        ws.cell(row=ws.max_row + 1, column=1).value = (
            f"Calibrated by checker correlate to the measurement {measurement} ({where}):"
            f" {', '.join(f'{p.label} x{p.factor:.4g}' for p in fit.parameters)}; residual"
            f" rms {fit.rms_before * 100:.1f} % before, {fit.rms_after * 100:.1f} % after.")
    buf = io.BytesIO()
    wb.save(buf)
    return buf.getvalue(), written
