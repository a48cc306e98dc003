"""How numbers, units and margins read in every output (text, JSON messages, HTML, PDF).

One style everywhere: units as engineers write them (``µm``, ``MPa``, ``N·m``, ``°``, ``mm²``),
values to four significant digits (more only where fewer would make a value look equal to its
limit), margins in words ("limit exceeded by 11 %", "12.4 × the limit"). Formatting only: no
unit conversion happens here (values arrive in the rule's display unit).
"""

from __future__ import annotations

import math
import re

SIG = 4
"""Significant digits of a displayed value."""

ENGINE_ITEM = "all"
"""The item key of a result about the whole engine (a quantity without an item axis: the
crank-nose amplitude, the cyclic irregularity); the JSON keeps this key."""
ENGINE_LABEL = "engine"
"""How that item reads wherever people read it (text, JUnit, the PDF, the results workbook,
messages)."""


def item_label(item: str) -> str:
    """An item as people read it: the whole engine's key ``all`` reads ``engine``; any other
    item (``M1``, ``crank nose``, ``order 2``) as it is."""
    return ENGINE_LABEL if item == ENGINE_ITEM else item

_WORD_UNITS = {
    "um": "µm", "micron": "µm", "microns": "µm", "deg": "°", "degree": "°", "degrees": "°",
    "percent": "%", "N/mm^2": "MPa", "N/mm**2": "MPa", "N/mm²": "MPa", "Nm": "N·m",
    "N m": "N·m", "N*m": "N·m", "kNm": "kN·m", "kN m": "kN·m", "kN*m": "kN·m", "-": "", "1": "",
    "dimensionless": "", "W/m**3": "W/m³", "W/cm^3": "W/cm³", "W/cm**3": "W/cm³",
}


def unit_text(unit: str | None) -> str:
    """A unit string as displayed: ``um`` -> ``µm``, ``N m`` -> ``N·m``, ``mm^2`` -> ``mm²``,
    ``N/mm^2`` -> ``MPa`` (the same number), ``-`` -> empty (dimensionless)."""
    if not unit:
        return ""
    u = unit.strip()
    if u in _WORD_UNITS:
        return _WORD_UNITS[u]
    u = re.sub(r"\*\*2|\^2", "²", u)
    u = re.sub(r"\*\*3|\^3", "³", u)
    u = re.sub(r"\*\*-1|\^-1", "⁻¹", u)
    u = re.sub(r"(?<![A-Za-z])um(?![A-Za-z])", "µm", u)
    u = re.sub(r"(?<![A-Za-z])deg(?![A-Za-z])", "°", u)
    u = u.replace("*", "·")
    u = re.sub(r"(?<=[A-Za-z²³])\s+(?=[A-Za-z])", "·", u)
    return u


def number(v: float | None, sig: int = SIG, distinct_from: float | None = None) -> str:
    """``v`` to ``sig`` significant digits (``-`` for None/NaN). Values of 10⁴ and more show
    as whole numbers; below 10⁻³ in scientific notation. With ``distinct_from`` (the limit),
    digits are added (up to 8) until the shown value differs from the shown limit, so a
    failing 1.7996 never reads "1.8" against a limit of 1.8."""
    if v is None or not math.isfinite(v):
        return "-"
    s = _number(v, sig)
    if distinct_from is not None and math.isfinite(distinct_from) and v != distinct_from:
        n = sig
        while n < 8 and float(s.replace("−", "-")) == float(
                _number(distinct_from, n).replace("−", "-")):
            n += 1
            s = _number(v, n)
    return s


ROUND_OFF = 1e-9

CELL_REF = re.compile(r"\b[A-Za-z][A-Za-z0-9_]*![A-Z]{1,3}[0-9]+\b")
"""A workbook cell named in a message, ``Bearings!Q3``."""
"""Shown values smaller than this (in their display unit) are zero to round-off (the free
moments of an inline 4 come out near 1e-13 N·m): shown as 0."""


def _number(v: float, sig: int) -> str:
    if v == 0 or abs(v) < ROUND_OFF:
        return "0"
    a = abs(v)
    if a >= 10 ** sig:
        s = f"{v:.0f}"
    elif a < 1e-3:
        s = f"{v:.{sig - 1}e}"
        mant, exp = s.split("e")
        s = f"{mant.rstrip('0').rstrip('.')}e{int(exp)}"
    else:
        digits = max(0, sig - 1 - int(math.floor(math.log10(a))))
        s = f"{v:.{digits}f}"
        if "." in s:
            s = s.rstrip("0").rstrip(".")
    return s.replace("-", "−") if s.startswith("-") else s


def with_unit(v: float | None, unit: str | None, sig: int = SIG,
              distinct_from: float | None = None) -> str:
    """``0.8713 µm``, ``0.156°``, ``79.51 %``, ``1.467`` (dimensionless)."""
    s = number(v, sig, distinct_from)
    u = unit_text(unit)
    if s == "-" or not u:
        return s
    return s + u if u == "°" else f"{s} {u}"


def limit_text(check: str, limit: tuple[float, ...] | list[float] | None, unit: str | None
               ) -> str:
    """``≤ 48 MPa``, ``≥ 1.2 µm``, ``70..75 %``."""
    if not limit:
        return "-"
    u = unit_text(unit)
    sfx = ("" if not u else u if u == "°" else f" {u}")
    if check == "between":
        return f"{_g(limit[0])}..{_g(limit[1])}{sfx}"
    sym = {">=": "≥", "<=": "≤", ">": ">", "<": "<"}.get(check, check)
    return f"{sym} {_g(limit[0])}{sfx}"


def _g(x: float) -> str:
    return f"{x:g}".replace("-", "−")


def _pct(p: float) -> str:
    p = abs(p)
    return f"{p:.1f}" if p < 10 else f"{p:.0f}"


def _pts(p: float) -> str:
    p = abs(p)
    return f"{number(p, 3)} point" + ("" if p == 1 else "s")


def margin_words(check: str, value: float | None, limit: list[float] | tuple | None,
                 margin: float | None, passed: bool, unit: str | None = None) -> str:
    """The distance to the limit in words, e.g. "limit exceeded by 11 %", "27 % below the
    minimum", "12.4 × the limit", "5.7 % below the limit"; ``-`` without a value.

    With ``unit``: a limit in percent is a distance in percentage points ("4.5 points above the
    range", never a percentage of a percentage); a value of zero against an upper limit reads
    "0 N (limit 500 N)" (not "100 % below the limit")."""
    if value is None or margin is None or not limit or not math.isfinite(margin):
        return "-"
    lim = list(limit)
    u = unit_text(unit)
    if check in ("<=", "<") and passed and lim[0] > 0 and abs(value) < ROUND_OFF:
        return f"{with_unit(0.0, unit)} (limit {with_unit(lim[0], unit)})"
    if u == "%":
        if check in ("<=", "<"):
            d = value - lim[0]
            return (f"{_pts(d)} above the limit" if not passed
                    else f"{_pts(d)} below the limit")
        if check in (">=", ">"):
            d = lim[0] - value
            return (f"{_pts(d)} below the minimum" if not passed
                    else f"{_pts(d)} above the minimum")
        if passed:
            return f"within the range ({_pts(min(value - lim[0], lim[1] - value))} from its" \
                   " nearer end)"
        return (f"{_pts(lim[0] - value)} below the range" if value < lim[0]
                else f"{_pts(value - lim[1])} above the range")
    if check in ("<=", "<"):
        if not passed:
            if lim[0] > 0 and value / lim[0] >= 2:
                return f"{number(value / lim[0], 3)} × the limit"
            return (f"limit exceeded by {_pct(margin * 100)} %" if lim[0]
                    else f"limit exceeded by {number(-margin)}")
        return (f"{_pct(margin * 100)} % below the limit" if lim[0]
                else f"{number(margin)} below the limit")
    if check in (">=", ">"):
        if not passed:
            return (f"{_pct(margin * 100)} % below the minimum" if lim[0]
                    else f"{number(-margin)} below the minimum")
        return (f"{_pct(margin * 100)} % above the minimum" if lim[0]
                else f"{number(margin)} above the minimum")
    # between
    if passed:
        return f"within the range ({_pct(margin * 100)} % from its nearer end)"
    return (f"{_pct(margin * 100)} % below the range" if value < lim[0]
            else f"{_pct(margin * 100)} % above the range")


CASE_TEXT = {"full": "full load", "no": "no load", "part": "part load"}
"""Load cases as every output names them."""


def case_text(case: str) -> str:
    """A load case in words (``"full"`` -> ``"full load"``); unknown labels as given."""
    return CASE_TEXT.get(case, case)
