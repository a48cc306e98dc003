"""One numbering of a study's variants (issue 43, item 11): the terminal's list of variants
with input errors, the results tables and the PDF number a variant alike, from 1 as the
default names do."""

from __future__ import annotations

from click.testing import CliRunner

from checker.cli import main
from checker.report.study import context
from checker.study.results import report_frame, write_tables
from checker.study.run import run_study
from checker.study.spec import load_study
from tests.helpers import example_path

STUDY = """[study]
name = "numbers"
design = "one-at-a-time"
select = ["BRG-001"]

[[parameter]]
sheet = "Oil"
row = "Oil supply temperature"
unit = "°C"
values = [-400, 100]
"""


def test_a_refused_variant_has_one_number_everywhere(tmp_path):
    wb = example_path(tmp_path)
    st = tmp_path / "study.toml"
    st.write_text(STUDY, encoding="utf-8")
    run = run_study(load_study(st), wb, tmp_path / "o", workers=1)
    (bad,) = run.input_errors()
    write_tables(run, tmp_path / "o")
    df = report_frame(tmp_path / "o", run)
    in_table = df.loc[df["status"] == "input error", "variant"].unique().tolist()
    ctx = context(run, df)
    in_pdf = [e["variant"] for e in ctx["errors"]]
    row = next(r for r in ctx["rows"] if r["input_error"])
    assert in_table == in_pdf == [bad["variant"]] == [row["variant"]]
    # numbered from 1 in variant order, the order of the default names
    names = [rec["name"] for rec in run.records]
    assert names.index(bad["name"]) + 1 == bad["variant"]
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(tmp_path / "o2"),
                                  "--workers", "1", "--no-pdf"])
    assert r.exit_code == 0, r.output
    assert any(x.startswith(f"  variant {bad['variant']} ({bad['name']}):")
               for x in r.output.splitlines()), r.output
