"""The crankshaft as a continuous beam: statically indeterminate main-bearing loads.

The classical concept scheme (:func:`checker.calc.crank_forces.main_bearing_loads`) cuts the
crank at every main journal: each throw is a rigid beam simply supported on its two mains
(statically determinate). Here the whole crank is one elastic 3D frame on ``n_main`` supports
(statically indeterminate), the scheme of the Cummins concept stage (Piraner, Pflueger and
Bouthier, "Cummins Crankshaft and Bearing Analysis Process", 2002, Fig. 1) and of the
"hyperstatic" main-bearing reactions of Agostini (Politecnico di Torino course notes,
"Powertrain Components Design - Engine", 2019, "Static Analysis").

Model (stated idealisation)
---------------------------
* **Frame** of Euler-Bernoulli beam elements in 3D (12 degrees of freedom per element: three
  displacements and three rotations at each end; Przemieniecki, "Theory of Matrix Structural
  Analysis", McGraw-Hill 1968, ch. 5, eq. 5.115), crank frame coordinates: ``z`` the crank axis,
  main axis at ``x = y = 0``. Each element carries its own ``EA``, ``GJ`` and bending stiffness
  about its two principal axes (``EI_1`` about the axis ``e_1`` given per element, ``EI_2``
  about ``e_3 x e_1``), so a web (a plate joining journal and pin) bends stiffly in its own
  plane and flexibly out of it.
* **Throw bending stiffness** from the dimensions (:func:`crank_frame`): the plain beam
  idealisation of the webs is 24-1350 % too flexible against a 3D FE of single throws, so the
  webs' bending and torsion and the journal and pin sections inside the webs carry factors
  fitted to that FE (:func:`web_stiffness_factors`; stated error 18 % on a throw's end
  rotations and deflections; docs/crank-geometry.md, "Throw bending stiffness").
* **Supports** at the main journals' mid-planes act in ``x`` and ``y`` only (a main bearing
  holds the journal centre and lets it tilt): rigid, or elastic with a radial stiffness ``k``
  per main (isotropic: the same in every radial direction, hence the same in the rotating crank
  frame). Optional support offsets (misalignment) are prescribed support displacements (rigid)
  or spring foot positions (elastic).
* **Rigid-body motions** left by the supports are removed by holding the axial displacement of
  the first support node and the rotation about ``z`` of one stated node. Neither carries a
  force in a load case without axial force and with balanced torque. A torque left to the
  rotation hold is not neutral: through the offset pins it bends the crank, and where the
  hold is changes the radial reactions (issue 43). The caller balances the torque
  (:func:`balancing_torques`: the load at the flywheel flange, d'Alembert's torques on the
  rotating inertias), so the hold reacts nothing.
* **Torsion** (issue 43): with ``throw_torsional_stiffness`` each throw's web in-plane bending
  is calibrated so that the throw alone has its torsional stiffness from the 3D FE
  (:func:`web_inplane_factor`). The same frame gives the assembled crank's torsional
  stiffness on its bearings (:func:`assembled_torsional_stiffness`), verified against a 3D FE
  of multi-throw pieces within 1 %.

Because the stiffness matrix does not depend on the crank angle, the support reactions are a
linear map of the nodal loads, computed once per configuration by one factorisation
(:class:`BeamSolution`); a whole sweep of angles, speeds and load cases is then one matrix
product (:meth:`BeamSolution.bearing_loads`).

Sign convention: as in :mod:`checker.calc.crank_forces`, a **bearing load is the force the
journal exerts on the bearing** (the negative of the support reaction on the crank).

References
----------
.. [1] J. S. Przemieniecki, "Theory of Matrix Structural Analysis", McGraw-Hill, 1968, ch. 5,
   eq. 5.115 (3D beam element stiffness).
.. [2] V. Piraner, A. Pflueger, B. Bouthier, "Cummins Crankshaft and Bearing Analysis
   Process", MDI conference, 2002, Fig. 1 (determinate and indeterminate schemes).
.. [3] M. Agostini, "Powertrain Components Design - Engine", course notes, Politecnico di
   Torino, 2019, "Static Analysis" (isostatic and hyperstatic main-bearing reactions).
.. [4] W. C. Young, R. G. Budynas, "Roark's Formulas for Stress and Strain", 7th ed., 2002,
   Table 10.7 (torsion constant of a rectangle).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._checks import finite, positive

__all__ = [
    "BeamSolution",
    "CrankFrame",
    "Frame",
    "assembled_torsional_stiffness",
    "balancing_torques",
    "crank_frame",
    "element_stiffness",
    "rectangle_torsion_constant",
    "section_moment",
    "solve_frame",
    "throw_section_loads",
    "web_inplane_factor",
    "web_stiffness_factors",
]

_DOF = 6


@dataclass(frozen=True, kw_only=True)
class Frame:
    """A 3D frame of beam elements on radial supports (SI, crank frame).

    Attributes
    ----------
    nodes : ndarray, shape (n_node, 3) [m]
        Node positions ``(x, y, z)``.
    elements : ndarray of int, shape (n_el, 2)
        Node indices of each element's two ends.
    axial_stiffness : ndarray, shape (n_el,) [N]
        ``E A`` of each element.
    torsional_stiffness : ndarray, shape (n_el,) [N m^2]
        ``G J`` of each element (``J`` the torsion constant of its section).
    bending_stiffness : ndarray, shape (n_el, 2) [N m^2]
        ``E I_1`` about the element's axis ``e_1`` and ``E I_2`` about ``e_2 = e_3 x e_1``
        (``e_3`` = unit vector along the element).
    first_axis : ndarray, shape (n_el, 3) [-]
        A vector not parallel to the element, whose component normal to it is ``e_1``.
    support_nodes : ndarray of int, shape (n_main,)
        Node of each main bearing.
    support_stiffness : ndarray, shape (n_main,) [N/m]
        Radial stiffness of each main bearing; ``inf`` for a rigid support.
    torsion_node : int
        Node whose rotation about ``z`` is held (the flywheel end).
    """

    nodes: np.ndarray
    elements: np.ndarray
    axial_stiffness: np.ndarray
    torsional_stiffness: np.ndarray
    bending_stiffness: np.ndarray
    first_axis: np.ndarray
    support_nodes: np.ndarray
    support_stiffness: np.ndarray
    torsion_node: int

    def __post_init__(self) -> None:
        nodes = finite("nodes", self.nodes)
        if nodes.ndim != 2 or nodes.shape[1] != 3:
            raise ValueError("nodes must have shape (n_node, 3)")
        el = np.asarray(self.elements)
        n_el = el.shape[0] if el.ndim == 2 else -1
        if el.ndim != 2 or el.shape[1] != 2 or not np.issubdtype(el.dtype, np.integer):
            raise ValueError("elements must be an integer array of shape (n_el, 2)")
        if n_el and (el.min() < 0 or el.max() >= nodes.shape[0] or np.any(el[:, 0] == el[:, 1])):
            raise ValueError("elements must join two different existing nodes")
        for name in ("axial_stiffness", "torsional_stiffness"):
            if positive(name, getattr(self, name)).shape != (n_el,):
                raise ValueError(f"{name} must have shape (n_el,)")
        if positive("bending_stiffness", self.bending_stiffness).shape != (n_el, 2):
            raise ValueError("bending_stiffness must have shape (n_el, 2)")
        if finite("first_axis", self.first_axis).shape != (n_el, 3):
            raise ValueError("first_axis must have shape (n_el, 3)")
        sup = np.asarray(self.support_nodes)
        if sup.ndim != 1 or sup.size < 2 or not np.issubdtype(sup.dtype, np.integer):
            raise ValueError("support_nodes must list at least two nodes")
        if sup.min() < 0 or sup.max() >= nodes.shape[0] or np.unique(sup).size != sup.size:
            raise ValueError("support_nodes must be distinct existing nodes")
        k = np.asarray(self.support_stiffness, dtype=float)
        if k.shape != sup.shape or np.any(np.isnan(k)) or np.any(k <= 0):
            raise ValueError("support_stiffness must be > 0 N/m (inf = rigid), one per support")
        if not 0 <= int(self.torsion_node) < nodes.shape[0]:
            raise ValueError("torsion_node must be an existing node")


def element_stiffness(
    start: ArrayLike, end: ArrayLike, ea: float, gj: float, ei1: float, ei2: float,
    first_axis: ArrayLike,
) -> np.ndarray:
    """Stiffness matrix of a 3D Euler-Bernoulli beam element in global coordinates.

    Local matrix of Przemieniecki (1968, eq. 5.115) for degrees of freedom
    ``(u1, v1, w1, rx1, ry1, rz1, u2, ..., rz2)`` along local axes ``(e_1, e_2, e_3)`` with
    ``e_3`` along the element, turned to global axes by ``T = diag(L, L, L, L)``, ``L`` the
    rows ``e_1, e_2, e_3``: ``K = T^T k T``.

    Parameters
    ----------
    start, end : array_like, shape (3,) [m]
        End positions.
    ea [N], gj [N m^2], ei1, ei2 [N m^2] : float
        Axial, torsional and bending stiffness (``ei1`` about ``e_1``, ``ei2`` about ``e_2``).
    first_axis : array_like, shape (3,)
        Vector whose component normal to the element gives ``e_1``.

    Returns
    -------
    ndarray, shape (12, 12) [N/m, N, N m]
    """
    p0 = np.asarray(start, dtype=float)
    p1 = np.asarray(end, dtype=float)
    d = p1 - p0
    length = float(np.linalg.norm(d))
    if length <= 0.0:
        raise ValueError("a beam element must have a length > 0 m")
    e3 = d / length
    a = np.asarray(first_axis, dtype=float)
    e1 = a - (a @ e3) * e3
    n1 = float(np.linalg.norm(e1))
    if n1 < 1e-9 * max(float(np.linalg.norm(a)), 1e-300):
        raise ValueError("first_axis must not be parallel to the element")
    e1 = e1 / n1
    e2 = np.array([e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2],
                   e3[0] * e1[1] - e3[1] * e1[0]])  # e3 x e1
    rot = np.stack([e1, e2, e3])  # local = rot @ global
    k = np.zeros((12, 12))
    L, L2, L3 = length, length**2, length**3
    # axial (w along e3) and torsion (r about e3)
    for i, s in ((2, ea / L), (5, gj / L)):
        k[i, i] = k[i + 6, i + 6] = s
        k[i, i + 6] = k[i + 6, i] = -s
    # bending: displacement along e1 (u) with rotation about e2 (ry): stiffness ei2;
    # displacement along e2 (v) with rotation about e1 (rx): stiffness ei1
    for disp, rotn, ei, sgn in ((0, 4, ei2, 1.0), (1, 3, ei1, -1.0)):
        a12, a6, a4, a2 = 12 * ei / L3, 6 * ei / L2, 4 * ei / L, 2 * ei / L
        u1, r1, u2, r2 = disp, rotn, disp + 6, rotn + 6
        k[u1, u1] = k[u2, u2] = a12
        k[u1, u2] = k[u2, u1] = -a12
        k[r1, r1] = k[r2, r2] = a4
        k[r1, r2] = k[r2, r1] = a2
        for u, r, c in ((u1, r1, sgn * a6), (u1, r2, sgn * a6), (u2, r1, -sgn * a6),
                        (u2, r2, -sgn * a6)):
            k[u, r] = k[r, u] = c
    t = np.zeros((12, 12))  # diag(rot, rot, rot, rot)
    for i in range(0, 12, 3):
        t[i:i + 3, i:i + 3] = rot
    return t.T @ k @ t


def _assemble(frame: Frame) -> np.ndarray:
    nodes = np.asarray(frame.nodes, dtype=float)
    n = nodes.shape[0] * _DOF
    kg = np.zeros((n, n))
    el = np.asarray(frame.elements)
    ea = np.asarray(frame.axial_stiffness, dtype=float)
    gj = np.asarray(frame.torsional_stiffness, dtype=float)
    ei = np.asarray(frame.bending_stiffness, dtype=float)
    ax = np.asarray(frame.first_axis, dtype=float)
    for e, (i, j) in enumerate(el):
        ke = element_stiffness(nodes[i], nodes[j], ea[e], gj[e], ei[e, 0], ei[e, 1], ax[e])
        idx = np.r_[i * _DOF:(i + 1) * _DOF, j * _DOF:(j + 1) * _DOF]
        kg[np.ix_(idx, idx)] += ke
    return kg


@dataclass(frozen=True, kw_only=True)
class BeamSolution:
    """Linear map from nodal forces to main-bearing loads of one frame (factorised once).

    Attributes
    ----------
    load_nodes : ndarray of int, shape (n_load,)
        Nodes at which forces may be applied.
    load_positions : ndarray, shape (n_load, 3) [m]
        Their positions.
    force_map : ndarray, shape (n_main, 2, n_load, 3) [-]
        Bearing load ``(x, y)`` at each main per unit force ``(x, y, z)`` at each load node.
    moment_map : ndarray, shape (n_main, 2, n_load, 3) [1/m]
        Bearing load per unit moment ``(x, y, z)`` at each load node.
    offset_map : ndarray, shape (n_main, 2, n_main, 2) [N/m]
        Bearing load per unit support offset ``(x, y)`` of each main (misalignment).
    support_z : ndarray, shape (n_main,) [m]
        Axial position of each support.
    """

    load_nodes: np.ndarray
    load_positions: np.ndarray
    force_map: np.ndarray
    moment_map: np.ndarray
    offset_map: np.ndarray
    support_z: np.ndarray

    def bearing_loads(
        self, force: ArrayLike, point: ArrayLike | None = None, offset: ArrayLike | None = None,
    ) -> np.ndarray:
        """Main-bearing loads for a batch of load sets (one matrix product).

        Parameters
        ----------
        force : array_like, shape (..., n_load, 3) [N]
            Force on the crank at each load node, crank frame (any leading batch axes: crank
            angle, speed, load case).
        point : array_like, shape (..., n_load, 3) [m], optional
            Where each force acts; a force off its node adds the moment
            ``(point - node) x force`` at the node. Default: at the node.
        offset : array_like, shape (..., n_main, 2) [m], optional
            Support offsets in the crank frame (a block-frame offset turned by the crank angle).

        Returns
        -------
        ndarray, shape (..., n_main, 2) [N]
            Force of each main journal on its bearing, crank frame.
        """
        f = np.asarray(force, dtype=float)
        out = np.einsum("mcla,...la->...mc", self.force_map, f)
        if point is not None:
            arm = np.asarray(point, dtype=float) - self.load_positions
            out = out + np.einsum("mcla,...la->...mc", self.moment_map, np.cross(arm, f))
        if offset is not None:
            out = out + np.einsum("mcna,...na->...mc", self.offset_map,
                                  np.asarray(offset, dtype=float))
        return out


def solve_frame(frame: Frame, load_nodes: ArrayLike) -> BeamSolution:
    """Factorise a frame once and return its load -> bearing-load map.

    Rigid supports (``k = inf``) are held exactly (their ``x, y`` displacements eliminated;
    the reaction is ``K_cf u_f + K_cc d_c - f_c``); elastic supports add ``k`` to the
    ``x, y`` diagonal of their node and load the bearing with ``k (u - d)``.

    Parameters
    ----------
    frame : Frame
    load_nodes : array_like of int, shape (n_load,)
        Nodes that will carry forces or moments.

    Returns
    -------
    BeamSolution

    Raises
    ------
    ValueError
        If the frame is not held (a mechanism: singular stiffness).
    """
    nodes = np.asarray(frame.nodes, dtype=float)
    n_node = nodes.shape[0]
    n = n_node * _DOF
    loads = np.asarray(load_nodes)
    if loads.ndim != 1 or not np.issubdtype(loads.dtype, np.integer) or (
        loads.size and (loads.min() < 0 or loads.max() >= n_node)
    ):
        raise ValueError("load_nodes must be existing node indices")
    kg = _assemble(frame)
    sup = np.asarray(frame.support_nodes)
    ks = np.asarray(frame.support_stiffness, dtype=float)
    n_main = sup.size
    rigid = ~np.isfinite(ks)
    # degrees of freedom held: x, y of rigid supports; z of the first support; rz of torsion node
    held_sup = [sup[m] * _DOF + c for m in range(n_main) if rigid[m] for c in (0, 1)]
    held_extra = [sup[0] * _DOF + 2, int(frame.torsion_node) * _DOF + 5]
    held = np.array(held_sup + held_extra, dtype=int)
    free = np.setdiff1d(np.arange(n), held)
    for m in np.flatnonzero(~rigid):
        for c in (0, 1):
            kg[sup[m] * _DOF + c, sup[m] * _DOF + c] += ks[m]
    import scipy.linalg  # only a continuous-beam check needs it (the check imports no scipy)

    kff = kg[np.ix_(free, free)]
    try:
        factor = scipy.linalg.cho_factor(kff)
    except np.linalg.LinAlgError as exc:
        raise ValueError("the frame is not held by its supports (singular stiffness)") from exc
    pos = np.full(n, -1)
    pos[free] = np.arange(free.size)

    # right-hand sides: unit force/moment components at the load nodes, unit offsets
    n_load = loads.size
    cols = [loads[i] * _DOF + c for i in range(n_load) for c in range(6)]
    n_rhs = len(cols) + 2 * n_main
    rhs_full = np.zeros((n, n_rhs))
    for r, dof in enumerate(cols):
        rhs_full[dof, r] = 1.0
    # offsets: rigid -> prescribed displacement d_c (u_f = K_ff^-1 (-K_fc d_c));
    # elastic -> spring foot at d: load k d on the node
    disp_held = np.zeros((n, n_rhs))
    for m in range(n_main):
        for c in (0, 1):
            r = len(cols) + 2 * m + c
            dof = sup[m] * _DOF + c
            if rigid[m]:
                disp_held[dof, r] = 1.0
            else:
                rhs_full[dof, r] += ks[m]
    rhs = rhs_full[free] - kg[np.ix_(free, held)] @ disp_held[held]
    u = np.zeros((n, n_rhs))
    u[free] = scipy.linalg.cho_solve(factor, rhs)
    u[held] = disp_held[held]
    if not np.all(np.isfinite(u)):
        raise ValueError("the frame is not held by its supports (singular stiffness)")
    # bearing load = -(support reaction on the crank)
    bearing = np.zeros((n_main, 2, n_rhs))
    for m in range(n_main):
        for c in (0, 1):
            dof = sup[m] * _DOF + c
            if rigid[m]:
                reaction = kg[dof] @ u - rhs_full[dof]
                bearing[m, c] = -reaction
            else:
                foot = np.zeros(n_rhs)
                foot[len(cols) + 2 * m + c] = 1.0
                bearing[m, c] = ks[m] * (u[dof] - foot)
    unit = bearing[:, :, : len(cols)].reshape(n_main, 2, n_load, 6)
    return BeamSolution(
        load_nodes=loads.copy(),
        load_positions=nodes[loads].copy(),
        force_map=unit[..., :3].copy(),
        moment_map=unit[..., 3:].copy(),
        offset_map=bearing[:, :, len(cols):].reshape(n_main, 2, n_main, 2).copy(),
        support_z=nodes[sup, 2].copy(),
    )


def section_moment(
    cut_z: ArrayLike, force: ArrayLike, force_z: ArrayLike, force_xy: ArrayLike | None = None,
) -> np.ndarray:
    """Internal moment at axial cuts from the forces on the crank left of each cut (statics).

    ``M(z_c) = sum_{z_i < z_c} (r_i - r_c) x F_i`` about the point ``(0, 0, z_c)``, forces
    ``F_i`` on the crank (applied loads and support reactions, i.e. minus the bearing loads)
    at positions ``r_i``. For transverse forces the bending components are
    ``M_x = (z_c - z_i) F_y`` and ``M_y = -(z_c - z_i) F_x``; they do not depend on the forces'
    radial positions, so one expression serves a straight and a cranked beam alike.

    Parameters
    ----------
    cut_z : array_like, shape (n_cut,) [m]
    force : array_like, shape (..., n_f, 2 or 3) [N]
        Transverse (and optional axial) forces on the crank.
    force_z : array_like, shape (n_f,) [m]
        Axial position of each force.
    force_xy : array_like, shape (n_f, 2) [m], optional
        Radial positions, used only for the torsion component ``M_z``.

    Returns
    -------
    ndarray, shape (..., n_cut, 3) [N m]
        ``(M_x, M_y, M_z)`` at each cut.
    """
    zc = finite("cut_z", cut_z).ravel()
    zf = finite("force_z", force_z).ravel()
    f = finite("force", force)
    if f.shape[-2] != zf.size:
        raise ValueError("force and force_z must list the same forces")
    lever = np.where(zf[None, :] < zc[:, None], zc[:, None] - zf[None, :], 0.0)  # (n_cut, n_f)
    mx = np.einsum("cf,...f->...c", lever, f[..., 1])
    my = -np.einsum("cf,...f->...c", lever, f[..., 0])
    if force_xy is None:
        mz = np.zeros_like(mx)
    else:
        xy = finite("force_xy", force_xy)
        left = (zf[None, :] < zc[:, None]).astype(float)
        tq = xy[:, 0] * f[..., 1] - xy[:, 1] * f[..., 0]
        mz = np.einsum("cf,...f->...c", left, tq)
    return np.stack([mx, my, mz], axis=-1)



@dataclass(frozen=True, kw_only=True)
class CrankFrame:
    """A crank idealised as a frame (:func:`crank_frame`) with the nodes loads go to.

    Attributes
    ----------
    frame : Frame
    main_nodes : ndarray of int, shape (n_main,)
    web_nodes : ndarray of int, shape (n_pins, 2)
        Node on the main axis at each web's mid-plane (web and counterweight forces go here,
        with the moment of their offset).
    pin_nodes : list of ndarray of int
        Per pin, the nodes at ``pin_load_z`` (con-rod forces, the pin's own mass).
    web_elements : ndarray of int, shape (n_pins, 2)
        Element index of each throw's two webs.
    web_inplane_factor : ndarray, shape (n_pins,)
        Factor on each throw's web in-plane bending stiffness (1: not calibrated; see
        ``throw_torsional_stiffness`` of :func:`crank_frame`).
    """

    frame: Frame
    main_nodes: np.ndarray
    web_nodes: np.ndarray
    pin_nodes: list[np.ndarray]
    web_elements: np.ndarray | None = None
    web_inplane_factor: np.ndarray | None = None

    @property
    def load_nodes(self) -> np.ndarray:
        """Web nodes, then every pin node, in order (the order :func:`solve_frame` takes)."""
        return np.concatenate([self.web_nodes.ravel(), *self.pin_nodes]).astype(int)


def _circle_section(d: float, bore: float) -> tuple[float, float]:
    """Area and second moment of a (bored) circle: ``pi/4 (D^2-d^2)``, ``pi/64 (D^4-d^4)``."""
    return np.pi / 4 * (d**2 - bore**2), np.pi / 64 * (d**4 - bore**4)


def rectangle_torsion_constant(width: ArrayLike, thickness: ArrayLike) -> np.ndarray:
    """Torsion constant of a solid rectangle, ``J = b t^3 (1/3 - 0.21 (t/b) (1 - t^4/(12 b^4)))``.

    ``b >= t`` the long and short sides (Roark's Formulas for Stress and Strain, 7th ed., 2002,
    Table 10.7 case 4; within 4 % of the exact series for every aspect ratio).

    Parameters
    ----------
    width, thickness : array_like [m]

    Returns
    -------
    ndarray [m^4]
    """
    w = positive("width", width)
    t = positive("thickness", thickness)
    b, s = np.maximum(w, t), np.minimum(w, t)
    r = s / b
    return b * s**3 * (1.0 / 3.0 - 0.21 * r * (1.0 - r**4 / 12.0))


def crank_frame(
    *,
    main_z: ArrayLike,
    web_z: ArrayLike,
    pin_load_z: list[ArrayLike],
    throw_angle: ArrayLike,
    crank_radius: float,
    journal_diameter: ArrayLike,
    journal_bore: ArrayLike,
    pin_diameter: ArrayLike,
    pin_bore: ArrayLike,
    web_thickness: ArrayLike,
    web_width: ArrayLike,
    youngs_modulus: float,
    poisson_ratio: float,
    support_stiffness: ArrayLike,
    web_correction: bool = True,
    throw_torsional_stiffness: ArrayLike | None = None,
) -> CrankFrame:
    """The crank as a 3D frame through its journal and pin centre lines.

    Per throw ``j`` (between mains ``j`` and ``j+1``): a journal element on the main axis from
    main ``j`` to the first web's mid-plane, a web element from the main axis to the pin axis
    in that plane, pin elements along the pin axis through the load points, the second web,
    and a journal element to main ``j+1``. Sections: journal and pin as bored circles
    (``EI = E pi (D^4 - d^4)/64``, ``GJ = G pi (D^4 - d^4)/32``), web as a rectangle of
    thickness ``t_w`` (axial) and width ``B`` (tangential): ``EI = E B t_w^3/12`` about the
    tangential axis (the web bending that the radial pin force causes), ``E t_w B^3/12`` about
    the crank axis, ``GJ`` of the rectangle (:func:`rectangle_torsion_constant`). Journal and
    pin sections reach the web mid-planes (the web's half thickness taken as journal/pin):
    a stated beam idealisation, the usual one of concept-stage crank models (Agostini 2019,
    "Static Analysis": a beam on ``n`` supports).

    Parameters
    ----------
    main_z : array_like, shape (n_main,) [m]
        Axial positions of the main journals' mid-planes, increasing.
    web_z : array_like, shape (n_pins, 2) [m]
        Mid-planes of each throw's two webs, ``main_z[j] < web_z[j,0] < web_z[j,1] <
        main_z[j+1]``.
    pin_load_z : list of array_like [m]
        Per pin, the axial positions where forces act (each rod's big-end centre, the pin's
        mass centre), strictly between its webs.
    throw_angle : array_like, shape (n_pins,) [rad]
        Crank-frame angle of each pin (pin at ``R (sin g, cos g)``).
    crank_radius : float [m]
    journal_diameter, journal_bore : array_like, shape (n_pins,) [m]
        Each throw's journal halves (the element from a main into a throw takes that
        throw's journal section).
    pin_diameter, pin_bore, web_thickness, web_width : array_like, shape (n_pins,) [m]
    youngs_modulus : float [Pa]
    poisson_ratio : float [-]
    support_stiffness : array_like, () or (n_main,) [N/m]
        Radial stiffness of each main bearing, ``inf`` = rigid.
    web_correction : bool, default True
        Apply the web and junction correction fitted to the 3D FE of single throws
        (:func:`web_stiffness_factors`); ``False`` gives the plain beam idealisation above,
        which is 24-1350 % too flexible in bending against the FE.
    throw_torsional_stiffness : array_like, shape (n_pins,) [N m/rad], optional
        Each throw's torsional stiffness by the project's definition (between its journal
        mid-planes, both free to tilt: :mod:`checker.calc.throw_stiffness`, fitted to the 3D
        FE). Given, each throw's webs get their in-plane bending stiffness (``EI`` about the
        crank axis) scaled so that the throw alone in the frame, under that definition, has
        this stiffness (:func:`web_inplane_factor`): the plain web, a beam of length ``R``
        and depth ``B``, is a deep beam whose parts inside the journal and pin circles hardly
        bend (the I4 throw of Bell 2013 alone in the frame: 426 against the FE's
        519 kN m/rad; its webs' in-plane ``EI`` times 4.2). The coupling of torsion and
        bending is the frame's own (docs/crank-geometry.md, "The assembled crank on its main
        bearings").

    Returns
    -------
    CrankFrame
    """
    zm = finite("main_z", main_z).ravel()
    n_main = zm.size
    n_pins = n_main - 1
    if n_pins < 1 or np.any(np.diff(zm) <= 0):
        raise ValueError("main_z must hold at least two increasing positions")
    zw = finite("web_z", web_z).reshape(n_pins, 2)
    if len(pin_load_z) != n_pins:
        raise ValueError("pin_load_z must give the load positions of every pin")
    gam = finite("throw_angle", throw_angle).ravel()
    r = float(positive("crank_radius", crank_radius))
    dj = positive("journal_diameter", journal_diameter) * np.ones(n_pins)
    bj = finite("journal_bore", journal_bore) * np.ones(n_pins)
    dp = positive("pin_diameter", pin_diameter) * np.ones(n_pins)
    bp = finite("pin_bore", pin_bore) * np.ones(n_pins)
    tw = positive("web_thickness", web_thickness) * np.ones(n_pins)
    bw = positive("web_width", web_width) * np.ones(n_pins)
    e = float(positive("youngs_modulus", youngs_modulus))
    nu = float(finite("poisson_ratio", poisson_ratio))
    if not 0.0 <= nu < 0.5:
        raise ValueError("poisson_ratio must lie in [0, 0.5)")
    g = e / (2.0 * (1.0 + nu))
    if gam.size != n_pins or np.any(bj < 0) or np.any(bj >= dj) or np.any(bp < 0) or np.any(
        bp >= dp
    ):
        raise ValueError("one throw angle per pin; bores >= 0 and smaller than their diameters")

    nodes: list[tuple[float, float, float]] = []
    elements: list[tuple[int, int]] = []
    props: list[tuple[float, float, float, float]] = []  # EA, GJ, EI1, EI2
    axes: list[np.ndarray] = []

    def node(x: float, y: float, z: float) -> int:
        nodes.append((x, y, z))
        return len(nodes) - 1

    def shaft(i: int, k: int, d: float, bore: float, factor: float = 1.0) -> None:
        a, inertia = _circle_section(d, bore)
        elements.append((i, k))
        props.append((e * a, g * 2 * inertia, e * inertia * factor, e * inertia * factor))
        axes.append(np.array([1.0, 0.0, 0.0]))

    mains = [node(0.0, 0.0, zm[0])]
    webs = np.zeros((n_pins, 2), dtype=int)
    web_elements = np.zeros((n_pins, 2), dtype=int)
    pins: list[np.ndarray] = []
    for j in range(n_pins):
        if not zm[j] < zw[j, 0] < zw[j, 1] < zm[j + 1]:
            raise ValueError(f"web mid-planes of throw {j + 1} must lie between its mains")
        er = np.array([np.sin(gam[j]), np.cos(gam[j]), 0.0])
        et = np.array([np.cos(gam[j]), -np.sin(gam[j]), 0.0])
        zl = np.unique(finite("pin_load_z", pin_load_z[j]).ravel())
        if zl.size == 0 or zl.min() <= zw[j, 0] or zl.max() >= zw[j, 1]:
            raise ValueError(f"pin load positions of throw {j + 1} must lie between its webs")
        a_w = bw[j] * tw[j]
        if web_correction:
            f_j0, f_p, f_j1, f_wb, f_wt = web_stiffness_factors(
                journal_element=(zw[j, 0] - zm[j], zm[j + 1] - zw[j, 1]),
                pin_span=zw[j, 1] - zw[j, 0], web_thickness=tw[j], web_width=bw[j],
                journal_diameter=dj[j], pin_diameter=dp[j], crank_radius=r)
        else:
            f_j0 = f_p = f_j1 = f_wb = f_wt = 1.0
        bw_e = _effective_web_width(bw[j], dj[j], dp[j]) if web_correction else bw[j]
        web_props = (
            e * a_w,
            g * float(rectangle_torsion_constant(bw_e, tw[j])) * f_wt,
            e * bw_e * tw[j] ** 3 / 12.0 * f_wb,
            e * tw[j] * bw[j] ** 3 / 12.0,
        )
        prev = mains[-1]
        pin_chain = []
        for side in (0, 1):
            axis_node = node(0.0, 0.0, zw[j, side])
            pin_node = node(r * er[0], r * er[1], zw[j, side])
            webs[j, side] = axis_node
            if side == 0:
                shaft(prev, axis_node, dj[j], bj[j], f_j0)
            web_elements[j, side] = len(elements)
            elements.append((axis_node, pin_node))
            props.append(web_props)
            axes.append(et)
            if side == 0:
                pin_chain.append(pin_node)
                loads = [node(r * er[0], r * er[1], z) for z in zl]
                pin_chain.extend(loads)
                pins.append(np.array(loads, dtype=int))
            else:
                pin_chain.append(pin_node)
                for a, b in zip(pin_chain[:-1], pin_chain[1:]):
                    shaft(a, b, dp[j], bp[j], f_p)
                nxt = node(0.0, 0.0, zm[j + 1])
                shaft(axis_node, nxt, dj[j], bj[j], f_j1)
                mains.append(nxt)
    ks = np.asarray(support_stiffness, dtype=float) * np.ones(n_main)
    pr = np.array(props)
    factor = np.ones(n_pins)
    if throw_torsional_stiffness is not None:
        target = positive("throw_torsional_stiffness", throw_torsional_stiffness) * np.ones(
            n_pins)
        cache: dict[tuple, float] = {}
        for j in range(n_pins):
            key = tuple(float(f"{v:.12g}") for v in (  # equal throws: one calibration
                zm[j + 1] - zm[j], zw[j, 0] - zm[j], zw[j, 1] - zm[j], dj[j], bj[j], dp[j],
                bp[j], tw[j], bw[j], target[j]))
            if key not in cache:
                cache[key] = web_inplane_factor(
                    bay_length=key[0], web_z=key[1:3], crank_radius=r, journal_diameter=dj[j],
                    journal_bore=bj[j], pin_diameter=dp[j], pin_bore=bp[j],
                    web_thickness=tw[j], web_width=bw[j], youngs_modulus=e,
                    poisson_ratio=nu, web_correction=web_correction,
                    torsional_stiffness=float(target[j]))
            factor[j] = cache[key]
            pr[web_elements[j], 3] *= factor[j]
    frame = Frame(
        nodes=np.array(nodes),
        elements=np.array(elements, dtype=int),
        axial_stiffness=pr[:, 0],
        torsional_stiffness=pr[:, 1],
        bending_stiffness=pr[:, 2:4],
        first_axis=np.array(axes),
        support_nodes=np.array(mains, dtype=int),
        support_stiffness=ks,
        torsion_node=mains[-1],
    )
    return CrankFrame(
        frame=frame, main_nodes=np.array(mains, dtype=int), web_nodes=webs, pin_nodes=pins,
        web_elements=web_elements, web_inplane_factor=factor,
    )


# Web correction fitted to the 3D FE of single throws (scripts/throw_bending_fe.py; samples with
# their FE flexibilities in checker/calc/data/throw_bending_fe.csv; docs/crank-geometry.md,
# "Throw bending stiffness"): e, eta, (a_b, c_b, k_b) web bending, (a_t, c_t, k_t) web torsion.
WEB_FIT = (0.79, 0.244, 0.717, 0.542, 0.587, 0.443, 0.372, 0.401)
#: Stated error of the corrected frame's bending flexibility of a throw against the 3D FE over
#: the fitted range (largest sample error 15.4 % plus the FE's discretisation error, about 2 %).
WEB_FIT_ERROR = 0.18


def _effective_web_width(width, journal_diameter, pin_diameter, eta: float | None = None):
    """``B' = D + eta (B - D)``, ``D = (Dj + Dp)/2``: the web beyond the shafts counts ``eta``."""
    d = (np.asarray(journal_diameter) + np.asarray(pin_diameter)) / 2.0
    eta = WEB_FIT[1] if eta is None else eta
    return d + eta * (np.asarray(width) - d)


def web_stiffness_factors(
    *, journal_element: tuple[ArrayLike, ArrayLike], pin_span: ArrayLike,
    web_thickness: ArrayLike, web_width: ArrayLike, journal_diameter: ArrayLike,
    pin_diameter: ArrayLike, crank_radius: ArrayLike, coefficients: tuple | None = None,
) -> tuple[np.ndarray, ...]:
    """Bending-stiffness factors of one throw's frame elements, fitted to the 3D FE.

    The plain frame (journal and pin sections up to the web mid-planes, webs as rectangles
    ``B x t_w`` of length ``R``) is 24-1350 % too flexible in bending against a 3D FE of the
    same throw (rigid journal mid-plane faces, docs/crank-geometry.md): the web is a short,
    thick plate whose parts inside the journal and pin circles hardly bend. The correction:

    * journal and pin: of their section's length inside the web only the fraction ``e``
      bends: ``EI`` times ``l / (l - (1 - e) t_w/2)`` for a journal element of length ``l``
      (main to web mid-plane), ``l_p / (l_p - (1 - e) t_w)`` for the pin between the web
      mid-planes;
    * web: effective width ``B' = D + eta (B - D)``, ``D = (Dj + Dp)/2`` (the caller uses it
      for the web's ``I = B' t_w^3/12`` and torsion constant); flexible lengths
      ``l_b = a_b R - c_b D + k_b t_w`` (out-of-plane bending, the pin-plane bending of the
      throw) and ``l_t = a_t R - c_t D + k_t t_w`` (torsion of the web, the bending of the
      throw perpendicular to the pin plane), each at least ``0.05 R``: the web element of
      length ``R`` gets ``EI_1`` times ``R / l_b`` and ``GJ`` times ``R / l_t``.
      ``- c D`` are rigid zones inside the journal and pin, ``k t_w`` the flexibility of the
      web's roots (an equivalent length proportional to the thickness).

    Coefficients (``WEB_FIT``): e 0.79, eta 0.244, a_b 0.717, c_b 0.542, k_b 0.587, a_t 0.443,
    c_t 0.372, k_t 0.401, fitted (L8 norm of the log errors of the end rotations and
    deflections in both planes) to 17 FE throws (the I4 of Bell 2013, 8 extreme combinations,
    8 of a Latin hypercube) and checked on 12 held out (a second Latin hypercube) over the
    issue-33 range (Dp/Dj 0.75-1.0, S/Dj -0.15..0.30, tw/Dj 0.2-0.5, Bj/Dj and Bp/Dp 1.2-1.8,
    Lj/Dj 0.35-0.6, Lp/Dp 0.35-0.75). Largest error (frame / FE - 1) over all 29 throws: in
    the pin plane 8.9 % (rotation under end moment) and 7.5 % (deflection under end force);
    perpendicular to it 12.5 % (rotation) and 15.4 % (deflection, held out; 11.3 % in the
    fit); mean 4.3 %. Stated error ``WEB_FIT_ERROR`` = 18 % (with the FE's own, about 2 %:
    its mesh, 0.15 Dj, is that much too stiff).

    Parameters
    ----------
    journal_element : tuple of two array_like [m]
        Length of the journal elements main -> first web mid-plane and last web -> main.
    pin_span : array_like [m]
        Distance between the web mid-planes (``Lp + t_w``).
    web_thickness, web_width, journal_diameter, pin_diameter, crank_radius : array_like [m]
    coefficients : tuple of 8 floats, optional
        Override of ``WEB_FIT`` (used by the fit).

    Returns
    -------
    f_j0, f_p, f_j1, f_web_bending, f_web_torsion : ndarray [-]
        Factors on the first journal's ``EI``, the pin's ``EI``, the second journal's ``EI``,
        the web's out-of-plane ``EI_1`` and the web's ``GJ`` (all with the effective width).
    """
    e, _eta, ab, cb, kb, at, ct, kt = WEB_FIT if coefficients is None else coefficients
    tw = np.asarray(web_thickness, dtype=float)
    r = np.asarray(crank_radius, dtype=float)
    d = (np.asarray(journal_diameter, dtype=float) + np.asarray(pin_diameter, dtype=float)) / 2
    l0, l1 = (np.asarray(x, dtype=float) for x in journal_element)
    lp = np.asarray(pin_span, dtype=float)
    f_j0 = l0 / (l0 - (1.0 - e) * tw / 2.0)
    f_j1 = l1 / (l1 - (1.0 - e) * tw / 2.0)
    f_p = lp / (lp - (1.0 - e) * tw)
    l_b = np.maximum(ab * r - cb * d + kb * tw, 0.05 * r)
    l_t = np.maximum(at * r - ct * d + kt * tw, 0.05 * r)
    return f_j0, f_p, f_j1, r / l_b, r / l_t


def throw_section_loads(
    pin_force: ArrayLike, bearing_load: ArrayLike, *, pin_z: ArrayLike, main_z: ArrayLike,
    throw_angle: ArrayLike, cut_z: ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bending moments and radial shear at sections of each throw, by statics.

    The crank carries the con-rod forces on its pins and, at its mains, minus the bearing
    loads; the internal loads at an axial cut follow from everything in front of it
    (:func:`section_moment`), whatever scheme gave the bearing loads. Projected on throw ``j``'s
    radial and tangential directions ``e_r = (sin g, cos g)``, ``e_t = (cos g, -sin g)``:

    * ``m_r = -(M . e_t)``: the moment of the radial force (IACS UR M53's ``M_BRF``; with
      lever-rule bearing loads ``m_r`` at the front web centre is ``Q_RF L1`` exactly);
    * ``m_t = M . e_r``: the moment of the tangential force (M53's ``M_BTO``);
    * ``v_r = V . e_r``: the radial shear, ``V`` the sum of the forces in front of the cut
      (the front web's direct force is ``-v_r``, the rear web's ``+v_r``).

    Parameters
    ----------
    pin_force : array_like, shape (..., T, N, 2) [N]
        Force on each pin (sum of its rods), crank frame.
    bearing_load : array_like, shape (..., M, N, 2) [N]
        Force of each main journal on its bearing, crank frame.
    pin_z : array_like, shape (T,) [m]
    main_z : array_like, shape (M,) [m]
    throw_angle : array_like, shape (T,) [rad]
    cut_z : array_like, shape (T, K) [m]
        Axial positions of the sections of each throw.

    Returns
    -------
    m_r, m_t, v_r : ndarray, shape (..., T, K, N) [N m, N m, N]
    """
    fp = finite("pin_force", pin_force)
    fb = finite("bearing_load", bearing_load)
    zp = finite("pin_z", pin_z).ravel()
    zm = finite("main_z", main_z).ravel()
    g = finite("throw_angle", throw_angle).ravel()
    zc = finite("cut_z", cut_z)
    n_t, n_k = zc.shape
    if fp.shape[-3] != zp.size or fb.shape[-3] != zm.size or g.size != n_t:
        raise ValueError("pin_force, bearing_load, pin_z, main_z and throw_angle must match")
    cuts = zc.ravel()
    lp = np.where(zp[None, :] < cuts[:, None], cuts[:, None] - zp[None, :], 0.0)  # (TK, T)
    lm = np.where(zm[None, :] < cuts[:, None], cuts[:, None] - zm[None, :], 0.0)  # (TK, M)
    sp = (zp[None, :] < cuts[:, None]).astype(float)
    sm = (zm[None, :] < cuts[:, None]).astype(float)
    # forces on the crank: the pin forces and minus the bearing loads
    n_ang = fp.shape[-2]
    fp2 = fp.reshape(fp.shape[:-2] + (2 * n_ang,))  # (..., T, 2N): one matrix product each
    fb2 = fb.reshape(fb.shape[:-2] + (2 * n_ang,))
    moment = (lp @ fp2 - lm @ fb2).reshape(fp.shape[:-3] + (cuts.size, n_ang, 2))
    shear = (sp @ fp2 - sm @ fb2).reshape(moment.shape)
    # M = (M_x, M_y) = (lever F_y, -lever F_x)
    mx, my = moment[..., 1], -moment[..., 0]
    gk = np.repeat(g, n_k)[:, None]  # (TK, 1)
    et = (np.cos(gk), -np.sin(gk))
    er = (np.sin(gk), np.cos(gk))
    m_r = -(mx * et[0] + my * et[1])
    m_t = mx * er[0] + my * er[1]
    v_r = shear[..., 0] * er[0] + shear[..., 1] * er[1]
    shape = m_r.shape[:-2] + (n_t, n_k, m_r.shape[-1])
    return m_r.reshape(shape), m_t.reshape(shape), v_r.reshape(shape)


# ------------------------------------------------------------------------------------------
# torsion of the assembled crank (issue 43)
# ------------------------------------------------------------------------------------------
def _torsion_solve(kg: np.ndarray, support_stiffness: np.ndarray, mains: np.ndarray
                   ) -> np.ndarray:
    """Rotation about z of every main node under a unit torque at the last main, the first
    main's rotation and axial motion held, every main held radially by its support (``inf``:
    held; finite: its spring). Returns (n_main,) [rad/(N m)]."""
    n = kg.shape[0]
    k = kg.copy()
    held = [int(mains[0]) * _DOF + 5, int(mains[0]) * _DOF + 2]
    for m, s in zip(mains, support_stiffness, strict=True):
        for c in (0, 1):
            if np.isfinite(s):
                k[m * _DOF + c, m * _DOF + c] += s
            else:
                held.append(int(m) * _DOF + c)
    free = np.setdiff1d(np.arange(n), held)
    f = np.zeros(n)
    f[int(mains[-1]) * _DOF + 5] = 1.0
    u = np.zeros(n)
    try:  # numpy only: the torsional model's derivation imports no scipy
        u[free] = np.linalg.solve(k[np.ix_(free, free)], f[free])
    except np.linalg.LinAlgError as exc:
        raise ValueError("the crank frame is not held in torsion (singular stiffness)") from exc
    return u[np.asarray(mains, dtype=int) * _DOF + 5]


def assembled_torsional_stiffness(crank: CrankFrame) -> np.ndarray:
    r"""Torsional stiffness of each throw of the assembled crank on its main bearings [N m/rad].

    A torque ``T`` passed through the whole frame (applied at the last main, the first main's
    rotation held), every main held radially by its support and free to tilt: throw ``j``'s
    stiffness is ``T / (phi_{j+1} - phi_j)``, ``phi`` the mains' rotations about the crank
    axis. Unlike a throw alone (the project's definition, both journal mid-planes free to
    tilt), a throw in the assembled crank is restrained by its neighbours and the bearings:
    a twisted throw tilts its journals (the offset pin bends under the torque's tangential
    force), and where the neighbour is not its mirror image (180 deg in an I4, 120 deg in an
    I6, 90 deg in a cross-plane V8) the tilts disagree at the shared journal, which the
    bearing holds in place: the bearing reacts a force and the crank is stiffer (the whole I4
    crank: +17 % per throw; pieces of the I4, I6 and V8: +7 to +24 %; docs/crank-geometry.md,
    "The assembled crank on its main bearings", verified against a 3D FE of 2- to 4-throw
    pieces, ``scripts/crank_piece_fe.py``, within 0.6 %).

    Parameters
    ----------
    crank : CrankFrame
        The crank's frame (:func:`crank_frame`, best with ``throw_torsional_stiffness``: its
        throws' torsion calibrated to the 3D FE).

    Returns
    -------
    ndarray, shape (n_pins,) [N m/rad]

    Raises
    ------
    ValueError
        The frame is not held, or a throw's twist is not positive (numerical trouble).
    """
    fr = crank.frame
    phi = _torsion_solve(_assemble(fr), np.asarray(fr.support_stiffness, dtype=float),
                         np.asarray(crank.main_nodes))
    twist = np.diff(phi)
    if not np.all(np.isfinite(twist)) or np.any(twist <= 0.0):
        raise ValueError("the assembled crank's twist per throw is not positive:"
                         f" {twist.tolist()} rad/(N m)")
    return 1.0 / twist


def web_inplane_factor(
    *, bay_length: float, web_z: tuple[float, float], crank_radius: float,
    journal_diameter: float, journal_bore: float, pin_diameter: float, pin_bore: float,
    web_thickness: float, web_width: float, youngs_modulus: float, poisson_ratio: float,
    torsional_stiffness: float, web_correction: bool = True,
) -> float:
    """Factor on a throw's web in-plane bending stiffness that gives the throw alone in the
    frame the stated torsional stiffness (the project's definition: both journal mid-planes
    held radially, free to tilt and to move axially, one turned about the crank axis).

    The frame's stiffness matrix is linear in the factor ``s``: ``K(s) = K_1 + (s - 1) K_w``
    with ``K_w`` the webs' in-plane bending alone; diagonalised once (Cholesky of ``K_1``,
    symmetric eigenproblem of ``K_w`` in its metric), the throw's torsional compliance is a
    sum of ``g_i^2 / (1 + (s - 1) lam_i)``, falling monotonically with ``s``; the root is found
    in ``log s`` on ``[1e-3, 1e4]`` (Illinois false position, to 1e-13 in ``log k``).

    Parameters
    ----------
    bay_length : float [m]
        Distance between the throw's main journal mid-planes.
    web_z : tuple of two floats [m]
        The webs' mid-planes from the first main.
    crank_radius, journal_diameter, journal_bore, pin_diameter, pin_bore, web_thickness,
    web_width : float [m]
    youngs_modulus : float [Pa]
    poisson_ratio : float [-]
    torsional_stiffness : float [N m/rad]
        The throw's stiffness by the definition (:mod:`checker.calc.throw_stiffness`).
    web_correction : bool
        As :func:`crank_frame`.

    Returns
    -------
    float [-]

    Raises
    ------
    ValueError
        No factor in ``[1e-3, 1e4]`` reaches the stiffness (the frame's journals and pin
        alone are more flexible than the throw, or its webs far too stiff).
    """
    one = crank_frame(
        main_z=[0.0, bay_length], web_z=[list(web_z)], pin_load_z=[[sum(web_z) / 2.0]],
        throw_angle=[0.0], crank_radius=crank_radius, journal_diameter=journal_diameter,
        journal_bore=journal_bore, pin_diameter=pin_diameter, pin_bore=pin_bore,
        web_thickness=web_thickness, web_width=web_width, youngs_modulus=youngs_modulus,
        poisson_ratio=poisson_ratio, support_stiffness=np.inf, web_correction=web_correction)
    fr = one.frame
    k1 = _assemble(fr)
    kw = np.zeros_like(k1)
    for e_idx in one.web_elements.ravel():
        i, k = fr.elements[e_idx]
        ke = element_stiffness(fr.nodes[i], fr.nodes[k], 0.0, 0.0, 0.0,
                               float(fr.bending_stiffness[e_idx, 1]), fr.first_axis[e_idx])
        idx = np.r_[i * _DOF:(i + 1) * _DOF, k * _DOF:(k + 1) * _DOF]
        kw[np.ix_(idx, idx)] += ke
    mains = np.asarray(one.main_nodes)
    target = float(torsional_stiffness)
    # the definition's held dofs; on the free ones K(s) = K_1 + t K_w (t = s - 1) is
    # diagonalised once: with K_1 = L L^T and L^-1 K_w L^-T = U diag(lam) U^T, the compliance
    # under the unit torque f is sum g_i^2 / (1 + t lam_i), g = U^T L^-1 f (lam >= 0)
    held = {int(mains[0]) * _DOF + 5, int(mains[0]) * _DOF + 2}
    held |= {int(m) * _DOF + c for m in mains for c in (0, 1)}
    free = np.array(sorted(set(range(k1.shape[0])) - held))
    f = np.zeros(k1.shape[0])
    f[int(mains[-1]) * _DOF + 5] = 1.0
    try:
        chol = np.linalg.cholesky(k1[np.ix_(free, free)])
    except np.linalg.LinAlgError as exc:
        raise ValueError("the throw's frame is not held in torsion") from exc
    x = np.linalg.solve(chol, kw[np.ix_(free, free)])
    lam, u = np.linalg.eigh(np.linalg.solve(chol, x.T))
    g2 = (u.T @ np.linalg.solve(chol, f[free])) ** 2
    lam = np.maximum(lam, 0.0)

    def gap(log_s: float) -> float:
        compliance = float(np.sum(g2 / (1.0 + (np.exp(log_s) - 1.0) * lam)))
        return float(np.log(1.0 / (compliance * target)))

    lo, hi = np.log(1e-3), np.log(1e4)
    g_lo, g_hi = gap(lo), gap(hi)
    if not (g_lo <= 0.0 <= g_hi):
        k_lo, k_hi = (target * np.exp(g) for g in (g_lo, g_hi))
        raise ValueError(
            f"the throw's torsional stiffness {target:.6g} N m/rad is outside what the frame"
            f" reaches by its webs' in-plane stiffness ({k_lo:.6g} to {k_hi:.6g} N m/rad)")
    # the Illinois variant of the false position (the gap rises monotonically with log s)
    a, b, fa, fb = lo, hi, g_lo, g_hi
    for _ in range(200):
        c = b - fb * (b - a) / (fb - fa)
        fc = gap(c)
        if abs(fc) < 1e-13 or fc == fb:
            return float(np.exp(c))
        if fc * fb < 0.0:
            a, fa = b, fb
        else:
            fa *= 0.5
        b, fb = c, fc
    raise ValueError("the web in-plane factor did not converge")


def balancing_torques(torque: ArrayLike, inertia: ArrayLike, output: int) -> np.ndarray:
    r"""Torques that balance the crank's applied torque: the load at the output, d'Alembert's
    inertia torques on the rotating inertias.

    Over one steady cycle the torque of the con-rods about the crank axis, ``T(theta)``, leaves
    the engine at its output (the flywheel flange) as its cycle mean ``T_m`` (the load); the
    rest speeds up and slows down the rotating system as a rigid body,
    ``J alpha = T - T_m`` with ``J = sum J_i``, and each inertia takes its d'Alembert torque
    ``-J_i alpha`` (Ker Wilson, Practical Solution of Torsional Vibration Problems, vol. 1,
    1956, the engine's turning-moment diagram and its flywheel; Den Hartog, Mechanical
    Vibrations, 4th ed., 1956, sec. 5.9):

    .. math::

        M_i = -\frac{J_i}{J} (T - T_m) - \delta_{i,out} T_m,
        \qquad \sum_i M_i = -T .

    Parameters
    ----------
    torque : array_like, shape (..., N) [N m]
        Applied torque about the crank axis at ``N`` equally spaced angles of one cycle.
    inertia : array_like, shape (K,) [kg m^2]
        The rotating inertias (e.g. the torsional model's stations), each > 0.
    output : int
        Index of the inertia where the torque leaves the engine (the flywheel).

    Returns
    -------
    ndarray, shape (..., K, N) [N m]
        Torque on the crank at each inertia; with ``torque`` they sum to zero at every angle.
    """
    t = finite("torque", torque)
    j = positive("inertia", inertia).ravel()
    if not 0 <= int(output) < j.size:
        raise ValueError("output must index one of the inertias")
    mean = t.mean(axis=-1, keepdims=True)
    out = -(j / j.sum())[:, None] * (t - mean)[..., None, :]
    out[..., int(output), :] -= mean
    return out
