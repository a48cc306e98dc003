"""checker new's sizing loop (issue 47 item 2): layouts checked in memory, the sizing levers in
their order of design preference, the history in the Notes, ``--no-iterate``; briefs of an I3,
I4, I6 diesel (bore >= 120 mm), 60-degree V6 on shared pins, 270-degree twin, V8 and V12 end
to end."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import openpyxl
import pytest

from checker import api
from checker.sizing.bench import cells_of
from checker.sizing.brief import parse_brief
from checker.sizing.loop import MOVES, Move, _most_demanding, relayout
from checker.sizing.new_engine import content, layout, tune_layout
from checker.workbook.example import write_workbook

I4 = {"cylinders": 4, "layout": "inline", "bore": "86 mm", "stroke": "94.6 mm",
      "rated_power": "110 kW", "rated_speed": "6000 rpm", "max_speed": "7000 rpm",
      "peak_pressure": "85 bar", "fuel": "gasoline"}

BRIEFS = {
    "i3": 'cylinders = 3\nbore = "71.9 mm"\nstroke = "82 mm"\nrated_power = "92 kW"\n'
          'rated_speed = "6000 rpm"\npeak_pressure = "120 bar"\n',
    "i4": 'cylinders = 4\nlayout = "inline"\nbore = "86 mm"\nstroke = "94.6 mm"\n'
          'rated_power = "110 kW"\nrated_speed = "6000 rpm"\nmax_speed = "7000 rpm"\n'
          'peak_pressure = "85 bar"\nfuel = "gasoline"\n',
    "i6-diesel-123": 'cylinders = 6\nbore = "123 mm"\nstroke = "152 mm"\n'
                     'rated_power = "320 kW"\nrated_speed = "1900 rpm"\n'
                     'max_speed = "2200 rpm"\nfuel = "diesel"\n',
    "v8": 'cylinders = 8\nlayout = "V"\nbank_angle = "90 deg"\nbore = "99 mm"\n'
          'stroke = "92 mm"\nrated_power = "257 kW"\nrated_speed = "5600 rpm"\n'
          'max_speed = "6500 rpm"\n',
    "v12": 'cylinders = 12\nlayout = "V"\nbank_angle = "60 deg"\nbore = "89 mm"\n'
           'stroke = "79.5 mm"\nrated_power = "400 kW"\nrated_speed = "6500 rpm"\n'
           'max_speed = "7200 rpm"\n',
    "v8-flat": 'cylinders = 8\nlayout = "V"\nbank_angle = "90 deg"\ncrank_type = "flat-plane"\n'
               'bore = "94 mm"\nstroke = "81 mm"\nrated_power = "400 kW"\n'
               'rated_speed = "8000 rpm"\nmax_speed = "8500 rpm"\n',
    "v6-shared": 'cylinders = 6\nlayout = "V"\nbank_angle = "60 deg"\nbore = "94 mm"\n'
                 'stroke = "84 mm"\nrated_power = "150 kW"\nrated_speed = "5600 rpm"\n',
    "v6-split": 'cylinders = 6\nlayout = "V"\nbank_angle = "60 deg"\ncrank_type = "split pins"\n'
                'bore = "94 mm"\nstroke = "84 mm"\nrated_power = "150 kW"\n'
                'rated_speed = "5600 rpm"\n',
    "twin-270": 'cylinders = 2\ncrank_type = "270 deg"\nbore = "84 mm"\nstroke = "61 mm"\n'
                'rated_power = "55 kW"\nrated_speed = "8000 rpm"\nmax_speed = "8500 rpm"\n',
}


def _new(tmp_path: Path, name: str, *extra: str) -> subprocess.CompletedProcess:
    brief = tmp_path / f"{name}.toml"
    brief.write_text(BRIEFS[name])
    return subprocess.run([sys.executable, "-m", "checker", "new", str(tmp_path / f"{name}.xlsx"),
                           "--brief", str(brief), *extra], capture_output=True, text=True)


def _notes(path: Path) -> list[str]:
    ws = openpyxl.load_workbook(path)["Notes"]
    return [str(r[0].value) for r in ws.iter_rows() if r[0].value is not None]


def test_preference_order_reaches_films_through_oil_and_clearance_first():
    # issue 47: bearing-film limits first through the levers that keep the crank like real
    # ones (oil grade, clearance), the journal sizes only after them
    ids = [m.id for m in MOVES if m.applies("BRG-003", "BE1")]
    assert ids[:2] == ["oil-grade", "pin-clearance"]
    assert ids.index("crank-pin") > ids.index("pin-land") > ids.index("pin-clearance")
    assert [m.id for m in MOVES if m.applies("BRG-004", "M3")][:2] == ["oil-grade",
                                                                      "main-clearance"]


def test_several_dimensions_move_together_and_the_layout_stays_consistent():
    L = layout(parse_brief(I4))
    m = next(m for m in MOVES if m.id == "main-journal")
    from checker.sizing.loop import Design

    d = m.apply(Design(L, None), 1.2)  # type: ignore[arg-type]
    N = d.layout
    assert N.dj == pytest.approx(1.2 * L.dj) and N.main_land == pytest.approx(1.2 * L.main_land)
    assert N.main_len == pytest.approx(N.main_land + 2 * (N.fillet_j + 1e-3))
    assert N.spacing >= N.main_len + 2 * N.tw + N.pin_len - 1e-12
    assert N.cw_ri / N.dj == pytest.approx(L.cw_ri / L.dj)
    assert N.clearance_main / N.dj == pytest.approx(L.clearance_main / L.dj)
    w = relayout(L, tw=1.3 * L.tw)
    assert w.spacing == pytest.approx(L.spacing + 0.6 * L.tw)  # two webs per throw


def test_the_most_demanding_answer_passes_every_result_of_a_move():
    inc = Move("x", "x", ("FAT-",), (), "x", lambda d, x: d, lambda d: 1.0)
    assert _most_demanding(inc, [(None, 1.1), (None, 1.3), (None, 1.2)]) == 1.3
    grade = next(m for m in MOVES if m.id == "oil-grade")
    assert _most_demanding(grade, [(None, "10W-40"), (None, "5W-40")]) == "10W-40"


def test_a_layout_checked_in_memory_equals_its_written_workbook(tmp_path):
    """The loop's evaluator checks a layout as cell changes of the first one: the same
    results as checking the workbook file written for it."""
    L = layout(parse_brief(I4))
    L, tune, bench = tune_layout(L)
    moved = relayout(L, dp=1.1 * L.dp, rod_land=1.1 * L.rod_land)
    cont = content(moved, replace(tune, oil_grade="10W-40"))
    ch = bench.changes(cont)
    assert ("Oil", 2, 2) in ch and any(k[0] == "Crank" for k in ch)
    # the tuning adds the project's free-force limits to sheet Engine: rows written too
    assert {k[0] for k in set(cells_of(cont)) - set(bench.cells)} <= {"Engine"}
    sel = ["BRG-001", "BRG-002", "FAT-001"]
    mem = bench.check(cont, sel)
    path = tmp_path / "moved.xlsx"
    write_workbook(path, cont)
    disk = api.check(str(path), select=sel)
    assert [(r.rule, r.item, r.status) for r in mem.results] == [
        (r.rule, r.item, r.status) for r in disk.results]
    for a, b in zip(mem.results, disk.results):
        assert (a.value is None) == (b.value is None)
        if a.value is not None:
            assert a.value == pytest.approx(b.value, rel=1e-9)


def test_no_iterate_writes_the_open_loop_layout(tmp_path):
    r = _new(tmp_path, "i3", "--no-iterate")
    assert r.returncode == 0, r.stderr
    assert "sizing loop" not in r.stderr
    assert not any(n.startswith("How this layout was sized") for n in
                   _notes(tmp_path / "i3.xlsx"))


STILL_FAILING: dict[str, str] = {}
"""What the loop leaves failing on these briefs today (docs/sizing-loop.md), each named with
the brief value that prevents it: none since the cylinders carry their published damping
(the V12's second crank mode, the V8's higher orders). Strict: a brief that starts passing
fails here until its mark is removed."""


END_TO_END = ("i3", "i4", "i6-diesel-123", "v6-shared", "v6-split", "v8", "v8-flat", "v12",
              "twin-270")
"""The briefs of issue 47 run end to end (new with its loop, check, report): an I3, an I4, an
I6 diesel of 123 mm bore, the 60-degree V6 on shared and on split pins, the 90-degree V8
cross- and flat-plane, the V12 and the 270-degree twin (the V12's loop takes about 25 s of
processor time, docs/sizing-loop.md)."""


@pytest.mark.ci
@pytest.mark.parametrize("name", END_TO_END)
def test_brief_sizes_with_the_loop_end_to_end(tmp_path, name):
    """new (with its loop), check and report; the loop never leaves more failed results than
    the open-loop layout had, and its history is in the Notes and on the console; a brief the
    loop closes passes every rule with none not evaluated, one it does not close still fails
    (:data:`STILL_FAILING`: a brief that starts passing fails here until it is removed)."""
    r = _new(tmp_path, name)
    assert r.returncode == 0, r.stderr
    line = next(x for x in r.stderr.splitlines() if x.startswith("sizing loop:"))
    before = int(line.split(" failed results")[0].split()[-1])
    notes = _notes(tmp_path / f"{name}.xlsx")
    assert any(n.startswith("How this layout was sized") for n in notes)
    res = api.check(str(tmp_path / f"{name}.xlsx"))
    failed = [x for x in res.results if x.status == "fail" and x.severity == "error"]
    assert len(failed) <= before
    assert not [x for x in res.results if x.status == "not_evaluated"]
    if name in STILL_FAILING:
        assert failed and "prevents it" in r.stderr, f"{name} passes now: update STILL_FAILING"
    else:
        assert res.verdict == "pass" and res.complete, [(x.rule, x.item) for x in failed]
    rep = subprocess.run([sys.executable, "-m", "checker", "report",
                          str(tmp_path / f"{name}.xlsx"), "-q"], capture_output=True, text=True)
    assert rep.returncode in (0, 1), rep.stderr


def test_a_rule_the_levers_cannot_pass_names_the_brief_value_with_its_margin():
    from types import SimpleNamespace

    from checker.sizing.loop import Design, _why_not

    L = layout(parse_brief(I4))
    r = SimpleNamespace(rule="BRG-003", item="BE1", margin=-0.47, value_text="0.6357 µm",
                        limit="≥ 1.2 µm")
    tried = {("BRG-003", "BE1"): {"oil-grade", "pin-clearance", "pin-land", "crank-pin"}}
    (text,) = _why_not(Design(L, None), [r], tried)  # type: ignore[arg-type]
    assert text.startswith("BRG-003 BE1: 0.6357 µm against ≥ 1.2 µm (margin -47 %)")
    assert "oil grade (sae j300), big-end clearance, big-end width, crank pin" in text
    assert "peak pressure 85 bar at bore 86 mm" in text and text.endswith("prevents it.")


def test_a_move_is_solved_for_the_worst_result_of_each_rule():
    from types import SimpleNamespace as R

    from checker.sizing.loop import _worst_per_rule

    rs = [R(rule="FAT-001", item="pin 1 fillet", margin=-0.2),
          R(rule="FAT-001", item="pin 2 fillet", margin=-0.5),
          R(rule="FAT-002", item="pin 2 fillet", margin=-0.1)]
    assert [(r.rule, r.item) for r in _worst_per_rule(rs)] == [("FAT-001", "pin 2 fillet"),
                                                              ("FAT-002", "pin 2 fillet")]


def test_the_history_reaches_the_report_through_the_moved_values_notes(tmp_path):
    from checker.report.render import sizing_history
    from checker.sizing.loop import HISTORY_MARK, Step, annotate

    L = layout(parse_brief(I4))
    L, tune, _bench = tune_layout(L)
    steps = [Step(2, "web", "web thickness and web width", ["FAT-001 pin 4 fillet"],
                  "web 23.2 mm", "web 24.0 mm"),
             Step(1, "oil-grade", "oil grade", ["BRG-003 BE1"], "5W30", "10W-40")]
    cont = annotate(content(L, tune), steps)
    oil = next(r for r in cont["Oil"] if r[0] == "Oil grade")
    assert f"[{HISTORY_MARK} round 1: BRG-003 BE1 drove the oil grade: 5W30 -> 10W-40]" in oil[3]
    path = tmp_path / "annotated.xlsx"
    write_workbook(path, cont)
    res = api.check(str(path), select=["FLY"])
    assert sizing_history(res.engine) == [s.text() for s in reversed(steps)]  # by round
    assert sizing_history(replace(res.engine, estimates=())) == []  # another workbook


def test_the_journals_stay_inside_the_band_of_real_engines_and_the_main_above_the_pin():
    """The crank-pin move takes the main journal with it (at least MAIN_PIN_MIN x the pin,
    as in real cranks) and stops at the class's bands of pin and main per bore."""
    from checker.calc import first_layout as fl
    from checker.sizing.loop import Design, _cap_main, _cap_pin

    L = layout(parse_brief(I4))
    pin = next(m for m in MOVES if m.id == "crank-pin")
    d = Design(L, None)  # type: ignore[arg-type]
    cap = _cap_pin(d)
    top_pin, top_main = (fl.CLASSES["passenger car"][k][1] * 0.086
                         for k in ("pin_bore_band", "main_bore_band"))
    assert L.dp * cap == pytest.approx(min(top_pin, top_main / fl.MAIN_PIN_MIN))
    assert pin.bounds_for(d)[1] == pytest.approx(min(1.4, cap))
    N = pin.apply(d, cap).layout  # the I4's main is 1.11 x the pin at its cap: stays
    assert N.dj == L.dj and N.dp == pytest.approx(top_pin)
    assert _cap_main(Design(N, None)) * N.dj == pytest.approx(top_main)  # type: ignore[arg-type]
    close = Design(relayout(L, dj=1.06 * L.dp), None)  # type: ignore[arg-type]
    M = pin.apply(close, 1.1).layout  # the main grows with the pin
    assert M.dj == pytest.approx(fl.MAIN_PIN_MIN * M.dp) and M.dj > close.layout.dj
    assert M.main_land / M.dj == pytest.approx(L.main_land / close.layout.dj)


def test_the_washer_and_oil_hole_moves_reach_the_workbook():
    """A diamond washer (friction 0.3, Bell 2013) raises the joint's slip capacity in
    proportion and is written to sheet Joints; the oil hole's angle goes to the big ends'
    rows and the fatigue sheet's oil-hole height."""
    from checker.sizing.loop import Design

    L, tune, _bench = tune_layout(layout(parse_brief(I4)))
    d = Design(L, tune)
    washer = next(m for m in MOVES if m.id == "nose-washer")
    assert washer.today(d) == 0.2 and washer.to_end
    w = washer.apply(d, 0.3)
    nose0, nose = (next(j for j in t.joints if j["name"] == "crank nose")
                   for t in (tune, w.tune))
    assert nose["capacity"] == pytest.approx(1.5 * nose0["capacity"])
    assert [j["friction"] for j in w.tune.joints if j["name"] == "flywheel"] == [0.2]
    cols, rows = content(w.layout, w.tune)["Joints"]
    k = [h for h, _u in cols].index("friction coefficient")
    assert {r[0]: r[k] for r in rows} == {"crank nose": 0.3, "flywheel": 0.2}
    hole = next(m for m in MOVES if m.id == "oil-hole")
    h = hole.apply(d, 90.0)
    cont = content(h.layout, h.tune)
    cols, rows = cont["Bearings"]
    k = [c for c, _u in cols].index("oil hole angle")
    assert {r[k] for r in rows if r[1] == "big end"} == {90.0}
    height = next(r[1] for r in cont["Fatigue"] if r[0] == "Pin journal oil hole height")
    assert height == pytest.approx(L.dp / 2 * 1e3, abs=0.006)  # written to 0.01 mm


def test_a_gasoline_brief_takes_the_shape_of_a_published_full_load_curve():
    """Torque and peak pressure against speed of the production I4 of Bell 2013, scaled to
    the brief: the rated torque at the rated speed, the brief's peak pressure the maximum,
    and at a sixth of the rated speed 63 % of it (53.4 of 84.4 bar)."""
    from checker.calc import first_layout as fl
    from checker.sizing.new_engine import rating

    b = parse_brief(I4)
    L, tune, _bench = tune_layout(layout(b))
    cont = content(L, tune)
    bt = {r[0]: r[1] for r in cont["BrakeTorque"][1]}
    pp = {r[1]: r[2] for r in cont["PeakPressure"][1] if r[0] == "full"}
    assert bt[6000] == pytest.approx(rating(b).torque, abs=0.05)
    assert max(pp.values()) == pytest.approx(85.0, abs=0.05)
    assert pp[1000] == pytest.approx(85.0 * 53.4 / 84.4, abs=0.05)
    assert fl.full_load_shape(0.01) == fl.full_load_shape(1000 / 6000)  # its end values


def test_a_heavier_damper_ring_gets_den_hartogs_optimum_rubber():
    """The damper move keeps the rubber at Den Hartog's optimum for the new inertia ratio
    (Mechanical Vibrations, 1956, sec. 3.3): f_opt = 1/(1 + mu), zeta_opt = sqrt(3 mu / (8
    (1 + mu)^3)), the crank mode's frequency unchanged; a ring at today's tuning would be
    detuned (the loop's V6 briefs failed TV-003 after such a move)."""
    import math

    from checker.sizing.loop import Design
    from checker.sizing.new_engine import Tuning

    mu0, w_n = 0.25, 2 * math.pi * 300.0
    f0 = 1 / (1 + mu0)
    t = Tuning(flywheel=0.2, ring=0.01, ring_stiffness=0.01 * (f0 * w_n) ** 2,
               loss_factor=0.5, joints=[], tuning=f0)
    damper = next(m for m in MOVES if m.id == "damper")
    n = damper.apply(Design(None, t), 2.0).tune  # type: ignore[arg-type]
    mu = 2 * mu0
    f = 1 / (1 + mu)
    assert n.ring == pytest.approx(0.02) and n.tuning == pytest.approx(f)
    assert n.ring_stiffness == pytest.approx(0.02 * (f * w_n) ** 2)
    assert n.loss_factor == pytest.approx(2 * math.sqrt(3 * mu / (8 * (1 + mu) ** 3)) / f)
    same = damper.apply(Design(None, t), 1.0).tune  # type: ignore[arg-type]
    assert same.ring_stiffness == pytest.approx(t.ring_stiffness)


def test_the_material_move_writes_the_stronger_steels_strengths():
    """42CrMo4 +QT (EN 10083-3, R_m 900 MPa at 40-100 mm) with Bell 2013's derivation: base
    fatigue 0.5 x UTS = 450 MPa, pin oil hole 450 x 0.868 = 391 MPa; brief synonyms too."""
    from checker.sizing.loop import STEELS, Design

    L, tune, _bench = tune_layout(layout(parse_brief(I4)))
    mat = next(m for m in MOVES if m.id == "material")
    assert mat.today(Design(L, tune)) == "forged steel" and STEELS[-1] == "42CrMo4"
    d = mat.apply(Design(L, tune), "42CrMo4")
    fat = {r[0]: r[1] for r in content(d.layout, d.tune)["Fatigue"]}
    assert fat["Base material UTS"] == 900 and fat["Base infinite life fatigue strength"] == 450
    assert fat["Pin oil hole fatigue strength"] == round(450 * 0.868)
    assert fat["Pin fillet fatigue strength"] == round(450 * 0.868 * 1.9)
    assert parse_brief({**I4, "crank_material": "alloy steel"}).crank_material == "42CrMo4"


def test_the_oil_cooler_move_lowers_the_gallery_temperature_and_says_so():
    from checker.sizing.loop import COOLING, Design

    L, tune, _bench = tune_layout(layout(parse_brief(I4)))
    cooler = next(m for m in MOVES if m.id == "oil-cooler")
    assert cooler.today(Design(L, tune)) == 0.0 and COOLING[-1] == 20.0 and cooler.to_end
    d = cooler.apply(Design(L, tune), 20.0)
    oil = {r[0]: r for r in content(d.layout, d.tune)["Oil"]}
    assert oil["Oil supply temperature"][1] == 100.0  # gasoline: 120 °C usual
    assert "oil cooler" in oil["Oil supply temperature"][3]
    first = {r[0]: r for r in content(L, tune)["Oil"]}
    assert first["Oil supply temperature"][1] == 120 and "cooler" not in first[
        "Oil supply temperature"][3]


def test_the_nose_move_widens_the_nose_its_joint_face_and_bolt_together():
    """The crank nose grows with its joint's clamped face (one source: the nose diameter of
    sheet CrankEnds and the joint's face both follow Layout.nose_ratio), up to 0.9 x the main
    journal; the bolt is the largest the wider face allows."""
    from checker.sizing.loop import NOSE_MAX, Design, _cap_nose

    L, tune, _bench = tune_layout(layout(parse_brief(I4)))
    d = Design(L, tune)
    nose = next(m for m in MOVES if m.id == "nose")
    assert nose.bounds_for(d)[1] == pytest.approx(min(1.2, NOSE_MAX / 0.75))
    w = nose.apply(d, 1.2)
    assert w.layout.nose_ratio == pytest.approx(0.9) and _cap_nose(w) == pytest.approx(1.0)
    cont = content(w.layout, w.tune)
    ends = {r[0]: r[1] for r in cont["CrankEnds"]}
    assert ends["Crank nose diameter"] == pytest.approx(0.9 * L.dj * 1e3, abs=0.006)
    cols, rows = cont["Joints"]
    k = [h for h, _u in cols].index("face outer diameter")
    row = next(r for r in rows if r[0] == "crank nose")
    assert row[k] == pytest.approx(0.9 * L.dj * 1e3, abs=0.006)
    j0, j1 = (next(j for j in t.joints if j["name"] == "crank nose") for t in (tune, w.tune))
    assert j1["d"] >= j0["d"] and j1["capacity"] > j0["capacity"]
    assert "moved by the sizing loop" in next(r[3] for r in cont["CrankEnds"]
                                              if r[0] == "Crank nose diameter")


def test_the_lining_moves_write_a_stronger_lining_on_their_bearings_only():
    from checker.sizing.loop import LININGS, Design

    L, tune, _bench = tune_layout(layout(parse_brief(I4)))
    pin = next(m for m in MOVES if m.id == "pin-lining")
    assert pin.today(Design(L, tune)) == "aluminium bimetal" and LININGS[-1] == "sputter"
    assert pin.applies("BRG-001", "BE3") and not pin.applies("BRG-001", "M2")
    d = pin.apply(Design(L, tune), "sputter")
    cols, rows = content(d.layout, d.tune)["Bearings"]
    k = [h for h, _u in cols].index("lining")
    assert {r[1]: r[k] for r in rows} == {"main": "aluminium bimetal", "big end": "sputter"}
    assert all("chosen by the sizing loop" in r[-1] for r in rows if r[1] == "big end")


def test_the_damper_is_a_lever_of_the_oil_holes_fatigue_after_the_crank_dimensions():
    """A crank mode met by the firing order inside the speed range twists the pins: the damper
    (its ring and rubber) is tried on FAT-001 after the crank's own dimensions (the Ford 6.8
    V10 and Lexus 2GR briefs pass their pin oil holes with it)."""
    order = [m.id for m in MOVES if m.applies("FAT-001", "pin 5 oil hole")]
    assert order.index("damper") > max(order.index(x) for x in ("crank-pin", "web", "material"))
    assert "damper" in [m.id for m in MOVES if m.applies("TV-001", "all")]


def test_the_damper_tuning_move_stays_about_den_hartogs_optimum_and_survives_a_retune():
    """The rubber's stiffness about Den Hartog's optimum (a single-mode optimum; the Volvo I5
    brief's 5th order passes at 1.18 x it): the total ratio held within DETUNE, the ring and
    loss factor kept; a later retune of a moved crank keeps the ratio."""
    from checker.sizing.loop import DETUNE, Design
    from checker.sizing.new_engine import Tuning

    t = Tuning(flywheel=0.2, ring=0.01, ring_stiffness=3.0e4, loss_factor=0.3, joints=[],
               tuning=0.8)
    move = next(m for m in MOVES if m.id == "damper-tuning")
    assert move.direction == "either" and move.bounds == DETUNE
    up = move.apply(Design(None, t), 1.1).tune  # type: ignore[arg-type]
    assert up.detune == pytest.approx(1.1) and up.ring_stiffness == pytest.approx(3.3e4)
    assert (up.ring, up.loss_factor, up.tuning) == (t.ring, t.loss_factor, t.tuning)
    far = move.apply(Design(None, up), 1.2).tune  # type: ignore[arg-type]
    assert far.detune == pytest.approx(DETUNE[1])
    assert far.ring_stiffness == pytest.approx(3.0e4 * DETUNE[1])
    # a heavier ring keeps the detuning on its own optimum
    damper = next(m for m in MOVES if m.id == "damper")
    heavy = damper.apply(Design(None, up), 2.0).tune  # type: ignore[arg-type]
    opt = damper.apply(Design(None, t), 2.0).tune  # type: ignore[arg-type]
    assert heavy.ring_stiffness == pytest.approx(1.1 * opt.ring_stiffness)
    # tried on the crank's vibration before the crank's own stiffness and the damper's size
    order = [m.id for m in MOVES if m.applies("TV-001", "all")]
    assert order.index("damper-tuning") < order.index("main-stiffness") < order.index("web")
    assert order.index("web") < order.index("damper")


def test_a_crank_move_for_the_cranks_vibration_is_judged_with_the_damper_tuned_to_it():
    """A stiffer crank with today's damper is a detuned damper: on the Volvo I5 brief a main
    journal 10 % larger raised the 5th-order nose amplitude with the damper kept, and lowered
    it with the damper tuned to the moved crank. The binding of such a move retunes the
    damper for each trial layout (the rubber's cell moves with the journal's)."""
    from checker.sizing.loop import Design, MoveBinding

    L, tune, bench = tune_layout(layout(parse_brief(dict(I4))))
    d = Design(L, tune)
    m = next(x for x in MOVES if x.id == "main-stiffness")
    plain = MoveBinding(bench, d, m).changes(1.1)
    tuned = MoveBinding(bench, d, m, retune=True).changes(1.1)
    # the rubber's stiffness moved too; the crank's cells as without the retune
    assert any(tuned[k] != plain.get(k) for k in tuned if k[0] == "TVModel")
    assert all(tuned[k] == v for k, v in plain.items() if k[0] == "Crank")


def test_the_web_move_keeps_its_width_inside_the_fitted_range_of_the_throw_stiffness():
    """Web width at most 1.8 x the smaller journal (the throw-stiffness model's fitted
    Bp/Dp, Bj/Dj 1.2-1.8): the thickness moves on alone beyond it."""
    from checker.calc.throw_stiffness import RANGE
    from checker.sizing.loop import WEB_WIDTH_MAX, Design

    assert WEB_WIDTH_MAX == RANGE["Bp/Dp"][1] == RANGE["Bj/Dj"][1]
    L, tune, _ = tune_layout(layout(parse_brief(dict(I4))))
    web = next(m for m in MOVES if m.id == "web")
    n = web.apply(Design(L, tune), 1.5).layout
    assert n.tw == pytest.approx(1.5 * L.tw)
    assert n.bw == pytest.approx(WEB_WIDTH_MAX * min(L.dp, L.dj)) and n.bw < 1.5 * L.bw
    small = web.apply(Design(L, tune), 1.05).layout
    assert small.bw == pytest.approx(1.05 * L.bw)


def test_the_looped_layouts_plausibility_is_its_own():
    """The console's warnings and the report's caveats are of the crank written: a main land
    the loop widened past the band of real engines is named, and one back inside is not."""
    from checker.sizing.loop import Design, _plausible

    L, tune, bench = tune_layout(layout(parse_brief(dict(I4))))
    wide = relayout(L, main_land=0.55 * L.dj)
    names = " ".join(_plausible(bench, Design(wide, tune)).plausibility)
    assert "main land L/D 0.55" in names
    back = " ".join(_plausible(bench, Design(L, tune)).plausibility)
    assert "main land L/D" not in back
