"""Peak oil-film pressure along a journal orbit of the mobility method.

The finite-length film's peak pressure at each orbit step comes from the stored Reynolds map
(:func:`checker.calc.reynolds_map.film_state_map`); this module takes the peak over the cycle
and treats a full circumferential groove as two lands. The short-bearing (Ocvirk) peak is
computed along its orbit by :mod:`checker.calc.orbit` (``peak_pressure=True``). All inputs SI;
vectorised over any batch shape (bearing x load case x speed x crank angle).

References
----------
.. [1] J. F. Booker, "Dynamically loaded journal bearings: mobility method of solution", Trans. ASME
   J. Basic Eng. 87(3), 1965, pp. 537-546.
.. [2] P. K. Goenka, "Analytical curve fits for solution parameters of dynamically loaded journal
   bearings", Trans. ASME J. Tribol. 106, 1984, pp. 421-428.
.. [3] F. W. Ocvirk, "Short-bearing approximation for full journal bearings", NACA TN 2808, 1952.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from checker.calc import reynolds_map as rm

__all__ = ["peak_film_pressure_finite"]


def peak_film_pressure_finite(
    load_x: ArrayLike, load_y: ArrayLike, eps_x: ArrayLike, eps_y: ArrayLike,
    theta: ArrayLike, diameter: ArrayLike, length: ArrayLike, clearance: ArrayLike,
    viscosity: ArrayLike, full_groove: ArrayLike = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Peak finite-length film pressure over a journal orbit and the crank angle where it
    occurs.

    .. math::

        p_{max} = \\max_t\\ \\Pi(\\varepsilon(t), L_l/D)\\,\\frac{|F_l(t)|}{L_l D},
        \\qquad L_l = s L,\\ F_l = s F,\\ s = \\tfrac12\\ \\text{(full groove) else } 1

    at each orbit step the peak pressure of the finite-length film of the mobility-method
    state (:func:`checker.calc.reynolds_map.film_state_map`); a full circumferential groove
    in the middle splits the bearing into two lands, each carrying half the load over half
    the length.

    Parameters
    ----------
    load_x, load_y : array_like [N]
        Load on the journal in the orbit frame, shape ``(..., angle)``.
    eps_x, eps_y : array_like [-]
        Eccentricity ratio along the orbit, same frame and shape (``|eps| < 1``).
    theta : array_like [rad]
        Crank angle of the orbit steps, shape ``(angle,)``.
    diameter, length, clearance : array_like [m]
        Journal diameter, effective length, radial clearance (broadcast to ``(..., angle)``;
        land length / diameter within the map's range).
    viscosity : array_like [Pa s]
        Broadcast to ``(..., angle)``.
    full_groove : array_like of bool
        A full circumferential groove in the middle of the bearing.

    Returns
    -------
    p_max : numpy.ndarray [Pa]
        Shape ``(...)``.
    theta_p_max : numpy.ndarray [rad]
        Crank angle of ``p_max``, shape ``(...)``.

    Notes
    -----
    Finite-length Reynolds equation with Swift-Stieber cavitation, tabulated (Booker 1965
    mobility method; map as in Goenka, J. Tribology 106, 1984). The groove split neglects the
    groove's width and its supply pressure (the pressure of the hydrodynamic film is far
    higher). Validity: that of the map (its ``L/D`` range, ``|eps| < 1``).
    """
    share = np.where(full_groove, 0.5, 1.0)
    pm, _ = rm.film_state_map(np.asarray(load_x) * share, np.asarray(load_y) * share, eps_x,
                              eps_y, diameter, np.asarray(length) * share, clearance,
                              viscosity)
    k = np.argmax(pm, axis=-1)
    return np.take_along_axis(pm, k[..., None], axis=-1)[..., 0], np.asarray(theta)[k]
