"""Crank-train forces: gas and inertia forces, big-end bearing loads, crank torque, main loads.

Frames (all plane, all right-angled; every frame has a reference axis ``y`` and an axis ``x`` at
+90 deg from it **in the direction of crank rotation**, so ``angle = atan2(x, y)`` is measured
from ``y`` in the direction of rotation):

* **block** (engine) frame: ``y`` along the axis of a cylinder of bank angle 0, pointing from the
  crank axis toward the head; ``x`` the way the crank pin moves when passing the top. With the
  crank turning clockwise seen from the front (example engine) ``x`` points right, ``y`` up.
* **cylinder** frame ``(t, c)`` of :mod:`checker.calc.kinematics`: the block frame turned by the
  cylinder's bank angle ``alpha`` (``c`` = its bore axis, ``t`` = the +90 deg axis).
* **crank** frame: fixed to the crankshaft, coincides with the block frame at ``theta = 0``
  (firing TDC of cylinder 1); at crank angle ``theta`` it is the block frame turned by
  ``theta``. A throw whose pin points along crank-frame angle ``gamma`` is at block angle
  ``gamma + theta``; cylinder ``i`` (bank ``alpha_i``, firing angle ``phi_i``) has its throw at
  ``gamma_i = alpha_i - phi_i`` (:func:`throw_angles`).
* **rod** frame: fixed to the con-rod, ``y`` along the rod centre line from the big-end centre to
  the small-end centre, ``x`` +90 deg from it in the direction of rotation.

Cylinder ``i`` fires ``phi_i`` after cylinder 1; its kinematic crank angle is ``theta - phi_i``.

Sign of bearing loads: a **bearing load is the force the journal exerts on the bearing shell**
(Booker's journal load, what a mobility solution takes): big end = force of the crank pin on the
con-rod's big-end bearing; main bearing = force of the main journal on the block's bearing. The
force of a rod on its crank pin is the negative of its big-end load. Torque is positive when it
drives the crankshaft in its direction of rotation.

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013, "Concept
   level bearing analysis assumptions" (statically determinate main loads, example engine masses).
.. [2] M. Agostini, "Powertrain Components Design - Engine", course notes, Master Degree in
   Automotive Engineering, Politecnico di Torino, 2019 (A.Y. 2018-2019), ch. 1 "Dynamics" (two-mass
   con-rod, inertia forces).
.. [3] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546 (journal load convention).
.. [4] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, sec. 2.2 (gas
   torque of a centred slider crank).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from checker.calc.kinematics import FOUR_STROKE_CYCLE, slider_kinematics

__all__ = [
    "CylinderLoads",
    "Vector2",
    "block_to_crank",
    "crank_to_block",
    "crankpin_force",
    "cylinder_loads",
    "main_bearing_loads",
    "mass_positions",
    "rod_mass_split",
    "rotate_frame",
    "throw_angles",
]


class Vector2(NamedTuple):
    """Plane vector field as two component arrays of equal shape.

    Attributes
    ----------
    x, y : numpy.ndarray
        Components in the frame named by the producing function (module docstring).
    """

    x: np.ndarray
    y: np.ndarray

    @property
    def magnitude(self) -> np.ndarray:
        """``|v|``, same shape as the components."""
        return np.hypot(self.x, self.y)

    @property
    def angle(self) -> np.ndarray:
        """Direction [rad], ``atan2(x, y)``: from the frame's ``y`` axis in the direction of
        crank rotation, in ``(-pi, pi]``."""
        return np.arctan2(self.x, self.y)


def rotate_frame(v: Vector2, angle: ArrayLike) -> Vector2:
    """Components of ``v`` in a frame turned by ``angle`` (direction of rotation) from its own.

    ``x' = x cos(g) - y sin(g)``, ``y' = x sin(g) + y cos(g)`` with ``g = angle``.

    Parameters
    ----------
    v : Vector2
        Components in the original frame.
    angle : array_like [rad]
        Angle of the new frame's ``y`` axis measured from the old one in the direction of
        rotation; broadcast with the components.

    Returns
    -------
    Vector2
    """
    g = np.asarray(angle, dtype=float)
    c, s = np.cos(g), np.sin(g)
    return Vector2(v.x * c - v.y * s, v.x * s + v.y * c)


def block_to_crank(v: Vector2, theta: ArrayLike) -> Vector2:
    """Block-frame components -> crank-frame components at crank angle ``theta`` [rad]."""
    return rotate_frame(v, theta)


def crank_to_block(v: Vector2, theta: ArrayLike) -> Vector2:
    """Crank-frame components -> block-frame components at crank angle ``theta`` [rad]."""
    return rotate_frame(v, -np.asarray(theta, dtype=float))


def rod_mass_split(
    rod_mass: ArrayLike,
    rod_length: ArrayLike,
    rod_cg_from_big_end: ArrayLike,
    rod_inertia: ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two-mass equivalent of a con-rod and its inertia correction.

    ``m_a = m l_g / l`` (small end, reciprocating), ``m_b = m (l - l_g)/l`` (big end, rotating),
    ``dI = m l_g (l - l_g) - I_G`` with ``l_g`` the centre-of-mass distance from the big end.

    Parameters
    ----------
    rod_mass : array_like [kg]
    rod_length : array_like [m]
    rod_cg_from_big_end : array_like [m]
        ``0 < l_g < l``.
    rod_inertia : array_like [kg*m^2]
        Moment of inertia about the centre of mass, ``I_G > 0``.

    Returns
    -------
    small_end_mass, big_end_mass : numpy.ndarray [kg]
    inertia_excess : numpy.ndarray [kg*m^2]
        ``dI`` = inertia of the two point masses about the centre of mass minus the true ``I_G``
        (usually > 0: the two-mass model overstates the rotary inertia).

    Notes
    -----
    The two masses reproduce the rod's mass and centre of mass, hence its inertia *force*,
    exactly; their inertia ``m_a (l - l_g)^2 + m_b l_g^2 = m l_g (l - l_g)`` generally differs
    from ``I_G``, so a correction couple ``dI * rod_alpha`` must act on the rod (Agostini,
    Powertrain Components Design, Politecnico di Torino, 2019, "Dynamics": ``J_0 = J_cr - m x1
    x2``, ``J_0 = -dI``). Example engine: m = 0.597 kg, l = 145.7 mm, l_g = 35.73 mm:
    m_a = 0.1464 kg (piston + m_a = 0.6419 kg, the reciprocating mass of Bell, Ricardo 2013),
    two-mass inertia 2346 vs I_G = 2128 kg mm^2.
    """
    m = np.asarray(rod_mass, dtype=float)
    l = np.asarray(rod_length, dtype=float)
    lg = np.asarray(rod_cg_from_big_end, dtype=float)
    ig = np.asarray(rod_inertia, dtype=float)
    if np.any(m < 0) or np.any(ig < 0):
        raise ValueError("rod_mass and rod_inertia must be >= 0")
    if np.any(lg <= 0) or np.any(lg >= l):
        raise ValueError("rod_cg_from_big_end must lie strictly between 0 and rod_length")
    m_a = m * lg / l
    return m_a, m - m_a, m * lg * (l - lg) - ig


class CylinderLoads(NamedTuple):
    """Forces of each cylinder's crank slider; every array has shape ``(..., n_cyl, N)``.

    ``inertia_force`` and ``rod_omega`` do not depend on the pressure; where ``pressure`` has more
    leading axes than ``omega`` they are read-only broadcast views (copy before writing).

    Attributes
    ----------
    gas_force : numpy.ndarray [N]
        ``(p - p_cc) A`` on the piston, positive pushing the piston toward the crank.
    inertia_force : numpy.ndarray [N]
        d'Alembert force of the reciprocating mass (piston assembly + rod small-end share),
        ``-m_rec x_ddot``, positive toward the crank.
    side_force : numpy.ndarray [N]
        Force of the piston on the liner along ``+t`` of the cylinder frame (negative = toward
        the major thrust side during expansion).
    torque : numpy.ndarray [N*m]
        Crank torque of the cylinder (gas + inertia), positive driving.
    big_end_block, big_end_crank, big_end_rod : Vector2 [N]
        Big-end bearing load (force of the crank pin on the rod's big-end bearing) in the block,
        crank and rod frames.
    rod_omega : numpy.ndarray [rad/s]
        Absolute angular velocity of the con-rod (positive in the direction of rotation); the
        big-end bearing sees journal speed ``omega`` and bearing speed ``rod_omega``.
    """

    gas_force: np.ndarray
    inertia_force: np.ndarray
    side_force: np.ndarray
    torque: np.ndarray
    big_end_block: Vector2
    big_end_crank: Vector2
    big_end_rod: Vector2
    rod_omega: np.ndarray


def _cycle_step(theta: np.ndarray) -> float:
    n = theta.size
    if theta.ndim != 1 or n < 8:
        raise ValueError("theta must be a 1-D cycle grid with at least 8 points")
    step = FOUR_STROKE_CYCLE / n
    if not np.allclose(theta, np.arange(n) * step, rtol=0.0, atol=1e-9):
        raise ValueError("theta must be the uniform cycle grid k*4*pi/N (kinematics.cycle_grid)")
    return step


def _per_cyl(value: ArrayLike, n_cyl: int, name: str) -> np.ndarray:
    a = np.asarray(value, dtype=float)
    try:
        a = np.broadcast_to(a, (n_cyl,))
    except ValueError:
        raise ValueError(f"{name} must be a scalar or have one value per cylinder") from None
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return a


def _phase(p: np.ndarray, firing: np.ndarray, step: float) -> np.ndarray:
    """``p_i(theta_k - phi_i)`` by exact index shift or periodic linear interpolation."""
    n = p.shape[-1]
    shift = firing / step
    n0 = np.floor(shift + 1e-9)
    frac = np.clip(shift - n0, 0.0, None)
    k = np.arange(n)
    idx0 = np.mod(k[None, :] - n0[:, None].astype(int), n)  # (n_cyl, N)
    if p.shape[-2] == 1:
        p0 = p[..., 0, :][..., idx0]
    else:
        p0 = np.take_along_axis(p, np.broadcast_to(idx0, p.shape), axis=-1)
    if np.all(frac < 1e-9):
        return p0
    idx1 = np.mod(idx0 - 1, n)
    if p.shape[-2] == 1:
        p1 = p[..., 0, :][..., idx1]
    else:
        p1 = np.take_along_axis(p, np.broadcast_to(idx1, p.shape), axis=-1)
    f = frac[:, None]
    return p0 * (1.0 - f) + p1 * f


def cylinder_loads(
    theta: ArrayLike,
    omega: ArrayLike,
    pressure: ArrayLike,
    *,
    bore: ArrayLike,
    crank_radius: ArrayLike,
    rod_length: ArrayLike,
    piston_mass: ArrayLike,
    rod_mass: ArrayLike,
    rod_cg_from_big_end: ArrayLike,
    rod_inertia: ArrayLike,
    firing_angle: ArrayLike,
    bank_angle: ArrayLike = 0.0,
    cylinder_offset: ArrayLike = 0.0,
    pin_offset: ArrayLike = 0.0,
    crankcase_pressure: float = 1.0e5,
) -> CylinderLoads:
    """Gas/inertia forces, big-end loads and crank torque of every cylinder over the cycle.

    Model: piston assembly + rod small-end mass ``m_a`` translate with the piston pin; rod
    big-end mass ``m_b`` rotates with the crank pin; a massless link between them carries the
    correction couple ``C = dI * rod_alpha`` (direction-of-rotation sense, ``rod_alpha`` of
    :class:`~checker.calc.kinematics.SliderKinematics`) that restores the rod's true moment of
    inertia (:func:`rod_mass_split`). This is the exact rigid-body dynamics of the slider,
    written in the two-mass form. In the cylinder frame ``(t, c)`` with ``u = (-sin b, cos b)``
    (rod, big end -> small end) and ``n = (cos b, sin b)``::

        F       = (p - p_cc) A - m_rec omega^2 x''        axial force on the pin, toward crank
        L_n     = C / l = -dI omega^2 beta'' / l          transverse link force from the couple
        L_u     = (F - L_n sin b) / cos b                 link force along the rod
        L       = L_u u + L_n n                           force of the link on the piston
        big end = L + m_b a_B,   a_B = -omega^2 r (sin phi, cos phi)
        torque  = r (sin phi, cos phi) x big_end  (= r sin phi be_c - r cos phi be_t)
        side    = L_t

    With zero offsets and no masses the torque is ``(p - p_cc) A r sin(phi) [1 + lam cos(phi) /
    sqrt(1 - lam^2 sin^2 phi)]`` (Heywood 1988, sec. 2.2); at TDC without gas the big-end load is
    ``-(m_rec (1 + lam) + m_b) r omega^2`` along ``c`` (Agostini, Powertrain Components Design,
    Politecnico di Torino, 2019, "Dynamics").

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Uniform cycle grid ``k*4*pi/N`` (crank angle from firing TDC of cylinder 1).
    omega : array_like, shape (...) [rad/s]
        Constant crank speed; broadcast against the leading axes ``...`` of ``pressure``.
    pressure : array_like, shape (..., n_cyl or 1, N) [Pa]
        Absolute cylinder pressure of each cylinder **versus its own cycle angle** (from its own
        firing TDC) on the grid ``theta``; a size-1 cylinder axis uses the same trace for all.
        It is phased here: cylinder ``i`` sees ``p_i(theta - phi_i)``.
    bore : array_like, () or (n_cyl,) [m]
    crank_radius, rod_length : array_like, () or (n_cyl,) [m]
    piston_mass : array_like, () or (n_cyl,) [kg]
        Piston assembly (piston, rings, pin, clips).
    rod_mass : array_like, () or (n_cyl,) [kg]
        Con-rod including bolts and bearing shells.
    rod_cg_from_big_end : array_like, () or (n_cyl,) [m]
        Distance of the rod's centre of mass from the big-end centre.
    rod_inertia : array_like, () or (n_cyl,) [kg*m^2]
        Rod moment of inertia about its centre of mass.
    firing_angle : array_like, shape (n_cyl,) [rad]
        ``phi_i``, crank angle of cylinder ``i``'s firing TDC after cylinder 1's (example I4,
        firing order 1-3-4-2: 0, 3*pi, pi, 2*pi); fractions of the grid step are interpolated.
    bank_angle : array_like, () or (n_cyl,) [rad]
        ``alpha_i``, bore axis direction in the block frame (from ``y``, direction of rotation).
    cylinder_offset, pin_offset : array_like, () or (n_cyl,) [m]
        As in :func:`checker.calc.kinematics.slider_kinematics`.
    crankcase_pressure : float [Pa]
        Pressure under the piston (default 1.0e5, ventilated crankcase).

    Returns
    -------
    CylinderLoads
        Arrays of shape ``broadcast(omega.shape, pressure.shape[:-2]) + (n_cyl, N)``.

    Notes
    -----
    Rigid links, constant crank speed, no friction, gravity neglected. Rods sharing a crank pin
    (V engines) are separate cylinders here; combine them with :func:`crankpin_force` or
    :func:`main_bearing_loads` through their pin index. Validity of the slider geometry as in
    :func:`~checker.calc.kinematics.slider_kinematics`.
    """
    th = np.asarray(theta, dtype=float)
    step = _cycle_step(th)
    phi = np.asarray(firing_angle, dtype=float)
    if phi.ndim != 1 or phi.size < 1 or not np.all(np.isfinite(phi)):
        raise ValueError("firing_angle must be a finite 1-D array (one value per cylinder)")
    n_cyl = phi.size
    phi = np.mod(phi, FOUR_STROKE_CYCLE)
    geo = {
        name: _per_cyl(val, n_cyl, name)
        for name, val in (
            ("bore", bore),
            ("crank_radius", crank_radius),
            ("rod_length", rod_length),
            ("piston_mass", piston_mass),
            ("rod_mass", rod_mass),
            ("rod_cg_from_big_end", rod_cg_from_big_end),
            ("rod_inertia", rod_inertia),
            ("bank_angle", bank_angle),
            ("cylinder_offset", cylinder_offset),
            ("pin_offset", pin_offset),
        )
    }
    if np.any(geo["bore"] <= 0) or np.any(geo["piston_mass"] < 0):
        raise ValueError("bore must be > 0 m and piston_mass >= 0 kg")
    p = np.asarray(pressure, dtype=float)
    if p.ndim < 2 or p.shape[-1] != th.size or p.shape[-2] not in (1, n_cyl):
        raise ValueError(
            f"pressure must have shape (..., {n_cyl} or 1, {th.size}), got {p.shape}"
        )
    if not np.all(np.isfinite(p)) or np.any(p < 0):
        raise ValueError("pressure must be finite and >= 0 Pa (absolute)")
    w = np.asarray(omega, dtype=float)
    if not np.all(np.isfinite(w)) or np.any(w < 0):
        raise ValueError("omega must be finite and >= 0 rad/s")

    col = {name: val[:, None] for name, val in geo.items()}  # (n_cyl, 1)
    r, l = col["crank_radius"], col["rod_length"]
    m_a, m_b, d_i = rod_mass_split(
        col["rod_mass"], l, col["rod_cg_from_big_end"], col["rod_inertia"]
    )
    m_rec = col["piston_mass"] + m_a
    area = np.pi / 4.0 * col["bore"] ** 2

    ang = th[None, :] - phi[:, None]  # kinematic crank angle per cylinder (n_cyl, N)
    kin = slider_kinematics(ang, r, l, 0.0, col["cylinder_offset"], col["pin_offset"])
    sb, cb = np.sin(kin.beta), np.cos(kin.beta)
    sp, cp = np.sin(ang), np.cos(ang)

    w2 = (w**2)[..., None, None]
    gas = (_phase(p, phi, step) - crankcase_pressure) * area  # (..., n_cyl, N)
    inertia = -m_rec * kin.d2x_dtheta2 * w2
    axial = gas + inertia
    l_n = (-d_i * kin.d2beta_dtheta2 / l) * w2
    l_u = (axial - l_n * sb) / cb
    l_t = -l_u * sb + l_n * cb
    cen = m_b * r * w2  # big-end mass centripetal term
    be_t = l_t - cen * sp
    be_c = axial - cen * cp
    torque = r * (sp * be_c - cp * be_t)

    be_local = Vector2(be_t, be_c)
    alpha = col["bank_angle"]
    big_block = rotate_frame(be_local, -alpha)
    big_crank = rotate_frame(be_local, th[None, :] - alpha)
    big_rod = rotate_frame(be_local, -kin.beta)
    rod_omega = np.broadcast_to(-kin.dbeta_dtheta * np.sqrt(w2), torque.shape)
    return CylinderLoads(
        gas_force=gas,
        inertia_force=np.broadcast_to(inertia, torque.shape),
        side_force=l_t,
        torque=torque,
        big_end_block=big_block,
        big_end_crank=big_crank,
        big_end_rod=big_rod,
        rod_omega=rod_omega,
    )


def throw_angles(
    firing_angle: ArrayLike, bank_angle: ArrayLike, pin_index: ArrayLike, n_pins: int
) -> np.ndarray:
    """Crank-frame direction of each crank throw from the cylinders' firing and bank angles.

    ``gamma_j = alpha_i - phi_i (mod 2 pi)`` for every cylinder ``i`` on pin ``j``.

    Parameters
    ----------
    firing_angle : array_like, shape (n_cyl,) [rad]
    bank_angle : array_like, () or (n_cyl,) [rad]
    pin_index : array_like of int, shape (n_cyl,)
        Crank pin (= bay) of each cylinder, ``0 .. n_pins-1``.
    n_pins : int
        Number of crank pins (throws).

    Returns
    -------
    numpy.ndarray, shape (n_pins,) [rad]
        In ``[0, 2 pi)``; use it to place crank-pin masses (``r (sin g, cos g)`` in the crank
        frame).

    Notes
    -----
    Raises ``ValueError`` if cylinders sharing a pin imply different directions (inconsistent
    firing/bank angles) or a pin carries no cylinder. Example I4 (1-3-4-2): 0, pi, pi, 0.
    """
    phi = np.asarray(firing_angle, dtype=float)
    n_cyl = phi.size
    alpha = _per_cyl(bank_angle, n_cyl, "bank_angle")
    pins = _pin_index(pin_index, n_cyl, n_pins)
    gam = np.mod(alpha - phi, 2 * np.pi)
    out = np.full(n_pins, np.nan)
    for j in range(n_pins):
        g = gam[pins == j]
        if g.size == 0:
            raise ValueError(f"crank pin {j} carries no cylinder")
        d = np.angle(np.exp(1j * (g - g[0])))
        if np.any(np.abs(d) > 1e-6):
            raise ValueError(
                f"cylinders on pin {j} imply different throw directions "
                f"{np.rad2deg(g)} deg: check firing and bank angles"
            )
        out[j] = g[0]
    return out


def mass_positions(
    lateral: ArrayLike, radial: ArrayLike, throw_index: ArrayLike, pin_axis: ArrayLike,
    throw_angle: ArrayLike, crank_radius: float,
) -> np.ndarray:
    """Crank-frame centres of mass of crank components given in the throw-1 frame.

    The workbook (sheet CrankMass) gives each centre of mass as ``Y`` along throw 1 and ``Z``
    +90 deg from it in the direction of rotation, from the main axis or from its own crank
    pin's axis. Throw 1 points at crank-frame angle ``gamma_1`` (:func:`throw_angles`; 0 for an
    in-line engine whose cylinder 1 is upright, the bank angle of cylinder 1 for a V engine),
    so the point is turned by ``gamma_1``; a pin-axis point is then moved by the pin position
    ``r (sin gamma_j, cos gamma_j)`` of its throw ``j``::

        x = Z cos g1 + Y sin g1,   y = Y cos g1 - Z sin g1   (+ r e_j for pin-axis points)

    Parameters
    ----------
    lateral, radial : array_like, shape (n_m,) [m]
        ``Z`` and ``Y`` of each component.
    throw_index : array_like of int, shape (n_m,)
        Throw ``0..n_pins-1`` of each component.
    pin_axis : array_like of bool, shape (n_m,)
        True where the coordinates are relative to the pin axis.
    throw_angle : array_like, shape (n_pins,) [rad]
        ``gamma_j`` of every throw.
    crank_radius : float [m]

    Returns
    -------
    numpy.ndarray, shape (n_m, 2) [m]
        ``(x, y)`` in the crank frame, from the main axis.
    """
    zl = np.asarray(lateral, dtype=float).ravel()
    yr = np.asarray(radial, dtype=float).ravel()
    j = np.asarray(throw_index, dtype=int).ravel()
    pa = np.asarray(pin_axis, dtype=bool).ravel()
    gam = np.asarray(throw_angle, dtype=float).ravel()
    if not (zl.size == yr.size == j.size == pa.size):
        raise ValueError("lateral, radial, throw_index and pin_axis must match")
    if j.size and (j.min() < 0 or j.max() >= gam.size):
        raise ValueError(f"throw_index must lie in 0..{gam.size - 1}")
    g1 = gam[0] if gam.size else 0.0
    c, s = np.cos(g1), np.sin(g1)
    out = np.stack([zl * c + yr * s, yr * c - zl * s], axis=-1)
    if j.size:
        e = np.stack([np.sin(gam[j]), np.cos(gam[j])], axis=-1)
        out = out + np.where(pa[:, None], float(crank_radius) * e, 0.0)
    return out


def _pin_index(pin_index: ArrayLike, n_cyl: int, n_pins: int) -> np.ndarray:
    pins = np.asarray(pin_index)
    if pins.shape != (n_cyl,) or not np.issubdtype(pins.dtype, np.integer):
        raise ValueError("pin_index must be an integer array with one entry per cylinder")
    if np.any(pins < 0) or np.any(pins >= n_pins):
        raise ValueError(f"pin_index must lie in 0..{n_pins - 1}")
    return pins


def crankpin_force(big_end: Vector2, pin_index: ArrayLike, n_pins: int) -> Vector2:
    """Total force of the con-rods on each crank pin (rods sharing a pin are summed).

    ``F_pin_j = -sum_{i on pin j} big_end_i`` (a big-end load acts on the rod; the pin gets the
    opposite).

    Parameters
    ----------
    big_end : Vector2, components of shape (..., n_cyl, N) [N]
        Big-end loads in any one frame (:class:`CylinderLoads`).
    pin_index : array_like of int, shape (n_cyl,)
    n_pins : int

    Returns
    -------
    Vector2, components of shape (..., n_pins, N) [N], same frame as ``big_end``.
    """
    n_cyl = big_end.x.shape[-2]
    pins = _pin_index(pin_index, n_cyl, n_pins)
    inc = (pins[None, :] == np.arange(n_pins)[:, None]).astype(float)  # (n_pins, n_cyl)
    return Vector2(-(inc @ big_end.x), -(inc @ big_end.y))


def main_bearing_loads(
    theta: ArrayLike,
    omega: ArrayLike,
    big_end_block: Vector2,
    *,
    pin_index: ArrayLike,
    rod_axial_position: ArrayLike,
    bay_length: ArrayLike,
    mass: ArrayLike,
    mass_bay: ArrayLike,
    mass_position: ArrayLike,
    mass_axial_position: ArrayLike,
) -> Vector2:
    """Main bearing loads by the statically determinate (simply supported bay) method.

    Each bay ``j`` (throw ``j``) is a rigid beam pin-jointed at main ``j`` and main ``j+1``
    (Bell, Ricardo 2013, "Concept level bearing analysis assumptions": each main carries only the
    adjacent
    throws; load sharing with distant mains ignored). A force ``F`` at axial position ``z`` from
    main ``j`` in a bay of length ``L_j`` loads main ``j`` with ``F (1 - z/L_j)`` and main
    ``j+1`` with ``F z/L_j`` (lever rule). Forces on the crank in bay ``j``:

    * the con-rod forces on pin ``j`` (``-big_end`` of each rod on it), each at its own axial
      position (two rods side by side on one pin of a V engine);
    * the centrifugal forces ``m omega^2 rho`` of the bay's rotating masses (webs,
      counterweights, crank pin; ``rho`` = centre-of-mass position in the crank frame relative to
      the main axis), turned into the block frame at ``theta``.

    Main ``k`` (``0..n_pins``) receives the right-hand share of bay ``k-1`` and the left-hand
    share of bay ``k``.

    Parameters
    ----------
    theta : array_like, shape (N,) [rad]
        Crank angle grid (crank frame = block frame at ``theta = 0``).
    omega : array_like, shape (...) [rad/s]
        Constant crank speed, broadcast with the leading axes of ``big_end_block``.
    big_end_block : Vector2, components of shape (..., n_cyl, N) [N]
        Big-end loads in the block frame (:func:`cylinder_loads`).
    pin_index : array_like of int, shape (n_cyl,)
        Pin / bay of each cylinder, ``0..n_pins-1``.
    rod_axial_position : array_like, () or (n_cyl,) [m]
        Axial position of each rod's big-end centre from the bay's first main (mid-bay for an
        in-line engine).
    bay_length : array_like, shape (n_pins,) [m]
        Distance between main ``j`` and main ``j+1``.
    mass : array_like, shape (n_m,) [kg]
        Rotating crankshaft masses (webs, counterweights, crank pins).
    mass_bay : array_like of int, shape (n_m,)
        Bay each mass belongs to.
    mass_position : array_like, shape (n_m, 2) [m]
        Centre of mass ``(x, y)`` in the crank frame relative to the main-bearing axis.
    mass_axial_position : array_like, shape (n_m,) [m]
        Axial position from the bay's first main (values outside ``[0, L_j]`` act as overhangs
        and are shared by the lever rule).

    Returns
    -------
    Vector2, components of shape (..., n_pins + 1, N) [N]
        Load on each main bearing (force of the journal on the bearing) in the block frame.

    Notes
    -----
    Rigid crankshaft and bearings, gravity, flywheel/pulley and belt loads neglected (Bell, Ricardo
    2013
    concept-level assumptions). ``n_pins + 1`` mains; the rod's big-end mass is already in the
    big-end load, so it must not be repeated in ``mass``.
    """
    th = np.asarray(theta, dtype=float)
    bx, by = np.asarray(big_end_block.x), np.asarray(big_end_block.y)
    if bx.ndim < 2 or bx.shape[-1] != th.size:
        raise ValueError("big_end_block components must have shape (..., n_cyl, N) matching theta")
    n_cyl = bx.shape[-2]
    lengths = np.asarray(bay_length, dtype=float)
    if lengths.ndim != 1 or np.any(~np.isfinite(lengths)) or np.any(lengths <= 0):
        raise ValueError("bay_length must be a 1-D array of lengths > 0 m (one per bay)")
    n_pins = lengths.size
    pins = _pin_index(pin_index, n_cyl, n_pins)
    z_rod = _per_cyl(rod_axial_position, n_cyl, "rod_axial_position")
    m = np.asarray(mass, dtype=float)
    bays = np.asarray(mass_bay)
    rho = np.asarray(mass_position, dtype=float)
    z_m = np.asarray(mass_axial_position, dtype=float)
    n_m = m.size
    if m.shape != (n_m,) or bays.shape != (n_m,) or z_m.shape != (n_m,) or rho.shape != (n_m, 2):
        raise ValueError("mass, mass_bay, mass_axial_position (n_m,) and mass_position (n_m, 2)")
    bad_bay = n_m and (
        not np.issubdtype(bays.dtype, np.integer) or bays.min() < 0 or bays.max() >= n_pins
    )
    if bad_bay:
        raise ValueError(f"mass_bay must be integers in 0..{n_pins - 1}")
    if np.any(m < 0) or not (np.all(np.isfinite(rho)) and np.all(np.isfinite(z_m))):
        raise ValueError("masses must be >= 0 kg with finite positions")
    w = np.asarray(omega, dtype=float)
    if not np.all(np.isfinite(w)) or np.any(w < 0):
        raise ValueError("omega must be finite and >= 0 rad/s")

    def shares(bay_of: np.ndarray, z: np.ndarray) -> np.ndarray:
        frac = z / lengths[bay_of]
        mat = np.zeros((n_pins + 1, bay_of.size))
        cols = np.arange(bay_of.size)
        np.add.at(mat, (bay_of, cols), 1.0 - frac)
        np.add.at(mat, (bay_of + 1, cols), frac)
        return mat

    w_rod = shares(pins, z_rod)  # (n_main, n_cyl)
    fx = -(w_rod @ bx)
    fy = -(w_rod @ by)
    if n_m:
        cf = shares(bays.astype(int), z_m) @ (m[:, None] * rho)  # (n_main, 2), crank frame / w^2
        c, s = np.cos(th), np.sin(th)
        w2 = (w**2)[..., None, None]
        fx = fx + w2 * (cf[:, :1] * c + cf[:, 1:] * s)
        fy = fy + w2 * (-cf[:, :1] * s + cf[:, 1:] * c)
    return Vector2(fx, fy)
