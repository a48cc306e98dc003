"""Linear-elastic 3D finite-element model of one crank throw: torsional stiffness.

    python scripts/throw_fe.py [--Dj MM ...] [--size H] [--variant free|rigid|held] [--full]

Needs the optional extra ``fe`` (``pip install -e .[fe]``: gmsh, scikit-fem, meshio); the
check never imports this file (it reads the fitted data of
``checker/calc/throw_stiffness.py``).

Geometry (the project's crank-geometry definition, docs/crank-geometry.md): crank axis z, main
axis at x = y = 0, pin axis at (0, R). Between the mid-planes of its two main journals
(z = 0 .. L, L = Lj + 2 tw + Lp): half journal (Lj/2, diameter Dj, bore dj), web (tw), pin
(Lp, Dp, bore dp), web, half journal. A web's outline is the convex hull of a circle of
diameter Bj about the main axis and one of diameter Bp about the pin axis; a counterweight is
an annular sector (ri, ro, included angle alpha, axial thickness tc centred on the web) about
the main axis, bisected by -y, fused with its web. Built with gmsh's OpenCASCADE kernel
(boolean union), meshed with curved quadratic tetrahedra (10 nodes, isoparametric), assembled
and solved with scikit-fem (isotropic linear elasticity, E, nu).

Definition of the stiffness (boundary conditions)
-------------------------------------------------
On both journal mid-plane faces the in-plane displacement is prescribed as a rigid rotation
about the crank axis (face z = 0: angle 0; face z = L: angle theta): ``u_x = -theta y``,
``u_y = theta x``. This holds the journal centre in x and y (as a main bearing does) and turns
the face rigidly about the axis. The axial displacement ``u_z`` of the faces is left free
(variant ``free``, the definition): the faces may tilt, shift axially (and warp). Stiffness =
reaction torque / theta = ``u^T K u / theta^2`` (the work of the prescribed displacements; the
same number as the summed nodal reaction moments).

Why ``u_z`` free node by node: for a chain of identical throws under a uniform torque each
journal mid-plane is a plane of mirror symmetry of the geometry, and the twist is antisymmetric
about it; the antisymmetry forces the in-plane displacement of the plane to be exactly a rigid
rotation and leaves ``u_z`` unconstrained. The variants, for comparison:

* ``rigid``: each face stays plane and rigid (``u_z = a + b x + c y`` with a, b, c free: a
  rigid face on a bearing, free to tilt and shift axially, not to warp);
* ``held``: ``u_z = 0`` on both faces (the faces clamped axially): markedly stiffer.

Symmetry used (exact for this geometry): the plane x = 0 (it contains both axes) is a mirror
plane of the throw and the twist is antisymmetric about it, so ``u_y = u_z = 0`` there; with
equal journals and webs the pin mid-plane z = L/2 is one too, where the in-plane displacement
is the rigid rotation theta/2 and ``u_z`` is free. The model solves the quarter
``x >= 0, z <= L/2`` (``full=True`` solves the whole throw, used to check the symmetry).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import dataclass, field, replace

import numpy as np

__all__ = ["Throw", "FEResult", "build_mesh", "solve_throw", "shaft", "rect_bar", "I4_THROW"]


@dataclass(frozen=True)
class Throw:
    """One throw's dimensions [m] and material [Pa, -]."""

    Dj: float
    Dp: float
    Lj: float
    Lp: float
    tw: float
    R: float
    Bj: float
    Bp: float
    dj: float = 0.0
    dp: float = 0.0
    E: float = 210e9
    nu: float = 0.3
    cw_ri: float = 0.0
    cw_ro: float = 0.0
    cw_angle: float = 0.0
    cw_t: float = 0.0

    @property
    def length(self) -> float:
        return self.Lj + 2.0 * self.tw + self.Lp

    @property
    def G(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def has_cw(self) -> bool:
        return self.cw_t > 0.0 and self.cw_ro > self.cw_ri and self.cw_angle > 0.0


# The I4 of Bell (2013): Dj 55, Dp 48, Lj 27, Lp 24.4, tw 22.3, R 47.3 mm, web width 75.7 mm,
# G 80.8 GPa (E 210 GPa, nu 0.2995). Solid journals and pin, no counterweight, both web widths
# 75.7 mm (the only width published).
I4_THROW = Throw(Dj=0.055, Dp=0.048, Lj=0.027, Lp=0.0244, tw=0.0223, R=0.0473,
                 Bj=0.0757, Bp=0.0757, E=210e9, nu=210e9 / (2 * 80.8e9) - 1.0)


@dataclass
class FEResult:
    stiffness: float          # N m/rad, whole throw between the journal mid-planes
    n_nodes: int
    n_elements: int
    n_dofs: int
    seconds: float
    variant: str
    size: float
    info: dict = field(default_factory=dict)


# --------------------------------------------------------------------------------------------
# geometry and mesh
# --------------------------------------------------------------------------------------------
def _web_outline_volume(occ, z0: float, t: float, r1: float, r2: float, R: float) -> list:
    """Prism of thickness t from z0: convex hull of circle r1 at (0,0) and r2 at (0,R)."""
    if R + r2 <= r1:
        return [(3, occ.addCylinder(0, 0, z0, 0, 0, t, r1))]
    if R + r1 <= r2:
        return [(3, occ.addCylinder(0, R, z0, 0, 0, t, r2))]
    c1 = occ.addCylinder(0, 0, z0, 0, 0, t, r1)
    c2 = occ.addCylinder(0, R, z0, 0, 0, t, r2)
    s = (r1 - r2) / R                     # sin(phi): tangent normal n = (+-cos phi, sin phi)
    c = math.sqrt(1.0 - s * s)
    pts = [(r1 * c, r1 * s), (r2 * c, R + r2 * s), (-r2 * c, R + r2 * s), (-r1 * c, r1 * s)]
    tags = [occ.addPoint(x, y, z0) for x, y in pts]
    lines = [occ.addLine(tags[i], tags[(i + 1) % 4]) for i in range(4)]
    surf = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    ext = occ.extrude([(2, surf)], 0, 0, t)
    prism = [e for e in ext if e[0] == 3]
    return [(3, c1), (3, c2)] + prism


def _tube(occ, x: float, y: float, z0: float, length: float, d_out: float, d_in: float) -> list:
    outer = occ.addCylinder(x, y, z0, 0, 0, length, d_out / 2)
    if d_in <= 0.0:
        return [(3, outer)]
    inner = occ.addCylinder(x, y, z0, 0, 0, length, d_in / 2)
    out, _ = occ.cut([(3, outer)], [(3, inner)])
    return out


def _counterweight(occ, th: Throw, zmid: float) -> list:
    z0 = zmid - th.cw_t / 2
    sec = occ.addCylinder(0, 0, z0, 0, 0, th.cw_t, th.cw_ro, -1, th.cw_angle)
    occ.rotate([(3, sec)], 0, 0, 0, 0, 0, 1, -math.pi / 2 - th.cw_angle / 2)
    if th.cw_ri <= 0.0:
        return [(3, sec)]
    hole = occ.addCylinder(0, 0, z0 - 1e-3 * th.cw_t, 0, 0, 1.002 * th.cw_t, th.cw_ri)
    out, _ = occ.cut([(3, sec)], [(3, hole)])
    return out


def _size_expression(th: Throw, h: float, grade: float, quarter: bool) -> str:
    """Mesh size: h far away, h * 0.25 at the re-entrant junction edges (journal-web,
    pin-web, bore bottoms), growing linearly with distance (gradient ``grade``)."""
    z1 = th.Lj / 2
    z2 = th.Lj / 2 + th.tw
    circles = [(0.0, th.Dj / 2, z1), (th.R, th.Dp / 2, z2)]
    if not quarter:
        z3, z4 = th.length - z2, th.length - z1
        circles += [(th.R, th.Dp / 2, z3), (0.0, th.Dj / 2, z4)]
    if th.dj > 0:
        circles.append((0.0, th.dj / 2, z1))
        if not quarter:
            circles.append((0.0, th.dj / 2, th.length - z1))
    if th.dp > 0:
        circles.append((th.R, th.dp / 2, z2))
        if not quarter:
            circles.append((th.R, th.dp / 2, th.length - z2))
    dists = [f"Sqrt((Sqrt(x*x+(y-{yc!r})*(y-{yc!r}))-{r!r})^2+(z-{zc!r})^2)"
             for yc, r, zc in circles]
    d = dists[0]
    for e in dists[1:]:
        d = f"Min({d},{e})"
    hmin = 0.25 * h
    return f"Min({h!r},{hmin!r}+{grade!r}*{d})"


def _tet_arrays(gmsh) -> tuple[np.ndarray, np.ndarray]:
    """The generated mesh as arrays: node coordinates (n, 3) [m] and the 10-node tetrahedra
    (m, 10) as indices into them (gmsh numbers nodes by tags)."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    etypes, _, enodes = gmsh.model.mesh.getElements(3)
    if list(etypes) != [11]:
        raise RuntimeError(f"expected only 10-node tetrahedra, got types {list(etypes)}")
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    return coords.reshape(-1, 3), index[enodes[0].astype(np.int64)].reshape(-1, 10)


def build_mesh(th: Throw, size: float, *, full: bool = False, grade: float = 0.5,
               verbose: bool = False, half: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Mesh the throw (or its quarter x >= 0, z <= L/2; ``half``: the half x >= 0 over the
    whole length, used by the bending FE) with 10-node tetrahedra.

    ``size`` is the element size far from the junctions as a fraction of Dj. Returns
    ``(points (n, 3), tets (m, 10))`` in gmsh's node order.
    """
    import gmsh

    h = size * th.Dj
    L = th.length
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("throw")
        occ = gmsh.model.occ
        z1 = th.Lj / 2
        parts = _tube(occ, 0, 0, 0, z1, th.Dj, th.dj)
        parts += _web_outline_volume(occ, z1, th.tw, th.Bj / 2, th.Bp / 2, th.R)
        parts += _tube(occ, 0, th.R, z1 + th.tw, th.Lp, th.Dp, th.dp)
        parts += _web_outline_volume(occ, z1 + th.tw + th.Lp, th.tw, th.Bj / 2, th.Bp / 2, th.R)
        parts += _tube(occ, 0, 0, L - z1, z1, th.Dj, th.dj)
        if th.has_cw:
            parts += _counterweight(occ, th, z1 + th.tw / 2)
            parts += _counterweight(occ, th, L - z1 - th.tw / 2)
        vol, _ = occ.fuse(parts[:1], parts[1:])
        if not full:
            big = 10.0 * (th.R + th.Bj + th.Bp + th.cw_ro)
            box = occ.addBox(0, -big, -0.1 * L, big, 2 * big, (1.2 if half else 0.6) * L)
            vol, _ = occ.intersect(vol, [(3, box)])
        occ.synchronize()
        if len(vol) != 1:
            raise RuntimeError(f"geometry is not one solid ({len(vol)} volumes)")
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        fld = gmsh.model.mesh.field
        f = fld.add("MathEval")
        fld.setString(f, "F", _size_expression(th, h, grade, quarter=not (full or half)))
        fld.setAsBackgroundMesh(f)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)
        gmsh.model.mesh.generate(3)
        return _tet_arrays(gmsh)
    finally:
        gmsh.finalize()


def _skfem_mesh(pts: np.ndarray, tets: np.ndarray):
    """scikit-fem MeshTet2 from gmsh 10-node tetrahedra (the edge nodes matched to the edges
    by vertex pair, whatever the two programs' local orders)."""
    from skfem import MeshTet1, MeshTet2

    verts = np.unique(tets[:, :4])
    remap = -np.ones(len(pts), dtype=np.int64)
    remap[verts] = np.arange(len(verts))
    t4 = remap[tets[:, :4]]
    m1 = MeshTet1(np.ascontiguousarray(pts[verts].T), np.ascontiguousarray(t4.T))
    m2 = MeshTet2.from_mesh(m1)
    # gmsh's edge-node slots: find which vertex pair each slot belongs to (nearest midpoint)
    sample = tets[: min(len(tets), 200)]
    pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    slot_pair = []
    for s in range(4, 10):
        d = [np.linalg.norm(pts[sample[:, s]] - 0.5 * (pts[sample[:, a]] + pts[sample[:, b]]),
                            axis=1).mean() for a, b in pairs]
        slot_pair.append(pairs[int(np.argmin(d))])
    if len(set(slot_pair)) != 6:
        raise RuntimeError("could not match gmsh's edge nodes to edges")
    nv = len(verts)
    keys, locs = [], []
    for s, (a, b) in zip(range(4, 10), slot_pair):
        va, vb = t4[:, a], t4[:, b]
        keys.append(np.minimum(va, vb) * nv + np.maximum(va, vb))
        locs.append(pts[tets[:, s]])
    keys = np.concatenate(keys)
    locs = np.concatenate(locs)
    ukeys, first = np.unique(keys, return_index=True)
    edges = np.sort(m2.edges, axis=0)
    ekeys = edges[0].astype(np.int64) * nv + edges[1]
    pos = np.searchsorted(ukeys, ekeys)
    if not np.array_equal(ukeys[pos], ekeys):
        raise RuntimeError("edge nodes missing")
    doflocs = m2.doflocs.copy()
    doflocs[:, nv:nv + m2.edges.shape[1]] = locs[first[pos]].T
    return MeshTet2(doflocs, m2.t)


# --------------------------------------------------------------------------------------------
# solve
# --------------------------------------------------------------------------------------------
def solve_mesh(pts: np.ndarray, tets: np.ndarray, *, E: float, nu: float, length: float,
               quarter: bool, variant: str = "free", theta: float = 1e-3) -> tuple[float, dict]:
    """Stiffness [N m/rad] of the body between z = 0 and z = length (or its quarter)."""
    import scipy.sparse as sp
    from skfem import Basis, ElementTetP2, ElementVector, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    mesh = _skfem_mesh(pts, tets)
    basis = Basis(mesh, ElementVector(ElementTetP2()), intorder=3)
    K = asm(linear_elasticity(*lame_parameters(E, nu)), basis).tocsr()
    n = K.shape[0]
    ix, iy, iz = basis.split_indices()
    X = basis.doflocs
    x, y, z = X[0, ix], X[1, ix], X[2, ix]
    tol = 1e-7 * length
    zend = length / 2 if quarter else length
    th_end = theta / 2 if quarter else theta
    at_a = np.abs(z) < tol
    at_b = np.abs(z - zend) < tol
    u = np.zeros(n)
    fixed = np.zeros(n, dtype=bool)
    for sel, ang in ((at_a, 0.0), (at_b, th_end)):
        fixed[ix[sel]] = True
        fixed[iy[sel]] = True
        u[ix[sel]] = -ang * y[sel]
        u[iy[sel]] = ang * x[sel]
    if quarter:
        on_sym = np.abs(x) < tol
        fixed[iy[on_sym]] = True
        fixed[iz[on_sym]] = True
        u[iy[on_sym]] = 0.0
        u[iz[on_sym]] = 0.0
    T = None
    if variant == "held":
        for sel in (at_a, at_b):
            fixed[iz[sel]] = True
    elif variant == "rigid":
        if not quarter:
            raise NotImplementedError("the rigid-face variant is implemented for the quarter")
        # u_z on each face = b x (a rigid face; the x-antisymmetry of the quarter leaves only
        # the tilt b about y): u = u0 + T v, v = (free dofs other than the faces' u_z, b_A, b_B)
        slave = np.zeros(n, dtype=bool)
        slave[iz[at_a]] = True
        slave[iz[at_b]] = True
        keep = np.flatnonzero(~fixed & ~slave)
        rows = [keep, iz[at_a], iz[at_b]]
        cols = [np.arange(len(keep)), np.full(at_a.sum(), len(keep)),
                np.full(at_b.sum(), len(keep) + 1)]
        vals = [np.ones(len(keep)), x[at_a], x[at_b]]
        T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(n, len(keep) + 2))
    elif variant != "free":
        raise ValueError(f"unknown variant {variant!r}")
    if not quarter and variant == "free":
        # the axial translation is a rigid mode: hold one node's u_z on face A
        fixed[iz[np.flatnonzero(at_a)[0]]] = True
    f = -(K @ u)
    t0 = time.perf_counter()
    if T is None:
        fr = np.flatnonzero(~fixed)
        u[fr] = _spd_solve(K[fr][:, fr], f[fr])
    else:
        u = u + T @ _spd_solve((T.T @ K @ T).tocsr(), T.T @ f)
    t_solve = time.perf_counter() - t0
    energy2 = float(u @ (K @ u))           # = 2 U
    if quarter:
        k = energy2 / (th_end ** 2)        # 2 U_q / (theta/2)^2 with U_q = energy2/2
    else:
        k = energy2 / theta ** 2
    info = dict(t_solve=t_solve, n_dofs=n, n_vertices=mesh.nvertices)
    return k, info


def _spd_solve(A, b: np.ndarray) -> np.ndarray:
    """Sparse symmetric positive definite solve: MKL PARDISO (``pypardiso``) where installed,
    else SuperLU (COLAMD ordering); the same answer, PARDISO a few times faster."""
    try:
        import pypardiso
    except ImportError:
        import scipy.sparse.linalg as spla

        return spla.splu(A.tocsc(), permc_spec="COLAMD").solve(b)
    x = pypardiso.spsolve(A.tocsr(), b)
    pypardiso.ps.free_memory(everything=True)
    return x


def solve_throw(th: Throw, size: float = 0.12, *, variant: str = "free", full: bool = False,
                grade: float = 0.5) -> FEResult:
    """Torsional stiffness of one throw between its journal mid-planes [N m/rad]."""
    t0 = time.perf_counter()
    pts, tets = build_mesh(th, size, full=full, grade=grade)
    t_mesh = time.perf_counter() - t0
    k, info = solve_mesh(pts, tets, E=th.E, nu=th.nu, length=th.length, quarter=not full,
                         variant=variant)
    info["t_mesh"] = t_mesh
    return FEResult(stiffness=k, n_nodes=len(pts), n_elements=len(tets), n_dofs=info["n_dofs"],
                    seconds=time.perf_counter() - t0, variant=variant, size=size, info=info)


# --------------------------------------------------------------------------------------------
# validation bodies: shafts with closed-form stiffness
# --------------------------------------------------------------------------------------------
def shaft_mesh(D: float, d: float, L: float, size: float, full: bool = False):
    """Plain (d = 0) or hollow shaft z = 0 .. L (quarter: x >= 0, z <= L/2)."""
    import gmsh

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("shaft")
        occ = gmsh.model.occ
        vol = _tube(occ, 0, 0, 0, L, D, d)
        if not full:
            box = occ.addBox(0, -D, -0.1 * L, D, 2 * D, 0.6 * L)
            vol, _ = occ.intersect(vol, [(3, box)])
        occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", size * D)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size * D)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(3)
        return _tet_arrays(gmsh)
    finally:
        gmsh.finalize()


def shaft(D: float, d: float, L: float, *, E: float = 210e9, nu: float = 0.3,
          size: float = 0.25, variant: str = "free", full: bool = False) -> float:
    """FE torsional stiffness of a plain or hollow round shaft [N m/rad]."""
    pts, tets = shaft_mesh(D, d, L, size, full=full)
    k, _ = solve_mesh(pts, tets, E=E, nu=nu, length=L, quarter=not full, variant=variant)
    return k


def rect_bar(a: float, b: float, L: float, *, E: float = 210e9, nu: float = 0.3,
             size: float = 0.2, variant: str = "free") -> float:
    """FE torsional stiffness of a rectangular bar a x b (x by y), quarter model."""
    import gmsh

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("bar")
        occ = gmsh.model.occ
        occ.addBox(0, -b / 2, 0, a / 2, b, L / 2)
        occ.synchronize()
        h = size * min(a, b)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(3)
        pts, tets = _tet_arrays(gmsh)
    finally:
        gmsh.finalize()
    k, _ = solve_mesh(pts, tets, E=E, nu=nu, length=L, quarter=True, variant=variant)
    return k


def rect_torsion_constant(a: float, b: float, n_terms: int = 200) -> float:
    """Saint-Venant torsion constant of an a x b rectangle (a >= b) [m^4]: the series
    J = a b^3 / 3 [1 - 192 b / (pi^5 a) sum_{n odd} tanh(n pi a / (2 b)) / n^5]
    (Timoshenko & Goodier, Theory of Elasticity, 3rd ed. 1970, sec. 109, eq. (163))."""
    a, b = max(a, b), min(a, b)
    n = np.arange(1, 2 * n_terms, 2, dtype=float)
    s = np.sum(np.tanh(n * np.pi * a / (2 * b)) / n ** 5)
    return a * b ** 3 / 3 * (1 - 192 * b / (np.pi ** 5 * a) * s)


_MM = ("Dj", "Dp", "Lj", "Lp", "tw", "R", "Bj", "Bp", "dj", "dp", "cw_ri", "cw_ro", "cw_t")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description=__doc__.splitlines()[0],
        epilog="Without dimensions: the I4 throw of Bell (2013). Dimensions in mm, e.g. "
               "--Dj 55 --Dp 48 --Lj 27 --Lp 24.4 --tw 22.3 --R 47.3 --Bj 75.7 --Bp 75.7")
    for name in _MM:
        ap.add_argument(f"--{name}", type=float, help="mm")
    ap.add_argument("--E", type=float, help="Young's modulus, GPa")
    ap.add_argument("--nu", type=float, help="Poisson's ratio")
    ap.add_argument("--cw_angle", type=float, help="counterweight included angle, deg")
    ap.add_argument("--size", type=float, default=0.12, help="element size / Dj (far field)")
    ap.add_argument("--variant", default="free", choices=["free", "rigid", "held"])
    ap.add_argument("--full", action="store_true", help="whole throw instead of the quarter")
    args = ap.parse_args(argv)
    given = {k: getattr(args, k) / 1e3 for k in _MM if getattr(args, k) is not None}
    if args.E is not None:
        given["E"] = args.E * 1e9
    if args.nu is not None:
        given["nu"] = args.nu
    if args.cw_angle is not None:
        given["cw_angle"] = math.radians(args.cw_angle)
    th = replace(I4_THROW, **given)
    r = solve_throw(th, args.size, variant=args.variant, full=args.full)
    what = "I4 throw (Bell 2013 dimensions)" if not given else "throw"
    print(f"{what}: {r.stiffness / 1e3:.2f} kN m/rad [{r.variant}, size {r.size}, "
          f"{r.n_elements} tets, {r.n_dofs} dofs, {r.seconds:.1f} s]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
