"""The rule table: loading and validating rule files (TOML), workbook overrides, evaluation.

A rule names a quantity of the calculation graph, where it applies (item attributes and
coordinates such as the operating point or load case), a comparison and a limit with its unit,
a severity, its source and a one-line rationale. ``docs/rules.md`` lists every rule of the
default table (generated from ``rules/*.toml`` by ``scripts/make_rules_doc.py``).
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from .. import modules as _modules  # noqa: F401  (registers the quantities rules name
from ..description.engine import Engine
from ..errors import InputError, InputErrors, RuleFileError, UsageProblem
from ..results import display
from ..workbook.units import convert_affine, from_si
from .graph import QUANTITIES, Quantity, QuantitySpec, ensure_registered

ID_PATTERN = re.compile(r"^[A-Z]{2,5}-\d{3}$")
CHECKS = (">=", "<=", ">", "<", "between")
SEVERITIES = ("error", "warning")
REQUIRED = ("id", "name", "quantity", "check", "unit", "severity", "source", "rationale")
OPTIONAL = ("limit", "limit_by", "limits", "limit_from", "where", "applies_to", "status",
            "method")
LIMIT_FROM = ("workbook",)
"""Values of ``limit_from``: ``workbook`` = the limit is the engine's own (a workbook value
such as a balancing limit or a target), carried by the quantity per item (item attributes
``limit`` in SI, ``limit_cell``, and ``limit_missing`` when not given)."""
REL_TOL = 1e-9
"""Values within this relative distance of a limit count as on the limit (float noise)."""
SCOPE_ATTRIBUTES = ("location", "type", "role", "kind", "order")
"""Item attributes that say what an item *is* (the crank-nose joint, a main bearing): a rule
filtering on them (``where = { location = "crank nose" }``) is about other items, and the
items it leaves out get no line. An item left out by any other attribute (a joint's
tightening method, a bearing's lining) is one the rule would judge but does not apply to:
it is listed as *not applicable* with the reason, as is an item none of whose points the
quantity judges (``Quantity.applies``), and a rule that applies to nothing in the engine."""


@dataclass(frozen=True)
class Rule:
    id: str
    name: str
    quantity: str
    check: str
    unit: str  # display unit of limit and value ("" dimensionless)
    severity: str
    source: str
    rationale: str
    limit: tuple[float, ...] | None = None  # display units; 1 value or (low, high)
    limit_by: str | None = None
    limits: dict[str, tuple[float, ...]] = field(default_factory=dict)
    where: dict[str, tuple[str, ...]] = field(default_factory=dict)
    applies_to: str = ""
    origin: str = ""
    limit_from: str | None = None  # "workbook": per-engine limit carried by the quantity
    method: str | None = None  # method tag of a film-thickness limit (selects the quantity)
    not_applicable: str | None = None  # the project's reason (RuleOverrides 'not applicable')

    def limit_text(self, limit: tuple[float, ...] | None = None) -> str:
        """The limit as displayed (``≤ 48 MPa``, ``≥ 1.2 µm``, ``70..75 %``)."""
        lim = self.limit if limit is None else limit
        if lim is None:
            if self.limit_from == "workbook":
                if self.check == "between":
                    return "within the workbook range"
                sym = {">=": "≥", "<=": "≤", ">": ">", "<": "<"}[self.check]
                return f"{sym} workbook limit"
            if self.limit_by == "engine_class":
                return "; ".join(f"{display.limit_text(self.check, v, self.unit)} ({k})"
                                 for k, v in self.limits.items()) + "; other classes:" \
                    " project limit"
            return f"by {self.limit_by.replace('_', ' ')}" if self.limit_by else "-"
        return display.limit_text(self.check, lim, self.unit)


@dataclass(frozen=True)
class Override:
    rule: str
    old: str
    new: str
    reason: str
    where: str


@dataclass
class RuleTable:
    rules: list[Rule]
    files: list[str]
    overrides: list[Override] = field(default_factory=list)
    levers: list = field(default_factory=list)  # design levers (checker.description.levers)

    def get(self, rule_id: str) -> Rule:
        for r in self.rules:
            if r.id == rule_id:
                return r
        raise KeyError(rule_id)


def default_rule_dir() -> Path:
    """The installed default rule table folder (``rules/`` of the project)."""
    from ..plumbing.resources import rules_dir

    return rules_dir()


def _as_tuple(v: Any) -> tuple[float, ...] | None:
    if isinstance(v, bool):
        return None
    if isinstance(v, (int, float)):
        return (float(v),)
    if isinstance(v, list) and len(v) == 2 and all(
            isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
        return (float(v[0]), float(v[1]))
    return None


def _parse_rule(raw: dict, origin: str, problems: list[str]) -> Rule | None:
    rid = raw.get("id", "?")
    pre = f"{origin}: rule {rid}"
    bad = False
    for k in REQUIRED:
        if k not in raw or (isinstance(raw[k], str) and not raw[k].strip() and k != "unit"):
            problems.append(f"{pre}: missing '{k}'")
            bad = True
    for k in raw:
        if k not in REQUIRED and k not in OPTIONAL:
            problems.append(f"{pre}: unknown key '{k}'")
            bad = True
    if bad:
        return None
    if not isinstance(rid, str) or not ID_PATTERN.match(rid):
        problems.append(f"{pre}: id must look like 'JNT-001' (family prefix, dash, 3 digits)")
        return None
    ensure_registered()
    spec = QUANTITIES.get(raw["quantity"])
    if spec is None:
        problems.append(f"{pre}: unknown quantity '{raw['quantity']}' (known: "
                        + ", ".join(sorted(QUANTITIES)) + ")")
        return None
    method = raw.get("method")
    if spec.methods:
        # a film-thickness limit is only meaningful with the method it was calibrated to
        if method not in spec.methods:
            problems.append(f"{pre}: a limit on {spec.name} must say which method it belongs"
                            f" to: method = one of {', '.join(repr(m) for m in spec.methods)}"
                            + (f", found {method!r}" if method is not None else ""))
            return None
        target = spec.methods[method]
        if spec.name != "bearing.moft" and spec.name != target:
            problems.append(f"{pre}: method '{method}' is judged on {target}, but the rule"
                            f" names {spec.name}")
            return None
        spec = QUANTITIES[target]
    elif method is not None:
        problems.append(f"{pre}: 'method' applies only to method-tagged quantities")
        return None
    check = raw["check"]
    if check not in CHECKS:
        problems.append(f"{pre}: check must be one of {', '.join(CHECKS)}, found '{check}'")
        return None
    if raw["severity"] not in SEVERITIES:
        problems.append(f"{pre}: severity must be 'error' or 'warning', found"
                        f" '{raw['severity']}'")
        return None
    unit = str(raw["unit"]).strip()
    unit = "" if unit in ("-", "1") else unit
    try:
        convert_affine(spec.unit or "", unit.replace("%", "percent"))
    except Exception:
        problems.append(f"{pre}: unit '{raw['unit']}' does not fit quantity {spec.name}"
                        f" (SI unit '{spec.unit or '-'}')")
        return None
    n_lim = 2 if check == "between" else 1
    limit = None
    limits: dict[str, tuple[float, ...]] = {}
    if "limit" in raw:
        limit = _as_tuple(raw["limit"])
        if limit is None or len(limit) != n_lim:
            problems.append(f"{pre}: limit must be {'[low, high]' if n_lim == 2 else 'a number'}"
                            f" for check '{check}', found {raw['limit']!r}")
            return None
        if n_lim == 2 and limit[0] > limit[1]:
            problems.append(f"{pre}: range limit low > high")
            return None
    if "limit_by" in raw:
        if raw["limit_by"] not in spec.filters:
            problems.append(f"{pre}: limit_by '{raw['limit_by']}' is not an attribute of"
                            f" {spec.name} (one of {', '.join(spec.filters)})")
            return None
        if not isinstance(raw.get("limits"), dict) or not raw["limits"]:
            problems.append(f"{pre}: limit_by needs a 'limits' table")
            return None
        for k, v in raw["limits"].items():
            t = _as_tuple(v)
            if t is None or len(t) != n_lim:
                problems.append(f"{pre}: limits.{k} must be a number or [low, high]")
                return None
            limits[k.lower()] = t
    limit_from = raw.get("limit_from")
    if limit_from is not None:
        if limit_from not in LIMIT_FROM:
            problems.append(f"{pre}: limit_from must be one of {', '.join(LIMIT_FROM)}, found"
                            f" {limit_from!r}")
            return None
        if limit is not None or limits:
            problems.append(f"{pre}: give either 'limit_from' or a limit, not both")
            return None
    elif limit is None and not limits:
        problems.append(f"{pre}: give 'limit', 'limit_by' with 'limits', or 'limit_from'")
        return None
    where: dict[str, tuple[str, ...]] = {}
    for k, v in (raw.get("where") or {}).items():
        vals = tuple(str(x) for x in (v if isinstance(v, list) else [v]))
        if k not in spec.filters and k not in spec.dims:
            problems.append(f"{pre}: where-key '{k}' is not an attribute or dimension of"
                            f" {spec.name} (attributes: {', '.join(spec.filters) or '-'};"
                            f" dimensions: {', '.join(spec.dims)})")
            return None
        if k in spec.coords:
            for x in vals:
                if x not in spec.coords[k]:
                    problems.append(f"{pre}: where {k} = '{x}' is not one of"
                                    f" {', '.join(spec.coords[k])}")
                    return None
        where[k] = vals
    return Rule(id=rid, name=raw["name"], quantity=spec.name, check=check, unit=unit,
                method=method,
                severity=raw["severity"], source=raw["source"], rationale=raw["rationale"],
                limit=limit, limit_by=raw.get("limit_by"), limits=limits, where=where,
                applies_to=raw.get("applies_to", ""), origin=origin, limit_from=limit_from)


def load_rules(path: str | Path | None = None) -> RuleTable:
    """Load and validate a rule file or a folder of ``*.toml`` rule files.

    Raises :class:`RuleFileError` listing every problem (exit code 2 in the CLI).
    """
    p = Path(path) if path is not None else default_rule_dir()
    if p.is_dir():
        files = sorted(p.glob("*.toml"))
        if not files:
            raise RuleFileError([f"{p}: no *.toml rule files"])
    elif p.is_file():
        files = [p]
    else:
        raise RuleFileError([f"{p}: rule file not found"])
    problems: list[str] = []
    rules: list[Rule] = []
    lever_docs: list[tuple[dict, str]] = []
    for f in files:
        try:
            doc = tomllib.loads(f.read_text(encoding="utf-8"))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            problems.append(f"{f.name}: not valid TOML: {exc}")
            continue
        if "lever" in doc and "rule" not in doc:  # design levers (rules/levers.toml)
            lever_docs.append((doc, f.name))
            continue
        entries = doc.get("rule")
        if not isinstance(entries, list) or not entries:
            problems.append(f"{f.name}: expected one or more [[rule]] tables")
            continue
        for raw in entries:
            if not isinstance(raw, dict):
                problems.append(f"{f.name}: [[rule]] entries must be tables")
                continue
            r = _parse_rule(raw, f.name, problems)
            if r is not None:
                rules.append(r)
    seen: dict[str, str] = {}
    for r in rules:
        if r.id in seen:
            problems.append(f"{r.origin}: duplicate rule id {r.id} (also in {seen[r.id]})")
        seen[r.id] = r.origin
    levers = []
    if lever_docs:
        from ..description.levers import parse_lever_doc

        for doc, name in lever_docs:
            levers += parse_lever_doc(doc, name, problems, set(seen))
    if problems:
        raise RuleFileError(problems)
    rules.sort(key=lambda r: r.id)
    return RuleTable(rules, [str(f) for f in files if f.name not in
                             {n for _, n in lever_docs}], levers=levers)


def _parse_limit(text: str) -> tuple[float, ...] | None:
    t = text.strip().replace("–", "..").replace(" ", "")
    m = re.match(r"^([+-]?[\d.eE+-]+?)(?:\.\.|-(?=\d))([+-]?[\d.eE+-]+)$", t)
    try:
        if m:
            return (float(m.group(1)), float(m.group(2)))
        return (float(t),)
    except ValueError:
        return None


NOT_APPLICABLE_WORDS = ("not applicable", "n/a", "na")
"""A RuleOverrides limit that declares the rule not applicable to the project (its reason is
required and shown with every result of the rule)."""


def override_problems(table: RuleTable, overrides) -> tuple[list[Rule], list[Override],
                                                             list[InputError]]:
    """Resolve workbook RuleOverrides against ``table``: the new rule list, the applied
    overrides and every problem (unknown rule, bad limit, unit) with its cell."""
    errs: list[InputError] = []
    rules = list(table.rules)
    applied: list[Override] = []
    by_id = {r.id: i for i, r in enumerate(rules)}
    for o in overrides:
        rid = o.rule.strip().upper()
        if rid not in by_id:
            import difflib

            near = difflib.get_close_matches(rid, list(by_id), n=1)
            hint = f"; did you mean '{near[0]}'?" if near else " (see 'checker rules')"
            errs.append(InputError(o.where or "RuleOverrides", f"unknown rule '{o.rule}'{hint}"))
            continue
        r = rules[by_id[rid]]
        if str(o.limit).strip().lower() in NOT_APPLICABLE_WORDS:
            if not str(o.reason or "").strip():
                errs.append(InputError(o.where or "RuleOverrides", f"{r.id} declared not"
                                       " applicable: expected the reason why (column reason),"
                                       " found nothing"))
                continue
            rules[by_id[rid]] = replace(r, not_applicable=str(o.reason).strip())
            applied.append(Override(r.id, r.limit_text(), "not applicable", o.reason,
                                    o.where))
            continue
        lim = _parse_limit(o.limit)
        n = 2 if r.check == "between" else 1
        if lim is None or len(lim) != n or not all(math.isfinite(x) for x in lim):
            errs.append(InputError(o.where or "RuleOverrides", f"limit for {r.id} must be"
                                   f" {'a range low..high' if n == 2 else 'a number'},"
                                   f" found '{o.limit}'"))
            continue
        unit = (o.unit or r.unit or "").strip()
        unit = "" if unit in ("-", "1") else unit
        try:
            factor = _affine((unit or "").replace("%", "percent"), r.unit)
        except Exception:
            errs.append(InputError(o.where or "RuleOverrides", f"unit '{o.unit}' does not fit"
                                   f" rule {r.id} (limit in '{r.unit or '-'}')"))
            continue
        new = tuple(float(factor(x)) for x in lim)
        old_text = r.limit_text()
        rules[by_id[rid]] = replace(r, limit=new, limit_by=None, limits={}, limit_from=None)
        applied.append(Override(r.id, old_text, rules[by_id[rid]].limit_text(), o.reason,
                                o.where))
    return rules, applied, errs


def apply_overrides(table: RuleTable, engine: Engine) -> RuleTable:
    """Replace limits with the workbook's RuleOverrides; every change is recorded."""
    rules, applied, errs = override_problems(table, engine.overrides)
    if errs:
        raise InputErrors(errs)
    return RuleTable(rules, table.files, applied, table.levers)


def select_rules(table: RuleTable, select: list[str] | None, ignore: list[str] | None
                 ) -> list[Rule]:
    """Rules whose id starts with a ``select`` prefix and with no ``ignore`` prefix.

    Prefixes are case-insensitive (``jnt`` = ``JNT``). Raises :class:`UsageProblem` for a
    selector that matches no rule.
    """
    def matches(r: Rule, s: str) -> bool:
        return r.id.startswith(s)

    select = [x.strip().upper() for x in select] if select else None
    ignore = [x.strip().upper() for x in ignore] if ignore else None
    for s in (select or []) + (ignore or []):
        if not any(matches(r, s) for r in table.rules):
            raise UsageProblem(f"'{s}' matches no rule id (see 'checker rules')")
    chosen = [r for r in table.rules if not select or any(matches(r, s) for s in select)]
    return [r for r in chosen if not any(matches(r, s) for s in (ignore or []))]


# ------------------------------------------------------------------ evaluation
@dataclass
class RuleResult:
    rule: str
    name: str
    item: str
    status: str  # "pass" | "fail" | "not_evaluated" | "not_applicable"
    severity: str
    value: float | None
    unit: str
    limit: str
    limit_values: list[float] | None
    margin: float | None
    case: str
    message: str
    source: str
    missing: list[str] = field(default_factory=list)
    findings: list[str] = field(default_factory=list)
    internal_error: bool = False  # the calculation ran but produced no number (NaN/inf)
    compare: dict[str, float] = field(default_factory=dict)  # other methods at the point
    judged_on: str = ""  # which of ``compare`` the rule judged (method-tagged quantities)
    check: str = ""  # the rule's comparison (">=", "<=", ">", "<", "between")
    override: str = ""  # how the workbook's RuleOverrides changed the limit ("" if not)
    what_it_takes: str = ""  # smallest lever change that passes + side effects (--remedies)
    worst_corner: str = ""  # value and corner at the tolerance corners (--corners)
    limit_missing: list[str] = field(default_factory=list)
    """The workbook limit that is missing (texts naming its cells, as in ``missing``): a
    result not evaluated for it stays so while those cells stay blank."""

    @property
    def value_text(self) -> str:
        """The value with its unit as displayed (digits enough to differ from the limit)."""
        near = self.limit_values[0] if self.limit_values else None
        if self.limit_values and len(self.limit_values) == 2 and self.value is not None:
            near = min(self.limit_values, key=lambda x: abs(x - self.value))
        return display.with_unit(self.value, self.unit, distinct_from=near)

    @property
    def margin_text(self) -> str:
        """The distance to the limit in words ("limit exceeded by 11 %"); empty for a result
        that was not judged (not evaluated, not applicable)."""
        if self.status not in ("pass", "fail"):
            return ""
        return display.margin_words(self.check, self.value, self.limit_values, self.margin,
                                    self.status == "pass", self.unit)

    def as_dict(self) -> dict[str, Any]:
        return {
            "rule": self.rule, "name": self.name, "item": self.item, "status": self.status,
            "severity": self.severity,
            "value": None if self.value is None else float(f"{self.value:.6g}"),
            "unit": self.unit, "limit": self.limit_values, "limit_text": self.limit,
            "margin": None if self.margin is None else float(f"{self.margin:.4g}"),
            "case": self.case, "message": self.message, "source": self.source,
            "missing": self.missing, "findings": self.findings,
            "internal_error": self.internal_error,
            "margin_text": self.margin_text,
            "override": self.override or None,
            "compare": {k: float(f"{v:.6g}") for k, v in self.compare.items()} or None,
            "judged_on": self.judged_on or None,
        }


def _collect(by_index: dict[tuple, list[str]], sel: list[np.ndarray]) -> list[str]:
    """The texts of ``by_index`` (keys: leading index tuples) whose key lies in the selection
    ``sel`` (one index array per dimension), without repeats, in the order of a C-order walk
    over the selected points with the longest key first at each point."""
    if not by_index:
        return []
    first = [int(x[0]) if len(x) else 0 for x in sel]
    pos = [{int(v): k for k, v in enumerate(x)} for x in sel]
    keyed = []
    for key, texts in by_index.items():
        if not texts or len(key) > len(sel):
            continue
        try:
            order = tuple(pos[j][int(v)] for j, v in enumerate(key))
        except KeyError:  # outside the selection
            continue
        # the first selected point below this key, then longer keys first
        keyed.append((order + tuple(0 for _ in first[len(key):]), -len(key), texts))
    out: list[str] = []
    for _, _, texts in sorted(keyed, key=lambda x: (x[0], x[1])):
        for t in texts:
            if t not in out:
                out.append(t)
    return out


_PARENS = re.compile(r"\([^()]*\)")
_LOCATION = re.compile(r"^[A-Za-z][\w!$]*\s*:\s+")
_CLAUSE = re.compile(r"^(?:no|not|none)\b|\b(?:is|are|was|were|must|did|does|do|cannot|can|could"
                     r"|would|has|have|had|gives?|gave|needs?|lies|lie|meets?|met)\b", re.I)


def _item_phrase(item: str) -> str:
    """An item inside a sentence: "the engine" for the whole engine, else "'M1'"."""
    label = display.item_label(item)
    return f"the {label}" if item == display.ENGINE_ITEM else f"'{label}'"


def is_sentence(reason: str) -> bool:
    """Whether a not-evaluated reason is a clause of its own ("Joints: no bolted joints are
    given", "the engine class 'truck' has no published limit") rather than the name of a
    missing input ("Bearings!Q3: max film temperature of M1 (the shell supplier's limit)"),
    which reads after the word *missing*. Parenthesised remarks and a leading location
    ("Sheet!B3: ", "TVModel: ") are not read."""
    body = reason
    for _ in range(3):  # nested parentheses
        body = _PARENS.sub("", body)
    return bool(_CLAUSE.search(_LOCATION.sub("", body.strip(), count=1)))


def not_evaluated_message(reasons: list[str]) -> str:
    """The message of a result that is not evaluated, in sentences: ``not evaluated: missing
    A; B`` for the inputs it names, each reason that is a clause of its own as it is
    (:func:`is_sentence`), in the order given."""
    parts: list[str] = []
    inputs: list[str] = []

    def flush() -> None:
        if inputs:
            parts.append("missing " + "; ".join(inputs))
            inputs.clear()

    for r in reasons:
        if is_sentence(r):
            flush()
            parts.append(r)
        else:
            inputs.append(r)
    flush()
    return "not evaluated: " + ("; ".join(parts) or "no reason was given")


def _coord_text(dim: str, label: Any) -> str:
    if dim == "speed":
        return f"{from_si(float(label), 'rad/s', 'rpm'):.0f} rpm"
    if dim == "case":
        return {"full": "full load", "part": "part load", "no": "no load"}.get(str(label),
                                                                            str(label))
    return str(label)


def _unjudged_worst(rule: Rule, q: Quantity, sel_i: list, dims: tuple, factor
                    ) -> tuple[float | None, str]:
    """Worst value of a rule's selection in its direction (largest for an upper limit,
    smallest for a lower one) at the points the rule would judge, and where; ``(None, "")``
    for a range check or when nothing is finite."""
    if rule.check not in ("<=", "<", ">=", ">"):
        return None, ""
    sub = factor(q.values[np.ix_(*sel_i)])
    ok = np.isfinite(sub)
    if q.applies is not None:
        ok &= q.applies[np.ix_(*sel_i)]
    if not ok.any():
        return None, ""
    upper = rule.check in ("<=", "<")
    k = int(np.argmax(np.where(ok, sub, -np.inf)) if upper
            else np.argmin(np.where(ok, sub, np.inf)))
    worst = np.unravel_index(k, sub.shape)
    parts = [_coord_text(d, q.coords[d][sel_i[j][worst[j]]])
             for j, d in enumerate(dims) if d != "item"]
    return float(sub[worst]), ", ".join(parts)


def _margin(check: str, v: np.ndarray, lim: tuple[float, ...]) -> np.ndarray:
    if check in (">=", ">"):
        return (v - lim[0]) / abs(lim[0]) if lim[0] else v - lim[0]
    if check in ("<=", "<"):
        return (lim[0] - v) / abs(lim[0]) if lim[0] else lim[0] - v
    lo = (v - lim[0]) / abs(lim[0]) if lim[0] else v - lim[0]
    hi = (lim[1] - v) / abs(lim[1]) if lim[1] else lim[1] - v
    return np.minimum(lo, hi)


def _passes(check: str, margin: float) -> bool:
    if check in (">", "<"):
        return margin > 0
    return margin >= -REL_TOL


def evaluate_rule(rule: Rule, q: Quantity | None, unavailable: list[str] | None,
                  others: dict[str, Quantity] | None = None) -> list[RuleResult]:
    """Evaluate one rule on its quantity: one result per item it applies to.

    Per item, in this order: is the item selected (the rule's ``where`` filters,
    :func:`_item_selected`); which limit applies (:func:`_item_limit`: a missing limit makes
    the result ``not evaluated``); are the values there (:func:`_nonfinite_result`: a missing
    input makes it ``not evaluated``, a NaN no input explains is an internal error that
    fails); and finally the judgement at the worst judged point (:func:`_judge`).

    ``others`` holds the quantities the rule's quantity is compared with
    (``QuantitySpec.compare``, e.g. the film thickness by the other method): each result
    carries their values at its judged point, and which one the rule judged."""
    spec = QUANTITIES[rule.quantity]
    base = dict(rule=rule.id, name=rule.name, severity=rule.severity, unit=rule.unit,
                source=rule.source, check=rule.check)
    if rule.not_applicable:
        return [not_applicable_result(rule, f"{rule.not_applicable} (declared by the project"
                                      " in RuleOverrides)")]
    if q is None:
        reasons = unavailable or [f"the quantity {rule.quantity} was not computed"]
        return [RuleResult(**base, item="all", status="not_evaluated", value=None,
                           limit=rule.limit_text(), limit_values=None, margin=None, case="",
                           message=not_evaluated_message(reasons),
                           missing=list(reasons))]
    dims = spec.dims
    results: list[RuleResult] = []
    items = q.coords["item"] if "item" in dims else ["all"]
    # coordinate filters
    sel = [np.arange(len(q.coords[d])) for d in dims]
    for k, vals in rule.where.items():
        if k in dims:
            d = dims.index(k)
            sel[d] = np.array([i for i, c in enumerate(q.coords[k]) if str(c) in vals], int)
    factor = _affine(spec.unit, rule.unit)
    # (item, what it has, why the rule does not apply, out of the rule's scope)
    not_applicable: list[tuple[str, str, str, bool]] = []
    for ii, item in enumerate(items):
        attrs = q.item_attrs.get(item, {})
        if "item" in dims:
            sel_i = list(sel)
            sel_i[dims.index("item")] = np.array([ii])
        else:
            sel_i = sel
        if not _item_selected(rule, attrs, dims):
            unknown = _unknown_attributes(rule, attrs, dims, item)
            if unknown:  # whether the rule applies depends on a blank cell
                results.append(_unknown_result(rule, q, item, unknown, sel_i, factor, base))
            else:
                not_applicable.append((item, *_not_selected_reason(rule, attrs, dims)))
            continue
        lim, unjudged = _item_limit(rule, q, item, attrs, sel_i, factor, base)
        if unjudged is not None:
            results.append(unjudged)
            continue
        sub = q.values[np.ix_(*sel_i)]
        if sub.size == 0 or (q.applies is not None
                             and not q.applies[np.ix_(*sel_i)].any()):
            not_applicable.append((item, *_unjudged_reason(q), False))
            continue
        if not np.isfinite(sub).all():
            results.append(_nonfinite_result(rule, q, item, sub, sel_i, lim, base))
            continue
        r = _judge(rule, spec, q, item, attrs, sub, sel_i, lim, factor, others, base)
        if r is not None:
            results.append(r)
    return results + _not_applicable(rule, q, results, not_applicable, base)


def not_applicable_result(rule: Rule, reason: str) -> RuleResult:
    """The one result of a rule whose analysis does not apply to the engine at all."""
    return RuleResult(rule=rule.id, name=rule.name, severity=rule.severity, unit=rule.unit,
                      source=rule.source, check=rule.check, item="all",
                      status="not_applicable", value=None, limit=rule.limit_text(),
                      limit_values=None, margin=None, case="",
                      message=f"not applicable: {reason}")


def _not_applicable(rule: Rule, q: Quantity, results: list[RuleResult],
                    left_out: list[tuple[str, str, str, bool]], base: dict
                    ) -> list[RuleResult]:
    """The ``not applicable`` results of a rule (never a pass, never counted as incomplete).
    ``left_out``: (item, what it has, why, out of the rule's scope) per item the rule does not
    judge. With results on other items: one per such item (those out of its scope get no
    line); with none: one for the rule, which says why it applies to nothing here."""
    def result(item: str, reason: str) -> RuleResult:
        return RuleResult(**base, item=item, status="not_applicable", value=None,
                          limit=rule.limit_text(), limit_values=None, margin=None, case="",
                          message=f"not applicable: {reason}")

    if results:
        return [result(item, f"{has}; {why}" if has else
                       f"the rule judges none of its points: {why}")
                for item, has, why, scope in left_out if not scope]
    if not left_out:
        # an empty item axis says why in the quantity's words (no barred speed range)
        return [result("all", (q.applies_text or "").rstrip(".")
                       or "the quantity has no item to judge")]
    by_why: dict[str, dict[str, list[str]]] = {}
    for item, has, why, _ in left_out:
        by_why.setdefault(why, {}).setdefault(has, []).append(item)
    parts = []
    for why, groups in by_why.items():
        if "" in groups:  # no judged point (the quantity's applies mask)
            items = groups.pop("")
            whose = ("this engine" if items == [display.ENGINE_ITEM]
                     else ", ".join(display.item_label(i) for i in items))
            parts.append(f"the rule judges no point of {whose}: {why}")
        if groups:
            have = "; ".join(f"{has} ({', '.join(display.item_label(i) for i in items)})"
                             for has, items in groups.items())
            parts.append(f"{why}; none of this engine's items does: {have}")
    return [result("all", "; ".join(parts))]


def _not_selected_reason(rule: Rule, attrs: dict, dims: tuple[str, ...]
                         ) -> tuple[str, str, bool]:
    """Why the ``where`` filters leave an item out: (what the item has, what the rule applies
    to, whether the filter is on what the item is (:data:`SCOPE_ATTRIBUTES`: out of the
    rule's scope))."""
    to = f"{rule.id} applies to {rule.applies_to or 'other items'}"
    for k, vals in rule.where.items():
        if k in dims:
            continue
        v = attrs.get(k)
        if str(v) in vals or str(v).lower() in [x.lower() for x in vals]:
            continue
        label = k.replace("_", " ")
        if not rule.applies_to:
            to = f"{rule.id} applies to {label} {' or '.join(vals)}"
        have = f"its {label} is '{v}'" if v not in (None, "") else f"its {label} is not given"
        return have, to, k in SCOPE_ATTRIBUTES
    return "it is not one of its items", to, False


def _unknown_attributes(rule: Rule, attrs: dict, dims: tuple[str, ...], item: str
                        ) -> list[str]:
    """The inputs an item lacks to tell whether the rule applies to it: a ``where`` filter
    on an attribute that is not given (a bearing's lining left blank: the sputter guideline
    BRG-005 may apply), named by the quantity's ``<attribute>_missing`` (the cell to fill
    in); empty when the item's given attributes decide (among them one that puts it out of
    the rule's scope, :data:`SCOPE_ATTRIBUTES`)."""
    unknown: list[str] = []
    for k, vals in rule.where.items():
        if k in dims:
            continue
        v = attrs.get(k)
        if v in (None, ""):
            if k in SCOPE_ATTRIBUTES:
                return []
            unknown += list(attrs.get(f"{k}_missing") or [
                f"{k.replace('_', ' ')} of {_item_phrase(item)}"])
        elif str(v).lower() not in [x.lower() for x in vals]:
            return []  # a given attribute the rule does not apply to
    return unknown


def _unknown_result(rule: Rule, q: Quantity, item: str, unknown: list[str], sel_i: list,
                    factor, base: dict) -> RuleResult:
    """``not evaluated`` for an item whose blank cells leave open whether the rule applies
    (:func:`_unknown_attributes`), with the worst computed value, not judged."""
    value, where_txt = _unjudged_worst(rule, q, sel_i, q.spec.dims, factor)
    msg = not_evaluated_message(unknown)
    if value is not None:
        msg += (f" (computed, not judged: {display.with_unit(value, rule.unit)}"
                + (f" at {where_txt}" if where_txt else "") + ")")
    return RuleResult(**base, item=item, status="not_evaluated", value=value,
                      limit=rule.limit_text(), limit_values=None, margin=None, case=where_txt,
                      message=msg, missing=unknown)


def _unjudged_reason(q: Quantity) -> tuple[str, str]:
    """Why no point of an item is judged: ("", the quantity's ``applies_text``)."""
    text = (q.applies_text or "").rstrip(".")
    return "", (text or "the quantity marks none of its points as judged")


def _item_selected(rule: Rule, attrs: dict, dims: tuple[str, ...]) -> bool:
    """Whether an item passes the rule's ``where`` filters on item attributes (bearing type,
    lining...; case-insensitive); filters on coordinates are applied to the selection."""
    return not any(k not in dims and str(attrs.get(k)) not in vals and
                   str(attrs.get(k)).lower() not in [v.lower() for v in vals]
                   for k, vals in rule.where.items())


def _item_limit(rule: Rule, q: Quantity, item: str, attrs: dict, sel_i: list, factor,
                base: dict) -> tuple[tuple[float, ...], RuleResult | None]:
    """The limit that applies to one item (in the rule's unit), or the ``not evaluated``
    result when there is none: no limit for the item's class/lining (``limit_by``), or no
    engine limit in the workbook (``limit_from = "workbook"``). The not-evaluated result
    still reports the worst computed value in the rule's direction, not judged."""
    dims = q.spec.dims
    lim = rule.limit
    why: list[str] = []
    no_limit: list[str] = []
    limit_text = rule.limit_text()
    if rule.limit_by is not None:
        key = str(attrs.get(rule.limit_by) or "").lower()
        lim = rule.limits.get(key)
        if lim is None:
            if rule.limit_by == "engine_class" and key:
                why = [f"no published limit for a {key} engine: the limit of {rule.id} is"
                       f" for {' and '.join(rule.limits)} engines"
                       f" ({_source_short(rule.source)}); enter the project's limit in"
                       f" RuleOverrides (engine class from"
                       f" {attrs.get('engine_class_cell') or 'sheet Engine'})"]
                limit_text = "project limit"
            elif not key:  # the cell to fill in, where the quantity names it
                why = list(attrs.get(f"{rule.limit_by}_missing") or [
                    f"no {rule.limit_by.replace('_', ' ')} is given for {_item_phrase(item)}"])
            else:
                why = [f"{rule.limit_by.replace('_', ' ')} '{key}' of"
                       f" {_item_phrase(item)} has no limit in rule {rule.id} (known:"
                       f" {', '.join(rule.limits)}); add a RuleOverrides row"]
    if not why and rule.limit_from == "workbook":
        # the engine's own limit, carried by the quantity (SI, converted to the rule unit)
        given = attrs.get("limit")
        n_lim = 2 if rule.check == "between" else 1
        if given is None or len(tuple(given)) != n_lim:
            no_limit = list(attrs.get("limit_missing") or [])
            why = list(no_limit) or [f"no limit for {_item_phrase(item)} is given in"
                                     " the workbook"]
            why += [m for m in _collect(q.missing, sel_i) if m not in why]
        else:
            lim = tuple(float(factor(float(x))) for x in given)
    if not why:
        return lim, None
    # reported but not judged: the worst value in the rule's direction
    value, where_txt = _unjudged_worst(rule, q, sel_i, dims, factor)
    msg = not_evaluated_message(why)
    if value is not None:
        msg += (f" (computed, not judged: {display.with_unit(value, rule.unit)}"
                + (f" at {where_txt}" if where_txt else "") + ")")
    return lim, RuleResult(**base, item=item, status="not_evaluated", value=value,
                           limit=limit_text, limit_values=None, margin=None, case=where_txt,
                           message=msg, missing=why, limit_missing=no_limit)


def _nonfinite_result(rule: Rule, q: Quantity, item: str, sub: np.ndarray, sel_i: list,
                      lim: tuple[float, ...], base: dict) -> RuleResult:
    """The result of an item with non-finite values: ``not evaluated`` where missing inputs
    explain them; anywhere else the calculation ran and failed: an internal error of this
    result, which fails (never a missing input, never a pass)."""
    dims = q.spec.dims
    lim_text = rule.limit_text(lim)
    missing = _collect(q.missing, sel_i)
    findings = _collect(q.findings, sel_i)
    bad = ~np.isfinite(sub)
    unexplained = [loc for loc in np.argwhere(bad) if not any(
        q.missing.get(t[:n]) for t in [tuple(int(sel_i[j][loc[j]])
                                             for j in range(len(dims)))]
        for n in range(len(t), 0, -1))]
    if unexplained:
        loc = unexplained[0]
        where_txt = ", ".join(_coord_text(d, q.coords[d][sel_i[j][loc[j]]])
                              for j, d in enumerate(dims) if d != "item")
        kind = "NaN" if np.isnan(sub[tuple(loc)]) else "an infinite value"
        msg = (f"{rule.name}: internal error: the calculation ran but gave {kind}"
               + (f" at {where_txt}" if where_txt else "")
               + (f" ({len(unexplained)} points)" if len(unexplained) > 1 else "")
               + "; the result cannot be judged and counts as failed"
               + (f". Findings: {'; '.join(findings[:3])}" if findings else "")
               + ". Please report it with the workbook.")
        return RuleResult(**base, item=item, status="fail", value=None, limit=lim_text,
                          limit_values=list(lim), margin=None, case=where_txt, message=msg,
                          findings=findings, internal_error=True)
    if not missing:
        missing = ["some values could not be computed (the calculation names no input)"]
    return RuleResult(**base, item=item, status="not_evaluated", value=None, limit=lim_text,
                      limit_values=list(lim), margin=None, case="",
                      message=not_evaluated_message(missing), missing=missing,
                      findings=findings)


def _judge(rule: Rule, spec: QuantitySpec, q: Quantity, item: str, attrs: dict,
           sub: np.ndarray, sel_i: list, lim: tuple[float, ...], factor,
           others: dict[str, Quantity] | None, base: dict) -> RuleResult | None:
    """Pass or fail at the worst judged point of one item (the smallest margin among the
    points the quantity's ``applies`` mask judges); ``None`` when the mask judges none of
    the item's points (no result, as for an item the ``where`` filter excludes: never a pass
    without a value)."""
    dims = spec.dims
    lim_text = rule.limit_text(lim)
    name = rule.name
    if rule.limit_by == "engine_class":  # the row says which class its limit is for
        name = f"{rule.name} ({str(attrs.get('engine_class') or '').lower()} limit)"
    limit_cell = attrs.get("limit_cell") if rule.limit_from == "workbook" else None
    findings = _collect(q.findings, sel_i)
    disp = factor(sub)
    m = _margin(rule.check, disp, lim)
    if q.applies is not None:
        app = q.applies[np.ix_(*sel_i)]
        if not app.any():
            return None
        m = np.where(app, m, np.inf)
    k = int(np.argmin(m))
    worst = np.unravel_index(k, sub.shape)
    value = float(disp[worst])
    margin = float(m[worst])
    case_parts = [_coord_text(d, q.coords[d][sel_i[j][worst[j]]])
                  for j, d in enumerate(dims) if d != "item"]
    ok = _passes(rule.check, margin)
    status = "pass" if ok else "fail"
    verb = "meets" if ok else "violates"
    near = min(lim, key=lambda x: abs(x - value))
    msg = (f"{name}: {display.with_unit(value, rule.unit, distinct_from=near)} {verb}"
           f" {lim_text}")
    if case_parts:
        msg += f" (worst at {', '.join(case_parts)})"
    if limit_cell:
        msg += f"; limit from {limit_cell}"
    at = tuple(int(sel_i[j][worst[j]]) for j in range(len(dims)))
    # the findings of the judged point first (a note beside the value describes it)
    here = _collect(q.findings, [np.array([x]) for x in at])
    findings = here + [f for f in findings if f not in here]
    compare, judged_on = _compare_at(spec, others, q, at, factor)
    if compare:
        judged_on = next((lab for lab, n in spec.compare if n == rule.quantity), "")
        parts = [f"{lab} {display.with_unit(v, rule.unit)}" for lab, v in compare.items()]
        vals = list(compare.values())
        ratio = (f", ratio {max(vals) / min(vals):.2f}" if len(vals) == 2 and min(vals) > 0
                 else "")
        msg += f" [{'; '.join(parts)}{ratio}; judged on {judged_on or rule.quantity}]"
    return RuleResult(**dict(base, name=name), item=item, status=status, value=value,
                      limit=lim_text, limit_values=list(lim), margin=margin,
                      case=", ".join(case_parts), message=msg, findings=findings,
                      compare=compare, judged_on=judged_on)


def _source_short(source: str) -> str:
    """The first author and year of a rule's source ("Bell 2013")."""
    m = re.match(r"\s*([A-Z][A-Za-z\-]+)[^0-9]*?(\d{4})", source)
    return f"{m.group(1)} {m.group(2)}" if m else "its source"


def _compare_at(spec, others, q, index: tuple[int, ...], factor
                ) -> tuple[dict[str, float], str]:
    """Values of the compared quantities at ``index`` (display units of the rule)."""
    out: dict[str, float] = {}
    if not spec.compare:
        return out, ""
    for label, name in spec.compare:
        o = q if name == spec.name else (others or {}).get(name)
        if o is None or o.values.shape != q.values.shape:
            continue
        v = float(o.values[index])
        if math.isfinite(v):
            out[label] = float(factor(v))
    return out, ""


def _affine(si_unit: str, unit: str):
    """Conversion from an SI unit to a rule's unit, ``x -> a x + b`` (offset units such as
    °C convert affinely)."""
    a, b = convert_affine(si_unit or "", (unit or "").replace("%", "percent"))
    if b == 0.0:
        return lambda x: x * a
    return lambda x: x * a + b


def is_finite(x: float | None) -> bool:
    return x is not None and math.isfinite(x)
