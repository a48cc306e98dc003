"""Variants of a template workbook as a user makes them (openpyxl, one cell changed): a main
bearing clearance, the oil supply temperature and a bolt tightening torque."""

from __future__ import annotations

from pathlib import Path

import openpyxl

from tests.helpers import column, param_row


def _edit(src: Path, dst: Path, edit) -> Path:
    wb = openpyxl.load_workbook(src)
    edit(wb)
    wb.save(dst)
    return dst


def clearance(src: Path, dst: Path, add_mm: float = 0.008) -> Path:
    """The middle main bearing's radial clearance opened by ``add_mm`` (22 -> 30 um on the I4)."""
    def edit(wb):
        ws = wb["Bearings"]
        t, c = column(ws, "type"), column(ws, "radial clearance")
        mains = [r for r in range(3, ws.max_row + 1) if ws.cell(r, t).value == "main"]
        r = mains[len(mains) // 2]
        ws.cell(r, c).value = round(float(ws.cell(r, c).value) + add_mm, 6)
    return _edit(src, dst, edit)


def oil_temperature(src: Path, dst: Path, add_c: float = 10.0) -> Path:
    """The oil supply temperature raised by ``add_c``."""
    def edit(wb):
        ws = wb["Oil"]
        r = param_row(ws, "Oil supply temperature")
        ws.cell(r, 2).value = float(ws.cell(r, 2).value) + add_c
    return _edit(src, dst, edit)


def bolt_torque(src: Path, dst: Path, factor: float = 0.9) -> Path:
    """The first joint's tightening torque times ``factor``."""
    def edit(wb):
        ws = wb["Joints"]
        c = column(ws, "tightening torque")
        r = next(r for r in range(3, ws.max_row + 1) if ws.cell(r, c).value is not None)
        ws.cell(r, c).value = round(float(ws.cell(r, c).value) * factor, 3)
    return _edit(src, dst, edit)


VARIANTS = {"clearance": clearance, "oil-temperature": oil_temperature,
            "bolt-torque": bolt_torque}
