"""The crank described by its geometry (sheets ``Crank`` and ``CrankEnds``), typed in SI.

Sheet ``Crank`` has a row ``all`` for what every throw shares and a row per throw number for
what differs on that throw; a throw row's blank cell takes the ``all`` row's value (or one row
per throw, without ``all``). :func:`build_crank` resolves every throw's dimensions, remembers
the cell each came from, and checks the geometry (:func:`check_throw`): every problem is an
error at its cell, all reported in one pass.

The geometry and its coordinate system are those of :mod:`checker.calc.crank_geometry`
(docs/crank-geometry.md).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

THROW_DIMENSIONS = ("journal_diameter", "journal_bore", "journal_length", "pin_diameter",
                    "pin_bore", "pin_length", "web_thickness", "web_width_journal",
                    "web_width_pin", "cw_inner_radius", "cw_outer_radius", "cw_angle",
                    "cw_thickness", "pin_fillet_radius", "pin_fillet_undercut",
                    "pin_fillet_web_undercut", "main_fillet_radius", "main_fillet_undercut",
                    "main_fillet_web_undercut", "pin_oil_hole_diameter",
                    "main_oil_hole_diameter")
"""Per-throw columns of sheet Crank (the material is one for the crank)."""

REQUIRED = ("journal_diameter", "journal_length", "pin_diameter", "pin_length",
            "web_thickness", "web_width_journal", "web_width_pin")
MATERIAL = ("density", "youngs_modulus", "poisson_ratio")
JOURNAL = ("journal_diameter", "journal_bore", "journal_length")
COUNTERWEIGHT = ("cw_inner_radius", "cw_outer_radius", "cw_angle")


@dataclass(frozen=True)
class CrankThrow:
    """One throw's dimensions [m, rad]; bores and an absent counterweight are 0; fillet and
    oil-hole entries ``None`` when not given."""

    number: int
    journal_diameter: float
    journal_bore: float
    journal_length: float
    pin_diameter: float
    pin_bore: float
    pin_length: float
    web_thickness: float
    web_width_journal: float
    web_width_pin: float
    cw_inner_radius: float = 0.0
    cw_outer_radius: float = 0.0
    cw_angle: float = 0.0
    cw_thickness: float = 0.0  # 0 = the web thickness
    pin_fillet_radius: float | None = None
    pin_fillet_undercut: float | None = None
    pin_fillet_web_undercut: float | None = None
    main_fillet_radius: float | None = None
    main_fillet_undercut: float | None = None
    main_fillet_web_undercut: float | None = None
    pin_oil_hole_diameter: float | None = None
    main_oil_hole_diameter: float | None = None

    @property
    def length(self) -> float:
        """Throw length between its journal mid-planes, ``Lj + 2 tw + Lp`` [m]."""
        return self.journal_length + 2.0 * self.web_thickness + self.pin_length

    @property
    def has_counterweight(self) -> bool:
        return self.cw_outer_radius > 0.0 and self.cw_angle > 0.0


@dataclass(frozen=True)
class CrankGeometry:
    """The crank (SI): its throws front to rear, material, ends and off-crank unbalances.

    ``cells`` maps ``(throw number, attr)`` (throw 0 for CrankEnds parameters and the
    material) to the workbook cell the value came from (for messages and the report).
    """

    throws: tuple[CrankThrow, ...]
    crank_radius: float  # [m] stroke / 2
    density: float  # [kg/m^3]
    youngs_modulus: float  # [Pa]
    poisson_ratio: float
    nose_diameter: float | None = None
    nose_bore: float = 0.0
    nose_length: float | None = None
    flange_diameter: float | None = None
    flange_bore: float = 0.0
    flange_length: float | None = None
    pulley_unbalance: float = 0.0  # [kg m]
    pulley_angle: float = 0.0  # [rad] from throw 1 in the direction of rotation
    pulley_distance: float = 0.0  # [m] ahead of the first main journal's mid-plane
    flywheel_unbalance: float = 0.0
    flywheel_angle: float = 0.0
    flywheel_distance: float = 0.0  # [m] behind the last main journal's mid-plane
    cells: dict[tuple[int, str], str] = field(default_factory=dict, compare=False, repr=False)

    @property
    def shear_modulus(self) -> float:
        """``G = E / (2 (1 + nu))`` [Pa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    def cell(self, attr: str, throw: int = 0) -> str:
        """Cell a value came from (``Crank`` when unknown)."""
        return self.cells.get((throw, attr), self.cells.get((0, attr), "Crank"))

    def column(self, attr: str) -> list[float]:
        """One dimension of every throw, front to rear."""
        return [float(getattr(t, attr)) for t in self.throws]

    @functools.cached_property
    def mass_properties(self):
        """:class:`checker.calc.crank_geometry.ThrowMassProperties` of every throw."""
        from ..calc.crank_geometry import throw_mass_properties

        return throw_mass_properties(
            **{k: self.column(k) for k in (
                "journal_diameter", "journal_bore", "journal_length", "pin_diameter",
                "pin_bore", "pin_length", "web_thickness", "web_width_journal",
                "web_width_pin", "cw_inner_radius", "cw_outer_radius", "cw_angle",
                "cw_thickness")},
            crank_radius=self.crank_radius, density=self.density)


def _throw_key(value: Any) -> int | str | None:
    """``'all'``, a throw number, or None (not a throw key)."""
    text = str(value).strip().lower()
    if text == "all":
        return "all"
    try:
        num = float(text)
    except ValueError:
        return None
    return int(num) if num.is_integer() and num >= 1 else None


def counterweight_pin_gap(t: CrankThrow, crank_radius: float) -> float:
    """Smallest distance [m] in the end view between the pin's outline (circle ``Dp/2`` about
    ``(0, R)``) and the counterweight's annular sector (negative: they overlap)."""
    h = t.cw_angle / 2.0  # half angle from -y; the pin lies at angle pi from -y
    if h >= math.pi:
        d = max(t.cw_inner_radius - crank_radius, crank_radius - t.cw_outer_radius, 0.0)
    else:
        # nearest point of an edge ray at angle h from -y, between ri and ro
        along = min(max(-crank_radius * math.cos(h), t.cw_inner_radius), t.cw_outer_radius)
        ex, ey = along * math.sin(h), -along * math.cos(h)
        d = math.hypot(ex, ey - crank_radius)
    return d - t.pin_diameter / 2.0


def check_throw(t: CrankThrow, crank_radius: float, bad: Callable[[str, str], None]) -> None:
    """Geometry of one throw; ``bad(attr, message)`` for each problem (issue 33, item 7)."""
    mm = 1e3
    for d, b, what in (("journal_diameter", "journal_bore", "main journal"),
                       ("pin_diameter", "pin_bore", "pin")):
        if getattr(t, b) >= getattr(t, d):
            bad(b, f"the {what} bore {getattr(t, b) * mm:g} mm must be smaller than the"
                f" {what} diameter {getattr(t, d) * mm:g} mm")
    if t.web_width_journal < t.journal_diameter:
        bad("web_width_journal", f"the web ({t.web_width_journal * mm:g} mm wide at the"
            f" journal) is narrower than its main journal ({t.journal_diameter * mm:g} mm)")
    if t.web_width_pin < t.pin_diameter:
        bad("web_width_pin", f"the pin ({t.pin_diameter * mm:g} mm) lies outside its web"
            f" ({t.web_width_pin * mm:g} mm wide at the pin): the web width at the pin must be"
            " at least the pin diameter")
    if not t.has_counterweight:
        return
    if t.cw_inner_radius >= t.cw_outer_radius:
        bad("cw_inner_radius", f"counterweight inner radius {t.cw_inner_radius * mm:g} mm must"
            f" be smaller than its outer radius {t.cw_outer_radius * mm:g} mm")
        return
    if t.cw_angle > 2.0 * math.pi + 1e-12:
        bad("cw_angle", "counterweight angle must be at most 360 deg")
        return
    gap = counterweight_pin_gap(t, crank_radius)
    if gap < 0.0:
        bad("cw_angle", f"the counterweight overlaps the crank pin in the end view (by"
            f" {-gap * mm:.3g} mm): reduce its angle or radii")
    tc = t.cw_thickness or t.web_thickness
    if tc > t.web_thickness:
        if t.cw_inner_radius < t.journal_diameter / 2.0:
            bad("cw_thickness", f"a counterweight thicker than its web"
                f" ({tc * mm:g} > {t.web_thickness * mm:g} mm) must clear the main journal:"
                f" inner radius at least {t.journal_diameter / 2 * mm:g} mm")
        if tc - t.web_thickness > min(t.pin_length, t.journal_length):
            bad("cw_thickness", f"counterweight thickness {tc * mm:g} mm exceeds the web"
                f" thickness by more than the pin or journal length: neighbouring"
                " counterweights would meet")


def build_crank(rows: list[dict[str, Any]], ends: dict[str, Any], n_throws: int,
                stroke: float | None, where: dict[tuple, str],
                err: Callable[[str, str, int | None, str], None],
                sheet_error: Callable[[str, str], None],
                blank: Callable[[str, str, int | None, str], None] | None = None,
                refused: Callable[[int, str], bool] | None = None
                ) -> CrankGeometry | None:
    """The crank from sheet Crank's rows and sheet CrankEnds' parameters (SI values), or None
    without a Crank sheet (or when it has errors: they are reported through ``err``).

    ``refused(row, attr)``: whether the loader refused that cell's value (its error is
    reported; the dimension it leaves missing is not reported again). A problem of a value
    several throws take from the same cell (the ``all`` row) is reported once, naming the
    throws."""
    if not rows:
        return None
    blank = blank or err  # a required cell left blank (silent where the cell has an error)
    refused = refused or (lambda i, attr: False)
    ok = True
    by_key: dict[int | str, int] = {}
    for i, r in enumerate(rows):
        if r.get("throw") is None:
            continue
        k = _throw_key(r["throw"])
        if k is None or (k != "all" and n_throws and k > n_throws):
            err("Crank", "throw", i, f"expected 'all' or a throw number 1..{n_throws},"
                f" found '{r['throw']}'")
            ok = False
            continue
        by_key[k] = i
    if not n_throws:
        return None
    if "all" not in by_key:
        lacking = [j for j in range(1, n_throws + 1) if j not in by_key]
        if lacking:
            sheet_error("Crank", f"no row for throw {', '.join(map(str, lacking))}: the"
                        f" engine has {n_throws} throws (crank pins); give a row 'all' for"
                        " what they share, or one row per throw")
            return None
    if stroke is None:
        return None
    cells: dict[tuple[int, str], str] = {}
    origin: dict[tuple[int, str], int] = {}
    # (row, attr, message with "{whose}", blank cell) -> the throws with that problem
    problems: dict[tuple[int | None, str, str, bool], list[int]] = {}

    def was_refused(j: int, attr: str) -> bool:
        return any(refused(by_key[k], attr) for k in (j, "all") if k in by_key)

    def pick(j: int, attr: str) -> tuple[Any, int | None]:
        for key in (j, "all"):
            i = by_key.get(key)
            if i is not None and rows[i].get(attr) is not None:
                return rows[i][attr], i
        return None, None

    # the material: one for the crank
    material: dict[str, float] = {}
    for attr in MATERIAL:
        seen = [(i, rows[i][attr]) for i in sorted(by_key.values())
                if rows[i].get(attr) is not None]
        if not seen:
            if any(refused(i, attr) for i in by_key.values()):  # reported at its cell
                ok = False
                continue
            i0 = by_key.get("all", min(by_key.values()))
            err("Crank", attr, i0, f"{_LABEL[attr]} of the crank material is needed to derive"
                f" its masses and stiffnesses ({_EXPECT[attr]})")
            ok = False
            continue
        for i, v in seen[1:]:
            if v != seen[0][1]:
                err("Crank", attr, i, f"the crank has one material: {_LABEL[attr]} differs"
                    f" from {where.get(('Crank', seen[0][0], attr), 'Crank')}")
                ok = False
        material[attr] = float(seen[0][1])
        cells[(0, attr)] = where.get(("Crank", seen[0][0], attr), "Crank")
    if material.get("poisson_ratio", 0.0) >= 0.5:
        err("Crank", "poisson_ratio", by_key.get("all", min(by_key.values())),
            "Poisson's ratio must be below 0.5")
        ok = False
    throws = []
    for j in range(1, n_throws + 1):
        vals: dict[str, Any] = {}
        for attr in THROW_DIMENSIONS:
            v, i = pick(j, attr)
            vals[attr] = v
            if i is not None:
                cells[(j, attr)] = where.get(("Crank", i, attr), "Crank")
                origin[(j, attr)] = i
        missing = [a for a in REQUIRED if vals[a] is None]
        for a in missing:
            if not was_refused(j, a):
                i0 = by_key.get("all", by_key.get(j))
                problems.setdefault((i0, a, f"{_LABEL[a]} of {{whose}} is missing (expected a"
                                     " length, e.g. mm): give it on the 'all' row or the"
                                     " throw's row", True), []).append(j)
        if missing:
            ok = False
            continue
        cw_given = [a for a in COUNTERWEIGHT if vals[a] is not None]
        if cw_given and len(cw_given) < len(COUNTERWEIGHT):
            i0 = by_key.get(j, by_key.get("all"))
            for a in COUNTERWEIGHT:
                if vals[a] is None and not was_refused(j, a):
                    problems.setdefault((i0, a, f"{{whose}}: the counterweight needs its inner"
                                         f" radius, outer radius and angle: {_LABEL[a]} is"
                                         " missing", False), []).append(j)
            ok = False
            continue
        t = CrankThrow(number=j, **{a: (0.0 if vals[a] is None and a in (
            "journal_bore", "pin_bore", "cw_inner_radius", "cw_outer_radius", "cw_angle",
            "cw_thickness") else vals[a]) for a in THROW_DIMENSIONS})

        def bad(attr: str, msg: str, j: int = j) -> None:
            i = origin.get((j, attr), by_key.get(j, by_key.get("all")))
            problems.setdefault((i, attr, "{whose}: " + msg, False), []).append(j)

        check_throw(t, stroke / 2.0, bad)
        throws.append(t)
    for (i, attr, msg, is_blank), js in problems.items():  # once per cell and problem
        ok = False
        whose = (f"throw {js[0]}" if len(js) == 1 else "every throw" if len(js) == n_throws
                 else f"throws {', '.join(map(str, js))}")
        (blank if is_blank else err)("Crank", attr, i, msg.replace("{whose}", whose))
    # a main journal is shared by its two neighbouring throws: they must agree
    for a, b in zip(throws, throws[1:]):
        for attr in JOURNAL:
            if getattr(a, attr) != getattr(b, attr):
                ia = cells.get((a.number, attr), "Crank")
                ib = cells.get((b.number, attr), "Crank")
                for t, other in ((a, ib), (b, ia)):
                    err("Crank", attr, origin.get((t.number, attr)), f"main journal"
                        f" {b.number} lies between throws {a.number} and {b.number}, which"
                        f" give different {_LABEL[attr]}s (this cell and {other}): a main"
                        " journal is shared by its two throws, give its dimensions once")
                ok = False
    for attr, _ in ends.items():
        if ends.get(attr) is not None and ("CrankEnds", attr) in where:
            cells[(0, attr)] = where[("CrankEnds", attr)]
    for d, b, what in (("nose_diameter", "nose_bore", "crank nose"),
                       ("flange_diameter", "flange_bore", "flywheel flange")):
        if ends.get(d) is not None and ends.get(b) is not None and ends[b] >= ends[d]:
            err("CrankEnds", b, None, f"the {what} bore {ends[b] * 1e3:g} mm must be smaller"
                f" than its diameter {ends[d] * 1e3:g} mm"
                f" ({where.get(('CrankEnds', d), 'CrankEnds')})")
            ok = False
    if not ok:
        return None
    e = {k: v for k, v in ends.items() if v is not None}
    return CrankGeometry(
        throws=tuple(throws), crank_radius=stroke / 2.0, density=material["density"],
        youngs_modulus=material["youngs_modulus"], poisson_ratio=material["poisson_ratio"],
        nose_diameter=e.get("nose_diameter"), nose_bore=e.get("nose_bore", 0.0),
        nose_length=e.get("nose_length"), flange_diameter=e.get("flange_diameter"),
        flange_bore=e.get("flange_bore", 0.0), flange_length=e.get("flange_length"),
        pulley_unbalance=e.get("pulley_unbalance", 0.0), pulley_angle=e.get("pulley_angle", 0.0),
        pulley_distance=e.get("pulley_distance", 0.0),
        flywheel_unbalance=e.get("flywheel_unbalance", 0.0),
        flywheel_angle=e.get("flywheel_angle", 0.0),
        flywheel_distance=e.get("flywheel_distance", 0.0), cells=cells)


def _labels() -> tuple[dict[str, str], dict[str, str]]:
    from ..workbook.schema import SHEETS
    from ..workbook.units import KINDS

    labels, expect = {}, {}
    for f in SHEETS["Crank"].fields:
        labels[f.attr] = f.label
        k = KINDS.get(f.kind)
        expect[f.attr] = ("a number, no unit" if f.kind == "ratio"
                          else f"{k.name.replace('_', ' ')}, e.g. {k.example}" if k else "")
    return labels, expect


_LABEL, _EXPECT = _labels()
