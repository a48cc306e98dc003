"""checker.blas_threads: one BLAS thread per process while checker's processes share the
cores (the remedies' helpers, the corners' process)."""

from __future__ import annotations

import numpy as np  # noqa: F401 - loads NumPy's BLAS
from threadpoolctl import threadpool_info

from checker.blas_threads import one_per_process
from checker.forked import Forked


def _blas_threads() -> list[int]:
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_one_thread_inside_and_restored_after():
    before = _blas_threads()
    assert before, "NumPy's BLAS is not seen by threadpoolctl"
    with one_per_process():
        assert _blas_threads() == [1] * len(before)
    assert _blas_threads() == before


def test_inactive_changes_nothing():
    before = _blas_threads()
    with one_per_process(False):
        assert _blas_threads() == before


def test_forked_process_inherits_the_limit():
    with one_per_process():
        job = Forked(_blas_threads)
        try:
            got = job.result()
        finally:
            job.close()
    assert got and set(got) == {1}
