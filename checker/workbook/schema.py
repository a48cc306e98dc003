"""Declared layout of the engine workbook: every sheet, parameter and column with its kind.

Two sheet shapes:

* **parameter sheets** (``Engine``, ``Oil``, ``Damper``, ``Fatigue``): one parameter per row,
  columns ``parameter | value | unit | note``. The parameter names in column A are matched
  case-insensitively.
* **table sheets** (``Cylinders``, ``Bearings``, ``Joints``...): row 1 holds the column names,
  row 2 the unit of each column (``-`` or blank for text and dimensionless), data from row 3.

Each field has a *kind* (a key of :data:`checker.workbook.units.KINDS`, or ``int``, ``text``,
``choice``), whether it is required, a sign check, and two declared ranges (:class:`Span`):

* ``valid``: outside it the calculations cannot run meaningfully (overflow, a grid that would
  take hours, a temperature below absolute zero...): an **input error**;
* ``usual``: the range of crank-train engines, from small high-speed engines to marine
  two-strokes; outside it the value is probably a unit or typing slip: a **warning**.

A choice field accepts its :attr:`Field.choices` (and :attr:`Field.aliases`), compared
ignoring case, spaces, hyphens and underscores (:func:`resolve_choice`, the one place where
spellings are mapped). :data:`CHOICE_SETS` lists the allowed values per attribute so the rule
table can be checked against them. The loader converts every value to SI and reports all
problems of a workbook together.
"""

from __future__ import annotations

import difflib
import functools
import re
from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class Span:
    """A closed range ``lo..hi`` of a field, in the stated ``unit`` (``None`` = open end).

    ``unit`` is read like a workbook unit cell (``mm``, ``rpm``, ``°C``, ``-``...); the loader
    converts the ends to SI with :func:`checker.workbook.units.to_si` (:meth:`si`).
    """

    lo: float | None
    hi: float | None
    unit: str = ""

    def text(self) -> str:
        """The range as users read it, e.g. ``25..1000 mm``."""
        lo = "" if self.lo is None else f"{self.lo:g}"
        hi = "" if self.hi is None else f"{self.hi:g}"
        if self.lo is None:
            rng = f"at most {hi}"
        elif self.hi is None:
            rng = f"at least {lo}"
        else:
            rng = f"{lo}..{hi}"
        return rng + ("" if self.unit in ("", "-") else f" {self.unit}")

    def si(self, kind: str) -> tuple[float, float]:
        """The ends in SI for a field of ``kind`` (open ends as -inf/inf)."""
        return _span_si(self, kind)

    def contains(self, value_si: float, kind: str) -> bool:
        lo, hi = self.si(kind)
        return lo <= value_si <= hi


@functools.cache
def _span_si(span: Span, kind: str) -> tuple[float, float]:
    if kind in ("int", "int_list"):
        conv = float
    else:
        from .units import to_si

        def conv(v: float) -> float:
            return to_si(v, span.unit, kind)
    lo = -float("inf") if span.lo is None else conv(span.lo)
    hi = float("inf") if span.hi is None else conv(span.hi)
    return lo, hi


@dataclass(frozen=True)
class Field:
    """One parameter (parameter sheet) or column (table sheet).

    ``aliases`` maps other spellings to a choice, ``(spelling, choice)``; ``ambiguous`` names
    spellings that could mean several choices, ``(spelling, (choice, ...))``: such a value is
    an input error that asks the user to pick one.
    """

    label: str
    attr: str
    kind: str
    required: bool = True
    check: str | None = None  # ">0", ">=0", "0..1", "<0.5" ...
    choices: tuple[str, ...] = ()
    note: str = ""
    valid: Span | None = None
    usual: Span | None = None
    aliases: tuple[tuple[str, str], ...] = ()
    ambiguous: tuple[tuple[str, tuple[str, ...]], ...] = ()
    expected: str = ""
    """What an error message says was expected, where the kind alone would mislead (a number
    whose unit another column gives)."""


@dataclass(frozen=True)
class Sheet:
    """A sheet of the workbook."""

    name: str
    shape: str  # "parameters" | "table" | "notes"
    fields: tuple[Field, ...] = ()
    required: bool = False
    key: str | None = None  # table column whose values must be unique (names)
    note: str = ""
    extra_columns: tuple[str, ...] = field(default=("note", "notes", "source", "comment"))
    max_rows: int | None = None  # more data rows than this is an input error (run time)
    # more data rows than this is a warning (unusually dense, e.g. a logged curve); only for
    # tables the calculations merely interpolate, whose cost is linear in the rows
    dense_rows: int | None = None


# ---------------------------------------------------------------------------- choices
def choice_key(text: Any) -> str:
    """Spelling-insensitive form of a choice: lower case without spaces, hyphens, underscores."""
    if isinstance(text, float):
        text = f"{text:g}"
    return re.sub(r"[\s_\-]+", "", str(text)).lower()


class ChoiceProblem(ValueError):
    """A value that is not one of a choice field's values; the message is for the user."""


@functools.cache
def _choice_table(f: Field) -> dict[str, str]:
    table = {choice_key(c): c for c in f.choices}
    for spelling, target in f.aliases:
        if target not in f.choices:  # pragma: no cover - schema error
            raise AssertionError(f"{f.label}: alias '{spelling}' -> unknown choice '{target}'")
        table.setdefault(choice_key(spelling), target)
    return table


def expected_choices(f: Field) -> str:
    """``one of 'a', 'b', 'c'`` for messages."""
    return "one of " + ", ".join(f"'{c}'" for c in f.choices)


def resolve_choice(f: Field, value: Any) -> str:
    """The choice of field ``f`` that ``value`` names (aliases and spelling variants included).

    Raises
    ------
    ChoiceProblem
        With the allowed values and, where one is close, a "did you mean" suggestion; an
        ambiguous spelling (``ambiguous``) names the choices it could mean.
    """
    text = f"{value:g}" if isinstance(value, float) else re.sub(r"\s+", " ", str(value)).strip()
    key = choice_key(text)
    table = _choice_table(f)
    if key in table:
        return table[key]
    for spelling, options in f.ambiguous:
        if choice_key(spelling) == key:
            raise ChoiceProblem(
                f"'{text}' is ambiguous: give one of " + ", ".join(f"'{c}'" for c in options)
                + " (their limits differ)")
    close = difflib.get_close_matches(key, list(table), n=1, cutoff=0.6)
    hint = f"; did you mean '{table[close[0]]}'?" if close else ""
    raise ChoiceProblem(f"expected {expected_choices(f)}, found '{text}'{hint}")


#: Bearing linings (``Bearings`` column ``lining``); the keys of ``limit_by = "lining"`` rules.
LININGS = ("as15", "as16", "aluminium bimetal", "tri-metal", "sputter", "polymer")
_LINING_ALIASES = (
    ("aluminum bimetal", "aluminium bimetal"),
    ("al bimetal", "aluminium bimetal"), ("aluminium-tin bimetal", "aluminium bimetal"),
    ("alsn bimetal", "aluminium bimetal"), ("alsn", "aluminium bimetal"),
    ("trimetallic", "tri-metal"), ("sputtered", "sputter"), ("sputter bearing", "sputter"),
    ("sputter coated", "sputter"), ("polymer coated", "polymer"), ("polymer coating", "polymer"),
)
#: Clamped materials under a bolt head (``Joints`` column ``clamped material``); the keys of
#: ``limit_by = "clamped_material"`` rules.
CLAMPED_MATERIALS = ("steel", "grey cast iron", "nodular cast iron", "aluminium")
_CLAMPED_ALIASES = (
    ("gray cast iron", "grey cast iron"), ("grey iron", "grey cast iron"),
    ("gray iron", "grey cast iron"), ("lamellar cast iron", "grey cast iron"),
    ("gjl", "grey cast iron"), ("en gjl", "grey cast iron"),
    ("ductile iron", "nodular cast iron"), ("ductile cast iron", "nodular cast iron"),
    ("nodular iron", "nodular cast iron"), ("sg iron", "nodular cast iron"),
    ("spheroidal graphite iron", "nodular cast iron"), ("gjs", "nodular cast iron"),
    ("en-gjs", "nodular cast iron"), ("aluminum", "aluminium"), ("aluminium alloy", "aluminium"),
    ("aluminum alloy", "aluminium"), ("cast aluminium", "aluminium"), ("al", "aluminium"),
)
_CASE_ALIASES = (("full load", "full"), ("part load", "part"), ("no load", "no"))


F = Field
R = Span

ENGINE = Sheet(
    "Engine",
    "parameters",
    required=True,
    note="Engine geometry, masses and operating range.",
    fields=(
        F("Engine name", "name", "text"),
        F("Project", "project", "text", required=False, note="Document control (report page 1)."),
        F("Revision", "revision", "text", required=False, note="Document control, e.g. B."),
        F("Author", "author", "text", required=False, note="Document control."),
        F("Reviewer", "reviewer", "text", required=False, note="Document control."),
        F("Document date", "document_date", "text", required=False,
          note="Document control (the report's run date when blank)."),
        F("Number of cylinders", "cylinders", "int", check=">0",
          valid=R(1, 64), usual=R(1, 24)),
        F("Engine class", "engine_class", "choice",
          choices=("passenger car", "commercial vehicle", "industrial", "marine"),
          required=False,
          note="Selects the published limits that fit the engine (the crank-nose TV targets"
               " TV-001..003 are Bell 2013's for a refined passenger-car engine with a rubber"
               " damper); a class without published limits leaves those rules not evaluated"
               " until the project's limits are entered in RuleOverrides. Blank = passenger"
               " car (stated as an assumption).",
          aliases=(("car", "passenger car"), ("passenger", "passenger car"),
                   ("pc", "passenger car"), ("truck", "commercial vehicle"),
                   ("heavy duty", "commercial vehicle"), ("commercial", "commercial vehicle"),
                   ("bus", "commercial vehicle"), ("off highway", "industrial"),
                   ("genset", "industrial"), ("stationary", "industrial"))),
        F("Layout", "layout", "choice", choices=("inline", "v"), required=False,
          note="inline or V; a V engine gives a bank angle per cylinder in Cylinders.",
          aliases=(("straight", "inline"), ("vee", "v"),
                   ("v engine", "v"))),
        F("Bore", "bore", "length", check=">0",
          valid=R(1, 5000, "mm"), usual=R(25, 1000, "mm")),
        F("Stroke", "stroke", "length", check=">0",
          valid=R(1, 10000, "mm"), usual=R(25, 3500, "mm")),
        F("Connecting rod length", "rod_length", "length", check=">0",
          note="Big-end to small-end centre distance.",
          valid=R(1, 20000, "mm"), usual=R(50, 8000, "mm")),
        F("Cylinder offset", "cylinder_offset", "length", required=False,
          note="Offset of the cylinder axis from the crank axis (convention of Agostini,"
               " Powertrain Components Design, 2019).",
          valid=R(-1000, 1000, "mm"), usual=R(-50, 50, "mm")),
        F("Pin offset", "pin_offset", "length", required=False,
          note="Piston pin offset from the cylinder axis, towards the thrust side positive.",
          valid=R(-500, 500, "mm"), usual=R(-10, 10, "mm")),
        F("Crankshaft rotation", "rotation", "choice", choices=("clockwise", "anticlockwise"),
          required=False, note="Seen from the front (crank nose).",
          aliases=(("cw", "clockwise"), ("ccw", "anticlockwise"), ("acw", "anticlockwise"),
                   ("counterclockwise", "anticlockwise"))),
        F("Firing order", "firing_order", "text", note="e.g. 1-3-4-2"),
        F("Cylinder spacing", "cylinder_spacing", "length", check=">0", required=False,
          valid=R(1, 20000, "mm"), usual=R(50, 2000, "mm")),
        F("Main journal spacing", "main_spacing", "length", check=">0", required=False,
          valid=R(1, 20000, "mm"), usual=R(50, 2000, "mm")),
        F("Main bearing supports", "support_scheme", "choice",
          choices=("determinate", "continuous beam, rigid supports",
                   "continuous beam, elastic supports"),
          required=False,
          note="How the crank carries its loads to the main bearings. determinate (default):"
               " each throw a rigid beam simply supported on its two mains (Bell 2013, the"
               " classical concept method). continuous beam: the whole crank an elastic beam"
               " through its journal and pin centre lines on every main, rigid supports or"
               " elastic ones (radial stiffness below or per main bearing in Bearings); needs"
               " sheet Crank (each throw's bending stiffness from its dimensions).",
          aliases=(("isostatic", "determinate"), ("statically determinate", "determinate"),
                   ("simply supported", "determinate"),
                   ("continuous beam", "continuous beam, rigid supports"),
                   ("hyperstatic", "continuous beam, rigid supports"),
                   ("indeterminate", "continuous beam, rigid supports"),
                   ("continuous beam rigid supports", "continuous beam, rigid supports"),
                   ("continuous beam, rigid", "continuous beam, rigid supports"),
                   ("continuous beam elastic supports", "continuous beam, elastic supports"),
                   ("continuous beam, elastic", "continuous beam, elastic supports"),
                   ("elastic supports", "continuous beam, elastic supports"))),
        F("Main bearing support stiffness", "support_stiffness", "linear_stiffness",
          check=">0", required=False,
          note="Radial stiffness of every main bearing's support (block, cap, shell and oil"
               " film in series) for the continuous beam on elastic supports; a value in"
               " Bearings' 'support stiffness' wins for its main. No published value is general:"
               " take it from the block's FE or a test.",
          valid=R(1e3, 1e10, "N/mm"), usual=R(1e4, 1e7, "N/mm")),
        F("Connecting rod mass", "rod_mass", "mass", check=">0", required=False,
          note="Including bolts and bearing shells.",
          valid=R(0.001, 100000, "kg"), usual=R(0.05, 10000, "kg")),
        F("Rod centre of mass from big end", "rod_com", "length", check=">0", required=False,
          valid=R(0.1, 20000, "mm"), usual=R(5, 5000, "mm")),
        F("Rod moment of inertia about centre of mass", "rod_inertia", "inertia", check=">0",
          required=False,
          valid=R(1e-9, 1e6, "kg m^2"), usual=R(1e-5, 1e4, "kg m^2")),
        F("Piston assembly mass", "piston_mass", "mass", check=">0", required=False,
          note="Piston, rings, pin and clips.",
          valid=R(0.001, 100000, "kg"), usual=R(0.05, 10000, "kg")),
        F("Compression ratio", "compression_ratio", "ratio", check=">1", required=False,
          valid=R(1, 100), usual=R(6, 25)),
        F("Intake manifold pressure at full load", "intake_pressure", "pressure", check=">0",
          required=False,
          valid=R(0.05, 50, "bar"), usual=R(0.3, 6, "bar")),
        F("Rated speed", "rated_speed", "speed", check=">0", required=False,
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("Minimum speed", "speed_min", "speed", check=">0", required=False,
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("Maximum speed", "speed_max", "speed", check=">0", required=False,
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("Speed step", "speed_step", "speed", check=">0", required=False,
          valid=R(0.1, 10000, "rpm"), usual=R(10, 1000, "rpm")),
        F("Overspeed", "overspeed", "speed", check=">0", required=False,
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("Accessory drive torque at crank nose", "fead_torque", "torque", check=">=0",
          required=False, note="FEAD + timing drive torque added at the crank-nose joint.",
          valid=R(0, 1e8, "N m"), usual=R(0, 1e5, "N m")),
        F("Free force limit, 1st order", "free_force_limit_1", "force", check=">0",
          required=False, valid=R(1e-3, 1e9, "N"), usual=R(1, 1e7, "N"),
          note="Project limit on the 1st-order free force at the rated speed"
                               " (BAL-001; blank = not judged)."),
        F("Free force limit, 2nd order", "free_force_limit_2", "force", check=">0",
          required=False, valid=R(1e-3, 1e9, "N"), usual=R(1, 1e7, "N"),
          note="Project limit on the 2nd-order free force at the rated speed"
                               " (BAL-002; blank = not judged)."),
        F("Free moment limit, 1st order", "free_moment_limit_1", "torque", check=">0",
          required=False, valid=R(1e-3, 1e9, "N m"), usual=R(1, 1e7, "N m"),
          note="Project limit on the 1st-order free moment at the rated speed"
                               " (BAL-003; blank = not judged)."),
        F("Free moment limit, 2nd order", "free_moment_limit_2", "torque", check=">0",
          required=False, valid=R(1e-3, 1e9, "N m"), usual=R(1, 1e7, "N m"),
          note="Project limit on the 2nd-order free moment at the rated speed"
                               " (BAL-004; blank = not judged)."),
        F("Balance ratio, minimum", "balance_ratio_min", "ratio", check=">=0", required=False,
          valid=R(0, 10), usual=R(0, 2),
          note="Lowest acceptable counterweight balance ratio per throw (counterweight /"
               " rotating unbalance, e.g. 50 %; BAL-005 needs minimum and maximum)."),
        F("Balance ratio, maximum", "balance_ratio_max", "ratio", check=">0", required=False,
          valid=R(0, 10), usual=R(0, 2),
          note="Highest acceptable counterweight balance ratio per throw (e.g. 100 %)."),
        F("Target cyclic irregularity", "target_irregularity", "ratio", check="0..1",
          required=False, valid=R(1e-6, 1), usual=R(1e-4, 0.5),
          note="(w_max - w_min)/w_mean (w_mean the time-mean speed) allowed at the lowest"
                               " speed, by"
                               " application (FLY-001; blank = not judged)."),
    ),
)

OIL = Sheet(
    "Oil",
    "parameters",
    note="Lubricant and supply conditions.",
    fields=(
        F("Oil grade", "grade", "text", required=False, note="SAE J300 grade, e.g. 5W30"),
        F("Kinematic viscosity at 40 °C", "kv40", "kinematic_viscosity", check=">0",
          required=False,
          valid=R(2, 1e5, "mm^2/s"), usual=R(10, 1000, "mm^2/s")),
        F("Kinematic viscosity at 100 °C", "kv100", "kinematic_viscosity", check=">0",
          required=False,
          valid=R(2, 1e4, "mm^2/s"), usual=R(3, 50, "mm^2/s")),
        F("Density at 15 °C", "density", "density", check=">0", required=False,
          valid=R(650, 1050, "kg/m^3"), usual=R(800, 950, "kg/m^3")),
        F("HTHS viscosity at 150 °C", "hths", "viscosity", check=">0", required=False,
          valid=R(0.5, 1000, "mPa s"), usual=R(1.5, 8, "mPa s")),
        F("Oil supply pressure", "supply_pressure", "pressure_gauge", check=">=0",
          required=False,
          valid=R(0, 200, "bar(g)"), usual=R(0, 15, "bar(g)")),
        F("Oil supply temperature", "supply_temperature", "temperature", check=">0",
          required=False,
          valid=R(-40, 250, "°C"), usual=R(20, 160, "°C")),
        F("Film temperature rise", "temperature_rise", "temperature_difference", check=">=0",
          required=False, note="Added to the supply temperature to give the film temperature"
                               " (not used with Film temperature = heat balance).",
          valid=R(0, 200, "K"), usual=R(0, 60, "K")),
        F("Film temperature", "film_temperature_method", "choice",
          choices=("supply plus rise", "heat balance"), required=False,
          note="supply plus rise = the film runs at the supply temperature plus the film"
               " temperature rise (default); heat balance = every bearing, load case and speed"
               " at the effective temperature of its heat balance (friction power carried away"
               " by its oil flow, ISO 7902-1), also for the film thickness.",
          aliases=(("supply", "supply plus rise"), ("supply + rise", "supply plus rise"),
                   ("fixed", "supply plus rise"), ("balance", "heat balance"),
                   ("thermal", "heat balance"), ("heat-balance", "heat balance"))),
        F("Heat fraction carried by the oil", "heat_to_oil", "ratio", check=">0",
          required=False,
          note="Fraction of the bearing friction heat that leaves with the oil flow (default 1:"
               " none conducted to journal and housing, conservative).",
          valid=R(1e-3, 1), usual=R(0.5, 1)),
        F("Mobility model", "mobility_model", "choice",
          choices=("short bearing", "exact short bearing", "finite length", "Butenschoen fits"),
          required=False,
          note="short bearing = Booker closed form (default, Bell, Ricardo 2013); exact short"
               " bearing = numerical short-bearing mobility (reference); finite length ="
               " mobility map of"
               " the finite-length Reynolds equation (checker's solver, L/D 1/16..1);"
               " Butenschoen fits = Butenschoen (1976) curve fits (L/D 1/8..1).",
          aliases=(("short", "short bearing"), ("booker", "short bearing"),
                   ("exact short", "exact short bearing"), ("finite", "finite length"),
                   ("reynolds", "finite length"), ("finite bearing", "finite length"),
                   ("butenschoen", "Butenschoen fits"))),
    ),
)

DAMPER = Sheet(
    "Damper",
    "parameters",
    note="TV damper rubber: properties, geometry and the supplier's limits.",
    fields=(
        F("Rubber loss factor", "loss_factor", "ratio", check=">=0", required=False,
          valid=R(0, 10), usual=R(0.02, 1)),
        F("Rubber inner radius", "inner_radius", "length", check=">0", required=False,
          valid=R(1, 5000, "mm"), usual=R(10, 1000, "mm")),
        F("Rubber outer radius", "outer_radius", "length", check=">0", required=False,
          valid=R(1, 5000, "mm"), usual=R(10, 1000, "mm")),
        F("Rubber axial length", "axial_length", "length", check=">0", required=False,
          valid=R(0.1, 5000, "mm"), usual=R(2, 500, "mm")),
        F("Rubber shear stress limit", "shear_stress_limit", "stress", check=">0",
          required=False,
          valid=R(0.001, 1000, "MPa"), usual=R(0.05, 10, "MPa")),
        F("Rubber heat per unit volume limit", "heat_limit", "power_density", check=">0",
          required=False,
          valid=R(1e-6, 1e4, "W/cm^3"), usual=R(0.001, 10, "W/cm^3")),
        F("Tuning ratio, minimum", "tuning_ratio_min", "ratio", check=">0", required=False,
          valid=R(1e-3, 100), usual=R(0.3, 3),
          note="Lowest acceptable ring frequency / crank first-mode frequency (DMP-004 needs"
               " minimum and maximum)."),
        F("Tuning ratio, maximum", "tuning_ratio_max", "ratio", check=">0", required=False,
          valid=R(1e-3, 100), usual=R(0.3, 3),
          note="Highest acceptable ring frequency / crank first-mode frequency."),
        # --- damper type, operating temperatures and heat path (rubber and viscous)
        F("Damper type", "damper_type", "choice", required=False,
          choices=("rubber", "viscous"),
          aliases=(("elastomer", "rubber"), ("rubber damper", "rubber"),
                   ("silicone", "viscous"), ("viscous damper", "viscous"),
                   ("houdaille", "viscous"), ("untuned viscous", "viscous")),
          note="rubber (blank): tuned ring on rubber, TVModel 'stiffness to next' of the ring"
               " row = rubber stiffness; viscous: untuned ring in silicone (Houdaille), the"
               " ring row's stiffness and damping to next blank, the coupling from this"
               " sheet."),
        F("Operating temperature, minimum", "operating_temperature_min", "temperature",
          required=False, valid=R(-100, 300, "°C"), usual=R(-50, 150, "°C"),
          note="Air temperature around the damper at the cold end of operation (the damper"
               " is judged at both ends: DMP-005..007, DMP-008..010)."),
        F("Operating temperature, maximum", "operating_temperature_max", "temperature",
          required=False, valid=R(-100, 300, "°C"), usual=R(-50, 150, "°C"),
          note="Air temperature around the damper at the hot end of operation."),
        F("Damper heat transfer coefficient", "heat_transfer", "heat_transfer_coefficient",
          check=">0", required=False, valid=R(0.1, 1e5, "W/(m^2 K)"),
          usual=R(5, 1000, "W/(m^2 K)"),
          note="Convective heat-transfer coefficient from the damper's cooled surface to the"
               " air: with the area, the damper's own temperature T = T_air + P/(h A)"
               " (blank: no self-heating, the damper at the air temperature)."),
        F("Damper cooled surface area", "cooled_area", "area", check=">0", required=False,
          valid=R(1, 1e8, "mm^2"), usual=R(1e3, 1e7, "mm^2"),
          note="Outer surface of the housing (viscous) or ring (rubber) the heat leaves by."),
        # --- viscous (untuned, Houdaille) damper
        F("Viscous damping coefficient", "viscous_damping", "torsional_damping", check=">0",
          required=False, valid=R(1e-6, 1e7, "N m s/rad"), usual=R(0.01, 1e5, "N m s/rad"),
          note="Viscous damper: the coupling ring-housing c, if known; blank = from the"
               " silicone's viscosity and the gap geometry (Couette shear). Give one, not"
               " both."),
        F("Silicone kinematic viscosity", "silicone_viscosity", "kinematic_viscosity",
          check=">0", required=False, valid=R(1, 1e8, "mm^2/s"), usual=R(100, 2e6, "mm^2/s"),
          note="At the reference temperature (the grade, e.g. 100 000 cSt at 25 °C)."),
        F("Silicone reference temperature", "silicone_temperature_ref", "temperature",
          required=False, valid=R(-100, 300, "°C"), usual=R(0, 60, "°C")),
        F("Silicone viscosity temperature coefficient", "silicone_vtc", "ratio",
          check="0..1", required=False, valid=R(0.01, 0.99), usual=R(0.3, 0.9),
          note="VTC = 1 - nu(98.9 °C)/nu(37.8 °C) (210/100 °F) of the silicone-fluid"
               " datasheet; with it ln nu = A + B/T (Andrade 1930) gives the viscosity at the"
               " silicone's temperature."),
        F("Silicone density", "silicone_density", "density", check=">0", required=False,
          valid=R(100, 5000, "kg/m^3"), usual=R(900, 1100, "kg/m^3")),
        F("Silicone shear modulus", "silicone_shear_modulus", "stress", check=">0",
          required=False, valid=R(1, 1e9, "Pa"), usual=R(100, 1e7, "Pa"),
          note="Optional: the fluid's shear stiffness in series with its viscosity (Maxwell"
               " model, Andre & Spurk 1982); blank = Newtonian."),
        F("Ring inner radius", "ring_inner_radius", "length", check=">0", required=False,
          valid=R(1, 5000, "mm"), usual=R(10, 1000, "mm")),
        F("Ring outer radius", "ring_outer_radius", "length", check=">0", required=False,
          valid=R(1, 5000, "mm"), usual=R(10, 1000, "mm")),
        F("Ring width", "ring_width", "length", check=">0", required=False,
          valid=R(0.1, 5000, "mm"), usual=R(2, 500, "mm")),
        F("Radial gap", "gap_radial", "length", check=">0", required=False,
          valid=R(0.001, 100, "mm"), usual=R(0.05, 3, "mm"),
          note="Silicone film at the ring's inner and outer cylindrical faces."),
        F("Axial gap", "gap_axial", "length", check=">0", required=False,
          valid=R(0.001, 100, "mm"), usual=R(0.05, 3, "mm"),
          note="Silicone film at each side face of the ring."),
        F("Silicone heat flux limit", "heat_flux_limit", "heat_flux", check=">0",
          required=False, valid=R(1e-6, 1e3, "W/cm^2"), usual=R(0.001, 10, "W/cm^2"),
          note="Largest dissipated power per wetted ring area (supplier; DMP-008)."),
        F("Silicone temperature limit", "silicone_temperature_limit", "temperature",
          required=False, valid=R(-50, 400, "°C"), usual=R(60, 250, "°C"),
          note="Highest silicone temperature (fluid supplier; DMP-009)."),
        F("Damping to optimum, minimum", "damping_ratio_min", "ratio", check=">0",
          required=False, valid=R(1e-3, 100), usual=R(0.2, 5),
          note="Lowest acceptable c / c_opt of the viscous damper (DMP-010 needs minimum and"
               " maximum)."),
        F("Damping to optimum, maximum", "damping_ratio_max", "ratio", check=">0",
          required=False, valid=R(1e-3, 100), usual=R(0.2, 5),
          note="Highest acceptable c / c_opt of the viscous damper."),
    ),
)

DAMPER_RUBBER = Sheet(
    "DamperRubber",
    "table",
    max_rows=200,
    note="Damper rubber against temperature (supplier data): storage shear modulus and loss"
         " factor, evaluated at the rubber's own temperature at the ends of the operating"
         " temperature range (sheet Damper). Blank table = one value (TVModel stiffness,"
         " Damper loss factor).",
    fields=(
        F("temperature", "temperature", "temperature",
          valid=R(-150, 400, "°C"), usual=R(-60, 200, "°C")),
        F("storage shear modulus", "storage_modulus", "stress", check=">0",
          valid=R(1e-3, 1e5, "MPa"), usual=R(0.1, 100, "MPa")),
        F("loss factor", "loss_factor", "ratio", check=">=0",
          valid=R(0, 10), usual=R(0.01, 2)),
    ),
)

FATIGUE = Sheet(
    "Fatigue",
    "parameters",
    note="Classical stress inputs: web, fillet, oil-hole geometry and material strengths.",
    fields=(
        F("Web reduced thickness", "web_thickness", "length", check=">0", required=False,
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Web full thickness", "web_full_thickness", "length", check=">0", required=False,
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Web minimum width", "web_min_width", "length", check=">0", required=False,
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Web maximum width", "web_max_width", "length", check=">0", required=False,
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Web offset", "web_offset", "length", required=False,
          valid=R(-5000, 5000, "mm"), usual=R(-1000, 1000, "mm")),
        F("Crank pin fillet radius", "pin_fillet_radius", "length", check=">0", required=False,
          valid=R(0.05, 1000, "mm"), usual=R(0.5, 100, "mm")),
        F("Crank pin fillet undercut", "pin_fillet_undercut", "length", check=">=0",
          required=False,
          valid=R(0, 1000, "mm"), usual=R(0, 20, "mm")),
        F("Crank pin fillet web undercut", "pin_fillet_web_undercut", "length", check=">=0",
          required=False,
          valid=R(0, 1000, "mm"), usual=R(0, 20, "mm")),
        F("Main journal fillet radius", "main_fillet_radius", "length", check=">0",
          required=False,
          valid=R(0.05, 1000, "mm"), usual=R(0.5, 100, "mm")),
        F("Main journal fillet undercut", "main_fillet_undercut", "length", check=">=0",
          required=False,
          valid=R(0, 1000, "mm"), usual=R(0, 20, "mm")),
        F("Main journal web undercut", "main_fillet_web_undercut", "length", check=">=0",
          required=False,
          valid=R(0, 1000, "mm"), usual=R(0, 20, "mm")),
        F("Pin journal oil hole diameter", "pin_oil_hole_diameter", "length", check=">0",
          required=False,
          valid=R(0.1, 1000, "mm"), usual=R(1, 100, "mm")),
        F("Pin journal oil hole height", "pin_oil_hole_height", "length", required=False,
          note="Height of the hole's mouth on the pin surface above the throw plane (the"
               " plane through the crank axis and the pin axis), measured at right angles to"
               " it, positive on the leading side: r_pin sin(phi), phi the Bearings 'oil hole"
               " angle' from the pin's outermost point. For the drawing record: the checks"
               " take the hole's position from that angle, not from this height.",
          valid=R(-5000, 5000, "mm"), usual=R(-1000, 1000, "mm")),
        F("Main journal oil hole diameter", "main_oil_hole_diameter", "length", check=">0",
          required=False,
          valid=R(0.1, 1000, "mm"), usual=R(1, 100, "mm")),
        F("Main journal oil hole height", "main_oil_hole_height", "length", required=False,
          note="Height of the hole's mouth on the main journal surface above the throw plane"
               " (the plane through the crank axis and the pin axis), measured at right angles"
               " to it: r_main sin(angle of the hole from that plane). For the drawing record:"
               " the main oil-hole check (torsion only) does not use it.",
          valid=R(-5000, 5000, "mm"), usual=R(-1000, 1000, "mm")),
        F("Pin journal land diameter", "pin_land_diameter", "length", check=">0", required=False,
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Pin journal land thickness", "pin_land_thickness", "length", check=">=0",
          required=False,
          valid=R(0, 1000, "mm"), usual=R(0, 200, "mm")),
        F("Main journal land diameter", "main_land_diameter", "length", check=">0",
          required=False,
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Main journal land thickness", "main_land_thickness", "length", check=">=0",
          required=False,
          valid=R(0, 1000, "mm"), usual=R(0, 200, "mm")),
        F("Pin bore diameter", "pin_bore", "length", check=">=0", required=False,
          valid=R(0, 5000, "mm"), usual=R(0, 1000, "mm")),
        F("Main journal bore diameter", "main_bore", "length", check=">=0", required=False,
          valid=R(0, 5000, "mm"), usual=R(0, 1000, "mm")),
        F("Base material UTS", "uts", "stress", check=">0", required=False,
          note="Valid up to 3000 MPa: the IACS UR M53 fatigue-strength fit turns negative"
               " above about 3400 MPa.",
          valid=R(1, 3000, "MPa"), usual=R(300, 2000, "MPa")),
        F("Fillet UTS", "fillet_uts", "stress", check=">0", required=False,
          valid=R(1, 3000, "MPa"), usual=R(300, 2000, "MPa")),
        F("Base tensile yield strength", "yield_strength", "stress", check=">0", required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Base compressive yield strength", "compressive_yield", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Base infinite life fatigue strength", "fatigue_strength", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Base hydrostatic fatigue strength", "hydrostatic_fatigue_strength", "stress",
          check=">0", required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Base torsional fatigue strength", "torsional_fatigue_strength", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Fillet tensile and compressive yield", "fillet_yield", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Pin fillet fatigue strength", "pin_fillet_fatigue", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Pin oil hole fatigue strength", "pin_oil_hole_fatigue", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Main fillet fatigue strength", "main_fillet_fatigue", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Main oil hole fatigue strength", "main_oil_hole_fatigue", "stress", check=">0",
          required=False,
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Pin fillet stress concentration bending", "scf_pin_bending", "ratio", check=">=1",
          required=False, note="Leave blank to use the IACS UR M53 empirical formula.",
          valid=R(1, 100), usual=R(1, 10)),
        F("Pin fillet stress concentration torsion", "scf_pin_torsion", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Main fillet stress concentration bending", "scf_main_bending", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Main fillet stress concentration torsion", "scf_main_torsion", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Oil hole stress concentration bending", "scf_oil_bending", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Oil hole stress concentration torsion", "scf_oil_torsion", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Crank nose diameter", "nose_diameter", "length", check=">0", required=False,
          note="Smallest nose section at the critical fillet (crank-nose check, FAT-003).",
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Crank nose bore diameter", "nose_bore", "length", check=">=0", required=False,
          valid=R(0, 5000, "mm"), usual=R(0, 1000, "mm")),
        F("Crank nose stress concentration bending", "scf_nose_bending", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Crank nose stress concentration torsion", "scf_nose_torsion", "ratio", check=">=1",
          required=False,
          valid=R(1, 100), usual=R(1, 10)),
        F("Crank nose fatigue strength", "nose_fatigue", "stress", check=">0", required=False,
          note="Fully reversed fatigue strength at the nose fillet (with its treatment).",
          valid=R(1, 20000, "MPa"), usual=R(20, 3000, "MPa")),
        F("Belt load on crank nose", "belt_load", "force", check=">=0", required=False,
          note="Resultant FEAD + timing drive belt/chain pull on the nose (blank = none"
               " given: torsion only, stated in the report).",
          valid=R(0, 1e5, "kN"), usual=R(0, 200, "kN")),
        F("Belt load overhang", "belt_overhang", "length", check=">=0", required=False,
          note="Axial distance from the belt load line to the critical nose section.",
          valid=R(0, 10000, "mm"), usual=R(0, 1000, "mm")),
    ),
)

CYLINDERS = Sheet(
    "Cylinders",
    "table",
    max_rows=64,
    key="cylinder",
    note="One row per cylinder: crank throw angle, firing angle, bank angle, crank pin.",
    fields=(
        F("cylinder", "cylinder", "int", check=">0",
          valid=R(1, 64)),
        F("throw angle", "throw_angle", "angle",
          note="Angle of the crank throw from throw 1, in the direction of rotation.",
          valid=R(-720, 720, "deg")),
        F("firing angle", "firing_angle", "angle",
          note="Crank angle after cylinder 1 fires at which this cylinder fires (0..720 deg).",
          valid=R(0, 720, "deg")),
        F("bank angle", "bank_angle", "angle", required=False,
          note="Cylinder axis angle from vertical (V engines); blank = 0.",
          valid=R(-360, 360, "deg"), usual=R(-180, 180, "deg")),
        F("crank pin", "pin", "int", check=">0", required=False,
          note="Crank pin (throw) carrying this cylinder's rod; blank = cylinder number.",
          valid=R(1, 64)),
    ),
)

PEAK_PRESSURE = Sheet(
    "PeakPressure",
    "table",
    max_rows=2000,
    note="Peak cylinder pressure per speed and load case (full, part, no load).",
    fields=(
        F("load case", "case", "choice", choices=("full", "part", "no"),
          aliases=_CASE_ALIASES),
        F("speed", "speed", "speed", check=">0",
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("peak pressure", "peak_pressure", "pressure", check=">0",
          valid=R(0.05, 5000, "bar"), usual=R(2, 350, "bar")),
    ),
)

PRESSURE_TRACES = Sheet(
    "PressureTraces",
    "table",
    max_rows=500000,
    note="Optional measured/simulated traces: crank angle vs absolute cylinder pressure, one"
         " trace per load case and speed, crank angle from firing TDC of that cylinder"
         " (-360..360 or 0..720 deg), one 720 deg cycle with at least 8 points and at most"
         " 10 deg between neighbouring points (including the wrap-around from the last point"
         " to the first).",
    fields=(
        F("load case", "case", "choice", choices=("full", "part", "no"),
          aliases=_CASE_ALIASES),
        F("speed", "speed", "speed", check=">0",
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("crank angle", "crank_angle", "angle",
          valid=R(-720, 720, "deg")),
        F("pressure", "pressure", "pressure", check=">0",
          valid=R(0.001, 5000, "bar"), usual=R(0.05, 350, "bar")),
    ),
)

BRAKE_TORQUE = Sheet(
    "BrakeTorque",
    "table",
    # a logged dyno curve is normal input: only interpolated (linear in the rows), so no
    # limit beyond Excel's own; more than dense_rows rows is a warning
    dense_rows=2000,
    note="Full-load brake torque vs speed (mean torque for stress and joints); a dense"
         " measured curve (thousands of rows) is accepted and interpolated.",
    fields=(
        F("speed", "speed", "speed", check=">0",
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("brake torque", "brake_torque", "torque",
          valid=R(-1e9, 1e9, "N m"), usual=R(0, 1e7, "N m")),
    ),
)

BEARINGS = Sheet(
    "Bearings",
    "table",
    max_rows=500,
    key="name",
    note="One row per bearing: mains M1..M(n+1) front to rear, big ends BE1..BEn.",
    fields=(
        F("name", "name", "text"),
        F("type", "type", "choice", choices=("main", "big end"),
          aliases=(("main bearing", "main"), ("big end bearing", "big end"),
                   ("con rod", "big end"), ("conrod", "big end"), ("rod", "big end"))),
        F("journal diameter", "diameter", "length", check=">0", required=False,
          note="Required unless sheet Crank gives it (main journal or pin diameter).",
          valid=R(1, 10000, "mm"), usual=R(15, 1500, "mm")),
        F("journal length", "journal_length", "length", check=">0", required=False,
          note="Journal length between the webs (fillet geometry); a crank pin carrying two"
               " rods (V engine): the whole pin.",
          valid=R(0.1, 5000, "mm"), usual=R(3, 1000, "mm")),
        F("effective length", "length", "length", check=">0",
          note="Shell land length carrying load (excluding chamfers and grooves).",
          valid=R(0.1, 5000, "mm"), usual=R(3, 1000, "mm")),
        F("radial clearance", "clearance", "length", check=">0",
          note="Mean cold radial clearance.",
          valid=R(0.1, 10000, "um"), usual=R(3, 1000, "um")),
        F("groove", "groove", "choice", choices=("none", "partial", "full"), required=False,
          aliases=(("no", "none"), ("ungrooved", "none"), ("half", "partial"),
                   ("partial groove", "partial"), ("full groove", "full"),
                   ("circumferential", "full"), ("fully grooved", "full"))),
        F("groove width", "groove_width", "length", check=">=0", required=False,
          valid=R(0, 5000, "mm"), usual=R(0, 100, "mm")),
        F("groove start", "groove_start", "angle", required=False,
          valid=R(-720, 720, "deg")),
        F("groove end", "groove_end", "angle", required=False,
          valid=R(-720, 720, "deg")),
        F("oil feed", "oil_feed", "text", required=False),
        F("oil holes", "oil_holes", "int", check=">=0", required=False,
          valid=R(0, 64), usual=R(0, 8)),
        F("oil hole type", "oil_hole_type", "text", required=False),
        F("oil hole diameter", "oil_hole_diameter", "length", check=">0", required=False,
          valid=R(0.1, 1000, "mm"), usual=R(1, 50, "mm")),
        F("oil hole angle", "oil_hole_angle", "angle", required=False,
          valid=R(-720, 720, "deg")),
        F("max film temperature", "max_film_temperature", "temperature", required=False,
          note="Supplier's limit of the effective film temperature for this shell (rule"
               " BRG-007). Blank: not judged.",
          valid=R(0, 400, "°C"), usual=R(80, 250, "°C")),
        F("max film pressure", "max_film_pressure", "stress", check=">0", required=False,
          note="Supplier's limit of the peak oil-film pressure for this lining (rule BRG-008)."
               " Blank: not judged.",
          valid=R(1, 5000, "MPa"), usual=R(20, 1000, "MPa")),
        F("min oil flow", "min_oil_flow", "volume_flow", check=">0", required=False,
          note="Supplier's minimum oil flow through this bearing (rule BRG-009). Blank: not"
               " judged.",
          valid=R(1e-4, 1000, "l/min"), usual=R(0.01, 50, "l/min")),
        F("support stiffness", "support_stiffness", "linear_stiffness", check=">0",
          required=False,
          note="Main bearings, continuous beam on elastic supports: this main's radial support"
               " stiffness (wins over the Engine sheet's). Blank: the Engine sheet's value.",
          valid=R(1e3, 1e10, "N/mm"), usual=R(1e4, 1e7, "N/mm")),
        F("support offset", "support_offset", "length", required=False,
          note="Main bearings, continuous beam: offset of this main's bore centre from the"
               " line of the others (misalignment), along the cylinder axis of an in-line"
               " engine (block y), + towards the head. Blank: 0.",
          valid=R(-5, 5, "mm"), usual=R(-0.2, 0.2, "mm")),
        F("lining", "lining", "choice", required=False, choices=LININGS,
          aliases=_LINING_ALIASES,
          note="Lining material; selects the specific-load and film-thickness limits (AS15/AS16"
               " are aluminium-tin bimetal linings). Blank: those rules are not evaluated."),
    ),
)

CRANK_MASS = Sheet(
    "CrankMass",
    "table",
    max_rows=10000,
    key="location",
    note="Crankshaft mass properties per web, counterweight and crank pin (crank frame).",
    fields=(
        F("location", "location", "text"),
        F("throw", "throw", "int", check=">0", note="Crank throw (bay) the mass belongs to.",
          valid=R(1, 64)),
        F("kind", "kind", "choice", choices=("web", "counterweight", "pin"),
          aliases=(("c/w", "counterweight"), ("cw", "counterweight"),
                   ("crank pin", "pin"), ("crankpin", "pin"), ("crank web", "web"))),
        F("mass", "mass", "mass", check=">=0",
          valid=R(0, 1e6, "kg"), usual=R(0, 20000, "kg")),
        F("X", "x", "length",
          note="Axial offset of the centre of mass from the component's reference plane"
               " (convention of Bell, Ricardo 2013: mirrored webs have opposite signs).",
          valid=R(-20000, 20000, "mm"), usual=R(-3000, 3000, "mm")),
        F("Y", "y", "length",
          note="Radial position in the crank frame, along throw 1 (throw 1 pin at +Y; for a V"
               " engine throw 1 is the pin of cylinder 1, not the vertical).",
          valid=R(-20000, 20000, "mm"), usual=R(-3000, 3000, "mm")),
        F("Z", "z", "length", required=False,
          note="Lateral position in the crank frame, +90 deg from Y in the direction of"
               " rotation; blank = 0.",
          valid=R(-20000, 20000, "mm"), usual=R(-3000, 3000, "mm")),
        F("axial position", "axial", "length", check=">=0",
          note="Axial position of the component's reference plane from the bay's front main"
               " bearing centre (the centre of mass is at axial position + X).",
          valid=R(0, 20000, "mm"), usual=R(0, 3000, "mm")),
        F("relative to", "reference", "choice", choices=("main axis", "pin axis"),
          aliases=(("main", "main axis"), ("crank axis", "main axis"), ("pin", "pin axis"),
                   ("crank pin axis", "pin axis"))),
    ),
)

def _len(label: str, attr: str, note: str, check: str = ">0", lo: float = 0.1,
         hi: float = 10000, ulo: float = 1, uhi: float = 2000) -> Field:
    """An optional length column of sheet Crank (mm ranges)."""
    vlo = 0 if check == ">=0" else lo
    return F(label, attr, "length", check=check, required=False, note=note,
             valid=R(vlo, hi, "mm"), usual=R(0 if check == ">=0" else ulo, uhi, "mm"))


CRANK = Sheet(
    "Crank",
    "table",
    max_rows=65,
    key="throw",
    note="Crankshaft geometry, one source for every analysis (docs/crank-geometry.md): a row"
         " 'all' for what every throw shares, and a row per throw number only for what differs"
         " on that throw (its blank cells take the 'all' row's value); or one row per throw."
         " Crank axis z, main axis at x = y = 0, pin axis at (0, stroke/2); a throw runs"
         " between the mid-planes of its two main journals: half journal, web, pin, web, half"
         " journal.",
    fields=(
        F("throw", "throw", "text",
          note="'all' (every throw), or a throw (crank pin) number 1..n front to rear."),
        _len("main journal diameter", "journal_diameter", "Main journal diameter Dj; also"
             " the main bearings' journal diameter (sheet Bearings).", ulo=15, uhi=1500),
        _len("main journal bore", "journal_bore", "Concentric bore through the journal's"
             " length only; blank = solid.", check=">=0", uhi=1000),
        _len("main journal length", "journal_length", "Main journal length Lj between the"
             " webs (half of it belongs to each neighbouring throw); also the main bearings'"
             " journal length.", ulo=3, uhi=1000),
        _len("pin diameter", "pin_diameter", "Crank pin diameter Dp; also the big-end"
             " bearings' journal diameter.", ulo=15, uhi=1500),
        _len("pin bore", "pin_bore", "Concentric bore through the pin's length only (about"
             " the pin axis); blank = solid.", check=">=0", uhi=1000),
        _len("pin length", "pin_length", "Crank pin length Lp between the webs (the whole pin"
             " when it carries two rods); also the big-end bearings' journal length.",
             ulo=3, uhi=1000),
        _len("web thickness", "web_thickness", "Web thickness tw along the crank axis (full"
             " thickness; also the Fatigue sheet's 'Web full thickness').", uhi=1000),
        _len("web width at journal", "web_width_journal", "Diameter Bj of the web outline's"
             " circle about the main axis: the web outline is the convex hull of this circle"
             " and the one about the pin axis.", uhi=3000),
        _len("web width at pin", "web_width_pin", "Diameter Bp of the web outline's circle"
             " about the pin axis.", uhi=3000),
        _len("counterweight inner radius", "cw_inner_radius", "Counterweight: an annular"
             " sector about the main axis opposite the pin, fused with its web (each web of"
             " the throw); blank with the other counterweight cells = no counterweight.",
             check=">=0", uhi=3000),
        _len("counterweight outer radius", "cw_outer_radius", "Outer radius of the"
             " counterweight sector.", uhi=3000),
        F("counterweight angle", "cw_angle", "angle", check=">=0", required=False,
          note="Included angle of the counterweight sector, bisected by the direction"
               " opposite the pin; 0 on a throw's row: that throw has no counterweight.",
          valid=R(0, 360, "deg"), usual=R(0, 270, "deg")),
        _len("counterweight thickness", "cw_thickness", "Axial thickness of the counterweight,"
             " centred on its web's mid-plane; blank = the web thickness.", uhi=1000),
        _len("pin fillet radius", "pin_fillet_radius", "Also the Fatigue sheet's 'Crank pin"
             " fillet radius' (not part of the mass and stiffness solid).", lo=0.05,
             uhi=100, ulo=0.5),
        _len("pin fillet undercut", "pin_fillet_undercut", "Fatigue 'Crank pin fillet"
             " undercut'.", check=">=0", uhi=20),
        _len("pin fillet web undercut", "pin_fillet_web_undercut", "Fatigue 'Crank pin fillet"
             " web undercut'.", check=">=0", uhi=20),
        _len("main fillet radius", "main_fillet_radius", "Fatigue 'Main journal fillet"
             " radius'.", lo=0.05, uhi=100, ulo=0.5),
        _len("main fillet undercut", "main_fillet_undercut", "Fatigue 'Main journal fillet"
             " undercut'.", check=">=0", uhi=20),
        _len("main fillet web undercut", "main_fillet_web_undercut", "Fatigue 'Main journal"
             " web undercut'.", check=">=0", uhi=20),
        _len("pin oil hole diameter", "pin_oil_hole_diameter", "Fatigue 'Pin journal oil hole"
             " diameter' and the big-end bearings' oil hole diameter.", uhi=50),
        _len("main oil hole diameter", "main_oil_hole_diameter", "Fatigue 'Main journal oil"
             " hole diameter'.", uhi=50),
        F("density", "density", "density", check=">0", required=False,
          note="Crank material (one for the whole crank).",
          valid=R(500, 25000, "kg/m^3"), usual=R(6500, 8500, "kg/m^3")),
        F("Young's modulus", "youngs_modulus", "stress", check=">0", required=False,
          note="Crank material.", valid=R(1, 1e6, "GPa"), usual=R(100, 250, "GPa")),
        F("Poisson's ratio", "poisson_ratio", "ratio", check=">=0", required=False,
          note="Crank material.", valid=R(0, 0.49), usual=R(0.2, 0.35)),
    ),
)

CRANK_ENDS = Sheet(
    "CrankEnds",
    "parameters",
    note="The crank's ends (crank nose, flywheel flange) and the unbalances mounted on them"
         " (pulley or damper hub, flywheel), with sheet Crank.",
    fields=(
        F("Crank nose diameter", "nose_diameter", "length", check=">0", required=False,
          note="Plain-shaft diameter of the crank nose between the damper hub and the first"
               " main journal (its torsional stiffness; the Fatigue sheet's 'Crank nose"
               " diameter' is the smallest section at the critical fillet).",
          valid=R(0.1, 10000, "mm"), usual=R(1, 1000, "mm")),
        F("Crank nose bore", "nose_bore", "length", check=">=0", required=False,
          valid=R(0, 5000, "mm"), usual=R(0, 1000, "mm")),
        F("Crank nose length", "nose_length", "length", check=">0", required=False,
          note="From the damper hub's mid-plane to the first main journal's mid-plane"
               " (the twisted length; torsional stiffness G Jp / L with the half journal).",
          valid=R(0.1, 10000, "mm"), usual=R(1, 2000, "mm")),
        F("Flywheel flange diameter", "flange_diameter", "length", check=">0",
          required=False, note="Plain-shaft diameter between the last main journal and the"
                               " flywheel face.",
          valid=R(0.1, 10000, "mm"), usual=R(1, 2000, "mm")),
        F("Flywheel flange bore", "flange_bore", "length", check=">=0", required=False,
          valid=R(0, 5000, "mm"), usual=R(0, 1000, "mm")),
        F("Flywheel flange length", "flange_length", "length", check=">0", required=False,
          note="From the last main journal's mid-plane to the flywheel's mid-plane.",
          valid=R(0.1, 10000, "mm"), usual=R(1, 2000, "mm")),
        F("Pulley unbalance", "pulley_unbalance", "unbalance", check=">=0", required=False,
          note="Unbalance (mass x radius) on the pulley or damper hub, e.g. to balance a"
               " first-order couple without a balance shaft (Ford 1.0 three-cylinder).",
          valid=R(0, 1e9, "g mm"), usual=R(0, 1e7, "g mm")),
        F("Pulley unbalance angle", "pulley_angle", "angle", required=False,
          note="Direction of the pulley unbalance from throw 1, in the direction of rotation.",
          valid=R(-720, 720, "deg")),
        F("Pulley unbalance distance", "pulley_distance", "length", check=">=0",
          required=False, note="Axial distance of the pulley unbalance ahead of (in front of)"
                               " the first main journal's mid-plane.",
          valid=R(0, 20000, "mm"), usual=R(0, 3000, "mm")),
        F("Flywheel unbalance", "flywheel_unbalance", "unbalance", check=">=0",
          required=False, note="Unbalance (mass x radius) on the flywheel.",
          valid=R(0, 1e9, "g mm"), usual=R(0, 1e7, "g mm")),
        F("Flywheel unbalance angle", "flywheel_angle", "angle", required=False,
          note="Direction of the flywheel unbalance from throw 1, in the direction of"
               " rotation.", valid=R(-720, 720, "deg")),
        F("Flywheel unbalance distance", "flywheel_distance", "length", check=">=0",
          required=False, note="Axial distance of the flywheel unbalance behind the last main"
                               " journal's mid-plane.",
          valid=R(0, 20000, "mm"), usual=R(0, 3000, "mm")),
    ),
)

TV_MODEL = Sheet(
    "TVModel",
    "table",
    max_rows=1000,
    key="station",
    note="Torsional lumped-mass chain from front (damper) to rear (flywheel).",
    fields=(
        F("station", "station", "text"),
        F("role", "role", "choice",
          choices=("damper ring", "crank nose", "cylinder", "flywheel", "generator",
                   "propeller", "other"),
          aliases=(("ring", "damper ring"), ("damper inertia ring", "damper ring"),
                   ("nose", "crank nose"), ("cyl", "cylinder"),
                   ("generator rotor", "generator"), ("alternator", "generator"),
                   ("prop", "propeller")),
          note="A 'propeller' station's inertia is the propeller's in air: the entrained"
               " water (sheet Driven) is added to it; a 'generator' station is the generator"
               " rotor."),
        F("cylinder", "cylinder", "int_list", check=">0", required=False,
          note="Cylinder(s) whose gas and inertia torque acts on this station: one number, or"
               " several separated by commas, e.g. '1, 2' for the two cylinders of a V-engine"
               " crank pin (the usual V model: one station per throw). Each cylinder on one"
               " station only.",
          valid=R(1, 64)),
        F("inertia", "inertia", "inertia", check=">0", required=False,
          note="Polar moment of inertia of the station about the crank axis, used as given:"
               " nothing is added. At a cylinder station it includes the con-rod and piston"
               " shares of its cylinder(s) (Bell 2013 practice): the throw's own inertia + the"
               " rod's rotating share m_rot r^2 + the mean inertia of the reciprocating masses"
               " (piston assembly + the rod's reciprocating share) 1/2 m_rec r^2 (r = crank"
               " radius). Their variable inertia torque is in the excitation, from the Engine"
               " sheet's masses. Required, except on a cylinder station when sheet Crank is"
               " given (then derived from the crank's geometry and the rod and piston masses;"
               " a typed value wins).",
          valid=R(1e-9, 1e7, "kg m^2"), usual=R(1e-5, 1e6, "kg m^2")),
        F("absolute damping", "absolute_damping", "torsional_damping", check=">=0",
          required=False,
          valid=R(0, 1e9, "N m s/rad"), usual=R(0, 1e6, "N m s/rad")),
        F("stiffness to next", "stiffness", "torsional_stiffness", check=">0", required=False,
          valid=R(1, 1e13, "N m/rad"), usual=R(1e3, 1e11, "N m/rad")),
        F("damping to next", "relative_damping", "torsional_damping", check=">=0",
          required=False,
          valid=R(0, 1e9, "N m s/rad"), usual=R(0, 1e6, "N m s/rad")),
        F("element to next", "element", "choice", choices=("shaft", "flexible coupling"),
          required=False,
          aliases=(("coupling", "flexible coupling"), ("elastic coupling", "flexible coupling"),
                   ("rubber coupling", "flexible coupling"), ("highly flexible coupling",
                                                              "flexible coupling")),
          note="What joins the station to the next: shaft (blank) with the row's stiffness"
               " and damping; flexible coupling: the maker's catalogue values of sheet"
               " Coupling (dynamic torsional stiffness and relative damping at the rubber's"
               " temperature), the row's 'stiffness to next' and 'damping to next' left"
               " blank."),
    ),
)

COUPLING = Sheet(
    "Coupling",
    "parameters",
    note="Flexible (elastic) coupling between engine and driven machine (the TVModel element"
         " whose 'element to next' is 'flexible coupling'): the maker's catalogue values in"
         " the conventions of DIN 740-2, and the rubber's temperature.",
    fields=(
        F("Coupling designation", "designation", "text", required=False,
          note="Maker, series and size, e.g. from the catalogue."),
        F("Nominal torque T_KN", "nominal_torque", "torque", check=">0", required=False,
          note="Torque the coupling transmits continuously (CPL-003).",
          valid=R(0.01, 1e9, "N m"), usual=R(10, 1e8, "N m")),
        F("Permissible vibratory torque T_KW", "vibratory_torque", "torque", check=">0",
          required=False,
          note="Amplitude of periodic torque the coupling takes continuously at 10 Hz and the"
               " catalogue's reference temperature (CPL-001, MIS-003).",
          valid=R(0.001, 1e9, "N m"), usual=R(1, 1e8, "N m")),
        F("Permissible damping power P_KV", "damping_power", "power", check=">0",
          required=False,
          note="Heat the coupling dissipates continuously at the catalogue's reference"
               " (ambient) temperature (CPL-002, MIS-004).",
          valid=R(0.001, 1e8, "W"), usual=R(1, 1e6, "W")),
        F("Dynamic torsional stiffness C_Tdyn", "stiffness", "torsional_stiffness",
          check=">0", required=False,
          note="Catalogue value at its reference state (load, amplitude, frequency,"
               " temperature); the factors of sheet CouplingTemperature move it to the"
               " rubber's temperature.",
          valid=R(1, 1e12, "N m/rad"), usual=R(100, 1e10, "N m/rad")),
        F("Relative damping psi", "relative_damping", "ratio", check=">=0", required=False,
          note="Damping work of a cycle over the elastic work, psi = 2 pi x loss factor"
               " (DIN 740-2); rubber couplings about 0.5 to 1.5.",
          valid=R(0, 20), usual=R(0.1, 3)),
        F("Rubber temperature", "temperature", "temperature", required=False,
          note="Temperature of the coupling's rubber in operation: reads the factors of"
               " sheet CouplingTemperature (blank: the catalogue's reference state).",
          valid=R(-100, 300, "°C"), usual=R(-40, 150, "°C")),
    ),
)

COUPLING_TEMPERATURE = Sheet(
    "CouplingTemperature",
    "table",
    max_rows=200,
    note="Flexible coupling against the rubber's temperature (maker's catalogue): factors on"
         " the dynamic torsional stiffness and on the relative damping, and the temperature"
         " factor S_t (>= 1) on the load compared with T_KW and P_KV; linear between rows,"
         " held beyond them. Blank table = factors 1.",
    fields=(
        F("temperature", "temperature", "temperature",
          valid=R(-150, 400, "°C"), usual=R(-60, 200, "°C")),
        F("stiffness factor", "stiffness_factor", "ratio", check=">0",
          valid=R(1e-3, 100), usual=R(0.2, 5)),
        F("damping factor", "damping_factor", "ratio", check=">0",
          valid=R(1e-3, 100), usual=R(0.2, 5)),
        F("temperature factor", "temperature_factor", "ratio", check=">0",
          note="S_t of DIN 740-2: the vibratory torque and the damping power are multiplied"
               " by it before the comparison with T_KW and P_KV.",
          valid=R(1e-3, 100), usual=R(1, 5)),
    ),
)

DRIVEN = Sheet(
    "Driven",
    "parameters",
    note="The driven machine: a generator (constant speed) or a propeller (torque following"
         " the propeller law), its inertia and damping in the torsional model.",
    fields=(
        F("Driven machine", "machine", "choice", choices=("generator", "propeller", "other"),
          required=False,
          aliases=(("alternator", "generator"), ("genset", "generator"),
                   ("fixed pitch propeller", "propeller"), ("fpp", "propeller"))),
        F("Propeller entrained water", "entrained_water", "ratio", check=">=0",
          required=False,
          note="Inertia of the water the propeller carries along, as a fraction of its dry"
               " inertia (TVModel station with role 'propeller'): the station's inertia in"
               " water is dry x (1 + fraction); typically 0.2 to 0.3.",
          valid=R(0, 5), usual=R(0.05, 0.6)),
        F("Propeller torque at rated speed", "propeller_torque", "torque", check=">0",
          required=False,
          note="Torque the propeller absorbs at the Engine sheet's rated speed; with the"
               " propeller law Q = Q_r (n/n_r)^2 it gives the propeller's damping"
               " c = dQ/domega = 2 Q/omega at every speed (blank: no propeller damping).",
          valid=R(0.01, 1e10, "N m"), usual=R(10, 1e9, "N m")),
    ),
)

JOINTS = Sheet(
    "Joints",
    "table",
    max_rows=100,
    key="name",
    note="Bolted joints at the crank nose and flywheel (any number).",
    fields=(
        F("name", "name", "text"),
        F("location", "location", "choice", choices=("crank nose", "flywheel", "other"),
          aliases=(("nose", "crank nose"), ("front end", "crank nose"))),
        F("bolts", "bolts", "int", check=">0",
          valid=R(1, 200), usual=R(1, 32)),
        F("nominal diameter", "diameter", "length", check=">0",
          valid=R(1, 1000, "mm"), usual=R(4, 100, "mm")),
        F("thread pitch", "pitch", "length", check=">0",
          valid=R(0.05, 50, "mm"), usual=R(0.35, 8, "mm")),
        F("stress area coefficient", "stress_area_coefficient", "ratio", check=">0",
          required=False,
          note="A_s = pi/4 (d - c p)^2; blank = 0.9382 (ISO 898-1).",
          valid=R(0.01, 10), usual=R(0.5, 1.5)),
        F("property class", "property_class", "choice",
          choices=("8.8", "9.8", "10.9", "11.9", "12.9")),
        F("tightening", "tightening", "choice",
          choices=("torque", "torque wrench", "yield controlled", "angle controlled"),
          aliases=(("yield", "yield controlled"), ("angle", "angle controlled"),
                   ("torque angle", "angle controlled"), ("torque controlled", "torque"),
                   ("wrench", "torque wrench"))),
        F("tightening torque", "tightening_torque", "torque", check=">0", required=False,
          valid=R(0.001, 1e8, "N m"), usual=R(1, 1e5, "N m")),
        F("nut factor", "nut_factor", "ratio", check=">0", required=False,
          note="F = T/(K d); blank = 0.2 (Bell, Ricardo 2013).",
          valid=R(0.01, 2), usual=R(0.08, 0.4)),
        F("preload fraction", "preload_fraction", "ratio", check="0..1", required=False,
          note="Fraction of the reference stress for method-based preload; blank = the table"
               " of Bell, Ricardo 2013, 'Crankshaft analysis (24)'.",
          valid=R(0, 1), usual=R(0.3, 1)),
        F("proof stress Rp0.2", "rp02", "stress", check=">0", required=False,
          note="Blank = ISO 898-1 minimum for the property class.",
          valid=R(1, 20000, "MPa"), usual=R(200, 2000, "MPa")),
        F("proof load stress", "proof_load_stress", "stress", check=">0", required=False,
          note="Blank = ISO 898-1 stress under proof load for the property class.",
          valid=R(1, 20000, "MPa"), usual=R(200, 2000, "MPa")),
        F("head bearing outer diameter", "head_outer", "length", check=">0", required=False,
          valid=R(1, 2000, "mm"), usual=R(3, 300, "mm")),
        F("head bearing inner diameter", "head_inner", "length", check=">0", required=False,
          valid=R(1, 2000, "mm"), usual=R(3, 300, "mm")),
        F("clamped material", "clamped_material", "choice", required=False,
          choices=CLAMPED_MATERIALS, aliases=_CLAMPED_ALIASES,
          ambiguous=(("cast iron", ("grey cast iron", "nodular cast iron")),
                     ("iron", ("grey cast iron", "nodular cast iron"))),
          note="Material under the bolt head; selects the head contact-pressure limit. 'cast"
               " iron' alone is refused: say grey or nodular (their limits differ)."),
        F("face outer diameter", "face_outer", "length", check=">0",
          valid=R(1, 10000, "mm"), usual=R(10, 3000, "mm")),
        F("face inner diameter", "face_inner", "length", check=">=0",
          valid=R(0, 10000, "mm"), usual=R(0, 3000, "mm")),
        F("friction coefficient", "friction", "ratio", check=">0", required=False,
          note="Blank = 0.2 (Bell, Ricardo 2013).",
          valid=R(0.001, 2), usual=R(0.05, 0.6)),
    ),
)

JOINT_TORQUES = Sheet(
    "JointTorques",
    "table",
    max_rows=300,
    note="Peak applied torque per joint and operating point (blank table = from TV module).",
    fields=(
        F("joint", "joint", "text"),
        F("operating point", "point", "choice", choices=("tv peak", "max power", "overspeed"),
          aliases=(("tv", "tv peak"), ("torsional peak", "tv peak"), ("maximum power", "max power"),
                   ("max. power", "max power"), ("rated power", "max power"))),
        F("speed", "speed", "speed", check=">0", required=False,
          valid=R(1, 100000, "rpm"), usual=R(30, 20000, "rpm")),
        F("applied torque", "torque", "torque", check=">0",
          valid=R(0.001, 1e9, "N m"), usual=R(1, 1e7, "N m")),
    ),
)

RULE_OVERRIDES = Sheet(
    "RuleOverrides",
    "table",
    max_rows=1000,
    key="rule",
    note="Project-specific limits replacing the rule table's defaults (each listed in the report).",
    fields=(
        F("rule", "rule", "text"),
        F("limit", "limit", "text", note="A number, a range 'low..high', or 'not applicable'"
          " (the rule does not apply to the project; the reason says why)."),
        F("unit", "unit", "text", required=False),
        F("reason", "reason", "text"),
    ),
)

TOLERANCES = Sheet(
    "Tolerances",
    "table",
    max_rows=200,
    note="Tolerance ranges of inputs (production, operating, tightening scatter): each result is"
         " also judged at its worst corner (checker check --corners). Blank table = nominal only.",
    fields=(
        F("sheet", "sheet", "text", note="Sheet of the input, e.g. Bearings, Oil, Joints."),
        F("row", "row", "text", required=False,
          note="Row key (M1, crank nose), several keys separated by commas, 'all', or"
               " 'column = value' (type = main); blank on parameter sheets."),
        F("column", "column", "text",
          note="Column (table sheet) or parameter name; on Joints also 'tightening factor'"
               " (VDI 2230 alpha_A = F_max/F_min: the preload range around today's torque)."),
        F("min", "low", "ratio", required=False,
          note="Lowest value (blank = today's value), in 'unit'.",
          expected="a number in the row's unit (column 'unit')"),
        F("max", "high", "ratio", required=False,
          note="Highest value (blank = today's value), in 'unit'.",
          expected="a number in the row's unit (column 'unit')"),
        F("unit", "unit", "text", required=False,
          note="Unit of min and max (as a unit cell), or '% of nominal' for deviations from"
               " today's value in percent (e.g. -5 and 5)."),
    ),
)

NOTES = Sheet("Notes", "notes", note="Free text; not read.")

#: Largest number of speeds in the swept speed grid (minimum..maximum in speed steps, plus the
#: overspeed): more is an input error (the run time grows linearly, ~15 ms per speed on the I4
#: example); more than :data:`USUAL_SPEEDS` is a warning.
MAX_SPEEDS = 1000
USUAL_SPEEDS = 300
#: Speed step used when the Engine sheet gives none [rpm] (as checker.modules.loads).
DEFAULT_SPEED_STEP_RPM = 100.0

SHEETS: dict[str, Sheet] = {
    s.name: s
    for s in (
        ENGINE, CYLINDERS, PEAK_PRESSURE, PRESSURE_TRACES, BRAKE_TORQUE, BEARINGS, CRANK,
        CRANK_ENDS, CRANK_MASS, OIL, TV_MODEL, DAMPER, DAMPER_RUBBER, COUPLING,
        COUPLING_TEMPERATURE, DRIVEN, FATIGUE, JOINTS, JOINT_TORQUES, RULE_OVERRIDES,
        TOLERANCES, NOTES,
    )
}


def _choice_sets() -> dict[str, tuple[str, ...]]:
    out: dict[str, tuple[str, ...]] = {}
    for sheet in SHEETS.values():
        for f in sheet.fields:
            if f.kind != "choice":
                continue
            if out.setdefault(f.attr, f.choices) != f.choices:  # pragma: no cover - schema error
                raise AssertionError(f"choice attribute '{f.attr}' has two different sets")
    return out


#: Allowed values of every choice attribute (``lining``, ``clamped_material``, ``case``,
#: ``point``, ``tightening``...): the item attributes and coordinates rules filter on and key
#: their ``limits`` by. A rule table keyed by a value outside these sets can never apply.
CHOICE_SETS: dict[str, tuple[str, ...]] = _choice_sets()


def choice_field(attr: str) -> Field:
    """The (first) choice field of attribute ``attr``: use with :func:`resolve_choice`."""
    for sheet in SHEETS.values():
        for f in sheet.fields:
            if f.kind == "choice" and f.attr == attr:
                return f
    raise KeyError(attr)
