"""Report section: what it takes to pass (design levers) and the verdict at the tolerance
corners (``checker report --remedies --corners``; :mod:`checker.remedies`).

Formats the answers the remedies package computed; computes nothing itself."""

from __future__ import annotations

from ..api import CheckResult
from ..display import with_unit
from .sections import section


def _bounds(lv) -> str:
    if lv.choices:
        vals = []
        for c in lv.choices:
            if isinstance(c, dict) and "nominal diameter" in c:
                vals.append(f"M{c['nominal diameter']:g}x{c['thread pitch']:g}")
            elif isinstance(c, dict):
                vals.append(", ".join(f"{k} {v:g}" for k, v in c.items()))
            else:
                vals.append(f"{c:g}" if isinstance(c, (int, float)) else str(c))
        return "choices " + ", ".join(vals)
    if lv.limits is not None:
        return f"{lv.limits[0]:g}..{lv.limits[1]:g} {lv.unit}".strip()
    return f"{lv.bounds[0]:g}..{lv.bounds[1]:g} x today's value"


@section("remedies", label="remedies and tolerance corners")
def remedies_section(res: CheckResult) -> dict:
    blocks: list[dict] = []
    rem = res.remedies
    if rem is not None:
        blocks.append({"type": "text", "text": (
            "For every failing result and every passing one within 10 % of its limit, each"
            " design lever that the lever table lists for its rule was moved from today's value"
            " in its allowed direction until the margin reached zero: a few trial values"
            " bracket the root, regula falsi refines it, and the value given was checked by a"
            " direct evaluation (margin between 0 and 0.1 %). Discrete levers (bolt size,"
            " number of bolts, oil grade) give the first standard choice that passes. At each"
            " answer the whole check was run again: the side effects are the other results"
            " whose status changes. "
            f"{rem['evaluations']} evaluations.")})
        rows, css = [], []
        for x in rem["results"]:
            for rm in x.remedies:
                fx = ", ".join(f"{e['rule']} {e['item']} → {e['to']}" for e in rm.side_effects)
                if rm.found:
                    ch = rm.change
                    change = "-" if ch is None else (
                        ("+" if ch >= 0 else "") + with_unit(ch, rm.lever.unit)
                        + (f" ({rm.change_pct:+.1f} %)" if rm.change_pct is not None else ""))
                    rows.append([f"{x.rule} {x.item}", rm.lever.name,
                                 rm.value_text(rm.nominal), rm.value_text(), change,
                                 fx or "none"])
                    css.append("pass")
                else:
                    rows.append([f"{x.rule} {x.item}", rm.lever.name,
                                 rm.value_text(rm.nominal), rm.reason or "no value", "-", "-"])
                    css.append("fail")
        if rows:
            blocks.append({"type": "table", "caption": "What it takes to pass: per result and"
                           " lever, the value at which the margin reaches zero (a failing"
                           " result passes there, a passing one near its limit fails beyond)",
                           "columns": ["result", "lever", "today", "margin zero at", "change",
                                       "side effects"],
                           "rows": rows, "row_css": css,
                           "widths": [15, 22, 11, 14, 14, 24]})
        conflicts = []
        for x in rem["results"]:
            for c in x.conflicts:
                if c not in conflicts:
                    conflicts.append(c)
        if conflicts:
            blocks.append({"type": "heading", "text": "Conflicts"})
            blocks.append({"type": "list", "items": conflicts})
        lrows = [[lv.name, ", ".join(lv.rules) + (f" ({', '.join(lv.items)})" if lv.items
                                                  else ""),
                  lv.where_text(), lv.direction, _bounds(lv)] for lv in rem["levers"]]
        blocks.append({"type": "table", "caption": "Design levers (rules/levers.toml and"
                       " --levers): the inputs a designer moves to fix each rule",
                       "columns": ["lever", "rules", "input", "direction", "bounds"],
                       "rows": lrows, "widths": [22, 20, 28, 10, 20]})
    cor = res.corners
    if cor is not None:
        tols = cor["tolerances"]
        blocks.append({"type": "heading", "text": "The verdict at the tolerance corners"})
        blocks.append({"type": "text", "text": (
            "Each result is judged at the worst corner of the tolerances that affect it"
            " (found one at a time; all 2^k corners for k ≤ 6, beyond that the corners of the"
            " six most influential with the others at their worse end), with a check that the"
            " worst point is not inside the box (each tolerance set back to the middle of its"
            " range at the worst corner; where that is worse, the worst point is refined by a"
            " golden-section search). "
            f"Verdict at the worst corners: {'FAIL' if _fails(res) else 'PASS'};"
            f" {cor['evaluations']} evaluations.")})
        if tols:
            blocks.append({"type": "table", "caption": "Tolerances (workbook sheet Tolerances)",
                           "columns": ["input", "cells", "min", "today", "max", "source"],
                           "rows": [[t.name, _cells(t.binding.labels),
                                     with_unit(t.low, t.unit), with_unit(t.nominal, t.unit),
                                     with_unit(t.high, t.unit), t.source or "-"]
                                    for t in tols],
                           "widths": [20, 14, 9, 9, 9, 39]})
        rows, css = [], []
        for c in cor["results"]:
            if not c.tolerances:
                continue
            rows.append([f"{c.rule} {c.item}", with_unit(c.nominal_value, c.unit)
                         + f" ({c.nominal_status})", with_unit(c.worst_value, c.unit)
                         + f" ({c.worst_status})", "; ".join(c.corner)
                         + (" (inside the box)" if c.inside else "")])
            css.append("pass" if c.worst_status == "pass" else "fail")
        if rows:
            blocks.append({"type": "table", "caption": "Nominal and worst-corner values",
                           "columns": ["result", "nominal", "worst", "at"],
                           "rows": rows, "row_css": css, "widths": [18, 17, 17, 48]})
        elif not tols:
            blocks.append({"type": "text", "text": "The workbook declares no tolerances"
                           " (sheet Tolerances): every result is judged at nominal values."})
    return {"id": "remedies", "title": "What it takes to pass; tolerance corners",
            "intro": "Design levers and tolerance ranges (checker.remedies).",
            "blocks": blocks}


def _cells(labels) -> str:
    if len(labels) <= 2:
        return ", ".join(labels)
    return f"{labels[0]} .. {labels[-1]} ({len(labels)} cells)"


def _fails(res: CheckResult) -> bool:
    from ..remedies import corners_fail

    return corners_fail(res)
