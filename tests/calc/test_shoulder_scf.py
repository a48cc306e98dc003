"""Shoulder-fillet stress concentration (Peterson's charts as fitted in Roark, Table 17.1)."""

from __future__ import annotations

import pytest

from checker.calc.shoulder_scf import shoulder_fillet_scf


def test_against_chart_readings():
    # Peterson's charts as reproduced by Budynas & Nisbett, Shigley's Mechanical Engineering
    # Design, 10th ed., Figs. A-15-9 (bending) and A-15-8 (torsion): D/d = 1.5, r/d = 0.1
    # reads K_t about 1.7 in bending; D/d = 1.33, r/d = 0.1 about 1.35 in torsion (chart
    # reading, 5 %)
    assert shoulder_fillet_scf(1.5, 1.0, 0.1, "bending")[0] == pytest.approx(1.7, rel=0.05)
    assert shoulder_fillet_scf(1.333, 1.0, 0.1, "torsion")[0] == pytest.approx(1.35, rel=0.05)


def test_branches_meet_and_sharper_fillets_concentrate_more():
    lo = shoulder_fillet_scf(1.4, 1.0, 0.1 - 1e-9, "bending")[0]  # h/r just above 2
    hi = shoulder_fillet_scf(1.4, 1.0, 0.1 + 1e-9, "bending")[0]  # just below 2
    assert lo == pytest.approx(hi, rel=0.03)
    ks = [shoulder_fillet_scf(1.33, 1.0, r, "bending")[0] for r in (0.02, 0.05, 0.1, 0.15)]
    assert ks == sorted(ks, reverse=True) and ks[-1] >= 1.0


def test_out_of_range_is_flagged_and_bad_geometry_refused():
    assert not shoulder_fillet_scf(2.0, 1.0, 0.01, "torsion")[1]  # h/r = 50
    with pytest.raises(ValueError):
        shoulder_fillet_scf(1.0, 1.2, 0.1, "bending")
