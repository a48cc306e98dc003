"""Misfire response (checker.calc.misfire) against closed forms.

* Two- and three-mass chains: the forced response to one cylinder's order torque has the
  closed form of the inverse of a 2x2 / tridiagonal 3x3 dynamic stiffness (cofactors,
  e.g. Den Hartog, *Mechanical Vibrations*, 4th ed., 1956, ch. 2 and 4); the misfire response
  is that closed form with the misfiring cylinder's motored torque. Tolerance 1e-10 relative
  (round-off of a 3x3 solve).
* The motored trace of a purely polytropic compression is the polytrope itself (Heywood 1988,
  sec. 9.2): round-off.
* A misfire of an evenly firing in-line six excites the half orders, which cancel in normal
  firing (Ker Wilson, vol. 2, ch. 19: the vector sum of order 0.5 of six cylinders 120 deg
  apart is zero).
"""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import excitation as exc
from checker.calc import misfire as mf
from checker.calc import pressure as pr
from checker.calc import torsional as tv
from checker.calc.kinematics import cycle_grid

GEO = dict(bore=0.13, crank_radius=0.08, rod_length=0.26, compression_ratio=15.0)
TH = cycle_grid(np.radians(1.0))


def _cylinder_coeffs(peak: float, speed: float):
    """Order coefficients of one cylinder's gas torque, firing and motored."""
    tr = pr.synthesize_trace(TH, peak, intake_pressure=2.5e5, **GEO)
    vol = pr.cylinder_volume(TH, GEO["bore"], GEO["crank_radius"], GEO["rod_length"],
                             GEO["compression_ratio"])
    mot = mf.motored_trace(TH, tr.pressure, vol)
    torques = exc.gas_torque(TH, np.stack([tr.pressure, mot.pressure]), GEO["bore"],
                             GEO["crank_radius"], GEO["rod_length"], 1e5)
    return exc.torque_harmonics(torques, 12.0)  # orders, (2, O)


def test_motored_trace_of_a_polytrope_is_the_polytrope():
    # a synthesized trace whose peak equals its motored peak has no heat release
    tr0 = pr.synthesize_trace(TH, 1.0e5, intake_pressure=2.0e5, **GEO)  # throttled motored
    assert bool(tr0.motored)
    vol = pr.cylinder_volume(TH, GEO["bore"], GEO["crank_radius"], GEO["rod_length"],
                             GEO["compression_ratio"])
    fired = pr.synthesize_trace(TH, 140e5, intake_pressure=float(tr0.intake_pressure), **GEO)
    mot = mf.motored_trace(TH, fired.pressure, vol)
    assert float(mot.exponent) == pytest.approx(1.32, rel=1e-12)
    psi = np.mod(TH + 2 * np.pi, 4 * np.pi) - 2 * np.pi
    closed = (psi >= np.radians(-140)) & (psi <= np.radians(130))  # IVC..EVO of the synthesis
    np.testing.assert_allclose(mot.pressure[closed], tr0.pressure[closed], rtol=1e-9)
    # outside the compression and expansion strokes: the firing trace (gas exchange)
    out = np.abs(psi) > np.pi
    np.testing.assert_array_equal(mot.pressure[out], fired.pressure[out])


def test_motored_trace_rejects_combustion_in_the_window():
    tr = pr.synthesize_trace(TH, 140e5, combustion_start=np.radians(-90), **GEO)
    vol = pr.cylinder_volume(TH, GEO["bore"], GEO["crank_radius"], GEO["rod_length"],
                             GEO["compression_ratio"])
    with pytest.raises(ValueError, match="no clean compression line"):
        mf.motored_trace(TH, tr.pressure, vol)


def _two_mass_closed_form(j1, j2, kstar, om, force):
    """Element torque of a 2-mass chain, force on mass 1: T = k* J2 F / (k*(J1+J2) - W^2 J1 J2)."""
    return kstar * j2 * force / (kstar * (j1 + j2) - om**2 * j1 * j2)


def test_two_mass_misfire_matches_closed_form():
    j1, j2, k, eta, c = 0.8, 12.0, 2.0e6, 0.02, 40.0  # engine mass + flywheel/generator
    model = tv.TorsionalModel(inertia=[j1, j2], stiffness=[k], loss_factor=[eta],
                              damping_rel=[c])
    orders, cc = _cylinder_coeffs(160e5, 150.0)
    speeds = np.array([60.0, 100.0, 157.0])
    fire = np.broadcast_to(cc[0], (speeds.size, 1, orders.size))
    delta = mf.misfire_excitation(cc[0], cc[1], orders, [0.0])
    delta = np.broadcast_to(delta, (speeds.size, 1, orders.size))
    res = mf.misfire_response(model, speeds, orders, fire, delta, [0])
    om = speeds[:, None] * orders
    kstar = k * (1 + 1j * eta) + 1j * om * c
    np.testing.assert_allclose(res.torque_normal[:, 0], _two_mass_closed_form(
        j1, j2, kstar, om, cc[0]), rtol=1e-10)
    np.testing.assert_allclose(res.torque[:, 0, 0], _two_mass_closed_form(
        j1, j2, kstar, om, cc[1]), rtol=1e-10)  # the motored cylinder's torque


def test_three_mass_misfire_matches_closed_form():
    # two cylinders (360 deg apart, a twin) and a flywheel; cylinder 2 misfires
    j = np.array([0.5, 0.5, 6.0])
    k1, k2 = 3.0e6, 1.5e6
    d = np.array([3.0, 3.0, 0.0])  # absolute damping at the cylinders
    model = tv.TorsionalModel(inertia=j, stiffness=[k1, k2], damping_abs=d, loss_factor=0.01)
    orders, cc = _cylinder_coeffs(150e5, 200.0)
    phi = np.array([0.0, 2 * np.pi])
    speeds = np.array([80.0, 140.0, 210.0])
    fire = np.broadcast_to(exc.phase_cylinders(cc[0], orders, phi), (speeds.size, 2, orders.size))
    delta = np.broadcast_to(mf.misfire_excitation(cc[0], cc[1], orders, phi),
                            (speeds.size, 2, orders.size))
    res = mf.misfire_response(model, speeds, orders, fire, delta, [0, 1])
    om = speeds[:, None] * orders
    z1, z2 = k1 * (1 + 0.01j), k2 * (1 + 0.01j)
    a1 = z1 - om**2 * j[0] + 1j * om * d[0]
    a2 = z1 + z2 - om**2 * j[1] + 1j * om * d[1]
    a3 = z2 - om**2 * j[2]
    det = a1 * (a2 * a3 - z2**2) - z1**2 * a3
    f1 = cc[0] * np.exp(-1j * orders * phi[0])
    f2 = cc[1] * np.exp(-1j * orders * phi[1])  # cylinder 2 motored
    # cofactors of the symmetric tridiagonal D: theta = adj(D) F / det
    th1 = ((a2 * a3 - z2**2) * f1 + z1 * a3 * f2) / det
    th2 = (z1 * a3 * f1 + a1 * a3 * f2) / det
    th3 = (z1 * z2 * f1 + a1 * z2 * f2) / det
    np.testing.assert_allclose(res.theta[:, 1, 0], th1, rtol=1e-10)
    np.testing.assert_allclose(res.theta[:, 1, 1], th2, rtol=1e-10)
    np.testing.assert_allclose(res.theta[:, 1, 2], th3, rtol=1e-10)
    np.testing.assert_allclose(res.torque[:, 1, 1], z2 * (th2 - th3), rtol=1e-10)
    # normal firing is the forced response of checker.calc.torsional
    ref = tv.forced_response(model, speeds, orders, tv.station_excitation(fire, [0, 1], 3))
    np.testing.assert_allclose(res.theta_normal, ref.theta, rtol=1e-10)


def test_misfire_excites_the_half_orders_an_even_six_cancels():
    n = 8  # six cylinders, a damper-less crank and a flywheel on stations 0..7
    j = np.r_[0.05, np.full(6, 0.4), 8.0]
    model = tv.TorsionalModel(inertia=j, stiffness=np.full(n - 1, 1.5e6), loss_factor=0.03,
                              damping_abs=np.r_[0, np.full(6, 2.0), 0])
    orders, cc = _cylinder_coeffs(180e5, 150.0)
    # firing order 1-5-3-6-2-4: firing angles of cylinders 1..6
    phi = np.radians([0, 480, 240, 600, 120, 360])
    speeds = np.array([100.0, 150.0])
    fire = np.broadcast_to(exc.phase_cylinders(cc[0], orders, phi), (2, 6, orders.size))
    delta = np.broadcast_to(mf.misfire_excitation(cc[0], cc[1], orders, phi), (2, 6, orders.size))
    half = orders == 0.5
    # the net (rigid-body) torque of order 0.5 cancels in normal firing, not with a misfire
    net = np.abs(fire[0, :, half].sum(axis=-1))
    assert net < 1e-12 * np.abs(cc[0][half])
    for i in range(6):
        mis = fire[0].copy()
        mis[i] += delta[0, i]
        assert np.abs(mis[:, half].sum()) == pytest.approx(np.abs(cc[1] - cc[0])[half][0],
                                                             rel=1e-12)
    res = mf.misfire_response(model, speeds, orders, fire, delta, np.arange(1, 7))
    # the flywheel element's order 0.5 below the first mode: the net torque, which the
    # misfire adds (normal firing leaves only the small elastic share of the minor order)
    normal = np.abs(res.torque_normal[:, -1, half]).max()
    misfire = np.abs(res.torque[:, :, -1, half]).min()
    assert misfire > 10 * normal
