"""Caveats of a check: model-validity flags and limits applied outside what they were made for,
as data for page 1 of the report and for the JSON (``caveats``).

A caveat does not change a verdict; it says what a reviewer must know before trusting one:
a synthesized pressure trace that misses its IMEP target (every no-load result rests on it), a
rule limit applied to an engine class its source does not cover. Each caveat is a dict::

    {"kind": "model validity" | "limit outside its class" | "assumption",
     "severity": "high" | "medium",
     "text": one sentence, "rules": [rule ids it affects] (may be empty)}

The calculations put caveats into their quantities' ``extra["caveats"]``; :func:`collect`
gathers them and adds the ones derived here from the computed quantities.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from . import caveats_of
from .display import case_text
from .loads import cycle_of

IMEP_TOLERANCE = 0.02
"""Largest accepted relative miss of a synthesized trace's IMEP against its target (2 %);
above it, the miss is a model-validity caveat."""



def _rpm_ranges(rpm: np.ndarray) -> str:
    r = [int(round(x)) for x in np.sort(rpm)]
    if not r:
        return ""
    return f"{r[0]} rpm" if len(r) == 1 else f"{r[0]}-{r[-1]} rpm"


def imep_caveats(cycle: Any) -> list[dict[str, Any]]:
    """A caveat per load case whose synthesized traces miss the IMEP target by more than
    :data:`IMEP_TOLERANCE` at speeds the rules judge (the operating envelope)."""
    out: list[dict[str, Any]] = []
    imep = np.asarray(cycle.imep, dtype=float)
    target = np.asarray(cycle.target_imep, dtype=float)
    env = (np.ones(imep.shape, bool) if getattr(cycle, "envelope", None) is None
           else np.asarray(cycle.envelope, dtype=bool))
    synth = np.asarray(cycle.synthesized, dtype=bool)
    rpm = np.asarray(cycle.speeds, dtype=float) * 30.0 / np.pi
    for ci, case in enumerate(cycle.cases):
        ok = synth[ci] & env[ci] & np.isfinite(target[ci]) & (target[ci] > 0)
        if not ok.any():
            continue
        dev = np.full(imep.shape[1], np.nan)
        dev[ok] = imep[ci, ok] / target[ci, ok] - 1.0
        bad = ok & (np.abs(np.nan_to_num(dev)) > IMEP_TOLERANCE)
        if not bad.any():
            continue
        k = int(np.nanargmax(np.where(bad, np.abs(dev), -np.inf)))
        word = "above" if dev[k] > 0 else "below"
        out.append({
            "kind": "model validity", "severity": "high",
            "text": (f"{case_text(case).capitalize()}: the synthesized cylinder"
                     f" pressure misses its IMEP target by up to {abs(dev[k]) * 100:.0f} %"
                     f" ({imep[ci, k] / 1e5:.2f} bar {word} {target[ci, k] / 1e5:.2f} bar at"
                     f" {rpm[k]:.0f} rpm; {int(bad.sum())} of {int(ok.sum())} judged speeds,"
                     f" {_rpm_ranges(rpm[bad])}): the given peak pressure and the"
                     " IMEP target (brake torque + friction) cannot both be met by the synthesis"
                     " there, and every"
                     f" {case_text(case)} result at those speeds rests on that"
                     " trace (give measured traces or check the peak pressure)."),
            "rules": [], "case": case, "speeds_rpm": [float(x) for x in rpm[bad]],
            "worst_deviation": float(dev[k])})
    return out


def applicable(caveats: list[dict[str, Any]], results: list, overridden: set[str]
               ) -> list[dict[str, Any]]:
    """The caveats that qualify a result of this run: those naming no rule, and those naming
    a rule that was judged (passed or failed) with its published limit (not one the
    workbook's RuleOverrides replaced: the project's own limit needs no caveat)."""
    judged = {r.rule for r in results if r.status in ("pass", "fail")}
    return [c for c in caveats if not c.get("rules")
            or any(x in judged and x not in overridden for x in c["rules"])]


ESTIMATE_SHEETS = {  # rule family -> the input sheets its results rest on
    "BRG": ("Engine", "Cylinders", "PeakPressure", "BrakeTorque", "Bearings", "Oil"),
    "TV": ("Engine", "Cylinders", "PeakPressure", "BrakeTorque", "TVModel", "Damper"),
    "DMP": ("Engine", "Cylinders", "PeakPressure", "BrakeTorque", "TVModel", "Damper"),
    "FAT": ("Engine", "Cylinders", "PeakPressure", "BrakeTorque", "Bearings", "TVModel",
            "Fatigue"),
    "JNT": ("Engine", "Cylinders", "PeakPressure", "BrakeTorque", "TVModel", "Joints",
            "JointTorques"),
    "BAL": ("Engine", "Cylinders", "CrankMass"),
    "FLY": ("Engine", "Cylinders", "PeakPressure", "BrakeTorque", "TVModel"),
}
"""The sheets each rule family's results are computed from (an estimate on one of them makes
every evaluated result of the family rest on estimates)."""


def estimate_caveat(engine: Any, results: list) -> dict[str, Any] | None:
    """The caveat of a workbook with inputs marked ESTIMATE (a first layout of ``checker
    new``): how many inputs, on which sheets, and how many evaluated results rest on them."""
    estimates = getattr(engine, "estimates", ())
    if not estimates:
        return None
    by: dict[str, int] = {}
    for e in estimates:  # "Sheet!B4 label: note" or "Sheet rows 3, 4: note"
        sheet = e.split("!")[0].split(" ")[0]
        head = e.split(":")[0]
        k = 1 if "!" in head else len(re.findall(r"\d+", head.split(" ", 1)[1]))
        by[sheet] = by.get(sheet, 0) + k
    resting = [r for r in results if r.status in ("pass", "fail")
               and set(ESTIMATE_SHEETS.get(r.rule.split("-")[0], ())) & set(by)]
    rules = sorted({r.rule for r in resting})
    n = sum(by.values())
    return {"kind": "estimates", "severity": "high",
            "text": (f"{len(resting)} of {sum(r.status in ('pass', 'fail') for r in results)}"
                     f" evaluated results rest on estimates: {n} input"
                     f"{'s' if n != 1 else ''} (parameters and table rows)"
                     f" {'are' if n != 1 else 'is'} marked ESTIMATE (sized by a stated design"
                     " rule, not data of this engine; sheets "
                     + ", ".join(f"{k} {v}" for k, v in by.items())
                     + "); replace them with the design's values as they become known."),
            "rules": rules, "count": n, "results": len(resting)}


PLAUSIBILITY_MARK = "outside the band of real engines"
"""The words a sized value's note carries when ``checker new`` found it outside the band of
real engines of its class (docs/new-engine.md)."""


def layout_caveats(engine: Any) -> list[dict[str, Any]]:
    """Caveats of the layout itself: firing that is not even (the crank type or bank angle
    allows no even firing: the torque's lower orders and the flywheel's task grow), and values a
    first layout sized outside the band of real engines (notes marked by ``checker new``)."""
    out: list[dict[str, Any]] = []
    cyl = list(getattr(engine, "cylinders", ()) or ())
    if len(cyl) > 1:
        f = np.sort(np.mod([float(c.firing_angle) for c in cyl], 4 * np.pi))
        gaps = np.degrees(np.diff(np.append(f, f[0] + 4 * np.pi)))
        if not np.allclose(gaps, 720.0 / len(cyl), atol=1e-6):
            order = sorted(cyl, key=lambda c: float(c.firing_angle) % (4 * np.pi))
            out.append({"kind": "uneven firing", "severity": "medium",
                        "text": ("The firing intervals are "
                                 + "/".join(f"{g:.0f}" for g in gaps) + " deg (cylinders "
                                 + "-".join(str(c.number) for c in order) + f"; even would be"
                                 f" {720.0 / len(cyl):g} deg): the crank type and bank angle"
                                 " allow no even firing, so the half and lower torque orders"
                                 " and the cyclic irregularity are larger than an even-firing"
                                 " engine's."), "rules": []})
    marked = [e for e in getattr(engine, "estimates", ()) if PLAUSIBILITY_MARK in e]
    for e in marked:
        text = e.split(PLAUSIBILITY_MARK, 1)[1].split("]", 1)[0].strip(" :;")
        out.append({"kind": "plausibility", "severity": "medium",
                    "text": f"{e.split(':')[0]}: {text}.", "rules": []})
    return out


def collect(outcome: Any) -> list[dict[str, Any]]:
    """Every caveat of a run (graph outcome): those the calculations attached to their
    quantities (:attr:`checker.results.Detail.caveats`) and the IMEP check of the pressure
    traces; each once."""
    out: list[dict[str, Any]] = []
    seen: set[str] = set()

    def add(c: dict[str, Any]) -> None:
        if c["text"] not in seen:
            seen.add(c["text"])
            out.append(c)

    for name in sorted(outcome.quantities):
        q = outcome.quantities[name]
        for c in caveats_of(q):
            add(c)
    cyc = cycle_of(outcome.quantities)
    if cyc is not None:
        for c in imep_caveats(cyc):
            add(c)
    return out
