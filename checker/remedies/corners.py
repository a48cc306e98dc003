"""The verdict at the tolerance corners.

The workbook's ``Tolerances`` sheet declares ranges of inputs (bearing clearance, oil supply
temperature, tightening torque and friction or VDI 2230's tightening factor, peak pressure,
material minimum strength): ``sheet | row | column | min | max | unit``; blank min or max =
today's value; unit ``% of nominal`` = deviations in percent. Each result is judged at the
worst corner of the tolerances that affect it:

1. one at a time: each tolerance at its min and at its max alone (all rules): a tolerance
   affects a result when its margin moves, and the size of the move ranks the tolerances;
2. the corners: all 2^k corners of the k tolerances affecting a group of results for
   k <= :data:`FULL_K`; beyond, the 2^FULL_K corners of the FULL_K most influential ones with
   the others at their worse end found in step 1 (the design is stated with the result);
3. the worst point is not inside the box: at each result's worst corner every tolerance is
   set back to its middle (the face midpoint); where that is worse than the corner the
   response is not monotonic and the worst point along it is refined (golden section); the
   nominal point itself is also compared.

The verdict uses the worst point: a result that passes at nominal and fails there fails.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Any

from ..errors import InputError, InputErrors
from ..ruletable import REL_TOL
from ..workbook.schema import SHEETS
from .variants import Binding, Evaluator, bind, find

FULL_K = 6
GOLDEN_STEPS = 8
TIGHTENING_FACTOR = "tightening factor"


@dataclass
class Tolerance:
    name: str  # "Bearings radial clearance (M1, M2)"
    where: str  # the Tolerances row, e.g. Tolerances!A3
    binding: Binding
    low: Any  # lever-unit value of the first cell at the low end
    high: Any
    nominal: Any
    source: str = ""
    unit: str = ""

    def value(self, u: float) -> float:
        """The value at the box coordinate ``u`` (0 = low, 1 = high)."""
        return self.low + u * (self.high - self.low)

    def end_text(self, u: float) -> str:
        from ..display import with_unit

        v = self.value(u)
        end = "min" if u == 0 else "max" if u == 1 else f"{u:.2f}"
        return f"{self.name} {end} ({with_unit(v, self.unit)})"


def _num(x) -> float | None:
    if x is None:
        return None
    try:
        return float(x)
    except (TypeError, ValueError):
        return None


def read_tolerances(base: Any) -> list[Tolerance]:
    """The Tolerances sheet of the base workbook (raises InputErrors naming the cells)."""
    from ..study.apply import _cell, _text
    from ..units import UnitProblem, to_si

    raw = base.sheets.get("Tolerances")
    if raw is None:
        return []
    cols: dict[str, int] = {}
    for j, (v, _) in sorted(raw.rows.get(1, {}).items()):
        cols[_text(v).lower()] = j
    errs: list[InputError] = []
    out: list[Tolerance] = []
    for r in sorted(raw.rows):
        if r < 3:
            continue

        def get(name: str, r: int = r):
            j = cols.get(name)
            return None if j is None else _cell(raw, r, j)
        sheet_in = _text(get("sheet"))
        if not sheet_in:
            continue
        at = f"Tolerances!A{r}"
        sheet = next((s for s in SHEETS if s.lower() == sheet_in.lower()), None)
        if sheet is None or SHEETS[sheet].shape == "notes":
            errs.append(InputError(at, f"unknown sheet '{sheet_in}'"))
            continue
        spec = SHEETS[sheet]
        column = _text(get("column"))
        row = _text(get("row"))
        unit = _text(get("unit"))
        lo_raw, hi_raw = _num(get("min")), _num(get("max"))
        rel = unit.lower().replace(" ", "") in ("%ofnominal", "%nominal", "percentofnominal")
        tf = column.lower() == TIGHTENING_FACTOR
        fname = "tightening torque" if tf else (column if spec.shape == "table" else
                                                column or row)
        f = next((x for x in spec.fields if fname.lower() in (x.label.lower(),
                                                              x.attr.lower())), None)
        if f is None or f.kind in ("text", "choice", "int_list"):
            errs.append(InputError(f"Tolerances!C{r}", f"sheet {sheet} has no numeric"
                                   f" {'column' if spec.shape == 'table' else 'parameter'}"
                                   f" '{fname}'"))
            continue
        rows: tuple[str, ...] | None = None
        where: tuple[tuple[str, str], ...] = ()
        if spec.shape == "table":
            if "=" in row:
                k, v = (x.strip() for x in row.split("=", 1))
                wf = next((x for x in spec.fields if k.lower() in (x.label.lower(),
                                                                   x.attr.lower())), None)
                if wf is None:
                    errs.append(InputError(f"Tolerances!B{r}", f"sheet {sheet} has no column"
                                           f" '{k}'"))
                    continue
                where = ((wf.attr, v),)
            elif row and row.lower() != "all":
                rows = tuple(x.strip() for x in row.split(",") if x.strip())
            elif not row:
                errs.append(InputError(f"Tolerances!B{r}", "name the row: a key, 'all' or"
                                       " 'column = value'"))
                continue
        bunit = "N m" if tf else ("" if rel else unit)
        if not rel and not tf and f.kind != "int":
            try:
                to_si(1.0, unit or None, f.kind)
            except UnitProblem as exc:
                errs.append(InputError(f"Tolerances!F{r}", f"unit '{unit}' does not fit"
                                       f" {f.label}: {exc}"))
                continue
        if rel or tf:
            # relative: bind in the first cell's own unit through SI ("" unit = SI)
            from ..units import KINDS

            bunit = KINDS[f.kind].example if f.kind in KINDS else ""
            bunit = "N m" if tf else bunit
            if f.kind == "temperature" and rel:
                errs.append(InputError(f"Tolerances!F{r}", "a temperature tolerance needs"
                                       " min and max in °C, not percent"))
                continue
        b = bind(base, sheet, (f,), bunit, rows, where)
        if isinstance(b, str):
            errs.append(InputError(f"Tolerances!B{r}", b))
            continue
        nom = b.nominal[0]
        if not isinstance(nom, (int, float)):
            errs.append(InputError(f"Tolerances!C{r}", f"{f.label} of {sheet} is blank: a"
                                   " tolerance needs today's value"))
            continue
        if tf:
            if hi_raw is None or hi_raw < 1:
                errs.append(InputError(f"Tolerances!E{r}", "tightening factor: give alpha_A"
                                       " >= 1 in max (VDI 2230, Table A8)"))
                continue
            a = hi_raw
            lo, hi = nom * 2.0 / (1.0 + a), nom * 2.0 * a / (1.0 + a)
        elif rel:
            lo = nom * (1 + (lo_raw or 0.0) / 100.0)
            hi = nom * (1 + (hi_raw or 0.0) / 100.0)
        else:
            lo = nom if lo_raw is None else lo_raw
            hi = nom if hi_raw is None else hi_raw
        if lo > hi:
            errs.append(InputError(f"Tolerances!D{r}", f"min {lo_raw} is above max {hi_raw}"))
            continue
        if lo == hi:
            continue
        rows_txt = row if row else ""
        name = f"{sheet} {'tightening torque (alpha_A ' + f'{hi_raw:g})' if tf else f.label}" + (
            f" ({rows_txt})" if rows_txt else "")
        out.append(Tolerance(name, at, b, lo, hi, nom, _text(get("source")),
                             unit if not (rel or tf) else bunit))
    if errs:
        raise InputErrors(errs)
    return out


@dataclass
class CornerResult:
    rule: str
    item: str
    nominal_status: str
    nominal_value: float | None
    nominal_margin: float | None
    worst_value: float | None = None
    worst_margin: float | None = None
    worst_status: str = ""
    corner: list[str] = field(default_factory=list)  # texts per tolerance end
    tolerances: list[str] = field(default_factory=list)
    design: str = ""
    inside: bool = False  # the worst point is inside the box (not monotonic)
    unit: str = ""
    severity: str = "error"

    def as_dict(self) -> dict:
        def n(x):
            return None if x is None else float(f"{x:.6g}")
        return {"rule": self.rule, "item": self.item, "unit": self.unit,
                "nominal": {"value": n(self.nominal_value), "margin": n(self.nominal_margin),
                            "status": self.nominal_status},
                "worst": {"value": n(self.worst_value), "margin": n(self.worst_margin),
                          "status": self.worst_status, "at": self.corner,
                          "inside_the_box": self.inside},
                "tolerances": self.tolerances, "design": self.design}


def _changes(tols: list[Tolerance], u: dict[int, float]) -> dict:
    ch: dict = {}
    for i, t in enumerate(tols):
        if i in u:
            ch.update(t.binding.changes(t.value(u[i])))
    return ch


def _margins(res) -> dict[tuple[str, str], float]:
    if isinstance(res, InputErrors) or res is None:
        return {}
    return {(r.rule, r.item): float(r.margin) for r in res.results
            if r.margin is not None and r.status != "not_evaluated"}


def evaluate_corners(nominal, ev: Evaluator, tols: list[Tolerance]) -> list[CornerResult]:
    """Each evaluated result of ``nominal`` judged at its worst tolerance corner."""
    base_m = _margins(nominal)
    results = {(r.rule, r.item): r for r in nominal.results
               if r.margin is not None and r.status != "not_evaluated"}
    if not tols:
        return []
    # 1. one at a time (all selected rules)
    oat_points = [{i: 0.0} for i in range(len(tols))] + [{i: 1.0} for i in range(len(tols))]
    known: dict[tuple, Any] = {}  # every evaluated point: its check (reused at the end)

    def run(points: list[dict], select=None) -> list:
        out_r = ev.evaluate_variants([_changes(tols, u) for u in points], select=select)
        for u, r in zip(points, out_r):
            known.setdefault(tuple(sorted(u.items())), r)
        return out_r

    oat = run(oat_points)
    oat_m = [_margins(r) for r in oat]
    n = len(tols)
    affects: dict[tuple[str, str], list[int]] = {}
    effect: dict[tuple[tuple[str, str], int], float] = {}
    worse_end: dict[tuple[tuple[str, str], int], float] = {}
    for key, m0 in base_m.items():
        for i in range(n):
            lo, hi = oat_m[i].get(key), oat_m[n + i].get(key)
            if lo is None or hi is None:
                continue
            d = max(abs(lo - m0), abs(hi - m0))
            if d > 1e-9 * max(1.0, abs(m0)):
                affects.setdefault(key, []).append(i)
                effect[(key, i)] = d
                worse_end[(key, i)] = 0.0 if lo < hi else 1.0
    # 2. corners per group of results with the same tolerances
    groups: dict[tuple[int, ...], list[tuple[str, str]]] = {}
    for key, idx in affects.items():
        groups.setdefault(tuple(sorted(idx)), []).append(key)
    out: dict[tuple[str, str], CornerResult] = {}
    for idx, keys in groups.items():
        design = f"all {2 ** len(idx)} corners of {len(idx)} tolerances"
        full = list(idx)
        fixed: dict[int, float] = {}
        if len(idx) > FULL_K:
            score = {i: sum(effect.get((k, i), 0.0) for k in keys) for i in idx}
            full = sorted(idx, key=lambda i: -score[i])[:FULL_K]
            for i in idx:
                if i not in full:
                    ends = [worse_end.get((k, i), 0.0) for k in keys]
                    fixed[i] = 1.0 if sum(ends) * 2 >= len(ends) else 0.0
            design = (f"2^{FULL_K} corners of the {FULL_K} most influential of {len(idx)}"
                      " tolerances (one-at-a-time ranking), the others at their worse end")
        corners = [dict(zip(full, c), **fixed) for c in itertools.product((0.0, 1.0),
                                                                          repeat=len(full))]
        if len(idx) == 1:
            cm = [oat_m[idx[0]], oat_m[n + idx[0]]]
        else:
            sel = sorted({k[0] for k in keys})
            cm = [_margins(r) for r in run(corners, select=sel)]
        for key in keys:
            ms = [(m.get(key), c) for m, c in zip(cm, corners) if m.get(key) is not None]
            if not ms:
                continue
            m_w, c_w = min(ms, key=lambda t: t[0])
            r = results[key]
            cr = CornerResult(key[0], key[1], r.status, r.value, r.margin, unit=r.unit,
                              severity=r.severity, design=design,
                              tolerances=[tols[i].name for i in idx])
            cr.worst_margin = m_w
            cr._u = dict(c_w)
            out[key] = cr
    # 3. is the worst point inside the box? face midpoints at each worst corner
    probes: list[tuple[tuple[str, str], int, dict]] = []
    for key, cr in out.items():
        for i in cr._u:
            u = dict(cr._u)
            u[i] = 0.5
            probes.append((key, i, u))
    uniq: dict[tuple, int] = {}
    pts: list[dict] = []
    rules_at: list[set[str]] = []
    for key, _, u in probes:
        k = tuple(sorted(u.items()))
        if k not in uniq:
            uniq[k] = len(pts)
            pts.append(u)
            rules_at.append(set())
        rules_at[uniq[k]].add(key[0])
    sel = sorted({k[0] for k in out})
    # each probe checked on the rules of the results probed there (one call per selection)
    pm: list[dict] = [{} for _ in pts]
    by_sel: dict[tuple[str, ...], list[int]] = {}
    for i, rs in enumerate(rules_at):
        by_sel.setdefault(tuple(sorted(rs)), []).append(i)
    for rs, idx in by_sel.items():
        for i, r in zip(idx, run([pts[i] for i in idx], select=list(rs))):
            pm[i] = _margins(r)
    refine: dict[tuple[str, str], list[int]] = {}
    for key, i, u in probes:
        m = pm[uniq[tuple(sorted(u.items()))]].get(key)
        cr = out[key]
        if m is not None and m < cr.worst_margin - 1e-9 * max(1.0, abs(cr.worst_margin)):
            refine.setdefault(key, []).append(i)
            if m < cr.worst_margin:
                cr.worst_margin, cr._u = m, u
                cr.inside = True
        if base_m[key] < cr.worst_margin:
            cr.worst_margin, cr._u, cr.inside = base_m[key], {}, True
    for key, dims in refine.items():
        cr = out[key]
        for i in dims:
            _golden(cr, key, i, run)
    # values and statuses at the worst point (one evaluation per distinct point)
    pts2: dict[tuple, dict] = {}
    for cr in out.values():
        pts2.setdefault(tuple(sorted(cr._u.items())), cr._u)
    need = {k: u for k, u in pts2.items() if k != () and k not in known}
    run(list(need.values()), select=sel)
    for key, cr in out.items():
        pk = tuple(sorted(cr._u.items()))
        r = find(nominal, *key) if pk == () else find(known.get(pk), *key)
        if r is None:
            r = find(run([cr._u], select=[key[0]])[0], *key)
        if r is not None:
            cr.worst_value, cr.worst_margin, cr.worst_status = r.value, r.margin, r.status
        cr.corner = [tols[i].end_text(u) for i, u in sorted(cr._u.items())] or [
            "nominal (the worst point is today's value)"]
    for key, r in results.items():  # results no tolerance affects: worst = nominal
        if key not in out:
            out[key] = CornerResult(key[0], key[1], r.status, r.value, r.margin, r.value,
                                    r.margin, r.status, ["unaffected by the tolerances"],
                                    unit=r.unit, severity=r.severity, design="-")
    order = {(r.rule, r.item): k for k, r in enumerate(nominal.results)}
    return sorted(out.values(), key=lambda c: order.get((c.rule, c.item), 0))


def _golden(cr: CornerResult, key, i: int, run) -> None:
    """Refine the worst point along tolerance ``i`` (golden-section search on [0, 1])."""
    g = (math.sqrt(5) - 1) / 2
    a, b = 0.0, 1.0

    def f(x: float) -> float:
        u = dict(cr._u)
        u[i] = x
        m = _margins(run([u], select=[key[0]])[0]).get(key)
        m = math.inf if m is None else m
        if m < cr.worst_margin:
            cr.worst_margin, cr._u = m, u
        return m

    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(GOLDEN_STEPS):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)


def verdict_fails(corners: list[CornerResult], fail_on: str = "error") -> bool:
    """True when an error-severity result fails at its worst point."""
    sev = ("error", "warning") if "warning" in fail_on else ("error",)
    return any(c.worst_status == "fail" and c.severity in sev for c in corners)


_ = REL_TOL
