"""Bending (and axial/torsional) end flexibility of one crank throw: 3D FE against the frame.

    python scripts/throw_bending_fe.py [--size H] [--out FILE] [--only NAME ...]
    python scripts/throw_bending_fe.py --compare [FILE]

Needs the optional extra ``fe`` (gmsh, scikit-fem) for the FE; ``--compare`` and
:func:`frame_flexibility` need only the checker. The check never imports this file.

Definition (the FE and the frame both use it)
---------------------------------------------
One throw between its journal mid-planes (z = 0 .. L, L = Lj + 2 tw + Lp; geometry of
docs/crank-geometry.md, pin axis at (0, R)). Both end faces are rigid: each face's nodes move
as a rigid plate (6 degrees of freedom). Face 1 (z = 0) is fixed; at face 2's centre
(0, 0, L) the generalised loads ``(Fx, Fy, Fz, Mx, My, Mz)`` are applied one at a time and the
generalised displacements ``(ux, uy, uz, rx, ry, rz)`` of face 2 give the 6 x 6 flexibility
``C`` (m/N, 1/N, 1/(N m)). The pin plane is the plane x = 0 (both axes): ``Fy`` and ``Mx``
bend the throw in the pin plane, ``Fx`` and ``My`` perpendicular to it.

FE: the throw's solid of ``scripts/throw_fe.py`` (curved 10-node tetrahedra, scikit-fem,
linear elasticity). The plane x = 0 is a mirror plane of the geometry: the loads ``Fy, Fz,
Mx`` are symmetric about it (``u_x = 0`` there), ``Fx, My, Mz`` antisymmetric (``u_y = u_z =
0``); the half x >= 0 is solved twice, each time with the three generalised dofs of its kind
(the half carries half of the load: ``C = C_half / 2``). Face 2's dofs are eliminated in
favour of the rigid-plate dofs (``u = q + r x (X - c)``); the flexibility is the inverse of
the Schur complement of the interior.

Frame: :func:`checker.calc.crank_beam.crank_frame` with ``main_z = [0, L]``; node of main 1
fixed in all six dofs, the flexibility of main 2's node.
"""

from __future__ import annotations

import argparse
import csv
import importlib.util
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "checker" / "calc" / "data" / "throw_bending_fe.csv"

_spec = importlib.util.spec_from_file_location("throw_fe", ROOT / "scripts" / "throw_fe.py")
throw_fe = importlib.util.module_from_spec(_spec)
sys.modules.setdefault("throw_fe", throw_fe)
_spec.loader.exec_module(throw_fe)
Throw = throw_fe.Throw

_ORDER = "COLAMD"
GEOM = ("Dj", "Dp", "Lj", "Lp", "tw", "R", "Bj", "Bp", "dj", "dp", "E", "nu")
# the upper triangle of C, row-major: c00 c01 ... c05 c11 ... c55
C_KEYS = tuple(f"c{i}{j}" for i in range(6) for j in range(i, 6))
# the terms that matter for the support reactions: (name, i, j)
MAIN_TERMS = (
    ("ux/Fx", 0, 0),   # deflection under end force, bending perpendicular to the pin plane
    ("uy/Fy", 1, 1),   # deflection under end force, bending in the pin plane
    ("rx/Mx", 3, 3),   # rotation under end moment, in the pin plane
    ("ry/My", 4, 4),   # rotation under end moment, perpendicular to the pin plane
    ("ux/My", 0, 4),   # coupling, perpendicular plane
    ("uy/Mx", 1, 3),   # coupling, pin plane
)
OTHER_TERMS = (("uz/Fz", 2, 2), ("rz/Mz", 5, 5))


# --------------------------------------------------------------------------------------------
# FE
# --------------------------------------------------------------------------------------------
def _rigid_map(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(n, 3, 6): displacement of face points (x, y, 0) relative to the centre per unit
    generalised dof (ux, uy, uz, rx, ry, rz): u = q + r x (x, y, 0)."""
    n = x.size
    m = np.zeros((n, 3, 6))
    m[:, 0, 0] = m[:, 1, 1] = m[:, 2, 2] = 1.0
    m[:, 0, 5] = -y
    m[:, 1, 5] = x
    m[:, 2, 3] = y
    m[:, 2, 4] = -x
    return m


def fe_flexibility(th: Throw, size: float = 0.12, *, half: bool = True,
                   grade: float = 0.5) -> tuple[np.ndarray, dict]:
    """6 x 6 end flexibility of a throw (definition in the module docstring) by 3D FE."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from skfem import Basis, ElementTetP2, ElementVector, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    t0 = time.perf_counter()
    pts, tets = throw_fe.build_mesh(th, size, full=not half, half=half, grade=grade)
    t_mesh = time.perf_counter() - t0
    mesh = throw_fe._skfem_mesh(pts, tets)
    basis = Basis(mesh, ElementVector(ElementTetP2()), intorder=3)
    K = asm(linear_elasticity(*lame_parameters(th.E, th.nu)), basis).tocsr()
    n = K.shape[0]
    ix, iy, iz = basis.split_indices()
    X = basis.doflocs
    x, y, z = X[0, ix], X[1, ix], X[2, ix]
    L = th.length
    tol = 1e-7 * L
    at_a = np.abs(z) < tol
    at_b = np.abs(z - L) < tol
    on_sym = np.abs(x) < tol
    comp = np.stack([ix, iy, iz], axis=1)  # (n_nodes, 3) dof numbers
    cases = ([1, 2, 3], [0, 4, 5]) if half else (list(range(6)),)
    C = np.zeros((6, 6))
    t_solve = 0.0
    for masters in cases:
        fixed = np.zeros(n, dtype=bool)
        fixed[comp[at_a].ravel()] = True
        if half:
            sym_fixed = [0] if masters == [1, 2, 3] else [1, 2]
            for c in sym_fixed:
                fixed[comp[on_sym, c]] = True
        bnodes = np.flatnonzero(at_b)
        bdofs = comp[bnodes].ravel()
        fixed[bdofs] = False
        free = np.flatnonzero(~fixed & ~np.isin(np.arange(n), bdofs))
        tb = _rigid_map(x[bnodes], y[bnodes])[:, :, masters].reshape(-1, len(masters))
        tb = sp.csr_matrix(tb)
        kfb = K[free][:, bdofs] @ tb
        kbb = (tb.T @ K[bdofs][:, bdofs] @ tb).toarray()
        t1 = time.perf_counter()
        lu = spla.splu(K[free][:, free].tocsc(), permc_spec=_ORDER)
        sol = lu.solve(np.asarray(kfb.toarray()))
        t_solve += time.perf_counter() - t1
        schur = kbb - np.asarray(kfb.T @ sol)
        ch = np.linalg.inv(schur)
        if half:
            ch = ch / 2.0
        C[np.ix_(masters, masters)] = ch
    C = 0.5 * (C + C.T)
    info = dict(n_dofs=n, n_tets=len(tets), t_mesh=t_mesh, t_solve=t_solve,
                seconds=time.perf_counter() - t0)
    return C, info


def shaft_flexibility(D: float, L: float, *, E: float = 210e9, nu: float = 0.3,
                      size: float = 0.25) -> np.ndarray:
    """FE end flexibility of a plain round shaft (a throw with no offset: R = 0 is not a
    throw, so the shaft is meshed directly), half model, rigid end faces."""
    th = Throw(Dj=D, Dp=D, Lj=L, Lp=0.0, tw=0.0, R=0.0, Bj=D, Bp=D, E=E, nu=nu)
    import gmsh

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        occ = gmsh.model.occ
        vol = [(3, occ.addCylinder(0, 0, 0, 0, 0, L, D / 2))]
        box = occ.addBox(0, -D, -0.1 * L, D, 2 * D, 1.2 * L)
        occ.intersect(vol, [(3, box)])
        occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", size * D)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size * D)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.model.mesh.generate(3)
        pts, tets = throw_fe._tet_arrays(gmsh)
    finally:
        gmsh.finalize()
    saved = throw_fe.build_mesh
    throw_fe.build_mesh = lambda *a, **k: (pts, tets)
    try:
        C, _ = fe_flexibility(th, size, half=True)
    finally:
        throw_fe.build_mesh = saved
    return C


# --------------------------------------------------------------------------------------------
# frame
# --------------------------------------------------------------------------------------------
def throw_frame(th: Throw, **kwargs):
    """The frame of one throw (:func:`checker.calc.crank_beam.crank_frame`, pin at (0, R),
    mean web width (Bj + Bp)/2 as the checker builds it)."""
    from checker.calc import crank_beam as cb

    L = th.length
    return cb.crank_frame(
        main_z=[0.0, L], web_z=[[th.Lj / 2 + th.tw / 2, L - th.Lj / 2 - th.tw / 2]],
        pin_load_z=[[L / 2]], throw_angle=[0.0], crank_radius=th.R,
        journal_diameter=th.Dj, journal_bore=th.dj, pin_diameter=th.Dp, pin_bore=th.dp,
        web_thickness=th.tw, web_width=(th.Bj + th.Bp) / 2, youngs_modulus=th.E,
        poisson_ratio=th.nu, support_stiffness=np.inf, **kwargs)


def frame_flexibility(cf) -> np.ndarray:
    """6 x 6 flexibility of a crank frame's last main node with its first main node fixed
    in all six dofs (assembled with :func:`checker.calc.crank_beam.element_stiffness`)."""
    from checker.calc.crank_beam import element_stiffness

    fr = cf.frame
    nodes = np.asarray(fr.nodes)
    n = 6 * nodes.shape[0]
    kg = np.zeros((n, n))
    for e, (i, j) in enumerate(np.asarray(fr.elements)):
        ke = element_stiffness(nodes[i], nodes[j], fr.axial_stiffness[e],
                               fr.torsional_stiffness[e], fr.bending_stiffness[e, 0],
                               fr.bending_stiffness[e, 1], fr.first_axis[e])
        idx = np.r_[6 * i:6 * i + 6, 6 * j:6 * j + 6]
        kg[np.ix_(idx, idx)] += ke
    a, b = int(cf.main_nodes[0]), int(cf.main_nodes[-1])
    free = np.setdiff1d(np.arange(n), np.arange(6 * a, 6 * a + 6))
    pos = np.searchsorted(free, np.arange(6 * b, 6 * b + 6))
    inv = np.linalg.inv(kg[np.ix_(free, free)])
    return inv[np.ix_(pos, pos)]


# --------------------------------------------------------------------------------------------
# samples
# --------------------------------------------------------------------------------------------
I4 = replace(throw_fe.I4_THROW, nu=0.3)


def _from_ratios(dp_dj, s_dj, tw_dj, bj_dj, bp_dp, lj_dj, lp_dp, dj=0.06) -> Throw:
    dp = dp_dj * dj
    return Throw(Dj=dj, Dp=dp, Lj=lj_dj * dj, Lp=lp_dp * dp, tw=tw_dj * dj,
                 R=(dj + dp) / 2 - s_dj * dj, Bj=bj_dj * dj, Bp=bp_dp * dp, E=210e9, nu=0.3)


RANGES = dict(dp_dj=(0.75, 1.0), s_dj=(-0.15, 0.30), tw_dj=(0.2, 0.5), bj_dj=(1.2, 1.8),
              bp_dp=(1.2, 1.8), lj_dj=(0.35, 0.6), lp_dp=(0.35, 0.75))


def _lhs(n: int, seed: int) -> list[dict]:
    rng = np.random.default_rng(seed)
    cols = {}
    for k, (a, b) in RANGES.items():
        u = (rng.permutation(n) + rng.random(n)) / n
        cols[k] = a + (b - a) * u
    return [{k: float(cols[k][i]) for k in RANGES} for i in range(n)]


def design() -> list[tuple[str, str, Throw]]:
    """The samples: the I4 throw, 8 extreme combinations of the ranges and a Latin hypercube
    of 8 (seeded) for the fit; a second Latin hypercube of 12 held out."""
    out = [("I4", "fit", I4)]
    lo = {k: v[0] for k, v in RANGES.items()}
    hi = {k: v[1] for k, v in RANGES.items()}
    corners = [
        dict(lo, s_dj=-0.15, tw_dj=0.2, dp_dj=0.75),   # thin narrow webs, long webs
        dict(hi, s_dj=0.30, tw_dj=0.5, lj_dj=0.35, lp_dp=0.35),  # thick wide webs, overlap
        dict(hi, tw_dj=0.2, bj_dj=1.8, bp_dp=1.8, dp_dj=1.0),    # thin wide webs, overlap
        dict(lo, s_dj=-0.15, tw_dj=0.5),                # thick narrow webs, no overlap
        dict(lo, s_dj=0.30, tw_dj=0.2, dp_dj=1.0),      # thin narrow webs, overlap
        dict(hi, s_dj=-0.15, tw_dj=0.5, dp_dj=0.75),    # thick wide webs, long journals
        dict(lo, s_dj=0.30, tw_dj=0.35, bj_dj=1.8, bp_dp=1.8),  # wide webs, overlap, short
        dict(hi, s_dj=-0.15, tw_dj=0.2),                # thin wide webs, no overlap
    ]
    for i, c in enumerate(corners):
        out.append((f"corner{i}", "fit", _from_ratios(**c)))
    for i, r in enumerate(_lhs(8, 34)):
        out.append((f"lhs{i}", "fit", _from_ratios(**r)))
    for i, r in enumerate(_lhs(12, 35)):
        out.append((f"hold{i}", "hold", _from_ratios(**r)))
    return out


def _row(name: str, kind: str, th: Throw, C: np.ndarray, size: float, info: dict) -> dict:
    g = {k: getattr(th, k) for k in GEOM}
    c = {k: float(C[int(k[1]), int(k[2])]) for k in C_KEYS}
    return dict(name=name, set=kind, **g, **c, mesh_size=size, n_dofs=info["n_dofs"],
                seconds=round(info["seconds"], 1))


def read_samples(path: Path = DATA) -> list[tuple[str, str, Throw, np.ndarray]]:
    """(name, set, throw, C) of the stored FE samples."""
    out = []
    with open(path, newline="") as fh:
        for r in csv.DictReader(fh):
            th = Throw(**{k: float(r[k]) for k in GEOM})
            C = np.zeros((6, 6))
            for k in C_KEYS:
                i, j = int(k[1]), int(k[2])
                C[i, j] = C[j, i] = float(r[k])
            out.append((r["name"], r["set"], th, C))
    return out


def fit(path: Path = DATA) -> tuple[float, ...]:
    """Refit ``checker.calc.crank_beam.WEB_FIT`` to the stored samples of the set "fit": the
    L8 norm of the log errors of the four main terms (end deflection and rotation in both
    planes), started from the L2 fit; prints the error of both sets."""
    from scipy.optimize import least_squares

    from checker.calc import crank_beam as cb

    samples = read_samples(path)
    terms = [(i, j) for t, i, j in MAIN_TERMS if i == j]

    def res(p, kind):
        cb.WEB_FIT = tuple(p)
        out = []
        for _, k, th, C in samples:
            if k == kind:
                Cb = frame_flexibility(throw_frame(th))
                out += [math.log(Cb[i, j] / C[i, j]) for i, j in terms]
        return np.array(out)

    saved = cb.WEB_FIT
    lb, ub = [0.0] * 8, [1.0, 1.0, 2.0, 2.0, 3.0, 2.0, 2.0, 3.0]
    try:
        r2 = least_squares(res, saved, args=("fit",), bounds=(lb, ub))
        r8 = least_squares(lambda p: np.sign(res(p, "fit")) * res(p, "fit") ** 4, r2.x,
                           bounds=(lb, ub))
        for kind in ("fit", "hold"):
            e = res(r8.x, kind)
            print(f"{kind}: n {e.size // 4}, max {100 * np.abs(e).max():.1f} %, "
                  f"mean {100 * np.abs(e).mean():.1f} %")
    finally:
        cb.WEB_FIT = saved
    return tuple(float(v) for v in np.round(r8.x, 3))


def compare(path: Path = DATA, **frame_kwargs) -> list[dict]:
    """Relative error (frame / FE - 1) of every term of MAIN_TERMS + OTHER_TERMS, per sample."""
    rows = []
    for name, kind, th, C in read_samples(path):
        Cb = frame_flexibility(throw_frame(th, **frame_kwargs))
        r = dict(name=name, set=kind)
        for t, i, j in MAIN_TERMS + OTHER_TERMS:
            r[t] = Cb[i, j] / C[i, j] - 1.0
        rows.append(r)
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=float, default=0.12, help="element size / Dj (far field)")
    ap.add_argument("--out", type=Path, default=DATA)
    ap.add_argument("--only", nargs="*", help="sample names to run")
    ap.add_argument("--compare", nargs="?", const=DATA, type=Path, help="table from a file")
    ap.add_argument("--full", action="store_true", help="whole throw instead of the half")
    ap.add_argument("--fit", nargs="?", const=DATA, type=Path, help="refit WEB_FIT to a file")
    args = ap.parse_args(argv)
    if args.fit is not None:
        print("WEB_FIT =", fit(args.fit))
        return 0
    if args.compare is not None:
        terms = [t for t, _, _ in MAIN_TERMS + OTHER_TERMS]
        print("sample   set   " + " ".join(f"{t:>8}" for t in terms))
        for r in compare(args.compare):
            print(f"{r['name']:8} {r['set']:5} " + " ".join(f"{100 * r[t]:+7.1f}%"
                                                          for t in terms))
        return 0
    done = set()
    if args.out.exists():
        with open(args.out, newline="") as fh:
            done = {r["name"] for r in csv.DictReader(fh)}
    for name, kind, th in design():
        if (args.only and name not in args.only) or (not args.only and name in done):
            continue
        C, info = fe_flexibility(th, args.size, half=not args.full)
        row = _row(name, kind, th, C, args.size, info)
        new = not args.out.exists()
        with open(args.out, "a", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(row))
            if new:
                w.writeheader()
            w.writerow(row)
        Cb = frame_flexibility(throw_frame(th))
        errs = " ".join(f"{t} {100 * (Cb[i, j] / C[i, j] - 1):+.1f}%" for t, i, j in MAIN_TERMS)
        print(f"{name} {kind}: {info['n_dofs']} dofs, {info['seconds']:.0f} s; frame vs FE: "
              f"{errs}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
