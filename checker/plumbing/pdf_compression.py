"""pydyf's content streams compressed at one zlib level while a PDF is written.

Patches a dependency: pydyf (:data:`MEASURED_ON`) calls ``zlib.compressobj`` /
``zlib.compress`` through its module attribute ``pydyf.zlib`` at level 9. Where that attribute
is not the ``zlib`` module, nothing is patched (the PDF is written at pydyf's own levels);
:func:`missing_targets` names what a release no longer has, and
tests/plumbing/test_patch_targets.py fails on it loudly.
"""

from __future__ import annotations

from contextlib import contextmanager

from . import swapped

MEASURED_ON = "pydyf 0.10 to 0.13 (timed on 0.13.0, with WeasyPrint 70.0)"
"""The releases this patch was measured on."""


def missing_targets() -> list[str]:
    """What the patch replaces and the installed pydyf does not have (empty: all)."""
    import inspect
    import zlib

    import pydyf

    out = []
    if getattr(pydyf, "zlib", None) is not zlib:
        out.append("pydyf.zlib (the zlib module)")
    elif "zlib.compressobj(" not in inspect.getsource(pydyf):
        out.append("pydyf calling zlib.compressobj")
    return out

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
