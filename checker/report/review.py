"""Page 1 of the report for a reviewer: failures ranked by severity with the mechanism behind
each, the caveats that qualify the results, and the document-control block (formatting only:
every number comes from the rule results and the quantities).

Severity: a *predicted failure* first (a Goodman or M53 factor below 1: the part is expected
to crack; a joint cover factor below 1: the joint slips), then the other failures by their
distance to the limit, the furthest first.
"""

from __future__ import annotations

import datetime as _dt
import re

from ..api import CheckResult
from ..evaluation.ruletable import RuleResult
from ..results import caveats_of
from ..results.loads import cycle_of

MECHANISMS: dict[str, str] = {
    "BAL-001": "Free forces of the reciprocating and rotating masses shake the engine mounts"
               " and the vehicle at that order (Taylor 1985, ch. 8).",
    "BAL-003": "Free moments rock the engine on its mounts at that order (Taylor 1985, ch. 8).",
    "BAL-005": "Too little counterweight leaves the rotating masses on the main bearings; too"
               " much adds mass and its own bearing load (Agostini 2019, 'Crankshaft').",
    "BAL-006": "Rotating unbalance in a layout that should balance itself shakes the engine at"
               " first order and loads the mains (Taylor 1985, ch. 8).",
    "BRG-001": "Specific load above the lining's rated capacity: fatigue cracking of the lining"
               " (lining suppliers' ratings, Clevite 2000).",
    "BRG-003": "Film thinner than three times the composite roughness: the surfaces touch"
               " (mixed lubrication), wear and seizure (Hamrock, Schmid and Jacobson 2004).",
    "BRG-005": "Film below the guideline of the short-bearing method: wear and seizure risk"
               " (Bell, Ricardo 2013, 'Crankshaft analysis (2)').",
    "BRG-007": "Hot film: lower viscosity and load capacity; lining and oil degrade above the"
               " supplier's temperature (ISO 7902-1:2020).",
    "BRG-008": "Peak film pressure above the lining's strength: lining fatigue under the"
               " hydrodynamic pressure ('Hydrodynamic aspects of fatigue in plain journal"
               " bearings', J. Lubrication Technology 103(1), 1981).",
    "BRG-009": "Too little oil through the bearing: it carries less friction heat away and the"
               " film runs hotter (Budynas and Nisbett, Shigley's, ch. 12).",
    "DMP-001": "Rubber shear stress above the supplier's limit: the rubber tears or its bond"
               " fails (Bell, Ricardo 2013, 'Crankshaft analysis (21)').",
    "DMP-002": "Too much heat per volume of rubber: the rubber overheats and ages, the damper"
               " loses its damping (Bell 2013; Nashif, Jones and Henderson 1985).",
    "DMP-004": "Damper tuned away from Den Hartog's optimum: less damping of the crank mode"
               " (Den Hartog 1956, sec. 3.3).",
    "DMP-005": "The rubber's stiffness changes with its temperature: at that end of the range"
               " the ring is tuned away from the crank mode, which then resonates more (Den"
               " Hartog 1956, sec. 3.3).",
    "DMP-006": "Rubber shear stress above the supplier's limit at that end of the temperature"
               " range: the rubber tears or its bond fails (Bell, Ricardo 2013, (21)).",
    "DMP-007": "Too much heat per volume of rubber at that end of the temperature range: the"
               " rubber overheats and ages (Bell 2013; Nashif, Jones and Henderson 1985).",
    "DMP-008": "Too much heat per wetted area of the silicone film: the fluid ages, loses"
               " viscosity and the damper its damping (Andre and Spurk 1982).",
    "DMP-009": "Silicone above its temperature limit: the fluid degrades and the damper stops"
               " damping (housing heat balance, Incropera et al. 2007).",
    "DMP-010": "Damping away from Den Hartog's optimum for an untuned damper: too little lets"
               " the crank resonate, too much locks the ring to the crank (Den Hartog 1956,"
               " ch. 3).",
    "FAT-001": "Goodman safety factor below the target: a fatigue crack can start at the fillet"
               " or oil hole (Bell, Ricardo 2013, 'Crankshaft analysis (25)-(28)').",
    "FAT-002": "Equivalent alternating stress too close to the M53 fatigue strength: crack"
               " initiation at the fillet or oil hole (IACS UR M53, 2019, sec. 7).",
    "FAT-003": "Crank-nose fatigue under belt bending and torsion (Bell, Ricardo 2013,"
               " 'Crankshaft analysis (29)').",
    "FLY-001": "Speed fluctuation over the cycle too large: rough idle, drive-line and"
               " accessory-drive loads (Agostini 2019, 'Engine degree of irregularity').",
    "JNT-001": "Preload outside the recommended band: too low loses clamp force, too high"
               " yields the bolt (Bell, Ricardo 2013, 'Crankshaft analysis (23)').",
    "JNT-002": "Head contact pressure above the clamped material's limit: the face embeds and"
               " the preload relaxes (Bell 2013; VDI 2230-1, 2015).",
    "JNT-003": "Friction capacity of the joint too close to the torque it carries: fretting and"
               " bolt loosening; below 1 the joint slips (Bell, Ricardo 2013, (23)-(24)).",
    "JNT-008": "The torque the cover-factor rules use is below the torsional model's: their"
               " cover factors are optimistic (Bell, Ricardo 2013, (23)-(24)).",
    "TV-001": "Torsional vibration above the target: higher crank stresses, noise and"
              " accessory-drive loads (Bell, Ricardo 2013, 'Crankshaft analysis (15)').",
    "TV-004": "Crank vibratory torsional stress above the class society's permissible stress:"
              " torsional fatigue of the crank (Korean Register 2025, Pt 5 Ch 4, 201).",
    "TV-007": "A barred speed range where the engine must run: it would dwell at a critical"
              " above the continuous limit (Korean Register 2025, Pt 5 Ch 4, 206).",
    "TV-008": "A major critical near the rated speed: every cylinder in phase excites the crank"
              " mode where the engine runs most (Korean Register 2025, Pt 5 Ch 4, 204).",
    "CPL-001": "Vibratory torque above the coupling's permissible T_KW: its elastic elements"
               " fatigue and tear (DIN 740-2:1986).",
    "CPL-002": "Damping heat above the coupling's permissible P_KV: its rubber overheats,"
               " hardens and fails (DIN 740-2:1986).",
    "CPL-003": "Mean torque above the coupling's nominal T_KN: its elements creep and fail"
               " (DIN 740-2:1986).",
    "MIS-001": "A misfiring cylinder excites the half and lower orders: damper, coupling and"
               " crank carry vibratory loads beyond normal firing (Korean Register 2025, Pt 5"
               " Ch 4, 102.1).",
}
"""The mechanism behind a failure, by rule id; a rule not listed here takes the entry of the
nearest lower id of its family (BRG-002 -> BRG-001, JNT-005 -> JNT-003)."""

PREDICTED = {"FAT-001": "a fatigue crack is expected (Goodman safety factor below 1)",
             "FAT-003": "a fatigue crack is expected (Goodman safety factor below 1)",
             "FAT-002": "a fatigue crack is expected (M53 acceptability factor below 1)",
             "JNT-003": "the joint slips (cover factor below 1)",
             "JNT-004": "the joint slips (cover factor below 1)",
             "JNT-005": "the joint slips (cover factor below 1)",
             "JNT-006": "the joint slips (cover factor below 1)",
             "JNT-007": "the joint slips (cover factor below 1)"}
"""Rules whose value below 1 means the part is predicted to fail, not only to miss a design
margin: safety factors (stress at the fatigue strength) and cover factors (torque at the
joint's friction capacity)."""


def mechanism(rule: str) -> str:
    """The mechanism line of a rule (its own entry or its family's nearest lower id)."""
    if rule in MECHANISMS:
        return MECHANISMS[rule]
    fam, _, num = rule.partition("-")
    same = sorted((k for k in MECHANISMS if k.split("-")[0] == fam
                   and k.split("-")[1] <= num), reverse=True)
    return MECHANISMS[same[0]] if same else ""


def predicted(r: RuleResult) -> str:
    """What is predicted to happen when ``r`` is a predicted failure, else ''."""
    if r.status == "fail" and r.rule in PREDICTED and r.value is not None and r.value < 1:
        return PREDICTED[r.rule]
    return ""


def rank_failures(rows: list) -> list:
    """Failure rows (:class:`summary.Row`) most severe first: predicted failures (lowest
    factor first), then by distance to the limit (the furthest first); each row gets
    ``predicted`` and ``mechanism`` texts."""
    for x in rows:
        x.predicted = next((p for p in map(predicted, x.results) if p), "")
        x.mechanism = mechanism(x.rule)
        x.first_of_item = True

    def key(x):
        if x.predicted:
            return (0, min(r.value for r in x.results if r.value is not None), x.rule)
        m = x.margin_value
        return (1, m if m is not None else 0.0, x.rule)

    out = sorted(rows, key=key)
    first: dict[str, int] = {}
    for k, x in enumerate(out, 1):
        fam = _mechanism_key(x.rule)
        x.mechanism_text = x.mechanism if fam not in first else f"Mechanism as #{first[fam]}."
        first.setdefault(fam, k)
        x.case_text = _plain_case(x.case)
    return out


def _mechanism_key(rule: str) -> str:
    return mechanism(rule)


def _plain_case(case: str) -> str:
    return re.sub(r"\btv peak\b", "TV peak", case or "-")


# ------------------------------------------------------------------------------ caveats
_VALIDITY = re.compile(r"validity|outside \[|taken as|collaps|did not converge|not converged|"
                       r"extrapolat|IMEP|caveat", re.I)


CAVEAT_TITLES = {"model validity": "Model validity",
                 "limit outside its class": "Limits outside their engine class",
                 "assumption": "Assumptions behind the limits"}
"""The heading of each caveat kind on page 1 (:mod:`checker.results.caveats`), in page order."""


def _sentence(t: str) -> str:
    t = t.strip().rstrip(".")
    return t[:1].upper() + t[1:] + "."


def _validity_flags(res: CheckResult) -> list[str]:
    """Model-validity findings of the quantities (one line per distinct finding, with the
    number of items it concerns)."""
    seen: dict[str, int] = {}
    for q in res.outcome.quantities.values():
        for texts in (q.findings or {}).values():
            for t in texts:
                if _VALIDITY.search(t):
                    seen[t] = seen.get(t, 0) + 1
    out = []
    for t, n in seen.items():
        t = t.rstrip(".")
        out.append(t + (f" ({n} items)" if n > 1 else "") + ".")
    return out


def _stated_caveats(res: CheckResult) -> dict[str, list[str]]:
    """The caveats the calculations state (:func:`checker.results.caveats_of`: dicts with a
    ``kind`` and a one-sentence ``text``), their sentences by page-1 heading."""
    from ..results.caveats import applicable

    out: dict[str, list[str]] = {}
    stated = [c for name in sorted(res.outcome.quantities)
              for c in caveats_of(res.outcome.quantities[name])]
    for c in applicable(stated, res.results, {o.rule for o in res.table.overrides}):
        title = CAVEAT_TITLES.get(str(c.get("kind", "")), "Model validity")
        text = _sentence(str(c["text"]))
        if text not in out.setdefault(title, []):
            out[title].append(text)
    return out


def _imep_miss(res: CheckResult) -> str:
    """The synthesized cylinder pressure missing its IMEP target by more than 5 % at a judged
    speed (it moves every result of that load case); the numbers are the loads module's."""
    import numpy as np

    from . import judged as jd

    cyc = cycle_of(res.outcome.quantities)
    if cyc is None:
        return ""
    ref = res.outcome.quantities.get("bearing.peak_specific_load")
    n = np.asarray(cyc.speeds).size
    judged = np.ones((len(cyc.cases), n), bool)
    if ref is not None and list(ref.coords["case"]) == list(cyc.cases) and len(
            ref.coords["speed"]) == n:
        judged = jd.mask(ref).any(axis=0)
    worst: list[tuple[float, str]] = []
    for ci, case in enumerate(cyc.cases):
        tgt = np.asarray(cyc.target_imep[ci], float)
        ok = np.isfinite(tgt) & (np.abs(tgt) > 0) & judged[ci]
        if ok.any():
            dev = np.abs(np.asarray(cyc.imep[ci], float)[ok] / tgt[ok] - 1).max()
            if dev > 0.05:
                worst.append((float(dev), str(case)))
    if not worst:
        return ""
    parts = ", ".join(f"{c} load by up to {d * 100:.0f} %" for d, c in worst)
    which = "that load case rests" if len(worst) == 1 else "those load cases rest"
    return (f"The synthesized cylinder pressure misses its IMEP target at the judged speeds"
            f" ({parts}): every result of {which} on it (section Crank-train loads).")


def _class_limits(res: CheckResult) -> list[str]:
    """Rules whose limit is a target for one engine class, applied without a project limit."""
    over = {o.rule for o in res.table.overrides}
    ran = {r.rule for r in res.results if r.status in ("pass", "fail")}
    out = []
    for r in res.table.rules:
        src = (r.source or "").lower()
        if r.id in ran and r.id not in over and "passenger-car" in src:
            out.append(r.id)
    if not out:
        return []
    return [f"{', '.join(out)}: the limits are concept targets for a refined passenger-car"
            " engine with a rubber TV damper (Bell, Ricardo 2013, 'Crankshaft analysis (15)');"
            " for another engine class enter project limits (sheet RuleOverrides)."]


def assumption_rows(res: CheckResult) -> list[dict]:
    """The workbook's assumptions as ``{"sheet", "cell", "parameter", "value", "source"}``."""
    pat = re.compile(r"^(?:Workbook: )?([A-Za-z][\w ]*)!([A-Z]{1,3}\d+) (.*?) = (.*?): (.*)$",
                     re.S)
    table = re.compile(r"^(?:Workbook: )?([A-Za-z]\w*) (rows? [\d, ]+): (.*)$", re.S)
    out = []
    for a in res.assumptions:
        m = pat.match(a)
        if m:
            src = re.sub(r"^ASSUMPTION(?: \([^)]*\))?:?\s*", "", m.group(5)).strip()
            out.append({"sheet": m.group(1), "cell": m.group(2), "parameter": m.group(3),
                        "value": m.group(4), "source": src or "assumption"})
            continue
        m = table.match(a)
        if m:
            nums = [int(x) for x in re.findall(r"\d+", m.group(2))]
            rows = (f"row {nums[0]}" if len(nums) == 1 else f"rows {nums[0]}..{nums[-1]}"
                    if nums == list(range(nums[0], nums[-1] + 1)) else
                    "rows " + ", ".join(map(str, nums)))
            out.append({"sheet": m.group(1), "cell": rows, "parameter": "table rows",
                        "value": "", "source": re.sub(r"ASSUMPTION:?\s*", "", m.group(3))})
        else:
            out.append({"sheet": "", "cell": "", "parameter": "", "value": "",
                        "source": re.sub(r"^Workbook:\s*", "", a)})
    return out


def caveats(res: CheckResult) -> list[dict]:
    """``[{"title", "items"}]``: model-validity flags, limits applied outside their engine
    class, and the inputs that are assumptions."""
    out = []
    stated = _stated_caveats(res)
    flags = _validity_flags(res)
    flags += [t for t in stated.pop("Model validity", []) if t not in flags]
    imep = _imep_miss(res)
    if imep:
        flags.insert(0, imep)
    if flags:
        more = len(flags) - 6
        out.append({"title": "Model validity", "items": flags[:6] + (
            [f"... and {more} more in the module sections."] if more > 0 else [])})
    from ..results.caveats import estimate_caveat

    est = estimate_caveat(res.engine, res.results)
    if est:
        out.append({"title": "Results resting on estimates", "items": [est["text"]]})
    from ..results.caveats import layout_caveats

    for kind, title in (("uneven firing", "Uneven firing"),
                        ("plausibility", "Dimensions outside the band of real engines")):
        items = [c["text"] for c in layout_caveats(res.engine) if c["kind"] == kind]
        if items:
            out.append({"title": title, "items": items})
    cls = _class_limits(res) + stated.pop("Limits outside their engine class", [])
    if cls:
        out.append({"title": "Limits outside their engine class", "items": cls})
    for title, items in stated.items():
        out.append({"title": title, "items": items})
    rows = assumption_rows(res)
    if rows:
        by: dict[str, int] = {}
        for r in rows:
            if r["sheet"]:
                by[r["sheet"]] = by.get(r["sheet"], 0) + 1
        n = sum(by.values())
        model = len(rows) - n
        if n:
            out.append({"title": "Inputs that are assumptions", "items": [
                f"{n} input{'s are' if n != 1 else ' is'} marked as assumption"
                f"{'s' if n != 1 else ''} in the workbook (sheets "
                + ", ".join(f"{k} {v}" for k, v in by.items())
                + "), not data of this engine" + (f"; the model adds {model} assumptions of"
                                                  " its own" if model else "")
                + "; listed with value and source under Assumptions."]})
    return out


DOC_FIELDS = (("project", "Project"), ("revision", "Revision"), ("author", "Author"),
              ("reviewer", "Reviewer"), ("document_date", "Date"))


def document_control(res: CheckResult) -> list[tuple[str, str]]:
    """(label, value) of the document-control block, from the Engine sheet ('-' when blank;
    the date defaults to the run date)."""
    p = res.engine.params
    out = []
    for attr, label in DOC_FIELDS:
        v = p.get(attr)
        if attr == "document_date" and not v:
            v = _dt.date.today().isoformat()
        out.append((label, str(v) if v not in (None, "") else "-"))
    return out
