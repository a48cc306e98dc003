"""Stress concentration factor of a stepped round shaft with a shoulder fillet (the crank nose
where it steps down from the first main journal).

``K_t = C1 + C2 (2h/D) + C3 (2h/D)^2 + C4 (2h/D)^3`` with ``h = (D - d)/2`` the step height,
``r`` the fillet radius and ``C1..C4`` polynomials in ``sqrt(h/r)`` and ``h/r``: the curve fits of
Peterson's charts for a stepped bar of circular section, bending (Chart 3.10, two ranges
0.1 <= h/r <= 2 and 2 <= h/r <= 20) and torsion (Chart 3.12, 0.25 <= h/r <= 4), as tabulated by
Young, W. C., Budynas, R. G., "Roark's Formulas for Stress and Strain", 7th ed., McGraw-Hill,
2002, Table 17.1, cases 17b (bending) and 17c (torsion); the charts are those of Pilkey, W. D.,
Pilkey, D. F., "Peterson's Stress Concentration Factors", 3rd ed., Wiley, 2008. Nominal stress
on the small diameter ``d``. Outside the fits' ranges the value is still computed and flagged.

References
----------
.. [1] W. C. Young, R. G. Budynas, "Roark's Formulas for Stress and Strain", 7th ed., 2002,
   Table 17.1, 17b and 17c.
"""

from __future__ import annotations

import math

_BENDING = (  # (h/r upper bound, C1..C4 as (a, b, c): a + b sqrt(h/r) + c h/r)
    (2.0, ((0.947, 1.206, -0.131), (0.022, -3.405, 0.915), (0.869, 1.777, -0.555),
           (-0.810, 0.422, -0.260))),
    (20.0, ((1.232, 0.832, -0.008), (-3.813, 0.968, -0.260), (7.423, -4.868, 0.869),
            (-3.839, 3.070, -0.600))),
)
_TORSION = (
    (4.0, ((0.905, 0.783, -0.075), (-0.437, -1.969, 0.553), (1.557, 1.073, -0.578),
           (-1.061, 0.171, 0.086))),
)
_LOW = {"bending": 0.1, "torsion": 0.25}


def shoulder_fillet_scf(big_d: float, small_d: float, radius: float, load: str
                        ) -> tuple[float, bool]:
    """``(K_t, in_range)`` of a shoulder fillet (module docstring); ``load`` "bending" or
    "torsion"; diameters and radius in m (any consistent unit).

    >>> k, ok = shoulder_fillet_scf(0.055, 0.04125, 0.0022, "bending")
    >>> round(k, 3), ok
    (2.041, True)
    >>> round(shoulder_fillet_scf(0.055, 0.04125, 0.0022, "torsion")[0], 3)
    1.603
    """
    if not (big_d > small_d > 0 and radius > 0):
        raise ValueError("shoulder fillet: need D > d > 0 and r > 0")
    h = (big_d - small_d) / 2.0
    hr = h / radius
    table = _BENDING if load == "bending" else _TORSION
    coeffs = table[-1][1]
    for upper, cs in table:
        if hr <= upper:
            coeffs = cs
            break
    s = math.sqrt(hr)
    c = [a + b * s + e * hr for a, b, e in coeffs]
    t = 2.0 * h / big_d
    kt = c[0] + c[1] * t + c[2] * t * t + c[3] * t**3
    return max(kt, 1.0), _LOW[load] <= hr <= table[-1][0]
