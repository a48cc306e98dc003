"""Sheet Crank (issue 33): the crank described once; Bearings, Fatigue, CrankMass and TVModel
take its dimensions; bad geometry is an error at its cell, every problem in one pass."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from checker import api
from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.workbook.example import example_content, write_workbook

CRANK_COLS = [("throw", "-"), ("main journal diameter", "mm"), ("main journal length", "mm"),
              ("pin diameter", "mm"), ("pin bore", "mm"), ("pin length", "mm"),
              ("web thickness", "mm"), ("web width at journal", "mm"),
              ("web width at pin", "mm"), ("counterweight inner radius", "mm"),
              ("counterweight outer radius", "mm"), ("counterweight angle", "deg"),
              ("density", "kg/m^3"), ("Young's modulus", "GPa"), ("Poisson's ratio", "-"),
              ("note", "")]
ALL = ["all", 55, 27, 48, None, 24.4, 22.3, 80, 70, 30, 64, 150, 7850, 210, 0.3, "test"]


def i4_with_crank(rows=None, ends=None, edit=None) -> dict:
    """The I4 example (described by sheet Crank) with the Crank rows ``rows`` in place of its
    own (default: the example's), and sheet CrankEnds."""
    base = copy.deepcopy(example_content())
    out = {}
    for k, v in base.items():
        if k == "CrankEnds" and ends:
            continue
        out[k] = v
        if k == "Crank" and rows is not None:
            out["Crank"] = (CRANK_COLS, [list(r) for r in rows])
        if k == "Crank" and ends:
            out["CrankEnds"] = ends
    if edit:
        edit(out)
    return out


def _write(tmp_path, content, name="crank.xlsx"):
    p = tmp_path / name
    write_workbook(p, content)
    return p


def _errors(path) -> dict[str, str]:
    with pytest.raises(InputErrors) as exc:
        load_engine(path)
    return {e.where: e.message for e in exc.value.errors}


def _set_table(content, sheet, col, value, where=lambda r: True):
    cols, rows = content[sheet]
    j = [c for c, _ in cols].index(col)
    for r in rows:
        if where(r):
            while len(r) <= j:
                r.append(None)
            r[j] = value


def test_same_results_when_a_dimension_given_twice_agrees(tmp_path):
    def twice(c):
        _set_table(c, "Bearings", "journal diameter", 55.0, lambda r: r[1] == "main")
        _set_table(c, "Bearings", "journal length", 24.4, lambda r: r[1] == "big end")
        c["Fatigue"].append(("Web full thickness", 22.3, "mm", "test"))

    plain = api.check(_write(tmp_path, example_content(), "plain.xlsx"))
    with_crank = api.check(_write(tmp_path, i4_with_crank(edit=twice)))
    a = [(r.rule, r.item, r.case, r.status, r.value) for r in plain.results]
    b = [(r.rule, r.item, r.case, r.status, r.value) for r in with_crank.results]
    assert a == b
    e = with_crank.engine
    assert e.crank is not None and len(e.crank.throws) == 4
    assert [b.diameter for b in e.bearings] == [0.055] * 5 + [0.048] * 4
    assert e.crank.throws[0].length == pytest.approx(0.096)


def test_bearings_and_fatigue_take_the_crank_dimensions(tmp_path):
    # the I4 example types its journals, pin, web thickness and fillets once, on sheet Crank
    e = load_engine(_write(tmp_path, example_content()))
    mains = [b for b in e.bearings if b.type == "main"]
    bigs = [b for b in e.bearings if b.type == "big end"]
    assert [b.diameter for b in mains] == [0.055] * 5
    assert [b.journal_length for b in bigs] == [pytest.approx(0.0244)] * 4
    assert e.fatigue["web_full_thickness"] == pytest.approx(0.0223)
    assert e.fatigue["pin_fillet_radius"] == pytest.approx(0.0016)


def test_a_dimension_given_twice_and_different_names_both_cells(tmp_path):
    def edit(c):
        _set_table(c, "Bearings", "journal diameter", 56.0, lambda r: r[0] == "M2")
        c["Fatigue"].append(("Web full thickness", 23.0, "mm", "test"))

    errs = _errors(_write(tmp_path, i4_with_crank(edit=edit)))
    bearing = next(m for w, m in errs.items() if w.startswith("Bearings!C"))
    assert "56 mm differs from the crank's 55 mm (Crank!B3)" in bearing
    fat = next(m for w, m in errs.items() if w.startswith("Fatigue!"))
    assert "23 mm differs from the crank's 22.3 mm (Crank!F3)" in fat


def test_bad_geometry_every_problem_at_its_cell_in_one_pass(tmp_path):
    rows = [ALL,
            ["2", None, None, None, 50, None, None, None, 40],  # pin bore = pin diameter 48?
            ["3", None, None, None, None, None, None, 45],  # web narrower than the journal
            ["4", None, None, None, None, None, None, None, 40, None, None, 300],  # cw on pin
            ["5"]]  # no such throw
    errs = _errors(_write(tmp_path, i4_with_crank(rows=rows)))
    text = "\n".join(f"{w}: {m}" for w, m in errs.items())
    assert "Crank!E4: throw 2: the pin bore 50 mm must be smaller than the pin diameter" in text
    assert "Crank!I4: throw 2: the pin (48 mm) lies outside its web (40 mm wide" in text
    assert "Crank!H5: throw 3: the web (45 mm wide at the journal) is narrower than its" \
        " main journal (55 mm)" in text
    assert "Crank!L6: throw 4: the counterweight overlaps the crank pin" in text
    assert "Crank!A7: expected 'all' or a throw number 1..4, found '5'" in text


def test_throw_count_must_match_the_cylinders(tmp_path):
    rows = [["1", *ALL[1:]], ["2", *ALL[1:]]]
    errs = _errors(_write(tmp_path, i4_with_crank(rows=rows)))
    assert "no row for throw 3, 4: the engine has 4 throws" in errs["Crank"]


def test_non_positive_length_is_an_error_at_the_cell(tmp_path):
    row = list(ALL)
    row[5] = 0
    errs = _errors(_write(tmp_path, i4_with_crank(rows=[row])))
    assert "Crank!F3" in errs and "greater than zero" in errs["Crank!F3"]


def test_derived_crank_masses_and_station_inertias(tmp_path):
    def edit(c):
        c["CrankMass"] = (c["CrankMass"][0], [])
        _set_table(c, "TVModel", "inertia", None, lambda r: r[1] == "cylinder")

    e = load_engine(_write(tmp_path, i4_with_crank(edit=edit)))
    mp = e.crank.mass_properties
    # CrankMass rows: two webs, two counterweights and a pin per throw
    assert len(e.crank_mass) == 4 * 5
    webs = [m for m in e.crank_mass if m.kind == "web" and m.throw == 2]
    assert webs[0].y == pytest.approx(-mp.y[1, 1])  # throw 2 at 180 deg from throw 1
    r, lam = 0.0473, 0.0473 / 0.1457
    m_rot = 0.597 * (1 - 35.73 / 145.7)
    m_osc = 0.4955 + 0.597 * 35.73 / 145.7
    want = mp.inertia_total[0] + m_rot * r * r + m_osc * r * r * (0.5 + lam**2 / 8)
    cyl = [s for s in e.tv_model if s.role == "cylinder"]
    assert [s.inertia for s in cyl] == pytest.approx([want] * 4, rel=1e-12)
    origins = {(m.item, m.attr): m.origin for m in e.crank_model}
    assert origins[("Cylinder 1", "inertia")] == "derived"
    # the balance module runs on the derived masses: the I4 crank balances itself
    res = api.check(e, select=["BAL"])
    assert res.outcome.quantities["balance.crank_unbalance"].values[0] == pytest.approx(
        0.0, abs=1e-9)


def test_pulley_unbalance_adds_its_first_order_force(tmp_path):
    ends = [("Pulley unbalance", 200, "g mm", "test"),
            ("Pulley unbalance angle", 90, "deg", "test"),
            ("Pulley unbalance distance", 60, "mm", "test")]
    base = api.check(_write(tmp_path, i4_with_crank(), "a.xlsx"), select=["BAL"])
    res = api.check(_write(tmp_path, i4_with_crank(ends=ends), "b.xlsx"), select=["BAL"])
    w = 6000 * 2 * math.pi / 60
    f0 = base.outcome.quantities["balance.free_force"].values[0]
    f1 = res.outcome.quantities["balance.free_force"].values[0]
    assert f1 - f0 == pytest.approx(200e-6 * w * w, rel=1e-6)
    # the throws' own balance ratio is unchanged (the unbalance belongs to no throw)
    assert np.allclose(base.outcome.quantities["balance.balance_ratio"].values,
                       res.outcome.quantities["balance.balance_ratio"].values)


# ------------------------------------------------------------------ throw stiffness wiring
class _StandIn:
    """A stand-in for checker.calc.throw_stiffness with the agreed interface (the real model
    is built on another branch): k = G Jp(Dj) / (throw length), so the wiring is checkable."""

    @staticmethod
    def throw_torsional_stiffness(**kw):
        from types import SimpleNamespace

        g = kw["youngs_modulus"] / (2 * (1 + kw["poisson_ratio"]))
        length = kw["journal_length"] + 2 * kw["web_thickness"] + kw["pin_length"]
        k = g * np.pi * kw["journal_diameter"]**4 / 32 / length
        return SimpleNamespace(stiffness=k, in_range=np.ones_like(k, bool),
                               method="stand-in", model_error=0.03,
                               outside=("",) * np.size(k))


@pytest.fixture
def stand_in(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "checker.calc.throw_stiffness", _StandIn)
    return _StandIn


def test_tv_stiffness_derived_where_blank_typed_wins(tmp_path, stand_in):
    ends = [("Crank nose diameter", 40, "mm", "test"), ("Crank nose length", 60, "mm", "test"),
            ("Flywheel flange diameter", 70, "mm", "test"),
            ("Flywheel flange length", 30, "mm", "test")]

    def edit(c):
        _set_table(c, "TVModel", "stiffness to next", None,
                   lambda r: r[0] in ("Crank nose", "Cylinder 1", "Cylinder 4"))

    e = load_engine(_write(tmp_path, i4_with_crank(ends=ends, edit=edit)))
    g = 210e9 / 2.6
    k_throw = g * math.pi * 0.055**4 / 32 / 0.096

    def comp(d, ln):
        return ln / (g * math.pi * d**4 / 32)

    st = {s.station: s.stiffness for s in e.tv_model}
    assert st["Cylinder 1"] == pytest.approx(k_throw, rel=1e-12)  # two halves of equal throws
    assert st["Cylinder 2"] == 416625  # typed wins
    assert st["Crank nose"] == pytest.approx(
        1 / (comp(0.040, 0.060 - 0.0135) + comp(0.055, 0.0135) + 1 / (2 * k_throw)), rel=1e-12)
    assert st["Cylinder 4"] == pytest.approx(
        1 / (1 / (2 * k_throw) + comp(0.055, 0.0135) + comp(0.070, 0.030 - 0.0135)), rel=1e-12)
    origin = {(m.item, m.attr): (m.origin, m.derived) for m in e.crank_model}
    assert origin[("Cylinder 1", "stiffness")][0] == "derived"
    assert origin[("Cylinder 2", "stiffness")] == ("typed", pytest.approx(k_throw))
    # the JSON quantities: always the geometry's values, also where typed values win
    res = api.check(e, select=["TV-001"])
    q = res.outcome.quantities
    assert q["crank.throw_stiffness"].values == pytest.approx([k_throw] * 4)
    assert q["crank.throw_inertia"].values == pytest.approx(
        e.crank.mass_properties.inertia_total)
    assert q["crank.throw_mass"].values == pytest.approx(e.crank.mass_properties.mass_total)
    d = res.to_dict(timings=False)
    assert d["quantities"]["crank.throw_stiffness"]["coords"]["item"] == [
        "throw 1", "throw 2", "throw 3", "throw 4"]
    assert {m["origin"] for m in d["crank_model"]} == {"typed", "derived"}
    assert "crank" in d["modules"]["run"]


def test_no_crank_sheet_no_crank_quantities_or_module(tmp_path):
    c = copy.deepcopy(example_content())
    del c["Crank"]
    _set_table(c, "Bearings", "journal diameter", 55.0, lambda r: r[1] == "main")
    _set_table(c, "Bearings", "journal diameter", 48.0, lambda r: r[1] == "big end")
    d = api.check(_write(tmp_path, c, "plain.xlsx"), select=["BAL"]).to_dict(timings=False)
    assert not [k for k in d["quantities"] if k.startswith("crank.")]
    assert "crank" not in d["modules"]["run"] + d["modules"]["skipped"]
    assert "crank_model" not in d


def test_stiffness_not_derivable_without_the_model_is_an_error_at_the_cell(tmp_path,
                                                                            monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "checker.calc.throw_stiffness", None)  # ImportError

    def edit(c):
        _set_table(c, "TVModel", "stiffness to next", None, lambda r: r[0] == "Cylinder 2")

    errs = _errors(_write(tmp_path, i4_with_crank(edit=edit)))
    msg = errs["TVModel!F6"]
    assert "stiffness to the next station is required" in msg
    assert "throw stiffness model" in msg


def test_derived_stiffness_outside_the_fitted_range_is_a_warning_at_its_cell(tmp_path):
    # the I6's throws lie outside the fast model's fitted range (the report says so); typed
    # stiffnesses win there, so no warning; blank, the derived one is used: a warning
    from checker.workbook.example_data import load_example

    c = load_example("i6")
    assert not [w for w in load_engine(_write(tmp_path, c, "i6.xlsx")).warnings
                if w.where.startswith("TVModel")]
    _set_table(c, "TVModel", "stiffness to next", None, lambda r: r[0] == "Cylinder 2")
    e = load_engine(_write(tmp_path, c, "i6-derived.xlsx"))
    (w,) = [w for w in e.warnings if w.where.startswith("TVModel")]
    assert w.where == "TVModel!F7"
    assert "derived from throw 2, 3 outside the fitted range" in w.message
    assert "(Dp/Dj 0.741 (fitted 0.75..1); stated error 3.5 % inside it)" in w.message
    assert next(m for m in e.crank_model if m.item == "Cylinder 2"
                and m.attr == "stiffness").origin == "derived"


def _v8_wide_throw(path, stroke_mm: float, web_mm: float, cw: tuple | None = None):
    """The V8 example (torsional model derived from sheet Crank) with the throw of issue 43,
    item 2: journal 80, pin 68 mm, the pin largely within the journal in the end view."""
    from checker.workbook.example_data import load_example

    c = load_example("v8")
    cols, rows = c["Crank"]
    names = [n for n, _ in cols]
    for k, v in {"main journal diameter": 80, "main journal length": 36, "pin diameter": 68,
                 "pin length": 34, "web thickness": web_mm, "web width at journal": 120,
                 "web width at pin": 95.2, "counterweight inner radius": None,
                 "counterweight outer radius": None, "counterweight angle": None}.items():
        rows[0][names.index(k)] = v
    if cw is not None:
        for k, v in zip(("counterweight inner radius", "counterweight outer radius",
                         "counterweight angle"), cw):
            rows[0][names.index(k)] = v
    c["Engine"] = [(e[0], stroke_mm, *e[2:]) if e[0] == "Stroke" else e for e in c["Engine"]]
    c.pop("CrankMass")
    return _write(path.parent, c, path.name)


def test_stiffness_model_outside_its_range_checks_and_names_its_groups(tmp_path):
    """Issue 43, item 2: stroke 10 mm, web 2 mm ended in 'internal error: ValueError:
    stiffness must be finite and > 0'; now the check runs, every derived stiffness is
    positive and its warning names the groups outside the fitted range."""
    res = api.check(_v8_wide_throw(tmp_path / "v8-wide.xlsx", 10.0, 2.0))
    k = [m.value for m in res.engine.crank_model if m.attr == "stiffness"
         and m.origin == "derived"]
    assert k and all(math.isfinite(x) and x > 0 for x in k)
    warns = [w for w in res.engine.warnings if w.where.startswith("TVModel")]
    assert warns and all("(overlap S/Dj 0.863 (fitted -0.15..0.3), tw/Dj 0.025 (fitted"
                         " 0.2..0.5); stated error 3.5 % inside it)" in w.message
                         for w in warns)


def test_counterweight_alone_outside_the_samples_is_no_warning(tmp_path):
    """The stiffness has no counterweight term: a counterweight beyond the samples' radii
    (outer radius 1.5 (R + Dp/2), the samples reach 1.25) flags no derived stiffness."""
    from checker.workbook.example_data import load_example

    c = load_example("v8")
    cols, rows = c["Crank"]
    rows[0][[n for n, _ in cols].index("counterweight outer radius")] = 1.5 * (46 + 26.66)
    e = load_engine(_write(tmp_path, c, "v8-cw.xlsx"))
    assert not [w for w in e.warnings if w.where.startswith("TVModel")]
    assert [m.origin for m in e.crank_model if m.attr == "stiffness"].count("derived") >= 3


def test_tv_stiffness_is_the_assembled_cranks_on_its_bearings(tmp_path):
    """Issue 43: the torsional model's derived stiffness between neighbouring cylinders is the
    assembled crank's on its main bearings, not the throws alone in series (their definition
    lets both journals tilt freely, exact only between mirror-image neighbours). The I4's
    throws at 180 deg: the stored 3D FE of the whole four-throw crank on its five bearings
    (``scripts/crank_piece_fe.py``) is 17.2 % stiffer per throw than the same FE's throw
    alone; the derived value must show the same within 3 %."""
    import json

    from checker.calc import crank_beam as cb
    from checker.description import crank_derive as cd

    def edit(c):
        _set_table(c, "TVModel", "stiffness to next", None, lambda r: r[0] == "Cylinder 1")

    e = load_engine(_write(tmp_path, i4_with_crank(edit=edit)))
    single = cd.throw_stiffness(e.crank).stiffness
    series = 1.0 / (1.0 / (2 * single[0]) + 1.0 / (2 * single[1]))
    derived = {s.station: s.stiffness for s in e.tv_model}["Cylinder 1"]
    path = cb.__file__.replace("crank_beam.py", "data/crank_piece_fe.json")
    with open(path, encoding="utf-8") as f:
        fe = next(p for p in json.load(f)["pieces"]
                  if p["engine"] == "i4" and p["throws"] == 4)
    fe_gain = fe["k_fe"] * 4 / fe["k_single_fe"]
    assert derived / series == pytest.approx(fe_gain, rel=0.03)
    method = next(m.method for m in e.crank_model
                  if m.item == "Cylinder 1" and m.attr == "stiffness")
    assert "assembled crank on its main bearings" in method
