"""checker.plumbing.forked: a call in a forked process gives what the direct call gives."""

import os
import time

import pytest

from checker.plumbing.forked import Forked


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
    from checker.plumbing.forked import ForkedCall

    job = ForkedCall(sorted, [3, 1, 2])
    assert job.result() == [1, 2, 3]
    with pytest.raises(ValueError, match="not a number"):
        ForkedCall(int, "not a number").result()


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: nothing is forked")
def test_forked_call_runs_elsewhere_and_close_ends_it_at_once():
    from checker.plumbing.forked import ForkedCall

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


def _before_and_after(first, later):
    """A fed call: ``first`` is done before the fed object is asked for."""
    head = sorted(first)
    return head, later(), os.getpid()


def test_fed_call_starts_before_its_input_and_gives_the_value():
    from checker.plumbing.forked import ForkedCall

    job = ForkedCall(_before_and_after, [3, 1, 2], fed=True)
    forked = job.forked
    big = list(range(200_000))  # more than a pipe holds: the child reads it from the start
    job.feed(big)
    head, got, pid = job.result()
    assert head == [1, 2, 3] and got == big
    assert (pid != os.getpid()) == forked


def test_fed_call_runs_here_without_fork(monkeypatch):
    from checker.plumbing.forked import ForkedCall

    monkeypatch.setattr(os, "cpu_count", lambda: 1)  # one core: nothing is forked
    job = ForkedCall(_before_and_after, [2, 1], fed=True)
    assert not job.forked
    with pytest.raises(RuntimeError, match="before feed"):
        job.result()
    job.feed("x")
    assert job.result()[:2] == ([1, 2], "x")


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: nothing is forked")
def test_fed_call_waiting_for_its_input_is_ended_by_close_and_passes_errors_on():
    from checker.plumbing.forked import ForkedCall

    job = ForkedCall(_before_and_after, [1], fed=True)
    pid = job.pid
    with pytest.raises(RuntimeError, match="before feed"):
        job.result()
    job.close()  # waiting for its input: killed, not waited for
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)
    bad = ForkedCall(_before_and_after, None, fed=True)  # sorted(None) fails in the child
    bad.feed(1)
    with pytest.raises(TypeError):
        bad.result()
