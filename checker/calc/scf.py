"""Stress concentration factors of crankshaft fillets and oil bores (IACS UR M53).

Empirical formulae of IACS UR M53 "Calculation of crankshafts for I.C. engines", section 3
(stress concentration factors), as transcribed in Korean Register, *Rules for Classification of
Steel Ships* (2025), Pt 5 Annex 5-3 "Guidance for Calculation of Crankshaft Stress (2)", §3.
The fillet formulae come from FVV
strain-gauge investigations, the oil-bore formulae from ESDU (radially drilled holes only).

Definitions (M53 §3.1):

* ``alpha_B``, ``beta_B``: maximum von Mises stress in the crankpin / journal fillet under
  bending divided by the nominal web bending stress ``sigma_BFN = M_BRFN / (B W^2 / 6)``;
* ``beta_Q``: maximum von Mises stress in the journal fillet due to the radial force divided by
  the nominal web compressive stress ``sigma_QFN = Q_RFN / (B W)``;
* ``alpha_T``, ``beta_T``: maximum equivalent shear stress in the fillet divided by the nominal
  torsional stress of the (bored) crankpin / journal ``tau_N = M_T / W_P``;
* ``gamma_B``, ``gamma_T``: maximum principal stress at the crankpin oil-bore outlet divided by
  the nominal bending / torsional stress of the bored crankpin.

Validity (M53 §3.1 table) is checked and returned as boolean flags: out-of-range values are
still computed (M53 requires FEM per its Appendix III/VI or measurements in that case; the
caller reports it), except where M53 itself prescribes a substitution (``s < -0.5`` and
``f(recess) < 1``), which is applied and flagged. User-given factors override these values in
the caller, not here.

Coefficient note: the KR transcription prints ``-0.85 b^3`` in ``f(b)`` of ``alpha_T`` and
``-1.527 w^2`` in ``f_B(s, w)`` of ``beta_B``; ``-0.857`` and ``-1.5276`` are taken as the
IACS values (recalled, not yet checked against the IACS document). This module uses 0.857
and 1.5276 (module constants below); with 0.85, ``alpha_T`` is about 2 % higher.

References
----------
.. [1] IACS Unified Requirement M53, "Calculation of crankshafts for I.C. engines", as transcribed
   in Korean Register, "Rules for Classification of Steel Ships", 2025, Pt 5, Annex 5-3 "Guidance
   for Calculation of Crankshaft Stress", §3 (stress concentration factors; fillet formulae from
   FVV, oil bore from ESDU).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._checks import non_negative as _non_negative
from ._checks import positive as _positive

__all__ = [
    "ALPHA_T_FB_CUBIC",
    "BETA_B_FSW_QUADRATIC",
    "VALIDITY",
    "M53SCF",
    "m53_ratios",
    "m53_scf",
]

#: Cubic coefficient of f(b) in alpha_T (IACS value, unverified; KR copy prints 0.85).
ALPHA_T_FB_CUBIC = 0.857
#: w^2 coefficient of the first bracket of f_B(s, w) in beta_B (KR copy prints 1.527).
BETA_B_FSW_QUADRATIC = 1.5276

#: M53 §3.1 validity ranges of the related dimensions: name -> (low, high); None = unbounded.
VALIDITY: dict[str, tuple[float | None, float | None]] = {
    "r_pin": (0.03, 0.13),
    "r_journal": (0.03, 0.13),
    "r_journal_torsion": (0.03, 0.13),
    "s": (None, 0.5),
    "w": (0.2, 0.8),
    "b": (1.1, 2.2),
    "d_O": (0.0, 0.2),
    "d_G": (0.0, 0.8),
    "d_H": (0.0, 0.8),
}

_S_LOW_EXTENSION = -0.5  # M53 §3.1: s < -0.5 -> f(s,w), f(r,s) evaluated at s = -0.5


class M53Ratios(NamedTuple):
    """Related dimensions of M53 §3.1 (all dimensionless)."""

    r_pin: np.ndarray  #: R_H / D
    r_journal: np.ndarray  #: R_G / D (journal bending/compression factors use D, per M53)
    r_journal_torsion: np.ndarray  #: R_G / D_G (beta_T when sizes differ)
    s: np.ndarray  #: S / D, S = (D + D_G)/2 - E
    w: np.ndarray  #: W / D (overlap) or W_red / D (no overlap)
    b: np.ndarray  #: B / D
    d_O: np.ndarray  #: D_O / D
    d_G: np.ndarray  #: D_BG / D
    d_H: np.ndarray  #: D_BH / D
    t_H: np.ndarray  #: T_H / D
    t_G: np.ndarray  #: T_G / D


class M53SCF(NamedTuple):
    """Result of :func:`m53_scf`.

    Every factor is an ndarray of the broadcast geometry shape (0-d for scalar input).
    ``flags`` maps a check name to a boolean array, True where the check fired:
    ``"<ratio>_out_of_range"`` for each entry of :data:`VALIDITY`, ``"s_clipped"`` (s < -0.5
    replaced by -0.5 in f(s,w) and f(r,s)), ``"journal_s_extrapolated"`` (s < -0.5 for the
    journal factors, for which M53 states no extension; evaluated at s = -0.5 as well),
    ``"recess_clipped"`` (f(recess) < 1 replaced by 1), ``"<factor>_invalid"`` (the formula
    gave a non-positive fillet factor far outside the validity range; the factor is returned
    as NaN so that it cannot be used unnoticed: supply FEM or user-given factors) and
    ``"beta_t_equal_to_alpha_t"`` (informational: M53 §3.3(C)(a) applied). ``messages`` lists
    human-readable texts for the checks that fired (informational flag excluded).
    """

    alpha_b: np.ndarray
    alpha_t: np.ndarray
    beta_b: np.ndarray
    beta_q: np.ndarray
    beta_t: np.ndarray
    gamma_b: np.ndarray
    gamma_t: np.ndarray
    ratios: M53Ratios
    flags: dict[str, np.ndarray]
    messages: list[str]

    @property
    def in_range(self) -> np.ndarray:
        """True where no validity check fired (informational flags ignored)."""
        fired = [v for k, v in self.flags.items() if k != "beta_t_equal_to_alpha_t"]
        return ~np.logical_or.reduce(fired)








def m53_ratios(
    *,
    pin_diameter: ArrayLike,
    journal_diameter: ArrayLike,
    throw: ArrayLike,
    web_thickness: ArrayLike,
    web_width: ArrayLike,
    pin_fillet_radius: ArrayLike,
    journal_fillet_radius: ArrayLike,
    pin_recess: ArrayLike = 0.0,
    journal_recess: ArrayLike = 0.0,
    pin_bore: ArrayLike = 0.0,
    journal_bore: ArrayLike = 0.0,
    oil_hole_diameter: ArrayLike = 0.0,
) -> M53Ratios:
    """Related dimensions r, s, w, b, d_O, d_G, d_H, t_H, t_G of IACS UR M53 §3.1.

    Parameters
    ----------
    pin_diameter : array_like [m]
        Crankpin diameter D.
    journal_diameter : array_like [m]
        Main journal diameter D_G.
    throw : array_like [m]
        Pin eccentricity E (half stroke).
    web_thickness : array_like [m]
        Web thickness W at the reference section (use the reduced thickness, lands removed).
    web_width : array_like [m]
        Web width B at the reference section.
    pin_fillet_radius, journal_fillet_radius : array_like [m]
        Fillet radii R_H, R_G.
    pin_recess, journal_recess : array_like [m]
        Fillet recesses T_H, T_G: depth by which the fillet is sunk into the web face (axial).
        A radial undercut into the pin/journal surface is not an M53 parameter.
    pin_bore, journal_bore : array_like [m]
        Axial bore diameters D_BH, D_BG (0 for solid).
    oil_hole_diameter : array_like [m]
        Crankpin oil-bore diameter D_O (0 if none).

    Returns
    -------
    M53Ratios
        ``s = S/D`` with the overlap ``S = (D + D_G)/2 - E``; ``w = W/D`` if ``S > 0``, else
        ``W_red/D`` with ``W_red = W - max(T_H - R_H, 0)`` (M53 §3.1, Fig 3).

    Raises
    ------
    ValueError
        For non-positive diameters/lengths, negative radii/recesses/bores, bores not smaller
        than their shaft, or an oil hole not smaller than the pin.

    Notes
    -----
    Source: IACS UR M53 §3.1 (KR RA-05-E 2025 Pt 5 Annex 5-3 §3(1)(G)).
    """
    D = _positive("pin_diameter", pin_diameter)
    DG = _positive("journal_diameter", journal_diameter)
    E = _positive("throw", throw)
    W = _positive("web_thickness", web_thickness)
    B = _positive("web_width", web_width)
    RH = _positive("pin_fillet_radius", pin_fillet_radius)
    RG = _positive("journal_fillet_radius", journal_fillet_radius)
    TH = _non_negative("pin_recess", pin_recess)
    TG = _non_negative("journal_recess", journal_recess)
    DBH = _non_negative("pin_bore", pin_bore)
    DBG = _non_negative("journal_bore", journal_bore)
    DO = _non_negative("oil_hole_diameter", oil_hole_diameter)
    if np.any(DBH >= D):
        raise ValueError("pin_bore must be smaller than pin_diameter")
    if np.any(DBG >= DG):
        raise ValueError("journal_bore must be smaller than journal_diameter")
    if np.any(DO >= D):
        raise ValueError("oil_hole_diameter must be smaller than pin_diameter")

    S = (D + DG) / 2.0 - E
    W_red = W - np.maximum(TH - RH, 0.0)
    if np.any(W_red <= 0.0):
        raise ValueError("reduced web thickness W - (T_H - R_H) must be > 0")
    w = np.where(S > 0.0, W, W_red) / D
    return M53Ratios(
        r_pin=RH / D,
        r_journal=RG / D,
        r_journal_torsion=RG / DG,
        s=S / D,
        w=w,
        b=B / D,
        d_O=DO / D,
        d_G=DBG / D,
        d_H=DBH / D,
        t_H=TH / D,
        t_G=TG / D,
    )


def _f_recess(t_h: np.ndarray, t_g: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    f = 1.0 + (t_h + t_g) * (1.8 + 3.2 * s)
    clipped = f < 1.0
    return np.where(clipped, 1.0, f), clipped


def _alpha_t_like(r: np.ndarray, s_c: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
    """0.8 f(r,s) f(b) f(w) of M53 §3.2(B) (also beta_T, §3.3(C)(b))."""
    f_rs = r ** (-0.322 + 0.1015 * (1.0 - s_c))
    f_b = 7.8955 - 10.654 * b + 5.3482 * b**2 - ALPHA_T_FB_CUBIC * b**3
    f_w = w ** (-0.145)
    return 0.8 * f_rs * f_b * f_w


def _range_flag(name: str, value: np.ndarray, messages: list[str]) -> np.ndarray:
    low, high = VALIDITY[name]
    flag = np.zeros(np.shape(value), dtype=bool)
    if low is not None:
        flag |= value < low
    if high is not None:
        flag |= value > high
    if np.any(flag):
        lo = "-inf" if low is None else f"{low:g}"
        hi = "+inf" if high is None else f"{high:g}"
        bad = value[flag] if np.ndim(value) else value
        messages.append(
            f"M53 {name} = {np.min(bad):.4g}"
            + (f"..{np.max(bad):.4g}" if np.size(bad) > 1 else "")
            + f" outside validity range [{lo}, {hi}] (IACS UR M53 §3.1): empirical SCF computed"
            " but to be confirmed by FEM (M53 Appendix III/VI) or measurement"
        )
    return flag


def m53_scf(
    *,
    pin_diameter: ArrayLike,
    journal_diameter: ArrayLike,
    throw: ArrayLike,
    web_thickness: ArrayLike,
    web_width: ArrayLike,
    pin_fillet_radius: ArrayLike,
    journal_fillet_radius: ArrayLike,
    pin_recess: ArrayLike = 0.0,
    journal_recess: ArrayLike = 0.0,
    pin_bore: ArrayLike = 0.0,
    journal_bore: ArrayLike = 0.0,
    oil_hole_diameter: ArrayLike = 0.0,
) -> M53SCF:
    r"""Empirical stress concentration factors of IACS UR M53 §3.2-3.4 with validity flags.

    Parameters
    ----------
    pin_diameter : array_like [m]
        Crankpin diameter D.
    journal_diameter : array_like [m]
        Main journal diameter D_G.
    throw : array_like [m]
        Pin eccentricity E (half stroke).
    web_thickness : array_like [m]
        Web thickness W (reduced thickness at the reference section).
    web_width : array_like [m]
        Web width B at the reference section.
    pin_fillet_radius, journal_fillet_radius : array_like [m]
        Fillet radii R_H, R_G.
    pin_recess, journal_recess : array_like [m]
        Fillet recesses into the web T_H, T_G (default 0).
    pin_bore, journal_bore : array_like [m]
        Axial bore diameters D_BH, D_BG (default 0, solid).
    oil_hole_diameter : array_like [m]
        Radial crankpin oil-bore diameter D_O (default 0).

    Returns
    -------
    M53SCF
        Factors ``alpha_b, alpha_t, beta_b, beta_q, beta_t, gamma_b, gamma_t`` [-], the
        ratios, validity ``flags`` (boolean arrays) and ``messages``.

    Notes
    -----
    Equations (IACS UR M53 §3.2-3.4)::

        alpha_B = 2.6914 f(s,w) f(w) f(b) f(r) f(d_G) f(d_H) f(recess)
        alpha_T = 0.8 f(r,s) f(b) f(w)
        beta_B  = 2.7146 f_B(s,w) f_B(w) f_B(b) f_B(r) f_B(d_G) f_B(d_H) f(recess)
        beta_Q  = 3.0128 f_Q(s) f_Q(w) f_Q(b) f_Q(r) f_Q(d_H) f(recess)
        beta_T  = alpha_T if D = D_G and R_H = R_G, else alpha_T evaluated with r = R_G/D_G
        gamma_B = 3 - 5.88 d_O + 34.6 d_O^2
        gamma_T = 4 - 6 d_O + 30 d_O^2
        f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s)

    Journal bending/compression factors use ``r = R_G/D`` (crankpin diameter), as M53 §3.1.

    Validity (M53 §3.1): 0.03 <= r <= 0.13, s <= 0.5, 0.2 <= w <= 0.8, 1.1 <= b <= 2.2,
    0 <= d_O <= 0.2, 0 <= d_G, d_H <= 0.8. Out of range: computed and flagged. M53 extension
    of the low range of s: f(recess) < 1 is set to 1; for s < -0.5, f(s,w) and f(r,s) are
    evaluated with s = -0.5 (both flagged). M53 states the s-extension only for these two
    functions; for s < -0.5 the journal functions f_B(s,w) and f_Q(s) (quadratics in s that
    turn negative) are also evaluated at s = -0.5 and flagged ``journal_s_extrapolated``.
    The oil-bore factors are valid for radially drilled holes only.

    Examples
    --------
    >>> k = m53_scf(pin_diameter=0.3, journal_diameter=0.32, throw=0.25, web_thickness=0.1,
    ...             web_width=0.44, pin_fillet_radius=0.015, journal_fillet_radius=0.015,
    ...             oil_hole_diameter=0.03)
    >>> round(float(k.alpha_b), 3), bool(k.in_range)
    (2.183, True)
    """
    q = m53_ratios(
        pin_diameter=pin_diameter,
        journal_diameter=journal_diameter,
        throw=throw,
        web_thickness=web_thickness,
        web_width=web_width,
        pin_fillet_radius=pin_fillet_radius,
        journal_fillet_radius=journal_fillet_radius,
        pin_recess=pin_recess,
        journal_recess=journal_recess,
        pin_bore=pin_bore,
        journal_bore=journal_bore,
        oil_hole_diameter=oil_hole_diameter,
    )
    s, w, b = q.s, q.w, q.b
    s_clipped = s < _S_LOW_EXTENSION
    s_c = np.maximum(s, _S_LOW_EXTENSION)
    f_rec, rec_clipped = _f_recess(q.t_H, q.t_G, s)

    # --- crankpin fillet, bending (M53 §3.2(A))
    u = 1.0 - s_c
    f_sw = (
        -4.1883
        + 29.2004 * w
        - 77.5925 * w**2
        + 91.9454 * w**3
        - 40.0416 * w**4
        + u * (9.5440 - 58.3480 * w + 159.3415 * w**2 - 192.5846 * w**3 + 85.2916 * w**4)
        + u**2 * (-3.8399 + 25.0444 * w - 70.5571 * w**2 + 87.0328 * w**3 - 39.1832 * w**4)
    )
    f_w = 2.1790 * w**0.7171
    f_b = 0.6840 - 0.0077 * b + 0.1473 * b**2
    f_r = 0.2081 * q.r_pin ** (-0.5231)
    f_dg = 0.9993 + 0.27 * q.d_G - 1.0211 * q.d_G**2 + 0.5306 * q.d_G**3
    f_dh = 0.9978 + 0.3145 * q.d_H - 1.5241 * q.d_H**2 + 2.4147 * q.d_H**3
    alpha_b = 2.6914 * f_sw * f_w * f_b * f_r * f_dg * f_dh * f_rec

    # --- crankpin fillet, torsion (M53 §3.2(B))
    alpha_t = _alpha_t_like(q.r_pin, s_c, b, w)

    # --- journal fillet, bending (M53 §3.3(A)); s clipped as for the pin (flagged separately)
    fb_sw = (
        -1.7625
        + 2.9821 * w
        - BETA_B_FSW_QUADRATIC * w**2
        + u * (5.1169 - 5.8089 * w + 3.1391 * w**2)
        + u**2 * (-2.1567 + 2.3297 * w - 1.2952 * w**2)
    )
    fb_w = 2.2422 * w**0.7548
    fb_b = 0.5616 + 0.1197 * b + 0.1176 * b**2
    fb_r = 0.1908 * q.r_journal ** (-0.5568)
    fb_dg = 1.0012 - 0.6441 * q.d_G + 1.2265 * q.d_G**2
    fb_dh = 1.0022 - 0.1903 * q.d_H + 0.0073 * q.d_H**2
    beta_b = 2.7146 * fb_sw * fb_w * fb_b * fb_r * fb_dg * fb_dh * f_rec

    # --- journal fillet, compression by the radial force (M53 §3.3(B))
    fq_s = 0.4368 + 2.1630 * u - 1.5212 * u**2
    fq_w = w / (0.0637 + 0.9369 * w)
    fq_b = -0.5 + b
    fq_r = 0.5331 * q.r_journal ** (-0.2038)
    fq_dh = 0.9937 - 1.1949 * q.d_H + 1.7373 * q.d_H**2
    beta_q = 3.0128 * fq_s * fq_w * fq_b * fq_r * fq_dh * f_rec

    # --- journal fillet, torsion (M53 §3.3(C))
    D = np.asarray(pin_diameter, dtype=float)
    DG = np.asarray(journal_diameter, dtype=float)
    same = np.isclose(D, DG, rtol=1e-12, atol=0.0) & np.isclose(
        np.asarray(pin_fillet_radius, dtype=float),
        np.asarray(journal_fillet_radius, dtype=float),
        rtol=1e-12,
        atol=0.0,
    )
    beta_t = np.where(same, alpha_t, _alpha_t_like(q.r_journal_torsion, s_c, b, w))

    # --- oil bore outlet (M53 §3.4)
    gamma_b = 3.0 - 5.88 * q.d_O + 34.6 * q.d_O**2
    gamma_t = 4.0 - 6.0 * q.d_O + 30.0 * q.d_O**2

    # --- validity
    messages: list[str] = []
    flags: dict[str, np.ndarray] = {}
    for name in ("r_pin", "r_journal", "s", "w", "b", "d_O", "d_G", "d_H"):
        flags[f"{name}_out_of_range"] = _range_flag(name, getattr(q, name), messages)
    # r = R_G/D_G only matters when beta_T is not taken equal to alpha_T
    rjt = np.where(same, q.r_pin, q.r_journal_torsion)
    flags["r_journal_torsion_out_of_range"] = _range_flag("r_journal_torsion", rjt, messages)
    flags["s_clipped"] = s_clipped
    flags["journal_s_extrapolated"] = s_clipped.copy()
    flags["recess_clipped"] = rec_clipped
    flags["beta_t_equal_to_alpha_t"] = same
    if np.any(s_clipped):
        messages.append(
            f"M53 s = {np.min(s):.4g} < -0.5: f(s,w) and f(r,s) evaluated with s = -0.5 "
            "(IACS UR M53 §3.1 extension); journal f_B(s,w), f_Q(s) also evaluated at s = -0.5,"
            " an extrapolation M53 does not state: confirm journal SCFs by FEM"
        )
    if np.any(rec_clipped):
        messages.append(
            "M53 f(recess) < 1 set to 1 (IACS UR M53 §3.1 extension of the low range of s)"
        )
    fillet = {
        "alpha_b": alpha_b,
        "alpha_t": alpha_t,
        "beta_b": beta_b,
        "beta_q": beta_q,
        "beta_t": beta_t,
    }
    for key, val in fillet.items():
        bad = ~(val > 0.0)
        flags[f"{key}_invalid"] = bad
        if np.any(bad):
            messages.append(
                f"M53 formula gives a non-positive {key} (min {np.min(val):.4g}) for this "
                "geometry, far outside the validity range: returned as NaN; use FEM or "
                "user-given factors"
            )
            fillet[key] = np.where(bad, np.nan, val)
    alpha_b, alpha_t, beta_b, beta_q, beta_t = (fillet[k] for k in fillet)
    shape = np.broadcast(alpha_b, beta_t, gamma_b).shape
    flags = {k: np.broadcast_to(v, shape).copy() for k, v in flags.items()}
    return M53SCF(
        alpha_b=np.asarray(alpha_b),
        alpha_t=np.asarray(alpha_t),
        beta_b=np.asarray(beta_b),
        beta_q=np.asarray(beta_q),
        beta_t=np.asarray(beta_t),
        gamma_b=np.asarray(gamma_b),
        gamma_t=np.asarray(gamma_t),
        ratios=q,
        flags=flags,
        messages=messages,
    )
