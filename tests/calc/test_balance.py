"""Free forces and moments, rotating unbalance and balance ratio (checker.calc.balance)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import balance as bal
from checker.calc.kinematics import slider_kinematics

R, L = 0.05, 0.2  # lam = 0.25
M_REC = 0.65


def test_harmonics_match_the_classical_series():
    # Series to lam^5 (Heywood 1988 eq. 2.5 expanded): truncation O(lam^7) ~ 6e-5 r
    a = bal.piston_acceleration_harmonics(R, L, 0.0, 8)
    s = bal.piston_acceleration_series(R, L, 8)
    np.testing.assert_allclose(a.real, s, atol=R * 0.25**7)
    np.testing.assert_allclose(a.imag, 0.0, atol=1e-15)
    assert a[1].real == pytest.approx(R, rel=1e-12)  # first order is exactly r


def test_harmonics_with_offset_reconstruct_the_exact_acceleration():
    # with a 2 mm offset: odd orders and sine terms appear; the 8-order series reproduces the
    # exact acceleration to the size of the 9th harmonic (< 1e-6 r here)
    e = 0.002
    a = bal.piston_acceleration_harmonics(R, L, e, 8)
    phi = np.linspace(0, 2 * np.pi, 777)
    exact = slider_kinematics(phi, R, L, 1.0, e).d2x_dtheta2
    rec = np.real(np.exp(1j * np.outer(phi, np.arange(9))) @ a)
    np.testing.assert_allclose(rec, exact, atol=1e-6 * R)
    assert abs(a[3]) > 1e-6 * R and abs(a[0]) < 1e-15 * R


def _per_throw_masses(throw_angles, z_pins, m_pin=0.35, m_web=0.66, r_web=0.027,
                      m_cw=0.8, r_cw=0.037):
    """Pin, two webs and two counterweights per throw, symmetric about the pin plane."""
    m, pos, z = [], [], []
    for g, zp in zip(throw_angles, z_pins):
        e = np.array([np.sin(g), np.cos(g)])
        for mass, rad, dz in ((m_pin, R, 0.0), (m_web, r_web, -0.012), (m_web, r_web, 0.012),
                              (m_cw, -r_cw, -0.012), (m_cw, -r_cw, 0.012)):
            m.append(mass)
            pos.append(rad * e)
            z.append(zp + dz)
    return np.array(m), np.array(pos), np.array(z)


def _engine(firing_deg, bank_deg=0.0, spacing=0.096, offset=0.0, masses=True):
    phi = np.radians(firing_deg)
    alpha = np.broadcast_to(np.radians(bank_deg), phi.shape)
    z = spacing * (np.arange(phi.size) - (phi.size - 1) / 2)  # reference plane mid-crank
    a = bal.piston_acceleration_harmonics(R, L, offset, 8)
    gam = np.mod(alpha - phi, 2 * np.pi)
    m, pos, zm = _per_throw_masses(gam, z) if masses else (np.zeros(0), np.zeros((0, 2)),
                                                            np.zeros(0))
    return bal.shaking_phasors(firing_angle=phi, bank_angle=alpha, cylinder_axial=z,
                               reciprocating_mass=M_REC, acceleration_harmonics=a,
                               rotating_mass=m, rotating_position=pos, rotating_axial=zm), a


def test_inline_four_only_even_orders_and_no_moments():
    # Taylor 1985 vol. 2 ch. 8: flat-plane I4 (1-3-4-2) is primary balanced, its secondary
    # force is 4 m r w^2 lam (first term), vertical, maximal at TDC; no free moments.
    res, a = _engine([0, 540, 180, 360])
    big, small, theta, direction = bal.order_vector_extremes(res.force, res.orders)
    scale = M_REC * R
    assert big[0] < 1e-12 * scale and big[2] < 1e-12 * scale  # orders 1 and 3
    lam = R / L
    np.testing.assert_allclose(big[1], 4 * M_REC * R * (lam + lam**3 / 4 + 15 * lam**5 / 128),
                               rtol=1e-4)
    assert big[1] == pytest.approx(4 * M_REC * R * lam, rel=lam**2 / 4 + 1e-3)
    assert small[1] < 1e-12 * scale  # along a fixed (vertical) line
    assert theta[1] == pytest.approx(0.0, abs=1e-12) and direction[1] == pytest.approx(0.0)
    assert big[3] == pytest.approx(4 * M_REC * abs(a[4]), rel=1e-12)  # 4th order adds too
    mbig, *_ = bal.order_vector_extremes(res.moment, res.orders)
    assert np.all(mbig < 1e-12 * scale * 0.1)


def test_inline_six_free_forces_and_moments_vanish():
    # I6, 1-5-3-6-2-4: every free force and moment of orders 1-5, 7, 8 is zero (Taylor 1985
    # vol. 2 ch. 8); only the 6th order (all vectors aligned) remains, 6 m A_6 (~ lam^5 r).
    fire = np.zeros(6)
    for k, cyl in enumerate([1, 5, 3, 6, 2, 4]):
        fire[cyl - 1] = 120.0 * k
    res, a = _engine(fire)
    big, *_ = bal.order_vector_extremes(res.force, res.orders)
    mbig, *_ = bal.order_vector_extremes(res.moment, res.orders)
    scale = M_REC * R
    keep = res.orders != 6
    assert np.all(big[keep] < 1e-13 * scale)
    assert big[5] == pytest.approx(6 * M_REC * abs(a[6]), rel=1e-9) and big[5] > 1e-6 * scale
    assert np.all(mbig < 1e-13 * scale)


def test_ninety_degree_v_twin_primary_is_a_rotating_force():
    # 90 deg V-twin on one pin (banks -45/+45 deg, firing 0/90 deg): the primary reciprocating
    # force has the constant magnitude m r w^2 and rotates with the crank (Taylor 1985 vol. 2
    # ch. 8), so a counterweight can balance it.
    phi = np.radians([0.0, 90.0])
    alpha = np.radians([-45.0, 45.0])
    a = bal.piston_acceleration_harmonics(R, L, 0.0, 4)
    res = bal.shaking_phasors(firing_angle=phi, bank_angle=alpha, cylinder_axial=[0.0, 0.0],
                              reciprocating_mass=M_REC, acceleration_harmonics=a,
                              rotating_mass=[], rotating_position=np.zeros((0, 2)),
                              rotating_axial=[])
    big, small, *_ = bal.order_vector_extremes(res.force_reciprocating, res.orders)
    assert big[0] == pytest.approx(M_REC * R, rel=1e-12)
    assert small[0] == pytest.approx(M_REC * R, rel=1e-12)
    # a counterweight of m_rec r opposite the pin cancels it
    cw = bal.shaking_phasors(firing_angle=phi, bank_angle=alpha, cylinder_axial=[0.0, 0.0],
                             reciprocating_mass=M_REC, acceleration_harmonics=a,
                             rotating_mass=[M_REC], rotating_position=[[R * np.sin(np.pi / 4),
                                                                        -R * np.cos(
                                                                            np.pi / 4)]],
                             rotating_axial=[0.0])
    assert abs(cw.force[0]).max() < 1e-12 * M_REC * R


def test_single_cylinder_against_direct_sampling():
    # Independent: the force computed from the exact kinematics on a fine grid (no Fourier
    # series) equals the synthesis of the order phasors; rotating unbalance adds m rho w^2.
    e = 0.001
    a = bal.piston_acceleration_harmonics(R, L, e, 8)
    m_rot, rho = 0.9, np.array([0.004, -0.03])  # net crank unbalance, off-axis
    res = bal.shaking_phasors(firing_angle=[0.0], bank_angle=0.0, cylinder_axial=[0.0],
                              reciprocating_mass=M_REC, acceleration_harmonics=a,
                              rotating_mass=[m_rot], rotating_position=[rho],
                              rotating_axial=[0.0])
    th = np.linspace(0, 2 * np.pi, 1001)
    fy = M_REC * slider_kinematics(th, R, L, 1.0, e).d2x_dtheta2
    # crank-frame rho turned into the block frame at theta
    fx_rot = rho[0] * np.cos(th) + rho[1] * np.sin(th)
    fy_rot = -rho[0] * np.sin(th) + rho[1] * np.cos(th)
    ph = np.exp(1j * np.outer(th, res.orders))
    syn = np.real(ph @ res.force)  # (N, 2)
    np.testing.assert_allclose(syn[:, 0], m_rot * fx_rot, atol=1e-12)
    np.testing.assert_allclose(syn[:, 1], fy + m_rot * fy_rot - M_REC * a[0].real,
                               atol=2e-6 * M_REC * R)


def test_order_vector_extremes_against_sampling():
    rng = np.random.default_rng(5)
    v = rng.normal(size=(20, 2)) + 1j * rng.normal(size=(20, 2))
    n = rng.integers(1, 7, size=20).astype(float)
    big, small, theta, direction = bal.order_vector_extremes(v, n)
    th = np.linspace(0, 2 * np.pi, 200_001)
    for i in range(20):
        vec = np.real(v[i][None, :] * np.exp(1j * n[i] * th)[:, None])
        mag = np.hypot(vec[:, 0], vec[:, 1])
        assert big[i] == pytest.approx(mag.max(), rel=1e-8)
        assert small[i] == pytest.approx(mag.min(), rel=1e-6, abs=1e-12)
        vt = np.real(v[i] * np.exp(1j * n[i] * theta[i]))
        assert np.hypot(*vt) == pytest.approx(big[i], rel=1e-12)
        assert np.arctan2(vt[0], vt[1]) == pytest.approx(direction[i], abs=1e-12)
        assert 0 <= theta[i] < np.pi / n[i]


def test_throw_balance_closed_form():
    # one throw at 0 deg: pin 0.35 kg at r, two webs 0.66 kg at 27 mm, two counterweights
    # 0.8 kg at -37 mm, rod big end 0.45 kg at r: U_rot = 0.35 r + 2*0.66*0.027 + 0.45 r,
    # U_cw = 2*0.8*0.037, ratio U_cw/U_rot, reciprocating factor (U_cw - U_rot)/(m_rec r).
    m, pos, _ = _per_throw_masses([0.0], [0.0])
    kind = np.array([False, False, False, True, True])
    tb = bal.throw_balance(throw_angle=[0.0], mass=m, position=pos, throw_of_mass=np.zeros(5, int),
                           is_counterweight=kind, pin_rotating_mass=[0.45],
                           pin_reciprocating_mass=[M_REC], crank_radius=R)
    u_rot = 0.35 * R + 2 * 0.66 * 0.027 + 0.45 * R
    u_cw = 2 * 0.8 * 0.037
    assert tb.rotating_along[0] == pytest.approx(u_rot, rel=1e-12)
    assert tb.counterweight_along[0] == pytest.approx(u_cw, rel=1e-12)
    assert tb.balance_ratio[0] == pytest.approx(u_cw / u_rot, rel=1e-12)
    assert tb.reciprocating_factor[0] == pytest.approx((u_cw - u_rot) / (M_REC * R), rel=1e-12)
    # turning the whole throw (and its masses) to 120 deg changes nothing
    g = np.radians(120.0)
    rot = np.array([[np.cos(g), -np.sin(g)], [np.sin(g), np.cos(g)]])  # row vectors turned by g
    tb2 = bal.throw_balance(throw_angle=[g], mass=m, position=pos @ rot,
                            throw_of_mass=np.zeros(5, int), is_counterweight=kind,
                            pin_rotating_mass=[0.45], pin_reciprocating_mass=[M_REC],
                            crank_radius=R)
    assert tb2.balance_ratio[0] == pytest.approx(tb.balance_ratio[0], rel=1e-12)
    assert tb2.crank_ratio == pytest.approx(u_cw / u_rot, rel=1e-12)


def test_internal_bending_moment_of_an_i4_crank():
    # pins of mass m at r on throws 0/180/180/0 at mid-bays of a 4-bay crank (mains at 0..4 L):
    # at the centre main B = m r e_1 [(2L - L/2) - (2L - 3L/2)] = m r L e_1; zero at both ends.
    m, Lb = 0.5, 0.1
    gam = np.radians([0, 180, 180, 0])
    pos = R * np.stack([np.sin(gam), np.cos(gam)], axis=-1)
    z = Lb * (np.arange(4) + 0.5)
    b = bal.internal_bending_moment(Lb * np.arange(5), np.full(4, m), pos, z)
    np.testing.assert_allclose(b[2], [0.0, m * R * Lb], atol=1e-15)
    np.testing.assert_allclose(b[[0, 4]], 0.0, atol=1e-15)
    np.testing.assert_allclose(b[1], [0.0, m * R * Lb / 2], atol=1e-15)


def test_validation():
    with pytest.raises(ValueError):
        bal.piston_acceleration_harmonics(R, 0.04)  # rod shorter than the crank
    with pytest.raises(ValueError):
        bal.piston_acceleration_harmonics(R, L, max_order=0)
    with pytest.raises(ValueError, match="throws"):
        bal.throw_balance(throw_angle=[0.0], mass=[1.0], position=[[0.0, -0.01]],
                          throw_of_mass=[0], is_counterweight=[False], pin_rotating_mass=[0.0],
                          pin_reciprocating_mass=[0.5], crank_radius=R)


# ------------------------------------------------------------------------------ V engines
# Hand formulas by the rotating-vector method (Norton, Design of Machinery, secs. 14.5-14.7;
# Taylor 1985 vol. 2 ch. 8): a reciprocating order-n force m A_n cos(n(theta + gamma - alpha))
# along the bore axis alpha is half a vector rotating forward, m A_n / 2 at angle
# n(theta + gamma) - (n - 1) alpha, and half a vector rotating backward, m A_n / 2 at
# (n + 1) alpha - n(theta + gamma) (angles from y in the direction of rotation; gamma the
# throw). A forward first-order vector is fixed in the crank frame, so crank counterweights can
# cancel it; a backward one cannot.
def _v_engine(bank_deg, gamma_deg, z, rotating=None):
    """shaking_phasors of cylinders given by bank and throw angles (firing = bank - throw)."""
    alpha = np.radians(np.asarray(bank_deg, float))
    gam = np.radians(np.asarray(gamma_deg, float))
    phi = np.mod(alpha - gam, 4 * np.pi)
    a = bal.piston_acceleration_harmonics(R, L, 0.0, 8)
    m, pos, zm = rotating if rotating is not None else (np.zeros(0), np.zeros((0, 2)),
                                                        np.zeros(0))
    res = bal.shaking_phasors(firing_angle=phi, bank_angle=alpha, cylinder_axial=z,
                              reciprocating_mass=M_REC, acceleration_harmonics=a,
                              rotating_mass=m, rotating_position=pos, rotating_axial=zm)
    return res, a


def _cancelling_counterweights(couple, z_end):
    """Two counterweights at -z_end and +z_end whose couple is -couple (and no force)."""
    c = np.asarray(couple, float)
    return (np.array([1.0, 1.0]), np.array([c / (2 * z_end), -c / (2 * z_end)]),
            np.array([-z_end, z_end]))


def test_cross_plane_v8_free_forces_zero_primary_couple_cancelled_by_counterweights():
    # 90 deg cross-plane V8, GM numbering and firing order 1-8-7-2-6-5-4-3: odd cylinders on
    # the bank at +45 deg, even at -45 deg, cylinders 2k-1 and 2k on pin k; throws at 45, 135,
    # 315, 225 deg (0/90/270/180 from throw 1), pins at z = (k - 2.5) s.
    s = 0.1118
    fo = [1, 8, 7, 2, 6, 5, 4, 3]
    phi = np.zeros(8)
    for k, c in enumerate(fo):
        phi[c - 1] = np.pi / 2 * k
    alpha = np.radians([45.0 if c % 2 else -45.0 for c in range(1, 9)])
    pins = np.arange(8) // 2
    gam_pin = np.radians([45.0, 135.0, 315.0, 225.0])
    np.testing.assert_allclose(np.mod(alpha - phi, 2 * np.pi), gam_pin[pins], atol=1e-12)
    z = (pins - 1.5) * s
    res, a = _v_engine(np.degrees(alpha), np.degrees(gam_pin[pins]), z)
    big, small, *_ = bal.order_vector_extremes(res.force, res.orders)
    mbig, msmall, *_ = bal.order_vector_extremes(res.moment, res.orders)
    scale = M_REC * R
    # free forces: none of orders 1-3 (per pin the backward halves of the two banks cancel,
    # the forward halves sum over the four throws to zero); 4th order: both banks' four
    # cylinders in phase, 4 m A_4 along each bank axis, resultant 4 sqrt(2) m |A_4| vertical
    assert np.all(big[:3] < 1e-14 * scale)
    assert big[3] == pytest.approx(4 * np.sqrt(2) * M_REC * abs(a[4]), rel=1e-9)
    assert small[3] < 1e-14 * scale
    # primary couple: forward only, m r per pin (the two halves of both banks), moment
    # m r s |sum (k - 2.5) e_k| = m r s |(-1, -3)| = sqrt(10) m r s, constant magnitude
    assert mbig[0] == pytest.approx(np.sqrt(10) * M_REC * R * s, rel=1e-12)
    assert msmall[0] == pytest.approx(mbig[0], rel=1e-12)
    assert mbig[1] < 1e-14 * scale * s  # no secondary couple
    # ... equal to the couple of a mass m_rec at each crank pin (crank frame), so two
    # counterweights at the crank ends cancel it: no 1st-order force or moment remains
    e = np.stack([np.sin(gam_pin), np.cos(gam_pin)], axis=-1)
    couple = (M_REC * R * (np.arange(4) - 1.5)[:, None] * s * e).sum(0)
    cw = _cancelling_counterweights(couple, 2.2 * s)
    res_cw, _ = _v_engine(np.degrees(alpha), np.degrees(gam_pin[pins]), z, cw)
    assert np.abs(res_cw.force[0]).max() < 1e-14 * scale
    assert np.abs(res_cw.moment[0]).max() < 1e-14 * scale * s


def test_ninety_degree_v6_common_pins():
    # 90 deg V6, three common pins at 120 deg (banks +-45 deg), pins at z = -s, 0, s:
    # primary: forces cancel; couple forward only, m r s |e_3 - e_1| = sqrt(3) m r s;
    # secondary: forward halves sqrt(2)/2 m A_2 e(2 gamma) per pin, backward halves likewise,
    # both couples sqrt(3/2) m A_2 s, so the secondary couple is planar with
    # maximum sqrt(6) m |A_2| s and minimum 0; no secondary force.
    s = 0.12
    gam = np.repeat([0.0, 120.0, 240.0], 2)
    bank = np.tile([45.0, -45.0], 3)
    z = np.repeat([-s, 0.0, s], 2)
    res, a = _v_engine(bank, gam, z)
    big, *_ = bal.order_vector_extremes(res.force, res.orders)
    mbig, msmall, *_ = bal.order_vector_extremes(res.moment, res.orders)
    scale = M_REC * R
    assert big[0] < 1e-14 * scale and big[1] < 1e-14 * scale
    assert mbig[0] == pytest.approx(np.sqrt(3) * M_REC * R * s, rel=1e-12)
    assert msmall[0] == pytest.approx(mbig[0], rel=1e-12)
    assert mbig[1] == pytest.approx(np.sqrt(6) * M_REC * abs(a[2]) * s, rel=1e-12)
    assert msmall[1] < 1e-12 * mbig[1]
    # the primary couple is that of m_rec at each pin: end counterweights cancel it
    g = np.radians([0.0, 120.0, 240.0])
    e = np.stack([np.sin(g), np.cos(g)], axis=-1)
    couple = (M_REC * R * np.array([-s, 0.0, s])[:, None] * e).sum(0)
    res_cw, _ = _v_engine(bank, gam, z, _cancelling_counterweights(couple, 1.6 * s))
    assert np.abs(res_cw.moment[0]).max() < 1e-14 * scale * s


def test_sixty_degree_v6_split_pins():
    # 60 deg V6 with split pins for even firing (1-2-3-4-5-6 every 120 deg; odd cylinders on
    # the bank at -30 deg, even at +30 deg): throws gamma = alpha - phi = -30, -90, 90, 30, 210,
    # 150 deg, one per cylinder at z_i = (i - 3.5) s. Primary and secondary forces cancel;
    # primary couple: forward halves (m r / 2) s |sum (i - 3.5) e(gamma_i)| = 3 m r s, backward
    # halves cancel, so a rotating couple 3 m r s that counterweights cancel; secondary couple:
    # forward halves cancel, backward (m A_2 / 2) s x 6 = 3 m |A_2| s, a couple of constant
    # magnitude turning against the crank (a balance shaft, not a counterweight, removes it).
    s = 0.06
    bank = np.tile([-30.0, 30.0], 3)
    phi = np.radians(120.0 * np.arange(6))
    gam = np.degrees(np.mod(np.radians(bank) - phi, 2 * np.pi))
    np.testing.assert_allclose(gam, [330, 270, 90, 30, 210, 150], atol=1e-9)
    z = (np.arange(6) - 2.5) * s
    res, a = _v_engine(bank, gam, z)
    big, *_ = bal.order_vector_extremes(res.force, res.orders)
    mbig, msmall, *_ = bal.order_vector_extremes(res.moment, res.orders)
    scale = M_REC * R
    assert big[0] < 1e-14 * scale and big[1] < 1e-14 * scale
    assert mbig[0] == pytest.approx(3 * M_REC * R * s, rel=1e-12)
    assert msmall[0] == pytest.approx(mbig[0], rel=1e-12)
    assert mbig[1] == pytest.approx(3 * M_REC * abs(a[2]) * s, rel=1e-12)
    assert msmall[1] == pytest.approx(mbig[1], rel=1e-12)
    # forward primary couple = (m r / 2) sum z_i e(gamma_i): two end counterweights cancel it
    gr = np.radians(gam)
    e = np.stack([np.sin(gr), np.cos(gr)], axis=-1)
    couple = (0.5 * M_REC * R * z[:, None] * e).sum(0)
    res_cw, _ = _v_engine(bank, gam, z, _cancelling_counterweights(couple, 3.5 * s))
    assert np.abs(res_cw.moment[0]).max() < 1e-14 * scale * s
    # direction of turning from the phasors: a forward vector (fixed in the crank frame,
    # crank_vector_phasor) has P_y = j P_x, a backward one P_y = -j P_x
    p1, p2 = res.moment[0], res.moment[1]
    assert abs(p1[1] - 1j * p1[0]) < 1e-14 * scale * s
    assert abs(p2[1] + 1j * p2[0]) < 1e-14 * scale * s
    # the secondary couple turns backward: the same counterweights leave it unchanged
    assert np.abs(res_cw.moment[1] - res.moment[1]).max() < 1e-16


@pytest.mark.parametrize(("throws_deg", "pins", "want"), [
    ([0, 180, 180, 0], [0, 1, 2, 3], (True, True)),  # in-line four (Taylor 1985 ch. 8)
    ([0, 120, 240, 240, 120, 0], list(range(6)), (True, True)),  # in-line six
    ([0, 240, 120], [0, 1, 2], (True, False)),  # in-line three: rotating couple
    ([0, 90, 270, 180], [0, 0, 1, 1, 2, 2, 3, 3], (True, False)),  # cross-plane V8
    ([0, 180, 180, 0], [0, 0, 1, 1, 2, 2, 3, 3], (True, True)),  # flat-plane V8
    ([0], [0], (False, False)),  # single throw
    ([0, 180], [0, 1, 1], (False, False)),  # unequal rods per pin
])
def test_inherent_balance_of_classical_layouts(throws_deg, pins, want):
    assert bal.inherent_balance(np.radians(throws_deg), pins) == want


def test_mean_throw_unbalance_hand_value():
    # throw 1: 0.4 kg at 45 mm -> 0.018 kg m; throw 2: 0.2 kg at 30 mm and 0.3 kg at 40 mm at
    # right angles -> hypot(0.006, 0.012) kg m (by hand)
    m = [0.4, 0.2, 0.3]
    rho = [[0.0, 0.045], [0.03, 0.0], [0.0, 0.04]]
    got = bal.mean_throw_unbalance(m, rho, [0, 1, 1], 2)
    assert got == pytest.approx(0.5 * (0.018 + np.hypot(0.006, 0.012)), rel=1e-14)
    with pytest.raises(ValueError):
        bal.mean_throw_unbalance(m, rho, [0, 1, 2], 2)
