"""Geometry levers (issue 33 item 5): a study or a remedy that moves the crank's dimensions
moves every analysis they touch, consistently.

The V8 example (without its typed CrankMass sheet) runs on the model derived from its
geometry (sheet Crank), so a larger pin
diameter must: raise each throw's mass, inertia and torsional stiffness (closed-form mass
properties, the throw stiffness model), change the torsional frequencies, lower the
counterweight balance ratio (more rotating mass on the pin side of each throw), lower the big
ends' specific load (same load on a larger diameter) and raise the pin fillets' fatigue safety
factor (larger section moduli, more overlap: IACS UR M53).
"""

from __future__ import annotations

import numpy as np
import openpyxl
import pytest

from checker import api
from checker.workbook.example import write_workbook
from checker.workbook.example_v8 import v8_content


def _set_crank(path, column: str, value: float, out):
    wb = openpyxl.load_workbook(path)
    ws = wb["Crank"]
    head = [c.value for c in ws[1]]
    col = head.index(column) + 1
    for r in range(3, ws.max_row + 1):
        if str(ws.cell(r, 1).value).strip().lower() == "all":
            ws.cell(r, col).value = value
    wb.save(out)
    return out


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("levers")
    base = tmp / "v8.xlsx"
    content = dict(v8_content())
    content.pop("CrankMass")  # the masses derived from the geometry too, not typed
    write_workbook(base, content)
    wb = openpyxl.load_workbook(base)
    ws = wb["Crank"]
    head = [c.value for c in ws[1]]
    row = next(r for r in range(3, ws.max_row + 1)
               if str(ws.cell(r, 1).value).strip().lower() == "all")
    pin = float(ws.cell(row, head.index("pin diameter") + 1).value)
    bigger = _set_crank(base, "pin diameter", pin * 1.08, tmp / "v8-pin.xlsx")
    return api.check(base), api.check(bigger)


def _q(res, name):
    return res.outcome.quantities[name]


def test_a_larger_pin_moves_every_analysis_consistently(pair):
    a, b = pair
    for name in ("crank.throw_mass", "crank.throw_inertia", "crank.throw_stiffness"):
        assert np.all(_q(b, name).values > _q(a, name).values), name
    fa, fb = _q(a, "tv.natural_frequency").values, _q(b, "tv.natural_frequency").values
    assert not np.allclose(fa, fb, rtol=1e-4)
    ra, rb = _q(a, "balance.balance_ratio").values, _q(b, "balance.balance_ratio").values
    assert np.nanmax(rb) < np.nanmax(ra)
    sa, sb = _q(a, "bearing.peak_specific_load"), _q(b, "bearing.peak_specific_load")
    bigs = [i for i, n in enumerate(sa.coords["item"]) if sa.item_attrs[n]["type"] == "big end"]
    assert np.all(np.nanmax(sb.values[bigs], axis=-1) < np.nanmax(sa.values[bigs], axis=-1))
    ga, gb = _q(a, "fatigue.goodman_sf"), _q(b, "fatigue.goodman_sf")
    pins = [i for i, n in enumerate(ga.coords["item"]) if n.startswith("pin") and "fillet" in n]
    assert np.nanmin(gb.values[pins]) > np.nanmin(ga.values[pins])


def test_remedies_offer_the_crank_dimensions(tmp_path):
    """What it takes to pass FAT-002 on the I4 (its crank by geometry) includes the crank's
    own dimensions, each answer checked at every rule whose status can change."""
    from checker import remedies
    from checker.workbook.example import example_content

    p = tmp_path / "i4.xlsx"
    write_workbook(p, example_content())
    res = api.check(p, select=["FAT-002"])
    assert res.engine.crank is not None
    remedies.attach(res, remedies=True)
    out = res.to_dict(timings=False)["remedies"]["results"]
    offered = {lv["lever"]: lv for r in out for lv in r["levers"]}
    for lid in ("crank-pin-diameter", "crank-journal-diameter", "crank-web-thickness",
                "crank-web-width"):
        assert lid in offered, lid
        assert offered[lid]["input"].startswith("Crank!")
    found = [lv for r in out for lv in r["levers"]
             if lv["lever"].startswith("crank-") and lv["found"]]
    assert found and all(lv["value"] is not None for lv in found)


def test_diameter_tolerance_at_the_corners(tmp_path):
    """A Tolerances row on the crank's pin diameter (sheet Crank) is a corner like any other:
    the worst corner of the pin fillets names it."""
    import subprocess
    import sys

    p = tmp_path / "v8.xlsx"
    write_workbook(p, v8_content())
    wb = openpyxl.load_workbook(p)
    ws = wb["Tolerances"]
    r = ws.max_row + 1
    for c, v in enumerate(["Crank", "all", "pin diameter", -0.1, 0.1, "% of nominal",
                           "test: pin diameter tolerance"], 1):
        ws.cell(r, c).value = v
    wb.save(p)
    out = subprocess.run([sys.executable, "-m", "checker", "check", str(p), "--corners",
                          "--select", "FAT-001"], capture_output=True, text=True)
    assert out.returncode in (0, 1), out.stderr
    assert "Crank pin diameter (all)" in out.stdout
