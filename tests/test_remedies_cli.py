"""`checker check --remedies --corners`: JSON blocks, text lines, exit code at the corners."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from checker.cli import main


def _workbook(path, tolerances):
    from checker.workbook import example

    content = example.example_content()
    cols, _ = content["Tolerances"]
    content["Tolerances"] = (cols, tolerances)
    example.write_workbook(path, content)
    return path


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_corners_verdict_fails_a_result_passing_at_nominal(tmp_path):
    # counterweights +-30 %: the balance ratio (82 %) leaves 50..100 % at the heavy end
    wb = _workbook(tmp_path / "e.xlsx", [
        ["CrankMass", "kind = counterweight", "mass", -30, 30, "% of nominal", "test"]])
    # BAL-005 is a warning: --fail-on warning makes it count for the verdict
    plain = run("check", wb, "--select", "BAL-005", "--format", "json", "--no-timings",
                "--fail-on", "warning")
    assert plain.exit_code == 0, plain.output
    r = run("check", wb, "--select", "BAL-005", "--corners", "--format", "json",
            "--no-timings", "--fail-on", "warning")
    assert r.exit_code == 1, r.output
    d = json.loads(r.output)
    assert d["verdict"] == "pass" and d["corners"]["verdict"] == "fail"
    crank = next(x for x in d["results"] if x["item"] == "crank")
    assert crank["corner"]["nominal"]["status"] == "pass"
    assert crank["corner"]["worst"]["status"] == "fail"
    assert crank["corner"]["worst"]["at"][0].startswith(
        "CrankMass mass (kind = counterweight) max")
    # every counterweight 30 % heavier: the balance ratio 30 % higher
    assert crank["corner"]["worst"]["value"] == pytest.approx(
        1.3 * crank["corner"]["nominal"]["value"], rel=1e-4)
    # deterministic without timings
    again = run("check", wb, "--select", "BAL-005", "--corners", "--format", "json",
                "--no-timings", "--fail-on", "warning")
    assert again.output == r.output


def test_remedies_text_and_json(tmp_path):
    wb = _workbook(tmp_path / "e.xlsx", [])
    r = run("check", wb, "--select", "JNT-002", "--remedies")
    assert r.exit_code == 1
    assert "What it takes to pass" in r.output
    assert "Tightening torque 400 N·m → 360.7 N·m" in r.output
    j = run("check", wb, "--select", "JNT-002", "--remedies", "--format", "json",
            "--no-timings")
    d = json.loads(j.output)
    nose = next(x for x in d["results"] if x["item"] == "crank nose")
    assert nose["what_it_takes"].startswith("To pass:")
    assert {x["lever"] for x in nose["remedies"]} >= {"joint-tightening-torque",
                                                      "joint-bolt-size"}
    assert "seconds" not in d["remedies"]


def test_bad_lever_file_is_exit_2(tmp_path):
    wb = _workbook(tmp_path / "e.xlsx", [])
    bad = tmp_path / "l.toml"
    bad.write_text("[[lever]]\nid = \"x\"\n", encoding="utf-8")
    r = run("check", wb, "--select", "JNT-002", "--remedies", "--levers", bad)
    assert r.exit_code == 2
    assert "lever x" in r.output
