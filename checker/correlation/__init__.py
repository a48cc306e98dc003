"""``checker correlate``: measured torsional vibration against the model, and its calibration.

The measurement (:mod:`~checker.correlation.measurement`: order tracks, or an angle-domain
signal analysed by :mod:`~checker.correlation.order_analysis`) is compared with the check's
torsional model evaluated at the measured speeds (:mod:`~checker.correlation.model`,
:mod:`~checker.correlation.compare`); the least-known parameters are fitted by bounded least
squares (:mod:`~checker.correlation.fit`) and written into a calibrated copy of the workbook
(:mod:`~checker.correlation.calibrated`). docs/correlation.md describes the formats and the
method with a worked example.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from .compare import Correlation, correlate
from .fit import FitResult, calibrate
from .measurement import Measurement, read_measurement
from .model import setup

__all__ = ["Correlation", "FitResult", "Measurement", "run", "to_dict"]


def run(workbook: str | Path, measured: str | Path, fit: bool = True,
        fit_excitation: bool = False, orders: list[float] | None = None,
        progress=None) -> Correlation:
    """Read both files, evaluate the model at the measured speeds, fit (unless ``fit`` is
    False) and compare. Raises :class:`checker.errors.InputErrors` for a bad file."""
    from ..description.engine import load_engine

    say = progress or (lambda _t: None)
    say(f"Reading {Path(measured).name}")
    meas = read_measurement(measured, orders)
    say(f"Reading {Path(workbook).name}")
    engine = load_engine(workbook)
    say("Evaluating the torsional model at the measured speeds")
    s = setup(engine, meas, fit_excitation=fit_excitation)
    result = None
    if fit and s.parameters:
        say("Fitting the damper and crank parameters (bounded least squares)")
        result = calibrate(s, meas)
    return correlate(s, meas, result)


def _num(x: Any, sig: int = 6) -> Any:
    if x is None:
        return None
    x = float(x)
    if not math.isfinite(x):
        return None
    return float(f"{x:.{sig}g}")


def _arr(a, scale: float = 1.0) -> list:
    return [_num(v * scale) for v in np.asarray(a, dtype=float).ravel()]


def _curves(c: Correlation, theta: np.ndarray, synthesis: np.ndarray) -> dict[str, Any]:
    """A model's curves on the fine grid: per order and synthesised [deg]."""
    return {"speeds_rpm": _arr(c.grid, RPM),
            "orders": {f"{o:g}": _arr(np.abs(theta[:, j]), DEG) for j, o in enumerate(c.orders)},
            "synthesis_deg": _arr(synthesis, DEG)}


RPM = 30.0 / math.pi
DEG = 180.0 / math.pi


def to_dict(c: Correlation, calibrated: str | None = None) -> dict[str, Any]:
    """The JSON output (stable keys; angles in deg, speeds in rpm, as labelled)."""
    m, s = c.measurement, c.setup
    meas: dict[str, Any] = {
        "file": m.source, "format": m.kind, "station": m.station,
        "model_station": s.station_name, "load": m.load,
        "damper_temperature_C": None if m.temperature is None else _num(m.temperature
                                                                         - 273.15),
        "speeds_rpm": _arr(m.speeds, RPM), "orders": _arr(m.orders), "notes": list(m.notes)}
    if m.runs:
        meas["order_analysis"] = {
            "cycle_deg": 720, "resolution_order": 0.5, "window": "rectangular over whole"
            " cycles (every half order on a bin)", "averaging": "complex, over the cycles",
            "runs": [{"speed_rpm": _num(r.speed * RPM), "cycles": r.cycles,
                      "samples_per_cycle": r.samples_per_cycle,
                      "highest_order": _num(r.highest_order),
                      "scatter_deg": _arr(r.scatter, DEG),
                      "leakage_deg": _arr(r.leakage, DEG)} for r in m.runs]}
    tracks = []
    for j, o in enumerate(c.orders):
        t = {"order": _num(o), "measured_deg": _arr(c.measured[:, j], DEG),
             "predicted_deg": _arr(np.abs(c.predicted[s.measured, j]), DEG)}
        if c.fitted is not None:
            t["fitted_deg"] = _arr(np.abs(c.fitted[s.measured, j]), DEG)
        tracks.append(t)
    syn = {"how": c.synthesis_how, "orders": _arr(c.synthesis_orders),
           "measured_deg": None if c.synthesis_measured is None
           else _arr(c.synthesis_measured, DEG),
           "predicted_deg": _arr(c.synthesis_predicted[s.measured], DEG)}
    if c.synthesis_fitted is not None:
        syn["fitted_deg"] = _arr(c.synthesis_fitted[s.measured], DEG)
    peaks = []
    for r in c.peaks:
        d = {}
        for k, v in r.items():
            if k == "order":
                d[k] = _num(v)
            elif k.startswith("speed"):
                d[k + "_rpm"] = _num(None if v is None else v * RPM)
            elif k.startswith("amplitude_difference"):
                d[k + "_percent"] = _num(None if v is None else v * 100)
            else:
                d[k + "_deg"] = _num(None if v is None else v * DEG)
        peaks.append(d)
    ci = c.irregularity
    irr = {"speed_rpm": _num(ci["speed"] * RPM), "how": ci["how"]}
    for k in ("measured", "predicted", "fitted", "predicted_measured_orders"):
        if k in ci:
            irr[k + "_percent"] = _num(None if ci[k] is None else ci[k] * 100)
    out: dict[str, Any] = {
        "measurement": meas, "tracks": tracks, "synthesis": syn, "peaks": peaks,
        "irregularity_lowest_speed": irr, "notes": list(c.notes),
        "predicted_curves": _curves(c, c.predicted, c.synthesis_predicted)}
    if c.fit is not None:
        f = c.fit
        out["calibration"] = {
            "method": "bounded least squares (trust-region reflective) on ln amplitude at"
                      " the resonant peaks and flanks; confidence from the Jacobian",
            "points": f.points, "evaluations": f.evaluations, "converged": f.converged,
            "solver_message": f.status,
            "residual_rms_before_percent": _num(f.rms_before * 100),
            "residual_rms_after_percent": _num(f.rms_after * 100),
            "residual_max_before_percent": _num(f.max_before * 100),
            "residual_max_after_percent": _num(f.max_after * 100),
            "parameters": [{
                "name": p.key, "label": p.label, "unit": p.unit, "start": _num(p.start),
                "fitted": _num(p.value), "factor": _num(p.factor),
                "sigma_relative": _num(p.sigma), "low95": _num(p.low95),
                "high95": _num(p.high95), "determined": p.determined,
                "at_bound": p.at_bound, "cells": list(p.cells), "source": p.source}
                for p in f.parameters],
            "calibrated_workbook": calibrated}
        out["fitted_curves"] = _curves(c, c.fitted, c.synthesis_fitted)
    return out
