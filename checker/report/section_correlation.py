"""The correlation section of ``checker correlate``: measured and predicted order tracks
overlaid with the fitted model, the resonant peaks side by side, the synthesis, the
irregularity at the lowest speed and the calibration. Formatting only: every number comes from
:mod:`checker.correlation`."""

from __future__ import annotations

import base64
import datetime as _dt
import hashlib
import math
from pathlib import Path
from typing import Any

import numpy as np

from .. import __version__
from ..correlation import Correlation
from ..plumbing.resources import templates_dir

RPM = 30.0 / math.pi
DEG = 180.0 / math.pi
PANELS_PER_FIGURE = 12
"""Order panels per figure (3 columns)."""


def _src(png) -> str:
    return "data:image/jpeg;base64," + base64.b64encode(bytes(png)).decode("ascii")


def _track_figures(c: Correlation) -> list[dict[str, Any]]:
    """Per order: measured points, predicted (workbook values) and fitted curves."""
    from .plots import figure, legend_below, to_image

    s = c.setup
    x_m, x_g = c.speeds * RPM, c.grid * RPM
    panels = [(f"order {o:g}", c.measured[:, j], np.abs(c.predicted[:, j]),
               None if c.fitted is None else np.abs(c.fitted[:, j]))
              for j, o in enumerate(c.orders)]
    panels.append(("synthesis", c.synthesis_measured, c.synthesis_predicted,
                   c.synthesis_fitted))
    out = []
    for k0 in range(0, len(panels), PANELS_PER_FIGURE):
        chunk = panels[k0: k0 + PANELS_PER_FIGURE]
        n = len(chunk)
        cols = min(3, n)
        rows = -(-n // cols)
        fig, axes = figure(170, 38 * rows + 12, nrows=rows, ncols=cols, squeeze=False,
                           legend_rows=1, hgap=11, wgap=15)
        for k, (title, meas, pred, fit) in enumerate(chunk):
            ax = axes[k // cols][k % cols]
            if meas is not None:
                ax.plot(x_m, np.asarray(meas) * DEG, "o", ms=2.8, color="k",
                        label="measured")
            ax.plot(x_g, pred * DEG, "--", color="C0", lw=1.0, label="predicted (workbook)")
            if fit is not None:
                ax.plot(x_g, fit * DEG, "-", color="C3", lw=1.2, label="fitted model")
            ax.set_title(title, fontsize=8)
            if k % cols == 0:
                ax.set_ylabel("amplitude [deg]")
            if k // cols == rows - 1 or k + cols >= n:
                ax.set_xlabel("speed [rpm]")
        for k in range(n, rows * cols):
            axes[k // cols][k % cols].set_visible(False)
        legend_below(fig, axes=[axes[0][0], axes[(n - 1) // cols][(n - 1) % cols]])
        out.append({"src": _src(to_image(fig)),
                    "caption": f"{s.station_name}, {c.measurement.load} load: measured order"
                    " amplitudes (0-to-peak) and the synthesis (half peak-to-peak) against"
                    " the model with the workbook's values (dashed) and with the fitted"
                    " values (solid)."})
    return out


def _f(x: float | None, fmt: str = ".3g", scale: float = 1.0) -> str:
    return "-" if x is None or not np.isfinite(x) else format(x * scale, fmt)


def _pct(x: float | None) -> str:
    return "-" if x is None else f"{x * 100:+.1f} %"


def _rpm(x: float | None) -> str:
    return "-" if x is None else f"{x * RPM:.0f}"


def _drpm(x: float | None) -> str:
    return "-" if x is None else f"{x * RPM:+.0f}"


def _value(v: float, unit: str) -> str:
    """``0.1021``, ``27 530 N m/rad`` (4 significant digits, thousands spaced)."""
    if not np.isfinite(v):
        return "-"
    if abs(v) >= 1e4:
        text = f"{float(f'{v:.4g}'):,.0f}".replace(",", " ")
    else:
        text = f"{v:.4g}"
    return text + (f" {unit.replace('*', ' ')}" if unit else "")


def section_context(c: Correlation) -> dict[str, Any]:
    """Everything the template prints (strings), and the figures."""
    m, s = c.measurement, c.setup
    fitted = c.fit is not None
    peaks = [{
        "order": f"{r['order']:g}",
        "m": f"{_rpm(r['speed_measured'])} rpm, {_f(r['amplitude_measured'], '.4f', DEG)}°"
        if r["speed_measured"] is not None else "no peak",
        "p": f"{_rpm(r['speed_predicted'])} rpm, {_f(r['amplitude_predicted'], '.4f', DEG)}°"
        if r["speed_predicted"] is not None else "no peak",
        "dp": f"{_drpm(r['speed_difference_predicted'])} rpm,"
              f" {_pct(r['amplitude_difference_predicted'])}",
        "f": (f"{_rpm(r.get('speed_fitted'))} rpm, {_f(r.get('amplitude_fitted'), '.4f', DEG)}°"
              if r.get("speed_fitted") is not None else "no peak") if fitted else "",
        "df": f"{_drpm(r.get('speed_difference_fitted'))} rpm,"
              f" {_pct(r.get('amplitude_difference_fitted'))}" if fitted else ""}
        for r in c.peaks]
    ir = c.irregularity
    irr = {"speed": _rpm(ir["speed"]), "how": ir["how"],
           "measured": _f(ir["measured"], ".3f", 100),
           "predicted": _f(ir["predicted"], ".3f", 100),
           "fitted": _f(ir.get("fitted"), ".3f", 100)}
    params = []
    if fitted:
        for p in c.fit.parameters:
            ci = (f"{_value(p.low95, p.unit)} to {_value(p.high95, p.unit)}" if p.determined
                  else "not determined by the measurement")
            params.append({"label": p.label, "start": _value(p.start, p.unit),
                           "fitted": _value(p.value, p.unit), "factor": f"{p.factor:.4g}",
                           "ci": ci + (" (at its bound)" if p.at_bound else ""),
                           "source": p.source, "cells": ", ".join(p.cells) or "-"})
    runs = [{"speed": f"{r.speed * RPM:.0f}", "cycles": r.cycles, "n": r.samples_per_cycle,
             "top": f"{r.highest_order:g}",
             "scatter": f"{np.max(r.scatter) / max(m.amplitude[i].max(), 1e-300) * 100:.2g} %",
             "leak": f"{np.max(r.leakage) / max(m.amplitude[i].max(), 1e-300) * 100:.2g} %"}
            for i, r in enumerate(m.runs)]
    return {
        "station": s.station_name, "station_asked": m.station, "load": m.load,
        "kind": m.kind, "file": m.source,
        "temperature": None if m.temperature is None else f"{m.temperature - 273.15:.0f} °C",
        "speeds": f"{m.speeds.min() * RPM:.0f} to {m.speeds.max() * RPM:.0f} rpm"
                  f" ({m.speeds.size} speeds)",
        "orders": ", ".join(f"{o:g}" for o in m.orders),
        "figures": _track_figures(c), "peaks": peaks, "fitted": fitted,
        "synthesis_how": c.synthesis_how, "irregularity": irr, "parameters": params,
        "fit": None if not fitted else {
            "points": c.fit.points, "evaluations": c.fit.evaluations,
            "before": f"{c.fit.rms_before * 100:.1f} %", "after": f"{c.fit.rms_after * 100:.1f} %",
            "max_before": f"{c.fit.max_before * 100:.1f} %",
            "max_after": f"{c.fit.max_after * 100:.1f} %"},
        "runs": runs,
        "notes": list(c.notes) + list(m.notes) + ([] if not fitted or c.fit.converged else [
            f"The fit did not converge ({c.fit.status}): the fitted values are the last"
            " iterate, not a minimum."]) + [
            f"{p.label}: at its bound (x{p.factor:.3g}); the measurement asks for a value"
            " outside the range the fit allows" for p in (c.fit.parameters if fitted else ())
            if p.at_bound],
    }


def render(c: Correlation, workbook: str, calibrated: str | None) -> tuple[str, bytes]:
    """(HTML, PDF bytes) of the correlation report."""
    from jinja2 import Environment, FileSystemLoader, StrictUndefined, select_autoescape
    from weasyprint import HTML

    engine = c.setup.engine
    ctx = {"title": "Correlation with measurement", "date": _dt.date.today().isoformat(),
           "version": __version__, "workbook": Path(workbook).name, "sha256": engine.sha256,
           "calibrated": calibrated,
           "css": (templates_dir() / "report.css").read_text(encoding="utf-8"),
           "c": section_context(c)}
    env = Environment(loader=FileSystemLoader(str(templates_dir())),
                      autoescape=select_autoescape(["html"]), undefined=StrictUndefined)
    html = env.get_template("correlation.html").render(**ctx)
    ident = hashlib.sha256(html.encode("utf-8")).hexdigest()[:32].encode()
    return html, HTML(string=html, base_url=str(templates_dir())).write_pdf(
        pdf_identifier=ident)
