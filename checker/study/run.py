"""Run a study: every variant validated and checked, results stored as they arrive.

Execution engines (no home-made scheduling):

* ``local`` (default): :class:`concurrent.futures.ProcessPoolExecutor` with one worker process
  per core; each worker loads the base workbook once (pool initializer) and keeps a
  calculation cache (:func:`checker.evaluation.graph.input_key`), so a variant that changes only
  bearing
  clearances reuses the loads computed for an earlier variant in the same worker.
* ``dask``: the same task on a Dask distributed cluster (``distributed.Client``, futures,
  ``as_completed``): a scheduler address, or ``"local"`` for a :class:`LocalCluster`.

A task is a chunk (a list) of variants, checked together by :func:`evaluate_chunk`
(:func:`checker.api.check_batch`: the film orbits of the chunk in one kernel call per model);
chunks are largest first and single variants at the end (:func:`plan_chunks`), so the workers
finish together. Only a few chunks per worker are queued at a time, and a worker's
calculation cache is bounded (:class:`CalcCache`): memory does not grow with the number of
variants, and an interruption has little to cancel.

Each finished variant is written at once to ``<out>/variants/<id>.json`` (atomic rename of a
uniquely named temporary file; by the local worker that checked it, by the study process for
Dask), so an interrupted study keeps what finished and a re-run skips it (resume).
Records are read back from disk when needed, never all held in memory.
A variant with bad values is reported with the study line and the workbook cell and the
study goes on (fail-soft).

Before any work: the study's size (:data:`checker.study.spec.MAX_VARIANTS`), the rule
selection, the base workbook, the output folder (writable, a folder, not in use by another
study: ``<out>/.checker-study.lock``, :func:`fcntl.flock`) and the Dask scheduler (reachable
within :data:`DASK_CONNECT_TIMEOUT` seconds) are checked; each problem is one sentence.
On Ctrl-C or SIGTERM (:mod:`checker.plumbing.interrupt`) pending variants are cancelled, the worker
processes ended, and the finished variants stay on disk.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from collections import OrderedDict
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import CheckerError, InputErrors, UsageProblem
from ..outputs.files import file_mode
from .apply import Target, apply_variant, resolve
from .design import Variant, variants
from .spec import Study, StudyFileError

_WORKER: dict[str, Any] = {}  # per worker process: base workbook, targets, graph cache

#: Seconds to wait for a Dask scheduler before saying it cannot be reached.
DASK_CONNECT_TIMEOUT = 8
#: Most variants per task (a worker checks a chunk together: :func:`evaluate_chunk`). Chunks
#: shrink towards the end of a study (:func:`plan_chunks`), so no worker waits long for the
#: last one. 4: the batching gain of 8 or 10 (1.38 against 1.37 s of CPU per variant of the
#: Latin-hypercube benchmark), half the variants lost to a Ctrl-C in the first chunks and
#: about 300 MB less memory per worker.
CHUNK = 4
#: Arrays a worker's calculation cache keeps between chunks (:class:`CalcCache`), bytes.
CACHE_BYTES = 192 * 2**20
LOCK_NAME = ".checker-study.lock"


class StudyOutputError(CheckerError):
    """The output folder cannot be used (not writable, a file, in use): one sentence."""


class DaskUnreachable(CheckerError):
    """The Dask scheduler address is malformed or nothing answers there."""


class RecordStore(Sequence):
    """The variants' stored records, read from ``variants/<id>.json`` one at a time (in
    variant order), so a 1000-variant study never holds every result in memory."""

    def __init__(self, folder: Path, keys: list[str]):
        self.folder = Path(folder)
        self.keys = list(keys)

    def __len__(self) -> int:
        return len(self.keys)

    def __getitem__(self, i):  # type: ignore[override]
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        return json.loads((self.folder / f"{self.keys[i]}.json").read_text(encoding="utf-8"))

    def __iter__(self) -> Iterator[dict]:
        for i in range(len(self)):
            yield self[i]

    def on_disk(self) -> int:
        """How many of the variants have a stored record."""
        return sum(1 for k in self.keys if (self.folder / f"{k}.json").is_file())


@dataclass
class StudyRun:
    """What a study produced: the variants, their stored records, where they are."""

    study: Study
    base_path: str
    base_sha256: str
    variants: list[Variant]
    targets: list[Target]
    records: Sequence[dict]  # one per variant, in variant order (read from disk on access)
    out_dir: Path
    computed: int = 0  # variants computed in this run (the others were resumed)
    seconds: float = 0.0
    engine: str = "local"
    extra: dict[str, Any] = field(default_factory=dict)

    def input_errors(self) -> list[dict]:
        """The variants with bad values: number (1-based, as in the tables and the PDF),
        name, errors (each with study line and workbook cell)."""
        return [{"variant": r["index"] + 1, "name": r["name"], "errors": r["errors"]}
                for r in self.records if r["status"] == "input error"]


# ---------------------------------------------------------------------------------------
# evaluation (in a worker)


def _setup(base, targets, select, ignore, fail_on) -> None:
    if _WORKER.get("sha") != base.sha256 or _WORKER.get("targets") != targets:
        _WORKER.clear()
        _WORKER.update(sha=base.sha256, base=base, targets=targets, cache=CalcCache(),
                       select=select, ignore=ignore, fail_on=fail_on)


class CalcCache(OrderedDict):
    """A worker's calculation cache (:func:`checker.evaluation.graph.run` ``cache``), least
    recently used
    first out: after each chunk it is trimmed to :data:`CACHE_BYTES` of arrays.

    What variants share (the loads of a clearance study, the torsional model of an oil study)
    is read by every variant and so stays; the outputs of a Latin-hypercube variant (about
    70 MB for the example I4 with every rule) are not read again and leave. Without the bound
    a worker kept every variant's quantities: about 1.8 GB after 20 variants."""

    def __init__(self) -> None:
        super().__init__()
        self.sizes: dict[str, int] = {}

    def get(self, key, default=None):  # type: ignore[override]
        if key in self:
            self.move_to_end(key)
            return self[key]
        return default

    def trim(self, limit: int) -> None:
        """Drop the least recently used entries until the arrays held are at most ``limit``
        bytes (an entry alone larger than ``limit`` is dropped too)."""
        from ..evaluation import graph

        for k in self:
            if k not in self.sizes:
                self.sizes[k] = graph.nbytes(self[k])
        total = sum(self.sizes[k] for k in self)
        while self and total > limit:
            k, _ = self.popitem(last=False)
            total -= self.sizes.pop(k, 0)
        for k in [k for k in self.sizes if k not in self]:
            del self.sizes[k]


def _where(variant: Variant, targets: list[Target], cell: str) -> str:
    """``study line N (parameter 'x')`` for the study entry that put a value into ``cell``."""
    if variant.line:
        return f"study line {variant.line} (variant '{variant.name}')"
    given = [t for t in targets if dict(variant.values).get(t.param.name) is not None]
    own = [t for t in given if cell in t.labels] or given  # else: a cell the values affect
    if not own:
        return "the base workbook"
    if len(own) == 1:
        return f"study line {own[0].param.line} (parameter '{own[0].param.name}')"
    return ("study lines " + ", ".join(str(t.param.line) for t in own) + " (parameters "
            + ", ".join(f"'{t.param.name}'" for t in own) + ")")


def _table():
    from ..evaluation.ruletable import load_rules

    if "table" not in _WORKER:
        _WORKER["table"] = load_rules(None)
    return _WORKER["table"]


def _record(variant: Variant, key: str) -> dict[str, Any]:
    return {"id": key, "index": variant.index, "name": variant.name,
            "values": [[k, v] for k, v in variant.values]}


def _input_error(rec: dict, variant: Variant, exc: InputErrors) -> dict:
    errs = []
    for e in exc.errors:
        cell = getattr(e, "where", "")
        errs.append(f"{_where(variant, _WORKER['targets'], str(cell))}: {e}")
    rec.update(status="input error", errors=errs, results=[])
    return rec


def _build(variant: Variant):
    """The variant's engine (InputErrors for its bad values, workbook limit overrides
    included)."""
    from ..description.engine import build_engine
    from ..evaluation.ruletable import override_problems
    from ..workbook.loader import convert_raw

    w = _WORKER
    table = _table()
    raw = apply_variant(w["base"], w["targets"], dict(variant.values))
    return build_engine(convert_raw(raw, raise_errors=False),
                        lambda ovs: override_problems(table, ovs)[2])


def _finish(rec: dict, res, seconds: float) -> dict:
    rec.update(status="nothing checked" if res.nothing_checked else "checked",
               verdict=res.verdict, complete=res.complete, errors=[],
               warnings=[str(x) for x in getattr(res.engine, "warnings", ())],
               results=[r.as_dict() for r in res.results])
    rec["seconds"] = round(seconds, 3)
    return rec


def _evaluate(variant: Variant, key: str) -> dict:
    """Check one variant in this worker; never raises for a variant's own bad input."""
    from .. import api

    w = _WORKER
    t0 = time.perf_counter()
    rec = _record(variant, key)
    try:
        engine = _build(variant)
        res = api.check(engine, rules=_table(), select=w["select"], ignore=w["ignore"],
                        fail_on=w["fail_on"], cache=w["cache"])
    except InputErrors as exc:
        return _input_error(rec, variant, exc)
    return _finish(rec, res, time.perf_counter() - t0)


def _films_batched(engine) -> bool:
    """Whether the study's rule selection needs a film calculation that
    :func:`checker.api.check_batch` batches (else batching only adds its planning)."""
    if "batched" not in _WORKER:
        from .. import api
        from ..evaluation import graph
        from ..evaluation.ruletable import select_rules

        w = _WORKER
        wanted = {r.quantity for r in select_rules(_table(), w["select"], w["ignore"])}
        wanted |= {n for q in list(wanted) for _, n in graph.QUANTITIES[q].compare}
        order = graph.plan(engine, wanted)
        w["batched"] = any(c in order for c, _, _ in api._BATCHED_FILMS)
    return _WORKER["batched"]


def evaluate_chunk(items: list[tuple[Variant, str]]) -> list[dict]:
    """Check a chunk of variants (``(variant, id)`` pairs) in this worker, one record each,
    in the order given.

    The chunk's valid variants are checked together by :func:`checker.api.check_batch` (their
    film orbits in one kernel call per model; the same results as one by one, tests) when
    the rule selection needs film orbits, else one by one (e.g. a joints study: batching
    would only add its planning); a variant with bad values gets its input-error record.
    A record's ``seconds`` is its own check's time, or its share of a batch's."""
    from .. import api

    w = _WORKER
    try:
        if len(items) == 1:
            return [_evaluate(*items[0])]
        t0 = time.perf_counter()
        out: list[dict | None] = [None] * len(items)
        ok: list[tuple[int, dict, Any]] = []
        for i, (v, k) in enumerate(items):
            rec = _record(v, k)
            try:
                ok.append((i, rec, _build(v)))
            except InputErrors as exc:
                out[i] = _input_error(rec, v, exc)
        if len(ok) == 1 or (ok and not _films_batched(ok[0][2])):
            # nothing to batch (no film orbits in the selection): one by one, as cheap
            t1 = time.perf_counter()
            for i, rec, engine in ok:
                try:
                    res = api.check(engine, rules=_table(), select=w["select"],
                                    ignore=w["ignore"], fail_on=w["fail_on"], cache=w["cache"])
                except InputErrors as exc:
                    out[i] = _input_error(rec, items[i][0], exc)
                    continue
                out[i] = _finish(rec, res, time.perf_counter() - t1)
                t1 = time.perf_counter()
        elif ok:
            try:
                results = api.check_batch([e for _, _, e in ok], rules=_table(),
                                          select=w["select"], ignore=w["ignore"],
                                          fail_on=w["fail_on"], cache=w["cache"])
            except InputErrors:  # not expected (checked when built): each its own message
                return [_evaluate(v, k) for v, k in items]
            share = (time.perf_counter() - t0) / len(items)
            for (i, rec, _), res in zip(ok, results):
                out[i] = _finish(rec, res, share)
        return [r for r in out if r is not None]
    finally:
        cache = w.get("cache")
        if isinstance(cache, CalcCache):
            cache.trim(CACHE_BYTES)


def _init_local_worker(setup_args) -> None:
    from ..plumbing.interrupt import worker_signals

    worker_signals()
    _die_with_parent()
    _setup(*setup_args)


def _die_with_parent() -> None:
    """Linux: the kernel ends this worker if the study process dies (even by SIGKILL)."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes
        import signal

        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, int(signal.SIGTERM))  # PDEATHSIG
    except (OSError, AttributeError):  # pragma: no cover - another libc
        pass


def _local_chunk(items, folder: Path) -> list[dict]:
    """A local worker's task: the chunk's records written to ``folder`` here (atomic), only
    their ids returned: the messages back to the study process stay a few bytes, so a worker
    ended in the middle of one (an interruption) never leaves half a message behind."""
    out = []
    for rec in evaluate_chunk(items):
        with _sigterm_held():  # the study ending its workers waits until the record is whole
            _write_record(folder, rec)
        out.append({"id": rec["id"], "written": True})
    return out


@contextmanager
def _sigterm_held() -> Iterator[None]:
    """SIGTERM blocked while inside (POSIX); delivered when the block ends."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _dask_chunk(base, targets, sel, ign, fo, items) -> list[dict]:
    _setup(base, targets, sel, ign, fo)
    return evaluate_chunk(items)


# ---------------------------------------------------------------------------------------
# output folder: checked before work, locked while a study writes


def _short(exc: BaseException) -> str:
    text = (exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def check_output(out_dir: str | Path) -> None:
    """Raise :class:`StudyOutputError` (one sentence) unless ``out_dir`` is, or can be
    created as, a writable folder. Creates nothing."""
    out = Path(out_dir)
    if out.exists():
        if not out.is_dir():
            raise StudyOutputError(f"the output folder {out} is a file; give a folder name")
        try:
            fd, tmp = tempfile.mkstemp(prefix=".checker-write-test-", dir=out)
            os.close(fd)
            os.unlink(tmp)
        except OSError as exc:
            raise StudyOutputError(f"cannot write to the output folder {out}"
                                   f" ({_short(exc)})") from None
        for sub in ("variants",):
            p = out / sub
            if p.exists() and (not p.is_dir() or not os.access(p, os.W_OK | os.X_OK)):
                raise StudyOutputError(f"cannot write to {p} (not a writable folder)")
        return
    parent = out.absolute().parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise StudyOutputError(f"cannot create the output folder {out}: {parent} is a file")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise StudyOutputError(f"cannot create the output folder {out}: {parent} is not"
                               " writable")


@contextmanager
def output_lock(out_dir: str | Path) -> Iterator[Path]:
    """Create ``out_dir`` and hold its lock file while inside; a second study into the same
    folder gets :class:`StudyOutputError` ("another study is writing to ...") at once.

    A folder this call created is removed again if the body fails before writing into it
    (no empty output folders from a refused study)."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX: no lock
        fcntl = None
    out = Path(out_dir)
    check_output(out)
    created = not out.exists()
    try:
        out.mkdir(parents=True, exist_ok=True)
        fd = os.open(out / LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o666)
    except OSError as exc:
        raise StudyOutputError(f"cannot write to the output folder {out} ({_short(exc)})"
                               ) from None
    try:
        try:
            if fcntl is not None:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise StudyOutputError(f"another study is writing to {out}; wait for it to"
                                   " finish or choose another output folder") from None
        try:
            os.ftruncate(fd, 0)
            os.write(fd, f"{os.getpid()}\n".encode())
        except OSError:
            pass
        ok = False
        try:
            yield out
            ok = True
        finally:
            if created and not ok:
                try:
                    names = set(os.listdir(out))
                    if names <= {LOCK_NAME}:
                        os.unlink(out / LOCK_NAME)
                        out.rmdir()
                except OSError:
                    pass
    finally:
        os.close(fd)  # releases the lock


def _write_record(folder: Path, rec: dict) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    data = json.dumps(rec, sort_keys=True, indent=1, default=str).encode("utf-8")
    fd, tmp = tempfile.mkstemp(prefix=f".{rec['id']}.", suffix=".tmp", dir=folder)
    try:
        os.fchmod(fd, file_mode())
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, folder / f"{rec['id']}.json")
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


# ---------------------------------------------------------------------------------------
# planning (everything that can be checked before work) and running


@dataclass
class StudyPlan:
    """A validated study on a base workbook: its variants and cells, nothing run yet."""

    study: Study
    base_path: str
    base: Any  # RawWorkbook
    targets: list[Target]
    variants: list[Variant]
    keys: list[str]

    def base_cells(self) -> dict[tuple[str, int, int], Any]:
        """The base workbook's value of every targeted cell: (sheet, row, column) -> value
        (the baseline of a parameter a variant leaves unchanged)."""
        out = {}
        for t in self.targets:
            rows = self.base.sheets[t.param.sheet].rows
            for r, c, _ in t.cells:
                out[(t.param.sheet, r, c)] = rows.get(r, {}).get(c, (None, None))[0]
        return out

    @property
    def setup_args(self) -> tuple:
        return (self.base, self.targets, self.study.select, self.study.ignore,
                self.study.fail_on)


def plan_study(study: Study, workbook: str | Path) -> StudyPlan:
    """Validate the study against ``workbook``: the base must be a valid workbook
    (InputErrors), the rule selection and the parameters' cells must exist
    (:class:`StudyFileError` naming the study lines). Writes nothing."""
    from ..description.engine import build_engine
    from ..evaluation.ruletable import load_rules, select_rules
    from ..workbook.loader import convert_raw, read_raw_workbook

    base = read_raw_workbook(workbook)
    build_engine(convert_raw(base, raise_errors=False))  # the base must be a valid workbook
    try:
        select_rules(load_rules(None), study.select, study.ignore)
    except UsageProblem as exc:
        raise _selection_error(study, exc) from None
    targets = resolve(study, base)
    vs = variants(study)
    keys = [v.key(base.sha256, study) for v in vs]
    return StudyPlan(study, str(workbook), base, targets, vs, keys)


def _selection_error(study: Study, exc: UsageProblem) -> StudyFileError:
    """A rule selection problem, named by its study-file line (with a "did you mean")."""
    from ..evaluation.ruletable import load_rules
    from .spec import did_you_mean

    text = str(exc).strip()
    ids = [r.id for r in load_rules(None).rules]
    choices = ids + sorted({i.split("-")[0] for i in ids})
    for k in ("select", "ignore"):
        bad = [v for v in getattr(study, k) or [] if f"'{v}'" in text]
        if bad:
            hint = "".join(did_you_mean(v, choices) for v in bad)
            return StudyFileError(study.path, [f"{study.line_of(k)}: '{k}': {text}{hint}"])
    return StudyFileError(study.path, [f"{study.line_of('select')}: {text}"])


class _Sink:
    """Writes each finished record and counts; progress on stderr."""

    def __init__(self, folder: Path, total: int, progress: bool, say):
        self.folder = folder
        self.total = total
        self.count = 0
        self.say = say
        self.bar = None
        if progress:
            from tqdm import tqdm

            self.bar = tqdm(total=total, desc="checker: variants", unit="variant",
                            file=sys.stderr, dynamic_ncols=True, leave=True)
        self.step = max(1, total // 10)
        self.t0 = time.monotonic()

    def __call__(self, rec: dict) -> None:
        if not rec.get("written"):  # else a local worker wrote it
            _write_record(self.folder, rec)
        self.count += 1
        if self.bar is not None:
            self.bar.update(1)
        elif self.count % self.step == 0 and self.count < self.total:
            self.say(f"{self.count} of {self.total} variants done"
                     f" ({time.monotonic() - self.t0:.0f} s)")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def plan_chunks(todo: list, workers: int, most: int | None = None) -> list[list]:
    """``todo`` in consecutive chunks, largest first (guided self-scheduling: each chunk a
    third of the remaining variants' share per worker, at most ``most`` = :data:`CHUNK`, at
    least 1): big chunks batch more variants, the last ones are single variants, so the
    workers finish together."""
    most = CHUNK if most is None else most
    out, i = [], 0
    while i < len(todo):
        size = max(1, min(most, -(-(len(todo) - i) // (3 * max(1, workers)))))
        out.append(todo[i:i + size])
        i += size
    return out


def run_plan(plan: StudyPlan, out_dir: str | Path, workers: int | None = None,
             dask: str | None = None, progress: bool = False,
             say: Callable[[str], None] | None = None, client: Any = None) -> StudyRun:
    """Run the variants of ``plan`` not yet on disk in ``out_dir`` (the caller holds
    :func:`output_lock`). ``client``: a connected Dask engine from :func:`connect_dask`."""
    t0 = time.perf_counter()
    say = say or (lambda s: None)
    out = Path(out_dir)
    folder = out / "variants"
    st = plan.study
    done = {k for k in plan.keys if (folder / f"{k}.json").is_file()}
    for tmp in folder.glob(".*.tmp") if folder.is_dir() else ():  # a killed writer's (we
        try:  # hold the folder's lock: nobody else writes here)
            tmp.unlink()
        except OSError:
            pass
    todo = [(v, k) for v, k in zip(plan.variants, plan.keys) if k not in done]
    n_local = max(1, min(workers or os.cpu_count() or 1, max(len(todo), 1)))
    say(f"study '{st.name}': {len(plan.variants)} variants ({st.design}), {len(done)} already"
        f" done, {len(todo)} to run"
        + (f" on Dask ({dask})" if dask else
           f" on {n_local} local worker process{'es' if n_local != 1 else ''}"))
    sink = _Sink(folder, len(todo), progress, say)
    engine_name = "dask" if dask else "local"
    try:
        if todo:
            if dask:
                own = client is None
                eng = client or connect_dask(dask, workers)
                try:
                    _run_dask(eng, plan.setup_args, todo, sink)
                finally:
                    if own:
                        eng.close()
            else:
                _run_local(plan.setup_args, plan_chunks(todo, n_local), n_local, sink)
    finally:
        sink.close()
    return StudyRun(st, plan.base_path, plan.base.sha256, plan.variants, plan.targets,
                    RecordStore(folder, plan.keys), out, computed=sink.count,
                    seconds=time.perf_counter() - t0, engine=engine_name,
                    extra={"base_cells": plan.base_cells()})


def run_study(study: Study, workbook: str | Path, out_dir: str | Path,
              workers: int | None = None, dask: str | None = None,
              progress: bool = False, say: Callable[[str], None] | None = None) -> StudyRun:
    """Run every variant of ``study`` on ``workbook``; results go to ``out_dir``.

    Raises InputErrors when the base workbook itself is not valid (nothing to vary),
    :class:`checker.study.spec.StudyFileError` when a parameter's cells are not in it,
    :class:`StudyOutputError` when ``out_dir`` cannot be written or another study writes
    to it, :class:`DaskUnreachable` for a bad scheduler address; all before any work.
    """
    plan = plan_study(study, workbook)
    check_output(out_dir)
    client = connect_dask(dask, workers) if dask else None
    try:
        with output_lock(out_dir):
            return run_plan(plan, out_dir, workers=workers, dask=dask, progress=progress,
                            say=say, client=client)
    finally:
        if client is not None:
            client.close()


# ---------------------------------------------------------------------------------------
# engines


def _drain(futs: Iterable, sink, result: Callable[[Any], list[dict]]) -> None:
    """Store the records of futures that finished but were not consumed yet (after an
    interruption): every finished variant is kept."""
    for f in futs:
        try:
            if f.done() and not f.cancelled():
                for rec in result(f):
                    sink(rec)
        except Exception:  # noqa: BLE001 - a failed chunk has nothing to keep
            pass


def _run_local(setup_args, chunks: list[list], n: int, sink) -> None:
    if n == 1:
        _setup(*setup_args)
        for ch in chunks:
            for rec in evaluate_chunk(ch):
                sink(rec)
        return
    import multiprocessing as mp
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
    from concurrent.futures.process import BrokenProcessPool

    ctx = mp.get_context("fork" if sys.platform.startswith("linux") else "spawn")
    ex = ProcessPoolExecutor(max_workers=n, mp_context=ctx, initializer=_init_local_worker,
                             initargs=(setup_args,))
    queue = iter(chunks)
    pending: set = set()
    clean = False
    try:
        def fill() -> None:
            while len(pending) < 2 * n:
                ch = next(queue, None)
                if ch is None:
                    return
                pending.add(ex.submit(_local_chunk, ch, sink.folder))

        fill()
        while pending:
            done, rest = wait(pending, return_when=FIRST_COMPLETED)
            for f in done:
                try:
                    recs = f.result()
                except BrokenProcessPool:
                    raise CheckerError("a worker process of the study ended unexpectedly"
                                       " (killed, or out of memory); the finished variants"
                                       " are kept, re-run to resume") from None
                pending.discard(f)
                for rec in recs:
                    sink(rec)
            fill()
        clean = True
    except BaseException:
        _drain(list(pending), sink, lambda f: f.result(timeout=0))
        raise
    finally:
        procs = list((getattr(ex, "_processes", None) or {}).values())
        manager = getattr(ex, "_executor_manager_thread", None)
        ex.shutdown(wait=clean, cancel_futures=True)
        if not clean:  # interrupted or failed: end the workers now, not after their tasks
            for p in procs:
                if p.is_alive():
                    p.terminate()
            for p in procs:
                p.join(timeout=3)
                if p.is_alive():
                    p.kill()
                    p.join(timeout=3)
            # the pool's manager thread sees its workers gone and closes its wake-up pipe;
            # waited for here, or the interpreter's exit may write to that pipe while it is
            # being closed ("OSError: [Errno 9] Bad file descriptor" after the command's
            # last line, about one interrupted study in fifteen on a loaded machine)
            if manager is not None:
                manager.join(timeout=3)


class DaskEngine:
    """A connected Dask client (and the LocalCluster it started, if any)."""

    def __init__(self, client, cluster=None, address: str = ""):
        self.client = client
        self.cluster = cluster
        self.address = address

    interrupted = False

    def close(self) -> None:
        if self.interrupted and self.cluster is not None:
            self._stop_workers_now()
        try:
            self.client.close(timeout=5)
        except Exception:  # noqa: BLE001 - closing a broken connection
            pass
        if self.cluster is not None:
            try:
                self.cluster.close(timeout=5)
            except Exception:  # noqa: BLE001
                pass

    def _stop_workers_now(self) -> None:
        """End the LocalCluster's worker processes at once (a busy worker otherwise gets 4 s
        to finish its variant): each nanny closes its worker with a 1 s grace, then kills it
        (a closing nanny does not restart it)."""
        import asyncio

        workers = list(getattr(self.cluster, "workers", {}).values())

        async def stop() -> None:
            await asyncio.gather(*(w.close(timeout=1) for w in workers if hasattr(w, "close")),
                                 return_exceptions=True)

        try:
            self.cluster.sync(stop)
        except Exception:  # noqa: BLE001 - the cluster's own close follows anyway
            pass


@contextmanager
def _sigint_ignored() -> Iterator[None]:
    """Ignore SIGINT while inside: processes started meanwhile inherit "ignored" (it survives
    exec), so a LocalCluster's workers leave a Ctrl-C to the process group to this process,
    which ends them. A Ctrl-C during these few seconds of start-up is lost."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)


class _InterruptedSyncNoise:
    """Logging filter: drops the traceback that Dask's event loop logs when a Ctrl-C reaches a
    blocking call (``distributed.utils.sync``) before its coroutine started: the ``cancel``
    callback it then schedules reads its not yet assigned ``future`` and raises ``NameError``
    in the loop thread, which tornado logs ("Exception in callback ... NameError: cannot
    access free variable 'future'"; distributed 2026.8). The interruption itself is handled
    (variants kept, exit 130); only that record is dropped, any other is logged."""

    def filter(self, record) -> bool:
        exc = record.exc_info[1] if record.exc_info else None
        if not isinstance(exc, NameError) or "future" not in str(exc):
            return True
        tb = record.exc_info[2]
        while tb is not None and tb.tb_next is not None:
            tb = tb.tb_next
        code = tb.tb_frame.f_code if tb is not None else None
        return not (code is not None and code.co_name == "cancel"
                    and code.co_filename.replace("\\", "/").endswith("distributed/utils.py"))


_SYNC_NOISE = _InterruptedSyncNoise()


def connect_dask(address: str, workers: int | None = None) -> DaskEngine:
    """Start a LocalCluster (``"local"``) or connect to the scheduler at ``address`` within
    :data:`DASK_CONNECT_TIMEOUT` s; :class:`DaskUnreachable` (one sentence) otherwise."""
    import logging

    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise DaskUnreachable("--dask needs the Dask distributed package (pip install"
                              " 'dask[distributed]')") from None
    tornado_log = logging.getLogger("tornado.application")
    if _SYNC_NOISE not in tornado_log.filters:
        tornado_log.addFilter(_SYNC_NOISE)
    if address == "local":
        import dask

        try:
            # Dask sets MALLOC_TRIM_THRESHOLD_=65536 in its workers' environment: glibc then
            # maps and unmaps every large NumPy temporary (the orbit kernel's), which made a
            # variant take 1.6x the CPU of a local worker (most of it system time); the
            # workers keep glibc's default here
            with _sigint_ignored(), dask.config.set(
                    {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
                # the workers inherit SIG_IGN: a Ctrl-C is for this process
                # the workers' own logs only for critical events: a variant's error reaches
                # this process through its future; at an interruption a worker whose
                # heartbeat meets the closed scheduler logs an error with a traceback
                # ("Failed to communicate with scheduler during heartbeat")
                cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1,
                                       threads_per_worker=1, processes=True,
                                       dashboard_address=None,
                                       silence_logs=logging.CRITICAL)
                client = Client(cluster)
        except Exception as exc:  # noqa: BLE001 - e.g. no free port, no process allowed
            raise DaskUnreachable(f"cannot start a local Dask cluster ({_short(exc)})"
                                  ) from None
        return DaskEngine(client, cluster, address)
    try:
        client = Client(address, timeout=DASK_CONNECT_TIMEOUT)
    except Exception as exc:  # noqa: BLE001 - any failure to connect is the address's
        raise DaskUnreachable(f"cannot reach the Dask scheduler at '{address}' ({_short(exc)});"
                              " give its address as tcp://host:port, or 'local'") from None
    return DaskEngine(client, None, address)


def _run_dask(eng: DaskEngine, setup_args, todo: list, sink) -> None:
    from distributed import as_completed

    client = eng.client
    n = max(1, len(client.scheduler_info().get("workers", {})) or 1)
    chunks = plan_chunks(todo, n)
    base_f = client.scatter(setup_args[0], broadcast=True)
    queue = iter(chunks)
    live: set = set()

    def submit(ch):
        f = client.submit(_dask_chunk, base_f, *setup_args[1:], ch,
                          key=f"checker-variants-{ch[0][1]}", pure=False)
        live.add(f)
        return f

    first = [submit(ch) for ch in (next(queue, None) for _ in range(2 * n)) if ch is not None]
    ac = as_completed(first)
    try:
        for f in ac:
            recs = f.result()
            live.discard(f)
            for rec in recs:
                sink(rec)
            ch = next(queue, None)
            if ch is not None:
                ac.add(submit(ch))
    except BaseException:
        _drain(list(live), sink, lambda f: f.result(timeout=1) if f.status == "finished"
               else [])
        import logging

        # closing a LocalCluster with busy workers is noisy ("still alive, killing")
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        eng.interrupted = True
        if eng.cluster is None:  # a shared scheduler: release the pending variants now
            try:
                client.cancel(list(live))
            except Exception:  # noqa: BLE001
                pass
        raise
