"""Flexible (elastic) couplings in a torsional model: catalogue values to element properties,
and the coupling's load against its ratings (pure NumPy).

Catalogue conventions (DIN 740-2, "Flexible shaft couplings; parameters and design
principles", as the coupling makers' catalogues state them: KTR, "Coupling selection according
to DIN 740 part 2"; Flender RUPEX, Siemens catalogue MD 10.1, 2015; VULKAN RATO-DS data sheets)
-----------------------------------------------------------------------------------------------
* ``T_KN`` nominal torque: transmissible continuously; ``T_KW`` permissible vibratory torque:
  the amplitude of a periodic torque the coupling takes continuously at 10 Hz and the reference
  temperature; ``P_KV`` permissible damping power: the heat the coupling dissipates
  continuously at the reference (ambient) temperature.
* ``C_Tdyn`` dynamic torsional stiffness and ``psi`` relative damping, the damping work of a
  cycle over the elastic work (``psi = Delta W / W_el``, ``W_el = C_Tdyn phi^2 / 2``): a
  hysteretic element ``k* = C_Tdyn (1 + j eta)`` with loss factor ``eta = psi / (2 pi)``
  (energy per cycle ``pi eta C phi^2 = psi W_el``).
* Rubber softens and its damping falls as it warms: catalogues give factors on ``C_Tdyn`` and
  ``psi`` against the rubber temperature, and on ``T_KW`` and ``P_KV`` the temperature factor
  ``S_t >= 1`` (the load is multiplied by it); for frequencies above 10 Hz the frequency factor
  ``S_f = sqrt(f / 10 Hz)`` multiplies the vibratory torque (1 at or below 10 Hz).
* Checks: ``T_W S_t S_f <= T_KW`` (the vibratory torque, all orders synthesised, at the
  frequency of its largest order) and ``P_W S_t <= P_KV`` (the damping power summed over the
  orders: orders are orthogonal over the cycle, so the heat of each adds).

Heat of one order of twist amplitude ``|dphi_n|`` at ``Omega_n = 2 pi f_n`` (hysteretic):
``P_n = 1/2 Omega_n eta C |dphi_n|^2 = psi f_n T_n^2 / (2 C)`` with ``T_n = C |dphi_n|``
(the elastic torque amplitude).

References
----------
.. [1] DIN 740-2:1986, "Flexible shaft couplings; parameters and design principles".
.. [2] KTR Kupplungstechnik, "Coupling selection according to DIN 740 part 2" (T_KN, T_KW,
   T_Kmax, S_t, S_f).
.. [3] Siemens, "FLENDER Standard Couplings", catalogue MD 10.1, 2015, p. 8/5 (RUPEX:
   C_Tdyn, psi, tolerances).
.. [4] L. E. Nielsen, R. F. Landel, "Mechanical Properties of Polymers and Composites", 1994,
   ch. 4 (loss factor, energy dissipated per cycle pi k'' phi^2).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "REFERENCE_FREQUENCY",
    "damping_power",
    "frequency_factor",
    "loss_factor",
    "table_factor",
    "vibratory_torque_ratio",
]

REFERENCE_FREQUENCY = 10.0
"""Frequency at which ``T_KW`` is rated [Hz] (DIN 740-2)."""


def loss_factor(relative_damping: ArrayLike) -> np.ndarray:
    """Loss factor ``eta = psi / (2 pi)`` of a coupling with relative damping ``psi``.

    Parameters
    ----------
    relative_damping : array_like [-]
        ``psi = Delta W / W_el`` (>= 0; rubber couplings about 0.5..1.5).

    Returns
    -------
    numpy.ndarray [-]

    Examples
    --------
    >>> round(float(loss_factor(1.13)), 4)  # VULKAN RATO-DS, rubber quality 5, nominal
    0.1798
    """
    psi = np.asarray(relative_damping, dtype=float)
    if np.any(~np.isfinite(psi)) or np.any(psi < 0):
        raise ValueError("relative damping psi must be finite and >= 0")
    return psi / (2.0 * np.pi)


def frequency_factor(frequency: ArrayLike) -> np.ndarray:
    """Frequency factor ``S_f = sqrt(f / 10 Hz)`` above 10 Hz, 1 at or below (DIN 740-2).

    Parameters
    ----------
    frequency : array_like [Hz]
        Vibration frequency (>= 0).

    Returns
    -------
    numpy.ndarray [-]
    """
    f = np.asarray(frequency, dtype=float)
    if np.any(~np.isfinite(f)) or np.any(f < 0):
        raise ValueError("frequency must be finite and >= 0 Hz")
    return np.sqrt(np.maximum(f, REFERENCE_FREQUENCY) / REFERENCE_FREQUENCY)


def table_factor(x: ArrayLike, table_x: ArrayLike, table_factor_: ArrayLike) -> np.ndarray:
    """A catalogue factor at ``x`` (temperature, vibratory torque), linear between the table's
    points and held at its ends; 1 for an empty table.

    Parameters
    ----------
    x : array_like [unit of table_x]
    table_x : array_like, shape (m,)
        Strictly increasing.
    table_factor_ : array_like, shape (m,) [-]
        > 0.

    Returns
    -------
    numpy.ndarray [-]
    """
    tx = np.asarray(table_x, dtype=float).ravel()
    tf = np.asarray(table_factor_, dtype=float).ravel()
    if tx.size == 0:
        return np.ones(np.shape(x))
    if tf.shape != tx.shape or np.any(np.diff(tx) <= 0) or np.any(tf <= 0):
        raise ValueError("the factor table needs strictly increasing abscissae and factors > 0")
    return np.interp(np.asarray(x, dtype=float), tx, tf)


def damping_power(twist: ArrayLike, omega: ArrayLike, stiffness: float,
                  relative_damping: float) -> np.ndarray:
    """Heat dissipated in the coupling per order, ``P_n = 1/2 Omega_n (psi / 2 pi) C |dphi_n|^2``.

    Parameters
    ----------
    twist : array_like, shape (..., O), complex [rad]
        Twist across the coupling per order (0-to-peak).
    omega : array_like, shape (..., O) [rad/s]
        Vibration frequency of each order.
    stiffness : float [N m/rad]
        Dynamic torsional stiffness ``C_Tdyn`` at the operating state.
    relative_damping : float [-]
        ``psi`` at the operating state.

    Returns
    -------
    numpy.ndarray, shape (..., O) [W]
        Sum over the order axis for the total (orders are orthogonal over the cycle).

    Examples
    --------
    5 kNm of 20 Hz vibratory torque in a coupling of 262.5 kNm/rad and psi = 1.13 (VULKAN
    RATO-DS 2200): ``psi f T^2 / (2 C) = 1.13 * 20 * 5000^2 / (2 * 262500) = 1076 W``.

    >>> import numpy as np
    >>> p = damping_power(5000.0 / 262500.0, 2 * np.pi * 20.0, 262500.0, 1.13)
    >>> round(float(p))
    1076
    """
    if not (stiffness > 0 and np.isfinite(stiffness)):
        raise ValueError("coupling stiffness must be finite and > 0 N m/rad")
    eta = loss_factor(relative_damping)
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0):
        raise ValueError("omega must be finite and >= 0 rad/s")
    return 0.5 * w * eta * stiffness * np.abs(np.asarray(twist)) ** 2


def vibratory_torque_ratio(torque_total: ArrayLike, torque_orders: ArrayLike,
                           frequency: ArrayLike, permissible: float,
                           temperature_factor: ArrayLike = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """``T_W S_t S_f / T_KW`` with ``S_f`` at the frequency of the largest order.

    Parameters
    ----------
    torque_total : array_like, shape (...) [N m]
        Synthesised vibratory torque (half peak-to-peak of all orders).
    torque_orders : array_like, shape (..., O) [N m]
        Amplitude of each order (0-to-peak).
    frequency : array_like, shape (..., O) [Hz]
        Frequency of each order.
    permissible : float [N m]
        ``T_KW`` (> 0).
    temperature_factor : array_like, broadcast to (...) [-]
        ``S_t >= 1`` at the rubber's temperature.

    Returns
    -------
    ratio : numpy.ndarray, shape (...) [-]
    frequency_of_largest : numpy.ndarray, shape (...) [Hz]
    """
    if not (permissible > 0 and np.isfinite(permissible)):
        raise ValueError("T_KW must be finite and > 0 N m")
    st = np.asarray(temperature_factor, dtype=float)
    if np.any(~np.isfinite(st)) or np.any(st <= 0):
        raise ValueError("temperature factor must be finite and > 0")
    t_o = np.abs(np.asarray(torque_orders))
    f = np.broadcast_to(np.asarray(frequency, dtype=float), t_o.shape)
    k = np.argmax(t_o, axis=-1)[..., None]
    f_big = np.take_along_axis(f, k, -1)[..., 0]
    return np.asarray(torque_total) * st * frequency_factor(f_big) / permissible, f_big
