"""The 3D FE of crank pieces on their main bearings (``scripts/crank_piece_fe.py``, optional
extra ``fe``) against symmetry and the throw FE.

Runs only where gmsh and scikit-fem are installed (``pip install -e .[fe]``); coarse meshes,
a minute or two in all.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import pytest

pytest.importorskip("gmsh")
pytest.importorskip("skfem")

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("crank_piece_fe",
                                               ROOT / "scripts" / "crank_piece_fe.py")
fe = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("crank_piece_fe", fe)
_spec.loader.exec_module(fe)

TH = fe.throw_fe.I4_THROW
SIZE = 0.35


@pytest.fixture(scope="module")
def single():
    return fe.solve_piece(TH, [0.0], SIZE).stiffness


def test_one_throw_piece_is_the_throw_fe(single):
    """A piece of one throw is the throw FE's definition (the same mesh generator and end
    conditions; the throw FE solves the quarter): within the discretisation error."""
    assert single == pytest.approx(fe.throw_fe.solve_throw(TH, SIZE).stiffness, rel=0.01)


def test_free_shared_journal_gives_the_series_sum(single):
    """Two throws at 180 deg with the shared journal free: the series sum of the throw alone
    (the issue's check: 0.05 %)."""
    r = fe.solve_piece(TH, [0.0, math.pi], SIZE, bearings=False)
    assert r.stiffness == pytest.approx(single / 2, rel=0.005)
    assert r.main_rotation[1] == pytest.approx(0.5, abs=0.002)


def test_bearing_on_the_shared_journal_stiffens_the_throws_at_180_deg(single):
    """Held by its bearing, the shared journal cannot follow the throws' opposite tilts: the
    piece is about 17 % stiffer than the series sum, and the bearing reacts a force across
    the pin plane (x); pins in line (mirror-image neighbours) add in series."""
    held = fe.solve_piece(TH, [0.0, math.pi], SIZE)
    assert 0.14 < held.stiffness / (single / 2) - 1 < 0.20
    assert abs(held.bearing_force[1, 0]) > 5.0 and held.bearing_force[1, 1] == 0.0
    inline = fe.solve_piece(TH, [0.0, 0.0], SIZE)
    assert inline.stiffness == pytest.approx(single / 2, rel=0.005)
    assert abs(inline.bearing_force[1, 0]) < 0.05

