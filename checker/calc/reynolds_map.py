"""Finite-length mobility map computed once by the Reynolds solver, and its interpolant.

The finite-length Reynolds film (rigid, isoviscous, Swift-Stieber cavitation) depends on the
journal motion only through Booker's squeeze velocity, so its mobility is a function of the
eccentricity ratio, the load direction and the width ratio alone (Booker J.F., 1965,
"Dynamically loaded journal bearings: mobility method of solution", J. Basic Eng.
87:537-546; the approach of Goenka P.K., 1984, "Analytical curve fits for solution
parameters of dynamically loaded journal bearings", J. Tribol. 106:421-428, with a table
instead of curve fits). The map stored in ``data/reynolds_map.npz`` holds the solver's own
output (:func:`checker.calc.reynolds.solve_film`) on nodes

* width ratios :data:`MAP_L_OVER_D` (1/16 .. 1),
* eccentricity rows uniform in ``x = ln((1 - eps) / (1 + eps))`` from ``eps = 0`` to
  ``1 - 1e-4`` (:data:`MAP_EPS_MAX`): clustered towards the wall, where the films that
  matter are,
* per row, squeeze directions ``alpha`` chosen so that the *short-bearing* load direction is
  uniform in ``t = asinh(vartheta / (1 - eps)) / asinh(pi / (1 - eps))`` (``vartheta``: angle
  of the eccentricity vector from the load, 0 .. pi), which resolves the two angular scales
  of the near-wall mobility (``vartheta ~ 1 - eps``: squeeze to rotation; ``~ sqrt(1 - eps)``).

Stored per node: ``alpha``, the dimensionless load ``W`` (components along / across the
eccentricity vector), the peak pressure ``P_max`` and the side flow ``Qbar`` (scaling in
:mod:`checker.calc.reynolds`). ``scripts/make_reynolds_map.py`` regenerates the file
(:func:`generate_map`).

Interpolant
-----------
The interpolated quantity is the complex ratio ``r = M / M_cf`` of the finite-length mobility
to Booker's closed-form short-bearing mobility at the same point (load frame), as
``log r``: the closed form carries the ``(1 - zeta)^(5/2)`` singularity and the ratio's
remaining power law (``|r| ~ (1 - eps)^-1`` at the wall, where the film is locally long) is
linear in ``x``. Per row, ``log r`` is splined in ``t`` (the nodes' own load directions) onto
a common ``t`` grid, then across the width ratio (cubic spline in ``ln(L/D)``), then along
``x`` onto a fine grid; the orbit reads that fine table bilinearly (:func:`table_for`). Below
the last row (``1 - eps < 1e-4``) ``log r`` is extended linearly in ``x``. The same is done
for the peak pressure and side flow per unit load (:func:`film_kernels`).

References
----------
.. [1] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [2] P. K. Goenka, "Analytical curve fits for solution parameters of dynamically loaded journal
   bearings", Trans. ASME J. Tribol. 106, 1984, pp. 421-428.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from checker.calc import pi_film as pf

__all__ = [
    "MAP_FILE",
    "MAP_L_OVER_D",
    "MAP_EPS_MAX",
    "MAP_N_X",
    "MAP_N_T",
    "MAP_MAX_REL_ERROR",
    "map_eccentricities",
    "map_directions",
    "generate_map",
    "load_map",
    "MapTable",
    "table_for",
    "stack_tables",
    "map_kernel",
    "kernel_table",
    "stack_kernel_tables",
    "mobility_map",
    "film_kernels",
    "film_state_map",
]

MAP_FILE = Path(__file__).resolve().parent / "data" / "reynolds_map.npz"
"""Package data file of the map."""

MAP_L_OVER_D = (1 / 16, 1 / 12, 1 / 8, 1 / 6, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6, 0.75, 1.0)
"""Width ratios of the map (the interpolant accepts ``MAP_L_OVER_D[0] .. MAP_L_OVER_D[-1]``)."""

MAP_EPS_MAX = 1.0 - 1e-4
"""Last eccentricity row of the map (film 1e-4 c)."""

MAP_N_X = 18
"""Eccentricity rows (uniform in ``x = ln((1 - eps)/(1 + eps))``, ``eps = 0 .. MAP_EPS_MAX``)."""

MAP_N_T = 33
"""Load directions per row."""

MAP_MAX_REL_ERROR = 1e-2
"""Bound on ``|M_map / M_solver - 1|`` (complex) against
:func:`checker.calc.reynolds.mobility_reynolds` on the same grid, ``eps <= 0.999``. Measured
on 360 random points (L/D 0.1, 0.2, 0.331, 0.371, 0.45, 0.7, most between the map's nodes):
max 0.62 %, 95th percentile 0.13 %, median 0.02 %; the largest errors are for loads 60-130
deg from the eccentricity near the wall, where the solver's own discretisation error is of
the same size (tests re-check a sample)."""

_FINE_NX = 481  # fine table rows, uniform in ln(1 - eps) from 0 to _XF_END
_FINE_NT = 201  # fine table columns, uniform in the lookup coordinate t from 0 to 1
_XF_END = float(np.log(1e-7))  # orbit EPS_CAP = 1 - 1e-7
_S_MIN = 1e-7
_TINY = 1e-300


# --------------------------------------------------------------------------------------------
# node coordinates
# --------------------------------------------------------------------------------------------
def _x_of_eps(eps: np.ndarray) -> np.ndarray:
    return np.log((1.0 - eps) / (1.0 + eps))


def _eps_of_x(x: np.ndarray) -> np.ndarray:
    return -np.tanh(0.5 * np.asarray(x, dtype=float))


def map_eccentricities(n_x: int = MAP_N_X) -> np.ndarray:
    """Eccentricity ratios of the map rows (``eps = 0 .. MAP_EPS_MAX``)."""
    return _eps_of_x(np.linspace(0.0, float(_x_of_eps(np.float64(MAP_EPS_MAX))), n_x))


def _t_of_theta(theta: np.ndarray, eps: np.ndarray) -> np.ndarray:
    d = 1.0 - eps
    return np.arcsinh(theta / d) / np.arcsinh(np.pi / d)


def _theta_of_t(t: np.ndarray, eps: np.ndarray) -> np.ndarray:
    d = 1.0 - eps
    return d * np.sinh(t * np.arcsinh(np.pi / d))


def map_directions(eps: float, n_t: int = MAP_N_T) -> tuple[np.ndarray, np.ndarray]:
    """Squeeze directions of one map row.

    Returns ``(vartheta, alpha)``: the node angles of the eccentricity vector from the load
    (uniform in ``t``) and the squeeze directions (from the eccentricity vector) for which
    the *exact short-bearing* film load would point at ``-vartheta`` from the eccentricity.
    """
    t = np.linspace(0.0, 1.0, n_t)
    if eps == 0.0:
        th = np.pi * t
        return th, -th
    e = np.full(n_t, float(eps))
    th = _theta_of_t(t, e)
    chi = -th
    a0 = np.angle(pf.m_closed(eps * np.exp(1j * th))) + chi
    return th, pf.solve_alpha(e, chi, a0)


# --------------------------------------------------------------------------------------------
# generation
# --------------------------------------------------------------------------------------------
def generate_map(
    l_over_d: ArrayLike = MAP_L_OVER_D,
    n_x: int = MAP_N_X,
    n_t: int = MAP_N_T,
    grid=None,
    rows: ArrayLike | None = None,
    progress: bool = False,
) -> dict[str, np.ndarray]:
    """Solve the Reynolds LCP on the map nodes (see the module docstring).

    Parameters
    ----------
    l_over_d : array_like [-]
        Width ratios.
    n_x, n_t : int
        Eccentricity rows and directions per row.
    grid : Grid
        Solver resolution.
    rows : array_like of int, optional
        Compute only these rows (for regeneration tests); the others are NaN.
    progress : bool
        Print one line per width ratio.

    Returns
    -------
    dict
        ``l_over_d (K,)``, ``eps (I,)``, ``alpha (K, I, J)``, ``w (K, I, J)`` complex,
        ``p_max (K, I, J)``, ``q_side (K, I, J)``, ``grid (2,)``.
    """
    from checker.calc import reynolds as ry

    grid = ry.DEFAULT_GRID if grid is None else grid
    lods = np.atleast_1d(np.asarray(l_over_d, dtype=float))
    eps = map_eccentricities(n_x)
    sel = np.arange(n_x) if rows is None else np.atleast_1d(np.asarray(rows, dtype=int))
    shape = (lods.size, n_x, n_t)
    alpha = np.full(shape, np.nan)
    w = np.full(shape, np.nan, dtype=complex)
    pm = np.full(shape, np.nan)
    qs = np.full(shape, np.nan)
    for k, lod in enumerate(lods):
        t0 = time.perf_counter()
        for i in sel:
            e = float(eps[i])
            _, al = map_directions(e, n_t)
            if e == 0.0:  # isotropic: one solve, rotated
                s = ry.solve_film(0.0, 0.0, float(lod), grid=grid)
                alpha[k, i] = al
                w[k, i] = complex(s.w_r, s.w_t) * np.exp(1j * al)
                pm[k, i] = s.p_max
                qs[k, i] = s.q_side
                continue
            for j in range(n_t):
                s = ry.solve_film(e, float(al[j]), float(lod), grid=grid)
                alpha[k, i, j] = al[j]
                w[k, i, j] = complex(s.w_r, s.w_t)
                pm[k, i, j] = s.p_max
                qs[k, i, j] = s.q_side
        if progress:
            print(f"L/D = {lod:.4f}: {time.perf_counter() - t0:.1f} s", flush=True)
    return {"l_over_d": lods, "eps": eps, "alpha": alpha, "w": w, "p_max": pm,
            "q_side": qs, "grid": np.array([grid.n_theta, grid.n_z])}


@functools.cache
def load_map() -> dict[str, np.ndarray]:
    """The stored map (:data:`MAP_FILE`): the solver output of :func:`generate_map` and the
    rows derived from it by :func:`derive_rows`."""
    with np.load(MAP_FILE) as f:
        data = {k: f[k] for k in f.files}
    if int(data["lookup_nt"]) != _FINE_NT or float(data["lookup_lin_q"]) != _LIN_Q:
        raise RuntimeError(f"{MAP_FILE.name} was derived for another lookup grid; run"
                           " scripts/make_reynolds_map.py")
    return data


# --------------------------------------------------------------------------------------------
# lookup coordinates
# --------------------------------------------------------------------------------------------
_LIN_Q = 4.0  # weight of the linear-in-q share of the lookup coordinate


def _lookup_t(delta: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Lookup coordinate across the load direction, 0 .. 1 (``q = 1 - cos vartheta``, 0 .. 2).

    ``t = (ln(1 + q/delta^2) + b q) / (ln(1 + 2/delta^2) + 2 b)`` with ``delta = 1 - eps`` and
    ``b = 4``: linear in ``q`` for ``vartheta << delta``, logarithmic beyond (resolves the
    near-wall scales ``vartheta ~ 1 - eps`` and ``~ sqrt(1 - eps)``), with a linear share that
    keeps large angles resolved; ``t = 1`` at ``vartheta = pi`` on every row. Three
    logarithms and no inverse trigonometric function per lookup.
    """
    d2 = delta * delta
    ld2 = np.log(d2)
    return (np.log(d2 + q) - ld2 + _LIN_Q * q) / (np.log(d2 + 2.0) - ld2 + 2.0 * _LIN_Q)


def _q_of_lookup_t(delta: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Inverse of :func:`_lookup_t` in ``q``: Newton on ``u = ln(delta^2 + q)``, for which
    ``u + b e^u = K`` is convex and increasing, so iterates started right of the root
    decrease monotonically to it (to rounding in 8 steps)."""
    delta, t = np.broadcast_arrays(np.asarray(delta, dtype=float), np.asarray(t, dtype=float))
    d2 = delta * delta
    ld2 = np.log(d2)
    k = t * (np.log(d2 + 2.0) - ld2 + 2.0 * _LIN_Q) + ld2 + _LIN_Q * d2
    u = np.where(k > _LIN_Q, np.minimum(k, np.log(np.maximum(k, _LIN_Q) / _LIN_Q)), k)
    for _ in range(40):
        eu = np.exp(u)
        step = (u + _LIN_Q * eu - k) / (1.0 + _LIN_Q * eu)
        u = u - step
        if np.all(np.abs(step) <= 1e-15 * (1.0 + np.abs(u))):
            break
    return np.clip(np.exp(u) - d2, 0.0, 2.0)


def _spline_matrix(x_nodes: np.ndarray, x_eval: np.ndarray) -> np.ndarray:
    """Matrix ``S`` with ``f(x_eval) = S @ f(x_nodes)`` for the natural cubic spline through
    the nodes (increasing ``x_nodes``); linear extrapolation outside. NumPy only."""
    x = np.asarray(x_nodes, dtype=float)
    n = x.size
    h = np.diff(x)
    # second derivatives m = A^-1 B f (natural: m_0 = m_{n-1} = 0)
    a = np.zeros((n, n))
    b = np.zeros((n, n))
    a[0, 0] = a[-1, -1] = 1.0
    for i in range(1, n - 1):
        a[i, i - 1] = h[i - 1] / 6.0
        a[i, i] = (h[i - 1] + h[i]) / 3.0
        a[i, i + 1] = h[i] / 6.0
        b[i, i - 1] = 1.0 / h[i - 1]
        b[i, i] = -1.0 / h[i - 1] - 1.0 / h[i]
        b[i, i + 1] = 1.0 / h[i]
    msec = np.linalg.solve(a, b)  # (n, n): second derivatives per unit node value
    xe = np.asarray(x_eval, dtype=float)
    k = np.clip(np.searchsorted(x, xe) - 1, 0, n - 2)
    hk = h[k]
    s = (xe - x[k]) / hk
    eye = np.eye(n)
    lin = eye[k] * (1.0 - s)[:, None] + eye[k + 1] * s[:, None]
    inside = (xe >= x[0]) & (xe <= x[-1])
    curv = (-(s * (1.0 - s)) * hk * hk / 6.0)[:, None] * (
        msec[k] * (2.0 - s)[:, None] + msec[k + 1] * (1.0 + s)[:, None])
    out = lin + np.where(inside[:, None], curv, 0.0)
    # linear extrapolation with the end slopes of the spline
    for end in (0, n - 1):
        beyond = (xe < x[0]) if end == 0 else (xe > x[-1])
        if beyond.any():
            j0, j1 = (0, 1) if end == 0 else (n - 2, n - 1)
            hh = h[j0]
            slope = (eye[j1] - eye[j0]) / hh + (
                -(2.0 * msec[j0] + msec[j1]) * hh / 6.0 if end == 0
                else (msec[j0] + 2.0 * msec[j1]) * hh / 6.0)
            out[beyond] = eye[end][None, :] + (xe[beyond] - x[end])[:, None] * slope[None, :]
    return out


# --------------------------------------------------------------------------------------------
# rows on the lookup coordinate (derived offline from the solver output)
# --------------------------------------------------------------------------------------------
def _node_values(data: dict, k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per node of width ratio ``k``: generation coordinate ``t`` of the film's own load
    direction, ``log r`` (complex), ``log Pi`` and ``log Gamma`` (peak pressure and side flow
    per unit load)."""
    lod = float(data["l_over_d"][k])
    eps = data["eps"][:, None]
    w = data["w"][k]
    alpha = data["alpha"][k]
    wabs = np.abs(w)
    chi = np.angle(w)  # load direction from e
    th = np.abs(np.angle(np.exp(-1j * chi)))  # e from the load, 0..pi
    wl = eps * np.exp(1j * th)  # eccentricity in the load frame
    m = 4.0 * lod**3 / wabs * np.exp(1j * (alpha - chi))  # mobility * (L/D)^2, load frame
    log_r = np.log(m / pf.m_closed(wl))
    log_r.imag = np.unwrap(log_r.imag, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(eps > 0.0, _t_of_theta(th, np.broadcast_to(eps, th.shape)),
                     np.linspace(0.0, 1.0, th.shape[1])[None, :])
    log_pi = np.log(4.0 * lod * data["p_max"][k] / wabs)
    log_g = np.log(4.0 * lod * data["q_side"][k] / wabs)
    return t, log_r, log_pi, log_g


def derive_rows(data: dict) -> dict[str, np.ndarray]:
    """Map rows on the lookup coordinate, from the solver output of :func:`generate_map`.

    Per width ratio and row, ``log r`` (complex), ``log Pi`` and ``log Gamma`` are splined
    in the generation coordinate through the nodes' own load directions (cubic; symmetry
    condition at ``vartheta = 0``: zero slope for the even parts, zero curvature for the odd
    phase) and evaluated at the :data:`_FINE_NT` lookup columns of the row's eccentricity.
    Done once, by ``scripts/make_reynolds_map.py``; stored with the solver output.
    """
    from scipy.interpolate import CubicSpline

    def spline(tn, vn, odd):
        keep = np.concatenate([[True], np.diff(tn) > 1e-12])
        bc = ((2, 0.0), "not-a-knot") if odd else ((1, 0.0), "not-a-knot")
        return CubicSpline(tn[keep], vn[keep], bc_type=bc)

    eps = data["eps"]
    tf = np.linspace(0.0, 1.0, _FINE_NT)
    kk, ii = data["w"].shape[:2]
    lr = np.empty((kk, ii, _FINE_NT), dtype=complex)
    lp = np.empty((kk, ii, _FINE_NT))
    lg = np.empty((kk, ii, _FINE_NT))
    for k in range(kk):
        t, log_r, log_pi, log_g = _node_values(data, k)
        for i in range(ii):
            if eps[i] == 0.0:  # isotropic row
                lr[k, i], lp[k, i], lg[k, i] = log_r[i, 0], log_pi[i, 0], log_g[i, 0]
                continue
            th = np.arccos(1.0 - _q_of_lookup_t(np.float64(1.0 - eps[i]), tf))
            tg = _t_of_theta(th, eps[i])
            lr[k, i].real = spline(t[i], log_r[i].real, False)(tg)
            lr[k, i].imag = spline(t[i], log_r[i].imag, True)(tg)
            lp[k, i] = spline(t[i], log_pi[i], False)(tg)
            lg[k, i] = spline(t[i], log_g[i], False)(tg)
    # single precision is plenty for logarithms (1e-7) and halves the package data
    return {"rows_log_r": lr.astype(np.complex64), "rows_log_pi": lp.astype(np.float32),
            "rows_log_gamma": lg.astype(np.float32),
            "lookup_nt": np.array(_FINE_NT), "lookup_lin_q": np.array(_LIN_Q)}


# --------------------------------------------------------------------------------------------
# fine tables
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class MapTable:
    """Fine lookup table of one width ratio (see :func:`table_for`).

    Arrays of shape (``_FINE_NX + 1``, ``_FINE_NT + 1``) (last row and column repeated, so
    that a lookup needs no index clamping) on rows uniform in ``ln(1 - eps)`` (0 .. ln 1e-7)
    and columns uniform in the lookup coordinate ``t`` (:func:`_lookup_t`):

    * ``mobility``: ``(Re M + i Im M / kappa) (L/D)^2 / (1 - eps)^1.5``, ``M`` the
      load-frame mobility at ``zeta + i kappa``: both parts even in ``vartheta`` and the wall
      singularity mostly divided out; the lookup multiplies back by ``(1 - eps)^1.5`` and
      ``kappa``;
    * ``log_pi``, ``log_gamma``: peak pressure and side flow per unit load (logarithms).
    """

    l_over_d: float
    mobility: np.ndarray
    log_pi: np.ndarray
    log_gamma: np.ndarray


def _pad(a: np.ndarray) -> np.ndarray:
    return np.concatenate([np.concatenate([a, a[:, -1:]], axis=1),
                           np.concatenate([a[-1:], a[-1:, -1:]], axis=1)], axis=0)


@functools.cache
def _fine_grid() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Fine rows (eps), the along-rows spline matrix, and ``q``, ``sin(vartheta)`` per node."""
    eps_rows = load_map()["eps"]
    eps_fine = 1.0 - np.exp(np.linspace(0.0, _XF_END, _FINE_NX))
    eps_fine[0] = 0.0
    # natural spline in x = ln((1-eps)/(1+eps)) (increasing order), linear beyond the last row
    xr = _x_of_eps(eps_rows)[::-1]
    s = _spline_matrix(xr, _x_of_eps(eps_fine))[:, ::-1]
    qf = _q_of_lookup_t((1.0 - eps_fine)[:, None], np.linspace(0.0, 1.0, _FINE_NT)[None, :])
    return eps_fine, s, qf, np.sqrt(qf * (2.0 - qf))


@functools.lru_cache(maxsize=64)
def table_for(l_over_d: float) -> MapTable:
    """Fine lookup table for one width ratio (built once per ratio, ~10 ms).

    Natural cubic spline across the map's width ratios in ``ln(L/D)``, then along the rows in
    ``x = ln((1 - eps)/(1 + eps))``; below the last row (``1 - eps < 1e-4``) the logarithms
    are extended linearly in ``x`` (power law towards the wall).
    """
    lo, hi = MAP_L_OVER_D[0], MAP_L_OVER_D[-1]
    if not (lo - 1e-12 <= l_over_d <= hi + 1e-12):
        raise ValueError(f"finite-length mobility map covers {lo:.4g} <= L/D <= {hi}; got"
                         f" L/D = {l_over_d:.4g}")
    data = load_map()
    lods = np.log(np.asarray(data["l_over_d"], dtype=float))
    wts = _spline_matrix(lods, np.array([np.log(float(l_over_d))]))[0]  # (K,)
    eps_fine, s, qf, sin_th = _fine_grid()
    log_r = s @ np.tensordot(wts, data["rows_log_r"], axes=1)  # (NX, NT)
    log_pi = s @ np.tensordot(wts, data["rows_log_pi"], axes=1)
    log_g = s @ np.tensordot(wts, data["rows_log_gamma"], axes=1)
    d = (1.0 - eps_fine)[:, None]
    wl = eps_fine[:, None] * ((1.0 - qf) + 1j * sin_th)  # load-frame eccentricity, kappa >= 0
    m = np.exp(log_r) * pf.m_closed(wl) / d**1.5
    kap = eps_fine[:, None] * sin_th
    with np.errstate(divide="ignore", invalid="ignore"):
        b = np.where(kap > 0.0, m.imag / kap, np.nan)
    b[:, 0] = 2.0 * b[:, 1] - b[:, 2]  # vartheta = 0, pi: linear limits (even in vartheta)
    b[:, -1] = 2.0 * b[:, -2] - b[:, -3]
    b[0] = 2.0 * b[1] - b[2]  # eps = 0: linear limit (M is linear in (zeta, kappa) there)
    mob = m.real + 1j * b
    if not np.all(np.isfinite(mob)):
        raise RuntimeError("finite-length mobility table: non-finite entries")
    return MapTable(float(l_over_d), _pad(mob), _pad(log_pi), _pad(log_g))


_SX = _FINE_NT + 1  # row stride of the padded tables
_CX = (_FINE_NX - 1) / _XF_END
_CT = float(_FINE_NT - 1)
# map_kernel's scalars as 0-d float64 arrays (the same numbers; NumPy calls with them are
# ~0.3 us faster than with Python floats): 1, wall-distance floor, tiny, b, 2, 2 b, column
# and row scales
_K = tuple(np.array(v) for v in (1.0, _S_MIN, _TINY, _LIN_Q, 2.0, 2.0 * _LIN_Q, _CT,
                                 0.5 * _CX))
_K_SX = np.array(_SX, dtype=np.intp)


def _coords(w: np.ndarray):
    """Fractional table coordinates of load-frame eccentricities ``w`` (no inverse trig).

    Returns ``(i0, tx, tt, e, d)``: flat index of the lower-left node (without the table
    offset), weights, ``|w|`` and the wall distance ``d = max(1 - |w|, 1e-7)``."""
    z = w.real
    e = np.sqrt(z * z + w.imag * w.imag)
    d = np.maximum(1.0 - e, _S_MIN)
    d2 = d * d
    ld2 = np.log(d2)
    q = (e - z) / (e + _TINY)
    t = (np.log(d2 + q) - ld2 + _LIN_Q * q) / (np.log(d2 + 2.0) - ld2 + 2.0 * _LIN_Q)
    fx = ld2 * (0.5 * _CX)
    ft = t * _CT
    ix = fx.astype(np.intp)
    it = ft.astype(np.intp)
    return ix * _SX + it, fx - ix, ft - it, e, d


def _bilinear(flat: np.ndarray, i0: np.ndarray, tx: np.ndarray, tt: np.ndarray) -> np.ndarray:
    a = flat[i0]
    b = flat[i0 + 1]
    v0 = a + tt * (b - a)
    i1 = i0 + _SX
    a = flat[i1]
    b = flat[i1 + 1]
    v1 = a + tt * (b - a)
    return v0 + tx * (v1 - v0)


def stack_tables(l_over_d: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Distinct width ratios -> stacked flat tables and the flat offset of each entry's table.

    Returns ``(mobility, log_pi, log_gamma, offset)``; raises ValueError for a ratio outside
    the map's range."""
    u, inv = np.unique(np.round(np.asarray(l_over_d, dtype=float), 12), return_inverse=True)
    tabs = [table_for(float(v)) for v in u]
    size = tabs[0].mobility.size
    return (np.concatenate([t.mobility.ravel() for t in tabs]),
            np.concatenate([t.log_pi.ravel() for t in tabs]),
            np.concatenate([t.log_gamma.ravel() for t in tabs]),
            (inv * size).reshape(np.shape(l_over_d)))


def kernel_table(mob_flat: np.ndarray) -> np.ndarray:
    """Lookup table of :func:`map_kernel` from a flat (stacked, padded) mobility table: per
    node ``i`` the pair ``mob_flat[i], mob_flat[i + 1] - mob_flat[i]`` (the ``a`` and
    ``b - a`` of :func:`_bilinear`, the same numbers), interleaved so that a lookup reads one
    cache line per table row. Built once per table (:func:`stack_kernel_tables`)."""
    pairs = np.zeros((mob_flat.size, 2), dtype=complex)
    pairs[:, 0] = mob_flat
    np.subtract(mob_flat[1:], mob_flat[:-1], out=pairs[:-1, 1])
    return pairs.reshape(-1)


@functools.lru_cache(maxsize=16)
def _kernel_table_for(l_over_d: float) -> np.ndarray:
    return kernel_table(table_for(l_over_d).mobility.ravel())


@functools.lru_cache(maxsize=2)
def _stacked_kernel_tables(lods: tuple[float, ...]) -> np.ndarray:
    tabs = [_kernel_table_for(v) for v in lods]
    return tabs[0] if len(tabs) == 1 else np.concatenate(tabs)


def stack_kernel_tables(l_over_d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distinct width ratios -> the stacked :func:`kernel_table` of their mobility tables and
    the flat node offset of each entry's table (as :func:`stack_tables`; the tables are kept
    for the next call with the same ratios). Raises ValueError for a ratio outside the map's
    range."""
    u, inv = np.unique(np.round(np.asarray(l_over_d, dtype=float), 12), return_inverse=True)
    size = table_for(float(u[0])).mobility.size  # checks the range
    tab = _stacked_kernel_tables(tuple(float(v) for v in u))
    return tab, (inv * size).reshape(np.shape(l_over_d))


def map_kernel(w: np.ndarray, mob_flat: np.ndarray, offset: np.ndarray | None,
               table: np.ndarray | None = None) -> np.ndarray:
    """Map mobility in the load frame times (L/D)**2 (complex); ``w`` may lie slightly
    outside the unit disk (RK stages): the wall distance is floored at 1e-7.

    Same arithmetic as :func:`_coords` (with ``|w|`` by ``np.abs``) and :func:`_bilinear`,
    fused with in-place operations (this is the inner loop of the finite-length orbits; the
    tests compare it bit for bit with the unfused formulas). ``offset``: flat offset of each
    entry's table (:func:`stack_tables`), or None (every entry in the first table).
    ``table``: :func:`kernel_table` of ``mob_flat`` (built here when not given; pass it when
    the same table is used again)."""
    if table is None:
        table = kernel_table(mob_flat)
    if w.ndim != 1:
        shape = w.shape
        off = None if offset is None else np.broadcast_to(offset, shape).reshape(-1)
        return map_kernel(w.reshape(-1), mob_flat, off, table).reshape(shape)
    mul, add, sub = np.multiply, np.add, np.subtract  # scalars as 0-d arrays (_K): faster
    e = np.abs(w)
    d = sub(_K[0], e)
    np.maximum(d, _K[1], out=d)
    d2 = mul(d, d)
    ld2 = np.log(d2)
    q = sub(e, w.real)
    add(e, _K[2], e)
    np.divide(q, e, q)
    t = add(d2, q, e)
    np.log(t, t)
    sub(t, ld2, t)
    mul(q, _K[3], q)
    add(t, q, t)
    add(d2, _K[4], d2)  # denominator
    np.log(d2, d2)
    sub(d2, ld2, d2)
    add(d2, _K[5], d2)
    np.divide(t, d2, t)
    mul(t, _K[6], t)
    mul(ld2, _K[7], ld2)  # fractional row
    i0 = ld2.astype(np.intp)
    it = t.astype(np.intp)
    sub(ld2, i0, ld2)
    sub(t, it, t)
    mul(i0, _K_SX, i0)
    add(i0, it, i0)
    if offset is not None:
        add(i0, offset, i0)
    add(i0, i0, i0)  # pairs (a, b - a) per node
    a = table[i0]  # a + t (b - a): row i0
    b = table[1:][i0]
    mul(b, t, b)
    add(a, b, a)
    c = table[2 * _SX:][i0]  # the next row
    b = table[2 * _SX + 1:][i0]
    mul(b, t, b)
    add(c, b, c)
    sub(c, a, c)
    mul(c, ld2, c)
    add(a, c, a)
    np.sqrt(d, d2)  # d**1.5 (d2 is free)
    mul(d2, d, d2)
    ar = a.real
    mul(ar, d2, ar)
    mul(d2, w.imag, d2)
    ai = a.imag
    mul(ai, d2, ai)
    return a


def mobility_map(zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Finite-length (Reynolds) mobility from the stored map.

    ``M = r(eps, vartheta, L/D) M_cf`` with Booker's closed-form short-bearing mobility
    ``M_cf`` (:func:`checker.calc.mobility.mobility_closed_form`) and the tabulated ratio
    ``r`` (module docstring).

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components along and across the load (``zeta**2 + kappa**2 < 1``).
    l_over_d : array_like [-]
        Width (land) over diameter, ``MAP_L_OVER_D[0] .. MAP_L_OVER_D[-1]``.

    Returns
    -------
    m_zeta, m_kappa : numpy.ndarray [-]
        Mobility in the load frame.

    Notes
    -----
    Interpolation error against the solver: :data:`MAP_MAX_REL_ERROR` (``eps <= 0.999``);
    the solver's own discretisation error at the map's grid is below 0.2 % for the steady
    and squeeze cases of the tests, up to about 1 % for near-wall loads at 60-90 degrees
    from the eccentricity.
    """
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa,
                                                                           l_over_d)))
    pf.check_in_disk(z, k)
    tab, off = stack_kernel_tables(lod)
    m = map_kernel(z + 1j * k, None, off, tab) / lod**2
    return m.real, m.imag


def film_kernels(zeta: ArrayLike, kappa: ArrayLike, l_over_d: ArrayLike
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Peak pressure and side flow of the finite-length film per unit load, from the map.

    .. math::

        p_{max} = \\Pi\\,\\frac{|F|}{L D}, \\qquad
        Q = \\Gamma\\,\\frac{c\\,R^2 \\psi^2 |F|}{\\mu L D}

    at the quasi-static state of the mobility method (load-frame eccentricity
    ``zeta + i kappa``); ``Pi = 4 (L/D) P_max / |W|``, ``Gamma = 4 (L/D) Qbar / |W|``
    (:mod:`checker.calc.reynolds`).

    Parameters
    ----------
    zeta, kappa : array_like [-]
        Eccentricity ratio components along and across the load.
    l_over_d : array_like [-]
        Width over diameter (map range).

    Returns
    -------
    Pi, Gamma : numpy.ndarray [-]
    """
    z, k, lod = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (zeta, kappa,
                                                                           l_over_d)))
    pf.check_in_disk(z, k)
    _, lp, lg, off = stack_tables(lod)
    i0, tx, tt, _, _ = _coords(z + 1j * k)
    return np.exp(_bilinear(lp, i0 + off, tx, tt)), np.exp(_bilinear(lg, i0 + off, tx, tt))


def film_state_map(
    load_x: ArrayLike,
    load_y: ArrayLike,
    eps_x: ArrayLike,
    eps_y: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Peak film pressure and side flow of the finite-length film at a mobility-method state.

    .. math::

        p_{max} = \\Pi\\,\\frac{|F|}{L D}, \\qquad
        Q = \\Gamma\\,\\frac{c R^2 \\psi^2 |F|}{\\mu L D}, \\qquad \\psi = \\frac{c}{R}

    with ``Pi``, ``Gamma`` from :func:`film_kernels` at the load-frame eccentricity. In the
    mobility method the squeeze velocity follows from the load (``V_s = c |F| psi^2 M /
    (mu L D)``), so both are functions of the load and the eccentricity.

    Parameters
    ----------
    load_x, load_y : array_like [N]
        Load applied to the journal (carried by the film).
    eps_x, eps_y : array_like [-]
        Eccentricity ratio vector, same frame, ``|eps| < 1``.
    diameter, length, clearance, viscosity : array_like [m, m, m, Pa s]
        Journal diameter, land length (map range of ``L/D``), radial clearance, viscosity.

    Returns
    -------
    p_max : numpy.ndarray [Pa]
    side_flow : numpy.ndarray [m^3/s]
        Flow out of both edges (the film's pressure-driven leakage; the feed must supply it).

    Notes
    -----
    Reynolds LCP of :mod:`checker.calc.reynolds` through the stored map; tested against the
    solver at random states (tests).
    """
    fx, fy, ex, ey, dia, ln, cl, mu = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (
        load_x, load_y, eps_x, eps_y, diameter, length, clearance, viscosity)))
    for name, val in (("diameter", dia), ("length", ln), ("clearance", cl),
                      ("viscosity", mu)):
        if not np.all(np.isfinite(val)) or np.any(val <= 0.0):
            raise ValueError(f"{name} must be finite and > 0")
    f = fx + 1j * fy
    fa = np.abs(f)
    u = np.where(fa > 0.0, np.conj(f) / np.where(fa > 0.0, fa, 1.0), 1.0)
    w = (ex + 1j * ey) * u
    pi_, gam = film_kernels(w.real, w.imag, ln / dia)
    r = 0.5 * dia
    psi = cl / r
    return pi_ * fa / (ln * dia), gam * cl * r * r * psi * psi * fa / (mu * ln * dia)
