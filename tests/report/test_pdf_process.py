"""The PDF engine process (issue 37 item 14): WeasyPrint imported and warmed in a process
forked before the analysis, which then lays out and writes the report. The PDF is byte for
byte the one laid out in the command's own process; a failure there comes back as its
exception; the process never outlives the command."""

from __future__ import annotations

import multiprocessing as mp

import pytest
from click.testing import CliRunner

from checker import api
from checker.cli import main
from checker.report import pdf_engine, pdf_process
from checker.report.render import build_report
from checker.workbook.example import example_content, write_workbook

pytestmark = pytest.mark.skipif(pdf_process.start() is None,
                                reason="needs fork and two cores")


@pytest.fixture(scope="module")
def res(tmp_path_factory):
    p = tmp_path_factory.mktemp("engine") / "engine.xlsx"
    write_workbook(p, example_content())
    return api.check(p)


def test_engine_writes_the_same_pdf_and_html_as_this_process(res):
    here = build_report(res, want_html=True)
    engine = pdf_process.start()
    try:
        there = build_report(res, want_html=True, engine=engine)
    finally:
        engine.close()
    assert there.document is None and here.document is not None
    assert there.pages == here.pages > 20
    assert there.pdf == here.pdf  # same layout, same drawn figures, same bytes
    assert there.html == here.html
    assert there.results == here.results
    for stage in ("PDF layout", "PDF write", "of which waiting for the figures"):
        assert stage in there.stages
    assert not [p for p in mp.active_children() if p.name.startswith("Process")]


def test_a_failure_in_the_engine_comes_back_as_its_exception(res, monkeypatch):
    real = pdf_engine.html_class
    monkeypatch.setattr(pdf_engine, "html_class", lambda wp: _Switch(real(wp)))
    engine = pdf_process.start()  # forked with the switch: the engine's report fails
    try:
        with pytest.raises(ValueError, match="layout failed on purpose"):
            build_report(res, want_html=False, engine=engine)
    finally:
        engine.close()
    assert engine.process is None


class _Switch:
    """An HTML class whose first document (the warm-up) is laid out and whose second (the
    report) fails."""

    def __init__(self, cls):
        self.cls = cls
        self.n = 0

    def __call__(self, *args, **kwargs):
        self.n += 1
        doc = self.cls(*args, **kwargs)
        if self.n > 1:
            def render(*a, **k):
                raise ValueError("layout failed on purpose")

            doc.render = render
        return doc


def test_an_idle_engine_ends_when_closed():
    engine = pdf_process.start()
    p = engine.process
    engine.close()
    assert not p.is_alive() and p.exitcode is not None
    engine.close()  # twice is harmless


def test_bad_input_ends_the_engine_with_the_command(tmp_path):
    p = tmp_path / "engine.xlsx"
    content = example_content()
    write_workbook(p, content)
    bad = tmp_path / "bad.xlsx"
    bad.write_bytes(b"not a workbook")
    before = set(mp.active_children())
    out = CliRunner().invoke(main, ["report", str(bad), "-o", str(tmp_path / "r.pdf")])
    assert out.exit_code == 2
    assert not (tmp_path / "r.pdf").exists()
    assert set(mp.active_children()) <= before
