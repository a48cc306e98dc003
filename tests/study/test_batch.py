"""Study variants checked in chunks (api.check_batch) give the records of one-by-one checks;
the worker's calculation cache is bounded; chunks shrink towards the end of a study."""

from __future__ import annotations

import numpy as np
import pytest

from checker.study import run as study_run
from checker.study.run import CalcCache, plan_chunks, run_study
from checker.study.spec import load_study
from tests.helpers import example_path

# film rules (both film models, batched orbits) on a clearance and a width: every variant
# changes the film inputs, one has a bad clearance (an input error inside a chunk)
FILM = """[study]
name = "film"
design = "one-at-a-time"
select = ["BRG-003", "BRG-004", "BRG-005", "BRG-006", "BRG-001"]

[[parameter]]
name = "main clearance"
sheet = "Bearings"
where = { type = "main" }
column = "radial clearance"
unit = "um"
values = [18, -3, 34]

[[parameter]]
name = "main width"
sheet = "Bearings"
where = { type = "main" }
column = "effective length"
unit = "mm"
values = [17, 20]
"""


def _strip(recs) -> list[dict]:
    return [{k: v for k, v in r.items() if k != "seconds"} for r in recs]


@pytest.fixture(scope="module")
def film_study(tmp_path_factory):
    d = tmp_path_factory.mktemp("batch")
    wb = example_path(d)
    st = d / "film.toml"
    st.write_text(FILM, encoding="utf-8")
    return d, wb, st


def test_chunked_study_equals_one_by_one(film_study, tmp_path, monkeypatch):
    from checker.modules import film_memo

    d, wb, st = film_study
    film_memo.clear()
    study_run._WORKER.clear()
    monkeypatch.setattr(study_run, "CHUNK", 1)
    one = run_study(load_study(st), wb, tmp_path / "one", workers=1)
    film_memo.clear()
    study_run._WORKER.clear()
    monkeypatch.setattr(study_run, "CHUNK", 8)
    monkeypatch.setattr(study_run, "plan_chunks", lambda todo, n: [todo])  # one chunk
    calls = []
    from checker import api

    orig = api.check_batch
    monkeypatch.setattr(api, "check_batch", lambda engines, **kw: calls.append(len(engines))
                        or orig(engines, **kw))
    batched = run_study(load_study(st), wb, tmp_path / "batched", workers=1)
    assert calls == [5]  # six variants, one of them an input error
    assert [r["status"] for r in batched.records].count("input error") == 1
    assert _strip(batched.records) == _strip(one.records)
    assert any(r["rule"] == "BRG-003" and r["value"] is not None
               for rec in batched.records for r in rec["results"])


def test_cache_is_trimmed_least_recently_used_first():
    c = CalcCache()
    mb = 2**20
    for k in "abcd":
        c[k] = ({"q": np.zeros(mb // 8)}, {})  # 1 MB each
    assert c.get("a") is not None  # read: now the most recently used
    c.trim(int(2.5 * mb))
    assert list(c) == ["d", "a"]
    c.trim(0)
    assert not c and not c.sizes


def test_worker_cache_stays_bounded(film_study, tmp_path, monkeypatch):
    d, wb, st = film_study
    study_run._WORKER.clear()
    monkeypatch.setattr(study_run, "CACHE_BYTES", 5 * 2**20)
    run_study(load_study(st), wb, tmp_path / "small", workers=1)
    cache = study_run._WORKER["cache"]
    assert sum(cache.sizes.values()) <= 5 * 2**20
    assert set(cache.sizes) == set(cache)


@pytest.mark.parametrize("n,workers", [(100, 2), (7, 2), (1, 4), (1000, 1)])
def test_chunks_cover_the_study_in_order_and_shrink(n, workers):
    ch = plan_chunks(list(range(n)), workers)
    assert [i for c in ch for i in c] == list(range(n))
    sizes = [len(c) for c in ch]
    assert sizes == sorted(sizes, reverse=True) and max(sizes) <= study_run.CHUNK
    assert sizes[-1] == 1


JOINTS = """[study]
name = "nose torque"
design = "one-at-a-time"
select = ["JNT-001"]

[[parameter]]
sheet = "Joints"
row = "crank nose"
column = "tightening torque"
unit = "N m"
values = [300, 330]
"""


def _cells(path) -> list[tuple]:
    import openpyxl

    return [tuple(r) for r in openpyxl.load_workbook(path, read_only=True)["results"]
            .iter_rows(values_only=True)]


def test_xlsx_written_alongside_the_pdf_equals_the_plain_one(film_study, tmp_path):
    from checker.study.results import write_tables

    d, wb, _ = film_study
    st = tmp_path / "j.toml"
    st.write_text(JOINTS, encoding="utf-8")
    run = run_study(load_study(st), wb, tmp_path / "out", workers=1)
    plain = write_tables(run, tmp_path / "plain")
    seen = []
    both = write_tables(run, tmp_path / "both", alongside=lambda: seen.append(1))
    assert seen == [1] and [p.split("/")[-1] for p in both] == ["results.parquet",
                                                               "results.xlsx"]
    assert _cells(tmp_path / "both" / "results.xlsx") == _cells(plain[1])
    # header, baseline and two torques: JNT-001 of the crank nose and, not applicable, of the
    # yield-controlled flywheel joint (issue 37)
    rows = _cells(plain[1])
    assert len(rows) == 1 + 3 * 2
    status = rows[0].index("status")
    assert sorted(r[status] for r in rows[1:]).count("not_applicable") == 3

    def broken() -> None:
        raise ValueError("no PDF")

    with pytest.raises(ValueError, match="no PDF"):  # the tables are kept all the same
        write_tables(run, tmp_path / "broken", alongside=broken)
    assert _cells(tmp_path / "broken" / "results.xlsx") == _cells(plain[1])
    assert not [p for p in (tmp_path / "broken").iterdir() if p.name.endswith(".tmp")]


def test_local_cluster_workers_keep_the_default_malloc_trim():
    pytest.importorskip("distributed")
    import os

    from checker.study.run import connect_dask

    before = os.environ.get("MALLOC_TRIM_THRESHOLD_")  # Dask would set 65536
    eng = connect_dask("local", 1)
    try:
        seen = eng.client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_"))
    finally:
        eng.close()
    assert seen and all(v == before for v in seen.values())
    # the Ctrl-C noise of Dask's event loop is filtered where tornado logs it
    import logging

    from checker.study.run import _SYNC_NOISE

    assert _SYNC_NOISE in logging.getLogger("tornado.application").filters
