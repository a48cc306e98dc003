"""Crankshaft fatigue: cycle amplitudes/means, equivalent stresses, Goodman and IACS M53 checks.

Two assessments are provided; they are **not** equivalent criteria:

1. **Goodman safety factor** (the Ricardo ENGDYN classical-stress output, Bell, Ricardo 2013,
   'Crankshaft analysis (25)-(28)': "Goodman fatigue safety factor ... minimum safety factor
   of 1.5 at all load/speed conditions"): per critical point, the alternating and mean values
   of the local stress histories over one working cycle, combined into equivalent alternating
   and mean stresses, then ``SF = 1 / (sigma_eq,a / S_e + sigma_eq,m / S_u)`` (proportional
   overload).
2. **IACS UR M53 acceptability** ``Q = sigma_DW / sigma_V >= 1.15`` with alternating stresses
   only (means neglected), ``sigma_V = sqrt((sigma_BH + sigma_add)^2 + 3 tau_H^2)`` and the M53
   fatigue strength formula (M53 §5-7).

Stress criteria chosen for the Goodman check (and why)
------------------------------------------------------
* Amplitude and mean of each component are the half range and mid value of its history over
  the cycle, ``X_a = (X_max - X_min)/2``, ``X_m = (X_max + X_min)/2`` (M53 §2.1.2: "X_N =
  +-1/2 [X_max - X_min]").
* **Equivalent alternating stress = von Mises of the component amplitudes**,
  ``sigma_eq,a = sqrt((sigma_a + sigma_add)^2 + 3 tau_a^2)``: the same combination as M53 §5
  (bending and torsion assumed in phase with peaks at the same point), consistent with the
  von Mises definition of the fillet SCFs alpha_B, beta_B, beta_Q (M53 §3.1); conservative for
  out-of-phase loading.
* **Equivalent mean stress = signed von Mises** (default), ``sigma_eq,m = sign(sigma_m)
  sqrt(sigma_m^2 + 3 tau_m^2)`` with sign(0) = +. It keeps the mean shear from the brake
  torque (the Cummins process combines the mean nominal shear from the brake power with the
  amplitude, Cummins crankshaft and bearing analysis process, 2002 §2.1, and the Bell, Ricardo 2013
  slides note torsion matters most at oil holes),
  while a compressive normal mean is not counted as tensile. Compressive equivalent means are
  **not credited** by default (clipped to 0) because the Goodman line is not validated on the
  compressive side. Alternatives: ``"normal"`` (Sines-type: only the normal mean acts; mean
  torsion is known to have little effect on ductile steels, less conservative) and
  ``"von_mises"`` (unsigned, most conservative).
* Oil-bore outlet: M53's maximum-principal combination (§5(4)) is applied to the amplitudes
  and, with signs, to the means.

References
----------
.. [1] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013, slides
   'Crankshaft analysis (25)-(28)' (Goodman safety factor >= 1.5, worked fatigue strengths).
.. [2] IACS Unified Requirement M53, "Calculation of crankshafts for I.C. engines", as transcribed
   in Korean Register, "Rules for Classification of Steel Ships", 2025, Pt 5, Annex 5-3 "Guidance
   for Calculation of Crankshaft Stress", §2-7 (acceptability factor Q >= 1.15).
.. [3] "Cummins Crankshaft and Bearing Analysis Process", Cummins, 2002, §2.1 (mean shear from the
   brake torque).
.. [4] R. G. Budynas, J. K. Nisbett, "Shigley's Mechanical Engineering Design", 10th ed.,
   McGraw-Hill, 2015, eq. 6-46 (Goodman line).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._checks import finite as _finite
from ._checks import non_negative as _non_negative
from ._checks import positive as _positive

__all__ = [
    "GOODMAN_SF_MIN",
    "M53_Q_MIN",
    "SIGMA_ADD_CROSSHEAD",
    "SIGMA_ADD_TRUNK_PISTON",
    "CycleFatigue",
    "M53FatigueStrength",
    "amplitude_and_mean",
    "equivalent_alternating_stress",
    "equivalent_mean_stress",
    "fatigue_strength",
    "fillet_goodman",
    "goodman_line",
    "goodman_safety_factor",
    "m53_acceptability_factor",
    "m53_fatigue_strength",
    "oil_bore_equivalent_stress",
    "oil_hole_goodman",
]

#: Minimum Goodman safety factor at all load/speed conditions (Bell, Ricardo 2013,
#: 'Crankshaft analysis (28)').
GOODMAN_SF_MIN = 1.5
#: Minimum M53 acceptability factor Q (IACS UR M53 §7; KR Annex 5-3 App. V §3(3)).
M53_Q_MIN = 1.15
#: M53 §4 additional alternating bending stress, trunk-piston engines [Pa].
SIGMA_ADD_TRUNK_PISTON = 10.0e6
#: M53 §4 additional alternating bending stress, crosshead engines [Pa].
SIGMA_ADD_CROSSHEAD = 30.0e6

_MEAN_CRITERIA = ("signed_von_mises", "normal", "von_mises")








# ---------------------------------------------------------------------------------------------
# cycle values and equivalent stresses


def amplitude_and_mean(history: ArrayLike, axis: int = -1) -> tuple[np.ndarray, np.ndarray]:
    """Alternating (half range) and mean (mid value) of a history over one cycle.

    Parameters
    ----------
    history : array_like [any unit, e.g. Pa]
        Values over the working cycle along ``axis`` (crank angle, last axis by default).
    axis : int
        Crank-angle axis.

    Returns
    -------
    amplitude : ndarray
        ``(max - min)/2`` (IACS UR M53 §2.1.2, "X_N = +-1/2 [X_max - X_min]").
    mean : ndarray
        ``(max + min)/2``.

    Notes
    -----
    Peak picking on the sampled grid: with a crank-angle step ``h`` the error of max/min is
    O(h^2) for smooth histories (see ``benchmarks/bench_fatigue.py``).
    """
    x = _finite("history", history)
    hi = np.max(x, axis=axis)
    lo = np.min(x, axis=axis)
    return 0.5 * (hi - lo), 0.5 * (hi + lo)


def equivalent_alternating_stress(
    sigma_a: ArrayLike, tau_a: ArrayLike, sigma_add: ArrayLike = 0.0
) -> np.ndarray:
    """Von Mises equivalent alternating stress of in-phase bending and torsion (M53 §5.2).

    Parameters
    ----------
    sigma_a : array_like [Pa]
        Alternating normal (bending) stress at the fillet, >= 0.
    tau_a : array_like [Pa]
        Alternating shear (torsional) stress at the fillet, >= 0.
    sigma_add : array_like [Pa]
        M53 additional alternating bending stress (§4: 10 MPa trunk-piston, 30 MPa crosshead;
        0 for a plain von Mises amplitude).

    Returns
    -------
    ndarray [Pa]
        ``sigma_V = sqrt((sigma_a + sigma_add)^2 + 3 tau_a^2)`` (IACS UR M53 §5(2)-(3)).
    """
    sa = _non_negative("sigma_a", sigma_a)
    ta = _non_negative("tau_a", tau_a)
    add = _non_negative("sigma_add", sigma_add)
    return np.sqrt((sa + add) ** 2 + 3.0 * ta**2)


def equivalent_mean_stress(
    sigma_m: ArrayLike, tau_m: ArrayLike, criterion: str = "signed_von_mises"
) -> np.ndarray:
    """Equivalent mean stress for the Goodman check.

    Parameters
    ----------
    sigma_m : array_like [Pa]
        Mean normal stress (signed, tension positive).
    tau_m : array_like [Pa]
        Mean shear stress (sign irrelevant).
    criterion : {"signed_von_mises", "normal", "von_mises"}
        ``"signed_von_mises"`` (default): ``sign(sigma_m) sqrt(sigma_m^2 + 3 tau_m^2)`` with
        sign(0) = +; ``"normal"``: ``sigma_m`` (Sines-type, mean shear ignored);
        ``"von_mises"``: ``sqrt(sigma_m^2 + 3 tau_m^2)`` (unsigned).

    Returns
    -------
    ndarray [Pa]

    Notes
    -----
    Choice and rationale in the module docstring; these are common practice, for which no
    primary source is cited here.
    """
    sm = _finite("sigma_m", sigma_m)
    tm = _finite("tau_m", tau_m)
    if criterion == "normal":
        return np.broadcast_to(sm, np.broadcast(sm, tm).shape).astype(float)
    vm = np.sqrt(sm**2 + 3.0 * tm**2)
    if criterion == "von_mises":
        return vm
    if criterion == "signed_von_mises":
        return np.where(sm < 0.0, -vm, vm)
    raise ValueError(f"criterion must be one of {_MEAN_CRITERIA}, got {criterion!r}")


def oil_bore_equivalent_stress(sigma_bending: ArrayLike, sigma_torsion: ArrayLike) -> np.ndarray:
    """Equivalent (maximum principal) stress at the crankpin oil-bore outlet (M53 §5(4)).

    Parameters
    ----------
    sigma_bending : array_like [Pa]
        sigma_BO = gamma_B sigma_BON (amplitude >= 0, or a signed mean).
    sigma_torsion : array_like [Pa]
        sigma_TO = gamma_T tau_N (sign irrelevant).

    Returns
    -------
    ndarray [Pa]
        ``sigma_V = 1/3 sigma_BO [1 + 2 sqrt(1 + 9/4 (sigma_TO/sigma_BO)^2)]``, evaluated as
        ``(sigma_BO + 2 sqrt(sigma_BO^2 + 9/4 sigma_TO^2))/3`` which has no singularity at
        sigma_BO = 0 (limit ``|sigma_TO|``) and equals M53's form for sigma_BO > 0.
    """
    sb = _finite("sigma_bending", sigma_bending)
    st = _finite("sigma_torsion", sigma_torsion)
    return (sb + 2.0 * np.sqrt(sb**2 + 2.25 * st**2)) / 3.0


# ---------------------------------------------------------------------------------------------
# Goodman


def goodman_safety_factor(
    sigma_a: ArrayLike,
    sigma_m: ArrayLike,
    endurance_limit: ArrayLike,
    ultimate_strength: ArrayLike,
    credit_compressive_mean: bool = False,
) -> np.ndarray:
    """Goodman fatigue safety factor under proportional overload.

    Parameters
    ----------
    sigma_a : array_like [Pa]
        (Equivalent) alternating stress, >= 0.
    sigma_m : array_like [Pa]
        (Equivalent) mean stress, signed.
    endurance_limit : array_like [Pa]
        Fully reversed fatigue strength S_e at the location (e.g. Bell, Ricardo 2013: pin
        fillet 619 MPa).
    ultimate_strength : array_like [Pa]
        Tensile strength S_u at the location (e.g. Bell, Ricardo 2013: fillet UTS 920 MPa).
    credit_compressive_mean : bool
        If False (default) a compressive mean is set to 0 (the factor is then S_e/sigma_a).

    Returns
    -------
    ndarray [-]
        ``SF = 1 / (sigma_a/S_e + sigma_m/S_u)``; ``inf`` where the denominator is <= 0 (no
        alternating load and a non-tensile mean), never NaN.

    Notes
    -----
    Goodman relation, 1/n = sigma_a/S_e + sigma_m/S_u (e.g. Shigley's Mechanical Engineering
    Design, 10th ed., eq. 6-46). Points on the line
    ``sigma_a = S_e (1 - sigma_m/S_u)`` give SF = 1; scaling both stresses by k divides SF by
    k. Valid for 0 <= sigma_m <= S_u (tensile side; yield is not checked here).
    """
    sa = _non_negative("sigma_a", sigma_a)
    sm = _finite("sigma_m", sigma_m)
    se = _positive("endurance_limit", endurance_limit)
    su = _positive("ultimate_strength", ultimate_strength)
    if not credit_compressive_mean:
        sm = np.maximum(sm, 0.0)
    denom = sa / se + sm / su
    with np.errstate(divide="ignore"):
        return np.where(denom > 0.0, 1.0 / np.where(denom > 0.0, denom, 1.0), np.inf)


def goodman_line(
    sigma_m: ArrayLike,
    endurance_limit: ArrayLike,
    ultimate_strength: ArrayLike,
    safety_factor: ArrayLike = 1.0,
) -> np.ndarray:
    """Alternating stress on the Goodman (Haigh diagram) line for a given safety factor.

    Parameters
    ----------
    sigma_m : array_like [Pa]
        Mean stress.
    endurance_limit, ultimate_strength : array_like [Pa]
        S_e, S_u.
    safety_factor : array_like [-]
        n >= 1 for a design line (default 1, the failure line).

    Returns
    -------
    ndarray [Pa]
        ``sigma_a = S_e (1/n - sigma_m/S_u)`` for ``0 <= sigma_m <= S_u/n``; S_e/n for
        compressive means (no credit, consistent with :func:`goodman_safety_factor`); 0 beyond
        ``S_u/n``. Points ``(sigma_m, sigma_a)`` with 0 <= sigma_m <= S_u/n give SF = n.
    """
    sm = _finite("sigma_m", sigma_m)
    se = _positive("endurance_limit", endurance_limit)
    su = _positive("ultimate_strength", ultimate_strength)
    n = _positive("safety_factor", safety_factor)
    return se * np.clip(1.0 / n - np.maximum(sm, 0.0) / su, 0.0, None)


class CycleFatigue(NamedTuple):
    """Cycle values and Goodman result at one kind of location (shapes: history minus axis)."""

    sigma_a: np.ndarray  #: alternating normal stress [Pa]
    sigma_m: np.ndarray  #: mean normal stress [Pa]
    tau_a: np.ndarray  #: alternating shear (or torsion-induced) stress [Pa]
    tau_m: np.ndarray  #: mean shear stress [Pa]
    sigma_eq_a: np.ndarray  #: equivalent alternating stress [Pa]
    sigma_eq_m: np.ndarray  #: equivalent mean stress [Pa]
    safety_factor: np.ndarray  #: Goodman SF [-]


def fillet_goodman(
    sigma_history: ArrayLike,
    tau_history: ArrayLike,
    *,
    endurance_limit: ArrayLike,
    ultimate_strength: ArrayLike,
    sigma_add: ArrayLike = 0.0,
    mean_criterion: str = "signed_von_mises",
    credit_compressive_mean: bool = False,
    axis: int = -1,
) -> CycleFatigue:
    """Goodman safety factor at a fillet from local bending and torsion histories.

    Parameters
    ----------
    sigma_history : array_like [Pa]
        Local normal stress at the fillet over the cycle (e.g.
        :attr:`checker.calc.crank_stress.LocalStresses.sigma_pin_fillet`).
    tau_history : array_like [Pa]
        Local shear stress at the fillet, broadcastable to ``sigma_history``.
    endurance_limit, ultimate_strength : array_like [Pa]
        S_e and S_u at the fillet.
    sigma_add : array_like [Pa]
        Additional alternating bending stress added to the amplitude (M53 §4); default 0.
    mean_criterion : str
        See :func:`equivalent_mean_stress`.
    credit_compressive_mean : bool
        See :func:`goodman_safety_factor`.
    axis : int
        Crank-angle axis.

    Returns
    -------
    CycleFatigue
        Amplitudes, means, equivalent stresses and SF, with the crank-angle axis removed.

    Notes
    -----
    ``sigma_eq,a = sqrt((sigma_a + sigma_add)^2 + 3 tau_a^2)`` (M53 §5),
    ``sigma_eq,m`` per ``mean_criterion``, ``SF = 1/(sigma_eq,a/S_e + sigma_eq,m/S_u)``.
    """
    s, t = np.broadcast_arrays(
        _finite("sigma_history", sigma_history), _finite("tau_history", tau_history)
    )
    sa, sm = amplitude_and_mean(s, axis)
    ta, tm = amplitude_and_mean(t, axis)
    eq_a = equivalent_alternating_stress(sa, ta, sigma_add)
    eq_m = equivalent_mean_stress(sm, tm, mean_criterion)
    sf = goodman_safety_factor(
        eq_a, eq_m, endurance_limit, ultimate_strength, credit_compressive_mean
    )
    return CycleFatigue(sa, sm, ta, tm, eq_a, eq_m, sf)


def oil_hole_goodman(
    sigma_bending_history: ArrayLike,
    sigma_torsion_history: ArrayLike,
    *,
    endurance_limit: ArrayLike,
    ultimate_strength: ArrayLike,
    credit_compressive_mean: bool = False,
    axis: int = -1,
) -> CycleFatigue:
    """Goodman safety factor at the crankpin oil-bore outlet.

    Parameters
    ----------
    sigma_bending_history : array_like [Pa]
        gamma_B * sigma_BO history (``LocalStresses.sigma_oil_bending``).
    sigma_torsion_history : array_like [Pa]
        gamma_T * tau_N history (``LocalStresses.sigma_oil_torsion``).
    endurance_limit, ultimate_strength : array_like [Pa]
        S_e and S_u at the oil bore (Bell 2013 example: pin oil hole 326 MPa).
    credit_compressive_mean : bool
        See :func:`goodman_safety_factor`.
    axis : int
        Crank-angle axis.

    Returns
    -------
    CycleFatigue
        ``tau_*`` fields hold the sigma_TO amplitude/mean; equivalent stresses use
        :func:`oil_bore_equivalent_stress` (M53 §5(4)) on amplitudes and on signed means.
    """
    b, t = np.broadcast_arrays(
        _finite("sigma_bending_history", sigma_bending_history),
        _finite("sigma_torsion_history", sigma_torsion_history),
    )
    ba, bm = amplitude_and_mean(b, axis)
    ta, tm = amplitude_and_mean(t, axis)
    eq_a = oil_bore_equivalent_stress(ba, ta)
    eq_m = oil_bore_equivalent_stress(bm, tm)
    sf = goodman_safety_factor(
        eq_a, eq_m, endurance_limit, ultimate_strength, credit_compressive_mean
    )
    return CycleFatigue(ba, bm, ta, tm, eq_a, eq_m, sf)


# ---------------------------------------------------------------------------------------------
# fatigue strength


def fatigue_strength(
    base_strength: ArrayLike,
    size_factor: ArrayLike = 1.0,
    surface_factor: ArrayLike = 1.0,
    treatment_factor: ArrayLike = 1.0,
) -> np.ndarray:
    """Local fatigue strength as base strength times modifying factors.

    Parameters
    ----------
    base_strength : array_like [Pa]
        Base infinite-life (fully reversed) strength, e.g. 0.5 x UTS (Bell 2013 example: 375 MPa).
    size_factor, surface_factor, treatment_factor : array_like [-]
        Multiplicative factors (Bell 2013 example: size 0.868 pin / 0.858 main; rolled fillet 1.9,
        induction-hardened oil hole 1.0). Treatment factors are user data: M53 accepts
        surface-treatment gains only from tests (M53 Appendix V).

    Returns
    -------
    ndarray [Pa]
        ``S_e = S_base k_size k_surface k_treatment`` (Bell, Ricardo 2013, 'Crankshaft analysis
        (26)': 375 x 0.868 x 1.9 =
        618 MPa, printed as 619).
    """
    return (
        _positive("base_strength", base_strength)
        * _positive("size_factor", size_factor)
        * _positive("surface_factor", surface_factor)
        * _positive("treatment_factor", treatment_factor)
    )


class M53FatigueStrength(NamedTuple):
    """Result of :func:`m53_fatigue_strength`."""

    value: np.ndarray  #: sigma_DW [Pa]
    radius_clipped: np.ndarray  #: True where the radius was raised to 2 mm (M53 §6)


def m53_fatigue_strength(
    ultimate_strength: ArrayLike,
    diameter: ArrayLike,
    radius: ArrayLike,
    k: ArrayLike = 1.05,
) -> M53FatigueStrength:
    """Fatigue strength sigma_DW of IACS UR M53 §6.

    Parameters
    ----------
    ultimate_strength : array_like [Pa]
        Minimum tensile strength sigma_B of the crankshaft material.
    diameter : array_like [m]
        Crankpin diameter D (pin fillet and oil bore) or journal diameter D_G (journal fillet).
    radius : array_like [m]
        R_X: fillet radius R_H or R_G, or half the oil-bore diameter D_O/2.
    k : array_like [-]
        K: 1.05 continuous-grain-flow / drop forged (default), 1.0 free-form forged, 0.93 cast
        steel with approved fillet cold rolling. Values > 1 apply to fillets only (use 1.0 for
        the oil bore).

    Returns
    -------
    M53FatigueStrength
        ``value`` [Pa] and ``radius_clipped`` (bool array).

    Notes
    -----
    IACS UR M53 §6 (KR Annex 5-3 §6(1)-(2)), sigma_B in N/mm^2, D and
    R_X in mm::

        sigma_DW = K (0.42 sigma_B + 39.3) [0.264 + 1.073 D^-0.2 + (785 - sigma_B)/4900
                   + (196/sigma_B) sqrt(1/R_X)]

    with R_X taken not less than 2 mm (applied and flagged). Surface-treated fillets and oil
    bores: M53 Appendix V (not covered here).
    """
    sb = _positive("ultimate_strength", ultimate_strength) / 1e6
    d_mm = _positive("diameter", diameter) * 1e3
    r_mm = _positive("radius", radius) * 1e3
    kk = _positive("k", k)
    clipped = r_mm < 2.0
    r_eff = np.maximum(r_mm, 2.0)
    s_dw = (
        kk
        * (0.42 * sb + 39.3)
        * (
            0.264
            + 1.073 * d_mm ** (-0.2)
            + (785.0 - sb) / 4900.0
            + 196.0 / sb * np.sqrt(1.0 / r_eff)
        )
    )
    shape = np.broadcast(s_dw, clipped).shape
    return M53FatigueStrength(
        value=np.broadcast_to(s_dw * 1e6, shape).copy(),
        radius_clipped=np.broadcast_to(clipped, shape).copy(),
    )


def m53_acceptability_factor(sigma_dw: ArrayLike, sigma_v: ArrayLike) -> np.ndarray:
    """IACS UR M53 acceptability factor Q = sigma_DW / sigma_V (required >= 1.15).

    Parameters
    ----------
    sigma_dw : array_like [Pa]
        Fatigue strength (:func:`m53_fatigue_strength`, or from tests per M53 App. IV).
    sigma_v : array_like [Pa]
        Equivalent alternating stress (:func:`equivalent_alternating_stress` with sigma_add,
        or :func:`oil_bore_equivalent_stress`), >= 0.

    Returns
    -------
    ndarray [-]
        Q; ``inf`` where sigma_V = 0. Compare with :data:`M53_Q_MIN`.

    Notes
    -----
    IACS UR M53 §7 (acceptability criteria), Q >= 1.15 at crankpin fillet, journal fillet and
    oil-bore outlet.
    """
    dw = _positive("sigma_dw", sigma_dw)
    sv = _non_negative("sigma_v", sigma_v)
    with np.errstate(divide="ignore"):
        return np.where(sv > 0.0, dw / np.where(sv > 0.0, sv, 1.0), np.inf)
