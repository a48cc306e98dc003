"""Tests for checker.calc.kinematics (crank-slider with offsets)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc.kinematics import (
    DEFAULT_STEP,
    DEFAULT_STEP_DEG,
    FOUR_STROKE_CYCLE,
    cycle_grid,
    dead_centres,
    slider_kinematics,
)

MM = 1e-3
R, L = 47.3 * MM, 145.7 * MM  # example engine (seed 000)
OFFSETS = [(0.0, 0.0), (0.0, 0.8 * MM), (12.0 * MM, -3.0 * MM), (-10.0 * MM, 0.0)]


def _vector_construction(phi, r, l, e):
    """Independent geometry: crank pin on its circle, piston pin where the rod of length l meets
    the line t = e (upper intersection); returns (c_P, beta, rod direction angle)."""
    b_t, b_c = r * np.sin(phi), r * np.cos(phi)
    c_p = b_c + np.sqrt(l**2 - (e - b_t) ** 2)
    # rod vector from big end to small end
    u_t, u_c = e - b_t, c_p - b_c
    beta = np.arctan2(-u_t, u_c)  # u = l (-sin beta, cos beta)
    return c_p, beta


@pytest.mark.parametrize(("e_cyl", "e_pin"), OFFSETS)
def test_derivatives_match_central_differences(e_cyl, e_pin):
    # Source: central differences, truncation error h^2/6 f''' -> with h = 1e-4 rad the error is
    # < 1e-8 * r for these smooth functions; tolerance 1e-7 relative to r.
    phi = np.linspace(-2 * np.pi, 2 * np.pi, 1441)
    h = 1e-4
    k0 = slider_kinematics(phi, R, L, 1.0, e_cyl, e_pin)
    kp = slider_kinematics(phi + h, R, L, 1.0, e_cyl, e_pin)
    km = slider_kinematics(phi - h, R, L, 1.0, e_cyl, e_pin)
    np.testing.assert_allclose((kp.x - km.x) / (2 * h), k0.dx_dtheta, atol=1e-7 * R)
    np.testing.assert_allclose(
        (kp.dx_dtheta - km.dx_dtheta) / (2 * h), k0.d2x_dtheta2, atol=1e-7 * R
    )
    np.testing.assert_allclose((kp.x - 2 * k0.x + km.x) / h**2, k0.d2x_dtheta2, atol=1e-5 * R)
    np.testing.assert_allclose((kp.beta - km.beta) / (2 * h), k0.dbeta_dtheta, atol=1e-7)
    np.testing.assert_allclose(
        (kp.dbeta_dtheta - km.dbeta_dtheta) / (2 * h), k0.d2beta_dtheta2, atol=1e-7
    )


@pytest.mark.parametrize(("e_cyl", "e_pin"), OFFSETS)
def test_position_and_rod_angle_match_vector_construction(e_cyl, e_pin):
    # Independent evaluation: direct vector construction of the linkage (circle-line
    # intersection); TDC height found by brute force over a 0.001 deg grid. Tolerance: 1e-12 m for
    # the pin height / rod angle (rounding), 1e-9 m for the TDC height (grid resolution,
    # curvature r (1+lam) * (0.5 * 1.7e-5 rad)^2 ~ 5e-12 m).
    e = e_cyl - e_pin  # pin offset towards the major thrust side = -t
    phi = np.linspace(0, 2 * np.pi, 360001)
    c_p, beta = _vector_construction(phi, R, L, e)
    w = 300.0
    kin = slider_kinematics(phi, R, L, w, e_cyl, e_pin)
    c_top = c_p.max()
    np.testing.assert_allclose(kin.x, c_top - c_p, atol=1e-9)
    np.testing.assert_allclose(kin.beta, beta, atol=1e-12)
    # rod angular velocity: derivative of the constructed rod direction (crank-sense angle of u
    # is -beta), central differences on the same fine grid (error ~ h^2 ~ 3e-10)
    dphi = phi[1] - phi[0]
    rod_w = -np.gradient(beta, dphi) * w
    np.testing.assert_allclose(kin.rod_omega[1:-1], rod_w[1:-1], atol=1e-6 * w)


def test_zero_offset_matches_published_closed_forms():
    # Seed 004 (Agostini 2019) centred layout: x = r[1 - cos + (1 - sqrt(1 - lam^2 sin^2))/lam],
    # v = omega r [sin + lam/2 sin 2theta / sqrt(1 - lam^2 sin^2)]; Heywood 1988 eq. 2.5. Exact
    # expressions, tolerance 1e-12 relative (rounding).
    phi = np.linspace(0, 4 * np.pi, 7201)
    w = 628.3
    lam = R / L
    root = np.sqrt(1 - lam**2 * np.sin(phi) ** 2)
    x_ref = R * (1 - np.cos(phi) + (1 - root) / lam)
    v_ref = w * R * (np.sin(phi) + lam / 2 * np.sin(2 * phi) / root)
    kin = slider_kinematics(phi, R, L, w)
    np.testing.assert_allclose(kin.x, x_ref, atol=1e-12 * R)
    np.testing.assert_allclose(kin.velocity, v_ref, atol=1e-12 * w * R)
    # TDC / BDC accelerations: r w^2 (1 + lam), -r w^2 (1 - lam) (exact at the dead centres)
    k2 = slider_kinematics(np.array([0.0, np.pi]), R, L, w)
    np.testing.assert_allclose(k2.acceleration, [R * w**2 * (1 + lam), -R * w**2 * (1 - lam)])
    # rod angular velocity at TDC: -omega lam (bearings.md sec. 1.1, omega_rod = -omega lam cos /
    # sqrt(...)), rod swings against the crank
    np.testing.assert_allclose(k2.rod_omega, [-w * lam, w * lam])


@pytest.mark.parametrize(("e_cyl", "e_pin"), OFFSETS)
def test_dead_centres_and_stroke(e_cyl, e_pin):
    # Rod and crank collinear at the dead centres: velocity zero, x = 0 at TDC and x = stroke at
    # BDC; brute-force extremes of the independent vector construction agree to 1e-9 m.
    e = e_cyl - e_pin  # pin offset towards the major thrust side = -t
    tdc, bdc, stroke = dead_centres(R, L, e_cyl, e_pin)
    kin = slider_kinematics(np.array([tdc, bdc]), R, L, 1.0, e_cyl, e_pin)
    np.testing.assert_allclose(kin.dx_dtheta, 0.0, atol=1e-15)
    np.testing.assert_allclose(kin.x, [0.0, stroke], atol=1e-15)
    c_p, _ = _vector_construction(np.linspace(0, 2 * np.pi, 720001), R, L, e)
    np.testing.assert_allclose(stroke, c_p.max() - c_p.min(), atol=1e-9)
    if e != 0:
        assert stroke > 2 * R  # offset lengthens the stroke
        assert np.sign(tdc) == np.sign(e)
    else:
        np.testing.assert_allclose([tdc, bdc, stroke], [0.0, np.pi, 2 * R], atol=1e-15)


def test_vectorized_over_angle_and_speed():
    # Broadcasting (speed, angle): acceleration scales with omega^2 exactly.
    phi = cycle_grid(np.deg2rad(2.0))
    w = np.array([100.0, 200.0, 400.0])[:, None]
    kin = slider_kinematics(phi, R, L, w, 0.0, 0.8 * MM)
    assert kin.acceleration.shape == (3, phi.size)
    np.testing.assert_allclose(kin.acceleration[2], 16 * kin.acceleration[0], rtol=1e-14)
    np.testing.assert_allclose(kin.rod_alpha[1], 4 * kin.rod_alpha[0], rtol=1e-14)


def test_invalid_geometry_raises():
    with pytest.raises(ValueError, match="rod_length"):
        slider_kinematics(0.0, R, R + 5 * MM, 1.0, 6 * MM)
    with pytest.raises(ValueError, match="crank_radius"):
        slider_kinematics(0.0, -R, L)
    with pytest.raises(ValueError, match="omega"):
        slider_kinematics(0.0, R, L, -1.0)
    with pytest.raises(ValueError, match="finite"):
        slider_kinematics(np.nan, R, L)


def test_cycle_grid_and_default_step():
    # Convention (docs/calc-conventions.md): theta_k = k * 4 pi / N without the end point.
    g = cycle_grid(np.deg2rad(0.5))
    assert g.size == 1440 and g[0] == 0.0
    np.testing.assert_allclose(g[-1] + np.deg2rad(0.5), FOUR_STROKE_CYCLE)
    assert cycle_grid().size == round(720 / DEFAULT_STEP_DEG)
    np.testing.assert_allclose(DEFAULT_STEP, np.deg2rad(DEFAULT_STEP_DEG))
    with pytest.raises(ValueError, match="integer"):
        cycle_grid(np.deg2rad(0.7))


def test_pin_offset_towards_the_major_thrust_side_advances_tdc():
    # Workbook convention: pin offset towards the major thrust side positive. By hand: the
    # major thrust side is -t (module docstring), so a pin offset a > 0 puts the piston pin on
    # the line t = -a. TDC is where crank and rod are in line, the crank pointing at the pin:
    # sin(phi_TDC) = -a/(l + r), i.e. -0.2375 deg for a = 0.8 mm on the example engine (TDC
    # before the geometric reference); BDC: the crank points away from the pin,
    # phi_BDC = pi - asin(a/(l - r)). At phi = 0 the crank pin is on the bore-parallel line,
    # the pin at -a: the rod leans with sin(beta) = a/l > 0 (big end on the +t side of the
    # pin). Exact relations, tolerance 1e-12.
    a = 0.8 * MM
    tdc, bdc, _ = dead_centres(R, L, 0.0, a)
    assert tdc < 0 and np.degrees(tdc) == pytest.approx(-0.2375, abs=5e-5)
    assert tdc == pytest.approx(-np.arcsin(a / (L + R)), rel=1e-12)
    assert bdc == pytest.approx(np.pi - np.arcsin(a / (L - R)), rel=1e-12)
    kin = slider_kinematics(np.array([0.0]), R, L, 1.0, 0.0, a)
    assert kin.beta[0] == pytest.approx(np.arcsin(a / L), rel=1e-12)
    # towards the minor thrust side (negative): the mirror image, TDC after the reference
    tdc_minor, _, _ = dead_centres(R, L, 0.0, -a)
    assert tdc_minor == pytest.approx(-tdc, rel=1e-12)
    # a cylinder offset along +t equal to the pin offset cancels it (e = c - a = 0)
    np.testing.assert_allclose(dead_centres(R, L, a, a), (0.0, np.pi, 2 * R), atol=1e-15)
