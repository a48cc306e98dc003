"""Graph calculation: the crank's throws as its geometry gives them (sheet Crank).

Always the values derived from the geometry, also where typed TVModel or CrankMass values win
in the analyses (issue 33): ``crank.throw_mass`` and ``crank.throw_inertia`` (the crank alone
between its journal mid-planes, :func:`checker.calc.crank_geometry.throw_mass_properties`)
and ``crank.throw_stiffness`` (between the journal mid-planes, one face held, the other turned
about the crank axis, axial motion free: :mod:`checker.calc.throw_stiffness`), and
``crank.assembled_stiffness``: each throw's stiffness in the assembled crank on its main
bearings, the torsional model's (issue 43,
:func:`checker.calc.crank_beam.assembled_torsional_stiffness`). The detail
lists every value of the crank model the analyses use with its origin (typed or derived) and
method (:class:`checker.description.crank_derive.ModelValue`). Runs only for a workbook with sheet
Crank.
"""

from __future__ import annotations

import numpy as np

from ..calc.crank_geometry import PARTS
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.crank import CrankDetail

THROW_MASS = quantity(QuantitySpec(
    "crank.throw_mass", "kg", ("item",),
    "Mass of each crank throw between its journal mid-planes (crank alone), from its geometry",
    "kg", detail=CrankDetail))
THROW_INERTIA = quantity(QuantitySpec(
    "crank.throw_inertia", "kg*m**2", ("item",),
    "Polar moment of inertia of each crank throw about the main axis (crank alone, between its"
    " journal mid-planes), from its geometry", "kg*m**2", detail=CrankDetail))
THROW_STIFFNESS = quantity(QuantitySpec(
    "crank.throw_stiffness", "N*m/rad", ("item",),
    "Torsional stiffness of each crank throw between its journal mid-planes (axial motion of"
    " the faces free), from its geometry", "N*m/rad", detail=CrankDetail))

ASSEMBLED_STIFFNESS = quantity(QuantitySpec(
    "crank.assembled_stiffness", "N*m/rad", ("item",),
    "Torsional stiffness of each crank throw in the assembled crank on its main bearings"
    " (the torsional model's: stiffer than the throw alone where neighbouring throws are not"
    " mirror images), from its geometry", "N*m/rad", detail=CrankDetail))

PROVIDES = ("crank.throw_mass", "crank.throw_inertia", "crank.throw_stiffness",
            "crank.assembled_stiffness")


@calculation("crank_geometry", "crank", provides=PROVIDES,
             reads=("crank", "crank_model", "cylinders"))
def crank_geometry(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Mass, inertia and stiffness of each throw from sheet Crank."""
    from ..description.crank_derive import throw_stiffness

    crank = engine.crank
    if crank is None:
        raise MissingInputs(["Crank: the crank's geometry (sheet Crank)"])
    mp = crank.mass_properties
    angle: dict[int, float] = {}
    for c in sorted(engine.cylinders, key=lambda c: c.number):
        angle.setdefault(c.pin, c.throw_angle)
    st = throw_stiffness(crank, angle)
    items = [f"throw {t.number}" for t in crank.throws]
    detail = CrankDetail(
        parts=PARTS, part_mass=mp.mass, part_y=mp.y, part_z=mp.z, part_inertia=mp.inertia_main,
        part_inertia_own=mp.inertia_own, stiffness_in_range=st.in_range,
        stiffness_method=st.method, stiffness_error=st.model_error,
        model=tuple(m.as_dict() for m in engine.crank_model),
        assumptions=("Crank geometry: journals, pin, webs (convex hull of the two web circles)"
                     " and counterweights (annular sectors fused with their webs), the geometry"
                     " stated in the documentation (crank geometry); fillets, undercuts, oil"
                     " holes and lightening holes are not part of the mass and stiffness"
                     " solid.",))
    coords = {"item": items}
    stiff_missing = {}
    findings = {}
    for i in range(len(items)):
        if not np.isfinite(st.stiffness[i]):
            stiff_missing[(i,)] = [st.missing or "throw stiffness not available"]
        elif not st.in_range[i]:
            groups = st.outside[i] if i < len(st.outside) else ""
            findings[(i,)] = [f"{items[i]}: outside the fitted range of the throw stiffness"
                              f" model{f' ({groups})' if groups else ''}: the value is"
                              " extrapolated"]
    return {
        "crank.throw_mass": Quantity(THROW_MASS, mp.mass_total, coords, detail=detail),
        "crank.throw_inertia": Quantity(THROW_INERTIA, mp.inertia_total, coords,
                                        detail=detail),
        "crank.throw_stiffness": Quantity(THROW_STIFFNESS, st.stiffness, coords,
                                          missing=stiff_missing, findings=findings,
                                          detail=detail),
        "crank.assembled_stiffness": Quantity(ASSEMBLED_STIFFNESS, st.for_model, coords,
                                              missing=stiff_missing, detail=detail),
    }
