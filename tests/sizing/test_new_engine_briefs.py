"""checker new on the briefs of issue 47 (I3, I4, a bore >= 120 mm I6 diesel, 60-degree V6 on
shared and split pins, 90-degree V8 cross- and flat-plane, V12, 270-degree twin, and a genset's
and a marine engine's I6, whose class rules judge misfire): each sizes
open loop into a workbook the check accepts, with no result left not evaluated, the firing
intervals of its crank type; brief errors give their line; synonyms are documented."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from checker import api
from checker.sizing.brief import CHOICES, load_brief
from checker.sizing.project_limits import SUPPLIER_RULES

BRIEFS = {
    "i3": ('cylinders = 3\nbore = "71.9 mm"\nstroke = "82 mm"\nrated_power = "92 kW"\n'
           'rated_speed = "6000 rpm"\npeak_pressure = "120 bar"\n', [240.0] * 3),
    "i4": ('cylinders = 4\nbore = "86 mm"\nstroke = "94.6 mm"\nrated_power = "110 kW"\n'
           'rated_speed = "6000 rpm"\nmax_speed = "7000 rpm"\n', [180.0] * 4),
    "i6_diesel": ('cylinders = 6\nbore = "130 mm"\nstroke = "160 mm"\nrated_power = "330 kW"\n'
                  'rated_speed = "1900 rpm"\nmax_speed = "2100 rpm"\nmin_speed = "600 rpm"\n'
                  'fuel = "diesel"\n', [120.0] * 6),
    "v6_shared": ('cylinders = 6\nlayout = "V"\nbank_angle = "60 deg"\nbore = "94 mm"\n'
                  'stroke = "84 mm"\nrated_power = "150 kW"\nrated_speed = "5600 rpm"\n',
                  [60.0, 120.0, 120.0, 120.0, 120.0, 180.0]),
    "v6_split": ('cylinders = 6\nlayout = "V"\nbank_angle = "60 deg"\ncrank_type = "split'
                 ' pins"\nbore = "94 mm"\nstroke = "84 mm"\nrated_power = "150 kW"\n'
                 'rated_speed = "5600 rpm"\n', [120.0] * 6),
    "v8_cross": ('cylinders = 8\nlayout = "V"\nbank_angle = "90 deg"\ncrank_type = "cross-plane"'
                 '\nbore = "99 mm"\nstroke = "92 mm"\nrated_power = "257 kW"\n'
                 'rated_speed = "5600 rpm"\nmax_speed = "6500 rpm"\n', [90.0] * 8),
    "v8_flat": ('cylinders = 8\nlayout = "V"\nbank_angle = "90 deg"\ncrank_type = "flat-plane"\n'
                'bore = "94 mm"\nstroke = "81 mm"\nrated_power = "400 kW"\n'
                'rated_speed = "8000 rpm"\nmax_speed = "8500 rpm"\n', [90.0] * 8),
    "v12": ('cylinders = 12\nlayout = "V"\nbank_angle = "60 deg"\nbore = "89 mm"\n'
            'stroke = "80 mm"\nrated_power = "450 kW"\nrated_speed = "7000 rpm"\n', [60.0] * 12),
    "twin_270": ('cylinders = 2\ncrank_type = "270 deg"\nbore = "84 mm"\nstroke = "61 mm"\n'
                 'rated_power = "55 kW"\nrated_speed = "8000 rpm"\nmax_speed = "8500 rpm"\n',
                 [270.0, 450.0]),
    "i6_genset": ('cylinders = 6\nbore = "137 mm"\nstroke = "169 mm"\nrated_power = "400 kW"\n'
                  'rated_speed = "1500 rpm"\nfuel = "diesel"\nengine_class = "genset"\n',
                  [120.0] * 6),
    "i6_marine": ('cylinders = 6\nbore = "200 mm"\nstroke = "280 mm"\nrated_power = "1200 kW"\n'
                  'rated_speed = "1000 rpm"\nfuel = "diesel"\nengine_class = "marine"\n',
                  [120.0] * 6),
}


def _new(tmp_path: Path, name: str, text: str) -> subprocess.CompletedProcess:
    brief = tmp_path / f"{name}.toml"
    brief.write_text(text)
    return subprocess.run([sys.executable, "-m", "checker", "new", str(tmp_path / f"{name}.xlsx"),
                           "--brief", str(brief), "--no-iterate"], capture_output=True, text=True)


@pytest.mark.parametrize("name", sorted(BRIEFS))
def test_brief_sizes_and_every_rule_is_judged(tmp_path, name):
    text, gaps = BRIEFS[name]
    r = _new(tmp_path, name, text)
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    res = api.check(str(tmp_path / f"{name}.xlsx"))  # geometry the check would refuse raises
    cls = res.engine.params.get("engine_class")
    left = [x for x in res.results if x.status == "not_evaluated"]
    assert not left, [(x.rule, x.item, x.message) for x in left]
    na = [x for x in res.results if x.status == "not_applicable" and "RuleOverrides" in
          x.message]
    supplier = set(SUPPLIER_RULES)  # the rubber's heat with a misfire (MIS-001) among them
    nose = {"TV-001", "TV-002", "TV-003"} if cls == "commercial vehicle" else set()
    assert {x.rule for x in na} <= supplier | nose
    assert all("supplier" in x.message for x in na if x.rule in supplier)
    assert all("TV-009" in x.message for x in na if x.rule in nose)
    if cls == "commercial vehicle":
        assert {x.rule for x in res.results if x.rule == "TV-009"}  # its crank stress judged
    # the firing intervals of the crank type (cylinder firing angles of the workbook)
    f = np.sort(np.degrees([c.firing_angle for c in res.engine.cylinders]) % 720.0)
    got = np.diff(np.append(f, f[0] + 720.0))
    assert sorted(np.round(got, 6)) == sorted(gaps)
    uneven = [c for c in res.caveats if c["kind"] == "uneven firing"]
    assert bool(uneven) == (len(set(gaps)) > 1)
    if uneven:
        assert "warning: " in r.stderr and "even firing is impossible" in r.stderr


def test_brief_errors_give_the_line(tmp_path):
    r = _new(tmp_path, "bad", 'name = "x"\ncylinders = 4\nbore = "86 kg"\nstroke = "94.6 mm"\n'
             'rated_power = "110 kW"\nrated_speed = "6000 rpm"\ncrank_type = "flat-plane"\n'
             'fuel = "kerosene"\n')
    assert r.returncode == 2 and not (tmp_path / "bad.xlsx").exists()
    for text in ("bad.toml:3: bore: expected a length", "bad.toml:8: fuel: expected"):
        assert text in r.stderr, (text, r.stderr)
    assert "Traceback" not in r.stderr
    # the cross-checks of keys run once every key reads (each problem once)
    r = _new(tmp_path, "bad", 'name = "x"\ncylinders = 4\nbore = "86 mm"\nstroke = "94.6 mm"\n'
             'rated_power = "110 kW"\nrated_speed = "6000 rpm"\ncrank_type = "flat-plane"\n')
    assert r.returncode == 2
    assert "bad.toml:7: crank_type: flat-plane is a crank of V8 engines" in r.stderr


def test_synonyms_are_documented_and_others_refused(tmp_path):
    doc = (Path(__file__).parents[2] / "docs" / "new-engine.md").read_text()
    for key in ("fuel", "engine_class", "crank_type"):
        for word in CHOICES[key]:
            assert f"`{word}`" in doc, (key, word)
    p = tmp_path / "b.toml"
    p.write_text('cylinders = 4\nbore = "86 mm"\nstroke = "94.6 mm"\nrated_power = "110 kW"\n'
                 'rated_speed = "6000 rpm"\nfuel = "petrol"\nengine_class = "car"\n')
    b = load_brief(p)
    assert b.fuel == "gasoline" and b.engine_class == "passenger car"
    p.write_text(p.read_text().replace('"petrol"', '"benzin"'))
    r = subprocess.run([sys.executable, "-m", "checker", "new", str(tmp_path / "b.xlsx"),
                        "--brief", str(p)], capture_output=True, text=True)
    assert r.returncode == 2 and "b.toml:6: fuel: expected" in r.stderr


def test_v_twin_crank_type_needs_its_bank_angle(tmp_path):
    r = _new(tmp_path, "vt", 'cylinders = 2\nlayout = "V"\nbank_angle = "60 deg"\n'
             'crank_type = "270 deg"\nbore = "84 mm"\nstroke = "61 mm"\nrated_power = "55 kW"'
             '\nrated_speed = "8000 rpm"\n')
    assert r.returncode == 2 and 'needs bank_angle = "90 deg"' in r.stderr


def test_geometry_the_check_refuses_is_never_written(tmp_path, capsys):
    """The LS1-like brief's counterweight once came out thicker than its web with an inner
    radius rounded inside the journal (refused at Crank!N3); the command now reads the sized
    workbook as the check will before writing it."""
    from checker.cli import _refused_by_the_check
    from checker.sizing.brief import parse_brief
    from checker.sizing.new_engine import size
    from checker.workbook.example import write_workbook

    b = parse_brief({"cylinders": 8, "layout": "V", "bank_angle": "90 deg", "bore": "99 mm",
                     "stroke": "92 mm", "rated_power": "257 kW", "rated_speed": "5600 rpm",
                     "crank_material": "nodular iron"})
    lay, content = size(b)
    cols, [row] = content["Crank"]
    names = [c for c, _u in cols]
    assert row[names.index("counterweight inner radius")] >= row[
        names.index("main journal diameter")] / 2  # clear of the journal as written
    good = tmp_path / "good.xlsx"
    write_workbook(good, content)
    _refused_by_the_check(good)  # accepted: returns
    row = list(row)
    row[names.index("counterweight thickness")] = row[names.index("web thickness")] * 1.5
    row[names.index("counterweight inner radius")] = row[names.index("main journal diameter")] / 3
    bad = tmp_path / "bad.xlsx"
    write_workbook(bad, {**content, "Crank": (cols, [row])})
    with pytest.raises(SystemExit) as exc:
        _refused_by_the_check(bad)
    assert exc.value.code == 2
    assert "must clear the main journal" in capsys.readouterr().err
