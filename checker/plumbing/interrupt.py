"""Interruptions (Ctrl-C, SIGTERM) as exceptions with the conventional exit codes.

Python turns SIGINT into :class:`KeyboardInterrupt`; SIGTERM by default kills the process at
once, without ``finally`` blocks, so worker processes and temporary files are left behind.
:func:`sigterm_raises` installs a handler that raises :class:`Terminated` in the main thread
instead, so the same clean-up path serves both. :func:`interruptible` wraps a command: on
either exception it prints one line and exits 130 (SIGINT) or 143 (SIGTERM), the shell
convention 128 + signal number, so CI can tell an interruption from a failed verdict (1)::

    from checker.plumbing.interrupt import interruptible

    with interruptible(lambda: "3 variants kept; re-run to resume"):
        long_work()
"""

from __future__ import annotations

import signal
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager

EXIT_SIGINT = 128 + signal.SIGINT  # 130
EXIT_SIGTERM = 128 + signal.SIGTERM  # 143


class Terminated(BaseException):
    """SIGTERM arrived (raised in the main thread by :func:`sigterm_raises`'s handler).

    A BaseException like KeyboardInterrupt, so ``except Exception`` does not swallow it."""

    exit_code = EXIT_SIGTERM


def exit_code(exc: BaseException) -> int | None:
    """130 for KeyboardInterrupt, 143 for :class:`Terminated`, else None."""
    if isinstance(exc, Terminated):
        return EXIT_SIGTERM
    if isinstance(exc, KeyboardInterrupt):
        return EXIT_SIGINT
    return None


_PENDING: list[type[BaseException] | None] = [None]  # an interruption not yet raised
_CALLBACKS = ("weakref.py", "_weakrefset.py")
"""Where an exception raised by a signal handler would be swallowed: the interpreter runs
weakref and garbage-collection callbacks with their exceptions printed as "Exception ignored"
and dropped (the command would then run to its end)."""


def _in_callback(frame) -> bool:
    """Whether an exception raised in ``frame`` would pass through a finalizer (``__del__``)
    or a weakref callback, where the interpreter drops it: the frame itself or any frame it
    was called from (a signal often arrives in a function a finalizer calls, e.g. a
    connection's ``_close`` under its ``__del__``)."""
    while frame is not None:
        code = frame.f_code
        if code.co_name == "__del__" or code.co_filename.endswith(_CALLBACKS):
            return True
        frame = getattr(frame, "f_back", None)
    return False


def _raise(exc: type[BaseException], frame) -> None:
    if _in_callback(frame):
        _PENDING[0] = exc  # raised here it would be dropped: raised at the next checkpoint
        return
    raise exc()


def _raise_terminated(signum, frame) -> None:  # noqa: ARG001 - signal handler signature
    _raise(Terminated, frame)


def _raise_interrupt(signum, frame) -> None:  # noqa: ARG001 - signal handler signature
    _raise(KeyboardInterrupt, frame)


def checkpoint() -> None:
    """Raise an interruption that arrived while the interpreter ran a weakref or
    garbage-collection callback (where its exception would have been dropped). Long commands
    call this at their progress points."""
    exc, _PENDING[0] = _PENDING[0], None
    if exc is not None:
        raise exc()


@contextmanager
def sigterm_raises() -> Iterator[None]:
    """While inside, SIGTERM raises :class:`Terminated` and SIGINT :class:`KeyboardInterrupt`
    in the main thread, or at the next :func:`checkpoint` when they arrive in a callback whose
    exceptions the interpreter drops (the previous handlers are restored on exit). Outside the
    main thread this does nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _PENDING[0] = None
    old = signal.signal(signal.SIGTERM, _raise_terminated)
    old_int = signal.signal(signal.SIGINT, _raise_interrupt)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, old)
        signal.signal(signal.SIGINT, old_int)


def worker_signals() -> None:
    """For a worker process forked from a command: ignore SIGINT (the parent decides what a
    Ctrl-C to the process group means and ends its workers) and die on SIGTERM (the default
    action, not the parent's inherited handler)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


@contextmanager
def interruptible(message: Callable[[], str] | str | None = None,
                  echo: Callable[[str], None] | None = None) -> Iterator[None]:
    """Run the body with SIGTERM raising :class:`Terminated`; on KeyboardInterrupt or
    Terminated print ``interrupted[: message]`` on stderr and exit 130 or 143.

    ``message`` may be a callable, evaluated after the interruption (e.g. to count what was
    kept). Clean-up belongs in the body's own ``finally`` blocks, which run first."""
    try:
        with sigterm_raises():
            yield
    except (KeyboardInterrupt, Terminated) as exc:
        code = exit_code(exc)
        # a second signal while reporting must not turn into a traceback
        main = threading.current_thread() is threading.main_thread()
        old = [(s, signal.signal(s, signal.SIG_IGN)) for s in (signal.SIGINT,
                                                             signal.SIGTERM)] if main else []
        try:
            text = message() if callable(message) else message
            line = "interrupted" + (f": {text}" if text else "")
            (echo or (lambda s: print(s, file=sys.stderr, flush=True)))(line)
        finally:
            for s, h in old:
                signal.signal(s, h)
        raise SystemExit(code) from None
