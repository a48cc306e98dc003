"""Cross-sheet checks of checker.description.engine: throw angles against firing and bank angles
(the
convention of checker.calc.crank_forces.throw_angles), pressure-trace spacing, speed grid, oil."""

from __future__ import annotations

import math

import numpy as np
import pytest

from checker.calc.crank_forces import throw_angles
from checker.description.engine import Cylinder, check_cylinders, load_engine
from checker.errors import InputErrors
from tests.helpers import edited, example_path, set_cell, set_param


def _errors(path) -> list[str]:
    with pytest.raises(InputErrors) as info:
        load_engine(path)
    return [str(e) for e in info.value.errors]


def _run_check(cyls: list[tuple[int, float, float, float, int]]) -> list[tuple[str, int, str]]:
    """check_cylinders on (number, throw, firing, bank, pin) rows in degrees."""
    out: list[tuple[str, int, str]] = []
    cylinders = [Cylinder(n, math.radians(t), math.radians(f), math.radians(b), p)
                 for n, t, f, b, p in cyls]
    row_of = {c.number: i for i, c in enumerate(cylinders)}
    check_cylinders(cylinders, row_of, lambda sh, attr, row, msg: out.append((attr, row, msg)))
    return out


# Cross-plane 90 deg V8 worked by hand: right bank (bank +45 deg) cylinders 1-4, left bank
# (-45 deg) 5-8, cylinder k and k+4 on pin k; throws 0/90/270/180 deg from throw 1 in the
# direction of rotation. A cylinder fires when its throw lies on its own bore axis: throw 3 is
# 270 deg ahead of (= 90 deg behind) throw 1, so cylinder 3 (same bank) fires 90 deg after
# cylinder 1; cylinder 5 shares pin 1 but its bank axis lies 90 deg before the right bank in the
# direction of rotation, so pin 1 reaches it 270 deg later (630 deg: the other crank revolution).
# Firing order 1-3-4-2-7-8-6-5 at 90 deg intervals.
V8 = [  # number, throw, firing, bank, pin
    (1, 0, 0, 45, 1), (2, 90, 270, 45, 2), (3, 270, 90, 45, 3), (4, 180, 180, 45, 4),
    (5, 0, 630, -45, 1), (6, 90, 540, -45, 2), (7, 270, 360, -45, 3), (8, 180, 450, -45, 4),
]


def test_v8_worked_by_hand_is_consistent_with_the_calculation():
    assert _run_check(V8) == []
    phi = np.radians([c[2] for c in V8])
    bank = np.radians([c[3] for c in V8])
    pins = np.array([c[4] - 1 for c in V8])
    gam = throw_angles(phi, bank, pins, 4)  # crank-frame directions used by the loads
    rel = np.degrees(np.mod(gam - gam[0], 2 * np.pi))
    np.testing.assert_allclose(rel, [0, 90, 270, 180], atol=1e-9)


def test_v8_wrong_throw_angle_names_the_expected_value():
    bad = [list(c) for c in V8]
    bad[2][1] = 90  # cylinder 3: throw 90 instead of 270
    errs = _run_check([tuple(c) for c in bad])
    assert len(errs) == 1
    attr, row, msg = errs[0]
    assert attr == "throw_angle" and row == 2
    assert "throw angle 90 deg contradicts" in msg and "throw is at 270 deg from throw 1" in msg


def test_v8_shared_pin_with_inconsistent_firing_angle():
    bad = [list(c) for c in V8]
    bad[4][2] = 600  # cylinder 5 shares pin 1 with cylinder 1: must fire at 270 or 630 deg
    errs = _run_check([tuple(c) for c in bad])
    assert len(errs) == 1
    attr, row, msg = errs[0]
    assert attr == "firing_angle" and row == 4
    assert "share crank pin 1" in msg and "expected 270 deg or 630 deg, found 600 deg" in msg


def test_pin_without_cylinder_and_cylinder_one_not_at_zero():
    errs = _run_check([(1, 0, 90, 0, 1), (2, 180, 450, 0, 3)])
    msgs = " | ".join(m for _, _, m in errs)
    assert "cylinder 1 fires at 0 deg by definition" in msgs
    assert "pin 2 carries no cylinder" in msgs


def test_example_throw_angle_contradiction_is_an_error_with_cell(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault(
        "c", set_cell(wb, "Cylinders", "cylinder", 2, "throw angle", 0)))
    errs = _errors(p)
    assert len(errs) == 1 and errs[0].startswith(cell["c"] + ":")
    assert "contradicts" in errs[0] and "throw is at 180 deg from throw 1" in errs[0]


def test_both_examples_load_without_warnings(tmp_path):
    from checker.workbook.example import write_workbook
    from checker.workbook.example_i6 import i6_content

    i4 = load_engine(example_path(tmp_path))
    p6 = tmp_path / "i6.xlsx"
    write_workbook(p6, i6_content())
    i6 = load_engine(p6)
    assert i4.warnings == () and i6.warnings == ()
    assert [round(math.degrees(c.throw_angle)) for c in i6.cylinders] == [0, 240, 120, 120,
                                                                          240, 0]


# ------------------------------------------------------------------ pressure traces
def _with_trace(tmp_path, angles_deg, name="trace.xlsx"):
    """The example with a PressureTraces sheet holding one full-load trace at 3000 rpm."""
    def edit(wb):
        ws = wb.create_sheet("PressureTraces")
        ws.append(["load case", "speed", "crank angle", "pressure"])
        ws.append(["-", "rpm", "deg", "bar"])
        for a in angles_deg:
            ws.append(["full", 3000, a, 1.0 + 50.0 * math.exp(-((a - 10) / 30) ** 2)])

    return edited(tmp_path, edit, name)


def test_trace_at_exactly_10_deg_passes_and_10_5_fails_with_cell(tmp_path):
    ok = list(range(-360, 360, 10))  # 72 points, every gap (and the wrap) exactly 10 deg
    e = load_engine(_with_trace(tmp_path, ok, "ok.xlsx"))
    assert len(e.pressure_traces) == 72
    # the calculation accepts it too (it used to reject 10 deg after degree->radian round-off)
    from checker.calc.kinematics import cycle_grid
    from checker.calc.pressure import interpolate_trace
    a = np.array([t[2] for t in e.pressure_traces])
    pv = np.array([t[3] for t in e.pressure_traces])
    assert np.all(np.isfinite(interpolate_trace(a, pv, cycle_grid(math.radians(1.0)))))
    # 10.5 deg: one gap widened (points 100 -> 110.5); the cell of the point after the gap
    bad = [a for a in ok if a != 110] + [110.5]
    bad.sort()
    p = _with_trace(tmp_path, bad, "bad.xlsx")
    errs = _errors(p)
    row = 3 + bad.index(110.5)
    assert len(errs) == 1 and errs[0].startswith(f"PressureTraces!C{row}:"), errs
    assert "gap of 10.5 deg" in errs[0] and "at most 10 deg" in errs[0]


def test_trace_wrap_around_gap(tmp_path):
    angles = list(range(-350, 360, 10))[:-1]  # -350..340: wrap from 340 to 370 = 30 deg
    errs = _errors(_with_trace(tmp_path, angles))
    assert len(errs) == 1 and "gap of 30 deg" in errs[0] and errs[0].startswith(
        "PressureTraces!C3:")


# ------------------------------------------------------------------ speed grid, oil
def test_speed_grid_too_fine_is_an_error_and_fine_is_a_warning(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault(
        "c", set_param(wb, "Engine", "Speed step", value=1)))  # 6001 speeds
    errs = _errors(p)
    assert len(errs) == 1 and errs[0].startswith(cell["c"]) and "6003 speeds" in errs[0]
    e = load_engine(edited(tmp_path, lambda wb: set_param(wb, "Engine", "Speed step",
                                                          value=10), "warn.xlsx"))
    assert [w.where for w in e.warnings] == [cell["c"]]
    assert "603 speeds" in e.warnings[0].message


def test_default_speed_step_agrees_with_the_loads_module():
    from checker.modules.loads import DEFAULT_SPEED_STEP
    from checker.workbook.schema import DEFAULT_SPEED_STEP_RPM

    assert DEFAULT_SPEED_STEP == pytest.approx(DEFAULT_SPEED_STEP_RPM * 2 * math.pi / 60)


def test_oil_datasheet_without_viscosity_curve_and_cold_oil(tmp_path):
    def edit(wb):  # KV100 above KV40: no viscosity curve
        wb["Oil"].append(["Kinematic viscosity at 40 °C", 8, "mm^2/s"])
        wb["Oil"].append(["Kinematic viscosity at 100 °C", 10, "mm^2/s"])

    errs = _errors(edited(tmp_path, edit))
    assert len(errs) == 1 and errs[0].startswith("Oil!B") and "Vogel" in errs[0]
    # a 5W30 oil at -35 °C: within the valid range (the curve holds), outside the usual one
    e = load_engine(edited(tmp_path, lambda wb: set_param(wb, "Oil", "Oil supply temperature",
                                                          value=-35), "cold.xlsx"))
    assert any("usual range" in w.message for w in e.warnings)


def test_loader_and_cross_check_problems_are_reported_together(tmp_path):
    cells = {}

    def edit(wb):
        cells["lining"] = set_cell(wb, "Bearings", "name", "M1", "lining", "AS61")  # loader
        cells["throw"] = set_cell(wb, "Cylinders", "cylinder", 3, "throw angle", 90)  # engine
        cells["step"] = set_param(wb, "Engine", "Speed step", value=2)  # engine: grid
        cells["temp"] = set_param(wb, "Oil", "Oil supply temperature", value=-300)  # loader

    errs = _errors(edited(tmp_path, edit))
    where = sorted(e.split(":")[0] for e in errs)
    assert where == sorted(cells.values()), errs


def test_offsets_the_rod_cannot_reach_are_an_input_error(tmp_path):
    """r + |cylinder offset| + |pin offset| < l (checker.calc.kinematics); both are within
    their valid ranges, the combination is not."""
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_param(
        wb, "Engine", "Cylinder offset", value=110)))  # r 47.3 + 110 + 0.8 > l 145.7 mm
    errs = _errors(p)
    assert len(errs) == 1 and errs[0].startswith(cell["c"]) and "cannot reach" in errs[0]


def test_bearing_length_to_diameter(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(
        wb, "Bearings", "name", "M1", "effective length", 0.5)))  # L/D 0.009
    errs = _errors(p)
    assert len(errs) == 1 and errs[0].startswith(cell["c"]) and "0.00909" in errs[0]
    e = load_engine(edited(tmp_path, lambda wb: set_cell(
        wb, "Bearings", "name", "M1", "effective length", 3), "narrow.xlsx"))  # L/D 0.055
    assert [w.where for w in e.warnings] == [cell["c"]]


def test_changed_firing_angle_is_reported_at_the_firing_angle_naming_both_cells(tmp_path):
    """Issue 37 item 10: only cylinder 2's firing angle changed (540 -> 500 deg): the error is
    at that cell, names the throw angle's cell too and says which to change."""
    cells = {}

    def edit(wb):
        cells["fire"] = set_cell(wb, "Cylinders", "cylinder", 2, "firing angle", 500)
        cells["throw"] = cells["fire"].replace("!C", "!B")

    errs = _errors(edited(tmp_path, edit))
    assert len(errs) == 1, errs
    assert cells["fire"] == "Cylinders!C4" and errs[0].startswith("Cylinders!C4:")
    assert cells["throw"] in errs[0]  # both cells named
    assert "change this firing angle to 540 deg" in errs[0]
    assert "or Cylinders!B4 to 220 deg" in errs[0]


def test_changed_throw_angle_is_reported_at_the_throw_angle_naming_both_cells(tmp_path):
    errs = _errors(edited(tmp_path, lambda wb: set_cell(
        wb, "Cylinders", "cylinder", 2, "throw angle", 90)))
    assert len(errs) == 1 and errs[0].startswith("Cylinders!B4:"), errs
    assert "(Cylinders!C4)" in errs[0] and "change this throw angle to 180 deg" in errs[0]


def test_uneven_firing_names_both_fixes():
    # uneven firing (0/200/480 deg) and no even alternative: either cell, with both values
    errs = _run_check([(1, 0, 0, 0, 1), (2, 100, 200, 0, 2), (3, 240, 480, 0, 3)])
    assert len(errs) == 1
    attr, row, msg = errs[0]
    assert attr == "throw_angle" and row == 1
    assert "Change one of the two: this throw angle to 160 deg" in msg
    assert "the firing angle to 260 deg or 620 deg" in msg


@pytest.mark.parametrize("cyl", [3, 4])
def test_a_rejected_cell_is_reported_once_without_its_knock_on_errors(tmp_path, cyl):
    """Issue 37 item 11: a firing angle of 840 deg is rejected (outside 0..720 deg), which
    leaves its cylinder row out; the cross-checks that count the cylinders' rows (crank pins
    of the CrankMass throws, cylinder numbering) are held back instead of reporting
    "throw 4 does not exist (the engine has 3 crank pins)"."""
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(
        wb, "Cylinders", "cylinder", cyl, "firing angle", 840)))
    with pytest.raises(InputErrors) as info:
        load_engine(p)
    errs = [str(e) for e in info.value.errors]
    assert len(errs) == 1 and errs[0].startswith(cell["c"] + ":"), errs
    assert "840" in errs[0]
    assert info.value.follow_on >= 1
    assert "held back" in str(info.value) and "does not exist" not in str(info.value)


def test_knock_on_rule_holds_back_only_checks_that_need_the_rejected_sheet(tmp_path):
    """A rejected cell elsewhere (Bearings) does not hide a CrankMass throw that does not
    exist; with the Cylinders sheet intact the throw check reports it."""
    cells = {}

    def edit(wb):
        cells["lining"] = set_cell(wb, "Bearings", "name", "M1", "lining", "AS61")
        ws = wb["CrankMass"]
        from tests.helpers import column
        r = 3
        while ws.cell(r, 1).value is not None and ws.cell(r + 1, 1).value is not None:
            r += 1
        c = column(ws, "throw")
        ws.cell(r, c).value = 7
        cells["throw"] = f"CrankMass!{ws.cell(r, c).coordinate}"

    with pytest.raises(InputErrors) as info:
        load_engine(edited(tmp_path, edit))
    where = sorted(str(e).split(":")[0] for e in info.value.errors)
    assert where == sorted(cells.values()), info.value.errors
    assert info.value.follow_on == 0


def test_cylinder_station_lighter_than_its_rod_and_piston_shares_is_a_warning(tmp_path):
    """The torsional model takes a station's inertia as given (it adds no con-rod or piston
    share): a cylinder station below those shares alone (the I4: 0.451 kg x 47.3^2 mm^2 +
    1/2 0.642 kg x 47.3^2 mm^2 = 1.73e-3 kg m^2) is warned about at its cell."""
    from checker.description.engine import _rod_piston_inertia

    e = load_engine(example_path(tmp_path))
    r = 0.0946 / 2
    a_l = 35.73 / 145.7
    hand = (0.597 * (1 - a_l) + 0.5 * (0.4955 + 0.597 * a_l)) * r * r
    assert _rod_piston_inertia(e.params) == pytest.approx(hand, rel=1e-12)
    assert hand == pytest.approx(1.73e-3, rel=5e-3)
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(
        wb, "TVModel", "station", "Cylinder 2", "inertia", 0.0015)), "light.xlsx")
    w = [x for x in load_engine(p).warnings if "con-rod and piston shares" in x.message]
    assert len(w) == 1 and w[0].where == cell["c"], w
