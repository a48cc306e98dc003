"""Measurement files for the correlation tests: order tracks from a (perturbed) model, and
angle-domain signals of known orders."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from checker.correlation import measurement as ms
from checker.correlation import model as md
from checker.description.engine import load_engine

RPM = np.pi / 30.0


def tracks_csv(path: Path, station: str, load: str, speeds_rpm, orders, amp_deg,
               phase_deg=None, temperature: str | None = None, units: bool = True,
               extra: dict | None = None) -> Path:
    """Write an order-track file (amplitudes in deg, optional phases in deg)."""
    lines = [f"# station: {station}", f"# load: {load}"]
    if temperature is not None:
        lines.append(f"# damper temperature: {temperature}")
    names = ["speed"] + [f"order {o:g}" for o in orders]
    unit = ["rpm"] + ["deg"] * len(orders)
    if phase_deg is not None:
        names += [f"order {o:g} phase" for o in orders]
        unit += ["deg"] * len(orders)
    lines.append(",".join(names))
    if units:
        lines.append(",".join(unit))
    for i, s in enumerate(speeds_rpm):
        row = [f"{s:g}"] + [f"{a:.7g}" for a in amp_deg[i]]
        if phase_deg is not None:
            row += [f"{p:.7g}" for p in phase_deg[i]]
        lines.append(",".join(row))
    for k, v in (extra or {}).items():
        lines.insert(0, f"# {k}: {v}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def perturbed_tracks(tmp: Path, workbook: Path, station: str, speeds_rpm, orders,
                     factors: dict[str, float], noise: float, seed: int = 1,
                     load: str = "full") -> tuple[Path, md.Setup]:
    """Tracks of the model with its parameters scaled by ``factors``, each amplitude with a
    relative Gaussian error of standard deviation ``noise``; the setup used."""
    placeholder = tracks_csv(tmp / "placeholder.csv", station, load, speeds_rpm, orders,
                             np.ones((len(speeds_rpm), len(orders))))
    eng = load_engine(workbook)
    s = md.setup(eng, ms.read_measurement(placeholder))
    theta = s.solve(factors, s.measured, s.order_index)
    rng = np.random.default_rng(seed)
    amp = np.abs(theta) * (1.0 + noise * rng.standard_normal(theta.shape))
    return tracks_csv(tmp / "measured.csv", station, load, speeds_rpm, orders,
                      np.degrees(amp)), s


def signal_csv(path: Path, station: str, runs: list[dict], column: str = "vibratory angle",
               unit: str = "deg", step_deg: float = 2.0) -> Path:
    """An angle-domain file: per run ``{"rpm", "cycles", "signal": f(theta_rad) -> value}``."""
    lines = [f"# station: {station}", "# load: full",
             f"run speed,crank angle,{column}", f"rpm,deg,{unit}"]
    for r in runs:
        n = int(round(720.0 / step_deg)) * r["cycles"] + r.get("extra", 0)
        th = np.arange(n) * step_deg + r.get("start", 0.0)
        x = r["signal"](np.radians(th))
        lines += [f"{r['rpm']:g},{a:.6f},{v:.9g}" for a, v in zip(th, x)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path
