"""The throw FE (``scripts/throw_fe.py``, optional extra ``fe``) against closed forms.

Runs only where gmsh and scikit-fem are installed (``pip install -e .[fe]``); small meshes,
a few seconds in all.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import math
import sys
from pathlib import Path

import pytest

pytest.importorskip("gmsh")
pytest.importorskip("skfem")

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("throw_fe", ROOT / "scripts" / "throw_fe.py")
fe = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("throw_fe", fe)
_spec.loader.exec_module(fe)

E, NU = 210e9, 0.3
G = E / (2 * (1 + NU))


@pytest.mark.parametrize("D, d", [(0.05, 0.0), (0.05, 0.025), (0.06, 0.045)])
def test_round_shaft_against_G_Jp_over_L(D, d):
    """Plain and hollow shafts: k = G pi (D^4 - d^4) / (32 L) within 0.3 % (the quarter model
    with the throw's boundary conditions; curved quadratic tetrahedra)."""
    L = 0.1
    k = fe.shaft(D, d, L, E=E, nu=NU, size=0.3)
    assert k == pytest.approx(G * math.pi * (D**4 - d**4) / (32 * L), rel=0.003)


def test_round_shaft_full_model():
    """The whole shaft (no symmetry planes) gives the same."""
    k = fe.shaft(0.05, 0.02, 0.08, E=E, nu=NU, size=0.35, full=True)
    assert k == pytest.approx(G * math.pi * (0.05**4 - 0.02**4) / (32 * 0.08), rel=0.003)


def test_rectangular_bar_free_warping_against_saint_venant():
    """End faces free axially: a 2:1 rectangular bar twists as Saint-Venant's (Timoshenko &
    Goodier 1970, eq. 163: J = 0.2287 a b^3 for a/b = 2) within 1 %; held axially (warping
    prevented at the ends) it is stiffer, the difference the throw's definition is about."""
    a, b, L = 0.04, 0.02, 0.12
    j = fe.rect_torsion_constant(a, b)
    assert j / (a * b**3) == pytest.approx(0.2287, abs=2e-4)
    k_free = fe.rect_bar(a, b, L, E=E, nu=NU, size=0.25)
    assert k_free == pytest.approx(G * j / L, rel=0.01)
    k_held = fe.rect_bar(a, b, L, E=E, nu=NU, size=0.25, variant="held")
    assert k_held > 1.01 * k_free


def test_throw_definition_and_symmetry():
    """A small throw: the quarter model equals the whole throw (the symmetry is exact); faces
    held axially make it much stiffer than the definition's free faces; rigid (non-warping)
    faces free to tilt are within 1 % of the definition."""
    th = dataclasses.replace(fe.I4_THROW, Lp=0.02)
    q = fe.solve_throw(th, 0.3).stiffness
    full = fe.solve_throw(th, 0.3, full=True).stiffness
    assert full == pytest.approx(q, rel=0.005)
    held = fe.solve_throw(th, 0.3, variant="held").stiffness
    rigid = fe.solve_throw(th, 0.3, variant="rigid").stiffness
    assert held > 1.3 * q
    assert rigid == pytest.approx(q, rel=0.01) and rigid >= q


def test_counterweight_is_in_the_solid():
    """The meshed volume of a throw with counterweights exceeds the one without by exactly
    the two annular sectors outside the web outline's journal circle."""
    import numpy as np

    cw = dataclasses.replace(fe.I4_THROW, cw_ri=0.02, cw_ro=0.085, cw_angle=math.radians(150),
                             cw_t=0.0223)

    def volume(th):
        pts, tets = fe.build_mesh(th, 0.3)
        p = pts[tets[:, :4]]
        v = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                      p[:, 3] - p[:, 0])
        return 4 * np.abs(v).sum() / 6       # quarter model

    added = 2 * cw.cw_t * cw.cw_angle / 2 * (cw.cw_ro**2 - (cw.Bj / 2) ** 2)
    assert volume(cw) - volume(fe.I4_THROW) == pytest.approx(added, rel=0.01)
