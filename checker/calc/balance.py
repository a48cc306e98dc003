"""Crankshaft balancing: free (shaking) forces and moments by order, rotating unbalance,
counterweight balance ratio and the internal bending moment of the rotating masses.

Frames and conventions are those of :mod:`checker.calc.crank_forces`: the block frame has
``y`` along the axis of a cylinder of bank angle 0 (crank axis toward the head) and ``x`` at
+90 deg in the direction of rotation; the crank frame coincides with it at ``theta = 0``
(firing TDC of cylinder 1); cylinder ``i`` (firing angle ``phi_i``, bank angle ``alpha_i``) has
its throw at crank-frame angle ``gamma_i = alpha_i - phi_i`` and its kinematic crank angle is
``theta - phi_i``. ``z`` is the axial position along the crank, front to rear.

Order phasors: a quantity of order ``n`` over the crank angle is ``Re{P_n exp(j n theta)}``;
a plane vector of order ``n`` has one complex phasor per component, ``(P_x, P_y)``. Forces and
moments are returned **per unit omega^2** (``kg m`` and ``kg m^2``); multiply by ``omega^2``.

Model (Taylor 1985, vol. 2, ch. 8; Norton, *Design of Machinery*, ch. 13-14): rigid crank
train at constant speed, con-rod as the two-mass equivalent of
:func:`checker.calc.crank_forces.rod_mass_split` (exact for the inertia *force*; its correction
couple is a roll torque about the crank axis, no free force or moment). The **free force** is
the resultant of all inertia forces the moving parts exert on the engine structure (the
shaking force), the **free moment** its moment about a transverse axis through the reference
plane ``z = 0``; gas forces are internal and do not appear.

* reciprocating mass ``m_rec`` of cylinder ``i``: ``F_i = m_rec omega^2 x''(theta - phi_i) c_i``
  with ``c_i = (sin alpha_i, cos alpha_i)`` its bore axis and ``x''`` = ``d^2x/dphi^2`` of
  :func:`checker.calc.kinematics.slider_kinematics` (displacement from TDC toward the crank):
  a piston decelerating at TDC pulls the engine toward the head;
* rotating masses (webs, counterweights, crank pins, rod big ends): ``F = omega^2 sum m rho``,
  ``rho`` the centre of mass in the crank frame turned into the block frame (first order only).

References
----------
.. [1] C. F. Taylor, "The Internal-Combustion Engine in Theory and Practice", Vol. 2, 1985, ch. 8
   (shaking forces and moments, balance factor, internal couple).
.. [2] R. L. Norton, "Design of Machinery", chs. 13-14, secs. 14.3, 14.5, 14.7 (balancing of in-line
   and V engines).
.. [3] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, eq. 2.5
   (slider-crank displacement).
.. [4] M. Agostini, "Powertrain Components Design - Engine", course notes, Master Degree in
   Automotive Engineering, Politecnico di Torino, 2019 (A.Y. 2018-2019), "Crankshaft"
   (counterweights).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from checker.calc._checks import finite, non_negative, positive
from checker.calc.kinematics import slider_kinematics

__all__ = [
    "BalanceOrders",
    "ThrowBalance",
    "crank_vector_phasor",
    "inherent_balance",
    "internal_bending_moment",
    "mean_throw_unbalance",
    "order_vector_extremes",
    "piston_acceleration_harmonics",
    "piston_acceleration_series",
    "shaking_phasors",
    "throw_balance",
]

DEFAULT_MAX_ORDER = 8
"""Highest order reported: the piston-acceleration harmonics fall as ``lam^(n-1)``; order 8 is
below 1e-4 of the first for ``lam <= 0.35``."""

_FFT_POINTS_PER_ORDER = 32


def piston_acceleration_harmonics(
    crank_radius: float, rod_length: float, offset: float = 0.0,
    max_order: int = DEFAULT_MAX_ORDER,
) -> np.ndarray:
    """Fourier coefficients of the exact piston acceleration per unit ``omega^2``.

    ``d^2x/dphi^2 = sum_{n=0}^{max_order} Re{A_n exp(j n phi)}`` with ``x`` the piston
    displacement from TDC toward the crank (:func:`checker.calc.kinematics.slider_kinematics`,
    exact, with offset). Computed by the discrete Fourier transform of the exact expression on
    ``32 max_order`` points per revolution; the harmonics decay like ``lam^n`` (``lam = r/l``),
    so aliasing is below round-off.

    Parameters
    ----------
    crank_radius : float [m]
    rod_length : float [m]
    offset : float [m]
        Total offset ``e`` = cylinder offset - pin offset (pin offset towards the major thrust
        side positive; :mod:`checker.calc.kinematics`), ``r + |e| < l``.
    max_order : int
        Highest order ``>= 1``.

    Returns
    -------
    numpy.ndarray, shape (max_order + 1,), complex [m/rad^2]
        ``A_0`` (0: the mean acceleration over a revolution vanishes) .. ``A_max``. Without
        offset the ``A_n`` are real,
        ``A_1 = r`` and only even orders follow (:func:`piston_acceleration_series`); an offset
        adds small odd orders and imaginary parts (sine terms).

    Notes
    -----
    Valid for ``0 < r``, ``r + |e| < l`` (checked by ``slider_kinematics``) and constant speed.
    """
    if int(max_order) != max_order or max_order < 1:
        raise ValueError(f"max_order must be a whole number >= 1, got {max_order!r}")
    n = _FFT_POINTS_PER_ORDER * int(max_order)
    phi = 2.0 * np.pi * np.arange(n) / n
    kin = slider_kinematics(phi, crank_radius, rod_length, 1.0, offset, 0.0)
    c = np.fft.rfft(kin.d2x_dtheta2) / n
    out = 2.0 * c[: int(max_order) + 1]
    out[0] = c[0].real
    return out


def piston_acceleration_series(crank_radius: float, rod_length: float,
                               max_order: int = 6) -> np.ndarray:
    """Classical power series of the piston-acceleration harmonics (no offset).

    ``d^2x/dphi^2 = r (cos phi + A_2 cos 2phi + A_4 cos 4phi + A_6 cos 6phi + ...)``::

        A_2 = lam + lam^3/4 + 15 lam^5/128,  A_4 = -(lam^3/4 + 3 lam^5/16),  A_6 = 9 lam^5/128

    (expansion of the exact slider-crank displacement, Heywood 1988 eq. 2.5, in powers of
    ``lam = r/l`` to ``lam^5``; Taylor 1985 vol. 2 ch. 8 keeps the first two terms,
    ``A_2 ~ lam``). Truncation error ``O(lam^7)``.

    Parameters
    ----------
    crank_radius, rod_length : float [m]
        ``0 < r < l``.
    max_order : int
        Highest order returned (orders above 6 are 0 at this truncation).

    Returns
    -------
    numpy.ndarray, shape (max_order + 1,) [m/rad^2]
        Real coefficients ``r A_n`` (``A_1 = 1``, odd orders above 1 are zero).
    """
    r = float(positive("crank_radius", crank_radius))
    l = float(positive("rod_length", rod_length))
    if r >= l:
        raise ValueError("crank_radius must be smaller than rod_length")
    lam = r / l
    a = np.zeros(int(max_order) + 1)
    coeffs = {1: 1.0, 2: lam + lam**3 / 4 + 15 * lam**5 / 128, 4: -(lam**3 / 4 + 3 * lam**5 / 16),
              6: 9 * lam**5 / 128}
    for k, v in coeffs.items():
        if k <= max_order:
            a[k] = r * v
    return a


def crank_vector_phasor(vector: ArrayLike) -> np.ndarray:
    """First-order block-frame phasors of a vector fixed in the crank frame.

    A crank-frame vector ``(u_x, u_y)`` seen in the block frame at crank angle ``theta`` is
    ``(u_x cos theta + u_y sin theta, -u_x sin theta + u_y cos theta)`` (the crank frame is the
    block frame turned by ``theta``, :func:`checker.calc.crank_forces.crank_to_block`), i.e.
    ``Re{(u_x - j u_y, u_y + j u_x) exp(j theta)}``.

    Parameters
    ----------
    vector : array_like, shape (..., 2) [any unit]

    Returns
    -------
    numpy.ndarray, shape (..., 2), complex
    """
    u = finite("vector", vector)
    return np.stack([u[..., 0] - 1j * u[..., 1], u[..., 1] + 1j * u[..., 0]], axis=-1)


class BalanceOrders(NamedTuple):
    """Free forces and moments per order, per unit ``omega^2``; order axis first.

    Attributes
    ----------
    orders : numpy.ndarray, shape (O,)
        1 .. max_order.
    force, force_reciprocating, force_rotating : numpy.ndarray, shape (O, 2), complex [kg m]
        Block-frame phasors ``(P_x, P_y)`` of the free force (total and its two parts; the
        rotating part is zero above order 1).
    moment, moment_reciprocating, moment_rotating : numpy.ndarray, shape (O, 2), complex
        [kg m^2]. Phasors ``(sum z F_x, sum z F_y)`` about the reference plane ``z = 0``: the
        moment of the ``x`` forces (about the ``y`` axis, yaw for an upright engine) and of
        the ``y`` forces (about the ``x`` axis, pitch).
    """

    orders: np.ndarray
    force: np.ndarray
    force_reciprocating: np.ndarray
    force_rotating: np.ndarray
    moment: np.ndarray
    moment_reciprocating: np.ndarray
    moment_rotating: np.ndarray


def shaking_phasors(
    *,
    firing_angle: ArrayLike,
    bank_angle: ArrayLike,
    cylinder_axial: ArrayLike,
    reciprocating_mass: ArrayLike,
    acceleration_harmonics: ArrayLike,
    rotating_mass: ArrayLike,
    rotating_position: ArrayLike,
    rotating_axial: ArrayLike,
) -> BalanceOrders:
    """Free force and free moment phasors of a multi-cylinder crank train by order.

    Order ``n >= 1`` (module docstring for the frames)::

        F_n = sum_i m_rec,i A_n exp(-j n phi_i) c_i               + [n = 1] sum_k m_k P(rho_k)
        M_n = sum_i m_rec,i A_n exp(-j n phi_i) z_i c_i           + [n = 1] sum_k m_k z_k P(rho_k)

    with ``c_i = (sin alpha_i, cos alpha_i)``, ``A_n`` the piston-acceleration harmonics
    (:func:`piston_acceleration_harmonics`) and ``P`` :func:`crank_vector_phasor`. This is the
    classical phase-diagram summation of the primary, secondary and higher-order inertia forces
    and their couples (Taylor 1985, vol. 2, ch. 8; Norton, *Design of Machinery*, secs. 14.3,
    14.5 and 14.7 for V engines), written with complex phasors so that any firing order, bank
    angle and crank (including uneven and split-pin layouts) is covered.

    Parameters
    ----------
    firing_angle : array_like, shape (n_cyl,) [rad]
        ``phi_i`` (0..4 pi; only ``n phi_i mod 2 pi`` matters, the free forces repeat every
        revolution).
    bank_angle : array_like, () or (n_cyl,) [rad]
        ``alpha_i``.
    cylinder_axial : array_like, shape (n_cyl,) [m]
        Axial position of each cylinder's rod (its crank pin) from the reference plane.
    reciprocating_mass : array_like, () or (n_cyl,) [kg]
        Piston assembly + rod small-end share.
    acceleration_harmonics : array_like, shape (O + 1,) or (n_cyl, O + 1), complex [m/rad^2]
        :func:`piston_acceleration_harmonics` (order 0 ignored).
    rotating_mass : array_like, shape (n_m,) [kg]
        Webs, counterweights, crank pins and the rods' big-end masses.
    rotating_position : array_like, shape (n_m, 2) [m]
        Centres of mass ``(x, y)`` in the crank frame relative to the crank axis.
    rotating_axial : array_like, shape (n_m,) [m]
        Axial positions from the reference plane.

    Returns
    -------
    BalanceOrders

    Notes
    -----
    Rigid crank train and block, constant speed; gravity and gas forces (internal) excluded.
    Free moments depend on the reference plane unless the free force of the same order is zero;
    the caller states the plane.
    """
    phi = finite("firing_angle", firing_angle).ravel()
    n_cyl = phi.size
    if n_cyl < 1:
        raise ValueError("at least one cylinder is needed")
    alpha = np.broadcast_to(finite("bank_angle", bank_angle), (n_cyl,))
    z = finite("cylinder_axial", cylinder_axial).ravel()
    if z.size != n_cyl:
        raise ValueError("cylinder_axial needs one value per cylinder")
    m_rec = np.broadcast_to(non_negative("reciprocating_mass", reciprocating_mass), (n_cyl,))
    a = np.asarray(acceleration_harmonics, dtype=complex)
    if not np.all(np.isfinite(a)):
        raise ValueError("acceleration_harmonics must be finite")
    a = np.broadcast_to(a, (n_cyl, a.shape[-1]))
    n_ord = a.shape[-1] - 1
    if n_ord < 1:
        raise ValueError("acceleration_harmonics must reach order 1 at least")
    m = non_negative("rotating_mass", rotating_mass).ravel()
    rho = finite("rotating_position", rotating_position).reshape(-1, 2)
    zm = finite("rotating_axial", rotating_axial).ravel()
    if not (m.size == rho.shape[0] == zm.size):
        raise ValueError("rotating_mass, rotating_position and rotating_axial must match")

    orders = np.arange(1, n_ord + 1)
    axis = np.stack([np.sin(alpha), np.cos(alpha)], axis=-1)  # (n_cyl, 2)
    amp = m_rec[:, None] * a[:, 1:] * np.exp(-1j * orders[None, :] * phi[:, None])  # (n_cyl, O)
    f_rec = np.einsum("io,ic->oc", amp, axis)
    m_rec_ph = np.einsum("io,ic->oc", amp * z[:, None], axis)
    f_rot = np.zeros((n_ord, 2), complex)
    m_rot = np.zeros((n_ord, 2), complex)
    if m.size:
        p = crank_vector_phasor(rho)  # (n_m, 2)
        f_rot[0] = (m[:, None] * p).sum(axis=0)
        m_rot[0] = ((m * zm)[:, None] * p).sum(axis=0)
    return BalanceOrders(orders, f_rec + f_rot, f_rec, f_rot, m_rec_ph + m_rot, m_rec_ph, m_rot)


def order_vector_extremes(phasors: ArrayLike, orders: ArrayLike
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Largest and smallest magnitude of an order-``n`` plane vector over the crank angle.

    ``v(theta) = Re{V exp(j n theta)}``, ``V = V_r + j V_i`` (two complex components) traces an
    ellipse: ``|v|^2 = (a + b)/2 + (a - b)/2 cos 2t - c sin 2t`` with ``t = n theta``,
    ``a = |V_r|^2``, ``b = |V_i|^2``, ``c = V_r . V_i``, so the semi-axes are
    ``sqrt((a + b)/2 +- sqrt(((a - b)/2)^2 + c^2))`` (exact).

    Parameters
    ----------
    phasors : array_like, shape (..., 2), complex
    orders : array_like, broadcast to ``phasors.shape[:-1]`` [-]
        ``n > 0``.

    Returns
    -------
    largest, smallest : numpy.ndarray
        Semi-major and semi-minor axes (unit of the phasors); ``smallest = largest`` for a
        vector of constant length rotating with the crank, ``smallest = 0`` for a force along a
        fixed line (e.g. an in-line engine's vertical secondary force).
    theta : numpy.ndarray [rad]
        First crank angle in ``[0, pi / n)`` at which the largest magnitude occurs (it recurs
        every ``pi / n`` with the opposite direction).
    direction : numpy.ndarray [rad]
        Direction of the vector there in the block frame, ``atan2(x, y)`` (from ``y``, in the
        direction of rotation).
    """
    v = np.asarray(phasors, dtype=complex)
    n = positive("orders", orders)
    vr, vi = v.real, v.imag
    a = (vr * vr).sum(-1)
    b = (vi * vi).sum(-1)
    c = (vr * vi).sum(-1)
    h = 0.5 * (a - b)
    root = np.sqrt(h * h + c * c)
    big = np.sqrt(np.maximum(0.5 * (a + b) + root, 0.0))
    small = np.sqrt(np.maximum(0.5 * (a + b) - root, 0.0))
    t = 0.5 * np.arctan2(-c, h)
    t = np.mod(t, np.pi)  # |v| has period pi in t (v(t + pi) = -v(t))
    t = np.where(np.pi - t < 1e-12, 0.0, t)  # -0 by round-off is the maximum at 0
    theta = t / n
    vec = vr * np.cos(n * theta)[..., None] - vi * np.sin(n * theta)[..., None]
    return big, small, theta, np.arctan2(vec[..., 0], vec[..., 1])


class ThrowBalance(NamedTuple):
    """Unbalance and counterweight balance per throw (crank frame, per unit omega^2).

    Attributes
    ----------
    rotating : numpy.ndarray, shape (n_throw, 2) [kg m]
        Unbalance ``sum m rho`` of the throw without counterweights: webs, crank pin and the
        rotating (big-end) mass of the rods on it.
    counterweight : numpy.ndarray, shape (n_throw, 2) [kg m]
        Unbalance of the throw's counterweights.
    rotating_along, counterweight_along : numpy.ndarray, shape (n_throw,) [kg m]
        Components along the throw direction (counterweights: along the opposite direction,
        positive when they oppose the throw).
    balance_ratio : numpy.ndarray, shape (n_throw,) [-]
        ``counterweight_along / rotating_along``: 1 = the throw's rotating unbalance is fully
        balanced within the throw.
    reciprocating_factor : numpy.ndarray, shape (n_throw,) [-]
        Fraction of the throw's reciprocating unbalance ``m_rec r`` that the counterweights
        balance on top of the rotating unbalance, ``(counterweight_along - rotating_along) /
        (m_rec r)`` (the single-cylinder "balance factor"; 0.5 is the classical choice).
    crank_ratio : float
        Whole crank: ``sum counterweight_along / sum rotating_along``.
    """

    rotating: np.ndarray
    counterweight: np.ndarray
    rotating_along: np.ndarray
    counterweight_along: np.ndarray
    balance_ratio: np.ndarray
    reciprocating_factor: np.ndarray
    crank_ratio: float


def throw_balance(
    *,
    throw_angle: ArrayLike,
    mass: ArrayLike,
    position: ArrayLike,
    throw_of_mass: ArrayLike,
    is_counterweight: ArrayLike,
    pin_rotating_mass: ArrayLike,
    pin_reciprocating_mass: ArrayLike,
    crank_radius: float,
) -> ThrowBalance:
    """Rotating unbalance and counterweight balance ratio of each crank throw.

    ``U_rot,j = sum_{k in j, not cw} m_k rho_k + m_b,j r e_j``, ``U_cw,j = sum_{k in j, cw} m_k
    rho_k``, ``e_j = (sin gamma_j, cos gamma_j)``; balance ratio ``-U_cw,j . e_j / U_rot,j .
    e_j`` (the percentage of the throw's rotating unbalance its own counterweights balance;
    100 % unloads the adjacent mains of the throw's centrifugal force, Agostini 2019,
    Politecnico di Torino, "Crankshaft": counterweights "balance and reduce the load on the
    main bearing"); the reciprocating factor is the single-cylinder balance factor of Taylor
    1985, vol. 2, ch. 8 (counterweight = rotating + a fraction of the reciprocating mass).

    Parameters
    ----------
    throw_angle : array_like, shape (n_throw,) [rad]
        ``gamma_j`` (:func:`checker.calc.crank_forces.throw_angles`).
    mass : array_like, shape (n_m,) [kg]
    position : array_like, shape (n_m, 2) [m]
        Centre of mass ``(x, y)`` in the crank frame from the crank axis.
    throw_of_mass : array_like of int, shape (n_m,)
        Throw ``0..n_throw-1`` of each mass.
    is_counterweight : array_like of bool, shape (n_m,)
    pin_rotating_mass : array_like, shape (n_throw,) [kg]
        Rods' big-end (rotating) mass on each pin.
    pin_reciprocating_mass : array_like, shape (n_throw,) [kg]
        Reciprocating mass of the cylinders on each pin.
    crank_radius : float [m]

    Returns
    -------
    ThrowBalance

    Notes
    -----
    A throw whose rotating unbalance along its own direction is not positive has no defined
    balance ratio: ``ValueError`` (the crank data are then inconsistent).
    """
    gam = finite("throw_angle", throw_angle).ravel()
    nt = gam.size
    m = non_negative("mass", mass).ravel()
    rho = finite("position", position).reshape(-1, 2)
    tj = np.asarray(throw_of_mass).ravel()
    cw = np.asarray(is_counterweight, dtype=bool).ravel()
    if not (m.size == rho.shape[0] == tj.size == cw.size):
        raise ValueError("mass, position, throw_of_mass and is_counterweight must match")
    if tj.size and (not np.issubdtype(tj.dtype, np.integer) or tj.min() < 0 or tj.max() >= nt):
        raise ValueError(f"throw_of_mass must be integers in 0..{nt - 1}")
    mb = np.broadcast_to(non_negative("pin_rotating_mass", pin_rotating_mass), (nt,))
    mr = np.broadcast_to(non_negative("pin_reciprocating_mass", pin_reciprocating_mass), (nt,))
    r = float(positive("crank_radius", crank_radius))
    e = np.stack([np.sin(gam), np.cos(gam)], axis=-1)  # (nt, 2)
    u = m[:, None] * rho
    rot = np.zeros((nt, 2))
    cwt = np.zeros((nt, 2))
    np.add.at(rot, tj[~cw], u[~cw])
    np.add.at(cwt, tj[cw], u[cw])
    rot += (mb * r)[:, None] * e
    along = (rot * e).sum(-1)
    cw_along = -(cwt * e).sum(-1)
    if np.any(along <= 0):
        bad = [int(j) + 1 for j in np.nonzero(along <= 0)[0]]
        raise ValueError(f"throws {bad}: the rotating unbalance without counterweights does not"
                         " point along the throw; check the crank masses and positions")
    with np.errstate(divide="ignore", invalid="ignore"):
        recip = np.where(mr > 0, (cw_along - along) / (mr * r), np.nan)
    return ThrowBalance(rot, cwt, along, cw_along, cw_along / along, recip,
                        float(cw_along.sum() / along.sum()))


def internal_bending_moment(
    stations: ArrayLike, mass: ArrayLike, position: ArrayLike, axial: ArrayLike
) -> np.ndarray:
    """Bending moment of the rotating masses' centrifugal forces along the crank (per omega^2).

    At axial station ``Z`` the crank carries the moment of the forces in front of it,
    ``B(Z) = sum_{z_k < Z} m_k rho_k (Z - z_k)``, a vector fixed in the crank frame
    (it rotates with the crank and loads the mains as a rotating couple: the "internal
    couple" of the crank's centrifugal forces, Taylor 1985, vol. 2, ch. 8). Exact for a rigid
    crank; equal to the moment of the forces behind ``Z`` when the crank's rotating masses have
    no net force or couple.

    Parameters
    ----------
    stations : array_like, shape (n_s,) [m]
        Axial cut positions (e.g. the main bearings).
    mass : array_like, shape (n_m,) [kg]
    position : array_like, shape (n_m, 2) [m]
        Crank-frame centres of mass.
    axial : array_like, shape (n_m,) [m]

    Returns
    -------
    numpy.ndarray, shape (n_s, 2) [kg m^2]
        Crank-frame components; multiply by ``omega^2`` for N m.
    """
    zs = finite("stations", stations).ravel()
    m = non_negative("mass", mass).ravel()
    rho = finite("position", position).reshape(-1, 2)
    z = finite("axial", axial).ravel()
    if not (m.size == rho.shape[0] == z.size):
        raise ValueError("mass, position and axial must match")
    lever = np.clip(zs[:, None] - z[None, :], 0.0, None)  # (n_s, n_m), only masses in front
    return lever @ (m[:, None] * rho)


INHERENT_TOLERANCE = 1e-9
"""Relative tolerance of :func:`inherent_balance` (throw angles from degrees round to ~1e-16)."""


def inherent_balance(throw_angle: ArrayLike, pin_of_rod: ArrayLike) -> tuple[bool, bool]:
    """Whether equal throws of a crank layout cancel as forces (static) and as couples too
    (dynamic).

    With ``e_j = (sin gamma_j, cos gamma_j)`` the unit vector of throw ``j`` (crank frame) and
    ``z_j = j + 1/2 - P/2`` its axial position from the crank's mid-plane in units of the main
    journal spacing (``P`` throws, evenly spaced), the layout is balanced statically when every
    pin carries the same number of rods and ``sum_j e_j = 0``, dynamically when also
    ``sum_j z_j e_j = 0`` (Taylor 1985, vol. 2, ch. 8: in-line four and six and the flat-plane
    V8 are both, the in-line three and the cross-plane V8 only statically, a single throw
    neither).

    Parameters
    ----------
    throw_angle : array_like, shape (P,) [rad]
        Crank-frame angle of each throw (:func:`checker.calc.crank_forces.throw_angles`).
    pin_of_rod : array_like of int, shape (n_cyl,)
        Throw (0-based) of each rod.

    Returns
    -------
    static, dynamic : bool
        Within :data:`INHERENT_TOLERANCE` (times ``P``, resp. ``P^2``).

    Examples
    --------
    >>> import numpy as np
    >>> inherent_balance(np.radians([0, 180, 180, 0]), [0, 1, 2, 3])  # in-line four
    (True, True)
    >>> inherent_balance(np.radians([0, 240, 120]), [0, 1, 2])  # in-line three
    (True, False)
    """
    gamma = finite("throw_angle", throw_angle).ravel()
    pins = np.asarray(pin_of_rod, dtype=int).ravel()
    n_pins = gamma.size
    if n_pins == 0 or pins.size == 0 or pins.min() < 0 or pins.max() >= n_pins:
        raise ValueError("inherent_balance: every rod needs a throw 0..P-1")
    e = np.stack([np.sin(gamma), np.cos(gamma)], axis=-1)
    n_on = np.bincount(pins, minlength=n_pins)
    z_pin = (np.arange(n_pins) + 0.5) - n_pins / 2.0  # in units of the main spacing
    same = bool(np.all(n_on == n_on[0]))
    static = bool(same and np.hypot(*e.sum(0)) < INHERENT_TOLERANCE * n_pins)
    dynamic = bool(static and np.hypot(*(z_pin[:, None] * e).sum(0))
                   < INHERENT_TOLERANCE * n_pins**2)
    return static, dynamic


def mean_throw_unbalance(mass: ArrayLike, position: ArrayLike, throw_of_mass: ArrayLike,
                         n_throws: int) -> float:
    """Mean over the throws of each throw's rotating unbalance ``|sum_(k in j) m_k rho_k|``
    [kg m] (per omega^2; pass the masses without the counterweights: webs, pin, rod big ends).

    The reference unbalance of one throw against which a crank's resultant unbalance is judged
    (Taylor 1985, vol. 2, ch. 8).

    Parameters
    ----------
    mass : array_like, shape (n_m,) [kg]
    position : array_like, shape (n_m, 2) [m]
        Crank-frame centres of mass.
    throw_of_mass : array_like of int, shape (n_m,)
        Throw (0-based) of each mass.
    n_throws : int

    Examples
    --------
    >>> mean_throw_unbalance([1.0, 2.0, 1.0], [[0, 0.5], [0, -0.25], [0, -0.5]], [0, 1, 1], 2)
    0.75
    """
    m = finite("mass", mass).ravel()
    rho = finite("position", position).reshape(-1, 2)
    t = np.asarray(throw_of_mass, dtype=int).ravel()
    if not (m.size == rho.shape[0] == t.size):
        raise ValueError("mass, position and throw_of_mass must match")
    if t.size and (t.min() < 0 or t.max() >= n_throws):
        raise ValueError("mean_throw_unbalance: throw_of_mass outside 0..n_throws-1")
    per_throw = np.zeros((n_throws, 2))
    np.add.at(per_throw, t, m[:, None] * rho)
    return float(np.mean(np.hypot(per_throw[:, 0], per_throw[:, 1])))
