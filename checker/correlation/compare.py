"""Measured against predicted: order tracks, resonant peaks, synthesis and irregularity.

Every number is the model's (:mod:`checker.correlation.model`) or the measurement's; this
module lines them up: the tracks of each order at the measured speeds and on a fine grid
(predicted with the workbook's values, and with the fitted ones), each resonance's peak speed
and amplitude side by side with the differences, the synthesis of all orders (half
peak-to-peak, :func:`checker.calc.torsional.half_peak_to_peak`) and the cyclic irregularity
at the lowest measured speed, ``(w_max - w_min) / w_mean``: twice the half range of
``sum Re{j n Theta_n exp(j n theta)}`` (the speed fluctuation over the mean speed).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..calc import torsional as tv
from .fit import FitResult, cancelled_orders
from .measurement import Measurement
from .model import Setup

PEAK_FLOOR = 0.3
"""A local maximum of a track is a resonant peak when at least this fraction of the order's
largest amplitude (smaller wiggles are noise or the flank of another mode)."""
MATCH = 0.15
"""A predicted peak answers a measured one when its speed is within this fraction."""


@dataclass(frozen=True)
class Correlation:
    """The comparison of one measurement with the model (SI)."""

    measurement: Measurement
    setup: Setup
    speeds: np.ndarray  # (S,) measured speeds [rad/s]
    grid: np.ndarray  # (G,) speeds of the curves [rad/s]
    orders: np.ndarray  # (O,) measured orders
    measured: np.ndarray  # (S, O) [rad]
    predicted: np.ndarray  # (G, O) complex [rad] (workbook values)
    fitted: np.ndarray | None  # (G, O) complex [rad] (fitted values)
    synthesis_orders: np.ndarray  # orders of the synthesis
    synthesis_measured: np.ndarray | None  # (S,) [rad]
    synthesis_predicted: np.ndarray  # (G,) [rad]
    synthesis_fitted: np.ndarray | None  # (G,) [rad]
    synthesis_how: str
    peaks: tuple[dict, ...]
    irregularity: dict
    fit: FitResult | None
    notes: tuple[str, ...]


def find_peaks(speeds: np.ndarray, amp: np.ndarray, floor: float = PEAK_FLOOR
               ) -> list[tuple[float, float]]:
    """Interior local maxima of a track at least ``floor`` of its largest value, each refined
    by the parabola through it and its neighbours: [(speed, amplitude)]."""
    a = np.asarray(amp, dtype=float)
    x = np.asarray(speeds, dtype=float)
    if a.size < 3 or not np.isfinite(a).all() or a.max() <= 0:
        return []
    out = []
    for i in range(1, a.size - 1):
        if a[i] > a[i - 1] and a[i] >= a[i + 1] and a[i] >= floor * a.max():
            x0, x1, x2 = x[i - 1: i + 2]
            y0, y1, y2 = a[i - 1: i + 2]
            den = (x0 - x1) * (x0 - x2) * (x1 - x2)
            ca = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / den
            cb = (x2**2 * (y0 - y1) + x1**2 * (y2 - y0) + x0**2 * (y1 - y2)) / den
            if ca < 0:
                xv = -cb / (2 * ca)
                xv = float(np.clip(xv, x0, x2))
                yv = float(y1 + (ca * (xv**2 - x1**2) + cb * (xv - x1)))
                out.append((xv, max(yv, float(y1))))
            else:
                out.append((float(x1), float(y1)))
    return out


def _nearest(peaks: list[tuple[float, float]], speed: float) -> tuple[float, float] | None:
    near = [p for p in peaks if abs(p[0] - speed) <= MATCH * speed]
    return min(near, key=lambda p: abs(p[0] - speed)) if near else None


def _peak_rows(meas: Measurement, pred: np.ndarray, fitted: np.ndarray | None
               ) -> list[dict]:
    """Peaks of the measured and the model's tracks, both at the measured speeds and refined
    alike (a sparse speed step lowers a sharp peak for both: like is compared with like)."""
    rows = []
    x = meas.speeds
    gone = cancelled_orders(pred)  # round-off wiggles of a cancelled order are no peaks
    for j, o in enumerate(meas.orders):
        mp = find_peaks(x, meas.amplitude[:, j])
        pp = [] if gone[j] else find_peaks(x, np.abs(pred[:, j]))
        fp = find_peaks(x, np.abs(fitted[:, j])) if fitted is not None and not gone[j] else []
        used = set()
        for s, a in mp:
            p = _nearest(pp, s)
            if p is not None:
                used.add(p)
            f = _nearest(fp, s)
            rows.append(_row(o, (s, a), p, f, fitted is not None))
        for p in pp:
            if p not in used and meas.speeds.min() < p[0] < meas.speeds.max() and \
                    p[1] >= PEAK_FLOOR * np.abs(pred[:, j]).max():
                rows.append(_row(o, None, p, _nearest(fp, p[0]), fitted is not None))
    rows.sort(key=lambda r: (r["order"], r["speed_measured"] if r["speed_measured"]
                             is not None else r["speed_predicted"]))
    return rows


Peak = tuple[float, float]  # (speed [rad/s], amplitude [rad])


def _row(order: float, m: Peak | None, p: Peak | None, f: Peak | None, with_fit: bool
         ) -> dict:
    """One line of the peak table: measured, predicted (and fitted) with the differences."""

    def diff(x: float | None, ref: float | None, rel: bool) -> float | None:
        if x is None or ref is None:
            return None
        return (x - ref) / ref if rel else x - ref

    r = {"order": float(order),
         "speed_measured": None if m is None else m[0],
         "amplitude_measured": None if m is None else m[1],
         "speed_predicted": None if p is None else p[0],
         "amplitude_predicted": None if p is None else p[1]}
    r["speed_difference_predicted"] = diff(r["speed_predicted"], r["speed_measured"], False)
    r["amplitude_difference_predicted"] = diff(r["amplitude_predicted"],
                                               r["amplitude_measured"], True)
    if with_fit:
        r["speed_fitted"] = None if f is None else f[0]
        r["amplitude_fitted"] = None if f is None else f[1]
        r["speed_difference_fitted"] = diff(r["speed_fitted"], r["speed_measured"], False)
        r["amplitude_difference_fitted"] = diff(r["amplitude_fitted"], r["amplitude_measured"],
                                                True)
    return r


def irregularity(orders: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Cyclic irregularity ``(w_max - w_min) / w_mean`` from the complex angle coefficients
    (..., O) [rad]: the speed fluctuation is ``sum Re{j n w Theta_n e^{j n theta}}``, so the
    irregularity is twice the half range of ``sum Re{j n Theta_n e^{j n theta}}``."""
    return 2.0 * tv.half_peak_to_peak(orders, 1j * np.asarray(orders) * theta)


def correlate(s: Setup, meas: Measurement, fit: FitResult | None) -> Correlation:
    """Line up the measurement, the prediction and (with a fit) the fitted model."""
    all_theta = s.solve()  # (G, O_all)
    fit_theta = s.solve(fit.factors()) if fit is not None else None
    oi = s.order_index
    pred, fitted = all_theta[:, oi], None if fit_theta is None else fit_theta[:, oi]
    notes = list(s.notes)
    if fit is not None and fit.cancelled:
        notes.append(f"Order {', '.join(f'{o:g}' for o in fit.cancelled)} left out of the fit:"
                     " the firing order cancels it in the model (its measured amplitude is"
                     " what the model cannot give: a cylinder's imbalance, noise).")
    # synthesis: the instrument's total against all model orders; else the measured orders
    if meas.total is not None:
        syn_o, syn_m = s.orders, meas.total
        how = ("measured: the file's 'total' column; predicted: all orders 0.5 to"
               f" {s.orders.max():g} synthesised (half peak-to-peak)")
        cols = np.arange(s.orders.size)
    elif meas.coeffs is not None:
        syn_o, cols = meas.orders, oi
        syn_m = tv.half_peak_to_peak(meas.orders, meas.coeffs)
        how = (f"the measured orders ({_orders_text(meas.orders)}) synthesised with their"
               " phases, measured and predicted alike (half peak-to-peak)")
    else:
        syn_o, cols, syn_m = s.orders, np.arange(s.orders.size), None
        how = ("predicted: all orders synthesised; the measurement gives neither phases nor a"
               " 'total' column, so its synthesis is not known")
    syn_p = tv.half_peak_to_peak(syn_o, all_theta[:, cols])
    syn_f = None if fit_theta is None else tv.half_peak_to_peak(syn_o, fit_theta[:, cols])
    # irregularity at the lowest measured speed
    k = int(s.measured[0])
    irr = {"speed": float(meas.speeds[0]),
           "predicted": float(irregularity(s.orders, all_theta[k])),
           "fitted": None if fit_theta is None else float(irregularity(s.orders,
                                                                        fit_theta[k])),
           "measured": None, "how": ""}
    if meas.irregularity is not None and np.isfinite(meas.irregularity[0]):
        irr["measured"] = float(meas.irregularity[0])
        irr["how"] = ("measured: " + ("(max - min) / mean of the cycle-averaged speed signal"
                                      if meas.kind != "order tracks" else
                                      "the file's 'irregularity' column")
                      + f"; predicted: all orders 0.5 to {s.orders.max():g} of the model")
    elif meas.coeffs is not None:
        irr["measured"] = float(irregularity(meas.orders, meas.coeffs[0]))
        irr["predicted_measured_orders"] = float(irregularity(meas.orders, pred[k]))
        irr["how"] = (f"measured: the measured orders ({_orders_text(meas.orders)}) with their"
                      f" phases; predicted: all orders 0.5 to {s.orders.max():g} (and the"
                      " measured orders only)")
    else:
        irr["how"] = ("not measured: the order tracks give no phases and no 'irregularity'"
                      " column; predicted: all orders of the model")
    return Correlation(
        measurement=meas, setup=s, speeds=np.asarray(meas.speeds, float), grid=s.speeds,
        orders=meas.orders, measured=meas.amplitude, predicted=pred, fitted=fitted,
        synthesis_orders=syn_o, synthesis_measured=syn_m, synthesis_predicted=syn_p,
        synthesis_fitted=syn_f, synthesis_how=how,
        peaks=tuple(_peak_rows(meas, pred[s.measured], None if fitted is None
                               else fitted[s.measured])), irregularity=irr, fit=fit,
        notes=tuple(notes))


def _orders_text(orders: np.ndarray) -> str:
    o = [f"{x:g}" for x in orders]
    return ", ".join(o) if len(o) <= 6 else f"{o[0]} to {o[-1]}, {len(o)} orders"
