"""Study files (TOML): which workbook inputs vary, how, and which rules judge the variants.

A study file addresses inputs the way a user sees them in the workbook: the sheet, the row (a
parameter name on a parameter sheet, a key such as a bearing name on a table sheet, several
keys, ``"all"`` rows, or the rows matching ``where``), and the column. Every parameter has a
unit and either a ``range`` (with ``steps`` for grid designs) or a list of ``values``::

    [study]
    name = "Main-bearing clearance and oil supply temperature"
    design = "full-factorial"    # one-at-a-time | full-factorial | latin-hypercube | table
    select = ["BRG"]             # rule id prefixes, as --select (default: all rules)

    [[parameter]]
    name = "main clearance"
    sheet = "Bearings"
    where = { type = "main" }    # every main bearing at once
    column = "radial clearance"
    unit = "um"
    range = [20, 40]
    steps = 5

    [[parameter]]
    sheet = "Oil"
    row = "Oil supply temperature"
    unit = "°C"
    values = [90, 110, 130]

Designs: ``one-at-a-time`` (the baseline, then each parameter through its levels with the
others at the workbook's values), ``full-factorial`` (every combination of levels),
``latin-hypercube`` (``samples`` points, ``seed``, :class:`scipy.stats.qmc.LatinHypercube`;
reproducible), ``table`` (explicit ``[[variant]]`` tables naming a value per parameter).
The file is validated on load; every problem names its line.
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import CheckerError
from ..workbook.schema import SHEETS, Field

DESIGNS = ("one-at-a-time", "full-factorial", "latin-hypercube", "table")
#: The most variants a study may have: each costs about a second of a worker and a file of
#: results; a larger design is refused before anything runs (say which number is too large).
MAX_VARIANTS = 100_000
_STUDY_KEYS = {"name", "design", "select", "ignore", "samples", "seed", "fail_on"}
_PARAM_KEYS = {"name", "sheet", "row", "rows", "where", "column", "unit", "range", "steps",
               "values"}


class StudyFileError(CheckerError):
    """A malformed study file: every problem with its line."""

    def __init__(self, path: str, problems: list[str]):
        self.path = path
        self.problems = list(problems)
        super().__init__("\n".join(problems))

    def __str__(self) -> str:
        n = len(self.problems)
        return (f"{n} problem{'s' if n != 1 else ''} in the study file {Path(self.path).name}:\n"
                + "\n".join(f"  {p}" for p in self.problems))


@dataclass(frozen=True)
class Parameter:
    """One varied input: where it is in the workbook and its levels (in ``unit``)."""

    name: str
    sheet: str
    field: Field
    rows: tuple[str, ...] | None  # table keys; None = every row matched by ``where``/all
    where: tuple[tuple[str, str], ...]  # (column attr, value) filters on table rows
    unit: str
    low: float | None = None
    high: float | None = None
    steps: int = 5
    values: tuple[Any, ...] = ()
    line: int = 0

    def levels(self) -> list[Any]:
        """The grid levels: ``values`` as given, or ``steps`` points over ``range``."""
        if self.values:
            return list(self.values)
        import numpy as np

        return [float(x) for x in np.linspace(self.low, self.high, self.steps)]

    def at(self, u: float) -> Any:
        """The value at the unit-interval coordinate ``u`` (Latin hypercube)."""
        if self.values:
            return self.values[min(int(u * len(self.values)), len(self.values) - 1)]
        return float(self.low + u * (self.high - self.low))

    @property
    def n_levels(self) -> int:
        """How many levels a grid design gives this parameter."""
        return len(self.values) if self.values else self.steps

    @property
    def numeric(self) -> bool:
        return self.field.kind not in ("text", "choice", "int_list")


@dataclass
class Study:
    """A validated study file."""

    path: str
    name: str
    design: str
    parameters: list[Parameter]
    select: list[str] | None = None
    ignore: list[str] | None = None
    fail_on: str = "error"
    samples: int = 0
    seed: int = 0
    table: list[tuple[str, dict[str, Any]]] = field(default_factory=list)  # (name, values)
    text: str = ""
    lines: dict[str, int] = field(default_factory=dict)  # [study] key -> line ("select"...)
    table_lines: list[int] = field(default_factory=list)  # line of each [[variant]]

    def line_of(self, key: str) -> str:
        """``line N`` of a [study] key (e.g. 'select'), for messages."""
        n = self.lines.get(key)
        return f"line {n}" if n else "[study]"


def _lines(text: str) -> dict[tuple[str, int, str], int]:
    """Line numbers of the keys: (table, index, key) -> line; table headers under key ''."""
    out: dict[tuple[str, int, str], int] = {}
    count: dict[str, int] = {}
    cur, idx = "", 0
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        m = re.match(r"^\[\[\s*([A-Za-z_]+)\s*\]\]", line)
        if m:
            cur = m.group(1)
            idx = count.get(cur, 0)
            count[cur] = idx + 1
            out[(cur, idx, "")] = n
            continue
        m = re.match(r"^\[\s*([A-Za-z_]+)\s*\]", line)
        if m:
            cur, idx = m.group(1), 0
            out[(cur, 0, "")] = n
            continue
        m = re.match(r'^("?)([^"=]+?)\1\s*=', line)
        if m and cur:
            out.setdefault((cur, idx, m.group(2).strip()), n)
    return out


def did_you_mean(word: str, choices, n: int = 3) -> str:
    """`` (did you mean 'x'?)`` for the closest of ``choices`` to ``word``, else ``""``."""
    import difflib

    ch = [str(c) for c in choices]
    low = {c.lower(): c for c in ch}
    hit = difflib.get_close_matches(str(word).strip().lower(), list(low), n=n, cutoff=0.6)
    if not hit:
        return ""
    return " (did you mean " + " or ".join(f"'{low[h]}'" for h in hit) + "?)"


def _field(sheet: str, column: str | None) -> Field | None:
    spec = SHEETS[sheet]
    norm = (column or "").strip().lower()
    for f in spec.fields:
        if norm in (f.label.lower(), f.attr.lower()):
            return f
    return None


def load_study(path: str | Path) -> Study:
    """Read and validate a study file (raises :class:`StudyFileError` naming the lines)."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise StudyFileError(str(p), [f"{p.name}: cannot be read ({exc})"]) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise StudyFileError(str(p), [f"not valid TOML: {exc}"]) from None
    lines = _lines(text)
    problems: list[str] = []

    def at(table: str, idx: int, key: str = "") -> str:
        n = lines.get((table, idx, key)) or lines.get((table, idx, ""))
        return f"line {n}" if n else f"[{table}]"

    st = doc.get("study")
    if not isinstance(st, dict):
        raise StudyFileError(str(p), ["a [study] table with 'design' is required (line 1)"])
    for k in st:
        if k not in _STUDY_KEYS:
            problems.append(f"{at('study', 0, k)}: unknown key '{k}' in [study]"
                            + (did_you_mean(k, sorted(_STUDY_KEYS)) or " (known: "
                               + ", ".join(sorted(_STUDY_KEYS)) + ")"))
    design = str(st.get("design", "")).strip().lower().replace("_", "-").replace(" ", "-")
    aliases = {"oat": "one-at-a-time", "factorial": "full-factorial", "lhs":
               "latin-hypercube", "explicit": "table"}
    design = aliases.get(design, design)
    if design not in DESIGNS:
        problems.append(f"{at('study', 0, 'design')}: design must be one of "
                        f"{', '.join(DESIGNS)}, found '{st.get('design', '')}'")

    def str_list(v: Any, key: str) -> list[str] | None:
        if v is None:
            return None
        vals = [v] if isinstance(v, str) else v
        if not isinstance(vals, list) or not all(isinstance(x, str) for x in vals):
            problems.append(f"{at('study', 0, key)}: '{key}' must be a list of rule id"
                            " prefixes, e.g. [\"BRG\"]")
            return None
        return [x.strip() for x in vals if x.strip()] or None

    select = str_list(st.get("select"), "select")
    ignore = str_list(st.get("ignore"), "ignore")
    samples, seed = st.get("samples", 0), st.get("seed", 0)
    if design == "latin-hypercube":
        if (not isinstance(samples, int) or isinstance(samples, bool)
                or not 2 <= samples <= MAX_VARIANTS):
            problems.append(f"{at('study', 0, 'samples')}: a latin-hypercube study needs"
                            f" 'samples' = a whole number from 2 to {MAX_VARIANTS:,}, found"
                            f" {samples!r}")
        if not isinstance(seed, int) or isinstance(seed, bool):
            problems.append(f"{at('study', 0, 'seed')}: 'seed' must be a whole number")
    params: list[Parameter] = []
    raw_params = doc.get("parameter", [])
    if not isinstance(raw_params, list) or not raw_params:
        problems.append("at least one [[parameter]] table is required")
        raw_params = []
    names: set[str] = set()
    for i, rp in enumerate(raw_params):
        prm = _parameter(rp, i, at, problems, design)
        if prm is None:
            continue
        if prm.name.lower() in names:
            problems.append(f"{at('parameter', i, 'name')}: duplicate parameter name"
                            f" '{prm.name}'")
            continue
        names.add(prm.name.lower())
        params.append(prm)
    table: list[tuple[str, dict[str, Any]]] = []
    table_lines: list[int] = []
    if design == "table":
        raw_var = doc.get("variant", [])
        if not isinstance(raw_var, list) or not raw_var:
            problems.append("a 'table' design needs one or more [[variant]] tables")
            raw_var = []
        by_name = {q.name.lower(): q for q in params}
        for i, rv in enumerate(raw_var):
            vals: dict[str, Any] = {}
            vname = str(rv.get("name", f"variant {i + 1}"))
            for k, v in rv.items():
                if k == "name":
                    continue
                q = by_name.get(k.lower())
                if q is None:
                    pn = [x.name for x in params]
                    problems.append(f"{at('variant', i, k)}: '{k}' is not a parameter name"
                                    + (did_you_mean(k, pn) or " (names: " + ", ".join(pn)
                                       + ")"))
                    continue
                if q.numeric and (isinstance(v, bool) or not isinstance(v, (int, float))):
                    problems.append(f"{at('variant', i, k)}: '{k}' needs a number (in"
                                    f" {q.unit or '-'}), found {v!r}")
                    continue
                vals[q.name] = float(v) if q.numeric else v
            table.append((vname, vals))
            table_lines.append(lines.get(("variant", i, ""), 0))
    elif doc.get("variant"):
        problems.append(f"{at('variant', 0)}: [[variant]] tables are only used by design"
                        " = 'table'")
    if design == "latin-hypercube":
        for q in params:
            if q.values and q.numeric:
                problems.append(f"line {q.line}: a latin-hypercube parameter needs a 'range'"
                                " (values lists are for grid designs)")
    study_lines = {k: n for (t, _, k), n in lines.items() if t == "study" and k}
    out = Study(str(p), str(st.get("name") or p.stem), design, params, select, ignore,
                str(st.get("fail_on", "error")), int(samples or 0), int(seed or 0), table,
                text, study_lines, table_lines)
    if not problems and design != "latin-hypercube":
        n = count_variants(out)
        if n > MAX_VARIANTS:
            levels = " x ".join(str(q.n_levels) for q in params)
            how = (f" ({levels} levels)" if design == "full-factorial" else "")
            problems.append(f"{at('study', 0, 'design')}: the {design} design has {n:,}"
                            f" variants{how}; at most {MAX_VARIANTS:,} are accepted (fewer"
                            " 'steps' or 'values', or a latin-hypercube design with 'samples')")
    if problems:
        raise StudyFileError(str(p), problems)
    return out


def _parameter(rp: Any, i: int, at, problems: list[str], design: str) -> Parameter | None:
    from ..workbook.units import KINDS, UnitProblem, to_si

    where0 = at("parameter", i)
    if not isinstance(rp, dict):
        problems.append(f"{where0}: [[parameter]] must be a table")
        return None
    bad = False
    for k in rp:
        if k not in _PARAM_KEYS:
            problems.append(f"{at('parameter', i, k)}: unknown key '{k}'"
                            + (did_you_mean(k, sorted(_PARAM_KEYS)) or " (known: "
                               + ", ".join(sorted(_PARAM_KEYS)) + ")"))
            bad = True
    sheet_in = str(rp.get("sheet", ""))
    sheet = next((s for s in SHEETS if s.lower() == sheet_in.strip().lower()), None)
    if sheet is None or SHEETS[sheet].shape == "notes":
        names = [s for s in SHEETS if SHEETS[s].shape != "notes"]
        problems.append(f"{at('parameter', i, 'sheet')}: unknown sheet '{sheet_in}'"
                        + (did_you_mean(sheet_in, names) or " (sheets: " + ", ".join(names)
                           + ")"))
        return None
    spec = SHEETS[sheet]
    rows: tuple[str, ...] | None = None
    where: tuple[tuple[str, str], ...] = ()
    if spec.shape == "parameters":
        f = _field(sheet, rp.get("row") or rp.get("column"))
        if f is None:
            word = rp.get("row") or rp.get("column")
            problems.append(f"{at('parameter', i, 'row')}: sheet {sheet} has no parameter"
                            f" '{word}'" + did_you_mean(word or "", [x.label for x in
                                                                      spec.fields]))
            return None
    else:
        f = _field(sheet, rp.get("column"))
        if f is None:
            labels = [x.label for x in spec.fields]
            problems.append(f"{at('parameter', i, 'column')}: sheet {sheet} has no column"
                            f" '{rp.get('column')}'" + (did_you_mean(rp.get("column") or "",
                                                                     labels)
                                                        or " (columns: " + ", ".join(labels)
                                                        + ")"))
            return None
        if spec.key and f.attr == spec.key:
            problems.append(f"{at('parameter', i, 'column')}: the key column '{f.label}'"
                            " names the rows; it cannot be varied")
            return None
        r = rp.get("rows", rp.get("row"))
        w = rp.get("where")
        if w is not None:
            if not isinstance(w, dict) or not w:
                problems.append(f"{at('parameter', i, 'where')}: 'where' must be a table such"
                                " as { type = \"main\" }")
                return None
            wl = []
            for k, v in w.items():
                wf = _field(sheet, k)
                if wf is None:
                    problems.append(f"{at('parameter', i, 'where')}: sheet {sheet} has no"
                                    f" column '{k}'" + did_you_mean(k, [x.label for x in
                                                                        spec.fields]))
                    return None
                wl.append((wf.attr, str(v)))
            where = tuple(wl)
        if r is None and w is None:
            problems.append(f"{at('parameter', i)}: name the rows: 'row' (e.g. \"M3\"), 'rows'"
                            " (a list, or \"all\") or 'where'")
            return None
        if r is not None and str(r).lower() != "all":
            rows = tuple(str(x) for x in (r if isinstance(r, list) else [r]))
    unit = str(rp.get("unit", "")).strip()
    numeric = f.kind not in ("text", "choice", "int_list")
    if numeric and f.kind != "int":
        try:
            to_si(1.0, unit or None, f.kind)
        except UnitProblem as exc:
            problems.append(f"{at('parameter', i, 'unit')}: unit '{unit}' does not fit"
                            f" {f.label} ({KINDS[f.kind].name}, e.g. {KINDS[f.kind].example}):"
                            f" {exc}")
            bad = True
    low = high = None
    values: tuple[Any, ...] = ()
    steps = rp.get("steps", 5)
    if "values" in rp:
        v = rp["values"]
        if not isinstance(v, list) or not v:
            problems.append(f"{at('parameter', i, 'values')}: 'values' must be a non-empty list")
            bad = True
        elif numeric and not all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                 for x in v):
            problems.append(f"{at('parameter', i, 'values')}: 'values' must be numbers (in"
                            f" {unit or '-'})")
            bad = True
        else:
            values = tuple(float(x) if numeric else str(x) for x in v)
    elif "range" in rp:
        v = rp["range"]
        if not (isinstance(v, list) and len(v) == 2 and all(
                isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)):
            problems.append(f"{at('parameter', i, 'range')}: 'range' must be [low, high]")
            bad = True
        elif not numeric:
            problems.append(f"{at('parameter', i, 'range')}: {f.label} is not a number; give"
                            " 'values'")
            bad = True
        elif not v[0] < v[1]:
            problems.append(f"{at('parameter', i, 'range')}: range low must be below high,"
                            f" found {v}")
            bad = True
        else:
            low, high = float(v[0]), float(v[1])
        if not isinstance(steps, int) or isinstance(steps, bool) or not 2 <= steps <= 1000:
            problems.append(f"{at('parameter', i, 'steps')}: 'steps' must be a whole number"
                            f" from 2 to 1000, found {steps!r}")
            bad = True
    elif design != "table":
        problems.append(f"{where0}: give 'range' = [low, high] or 'values' = [...]")
        bad = True
    if bad:
        return None
    name = str(rp.get("name") or (f.label if spec.shape == "parameters" else
                                   f"{f.label} of {', '.join(rows) if rows else 'all'}"))
    line = int(re.search(r"\d+", where0).group()) if re.search(r"\d+", where0) else 0
    return Parameter(name, sheet, f, rows, where, unit, low, high, int(steps) if isinstance(
        steps, int) else 5, values, line)


def count_variants(study: Study) -> int:
    """How many variants the design has, without making them (a 1000 x 1000 x 1000 factorial
    is counted, not built)."""
    params = study.parameters
    if study.design == "one-at-a-time":
        return 1 + sum(q.n_levels for q in params)
    if study.design == "full-factorial":
        return math.prod(q.n_levels for q in params) if params else 0
    if study.design == "latin-hypercube":
        return study.samples
    return len(study.table)
