"""Journal orbits and minimum oil film thickness (MOFT) by Booker's mobility method.

Many bearings / speeds / load cases are integrated at once: the batch axes are flattened and
advanced together by a fixed-step classical Runge-Kutta (RK4) scheme over the crank-angle grid
(one Python loop over the steps of a cycle, vectorised over the batch). Steps that are stiff
for some bearings (journal near the wall under a large load) or that would close more than
half of the remaining film gap are redone for those bearings only, with up to 8 RK4 sub-steps
or, when stiffer, with L-stable Rosenbrock (ROS2) sub-steps. The Butenschoen model, whose
receding-squeeze branch makes it stiff almost everywhere near the wall, is advanced with ROS2
(sub-steps of at most 0.5 deg) for all bearings. Sub-step counts are chosen per bearing, so a
bearing's orbit does not depend on the other bearings of the batch. Cycles are repeated until
the orbit closes (``|eps(end of cycle) - eps(start)| < tol``); converged bearings leave the
active set. ``|eps|`` is clamped at :data:`EPS_CAP`.

Equation (Booker 1965), integrated in crank angle
``theta`` (``d theta / dt = speed``)::

    d eps / d theta = |F| psi**2 / (mu L D speed) * M(eps, F_hat) + (omega_bar / speed) z_hat x eps
    omega_bar = (omega_journal + omega_bearing) / 2,    psi = 2 c / D

Frames and signs (how the caller passes loads and angular velocities)
---------------------------------------------------------------------
* Pick one right-handed frame (x, y) with z along the crank rotation vector, so the crank
  angle and all angular velocities are positive in the direction of crank rotation. For an
  engine turning clockwise seen from the front, look from the rear (or mirror y).
* ``load_x, load_y`` is the force transmitted by the oil film, **exerted by the journal on the
  bearing** (= the load applied to the journal; the film pushes the journal back with the
  opposite force). The journal centre moves towards the load direction. Mains: force of the
  crank main journal on the main bearing shell. Big end: force of the crank pin on the con-rod
  eye (points up towards the piston during firing).
* ``omega_journal`` / ``omega_bearing`` are the angular velocities of journal and bearing
  **relative to that frame**; arrays over crank angle (last axis ``N`` or 1) or scalars.
  - Main bearing, engine frame: ``omega_journal = speed``, ``omega_bearing = 0``
    (``omega_bar = speed/2``).
  - Big end, engine frame: ``omega_journal = speed``, ``omega_bearing = omega_rod(theta)``
    (absolute rod angular velocity, ``-speed lambda cos(theta) / sqrt(1 - lambda**2 sin**2
    theta)`` for a centred slider crank), loads in engine axes.
  - Big end, rod frame (loads resolved in rod-fixed axes, eccentricity then fixed to the
    shell): ``omega_journal = speed - omega_rod``, ``omega_bearing = 0``.
  - Big end, crank frame: ``omega_journal = 0``, ``omega_bearing = omega_rod - speed``.
  The film thickness does not depend on this choice (tests check engine vs rod frame).
* Returned eccentricities are in the caller's frame; ``phi_h_min`` is the direction of the
  eccentricity (location of the thinnest film) in that frame.
* With :mod:`checker.calc.crank_forces` (its frames have ``x`` at +90 deg from ``y`` in the
  direction of rotation, angles ``atan2(x, y)``, same load sign, ``rod_omega`` positive with
  the rotation) pass ``load_x = v.y`` and ``load_y = v.x``; ``phi_h_min`` is then an angle in
  that module's convention. E.g. big end in the block frame: ``big_end_block`` with
  ``omega_journal = omega``, ``omega_bearing = rod_omega``; rod frame: ``big_end_rod`` with
  ``omega_journal = omega - rod_omega``, ``omega_bearing = 0``.

Defaults (justified by ``benchmarks/bench_moft.py``: 61 speeds x 2 load cases x 9 bearings
of the example I4 with a synthetic load; see the module constants).

References
----------
.. [1] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [2] H.-J. Butenschoen, "Das hydrodynamische, zylindrische Gleitlager endlicher Breite unter
   instationaerer Belastung", Dissertation, Universitaet Karlsruhe, 1976.
.. [3] J. G. Verwer, E. J. Spee, J. G. Blom, W. Hundsdorfer, "A second-order Rosenbrock method
   applied to photochemical dispersion problems", SIAM J. Sci. Comput. 20, 1999, pp. 1456-1480, eq.
   2.2 (ROS2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from checker.calc import mobility as mb

__all__ = [
    "DEFAULT_STEPS_PER_CYCLE",
    "DEFAULT_PERIODIC_TOL",
    "DEFAULT_MAX_CYCLES",
    "DEFAULT_STIFF_LIMIT",
    "DEFAULT_MAX_SUBSTEPS",
    "EPS_CAP",
    "COLLAPSE_EPS",
    "COLLAPSE_H_MIN",
    "OrbitResult",
    "solve_orbit",
    "integrate_orbit",
]

DEFAULT_STEPS_PER_CYCLE = 360
"""RK4 steps per 4-stroke cycle (2 deg crank; the RK mid-stages use the load samples of a 1 deg
grid). Benchmark (1098 bearings: 61 speeds x 2 loads x 9 bearings, closed form, this 2-core
machine): MOFT error against a converged reference (2880 steps, tol 1e-7) at most 2.0e-4 in
0.31..0.43 s; 180 steps: 1.1e-3 (0.22..0.35 s); 90 steps: 1.5e-2; 720 steps: 6e-6 (0.56..0.75 s).
For ``"butenschoen"`` steps are at most 1 deg regardless (self-convergence 0.55 % max)."""

DEFAULT_PERIODIC_TOL = 1e-4
"""Periodicity criterion: closure of the stored cycle, ``|eps(cycle end) - eps(cycle start)|``
(vector difference) below this value. The cycle map contracts strongly (the example bearings:
a factor 1e-4..1e-5 per cycle), so the closure of cycle n equals the change of the whole orbit
from cycle n to n+1 (its largest value is at the cycle start) and the stored cycle is within
about ``tol`` of the periodic orbit at its start, much closer further on. Benchmark
(benchmarks/bench_speed.py, example I4/I6/V8 against the orbit of the earlier criterion, the
cycle-to-cycle change over the whole cycle, one cycle more): MOFT within 1e-5 relative,
2 cycles from the centred journal instead of 3."""

DEFAULT_MAX_CYCLES = 40
"""Cycles after which an orbit that is still not periodic is reported as not converged."""

DEFAULT_STIFF_LIMIT = 1.0
"""Largest ``lambda * h`` (closed-form Jacobian eigenvalue times step) taken by a plain RK4
step; above it the step is redone with sub-steps (RK4 stability limit on the negative real
axis: 2.79)."""

DEFAULT_MAX_SUBSTEPS = 16
"""Cap on ROS2 sub-steps per step (ROS2 is L-stable, so the cap only costs accuracy in
near-collapse states; hitting it is reported in the message)."""

EPS_CAP = 1.0 - 1e-7
"""Eccentricity ratios are clamped to this value: a film of 1e-7 c is a collapsed film."""

COLLAPSE_EPS = 0.999
"""Film-collapse flag threshold on the maximum eccentricity ratio (h_min < 1e-3 c)."""

COLLAPSE_H_MIN = 50e-9
"""[ASSUMPTION] Film-collapse flag threshold on the film thickness [m]: 0.05 um is about an
eighth of the composite roughness of engine bearings (sigma ~ 0.4 um), i.e. deep in boundary
lubrication where the rigid, isoviscous mobility result has no physical meaning. (Design limits
on MOFT, ~0.6..2 um, are applied by the rule layer.)"""

_S_MIN = 1.0 - EPS_CAP
_C4PI = 4.0 / np.pi
_STIFF_COEF = 2.5 / np.pi  # largest closed-form Jacobian eigenvalue: 2.5 |f| (1 - zeta)^1.5 / pi
_ROS2_GAMMA = 1.0 + 1.0 / np.sqrt(2.0)
_TRAVEL_FRAC = 0.5  # a step may close at most this fraction of the remaining film gap
_ROS2_LAMBDA_H = 4.0  # largest lambda * h of one ROS2 sub-step
_MAX_RK4_SUBSTEPS = 8  # moderately stiff steps: up to this many RK4 sub-steps, else ROS2
_ROS2_BASE_SUBSTEPS = 2  # ROS2 sub-steps per step for "butenschoen"
_BT_MAX_STEP = np.radians(1.0)  # "butenschoen": largest internal step
_ONE, _TWO, _S_MIN_0D, _MINUS_C4PI_0D, _CAP = (np.array(v) for v in (  # as 0-d arrays
    1.0, 2.0, _S_MIN, -_C4PI, EPS_CAP))


@dataclass(frozen=True)
class OrbitResult:
    """Result of :func:`solve_orbit` (batch shape ``S`` = broadcast shape without the
    crank-angle axis).

    Attributes
    ----------
    h_min : numpy.ndarray, shape S [m]
        Minimum oil film thickness over the periodic cycle, ``c (1 - eps_max)``.
    theta_h_min : numpy.ndarray, shape S [rad]
        Crank angle of ``h_min`` in ``[0, cycle_angle)``.
    eps_max : numpy.ndarray, shape S [-]
        Maximum eccentricity ratio (refined between steps by cubic Hermite interpolation).
    phi_h_min : numpy.ndarray, shape S [rad]
        Direction of the eccentricity vector at ``h_min`` (where the film is thinnest), in the
        caller's frame.
    theta : numpy.ndarray, shape (n_steps,) [rad]
        Crank angles of the stored orbit.
    eps_x, eps_y : numpy.ndarray, shape S + (n_steps,) [-]
        Periodic orbit (last cycle) in the caller's frame.
    p_max, theta_p_max : numpy.ndarray, shape S [Pa], [rad], or None
        Peak short-bearing film pressure over the cycle and its crank angle (only with
        ``peak_pressure=True``).
    vs_x, vs_y : numpy.ndarray, shape S + (n_steps,) [1/s], or None
        Squeeze velocity over clearance ``V_s / c = d eps/dt - omega_bar z_hat x eps`` along
        the stored orbit (the mobility term of the integrated rate at each step; only with
        ``squeeze_velocity=True``): :func:`checker.calc.mobility.squeeze_velocity` of the
        orbit, without evaluating the mobility again.
    converged : numpy.ndarray of bool, shape S
        Orbit periodic within ``tol``.
    collapse : numpy.ndarray of bool, shape S
        Film collapse: ``eps_max >= COLLAPSE_EPS`` (includes hitting ``EPS_CAP``) or
        ``h_min < collapse_h_min``.
    n_cycles : numpy.ndarray of int, shape S
        Cycles integrated.
    periodic_error : numpy.ndarray, shape S [-]
        Closure of the stored cycle ``|eps(end) - eps(start)|`` (= the change of the orbit in
        one more cycle, at the cycle start).
    message : numpy.ndarray of str (object), shape S
        Empty, or why the bearing is flagged.
    model : str
        Mobility model used.
    steps_per_cycle : int
    """

    h_min: np.ndarray
    theta_h_min: np.ndarray
    eps_max: np.ndarray
    phi_h_min: np.ndarray
    theta: np.ndarray
    eps_x: np.ndarray
    eps_y: np.ndarray
    p_max: np.ndarray | None
    theta_p_max: np.ndarray | None
    converged: np.ndarray
    collapse: np.ndarray
    n_cycles: np.ndarray
    periodic_error: np.ndarray
    message: np.ndarray
    model: str
    steps_per_cycle: int
    vs_x: np.ndarray | None = None
    vs_y: np.ndarray | None = None


# --------------------------------------------------------------------------------------------
# set-up
# --------------------------------------------------------------------------------------------
def _resample_periodic(a: np.ndarray, n_out: int) -> np.ndarray:
    """Periodic linear resampling of the last axis (length N) to ``n_out`` points."""
    n_in = a.shape[-1]
    if n_in == n_out:
        return a
    if n_in == 1:
        return np.repeat(a, n_out, axis=-1)
    if n_in % n_out == 0:
        return a[..., :: n_in // n_out]
    pos = np.arange(n_out) * (n_in / n_out)
    i0 = np.floor(pos).astype(np.intp)
    t = pos - i0
    i0 %= n_in
    i1 = (i0 + 1) % n_in
    return a[..., i0] * (1.0 - t) + a[..., i1] * t


def _resample_nodes(a: np.ndarray, n_out: int, out: np.ndarray) -> None:
    """:func:`_resample_periodic` of the rows of ``a`` (B, N), written transposed into
    ``out`` (n_out, B) (the node-major layout of the RK nodes; a real or imaginary part of a
    complex array). Same numbers: ``a_i0 (1 - t) + a_i1 t``, and ``a_i0`` itself where
    ``t = 0``."""
    n_in = a.shape[-1]
    at = np.ascontiguousarray(a.T)
    if n_in == n_out:
        out[...] = at
        return
    if n_in == 1:
        out[...] = at
        return
    if n_in % n_out == 0:
        out[...] = at[:: n_in // n_out]
        return
    pos = np.arange(n_out) * (n_in / n_out)
    i0 = np.floor(pos).astype(np.intp)
    t = pos - i0
    i0 %= n_in
    i1 = (i0 + 1) % n_in
    on = t == 0.0
    out[on] = at[i0[on]]
    k = np.flatnonzero(~on)
    if k.size:
        tk = t[k][:, None]
        v = at[i0[k]]
        v *= 1.0 - tk
        u = at[i1[k]]
        u *= tk
        v += u
        out[k] = v


class _Problem:
    """Batch arrays on the RK node grid (node-major, shape (2n, B)) and per-bearing data."""

    def __init__(
        self, load_x, load_y, omega_journal, omega_bearing, speed, diameter, length, clearance,
        viscosity, model, full_groove, steps_per_cycle, cycle_angle, solver_grid=None,
        solver_groove=None, share: bool = False, group=None,
    ):
        if model not in mb.MOBILITY_MODELS:
            raise ValueError(f"unknown model {model!r}; choose one of {mb.MOBILITY_MODELS}")
        if int(steps_per_cycle) != steps_per_cycle or steps_per_cycle < 8:
            raise ValueError("steps_per_cycle must be an integer >= 8")
        if not (np.isfinite(cycle_angle) and cycle_angle > 0.0):
            raise ValueError("cycle_angle must be > 0")
        fx = np.asarray(load_x, dtype=float)
        fy = np.asarray(load_y, dtype=float)
        if fx.ndim == 0 or fy.ndim == 0:
            raise ValueError("loads need a crank-angle axis (last axis, N points over the cycle)")
        fx, fy = np.broadcast_arrays(fx, fy)
        wj = np.asarray(omega_journal, dtype=float)
        wb = np.asarray(omega_bearing, dtype=float)
        full = np.broadcast_shapes(fx.shape, wj.shape, wb.shape)
        n_pts = full[-1]
        lead = np.broadcast_shapes(
            full[:-1], *(np.shape(a) for a in (speed, diameter, length, clearance, viscosity,
                                                full_groove))
        )
        shp = lead + (n_pts,)
        per = [
            np.broadcast_to(np.asarray(a, dtype=float), lead).reshape(-1)
            for a in (speed, diameter, length, clearance, viscosity)
        ]
        sp, dia, ln, cl, mu = per
        for name, val in (("speed", sp), ("diameter", dia), ("length", ln),
                          ("clearance", cl), ("viscosity", mu)):
            if not np.all(np.isfinite(val)) or np.any(val <= 0.0):
                raise ValueError(f"{name} must be finite and > 0")
        if np.any(cl >= 0.05 * dia):
            raise ValueError("radial clearance must be small compared with the diameter")
        grooved = np.broadcast_to(np.asarray(full_groove, dtype=bool), lead).reshape(-1)
        if np.prod(shp) > 0:  # checked before broadcasting (same verdict, less work)
            for name, val in (("load", fx), ("load", fy), ("omega_journal", wj),
                              ("omega_bearing", wb)):
                # a finite sum has finite terms (one pass, no temporary)
                if not (np.isfinite(np.sum(val)) or np.all(np.isfinite(val))):
                    raise ValueError(f"{name} must be finite")
        fx = np.broadcast_to(fx, shp).reshape(-1, n_pts)
        fy = np.broadcast_to(fy, shp).reshape(-1, n_pts)
        w = np.broadcast_to(wj + wb, shp).reshape(-1, n_pts)  # whirl: the sum only

        n = int(steps_per_cycle)
        if model == "butenschoen":  # stiff model: steps of at most 1 deg
            n = max(n, int(np.ceil(cycle_angle / _BT_MAX_STEP - 1e-9)))
        self.shape = lead
        self.n = n
        self.h = cycle_angle / n
        # orbits that are another's shifted by whole steps: solved once (_shared_rows)
        size_all = fx.shape[0]
        self.full_size = size_all
        self.rep = np.arange(size_all)
        self.shift = np.zeros(size_all, dtype=np.intp)
        self.uniq = self.rep
        if share and size_all > 1 and n_pts % n == 0:
            grp = (np.zeros(size_all, np.int64) if group is None
                   else np.broadcast_to(np.asarray(group), lead).reshape(-1))
            self.rep, self.shift = _shared_rows(fx, fy, w, (sp, dia, ln, cl, mu),
                                                grooved, grp, n_pts // n)
            self.uniq = np.flatnonzero(self.rep == np.arange(size_all))
            if self.uniq.size < size_all:
                u = self.uniq
                fx, fy, w = fx[u], fy[u], w[u]
                sp, dia, ln, cl, mu, grooved = sp[u], dia[u], ln[u], cl[u], mu[u], grooved[u]
        self.rpos = np.searchsorted(self.uniq, self.rep)  # each orbit's solved orbit
        self.cycle_angle = float(cycle_angle)
        self.model = model
        land = np.where(grooved, 0.5 * ln, ln)
        lod = land / dia
        if model == "butenschoen":
            mb._check_b_over_d(lod)
        psi = 2.0 * cl / dia
        k = psi**2 / (mu * ln * dia * sp)  # |f| = |F| k  [1/rad]
        scale = k / lod**2 if model != "butenschoen" else k
        if model == "closed_form":
            scale = scale / np.pi
        stiff_scale = k / lod**2  # closed-form equivalent for the stiffness estimate

        # node-major arrays (2n, B); few large temporaries (page faults dominate set-up time)
        if n_pts == 2 * n:
            f = np.empty((2 * n, fx.shape[0]), dtype=complex)
            f.real, f.imag = fx.T, fy.T
            iwb = np.zeros((2 * n, fx.shape[0]), dtype=complex)
            iwb.imag = w.T
        else:
            # periodic linear resampling (_resample_periodic) of the real parts
            f = np.empty((2 * n, fx.shape[0]), dtype=complex)
            _resample_nodes(fx, 2 * n, f.real)
            _resample_nodes(fy, 2 * n, f.imag)
            iwb = np.zeros((2 * n, fx.shape[0]), dtype=complex)
            _resample_nodes(w, 2 * n, iwb.imag)
        iwb *= 0.5 / sp
        fa = np.abs(f)
        uc = np.conj(f)
        np.divide(uc, fa, out=uc, where=fa > 0.0)
        uc[fa == 0.0] = 1.0
        f *= scale  # scaled complex load number per node
        fa *= stiff_scale  # closed-form-equivalent |f| for the stiffness estimate
        fs_step = np.maximum(fa[0::2], fa[1::2])
        np.maximum(fs_step, np.roll(fa[0::2], -1, axis=0), out=fs_step)
        fs_step *= _STIFF_COEF * self.h
        self.arr = {"fk": f, "uc": uc, "iwb": iwb, "lam": fs_step}  # lam: (n, B)

        self.shared = {}
        tid = np.zeros(lod.size, dtype=np.intp)
        if model in ("reynolds_map", "reynolds"):
            from checker.calc import reynolds_map as rm

            # ValueError outside the map's L/D range
            self.shared["map_table"], tid = rm.stack_kernel_tables(lod)
            if model == "reynolds":
                self.shared["solver_grid"] = solver_grid
                self.shared["solver_groove"] = solver_groove
        self.bear = {
            "tid": tid,
            "lod": lod,
            "coef": mb._butenschoen_coefficients(lod).T.copy() if model == "butenschoen"
            else np.zeros((lod.size, 0)),
            "clearance": cl,
            "viscosity": mu,
            "land": land,
            "speed": sp,
        }
        self.size = lod.size

    def take(self, keep: np.ndarray) -> None:
        for key, val in self.arr.items():
            self.arr[key] = val[:, keep]
        for key, val in self.bear.items():
            self.bear[key] = val[keep]
        self.size = int(np.count_nonzero(keep)) if keep.dtype == bool else len(keep)


# --------------------------------------------------------------------------------------------
# right-hand sides
# --------------------------------------------------------------------------------------------
def _make_rate(model: str, bear: dict, shared: dict | None = None):
    """Return rate(z, fk, uc, iwb, sel) -> d eps / d theta (complex) for the active bearings
    (``sel``: indices of a subset of the active bearings, for per-bearing model data)."""
    if model == "closed_form":

        def rate(z, fk, uc, iwb, sel=None):
            # fk M + iwb z, M = s^1.5 (s - i (4/pi) w.imag): real arithmetic on the parts
            w = z * uc
            s = np.subtract(_ONE, w.real)
            np.maximum(s, _S_MIN_0D, out=s)
            g = np.sqrt(s)
            np.multiply(s, g, out=g)
            m = np.empty(w.shape, dtype=complex)
            np.multiply(g, s, out=m.real)
            wi = np.multiply(w.imag, _MINUS_C4PI_0D, out=s)
            np.multiply(g, wi, out=m.imag)
            r = fk * m  # (not in place: NumPy's in-place complex product of one element
            p = iwb * z  # is rounded differently)
            np.add(r, p, out=r)
            rate.last = (w, p)  # load-frame eccentricity and whirl term, for the caller
            return r

        return rate

    def clip(w):
        a = np.abs(w)
        return np.where(a > EPS_CAP, w * (EPS_CAP / np.maximum(a, EPS_CAP)), w)

    if model == "exact_table":

        def rate(z, fk, uc, iwb, sel=None):
            return fk * mb._m_exact_table(clip(z * uc)) + iwb * z

        return rate
    if model == "exact":

        def rate(z, fk, uc, iwb, sel=None):
            return fk * mb._m_exact(clip(z * uc)) + iwb * z

        return rate
    if model == "reynolds_map":
        from checker.calc import reynolds_map as rm

        tab = shared["map_table"]
        tid = bear["tid"] if bear["tid"].any() else None  # None: one table

        def rate(z, fk, uc, iwb, sel=None):
            t = tid if sel is None or tid is None else tid[sel]
            w = z * uc
            m = rm.map_kernel(w, None, t, tab)
            r = fk * m  # (not in place: NumPy's in-place complex product of one element
            p = iwb * z  # is rounded differently)
            np.add(r, p, out=r)
            rate.last = (w, p)  # load-frame eccentricity and whirl term, for the caller
            return r

        return rate
    if model == "reynolds":
        from checker.calc import reynolds as ry
        from checker.calc import reynolds_map as rm

        tab = shared["map_table"]
        tid = bear["tid"]
        lod_all = bear["lod"]
        grid = shared.get("solver_grid") or ry.DEFAULT_GRID
        groove = shared.get("solver_groove")

        def rate(z, fk, uc, iwb, sel=None):
            t = tid if sel is None else tid[sel]
            lods = lod_all if sel is None else lod_all[sel]
            w = clip(z * uc)
            aw = np.abs(w)
            w = np.where(aw > ry.EPS_MAX, w * (ry.EPS_MAX / np.maximum(aw, ry.EPS_MAX)), w)
            guess = rm.map_kernel(w, None, t, tab)  # initial squeeze direction from the map
            alpha0 = np.angle(guess) - np.angle(w)  # M is along V_s: alpha = arg M + chi
            m = np.empty(w.shape, dtype=complex)
            phi = np.angle(z)  # eccentricity direction in the caller's frame
            for i in range(w.size):
                g_e = None if groove is None else (
                    groove[0] - phi[i], groove[1] - phi[i], groove[2])
                mz, mk = ry.mobility_reynolds(w.real[i], w.imag[i], float(lods[i]),
                                               grid=grid, alpha0=alpha0[i], groove=g_e)
                m[i] = complex(float(mz), float(mk)) * lods[i] ** 2
            return fk * m + iwb * z

        return rate
    x = bear["lod"]
    a = bear["coef"].T

    def rate(z, fk, uc, iwb, sel=None):
        if sel is None:
            return fk * mb._m_butenschoen(clip(z * uc), x, a) + iwb * z
        return fk * mb._m_butenschoen(clip(z * uc), x[sel], a[:, sel]) + iwb * z

    return rate


def _load_at(fk3, iw3, t: float, diff=None):
    """Load (complex), its unit conjugate and the whirl term at fraction ``t`` of a step,
    linear between the step's start, middle and end samples ``fk3``/``iw3``. ``diff``: the
    differences of consecutive samples (:func:`_step_diffs`), when already computed."""
    if diff is None:
        diff = _step_diffs(fk3, iw3)
    if t <= 0.5:
        s = np.array(2.0 * t)
        f = fk3[0] + s * diff[0]
        w = iw3[0] + s * diff[2]
    else:
        s = np.array(2.0 * t - 1.0)
        f = fk3[1] + s * diff[1]
        w = iw3[1] + s * diff[3]
    fa = np.abs(f)
    pos = fa > 0.0
    if pos.all():  # the common case: the same numbers without the masks
        uc = np.conj(f) / fa
    else:
        uc = np.where(pos, np.conj(f) / np.where(pos, fa, 1.0), 1.0)
    return f, uc, w


def _step_diffs(fk3, iw3):
    """Differences of the consecutive load and whirl samples of a step (for :func:`_load_at`)."""
    return fk3[1] - fk3[0], fk3[2] - fk3[1], iw3[1] - iw3[0], iw3[2] - iw3[1]


def _ros2_steps(rate, z, fk3, iw3, sel, h, nsub):
    """Advance ``z`` over one RK step of length ``h`` with ``nsub`` ROS2 sub-steps.

    ``fk3``/``iw3``: load numbers and ``i omega_bar/speed`` at the three nodes of the step
    (start, middle, end), interpolated piecewise-linearly; ``sel``: indices of the bearings in
    the active set (for per-bearing model data) or None. ROS2 (Verwer J.G., Spee E.J.,
    Blom J.G., Hundsdorfer W., 1999, "A second-order Rosenbrock method applied to
    photochemical dispersion problems", SIAM J. Sci. Comput. 20:1456-1480, eq. (2.2) with
    gamma = 1 + 1/sqrt(2)) is L-stable and of order 2 for any Jacobian approximation
    (W-method); the Jacobian is a finite difference at the start of each sub-step.

    Returns ``(z_new, rate_at_start, max lambda*h per sub-step)``.
    """

    diff = _step_diffs(fk3, iw3)

    def at(t):
        return _load_at(fk3, iw3, t, diff)

    hs = h / nsub
    gh = _ROS2_GAMMA * hs
    r_start = None
    lam_h = np.zeros(z.shape)
    f1, u1, w1 = at(0.0)
    for k in range(nsub):
        f0, u0, w0 = f1, u1, w1
        f1, u1, w1 = at((k + 1) / nsub)
        r0 = rate(z, f0, u0, w0, sel)
        if r_start is None:
            r_start = r0
        dz = 1e-6 * np.maximum(1.0 - np.abs(z), 1e-6)
        c1 = (rate(z + dz, f0, u0, w0, sel) - r0) / dz
        c2 = (rate(z + 1j * dz, f0, u0, w0, sel) - r0) / dz
        # spectral radius of the Jacobian (for the sub-step control of the caller)
        tr = 0.5 * (c1.real + c2.imag)
        det_j = c1.real * c2.imag - c2.real * c1.imag
        disc = tr * tr - det_j
        rad = np.where(disc >= 0.0, np.abs(tr) + np.sqrt(np.abs(disc)), np.sqrt(np.abs(det_j)))
        lam_h = np.maximum(lam_h, hs * rad)
        w11 = 1.0 - gh * c1.real
        w21 = -gh * c1.imag
        w12 = -gh * c2.real
        w22 = 1.0 - gh * c2.imag
        det = w11 * w22 - w12 * w21
        v = r0
        k1 = ((w22 * v.real - w12 * v.imag) + 1j * (-w21 * v.real + w11 * v.imag)) / det
        v = rate(z + hs * k1, f1, u1, w1, sel) - 2.0 * k1
        k2 = ((w22 * v.real - w12 * v.imag) + 1j * (-w21 * v.real + w11 * v.imag)) / det
        z = z + hs * (1.5 * k1 + 0.5 * k2)
        za = np.abs(z)
        if (za > EPS_CAP).any():  # (clamp only when needed: same numbers)
            z = np.where(za > EPS_CAP, z * (EPS_CAP / np.maximum(za, EPS_CAP)), z)
    return z, r_start, lam_h


def _rk4_steps(rate, z, fk3, iw3, h, nsub, sel=None):
    """Advance ``z`` over one step of length ``h`` with ``nsub`` classical RK4 sub-steps
    (loads piecewise-linear between the three nodes of the step)."""

    diff = _step_diffs(fk3, iw3)

    def at(t):
        return _load_at(fk3, iw3, t, diff)

    hs = h / nsub
    # z + hs/6 (k1 + 2 (k2 + k3) + k4); scalars as 0-d arrays (same numbers, faster calls)
    c_half, c_hs, c_h6 = np.array(0.5 * hs), np.array(hs), np.array(hs / 6.0)
    p1 = at(0.0)
    for k in range(nsub):
        p0 = p1
        pm = at((k + 0.5) / nsub)
        p1 = at((k + 1.0) / nsub)
        k1 = rate(z, *p0, sel)
        k2 = rate(z + c_half * k1, *pm, sel)
        k3 = rate(z + c_half * k2, *pm, sel)
        k4 = rate(z + c_hs * k3, *p1, sel)
        np.add(k2, k3, k2)
        np.multiply(_TWO, k2, k2)
        np.add(k1, k2, k2)
        np.add(k2, k4, k2)
        z = z + np.multiply(c_h6, k2, k2)
        za = np.abs(z)
        if (za > _CAP).any():  # (clamp only when needed: same numbers)
            z = np.where(za > EPS_CAP, z * (EPS_CAP / np.maximum(za, EPS_CAP)), z)
    return z


def _nsub_each(need: np.ndarray, max_substeps: int) -> np.ndarray:
    """Sub-steps per bearing: the power of two >= ``need`` (at least 1, at most
    ``max_substeps``). Per bearing, so that a bearing's orbit does not depend on the other
    bearings of the batch (batched and one-by-one evaluation give identical numbers)."""
    r = np.nan_to_num(need, nan=1e6, posinf=1e6)
    k = np.ceil(np.log2(np.clip(r, 1.0, 1e6)))
    return np.minimum(max_substeps, 2 ** k.astype(np.int64))


def _run_cycle(prob: _Problem, z: np.ndarray, stiff_limit: float, max_substeps: int):
    """One cycle for the active bearings. Returns (z_end, z_hist, k_hist, capped, stiff_cap).

    Scheme "rk4" (closed_form, exact, exact_table): classical RK4 on the node grid; a step is
    redone for the bearings where it is stiff (closed-form Jacobian eigenvalue estimate
    ``lambda h > stiff_limit``) or where it closes more than half of the remaining film gap:
    with up to 8 RK4 sub-steps, or, if more would be needed, with L-stable ROS2 sub-steps.
    Scheme "ros2" (butenschoen, stiff everywhere near the wall because its receding squeeze
    branch is very mobile): ROS2 sub-steps of at most 0.5 deg for all bearings, more where
    lambda h > 4 or where a sub-step would close more than half of the film gap.
    """
    n, h = prob.n, prob.h
    hh, h6 = 0.5 * h, h / 6.0
    arr = prob.arr
    fk, uc, iwb, lam = arr["fk"], arr["uc"], arr["iwb"], arr["lam"]
    rate = _make_rate(prob.model, prob.bear, prob.shared)
    map_stiff = prob.model in ("reynolds_map", "reynolds")
    reuse = prob.model in ("closed_form", "reynolds_map")  # rates that keep rate.last
    implicit = prob.model == "butenschoen"
    nbase = _ROS2_BASE_SUBSTEPS
    zh = np.empty((n, z.size), dtype=complex)
    kh = np.empty((n, z.size), dtype=complex)
    capped = np.zeros(z.size, dtype=bool)
    stiff_cap = np.zeros(z.size, dtype=bool)
    za0 = np.abs(z)
    thr = np.minimum(za0 * (1.0 - _TRAVEL_FRAC) + _TRAVEL_FRAC, EPS_CAP)
    # steps where the closed-form stiffness estimate (s <= 2) can exceed the limit somewhere
    stiff_possible = (np.ones(n, dtype=bool) if map_stiff or not lam.size
                      else lam.max(axis=1) * 2.0**1.5 > stiff_limit)
    # the scalars of the step loop as 0-d arrays: the same numbers, faster NumPy calls
    c_one, c_two, c_h, c_hh, c_h6, c_15h, c_lim, c_keep, c_frac, c_cap = (
        np.array(float(v)) for v in (1.0, 2.0, h, hh, h6, 1.5 * h, stiff_limit,
                                     1.0 - _TRAVEL_FRAC, _TRAVEL_FRAC, EPS_CAP))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        for j in range(n):
            a, m, b = 2 * j, 2 * j + 1, (2 * j + 2) % (2 * n)
            zh[j] = z
            if implicit:
                znew, k1, lh = _ros2_steps(rate, z, (fk[a], fk[m], fk[b]),
                                           (iwb[a], iwb[m], iwb[b]), None, h, nbase)
                kh[j] = k1
                za = np.abs(znew)
                need = np.maximum(lh / _ROS2_LAMBDA_H, (za - za0) / (_TRAVEL_FRAC * (1.0 - za0)))
                flag = need > 1.0
                if flag.any():
                    idx = np.flatnonzero(flag)
                    stiff_cap[idx[nbase * need[idx] > max_substeps]] = True
                    nsubs = _nsub_each(nbase * need[idx], max_substeps)
                    for nsub in sorted(set(nsubs.tolist())):
                        if nsub <= nbase:
                            continue
                        g = idx[nsubs == nsub]
                        znew[g], _, _ = _ros2_steps(
                            rate, z[g], (fk[a, g], fk[m, g], fk[b, g]),
                            (iwb[a, g], iwb[m, g], iwb[b, g]), g, h, int(nsub))
                        za[g] = np.abs(znew[g])
            else:
                k1 = rate(z, fk[a], uc[a], iwb[a])
                # z uc[a] and iwb[a] z as the rate computed them, or computed again
                w1, p1 = rate.last if reuse else (None, None)
                kh[j] = k1
                k2 = rate(z + c_hh * k1, fk[m], uc[m], iwb[m])
                k3 = rate(z + c_hh * k2, fk[m], uc[m], iwb[m])
                k4 = rate(z + c_h * k3, fk[b], uc[b], iwb[b])
                np.add(k2, k3, k2)
                np.multiply(k2, c_two, k2)
                np.add(k2, k1, k2)
                np.add(k2, k4, k2)
                np.multiply(k2, c_h6, k2)
                znew = np.add(k2, z, k2)
                za = np.abs(znew)
                # (2) travel: the step closes more than _TRAVEL_FRAC of the film gap
                # (za - za0 > F (1 - za0); the threshold also catches |eps| > EPS_CAP)
                flag = za > thr
                lh = None
                if stiff_possible[j]:
                    # (1) closed-form stiffness estimate 2.5/pi |f|max h s^1.5,
                    # s = 1 - zeta + travel
                    if w1 is None:
                        w1 = z * uc[a]
                    s = np.minimum(c_one - w1.real + c_h * np.abs(k1), c_two)
                    lh = lam[j] * (s * np.sqrt(s))
                    if map_stiff:
                        # finite length: Jacobian ~ p |f M| / s for M ~ s^p; p = 2.5 for the
                        # short bearing, 1.5 for the (locally long) finite-length film near
                        # the wall
                        if p1 is None:
                            p1 = iwb[a] * z
                        lh = np.maximum(lh, c_15h * np.abs(k1 - p1) / s)
                    flag |= lh > c_lim
                if flag.any():
                    idx = np.flatnonzero(flag)
                    travel = (za[idx] - za0[idx]) / (_TRAVEL_FRAC * (1.0 - za0[idx]))
                    lhi = np.zeros(idx.size) if lh is None else lh[idx]
                    sub = (travel > 1.0) | (lhi > stiff_limit)
                    if not sub.all():  # only beyond the eccentricity cap: clamp
                        io = idx[~sub]
                        capped[io] = True
                        znew[io] *= EPS_CAP / za[io]
                        za[io] = EPS_CAP
                        idx, travel, lhi = idx[sub], travel[sub], lhi[sub]
                    need = np.maximum(lhi / stiff_limit, travel)
                    # moderately stiff: RK4 sub-steps; very stiff: L-stable ROS2 sub-steps
                    rk = ~(np.nan_to_num(need, nan=np.inf) > _MAX_RK4_SUBSTEPS)
                    nsubs = _nsub_each(need, _MAX_RK4_SUBSTEPS)
                    need_r = np.maximum(lhi / _ROS2_LAMBDA_H, travel)
                    stiff_cap[idx[~rk & (need_r > max_substeps)]] = True
                    nsubs_r = _nsub_each(need_r, max_substeps)
                    for ros, nsub in sorted({(False, int(v)) for v in nsubs[rk]}
                                            | {(True, int(v)) for v in nsubs_r[~rk]}):
                        g = idx[(~rk & (nsubs_r == nsub)) if ros else (rk & (nsubs == nsub))]
                        fk3 = (fk[a, g], fk[m, g], fk[b, g])
                        iw3 = (iwb[a, g], iwb[m, g], iwb[b, g])
                        if ros:
                            znew[g], _, _ = _ros2_steps(rate, z[g], fk3, iw3, g, h, nsub)
                        else:
                            znew[g] = _rk4_steps(rate, z[g], fk3, iw3, h, nsub, g)
                    za[idx] = np.abs(znew[idx])
                    over = za[idx] > EPS_CAP
                    if over.any():
                        io = idx[over]
                        capped[io] = True
                        znew[io] *= EPS_CAP / za[io]
                        za[io] = EPS_CAP
                z = znew
                za0 = za
                thr = np.minimum(za0 * c_keep + c_frac, c_cap)
                continue
            over = za > EPS_CAP
            if over.any():
                capped |= over
                znew = np.where(over, znew * (EPS_CAP / np.maximum(za, EPS_CAP)), znew)
                za = np.minimum(za, EPS_CAP)
            z = znew
            za0 = za
    return z, zh, kh, capped, stiff_cap


def _hermite_max(zh: np.ndarray, kh: np.ndarray, h: float):
    """Max |eps| over the cycle from step values and slopes (cubic Hermite, 32 samples in the
    two steps around the discrete maximum). Returns (eps_max, position in steps, eps at max)."""
    n = zh.shape[0]
    r = np.abs(zh)
    j = np.argmax(r, axis=0)
    cols = np.arange(zh.shape[1])
    s = np.linspace(0.0, 1.0, 17)[1:-1, None]
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    best = r[j, cols]
    pos = j.astype(float)
    zbest = zh[j, cols]
    for j0 in ((j - 1) % n, j):
        j1 = (j0 + 1) % n
        p = (h00 * zh[j0, cols] + h10 * h * kh[j0, cols] + h01 * zh[j1, cols]
             + h11 * h * kh[j1, cols])
        ap = np.abs(p)
        i = np.argmax(ap, axis=0)
        v = ap[i, cols]
        better = v > best
        best = np.where(better, v, best)
        pos = np.where(better, j0 + s[i, 0], pos)
        zbest = np.where(better, p[i, cols], zbest)
    return np.minimum(best, EPS_CAP), pos % n, zbest


def _peak_pressure(zh, kh, iwb_steps, bear, n_refine: int = 8):
    """Peak short-bearing film pressure over the stored cycle (per bearing).

    Screening: ``cos(theta - alpha) / (1 - eps cos theta)^3`` on 16 points of the Sommerfeld
    variable at every step; the ``n_refine`` best steps per bearing are then maximised
    accurately by :func:`checker.calc.mobility.short_bearing_peak_pressure` (benchmark: same
    result as refining every step, to rounding).
    """
    vs = (kh - iwb_steps * zh) * bear["speed"]  # V_s / c  [1/s]
    za = np.abs(zh)
    zc = np.where(za > EPS_CAP, zh * (EPS_CAP / np.maximum(za, EPS_CAP)), zh)
    eps = np.abs(zc)
    alpha = np.angle(vs) - np.angle(zc)
    q = np.sqrt((1.0 - eps) * (1.0 + eps))
    ca, sb = np.cos(alpha), q * np.sin(alpha)
    screen = np.full(eps.shape, -np.inf)
    for g in np.linspace(-np.pi, np.pi, 16, endpoint=False):
        cg = np.cos(g)
        val = (ca * (cg + eps) + sb * np.sin(g)) * (1.0 + eps * cg) ** 2
        np.maximum(screen, val, out=screen)
    screen = screen / q**6 * np.abs(vs)
    k = min(n_refine, zh.shape[0])
    cand = np.argpartition(-screen, k - 1, axis=0)[:k]  # (k, B)
    cols = np.arange(zh.shape[1])
    zs, vv = zc[cand, cols], vs[cand, cols]
    p, _ = mb.short_bearing_peak_pressure(zs.real, zs.imag, vv.real, vv.imag, bear["land"],
                                            bear["clearance"], bear["viscosity"])
    best = np.argmax(p, axis=0)
    return p[best, cols], cand[best, cols]


def _quantize(a: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Integers equal for values equal to about 6e-11 of ``scale`` (relative; values that
    round differently are only not shared)."""
    return np.rint(a / scale * 2.0**34).astype(np.int64)


def _mantissa_key(a: np.ndarray) -> np.ndarray:
    """Integers equal for positive numbers equal to about 1.5e-11 relative."""
    m, e = np.frexp(np.asarray(a, dtype=float))
    return np.rint(m * 2.0**36).astype(np.int64) + (e.astype(np.int64) << 40)


def _shared_rows(fx, fy, w, scalars, grooved, group, p: int):
    """Orbits that are another orbit shifted in crank angle by whole steps.

    Two bearings with the same geometry, clearance, viscosity and speed whose loads and
    whirl (``omega_journal + omega_bearing``) are the same sequence shifted by a whole number
    of steps (``p`` load points per step; e.g. the big ends of an in-line engine, or mains 1
    and 5 of an I4) solve the same discrete problem relabelled in crank angle: their periodic
    orbits are one orbit shifted by that many steps. Candidates by a fingerprint (scalars and
    16 load points from the largest load), then every point checked to 1e-10 of the largest
    load and whirl. Returns ``(rep, shift)``: the index of the orbit that is solved (the first
    of its kind) and the shift in steps, ``orbit_i[k] = orbit_rep[k - shift]``. Orbits of
    different ``group`` are never shared.
    """
    size, n_pts = fx.shape
    rows = np.arange(size)
    mag = fx[:, ::p] ** 2 + fy[:, ::p] ** 2
    o = p * np.argmax(mag, axis=1)  # canonical start point (a step point)
    sf = np.sqrt(mag.max(axis=1))
    sf[sf == 0.0] = 1.0
    sw = np.maximum(w.max(axis=1), -w.min(axis=1))  # max |w|
    sw[sw == 0.0] = 1.0
    probe = (o[:, None] + np.arange(0, n_pts, max(1, n_pts // 16))[None, :]) % n_pts
    scal = [_mantissa_key(a) for a in scalars] + [
        grooved.astype(np.int64), group.astype(np.int64), _mantissa_key(sf),
        _mantissa_key(sw)]
    key = np.ascontiguousarray(np.concatenate(
        [np.stack(scal, axis=1), _quantize(fx[rows[:, None], probe], sf[:, None]),
         _quantize(fy[rows[:, None], probe], sf[:, None]),
         _quantize(w[rows[:, None], probe], sw[:, None])], axis=1))
    # the first row with the same key (np.unique's indices are first occurrences)
    _, first, inv = np.unique(key.view(np.dtype((np.void, key.shape[1] * key.itemsize)))
                              .reshape(-1), return_index=True, return_inverse=True)
    rep = first[inv.reshape(-1)].astype(np.intp)
    dup = np.flatnonzero(rep != rows)
    if dup.size:  # verify every point: the loads and whirl are the shifted sequence
        r = rep[dup]
        ok = np.ones(dup.size, dtype=bool)
        d_shift = (o[dup] - o[r]) % n_pts  # arr[d, j] == arr[r, j - d_shift]
        for s in sorted(set(d_shift.tolist())):  # a few distinct shifts: whole rows rolled
            m = np.flatnonzero(d_shift == s)
            for arr, sc in ((fx, sf), (fy, sf), (w, sw)):
                dev = arr[dup[m]]  # minus the representative's row rolled by s
                ref = arr[r[m]]
                dev[:, s:] -= ref[:, :n_pts - s]
                dev[:, :s] -= ref[:, n_pts - s:]
                dev = np.abs(dev, out=dev).max(axis=1)
                ok[m] &= dev <= 1e-10 * sc[r[m]]
        rep[dup[~ok]] = dup[~ok]
    shift = ((o - o[rep]) // p) % (n_pts // p)
    return rep, shift


def _prepare_eps0(eps0_x, eps0_y, prob: _Problem) -> np.ndarray:
    if eps0_x is None and eps0_y is None:
        return np.zeros(prob.full_size, dtype=complex)
    ex = np.broadcast_to(np.asarray(0.0 if eps0_x is None else eps0_x, dtype=float), prob.shape)
    ey = np.broadcast_to(np.asarray(0.0 if eps0_y is None else eps0_y, dtype=float), prob.shape)
    z = (ex + 1j * ey).reshape(-1).astype(complex)
    if not np.all(np.isfinite(z)) or np.any(np.abs(z) >= 1.0):
        raise ValueError("initial eccentricity ratio must be finite and < 1")
    return z


# --------------------------------------------------------------------------------------------
# public API
# --------------------------------------------------------------------------------------------
def solve_orbit(
    load_x: ArrayLike,
    load_y: ArrayLike,
    omega_journal: ArrayLike,
    omega_bearing: ArrayLike,
    speed: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
    *,
    model: str = "closed_form",
    full_groove: ArrayLike = False,
    steps_per_cycle: int = DEFAULT_STEPS_PER_CYCLE,
    tol: float = DEFAULT_PERIODIC_TOL,
    max_cycles: int = DEFAULT_MAX_CYCLES,
    stiff_limit: float = DEFAULT_STIFF_LIMIT,
    max_substeps: int = DEFAULT_MAX_SUBSTEPS,
    peak_pressure: bool = False,
    eps0_x: ArrayLike | None = None,
    eps0_y: ArrayLike | None = None,
    cycle_angle: float = 4.0 * np.pi,
    collapse_h_min: float = COLLAPSE_H_MIN,
    solver_grid=None,
    solver_groove=None,
    share_orbits: bool = True,
    group: ArrayLike | None = None,
    squeeze_velocity: bool = False,
) -> OrbitResult:
    """Periodic journal orbit and minimum oil film thickness for a batch of bearings.

    Integrates Booker's mobility equation (module docstring) over repeated engine cycles with
    fixed-step RK4 (``steps_per_cycle`` steps; the RK mid-stage loads are the load samples
    half-way between steps, so a 1-deg load grid with 360 steps is used without
    interpolation; other grids are resampled periodically-linearly) until
    the cycle closes, ``|eps(end) - eps(start)| < tol``. Stiff steps (estimated
    ``2.5/pi |F|psi^2/(mu L D speed) (D/L)^2 (1-zeta)^1.5 h > stiff_limit``) are redone for the
    affected bearings with ROS2 sub-steps; ``|eps|`` is clamped to ``EPS_CAP`` so the film never
    closes.

    Parameters
    ----------
    load_x, load_y : array_like, shape (..., N) [N]
        Load exerted by the journal on the bearing (module docstring), on the cycle grid
        ``theta_k = k * cycle_angle / N`` (end point excluded).
    omega_journal, omega_bearing : array_like, broadcastable to (..., N) [rad/s]
        Journal and bearing angular velocities in the frame of the loads (last axis N or 1).
    speed : array_like, shape (...) [rad/s]
        Crank angular speed (> 0); converts crank angle to time.
    diameter : array_like, shape (...) [m]
        Journal diameter.
    length : array_like, shape (...) [m]
        Effective bearing length (grooves/chamfers excluded; with ``full_groove`` both lands).
    clearance : array_like, shape (...) [m]
        Radial clearance (> 0, < 0.05 D).
    viscosity : array_like, shape (...) [Pa*s]
        Effective dynamic viscosity.
    model : {"closed_form", "exact", "exact_table", "butenschoen", "reynolds_map", "reynolds"}
        Mobility model (:mod:`checker.calc.mobility`). ``"exact"`` is very slow (reference
        for a handful of bearings); ``"exact_table"`` is its fast interpolated version.
        ``"reynolds_map"``: finite-length Reynolds mobility map
        (:mod:`checker.calc.reynolds_map`, L/D 1/16..1); ``"reynolds"``: the same film solved
        by :func:`checker.calc.reynolds.mobility_reynolds` at every evaluation (reference for
        a few bearings; seconds per step).
    full_groove : array_like of bool, shape (...)
        Full circumferential central groove: two lands of ``length/2`` each carrying half the
        load.
    steps_per_cycle : int
        RK4 steps per cycle (``"butenschoen"``: at least one step per degree, each made of two
        ROS2 sub-steps; the stored orbit then has that many points).
    solver_grid : checker.calc.reynolds.Grid, optional
        Resolution of the Reynolds solver for ``model="reynolds"`` (direct solution at every
        evaluation; default grid).
    solver_groove : (theta_start, theta_end, half_width), optional
        ``model="reynolds"`` only: a zero-pressure groove fixed in the caller's frame (angles
        [rad] in that frame, half width over the radius); ``length`` is then the total width
        including the groove. For measuring what the effective-width model costs.
    tol : float [-]
        Periodicity tolerance on the eccentricity ratio (closure of the cycle).
    max_cycles : int
        Maximum number of cycles.
    stiff_limit : float [-]
        ``lambda * h`` above which a step is sub-stepped.
    max_substeps : int
        Maximum ROS2 sub-steps per step.
    peak_pressure : bool
        Also compute the peak short-bearing film pressure (adds about 0.1 s per 1000
        bearings); its crank angle is on the step grid.
    eps0_x, eps0_y : array_like, shape (...), optional [-]
        Initial eccentricity ratio at ``theta = 0`` (default centred journal).
    cycle_angle : float [rad]
        Cycle length, ``4 pi`` for four-stroke engines.
    collapse_h_min : float [m]
        Film-collapse flag threshold on ``h_min`` (see :data:`COLLAPSE_H_MIN`).
    share_orbits : bool
        Solve once the orbits that are another bearing's orbit shifted by whole steps (same
        bearing data, loads and whirl shifted in crank angle, e.g. the big ends of an in-line
        engine); the others are that orbit shifted. Their initial state is then the first
        bearing's.
    group : array_like of int, shape (...), optional
        Orbits of different groups are never shared (e.g. the variants of a batch, so that
        each variant's numbers are those of its own evaluation).
    squeeze_velocity : bool
        Also return the squeeze velocity along the orbit (``vs_x``, ``vs_y``).

    Returns
    -------
    OrbitResult
        Arrays with the batch shape ``(...)``; see :class:`OrbitResult`.

    Raises
    ------
    ValueError
        Non-positive geometry, speed or viscosity, non-finite loads, unknown model, B/D outside
        1/8..1 for ``"butenschoen"``.

    Notes
    -----
    Booker J.F. (1965), "Dynamically loaded journal bearings: mobility method of solution",
    J. Basic Eng. 87:537-546 (not read); ``omega_bar`` and frames derived here (module
    docstring). Rigid journal and bearing,
    isoviscous, short-bearing (or Butenschoen finite-length) pi-film, no feed holes or partial
    grooves. Short-bearing MOFT is optimistic at L/D > 0.25. Flags: ``collapse``
    when ``eps_max >= COLLAPSE_EPS`` or ``h_min < collapse_h_min`` (result kept, finite,
    ``>= c (1 - EPS_CAP)``),
    ``converged`` false after ``max_cycles``; never NaN.
    """
    if not (tol > 0.0):
        raise ValueError("tol must be > 0")
    if int(max_cycles) < 2:
        raise ValueError("max_cycles must be >= 2")
    prob = _Problem(load_x, load_y, omega_journal, omega_bearing, speed, diameter, length,
                    clearance, viscosity, model, full_groove, steps_per_cycle, cycle_angle,
                    solver_grid, solver_groove, share=share_orbits, group=group)
    n, size_all = prob.n, prob.full_size
    uniq, rpos, shift = prob.uniq, prob.rpos, prob.shift
    z = _prepare_eps0(eps0_x, eps0_y, prob)[uniq]
    size = prob.size
    gid = np.arange(size)
    out_zh = np.empty((n, size), dtype=complex)
    out_kh = np.empty((n, size), dtype=complex)
    out_iwb = np.empty((n, size), dtype=complex)
    out = {
        "err": np.full(size, np.inf),
        "conv": np.zeros(size, dtype=bool),
        "ncyc": np.zeros(size, dtype=int),
        "capped": np.zeros(size, dtype=bool),
        "stiffcap": np.zeros(size, dtype=bool),
    }
    bear_all = {k: v.copy() for k, v in prob.bear.items()}
    for cyc in range(1, int(max_cycles) + 1):
        z_start = z
        z, zh, kh, capped, stiff_cap = _run_cycle(prob, z, stiff_limit, max_substeps)
        err = np.abs(z - z_start)  # closure of the cycle
        done = err < tol
        last = cyc == int(max_cycles)
        fin = np.ones(z.size, dtype=bool) if last else done
        if gid.size == size and fin.all():  # every orbit ends in this cycle: no copies
            out_zh, out_kh, out_iwb = zh, kh, prob.arr["iwb"][0::2]
            out["err"], out["conv"] = err, done
            out["ncyc"] = np.full(size, cyc)
            out["capped"], out["stiffcap"] = capped, stiff_cap
            break
        if fin.any():
            g = gid[fin]
            out_zh[:, g] = zh[:, fin]
            out_kh[:, g] = kh[:, fin]
            out_iwb[:, g] = prob.arr["iwb"][0::2][:, fin]
            out["err"][g] = err[fin]
            out["conv"][g] = done[fin]
            out["ncyc"][g] = cyc
            out["capped"][g] = capped[fin]
            out["stiffcap"][g] = stiff_cap[fin]
        if last or fin.all():
            break
        keep = ~fin
        if fin.any():
            prob.take(keep)
            gid, z = gid[keep], z[keep]

    eps_max, pos, zmax = _hermite_max(out_zh, out_kh, prob.h)
    p_max = theta_p = None
    if peak_pressure:
        pm, jp = _peak_pressure(out_zh, out_kh, out_iwb, bear_all)
    vs = None
    if squeeze_velocity:
        vs = (out_kh - out_iwb * out_zh) * bear_all["speed"]
    zt = out_zh.T  # (orbits, steps)
    vst = None if vs is None else vs.T
    if uniq.size < size_all:  # shared orbits: the solved orbit shifted by whole steps
        eps_max, zmax = eps_max[rpos], zmax[rpos]
        pos = (pos[rpos] + shift) % n
        out = {k: v[rpos] for k, v in out.items()}
        cols = (np.arange(n)[None, :] - shift[:, None]) % n  # gathered in output order
        zt = zt[rpos[:, None], cols]
        if vs is not None:
            vst = vst[rpos[:, None], cols]
        if peak_pressure:
            pm, jp = pm[rpos], (jp[rpos] + shift) % n
        size = size_all
    if peak_pressure:
        p_max = pm.reshape(prob.shape)
        theta_p = (jp * prob.h).reshape(prob.shape)
    cl = np.broadcast_to(np.asarray(clearance, dtype=float), prob.shape).reshape(-1)
    h_min = cl * (1.0 - eps_max)
    collapse = (eps_max >= COLLAPSE_EPS) | out["capped"] | (h_min < collapse_h_min)
    msg = np.full(size, "", dtype=object)
    for i in np.flatnonzero(collapse | ~out["conv"] | out["stiffcap"]):
        parts = []
        if collapse[i]:
            parts.append(
                f"film collapse: h_min = {h_min[i] * 1e9:.3g} nm (eps_max = {eps_max[i]:.6f}; "
                f"limits h_min >= {collapse_h_min * 1e9:.3g} nm, eps_max < {COLLAPSE_EPS})"
                + ("; eccentricity clamped at EPS_CAP" if out["capped"][i] else "")
            )
        if out["stiffcap"][i]:
            parts.append(f"stiff beyond {max_substeps} sub-steps per step (accuracy reduced)")
        if not out["conv"][i]:
            parts.append(
                f"orbit not periodic after {out['ncyc'][i]} cycles (change "
                f"{out['err'][i]:.2e} > tol {tol:.1e})"
            )
        msg[i] = "; ".join(parts)
    shp = prob.shape

    def part(a):  # one contiguous copy of a real or imaginary part, batch shape + (n,)
        return np.ascontiguousarray(a).reshape(shp + (n,))

    return OrbitResult(
        h_min=h_min.reshape(shp),
        theta_h_min=(pos * prob.h).reshape(shp),
        eps_max=eps_max.reshape(shp),
        phi_h_min=np.angle(zmax).reshape(shp),
        theta=np.arange(n) * prob.h,
        eps_x=part(zt.real),
        eps_y=part(zt.imag),
        p_max=p_max,
        theta_p_max=theta_p,
        converged=out["conv"].reshape(shp),
        collapse=collapse.reshape(shp),
        n_cycles=out["ncyc"].reshape(shp),
        periodic_error=out["err"].reshape(shp),
        message=msg.reshape(shp),
        model=model,
        steps_per_cycle=n,
        vs_x=None if vs is None else part(vst.real),
        vs_y=None if vs is None else part(vst.imag),
    )


def integrate_orbit(
    load_x: ArrayLike,
    load_y: ArrayLike,
    omega_journal: ArrayLike,
    omega_bearing: ArrayLike,
    speed: ArrayLike,
    diameter: ArrayLike,
    length: ArrayLike,
    clearance: ArrayLike,
    viscosity: ArrayLike,
    *,
    n_cycles: int = 1,
    model: str = "closed_form",
    full_groove: ArrayLike = False,
    steps_per_cycle: int = DEFAULT_STEPS_PER_CYCLE,
    stiff_limit: float = DEFAULT_STIFF_LIMIT,
    max_substeps: int = DEFAULT_MAX_SUBSTEPS,
    eps0_x: ArrayLike | None = None,
    eps0_y: ArrayLike | None = None,
    cycle_angle: float = 4.0 * np.pi,
    solver_grid=None,
    solver_groove=None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Transient orbit over a fixed number of cycles (no periodicity iteration).

    Same equation, inputs and integrator as :func:`solve_orbit`.

    Parameters
    ----------
    load_x, load_y, omega_journal, omega_bearing, speed, diameter, length, clearance, \
viscosity, model, full_groove, steps_per_cycle, stiff_limit, max_substeps, eps0_x, eps0_y, \
cycle_angle, solver_grid, solver_groove
        As in :func:`solve_orbit`.
    n_cycles : int
        Number of cycles to integrate.

    Returns
    -------
    theta : numpy.ndarray, shape (n_cycles * steps_per_cycle + 1,) [rad]
        Crank angle from the start (``0 .. n_cycles * cycle_angle``, end point included).
    eps_x, eps_y : numpy.ndarray, shape (...) + (n_cycles * steps_per_cycle + 1,) [-]
        Eccentricity ratio (clamped at ``EPS_CAP``).

    Notes
    -----
    See :func:`solve_orbit`.
    """
    if int(n_cycles) < 1:
        raise ValueError("n_cycles must be >= 1")
    prob = _Problem(load_x, load_y, omega_journal, omega_bearing, speed, diameter, length,
                    clearance, viscosity, model, full_groove, steps_per_cycle, cycle_angle,
                    solver_grid, solver_groove)
    z = _prepare_eps0(eps0_x, eps0_y, prob)
    hist = []
    for _ in range(int(n_cycles)):
        z, zh, _, _, _ = _run_cycle(prob, z, stiff_limit, max_substeps)
        hist.append(zh)
    hist.append(z[None, :])
    zz = np.concatenate(hist, axis=0).T.reshape(prob.shape + (-1,))
    theta = np.arange(zz.shape[-1]) * prob.h
    return theta, zz.real.copy(), zz.imag.copy()
