"""Write ``checker/workbook/unit_table.py``: pint's own conversion numbers for the units a check of
the
template workbooks uses, so that such a check does not import pint (about 0.2 s of CPU).

    python scripts/make_unit_table.py

Two tables, both computed by pint through the code paths of :mod:`checker.workbook.units` with the
table switched off (tests/test_unit_table.py compares every entry with pint again):

* ``TO_SI[(unit, kind)] = (scale, offset)``: :func:`checker.workbook.units.to_si` of a value cell
  with that unit cell (not percent-formatted); the units of the three template workbooks
  (I4, I6, V8), of the schema's ranges, the kinds' example units and the usual spellings
  (:data:`checker.workbook.units._COMMON_UNITS`, the speed and temperature spellings) that pint
  accepts for the kind.
* ``CONVERT[(src, dst)] = (a, b)``: :func:`checker.workbook.units.convert_affine` (rules and display
  conversions, ``x[dst] = a x[src] + b``): every shipped rule's unit against its quantity's
  SI unit, the schema's range units and the usual spellings against the kinds' SI units,
  every quantity's display unit and the conversions of the templates' report sections and
  results workbooks (so that the report's drawing processes do not import pint either).

Run it again after adding a rule or a template unit (the test names a missing unit).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import checker.workbook.units as U  # noqa: E402


class _Empty:
    TO_SI: dict = {}
    CONVERT: dict = {}


def _spellings() -> list[str]:
    extra = ["%", "percent", "-", "°C", "degC", "C", "K", "°F", "degF", "delta_degC",
             "mm^2", "mm2", "m^2", "cm^2", "kg mm^2", "kg m^2", "kg*m^2", "g mm^2",
             "N m s/rad", "N m/rad", "kN m/rad", "N/mm^2", "N/m", "N s/m", "N/m^2",
             "mPa s", "Pa s", "cP", "mm^2/s", "cSt", "kg/m^3", "g/cm^3", "W/cm^3",
             "W/cm**3", "l/min", "L/min", "m^3/s", "kW", "W", "bar(g)", "bar(a)", "barg",
             "bara", "psi", "psig", "psia", "kPa(g)", "hPa", "mbar", "atm", "m", "um",
             "µm", "mm", "cm", "in", "deg", "°", "rad", "rpm", "1/min", "min^-1", "Hz",
             "rev/s", "rad/s", "N", "kN", "MN", "N m", "Nm", "kN m", "kNm", "N*m", "kg",
             "g", "t", "MPa", "GPa", "kPa", "Pa", "bar", "s", "ms", "J", "kJ"]
    return list(dict.fromkeys([*U._COMMON_UNITS, *U._SPEED_ALIASES, *extra,
                               *(k.example for k in U.KINDS.values())]))


def collect() -> tuple[dict, dict]:
    from checker import api
    from checker.evaluation.ruletable import load_rules
    from checker.workbook.example import example_content, write_workbook
    from checker.workbook.example_i6 import i6_content
    from checker.workbook.example_v8 import v8_content
    from checker.workbook.loader import read_workbook
    from checker.workbook.schema import SHEETS

    U._table = lambda: _Empty  # noqa: SLF001 - pint only while generating
    U._affine.cache_clear()
    U._scale.cache_clear()
    U.convert_affine.cache_clear()
    to_si_keys: set[tuple[str, str]] = set()
    conv_keys: set[tuple[str, str]] = set()
    affine, convert = U._affine, U.convert_affine

    def rec_affine(unit, kind, pf):
        if not pf:
            to_si_keys.add((unit, kind))
        return affine(unit, kind, pf)

    def rec_convert(src, dst):
        conv_keys.add((src, dst))
        return convert(src, dst)

    U._affine = rec_affine
    U.convert_affine = rec_convert
    import checker.evaluation.ruletable as rt

    rt.convert_affine = rec_convert
    from_si = U.from_si

    def rec_from_si(value, si_unit, display):
        conv_keys.add((si_unit or "", display.replace("%", "percent")))
        return from_si(value, si_unit, display)

    U.from_si = rec_from_si  # the report's sections and results workbook import it late
    from checker.evaluation.graph import QUANTITIES
    from checker.report import results_book
    from checker.report.sections import SECTIONS, modules_with_sections

    tmp = Path(tempfile.mkdtemp(prefix="unit-table-"))
    for name, content in (("i4", example_content()), ("i6", i6_content()),
                          ("i6-ring", i6_content(damper_ring=True)), ("v8", v8_content())):
        p = tmp / f"{name}.xlsx"
        write_workbook(p, content)
        read_workbook(p, raise_errors=False)
        res = api.check(str(p))
        # the report's display conversions (sections and results workbook), which the drawing
        # and workbook processes would otherwise load pint for (about 0.35 s each)
        results_book.build(res, [])
        for m in modules_with_sections(res):
            SECTIONS[m](res)
    U.from_si = from_si
    for q in QUANTITIES.values():
        if q.display_unit and q.unit is not None:
            conv_keys.add((q.unit, q.display_unit.replace("%", "percent")))
    load_rules(None)
    words = _spellings()
    for sheet in SHEETS.values():
        for f in sheet.fields:
            if f.kind not in U.KINDS:
                continue
            for span in (f.valid, f.usual):
                if span is not None:
                    to_si_keys.add((span.unit.strip(), f.kind))
                    conv_keys.add((U.KINDS[f.kind].si, span.unit.replace("%", "percent")))
    for kind, k in U.KINDS.items():
        for w in words:
            to_si_keys.add((w, kind))
            conv_keys.add((k.si, w.replace("%", "percent")))
    U._affine, U.convert_affine, rt.convert_affine = affine, convert, convert
    to_si = {}
    for unit, kind in sorted(to_si_keys):
        got = affine(unit, kind, False)
        if not isinstance(got, str):
            to_si[(unit, kind)] = got
    conv = {}
    for src, dst in sorted(conv_keys):
        try:
            conv[(src, dst)] = convert(src, dst)
        except U.UnitProblem:
            continue
    return to_si, conv


def main() -> None:
    to_si, conv = collect()
    lines = ['"""pint\'s conversion numbers for the units of the template workbooks, the'
             " schema's ranges,",
             "the shipped rules and the usual spellings: :mod:`checker.workbook.units` takes them"
             " from here",
             "without importing pint. Generated by ``scripts/make_unit_table.py`` (do not edit);",
             'tests/test_unit_table.py checks every entry against pint."""', "",
             "TO_SI: dict[tuple[str, str], tuple[float, float]] = {"]
    lines += [f"    {k!r}: ({a!r}, {b!r})," for k, (a, b) in to_si.items()]
    lines += ["}", '"""``(unit cell, kind) -> (scale, offset)`` of'
              ' :func:`checker.workbook.units.to_si`."""', "",
              "CONVERT: dict[tuple[str, str], tuple[float, float]] = {"]
    lines += [f"    {k!r}: ({a!r}, {b!r})," for k, (a, b) in conv.items()]
    lines += ["}", '"""``(src, dst) -> (a, b)`` of'
              ' :func:`checker.workbook.units.convert_affine`."""', ""]
    out = ROOT / "checker" / "workbook" / "unit_table.py"
    out.write_text("\n".join(lines), encoding="utf-8")
    print(f"{out}: {len(to_si)} to-SI entries, {len(conv)} conversions")


if __name__ == "__main__":
    main()
