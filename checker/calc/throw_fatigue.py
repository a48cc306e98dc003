"""Fatigue of crank throws over the working cycle: nominal -> local stresses -> Goodman, per
throw, journal and oil hole, and the IACS UR M53 acceptability factor of a location.

The steps the crankshaft-fatigue graph node (:mod:`checker.modules.fatigue`) chains, as pure
NumPy functions on SI arrays (no loop over crank angle or speed):

* :func:`element_torque_cycle`: the torsional element torques over the cycle from their mean
  and complex order amplitudes, with a zero "free end" element appended;
* :func:`pin_torque`: the crank pin's torque from its two journal elements (determinate);
* :func:`main_journal_elements`: which torsional elements a main journal may carry;
* :func:`throw_goodman`: nominal stresses of the throws (M53 §2), local stresses with the
  stress concentration factors (M53 §3), Goodman safety factors of the pin fillets, journal
  fillets and pin oil holes (:mod:`checker.calc.fatigue`);
* :func:`main_oil_hole_goodman`: Goodman factor of a main-journal oil hole under torsion only;
* :func:`m53_q`: M53 equivalent alternating stress of the worst candidate and ``Q``.

References
----------
.. [1] IACS Unified Requirement M53, "Calculation of crankshafts for I.C. engines", Rev. 3, 2015,
   §2-7.
.. [2] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013, slides
   'Crankshaft analysis (25)-(28)' (classical stress analysis, Goodman safety factor >= 1.5).
.. [3] R. G. Budynas, J. K. Nisbett, "Shigley's Mechanical Engineering Design", 10th ed.,
   McGraw-Hill, 2015, eq. 6-46 (Goodman line).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from . import crank_stress as cs
from . import fatigue as fat
from . import torsional as tv


def element_torque_cycle(orders: ArrayLike, coeffs: ArrayLike, mean: ArrayLike,
                         n_angles: int) -> np.ndarray:
    r"""Torque of each torsional element over one 720° cycle, plus a zero free-end element.

    ``T_e(theta_k) = T_mean,e + sum_n Re{T_en exp(j n theta_k)}``, ``theta_k = 4 pi k / N``
    (:func:`checker.calc.torsional.synthesize`, inverse real FFT), the theta origin of the
    order amplitudes (firing TDC of cylinder 1 in the torsional module).

    Parameters
    ----------
    orders : array_like, shape (n_order,) [-]
        Positive multiples of 0.5, no duplicates.
    coeffs : array_like, shape (E, C, S, n_order), complex [N m]
        Complex torque amplitude of each element (E), load case (C), speed (S), order.
    mean : array_like, shape (E, C, S) [N m]
        Mean torque of each element.
    n_angles : int
        Crank-angle points per cycle N (those of the bending loads).

    Returns
    -------
    numpy.ndarray, shape (C, S, E + 1, N) [N m]
        Element torques over the cycle; index E (the last) is identically zero: the "element"
        beyond a free end of the chain.

    Examples
    --------
    Mean 5 N m plus 2 N m at order 1 (theta_k = 0, 90°, 180° ...: 5 + 2 cos theta):

    >>> coeffs, mean = np.full((1, 1, 1, 1), 2.0 + 0j), np.full((1, 1, 1), 5.0)
    >>> t = element_torque_cycle([1.0], coeffs, mean, 8)
    >>> t.shape, t[0, 0, 0].round(12).tolist(), bool(t[0, 0, 1].any())
    ((1, 1, 2, 8), [7.0, 5.0, 3.0, 5.0, 7.0, 5.0, 3.0, 5.0], False)
    """
    mean = np.asarray(mean, dtype=float)
    _, vib = tv.synthesize(orders, coeffs, n_angles)  # (E, C, S, N)
    n_el, n_c, n_s = mean.shape
    torque = np.zeros((n_c, n_s, n_el + 1, n_angles))
    torque[:, :, :n_el] = np.moveaxis(vib + mean[..., None], 0, 2)
    return torque


def main_journal_elements(throw_elements: ArrayLike, n_mains: int) -> np.ndarray:
    """The two candidate torsional elements of each main journal.

    Main journal ``m`` lies between throw ``m - 1`` and throw ``m`` (main 0 in front of the
    first throw, the last main behind the last throw): it carries the front element of throw
    ``m`` or, equally, the rear element of throw ``m - 1`` (the element between the two
    cylinder stations). Both are returned (the same one twice at the ends of the crank).

    Parameters
    ----------
    throw_elements : array_like of int, shape (T, 2)
        Front and rear element index of each throw.
    n_mains : int
        Number of main journals (T + 1 for a fully supported crank).

    Returns
    -------
    numpy.ndarray of int, shape (n_mains, 2)

    Examples
    --------
    >>> main_journal_elements([[0, 1], [1, 2]], 3).tolist()
    [[0, 0], [1, 1], [2, 2]]
    """
    sides = np.asarray(throw_elements, dtype=int)
    n_pins = sides.shape[0]
    out = np.empty((n_mains, 2), dtype=int)
    for m in range(n_mains):  # journals, not angles: a handful
        adj = ([sides[m, 0]] if m < n_pins else []) + ([sides[m - 1, 1]] if m > 0 else [])
        out[m] = (adj * 2)[:2]
    return out


class ThrowGoodman(NamedTuple):
    """Goodman results of the throws (:class:`checker.calc.fatigue.CycleFatigue` each)."""

    pin: fat.CycleFatigue  #: pin fillets, shape (..., T, 2 webs: front, rear)
    journal: fat.CycleFatigue  #: journal fillets, shape (..., T, 2 webs)
    pin_oil: fat.CycleFatigue | None  #: pin oil holes (..., T, 2 torques), None if not asked
    nominal: cs.ThrowNominalStresses  #: the nominal stresses (M53 §2)


def pin_torque(side_torque: ArrayLike, main_spacing: float,
               pin_position: float | None = None) -> np.ndarray:
    r"""Torque carried by the crank pin of each throw, from its two journal elements.

    The throw is simply supported at its main journals (M53 §2.1, the determinate scheme): the
    tangential rod force ``F_T`` on the pin, at ``L_2`` from the front main of a bay ``L_3``, is
    carried ``(L_3 - L_2)/L_3`` by the front main and ``L_2/L_3`` by the rear one. The pin's axis
    lies ``R`` off the crank axis, so the front main's reaction adds ``R F_T (L_3 - L_2)/L_3``
    to the front journal's torque about the pin axis; ``F_T`` itself passes through the pin
    axis and adds nothing. With ``T_r = T_f + R F_T``:

    ``T_pin = T_f + (L_3 - L_2)/L_3 (T_r - T_f)``, the same along the pin (the mean of the two
    journal torques for a centred pin). Statics of the free body (Timoshenko, Strength of
    Materials, Part I, 1955, ch. 1 and 9).

    Parameters
    ----------
    side_torque : array_like, shape (..., T, 2, N) [N m]
        Torque of the element in front of (index 0) and behind (1) each throw.
    main_spacing : float [m]
        Main bearing spacing ``L_3``.
    pin_position : float [m], optional
        Pin centre from the front main centre ``L_2`` (default ``L_3/2``).

    Returns
    -------
    ndarray, shape (..., T, N) [N m]

    Examples
    --------
    >>> t = np.array([[[100.0], [300.0]]])  # one throw, front 100 N m, rear 300 N m
    >>> float(pin_torque(t, 0.09)[0, 0]), float(pin_torque(t, 0.09, 0.03)[0, 0])
    (200.0, 233.33333333333331)
    """
    t = np.asarray(side_torque, dtype=float)
    l3 = float(main_spacing)
    l2 = l3 / 2.0 if pin_position is None else float(pin_position)
    if not (l3 > 0.0 and 0.0 < l2 < l3):
        raise ValueError(f"pin_position must lie inside the bay (0, {l3}), got {l2}")
    return t[..., 0, :] + (l3 - l2) / l3 * (t[..., 1, :] - t[..., 0, :])


def throw_goodman(force_radial: ArrayLike, force_tangential: ArrayLike, side_torque: ArrayLike,
                  geometry: dict[str, float], oil_hole_angle: float, scf: dict[str, float],
                  strengths: dict[str, tuple[float, float]], pin_oil_hole: bool = True,
                  mean_criterion: str = "signed_von_mises",
                  section_loads: cs.SectionLoads | None = None) -> ThrowGoodman:
    r"""Goodman safety factors of the pin fillets, journal fillets and pin oil holes of throws.

    Steps (IACS UR M53 §2-3, Goodman: Shigley 10th ed. eq. 6-46):

    1. nominal web bending ``sigma_BF``, direct ``sigma_QF``, oil-bore bending and journal
       torsion of each throw, simply supported at its main journals
       (:func:`checker.calc.crank_stress.throw_nominal_stresses`);
    2. local stresses with the stress concentration factors
       (:func:`checker.calc.crank_stress.local_stresses`); the pin fillets and the pin oil
       hole with the pin's own torque (:func:`pin_torque`), ``tau_H = alpha_T T_pin / W_P``;
    3. amplitude and mean over the cycle, von Mises equivalents, ``SF = 1 / (sigma_eq,a / S_e
       + sigma_eq,m / S_u)`` (:func:`checker.calc.fatigue.fillet_goodman`); pin oil holes
       with M53's maximum-principal combination (:func:`checker.calc.fatigue.oil_hole_goodman`).

    Parameters
    ----------
    force_radial, force_tangential : array_like, shape (..., T, N) [N]
        Con-rod force on each crank pin in the throw frame (+ outward, + rotation).
    side_torque : array_like, shape (..., T, 2, N) [N m]
        Torque of the element in front of (index 0) and behind (1) each throw.
    geometry : dict
        Keyword arguments of :func:`checker.calc.crank_stress.throw_nominal_stresses` [m].
    oil_hole_angle : float [rad]
        Pin oil hole angle from the throw axis, + leading.
    scf : dict
        Stress concentration factors [-]: ``alpha_b, alpha_t, beta_b, beta_q, beta_t,
        gamma_b, gamma_t``.
    strengths : dict
        ``(S_e, S_u)`` [Pa] of ``"pin fillet"``, ``"main fillet"`` and (if ``pin_oil_hole``)
        ``"pin oil hole"``.
    pin_oil_hole : bool
        Evaluate the pin oil holes.
    mean_criterion : str
        Mean-stress combination of the fillets (:func:`checker.calc.fatigue.fillet_goodman`).
    section_loads : SectionLoads, optional
        Bending moments and web forces of another support scheme (shapes (..., T, 2, N) and
        (..., T, N)), passed to :func:`checker.calc.crank_stress.throw_nominal_stresses`.

    Returns
    -------
    ThrowGoodman
        Fillet results per web (..., T, 2), oil holes (..., T, 2) (both entries the pin's
        torque: the axis is kept for the candidate selection).

    Raises
    ------
    ValueError
        Geometry outside the validity of the throw model (for example a web thinner than the
        overlap allows), from :func:`checker.calc.crank_stress.throw_nominal_stresses`.
    """
    t_side = np.asarray(side_torque, dtype=float)
    t_pin = pin_torque(t_side, geometry["main_spacing"], geometry.get("pin_position"))
    nom = cs.throw_nominal_stresses(force_radial, force_tangential, t_pin, t_side,
                                    **geometry, oil_hole_angle=oil_hole_angle,
                                    section_loads=section_loads)
    loc = cs.local_stresses(nom, **{n: scf[n] for n in ("alpha_b", "alpha_t", "beta_b",
                                                        "beta_q", "beta_t", "gamma_b",
                                                        "gamma_t")})
    # the pin's torque, the same at both webs (..., T, 1, N)
    tau_pin = cs.torsional_stress(t_pin, geometry["pin_diameter"],
                                  geometry.get("pin_bore", 0.0))[..., None, :]
    se, su = strengths["pin fillet"]
    pin = fat.fillet_goodman(loc.sigma_pin_fillet, scf["alpha_t"] * tau_pin,
                             endurance_limit=se, ultimate_strength=su,
                             mean_criterion=mean_criterion)
    se, su = strengths["main fillet"]
    jnl = fat.fillet_goodman(loc.sigma_journal_fillet, loc.tau_journal_fillet,
                             endurance_limit=se, ultimate_strength=su,
                             mean_criterion=mean_criterion)
    oil = None
    if pin_oil_hole:
        se, su = strengths["pin oil hole"]
        one = fat.oil_hole_goodman(loc.sigma_oil_bending[..., None, :],
                                   scf["gamma_t"] * tau_pin, endurance_limit=se,
                                   ultimate_strength=su)  # (..., T, 1): evaluated once
        oil = fat.CycleFatigue(*(np.broadcast_to(x, x.shape[:-1] + (2,)) for x in one))
    return ThrowGoodman(pin, jnl, oil, nom)


def main_oil_hole_goodman(element_torque: ArrayLike, journal_diameter: float,
                          journal_bore: float, gamma_t: float, endurance_limit: float,
                          ultimate_strength: float) -> fat.CycleFatigue:
    r"""Goodman safety factor of a main-journal oil hole under torsion only.

    In the statically determinate throw model the bending moment is zero at the main journal
    centre, so the oil hole sees ``sigma_TO = gamma_T T / W_P``, ``W_P = pi/16 (D_G^4 -
    D_BG^4)/D_G`` (M53 §2.2), combined by M53's maximum principal stress (§5(4)) with zero
    bending: ``sigma_eq = (2 sqrt(9/4 sigma_TO^2)) / 3 = |sigma_TO|`` for amplitude and mean;
    Goodman ``SF = 1 / (sigma_eq,a / S_e + sigma_eq,m / S_u)``. ``gamma_T`` is M53's crank-pin
    oil-bore factor with ``d_O = D_O / D_G`` (M53 has no journal factor: an extension).

    Parameters
    ----------
    element_torque : array_like, shape (..., N) [N m]
        Torque of the element(s) the journal carries over the cycle (last axis).
    journal_diameter, journal_bore : float [m]
        D_G > 0 and the axial bore 0 <= D_BG < D_G.
    gamma_t : float [-]
        Torsional stress concentration factor of the oil hole.
    endurance_limit, ultimate_strength : float [Pa]
        S_e and S_u of the location.

    Returns
    -------
    checker.calc.fatigue.CycleFatigue
        Arrays of shape ``element_torque.shape[:-1]``.

    Examples
    --------
    A fully reversed 100 N m on a 50 mm solid journal, gamma_T = 3, S_e = 300 MPa:
    tau = 16 T / (pi D^3) = 4.074 MPa, SF = 300 / (3 x 4.074) = 24.54

    >>> t = 100.0 * np.cos(np.linspace(0, 4 * np.pi, 64, endpoint=False))
    >>> float(main_oil_hole_goodman(t, 0.05, 0.0, 3.0, 300e6, 800e6).safety_factor.round(2))
    24.54
    """
    tau = cs.torsional_stress(element_torque, journal_diameter, journal_bore)
    zero = np.zeros((1,) * np.ndim(tau))
    return fat.oil_hole_goodman(zero, gamma_t * tau, endurance_limit=endurance_limit,
                                ultimate_strength=ultimate_strength)


def m53_q(sigma_a: ArrayLike, tau_a: ArrayLike, sigma_dw: float, oil_bore: bool,
          sigma_add: float = fat.SIGMA_ADD_TRUNK_PISTON) -> tuple[np.ndarray, np.ndarray]:
    r"""IACS UR M53 equivalent alternating stress of the worst candidate and ``Q``.

    Fillets: ``sigma_V = sqrt((sigma_a + sigma_add)^2 + 3 tau_a^2)`` (M53 §5); oil bore:
    ``sigma_V = (sigma_a + 2 sqrt(sigma_a^2 + 9/4 tau_a^2)) / 3`` (M53 §5(4), ``sigma_add`` not
    applied). The largest ``sigma_V`` over the candidate axis (last: the two fillets of a
    journal, the two torque sides of an oil hole) governs; ``Q = sigma_DW / sigma_V`` (M53 §7,
    acceptable when ``Q >= 1.15``).

    Parameters
    ----------
    sigma_a, tau_a : array_like, shape (..., K) [Pa]
        Local alternating normal and shear stresses of K candidates.
    sigma_dw : float [Pa]
        M53 §6 fatigue strength of the location.
    oil_bore : bool
        Oil-bore outlet (maximum principal combination) instead of a fillet.
    sigma_add : float [Pa]
        Additional alternating bending stress of M53 §4 (fillets only).

    Returns
    -------
    (sigma_v, q) : numpy.ndarray, shape (...,) each
        [Pa] and [-].

    Examples
    --------
    Fillet, sigma_a = 50 MPa, tau_a = 20 MPa, sigma_DW = 300 MPa: sigma_V = sqrt(60^2 + 3 x
    20^2) = 69.28 MPa, Q = 4.330

    >>> sv, q = m53_q(np.array([[50e6, 10e6]]), np.array([[20e6, 0.0]]), 300e6, False)
    >>> round(float(sv[0]) / 1e6, 2), round(float(q[0]), 3)
    (69.28, 4.33)
    """
    if oil_bore:
        sv = fat.oil_bore_equivalent_stress(sigma_a, tau_a)
    else:
        sv = fat.equivalent_alternating_stress(sigma_a, tau_a, sigma_add)
    sv_max = sv.max(axis=-1)
    return sv_max, fat.m53_acceptability_factor(sigma_dw, sv_max)


def gather_candidates(results: Sequence[fat.CycleFatigue],
                      index: Sequence[Sequence[tuple[int, int]]]) -> fat.CycleFatigue:
    """The candidate results of each judged location, side by side.

    A location (a journal fillet, an oil hole...) may be governed by one of K candidates (the
    fillets on either web, the torque on either side). Item ``i`` takes, from every field of
    ``results[i]`` (shape (..., A, B)), the K entries ``index[i] = [(a, b), ...]`` of its last
    two axes (fancy indexing: no loop over speed or angle).

    Parameters
    ----------
    results : sequence of checker.calc.fatigue.CycleFatigue, length I
        Fields of shape (..., A, B) (for example (case, speed, throw, web)).
    index : sequence of length I of K (a, b) pairs

    Returns
    -------
    checker.calc.fatigue.CycleFatigue
        Fields of shape (..., I, K).

    Examples
    --------
    >>> r = fat.CycleFatigue(*[np.arange(4.0).reshape(2, 2)] * 7)
    >>> gather_candidates([r, r], [[(0, 0), (0, 1)], [(1, 1), (1, 1)]]).safety_factor.tolist()
    [[0.0, 1.0], [3.0, 3.0]]
    """
    k = len(index[0])
    lead = np.shape(results[0].safety_factor)[:-2]
    out = {f: np.empty(lead + (len(index), k)) for f in fat.CycleFatigue._fields}
    for i, (r, idx) in enumerate(zip(results, index, strict=True)):
        a_idx, b_idx = [a for a, _ in idx], [b for _, b in idx]
        for f in fat.CycleFatigue._fields:
            out[f][..., i, :] = getattr(r, f)[..., a_idx, b_idx]
    return fat.CycleFatigue(**out)


def governing_candidate(candidates: fat.CycleFatigue) -> tuple[fat.CycleFatigue, np.ndarray]:
    """The candidate with the lowest Goodman safety factor (last axis) and its index.

    Parameters
    ----------
    candidates : checker.calc.fatigue.CycleFatigue
        Fields of shape (..., K) (:func:`gather_candidates`).

    Returns
    -------
    (picked, index)
        ``picked``: the fields of the governing candidate, shape (...); ``index``: int array,
        shape (...), its position along the candidate axis.

    Examples
    --------
    >>> c = fat.CycleFatigue(*[np.array([[2.0, 1.5], [1.0, 3.0]])] * 7)
    >>> picked, k = governing_candidate(c)
    >>> picked.safety_factor.tolist(), k.tolist()
    ([1.5, 1.0], [1, 0])
    """
    worst = np.argmin(candidates.safety_factor, axis=-1)[..., None]
    picked = fat.CycleFatigue(*(np.take_along_axis(np.asarray(v), worst, -1)[..., 0]
                                for v in candidates))
    return picked, worst[..., 0]
