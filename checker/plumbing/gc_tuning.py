"""Fewer garbage collections in the report's worker processes.

CPython's cyclic garbage collector runs a young-generation pass every 700 net allocations of
container objects and from time to time scans every object alive. Laying out a PDF (WeasyPrint
builds a box per element, line and word) and drawing figures (matplotlib builds an artist per
tick, label and line) allocate millions of such objects, most of them alive until the process
ends, so the collector's passes find little and cost a quarter of the work. The report's engine
and drawing processes are short-lived: they move what they inherited out of the collector's
way (:func:`gc.freeze`) and collect the young generation every 10 000 allocations. Measured on
the I4 example (processor time, benchmarks/bench_report.py): the PDF layout 2.2 -> 1.6 s, the
figures 2.5 -> 2.1 s; garbage is still collected, so memory stays bounded (the layout's peak
grows by a few per cent).
"""

from __future__ import annotations

import gc

MEASURED_ON = "CPython 3.11 (timed on 3.11.7)"
"""The interpreter this was measured on."""


def missing_targets() -> list[str]:
    """What the tuning calls and this interpreter lacks (empty: all)."""
    return [f"gc.{n}" for n in ("freeze", "get_threshold", "set_threshold")
            if not callable(getattr(gc, n, None))]

YOUNG_THRESHOLD = 10_000
"""Net allocations of container objects between two young-generation collections (CPython's
default: 700)."""


def fewer_collections(young: int = YOUNG_THRESHOLD) -> None:
    """In a short-lived worker process: what it inherited frozen out of the collector's scans,
    and the young generation collected every ``young`` allocations (the older generations'
    thresholds as CPython's defaults)."""
    gc.freeze()
    _, older, oldest = gc.get_threshold()
    gc.set_threshold(young, older, oldest)
