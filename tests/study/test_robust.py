"""`checker study` survives what users do (issue 21): interruptions keep the finished variants
and leave no process behind, mistakes are exit 2 with one sentence before any work, resource
bombs are refused with the number, two studies never share an output folder."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from checker.cli import main
from checker.plumbing.interrupt import Terminated, exit_code, interruptible
from checker.study.run import (
    LOCK_NAME,
    StudyOutputError,
    _write_record,
    output_lock,
    run_study,
)
from checker.study.spec import MAX_VARIANTS, StudyFileError, load_study
from tests.helpers import example_path, unwritable_folder

ROOT = Path(__file__).resolve().parents[2]

# every variant changes the bore: nothing is reused from a cache, each takes a moment
SLOW = """[study]
name = "bore"
design = "full-factorial"
select = ["BRG-001"]

[[parameter]]
sheet = "Engine"
row = "Bore"
unit = "mm"
range = [78, 84]
steps = 400
"""

TABLE = """[study]
name = "two clearances"
design = "table"
select = ["BRG-001"]

[[parameter]]
name = "main clearance"
sheet = "Bearings"
where = { type = "main" }
column = "radial clearance"
unit = "um"

[[parameter]]
sheet = "Oil"
row = "Oil supply temperature"
unit = "°C"

[[variant]]
name = "tight"
"main clearance" = 18

[[variant]]
name = "loose, hot"
"main clearance" = 36
"Oil supply temperature" = 120
"""

SMALL = """[study]
name = "small"
design = "one-at-a-time"
select = ["BRG-001"]

[[parameter]]
sheet = "Oil"
row = "Oil supply temperature"
unit = "°C"
values = [100, 120]
"""


@pytest.fixture(scope="module")
def wb(tmp_path_factory) -> Path:
    return example_path(tmp_path_factory.mktemp("robust"))


def _write(tmp: Path, text: str, name: str = "study.toml") -> Path:
    p = tmp / name
    p.write_text(text, encoding="utf-8")
    return p


# --- interruptions (items 3, 4, 11) ----------------------------------------------------------


def _group(pgid: int) -> list[int]:
    """Live (not zombie) processes of the process group ``pgid``, from /proc."""
    out = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            stat = Path(f"/proc/{d}/stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[2]) == pgid and fields[0] != "Z":
            out.append(int(d))
    return out


def _interrupt(wb: Path, tmp: Path, sig: int, group: bool, *extra: str):
    study = _write(tmp, SLOW)
    out = tmp / "out"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    p = subprocess.Popen([sys.executable, "-m", "checker", "study", str(wb), str(study), "-o",
                          str(out), "--no-progress", *extra], cwd=tmp, env=env,
                         start_new_session=True, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        t0 = time.monotonic()
        while not list((out / "variants").glob("*.json")):
            assert p.poll() is None, p.communicate()
            assert time.monotonic() - t0 < 120, "no variant finished in 120 s"
            time.sleep(0.05)
        assert len(_group(p.pid)) >= 2  # the study and its workers
        t1 = time.monotonic()
        if group:
            os.killpg(p.pid, sig)
        else:
            os.kill(p.pid, sig)
        _, err = p.communicate(timeout=30)
        stop = time.monotonic() - t1
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    deadline = time.monotonic() + 5
    while _group(p.pid) and time.monotonic() < deadline:
        time.sleep(0.1)
    left = _group(p.pid)
    kept = sorted((out / "variants").glob("*.json"))
    return p.returncode, err, stop, left, kept, out


@pytest.mark.parametrize("sig, group, code", [
    (signal.SIGINT, True, 130),  # Ctrl-C in a terminal: the whole process group
    (signal.SIGTERM, False, 143),  # kill <pid>: the study process alone
])
def test_interrupted_study_stops_keeps_finished_variants_and_leaves_no_process(
        wb, tmp_path, sig, group, code):
    rc, err, stop, left, kept, out = _interrupt(wb, tmp_path, sig, group, "--workers", "2")
    assert rc == code, err
    assert stop < 5, f"took {stop:.1f} s to stop"
    assert left == [], f"processes left behind: {left}"
    assert kept, "the finished variants were not kept"
    for f in kept:  # complete records, no temporary files left
        assert json.loads(f.read_text())["status"] == "checked"
    assert not list((out / "variants").glob("*.tmp"))
    last = err.strip().splitlines()[-1]
    assert last == f"checker: interrupted: {len(kept)} variant{'s' if len(kept) != 1 else ''}" \
        f" kept in {out}; re-run to resume"
    assert "Traceback" not in err and "Aborted" not in err


def test_interrupted_dask_study_leaves_no_process(wb, tmp_path):
    pytest.importorskip("distributed")
    rc, err, stop, left, kept, _ = _interrupt(wb, tmp_path, signal.SIGINT, True, "--workers",
                                              "2", "--dask", "local")
    assert rc == 130, err
    assert stop < 10, f"took {stop:.1f} s to stop"
    assert left == [], f"processes left behind: {left}"
    assert kept and "Traceback" not in err


def _log_in_worker(level: int, text: str) -> None:
    import logging

    logging.getLogger("distributed.worker").log(level, text)


def test_local_cluster_workers_log_only_critical_events(capfd):
    """A worker's error log (at an interruption: its heartbeat meeting the closed scheduler,
    with a traceback; CI caught it in an interrupted study's output) stays out of the
    command's stderr; a variant's own error reaches the command through its future."""
    pytest.importorskip("distributed")
    import logging

    from checker.study.run import connect_dask

    eng = connect_dask("local", 1)
    try:
        eng.client.run(_log_in_worker, logging.ERROR, "worker error noise")
        eng.client.run(_log_in_worker, logging.CRITICAL, "worker critical event")
    finally:
        eng.close()
    err = capfd.readouterr().err
    assert "worker error noise" not in err
    assert "worker critical event" in err


def test_interruptible_maps_signals_to_exit_codes():
    assert exit_code(KeyboardInterrupt()) == 130 and exit_code(Terminated()) == 143
    lines: list[str] = []
    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(SystemExit) as e:
        with interruptible(lambda: "2 kept", echo=lines.append):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # the handler raises Terminated before this ends
    assert e.value.code == 143 and lines == ["interrupted: 2 kept"]
    assert signal.getsignal(signal.SIGTERM) is before  # restored
    with pytest.raises(SystemExit) as e:
        with interruptible(echo=lines.append):
            raise KeyboardInterrupt
    assert e.value.code == 130 and lines[-1] == "interrupted"


# --- item 2: a table design draws its PDF ----------------------------------------------------


def test_table_study_writes_its_pdf(wb, tmp_path):
    st = _write(tmp_path, TABLE)
    out = tmp_path / "out"
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out), "--workers", "1"])
    assert r.exit_code == 0, r.output
    assert (out / "study.pdf").read_bytes()[:5] == b"%PDF-"
    import pandas as pd

    df = pd.read_parquet(out / "results.parquet")
    assert sorted(set(df["variant_name"])) == ["loose, hot", "tight"]


# --- item 5: output folder checked before any work -------------------------------------------


def test_output_under_a_file_is_exit_2_before_work(wb, tmp_path):
    st = _write(tmp_path, SMALL)
    f = tmp_path / "a-file"
    f.write_text("x")
    for out, words in [(f / "out", "is a file"), (f, "is a file")]:
        r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out)])
        assert r.exit_code == 2, r.output
        assert words in r.output and "internal error" not in r.output
        assert "variants" not in r.output  # refused before the variants were run
    assert f.read_text() == "x"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_output_folder_is_exit_2_before_work(wb, tmp_path):
    st = _write(tmp_path, SMALL)
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        for out in (ro, ro / "sub"):
            r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out)])
            assert r.exit_code == 2, r.output
            assert "cannot" in r.output and str(ro) in r.output
            assert "variants" not in r.output
    finally:
        ro.chmod(0o755)
    assert os.listdir(ro) == []


# --- item 6: resource bombs ------------------------------------------------------------------


def test_unwritable_output_folder_is_exit_2_before_work_even_for_root(wb, tmp_path):
    ro = unwritable_folder()
    if ro is None:
        pytest.skip("no folder here that refuses root")
    st = _write(tmp_path, SMALL)
    for out in (ro, ro / "checker-study-out"):
        r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out)])
        assert r.exit_code == 2, r.output
        assert f"cannot write to the output folder {out}" in r.output
        assert "variants" not in r.output and "internal error" not in r.output


def test_huge_factorial_is_refused_with_its_size_without_building_it(wb, tmp_path):
    params = "".join(f'\n[[parameter]]\nsheet = "Engine"\nrow = "{r}"\nunit = "mm"\n'
                     f"range = [{lo}, {lo + 5}]\nsteps = 1000\n"
                     for r, lo in [("Bore", 78), ("Stroke", 80), ("Connecting rod length", 140)])
    st = _write(tmp_path, '[study]\nname = "bomb"\ndesign = "full-factorial"\n' + params)
    t0 = time.monotonic()
    with pytest.raises(StudyFileError) as e:
        load_study(st)
    assert time.monotonic() - t0 < 2
    text = str(e.value)
    assert "1,000,000,000 variants" in text and "1000 x 1000 x 1000" in text
    assert f"{MAX_VARIANTS:,}" in text and "line 3" in text
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(tmp_path / "o")])
    assert r.exit_code == 2 and "1,000,000,000" in r.output
    assert not (tmp_path / "o").exists()


# --- item 7: one study per output folder -----------------------------------------------------


def test_second_study_into_a_busy_folder_is_exit_2(wb, tmp_path):
    st = _write(tmp_path, SMALL)
    out = tmp_path / "out"
    with output_lock(out):  # a study is writing there
        r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out)])
        assert r.exit_code == 2, r.output
        assert f"another study is writing to {out}" in r.output
        with pytest.raises(StudyOutputError):
            run_study(load_study(st), wb, out, workers=1)
    assert not (out / "variants").exists()
    # the lock is released with the first study: the next one runs
    run = run_study(load_study(st), wb, out, workers=1)
    assert run.computed == 3 and (out / LOCK_NAME).exists()


def test_records_written_concurrently_use_unique_temporary_files(tmp_path):
    (tmp_path / ".abc.tmp").mkdir()  # the old fixed temporary name, taken
    errors: list[BaseException] = []

    def write(n):
        try:
            for k in range(30):
                _write_record(tmp_path, {"id": "abc", "n": n, "k": k})
        except BaseException as exc:  # noqa: BLE001
            errors.append(exc)

    ts = [threading.Thread(target=write, args=(n,)) for n in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert errors == []
    assert json.loads((tmp_path / "abc.json").read_text())["k"] == 29
    assert sorted(p.name for p in tmp_path.iterdir()) == [".abc.tmp", "abc.json"]


# --- item 8: Dask addresses ------------------------------------------------------------------


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:1", "nonsense"])
def test_unreachable_dask_scheduler_is_exit_2_quickly(wb, tmp_path, address):
    pytest.importorskip("distributed")
    st = _write(tmp_path, SMALL)
    out = tmp_path / "out"
    t0 = time.monotonic()
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(out), "--dask", address])
    assert time.monotonic() - t0 < 20
    assert r.exit_code == 2, r.output
    assert f"cannot reach the Dask scheduler at '{address}'" in r.output
    assert "bug" not in r.output and "Traceback" not in r.output
    assert not out.exists()


# --- item 9: worker count --------------------------------------------------------------------


@pytest.mark.parametrize("n", ["-3", "0"])
def test_workers_below_one_is_a_usage_error(wb, tmp_path, n):
    st = _write(tmp_path, SMALL)
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(tmp_path / "o"),
                                  "--workers", n])
    assert r.exit_code == 2 and "--workers" in r.output
    assert not (tmp_path / "o").exists()


# --- friction: input errors listed, did you mean, select lines -------------------------------


def test_variant_input_errors_are_listed_with_study_line_and_cell(wb, tmp_path):
    st = _write(tmp_path, SMALL.replace("values = [100, 120]", "values = [100, -400]"))
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(tmp_path / "o"),
                                  "--workers", "1", "--no-pdf"])
    assert r.exit_code == 0, r.output
    assert "1 with input errors" in r.output
    # variants numbered from 1: the baseline, 100 °C, -400 °C
    line = next(x for x in r.output.splitlines() if x.startswith("  variant 3"))
    assert "Oil supply temperature = -400 °C" in line
    assert "study line 6 (parameter 'Oil supply temperature')" in line and "Oil!B" in line


def test_table_variant_errors_name_the_variant_line(wb, tmp_path):
    st = _write(tmp_path, TABLE.replace('"main clearance" = 36', '"main clearance" = -36'))
    run = run_study(load_study(st), wb, tmp_path / "o", workers=1)
    bad = run.input_errors()
    assert [b["name"] for b in bad] == ["loose, hot"]
    assert all(e.startswith("study line 22 (variant 'loose, hot'): Bearings!F")
               for e in bad[0]["errors"])


def test_did_you_mean_for_rows_parameters_and_rules(wb, tmp_path):
    st = _write(tmp_path, SMALL.replace("Oil supply temperature", "Oil suply temperature")
                .replace('select = ["BRG-001"]', 'select = ["BRX-001"]'))
    with pytest.raises(StudyFileError) as e:
        load_study(st)
    assert "did you mean 'Oil supply temperature'" in str(e.value)
    st = _write(tmp_path, SMALL.replace('select = ["BRG-001"]', 'select = ["BRX-001"]'))
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(tmp_path / "o")])
    assert r.exit_code == 2
    assert "line 4: 'select': 'BRX-001' matches no rule id" in r.output
    assert "did you mean 'BRG-001'" in r.output
    st = _write(tmp_path, TABLE.replace('where = { type = "main" }', 'rows = ["M3", "M33"]'))
    r = CliRunner().invoke(main, ["study", str(wb), str(st), "-o", str(tmp_path / "o")])
    assert r.exit_code == 2
    assert "line 6: parameter 'main clearance': sheet Bearings has no row M33" in r.output
    assert "did you mean 'M3'" in r.output
    assert not (tmp_path / "o").exists()


# --- memory: records stream from disk --------------------------------------------------------


def test_tables_are_streamed_from_the_stored_records(wb, tmp_path):
    import pandas as pd

    from checker.study.results import tidy, write_tables

    st = _write(tmp_path, SMALL)
    run = run_study(load_study(st), wb, tmp_path / "o", workers=1)
    assert not isinstance(run.records, list)  # read from variants/*.json when needed
    write_tables(run, tmp_path / "o")
    back = pd.read_parquet(tmp_path / "o" / "results.parquet")
    pd.testing.assert_frame_equal(back, tidy(run))
    xl = pd.read_excel(tmp_path / "o" / "results.xlsx")
    assert len(xl) == len(back) and list(xl.columns) == list(back.columns)


# --- examples: every example study is valid against its template workbook -------------------


@pytest.mark.parametrize("study", sorted((ROOT / "examples").glob("*.toml")),
                         ids=lambda p: p.name)
def test_example_studies_are_valid_for_their_templates(study, tmp_path):
    from checker.study.design import count_variants
    from checker.study.run import plan_study
    from checker.workbook.example import example_content, write_workbook
    from checker.workbook.example_classes import genset_content, marine_content
    from checker.workbook.example_i6 import i6_content
    from checker.workbook.example_v8 import v8_content

    content = {"i4": example_content, "i6": lambda: i6_content(damper_ring=True),
               "v8": v8_content, "genset": genset_content,
               "marine": marine_content}[study.name.split("-")[0]]()
    wb = tmp_path / "engine.xlsx"
    write_workbook(wb, content)
    st = load_study(study)
    plan = plan_study(st, wb)
    assert len(plan.variants) == count_variants(st) >= 3


def test_dask_interrupt_noise_is_dropped_and_other_errors_kept():
    """A Ctrl-C that reaches distributed's blocking ``sync`` before its coroutine started
    makes the loop thread log a NameError traceback from its ``cancel`` callback (seen in CI
    under load): that record only is dropped; any other error is still logged."""
    import logging

    from checker.study.run import _InterruptedSyncNoise

    ns: dict = {}
    exec(compile("def cancel():\n    if future is not None:\n        pass\nfuture = None\n"
                 "del future\n", "/x/site-packages/distributed/utils.py", "exec"), ns)

    def record(func):
        try:
            func()
        except Exception:  # noqa: BLE001
            return logging.LogRecord("tornado.application", logging.ERROR, __file__, 1,
                                     "Exception in callback", (), sys.exc_info())
        raise AssertionError("no exception")

    noise = record(ns["cancel"])
    assert isinstance(noise.exc_info[1], NameError) and "future" in str(noise.exc_info[1])
    f = _InterruptedSyncNoise()
    assert f.filter(noise) is False

    def cancel():  # the same name and error elsewhere: kept
        raise NameError("name 'future' is not defined")

    assert f.filter(record(cancel)) is True
    assert f.filter(record(lambda: 1 / 0)) is True
    assert f.filter(logging.LogRecord("x", logging.ERROR, __file__, 1, "m", (), None)) is True
