"""Screening speeds (checker.remedies.screening): the bearing remedies' trial values at the
speeds where each result is worst today, every answer confirmed at every speed."""

from __future__ import annotations

import json

import numpy as np
import pytest

from checker import api
from checker.evaluation.ruletable import load_rules
from checker.remedies import solve
from checker.remedies.screening import screenable, screening_speeds
from checker.remedies.solve import find_remedies
from checker.remedies.variants import Evaluator, bind, find
from checker.workbook.loader import read_raw_workbook
from tests.helpers import confirm_failing_answers, example_path

SEL = ["BRG-003", "BRG-004"]
LEVERS = ("bearing-clearance", "oil-supply-temperature")


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    return example_path(tmp_path_factory.mktemp("screen"))


def _setup(i4):
    table = load_rules()
    ev = Evaluator(read_raw_workbook(i4), table, select=SEL)
    nom = api.check(i4, select=SEL, cache=ev.cache)
    return table, ev, nom


def _run(i4, monkeypatch=None, speeds=None):
    """Remedies of BRG-003/004 by clearance and oil temperature; ``speeds``: screening
    speeds forced (``()``: none); returns (results, evaluator, jobs)."""
    table, ev, nom = _setup(i4)
    jobs: list = []
    run = solve._run
    if monkeypatch is not None:
        if speeds is not None:
            monkeypatch.setattr(solve, "screening_speeds", lambda *a: speeds or None)

        def spy(js, *a, **k):
            jobs.extend(js)
            return run(js, *a, **k)

        monkeypatch.setattr(solve, "_run", spy)
    levers = [lv for lv in table.levers if lv.id in LEVERS]
    return find_remedies(nom, ev, levers), ev, jobs


def _answers(out) -> dict:
    return {(rr.rule, rr.item, rm.lever.id): rm.value for rr in out for rm in rr.remedies
            if rm.found}


def test_screening_speeds_hold_each_results_worst_speed(i4):
    _, _, nom = _setup(i4)
    results = [(r.rule, r.item) for r in nom.results if r.status == "fail"]
    assert results
    speeds = screening_speeds(nom, results)
    q = nom.outcome.quantities["bearing.moft_finite"]
    sp = np.asarray(q.coords["speed"])
    assert speeds is not None and 2 <= len(speeds) <= 0.5 * sp.size
    items = list(q.coords["item"])
    for _, item in results:
        for row in np.asarray(q.values)[items.index(item)]:  # per load case
            assert float(sp[np.argmin(row)]) in speeds
    # a joint rule is not judged per speed: no screening
    assert not screenable(next(r for r in load_rules().rules if r.id == "JNT-001"), nom)


def test_values_at_the_screening_speeds_are_those_of_every_speed(i4):
    """The property screening rests on: a bearing variant checked at a few speeds has there,
    bitwise, the film of the check at every speed."""
    table, ev, nom = _setup(i4)
    speeds = screening_speeds(nom, [(r.rule, r.item) for r in nom.results
                                    if r.status == "fail"])
    lv = next(x for x in table.levers if x.id == "bearing-clearance")
    b = bind(ev.base, lv.sheet, lv.columns, lv.unit, ("M2",), lv.where, lv.default)
    ch = b.changes(1.1 * b.nominal[0])
    full = ev.evaluate_variants([ch], select=SEL)[0]
    part = ev.evaluate_variants([ch], select=SEL, speeds=speeds)[0]
    qf = full.outcome.quantities["bearing.moft_finite"]
    qp = part.outcome.quantities["bearing.moft_finite"]
    sp = np.asarray(qf.coords["speed"])
    keep = np.isin(sp, speeds)
    assert np.asarray(qp.coords["speed"]).tolist() == sp[keep].tolist()
    assert np.array_equal(np.asarray(qf.values)[..., keep], np.asarray(qp.values))
    # so its margins are never below those at every speed
    for r in part.results:
        rf = find(full, r.rule, r.item)
        if r.margin is not None:
            assert r.margin >= rf.margin


def test_screened_answers_equal_the_search_at_every_speed(i4, monkeypatch):
    out, ev, jobs = _run(i4, monkeypatch)
    assert any(j.full_res for j in jobs)  # screened and confirmed
    screened = _answers(out)
    with pytest.MonkeyPatch.context() as mp:
        full, _, jobs_full = _run(i4, mp, speeds=())
    assert not any(j.screen for j in jobs_full)
    assert screened == _answers(full)
    assert len(confirm_failing_answers(ev, out)) >= 10
    # the side effects found at the confirmation equal those of the search at every speed
    eff = {(rr.rule, rr.item, rm.lever.id): rm.side_effects for rr in out
           for rm in rr.remedies if rm.found}
    assert eff == {(rr.rule, rr.item, rm.lever.id): rm.side_effects for rr in full
                   for rm in rr.remedies if rm.found}


def test_value_failing_at_every_speed_goes_on_at_every_speed():
    """A value that passes at the screening speeds but not at every speed (the result is
    worst elsewhere there) is not an answer: the job leaves screening and goes on at every
    speed from that point; one that passes at every speed is the answer."""
    from types import SimpleNamespace

    from checker.remedies.solve import Remedy, _advance, _Job

    lv = SimpleNamespace(id="clearance", separable=True, discrete=False)

    def job() -> _Job:
        j = _Job(SimpleNamespace(margin=-0.2), "BRG-003", "M1", lv,
                 SimpleNamespace(cells=set()), Remedy(lv, "Bearings!F3", 30.0, direction=-1),
                 -1, True)
        j.x0, j.xb, j.screen = 30.0, 15.0, True
        return j

    j = job()
    _advance(j, [(28.0, -0.1)])  # screened trial: not yet passing
    nxt = j.queue[0]
    assert 15.0 < nxt < 28.0 and not j.done
    j.queue = []
    _advance(j, [(nxt, 0.0005)])  # passes at the screening speeds, in the window
    assert j.confirm == nxt and j.queue == [nxt] and not j.done
    j.queue = []
    j.full_x.add(repr(nxt))
    _advance(j, [(nxt, -0.04)])  # at every speed it fails
    assert not j.screen and j.confirm is None and not j.done
    assert j.pts == [(nxt, -0.04)] and j.queue and j.queue[0] < nxt  # on beyond it
    x2 = j.queue[0]
    j.queue = []
    j.full_x.add(repr(x2))
    _advance(j, [(x2, 0.0004)])  # at every speed, in the window: the answer at once
    assert j.done and j.remedy.found and j.remedy.value == x2 and j.remedy.margin == 0.0004

    k = job()  # confirmed at every speed: the answer
    _advance(k, [(25.0, 0.0002)])
    assert k.confirm == 25.0
    k.queue = []
    k.full_x.add(repr(25.0))
    _advance(k, [(25.0, 0.0002)])
    assert k.done and k.remedy.found and k.remedy.value == 25.0


def test_outputs_name_the_screening_speeds(i4):
    """The JSON, the text output and the report's remedies section say at which speeds the
    bearing results were searched and that each answer was checked at every speed."""
    from checker.outputs.formats import to_json
    from checker.remedies import attach, to_text
    from checker.report.section_remedies import remedies_section

    cache: dict = {}
    res = api.check(i4, select=["BRG-003"], cache=cache)
    attach(res, remedies=True, cache=cache, select=["BRG-003"], workers=1,
           levers_file=None)
    sp = res.remedies["screening_speeds"]
    assert sp and len(sp) < 61
    doc = json.loads(to_json(res))
    rpm = doc["remedies"]["screening_speeds_rpm"]
    assert rpm == [float(f"{x * 30.0 / np.pi:.6g}") for x in sp] and 1000.0 in rpm
    assert "each answer checked at every speed" in to_text(res)
    text = " ".join(b.get("text", "") for b in remedies_section(res)["blocks"]
                    if b.get("type") == "text")
    assert f"{len(sp)} swept speeds where they are worst today" in text
    assert "checked at every speed" in text
