"""A second example workbook: an inline six-cylinder truck diesel built from published data.

For benchmarks and stress tests, independent of the I4 gasoline example
(:mod:`checker.workbook.example`). :func:`i6_content` reads ``templates/example_i6.toml``
(same sheets and column headers as :func:`~checker.workbook.example.example_content`; throw
angles, crank masses and oil-hole heights derived by :mod:`checker.workbook.example_derived`)
and is written with :func:`~checker.workbook.example.write_workbook`.

Sources
-------
[MENDES] A. S. Mendes, P. S. Meirelles, D. E. Zampieri, "Analysis of torsional vibration in
    internal combustion engines: modelling and experimental validation", Proc. IMechE Part K,
    J. Multi-body Dynamics 222(2):155-178, 2008, doi:10.1243/14644193JMBD126. An MWM
    International six-cylinder diesel; the torsional model of its Fig. 4 and its measured and
    calculated vibratory torques (Figs 31 and 32).
[OT] Aalto-Arotor/openTorsion, ``examples/ICE_example.py`` with ``ICE_data/peak_data.csv`` and
    ``pressure_data.csv`` (MIT). It reproduces [MENDES]: inertias J2..J10 and stiffnesses
    k2..k9 of Fig. 4 **without** the damper inertia ring J1 and the rubber k1 (the code's own
    words: "crankshaft without torsional vibration damper"); J2 = crankshaft pulley, J3 = gear
    train, J4..J9 = cylinders 1..6, J10 = flywheel. Also bore 105 mm, stroke 137 mm, con-rod
    207 mm, reciprocating mass 2.521 kg, absolute damping 2 N m s/rad per cylinder, structural
    loss factor 0.035, the digitised peak-pressure curve (MPa against rpm), the digitised pressure
    trace, and, in ``opentorsion/examples/torsional_vibration_data_fig31.csv`` / ``fig32.csv``,
    the curves of [MENDES] Figs 31 and 32.
[MANUAL] "Workshop Manual MaxxForce 4.8/7.2 - Mechanical Injection", Group 08 (the MWM-built
    7.2 L family; that it is the engine of [MENDES] is inferred from 6 x 105 x 137 mm = 7.12 L
    and is itself an assumption): big-end bore with shells 63.015-63.031 mm and big-end
    clearance 0.026-0.081 mm.
[TORSION] free-free natural frequencies of the [OT] chain (an independent eigen-solution of
    the published J and k): 216.6 / 592.7 / 984.9 / 1171.0 / 1416.0 / 1660.0 / 1794.4 /
    2993.5 Hz.

What the sources do not give (bearings, crank mass properties, fillets, joints, oil, damper
rubber, brake torque...) is entered as a physically sound value for a ~7 L truck diesel, and its
note says ``ASSUMPTION`` with a one-line reason; the data file's ``[about.assumed]`` lists
them.

Two deliberate choices
----------------------
* The TVModel chain is the published one (pulley, gear train, 6 cylinders, flywheel): there is
  no damper ring, since [MENDES]'s J1/k1 are not available. ``i6_content(damper_ring=True)``
  adds an ASSUMED damper ring for damper checks: an untuned viscous (Houdaille) damper, a steel
  ring 90/130 x 40 mm of 0.1085 kg m^2 (mu = J_d / J_eq = 0.1085 / 0.1444 = 0.75, J_eq the
  modal inertia of the first mode at the pulley) in silicone whose grade is sized by Den
  Hartog's optimum untuned damping c_opt = 2 J_d w_n / sqrt(2 (1 + mu)(2 + mu)) = 95 N m s/rad
  at the hot end's silicone temperature (Den Hartog, Mechanical Vibrations, 1956, ch. 3);
  docs/dampers.md compares it with the tuned rubber damper (0.06 kg m^2, 55.5 kN m/rad) the
  example carried before. The shaft's damping to next is the viscous
  equivalent of the published loss factor at the first mode, c = 0.035 k / (2 pi 216.6 Hz).
* Throw angles follow the workbook convention ("from throw 1, in the direction of rotation",
  :func:`checker.calc.crank_forces.throw_angles`: gamma = -phi): with firing angles
  0/480/240/600/120/360 deg for cylinders 1..6 (order 1-5-3-6-2-4) the throws are
  0/240/120/120/240/0 deg (pairs 1&6, 2&5, 3&4). Measured against the rotation they are
  0/120/240/240/120/0 deg.
"""

from __future__ import annotations

from typing import Any

from .example_data import about, load_example, without_tv_role
from .example_derived import i6_throw_angles


def i6_content(damper_ring: bool = False) -> dict[str, Any]:
    """The I6 diesel workbook as ``{sheet: rows}`` (parameter sheets) or ``(columns, rows)``.

    ``damper_ring=True`` keeps the assumed (viscous) damper ring in front of the published chain
    (``checker template --engine i6``); without it the TVModel is the published chain.
    """
    content = load_example("i6")
    return content if damper_ring else without_tv_role(content, "damper ring")


def __getattr__(name: str) -> Any:
    """``THROW_ANGLES`` (cylinder -> throw angle [deg]) and ``ASSUMED`` (what the example
    assumes), from the data file when asked for."""
    if name == "THROW_ANGLES":
        return i6_throw_angles(load_example("i6"))
    if name == "ASSUMED":
        return about("i6").get("assumed", {})
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["i6_content"]
