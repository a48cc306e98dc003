"""The torsional model at the measured speeds, and its least-known parameters.

The prediction goes through the check's own path: the engine with its speed sweep replaced by
the measured speeds (and a fine grid between them for the curves) is evaluated by the graph up
to ``tv.nose_amplitude`` (loads cycle, crank-torque harmonics phased by the firing angles,
station excitation and forced response of :mod:`checker.modules.torsion`); its detail carries
the model and the station excitation. A parameter set re-solves only the forced response
(:func:`checker.calc.torsional.forced_response`) with the damper element, the crank's damping
and the excitation scaled, as the damper-tuning module re-solves it with the optimum rubber.

Parameters (each a factor on the value the workbook gives at the measured temperature):

* ``damper_damping``: a rubber damper's loss factor (and the element's viscous damping where
  given), or a viscous damper's silicone damping ``c``;
* ``damper_stiffness``: a rubber damper's storage stiffness (TVModel 'stiffness to next' of the
  ring), or a viscous damper's silicone shear stiffness (Maxwell, only where the workbook gives
  the silicone's shear modulus);
* ``crank_damping``: one factor on every other element's relative damping and every station's
  absolute damping (the crank's structural and friction damping of the TVModel);
* ``excitation_scale`` (optional): one factor on the crank-torque harmonics.

At the measured damper temperature a rubber damper with a DamperRubber table starts from the
table's ``k*(T) = Phi_r G'(T) (1 + j eta(T))``, a viscous one from ``c(T)`` of the silicone's
viscosity law (docs/dampers.md); without a temperature, from the workbook's nominal values.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..calc import torsional as tv
from ..calc import viscous_damper as vd
from ..description.engine import Engine, Params
from ..errors import InputError, InputErrors
from ..evaluation import graph
from ..evaluation.graph import MissingInputs
from ..modules import damper_inputs as dinp
from ..modules import loads
from ..modules.torsion import MAX_ORDER
from ..workbook.units import RPM
from .measurement import Measurement

GRID_POINTS = 121
"""Speeds of the fine grid the predicted curves and peaks are computed on (besides the measured
speeds), evenly between the lowest and the highest measured speed."""

BOUNDS = {"damper_damping": (0.1, 10.0), "damper_stiffness": (0.5, 2.0),
          "crank_damping": (0.1, 10.0), "excitation_scale": (0.5, 2.0)}
"""Bounds of each parameter's factor on its starting value in the fit."""

MODEL_ORDERS = 0.5 * np.arange(1, int(2 * MAX_ORDER) + 1)
"""The orders of the torsion module's excitation (0.5 to 24)."""


@dataclass(frozen=True)
class Parameter:
    """A model parameter the fit may move (SI)."""

    key: str
    label: str
    unit: str  # SI unit ("" for a ratio)
    start: float  # value at the measured temperature (SI): the fit's starting point
    cells: tuple[str, ...]  # workbook cells the calibrated copy scales by the fitted factor
    source: str  # where the starting value comes from, in words

    @property
    def bounds(self) -> tuple[float, float]:
        return BOUNDS[self.key]


@dataclass(frozen=True)
class Setup:
    """The model at the measured speeds for one station and load case."""

    engine: Engine
    model: tv.TorsionalModel  # the model of the check at the measured temperature
    base_model: tv.TorsionalModel  # the model of the check (nominal damper)
    ring: int | None
    viscous: bool
    shear_stiffness: float | None  # viscous damper's silicone shear stiffness [N m/rad]
    station: int
    station_name: str
    case: str
    speeds: np.ndarray  # (G,) every speed solved [rad/s]
    measured: np.ndarray  # (S,) index of each measured speed in ``speeds``
    orders: np.ndarray  # (O_all,) model orders
    order_index: np.ndarray  # (O,) index of each measured order in ``orders``
    force: np.ndarray  # (G, n, O_all) complex station excitation of the case [N m]
    parameters: tuple[Parameter, ...]
    notes: tuple[str, ...]

    def solve(self, factors: dict[str, float] | None = None, speeds: np.ndarray | None = None,
              orders: np.ndarray | None = None) -> np.ndarray:
        """Complex station angle (S, O) [rad] with the parameters scaled by ``factors``.

        ``speeds``/``orders``: indices into :attr:`speeds` / :attr:`orders` (default all).
        """
        f = {p.key: 1.0 for p in self.parameters}
        f.update(factors or {})
        si = np.arange(self.speeds.size) if speeds is None else np.asarray(speeds)
        oi = np.arange(self.orders.size) if orders is None else np.asarray(orders)
        model = self.scaled_model(f)
        force = self.force[np.ix_(si, np.arange(self.force.shape[1]), oi)]
        force = force * f.get("excitation_scale", 1.0)
        resp = tv.forced_response(model, self.speeds[si], self.orders[oi], force)
        return resp.theta[:, self.station, :]

    def scaled_model(self, f: dict[str, float]) -> tv.TorsionalModel:
        """The model with the damper element and the crank's damping scaled."""
        m = self.model
        kd, kk, kc = (f.get("damper_damping", 1.0), f.get("damper_stiffness", 1.0),
                      f.get("crank_damping", 1.0))
        stiff = m.stiffness.copy()
        loss = m.loss_factor.copy()
        rel = m.damping_rel * kc
        absd = m.damping_abs * kc
        dyn = dict(m.dynamic_stiffness)
        r = self.ring
        if r is not None:
            rel[r] = m.damping_rel[r] * kd  # the damper's viscous part (or its silicone's c)
            absd[r] = m.damping_abs[r]  # the ring's own absolute damping is not the crank's
            if not self.viscous:
                stiff[r] = m.stiffness[r] * kk
                loss[r] = m.loss_factor[r] * kd
            elif self.shear_stiffness is not None:
                dyn[r] = _Maxwell(m.dynamic_stiffness[r].damping * kd,
                                  self.shear_stiffness * kk)
        return tv.TorsionalModel(inertia=m.inertia, stiffness=stiff, damping_abs=absd,
                                 damping_rel=rel, loss_factor=loss, dynamic_stiffness=dyn)


@dataclass(frozen=True)
class _Maxwell:
    """A viscous damper's silicone coupling with its shear stiffness in series."""

    damping: float
    shear_stiffness: float

    def __call__(self, omega: np.ndarray) -> np.ndarray:
        return vd.maxwell_impedance(omega, self.damping, self.shear_stiffness)


def _error(where: str, message: str) -> InputErrors:
    return InputErrors([InputError(where, message)])


def station_index(engine: Engine, meas: Measurement) -> int:
    """The TVModel station of the measurement: a role (crank nose, damper ring, flywheel) or a
    station name (raises InputErrors naming the stations the model has)."""
    want = meas.station.strip().lower()
    st = engine.tv_model
    for i, s in enumerate(st):
        if s.role.lower() == want:
            return i
    for i, s in enumerate(st):
        if s.station.strip().lower() == want:
            return i
    have = ", ".join(f"'{s.station}' ({s.role})" for s in st) or "none"
    raise _error(meas.where("station"), f"station '{meas.station}' does not exist in the"
                 f" torsional model (sheet TVModel has the stations {have}); give a role"
                 " (crank nose, damper ring, flywheel) or a station name")


def check_against_model(engine: Engine, meas: Measurement) -> tuple[int, np.ndarray]:
    """Station index and the model's speed range checked against the measurement: every
    problem at its line (unknown station, an order the model has not, a speed outside the
    model's range)."""
    errs: list[InputError] = []
    station = None
    try:
        station = station_index(engine, meas)
    except InputErrors as exc:
        errs += exc.errors
    for o in meas.orders:
        if not np.any(np.abs(MODEL_ORDERS - o) < 1e-9):
            errs.append(InputError(meas.where(f"order {o:g}"), f"order {o:g} does not exist in"
                                   f" the model: the torsional excitation has the orders 0.5 to"
                                   f" {MAX_ORDER:g} in steps of 0.5"))
    try:
        sweep, _ = loads.speed_sweep(engine)
    except MissingInputs as exc:
        raise InputErrors([InputError(engine.source, r) for r in exc.reasons]) from None
    lo, hi = float(sweep.min()), float(sweep.max())
    for s, line in zip(meas.speeds, meas.speed_lines):
        if s < lo * (1 - 1e-9) or s > hi * (1 + 1e-9):
            errs.append(InputError(f"{meas.source}:{line}", f"speed {s / RPM:.0f} rpm is outside"
                                   f" the model's speed range {lo / RPM:.0f} to {hi / RPM:.0f}"
                                   " rpm (Engine sheet: minimum speed to maximum/overspeed)"))
    if errs:
        raise InputErrors(errs, source=meas.source)
    return int(station), sweep


def _grid(speeds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Measured speeds and a fine grid between them; the index of each measured speed."""
    grid = np.linspace(speeds.min(), speeds.max(), GRID_POINTS)
    grid = grid[np.min(np.abs(grid[:, None] - speeds[None, :]), axis=1) > 1e-6 * speeds.max()]
    allv = np.sort(np.concatenate([speeds, grid]))
    return allv, np.searchsorted(allv, speeds)


def setup(engine: Engine, meas: Measurement, fit_excitation: bool = False) -> Setup:
    """Evaluate the check's torsional model at the measured speeds (raises InputErrors for a
    measurement the model cannot be compared with, or a model that cannot be evaluated)."""
    station, _ = check_against_model(engine, meas)
    speeds, measured = _grid(np.asarray(meas.speeds, dtype=float))
    eng = dataclasses.replace(engine, params=Params({**engine.params,
                                                     "speed_points": tuple(speeds)}))
    out = graph.run(eng, ["tv.nose_amplitude"])
    q = out.quantities.get("tv.nose_amplitude")
    if q is None:
        why = out.unavailable.get("tv.nose_amplitude") or list(out.errors.values()) or [
            "the torsional model could not be evaluated"]
        raise InputErrors([InputError(engine.source, f"the torsional model cannot be"
                                      f" evaluated: {w}") for w in why])
    d = q.detail
    cases = list(q.coords["case"])
    ci = cases.index(meas.load)
    data = d.model_data
    base = d.model
    orders = np.asarray(d.orders, dtype=float)
    oi = np.array([int(np.argmin(np.abs(orders - o))) for o in meas.orders])
    viscous = dinp.is_viscous(engine)
    model, params, notes, ks = _parameters(engine, data, base, viscous, meas)
    if fit_excitation:
        params.append(Parameter("excitation_scale", "excitation scale (crank-torque"
                                " harmonics)", "", 1.0, (), "the loads module's cylinder"
                                " pressure and inertia torques (no workbook cell: reported,"
                                " not written)"))
    return Setup(engine=engine, model=model, base_model=base, ring=data.ring, viscous=viscous,
                 shear_stiffness=ks, station=station,
                 station_name=engine.tv_model[station].station, case=meas.load, speeds=speeds,
                 measured=measured, orders=orders, order_index=oi,
                 force=np.asarray(d.excitation)[ci], parameters=tuple(params), notes=tuple(notes))


def _cells(engine: Engine, *keys: tuple) -> tuple[str, ...]:
    out = []
    for k in keys:
        c = engine.where.get(k)
        if c:
            out.append(c)
    return tuple(out)


@dataclass
class _Start:
    """The model's damper and damping at the measured temperature, being gathered."""

    stiffness: np.ndarray
    loss_factor: np.ndarray
    damping_rel: np.ndarray
    dynamic: dict
    params: list[Parameter]
    notes: list[str]
    shear_stiffness: float | None = None


def _parameters(engine: Engine, data, base: tv.TorsionalModel, viscous: bool,
                meas: Measurement):
    """(model at the measured temperature, parameters, notes, silicone shear stiffness)."""
    st = _Start(base.stiffness.copy(), base.loss_factor.copy(), base.damping_rel.copy(),
                dict(base.dynamic_stiffness), [], [])
    if data.ring is None:
        st.notes.append("The torsional model has no damper ring (TVModel role 'damper ring'):"
                        " no damper parameter is fitted.")
    elif viscous:
        _viscous_start(engine, data.ring, meas.temperature, st)
    else:
        _rubber_start(engine, data.ring, base, meas, st)
    _crank_parameter(engine, base, data.ring, st)
    model = tv.TorsionalModel(inertia=base.inertia, stiffness=st.stiffness,
                              damping_abs=base.damping_abs, damping_rel=st.damping_rel,
                              loss_factor=st.loss_factor, dynamic_stiffness=st.dynamic)
    return model, st.params, st.notes, st.shear_stiffness


def _viscous_start(engine: Engine, ring: int, T: float | None, st: _Start) -> None:
    """A viscous damper's silicone damping ``c`` (at ``T`` by its viscosity law) and, with
    the silicone's shear modulus, its shear stiffness (Maxwell)."""
    coupling = dinp.viscous_coupling(engine)
    c0, how = coupling.damping, coupling.source
    if T is not None:
        if coupling.slope is None:
            st.notes.append("Damper temperature given, but the viscous damper's damping has no"
                            " temperature law (typed, or no viscosity temperature"
                            " coefficient): its nominal value is the starting point.")
        else:
            c0 = float(coupling.damping_at(np.array(T)))
            how = f"{how}, at the measured {T - 273.15:.0f} °C (Andrade's law)"
    typed = engine.damper.get("viscous_damping") is not None
    cells = _cells(engine, ("Damper", "viscous_damping" if typed else "silicone_viscosity"))
    st.params.append(Parameter("damper_damping", "viscous damper damping c", "N*m*s/rad", c0,
                               cells, how))
    ks = st.shear_stiffness = coupling.shear_stiffness
    if ks is None:
        st.damping_rel[ring] = c0
        st.notes.append("The viscous damper's silicone has no shear modulus (Damper sheet): the"
                        " coupling is purely viscous, no damper stiffness is fitted.")
        return
    st.params.append(Parameter("damper_stiffness", "silicone shear stiffness k_s", "N*m/rad",
                               ks, _cells(engine, ("Damper", "silicone_shear_modulus")),
                               "silicone shear modulus times the gap factor"))
    st.damping_rel[ring] = 0.0
    st.dynamic[ring] = _Maxwell(c0, ks)


def _rubber_at(engine: Engine, T: float, meas: Measurement) -> tuple[float, float]:
    """(k' [N m/rad], eta) of the rubber at ``T`` from the DamperRubber table."""
    rt = dinp.rubber_table(engine)
    g, eta = rt(np.array(T))
    if not np.isfinite(g):
        raise _error(meas.where("damper temperature"), f"damper temperature {T - 273.15:.1f}"
                     f" °C is outside the DamperRubber table ({rt.t_min - 273.15:.0f} to"
                     f" {rt.t_max - 273.15:.0f} °C)")
    try:
        phi = dinp.rubber_factor(engine)
    except MissingInputs as exc:
        raise InputErrors([InputError(engine.source, r) for r in exc.reasons]) from None
    return float(phi * g), float(eta)


def _rubber_start(engine: Engine, ring: int, base: tv.TorsionalModel, meas: Measurement,
                  st: _Start) -> None:
    """A rubber damper's loss factor (or the ring element's viscous damping) and storage
    stiffness, from the DamperRubber table at the measured temperature when both are given."""
    T = meas.temperature
    k0, eta0 = float(base.stiffness[ring]), float(base.loss_factor[ring])
    c0 = float(base.damping_rel[ring])
    how_k, how_d = "TVModel 'stiffness to next' of the ring", "Damper 'Rubber loss factor'"
    rows = range(len(engine.damper.get("rubber_table") or ()))
    if T is not None and rows:
        k0, eta0 = _rubber_at(engine, T, meas)
        how_k = how_d = (f"DamperRubber table at the measured {T - 273.15:.0f} °C (bonded"
                         " annulus, Gent 2012)")
    elif T is not None:
        st.notes.append("Damper temperature given, but the workbook has no DamperRubber table:"
                        " the rubber's nominal stiffness and loss factor are the starting"
                        " point.")
    st.stiffness[ring], st.loss_factor[ring] = k0, eta0
    d_cells = _cells(engine, ("Damper", "loss_factor"),
                     *(("DamperRubber", i, "loss_factor") for i in rows))
    if c0 > 0:
        d_cells += _cells(engine, ("TVModel", ring, "relative_damping"))
    if eta0 > 0:
        st.params.append(Parameter("damper_damping", "rubber loss factor", "", eta0, d_cells,
                                   how_d))
    elif c0 > 0:
        st.params.append(Parameter("damper_damping", "damper relative damping", "N*m*s/rad",
                                   c0, d_cells, "TVModel 'damping to next' of the ring"))
    else:
        st.notes.append("The damper rubber has no damping (loss factor 0): none is fitted.")
    st.params.append(Parameter(
        "damper_stiffness", "rubber storage stiffness k'", "N*m/rad", k0,
        _cells(engine, ("TVModel", ring, "stiffness"),
               *(("DamperRubber", i, "storage_modulus") for i in rows)), how_k))


def _crank_parameter(engine: Engine, base: tv.TorsionalModel, ring: int | None,
                     st: _Start) -> None:
    """One factor on the crank's damping: every other element's relative and every other
    station's absolute damping (when the TVModel gives any)."""
    rel = [e for e in range(base.n_elements) if e != ring and base.damping_rel[e] > 0]
    absd = [i for i in range(base.n_stations) if i != ring and base.damping_abs[i] > 0]
    if not (rel or absd):
        st.notes.append("The TVModel gives the crank no damping (relative or absolute): none"
                        " is fitted.")
        return
    parts = ([f"{len(rel)} elements' relative damping"] if rel else []) + (
        [f"{len(absd)} stations' absolute damping"] if absd else [])
    st.params.append(Parameter(
        "crank_damping", "crank damping (factor)", "", 1.0,
        _cells(engine, *(("TVModel", e, "relative_damping") for e in rel),
               *(("TVModel", i, "absolute_damping") for i in absd)),
        "TVModel: one factor on " + " and ".join(parts)))
