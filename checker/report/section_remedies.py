"""Report section: what it takes to pass (design levers) and the verdict at the tolerance
corners (``checker report --remedies --corners``; :mod:`checker.remedies`).

Formats the answers the remedies package computed; computes nothing itself. Written for a
design review, short: results with the same answers (four identical big ends) are one row,
the levers with no value within their bounds one line per result, and the corners table
lists the results whose status or margin the tolerances move. Every answer in full (each
lever's value, change, margin at the value, best margin reached, side effects with their
values; each result's nominal and worst-corner value, margin and corner) goes to the
results workbook, sheets :data:`REMEDIES_SHEET` and :data:`CORNERS_SHEET`.
"""

from __future__ import annotations

import re
from typing import Any

from ..api import CheckResult
from ..results.display import item_label, with_unit
from .sections import section

REMEDIES_SHEET = "Remedies"
CORNERS_SHEET = "Tolerance corners"
MOVED = 0.005
"""The corners table lists a result whose relative margin the tolerances move by at least this
much (0.5 % of the limit) and that is within :data:`NEAR` of its limit at the worst corner, or
whose status they change."""
NEAR = 0.10
"""Relative margin below which a result is near its limit (as the remedies' 10 %)."""

_NUM = re.compile(r"^(.*?)(\d+)(\D*)$")


def items_text(items: list[str]) -> str:
    """Items as a reader scans them: runs of three or more consecutive numbers with the same
    words around them shortened, ``BE1, BE2, BE3, BE4`` -> ``BE1–BE4``, ``main 3 fillet,
    main 4 fillet, main 5 fillet`` -> ``main 3–5 fillet``; the whole engine reads ``engine``."""
    items = [item_label(x) for x in items]
    out: list[str] = []
    k = 0
    while k < len(items):
        m = _NUM.match(items[k])
        j = k + 1
        if m:
            while j < len(items):
                n = _NUM.match(items[j])
                if not (n and n.group(1) == m.group(1) and n.group(3) == m.group(3)
                        and int(n.group(2)) == int(m.group(2)) + (j - k)):
                    break
                j += 1
        if m and j - k >= 3:
            last = _NUM.match(items[j - 1]).group(2)
            if m.group(3):  # "main 3–5 fillet"
                out.append(f"{m.group(1)}{m.group(2)}–{last}{m.group(3)}")
            else:  # "BE1–BE4"
                out.append(f"{items[k]}–{items[j - 1]}")
            k = j
        else:
            out.append(items[k])
            k += 1
    return ", ".join(out)


def results_text(keys: list[tuple[str, str]]) -> str:
    """``[(rule, item)]`` as ``BRG-003 M1–M5; BRG-004 M3, BE1–BE4`` (rules in order of first
    appearance)."""
    by: dict[str, list[str]] = {}
    for rule, item in keys:
        by.setdefault(rule, []).append(item)
    return "; ".join(f"{rule} {items_text(items)}".rstrip() for rule, items in by.items())


_STATUS = {"not_evaluated": "not evaluated"}


def effects_text(effects: list[dict], exclude: set[tuple[str, str]] = frozenset(),
                 sep: str = ". ") -> str:
    """The other results whose status changes, by the status they change to:
    ``→ pass: BRG-003 M1–M5; BRG-004 M3. → fail: FAT-001 main 5 oil hole`` ('' for none);
    ``exclude``: the results the row itself names."""
    by: dict[str, list[tuple[str, str]]] = {}
    for e in effects:
        if (e["rule"], e["item"]) not in exclude:
            by.setdefault(e["to"], []).append((e["rule"], e["item"]))
    order = sorted(by, key=lambda s: (s == "pass", s))  # what breaks first
    return sep.join(f"→ {_STATUS.get(s, s)}: {results_text(by[s])}" for s in order)


def _short_tolerance(t) -> str:
    """A tolerance as the corners table says it: ``radial clearance (big end)`` for
    ``Bearings radial clearance (type = big end)`` (its sheet is in the tolerance table)."""
    name = t.name
    if name.startswith(t.binding.sheet + " "):
        name = name[len(t.binding.sheet) + 1:]
    name = re.sub(r"\(([^()=]*?) = ([^()]*)\)", r"(\2)", name).replace(" (all)", "")
    if len(name) > 1 and name[0].isupper() and name[1].islower():
        name = name[0].lower() + name[1:]  # "Oil supply temperature" in a list
    return name


def corner_text(corner: list[str], tolerances: list) -> str:
    """The worst corner in short words: ``radial clearance (main) max, peak pressure min``
    (the end values are the tolerance table's min and max; a point inside the box keeps its
    value)."""
    out = []
    for text in corner:
        t = next((t for t in tolerances if text.startswith(t.name + " ")), None)
        if t is None:
            out.append(text)
            continue
        rest = text[len(t.name) + 1:]
        end = rest.split(" ")[0]
        out.append(f"{_short_tolerance(t)} {end if end in ('min', 'max') else rest}")
    return ", ".join(out)


# ------------------------------------------------------------------------- what it takes
def _size(rm) -> float:
    """The relative size of a change (as :meth:`ResultRemedies.best` ranks them)."""
    p = rm.change_pct
    if p is not None:
        return abs(p)
    if rm.change is not None and rm.lever.kind == "temperature" and rm.nominal:
        return abs(100.0 * rm.change / (float(rm.nominal) + 273.15))
    return 1e9


def _change_text(rm) -> str:
    ch = rm.change
    if ch is None:
        return "-"
    pct = rm.change_pct
    return (("+" if ch >= 0 else "") + with_unit(ch, rm.lever.unit)
            + (f" ({pct:+.1f} %)".replace("-", "−") if pct is not None else ""))


def _signature(x) -> tuple:
    """What a reader sees of one result's answers: results with the same signature (the same
    rule, the same lever values and the same results changing) are one row."""
    self_to = "fail" if x.status == "pass" else "pass"
    parts = []
    for rm in x.remedies:
        fx = frozenset((e["rule"], e["item"], e["to"]) for e in rm.side_effects)
        if rm.found and not rm.lever.separable:
            # one input for every item (oil temperature): the same set of results changes,
            # the result itself included; an input of the result's own row (its bearing's
            # clearance): the same other results
            fx = fx | {(x.rule, x.item, self_to)}
        parts.append((rm.lever.id, rm.found, rm.value_text(rm.nominal),
                      rm.value_text() if rm.found else rm.reason, fx))
    return (x.rule, x.status, tuple(parts), tuple(x.conflicts))


def remedy_groups(results: list) -> list[dict]:
    """``ResultRemedies`` with the same answers merged: ``[{"rule", "items", "first",
    "results"}]`` in order of first appearance."""
    groups: dict[tuple, dict] = {}
    for x in results:
        g = groups.setdefault(_signature(x), {"rule": x.rule, "items": [], "first": x,
                                              "results": []})
        g["items"].append(x.item)
        g["results"].append(x)
    return list(groups.values())


def _not_found_text(rms: list) -> str:
    """The levers that found no value, in one line: ``No value within the bounds: Radial
    clearance of that bearing (48 µm), Effective length of that bearing (24.92 mm). Oil grade
    (SAE J300): no standard choice within the table passes.``"""
    pat = re.compile(r"^no value within the bounds( \(.*\))?$")
    bounds = [rm.lever.name + ((m.group(1) or "") if (m := pat.match(rm.reason or "")) else "")
              for rm in rms if pat.match(rm.reason or "")]
    other = [f"{rm.lever.name}: {rm.reason or 'no value'}" for rm in rms
             if not pat.match(rm.reason or "")]
    parts = (["No value within the bounds: " + ", ".join(bounds)] if bounds else []) + other
    return ". ".join(parts) + "."


def _remedy_table(rows: list, css: list, caption: str, at: str) -> dict:
    """A table of remedy rows (:func:`_remedy_rows`); ``at``: the heading of the value column
    ("passes at", "fails at")."""
    return {"type": "table", "css": "remedies", "caption": caption,
            "columns": ["item", "lever", "today", at, "change", "other results that change"],
            "rows": rows, "row_css": css, "widths": [11, 21, 10, 11, 18, 29]}


def _remedy_rows(groups: list[dict], names: dict[str, str]) -> tuple[list, list]:
    """Rows of the what-it-takes table: a title row per rule, then per merged result its
    found levers (smallest change first) and one line for the levers that found none."""
    rows: list[list[Any]] = []
    css: list[str] = []
    rule = None
    for g in groups:
        x = g["first"]
        if g["rule"] != rule:
            rule = g["rule"]
            rows.append([{"text": f"{rule} {names.get(rule, '')}".strip(), "span": 6}])
            css.append("rule-row")
        exclude = {(g["rule"], it) for it in g["items"]}
        found = sorted((rm for rm in x.remedies if rm.found), key=_size)
        missing = [rm for rm in x.remedies if not rm.found]
        item = items_text(g["items"])
        first = True
        for rm in found:
            rows.append([item if first else "", rm.lever.name, rm.value_text(rm.nominal),
                         rm.value_text(), _change_text(rm),
                         effects_text(rm.side_effects, exclude) or "none"])
            css.append("item-start" if first else "")
            first = False
        if missing or not x.remedies:
            text = (_not_found_text(missing) if missing
                    else "No design lever is listed for this rule.")
            rows.append([item if first else "", {"text": text, "span": 5, "css": "none"}])
            css.append("item-start" if first else "")
    return rows, css


def _cell(rm, v: Any) -> Any:
    """A lever value for the workbook: the JSON's number, a choice as its text."""
    return v if isinstance(v, (int, float)) else rm.value_text(v)


def _remedies_sheet(rem: dict) -> dict:
    """Every result and lever with every number of the JSON ``remedies``."""
    def num(v):
        return "" if v is None else v

    rows = []
    for x in rem["results"]:
        for rm in x.remedies:
            d = rm.as_dict()
            rows.append([x.rule, item_label(x.item), x.status, d["name"], d["input"], d["unit"],
                         _cell(rm, d["nominal"]), _cell(rm, d["value"]) if rm.found else "",
                         num(d["change"]), num(d["change_percent"]),
                         num(d["margin_at_value"]), d["reason"] or "", num(d["best_margin"]),
                         "; ".join(f"{e['rule']} {item_label(e['item'])} {e['from']} → {e['to']}"
                                   + (f" ({e['value']:.6g} {e.get('unit') or ''})".replace(
                                       " )", ")") if isinstance(e.get("value"), (int, float))
                                      else "")
                                   for e in rm.side_effects),
                         " ".join(x.conflicts)])
        if not x.remedies:
            rows.append([x.rule, item_label(x.item), x.status,
                         "no design lever is listed for this rule"]
                        + [""] * 11)
    return {"type": "table", "detail": True, "sheet": REMEDIES_SHEET,
            "caption": "Each result and lever: today's value, the value at which the margin"
            " reaches zero, the change, the margin there, the best margin within the bounds"
            " where none was found, and the other results whose status changes (with their"
            " values)",
            "columns": ["rule", "item", "status", "lever", "input cells", "unit", "today",
                        "margin zero at", "change", "change %", "margin at the value",
                        "why none", "best margin within the bounds", "side effects",
                        "conflicts"],
            "rows": rows}


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
        if len(vals) > 6:  # the remedy names the choice it takes
            return f"{vals[0]}, {vals[1]} … {vals[-1]} ({len(vals)} choices)"
        return ", ".join(vals)
    if lv.limits is not None:
        return f"{lv.limits[0]:g}..{lv.limits[1]:g} {lv.unit}".strip()
    return f"{lv.bounds[0]:g}..{lv.bounds[1]:g} × today"


def _lever_rows(levers: list) -> list[list[str]]:
    return [[lv.name, lv.where_text(), ", ".join(lv.rules)
             + (f" ({', '.join(lv.items)})" if lv.items else ""),
             f"{lv.direction}: {_bounds(lv)}"] for lv in levers]


# ------------------------------------------------------------------------- corners
def corner_listed(c) -> bool:
    """True when the corners table lists the result: the tolerances change its status, or
    move its margin by :data:`MOVED` or more while it is within :data:`NEAR` of its limit
    (or beyond it) at the worst corner."""
    if not c.tolerances or c.worst_value is None:
        return False
    if c.worst_status != c.nominal_status:
        return True
    if c.worst_margin is None or c.nominal_margin is None:
        return True
    return abs(c.worst_margin - c.nominal_margin) >= MOVED and c.worst_margin < NEAR


def _corner_groups(results: list, tols: list) -> list[dict]:
    groups: dict[tuple, dict] = {}
    for c in results:
        if not corner_listed(c):
            continue
        at = corner_text(c.corner, tols) + (" (inside the box)" if c.inside else "")
        key = (c.rule, with_unit(c.nominal_value, c.unit), c.nominal_status,
               with_unit(c.worst_value, c.unit), c.worst_status, at)
        g = groups.setdefault(key, {"rule": c.rule, "items": [], "first": c, "at": at})
        g["items"].append(c.item)
    return list(groups.values())


def _status(s: str) -> str:
    return _STATUS.get(s, s)


def _corners_sheet(cor: dict) -> dict:
    def n(v):
        return "" if v is None else float(f"{v:.6g}")

    rows = [[c.rule, item_label(c.item), c.unit, n(c.nominal_value), n(c.nominal_margin),
             _status(c.nominal_status), n(c.worst_value), n(c.worst_margin),
             _status(c.worst_status), "; ".join(c.corner) or "no tolerance affects it",
             "yes" if c.inside else "no", c.design] for c in cor["results"]]
    return {"type": "table", "detail": True, "sheet": CORNERS_SHEET,
            "caption": "Every result at nominal values and at its worst tolerance corner:"
            " value, margin, status, the corner (with the end values) and the corners tried",
            "columns": ["rule", "item", "unit", "nominal value", "nominal margin",
                        "nominal status", "worst-corner value", "worst-corner margin",
                        "worst-corner status", "worst corner", "inside the box",
                        "corners tried"],
            "rows": rows}


def _cells(labels) -> str:
    """``Bearings!F3..F7`` for one column of one sheet, else the cells listed."""
    refs = list(labels)
    m = [re.match(r"^(.+)!([A-Z]+)(\d+)$", r) for r in refs]
    if len(refs) > 1 and all(m) and len({(x.group(1), x.group(2)) for x in m}) == 1:
        nums = sorted(int(x.group(3)) for x in m)
        return f"{m[0].group(1)}!{m[0].group(2)}{nums[0]}..{m[0].group(2)}{nums[-1]}"
    return ", ".join(refs)


def _count(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else (many or one + 's')}"


def _screening_text(rem: dict) -> str:
    from ..remedies.screening import speeds_text

    sp = rem.get("screening_speeds")
    if not sp:
        return ""
    return (" Failing bearing results (film thickness, specific load) were searched at the"
            f" {len(sp)} swept speeds where they are worst today ({speeds_text(sp)}), and each"
            " answer was then checked at every speed.")


@section("remedies", label="remedies and tolerance corners")
def remedies_section(res: CheckResult) -> dict:
    blocks: list[dict] = []
    names = {r.id: r.name for r in res.table.rules}
    rem = res.remedies
    if rem is not None:
        blocks.append({"type": "text", "text": (
            "For every failing result and every passing one within 10 % of its limit, each"
            " design lever listed for its rule was moved from today's value in its allowed"
            " direction until the margin reached zero (bracketed root finding; discrete"
            " levers: the first standard choice that passes); every value given was checked"
            " by a direct evaluation (margin 0 to 0.1 %)." + _screening_text(rem)
            + " At each value the check was run"
            " again (every rule whose status can change there: a result not evaluated for a"
            " blank limit stays so): the other results whose status changes are listed."
            f" {rem['evaluations']} evaluations. Results with the same answers share a row.")})
        fails = remedy_groups([x for x in rem["results"] if x.status != "pass"])
        near = remedy_groups([x for x in rem["results"] if x.status == "pass"])
        rows, css = _remedy_rows(fails, names)
        if rows:
            blocks.append(_remedy_table(rows, css, "Failing results: the value at which each"
                                        " passes (smallest change first; page 1 names it)",
                                        "passes at"))
        conflicts = list(dict.fromkeys(c for x in rem["results"] for c in x.conflicts))
        if conflicts:
            blocks.append({"type": "heading", "text": "Conflicts"})
            blocks.append({"type": "list", "items": conflicts})
        moved = [g for g in near if any(rm.found for rm in g["first"].remedies)]
        still = [g for g in near if g not in moved]
        if moved:
            rows, css = _remedy_rows(moved, names)
            blocks.append(_remedy_table(rows, css, "Passing results within 10 % of their"
                                        " limit: the value beyond which each fails",
                                        "fails at"))
        if still:
            blocks.append({"type": "text", "text": (
                "Passing within 10 % of their limit, and no lever value within its bounds"
                " makes them fail: " + results_text(
                    [(g["rule"], it) for g in still for it in g["items"]]) + ".")})
        blocks.append({"type": "table", "css": "levers",
                       "caption": "Design levers (rules/levers.toml and --levers): the inputs"
                       " a designer moves, the rules they fix, direction and bounds",
                       "columns": ["lever", "input (sheet: column)", "rules",
                                   "direction: bounds"],
                       "rows": _lever_rows(rem["levers"]), "widths": [24, 30, 20, 26]})
        blocks.append(_remedies_sheet(rem))
    cor = res.corners
    if cor is not None:
        tols = cor["tolerances"]
        blocks.append({"type": "heading", "text": "The verdict at the tolerance corners"})
        blocks.append({"type": "text", "text": (
            "Each result is judged at the worst corner of the tolerances that affect it"
            " (all 2^k corners for k ≤ 6, beyond that the corners of the six most influential"
            " with the others at their worse end), with a check that the worst point is not"
            " inside the box (each tolerance set back to the middle of its range; where that"
            " is worse, a golden-section search refines it). "
            f"Verdict at the worst corners: {'FAIL' if _fails(res) else 'PASS'};"
            f" {cor['evaluations']} evaluations.")})
        if tols:
            blocks.append({"type": "table", "caption": "Tolerances (workbook sheet Tolerances)",
                           "columns": ["tolerance", "cells", "min", "today", "max", "source"],
                           "rows": [[_short_tolerance(t), _cells(t.binding.labels),
                                     with_unit(t.low, t.unit, sig=6),
                                     with_unit(t.nominal, t.unit, sig=6),
                                     with_unit(t.high, t.unit, sig=6), t.source or "-"]
                                    for t in tols],
                           "widths": [19, 15, 10, 10, 10, 36]})
        groups = _corner_groups(cor["results"], tols)
        rows, css = [], []
        for g in groups:
            c = g["first"]
            rows.append([f"{g['rule']} {items_text(g['items'])}",
                         f"{with_unit(c.nominal_value, c.unit)} {_status(c.nominal_status)}",
                         f"{with_unit(c.worst_value, c.unit)} {_status(c.worst_status)}",
                         g["at"]])
            css.append("fail" if c.worst_status != "pass" else "")
            if c.worst_status != c.nominal_status:
                css[-1] += " changed"
        affected = [c for c in cor["results"] if c.tolerances]
        n_listed = sum(len(g["items"]) for g in groups)
        n_none = len(cor["results"]) - len(affected)
        n_small = len(affected) - n_listed
        if rows:
            blocks.append({"type": "table", "css": "corners",
                           "caption": "Results whose status or margin the tolerances move"
                           " (nominal and worst-corner value; bold: the status changes)",
                           "columns": ["result", "nominal", "worst corner",
                                       "at (tolerance ends)"],
                           "rows": rows, "row_css": css, "widths": [22, 17, 17, 44]})
        if tols:
            blocks.append({"type": "text", "text": (
                f"Not listed: {_count(n_small, 'result')} whose status the tolerances keep"
                f" and whose margin stays above {NEAR * 100:g} % or moves by less than"
                f" {MOVED * 100:g} % of the limit, and {_count(n_none, 'result')} no"
                " tolerance affects.")})
        else:
            blocks.append({"type": "text", "text": "The workbook declares no tolerances"
                           " (sheet Tolerances): every result is judged at nominal values."})
        blocks.append(_corners_sheet(cor))
    return {"id": "remedies", "title": "What it takes to pass; tolerance corners",
            "intro": "", "blocks": blocks}


def _fails(res: CheckResult) -> bool:
    from ..remedies import corners_fail

    return corners_fail(res)
