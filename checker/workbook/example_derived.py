"""What the example workbooks derive rather than enter: throw angles, counterweight phasing,
oil-hole heights.

The data files ``templates/example_<engine>.toml`` hold every cell; the cells listed here are
computed from other cells of the same file (and from the few crank-part assumptions below) by
:func:`derived_cells`. ``scripts/make_example_derived.py`` writes them into the files, and
``tests/workbook/test_example_derived.py`` checks that the files are up to date. The I4 (Bell,
Ricardo 2013) derives nothing: its crank masses are the workshop's own numbers.

I6 (Mendes et al. 2008, see :mod:`checker.workbook.example_i6`)
    * Cylinders: throw angle = -firing angle (mod 360), the workbook convention of
      :func:`checker.calc.crank_forces.throw_angles` for an in-line engine.
    * CrankMass: two 2.2 kg webs per throw along the throw, a 1.00 kg pin, and 1.65 kg
      counterweights on throws 1, 3, 4 and 6; the counterweights next to the
      uncounterweighted throws 2 and 5 (webs 2, 5, 8, 11) are turned toward the opposite of
      that neighbour so that they balance half of it (Taylor 1985, vol. 2, ch. 8): every throw
      is balanced to the same fraction and the crank is statically and dynamically balanced.
    * Fatigue: oil-hole heights = journal radius x sin(hole angle) (pin: the Bearings sheet's
      45 deg; main: 20 deg).

Genset and marine (:mod:`checker.workbook.example_classes`)
    * As the I6 (their crank train is the I6's scaled to a 200 mm bore), the crank masses
      scaled by :data:`SCALE` (mass x SCALE^3, centre-of-mass radius x SCALE).

V8 (GM LS1, see :mod:`checker.workbook.example_v8`)
    * Cylinders: firing angles at 720/8 deg intervals from the firing order; GM numbering (odd
      cylinders on the left bank at +45 deg, even on the right at -45 deg, cylinders 2k-1 and
      2k on pin k); throw = bank - firing angle, relative to throw 1.
    * Crank (web thickness) and Fatigue (reduced thickness, 1 mm less): web thickness =
      (spacing - main length - pin length) / 2; oil-hole heights as the I6.
    * CrankMass: 1.00 kg webs along their throws, a solid nodular-iron pin, and the
      counterweights of :func:`v8_counterweights`.
"""

from __future__ import annotations

import copy
import math
from typing import Any

ASSUMPTION = "ASSUMPTION"
MAIN_OIL_HOLE_ANGLE = 20.0  # deg, main journal oil hole from the web (both examples)


# ---------------------------------------------------------------- content access
def param(content: dict[str, Any], sheet: str, name: str) -> Any:
    """Value of parameter ``name`` of parameter sheet ``sheet``."""
    for row in content[sheet]:
        if row[0] == name:
            return row[1]
    raise KeyError(f"{sheet}: no parameter {name!r}")


def _set_param(content: dict[str, Any], sheet: str, name: str, value: Any) -> None:
    rows = content[sheet]
    for i, row in enumerate(rows):
        if row[0] == name:
            rows[i] = (row[0], value, *row[2:])
            return
    raise KeyError(f"{sheet}: no parameter {name!r}")


def column(content: dict[str, Any], sheet: str, name: str) -> int:
    """Index of column ``name`` of table sheet ``sheet``."""
    return [n for n, _u in content[sheet][0]].index(name)


CRANK_OF_BEARING = {("main", "journal diameter"): "main journal diameter",
                    ("main", "journal length"): "main journal length",
                    ("big end", "journal diameter"): "pin diameter",
                    ("big end", "journal length"): "pin length"}
"""Bearings columns that sheet Crank gives (the examples type them once, there)."""


def crank(content: dict[str, Any], name: str) -> Any:
    """Value of column ``name`` of sheet Crank's ``all`` row."""
    cols, rows = content["Crank"]
    j = [n for n, _u in cols].index(name)
    return next(r[j] for r in rows if str(r[0]).lower() == "all")


def _set_crank(content: dict[str, Any], name: str, value: Any) -> None:
    cols, rows = content["Crank"]
    j = [n for n, _u in cols].index(name)
    for r in rows:
        if str(r[0]).lower() == "all":
            r[j] = value


def web_thickness(content: dict[str, Any]) -> float:
    """The web (full) thickness: sheet Crank, else the Fatigue sheet's."""
    if "Crank" in content:
        return crank(content, "web thickness")
    return param(content, "Fatigue", "Web full thickness")


def bearing(content: dict[str, Any], kind: str, name: str) -> Any:
    """Value of column ``name`` of the first bearing of type ``kind`` (``main``,
    ``big end``); a journal's diameter and length from sheet Crank where it is given."""
    if "Crank" in content and (kind, name) in CRANK_OF_BEARING:
        return crank(content, CRANK_OF_BEARING[(kind, name)])
    rows = content["Bearings"][1]
    t, j = column(content, "Bearings", "type"), column(content, "Bearings", name)
    return next(r[j] for r in rows if r[t] == kind)


def _oil_hole_heights(content: dict[str, Any]) -> None:
    pin_d = bearing(content, "big end", "journal diameter")
    pin_a = bearing(content, "big end", "oil hole angle")
    main_d = bearing(content, "main", "journal diameter")
    _set_param(content, "Fatigue", "Pin journal oil hole height",
               round(pin_d / 2 * math.sin(math.radians(pin_a)), 2))
    _set_param(content, "Fatigue", "Main journal oil hole height",
               round(main_d / 2 * math.sin(math.radians(MAIN_OIL_HOLE_ANGLE)), 2))


# ---------------------------------------------------------------- I6
I6_WEB_MASS, I6_WEB_R = 2.2, 37.7  # kg, mm: 110 x 100 x 25 mm steel arm, centre 0.55 r
I6_CW_MASS, I6_CW_R = 1.65, 58.0  # kg, mm: centre of mass 0.85 r
I6_PIN_MASS = 1.00  # kg: pi/4 x 62.97^2 x 41 mm x 7850 kg/m^3
I6_CW_THROWS = (1, 3, 4, 6)
I6_CW_SHARED = {2: 2, 5: 2, 8: 5, 11: 5}
"""Web -> uncounterweighted neighbour throw whose half its counterweight also balances."""


def i6_throw_angles(content: dict[str, Any]) -> dict[int, int]:
    """Throw angle of each cylinder [deg] from the Cylinders sheet's firing angles:
    gamma = -phi (mod 360)."""
    c, f = column(content, "Cylinders", "cylinder"), column(content, "Cylinders", "firing angle")
    return {r[c]: (-r[f]) % 360 for r in content["Cylinders"][1]}


def _zy(rho: float, gamma_deg: float) -> tuple[float, float]:
    """Crank-frame lateral and radial coordinates (Z, Y) of a point at radius ``rho`` along
    the direction ``gamma`` (from Y, in the direction of rotation)."""
    g = math.radians(gamma_deg)
    return round(rho * math.sin(g), 3) + 0.0, round(rho * math.cos(g), 3) + 0.0


def _i6_cw_direction(throws: dict[int, int], web: int, throw: int) -> float:
    """Direction [deg] of a counterweight's centre of mass: opposite its throw, or opposite
    the bisector of its throw and the uncounterweighted neighbour throw (webs 2, 5, 8, 11)."""
    g = math.radians(throws[throw])
    ex, ey = math.sin(g), math.cos(g)
    if web in I6_CW_SHARED:
        h = math.radians(throws[I6_CW_SHARED[web]])
        ex, ey = ex + math.sin(h), ey + math.cos(h)
    return (math.degrees(math.atan2(-ex, -ey))) % 360


def i6_crank_mass_rows(content: dict[str, Any]) -> list[list[Any]]:
    """CrankMass rows of the I6: webs, counterweights and pins of the six throws."""
    throws = i6_throw_angles(content)
    spacing = param(content, "Engine", "Cylinder spacing")
    main_l = bearing(content, "main", "journal length")
    web_t = web_thickness(content)
    front = main_l / 2 + web_t / 2
    rear = spacing - front
    ax_note = (ASSUMPTION + f": web centre at half main journal + half web ({main_l / 2:g} +"
               f" {web_t / 2:g} mm) from its main, pin at mid-bay")
    rows: list[list[Any]] = []
    for t in range(1, 7):
        g = throws[t]
        wz, wy = _zy(I6_WEB_R, g)
        wn = (ASSUMPTION + f": {I6_WEB_MASS} kg web arm, centre of mass {I6_WEB_R} mm along"
              f" throw {t} ({g} deg): Z = r sin, Y = r cos of the throw angle; {ax_note}")
        for web, ax in ((2 * t - 1, front), (2 * t, rear)):
            rows.append([f"Web{web}", t, "web", I6_WEB_MASS, 0, wy, wz, ax, "main axis", wn])
            if t in I6_CW_THROWS:
                d = _i6_cw_direction(throws, web, t)
                cz, cy = _zy(I6_CW_R, d)
                why = (f"turned to {d:.0f} deg so that it also balances half of the"
                       f" uncounterweighted throw {I6_CW_SHARED[web]}" if web in I6_CW_SHARED
                       else f"opposite throw {t} ({d:.0f} deg)")
                rows.append([
                    f"Web{web} c/w", t, "counterweight", I6_CW_MASS, 0, cy, cz, ax, "main axis",
                    ASSUMPTION + ": 8-counterweight crank (published inertias of throws 2 and 5"
                    f" are 0.014 kg m^2 lower); {I6_CW_MASS} kg at {I6_CW_R} mm, {why}; the"
                    f" whole crank statically and dynamically balanced; {ax_note}"])
            if web % 2:
                rows.append([f"Crankpin{t}", t, "pin", I6_PIN_MASS, 0, 0, 0, spacing / 2,
                             "pin axis", ASSUMPTION + ": solid 62.97 x 41 mm steel pin; "
                             + ax_note])
    return rows


def derived_i6(content: dict[str, Any]) -> dict[str, Any]:
    """The I6 content with its derived cells recomputed (module docstring)."""
    out = copy.deepcopy(content)
    throws = i6_throw_angles(out)
    c, t = column(out, "Cylinders", "cylinder"), column(out, "Cylinders", "throw angle")
    for r in out["Cylinders"][1]:
        r[t] = throws[r[c]]
    _oil_hole_heights(out)
    out["CrankMass"] = (out["CrankMass"][0], i6_crank_mass_rows(out))
    return out


# ---------------------------------------------------------------- V8
V8_BANK = {"odd": 45, "even": -45}  # deg from the vertical in the direction of rotation
V8_WEB_MASS, V8_WEB_R = 1.00, 23.0  # kg, mm: ~95 x 80 x 18.9 mm nodular iron, centre 0.5 r
V8_CW_R = 52.0  # mm, counterweight centre of mass radius
V8_CW_LOCAL_FRACTION = 0.5  # of each throw's equivalent unbalance, in its own two webs
V8_PIN_DENSITY = 7.1e-6  # kg/mm^3, nodular iron
V8_CYLINDERS_NOTE = (
    "GM Service Manual, LS1 5.7 L Engine Mechanical Specifications: firing order"
    " 1-8-7-2-6-5-4-3 at 90 deg; " + ASSUMPTION + ": GM numbering (odd left bank at +45 deg,"
    " even right bank at -45 deg, cylinders 2k-1 and 2k on pin k); throw = bank - firing"
    " angle, relative to throw 1")


def _deg_mod(a: float) -> float:
    return a % 360.0


def v8_cylinders(content: dict[str, Any]) -> dict[str, dict[int, float]]:
    """Firing, bank and throw angles [deg] and the crank pin of each V8 cylinder."""
    order = [int(c) for c in str(param(content, "Engine", "Firing order")).split("-")]
    n = len(order)
    firing = {c: 720 // n * k for k, c in enumerate(order)}
    bank = {c: V8_BANK["odd" if c % 2 else "even"] for c in range(1, n + 1)}
    pins = {c: (c + 1) // 2 for c in range(1, n + 1)}
    gamma = {c: _deg_mod(bank[c] - firing[c]) for c in range(1, n + 1)}
    throw = {c: _deg_mod(gamma[c] - gamma[1]) for c in range(1, n + 1)}
    return {"firing": firing, "bank": bank, "pin": pins, "throw": throw}


def v8_pin_throw(content: dict[str, Any]) -> dict[int, float]:
    """Throw angle of each crank pin from throw 1 in the direction of rotation [deg]."""
    cyl = v8_cylinders(content)
    return {cyl["pin"][c]: cyl["throw"][c] for c in cyl["pin"]}


def _v8_geometry(content: dict[str, Any]) -> dict[str, float]:
    spacing = param(content, "Engine", "Cylinder spacing")
    main_l = bearing(content, "main", "journal length")
    pin_l = bearing(content, "big end", "journal length")
    pin_d = bearing(content, "big end", "journal diameter")
    web_t = round((spacing - main_l - pin_l) / 2, 2)
    rod_m = param(content, "Engine", "Connecting rod mass")
    rod_com = param(content, "Engine", "Rod centre of mass from big end")
    rod_l = param(content, "Engine", "Connecting rod length")
    front = main_l / 2 + web_t / 2
    return {
        "spacing": spacing, "main_l": main_l, "pin_l": pin_l, "pin_d": pin_d, "web_t": web_t,
        "front": front, "rear": spacing - front,
        "crank_r": param(content, "Engine", "Stroke") / 2,
        "pin_mass": round(math.pi / 4 * pin_d**2 * pin_l * V8_PIN_DENSITY, 3),
        "m_rec": param(content, "Engine", "Piston assembly mass") + rod_m * rod_com / rod_l,
        "m_big": rod_m - rod_m * rod_com / rod_l,
    }


def _e(deg: float) -> tuple[float, float]:
    """Unit vector (Z, Y) of a direction ``deg`` from throw 1 in the direction of rotation."""
    g = math.radians(deg)
    return math.sin(g), math.cos(g)


def v8_throw_unbalance(content: dict[str, Any]) -> dict[str, float]:
    """Equivalent first-order rotating unbalance of one V8 throw [kg m] and its parts: webs
    and pin, both rods' big ends, and the two reciprocating masses, whose primary forces add
    up to a force of constant magnitude m_rec r omega^2 turning with the throw in a 90-degree
    V (Taylor 1985, vol. 2, ch. 8)."""
    g = _v8_geometry(content)
    crank = (2 * V8_WEB_MASS * V8_WEB_R + g["pin_mass"] * g["crank_r"]) * 1e-3
    rods = 2 * g["m_big"] * g["crank_r"] * 1e-3
    recip = g["m_rec"] * g["crank_r"] * 1e-3
    return {"crank": crank, "rods": rods, "reciprocating": recip, "total": crank + rods + recip}


def v8_counterweights(content: dict[str, Any]) -> dict[int, tuple[float, float]]:
    """Counterweight unbalance vector (Z, Y) [kg m] of webs 1..8.

    The four throws of a cross-plane crank cancel as forces but leave a rotating couple
    ``C = U sum z_j e_j`` of magnitude ``sqrt(10) U L`` (``U`` the throw's equivalent
    unbalance, ``L`` the throw pitch). Every web carries a counterweight opposite its own
    throw balancing half of that web's share (``U / 4``), and the two end webs in addition
    ``+-(C / 2) / (z_web8 - z_web1)``, which cancel the rest of the couple: the crank leaves
    no first-order free force or moment.
    """
    g = _v8_geometry(content)
    pin_throw = v8_pin_throw(content)
    u = v8_throw_unbalance(content)["total"]
    local = V8_CW_LOCAL_FRACTION * u / 2
    z_pin = {j: (j - 0.5) * g["spacing"] * 1e-3 for j in range(1, 5)}
    cz = sum(z_pin[j] * u * _e(pin_throw[j])[0] for j in range(1, 5))
    cy = sum(z_pin[j] * u * _e(pin_throw[j])[1] for j in range(1, 5))
    z1 = g["front"] * 1e-3
    z8 = (3 * g["spacing"] + g["rear"]) * 1e-3
    rest = 1.0 - V8_CW_LOCAL_FRACTION
    e_rear = (-rest * cz / (z8 - z1), -rest * cy / (z8 - z1))
    out = {}
    for web in range(1, 9):
        j = (web + 1) // 2
        ez, ey = _e(pin_throw[j])
        vz, vy = -local * ez, -local * ey
        if web == 1:
            vz, vy = vz - e_rear[0], vy - e_rear[1]
        elif web == 8:
            vz, vy = vz + e_rear[0], vy + e_rear[1]
        out[web] = (vz, vy)
    return out


def _mzy(vec: tuple[float, float], radius: float) -> tuple[float, float, float]:
    """(mass [kg], Z [mm], Y [mm]) of a counterweight of unbalance ``vec`` [kg m]."""
    u = math.hypot(*vec)
    return (round(u / (radius * 1e-3), 4), round(radius * vec[0] / u, 3) + 0.0,
            round(radius * vec[1] / u, 3) + 0.0)


def v8_crank_mass_rows(content: dict[str, Any]) -> list[list[Any]]:
    """CrankMass rows of the V8: webs, counterweights and pins of the four throws."""
    g = _v8_geometry(content)
    pin_throw = v8_pin_throw(content)
    cws = v8_counterweights(content)
    ax_note = (f"web centre at half main journal + half web ({g['main_l'] / 2:g} +"
               f" {g['web_t'] / 2:g} mm) from its main, pin at mid-bay")
    rows: list[list[Any]] = []
    for j in range(1, 5):
        th = pin_throw[j]
        ez, ey = _e(th)
        wz, wy = round(V8_WEB_R * ez, 3) + 0.0, round(V8_WEB_R * ey, 3) + 0.0
        web_note = (ASSUMPTION + f": {V8_WEB_MASS:g} kg nodular iron web arm, centre of mass"
                    f" {V8_WEB_R:g} mm along throw {j} ({th:g} deg from throw 1); {ax_note}")
        for web, ax in ((2 * j - 1, g["front"]), (2 * j, g["rear"])):
            rows.append([f"Web{web}", j, "web", V8_WEB_MASS, 0, wy, wz, round(ax, 2),
                         "main axis", web_note])
            m, cz, cy = _mzy(cws[web], V8_CW_R)
            d = math.degrees(math.atan2(cz, cy)) % 360
            what = ("end counterweight: half of the throw's share plus the share of the"
                    " cross-plane couple, turned away from the throw" if web in (1, 8)
                    else "opposite the throw, half of the web's share of the throw's"
                    " equivalent unbalance")
            rows.append([f"Web{web} c/w", j, "counterweight", m, 0, cy, cz, round(ax, 2),
                         "main axis", ASSUMPTION + f": 8-counterweight cross-plane crank,"
                         f" centre of mass at {V8_CW_R:g} mm, {d:.1f} deg from throw 1; {what};"
                         f" crank free of 1st-order force and moment; {ax_note}"])
            if web % 2:
                rows.append([f"Crankpin{j}", j, "pin", g["pin_mass"], 0, 0, 0,
                             g["spacing"] / 2, "pin axis",
                             ASSUMPTION + f": solid {g['pin_d']} x {g['pin_l']:g} mm nodular"
                             f" iron pin; {ax_note}"])
    return rows


def derived_v8(content: dict[str, Any]) -> dict[str, Any]:
    """The V8 content with its derived cells recomputed (module docstring)."""
    out = copy.deepcopy(content)
    cyl = v8_cylinders(out)
    cols = out["Cylinders"][0]
    out["Cylinders"] = (cols, [
        [c, cyl["throw"][c], cyl["firing"][c], cyl["bank"][c], cyl["pin"][c], V8_CYLINDERS_NOTE]
        for c in sorted(cyl["pin"])])
    web_t = _v8_geometry(out)["web_t"]
    if "Crank" in out:
        _set_crank(out, "web thickness", web_t)
    else:
        _set_param(out, "Fatigue", "Web full thickness", web_t)
    _set_param(out, "Fatigue", "Web reduced thickness", web_t - 1.0)
    _oil_hole_heights(out)
    out["CrankMass"] = (out["CrankMass"][0], v8_crank_mass_rows(out))
    return out


SCALE = 1.97
"""Geometric similarity factor of the genset and marine examples' crank train to the I6's
(:mod:`checker.workbook.example_classes`)."""


def derived_scaled_i6(content: dict[str, Any]) -> dict[str, Any]:
    """The genset and marine examples (an I6 crank train scaled to the 200 mm bore): the I6's
    derived cells, its crank masses scaled by :data:`SCALE` (mass x SCALE^3, radius x SCALE)."""
    out = derived_i6(content)
    cols, rows = out["CrankMass"]
    for r in rows:
        r[3] = float(f"{r[3] * SCALE**3:.4g}")
        r[5], r[6] = (float(f"{v * SCALE:.4g}") for v in (r[5], r[6]))
        r[9] = (ASSUMPTION + f": the I6 example's crank mass scaled by geometric similarity"
                f" (mass x {SCALE:g}^3, radius x {SCALE:g}); " + r[9])
    return out


DERIVED = {"i6": derived_i6, "v8": derived_v8, "genset": derived_scaled_i6,
           "marine": derived_scaled_i6}
"""Engine -> the function recomputing its derived cells (the I4 derives nothing)."""


def derived_cells(engine: str, content: dict[str, Any]) -> dict[str, Any]:
    """``content`` of example ``engine`` with its derived cells recomputed."""
    f = DERIVED.get(engine)
    return copy.deepcopy(content) if f is None else f(content)
