"""The examples as a user runs them (issue 21, "Done when"): every template (I4, I6, V8) through
``checker check``, ``checker report --results`` and ``checker compare`` on a clearance, an
oil-temperature and a bolt-torque variant, each command a separate process of the installed
``checker`` with its exit code (0 pass, 1 a failing verdict, never 2) and its files checked.

The three engines run concurrently (one thread each starting its commands one after the other),
so the module takes about as long as the slowest engine on two cores (about 3 min of CPU in
all; a few minutes).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import openpyxl
import pypdf
import pytest

from tests import variants
from tests.helpers import pdf_internals

pytestmark = pytest.mark.ci

ENGINES = ("i4", "i6", "v8")


def _checker() -> list[str]:
    exe = Path(sys.executable).with_name("checker")
    return [str(exe)] if exe.is_file() else [sys.executable, "-m", "checker"]


def _run(args: list, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(_checker() + [str(a) for a in args], cwd=cwd, capture_output=True,
                          text=True, timeout=900)


def _engine_run(engine: str, root: Path) -> dict:
    """Everything a user does with one example, in order; the completed processes by step."""
    d = root / engine
    d.mkdir()
    out = {"dir": d}
    out["template"] = _run(["template", "--engine", engine, "engine.xlsx"], d)
    if out["template"].returncode:
        return out
    out["check"] = _run(["check", "engine.xlsx", "--format", "json", "-o", "check.json"], d)
    out["report"] = _run(["report", "engine.xlsx", "-o", "engine.pdf", "--results",
                          "results.xlsx", "-q"], d)
    names = []
    for name, make in variants.VARIANTS.items():
        make(d / "engine.xlsx", d / f"{name}.xlsx")
        names.append(f"{name}.xlsx")
    out["compare"] = _run(["compare", "engine.xlsx", *names, "-o", "compare.pdf"], d)
    if engine == "i4":  # the review pack with what it takes to pass and the corners
        out["remedies"] = _run(["report", "engine.xlsx", "--remedies", "--corners", "-o",
                                "remedies.pdf", "--results", "remedies.xlsx", "-q"], d)
    return out


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    root = tmp_path_factory.mktemp("examples")
    with ThreadPoolExecutor(max_workers=len(ENGINES)) as pool:
        futures = {e: pool.submit(_engine_run, e, root) for e in ENGINES}
        results = {e: f.result() for e, f in futures.items()}
    yield results
    shutil.rmtree(root, ignore_errors=True)


def _ok(r: subprocess.CompletedProcess, codes=(0, 1)) -> None:
    assert r.returncode in codes, f"exit {r.returncode}: {r.stderr[-2000:]}"
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr


def _pdf_pages(path: Path) -> list[str]:
    return [p.extract_text() for p in pypdf.PdfReader(path).pages]


@pytest.mark.parametrize("engine", ENGINES)
def test_check_exit_code_is_the_verdict(runs, engine):
    r = runs[engine]
    _ok(r["template"], (0,))
    _ok(r["check"])
    d = json.loads((r["dir"] / "check.json").read_text())
    assert r["check"].returncode == (1 if d["verdict"] == "fail" else 0)
    assert d["input"]["file"] == "engine.xlsx" and len(d["results"]) > 50
    assert not d["input_warnings"], d["input_warnings"]  # the templates are clean


@pytest.mark.parametrize("engine", ENGINES)
def test_report_writes_pdf_and_results(runs, engine):
    r = runs[engine]
    _ok(r["report"])
    assert r["report"].returncode == r["check"].returncode  # same verdict as the check
    pages = _pdf_pages(r["dir"] / "engine.pdf")
    assert len(pages) >= 15
    assert "wrote engine.pdf, results.xlsx" in r["report"].stderr
    wb = openpyxl.load_workbook(r["dir"] / "results.xlsx", read_only=True)
    assert len(wb.sheetnames) >= 2
    wb.close()
    # nothing else was written next to the workbook (no temporary files left)
    assert not [p.name for p in r["dir"].iterdir() if p.name.startswith(".checker-")]


def test_report_with_remedies_and_corners(runs):
    """``checker report --remedies --corners`` on the I4 as a user runs it (its figures are
    drawn while the remedies are searched): the verdict's exit code, page 1's lines, the
    section, the results workbook's sheets."""
    r = runs["i4"]
    _ok(r["remedies"])
    assert r["remedies"].returncode == 1  # the I4 fails some guidelines
    pages = _pdf_pages(r["dir"] / "remedies.pdf")
    plain = _pdf_pages(r["dir"] / "engine.pdf")
    assert len(pages) > len(plain)
    text = "".join(pages)
    assert "To pass: " in text and "At the tolerance corners: " in text
    assert "What it takes to pass; tolerance corners" in text
    # every module's figures are there, as in the plain report (each says where its data is)
    assert text.count("Data: ") == "".join(plain).count("Data: ") > 10
    wb = openpyxl.load_workbook(r["dir"] / "remedies.xlsx", read_only=True)
    assert {"Remedies", "Tolerance corners"} <= set(wb.sheetnames)
    wb.close()


@pytest.mark.parametrize("engine", ENGINES)
def test_compare_on_clearance_oil_temperature_and_bolt_torque(runs, engine):
    r = runs[engine]
    _ok(r["compare"])
    err = r["compare"].stderr
    for name in variants.VARIANTS:
        assert f"{name}.xlsx: " in err and "(1 input change;" in err, err
    text = "".join(_pdf_pages(r["dir"] / "compare.pdf"))
    for name in variants.VARIANTS:
        assert f"{name}.xlsx against engine.xlsx" in text
    # one chapter per variant, naming the changed input as the user wrote it, no crash on
    # not-evaluated results whose value moved (tests/test_compare.py checks the content)
    assert text.count("1 input change.") == len(variants.VARIANTS), text[:3000]
    assert ": radial clearance" in text and ": tightening torque" in text
    assert "Oil supply temperature" in text


@pytest.mark.parametrize("engine", ENGINES)
def test_no_page_shows_program_internals(runs, engine):
    """Every page of the example's report, its compare pack and (I4) the report with remedies
    and corners reads as written for people: no dict or list repr, None, nan or class name
    (issue 37; :func:`tests.helpers.program_internals`)."""
    d = runs[engine]["dir"]
    names = ["engine.pdf", "compare.pdf"] + (["remedies.pdf"] if engine == "i4" else [])
    for name in names:
        assert (d / name).is_file(), name
        bad = pdf_internals(d / name)
        assert not bad, f"{engine} {name}: {bad[:5]}"


# --- studies ---------------------------------------------------------------------------------
# Every study of examples/ (one per design: full factorial, Latin hypercube, one at a time,
# table) through ``checker study`` with its PDF, on the template it is written for, two local
# worker processes, as a user runs it; then the same command again resumes every variant.

STUDIES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.toml"))


def _study_run(study: Path, root: Path) -> dict:
    d = root / study.stem
    d.mkdir()
    engine = study.name.split("-")[0]  # i4, i6, v8, genset, marine
    out = {"dir": d, "template": _run(["template", "--engine", engine, "engine.xlsx"], d)}
    if out["template"].returncode:
        return out
    args = ["study", "engine.xlsx", study, "-o", "out", "--workers", "2", "--no-progress"]
    out["study"] = _run(args, d)
    out["resume"] = _run(args + ["--no-pdf"], d)
    return out


@pytest.fixture(scope="module")
def study_runs(tmp_path_factory):
    root = tmp_path_factory.mktemp("studies")
    results = {s.name: _study_run(s, root) for s in STUDIES}
    yield results
    shutil.rmtree(root, ignore_errors=True)


def test_every_design_has_an_example_study():
    import tomllib

    designs = {tomllib.loads(s.read_text(encoding="utf-8"))["study"]["design"]
               for s in STUDIES}
    assert designs == {"full-factorial", "latin-hypercube", "one-at-a-time", "table"}


@pytest.mark.parametrize("study", [s.name for s in STUDIES])
def test_example_study_writes_its_tables_and_pdf(study_runs, study):
    r = study_runs[study]
    _ok(r["template"], (0,))
    _ok(r["study"], (0,))
    out = r["dir"] / "out"
    for name in ("results.parquet", "results.xlsx", "study.pdf"):
        assert (out / name).is_file(), (name, r["study"].stderr[-2000:])
    n = len(list((out / "variants").glob("*.json")))
    assert n >= 3
    text = "".join(_pdf_pages(out / "study.pdf"))
    assert "Parametric study" in text
    bad = pdf_internals(out / "study.pdf")  # no dict, list, None, nan or class name (issue 37)
    assert not bad, f"{study}: {bad[:5]}"
    # the second run computes nothing: every variant is resumed from variants/
    _ok(r["resume"], (0,))
    assert f"(0 computed, {n} resumed" in r["resume"].stderr, r["resume"].stderr[-1500:]
