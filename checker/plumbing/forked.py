"""One call computed in a forked process while this process goes on.

Used where two pieces of work of one command are independent and each would leave a core idle:
the results workbook written while the PDF is laid out (:mod:`checker.report.render`), the
tolerance corners checked while the remedies are searched (:mod:`checker.remedies`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

_CALL: tuple | None = None
"""The call of the process being forked (inherited by fork: nothing is pickled on the way
in; the value comes back pickled)."""


SIGNALS = ("SIGINT", "SIGTERM")
"""The interruptions a command handles itself (:mod:`checker.plumbing.interrupt`) and its forked
processes leave to it."""


def hold_signals() -> tuple[str, ...]:
    """Hold SIGINT and SIGTERM back in this thread while forking (where the platform can): a
    signal reaching a child between its fork and :func:`child_start` would raise the parent's
    exception there, with a traceback. Returns the names held, for :func:`release_signals`."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        return ()
    signal.pthread_sigmask(signal.SIG_BLOCK, [getattr(signal, n) for n in SIGNALS])
    return SIGNALS


def release_signals(names: tuple[str, ...]) -> None:
    """Deliver the signals :func:`hold_signals` held back (pending ones arrive now)."""
    import signal

    if names and hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, [getattr(signal, n) for n in names])


def child_start(nice: int = 0) -> None:
    """In a forked process: an interrupt (Ctrl-C reaches the whole process group) or a SIGTERM
    from the parent ends it at once, the parent handling the interruption; the signals held
    while it was forked are delivered now; its scheduling priority lowered by ``nice``."""
    import os
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    release_signals(SIGNALS)
    if nice:
        try:
            os.nice(nice)
        except OSError:
            pass


def _call():
    fn, args = _CALL
    return fn(*args)


class Forked:
    """``fn(*args)`` computed in a forked process while this one goes on; in this process
    (when :meth:`result` is asked) where fork is unavailable, with one core or with
    ``fork=False``. :meth:`result` waits for the value (or raises the call's exception);
    :meth:`close` ends the process without waiting for the value; ``nice``: the forked
    process's scheduling priority increment (``os.nice``)."""

    def __init__(self, fn: Callable[..., Any], *args: Any, fork: bool = True, nice: int = 0):
        import multiprocessing as mp
        import os

        global _CALL
        self.fn, self.args, self.pool, self.future = fn, args, None, None
        if (not fork or (os.cpu_count() or 1) < 2
                or "fork" not in mp.get_all_start_methods()):
            return
        from concurrent.futures import ProcessPoolExecutor

        _CALL = (fn, args)
        try:
            self.pool = ProcessPoolExecutor(1, mp_context=mp.get_context("fork"),
                                            initializer=child_start, initargs=(nice,))
            self.future = self.pool.submit(_call)  # forks now, with _CALL set
        finally:
            _CALL = None

    @property
    def forked(self) -> bool:
        """True when the call runs in a forked process."""
        return self.pool is not None

    def result(self) -> Any:
        if self.pool is None:
            return self.fn(*self.args)
        try:
            return self.future.result()
        finally:
            self.close()

    def close(self) -> None:
        """End the forked process (at once if it is still working)."""
        if self.pool is None:
            return
        pool, self.pool = self.pool, None
        end_pool(pool, terminate=not self.future.done())


def end_pool(pool, terminate: bool = True) -> None:
    """Shut a process pool down; with ``terminate``, its processes are ended at once instead
    of finishing their work."""
    if terminate:
        for p in list(getattr(pool, "_processes", {}).values()):
            p.terminate()
    pool.shutdown(wait=True, cancel_futures=True)


class ForkedCall:
    """``fn(*args)`` computed in a child made by ``os.fork`` while this process goes on; the
    value comes back pickled through a pipe. Lighter than :class:`Forked` (no process pool, no
    helper thread: about a millisecond to start) for one short call of a command; in this
    process where the platform cannot fork or has one core. :meth:`result` waits for the value
    (or raises the call's exception); :meth:`close` ends the child at once."""

    def __init__(self, fn: Callable[..., Any], *args: Any, fed: bool = False, nice: int = 0):
        """``fed``: ``fn`` takes one more argument, a function that returns the object this
        process gives later with :meth:`feed` (waiting for it): the child starts on what it
        can do before that object exists. ``nice``: the child's scheduling priority increment
        (``os.nice``)."""
        import os

        self.fn, self.args, self.pid, self.fd = fn, args, None, None
        self.fed, self.feed_fd, self._fed = fed, None, None
        if not hasattr(os, "fork") or (os.cpu_count() or 1) < 2:
            return
        read, write = os.pipe()
        feed_read, feed_write = os.pipe() if fed else (None, None)
        held = hold_signals()
        try:
            pid = os.fork()
            if pid == 0:  # the child never returns from here
                os.close(read)
                if fed:
                    os.close(feed_write)
                    args = (*args, _Receiver(feed_read))
                _child(write, fn, args, nice)
            os.close(write)
            if fed:
                os.close(feed_read)
            self.pid, self.fd, self.feed_fd = pid, read, feed_write
        finally:
            release_signals(held)

    def feed(self, value: Any) -> None:
        """Give the child of a ``fed`` call its object (once)."""
        import os
        import pickle

        if not self.fed:
            raise RuntimeError("feed() of a call that takes nothing later")
        if self.feed_fd is None:
            self._fed = (value,)
            return
        fd, self.feed_fd = self.feed_fd, None
        data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        try:  # its length first: processes forked since hold the pipe too (no end of file)
            with os.fdopen(fd, "wb") as f:
                f.write(len(data).to_bytes(8, "little") + data)
        except BrokenPipeError:  # the child failed before reading: result() says why
            pass

    @property
    def forked(self) -> bool:
        """True when the call runs in a forked process."""
        return self.pid is not None

    def result(self) -> Any:
        import os
        import pickle

        if self.pid is None:
            if not self.fed:
                return self.fn(*self.args)
            if self._fed is None:
                raise RuntimeError("result() of a fed call before feed()")
            return self.fn(*self.args, lambda: self._fed[0])
        if self.feed_fd is not None:
            raise RuntimeError("result() of a fed call before feed()")
        with os.fdopen(self.fd, "rb") as f:
            self.fd = None
            data = f.read()
        os.waitpid(self.pid, 0)
        self.pid = None
        if not data:
            raise RuntimeError("a forked calculation ended without its result")
        ok, value = pickle.loads(data)
        if not ok:
            raise value
        return value

    def close(self) -> None:
        """End the child (at once if it is still working)."""
        import os
        import signal

        for name in ("fd", "feed_fd"):
            if getattr(self, name) is not None:
                os.close(getattr(self, name))
                setattr(self, name, None)
        if self.pid is not None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            os.waitpid(self.pid, 0)
            self.pid = None


class _Receiver:
    """In the child of a fed call: reads what the parent gives from the start, in a thread
    (the parent's write never waits for the child to be ready for it); calling it returns the
    object (waiting for it)."""

    def __init__(self, fd: int):
        import threading

        self._data = b""
        self._thread = threading.Thread(target=self._read, args=(fd,), daemon=True)
        self._thread.start()

    def _read(self, fd: int) -> None:
        import os

        with os.fdopen(fd, "rb") as f:
            head = f.read(8)
            if len(head) == 8:
                self._data = f.read(int.from_bytes(head, "little"))

    def __call__(self) -> Any:
        import pickle

        self._thread.join()
        if not self._data:
            raise RuntimeError("the parent process ended without giving the forked call its"
                               " input")
        return pickle.loads(self._data)


def _child(fd: int, fn: Callable[..., Any], args: tuple, nice: int = 0) -> None:
    """In the forked child: compute, send ``(ok, value or exception)`` pickled, and leave at
    once (``os._exit``: no clean-up of the parent's state, no flush of its buffers)."""
    import os
    import pickle

    code = 0
    try:
        child_start(nice)
        try:
            data = pickle.dumps((True, fn(*args)), protocol=pickle.HIGHEST_PROTOCOL)
        except BaseException as exc:  # noqa: BLE001 - every failure goes to the parent
            try:
                data = pickle.dumps((False, exc))
            except Exception:  # noqa: BLE001 - an exception that does not pickle
                data = pickle.dumps((False, RuntimeError(f"{type(exc).__name__}: {exc}")))
        with os.fdopen(fd, "wb") as f:
            f.write(data)
    except BaseException:  # noqa: BLE001 - the parent sees the missing result
        code = 1
    finally:
        os._exit(code)
