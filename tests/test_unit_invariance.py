"""The same engine entered in other units gives the same results to 1e-9 relative (issue 7):
inch, lbf, psi, lb in^2 ... against the example's mm, N, bar, kg mm^2."""

from __future__ import annotations

import copy
import json

import pytest

from checker import api
from checker.workbook.example import example_content, write_workbook
from checker.workbook.units import Q_

# unit in the example -> (replacement unit, converter of the value)
_PINT = {
    "mm": "in", "kg": "lb", "bar": "psi", "N m": "lbf*ft", "N/mm^2": "ksi", "MPa": "psi",
    "kg mm^2": "lb*in**2", "kg m^2": "lb*ft**2", "N m/rad": "lbf*ft/rad",
    "N m s/rad": "lbf*ft*s/rad", "W/cm^3": "W/in**3",
}
_SPECIAL = {
    "rpm": ("Hz", lambda v: v / 60.0),  # shaft speed: 3000 rpm = 50 rev/s
    "°C": ("°F", lambda v: v * 9.0 / 5.0 + 32.0),
    "K": ("delta_degF", lambda v: v * 9.0 / 5.0),  # a temperature rise
    "bar(g)": ("psig", lambda v: Q_(v, "bar").to("psi").magnitude),
    "deg": ("rad", lambda v: v * 3.141592653589793 / 180.0),
}


def _convert(value, unit):
    if not isinstance(value, (int, float)) or isinstance(value, bool) or unit is None:
        return value, unit
    if unit in _SPECIAL:
        new, f = _SPECIAL[unit]
        return f(float(value)), new
    if unit in _PINT:
        new = _PINT[unit]
        return Q_(float(value), unit).to(new).magnitude, new
    return value, unit


def imperial_content():
    content = copy.deepcopy(example_content())
    for name, body in content.items():
        if name == "Notes":
            continue
        if isinstance(body, list):
            content[name] = [(lab, *_convert(v, u), note) for lab, v, u, note in body]
        else:
            cols, rows = body
            new_cols = list(cols)
            for j, (h, u) in enumerate(cols):
                conv = [_convert(r[j], u) for r in rows]
                new_unit = next((c[1] for c in conv if c[1] != u), _convert(1.0, u)[1])
                new_cols[j] = (h, new_unit)
                for r, c in zip(rows, conv):
                    r[j] = c[0]
            content[name] = (new_cols, rows)
    return content


def _numbers(res):
    out = {}
    for r in res.to_dict(timings=False)["results"]:
        out[(r["rule"], r["item"])] = (r["status"], r["value"], r["case"])
    return out


@pytest.mark.parametrize("select", [None])
def test_imperial_units_give_identical_results(tmp_path, select):
    si, imp = tmp_path / "si.xlsx", tmp_path / "imperial.xlsx"
    write_workbook(si, example_content())
    write_workbook(imp, imperial_content())
    a, b = api.check(si, select=select), api.check(imp, select=select)
    ra, rb = _numbers(a), _numbers(b)
    assert ra.keys() == rb.keys()
    for k in ra:
        sa, va, ca = ra[k]
        sb, vb, cb = rb[k]
        assert sa == sb and ca == cb, k
        if va is not None:
            assert vb == pytest.approx(va, rel=1e-9), k
    # the raw quantities too (JSON values are rounded to 6 digits)
    import numpy as np

    for name, q in a.outcome.quantities.items():
        # round-off zeros (e.g. the free moments of an inline 4, ~1e-13 N m) are compared
        # against the quantity's own scale, everything else to 1e-9 relative
        finite = np.abs(q.values[np.isfinite(q.values)])
        scale = float(finite.max()) if finite.size else 0.0
        other = b.outcome.quantities[name].values
        if 0.0 < scale < 1e-9:  # zero to round-off in both (free moments of an I4)
            assert np.nanmax(np.abs(other)) < 1e-9, name
            continue
        np.testing.assert_allclose(other, q.values, rtol=1e-9, atol=1e-12 * scale,
                                   equal_nan=True, err_msg=name)


def test_imperial_workbook_really_uses_other_units():
    c = imperial_content()
    units = {u for _, _, u, _ in c["Engine"]} | {u for _, u in c["Bearings"][0]}
    assert {"in", "lb", "Hz"} <= units and "mm" not in units
    assert json.dumps(c["Oil"], default=str, ensure_ascii=False).count("°F") == 1
