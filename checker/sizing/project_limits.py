"""The project limits a first layout needs so that every rule is judged (issue 47, item 3).

Each limit the rule table leaves to the project gets a default by engine class with its source,
marked ESTIMATE, or the rule is declared not applicable with its reason (sheet RuleOverrides):

* free forces and moments (BAL-001..004): the classical inherent unbalance of the chosen crank
  type and bank angle (what the balance module computes for the sized crank), +5 %, at least 1 %
  of one cylinder's primary inertia force (or that force times the cylinder pitch): the project
  accepts its crank type's free forces (Taylor, C. F., The Internal-Combustion Engine in Theory
  and Practice, Vol. 2, rev. ed., MIT Press, 1985, ch. 8, balance of multi-cylinder engines);
  a balancer shaft would lower them;
* counterweight balance ratio band (BAL-005): 50 % to the sizing target (100 % of the rotating
  unbalance; a 90-degree V also the primary reciprocating force), industrial practice 50-100 %
  [band not confirmed in a public source];
* cyclic irregularity at the lowest speed (FLY-001): :data:`checker.calc.first_layout.CLASSES`;
* crank-nose fatigue (FAT-003): the nose diameter of sheet CrankEnds, the shoulder-fillet stress
  concentration of Peterson's charts (:mod:`checker.calc.shoulder_scf`) at the journal's fillet
  radius, the material's base fatigue strength (no rolling or hardening of the nose fillet);
* the shell supplier's limits (BRG-007..009) and the damper supplier's rubber limits
  (DMP-001..003, and MIS-001: the rubber's heat with a cylinder misfiring): no public default
  by lining or rubber was found, so a first layout declares them not applicable until a
  supplier is chosen (the reason is printed with each result);
* the crank-nose amplitude targets (TV-001..003) of a commercial-vehicle engine: Bell (2013)
  gives them for refined passenger-car engines only and no public source gives a truck's, so a
  first layout declares them not applicable; its crank's vibratory stress is judged by TV-009
  (the class rules' continuous limit as a stated engineering default).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..calc.shoulder_scf import shoulder_fillet_scf

TAG = "ESTIMATE (checker new)"

SUPPLIER_RULES = {
    "BRG-007": "the shell supplier's film temperature limit",
    "BRG-008": "the shell supplier's film pressure limit",
    "BRG-009": "the shell supplier's minimum oil flow",
    "DMP-001": "the damper supplier's rubber shear stress limit and rubber geometry",
    "DMP-002": "the damper supplier's rubber heat limit and rubber geometry",
    "DMP-003": "the damper supplier's rubber heat limit and rubber geometry",
    "MIS-001": "the damper supplier's rubber heat limit and rubber geometry",
}

BALANCE_SOURCE = ("Taylor, C. F., The Internal-Combustion Engine in Theory and Practice, Vol. 2,"
                  " rev. ed., MIT Press, 1985, ch. 8 (free forces and moments of"
                  " multi-cylinder engines)")


def free_limits(res: Any, m_rec: float, crank_radius: float, speed: float, pitch: float
                ) -> dict[str, float]:
    """Limits of the 1st- and 2nd-order free force [N] and moment [N m] at the rated speed:
    the sized crank's own values +5 %, at least 1 % of one cylinder's primary inertia force
    ``m_rec R w^2`` (moments: times the cylinder pitch)."""
    floor_f = 0.01 * m_rec * crank_radius * speed**2
    out: dict[str, float] = {}
    for name, key, floor in (("balance.free_force", "force", floor_f),
                             ("balance.free_moment", "moment", floor_f * pitch)):
        q = res.outcome.quantities.get(name)
        for order in (1, 2):
            v = float("nan")
            if q is not None:
                items = list(q.coords.get("item", []))
                if f"order {order}" in items:
                    v = float(np.asarray(q.values, float)[items.index(f"order {order}")])
            lim = max(1.05 * v, floor) if math.isfinite(v) else floor
            out[f"{key}_{order}"] = float(f"{lim:.3g}") if lim < 1e3 else math.ceil(lim)
    return out


def engine_rows(limits: dict[str, float], ratio_max: float) -> list[tuple]:
    """Engine-sheet rows: free force and moment limits, balance-ratio band."""
    note = (f"{TAG}: the chosen crank type's inherent free {{}} (balance module on the sized"
            f" crank) +5 %, at least 1 % of one cylinder's primary inertia force; the project"
            f" accepts its crank type ({BALANCE_SOURCE}); a balancer would lower it")
    band = (f"{TAG}: counterweights between 50 % (industrial practice 50-100 % of the rotating"
            " unbalance) and the sizing target (100 %; a 90-degree V also the primary"
            " reciprocating force) +5 % [band not confirmed in a public source]")
    return [("Free force limit, 1st order", limits["force_1"], "N", note.format("force")),
            ("Free force limit, 2nd order", limits["force_2"], "N", note.format("force")),
            ("Free moment limit, 1st order", limits["moment_1"], "N m", note.format("moment")),
            ("Free moment limit, 2nd order", limits["moment_2"], "N m", note.format("moment")),
            ("Balance ratio, minimum", 0.5, "-", band),
            ("Balance ratio, maximum", round(1.05 * max(ratio_max, 1.0), 3), "-", band)]


def nose_rows(journal_d: float, nose_d: float, fillet_r: float, fatigue: float,
              material: str) -> list[tuple]:
    """Fatigue-sheet rows of the crank-nose check (FAT-003)."""
    kb, ok_b = shoulder_fillet_scf(journal_d, nose_d, fillet_r, "bending")
    kt, ok_t = shoulder_fillet_scf(journal_d, nose_d, fillet_r, "torsion")
    rng = "" if ok_b and ok_t else " [outside the fit's h/r range]"
    scf = (f"{TAG}: shoulder fillet from the main journal to the nose, fillet radius"
           f" {fillet_r * 1e3:.2f} mm: Peterson's charts 3.10/3.12 as fitted in Young & Budynas,"
           f" Roark's Formulas for Stress and Strain, 7th ed., 2002, Table 17.1{rng}")
    return [("Crank nose diameter", round(nose_d * 1e3, 2), "mm",
             f"{TAG}: the nose diameter of sheet CrankEnds (0.75 x the main journal)"
             " [ratio not confirmed]"),
            ("Crank nose stress concentration bending", round(kb, 3), "-", scf),
            ("Crank nose stress concentration torsion", round(kt, 3), "-", scf),
            ("Crank nose fatigue strength", fatigue, "N/mm^2",
             f"{TAG}: the base material's fatigue strength ({material}), no rolling or"
             " hardening credited at the nose fillet")]


NOSE_TARGET_RULES = ("TV-001", "TV-002", "TV-003")
"""Crank-nose amplitude targets: published for passenger cars only (Bell 2013)."""


def override_rows(engine_class: str = "passenger car") -> list[list]:
    """RuleOverrides rows declaring the supplier-data rules not applicable to a first layout,
    and a commercial vehicle's crank-nose targets (none published)."""
    rows = [[rid, "not applicable", "-",
             f"first layout (checker new): {what} is the supplier's data and no public"
             " default was found; enter it when the supplier is chosen and remove this row"]
            for rid, what in SUPPLIER_RULES.items()]
    if engine_class == "commercial vehicle":
        rows += [[rid, "not applicable", "-",
                  "first layout (checker new): no published crank-nose target for a commercial"
                  " vehicle (Bell, Ricardo 2013, gives them for refined passenger cars only);"
                  " the crank's vibratory stress is judged by TV-009; enter the project's"
                  " target here when it has one"] for rid in NOSE_TARGET_RULES]
    return rows
