"""The TV damper's inputs from sheets Damper and DamperRubber, gathered once for the torsion
and damper modules: which damper (rubber, the default, or an untuned viscous one), the
viscous damper's silicone coupling, the rubber's table against temperature, the operating
temperature range and the heat path. Missing inputs are raised as
:class:`~checker.evaluation.graph.MissingInputs` naming the cells.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..calc import damper as dmp
from ..calc import damper_temperature as dtemp
from ..calc import viscous_damper as vd
from ..description.engine import Engine
from ..evaluation.graph import MissingInputs

ENDS = ("cold", "hot")
"""The ends of the operating temperature range (sheet Damper) the damper is judged at."""


def damper_type(engine: Engine) -> str:
    """``"rubber"`` (the default, also when the Damper sheet gives no type) or ``"viscous"``."""
    return "viscous" if engine.damper.get("damper_type") == "viscous" else "rubber"


def has_rubber_ends(engine: Engine) -> bool:
    """A rubber damper with a temperature table or an operating temperature range: judged at
    the cold and hot ends (DMP-005..007)."""
    d = engine.damper
    return damper_type(engine) == "rubber" and any(
        d.get(a) is not None for a in ("rubber_table", "operating_temperature_min",
                                        "operating_temperature_max"))


def is_viscous(engine: Engine) -> bool:
    return damper_type(engine) == "viscous"


def why_no_rubber_ends(engine: Engine) -> str:
    """Why DMP-005..007 do not apply (the words of their not-applicable results)."""
    if damper_type(engine) != "rubber":
        return "the damper is a viscous (silicone) one: DMP-008..010 judge it"
    return ("the workbook gives no rubber temperature table (sheet DamperRubber) and no operating"
            " temperature range (Damper sheet): the rubber is judged at its stated properties"
            " (DMP-001..004)")


def why_not_viscous(engine: Engine) -> str:
    """Why DMP-008..010 do not apply."""
    return "the damper is a tuned rubber damper, not a viscous one (Damper type)"


def why_not_rubber(engine: Engine) -> str:
    """Why the rubber damper's tuning rules do not apply."""
    return ("the damper is an untuned viscous (silicone) damper: it has no tuning; DMP-008..010"
            " judge its damping and heat")


@dataclass(frozen=True)
class ViscousCoupling:
    """The silicone coupling of an untuned viscous damper (SI).

    ``damping`` is ``c`` at the reference temperature (or the typed value);
    ``damping_at(T)`` gives it at the silicone temperature ``T`` [K].
    """

    damping: float  # c [N m s/rad] at the reference temperature / typed
    factor: float | None  # Couette geometry factor Phi [m^3] (None: c typed)
    wetted_area: float | None  # [m^2]
    shear_stiffness: float | None  # Maxwell k_s = G Phi [N m/rad] (None: Newtonian)
    density: float | None  # [kg/m^3]
    nu_ref: float | None  # [m^2/s]
    t_ref: float | None  # [K]
    slope: float | None  # Andrade B [K] (None: no temperature law)
    source: str  # how c was obtained, for the report

    def damping_at(self, temperature: np.ndarray) -> np.ndarray:
        """``c(T)`` [N m s/rad]; constant when typed or without a temperature law."""
        t = np.asarray(temperature, dtype=float)
        if self.slope is None or self.nu_ref is None:
            return np.full(t.shape, self.damping)
        nu = vd.andrade_viscosity(t, self.nu_ref, self.t_ref, self.slope)
        return self.density * nu * self.factor

    def impedance(self, omega: np.ndarray, damping: np.ndarray | float | None = None
                  ) -> np.ndarray:
        """Complex coupling ``z(Omega)`` [N m/rad] with ``damping`` (default: nominal)."""
        c = self.damping if damping is None else damping
        return vd.maxwell_impedance(omega, c, self.shear_stiffness)


def _missing(engine: Engine, attrs: tuple[str, ...], what: str) -> list[str]:
    return [engine.describe_missing("Damper", a, what=what) for a in attrs
            if engine.damper.get(a) is None]


def viscous_coupling(engine: Engine) -> ViscousCoupling:
    """The viscous damper's coupling from sheet Damper (raises MissingInputs)."""
    d = engine.damper
    geo_attrs = ("ring_inner_radius", "ring_outer_radius", "ring_width", "gap_radial",
                 "gap_axial")
    geo = None
    if all(d.get(a) is not None for a in geo_attrs):
        g = vd.GapGeometry(*(float(d[a]) for a in geo_attrs))
        try:
            geo = (vd.couette_factor(g), vd.wetted_area(g))
        except ValueError as exc:
            raise MissingInputs([f"{engine.cell('Damper', 'gap_radial')}: {exc}"]) from None
    ks = None
    if d.get("silicone_shear_modulus") is not None:
        if geo is None:
            raise MissingInputs(_missing(engine, geo_attrs, "the viscous damper (the"
                                         " silicone's shear stiffness needs the gaps)"))
        ks = float(d["silicone_shear_modulus"]) * geo[0]
    if d.get("viscous_damping") is not None:
        return ViscousCoupling(float(d["viscous_damping"]), None if geo is None else geo[0],
                               None if geo is None else geo[1], ks, None, None, None, None,
                               f"typed ({engine.cell('Damper', 'viscous_damping')})")
    need = ("silicone_viscosity", "silicone_temperature_ref", "silicone_density")
    miss = _missing(engine, need + geo_attrs, "the viscous damper")
    if miss:
        raise MissingInputs([engine.describe_missing(
            "Damper", "viscous_damping", what="the viscous damper (or the silicone's"
            " viscosity, reference temperature and density with the ring and gap geometry)")]
            + miss)
    rho, nu, t_ref = (float(d["silicone_density"]), float(d["silicone_viscosity"]),
                      float(d["silicone_temperature_ref"]))
    slope = None if d.get("silicone_vtc") is None else vd.andrade_slope(float(d["silicone_vtc"]))
    return ViscousCoupling(rho * nu * geo[0], geo[0], geo[1], ks, rho, nu, t_ref, slope,
                           "Couette shear of the silicone on every wetted face")


HEAT_PATH = ("heat_transfer", "cooled_area")
"""The cells of the damper's heat path (sheet Damper), ``R = 1 / (h A)``."""


def heat_resistance(engine: Engine, what: str) -> float | None:
    """``R = 1 / (h A)`` [K/W] of the damper's cooled surface; None when the heat transfer
    coefficient is blank: no self-heating, the damper at the air temperature (docs/workbook.md).
    A coefficient without the area raises MissingInputs naming the area's cell."""
    if engine.damper.get("heat_transfer") is None:
        return None
    miss = _missing(engine, HEAT_PATH, what)
    if miss:
        raise MissingInputs(miss)
    return 1.0 / (float(engine.damper["heat_transfer"]) * float(engine.damper["cooled_area"]))


def heat_path_assumption(engine: Engine, res_th: float | None) -> tuple[str, ...]:
    """The assumption a blank heat transfer coefficient makes (none when it is given)."""
    if res_th is not None:
        return ()
    cell = engine.cell("Damper", "heat_transfer")
    at = f" ({cell})" if cell != "Damper" else ""
    return (f"Damper heat transfer coefficient blank{at}: no self-heating, the damper at the"
            " air temperature of each end of the operating range (T = T_air).",)


def temperature_range(engine: Engine, what: str) -> tuple[float, float]:
    """(cold, hot) air temperature at the damper [K] (raises MissingInputs)."""
    miss = _missing(engine, ("operating_temperature_min", "operating_temperature_max"), what)
    if miss:
        raise MissingInputs(miss)
    return (float(engine.damper["operating_temperature_min"]),
            float(engine.damper["operating_temperature_max"]))


def rubber_table(engine: Engine) -> dtemp.RubberTable:
    """The DamperRubber table (raises MissingInputs when not given)."""
    rows = engine.damper.get("rubber_table")
    if not rows:
        raise MissingInputs(["DamperRubber: the rubber's storage shear modulus and loss"
                             " factor against temperature (sheet DamperRubber; needed to"
                             " judge the rubber at the ends of the operating temperature"
                             " range)"])
    t, g, eta = (np.array(x, dtype=float) for x in zip(*rows))
    return dtemp.RubberTable(t, g, eta)


def rubber_factor(engine: Engine) -> float:
    """``Phi_r`` [m^3]: rubber stiffness per unit storage shear modulus (bonded annulus)."""
    miss = _missing(engine, ("inner_radius", "outer_radius", "axial_length"),
                    "the damper rubber (its stiffness from the shear modulus table)")
    if miss:
        raise MissingInputs(miss)
    d = engine.damper
    return float(dmp.annulus_stiffness(1.0, d["inner_radius"], d["outer_radius"],
                                       d["axial_length"]))
