"""Mass properties of a crank throw described by its main dimensions (pure NumPy, SI).

Geometry (issue 33; docs/crank-geometry.md): crank axis ``z``, main (journal) axis at
``x = y = 0``, crank-pin axis at ``(0, R)`` with ``R`` = stroke / 2. A throw runs between the
mid-planes of its two main journals, along ``z`` from the front mid-plane (``z = 0``)::

    half journal (Lj/2) | web (tw) | pin (Lp) | web (tw) | half journal (Lj/2)

* journal: cylinder of diameter ``Dj`` about the main axis, concentric bore ``dj`` through its
  own length only; pin: cylinder ``Dp`` about the pin axis, bore ``dp``;
* web: a prismatic slab of thickness ``tw`` whose outline is the convex hull of a circle of
  diameter ``Bj`` ("web width at journal") about the main axis and a circle of diameter ``Bp``
  ("web width at pin") about the pin axis;
* counterweight (optional): an annular sector about the main axis, radii ``ri..ro``, included
  angle ``alpha``, bisected by ``-y`` (opposite the pin), axial thickness ``tc`` centred on its
  web's mid-plane, fused with the web: the solid is the union of the two prisms, their common
  part counted once (with the web: the counterweight's mass is what it adds to the web).

Every part is symmetric about the plane ``x = 0``, so its mass centre lies at ``x = 0``; the
functions return the mass, the mass centre ``(y, z)`` and the polar moment of inertia about the
main axis and about the part's own centre of mass (axis parallel to ``z``):
``J_own = J_main - m y_c^2`` (parallel-axis theorem).

Methods (all exact for the stated geometry):

* cylinders: ``m = rho pi (D^2 - d^2) L / 4``, ``J = m (D^2 + d^2) / 8`` about their own axis,
  plus ``m R^2`` for the pin about the main axis (any text on rigid-body dynamics, e.g.
  Meriam & Kraige, Engineering Mechanics: Dynamics, Appendix B);
* web outline: the exact decomposition of the convex hull of two circles into the journal-side
  circular sector (angle ``pi + 2 beta``, bisected by ``-y``), the pin-side sector (angle
  ``pi - 2 beta``, bisected by ``+y``) and the hexagon between the two centres and the four
  tangent points, ``sin beta = (Bj - Bp) / (2 R)``; sector moments in closed form, the hexagon's
  by Green's theorem on its edges (the shoelace formulas);
* counterweight: the annular sector in closed form, ``A = alpha (ro^2 - ri^2) / 2``,
  ``int y dA = -2 sin(alpha/2) (ro^3 - ri^3) / 3``, ``int r^2 dA = alpha (ro^4 - ri^4) / 4``,
  minus its overlap with the web outline, integrated in polar coordinates about the main axis
  over ``ri <= r <= min(ro, r_web(theta))``: ``r_web`` is analytic between the break angles
  (tangent points, where ``r_web`` crosses ``ri`` or ``ro``, the sector's edges), each interval
  integrated by 32-point Gauss-Legendre quadrature, exact to rounding for these smooth
  integrands (tests: the closed form where the overlap is an annular sector, a convergence
  check and an independent Monte Carlo integration).

References
----------
.. [1] J. L. Meriam, L. G. Kraige, "Engineering Mechanics: Dynamics", Wiley, Appendix B (mass
   moments of inertia of cylinders; parallel-axis theorem).
.. [2] W. D. Pilkey, "Analysis and Design of Elastic Beams", Wiley, 2002, ch. 1 (area moments
   of a plane outline by boundary integrals, Green's theorem).
.. [3] M. Abramowitz, I. A. Stegun, "Handbook of Mathematical Functions", 1964, sec. 25.4.29
   (Gauss-Legendre quadrature).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._checks import finite, non_negative, positive

PARTS = ("front journal", "front web", "front counterweight", "pin", "rear web",
         "rear counterweight", "rear journal")
"""The parts of a throw, front to rear (the last axis of :class:`ThrowMassProperties`)."""

_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(32)


@dataclass(frozen=True)
class PlaneMoments:
    """Area moments of a plane outline symmetric about ``x = 0``: area ``A`` [m^2], first
    moment ``Sy = int y dA`` [m^3] and polar moment ``Jo = int (x^2 + y^2) dA`` [m^4] about the
    origin (the main axis)."""

    area: np.ndarray
    first_y: np.ndarray
    polar: np.ndarray


@dataclass(frozen=True)
class ThrowMassProperties:
    """Mass properties of each part of each throw (arrays of shape ``(throws, 7)``, parts in
    the order of :data:`PARTS`), in the throw frame: ``y`` towards the pin, ``z`` from the front
    journal mid-plane.

    ``mass`` [kg]; ``y``, ``z``: mass centre [m]; ``inertia_main``: polar moment of inertia
    about the main axis [kg m^2]; ``inertia_own``: about the part's own mass centre (axis
    parallel to the crank axis) [kg m^2]. ``mass_total`` and ``inertia_total`` (shape
    ``(throws,)``) sum the parts: the crank alone between its journal mid-planes.
    """

    mass: np.ndarray
    y: np.ndarray
    z: np.ndarray
    inertia_main: np.ndarray
    inertia_own: np.ndarray

    @property
    def mass_total(self) -> np.ndarray:
        return self.mass.sum(axis=-1)

    @property
    def inertia_total(self) -> np.ndarray:
        return self.inertia_main.sum(axis=-1)

    @property
    def unbalance_y(self) -> np.ndarray:
        """Static unbalance ``sum m y`` along the throw [kg m], shape ``(throws,)``."""
        return (self.mass * self.y).sum(axis=-1)


def cylinder(*, diameter: ArrayLike, bore: ArrayLike, length: ArrayLike, density: ArrayLike,
             offset: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Hollow cylinder: mass [kg], polar inertia about its own axis and about a parallel axis
    at distance ``offset`` [kg m^2].

    ``m = rho pi (D^2 - d^2) L / 4``, ``J_own = m (D^2 + d^2) / 8``, ``J = J_own + m e^2``.
    Inputs in m and kg/m^3; valid for ``0 <= d < D``, ``L > 0``.

    >>> m, j, _ = cylinder(diameter=0.1, bore=0.0, length=1.0, density=1000.0)
    >>> round(float(m), 6), round(float(j), 9)
    (7.853982, 0.009817477)
    """
    d_o = positive("diameter", diameter)
    d_i = non_negative("bore", bore)
    ln = positive("length", length)
    rho = positive("density", density)
    e = finite("offset", offset)
    if np.any(d_i >= d_o):
        raise ValueError("bore must be smaller than the diameter")
    m = rho * np.pi * (d_o**2 - d_i**2) * ln / 4.0
    j_own = m * (d_o**2 + d_i**2) / 8.0
    return m, j_own, j_own + m * e**2


def _sector(radius: np.ndarray, angle: np.ndarray, sign: float, centre_y: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Circular sector of ``radius`` and included ``angle`` centred at ``(0, centre_y)``,
    bisected by ``sign * y``: area, int y dA, int r^2 dA about the origin."""
    area = angle * radius**2 / 2.0
    sy_own = sign * 2.0 * np.sin(angle / 2.0) * radius**3 / 3.0  # about its centre
    j_own = angle * radius**4 / 4.0
    return area, sy_own + centre_y * area, j_own + 2.0 * centre_y * sy_own + centre_y**2 * area


def _polygon(xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Area, int y dA and int (x^2 + y^2) dA of polygons (vertices counter-clockwise along the
    last axis) by Green's theorem on their edges (shoelace formulas)."""
    x1, y1 = np.roll(xs, -1, axis=-1), np.roll(ys, -1, axis=-1)
    c = xs * y1 - x1 * ys
    area = c.sum(axis=-1) / 2.0
    sy = ((ys + y1) * c).sum(axis=-1) / 6.0
    ixx = ((ys**2 + ys * y1 + y1**2) * c).sum(axis=-1) / 12.0  # int y^2
    iyy = ((xs**2 + xs * x1 + x1**2) * c).sum(axis=-1) / 12.0  # int x^2
    return area, sy, ixx + iyy


def _hull_angles(a: np.ndarray, b: np.ndarray, r: np.ndarray) -> np.ndarray:
    """``sin beta = (a - b) / R`` of the hull's tangent lines (clipped to [-1, 1])."""
    return np.arcsin(np.clip((a - b) / r, -1.0, 1.0))


def web_outline(*, width_journal: ArrayLike, width_pin: ArrayLike, crank_radius: ArrayLike
                ) -> PlaneMoments:
    """Area moments of the web outline: the convex hull of a circle of diameter
    ``width_journal`` about the main axis and one of diameter ``width_pin`` about ``(0, R)``.

    Exact: journal-side sector (angle ``pi + 2 beta``) + pin-side sector (``pi - 2 beta``) +
    the hexagon (main centre, tangent points, pin centre), ``sin beta = (a - b) / R`` with the
    radii ``a``, ``b``; where one circle contains the other the hull is that circle.

    >>> w = web_outline(width_journal=0.1, width_pin=0.1, crank_radius=0.05)
    >>> round(float(w.area), 8)  # a stadium: pi r^2 + 2 r R
    0.01285398
    """
    a = positive("width_journal", width_journal) / 2.0
    b = positive("width_pin", width_pin) / 2.0
    rr = positive("crank_radius", crank_radius)
    a, b, rr = np.broadcast_arrays(a, b, rr)
    beta = _hull_angles(a, b, rr)
    cb, sb = np.cos(beta), np.sin(beta)
    zero = np.zeros_like(a)
    a1, sy1, j1 = _sector(a, np.pi + 2.0 * beta, -1.0, zero)
    a2, sy2, j2 = _sector(b, np.pi - 2.0 * beta, 1.0, rr)
    xs = np.stack([zero, a * cb, b * cb, zero, -b * cb, -a * cb], axis=-1)
    ys = np.stack([zero, a * sb, rr + b * sb, rr, rr + b * sb, a * sb], axis=-1)
    a3, sy3, j3 = _polygon(xs, ys)
    area, sy, jo = a1 + a2 + a3, sy1 + sy2 + sy3, j1 + j2 + j3
    # one circle inside the other: the hull is that circle
    big_a = a >= rr + b
    big_b = b >= rr + a
    ca = (np.pi * a**2, zero, np.pi * a**4 / 2.0)
    cbm = (np.pi * b**2, np.pi * b**2 * rr, np.pi * b**4 / 2.0 + np.pi * b**2 * rr**2)
    out = []
    for k, v in enumerate((area, sy, jo)):
        out.append(np.where(big_a, ca[k], np.where(big_b, cbm[k], v)))
    return PlaneMoments(*out)


def web_radius(theta: ArrayLike, *, width_journal: ArrayLike, width_pin: ArrayLike,
               crank_radius: ArrayLike) -> np.ndarray:
    """Radial function of the web outline about the main axis: the distance [m] from the main
    axis to the outline in the direction at angle ``theta`` from ``+y`` (either side).

    Journal-side arc ``r = a``, tangent line ``r = a / cos(phi - (pi/2 - beta))``, pin-side
    arc ``r = R cos phi + sqrt(b^2 - R^2 sin^2 phi)``, ``phi = |theta|`` folded to [0, pi].
    """
    a = np.asarray(width_journal, dtype=float) / 2.0
    b = np.asarray(width_pin, dtype=float) / 2.0
    rr = np.asarray(crank_radius, dtype=float)
    th = np.asarray(theta, dtype=float)
    phi = np.abs((th + np.pi) % (2.0 * np.pi) - np.pi)
    beta = _hull_angles(a, b, rr)
    phi_a = np.pi / 2.0 - beta
    phi_b = np.arctan2(b * np.cos(beta), rr + b * np.sin(beta))
    with np.errstate(invalid="ignore", divide="ignore"):
        r_line = a / np.cos(phi - phi_a)
        r_pin = rr * np.cos(phi) + np.sqrt(np.maximum(b**2 - (rr * np.sin(phi))**2, 0.0))
    r = np.where(phi >= phi_a, a, np.where(phi > phi_b, r_line, r_pin))
    r = np.where(a >= rr + b, a, r)
    return np.where(b >= rr + a, r_pin, r)


def annular_sector(*, inner_radius: ArrayLike, outer_radius: ArrayLike, angle: ArrayLike
                   ) -> PlaneMoments:
    """Area moments of an annular sector about the main axis bisected by ``-y``:
    ``A = alpha (ro^2 - ri^2)/2``, ``Sy = -2 sin(alpha/2)(ro^3 - ri^3)/3``,
    ``Jo = alpha (ro^4 - ri^4)/4``; ``0 <= ri < ro``, ``0 < alpha <= 2 pi``."""
    ri = non_negative("inner_radius", inner_radius)
    ro = positive("outer_radius", outer_radius)
    al = positive("angle", angle)
    if np.any(ri >= ro) or np.any(al > 2.0 * np.pi + 1e-12):
        raise ValueError("annular sector needs inner radius < outer radius and angle <= 2 pi")
    return PlaneMoments(al * (ro**2 - ri**2) / 2.0,
                        -2.0 * np.sin(al / 2.0) * (ro**3 - ri**3) / 3.0,
                        al * (ro**4 - ri**4) / 4.0)


def _crossings(r: np.ndarray, a: np.ndarray, b: np.ndarray, rr: np.ndarray) -> np.ndarray:
    """Angles ``phi`` (from +y, 0..pi) where the outline's radius equals ``r``: on the tangent
    lines and on the pin-side arc (two candidates each; NaN where there is none)."""
    beta = _hull_angles(a, b, rr)
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.arccos(np.clip(a / r, -1.0, 1.0))
        line = np.stack([np.pi / 2.0 - beta - d, np.pi / 2.0 - beta + d], axis=-1)
        c = (r**2 + rr**2 - b**2) / (2.0 * r * rr)
        arc = np.where(np.abs(c) <= 1.0, np.arccos(np.clip(c, -1.0, 1.0)), np.nan)
    return np.concatenate([line, arc[..., None]], axis=-1)


def counterweight_web_overlap(*, inner_radius: ArrayLike, outer_radius: ArrayLike,
                              angle: ArrayLike, width_journal: ArrayLike,
                              width_pin: ArrayLike, crank_radius: ArrayLike) -> PlaneMoments:
    """Area moments of the common part of the counterweight's annular sector and the web
    outline: ``ri <= r <= min(ro, r_web(phi))`` for ``|phi - pi| <= alpha/2``.

    Integrated in polar coordinates about the main axis (``dA = r dr dphi``, inner integral in
    closed form), the angle split at every break of the integrand (tangent points, crossings
    of ``r_web`` with ``ri`` and ``ro``, the sector's edges) and each interval integrated by
    32-point Gauss-Legendre quadrature (smooth integrands: exact to rounding). Vectorised over
    the leading axis (one entry per counterweight).
    """
    ri = np.atleast_1d(non_negative("inner_radius", inner_radius))
    ro = np.atleast_1d(positive("outer_radius", outer_radius))
    al = np.atleast_1d(positive("angle", angle))
    a = np.atleast_1d(positive("width_journal", width_journal)) / 2.0
    b = np.atleast_1d(positive("width_pin", width_pin)) / 2.0
    rr = np.atleast_1d(positive("crank_radius", crank_radius))
    ri, ro, al, a, b, rr = np.broadcast_arrays(ri, ro, al, a, b, rr)
    beta = _hull_angles(a, b, rr)
    lo = np.pi - np.minimum(al, 2.0 * np.pi) / 2.0  # half of the sector, phi in [lo, pi]
    breaks = np.concatenate([
        np.stack([lo, np.full_like(lo, np.pi), np.pi / 2.0 - beta,
                  np.arctan2(b * np.cos(beta), rr + b * np.sin(beta))], axis=-1),
        _crossings(np.maximum(ri, 1e-300), a, b, rr), _crossings(ro, a, b, rr)], axis=-1)
    breaks = np.where(np.isfinite(breaks), breaks, lo[..., None])
    breaks = np.sort(np.clip(breaks, lo[..., None], np.pi), axis=-1)
    p0, p1 = breaks[..., :-1], breaks[..., 1:]
    half = (p1 - p0) / 2.0
    phi = (p0 + p1)[..., None] / 2.0 + half[..., None] * _GAUSS_NODES
    w = half[..., None] * _GAUSS_WEIGHTS
    shape = ri.shape + (1, 1)
    rw = web_radius(phi, width_journal=2.0 * a.reshape(shape), width_pin=2.0 * b.reshape(shape),
                    crank_radius=rr.reshape(shape))
    r_in = ri.reshape(shape)
    r_out = np.maximum(np.minimum(ro.reshape(shape), rw), r_in)

    def integral(k: int, f: np.ndarray) -> np.ndarray:
        # 2 x int f(phi) int_ri^rout r^(k+1) dr dphi (both sides of the y axis)
        g = (r_out**(k + 2) - r_in**(k + 2)) / (k + 2)
        return 2.0 * (w * f * g).sum(axis=(-2, -1))

    return PlaneMoments(integral(0, 1.0), integral(1, np.cos(phi)), integral(2, 1.0))


def throw_mass_properties(*, journal_diameter: ArrayLike, journal_bore: ArrayLike,
                          journal_length: ArrayLike, pin_diameter: ArrayLike,
                          pin_bore: ArrayLike, pin_length: ArrayLike,
                          web_thickness: ArrayLike, web_width_journal: ArrayLike,
                          web_width_pin: ArrayLike, crank_radius: ArrayLike,
                          density: ArrayLike, cw_inner_radius: ArrayLike = 0.0,
                          cw_outer_radius: ArrayLike = 0.0, cw_angle: ArrayLike = 0.0,
                          cw_thickness: ArrayLike = 0.0,
                          rear_journal_diameter: ArrayLike | None = None,
                          rear_journal_bore: ArrayLike | None = None,
                          rear_journal_length: ArrayLike | None = None
                          ) -> ThrowMassProperties:
    """Mass, mass centre and polar inertia of every part of crank throws (module docstring).

    Parameters (SI, each a scalar or an array over throws)
    ----------
    journal_diameter, journal_bore, journal_length : m
        Main journal (front half; the rear half too unless ``rear_journal_*`` are given).
    pin_diameter, pin_bore, pin_length : m
    web_thickness, web_width_journal, web_width_pin : m
        Both webs of a throw alike.
    crank_radius : m
        Stroke / 2.
    density : kg/m^3
    cw_inner_radius, cw_outer_radius : m; cw_angle : rad; cw_thickness : m
        Counterweight on each web (both alike); ``cw_outer_radius = 0`` or ``cw_angle = 0``:
        none; ``cw_thickness = 0``: the web thickness.

    Returns
    -------
    ThrowMassProperties
        Arrays ``(throws, 7)``, parts in the order of :data:`PARTS`.

    Valid for bores smaller than their diameters, positive lengths and a counterweight whose
    thickness does not exceed the web's unless it clears the journals (the caller's checks:
    :mod:`checker.description.engine`); raises ValueError otherwise.

    >>> p = throw_mass_properties(journal_diameter=0.055, journal_bore=0.0,
    ...     journal_length=0.027, pin_diameter=0.048, pin_bore=0.0, pin_length=0.0244,
    ...     web_thickness=0.0223, web_width_journal=0.0757, web_width_pin=0.0757,
    ...     crank_radius=0.0473, density=7850.0)
    >>> round(float(p.mass_total[0]), 4)
    3.6795
    """
    dj = np.atleast_1d(positive("journal_diameter", journal_diameter))
    n = np.broadcast_shapes(*(np.shape(np.atleast_1d(v)) for v in (
        journal_diameter, journal_bore, journal_length, pin_diameter, pin_bore, pin_length,
        web_thickness, web_width_journal, web_width_pin, crank_radius, density,
        cw_inner_radius, cw_outer_radius, cw_angle, cw_thickness)))

    def arr(name: str, v: ArrayLike) -> np.ndarray:
        return np.broadcast_to(np.atleast_1d(finite(name, v)), n).astype(float)

    dj = arr("journal_diameter", dj)
    dji, lj = arr("journal_bore", journal_bore), arr("journal_length", journal_length)
    dp, dpi, lp = (arr("pin_diameter", pin_diameter), arr("pin_bore", pin_bore),
                   arr("pin_length", pin_length))
    tw, bj, bp = (arr("web_thickness", web_thickness), arr("web_width_journal", web_width_journal),
                  arr("web_width_pin", web_width_pin))
    rr, rho = arr("crank_radius", crank_radius), arr("density", density)
    ri, ro = arr("cw_inner_radius", cw_inner_radius), arr("cw_outer_radius", cw_outer_radius)
    al, tc = arr("cw_angle", cw_angle), arr("cw_thickness", cw_thickness)
    djr = dj if rear_journal_diameter is None else arr("rear_journal_diameter",
                                                        rear_journal_diameter)
    djir = dji if rear_journal_bore is None else arr("rear_journal_bore", rear_journal_bore)
    ljr = lj if rear_journal_length is None else arr("rear_journal_length", rear_journal_length)
    positive("web_thickness", tw)
    tc = np.where(tc > 0.0, tc, tw)
    has_cw = (ro > 0.0) & (al > 0.0)
    if np.any(has_cw & (tc > tw) & (ri < np.maximum(dj, djr) / 2.0)):
        raise ValueError("a counterweight thicker than its web must clear the main journals"
                         " (inner radius at least the journal radius)")

    m_jf, jo_jf, _ = cylinder(diameter=dj, bore=dji, length=lj / 2.0, density=rho)
    m_jr, jo_jr, _ = cylinder(diameter=djr, bore=djir, length=ljr / 2.0, density=rho)
    m_p, jo_p, jm_p = cylinder(diameter=dp, bore=dpi, length=lp, density=rho, offset=rr)
    web = web_outline(width_journal=bj, width_pin=bp, crank_radius=rr)
    m_w = rho * tw * web.area
    y_w = web.first_y / web.area
    jm_w = rho * tw * web.polar

    m_c = np.zeros(n)
    sy_c = np.zeros(n)
    jm_c = np.zeros(n)
    if np.any(has_cw):
        idx = np.nonzero(has_cw)
        cw = annular_sector(inner_radius=ri[idx], outer_radius=ro[idx], angle=al[idx])
        ov = counterweight_web_overlap(inner_radius=ri[idx], outer_radius=ro[idx],
                                       angle=al[idx], width_journal=bj[idx],
                                       width_pin=bp[idx], crank_radius=rr[idx])
        t_c, t_min = tc[idx], np.minimum(tc[idx], tw[idx])
        # union of two prisms on one mid-plane: t_c A_cw + t_w A_web - min(t_c, t_w) A_common
        m_c[idx] = rho[idx] * (t_c * cw.area - t_min * ov.area)
        sy_c[idx] = rho[idx] * (t_c * cw.first_y - t_min * ov.first_y)
        jm_c[idx] = rho[idx] * (t_c * cw.polar - t_min * ov.polar)
    with np.errstate(invalid="ignore", divide="ignore"):
        y_c = np.where(m_c > 0.0, sy_c / np.where(m_c > 0.0, m_c, 1.0), 0.0)

    z_web1 = lj / 2.0 + tw / 2.0
    z_pin = lj / 2.0 + tw + lp / 2.0
    z_web2 = lj / 2.0 + 1.5 * tw + lp
    z_rear = lj / 2.0 + 2.0 * tw + lp + ljr / 4.0
    zero = np.zeros(n)
    mass = np.stack([m_jf, m_w, m_c, m_p, m_w, m_c, m_jr], axis=-1)
    y = np.stack([zero, y_w, y_c, rr, y_w, y_c, zero], axis=-1)
    z = np.stack([lj / 4.0, z_web1, z_web1, z_pin, z_web2, z_web2, z_rear], axis=-1)
    jm = np.stack([jo_jf, jm_w, jm_c, jm_p, jm_w, jm_c, jo_jr], axis=-1)
    return ThrowMassProperties(mass=mass, y=y, z=z, inertia_main=jm,
                               inertia_own=jm - mass * y**2)


def plain_shaft_stiffness(*, diameter: ArrayLike, bore: ArrayLike, length: ArrayLike,
                          shear_modulus: ArrayLike) -> np.ndarray:
    """Torsional stiffness of a plain (hollow) shaft [N m/rad]: ``k = G J_p / L`` with
    ``J_p = pi (D^4 - d^4) / 32`` (Saint-Venant torsion of a circular tube; e.g. Timoshenko &
    Goodier, Theory of Elasticity, 3rd ed. 1970, ch. 10).

    >>> round(float(plain_shaft_stiffness(diameter=0.04, bore=0.0, length=0.05,
    ...                                   shear_modulus=80e9)))
    402124
    """
    d_o = positive("diameter", diameter)
    d_i = non_negative("bore", bore)
    if np.any(d_i >= d_o):
        raise ValueError("bore must be smaller than the diameter")
    return positive("shear_modulus", shear_modulus) * np.pi * (d_o**4 - d_i**4) / 32.0 \
        / positive("length", length)


def shear_modulus(youngs_modulus: ArrayLike, poisson_ratio: ArrayLike) -> np.ndarray:
    """``G = E / (2 (1 + nu))`` [Pa] of an isotropic material (``-1 < nu < 0.5``)."""
    e = positive("youngs_modulus", youngs_modulus)
    nu = finite("poisson_ratio", poisson_ratio)
    if np.any(nu <= -1.0) or np.any(nu >= 0.5):
        raise ValueError("poisson_ratio must lie in (-1, 0.5)")
    return e / (2.0 * (1.0 + nu))


def web_width_at_pin_centre(*, width_journal: ArrayLike, width_pin: ArrayLike,
                            crank_radius: ArrayLike) -> np.ndarray:
    """Width of the web outline across the pin centre (``y = R``) [m], IACS UR M53's web width
    ``W`` "in way of the crank pin centre": the pin-side circle where it bounds the outline
    there (``Bj <= Bp``), else the tangent lines, ``W = 2 (a - R sin beta) / cos beta``."""
    a = positive("width_journal", width_journal) / 2.0
    b = positive("width_pin", width_pin) / 2.0
    rr = positive("crank_radius", crank_radius)
    beta = _hull_angles(a, b, rr)
    line = 2.0 * (a - rr * np.sin(beta)) / np.cos(beta)
    w = np.where(beta > 0.0, line, 2.0 * b)
    return np.where(a >= rr + b, 2.0 * np.sqrt(np.maximum(a**2 - rr**2, 0.0)), w)
