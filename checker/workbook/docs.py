"""Generate ``docs/workbook.md`` from the schema: ``python -m checker.workbook.docs``."""

from __future__ import annotations

from ..units import KINDS
from .schema import SHEETS


def _kind(kind: str) -> str:
    if kind in ("int", "text", "choice"):
        return {"int": "whole number", "text": "text", "choice": "choice"}[kind]
    k = KINDS[kind]
    return f"{k.name.replace('_', ' ')} (e.g. {k.example})"


def workbook_markdown() -> str:
    out = ["# Engine workbook layout", "",
           "Generated from `checker/workbook/schema.py` by `python -m checker.workbook.docs`.",
           "",
           "* **Parameter sheets**: columns `parameter | value | unit | note`, one parameter per"
           " row; names match case-insensitively.",
           "* **Table sheets**: row 1 column names, row 2 the unit of each column (`-` or blank"
           " for text and dimensionless columns), data from row 3. A `note` column is allowed"
           " anywhere.",
           "* Every number carries an explicit unit. Spellings handled on purpose: `Nm`/`kNm`"
           " (torque), `bar(g)`/`barg`/`psig` (gauge; a plain `bar` takes the parameter's own"
           " reference), `rpm` = `1/min` = `min^-1`, `Hz` = rev/s for shaft speeds, `°C`/`degC`"
           " (absolute temperatures; a temperature *rise* in `°C` is a difference), `-`/blank for"
           " dimensionless, `%` = 0.01. A percent-formatted cell stores the fraction it shows"
           " (75 % = 0.75) and is only accepted for dimensionless values.",
           "* Notes that contain the word `ASSUMPTION` are listed in the report's assumptions.",
           "* Unknown sheets, parameters and columns are errors (typos must not be ignored);"
           " the sheet `Notes` is free text.", ""]
    for s in SHEETS.values():
        req = " (required)" if s.required else ""
        out += [f"## {s.name}{req}", "", s.note, ""]
        if s.shape == "notes":
            continue
        head = "parameter" if s.shape == "parameters" else "column"
        out += [f"| {head} | kind | required | check | note |", "|---|---|---|---|---|"]
        for f in s.fields:
            kind = _kind(f.kind)
            if f.choices:
                kind += ": " + ", ".join(f"`{c}`" for c in f.choices)
            out.append(f"| {f.label} | {kind} | {'yes' if f.required else ''} |"
                       f" {f.check or ''} | {f.note} |")
        if s.key:
            out += ["", f"Values of `{s.key}` must be unique."]
        out.append("")
    return "\n".join(out)


if __name__ == "__main__":  # pragma: no cover
    print(workbook_markdown(), end="")
