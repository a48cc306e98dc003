"""Layouts of ``checker new`` checked in memory.

The first layout's workbook is written and read once; every later layout (a sizing pass, a
move of the loop) is the cell changes that turn it into the new one
(:meth:`checker.workbook.loader.RawWorkbook.with_values`), checked by the evaluator of the
remedies (:class:`checker.remedies.variants.Evaluator`) with its calculation cache: a
flywheel change recomputes only what the flywheel feeds.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..workbook.schema import SHEETS


def cells_of(cont: dict[str, Any]) -> dict[tuple[str, int, int], Any]:
    """The cells of a workbook's content as :func:`checker.workbook.example.write_workbook`
    writes them (parameters: name, value and unit in columns A-C from row 2; tables: from row
    3), the notes left out (they do not enter the check)."""
    out: dict[tuple[str, int, int], Any] = {}
    for name, body in cont.items():
        if name == "Notes" or name not in SHEETS:
            continue
        if isinstance(body, list):
            for i, row in enumerate(body, start=2):
                for j in (1, 2, 3):
                    out[(name, i, j)] = row[j - 1]
            continue
        cols, rows = body
        for i, row in enumerate(rows, start=3):
            for j, ((h, _u), v) in enumerate(zip(cols, row), start=1):
                if h != "note":
                    out[(name, i, j)] = v
    return out


@dataclass
class Bench:
    """The first layout's workbook, read once, and the evaluator that checks the later
    layouts as cell changes of it (in memory)."""

    first: dict[str, Any]
    table: Any = None
    ev: Any = None
    cells: dict = field(default_factory=dict)
    checks: int = 0

    def __post_init__(self) -> None:
        from ..evaluation.ruletable import load_rules
        from ..remedies.variants import Evaluator
        from ..workbook.example import write_workbook
        from ..workbook.loader import read_raw_workbook

        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "layout.xlsx"
            write_workbook(path, self.first)
            base = read_raw_workbook(path)
        self.table = self.table or load_rules(None)
        self.ev = Evaluator(base, self.table, cache={})
        self.cells = cells_of(self.first)

    def changes(self, cont: dict[str, Any]) -> dict[tuple[str, int, int], Any]:
        """The cell changes that turn the first layout into ``cont`` (rows it adds, e.g. the
        project limits the tuning sets, written; rows it lost emptied)."""
        now = cells_of(cont)
        out = {k: v for k, v in now.items() if self.cells.get(k) != v}
        out.update({k: None for k in self.cells if k not in now})  # rows the layout lost
        return out

    def check(self, cont: dict[str, Any], select: list[str] | None = None) -> Any:
        """The check of the layout ``cont`` (a :class:`checker.api.CheckResult`), or the
        :class:`checker.errors.InputErrors` of one that is not a valid workbook."""
        self.checks += 1
        return self.ev.evaluate_variants([self.changes(cont)], select=select)[0]

    @property
    def evaluations(self) -> int:
        return self.ev.evaluations
