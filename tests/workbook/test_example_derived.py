"""The derived cells of the example data files are up to date with their derivation
(:mod:`checker.workbook.example_derived`; ``python scripts/make_example_derived.py`` rewrites
them), and the derivation follows the cells it derives from."""

from __future__ import annotations

import math

import pytest

from checker.workbook import example_data as ed
from checker.workbook import example_derived as dv


@pytest.mark.parametrize("engine", ed.ENGINES)
def test_derived_cells_are_up_to_date(engine):
    content = ed.load_example(engine)
    diffs = ed.same_content(dv.derived_cells(engine, content), content, engine)
    assert not diffs, ("run python scripts/make_example_derived.py:\n  "
                       + "\n  ".join(diffs[:10]))


def test_i6_throws_and_oil_holes_follow_their_inputs():
    c = ed.load_example("i6")
    # throw = -firing angle (mod 360): order 1-5-3-6-2-4 gives pairs 1&6, 2&5, 3&4
    assert dv.i6_throw_angles(c) == {1: 0, 2: 240, 3: 120, 4: 120, 5: 240, 6: 0}
    d = dv.derived_i6(c)
    pin_d = dv.bearing(c, "big end", "journal diameter")
    assert dv.param(d, "Fatigue", "Pin journal oil hole height") == pytest.approx(
        pin_d / 2 / math.sqrt(2), abs=0.005)
    # a wider bay moves the rear webs and the pins, not the front webs
    c2 = ed.load_example("i6")
    i = next(k for k, r in enumerate(c2["Engine"]) if r[0] == "Cylinder spacing")
    c2["Engine"][i] = (c2["Engine"][i][0], 140.0, *c2["Engine"][i][2:])
    rows = {r[0]: r for r in dv.i6_crank_mass_rows(c2)}
    old = {r[0]: r for r in c["CrankMass"][1]}
    assert rows["Web1"][7] == old["Web1"][7]
    assert rows["Web2"][7] == pytest.approx(old["Web2"][7] + 10.0)
    assert rows["Crankpin1"][7] == 70.0


def test_i6_counterweights_balance_the_crank():
    """Sum of the CrankMass rows' unbalance m (Z, Y) and of its couple: zero (the rows are
    rounded to 1 um)."""
    c = ed.load_example("i6")
    spacing = dv.param(c, "Engine", "Cylinder spacing")
    throws = dv.i6_throw_angles(c)
    force = [0.0, 0.0]
    couple = [0.0, 0.0]
    for _loc, throw, _kind, m, _x, y, z, ax, ref, _note in dv.i6_crank_mass_rows(c):
        g = math.radians(throws[throw])
        r = 137.0 / 2 if ref == "pin axis" else 0.0
        py, pz = y + r * math.cos(g), z + r * math.sin(g)
        zpos = (throw - 1) * spacing + ax
        force[0] += m * pz
        force[1] += m * py
        couple[0] += m * pz * zpos
        couple[1] += m * py * zpos
    # the pins and webs alone leave U = 0.234 kg m per throw; the six throws cancel as forces
    # and couples (in-line six), so the counterweights must too
    assert math.hypot(*force) < 1e-2  # kg mm
    assert math.hypot(*couple) < 1.0  # kg mm^2 (~1e-6 of one throw's U x pitch)


def test_v8_firing_and_throws_follow_the_firing_order():
    c = ed.load_example("v8")
    cyl = dv.v8_cylinders(c)
    assert cyl["firing"] == {1: 0, 8: 90, 7: 180, 2: 270, 6: 360, 5: 450, 4: 540, 3: 630}
    assert dv.v8_pin_throw(c) == {1: 0.0, 2: 90.0, 3: 270.0, 4: 180.0}  # cross-plane
    d = dv.derived_v8(c)
    assert dv.web_thickness(d) == pytest.approx(
        (111.76 - 26.0 - 48.0) / 2, abs=0.005)
