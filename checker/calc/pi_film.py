"""Short-bearing (pi-film) kernels shared by :mod:`checker.calc.mobility` and
:mod:`checker.calc.reynolds_map`: Booker's closed-form mobility in the load frame, the
pi-film force integrals and the squeeze direction of a given load direction.

Kept in their own module so that the mobility models and the finite-length map (which is
expressed relative to the closed form) import this one without importing each other.
Equations and sources: :mod:`checker.calc.mobility` (Booker 1965).

References
----------
.. [1] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [2] F. W. Ocvirk, "Short-bearing approximation for full journal bearings", NACA TN 2808, 1952.
"""

from __future__ import annotations

import numpy as np

__all__ = ["FOUR_OVER_PI", "check_in_disk", "m_closed", "j_integrals", "solve_alpha"]

FOUR_OVER_PI = 4.0 / np.pi
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)


def check_in_disk(zeta: np.ndarray, kappa: np.ndarray) -> None:
    """Finite eccentricity components inside the unit disk, else ValueError."""
    if not (np.all(np.isfinite(zeta)) and np.all(np.isfinite(kappa))):
        raise ValueError("eccentricity components must be finite")
    if np.any(zeta * zeta + kappa * kappa >= 1.0):
        raise ValueError("eccentricity ratio must be < 1 (journal touching the bearing)")


def m_closed(w: np.ndarray) -> np.ndarray:
    """Closed-form mobility in the load frame times (L/D)**2, complex ``M_zeta + i M_kappa``."""
    s = 1.0 - w.real
    return s * np.sqrt(s) * (s - 1j * FOUR_OVER_PI * w.imag) / np.pi


def j_integrals(eps: np.ndarray, alpha: np.ndarray):
    """Force integrals of the short-bearing pi-film (see
    :func:`checker.calc.mobility.squeeze_load_integral`).

    Returns ``(g_r, g_t, h_r, h_t)``: ``G`` and ``dG/dalpha`` in the eccentricity frame.
    The integrals are evaluated with 16-point Gauss-Legendre quadrature in the Sommerfeld
    variable ``gamma`` (``1 - eps cos(theta) = (1 - eps**2) / (1 + eps cos(gamma))``), in which
    the integrands are trigonometric polynomials of degree 2, so the quadrature is exact to
    rounding; ``cos(gamma) + eps`` is evaluated as ``2 cos(gamma/2)**2 - (1 - eps)`` to keep
    full relative precision up to ``eps = 1 - 1e-12``.
    """
    e = eps[..., None]
    a = alpha[..., None]
    d = 1.0 - e
    sp = np.sqrt(1.0 + e)
    sd = np.sqrt(d)

    def gam(th):
        return 2.0 * np.arctan2(sp * np.sin(0.5 * th), sd * np.cos(0.5 * th))

    g1 = gam(a - 0.5 * np.pi)
    g2 = gam(a + 0.5 * np.pi)
    hw = 0.5 * (g2 - g1)
    g = 0.5 * (g1 + g2) + hw * _GL_X
    wq = hw * _GL_W
    cg = 2.0 * np.cos(0.5 * g) ** 2 - d  # cos(gamma) + eps
    sg = np.sin(g)
    q = np.sqrt(d * (1.0 + e))[..., 0]
    q2 = q * q
    j_ss = (wq * sg * sg).sum(-1) / (q2 * q)
    j_sc = (wq * sg * cg).sum(-1) / (q2 * q2)
    j_cc = (wq * cg * cg).sum(-1) / (q2 * q2 * q)
    ca = np.cos(alpha)
    sa = np.sin(alpha)
    return (
        ca * j_cc + sa * j_sc,
        ca * j_sc + sa * j_ss,
        ca * j_sc - sa * j_cc,
        ca * j_ss - sa * j_sc,
    )


def solve_alpha(eps: np.ndarray, chi: np.ndarray, alpha0: np.ndarray) -> np.ndarray:
    """Squeeze direction ``alpha`` whose pi-film load points at ``chi`` (both from e).

    ``f(alpha) = wrap(arg G - alpha) + alpha - chi`` is continuous and increasing (F . V_s > 0
    keeps ``arg G - alpha`` inside (-pi/2, pi/2)); the root lies in ``chi +- pi/2``.
    Safeguarded Newton, applied to the not-yet-converged entries only.
    """
    lo = chi - 0.5 * np.pi
    hi = chi + 0.5 * np.pi
    a = np.clip(alpha0, lo + 1e-12, hi - 1e-12)
    act = np.arange(a.size)
    a = a.ravel().copy()
    e_f, c_f, lo, hi = eps.ravel(), chi.ravel(), lo.ravel().copy(), hi.ravel().copy()
    for _ in range(200):
        if act.size == 0:
            break
        ea, aa, ca = e_f[act], a[act], c_f[act]
        g_r, g_t, h_r, h_t = j_integrals(ea, aa)
        f = np.angle(np.exp(1j * (np.arctan2(g_t, g_r) - aa))) + aa - ca
        la = np.where(f < 0.0, aa, lo[act])
        ha = np.where(f > 0.0, aa, hi[act])
        fp = (g_r * h_t - g_t * h_r) / (g_r * g_r + g_t * g_t)
        with np.errstate(divide="ignore", invalid="ignore"):
            an = aa - f / fp
        bad = ~((an > la) & (an < ha))
        an = np.where(bad, 0.5 * (la + ha), an)
        done = (np.abs(an - aa) < 1e-14) | (ha - la < 1e-14) | (f == 0.0)
        a[act], lo[act], hi[act] = an, la, ha
        act = act[~done]
    return a.reshape(eps.shape)
