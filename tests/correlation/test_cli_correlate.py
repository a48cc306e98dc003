"""``checker correlate`` end to end: the PDF, the JSON (byte-identical on a re-run) and the
calibrated copy; the comparison without a fit; measured phases give the irregularity."""

from __future__ import annotations

import json

import numpy as np
from click.testing import CliRunner

from checker.cli import main
from tests.helpers import example_path

from .synth import perturbed_tracks, tracks_csv

TRUE = {"damper_damping": 0.70, "damper_stiffness": 1.08}


def _run(*args):
    return CliRunner().invoke(main, ["correlate", *map(str, args)])


def test_correlate_writes_pdf_json_and_calibrated_copy(tmp_path):
    wb = example_path(tmp_path, "i4.xlsx")
    m, _ = perturbed_tracks(tmp_path, wb, "crank nose", np.linspace(1000, 7000, 19), [4, 6, 8],
                            TRUE, 0.03)
    pdf, js, cal = tmp_path / "c.pdf", tmp_path / "c.json", tmp_path / "cal.xlsx"
    r = _run(wb, m, "-o", pdf, "--json", js, "--calibrated", cal)
    assert r.exit_code == 0, r.output
    assert pdf.read_bytes()[:5] == b"%PDF-" and cal.exists()
    first = js.read_bytes()
    d = json.loads(first)
    assert d["measurement"]["model_station"] == "Crank nose"
    assert [t["order"] for t in d["tracks"]] == [4, 6, 8]
    cal_d = d["calibration"]
    assert cal_d["calibrated_workbook"] == "cal.xlsx"
    assert cal_d["residual_rms_after_percent"] < cal_d["residual_rms_before_percent"]
    names = {p["name"]: p for p in cal_d["parameters"]}
    assert abs(names["damper_damping"]["factor"] - 0.70) < 0.035
    assert {"order", "speed_measured_rpm", "amplitude_measured_deg", "speed_predicted_rpm",
            "amplitude_difference_predicted_percent", "speed_fitted_rpm"} <= set(d["peaks"][0])
    assert d["irregularity_lowest_speed"]["predicted_percent"] > 0
    r = _run(wb, m, "-o", pdf, "--json", js, "--calibrated", cal)
    assert r.exit_code == 0 and js.read_bytes() == first  # deterministic


def test_compare_only_with_phases(tmp_path):
    """--no-fit: no calibrated copy; tracks with phases give the measured synthesis and
    irregularity (here the model's own tracks: they agree with the prediction)."""
    wb = example_path(tmp_path, "i4.xlsx")
    m0, s = perturbed_tracks(tmp_path, wb, "flywheel", [1000, 1500, 2000, 3000], [0.5, 1, 2,
                                                                                  4], {}, 0.0)
    th = s.solve(None, s.measured, s.order_index)
    m = tracks_csv(tmp_path / "ph.csv", "flywheel", "full", [1000, 1500, 2000, 3000],
                   [0.5, 1, 2, 4], np.degrees(np.abs(th)), np.degrees(np.angle(th)))
    pdf = tmp_path / "c.pdf"
    r = _run(wb, m, "-o", pdf, "--json", "-", "--no-fit")
    assert r.exit_code == 0, r.output
    assert not (tmp_path / "i4-calibrated.xlsx").exists()
    d = json.loads(r.stdout)
    assert "calibration" not in d
    irr = d["irregularity_lowest_speed"]
    assert irr["measured_percent"] == irr["predicted_measured_orders_percent"]
    syn = d["synthesis"]
    assert np.allclose(syn["measured_deg"], syn["predicted_deg"], rtol=1e-5)
