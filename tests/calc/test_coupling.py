"""Flexible coupling (checker.calc.coupling): heat against P_KV by hand, DIN 740-2 factors.

Hand numbers: VULKAN RATO-DS series 2200, rubber quality 5 (data sheet: C_Tdyn 262.5 kNm/rad
nominal, psi 1.13, T_KW 15 kNm, P_KV 0.62 kW); the heat of a hysteretic element per cycle is
psi times the elastic work C phi^2 / 2 (the definition of the relative damping, DIN 740-2).
Tolerances: round-off (1e-12), the hand numbers to their printed digits.
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import coupling as cp
from checker.calc import torsional as tv

C_TDYN = 262.5e3  # N m/rad
PSI = 1.13
P_KV = 620.0  # W
T_KW = 15.0e3  # N m


def test_heat_of_one_order_by_hand():
    # 3 kNm vibratory torque at 15 Hz: P = psi f T^2 / (2 C) = 1.13 * 15 * 9e6 / 525e3
    p = cp.damping_power(3000.0 / C_TDYN, 2 * np.pi * 15.0, C_TDYN, PSI)
    assert float(p) == pytest.approx(290.571428571, rel=1e-9)
    assert float(p) / P_KV == pytest.approx(0.46866, abs=5e-6)  # 46.9 % of P_KV
    # warm rubber (S_t = 1.4 on the load): 406.8 W against 620 W
    assert float(p) * 1.4 == pytest.approx(406.8, abs=0.05)


def test_heat_equals_work_of_the_hysteresis_loop():
    # the time integral of torque x twist rate over a cycle (two orders), divided by the
    # cycle time, against the sum of the orders' heat
    orders = np.array([0.5, 3.0])
    speed = 2 * np.pi * 1500 / 60
    dphi = np.array([0.004 + 0.002j, -0.003j])
    eta = float(cp.loss_factor(PSI))
    n = 200000
    th = np.arange(n) * 4 * np.pi / n
    e = np.exp(1j * np.outer(th, orders))
    phi = (e * dphi).real.sum(-1)
    torque = (e * dphi * C_TDYN * (1 + 1j * eta)).real.sum(-1)
    rate = (e * dphi * 1j * orders * speed).real.sum(-1)
    work = np.sum(torque * rate) * (4 * np.pi / n) / speed  # J per 720 deg cycle
    power = work / (4 * np.pi / speed)
    p = cp.damping_power(dphi, orders * speed, C_TDYN, PSI).sum()
    assert p == pytest.approx(power, rel=1e-9)
    assert np.ptp(phi) > 0


def test_coupling_in_a_two_mass_model_heat_by_hand():
    # engine (J1) - coupling - generator (J2), order torque F on the engine: the twist is
    # F J2 / (k* (J1 + J2) - W^2 J1 J2) (closed form), its heat psi f T^2/(2 C)
    j1, j2 = 40.0, 55.0
    eta = float(cp.loss_factor(PSI))
    model = tv.TorsionalModel(inertia=[j1, j2], stiffness=[C_TDYN], loss_factor=[eta])
    speed = 2 * np.pi * 750 / 60
    f = 8000.0 + 0j
    res = tv.forced_response(model, [speed], [1.5], np.array([[[f], [0]]]))
    om = 1.5 * speed
    kstar = C_TDYN * (1 + 1j * eta)
    twist = f * j2 / (kstar * (j1 + j2) - om**2 * j1 * j2)
    got = res.theta[0, 0, 0] - res.theta[0, 1, 0]
    assert got == pytest.approx(twist, rel=1e-12)
    t_el = C_TDYN * abs(twist)
    hand = PSI * (om / (2 * np.pi)) * t_el**2 / (2 * C_TDYN)
    assert float(cp.damping_power(got, om, C_TDYN, PSI)) == pytest.approx(hand, rel=1e-12)


def test_frequency_factor_din_740_2():
    assert cp.frequency_factor([5.0, 10.0, 40.0]) == pytest.approx([1.0, 1.0, 2.0])
    ratio, f = cp.vibratory_torque_ratio(6000.0, [[1000.0, 5500.0]], [[12.0, 40.0]], T_KW, 1.2)
    assert f[0] == 40.0
    assert ratio[0] == pytest.approx(6000 * 1.2 * 2.0 / 15000)


def test_table_factor_interpolates_and_holds():
    temps = [30.0, 60.0, 90.0]
    fac = [1.0, 0.8, 0.6]
    assert cp.table_factor([20.0, 45.0, 100.0], temps, fac) == pytest.approx([1.0, 0.9, 0.6])
    assert cp.table_factor(50.0, [], []) == pytest.approx(1.0)
    with pytest.raises(ValueError):
        cp.table_factor(50.0, [60.0, 30.0], [1.0, 0.8])
