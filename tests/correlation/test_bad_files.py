"""Bad measurement files: each problem named at its file:line, exit code 2, no output file."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from checker.cli import main
from tests.helpers import example_path

from .synth import signal_csv, tracks_csv

SPEEDS = [1500, 2500, 3500, 4500]
ORDERS = [4, 6]
AMP = np.full((4, 2), 0.05)


@pytest.fixture(scope="module")
def workbook(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("wb"), "i4.xlsx")


def _run(tmp_path, workbook, measured):
    out = tmp_path / "out.pdf"
    js = tmp_path / "out.json"
    cal = tmp_path / "cal.xlsx"
    r = CliRunner().invoke(main, ["correlate", str(workbook), str(measured), "-o", str(out),
                                  "--json", str(js), "--calibrated", str(cal)])
    assert r.exit_code == 2, r.output
    assert not out.exists() and not js.exists() and not cal.exists()
    assert "Traceback" not in r.output
    return r.output


def _write(tmp_path, text):
    p = tmp_path / "m.csv"
    p.write_text(text, encoding="utf-8")
    return p


def test_missing_units(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "crank nose", "full", SPEEDS, ORDERS, AMP, units=False)
    out = _run(tmp_path, workbook, p)
    assert "m.csv:4" in out and "missing units" in out


def test_blank_unit_of_one_column(tmp_path, workbook):
    p = _write(tmp_path, "# station: crank nose\n# load: full\nspeed,order 4\nrpm,\n"
               "1500,0.05\n2500,0.06\n")
    out = _run(tmp_path, workbook, p)
    assert "m.csv:4: column 'order 4' has no unit" in out


def test_unknown_station(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "camshaft", "full", SPEEDS, ORDERS, AMP)
    out = _run(tmp_path, workbook, p)
    assert "m.csv:1: station 'camshaft' does not exist in the torsional model" in out
    assert "'Crank nose' (crank nose)" in out


def test_order_not_in_model(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "crank nose", "full", SPEEDS, [4, 30],
                   np.full((4, 2), 0.01))
    out = _run(tmp_path, workbook, p)
    assert "m.csv:3: order 30 does not exist in the model" in out


def test_speeds_outside_the_model(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "crank nose", "full", [500, 1500, 2500, 9000], ORDERS,
                   AMP)
    out = _run(tmp_path, workbook, p)
    assert "m.csv:5: speed 500 rpm is outside the model's speed range 1000 to 7000 rpm" in out
    assert "m.csv:8: speed 9000 rpm is outside" in out


def test_non_monotone_speed(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "crank nose", "full", [1500, 2500, 2000, 3500], ORDERS,
                   AMP)
    out = _run(tmp_path, workbook, p)
    assert "m.csv:7: speed 2000 rpm is not above the previous row's 2500" in out
    assert "non-monotone speed" in out


def test_nan_samples(tmp_path, workbook):
    p = _write(tmp_path, "# station: crank nose\n# load: full\nspeed,order 4\nrpm,deg\n"
               "1500,0.05\n2500,nan\n3500,\n")
    out = _run(tmp_path, workbook, p)
    assert "m.csv:6: column 'order 4': expected a number, found 'nan'" in out
    assert "m.csv:7: column 'order 4': expected a number, found an empty cell" in out


def test_too_few_cycles(tmp_path, workbook):
    p = signal_csv(tmp_path / "m.csv", "flywheel", [
        {"rpm": 1500, "cycles": 6, "signal": lambda t: 0.1 * np.cos(2 * t)},
        {"rpm": 2500, "cycles": 2, "signal": lambda t: 0.1 * np.cos(2 * t)}])
    out = _run(tmp_path, workbook, p)
    assert "run at 2500 rpm: 2 whole 720 deg cycles" in out and "too few cycles" in out


def test_order_above_the_signals_resolution(tmp_path, workbook):
    p = signal_csv(tmp_path / "m.csv", "flywheel", [
        {"rpm": 1500, "cycles": 5, "signal": lambda t: 0.1 * np.cos(2 * t)}], step_deg=30.0)
    r = CliRunner().invoke(main, ["correlate", str(workbook), str(p), "-o",
                                  str(tmp_path / "o.pdf"), "--orders", "2,8"])
    assert r.exit_code == 2 and not (tmp_path / "o.pdf").exists()
    assert "order 8 asked but 24 samples per cycle resolve orders up to 5.5" in r.output


def test_every_problem_at_once(tmp_path, workbook):
    """Missing load line, an unknown column and a bad unit: all three in one run."""
    p = _write(tmp_path, "# station: crank nose\nspeed,order 4,torque\nrpm,mm,N m\n"
               "1500,0.05,3\n")
    out = _run(tmp_path, workbook, p)
    assert "missing '# load: full'" in out
    assert "unknown column 'torque'" in out
    assert "unit 'mm' is not an angle" in out


def test_calibrated_without_fit_is_a_usage_error(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "crank nose", "full", SPEEDS, ORDERS, AMP)
    r = CliRunner().invoke(main, ["correlate", str(workbook), str(p), "--no-fit",
                                  "--calibrated", str(tmp_path / "c.xlsx"), "-o",
                                  str(tmp_path / "o.pdf")])
    assert r.exit_code == 2 and "--calibrated with --no-fit" in r.output
    assert not (tmp_path / "o.pdf").exists()


def test_output_over_the_measurement_is_refused(tmp_path, workbook):
    p = tracks_csv(tmp_path / "m.csv", "crank nose", "full", SPEEDS, ORDERS, AMP)
    before = p.read_bytes()
    r = CliRunner().invoke(main, ["correlate", str(workbook), str(p), "--json", str(p)])
    assert r.exit_code == 2 and "would overwrite the measurement file" in r.output
    assert p.read_bytes() == before


def test_semicolon_separated(tmp_path, workbook):
    p = _write(tmp_path, "# station: crank nose\n# load: full\nspeed;order 4\nrpm;deg\n"
               "1500;0,05\n")
    out = _run(tmp_path, workbook, p)
    assert "m.csv:3: expected columns separated by commas" in out
