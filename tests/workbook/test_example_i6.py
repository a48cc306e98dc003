"""The I6 diesel example workbook (checker.workbook.example_i6): it loads cleanly and carries the
published numbers of Mendes, Meirelles & Zampieri (2008), doi 10.1243/14644193JMBD126, as
reproduced by openTorsion (Aalto-Arotor/openTorsion, examples/ICE_example.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg

from checker.calc.crank_forces import throw_angles
from checker.description.engine import load_engine
from checker.workbook.example import example_content, write_workbook
from checker.workbook.example_i6 import i6_content

RPM = math.pi / 30  # rad/s per rpm

# openTorsion examples/ICE_example.py, assembly of Mendes et al. Fig. 4 without the damper:
# J2 pulley, J3 gear train, J4..J9 cylinders 1..6, J10 flywheel [kg m^2] (printed to 1e-4)
PUBLISHED_J = [0.0170, 0.0090, 0.0467, 0.0327, 0.0467, 0.0467, 0.0327, 0.0487, 2.0750]
# k2..k9 [N m/rad] (printed to 1e3 N m/rad)
PUBLISHED_K = [1.106e6, 1.631e6, 1.253e6, 1.253e6, 1.678e6, 1.253e6, 1.253e6, 1.976e6]
# Free-free natural frequencies of that chain [Hz], shared/reference/torsion.md sections 1.1 and 5
# ("my free-free eig 216.6/592.7/984.9 Hz (no damper ring)"; printed to 0.1 Hz)
PUBLISHED_F = [216.6, 592.7, 984.9, 1171.0, 1416.0, 1660.0, 1794.4, 2993.5]


@pytest.fixture(scope="module")
def engine(tmp_path_factory):
    path = tmp_path_factory.mktemp("i6") / "i6.xlsx"
    write_workbook(path, i6_content())
    return load_engine(path)  # raises InputErrors on any input error


def _chain_frequencies(stations) -> np.ndarray:
    """Undamped natural frequencies [Hz] of a TV chain (free-free)."""
    j = np.array([s.inertia for s in stations])
    k = np.array([s.stiffness for s in stations[:-1]])
    n = len(j)
    kk = np.zeros((n, n))
    for e, ke in enumerate(k):
        kk[e:e + 2, e:e + 2] += ke * np.array([[1.0, -1.0], [-1.0, 1.0]])
    w2 = scipy.linalg.eigh(kk, np.diag(j), eigvals_only=True)
    return np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)


def test_same_sheets_and_columns_as_the_i4_example():
    i4, i6 = example_content(), i6_content()
    # the I4 alone carries the optional rubber table against temperature
    assert list(i6) == [s for s in i4 if s != "DamperRubber"]
    for name, body in i4.items():
        if isinstance(body, tuple) and name != "DamperRubber":
            assert [c for c, _u in i6[name][0]] == [c for c, _u in body[0]], name


def test_every_value_has_a_source_or_an_assumption():
    for name, body in i6_content(damper_ring=True).items():
        if name == "Notes":
            continue
        rows = body if isinstance(body, list) else body[1]
        for row in rows:
            if isinstance(body, list) and row[1] is None:
                continue  # a blank for the user to fill (FAT-003's nose inputs): no value
            note = str(row[-1])
            assert "ASSUMPTION" in note or "Mendes" in note or "MaxxForce" in note, (name, row)


def test_loads_without_input_errors(engine):
    p = engine.params
    assert p["cylinders"] == 6 and p["layout"] == "inline"
    # Mendes et al. via openTorsion: bore 105 mm, stroke 137 mm (r = 68.5 mm), rod 207 mm
    assert p["bore"] == pytest.approx(0.105)
    assert p["stroke"] == pytest.approx(0.137)
    assert p["rod_length"] == pytest.approx(0.207)
    # published reciprocating mass m_a = 2.521 kg = piston assembly + rod small-end share
    m_rec = p["piston_mass"] + p["rod_mass"] * p["rod_com"] / p["rod_length"]
    assert m_rec == pytest.approx(2.521, abs=5e-4)
    assert p["speed_min"] == pytest.approx(1000 * RPM) and p["speed_max"] == pytest.approx(
        2550 * RPM)
    assert engine.assumptions and all("ASSUMPTION" in a for a in engine.assumptions)


def test_firing_order_and_throws(engine):
    cyl = engine.cylinders
    assert [c.number for c in cyl] == [1, 2, 3, 4, 5, 6]
    assert engine.params["firing_order"] == "1-5-3-6-2-4"
    assert [c.number for c in sorted(cyl, key=lambda c: c.firing_angle)] == [1, 5, 3, 6, 2, 4]
    # even firing: 120 deg between consecutive firings; cylinder i fires phi_i after cylinder 1
    fired = sorted(c.firing_angle for c in cyl)
    assert np.diff(fired) == pytest.approx([2 * math.pi / 3] * 5)
    assert {c.number: round(math.degrees(c.firing_angle)) for c in cyl} == {
        1: 0, 2: 480, 3: 240, 4: 600, 5: 120, 6: 360}
    # the throw angle column agrees with the throws the firing angles imply (gamma = -phi)
    gam = throw_angles([c.firing_angle for c in cyl], [c.bank_angle for c in cyl],
                       [c.pin - 1 for c in cyl], 6)
    assert np.degrees(gam) == pytest.approx([math.degrees(c.throw_angle) for c in cyl])
    # mirror-symmetric I6 crank: pairs 1&6, 2&5, 3&4 share a direction, 120 deg apart
    deg = {c.number: round(math.degrees(c.throw_angle)) % 360 for c in cyl}
    assert deg[1] == deg[6] == 0 and deg[2] == deg[5] and deg[3] == deg[4]
    assert {deg[2], deg[3]} == {120, 240}


def test_bearings(engine):
    b = engine.bearings
    assert len(b) == 13
    mains = [x for x in b if x.type == "main"]
    ends = [x for x in b if x.type == "big end"]
    assert [x.name for x in mains] == [f"M{i}" for i in range(1, 8)]
    assert [x.name for x in ends] == [f"BE{i}" for i in range(1, 7)]
    # MaxxForce 4.8/7.2 manual: shell bore 63.015-63.031 mm, clearance 0.026-0.081 mm
    assert ends[0].diameter == pytest.approx(62.97e-3)
    assert ends[0].clearance == pytest.approx(0.027e-3)


def test_crank_mass(engine):
    m = engine.crank_mass
    assert {x.throw for x in m} == set(range(1, 7))
    pins = [x for x in m if x.kind == "pin"]
    assert len(pins) == 6 and all(x.reference == "pin axis" for x in pins)
    assert sum(x.kind == "web" for x in m) == 12
    # 8-counterweight crank: none on throws 2 and 5 (published inertias 0.0327 vs 0.0467)
    assert sorted({x.throw for x in m if x.kind == "counterweight"}) == [1, 3, 4, 6]
    # lateral coordinates in Z (crank frame), not in the axial offset X: every centre of mass
    # lies in its component's plane, inside the web (|X| <= half the web thickness)
    assert all(x.x == 0.0 for x in m)
    gam = {c.pin: c.throw_angle for c in engine.cylinders}
    for x in m:
        if x.kind == "pin":
            continue
        ang = math.atan2(x.z, x.y)  # crank-frame direction from Y toward Z
        if x.kind == "web":
            expected = gam[x.throw]
        else:
            # opposite the throw, or (webs next to throws 2 and 5) opposite the bisector of the
            # own and the uncounterweighted neighbour throw, 120 deg apart
            web = int(x.location.split()[0][3:])
            nb = {2: 2, 5: 2, 8: 5, 11: 5}.get(web)
            expected = gam[x.throw] + math.pi
            if nb is not None:
                expected = math.atan2(math.sin(gam[x.throw]) + math.sin(gam[nb]),
                                      math.cos(gam[x.throw]) + math.cos(gam[nb])) + math.pi
        assert math.cos(ang - expected) == pytest.approx(1.0), x.location
        assert 0 < x.axial < engine.params["main_spacing"]


def test_crank_is_statically_and_dynamically_balanced(engine):
    """A real in-line six with eight counterweights is balanced: the crank's own masses (webs,
    counterweights, pins at the crank radius) have no resultant force or couple (Taylor 1985,
    vol. 2, ch. 8: the I6's rotating masses are inherently balanced only when every throw
    carries the same unbalance). Sums by hand over the sheet; tolerance: the coordinates are
    rounded to 1 um, 1e-6 of one throw's unbalance."""
    r = engine.params["stroke"] / 2
    spacing = engine.params["main_spacing"]
    gam = {c.pin: c.throw_angle for c in engine.cylinders}
    force, couple, per_throw = np.zeros(2), np.zeros(2), np.zeros((7, 2))
    for x in engine.crank_mass:
        pos = np.array([x.z, x.y])
        if x.reference == "pin axis":
            pos = pos + r * np.array([math.sin(gam[x.throw]), math.cos(gam[x.throw])])
        z = (x.throw - 1) * spacing + x.axial + x.x
        force += x.mass * pos
        couple += x.mass * pos * z
        if x.kind != "counterweight":
            per_throw[x.throw] += x.mass * pos
    u_throw = np.hypot(*per_throw[1])  # 2 x 2.2 kg x 37.7 mm + 1.0 kg x 68.5 mm
    assert u_throw == pytest.approx(2 * 2.2 * 0.0377 + 1.0 * 0.0685, rel=1e-4)
    assert np.hypot(*force) < 1e-5 * u_throw
    assert np.hypot(*couple) < 1e-5 * u_throw * spacing


def test_tv_model_is_the_published_chain(engine):
    tv = engine.tv_model
    assert [s.role for s in tv] == ["crank nose", "other"] + ["cylinder"] * 6 + ["flywheel"]
    assert [s.cylinder for s in tv if s.role == "cylinder"] == [1, 2, 3, 4, 5, 6]
    assert [s.inertia for s in tv] == pytest.approx(PUBLISHED_J, abs=5e-5)
    assert [s.stiffness for s in tv[:-1]] == pytest.approx(PUBLISHED_K, abs=500)
    assert tv[-1].stiffness is None
    # openTorsion: absolute damping c_a = 2 N m s/rad at each cylinder
    assert [s.absolute_damping for s in tv] == pytest.approx([0, 0] + [2.0] * 6 + [0])


def test_natural_frequencies(engine):
    f = _chain_frequencies(engine.tv_model)
    assert f[0] == pytest.approx(0.0, abs=1e-3)  # free-free rigid-body mode
    assert f[1:] == pytest.approx(PUBLISHED_F, abs=0.05)


def test_first_mode_resonance_matches_published_torque_peak(engine):
    # Mendes et al. Fig. 31 (vibratory torque cylinder 6 - flywheel), digitised in openTorsion
    # opentorsion/examples/torsional_vibration_data_fig31.csv: peak 9477 N m at 2149 rpm, the
    # 6th-order (major order of an even-firing I6) resonance of the first mode.
    f1 = _chain_frequencies(engine.tv_model)[1]
    assert 60 * f1 / 6 == pytest.approx(2149.3, rel=0.02)


def test_peak_pressure_brake_torque_and_joints(engine):
    full = {round(n / RPM): p for case, n, p in engine.peak_pressure if case == "full"}
    no = [(round(n / RPM), p) for case, n, p in engine.peak_pressure if case == "no"]
    assert sorted(full) == list(range(1000, 2401, 100))
    # openTorsion ICE_data/peak_data.csv: 15.149 MPa at 2197.7 rpm (curve maximum)
    assert max(full.values()) == pytest.approx(151.5e5) == full[2200]
    assert no == [(2550, pytest.approx(58.8e5))]
    assert len(engine.brake_torque) > 10
    assert {j.name for j in engine.joints} == {"crank nose", "flywheel"}
    pts = {(t.joint, t.point): t.torque for t in engine.joint_torques}
    # Fig. 32 peak 840.8 N m + 40 N m FEAD; Fig. 31 peak 9476.7 N m + brake torque
    assert pts[("crank nose", "tv peak")] == pytest.approx(881)
    assert pts[("flywheel", "tv peak")] > 9476.7


def test_damper_ring_variant(tmp_path):
    path = tmp_path / "i6_damper.xlsx"
    write_workbook(path, i6_content(damper_ring=True))
    e = load_engine(path)
    tv = e.tv_model
    assert len(tv) == 10 and tv[0].role == "damper ring"
    assert [s.inertia for s in tv[1:]] == pytest.approx(PUBLISHED_J, abs=5e-5)
    # an untuned viscous damper: no spring on the ring; its inertia is the steel ring's
    assert e.damper["damper_type"] == "viscous" and tv[0].stiffness is None
    d = e.damper
    j_ring = 7850 * math.pi * d["ring_width"] * (d["ring_outer_radius"] ** 4
                                                 - d["ring_inner_radius"] ** 4) / 2
    assert tv[0].inertia == pytest.approx(j_ring, rel=1e-3)
