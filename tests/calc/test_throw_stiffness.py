"""Fast throw torsional stiffness against the 3D FE samples it was fitted on (no mesher needed).

Reference: the linear-elastic 3D FE of ``scripts/throw_fe.py`` (validated against G Jp / L and
Saint-Venant's rectangle in ``tests/test_throw_fe_script.py``), solved on the geometries of
``checker/calc/data/throw_stiffness_fe.csv``; tolerance 5 % (issue 33, item 4).
"""

from __future__ import annotations

import csv
import importlib.util
import json

import numpy as np
import pytest

from checker.calc import throw_stiffness as ts

I4 = dict(journal_diameter=0.055, journal_bore=0.0, journal_length=0.027, pin_diameter=0.048,
          pin_bore=0.0, pin_length=0.0244, web_thickness=0.0223, web_width_journal=0.0757,
          web_width_pin=0.0757, crank_radius=0.0473, youngs_modulus=210e9,
          poisson_ratio=210e9 / (2 * 80.8e9) - 1.0)
I4_FE = 518.8e3  # scripts/throw_fe.py, quarter model, size 0.12 Dj (benchmarks/bench_throw_fe.py)


def _samples() -> dict[str, np.ndarray]:
    with ts.SAMPLES_FILE.open() as f:
        rows = list(csv.DictReader(f))
    out = {c: np.array([r[c] for r in rows]) for c in ("name", "set")}
    for c in rows[0]:
        if c not in out:
            out[c] = np.array([float(r[c]) for r in rows])
    return out


def _fast(d: dict[str, np.ndarray]) -> ts.ThrowStiffness:
    return ts.throw_torsional_stiffness(
        journal_diameter=d["Dj"], journal_bore=d["dj"], journal_length=d["Lj"],
        pin_diameter=d["Dp"], pin_bore=d["dp"], pin_length=d["Lp"], web_thickness=d["tw"],
        web_width_journal=d["Bj"], web_width_pin=d["Bp"], crank_radius=d["R"],
        youngs_modulus=d["E"], poisson_ratio=d["nu"], cw_inner_radius=d["cw_ri"],
        cw_outer_radius=d["cw_ro"], cw_angle=d["cw_angle"], cw_thickness=d["cw_t"])


def test_every_fe_sample_within_5_percent():
    d = _samples()
    r = _fast(d)
    err = r.stiffness / d["k_fe"] - 1
    assert len(err) >= 12
    assert r.in_range.all()
    assert np.abs(err).max() < 0.05, dict(zip(d["name"], np.round(err, 4)))
    assert np.abs(err).max() <= r.model_error


def test_held_out_samples_within_5_percent():
    """The hold-out geometries (a separate Latin hypercube) were not used by the fit."""
    d = _samples()
    hold = d["set"] == "holdout"
    assert hold.sum() >= 12
    err = _fast(d).stiffness[hold] / d["k_fe"][hold] - 1
    assert np.abs(err).max() < 0.05


def test_samples_spread_over_the_range():
    """The samples reach into every corner of every group of the fitted range."""
    d = _samples()
    groups = ts._groups(d["Dj"], d["dj"], d["Lj"], d["Dp"], d["dp"], d["Lp"], d["tw"], d["Bj"],
                        d["Bp"], d["R"], d["nu"], d["cw_ri"], d["cw_ro"], d["cw_angle"],
                        d["cw_t"])
    cw = d["cw_t"] > 0
    for name, (lo, hi) in ts.RANGE.items():
        g = groups[name][cw] if name.startswith("cw") else groups[name]
        span = hi - lo
        assert g.min() < lo + 0.1 * span and g.max() > hi - 0.1 * span, name
    assert 0.2 < cw.mean() < 0.8
    assert ((d["dp"] > 0).mean() > 0.3) and ((d["dj"] > 0).mean() > 0.3)


def test_coefficients_are_the_fit_of_the_samples():
    """The committed coefficients are what ``scripts/make_throw_stiffness.py fit`` gives on
    the committed samples (data up to date)."""
    spec = importlib.util.spec_from_file_location(
        "make_throw_stiffness", ts.COEF_FILE.parents[3] / "scripts" / "make_throw_stiffness.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    stored = json.loads(ts.COEF_FILE.read_text(encoding="utf-8"))
    new = mod.fit_and_write(out=None, write=False)
    d = _samples()
    k_stored = mod.model_stiffness(stored["coefficients"], d)
    k_new = mod.model_stiffness(new["coefficients"], d)
    np.testing.assert_allclose(k_new, k_stored, rtol=2e-4)
    assert new["model_error"] == stored["model_error"]
    assert new["errors"]["all"]["max"] == pytest.approx(stored["errors"]["all"]["max"], abs=2e-4)


def test_i4_throw_against_fe_and_classical_formulas():
    """Bell (2013) I4 dimensions: the fast model within 3 % of the FE of the same idealised
    geometry; Carter and Ker Wilson as quoted in issue 33 (506 and 486 kN m/rad, G 80.8 GPa)."""
    r = ts.throw_torsional_stiffness(**I4)
    assert r.in_range[0]
    assert r.stiffness[0] == pytest.approx(I4_FE, rel=0.03)
    args = dict(Dj=0.055, Lj=0.027, Dp=0.048, Lp=0.0244, tw=0.0223, B=0.0757, R=0.0473,
                G=80.8e9)
    assert ts.carter_stiffness(**args) == pytest.approx(506e3, rel=0.002)
    assert ts.ker_wilson_stiffness(dj=0.0, dp=0.0, **args) == pytest.approx(486e3, rel=0.002)


@pytest.mark.parametrize("name, sign", [
    ("pin_diameter", +1), ("journal_diameter", +1), ("web_thickness", +1),
    ("web_width_journal", +1), ("web_width_pin", +1), ("journal_length", -1),
    ("pin_length", -1), ("crank_radius", -1), ("pin_bore", -1), ("journal_bore", -1),
])
def test_monotone_and_smooth_in_each_dimension(name, sign):
    """A study moving one dimension sees the stiffness move one way, smoothly."""
    base = dict(I4, pin_bore=0.015, journal_bore=0.015)
    lo, hi = {"pin_bore": (0.0, 0.028), "journal_bore": (0.0, 0.032),
              "pin_diameter": (0.042, 0.055)}.get(name, (0.85 * base[name], 1.15 * base[name]))
    x = np.linspace(lo, hi, 201)
    k = ts.throw_torsional_stiffness(**{**base, name: x}).stiffness
    dk = np.diff(k) * sign
    assert np.all(dk > 0)
    assert np.all(np.abs(np.diff(dk)) < 0.05 * np.abs(dk).max())   # no kinks


def test_vectorised_equals_one_by_one():
    d = _samples()
    r = _fast(d)
    for i in (0, 7, len(d["name"]) - 1):
        one = _fast({k: v[i] for k, v in d.items()})
        assert one.stiffness.shape == (1,)
        assert one.stiffness[0] == pytest.approx(r.stiffness[i], rel=1e-12)


def test_in_range_flags_outside_the_fit():
    x = ts.throw_torsional_stiffness(**{**I4, "pin_diameter": np.array([0.048, 0.035, 0.050]),
                                        "pin_length": np.array([0.0244, 0.0244, 0.09])})
    assert x.in_range.tolist() == [True, False, False]   # Dp/Dj 0.64; Lp/Dp 1.8
    assert np.all(np.isfinite(x.stiffness)) and np.all(x.stiffness > 0)
    assert x.outside == ("", "Dp/Dj 0.636 (fitted 0.75..1), Bp/Dp 2.16 (fitted 1.2..1.8)",
                         "Lp/Dp 1.8 (fitted 0.35..1.5)")
    # the counterweight groups bound the samples, not the model (no counterweight term): a
    # 200 deg counterweight reaching inside the web circle changes nothing and flags nothing
    cw = ts.throw_torsional_stiffness(**I4, cw_inner_radius=np.array([0.02, 0.05]),
                                      cw_outer_radius=0.08, cw_angle=np.radians([150.0, 200.0]),
                                      cw_thickness=0.02)
    assert cw.in_range.tolist() == [True, True] and cw.outside == ("", "")
    assert cw.stiffness[0] == cw.stiffness[1]
    assert 0.0 < cw.model_error < 0.05
    assert "Carter" in cw.method and "FE" in cw.method


@pytest.mark.parametrize("change, match", [
    (dict(pin_bore=0.048), "pin_bore"), (dict(journal_bore=0.06), "journal_bore"),
    (dict(web_width_pin=0.04), "web_width_pin"), (dict(web_width_journal=0.05), "web_width_j"),
    (dict(web_thickness=0.0), "web_thickness"), (dict(crank_radius=np.nan), "crank_radius"),
    (dict(cw_thickness=0.02, cw_inner_radius=0.05, cw_outer_radius=0.04, cw_angle=2.0), "count"),
])
def test_bad_geometry_is_an_error(change, match):
    with pytest.raises(ValueError, match=match):
        ts.throw_torsional_stiffness(**{**I4, **change})


def test_samples_are_the_scripts_design():
    """The stored geometries are those of ``scripts/make_throw_stiffness.py`` (so ``fe``
    regenerates the same samples)."""
    spec = importlib.util.spec_from_file_location(
        "make_throw_stiffness", ts.COEF_FILE.parents[3] / "scripts" / "make_throw_stiffness.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    design = mod.sample_design()
    d = _samples()
    assert [r["name"] for r in design] == d["name"].tolist()
    assert [r["set"] for r in design] == d["set"].tolist()
    for col in ("Dj", "Dp", "Lj", "Lp", "tw", "R", "Bj", "Bp", "dj", "dp", "E", "nu", "cw_ri",
                "cw_ro", "cw_angle", "cw_t"):
        np.testing.assert_allclose([r[col] for r in design], d[col], rtol=1e-8, err_msg=col)


# Issue 43, item 2: a large overlap (the pin largely within the journal in the end view) made
# the web's effective length R - c_s (Dj + Dp)/2 small or negative: a thinner web gave a
# stiffer throw, and below R = c_s (Dj + Dp)/2 the stiffness could turn negative.
WIDE = dict(journal_diameter=0.080, journal_bore=0.0, journal_length=0.036, pin_diameter=0.068,
            pin_bore=0.0, pin_length=0.034, web_width_journal=0.120, web_width_pin=0.0952,
            youngs_modulus=210e9, poisson_ratio=0.3)


def test_thinner_web_never_stiffer_at_any_overlap():
    """Stiffness rises with the web thickness over a sweep of thicknesses at every crank
    radius from the pin's axis almost on the journal's to the fitted range and beyond (with
    the axes 0.1 mm apart the webs' bending is below round-off: constant)."""
    tw = np.linspace(0.002, 0.040, 77)
    for r in (1e-4, 0.005, 0.010, 0.0204, 0.020, 0.025, 0.030, 0.045, 0.060, 0.100):
        k = ts.throw_torsional_stiffness(**WIDE, web_thickness=tw, crank_radius=r).stiffness
        assert np.all(np.isfinite(k)) and np.all(k > 0), r
        assert np.all(np.diff(k) > 0 if r >= 0.005 else np.diff(k) >= 0), r


def test_issue_cases_positive_and_ordered():
    """The issue's cases: stroke 40 mm, web 16 and 40 mm (the thinner one came out stiffer,
    2.076e6 against 2.068e6 N m/rad); stroke 10 mm, web 2 mm (negative)."""
    k = ts.throw_torsional_stiffness(**WIDE, web_thickness=np.array([0.016, 0.040]),
                                     crank_radius=0.020)
    assert k.stiffness[0] < k.stiffness[1]
    assert not k.in_range.any() and all("overlap S/Dj 0.675" in o for o in k.outside)
    thin = ts.throw_torsional_stiffness(**WIDE, web_thickness=0.002, crank_radius=0.005)
    assert thin.stiffness[0] > 0 and not thin.in_range[0]
    assert thin.outside[0] == ("overlap S/Dj 0.863 (fitted -0.15..0.3),"
                               " tw/Dj 0.025 (fitted 0.2..0.5)")


def test_large_overlap_tends_to_the_stepped_shaft():
    """With the pin's axis on the journal's (R -> 0) the webs bend no more: the throw is the
    series of journal and pin torsion with their junction lengths (the web term vanishes);
    the stiffness falls monotonically with R from there, smoothly through the knee."""
    coef = ts._coefficients()["coefficients"]
    g = 210e9 / 2.6
    jj, jp = np.pi * 0.080**4 / 32, np.pi * 0.068**4 / 32
    shaft = 1 / ((0.036 + coef["c_j"] * 0.080) / (g * jj) + (0.034 + coef["c_p"] * 0.068)
                 / (g * jp))
    r = np.linspace(1e-6, 0.08, 4001)
    k = ts.throw_torsional_stiffness(**WIDE, web_thickness=0.016, crank_radius=r).stiffness
    assert k[0] == pytest.approx(shaft, rel=1e-9)
    dk = np.diff(k)
    assert np.all(dk <= 0) and np.all(dk[r[1:] > 0.002] < 0)
    assert np.all(np.abs(np.diff(dk)) < 0.02 * np.abs(dk).max())   # no kink at the knee


def test_web_length_continuation():
    """Unchanged down to half the crank radius (every sample is above 0.579 R); below it
    equal in value and slope at the knee, positive, increasing in R."""
    r = 0.02
    inset = np.linspace(0.0, 0.05, 5001)
    lw = ts.web_length(r, inset)
    above = r - inset >= ts.WEB_KNEE * r
    assert np.array_equal(lw[above], (r - inset)[above])
    assert np.all(lw > 0) and np.all(np.diff(lw) < 0)
    h = 1e-7
    knee = r - ts.WEB_KNEE * r
    slope = (ts.web_length(r, knee + h) - ts.web_length(r, knee - h)) / (2 * h)
    assert float(slope) == pytest.approx(-1.0, rel=1e-5)
    rr = np.linspace(1e-5, 0.1, 1001)
    assert np.all(np.diff(ts.web_length(rr, 0.0204)) > 0)
    d = _samples()
    c_s = ts._coefficients()["coefficients"]["c_s"]
    assert np.all(d["R"] - c_s * (d["Dj"] + d["Dp"]) / 2 >= 0.579 * d["R"])
