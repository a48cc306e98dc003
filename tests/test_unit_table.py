"""The unit table (checker/workbook/unit_table.py) holds pint's own numbers: every entry equals
pint's
conversion exactly, and a check of the template workbooks needs no pint at all."""

from __future__ import annotations

import pytest

import checker.workbook.units as U
from checker.workbook import unit_table
from tests.helpers import fresh_python, template_paths


class _Empty:
    TO_SI: dict = {}
    CONVERT: dict = {}


@pytest.fixture
def pint_only(monkeypatch):
    """checker.workbook.units with the table switched off (every conversion through pint)."""
    monkeypatch.setattr(U, "_table", lambda: _Empty)
    for f in (U._affine, U._scale, U.convert_affine):
        f.cache_clear()
    yield
    for f in (U._affine, U._scale, U.convert_affine):
        f.cache_clear()


def test_to_si_entries_equal_pint(pint_only):
    assert len(unit_table.TO_SI) > 100
    for (unit, kind), (scale, offset) in unit_table.TO_SI.items():
        got = U._affine(unit, kind, False)
        assert got == (scale, offset), (unit, kind, got)
        for v in (0.0, 1.0, -3.5, 123.456):  # the values themselves, bitwise
            assert U._to_si(v, unit, kind) == v * scale + offset


def test_conversion_entries_equal_pint(pint_only):
    assert len(unit_table.CONVERT) > 50
    for (src, dst), ab in unit_table.CONVERT.items():
        assert U.convert_affine(src, dst) == ab, (src, dst)


def test_table_and_pint_give_identical_si_values(monkeypatch):
    """The same cells converted with and without the table: identical floats (and the
    spellings the table does not hold still convert through pint)."""
    cells = [(0.8, "mm", "length"), (7.5, "bar(g)", "pressure"), (90.0, "°C", "temperature"),
             (3000.0, "1/min", "speed"), (12.0, "mPa s", "viscosity"), (2.5, "kNm", "torque"),
             (45.0, "deg", "angle"), (5.0, "%", "ratio"), (0.02, "kg mm^2", "inertia"),
             (1.5, "in", "length"), (40.0, "ft*lbf", "torque")]
    with_table = [U.to_si(v, u, k) for v, u, k in cells]
    monkeypatch.setattr(U, "_table", lambda: _Empty)
    for f in (U._affine, U._scale):
        f.cache_clear()
    try:
        assert [U.to_si(v, u, k) for v, u, k in cells] == with_table
    finally:
        for f in (U._affine, U._scale):
            f.cache_clear()


def test_check_of_the_templates_imports_neither_pint_nor_openpyxl(tmp_path):
    """The template workbooks and the shipped rules use only units of the table (run
    scripts/make_unit_table.py after adding a unit), and the workbook is read without
    openpyxl: ``checker check`` pays for neither import."""
    paths = template_paths(tmp_path, damper_ring=False)
    code = ("import sys; from checker import api; from checker.outputs import formats as outputs\n"
            f"for p in {paths!r}:\n"
            "    r = api.check(p); outputs.to_json(r); outputs.to_text(r)\n"
            "print(sorted(m for m in ('pint', 'openpyxl') if m in sys.modules))")
    out = fresh_python(code)
    assert out == "[]"


def test_report_of_the_templates_converts_without_pint(tmp_path):
    """The report's display conversions (every section and the results workbook) of the
    template workbooks are in the table too: the drawing and workbook processes of
    ``checker report`` do not load pint (about 0.35 s of processor time each)."""
    paths = template_paths(tmp_path)
    code = ("import sys; from checker import api; from checker.workbook import units\n"
            "from checker.report import results_book, plots\n"
            "from checker.report.sections import SECTIONS, modules_with_sections\n"
            "plots.DEFERRED = []\n"  # figures set up, not drawn: the conversions are the test
            "for p in " + repr(paths) + ":\n"
            "    r = api.check(p); results_book.build(r, [])\n"
            "    for m in modules_with_sections(r):\n"
            "        SECTIONS[m](r)\n"
            "print('pint' in sys.modules)")
    out = fresh_python(code)
    assert out == "False"
