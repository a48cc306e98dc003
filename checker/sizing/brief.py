"""The concept brief of ``checker new``: a dozen numbers with units (TOML file or options).

Values with units are strings, ``bore = "86 mm"``, converted to SI by :func:`checker.workbook.units.
to_si` (the workbook's unit handling); every problem of a brief is reported at once
(:class:`checker.errors.InputErrors`: ``file:line``, key, expected with unit, found), exit code
2; a file that is not UTF-8 text or not TOML is refused at its line.
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError, InputErrors
from ..workbook.units import UnitProblem, kind_words, to_si

# key: (kind, example, required, default text or None)
KEYS: dict[str, tuple[str, str, bool, str | None]] = {
    "name": ("text", '"My engine"', False, "'New engine (checker new)'"),
    "cylinders": ("int", "4", True, None),
    "layout": ("choice", '"inline" or "V"', False, "inline"),
    "bank_angle": ("angle", '"90 deg"', False, "V engines: the even-firing angle 720/cylinders"),
    "bore": ("length", '"86 mm"', True, None),
    "stroke": ("length", '"94.6 mm"', True, None),
    "rated_power": ("power", '"110 kW"', True, None),
    "rated_speed": ("speed", '"6000 rpm"', True, None),
    "max_speed": ("speed", '"7000 rpm"', False, "1.1 x rated speed"),
    "min_speed": ("speed", '"1000 rpm"', False, "1000 rpm (gasoline) or 800 rpm (diesel)"),
    "peak_pressure": ("pressure", '"85 bar"', False, "typical by fuel: gasoline 85 bar,"
                      " diesel 180 bar"),
    "bearing_pressure": ("pressure", '"44.5 MPa"', False, "the specific-load capacity of the"
                         " fuel's usual lining: 44.5 MPa (aluminium bimetal, gasoline) or 66.5"
                         " MPa (tri-metal, diesel)"),
    "fuel": ("choice", '"gasoline" or "diesel"', False, "gasoline"),
    "crank_material": ("choice", '"forged steel", "nodular iron", "42CrMo4"', False,
                       "forged steel"),
    "bearing_lining": ("choice", '"aluminium bimetal", "tri-metal"...', False,
                       "aluminium bimetal (gasoline), tri-metal (diesel)"),
    "engine_class": ("choice", '"passenger car", "commercial vehicle", "industrial" or'
                     ' "marine"', False, "by fuel and bore: gasoline passenger car; diesel"
                     " below 95 mm passenger car, to 200 mm commercial vehicle, above marine"),
    "crank_type": ("choice", '"shared pins", "split pins", "flat-plane", "cross-plane" (V);'
                   ' "180 deg", "270 deg", "360 deg" (twins)', False,
                   "V engines: shared pins (a V8: cross-plane); twins: 360 deg in-line, one"
                   " pin on a V"),
    "firing_order": ("text", '"1-3-4-2"', False, "the most even firing the crank type allows"),
}
CHOICES = {
    "layout": {"inline": "inline", "straight": "inline", "v": "V", "vee": "V"},
    "fuel": {"gasoline": "gasoline", "petrol": "gasoline",
             "spark ignition": "gasoline", "si": "gasoline", "diesel": "diesel",
             "compression ignition": "diesel", "ci": "diesel"},
    "engine_class": {"passenger car": "passenger car", "car": "passenger car",
                     "commercial vehicle": "commercial vehicle", "truck": "commercial vehicle",
                     "heavy duty": "commercial vehicle", "bus": "commercial vehicle",
                     "industrial": "industrial", "genset": "industrial",
                     "stationary": "industrial", "off highway": "industrial",
                     "marine": "marine"},
    "crank_type": {"shared pins": "shared pins", "shared": "shared pins",
                   "common pins": "shared pins", "split pins": "split pins",
                   "split": "split pins", "offset pins": "split pins",
                   "flat plane": "flat-plane", "flat": "flat-plane", "flatplane": "flat-plane",
                   "cross plane": "cross-plane", "cross": "cross-plane",
                   "crossplane": "cross-plane", "180 deg": "180 deg", "180": "180 deg",
                   "180°": "180 deg", "270 deg": "270 deg", "270": "270 deg",
                   "270°": "270 deg", "360 deg": "360 deg", "360": "360 deg",
                   "360°": "360 deg"},
    "crank_material": {"forged steel": "forged steel", "steel": "forged steel",
                       "nodular iron": "nodular iron", "nodular cast iron": "nodular iron",
                       "ductile iron": "nodular iron", "cast iron": "nodular iron",
                       "42crmo4": "42CrMo4", "alloy steel": "42CrMo4"},
    "bearing_lining": {"aluminium bimetal": "aluminium bimetal", "aluminum bimetal":
                       "aluminium bimetal", "tri-metal": "tri-metal", "trimetal": "tri-metal",
                       "as15": "AS15", "as16": "AS16", "sputter": "sputter",
                       "polymer": "polymer"},
}
VALID = {  # (lo, hi) in SI: outside, no rule of checker new has data (stated)
    "cylinders": (1, 16),
    "bore": (0.04, 0.30),
    "stroke": (0.04, 0.40),
    "bank_angle": (math.radians(15), math.radians(180)),
    "rated_speed": (500 * math.pi / 30, 12000 * math.pi / 30),
    "peak_pressure": (30e5, 300e5),
    "bearing_pressure": (5e6, 120e6),
}


@dataclass(frozen=True)
class Brief:
    """The brief in SI, and which values were defaults (``defaults``: key -> text)."""

    cylinders: int
    layout: str
    bank_angle: float
    bore: float
    stroke: float
    rated_power: float
    rated_speed: float
    max_speed: float
    min_speed: float
    peak_pressure: float
    fuel: str
    bearing_pressure: float
    crank_material: str
    bearing_lining: str
    name: str = "New engine (checker new)"
    defaults: dict[str, str] = field(default_factory=dict)
    engine_class: str = "passenger car"
    crank_type: str | None = None
    firing_order: str | None = None
    lines: dict[str, int] = field(default_factory=dict)  # brief key -> line of the file


_NUM = re.compile(r"^\s*([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?|[-+]?\.\d+(?:[eE][-+]?\d+)?)\s*(.*)$")


def _norm(s: str) -> str:
    return re.sub(r"[\s_\-]+", " ", s.strip().lower())


def parse_brief(raw: dict[str, Any], where: str = "brief",
                lines: dict[str, int] | None = None) -> Brief:
    """Check and convert a brief (``{key: value}``, TOML types); all problems in one
    :class:`InputErrors`. ``lines``: the line of each key in the brief file (messages say
    ``file:line: key``)."""
    errs: list[InputError] = []
    vals: dict[str, Any] = {}
    lines = lines or {}

    def loc(k: str) -> str:
        return f"{where}:{lines[k]}: {k}" if k in lines else f"{where}: {k}"

    for k in raw:
        if k not in KEYS:
            near = difflib.get_close_matches(k.lower(), list(KEYS), n=1, cutoff=0.7)
            errs.append(InputError(loc(k), "unknown key; expected one of "
                                   + ", ".join(KEYS) + (f" (did you mean {near[0]}?)"
                                                        if near else "")))
    for k, (kind, example, required, _dflt) in KEYS.items():
        if k not in raw:
            if required:
                errs.append(InputError(loc(k), f"required: expected e.g. {k} = "
                                       f"{example}, found nothing"))
            continue
        v = raw[k]
        at = loc(k)
        if kind == "text":
            vals[k] = str(v)
        elif kind == "int":
            if isinstance(v, bool) or not isinstance(v, int) or v <= 0:
                errs.append(InputError(at, f"expected a whole number > 0, e.g. {example};"
                                       f" found {v!r}"))
            else:
                vals[k] = v
        elif kind == "choice":
            c = CHOICES[k].get(_norm(str(v))) if isinstance(v, str) else None
            if c is None:
                errs.append(InputError(at, f"expected {example} (one of "
                                       + ", ".join(sorted(set(CHOICES[k].values())))
                                       + f"); found {v!r}"))
            else:
                vals[k] = c
        else:
            m = _NUM.match(v) if isinstance(v, str) else None
            if m is None or not m.group(2).strip():
                errs.append(InputError(at, f"expected a number with its unit as a string, e.g."
                                       f" {k} = {example}; found {v!r}"))
                continue
            try:
                x = to_si(float(m.group(1)), m.group(2).strip(), kind)
            except UnitProblem as exc:
                errs.append(InputError(at, f"expected {kind_words(kind)} with its unit, e.g."
                                       f" {example}; found {v!r} ({exc})"))
                continue
            if x <= 0:
                errs.append(InputError(at, f"expected {kind_words(kind)} > 0, e.g. {example};"
                                       f" found {v!r}"))
                continue
            vals[k] = x
    defaults: dict[str, str] = {}
    if not errs:
        for k, (_kind, _ex, _req, dflt) in KEYS.items():
            if k not in vals and dflt is not None:
                defaults[k] = dflt
        fuel = vals.get("fuel", "gasoline")
        layout = vals.get("layout", "inline")
        n = vals["cylinders"]
        if layout == "V" and n % 2:
            errs.append(InputError(loc("cylinders"), "a V engine needs an even number of"
                                   f" cylinders (two banks, two rods per pin); found {n}"))
        if layout == "inline" and "bank_angle" in vals:
            errs.append(InputError(loc("bank_angle"), "only for layout = \"V\"; found a"
                                   " bank angle with an in-line layout"))
        bank = vals.get("bank_angle", 4 * math.pi / n if layout == "V" else 0.0)
        if layout == "V" and n == 2 and "bank_angle" not in vals:
            bank = math.pi / 2
        ctype = vals.get("crank_type")
        if ctype in ("flat-plane", "cross-plane") and not (layout == "V" and n == 8):
            errs.append(InputError(loc("crank_type"), f"{ctype} is a crank of V8 engines; found"
                                   f" {'a V' if layout == 'V' else 'an in-line '}{n}"))
        if ctype in ("180 deg", "270 deg", "360 deg") and n != 2:
            errs.append(InputError(loc("crank_type"), f"{ctype} is a crank of twins; found {n}"
                                   " cylinders"))
        if ctype in ("shared pins", "split pins") and layout != "V":
            errs.append(InputError(loc("crank_type"), f"{ctype} is a crank of V engines; found"
                                   " an in-line layout"))
        if ctype in ("180 deg", "270 deg", "360 deg") and layout == "V" and n == 2:
            need = 360.0 - float(ctype.split()[0])  # one pin: intervals 360 -/+ bank angle
            given = math.degrees(vals.get("bank_angle", math.radians(need)))
            if need <= 0.0 or abs(given - need) > 1e-6:
                what = (f"needs bank_angle = \"{need:g} deg\"" if need > 0 else
                        "cannot be a V on one pin (use layout = \"inline\")")
                errs.append(InputError(loc("crank_type"), "a V-twin on one pin fires 360 deg"
                                       f" -/+ its bank angle apart: a {ctype} twin {what};"
                                       f" found {given:g} deg"))
            elif "bank_angle" not in vals:
                vals["bank_angle"] = math.radians(need)
        rated = vals["rated_speed"]
        vmax = vals.get("max_speed", 1.1 * rated)
        vmin = vals.get("min_speed", (1000.0 if fuel == "gasoline" else 800.0) * math.pi / 30)
        if vmax < rated:
            errs.append(InputError(loc("max_speed"), "expected at least the rated speed"
                                   f" ({rated * 30 / math.pi:.0f} rpm); found"
                                   f" {vmax * 30 / math.pi:.0f} rpm"))
        if vmin >= rated:
            errs.append(InputError(loc("min_speed"), "expected below the rated speed"
                                   f" ({rated * 30 / math.pi:.0f} rpm); found"
                                   f" {vmin * 30 / math.pi:.0f} rpm"))
        from ..calc.first_layout import SIZING_LOAD, engine_class
        from ..calc.first_layout import peak_pressure as typical

        lining = vals.get("bearing_lining",
                          "aluminium bimetal" if fuel == "gasoline" else "tri-metal")
        brief = Brief(
            cylinders=n, layout=layout, bank_angle=bank, bore=vals["bore"],
            stroke=vals["stroke"], rated_power=vals["rated_power"], rated_speed=rated,
            max_speed=vmax, min_speed=vmin,
            peak_pressure=vals.get("peak_pressure", typical(fuel)), fuel=fuel,
            bearing_pressure=vals.get("bearing_pressure", SIZING_LOAD[fuel]),
            crank_material=vals.get("crank_material", "forged steel"),
            bearing_lining=lining, name=vals.get("name", "New engine (checker new)"),
            defaults=defaults,
            engine_class=vals.get("engine_class", engine_class(fuel, vals["bore"])),
            crank_type=ctype, firing_order=vals.get("firing_order"), lines=dict(lines))
        for k, (lo, hi) in VALID.items():
            x = getattr(brief, k)
            if layout != "V" and k == "bank_angle":
                continue
            if not lo <= x <= hi:
                errs.append(InputError(loc(k), _no_data(k, x, lo, hi)))
        if errs:
            raise InputErrors(errs, source=str(where))
        return brief
    raise InputErrors(errs, source=str(where))


def _fmt(k: str, x: float) -> str:
    if k in ("bore", "stroke"):
        return f"{x * 1e3:g} mm"
    if k == "bank_angle":
        return f"{math.degrees(x):g} deg"
    if k == "rated_speed":
        return f"{x * 30 / math.pi:g} rpm"
    if k == "peak_pressure":
        return f"{x / 1e5:g} bar"
    if k == "bearing_pressure":
        return f"{x / 1e6:g} MPa"
    return f"{x:g}"


def _no_data(k: str, x: float, lo: float, hi: float) -> str:
    why = {
        "bore": "the piston and rod mass rules and the web ratio are car/truck-engine rules",
        "stroke": "the rod-length ratio is a car/truck-engine ratio",
        "cylinders": "firing orders are tabled or derived for 1-16 cylinders",
        "bank_angle": "V engines with two rods per pin",
        "rated_speed": "the sized joints and damper are car/truck-engine designs",
        "peak_pressure": "Agostini 2019's admissible bearing pressure is for engine pressures",
        "bearing_pressure": "the journal-length rule sizes engine plain bearings",
    }[k]
    return (f"no rule of checker new has data for {_fmt(k, x)} (covered: {_fmt(k, lo)} to"
            f" {_fmt(k, hi)}; {why}): type this engine's workbook by hand (checker template)"
            " or change the brief")


_KEY_LINE = re.compile(r"""^\s*(?:"([^"]*)"|'([^']*)'|([A-Za-z0-9_-]+))\s*(?:\.[^=]*)?=""")
_TOML_AT = re.compile(r"\s*\(at line (\d+), column (\d+)\)\s*$")


def key_lines(text: str) -> dict[str, int]:
    """Line (1-based) of each top-level key of a TOML brief (the first assignment; a brief
    has no tables)."""
    out: dict[str, int] = {}
    for i, line in enumerate(text.splitlines(), start=1):
        if line.lstrip().startswith("["):
            break
        m = _KEY_LINE.match(line)
        if m:
            out.setdefault(next(g for g in m.groups() if g is not None), i)
    return out


def _read_toml(path: str | Path, where: str) -> tuple[dict[str, Any], dict[str, int]]:
    """The brief file's keys and their lines; a file that cannot be read, is not UTF-8 text
    or is not TOML is an error at its line."""
    def fail(message: str) -> InputErrors:
        return InputErrors([InputError(where, message)], source=where)

    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise fail(f"cannot be read: {exc.strerror}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise InputErrors([InputError(
            f"{where}:{line}", f"expected a text file (TOML, UTF-8), e.g. bore = \"86 mm\";"
            f" found the byte 0x{data[exc.start]:02x}, which is not UTF-8 text (a binary"
            " or differently encoded file?)")], source=where) from None
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc)
        m = _TOML_AT.search(msg)
        at = f"{where}:{m.group(1)}" if m else where
        reason = _TOML_AT.sub("", msg) if m else msg
        line = text.splitlines()[int(m.group(1)) - 1].strip() if m and int(m.group(1)) <= len(
            text.splitlines()) else ""
        raise InputErrors([InputError(
            at, "expected TOML lines key = value, e.g. bore = \"86 mm\"; found"
            + (f" '{line}'" if line else " the end of the file")
            + (f" (column {m.group(2)}: {reason.lower()})" if m else f" ({reason.lower()})"))],
            source=where) from None
    return raw, key_lines(text)


def load_brief(path: str | Path, options: dict[str, Any] | None = None) -> Brief:
    """Read a brief file (TOML) and/or options (options win); all problems at once, each at
    ``file:line`` with its key."""
    raw: dict[str, Any] = {}
    lines: dict[str, int] = {}
    where = "options"
    if path is not None:
        where = Path(path).name
        raw, lines = _read_toml(path, where)
    given = {k: v for k, v in (options or {}).items() if v is not None}
    raw.update(given)
    for k in given:
        lines.pop(k, None)  # an option wins over the file: no line of the file
    return parse_brief(raw, where, lines)
