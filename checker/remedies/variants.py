"""Variants of a workbook's inputs evaluated through one function.

Every remedy and tolerance-corner evaluation goes through :meth:`Evaluator.evaluate_variants`:
a list of cell changes ``{(sheet, row, column): value in the cell's unit}`` (the mechanism of
the parametric study, :func:`checker.study.apply.resolve` and
:meth:`checker.workbook.loader.RawWorkbook.with_values`), each converted and built like a
workbook and checked with a shared calculation cache (:func:`checker.evaluation.graph.input_key`),
so a
joint-torque variant recomputes only the joints. The variants are checked in batches
(:func:`checker.api.check_batch`: their film orbits in one kernel call; the film orbits of
unchanged bearings are reused, :mod:`checker.modules.film_memo`) and without the compared
film quantity (``compare=False``: the same values, statuses and margins).

:class:`Binding` ties a lever or a tolerance to the cells it moves (one value, in the lever's
unit, for every targeted cell: one cell takes it as given, several cells keep their ratios,
or their differences for a temperature).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

from ..errors import InputErrors
from ..study.apply import Target, cell_value, resolve
from ..study.spec import Parameter, Study
from ..workbook.schema import SHEETS, Field

Changes = dict[tuple[str, int, int], Any]

OFFSET_KINDS = ("temperature",)
"""Kinds whose cells move together by a difference (°C), not by a ratio."""


@dataclass
class Evaluator:
    """The base workbook, the rule table and the shared calculation cache of one check."""

    base: Any  # RawWorkbook
    table: Any  # RuleTable (without workbook overrides: check applies them)
    select: list[str] | None = None
    ignore: list[str] | None = None
    fail_on: str = "error"
    cache: dict = field(default_factory=dict)
    evaluations: int = 0
    seconds: float = 0.0
    """Time spent checking variants in this process [s]."""
    keep_bytes: int = 512 * 2**20
    """Memory of the calculation results of variants kept in the cache beyond the check's own
    (the oldest are dropped first: the bearing loads hold about 30 MB, a film calculation of
    all bearings about 5 MB, a heat balance 10 kB, so the small results of the variants whose
    answers are checked again for their side effects stay)."""
    batch: int = 8
    """Variants checked together (:func:`checker.api.check_batch`: their film orbits in one
    kernel call); bounded because each variant's films stay in memory until the batch ends."""
    workers: int = 1
    """Processes that check variants: this one and ``workers - 1`` forked helpers
    (:meth:`start_workers`); a call with several variants is shared among them."""
    _pinned: set | None = None
    _sizes: dict = field(default_factory=dict)
    _pool: Any = None

    def evaluate_variants(self, changes: list[Changes], select: list[str] | None = None,
                          task_size: int | None = None,
                          speeds: tuple[float, ...] | None = None) -> list[Any]:
        """Check every variant (cell changes on the base workbook).

        Returns per variant a :class:`checker.api.CheckResult`, or the
        :class:`InputErrors` of a variant whose values are not a valid workbook (outside a
        field's valid range, a cross-sheet check). ``select`` restricts the rules (rule id
        prefixes); the check's own ``ignore`` always applies.

        With helper processes (:meth:`start_workers`) the variants are shared among them and
        this process (:meth:`evaluate_groups`). A variant checked by a helper comes back with
        its rule results, without its calculated quantities. The numbers are the same in
        every process (each variant's check equals a cold check). ``task_size``: see
        :meth:`evaluate_groups`. ``speeds`` [rad/s]: check at these of the swept speeds only
        (screening, :mod:`checker.remedies.screening`).
        """
        return self.evaluate_groups([(changes, select, speeds)], task_size)[0]

    def input_errors(self, changes: Changes) -> InputErrors | None:
        """The input errors of a variant (its cells converted and the engine built, nothing
        calculated: a few milliseconds), or None for a valid workbook."""
        built = self._build(changes)
        return built if isinstance(built, InputErrors) else None

    def _build(self, changes: Changes, speeds: tuple[float, ...] | None = None) -> Any:
        """The engine of a variant, or the :class:`InputErrors` of one that is not a valid
        workbook (including values a calculation refuses while the engine is built);
        ``speeds``: its sweep restricted to them (:func:`checker.modules.loads.speed_sweep`)."""
        from ..description.engine import Params, build_engine
        from ..workbook.loader import convert_raw

        try:
            engine = build_engine(convert_raw(self.base.with_values(changes),
                                              raise_errors=False))
        except InputErrors as exc:
            return exc
        except (ValueError, ArithmeticError) as exc:
            return _refused(exc)
        if speeds:
            engine = dataclasses.replace(engine, params=Params({**engine.params,
                                                                "speed_subset": speeds}))
        return engine

    def evaluate_groups(self, groups: list[tuple], task_size: int | None = None
                        ) -> list[list[Any]]:
        """:meth:`evaluate_variants` of several groups ``(changes, select)`` or ``(changes,
        select, speeds)`` (e.g. the variants of one round of root finding, grouped by the
        rules they are checked on).

        With helper processes the groups are cut into tasks of a few variants (about
        :data:`TASKS_PER_PROCESS` tasks per process, at most :attr:`batch` variants each: the
        variants of a task have their film orbits solved in one kernel call), the largest
        first. The helpers take the tasks in that order as they become free, and this process
        takes the last ones that no helper has started, so that the processes end together
        whatever each task costs (an oil variant moves every bearing's film, a fillet variant
        only the fatigue). ``task_size``: variants per task instead (e.g. 1 for variants whose
        films are already computed, where only the balance among the processes counts)."""
        # every variant with its own selection, in the order of the groups: a task may hold
        # variants of several groups (their film orbits still in one kernel call)
        groups = [tuple(g) + (None,) * (3 - len(g)) for g in groups]
        flat = [(g, i, c, sel, sp) for g, (ch, sel, sp) in enumerate(groups)
                for i, c in enumerate(ch)]
        out: list[list[Any]] = [[None] * len(g[0]) for g in groups]

        def args(task):
            return ([c for _, _, c, _, _ in task], [sel for _, _, _, sel, _ in task],
                    [sp for _, _, _, _, sp in task])

        if self._pool is None or len(flat) < 2:
            res = self._evaluate_here(*args(flat))
            for (g, i, _, _, _), r in zip(flat, res):
                out[g][i] = r
            return out
        size = task_size or max(1, min(self.batch,
                                       -(-len(flat) // (TASKS_PER_PROCESS * self.workers))))
        tasks = [flat[start:start + size] for start in range(0, len(flat), size)]
        tasks.sort(key=lambda t: -len(t))  # stable: the order of the groups otherwise

        def here(task):
            return self._evaluate_here(*args(task))

        futures = [self._pool.submit(_helper_evaluate, *args(t)) for t in tasks]
        got: list[list[Any] | None] = [None] * len(tasks)
        for k in range(len(tasks) - 1, -1, -1):
            if not futures[k].cancel():  # a helper has it (and every task before it)
                break
            got[k] = here(tasks[k])
        for k, fut in enumerate(futures):
            if got[k] is not None:
                continue
            try:
                res, n_eval = fut.result()
            except Exception:  # noqa: BLE001 - a helper that died: check its task here
                res, n_eval = here(tasks[k]), 0
            self.evaluations += n_eval
            for r in res:
                if hasattr(r, "results"):
                    r.table = self.table
            got[k] = res
        for task, res in zip(tasks, got):
            for (g, i, _, _, _), r in zip(task, res):
                out[g][i] = r
        return out

    def start_workers(self, workers: int | None = None) -> None:
        """Fork ``workers - 1`` helper processes (default: one per core, at most 4 in all)
        that check variants with a copy of this process's calculation cache as it is now
        (the nominal check's); nothing where fork is unavailable or with one core."""
        import multiprocessing as mp

        global _HELPER
        n = self.processes(workers)
        if n < 2 or self._pool is not None:
            return
        from concurrent.futures import ProcessPoolExecutor

        if self._pinned is None:
            self._pinned = set(self.cache)
        self.workers = n
        _HELPER = self
        self._pool = ProcessPoolExecutor(n - 1, mp_context=mp.get_context("fork"),
                                         initializer=_helper_start)
        # fork them now, with this cache (a later fork would copy more)
        for f in [self._pool.submit(_helper_ping) for _ in range(n - 1)]:
            f.result()

    @staticmethod
    def processes(workers: int | None = None) -> int:
        """Processes that :meth:`start_workers` would use: ``workers``, by default one per
        core and at most 4; 1 where fork is unavailable."""
        import multiprocessing as mp
        import os

        if "fork" not in mp.get_all_start_methods():
            return 1
        if workers is not None:
            return max(int(workers), 1)
        return min(len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                   else (os.cpu_count() or 1), 4)

    def stop_workers(self) -> None:
        """End the helper processes."""
        global _HELPER
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
        self.workers = 1
        _HELPER = None

    def _selection(self, select: list[str] | None) -> list[str] | None:
        """A variant's rule selection within the check's own."""
        sel = self.select if select is None else select
        if sel is not None and self.select is not None:
            sel = [s for s in sel if any(s.startswith(x) or x.startswith(s)
                                         for x in self.select)]
        return sel

    def _evaluate_here(self, changes: list[Changes], selects: list[list[str] | None],
                       speeds: list[tuple[float, ...] | None] | None = None) -> list[Any]:
        """:meth:`evaluate_variants` in this process, each variant on its own selection (and
        its own screening speeds, or all)."""
        import time

        from .. import api
        from ..description.engine import Engine

        out: list[Any] = []
        t0 = time.perf_counter()
        if self._pinned is None:
            self._pinned = set(self.cache)
        for start in range(0, len(changes), self.batch):
            built = [self._build(ch, sp) for ch, sp in zip(
                changes[start:start + self.batch],
                (speeds or [None] * len(changes))[start:start + self.batch])]
            sels = [self._selection(s) for s in selects[start:start + self.batch]]
            live = [(e, s) for e, s in zip(built, sels) if isinstance(e, Engine)]
            done: list[Any] | None = None
            if len(live) > 1:
                # the film orbits of the variants in one kernel call (same results as one by
                # one); a variant a calculation refuses is then checked alone below
                try:
                    done = api.check_batch([e for e, _ in live], rules=self.table,
                                           selects=[s for _, s in live],
                                           ignore=self.ignore, fail_on=self.fail_on,
                                           cache=self.cache, compare=False)
                except (ValueError, ArithmeticError):
                    done = None
            it = iter(done or ())
            for e, sel in zip(built, sels):
                if not isinstance(e, Engine):
                    out.append(e)
                elif done is not None:
                    out.append(next(it))
                else:
                    try:
                        out.append(api.check(e, rules=self.table, select=sel,
                                             ignore=self.ignore, fail_on=self.fail_on,
                                             cache=self.cache, compare=False))
                    except (ValueError, ArithmeticError) as exc:
                        out.append(_refused(exc))
                self.evaluations += 1
            self._evict()
        self.seconds += time.perf_counter() - t0
        return out


    def release(self) -> None:
        """End the helper processes, drop the variants' results from the cache (the check's
        own stay) and empty the film and heat-balance memos: hundreds of megabytes the report
        need not carry (its worker processes are forked from this one)."""
        from ..modules import film_memo, heat_memo

        self.stop_workers()
        for k in [k for k in self.cache if self._pinned is not None and k not in self._pinned]:
            del self.cache[k]
        self._sizes.clear()
        film_memo.clear()
        heat_memo.clear()

    def _evict(self) -> None:
        """Drop the oldest variant results beyond :attr:`keep_bytes`."""
        from ..evaluation import graph

        extra = [k for k in self.cache if k not in self._pinned]
        for k in extra:
            if k not in self._sizes:
                self._sizes[k] = graph.nbytes(self.cache[k])
        total = sum(self._sizes[k] for k in extra)
        for k in extra:
            if total <= self.keep_bytes:
                break
            total -= self._sizes.pop(k)
            del self.cache[k]


def _refused(exc: Exception) -> InputErrors:
    """A calculation refused the variant's values (outside its validity range): the variant
    is not a valid design, like an input error."""
    from ..errors import InputError

    return InputErrors([InputError("variant", f"{type(exc).__name__}: {exc}")])


TASKS_PER_PROCESS = 3
"""Tasks per process of a call with helper processes (:meth:`Evaluator.evaluate_groups`):
enough that the processes end together, few enough that the variants of a task share their
film orbits' kernel call."""

_HELPER: Evaluator | None = None
"""The evaluator of this process while it has helper processes (they inherit it by fork)."""


def _helper_start() -> None:
    """In a helper process: the interrupt is the parent's to handle (the helper is ended by
    :meth:`Evaluator.stop_workers` or with the parent's process group)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _helper_ping() -> bool:
    return _HELPER is not None


def _helper_evaluate(changes: list[Changes], selects: list[list[str] | None],
                     speeds: list[tuple[float, ...] | None] | None = None) -> tuple[list, int]:
    """In a helper process: check the variants with the inherited evaluator (its own cache
    grows from the parent's) and return their rule results without the calculated
    quantities (they stay in this process's cache), and the number of evaluations."""
    ev = _HELPER
    assert ev is not None
    n0 = ev.evaluations
    out = ev._evaluate_here(changes, selects, speeds)
    slim = []
    for r in out:
        if hasattr(r, "results"):
            r = dataclasses.replace(r, table=None,
                                    outcome=dataclasses.replace(r.outcome, quantities={}))
        slim.append(r)
    return slim, ev.evaluations - n0


def find(res: Any, rule: str, item: str):
    """The result (rule, item) of a check, or None."""
    if isinstance(res, InputErrors) or res is None:
        return None
    for r in res.results:
        if r.rule == rule and r.item == item:
            return r
    return None


def _affine_from(unit: str | None, kind: str) -> tuple[float, float]:
    """``si = a x + b`` for values ``x`` in ``unit``."""
    from ..workbook.units import to_si

    b = to_si(0.0, unit or None, kind)
    return to_si(1.0, unit or None, kind) - b, b


def _raw_number(v: Any) -> float | None:
    if v is None or (isinstance(v, str) and not v.strip()):
        return None
    if isinstance(v, bool):
        return None
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


@dataclass
class Binding:
    """The cells one lever or tolerance moves, with today's values."""

    sheet: str
    fields: tuple[Field, ...]
    unit: str
    targets: list[Target]  # one per field, same rows
    nominal: list[Any]  # per field: today's value (lever unit) of the first cell
    nominal_si: list[list[float | None]]  # per field, per cell: today's SI value
    labels: tuple[str, ...]

    @property
    def cells(self) -> set[tuple[str, int, int]]:
        return {(self.sheet, r, c) for t in self.targets for r, c, _ in t.cells}

    def _fmt(self, r: int, c: int) -> str | None:
        return self._base.sheets[self.sheet].rows.get(r, {}).get(c, (None, None))[1]

    def changes(self, value: Any) -> Changes:
        """Cell changes that put ``value`` (lever unit; a dict per column for a
        several-column choice; a text for a choice field) into the cells."""
        out: Changes = {}
        for k, (f, t) in enumerate(zip(self.fields, self.targets)):
            v = value.get(f.label) if isinstance(value, dict) else value
            if f.kind in ("text", "choice") or not isinstance(v, (int, float)):
                for r, c, _ in t.cells:
                    out[(self.sheet, r, c)] = v
                continue
            if f.kind == "int":
                for r, c, _ in t.cells:
                    out[(self.sheet, r, c)] = int(round(v))
                continue
            a, b = _affine_from(self.unit, f.kind)
            want0 = a * float(v) + b
            nom = self.nominal_si[k]
            for (r, c, unit), n_si in zip(t.cells, nom):
                if n_si is None or nom[0] is None:
                    new_si = want0
                elif f.kind in OFFSET_KINDS:
                    new_si = n_si + (want0 - nom[0])
                elif nom[0] == 0:
                    new_si = want0
                else:
                    new_si = n_si * want0 / nom[0]
                x = (new_si - b) / a  # in the lever unit
                out[(self.sheet, r, c)] = cell_value(t, unit, x, self._fmt(r, c))
        return out


def bind(base: Any, sheet: str, fields: tuple[Field, ...], unit: str, rows: tuple[str, ...] | None,
         where: tuple[tuple[str, str], ...], default: float | None = None) -> Binding | str:
    """Resolve the cells of (sheet, rows/where, fields) in the base workbook; a text saying
    why not (no such row or column) otherwise."""
    from ..errors import CheckerError
    from ..workbook.units import to_si

    spec = SHEETS[sheet]
    targets: list[Target] = []
    params = [Parameter(f.label, sheet, f, rows if spec.shape == "table" else None, where,
                        unit, values=(0.0,)) for f in fields]
    try:
        targets = resolve(Study(base.path, "remedies", "table", params), base)
    except CheckerError as exc:
        return "; ".join(getattr(exc, "problems", [str(exc)]))
    nominal: list[Any] = []
    nominal_si: list[list[float | None]] = []
    raw = base.sheets[sheet]
    for f, t in zip(fields, targets):
        per: list[float | None] = []
        first: Any = None
        for i, (r, c, cu) in enumerate(t.cells):
            v = raw.rows.get(r, {}).get(c, (None, None))
            if f.kind in ("text", "choice", "int_list"):
                per.append(None)
                if i == 0:
                    first = v[0]
                continue
            x = _raw_number(v[0])
            if x is None:
                si = None if default is None else to_si(default, unit or None, f.kind)
            elif f.kind == "int":
                si = x
            else:
                try:
                    si = to_si(x, cu, f.kind, percent_formatted="%" in (v[1] or ""))
                except Exception:  # noqa: BLE001 - the loader reports bad cells
                    si = None
            per.append(si)
            if i == 0 and si is not None:
                if f.kind == "int":
                    first = si
                else:
                    a, b = _affine_from(unit, f.kind)
                    first = (si - b) / a
        nominal.append(first)
        nominal_si.append(per)
    labels = tuple(x for t in targets for x in t.labels)
    b = Binding(sheet, fields, unit, targets, nominal, nominal_si, labels)
    b._base = base
    return b
