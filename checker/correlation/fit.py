"""Calibration: the least-known parameters fitted to the measured order tracks.

Residuals: ``r_i = ln |Theta_pred,i(p)| - ln A_meas,i`` at every measured speed and order whose
measured amplitude is at least :data:`PEAK_FLOOR` of that order's largest (an order the firing
order cancels in the model, :data:`CANCELLED`, left out): the resonant peaks and their
flanks, where the damper's and the crank's damping and the damper's stiffness show (a peak's
height and its speed); relative residuals weigh a 3 % error alike on every order.
The parameters are the logarithms of factors on the starting values, bounded by
:data:`checker.correlation.model.BOUNDS`, solved by a trust-region reflective least-squares
method (``scipy.optimize.least_squares``, Branch, Coleman & Li 1999). Each evaluation
re-solves only the forced response (:meth:`checker.correlation.model.Setup.solve`).

Confidence: the linearised covariance at the solution, ``cov = s^2 (J^T J)^-1`` with
``s^2 = sum r^2 / (m - p)`` (Bates & Watts 1988, ch. 2), gives each factor's standard error and
a 95 % interval with Student's t for ``m - p`` degrees of freedom; a parameter the residuals
hardly move (a singular ``J^T J``) is reported as not determined. Model updating of this kind
is described by Friswell & Mottershead 1995 (ch. 7); Bell 2013 (Ricardo) calls the
correlation of the concept model with the measured torsional vibration "a vital step".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, InputErrors
from .measurement import Measurement
from .model import Setup

PEAK_FLOOR = 0.1
"""Points fitted: measured amplitude at least this fraction of the order's largest."""
DETERMINED = 1.0
"""A factor whose standard error (of its logarithm) exceeds this is reported as not
determined by the measurement."""


@dataclass(frozen=True)
class FittedParameter:
    key: str
    label: str
    unit: str
    start: float  # SI
    value: float  # SI
    factor: float  # value / start
    sigma: float  # standard error of ln(factor) [-] (inf: not determined)
    low95: float  # 95 % interval of the value (SI)
    high95: float
    at_bound: bool
    cells: tuple[str, ...]
    source: str

    @property
    def determined(self) -> bool:
        return bool(np.isfinite(self.sigma) and self.sigma <= DETERMINED)


@dataclass(frozen=True)
class FitResult:
    parameters: tuple[FittedParameter, ...]
    points: int  # residuals
    rms_before: float  # rms of the log residuals before [-] (about the relative error)
    rms_after: float
    max_before: float  # largest |residual|
    max_after: float
    evaluations: int  # forced-response solves (the residuals' and the Jacobians')
    status: str  # the solver's message
    converged: bool  # the solver met a tolerance (not its evaluation limit)
    correlation: np.ndarray  # (p, p) correlation of the fitted log factors
    mask: np.ndarray  # (S, O) bool: the points fitted
    cancelled: tuple[float, ...] = ()  # orders the model cancels, left out

    def factors(self) -> dict[str, float]:
        return {p.key: p.factor for p in self.parameters}


CANCELLED = 1e-6
"""An order whose predicted amplitude stays below this fraction of the largest order's is one
the firing order cancels (a V8's 6th): its measured amplitude is noise, not fitted."""


def fit_mask(meas: Measurement) -> np.ndarray:
    """(S, O) bool: the measured points at the resonances (the fit's points)."""
    a = meas.amplitude
    top = a.max(axis=0, keepdims=True)
    return (a >= PEAK_FLOOR * top) & (a > 0)


def cancelled_orders(predicted: np.ndarray) -> np.ndarray:
    """(O,) bool: orders whose predicted amplitude (S, O) is round-off (:data:`CANCELLED`)."""
    p = np.abs(predicted).max(axis=0)
    return p < CANCELLED * p.max()


def calibrate(s: Setup, meas: Measurement) -> FitResult:
    """Fit the setup's parameters to the measurement (bounded least squares)."""
    from scipy.optimize import least_squares
    from scipy.special import stdtrit

    keys = [p.key for p in s.parameters]
    rows = s.measured
    cols = s.order_index
    cancelled = cancelled_orders(s.solve(None, rows, cols))
    mask = fit_mask(meas) & ~cancelled[None, :]
    if int(mask.sum()) <= len(keys):
        raise InputErrors([InputError(meas.source, f"{int(mask.sum())} measured points at the"
                                      " resonances (amplitudes of at least"
                                      f" {PEAK_FLOOR * 100:.0f} % of their order's largest):"
                                      f" too few to fit {len(keys)} parameters; give more"
                                      " speeds or orders, or compare only (--no-fit)")],
                          source=meas.source)
    target = np.log(meas.amplitude[mask])

    def residual(x: np.ndarray) -> np.ndarray:
        f = dict(zip(keys, np.exp(x)))
        amp = np.abs(s.solve(f, rows, cols))
        return np.log(np.maximum(amp[mask], 1e-300)) - target

    r0 = residual(np.zeros(len(keys)))
    lo = np.log([p.bounds[0] for p in s.parameters])
    hi = np.log([p.bounds[1] for p in s.parameters])
    sol = least_squares(residual, np.zeros(len(keys)), bounds=(lo, hi), method="trf",
                        x_scale=1.0, diff_step=1e-6, xtol=1e-10, ftol=1e-12, gtol=1e-12,
                        max_nfev=200)
    m, p = target.size, len(keys)
    dof = max(m - p, 1)
    s2 = float(np.sum(sol.fun**2)) / dof
    jtj = sol.jac.T @ sol.jac
    cov = s2 * np.linalg.pinv(jtj, rcond=1e-12)
    sig = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    ev = np.linalg.eigvalsh(jtj) if p else np.zeros(0)
    if p and ev.min() <= 1e-12 * max(ev.max(), 1e-300):  # a direction the residuals ignore
        null = np.abs(np.linalg.eigh(jtj)[1][:, 0]) > 0.1
        sig = np.where(null, np.inf, sig)
    tq = float(stdtrit(dof, 0.975))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.sqrt(np.outer(np.diag(cov), np.diag(cov)))
    out = []
    for i, prm in enumerate(s.parameters):
        x = float(sol.x[i])
        at = bool(x <= lo[i] + 1e-6 or x >= hi[i] - 1e-6)
        out.append(FittedParameter(
            key=prm.key, label=prm.label, unit=prm.unit, start=prm.start,
            value=prm.start * np.exp(x), factor=float(np.exp(x)), sigma=float(sig[i]),
            low95=prm.start * float(np.exp(x - tq * sig[i])) if np.isfinite(sig[i]) else 0.0,
            high95=prm.start * float(np.exp(x + tq * sig[i])) if np.isfinite(sig[i])
            else float("inf"), at_bound=at, cells=prm.cells, source=prm.source))
    return FitResult(parameters=tuple(out), points=m,
                     rms_before=float(np.sqrt(np.mean(r0**2))),
                     rms_after=float(np.sqrt(np.mean(sol.fun**2))),
                     max_before=float(np.abs(r0).max()), max_after=float(np.abs(sol.fun).max()),
                     evaluations=int(sol.nfev + (sol.njev or 0) * len(keys)),
                     status=str(sol.message), converged=bool(sol.success),
                     correlation=np.nan_to_num(corr), mask=mask,
                     cancelled=tuple(float(o) for o in meas.orders[cancelled]))
