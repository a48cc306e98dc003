"""Tuning of a rubber torsional-vibration damper against Den Hartog's optimum.

The damper ring (inertia ``J_d``) hangs on the crank nose (the hub) through the rubber
(storage stiffness ``k_d``, hysteretic loss factor ``eta``, optional viscous ``c_d``). Seen from
the crank's first flexible mode, the crank is a single-degree-of-freedom primary system of
natural frequency ``omega_n`` (the chain *without* the ring) and modal inertia ``J_eq`` at the
hub (:func:`checker.calc.torsional.equivalent_inertia`, Drapal & Novotny 2017, J. Vibroeng.
19(7), eq. 3), so Den Hartog's tuned-absorber theory applies with the inertia ratio
``mu = J_d / J_eq`` (Den Hartog, *Mechanical Vibrations*, 4th ed. 1956, sec. 3.3, eqs. 3.19,
3.23; :func:`checker.calc.damper.den_hartog_optimum`):

    f = omega_d / omega_n,   omega_d = sqrt(k_d / J_d)         actual tuning ratio
    f_opt = 1 / (1 + mu),    zeta_opt = sqrt(3 mu / (8 (1 + mu)^3))

Damping is compared as the viscous ratio ``zeta = c/(2 J_d omega_n)``; a hysteretic rubber is
equivalent at the ring frequency to ``c = eta k_d / omega_d``, i.e. ``zeta = eta f / 2`` and
``eta_opt = 2 zeta_opt / f_opt`` (equal dissipation per cycle at the ring frequency). The
optimum rubber is ``k_opt = J_d (f_opt omega_n)^2`` with loss factor ``eta_opt``.

References
----------
.. [1] J. P. Den Hartog, "Mechanical Vibrations", 4th ed., 1956, sec. 3.3, eqs. 3.19, 3.23.
.. [2] L. Drapal, P. Novotny, "Torsional vibration analysis of crank train with low friction
   losses", J. Vibroeng. 19(7), 2017, doi:10.21595/jve.2017.17876, eq. 3 (equivalent inertia).
"""

from __future__ import annotations

from dataclasses import replace
from typing import NamedTuple

import numpy as np

from checker.calc._checks import non_negative, positive
from checker.calc.damper import den_hartog_optimum
from checker.calc.torsional import TorsionalModel, equivalent_inertia, natural_frequencies

__all__ = ["DamperTuning", "PrimaryMode", "absorber_tuning", "optimum_model", "primary_mode"]


class PrimaryMode(NamedTuple):
    """First flexible mode of the chain without the damper ring.

    Attributes
    ----------
    omega : float [rad/s]
    equivalent_inertia : float [kg m^2]
        ``J_eq = sum J_i (phi_i / phi_hub)^2``.
    mode : numpy.ndarray, shape (n - 1,) [-]
        Mode shape normalised to 1 at the hub.
    """

    omega: float
    equivalent_inertia: float
    mode: np.ndarray


def primary_mode(model: TorsionalModel, ring: int) -> PrimaryMode:
    """First flexible mode of ``model`` with the damper ring station removed, at its hub.

    Parameters
    ----------
    model : TorsionalModel
        Chain model (default element ends ``e -> e + 1``) including the ring.
    ring : int
        Index of the ring station; it must be the first station (the ring hangs on the next
        station, its hub, through element 0 only).

    Returns
    -------
    PrimaryMode

    Notes
    -----
    Free-free or grounded chains; the rigid-body mode of a free-free chain (``omega = 0``) is
    skipped. ``ValueError`` if the ring is not the first station, if the remaining chain has
    no flexible mode, or if the mode has a node at the hub.
    """
    if ring != 0:
        raise ValueError("the damper ring must be the first station of the chain (hung on the"
                         " next station through its rubber element only)")
    if model.n_stations < 2:
        raise ValueError("the chain needs the ring and at least one more station")
    if not (np.array_equal(model.node_a, np.arange(model.n_elements))
            and np.array_equal(model.node_b, np.arange(1, model.n_elements + 1))):
        raise ValueError("primary_mode needs a plain chain model (element e joins e and e+1)")
    prim = TorsionalModel(model.inertia[1:], model.stiffness[1:],
                          damping_abs=model.damping_abs[1:], damping_rel=model.damping_rel[1:],
                          loss_factor=model.loss_factor[1:],
                          stiffness_ground=model.stiffness_ground[1:])
    w, modes = natural_frequencies(prim)
    flex = np.nonzero(w > 1e-6 * max(float(w.max()), 1.0))[0]
    if flex.size == 0:
        raise ValueError("the chain without the ring has no flexible mode")
    k = int(flex[0])
    phi = modes[:, k]
    j_eq = equivalent_inertia(prim, phi, 0)
    return PrimaryMode(float(w[k]), j_eq, phi / phi[0])


class DamperTuning(NamedTuple):
    """Actual and optimum damper parameters (floats).

    Attributes
    ----------
    mass_ratio : ``mu = J_d / J_eq`` [-]
    ring_frequency : ``omega_d = sqrt(k_d/J_d)`` [rad/s]
    tuning : actual ``f = omega_d / omega_n`` [-]
    tuning_optimum : ``f_opt = 1/(1+mu)`` [-]
    tuning_deviation : ``f / f_opt - 1`` [-]
    damping_ratio : actual equivalent ``zeta = eta f/2 + c_d/(2 J_d omega_n)`` [-]
    damping_optimum : ``zeta_opt`` [-]
    loss_factor_optimum : ``eta_opt = 2 zeta_opt / f_opt`` [-]
    stiffness_optimum : ``k_opt = J_d (f_opt omega_n)^2`` [N m/rad]
    peak_magnification : Den Hartog's optimum peak ``sqrt(1 + 2/mu)`` [-]
    """

    mass_ratio: float
    ring_frequency: float
    tuning: float
    tuning_optimum: float
    tuning_deviation: float
    damping_ratio: float
    damping_optimum: float
    loss_factor_optimum: float
    stiffness_optimum: float
    peak_magnification: float


def absorber_tuning(ring_inertia: float, rubber_stiffness: float, loss_factor: float,
                    relative_damping: float, primary_omega: float,
                    primary_inertia: float) -> DamperTuning:
    """Actual tuning and damping of the damper against Den Hartog's optimum (module docstring).

    Parameters
    ----------
    ring_inertia : float [kg m^2]
        ``J_d > 0``.
    rubber_stiffness : float [N m/rad]
        Storage stiffness ``k_d > 0``.
    loss_factor : float [-]
        Rubber hysteretic loss factor ``eta >= 0``.
    relative_damping : float [N m s/rad]
        Viscous damping ``c_d >= 0`` of the rubber element.
    primary_omega : float [rad/s]
        ``omega_n`` of the crank's first mode without the ring (:func:`primary_mode`).
    primary_inertia : float [kg m^2]
        ``J_eq`` at the hub.

    Returns
    -------
    DamperTuning

    Notes
    -----
    Den Hartog's optimum is derived for an undamped primary system and a viscous absorber; the
    crank's own damping and the hysteretic (rather than viscous) rubber make it approximate;
    the forced response with the optimum parameters (:func:`optimum_model`) shows the result
    in the real model.
    """
    jd = float(positive("ring_inertia", ring_inertia))
    kd = float(positive("rubber_stiffness", rubber_stiffness))
    eta = float(non_negative("loss_factor", loss_factor))
    c = float(non_negative("relative_damping", relative_damping))
    wn = float(positive("primary_omega", primary_omega))
    jeq = float(positive("primary_inertia", primary_inertia))
    mu = jd / jeq
    wd = np.sqrt(kd / jd)
    f = wd / wn
    f_opt, z_opt, peak = (float(x) for x in den_hartog_optimum(mu))
    zeta = eta * f / 2.0 + c / (2.0 * jd * wn)
    return DamperTuning(mu, float(wd), float(f), f_opt, float(f / f_opt - 1.0), float(zeta),
                        z_opt, 2.0 * z_opt / f_opt, jd * (f_opt * wn) ** 2, peak)


def optimum_model(model: TorsionalModel, ring: int, tuning: DamperTuning) -> TorsionalModel:
    """``model`` with the rubber element of ``ring`` at Den Hartog's optimum.

    Storage stiffness ``k_opt``, loss factor ``eta_opt``, no viscous damping in the element;
    every other station and element unchanged (same model, optimum parameters).

    Parameters
    ----------
    model : TorsionalModel
    ring : int
        Ring station; its rubber is element ``ring``.
    tuning : DamperTuning

    Returns
    -------
    TorsionalModel
    """
    k = model.stiffness.copy()
    eta = model.loss_factor.copy()
    c = model.damping_rel.copy()
    k[ring] = tuning.stiffness_optimum
    eta[ring] = tuning.loss_factor_optimum
    c[ring] = 0.0
    dyn = {e: f for e, f in model.dynamic_stiffness.items() if e != ring}
    return replace(model, stiffness=k, loss_factor=eta, damping_rel=c, dynamic_stiffness=dyn)
