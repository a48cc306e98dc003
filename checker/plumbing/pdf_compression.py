"""pydyf's content streams compressed at one zlib level while a PDF is written.

Patches a dependency: pydyf (measured on pydyf 0.10-0.11, as WeasyPrint 62-66 use it) calls
``zlib.compressobj`` / ``zlib.compress`` through its module attribute ``pydyf.zlib`` at level 9.
Where that attribute is not the ``zlib`` module, nothing is patched (the PDF is written at
pydyf's own levels); :func:`patch_target_present` tells whether it still is, and a test fails
loudly when it is not.
"""

from __future__ import annotations

from contextlib import contextmanager

from . import swapped

FLATE_LEVEL = 6
"""zlib level of the PDF's compressed streams. The PDF writer (pydyf) compresses each page's
content stream at level 9; level 6 (zlib's default) gives a file 0.2 % larger in a fifth less
writing time (I4 report: 0.53 -> 0.42 s of processor time; benchmarks/bench_report.py)."""


class ZlibAtLevel:
    """zlib with every compression at one level (the module pydyf calls)."""

    def __init__(self, zlib, level: int):
        self._zlib, self._level = zlib, level

    def compressobj(self, level: int = -1, *args, **kwargs):  # noqa: ARG002 - overridden
        return self._zlib.compressobj(self._level, *args, **kwargs)

    def compress(self, data, level: int = -1, **kwargs):  # noqa: ARG002 - overridden
        return self._zlib.compress(data, self._level, **kwargs)

    def __getattr__(self, name: str):
        return getattr(self._zlib, name)


@contextmanager
def flate_level(level: int):
    """pydyf's streams compressed at ``level`` while the PDF is written (where pydyf calls
    zlib as a module attribute; otherwise its own levels)."""
    import zlib

    import pydyf

    if getattr(pydyf, "zlib", None) is not zlib:
        yield
        return
    with swapped.attribute(pydyf, "zlib", ZlibAtLevel(zlib, level)):
        yield
