"""Lumped-mass torsional vibration of a crank train (frequency domain, pure NumPy/SciPy).

Model
-----
Stations ``i = 0..n-1`` carry polar inertias ``J_i`` [kg m^2]; elements ``e = 0..n_e-1`` connect
station ``a_e`` to station ``b_e`` (default: a chain, ``a_e = e``, ``b_e = e + 1``). Each element
has a complex impedance

    z_e(Omega) = k_e (1 + j eta_e) + j Omega c_e        (or a user dynamic stiffness k*_e(Omega))

(``k_e`` static stiffness [N m/rad], ``eta_e`` hysteretic loss factor, ``c_e`` relative viscous
damping [N m s/rad]); each station may have absolute viscous damping ``d_i`` to a node rotating
at the mean speed (bearing/friction damping) and a stiffness ``g_i`` to ground. With the
incidence matrix ``B`` (``B[e, a_e] = 1``, ``B[e, b_e] = -1``)

    D(Omega) = B^T diag(z(Omega)) B + diag(g + j Omega d) - Omega^2 diag(J)

and the steady-state response to order ``n`` at mean crank speed ``w`` (``Omega = n w``) solves
``D(Omega) Theta_n = F_n`` (Friswell et al. 2010, *Dynamics of Rotating
Machines*, ch. 3 and 9; Hafner & Maass 1985, *Torsionsschwingungen in der
Verbrennungskraftmaschine*).

Conventions
-----------
* Complex amplitudes follow :mod:`checker.calc.excitation`: ``theta_i(t) = sum_n Re{Theta_{i,n}
  exp(j n w t)}``; ``|Theta|`` is 0-to-peak [rad]. ``Theta`` is the angle of a station relative
  to a node rotating at the mean speed (it contains the rigid-body speed fluctuation, it is not
  twist). Twist is ``Theta_a - Theta_b``.
* Element torque ``T_e = z_e (Theta_a - Theta_b)`` [N m], positive when station ``a`` leads ``b``.
* "Amplitude" of a synthesised quantity = half peak-to-peak, ``(max - min)/2`` of the time signal
  of all orders over 720 deg (Lloyd's Register rules "half-range"; Drapal & Novotny 2017).
* Array layout: speed axis first, order axis last: ``Theta`` is (n_speed, n_station, n_order).

References
----------
.. [1] M. I. Friswell, J. E. T. Penny, S. D. Garvey, A. W. Lees, "Dynamics of Rotating Machines",
   Cambridge University Press, 2010, ch. 2-3 and 9.
.. [2] K. E. Hafner, H. Maass, "Torsionsschwingungen in der Verbrennungskraftmaschine", 1985.
.. [3] L. Drapal, P. Novotny, "Torsional vibration analysis of crank train with low friction
   losses", J. Vibroeng. 19(7), 2017, doi:10.21595/jve.2017.17876, eq. 3.
.. [4] J. P. Den Hartog, "Mechanical Vibrations", 4th ed., 1956, ch. 2.
.. [5] Lloyd's Register, Rules and Regulations for the Classification of Naval Ships, Vol. 2, Pt 5,
   Ch 1, Sec 3 (half-range amplitude of the synthesis of all harmonic orders).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "NEAR_RESONANCE_AMPLIFICATION",
    "RESONANCE_TOLERANCE",
    "SYNTHESIS_SAMPLES_PER_PERIOD",
    "ComplexStiffnessTable",
    "ForcedResponse",
    "TorsionalModel",
    "damping_matrix",
    "dynamic_stiffness_matrix",
    "element_impedance",
    "equivalent_inertia",
    "forced_response",
    "half_peak_to_peak",
    "mass_matrix",
    "modal_damping_ratios",
    "natural_frequencies",
    "station_excitation",
    "stiffness_matrix",
    "synthesize",
    "undamped_resonance_band",
    "UndampedBand",
]

#: A (speed, order) point is flagged as an unbounded resonance when, for some undamped mode r of
#: the real part of D, ``|(omega_r^2 - Omega^2) + j b_r| < RESONANCE_TOLERANCE * Omega^2`` (b_r
#: the modal damping term), i.e. the dynamic magnification would exceed 1e6. Real crank trains
#: have magnifications below ~1e4 (steel loss factor ~1e-4), so only (nearly) undamped modes hit.
RESONANCE_TOLERANCE = 1e-6

#: Near-resonance band of an undamped mode (:func:`undamped_resonance_band`): a (speed, order)
#: point is *near* an undamped resonance when the undamped amplification of a mode,
#: ``omega_r^2 / |omega_r^2 - Omega^2|`` (force-excited single degree of freedom, e.g. Den Hartog
#: 1956, *Mechanical Vibrations*, ch. 2), reaches this value, i.e. ``|1 - (Omega/omega_r)^2| <=
#: 0.1``, Omega within about -5 %/+5 % of omega_r. 10 is the resonant amplification
#: ``Q = 1/(2 zeta)`` of a damped crank mode with zeta = 0.05: an undamped mode this close to an
#: order is amplified more than a damped crank resonance at its peak.
NEAR_RESONANCE_AMPLIFICATION = 10.0

#: Samples per period of the highest order used by :func:`synthesize` by default. The samples
#: only locate the extremes for :func:`half_peak_to_peak`, which polishes them by Newton steps on
#: the exact trigonometric polynomial.
SYNTHESIS_SAMPLES_PER_PERIOD = 16

DynamicStiffness = Callable[[np.ndarray], np.ndarray]


class ComplexStiffnessTable:
    """Frequency-dependent complex element stiffness ``k*(Omega) = k'(Omega) (1 + j eta(Omega))``.

    Linear interpolation of a table (e.g. supplier rubber data at the operating temperature).

    Parameters
    ----------
    omega : array_like, shape (m,) [rad/s]
        Strictly increasing frequencies.
    storage_stiffness : array_like, shape (m,) [N m/rad]
        ``k' > 0``.
    loss_factor : array_like, shape (m,) [-]
        ``eta = k''/k' >= 0``.
    outside : {"clip", "raise"}
        Beyond the table: hold the end values (default) or raise ``ValueError``.
    """

    def __init__(
        self,
        omega: ArrayLike,
        storage_stiffness: ArrayLike,
        loss_factor: ArrayLike,
        outside: str = "clip",
    ) -> None:
        w = np.asarray(omega, dtype=float)
        ks = np.asarray(storage_stiffness, dtype=float)
        eta = np.asarray(loss_factor, dtype=float)
        if w.ndim != 1 or w.size < 1 or ks.shape != w.shape or eta.shape != w.shape:
            raise ValueError("omega, storage_stiffness and loss_factor must be 1-D, same length")
        if np.any(np.diff(w) <= 0):
            raise ValueError("omega must be strictly increasing")
        if np.any(ks <= 0) or np.any(eta < 0):
            raise ValueError("storage_stiffness must be > 0 and loss_factor >= 0")
        if outside not in ("clip", "raise"):
            raise ValueError("outside must be 'clip' or 'raise'")
        self.omega, self.storage_stiffness, self.loss_factor, self.outside = w, ks, eta, outside

    def __call__(self, omega: ArrayLike) -> np.ndarray:
        """Complex stiffness [N m/rad] at ``omega`` [rad/s] (any shape)."""
        w = np.asarray(omega, dtype=float)
        if self.outside == "raise" and (np.any(w < self.omega[0]) or np.any(w > self.omega[-1])):
            raise ValueError(
                f"frequency outside the stiffness table [{self.omega[0]:g}, {self.omega[-1]:g}]"
                " rad/s"
            )
        ks = np.interp(w, self.omega, self.storage_stiffness)
        return ks * (1.0 + 1j * np.interp(w, self.omega, self.loss_factor))


@dataclass(frozen=True)
class TorsionalModel:
    """Lumped torsional model (see module docstring). Arrays are validated and copied.

    Parameters
    ----------
    inertia : array_like, shape (n,) [kg m^2]
        Station inertias ``J_i > 0``.
    stiffness : array_like, shape (n_e,) [N m/rad]
        Static element stiffnesses ``k_e > 0`` (used for natural frequencies; for elements in
        ``dynamic_stiffness`` the value is the reference used by :func:`natural_frequencies`).
        ``k_e = 0`` only for a coupling without a spring (the silicone of an untuned viscous
        damper): ``damping_rel[e] > 0`` or a ``dynamic_stiffness`` entry.
    damping_abs : array_like, shape (n,) [N m s/rad]
        Absolute viscous damping ``d_i >= 0`` (scalar broadcast).
    damping_rel : array_like, shape (n_e,) [N m s/rad]
        Relative viscous damping ``c_e >= 0`` of the elements (scalar broadcast).
    loss_factor : array_like, shape (n_e,) [-]
        Hysteretic loss factor ``eta_e >= 0``: ``k*_e = k_e (1 + j eta_e)`` (scalar broadcast).
    dynamic_stiffness : mapping {element index: callable}, optional
        ``f(Omega) -> k*_e(Omega)`` complex [N m/rad] (e.g. :class:`ComplexStiffnessTable`);
        replaces ``k_e (1 + j eta_e)`` in the forced response (``c_e`` is still added).
    stiffness_ground : array_like, shape (n,) [N m/rad]
        Stiffness ``g_i >= 0`` of station ``i`` to ground (default 0: free-free).
    node_a, node_b : array_like of int, shape (n_e,), optional
        Element end stations (default chain ``e -> e+1``).
    """

    inertia: np.ndarray
    stiffness: np.ndarray
    damping_abs: np.ndarray | float = 0.0
    damping_rel: np.ndarray | float = 0.0
    loss_factor: np.ndarray | float = 0.0
    dynamic_stiffness: Mapping[int, DynamicStiffness] = field(default_factory=dict)
    stiffness_ground: np.ndarray | float = 0.0
    node_a: np.ndarray | None = None
    node_b: np.ndarray | None = None

    def __post_init__(self) -> None:
        j = np.array(self.inertia, dtype=float).ravel()
        k = np.array(self.stiffness, dtype=float).ravel()
        n, ne = j.size, k.size
        if n < 1:
            raise ValueError("at least one station is needed")
        if np.any(~np.isfinite(j)) or np.any(j <= 0):
            raise ValueError("inertia must be finite and > 0 kg m^2 at every station")
        if np.any(~np.isfinite(k)) or np.any(k < 0):
            raise ValueError("stiffness must be finite and > 0 N m/rad for every element")

        def vec(name: str, value: object, size: int) -> np.ndarray:
            v = np.array(np.broadcast_to(np.asarray(value, dtype=float), (size,)))
            if np.any(~np.isfinite(v)) or np.any(v < 0):
                raise ValueError(f"{name} must be finite and >= 0")
            return v

        if self.node_a is None and self.node_b is None:
            a, b = np.arange(ne), np.arange(1, ne + 1)
        elif self.node_a is not None and self.node_b is not None:
            a = np.array(self.node_a, dtype=int).ravel()
            b = np.array(self.node_b, dtype=int).ravel()
        else:
            raise ValueError("give both node_a and node_b or neither")
        if a.size != ne or b.size != ne:
            raise ValueError(f"node_a/node_b must have {ne} entries (one per element)")
        if ne and (min(a.min(), b.min()) < 0 or max(a.max(), b.max()) >= n or np.any(a == b)):
            raise ValueError(f"element end stations must be distinct and in 0..{n - 1}")
        dyn = dict(self.dynamic_stiffness)
        for e, f in dyn.items():
            if not (0 <= int(e) < ne) or not callable(f):
                raise ValueError(f"dynamic_stiffness key {e!r} is no element or not callable")
        set_ = object.__setattr__
        zero = np.nonzero(k == 0)[0]
        rel = vec("damping_rel", self.damping_rel, ne)
        for e in zero:  # a purely viscous coupling (untuned viscous damper): no spring
            if int(e) not in dyn and rel[e] <= 0:
                raise ValueError("stiffness must be finite and > 0 N m/rad for every element"
                                 " (0 only for a viscous coupling: damping_rel > 0 or a"
                                 " dynamic stiffness)")
        set_(self, "inertia", j)
        set_(self, "stiffness", k)
        set_(self, "damping_abs", vec("damping_abs", self.damping_abs, n))
        set_(self, "damping_rel", vec("damping_rel", self.damping_rel, ne))
        set_(self, "loss_factor", vec("loss_factor", self.loss_factor, ne))
        set_(self, "stiffness_ground", vec("stiffness_ground", self.stiffness_ground, n))
        set_(self, "node_a", a)
        set_(self, "node_b", b)
        set_(self, "dynamic_stiffness", dyn)

    @property
    def n_stations(self) -> int:
        return self.inertia.size

    @property
    def n_elements(self) -> int:
        return self.stiffness.size

    @property
    def incidence(self) -> np.ndarray:
        """Incidence matrix ``B``, shape (n_e, n): ``B[e, a_e] = 1``, ``B[e, b_e] = -1``."""
        bmat = np.zeros((self.n_elements, self.n_stations))
        e = np.arange(self.n_elements)
        bmat[e, self.node_a] = 1.0
        bmat[e, self.node_b] = -1.0
        return bmat


def mass_matrix(model: TorsionalModel) -> np.ndarray:
    """Inertia matrix ``M = diag(J)``, shape (n, n) [kg m^2]."""
    return np.diag(model.inertia)


def stiffness_matrix(model: TorsionalModel) -> np.ndarray:
    """Static stiffness matrix ``K = B^T diag(k) B + diag(g)``, shape (n, n) [N m/rad]."""
    bmat = model.incidence
    return bmat.T @ (model.stiffness[:, None] * bmat) + np.diag(model.stiffness_ground)


def damping_matrix(model: TorsionalModel) -> np.ndarray:
    """Viscous damping matrix ``C = B^T diag(c) B + diag(d)``, shape (n, n) [N m s/rad]."""
    bmat = model.incidence
    return bmat.T @ (model.damping_rel[:, None] * bmat) + np.diag(model.damping_abs)


def element_impedance(model: TorsionalModel, omega: ArrayLike) -> np.ndarray:
    """Complex element impedances ``z_e(Omega) = k*_e(Omega) + j Omega c_e``.

    Parameters
    ----------
    model : TorsionalModel
    omega : array_like, shape (...) [rad/s]
        Vibration frequencies ``Omega > 0``.

    Returns
    -------
    numpy.ndarray, shape (..., n_e), complex [N m/rad]
    """
    w = np.asarray(omega, dtype=float)
    z = model.stiffness * (1.0 + 1j * model.loss_factor) + 1j * w[..., None] * model.damping_rel
    for e, f in model.dynamic_stiffness.items():
        ks = np.broadcast_to(np.asarray(f(w), dtype=complex), w.shape)
        if np.any(~np.isfinite(ks)) or np.any(ks.real <= 0) or np.any(ks.imag < 0):
            raise ValueError(
                f"dynamic stiffness of element {e} must be finite with Re > 0 and Im >= 0 (passive)"
            )
        z[..., e] = ks + 1j * w * model.damping_rel[e]
    return z


def dynamic_stiffness_matrix(model: TorsionalModel, omega: ArrayLike) -> np.ndarray:
    """Dynamic stiffness ``D(Omega) = B^T diag(z) B + diag(g + j Omega d) - Omega^2 M``.

    Parameters
    ----------
    model : TorsionalModel
    omega : array_like, shape (...) [rad/s]

    Returns
    -------
    numpy.ndarray, shape (..., n, n), complex [N m/rad]
    """
    w = np.asarray(omega, dtype=float)
    return _assemble(model, w, element_impedance(model, w))


def _assemble(model: TorsionalModel, w: np.ndarray, z: np.ndarray) -> np.ndarray:
    bmat = model.incidence
    # B^T diag(z) B as a product (the incidence entries are 0 and +-1, at most two per row:
    # the same sums as the element-wise einsum, a quarter of its time)
    d = (bmat.T * z[..., None, :]) @ bmat
    diag = model.stiffness_ground + 1j * w[..., None] * model.damping_abs
    diag = diag - w[..., None] ** 2 * model.inertia
    idx = np.arange(model.n_stations)
    d[..., idx, idx] += diag
    return d


def natural_frequencies(
    model: TorsionalModel, omega: float | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Undamped natural frequencies and mode shapes: ``K phi = omega_r^2 M phi``.

    Parameters
    ----------
    model : TorsionalModel
    omega : float, optional [rad/s]
        If given, elements with a dynamic stiffness use ``Re k*_e(omega)`` instead of ``k_e``.

    Returns
    -------
    omega_n : numpy.ndarray, shape (n,) [rad/s]
        Ascending; a free-free model has a rigid-body mode ``omega_0 = 0`` (tiny negative
        round-off eigenvalues are set to 0).
    modes : numpy.ndarray, shape (n, n) [-]
        Mass-normalised mode shapes in the columns (``phi^T M phi = 1``).

    Notes
    -----
    Symmetric-definite generalized eigenproblem (Friswell et al. 2010, sec. 2.4); with the
    diagonal ``M`` it is the standard symmetric problem of ``M^-1/2 K M^-1/2`` (NumPy
    ``eigh``; no SciPy import on the check's path). Valid for any connected or unconnected
    model with ``J > 0``.
    """
    kmat = stiffness_matrix(model)
    if omega is not None and model.dynamic_stiffness:
        z = element_impedance(model, np.asarray(float(omega)))
        bmat = model.incidence
        kmat = bmat.T @ (z.real[:, None] * bmat) + np.diag(model.stiffness_ground)
    s = 1.0 / np.sqrt(np.asarray(model.inertia, dtype=float))
    lam, y = np.linalg.eigh(s[:, None] * kmat * s[None, :])
    modes = s[:, None] * y
    return np.sqrt(np.clip(lam, 0.0, None)), modes


def modal_damping_ratios(model: TorsionalModel, omega_n: ArrayLike, modes: ArrayLike) -> np.ndarray:
    """Modal damping ratios of undamped modes (diagonal approximation).

    ``zeta_r = phi_r^T (C + K''/omega_r) phi_r / (2 omega_r)`` for mass-normalised ``phi_r``,
    with ``K'' = Im B^T diag(k*(omega_r)) B`` (hysteretic part at the mode's frequency).

    Parameters
    ----------
    model : TorsionalModel
    omega_n : array_like, shape (m,) [rad/s]
    modes : array_like, shape (n, m) [-]
        Mass-normalised (as returned by :func:`natural_frequencies`).

    Returns
    -------
    numpy.ndarray, shape (m,) [-]
        0 is returned for rigid-body modes (``omega_r = 0``), whose damping ratio is undefined.
    """
    w = np.asarray(omega_n, dtype=float)
    phi = np.asarray(modes, dtype=float)
    cmat = damping_matrix(model)
    bmat = model.incidence
    w_safe = np.where(w > 0, w, 1.0)
    z = element_impedance(model, w_safe)  # (m, n_e)
    kpp = z.imag - w_safe[:, None] * model.damping_rel  # hysteretic part only
    bphi = bmat @ phi  # (n_e, m)
    hyst = np.einsum("em,me->m", bphi**2, kpp)
    visc = np.einsum("im,ij,jm->m", phi, cmat, phi)
    zeta = (visc + hyst / w_safe) / (2.0 * w_safe)
    return np.where(w > 0, zeta, 0.0)


def equivalent_inertia(model: TorsionalModel, mode: ArrayLike, reference_station: int) -> float:
    """Equivalent (modal) inertia of a mode at a station.

    ``J_eq = sum_i J_i (phi_i / phi_ref)^2`` (Drapal & Novotny 2017, J. Vibroeng. 19(7), eq. 3;
    used with Den Hartog's tuning rules).

    Parameters
    ----------
    model : TorsionalModel
    mode : array_like, shape (n,) [-]
    reference_station : int
        Station where the absorber acts (``phi_ref != 0``).

    Returns
    -------
    float [kg m^2]
    """
    phi = np.asarray(mode, dtype=float)
    ref = phi[reference_station]
    if abs(ref) <= 1e-12 * np.max(np.abs(phi)):
        raise ValueError("the mode has a node at the reference station")
    return float(np.sum(model.inertia * (phi / ref) ** 2))


def station_excitation(
    cylinder_coeffs: ArrayLike, stations: ArrayLike, n_stations: int
) -> np.ndarray:
    """Place per-cylinder order coefficients on the model stations.

    Parameters
    ----------
    cylinder_coeffs : array_like, shape (..., n_cyl, n_order), complex [N m]
        E.g. :func:`checker.calc.excitation.phase_cylinders` of one cylinder's harmonics, or
        :func:`checker.calc.excitation.torque_harmonics` of the already phased per-cylinder
        torques of :func:`checker.calc.crank_forces.cylinder_loads`.
    stations : array_like of int, shape (n_cyl,)
        Station of each cylinder (several cylinders may share a station, e.g. a V-engine pin).
    n_stations : int

    Returns
    -------
    numpy.ndarray, shape (..., n_stations, n_order), complex [N m]
    """
    c = np.asarray(cylinder_coeffs, dtype=complex)
    s = np.asarray(stations, dtype=int).ravel()
    if c.ndim < 2 or c.shape[-2] != s.size:
        raise ValueError("cylinder_coeffs must have shape (..., n_cyl, n_order) matching stations")
    if np.any(s < 0) or np.any(s >= n_stations):
        raise ValueError(f"stations must be in 0..{n_stations - 1}")
    f = np.zeros(c.shape[:-2] + (n_stations, c.shape[-1]), dtype=complex)
    np.add.at(f, (..., s, slice(None)), c)
    return f


@dataclass(frozen=True)
class ForcedResponse:
    """Steady-state response per speed and order (order axis last).

    Attributes
    ----------
    speeds : numpy.ndarray, shape (n_speed,) [rad/s]
        Mean crank speeds.
    orders : numpy.ndarray, shape (n_order,) [-]
    omega : numpy.ndarray, shape (n_speed, n_order) [rad/s]
        Vibration frequencies ``Omega = order * speed``.
    theta : numpy.ndarray, shape (n_speed, n, n_order), complex [rad]
        Station angles relative to a node rotating at the mean speed.
    element_torque : numpy.ndarray, shape (n_speed, n_e, n_order), complex [N m]
        ``z_e (Theta_a - Theta_b)``.
    resonance : numpy.ndarray of bool, shape (n_speed, n_order)
        True where the dynamic stiffness is (nearly) singular: an undamped resonance. The
        values there come from a regularised solve (added loss ``RESONANCE_TOLERANCE Omega^2
        J_i`` at every station): finite but not physical.
    """

    speeds: np.ndarray
    orders: np.ndarray
    omega: np.ndarray
    theta: np.ndarray
    element_torque: np.ndarray
    resonance: np.ndarray

    def station_amplitude(self, n_points: int | None = None) -> np.ndarray:
        """Synthesised half peak-to-peak angle of every station, (n_speed, n) [rad]."""
        return half_peak_to_peak(self.orders, self.theta, n_points)

    def twist_amplitude(self, a: int, b: int, n_points: int | None = None) -> np.ndarray:
        """Synthesised half peak-to-peak twist ``theta_a - theta_b``, (n_speed,) [rad]."""
        return half_peak_to_peak(self.orders, self.theta[:, a] - self.theta[:, b], n_points)

    def element_torque_amplitude(self, n_points: int | None = None) -> np.ndarray:
        """Synthesised half peak-to-peak element torques, (n_speed, n_e) [N m]."""
        return half_peak_to_peak(self.orders, self.element_torque, n_points)

    @property
    def resonance_at_speed(self) -> np.ndarray:
        """True for speeds where any order hits an undamped resonance, (n_speed,)."""
        return self.resonance.any(axis=-1)


def speeds_and_orders(speeds: ArrayLike, orders: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Mean speeds [rad/s] and orders [-] of a forced response as flat float arrays; raises
    ValueError unless both are non-empty, finite and > 0."""
    w = np.asarray(speeds, dtype=float).ravel()
    n_ord = np.asarray(orders, dtype=float).ravel()
    if w.size == 0 or np.any(~np.isfinite(w)) or np.any(w <= 0):
        raise ValueError("speeds must be finite and > 0 rad/s")
    if n_ord.size == 0 or np.any(~np.isfinite(n_ord)) or np.any(n_ord <= 0):
        raise ValueError("orders must be finite and > 0")
    return w, n_ord


def forced_response(
    model: TorsionalModel,
    speeds: ArrayLike,
    orders: ArrayLike,
    excitation: ArrayLike,
    impedance: Mapping[int, ArrayLike] | None = None,
    station_damping: ArrayLike | None = None,
) -> ForcedResponse:
    """Steady-state forced response for all speeds and orders in one batched solve.

    ``D(n w) Theta_n = F_n`` for every speed ``w`` and order ``n`` (module docstring), solved as
    one batched ``numpy.linalg.solve`` (LU with partial pivoting) of shape
    (n_speed, n_order, n, n).

    Parameters
    ----------
    model : TorsionalModel
    speeds : array_like, shape (n_speed,) [rad/s]
        Mean crank speeds ``w > 0``.
    orders : array_like, shape (n_order,) [-]
        Harmonic orders ``n > 0`` (multiples of 0.5 if the result is to be synthesised).
    excitation : array_like, shape (n_speed, n, n_order) or broadcastable, complex [N m]
        Complex order torques at the stations (:func:`station_excitation`), module convention.
    impedance : mapping {element index: array_like}, optional
        Complex impedance ``z_e`` [N m/rad] of an element per speed and order, broadcast to
        (n_speed, n_order), replacing :func:`element_impedance` for that element (a damper
        whose properties depend on its own temperature, which differs from speed to speed).
        Passive: finite, ``Re >= 0``, ``Im >= 0``.
    station_damping : array_like, shape (n_speed, n) or broadcastable, optional [N m s/rad]
        Absolute viscous damping added to ``damping_abs`` per speed (a propeller's damping,
        which follows its torque and so the speed). Finite and ``>= 0``.

    Returns
    -------
    ForcedResponse

    Notes
    -----
    Linear, steady state; the order-0 (mean) torque is not handled (free-free models have no
    static solution). Accuracy: LU is backward stable, so the relative error is about machine
    epsilon times the condition number of ``D`` (rounding of the assembled entries alone gives
    the same); a chain mixing 1e9 and 1 N m/rad elements stays within 1e-10 (tested against
    exact rational arithmetic). Undamped (near-)resonances are flagged in
    ``ForcedResponse.resonance`` (criterion: :data:`RESONANCE_TOLERANCE`) instead of returning
    inf/NaN.
    """
    w, n_ord = speeds_and_orders(speeds, orders)
    n = model.n_stations
    f = np.asarray(excitation, dtype=complex)
    try:
        f = np.broadcast_to(f, (w.size, n, n_ord.size))
    except ValueError as err:
        raise ValueError(
            f"excitation shape {f.shape} does not broadcast to (n_speed, n_station, n_order) = "
            f"{(w.size, n, n_ord.size)}"
        ) from err
    if np.any(~np.isfinite(f)):
        raise ValueError("excitation contains non-finite values")

    om = w[:, None] * n_ord  # (S, O)
    z = element_impedance(model, om)  # (S, O, E)
    for e, ze in (impedance or {}).items():
        if not 0 <= int(e) < model.n_elements:
            raise ValueError(f"impedance key {e!r} is no element")
        ze = np.broadcast_to(np.asarray(ze, dtype=complex), om.shape)
        if np.any(~np.isfinite(ze)) or np.any(ze.real < 0) or np.any(ze.imag < 0):
            raise ValueError(f"impedance of element {e} must be finite with Re >= 0 and"
                             " Im >= 0 (passive)")
        z[..., int(e)] = ze
    dmat = _assemble(model, om, z)  # (S, O, n, n)
    if station_damping is not None:
        extra = np.asarray(station_damping, dtype=float)
        try:
            extra = np.broadcast_to(extra, (w.size, n))
        except ValueError as err:
            raise ValueError(f"station_damping shape {extra.shape} does not broadcast to"
                             f" (n_speed, n_station) = {(w.size, n)}") from err
        if np.any(~np.isfinite(extra)) or np.any(extra < 0):
            raise ValueError("station_damping must be finite and >= 0 N m s/rad")
        idx = np.arange(n)
        dmat[..., idx, idx] += 1j * om[..., None] * extra[:, None, :]

    resonance = _undamped_resonance(model, om, dmat)
    if np.any(resonance):
        idx = np.arange(n)
        reg = np.where(resonance, RESONANCE_TOLERANCE * om**2, 0.0)
        dmat[..., idx, idx] += 1j * reg[..., None] * model.inertia

    theta = np.linalg.solve(dmat, np.moveaxis(f, -1, -2)[..., None])[..., 0]  # (S, O, n)

    bmat = model.incidence
    torque = z * np.einsum("ei,...i->...e", bmat, theta)  # (S, O, E)
    return ForcedResponse(
        speeds=w,
        orders=n_ord,
        omega=om,
        theta=np.moveaxis(theta, -1, -2),
        element_torque=np.moveaxis(torque, -1, -2),
        resonance=resonance,
    )


def _modal_terms(model: TorsionalModel, om: np.ndarray, dmat: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues ``a_r`` of ``M^-1/2 Re D M^-1/2`` (``omega_r^2 - Omega^2`` for constant
    stiffness) and modal damping terms ``b_r = v_r^T M^-1/2 Im D M^-1/2 v_r``, (..., n) each.
    """
    minv = 1.0 / np.sqrt(model.inertia)
    if model.dynamic_stiffness:
        a_s = dmat.real * minv[:, None] * minv
        lam, vec = np.linalg.eigh(a_s)
    else:  # Re D = K - Omega^2 M: one eigen-solution serves all frequencies
        k_s = stiffness_matrix(model) * minv[:, None] * minv
        lam0, vec = np.linalg.eigh(k_s)
        lam = lam0 - om[..., None] ** 2
    b_s = dmat.imag * minv[:, None] * minv
    b_r = np.sum(vec * (b_s @ vec), axis=-2)  # v_r^T B v_r (a product: ~10x the einsum)
    return lam, b_r


def _undamped_resonance(model: TorsionalModel, om: np.ndarray, dmat: np.ndarray) -> np.ndarray:
    """Flag (speed, order) points where D has an (almost) undamped null vector.

    For passive damping (Im D positive semidefinite) ``D x = 0`` iff ``Re D x = 0`` and
    ``Im D x = 0``: the excitation frequency is an undamped natural frequency whose mode is not
    damped at all. Test, in the M^-1/2-scaled eigenbasis of Re D, ``|a_r + j b_r| < tol Omega^2``
    with ``a_r`` the eigenvalue of Re D and ``b_r = v_r^T Im D v_r``.
    """
    lam, b_r = _modal_terms(model, om, dmat)
    mag = np.hypot(lam, b_r)
    return np.any(mag < RESONANCE_TOLERANCE * om[..., None] ** 2, axis=-1)


@dataclass(frozen=True)
class UndampedBand:
    """Points of a speed sweep near a resonance of an undamped mode (all (n_speed, n_order)).

    Attributes
    ----------
    near : numpy.ndarray of bool
        Near an undamped resonance: within the amplification band, or next to a crossing.
    amplification : numpy.ndarray [-]
        Largest undamped amplification ``omega_r^2 / |omega_r^2 - Omega^2|`` over the undamped
        modes (0 where no mode is undamped; inf exactly on a natural frequency).
    natural_frequency : numpy.ndarray [rad/s]
        Natural frequency of the undamped mode the point is near (nan where not near).
    critical_speed : numpy.ndarray [rad/s]
        Speed at which the order crosses that natural frequency between this swept speed and
        a neighbour (nan where no crossing is next to the point).
    """

    near: np.ndarray
    amplification: np.ndarray
    natural_frequency: np.ndarray
    critical_speed: np.ndarray


def undamped_resonance_band(
    model: TorsionalModel,
    speeds: ArrayLike,
    orders: ArrayLike,
    amplification: float = NEAR_RESONANCE_AMPLIFICATION,
) -> UndampedBand:
    """Speed-sweep points near a resonance of an undamped mode, missed or not by the sweep.

    A mode ``r`` is *undamped* at ``Omega`` when its modal damping term ``b_r`` (the imaginary
    part of ``D`` in the mass-scaled eigenbasis of ``Re D``, as in :func:`forced_response`)
    cannot bound the resonant magnification ``Omega^2 / b_r`` below ``1 / RESONANCE_TOLERANCE``
    (1e6). A swept point ``(speed, order)`` is *near* such a mode when

    * the undamped amplification ``omega_r^2 / |omega_r^2 - Omega^2|`` is at least
      ``amplification`` (:data:`NEAR_RESONANCE_AMPLIFICATION`), or
    * the order crosses ``omega_r`` between this speed and the previous or next swept speed
      (``omega_r^2 - Omega^2`` changes sign): the response at the crossing is unbounded while
      the swept points, however far from it, show finite amplitudes. The crossing speed is
      interpolated linearly in ``speed^2`` (exact for constant stiffness, where
      ``omega_r^2 - Omega^2 = omega_r^2 - n^2 w^2``).

    Parameters
    ----------
    model : TorsionalModel
    speeds : array_like, shape (n_speed,) [rad/s]
        Strictly increasing mean crank speeds (> 0).
    orders : array_like, shape (n_order,) [-]
        Harmonic orders (> 0).
    amplification : float [-]
        Amplification threshold of the band (> 1).

    Returns
    -------
    UndampedBand

    Notes
    -----
    With frequency-dependent element stiffness the modes are followed by their rank (sorted
    eigenvalues), which is exact as long as two modes do not exchange order between adjacent
    speeds.
    """
    w = np.asarray(speeds, dtype=float).ravel()
    n_ord = np.asarray(orders, dtype=float).ravel()
    if w.size == 0 or np.any(~np.isfinite(w)) or np.any(w <= 0) or np.any(np.diff(w) <= 0):
        raise ValueError("speeds must be finite, > 0 rad/s and strictly increasing")
    if n_ord.size == 0 or np.any(~np.isfinite(n_ord)) or np.any(n_ord <= 0):
        raise ValueError("orders must be finite and > 0")
    if not (np.isfinite(amplification) and amplification > 1.0):
        raise ValueError("amplification must be finite and > 1")
    om = w[:, None] * n_ord  # (S, O)
    lam, b_r = _modal_terms(model, om, _assemble(model, om, element_impedance(model, om)))
    undamped = b_r < RESONANCE_TOLERANCE * om[..., None] ** 2  # (S, O, n)
    w_r2 = lam + om[..., None] ** 2  # natural frequency squared of each mode
    with np.errstate(divide="ignore", invalid="ignore"):
        amp = np.where(undamped & (w_r2 > 0), w_r2 / np.abs(lam), 0.0)
    in_band = amp >= amplification
    # crossings between adjacent speeds, the mode undamped at both ends
    cross = (np.sign(lam[:-1]) != np.sign(lam[1:])) & undamped[:-1] & undamped[1:] & (
        w_r2[:-1] > 0)  # (S-1, O, n)
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.clip(lam[:-1] / (lam[:-1] - lam[1:]), 0.0, 1.0)
    w2 = w**2
    w_cross = np.sqrt(w2[:-1, None, None] + (w2[1:] - w2[:-1])[:, None, None] * frac)
    crit = np.full(lam.shape, np.nan)  # (S, O, n)
    crit[:-1] = np.where(cross, w_cross, np.nan)  # crossing above this speed
    crit[1:] = np.where(cross, w_cross, crit[1:])  # crossing below this speed
    near_r = in_band | np.isfinite(crit)
    near = near_r.any(axis=-1)
    # the mode each near point refers to: the most amplified near mode
    score = np.where(near_r, np.where(np.isfinite(crit), np.inf, amp), -1.0)
    r = np.argmax(score, axis=-1)[..., None]
    nat = np.where(near, np.sqrt(np.take_along_axis(w_r2, r, -1)[..., 0].clip(0.0)), np.nan)
    crit_r = np.where(near, np.take_along_axis(crit, r, -1)[..., 0], np.nan)
    return UndampedBand(near=near, amplification=amp.max(axis=-1, initial=0.0),
                        natural_frequency=nat, critical_speed=crit_r)


def _check_orders(orders: np.ndarray) -> np.ndarray:
    m = np.rint(2.0 * orders)
    if np.any(m < 1) or np.any(np.abs(2.0 * orders - m) > 1e-9):
        raise ValueError("orders must be positive multiples of 0.5 for synthesis over 720 deg")
    return m.astype(int)


def _next_fast_len(n: int) -> int:
    """The smallest 5-smooth number (2^a 3^b 5^c) >= ``n``: a fast FFT length (as
    ``scipy.fft.next_fast_len(n, real=True)``)."""
    best = 1 << max(0, int(n - 1).bit_length())
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            p2 = p35
            while p2 < n:
                p2 *= 2
            best = min(best, p2)
            p35 *= 3
        p5 *= 5
    return best


def _synthesis_points(m_max: int, n_points: int | None) -> int:
    if n_points is None:
        return max(64, _next_fast_len(SYNTHESIS_SAMPLES_PER_PERIOD * m_max))
    if n_points <= 2 * m_max:
        raise ValueError(f"n_points must exceed {2 * m_max} to represent the highest order")
    return int(n_points)


def synthesize(
    orders: ArrayLike, coeffs: ArrayLike, n_points: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Time (crank-angle) signal of a sum of orders over one 720 deg cycle.

    ``x(theta) = sum_n Re{X_n exp(j n theta)}``, ``theta_k = 4 pi k / N`` (inverse real FFT).

    Parameters
    ----------
    orders : array_like, shape (n_order,) [-]
        Positive multiples of 0.5 (no duplicates).
    coeffs : array_like, shape (..., n_order), complex [any unit]
        Order axis last.
    n_points : int, optional
        Points per cycle; default ``SYNTHESIS_SAMPLES_PER_PERIOD`` per period of the highest
        order (at least 64).

    Returns
    -------
    theta : numpy.ndarray, shape (N,) [rad]
    signal : numpy.ndarray, shape (..., N) [unit of coeffs]
    """
    n_ord = np.asarray(orders, dtype=float).ravel()
    c = np.asarray(coeffs, dtype=complex)
    if c.shape[-1:] != n_ord.shape:
        raise ValueError("coeffs must have the order axis last, matching orders")
    m = _check_orders(n_ord)
    if len(set(m.tolist())) != m.size:  # (np.unique would import numpy.ma: 20 ms)
        raise ValueError("orders must not repeat")
    npts = _synthesis_points(int(m.max()), n_points)
    spec = np.zeros(c.shape[:-1] + (npts // 2 + 1,), dtype=complex)
    spec[..., m] = c * (npts / 2.0)
    return np.arange(npts) * (4.0 * np.pi / npts), np.fft.irfft(spec, n=npts, axis=-1)


def half_peak_to_peak(
    orders: ArrayLike, coeffs: ArrayLike, n_points: int | None = None
) -> np.ndarray:
    """Half peak-to-peak ("half range") amplitude of the synthesised signal of all orders.

    ``(max_theta x - min_theta x) / 2`` over 720 deg. The signal is sampled by
    :func:`synthesize`; the largest (smallest) sample is refined by the vertex of the parabola
    through it and its neighbours and then by ``_NEWTON_STEPS`` Newton steps on the
    trigonometric polynomial itself (exact derivatives). The result is exact to round-off
    unless another lobe whose samples fall lower is in fact higher; that can only happen for
    lobes tying within the sampling error ``1 - cos(pi/16) = 1.9 %`` of the highest order's
    amplitude (default sampling), which bounds the error.

    Parameters
    ----------
    orders : array_like, shape (n_order,) [-]
    coeffs : array_like, shape (..., n_order), complex
    n_points : int, optional
        See :func:`synthesize`.

    Returns
    -------
    numpy.ndarray, shape (...) [unit of coeffs]

    Notes
    -----
    Lloyd's Register Naval Ships Rules Vol 2 Pt 5 Ch 1 Sec 3 ("half-range amplitudes ...
    synthesis of all harmonic orders"); Drapal & Novotny 2017 (crank-pulley 1/2 peak-to-peak).
    ``sum |X_n|`` is only an upper bound.
    """
    n_ord = np.asarray(orders, dtype=float).ravel()
    c = np.asarray(coeffs, dtype=complex)
    theta, x = synthesize(n_ord, c, n_points)
    return 0.5 * (_refined_max(n_ord, c, theta, x) + _refined_max(n_ord, -c, theta, -x))


_NEWTON_STEPS = 2


def _refined_max(orders: np.ndarray, c: np.ndarray, theta: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Maximum over theta of ``sum Re{c_n exp(j n theta)}`` from its periodic samples ``x``.

    Candidates: the largest sample of each of the ``_N_CANDIDATES`` blocks (of
    ``_BLOCK`` samples) with the largest maxima; each is refined (parabola, then Newton).
    """
    npts = x.shape[-1]
    nb = -(-npts // _BLOCK)
    pad = nb * _BLOCK - npts
    xb = np.concatenate([x, np.full(x.shape[:-1] + (pad,), -np.inf)], -1) if pad else x
    xb = xb.reshape(x.shape[:-1] + (nb, _BLOCK))
    kb = np.argmax(xb, axis=-1)  # (..., nb)
    bmax = np.take_along_axis(xb, kb[..., None], -1)[..., 0]
    n_cand = min(_N_CANDIDATES, nb)
    top = np.argpartition(-bmax, n_cand - 1, axis=-1)[..., :n_cand]  # (..., K)
    k = top * _BLOCK + np.take_along_axis(kb, top, -1)
    y0 = np.take_along_axis(x, k, -1)
    ym = np.take_along_axis(x, (k - 1) % npts, -1)
    yp = np.take_along_axis(x, (k + 1) % npts, -1)
    curv = ym + yp - 2.0 * y0
    shift = np.where(curv < 0, (ym - yp) / (2.0 * np.where(curv < 0, curv, -1.0)), 0.0)
    shift = np.clip(shift, -1.0, 1.0)
    h = theta[1] - theta[0]
    th = (k + shift) * h  # (..., K)
    lo, hi = th - h, th + h
    cc = c[..., None, :]
    m = _check_orders(orders)
    for _ in range(_NEWTON_STEPS):
        e = cc * _phasors(m, th)
        d1 = -(e.imag @ orders)  # d/dtheta of sum Re{c e^{j n theta}}
        d2 = -(e.real @ orders**2)
        step = np.where(d2 < 0, -d1 / np.where(d2 < 0, d2, -1.0), 0.0)
        th = np.clip(th + step, lo, hi)
    val = (cc * _phasors(m, th)).real.sum(-1)
    return np.maximum(val.max(-1), x.max(-1))


def _phasors(m: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """``exp(j m theta / 2)`` for integer ``m >= 1``, shape theta.shape + m.shape (powers)."""
    z = np.exp(0.5j * theta)[..., None]
    powers = np.cumprod(np.broadcast_to(z, theta.shape + (int(m.max()),)), axis=-1)
    return powers[..., m - 1]


_BLOCK = 8
_N_CANDIDATES = 3
