"""The crank frame's bending flexibility of one throw against the stored 3D FE samples.

The samples (geometry and the FE's 6 x 6 end flexibility of a throw clamped at one journal
mid-plane, both mid-plane faces rigid) are ``checker/calc/data/throw_bending_fe.csv``, made by
``scripts/throw_bending_fe.py`` (gmsh + scikit-fem); these tests need no mesher.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from checker.calc import crank_beam as cb

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("throw_bending_fe",
                                               ROOT / "scripts" / "throw_bending_fe.py")
tb = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("throw_bending_fe", tb)
_spec.loader.exec_module(tb)

SAMPLES = tb.read_samples()
# end deflection under end force and rotation under end moment, both planes
TERMS = {"ux/Fx": (0, 0), "uy/Fy": (1, 1), "rx/Mx": (3, 3), "ry/My": (4, 4)}


def test_stored_samples_are_the_scripts_design():
    design = tb.design()
    assert [(n, k) for n, k, _, _ in SAMPLES] == [(n, k) for n, k, _ in design]
    for (_, _, th, _), (_, _, ref) in zip(SAMPLES, design):
        for name in tb.GEOM:
            assert getattr(th, name) == pytest.approx(getattr(ref, name), rel=1e-9)
    assert sum(k == "fit" for _, k, _, _ in SAMPLES) == 17
    assert sum(k == "hold" for _, k, _, _ in SAMPLES) == 12


@pytest.mark.parametrize("name, kind, th, C", SAMPLES, ids=[s[0] for s in SAMPLES])
def test_corrected_frame_within_the_stated_error_of_the_fe(name, kind, th, C):
    """Default frame (web correction) vs FE: bending in the pin plane within 9 %, perpendicular
    to it within 13 % (rotation) and 16 % (deflection): the largest sample errors 8.9, 12.5
    and 15.4 %; the stated error WEB_FIT_ERROR (18 %) adds the FE's own, about 2 %."""
    Cb = tb.frame_flexibility(tb.throw_frame(th))
    err = {t: Cb[i, j] / C[i, j] - 1.0 for t, (i, j) in TERMS.items()}
    bound = {"ux/Fx": 0.16, "uy/Fy": 0.09, "rx/Mx": 0.09, "ry/My": 0.13}
    assert all(abs(err[t]) < bound[t] for t in TERMS), err
    assert cb.WEB_FIT_ERROR >= max(bound.values())


def test_plain_beam_idealisation_is_far_too_flexible():
    """Without the correction the frame is 24 % to 14 times too flexible: the reason for it."""
    errs = []
    for _, _, th, C in SAMPLES:
        Cb = tb.frame_flexibility(tb.throw_frame(th, web_correction=False))
        errs += [Cb[i, j] / C[i, j] - 1.0 for i, j in TERMS.values()]
    assert min(errs) > 0.2
    assert max(errs) > 10.0


def test_fe_flexibility_is_symmetric_and_its_couplings_follow_from_the_throws_symmetry():
    """The throw is its own mirror image about the pin mid-plane z = L/2, so the end
    deflection under an end moment is the rotation times L/2 (both planes); the FE's
    symmetric matrix is positive definite."""
    for _, _, th, C in SAMPLES:
        half = th.length / 2
        assert C[0, 4] == pytest.approx(C[4, 4] * half, rel=2e-3)
        assert C[1, 3] == pytest.approx(-C[3, 3] * half, rel=2e-3)
        assert np.all(np.linalg.eigvalsh(C) > 0)


def test_web_stiffness_factors_vectorised_and_floored():
    """Vectorised over throws; the web's flexible length never drops below 0.05 R."""
    r = np.array([0.047, 0.02])
    f = cb.web_stiffness_factors(
        journal_element=(np.array([0.025, 0.025]), np.array([0.025, 0.025])),
        pin_span=np.array([0.047, 0.047]), web_thickness=np.array([0.022, 0.022]),
        web_width=np.array([0.076, 0.076]), journal_diameter=np.array([0.055, 0.055]),
        pin_diameter=np.array([0.048, 0.048]), crank_radius=r)
    assert all(np.shape(v) == (2,) for v in f)
    assert f[3][1] == pytest.approx(20.0) and f[4][1] == pytest.approx(20.0)
    assert np.all(np.asarray(f) >= 1.0)
