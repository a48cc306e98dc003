"""Run a study: every variant validated and checked, results stored as they arrive.

Execution engines (no home-made scheduling):

* ``local`` (default): :class:`concurrent.futures.ProcessPoolExecutor` with one worker process
  per core; each worker loads the base workbook once and keeps a calculation cache
  (:func:`checker.graph.input_key`), so a variant that changes only bearing clearances
  reuses the loads computed for an earlier variant in the same worker.
* ``dask``: the same task on a Dask distributed cluster (``distributed.Client``, futures,
  ``as_completed``): a scheduler address, or ``"local"`` for a :class:`LocalCluster`.

Each finished variant is written at once to ``<out>/variants/<id>.json`` (atomic rename), so
a killed study keeps what finished and a re-run skips it (resume). A variant with bad values
is reported with the study line and the workbook cell and the study goes on (fail-soft).
"""

from __future__ import annotations

import json
import os
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputErrors
from .apply import Target, apply_variant, resolve
from .design import Variant, variants
from .spec import Study

_WORKER: dict[str, Any] = {}  # per worker process: base workbook, targets, graph cache


@dataclass
class StudyRun:
    """What a study produced: the variants, their stored records, where they are."""

    study: Study
    base_path: str
    base_sha256: str
    variants: list[Variant]
    targets: list[Target]
    records: list[dict]  # one per variant, in variant order
    out_dir: Path
    computed: int = 0  # variants computed in this run (the others were resumed)
    seconds: float = 0.0
    engine: str = "local"
    extra: dict[str, Any] = field(default_factory=dict)


def _setup(base, targets, select, ignore, fail_on) -> None:
    if _WORKER.get("sha") != base.sha256:
        _WORKER.clear()
        _WORKER.update(sha=base.sha256, base=base, targets=targets, cache={},
                       select=select, ignore=ignore, fail_on=fail_on)


def _evaluate(variant: Variant, key: str) -> dict:
    """Check one variant in this worker; never raises for a variant's own bad input."""
    from .. import api
    from ..engine import build_engine
    from ..ruletable import load_rules, override_problems
    from ..workbook.loader import convert_raw

    w = _WORKER
    t0 = time.perf_counter()
    rec: dict[str, Any] = {"id": key, "index": variant.index, "name": variant.name,
                           "values": [[k, v] for k, v in variant.values]}
    try:
        raw = apply_variant(w["base"], w["targets"], dict(variant.values))
        data = convert_raw(raw, raise_errors=False)
        table = w.get("table") or load_rules(None)
        w["table"] = table
        resolved: dict[str, Any] = {}

        def _ovr(ovs):
            resolved["r"], resolved["a"], errs = override_problems(table, ovs)
            return errs

        engine = build_engine(data, _ovr)
        from ..ruletable import RuleTable

        res = api.check(engine, rules=RuleTable(resolved["r"], table.files, resolved["a"]),
                        select=w["select"], ignore=w["ignore"], fail_on=w["fail_on"],
                        cache=w["cache"])
    except InputErrors as exc:
        rec.update(status="input error", errors=[str(e) for e in exc.errors], results=[])
        return rec
    rec.update(status="nothing checked" if res.nothing_checked else "checked",
               verdict=res.verdict, complete=res.complete, errors=[],
               warnings=[str(x) for x in getattr(res.engine, "warnings", ())],
               results=[r.as_dict() for r in res.results])
    rec["seconds"] = round(time.perf_counter() - t0, 3)
    return rec


def _local_task(args) -> dict:
    base, targets, sel, ign, fo, variant, key = args
    _setup(base, targets, sel, ign, fo)
    return _evaluate(variant, key)


def _dask_task(base, targets, sel, ign, fo, variant, key) -> dict:
    _setup(base, targets, sel, ign, fo)
    return _evaluate(variant, key)


def _write_record(folder: Path, rec: dict) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    tmp = folder / f".{rec['id']}.tmp"
    tmp.write_text(json.dumps(rec, sort_keys=True, indent=1, default=str), encoding="utf-8")
    os.replace(tmp, folder / f"{rec['id']}.json")


def _progress_bar(total: int, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, desc="checker: variants", unit="variant", file=sys.stderr,
                disable=not enabled, dynamic_ncols=True, leave=True)


def run_study(study: Study, workbook: str | Path, out_dir: str | Path,
              workers: int | None = None, dask: str | None = None,
              progress: bool = False, say: Callable[[str], None] | None = None) -> StudyRun:
    """Run every variant of ``study`` on ``workbook``; results go to ``out_dir``.

    Raises InputErrors when the base workbook itself is not valid (nothing to vary), and
    :class:`checker.study.spec.StudyFileError` when a parameter's cells are not in it.
    """
    from ..engine import build_engine
    from ..ruletable import load_rules, select_rules
    from ..workbook.loader import convert_raw, read_raw_workbook

    t0 = time.perf_counter()
    say = say or (lambda s: None)
    out = Path(out_dir)
    base = read_raw_workbook(workbook)
    build_engine(convert_raw(base, raise_errors=False))  # the base must be a valid workbook
    select_rules(load_rules(None), study.select, study.ignore)  # usage errors before work
    targets = resolve(study, base)
    vs = variants(study)
    keys = [v.key(base.sha256, study) for v in vs]
    folder = out / "variants"
    done = {k for k in keys if (folder / f"{k}.json").is_file()}
    todo = [(v, k) for v, k in zip(vs, keys) if k not in done]
    say(f"study '{study.name}': {len(vs)} variants ({study.design}), {len(done)} already"
        f" done, {len(todo)} to run"
        + (f" on Dask ({dask})" if dask else f" on {workers or os.cpu_count() or 1} local"
           " worker processes"))
    args = (base, targets, study.select, study.ignore, study.fail_on)
    engine_name = "local"
    if todo:
        bar = _progress_bar(len(todo), progress)
        try:
            if dask:
                engine_name = "dask"
                for rec in _run_dask(dask, args, todo, workers):
                    _write_record(folder, rec)
                    bar.update(1)
            else:
                for rec in _run_local(args, todo, workers):
                    _write_record(folder, rec)
                    bar.update(1)
        finally:
            bar.close()
    records = [json.loads((folder / f"{k}.json").read_text(encoding="utf-8")) for k in keys]
    return StudyRun(study, str(workbook), base.sha256, vs, targets, records, out,
                    computed=len(todo), seconds=time.perf_counter() - t0, engine=engine_name)


def _run_local(args, todo, workers) -> Iterable[dict]:
    n = max(1, min(workers or os.cpu_count() or 1, len(todo)))
    if n == 1:
        _setup(*args)
        for v, k in todo:
            yield _evaluate(v, k)
        return
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = mp.get_context("fork" if sys.platform.startswith("linux") else "spawn")
    # contiguous chunks keep a worker's variants together (cache reuse across neighbours)
    with ProcessPoolExecutor(max_workers=n, mp_context=ctx) as ex:
        futs = [ex.submit(_local_task, args + (v, k)) for v, k in todo]
        for f in as_completed(futs):
            yield f.result()


def _run_dask(address: str, args, todo, workers) -> Iterable[dict]:
    from distributed import Client, LocalCluster, as_completed

    cluster = None
    if address == "local":
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                               processes=True, dashboard_address=None)
        client = Client(cluster)
    else:
        client = Client(address)
    try:
        base_f = client.scatter(args[0], broadcast=True)
        futs = [client.submit(_dask_task, base_f, *args[1:], v, k, key=f"checker-variant-{k}",
                              pure=False) for v, k in todo]
        for f in as_completed(futs):
            yield f.result()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
