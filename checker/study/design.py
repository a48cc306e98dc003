"""Variants of a study: the parameter values of every design point, with stable ids."""

from __future__ import annotations

import hashlib
import itertools
import json
from dataclasses import dataclass
from typing import Any

from .spec import Study, count_variants  # noqa: F401 (re-exported)


@dataclass(frozen=True)
class Variant:
    """One design point: its number, a readable name and the value of each parameter
    (``None`` = the workbook's own value, the baseline)."""

    index: int
    name: str
    values: tuple[tuple[str, Any], ...]
    line: int = 0  # study-file line of a table design's [[variant]] (0: the parameters')

    def value(self, param: str) -> Any:
        return dict(self.values).get(param)

    def key(self, base_sha256: str, study: Study) -> str:
        """Stable id: base workbook, rule selection and the values (resume skips done ids)."""
        blob = json.dumps([base_sha256, study.select, study.ignore, study.fail_on,
                           [[k, v] for k, v in self.values]], sort_keys=True, default=str)
        return hashlib.sha256(blob.encode()).hexdigest()[:16]


def _fmt(v: Any) -> str:
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def variants(study: Study) -> list[Variant]:
    """Every variant of the study's design, in a deterministic order."""
    params = study.parameters
    out: list[Variant] = []
    if study.design == "one-at-a-time":
        out.append(Variant(0, "baseline", tuple((q.name, None) for q in params)))
        for q in params:
            for lev in q.levels():
                vals = tuple((p.name, lev if p is q else None) for p in params)
                out.append(Variant(len(out), f"{q.name} = {_fmt(lev)} {q.unit}".strip(), vals))
    elif study.design == "full-factorial":
        for combo in itertools.product(*(q.levels() for q in params)):
            vals = tuple((q.name, v) for q, v in zip(params, combo))
            name = ", ".join(f"{q.name} = {_fmt(v)}" for q, v in zip(params, combo))
            out.append(Variant(len(out), name, vals))
    elif study.design == "latin-hypercube":
        from scipy.stats import qmc

        u = qmc.LatinHypercube(d=len(params), seed=study.seed).random(study.samples)
        for k, row in enumerate(u):
            vals = tuple((q.name, q.at(float(x))) for q, x in zip(params, row))
            out.append(Variant(k, f"sample {k + 1}", vals))
    else:  # table
        for name, given in study.table:
            vals = tuple((q.name, given.get(q.name)) for q in params)
            out.append(Variant(len(out), name, vals,
                               study.table_lines[len(out)] if study.table_lines else 0))
    return out
