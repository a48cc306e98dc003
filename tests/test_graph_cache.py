"""Result caching across variants: declared inputs are complete, cached equals cold."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from checker import api
from checker.description.engine import Engine, Params, load_engine
from checker.evaluation import graph
from checker.outputs.formats import to_json
from tests.helpers import example_path


@pytest.fixture(scope="module")
def engine(tmp_path_factory) -> Engine:
    return load_engine(example_path(tmp_path_factory.mktemp("cache")))


def _bump(v):
    if isinstance(v, bool) or v is None:
        return v
    if isinstance(v, float):
        return v * 1.07 + 1e-6
    if isinstance(v, str):
        return v + " x"
    return v


def _perturbed(engine: Engine, part: str, fld: str | tuple[str, ...] | None) -> Engine:
    """``engine`` with one part, one field of it, or several fields (tuple) perturbed."""
    obj = getattr(engine, part)
    pick = (lambda k: True) if fld is None else (lambda k: k in fld) if isinstance(
        fld, tuple) else (lambda k: k == fld)
    if isinstance(obj, dict):
        new = Params({k: (_bump(v) if pick(k) else v) for k, v in obj.items()})
    elif obj and dataclasses.is_dataclass(obj[0]):
        new = tuple(dataclasses.replace(r, **{f.name: _bump(getattr(r, f.name))
                                              for f in dataclasses.fields(r)
                                              if pick(f.name)}) for r in obj)
    else:  # tuples of plain tuples (peak pressure, traces, brake torque)
        new = tuple(tuple(_bump(x) for x in row) for row in obj)
    return dataclasses.replace(engine, **{part: new})


def _call(calc: graph.Calculation, engine: Engine, inputs: dict) -> dict:
    """The calculation's results, or its missing-input reasons (compared like results)."""
    try:
        return calc.func(engine, inputs)
    except graph.MissingInputs as exc:
        return {"__missing__": exc.reasons}


def _same(a: dict, b: dict) -> bool:
    if "__missing__" in a or "__missing__" in b:
        return a == b
    if set(a) != set(b):
        return False
    for k in a:
        qa, qb = a[k], b[k]
        if qa.values.shape != qb.values.shape or not np.array_equal(qa.values, qb.values,
                                                                     equal_nan=True):
            return False
        if qa.coords != qb.coords or qa.item_attrs != qb.item_attrs or \
                qa.missing != qb.missing or qa.findings != qb.findings:
            return False
    return True


def _undeclared(calc: graph.Calculation, engine: Engine) -> list[tuple[str, str | None]]:
    """Every engine part, or field of a part, that ``calc`` does not declare in ``reads``."""
    reads = set(calc.reads)
    out = []
    for part in graph.ENGINE_PARTS:
        if part in reads:
            continue
        fields = [r.split(".", 1)[1] for r in reads if r.startswith(part + ".")]
        if not fields:
            out.append((part, None))
            continue
        obj = getattr(engine, part)
        names = list(obj) if isinstance(obj, dict) else [f.name for f in dataclasses.fields(
            obj[0])] if obj else []
        out += [(part, n) for n in names if n not in fields]
    return out


DECLARED = sorted(n for n, c in (graph.ensure_registered() or graph.CALCULATIONS).items()
                  if c.reads is not None)


@pytest.mark.parametrize("name", DECLARED)
def test_declared_reads_are_complete(engine, name):
    """Perturbing any input a calculation does not declare leaves its results identical."""
    calc = graph.CALCULATIONS[name]
    deps = calc.needs(engine)
    outcome = graph.run(engine, deps) if deps else None
    inputs = {d: outcome.quantities[d] for d in deps} if outcome else {}
    ref = _call(calc, engine, inputs)
    groups: dict[str, list] = {}
    for part, fld in _undeclared(calc, engine):
        groups.setdefault(part, []).append(fld)
    for part, flds in groups.items():
        # all undeclared fields of a part at once; field by field only to name a culprit
        together = None if flds == [None] else tuple(flds)
        if _same(ref, _call(calc, _perturbed(engine, part, together), inputs)):
            continue
        for fld in flds:
            got = _call(calc, _perturbed(engine, part, fld), inputs)
            assert _same(ref, got), f"{name} reads {part}{'.' + fld if fld else ''} undeclared"
        pytest.fail(f"{name} reads undeclared fields of {part} (together)")


def test_declared_reads_detect_a_real_dependency(engine):
    """The check above can fail: the loads do depend on the bore."""
    calc = graph.CALCULATIONS["pressure_traces"]
    a = calc.func(engine, {})
    b = calc.func(_perturbed(engine, "params", "bore"), {})
    assert not _same(a, b)


def test_clearance_variant_reuses_loads_and_equals_cold(engine):
    cache: dict = {}
    api.check(engine, select=["BRG"], cache=cache)
    bearings = tuple(dataclasses.replace(b, clearance=b.clearance * 1.2) if b.name == "M3"
                     else b for b in engine.bearings)
    variant = dataclasses.replace(engine, bearings=bearings)
    warm = api.check(variant, select=["BRG"], cache=cache)
    cold = api.check(variant, select=["BRG"])
    assert {"pressure_traces", "bearing_loads"} <= set(warm.outcome.reused)
    assert "moft" not in warm.outcome.reused
    assert to_json(warm, timings=False) == to_json(cold, timings=False)
    d = json.loads(to_json(warm, timings=False))
    m3 = [r for r in d["results"] if r["rule"] == "BRG-003" and r["item"] == "M3"]
    assert m3 and m3[0]["value"] is not None
    # the baseline from the same cache is unchanged by the variant
    again = api.check(engine, select=["BRG"], cache=cache)
    assert to_json(again, timings=False) == to_json(api.check(engine, select=["BRG"]),
                                                    timings=False)
