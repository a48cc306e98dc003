"""Every calculation module names its publications in a numpydoc ``References`` section, and
nothing in the package cites the project's internal source files instead of a publication."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CALC = ROOT / "checker" / "calc"
CALC_MODULES = sorted(p for p in CALC.glob("*.py") if p.name not in {"__init__.py", "_checks.py"})
ENTRY = re.compile(r"^\.\. \[(\d+)\] \S", re.MULTILINE)
#: the project's seed documents and research notes are not publications: cite the source instead
INTERNAL = ("seed 0", "shared/seeds", "../shared", "bearings.md", "torsion.md", "standards.md",
            "practices.md")


def _references(path: Path) -> str | None:
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8")))
    assert doc, f"{path.name} has no module docstring"
    m = re.search(r"^References\n-{10}\n(.*)", doc, flags=re.MULTILINE | re.DOTALL)
    return m.group(1) if m else None


def test_calc_modules_found():
    assert len(CALC_MODULES) >= 20


@pytest.mark.parametrize("path", CALC_MODULES, ids=lambda p: p.stem)
def test_module_docstring_has_references(path):
    refs = _references(path)
    assert refs is not None, f"{path.name}: module docstring has no 'References' section"
    numbers = [int(n) for n in ENTRY.findall(refs)]
    assert numbers, f"{path.name}: 'References' section has no '.. [n]' entry"
    assert numbers == list(range(1, len(numbers) + 1)), f"{path.name}: entries not numbered 1..n"
    for line in refs.splitlines():
        assert not line or line.startswith((".. [", "   ")), f"{path.name}: stray line {line!r}"
    assert "seed" not in refs.lower() and ".md" not in refs, f"{path.name}: internal citation"


def test_references_helper_rejects_missing_section(tmp_path):
    bare = tmp_path / "bare.py"
    bare.write_text('"""A module.\n\nNotes\n-----\nNo sources."""\n', encoding="utf-8")
    assert _references(bare) is None


def test_no_internal_source_citation_in_package():
    offenders = []
    for path in sorted((ROOT / "checker").rglob("*")):
        if path.suffix not in {".py", ".toml", ".html", ".css", ".md", ".txt", ".json"}:
            continue
        text = path.read_text(encoding="utf-8").lower()
        offenders += [f"{path.relative_to(ROOT)}: {s!r}" for s in INTERNAL if s in text]
    assert not offenders, offenders
