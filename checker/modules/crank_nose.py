"""Graph calculation: classical fatigue check of the crank nose (TV + FEAD torque, belt
bending), Bell, Ricardo 2013, 'Crankshaft analysis (29)'. Part of the fatigue module."""

from __future__ import annotations

from ..calc.crank_nose import crank_nose_safety_factor, crank_nose_stresses
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.crank_nose import CrankNoseDetail
from .loads import CASES

NOSE_SF = quantity(QuantitySpec(
    "fatigue.nose_goodman_sf", "", ("case", "speed"),
    "Goodman safety factor at the crank-nose fillet (belt bending + mean and TV torsion)", "",
    coords={"case": CASES}, detail=CrankNoseDetail))

_NEEDED = ("nose_diameter", "scf_nose_bending", "scf_nose_torsion", "nose_fatigue", "uts")


@calculation("crank_nose_fatigue", "fatigue", provides=("fatigue.nose_goodman_sf",),
             needs=("tv.element_torque",), reads=("fatigue", "tv_model.station", "tv_model.role"))
def crank_nose_fatigue(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Goodman SF of the crank-nose section per load case and speed."""
    f = engine.fatigue
    miss = [engine.describe_missing("Fatigue", a)
            for a in _NEEDED if f.get(a) is None]
    if miss:
        raise MissingInputs(miss)
    el = inputs["tv.element_torque"]
    nose = next((s.station for s in engine.tv_model if s.role == "crank nose"), None)
    names = el.coords["item"]
    k = next((i for i, n in enumerate(names) if el.item_attrs[n].get("front") == nose), None)
    if nose is None or k is None:
        raise MissingInputs(["TVModel: no 'crank nose' station followed by a shaft element"])
    ex = el.detail
    tmax = ex.mean[k] + ex.vib_max[k]
    tmin = ex.mean[k] + ex.vib_min[k]
    notes = []
    belt = f.get("belt_load")
    lever = f.get("belt_overhang")
    if belt is None or lever is None:
        belt, lever = 0.0, 0.0
        notes.append("Crank nose: no belt load and overhang given (Fatigue sheet): torsion only,"
                     " no FEAD/timing-drive bending included.")
    eq_a, eq_m = crank_nose_stresses(tmax, tmin, belt, lever, f["nose_diameter"],
                                     f.get("nose_bore") or 0.0, f["scf_nose_bending"],
                                     f["scf_nose_torsion"])
    sf = crank_nose_safety_factor(eq_a, eq_m, f["nose_fatigue"], f["uts"])
    notes.append(f"Crank nose: torque of the TV element '{names[k]}' (mean incl. the accessory"
                 " drive torque + synthesized TV); belt bending fully reversed; Goodman with the"
                 " nose fatigue strength and the base UTS (Shigley 10th ed. eq. 7-7/7-8).")
    return {"fatigue.nose_goodman_sf": Quantity(
        NOSE_SF, sf, {"case": el.coords["case"], "speed": el.coords["speed"]},
        detail=CrankNoseDetail(sigma_eq_a=eq_a, sigma_eq_m=eq_m, torque_max=tmax,
                               torque_min=tmin, element=names[k], assumptions=tuple(notes)))}
