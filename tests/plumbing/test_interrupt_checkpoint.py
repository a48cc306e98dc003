"""An interruption that arrives inside a weakref/garbage-collection callback (where the
interpreter drops a handler's exception, "Exception ignored") is raised at the next progress
checkpoint instead of being lost (the report then ran to its end and exited 1, not 130)."""

from __future__ import annotations

import types

import pytest

from checker.plumbing import interrupt


def _frame(filename: str, name: str = "remove"):
    code = types.SimpleNamespace(co_filename=filename, co_name=name)
    return types.SimpleNamespace(f_code=code)


def test_signal_in_a_weakref_callback_is_raised_at_the_next_checkpoint():
    interrupt.checkpoint()  # nothing pending
    interrupt._raise_interrupt(2, _frame("/usr/lib/python3.11/weakref.py"))  # no raise here
    with pytest.raises(KeyboardInterrupt):
        interrupt.checkpoint()
    interrupt.checkpoint()  # raised once only
    interrupt._raise_terminated(15, _frame("x.py", "__del__"))
    with pytest.raises(interrupt.Terminated):
        interrupt.checkpoint()


def test_signal_elsewhere_raises_at_once():
    with pytest.raises(KeyboardInterrupt):
        interrupt._raise_interrupt(2, _frame("/work/checker/report/render.py", "build"))
    with pytest.raises(interrupt.Terminated):
        interrupt._raise_terminated(15, None)
    interrupt.checkpoint()  # nothing left pending


def test_signal_in_a_function_a_finalizer_calls_is_raised_at_the_next_checkpoint():
    """CI caught a SIGTERM that arrived in multiprocessing's ``_close``, called by a
    connection's ``__del__``: the frame the handler gets is ``_close``, not ``__del__``."""
    import sys

    def close():  # the handler runs here, two frames below the finalizer
        interrupt._raise_terminated(15, sys._getframe())

    class Connection:
        def __del__(self):
            close()

    interrupt.checkpoint()
    Connection()  # finalized at once; nothing raised here
    with pytest.raises(interrupt.Terminated):
        interrupt.checkpoint()
    interrupt.checkpoint()  # raised once only
