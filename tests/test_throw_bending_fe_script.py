"""The throw bending FE (``scripts/throw_bending_fe.py``, optional extra ``fe``) against closed
forms and the stored samples. Runs only where gmsh and scikit-fem are installed; small meshes.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("gmsh")
pytest.importorskip("skfem")

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("throw_bending_fe",
                                               ROOT / "scripts" / "throw_bending_fe.py")
tb = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("throw_bending_fe", tb)
_spec.loader.exec_module(tb)

E = 210e9


def test_cantilever_shaft_against_timoshenko_beam():
    """Round shaft D 50, L 200 mm, rigid end faces, nu = 0 (no Poisson restraint at the rigid
    faces): end flexibility = the Timoshenko cantilever (rotation L/EI, deflection
    L^3/3EI + L/(kappa G A), kappa = 6 (1+nu)/(7+6 nu), Cowper 1966; axial L/EA; torsion
    L/GJ) within 0.1 %. With nu = 0.3 the rigid faces stiffen the ends (1.2 % at L/D = 4,
    half of that at L/D = 8: an end effect)."""
    D, L = 0.05, 0.2
    I, A = math.pi * D**4 / 64, math.pi * D**2 / 4
    C = tb.shaft_flexibility(D, L, E=E, nu=0.0, size=0.3)
    G, kappa = E / 2, 6 / 7
    ref = {(0, 0): L**3 / (3 * E * I) + L / (kappa * G * A), (1, 1): L**3 / (3 * E * I)
           + L / (kappa * G * A), (3, 3): L / (E * I), (4, 4): L / (E * I),
           (0, 4): L**2 / (2 * E * I), (1, 3): -L**2 / (2 * E * I), (2, 2): L / (E * A),
           (5, 5): L / (G * 2 * I)}
    for (i, j), v in ref.items():
        assert C[i, j] == pytest.approx(v, rel=1e-3), (i, j)
    stiffening = []
    for length in (0.2, 0.4):
        C3 = tb.shaft_flexibility(D, length, E=E, nu=0.3, size=0.3)
        stiffening.append(1 - C3[3, 3] / (length / (E * I)))
    assert 0.005 < stiffening[0] < 0.02
    assert stiffening[1] == pytest.approx(stiffening[0] / 2, rel=0.15)


def test_half_model_equals_the_whole_throw_and_reproduces_the_stored_i4():
    """The half model (mirror plane of both axes) equals the whole throw within the
    discretisation error (size 0.3 Dj: 1.3 %, 0.2 Dj: 0.4 %, shrinking with the mesh); a coarse
    mesh (0.25 Dj) is within 2 % of the stored I4 sample (0.15 Dj; the FE converges from the
    stiff side: +1.4 % from 0.25 to 0.15)."""
    th = tb.I4
    Ch, _ = tb.fe_flexibility(th, 0.2, half=True)
    Cf, _ = tb.fe_flexibility(th, 0.2, half=False)
    for i, j in ((0, 0), (1, 1), (3, 3), (4, 4)):
        assert Ch[i, j] == pytest.approx(Cf[i, j], rel=0.006)
    stored = {n: C for n, _, _, C in tb.read_samples()}["I4"]
    C, _ = tb.fe_flexibility(th, 0.25)
    for i, j in ((0, 0), (1, 1), (3, 3), (4, 4)):
        assert C[i, j] == pytest.approx(stored[i, j], rel=0.02)
        assert C[i, j] < stored[i, j]
    assert np.all(np.linalg.eigvalsh(C) > 0)
