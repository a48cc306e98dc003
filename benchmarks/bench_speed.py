"""Speed of the check (issue 25): the issue's command table before/after, time per stage,
run time against error of the orbit settings, results against an earlier checker, and the
100-variant studies through :func:`checker.api.check_batch`.

    python benchmarks/bench_speed.py [--before /path/to/old/checker/tree] [--repeat 5]
                                     [--skip-commands] [--skip-orbits] [--skip-study]

* Commands: whole process (``python -m checker ...``) after one warm-up run (byte code cached
  as after an ordinary install, also where ``PYTHONDONTWRITEBYTECODE`` is set), median of
  ``--repeat`` runs (with ``--before`` the two trees alternately, and the median ratio
  after/before of the pairs, which holds when the machine's speed drifts), wall time
  and user+system CPU time (the CPU time is the better measure while other jobs share the
  machine; on an idle machine both agree). ``--before`` runs the same commands with an
  earlier source tree first on ``PYTHONPATH`` (same interpreter and packages) and compares
  every number of the JSON output of the two (largest relative difference per quantity).
* Orbits: the film-thickness orbits of the example I4 (every bearing, both cases, 61
  speeds) for each periodicity tolerance and with/without shared shifted orbits, against the
  orbit converged to round-off (tolerance 1e-11).
* Study: 100 variants of the I4's main clearance (BRG-001..006) and a 100-variant Latin
  hypercube over bore, stroke, rod length, piston mass and main width (every rule), each
  evaluated by ``check_batch`` in 2 worker processes (contiguous chunks of 10 variants).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
COMMANDS = [
    ("`checker check` I4, every rule", ["check", "{i4}"]),
    ("`checker check` I4 without BRG-007..009", ["check", "{i4}", "--ignore", "BRG-007",
                                                  "--ignore", "BRG-008", "--ignore",
                                                  "BRG-009"]),
    ("`checker check` I6, every rule", ["check", "{i6}"]),
    ("`checker check` V8, every rule", ["check", "{v8}"]),
    ("`checker check --select JNT` I4", ["check", "{i4}", "--select", "JNT"]),
    ("`checker rules` (start-up alone)", ["rules"]),
]

TARGETS = {
    "`checker check` I4, every rule": "1.5 s (issue 37: 1.63 s on its quiet machine, so"
                                      " after/before <= 0.92)",
    "`checker check` I6, every rule": "2.0 s",
    "`checker check` V8, every rule": "2.0 s",
}


PYCACHE = Path(tempfile.mkdtemp(prefix="bench-speed-pycache-"))


def _env() -> dict[str, str]:
    """The children's environment: byte code cached (in a folder of the benchmark, so no
    source tree is written to) even where ``PYTHONDONTWRITEBYTECODE`` is set, as after an
    ordinary install; without it every run compiles checker's modules again (about 0.3 s
    CPU of every command on this machine)."""
    env = dict(os.environ, PYTHONPYCACHEPREFIX=str(PYCACHE))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def _run(args: list[str], tree: Path | None, out: Path | None = None) -> tuple[float, float]:
    env = _env()
    if tree is not None:
        env["PYTHONPATH"] = str(tree)
    cmd = [sys.executable, "-m", "checker", *args]
    if out is not None:
        cmd += ["--format", "json", "-o", str(out)]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    # a neutral working folder: ``python -m`` puts it first on sys.path
    subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   check=False, cwd=tempfile.gettempdir())
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)


def _numbers(x, path="", out=None) -> dict[str, float]:
    out = {} if out is None else out
    if isinstance(x, dict):
        for k, v in x.items():
            if k != "timings":
                _numbers(v, f"{path}/{k}", out)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            _numbers(v, f"{path}[{i}]", out)
    elif isinstance(x, float):
        out[path] = x
    return out


def _compare(a: Path, b: Path) -> dict[str, float]:
    """Largest relative difference of every number of two JSON outputs, per quantity."""
    na, nb = _numbers(json.loads(a.read_text())), _numbers(json.loads(b.read_text()))
    worst: dict[str, float] = {}
    for k, v in na.items():
        if not k.startswith("/quantities/"):
            continue
        w = nb.get(k)
        q = k.split("/")[2]
        d = 0.0 if w == v else (np.inf if w is None else abs(w - v) / max(abs(v), 1e-300))
        worst[q] = max(worst.get(q, 0.0), d)
    return worst


def commands(files: dict[str, Path], before: Path | None, repeat: int, tmp: Path) -> None:
    for tag, tree in (("before", before), ("after", None)):
        env = dict(os.environ, **({"PYTHONPATH": str(tree)} if tree else {}))
        where = subprocess.run([sys.executable, "-c", "import checker; print(checker.__file__)"],
                               env=env, capture_output=True, text=True,
                               cwd=tempfile.gettempdir()).stdout.strip()
        print(f"{tag}: {where}")
    print(f"## Commands (whole process, median of {repeat}; wall / CPU seconds;"
          f" load average {os.getloadavg()[0]:.1f})\n")
    print("| command | before wall | before CPU | after wall | after CPU | after/before wall,"
          " CPU (median of the pairs) | target |")
    print("|---|---|---|---|---|---|---|")
    stages: dict[str, dict[str, list[float]]] = {"before": {}, "after": {}}
    tags = (("before", before), ("after", None)) if before is not None else (("after", None),)
    for label, args in COMMANDS:
        a = [x.format(**{k: str(v) for k, v in files.items()}) for x in args]
        walls: dict[str, list[float]] = {t: [] for t, _ in tags}
        cpus: dict[str, list[float]] = {t: [] for t, _ in tags}
        for _, tree in tags:
            _run(a, tree)  # warm-up: byte code written, files in the page cache
        for i in range(repeat):  # alternately, so that each pair sees the same machine
            for tag, tree in tags:
                out = tmp / f"{tag}-{abs(hash(label))}-{i}.json" if a[0] == "check" else None
                w, c = _run(a, tree, out)
                walls[tag].append(w)
                cpus[tag].append(c)
                if out is not None and out.is_file():
                    for mod, sec in json.loads(out.read_text()).get("timings", {}).items():
                        stages[tag].setdefault(f"{label}|{mod}", []).append(sec)
        cells = []
        for tag in ("before", "after"):
            if tag not in walls:
                cells += ["-", "-"]
                continue
            cells += [f"{statistics.median(walls[tag]):.2f} s",
                      f"{statistics.median(cpus[tag]):.2f} s"]
        if "before" in walls:
            rw = statistics.median(x / y for x, y in zip(walls["after"], walls["before"]))
            rc = statistics.median(x / y for x, y in zip(cpus["after"], cpus["before"]))
            cells.append(f"{rw:.3f}, {rc:.3f}")
        else:
            cells.append("-")
        cells.append(TARGETS.get(label, ""))
        print(f"| {label} | " + " | ".join(cells) + " |", flush=True)
    print(f"\n(load average at the end: {os.getloadavg()[0]:.1f}; the CPU time is user +"
          " system of the process, the better measure while other jobs share the machine)")
    imports(files["i4"], before)
    print("\n## Time per stage (JSON `timings`, median) [s]\n")
    print("| command | stage | before | after |")
    print("|---|---|---|---|")
    for key in sorted(stages["after"]):
        label, mod = key.split("|")
        vb = stages["before"].get(key)
        va = stages["after"][key]
        if statistics.median(va) < 0.02 and (vb is None or statistics.median(vb) < 0.02):
            continue
        print(f"| {label} | {mod} | " + (f"{statistics.median(vb):.3f}" if vb else "-")
              + f" | {statistics.median(va):.3f} |")
    if before is not None:
        print("\n## Results against the earlier checker (largest relative difference per"
              " quantity; quantities not listed are identical)\n")
        for name in ("i4", "i6", "v8"):
            ob, oa = tmp / f"cmp-before-{name}.json", tmp / f"cmp-after-{name}.json"
            _run(["check", str(files[name])], before, ob)
            _run(["check", str(files[name])], None, oa)
            diff = {q: d for q, d in _compare(ob, oa).items() if d > 0}
            text = ", ".join(f"{q} {d:.1e}" for q, d in sorted(diff.items(), key=lambda x: -x[1]))
            print(f"* {name.upper()}: {text or 'identical'}")


HEAVY = ("numpy", "pint", "openpyxl", "urllib.request", "numpy.ma", "checker.remedies",
         "checker.calc.reynolds_map")


def imports(i4: Path, before: Path | None) -> None:
    """What a check of the I4 imports (``python -X importtime``, cumulative microseconds of
    the packages that cost most; one run each, wall time of the imports, so indicative only
    while other jobs run)."""
    print("\n## Imports of `checker check` I4 (`-X importtime`, cumulative ms, one run)\n")
    print("| tree | all imports | " + " | ".join(HEAVY) + " |")
    print("|---|---|" + "---|" * len(HEAVY))
    for tag, tree in (("before", before), ("after", None)):
        if tag == "before" and before is None:
            continue
        env = _env()
        if tree is not None:
            env["PYTHONPATH"] = str(tree)
        cmd = [sys.executable, "-X", "importtime", "-m", "checker", "check", str(i4),
               "--format", "json", "-o", os.devnull]
        for _ in range(2):  # the first run writes the byte code
            err = subprocess.run(cmd, env=env, capture_output=True, text=True,
                                 cwd=tempfile.gettempdir()).stderr
        cum: dict[str, int] = {}
        total = 0
        for line in err.splitlines():
            if not line.startswith("import time:") or "self [us]" in line:
                continue
            _, c, name = line.split("|")
            if not name.startswith("  "):  # top level: counted once
                total += int(c)
            cum.setdefault(name.strip(), int(c))
        cells = [f"{cum[m] / 1e3:.0f}" if m in cum else "not imported" for m in HEAVY]
        print(f"| {tag} | {total / 1e3:.0f} | " + " | ".join(cells) + " |", flush=True)


def orbits(i4: Path) -> None:
    """Run time against error of the periodicity tolerance and of shared orbits."""
    from checker import api
    from checker.calc import orbit as ob
    from checker.description.engine import load_engine

    calls = []
    real = ob.solve_orbit

    def capture(*a, **k):
        calls.append((a, k))
        return real(*a, **k)

    ob.solve_orbit = capture
    try:
        api.check(load_engine(i4), select=["BRG-003", "BRG-004", "BRG-005", "BRG-006"])
    finally:
        ob.solve_orbit = real
    print("\n## Orbit settings (I4 film orbits: 9 bearings x 2 cases x 61 speeds; CPU s, min"
          " of 3; error: largest relative MOFT difference to the orbit converged to"
          " tolerance 1e-11)\n")
    print("| model | setting | CPU [s] | cycles | MOFT error |")
    print("|---|---|---|---|---|")
    for a, k in calls:
        model = k.get("model", "closed_form")
        ref = real(*a, **{**k, "tol": 1e-11})
        for label, kw in (("tol 1e-3", {"tol": 1e-3}), ("**tol 1e-4 (default)**", {}),
                          ("tol 1e-6", {"tol": 1e-6}),
                          ("tol 1e-4, no shared orbits", {"share_orbits": False})):
            ts = []
            for _ in range(3):
                t0 = time.process_time()
                r = real(*a, **{**k, **kw})
                ts.append(time.process_time() - t0)
            err = np.max(np.abs(r.h_min / ref.h_min - 1.0))
            cyc = ", ".join(f"{c}: {n}" for c, n in enumerate(np.bincount(r.n_cycles.ravel()))
                            if n)
            print(f"| {model} | {label} | {min(ts):.3f} | {cyc} | {err:.1e} |", flush=True)


def _chunk_worker(args) -> tuple[int, float]:
    """Build the variant engines of one chunk and check them with check_batch."""
    wb, study_path, idx = args
    from checker import api
    from checker.description.engine import build_engine
    from checker.evaluation.ruletable import load_rules, override_problems
    from checker.study.apply import apply_variant, resolve
    from checker.study.design import variants
    from checker.study.spec import load_study
    from checker.workbook.loader import convert_raw, read_raw_workbook

    study = load_study(study_path)
    base = read_raw_workbook(wb)
    targets = resolve(study, base)
    vs = variants(study)
    table = load_rules(None)
    cache = _chunk_worker.__dict__.setdefault("cache", {})
    t0 = time.perf_counter()
    engines = []
    for i in idx:
        raw = apply_variant(base, targets, dict(vs[i].values))
        engines.append(build_engine(convert_raw(raw, raise_errors=False),
                                    lambda o: override_problems(table, o)[2]))
    api.check_batch(engines, rules=table, select=study.select, ignore=study.ignore,
                    cache=cache)
    return len(idx), time.perf_counter() - t0


def study(i4: Path, tmp: Path, n: int, chunk: int = 10) -> None:
    import multiprocessing as mp

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_study import CLEARANCE, LHS

    print(f"\n## Studies ({n} variants, check_batch in 2 worker processes, chunks of {chunk})\n")
    print("| study | variants | wall [s] | per variant [ms] |")
    print("|---|---|---|---|")
    for label, text in (("clearance (all mains), BRG-001..006", CLEARANCE),
                        ("Latin hypercube, 5 parameters, every rule", LHS)):
        st = tmp / f"study-{len(label)}.toml"
        st.write_text(text.format(n=n), encoding="utf-8")
        chunks = [(i4, st, list(range(s, min(n, s + chunk)))) for s in range(0, n, chunk)]
        t0 = time.perf_counter()
        with mp.get_context("fork").Pool(2) as pool:
            done = sum(k for k, _ in pool.imap_unordered(_chunk_worker, chunks))
        sec = time.perf_counter() - t0
        print(f"| {label} | {done} | {sec:.1f} | {sec / done * 1e3:.0f} |", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", type=Path, default=None,
                    help="earlier checker source tree (its folder holding 'checker/')")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--variants", type=int, default=100)
    ap.add_argument("--skip-commands", action="store_true")
    ap.add_argument("--skip-orbits", action="store_true")
    ap.add_argument("--skip-study", action="store_true")
    a = ap.parse_args()
    from checker.workbook.example import example_content, write_workbook
    from checker.workbook.example_i6 import i6_content
    from checker.workbook.example_v8 import v8_content

    tmp = Path(tempfile.mkdtemp(prefix="bench-speed-"))
    files = {"i4": tmp / "engine.xlsx", "i6": tmp / "engine-i6.xlsx",
             "v8": tmp / "engine-v8.xlsx"}
    write_workbook(files["i4"], example_content())
    write_workbook(files["i6"], i6_content())
    write_workbook(files["v8"], v8_content())
    if not a.skip_commands:
        commands(files, a.before, a.repeat, tmp)
    if not a.skip_orbits:
        orbits(files["i4"])
    if not a.skip_study:
        study(files["i4"], tmp, a.variants)


if __name__ == "__main__":
    main()
