"""TVModel column 'cylinder': a station may carry several cylinders ('1, 2', the usual V-engine
model with one station per crank throw); every problem names its cell."""

from __future__ import annotations

import pytest

from checker.description.engine import load_engine
from checker.errors import InputErrors
from tests.helpers import edited, set_cell


def _errors(path) -> list[str]:
    with pytest.raises(InputErrors) as info:
        load_engine(path)
    return [str(e) for e in info.value.errors]


def _merge_1_2(wb, text="1, 2"):
    set_cell(wb, "TVModel", "station", "Cylinder 1", "cylinder", text)
    set_cell(wb, "TVModel", "station", "Cylinder 2", "cylinder", None)
    set_cell(wb, "TVModel", "station", "Cylinder 2", "role", "other")


@pytest.mark.parametrize("text", ["1, 2", "1,2", "1; 2", " 2 ,1 "])
def test_a_station_carries_several_cylinders(tmp_path, text):
    e = load_engine(edited(tmp_path, lambda wb: _merge_1_2(wb, text)))
    st = {s.station: s for s in e.tv_model}
    assert sorted(st["Cylinder 1"].cylinders) == [1, 2]
    assert st["Cylinder 2"].cylinders == ()
    assert st["Cylinder 3"].cylinders == (3,) and st["Cylinder 3"].cylinder == 3
    assert st["Flywheel"].cylinders == () and st["Flywheel"].cylinder is None


@pytest.mark.parametrize("text,expect", [
    ("1, x", "expected a whole number, or whole numbers separated by commas (e.g. 1, 5)"),
    ("1,,2", "expected a whole number, or whole numbers separated by commas"),
    (1.5, "stored as the number 1.5: write '1; 5'"),
    ("0, 1", "must be greater than zero, found 0"),
    ("1, 1", "1 is listed twice in '1, 1'"),
    ("1, 99", "is outside 1..64"),
])
def test_bad_cylinder_lists_are_errors_with_cell(tmp_path, text, expect):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(
        wb, "TVModel", "station", "Cylinder 1", "cylinder", text)))
    errs = _errors(p)
    mine = [x for x in errs if x.startswith(cell["c"] + ":")]
    assert mine and expect in mine[0], errs


def test_a_cylinder_on_two_stations_is_an_error(tmp_path):
    cell = {}

    def edit(wb):
        set_cell(wb, "TVModel", "station", "Cylinder 1", "cylinder", "1, 2")
        cell["c"] = set_cell(wb, "TVModel", "station", "Cylinder 2", "cylinder", 2)

    errs = _errors(edited(tmp_path, edit))
    assert any(x.startswith(cell["c"] + ":") and "cylinder 2 is already on station"
               " 'Cylinder 1'" in x for x in errs), errs


def test_a_cylinder_that_does_not_exist(tmp_path):
    cell = {}
    p = edited(tmp_path, lambda wb: cell.setdefault("c", set_cell(
        wb, "TVModel", "station", "Cylinder 4", "cylinder", "4, 5")))
    errs = _errors(p)
    assert any(x.startswith(cell["c"] + ":") and "cylinder 5 does not exist (the engine has 4"
               " cylinders)" in x for x in errs), errs
