"""Choice columns: a value outside the allowed set is an input error with the cell, the allowed
values and a "did you mean" suggestion; spellings are mapped in one place (the schema); the rule
table's ``limits`` keys are allowed values of the attribute they are keyed by."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.workbook.schema import (
    CHOICE_SETS,
    CLAMPED_MATERIALS,
    LININGS,
    SHEETS,
    ChoiceProblem,
    choice_field,
    choice_key,
    resolve_choice,
)
from tests.helpers import edited, set_cell, set_param

RULES = Path(__file__).resolve().parents[2] / "rules"


def _errors(path) -> list[str]:
    with pytest.raises(InputErrors) as info:
        load_engine(path)
    return [str(e) for e in info.value.errors]


def test_lining_typo_is_an_error_with_cell_choices_and_suggestion(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault(
        "c", set_cell(wb, "Bearings", "name", "BE2", "lining", "AS61")))
    errs = _errors(p)
    assert len(errs) == 1
    e = errs[0]
    assert e.startswith(cell["c"] + ":"), e
    assert "'as15', 'as16', 'aluminium bimetal', 'tri-metal', 'sputter', 'polymer'" in e
    assert "found 'AS61'" in e and "did you mean 'as1" in e


@pytest.mark.parametrize("sheet,key,col,value,expect", [
    ("Joints", "flywheel", "tightening", "yeild controlled", "yield controlled"),
    ("Joints", "flywheel", "location", "flywhel", "flywheel"),
    ("Joints", "crank nose", "clamped material", "stel", "steel"),
    ("TVModel", "Flywheel", "role", "flywheels", "flywheel"),
    ("Bearings", "M1", "groove", "partal", "partial"),
    ("Bearings", "M1", "type", "mian", "main"),
    ("CrankMass", "Web1", "kind", "wbe", "web"),
])
def test_every_choice_column_suggests(tmp_path, sheet, key, col, value, expect):
    key_col = {"TVModel": "station", "CrankMass": "location"}.get(sheet, "name")
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(wb, sheet, key_col, key, col,
                                                                   value)))
    errs = _errors(p)
    assert any(e.startswith(cell["c"] + ":") and f"did you mean '{expect}'?" in e
               for e in errs), errs


def test_parameter_choice_typo(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_param(
        wb, "Engine", "Crankshaft rotation", value="clokwise")))
    errs = _errors(p)
    assert any(e.startswith(cell["c"]) and "did you mean 'clockwise'?" in e for e in errs)


@pytest.mark.parametrize("spelling,choice", [
    ("AS16", "as16"), ("as 16", "as16"), ("As-15", "as15"), ("trimetal", "tri-metal"),
    ("Tri Metal", "tri-metal"), ("TRI-METAL", "tri-metal"), ("sputtered", "sputter"),
    ("Sputter", "sputter"), ("aluminum bimetal", "aluminium bimetal"), ("polymer", "polymer"),
])
def test_lining_spellings(spelling, choice):
    assert resolve_choice(choice_field("lining"), spelling) == choice


@pytest.mark.parametrize("spelling,choice", [
    ("Steel", "steel"), ("grey iron", "grey cast iron"), ("Gray cast iron", "grey cast iron"),
    ("EN-GJL", "grey cast iron"), ("ductile iron", "nodular cast iron"),
    ("SG iron", "nodular cast iron"), ("aluminum", "aluminium"),
])
def test_clamped_material_spellings(spelling, choice):
    assert resolve_choice(choice_field("clamped_material"), spelling) == choice


def test_cast_iron_is_refused_as_ambiguous(tmp_path):
    """'cast iron' could be grey (850 N/mm^2) or nodular (600 N/mm^2): never guess."""
    with pytest.raises(ChoiceProblem, match="ambiguous.*'grey cast iron', 'nodular cast iron'"):
        resolve_choice(choice_field("clamped_material"), "Cast Iron")
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault(
        "c", set_cell(wb, "Joints", "name", "flywheel", "clamped material", "cast iron")))
    errs = _errors(p)
    assert len(errs) == 1 and errs[0].startswith(cell["c"]) and "ambiguous" in errs[0]


def test_accepted_spellings_reach_the_engine(tmp_path):
    def edit(wb):
        set_cell(wb, "Bearings", "name", "M1", "lining", "Tri Metal")
        set_cell(wb, "Bearings", "name", "BE1", "lining", "sputtered")
        set_cell(wb, "Joints", "name", "flywheel", "clamped material", "Grey iron")
        set_cell(wb, "Joints", "name", "flywheel", "tightening", "Yield")
        set_cell(wb, "Bearings", "name", "BE2", "type", "Big-End")

    e = load_engine(edited(tmp_path, edit))
    lin = {b.name: b.lining for b in e.bearings}
    assert lin["M1"] == "tri-metal" and lin["BE1"] == "sputter" and lin["M2"] == "as16"
    fw = next(j for j in e.joints if j.name == "flywheel")
    assert fw.clamped_material == "grey cast iron" and fw.tightening == "yield controlled"
    assert next(b for b in e.bearings if b.name == "BE2").type == "big end"


def test_property_class_number_cell(tmp_path):
    """A property class typed as a number (10.9, 12.9) is the same choice as the text."""
    e = load_engine(edited(tmp_path, lambda wb: set_cell(wb, "Joints", "name", "flywheel",
                                                         "property class", 12.9)))
    assert next(j for j in e.joints if j.name == "flywheel").property_class == "12.9"


def test_lining_and_clamped_material_are_choices():
    assert choice_field("lining").choices == LININGS
    assert choice_field("clamped_material").choices == CLAMPED_MATERIALS
    for name in ("lining", "clamped_material", "case", "point", "tightening", "location",
                 "property_class", "type", "role", "mobility_model"):
        assert name in CHOICE_SETS


def test_aliases_and_choices_are_unambiguous():
    """No two choices of a field (or an alias and another choice) share a spelling key, and no
    ambiguous spelling is also accepted."""
    for sheet in SHEETS.values():
        for f in sheet.fields:
            if f.kind != "choice":
                continue
            keys = [choice_key(c) for c in f.choices]
            assert len(set(keys)) == len(keys), f.label
            for spelling, target in f.aliases:
                assert target in f.choices, (f.label, spelling)
                k = choice_key(spelling)
                assert k not in keys or f.choices[keys.index(k)] == target, (f.label, spelling)
            for spelling, options in f.ambiguous:
                assert set(options) <= set(f.choices)
                with pytest.raises(ChoiceProblem):
                    resolve_choice(f, spelling)


def _rules() -> list[dict]:
    out = []
    for path in sorted(RULES.glob("*.toml")):
        out += tomllib.loads(path.read_text()).get("rule", [])  # levers.toml: [[lever]]
    return out


def test_rule_limits_keys_are_allowed_choice_values():
    """Every ``limits`` key of a ``limit_by`` rule is an allowed value of that attribute, so a
    workbook value that passes the loader always finds its limit (and no limit is dead)."""
    keyed = [r for r in _rules() if "limit_by" in r]
    assert {r["limit_by"] for r in keyed} >= {"lining", "clamped_material"}
    for r in keyed:
        allowed = CHOICE_SETS[r["limit_by"]]
        for k in r["limits"]:
            assert k in allowed, (r["id"], k, allowed)
        if r["limit_by"] in ("lining", "clamped_material"):  # a limit for every allowed value
            assert set(allowed) <= set(r["limits"]), (r["id"], set(allowed) - set(r["limits"]))


def test_rule_where_values_are_allowed_choice_values():
    for r in _rules():
        for attr, val in r.get("where", {}).items():
            if attr in CHOICE_SETS:
                vals = val if isinstance(val, list) else [val]
                assert set(vals) <= set(CHOICE_SETS[attr]), (r["id"], attr, vals)
