"""The example workbooks load from data files (``templates/example_<engine>.toml``) and
``checker template`` writes them cell for cell as recorded in ``tests/workbook/data/``: values,
number formats, fills, fonts, wrap, comments, data validations, column widths, freeze panes
(``scripts/examples_to_data.py`` checks the content itself, int and float apart). The
reference digests were recorded from the workbooks the Python literals wrote before the
examples became data (``scripts/examples_to_data.py``); an intended change of the examples, of
the schema's descriptions or of the writer is recorded with
``python scripts/examples_to_data.py --digest-only``."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.workbook import example_data as ed
from checker.workbook.example import write_workbook
from tests.workbook.template_digest import workbook_digest

DATA = Path(__file__).parent / "data"


def _differences(got: dict, ref: dict) -> list[str]:
    out = []
    if got["properties"] != ref["properties"]:
        out.append(f"properties {got['properties']} != {ref['properties']}")
    names = [s["name"] for s in got["sheets"]]
    ref_names = [s["name"] for s in ref["sheets"]]
    if names != ref_names:
        out.append(f"sheets {names} != {ref_names}")
    for s, r in zip(got["sheets"], ref["sheets"]):
        for k in ("freeze", "widths", "validations"):
            if s[k] != r[k]:
                out.append(f"{s['name']} {k}: {s[k]} != {r[k]}")
        cells = {c[0]: c[1:] for c in s["cells"]}
        ref_cells = {c[0]: c[1:] for c in r["cells"]}
        for ref_c in sorted(set(cells) | set(ref_cells)):
            if cells.get(ref_c) != ref_cells.get(ref_c):
                out.append(f"{s['name']}!{ref_c}: {cells.get(ref_c)} != {ref_cells.get(ref_c)}")
    return out


def _reference(engine: str) -> dict:
    return json.loads((DATA / f"template_{engine}.json").read_text(encoding="utf-8"))


def _json_round(dg: dict) -> dict:
    """The digest as the JSON file holds it (tuples become lists)."""
    return json.loads(json.dumps(dg, ensure_ascii=False))


@pytest.mark.parametrize("engine", ed.ENGINES)
def test_template_unchanged_cell_for_cell(engine, tmp_path):
    p = tmp_path / "engine.xlsx"
    r = CliRunner().invoke(main, ["template", str(p), "--engine", engine])
    assert r.exit_code == 0, r.output
    diffs = _differences(_json_round(workbook_digest(p)), _reference(engine))
    assert not diffs, f"{len(diffs)} differences, first: " + "\n".join(diffs[:10])


@pytest.mark.parametrize("engine", ed.ENGINES)
def test_data_file_writes_the_reference_workbook(engine, tmp_path):
    p = tmp_path / "engine.xlsx"
    write_workbook(p, ed.load_example(engine))
    diffs = _differences(_json_round(workbook_digest(p)), _reference(engine))
    assert not diffs, f"{len(diffs)} differences, first: " + "\n".join(diffs[:10])


def test_digest_sees_a_changed_cell(tmp_path):
    """The comparison is not blind: one changed value and one lost highlight are found."""
    content = ed.load_example("i4")
    eng = content["Engine"]
    i = next(k for k, row in enumerate(eng) if row[0] == "Bore")
    content["Engine"] = eng[:i] + [(eng[i][0], 86.5, eng[i][2], eng[i][3])] + eng[i + 1:]
    j = next(k for k, row in enumerate(eng) if "ASSUMPTION" in row[3])
    content["Engine"][j] = content["Engine"][j][:3] + ("assumed elsewhere",)
    p = tmp_path / "engine.xlsx"
    write_workbook(p, content)
    diffs = _differences(_json_round(workbook_digest(p)), _reference("i4"))
    assert any(d.startswith(f"Engine!B{i + 2}:") for d in diffs), diffs  # 86.0 -> 86.5
    assert any(d.startswith(f"Engine!D{j + 2}:") for d in diffs), diffs
    assert any(d.startswith(f"Engine!B{j + 2}:") for d in diffs), diffs  # fill gone


@pytest.mark.parametrize("engine", ed.ENGINES)
def test_data_files_are_in_canonical_form(engine):
    """Each file is what the writer makes of its own content (the scripts rewrite it so)."""
    text = ed.example_file(engine).read_text(encoding="utf-8")
    assert ed.rewrite_example(engine, ed.load_example(engine)) == text


def test_table_row_with_an_unknown_column_is_named():
    data = tomllib.loads('[Joints]\ncolumns = [["name", "-"]]\n[[Joints.rows]]\nnme = "x"\n')
    with pytest.raises(ValueError, match=r"Joints row 1: no column \['nme'\]"):
        ed.content_from_data(data)


def test_writer_refuses_what_toml_cannot_hold():
    with pytest.raises(ValueError, match="Engine row 1"):
        ed.dumps_example({"Engine": [("Bore", float("nan"), "mm", "")]})
    with pytest.raises(ValueError, match="Bearings row 1: 1 values for 2 columns"):
        ed.dumps_example({"Bearings": ([("name", "-"), ("note", "")], [["M1"]])})


def test_variants_follow_from_the_data():
    """The I6 without its assumed damper ring and the V8 with one station per cylinder, as
    the tests use them."""
    from checker.workbook.example_i6 import i6_content
    from checker.workbook.example_v8 import v8_content

    i6 = ed.load_example("i6")
    assert not ed.same_content(i6_content(damper_ring=True), i6)
    plain = i6_content()
    assert not ed.same_content(plain, ed.without_tv_role(i6, "damper ring"))
    assert len(plain["TVModel"][1]) == len(i6["TVModel"][1]) - 1
    v8 = ed.load_example("v8")
    assert not ed.same_content(v8_content(), v8)
    split = v8_content(split_stations=True, link=1e13)
    stations = split["TVModel"][1]
    assert len(stations) == len(v8["TVModel"][1]) + 4
    assert [r[2] for r in stations if r[1] == "cylinder"] == list(range(1, 9))


def test_loaded_content_is_a_fresh_copy():
    """Tests edit the content they load; the next load is unaffected."""
    a = ed.load_example("i4")
    a["Engine"].clear()
    a["Bearings"][1][0][0] = "X"
    a["Notes"].append("x")
    ed.read_example("i4")["Engine"].clear()
    b = ed.load_example("i4")
    assert b["Engine"] and b["Bearings"][1][0][0] == "M1" and "x" not in b["Notes"]
