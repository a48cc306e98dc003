"""The calculation graph: named quantities, the calculations that provide them, and a runner
that computes only what the selected rules need.

* A :class:`QuantitySpec` declares a named quantity (unit, dimensions, the item attributes a
  rule may filter on) so rule files can be validated before anything runs.
* A :class:`Calculation` belongs to a module (``joints``, ``loads``, ``bearings``,
  ``torsion``, ``fatigue``), declares what it provides and, as a function of the engine, what it
  needs. A quantity the workbook gives directly makes its provider need nothing upstream, so
  the upstream module is skipped.
* A calculation that cannot run raises :class:`MissingInputs`; its quantities become
  *unavailable* with the reasons, and every rule on them reports ``not evaluated``.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..description.engine import Engine


class MissingInputs(Exception):
    """A calculation cannot run: ``reasons`` name the missing inputs (sheet/cell where known)."""

    def __init__(self, reasons: Iterable[str]):
        self.reasons = list(reasons)
        super().__init__("; ".join(self.reasons))


@dataclass(frozen=True)
class QuantitySpec:
    """Declaration of a named quantity."""

    name: str
    unit: str  # SI unit ("" = dimensionless)
    dims: tuple[str, ...]  # e.g. ("item",), ("item", "point"), ("item", "case", "speed")
    description: str
    display_unit: str | None = None  # default display unit in reports
    filters: tuple[str, ...] = ()  # item attributes a rule may filter on
    coords: dict[str, tuple[str, ...]] = field(default_factory=dict)  # fixed labels of a dim
    methods: dict[str, str] = field(default_factory=dict)
    """Method-tagged quantity families (film thickness): a rule on this quantity must name its
    ``method``, which selects the quantity it is judged on (method -> quantity name)."""
    compare: tuple[tuple[str, str], ...] = ()
    """(label, quantity) computed beside this one: a result carries their values at its
    judged point (e.g. the short-bearing and the finite-length film)."""
    detail: type | None = None
    """The declared type of the quantity's :attr:`Quantity.detail` (a frozen subclass of
    :class:`checker.results.Detail`); ``None``: the quantity carries no detail. The runner
    checks every computed quantity against it."""


@dataclass
class Quantity:
    """A computed quantity: an array over ``dims`` with coordinate labels.

    ``values`` holds SI magnitudes. Entries that could not be computed are NaN and ``missing``
    maps their index (a tuple over the leading dims) to the reasons. ``findings`` maps an index
    to numerical findings (film collapse, resonance...) that the report must show.
    """

    spec: QuantitySpec
    values: np.ndarray
    coords: dict[str, list]
    item_attrs: dict[str, dict[str, Any]] = field(default_factory=dict)
    missing: dict[tuple, list[str]] = field(default_factory=dict)
    findings: dict[tuple, list[str]] = field(default_factory=dict)
    applies: np.ndarray | None = None  # bool mask: points a rule judges (None = all)
    detail: Any = None
    """The node's typed result beside the numbers (curves, inputs, intermediate values for
    the report), of the type the spec declares (:attr:`QuantitySpec.detail`)."""
    applies_text: str = ""
    """Why the points outside ``applies`` are not judged (words for the report)."""

    @property
    def name(self) -> str:
        return self.spec.name

    def __post_init__(self) -> None:
        shape = tuple(len(self.coords[d]) for d in self.spec.dims)
        self.values = np.asarray(self.values, dtype=float)
        if self.values.shape != shape:
            raise ValueError(f"{self.spec.name}: values shape {self.values.shape} does not match"
                             f" coords {shape}")
        if self.applies is not None:
            self.applies = np.broadcast_to(np.asarray(self.applies, dtype=bool), shape)
        want = self.spec.detail
        if want is not None and self.detail is not None and not isinstance(self.detail, want):
            raise TypeError(f"{self.spec.name}: detail is a {type(self.detail).__name__}, the"
                            f" quantity declares {want.__name__}")
        if want is None and self.detail is not None:
            raise TypeError(f"{self.spec.name}: carries a {type(self.detail).__name__} detail"
                            " but declares none (QuantitySpec.detail)")


def resonant_peaks(values: np.ndarray, axis: int = -1, envelope: np.ndarray | None = None
                   ) -> np.ndarray:
    """Mask of the resonant peaks to judge along ``axis`` (the speed axis), within an envelope.

    ``envelope`` (bool, broadcastable to ``values``; ``None`` = every speed) marks the speeds
    each curve is judged at, for example the full-load data range of the full-load case; each
    contiguous run of judged speeds is a range of its own. A point is a resonant peak when

    * it is an interior local maximum of the whole curve (strictly above one neighbour) inside
      the envelope;
    * it is the top speed of an envelope range and the curve still rises into it: a resonance
      flank leaving the range is judged at the range's top (not at a higher speed outside the
      range, nor missed because the curve's maximum lies outside);
    * it is the bottom speed of an envelope range above the sweep's lowest speed, the curve
      falls from it, and a resonant peak lies below the range: the falling flank of that
      resonance is judged at the range's bottom.

    The sweep's first speed is never a peak by itself: a curve that falls from the lowest speed
    is the rigid-body (rolling-mode) motion, not a resonance. Plateaus count once at most.
    """
    a = np.moveaxis(np.asarray(values, dtype=float), axis, -1)
    n = a.shape[-1]
    if envelope is None:
        env = np.ones(a.shape, dtype=bool)
    else:
        env = np.moveaxis(np.broadcast_to(np.asarray(envelope, dtype=bool),
                                          np.shape(values)), axis, -1)
    interior = np.zeros(a.shape, dtype=bool)
    if n >= 3:
        interior[..., 1:-1] = (a[..., 1:-1] >= a[..., :-2]) & (a[..., 1:-1] >= a[..., 2:]) & (
            a[..., 1:-1] > np.minimum(a[..., :-2], a[..., 2:]))
    m = interior & env
    if n >= 2:
        # top of each envelope range (the sweep's last speed included): rising into it
        top = env.copy()
        top[..., :-1] &= ~env[..., 1:]
        rising = np.zeros(a.shape, dtype=bool)
        rising[..., 1:] = a[..., 1:] > a[..., :-1]
        m |= top & rising
        # bottom of an envelope range above the lowest speed: falling out of it with a
        # resonant peak below
        bottom = env.copy()
        bottom[..., 1:] &= ~env[..., :-1]
        bottom[..., 0] = False
        falling = np.zeros(a.shape, dtype=bool)
        falling[..., :-1] = a[..., :-1] > a[..., 1:]
        below = np.zeros(a.shape, dtype=bool)
        below[..., 1:] = np.cumsum(interior, axis=-1)[..., :-1] > 0
        m |= bottom & falling & below
    return np.moveaxis(m, -1, axis)


@dataclass(frozen=True)
class Calculation:
    """One node of the graph."""

    name: str
    module: str
    provides: tuple[str, ...]
    func: Callable[[Engine, dict[str, Quantity]], dict[str, Quantity]]
    needs: Callable[[Engine], tuple[str, ...]] = lambda engine: ()
    description: str = ""
    optional: tuple[str, ...] = ()  # needs that may be unavailable (the calc copes)
    reads: tuple[str, ...] | None = None  # engine inputs read (None = all); see input_key
    applies: Callable[[Engine], bool] | None = None
    """Whether the calculation applies to an engine at all (``None``: always). The rules on
    the quantities of a calculation that does not apply are ``not applicable`` (a rubber
    damper's tuning for an engine with a viscous damper): :func:`applies_to`."""
    applies_why: Callable[[Engine], str] | None = None
    """Why it does not apply, in words (the not-applicable results' reason)."""
    separate: bool = False
    """Long and needed late: where the caller allows (:func:`run` with ``parallel``), it is
    computed in a forked process while this one computes what does not depend on it."""


UNAVAILABLE = "__unavailable__"
"""Key of the inputs dict that maps optional needs that could not be computed to reasons."""

QUANTITIES: dict[str, QuantitySpec] = {}
CALCULATIONS: dict[str, Calculation] = {}
PROVIDER: dict[str, str] = {}
MODULES: dict[str, str] = {}
"""Analysis module name -> title, in report order: :mod:`checker.modules` registers them from
its ``REGISTRY`` (the graph imports no module; modules import the graph)."""


QUIET_MODULES: set[str] = set()
"""Modules that apply only when their sheet is given (``crank``: sheet Crank): listed when
they run, never as skipped (a workbook without the sheet reads as before)."""


def register_module(name: str, title: str, quiet: bool = False) -> None:
    """Register an analysis module. Registering it again keeps its place and must give the
    same title. ``quiet``: listed only when it runs (:data:`QUIET_MODULES`)."""
    if MODULES.get(name, title) != title:
        raise ValueError(f"module {name!r} registered as {MODULES[name]!r} and as {title!r}")
    MODULES[name] = title
    if quiet:
        QUIET_MODULES.add(name)


def quantity(spec: QuantitySpec) -> QuantitySpec:
    QUANTITIES[spec.name] = spec
    return spec


def calculation(name: str, module: str, provides: Iterable[str],
                needs: Callable[[Engine], tuple[str, ...]] | Iterable[str] = (),
                description: str = "", optional: Iterable[str] = (),
                reads: Iterable[str] | None = None,
                applies: Callable[[Engine], bool] | None = None,
                applies_why: Callable[[Engine], str] | None = None, separate: bool = False):
    """Decorator registering a calculation function ``f(engine, inputs) -> {name: Quantity}``.

    ``reads`` names the engine inputs the calculation reads, for result caching across
    variants (:func:`input_key`): a part of the engine (``"params"``, ``"bearings"``,
    ``"oil"``...) or one field of it (``"params.bore"``, ``"bearings.clearance"``). ``None``
    (the default) means the whole engine: always safe, never reused across variants.
    A test perturbs every input a calculation does not declare and checks its results stay
    identical. ``applies`` (engine -> bool): whether the calculation applies to the engine at
    all (:attr:`Calculation.applies`; it may read only what ``reads`` declares);
    ``applies_why`` (engine -> str) says why not. ``separate``: see
    :attr:`Calculation.separate`.
    """
    provides = tuple(provides)
    needs_f = needs if callable(needs) else (lambda engine, _n=tuple(needs): _n)

    def deco(func):
        calc = Calculation(name, module, provides, func, needs_f, description or func.__doc__
                           or "", tuple(optional), None if reads is None else tuple(reads),
                           applies, applies_why, separate)
        CALCULATIONS[name] = calc
        for q in provides:
            if q not in QUANTITIES:
                raise ValueError(f"calculation {name} provides undeclared quantity {q}")
            PROVIDER[q] = name
        return func

    return deco


def why_not_applies(engine: Engine, qname: str) -> str:
    """Why the calculation providing ``qname`` does not apply to ``engine`` (words)."""
    calc = CALCULATIONS.get(PROVIDER.get(qname, ""))
    if calc is not None and calc.applies_why is not None:
        return calc.applies_why(engine)
    return f"the analysis behind {qname} does not apply to this engine"


def applies_to(engine: Engine, qname: str) -> bool:
    """Whether the calculation providing ``qname`` applies to ``engine``
    (:attr:`Calculation.applies`; unknown quantities apply)."""
    cname = PROVIDER.get(qname)
    calc = CALCULATIONS.get(cname) if cname else None
    return calc is None or calc.applies is None or bool(calc.applies(engine))


def ensure_registered() -> None:
    """Check that the calculation modules are registered: importing :mod:`checker.modules`
    registers them (:mod:`checker.evaluation.ruletable`, and through it :mod:`checker.api`,
    does)."""
    if not CALCULATIONS:
        raise RuntimeError("no calculation is registered: import checker.modules first")


ENGINE_PARTS = ("params", "cylinders", "bearings", "crank_mass", "tv_model", "joints",
                "joint_torques", "peak_pressure", "pressure_traces", "brake_torque", "oil",
                "damper", "fatigue")
"""Parts of :class:`checker.description.engine.Engine` that calculations read (``reads``
entries)."""


def engine_projection(engine: Engine, reads: tuple[str, ...] | None, where: bool = True
                      ) -> tuple:
    """The values of the engine inputs named by ``reads`` (all parts when None), plus the
    cell addresses (messages name cells; ``where=False``: without them), as a plain tuple
    with a deterministic ``repr``."""
    out: list = [("where", tuple(sorted((repr(k), v) for k, v in engine.where.items())))
                 ] if where else []
    for entry in sorted(ENGINE_PARTS if reads is None else reads):
        part, _, fld = entry.partition(".")
        obj = getattr(engine, part)
        if not fld:
            val = tuple(obj.items()) if isinstance(obj, dict) else obj
        elif isinstance(obj, dict):
            val = obj.get(fld)
        else:
            val = tuple(getattr(r, fld) for r in obj)
        out.append((entry, val))
    return tuple(out)


def _where_digest(engine: Engine) -> bytes:
    """Digest of the engine's cell addresses, computed once per engine (every calculation's
    key covers them; hundreds of cells)."""
    import hashlib

    w = engine.where
    hit = engine.__dict__.get("_where_digest")
    if hit is not None and hit[0] is w and hit[1] == len(w):
        return hit[2]
    d = hashlib.sha256(repr(tuple(sorted((repr(k), v) for k, v in w.items()))).encode()).digest()
    engine.__dict__["_where_digest"] = (w, len(w), d)
    return d


def input_key(engine: Engine, calc: Calculation, upstream: Iterable[str]) -> str:
    """Cache key of one calculation: its name, the engine inputs it reads and the keys of the
    calculations upstream of it (a change anywhere upstream changes the key)."""
    import hashlib

    h = hashlib.sha256(calc.name.encode())
    h.update(_where_digest(engine))
    h.update(repr(engine_projection(engine, calc.reads, where=False)).encode())
    for k in upstream:
        h.update(k.encode())
    return h.hexdigest()


def input_keys(engine: Engine, order: Iterable[str]) -> dict[str, str]:
    """:func:`input_key` of every calculation of ``order`` (dependency order, as returned by
    :func:`plan`): the keys :func:`run` uses for its cache."""
    keys: dict[str, str] = {}
    for cname in order:
        calc = CALCULATIONS[cname]
        keys[cname] = input_key(engine, calc, [keys[PROVIDER[d]] for d in calc.needs(engine)])
    return keys


def nbytes(obj: Any, seen: set | None = None, depth: int = 0) -> int:
    """Bytes of the NumPy arrays reachable from ``obj`` (dicts, lists, tuples, objects with
    attributes such as quantities and their typed details), each array counted once: the
    memory a cached calculation result holds (the caches of studies and remedies are bounded
    by it). Declared types (``QuantitySpec.detail``) hold no data and count nothing."""
    seen = set() if seen is None else seen
    if id(obj) in seen or depth > 8:
        return 0
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        return int(obj.nbytes)
    if isinstance(obj, dict):
        return sum(nbytes(v, seen, depth + 1) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return sum(nbytes(v, seen, depth + 1) for v in obj)
    d = getattr(obj, "__dict__", None)
    return nbytes(d, seen, depth + 1) if isinstance(d, dict) else 0


@dataclass
class RunOutcome:
    quantities: dict[str, Quantity]
    unavailable: dict[str, list[str]]
    timings: dict[str, float]  # module -> seconds
    ran: list[str]  # calculation names in run order
    modules_run: list[str]
    modules_skipped: list[str]
    errors: dict[str, str] = field(default_factory=dict)  # calculation -> internal error text
    reused: list[str] = field(default_factory=list)  # calculations taken from the cache


def plan(engine: Engine, wanted: Iterable[str]) -> list[str]:
    """Calculation names needed for ``wanted`` quantities, in dependency order."""
    ensure_registered()
    order: list[str] = []
    state: dict[str, int] = {}

    def visit(qname: str, stack: tuple[str, ...]) -> None:
        cname = PROVIDER.get(qname)
        if cname is None:
            raise KeyError(f"no calculation provides quantity '{qname}'")
        st = state.get(cname)
        if st == 2:
            return
        if st == 1:
            raise RuntimeError("cycle in calculation graph: " + " -> ".join(stack + (cname,)))
        state[cname] = 1
        for dep in CALCULATIONS[cname].needs(engine):
            visit(dep, stack + (cname,))
        state[cname] = 2
        order.append(cname)

    for q in sorted(set(wanted)):
        visit(q, ())
    return order


def _timed(func, engine: Engine, inputs: dict) -> tuple[dict, float]:
    """``func(engine, inputs)`` and its run time [s] (in a forked process: see :func:`run`)."""
    t0 = time.perf_counter()
    return func(engine, inputs), time.perf_counter() - t0


def run(engine: Engine, wanted: Iterable[str], progress: Callable[[str], None] | None = None,
        cache: dict | None = None, parallel: bool = False) -> RunOutcome:
    """Compute the ``wanted`` quantities and only what they need.

    ``cache`` (a dict kept by the caller, e.g. across the variants of a study) stores each
    calculation's outputs under :func:`input_key`; a calculation whose key is in the cache is
    not run again. Cached quantities are shared: treat them as read-only.

    ``parallel``: the calculations marked :attr:`Calculation.separate` are computed in a forked
    process (:class:`checker.plumbing.forked.ForkedCall`) while this one goes on with those that do
    not
    need them, on a machine with two cores or more (a command's own process: not inside the
    worker processes of a study, which use the cores already). The same numbers either way.
    """
    order = plan(engine, wanted)
    have: dict[str, Quantity] = {}
    unavailable: dict[str, list[str]] = {}
    timings: dict[str, float] = {}
    errors: dict[str, str] = {}
    keys: dict[str, str] = {}
    reused: list[str] = []
    forked: dict[str, object] = {}  # calculation -> Forked computing it
    emitted: dict[str, list[str]] = {}  # calculation -> its quantities, in their order
    went_apart = False

    def finish(calc: Calculation, compute: Callable[[], tuple[dict, float]]) -> None:
        try:
            out, seconds = compute()
        except MissingInputs as exc:
            for q in calc.provides:
                unavailable[q] = exc.reasons
            out, seconds = {}, 0.0
        timings[calc.module] = timings.get(calc.module, 0.0) + seconds
        emitted[calc.name] = list(out)
        for q, val in out.items():
            have[q] = val
        for q in calc.provides:
            if q not in have and q not in unavailable:
                unavailable[q] = [f"{calc.name} did not produce {q}"]
        if cache is not None:
            cache[keys[calc.name]] = ({q: have[q] for q in calc.provides if q in have},
                                      {q: unavailable[q] for q in calc.provides
                                       if q in unavailable})

    def settle(cname: str) -> None:
        job = forked.pop(cname)
        finish(CALCULATIONS[cname], job.result)

    try:
        for cname in order:
            calc = CALCULATIONS[cname]
            deps = calc.needs(engine)
            for d in deps:  # a need being computed in a forked process: wait for it
                if PROVIDER.get(d) in forked:
                    settle(PROVIDER[d])
            if cache is not None:
                keys[cname] = input_key(engine, calc, [keys[PROVIDER[d]] for d in deps])
                hit = cache.get(keys[cname])
                if hit is not None:
                    out_q, out_u = hit
                    emitted[cname] = list(out_q)
                    have.update(out_q)
                    unavailable.update(out_u)
                    reused.append(cname)
                    continue
            blocked = [d for d in deps if d in unavailable and d not in calc.optional]
            if blocked:
                reasons = []
                for d in blocked:
                    for r in unavailable[d]:
                        if r not in reasons:
                            reasons.append(r)
                for q in calc.provides:
                    unavailable[q] = reasons
                continue
            if progress is not None:
                progress(f"{calc.module}: {calc.name}")
            inputs: dict = {d: have[d] for d in deps if d in have}
            gone = {d: unavailable[d] for d in deps if d in unavailable}
            if gone:
                inputs[UNAVAILABLE] = gone
            if parallel and calc.separate:
                from ..plumbing.forked import ForkedCall

                job = ForkedCall(_timed, calc.func, engine, inputs)
                if job.forked:
                    forked[cname] = job
                    went_apart = True
                    continue
            finish(calc, lambda calc=calc, inputs=inputs: _timed(calc.func, engine, inputs))
        for cname in list(forked):
            settle(cname)
    finally:  # an exception or interruption: no forked calculation outlives the run
        for job in forked.values():
            job.close()
    if went_apart:  # the quantities in the order of a run in one process (outputs list them)
        have = {q: have[q] for c in order for q in emitted.get(c, ()) if q in have}
        unavailable = {q: unavailable[q] for c in order for q in CALCULATIONS[c].provides
                       if q in unavailable}
    from_cache = {CALCULATIONS[c].module for c in reused}
    # a module whose results came from the cache counts as run (its results are used)
    ran_modules = [m for m in MODULES if m in timings or m in from_cache]
    skipped = [m for m in MODULES if m not in ran_modules and m not in QUIET_MODULES]
    return RunOutcome(have, unavailable, timings, order, ran_modules, skipped, errors, reused)
