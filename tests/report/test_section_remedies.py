"""The report's "what it takes to pass" and "verdict at the tolerance corners" for a design
review: identical answers share a row, the levers without a value are one line per result,
the corners table lists only the results the tolerances move (with the count of the others),
page 1 names the smallest change with its side effects, and every number of the JSON stays in
the results workbook."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from checker.description.levers import load_levers
from checker.evaluation.ruletable import RuleResult
from checker.remedies.corners import CornerResult
from checker.remedies.solve import Remedy, ResultRemedies
from checker.report import section_remedies as sr
from checker.report import summary

LEVERS = {lv.id: lv for lv in load_levers(None)}


def _fx(*pairs, to="pass", frm="fail"):
    return [{"rule": r, "item": i, "from": frm, "to": to, "value": 1.25, "unit": "um"}
            for r, i in pairs]


def _big_end(item: str) -> ResultRemedies:
    """BRG-003 on one of four identical big ends (the I4 example's numbers): the oil supply
    temperature (one input for every bearing) passes it at 73.35 °C and with it every other
    bearing; its own clearance and width have no value within their bounds."""
    others = [("BRG-003", f"BE{k}") for k in range(1, 5) if f"BE{k}" != item]
    return ResultRemedies("BRG-003", item, "fail", -0.6931, [
        Remedy(LEVERS["oil-supply-temperature"], "Oil!B4", 130.0, 73.35, 4e-4, True,
               side_effects=_fx(("BRG-003", "M1"), ("BRG-003", "M2"), ("BRG-003", "M3"),
                                ("BRG-003", "M4"), ("BRG-003", "M5"), *others,
                                ("BRG-004", "M3"))),
        Remedy(LEVERS["bearing-clearance"], "Bearings!F8", 24.0,
               reason="no value within the bounds (48 µm)", best_margin=-0.7211),
        Remedy(LEVERS["bearing-width"], "Bearings!G8", 17.8,
               reason="no value within the bounds (24.92 mm)", best_margin=-0.5766),
    ])


def _main(item: str, twin: str) -> ResultRemedies:
    """BRG-003 on main bearing M1 or M5 (the same answers): its own clearance (a lever of
    its own row) passes it alone; the oil temperature passes its twin, M3 and BRG-004 M3."""
    return ResultRemedies("BRG-003", item, "fail", -0.16, [
        Remedy(LEVERS["bearing-clearance"], "Bearings!F3", 22.0, 14.77, 2e-4, True),
        Remedy(LEVERS["oil-supply-temperature"], "Oil!B4", 130.0, 117.5, 3e-4, True,
               side_effects=_fx(("BRG-003", twin), ("BRG-003", "M3"), ("BRG-004", "M3"))),
    ])


CONFLICT = ("Conflict: no tightening torque passes JNT-001, JNT-002 together (JNT-001 needs"
            " ≤ 377.3 N·m; JNT-002 needs ≤ 360.7 N·m). Levers that can: JNT-002: Bolt size"
            " (ISO metric fine thread) M18x1.5.")


def _remedies() -> dict:
    nose = ResultRemedies("JNT-002", "crank nose", "fail", -0.1091, [
        Remedy(LEVERS["joint-tightening-torque"], "Joints!I3", 400.0, 360.655, 1.09e-7, True,
               side_effects=_fx(("JNT-001", "crank nose"))),
        Remedy(LEVERS["joint-bolt-size"], "Joints!D3, Joints!E3",
               {"nominal diameter": 16.0, "thread pitch": 1.5},
               {"nominal diameter": 18, "thread pitch": 1.5}, 0.0141, True),
    ], [CONFLICT])
    fly = ResultRemedies("FLY-001", "all", "fail", -0.4543, [
        Remedy(LEVERS["flywheel-inertia"], "TVModel!C9", 0.1747, 0.2679, 5e-4, True,
               side_effects=_fx(("FAT-001", "main 5 oil hole"), to="fail", frm="pass"))])
    near = ResultRemedies("FAT-002", "main 4 fillet", "pass", 0.0528, [
        Remedy(LEVERS["main-fillet-radius"], "Fatigue!B20", 1.6,
               reason="no value within the bounds (3.2 mm)", best_margin=0.109)])
    none = ResultRemedies("TV-003", "all", "fail", -0.99, [])
    results = ([_main("M1", "M5"), _main("M5", "M1")]
               + [_big_end(f"BE{k}") for k in range(1, 5)] + [nose, fly, near, none])
    return {"results": results, "levers": list(LEVERS.values()), "evaluations": 181}


def _tolerance(name, sheet, labels, low, nominal, high, unit):
    return SimpleNamespace(name=name, binding=SimpleNamespace(sheet=sheet, labels=labels),
                           low=low, nominal=nominal, high=high, unit=unit,
                           source="ASSUMPTION (test)", where="Tolerances!A3")


TOLS = [_tolerance("Bearings radial clearance (type = big end)", "Bearings",
                   ("Bearings!F8", "Bearings!F9", "Bearings!F10", "Bearings!F11"),
                   19.0, 24.0, 29.0, "um"),
        _tolerance("Oil Oil supply temperature", "Oil", ("Oil!B4",), 120.0, 130.0, 140.0,
                   "°C"),
        _tolerance("PeakPressure peak pressure (all)", "PeakPressure",
                   ("PeakPressure!C3", "PeakPressure!C4"), 51.8, 53.4, 55.0, "bar")]
BE_CORNER = ["Bearings radial clearance (type = big end) max (29 µm)",
             "Oil Oil supply temperature max (140 °C)",
             "PeakPressure peak pressure (all) max (55 bar)"]
BE_TOLS = [t.name for t in TOLS]


def _corner(rule, item, ns, nv, nm, ws, wv, wm, corner=BE_CORNER, tols=BE_TOLS, unit="um"):
    return CornerResult(rule, item, ns, nv, nm, wv, wm, ws, list(corner), list(tols),
                        "all 8 corners of 3 tolerances", unit=unit)


def _corners() -> dict:
    res = [_corner("BRG-003", f"BE{k}", "fail", 0.3683, -0.6931, "fail", 0.2635, -0.7804)
           for k in range(1, 5)]
    res += [_corner("BRG-004", "M2", "pass", 1.479, 0.232, "fail", 1.174, -0.021),
            # passes with ample margin at every corner: not listed
            _corner("FAT-001", "pin 1 fillet", "pass", 2.073, 0.382, "pass", 2.012, 0.342,
                    BE_CORNER[2:], BE_TOLS[2:], ""),
            # fails, the tolerances move it by 0.1 % of the limit: not listed
            _corner("FAT-002", "pin 3 oil hole", "fail", 1.124, -0.0226, "fail", 1.123,
                    -0.0234, BE_CORNER[2:], BE_TOLS[2:], ""),
            # no tolerance affects it
            CornerResult("BAL-001", "order 1", "pass", 0.0, 1.0, 0.0, 1.0, "pass",
                         ["unaffected by the tolerances"], [], "-", unit="N")]
    return {"results": res, "tolerances": TOLS, "evaluations": 55}


def _res(remedies=True, corners=True, results=()):
    rules = [SimpleNamespace(id=i, name=n) for i, n in (
        ("BRG-003", "Minimum oil film thickness, full load"), ("JNT-002", "Contact stress"
                                                               " under the bolt head"),
        ("FLY-001", "Cyclic irregularity"), ("TV-003", "Crank-nose elastic amplitude"),
        ("FAT-002", "IACS M53 acceptability factor"))]
    return SimpleNamespace(table=SimpleNamespace(rules=rules), fail_on="error",
                           remedies=_remedies() if remedies else None,
                           corners=_corners() if corners else None, results=list(results))


def _table(sec, caption_start):
    return next(b for b in sec["blocks"] if b["type"] == "table"
                and b.get("caption", "").startswith(caption_start))


def _text(cell) -> str:
    return cell["text"] if isinstance(cell, dict) else cell


def test_items_and_results_in_short_words():
    assert sr.items_text(["BE1", "BE2", "BE3", "BE4"]) == "BE1–BE4"
    assert sr.items_text(["M1", "M2"]) == "M1, M2"
    assert sr.items_text(["M1", "M3", "M4", "M5"]) == "M1, M3–M5"
    assert sr.items_text(["main 3 fillet", "main 4 fillet", "main 5 fillet",
                          "pin 1 oil hole"]) == "main 3–5 fillet, pin 1 oil hole"
    assert sr.results_text([("BRG-003", "M1"), ("BRG-004", "M3"), ("BRG-003", "M2"),
                            ("BRG-003", "M3")]) == "BRG-003 M1–M3; BRG-004 M3"


def test_side_effects_by_status_breaking_ones_first_own_items_left_out():
    fx = (_fx(("BRG-003", "M1"), ("BRG-003", "BE2"), ("BRG-004", "M3"))
          + _fx(("FAT-001", "main 5 oil hole"), to="fail", frm="pass"))
    assert sr.effects_text(fx, {("BRG-003", "BE2")}) == (
        "→ fail: FAT-001 main 5 oil hole. → pass: BRG-003 M1; BRG-004 M3")
    assert sr.effects_text([]) == ""


def test_corner_in_short_words():
    assert sr.corner_text(BE_CORNER, TOLS) == (
        "radial clearance (big end) max, oil supply temperature max, peak pressure max")
    # a point inside the box keeps its value
    assert sr.corner_text(["Oil Oil supply temperature 0.38 (127.6 °C)"], TOLS) == (
        "oil supply temperature 0.38 (127.6 °C)")


def test_identical_answers_share_a_row_and_levers_without_value_are_one_line():
    sec = sr.remedies_section(_res())
    t = _table(sec, "Failing results")
    rows = t["rows"]
    first = [r[0] for r in rows if not isinstance(r[0], dict) and r[0]]
    # M1 and M5: the same values by their own clearance and by the oil temperature;
    # BE1..BE4 one row: every big end passes at the same oil temperature
    assert first == ["M1, M5", "BE1–BE4", "crank nose", "engine", "engine"]  # issue 37
    be = rows.index(next(r for r in rows if r[0] == "BE1–BE4"))
    assert rows[be][1:5] == ["Oil supply temperature", "130 °C", "73.35 °C", "−56.65 °C"]
    # the other results that change: not the row's own big ends
    assert rows[be][5] == "→ pass: BRG-003 M1–M5; BRG-004 M3"
    # the two levers with no value within their bounds: one line, bounds given
    line = _text(rows[be + 1][1])
    assert rows[be + 1][0] == "" and line == (
        "No value within the bounds: Radial clearance of that bearing (48 µm),"
        " Effective length of that bearing (24.92 mm).")
    # smallest relative change first (the one page 1 names): the oil temperature −12.5 K
    # (3.1 % of 403 K) before the clearance −32.9 %; units and percent given
    m = rows.index(next(r for r in rows if r[0] == "M1, M5"))
    assert rows[m][1:] == ["Oil supply temperature", "130 °C", "117.5 °C", "−12.5 °C",
                           "→ pass: BRG-003 M3; BRG-004 M3"]
    assert rows[m + 1][1:] == ["Radial clearance of that bearing", "22 µm", "14.77 µm",
                               "−7.23 µm (−32.9 %)", "none"]
    # a rule title row names the rule once
    assert {"text": "BRG-003 Minimum oil film thickness, full load", "span": 6} in [
        r[0] for r in rows]
    # the breaking side effect of the flywheel inertia, and a rule without levers
    fly = next(r for r in rows if len(r) > 1 and r[1] == "Flywheel inertia")
    assert fly[3] == "0.2679 kg·m²" and fly[5] == "→ fail: FAT-001 main 5 oil hole"
    assert any(_text(c) == "No design lever is listed for this rule." for r in rows
               for c in r)
    # the conflict is stated in full
    lst = next(b for b in sec["blocks"] if b["type"] == "list")
    assert lst["items"] == [CONFLICT]


def test_near_passes_without_value_collapse_into_one_sentence():
    sec = sr.remedies_section(_res())
    assert not any(b.get("caption", "").startswith("Passing results") for b in sec["blocks"])
    text = [b["text"] for b in sec["blocks"] if b["type"] == "text"]
    assert any(t.endswith("makes them fail: FAT-002 main 4 fillet.") for t in text)


def test_every_remedy_number_is_in_the_results_workbook_sheet():
    sec = sr.remedies_section(_res())
    sheet = next(b for b in sec["blocks"] if b.get("sheet") == sr.REMEDIES_SHEET)
    assert sheet["detail"]
    cols = sheet["columns"]
    rows = {(r[0], r[1], r[3]): dict(zip(cols, r)) for r in sheet["rows"]}
    # one row per result and lever, the merged ones too
    assert len(sheet["rows"]) == sum(max(1, len(x.remedies))
                                     for x in _remedies()["results"])
    be3 = rows[("BRG-003", "BE3", "Radial clearance of that bearing")]
    assert be3["best margin within the bounds"] == pytest.approx(-0.7211)
    assert be3["why none"] == "no value within the bounds (48 µm)"
    t = rows[("JNT-002", "crank nose", "Tightening torque")]
    assert t["today"] == 400.0 and t["margin zero at"] == 360.655
    assert t["change"] == pytest.approx(-39.345)
    assert t["change %"] == pytest.approx(-9.836, abs=1e-3)
    assert t["margin at the value"] == pytest.approx(1.09e-7)
    assert t["side effects"] == "JNT-001 crank nose fail → pass (1.25 um)"
    assert t["conflicts"] == CONFLICT
    assert rows[("JNT-002", "crank nose", "Bolt size (ISO metric fine thread)")][
        "margin zero at"] == "M18x1.5"


def test_corners_table_lists_what_the_tolerances_move_and_counts_the_rest():
    sec = sr.remedies_section(_res())
    t = _table(sec, "Results whose status or margin")
    assert t["rows"] == [
        ["BRG-003 BE1–BE4", "0.3683 µm fail", "0.2635 µm fail",
         "radial clearance (big end) max, oil supply temperature max, peak pressure max"],
        ["BRG-004 M2", "1.479 µm pass", "1.174 µm fail",
         "radial clearance (big end) max, oil supply temperature max, peak pressure max"]]
    assert t["row_css"] == ["fail", "fail changed"]
    text = " ".join(b["text"] for b in sec["blocks"] if b["type"] == "text")
    assert ("Not listed: 2 results whose status the tolerances keep and whose margin stays"
            " above 10 % or moves by less than 0.5 % of the limit, and 1 result no"
            " tolerance affects.") in text
    assert "Verdict at the worst corners: FAIL; 55 evaluations." in text
    tol = _table(sec, "Tolerances")
    assert tol["rows"][0][:5] == ["radial clearance (big end)", "Bearings!F8..F11", "19 µm",
                                  "24 µm", "29 µm"]
    # every result, the unlisted ones too, with value, margin and corner in the workbook
    sheet = next(b for b in sec["blocks"] if b.get("sheet") == sr.CORNERS_SHEET)
    assert len(sheet["rows"]) == len(_corners()["results"])
    fat = next(dict(zip(sheet["columns"], r)) for r in sheet["rows"] if r[0] == "FAT-002")
    assert fat["worst-corner margin"] == pytest.approx(-0.0234)
    assert fat["worst corner"] == "PeakPressure peak pressure (all) max (55 bar)"


def _rr(item, status="fail", value=0.3683):
    return RuleResult("BRG-003", "Minimum oil film thickness, full load", item, status,
                      "error", value, "um", "≥ 1.2 µm", [1.2], -0.6931, "full load, 1000 rpm",
                      "", "", findings=["Film thinner than three times the roughness."],
                      check=">=")


def test_page_one_line_merges_identical_big_ends_and_names_the_smallest_change():
    results = [_rr(f"BE{k}") for k in range(1, 5)]
    res = _res(results=results)
    rows = [r for r in summary.rows(res) if r.kind == "fail"]
    assert len(rows) == 1 and rows[0].items == ["BE1", "BE2", "BE3", "BE4"]
    assert rows[0].note == (
        "Film thinner than three times the roughness. To pass: Oil supply temperature"
        " 130 °C → 73.35 °C (−56.65 °C); side effects → pass: BRG-003 M1–M5; BRG-004 M3."
        " At the tolerance corners: 0.2635 µm fail at radial clearance (big end) max, oil"
        " supply temperature max, peak pressure max.")
    # without remedies and corners the row is the plain report's
    plain = summary.rows(_res(remedies=False, corners=False, results=results))
    assert plain[0].note == "Film thinner than three times the roughness."


def test_page_one_line_states_the_conflict():
    r = RuleResult("JNT-002", "Contact stress under the bolt head", "crank nose", "fail",
                   "error", 554.5, "MPa", "≤ 500 MPa", [500.0], -0.1091, "-", "", "",
                   check="<=")
    note = summary.rows(_res(corners=False, results=[r]))[0].note
    assert note == ("To pass: Tightening torque 400 N·m → 360.7 N·m (−39.35 N·m, −9.8 %);"
                    " side effects → pass: JNT-001 crank nose. Conflict: no tightening"
                    " torque passes JNT-001, JNT-002 together: see 'What it takes to pass'.")


def test_report_html_of_a_real_check(tmp_path):
    # the crank-nose joint of the example: the section reaches the HTML, a lever without a
    # value spans the row, page 1 says what it takes
    from checker import api
    from checker.remedies import attach
    from checker.report.render import render_html
    from tests.helpers import example_path

    res = api.check(example_path(tmp_path), select=["JNT-002"])
    attach(res, remedies=True, cache={})
    html = render_html(res)
    assert "What it takes to pass; tolerance corners" in html
    assert "To pass: Tightening torque 400 N·m → 360.7 N·m" in html
    assert '<td colspan="6">JNT-002 Contact stress under the bolt head</td>' in html
    assert 'class="data remedies"' in html
