"""The parts of the report renderer that make it faster must not change what it shows: the
PDF's streams at one zlib level with pydyf restored after, the results workbook written in a
forked process is the one written in this process, and a worst-case table's repeated
not-judged reason is said once."""

from __future__ import annotations

from checker.plumbing import pdf_compression
from checker.report import pdf_engine, render


def _table(reasons: list[str]) -> dict:
    rows = [["pin 1", "1.5", "FAT-001"]]
    css = [""]
    for r in reasons:
        rows.append(["pin 1", "1.4", r])
        css.append("not-judged")
    return {"type": "table", "caption": "Worst cases.", "columns": ["item", "SF", "judged by"],
            "rows": rows, "row_css": css}


def test_one_repeated_reason_is_said_once():
    b = render._collapse_marked_reason(_table(["not judged: outside the envelope"] * 3))
    assert [r[2] for r in b["rows"]] == ["FAT-001"] + ["not judged"] * 3
    assert b["note"] == "Marked rows: not judged: outside the envelope."
    assert b["caption"] == "Worst cases."


def test_several_reasons_are_numbered():
    b = render._collapse_marked_reason(_table(["not judged: a", "not judged: b",
                                               "not judged: a"]))
    assert [r[2] for r in b["rows"]][1:] == ["not judged (1)", "not judged (2)",
                                             "not judged (1)"]
    assert b["note"] == "Marked rows: (1) not judged: a; (2) not judged: b."


def test_reasons_said_once_each_stay_in_their_rows():
    t = _table(["not judged: a", "not judged: b"])
    assert render._collapse_marked_reason(t) is t
    t = _table(["not judged: a"])
    assert render._collapse_marked_reason(t) is t


def test_pdf_streams_at_the_chosen_zlib_level_and_pydyf_restored():
    """The PDF's streams are compressed at FLATE_LEVEL while it is written, and pydyf's zlib
    is zlib again afterwards (also after a failure)."""
    import zlib

    import pydyf
    import pytest

    wp = pdf_engine.load_weasyprint()
    doc = wp.HTML(string="<p>" + "text " * 2000 + "</p>").render()
    pdf = pdf_engine.write_pdf(wp, doc, "<p>x</p>", [])
    assert pydyf.zlib is zlib
    seen = []
    real = zlib.compressobj

    def spy(level=-1, *args, **kwargs):
        seen.append(level)
        return real(level, *args, **kwargs)

    zlib.compressobj = spy
    try:
        again = pdf_engine.write_pdf(wp, doc, "<p>x</p>", [])
    finally:
        zlib.compressobj = real
    assert again == pdf and seen and set(seen) == {pdf_compression.FLATE_LEVEL}
    with pytest.raises(RuntimeError), pdf_compression.flate_level(1):
        assert pydyf.zlib is not zlib
        raise RuntimeError
    assert pydyf.zlib is zlib


def test_fewer_collections_keeps_collecting_garbage():
    """The workers' collector setting: the young generation less often, garbage still
    collected (a reference cycle made afterwards is freed)."""
    import gc
    import weakref

    from checker.plumbing.gc_tuning import YOUNG_THRESHOLD, fewer_collections

    old = gc.get_threshold()
    try:
        fewer_collections()
        assert gc.get_threshold()[0] == YOUNG_THRESHOLD

        class Node:
            pass

        a, b = Node(), Node()
        a.other, b.other = b, a
        gone = weakref.ref(a)
        del a, b
        kept = [[] for _ in range(3 * YOUNG_THRESHOLD)]  # net allocations: collections run
        assert gone() is None and len(kept) == 3 * YOUNG_THRESHOLD
    finally:
        gc.unfreeze()
        gc.set_threshold(*old)
