"""Which tolerances can move which results, read from the calculation graph (no evaluation).

A tolerance moves cells of one sheet. The engine built at each end of its range is compared
with today's engine: the parts and fields that differ (``bearings.clearance`` of rows M1..M5,
``oil.supply_temperature``, ``peak_pressure``...) are what the tolerance changes. A calculation
is affected when it reads a changed input (``reads=`` of
:func:`checker.evaluation.graph.calculation`,
``None`` = every input) or needs a quantity of an affected calculation (the same rule as the
calculation cache, :func:`checker.evaluation.graph.input_key`: an unaffected calculation is reused
bitwise). A result is affected when its rule's quantity is, or, for a quantity over (case,
speed), the load cycle whose operating envelope restricts it (:func:`checker.api.check`).

Items. A few calculations are item by item for a few fields (:data:`ITEMWISE`): a change of
those fields in some rows of a table moves only the results of the items of the same class
(bearing type), and an upstream quantity moved only for some items moves only those items.
The class, not the row: bearings whose orbits are shifted copies of each other share them
(:func:`checker.calc.orbit.solve_orbit`), so a main bearing's clearance moves the other main
bearings' films in the last digits, never a big end's (tests/remedies/test_influence_corners.py
checks this bitwise on the I4, I6 and V8 templates). Everything else is conservative: a result
of another family (an engine-level sum, a joint) is affected by every row.

Anything that cannot be read this way (a tolerance whose engine cannot be built, a change of
the cell addresses or of the rule overrides, a test double without a workbook) makes the
tolerance affect every result: the corners then simply evaluate more.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

ALL = "all"
"""Every item of a quantity is affected."""

ITEMWISE: dict[str, tuple[str, str, frozenset[str]]] = {
    name: ("bearings", "type", frozenset({"clearance"}))
    for name in ("moft", "moft_short", "moft_finite", "bearing_heat_balance", "film_pressure",
                 "film_pressure_short", "specific_load")
}
"""Calculation -> (engine part, class field, fields): a change of those fields of some rows of
the part moves only the items of the same class of the calculation's quantities over items;
and an upstream quantity moved for some items moves only those items."""


def _rows(part: Any) -> bool:
    return isinstance(part, tuple) and bool(part) and all(
        dataclasses.is_dataclass(r) for r in part)


def engine_changes(e0: Any, e1: Any) -> dict[str, Any] | None:
    """The inputs that differ between two engines: ``{"part.field": set of row indices}``
    for tables of records, ``{"part.key": ALL}`` for parameter sheets, ``{"part": ALL}``
    otherwise; ``None`` when a change is not visible to the calculations' ``reads`` (cell
    addresses, rule overrides): everything may change."""
    from ..evaluation.graph import ENGINE_PARTS

    if e0.where != e1.where or repr(e0.overrides) != repr(e1.overrides):
        return None
    out: dict[str, Any] = {}
    for part in ENGINE_PARTS:
        a, b = getattr(e0, part), getattr(e1, part)
        if repr(a) == repr(b):
            continue
        if isinstance(a, dict) and isinstance(b, dict):
            for k in set(a) | set(b):
                if repr(a.get(k)) != repr(b.get(k)):
                    out[f"{part}.{k}"] = ALL
        elif _rows(a) and _rows(b) and len(a) == len(b):
            for i, (ra, rb) in enumerate(zip(a, b)):
                if type(ra) is not type(rb):
                    out[part] = ALL
                    continue
                for f in dataclasses.fields(ra):
                    if repr(getattr(ra, f.name)) != repr(getattr(rb, f.name)):
                        rows = out.setdefault(f"{part}.{f.name}", set())
                        if rows is not ALL:
                            rows.add(i)
        else:
            out[part] = ALL
    return out


def _merge(a: dict[str, Any], b: dict[str, Any]) -> dict[str, Any]:
    out = dict(a)
    for k, v in b.items():
        if k not in out:
            out[k] = v if v is ALL else set(v)
        elif out[k] is ALL or v is ALL:
            out[k] = ALL
        else:
            out[k] = out[k] | v
    return out


def _reads(calc: Any, entry: str) -> bool:
    if calc.reads is None:
        return True
    part = entry.partition(".")[0]
    return any(r == part or r == entry or (r.partition(".")[0] == part and "." not in entry)
               for r in calc.reads)


def affected_quantities(engines: list[Any], changes: dict[str, Any],
                        calcs: set[str] | None = None) -> dict[str, Any]:
    """Quantity -> ``ALL`` or the frozenset of item names it may change for, given the
    ``changes`` of :func:`engine_changes` between ``engines[0]`` (today's) and the others.
    ``calcs`` (a set) receives the names of the affected calculations."""
    from ..evaluation import graph

    e0 = engines[0]
    order: list[str] = []
    for e in engines:
        for c in graph.plan(e, [q for q in graph.QUANTITIES if q in graph.PROVIDER]):
            if c not in order:
                order.append(c)
    needs: dict[str, set[str]] = {c: set() for c in order}
    for e in engines:
        for c in order:
            needs[c] |= set(graph.CALCULATIONS[c].needs(e))
    # topological order over the union of needs
    done: list[str] = []
    seen: set[str] = set()

    def visit(c: str) -> None:
        if c in seen:
            return
        seen.add(c)
        for q in sorted(needs.get(c, ())):
            p = graph.PROVIDER.get(q)
            if p is not None and p in needs:
                visit(p)
        done.append(c)

    for c in order:
        visit(c)
    qstate: dict[str, Any] = {}
    for c in done:
        calc = graph.CALCULATIONS[c]
        wise = ITEMWISE.get(c)
        state: Any = None
        for entry, rows in changes.items():
            if not _reads(calc, entry):
                continue
            part, _, fld = entry.partition(".")
            if (wise is not None and rows is not ALL and part == wise[0]
                    and fld in wise[2]):
                recs = getattr(e0, part)
                kinds = {getattr(recs[i], wise[1]) for i in rows}
                items = frozenset(r.name for r in recs if getattr(r, wise[1]) in kinds)
                state = items if state is None else (ALL if state is ALL else state | items)
            else:
                state = ALL
        for q in needs[c]:
            s = qstate.get(q)
            if s is None:
                continue
            if wise is not None and s is not ALL:
                state = s if state is None else (ALL if state is ALL else state | s)
            else:
                state = ALL
        if state is None:
            continue
        if calcs is not None:
            calcs.add(c)
        for q in calc.provides:
            spec = graph.QUANTITIES[q]
            qstate[q] = state if "item" in spec.dims else ALL
    return qstate


@dataclass
class Influence:
    """Which tolerances can move which results, and what a variant recomputes."""

    affects: dict[tuple[str, str], tuple[int, ...]]
    """Per evaluated result (rule, item): the indices of the tolerances that can move it."""
    tol_calcs: list[set[str] | None] = field(default_factory=list)
    """Per tolerance: the calculations it changes (None: unknown, every one)."""
    rule_calcs: dict[str, set[str]] = field(default_factory=dict)
    """Per rule id: the calculations its result needs."""

    calc_cost: dict[str, float] = field(default_factory=dict)
    """Per calculation: its seconds in today's check (its module's time shared among the
    module's calculations that ran); 0 when unknown."""

    def calc_keys(self, point: dict[int, Any], rules: set[str]) -> set[tuple] | None:
        """The calculations a variant at ``point`` (tolerance index -> box coordinate,
        absent = today's value) runs for ``rules``, each with the values of the tolerances
        that reach it (the same pair = the same cached result); today's are left out
        (today's check holds them). None: unknown."""
        need: set[str] = set()
        for r in rules:
            c = self.rule_calcs.get(r)
            if c is None:
                return None
            need |= c
        out: set[tuple] = set()
        for c in need:
            k = tuple((i, u) for i, u in sorted(point.items())
                      if u is not None and (self.tol_calcs[i] is None or c in self.tol_calcs[i]))
            if k:
                out.add((c, k))
        return out

    def cost(self, keys: set[tuple], done: set[tuple] = frozenset()) -> float:
        return sum(self.calc_cost.get(c, 0.0) for c, k in keys if (c, k) not in done)


def affecting(nominal: Any, ev: Any, tols: list[Any]) -> Influence:
    """Per evaluated result ``(rule, item)`` of ``nominal``: the indices of the tolerances
    that can move it (all of them where the structure cannot tell)."""
    from ..description.engine import build_engine
    from ..evaluation import graph
    from ..workbook.loader import convert_raw

    keys = [(r.rule, r.item) for r in nominal.results
            if r.margin is not None and r.status != "not_evaluated"]
    every = tuple(range(len(tols)))
    try:
        base = ev.base
        e0 = build_engine(convert_raw(base, raise_errors=False))
        quantity = {r.id: r.quantity for r in ev.table.rules}
    except Exception:  # noqa: BLE001 - no workbook (a test double): every tolerance counts
        return Influence({k: every for k in keys})
    per_tol: list[dict[str, Any] | None] = []
    tol_calcs: list[set[str] | None] = []
    for t in tols:
        try:
            engines = [e0]
            changes: dict[str, Any] = {}
            for u in (0.0, 1.0):
                e1 = build_engine(convert_raw(base.with_values(t.binding.changes(t.value(u))),
                                              raise_errors=False))
                ch = engine_changes(e0, e1)
                if ch is None:
                    raise ValueError("not visible")
                changes = _merge(changes, ch)
                engines.append(e1)
            if not changes:
                raise ValueError("no visible change")
            calcs: set[str] = set()
            per_tol.append(affected_quantities(engines, changes, calcs))
            tol_calcs.append(calcs)
        except Exception:  # noqa: BLE001 - unknown: conservative
            per_tol.append(None)
            tol_calcs.append(None)
    out: dict[tuple[str, str], tuple[int, ...]] = {}
    rule_calcs: dict[str, set[str]] = {}
    for key in keys:
        q = quantity.get(key[0])
        if q is None or q not in graph.QUANTITIES:
            out[key] = every
            continue
        dims = graph.QUANTITIES[q].dims
        deps = [q] + (["loads.cycle"] if "case" in dims and "speed" in dims else [])
        if key[0] not in rule_calcs:
            try:
                rule_calcs[key[0]] = set(graph.plan(e0, deps))
            except Exception:  # noqa: BLE001 - unknown cost: no entry
                pass
        idx = []
        for i, st in enumerate(per_tol):
            if st is None:
                idx.append(i)
                continue
            for d in deps:
                s = st.get(d)
                if s is ALL or (s is not None and key[1] in s):
                    idx.append(i)
                    break
        out[key] = tuple(idx)
    cost: dict[str, float] = {}
    outcome = getattr(nominal, "outcome", None)
    if outcome is not None:
        ran = [c for c in outcome.ran if c not in outcome.reused]
        for c in ran:
            m = graph.CALCULATIONS[c].module
            cost[c] = outcome.timings.get(m, 0.0) / sum(
                graph.CALCULATIONS[x].module == m for x in ran)
    return Influence(out, tol_calcs, rule_calcs, cost)
