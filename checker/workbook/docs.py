"""Generate ``docs/workbook.md`` from the schema: ``python -m checker.workbook.docs``."""

from __future__ import annotations

from .schema import MAX_SPEEDS, SHEETS, USUAL_SPEEDS, choice_key
from .units import KINDS


def _kind(kind: str) -> str:
    if kind in ("int", "int_list", "text", "choice"):
        return {"int": "whole number", "int_list": "whole number(s), comma-separated",
                "text": "text", "choice": "choice"}[kind]
    k = KINDS[kind]
    return f"{k.name.replace('_', ' ')} (e.g. {k.example})"


def field_description(f) -> str:
    """One line on a workbook field for the template's description column and comments:
    kind, choices, required, usual range and the schema's note."""
    parts = [_kind(f.kind)]
    if f.choices:
        parts[0] += ": " + ", ".join(f.choices)
    parts.append("required" if f.required else "optional")
    if f.usual:
        parts.append(f"usual {f.usual.text()}")
    text = "; ".join(parts) + "."
    return text + (f" {f.note}" if f.note else "")


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
           "* Notes that contain `ESTIMATE` (upper case; written by `checker new`, see"
           " docs/new-engine.md) mark values sized by a stated design rule: the check counts"
           " them and the results resting on them (page-1 caveat, JSON caveat `estimates`).",
           "* Unknown sheets, parameters and columns are errors (typos must not be ignored);"
           " the sheet `Notes` is free text.",
           "* **Choice** columns accept only the listed values, compared ignoring case, spaces,"
           " hyphens and underscores (`AS16` = `as16`, `Tri Metal` = `tri-metal`), plus the"
           " other spellings listed under each table. Anything else is an input error that"
           " names the cell, the allowed values and the closest one (\"did you mean\"); an"
           " ambiguous spelling (a clamped material `cast iron`: grey or nodular?) is an error"
           " that asks which one is meant, never a silent guess. A typo can therefore never"
           " leave a rule not evaluated unnoticed.",
           "* **Ranges**: every number is checked against two ranges declared per field"
           " (columns *valid* and *usual*, in the unit shown; an open end is `at least` /"
           " `at most`). Outside *valid* the calculations cannot run meaningfully (overflow,"
           " a grid that would take hours, a temperature below absolute zero, a unit slip of"
           " orders of magnitude): an **input error** with the cell. Outside *usual*, the range"
           " of crank-train engines from small high-speed engines to marine two-strokes, the"
           " check runs and the value is reported as a **warning** with its cell (often a unit"
           " slip such as a bore in `in` instead of `mm`).",
           f"* The swept speed grid (minimum..maximum speed in speed steps, plus the overspeed)"
           f" may have at most {MAX_SPEEDS} speeds (error) and usually has at most"
           f" {USUAL_SPEEDS} (warning). A table sheet with more data rows than its stated"
           " maximum is an error.", ""]
    for s in SHEETS.values():
        req = " (required)" if s.required else ""
        out += [f"## {s.name}{req}", "", s.note, ""]
        if s.shape == "notes":
            continue
        head = "parameter" if s.shape == "parameters" else "column"
        out += [f"| {head} | kind | required | check | valid | usual | note |",
                "|---|---|---|---|---|---|---|"]
        for f in s.fields:
            kind = _kind(f.kind)
            if f.choices:
                kind += ": " + ", ".join(f"`{c}`" for c in f.choices)
            valid = f.valid.text() if f.valid else ""
            usual = f.usual.text() if f.usual else ""
            out.append(f"| {f.label} | {kind} | {'yes' if f.required else ''} |"
                       f" {f.check or ''} | {valid} | {usual} | {f.note} |")
        extra = []
        if s.key:
            extra.append(f"Values of `{s.key}` must be unique.")
        if s.max_rows is not None:
            extra.append(f"At most {s.max_rows} data rows.")
        if s.dense_rows is not None:
            extra.append(f"Any number of data rows (more than {s.dense_rows}: a warning).")
        for f in s.fields:
            shown = [(a, c) for a, c in f.aliases if choice_key(a) != choice_key(c)]
            if shown:
                extra.append(f"Also accepted for *{f.label}*: " + ", ".join(
                    f"`{a}` (= `{c}`)" for a, c in shown) + ".")
            for spelling, options in f.ambiguous:
                extra.append(f"*{f.label}* `{spelling}` is refused as ambiguous: give "
                             + " or ".join(f"`{c}`" for c in options) + ".")
        for text in extra:
            out += ["", text]
        out.append("")
    return "\n".join(out)


if __name__ == "__main__":  # pragma: no cover
    print(workbook_markdown(), end="")
