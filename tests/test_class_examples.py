"""The genset and marine examples (issue 46 item 6) end to end: ``checker template --engine
genset|marine``, ``checker check`` (every torsional, coupling and misfire rule judged or not
applicable, never a missing input), ``checker report`` (the coupling and misfire sections)
and ``checker study`` on the studies of ``examples/``; the examples' classes (industrial,
marine) and their sourced values.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from checker import api
from checker.cli import main
from checker.workbook.example_data import about, read_example

ROOT = Path(__file__).resolve().parents[1]
CLASSES = {"genset": "industrial", "marine": "marine"}


def _template(tmp_path: Path, engine: str) -> Path:
    p = tmp_path / f"engine-{engine}.xlsx"
    r = CliRunner().invoke(main, ["template", "--engine", engine, str(p)])
    assert r.exit_code == 0, r.output
    return p


@pytest.mark.parametrize("engine", ["genset", "marine"])
def test_check_judges_every_tv_coupling_and_misfire_rule(tmp_path, engine):
    p = _template(tmp_path, engine)
    out = tmp_path / "check.json"
    r = CliRunner().invoke(main, ["check", str(p), "--format", "json", "-o", str(out)])
    assert r.exit_code in (0, 1), r.output
    doc = json.loads(out.read_text())
    assert doc  # machine-readable results written
    res = api.check(p)
    assert str(res.engine.params["engine_class"]) == CLASSES[engine]
    got = {}
    for x in res.results:
        if x.rule.startswith(("CPL-", "MIS-", "TV-")):
            got.setdefault(x.rule, set()).add(x.status)
    assert {"CPL-001", "CPL-002", "CPL-003", "MIS-002", "MIS-003", "MIS-004", "MIS-005",
            "TV-004", "TV-005", "TV-008"} <= set(got)
    for rule, st in got.items():
        assert "not_evaluated" not in st, rule
    # the viscous damper: the rubber's misfire rule does not apply
    assert got["MIS-001"] == {"not_applicable"}


@pytest.mark.parametrize("engine", ["genset", "marine"])
def test_every_value_is_sourced_or_an_assumption(engine):
    data = read_example(engine)
    for sheet, body in data.items():
        if sheet in ("about", "Notes"):
            continue
        rows = body if isinstance(body, list) else body.get("rows", [])
        for r in rows:
            vals = {k: v for k, v in r.items() if k not in ("note", "parameter", "unit")}
            if not any(v is not None for v in vals.values()):
                continue
            assert r.get("note") or r.get("source"), f"{engine}: {sheet} row {r} has no source"
    assert about(engine)["assumed"]


@pytest.mark.ci
@pytest.mark.parametrize("engine,study", [("genset", "genset-coupling.toml"),
                                          ("marine", "marine-propeller.toml")])
def test_report_and_study(tmp_path, engine, study):
    p = _template(tmp_path, engine)
    pdf = tmp_path / "engine.pdf"
    html = tmp_path / "engine.html"
    r = CliRunner().invoke(main, ["report", str(p), "-o", str(pdf), "--html", str(html), "-q"])
    assert r.exit_code in (0, 1), r.output
    assert pdf.stat().st_size > 0
    text = html.read_text()
    assert "<h2>Flexible coupling" in text and "<h2>Misfire" in text
    out = tmp_path / "study"
    r = CliRunner().invoke(main, ["study", str(p), str(ROOT / "examples" / study), "-o",
                                  str(out), "--workers", "1"])
    assert r.exit_code in (0, 1), r.output
    assert (out / "results.parquet").is_file()
