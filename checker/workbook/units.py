"""The project's single pint registry and the spreadsheet unit-string handling.

Everything the workbook says about units passes through :func:`to_si`. Spreadsheet unit
strings carry traps that pint alone gets silently wrong (see ``docs/workbook.md``):

* ``Nm`` parses in pint as *number-metre*; ``kNm`` as *kilo-number-metre*. We rewrite
  ``Nm``/``kNm``/``mNm`` to ``N*m`` before parsing.
* ``bar(g)`` parses as *bar x gram*, ``barg`` is undefined. Gauge and absolute pressures are
  handled on purpose: a parameter declares whether it is an absolute or a gauge pressure;
  ``bar(g)``/``barg``/``psig``/``kPa(g)`` are gauge, ``bar(a)``/``bara``/``psia`` absolute, and a
  plain ``bar`` is taken in the parameter's own reference.
* ``rpm`` converts to 2*pi*n/60 rad/s but ``1/min`` to n/60 1/s and ``Hz`` to n 1/s: for a
  shaft speed we map ``1/min``, ``min^-1``, ``U/min``, ``r/min`` to ``rpm`` and ``Hz``, ``1/s``,
  ``rps`` to revolutions per second, so 3000 rpm = 3000 1/min = 50 Hz = 314.159 rad/s.
* ``°C`` is an offset unit: absolute temperatures are built with ``Q_(value, unit)``; a
  temperature *difference* given in ``°C`` or ``°F`` means ``delta_degC``/``delta_degF``.
* ``-``, ``1`` or an empty unit cell mean dimensionless; ``%`` is 0.01.
"""

from __future__ import annotations

import functools
import math
import re
import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING

RPM = 2.0 * math.pi / 60.0
"""One revolution per minute in rad/s (speeds are rad/s inside checker)."""

if TYPE_CHECKING:
    import pint


def _import_pint():
    """``import pint`` without its optional dask and SciPy support: pint imports ``dask``
    whenever it is installed (it is, for ``checker study``), which costs about 0.4 s on every
    command, and ``scipy`` (about 0.02 s); neither is used through pint here (no pint
    quantity wraps a dask array or goes through a SciPy function). A dask or SciPy imported
    earlier is kept as is; both stay importable afterwards."""
    hidden = [m for m in ("dask", "scipy") if m not in sys.modules]
    for m in hidden:
        sys.modules[m] = None  # type: ignore[assignment]  # find_spec/import -> not there
    stub = "importlib.metadata" not in sys.modules
    if stub:  # pint, flexcache and flexparser ask it only for their own version
        sys.modules["importlib.metadata"] = _metadata_stub()  # type: ignore[assignment]
    try:
        import pint as p
    finally:
        for m in hidden:
            del sys.modules[m]
        if stub:
            del sys.modules["importlib.metadata"]
    return p


def _metadata_stub():
    """A stand-in for :mod:`importlib.metadata` while pint is imported: pint and its helpers
    flexcache and flexparser import it only to read their own version (pint's cache of
    parsed definitions is keyed by it), and importing it costs about 0.04 s of every
    command. ``version(name)`` reads the version from the ``name-<version>.dist-info``
    folder next to the package (what :mod:`importlib.metadata` finds there too) and raises
    when there is none (the packages then say "unknown", as they do for a source copy)."""
    import types

    def version(name: str) -> str:
        import importlib.util
        import os

        spec = importlib.util.find_spec(name)
        if spec is None or not spec.submodule_search_locations:
            raise LookupError(name)
        site = os.path.dirname(list(spec.submodule_search_locations)[0])
        prefix = name.replace("-", "_").lower() + "-"
        for entry in os.listdir(site):
            low = entry.lower()
            if low.startswith(prefix) and low.endswith(".dist-info"):
                return entry[len(prefix):-len(".dist-info")]
        raise LookupError(name)

    mod = types.ModuleType("importlib.metadata")
    mod.version = version  # type: ignore[attr-defined]
    return mod


_PREPROCESSORS = [
    # Nm, kNm, mNm, MNm as torque, not number-metre (word boundary so "Nmm" is untouched)
    lambda s: re.sub(r"(?<![A-Za-z_])([kmM]?)Nm(?![A-Za-z_])", r"\1N*m", s),
    lambda s: re.sub(r"(?<![A-Za-z_])([kmM]?)Nmm(?![A-Za-z_])", r"\1N*mm", s),
    lambda s: re.sub(r"(?<![A-Za-z_])Nms(?![A-Za-z_])", "N*m*s", s),
    lambda s: re.sub(r"(?<![A-Za-z_])kgm(?=\^|\*\*|²|2)", "kg*m", s),
    lambda s: re.sub(r"(?<![A-Za-z_])kgmm(?=\^|\*\*|²|2)", "kg*mm", s),
    lambda s: s.replace("·", "*").replace("⋅", "*").replace("²", "**2").replace("³", "**3"),
    lambda s: s.replace("µ", "u").replace("μ", "u"),
]


def _registry(pint):
    """The registry, with pint's parsed-definitions cache (user cache folder) when it can be
    used: building the registry from the definition file costs about 1 s, reading the cache
    about 0.1 s. Without a writable cache folder the registry is built as usual."""
    try:
        return pint.UnitRegistry(cache_folder=":auto:", preprocessors=_PREPROCESSORS)
    except Exception:  # noqa: BLE001 - any cache problem: build without the cache
        return pint.UnitRegistry(preprocessors=_PREPROCESSORS)


@functools.cache
def _pint():
    """``(pint, ureg, Q_)``: pint and the project's registry, imported and built on first use.

    pint costs about 0.2 s of CPU per process (import and registry); the units of the
    template workbooks and of the shipped rules convert through the table of
    :mod:`checker.workbook.unit_table` (pint's own numbers, tests check them against pint), so a
    check of such a workbook never needs it. ``checker.workbook.units.pint``, ``.ureg`` and ``.Q_``
    are still available as module attributes (importing pint then)."""
    pint = _import_pint()
    ureg = _registry(pint)
    pint.set_application_registry(ureg)
    return pint, ureg, ureg.Quantity


def __getattr__(name: str):
    if name in ("pint", "ureg", "Q_"):
        return _pint()[("pint", "ureg", "Q_").index(name)]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


ATMOSPHERE_PA = 101325.0
"""Standard atmosphere [Pa] used to convert gauge to absolute pressure."""


class UnitProblem(ValueError):
    """A unit string or value that cannot be converted; the message is for the user."""


@dataclass(frozen=True)
class Kind:
    """What a workbook value is: its SI unit and how to read spreadsheet spellings.

    ``name`` is shown to users ("length", "pressure"...); ``si`` is the SI unit the calculation
    core receives; ``example`` is a typical unit for messages.
    """

    name: str
    si: str
    example: str


KINDS: dict[str, Kind] = {
    k.name: k
    for k in [
        Kind("length", "m", "mm"),
        Kind("area", "m**2", "mm^2"),
        Kind("mass", "kg", "kg"),
        Kind("inertia", "kg*m**2", "kg m^2"),
        Kind("unbalance", "kg*m", "g mm"),
        Kind("force", "N", "kN"),
        Kind("torque", "N*m", "N m"),
        Kind("pressure", "Pa", "bar"),
        Kind("pressure_gauge", "Pa", "bar(g)"),
        Kind("stress", "Pa", "MPa"),
        Kind("angle", "rad", "deg"),
        Kind("speed", "rad/s", "rpm"),
        Kind("temperature", "K", "°C"),
        Kind("temperature_difference", "K", "K"),
        Kind("viscosity", "Pa*s", "mPa s"),
        Kind("kinematic_viscosity", "m**2/s", "mm^2/s"),
        Kind("density", "kg/m**3", "kg/m^3"),
        Kind("torsional_stiffness", "N*m/rad", "N m/rad"),
        Kind("torsional_damping", "N*m*s/rad", "N m s/rad"),
        Kind("linear_stiffness", "N/m", "N/mm"),
        Kind("linear_damping", "N*s/m", "N s/m"),
        Kind("power_density", "W/m**3", "W/cm^3"),
        Kind("heat_flux", "W/m**2", "W/cm^2"),
        Kind("heat_transfer_coefficient", "W/(m**2*K)", "W/(m^2 K)"),
        Kind("power", "W", "kW"),
        Kind("volume_flow", "m**3/s", "l/min"),
        Kind("dimensionless", "", "-"),
        Kind("ratio", "", "-"),
    ]
}

_DIMENSIONLESS_SPELLINGS = {"", "-", "1", "—", "–", "none", "ratio"}
_ANGLE_UNITS = {"radian", "degree", "revolution", "arcminute", "arcsecond", "turn", "gradian"}

_GAUGE = re.compile(r"^\s*(.*?)\s*(?:\(g\)|\(gauge\)|g|gauge)\s*$", re.IGNORECASE)
_ABS = re.compile(r"^\s*(.*?)\s*(?:\(a\)|\(abs\)|a|abs)\s*$", re.IGNORECASE)
_PRESSURE_BASES = {"bar", "mbar", "psi", "kpa", "mpa", "pa", "atm", "hpa"}

_SPEED_ALIASES = {
    "rpm": "rpm",
    "1/min": "rpm",
    "min^-1": "rpm",
    "min**-1": "rpm",
    "min-1": "rpm",
    "/min": "rpm",
    "u/min": "rpm",
    "r/min": "rpm",
    "rev/min": "rpm",
    "hz": "revolution/second",
    "1/s": "revolution/second",
    "/s": "revolution/second",
    "s^-1": "revolution/second",
    "rps": "revolution/second",
    "rev/s": "revolution/second",
    "rad/s": "radian/second",
    "deg/s": "degree/second",
}


def _pressure_reference(unit: str) -> tuple[str, str | None]:
    """Split a pressure unit string into (base unit, 'gauge'|'absolute'|None)."""
    u = unit.strip()
    for pattern, ref in ((_GAUGE, "gauge"), (_ABS, "absolute")):
        m = pattern.match(u)
        if m and m.group(1).lower() in _PRESSURE_BASES:
            return m.group(1), ref
    return u, None


@functools.lru_cache(maxsize=4096)
def parse_unit(unit: str) -> pint.Unit:
    """Parse a unit string with the project's registry (pint errors become UnitProblem).

    Cached: a workbook repeats a few unit strings hundreds of times."""
    pint, _, Q_ = _pint()
    try:
        q = Q_(1.0, unit)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        raise UnitProblem(f"unknown unit '{unit}'") from exc
    except Exception as exc:  # pint raises AssertionError/TokenError on some strings
        raise UnitProblem(f"cannot read unit '{unit}'") from exc
    return q.units


def _dimension_words(unit: pint.Unit) -> str:
    dim = _pint()[1].Quantity(1.0, unit).dimensionality
    known = {
        "[length]": "length",
        "[mass]": "mass",
        "[length] ** 2": "area",
        "[mass] / [length] / [time] ** 2": "pressure/stress",
        "[length] * [mass] / [time] ** 2": "force",
        "[length] ** 2 * [mass] / [time] ** 2": "torque/energy",
        "[temperature]": "temperature",
        "1 / [time]": "frequency/speed",
        "dimensionless": "dimensionless",
        "[substance] / [length] ** 3": "a molar concentration",
    }
    return known.get(str(dim), str(dim))


@functools.lru_cache(maxsize=4096)
def _scale(unit: str | None, kind: str, percent_formatted: bool) -> float | None:
    """The SI factor of a purely multiplicative unit (``None`` for offset units such as °C
    or gauge pressures, and for units :func:`_to_si` rejects)."""
    try:
        if _to_si(0.0, unit, kind, percent_formatted) != 0.0:
            return None
        return _to_si(1.0, unit, kind, percent_formatted)
    except UnitProblem:
        return None


def kind_words(name: str) -> str:
    """A unit kind's name in words with its article: ``an angle``, ``a length``."""
    words = name.replace("_", " ")
    return ("an " if words[:1].lower() in "aeiou" else "a ") + words


def to_si(value: float, unit: str | None, kind: str, percent_formatted: bool = False) -> float:
    """Convert a spreadsheet value with its unit cell to the SI magnitude of ``kind``.

    Multiplicative units use a cached factor; offset units and problems take the full path
    (:func:`_to_si`, which has the documentation of the arguments and the messages).
    """
    if not math.isfinite(value):
        raise UnitProblem(f"expected a finite number, found {value!r}")
    factor = _scale(unit, kind, percent_formatted)
    if factor is not None:
        return float(value) * factor
    return _to_si(value, unit, kind, percent_formatted)


def _to_si(value: float, unit: str | None, kind: str, percent_formatted: bool = False) -> float:
    """Convert a spreadsheet value with its unit cell to the SI magnitude of ``kind``.

    Parameters
    ----------
    value : float
        The number in the value cell (as stored, not as displayed).
    unit : str or None
        The unit cell text; ``None``/blank/``-`` mean dimensionless.
    kind : str
        A key of :data:`KINDS` (e.g. ``"length"``, ``"pressure"``).
    percent_formatted : bool
        The value cell has a percent number format: it stores the fraction the user sees as a
        percentage (a cell showing 75 % holds 0.75). Such a cell is only valid for a
        dimensionless kind, with a unit of ``%``, ``-`` or blank; its stored value is used as
        the fraction.

    Returns
    -------
    float
        Magnitude in the SI unit ``KINDS[kind].si``.

    Raises
    ------
    UnitProblem
        With a message naming what was expected and what was found.

    Notes
    -----
    Every conversion is affine in the value (a factor, plus an offset for temperatures and
    gauge/absolute pressures), so the unit string is parsed once per (unit, kind) and the
    factor and offset are cached: a workbook of 100,000 values converts in well under a
    second instead of minutes of pint parsing.
    """
    if not math.isfinite(value):
        raise UnitProblem(f"expected a finite number, found {value!r}")
    u = "" if unit is None else str(unit).strip()
    conv = _affine(u, kind, bool(percent_formatted))
    if isinstance(conv, str):
        raise UnitProblem(conv)
    scale, offset = conv
    return float(value) * scale + offset


@functools.lru_cache(maxsize=4096)
def _affine(unit: str, kind: str, percent_formatted: bool) -> tuple[float, float] | str:
    """(scale, offset) of the conversion of ``unit`` to SI for ``kind``, or the problem text.

    Units of the table :data:`checker.workbook.unit_table.TO_SI` (pint's own numbers for the units
    of
    the template workbooks and the usual spellings; tests compare every entry with pint) are
    taken from it without importing pint."""
    if not percent_formatted:
        got = _table().TO_SI.get((unit, kind))
        if got is not None:
            return got
    try:
        offset = _to_si_pint(0.0, unit, kind, percent_formatted)
        scale = _to_si_pint(1.0, unit, kind, percent_formatted) - offset
    except UnitProblem as exc:
        return str(exc)
    return scale, offset


# units engineers type, in their usual spelling: a unit typed in another case ("MM", read by
# pint as megamolar; "Mpa") that fails is hinted at with the spelling that works
_COMMON_UNITS = ("mm", "um", "µm", "m", "cm", "MPa", "kPa", "GPa", "Pa", "bar", "N", "kN",
                 "N m", "Nm", "kN m", "kg", "g", "kg m^2", "kg*m**2", "rpm", "deg", "rad",
                 "l/min", "°C", "K", "Hz", "N m/rad", "N m/deg", "N/mm", "W", "kW", "s", "ms")


def _case_hint(unit: str, kind: str, percent_formatted: bool) -> str | None:
    """A common spelling of ``unit`` that differs only in letter case and is a valid unit of
    ``kind`` (``MM`` -> ``mm``), or None."""
    low = unit.strip().lower()
    for cand in dict.fromkeys([*(c for c in _COMMON_UNITS if c.lower() == low), low]):
        if cand == unit.strip():
            continue
        try:
            _to_si_pint_checked(1.0, cand, kind, percent_formatted)
        except UnitProblem:
            continue
        return cand
    return None


def _to_si_pint(value: float, unit: str, kind: str, percent_formatted: bool) -> float:
    """The conversion itself (pint); :func:`to_si` caches it as a factor and an offset. A
    unit refused only because of its letter case gets a "did you mean" hint."""
    try:
        return _to_si_pint_checked(value, unit, kind, percent_formatted)
    except UnitProblem as exc:
        hint = _case_hint(unit, kind, percent_formatted) if unit.strip() else None
        if hint is None:
            raise
        raise UnitProblem(f"{exc}; did you mean '{hint}'? (units are case-sensitive)"
                          ) from None


def _to_si_pint_checked(value: float, unit: str, kind: str, percent_formatted: bool
                        ) -> float:
    """:func:`_to_si_pint` without the hint."""
    k = KINDS[kind]
    u = unit
    expected = f"{kind_words(k.name)} (e.g. {k.example})"

    if percent_formatted:
        if kind not in ("dimensionless", "ratio") or u.lower() not in _DIMENSIONLESS_SPELLINGS | {
            "%",
            "percent",
        }:
            raise UnitProblem(
                f"percent-formatted cell with unit '{u}': expected {expected}; a cell shown as"
                " a percentage may only hold a dimensionless value"
            )
        return float(value)

    dimensionless = kind in ("dimensionless", "ratio")
    if u.lower() in _DIMENSIONLESS_SPELLINGS:
        if dimensionless:
            return float(value)
        raise UnitProblem(f"expected {expected}, but the unit cell is empty")
    pint, _, Q_ = _pint()
    if dimensionless:
        units = parse_unit(u)
        q = Q_(float(value), units)
        if not q.dimensionless or str(units) in _ANGLE_UNITS:
            raise UnitProblem(f"expected {expected}, found unit '{u}' ({_dimension_words(units)})")
        return float(q.to("").magnitude)

    if kind == "angle":
        units = parse_unit(u.replace("°", "degree"))
        if str(units) not in _ANGLE_UNITS:
            raise UnitProblem(f"expected {expected}, found unit '{u}' ({_dimension_words(units)})")
        return float(Q_(float(value), units).to("radian").magnitude)

    if kind == "speed":
        key = u.lower().replace(" ", "")
        target = _SPEED_ALIASES.get(key)
        if target is None:
            units = parse_unit(u)
            raise UnitProblem(
                f"expected {expected} (accepted: rpm, 1/min, min^-1, Hz or rev/s, rad/s),"
                f" found unit '{u}' ({_dimension_words(units)})"
            )
        return float(Q_(float(value), target).to("radian/second").magnitude)

    if kind in ("temperature", "temperature_difference"):
        t = u.replace("°", "deg").replace(" ", "")
        aliases = {"degC": "degC", "C": "degC", "degF": "degF", "F": "degF", "K": "kelvin",
                   "kelvin": "kelvin", "degR": "degR"}
        base = aliases.get(t)
        if base is None and t in ("delta_degC", "delta_degF", "Δ°C", "Δ°F"):
            if kind == "temperature":
                raise UnitProblem(f"expected an absolute temperature (°C, K or °F), found the"
                                  f" temperature difference unit '{u}'")
            base = t.replace("Δ", "delta_")
        if base is None:
            units = parse_unit(u)
            raise UnitProblem(f"expected {expected} (°C, K or °F), found unit '{u}'"
                              f" ({_dimension_words(units)})")
        if kind == "temperature_difference" and base in ("degC", "degF"):
            base = "delta_" + base
        return float(Q_(float(value), base).to("kelvin").magnitude)

    if kind in ("pressure", "pressure_gauge"):
        base, ref = _pressure_reference(u)
        units = parse_unit(base)
        try:
            pa = float(Q_(float(value), units).to("Pa").magnitude)
        except pint.errors.DimensionalityError as exc:
            raise UnitProblem(
                f"expected {expected}, found unit '{u}' ({_dimension_words(units)})"
            ) from exc
        if kind == "pressure" and ref == "gauge":
            pa += ATMOSPHERE_PA
        elif kind == "pressure_gauge" and ref == "absolute":
            pa -= ATMOSPHERE_PA
        return pa

    units = parse_unit(u)
    q = Q_(float(value), units)
    si = k.si
    if kind in ("torsional_stiffness", "torsional_damping"):
        # rad is dimensionless in pint: accept N m/rad, N m/deg, N m (per radian implied)
        try:
            return float(q.to(si).magnitude)
        except pint.errors.DimensionalityError as exc:
            raise UnitProblem(
                f"expected {expected}, found unit '{u}' ({_dimension_words(units)})"
            ) from exc
    try:
        return float(q.to(si).magnitude)
    except pint.errors.DimensionalityError as exc:
        raise UnitProblem(
            f"expected {expected}, found unit '{u}' ({_dimension_words(units)})"
        ) from exc


def _table():
    from . import unit_table

    return unit_table


@functools.lru_cache(maxsize=1024)
def convert_affine(src: str, dst: str) -> tuple[float, float]:
    """``(a, b)`` with ``x[dst] = a x[src] + b`` (pint unit strings; offset units such as °C
    convert affinely): ``b = Q(0, src).to(dst)``, ``a = Q(1, src).to(dst) - b``. From the
    table :data:`checker.workbook.unit_table.CONVERT` (the pairs of the shipped rules and of the
    workbook ranges, pint's own numbers) or by pint. Raises :class:`UnitProblem` when the
    units do not fit each other."""
    got = _table().CONVERT.get((src, dst))
    if got is not None:
        return got
    _, _, Q_ = _pint()
    try:
        b = float(Q_(0.0, src).to(dst).magnitude)
        a = float(Q_(1.0, src).to(dst).magnitude) - b
    except Exception as exc:  # noqa: BLE001 - pint raises several kinds
        raise UnitProblem(f"cannot convert '{src}' to '{dst}'") from exc
    return a, b


def from_si(value, si_unit: str, display: str):
    """Convert an SI magnitude (float or array) to a display unit (report layer only)."""
    if si_unit == "rad/s" and display == "rpm":
        return value * 60.0 / (2.0 * math.pi)
    if si_unit == "K" and display in ("°C", "degC"):
        return value - 273.15
    if si_unit == "rad" and display in ("deg", "°"):
        return value * 180.0 / math.pi
    if si_unit == display:
        return value
    src, dst = si_unit if si_unit else "", display.replace("%", "percent")
    got = _table().CONVERT.get((src, dst))
    if got is not None and got[1] == 0.0:  # a factor: Q(1, src).to(dst) - 0.0
        return value * got[0]
    factor = _pint()[2](1.0, src).to(dst).magnitude
    return value * factor
