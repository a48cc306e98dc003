"""Nominal crankshaft stresses over the engine cycle (classical, statically determinate).

Method: IACS UR M53 §2 (as transcribed in KR RA-05-E 2025 Pt 5 Annex 5-3 §2), which is also
the concept-stage "classical stress analysis" of the Ricardo ENGDYN slides (Bell, Ricardo 2013,
'Crankshaft analysis (25)-(28)') and the Cummins "statically determinate scheme" (Cummins
crankshaft and bearing analysis process, 2002, §2): each crank throw is a beam simply supported at
the centres of its two main journals (span ``L3``) and loaded by the con-rod force at the
crankpin centre; bending moments follow from the triangular moment diagrams of the radial and
tangential force components; torsion comes from an element torque supplied by the caller.

Crank-fixed frame and signs (input convention)
----------------------------------------------
For each throw, with ``e_r`` the unit vector from the crankshaft axis to the crankpin centre,
``e_t`` the unit vector perpendicular to it in the direction of crank rotation, and the axial
coordinate ``x`` measured from the centre of the throw's *front* main journal (the main
journal with the lower number) towards its rear main journal:

* ``force_radial`` F_R [N]: component along ``e_r`` of the force applied to the crankpin by
  the con-rod (big-end bearing force on the pin), **positive outward** (pulling the pin away
  from the crank axis, e.g. reciprocating inertia near TDC, rotating big-end mass); the gas
  force near firing TDC gives F_R < 0. Any other force applied at the pin centre (the pin's own
  centrifugal force) may be added by the caller. Counterweight and web centrifugal forces are
  not part of M53's loading and are not modelled.
* ``force_tangential`` F_T [N]: component along ``e_t``, **positive in the direction of
  rotation** (driving; F_T * E is the positive torque on the crank from this cylinder).
* Adapter: with :mod:`checker.calc.crank_forces` (crank frame ``y`` = reference, ``x`` = +90 deg
  in the direction of rotation; throw ``j`` at crank-frame angle ``gamma_j`` from
  ``throw_angles``; force on the pin = ``crankpin_force(loads.big_end_crank, ...)``), use
  :func:`pin_force_in_throw_frame` to get ``(force_radial, force_tangential)``.
* torques [N*m]: element torques (mean brake torque + TV torque from the torsional model) in
  the crankpin and in the two main journals of the throw. Only their variation over the cycle
  and their mean enter the fatigue check; their sign convention is the caller's (the stresses
  carry the same sign).

Results (signed time histories, positive = tension for normal stresses)
-----------------------------------------------------------------------
* ``sigma_web_bending`` sigma_BF = K_e M_BRF / (B W^2/6), the nominal web bending stress at the
  reference section (web centre, M53 Fig 3) **on the web face towards the main journal**; the
  face towards the crankpin carries ``-sigma_BF``. Hence (free-body of the web) a gas force
  (F_R < 0) puts the crankpin-side face (pin fillet) in tension and the journal-side face
  (journal fillet) in compression. M_BRF = Q_RF * L1 with Q_RF the share of F_R carried by the
  web's main bearing.
* ``sigma_web_direct`` sigma_QF = K_e Q_RF / (B W), direct (axial) web stress from the radial
  force (compressive under gas load).
* ``tau_pin``, ``tau_journal`` = T / W_P, W_P = pi/16 (D^4 - D_b^4)/D.
* ``sigma_oil_bending`` = (M_BRO cos(phi) + M_BTO sin(phi)) / W_e, W_e = pi/32 (D^4 - D_BH^4)/D,
  the nominal bending stress of the crankpin section through the oil bore at the bore outlet;
  ``phi`` = oil-hole angle measured on the pin from ``e_r`` (the pin surface point farthest from
  the crank axis) positive in the direction of rotation ("leading"). M53's ``psi`` in
  M_BO = M_BTO cos(psi) + M_BRO sin(psi) is ``pi/2 - phi``.

The tangential force also bends the web about its strong axis and twists it; M53 does not use
these for the fillet stresses (the torque enters via the pin/journal torsion, the tangential
moment only via the oil-bore bending M_BTO). The tangential web moment at the web centre
(``moment_web_tangential`` = share of F_T * L1) is returned for reporting only.

Web and web-axis layout
-----------------------
Web quantities get an axis of length 2 inserted before the crank-angle axis: index 0 = front
web (the one next to the front main journal, x = L1), index 1 = rear web (x = L3 - L1). With
the pin centred in the bay (L2 = L3/2, the in-line case of M53 Fig 1) both webs carry the same
bending; they differ in journal torque.

References
----------
.. [1] IACS Unified Requirement M53, "Calculation of crankshafts for I.C. engines", as transcribed
   in Korean Register, "Rules for Classification of Steel Ships", 2025, Pt 5, Annex 5-3 "Guidance
   for Calculation of Crankshaft Stress", §2 (nominal stresses), §3.1, Figs 1 and 3.
.. [2] D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo, 4 February 2013, slides
   'Crankshaft analysis (25)-(28)' (classical stress analysis).
.. [3] "Cummins Crankshaft and Bearing Analysis Process", Cummins, 2002, §2 (statically determinate
   scheme).
.. [4] "Roark's Formulas for Stress and Strain" (torsion of solid and hollow circular shafts).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._checks import finite as _finite

__all__ = [
    "LocalStresses",
    "SectionLoads",
    "ThrowNominalStresses",
    "bay_bending_moment",
    "local_stresses",
    "oil_hole_bending_stress",
    "pin_force_in_throw_frame",
    "shaft_section_moduli",
    "throw_nominal_stresses",
    "torsional_stress",
    "web_centre_distance",
    "web_overlap",
    "web_section_properties",
    "web_width",
]


# ---------------------------------------------------------------------------------------------
# validation helpers




def _pos(name: str, value: float) -> float:
    v = float(value)
    if not np.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name} must be a finite value > 0, got {value!r}")
    return v


def _nonneg(name: str, value: float) -> float:
    v = float(value)
    if not np.isfinite(v) or v < 0.0:
        raise ValueError(f"{name} must be a finite value >= 0, got {value!r}")
    return v


# ---------------------------------------------------------------------------------------------
# frames and geometry


def pin_force_in_throw_frame(
    force_x: ArrayLike, force_y: ArrayLike, throw_angle: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Radial and tangential components of a crank-frame pin force for one or more throws.

    Parameters
    ----------
    force_x, force_y : array_like [N]
        Force on the crankpin in the crank-fixed frame of :mod:`checker.calc.crank_forces`
        (``y`` = reference axis, ``x`` = +90 deg in the direction of rotation), e.g. shape
        (..., n_throws, N).
    throw_angle : array_like [rad]
        Crank-frame direction ``gamma`` of each throw (from ``y`` in the direction of rotation),
        broadcast against the forces (e.g. shape (n_throws, 1)).

    Returns
    -------
    force_radial : ndarray [N]
        ``F_R = F_x sin(gamma) + F_y cos(gamma)`` (along the throw, + outward).
    force_tangential : ndarray [N]
        ``F_T = F_x cos(gamma) - F_y sin(gamma)`` (+ in the direction of rotation).
    """
    fx = _finite("force_x", force_x)
    fy = _finite("force_y", force_y)
    g = _finite("throw_angle", throw_angle)
    c, s = np.cos(g), np.sin(g)
    return fx * s + fy * c, fx * c - fy * s


def web_overlap(
    pin_diameter: ArrayLike, journal_diameter: ArrayLike, throw: ArrayLike
) -> np.ndarray:
    """Pin/journal overlap S of the crank web (IACS UR M53 §3.1).

    Parameters
    ----------
    pin_diameter : array_like [m]
        Crankpin diameter D.
    journal_diameter : array_like [m]
        Main journal diameter D_G.
    throw : array_like [m]
        Pin eccentricity E (half the stroke).

    Returns
    -------
    ndarray [m]
        ``S = (D + D_G)/2 - E``; S > 0 means the pin and journal cross-sections overlap
        (seen along the crank axis), S <= 0 means no overlap.

    Notes
    -----
    Source: IACS UR M53 §3.1 (KR RA-05-E 2025 Pt 5 Annex 5-3 §3(1)(G)). Valid for any
    positive dimensions; M53's SCFs require s = S/D <= 0.5 (checked in :mod:`checker.calc.scf`).

    Examples
    --------
    >>> round(float(web_overlap(0.048, 0.055, 0.0473)) * 1e3, 6)
    4.2
    """
    D = _finite("pin_diameter", pin_diameter)
    DG = _finite("journal_diameter", journal_diameter)
    E = _finite("throw", throw)
    if np.any(D <= 0) or np.any(DG <= 0) or np.any(E <= 0):
        raise ValueError("pin_diameter, journal_diameter and throw must be > 0")
    return (D + DG) / 2.0 - E


def web_centre_distance(
    main_spacing: float,
    main_journal_length: float,
    pin_journal_length: float,
    web_offset: float = 0.0,
) -> float:
    """Distance L1 from the main journal centre to the web centre (M53 Fig 1).

    Parameters
    ----------
    main_spacing : float [m]
        Main bearing spacing L3 (distance between adjacent main journal centres).
    main_journal_length : float [m]
        Axial length of the main journal (web face to web face).
    pin_journal_length : float [m]
        Axial length of the crankpin (web face to web face).
    web_offset : float [m]
        Axial shift of the web reference section from the geometric mid-plane of the web,
        positive towards the crankpin (Bell 2013 "web offset", 0 in the example engine).

    Returns
    -------
    float [m]
        ``L1 = L_G/2 + W_full/2 + offset`` with the full web thickness
        ``W_full = (L3 - L_G - L_H)/2`` (symmetric throw, pin centred in the bay).

    Raises
    ------
    ValueError
        If the lengths leave no web (``W_full <= 0``) or the offset moves the web centre out of
        the web.

    Notes
    -----
    Example engine (Bell, Ricardo 2013): L3 = 96, L_G = 27, L_H = 24.4 mm gives W_full = 22.3 mm
    (the
    workshop's "full width 22.3") and L1 = 24.65 mm. The interpretation of "web offset" as an axial
    shift of the reference section is this module's (Bell 2013 does not define it).
    """
    L3 = _pos("main_spacing", main_spacing)
    LG = _pos("main_journal_length", main_journal_length)
    LH = _pos("pin_journal_length", pin_journal_length)
    off = float(web_offset)
    w_full = (L3 - LG - LH) / 2.0
    if w_full <= 0.0:
        raise ValueError(
            f"main_spacing {L3} m leaves no web for journal {LG} m + pin {LH} m lengths"
        )
    if abs(off) >= w_full / 2.0:
        raise ValueError(f"|web_offset| = {abs(off)} m must be < half the web thickness")
    return LG / 2.0 + w_full / 2.0 + off


def web_width(width_min: float, width_max: float | None = None, choice: str = "min") -> float:
    """Web width B used for the web reference section (M53 Fig 3).

    Parameters
    ----------
    width_min : float [m]
        Minimum web width (drawing).
    width_max : float [m], optional
        Maximum web width (drawing).
    choice : {"min", "max", "mean"}
        ``"min"`` (default, conservative: the smallest section carries the highest nominal
        stress) or ``"max"``/``"mean"``. Use the same B for the nominal stresses and the SCFs.

    Returns
    -------
    float [m]
    """
    bmin = _pos("width_min", width_min)
    if choice == "min":
        return bmin
    if width_max is None:
        raise ValueError(f"choice={choice!r} needs width_max")
    bmax = _pos("width_max", width_max)
    if bmax < bmin:
        raise ValueError("width_max must be >= width_min")
    if choice == "max":
        return bmax
    if choice == "mean":
        return 0.5 * (bmin + bmax)
    raise ValueError(f"choice must be 'min', 'max' or 'mean', got {choice!r}")


def web_section_properties(thickness: ArrayLike, width: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Area and section modulus of the rectangular web reference section (M53 §2.1).

    Parameters
    ----------
    thickness : array_like [m]
        Web thickness W (reduced: lands removed).
    width : array_like [m]
        Web width B.

    Returns
    -------
    area : ndarray [m^2]
        ``F = B W``.
    section_modulus : ndarray [m^3]
        ``W_eqw = B W^2 / 6`` (bending in the throw plane, about the axis along B).
    """
    W = _finite("thickness", thickness)
    B = _finite("width", width)
    if np.any(W <= 0) or np.any(B <= 0):
        raise ValueError("web thickness and width must be > 0")
    return B * W, B * W**2 / 6.0


def shaft_section_moduli(
    diameter: ArrayLike, bore: ArrayLike = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Bending and polar section moduli of a (hollow) round pin or journal (M53 §2.1, §2.2).

    Parameters
    ----------
    diameter : array_like [m]
        Outer diameter D.
    bore : array_like [m]
        Axial bore diameter D_B (0 for solid), ``0 <= D_B < D``.

    Returns
    -------
    W_e : ndarray [m^3]
        ``pi/32 (D^4 - D_B^4)/D``.
    W_p : ndarray [m^3]
        ``pi/16 (D^4 - D_B^4)/D``.
    """
    D = _finite("diameter", diameter)
    Db = _finite("bore", bore)
    if np.any(D <= 0) or np.any(Db < 0) or np.any(Db >= D):
        raise ValueError("need diameter > 0 and 0 <= bore < diameter")
    k = (D**4 - Db**4) / D
    return np.pi / 32.0 * k, np.pi / 16.0 * k


def bay_bending_moment(
    force: ArrayLike, position: ArrayLike, main_spacing: float, pin_position: float | None = None
) -> np.ndarray:
    """Bending moment of a simply supported bay under a point force at the pin (M53 Fig 1).

    Parameters
    ----------
    force : array_like [N]
        Force component at the pin centre (radial or tangential), any shape.
    position : array_like [m]
        Axial position(s) x of the section, from the front main journal centre,
        ``0 <= x <= L3``; broadcast against ``force``.
    main_spacing : float [m]
        Span L3 between the two main journal centres.
    pin_position : float [m], optional
        Position L2 of the pin centre (default ``L3/2``), ``0 < L2 < L3``.

    Returns
    -------
    ndarray [N*m]
        ``M(x) = F (L3 - L2) x / L3`` for ``x <= L2`` and ``F L2 (L3 - x) / L3`` for ``x > L2``
        (triangular diagram). Sign: same as the force; a positive moment puts the pin-section
        fibre on the side the force points to in tension.
    """
    L3 = _pos("main_spacing", main_spacing)
    L2 = L3 / 2.0 if pin_position is None else float(pin_position)
    if not 0.0 < L2 < L3:
        raise ValueError(f"pin_position must lie inside the bay (0, {L3}), got {L2}")
    x = _finite("position", position)
    if np.any(x < 0.0) or np.any(x > L3):
        raise ValueError(f"position must lie in [0, {L3}] m")
    lever = np.where(x <= L2, (L3 - L2) * x / L3, L2 * (L3 - x) / L3)
    return np.asarray(force, dtype=float) * lever


def torsional_stress(torque: ArrayLike, diameter: float, bore: float = 0.0) -> np.ndarray:
    """Nominal torsional stress of a (bored) pin or journal (IACS UR M53 §2.2).

    Parameters
    ----------
    torque : array_like [N*m]
        Element torque (any shape).
    diameter : float [m]
        Crankpin diameter D or journal diameter D_G.
    bore : float [m]
        Axial bore diameter (0 for solid).

    Returns
    -------
    ndarray [Pa]
        ``tau = T / W_P``, ``W_P = pi/16 (D^4 - D_B^4)/D`` (M53 §2.2; Roark thin/solid circular
        shaft), same shape as ``torque``.
    """
    _, wp = shaft_section_moduli(diameter, bore)
    return _finite("torque", torque) / wp


def oil_hole_bending_stress(
    moment_radial: ArrayLike,
    moment_tangential: ArrayLike,
    angle: float,
    diameter: float,
    bore: float = 0.0,
) -> np.ndarray:
    """Nominal bending stress at the oil-bore outlet on the crankpin surface (M53 §2.1.2.2).

    Parameters
    ----------
    moment_radial : array_like [N*m]
        Bending moment M_BRO of the radial force component at the oil-bore section.
    moment_tangential : array_like [N*m]
        Bending moment M_BTO of the tangential force component at the same section.
    angle : float [rad]
        Oil-hole angle phi from ``e_r`` (pin surface farthest from the crank axis), positive in
        the direction of rotation.
    diameter : float [m]
        Crankpin diameter D.
    bore : float [m]
        Crankpin axial bore D_BH.

    Returns
    -------
    ndarray [Pa]
        ``sigma = (M_BRO cos(phi) + M_BTO sin(phi)) / W_e``, identical to M53's
        ``M_BO / W_e`` with ``M_BO = M_BTO cos(psi) + M_BRO sin(psi)``, ``psi = pi/2 - phi``.
    """
    we, _ = shaft_section_moduli(diameter, bore)
    phi = float(angle)
    mr = _finite("moment_radial", moment_radial)
    mt = _finite("moment_tangential", moment_tangential)
    return (mr * np.cos(phi) + mt * np.sin(phi)) / we


# ---------------------------------------------------------------------------------------------
# throw evaluation


class ThrowNominalStresses(NamedTuple):
    """Nominal loads and stresses of one or many throws (see module docstring for signs).

    Shapes: ``F = np.broadcast(force_radial, force_tangential).shape = (..., N)``;
    web quantities ``(..., 2, N)`` (front web, rear web); pin/oil-hole quantities ``(..., N)``.
    """

    overlap: float  #: S = (D + D_G)/2 - E [m]
    web_centre_distance: float  #: L1 [m]
    web_force: np.ndarray  #: Q_RF, radial force in the web, + = tension [N], (..., 2, N)
    moment_web: np.ndarray  #: M_BRF = Q_RF L1 at the web centre [N*m], (..., 2, N)
    moment_web_tangential: np.ndarray  #: tangential share * L1 (report only) [N*m]
    moment_journal_fillet: np.ndarray  #: radial-force moment at the journal fillet [N*m]
    moment_pin_fillet: np.ndarray  #: radial-force moment at the pin fillet [N*m]
    sigma_web_bending: np.ndarray  #: sigma_BF, journal-side face [Pa], (..., 2, N)
    sigma_web_direct: np.ndarray  #: sigma_QF [Pa], (..., 2, N)
    tau_pin: np.ndarray  #: crankpin nominal torsion [Pa], (..., N)
    tau_journal: np.ndarray  #: main journal nominal torsion [Pa], (..., 2, N)
    moment_oil_radial: np.ndarray  #: M_BRO [N*m], (..., N)
    moment_oil_tangential: np.ndarray  #: M_BTO [N*m], (..., N)
    sigma_oil_bending: np.ndarray  #: sigma_BO nominal at the outlet [Pa], (..., N)


def throw_nominal_stresses(
    force_radial: ArrayLike,
    force_tangential: ArrayLike,
    pin_torque: ArrayLike,
    journal_torque: ArrayLike,
    *,
    pin_diameter: float,
    journal_diameter: float,
    throw: float,
    main_spacing: float,
    main_journal_length: float,
    pin_journal_length: float,
    web_thickness: float,
    web_width: float,
    web_offset: float = 0.0,
    pin_bore: float = 0.0,
    journal_bore: float = 0.0,
    pin_position: float | None = None,
    oil_hole_angle: float = 0.0,
    oil_hole_position: float | None = None,
    k_e: float = 1.0,
    section_loads: SectionLoads | None = None,
) -> ThrowNominalStresses:
    r"""Nominal bending, direct and torsional stresses of crank throws over the cycle.

    Parameters
    ----------
    force_radial : array_like [N], shape (..., N)
        F_R, con-rod force on the crankpin along ``e_r``, + outward (module docstring).
        Leading axes are free (e.g. case x speed x throw); the last axis is crank angle.
    force_tangential : array_like [N], shape broadcastable with ``force_radial``
        F_T along ``e_t``, + in the direction of rotation.
    pin_torque : array_like [N*m], broadcastable to (..., N)
        Element torque in the crankpin (mean brake torque + TV torque); M53 §2.2 uses the most
        torsionally loaded mass point. Used for both pin fillets and the oil bore.
    journal_torque : array_like [N*m], broadcastable to (..., 2, N)
        Element torque in the front (index 0) and rear (index 1) main journal of the throw
        (pass ``T[..., None, :]`` to use one torque for both).
    pin_diameter, journal_diameter : float [m]
        D, D_G.
    throw : float [m]
        Crank radius E (half stroke).
    main_spacing : float [m]
        L3, distance between the main journal centres of the bay.
    main_journal_length, pin_journal_length : float [m]
        Axial journal and pin lengths (web face to web face); they locate the web centre and
        the fillets (:func:`web_centre_distance`).
    web_thickness : float [m]
        W at the reference section (reduced thickness, lands removed).
    web_width : float [m]
        B (see :func:`web_width`).
    web_offset : float [m]
        Axial shift of the web reference section towards the pin (default 0).
    pin_bore, journal_bore : float [m]
        Axial bores D_BH, D_BG (default solid).
    pin_position : float [m], optional
        L2, pin centre from the front main centre (default L3/2).
    oil_hole_angle : float [rad]
        Oil-hole angle phi on the pin, from ``e_r``, + in the direction of rotation.
    oil_hole_position : float [m], optional
        Axial position of the oil-bore section (default: pin centre L2).
    k_e : float [-]
        M53 empirical factor K_e: 1.0 for 4-stroke (default), 0.8 for 2-stroke engines.
    section_loads : SectionLoads, optional
        Bending moments and web forces from another support scheme (the crank as a
        continuous beam, :func:`checker.calc.crank_beam.throw_section_loads`): they replace
        the statically determinate ``Q_RF``, ``M_BRF``, the fillet moments and ``M_BRO``,
        ``M_BTO``; torsion is unchanged.

    Returns
    -------
    ThrowNominalStresses
        Signed time histories; see the class and module docstrings.

    Raises
    ------
    ValueError
        Non-finite loads, non-positive dimensions, bores >= diameters, pin/oil-hole position
        outside the bay, web centre not between the journal and pin faces.

    Notes
    -----
    Equations (IACS UR M53 §2.1-2.2; Bell, Ricardo 2013, 'Crankshaft analysis (25)' "statically
    determinate loading")::

        Q_RF,front = F_R (L3 - L2)/L3,  Q_RF,rear = F_R L2/L3
        M_BRF = Q_RF L1
        sigma_BF = K_e M_BRF / (B W^2/6),  sigma_QF = K_e Q_RF / (B W)
        tau = T / W_P,  W_P = pi/16 (D^4 - D_B^4)/D
        sigma_BO = (M_BRO cos(phi) + M_BTO sin(phi)) / W_e,  W_e = pi/32 (D^4 - D_BH^4)/D

    M53 takes alternating values X_N = (X_max - X_min)/2 of these histories; this function
    keeps the histories so that means are also available (``checker.calc.fatigue``).
    The fillet moments (``moment_journal_fillet`` at x = L_G/2, ``moment_pin_fillet`` at
    x = L2 -/+ L_H/2) are reported for information; M53's SCFs refer to the web-centre
    stresses. Validity: statically determinate bay (no load sharing between bays, rigid
    supports, no bending vibration: M53 covers those with sigma_add); in-line throws with one
    con-rod per pin (V engines: superpose both rods' forces before calling).
    """
    D = _pos("pin_diameter", pin_diameter)
    DG = _pos("journal_diameter", journal_diameter)
    E = _pos("throw", throw)
    L3 = _pos("main_spacing", main_spacing)
    LG = _pos("main_journal_length", main_journal_length)
    LH = _pos("pin_journal_length", pin_journal_length)
    W = _pos("web_thickness", web_thickness)
    B = _pos("web_width", web_width)
    DBH = _nonneg("pin_bore", pin_bore)
    DBG = _nonneg("journal_bore", journal_bore)
    ke = _pos("k_e", k_e)
    L2 = L3 / 2.0 if pin_position is None else _pos("pin_position", pin_position)
    if not L2 < L3:
        raise ValueError("pin_position must lie inside the bay")
    xO = L2 if oil_hole_position is None else _pos("oil_hole_position", oil_hole_position)

    L1 = web_centre_distance(L3, LG, LH, web_offset)
    # web centres must lie between the journal face and the pin face on each side
    if not (LG / 2.0 < L1 < L2 - LH / 2.0 and L3 - L1 > L2 + LH / 2.0):
        raise ValueError(
            f"web centre (L1 = {L1:.4g} m) not between journal and pin faces; check pin_position"
            " and lengths"
        )
    if not (L2 - LH / 2.0 <= xO <= L2 + LH / 2.0):
        raise ValueError("oil_hole_position must lie on the crankpin")

    fr = _finite("force_radial", force_radial)
    ft = _finite("force_tangential", force_tangential)
    fr, ft = np.broadcast_arrays(fr, ft)
    if fr.ndim < 1:
        raise ValueError("forces need a crank-angle axis (last axis)")
    tp = np.broadcast_to(_finite("pin_torque", pin_torque), fr.shape)
    web_shape = fr.shape[:-1] + (2, fr.shape[-1])
    tj = np.broadcast_to(_finite("journal_torque", journal_torque), web_shape)

    # share of the pin force carried through the front / rear web (reaction fractions)
    share = np.array([(L3 - L2) / L3, L2 / L3])[:, None]  # (2, 1)
    q_rf = fr[..., None, :] * share  # (..., 2, N)
    q_tf = ft[..., None, :] * share

    area, w_eqw = web_section_properties(W, B)
    moment_web = q_rf * L1
    # journal fillet at L_G/2 from its main centre, pin fillet at L2 - L_H/2 (front) or
    # L3 - L2 - L_H/2 from the rear main centre (rear)
    pin_arm = np.array([L2 - LH / 2.0, L3 - L2 - LH / 2.0])[:, None]
    moment_journal_fillet = q_rf * (LG / 2.0)
    moment_pin_fillet = q_rf * pin_arm

    _, wp_pin = shaft_section_moduli(D, DBH)
    _, wp_jnl = shaft_section_moduli(DG, DBG)
    m_bro = bay_bending_moment(fr, xO, L3, L2)
    m_bto = bay_bending_moment(ft, xO, L3, L2)
    if section_loads is not None:
        sl = section_loads
        q_rf, moment_web = np.broadcast_arrays(sl.web_force, sl.moment_web)
        moment_journal_fillet = np.asarray(sl.moment_journal_fillet)
        moment_pin_fillet = np.asarray(sl.moment_pin_fillet)
        m_bro, m_bto = np.asarray(sl.moment_oil_radial), np.asarray(sl.moment_oil_tangential)
        m_web_t = np.asarray(sl.moment_web_tangential)
    else:
        m_web_t = q_tf * L1
    return ThrowNominalStresses(
        overlap=float(web_overlap(D, DG, E)),
        web_centre_distance=L1,
        web_force=q_rf,
        moment_web=moment_web,
        moment_web_tangential=m_web_t,
        moment_journal_fillet=moment_journal_fillet,
        moment_pin_fillet=moment_pin_fillet,
        sigma_web_bending=ke * moment_web / float(w_eqw),
        sigma_web_direct=ke * q_rf / float(area),
        tau_pin=tp / float(wp_pin),
        tau_journal=tj / float(wp_jnl),
        moment_oil_radial=m_bro,
        moment_oil_tangential=m_bto,
        sigma_oil_bending=oil_hole_bending_stress(m_bro, m_bto, oil_hole_angle, D, DBH),
    )


class SectionLoads(NamedTuple):
    """Section loads of crank throws from a support scheme other than the determinate one.

    Web arrays (..., 2, N) (front/rear web), oil-bore arrays (..., N); the signs of
    :func:`throw_nominal_stresses` (``moment_web`` = M53's ``M_BRF``, ``web_force`` = its
    ``Q_RF``).
    """

    moment_web: np.ndarray  #: [N m] at the web centres (M53 reference section)
    moment_web_tangential: np.ndarray  #: [N m] of the tangential force at the web centres
    web_force: np.ndarray  #: [N] radial force carried by each web
    moment_journal_fillet: np.ndarray  #: [N m] at the journal fillets
    moment_pin_fillet: np.ndarray  #: [N m] at the pin fillets
    moment_oil_radial: np.ndarray  #: [N m] M_BRO at the oil-bore section
    moment_oil_tangential: np.ndarray  #: [N m] M_BTO at the oil-bore section


class LocalStresses(NamedTuple):
    """Local (notch) stress histories at the M53 critical locations [Pa].

    Fillet arrays have shape (..., 2, N) (front/rear web), oil-bore arrays (..., N).
    """

    sigma_pin_fillet: np.ndarray  #: alpha_B * (-sigma_BF) (crankpin-side web face)
    tau_pin_fillet: np.ndarray  #: alpha_T * tau_pin
    sigma_journal_fillet: np.ndarray  #: beta_B * sigma_BF + beta_Q * sigma_QF
    tau_journal_fillet: np.ndarray  #: beta_T * tau_journal
    sigma_oil_bending: np.ndarray  #: gamma_B * sigma_BO (M53 sigma_BO)
    sigma_oil_torsion: np.ndarray  #: gamma_T * tau_pin (M53 sigma_TO)


def local_stresses(
    nominal: ThrowNominalStresses,
    *,
    alpha_b: ArrayLike,
    alpha_t: ArrayLike,
    beta_b: ArrayLike,
    beta_q: ArrayLike,
    beta_t: ArrayLike,
    gamma_b: ArrayLike,
    gamma_t: ArrayLike,
) -> LocalStresses:
    """Fillet and oil-bore stress histories from nominal stresses and SCFs (M53 §2.1.3, §2.2.3).

    Parameters
    ----------
    nominal : ThrowNominalStresses
        Output of :func:`throw_nominal_stresses`.
    alpha_b, alpha_t, beta_b, beta_q, beta_t, gamma_b, gamma_t : array_like [-]
        Stress concentration factors (M53 empirical from :func:`checker.calc.scf.m53_scf`, or
        user-given); scalars or arrays broadcastable to the results.

    Returns
    -------
    LocalStresses
        Signed histories: ``sigma_H = alpha_B (-sigma_BF)``, ``tau_H = alpha_T tau_pin``,
        ``sigma_G = beta_B sigma_BF + beta_Q sigma_QF``, ``tau_G = beta_T tau_journal``,
        ``sigma_BO = gamma_B sigma_BO,nom``, ``sigma_TO = gamma_T tau_pin``.

    Notes
    -----
    M53 §2.1.3 writes the alternating values sigma_BH = alpha_B sigma_BFN and
    sigma_BG = beta_B sigma_BFN + beta_Q sigma_QFN; applying the (positive) factors to the
    signed histories gives the same alternating values and, in addition, a mean with the sign
    of the stress at the fillet: the pin fillet lies on the crankpin-side web face (stress
    ``-sigma_BF``), the journal fillet on the journal-side face where bending and the direct
    stress add. M53 has no direct-stress term at the crankpin fillet.
    """
    factors = {
        "alpha_b": alpha_b,
        "alpha_t": alpha_t,
        "beta_b": beta_b,
        "beta_q": beta_q,
        "beta_t": beta_t,
        "gamma_b": gamma_b,
        "gamma_t": gamma_t,
    }
    k = {}
    for name, val in factors.items():
        arr = _finite(name, val)
        if np.any(arr <= 0.0):
            raise ValueError(f"{name} must be > 0")
        k[name] = arr
    tau_pin_web = nominal.tau_pin[..., None, :]
    shape = nominal.sigma_web_bending.shape
    return LocalStresses(
        sigma_pin_fillet=-k["alpha_b"] * nominal.sigma_web_bending,
        tau_pin_fillet=np.broadcast_to(k["alpha_t"] * tau_pin_web, shape),
        sigma_journal_fillet=k["beta_b"] * nominal.sigma_web_bending
        + k["beta_q"] * nominal.sigma_web_direct,
        tau_journal_fillet=k["beta_t"] * nominal.tau_journal,
        sigma_oil_bending=k["gamma_b"] * nominal.sigma_oil_bending,
        sigma_oil_torsion=k["gamma_t"] * nominal.tau_pin,
    )
