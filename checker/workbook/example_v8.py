"""A third example workbook: a 90-degree cross-plane V8 built from public service data.

``checker template --engine v8`` writes it. It exercises what only a V engine has: two rods on
each crank pin (pin, main-bearing and fillet loads from both rods, big-end loads per rod in its
own rod frame), one torsional station per throw carrying both cylinders of the pin, bank
angles in the balancing, and the counterweights of a cross-plane crank. :func:`v8_content`
reads ``templates/example_v8.toml`` (same sheets and column headers as
:func:`checker.workbook.example.example_content`); the firing and throw angles, the web
thickness, the crank masses and the counterweights are derived by
:mod:`checker.workbook.example_derived`.

Sources
-------
[GM] GM Service Manual, "Engine Mechanical Specifications", 5.7 L V8 RPO LS1 (1997-2004
    Corvette and F-car): bore 99.0-99.018 mm, stroke 92.0 mm, firing order 1-8-7-2-6-5-4-3,
    compression ratio 10.1:1, oil 5W-30, connecting rod journal diameter 53.318-53.338 mm,
    connecting rod bearing clearance (production) 0.023-0.065 mm, crankshaft (main) bearing
    clearance (production) 0.020-0.052 mm; 90-degree V, five main bearings, cast nodular iron
    crankshaft with undercut and rolled journal fillets (GM's LS1 engine description).

Everything else is assumed for a 5.7 L two-valve passenger-car V8 and marked ``ASSUMPTION`` in
the note column with a one-line reason; the data file's ``[about.assumed]`` lists them.

Layout and conventions
----------------------
* GM numbering: odd cylinders 1-3-5-7 on the left bank, even 2-4-6-8 on the right bank,
  cylinders ``2k - 1`` and ``2k`` on crank pin ``k`` (the left bank is the forward one). With the
  crank turning clockwise seen from the front, the left bank lies at +45 deg from the vertical
  in the direction of rotation and the right bank at -45 deg (sheet Cylinders, bank angle).
* Firing angles from the firing order at 90-degree intervals: 1: 0, 8: 90, 7: 180, 2: 270,
  6: 360, 5: 450, 4: 540, 3: 630 deg. Throws (workbook convention, :func:`checker.calc.
  crank_forces.throw_angles`: gamma = bank - firing, relative to throw 1): pins 1-4 at 0, 90,
  270, 180 deg, the cross-plane crank. Both cylinders of a pin give the same throw.
* Crank masses in the throw-1 frame (Y along throw 1, Z +90 deg in the direction of rotation,
  X the axial offset from the component's plane).

Counterweights (:func:`counterweights`, derived in
:func:`checker.workbook.example_derived.v8_counterweights`)
---------------------------------------
A 90-degree V8 throw carries an equivalent first-order rotating unbalance ``U = U_crank + 2 m_b r
+ m_rec r`` (webs and pin, both rods' big ends, and the primary forces of the two reciprocating
masses, which for a 90-degree V add up to a force of constant magnitude ``m_rec r omega^2``
turning with the throw; Taylor 1985, vol. 2, ch. 8). The four throws cancel as forces but leave
a rotating couple ``C = U sum z_j e_j`` of magnitude ``sqrt(10) U L`` (``L`` the throw pitch),
which counterweights must cancel. As cross-plane cranks are built, every web carries a
counterweight opposite its own throw balancing half of that web's share (``U / 4`` per web),
and the two end webs carry in addition the counterweights ``+-(C / 2) / (z_web8 - z_web1)``
that cancel the rest of the couple: the end counterweights are the heaviest and are turned
away from their own throws. The crank then leaves no first-order free force or moment.

Torsional model
---------------
Derived from the crank's geometry (sheet Crank, issue 33; docs/crank-geometry.md): each throw
station's inertia is the throw about the main axis plus both rods' rotating share and
reciprocating mean ``m_b r^2 + m_rec r^2 (1/2 + lambda^2/8)``; the stiffnesses between throws
are the halves of neighbouring throws in series, each throw's stiffness that of the assembled
crank on its main bearings (:func:`checker.calc.crank_beam.assembled_torsional_stiffness`,
issue 43), the crank nose and the flywheel flange plain shafts (sheet CrankEnds, assumed) in
series with half a throw. The rubber stiffness is Den Hartog tuned to the first mode of that
chain without the ring (365.0 Hz; 334.5 Hz with the throws alone in series before issue 43):
mu = 0.0065 kg m^2 / modal inertia at the nose = 0.117, f_ring = 365.0/(1 + mu) = 326.7 Hz,
k = J_ring (2 pi f_ring)^2 = 27.4 kN m/rad.
"""

from __future__ import annotations

from typing import Any

from . import example_derived as dv
from .example_data import about, load_example, split_tv_stations


def v8_content(split_stations: bool = False, link: float = 1e13) -> dict[str, Any]:
    """The V8 workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``.

    ``split_stations=True`` models every throw by two TV stations (one per cylinder) joined by
    a stiffness ``link`` [N m/rad] instead of one station carrying both cylinders.
    """
    content = load_example("v8")
    if not split_stations:
        return content
    cols, _rows = content["TVModel"]
    return split_tv_stations({**content, "TVModel": (cols, tv_completed(content))}, link)


def throw_unbalance() -> dict[str, float]:
    """Equivalent first-order rotating unbalance of one throw [kg m] and its parts."""
    return dv.v8_throw_unbalance(load_example("v8"))


def counterweights() -> dict[int, tuple[float, float]]:
    """Counterweight unbalance vector (Z, Y) [kg m] of webs 1..8 (module docstring)."""
    return dv.v8_counterweights(load_example("v8"))


def __getattr__(name: str) -> Any:
    """``PIN_THROW`` (crank pin -> throw angle from throw 1 [deg]) and ``ASSUMED`` (what the
    example assumes), from the data file when asked for."""
    if name == "PIN_THROW":
        return dv.v8_pin_throw(load_example("v8"))
    if name == "ASSUMED":
        return about("v8").get("assumed", {})
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["v8_content", "counterweights", "throw_unbalance"]


def tv_completed(content: dict[str, Any]) -> list[list[Any]]:
    """The TVModel rows with the values derived from sheet Crank typed in (inertia and
    stiffness cells left blank take the engine's derived values, in the sheet's units kg m^2
    and N m/rad)."""
    cols, rows = content["TVModel"]
    ix = {n: j for j, (n, _u) in enumerate(cols)}
    if not any(r[ix["inertia"]] is None or (r[ix["stiffness to next"]] is None and i < len(
            rows) - 1) for i, r in enumerate(rows)):
        return [list(r) for r in rows]
    import tempfile
    from pathlib import Path

    from ..description.engine import load_engine
    from .example import write_workbook

    units = {n: u for n, u in cols}
    assert units["inertia"] == "kg m^2" and units["stiffness to next"] == "N m/rad"
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "engine.xlsx"
        write_workbook(path, content)
        stations = {s.station: s for s in load_engine(path).tv_model}
    out = []
    for r in rows:
        s = list(r)
        st = stations[r[ix["station"]]]
        if s[ix["inertia"]] is None:
            s[ix["inertia"]] = st.inertia
        if s[ix["stiffness to next"]] is None and st.stiffness is not None:
            s[ix["stiffness to next"]] = st.stiffness
        out.append(s)
    return out
