"""WeasyPrint imported without a search of the system's libraries where their usual names load.

WeasyPrint loads Pango, HarfBuzz, fontconfig and GObject through cffi, trying several names
per library for the different platforms (``weasyprint/text/ffi.py``: ``libgobject-2.0-0``,
``gobject-2.0-0``, ``gobject-2.0``, ``libgobject-2.0.so.0``, ...). For every name that is not
a loadable file name, cffi asks :func:`ctypes.util.find_library`, which on Linux runs
``ldconfig -p`` and then the C compiler or linker to look for it: about fifteen programs
started before the usual name (``libgobject-2.0.so.0``) is tried, 0.13 s of processor time
and 0.15 s of the import's 0.39 s (benchmarks/bench_report.py, docs/benchmarks.md, "Report
speed, fourth round"). The libraries loaded are the same.

:func:`import_weasyprint` imports WeasyPrint with that search answered "not found", so each
library loads under the first of its names the dynamic loader knows; if that fails for a
library WeasyPrint requires, or HarfBuzz's subsetting library (which the PDF's fonts use) is
left out, the import is done again in WeasyPrint's own way. Only on Linux (elsewhere the
search starts no programs).

Measured on :data:`MEASURED_ON`. :func:`missing_targets` names what a release no longer has
(cffi no longer asking ``ctypes.util.find_library``, WeasyPrint's ``_dlopen`` gone): the
shortcut would then do nothing, and tests/plumbing/test_patch_targets.py fails on it loudly.
"""

from __future__ import annotations

import sys
from contextlib import AbstractContextManager
from types import ModuleType

from . import swapped

MEASURED_ON = "WeasyPrint 62 to 70 with cffi 1.16 to 2.1 (timed on WeasyPrint 70.0, cffi 2.1.1)"
"""The releases this shortcut was measured on."""


def missing_targets() -> list[str]:
    """What the shortcut relies on and the installed cffi and WeasyPrint lack (empty: all)."""
    import importlib.util
    import inspect

    import cffi.api

    out = []
    if "ctypes.util.find_library(" not in inspect.getsource(cffi.api):
        out.append("cffi.api calling ctypes.util.find_library")
    spec = importlib.util.find_spec("weasyprint.text.ffi")
    source = spec.loader.get_source(spec.name) if spec and spec.loader else ""
    if "def _dlopen(" not in (source or "") or "harfbuzz_subset" not in (source or ""):
        out.append("weasyprint.text.ffi._dlopen and harfbuzz_subset")
    return out


def _no_library_search() -> AbstractContextManager[None]:
    import ctypes.util

    return swapped.attribute(ctypes.util, "find_library", lambda _name: None)  # "not found"


def _forget_weasyprint() -> None:
    for name in [m for m in sys.modules if m == "weasyprint" or m.startswith("weasyprint.")]:
        del sys.modules[name]


def import_weasyprint() -> ModuleType:
    """The ``weasyprint`` module (see the module docstring); raises what WeasyPrint's own
    import raises (``OSError`` without Pango)."""
    if "weasyprint" in sys.modules or not sys.platform.startswith("linux"):
        import weasyprint

        return weasyprint
    try:
        with _no_library_search():
            import weasyprint
            from weasyprint.text import ffi
        if ffi.harfbuzz_subset is not None:
            return weasyprint
    except OSError:
        pass
    _forget_weasyprint()
    import weasyprint

    return weasyprint
