"""The example workbook: the 4-cylinder gasoline engine of Ricardo's 2013 workshop slides.

Source: D. Bell, "Cranktrain Analysis Using ENGDYN and VALDYN", Ricardo workshop, 4 Feb 2013:
engine and bearing data, peak cylinder
pressures, crankshaft mass properties, torsional model data, classical stress inputs, brake
torque, and the crank-nose and flywheel bolted-joint worked calculations. Values a later
analysis needs that the workshop slides do not give are entered as labelled ASSUMPTIONS in the note
column; :data:`ASSUMED` lists them so the report can state them.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import Any

SEED = "Bell, Ricardo 2013"
ASSUMPTION = "ASSUMPTION (not in Bell 2013)"

# ---------------------------------------------------------------- parameter sheets
ENGINE_ROWS: list[tuple[str, Any, str, str]] = [
    ("Engine name", "Example I4 gasoline (Ricardo 2013 workshop)", "-", SEED),
    ("Number of cylinders", 4, "-", SEED),
    ("Layout", "inline", "-", SEED),
    ("Bore", 86.0, "mm", SEED),
    ("Stroke", 94.6, "mm", SEED),
    ("Connecting rod length", 145.7, "mm", SEED),
    ("Cylinder offset", 0.0, "mm", SEED),
    ("Pin offset", 0.8, "mm", SEED),
    ("Crankshaft rotation", "clockwise", "-", SEED),
    ("Firing order", "1-3-4-2", "-", SEED),
    ("Cylinder spacing", 96.0, "mm", SEED),
    ("Main journal spacing", 96.0, "mm", SEED),
    ("Connecting rod mass", 0.597, "kg", SEED + ": including bolts and bearing shells"),
    ("Rod centre of mass from big end", 35.73, "mm", SEED),
    ("Rod moment of inertia about centre of mass", 2128, "kg mm^2", SEED),
    ("Piston assembly mass", 0.4955, "kg", SEED + ": including rings and piston pin"),
    ("Compression ratio", 10.5, "-", ASSUMPTION + ": typical port-injected gasoline engine;"
     " used to synthesize pressure traces"),
    ("Intake manifold pressure at full load", 1.0, "bar", ASSUMPTION + ": naturally aspirated"),
    ("Rated speed", 6000, "rpm", SEED),
    ("Minimum speed", 1000, "rpm", SEED + ": lowest speed of the pressure data"),
    ("Maximum speed", 7000, "rpm", SEED + ": no-load overspeed point of the pressure data"),
    ("Speed step", 100, "rpm", SEED + ": 'in 100 rpm intervals'"),
    ("Overspeed", 7000, "rpm", SEED + ": no-load peak pressure given at 7000 rpm"),
    ("Accessory drive torque at crank nose", 19, "N m", SEED + ": 'typical FEAD torque'"),
    ("Free force limit, 1st order", 500, "N", ASSUMPTION + ": ILLUSTRATIVE project limit at"
     " rated speed (no published limit), replace with the project's value"),
    ("Free force limit, 2nd order", 10, "kN", ASSUMPTION + ": ILLUSTRATIVE project limit at"
     " rated speed (no published limit; an I4 without balance shafts exceeds it by design)"),
    ("Free moment limit, 1st order", 100, "N m", ASSUMPTION + ": ILLUSTRATIVE project limit"
     " at rated speed (no published limit)"),
    ("Free moment limit, 2nd order", 100, "N m", ASSUMPTION + ": ILLUSTRATIVE project limit"
     " at rated speed (no published limit)"),
    ("Balance ratio, minimum", 50, "%", ASSUMPTION + ": ILLUSTRATIVE band for the"
     " counterweight balance ratio per throw"),
    ("Balance ratio, maximum", 100, "%", ASSUMPTION + ": ILLUSTRATIVE band (100 % = each"
     " throw's rotating unbalance fully balanced within the throw)"),
    ("Target cyclic irregularity", 10, "%", ASSUMPTION + ": ILLUSTRATIVE target at the lowest"
     " speed, replace with the application's value (Agostini 2019 quotes 1 % as a bound)"),
    ("Project", "Example review: Ricardo 2013 workshop I4", "-", "document control"),
    ("Revision", "A", "-", "document control"),
]

OIL_ROWS = [
    ("Oil grade", "5W30", "-", SEED),
    ("Oil supply pressure", 4.0, "bar(g)", SEED + " (gauge)"),
    ("Oil supply temperature", 130, "°C", SEED),
    ("Film temperature rise", 0, "K", ASSUMPTION + ": film at supply temperature"),
    ("Film temperature", "supply plus rise", "-", ASSUMPTION + ": supply plus rise (the"
     " default); 'heat balance' runs the film thickness at each bearing's balance temperature"),
    ("Heat fraction carried by the oil", 1.0, "-", ASSUMPTION + ": all bearing friction heat"
     " leaves with the oil (conservative; the default when blank)"),
]

DAMPER_ROWS = [
    ("Rubber loss factor", 0.15, "-", ASSUMPTION + ": typical EPDM/NR loss factor tan(delta)"),
    ("Rubber inner radius", 55, "mm", ASSUMPTION + ": ILLUSTRATIVE geometry"),
    ("Rubber outer radius", 59, "mm", ASSUMPTION + ": ILLUSTRATIVE geometry"),
    ("Rubber axial length", 28, "mm", ASSUMPTION + ": ILLUSTRATIVE geometry"),
    ("Rubber shear stress limit", 0.5, "MPa", ASSUMPTION + ": ILLUSTRATIVE limit, replace with"
     " the damper supplier's value"),
    ("Rubber heat per unit volume limit", 0.5, "W/cm^3", ASSUMPTION + ": ILLUSTRATIVE limit,"
     " replace with the damper supplier's value"),
    ("Tuning ratio, minimum", 0.65, "-", ASSUMPTION + ": ILLUSTRATIVE band, about -10 % around"
     " Den Hartog's optimum 0.72 for this ring/crank inertia ratio"),
    ("Tuning ratio, maximum", 0.79, "-", ASSUMPTION + ": ILLUSTRATIVE band, about +10 % around"
     " Den Hartog's optimum"),
]

#: The crank-nose inputs of FAT-003, none given in the examples' sources: left blank (the check
#: stays "not evaluated", naming these cells), so the user sees where to type them.
NOSE_ROWS = [
    ("Crank nose diameter", None, "mm", "not in the source: type the smallest nose section"
     " at the critical fillet to evaluate FAT-003"),
    ("Crank nose stress concentration bending", None, "-", "not in the source (FAT-003)"),
    ("Crank nose stress concentration torsion", None, "-", "not in the source (FAT-003)"),
    ("Crank nose fatigue strength", None, "N/mm^2", "not in the source: fully reversed, at"
     " the nose fillet with its treatment (FAT-003)"),
]

FATIGUE_ROWS = [
    ("Web reduced thickness", 21.3, "mm", SEED + ": full width 22.3 - land width"),
    ("Web full thickness", 22.3, "mm", SEED),
    ("Web minimum width", 71.4, "mm", SEED + ": from drawing"),
    ("Web maximum width", 80.0, "mm", SEED + ": from drawing"),
    ("Web offset", 0, "mm", SEED),
    ("Crank pin fillet radius", 1.6, "mm", SEED),
    ("Crank pin fillet undercut", 0.52, "mm", SEED),
    ("Crank pin fillet web undercut", 0, "mm", SEED),
    ("Main journal fillet radius", 1.6, "mm", SEED),
    ("Main journal fillet undercut", 0.5, "mm", SEED),
    ("Main journal web undercut", 0, "mm", SEED),
    ("Pin journal oil hole diameter", 5.4, "mm", SEED),
    ("Pin journal oil hole height", 16.9706, "mm", SEED),
    ("Main journal oil hole diameter", 5.4, "mm", SEED),
    ("Main journal oil hole height", 9.406, "mm", SEED),
    ("Pin journal land diameter", 60.0, "mm", SEED),
    ("Pin journal land thickness", 0.5, "mm", SEED),
    ("Main journal land diameter", 70.0, "mm", SEED),
    ("Main journal land thickness", 0.5, "mm", SEED),
    ("Base material UTS", 750, "N/mm^2", SEED + ": C38+N2BY steel"),
    ("Fillet UTS", 920, "N/mm^2", SEED + ": Ricardo experience"),
    ("Base tensile yield strength", 450, "N/mm^2", SEED),
    ("Base compressive yield strength", 450, "N/mm^2", SEED),
    ("Base infinite life fatigue strength", 375, "N/mm^2", SEED + ": 0.5 x base UTS"),
    ("Base hydrostatic fatigue strength", 543.75, "N/mm^2", SEED + ": 2.5 x 217.5"),
    ("Base torsional fatigue strength", 217.5, "N/mm^2", SEED + ": 0.58 x 375"),
    ("Fillet tensile and compressive yield", 750, "N/mm^2", SEED),
    ("Pin fillet fatigue strength", 619, "N/mm^2", SEED + ": 375 x 0.868 x 1.9 (rolled)"),
    ("Pin oil hole fatigue strength", 326, "N/mm^2", SEED + ": 375 x 0.868 x 1.0 (induction"
     " hardened)"),
    ("Main fillet fatigue strength", 611, "N/mm^2", SEED + ": 375 x 0.858 x 1.9 (rolled)"),
    ("Main oil hole fatigue strength", 326, "N/mm^2", SEED + ": 375 x 0.858 x 1.0 (induction"
     " hardened)"),
]

# ---------------------------------------------------------------- table sheets
CYLINDER_COLUMNS = [
    ("cylinder", "-"), ("throw angle", "deg"), ("firing angle", "deg"), ("bank angle", "deg"),
    ("crank pin", "-"), ("note", ""),
]
BRAKE_TORQUE_COLUMNS = [
    ("speed", "rpm"), ("brake torque", "N m"), ("note", ""),
]
BEARING_COLUMNS = [
    ("name", "-"), ("type", "-"), ("journal diameter", "mm"), ("journal length", "mm"),
    ("effective length", "mm"), ("radial clearance", "mm"), ("groove", "-"),
    ("groove width", "mm"), ("groove start", "deg"), ("groove end", "deg"), ("oil feed", "-"),
    ("oil holes", "-"), ("oil hole type", "-"), ("oil hole diameter", "mm"),
    ("oil hole angle", "deg"), ("lining", "-"), ("max film temperature", "°C"),
    ("max film pressure", "MPa"), ("min oil flow", "l/min"), ("note", ""),
]
_NO_SUPPLIER_LIMITS = [None, None, None]
"""Max film temperature, max film pressure, min oil flow: the shell supplier's data (none
published for the example engines: rules BRG-007..009 are not evaluated, naming the cells)."""
CRANK_MASS_COLUMNS = [
    ("location", "-"), ("throw", "-"), ("kind", "-"), ("mass", "kg"), ("X", "mm"), ("Y", "mm"),
    ("Z", "mm"), ("axial position", "mm"), ("relative to", "-"), ("note", ""),
]
TV_MODEL_COLUMNS = [
    ("station", "-"), ("role", "-"), ("cylinder", "-"), ("inertia", "kg m^2"),
    ("absolute damping", "N m s/rad"), ("stiffness to next", "N m/rad"),
    ("damping to next", "N m s/rad"), ("note", ""),
]
JOINT_COLUMNS = [
    ("name", "-"), ("location", "-"), ("bolts", "-"), ("nominal diameter", "mm"),
    ("thread pitch", "mm"), ("stress area coefficient", "-"), ("property class", "-"),
    ("tightening", "-"), ("tightening torque", "N m"), ("nut factor", "-"),
    ("preload fraction", "-"), ("proof stress Rp0.2", "N/mm^2"),
    ("proof load stress", "N/mm^2"), ("head bearing outer diameter", "mm"),
    ("head bearing inner diameter", "mm"), ("clamped material", "-"),
    ("face outer diameter", "mm"), ("face inner diameter", "mm"),
    ("friction coefficient", "-"), ("note", ""),
]
JOINT_TORQUE_COLUMNS = [
    ("joint", "-"), ("operating point", "-"), ("speed", "rpm"), ("applied torque", "N m"),
    ("note", ""),
]
RULE_OVERRIDE_COLUMNS = [
    ("rule", "-"), ("limit", "-"), ("unit", "-"), ("reason", "-"),
]

CYLINDERS = (
    CYLINDER_COLUMNS,
    [
        [1, 0, 0, 0, 1, SEED + ": phase angle 0"],
        [2, 180, 540, 0, 2, SEED + ": phase angle 540"],
        [3, 180, 180, 0, 3, SEED + ": phase angle 180"],
        [4, 0, 360, 0, 4, SEED + ": phase angle 360"],
    ],
)

_FULL = [(1000, 53.4), (1500, 59.0), (2000, 68.1), (2500, 73.6), (3000, 77.1), (3500, 77.5),
         (4000, 80.0), (4500, 83.8), (5000, 84.4), (5500, 82.7), (6000, 79.8), (6500, 73.3)]
PEAK_PRESSURE = (
    [("load case", "-"), ("speed", "rpm"), ("peak pressure", "bar"), ("note", "")],
    [["full", n, p, SEED + " (absolute)"] for n, p in _FULL]
    + [["part", 6500, 55.7, SEED], ["no", 7000, 29.1, SEED]],
)

BRAKE_TORQUE = (
    BRAKE_TORQUE_COLUMNS,
    [[n, t, SEED] for n, t in [(1000, 175), (1500, 200), (2000, 245), (2500, 255), (3000, 265),
                               (3500, 265), (4000, 265), (4500, 265), (5000, 265), (5500, 255),
                               (6000, 220), (6500, 190)]],
)

_MAIN = ["main", 55.0, 27.0, 18.2, 0.022, "partial", 4, 270, 90, "bearing", 0, None, None, None]
_PIN = ["big end", 48.0, 24.4, 17.8, 0.024, "none", None, None, None, "crank", 1, "leading", 5.4,
        45]
BEARINGS = (
    BEARING_COLUMNS,
    [[f"M{i}", *_MAIN, "AS16", *_NO_SUPPLIER_LIMITS, SEED + "; lining AS16 is an " + ASSUMPTION]
     for i in range(1, 6)]
    + [[f"BE{i}", *_PIN, "AS15", *_NO_SUPPLIER_LIMITS, SEED + "; lining AS15 is an " + ASSUMPTION]
       for i in range(1, 5)],
)

_W_FRONT, _W_REAR, _PIN_Z = 24.65, 71.35, 48.0
_AX_NOTE = ("axial position is an " + ASSUMPTION + ": web centre at half main journal length"
            " + half web thickness (13.5 + 11.15 mm) from its main; pin at mid-bay")
_sgn = {1: 1, 2: -1, 3: -1, 4: 1}  # throw direction: throws 1,4 at 0 deg, 2,3 at 180 deg
CRANK_MASS_ROWS = []
for _t in range(1, 5):
    s = _sgn[_t]
    a, b = 2 * _t - 1, 2 * _t
    CRANK_MASS_ROWS += [
        [f"Web{a}", _t, "web", 0.659, 1.46, s * 26.763, 0, _W_FRONT, "main axis", SEED],
        [f"Web{a} c/w", _t, "counterweight", 0.794, -0.541, -s * 37.611, 0, _W_FRONT,
         "main axis", SEED],
        [f"Crankpin{_t}", _t, "pin", 0.341, 0, -s * 0.1, 0, _PIN_Z, "pin axis",
         SEED + "; coordinates taken relative to the pin axis (" + ASSUMPTION + ")"],
        [f"Web{b}", _t, "web", 0.659, -1.46, s * 26.763, 0, _W_REAR, "main axis", SEED],
        [f"Web{b} c/w", _t, "counterweight", 0.794, 0.541, -s * 37.611, 0, _W_REAR,
         "main axis", SEED],
    ]
CRANK_MASS_ROWS = [r[:-1] + [r[-1] + "; " + _AX_NOTE] for r in CRANK_MASS_ROWS]
CRANK_MASS = (
    CRANK_MASS_COLUMNS,
    CRANK_MASS_ROWS,
)

TV_MODEL = (
    TV_MODEL_COLUMNS,
    [
        ["Damper ring", "damper ring", None, 0.0055, None, 25500, None,
         SEED + ": damper stiffness 1 = rubber; rubber damping from Damper loss factor"],
        ["Crank nose", "crank nose", None, 0.001155, None, 171035, None, SEED],
        ["Cylinder 1", "cylinder", 1, 0.0065732, 1.5, 403300, None,
         SEED + ": crankshaft damping 1.5 N m s/rad to a constant-speed node at each cylinder"],
        ["Cylinder 2", "cylinder", 2, 0.0065732, 1.5, 416625, None, SEED],
        ["Cylinder 3", "cylinder", 3, 0.0065732, 1.5, 403300, None, SEED],
        ["Cylinder 4", "cylinder", 4, 0.0065732, 1.5, 661013, None, SEED],
        ["Flywheel", "flywheel", None, 0.174743, None, None, None,
         SEED + ": AUTO flywheel etc.; DMF alternative 0.112772 kg m^2"],
    ],
)

JOINTS = (
    JOINT_COLUMNS,
    [
        ["crank nose", "crank nose", 1, 16, 1.5, 0.938, "10.9", "torque", 400, 0.2, None, 940,
         None, 24, 17, "steel", 36, 20, 0.2,
         SEED + " worked example: R1 = 18 mm, r1 = 10 mm; the workshop's stress area uses"
         " 0.938 p; P = 940 N/mm^2 (grade 10.9)"],
        ["flywheel", "flywheel", 6, 10, 1.0, None, "12.9", "yield controlled", None, None, 0.75,
         1100, None, None, None, "steel", 84.4, 47, 0.2,
         SEED + " worked example; bolt head bearing diameters not given by Bell 2013"],
    ],
)

JOINT_TORQUES = (
    JOINT_TORQUE_COLUMNS,
    [
        ["crank nose", "tv peak", 7100, 245,
         SEED + ": 226 N m max positive nose torque from VALDYN at 7100 rpm + 19 N m FEAD"],
        ["flywheel", "tv peak", 5000, 1216,
         SEED + ": 5000 rpm brake torque 265 N m + max TV torque 951 N m"],
    ],
)

RULE_OVERRIDES = (
    RULE_OVERRIDE_COLUMNS,
    [],
)

TOLERANCE_COLUMNS = [
    ("sheet", "-"), ("row", "-"), ("column", "-"), ("min", "-"), ("max", "-"), ("unit", "-"),
    ("source", ""),
]
TOLERANCES = (
    TOLERANCE_COLUMNS,
    [
        ["Bearings", "type = main", "radial clearance", 17, 27, "um",
         ASSUMPTION + ": production range of the radial clearance, journal and bore tolerances"
         " (IT5/IT6 at these diameters) around the nominal clearance"],
        ["Bearings", "type = big end", "radial clearance", 19, 29, "um", ASSUMPTION
         + ": as above"],
        ["Oil", "", "Oil supply temperature", 120, 140, "°C",
         ASSUMPTION + ": gallery temperature range at full load, hot day to cold day"],
        ["Joints", "crank nose", "tightening factor", None, 1.6, "-",
         ASSUMPTION + ": tightening by torque wrench with estimated friction; VDI 2230"
         " Part 1 (2015), Table A8: alpha_A = 1.4..1.6, 1.6 taken"],
        ["Joints", "crank nose", "friction coefficient", 0.15, 0.25, "-",
         ASSUMPTION + ": friction of a dry steel face 0.15..0.25 around the 0.2 of Bell,"
         " Ricardo 2013"],
        ["PeakPressure", "all", "peak pressure", -3, 3, "% of nominal",
         ASSUMPTION + ": cycle-to-cycle and cylinder-to-cylinder scatter of the peak pressure"],
        ["Fatigue", "", "Pin oil hole fatigue strength", 304, None, "N/mm^2",
         ASSUMPTION + ": material minimum, 326 N/mm^2 x 700/750 (minimum against typical UTS"
         " of the steel; fatigue strength proportional to UTS)"],
    ],
)

NOTES = [
    "Example engine workbook for checker.",
    "Source: D. Bell, 'Cranktrain Analysis Using ENGDYN and VALDYN', Ricardo, 4 Feb 2013.",
    "Parameter sheets: columns parameter | value | unit | note.",
    "Table sheets: row 1 column names, row 2 units, data from row 3.",
    "Every value carries an explicit unit; '-' marks text and dimensionless columns.",
    "Values marked ASSUMPTION are not in Bell 2013 and are stated in the report.",
    "See docs/workbook.md for every sheet, parameter and column.",
]

ASSUMED = {
    "Engine": ["Compression ratio", "Intake manifold pressure at full load",
               "Free force limit, 1st order", "Free force limit, 2nd order",
               "Free moment limit, 1st order", "Free moment limit, 2nd order",
               "Balance ratio, minimum", "Balance ratio, maximum", "Target cyclic irregularity"],
    "Oil": ["Film temperature rise"],
    "Damper": [r[0] for r in DAMPER_ROWS],
    "Bearings": ["lining"],
    "CrankMass": ["axial position", "pin coordinates relative to the pin axis"],
}


def example_content() -> dict[str, Any]:
    """The example workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``."""
    return {
        "Engine": ENGINE_ROWS,
        "Cylinders": CYLINDERS,
        "PeakPressure": PEAK_PRESSURE,
        "BrakeTorque": BRAKE_TORQUE,
        "Bearings": BEARINGS,
        "CrankMass": CRANK_MASS,
        "Oil": OIL_ROWS,
        "TVModel": TV_MODEL,
        "Damper": DAMPER_ROWS,
        "Fatigue": FATIGUE_ROWS + NOSE_ROWS,
        "Joints": JOINTS,
        "JointTorques": JOINT_TORQUES,
        "RuleOverrides": RULE_OVERRIDES,
        "Tolerances": TOLERANCES,
        "Notes": NOTES,
    }


def write_workbook(path: str | Path, content: dict[str, Any]) -> None:
    """Write a workbook from ``content`` (see :func:`example_content`) with openpyxl.

    Parameter sheets are lists of ``(parameter, value, unit, note)``; table sheets are
    ``(columns, rows)`` with ``columns`` a list of ``(name, unit)``; ``Notes`` is a list of lines.
    """
    import openpyxl
    from openpyxl.comments import Comment
    from openpyxl.styles import Alignment, Font, PatternFill
    from openpyxl.worksheet.datavalidation import DataValidation

    from .docs import field_description
    from .loader import DITTO
    from .schema import SHEETS

    wb = openpyxl.Workbook()
    wb.remove(wb.active)
    bold = Font(bold=True)
    grey = Font(italic=True, color="666666")
    unit_fill = PatternFill("solid", fgColor="EEEEEE")
    assumed = PatternFill("solid", fgColor="FFF2CC")  # ASSUMPTION values stand out
    wrap = Alignment(wrap_text=True, vertical="top")

    def choice_list(ws, f, ref: str) -> None:
        """A drop-down of the field's choices (other accepted spellings still allowed)."""
        if not f.choices:
            return
        dv = DataValidation(type="list", formula1='"' + ",".join(f.choices) + '"',
                            allow_blank=True, showErrorMessage=False)
        dv.add(ref)
        ws.add_data_validation(dv)

    for name, body in content.items():
        ws = wb.create_sheet(name)
        spec = SHEETS.get(name)
        fields = {} if spec is None else {f.label.lower(): f for f in spec.fields}
        if name == "Notes":
            for i, line in enumerate(body, start=1):
                ws.cell(row=i, column=1, value=line)
            ws.column_dimensions["A"].width = 100
            continue
        if isinstance(body, list):
            for j, h in enumerate(("parameter", "value", "unit", "note", "description"),
                                  start=1):
                ws.cell(row=1, column=j, value=h).font = bold
            for i, row in enumerate(body, start=2):
                for j, v in enumerate(row, start=1):
                    ws.cell(row=i, column=j, value=v)
                f = fields.get(str(row[0]).lower())
                if f is not None:
                    d = ws.cell(row=i, column=5, value=field_description(f))
                    d.font = grey
                    choice_list(ws, f, f"B{i}")
                if len(row) > 3 and row[3] and "assumption" in str(row[3]).lower():
                    ws.cell(row=i, column=2).fill = assumed
                    ws.cell(row=i, column=4).fill = assumed
            for col, w in zip("ABCDE", (40, 24, 10, 70, 70)):
                ws.column_dimensions[col].width = w
        else:
            cols, rows = body
            note_j = next((j for j, (h, _u) in enumerate(cols, start=1) if h == "note"), None)
            for j, (h, u) in enumerate(cols, start=1):
                c = ws.cell(row=1, column=j, value=h)
                c.font = bold
                f = fields.get(str(h).lower())
                if f is not None:
                    c.comment = Comment(field_description(f), "checker", width=320,
                                        height=120)
                    choice_list(ws, f, f"{openpyxl.utils.get_column_letter(j)}3:"
                                       f"{openpyxl.utils.get_column_letter(j)}"
                                       f"{max(50, len(rows) + 30)}")
                c = ws.cell(row=2, column=j, value=u)
                c.fill = unit_fill
            last = None
            for i, row in enumerate(rows, start=3):
                for j, v in enumerate(row, start=1):
                    if j == note_j and v and v == last:
                        v = DITTO[0]  # a long note once per run of rows
                    elif j == note_j:
                        last = row[j - 1]
                    ws.cell(row=i, column=j, value=v)
                note = row[note_j - 1] if note_j and note_j <= len(row) else None
                if note and "assumption" in str(note).lower():
                    for j in range(1, len(row) + 1):
                        ws.cell(row=i, column=j).fill = assumed
                if note_j:
                    ws.cell(row=i, column=note_j).alignment = wrap
            for j, (h, _u) in enumerate(cols, start=1):
                ws.column_dimensions[openpyxl.utils.get_column_letter(j)].width = max(
                    10, min(60, len(h) + 4)) if h != "note" else 80
        ws.freeze_panes = "A2" if isinstance(body, list) else "A3"
    fixed = _dt.datetime(2013, 2, 4)
    wb.properties.created = fixed
    wb.properties.modified = fixed
    wb.properties.creator = "checker"
    wb.save(path)
