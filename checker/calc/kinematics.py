"""Crank-slider kinematics with cylinder (crank-axis) offset and piston-pin offset.

Geometry and sign convention
----------------------------
Each cylinder is described in its own plane frame ``(t, c)``:

* ``c`` is the cylinder axis, pointing from the crank axis toward the cylinder head;
* ``t`` is perpendicular to it, pointing the way the crank pin moves when it passes the top of
  its circle (i.e. ``t`` is ``c`` turned by +90 deg in the direction of crank rotation).

The crank pin sits at ``B = r (sin(phi), cos(phi))`` in ``(t, c)``; ``phi`` is the cylinder's
crank angle, measured from the line through the crank axis parallel to the cylinder axis, positive
in the direction of rotation. The piston pin (small end) moves on the line ``t = e`` with the
**total offset**

    e = cylinder_offset - pin_offset

* ``cylinder_offset`` [m]: position of the cylinder (bore) axis relative to the crank axis,
  measured along ``+t`` (Agostini's ``z_o,c``);
* ``pin_offset`` [m]: offset of the piston-pin axis from the bore axis **towards the major thrust
  side positive** (the workbook's documented convention, "towards the thrust side positive").

The major thrust side is the side of the liner the piston bears on during expansion: the gas
force pushes the piston toward the crank, the rod then leans with its big end on the ``+t``
side (``beta > 0``), its compression pushes the piston toward ``-t`` and the liner reacts
toward ``+t``, so the piston presses on the ``-t`` side (``CylinderLoads.side_force < 0`` in
:mod:`checker.calc.crank_forces`). A pin offset towards the major thrust side therefore moves the
pin to ``-t``: Agostini's ``z_o,wp = -pin_offset``. Because ``t`` is defined by the direction of
rotation, this holds for either rotation (clockwise seen from the front with the head up: ``+t``
points right and the major thrust side is on the left). Such an offset (Agostini 2019, "Methods to
decrease slap": the pin "moved towards the major thrust side") brings the piston's crossover from
the minor to the major thrust side (``beta = 0``, ``sin(phi) = e/r``) ahead of the top dead centre,
which itself comes early: ``phi_TDC = asin(e/(l + r)) < 0``. Only ``e`` enters the kinematics and
the forces on the crank train. With ``lam = r/l`` and ``delta = e/l`` (Agostini 2019,
*Powertrain Components Design*, Politecnico di Torino, ch. 1 "Offset layout"):

    sin(beta) = lam sin(phi) - delta                       (con-rod obliquity beta)
    y_P       = r cos(phi) + l cos(beta)                   (piston pin along c)
    x         = sqrt((l + r)^2 - e^2) - y_P                (displacement from TDC, >= 0)

``x`` is the piston displacement from its top dead centre, positive toward the crank, so the
cylinder volume is ``V_c + A x`` and the gas torque is ``(p - p_cc) A dx/dphi``. ``beta`` is
positive when the crank pin lies on the ``+t`` side of the piston pin (first half-turn after TDC
for ``e = 0``). The rod direction from big end to small end is ``(-sin(beta), cos(beta))``; its
absolute angular velocity, positive in the direction of crank rotation, is
``rod_omega = -dbeta/dt`` (what a big-end mobility solution needs for the bearing speed).

With an offset the piston's dead centres are not at ``phi = 0, pi`` but at
``phi_TDC = asin(e/(l + r))`` and ``phi_BDC = pi + asin(e/(l - r))`` and the stroke is slightly
longer than ``2 r`` (:func:`dead_centres`). Crank angles in this package keep the geometric
reference ``phi = 0`` (pin on the line parallel to the bore through the crank axis); a measured
pressure trace referenced to the true TDC may be shifted by ``phi_TDC`` if that matters (-0.24 deg,
TDC before the reference, for the example engine's 0.8 mm pin offset towards the major thrust
side).

The crank speed ``omega`` is constant (no cyclic speed fluctuation).

References
----------
.. [1] M. Agostini, "Powertrain Components Design - Engine", course notes, Master Degree in
   Automotive Engineering, Politecnico di Torino, 2019 (A.Y. 2018-2019), ch. 1 "Offset layout",
   "Methods to decrease slap".
.. [2] J. B. Heywood, "Internal Combustion Engine Fundamentals", McGraw-Hill, 1988, eq. 2.5.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "DEFAULT_STEP",
    "DEFAULT_STEP_DEG",
    "FOUR_STROKE_CYCLE",
    "SliderKinematics",
    "cycle_grid",
    "dead_centres",
    "slider_kinematics",
]

#: Crank angle of one 4-stroke cycle [rad].
FOUR_STROKE_CYCLE = 4.0 * np.pi

#: Recommended crank-angle step [deg] for load sweeps. ``benchmarks/bench_loads.py`` (example I4,
#: 61 speeds x 2 load cases x 4 cylinders, synthesized traces) shows that a 1 deg grid reproduces
#: the peak specific loads of all big ends and mains of a 0.1 deg grid to within 0.08 % (worst
#: case, speed and bearing; 0.02 % for the envelope over speed) with the whole force sweep taking
#: ~0.05 s; 2 deg errs by up to 0.26 %, 4 deg by 0.85 % (under-sampled combustion peak), while
#: 0.5 deg gains < 0.07 % for twice the time. The error falls as step^2.
DEFAULT_STEP_DEG = 1.0

#: :data:`DEFAULT_STEP_DEG` in radians.
DEFAULT_STEP = float(np.deg2rad(DEFAULT_STEP_DEG))


class SliderKinematics(NamedTuple):
    """Kinematics of one crank-slider, arrays broadcast from ``theta`` and ``omega``.

    Attributes
    ----------
    x : numpy.ndarray [m]
        Piston (pin) displacement from top dead centre, positive toward the crank.
    dx_dtheta : numpy.ndarray [m/rad]
        ``dx/dphi``; the gas torque is ``(p - p_cc) A dx/dphi``.
    d2x_dtheta2 : numpy.ndarray [m/rad^2]
        ``d^2x/dphi^2``.
    velocity : numpy.ndarray [m/s]
        ``omega dx/dphi`` (positive moving toward the crank).
    acceleration : numpy.ndarray [m/s^2]
        ``omega^2 d^2x/dphi^2`` (positive toward the crank; constant ``omega``).
    beta : numpy.ndarray [rad]
        Con-rod obliquity, ``sin(beta) = (r sin(phi) - e)/l``.
    dbeta_dtheta : numpy.ndarray [-]
        ``dbeta/dphi``.
    d2beta_dtheta2 : numpy.ndarray [1/rad]
        ``d^2beta/dphi^2``.
    rod_omega : numpy.ndarray [rad/s]
        Absolute angular velocity of the con-rod, positive in the direction of crank rotation
        (``-omega dbeta/dphi``).
    rod_alpha : numpy.ndarray [rad/s^2]
        Absolute angular acceleration of the con-rod, same sign convention
        (``-omega^2 d^2beta/dphi^2``).
    """

    x: np.ndarray
    dx_dtheta: np.ndarray
    d2x_dtheta2: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    beta: np.ndarray
    dbeta_dtheta: np.ndarray
    d2beta_dtheta2: np.ndarray
    rod_omega: np.ndarray
    rod_alpha: np.ndarray


def _check_geometry(
    crank_radius: ArrayLike, rod_length: ArrayLike, offset: ArrayLike
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r = np.asarray(crank_radius, dtype=float)
    l = np.asarray(rod_length, dtype=float)
    e = np.asarray(offset, dtype=float)
    if not (np.all(np.isfinite(r)) and np.all(np.isfinite(l)) and np.all(np.isfinite(e))):
        raise ValueError("crank_radius, rod_length and offsets must be finite")
    if np.any(r <= 0):
        raise ValueError(f"crank_radius must be > 0 m, got {crank_radius!r}")
    if np.any(r + np.abs(e) >= l):
        raise ValueError(
            "crank_radius + |cylinder_offset - pin_offset| must be < rod_length "
            "(otherwise the con-rod cannot reach the piston pin at every crank angle)"
        )
    return r, l, e


def slider_kinematics(
    theta: ArrayLike,
    crank_radius: ArrayLike,
    rod_length: ArrayLike,
    omega: ArrayLike = 1.0,
    cylinder_offset: ArrayLike = 0.0,
    pin_offset: ArrayLike = 0.0,
) -> SliderKinematics:
    """Exact crank-slider kinematics with offset at constant crank speed.

    Equations (module docstring for the frame; ``s = sin(beta)``, ``c = cos(beta)``)::

        s = lam sin(phi) - delta,  c = sqrt(1 - s^2)
        x        = sqrt((l+r)^2 - e^2) - r cos(phi) - l c
        dx/dphi  = r (sin(phi) + s cos(phi)/c)             = r sin(phi + beta)/cos(beta)
        d2x/dphi2 = r (cos(phi) - s sin(phi)/c + lam cos^2(phi)/c^3)
        dbeta/dphi   = lam cos(phi)/c
        d2beta/dphi2 = -lam sin(phi)/c + lam^2 cos^2(phi) s/c^3

    The position and obliquity are those of Agostini (Powertrain Components Design, Politecnico di
    Torino, 2019, "Offset layout"); the
    derivatives are differentiated here in closed form (the acceleration printed in that source
    lacks the ``cos(phi)`` term and has the sign of the ``s sin(phi)`` term reversed; the forms
    above are checked against finite differences and a direct vector construction in
    ``tests/calc/test_kinematics.py``). For ``e = 0`` they reduce to Heywood (1988, *Internal
    Combustion Engine Fundamentals*, eq. 2.5).

    Parameters
    ----------
    theta : array_like [rad]
        Cylinder crank angle ``phi`` from the geometric top reference (module docstring),
        positive in the direction of rotation; any shape.
    crank_radius : array_like [m]
        Crank throw ``r`` (half the nominal stroke); broadcast with ``theta``.
    rod_length : array_like [m]
        Con-rod length ``l``, big-end centre to small-end centre.
    omega : array_like [rad/s]
        Constant crank speed, ``>= 0``; broadcast with ``theta``.
    cylinder_offset : array_like [m]
        Bore axis relative to the crank axis along ``+t`` (module docstring).
    pin_offset : array_like [m]
        Piston-pin axis offset from the bore axis, towards the major thrust side positive
        (i.e. along ``-t``; module docstring).

    Returns
    -------
    SliderKinematics
        All fields have the broadcast shape of the inputs.

    Notes
    -----
    Valid for ``0 < r`` and ``r + |e| < l`` (``ValueError`` otherwise), rigid links, constant
    ``omega``. No small-``lam`` approximation is made.
    """
    r, l, e = _check_geometry(crank_radius, rod_length, np.subtract(cylinder_offset, pin_offset))
    th = np.asarray(theta, dtype=float)
    w = np.asarray(omega, dtype=float)
    if not np.all(np.isfinite(th)):
        raise ValueError("theta must be finite")
    if not np.all(np.isfinite(w)) or np.any(w < 0):
        raise ValueError(f"omega must be finite and >= 0 rad/s, got {omega!r}")
    lam = r / l
    sp, cp = np.sin(th), np.cos(th)
    s = lam * sp - e / l
    c = np.sqrt(1.0 - s * s)
    x = np.sqrt((l + r) ** 2 - e * e) - r * cp - l * c
    dx = r * (sp + s * cp / c)
    d2x = r * (cp - s * sp / c + lam * cp * cp / c**3)
    beta = np.arcsin(s)
    db = lam * cp / c
    d2b = -lam * sp / c + lam * lam * cp * cp * s / c**3
    return SliderKinematics(
        x=x,
        dx_dtheta=dx,
        d2x_dtheta2=d2x,
        velocity=w * dx,
        acceleration=w * w * d2x,
        beta=beta,
        dbeta_dtheta=db,
        d2beta_dtheta2=d2b,
        rod_omega=-w * db,
        rod_alpha=-w * w * d2b,
    )


def dead_centres(
    crank_radius: ArrayLike,
    rod_length: ArrayLike,
    cylinder_offset: ArrayLike = 0.0,
    pin_offset: ArrayLike = 0.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Crank angles of the piston's dead centres and the exact stroke with offset.

    ``phi_TDC = asin(e/(l + r))``, ``phi_BDC = pi + asin(e/(l - r))`` (rod and crank in line),
    ``stroke = sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2)``.

    Parameters
    ----------
    crank_radius, rod_length : array_like [m]
        Crank throw and con-rod length.
    cylinder_offset, pin_offset : array_like [m]
        Offsets as in :func:`slider_kinematics`.

    Returns
    -------
    theta_tdc : numpy.ndarray [rad]
        Crank angle of top dead centre (``0`` for zero offset).
    theta_bdc : numpy.ndarray [rad]
        Crank angle of bottom dead centre (``pi`` for zero offset).
    stroke : numpy.ndarray [m]
        Piston travel between the dead centres (``2 r`` for zero offset).

    Notes
    -----
    Geometry of Agostini (Powertrain Components Design, Politecnico di Torino, 2019, "Offset
    layout"); valid for ``r + |e| < l``.
    """
    r, l, e = _check_geometry(crank_radius, rod_length, np.subtract(cylinder_offset, pin_offset))
    tdc = np.arcsin(e / (l + r))
    bdc = np.pi + np.arcsin(e / (l - r))
    stroke = np.sqrt((l + r) ** 2 - e * e) - np.sqrt((l - r) ** 2 - e * e)
    return tdc, bdc, stroke


def cycle_grid(step: float = DEFAULT_STEP, cycle: float = FOUR_STROKE_CYCLE) -> np.ndarray:
    """Uniform crank-angle grid over one cycle, without the end point.

    Parameters
    ----------
    step : float [rad]
        Grid step; ``cycle/step`` must be an integer (to 1e-6), e.g. 0.1, 0.25, 0.5, 1, 2 or
        4 deg for a 720 deg cycle.
    cycle : float [rad]
        Cycle length, ``4*pi`` (4-stroke, default).

    Returns
    -------
    numpy.ndarray, shape (N,) [rad]
        ``theta_k = k * cycle / N`` with ``N = cycle/step`` (docs/calc-conventions.md).
    """
    if not (np.isfinite(step) and step > 0 and np.isfinite(cycle) and cycle > 0):
        raise ValueError(f"step and cycle must be finite and > 0 rad, got {step!r}, {cycle!r}")
    n = cycle / step
    n_int = int(round(n))
    if n_int < 4 or abs(n - n_int) > 1e-6 * n:
        raise ValueError(
            f"the cycle ({np.rad2deg(cycle):g} deg) must hold an integer number (>= 4) of steps; "
            f"step {np.rad2deg(step):g} deg gives {n:g}"
        )
    return np.arange(n_int) * (cycle / n_int)
