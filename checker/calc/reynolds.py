"""Finite-length Reynolds equation of a journal bearing, solved by finite volumes.

Rigid, aligned, isoviscous journal bearing; Swift-Stieber (Reynolds) cavitation condition
``p >= 0`` written as a linear complementarity problem (LCP) and solved exactly (to rounding)
by the primal-dual active-set method on the sparse system. Pure NumPy/SciPy.

Booker's squeeze formulation
----------------------------
Journal and bearing surface speeds and the motion of the journal centre enter the Reynolds
equation only through the *squeeze velocity* ``V_s = d e/dt - omega_bar z_hat x e`` with
``omega_bar = (omega_journal + omega_bearing) / 2`` (Booker 1965):

.. math::

    \\nabla\\cdot\\left(h^3 \\nabla p\\right)
    = -12 \\mu\\, \\mathbf V_s\\cdot\\hat{\\mathbf n}(\\theta),
    \\qquad h = c\\,(1 - \\varepsilon\\cos\\theta)

with ``theta`` measured from the eccentricity vector (thinnest film at ``theta = 0``). With
``P = p psi^2 / (mu |v|)``, ``v = V_s / c`` [1/s], ``psi = c / R``, ``zeta = z / R`` this is the
dimensionless problem solved here:

.. math::

    -\\partial_\\theta(H^3 \\partial_\\theta P) - \\partial_\\zeta(H^3 \\partial_\\zeta P)
    = 12 \\cos(\\theta - \\alpha), \\quad H = 1 - \\varepsilon\\cos\\theta, \\quad
    P = 0 \\text{ at } \\zeta = \\pm L/D, \\quad P \\ge 0 \\;\\perp\\; \\text{residual} \\ge 0

``alpha`` is the direction of ``V_s`` measured from the eccentricity vector. The load the
film carries (= the load applied to the journal in quasi-static equilibrium) is

.. math::

    \\mathbf F = \\frac{\\mu |v| R^2}{\\psi^2} \\mathbf W, \\qquad
    \\mathbf W = \\int_{-L/D}^{L/D}\\int_0^{2\\pi} P\\,(\\cos\\theta, \\sin\\theta)
    \\,d\\theta\\,d\\zeta

(components along / across the eccentricity vector). Because the LCP is positively
homogeneous in its right-hand side, ``W`` per unit ``|v|`` depends on ``(eps, alpha, L/D)``
only: the impedance of the bearing. Derived quantities (module functions):

* mobility (Booker): ``|M| = 4 (L/D) / |W|`` along ``V_s``;
* Sommerfeld numbers of Butenschoen (1976): rotation ``So = eps |W(eps, -90 deg)| / (8 L/D)``
  with the attitude angle ``beta`` between load and eccentricity, squeeze
  ``So_V = |W(eps, 0)| / (4 L/D)``;
* side flow ``Q = c R^2 |v| Qbar`` out of both edges;
* peak pressure ``p_max = mu |v| P_max / psi^2``.

Discretisation
--------------
Node-centred finite volumes on a tensor grid that is uniform in mapped coordinates:
circumferentially a blend of the Sommerfeld substitution (clusters nodes around the thinnest
film, width ``~ sqrt(1 - eps)``) and a uniform grid; axially (half width, symmetry plane at
``zeta = 0``) a blend of a uniform grid and nodes clustered towards the edge over the same
width. Face conductances use ``H^3`` at the face, sources and load integrals use exact
integrals of the trigonometric factors over each control volume. The discrete operator is a
symmetric M-matrix, so the LCP has a unique solution and the primal-dual active-set iteration
(Hintermueller M., Ito K., Kunisch K., 2002, "The primal-dual active set strategy as a
semismooth Newton method", SIAM J. Optim. 13:865-888) reaches it in finitely many steps; it
stops when the active set repeats, i.e. when ``min(P, A P - f) = 0`` holds to rounding.

Accuracy (tests): Butenschoen's (1976) tables of the rotation and squeeze Sommerfeld numbers
and of the side flow, Ocvirk's short-bearing solution as ``L/D -> 0``, grid convergence.

References
----------
.. [1] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [2] H.-J. Butenschoen, "Das hydrodynamische, zylindrische Gleitlager endlicher Breite unter
   instationaerer Belastung", Dissertation, Universitaet Karlsruhe, 1976.
.. [3] F. W. Ocvirk, "Short-bearing approximation for full journal bearings", NACA TN 2808, 1952.
.. [4] M. Hintermueller, K. Ito, K. Kunisch, "The primal-dual active set strategy as a semismooth
   Newton method", SIAM J. Optim. 13, 2002, pp. 865-888.
.. [5] M. Giacopini, M. T. Fowell, D. Dini, A. Strozzi, "A mass-conserving complementarity
   formulation to study lubricant films in the presence of cavitation", J. Tribol. 132, 2010,
   041702.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike
from scipy.linalg import solveh_banded
from scipy.sparse.linalg import splu

from checker.calc import _checks
from checker.calc.bearing_performance import film_losses  # noqa: F401 (re-export)

__all__ = [
    "Grid",
    "DEFAULT_GRID",
    "FINE_GRID",
    "EPS_MAX",
    "L_OVER_D_RANGE",
    "FilmSolution",
    "solve_film",
    "sommerfeld_rotation",
    "sommerfeld_squeeze",
    "mobility_reynolds",
    "FilmState",
    "film_force",
    "film_losses",
]

EPS_MAX = 1.0 - 1e-5
"""Largest eccentricity ratio accepted by the solver (film 1e-5 c; far below any film that
matters: the grid is designed and checked for ``1 - eps >= 1e-4``)."""

L_OVER_D_RANGE = (1.0 / 64.0, 2.0)
"""Width (land length) over diameter accepted by the solver."""


@dataclass(frozen=True)
class Grid:
    """Finite-volume grid resolution.

    Attributes
    ----------
    n_theta : int
        Nodes around the circumference (periodic).
    n_z : int
        Cells across the half width (symmetry plane to edge).
    """

    n_theta: int = 144
    n_z: int = 24


DEFAULT_GRID = Grid()
"""Default resolution. Grid convergence (tests): second order; film load within 0.2 % of the
Richardson extrapolate for loaded (rotation, approach) states up to ``eps = 0.9999``; receding
states near the wall within 1 % (0.7 % at ``eps = 0.999``). Side flow and peak pressure within
0.2 %. One solution takes 10-50 ms."""

FINE_GRID = Grid(288, 48)
"""Twice the default resolution in each direction (reference for the convergence tests)."""

_BLEND_THETA = 0.3  # share of uniformly spaced nodes around the circumference
_BLEND_Z = 0.4  # share of uniformly spaced nodes across the half width


@dataclass(frozen=True)
class FilmSolution:
    """Dimensionless solution of one film (see the module docstring for the scaling).

    Attributes
    ----------
    w_r, w_t : float
        Load ``W`` along and across (``z_hat x e``) the eccentricity vector.
    p_max : float
        Peak dimensionless pressure ``P_max``.
    theta_p_max : float [rad]
        Location of the peak, from the eccentricity vector.
    q_side : float
        Side flow out of both edges, ``Q / (c R^2 |v|)``.
    iterations : int
        Active-set iterations used.
    theta, zeta : numpy.ndarray
        Node coordinates (half width, ``zeta >= 0``).
    pressure : numpy.ndarray, shape (n_theta, n_z + 1)
        Dimensionless pressure at the nodes (last column: edge, 0).
    """

    w_r: float
    w_t: float
    p_max: float
    theta_p_max: float
    q_side: float
    iterations: int
    theta: np.ndarray
    zeta: np.ndarray
    pressure: np.ndarray


# --------------------------------------------------------------------------------------------
# grid
# --------------------------------------------------------------------------------------------
def _sommerfeld_gamma(theta: np.ndarray, a: float) -> np.ndarray:
    """Sommerfeld variable: ``tan(gamma/2) = sqrt((1+a)/(1-a)) tan(theta/2)``, unwrapped."""
    t = np.asarray(theta, dtype=float)
    k = np.round(t / (2.0 * np.pi))
    r = t - 2.0 * np.pi * k
    g = 2.0 * np.arctan2(np.sqrt(1.0 + a) * np.sin(0.5 * r), np.sqrt(1.0 - a) * np.cos(0.5 * r))
    return g + 2.0 * np.pi * k


def _invert_monotone(fun, dfun, target: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Solve ``fun(x) = target`` for increasing ``fun`` on ``[lo, hi]``: a few bisection
    steps, then Newton (derivative ``dfun``) kept inside the bracket, to rounding."""
    a = np.full(target.shape, lo)
    b = np.full(target.shape, hi)
    for _ in range(6):
        m = 0.5 * (a + b)
        below = fun(m) < target
        a = np.where(below, m, a)
        b = np.where(below, b, m)
    x = 0.5 * (a + b)
    tol = 1e-15 * max(1.0, abs(lo), abs(hi))
    for _ in range(60):
        f = fun(x) - target
        a = np.where(f < 0.0, x, a)
        b = np.where(f < 0.0, b, x)
        xn = x - f / dfun(x)
        xn = np.where((xn >= a) & (xn <= b), xn, 0.5 * (a + b))
        done = np.max(np.abs(xn - x)) <= tol
        x = xn
        if done:
            break
    return x


@functools.lru_cache(maxsize=64)
def _theta_nodes(n: int, eps_key: float) -> tuple[np.ndarray, np.ndarray]:
    """Node and face angles (face k+1/2 between nodes k and k+1; last face wraps).

    Mapping ``s(theta) = (1 - b) gamma(theta) + b theta`` uniform in ``s`` (b =
    :data:`_BLEND_THETA`): Sommerfeld clustering at ``theta = 0`` plus a uniform share.
    """
    a = min(eps_key, 1.0 - 1e-9)
    b = _BLEND_THETA

    def s_of(t):
        return (1.0 - b) * _sommerfeld_gamma(t, a) + b * t

    q = np.sqrt((1.0 - a) * (1.0 + a))

    def ds(t):
        return (1.0 - b) * q / (1.0 - a * np.cos(t)) + b

    s_nodes = -np.pi + 2.0 * np.pi * np.arange(n) / n
    s_faces = s_nodes + np.pi / n
    if a == 0.0:
        return s_nodes, s_faces
    nodes = _invert_monotone(s_of, ds, s_nodes, -np.pi - 1e-12, np.pi + 1e-12)
    faces = _invert_monotone(s_of, ds, s_faces, -np.pi - 1e-12,
                             np.pi + 2.0 * np.pi / n + 1e-9)
    return nodes, faces


_GRID_EPS_STEP = 0.05  # grid clustering parameter: 1 - eps rounded to 5 % steps (log scale)


def _grid_eps(eps: float) -> float:
    """Eccentricity ratio used to cluster the grid: ``1 - eps`` rounded to
    :data:`_GRID_EPS_STEP` in ``ln(1 - eps)``, so that nearby eccentricities (orbits, root
    finds) share grids (cached) while every grid stays clustered at the right scale."""
    if eps <= 0.0:
        return 0.0
    k = round(np.log1p(-eps) / _GRID_EPS_STEP)
    return float(-np.expm1(k * _GRID_EPS_STEP))


def _edge_width(eps: float) -> float:
    """Axial width of the edge layer [in units of R]: width of the pressure peak,
    ``sqrt(2 (1 - eps))``."""
    return float(np.sqrt(2.0 * (1.0 - eps)))


@functools.lru_cache(maxsize=64)
def _zeta_nodes(n: int, half: float, width: float, groove: float) -> np.ndarray:
    """Axial nodes ``0 = zeta_0 < ... < zeta_n = half`` (edge at ``half``).

    Uniform share :data:`_BLEND_Z` plus nodes clustered towards the edge with an arctangent
    density of width ``width``. With a central groove of half width ``groove`` > 0, one node
    is placed on the groove edge and each part gets a proportional share of the nodes.
    """
    if groove > 0.0:
        n_g = max(2, int(round(n * groove / half)))
        n_g = min(n_g, n - 4)
        inner = np.linspace(0.0, groove, n_g + 1)
        outer = groove + _zeta_nodes(n - n_g, half - groove, width, 0.0)
        return np.concatenate([inner, outer[1:]])
    s = np.linspace(0.0, 1.0, n + 1)
    w = max(width, 1e-6)
    b = _BLEND_Z
    lo = np.arctan(-half / w)

    def g(z):
        return b * z / half + (1.0 - b) * (np.arctan((z - half) / w) - lo) / (0.0 - lo)

    def dg(z):
        u = (z - half) / w
        return b / half + (1.0 - b) / (w * (1.0 + u * u) * (0.0 - lo))

    z = _invert_monotone(g, dg, s, 0.0, half)
    z[0], z[-1] = 0.0, half
    return z


# --------------------------------------------------------------------------------------------
# single-threaded BLAS for the small banded factorisations
# --------------------------------------------------------------------------------------------
@functools.cache
def _blas_thread_setter():
    """``openblas_set_num_threads_local`` of SciPy's bundled OpenBLAS, or None.

    The banded Cholesky factorisation of a few thousand unknowns takes ~2 ms on one thread;
    with OpenBLAS worker threads on a loaded machine it was measured 1000 times slower.
    """
    try:
        import ctypes
        import glob
        import os

        import scipy

        root = os.path.dirname(os.path.dirname(scipy.__file__))
        for path in glob.glob(os.path.join(root, "scipy.libs", "libscipy_openblas*.so*")):
            lib = ctypes.CDLL(path)
            fn = getattr(lib, "openblas_set_num_threads_local", None)
            if fn is not None:
                fn.restype = ctypes.c_int
                fn.argtypes = [ctypes.c_int]
                return fn
    except OSError:  # pragma: no cover - platform without the bundled library
        return None
    return None


def _solveh_banded_1t(ab: np.ndarray, b: np.ndarray) -> np.ndarray:
    setter = _blas_thread_setter()
    if setter is None:
        return solveh_banded(ab, b, check_finite=False)
    old = setter(1)
    try:
        return solveh_banded(ab, b, check_finite=False)
    finally:
        setter(max(int(old), 1))


# --------------------------------------------------------------------------------------------
# assembly and LCP
# --------------------------------------------------------------------------------------------
@dataclass
class _System:
    """Five-point operator on the half-width grid, theta-major unknowns ``(i, j)``.

    ``diag`` (n, m); ``cth[i, j]`` couples ``(i, j)`` with ``(i + 1 mod n, j)``; ``cz[i, j]``
    couples ``(i, j)`` with ``(i, j + 1)`` (m - 1 columns); the edge face (Dirichlet 0) is
    in ``diag``.
    """

    diag: np.ndarray
    cth: np.ndarray
    cz: np.ndarray
    theta: np.ndarray
    faces: np.ndarray
    zeta: np.ndarray
    dz: np.ndarray  # control-volume widths in zeta (m,)
    cz_edge: np.ndarray  # conductance of the edge face per theta node (n,)
    fixed: np.ndarray  # bool (n, m): unknowns held at P = 0 (groove)
    last_active: np.ndarray | None = None
    last_alpha: float = 0.0

    def apply(self, p: np.ndarray) -> np.ndarray:
        """``A p`` for ``p`` of shape (n, m)."""
        out = self.diag * p
        out -= self.cth * np.roll(p, -1, axis=0)
        out -= np.roll(self.cth * p, 1, axis=0)
        out[:, :-1] -= self.cz * p[:, 1:]
        out[:, 1:] -= self.cz * p[:, :-1]
        return out


def _assemble(eps: float, half: float, grid: Grid, groove=None, supply=None) -> _System:
    n, m = grid.n_theta, grid.n_z
    eg = _grid_eps(eps)
    th, fa = _theta_nodes(n, eg)
    g_half = 0.0 if groove is None else float(groove[2])
    z = _zeta_nodes(m, float(half), _edge_width(eg), g_half)
    # control volumes in zeta: node j owns [z_{j-1/2}, z_{j+1/2}] (j = 0: from 0)
    zm = 0.5 * (z[1:] + z[:-1])  # faces j+1/2, j = 0..m-1
    dz = np.empty(m)
    dz[0] = zm[0]
    dz[1:] = zm[1:] - zm[:-1]
    # theta: face k+1/2 at fa[k]; cell k spans fa[k-1] .. fa[k]
    fa_prev = np.roll(fa, 1)
    fa_prev[0] -= 2.0 * np.pi
    dth_nodes = np.roll(th, -1) - th
    dth_nodes[-1] += 2.0 * np.pi
    h_face = 1.0 - eps * np.cos(fa)
    h_node = 1.0 - eps * np.cos(th)
    cth = (h_face**3 / dth_nodes)[:, None] * dz[None, :]  # (n, m)
    czf = h_node[:, None] ** 3 * (fa - fa_prev)[:, None] / (z[1:] - z[:-1])[None, :]  # (n, m)
    diag = cth + np.roll(cth, 1, axis=0)
    diag[:, :-1] += czf[:, :-1]
    diag[:, 1:] += czf[:, :-1]
    diag[:, -1] += czf[:, -1]
    fixed = np.zeros((n, m), dtype=bool)
    if groove is not None:
        t0, span = float(groove[0]), float(groove[1])
        in_arc = ((th - t0) % (2.0 * np.pi)) <= span + 1e-12
        fixed = in_arc[:, None] & (z[:-1] <= g_half + 1e-12)[None, :]
    if supply is not None:
        k = int(np.argmin(np.abs(np.angle(np.exp(1j * (th - supply))))))
        fixed[k, :] = True
    return _System(diag, cth, czf[:, :-1].copy(), th, fa, z, dz, czf[:, -1].copy(), fixed)


@functools.lru_cache(maxsize=256)
def _system_cached(eps: float, half: float, grid: Grid, groove, supply) -> _System:
    return _assemble(eps, half, grid, groove, supply)


def _source(sys_: _System, alpha: float) -> np.ndarray:
    """Right-hand side ``int 12 cos(theta - alpha)`` over each control volume, (n, m)."""
    fa = sys_.faces
    fa_prev = np.roll(fa, 1)
    fa_prev[0] -= 2.0 * np.pi
    s = 12.0 * (np.sin(fa - alpha) - np.sin(fa_prev - alpha))
    return s[:, None] * sys_.dz[None, :]


def _solve_restricted(s: _System, f: np.ndarray, active: np.ndarray) -> np.ndarray:
    """Solve ``A_II p_I = f_I`` with ``p = 0`` on the active set (banded Cholesky).

    The periodic direction is cut at a theta line that is entirely active (then the
    restricted operator has half-bandwidth m); without such a line the wrap-around
    coupling is kept by a dense-free fallback (sparse LU).
    """
    n, m = s.diag.shape
    full_lines = np.flatnonzero(active.all(axis=1))
    free = ~active
    if full_lines.size == 0:
        return _solve_restricted_lu(s, f, active)
    k = int(full_lines[0])
    order = (np.arange(n) + k + 1) % n  # rolled line order; line k last
    fr = free[order]
    d = np.where(fr, s.diag[order], 1.0)
    cz = s.cz[order] * (fr[:, 1:] & fr[:, :-1])
    cth = s.cth[order] * (fr & np.roll(fr, -1, axis=0))
    cth[-1] = 0.0  # wrap coupling (through the active line k)
    ab = np.zeros((m + 1, n * m))
    ab[m] = d.ravel()
    sup1 = np.zeros((n, m))
    sup1[:, 1:] = -cz
    ab[m - 1] = sup1.ravel()
    ab[0, m:] = -cth.ravel()[:-m]
    rhs = np.where(fr, f[order], 0.0).ravel()
    x = _solveh_banded_1t(ab, rhs).reshape(n, m)
    p = np.empty((n, m))
    p[order] = np.where(fr, x, 0.0)
    return p


def _solve_restricted_lu(s: _System, f: np.ndarray, active: np.ndarray) -> np.ndarray:
    n, m = s.diag.shape
    idx = np.arange(n * m).reshape(n, m)
    nxt = np.roll(idx, -1, axis=0)
    rows = np.concatenate([idx.ravel(), idx.ravel(), nxt.ravel(), idx[:, :-1].ravel(),
                           idx[:, 1:].ravel()])
    cols = np.concatenate([idx.ravel(), nxt.ravel(), idx.ravel(), idx[:, 1:].ravel(),
                           idx[:, :-1].ravel()])
    vals = np.concatenate([s.diag.ravel(), -s.cth.ravel(), -s.cth.ravel(), -s.cz.ravel(),
                           -s.cz.ravel()])
    a = sp.csr_matrix((vals, (rows, cols)), shape=(n * m, n * m))
    fi = np.flatnonzero(~active.ravel())
    p = np.zeros(n * m)
    if fi.size:
        p[fi] = splu(a[fi][:, fi].tocsc(), permc_spec="MMD_AT_PLUS_A").solve(f.ravel()[fi])
    return p.reshape(n, m)


_MAX_ACTIVE_SET_ITER = 200


def _solve_lcp(s: _System, f: np.ndarray, active0: np.ndarray | None
               ) -> tuple[np.ndarray, np.ndarray, int]:
    """Primal-dual active-set solution of ``P >= 0, A P - f >= 0, P (A P - f) = 0``.

    Unknowns in ``s.fixed`` (groove) are held at 0. Returns ``(P, active set, iterations)``;
    on return ``P >= 0`` on the free set with ``A P = f`` there, and ``A P - f > 0`` on the
    active set (to rounding). Raises RuntimeError if the active set does not settle (finite
    termination is guaranteed for M-matrices; not observed).
    """
    fixed = s.fixed
    active = (f <= 0.0) if active0 is None else active0.copy()
    active |= fixed
    scale = np.max(np.abs(f)) + 1e-300
    for it in range(1, _MAX_ACTIVE_SET_ITER + 1):
        p = _solve_restricted(s, f, active)
        lam = s.apply(p) - f
        tol_p = 1e-13 * (np.max(np.abs(p)) + 1e-300)
        tol_l = 1e-13 * scale
        new_active = (~active & (p < -tol_p)) | (active & (lam > tol_l))
        new_active |= fixed
        if np.array_equal(new_active, active):
            return np.maximum(p, 0.0), active, it
        active = new_active
    raise RuntimeError("Reynolds LCP: active set did not settle")


_WARM_DALPHA = 0.25  # [rad] reuse the last active set of the same system below this change
_COARSEST = (36, 6)  # nested iteration: coarsest grid


def _nested_guess(eps: float, half: float, grid: Grid, alpha: float, groove=None
                  ) -> np.ndarray | None:
    """Initial active set from the solution on a grid half as fine (recursively, down to
    :data:`_COARSEST`): nested iteration. The mapped grids nest (every second node of the
    fine grid is a coarse node), so the coarse pressure is prolonged by linear interpolation
    in the mapped coordinates; nodes where it is zero start active. This keeps the number of
    active-set iterations nearly independent of the resolution (without it, it grows about
    linearly with the resolution: the free boundary moves by a few nodes per iteration)."""
    n, m = grid.n_theta, grid.n_z
    if n % 2 or m % 2 or n // 2 < _COARSEST[0] or m // 2 < _COARSEST[1]:
        return None
    coarse = Grid(n // 2, m // 2)
    sc = _system_cached(eps, half, coarse, groove, None)
    if groove is not None:  # the composite axial grid nests only for some node counts
        sf = _system_cached(eps, half, grid, groove, None)
        if not np.allclose(sf.zeta[::2], sc.zeta, rtol=0.0, atol=1e-12):
            return None
    fc = _source(sc, alpha)
    pc, _, _ = _solve_lcp(sc, fc, _nested_guess(eps, half, coarse, alpha, groove))
    pcz = np.concatenate([pc, np.zeros((pc.shape[0], 1))], axis=1)  # with the edge column
    pf = np.zeros((n, m + 1))
    pf[0::2, 0::2] = pcz
    pf[1::2, 0::2] = 0.5 * (pcz + np.roll(pcz, -1, axis=0))
    pf[:, 1::2] = 0.5 * (pf[:, 0:-1:2] + pf[:, 2::2])
    guess = pf[:, :m] <= 0.0
    if groove is not None:
        guess |= _system_cached(eps, half, grid, groove, None).fixed
    return guess


def _check_inputs(eps: float, l_over_d: float) -> None:
    if not (np.isfinite(eps) and 0.0 <= eps <= EPS_MAX):
        raise ValueError(f"eccentricity ratio must satisfy 0 <= eps <= {EPS_MAX}, got {eps!r}")
    lo, hi = L_OVER_D_RANGE
    if not (np.isfinite(l_over_d) and lo <= l_over_d <= hi):
        raise ValueError(f"L/D must lie in [{lo:.4g}, {hi}], got {l_over_d!r}")


def _groove_key(groove) -> tuple | None:
    """``(start mod 2 pi, span in (0, 2 pi], half width)`` of a groove specification."""
    if groove is None:
        return None
    t0, t1, b = (float(x) for x in groove)
    if not (np.isfinite(t0) and np.isfinite(t1) and np.isfinite(b) and b > 0.0):
        raise ValueError("groove must be (theta_start, theta_end, half_width > 0), finite")
    span = t1 - t0
    if not 0.0 < span <= 2.0 * np.pi:
        span %= 2.0 * np.pi
    if span == 0.0:
        raise ValueError("groove arc is empty (theta_end == theta_start)")
    return (round(t0 % (2.0 * np.pi), 12), round(span, 12), b)


def solve_film(
    eps: float,
    alpha: float,
    l_over_d: float,
    *,
    grid: Grid = DEFAULT_GRID,
    groove: tuple[float, float, float] | None = None,
    supply_angle: float | None = None,
) -> FilmSolution:
    """Solve the dimensionless finite-length Reynolds LCP for one film (module docstring).

    Parameters
    ----------
    eps : float [-]
        Eccentricity ratio, ``0 <= eps <= EPS_MAX``.
    alpha : float [rad]
        Direction of the squeeze velocity ``V_s`` measured from the eccentricity vector
        (0: pure approach, pi: pure recession, -pi/2: steady rotation of the journal in the
        positive sense with a fixed bearing).
    l_over_d : float [-]
        Width (land length ``L``) over diameter ``D``; the film spans ``|z| <= L/2``.
    grid : Grid
        Resolution (:data:`DEFAULT_GRID`).
    groove : (theta_start, theta_end, half_width), optional
        Zero-pressure circumferential groove in the middle of the width: angles [rad] from the
        eccentricity vector (counter-clockwise from start to end; ``end = start + 2 pi``: full
        groove) and half width over ``R`` (``b_groove / D``). ``l_over_d`` is then the total
        width including the groove. Nodes on the groove (to the node) are held at ``P = 0``.
    supply_angle : float, optional [rad]
        Hold ``P = 0`` along the axial line of nodes nearest to this angle (from the
        eccentricity vector): an axial supply groove at ambient pressure, as in the set-up of
        Butenschoen's rotation table (supply at the thickest film, ``pi``).

    Returns
    -------
    FilmSolution

    Notes
    -----
    Reynolds equation with Booker's squeeze velocity (Booker J.F., 1965, "Dynamically loaded
    journal bearings: mobility method of solution", J. Basic Eng. 87:537-546); Swift-Stieber
    condition as an LCP (e.g. Giacopini M., Fowell M.T., Dini D., Strozzi A., 2010, "A
    mass-conserving complementarity formulation to study lubricant films in the presence of
    cavitation", J. Tribol. 132:041702, for the complementarity form of the condition);
    primal-dual active sets (Hintermueller, Ito & Kunisch 2002). Validity: rigid aligned
    journal, isoviscous incompressible film, ambient (zero) pressure at the edges and in the
    groove, no feed pressure, ``0 <= eps <= EPS_MAX``, ``L/D`` in :data:`L_OVER_D_RANGE`.
    """
    eps = float(eps)
    alpha = float(alpha)
    l_over_d = float(l_over_d)
    _check_inputs(eps, l_over_d)
    if not np.isfinite(alpha):
        raise ValueError(f"alpha must be finite, got {alpha!r}")
    gkey = _groove_key(groove)
    if gkey is not None and gkey[2] >= l_over_d:
        raise ValueError("groove half width must be smaller than the half width L/D")
    skey = None if supply_angle is None else float(np.angle(np.exp(1j * float(supply_angle))))
    s = _system_cached(eps, l_over_d, grid, gkey, skey)
    f = _source(s, alpha)
    warm = None
    d_alpha = abs(float(np.angle(np.exp(1j * (alpha - s.last_alpha)))))
    if s.last_active is not None and d_alpha < _WARM_DALPHA:
        warm = s.last_active
    elif skey is None:
        warm = _nested_guess(eps, l_over_d, grid, alpha, gkey)
    pp, active, it = _solve_lcp(s, f, warm)
    s.last_active = active
    s.last_alpha = alpha
    n = grid.n_theta
    fa = s.faces
    fa_prev = np.roll(fa, 1)
    fa_prev[0] -= 2.0 * np.pi
    ic = np.sin(fa) - np.sin(fa_prev)  # int cos over the cell
    is_ = -(np.cos(fa) - np.cos(fa_prev))  # int sin over the cell
    col = pp @ s.dz  # int P dzeta over the half width, per theta node
    w_r = 2.0 * float(col @ ic)
    w_t = 2.0 * float(col @ is_)
    q_side = 2.0 * float(np.sum(_edge_flux(s, pp, alpha, active))) / 12.0
    p_max, th_max = _peak(s.theta, pp)
    full = np.concatenate([pp, np.zeros((n, 1))], axis=1)
    return FilmSolution(w_r, w_t, p_max, th_max, q_side, it, s.theta, s.zeta, full)


def _edge_flux(s: _System, pp: np.ndarray, alpha: float, active: np.ndarray) -> np.ndarray:
    """Flow out of one edge per theta cell, ``int -H^3 dP/dzeta dtheta``.

    Flux through the face next to the edge plus the source of the half cell between that face
    and the edge (the Reynolds equation holds there where the film is full, i.e. where the
    last node is not cavitated), which makes the flux second-order accurate.
    """
    fa = s.faces
    fa_prev = np.roll(fa, 1)
    fa_prev[0] -= 2.0 * np.pi
    z = s.zeta
    half_cell = z[-1] - 0.5 * (z[-1] + z[-2])
    src = 12.0 * (np.sin(fa - alpha) - np.sin(fa_prev - alpha)) * half_cell
    return np.where(active[:, -1], 0.0, s.cz_edge * pp[:, -1] + src)


def _peak(theta: np.ndarray, pp: np.ndarray) -> tuple[float, float]:
    """Peak pressure: largest node value refined by a parabola through its neighbours in
    theta (non-uniform nodes)."""
    i, j = np.unravel_index(int(np.argmax(pp)), pp.shape)
    pm = float(pp[i, j])
    if pm <= 0.0:
        return 0.0, 0.0
    n = theta.size
    t0 = theta[i]
    tl = theta[i - 1] - (2.0 * np.pi if i == 0 else 0.0)
    tr = theta[(i + 1) % n] + (2.0 * np.pi if i == n - 1 else 0.0)
    yl, yr = pp[i - 1, j], pp[(i + 1) % n, j]
    # parabola through (tl, yl), (t0, pm), (tr, yr)
    d1 = (pm - yl) / (t0 - tl)
    d2 = (yr - pm) / (tr - t0)
    curv = (d2 - d1) / (tr - tl)
    if curv >= 0.0:
        return pm, float(t0)
    slope0 = d1 + curv * (t0 - tl)  # derivative at t0
    dt = -slope0 / (2.0 * curv)
    dt = float(np.clip(dt, tl - t0, tr - t0))
    return pm + slope0 * dt + curv * dt * dt, float(t0 + dt)


# --------------------------------------------------------------------------------------------
# derived dimensionless quantities
# --------------------------------------------------------------------------------------------
def sommerfeld_rotation(
    eps: float, l_over_d: float, *, grid: Grid = DEFAULT_GRID, supply_at_max_gap: bool = False
) -> tuple[float, float]:
    """Sommerfeld number and attitude angle of a journal turning in a fixed bearing.

    .. math::

        So = \\frac{F \\psi^2}{B D \\eta |\\omega|} = \\frac{\\varepsilon |\\mathbf W(\\varepsilon,
        -\\pi/2)|}{8\\,L/D}, \\qquad \\beta = \\angle(\\mathbf e, -\\mathbf F)

    (Butenschoen's definitions; ``omega`` is the sum of the journal and bearing speeds
    relative to the line of centres, ``|v| = eps omega / 2``).

    Parameters
    ----------
    eps : float [-]
        Eccentricity ratio.
    l_over_d : float [-]
        Width over diameter.
    grid : Grid
        Resolution.
    supply_at_max_gap : bool
        Hold ambient pressure along the thickest film (Butenschoen's set-up with the oil supply
        there); default: free Swift-Stieber condition all round.

    Returns
    -------
    So : float [-]
    beta : float [rad]
        Angle by which the load lags the eccentricity vector (positive).

    Notes
    -----
    Butenschoen H.-J. (1976), "Das hydrodynamische, zylindrische Gleitlager endlicher Breite
    unter instationaerer Belastung", Diss. Univ. Karlsruhe (definitions as in his tables).
    """
    s = solve_film(eps, -0.5 * np.pi, l_over_d, grid=grid,
                   supply_angle=np.pi if supply_at_max_gap else None)
    return eps * float(np.hypot(s.w_r, s.w_t)) / (8.0 * l_over_d), float(np.arctan2(-s.w_t,
                                                                                     s.w_r))


def sommerfeld_squeeze(eps_signed: float, l_over_d: float, *, grid: Grid = DEFAULT_GRID
                       ) -> float:
    """Sommerfeld number of pure squeeze along the line of centres (Butenschoen).

    .. math::

        So_V = \\frac{F \\psi^2}{B D \\eta |\\dot\\varepsilon|} =
        \\frac{|\\mathbf W(|\\varepsilon|, \\alpha)|}{4\\,L/D}, \\quad \\alpha = 0
        \\text{ (approach, } \\varepsilon > 0), \\ \\pi \\text{ (recession, } \\varepsilon < 0)

    Parameters
    ----------
    eps_signed : float [-]
        Eccentricity ratio signed with ``d eps/dt``.
    l_over_d : float [-]
        Width over diameter.
    grid : Grid
        Resolution.

    Returns
    -------
    float [-]

    Notes
    -----
    Definitions of Butenschoen (1976), see :func:`sommerfeld_rotation`.
    """
    s = solve_film(abs(eps_signed), 0.0 if eps_signed >= 0.0 else np.pi, l_over_d, grid=grid)
    return float(np.hypot(s.w_r, s.w_t)) / (4.0 * l_over_d)


def _alpha_for_load(eps: float, chi: float, l_over_d: float, grid: Grid,
                    alpha0: float | None, groove=None, tol: float = 1e-9
                    ) -> tuple[float, FilmSolution]:
    """Squeeze direction ``alpha`` (from e) whose film load points at ``chi`` (from e).

    ``g(alpha) = wrap(arg W - alpha) + alpha - chi`` is continuous and increasing on
    ``(chi - pi/2, chi + pi/2)`` (``W . V_s = int P f / 12 > 0``, so ``arg W - alpha`` stays
    in ``(-pi/2, pi/2)``). Safeguarded secant iteration (bracket kept, bisection fallback),
    started at ``alpha0``; stops when the load direction matches to ``tol / 10`` or the
    bracket or the step is below ``tol`` [rad].
    """

    def g(a):
        s = solve_film(eps, a, l_over_d, grid=grid, groove=groove)
        return float(np.angle(np.exp(1j * (np.arctan2(s.w_t, s.w_r) - a)))) + a - chi, s

    lo, hi = chi - 0.5 * np.pi + 1e-9, chi + 0.5 * np.pi - 1e-9
    a0 = chi if alpha0 is None else float(np.clip(alpha0, lo, hi))
    g0, s0 = g(a0)
    if g0 == 0.0:
        return a0, s0
    if g0 < 0.0:
        lo = a0
    else:
        hi = a0
    step = -g0 if alpha0 is None else -np.sign(g0) * 1e-4
    a1 = float(np.clip(a0 + step, lo, hi))
    g1, s1 = g(a1)
    for _ in range(100):
        if abs(g1) < 0.1 * tol:  # load direction matched to 1e-10 rad
            return a1, s1
        if g1 < 0.0:
            lo = max(lo, a1)
        else:
            hi = min(hi, a1)
        if hi - lo < tol:
            return a1, s1
        den = g1 - g0
        a2 = a1 - g1 * (a1 - a0) / den if den != 0.0 else 0.5 * (lo + hi)
        if not (lo < a2 < hi):
            a2 = 0.5 * (lo + hi)
        if abs(a2 - a1) < tol:
            g2, s2 = g(a2)
            return a2, s2
        a0, g0 = a1, g1
        a1 = a2
        g1, s1 = g(a1)
    raise RuntimeError("Reynolds mobility: squeeze direction did not converge")


def mobility_reynolds(
    zeta: ArrayLike, kappa: ArrayLike, l_over_d: float, *, grid: Grid = DEFAULT_GRID,
    alpha0: ArrayLike | None = None, groove: tuple[float, float, float] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Finite-length mobility (Booker's convention) by direct solution of the Reynolds LCP.

    For the load direction ``chi`` seen from the eccentricity vector the squeeze direction
    ``alpha`` is found from ``arg W(eps, alpha) = chi``; then

    .. math::

        |\\mathbf M| = \\frac{4\\,L/D}{|\\mathbf W(\\varepsilon, \\alpha)|}, \\qquad
        \\angle\\mathbf M = \\alpha \\ (\\text{from } \\mathbf e)

    so that ``d eps/dt = |F| psi^2 / (mu L D) M + omega_bar z_hat x eps`` (Booker
    1965). Slow (one root find of a few LCP solutions per point): the
    reference for :mod:`checker.calc.reynolds_map` and for direct orbits.

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components along and across the load (load frame),
        ``zeta**2 + kappa**2 <= EPS_MAX**2``.
    l_over_d : float [-]
        Width over diameter.
    grid : Grid
        Resolution.
    alpha0 : array_like, optional [rad]
        Initial guesses of the squeeze direction from the eccentricity vector.
    groove : (theta_start, theta_end, half_width), optional
        Zero-pressure groove, angles from the eccentricity vector (:func:`solve_film`). A
        groove fixed in the bearing breaks the rotational symmetry the mobility method rests
        on; the result holds for the given groove position only.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
        Mobility in the load frame.

    Notes
    -----
    Booker J.F. (1965), J. Basic Eng. 87:537-546 (mobility method); Reynolds LCP of
    :func:`solve_film`.
    """
    z, k = np.broadcast_arrays(_checks.finite("zeta", zeta), _checks.finite("kappa", kappa))
    a0 = None if alpha0 is None else np.broadcast_to(np.asarray(alpha0, dtype=float), z.shape)
    out = np.empty(z.shape, dtype=complex)
    for idx in np.ndindex(z.shape):
        w = complex(z[idx], k[idx])
        eps = abs(w)
        if eps > EPS_MAX:
            raise ValueError(f"eccentricity ratio {eps} above EPS_MAX = {EPS_MAX}")
        chi = -float(np.angle(w)) if eps > 0.0 else 0.0
        alpha, s = _alpha_for_load(eps, chi, float(l_over_d), grid,
                                   None if a0 is None else float(a0[idx]), groove)
        wm = float(np.hypot(s.w_r, s.w_t))
        out[idx] = 4.0 * l_over_d / wm * np.exp(1j * (alpha - chi))
    return out.real, out.imag


# --------------------------------------------------------------------------------------------
# SI wrappers
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FilmState:
    """Film force, peak pressure and side flow (SI) of :func:`film_force`.

    Attributes
    ----------
    force_x, force_y : numpy.ndarray [N]
        Load carried by the film (= load applied to the journal in quasi-static equilibrium),
        in the frame of the inputs.
    p_max : numpy.ndarray [Pa]
        Peak film pressure.
    side_flow : numpy.ndarray [m^3/s]
        Flow out of both bearing edges.
    """

    force_x: np.ndarray
    force_y: np.ndarray
    p_max: np.ndarray
    side_flow: np.ndarray


def film_force(
    eps_x: ArrayLike,
    eps_y: ArrayLike,
    vs_x: ArrayLike,
    vs_y: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
    *,
    grid: Grid = DEFAULT_GRID,
) -> FilmState:
    """Finite-length film force, peak pressure and side flow for a given squeeze velocity.

    .. math::

        \\mathbf F = \\frac{\\mu |v| R^2}{\\psi^2}\\mathbf W, \\quad
        p_{max} = \\frac{\\mu |v|}{\\psi^2} P_{max}, \\quad Q = c R^2 |v| \\bar Q,
        \\qquad v = \\frac{\\mathbf V_s}{c}, \\ \\psi = \\frac{c}{R}

    with ``W``, ``P_max``, ``Qbar`` from :func:`solve_film` (module docstring).

    Parameters
    ----------
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector (journal centre relative to the bearing centre over ``c``).
    vs_x, vs_y : array_like [1/s]
        Squeeze velocity over clearance, ``V_s / c = d eps/dt - omega_bar z_hat x eps``,
        ``omega_bar = (omega_journal + omega_bearing) / 2`` (same frame as ``eps``).
    diameter : array_like [m]
        Journal diameter ``D``.
    length : array_like [m]
        Land length ``L`` (film width).
    clearance : array_like [m]
        Radial clearance ``c`` (``c < 0.05 D``).
    viscosity : array_like [Pa s]
        Dynamic viscosity.
    grid : Grid
        Resolution.

    Returns
    -------
    FilmState

    Notes
    -----
    Booker (1965) squeeze formulation of the finite-length Reynolds equation with the
    Swift-Stieber condition (:func:`solve_film`). Validity as there; one LCP solution per
    point (about 20-50 ms): use :mod:`checker.calc.reynolds_map` in loops over crank angle.
    """
    ex, ey, vx, vy = np.broadcast_arrays(*(_checks.finite(n, a) for n, a in (
        ("eps_x", eps_x), ("eps_y", eps_y), ("vs_x", vs_x), ("vs_y", vs_y))))
    shape = ex.shape
    dia, ln, cl, mu = (np.broadcast_to(_checks.positive(n, a), shape) for n, a in (
        ("diameter", diameter), ("length", length), ("clearance", clearance),
        ("viscosity", viscosity)))
    if np.any(cl >= 0.05 * dia):
        raise ValueError("radial clearance must be small compared with the diameter")
    fx, fy, pm, qs = (np.zeros(shape) for _ in range(4))
    for idx in np.ndindex(shape):
        z = complex(ex[idx], ey[idx])
        v = complex(vx[idx], vy[idx])
        eps = abs(z)
        if abs(v) == 0.0:
            continue
        phi = float(np.angle(z)) if eps > 0.0 else float(np.angle(v))
        alpha = float(np.angle(v)) - phi
        r = 0.5 * dia[idx]
        s = solve_film(eps, alpha, float(ln[idx] / dia[idx]), grid=grid)
        psi = cl[idx] / r
        scale = mu[idx] * abs(v) / psi**2
        f = scale * r * r * complex(s.w_r, s.w_t) * np.exp(1j * phi)
        fx[idx], fy[idx] = f.real, f.imag
        pm[idx] = scale * s.p_max
        qs[idx] = cl[idx] * r * r * abs(v) * s.q_side
    return FilmState(fx, fy, pm, qs)
