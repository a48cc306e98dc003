"""Graph calculation for flexible (elastic) couplings between engine and driven machine
(module ``coupling``, "Flexible coupling"): the coupling's vibratory torque, mean torque and
damping heat against the maker's ratings (rules CPL-).

Model: a TVModel element whose 'element to next' is ``flexible coupling`` is a hysteretic
element ``k* = C_Tdyn(T) (1 + j psi(T) / (2 pi))`` (:mod:`checker.calc.coupling`): the
catalogue's dynamic torsional stiffness and relative damping (sheet Coupling) times their
factors at the rubber's temperature (sheet CouplingTemperature, linear between its rows; 1
without the table). The torsion module solves the model with it (``tv.element_torque``); this
node reads the coupling element's torques and twists and judges them by the DIN 740-2
conventions: vibratory torque (all orders synthesised, half range) times ``S_t`` and ``S_f``
against ``T_KW``; damping power (sum of the orders) times ``S_t`` against ``P_KV``; mean torque
against ``T_KN``.
"""

from __future__ import annotations

import numpy as np

from ..calc import coupling as cp
from ..calc import propeller as prop
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs, Quantity, QuantitySpec, calculation, quantity
from ..results.coupling import CouplingDetail, CouplingState

COUPLING = "flexible coupling"
CASES = ("full", "no")

C_TORQUE = quantity(QuantitySpec(
    "coupling.vibratory_torque", "N*m", ("item", "case", "speed"),
    "Vibratory torque in the flexible coupling, all orders synthesised (half peak-to-peak)",
    "kN*m", coords={"case": CASES}, detail=CouplingDetail))
C_TORQUE_RATIO = quantity(QuantitySpec(
    "coupling.vibratory_torque_ratio", "", ("item", "case", "speed"),
    "Flexible coupling vibratory torque x S_t x S_f over the permissible vibratory torque T_KW",
    "", coords={"case": CASES}, detail=CouplingDetail))
C_POWER = quantity(QuantitySpec(
    "coupling.power", "W", ("item", "case", "speed"),
    "Damping power (heat) of the flexible coupling, sum of the orders", "W",
    coords={"case": CASES}, detail=CouplingDetail))
C_HEAT_RATIO = quantity(QuantitySpec(
    "coupling.heat_ratio", "", ("item", "case", "speed"),
    "Flexible coupling damping power x S_t over the permissible damping power P_KV", "",
    coords={"case": CASES}, detail=CouplingDetail))
C_MEAN_RATIO = quantity(QuantitySpec(
    "coupling.mean_torque_ratio", "", ("item", "case", "speed"),
    "Mean torque through the flexible coupling over its nominal torque T_KN", "",
    coords={"case": CASES}, detail=CouplingDetail))
PROVIDES = ("coupling.vibratory_torque", "coupling.vibratory_torque_ratio", "coupling.power",
            "coupling.heat_ratio", "coupling.mean_torque_ratio")

ENVELOPE_TEXT = ("judged within each load case's operating envelope (full load: the full-load"
                 " data range; no load: every speed up to the overspeed)")

_REQUIRED = (("nominal_torque", "the coupling's nominal torque T_KN"),
             ("vibratory_torque", "the coupling's permissible vibratory torque T_KW"),
             ("damping_power", "the coupling's permissible damping power P_KV"),
             ("stiffness", "the coupling's dynamic torsional stiffness C_Tdyn"),
             ("relative_damping", "the coupling's relative damping psi"))


def coupling_elements(engine: Engine) -> list[int]:
    """Element indices (front station's row) of the flexible couplings of sheet TVModel."""
    return [i for i, s in enumerate(engine.tv_model[:-1])
            if getattr(s, "element", "shaft") == COUPLING]


def has_coupling(engine: Engine) -> bool:
    """Whether the TV model has a flexible coupling."""
    return bool(coupling_elements(engine))


def _no_coupling(engine: Engine) -> str:
    return ("no element of sheet TVModel is a flexible coupling (column 'element to next'):"
            " the engine drives its load without one")


def station_inertia(engine: Engine) -> list[float]:
    """Inertia of every TVModel station [kg m^2]: a 'propeller' station in water (its dry
    inertia times 1 + the entrained water of sheet Driven)."""
    f = engine.driven.get("entrained_water")
    return [float(prop.wet_inertia(s.inertia, f)) if s.role == "propeller" and f is not None
            else s.inertia for s in engine.tv_model]


def station_damping(engine: Engine, speeds: np.ndarray) -> np.ndarray | None:
    """Absolute damping added per speed, (S, n) [N m s/rad]: a propeller's on the propeller
    curve (sheet Driven's torque at the Engine sheet's rated speed); None without."""
    q_r = engine.driven.get("propeller_torque")
    w_r = engine.params.get("rated_speed")
    props = [i for i, s in enumerate(engine.tv_model) if s.role == "propeller"]
    if q_r is None or w_r is None or not props:
        return None
    out = np.zeros((speeds.size, len(engine.tv_model)))
    out[:, props] = prop.propeller_damping(speeds, q_r, w_r)[:, None] / len(props)
    return out


def driven_text(engine: Engine) -> list[str]:
    """The driven machine's model in words (assumptions list); empty without one."""
    out = []
    f = engine.driven.get("entrained_water")
    if f is not None:
        out.append(f"Propeller inertia in water: the TVModel 'propeller' station's inertia"
                   f" times {1 + f:.3g} (entrained water {f:.3g} of the dry inertia, sheet"
                   " Driven; MacPherson, Puleo, Packard 2007).")
    if engine.driven.get("propeller_torque") is not None:
        out.append("Propeller damping: the slope of the propeller law, c = dQ/domega ="
                   " 2 Q_r omega / omega_r^2 at each speed (sheet Driven, Engine rated speed);"
                   " a quasi-static lower estimate of the propeller's damping.")
    return out


def coupling_state(engine: Engine) -> CouplingState:
    """The catalogue values (sheet Coupling) at the rubber's temperature (CouplingTemperature);
    raises MissingInputs naming every missing cell."""
    c = engine.coupling
    missing = [engine.describe_missing("Coupling", a, what=w)
               for a, w in _REQUIRED if c.get(a) is None]
    table = c.get("temperature_table") or ()
    t = c.get("temperature")
    if table and t is None:
        missing.append(engine.describe_missing(
            "Coupling", "temperature", what="the coupling rubber (needed to read the"
            " CouplingTemperature table)"))
    if missing:
        raise MissingInputs(missing)
    if table:
        tx = [r[0] for r in table]
        fac = [cp.table_factor(t, tx, [r[k] for r in table]) for k in (1, 2, 3)]
    else:
        fac = [np.ones(()), np.ones(()), np.ones(())]
    return CouplingState(
        nominal_torque=float(c["nominal_torque"]), vibratory_torque=float(c["vibratory_torque"]),
        damping_power=float(c["damping_power"]), stiffness_catalogue=float(c["stiffness"]),
        relative_damping_catalogue=float(c["relative_damping"]),
        temperature=None if t is None else float(t), stiffness_factor=float(fac[0]),
        damping_factor=float(fac[1]), temperature_factor=float(fac[2]))


def state_text(state: CouplingState) -> str:
    """The coupling's state in words (assumptions list)."""
    if state.temperature is None:
        where = "at the catalogue's reference state (no CouplingTemperature table)"
    else:
        where = (f"at the rubber temperature {state.temperature - 273.15:.0f} °C (factors"
                 f" {state.stiffness_factor:.3g} on C_Tdyn, {state.damping_factor:.3g} on psi,"
                 f" S_t {state.temperature_factor:.3g}, sheet CouplingTemperature)")
    return (f"Flexible coupling: C_Tdyn {state.stiffness / 1e3:.4g} kN m/rad, relative damping"
            f" psi {state.relative_damping:.3g} (loss factor psi/2pi) {where}; DIN 740-2"
            " conventions: T_W S_t S_f <= T_KW with S_f = sqrt(f/10 Hz) above 10 Hz at the"
            " frequency of the largest order, P_W S_t <= P_KV.")


@calculation("coupling_load", "coupling", provides=PROVIDES,
             needs=("tv.element_torque", "loads.cycle"),
             reads=("params", "tv_model", "coupling"), applies=has_coupling,
             applies_why=_no_coupling)
def coupling_load(engine: Engine, inputs: dict) -> dict[str, Quantity]:
    """Vibratory torque, damping heat and mean torque of each flexible coupling."""
    state = coupling_state(engine)
    el = inputs["tv.element_torque"]
    d = el.detail
    idx = coupling_elements(engine)
    names = [el.coords["item"][e] for e in idx]
    orders, speeds = d.orders, d.speeds
    omega = speeds[:, None] * orders  # (S, O)
    t_orders = d.coeffs[idx]  # (K, C, S, O)
    twist = d.twist_coeffs[idx]
    power_o = cp.damping_power(twist, omega, state.stiffness, state.relative_damping)
    power = power_o.sum(-1)
    vib = np.asarray(el.values)[idx]  # (K, C, S)
    ratio, f_big = cp.vibratory_torque_ratio(
        vib, np.abs(t_orders), omega / (2 * np.pi), state.vibratory_torque,
        state.temperature_factor)
    mean = d.mean[idx]
    detail = CouplingDetail(
        state=state, elements=tuple(names), speeds=speeds, orders=orders,
        torque_orders=t_orders, power_orders=power_o, vibratory_torque=vib, mean_torque=mean,
        power=power, frequency_factor=cp.frequency_factor(f_big), frequency=f_big,
        assumptions=(state_text(state),))
    coords = {"item": names, "case": list(el.coords["case"]), "speed": list(el.coords["speed"])}
    env = inputs["loads.cycle"].detail.cycle.envelope  # (C, S) judged points (None: all)

    def q(spec: QuantitySpec, values: np.ndarray) -> Quantity:
        return Quantity(spec, values, coords, detail=detail,
                        applies=None if env is None else np.broadcast_to(env, values.shape),
                        applies_text=ENVELOPE_TEXT)

    return {
        "coupling.vibratory_torque": q(C_TORQUE, vib),
        "coupling.vibratory_torque_ratio": q(C_TORQUE_RATIO, ratio),
        "coupling.power": q(C_POWER, power),
        "coupling.heat_ratio": q(C_HEAT_RATIO, power * state.temperature_factor
                                 / state.damping_power),
        "coupling.mean_torque_ratio": q(C_MEAN_RATIO, np.abs(mean) / state.nominal_torque),
    }
