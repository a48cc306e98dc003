"""The V8 example workbook (checker.workbook.example_v8): public GM LS1 service data, the
cross-plane crank's layout and counterweights, and a torsional model with one station per
throw; every other value an ASSUMPTION."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
import scipy.linalg
from click.testing import CliRunner

from checker.calc.crank_forces import throw_angles
from checker.cli import main
from checker.description.engine import load_engine
from checker.workbook import example_v8 as v8
from checker.workbook.example import example_content, write_workbook

RPM = math.pi / 30


@pytest.fixture(scope="module")
def engine(tmp_path_factory):
    path = tmp_path_factory.mktemp("v8") / "v8.xlsx"
    write_workbook(path, v8.v8_content())
    return load_engine(path)  # raises InputErrors on any input error


def test_same_sheets_and_columns_as_the_i4_example():
    i4, v = example_content(), v8.v8_content()
    assert list(v) == [s for s in i4 if s != "DamperRubber"]  # the I4's optional table
    for name, body in i4.items():
        if isinstance(body, tuple) and name != "DamperRubber":
            assert [c for c, _u in v[name][0]] == [c for c, _u in body[0]], name


def test_every_value_has_a_source_or_an_assumption():
    for name, body in v8.v8_content().items():
        if name == "Notes":
            continue
        rows = body if isinstance(body, list) else body[1]
        for row in rows:
            if isinstance(body, list) and row[1] is None:
                continue  # a blank for the user to fill (FAT-003's nose inputs): no value
            note = str(row[-1])
            assert "ASSUMPTION" in note or "GM " in note, (name, row)


def test_public_data_and_no_warning(engine):
    p = engine.params
    # GM service manual, LS1: bore 99.0 mm, stroke 92.0 mm, firing order 1-8-7-2-6-5-4-3
    assert p["bore"] == pytest.approx(0.099) and p["stroke"] == pytest.approx(0.092)
    assert p["firing_order"] == "1-8-7-2-6-5-4-3" and p["layout"] == "v"
    ends = [b for b in engine.bearings if b.type == "big end"]
    mains = [b for b in engine.bearings if b.type == "main"]
    assert len(ends) == 8 and len(mains) == 5
    assert ends[0].diameter == pytest.approx(53.32e-3)
    # radial = mean diametral production clearance / 2: (0.023 + 0.065)/4, (0.020 + 0.052)/4
    assert ends[0].clearance == pytest.approx(0.022e-3)
    assert mains[0].clearance == pytest.approx(0.018e-3)
    assert engine.warnings == ()
    assert engine.assumptions and all("ASSUMPTION" in a for a in engine.assumptions)


def test_cross_plane_layout(engine):
    cyl = engine.cylinders
    assert [c.number for c in sorted(cyl, key=lambda c: c.firing_angle)] == [
        1, 8, 7, 2, 6, 5, 4, 3]
    assert np.diff(sorted(c.firing_angle for c in cyl)) == pytest.approx([math.pi / 2] * 7)
    assert {c.number: c.pin for c in cyl} == {1: 1, 2: 1, 3: 2, 4: 2, 5: 3, 6: 3, 7: 4, 8: 4}
    assert {round(math.degrees(c.bank_angle)) for c in cyl if c.number % 2} == {45}
    assert {round(math.degrees(c.bank_angle)) for c in cyl if not c.number % 2} == {-45}
    gam = throw_angles([c.firing_angle for c in cyl], [c.bank_angle for c in cyl],
                       [c.pin - 1 for c in cyl], 4)
    rel = np.mod(np.degrees(gam - gam[0]), 360)
    np.testing.assert_allclose(rel, [0, 90, 270, 180], atol=1e-9)  # the cross-plane crank
    assert math.degrees(gam[0]) == pytest.approx(45.0)  # throw 1 on the left bank's axis


def _rotating(engine):
    """Crank-frame rotating masses by hand: CrankMass rows (throw-1 frame turned by 45 deg),
    both rods' big ends and, for the 90-degree V, each pin's reciprocating pair as a mass
    m_rec at the pin (Taylor 1985 vol. 2 ch. 8); positions (x, y) and axial z."""
    p = engine.params
    r = p["stroke"] / 2
    spacing = p["main_spacing"]
    g1 = math.radians(45.0)
    gam = {j: g1 + math.radians(v8.PIN_THROW[j]) for j in range(1, 5)}
    m_small = p["rod_mass"] * p["rod_com"] / p["rod_length"]
    m_rec, m_big = p["piston_mass"] + m_small, p["rod_mass"] - m_small
    out = []
    for x in engine.crank_mass:
        a = g1 + math.atan2(x.z, x.y)
        rho = math.hypot(x.z, x.y)
        pos = np.array([rho * math.sin(a), rho * math.cos(a)])
        if x.reference == "pin axis":
            pos = pos + r * np.array([math.sin(gam[x.throw]), math.cos(gam[x.throw])])
        out.append((x.mass, pos, (x.throw - 1) * spacing + x.axial + x.x, x.kind))
    for j in range(1, 5):
        e = np.array([math.sin(gam[j]), math.cos(gam[j])])
        out.append((2 * m_big + m_rec, r * e, (j - 0.5) * spacing, "rods"))
    return out


def test_counterweights_cancel_the_first_order_force_and_couple(engine):
    # sums by hand: no 1st-order force or couple of the whole crank train remains (the rotating
    # couple sqrt(10) U L of the cross-plane throws is cancelled by the end counterweights);
    # tolerance: coordinates rounded to 1 um and masses to 0.1 g, 1e-4 of one throw
    items = _rotating(engine)
    force = sum(m * pos for m, pos, _z, _k in items)
    couple = sum(m * pos * z for m, pos, z, _k in items)
    u = v8.throw_unbalance()["total"]
    spacing = engine.params["main_spacing"]
    assert np.hypot(*force) < 1e-4 * u
    assert np.hypot(*couple) < 1e-4 * u * spacing
    # without the counterweights the couple is sqrt(10) U L (cross-plane V8, hand formula)
    bare = sum(m * pos * z for m, pos, z, k in items if k != "counterweight")
    assert np.hypot(*bare) == pytest.approx(math.sqrt(10) * u * spacing, rel=1e-3)
    # the end counterweights are the heaviest and turned away from their throws
    cw = {x.location: x for x in engine.crank_mass if x.kind == "counterweight"}
    assert cw["Web1 c/w"].mass == cw["Web8 c/w"].mass > 2 * cw["Web4 c/w"].mass
    for x in engine.crank_mass:
        assert x.x == 0.0  # every centre of mass in its component's plane


def test_balance_module_agrees(tmp_path):
    from checker import api

    p = tmp_path / "v8.xlsx"
    write_workbook(p, v8.v8_content())
    res = api.check(p, select=["BAL"])
    by = {(r.rule, r.item): r for r in res.results}
    assert by[("BAL-001", "order 1")].value < 1e-6  # N
    assert by[("BAL-003", "order 1")].value < 1.0  # N m (rounded inputs)
    assert by[("BAL-002", "order 2")].value < 1e-6 and by[("BAL-004", "order 2")].value < 1e-6
    assert by[("BAL-006", "static")].status == "pass"
    # the cross-plane layout is not dynamically balanced by symmetry: not judged, listed as
    # not applicable with the reason (never a pass without a value)
    assert by[("BAL-006", "dynamic")].status == "not_applicable"
    # 4th-order free force of a cross-plane V8: 4 sqrt(2) m_rec |A_4| w^2 (both banks' four
    # cylinders in phase), the only free force left
    f = res.outcome.quantities["balance.free_force"]
    assert f.values[3] > 100 and np.all(f.values[[0, 1, 2]] < 1e-6)


def test_tv_inertias_and_damper_tuning(engine):
    # station inertia derived from sheet Crank: the throw about the main axis + both rods'
    # rotating share m_b r^2 and reciprocating mean m_rec r^2 (1/2 + lambda^2/8)
    p = engine.params
    r = p["stroke"] / 2
    lam = r / p["rod_length"]
    m_small = p["rod_mass"] * p["rod_com"] / p["rod_length"]
    m_rec, m_big = p["piston_mass"] + m_small, p["rod_mass"] - m_small
    throw = engine.crank.mass_properties.inertia_total
    for j in range(1, 5):
        j_est = throw[j - 1] + 2 * (m_big * r * r + m_rec * r * r * (0.5 + lam**2 / 8))
        st = next(s for s in engine.tv_model if s.station == f"Throw {j}")
        assert st.inertia == pytest.approx(j_est, rel=1e-12)
        assert st.cylinders == (2 * j - 1, 2 * j)
        assert next(m for m in engine.crank_model if m.item == st.station
                    and m.attr == "inertia").origin == "derived"
    # Den Hartog: ring frequency = f1 / (1 + mu), f1 and mu of the chain without the ring
    tv = engine.tv_model
    j_ = np.array([s.inertia for s in tv[1:]])
    k_ = np.array([s.stiffness for s in tv[1:-1]])
    kk = np.zeros((j_.size, j_.size))
    for e, ke in enumerate(k_):
        kk[e:e + 2, e:e + 2] += ke * np.array([[1.0, -1.0], [-1.0, 1.0]])
    w2, modes = scipy.linalg.eigh(kk, np.diag(j_))
    f1 = math.sqrt(w2[1]) / (2 * math.pi)
    beta = modes[:, 1] / modes[0, 1]
    mu = tv[0].inertia / float(j_ @ beta**2)
    f_ring = math.sqrt(tv[0].stiffness / tv[0].inertia) / (2 * math.pi)
    assert f1 == pytest.approx(365.0, abs=0.1)  # the assembled crank's (issue 43)
    assert f_ring == pytest.approx(f1 / (1 + mu), rel=2e-3)  # the ring's 27.4 kN m/rad


def test_template_v8_default_name(tmp_path):
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        r = CliRunner().invoke(main, ["template", "--engine", "v8"])
        assert r.exit_code == 0, r.output
        assert (tmp_path / "engine-v8.xlsx").exists()
        assert load_engine(tmp_path / "engine-v8.xlsx").params["cylinders"] == 8
    finally:
        os.chdir(cwd)
