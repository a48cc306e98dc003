"""Figures drawn while the PDF is laid out (issue 37 item 14): the drawing processes send
each section with placeholders of its figures' exact pixel size and draw the figures
afterwards; the report's PDF and HTML carry the drawn figures, byte for byte the images that
drawing at once gives, and never a placeholder."""

from __future__ import annotations

import base64
import re

import pytest

from checker import api
from checker.report import plots
from checker.report.render import build_report
from checker.report.sections import SECTIONS, SectionJob
from checker.workbook.example import example_content, write_workbook
from tests.helpers import fresh_python, template_paths


@pytest.fixture(scope="module")
def res(tmp_path_factory):
    p = tmp_path_factory.mktemp("deferred") / "engine.xlsx"
    write_workbook(p, example_content())
    return api.check(p)


@pytest.fixture(scope="module")
def drawn_at_once(res):
    """Every figure of the sections, drawn at once (no placeholders), in section order."""
    return [b["png"] for s in SectionJob(res).result() for b in s["blocks"]
            if b["type"] == "figure"]


def test_placeholders_have_the_size_of_the_drawn_figures(res, drawn_at_once):
    job = SectionJob(res, defer=True)
    sections = job.result()
    held = [b["png"] for s in sections for b in s["blocks"] if b["type"] == "figure"]
    images = job.images()
    assert job.procs == []  # the drawing processes have ended
    assert len(held) == len(drawn_at_once) > 10
    assert all(isinstance(p, plots.Deferred) for p in held)
    assert len({p.key for p in held}) == len(held) == len(images)
    for ph, now in zip(held, drawn_at_once):
        assert plots.image_size(ph) == ph.size == plots.image_size(now)
        assert ph.width_mm == now.width_mm
        later = images[ph.key]
        assert bytes(later) == bytes(now)  # deterministic JPEG: the same figure
        assert later.texts == now.texts


def test_report_carries_the_drawn_figures(res, drawn_at_once):
    rep = build_report(res, want_html=True)
    import io

    import pypdf

    reader = pypdf.PdfReader(io.BytesIO(rep.pdf))
    in_pdf = set()
    for page in reader.pages:
        xobjects = page["/Resources"].get("/XObject") or {}
        for ref in xobjects.values():
            x = ref.get_object()
            if x.get("/Subtype") == "/Image":
                assert x["/Filter"] == "/DCTDecode"
                in_pdf.add(x._data)  # the embedded JPEG as it is
    at_once = {bytes(p) for p in drawn_at_once}
    assert in_pdf == at_once
    in_html = {base64.b64decode(m) for m in
               re.findall(r'src="data:image/jpeg;base64,([^"]+)"', rep.html)}
    assert in_html == at_once
    assert "of which waiting for the figures" in rep.stages


def test_a_failing_section_fails_the_job_and_ends_its_processes(res):
    def boom(_res):
        raise ValueError("section failed on purpose")

    SECTIONS["boom"] = boom
    try:
        job = SectionJob(res, modules=["boom", "joints"], defer=True)
        with pytest.raises(ValueError, match="on purpose"):
            job.result()
        assert job.procs == []
    finally:
        del SECTIONS["boom"]


def test_a_drawing_process_that_dies_fails_the_job(res, monkeypatch):
    """A drawing process that ends before sending its figures (killed, out of memory) is
    an error of the report, never a placeholder in the PDF."""
    import os

    monkeypatch.setattr(plots, "draw_deferred", lambda index: os._exit(3))
    job = SectionJob(res, modules=["joints"], defer=True)
    sections = job.result()
    assert any(isinstance(b.get("png"), plots.Deferred) for s in sections
               for b in s["blocks"])
    with pytest.raises(RuntimeError, match="exit code 3"):
        job.images()
    assert job.procs == []


def _failing_figure() -> bytes:
    raise ValueError("figure failed on purpose")


def test_a_failing_figure_fails_the_job_and_ends_its_processes(res):
    """A figure is built where it is drawn (plots.later): its failure there fails the job."""
    def with_bad_figure(_res):
        return {"id": "bad", "title": "bad", "intro": "", "blocks": [
            {"type": "figure", "png": plots.later((170, 60), _failing_figure),
             "caption": "never drawn"}]}

    SECTIONS["bad"] = with_bad_figure
    try:
        job = SectionJob(res, modules=["bad", "joints"], defer=True)
        sections = job.result()  # the sections arrive: the figure is only a placeholder
        assert isinstance(sections[0]["blocks"][0]["png"], plots.Deferred)
        with pytest.raises(ValueError, match="figure failed on purpose"):
            job.images()
        assert job.procs == []
    finally:
        del SECTIONS["bad"]


def test_sections_are_built_without_matplotlib(tmp_path):
    """While figures are deferred a section needs no matplotlib (plots.later): the drawing
    processes send the sections before they build a figure, so the PDF engine gets the HTML
    sooner, and build and draw the figures while it lays the pages out."""
    paths = template_paths(tmp_path)
    code = ("import sys; from checker import api\n"
            "from checker.report import plots\n"
            "from checker.report.sections import SECTIONS, modules_with_sections\n"
            "n = 0\n"
            "for p in " + repr(paths) + ":\n"
            "    r = api.check(p)\n"
            "    plots.DEFERRED = []\n"
            "    for m in modules_with_sections(r):\n"
            "        n += sum(isinstance(b.get('png'), plots.Deferred)\n"
            "                 for b in SECTIONS[m](r)['blocks'])\n"
            "    assert all(isinstance(x, tuple) for x in plots.DEFERRED)\n"
            "print('matplotlib' in sys.modules, n)")
    out = fresh_python(code).split()
    assert out[0] == "False" and int(out[1]) > 40
