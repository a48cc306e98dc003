"""Test helpers: build example workbooks and edit them cell by cell with openpyxl."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import openpyxl

from checker.workbook.example import example_content, write_workbook


def example_path(tmp_path: Path, name: str = "engine.xlsx") -> Path:
    p = tmp_path / name
    write_workbook(p, example_content())
    return p


def fresh_python(code: str) -> str:
    """What ``code`` prints when run in a fresh interpreter (which modules a command imports
    can only be seen there), stripped."""
    import subprocess
    import sys

    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True).stdout.strip()


def template_paths(tmp_path: Path, damper_ring: bool = True) -> list[str]:
    """The three example engines (I4, I6 with its damper ring unless ``damper_ring`` is
    false, V8) written as workbooks in ``tmp_path``; their paths."""
    from checker.workbook.example_i6 import i6_content
    from checker.workbook.example_v8 import v8_content

    paths = []
    for name, content in (("i4", example_content()), ("i6", i6_content(damper_ring)),
                          ("v8", v8_content())):
        p = tmp_path / f"{name}.xlsx"
        write_workbook(p, content)
        paths.append(str(p))
    return paths


def analyses_run(outcome) -> list[str]:
    """The modules a check ran for its rules: the crank module runs whenever the workbook has
    sheet Crank (its quantities are always reported) and is left out here."""
    return [m for m in outcome.modules_run if m != "crank"]


def without_crank(wb) -> None:
    """The example workbook typed as before sheet Crank: Crank and CrankEnds removed, the
    journal diameters and lengths in Bearings and the web thickness in Fatigue."""
    ws = wb["Crank"]
    head = [c.value for c in ws[1]]
    vals = {h: ws.cell(3, j + 1).value for j, h in enumerate(head)}
    del wb["Crank"]
    if "CrankEnds" in wb.sheetnames:
        del wb["CrankEnds"]
    b = wb["Bearings"]
    jd, jl, ty = (column(b, n) for n in ("journal diameter", "journal length", "type"))
    for r in range(3, b.max_row + 1):
        main = b.cell(r, ty).value == "main"
        b.cell(r, jd).value = vals["main journal diameter" if main else "pin diameter"]
        b.cell(r, jl).value = vals["main journal length" if main else "pin length"]
    f = wb["Fatigue"]
    f.append(["Web full thickness", vals["web thickness"], "mm", "as sheet Crank gave it"])


def param_row(ws, label: str) -> int:
    """Row number of a parameter on a parameter sheet."""
    for row in ws.iter_rows(min_col=1, max_col=1):
        c = row[0]
        if c.value is not None and str(c.value).strip().lower() == label.lower():
            return c.row
    raise KeyError(label)


def column(ws, name: str) -> int:
    """Column number of a table column (row 1 header)."""
    for c in ws[1]:
        if c.value is not None and str(c.value).strip().lower() == name.lower():
            return c.column
    raise KeyError(name)


def table_row(ws, key_col: str, key) -> int:
    j = column(ws, key_col)
    for r in range(3, ws.max_row + 1):
        if ws.cell(r, j).value == key:
            return r
    raise KeyError(key)


def edited(tmp_path: Path, edit: Callable[[openpyxl.Workbook], None],
           name: str = "edited.xlsx") -> Path:
    """The example workbook with ``edit(workbook)`` applied, saved as a new file."""
    p = example_path(tmp_path, name)
    wb = openpyxl.load_workbook(p)
    edit(wb)
    wb.save(p)
    return p


def set_param(wb, sheet: str, label: str, value=None, unit=None) -> str:
    ws = wb[sheet]
    r = param_row(ws, label)
    if value is not None:
        ws.cell(r, 2).value = value
    if unit is not None:
        ws.cell(r, 3).value = unit
    return f"{sheet}!B{r}"


def set_cell(wb, sheet: str, key_col: str, key, col: str, value) -> str:
    ws = wb[sheet]
    r = table_row(ws, key_col, key)
    c = column(ws, col)
    ws.cell(r, c).value = value
    return f"{sheet}!{ws.cell(r, c).coordinate}"


def compliant_joints(wb) -> None:
    """Make both example joints meet every joint rule (used for the exit-0 check)."""
    # the given 'tv peak' torques at or above the torsional model's (317 and 1512 N m at 5000
    # and 6500 rpm), so that JNT-008 (given below computed) is met too
    for joint, speed, torque in (("crank nose", 5000, 320), ("flywheel", 6500, 1520)):
        set_cell(wb, "JointTorques", "joint", joint, "speed", speed)
        set_cell(wb, "JointTorques", "joint", joint, "applied torque", torque)
    # crank nose: 355 N m -> 110.9 kN, 70.6 % of proof, 492 MPa under the head;
    # diamond washer (mu 0.3, seed 000) and a larger face (54 mm): capacity 659 N m,
    # > 2.0 x 320 N m
    set_cell(wb, "Joints", "name", "crank nose", "tightening torque", 355)
    set_cell(wb, "Joints", "name", "crank nose", "friction coefficient", 0.3)
    set_cell(wb, "Joints", "name", "crank nose", "face outer diameter", 54)
    # flywheel: 8 bolts instead of 6 and the bolt head bearing face from the drawing
    set_cell(wb, "Joints", "name", "flywheel", "bolts", 8)
    # the max-power and overspeed torques now come from the TV module (about 1260 and 1800 N m,
    # JNT-006 >= 2.0, JNT-007 >= 1.7): a diamond washer at the flywheel face too (mu 0.3,
    # seed 000) gives a capacity of about 4300 N m, compliant at all three operating points
    set_cell(wb, "Joints", "name", "flywheel", "friction coefficient", 0.3)
    set_cell(wb, "Joints", "name", "flywheel", "head bearing outer diameter", 16)
    set_cell(wb, "Joints", "name", "flywheel", "head bearing inner diameter", 10.5)


def unwritable_folder() -> Path | None:
    """A folder even root cannot create files in (sysfs refuses new files), if there is one:
    tests run as root, where a chmod 0o555 folder is still writable."""
    import os
    import tempfile

    p = Path("/sys/fs")
    if not p.is_dir():
        return None
    try:
        fd, tmp = tempfile.mkstemp(dir=p)
    except OSError:
        return p
    os.close(fd)  # pragma: no cover - a writable /sys/fs
    os.unlink(tmp)
    return None


def stub_section_images(monkeypatch, modules=None) -> None:
    """Section figures drawn (the plotting code runs) but not encoded: every report section
    module's ``to_image`` returns an empty image with no drawn texts. ``modules``: the
    section modules' short names (``"loads"``...); ``None`` = every registered section."""
    import importlib

    from checker.report import plots
    from checker.report.sections import SECTIONS, load_sections

    def fake(fig):
        plots.plt.close(fig)
        png = plots.Png(b"")
        png.texts = []
        return png

    if modules is None:
        load_sections()
        names = [SECTIONS[m].__module__ for m in SECTIONS]
    else:
        names = [f"checker.report.section_{m}" for m in modules]
    for name in names:
        mod = importlib.import_module(name)
        if hasattr(mod, "to_image"):
            monkeypatch.setattr(mod, "to_image", fake)


def confirm_failing_answers(ev, out) -> list:
    """Each answer of a failing result in ``out`` (find_remedies) checked by a direct
    evaluation at its value (its lever bound to the item's cells anew, independent of the
    search's own binding): the margin lies in the accepted window. Returns the remedies
    checked."""
    from checker.description.levers import ITEM
    from checker.evaluation.ruletable import REL_TOL
    from checker.remedies.solve import TOL
    from checker.remedies.variants import bind, find

    done = []
    for rr in out:
        if rr.status == "pass":
            continue
        for rm in rr.remedies:
            if not rm.found:
                continue
            lv = rm.lever
            rows = (rr.item,) if lv.row == ITEM else ((lv.row,) if lv.row else None)
            b = bind(ev.base, lv.sheet, lv.columns, lv.unit, rows, lv.where, lv.default)
            r = find(ev.evaluate_variants([b.changes(rm.value)], select=[rr.rule])[0],
                     rr.rule, rr.item)
            assert -REL_TOL <= r.margin <= TOL, (rr.rule, rr.item, lv.id, r.margin)
            done.append(rm)
    return done


# Program internals that must never reach a page (issue 37): a Python dict or list printed
# where a sentence belongs, None/nan for a missing number, a class or object repr.
INTERNALS = (
    (r"\{\s*'\w+'\s*:", "a dict repr"),
    (r"\{\s*\"\w+\"\s*:", "a dict repr"),
    (r"\[\s*'[^'\n]*'\s*(?:,|\])", "a list repr"),
    (r"\bNone\b", "None"),
    (r"\b(?:nan|NaN|inf)\b", "a nan or inf"),
    (r"<[\w.]+ object at 0x", "an object repr"),
    (r"<(?:checker|numpy|pandas)\.", "a class name"),
    (r"<class '", "a class name"),
    (r"\b[A-Z]\w*(?:Detail|Result|Quantity|Spec|Row|Rule)\(", "a dataclass repr"),
    (r"\b\w+\(\w+=", "a dataclass repr"),
    (r"\barray\(\[|\bdtype\b|np\.float", "a numpy repr"),
    (r"Traceback \(most recent call last\)", "a traceback"),
)


def program_internals(text: str) -> list[str]:
    """What of ``text`` (one page) is a program internal (:data:`INTERNALS`), each with 40
    characters around it; empty when the page reads as written for people."""
    import re

    out = []
    flat = " ".join(text.split())
    for pattern, what in INTERNALS:
        for m in re.finditer(pattern, flat):
            out.append(f"{what}: ...{flat[max(0, m.start() - 40):m.end() + 40]}...")
    return out


def pdf_internals(pdf) -> list[str]:
    """:func:`program_internals` of every page of a PDF (bytes or path), as
    ``page N: ...``; text extracted with pypdf."""
    import io

    import pypdf

    src = io.BytesIO(pdf) if isinstance(pdf, (bytes, bytearray)) else pdf
    return [f"page {n}: {x}" for n, page in enumerate(pypdf.PdfReader(src).pages, start=1)
            for x in program_internals(page.extract_text())]
