"""Design levers as data: which workbook inputs a designer moves to fix a rule.

Levers live beside the rules (``rules/levers.toml``, a ``[[lever]]`` file loaded and validated
with the rule table) and can be added to or restricted by a user file of the same format
(``checker check --remedies --levers FILE``; ``enabled = false`` removes a lever by id).

A lever addresses its input the way a study file does (sheet, row or ``where``, column, unit:
:mod:`checker.study.spec`); the row ``"{item}"`` is the row of the result's own item (the
bearing ``BE1``, the joint ``crank nose``). Cells are found with
:func:`checker.study.apply.resolve` and changed with :meth:`RawWorkbook.with_values`.
"""

from __future__ import annotations

import fnmatch
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import RuleFileError
from ..workbook.schema import SHEETS, Field

DIRECTIONS = ("increase", "decrease", "either")
ITEM = "{item}"
_KEYS = {"id", "name", "rules", "items", "sheet", "row", "where", "column", "unit",
         "direction", "bounds", "limits", "choices", "default", "separable", "note", "enabled",
         "when"}


@dataclass(frozen=True)
class Lever:
    """One design lever (validated)."""

    id: str
    name: str
    rules: tuple[str, ...]  # rule ids or family prefixes
    sheet: str
    columns: tuple[Field, ...]  # one field; several for a multi-column discrete choice
    row: str | None = None  # parameter name, table key, or "{item}"
    where: tuple[tuple[str, str], ...] = ()
    items: tuple[str, ...] = ()  # glob patterns on the result item ("" = every item)
    unit: str = ""
    direction: str = "either"
    bounds: tuple[float, float] | None = None  # factors on today's value
    limits: tuple[float, float] | None = None  # absolute, in unit
    choices: tuple[Any, ...] = ()  # numbers/texts, or dicts {column label: value}
    default: float | None = None
    separable: bool = False
    note: str = ""
    origin: str = ""
    when: tuple[tuple[Field, tuple[str, ...]], ...] = ()  # the row's choice must be one of


    @property
    def discrete(self) -> bool:
        return bool(self.choices)

    @property
    def kind(self) -> str:
        return self.columns[0].kind

    def applies(self, rule_id: str, item: str) -> bool:
        """True when this lever can fix the result (rule, item)."""
        if not any(rule_id.startswith(r) for r in self.rules):
            return False
        if not self.items:
            return True
        it = item.lower()
        return any(fnmatch.fnmatchcase(it, p.lower()) for p in self.items)

    def holds_for(self, row_values: dict[str, Any]) -> bool:
        """True when the row's values (``{field attr: raw cell value}``) meet ``when``."""
        from ..workbook.schema import ChoiceProblem, resolve_choice

        for f, allowed in self.when:
            v = row_values.get(f.attr)
            try:
                choice = resolve_choice(f, v) if v is not None else None
            except ChoiceProblem:
                return False
            if choice not in allowed:
                return False
        return True

    def where_text(self) -> str:
        """Where the input is, as users read it: ``Bearings, radial clearance of BE1``."""
        cols = " and ".join(f.label for f in self.columns)
        if SHEETS[self.sheet].shape == "parameters":
            return f"{self.sheet}: {cols}"
        rows = ("the result's row" if self.row == ITEM else self.row or
                ", ".join(f"{k} = {v}" for k, v in self.where) or "every row")
        return f"{self.sheet}: {cols} ({rows})"


def _j300_order(grade: str) -> tuple[float, float]:
    from ..calc.viscosity import j300_order

    return j300_order(grade)


CHOICE_ORDERS: dict[tuple[str, str], Any] = {("Oil", "grade"): _j300_order}
"""Text inputs whose choices have a physical order, by (sheet, field attribute): a key
function (raises ValueError for a text it does not know). The oil grade ranks by its SAE J300
viscosity (HTHS at 150 C, then kinematic at 100 C), so a lever's grades are tried thinner to
thicker whatever their order in the file, and today's grade need not be one of them."""


def _preload_fraction_default(row_values: dict[str, Any]) -> float | None:
    from ..calc.bolted_joint import PRELOAD_FRACTIONS
    from ..workbook.schema import ChoiceProblem, resolve_choice

    try:
        method = resolve_choice(_field("Joints", "tightening"), row_values.get("tightening"))
    except (ChoiceProblem, TypeError):
        return None
    frac = PRELOAD_FRACTIONS.get(method)
    return None if frac is None else frac[0]


ROW_DEFAULTS: dict[tuple[str, str], tuple[tuple[str, ...], Any]] = {
    ("Joints", "preload_fraction"): (("tightening",), _preload_fraction_default),
}
"""Blank cells whose calculation default depends on another cell of the row, by (sheet,
field attribute): (the attributes it reads, a function of ``{attr: raw value}`` giving the
default in the field's unit, or None). A blank preload fraction is the tightening method's
fraction of Bell, Ricardo 2013 (:data:`checker.calc.bolted_joint.PRELOAD_FRACTIONS`)."""


def row_needs(lever: Lever) -> tuple[str, ...]:
    """Field attributes of the result's row the lever needs to know (``when``, defaults)."""
    out = [f.attr for f, _ in lever.when]
    if lever.default is None and len(lever.columns) == 1:
        out += ROW_DEFAULTS.get((lever.sheet, lever.columns[0].attr), ((), None))[0]
    return tuple(dict.fromkeys(out))


def row_default(lever: Lever, row_values: dict[str, Any]) -> float | None:
    """Today's value of the lever's blank cell from the row's other cells (``ROW_DEFAULTS``)."""
    if lever.default is not None or len(lever.columns) != 1:
        return lever.default
    entry = ROW_DEFAULTS.get((lever.sheet, lever.columns[0].attr))
    return None if entry is None else entry[1](row_values)


def choice_order(lever: Lever) -> Any:
    """The key function ranking the lever's text choices, or None (the order given)."""
    if len(lever.columns) != 1:
        return None
    return CHOICE_ORDERS.get((lever.sheet, lever.columns[0].attr))


def _field(sheet: str, name: str | None) -> Field | None:
    norm = (name or "").strip().lower()
    for f in SHEETS[sheet].fields:
        if norm in (f.label.lower(), f.attr.lower()):
            return f
    return None


def _pair(v: Any) -> tuple[float, float] | None:
    if (isinstance(v, list) and len(v) == 2 and all(isinstance(x, (int, float))
                                                   and not isinstance(x, bool) for x in v)
            and v[0] < v[1]):
        return float(v[0]), float(v[1])
    return None


def parse_lever(raw: Any, origin: str, problems: list[str], rule_ids: set[str] | None = None
                ) -> Lever | None:
    """Validate one ``[[lever]]`` table; problems are appended (with the file and lever id)."""
    from ..workbook.units import UnitProblem, to_si

    if not isinstance(raw, dict):
        problems.append(f"{origin}: [[lever]] entries must be tables")
        return None
    lid = str(raw.get("id", "?"))
    pre = f"{origin}: lever {lid}"
    bad = [k for k in raw if k not in _KEYS]
    if bad:
        problems.append(f"{pre}: unknown key '{bad[0]}' (known: {', '.join(sorted(_KEYS))})")
        return None
    if raw.get("enabled") is False:  # a removal entry needs only the id
        return Lever(lid, "", (), "Engine", (), origin=origin, note="__disabled__")
    for k in ("id", "rules", "sheet", "direction"):
        if k not in raw:
            problems.append(f"{pre}: missing '{k}'")
            return None
    if not re.match(r"^[a-z0-9][a-z0-9-]*$", lid):
        problems.append(f"{pre}: id must be lower case words joined by hyphens")
        return None
    rules = raw["rules"]
    rules = [rules] if isinstance(rules, str) else rules
    if not isinstance(rules, list) or not rules or not all(isinstance(r, str) for r in rules):
        problems.append(f"{pre}: 'rules' must be a list of rule ids or prefixes")
        return None
    rules = [r.strip().upper() for r in rules]
    if rule_ids is not None:
        for r in rules:
            if not any(x == r or x.startswith(r) for x in rule_ids):
                problems.append(f"{pre}: '{r}' matches no rule id of the rule table")
                return None
    sheet = next((s for s in SHEETS if s.lower() == str(raw["sheet"]).strip().lower()), None)
    if sheet is None or SHEETS[sheet].shape == "notes":
        problems.append(f"{pre}: unknown sheet '{raw['sheet']}'")
        return None
    spec = SHEETS[sheet]
    direction = str(raw["direction"]).strip().lower()
    if direction not in DIRECTIONS:
        problems.append(f"{pre}: direction must be one of {', '.join(DIRECTIONS)}")
        return None
    choices = raw.get("choices", [])
    if not isinstance(choices, list):
        problems.append(f"{pre}: 'choices' must be a list")
        return None
    # columns: the 'column' (table) or 'row' (parameter sheet), or the keys of table choices
    cols: list[Field] = []
    if choices and all(isinstance(c, dict) for c in choices):
        names = list(dict.fromkeys(k for c in choices for k in c))
        for n in names:
            f = _field(sheet, n)
            if f is None:
                problems.append(f"{pre}: sheet {sheet} has no column '{n}'")
                return None
            cols.append(f)
        if any(set(c) != set(names) for c in choices):
            problems.append(f"{pre}: every choice must give the same columns")
            return None
    else:
        name = raw.get("row") if spec.shape == "parameters" else raw.get("column")
        f = _field(sheet, name)
        if f is None:
            what = "parameter" if spec.shape == "parameters" else "column"
            problems.append(f"{pre}: sheet {sheet} has no {what} '{name}'")
            return None
        cols.append(f)
    row = raw.get("row") if spec.shape == "table" else None
    where: tuple[tuple[str, str], ...] = ()
    if spec.shape == "table":
        w = raw.get("where")
        if w is not None:
            if not isinstance(w, dict) or not w:
                problems.append(f"{pre}: 'where' must be a table such as {{ role = \"flywheel\" }}")
                return None
            wl = []
            for k, v in w.items():
                wf = _field(sheet, k)
                if wf is None:
                    problems.append(f"{pre}: sheet {sheet} has no column '{k}'")
                    return None
                wl.append((wf.attr, str(v)))
            where = tuple(wl)
        if row is None and not where:
            problems.append(f"{pre}: name the row: 'row' (\"{ITEM}\" or a key) or 'where'")
            return None
    unit = str(raw.get("unit", "")).strip()
    numeric = [f for f in cols if f.kind not in ("text", "choice", "int_list", "int")]
    for f in numeric:
        try:
            to_si(1.0, unit or None, f.kind)
        except UnitProblem as exc:
            problems.append(f"{pre}: unit '{unit}' does not fit {f.label}: {exc}")
            return None
    bounds = limits = None
    if "bounds" in raw:
        bounds = _pair(raw["bounds"])
        if bounds is None or bounds[0] <= 0:
            problems.append(f"{pre}: 'bounds' must be [low, high] factors on today's value,"
                            " 0 < low < high")
            return None
    if "limits" in raw:
        limits = _pair(raw["limits"])
        if limits is None:
            problems.append(f"{pre}: 'limits' must be [low, high] in {unit or '-'}")
            return None
    if not choices and bounds is None and limits is None:
        problems.append(f"{pre}: give 'bounds' (factors), 'limits' (in {unit or '-'}) or"
                        " 'choices'")
        return None
    if not choices and cols[0].kind in ("text", "choice"):
        problems.append(f"{pre}: {cols[0].label} is not a number: give 'choices'")
        return None
    items = raw.get("items", [])
    items = [items] if isinstance(items, str) else items
    default = raw.get("default")
    if default is not None and (isinstance(default, bool) or not isinstance(default, (int, float))):
        problems.append(f"{pre}: 'default' must be a number in {unit or '-'}")
        return None
    when = []
    if "when" in raw:
        w = raw["when"]
        if spec.shape != "table" or row != ITEM or not isinstance(w, dict) or not w:
            problems.append(f"{pre}: 'when' must be a table such as {{ tightening ="
                            f" [\"torque\"] }} on a table lever of row \"{ITEM}\"")
            return None
        for k, v in w.items():
            wf = _field(sheet, k)
            if wf is None or wf.kind != "choice":
                problems.append(f"{pre}: 'when': sheet {sheet} has no choice column '{k}'")
                return None
            vals = [v] if isinstance(v, str) else v
            from ..workbook.schema import ChoiceProblem, resolve_choice

            try:
                allowed = tuple(resolve_choice(wf, x) for x in vals)
            except (ChoiceProblem, TypeError) as exc:
                problems.append(f"{pre}: 'when' {k}: {exc}")
                return None
            when.append((wf, allowed))
    order = CHOICE_ORDERS.get((sheet, cols[0].attr)) if len(cols) == 1 else None
    for c in choices if order is not None else ():
        try:
            order(str(c))
        except ValueError as exc:
            problems.append(f"{pre}: choice '{c}': {exc}")
            return None
    return Lever(lid, str(raw.get("name") or cols[0].label), tuple(rules), sheet, tuple(cols),
                 row=None if row is None else str(row), where=where,
                 items=tuple(str(x) for x in items), unit=unit, direction=direction,
                 bounds=bounds, limits=limits, choices=tuple(choices),
                 default=None if default is None else float(default),
                 separable=bool(raw.get("separable", False)), note=str(raw.get("note", "")),
                 origin=origin, when=tuple(when))


def parse_lever_doc(doc: dict, origin: str, problems: list[str],
                    rule_ids: set[str] | None = None) -> list[Lever]:
    entries = doc.get("lever")
    if not isinstance(entries, list) or not entries:
        problems.append(f"{origin}: expected one or more [[lever]] tables")
        return []
    out = []
    for raw in entries:
        lv = parse_lever(raw, origin, problems, rule_ids)
        if lv is not None:
            out.append(lv)
    return out


def merge(base: list[Lever], extra: list[Lever]) -> list[Lever]:
    """``base`` with the user's levers: same id replaces, ``enabled = false`` removes."""
    out = {lv.id: lv for lv in base}
    for lv in extra:
        if lv.note == "__disabled__":
            out.pop(lv.id, None)
        else:
            out[lv.id] = lv
    return list(out.values())


def load_levers(path: str | Path | None = None, rule_ids: set[str] | None = None
                ) -> list[Lever]:
    """Levers of a ``[[lever]]`` file (``None`` = ``rules/levers.toml`` of the default table).

    Raises :class:`RuleFileError` listing every problem."""
    from ..plumbing.resources import rules_dir as default_rule_dir

    p = Path(path) if path is not None else default_rule_dir() / "levers.toml"
    if not p.is_file():
        raise RuleFileError([f"{p}: lever file not found"])
    try:
        doc = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise RuleFileError([f"{p.name}: not valid TOML: {exc}"]) from None
    problems: list[str] = []
    out = parse_lever_doc(doc, p.name, problems, rule_ids)
    ids = [lv.id for lv in out]
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if dup:
        problems.append(f"{p.name}: duplicate lever id {dup[0]}")
    if problems:
        raise RuleFileError(problems)
    return out


@dataclass
class LeverSet:
    levers: list[Lever] = field(default_factory=list)

    def for_result(self, rule_id: str, item: str) -> list[Lever]:
        return [lv for lv in self.levers if lv.applies(rule_id, item)]
