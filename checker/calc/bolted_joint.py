"""Bolted joints at the crank nose and flywheel: preload, bolt stress, head contact stress and
slip torque capacity (cover factor).

All functions take SI inputs and broadcast over NumPy arrays (e.g. over joints).

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo plc, 2013, slides 23-24
   (crank-nose and flywheel joint worked calculations).
.. [2] ISO 898-1:2013, "Mechanical properties of fasteners made of carbon steel and alloy steel
   - Part 1: Bolts, screws and studs", clause 9.1.6.1 (stress area), Table 3 (R_p0.2, S_p).
.. [3] VDI 2230 Part 1 (2015), "Systematic calculation of highly stressed bolted joints",
   R10 (surface pressure under the head, A_p = pi/4 (d_W^2 - d_h^2)).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

ISO_STRESS_AREA_COEFFICIENT = 0.9382
"""ISO 898-1 stress-area coefficient: d_s = (d2 + d3)/2 = d - 0.938194 p [2]."""

DEFAULT_NUT_FACTOR = 0.2
"""Nut factor K in F = T / (K d); the value used in [1] (F = 5 T / D)."""

DEFAULT_FRICTION = 0.2
"""Coefficient of friction at the clamped face; 'typical value' in [1] (0.3 with a diamond
washer)."""

# Property classes: (R_p0.2 min [Pa], stress under proof load S_p [Pa]).
# 10.9 and 12.9: ISO 898-1:2013 Table 3, also printed in [1]; 11.9 (not an ISO class) from [1];
# 8.8 and 9.8 for d <= 16 mm from ISO 898-1:2013 Table 3.
PROPERTY_CLASSES: dict[str, tuple[float, float]] = {
    "8.8": (640e6, 580e6),
    "9.8": (720e6, 650e6),
    "10.9": (940e6, 830e6),
    "11.9": (1020e6, 900e6),
    "12.9": (1100e6, 970e6),
}

# Tightening method -> (fraction, reference stress) for method-based preload, table in [1]:
# snug torque + angle of turn 0.85 R_p0.2; yield-controlled 0.75 R_p0.2; torque wrench 0.70 S_p.
PRELOAD_FRACTIONS: dict[str, tuple[float, str]] = {
    "angle controlled": (0.85, "rp02"),
    "yield controlled": (0.75, "rp02"),
    "torque wrench": (0.70, "proof_load_stress"),
}


def _positive(name: str, *arrays: np.ndarray) -> None:
    for a in arrays:
        if np.any(~np.isfinite(a)) or np.any(a <= 0):
            raise ValueError(f"{name} must be finite and positive")


def tensile_stress_area(d: ArrayLike, p: ArrayLike,
                        coefficient: ArrayLike = ISO_STRESS_AREA_COEFFICIENT) -> np.ndarray:
    r"""Tensile stress area of a metric thread.

    .. math:: A_s = \frac{\pi}{4}\,(d - c\,p)^2, \qquad c = 0.9382 \text{ (ISO 898-1)}

    Parameters
    ----------
    d : array_like [m]
        Nominal diameter.
    p : array_like [m]
        Thread pitch.
    coefficient : array_like [-]
        ``c``; 0.9382 per ISO 898-1 [2]. The crank-nose worksheet of [1] uses 0.938.

    Returns
    -------
    numpy.ndarray [m^2]

    Notes
    -----
    Valid for ISO metric threads, ``p < d/2``.

    Examples
    --------
    >>> round(float(tensile_stress_area(0.010, 0.001)) * 1e6, 3)  # [1]: 64.494 mm^2
    64.494
    """
    d, p, c = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (d, p, coefficient)))
    _positive("diameter and pitch", d, p)
    if np.any(p >= d / 2):
        raise ValueError("thread pitch must be below half the nominal diameter")
    return np.pi / 4.0 * (d - c * p) ** 2


def preload_from_torque(torque: ArrayLike, d: ArrayLike,
                        nut_factor: ArrayLike = DEFAULT_NUT_FACTOR) -> np.ndarray:
    r"""Bolt preload from the tightening torque with a nut factor.

    .. math:: F = \frac{T}{K\,d}

    Parameters
    ----------
    torque : array_like [N m]
        Tightening torque.
    d : array_like [m]
        Nominal diameter.
    nut_factor : array_like [-]
        K, 0.2 in [1] ([1] writes F = 5 T / D).

    Returns
    -------
    numpy.ndarray [N]

    Notes
    -----
    The short-form torque-tension relation; K lumps thread and head friction (typ. 0.15-0.25).
    """
    t, d, k = (np.asarray(x, dtype=float) for x in (torque, d, nut_factor))
    _positive("tightening torque, diameter and nut factor", t, d, k)
    return t / (k * d)


def preload_from_stress(fraction: ArrayLike, stress: ArrayLike, area: ArrayLike) -> np.ndarray:
    r"""Bolt preload as a fraction of a reference stress (yield/angle-controlled tightening).

    .. math:: F = k\,\sigma_{ref}\,A_s

    Parameters
    ----------
    fraction : array_like [-]
        k (0.85 snug + angle, 0.75 yield controlled of R_p0.2; 0.70 of S_p for a torque
        wrench; table in [1]).
    stress : array_like [Pa]
        Reference stress (R_p0.2 or S_p).
    area : array_like [m^2]
        Tensile stress area.

    Returns
    -------
    numpy.ndarray [N]
    """
    k, s, a = (np.asarray(x, dtype=float) for x in (fraction, stress, area))
    _positive("fraction, stress and area", k, s, a)
    if np.any(k > 1):
        raise ValueError("preload fraction must not exceed 1")
    return k * s * a


def proof_stress_ratio(preload: ArrayLike, proof_stress: ArrayLike,
                       area: ArrayLike) -> np.ndarray:
    r"""Bolt stress as a fraction of the proof stress.

    .. math:: \frac{F}{P\,A_s}

    ``P`` is the proof stress [1] uses (940 N/mm^2 for grade 10.9, i.e. R_p0.2) [1].
    Multiply by 100 for the percentage (70-75 % recommended in [1]).

    Returns
    -------
    numpy.ndarray [-]
    """
    f, p, a = (np.asarray(x, dtype=float) for x in (preload, proof_stress, area))
    _positive("preload, proof stress and area", f, p, a)
    return f / (p * a)


def head_contact_stress(preload: ArrayLike, d_outer: ArrayLike, d_inner: ArrayLike
                        ) -> np.ndarray:
    r"""Contact stress under the bolt head on the annular bearing face.

    .. math:: \sigma = \frac{F}{\frac{\pi}{4}(d_o^2 - d_i^2)}

    Parameters
    ----------
    preload : array_like [N]
    d_outer, d_inner : array_like [m]
        Outer (head bearing) and inner (hole/chamfer) diameters of the annulus; [3] R10.

    Returns
    -------
    numpy.ndarray [Pa]
    """
    f, do, di = (np.asarray(x, dtype=float) for x in (preload, d_outer, d_inner))
    _positive("preload and outer diameter", f, do)
    if np.any(di < 0) or np.any(di >= do):
        raise ValueError("head bearing inner diameter must be in [0, outer diameter)")
    return f / (np.pi / 4.0 * (do**2 - di**2))


def effective_friction_diameter(d_outer: ArrayLike, d_inner: ArrayLike) -> np.ndarray:
    r"""Effective friction diameter of a uniformly pressed annulus.

    .. math:: D_{eff} = \frac{2}{3}\,\frac{D^3 - d^3}{D^2 - d^2}

    Returns
    -------
    numpy.ndarray [m]

    Examples
    --------
    >>> round(float(effective_friction_diameter(0.0844, 0.047)) * 1e3, 3)  # [1]: 67.474 mm
    67.474
    """
    do, di = (np.asarray(x, dtype=float) for x in (d_outer, d_inner))
    if np.any(do <= 0) or np.any(di < 0) or np.any(di >= do):
        raise ValueError("face diameters need 0 <= inner < outer")
    return 2.0 / 3.0 * (do**3 - di**3) / (do**2 - di**2)


def slip_torque_capacity(friction: ArrayLike, clamp_force: ArrayLike, d_outer: ArrayLike,
                         d_inner: ArrayLike) -> np.ndarray:
    r"""Torque the clamped annular face transmits by friction before it slips.

    .. math:: T = \mu\,F\,\frac{2}{3}\,\frac{R^3 - r^3}{R^2 - r^2} = \mu\,F\,\frac{D_{eff}}{2}

    Parameters
    ----------
    friction : array_like [-]
        Coefficient of friction at the face (0.2 typical, [1]).
    clamp_force : array_like [N]
        Total clamp force of all bolts of the joint.
    d_outer, d_inner : array_like [m]
        Face outer and inner diameters.

    Returns
    -------
    numpy.ndarray [N m]
    """
    mu, f = (np.asarray(x, dtype=float) for x in (friction, clamp_force))
    _positive("friction coefficient and clamp force", mu, f)
    return mu * f * effective_friction_diameter(d_outer, d_inner) / 2.0


def cover_factor(capacity: ArrayLike, applied_torque: ArrayLike) -> np.ndarray:
    r"""Joint cover factor: slip torque capacity over peak applied torque [1].

    Returns
    -------
    numpy.ndarray [-]
    """
    c, t = (np.asarray(x, dtype=float) for x in (capacity, applied_torque))
    _positive("capacity and applied torque", c, t)
    return c / t
