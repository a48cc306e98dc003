"""Parametric studies: variants equal single checks, fail-soft, resume, Dask equals local."""

from __future__ import annotations

import json

import openpyxl
import pytest
from click.testing import CliRunner

from checker import api
from checker.cli import main
from checker.outputs.formats import to_json
from checker.study.design import variants
from checker.study.results import tidy
from checker.study.run import run_study
from checker.study.spec import StudyFileError, load_study
from tests.helpers import example_path, set_cell

STUDY = """
[study]
name = "crank-nose bolt torque"
design = "one-at-a-time"
select = ["JNT-001", "JNT-002", "JNT-003"]

[[parameter]]
name = "nose torque"
sheet = "Joints"
row = "crank nose"
column = "tightening torque"
unit = "N m"
values = [300, 330, -5]

[[parameter]]
name = "nose friction"
sheet = "Joints"
row = "crank nose"
column = "friction coefficient"
unit = "-"
values = [0.15, 0.3]
"""


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    d = tmp_path_factory.mktemp("study")
    wb = example_path(d)
    st = d / "study.toml"
    st.write_text(STUDY, encoding="utf-8")
    return d, wb, st


def _single(tmp, wb, changes, name):
    book = openpyxl.load_workbook(wb)
    for col, v in changes.items():
        set_cell(book, "Joints", "name", "crank nose", col, v)
    p = tmp / name
    book.save(p)
    return api.check(p, select=["JNT-001", "JNT-002", "JNT-003"])


def test_one_at_a_time_equals_single_checks_and_is_fail_soft(setup, tmp_path):
    d, wb, st = setup
    run = run_study(load_study(st), wb, tmp_path / "out", workers=1)
    assert [r["name"] for r in run.records] == [
        "baseline", "nose torque = 300 N m", "nose torque = 330 N m", "nose torque = -5 N m",
        "nose friction = 0.15 -", "nose friction = 0.3 -"]
    bad = run.records[3]
    assert bad["status"] == "input error"
    assert any("Joints!" in e and "tightening torque" in e.lower() for e in bad["errors"])
    for rec, changes in [(run.records[0], {}),
                         (run.records[2], {"tightening torque": 330}),
                         (run.records[5], {"friction coefficient": 0.3})]:
        single = _single(tmp_path, wb, changes, f"v{rec['index']}.xlsx")
        want = json.loads(to_json(single, timings=False))["results"]
        assert rec["results"] == want
    df = tidy(run)
    assert (df["status"] == "input error").sum() == 1
    assert set(df["rule"]) >= {"JNT-001", "JNT-002", "JNT-003"}


def test_resume_skips_done_variants(setup, tmp_path):
    d, wb, st = setup
    out = tmp_path / "out"
    first = run_study(load_study(st), wb, out, workers=1)
    assert first.computed == 6
    (out / "variants" / f"{first.records[1]['id']}.json").unlink()
    again = run_study(load_study(st), wb, out, workers=1)
    assert again.computed == 1
    def strip(recs):
        return [{k: v for k, v in r.items() if k != "seconds"} for r in recs]

    assert strip(again.records) == strip(first.records)


def test_local_cluster_equals_local(setup, tmp_path):
    pytest.importorskip("distributed")
    d, wb, st = setup
    a = run_study(load_study(st), wb, tmp_path / "a", workers=2)
    b = run_study(load_study(st), wb, tmp_path / "b", workers=2, dask="local")
    assert b.engine == "dask"
    ta, tb = tidy(a), tidy(b)
    assert ta.to_csv(index=False) == tb.to_csv(index=False)


def test_study_file_errors_name_lines(setup, tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('[study]\ndesign = "lhs"\nsamples = 1\n\n[[parameter]]\nsheet = "Bearings"\n'
                 'row = "M3"\ncolumn = "radial clearence"\nunit = "um"\nrange = [20, 10]\n',
                 encoding="utf-8")
    with pytest.raises(StudyFileError) as e:
        load_study(p)
    text = str(e.value)
    assert "line 3" in text and "samples" in text
    assert "line 8" in text and "radial clearence" in text


def test_latin_hypercube_is_seeded(tmp_path):
    p = tmp_path / "lhs.toml"
    p.write_text('[study]\ndesign = "latin-hypercube"\nsamples = 8\nseed = 3\n\n'
                 '[[parameter]]\nsheet = "Engine"\nrow = "Bore"\nunit = "mm"\nrange = [78, 84]\n',
                 encoding="utf-8")
    a, b = variants(load_study(p)), variants(load_study(p))
    assert a == b and len(a) == 8
    xs = sorted(v.values[0][1] for v in a)
    # one sample in each of the 8 strata of the range
    assert [int((x - 78) / 6 * 8) for x in xs] == list(range(8))


def test_cli_study_writes_tables_and_pdf(setup, tmp_path):
    d, wb, st = setup
    out = tmp_path / "cli"
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out), "--workers", "1"])
    assert r.exit_code == 0, r.output
    for f in ("results.parquet", "results.xlsx", "study.pdf"):
        assert (out / f).is_file()
    import pandas as pd

    df = pd.read_parquet(out / "results.parquet")
    assert {"variant", "nose torque", "rule", "item", "value", "margin", "status"} <= set(df)


def test_compare_shows_joint_status_change_first(setup, tmp_path):
    d, wb, st = setup
    book = openpyxl.load_workbook(wb)
    # 400 -> 362 N m: preload 79.5 -> 72 % of proof (JNT-001 passes), head stress still > 500
    set_cell(book, "Joints", "name", "crank nose", "tightening torque", 362)
    v = tmp_path / "variant.xlsx"
    book.save(v)
    r = CliRunner().invoke(main, ["compare", str(wb), str(v), "--select", "JNT-00",
                                  "--ignore", "JNT-006,JNT-007", "--format", "json"])
    d = json.loads(r.stdout)
    c = d["comparisons"][0]
    assert c["input_changes"][0]["cell"].startswith("Joints!")
    first = c["result_changes"][0]
    assert first["rule"] == "JNT-001" and first["change"] == "newly passing"
    assert all(x["change"] == "margin changed" for x in c["result_changes"][1:])
    pdf = tmp_path / "pack.pdf"
    r = CliRunner().invoke(main, ["compare", str(wb), str(v), "--select", "JNT-00",
                                  "--ignore", "JNT-006,JNT-007", "-o", str(pdf)])
    assert pdf.is_file() and r.exit_code == 0, r.output
