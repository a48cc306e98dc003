"""End-to-end CLI: exit codes, output formats, selection, the example's joint verdicts."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest
from click.testing import CliRunner

from checker.cli import main
from tests.helpers import compliant_joints, edited, example_path, fresh_python


@pytest.fixture()
def example(tmp_path):
    return example_path(tmp_path)


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_template_writes_and_refuses_overwrite(tmp_path):
    p = tmp_path / "e.xlsx"
    assert run("template", p).exit_code == 0 and p.exists()
    r = run("template", p)
    assert r.exit_code == 2 and "--force" in r.output
    assert run("template", p, "--force").exit_code == 0


def test_example_joints_fail_with_named_rules(example):
    r = run("check", example, "--select", "JNT")
    assert r.exit_code == 1
    lines = {tuple(line.split()[:2]) for line in r.stdout.splitlines() if line.strip()}
    # seed 000: crank nose above proof-stress (79.5 %) and head pressure (554.5 N/mm^2)
    # guidelines and below cover factor 1.8 (1.467); flywheel 1.771 < 1.8 at the TV peak
    for rule in ("JNT-001", "JNT-002", "JNT-003", "JNT-005"):
        assert (rule, "FAIL") in lines, r.stdout
    assert ("JNT-004", "WARN") in lines


def test_compliant_joints_exit_zero(tmp_path):
    p = edited(tmp_path, compliant_joints)
    r = run("check", p, "--select", "JNT", "--format", "json")
    assert r.exit_code == 0, r.stdout
    d = json.loads(r.stdout)
    assert d["verdict"] == "pass"
    assert all(x["status"] != "fail" for x in d["results"])


def test_json_format_stable_keys_and_deterministic(example):
    a = run("check", example, "--format", "json", "--no-timings", "--select", "JNT")
    b = run("check", example, "--format", "json", "--no-timings", "--select", "JNT")
    assert a.stdout == b.stdout  # byte-identical without run times
    d = json.loads(a.stdout)
    assert d["verdict"] == "fail" and "timings" not in d
    for res in d["results"]:
        assert {"rule", "item", "status", "value", "unit", "limit"} <= set(res)
        assert res["status"] in ("pass", "fail", "not_evaluated", "not_applicable")
    cn = next(x for x in d["results"] if x["rule"] == "JNT-001")
    assert cn["item"] == "crank nose" and cn["value"] == pytest.approx(79.507, abs=5e-4)
    assert cn["limit"] == [70.0, 75.0] and cn["unit"] == "%"
    t = json.loads(run("check", example, "--format", "json", "--select", "JNT").stdout)
    assert "joints" in t["timings"]


def test_not_evaluated_names_missing_inputs(example, tmp_path):
    d = json.loads(run("check", example, "--format", "json", "--select", "JNT").stdout)
    fw_head = next(x for x in d["results"] if x["rule"] == "JNT-002" and x["item"] == "flywheel")
    assert fw_head["status"] == "not_evaluated"
    assert any("head bearing outer diameter" in m and "Joints!N4" in m for m in fw_head["missing"])
    # without brake torque the max-power point (and so its joint torque) is unknown
    p = edited(tmp_path, lambda wb: wb.remove(wb["BrakeTorque"]), "nobrake.xlsx")
    d = json.loads(run("check", p, "--format", "json", "--select", "JNT").stdout)
    fw_power = next(x for x in d["results"] if x["rule"] == "JNT-006")
    assert fw_power["status"] == "not_evaluated" and "max power" in fw_power["missing"][0]
    assert "BrakeTorque" in fw_power["missing"][0]


def test_junit_format(example):
    r = run("check", example, "--format", "junit", "--select", "JNT")
    assert r.exit_code == 1
    root = ET.fromstring(r.stdout)
    cases = root.findall(".//testcase")
    # JNT-001..007 and JNT-008 for both joints, and JNT-001 not applicable to the
    # yield-controlled flywheel joint (issue 37)
    assert len(cases) == 11
    failed = [c.get("name") for c in cases if c.find("failure") is not None]
    assert any(n.startswith("JNT-003") for n in failed)
    skipped = [c for c in cases if c.find("skipped") is not None]
    # flywheel head stress: bolt head diameters not in the seed; JNT-001 flywheel not applicable
    assert len(skipped) == 2
    assert sum(c.find("skipped").get("message").startswith("not applicable: ")
               for c in skipped) == 1


def test_fail_on_warning(tmp_path):
    def edit(wb):
        compliant_joints(wb)
        from tests.helpers import set_cell
        set_cell(wb, "Joints", "name", "crank nose", "friction coefficient", 0.27)

    p = edited(tmp_path, edit)  # crank-nose CF ~1.85: meets 1.8, misses the preferred 2.0
    assert run("check", p, "--select", "JNT").exit_code == 0
    assert run("check", p, "--select", "JNT", "--fail-on", "warning").exit_code == 1


def test_usage_errors_exit_2(example, tmp_path):
    assert run("check", example, "--select", "XYZ").exit_code == 2
    assert run("check", tmp_path / "missing.xlsx").exit_code == 2
    assert run("check", example, "--format", "yaml").exit_code == 2
    assert run("rules", "--explain", "JNT-999").exit_code == 2
    assert run("frobnicate").exit_code == 2


def test_rules_listing_and_explain():
    r = run("rules")
    assert r.exit_code == 0 and "JNT-003" in r.stdout
    e = run("rules", "--explain", "JNT-003")
    assert "Bell" in e.stdout and "Ricardo" in e.stdout and "tv peak" in e.stdout
    assert "seed" not in e.stdout.lower() and "shared/" not in e.stdout


def test_bad_rule_file_exit_2(example, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[[rule]]\nid = "JNT-1"\nname = "x"\n')
    r = run("check", example, "--rules", bad)
    assert r.exit_code == 2 and "rule table" in r.stderr


def test_report_pdf_and_html(example, tmp_path):
    from pypdf import PdfReader

    pdf, html = tmp_path / "r.pdf", tmp_path / "r.html"
    r = run("report", example, "-o", pdf, "--html", html, "--select", "JNT", "--no-progress")
    assert r.exit_code == 1, r.output
    text = "\n".join(p.extract_text() for p in PdfReader(pdf).pages)
    assert "FAIL" in text and "JNT-003" in text and "Bolted joints" in text
    # Bell, Ricardo 2013, 'Crankshaft analysis (23)' and (24), to the report's 4 digits
    assert "79.51" in text and "554.5" in text and "359.5" in text
    assert "64.49" in text and "67.47" in text and "2154" in text
    assert "Page 1 of" in text
    # figures are raster images (the PDF engine draws vector figures in pure Python: seconds
    # per report); their captions are text
    assert "Joint cover factors coloured by the result" in text
    assert any(p.images for p in PdfReader(pdf).pages)
    outline = [o.title for o in PdfReader(pdf).outline if not isinstance(o, list)]
    assert "Warnings and results not evaluated" in outline and "Bolted joints" in outline
    h = html.read_text()
    assert 'id="summary"' in h and "sec-joints" in h


def test_whole_check_is_deterministic_and_exit_1(example):
    # all modules; run times are the only run-dependent output and sit under "timings"
    a = run("check", example, "--format", "json", "--no-timings")
    b = run("check", example, "--format", "json", "--no-timings")
    assert a.exit_code == 1 and a.stdout == b.stdout
    d = json.loads(a.stdout)
    assert set(d["modules"]["run"]) == {"joints", "loads", "torsion", "fatigue", "bearings",
                                        "bearing_performance", "balance", "flywheel",
                                        "damper", "crank"}  # the I4 has sheet Crank
    # the coupling and misfire rules are listed as not applicable (a passenger car without a
    # flexible coupling)
    assert {r["rule"].split("-")[0] for r in d["results"]} == {"JNT", "BRG", "TV", "DMP", "FAT",
                                                               "BAL", "FLY", "CPL", "MIS"}
    assert {r["status"] for r in d["results"] if r["rule"][:3] in ("CPL", "MIS")} == {
        "not_applicable"}


def test_report_figures_use_display_units(example, tmp_path):
    # the specific-load and MOFT plots are in MPa and um: their axis tick labels stay small

    from checker import api
    from checker.report.section_bearings import bearings_section
    from checker.report.section_loads import loads_section

    res = api.check(example, select=["BRG"])
    for sec in (loads_section(res), bearings_section(res)):
        texts = [t for b in sec["blocks"] if b["type"] == "figure" for t in b["png"].texts]
        assert "1e" not in " ".join(t for t in texts if len(t) <= 12), sec["id"]


def test_template_i6_engine(tmp_path):
    p = tmp_path / "i6.xlsx"
    assert run("template", p, "--engine", "i6").exit_code == 0
    r = run("check", p, "--select", "JNT", "--format", "json")
    assert r.exit_code in (0, 1) and json.loads(r.stdout)["engine"].startswith("Example I6")


def test_report_progress_in_words_only_when_asked(example, tmp_path):
    pdf = tmp_path / "r.pdf"
    # stderr is not a terminal here: no progress unless asked, the final line always
    quiet = run("report", example, "-o", pdf, "--select", "JNT-003")
    assert quiet.stderr.strip().splitlines() == [quiet.stderr.strip()]
    assert quiet.stderr.startswith(f"wrote {pdf} (")
    loud = run("report", example, "-o", pdf, "--select", "JNT-003", "--progress")
    assert "checker: Drawing the bolted joint figures" in loud.stderr
    assert "checker: Laying out the PDF, page 10" in loud.stderr or \
        "checker: Writing the PDF" in loud.stderr
    assert "Computing the" in loud.stderr and "joint_bolts" not in loud.stderr


def test_check_imports_no_plotting_pdf_or_dask(example):
    code = ("import sys; from click.testing import CliRunner; from checker.cli import main;"
            f" CliRunner().invoke(main, ['check', {str(example)!r}]);"
            " print(sorted(m for m in ('matplotlib', 'weasyprint', 'dask',"
            " 'scipy', 'pandas') if m in sys.modules))")
    out = fresh_python(code).splitlines()[-1]
    assert out == "[]"


def test_run_freezes_the_heap_after_the_command_and_keeps_its_exit_code(monkeypatch):
    """The console script (checker.cli:run) runs the command, then freezes what is alive out
    of the collector's exit-time passes, whatever the command's exit."""
    import gc

    import checker.cli as cli

    frozen = []
    monkeypatch.setattr(gc, "freeze", lambda: frozen.append(1))

    def command():
        raise SystemExit(3)

    monkeypatch.setattr(cli, "main", command)
    with pytest.raises(SystemExit) as got:
        cli.run()
    assert got.value.code == 3 and frozen == [1]
    import tomllib
    from pathlib import Path

    project = tomllib.loads((Path(__file__).parents[1] / "pyproject.toml").read_text())
    assert project["project"]["scripts"]["checker"] == "checker.cli:run"
