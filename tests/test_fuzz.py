"""Fuzz: the example workbook mutated cell by cell must never crash the checker.

Each case changes ONE cell of the example (a value, a unit or a name) to a hostile value: a
wrong type, a magnitude from 1e-300 to 1e300, a unit pint misreads, a string with markup. The
check must then end with exit code 0, 1 or 2 only, print no traceback and no "internal error",
write no NaN or inf into the JSON, write nothing on exit 2 and leave the input unchanged.

The cases are a seeded sample (deterministic); ``CHECKER_FUZZ_CASES=600 pytest
tests/test_fuzz.py`` runs a longer campaign.
"""

from __future__ import annotations

import hashlib
import json
import os
import random
from pathlib import Path

import openpyxl
import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.workbook.example import example_content, write_workbook
from checker.workbook.schema import SHEETS

N_CASES = int(os.environ.get("CHECKER_FUZZ_CASES", "40"))
SEED = int(os.environ.get("CHECKER_FUZZ_SEED", "20261123"))

VALUES = [
    # types
    "abc", True, "", " ", "1,5", "1e", "=A1+1", "#N/A", "NaN", "inf", "-inf",
    # magnitudes
    1e-300, -1e-300, 1e300, -1e300, 0, -1, 1e-12, 1e12, 3.0e38, 123456789012, 0.5,
    # markup and special text
    "$x^2$", "M$1$", "<b>bold</b>", "{{ engine }}", "{% raw %}", "\\", "&amp;", "_^~%#",
    "1-3-4-2", "1-1-1-1", "α β γ", "x" * 300,
]
UNITS = ["in", "Nm", "kNm", "bar(g)", "barg", "1/min", "rpm", "Hz", "°C", "degF", "K", "%",
         "furlong", "m/s", "", "-", "mm^2", "N", "kg", "$m$", "um", "1e300 m", "deg", "rad"]


def _targets(path: Path) -> list[tuple[str, str, str]]:
    """(sheet, cell, role) of every input cell of the example: value, unit or name cells."""
    wb = openpyxl.load_workbook(path)
    out = []
    for name, spec in SHEETS.items():
        if name not in wb.sheetnames or spec.shape == "notes":
            continue
        ws = wb[name]
        if spec.shape == "parameters":
            for r in range(2, ws.max_row + 1):
                if ws.cell(r, 1).value is None:
                    continue
                out.append((name, f"B{r}", "value"))
                out.append((name, f"C{r}", "unit"))
        else:
            for c in range(1, ws.max_column + 1):
                if ws.cell(1, c).value is None:
                    continue
                col = ws.cell(1, c).column_letter
                out.append((name, f"{col}2", "unit"))
                for r in range(3, ws.max_row + 1):
                    if ws.cell(r, c).value is not None:
                        out.append((name, f"{col}{r}", "value"))
    return out


def _cases() -> list[tuple[str, str, object]]:
    base = Path(os.environ.get("TMPDIR", "/tmp")) / f"checker-fuzz-base-{os.getpid()}.xlsx"
    write_workbook(base, example_content())
    targets = _targets(base)
    base.unlink()
    rng = random.Random(SEED)
    cases = []
    for _ in range(N_CASES):
        sheet, cell, role = rng.choice(targets)
        pool = UNITS if role == "unit" else VALUES
        cases.append((sheet, cell, rng.choice(pool)))
    return cases


CASES = _cases()


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("fuzz") / "engine.xlsx"
    write_workbook(p, example_content())
    return p


def _no_nonfinite(text: str) -> None:
    def bad(const: str):
        raise AssertionError(f"non-finite number {const} in the JSON output")

    json.loads(text, parse_constant=bad)


@pytest.mark.parametrize("sheet, cell, value", CASES,
                         ids=[f"{s}!{c}={str(v)[:20]!r}" for s, c, v in CASES])
def test_mutated_cell_never_crashes(base, tmp_path, sheet, cell, value):
    wb = openpyxl.load_workbook(base)
    wb[sheet][cell].value = value
    p = tmp_path / "mutated.xlsx"
    wb.save(p)
    before = hashlib.sha256(p.read_bytes()).hexdigest()
    out = tmp_path / "results.json"
    r = CliRunner().invoke(main, ["check", str(p), "--format", "json", "--no-timings",
                                  "-o", str(out)])
    text = r.output
    assert r.exit_code in (0, 1, 2), text
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    assert "Traceback" not in text and "internal error" not in text, text
    if r.exit_code == 2:
        assert not out.exists(), "an output file was written on exit 2"
        assert "error" in text
    else:
        _no_nonfinite(out.read_text(encoding="utf-8"))
    assert hashlib.sha256(p.read_bytes()).hexdigest() == before, "the input was modified"
    assert sorted(x.name for x in tmp_path.iterdir()) == sorted(
        ["mutated.xlsx"] + (["results.json"] if r.exit_code != 2 else []))
