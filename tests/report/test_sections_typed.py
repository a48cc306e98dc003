"""Every report section renders from the typed results (issue 24): for each example engine,
each module that ran has its section built from the quantities' declared detail types, and
every quantity of the run carries the detail type its spec declares (no untyped hand-off).

Figures are drawn (the plotting code runs) but not serialised, as in test_sections_judged.
"""

from __future__ import annotations

import pytest

from checker import api
from checker.report.sections import SECTIONS, modules_with_sections
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content
from checker.workbook.example_v8 import v8_content
from tests.helpers import stub_section_images

CONTENT = {"i4": example_content, "i6": lambda: i6_content(damper_ring=True),
           "v8": v8_content}


@pytest.mark.parametrize("engine", ["i4", "i6", "v8"])
def test_every_section_renders_from_typed_details(engine, tmp_path, monkeypatch):
    path = tmp_path / f"{engine}.xlsx"
    write_workbook(path, CONTENT[engine]())
    res = api.check(path)
    for name, q in res.outcome.quantities.items():
        if q.spec.detail is not None:
            assert q.detail is None or isinstance(q.detail, q.spec.detail), name
    stub_section_images(monkeypatch)
    shown = modules_with_sections(res)
    assert set(shown) >= {"loads", "bearings", "torsion", "joints", "fatigue"}
    for m in shown:
        if m not in SECTIONS:
            continue
        sec = SECTIONS[m](res)
        assert sec["title"] and isinstance(sec["blocks"], list), m
