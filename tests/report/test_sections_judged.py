"""Module sections agree with the rule results: per item the judged worst row comes first and
equals the rule result's value and operating point; points that are computed but not judged
(``Quantity.applies``) are marked in tables (and shaded in plots), with the reason.

The section data are built with the figures' SVG serialisation stubbed out (the plotting
calls still run): fast, and the figures themselves are covered by test_plot_text.py and the
shading test below.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

from checker import api
from checker.evaluation.graph import QUANTITIES, Quantity, QuantitySpec
from checker.evaluation.ruletable import Rule, evaluate_rule
from checker.report import judged as jd
from checker.report import plots
from tests.helpers import example_path, stub_section_images

RPM = 2 * np.pi / 60
SECTION_MODULES = ("loads", "bearings", "torsion", "fatigue", "joints", "flywheel", "damper")


def _stub_svg(monkeypatch) -> None:
    stub_section_images(monkeypatch, SECTION_MODULES)


def _sections(res, monkeypatch) -> dict[str, dict]:
    import importlib

    _stub_svg(monkeypatch)
    out = {}
    for m in SECTION_MODULES:
        mod = importlib.import_module(f"checker.report.section_{m}")
        out[m] = getattr(mod, f"{m}_section")(res)
    return out


def _tables(sec: dict) -> list[dict]:
    return [b for b in sec["blocks"] if b["type"] == "table" and "judged by" in b["columns"]]


def _rows(table: dict) -> list[dict]:
    css = table.get("row_css") or [""] * len(table["rows"])
    return [dict(zip(table["columns"], r), _css=c) for r, c in zip(table["rows"], css)]


def _num(text: str) -> float:
    return float(re.match(r"[-+0-9.e]+", text).group(0))


def _case_speed(result_case: str) -> tuple[str, str]:
    """('full load', '6500') from a rule result's case text 'full load, 6500 rpm'."""
    parts = [p.strip() for p in result_case.split(",")]
    case = next(p for p in parts if p.endswith(" load"))
    speed = next(p for p in parts if p.endswith(" rpm"))[:-4]
    return case, speed


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("judged"))


@pytest.fixture(scope="module")
def result(example):
    return api.check(example)


def _restrict(res, band: tuple[float, float]):
    """The same check with every (case, speed) quantity's judged points also restricted to
    speeds outside ``band`` [rpm], and the rule results evaluated again (any mask content)."""
    for q in res.outcome.quantities.values():
        dims = q.spec.dims
        if len(dims) >= 2 and dims[-2:] == ("case", "speed"):
            sp = np.asarray(q.coords["speed"], dtype=float) / RPM
            keep = ~((sp >= band[0]) & (sp <= band[1]))
            q.applies = jd.mask(q) & keep
    res.results = [x for r in res.rules for x in evaluate_rule(
        r, res.outcome.quantities.get(r.quantity), res.outcome.unavailable.get(r.quantity))]
    return res


def _check_agreement(res, secs) -> int:
    """Every rule result with a value is the first row its rule judges in the section tables
    (for its item), with the same value and operating point; returns the number checked."""
    by_rule = {r.id: r for r in res.rules}
    tables = [t for m in secs for t in _tables(secs[m])]
    checked = 0
    for rr in res.results:
        if rr.value is None or rr.rule.startswith("JNT") or rr.status == "not_evaluated":
            continue  # (a rule without its workbook limit reports a value it does not judge)
        rule = by_rule[rr.rule]
        if "speed" not in QUANTITIES[rule.quantity].dims:
            continue  # one value per item (balancing, damper tuning): no speed table
        found = False
        for t in tables:
            rows = [r for r in _rows(t) if rr.rule in r["judged by"].split(", ")]
            if rr.item != "all":
                # items with identical rows share one ("BE1, BE2, BE3, BE4")
                rows = [r for r in rows if rr.item in r[t["columns"][0]].split(", ")]
            if not rows:
                continue
            found = True
            fat_q = rule.quantity == "fatigue.m53_q"
            col = ("M53 Q min" if fat_q else "SF min") if "SF min" in t["columns"] \
                else t["columns"][2]
            first = rows[0]
            at = tuple(x.strip() for x in first["Q at"].split(",")) if fat_q else (
                first["case"], first["speed [rpm]"])
            assert _num(first[col]) == pytest.approx(rr.value, rel=6e-4), (rr.rule, rr.item,
                                                                          first)
            assert at == _case_speed(rr.case), (rr.rule, rr.item, first, rr.case)
            assert first["_css"] == ""
            sign = 1 if rule.check in ("<", "<=") else -1
            assert all(sign * _num(r[col]) <= sign * _num(first[col]) for r in rows)
        assert found, f"{rr.rule} {rr.item}: no judged row in any section"
        checked += 1
    return checked


def _check_marking(secs) -> int:
    """Rows of points the rules do not judge say so and carry the not-judged style, and the
    other rows do not; returns the number of not-judged rows."""
    n = 0
    for sec in secs.values():
        for t in _tables(sec):
            for r in _rows(t):
                marked = r["judged by"].startswith("not judged: ")
                assert marked == (r["_css"] == jd.NOT_JUDGED_CSS), r
                if marked:
                    assert len(r["judged by"]) > len("not judged: ") + 5  # with the reason
                n += marked
    return n


def test_sections_agree_with_rule_results(result, monkeypatch):
    secs = _sections(result, monkeypatch)
    # BRG-001..004, TV-001/002, DMP-001..003, FAT-001/002 on every item with a value
    assert _check_agreement(result, secs) >= 60
    _check_marking(secs)


def test_agreement_holds_for_any_judged_mask(example, monkeypatch):
    # exclude the speeds of the example's usual worst points (3000..4500 rpm): new worst
    # points, new not-judged rows; the sections follow the mask, whatever it holds
    res = _restrict(api.check(example), (2900.0, 4600.0))
    secs = _sections(res, monkeypatch)
    assert _check_agreement(res, secs) >= 60
    assert _check_marking(secs) > 20
    # e.g. the big ends' full-load peak specific load (45.3 MPa at 3000 rpm) is now shown,
    # marked, after the judged worst
    rows = [r for t in _tables(secs["loads"]) for r in _rows(t)
            if r["bearing"] == "BE1" and r["case"] == "full load"]
    assert [r["_css"] for r in rows] == ["", jd.NOT_JUDGED_CSS]
    assert rows[1]["speed [rpm]"] == "3000" and _num(rows[1]["p [MPa]"]) > _num(
        rows[0]["p [MPa]"])


def test_example_marks_extrapolated_full_load_and_rolling_mode(result, monkeypatch):
    secs = _sections(result, monkeypatch)
    loads = _rows(_tables(secs["loads"])[0])
    sl = result.outcome.quantities["bearing.peak_specific_load"]
    i, ci = sl.coords["item"].index("M3"), sl.coords["case"].index("full")
    j, u = jd.worst(sl, (i, ci), "max")
    if u is None:  # nothing above the judged worst outside the judged points
        pytest.skip("the example has no worse point outside the judged ones")
    m3 = [r for r in loads if r["bearing"] == "M3" and r["case"] == "full load"]
    assert m3[0]["judged by"] == "BRG-001" and m3[1]["_css"] == jd.NOT_JUDGED_CSS
    assert m3[1]["judged by"] == "not judged: " + jd.reason(sl)
    # the TV table: the rule's value first, not a larger not-judged amplitude
    tv = [r for r in _rows(_tables(secs["torsion"])[0]) if r["content"].startswith("order")]
    r1 = next(r for r in result.results if r.rule == "TV-001")
    assert _num(tv[0]["amplitude [°]"]) == pytest.approx(r1.value, rel=6e-4)
    assert all(_num(r["amplitude [°]"]) <= _num(tv[0]["amplitude [°]"])
               for r in tv if r["_css"] == "")


def test_joint_cover_factors_name_the_rules_and_torques(result, monkeypatch):
    secs = _sections(result, monkeypatch)
    table = next(b for b in secs["joints"]["blocks"] if b["type"] == "table"
                 and "used by the rules" in b["columns"])
    rows = {(r["joint"], r["operating point"]): r for r in _rows(table)}
    for rr in result.results:
        if rr.rule in ("JNT-003", "JNT-004", "JNT-005", "JNT-006", "JNT-007"):
            r = rows[(rr.item, rr.case)]
            assert rr.rule in r["rules"].split(", ")
            assert _num(r["cover factor (used T)"]) == pytest.approx(rr.value, rel=6e-4)
    assert rows[("crank nose", "tv peak")]["used by the rules"].startswith("given: 245 N·m")
    assert rows[("crank nose", "tv peak")]["given T [N·m]"].startswith("245 (7100 rpm)")
    comp = result.outcome.quantities["joint.computed_torque"]
    tv_speed = comp.detail.speed[0, 0] / RPM
    assert f"{tv_speed:.0f} rpm" in rows[("crank nose", "tv peak")]["computed T [N·m]"]
    assert rows[("crank nose", "max power")]["rules"] == "none (not judged)"
    # the torsion section's TV-peak speed of the joint is the same quantity's
    tq = next(b for b in secs["torsion"]["blocks"] if b["type"] == "table"
              and "TV torque [N·m]" in b["columns"])
    tv_row = next(r for r in _rows(tq) if (r["joint"], r["operating point"])
                  == ("crank nose", "tv peak"))
    assert tv_row["speed [rpm]"] == f"{tv_speed:.0f}"


# ------------------------------------------------------------------ the helpers themselves

def _quantity(values, applies=None, dims=("item", "case", "speed")) -> Quantity:
    spec = QuantitySpec("test.q", "", dims, "test quantity")
    coords = {d: list(range(n)) for d, n in zip(dims, np.shape(values))}
    coords["item"] = [f"i{k}" for k in range(np.shape(values)[0])]
    coords["case"] = ["full", "no", "part"][:len(coords["case"])]
    coords["speed"] = [k * 100 * RPM for k in coords["speed"]]  # 0, 100, 200 ... rpm
    return Quantity(spec, values, coords, applies=applies,
                    applies_text="outside the test band")


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("check", ["<=", ">="])
def test_worst_locates_the_point_the_rule_names(seed, check, monkeypatch):
    # random values with ties and a random mask: jd.worst picks the rule evaluation's point
    rng = np.random.default_rng(seed)
    vals = rng.integers(0, 6, size=(3, 2, 9)).astype(float)
    applies = rng.random((3, 2, 9)) < 0.5
    applies[:, :, 0] = True
    q = _quantity(vals, applies)
    import checker.evaluation.ruletable as rt

    monkeypatch.setitem(rt.QUANTITIES, "test.q", q.spec)
    rule = Rule(id="TST-001", name="t", quantity="test.q", check=check, unit="", severity="error",
                source="s", rationale="r", limit=(3.0,))
    how = "max" if check == "<=" else "min"
    for res in evaluate_rule(rule, q, None):
        i = q.coords["item"].index(res.item)
        p, _ = jd.worst(q, (i,), how)
        assert p is not None and p.judged and p.value == res.value
        case = ("full load", "no load")[p.index[1]]
        assert res.case == f"{case}, {p.index[2] * 100} rpm"


def test_worst_reports_a_worse_unjudged_point_and_slices():
    vals = np.array([[[1.0, 5.0, 2.0, 9.0]], [[3.0, np.nan, 4.0, 0.5]]])
    q = _quantity(vals, np.array([True, True, True, False]))
    j, u = jd.worst(q, (0, 0), "max")
    assert (j.index, j.value, u.index, u.value, u.judged) == ((0, 0, 1), 5.0, (0, 0, 3), 9.0,
                                                              False)
    j, u = jd.worst(q, (1, 0), "max")
    assert j.value == 4.0 and u is None  # NaN ignored, the unjudged 0.5 is not worse
    j, u = jd.worst(q, (slice(None), 0), "min")
    assert j.index == (0, 0, 0) and u.index == (1, 0, 3)
    assert jd.judged_text(None, q, u) == "not judged: outside the test band"


def test_runs_and_shading():
    assert jd.runs(np.array([1, 0, 0, 1, 0], bool)) == [(1, 2), (4, 4)]
    fig, ax = plots.figure(60, 30)
    x = np.arange(5) * 100.0
    assert jd.shade(ax, x, np.array([1, 1, 1, 0, 0], bool))
    spans = [p for p in ax.patches]
    assert len(spans) == 1
    lo = spans[0].get_x()
    assert (lo, lo + spans[0].get_width()) == (250.0, 450.0)  # half a step beyond the ends
    assert not jd.shade(ax, x, np.ones(5, bool))
    plots.plt.close(fig)


def test_shaded_figure_names_the_reason(result):
    from checker.report.section_loads import bearing_speed_figure, shade_caption

    sl = dataclasses.replace(result.outcome.quantities["bearing.peak_specific_load"])
    sl.applies = jd.mask(sl).copy()
    sl.applies[..., -3:] = False
    png = bearing_speed_figure(result, sl, 1e-6, "p [MPa]", "MPa")
    assert png.texts.count("not judged") == 1  # one legend entry below the panels
    assert jd.reason(sl) in shade_caption(sl)
