r"""Torsional stiffness of one crank throw from its dimensions, fitted to a 3D FE model.

Definition (the project's crank geometry, docs/crank-geometry.md, "Throw stiffness"): the
stiffness between the mid-planes of the throw's two main journals (half journal, web, pin,
web, half journal), one mid-plane face fixed against rotation about the crank axis, the other
turned rigidly about it; both journal centres held in x and y as the main bearings hold them,
the faces free to tilt and to move axially; stiffness = reaction torque / angle. (Faces held
axially as well make the throw much stiffer: +85 % on the I4 throw of Bell 2013.)

Model: a series of the journal's and pin's torsion and the two webs' in-plane bending (the
structure of Carter's and Ker Wilson's equivalent lengths), with five coefficients fitted to
the linear-elastic 3D FE solutions of ``scripts/throw_fe.py`` (stored with the geometry in
``data/throw_stiffness_fe.csv``; coefficients in ``data/throw_stiffness.json``, both written
by ``scripts/make_throw_stiffness.py``):

.. math::

    \frac{1}{k} = \frac{L_j}{G J_j} + \frac{c_j D_j}{G J_{j0}} + \frac{L_p}{G J_p}
        + \frac{c_p D_p}{G J_{p0}}
        + 2\,c_w\,\frac{12\,(R - c_s (D_j + D_p)/2)}{E\,t_w}\,
          \frac{B'_j + B'_p}{2 B'^2_j B'^2_p},
    \qquad B'_j = D_j + \eta (B_j - D_j),\; B'_p = D_p + \eta (B_p - D_p)

with :math:`J = \pi (D^4 - d^4)/32` of journal and pin (:math:`J_0` without the bore),
:math:`G = E / (2 (1 + \nu))`. The web term is the in-plane bending of a web whose effective
width varies linearly from :math:`B'_j` to :math:`B'_p` over the effective length
:math:`R - c_s (D_j + D_p)/2` (:math:`\int dy / b^3` of the linear taper; the web beyond the
journal or pin counts with the fitted factor :math:`\eta`); :math:`c_j D_j` and :math:`c_p D_p`
are the extra equivalent lengths at the journal-web and pin-web junctions (Ker Wilson's
0.4 D; the fit favours the solid section there: the web, not the bore, governs the
spreading). Counterweights are not a term: fused with the webs they change the FE stiffness
by less than 1 % (I4 throw with a 150 deg sector to 85 mm radius: +0.2 %); the samples include
them and the stated error covers them. The classical formulas are the same series with fixed
coefficients: Carter (1928) and Ker Wilson (1956) as usually quoted [1]_ [2]_
(:func:`carter_stiffness`, :func:`ker_wilson_stiffness`).

Accuracy against the FE of the same geometry, 98 throws over the fitted range (64 of a Sobol
sequence and 10 extreme corners used by the fit, 24 of a Latin hypercube held out): max 2.6 %
(corners), hold-out max 1.5 %, mean 0.7 %; fitted on the Sobol throws alone the model is
within 3.2 % of the corners, so the form, not the fit, sets the error. The FE's own
discretisation error at the samples' mesh is below 0.5 % and systematic (the samples are
0.12-0.26 % above a mesh of two-thirds the size; convergence study in
``benchmarks/bench_throw_fe.py``). The stated model error, ``ThrowStiffness.model_error``,
is their sum rounded up: 3.5 %. The model is smooth and monotone in every dimension (positive
coefficients; the web's effective length stays above half the crank radius over the range,
R - c_s (Dj + Dp)/2 >= 0.579 R).

Outside the range, where the pin comes to lie largely within the journal in the end view
(``R < 2 c_s (Dj + Dp)/2``), the web's effective length ``l_w = R - c_s (Dj + Dp)/2`` would
fall below half the crank radius and, below ``R = c_s (Dj + Dp)/2``, turn negative: a thinner
web would give a stiffer throw and the stiffness could turn negative. There the length
continues as ``l_w' = (R/2) exp(2 l_w / R - 1)`` (:func:`web_length`): equal in value and
slope at ``l_w = R/2``, positive, increasing in R and falling in Dj and Dp, tending to zero
(rigid webs: the throw a stepped shaft) as the pin's axis approaches the journal's. The model
is then smooth, positive and monotone in every dimension over every geometry; the
continuation is not fitted (no sample lies there), so such a throw is outside the range and
reported so (:attr:`ThrowStiffness.outside`).

On the I4 throw of Bell (2013) (idealised: solid, web width 75.7 mm): FE 518.8, this model
520.7, Carter 506, Ker Wilson 486 kN m/rad (published FE of the real crank, with lightening
and fillets: 403.3).

References
----------
.. [1] B. C. Carter, "An empirical formula for crankshaft stiffness in torsion",
   Engineering 126, 1928, p. 36.
.. [2] W. Ker Wilson, "Practical Solution of Torsional Vibration Problems", vol. 1, 3rd ed.,
   Chapman & Hall, 1956 (equivalent lengths of crank throws).
"""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ._checks import non_negative, positive

__all__ = [
    "COEF_FILE",
    "SAMPLES_FILE",
    "RANGE",
    "ThrowStiffness",
    "throw_torsional_stiffness",
    "throw_compliance_terms",
    "carter_stiffness",
    "ker_wilson_stiffness",
]

DATA = Path(__file__).resolve().parent / "data"
COEF_FILE = DATA / "throw_stiffness.json"
"""Fitted coefficients, range and errors (``scripts/make_throw_stiffness.py fit``)."""
SAMPLES_FILE = DATA / "throw_stiffness_fe.csv"
"""The FE samples the coefficients were fitted on (``scripts/make_throw_stiffness.py fe``)."""

RANGE = {
    "Dp/Dj": (0.75, 1.0),
    "S/Dj": (-0.15, 0.30),
    "tw/Dj": (0.2, 0.5),
    "Bj/Dj": (1.2, 1.8),
    "Bp/Dp": (1.2, 1.8),
    "Lj/Dj": (0.35, 0.6),
    "Lp/Dp": (0.35, 1.5),
    "dj/Dj": (0.0, 0.6),
    "dp/Dp": (0.0, 0.6),
    "nu": (0.27, 0.31),
    "cw_ro/(R+Dp/2)": (0.95, 1.25),
    "cw_angle": (np.radians(120.0), np.radians(180.0)),
    "cw_t/tw": (0.6, 1.0),
}
"""Range of the FE samples' dimensionless groups (S = (Dj + Dp)/2 - R; the counterweight
groups only where there is a counterweight). ``in_range`` checks the groups the model uses
(:data:`MODEL_GROUPS`)."""

_RANGE_TOL = 1e-6

MODEL_GROUPS = ("Dp/Dj", "S/Dj", "tw/Dj", "Bj/Dj", "Bp/Dp", "Lj/Dj", "Lp/Dp", "dj/Dj", "dp/Dp",
                "nu")
"""The groups of :data:`RANGE` the model's terms use; the counterweight groups bound the
samples only (the stiffness has no counterweight term), so they do not flag a value."""

_GROUP_TEXT = {"S/Dj": "overlap S/Dj", "nu": "Poisson's ratio"}

WEB_KNEE = 0.5
"""Fraction of the crank radius below which the web's effective length continues
exponentially (:func:`web_length`); over the fitted range it is at least 0.579 R."""


@dataclass(frozen=True)
class ThrowStiffness:
    """Result of :func:`throw_torsional_stiffness`."""

    stiffness: np.ndarray
    """Torsional stiffness between the journal mid-planes [N m/rad], per throw."""
    in_range: np.ndarray
    """True where every group the model uses is inside the fitted range (:data:`RANGE`,
    :data:`MODEL_GROUPS`)."""
    method: str
    """Method and source, for the report."""
    model_error: float
    """Stated relative error against the 3D FE over the fitted range."""
    outside: tuple[str, ...] = ()
    """Per throw, the model's groups outside the fitted range with their values and ranges
    (``""`` inside it), for the caller's warning."""


@functools.cache
def _coefficients() -> dict:
    with COEF_FILE.open(encoding="utf-8") as f:
        return json.load(f)


def _groups(Dj, dj, Lj, Dp, dp, Lp, tw, Bj, Bp, R, nu, ri, ro, alpha, tc) -> dict:
    cw = tc > 0
    return {
        "Dp/Dj": Dp / Dj, "S/Dj": ((Dj + Dp) / 2 - R) / Dj, "tw/Dj": tw / Dj,
        "Bj/Dj": Bj / Dj, "Bp/Dp": Bp / Dp, "Lj/Dj": Lj / Dj, "Lp/Dp": Lp / Dp,
        "dj/Dj": dj / Dj, "dp/Dp": dp / Dp, "nu": nu,
        "cw_ro/(R+Dp/2)": np.where(cw, ro / (R + Dp / 2), 1.0),
        "cw_angle": np.where(cw, alpha, np.radians(150.0)),
        "cw_t/tw": np.where(cw, tc / tw, 0.8),
    }


def web_length(R: ArrayLike, inset: ArrayLike) -> np.ndarray:
    r"""Effective length of a web's in-plane bending [m]: ``R - inset`` (``inset`` =
    ``c_s (Dj + Dp)/2``) down to ``WEB_KNEE R``, below it the continuation
    ``WEB_KNEE R exp((R - inset)/(WEB_KNEE R) - 1)`` (module docstring; C1 at the knee,
    positive, increasing in R and falling with ``inset``)."""
    R = np.asarray(R, dtype=float)
    lw = R - np.asarray(inset, dtype=float)
    knee = WEB_KNEE * R
    below = knee * np.exp(np.minimum(lw / knee - 1.0, 0.0))
    return np.where(lw >= knee, lw, below)


def _outside(groups: dict) -> tuple[str, ...]:
    """Per throw, the model's groups outside :data:`RANGE`, with value and range."""
    n = len(next(iter(groups.values())))
    texts: list[list[str]] = [[] for _ in range(n)]
    for name in MODEL_GROUPS:
        lo, hi = RANGE[name]
        g = np.asarray(groups[name], dtype=float)
        for i in np.flatnonzero((g < lo - _RANGE_TOL) | (g > hi + _RANGE_TOL)):
            texts[i].append(f"{_GROUP_TEXT.get(name, name)} {g[i]:.3g} (fitted {lo:g}..{hi:g})")
    return tuple(", ".join(t) for t in texts)


def throw_compliance_terms(coef: dict, *, Dj, dj, Lj, Dp, dp, Lp, tw, Bj, Bp, R, E, nu,
                           ri, ro, alpha, tc) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The three compliances of the series [rad/(N m)]: journal, pin, two webs (see module
    docstring; ``coef`` holds ``c_j, c_p, c_w, c_s, eta``)."""
    G = E / (2 * (1 + nu))
    Jj = np.pi * (Dj**4 - dj**4) / 32
    Jp = np.pi * (Dp**4 - dp**4) / 32
    c_j = Lj / (G * Jj) + coef["c_j"] * Dj / (G * np.pi * Dj**4 / 32)
    c_p = Lp / (G * Jp) + coef["c_p"] * Dp / (G * np.pi * Dp**4 / 32)
    lw = web_length(R, coef["c_s"] * (Dj + Dp) / 2)
    bj = Dj + coef["eta"] * (Bj - Dj)
    bp = Dp + coef["eta"] * (Bp - Dp)
    c_w = 2 * coef["c_w"] * 12 * lw / (E * tw) * (bj + bp) / (2 * bj**2 * bp**2)
    return c_j, c_p, c_w


def throw_torsional_stiffness(*, journal_diameter: ArrayLike, journal_bore: ArrayLike,
                              journal_length: ArrayLike, pin_diameter: ArrayLike,
                              pin_bore: ArrayLike, pin_length: ArrayLike,
                              web_thickness: ArrayLike, web_width_journal: ArrayLike,
                              web_width_pin: ArrayLike, crank_radius: ArrayLike,
                              youngs_modulus: ArrayLike, poisson_ratio: ArrayLike,
                              cw_inner_radius: ArrayLike = 0.0, cw_outer_radius: ArrayLike = 0.0,
                              cw_angle: ArrayLike = 0.0, cw_thickness: ArrayLike = 0.0,
                              ) -> ThrowStiffness:
    r"""Torsional stiffness of crank throws between their main-journal mid-planes.

    Series of journal torsion, pin torsion and web in-plane bending with coefficients fitted
    to a linear-elastic 3D FE of the same geometry (module docstring: equation, definition,
    sources). Vectorised: every argument broadcasts (one value per throw).

    Parameters
    ----------
    journal_diameter, journal_bore, journal_length : array_like [m]
        Main journal Dj, its concentric bore dj (0 = solid) and its full length Lj (the throw
        holds half of each of its two journals).
    pin_diameter, pin_bore, pin_length : array_like [m]
        Crank pin Dp, bore dp (0 = solid) and length Lp between the webs.
    web_thickness : array_like [m]
        Axial thickness tw of each web.
    web_width_journal, web_width_pin : array_like [m]
        Diameters Bj, Bp of the web outline's circles about the main and the pin axis (the
        outline is their convex hull).
    crank_radius : array_like [m]
        R = stroke / 2.
    youngs_modulus : array_like [Pa]
    poisson_ratio : array_like [-]
    cw_inner_radius, cw_outer_radius : array_like [m]
        Counterweight annular sector about the main axis (bisected by -y, opposite the pin).
    cw_angle : array_like [rad]
        Included angle of the counterweight sector.
    cw_thickness : array_like [m]
        Axial thickness of the counterweight, centred on its web (0 = no counterweight).

    Returns
    -------
    ThrowStiffness
        ``stiffness`` [N m/rad], ``in_range`` (inside the fitted range :data:`RANGE`),
        ``method``, ``model_error``, ``outside`` (the groups outside it, per throw).

    Raises
    ------
    ValueError
        Non-positive dimensions, a bore not smaller than its diameter, a web narrower than its
        journal or pin, a counterweight with outer radius not above its inner radius.

    Notes
    -----
    Valid for the fitted range :data:`RANGE` (Dp/Dj 0.75-1.0; overlap S/Dj -0.15..0.30 with
    S = (Dj + Dp)/2 - R; tw/Dj 0.2-0.5; Bj/Dj, Bp/Dp 1.2-1.8; Lj/Dj 0.35-0.6; Lp/Dp
    0.35-1.5; bores up to 0.6 D; counterweights of 120-180 deg, outer radius 0.95-1.25
    (R + Dp/2), thickness 0.6-1.0 tw; nu 0.27-0.31). Outside it the value is the same
    physically based series (smooth, positive, monotone; the web's length continued below
    R/2, :func:`web_length`), ``in_range`` is False and ``outside`` names the groups: the
    caller warns. The counterweight groups bound the samples, not the model (it has no
    counterweight term): they do not flag a value.
    Fillets, undercuts and oil holes are not part of the solid.

    Examples
    --------
    The I4 of Bell (2013), idealised (solid, web width 75.7 mm at both circles):

    >>> r = throw_torsional_stiffness(journal_diameter=0.055, journal_bore=0.0,
    ...     journal_length=0.027, pin_diameter=0.048, pin_bore=0.0, pin_length=0.0244,
    ...     web_thickness=0.0223, web_width_journal=0.0757, web_width_pin=0.0757,
    ...     crank_radius=0.0473, youngs_modulus=210e9, poisson_ratio=0.2995)
    >>> round(float(r.stiffness[0]) / 1e3, -1), bool(r.in_range[0])
    (520.0, True)
    """
    Dj = positive("journal_diameter", journal_diameter)
    dj = non_negative("journal_bore", journal_bore)
    Lj = positive("journal_length", journal_length)
    Dp = positive("pin_diameter", pin_diameter)
    dp = non_negative("pin_bore", pin_bore)
    Lp = positive("pin_length", pin_length)
    tw = positive("web_thickness", web_thickness)
    Bj = positive("web_width_journal", web_width_journal)
    Bp = positive("web_width_pin", web_width_pin)
    R = positive("crank_radius", crank_radius)
    E = positive("youngs_modulus", youngs_modulus)
    nu = positive("poisson_ratio", poisson_ratio)
    ri = non_negative("cw_inner_radius", cw_inner_radius)
    ro = non_negative("cw_outer_radius", cw_outer_radius)
    alpha = non_negative("cw_angle", cw_angle)
    tc = non_negative("cw_thickness", cw_thickness)
    (Dj, dj, Lj, Dp, dp, Lp, tw, Bj, Bp, R, E, nu, ri, ro, alpha, tc) = np.broadcast_arrays(
        *(np.atleast_1d(a) for a in (Dj, dj, Lj, Dp, dp, Lp, tw, Bj, Bp, R, E, nu, ri, ro,
                                     alpha, tc)))
    if np.any(dj >= Dj):
        raise ValueError("journal_bore must be smaller than journal_diameter")
    if np.any(dp >= Dp):
        raise ValueError("pin_bore must be smaller than pin_diameter")
    if np.any(Bj < Dj):
        raise ValueError("web_width_journal must not be smaller than journal_diameter")
    if np.any(Bp < Dp):
        raise ValueError("web_width_pin must not be smaller than pin_diameter")
    if np.any(nu >= 0.5):
        raise ValueError("poisson_ratio must be below 0.5")
    cw = tc > 0
    if np.any(cw & ((ro <= ri) | (alpha <= 0) | (alpha > 2 * np.pi))):
        raise ValueError("a counterweight needs cw_outer_radius > cw_inner_radius and "
                         "0 < cw_angle <= 2 pi")
    coef = _coefficients()
    parts = throw_compliance_terms(coef["coefficients"], Dj=Dj, dj=dj, Lj=Lj, Dp=Dp, dp=dp,
                                   Lp=Lp, tw=tw, Bj=Bj, Bp=Bp, R=R, E=E, nu=nu, ri=ri, ro=ro,
                                   alpha=alpha, tc=tc)
    k = 1.0 / (parts[0] + parts[1] + parts[2])
    outside = _outside(_groups(Dj, dj, Lj, Dp, dp, Lp, tw, Bj, Bp, R, nu, ri, ro, alpha, tc))
    ok = np.array([not o for o in outside], dtype=bool)
    err = float(coef["model_error"])
    method = (f"series of journal and pin torsion and web in-plane bending (after Carter 1928, "
              f"Ker Wilson 1956) fitted to a linear-elastic 3D FE of the throw "
              f"({coef['n_samples']} geometries, within {100 * err:g} %)")
    return ThrowStiffness(stiffness=k, in_range=ok, method=method, model_error=err,
                          outside=outside)


def _classical_inputs(Dj, dj, Lj, Dp, dp, Lp, tw, B, R, G):
    return [np.asarray(a, dtype=float) for a in (Dj, dj, Lj, Dp, dp, Lp, tw, B, R, G)]


def carter_stiffness(Dj, Lj, Dp, Lp, tw, B, R, G) -> np.ndarray:
    """Carter's (1928) empirical throw stiffness as usually quoted [N m/rad] (solid
    journal and pin; ``B`` web width): ``k = G pi Dj^4 / (32 Le)``,
    ``Le = (Lj + 0.8 tw) + 0.75 Lp (Dj/Dp)^4 + 1.5 R Dj^4 / (tw B^3)``. For comparison."""
    Dj, Lj, Dp, Lp, tw, B, R, G = (np.asarray(a, dtype=float)
                                   for a in (Dj, Lj, Dp, Lp, tw, B, R, G))
    le = (Lj + 0.8 * tw) + 0.75 * Lp * (Dj / Dp) ** 4 + 1.5 * R * Dj**4 / (tw * B**3)
    return G * np.pi * Dj**4 / (32 * le)


def ker_wilson_stiffness(Dj, dj, Lj, Dp, dp, Lp, tw, B, R, G) -> np.ndarray:
    """Ker Wilson's (1956) throw stiffness as usually quoted [N m/rad]: ``k = G pi Dj^4 /
    (32 Le)``, ``Le = Dj^4 [(Lj + 0.4 Dj)/(Dj^4 - dj^4) + (Lp + 0.4 Dp)/(Dp^4 - dp^4)
    + (R - 0.2 (Dj + Dp)) / (tw B^3)]``. For comparison."""
    Dj, dj, Lj, Dp, dp, Lp, tw, B, R, G = _classical_inputs(Dj, dj, Lj, Dp, dp, Lp, tw, B, R, G)
    le = Dj**4 * ((Lj + 0.4 * Dj) / (Dj**4 - dj**4) + (Lp + 0.4 * Dp) / (Dp**4 - dp**4)
                  + (R - 0.2 * (Dj + Dp)) / (tw * B**3))
    return G * np.pi * Dj**4 / (32 * le)
