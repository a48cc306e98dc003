"""Python API: run the check on a workbook path or an in-memory :class:`Engine`.

>>> from checker import api
>>> result = api.check("engine.xlsx")            # doctest: +SKIP
>>> result.verdict, result.to_frame()            # doctest: +SKIP
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from . import __version__, graph
from .engine import Engine, load_engine
from .ruletable import Rule, RuleResult, RuleTable, apply_overrides, evaluate_rule, load_rules
from .ruletable import select_rules as _select


@dataclass
class CheckResult:
    """Everything a check produced: rule results, quantities, timings, assumptions."""

    engine: Engine
    table: RuleTable
    rules: list[Rule]
    results: list[RuleResult]
    outcome: graph.RunOutcome
    fail_on: str = "error"
    assumptions: list[str] = field(default_factory=list)

    @property
    def failed(self) -> list[RuleResult]:
        sev = ("error", "warning") if self.fail_on == "warning" else ("error",)
        return [r for r in self.results if r.status == "fail" and r.severity in sev]

    @property
    def verdict(self) -> str:
        return "fail" if self.failed else "pass"

    @property
    def exit_code(self) -> int:
        return 1 if self.failed else 0

    def counts(self) -> dict[str, int]:
        out = {"pass": 0, "fail": 0, "warning": 0, "not_evaluated": 0}
        for r in self.results:
            if r.status == "fail" and r.severity == "warning":
                out["warning"] += 1
            else:
                out[r.status] += 1
        return out

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
            "fail_on": self.fail_on,
            "counts": self.counts(),
            "results": [r.as_dict() for r in self.results],
            "modules": {"run": self.outcome.modules_run,
                        "skipped": self.outcome.modules_skipped},
            "overrides": [o.__dict__ for o in self.table.overrides],
            "assumptions": self.assumptions,
        }
        if timings:
            d["timings"] = {m: round(t, 6) for m, t in self.outcome.timings.items()}
        return d


def _assumptions(engine: Engine, outcome: graph.RunOutcome) -> list[str]:
    """Assumptions stated in the report: workbook values marked as such + calculation notes."""
    out: list[str] = [f"Workbook: {a}" for a in engine.assumptions]
    for q in outcome.quantities.values():
        for a in q.extra.get("assumptions", []):
            if a not in out:
                out.append(a)
    return out


def _apply_envelope(outcome: graph.RunOutcome) -> None:
    """Restrict rules on (case, speed) quantities to the engine's operating envelope (full load
    only within its data range; see :func:`checker.modules.loads.build_cycle`)."""
    cyc_q = outcome.quantities.get("loads.cycle")
    if cyc_q is None:
        return
    cyc = cyc_q.extra["cycle"]
    env = getattr(cyc, "envelope", None)
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
        q.extra.setdefault("applies_text", "outside the operating envelope")


def check(source: str | Path | Engine, rules: str | Path | RuleTable | None = None,
          select: list[str] | None = None, ignore: list[str] | None = None,
          fail_on: str = "error", progress: Callable[[str], None] | None = None
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
    fail_on : {"error", "warning"}
        Lowest severity whose failure fails the verdict.

    Raises
    ------
    checker.errors.InputErrors, checker.errors.RuleFileError, ValueError
    """
    engine = source if isinstance(source, Engine) else load_engine(source)
    table = rules if isinstance(rules, RuleTable) else load_rules(rules)
    table = apply_overrides(table, engine)
    chosen = _select(table, select, ignore)
    outcome = graph.run(engine, {r.quantity for r in chosen}, progress=progress)
    _apply_envelope(outcome)
    results: list[RuleResult] = []
    for r in chosen:
        results += evaluate_rule(r, outcome.quantities.get(r.quantity),
                                 outcome.unavailable.get(r.quantity))
    return CheckResult(engine, table, chosen, results, outcome, fail_on,
                       _assumptions(engine, outcome))


def today() -> str:
    return _dt.date.today().isoformat()
