"""The report's first pages: rule results grouped for a reader (formatting only).

Failures first, then warnings, results that could not be evaluated, and passes; within each
group one item's results sit together; a finding repeated on several items (the same rule,
value, limit and case, e.g. four identical big-end bearings) is one row naming every item.
With ``--remedies`` / ``--corners`` a failure's note adds what it takes to pass (the smallest
change and the other results it changes) and its worst tolerance corner; results with the same
answers stay one row.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from ..api import CheckResult
from ..evaluation.ruletable import RuleResult
from ..results.display import CELL_REF, item_label

GROUPS = (
    ("fail", "Failed", "fail"),
    ("warning", "Warnings", "warn"),
    ("not_evaluated", "Not evaluated", "ne"),
    ("pass", "Passed", "pass"),
    ("not_applicable", "Not applicable", "na"),
)
"""(kind, heading, CSS class) in the order the report shows them."""

LOOK_FIRST = 5
"""How many passing findings closest to their limits page 1 lists."""


@dataclass
class Row:
    """One line of a results table: a finding and the items it applies to."""

    kind: str  # fail | warning | not_evaluated | pass | not_applicable
    rule: str
    name: str
    items: list[str]
    case: str
    value: str
    limit: str
    margin: str
    note: str
    override: str
    margin_value: float | None
    results: list[RuleResult] = field(default_factory=list)
    first_of_item: bool = True

    @property
    def item_text(self) -> str:
        return ", ".join(item_label(x) for x in self.items)

    @property
    def css(self) -> str:
        return {"fail": "fail", "warning": "warn", "not_evaluated": "ne", "pass": "pass",
                "not_applicable": "na"}[self.kind]


def kind(r: RuleResult) -> str:
    """The group of a result: failed (an error, or any internal error), warning (a failed
    warning-severity rule), not evaluated, passed."""
    if r.status == "fail":
        return "warning" if r.severity == "warning" and not r.internal_error else "fail"
    return r.status


def _note(r: RuleResult) -> str:
    """The note under a row: why a result is not evaluated or an internal error, or the
    first finding of a failed result (passes carry their findings in the module section).
    What it takes to pass and the worst tolerance corner follow (:class:`_Extras`)."""
    if r.status == "not_applicable":
        return r.message
    if r.status == "not_evaluated":
        # the computed value of a rule without its limit is shown in the module section
        return re.sub(r" \(computed, not judged: [^)]*\)$", "", r.message)
    if r.internal_error:
        return r.message
    if not r.findings or r.status == "pass":
        return ""
    first = r.findings[0]
    more = len(r.findings) - 1
    return first + (f" (and {more} more finding{'s' if more > 1 else ''} in the module"
                    " section)" if more else "")


class _Extras:
    """--remedies / --corners (:mod:`checker.remedies`): per result what it takes to pass
    and the worst tolerance corner, as page 1 says them; results with the same answers
    (four identical big ends) share a row, which names its own items once."""

    def __init__(self, res: CheckResult):
        rem, cor = getattr(res, "remedies", None), getattr(res, "corners", None)
        self.rem = {(x.rule, x.item): x for x in (rem or {}).get("results", [])}
        self.cor = {(c.rule, c.item): c for c in (cor or {}).get("results", [])}
        self.tols = (cor or {}).get("tolerances", [])

    def key(self, r: RuleResult) -> tuple:
        """What the extra text of ``r`` depends on (equal keys: one row)."""
        if r.status == "pass":
            return ()
        from .section_remedies import _signature, corner_text

        x = self.rem.get((r.rule, r.item))
        c = self.cor.get((r.rule, r.item))
        ck = None
        if c is not None and c.tolerances and c.worst_value is not None:
            ck = (c.worst_value, c.worst_status, corner_text(c.corner, self.tols), c.inside)
        return (_signature(x) if x is not None else r.what_it_takes,
                ck if c is not None else r.worst_corner)

    def text(self, results: list[RuleResult]) -> str:
        """``To pass: ... At the tolerance corners: ...`` for a row of ``results``."""
        r = results[0]
        if r.status == "pass":
            return ""
        from ..results.display import with_unit
        from .section_remedies import corner_text, effects_text

        mine = {(x.rule, x.item) for x in results}
        parts = []
        x = self.rem.get((r.rule, r.item))
        if x is None:
            parts.append(r.what_it_takes)
        elif not x.remedies:
            parts.append("What it takes to pass: no design lever is listed for this rule")
        elif x.status != "pass":
            b = x.best()
            if b is None:
                txt = "no lever of the table passes it within its bounds"
            else:
                fx = effects_text(b.side_effects, mine, sep=", ")
                txt = b.text() + (f"; side effects {fx}" if fx else
                                  "; no other result changes")
            if x.conflicts:
                txt += (". " + x.conflicts[0].split(" (")[0]
                        + ": see 'What it takes to pass'")
            parts.append("To pass: " + txt)
        c = self.cor.get((r.rule, r.item))
        if c is None:
            parts.append(r.worst_corner and "At the tolerance corners: " + r.worst_corner)
        elif c.tolerances and c.worst_value is not None:
            parts.append(f"At the tolerance corners: {with_unit(c.worst_value, r.unit)}"
                         f" {c.worst_status} at {corner_text(c.corner, self.tols)}"
                         + (" (inside the box)" if c.inside else ""))
        return " ".join(p + "." for p in parts if p)




def _cell_span(refs: list[str]) -> str:
    """``Sheet!S2, Sheet!S3, ...`` as ``Sheet!S2..S10`` when one column of one sheet."""
    if not refs:
        return ""
    sheets = {r.split("!")[0] for r in refs}
    cols = {re.sub(r"[0-9]+$", "", r.split("!")[1]) for r in refs}
    if len(sheets) == 1 and len(cols) == 1 and len(refs) > 1:
        nums = sorted(int(re.sub(r"^[A-Z]+", "", r.split("!")[1])) for r in refs)
        col = cols.pop()
        return f"{sheets.pop()}!{col}{nums[0]}..{col}{nums[-1]}"
    return ", ".join(dict.fromkeys(refs))


def rows(res: CheckResult, results: list[RuleResult] | None = None) -> list[Row]:
    """Rows of ``results`` (default: all), identical findings on several items merged,
    ordered by group, then item (order of first appearance), then rule."""
    results = res.results if results is None else results
    item_order: dict[str, int] = {}
    for r in res.results:
        item_order.setdefault(r.item, len(item_order))
    merged: dict[tuple, Row] = {}
    cells: dict[tuple, list[list[str]]] = {}
    extras = _Extras(res)
    for r in results:
        k = kind(r)
        value = "-" if r.value is None else r.value_text
        note = _note(r)
        pattern, case = note, r.case
        if k in ("not_evaluated", "not_applicable"):
            # shown with the missing inputs, not by value; the same missing input on several
            # items (one cell each) is one row
            pattern = CELL_REF.sub("\x00", note).replace(r.item, "\x01") if r.item else note
            value, case = "-", ""
        key = (k, r.rule, case, value, r.limit, pattern, r.override, extras.key(r))
        row = merged.get(key)
        cells.setdefault(key, []).append(CELL_REF.findall(note))
        if row is None:
            merged[key] = Row(k, r.rule, r.name, [r.item], case or "-", value, r.limit,
                              r.margin_text or "-", note,
                              r.override, r.margin, [r])
        else:
            row.items.append(r.item)
            row.results.append(r)
    for key, row in merged.items():
        if row.kind in ("not_evaluated", "not_applicable") and len(row.items) > 1:
            text = key[5].replace("\x01", "each listed item")
            for j in range(text.count("\x00")):
                refs = [c[j] for c in cells[key] if len(c) > j]
                text = text.replace("\x00", _cell_span(refs), 1)
            row.note = text
    for row in merged.values():
        extra = extras.text(row.results)
        if extra:
            row.note = (row.note + " " + extra) if row.note else extra
    order = {g[0]: i for i, g in enumerate(GROUPS)}
    out = sorted(merged.values(), key=lambda x: (order[x.kind], item_order.get(x.items[0], 0),
                                                 x.rule, x.case))
    prev = None
    for x in out:
        x.first_of_item = (x.kind, x.item_text) != prev
        prev = (x.kind, x.item_text)
    return out


def groups(res: CheckResult) -> list[dict]:
    """``[{"kind", "title", "css", "rows", "count"}]`` in report order (empty groups left
    out); ``count`` is the number of results, ``rows`` the merged findings."""
    all_rows = rows(res)
    out = []
    for k, title, css in GROUPS:
        rs = [x for x in all_rows if x.kind == k]
        if rs:
            out.append({"kind": k, "title": title, "css": css, "rows": rs,
                        "count": sum(len(x.results) for x in rs)})
    return out


def look_first(res: CheckResult, n: int = LOOK_FIRST) -> list[Row]:
    """The passing findings closest to their limits (smallest relative margin first)."""
    ps = [x for x in rows(res, [r for r in res.results if r.status == "pass"])
          if x.margin_value is not None]
    ps.sort(key=lambda x: x.margin_value)
    for x in ps:
        x.first_of_item = True
    return ps[:n]
