"""Tests for checker.calc.crank_forces (big-end loads, torque, main bearing loads)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.crank_forces import (
    Vector2,
    block_to_crank,
    crank_to_block,
    crankpin_force,
    cylinder_loads,
    main_bearing_loads,
    rod_mass_split,
    throw_angles,
)
from checker.calc.kinematics import cycle_grid
from checker.calc.pressure import (
    cylinder_volume,
    indicated_mean_effective_pressure,
    swept_volume,
    synthesize_trace,
)

MM, BAR, DEG, RPM = 1e-3, 1e5, np.pi / 180, np.pi / 30
# seed 000 example engine
BORE, R, L = 86.0 * MM, 47.3 * MM, 145.7 * MM
M_PISTON, M_ROD, L_G, I_ROD = 0.4955, 0.597, 35.73 * MM, 2128e-9
FIRING_I4 = np.array([0.0, 540.0, 180.0, 360.0]) * DEG  # 1-3-4-2, cylinders 1..4
P_CC = 1.0e5
ROD = dict(
    bore=BORE, crank_radius=R, rod_length=L, piston_mass=M_PISTON, rod_mass=M_ROD,
    rod_cg_from_big_end=L_G, rod_inertia=I_ROD, crankcase_pressure=P_CC,
)


def _single(theta, omega, p, **kw):
    """One cylinder firing at theta = 0; p shape (..., N)."""
    args = {**ROD, "firing_angle": np.array([0.0]), **kw}
    return cylinder_loads(theta, omega, np.asarray(p)[..., None, :], **args)


def _linkage(phi, e):
    """Independent vector construction (cylinder frame): crank pin B, piston pin P."""
    b = np.stack([R * np.sin(phi), R * np.cos(phi)])
    p_c = b[1] + np.sqrt(L**2 - (e - b[0]) ** 2)
    p = np.stack([np.full_like(phi, e), p_c])
    return b, p


def test_rod_mass_split_seed_values():
    # Seed 000: reciprocating mass 0.6419 kg = piston 0.4955 + small-end share (VALDYN table);
    # seed 004: m_a = m x2/l, J_0 = J - m x1 x2 (so dI = -J_0). Tolerance 1e-4 kg (4 digits).
    m_a, m_b, d_i = rod_mass_split(M_ROD, L, L_G, I_ROD)
    np.testing.assert_allclose(M_PISTON + m_a, 0.6419, atol=1e-4)
    np.testing.assert_allclose(m_a + m_b, M_ROD, rtol=1e-15)
    np.testing.assert_allclose(d_i, M_ROD * L_G * (L - L_G) - I_ROD, rtol=1e-15)
    assert d_i > 0


def test_motored_big_end_load_at_tdc_closed_form():
    # Closed form (seed 004 "Dynamics"; brief): without gas force, zero offsets, at TDC the
    # big-end load is m_rec r w^2 (1 + lam) + m_b r w^2 along the cylinder axis; the correction
    # couple vanishes at TDC (d2beta = 0). Exact up to rounding: rtol 1e-12.
    th = cycle_grid(1.0 * DEG)
    w = np.array([1000.0, 4000.0, 7000.0]) * RPM
    p = np.full((3, th.size), P_CC)  # no net gas force
    res = _single(th, w, p)
    m_a, m_b, _ = rod_mass_split(M_ROD, L, L_G, I_ROD)
    lam = R / L
    ref = ((M_PISTON + m_a) * (1 + lam) + m_b) * R * w**2
    be = res.big_end_block
    np.testing.assert_allclose(be.magnitude[:, 0, 0], ref, rtol=1e-12)
    # direction: the crank pin pulls the rod toward the crank (block -y)
    np.testing.assert_allclose(be.y[:, 0, 0], -ref, rtol=1e-12)
    np.testing.assert_allclose(be.x[:, 0, 0], 0.0, atol=1e-9 * ref.max())
    # 720 deg later / at gas-exchange TDC (360 deg) the same
    np.testing.assert_allclose(be.magnitude[:, 0, 360], ref, rtol=1e-12)


def test_single_cylinder_gas_torque_closed_form():
    # torsion.md sec. 3.1: T = p A r sin(t) (1 + lam cos(t)/sqrt(1 - lam^2 sin^2 t)), zero
    # offsets; masses and speed zero so only the gas acts. Exact: rtol 1e-12 of the peak.
    th = cycle_grid(0.5 * DEG)
    p = 1e5 + 50e5 * np.exp(-(((th - 2 * np.pi) / 2.0) ** 2))  # arbitrary positive trace
    res = _single(th, 0.0, p, piston_mass=0.0, rod_mass=0.0, rod_inertia=0.0)
    lam = R / L
    area = np.pi / 4 * BORE**2
    ref = (p - P_CC) * area * R * np.sin(th) * (
        1 + lam * np.cos(th) / np.sqrt(1 - lam**2 * np.sin(th) ** 2)
    )
    np.testing.assert_allclose(res.torque[0], ref, atol=1e-12 * np.abs(ref).max())
    # equivalent classical form F_g sin(t + b)/cos(b) r (same source)
    beta = np.arcsin(lam * np.sin(th))
    np.testing.assert_allclose(
        res.torque[0], (p - P_CC) * area * R * np.sin(th + beta) / np.cos(beta),
        atol=1e-12 * np.abs(ref).max(),
    )


@pytest.mark.parametrize(("e_cyl", "e_pin", "bank"), [(0.0, 0.0, 0.0), (10 * MM, 0.8 * MM, 0.0),
                                                       (-5 * MM, 1.0 * MM, 30 * DEG)])
def test_big_end_load_matches_rigid_body_newton_euler(e_cyl, e_pin, bank):
    # Independent evaluation: rigid con-rod (mass m, CoM at l_g from the big end, inertia I_G)
    # and piston solved by Newton-Euler as a 5x5 linear system per crank angle, with positions
    # from the vector construction and accelerations by central differences (h = 1e-4 rad,
    # error ~1e-8 relative). This checks the two-mass model + correction couple, the offsets
    # and the bank rotation. Tolerance: 1e-6 of the peak load.
    th = cycle_grid(2.0 * DEG)
    w = 6000 * RPM
    e = e_cyl - e_pin  # pin offset towards the major thrust side = -t
    p = 1e5 + 60e5 * np.exp(-(((np.mod(th + 2 * np.pi, 4 * np.pi) - 2 * np.pi - 0.3) / 0.4) ** 2))
    res = _single(th, w, p, cylinder_offset=e_cyl, pin_offset=e_pin, bank_angle=bank)
    area = np.pi / 4 * BORE**2
    h = 1e-4
    b0, p0 = _linkage(th, e)
    bp, pp = _linkage(th + h, e)
    bm, pm = _linkage(th - h, e)

    def acc(xp, x0, xm):
        return w**2 * (xp - 2 * x0 + xm) / h**2

    g0, gp, gm = (b + L_G / L * (q - b) for b, q in ((b0, p0), (bp, pp), (bm, pm)))

    def ang(b, q):  # math-sense angle of the rod (big end -> small end)
        return np.arctan2(q[1] - b[1], q[0] - b[0])

    alpha = w**2 * (ang(bp, pp) - 2 * ang(b0, p0) + ang(bm, pm)) / h**2
    a_g, a_p = acc(gp, g0, gm), acc(pp, p0, pm)
    q_ref = np.empty((2, th.size))
    for k in range(th.size):
        rp, rb = p0[:, k] - g0[:, k], b0[:, k] - g0[:, k]
        # unknowns: S (piston on rod, 2), Q (pin on rod, 2), N (liner on piston)
        a_mat = np.array([
            [1, 0, 1, 0, 0],
            [0, 1, 0, 1, 0],
            [-rp[1], rp[0], -rb[1], rb[0], 0],
            [-1, 0, 0, 0, 1],
            [0, -1, 0, 0, 0],
        ])
        rhs = np.array([
            M_ROD * a_g[0, k],
            M_ROD * a_g[1, k],
            I_ROD * alpha[k],
            M_PISTON * a_p[0, k],
            M_PISTON * a_p[1, k] + (p[k] - P_CC) * area,
        ])
        q_ref[:, k] = np.linalg.solve(a_mat, rhs)[2:4]
    # cylinder frame -> block frame (bank rotation)
    ref = Vector2(q_ref[0] * np.cos(bank) + q_ref[1] * np.sin(bank),
                  -q_ref[0] * np.sin(bank) + q_ref[1] * np.cos(bank))
    scale = np.hypot(ref.x, ref.y).max()
    np.testing.assert_allclose(res.big_end_block.x[0], ref.x, atol=1e-6 * scale)
    np.testing.assert_allclose(res.big_end_block.y[0], ref.y, atol=1e-6 * scale)
    # torque = B x Q (crank sense), from the same independent quantities
    t_ref = b0[0] * q_ref[1] - b0[1] * q_ref[0]
    np.testing.assert_allclose(res.torque[0], t_ref, atol=1e-6 * scale * R)


def test_inertia_torque_equals_kinetic_energy_rate():
    # Energy (Lagrange) check independent of the force path: with no gas, the crank torque at
    # constant speed is T = -d(KE)/dtheta, KE = m v_G^2/2 + I_G w_rod^2/2 + m_p v_P^2/2 of the
    # true rigid rod (vector construction, velocities and d/dtheta by central differences).
    # Tolerance 1e-6 of the peak torque (difference error).
    th = cycle_grid(1.0 * DEG)
    w = 5000 * RPM
    e = -0.8 * MM  # pin 0.8 mm towards the major thrust side (-t)
    res = _single(th, w, np.full(th.size, P_CC), pin_offset=-e)
    h = 1e-4

    def ke(phi):
        b0, p0 = _linkage(phi, e)
        bp, pp = _linkage(phi + h, e)
        bm, pm = _linkage(phi - h, e)
        vp = w * (pp - pm) / (2 * h)
        vb = w * (bp - bm) / (2 * h)
        vg = vb + L_G / L * (vp - vb)
        ang = np.arctan2(*(pp - bp)[::-1]) - np.arctan2(*(pm - bm)[::-1])
        w_rod = w * ang / (2 * h)
        return 0.5 * M_ROD * (vg**2).sum(0) + 0.5 * I_ROD * w_rod**2 + 0.5 * M_PISTON * (
            vp**2
        ).sum(0)

    hh = 1e-3
    t_ref = -(ke(th + hh) - ke(th - hh)) / (2 * hh)
    np.testing.assert_allclose(res.torque[0], t_ref, atol=1e-6 * np.abs(t_ref).max())


def test_mean_indicated_torque_equals_imep_work():
    # Brief requirement: mean torque from the force path = IMEP Vd / (4 pi) to < 0.1 %.
    # IMEP from the trace's p dV integral (trapezoid in V, independent of the torque path).
    # Masses and speed included (their torque averages to zero over the cycle).
    th = cycle_grid(0.25 * DEG)
    geo = dict(bore=BORE, crank_radius=R, rod_length=L, compression_ratio=10.5, pin_offset=0.8 * MM)
    peaks = np.array([53.4, 84.4, 29.1]) * BAR
    tr = synthesize_trace(th, peaks, **geo)
    vd = swept_volume(BORE, R, L, 0.0, 0.8 * MM)
    imep = indicated_mean_effective_pressure(tr.pressure, cylinder_volume(th, **geo), vd)
    res = _single(th, np.array([1000, 5000, 7000]) * RPM, tr.pressure, pin_offset=0.8 * MM)
    mean_t = res.torque[:, 0].mean(axis=-1)
    np.testing.assert_allclose(mean_t, imep * vd / (4 * np.pi), rtol=1e-3)


@pytest.mark.parametrize(
    ("e_cyl", "e_pin", "bank"), [(0.0, 0.0, 0.0), (8 * MM, -0.8 * MM, 45 * DEG)]
)
def test_pure_gas_torque_conserves_work(e_cyl, e_pin, bank):
    # Energy conservation: the cumulative crank work int T dtheta equals the cumulative piston
    # work int (p - p_cc) dV at every crank angle (V from the independent vector construction,
    # both integrals by the trapezoidal rule on a 0.1 deg grid -> agreement 1e-4 of the cycle's
    # expansion work).
    th = cycle_grid(0.1 * DEG)
    p = 1e5 + 70e5 * np.exp(-(((np.mod(th + 2 * np.pi, 4 * np.pi) - 2 * np.pi - 0.25) / 0.5) ** 2))
    res = _single(th, 0.0, p, piston_mass=0.0, rod_mass=0.0, rod_inertia=0.0,
                  cylinder_offset=e_cyl, pin_offset=e_pin, bank_angle=bank)
    area = np.pi / 4 * BORE**2
    _, pin = _linkage(th, e_cyl - e_pin)
    vol = -area * pin[1]  # volume change = -A * d(pin height)
    t = np.append(res.torque[0], res.torque[0, 0])
    pp = np.append(p - P_CC, p[0] - P_CC)
    v = np.append(vol, vol[0])
    dth = np.diff(np.append(th, 4 * np.pi))
    w_crank = np.concatenate([[0], np.cumsum(0.5 * (t[1:] + t[:-1]) * dth)])
    w_gas = np.concatenate([[0], np.cumsum(0.5 * (pp[1:] + pp[:-1]) * np.diff(v))])
    scale = np.abs(w_gas).max()
    np.testing.assert_allclose(w_crank, w_gas, atol=1e-4 * scale)


def test_frames_are_consistent():
    # Rotations preserve the magnitude; crank <-> block round trip; the rod-frame y component is
    # the projection on the rod direction from the vector construction (exact identities).
    th = cycle_grid(2.0 * DEG)
    p = 1e5 + 40e5 * np.exp(-(((th - 0.3) / 0.4) ** 2))
    res = _single(th, 3000 * RPM, p, pin_offset=0.8 * MM)
    mag = res.big_end_block.magnitude
    np.testing.assert_allclose(res.big_end_crank.magnitude, mag, rtol=1e-12)
    np.testing.assert_allclose(res.big_end_rod.magnitude, mag, rtol=1e-12)
    back = crank_to_block(res.big_end_crank, th)
    np.testing.assert_allclose(back.x, res.big_end_block.x, atol=1e-9 * mag.max())
    b, q = _linkage(th, -0.8 * MM)  # pin towards the major thrust side
    u = (q - b) / L
    proj = res.big_end_block.x[0] * u[0] + res.big_end_block.y[0] * u[1]
    np.testing.assert_allclose(res.big_end_rod.y[0], proj, atol=1e-9 * mag.max())
    # crank frame at theta = 0 is the block frame
    c0 = block_to_crank(Vector2(np.array(1.0), np.array(2.0)), 0.0)
    np.testing.assert_allclose([c0.x, c0.y], [1.0, 2.0])


def test_bank_angle_rotates_loads():
    # Symmetry: a cylinder of bank angle alpha firing at theta = alpha has its throw at crank
    # angle 0; its block-frame loads are those of a bank-0 cylinder (firing at 0) evaluated
    # alpha earlier, turned by alpha. Exact index shift on a 1 deg grid: rtol 1e-12.
    th = cycle_grid(1.0 * DEG)
    p = 1e5 + 60e5 * np.exp(-(((th - 0.3) / 0.4) ** 2))
    a0 = _single(th, 4000 * RPM, p)
    alpha = 90 * DEG
    a1 = _single(th, 4000 * RPM, p, bank_angle=alpha, firing_angle=np.array([alpha]))
    be0 = a0.big_end_block
    ref = Vector2(np.roll(be0.x, 90, axis=-1), np.roll(be0.y, 90, axis=-1))
    rot = Vector2(ref.x * np.cos(alpha) + ref.y * np.sin(alpha),
                  -ref.x * np.sin(alpha) + ref.y * np.cos(alpha))
    scale = a0.big_end_block.magnitude.max()
    np.testing.assert_allclose(a1.big_end_block.x, rot.x, atol=1e-12 * scale)
    np.testing.assert_allclose(a1.big_end_block.y, rot.y, atol=1e-12 * scale)
    np.testing.assert_allclose(a1.torque, np.roll(a0.torque, 90, axis=-1), atol=1e-9 * scale * R)


def test_fractional_firing_angle_is_interpolated():
    # Phasing: cylinder with phi = 100.5 deg on a 1 deg grid sees p(theta - phi) by periodic
    # linear interpolation (numpy.interp with period = exact reference, rtol 1e-12 + rounding).
    th = cycle_grid(1.0 * DEG)
    p = 1e5 + 60e5 * np.exp(-(((th - 0.3) / 0.4) ** 2))
    res = _single(th, 0.0, p, firing_angle=np.array([100.5 * DEG]))
    ref = np.interp(th - 100.5 * DEG, th, p, period=4 * np.pi)
    f_ref = (ref - P_CC) * np.pi / 4 * BORE**2
    np.testing.assert_allclose(res.gas_force[0], f_ref, rtol=1e-12, atol=1e-12 * f_ref.max())


# ------------------------------------------------------------------------------ main bearings
def _example_i4(step_deg=1.0):
    """Seed 000 example I4 at 1000..7000 rpm, full load (synthesized) and no load."""
    th = cycle_grid(step_deg * DEG)
    w = np.array([1000.0, 3000.0, 5000.0, 6000.0, 7000.0]) * RPM
    geo = dict(bore=BORE, crank_radius=R, rod_length=L, compression_ratio=10.5, pin_offset=0.8 * MM)
    peaks = np.array([[53.4, 77.1, 84.4, 79.8, 73.3], [29.1] * 5]) * BAR
    tr = synthesize_trace(th, peaks, **geo)
    loads = cylinder_loads(th, w, tr.pressure[:, :, None, :], firing_angle=FIRING_I4,
                           pin_offset=0.8 * MM, **ROD)
    # seed 000 mass table (crank frame: y toward throw 1); webs / counterweights relative to the
    # main axis, crank pins relative to the pin axis. Axial: web CoM at 27/2 + 22.3/2 = 24.65 mm
    # from its nearest main, pins mid-bay (48 mm), main spacing 96 mm (brief).
    y_tab = np.array([26.763, -37.611, -0.1, 26.763, -37.611,
                      -26.763, 37.611, 0.1, -26.763, 37.611,
                      -26.763, 37.611, 0.1, -26.763, 37.611,
                      26.763, -37.611, -0.1, 26.763, -37.611]) * MM
    mass = np.tile([0.659, 0.794, 0.341, 0.659, 0.794], 4)
    bay = np.repeat(np.arange(4), 5)
    throws = throw_angles(FIRING_I4, 0.0, np.arange(4), 4)
    is_pin = np.tile([False, False, True, False, False], 4)
    y = y_tab + is_pin * R * np.cos(throws[bay])
    x = is_pin * R * np.sin(throws[bay])
    z = np.tile([24.65, 24.65, 48.0, 71.35, 71.35], 4) * MM
    mains = main_bearing_loads(
        th, w, loads.big_end_block, pin_index=np.arange(4), rod_axial_position=48 * MM,
        bay_length=np.full(4, 96 * MM), mass=mass, mass_bay=bay,
        mass_position=np.stack([x, y], axis=1), mass_axial_position=z,
    )
    return th, w, loads, mains, dict(mass=mass, x=x, y=y)


def test_example_i4_main_bearing_symmetry():
    # Seed 000 "Concept level bearing analysis results (8)": peak forces are similar at mains
    # 1 and 5 and at mains 2 and 4. Brief tolerance: < 1 % (the statically determinate model of
    # this symmetric crank gives equality to rounding).
    _, _, loads, mains, _ = _example_i4()
    peak = mains.magnitude.max(axis=-1)  # (case, speed, main)
    assert peak.shape == (2, 5, 5)
    np.testing.assert_allclose(peak[..., 0], peak[..., 4], rtol=1e-2)
    np.testing.assert_allclose(peak[..., 1], peak[..., 3], rtol=1e-2)
    # all four big ends see the same peak load (same trace, phased)
    be = loads.big_end_block.magnitude.max(axis=-1)
    np.testing.assert_allclose(be, be[..., :1].repeat(4, axis=-1), rtol=1e-12)
    # seed 000: "Centre main bearing (3) is often the worst case at high speed": at 7000 rpm
    # main 3 is the most loaded main in both load cases (margin > 30 % here)
    assert np.all(np.argmax(peak[:, -1], axis=-1) == 2)


def test_main_bearing_loads_balance_applied_forces():
    # Global equilibrium (statics): the sum of all main bearing loads equals the sum of all
    # forces applied to the crankshaft: rod forces on the pins (-big end) plus centrifugal forces
    # m w^2 rho turned to the block frame. rtol 1e-12 of the peak.
    th, w, loads, mains, mp = _example_i4(2.0)
    tot = Vector2(mains.x.sum(axis=-2), mains.y.sum(axis=-2))
    cx, cy = (mp["mass"] * mp["x"]).sum(), (mp["mass"] * mp["y"]).sum()
    w2 = (w**2)[None, :, None]
    ref_x = -loads.big_end_block.x.sum(axis=-2) + w2 * (cx * np.cos(th) + cy * np.sin(th))
    ref_y = -loads.big_end_block.y.sum(axis=-2) + w2 * (-cx * np.sin(th) + cy * np.cos(th))
    scale = mains.magnitude.max()
    np.testing.assert_allclose(tot.x, ref_x, atol=1e-12 * scale)
    np.testing.assert_allclose(tot.y, ref_y, atol=1e-12 * scale)


def test_v_engine_shared_pin_lever_rule():
    # V twin on one pin (bank +-45 deg, firing 0 / 450 deg = 90 deg V, 270/450 firing). The
    # cylinders imply the same throw (throw_angles consistency). Lever rule for a simply
    # supported bay (statics): rod A at z = 30 mm and rod B at z = 60 mm of a 90 mm bay.
    th = cycle_grid(1.0 * DEG)
    firing = np.array([0.0, 450.0]) * DEG
    bank = np.array([-45.0, 45.0]) * DEG
    g = throw_angles(firing, bank, np.array([0, 0]), 1)
    np.testing.assert_allclose(g, [315 * DEG])
    with pytest.raises(ValueError, match="different throw"):
        throw_angles(np.array([0.0, 400.0]) * DEG, bank, np.array([0, 0]), 1)
    p = 1e5 + 60e5 * np.exp(-(((th - 0.3) / 0.4) ** 2))
    loads = cylinder_loads(th, 5000 * RPM, p[None, :], firing_angle=firing, bank_angle=bank,
                           **ROD)
    pin = crankpin_force(loads.big_end_block, np.array([0, 0]), 1)
    np.testing.assert_allclose(pin.x[0], -(loads.big_end_block.x.sum(axis=0)), rtol=1e-14)
    mains = main_bearing_loads(
        th, 5000 * RPM, loads.big_end_block, pin_index=np.array([0, 0]),
        rod_axial_position=np.array([30.0, 60.0]) * MM, bay_length=np.array([90.0 * MM]),
        mass=np.zeros(0), mass_bay=np.zeros(0, dtype=int), mass_position=np.zeros((0, 2)),
        mass_axial_position=np.zeros(0),
    )
    fa, fb = -loads.big_end_block.x[0], -loads.big_end_block.x[1]
    np.testing.assert_allclose(mains.x[0], fa * 2 / 3 + fb / 3, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(mains.x[1], fa / 3 + fb * 2 / 3, rtol=1e-12, atol=1e-9)


def test_input_validation():
    th = cycle_grid(1.0 * DEG)
    p = np.full((1, th.size), 2e5)
    with pytest.raises(ValueError, match="shape"):
        cylinder_loads(th, 100.0, np.full((3, th.size), 2e5), firing_angle=FIRING_I4, **ROD)
    with pytest.raises(ValueError, match="cycle grid"):
        cylinder_loads(th[:-1], 100.0, p[:, :-1], firing_angle=FIRING_I4, **ROD)
    with pytest.raises(ValueError, match="rod_cg"):
        cylinder_loads(th, 100.0, p, firing_angle=FIRING_I4, **{**ROD, "rod_cg_from_big_end": L})
    with pytest.raises(ValueError, match="pin_index"):
        crankpin_force(Vector2(np.zeros((2, 4)), np.zeros((2, 4))), np.array([0, 3]), 2)


def test_mass_positions_turn_the_throw1_frame_into_the_crank_frame():
    # V engine: throw 1 at gamma_1 = 45 deg (bank 45 deg, cylinder 1 fires at 0). A web along
    # throw 1 in the sheet (Y = rho, Z = 0) lies at 45 deg in the crank frame; a counterweight
    # opposite throw 3 (throw at 45 + 270 = 315 deg: sheet direction 270 + 180 = 90 deg from
    # throw 1, Z = rho) at 45 + 90 = 135 deg; a pin-axis point at the pin of throw 2 (135 deg)
    # plus its offset (Y = -0.1 mm, turned by 45 deg).
    from checker.calc.crank_forces import mass_positions

    r, rho = 0.046, 0.023
    gam = np.radians([45.0, 135.0, 315.0, 225.0])
    pos = mass_positions([0.0, rho, 0.0], [rho, 0.0, -1e-4], [0, 2, 1], [False, False, True],
                         gam, r)
    s = np.sqrt(0.5)
    np.testing.assert_allclose(pos[0], [rho * s, rho * s], atol=1e-15)
    np.testing.assert_allclose(pos[1], [rho * s, -rho * s], atol=1e-15)
    np.testing.assert_allclose(pos[2], [r * s - 1e-4 * s, -r * s - 1e-4 * s], atol=1e-15)
    # in-line engine (gamma_1 = 0): the sheet's (Z, Y) are the crank frame's (x, y)
    pos0 = mass_positions([0.01], [0.02], [0], [False], [0.0, np.pi], r)
    np.testing.assert_allclose(pos0, [[0.01, 0.02]], atol=1e-15)


def test_side_force_direction_and_pin_offset_crossover_by_hand():
    # By hand, gas force only (omega = 0, constant 50 bar): the rod in compression pushes the
    # piston along the rod towards the small end, u = (-sin b, cos b); axial balance gives the
    # rod force F/cos(b) and the piston presses on the liner with N = -F tan(b) along +t.
    # Zero offset, expansion (0 < phi < pi): b > 0 -> N < 0, the piston bears on -t, the
    # major thrust side. With the pin offset a towards the major thrust side (workbook
    # convention) the pin runs on t = -a: sin(b) = (r sin(phi) + a)/l, so N changes sign (the
    # crossover from the minor to the major thrust side) at phi_x = -asin(a/r) = -0.969 deg,
    # before TDC (-0.2375 deg): at TDC the piston already bears on the major thrust side,
    # which relaxes piston slap (seed 004, "Methods to decrease slap": the pin "moved towards
    # the major thrust side"). The mirror offset crosses over at +0.969 deg, after TDC, under
    # gas load. Exact relation N = -F tan(b): tolerance 1e-12 of F.
    th = cycle_grid(0.01 * DEG)
    p = np.full(th.size, 50 * BAR)
    f_gas = (50 * BAR - P_CC) * np.pi / 4 * BORE**2
    a = 0.8 * MM
    phi = np.where(th > 2 * np.pi, th - 4 * np.pi, th)  # (-2 pi, 2 pi], 0 = firing TDC

    def side(offset, deg):
        k = int(np.argmin(np.abs(phi - np.radians(deg))))
        return res[offset].side_force[0, k]

    res = {o: _single(th, 0.0, p, pin_offset=o) for o in (0.0, a, -a)}
    expansion = (phi > 0.05) & (phi < np.pi - 0.05)
    assert np.all(res[0.0].side_force[0, expansion] < 0)  # major thrust side = -t
    b = np.arcsin((R * np.sin(phi) + a) / L)
    np.testing.assert_allclose(res[a].side_force[0], -f_gas * np.tan(b), atol=1e-12 * f_gas)
    x_deg = np.degrees(np.arcsin(a / R))
    assert x_deg == pytest.approx(0.969, abs=1e-3)
    tdc_deg = -np.degrees(np.arcsin(a / (L + R)))
    assert side(a, -x_deg - 0.03) > 0 and side(a, -x_deg + 0.03) < 0  # crossover at -0.969
    assert side(a, tdc_deg) < 0 and side(a, 0.0) < 0  # on the major thrust side at TDC
    assert side(-a, -tdc_deg) > 0 and side(-a, x_deg - 0.03) > 0 and side(-a, x_deg + 0.03) < 0
