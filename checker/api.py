"""Python API: run the check on a workbook path or an in-memory :class:`Engine`.

>>> from checker import api
>>> result = api.check("engine.xlsx")            # doctest: +SKIP
>>> result.verdict, result.to_frame()            # doctest: +SKIP
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from . import __version__
from .description.engine import Engine, load_engine
from .evaluation import graph
from .evaluation.ruletable import (
    Rule,
    RuleResult,
    RuleTable,
    apply_overrides,
    evaluate_rule,
    load_rules,
    not_applicable_result,
    override_problems,
)
from .evaluation.ruletable import select_rules as _select
from .results import assumptions_of
from .results.loads import cycle_of

FAIL_ON = ("error", "warning", "not-evaluated")
"""Values of ``fail_on``: ``error`` (default), ``warning`` (also failed warnings),
``not-evaluated`` (also results that could not be evaluated); combine with commas."""


def parse_fail_on(value: str | list[str] | tuple[str, ...] | None) -> str:
    """Normalize ``fail_on`` (``"warning,not-evaluated"`` or a list) to a canonical string.

    Raises :class:`checker.errors.UsageProblem` for an unknown value.
    """
    from .errors import UsageProblem

    if value is None:
        return "error"
    parts = value.split(",") if isinstance(value, str) else list(value)
    got = {p.strip().lower().replace("_", "-") for p in parts if p.strip()} or {"error"}
    bad = sorted(got - set(FAIL_ON))
    if bad:
        raise UsageProblem(f"--fail-on: unknown value '{bad[0]}' (use one or more of"
                           f" {', '.join(FAIL_ON)})")
    return ",".join(x for x in FAIL_ON if x in got)


@dataclass
class CheckResult:
    """Everything a check produced: rule results, quantities, timings, assumptions.

    Verdict rules (README, "Verdicts"):

    * ``verdict`` is ``fail`` when an error-severity result fails (or a warning with
      ``fail_on`` warning, or a not-evaluated result with ``fail_on`` not-evaluated), else
      ``pass``;
    * ``complete`` is False when any selected result is not evaluated: a pass is then an
      *incomplete* pass, shown as such everywhere;
    * ``nothing_checked``: no selected result was evaluated at all; the CLI then exits 2;
    * a ``not_applicable`` result (a rule or item the rule does not apply to, with the reason)
      is listed for the reader only: never a pass, never incomplete, no effect on the verdict
      or the exit code.
    """

    engine: Engine
    table: RuleTable
    rules: list[Rule]
    results: list[RuleResult]
    outcome: graph.RunOutcome
    fail_on: str = "error"
    assumptions: list[str] = field(default_factory=list)
    remedies: Any = None  # checker.remedies: what it takes to pass (--remedies)
    corners: Any = None  # checker.remedies: the verdict at the tolerance corners (--corners)
    # adds the remedy and corner blocks to the JSON (set by checker.remedies, which builds on
    # this module: the API never imports it)
    json_extras: Callable[[CheckResult, dict, bool], None] | None = None
    # the continuous-beam scheme against the determinate one (report; compare_schemes)
    scheme_changes: list[dict[str, Any]] | None = None

    @property
    def not_evaluated(self) -> list[RuleResult]:
        return [r for r in self.results if r.status == "not_evaluated"]

    @property
    def not_applicable(self) -> list[RuleResult]:
        return [r for r in self.results if r.status == "not_applicable"]

    @property
    def failed(self) -> list[RuleResult]:
        modes = self.fail_on.split(",")
        sev = ("error", "warning") if "warning" in modes else ("error",)
        out = [r for r in self.results if r.status == "fail" and
               (r.severity in sev or r.internal_error)]
        if "not-evaluated" in modes:
            out += self.not_evaluated
        return out

    @property
    def complete(self) -> bool:
        """True when every selected result was evaluated."""
        return not self.not_evaluated

    @property
    def nothing_checked(self) -> bool:
        """True when not a single selected result was evaluated (a vacuous check); results
        that are not applicable do not count either way."""
        return all(r.status == "not_evaluated" for r in self.results
                   if r.status != "not_applicable")

    def nothing_checked_reason(self) -> str:
        """Why nothing was checked: the selection and the distinct missing inputs."""
        results = [r for r in self.results if r.status != "not_applicable"]
        if not results:
            why = "; ".join(dict.fromkeys(f"{r.rule}: {r.message}" for r in self.results))
            return ("no rule result was produced for the selected rules"
                    + (f" ({why})" if why else ""))
        reasons: list[str] = []
        for r in results:
            for m in r.missing or [r.message]:
                if m not in reasons:
                    reasons.append(m)
        shown = reasons[:8] + ([f"... and {len(reasons) - 8} more"] if len(reasons) > 8
                               else [])
        ids = sorted({r.rule for r in results})
        return (f"nothing was checked: none of the {len(results)} selected rule results"
                f" ({', '.join(ids)}) could be evaluated. Missing:\n"
                + "\n".join(f"  - {x}" for x in shown))

    @property
    def verdict(self) -> str:
        return "fail" if self.failed else "pass"

    @property
    def verdict_text(self) -> str:
        """The verdict as shown to people: ``FAIL``, ``PASS``, or ``PASS (INCOMPLETE)``;
        a failing incomplete check reads ``FAIL (INCOMPLETE)``."""
        v = self.verdict.upper()
        return v if self.complete else f"{v} (INCOMPLETE)"

    @property
    def exit_code(self) -> int:
        if self.nothing_checked:
            return 2
        return 1 if self.failed else 0

    def counts(self) -> dict[str, int]:
        out = {"pass": 0, "fail": 0, "warning": 0, "not_evaluated": 0, "not_applicable": 0}
        for r in self.results:
            if r.status == "fail" and r.severity == "warning" and not r.internal_error:
                out["warning"] += 1
            else:
                out[r.status] += 1
        return out

    def summary_text(self) -> str:
        """One line: verdict, counts and completeness (text output, report command)."""
        c = self.counts()
        line = (f"{self.verdict_text} - {c['pass']} passed, {c['fail']} failed,"
                f" {c['warning']} warning{'s' if c['warning'] != 1 else ''},"
                f" {c['not_evaluated']} not evaluated"
                + (f", {c['not_applicable']} not applicable" if c.get("not_applicable")
                   else ""))
        if not self.complete and "not-evaluated" not in self.fail_on:
            line += (f"; incomplete: {c['not_evaluated']} result"
                     f"{'s' if c['not_evaluated'] != 1 else ''} could not be evaluated"
                     " (not a pass; --fail-on not-evaluated makes them fail)")
        return line

    @property
    def caveats(self) -> list[dict[str, Any]]:
        """Model-validity flags and limits applied outside their engine class
        (:mod:`checker.results.caveats`): what page 1 shows beside the verdict."""
        from .results import caveats

        out = caveats.applicable(caveats.collect(self.outcome), self.results,
                                 {o.rule for o in self.table.overrides})
        est = caveats.estimate_caveat(self.engine, self.results)
        return out + ([est] if est else []) + caveats.layout_caveats(self.engine)

    def to_frame(self):
        """The rule results as a pandas DataFrame (one row per rule and item)."""
        import pandas as pd

        return pd.DataFrame([r.as_dict() for r in self.results])

    def to_dict(self, timings: bool = True) -> dict[str, Any]:
        """JSON-ready dict with stable keys; ``timings`` is the only run-dependent part."""
        d: dict[str, Any] = {
            "tool": "checker",
            "version": __version__,
            "input": {"file": Path(self.engine.source).name, "sha256": self.engine.sha256},
            "engine": self.engine.name,
            "verdict": self.verdict,
            "complete": self.complete,
            "not_evaluated": len(self.not_evaluated),
            "fail_on": self.fail_on,
            "counts": self.counts(),
            "results": [r.as_dict() for r in self.results],
            "modules": {"run": self.outcome.modules_run,
                        "skipped": self.outcome.modules_skipped},
            "overrides": [o.__dict__ for o in self.table.overrides],
            "assumptions": self.assumptions,
            "input_warnings": [str(w) for w in self.engine.warnings],
            "quantities": quantity_summary(self.outcome.quantities),
            "caveats": self.caveats,
        }
        if self.engine.crank is not None:
            # each value of the crank model: typed (wins) or derived from sheet Crank
            d["crank_model"] = [m.as_dict() for m in self.engine.crank_model]
        bl = self.outcome.quantities.get("loads.bearing_load")
        if bl is not None and getattr(bl.detail, "beam", None) is not None:
            # the continuous beam, enough to recompute the main loads with another solver
            d["crank_beam"] = bl.detail.beam.as_dict()
        if timings:
            d["timings"] = {m: round(t, 6) for m, t in self.outcome.timings.items()}
        if self.json_extras is not None:
            self.json_extras(self, d, timings)
        return d


def _num(v: float) -> float | None:
    v = float(v)
    return float(f"{v:.6g}") if np.isfinite(v) else None


def quantity_summary(quantities: dict[str, graph.Quantity]) -> dict[str, Any]:
    """Every computed quantity in the JSON, compactly: the values themselves when the
    quantity has no speed axis; otherwise, per index of the other axes, the smallest and
    largest value over speed with the speed (rpm) where each occurs, and for engine-level
    quantities (no item axis) also every value (``values`` over ``speed_rpm``, speed last).
    SI units; the full per-speed arrays are in the API (``outcome.quantities``)."""
    out: dict[str, Any] = {}
    for name in sorted(quantities):
        q = quantities[name]
        if name == "loads.cycle":
            continue
        dims = list(q.spec.dims)
        coords = {d: [str(c) if d != "speed" else _num(float(c) * 30.0 / np.pi)
                      for c in q.coords[d]] for d in dims if d != "speed"}
        entry: dict[str, Any] = {"unit": q.spec.unit, "dims": dims, "coords": coords}
        v = np.asarray(q.values, dtype=float)
        if "speed" not in dims:
            entry["values"] = np.vectorize(_num, otypes=[object])(v).tolist() if v.size else []
        else:
            ax = dims.index("speed")
            rpm = np.asarray(q.coords["speed"], dtype=float) * 30.0 / np.pi
            moved = np.moveaxis(v, ax, -1)
            lead = moved.reshape(-1, moved.shape[-1]) if moved.size else moved.reshape(0, 0)
            rows = []
            for r in lead:
                ok = np.isfinite(r)
                if not ok.any():
                    rows.append(None)
                    continue
                i_max = int(np.nanargmax(np.where(ok, r, -np.inf)))
                i_min = int(np.nanargmin(np.where(ok, r, np.inf)))
                rows.append({"max": _num(r[i_max]), "max_at_rpm": _num(rpm[i_max]),
                             "min": _num(r[i_min]), "min_at_rpm": _num(rpm[i_min])})
            entry["over_speed"] = rows
            entry["over_speed_index"] = [d for d in dims if d != "speed"]
            if "item" not in dims and lead.size <= 2000:
                # engine-level curves (e.g. total bearing friction vs speed): every value
                entry["speed_rpm"] = [_num(x) for x in rpm]
                entry["values"] = np.vectorize(_num, otypes=[object])(moved).tolist()
        out[name] = entry
    return out


def _assumptions(engine: Engine, outcome: graph.RunOutcome) -> list[str]:
    """Assumptions stated in the report: workbook values marked as such + calculation notes."""
    out: list[str] = [f"Workbook: {a}" for a in engine.assumptions]
    for q in outcome.quantities.values():
        for a in assumptions_of(q):
            if a not in out:
                out.append(a)
    return out


def _mark_overrides(results: list[RuleResult], table: RuleTable) -> None:
    """Every result of a rule whose limit the workbook overrode says so where it is shown
    (summary rows, text output, JSON), not only in the report's appendix."""
    by_rule = {o.rule: o for o in table.overrides}
    for r in results:
        o = by_rule.get(r.rule)
        if o is not None:
            r.override = (f"limit overridden by the workbook ({o.where}): {o.old} → {o.new}"
                          + (f"; reason: {o.reason}" if o.reason else ""))


def _apply_envelope(outcome: graph.RunOutcome) -> None:
    """Restrict rules on (case, speed) quantities to the engine's operating envelope (full load
    only within its data range; see :func:`checker.modules.loads.build_cycle`)."""
    cyc = cycle_of(outcome.quantities)
    env = None if cyc is None else cyc.envelope
    if env is None or env.all():
        return
    for q in outcome.quantities.values():
        dims = q.spec.dims
        if "case" not in dims or "speed" not in dims or dims.index("speed") != len(dims) - 1:
            continue
        if list(q.coords["case"]) != list(cyc.cases) or len(q.coords["speed"]) != env.shape[1]:
            continue
        if dims.index("case") != len(dims) - 2:
            continue
        mask = np.broadcast_to(env, q.values.shape)
        q.applies = mask if q.applies is None else (q.applies & mask)
        if not q.applies_text:
            q.applies_text = "outside the operating envelope"


def check(source: str | Path | Engine, rules: str | Path | RuleTable | None = None,
          select: list[str] | None = None, ignore: list[str] | None = None,
          fail_on: str = "error", progress: Callable[[str], None] | None = None,
          cache: dict | None = None, compare: bool = True, parallel: bool = False
          ) -> CheckResult:
    """Run the design-rule check.

    Parameters
    ----------
    source : path or Engine
        Engine workbook (``.xlsx``) or an engine description built in Python.
    rules : path, RuleTable or None
        Rule file or folder; ``None`` = the default table in ``rules/``.
    select, ignore : list of str
        Rule id prefixes to run / to skip (``["JNT"]``, ``["BRG-002"]``).
    fail_on : str
        ``"error"`` (default), ``"warning"`` (failed warnings fail the verdict too),
        ``"not-evaluated"`` (results that could not be evaluated fail the verdict); combine
        with commas, e.g. ``"warning,not-evaluated"``.
    cache : dict, optional
        Calculation results kept across calls (parametric studies): a calculation whose
        inputs are unchanged is reused (:func:`checker.evaluation.graph.input_key`).
    compare : bool
        Also compute the quantities a result is shown beside (the film thickness by the
        other method). ``False`` for variants judged on their margins only (remedies,
        tolerance corners): the same values, statuses and margins, without ``compare``.
    parallel : bool
        Compute the long calculations that others do not wait for (the bearings' heat
        balance) in a forked process meanwhile (:func:`checker.evaluation.graph.run`): for a
        command's
        own process on a machine with two cores or more, not for the workers of a study. The
        same result.

    Raises
    ------
    checker.errors.InputErrors, checker.errors.RuleFileError, checker.errors.UsageProblem
    """
    fail_on = parse_fail_on(fail_on)
    table = rules if isinstance(rules, RuleTable) else load_rules(rules)
    if isinstance(source, Engine):
        engine = source
        table = apply_overrides(table, engine)
    else:
        # Override problems (unknown rule, bad limit) are input problems of the workbook:
        # reported in the same pass as every cell problem.
        resolved: dict[str, Any] = {}

        def _check_overrides(overrides):
            resolved["rules"], resolved["applied"], errs = override_problems(table, overrides)
            return errs

        engine = load_engine(source, check_overrides=_check_overrides)
        table = RuleTable(resolved["rules"], table.files, resolved["applied"], table.levers)
    chosen = _select(table, select, ignore)
    # rules on the quantities of a calculation that does not apply to this engine (a rubber
    # damper's rules on an engine with a viscous damper): not applicable, with the reason
    inapplicable = {r.id: graph.why_not_applies(engine, r.quantity) for r in chosen
                    if not graph.applies_to(engine, r.quantity)}
    every_rule = chosen
    chosen = [r for r in chosen if r.id not in inapplicable]
    wanted = {r.quantity for r in chosen}
    if engine.crank is not None:
        # the crank's throws as its geometry gives them (JSON, results workbook), judged or not
        wanted |= {n for n in graph.QUANTITIES if n.startswith("crank.")}
        if (engine.params.get("support_scheme") or "determinate") != "determinate":
            # the continuous beam against the determinate scheme (JSON, report)
            wanted.add("fatigue.fillet_bending_ratio")
    # quantities a result is shown beside (the film thickness by the other method); not
    # computed with compare=False (variants judged on their margins: remedies, corners)
    if compare:
        wanted |= {n for r in chosen for _, n in graph.QUANTITIES[r.quantity].compare}
    outcome = graph.run(engine, wanted, progress=progress, cache=cache, parallel=parallel)
    if cache is not None:  # cached quantities are shared between variants: judge on copies
        outcome.quantities = {k: replace(q)
                              for k, q in outcome.quantities.items()}
    _apply_envelope(outcome)
    results: list[RuleResult] = []
    for r in every_rule:
        if r.id in inapplicable:
            results.append(not_applicable_result(r, inapplicable[r.id]))
            continue
        results += evaluate_rule(r, outcome.quantities.get(r.quantity),
                                 outcome.unavailable.get(r.quantity), outcome.quantities)
    _mark_overrides(results, table)
    return CheckResult(engine, table, chosen, results, outcome, fail_on,
                       _assumptions(engine, outcome))


_BATCHED_FILMS = (("moft_short", "closed_form", "bearing.moft_short"),
                  ("moft_finite", "reynolds_map", "bearing.moft_finite"))
"""Calculations whose orbits :func:`check_batch` solves for all variants in one kernel call:
(calculation, mobility model, quantity)."""


def check_batch(engines: list[Engine], rules: str | Path | RuleTable | None = None,
                select: list[str] | None = None, ignore: list[str] | None = None,
                fail_on: str = "error", cache: dict | None = None,
                compare: bool = True,
                selects: list[list[str] | None] | None = None) -> list[CheckResult]:
    """Check several engine variants together; the same results as :func:`check` one by one.

    The journal orbits of the film-thickness calculations (short-bearing and finite-length
    MOFT) of all variants are solved in one orbit kernel call per model (the variants are one
    more batch axis: a clearance, oil or width study costs about one check's orbits, not one
    per variant); every other calculation is evaluated per variant with the calculation cache
    (:func:`checker.evaluation.graph.input_key`), so what the variants share (e.g. the loads of a
    clearance study) is computed once. Orbits are never shared between variants, so each
    variant's numbers are exactly those of its own :func:`check` (tests).

    Parameters
    ----------
    engines : list of Engine
        The variants (e.g. :func:`checker.description.engine.build_engine` of each study variant).
    rules, select, ignore, fail_on
        As in :func:`check` (workbook limit overrides are applied per engine).
    cache : dict, optional
        Calculation cache kept across calls (a study's worker keeps one); a new one is used
        when not given.
    selects : list, optional
        Per engine, its own ``select`` (instead of ``select`` for all): variants checked on
        different rules still share the kernel calls of their film orbits.

    Returns
    -------
    list of CheckResult
        One per engine, in order.
    """
    from .modules import bearings as m_bearings

    sels = list(selects) if selects is not None else [select] * len(engines)
    if len(sels) != len(engines):
        raise ValueError("check_batch: one selection per engine")

    fail_on = parse_fail_on(fail_on)
    cache = {} if cache is None else cache
    base = rules if isinstance(rules, RuleTable) else load_rules(rules)
    graph.ensure_registered()
    # 1. the loads (and what else the films need) of every variant, then the film orbits of
    #    all variants whose film calculation is not cached yet, one kernel call per model
    todo: dict[str, list[tuple[Engine, str]]] = {c: [] for c, _, _ in _BATCHED_FILMS}
    for engine, sel in zip(engines, sels):
        table = apply_overrides(base, engine)
        chosen = _select(table, sel, ignore)
        wanted = {r.quantity for r in chosen}
        if compare:
            wanted |= {n for r in chosen for _, n in graph.QUANTITIES[r.quantity].compare}
        order = graph.plan(engine, wanted)
        keys = graph.input_keys(engine, order)
        for cname, _, _ in _BATCHED_FILMS:
            if cname in order and keys[cname] not in cache:
                todo[cname].append((engine, keys[cname]))
    for cname, model, qname in _BATCHED_FILMS:
        items = []
        for engine, key in todo[cname]:
            deps = graph.CALCULATIONS[cname].needs(engine)
            pre = graph.run(engine, deps, cache=cache)
            if any(d not in pre.quantities for d in deps):
                continue  # an input is missing: the variant's own run reports it
            items.append((engine, key, {d: pre.quantities[d] for d in deps}))
        outs = m_bearings.solve_many([(e, inp) for e, _, inp in items], model, qname)
        for (_, key, _), out in zip(items, outs):
            if isinstance(out, graph.MissingInputs):
                cache[key] = ({}, {qname: out.reasons})
            else:
                cache[key] = ({qname: out}, {})
    # 2. every variant, its film quantities from the cache
    return [check(engine, base, sel, ignore, fail_on, cache=cache, compare=compare)
            for engine, sel in zip(engines, sels)]


def today() -> str:
    return _dt.date.today().isoformat()


def compare_schemes(res: CheckResult) -> list[dict[str, Any]]:
    """The verdicts that change when the crank of a continuous-beam workbook is taken as
    statically determinate (the same engine and rules with Engine 'Main bearing supports' =
    determinate): one dict per rule result whose status differs (rule, item, case, the two
    statuses and values). Empty under the determinate scheme."""
    from dataclasses import replace as _replace

    from .description.engine import Params

    if (res.engine.params.get("support_scheme") or "determinate") == "determinate":
        return []
    det_engine = _replace(res.engine, params=Params({**res.engine.params,
                                                     "support_scheme": "determinate"}))
    det = check(det_engine, rules=res.table, select=[r.id for r in res.rules],
                fail_on=res.fail_on, compare=False)
    # one result per rule, item and load case in both (the case text names each scheme's own
    # worst speed): paired in order
    out = []
    pairs = zip(det.results, res.results, strict=False)
    for d, r in pairs:
        if (d.rule, d.item) != (r.rule, r.item):
            break
        if d.status != r.status:
            out.append({"rule": r.rule, "item": r.item, "case": r.case,
                        "determinate_case": d.case, "determinate": d.status,
                        "determinate_value": d.value,
                        "continuous": r.status, "continuous_value": r.value})
    return out
