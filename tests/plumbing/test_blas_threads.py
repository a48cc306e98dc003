"""checker.plumbing.blas_threads: one BLAS thread per process while checker's processes share the
cores (the remedies' helpers, the corners' process)."""

from __future__ import annotations

import numpy as np  # noqa: F401 - loads NumPy's BLAS
from threadpoolctl import threadpool_info

from checker.plumbing.blas_threads import one_per_process
from checker.plumbing.forked import Forked


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


_CLI_THREADS = ("import checker.cli, numpy\n"
                "from threadpoolctl import threadpool_info\n"
                "print(sorted({i['num_threads'] for i in threadpool_info()"
                " if i['user_api'] == 'blas'}))")


def _cli_threads(**env: str) -> str:
    import os
    import subprocess
    import sys

    e = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    e.update(env)
    return subprocess.run([sys.executable, "-c", _CLI_THREADS], env=e, capture_output=True,
                          text=True, check=True).stdout.strip()


def test_command_line_starts_numpy_with_one_blas_thread():
    """The command line sets one BLAS thread before NumPy is loaded (OpenBLAS's idle worker
    threads spin: about 15 % of an I4 check's processor time, docs/benchmarks.md)."""
    assert _cli_threads() == "[1]"


def test_command_line_keeps_the_users_blas_threads():
    import os

    import pytest

    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: OpenBLAS starts one thread whatever is asked")
    assert _cli_threads(OPENBLAS_NUM_THREADS="2") == "[2]"
