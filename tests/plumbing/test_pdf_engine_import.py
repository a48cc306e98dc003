"""checker.plumbing.pdf_engine_import: WeasyPrint imported with the same system libraries as
its own import, without starting programs to search for them, and in its own way when the
usual names do not load."""

import sys

import pytest

from tests.helpers import fresh_python

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="the library search starts programs only on Linux")

LIBRARIES = """
import resource
libs = sorted({line.split()[-1].rsplit("/", 1)[-1] for line in open("/proc/self/maps")
               if any(k in line for k in ("pango", "harfbuzz", "fontconfig", "gobject"))})
from weasyprint.text import ffi
children = resource.getrusage(resource.RUSAGE_CHILDREN)
print(libs, ffi.harfbuzz_subset is not None, ffi.harfbuzz_vector is not None,
      children.ru_utime + children.ru_stime > 0)
"""


def test_same_libraries_as_weasyprints_own_import_and_no_programs_started():
    own = fresh_python("import weasyprint\n" + LIBRARIES)
    ours = fresh_python("from checker.plumbing.pdf_engine_import import import_weasyprint\n"
                        "import_weasyprint()\n" + LIBRARIES)
    assert own.rsplit(" ", 1)[0] == ours.rsplit(" ", 1)[0]
    assert "libpango-1.0.so" in ours
    assert ours.endswith("False"), "a program was started to find a library"


def test_the_import_is_done_again_in_weasyprints_way_when_the_usual_names_fail():
    """The usual names made to fail (a system whose libraries only the search finds): the
    first import raises OSError, the second, with the search, succeeds."""
    out = fresh_python("""
from contextlib import contextmanager
import ctypes.util
from checker.plumbing import pdf_engine_import as m
calls = []

@contextmanager
def failing():
    real = ctypes.util.find_library
    def fail(name):
        calls.append(name)
        raise OSError(f"no {name} here")
    ctypes.util.find_library = fail
    try:
        yield
    finally:
        ctypes.util.find_library = real

m._no_library_search = failing
wp = m.import_weasyprint()
from weasyprint.text import ffi
print(len(calls) > 0, wp.HTML is not None, ffi.pango is not None)
""")
    assert out == "True True True"
