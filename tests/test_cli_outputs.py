"""Every command's outputs survive what users do (issue 21): an unwritable output is exit code
2 with one sentence before any work and no partial file (item 5); ``template`` refuses a
non-.xlsx name (item 10); SIGINT/SIGTERM end any command with 130/143 and no partial file
(item 11); case-insensitive rule ids and engine names; plural words; progress in words."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import pytest
from click.testing import CliRunner

from checker.api import CheckResult
from checker.cli import STEP_WORDS, _Progress, main
from checker.errors import OutputError
from checker.outputs.files import check_writable, check_writable_folder, write_files
from tests.helpers import example_path, unwritable_folder

ROOT = os.geteuid() == 0 if hasattr(os, "geteuid") else False


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def book(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("book"))


def _blocked(tmp_path: Path, kind: str) -> Path:
    """A folder no file can be written in: under a regular file (works as root too), a folder
    the system refuses (sysfs, also for root), or a read-only folder (chmod; not enforced for
    root)."""
    if kind == "under-a-file":
        f = tmp_path / "plain-file"
        f.write_text("x")
        return f
    if kind == "sysfs":
        return unwritable_folder()
    d = tmp_path / "ro"
    d.mkdir()
    d.chmod(0o555)
    return d


KINDS = ["under-a-file",
         pytest.param("sysfs", marks=pytest.mark.skipif(
             unwritable_folder() is None, reason="no folder here that refuses root")),
         pytest.param("read-only", marks=pytest.mark.skipif(
             ROOT, reason="root writes into read-only folders"))]


@pytest.mark.parametrize("kind", KINDS)
def test_unwritable_outputs_are_exit_2_before_any_work(tmp_path, book, kind):
    bad = _blocked(tmp_path, kind)
    ok = tmp_path / "ok.pdf"
    cases = [
        ("check", book, "-o", bad / "out.json"),
        ("report", book, "-o", bad / "r.pdf"),
        ("report", book, "-o", ok, "--html", bad / "r.html"),
        ("report", book, "-o", ok, "--results", bad / "r.xlsx"),
        ("template", bad / "e.xlsx"),
        ("compare", book, book, "-o", bad / "c.pdf"),
        ("compare", book, book, "--format", "json", "-o", bad / "c.json"),
    ]
    try:
        for args in cases:
            t0 = time.perf_counter()
            r = run(*args)
            took = time.perf_counter() - t0
            assert r.exit_code == 2, (args, r.output)
            assert r.stderr.startswith("error: cannot write"), (args, r.stderr)
            assert len(r.stderr.strip().splitlines()) == 1, r.stderr  # one sentence
            assert "Traceback" not in r.output
            assert took < 3.0, (args, took)  # refused before the analyses (seconds each)
            assert not ok.exists()  # no partial output: the PDF is not written either
    finally:
        if kind == "read-only":
            bad.chmod(0o755)


def test_output_that_is_a_folder_or_a_read_only_file(tmp_path, book):
    r = run("check", book, "-o", tmp_path)
    assert r.exit_code == 2  # click refuses a folder for a file option
    ro = tmp_path / "old.json"
    ro.write_text("{}")
    ro.chmod(0o444)
    if not ROOT:
        r = run("check", book, "-o", ro)
        assert r.exit_code == 2 and "read-only" in r.stderr
        assert ro.read_text() == "{}"


def test_helpers_refuse_and_leave_nothing_behind(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    with pytest.raises(OutputError, match="is a file, not a folder"):
        check_writable([tmp_path / "a.pdf", f / "sub" / "b.pdf"])
    with pytest.raises(OutputError, match="is a folder"):
        check_writable([tmp_path])
    with pytest.raises(OutputError, match="is a file"):
        check_writable_folder(f)
    check_writable_folder(tmp_path / "new" / "deeper")  # may be created later
    assert not (tmp_path / "new").exists()
    # all or none: the second file cannot be written, so the first is not either
    with pytest.raises(OutputError):
        write_files([(tmp_path / "one.txt", b"1"), (f / "two.txt", b"2")])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]
    write_files([(tmp_path / "one.txt", b"1"), (tmp_path / "sub" / "two.txt", b"2")])
    assert (tmp_path / "sub" / "two.txt").read_bytes() == b"2"


def test_template_refuses_a_name_that_is_not_xlsx(tmp_path):
    r = run("template", tmp_path / "foo.txt")
    assert r.exit_code == 2 and "not an .xlsx file name" in r.output
    assert "foo.xlsx" in r.output  # the hint
    assert not (tmp_path / "foo.txt").exists()
    assert run("template", tmp_path / "FOO.XLSX").exit_code == 0


def test_engine_names_and_rule_ids_are_case_insensitive(tmp_path):
    r = run("template", tmp_path / "e.xlsx", "--engine", "I6")
    assert r.exit_code == 0, r.output
    r = run("rules", "--explain", "jnt-003")
    assert r.exit_code == 0 and r.stdout.startswith("JNT-003"), r.output
    assert run("rules", "--explain", "nope-1").exit_code == 2


def test_summary_says_1_warning_not_1_warnings():
    def summary(n_warn):
        res = SimpleNamespace(
            counts=lambda: {"pass": 2, "fail": 1, "warning": n_warn, "not_evaluated": 0},
            verdict_text="FAIL", complete=True, fail_on="error")
        return CheckResult.summary_text(res)
    assert "1 warning," in summary(1) and "2 warnings," in summary(2)


def test_progress_names_every_calculation_in_words(capsys):
    import checker.modules  # noqa: F401 - registers the calculations
    from checker.evaluation.graph import CALCULATIONS

    assert {c.name for c in CALCULATIONS.values()} <= set(STEP_WORDS)
    p = _Progress(True)
    p("torsion: tv_joint_torque")
    err = capsys.readouterr().err
    assert err == "checker: Computing the joint torques from the torsional model\n"


# --------------------------------------------------------------- interruption (item 11)
def _interrupt(args: list[str], cwd: Path, sig: int, wait_for: str) -> tuple[int, str]:
    """Run checker in a subprocess, send ``sig`` once stderr shows ``wait_for``."""
    p = subprocess.Popen([sys.executable, "-m", "checker", *args], cwd=cwd,
                         stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    seen = ""
    try:
        for line in p.stderr:
            seen += line
            if wait_for in line:
                p.send_signal(sig)
                break
        rest = p.communicate(timeout=60)[1]
    finally:
        if p.poll() is None:
            p.kill()
    return p.returncode, seen + rest


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_interrupted_report_exits_130_or_143_without_partial_files(tmp_path, sig, code):
    book = example_path(tmp_path)
    rc, err = _interrupt(["report", book.name, "-o", "r.pdf", "--html", "r.html",
                          "--results", "r.xlsx", "--progress"], tmp_path, sig, "Drawing")
    assert rc == code, err
    assert "Aborted" not in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["engine.xlsx"]  # no partial files


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_interrupted_check_exits_130_or_143(tmp_path, sig, code):
    book = example_path(tmp_path)
    rc, err = _interrupt(["check", book.name, "-o", "out.json", "--format", "json",
                          "--progress"], tmp_path, sig, "Computing")
    assert rc == code, err
    assert "Aborted" not in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["engine.xlsx"]
