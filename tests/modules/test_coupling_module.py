"""Flexible coupling and driven machine in the TV model (module ``coupling``, rules CPL-).

The I6 example with a generator behind its flywheel through a flexible coupling (catalogue
values of a VULKAN RATO-DS 2200, rubber quality 5: C_Tdyn 262.5 kNm/rad, psi 1.13, T_KN 50 kNm,
T_KW 15 kNm, P_KV 0.62 kW; the generator's inertia an assumption of the test). Checked:
the coupling element in the solved model has the catalogue stiffness times the factor read
at the rubber's temperature (linear between the table's rows, by hand); its heat against
P_KV equals the hand formula psi f T^2 / (2 C) summed over the orders of the element's own
torque; the ratios are the quantities over the ratings; input errors name their cells.
"""

from __future__ import annotations

import numpy as np
import pytest

from checker import api
from checker.errors import InputErrors
from checker.workbook.example import write_workbook
from checker.workbook.example_i6 import i6_content

C_TDYN, PSI, T_KN, T_KW, P_KV = 262.5e3, 1.13, 50e3, 15e3, 620.0
TABLE = [(20.0, 1.0, 1.0, 1.0), (60.0, 0.7, 0.7, 1.4), (100.0, 0.5, 0.6, 1.8)]
J_GEN = 4.0  # kg m^2, generator rotor (test assumption)


def _content(temperature: float | None = 50.0, coupling_stiffness=None, table=True):
    c = i6_content(damper_ring=True)
    cols, rows = c["TVModel"]
    cols = list(cols) + [("element to next", "-")]
    rows = [list(r) + [None] for r in rows]
    fw = rows[-1]
    fw[cols.index(("stiffness to next", "N m/rad"))] = coupling_stiffness
    fw[-1] = "flexible coupling"
    gen = [None] * len(cols)
    gen[0], gen[1], gen[3] = "Generator", "generator", J_GEN
    rows.append(gen)
    c["TVModel"] = (cols, rows)
    params = [("Coupling designation", "RATO-DS 2200 (test)", "-", ""),
              ("Nominal torque T_KN", T_KN / 1e3, "kN m", ""),
              ("Permissible vibratory torque T_KW", T_KW / 1e3, "kN m", ""),
              ("Permissible damping power P_KV", P_KV / 1e3, "kW", ""),
              ("Dynamic torsional stiffness C_Tdyn", C_TDYN / 1e3, "kN m/rad", ""),
              ("Relative damping psi", PSI, "-", "")]
    if temperature is not None:
        params.append(("Rubber temperature", temperature, "°C", ""))
    c["Coupling"] = params
    if table:
        c["CouplingTemperature"] = (
            [("temperature", "°C"), ("stiffness factor", "-"), ("damping factor", "-"),
             ("temperature factor", "-")], [list(r) for r in TABLE])
    return c


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    p = tmp_path_factory.mktemp("cpl") / "genset.xlsx"
    write_workbook(p, _content())
    return api.check(p)


def test_coupling_element_has_the_catalogue_values_at_temperature(result):
    q = result.outcome.quantities
    model = q["tv.nose_amplitude"].detail.model
    e = model.n_elements - 1  # flywheel -> generator
    # 50 degC: 3/4 of the way from 20 to 60 degC
    k_fac, d_fac = 1.0 - 0.75 * 0.3, 1.0 - 0.75 * 0.3
    assert model.stiffness[e] == pytest.approx(C_TDYN * k_fac, rel=1e-12)
    assert model.loss_factor[e] == pytest.approx(PSI * d_fac / (2 * np.pi), rel=1e-12)
    assert model.inertia[-1] == J_GEN
    st = q["coupling.power"].detail.state
    assert st.temperature_factor == pytest.approx(1.0 + 0.75 * 0.4, rel=1e-12)


def test_coupling_heat_by_hand_against_p_kv(result):
    q = result.outcome.quantities
    el = q["tv.element_torque"]
    e = len(el.coords["item"]) - 1
    d = el.detail
    torque = np.abs(d.coeffs[e])  # (C, S, O) elastic + damping torque amplitude per order
    c = C_TDYN * 0.775
    psi = PSI * 0.775
    eta = psi / (2 * np.pi)
    f = d.speeds[:, None] * d.orders / (2 * np.pi)  # (S, O) [Hz]
    t_el = torque / np.hypot(1.0, eta)  # the elastic part C |dphi| of |k* dphi|
    hand = (psi * f * t_el**2 / (2 * c)).sum(-1)  # (C, S) [W]
    power = q["coupling.power"].values[0]
    np.testing.assert_allclose(power, hand, rtol=1e-9)
    ratio = q["coupling.heat_ratio"].values[0]
    np.testing.assert_allclose(ratio, hand * 1.3 / P_KV, rtol=1e-9)
    mean = q["coupling.mean_torque_ratio"].values[0]
    np.testing.assert_allclose(mean, np.abs(d.mean[e]) / T_KN, rtol=1e-12)


def test_coupling_rules_evaluate(result):
    got = {r.rule: r.status for r in result.results if r.rule.startswith("CPL-")}
    assert set(got) == {"CPL-001", "CPL-002", "CPL-003"}
    assert all(s in ("pass", "fail") for s in got.values())


def test_coupling_without_its_catalogue_values_is_not_evaluated(tmp_path):
    c = _content()
    c["Coupling"] = [r for r in c["Coupling"] if not r[0].startswith("Permissible damping")]
    p = tmp_path / "missing.xlsx"
    write_workbook(p, c)
    res = api.check(p)
    tv = [r for r in res.results if r.rule.startswith(("CPL-", "TV-"))]
    assert tv and all(r.status == "not_evaluated" for r in tv if r.rule.startswith("CPL"))
    assert any("P_KV" in m for r in tv for m in r.missing)


def test_typed_stiffness_on_a_coupling_row_is_an_input_error(tmp_path):
    p = tmp_path / "typed.xlsx"
    write_workbook(p, _content(coupling_stiffness=1.0e5))
    with pytest.raises(InputErrors) as err:
        api.check(p)
    text = str(err.value)
    assert "TVModel!" in text and "flexible coupling's stiffness" in text


def test_table_without_temperature_is_not_evaluated(tmp_path):
    p = tmp_path / "notemp.xlsx"
    write_workbook(p, _content(temperature=None))
    res = api.check(p)
    cpl = [r for r in res.results if r.rule.startswith("CPL-")]
    assert cpl and all(r.status == "not_evaluated" for r in cpl)
    assert any("Rubber temperature" in m for r in cpl for m in r.missing)
