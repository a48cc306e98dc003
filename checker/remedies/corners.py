"""The verdict at the tolerance corners.

The workbook's ``Tolerances`` sheet declares ranges of inputs (bearing clearance, oil supply
temperature, tightening torque and friction or VDI 2230's tightening factor, peak pressure,
material minimum strength): ``sheet | row | column | min | max | unit``; blank min or max =
today's value; unit ``% of nominal`` = deviations in percent. Each result is judged at the
worst corner of the tolerances that move it:

0. which tolerances can move which result is read from the calculation graph, without
   evaluating (:mod:`checker.remedies.influence`: the inputs a tolerance changes, the
   calculations that read them and everything downstream, the rule's quantity; a bearing's
   clearance moves only the bearings of its type); where the structure cannot tell, every
   tolerance can;
1. the corners: all 2^k corners of the k tolerances that can move a result, for
   k <= :data:`FULL_K`; the tolerances that do move it are those whose flip between two
   corners changes its margin (a result no tolerance moves is "unaffected"). For more than
   FULL_K tolerances, each one at its min and at its max alone first (one at a time: which
   move it, and by how much), then the 2^FULL_K corners of the FULL_K most influential with
   the others at their worse end (the design is stated with the result);
2. the worst point is not inside the box: at each result's worst corner every tolerance is
   set back to its middle (the face midpoint); where that is worse than the corner the
   response is not monotonic and the worst point along it is refined (golden section); the
   nominal point itself is also compared;
3. the value and status at the worst point, read from the evaluation there.

Every evaluation is a check of the workbook at a point of the box, and every point a result
needs is evaluated directly: a result's point fixes the tolerances that can move it (those
that do not move it at today's value), so points of results that no common tolerance moves
share one variant (the corners of the main bearings' films with those of the big ends', each
clearance at its own end). A variant is checked on the rules of the results it serves; the
variants of a step are checked in batches (:class:`_Packer`). On the I4 template the 55
evaluations of one at a time over every rule followed by one variant per corner became 19.

The verdict uses the worst point: a result that passes at nominal and fails there fails.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Any

from ..errors import InputError, InputErrors
from ..evaluation.ruletable import REL_TOL
from ..workbook.schema import SHEETS
from .variants import Binding, Evaluator, bind, find

FULL_K = 6
MERGE_SLACK = 0.05
"""Seconds of calculations a variant's own rules do not need that it may run to be checked
in the same batch as others (:class:`_Packer`)."""
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
        from ..results.display import with_unit

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
    from ..workbook.units import UnitProblem, to_si

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
            from ..workbook.units import KINDS

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


class _Packer:
    """Evaluations of results at points of the tolerance box, packed into few variants.

    A request ``(result, point)`` (``point``: tolerance index -> box coordinate, absent =
    today's value) needs a variant equal to the point on the tolerances that can move the
    result (:func:`checker.remedies.influence.affecting`); the other tolerances are free, so
    requests of results that no common tolerance moves share a variant (a main bearing's
    clearance at its min with a big end's clearance at its min). Every variant is a check of
    the workbook on the rules of the requests it serves, so each result read from it is the
    result of a direct evaluation at its point (its calculations have the same inputs there:
    the calculation cache would return them). Variants already evaluated serve later requests
    they fit, today's check among them."""

    def __init__(self, ev: Evaluator, tols: list[Tolerance], infl, nominal) -> None:
        self.ev, self.tols, self.infl, self.affects = ev, tols, infl, infl.affects
        self.done: list[tuple[dict[int, float], set[str] | None, Any]] = [({}, None, nominal)]
        self.computed: set[tuple] = set()  # calculations of the variants checked so far

    def _need(self, key, point: dict[int, float]) -> dict[int, float | None]:
        return {i: point.get(i) for i in self.affects[key]}

    def _serving(self, key, need) -> Any:
        for pt, rules, res in self.done:
            if (rules is None or key[0] in rules) and not isinstance(res, InputErrors) and all(
                    pt.get(i) == u for i, u in need.items()):
                return res
        return _NONE

    def ask(self, requests: list[tuple[tuple[str, str], dict[int, float]]]) -> list[Any]:
        """The check (or InputErrors) that serves each request."""
        out: list[Any] = [_NONE] * len(requests)
        packs: list[tuple[dict[int, float | None], set[str], list[int]]] = []
        # first fit, the requests that fix the most tolerances first
        for n in sorted(range(len(requests)), key=lambda n: -len(self.affects[requests[n][0]])):
            key, point = requests[n]
            need = self._need(key, point)
            hit = self._serving(key, need)
            if hit is not _NONE:
                out[n] = hit
                continue
            for c, rules, ns in packs:
                if all(c.get(i, u) == u for i, u in need.items()):
                    c.update(need)
                    rules.add(key[0])
                    ns.append(n)
                    break
            else:
                packs.append((dict(need), {key[0]}, [n]))
        got = self._run([({i: u for i, u in c.items() if u is not None}, rules)
                         for c, rules, _ in packs])
        for (_, _, ns), res in zip(packs, got):
            by_need: dict[tuple, list[int]] = {}
            for n in ns:
                need = self._need(*requests[n])
                by_need.setdefault(tuple((i, u) for i, u in sorted(need.items())
                                         if u is not None), []).append(n)
            if isinstance(res, InputErrors) and len(by_need) > 1:
                # a packed variant is not a valid workbook: each point of it alone
                alone = self._run([(dict(k), {requests[n][0][0] for n in v})
                                   for k, v in by_need.items()])
                for v, r in zip(by_need.values(), alone):
                    for n in v:
                        out[n] = r
                continue
            for n in ns:
                out[n] = res
        return out

    def _run(self, variants: list[tuple[dict[int, float], set[str]]]) -> list[Any]:
        """Check the variants in few batches (their film orbits in one kernel call): a
        variant joins a batch, checked on the rules of all its variants, unless that runs
        calculations its own rules do not need (by today's times, beyond
        :data:`MERGE_SLACK`)."""
        infl = self.infl
        batches: list[tuple[set[str], list[int], set[tuple] | None]] = []
        for k in sorted(range(len(variants)), key=lambda k: -len(variants[k][1])):
            v, rules = variants[k]
            own = infl.calc_keys(v, rules)
            for b, (sel, ks, keys) in enumerate(batches):
                union = sel | rules
                new: set[tuple] | None = set()
                for j in ks + [k]:
                    c = infl.calc_keys(variants[j][0], union)
                    if c is None or new is None:
                        new = None
                        break
                    new |= c
                if (new is not None and keys is not None and own is not None
                        and infl.cost(new, self.computed) <= infl.cost(keys, self.computed)
                        + infl.cost(own, self.computed) + MERGE_SLACK):
                    batches[b] = (union, ks + [k], new)
                    break
            else:
                batches.append((set(rules), [k], own))
        out: list[Any] = [None] * len(variants)
        for sel, ks, keys in batches:
            res = self.ev.evaluate_variants([_changes(self.tols, variants[k][0]) for k in ks],
                                            select=sorted(sel))
            self.computed |= keys or set()
            for k, r in zip(ks, res):
                out[k] = r
                self.done.append((variants[k][0], set(sel), r))
        return out

    def margins(self, requests) -> list[float | None]:
        return [_margins(r).get(key) for (key, _), r in zip(requests, self.ask(requests))]


_NONE = object()


def _corners(idx, fixed: dict[int, float] | None = None) -> list[dict[int, float]]:
    return [{**dict(zip(idx, c)), **(fixed or {})}
            for c in itertools.product((0.0, 1.0), repeat=len(idx))]


def evaluate_corners(nominal, ev: Evaluator, tols: list[Tolerance]) -> list[CornerResult]:
    """Each evaluated result of ``nominal`` judged at its worst tolerance corner."""
    from .influence import affecting

    base_m = _margins(nominal)
    results = {(r.rule, r.item): r for r in nominal.results
               if r.margin is not None and r.status != "not_evaluated"}
    if not tols:
        return []
    infl = affecting(nominal, ev, tols)
    affects = infl.affects
    pk = _Packer(ev, tols, infl, nominal)

    def eps(key) -> float:
        return 1e-9 * max(1.0, abs(base_m[key]))

    # 1. the corners of the tolerances that can move each result (one at a time for a
    #    result more than FULL_K tolerances can move: the ranking needs it)
    small = sorted((k for k in results if 0 < len(affects[k]) <= FULL_K),
                   key=lambda k: -len(affects[k]))
    big = [k for k in results if len(affects[k]) > FULL_K]
    reqs = [(k, u) for k in big for i in affects[k] for u in ({i: 0.0}, {i: 1.0})]
    reqs += [(k, u) for k in small for u in _corners(affects[k])]
    got = dict(zip(((k, tuple(sorted(u.items()))) for k, u in reqs), pk.margins(reqs)))
    used: dict[tuple[str, str], tuple[int, ...]] = {}  # the tolerances that do move it
    worst0: dict[tuple[str, str], tuple[float, dict]] = {}
    for k in small:
        s = affects[k]
        ms = {c: got[(k, c)] for c in (tuple(sorted(u.items())) for u in _corners(s))}
        ms = {c: m for c, m in ms.items() if m is not None}
        if not ms:
            continue
        moves = []
        for i in s:
            for c, m in ms.items():
                flip = tuple((j, 1.0 - u if j == i else u) for j, u in c)
                if flip in ms and abs(ms[flip] - m) > eps(k):
                    moves.append(i)
                    break
        used[k] = tuple(moves)
        if not moves:
            continue
        best: tuple[float, dict] | None = None
        for u in _corners(used[k]):  # the first worst in the order of the corners
            m = min((m for c, m in ms.items() if all(dict(c)[i] == u[i] for i in u)),
                    default=None)
            if m is not None and (best is None or m < best[0]):
                best = (m, u)
        if best is not None:
            worst0[k] = best
    effect: dict[tuple, float] = {}
    worse_end: dict[tuple, float] = {}
    for k in big:
        m0 = base_m[k]
        moves = []
        for i in affects[k]:
            lo, hi = got[(k, ((i, 0.0),))], got[(k, ((i, 1.0),))]
            if lo is None or hi is None:
                continue
            d = max(abs(lo - m0), abs(hi - m0))
            if d > eps(k):
                moves.append(i)
                effect[(k, i)] = d
                worse_end[(k, i)] = 0.0 if lo < hi else 1.0
        used[k] = tuple(moves)
    # 2. for those: all 2^k corners of the tolerances that move them for k <= FULL_K, else
    #    the 2^FULL_K corners of the FULL_K most influential (one at a time), the others at
    #    their worse end
    designs: dict[tuple[str, str], tuple[str, list[dict]]] = {}
    groups: dict[tuple[int, ...], list[tuple[str, str]]] = {}
    for k in big:
        if used[k]:
            groups.setdefault(used[k], []).append(k)
    for idx, keys in groups.items():
        full, fixed = list(idx), {}
        design = f"all {2 ** len(idx)} corners of {len(idx)} tolerances"
        if len(idx) > FULL_K:
            score = {i: sum(effect.get((k, i), 0.0) for k in keys) for i in idx}
            full = sorted(idx, key=lambda i: -score[i])[:FULL_K]
            for i in idx:
                if i not in full:
                    ends = [worse_end.get((k, i), 0.0) for k in keys]
                    fixed[i] = 1.0 if sum(ends) * 2 >= len(ends) else 0.0
            design = (f"2^{FULL_K} corners of the {FULL_K} most influential of {len(idx)}"
                      " tolerances (one-at-a-time ranking), the others at their worse end")
        for k in keys:
            designs[k] = (design, _corners(full, fixed))
    reqs = [(k, u) for k, (_, cs) in designs.items() for u in cs]
    for (k, u), m in zip(reqs, pk.margins(reqs)):
        if m is not None and (k not in worst0 or m < worst0[k][0]):
            worst0[k] = (m, u)
    out: dict[tuple[str, str], CornerResult] = {}
    for k, (m, u) in worst0.items():
        r = results[k]
        idx = used[k]
        design = designs[k][0] if k in designs else f"all {2 ** len(idx)} corners of" \
            f" {len(idx)} tolerances"
        cr = CornerResult(k[0], k[1], r.status, r.value, r.margin, unit=r.unit,
                          severity=r.severity, design=design,
                          tolerances=[tols[i].name for i in idx])
        cr.worst_margin = m
        cr._u = dict(u)
        out[k] = cr
    # 3. is the worst point inside the box? face midpoints at each worst corner (with the
    #    worst corner itself where tolerances that do not move the result were at an end)
    again = [(k, cr._u) for k, cr in out.items() if k in small and used[k] != affects[k]]
    probes = [(k, i, {**cr._u, i: 0.5}) for k, cr in out.items() for i in cr._u]
    ms = pk.margins(again + [(k, u) for k, _, u in probes])
    for (k, _), m in zip(again, ms):
        if m is not None:
            out[k].worst_margin = m
    refine: dict[tuple[str, str], list[int]] = {}
    for (k, i, u), m in zip(probes, ms[len(again):]):
        cr = out[k]
        if m is not None and m < cr.worst_margin - eps(k):
            refine.setdefault(k, []).append(i)
            if m < cr.worst_margin:
                cr.worst_margin, cr._u = m, u
                cr.inside = True
        if base_m[k] < cr.worst_margin:
            cr.worst_margin, cr._u, cr.inside = base_m[k], {}, True
    for k, dims in refine.items():
        for i in dims:
            _golden(out[k], k, i, lambda pts, select, _k=k: pk.ask([(_k, u) for u in pts]))
    # values and statuses at the worst point (direct evaluations, mostly done already)
    keys = list(out)
    for k, r in zip(keys, pk.ask([(k, out[k]._u) for k in keys])):
        cr = out[k]
        f = find(r, *k)
        if f is not None:
            cr.worst_value, cr.worst_margin, cr.worst_status = f.value, f.margin, f.status
        cr.corner = [tols[i].end_text(u) for i, u in sorted(cr._u.items())] or [
            "nominal (the worst point is today's value)"]
    for key, r in results.items():  # results no tolerance moves: worst = nominal
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
