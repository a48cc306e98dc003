"""What it takes to pass, and the verdict at the tolerance corners.

* :func:`checker.remedies.solve.find_remedies`: per failing result (and passing ones within
  10 % of their limit) and per design lever (``rules/levers.toml``), the input value at which
  the margin reaches zero, its side effects and conflicts;
* :func:`checker.remedies.corners.evaluate_corners`: each result at the worst corner of the
  workbook's ``Tolerances``.

Both evaluate variants of the workbook through one function,
:meth:`checker.remedies.variants.Evaluator.evaluate_variants`, with the check's calculation
cache. :func:`attach` runs them on a finished check (``checker check --remedies --corners``).
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from ..errors import UsageProblem
from ..results.display import item_label


def attach(res, remedies: bool = False, corners: bool = False, levers_file: str | None = None,
           cache: dict | None = None, select: list[str] | None = None,
           ignore: list[str] | None = None, rules: Any = None,
           workers: int | None = None) -> None:
    """Compute remedies and/or corners for the check ``res`` and store them on it
    (``res.remedies``, ``res.corners``; per result ``what_it_takes`` and ``worst_corner``).

    The remedies' variants are checked in this process and ``workers - 1`` forked helper
    processes (default: one process per core, at most 4; ``workers=1``: this process alone);
    the answers do not depend on it. The corners are checked in one process (their variants
    share calculations, the loads and torsion at one peak pressure, that separate processes
    would each compute again: on the I4 two processes took longer than one): with remedies
    and more than one process, a forked process of their own that works while the remedies
    are searched; else this process.

    Needs the check's workbook file (variants change its cells in memory). Raises
    :class:`checker.errors.InputErrors` for a bad Tolerances sheet and
    :class:`checker.errors.RuleFileError` for a bad lever file.
    """
    from ..evaluation.ruletable import RuleTable, load_rules
    from ..plumbing.blas_threads import one_per_process
    from ..workbook.loader import read_raw_workbook
    from .variants import Evaluator

    if not remedies and not corners:
        return
    src = Path(res.engine.source or "")
    if not src.is_file():
        raise UsageProblem("--remedies and --corners need the engine workbook file (an engine"
                           " built in Python has no cells to move)")
    table = rules if isinstance(rules, RuleTable) else load_rules(rules)
    base = read_raw_workbook(src)
    ev = Evaluator(base, table, select=select, ignore=ignore, fail_on=res.fail_on,
                   cache=cache if cache is not None else {})
    tols = None
    if corners:
        from .corners import read_tolerances

        tols = read_tolerances(base)  # a bad Tolerances sheet: an input error before any work
    # helper processes, the corners' process and the report's drawing processes share the
    # cores: one BLAS thread each
    with one_per_process(ev.processes(workers) > 1):
        _attach_all(res, ev, table, remedies, tols, levers_file, workers)


def _attach_all(res, ev, table, remedies: bool, tols, levers_file: str | None,
                workers: int | None) -> None:
    from ..plumbing.forked import Forked

    corner_job = None
    if remedies:
        if tols is not None and ev.processes(workers) > 1:
            # the corners in a forked process of their own while the remedies are searched
            # (forked first: it does not inherit the remedies' helpers); the root finding's
            # rounds leave cores idle that the corners fill
            corner_job = Forked(_corners_here, res, ev, tols)
        ev.start_workers(workers)
    try:
        _attach(res, ev, table, remedies, tols, levers_file, corner_job)
    finally:
        if corner_job is not None:
            corner_job.close()
        ev.release()


def _corners_here(res, ev, tols) -> tuple[list, int, float]:
    """The corners of ``res`` checked with ``ev`` in this process: (results, evaluations,
    seconds)."""
    from .corners import evaluate_corners

    t0 = time.perf_counter()
    n0 = ev.evaluations
    out = evaluate_corners(res, ev, tols)
    return out, ev.evaluations - n0, time.perf_counter() - t0


def _attach(res, ev, table, remedies: bool, tols, levers_file: str | None,
            corner_job=None) -> None:
    from ..description.levers import load_levers, merge

    if remedies:
        from .solve import find_remedies

        t0 = time.perf_counter()
        # a user rule file without levers: the default levers (those of absent rules idle)
        levers = list(table.levers) or load_levers(None)
        if levers_file:
            levers = merge(levers, load_levers(levers_file, {r.id for r in table.rules}))
        n0 = ev.evaluations
        info: dict = {}
        out = find_remedies(res, ev, levers, info=info)
        by = {(x.rule, x.item): x for x in out}
        for r in res.results:
            x = by.get((r.rule, r.item))
            if x is not None:
                r.what_it_takes = x.line()
        res.json_extras = add_to_json
        res.remedies = {"results": out, "levers": levers,
                        "evaluations": ev.evaluations - n0,
                        "screening_speeds": info.get("screening_speeds"),
                        "seconds": time.perf_counter() - t0}
        ev.stop_workers()
    if tols is not None:
        from ..results.display import with_unit

        out_c, n_eval, seconds = (corner_job.result() if corner_job is not None
                                  else _corners_here(res, ev, tols))
        by_c = {(c.rule, c.item): c for c in out_c}
        for r in res.results:
            c = by_c.get((r.rule, r.item))
            if c is not None and c.tolerances:
                r.worst_corner = (f"{with_unit(c.worst_value, r.unit)} at "
                                  + ", ".join(c.corner) + f": {c.worst_status}"
                                  if c.worst_value is not None else "")
        res.json_extras = add_to_json
        res.corners = {"results": out_c, "tolerances": tols, "evaluations": n_eval,
                       "seconds": seconds}


def corners_fail(res) -> bool:
    """True when a result that counts for the verdict fails at its worst corner."""
    from .corners import verdict_fails

    if not res.corners:
        return False
    return verdict_fails(res.corners["results"], res.fail_on)


def add_to_json(res, d: dict, timings: bool = True) -> None:
    """The ``remedies`` and ``corners`` blocks of the JSON output (and per result)."""
    from .screening import in_rpm

    by_key = {(x["rule"], x["item"]): x for x in d["results"]}
    if res.remedies is not None:
        items = [x.as_dict() for x in res.remedies["results"]]
        sp = res.remedies.get("screening_speeds")
        d["remedies"] = {"results": items, "evaluations": res.remedies["evaluations"],
                         "screening_speeds_rpm": None if not sp else
                         [float(f"{x:.6g}") for x in in_rpm(sp)],
                         "levers": [{"id": lv.id, "name": lv.name, "rules": list(lv.rules),
                                     "input": lv.where_text(), "direction": lv.direction,
                                     "unit": lv.unit} for lv in res.remedies["levers"]]}
        if timings:
            d["remedies"]["seconds"] = round(res.remedies["seconds"], 3)
        for x in items:
            r = by_key.get((x["rule"], x["item"]))
            if r is not None:
                r["remedies"] = x["levers"]
                r["what_it_takes"] = x["what_it_takes"]
    if res.corners is not None:
        items = [c.as_dict() for c in res.corners["results"]]
        d["corners"] = {
            "results": items, "evaluations": res.corners["evaluations"],
            "verdict": "fail" if corners_fail(res) else "pass",
            "tolerances": [{"name": t.name, "row": t.where, "cells": list(t.binding.labels),
                            "min": float(f"{t.low:.6g}"), "max": float(f"{t.high:.6g}"),
                            "nominal": float(f"{t.nominal:.6g}"), "unit": t.unit,
                            "source": t.source} for t in res.corners["tolerances"]]}
        if timings:
            d["corners"]["seconds"] = round(res.corners["seconds"], 3)
        for x in items:
            r = by_key.get((x["rule"], x["item"]))
            if r is not None:
                r["corner"] = {"nominal": x["nominal"], "worst": x["worst"]}


def to_text(res) -> str:
    """Text lines for ``checker check --format text``: what it takes, and the corners."""
    lines: list[str] = []
    if res.remedies is not None:
        lines.append("")
        from .screening import speeds_text

        sp = res.remedies.get("screening_speeds")
        how = (f"; failing bearing results searched at {len(sp)} speeds where they are worst"
               f" today ({speeds_text(sp)}), each answer checked at every speed" if sp else "")
        lines.append(f"What it takes to pass ({res.remedies['evaluations']} evaluations{how}):")
        for x in res.remedies["results"]:
            if x.status == "pass" and not x.remedies:
                continue
            lines.append(f"  {x.rule} {item_label(x.item)} ({x.status}"
                         + ("; the margin reaches zero at" if x.status == "pass" else "; passes at")
                         + "):")
            for rm in x.remedies:
                fx = ", ".join(f"{e['rule']} {item_label(e['item'])} -> {e['to']}"
                               for e in rm.side_effects)
                lines.append(f"    - {rm.text()}" + (f"; side effects: {fx}" if fx else ""))
            for c in x.conflicts:
                lines.append(f"    ! {c}")
            if not x.remedies:
                lines.append("    - no design lever is listed for this rule")
    if res.corners is not None:
        lines.append("")
        lines.append(f"At the tolerance corners ({res.corners['evaluations']} evaluations;"
                     f" verdict {'FAIL' if corners_fail(res) else 'PASS'}):")
        for c in res.corners["results"]:
            if not c.tolerances:
                continue
            from ..results.display import with_unit

            lines.append(f"  {c.rule} {item_label(c.item)}:"
                         f" nominal {with_unit(c.nominal_value, c.unit)}"
                         f" ({c.nominal_status}), worst {with_unit(c.worst_value, c.unit)}"
                         f" ({c.worst_status}) at {', '.join(c.corner)}"
                         + (" [inside the box]" if c.inside else ""))
    return "\n".join(lines) + ("\n" if lines else "")
