"""The numbers docs/examples.md quotes are those of a fresh check of the examples (issue 43,
item 13): the page is generated from ``scripts/examples_doc_template.md`` by
``scripts/make_examples_doc.py``; after a change that moves the examples' results run
``python scripts/make_examples_doc.py`` and read the diff."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _script():
    spec = importlib.util.spec_from_file_location(
        "make_examples_doc", ROOT / "scripts" / "make_examples_doc.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # (its dataclasses look their module up)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def script():
    return _script()


def test_the_page_quotes_a_fresh_check_of_the_examples(script):
    template = script.TEMPLATE.read_text(encoding="utf-8")
    page = script.OUT.read_text(encoding="utf-8")
    numbers = script.quoted(template)  # a check of the I4, I6 and V8
    assert len(numbers) > 50
    off = script.differences(template, page, numbers)
    assert not off, ("docs/examples.md is stale; run python scripts/make_examples_doc.py:\n"
                     + "\n".join(off))


def test_the_v8_natural_frequencies_are_quoted_from_the_check(script):
    template = script.TEMPLATE.read_text(encoding="utf-8")
    for k in (1, 2):
        assert f"v8.mode({k})" in template


def test_a_stale_number_is_found_within_the_printed_digits(script):
    template = "modes {{ v8.mode(1) | .0f }} and {{ v8.mode(2) | .0f }} Hz, {{ v8.count('x') | d }}"
    nums = [script.Quoted("v8.mode(1)", ".0f", 263.121),
            script.Quoted("v8.mode(2)", ".0f", 371.388), script.Quoted("n", "d", 40)]
    assert script.render(template, nums) == "modes 263 and 371 Hz, 40"
    assert script.differences(template, "modes 263 and 371 Hz, 40", nums) == []
    # one unit of the last printed digit: rounding on another machine cannot cross it
    assert script.differences(template, "modes 264 and 372 Hz, 40", nums) == []
    stale = script.differences(template, "modes 267 and 419 Hz, 40", nums)
    assert len(stale) == 2 and "says 267" in stale[0] and "gives 263" in stale[0]
    assert len(script.differences(template, "modes 263 and 371 Hz, 41", nums)) == 1  # counts
    (text,) = script.differences(template, "modes 263 and 371 Hz; 40", nums)
    assert text.startswith("the page's text differs from the template at: 'Hz,'")
