"""Linear-elastic 3D FE of a piece of crank (several throws) on its main bearings: torsion.

    python scripts/crank_piece_fe.py [--engine i4|i6|v8] [--throws N] [--size H] [--free-inner]
    python scripts/crank_piece_fe.py --table [--size H]
        (the verification pieces -> checker/calc/data/crank_piece_fe.json)

Needs the optional extra ``fe`` (gmsh, scikit-fem), like ``scripts/throw_fe.py`` whose throw
solid and mesh it reuses; the check never imports this file.

Geometry: ``n`` equal throws of ``scripts/throw_fe.py`` (crank axis z, the geometry of
docs/crank-geometry.md) one after the other, throw ``j`` between the main-journal mid-planes
``z = j L`` and ``(j + 1) L`` (``L = Lj + 2 tw + Lp``), its pin axis at
``R (sin g_j, cos g_j)`` (the crank frame of :mod:`checker.calc.crank_beam`). Each throw is
fused on its own and the throws are joined with gmsh's ``fragment``, so the inner main-journal
mid-planes are faces of the mesh (a conforming interface: the journal is continuous).

Boundary conditions (the throw definition of ``scripts/throw_fe.py`` at the piece's ends, the
main bearings inside):

* the two end faces (outer main mid-planes): in-plane rigid rotation about the crank axis
  (``u_x = -theta y``, ``u_y = theta x``; angle 0 at ``z = 0``, ``theta`` at ``z = n L``),
  ``u_z`` free node by node (tilt, axial motion and warping free);
* every inner main journal is held by its bearing: the centre of its mid-plane section does
  not move in x and y, ``int u_x dA = int u_y dA = 0`` over the section (Lagrange
  multipliers, the multiplier is the bearing's reaction force); the journal is free to turn,
  to tilt and to move axially (the continuous beam's support, :mod:`checker.calc.crank_beam`);
  ``--free-inner`` drops the bearings (the series sum of the throws then holds for throws at
  180 deg, the check of issue 43).

Outputs: the end-to-end stiffness ``k = u^T K u / theta^2`` (the work of the prescribed
rotation; the bearings do no work), the rotation of every inner main (the section's
least-squares rigid rotation ``int (x u_y - y u_x) dA / int (x^2 + y^2) dA``) and its bearing
reaction per unit torque.

Symmetry: where every pin lies in the plane x = 0 (throws at 0 and 180 deg: the I4), that
plane is a mirror plane of the piece with the twist antisymmetric about it (``u_y = u_z = 0``
there, ``u_x`` even: only the x bearing constraint remains); the half ``x >= 0`` is solved.
Otherwise (the I6's 120 deg) the whole piece.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
_spec = importlib.util.spec_from_file_location("throw_fe", ROOT / "scripts" / "throw_fe.py")
throw_fe = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("throw_fe", throw_fe)
_spec.loader.exec_module(throw_fe)
Throw = throw_fe.Throw

__all__ = ["PieceResult", "build_piece_mesh", "solve_piece", "PIECES", "EXAMPLE_THROWS"]


@dataclass
class PieceResult:
    stiffness: float            # N m/rad, end to end (outer main mid-planes)
    main_rotation: np.ndarray   # (n + 1,) rad per rad of end rotation, every main
    bearing_force: np.ndarray   # (n + 1, 2) N per N m of torque, (x, y) at every main (0 at ends)
    n_dofs: int
    seconds: float
    size: float
    info: dict = field(default_factory=dict)


def _all_in_plane(gammas: list[float]) -> bool:
    return all(abs(math.sin(g)) < 1e-9 for g in gammas)


def _throw_volume(occ, th: Throw, z0: float, gamma: float) -> list:
    """One throw (the solid of ``throw_fe.build_mesh``) from z0, turned by gamma about z
    (pin from +y towards +x: the crank frame's R (sin g, cos g))."""
    z1 = th.Lj / 2
    L = th.length
    parts = throw_fe._tube(occ, 0, 0, z0, z1, th.Dj, th.dj)
    parts += throw_fe._web_outline_volume(occ, z0 + z1, th.tw, th.Bj / 2, th.Bp / 2, th.R)
    parts += throw_fe._tube(occ, 0, th.R, z0 + z1 + th.tw, th.Lp, th.Dp, th.dp)
    parts += throw_fe._web_outline_volume(occ, z0 + z1 + th.tw + th.Lp, th.tw, th.Bj / 2,
                                          th.Bp / 2, th.R)
    parts += throw_fe._tube(occ, 0, 0, z0 + L - z1, z1, th.Dj, th.dj)
    if th.has_cw:
        for zc in (z0 + z1 + th.tw / 2, z0 + L - z1 - th.tw / 2):
            parts += throw_fe._counterweight(occ, th, zc)
    vol, _ = occ.fuse(parts[:1], parts[1:])
    # rotate so that the pin at (0, R) goes to R (sin g, cos g): a turn by -g about z
    if abs(gamma) > 0:
        occ.rotate(vol, 0, 0, 0, 0, 0, 1, -gamma)
    return vol


def _size_expression(th: Throw, gammas: list[float], h: float, grade: float) -> str:
    """h far away, h/4 at the re-entrant junction edges of every throw (journal-web, pin-web,
    bore bottoms), growing linearly with the distance (as ``throw_fe``)."""
    L = th.length
    circles = []
    for j, g in enumerate(gammas):
        z0 = j * L
        xp, yp = th.R * math.sin(g), th.R * math.cos(g)
        zj = (z0 + th.Lj / 2, z0 + L - th.Lj / 2)
        zp = (z0 + th.Lj / 2 + th.tw, z0 + L - th.Lj / 2 - th.tw)
        for z in zj:
            circles.append((0.0, 0.0, th.Dj / 2, z))
            if th.dj > 0:
                circles.append((0.0, 0.0, th.dj / 2, z))
        for z in zp:
            circles.append((xp, yp, th.Dp / 2, z))
            if th.dp > 0:
                circles.append((xp, yp, th.dp / 2, z))
    dists = [f"Sqrt((Sqrt((x-({xc:.9f}))^2+(y-({yc:.9f}))^2)-{r:.9f})^2+(z-({zc:.9f}))^2)"
             for xc, yc, r, zc in circles]
    d = dists[0]
    for e in dists[1:]:
        d = f"Min({d},{e})"
    return f"Min({h!r},{0.25 * h!r}+{grade!r}*{d})"


def build_piece_mesh(ths: list[Throw], gammas: list[float], size: float, *,
                     half: bool | None = None, grade: float = 0.5
                     ) -> tuple[np.ndarray, np.ndarray, bool]:
    """Mesh the piece (10-node tetrahedra; ``ths`` one throw per angle, equal but for their
    counterweights); returns (points, tets, half)."""
    import gmsh

    th = ths[0]
    if half is None:
        half = _all_in_plane(gammas)
    h = size * th.Dj
    L = th.length
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("piece")
        occ = gmsh.model.occ
        vols = [_throw_volume(occ, t, j * L, g) for j, (t, g) in enumerate(zip(ths, gammas))]
        if half:
            big = 10.0 * (th.R + th.Bj + th.Bp + th.cw_ro)
            cut = []
            for v in vols:
                box = occ.addBox(0, -big, -0.1 * L, big, 2 * big, (len(gammas) + 0.2) * L)
                out, _ = occ.intersect(v, [(3, box)])
                cut.append(out)
            vols = cut
        flat = [e for v in vols for e in v]
        if len(vols) > 1:
            flat, _ = occ.fragment(flat[:1], flat[1:])
        occ.synchronize()
        if len(flat) != len(gammas):
            raise RuntimeError(f"expected {len(gammas)} volumes, got {len(flat)}")
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        fld = gmsh.model.mesh.field
        f = fld.add("MathEval")
        fld.setString(f, "F", _size_expression(th, gammas, h, grade))
        fld.setAsBackgroundMesh(f)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)
        gmsh.model.mesh.generate(3)
        pts, tets = throw_fe._tet_arrays(gmsh)
        return pts, tets, half
    finally:
        gmsh.finalize()


def _face_weights(mesh, z: float, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Consistent nodal weights of a unit uniform traction on the mesh's facets in the plane
    ``z`` (scalar P2 dofs): (dof indices, weights); their sum is the area."""
    from skfem import ElementTetP2, FacetBasis, LinearForm, asm

    facets = mesh.facets_satisfying(lambda x: np.abs(x[2] - z) < tol)
    fb = FacetBasis(mesh, ElementTetP2(), facets=facets, intorder=4)

    @LinearForm
    def one(v, w):
        return v

    w = asm(one, fb)
    idx = np.flatnonzero(np.abs(w) > 0)
    return idx, w[idx]


def solve_piece(ths: Throw | list[Throw], gammas: list[float], size: float = 0.2, *,
                bearings: bool = True, theta: float = 1e-3, half: bool | None = None
                ) -> PieceResult:
    """End-to-end torsional stiffness of the piece, the mains' rotations and bearing forces
    (``ths``: one throw for all, or one per angle)."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from skfem import Basis, ElementTetP2, ElementVector, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    ths = [ths] * len(gammas) if isinstance(ths, Throw) else list(ths)
    th = ths[0]
    t0 = time.perf_counter()
    pts, tets, half = build_piece_mesh(ths, gammas, size, half=half)
    t_mesh = time.perf_counter() - t0
    n_t = len(gammas)
    L = th.length
    mesh = throw_fe._skfem_mesh(pts, tets)
    basis = Basis(mesh, ElementVector(ElementTetP2()), intorder=3)
    K = asm(linear_elasticity(*lame_parameters(th.E, th.nu)), basis).tocsr()
    n = K.shape[0]
    ix, iy, iz = basis.split_indices()
    X = basis.doflocs
    x, y, z = X[0, ix], X[1, ix], X[2, ix]
    tol = 1e-7 * L
    u = np.zeros(n)
    fixed = np.zeros(n, dtype=bool)
    for zf, ang in ((0.0, 0.0), (n_t * L, theta)):
        sel = np.abs(z - zf) < tol
        fixed[ix[sel]] = fixed[iy[sel]] = True
        u[ix[sel]] = -ang * y[sel]
        u[iy[sel]] = ang * x[sel]
    if half:
        on = np.abs(x) < tol
        fixed[iy[on]] = fixed[iz[on]] = True
    else:
        fixed[iz[np.flatnonzero(np.abs(z) < tol)[0]]] = True   # the axial rigid mode
    # bearing constraints: B u = 0
    faces = [_face_weights(mesh, j * L, tol) for j in range(n_t + 1)]
    rows, cols, vals = [], [], []
    kinds = []
    if bearings:
        for j in range(1, n_t):
            idx, w = faces[j]
            for c, comp in enumerate((ix, iy)):
                if half and c == 1:
                    continue        # u_y odd about x = 0: its mean vanishes by symmetry
                rows.append(np.full(idx.size, len(kinds)))
                cols.append(comp[idx])
                vals.append(w / w.sum())
                kinds.append((j, c))
    fr = np.flatnonzero(~fixed)
    pos = -np.ones(n, dtype=np.int64)
    pos[fr] = np.arange(fr.size)
    f = -(K @ u)
    Kff = K[fr][:, fr]
    if kinds:
        B = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                  pos[np.concatenate(cols)])),
                          shape=(len(kinds), fr.size))
        A = sp.bmat([[Kff, B.T], [B, None]]).tocsc()
        rhs = np.concatenate([f[fr], np.zeros(len(kinds))])
    else:
        A = Kff.tocsc()
        rhs = f[fr]
    t1 = time.perf_counter()
    sol = spla.splu(A, permc_spec="COLAMD").solve(rhs)
    t_solve = time.perf_counter() - t1
    u[fr] = sol[:fr.size]
    lam = sol[fr.size:]
    mult = 2.0 if half else 1.0
    k = mult * float(u @ (K @ u)) / theta**2
    torque = k * theta
    rot = np.zeros(n_t + 1)
    for j, (idx, w) in enumerate(faces):
        xs, ys = x[idx], y[idx]
        rot[j] = np.sum(w * (xs * u[iy[idx]] - ys * u[ix[idx]])) / np.sum(w * (xs**2 + ys**2))
    force = np.zeros((n_t + 1, 2))
    for (j, c), lv in zip(kinds, lam):
        # the multiplier is the force on the crank's constraint: reaction = -lambda
        force[j, c] = -mult * lv / torque
    return PieceResult(stiffness=k, main_rotation=rot / theta, bearing_force=force,
                       n_dofs=n, seconds=time.perf_counter() - t0, size=size,
                       info=dict(t_mesh=t_mesh, t_solve=t_solve, half=half))


# the example cranks' throws (sheet Crank of ``checker template --engine i4|i6|v8``: solid
# journals and pins, counterweights as there; the I6 has none on throws 2 and 5)
def _throw(**kw) -> Throw:
    return Throw(**{k: (math.radians(v) if k == "cw_angle" else v / 1e3 if k not in ("E", "nu")
                        else v) for k, v in kw.items()})


EXAMPLE_THROWS: dict[str, Throw] = {
    "i4": _throw(Dj=55.0, Dp=48.0, Lj=27.0, Lp=24.4, tw=22.3, R=47.3, Bj=75.7, Bp=75.7,
                 E=210e9, nu=0.3, cw_ri=30.0, cw_ro=77.2, cw_angle=150.0, cw_t=22.3),
    "i6": _throw(Dj=85.0, Dp=62.97, Lj=38.0, Lp=40.0, tw=25.0, R=68.5, Bj=125.0, Bp=105.0,
                 E=210e9, nu=0.3, cw_ri=45.0, cw_ro=103.7, cw_angle=150.0, cw_t=25.0),
    "v8": _throw(Dj=64.99, Dp=53.32, Lj=26.0, Lp=48.0, tw=18.88, R=46.0, Bj=110.0, Bp=90.0,
                 E=169e9, nu=0.275, cw_ri=35.0, cw_ro=87.5, cw_angle=150.0, cw_t=18.88),
}
#: The examples' throw angles [deg] (sheet Cylinders) and which throws carry counterweights.
PIECES = {
    "i4": ([0.0, 180.0, 180.0, 0.0], [True] * 4),
    "i6": ([0.0, 240.0, 120.0, 120.0, 240.0, 0.0], [True, False, True, True, False, True]),
    "v8": ([0.0, 90.0, 270.0, 180.0], [True] * 4),
}
#: The verification table: (engine, mesh size, numbers of throws).
TABLE = (("i4", 0.25, (2, 3, 4)), ("i4", 0.15, (2,)), ("i6", 0.3, (2, 3, 4)), ("i6", 0.2, (2,)),
         ("v8", 0.3, (2, 3, 4)))
TABLE_FILE = ROOT / "checker" / "calc" / "data" / "crank_piece_fe.json"


def _piece_throws(engine: str, n: int) -> tuple[list[Throw], list[float]]:
    angles, cw = PIECES[engine]
    base = EXAMPLE_THROWS[engine]
    bare = replace(base, cw_ri=0.0, cw_ro=0.0, cw_angle=0.0, cw_t=0.0)
    return ([base if c else bare for c in cw[:n]], [math.radians(a) for a in angles[:n]])


def table(size: float | None = None, out: Path = TABLE_FILE) -> dict:
    """Solve the verification pieces (``TABLE``; ``size`` overrides every mesh size) and the
    single throw at each mesh, and write them with the throws' geometry to ``out`` (JSON)."""
    data = {"throws": {k: {f: getattr(t, f) for f in Throw.__dataclass_fields__}
                       for k, t in EXAMPLE_THROWS.items()}, "pieces": []}
    for engine, h, counts in TABLE:
        h = size or h
        single = solve_piece(EXAMPLE_THROWS[engine], [0.0], h)
        for n in counts:
            ths, gam = _piece_throws(engine, n)
            r = solve_piece(ths, gam, h)
            data["pieces"].append(dict(
                engine=engine, throws=n, angles_deg=PIECES[engine][0][:n], size=h,
                k_fe=r.stiffness, k_single_fe=single.stiffness,
                main_rotation=r.main_rotation.tolist(), bearing_force=r.bearing_force.tolist(),
                n_dofs=r.n_dofs, seconds=round(r.seconds, 1)))
            gain = r.stiffness * n / single.stiffness - 1
            print(f"{engine} {n} throws, size {h}: {r.stiffness / 1e3:.2f} kN m/rad, series"
                  f" {single.stiffness / n / 1e3:.2f} ({gain:+.1%}); {r.n_dofs} dofs,"
                  f" {r.seconds:.0f} s", flush=True)
    out.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    return data


def _fast_stiffness(th: Throw) -> float:
    """The fast throw model of the checker (:mod:`checker.calc.throw_stiffness`)."""
    from checker.calc.throw_stiffness import throw_torsional_stiffness

    return float(throw_torsional_stiffness(
        journal_diameter=th.Dj, journal_bore=th.dj, journal_length=th.Lj, pin_diameter=th.Dp,
        pin_bore=th.dp, pin_length=th.Lp, web_thickness=th.tw, web_width_journal=th.Bj,
        web_width_pin=th.Bp, crank_radius=th.R, youngs_modulus=th.E, poisson_ratio=th.nu,
        cw_inner_radius=th.cw_ri, cw_outer_radius=th.cw_ro, cw_angle=th.cw_angle,
        cw_thickness=th.cw_t).stiffness[0])


def model_of(engine: str, n: int, single) -> tuple[np.ndarray, np.ndarray]:
    """The checker's model of a piece: each throw's stiffness in the assembled crank
    (:func:`checker.calc.crank_beam.assembled_torsional_stiffness`, the frame calibrated to
    ``single``, one value or one per throw) and the bearing forces per unit torque (n + 1, 2)."""
    from checker.calc import crank_beam as cb

    ths, gam = _piece_throws(engine, n)
    th = ths[0]
    mz = np.arange(n + 1) * th.length
    wz = np.column_stack([mz[:-1] + th.Lj / 2 + th.tw / 2, mz[1:] - th.Lj / 2 - th.tw / 2])
    frame = cb.crank_frame(
        main_z=mz, web_z=wz, pin_load_z=[[z] for z in (mz[:-1] + mz[1:]) / 2],
        throw_angle=gam, crank_radius=th.R, journal_diameter=th.Dj, journal_bore=th.dj,
        pin_diameter=th.Dp, pin_bore=th.dp, web_thickness=th.tw,
        web_width=(th.Bj + th.Bp) / 2, youngs_modulus=th.E, poisson_ratio=th.nu,
        support_stiffness=np.inf, throw_torsional_stiffness=single)
    k = cb.assembled_torsional_stiffness(frame)
    fr = frame.frame
    kg = cb._assemble(fr)
    mains = np.asarray(frame.main_nodes)
    phi = cb._torsion_solve(kg, np.full(mains.size, np.inf), mains)
    u = np.zeros(kg.shape[0])
    held = set([mains[0] * 6 + 5, mains[0] * 6 + 2] + [m * 6 + c for m in mains for c in (0, 1)])
    free = np.array(sorted(set(range(kg.shape[0])) - held))
    f = np.zeros(kg.shape[0])
    f[mains[-1] * 6 + 5] = 1.0
    u[free] = np.linalg.solve(kg[np.ix_(free, free)], f[free])
    reaction = kg @ u - f
    force = np.array([[reaction[m * 6], reaction[m * 6 + 1]] for m in mains])
    assert np.allclose(u[mains * 6 + 5], phi)
    return k, force


def compare(path: Path = TABLE_FILE) -> str:
    """The verification table of docs/crank-geometry.md from the stored FE (Markdown): per
    piece the FE, the throws in series, the model calibrated to the FE's throw alone (same
    mesh) and the model on the checker's fast throw model, and the largest inner bearing
    force per unit torque."""
    data = json.loads(path.read_text(encoding="utf-8"))
    lines = ["| engine | throws | angles, deg | mesh | FE, kN m/rad | throws in series |"
             " model (throw FE) | model (fast throw model) | bearing force FE / model,"
             " N/(N m) |", "|" + " --- |" * 9]
    for p in data["pieces"]:
        e, n = p["engine"], p["throws"]
        k_fe, series = p["k_fe"], p["k_single_fe"] / n
        k_a, force = model_of(e, n, p["k_single_fe"])
        ths, _ = _piece_throws(e, n)
        k_b, _ = model_of(e, n, np.array([_fast_stiffness(t) for t in ths]))
        end_a, end_b = 1 / np.sum(1 / k_a), 1 / np.sum(1 / k_b)
        f_fe = np.hypot(*np.array(p["bearing_force"])[1:-1].T)
        f_m = np.hypot(*force[1:-1].T)
        i = int(np.argmax(f_fe))
        lines.append(
            f"| {e.upper()} | {n} | {', '.join(f'{a:g}' for a in p['angles_deg'])} |"
            f" {p['size']} | {k_fe / 1e3:.1f} | {series / 1e3:.1f} ({series / k_fe - 1:+.1%}) |"
            f" {end_a / 1e3:.1f} ({end_a / k_fe - 1:+.1%}) |"
            f" {end_b / 1e3:.1f} ({end_b / k_fe - 1:+.1%}) |"
            f" {f_fe[i]:.2f} / {f_m[i]:.2f} |")
    return "\n".join(lines).replace("%", " %")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engine", default="i4", choices=sorted(PIECES))
    ap.add_argument("--throws", type=int, default=2)
    ap.add_argument("--size", type=float, default=None, help="element size / Dj (default 0.25;"
                    " with --table the table's own)")
    ap.add_argument("--free-inner", action="store_true", help="no bearings inside the piece")
    ap.add_argument("--table", action="store_true", help="solve the verification pieces and"
                    " write checker/calc/data/crank_piece_fe.json")
    ap.add_argument("--compare", action="store_true", help="print the verification table of"
                    " the stored FE against the checker's model (needs only the checker)")
    args = ap.parse_args(argv)
    if args.compare:
        print(compare())
        return 0
    if args.table:
        table(args.size)
        return 0
    size = args.size or 0.25
    ths, g = _piece_throws(args.engine, args.throws)
    r = solve_piece(ths, g, size, bearings=not args.free_inner)
    single = solve_piece(ths[0], [0.0], size).stiffness
    print(f"{args.engine}, {args.throws} throws {PIECES[args.engine][0][:args.throws]} deg: "
          f"{r.stiffness / 1e3:.2f} kN m/rad; throw 1 alone {single / 1e3:.2f}, in series "
          f"{single / args.throws / 1e3:.2f} ({r.stiffness * args.throws / single - 1:+.2%});"
          f" {r.n_dofs} dofs, {r.seconds:.1f} s")
    print("mains' rotation / end rotation:", np.round(r.main_rotation, 4).tolist())
    print("bearing force per torque [N/(N m)]:", np.round(r.bearing_force, 3).tolist())
    return 0


if __name__ == "__main__":
    sys.exit(main())
