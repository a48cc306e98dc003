"""Journal-bearing mobility models (Booker's mobility method, rigid journal, rigid bearing).

All functions are pure NumPy, SI units in and out.

Conventions
-----------
* ``e`` is the vector from the bearing centre to the journal centre; ``eps = e / c`` with the
  radial clearance ``c`` and ``psi = c / R = 2 c / D`` (relative clearance, Butenschoen's
  ``(D - d) / d``).
* ``F`` is the **load applied to the journal** (N). In a steady state the oil film pushes
  back with ``-F``.
* The *load frame* has its first axis along ``F``: ``zeta = eps . F_hat`` and
  ``kappa = F_hat x eps`` (z-component of the cross product), i.e. ``zeta + i kappa`` is the
  eccentricity rotated by ``-angle(F)``. The dimensionless mobility ``M = (M_zeta, M_kappa)``
  is resolved in the same frame.
* Booker's mobility equation (vector form, any frame in which ``omega_bar`` is defined, see
  Booker 1965)::

      d eps / dt = |F| psi**2 / (mu L D) * M(eps, F_hat) + omega_bar * z_hat x eps,
      omega_bar = (omega_journal + omega_bearing) / 2

  ``V_s / c = d eps/dt - omega_bar z_hat x eps`` is the (normalised) squeeze velocity; the
  mobility vector gives its direction and magnitude per unit load.

Models
------
``"closed_form"``
    Booker's closed-form approximation of the short-bearing (pi-film) mobility.
``"exact"``
    Exact short-bearing pi-film mobility: numerical force integral (Gauss-Legendre in the
    Sommerfeld variable) and a safeguarded Newton root find for the squeeze direction. Accurate
    to ~1e-12 but slow: reference option.
``"exact_table"``
    The exact mobility as the closed form times a tabulated complex correction factor, bilinear
    interpolation on a 121 x 81 grid (built once, on first use, ~0.2 s). Maximum relative error of
    ``M`` against ``"exact"``: 2.5e-4 (:data:`EXACT_TABLE_MAX_REL_ERROR`, checked in the tests).
``"butenschoen"``
    Butenschoen's (1976) curve fits of the finite-length (B/D = 1/8 .. 1) solution, rotation and
    squeeze superposed and inverted into a mobility.
``"reynolds_map"``
    Finite-length mobility of the Reynolds equation with the Swift-Stieber condition, from the
    map computed once by checker's own solver (:mod:`checker.calc.reynolds_map`, L/D 1/16..1).
``"reynolds"``
    The same film solved directly at every call (:func:`checker.calc.reynolds.mobility_reynolds`;
    reference, about 0.1-0.3 s per point).

References
----------
.. [1] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [2] P. Flores et al., "Journal bearings subjected to dynamic loads: the analytical mobility
   method", 2006 (closed-form short-bearing mobility).
.. [3] F. W. Ocvirk, "Short-bearing approximation for full journal bearings", NACA TN 2808, 1952.
.. [4] H.-J. Butenschoen, "Das hydrodynamische, zylindrische Gleitlager endlicher Breite unter
   instationaerer Belastung", Dissertation, Universitaet Karlsruhe, 1976.
"""

from __future__ import annotations

import functools

import numpy as np
from numpy.typing import ArrayLike

from checker.calc import pi_film as pf
from checker.calc import reynolds_map as rm
from checker.calc.pi_film import check_in_disk as _check_in_disk
from checker.calc.pi_film import j_integrals as _j_integrals
from checker.calc.pi_film import m_closed as _m_closed
from checker.calc.pi_film import solve_alpha as _solve_alpha

__all__ = [
    "MOBILITY_MODELS",
    "EXACT_TABLE_MAX_REL_ERROR",
    "BUTENSCHOEN_B_OVER_D_RANGE",
    "mobility",
    "mobility_closed_form",
    "mobility_exact",
    "mobility_exact_table",
    "mobility_butenschoen",
    "squeeze_load_integral",
    "squeeze_load_radial",
    "butenschoen_sommerfeld_rotation",
    "butenschoen_attitude_angle",
    "butenschoen_sommerfeld_squeeze",
    "eccentricity_rate",
    "squeeze_velocity",
    "short_bearing_peak_pressure",
]

MOBILITY_MODELS = ("closed_form", "exact", "exact_table", "butenschoen", "reynolds_map", "reynolds")
"""Names accepted by the ``model`` argument."""

EXACT_TABLE_MAX_REL_ERROR = 2.5e-4
"""Bound on ``|M_table / M_exact - 1|`` of ``"exact_table"`` for ``|eps| <= 1 - 1e-8`` (measured
on 4000 random points biased towards ``eps -> 1``: 2.1e-4; re-checked in the tests)."""

BUTENSCHOEN_B_OVER_D_RANGE = (0.125, 1.0)
"""Range of width/diameter ratios covered by Butenschoen's tables and fits."""

_FOUR_OVER_PI = pf.FOUR_OVER_PI


# --------------------------------------------------------------------------------------------
# validation helpers
# --------------------------------------------------------------------------------------------
def _check_positive(name: str, value: np.ndarray) -> None:
    if not np.all(np.isfinite(value)) or np.any(value <= 0.0):
        raise ValueError(f"{name} must be finite and > 0, got {value!r}")


def _check_model(model: str) -> None:
    if model not in MOBILITY_MODELS:
        raise ValueError(f"unknown mobility model {model!r}; choose one of {MOBILITY_MODELS}")


def _check_b_over_d(b_over_d: np.ndarray) -> None:
    lo, hi = BUTENSCHOEN_B_OVER_D_RANGE
    if np.any(b_over_d < lo - 1e-9) or np.any(b_over_d > hi + 1e-9):
        raise ValueError(
            f"Butenschoen fits cover {lo} <= B/D <= {hi}; got B/D in "
            f"[{np.min(b_over_d):.4g}, {np.max(b_over_d):.4g}]"
        )


# --------------------------------------------------------------------------------------------
# closed form (Booker)
# --------------------------------------------------------------------------------------------
def mobility_closed_form(
    zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Booker's closed-form short-bearing mobility.

    .. math::

        M_\\zeta = \\frac{(1-\\zeta)^{5/2}}{\\pi (L/D)^2}, \\qquad
        M_\\kappa = -\\frac{4 \\kappa (1-\\zeta)^{3/2}}{\\pi^2 (L/D)^2}

    Parameters
    ----------
    zeta : array_like [-]
        Eccentricity ratio component along the load direction.
    kappa : array_like [-]
        Eccentricity ratio component across the load (``F_hat x eps``).
    l_over_d : array_like [-]
        Bearing (land) length over diameter.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
        Mobility components in the load frame (broadcast shape of the inputs).

    Notes
    -----
    Source: Booker J.F. (1965), "Dynamically loaded journal bearings: mobility method of
    solution", Trans. ASME J. Basic Eng. 87:537-546 (not read here); the form used is the one
    in ibell/pdsim ``PDSim/core/mobility.py``, which cites Flores P. et al. (2006), "Journal
    bearings subjected to dynamic loads: the analytical mobility method" (equation numbers
    not verified). Exact at ``eps = 0``; against the exact short-bearing pi-film mobility the
    magnitude ratio exact/closed-form lies in 0.943..1.131 and the direction differs by at most
    4.4 degrees over the whole disk; the along-load ratio M_zeta is 0.944..1.133 for
    eps <= 0.99 (computed here, see ``"exact"``). In steady rotation
    this makes h_min 0..+1.4 % optimistic (attitude within 0.7 deg).
    Validity: ``zeta**2 + kappa**2 < 1``, ``l_over_d > 0``; short-bearing theory is
    optimistic for L/D above about 0.25 (use ``"butenschoen"`` to gauge).
    """
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa, l_over_d)))
    _check_in_disk(z, k)
    _check_positive("l_over_d", lod)
    m = _m_closed(z + 1j * k) / lod**2
    return m.real, m.imag


# --------------------------------------------------------------------------------------------
# exact short-bearing pi-film mobility
# --------------------------------------------------------------------------------------------
def squeeze_load_integral(eps: ArrayLike, alpha: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Dimensionless load of a short pi-film bearing squeezed in direction ``alpha``.

    .. math::

        \\mathbf F = \\frac{\\mu L^3 R |V_s|}{c^3} \\mathbf G(\\varepsilon, \\alpha), \\quad
        \\mathbf G = \\int_{\\alpha-\\pi/2}^{\\alpha+\\pi/2}
        \\frac{\\cos(\\theta-\\alpha)\\,(\\cos\\theta, \\sin\\theta)}
        {(1-\\varepsilon\\cos\\theta)^3} \\, d\\theta

    ``theta`` and ``alpha`` are measured from the eccentricity direction; the film pressure
    ``p = 6 mu (L**2/4 - z**2) V_s.n / h**3`` is kept where ``V_s.n > 0``.

    Parameters
    ----------
    eps : array_like [-]
        Eccentricity ratio, ``0 <= eps < 1``.
    alpha : array_like [rad]
        Direction of the squeeze velocity relative to the eccentricity vector.

    Returns
    -------
    g_r, g_t : numpy.ndarray [-]
        Components of ``G`` along and across (``z_hat x e``) the eccentricity vector.

    Notes
    -----
    Derivation: the short-bearing
    (Ocvirk) Reynolds equation with Booker's squeeze-velocity substitution (Booker 1965).
    Pure approach (``alpha = 0``) equals :func:`squeeze_load_radial`.
    """
    e, a = np.broadcast_arrays(np.asarray(eps, dtype=float), np.asarray(alpha, dtype=float))
    if np.any(e < 0.0) or np.any(e >= 1.0) or not np.all(np.isfinite(e)):
        raise ValueError("eps must satisfy 0 <= eps < 1")
    g_r, g_t, _, _ = _j_integrals(e, a)
    return g_r, g_t


def squeeze_load_radial(eps: ArrayLike) -> np.ndarray:
    """Closed-form ``G`` for pure approach along the line of centres (short pi-film).

    .. math::

        G_{rad}(\\varepsilon) = \\frac{2\\left[(\\tfrac{\\pi}{2} - \\tfrac12\\arccos\\varepsilon)
        (1+2\\varepsilon^2) + \\tfrac32\\varepsilon\\sqrt{1-\\varepsilon^2}\\right]}
        {(1-\\varepsilon^2)^{5/2}}

    Parameters
    ----------
    eps : array_like [-]
        Signed eccentricity ratio, ``-1 < eps < 1``; negative values give the receding case.

    Returns
    -------
    numpy.ndarray [-]
        ``G_rad`` (load ``F = mu L**3 R eps_dot G_rad / c**2``).

    Notes
    -----
    Derived from the short-bearing (Ocvirk) film with Booker's squeeze velocity; identical to the
    bracket of
    Butenschoen's squeeze Sommerfeld number (So_V = 2 (B/D)**2 G_rad for the short bearing).
    """
    e = np.asarray(eps, dtype=float)
    if np.any(np.abs(e) >= 1.0) or not np.all(np.isfinite(e)):
        raise ValueError("|eps| must be < 1")
    return 2.0 * _squeeze_bracket(e) / _one_minus_sq(e) ** 2.5


def _m_exact(w: np.ndarray) -> np.ndarray:
    """Exact short pi-film mobility in the load frame times (L/D)**2 (complex)."""
    eps = np.abs(w)
    chi = -np.angle(w)  # load direction seen from the eccentricity vector
    m_cf = _m_closed(w)
    alpha0 = np.angle(m_cf) + chi  # closed-form squeeze direction, from e
    alpha = _solve_alpha(eps, chi, alpha0)
    g_r, g_t, _, _ = _j_integrals(eps, alpha)
    return np.exp(1j * (alpha - chi)) / (2.0 * np.hypot(g_r, g_t))


def mobility_exact(
    zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Exact short-bearing (Ocvirk pi-film) mobility by root finding.

    For the load direction ``chi`` (seen from the eccentricity vector) the squeeze direction
    ``alpha`` is found from ``arg G(eps, alpha) = chi`` (:func:`squeeze_load_integral`); then

    .. math::

        |\\mathbf M| = \\frac{(D/L)^2}{2 |\\mathbf G(\\varepsilon, \\alpha)|}, \\qquad
        \\angle \\mathbf M = \\alpha \\;(\\text{from } \\mathbf e)

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components in the load frame (``zeta**2 + kappa**2 < 1``).
    l_over_d : array_like [-]
        Bearing (land) length over diameter.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
        Mobility in the load frame.

    Notes
    -----
    Short-bearing (Ocvirk) film with Booker's squeeze velocity; reproduces Ocvirk's steady
    solution to rounding (tests). Root find converges to 1e-14 rad in ``alpha`` for
    ``eps <= 1 - 1e-12``. Cost: about 1 ms per 1000 points; use ``"exact_table"`` in orbits.
    """
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa, l_over_d)))
    _check_in_disk(z, k)
    _check_positive("l_over_d", lod)
    m = _m_exact(z + 1j * k) / lod**2
    return m.real, m.imag


# table of the complex ratio exact / closed form on (u, v):
#   d = 1 - zeta in (0, 2), u = ln(d / (2 - d));  kappa_max = sqrt(1 - zeta**2) = sqrt(d (2 - d))
#   v = asinh(|kappa| / d) / asinh(kappa_max / d) in [0, 1]
# u resolves both ends of the load line (zeta -> +-1) and v the two tangential scales
# |kappa| ~ d and |kappa| ~ sqrt(d) of the corner zeta -> 1; ratio is symmetric:
# r(zeta, -kappa) = conj(r(zeta, kappa)).
_TAB_D_MIN = 1e-8
_TAB_U_MAX = float(np.log((2.0 - _TAB_D_MIN) / _TAB_D_MIN))
_TAB_NU = 121
_TAB_NV = 81


def _tab_uv(zeta: np.ndarray, kappa_abs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d = np.clip(1.0 - zeta, _TAB_D_MIN, 2.0 - _TAB_D_MIN)
    dd = 2.0 - d
    u = np.log(d / dd)
    v = np.arcsinh(kappa_abs / d) / np.arcsinh(np.sqrt(d * dd) / d)
    return u, np.minimum(v, 1.0)


@functools.cache
def _exact_ratio_table() -> np.ndarray:
    u = np.linspace(-_TAB_U_MAX, _TAB_U_MAX, _TAB_NU)
    v = np.linspace(0.0, 1.0, _TAB_NV)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    d = 2.0 / (1.0 + np.exp(-uu))
    kmax = np.sqrt(d * (2.0 - d))
    kap = d * np.sinh(vv * np.arcsinh(kmax / d))
    w = (1.0 - d) + 1j * kap
    # points on the rim (eps = 1) are evaluated at eps = 1 - 1e-10 (limit is reached there)
    eps = np.abs(w)
    w = np.where(eps > 1.0 - 1e-10, w * ((1.0 - 1e-10) / np.maximum(eps, 0.5)), w)
    return _m_exact(w) / _m_closed(w)


def _m_exact_table(w: np.ndarray) -> np.ndarray:
    """Exact mobility via the tabulated ratio (load frame, times (L/D)**2, complex)."""
    tab = _exact_ratio_table()
    kap = w.imag
    u, v = _tab_uv(w.real, np.abs(kap))
    fu = (u + _TAB_U_MAX) * ((_TAB_NU - 1) / (2.0 * _TAB_U_MAX))
    fv = v * (_TAB_NV - 1)
    iu = np.minimum(fu.astype(np.intp), _TAB_NU - 2)
    iv = np.minimum(fv.astype(np.intp), _TAB_NV - 2)
    tu = fu - iu
    tv = fv - iv
    flat = tab.ravel()
    i0 = iu * _TAB_NV + iv
    r0 = flat[i0] + tv * (flat[i0 + 1] - flat[i0])
    r1 = flat[i0 + _TAB_NV] + tv * (flat[i0 + _TAB_NV + 1] - flat[i0 + _TAB_NV])
    r = r0 + tu * (r1 - r0)
    r = np.where(kap < 0.0, np.conj(r), r)
    return r * _m_closed(w)


def mobility_exact_table(
    zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Exact short-bearing mobility from a pre-computed table (fast reference option).

    ``M = r(zeta, kappa) * M_closed_form``; the complex ratio ``r`` (|r| in 0.943..1.131,
    phase within +-4.4 degrees) is tabulated once on a 121 x 81 grid in the coordinates
    ``u = ln(d / (2 - d))``, ``v = asinh(|kappa|/d) / asinh(sqrt(1 - zeta**2)/d)``,
    ``d = 1 - zeta``, and interpolated bilinearly (``r(zeta, -kappa) = conj r``).

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components in the load frame (``zeta**2 + kappa**2 < 1``).
    l_over_d : array_like [-]
        Bearing (land) length over diameter.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
        Mobility in the load frame.

    Notes
    -----
    Interpolation error: ``|M_table/M_exact - 1| <= EXACT_TABLE_MAX_REL_ERROR`` (2.5e-4) for
    ``1 - zeta >= 1e-8``; beyond, ``r`` is held at the ``1 - zeta = 1e-8`` value (film collapse
    region). Grid convergence measured: 61x41 -> 1.2e-3, 121x81 -> 2.1e-4, 241x161 -> 7e-5.
    Table build on first call: about 0.2 s. Cost per call about 12x the closed form.
    """
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa, l_over_d)))
    _check_in_disk(z, k)
    _check_positive("l_over_d", lod)
    m = _m_exact_table(z + 1j * k) / lod**2
    return m.real, m.imag


# --------------------------------------------------------------------------------------------
# squeeze bracket without cancellation (shared by the short-bearing and Butenschoen squeeze)
# --------------------------------------------------------------------------------------------
_G_SERIES_SWITCH = 1.0
"""Angle [rad] below which :func:`_bracket_of_angle` sums its Taylor series (direct formula
above: its two terms are then at most 7 times the result, so no significant cancellation)."""
_G_SERIES = np.array([(-1.0) ** k * (2 * k - 2) * 2.0 ** (2 * k + 1) / 4.0
                      / float(np.prod(np.arange(1, 2 * k + 2, dtype=float)))
                      for k in range(2, 13)])
"""Coefficients ``c_k`` of ``g(phi) = phi^5 sum_k c_k phi^(2k-4)``, k = 2..12 (see
:func:`_squeeze_bracket`); truncation error below 1e-16 relative for phi < 1."""
_G_POWERS = np.arange(_G_SERIES.size, dtype=float)


def _one_minus_sq(e: np.ndarray) -> np.ndarray:
    """``1 - e**2`` as ``(1 - e)(1 + e)``: exact to rounding also for ``|e| -> 1``."""
    return (1.0 - e) * (1.0 + e)


def _squeeze_bracket(es: np.ndarray) -> np.ndarray:
    """The squeeze-load bracket ``(pi/2 - acos(es)/2)(1 + 2 es^2) + 3/2 es sqrt(1 - es^2)``
    for signed ``es`` in (-1, 1), evaluated without cancellation.

    With ``phi = acos(-es)`` (``es = -cos(phi)``, ``sqrt(1 - es^2) = sin(phi)``) the bracket
    is ``g(phi) = phi/2 (1 + 2 cos^2 phi) - 3/2 cos(phi) sin(phi)
    = [2u + u cos(u) - 3 sin(u)] / 4`` with ``u = 2 phi`` (trigonometric identities). For the
    receding case ``es -> -1`` (``phi -> 0``) the two terms cancel to ``(2/15) phi^5``, so the
    direct formula loses all digits below ``1 - |es|`` of about 1e-4 (and returned 0, NaN or
    the wrong sign beyond 1e-8). Below ``phi = 1`` the Taylor series of the bracket in ``u`` is
    summed instead: ``g = 1/4 sum_{k>=2} (-1)^k (2k - 2) u^(2k+1) / (2k+1)!`` (term by term
    from the series of ``sin`` and ``cos``; the ``u`` and ``u^3`` terms vanish).
    """
    return _bracket_of_angle(np.arccos(-es))


def _bracket_of_angle(phi: np.ndarray) -> np.ndarray:
    """``g(phi)`` of :func:`_squeeze_bracket` for ``0 <= phi <= pi``."""
    c, sn = np.cos(phi), np.sin(phi)
    direct = 0.5 * phi * (1.0 + 2.0 * c * c) - 1.5 * c * sn
    return np.where(phi < _G_SERIES_SWITCH, _bracket_series(phi), direct)


def _bracket_series(phi: np.ndarray) -> np.ndarray:
    """Taylor series of ``g(phi)`` (accurate for ``phi < _G_SERIES_SWITCH``)."""
    p2 = phi * phi
    return (p2[..., None] ** _G_POWERS) @ _G_SERIES * (p2 * p2 * phi)


# --------------------------------------------------------------------------------------------
# Butenschoen finite-length fits
# --------------------------------------------------------------------------------------------
def _butenschoen_coefficients(x: np.ndarray) -> np.ndarray:
    """Coefficients a1..a9 of Butenschoen's fits for B/D = x; shape (9,) + x.shape."""
    x2, x3, x4 = x * x, x**3, x**4
    return np.stack(
        [
            1.1642 - 1.9456 * x + 7.1161 * x2 - 10.1073 * x3 + 5.0141 * x4,
            -1.000026 - 0.023634 * x - 0.4215 * x2 - 0.038817 * x3 - 0.090551 * x4,
            1.152624 - 0.104565 * x,
            -2.5905 + 0.798745 * x,
            8.73393 - 2.3291 * x,
            -13.3414 + 3.424337 * x,
            6.6294 - 1.591732 * x,
            0.70038 + 3.2415 * x - 12.2486 * x2 + 18.895 * x3 - 9.3561 * x4,
            -0.999935 + 0.0157434 * x - 0.74224 * x2 + 0.42278 * x3 - 0.368928 * x4,
        ]
    )


def _bt_so_rot_over_eps(e: np.ndarray, x: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Butenschoen rotation Sommerfeld number divided by |eps| (finite at eps = 0)."""
    # x^2 / (2 (1-e^2)^2) ... a1 (e - 1) / (a2 + e) with one factor (1 - e) cancelled by hand
    q2 = _one_minus_sq(e)
    return (
        -x * x / (2.0 * (1.0 - e) * (1.0 + e) ** 2) * np.sqrt(np.pi**2 * q2 + 16.0 * e * e)
        * a[0] / (a[1] + e)
    )


def _bt_beta(e: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Butenschoen attitude angle; below eps = 0.1 linear from the fit at 0.1 to pi/2 at 0."""
    ep = np.maximum(e, 0.1)
    poly = a[2] + ep * (a[3] + ep * (a[4] + ep * (a[5] + ep * a[6])))
    beta = np.arctan2(np.pi * np.sqrt(_one_minus_sq(ep)), 2.0 * ep) * poly
    return np.where(e < 0.1, 0.5 * np.pi + (beta - 0.5 * np.pi) * (e / 0.1), beta)


def _bt_so_sq(es: np.ndarray, x: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Butenschoen squeeze Sommerfeld number at signed eps (sign of d eps/dt)."""
    br = _squeeze_bracket(es)
    return 4.0 * x * x * br / _one_minus_sq(es) ** 2.5 * a[7] * (1.0 - es) / (-a[8] - es)


def _bt_inv_so_sq_pair(e: np.ndarray, x: np.ndarray, a: np.ndarray):
    """1/So_V at +eps and -eps (eps >= 0) (same as :func:`_bt_so_sq`, without cancellation).

    ``1/So_V(+-eps) = (1 - eps^2)^(5/2) (-a9 -+ eps) / (4 x^2 a8 g(acos(-+eps)) (1 -+ eps))``
    with the bracket ``g`` of :func:`_squeeze_bracket`; at ``-eps`` the ratio
    ``sin(phi)^5 / g(phi)`` (``phi = acos(eps)``) is evaluated as such: both factors vanish
    like ``phi^5`` as eps -> 1, the ratio tends to 15/2.
    """
    ome, ope = 1.0 - e, 1.0 + e
    q2 = ome * ope
    sq = np.sqrt(q2)
    phi = np.arccos(e)  # recession: g(phi) with cos(phi) = eps, sin(phi) = sqrt(1 - eps^2)
    half_c1 = 0.5 + e * e  # (1 + 2 eps^2) / 2
    b = 1.5 * e * sq
    g_m = np.where(phi < _G_SERIES_SWITCH, _bracket_series(phi), phi * half_c1 - b)
    g_p = (np.pi - phi) * half_c1 + b  # approach: no cancellation (g -> 3 pi / 2)
    pre = 1.0 / (4.0 * x * x * a[7])
    # (1 - eps^2)^2 / (1 - eps) = (1 - eps)(1 + eps)^2, cancelled by hand
    inv_p = pre * (ome * ope * ope * sq) * (-a[8] - e) / g_p
    inv_m = pre * (q2 * q2 * sq / g_m) * (-a[8] + e) / ope
    return inv_p, inv_m


def butenschoen_sommerfeld_rotation(eps: ArrayLike, b_over_d: ArrayLike) -> np.ndarray:
    """Butenschoen's Sommerfeld number for pure rotation of a finite-length bearing.

    .. math::

        So_D = \\frac{(B/D)^2 \\varepsilon}{2 (1-\\varepsilon^2)^2}
        \\sqrt{\\pi^2 (1-\\varepsilon^2) + 16 \\varepsilon^2}\\;
        \\frac{a_1 (\\varepsilon - 1)}{a_2 + \\varepsilon},
        \\qquad |F| = So_D\\, B D \\eta |\\omega_{res}| / \\psi^2

    Parameters
    ----------
    eps : array_like [-]
        Eccentricity ratio, ``0 <= eps < 1``.
    b_over_d : array_like [-]
        Width over diameter, 1/8 .. 1.

    Returns
    -------
    numpy.ndarray [-]

    Notes
    -----
    Butenschoen H.-J. (1976), "Das hydrodynamische, zylindrische Gleitlager endlicher Breite
    unter instationaerer Belastung", Diss. TU Karlsruhe (not read); fit coefficients as in
    alex-marinov/mbdyn ``hydrodynamic_plain_bearing_force.f95``.
    Error against Butenschoen's tables (tests): -3.3 % .. +6.8 % for eps = 0.1 .. 0.99.
    """
    e, x = np.broadcast_arrays(np.asarray(eps, dtype=float), np.asarray(b_over_d, dtype=float))
    if np.any(e < 0.0) or np.any(e >= 1.0):
        raise ValueError("eps must satisfy 0 <= eps < 1")
    _check_b_over_d(x)
    return e * _bt_so_rot_over_eps(e, x, _butenschoen_coefficients(x))


def butenschoen_attitude_angle(eps: ArrayLike, b_over_d: ArrayLike) -> np.ndarray:
    """Butenschoen's attitude angle ``beta`` between load and eccentricity (pure rotation).

    .. math::

        \\beta = \\arctan\\frac{\\pi\\sqrt{1-\\varepsilon^2}}{2\\varepsilon}
        (a_3 + a_4\\varepsilon + a_5\\varepsilon^2 + a_6\\varepsilon^3 + a_7\\varepsilon^4)

    Parameters
    ----------
    eps : array_like [-]
        Eccentricity ratio, ``0 <= eps < 1``.
    b_over_d : array_like [-]
        Width over diameter, 1/8 .. 1.

    Returns
    -------
    numpy.ndarray [rad]

    Notes
    -----
    Source as :func:`butenschoen_sommerfeld_rotation`. Error against the tables: within
    +-2.4 degrees for eps = 0.1 .. 0.99. The fit exceeds 90 degrees for eps < 0.05; below
    eps = 0.1 this module interpolates linearly between the fit at eps = 0.1 and 90 degrees at
    eps = 0 (the short-bearing limit), which keeps the mobility continuous at the centre.
    """
    e, x = np.broadcast_arrays(np.asarray(eps, dtype=float), np.asarray(b_over_d, dtype=float))
    if np.any(e < 0.0) or np.any(e >= 1.0):
        raise ValueError("eps must satisfy 0 <= eps < 1")
    _check_b_over_d(x)
    return _bt_beta(e, _butenschoen_coefficients(x))


def butenschoen_sommerfeld_squeeze(eps: ArrayLike, b_over_d: ArrayLike) -> np.ndarray:
    """Butenschoen's Sommerfeld number for pure squeeze (approach along the line of centres).

    .. math::

        So_V = \\frac{4 (B/D)^2}{(1-\\varepsilon^2)^{5/2}}
        \\left[(\\tfrac{\\pi}{2} - \\tfrac12 \\arccos\\varepsilon)(1+2\\varepsilon^2)
        + \\tfrac32 \\varepsilon\\sqrt{1-\\varepsilon^2}\\right]
        \\frac{a_8 (1-\\varepsilon)}{-a_9-\\varepsilon},
        \\qquad F_V = So_V B D \\eta \\dot\\varepsilon / \\psi^2

    Parameters
    ----------
    eps : array_like [-]
        Eccentricity ratio signed with the sign of ``d eps/dt`` (negative: receding),
        ``-1 < eps < 1``.
    b_over_d : array_like [-]
        Width over diameter, 1/8 .. 1.

    Returns
    -------
    numpy.ndarray [-]

    Notes
    -----
    Source as :func:`butenschoen_sommerfeld_rotation`. Error against the squeeze table
    (tests): within +-5.5 % except three table entries that look like typing errors
    (B/D = 1/2.5 at eps = 0.8: +26 %; B/D = 1/6 at eps = 0.99: +48 %; B/D = 1/2 at
    eps = 0.1: -6.9 %).
    """
    e, x = np.broadcast_arrays(np.asarray(eps, dtype=float), np.asarray(b_over_d, dtype=float))
    if np.any(np.abs(e) >= 1.0):
        raise ValueError("|eps| must be < 1")
    _check_b_over_d(x)
    return _bt_so_sq(e, x, _butenschoen_coefficients(x))


_BT_BLEND = 0.1


def _m_butenschoen(w: np.ndarray, x: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Butenschoen mobility in the load frame (complex, includes the B/D dependence).

    Load frame: F_hat = 1, e_r = exp(i psi), e_t = i exp(i psi), so F_hat.e_r = cos(psi),
    F_hat.e_t = -sin(psi). Tangential balance gives the rotation part, the remaining radial
    load F_V = F.e_r - |F.e_t| cot(beta) drives the squeeze (explicit inversion):

        M_r = F_V/|F| / So_V(+-eps),   M_t = (F_hat.e_t) / (2 (So_D/eps) sin(beta))
    """
    e = np.abs(w)
    cpsi = np.where(e > 0.0, w.real / np.where(e > 0.0, e, 1.0), 1.0)
    spsi = np.where(e > 0.0, w.imag / np.where(e > 0.0, e, 1.0), 0.0)
    beta = _bt_beta(e, a)
    fv = cpsi - np.abs(spsi) * np.cos(beta) / np.sin(beta)
    # approach (fv > 0) uses So_V(+eps), recession So_V(-eps); the slope change is spread over
    # -_BT_BLEND < fv < 0 (smoothstep, C1) so that the Jacobian stays continuous
    inv_p, inv_m = _bt_inv_so_sq_pair(e, x, a)
    t = np.clip(-fv / _BT_BLEND, 0.0, 1.0)
    m_r = fv * (inv_p + (inv_m - inv_p) * (t * t * (3.0 - 2.0 * t)))
    m_t = -spsi / (2.0 * _bt_so_rot_over_eps(e, x, a) * np.sin(beta))
    return (cpsi + 1j * spsi) * (m_r + 1j * m_t)


def mobility_butenschoen(
    zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Finite-length mobility from Butenschoen's rotation and squeeze fits.

    With ``F_hat.e_r = zeta/eps``, ``F_hat.e_t = -kappa/eps`` and ``beta``, ``So_D``, ``So_V``
    from :func:`butenschoen_attitude_angle`, :func:`butenschoen_sommerfeld_rotation`,
    :func:`butenschoen_sommerfeld_squeeze`:

    .. math::

        M_r = \\frac{\\hat F\\cdot e_r - |\\hat F\\cdot e_t| \\cot\\beta}{So_V(\\pm\\varepsilon)},
        \\qquad M_t = \\frac{\\varepsilon\\, \\hat F\\cdot e_t}{2\\, So_D \\sin\\beta}

    (``So_V`` evaluated at ``+eps`` when the radial remainder pushes the journal outwards,
    else at ``-eps``.)

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components in the load frame (``zeta**2 + kappa**2 < 1``).
    l_over_d : array_like [-]
        Width (land) over diameter, 1/8 .. 1.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
        Mobility in the load frame.

    Notes
    -----
    Inversion of Butenschoen's force model (derived here). The
    superposition of a cavitated rotation and a cavitated squeeze force is an approximation
    (the short-bearing mobility of ``"exact"`` is not a superposition). Steady states
    reproduce the fitted So_D and beta exactly (tests). This module's choices: the switch
    from the approach branch ``So_V(+eps)`` to the (up to 10^4 times more mobile) recession
    branch ``So_V(-eps)`` is spread over ``-0.1 < F_V/|F| < 0`` with a C1 smoothstep (the
    approach side and all steady states are unchanged), and beta is taken linearly to 90 deg
    between eps = 0.1 and 0 (:func:`butenschoen_attitude_angle`). The model is stiff near the
    wall; :func:`checker.calc.orbit.solve_orbit` integrates it with ROS2. Finite for every
    ``eps < 1``: the receding squeeze bracket, a difference that cancels to ``(2/15) phi^5``
    as eps -> 1, is summed as its Taylor series there (:func:`_squeeze_bracket`; the direct
    difference returned NaN beyond 1 - eps ~ 1e-8), and ``1 - eps^2`` is formed as
    ``(1 - eps)(1 + eps)``.
    """
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa, l_over_d)))
    _check_in_disk(z, k)
    _check_b_over_d(lod)
    m = _m_butenschoen(z + 1j * k, lod, _butenschoen_coefficients(lod))
    return m.real, m.imag


# --------------------------------------------------------------------------------------------
# common interface
# --------------------------------------------------------------------------------------------
def mobility(
    zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike, model: str = "closed_form"
) -> tuple[np.ndarray, np.ndarray]:
    """Mobility vector in the load frame for the chosen model.

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components along / across the load (``zeta**2 + kappa**2 < 1``).
    l_over_d : array_like [-]
        Bearing (land) length over diameter.
    model : {"closed_form", "exact", "exact_table", "butenschoen", "reynolds_map", "reynolds"}
        See the module docstring.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
    """
    _check_model(model)
    if model in ("reynolds_map", "reynolds"):
        return _mobility_finite(zeta, kappa, l_over_d, model)
    fn = {
        "closed_form": mobility_closed_form,
        "exact": mobility_exact,
        "exact_table": mobility_exact_table,
        "butenschoen": mobility_butenschoen,
    }[model]
    return fn(zeta, kappa, l_over_d)


def _mobility_finite(zeta, kappa, l_over_d, model: str) -> tuple[np.ndarray, np.ndarray]:
    """Finite-length Reynolds mobility: stored map, or the solver itself (per point)."""
    from checker.calc import reynolds as ry  # scipy: only for the direct solution

    if model == "reynolds_map":
        return rm.mobility_map(zeta, kappa, l_over_d)
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa,
                                                                           l_over_d)))
    _check_in_disk(z, k)
    mz, mk = np.empty(z.shape), np.empty(z.shape)
    for idx in np.ndindex(z.shape):
        a, b = ry.mobility_reynolds(z[idx], k[idx], float(lod[idx]))
        mz[idx], mk[idx] = float(a), float(b)
    return mz, mk


def eccentricity_rate(
    load_x: ArrayLike,
    load_y: ArrayLike,
    eps_x: ArrayLike,
    eps_y: ArrayLike,
    omega_journal: ArrayLike,
    omega_bearing: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
    model: str = "closed_form",
    full_groove: ArrayLike = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Rate of the eccentricity-ratio vector from Booker's mobility equation.

    .. math::

        \\dot{\\boldsymbol\\varepsilon} = \\frac{|F| \\psi^2}{\\mu L D} \\mathbf M
        + \\bar\\omega\\, \\hat z \\times \\boldsymbol\\varepsilon, \\qquad
        \\psi = \\frac{2c}{D}, \\quad \\bar\\omega = \\frac{\\omega_J + \\omega_B}{2}

    All vectors and angular velocities must be expressed in one frame (see
    :mod:`checker.calc.orbit` for mains and big ends).

    Parameters
    ----------
    load_x, load_y : array_like [N]
        Load applied to the journal.
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector (journal centre relative to bearing centre over ``c``),
        ``|eps| < 1``.
    omega_journal, omega_bearing : array_like [rad/s]
        Angular velocities of journal and bearing in the frame of the vectors
        (counter-clockwise positive about z).
    diameter : array_like [m]
        Journal diameter ``D``.
    length : array_like [m]
        Effective bearing length ``L`` (grooves and chamfers excluded; with ``full_groove``
        the sum of both lands).
    clearance : array_like [m]
        Radial clearance ``c``.
    viscosity : array_like [Pa*s]
        Dynamic viscosity ``mu``.
    model : str
        Mobility model, one of :data:`MOBILITY_MODELS`.
    full_groove : array_like of bool
        Full circumferential central groove: two lands of ``length/2``, each carrying half the
        load (equivalent to one bearing of ``L/2`` with the full ``F/(mu L D)``).

    Returns
    -------
    rate_x, rate_y : numpy.ndarray [1/s]

    Notes
    -----
    Booker J.F. (1965), J. Basic Eng. 87:537-546 (mobility method; not read); the vector form and
    ``omega_bar`` are derived here (module docstring).
    """
    wj, wb = np.broadcast_arrays(np.asarray(omega_journal, dtype=float),
                                 np.asarray(omega_bearing, dtype=float))
    if not (np.all(np.isfinite(wj)) and np.all(np.isfinite(wb))):
        raise ValueError("angular velocities must be finite")
    vx, vy = squeeze_velocity(load_x, load_y, eps_x, eps_y, diameter, length, clearance,
                              viscosity, model, full_groove)
    z = np.asarray(eps_x, dtype=float) + 1j * np.asarray(eps_y, dtype=float)
    rate = (vx + 1j * vy) + 0.5j * (wj + wb) * z
    return rate.real, rate.imag


def squeeze_velocity(
    load_x: ArrayLike,
    load_y: ArrayLike,
    eps_x: ArrayLike,
    eps_y: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
    model: str = "closed_form",
    full_groove: ArrayLike = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Squeeze velocity over clearance that carries the load, by the mobility method.

    .. math::

        \\frac{\\mathbf V_s}{c} = \\dot{\\boldsymbol\\varepsilon}
        - \\bar\\omega\\,\\hat z \\times \\boldsymbol\\varepsilon
        = \\frac{|F| \\psi^2}{\\mu L D} \\mathbf M(\\boldsymbol\\varepsilon, \\hat F),
        \\qquad \\psi = \\frac{2c}{D}

    Parameters
    ----------
    load_x, load_y : array_like [N]
        Load applied to the journal.
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector, ``|eps| < 1`` (same frame).
    diameter, length, clearance, viscosity : array_like [m, m, m, Pa*s]
        As in :func:`eccentricity_rate`.
    model : str
        Mobility model, one of :data:`MOBILITY_MODELS`.
    full_groove : array_like of bool
        Full circumferential central groove (per entry): two lands of ``length/2``.

    Returns
    -------
    vs_x, vs_y : numpy.ndarray [1/s]

    Notes
    -----
    Booker J.F. (1965), J. Basic Eng. 87:537-546; the part of :func:`eccentricity_rate`
    without the whirl term ``omega_bar z_hat x eps``.
    """
    _check_model(model)
    fx, fy, ex, ey, dia, ln, cl, mu, grooved = np.broadcast_arrays(
        *(
            np.asarray(a, dtype=float)
            for a in (load_x, load_y, eps_x, eps_y, diameter, length, clearance, viscosity)
        ),
        np.asarray(full_groove, dtype=bool),
    )
    for name, val in (("diameter", dia), ("length", ln), ("clearance", cl), ("viscosity", mu)):
        _check_positive(name, val)
    if not (np.all(np.isfinite(fx)) and np.all(np.isfinite(fy))):
        raise ValueError("load must be finite")
    _check_in_disk(ex, ey)
    land = np.where(grooved, ln / 2.0, ln)
    lod = land / dia
    f = fx + 1j * fy
    fa = np.abs(f)
    u = np.where(fa > 0.0, f / np.where(fa > 0.0, fa, 1.0), 1.0)
    z = ex + 1j * ey
    wz = z * np.conj(u)
    if model == "butenschoen":
        _check_b_over_d(lod)
        m = _m_butenschoen(wz, lod, _butenschoen_coefficients(lod))
    elif model in ("reynolds_map", "reynolds"):
        mz, mk = _mobility_finite(wz.real, wz.imag, lod, model)
        m = mz + 1j * mk
    else:
        m = {"closed_form": _m_closed, "exact": _m_exact, "exact_table": _m_exact_table}[model](
            wz
        ) / lod**2
    psi = 2.0 * cl / dia
    v = fa * psi**2 / (mu * ln * dia) * u * m
    return v.real, v.imag


def short_bearing_peak_pressure(
    eps_x: ArrayLike,
    eps_y: ArrayLike,
    vs_x: ArrayLike,
    vs_y: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Peak film pressure of a short (Ocvirk) pi-film for a given squeeze velocity.

    .. math::

        p(\\theta, 0) = \\frac{3 \\mu L^2}{2 c^2} \\frac{|V_s|}{c}
        \\frac{\\cos(\\theta-\\alpha)}{(1-\\varepsilon\\cos\\theta)^3}, \\quad
        \\cos(\\theta-\\alpha) > 0

    maximised over ``theta`` (measured from the eccentricity vector); ``alpha`` is the
    direction of ``V_s`` from ``e``. The maximum is found in the Sommerfeld variable ``gamma``
    (the expression becomes a degree-3 trigonometric polynomial) by a 24-point scan and four
    Newton steps.

    Parameters
    ----------
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector, ``|eps| < 1``.
    vs_x, vs_y : array_like [1/s]
        Squeeze velocity over clearance, ``V_s / c = d eps/dt - omega_bar z_hat x eps``.
    length : array_like [m]
        Land length (per land for a grooved bearing).
    clearance : array_like [m]
        Radial clearance.
    viscosity : array_like [Pa*s]
        Dynamic viscosity.

    Returns
    -------
    p_max : numpy.ndarray [Pa]
        Peak film pressure (0 for zero squeeze velocity).
    angle : numpy.ndarray [rad]
        Direction of the peak-pressure location in the frame of the vectors.

    Notes
    -----
    Short-bearing Reynolds equation (Ocvirk F.W., 1952, "Short-bearing approximation for full
    journal bearings", NACA TN 2808) with Booker's squeeze velocity; for steady rotation it
    reduces to Ocvirk's pressure (tests check ``cos theta_max = (1 - sqrt(1 + 24 eps**2)) /
    (4 eps)``). Short-bearing pressures are higher than finite-length ones.
    """
    ex, ey, vx, vy, ln, cl, mu = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (eps_x, eps_y, vs_x, vs_y, length, clearance,
                                                viscosity))
    )
    _check_in_disk(ex, ey)
    for name, val in (("length", ln), ("clearance", cl), ("viscosity", mu)):
        _check_positive(name, val)
    z = ex + 1j * ey
    v = vx + 1j * vy
    eps = np.abs(z)
    phi_e = np.where(eps > 0.0, np.angle(z), np.angle(v))
    alpha = np.angle(v) - phi_e
    q = np.sqrt((1.0 - eps) * (1.0 + eps))
    ca = np.cos(alpha)
    sb = q * np.sin(alpha)
    e = eps[..., None]

    def poly(g):  # P(gamma) * q**6 and its first two derivatives
        c, s = np.cos(g), np.sin(g)
        a_ = ca[..., None] * (c + e) + sb[..., None] * s
        a1 = -ca[..., None] * s + sb[..., None] * c
        a2 = -ca[..., None] * c - sb[..., None] * s
        b = 1.0 + e * c
        b1 = -e * s
        b2 = -e * c
        p0 = a_ * b * b
        p1 = a1 * b * b + 2.0 * a_ * b * b1
        p2 = a2 * b * b + 4.0 * a1 * b * b1 + 2.0 * a_ * (b1 * b1 + b * b2)
        return p0, p1, p2

    grid = np.linspace(-np.pi, np.pi, 24, endpoint=False)
    p0, _, _ = poly(np.broadcast_to(grid, eps.shape + grid.shape))
    g = grid[np.argmax(p0, axis=-1)][..., None]
    for _ in range(4):
        _, p1, p2 = poly(g)
        step = np.where(p2 < 0.0, -p1 / np.where(p2 < 0.0, p2, -1.0), 0.0)
        g = g + np.clip(step, -0.2, 0.2)
    p0, _, _ = poly(g)
    g = g[..., 0]
    pmax = np.maximum(p0[..., 0], 0.0) / q**6
    theta = 2.0 * np.arctan2(np.sqrt(1.0 - eps) * np.sin(0.5 * g), np.sqrt(1.0 + eps) *
                             np.cos(0.5 * g))
    p = 1.5 * mu * ln * ln / (cl * cl) * np.abs(v) * pmax
    return p, phi_e + theta
