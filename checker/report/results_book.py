"""The results workbook: every computed quantity (item, load case, speed, with units), the rule
results and the data behind the report's crank-angle plots, as one .xlsx.

The PDF report carries it as an attachment (``results.xlsx``); ``checker report --results
FILE`` also writes it beside the PDF. The report's body shows the judged worst cases only and
says, under each plot, which sheet holds its data.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np

from ..api import CheckResult
from ..results.display import case_text, item_label, unit_text
from ..results.loads import cycle_of

ATTACHMENT_NAME = "results.xlsx"

DEFAULT_DISPLAY = {"Pa": "MPa", "m": "mm", "rad": "deg", "N*m": "N*m", "W/m**3": "W/cm**3",
                   "m**2": "mm**2", "N": "kN", "rad/s": "rpm", "Hz": "Hz", "W": "W",
                   "K": "°C", "": "", "-": ""}
"""Display unit of a quantity's SI unit when no rule names one: every temperature in °C, as
the report gives it (a temperature, not a difference: no quantity in K is a difference)."""



SHEET_CHARS = 31
"""Longest sheet name Excel accepts."""
ABBREVIATIONS = (("amplitude", "ampl"), ("lower_order", "low_order"), ("pressure", "press"),
                 ("temperature", "temp"), ("cylinder", "cyl"), ("frequency", "freq"),
                 ("_order", "_ord"), ("bearing.", "brg."), ("elastic", "elast"),
                 ("continuous", "cont"))
"""Word abbreviations applied in turn (only as far as needed) to a quantity name longer than
a sheet name may be: ``tv.nose_cylinder_order_amplitude`` -> ``tv.nose_cylinder_order_ampl``,
never a name cut mid-word."""


def sheet_name(quantity: str) -> str:
    """The sheet of a quantity or a plot's data: the name itself when it fits (Excel allows 31
    characters, no ``[]:*?/\\``), else shortened word by word (:data:`ABBREVIATIONS`); the
    workbook's Index sheet maps every sheet to its quantity and description."""
    s = re.sub(r"[\[\]:*?/\\]", "_", quantity)
    for long, short in ABBREVIATIONS:
        if len(s) <= SHEET_CHARS:
            break
        s = s.replace(long, short)
    return s if len(s) <= SHEET_CHARS else s[:SHEET_CHARS]


def display_unit(res: CheckResult, q) -> str:
    """The unit a quantity is shown in: the unit of a rule on it, else a readable default."""
    for r in list(res.rules) + list(res.table.rules):
        if r.quantity == q.name and r.unit not in ("", "-", "%"):
            return r.unit
    if q.name.endswith("moft"):
        return "um"
    return DEFAULT_DISPLAY.get(q.spec.unit or "", q.spec.unit or "")


def convert(values, si: str, disp: str) -> tuple[np.ndarray, str]:
    """SI values in the display unit, through :func:`checker.workbook.units.from_si`, which converts
    offset units affinely (K -> °C subtracts 273.15; a factor from ``from_si(1.0, ...)`` would
    turn 403.6 K into -109,846 °C). Returns ``(values, unit)``; an exotic unit that cannot be
    converted stays in SI."""
    from ..workbook.units import from_si

    v = np.asarray(values, dtype=float)
    if si in ("", "-") and disp in ("", "-"):
        return v, disp
    if si == disp:
        return v, disp
    try:
        return np.asarray(from_si(v, si, disp), dtype=float), disp
    except Exception:  # noqa: BLE001 - an exotic unit: keep SI
        return v, si


def _coord(dim: str, label) -> object:
    if dim == "speed":
        return round(float(label) * 60 / (2 * np.pi), 3)
    if dim == "case":
        return case_text(str(label))
    return label if isinstance(label, (int, float, str)) else str(label)


def _cell(v):
    if v is None:
        return None
    if isinstance(v, (float, np.floating)):
        return float(v) if np.isfinite(v) else None
    if isinstance(v, (np.integer,)):
        return int(v)
    return v


def quantity_rows(res: CheckResult, q) -> tuple[list[str], list[list], str]:
    """Header, rows and display unit of one quantity: with a speed dimension (last), one row
    per combination of the other coordinates and one column per speed; otherwise one row per
    point."""
    vals, disp = convert(q.values, q.spec.unit or "", display_unit(res, q))
    dims = list(q.spec.dims)
    judged = None if q.applies is None else np.broadcast_to(
        np.asarray(q.applies, dtype=bool), vals.shape)
    if dims and dims[-1] == "speed":
        speeds = [_coord("speed", s) for s in q.coords["speed"]]
        lead = dims[:-1]
        header = [*lead, *[f"{s:g} rpm" for s in speeds]]
        rows = []
        for idx in np.ndindex(*vals.shape[:-1]):
            rows.append([_coord(d, q.coords[d][i]) for d, i in zip(lead, idx)]
                        + [_cell(v) for v in vals[idx]])
        if judged is not None and not judged.all():
            rows.append([])
            rows.append(["judged by the rules (1) or computed only (0):"])
            for idx in np.ndindex(*vals.shape[:-1]):
                rows.append([_coord(d, q.coords[d][i]) for d, i in zip(lead, idx)]
                            + [int(x) for x in judged[idx]])
        return header, rows, disp
    header = [*dims, "value"]
    rows = []
    for idx in np.ndindex(*vals.shape):
        rows.append([_coord(d, q.coords[d][i]) for d, i in zip(dims, idx)]
                    + [_cell(vals[idx])])
    return header, rows, disp


def _results_rows(res: CheckResult) -> tuple[list[str], list[list]]:
    header = ["rule", "name", "item", "status", "severity", "value", "unit", "limit",
              "margin [%]", "margin", "case", "message", "override"]
    rows = []
    for r in res.results:
        st = "WARN" if r.status == "fail" and r.severity == "warning" else r.status.upper()
        rows.append([r.rule, r.name, item_label(r.item), st.replace("_", " "), r.severity,
                     _cell(r.value),
                     unit_text(r.unit), r.limit,
                     None if r.margin is None else round(r.margin * 100, 3),
                     r.margin_text, r.case, r.message,
                     r.override])
    return header, rows


MAX_TRACE_ROWS = 720
"""Crank-angle rows of the pressure traces in the workbook (the cycle grid, thinned to at most
this many points: 1 deg steps or finer)."""


def _cycle_rows(q) -> list[list]:
    """Below the peak pressure of ``loads.cycle``: the IMEP of the trace used, the IMEP target
    it was calibrated to (brake torque + friction), which trace was used, and the traces
    themselves (bar over the cycle angle, one column per load case and speed)."""
    cyc = cycle_of({q.name: q})
    if cyc is None:
        return []
    speeds = [_coord("speed", s) for s in cyc.speeds]
    head = ["case", *[f"{s:g} rpm" for s in speeds]]
    out: list[list] = []

    def block(title: str, values, fmt) -> None:
        out.extend([[], [title], head])
        for ci, c in enumerate(cyc.cases):
            out.append([_coord("case", c), *[fmt(v) for v in values[ci]]])

    def bar(v) -> float | None:
        return _cell(float(v) / 1e5)

    block("IMEP of the trace used [bar]", cyc.imep, bar)
    block("IMEP target (brake torque + friction) [bar]; blank: not calibrated to a target",
          cyc.target_imep, bar)
    with np.errstate(all="ignore"):
        dev = (np.asarray(cyc.imep) / np.asarray(cyc.target_imep) - 1.0) * 100.0
    block("IMEP of the trace / target - 1 [%]", dev, lambda v: _cell(float(v)))
    block("trace used", np.where(cyc.synthesized, "synthesized", "workbook"), str)
    n = len(cyc.theta)
    step = max(1, -(-n // MAX_TRACE_ROWS))
    out.extend([[], ["Cylinder pressure traces [bar] over the cycle angle from firing TDC of"
                     " each load case and speed"],
                ["crank angle [deg]", *[f"{_coord('case', c)}, {sp:g} rpm" for c in cyc.cases
                                        for sp in speeds]]])
    p = np.asarray(cyc.pressure, dtype=float) / 1e5  # (C, S, N)
    flat = p.reshape(-1, n)
    deg = np.degrees(np.asarray(cyc.theta, dtype=float))
    for k in range(0, n, step):
        out.append([round(float(deg[k]), 6), *[_cell(v) for v in flat[:, k]]])
    return out


def sheet_names(res: CheckResult, extra: list[dict] | None = None) -> set[str]:
    """The sheets :func:`build` writes (for the report's "Data:" notes under plots)."""
    out = {"Index", "Rule results"}
    for q in res.outcome.quantities.values():
        if q.values is not None and np.size(q.values):
            out.add(sheet_name(q.name))
    out |= {sheet_name(e["sheet"]) for e in extra or []}
    return out


def build(res: CheckResult, extra: list[dict] | None = None) -> bytes:
    """The workbook as bytes (byte-identical for the same results).

    ``extra``: further sheets ``{"sheet", "title", "columns", "rows"}`` (the curves of the
    report's crank-angle plots)."""
    return finish(prepare(res), res, extra)


def build_fed(res: CheckResult, extra: Callable[[], list[dict]]) -> bytes:
    """:func:`build` with the quantities' sheets written before ``extra()`` (which may wait
    for the report's sections) gives the further sheets: the bulk of the workbook is done
    while the sections are being built (:class:`checker.plumbing.forked.ForkedCall` with
    ``fed``)."""
    return finish(prepare(res), res, extra())


def prepare(res: CheckResult) -> dict:
    """The quantities' sheets of the workbook, their XML written (most of :func:`build`'s
    work), and the index rows naming them; :func:`finish` completes the workbook."""
    from .xlsx import sheet_xml

    source = res.engine.source.replace("\\", "/").split("/")[-1]
    contents = [[f"Results of the design-rule check: {res.engine.name}"],
                [f"Input workbook {source}, SHA-256 {res.engine.sha256}"],
                ["Every computed quantity with its items, load cases and speeds, in the unit"
                 " given on each sheet. Where a sheet has a 'judged' block, points marked 0"
                 " are computed but not judged by the rules (the report says why)."],
                [],
                ["sheet", "quantity", "description", "unit", "dimensions"]]
    sheets: list[dict] = []
    used: set[str] = {"Index", "Rule results"}
    for q in res.outcome.quantities.values():
        if q.values is None or not np.size(q.values):
            continue
        name = sheet_name(q.name)
        k = 2
        while name in used:
            name = sheet_name(q.name)[:28] + f"~{k}"
            k += 1
        used.add(name)
        header, rows, disp = quantity_rows(res, q)
        if q.name == "loads.cycle":
            rows = rows + _cycle_rows(q)
        sheets.append({"name": name, "xml": sheet_xml(
            [[q.spec.description], [f"unit: {unit_text(disp) or '-'}"], header, *rows],
            (0, 2), [18] * len(header[:1]))})
        desc = q.spec.description + ("; below: IMEP, its target and the pressure traces"
                                     if q.name == "loads.cycle" else "")
        contents.append([name, q.name, desc, unit_text(disp) or "-",
                         " x ".join(q.spec.dims)])
    return {"contents": contents, "sheets": sheets, "used": used}


def finish(prepared: dict, res: CheckResult, extra: list[dict] | None = None) -> bytes:
    """The workbook from :func:`prepare`'s sheets, the further sheets ``extra`` (see
    :func:`build`), the index and the rule results."""
    from .xlsx import write

    contents = list(prepared["contents"])
    sheets = list(prepared["sheets"])
    used = set(prepared["used"])
    for e in extra or []:
        name = sheet_name(e["sheet"])
        if name in used:
            continue
        used.add(name)
        sheets.append({"name": name, "rows": [[e.get("title", name)], [], list(e["columns"]),
                                              *e["rows"]], "bold_rows": (0, 2)})
        contents.append([name, "", e.get("title", name), "in the column headers",
                         "plot data"])
    header, rows = _results_rows(res)
    first = [{"name": "Index", "rows": contents, "bold_rows": (0, 4),
              "widths": [32, 36, 90, 10, 24]},
             {"name": "Rule results", "rows": [header, *rows], "bold_rows": (0,),
              "widths": [9, 40, 16, 8, 8, 10, 6, 12, 10, 28, 26, 60, 40]}]
    return write(first + sheets)
