"""checker.forked: a call in a forked process gives what the direct call gives."""

import os
import time

import pytest

from checker.forked import Forked


def test_forked_gives_the_same_value_as_a_direct_call():
    job = Forked(sorted, [3, 1, 2])
    assert job.result() == [1, 2, 3]


def test_forked_passes_an_error_on():
    job = Forked(int, "not a number")
    with pytest.raises(ValueError):
        job.result()


def test_unforked_call_runs_here_when_asked():
    job = Forked(os.getpid, fork=False)
    assert not job.forked
    assert job.result() == os.getpid()


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: nothing is forked")
def test_forked_call_runs_elsewhere_and_close_ends_it():
    job = Forked(os.getpid)
    assert job.forked
    assert job.result() != os.getpid()
    slow = Forked(time.sleep, 30)
    procs = list(slow.pool._processes.values())
    t = time.perf_counter()
    slow.close()
    assert time.perf_counter() - t < 10
    assert all(not p.is_alive() for p in procs)


def test_forked_call_gives_the_same_value_and_passes_an_error_on():
    from checker.forked import ForkedCall

    job = ForkedCall(sorted, [3, 1, 2])
    assert job.result() == [1, 2, 3]
    with pytest.raises(ValueError, match="not a number"):
        ForkedCall(int, "not a number").result()


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: nothing is forked")
def test_forked_call_runs_elsewhere_and_close_ends_it_at_once():
    from checker.forked import ForkedCall

    job = ForkedCall(os.getpid)
    assert job.forked and job.result() != os.getpid()
    slow = ForkedCall(time.sleep, 30)
    pid = slow.pid
    t = time.perf_counter()
    slow.close()
    assert time.perf_counter() - t < 10  # killed, not waited for
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)  # reaped: no such process
    slow.close()  # twice is harmless
