"""Compare a baseline workbook with variants: what changed in the inputs, what changed in the
results (status changes first), side-by-side worst cases, and the key curves overlaid.

The same comparison is given as data (``--format json``, for CI: "this change makes JNT-003
fail") and as the design-review pack (PDF)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..api import CheckResult
from ..errors import InputErrors
from ..workbook.schema import SHEETS

# status change classes, in the order a reviewer reads them
CHANGE_ORDER = ("newly failing", "newly passing", "newly not evaluated", "now evaluated",
                "warning changed", "margin changed", "value changed (not evaluated)",
                "new result", "result gone")


@dataclass
class Comparison:
    baseline: CheckResult
    variant: CheckResult
    inputs: list[dict[str, Any]] = field(default_factory=list)
    results: list[dict[str, Any]] = field(default_factory=list)
    n_compared: int = 0  # input cells compared (for "these look like different engines")

    @property
    def different_engines(self) -> bool:
        """Whether so many inputs differ that the two workbooks are rather different engines
        than a variant of one (more than a third of the compared cells, at least 30)."""
        n = len(self.inputs)
        return n >= 30 and n > self.n_compared / 3

    def inputs_text(self) -> str:
        """How many inputs changed, in words (with a hint when the engines differ)."""
        n = len(self.inputs)
        text = f"{n} input change{'s' if n != 1 else ''}"
        if self.different_engines:
            text += (f"; these look like different engines ({n} of {self.n_compared}"
                     " inputs differ)")
        return text

    def to_dict(self) -> dict[str, Any]:
        return {"baseline": Path(self.baseline.engine.source).name,
                "variant": Path(self.variant.engine.source).name,
                "verdict": {"baseline": self.baseline.verdict,
                            "variant": self.variant.verdict},
                "complete": {"baseline": self.baseline.complete,
                             "variant": self.variant.complete},
                "input_changes": self.inputs, "result_changes": self.results,
                "inputs_compared": self.n_compared,
                "different_engines": self.different_engines}


def _text(v: Any) -> str:
    if v is None:
        return ""
    if isinstance(v, float):
        return f"{v:.10g}"
    return str(v).strip()


def _with_unit(value: str, unit: str) -> str:
    """A cell's text with its unit as the user reads it ("30 um"; no unit for "-" or blank)."""
    if not value:
        return "(blank)"
    u = unit.strip() if unit else ""
    return f"{value} {u}" if u and u not in ("-", "1") else value


def input_changes(base_raw, var_raw) -> list[dict[str, Any]]:
    """Every differing input cell (value or unit), addressed as the user sees it."""
    return _input_diff(base_raw, var_raw)[0]


def _input_diff(base_raw, var_raw) -> tuple[list[dict[str, Any]], int]:
    """(the differing input cells, how many input cells were compared)."""
    from openpyxl.utils import get_column_letter

    out: list[dict[str, Any]] = []
    total = [0]
    for name, spec in SHEETS.items():
        a, b = base_raw.sheets.get(name), var_raw.sheets.get(name)
        if spec.shape == "notes":
            continue
        if (a is None) != (b is None):
            total[0] += 1
            out.append({"sheet": name, "cell": name, "what": "sheet",
                        "baseline": "present" if a else "missing",
                        "variant": "present" if b else "missing"})
            continue
        if a is None:
            continue
        if spec.shape == "parameters":
            def rows_by_label(raw):
                d = {}
                for r, row in raw.rows.items():
                    label = _text(row.get(1, (None, None))[0])
                    if r > 1 and label:
                        d[label.lower()] = (r, [_text(row.get(c, (None, None))[0])
                                                for c in (1, 2, 3)])
                return d
            ra, rb = rows_by_label(a), rows_by_label(b)
            for label in sorted(set(ra) | set(rb), key=lambda k: (ra.get(k, rb.get(k))[0])):
                (r1, x), (r2, y) = ra.get(label, (None, None)), rb.get(label, (None, None))
                va = (x[1], x[2]) if x else ("", "")
                vb = (y[1], y[2]) if y else ("", "")
                total[0] += 1
                if va != vb:
                    nm = (x or y)[0]
                    out.append({"sheet": name, "cell": f"{name}!B{r2 or r1}", "what": nm,
                                "baseline": _with_unit(*va), "variant": _with_unit(*vb)})
            continue
        def line(raw, r):
            row = raw.rows.get(r, {})
            n = max(row, default=0)
            return [_text(row.get(c, (None, None))[0]) for c in range(1, n + 1)]
        ha, hb, ua, ub = line(a, 1), line(b, 1), line(a, 2), line(b, 2)
        cols = [c for c in ha if c] + [c for c in hb if c and c not in ha]
        key = None
        if spec.key:
            kf = next(f for f in spec.fields if f.attr == spec.key)
            key = next((c for c in cols if c.lower() in (kf.label.lower(), kf.attr)), None)

        def keyed(raw, hdr, key=key):
            j = hdr.index(key) if key in hdr else None
            d = {}
            for r in sorted(raw.rows):
                if r < 3:
                    continue
                vals = line(raw, r)
                shown = vals[j] if j is not None and j < len(vals) and vals[j] else f"row {r}"
                # matched case-insensitively, shown as the user typed it
                d[shown.lower()] = (r, {hdr[i]: v for i, v in enumerate(vals)
                                        if i < len(hdr) and hdr[i]}, shown)
            return d
        da, db = keyed(a, ha), keyed(b, hb)
        for c in cols:
            i, k = (ha.index(c) if c in ha else None), (hb.index(c) if c in hb else None)
            u1 = ua[i] if i is not None and i < len(ua) else ""
            u2 = ub[k] if k is not None and k < len(ub) else ""
            total[0] += 1
            if u1 != u2:
                col = get_column_letter((k if k is not None else i) + 1)
                out.append({"sheet": name, "cell": f"{name}!{col}2", "what": f"unit of '{c}'",
                            "baseline": u1 or "(blank)", "variant": u2 or "(blank)"})
        for rk in list(da) + [x for x in db if x not in da]:
            (r1, x, s1), (r2, y, s2) = (da.get(rk, (None, None, None)),
                                        db.get(rk, (None, None, None)))
            shown = s2 or s1
            if x is None or y is None:
                total[0] += 1
                out.append({"sheet": name, "cell": f"{name}!A{r2 or r1}",
                            "what": f"row '{shown}'", "baseline": "present" if x else "missing",
                            "variant": "present" if y else "missing"})
                continue
            for c in cols:
                total[0] += 1
                if x.get(c, "") != y.get(c, ""):
                    k = hb.index(c) if c in hb else ha.index(c)
                    unit = (ub[k] if k < len(ub) else "") if c in hb else ""
                    out.append({"sheet": name, "cell": f"{name}!{get_column_letter(k + 1)}{r2}",
                                "what": f"{shown}: {c}",
                                "baseline": _with_unit(x.get(c, ""), unit),
                                "variant": _with_unit(y.get(c, ""), unit)})
    return out, total[0]


def _state(r) -> str:
    if r is None:
        return "absent"
    if r.status == "fail" and r.severity == "warning" and not r.internal_error:
        return "warning"
    return r.status


def result_changes(base: CheckResult, var: CheckResult) -> list[dict[str, Any]]:
    """Results that differ, status changes first, then the largest margin changes. A rule
    that does not apply (``not_applicable``) has no result to compare: one that applies on one
    side only is a new result or a result gone."""
    a = {(r.rule, r.item): r for r in base.results if r.status != "not_applicable"}
    b = {(r.rule, r.item): r for r in var.results if r.status != "not_applicable"}
    out = []
    for k in list(a) + [x for x in b if x not in a]:
        ra, rb = a.get(k), b.get(k)
        sa, sb = _state(ra), _state(rb)
        if ra is None:
            kind = "new result"
        elif rb is None:
            kind = "result gone"
        elif sa != "fail" and sb == "fail":
            kind = "newly failing"
        elif sa == "fail" and sb != "fail" and sb != "not_evaluated":
            kind = "newly passing"
        elif sb == "not_evaluated" and sa != "not_evaluated":
            kind = "newly not evaluated"
        elif sa == "not_evaluated" and sb != "not_evaluated":
            kind = "now evaluated"
        elif sa != sb:
            kind = "warning changed"
        else:
            kind = "margin changed"
        ma = None if ra is None else ra.margin
        mb = None if rb is None else rb.margin
        dm = None if ma is None or mb is None else mb - ma
        if kind == "margin changed":
            if dm is None:
                # no margin on one side (both not evaluated: a computed value without a
                # limit): only a moved value is worth a line, and never as a margin change
                if ra.value == rb.value:
                    continue
                kind = "value changed (not evaluated)"
            elif abs(dm) < 1e-6 and ra.value == rb.value:
                continue
        r0 = rb or ra
        out.append({"rule": k[0], "item": k[1], "name": r0.name, "change": kind,
                    "baseline": _side(ra), "variant": _side(rb),
                    "margin_change": None if dm is None else float(f"{dm:.4g}")})
    out.sort(key=lambda d: (CHANGE_ORDER.index(d["change"]),
                            -abs(d["margin_change"] or 0.0), d["rule"], d["item"]))
    return out


def _side(r) -> dict[str, Any] | None:
    if r is None:
        return None
    d = r.as_dict()
    return {"status": _state(r), "value": d["value"], "unit": d["unit"],
            "limit": d["limit_text"], "margin": d["margin"], "case": d["case"]}


def compare(baseline: str | Path, variants: list[str | Path], select=None, ignore=None,
            fail_on: str = "error") -> list[Comparison]:
    """Check the baseline and every variant with the same rules; one comparison per variant."""
    from .. import api
    from ..workbook.loader import read_raw_workbook

    def checked(path):
        try:
            return api.check(path, select=select, ignore=ignore, fail_on=fail_on)
        except InputErrors as exc:  # say which of the workbooks it is
            raise InputErrors(exc.errors, exc.warnings, source=Path(path).name,
                              follow_on=exc.follow_on) from None

    base_res = checked(baseline)
    base_raw = read_raw_workbook(baseline)
    out = []
    for v in variants:
        res = checked(v)
        diff, n = _input_diff(base_raw, read_raw_workbook(v))
        out.append(Comparison(base_res, res, diff, result_changes(base_res, res), n))
    return out
