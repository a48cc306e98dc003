"""Verdict rules: no vacuous pass, incomplete checks shown as such, NaN never a pass, override
problems reported with cell problems, internal errors not usage errors, outputs to devices."""

from __future__ import annotations

import json
import os
import stat
import threading
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from click.testing import CliRunner

from checker import api
from checker.cli import main
from checker.errors import InputErrors
from checker.evaluation import graph
from checker.evaluation.graph import Quantity, QuantitySpec
from checker.evaluation.ruletable import Rule, evaluate_rule
from tests.helpers import edited, example_path, set_param


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("verdicts"))


def _drop(*sheets):
    def edit(wb):
        for s in sheets:
            del wb[s]
    return edit


# ---------------------------------------------------------------- vacuous pass
@pytest.mark.parametrize("sheets, prefix", [(("Bearings",), "BRG"),
                                            (("Joints", "JointTorques"), "JNT")])
def test_nothing_checked_is_exit_2_not_pass(tmp_path, sheets, prefix):
    sheet = sheets[0]
    p = edited(tmp_path, _drop(*sheets))
    out = tmp_path / "out.json"
    r = run("check", p, "--select", prefix, "--format", "json", "-o", out)
    assert r.exit_code == 2, r.output
    assert "nothing was checked" in r.stderr and sheet in r.stderr
    assert "PASS" not in r.output
    assert not out.exists()  # no output on exit 2
    pdf = tmp_path / "out.pdf"
    r = run("report", p, "--select", prefix, "-o", pdf)
    assert r.exit_code == 2 and "nothing was checked" in r.stderr
    assert not pdf.exists()


def test_api_reports_nothing_checked(tmp_path):
    res = api.check(edited(tmp_path, _drop("Bearings")), select=["BRG"])
    assert res.nothing_checked and res.exit_code == 2 and not res.complete
    assert "Bearings" in res.nothing_checked_reason()


# ---------------------------------------------------------------- incomplete verdict
def test_incomplete_verdict_everywhere(example):
    # the example's flywheel joint has no bolt-head diameters: JNT-002 is not evaluated
    r = run("check", example, "--select", "JNT", "--format", "json", "--no-timings")
    d = json.loads(r.stdout)
    assert d["verdict"] == "fail" and d["complete"] is False and d["not_evaluated"] >= 1
    assert d["counts"]["not_evaluated"] == d["not_evaluated"]
    t = run("check", example, "--select", "JNT")
    assert "INCOMPLETE" in t.stdout.splitlines()[-1]
    j = ET.fromstring(run("check", example, "--select", "JNT", "--format", "junit").stdout)
    props = {p.get("name"): p.get("value") for p in j.iter("property")}
    assert props["complete"] == "false" and int(props["not_evaluated"]) >= 1


def test_incomplete_pass_is_never_a_bare_pass(tmp_path):
    from tests.helpers import compliant_joints

    def edit(wb):
        compliant_joints(wb)
        ws = wb["Joints"]
        # remove the flywheel's head diameters again: JNT-002 not evaluated
        from tests.helpers import set_cell
        set_cell(wb, "Joints", "name", "flywheel", "head bearing outer diameter", None)
        set_cell(wb, "Joints", "name", "flywheel", "head bearing inner diameter", None)
        assert ws is not None

    p = edited(tmp_path, edit)
    res = api.check(p, select=["JNT"])
    assert res.verdict == "pass" and not res.complete
    assert res.verdict_text == "PASS (INCOMPLETE)"
    r = run("check", p, "--select", "JNT")
    assert r.exit_code == 0
    assert "PASS (INCOMPLETE)" in r.stdout and "incomplete" in r.stdout.splitlines()[-1]
    # --fail-on not-evaluated: a result that could not be evaluated fails the gate
    r = run("check", p, "--select", "JNT", "--fail-on", "not-evaluated")
    assert r.exit_code == 1
    d = json.loads(run("check", p, "--select", "JNT", "--fail-on", "warning,not-evaluated",
                       "--format", "json").stdout)
    assert d["verdict"] == "fail" and d["fail_on"] == "warning,not-evaluated"
    from checker.report.render import context
    ctx = context(res)
    assert ctx["verdict"] == "PASS (INCOMPLETE)" and "incomplete" in ctx["verdict_css"]


def test_fail_on_rejects_unknown_value(example):
    r = run("check", example, "--fail-on", "sometimes")
    assert r.exit_code == 2 and "not-evaluated" in r.output


def test_rule_prefixes_case_insensitive(example):
    a = api.check(example, select=["jnt-00"], ignore=["jnt-004"])
    assert {r.rule for r in a.results} and all(r.rule.startswith("JNT-00") for r in a.results)
    assert "JNT-004" not in {r.rule for r in a.results}


# ---------------------------------------------------------------- NaN never a pass
_SPEC = QuantitySpec("test.nan_quantity", "m", ("item", "speed"), "test quantity")


def _rule():
    return Rule(id="TST-001", name="test film", quantity=_SPEC.name, check=">=", unit="um",
                severity="warning", source="test", rationale="test", limit=(1.0,))


@pytest.fixture()
def nan_quantity(monkeypatch):
    monkeypatch.setitem(graph.QUANTITIES, _SPEC.name, _SPEC)
    vals = np.array([[2e-6, np.nan, 3e-6], [2e-6, np.nan, 3e-6]])
    return Quantity(_SPEC, vals, {"item": ["A", "B"], "speed": [100.0, 200.0, 300.0]},
                    missing={(1,): ["Sheet!B3: an input of B"]},
                    findings={(0, 1): ["film collapse at 1910 rpm"]})


def test_nan_from_a_calculation_that_ran_fails(nan_quantity):
    res = {r.item: r for r in evaluate_rule(_rule(), nan_quantity, None)}
    a, b = res["A"], res["B"]
    # item A: NaN with no missing input behind it -> internal error, failing, with finding
    assert a.status == "fail" and a.internal_error and "internal error" in a.message
    assert "film collapse" in a.message and "1910 rpm" in a.case
    # item B: NaN explained by a missing input -> not evaluated, naming the input
    assert b.status == "not_evaluated" and b.missing == ["Sheet!B3: an input of B"]


def test_internal_error_result_fails_the_verdict_even_as_warning(nan_quantity, example):
    base = api.check(example, select=["JNT-001"])
    results = evaluate_rule(_rule(), nan_quantity, None)
    res = api.CheckResult(base.engine, base.table, base.rules, results, base.outcome)
    assert res.verdict == "fail" and res.exit_code == 1 and res.counts()["fail"] == 1


# ---------------------------------------------------------------- overrides in one pass
def test_override_errors_reported_with_cell_errors(tmp_path):
    def edit(wb):
        set_param(wb, "Engine", "Bore", "eighty")
        ws = wb["RuleOverrides"]
        r = ws.max_row + 1
        ws.cell(r, 1).value = "JNT-0001"
        ws.cell(r, 2).value = 80
        ws.cell(r, 3).value = "%"
        ws.cell(r, 4).value = "test"

    p = edited(tmp_path, edit)
    with pytest.raises(InputErrors) as e:
        api.check(p)
    text = str(e.value)
    assert "Engine!B" in text and "Bore" in text
    assert "unknown rule 'JNT-0001'" in text and "did you mean 'JNT-001'" in text
    r = run("check", p)
    assert r.exit_code == 2 and "Bore" in r.stderr and "JNT-0001" in r.stderr


# ---------------------------------------------------------------- internal errors
def test_calculation_error_is_internal_not_usage(example, monkeypatch):
    calc = graph.CALCULATIONS["joints"] if "joints" in graph.CALCULATIONS else next(
        c for c in graph.CALCULATIONS.values() if c.module == "joints")

    def boom(engine, inputs):
        raise ValueError("bad shape " + repr(np.arange(2000.0)))

    monkeypatch.setitem(graph.CALCULATIONS, calc.name,
                        graph.Calculation(calc.name, calc.module, calc.provides, boom,
                                          calc.needs, calc.description, calc.optional))
    r = run("check", example, "--select", "JNT-001")
    assert r.exit_code == 2
    assert "Usage:" not in r.output and "internal error" in r.stderr
    assert "1999" not in r.stderr and len(r.stderr) < 1000  # no array dump


# ---------------------------------------------------------------- outputs to non-files
def test_output_to_fifo_writes_and_keeps_the_fifo(example, tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got: list[bytes] = []

    def reader():
        with open(fifo, "rb") as f:
            got.append(f.read())

    t = threading.Thread(target=reader)
    t.start()
    r = run("check", example, "--select", "JNT", "--format", "json", "-o", fifo)
    t.join(timeout=60)
    assert r.exit_code == 1
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)  # still a FIFO, not replaced by a file
    assert json.loads(got[0].decode())["engine"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".checker-")]


# ---------------------------------------------------------------- input warnings shown
def test_input_warnings_in_every_output(tmp_path):
    p = edited(tmp_path, lambda wb: set_param(wb, "Engine", "Bore", unit="in"))
    r = run("check", p, "--select", "JNT", "--format", "json", "--no-timings")
    d = json.loads(r.stdout)
    assert any("Engine!B" in w and "Bore" in w for w in d["input_warnings"]), d
    t = run("check", p, "--select", "JNT")
    assert "input warnings" in t.stdout and "Bore" in t.stdout
    j = ET.fromstring(run("check", p, "--select", "JNT", "--format", "junit").stdout)
    assert any(e.get("name") == "input_warning" for e in j.iter("property"))


def test_json_carries_every_computed_quantity(example):
    d = json.loads(run("check", example, "--format", "json", "--no-timings").stdout)
    q = d["quantities"]
    assert {"balance.free_force", "flywheel.minimum_inertia", "damper.tuning_ratio",
            "bearing.moft_finite", "bearing.moft_short", "tv.nose_amplitude"} <= set(q)
    ff = q["balance.free_force"]
    assert ff["coords"]["item"][1] == "order 2" and ff["values"][1] > 1000
    mi = q["flywheel.minimum_inertia"]["over_speed"]
    assert mi[0]["max"] > 0 and mi[0]["max_at_rpm"] > 0
