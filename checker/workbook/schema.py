"""Declared layout of the engine workbook: every sheet, parameter and column with its kind.

Two sheet shapes:

* **parameter sheets** (``Engine``, ``Oil``, ``Damper``, ``Fatigue``): one parameter per row,
  columns ``parameter | value | unit | note``. The parameter names in column A are matched
  case-insensitively.
* **table sheets** (``Cylinders``, ``Bearings``, ``Joints``...): row 1 holds the column names,
  row 2 the unit of each column (``-`` or blank for text and dimensionless), data from row 3.

Each field has a *kind* (a key of :data:`checker.units.KINDS`, or ``int``, ``text``,
``choice``), whether it is required, and a physical check. The loader converts every value to
SI and reports all problems of a workbook together.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Field:
    """One parameter (parameter sheet) or column (table sheet)."""

    label: str
    attr: str
    kind: str
    required: bool = True
    check: str | None = None  # ">0", ">=0", "0..1", "<0.5" ...
    choices: tuple[str, ...] = ()
    note: str = ""


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


F = Field

ENGINE = Sheet(
    "Engine",
    "parameters",
    required=True,
    note="Engine geometry, masses and operating range.",
    fields=(
        F("Engine name", "name", "text"),
        F("Number of cylinders", "cylinders", "int", check=">0"),
        F("Layout", "layout", "choice", choices=("inline", "v"), required=False,
          note="inline or V; a V engine gives a bank angle per cylinder in Cylinders."),
        F("Bore", "bore", "length", check=">0"),
        F("Stroke", "stroke", "length", check=">0"),
        F("Connecting rod length", "rod_length", "length", check=">0",
          note="Big-end to small-end centre distance."),
        F("Cylinder offset", "cylinder_offset", "length", required=False,
          note="Offset of the cylinder axis from the crank axis (seed 004 convention)."),
        F("Pin offset", "pin_offset", "length", required=False,
          note="Piston pin offset from the cylinder axis, towards the thrust side positive."),
        F("Crankshaft rotation", "rotation", "choice", choices=("clockwise", "anticlockwise"),
          required=False, note="Seen from the front (crank nose)."),
        F("Firing order", "firing_order", "text", note="e.g. 1-3-4-2"),
        F("Cylinder spacing", "cylinder_spacing", "length", check=">0", required=False),
        F("Main journal spacing", "main_spacing", "length", check=">0", required=False),
        F("Connecting rod mass", "rod_mass", "mass", check=">0", required=False,
          note="Including bolts and bearing shells."),
        F("Rod centre of mass from big end", "rod_com", "length", check=">0", required=False),
        F("Rod moment of inertia about centre of mass", "rod_inertia", "inertia", check=">0",
          required=False),
        F("Piston assembly mass", "piston_mass", "mass", check=">0", required=False,
          note="Piston, rings, pin and clips."),
        F("Compression ratio", "compression_ratio", "ratio", check=">1", required=False),
        F("Intake manifold pressure at full load", "intake_pressure", "pressure", check=">0",
          required=False),
        F("Rated speed", "rated_speed", "speed", check=">0", required=False),
        F("Minimum speed", "speed_min", "speed", check=">0", required=False),
        F("Maximum speed", "speed_max", "speed", check=">0", required=False),
        F("Speed step", "speed_step", "speed", check=">0", required=False),
        F("Overspeed", "overspeed", "speed", check=">0", required=False),
        F("Accessory drive torque at crank nose", "fead_torque", "torque", check=">=0",
          required=False, note="FEAD + timing drive torque added at the crank-nose joint."),
    ),
)

OIL = Sheet(
    "Oil",
    "parameters",
    note="Lubricant and supply conditions.",
    fields=(
        F("Oil grade", "grade", "text", required=False, note="SAE J300 grade, e.g. 5W30"),
        F("Kinematic viscosity at 40 °C", "kv40", "kinematic_viscosity", check=">0",
          required=False),
        F("Kinematic viscosity at 100 °C", "kv100", "kinematic_viscosity", check=">0",
          required=False),
        F("Density at 15 °C", "density", "density", check=">0", required=False),
        F("HTHS viscosity at 150 °C", "hths", "viscosity", check=">0", required=False),
        F("Oil supply pressure", "supply_pressure", "pressure_gauge", check=">=0",
          required=False),
        F("Oil supply temperature", "supply_temperature", "temperature", check=">0",
          required=False),
        F("Film temperature rise", "temperature_rise", "temperature_difference", check=">=0",
          required=False, note="Added to the supply temperature to give the film temperature."),
        F("Mobility model", "mobility_model", "choice",
          choices=("short bearing", "exact short bearing", "finite length", "Butenschoen fits"),
          required=False,
          note="short bearing = Booker closed form (default, seed 000); exact short bearing ="
               " numerical short-bearing mobility (reference); finite length = mobility map of"
               " the finite-length Reynolds equation (checker's solver, L/D 1/16..1);"
               " Butenschoen fits = Butenschoen (1976) curve fits (L/D 1/8..1)."),
    ),
)

DAMPER = Sheet(
    "Damper",
    "parameters",
    note="TV damper rubber: properties, geometry and the supplier's limits.",
    fields=(
        F("Rubber loss factor", "loss_factor", "ratio", check=">=0", required=False),
        F("Rubber inner radius", "inner_radius", "length", check=">0", required=False),
        F("Rubber outer radius", "outer_radius", "length", check=">0", required=False),
        F("Rubber axial length", "axial_length", "length", check=">0", required=False),
        F("Rubber shear stress limit", "shear_stress_limit", "stress", check=">0",
          required=False),
        F("Rubber heat per unit volume limit", "heat_limit", "power_density", check=">0",
          required=False),
    ),
)

FATIGUE = Sheet(
    "Fatigue",
    "parameters",
    note="Classical stress inputs: web, fillet, oil-hole geometry and material strengths.",
    fields=(
        F("Web reduced thickness", "web_thickness", "length", check=">0", required=False),
        F("Web full thickness", "web_full_thickness", "length", check=">0", required=False),
        F("Web minimum width", "web_min_width", "length", check=">0", required=False),
        F("Web maximum width", "web_max_width", "length", check=">0", required=False),
        F("Web offset", "web_offset", "length", required=False),
        F("Crank pin fillet radius", "pin_fillet_radius", "length", check=">0", required=False),
        F("Crank pin fillet undercut", "pin_fillet_undercut", "length", check=">=0",
          required=False),
        F("Crank pin fillet web undercut", "pin_fillet_web_undercut", "length", check=">=0",
          required=False),
        F("Main journal fillet radius", "main_fillet_radius", "length", check=">0",
          required=False),
        F("Main journal fillet undercut", "main_fillet_undercut", "length", check=">=0",
          required=False),
        F("Main journal web undercut", "main_fillet_web_undercut", "length", check=">=0",
          required=False),
        F("Pin journal oil hole diameter", "pin_oil_hole_diameter", "length", check=">0",
          required=False),
        F("Pin journal oil hole height", "pin_oil_hole_height", "length", required=False),
        F("Main journal oil hole diameter", "main_oil_hole_diameter", "length", check=">0",
          required=False),
        F("Main journal oil hole height", "main_oil_hole_height", "length", required=False),
        F("Pin journal land diameter", "pin_land_diameter", "length", check=">0", required=False),
        F("Pin journal land thickness", "pin_land_thickness", "length", check=">=0",
          required=False),
        F("Main journal land diameter", "main_land_diameter", "length", check=">0",
          required=False),
        F("Main journal land thickness", "main_land_thickness", "length", check=">=0",
          required=False),
        F("Pin bore diameter", "pin_bore", "length", check=">=0", required=False),
        F("Main journal bore diameter", "main_bore", "length", check=">=0", required=False),
        F("Base material UTS", "uts", "stress", check=">0", required=False),
        F("Fillet UTS", "fillet_uts", "stress", check=">0", required=False),
        F("Base tensile yield strength", "yield_strength", "stress", check=">0", required=False),
        F("Base compressive yield strength", "compressive_yield", "stress", check=">0",
          required=False),
        F("Base infinite life fatigue strength", "fatigue_strength", "stress", check=">0",
          required=False),
        F("Base hydrostatic fatigue strength", "hydrostatic_fatigue_strength", "stress",
          check=">0", required=False),
        F("Base torsional fatigue strength", "torsional_fatigue_strength", "stress", check=">0",
          required=False),
        F("Fillet tensile and compressive yield", "fillet_yield", "stress", check=">0",
          required=False),
        F("Pin fillet fatigue strength", "pin_fillet_fatigue", "stress", check=">0",
          required=False),
        F("Pin oil hole fatigue strength", "pin_oil_hole_fatigue", "stress", check=">0",
          required=False),
        F("Main fillet fatigue strength", "main_fillet_fatigue", "stress", check=">0",
          required=False),
        F("Main oil hole fatigue strength", "main_oil_hole_fatigue", "stress", check=">0",
          required=False),
        F("Pin fillet stress concentration bending", "scf_pin_bending", "ratio", check=">=1",
          required=False, note="Leave blank to use the IACS UR M53 empirical formula."),
        F("Pin fillet stress concentration torsion", "scf_pin_torsion", "ratio", check=">=1",
          required=False),
        F("Main fillet stress concentration bending", "scf_main_bending", "ratio", check=">=1",
          required=False),
        F("Main fillet stress concentration torsion", "scf_main_torsion", "ratio", check=">=1",
          required=False),
        F("Oil hole stress concentration bending", "scf_oil_bending", "ratio", check=">=1",
          required=False),
        F("Oil hole stress concentration torsion", "scf_oil_torsion", "ratio", check=">=1",
          required=False),
        F("Crank nose diameter", "nose_diameter", "length", check=">0", required=False,
          note="Smallest nose section at the critical fillet (crank-nose check, FAT-003)."),
        F("Crank nose bore diameter", "nose_bore", "length", check=">=0", required=False),
        F("Crank nose stress concentration bending", "scf_nose_bending", "ratio", check=">=1",
          required=False),
        F("Crank nose stress concentration torsion", "scf_nose_torsion", "ratio", check=">=1",
          required=False),
        F("Crank nose fatigue strength", "nose_fatigue", "stress", check=">0", required=False,
          note="Fully reversed fatigue strength at the nose fillet (with its treatment)."),
        F("Belt load on crank nose", "belt_load", "force", check=">=0", required=False,
          note="Resultant FEAD + timing drive belt/chain pull on the nose (blank = none"
               " given: torsion only, stated in the report)."),
        F("Belt load overhang", "belt_overhang", "length", check=">=0", required=False,
          note="Axial distance from the belt load line to the critical nose section."),
    ),
)

CYLINDERS = Sheet(
    "Cylinders",
    "table",
    key="cylinder",
    note="One row per cylinder: crank throw angle, firing angle, bank angle, crank pin.",
    fields=(
        F("cylinder", "cylinder", "int", check=">0"),
        F("throw angle", "throw_angle", "angle",
          note="Angle of the crank throw from throw 1, in the direction of rotation."),
        F("firing angle", "firing_angle", "angle",
          note="Crank angle after cylinder 1 fires at which this cylinder fires (0..720 deg)."),
        F("bank angle", "bank_angle", "angle", required=False,
          note="Cylinder axis angle from vertical (V engines); blank = 0."),
        F("crank pin", "pin", "int", check=">0", required=False,
          note="Crank pin (throw) carrying this cylinder's rod; blank = cylinder number."),
    ),
)

PEAK_PRESSURE = Sheet(
    "PeakPressure",
    "table",
    note="Peak cylinder pressure per speed and load case (full, part, no load).",
    fields=(
        F("load case", "case", "choice", choices=("full", "part", "no")),
        F("speed", "speed", "speed", check=">0"),
        F("peak pressure", "peak_pressure", "pressure", check=">0"),
    ),
)

PRESSURE_TRACES = Sheet(
    "PressureTraces",
    "table",
    note="Optional measured/simulated traces: crank angle vs cylinder pressure per speed/case.",
    fields=(
        F("load case", "case", "choice", choices=("full", "part", "no")),
        F("speed", "speed", "speed", check=">0"),
        F("crank angle", "crank_angle", "angle"),
        F("pressure", "pressure", "pressure", check=">0"),
    ),
)

BRAKE_TORQUE = Sheet(
    "BrakeTorque",
    "table",
    note="Full-load brake torque vs speed (mean torque for stress and joints).",
    fields=(
        F("speed", "speed", "speed", check=">0"),
        F("brake torque", "brake_torque", "torque"),
    ),
)

BEARINGS = Sheet(
    "Bearings",
    "table",
    key="name",
    note="One row per bearing: mains M1..M(n+1) front to rear, big ends BE1..BEn.",
    fields=(
        F("name", "name", "text"),
        F("type", "type", "choice", choices=("main", "big end")),
        F("journal diameter", "diameter", "length", check=">0"),
        F("journal length", "journal_length", "length", check=">0", required=False),
        F("effective length", "length", "length", check=">0",
          note="Shell land length carrying load (excluding chamfers and grooves)."),
        F("radial clearance", "clearance", "length", check=">0",
          note="Mean cold radial clearance."),
        F("groove", "groove", "choice", choices=("none", "partial", "full"), required=False),
        F("groove width", "groove_width", "length", check=">=0", required=False),
        F("groove start", "groove_start", "angle", required=False),
        F("groove end", "groove_end", "angle", required=False),
        F("oil feed", "oil_feed", "text", required=False),
        F("oil holes", "oil_holes", "int", check=">=0", required=False),
        F("oil hole type", "oil_hole_type", "text", required=False),
        F("oil hole diameter", "oil_hole_diameter", "length", check=">0", required=False),
        F("oil hole angle", "oil_hole_angle", "angle", required=False),
        F("lining", "lining", "text", required=False,
          note="Lining material, e.g. AS16, AS15, sputter; selects the specific-load limit."),
    ),
)

CRANK_MASS = Sheet(
    "CrankMass",
    "table",
    key="location",
    note="Crankshaft mass properties per web, counterweight and crank pin (crank frame).",
    fields=(
        F("location", "location", "text"),
        F("throw", "throw", "int", check=">0", note="Crank throw (bay) the mass belongs to."),
        F("kind", "kind", "choice", choices=("web", "counterweight", "pin")),
        F("mass", "mass", "mass", check=">=0"),
        F("X", "x", "length",
          note="Axial offset of the centre of mass from the component's reference plane"
               " (seed 000 convention: mirrored webs have opposite signs)."),
        F("Y", "y", "length",
          note="Radial position in the crank frame, along throw 1 (throw 1 pin at +Y)."),
        F("Z", "z", "length", required=False,
          note="Lateral position in the crank frame, +90 deg from Y in the direction of"
               " rotation; blank = 0."),
        F("axial position", "axial", "length", check=">=0",
          note="Axial position of the component's reference plane from the bay's front main"
               " bearing centre (the centre of mass is at axial position + X)."),
        F("relative to", "reference", "choice", choices=("main axis", "pin axis")),
    ),
)

TV_MODEL = Sheet(
    "TVModel",
    "table",
    key="station",
    note="Torsional lumped-mass chain from front (damper) to rear (flywheel).",
    fields=(
        F("station", "station", "text"),
        F("role", "role", "choice",
          choices=("damper ring", "crank nose", "cylinder", "flywheel", "other")),
        F("cylinder", "cylinder", "int", check=">0", required=False),
        F("inertia", "inertia", "inertia", check=">0"),
        F("absolute damping", "absolute_damping", "torsional_damping", check=">=0",
          required=False),
        F("stiffness to next", "stiffness", "torsional_stiffness", check=">0", required=False),
        F("damping to next", "relative_damping", "torsional_damping", check=">=0",
          required=False),
    ),
)

JOINTS = Sheet(
    "Joints",
    "table",
    key="name",
    note="Bolted joints at the crank nose and flywheel (any number).",
    fields=(
        F("name", "name", "text"),
        F("location", "location", "choice", choices=("crank nose", "flywheel", "other")),
        F("bolts", "bolts", "int", check=">0"),
        F("nominal diameter", "diameter", "length", check=">0"),
        F("thread pitch", "pitch", "length", check=">0"),
        F("stress area coefficient", "stress_area_coefficient", "ratio", check=">0",
          required=False,
          note="A_s = pi/4 (d - c p)^2; blank = 0.9382 (ISO 898-1)."),
        F("property class", "property_class", "choice",
          choices=("8.8", "9.8", "10.9", "11.9", "12.9")),
        F("tightening", "tightening", "choice",
          choices=("torque", "torque wrench", "yield controlled", "angle controlled")),
        F("tightening torque", "tightening_torque", "torque", check=">0", required=False),
        F("nut factor", "nut_factor", "ratio", check=">0", required=False,
          note="F = T/(K d); blank = 0.2 (seed 000)."),
        F("preload fraction", "preload_fraction", "ratio", check="0..1", required=False,
          note="Fraction of the reference stress for method-based preload; blank = seed table."),
        F("proof stress Rp0.2", "rp02", "stress", check=">0", required=False,
          note="Blank = ISO 898-1 minimum for the property class."),
        F("proof load stress", "proof_load_stress", "stress", check=">0", required=False,
          note="Blank = ISO 898-1 stress under proof load for the property class."),
        F("head bearing outer diameter", "head_outer", "length", check=">0", required=False),
        F("head bearing inner diameter", "head_inner", "length", check=">0", required=False),
        F("clamped material", "clamped_material", "text", required=False,
          note="Selects the head contact-pressure limit (steel, cast iron, aluminium...)."),
        F("face outer diameter", "face_outer", "length", check=">0"),
        F("face inner diameter", "face_inner", "length", check=">=0"),
        F("friction coefficient", "friction", "ratio", check=">0", required=False,
          note="Blank = 0.2 (seed 000)."),
    ),
)

JOINT_TORQUES = Sheet(
    "JointTorques",
    "table",
    note="Peak applied torque per joint and operating point (blank table = from TV module).",
    fields=(
        F("joint", "joint", "text"),
        F("operating point", "point", "choice", choices=("tv peak", "max power", "overspeed")),
        F("speed", "speed", "speed", check=">0", required=False),
        F("applied torque", "torque", "torque", check=">0"),
    ),
)

RULE_OVERRIDES = Sheet(
    "RuleOverrides",
    "table",
    key="rule",
    note="Project-specific limits replacing the rule table's defaults (each listed in the report).",
    fields=(
        F("rule", "rule", "text"),
        F("limit", "limit", "text", note="A number, or a range 'low..high'."),
        F("unit", "unit", "text", required=False),
        F("reason", "reason", "text"),
    ),
)

NOTES = Sheet("Notes", "notes", note="Free text; not read.")

SHEETS: dict[str, Sheet] = {
    s.name: s
    for s in (
        ENGINE, CYLINDERS, PEAK_PRESSURE, PRESSURE_TRACES, BRAKE_TORQUE, BEARINGS, CRANK_MASS,
        OIL, TV_MODEL, DAMPER, FATIGUE, JOINTS, JOINT_TORQUES, RULE_OVERRIDES, NOTES,
    )
}
