"""pint traps with spreadsheet unit strings, handled on purpose (practices.md part 4)."""

import math

import pytest

from checker.workbook.units import ATMOSPHERE_PA, UnitProblem, from_si, to_si


@pytest.mark.parametrize("unit", ["Nm", "N m", "N·m", "N*m", "Nm ", "J"])
def test_torque_spellings(unit):
    # pint alone reads 'Nm' as number-metre ([length]/[mass]): silently wrong
    assert to_si(400, unit, "torque") == pytest.approx(400.0)


def test_kilo_newton_metre():
    assert to_si(1.2, "kNm", "torque") == pytest.approx(1200.0)
    assert to_si(5, "Nmm", "torque") == pytest.approx(0.005)


@pytest.mark.parametrize("unit", ["bar(g)", "barg", "bar (g)", "bar(gauge)"])
def test_gauge_pressure_to_absolute(unit):
    # pint alone reads 'bar(g)' as bar x gram and rejects 'barg'
    assert to_si(4.0, unit, "pressure") == pytest.approx(4e5 + ATMOSPHERE_PA)


def test_gauge_parameter_keeps_gauge_and_converts_absolute():
    assert to_si(4.0, "bar", "pressure_gauge") == pytest.approx(4e5)
    assert to_si(4.0, "bar(g)", "pressure_gauge") == pytest.approx(4e5)
    assert to_si(5.01325, "bar(a)", "pressure_gauge") == pytest.approx(4e5)
    assert to_si(58.0, "psig", "pressure") == pytest.approx(58 * 6894.757 + ATMOSPHERE_PA,
                                                            rel=1e-6)


@pytest.mark.parametrize("unit,value", [("rpm", 3000), ("1/min", 3000), ("min^-1", 3000),
                                        ("U/min", 3000), ("Hz", 50), ("rev/s", 50),
                                        ("rad/s", 100 * math.pi)])
def test_speed_is_shaft_speed(unit, value):
    # 3000 rpm = 50 rev/s = 314.159 rad/s; pint alone gives 3000 1/min = 50 1/s (2 pi off)
    assert to_si(value, unit, "speed") == pytest.approx(314.159265, rel=1e-8)


def test_offset_temperature():
    assert to_si(130, "°C", "temperature") == pytest.approx(403.15)
    assert to_si(130, "degC", "temperature") == pytest.approx(403.15)
    assert to_si(266, "°F", "temperature") == pytest.approx(403.15, abs=1e-9)
    # a temperature difference in °C is a delta, not an offset
    assert to_si(10, "°C", "temperature_difference") == pytest.approx(10.0)
    assert to_si(18, "°F", "temperature_difference") == pytest.approx(10.0)


@pytest.mark.parametrize("unit", [None, "", "-", "1"])
def test_dimensionless_spellings(unit):
    assert to_si(0.2, unit, "ratio") == 0.2


def test_percent():
    assert to_si(75, "%", "ratio") == pytest.approx(0.75)
    # a percent-formatted cell shows 75 % and stores 0.75: the stored fraction is meant
    assert to_si(0.75, "%", "ratio", percent_formatted=True) == pytest.approx(0.75)
    assert to_si(0.75, "-", "ratio", percent_formatted=True) == pytest.approx(0.75)
    with pytest.raises(UnitProblem, match="percent-formatted"):
        to_si(0.75, "mm", "length", percent_formatted=True)


def test_inertia_and_stiffness_spellings():
    assert to_si(2128, "kg mm^2", "inertia") == pytest.approx(0.002128)
    assert to_si(2128, "kgmm²", "inertia") == pytest.approx(0.002128)
    assert to_si(0.0055, "kgm^2", "inertia") == pytest.approx(0.0055)
    assert to_si(25500, "Nm/rad", "torsional_stiffness") == pytest.approx(25500)
    assert to_si(1.5, "Nms/rad", "torsional_damping") == pytest.approx(1.5)
    assert to_si(294886, "N/mm", "linear_stiffness") == pytest.approx(294886e3)


def test_angles_need_an_angle_unit():
    assert to_si(45, "deg", "angle") == pytest.approx(math.pi / 4)
    assert to_si(45, "°", "angle") == pytest.approx(math.pi / 4)
    with pytest.raises(UnitProblem):
        to_si(45, "%", "angle")
    with pytest.raises(UnitProblem):
        to_si(45, "", "angle")


@pytest.mark.parametrize("value,unit,kind,match", [
    (86, "bar", "length", "expected a length"),
    (53.4, "mm", "pressure", "expected a pressure"),
    (1, "furlongs_per_fortnight_x", "length", "unknown unit"),
    (3000, "m/s", "speed", "expected a speed"),
    (1, "", "length", "unit cell is empty"),
    (100, "kg", "temperature", "expected a temperature"),
])
def test_wrong_units_are_refused(value, unit, kind, match):
    with pytest.raises(UnitProblem, match=match):
        to_si(value, unit, kind)


def test_display_conversions():
    assert from_si(314.159265358979, "rad/s", "rpm") == pytest.approx(3000)
    assert from_si(403.15, "K", "°C") == pytest.approx(130)
    assert from_si(5e8, "Pa", "MPa") == pytest.approx(500)
    assert from_si(2.2e-6, "m", "um") == pytest.approx(2.2)


def test_delta_temperature_spellings():
    assert to_si(9, "delta_degF", "temperature_difference") == pytest.approx(5.0)
    assert to_si(5, "delta_degC", "temperature_difference") == pytest.approx(5.0)
    with pytest.raises(UnitProblem, match="absolute temperature"):
        to_si(5, "delta_degC", "temperature")


def test_pint_imported_without_metadata_keeps_versions():
    """checker.workbook.units imports pint with a stand-in for importlib.metadata (start-up time):
    the
    versions pint, flexcache and flexparser report (pint keys its definitions cache by its
    version) equal importlib.metadata's, and importlib.metadata stays importable."""
    from tests.helpers import fresh_python

    code = ("import sys, checker.workbook.units; checker.workbook.units.ureg;"
            " import pint, flexcache, flexparser;"
            " assert 'importlib.metadata' not in sys.modules;"
            " import importlib.metadata as m;"
            " print([(p.__version__, m.version(p.__name__))"
            " for p in (pint, flexcache, flexparser)])")
    out = fresh_python(code)
    pairs = eval(out)  # noqa: S307 - our own repr of a list of string pairs
    assert len(pairs) == 3
    assert all(a == b and a != "unknown" for a, b in pairs)
