"""The text, JSON and JUnit outputs (checker/outputs/formats.py) and the report's rows say the same
things in the same words (issue 37)."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET

import pytest

from checker import api
from checker.outputs.formats import to_json, to_junit, to_text
from checker.report import results_book, summary
from tests.helpers import example_path


@pytest.fixture(scope="module")
def whole_engine(tmp_path_factory):
    """The I4's damper heat (DMP-002) and crank-nose amplitude (TV-001): results about the
    whole engine, not one of its items."""
    return api.check(example_path(tmp_path_factory.mktemp("outputs")),
                     select=["DMP-002", "TV-001"])


def test_the_whole_engine_reads_engine_everywhere(whole_engine):
    """Issue 37, item 3: page 1 named DMP-002's item "engine" where the text output said
    "all". One word for people (text, JUnit, the PDF's rows, the results workbook); the JSON
    keeps its item key ``all`` for programs that read it."""
    res = whole_engine
    assert {r.item for r in res.results} == {"all"}
    text = to_text(res)
    lines = [x for x in text.splitlines() if x.startswith(("DMP-002", "TV-001"))]
    assert len(lines) == 2
    for line in lines:
        assert re.search(r"\bengine\b", line) and not re.search(r"\ball\b", line), line
    cases = ET.fromstring(to_junit(res)).iter("testcase")
    names = [c.get("name") for c in cases]
    assert names and all(n.endswith("[engine]") for n in names), names
    rows = summary.rows(res)
    assert rows and all(x.item_text == "engine" for x in rows)
    _, book = results_book._results_rows(res)
    assert {row[2] for row in book} == {"engine"}
    assert {r["item"] for r in json.loads(to_json(res, timings=False))["results"]} == {"all"}
