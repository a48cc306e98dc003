"""A call whose nested Python frames live in one large block of the interpreter's frame stack.

CPython (3.11 and later) keeps the frames of Python calls on a stack of 16 KiB chunks
(``Python/pystate.c``: ``push_chunk``, ``_PyThreadState_PopFrame``): a call that does not fit
in the current chunk maps a new one, and the chunk is unmapped again as soon as that call
returns. A deep recursion that goes up and down across a chunk boundary, as the PDF engine's
layout of nested boxes and matplotlib's drawing of nested artists do, thus maps, touches and
unmaps memory at every crossing (two system calls and a page fault or more each): in the
engine process of an I4 report about 50 000 page faults, a fifth of all page faults of the
command (``docs/benchmarks.md``, "Report speed, fourth round").

:func:`call` runs a function below a frame that reserves a large evaluation stack: the chunk
mapped for that frame is sized for it (chunks double from 16 KiB until the frame fits), and
the frames of everything the function calls, to the interpreter's recursion limit, fit in
the rest of that chunk, which stays mapped until the function returns. The reserved stack is
never written, so its pages are never touched. Nothing else changes: on another
implementation, or should CPython size its chunks otherwise, the function is simply called.

Measured on :data:`MEASURED_ON`; :func:`missing_targets` says when this CPython no longer
takes the large frame, and tests/plumbing/test_frame_stack.py counts the pages a recursion
touches below it (a release that sizes its chunks otherwise fails there, loudly).
"""

from __future__ import annotations

import sys
import types
from collections.abc import Callable
from typing import Any, TypeVar

T = TypeVar("T")

MEASURED_ON = "CPython 3.11 (timed on 3.11.7)"
"""The interpreter this was measured on."""

RESERVED_SLOTS = 140_000
"""Evaluation-stack slots the outer frame reserves (8 bytes each, 1.1 MB): its chunk is
2 MiB (16 KiB doubled until the frame fits), which leaves 0.9 MB, about 110 000 slots, for
the frames below it; a Python frame takes 10-60 slots, so the interpreter's default
recursion limit (1000 frames) stays within the chunk."""


def _outer(fn, args, kwargs):
    return fn(*args, **kwargs)


def _make_outer() -> Callable[..., Any] | None:
    if sys.implementation.name != "cpython" or sys.version_info < (3, 11):
        return None  # no chunked frame stack (3.10: frames are heap objects)
    try:
        code = _outer.__code__.replace(co_stacksize=RESERVED_SLOTS)
    except (TypeError, ValueError):  # pragma: no cover - a code object that refuses it
        return None
    return types.FunctionType(code, _outer.__globals__, "_outer_large_frame")


_OUTER = _make_outer()


def call(fn: Callable[..., T], /, *args: Any, **kwargs: Any) -> T:
    """``fn(*args, **kwargs)`` with its nested frames in one mapped block of the frame stack
    (see the module); the same result and exceptions as the plain call."""
    if _OUTER is None:
        return fn(*args, **kwargs)
    return _OUTER(fn, args, kwargs)


def missing_targets() -> list[str]:
    """What the large frame relies on and this CPython lacks (empty: all, or not CPython
    3.11+, where there is nothing to patch)."""
    if sys.implementation.name == "cpython" and sys.version_info >= (3, 11) and _OUTER is None:
        return ["a code object's co_stacksize replaced (CPython's chunked frame stack)"]
    return []
