"""The crank as a continuous beam in the load analysis (Engine 'Main bearing supports').

Not a graph node: the helpers :func:`checker.modules.loads.bearing_loads` and
:func:`checker.modules.fatigue.crank_fatigue` call when the workbook chooses a continuous beam.
They build the beam of :mod:`checker.calc.crank_beam` from the crank's geometry (sheet Crank),
factorise it once, and push every crank angle, speed and load case through the resulting
linear map in one product.

Axial layout: main ``k`` at ``z_k = k L`` with ``L`` the Engine sheet's main journal spacing
(the determinate scheme's bay length; without it, each throw's length ``Lj + 2 tw + Lp``
summed); a throw's webs at ``Lj/2 + tw/2`` from its mains; the con-rods at mid-bay (as the
determinate scheme). Loads: the con-rod forces on the pins and the centrifugal forces of the
crank masses (sheet CrankMass, typed or derived from the geometry) at their mass centres,
carried to the nearest web or pin node of their throw with the moment of their offset; the
torque of the con-rods balanced where it goes (issue 43): its cycle mean leaves at the
flywheel flange, the rest accelerates the rotating inertias (the torsional model's stations:
d'Alembert's torques, :func:`checker.calc.crank_beam.balancing_torques`), so the frame's
rotation hold reacts nothing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..calc import crank_beam as cb
from ..calc import crank_forces as cf
from ..calc import crank_stress as cs
from ..description.engine import Engine
from ..results.loads import CrankBeamDetail

SCHEMES = ("determinate", "continuous beam, rigid supports", "continuous beam, elastic supports")
JSON_STEP = np.deg2rad(10.0)  # angle step of the beam's loads and reactions in the JSON


def scheme_of(engine: Engine) -> str:
    """The workbook's support scheme (default: determinate)."""
    return engine.params.get("support_scheme") or "determinate"


@dataclass(frozen=True)
class Beam:
    """A factorised crank beam with the axial layout the loads need."""

    crank: cb.CrankFrame
    solution: cb.BeamSolution
    main_z: np.ndarray  # (n_main,) [m]
    web_z: np.ndarray  # (n_pins, 2) [m]
    pin_z: np.ndarray  # (n_pins,) [m]
    offsets: np.ndarray  # (n_main,) [m] block-frame y offset of each main
    stiffness: np.ndarray  # (n_main,) [N/m], inf = rigid
    #: Rotating inertias that balance the rods' torque: inertia [kg m^2], load-node index of
    #: each (the front end at throw 1's front web, a cylinder station at its pin, the
    #: flywheel end at the last web), and which one is the output (the flywheel).
    inertia: np.ndarray
    inertia_node: np.ndarray
    output: int
    inertia_note: str
    radius: float  # [m] crank radius

    @property
    def pin_load_index(self) -> np.ndarray:
        """Positions of the pin nodes in the solution's load nodes (one per pin)."""
        n_web = self.crank.web_nodes.size
        return n_web + np.arange(len(self.crank.pin_nodes))


def build_beam(engine: Engine, gamma: np.ndarray, scheme: str | None = None) -> Beam:
    """The crank's beam for a continuous scheme (default: the workbook's; the determinate
    scheme's counterpart is the beam on rigid supports)."""
    crank = engine.crank
    if crank is None:  # the engine builder refuses a continuous scheme without sheet Crank
        raise ValueError("a continuous beam needs the crank's geometry (sheet Crank)")
    scheme = scheme or scheme_of(engine)
    throws = crank.throws
    n_pins = len(throws)
    spacing = engine.params.get("main_spacing")
    lengths = np.array([t.length for t in throws]) if spacing is None else np.full(n_pins,
                                                                                    spacing)
    main_z = np.concatenate([[0.0], np.cumsum(lengths)])
    lj = np.array([t.journal_length for t in throws])
    tw = np.array([t.web_thickness for t in throws])
    web_z = np.column_stack([main_z[:-1] + lj / 2 + tw / 2, main_z[1:] - lj / 2 - tw / 2])
    pin_z = (main_z[:-1] + main_z[1:]) / 2.0
    mains = sorted((b for b in engine.bearings if b.type == "main"), key=lambda b: b.index)
    k_all = engine.params.get("support_stiffness")
    if scheme == "continuous beam, elastic supports":
        k = np.array([b.support_stiffness if b.support_stiffness is not None else k_all
                      for b in mains] if mains else [k_all] * (n_pins + 1), dtype=float)
    else:
        k = np.full(n_pins + 1, np.inf)
    offsets = np.array([b.support_offset or 0.0 for b in mains] if mains
                       else [0.0] * (n_pins + 1))
    single = _single_throw_stiffness(engine)
    kwargs = dict(
        main_z=main_z, web_z=web_z, pin_load_z=[[z] for z in pin_z], throw_angle=gamma,
        crank_radius=crank.crank_radius,
        journal_diameter=[t.journal_diameter for t in throws],
        journal_bore=[t.journal_bore for t in throws],
        pin_diameter=[t.pin_diameter for t in throws], pin_bore=[t.pin_bore for t in throws],
        web_thickness=tw,
        web_width=[(t.web_width_journal + t.web_width_pin) / 2.0 for t in throws],
        youngs_modulus=crank.youngs_modulus, poisson_ratio=crank.poisson_ratio,
        support_stiffness=k)
    calibration = ""
    try:
        frame = cb.crank_frame(**kwargs, throw_torsional_stiffness=single)
    except ValueError as exc:  # a throw the calibration cannot reach: the frame's own torsion
        frame = cb.crank_frame(**kwargs)
        calibration = f"; the frame's torsion is not calibrated to the throws' ({exc})"
    if single is None:
        calibration = ("; the frame's torsion is not calibrated to the throws' (the throw"
                       " stiffness model is not available)")
    inertia, node, output, note = _rotating_inertias(engine, n_pins)
    note += calibration
    return Beam(frame, cb.solve_frame(frame.frame, frame.load_nodes), main_z, web_z, pin_z,
                offsets, k, inertia, node, output, note, crank.crank_radius)


def _single_throw_stiffness(engine: Engine) -> np.ndarray | None:
    """Each throw's torsional stiffness alone (:mod:`checker.calc.throw_stiffness`), to
    calibrate the frame's torsion; None where it is not available."""
    from ..description.crank_derive import throw_stiffness

    k = throw_stiffness(engine.crank).stiffness
    return k if np.all(np.isfinite(k)) else None


def _rotating_inertias(engine: Engine, n_pins: int) -> tuple[np.ndarray, np.ndarray, int, str]:
    """The inertias that balance the rods' torque and the load node of each: the torsional
    model's stations (sheet TVModel), those ahead of the first cylinder station on throw 1's
    front web, a cylinder station on its pin, those behind the last on the last web (a pure
    torque passes the straight journal, nose or flange to the web unchanged); the output is
    the flywheel station (else the last). Without a usable model: one inertia, the flywheel
    end, carrying the whole torque."""
    pin_of = {c.number: c.pin for c in engine.cylinders}
    stations = list(engine.tv_model)
    cyl = [i for i, s in enumerate(stations) if s.cylinders]
    rear = 2 * n_pins - 1
    if not cyl or any(not (s.inertia and s.inertia > 0) for s in stations) or any(
            not 1 <= pin_of.get(s.cylinders[0], 0) <= n_pins for s in stations if s.cylinders):
        return (np.ones(1), np.array([rear]), 0, "the whole torque of the rods at the flywheel"
                " flange (no complete torsional model to share its fluctuation)")
    node = []
    for i, s in enumerate(stations):
        if s.cylinders:
            node.append(2 * n_pins + pin_of[s.cylinders[0]] - 1)
        else:
            node.append(0 if i < cyl[0] else rear)
    fly = [i for i, s in enumerate(stations) if s.role == "flywheel" and i > cyl[-1]]
    output = fly[0] if fly else len(stations) - 1
    if node[output] != rear:
        return (np.ones(1), np.array([rear]), 0, "the whole torque of the rods at the flywheel"
                " flange (no station behind the last cylinder)")
    return (np.array([s.inertia for s in stations], dtype=float), np.array(node, dtype=int),
            output, "the mean torque of the rods at the flywheel flange, its fluctuation on"
            " the rotating inertias of the torsional model (d'Alembert)")


def _balancing_moments(beam: Beam, f_pin: cf.Vector2, gamma: np.ndarray, r: float
                       ) -> np.ndarray:
    """Torques about the crank axis at the load nodes (C, S, n_load, N) [N m] that balance
    the rods' torque at every angle (:func:`checker.calc.crank_beam.balancing_torques`)."""
    g = np.asarray(gamma, dtype=float)[:, None]
    torque = (r * (np.sin(g) * f_pin.y - np.cos(g) * f_pin.x)).sum(axis=-2)  # (C, S, N)
    per = cb.balancing_torques(torque, beam.inertia, beam.output)  # (C, S, K, N)
    out = np.zeros(torque.shape[:-1] + (beam.solution.load_nodes.size, torque.shape[-1]))
    np.add.at(out, (Ellipsis, beam.inertia_node, slice(None)), per)
    return out


def _offset_loads(beam: Beam, theta: np.ndarray) -> np.ndarray | None:
    """Bearing loads (M, 2, N) of the support offsets (block-frame y, turned into the crank
    frame at every angle), or None without offsets."""
    if not np.any(beam.offsets != 0.0):
        return None
    th = np.asarray(theta, dtype=float)
    off = cf.block_to_crank(cf.Vector2(np.zeros((beam.offsets.size, th.size)),
                                       beam.offsets[:, None] * np.ones(th.size)), th)
    per = np.stack([off.x, off.y], axis=1)  # (M', 2, N)
    return np.einsum("mikj,kjn->min", beam.solution.offset_map, per)


def _mass_loads(beam: Beam, engine: Engine, gamma: np.ndarray, r: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centrifugal forces per unit omega^2 of the crank masses, carried to the nearest web or
    pin node of their throw: force and moment at every load node (n_load, 3) each, and the
    masses' points (n_m, 3) for the record."""
    sol = beam.solution
    n_load = sol.load_nodes.size
    force = np.zeros((n_load, 3))
    moment = np.zeros((n_load, 3))
    m = engine.crank_mass
    if not m:
        return force, moment, np.zeros((0, 3))
    pos = cf.mass_positions([it.z for it in m], [it.y for it in m], [it.throw - 1 for it in m],
                            [it.reference == "pin axis" for it in m], gamma, r)
    n_pins = beam.pin_z.size
    web_idx = np.arange(2 * n_pins).reshape(n_pins, 2)
    points = []
    for it, (x, y) in zip(m, pos, strict=True):
        j = it.throw - 1
        z = beam.main_z[j] + it.axial + it.x
        cand = [(beam.web_z[j, 0], web_idx[j, 0]), (beam.pin_z[j], beam.pin_load_index[j]),
                (beam.web_z[j, 1], web_idx[j, 1])]
        _, li = min(cand, key=lambda c: abs(c[0] - z))
        f = np.array([it.mass * x, it.mass * y, 0.0])
        p = np.array([x, y, z])
        force[li] += f
        moment[li] += np.cross(p - sol.load_positions[li], f)
        points.append(p)
    return force, moment, np.array(points)


def continuous_main_loads(beam: Beam, engine: Engine, theta: np.ndarray, speeds: np.ndarray,
                          big_end_crank: cf.Vector2, pins: np.ndarray, gamma: np.ndarray,
                          r: float, case_names: list[str]
                          ) -> tuple[cf.Vector2, CrankBeamDetail]:
    """Main-bearing loads (block frame, (C, S, n_main, N)) of the continuous beam, and the
    beam's record for the outputs.

    ``big_end_crank``: force of each rod on... (the big-end load, (C, S, n_cyl, N), crank
    frame); the force on pin ``j`` is minus the sum over its rods.
    """
    sol = beam.solution
    n_pins = beam.pin_z.size
    f_pin = cf.crankpin_force(big_end_crank, pins, n_pins)  # (C, S, P, N) crank frame
    fm = sol.force_map  # (M, 2, L, 3)
    pin_map = fm[:, :, beam.pin_load_index, :2]  # (M, 2, P, 2)
    bx = (np.einsum("mp,cspn->csmn", pin_map[:, 0, :, 0], f_pin.x)
          + np.einsum("mp,cspn->csmn", pin_map[:, 0, :, 1], f_pin.y))
    by = (np.einsum("mp,cspn->csmn", pin_map[:, 1, :, 0], f_pin.x)
          + np.einsum("mp,cspn->csmn", pin_map[:, 1, :, 1], f_pin.y))
    mz = _balancing_moments(beam, f_pin, gamma, r)  # (C, S, L, N)
    mz_map = sol.moment_map[:, :, :, 2]  # (M, 2, L)
    bx = bx + np.einsum("ml,csln->csmn", mz_map[:, 0], mz)
    by = by + np.einsum("ml,csln->csmn", mz_map[:, 1], mz)
    force_w2, moment_w2, _ = _mass_loads(beam, engine, gamma, r)
    per_w2 = (np.einsum("mcla,la->mc", fm, force_w2)
              + np.einsum("mcla,la->mc", sol.moment_map, moment_w2))  # (M, 2) crank frame
    w2 = (np.asarray(speeds, dtype=float) ** 2)[None, :, None, None]
    bx = bx + w2 * per_w2[None, None, :, 0, None]
    by = by + w2 * per_w2[None, None, :, 1, None]
    off = _offset_loads(beam, theta)
    if off is not None:
        bx = bx + off[:, 0]
        by = by + off[:, 1]
    block = cf.crank_to_block(cf.Vector2(bx, by), theta)
    detail = _record(beam, engine, theta, speeds, f_pin, force_w2, moment_w2,
                     cf.Vector2(bx, by), case_names, mz)
    return block, detail


def _record(beam: Beam, engine: Engine, theta: np.ndarray, speeds: np.ndarray,
            f_pin: cf.Vector2, force_w2: np.ndarray, moment_w2: np.ndarray,
            crank_loads: cf.Vector2, case_names: list[str], mz: np.ndarray
            ) -> CrankBeamDetail:
    """The beam as the outputs show it, with its loads and reactions at one operating point
    (the load case and speed of the largest main-bearing load), every 10 deg."""
    fr = beam.crank.frame
    mag = np.hypot(crank_loads.x, crank_loads.y)  # (C, S, M, N)
    ci, si = np.unravel_index(int(np.argmax(mag.max(axis=(2, 3)))), mag.shape[:2])
    step = max(1, int(round(JSON_STEP / (theta[1] - theta[0])))) if theta.size > 1 else 1
    idx = np.arange(0, theta.size, step)
    w2 = float(speeds[si]) ** 2
    n_load = beam.solution.load_nodes.size
    loads = np.zeros((idx.size, n_load, 6))
    loads[:, :, :3] = w2 * force_w2
    loads[:, :, 3:] = w2 * moment_w2
    pin_idx = beam.pin_load_index
    loads[:, pin_idx, 0] += f_pin.x[ci, si][:, idx].T
    loads[:, pin_idx, 1] += f_pin.y[ci, si][:, idx].T
    loads[:, :, 5] += mz[ci, si][:, idx].T
    reactions = np.stack([crank_loads.x[ci, si][:, idx].T, crank_loads.y[ci, si][:, idx].T],
                         axis=-1)  # (n_angle, M, 2)
    return CrankBeamDetail(
        scheme=scheme_of(engine), nodes=np.asarray(fr.nodes), elements=np.asarray(fr.elements),
        axial_stiffness=np.asarray(fr.axial_stiffness),
        torsional_stiffness=np.asarray(fr.torsional_stiffness),
        bending_stiffness=np.asarray(fr.bending_stiffness),
        first_axis=np.asarray(fr.first_axis), support_nodes=np.asarray(fr.support_nodes),
        support_stiffness=beam.stiffness, support_offset=beam.offsets,
        torsion_node=int(fr.torsion_node), load_nodes=beam.solution.load_nodes,
        case=case_names[ci], speed=float(speeds[si]), angles=theta[idx], node_loads=loads,
        main_loads=reactions,
        assumptions=(
            "Main bearing loads of the crank as a continuous beam"
            f" ({scheme_of(engine)}): a 3D Euler-Bernoulli frame through the journal and pin"
            " centre lines (journals and pins as bored circles, webs as rectangles of their"
            " thickness and mean width, counterweights adding mass but no stiffness), pinned on"
            " every main (Piraner, Pflueger and Bouthier, Cummins crankshaft and bearing"
            " analysis process, 2002; Agostini, Powertrain Components Design, 2019, 'Static"
            f" Analysis'); {beam.inertia_note}.",))


def throw_sections(beam: Beam, f_r: np.ndarray, f_t: np.ndarray, gamma: np.ndarray,
                   geometry: dict[str, float], theta: np.ndarray
                   ) -> tuple[cs.SectionLoads, cs.SectionLoads]:
    """Section loads of every throw under the con-rod forces on the pins (the loads IACS UR M53
    counts), on the continuous beam and by the lever rule (determinate), for the fatigue check.

    ``f_r``, ``f_t``: force on each pin in its throw frame, (C, S, T, N) [N]. Sections (M53's,
    :func:`checker.calc.crank_stress.throw_nominal_stresses`): the web centres at ``L1`` from
    each main, the journal fillets at ``L_G/2``, the pin fillets at ``L2 -/+ L_H/2`` and the
    oil bore at the pin centre. Support offsets (misalignment) load the continuous beam too.
    Returns (continuous, determinate), arrays (C, S, T, 2, N) and (C, S, T, N).
    """
    from ..calc import crank_beam as cb

    sol = beam.solution
    n_t = beam.pin_z.size
    g = np.asarray(gamma, dtype=float)[:, None]
    fx = f_r * np.sin(g) + f_t * np.cos(g)  # crank frame: F_R e_r + F_T e_t
    fy = f_r * np.cos(g) - f_t * np.sin(g)
    L1 = cs.web_centre_distance(geometry["main_spacing"], geometry["main_journal_length"],
                                geometry["pin_journal_length"], geometry.get("web_offset", 0.0))
    lg, lh = geometry["main_journal_length"], geometry["pin_journal_length"]
    z0, z1 = beam.main_z[:-1], beam.main_z[1:]
    half = (z1 - z0) / 2.0
    cuts = np.column_stack([z0 + L1, z1 - L1, z0 + lg / 2, z1 - lg / 2, z0 + half - lh / 2,
                            z0 + half + lh / 2, beam.pin_z])
    # everything is linear in the pin forces: the section loads of a unit force at each pin
    # in x and y (2 T load sets) give the whole sweep as one matrix product
    unit = np.zeros((2 * n_t, n_t, 1, 2))
    for t in range(n_t):
        unit[2 * t, t, 0, 0] = unit[2 * t + 1, t, 0, 1] = 1.0
    pm = sol.force_map[:, :, beam.pin_load_index, :2]  # (M, 2, T, 2)
    b_cont = np.einsum("mitj,btnj->bmni", pm, unit)  # (2T, M, 1, 2)
    share_front = (z1 - beam.pin_z) / (z1 - z0)  # lever rule, (T,)
    b_det = np.zeros_like(b_cont)
    b_det[:, :-1] += share_front[None, :, None, None] * unit
    b_det[:, 1:] += (1.0 - share_front)[None, :, None, None] * unit
    # the rods' torque balanced at the flywheel flange and the rotating inertias: their
    # torques' bearing loads, (C, S, M, N, 2), enter the continuous beam as extra main loads
    mz = _balancing_moments(beam, cf.Vector2(fx, fy), gamma, beam.radius)
    torque_b = np.einsum("mil,csln->csmni", sol.moment_map[:, :, :, 2], mz)
    forces = np.stack([fx, fy], axis=-2)  # (C, S, T, 2, N)
    lead = forces.shape[:-3]
    f2 = forces.reshape(lead + (2 * n_t, forces.shape[-1]))  # (C, S, 2T, N)
    off = _offset_loads(beam, theta)
    out = []
    for bearing in (b_cont, b_det):
        infl = cb.throw_section_loads(unit, bearing, pin_z=beam.pin_z, main_z=beam.main_z,
                                      throw_angle=gamma, cut_z=cuts)  # 3 x (2T, T, K, 1)
        m_r, m_t, v_r = ((a[..., 0].reshape(2 * n_t, -1).T @ f2).reshape(
            lead + (n_t, cuts.shape[1], f2.shape[-1])) for a in infl)
        if bearing is b_cont:
            extra_b = torque_b if off is None else torque_b + np.moveaxis(off, 1, 2)
            zero = np.zeros(extra_b.shape[:-3] + (n_t,) + extra_b.shape[-2:])
            extra = cb.throw_section_loads(zero, extra_b, pin_z=beam.pin_z,
                                           main_z=beam.main_z, throw_angle=gamma, cut_z=cuts)
            m_r, m_t, v_r = (x + e for x, e in zip((m_r, m_t, v_r), extra, strict=True))
        out.append(cs.SectionLoads(
            moment_web=m_r[..., 0:2, :], moment_web_tangential=m_t[..., 0:2, :],
            web_force=np.stack([-v_r[..., 0, :], v_r[..., 1, :]], axis=-2),
            moment_journal_fillet=m_r[..., 2:4, :], moment_pin_fillet=m_r[..., 4:6, :],
            moment_oil_radial=m_r[..., 6, :], moment_oil_tangential=m_t[..., 6, :]))
    return out[0], out[1]
