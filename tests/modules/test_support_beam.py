"""The crank as a continuous beam in the checker (Engine 'Main bearing supports', issue 34).

Independent numbers: equilibrium (both schemes carry the same loads to the mains: the sums of
their main loads agree at every angle, speed and case, 1e-9); statics (the section loads of
the lever-rule bearing loads reproduce IACS UR M53's determinate moments, 1e-9); the limits
(very stiff elastic supports give the rigid result).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from checker import api
from checker.calc import crank_stress as cs
from checker.description.engine import load_engine
from checker.errors import InputErrors
from checker.workbook.example import write_workbook

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "workbook"))
from test_crank_sheet import i4_with_crank  # noqa: E402


def _workbook(tmp_path, scheme, stiffness=None, name=None, edit=None):
    def change(c):
        eng = c["Engine"]
        eng.append(["Main bearing supports", scheme, "-", "test"])
        if stiffness is not None:
            eng.append(["Main bearing support stiffness", stiffness, "N/mm", "test"])
        if edit:
            edit(c)
    p = tmp_path / (name or f"{scheme.replace(',', '').replace(' ', '_')}.xlsx")
    write_workbook(p, i4_with_crank(edit=change))
    return p


@pytest.fixture(scope="module")
def checks(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("beam")
    out = {}
    for scheme, k in (("determinate", None), ("continuous beam, rigid supports", None),
                      ("continuous beam, elastic supports", 1e6),
                      ("continuous beam, elastic supports", 1e10)):
        out[(scheme, k)] = api.check(_workbook(tmp, scheme, k, name=f"{scheme}{k}.xlsx"))
    return out


def _mains(res):
    q = res.outcome.quantities["loads.bearing_load"]
    rows = [i for i, n in enumerate(q.coords["item"]) if q.item_attrs[n]["type"] == "main"]
    return q.detail.fx[rows], q.detail.fy[rows], q.detail


def test_both_schemes_carry_the_same_loads_to_the_mains(checks):
    dx, dy, _ = _mains(checks[("determinate", None)])
    for key in (("continuous beam, rigid supports", None),
                ("continuous beam, elastic supports", 1e6)):
        cx, cy, det = _mains(checks[key])
        scale = np.abs(dx).max()
        np.testing.assert_allclose(cx.sum(axis=0), dx.sum(axis=0), atol=1e-9 * scale)
        np.testing.assert_allclose(cy.sum(axis=0), dy.sum(axis=0), atol=1e-9 * scale)
        # the determinate loads kept beside the continuous ones are today's
        np.testing.assert_array_equal(det.main_determinate.x, np.moveaxis(dx, 0, 2))
        assert det.scheme == key[0] and det.beam is not None
        assert not np.allclose(cx, dx)  # the scheme changes the share between the mains


def test_very_stiff_supports_give_the_rigid_result(checks):
    rx, ry, _ = _mains(checks[("continuous beam, rigid supports", None)])
    sx, sy, _ = _mains(checks[("continuous beam, elastic supports", 1e10)])
    scale = np.abs(rx).max()
    np.testing.assert_allclose(sx, rx, atol=1e-4 * scale)
    np.testing.assert_allclose(sy, ry, atol=1e-4 * scale)


def test_determinate_scheme_leaves_every_result_unchanged(checks, tmp_path):
    plain = api.check(write_and_return(tmp_path))
    det = checks[("determinate", None)]
    a = [(r.rule, r.item, r.case, r.status, r.value) for r in plain.results]
    b = [(r.rule, r.item, r.case, r.status, r.value) for r in det.results]
    assert a == b


def _set_first_main(content, k_n_per_mm):
    cols, rows = content["Bearings"]
    cols.append(("support stiffness", "N/mm"))
    for r in rows:
        while len(r) < len(cols):
            r.append(None)
    rows[0][-1] = k_n_per_mm


def write_and_return(tmp_path):
    p = tmp_path / "plain.xlsx"
    write_workbook(p, i4_with_crank())
    return p


def test_fillet_ratio_and_beam_record(checks):
    rigid = checks[("continuous beam, rigid supports", None)]
    q = rigid.outcome.quantities["fatigue.fillet_bending_ratio"]
    assert len(q.coords["item"]) == 16  # 4 throws x 2 webs x (pin, main fillet)
    pin = [v for n, v in zip(q.coords["item"], q.values, strict=True) if "pin fillet" in n]
    # the continuous beam relieves the pin fillets (Cummins 2002 Fig. 1: 80 % rigid)
    assert 0.5 < min(pin) and max(pin) < 1.0
    elastic = checks[("continuous beam, elastic supports", 1e6)]
    qe = elastic.outcome.quantities["fatigue.fillet_bending_ratio"]
    pin_e = [v for n, v in zip(qe.coords["item"], qe.values, strict=True) if "pin fillet" in n]
    assert all(e > r for e, r in zip(pin_e, pin, strict=True))  # softer supports: nearer 1
    d = rigid.to_dict(timings=False)
    beam = d["crank_beam"]
    assert beam["scheme"] == "continuous beam, rigid supports"
    assert len(beam["supports"]) == 5 and beam["supports"][0]["stiffness_N_per_m"] is None
    loads = np.array(beam["node_loads_N_Nm"])
    mains = np.array(beam["main_loads_N"])
    # the record balances: the main loads carry the nodal forces (sum over the crank)
    np.testing.assert_allclose(mains.sum(axis=1), loads[..., :2].sum(axis=1),
                               atol=1e-4 * np.abs(mains).max())


def test_lever_rule_section_loads_are_m53s():
    from checker.calc.crank_beam import throw_section_loads

    rng = np.random.default_rng(3)
    n = 24
    fr, ft = rng.normal(0, 2e4, n), rng.normal(0, 1e4, n)
    g = 0.7
    l3, lg, lh, w = 0.096, 0.027, 0.0244, 0.0223
    nom = cs.throw_nominal_stresses(fr, ft, 0.0, 0.0, pin_diameter=0.048,
                                    journal_diameter=0.055, throw=0.0473, main_spacing=l3,
                                    main_journal_length=lg, pin_journal_length=lh,
                                    web_thickness=w, web_width=0.0757)
    f = np.stack([fr * np.sin(g) + ft * np.cos(g), fr * np.cos(g) - ft * np.sin(g)], axis=-1)
    bearing = np.stack([f / 2, f / 2])  # lever rule, pin at mid-bay
    l1 = nom.web_centre_distance
    cuts = [[l1, l3 - l1, lg / 2, l3 - lg / 2, l3 / 2 - lh / 2, l3 / 2 + lh / 2, l3 / 2]]
    m_r, m_t, v_r = throw_section_loads(f[None], bearing, pin_z=[l3 / 2], main_z=[0.0, l3],
                                        throw_angle=[g], cut_z=cuts)
    np.testing.assert_allclose(m_r[0, :2], nom.moment_web, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(m_r[0, 2:4], nom.moment_journal_fillet, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(m_r[0, 4:6], nom.moment_pin_fillet, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(m_r[0, 6], nom.moment_oil_radial, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(m_t[0, 6], nom.moment_oil_tangential, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(m_t[0, :2], nom.moment_web_tangential, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(np.stack([-v_r[0, 0], v_r[0, 1]]), nom.web_force, rtol=1e-9,
                               atol=1e-9)


def test_scheme_needs_what_it_uses(tmp_path):

    from tests.helpers import edited, without_crank

    def no_crank(wb):
        without_crank(wb)
        ws = wb["Engine"]
        r = ws.max_row + 1
        for c, v in enumerate(("Main bearing supports", "continuous beam", "-"), 1):
            ws.cell(r, c).value = v

    p = edited(tmp_path, no_crank)
    with pytest.raises(InputErrors) as exc:
        load_engine(p)
    assert any("needs the crank's dimensions" in e.message for e in exc.value.errors)
    p2 = _workbook(tmp_path, "continuous beam, elastic supports")
    with pytest.raises(InputErrors) as exc:
        load_engine(p2)
    (e,) = exc.value.errors
    assert e.where.startswith("Engine!B") and "radial stiffness" in e.message
    p4 = _workbook(tmp_path, "continuous beam, elastic supports", name="one.xlsx",
                   edit=lambda c: _set_first_main(c, 5e5))
    with pytest.raises(InputErrors) as exc:
        load_engine(p4)
    where = [e.where for e in exc.value.errors]
    assert len(where) == 4 and all(w.startswith("Bearings!") for w in where)  # other mains
    p3 = _workbook(tmp_path, "determinate", 1e6)
    with pytest.raises(InputErrors) as exc:
        load_engine(p3)
    assert "used by 'continuous beam, elastic supports' only" in exc.value.errors[0].message


def test_sweep_section_loads_of_the_lever_rule_are_m53s(checks):
    """throw_sections' determinate half (the sweep as one product of unit-load influences)
    equals IACS UR M53's determinate moments at every case, speed, throw and angle."""
    from checker.calc import crank_forces as cf
    from checker.modules import support_beam
    from checker.modules.fatigue import _geometry

    res = checks[("continuous beam, rigid supports", None)]
    e = res.engine
    pins = np.array([c.pin - 1 for c in e.cylinders])
    gamma = cf.throw_angles(np.array([c.firing_angle for c in e.cylinders]),
                            np.array([c.bank_angle for c in e.cylinders]), pins, 4)
    g = res.outcome.quantities["fatigue.goodman_sf"].detail
    geo = _geometry(e)[0].as_kwargs()
    theta = res.outcome.quantities["loads.bearing_load"].detail.theta
    beam = support_beam.build_beam(e, gamma)
    _, det = support_beam.throw_sections(beam, g.pin_force_radial, g.pin_force_tangential,
                                         gamma, geo, theta)
    nom = cs.throw_nominal_stresses(g.pin_force_radial, g.pin_force_tangential, 0.0, 0.0,
                                    **geo)
    scale = np.abs(nom.moment_web).max()
    for a, b in ((det.moment_web, nom.moment_web), (det.web_force, nom.web_force),
                 (det.moment_pin_fillet, nom.moment_pin_fillet),
                 (det.moment_journal_fillet, nom.moment_journal_fillet),
                 (det.moment_oil_radial, nom.moment_oil_radial),
                 (det.moment_oil_tangential, nom.moment_oil_tangential)):
        np.testing.assert_allclose(a, b, atol=1e-9 * max(scale, np.abs(b).max()))


def test_determinate_json_is_byte_identical_to_no_scheme_row(checks, tmp_path):
    from checker.outputs.formats import to_json

    plain = api.check(write_and_return(tmp_path))
    det = checks[("determinate", None)]
    a = to_json(plain, timings=False).replace(plain.engine.sha256, "")
    b = to_json(det, timings=False).replace(det.engine.sha256, "")

    def strip(text: str) -> str:
        # the workbooks differ by the Engine row: file name, hash, Engine cell rows
        return "\n".join(x for x in text.splitlines()
                         if '"file"' not in x and "Engine!" not in x)

    assert strip(a) == strip(b)
    assert "crank_beam" not in b and "fillet_bending_ratio" not in b


def test_the_rods_torque_is_balanced_where_it_goes(checks):
    """Issue 43: the torque of the con-rods leaves at the flywheel flange (its cycle mean) and
    accelerates the rotating inertias (the rest, d'Alembert), so the loads on the frame are
    in equilibrium about the crank axis at every recorded angle: the torque of the nodal
    forces plus the nodal torques is zero (before, the torque went to the frame's rotation
    hold at the last main and the record did not balance)."""
    d = checks[("continuous beam, rigid supports", None)].to_dict(timings=False)
    beam = d["crank_beam"]
    nodes = np.array(beam["nodes_m"])[np.array(beam["load_nodes"])]
    loads = np.array(beam["node_loads_N_Nm"])  # (angle, load node, 6)
    torque = (nodes[None, :, 0] * loads[..., 1] - nodes[None, :, 1] * loads[..., 0]
              + loads[..., 5]).sum(axis=1)
    rods = np.abs(nodes[None, :, 0] * loads[..., 1] - nodes[None, :, 1] * loads[..., 0]).sum(
        axis=1)
    assert rods.max() > 100.0  # the rods do turn the crank
    np.testing.assert_allclose(torque, 0.0, atol=1e-5 * rods.max())  # JSON: 6 digits
    assert "flywheel flange" in " ".join(d["assumptions"]) or any(
        "flywheel flange" in a for a in beam.get("assumptions", []))


def test_main_loads_do_not_depend_on_where_the_frame_is_held_in_rotation(
        checks, tmp_path, monkeypatch):
    """Holding the frame's rotation at the first main instead of the last changes no main load
    (the balanced torques leave the hold nothing to react); before issue 43 the I4's peaks
    at no load moved by up to 3 kN (11.61/16.03/37.14/19.11/12.96 against their mirror
    image)."""
    from checker.calc import crank_beam as cb
    from checker.modules import support_beam

    real = cb.crank_frame

    def held_at_first(**kw):
        out = real(**kw)
        fr = out.frame.__class__(**{**out.frame.__dict__,
                                    "torsion_node": int(out.main_nodes[0])})
        return out.__class__(**{**out.__dict__, "frame": fr})

    monkeypatch.setattr(support_beam.cb, "crank_frame", held_at_first)
    first = api.check(_workbook(tmp_path, "continuous beam, rigid supports"))
    fx0, fy0, _ = _mains(checks[("continuous beam, rigid supports", None)])
    fx1, fy1, _ = _mains(first)
    scale = np.abs(np.hypot(fx0, fy0)).max()
    np.testing.assert_allclose(fx1, fx0, atol=1e-9 * scale)
    np.testing.assert_allclose(fy1, fy0, atol=1e-9 * scale)
