"""A study on the crank's geometry (sheet Crank): one pin diameter moves every analysis it
touches (issue 33): the big-end film load (Bearings take the pin from Crank), the balance (the
crank masses derived from the geometry), the torsional model (derived throw inertias and
stiffnesses) and the fatigue check (M53 on the pin diameter)."""

from __future__ import annotations

import pytest

from checker.study.run import run_study
from checker.study.spec import load_study
from checker.workbook.example import write_workbook
from checker.workbook.example_data import load_example

STUDY = """
[study]
name = "pin diameter"
design = "one-at-a-time"
select = ["BAL-005", "TV-001", "BRG-001", "FAT-002"]

[[parameter]]
name = "pin diameter"
sheet = "Crank"
row = "all"
column = "pin diameter"
unit = "mm"
values = [53.32, 57]
"""


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    d = tmp_path_factory.mktemp("crankstudy")
    c = load_example("v8")  # its torsional model is derived from sheet Crank
    c["CrankMass"] = (c["CrankMass"][0], [])  # and here its crank masses too
    wb = d / "v8.xlsx"
    write_workbook(wb, c)
    st = d / "pin.toml"
    st.write_text(STUDY, encoding="utf-8")
    return run_study(load_study(st), wb, d / "out", workers=1)


def _values(rec) -> dict:
    return {(r["rule"], r["item"]): r["value"] for r in rec["results"]}


def test_pin_diameter_moves_every_analysis_it_touches(run):
    base, same, bigger = (_values(r) for r in run.records)
    assert [r["status"] for r in run.records] == ["checked"] * 3
    assert same == base  # 53.32 mm is today's pin

    def moved(rule: str) -> list:
        return [k for k in base if k[0] == rule and base[k] is not None
                and bigger[k] is not None and abs(bigger[k] / base[k] - 1) > 1e-3]

    # balance: a heavier pin at the crank radius lowers the counterweights' share
    assert moved("BAL-005") and all(bigger[k] < base[k] for k in moved("BAL-005"))
    # film load: the big ends' specific load F / (D L) falls with the diameter
    be = [k for k in base if k[0] == "BRG-001" and k[1].startswith("BE")]
    assert be and all(bigger[k] < base[k] for k in be)
    assert bigger[be[0]] / base[be[0]] == pytest.approx(53.32 / 57, rel=0.02)
    # the torsional model (derived throw inertia and stiffness) and the pin fillet fatigue
    assert moved("TV-001")
    assert moved("FAT-002")
