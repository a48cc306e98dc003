"""What the engine builder derives from the crank's geometry (sheets Crank, CrankEnds).

One source per fact (issue 33): the Bearings and Fatigue sheets take the crank's dimensions
from sheet Crank (a cell given in both must agree: otherwise an error naming both cells);
blank cells of TVModel (station inertias, stiffnesses) and throws without CrankMass rows take
values derived from the geometry, a typed value winning. Every derived or typed value of the
crank model is recorded as a :class:`ModelValue` with its origin and method, for the report
and the JSON.

Conventions (docs/crank-geometry.md):

* station inertia of a cylinder station = the crank throw about the main axis (between its
  journal mid-planes, :func:`checker.calc.crank_geometry.throw_mass_properties`) + per
  cylinder on it the con-rod's rotating share ``m_rot R^2`` and the reciprocating mean
  ``m_osc R^2 (1/2 + lambda^2/8)`` (``m_rot = m_rod (1 - a/l)``, ``m_osc`` = piston + ``m_rod a /
  l``, ``a`` the rod's centre of mass from the big end, ``lambda = R / l``; the mean over a
  revolution of the slider-crank's equivalent inertia, Ker Wilson, Practical Solution of
  Torsional Vibration Problems, vol. 1, 1956, ch. 3; Bell, Ricardo 2013: constant inertia
  applied at each crank pin);
* a throw's stiffness in the assembled crank on its main bearings
  (:func:`checker.calc.crank_beam.assembled_torsional_stiffness`: the crank's 3D frame with
  each throw's torsion calibrated to its stiffness alone, :mod:`checker.calc.throw_stiffness`;
  issue 43) is split into two equal halves at the pin's mid-plane, where the cylinder station
  sits: between neighbouring cylinder stations ``1/k = 1/(2 k_a) + 1/(2 k_b)``; crank nose to
  cylinder 1 adds the nose shaft and the front half of main journal 1 (plain shafts,
  ``G Jp / L``); the last cylinder to the flywheel adds the rear half journal and the flywheel
  flange.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .crank_input import CrankGeometry

Err = Callable[[str, str, int | None, str], None]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class ModelValue:
    """One value of the model the analyses use, with where it came from.

    ``origin`` is ``"typed"`` (the workbook's cell wins) or ``"derived"`` (from the crank's
    geometry); ``derived`` is the geometry's value also where a typed one wins (``None`` where
    it cannot be derived); ``method`` names how it was derived.
    """

    sheet: str
    item: str
    attr: str
    value: float
    origin: str
    derived: float | None
    method: str
    cell: str

    def as_dict(self) -> dict[str, Any]:
        return {"sheet": self.sheet, "item": self.item, "attr": self.attr,
                "value": float(f"{self.value:.6g}"), "origin": self.origin,
                "derived": None if self.derived is None else float(f"{self.derived:.6g}"),
                "method": self.method, "cell": self.cell}


def _same(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-9 * max(abs(a), abs(b), 1e-12)


def _mm(v: float) -> str:
    return f"{v * 1e3:.6g} mm"


# ------------------------------------------------------------------------------ Bearings
def _from_crank(attr: str) -> str:
    """The method of a dimension taken from sheet Crank: its column there."""
    from .crank_input import _LABEL

    return f"sheet Crank's {_LABEL.get(attr, attr.replace('_', ' '))}"


def bearings_from_crank(rows: list[dict[str, Any]], crank: CrankGeometry,
                        pin_of_cylinder: dict[int, int], where: dict[tuple, str],
                        err: Err) -> list[ModelValue]:
    """Fill the Bearings rows' journal diameter and length (and big-end oil hole diameter)
    from the crank, in place; a typed value that differs is an error naming both cells.
    Returns each such value of the model, typed (checked against the crank) or derived."""
    n = len(crank.throws)
    model: list[ModelValue] = []
    counts = {"main": 0, "big end": 0}
    for i, r in enumerate(rows):
        kind = r.get("type")
        if kind not in counts:
            continue
        counts[kind] += 1
        k = counts[kind]
        if kind == "main":
            t = crank.throws[min(k, n) - 1]
            pairs = (("diameter", "journal_diameter"), ("journal_length", "journal_length"))
        else:
            pin = pin_of_cylinder.get(k, k)
            if not 1 <= pin <= n:
                continue
            t = crank.throws[pin - 1]
            pairs = (("diameter", "pin_diameter"), ("journal_length", "pin_length"))
            if (r.get("oil_holes") or 0) > 0 and t.pin_oil_hole_diameter is not None:
                pairs += (("oil_hole_diameter", "pin_oil_hole_diameter"),)
        for battr, cattr in pairs:
            value = getattr(t, cattr)
            typed = r.get(battr)
            if typed is None:
                r[battr] = value
            elif not _same(typed, value):
                err("Bearings", battr, i, f"{_mm(typed)} differs from the crank's"
                    f" {_mm(value)} ({crank.cell(cattr, t.number)}): the dimension is given"
                    " twice; leave this cell blank (it is taken from sheet Crank) or make them"
                    " equal")
                continue
            model.append(ModelValue(
                "Bearings", str(r.get("name") or f"row {i + 1}"), battr,
                float(typed if typed is not None else value),
                "typed" if typed is not None else "derived", float(value),
                _from_crank(cattr) + (" (the cylinder's crank pin)" if kind != "main" else ""),
                where.get(("Bearings", i, battr), "Bearings") if typed is not None
                else crank.cell(cattr, t.number)))
    return model


# ------------------------------------------------------------------------------- Fatigue
FATIGUE_SAME = {
    "web_full_thickness": "web_thickness", "pin_fillet_radius": "pin_fillet_radius",
    "pin_fillet_undercut": "pin_fillet_undercut",
    "pin_fillet_web_undercut": "pin_fillet_web_undercut",
    "main_fillet_radius": "main_fillet_radius", "main_fillet_undercut": "main_fillet_undercut",
    "main_fillet_web_undercut": "main_fillet_web_undercut",
    "pin_oil_hole_diameter": "pin_oil_hole_diameter",
    "main_oil_hole_diameter": "main_oil_hole_diameter", "pin_bore": "pin_bore",
    "main_bore": "journal_bore",
}
"""Fatigue parameter -> the same dimension on sheet Crank."""
FATIGUE_ENDS: dict[str, str] = {}
"""(The Fatigue sheet's crank nose diameter is the smallest section at the critical fillet,
another section than the nose shaft of sheet CrankEnds: not the same dimension.)"""


def fatigue_from_crank(fatigue: dict[str, Any], crank: CrankGeometry, err: Err,
                       where: dict[tuple, str], filled: dict[tuple, str]
                       ) -> tuple[dict[str, Any], list[ModelValue]]:
    """The Fatigue parameters with the crank's dimensions (the smallest over the throws where
    they differ, conservative) and the derived M53 web geometry; the values' origins.
    ``filled`` receives the Crank cell of each Fatigue parameter taken from the crank."""
    from ..calc.crank_geometry import web_width_at_pin_centre

    out = dict(fatigue)
    model: list[ModelValue] = []
    for fattr, cattr in {**FATIGUE_SAME, **FATIGUE_ENDS}.items():
        if fattr in FATIGUE_ENDS:
            value = getattr(crank, cattr)
            cell = crank.cell(cattr)
            if value is None or (cattr == "nose_bore" and crank.nose_diameter is None):
                continue
        else:
            vals = [getattr(t, cattr) for t in crank.throws]
            if any(v is None for v in vals):
                continue
            value = min(vals)
            cell = crank.cell(cattr, 1 + int(np.argmin(vals)))
        typed = fatigue.get(fattr)
        if typed is None:
            out[fattr] = value
            filled[("Fatigue", fattr)] = cell
        elif not _same(typed, value):
            err("Fatigue", fattr, None, f"{_mm(typed)} differs from the crank's {_mm(value)}"
                f" ({cell}): the dimension is given twice; leave this cell blank (it is taken"
                " from the crank) or make them equal")
            continue
        model.append(ModelValue(
            "Fatigue", "crank", fattr, float(typed if typed is not None else value),
            "typed" if typed is not None else "derived", float(value),
            _from_crank(cattr) + (", the smallest over the throws" if len(crank.throws) > 1
                                  else "")
            + (" (blank there: 0, solid)" if cattr.endswith("bore") and cell == "Crank"
               else ""),
            where.get(("Fatigue", fattr), "Fatigue") if typed is not None else cell))
    # derived M53 web geometry (a typed value wins)
    t0 = min(crank.throws, key=lambda t: t.web_thickness)
    lands = [fatigue.get(a) for a in ("pin_land_thickness", "main_land_thickness")]
    reduced = t0.web_thickness - sum(v for v in lands if v is not None)
    w_pin = min(float(web_width_at_pin_centre(
        width_journal=t.web_width_journal, width_pin=t.web_width_pin,
        crank_radius=crank.crank_radius)) for t in crank.throws)
    w_max = max(max(t.web_width_journal, t.web_width_pin) for t in crank.throws)
    derived = (
        ("web_thickness", reduced, "web thickness less the pin and main journal land"
         " thicknesses (Fatigue), the thinnest throw"),
        ("web_min_width", w_pin, "width of the web outline across the crank-pin centre (IACS"
         " UR M53 W), the narrowest throw"),
        ("web_max_width", w_max, "largest width of the web outline (the larger of its two"
         " circles)"),
    )
    for attr, value, method in derived:
        typed = fatigue.get(attr)
        if typed is None:
            out[attr] = value
        model.append(ModelValue("Fatigue", "crank", attr, float(typed if typed is not None
                                                                 else value),
                                "typed" if typed is not None else "derived", float(value),
                                method, where.get(("Fatigue", attr), "Fatigue")
                                if typed is not None else crank.cell("web_thickness")))
    return out, model


# ----------------------------------------------------------------------------- CrankMass
def crank_mass_rows(crank: CrankGeometry, throw_angle: dict[int, float],
                    typed_throws: set[int]) -> list[dict[str, Any]]:
    """CrankMass rows (SI, as the sheet's columns) of the throws without typed rows, and the
    pulley and flywheel unbalances.

    Webs and counterweights relative to the main axis at their mass centre's radius along
    their throw, expressed in the throw-1 frame (``Z = rho sin gamma``, ``Y = rho cos gamma``,
    ``gamma`` the throw angle from throw 1 in the direction of rotation); the pin on its axis;
    axial position = the part's mass centre from the bay's front main journal mid-plane.
    Journals (mass centre on the main axis) add no unbalance and are left out.
    """
    mp = crank.mass_properties
    rows: list[dict[str, Any]] = []
    for j in range(1, len(crank.throws) + 1):
        if j in typed_throws:
            continue
        g = throw_angle.get(j, 0.0)
        for k, (name, kind) in enumerate((
                ("front journal", None), (f"throw {j} front web", "web"),
                (f"throw {j} front counterweight", "counterweight"),
                (f"throw {j} pin", "pin"), (f"throw {j} rear web", "web"),
                (f"throw {j} rear counterweight", "counterweight"), ("rear journal", None))):
            m = float(mp.mass[j - 1, k])
            if kind is None or m <= 0.0:
                continue
            rho = float(mp.y[j - 1, k])
            if kind == "pin":
                rows.append(dict(location=name, throw=j, kind=kind, mass=m, x=0.0, y=0.0,
                                 z=0.0, axial=float(mp.z[j - 1, k]), reference="pin axis"))
            else:
                rows.append(dict(location=name, throw=j, kind=kind, mass=m, x=0.0,
                                 y=rho * math.cos(g), z=rho * math.sin(g),
                                 axial=float(mp.z[j - 1, k]), reference="main axis"))
    r = crank.crank_radius
    n = len(crank.throws)
    for name, u, angle, throw, axial in (
            ("pulley unbalance", crank.pulley_unbalance, crank.pulley_angle, 1,
             -crank.pulley_distance),
            ("flywheel unbalance", crank.flywheel_unbalance, crank.flywheel_angle, n,
             crank.throws[-1].length + crank.flywheel_distance)):
        if u > 0.0:
            # the unbalance as a mass u / R at the crank radius (only m rho enters)
            rows.append(dict(location=name, throw=throw, kind="unbalance", mass=u / r, x=0.0,
                             y=r * math.cos(angle), z=r * math.sin(angle), axial=axial,
                             reference="main axis"))
    return rows


# ------------------------------------------------------------------------------- TVModel
def rod_inertia_share(params: dict[str, Any]) -> tuple[float, str] | None:
    """Per cylinder: the con-rod's rotating share plus the reciprocating mean inertia
    [kg m^2], ``m_rot R^2 + m_osc R^2 (1/2 + lambda^2/8)``, and its text; None without the
    Engine sheet's masses."""
    need = ("rod_mass", "rod_com", "rod_length", "piston_mass", "stroke")
    if any(params.get(n) is None for n in need):
        return None
    r = params["stroke"] / 2.0
    ln = params["rod_length"]
    m_rot = params["rod_mass"] * (1.0 - params["rod_com"] / ln)
    m_osc = params["piston_mass"] + params["rod_mass"] * params["rod_com"] / ln
    lam = r / ln
    j = m_rot * r**2 + m_osc * r**2 * (0.5 + lam**2 / 8.0)
    return j, (f"con-rod rotating share {m_rot:.4g} kg x R^2 + reciprocating mean"
               f" {m_osc:.4g} kg x R^2 (1/2 + lambda^2/8)")


@dataclass(frozen=True)
class ThrowStiffnessInfo:
    """Each throw's stiffness between its journal mid-planes [N m/rad] (NaN: not available),
    whether each lies in the fast model's fitted range, the method and its stated error;
    ``assembled``: each throw's stiffness in the assembled crank on its main bearings (the
    torsional model's; NaN where not available) and how it was found."""

    stiffness: np.ndarray
    in_range: np.ndarray
    method: str
    model_error: float | None
    missing: str = ""
    outside: tuple[str, ...] = ()  # per throw: the model's groups outside the range ("" in)
    assembled: np.ndarray | None = None
    assembled_method: str = ""

    @property
    def for_model(self) -> np.ndarray:
        """The stiffness the torsional model uses: the assembled crank's where known."""
        return self.stiffness if self.assembled is None else self.assembled


def throw_stiffness(crank: CrankGeometry, throw_angle: dict[int, float] | None = None
                    ) -> ThrowStiffnessInfo:
    """The throws' torsional stiffness from :mod:`checker.calc.throw_stiffness` (issue 33,
    item 4); NaN with the reason when that model is not available. With the throws' angles
    (``throw_angle``: pin -> angle from throw 1 [rad]) also each throw's stiffness in the
    assembled crank on its main bearings (:func:`assembled_stiffness`, issue 43)."""
    n = len(crank.throws)
    try:
        from ..calc.throw_stiffness import throw_torsional_stiffness
    except ImportError:
        return ThrowStiffnessInfo(np.full(n, np.nan), np.zeros(n, bool), "", None,
                                  "the throw stiffness model (checker.calc.throw_stiffness)"
                                  " is not installed")
    res = throw_torsional_stiffness(
        journal_diameter=np.array(crank.column("journal_diameter")),
        journal_bore=np.array(crank.column("journal_bore")),
        journal_length=np.array(crank.column("journal_length")),
        pin_diameter=np.array(crank.column("pin_diameter")),
        pin_bore=np.array(crank.column("pin_bore")),
        pin_length=np.array(crank.column("pin_length")),
        web_thickness=np.array(crank.column("web_thickness")),
        web_width_journal=np.array(crank.column("web_width_journal")),
        web_width_pin=np.array(crank.column("web_width_pin")),
        crank_radius=crank.crank_radius, youngs_modulus=crank.youngs_modulus,
        poisson_ratio=crank.poisson_ratio,
        cw_inner_radius=np.array(crank.column("cw_inner_radius")),
        cw_outer_radius=np.array(crank.column("cw_outer_radius")),
        cw_angle=np.array(crank.column("cw_angle")),
        cw_thickness=np.array([(t.cw_thickness or t.web_thickness) if t.has_counterweight
                               else 0.0 for t in crank.throws]))  # 0: no counterweight
    single = np.asarray(res.stiffness, dtype=float)
    assembled, how = (None, "") if throw_angle is None else assembled_stiffness(
        crank, throw_angle, single)
    return ThrowStiffnessInfo(single, np.asarray(res.in_range, dtype=bool), str(res.method),
                              None if res.model_error is None else float(res.model_error),
                              outside=tuple(res.outside), assembled=assembled,
                              assembled_method=how)


def assembled_stiffness(crank: CrankGeometry, throw_angle: dict[int, float],
                        single: np.ndarray) -> tuple[np.ndarray, str]:
    """Each throw's torsional stiffness in the assembled crank on rigid main bearings [N m/rad]
    and its method: the crank's 3D frame (:func:`checker.calc.crank_beam.crank_frame`, mains
    at the throws' lengths) with each throw's web in-plane stiffness calibrated to its
    stiffness alone (``single``), a torque passed through it
    (:func:`checker.calc.crank_beam.assembled_torsional_stiffness`). Where the frame cannot
    be calibrated (a throw far outside the stiffness model's range) the throws in series
    (``single``) with the reason in the method."""
    throws = crank.throws
    if not np.all(np.isfinite(single)):
        return single, ""
    key = (tuple((t.length, t.journal_length, t.web_thickness, t.journal_diameter,
                  t.journal_bore, t.pin_diameter, t.pin_bore, t.web_width_journal,
                  t.web_width_pin, float(throw_angle.get(t.number, 0.0))) for t in throws),
           crank.crank_radius, crank.youngs_modulus, crank.poisson_ratio,
           tuple(float(k) for k in single))
    k, how = _assembled(key)
    return np.array(k), how


@functools.lru_cache(maxsize=16)
def _assembled(key: tuple) -> tuple[tuple[float, ...], str]:
    """:func:`assembled_stiffness` of one crank (its values as a key: the engine's build and
    the crank module ask for the same crank)."""
    from ..calc import crank_beam as cb

    throws, radius, youngs, poisson, single = key
    t = np.array(throws)  # columns as in the key
    try:
        lengths, lj, tw = t[:, 0], t[:, 1], t[:, 2]
        main_z = np.concatenate([[0.0], np.cumsum(lengths)])
        web_z = np.column_stack([main_z[:-1] + lj / 2 + tw / 2, main_z[1:] - lj / 2 - tw / 2])
        frame = cb.crank_frame(
            main_z=main_z, web_z=web_z,
            pin_load_z=[[z] for z in (main_z[:-1] + main_z[1:]) / 2], throw_angle=t[:, 9],
            crank_radius=radius, journal_diameter=t[:, 3], journal_bore=t[:, 4],
            pin_diameter=t[:, 5], pin_bore=t[:, 6], web_thickness=tw,
            web_width=(t[:, 7] + t[:, 8]) / 2.0, youngs_modulus=youngs,
            poisson_ratio=poisson, support_stiffness=np.inf,
            throw_torsional_stiffness=np.array(single))
        k = cb.assembled_torsional_stiffness(frame)
    except ValueError as exc:
        return single, (f"throws in series (the assembled crank's frame could not be"
                        f" calibrated: {exc})")
    return tuple(float(v) for v in k), (
        "assembled crank on its main bearings: 3D frame of the crank with each throw's"
        " torsion calibrated to its stiffness alone, a torque passed through it (verified"
        " against a 3D FE of 2- to 4-throw pieces of the I4 and I6 within 1 %)")


def _methods(stiff: ThrowStiffnessInfo) -> str:
    """The throw stiffness's method, and the assembled crank's where it is used."""
    if not stiff.assembled_method:
        return stiff.method
    return f"{stiff.assembled_method}; each throw alone: {stiff.method}"


def outside_text(stiff: ThrowStiffnessInfo, throws: list[int]) -> str:
    """The stiffness model's groups outside its fitted range for throws (1-based), once
    each: ``throw 2: Dp/Dj 0.741 (fitted 0.75..1)``; the groups alone when all throws
    share them."""
    texts = {t: stiff.outside[t - 1] for t in sorted(set(throws))
             if t - 1 < len(stiff.outside) and stiff.outside[t - 1]}
    if not texts:
        return "outside the samples"
    if len(set(texts.values())) == 1:
        return next(iter(texts.values()))
    return "; ".join(f"throw {t}: {g}" for t, g in texts.items())


def _shaft_compliance(d: float, bore: float, length: float, g: float) -> float:
    return length / (g * math.pi * (d**4 - bore**4) / 32.0)


def tv_from_crank(rows: list[dict[str, Any]], crank: CrankGeometry, params: dict[str, Any],
                  pin_of_cylinder: dict[int, int], where: dict[tuple, str], err: Err,
                  stiff: ThrowStiffnessInfo, warn: Err | None = None,
                  viscous_ring: bool = False) -> list[ModelValue]:
    """Fill the TVModel rows' blank inertias of cylinder stations and blank stiffnesses
    between crank stations from the geometry (in place); every value's origin. A derived
    stiffness that uses a throw outside the stiffness model's fitted range is a warning
    (``warn``) at its cell. ``viscous_ring``: the damper is viscous, its ring row has no
    stiffness to the next station (the silicone couples it)."""
    model: list[ModelValue] = []
    mp = crank.mass_properties
    share = rod_inertia_share(params)
    g = crank.shear_modulus
    k = stiff.for_model
    n = len(crank.throws)

    def pin_of(r: dict[str, Any]) -> int | None:
        pins = {pin_of_cylinder.get(c, c) for c in (r.get("cylinder") or ())}
        return pins.pop() if r.get("role") == "cylinder" and len(pins) == 1 else None

    complete = [r for r in rows if r.get("station") is not None and r.get("role") is not None]
    for i, r in enumerate(rows):
        if r not in complete:
            continue
        pin = pin_of(r)
        # station inertia
        derived = method = None
        if pin is not None and 1 <= pin <= n and share is not None:
            n_cyl = len(r.get("cylinder") or ())
            derived = float(mp.inertia_total[pin - 1]) + n_cyl * share[0]
            method = (f"crank throw {pin} about the main axis {mp.inertia_total[pin - 1]:.5g}"
                      f" kg m^2 (geometry) + {n_cyl} x ({share[1]})")
        typed = r.get("inertia")
        if typed is None and derived is not None:
            r["inertia"] = derived
        if typed is None and derived is None:
            err("TVModel", "inertia", i, "inertia is required: expected an inertia, e.g. kg"
                " m^2 (derived from sheet Crank only for a cylinder station whose cylinders"
                " share one crank pin, with the Engine sheet's rod and piston masses)")
            continue
        if derived is not None or r.get("role") == "cylinder":
            model.append(ModelValue("TVModel", str(r["station"]), "inertia",
                                    float(r["inertia"]), "typed" if typed is not None
                                    else "derived", derived, method or "",
                                    where.get(("TVModel", i, "inertia"), "TVModel")))
    for i, r in enumerate(rows):
        if r not in complete or i == len(rows) - 1:
            continue
        if viscous_ring and r.get("role") == "damper ring":
            continue
        if r.get("element") == "flexible coupling":  # the catalogue's (sheet Coupling)
            continue
        nxt = rows[i + 1]
        a, b = pin_of(r), pin_of(nxt)
        derived = method = None
        why = ""
        if a is not None and b is not None and abs(a - b) == 1 and max(a, b) <= n:
            lo, hi = min(a, b), max(a, b)
            if np.isfinite(k[lo - 1]) and np.isfinite(k[hi - 1]):
                derived = 1.0 / (1.0 / (2 * k[lo - 1]) + 1.0 / (2 * k[hi - 1]))
                method = f"halves of throws {lo} and {hi} in series ({_methods(stiff)})"
            else:
                why = stiff.missing
        elif r.get("role") == "crank nose" and b == 1 or (
                a == n and nxt.get("role") == "flywheel"):
            end = "nose" if b == 1 else "flange"
            t = crank.throws[0 if end == "nose" else -1]
            dia = crank.nose_diameter if end == "nose" else crank.flange_diameter
            bore = crank.nose_bore if end == "nose" else crank.flange_bore
            ln = crank.nose_length if end == "nose" else crank.flange_length
            half = t.journal_length / 2.0
            kt = k[t.number - 1]
            if dia is None or ln is None:
                why = (f"CrankEnds: the {'crank nose' if end == 'nose' else 'flywheel flange'}"
                       " diameter and length")
            elif ln <= half:
                err("CrankEnds", f"{end}_length", None, f"the length {_mm(ln)} is measured"
                    " to the main journal's mid-plane: it must exceed half the journal length"
                    f" ({_mm(half)})")
                continue
            elif not np.isfinite(kt):
                why = stiff.missing
            else:
                c = (_shaft_compliance(dia, bore, ln - half, g)
                     + _shaft_compliance(t.journal_diameter, t.journal_bore, half, g)
                     + 1.0 / (2.0 * kt))
                derived = 1.0 / c
                method = (f"{'nose' if end == 'nose' else 'flange'} shaft and half main"
                          f" journal (G Jp / L) in series with half of throw {t.number}"
                          f" ({_methods(stiff)})")
        typed = r.get("stiffness")
        if typed is None and derived is not None:
            r["stiffness"] = derived
            used = [t for t in ((a, b) if a is not None and b is not None else (a or b,))
                    if t is not None and 1 <= t <= n and not stiff.in_range[t - 1]]
            if used and warn is not None:
                err_text = ("" if stiff.model_error is None
                            else f"; stated error {stiff.model_error * 100:.1f} % inside it")
                warn("TVModel", "stiffness", i, "stiffness derived from throw"
                     f" {', '.join(map(str, sorted(set(used))))} outside the fitted range of"
                     f" the throw stiffness model ({outside_text(stiff, used)}{err_text}):"
                     " the value is extrapolated; check it or type the stiffness")
        if typed is None and derived is None:
            err("TVModel", "stiffness", i, "stiffness to the next station is required for"
                " every station but the last (expected a torsional stiffness, e.g. N m/rad;"
                " derived from sheet Crank only between neighbouring crank-pin stations, from"
                " the crank nose to cylinder 1 and from the last cylinder to the flywheel"
                + (f"; missing: {why}" if why else "") + ")")
            continue
        if derived is not None or why:
            model.append(ModelValue("TVModel", str(r["station"]), "stiffness",
                                    float(r["stiffness"]), "typed" if typed is not None
                                    else "derived", derived, method or why,
                                    where.get(("TVModel", i, "stiffness"), "TVModel")))
    return model
