"""Calibration: a measurement synthesised from a perturbed model (damper damping -30 %, damper
stiffness +8 %, 3 % noise) is recovered by the fit; the prediction is the check's own; the
calibrated copy reproduces the fitted model and the input stays untouched."""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

from checker import correlation as cr
from checker.correlation.calibrated import calibrated_workbook
from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.evaluation import graph
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content

from .synth import perturbed_tracks

TRUE = {"damper_damping": 0.70, "damper_stiffness": 1.08}
"""The perturbation of the issue: damper damping -30 %, damper (ring) stiffness +8 %."""


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    p = tmp_path_factory.mktemp("i4") / "i4.xlsx"
    write_workbook(p, example_content())
    return p


@pytest.fixture(scope="module")
def i6(tmp_path_factory):
    """The I6 example; its viscous damper's silicone given a shear modulus (Maxwell: the
    coupling's stiffness in series with its damping, Andre & Spurk 1982), so that the damper
    has a stiffness to perturb (150 kPa: k_s = G Phi = 393 kN m/rad, of the order of the
    silicone's c Omega at the 6th order's resonance)."""
    content = i6_content(damper_ring=True)
    content["Damper"].append(("Silicone shear modulus", 150, "kPa",
                              "test: the silicone's elasticity (Maxwell)"))
    p = tmp_path_factory.mktemp("i6") / "i6.xlsx"
    write_workbook(p, content)
    return p


def _recovered(fit, tol=0.05):
    got = fit.factors()
    for k, v in TRUE.items():
        assert got[k] == pytest.approx(v, rel=tol), (k, got)
        p = next(x for x in fit.parameters if x.key == k)
        assert p.determined and p.low95 / p.start < v < p.high95 / p.start, p


def test_i4_rubber_damper_recovered(tmp_path, i4):
    """I4 (rubber damper, crank nose, 25 speeds 1000..7000 rpm, orders 2..8): the loss factor
    and storage stiffness within 5 % of the perturbed values, inside their 95 % intervals."""
    m, _ = perturbed_tracks(tmp_path, i4, "crank nose", np.linspace(1000, 7000, 25),
                            [2, 4, 6, 8], TRUE, 0.03)
    c = cr.run(i4, m)
    _recovered(c.fit)
    assert c.fit.rms_after < 0.04 < c.fit.rms_before
    # the peaks of the fitted model sit where the measured ones are
    for r in c.peaks:
        if r["speed_measured"] is not None and r["speed_fitted"] is not None:
            assert abs(r["speed_difference_fitted"]) < 0.02 * r["speed_measured"]


def test_i6_viscous_damper_recovered(tmp_path, i6):
    """I6 (viscous damper with an elastic silicone, 10 speeds 1000..2800 rpm, orders 3..9):
    the silicone's damping and shear stiffness within 5 %."""
    m, _ = perturbed_tracks(tmp_path, i6, "crank nose", np.linspace(1000, 2800, 10),
                            [3, 4.5, 6, 7.5, 9], TRUE, 0.03)
    c = cr.run(i6, m)
    _recovered(c.fit)


def test_i6_as_shipped_viscous_damping_recovered(tmp_path):
    """The I6 template as shipped: a purely viscous silicone (no stiffness to fit, said in a
    note); its damping -30 % recovered within 5 % from 10 speeds at the flywheel."""
    p = tmp_path / "i6.xlsx"
    write_workbook(p, i6_content(damper_ring=True))
    m, _ = perturbed_tracks(tmp_path, p, "flywheel", np.linspace(1000, 2800, 10),
                            [3, 4.5, 6, 7.5, 9], {"damper_damping": 0.70}, 0.03)
    c = cr.run(p, m)
    assert [x.key for x in c.fit.parameters] == ["damper_damping", "crank_damping"]
    assert c.fit.factors()["damper_damping"] == pytest.approx(0.70, rel=0.05)
    assert any("no damper stiffness is fitted" in n for n in c.notes)


def test_prediction_is_the_checks_own(tmp_path, i4):
    """With the workbook's values the re-solve gives the check's crank-nose response (graph
    quantity tv.nose_amplitude's detail) to round-off at the check's own speeds."""
    eng = load_engine(i4)
    q = graph.run(eng, ["tv.nose_amplitude"]).quantities["tv.nose_amplitude"]
    speeds = np.asarray(q.detail.speeds)[::10]
    m, s = perturbed_tracks(tmp_path, i4, "crank nose", speeds * 30 / np.pi, [2, 4, 6],
                            {}, 0.0)
    theta = s.solve(None, s.measured, s.order_index)
    ref = q.detail.theta[0][::10][:, s.order_index]
    assert np.max(np.abs(theta - ref)) <= 1e-12 * np.max(np.abs(ref))


def test_calibrated_copy(tmp_path, i4):
    """The copy's cells scaled by the fitted factors and marked FITTED with the file named;
    evaluated again, it gives the fitted model's amplitudes; the input is not modified."""
    before = hashlib.sha256(i4.read_bytes()).hexdigest()
    m, _ = perturbed_tracks(tmp_path, i4, "crank nose", np.linspace(1000, 7000, 13), [4, 6],
                            TRUE, 0.0)
    c = cr.run(i4, m)
    data, cells = calibrated_workbook(i4, c.fit, "measured.csv", "crank nose, full load")
    assert hashlib.sha256(i4.read_bytes()).hexdigest() == before
    assert {x["cell"] for x in cells} >= {"Damper!B2", "TVModel!F3"}
    out = tmp_path / "cal.xlsx"
    out.write_bytes(data)
    import openpyxl

    ws = openpyxl.load_workbook(out)["Damper"]
    assert ws["D2"].value.startswith("FITTED by checker correlate to measured.csv")
    c2 = cr.run(out, m, fit=False)
    fitted = np.abs(c.fitted[c.setup.measured])
    again = np.abs(c2.predicted[c2.setup.measured])
    assert again == pytest.approx(fitted, rel=2e-5)  # cells rounded to 6 digits


def test_temperature_outside_the_rubber_table(tmp_path, i4):
    m, _ = perturbed_tracks(tmp_path, i4, "crank nose", [1500, 2500, 3500], [4], {}, 0.0)
    text = m.read_text().replace("# load: full", "# load: full\n# damper temperature: 200 °C")
    m.write_text(text)
    with pytest.raises(InputErrors, match="outside the DamperRubber table"):
        cr.run(i4, m)


def test_worked_example_of_the_docs(i4):
    """docs/correlation.md's worked example (examples/i4-measured-crank-nose.csv, 60 °C: the
    DamperRubber table's value equals the workbook's nominal rubber): the numbers it prints."""
    from pathlib import Path

    m = Path(__file__).resolve().parents[2] / "examples" / "i4-measured-crank-nose.csv"
    c = cr.run(i4, m)
    f = c.fit.factors()
    assert f["damper_damping"] == pytest.approx(0.7345, rel=1e-3)
    assert f["damper_stiffness"] == pytest.approx(1.0821, rel=1e-3)
    assert f["crank_damping"] == pytest.approx(0.966, rel=2e-3)
    assert c.fit.rms_before == pytest.approx(0.1817, rel=2e-3)
    assert c.fit.rms_after == pytest.approx(0.0227, rel=5e-3)
    assert c.fit.points == 33
    k = next(p for p in c.fit.parameters if p.key == "damper_stiffness")
    assert k.start == pytest.approx(25497, rel=1e-4)  # Phi_r G'(60 °C)


def test_excitation_scale_recovered(tmp_path, i4):
    """--fit-excitation: the crank-torque harmonics x1.10 besides the damper's perturbation,
    all recovered within 5 % (the off-resonance flanks fix the excitation, the peaks the
    damping)."""
    true = dict(TRUE, excitation_scale=1.10)
    m, _ = perturbed_tracks(tmp_path, i4, "crank nose", np.linspace(1000, 7000, 25),
                            [2, 4, 6, 8], true, 0.03)
    got = cr.run(i4, m, fit_excitation=True).fit.factors()
    for k, v in true.items():
        assert got[k] == pytest.approx(v, rel=0.05), (k, got)


def test_explicit_speed_points(i4):
    """The loads module's sweep takes explicit speeds (the measured ones), sorted."""
    import dataclasses

    from checker.description.engine import Params
    from checker.modules import loads

    eng = load_engine(i4)
    eng = dataclasses.replace(eng, params=Params({**eng.params, "speed_points": (300.0, 150.0)}))
    assert loads.speed_sweep(eng)[0].tolist() == [150.0, 300.0]


def test_order_the_model_cancels_is_left_out(tmp_path):
    """V8 (cross-plane: the firing order cancels the 6th at the crank nose): a measured 6th of
    0.001 deg (imbalance, noise) would dominate relative residuals against the model's
    round-off; it is left out with a note and the damper still comes back within 5 %."""
    from checker.workbook.example_v8 import v8_content

    p = tmp_path / "v8.xlsx"
    write_workbook(p, v8_content())
    m, s = perturbed_tracks(tmp_path, p, "crank nose", np.linspace(1000, 6000, 21), [4, 6, 8],
                            TRUE, 0.03)
    assert np.abs(s.solve(None, s.measured, s.order_index))[:, 1].max() < 1e-15
    lines = m.read_text().splitlines()
    m.write_text("\n".join(lines[:4] + [",".join(x.split(",")[:2] + ["0.001"] + x.split(",")[3:])
                                        for x in lines[4:]]) + "\n")
    c = cr.run(p, m)
    assert c.fit.cancelled == (6.0,)
    assert any(n.startswith("Order 6 left out of the fit") for n in c.notes)
    for k, v in TRUE.items():
        assert c.fit.factors()[k] == pytest.approx(v, rel=0.05)
