"""The examples in the docstrings are tests (``>>>``, as fluids runs ``--doctest-modules``):
every module of the package whose docstrings hold an example, and every module of
:mod:`checker.calc`, runs its examples with :mod:`doctest`."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "checker"


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = sorted({_module_name(p) for p in PACKAGE.rglob("*.py")
                  if ">>>" in p.read_text(encoding="utf-8") or p.parent.name == "calc"})
FLAGS = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=FLAGS, report=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed in {name}"


def test_examples_run():
    """Not vacuous: the calc modules' examples are found and run (at least the four of the
    bolted joint, crank stress and SCF modules)."""
    ran = sum(doctest.testmod(importlib.import_module(n), optionflags=FLAGS,
                              report=False).attempted
              for n in MODULES if n.startswith("checker.calc"))
    assert ran >= 4


def test_a_wrong_example_fails():
    def f():
        """>>> 1 + 1
        3
        """

    runner = doctest.DocTestRunner(optionflags=FLAGS)
    for t in doctest.DocTestFinder().find(f, "f", globs={}):
        runner.run(t, out=lambda _s: None)
    assert runner.failures == 1
