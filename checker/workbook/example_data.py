"""The example workbooks as data: ``templates/example_<engine>.toml``, one file per engine.

Each file holds every cell the example workbook shows, sheet by sheet in workbook order:

* a parameter sheet is an array of tables, one per row: ``parameter``, ``value``, ``unit``,
  ``note``;
* a table sheet is a table with ``columns`` (``[name, unit]`` pairs, the workbook's first two
  rows) and ``rows``, one table per row keyed by column name (a column left out is a blank
  cell);
* ``Notes`` holds the lines of the Notes sheet;
* ``about`` (not a sheet) holds the example's title and what it assumes.

:func:`load_example` returns the content in the form
:func:`checker.workbook.example.write_workbook` writes (``{sheet: rows}`` for parameter sheets,
``(columns, rows)`` for tables, a list of lines for Notes). :func:`dumps_example` writes that
form back as TOML (deterministic; ``scripts/examples_to_data.py`` and
``scripts/make_example_derived.py`` use it). What is computed rather than entered
(counterweight phasing, oil-hole heights, throw angles) comes from
:mod:`checker.workbook.example_i6` / :mod:`checker.workbook.example_v8` and is written into the
files by ``scripts/make_example_derived.py``.
"""

from __future__ import annotations

import copy
import functools
import json
import math
import tomllib
from pathlib import Path
from typing import Any

ENGINES = ("i4", "i6", "v8", "genset", "marine")
PARAMETER_KEYS = ("parameter", "value", "unit", "note")
ABOUT = "about"


def example_file(engine: str) -> Path:
    """The data file of example ``engine`` (``i4``, ``i6``, ``v8``)."""
    from ..plumbing.resources import templates_dir

    if engine not in ENGINES:
        raise ValueError(f"unknown example engine {engine!r} (one of {', '.join(ENGINES)})")
    return templates_dir() / f"example_{engine}.toml"


def read_example(engine: str) -> dict[str, Any]:
    """The parsed data file of example ``engine`` (sheets and ``about``; a fresh copy)."""
    return copy.deepcopy(_parsed(engine))


def _parsed(engine: str) -> dict[str, Any]:
    """The parsed file, shared: not to be modified."""
    path = example_file(engine)
    st = path.stat()
    return _parse(path, st.st_mtime_ns, st.st_size)


@functools.lru_cache(maxsize=8)
def _parse(path: Path, _mtime_ns: int, _size: int) -> dict[str, Any]:
    """Parse once per file version (tomllib takes ~40 ms for the I6)."""
    with open(path, "rb") as f:
        return tomllib.load(f)


def content_from_data(data: dict[str, Any]) -> dict[str, Any]:
    """Workbook content (the form ``write_workbook`` takes) from a parsed data file."""
    content: dict[str, Any] = {}
    for sheet, body in data.items():
        if sheet == ABOUT:
            continue
        if sheet == "Notes":
            content[sheet] = list(body["lines"])
        elif isinstance(body, list):
            content[sheet] = [tuple(r.get(k) for k in PARAMETER_KEYS) for r in body]
        else:
            cols = [(str(n), str(u)) for n, u in body["columns"]]
            names = [n for n, _u in cols]
            rows = []
            for i, r in enumerate(body.get("rows", []), start=1):
                unknown = set(r) - set(names)
                if unknown:
                    raise ValueError(f"{sheet} row {i}: no column {sorted(unknown)}")
                rows.append([r.get(n) for n in names])
            content[sheet] = (cols, rows)
    return content


def load_example(engine: str) -> dict[str, Any]:
    """The content of example ``engine`` as :func:`~checker.workbook.example.write_workbook`
    takes it (read from ``templates/example_<engine>.toml``)."""
    return content_from_data(_parsed(engine))  # builds new rows: the cache stays intact


def about(engine: str) -> dict[str, Any]:
    """The ``about`` table of example ``engine``: ``title`` and ``assumed`` (sheet -> what)."""
    return read_example(engine).get(ABOUT, {})


# ---------------------------------------------------------------- writing
def _key(k: str) -> str:
    bare = k.replace("_", "a").replace("-", "a")
    return k if bare.isascii() and bare.isalnum() else _str(k)


def _str(s: str) -> str:
    return json.dumps(s, ensure_ascii=False)  # a JSON string is a TOML basic string


def _value(v: Any, where: str) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"{where}: {v} has no TOML form here")
        return repr(v)
    if isinstance(v, str):
        return _str(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x, where) for x in v) + "]"
    raise ValueError(f"{where}: cannot write {type(v).__name__} {v!r}")


def _long_list(items: list[str]) -> str:
    if not items:
        return "[]"
    return "[\n" + "".join(f"    {x},\n" for x in items) + "]"


def dumps_example(content: dict[str, Any], about_table: dict[str, Any] | None = None,
                  header: str = "") -> str:
    """TOML text of ``content`` (the form ``write_workbook`` takes); :func:`content_from_data`
    of its parse gives ``content`` back. ``header`` lines become comments at the top."""
    out: list[str] = [f"# {h}".rstrip() for h in header.splitlines()]
    if out:
        out.append("")
    if about_table:
        out.append(f"[{ABOUT}]")
        for k, v in about_table.items():
            if isinstance(v, dict):
                continue
            out.append(f"{_key(k)} = {_value(v, ABOUT)}")
        for k, v in about_table.items():
            if isinstance(v, dict):
                out += ["", f"[{ABOUT}.{_key(k)}]"]
                for kk, vv in v.items():
                    out.append(f"{_key(kk)} = "
                               + _long_list([_value(x, ABOUT) for x in vv]))
        out.append("")
    for sheet, body in content.items():
        s = _key(sheet)
        if sheet == "Notes":
            out += [f"[{s}]", "lines = " + _long_list([_str(x) for x in body]), ""]
        elif isinstance(body, list):
            for i, row in enumerate(body, start=1):
                if len(row) != len(PARAMETER_KEYS):
                    raise ValueError(f"{sheet} row {i}: {len(row)} values, expected"
                                     f" {len(PARAMETER_KEYS)} ({', '.join(PARAMETER_KEYS)})")
                out.append(f"[[{s}]]")
                for k, v in zip(PARAMETER_KEYS, row):
                    if v is not None:
                        out.append(f"{k} = {_value(v, f'{sheet} row {i}')}")
                out.append("")
        else:
            cols, rows = body
            names = [n for n, _u in cols]
            if len(set(names)) != len(names):
                raise ValueError(f"{sheet}: repeated column name in {names}")
            out += [f"[{s}]", "columns = " + _long_list(
                [f"[{_str(n)}, {_str(u)}]" for n, u in cols])]
            if not rows:
                out.append("rows = []")
            out.append("")
            for i, row in enumerate(rows, start=1):
                if len(row) != len(cols):
                    raise ValueError(f"{sheet} row {i}: {len(row)} values for {len(cols)}"
                                     " columns")
                out.append(f"[[{s}.rows]]")
                for n, v in zip(names, row):
                    if v is not None:
                        out.append(f"{_key(n)} = {_value(v, f'{sheet} row {i}')}")
                out.append("")
    return "\n".join(out).rstrip("\n") + "\n"


def file_header(text: str) -> str:
    """The comment lines at the top of a data file's ``text``, without the ``# ``."""
    lines = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        lines.append(line[2:])
    return "\n".join(lines)


def rewrite_example(engine: str, content: dict[str, Any]) -> str:
    """Text of example ``engine``'s data file with ``content`` in place of its sheets (its
    header and ``about`` table kept)."""
    text = example_file(engine).read_text(encoding="utf-8")
    about_table = tomllib.loads(text).get(ABOUT)
    return dumps_example(content, about_table, file_header(text))


def same_content(a: Any, b: Any, where: str = "") -> list[str]:
    """Differences between two contents, types included (``1`` is not ``1.0``, a tuple is not
    a list): an empty list when they are the same."""
    if type(a) is not type(b):
        return [f"{where}: {type(a).__name__} {a!r} != {type(b).__name__} {b!r}"]
    if isinstance(a, dict):
        diffs = []
        if list(a) != list(b):
            diffs.append(f"{where}: keys {list(a)} != {list(b)}")
        for k in a:
            if k in b:
                diffs += same_content(a[k], b[k], f"{where}/{k}")
        return diffs
    if isinstance(a, (list, tuple)):
        if len(a) != len(b):
            return [f"{where}: {len(a)} entries != {len(b)}"]
        diffs = []
        for i, (x, y) in enumerate(zip(a, b)):
            diffs += same_content(x, y, f"{where}[{i}]")
        return diffs
    return [] if a == b else [f"{where}: {a!r} != {b!r}"]


# ---------------------------------------------------------------- variants used by the tests
def without_tv_role(content: dict[str, Any], role: str) -> dict[str, Any]:
    """``content`` without the TVModel stations of ``role`` (e.g. the I6 without its assumed
    ``damper ring``)."""
    cols, rows = content["TVModel"]
    j = [n for n, _u in cols].index("role")
    return {**content, "TVModel": (cols, [r for r in rows if r[j] != role])}


def split_tv_stations(content: dict[str, Any], link: float) -> dict[str, Any]:
    """``content`` with every TVModel station that carries two cylinders (``"1, 2"``) split
    into two stations, one per cylinder, joined by the stiffness ``link`` [N m/rad], each with
    half the inertia and absolute damping (the V8's equivalent model in the tests; a split
    station is not a whole throw, so inertias derived from sheet Crank are typed in first)."""
    cols, rows = content["TVModel"]
    ix = {n: j for j, (n, _u) in enumerate(cols)}
    if any(r[ix["inertia"]] is None for r in rows):
        raise ValueError("split_tv_stations needs typed inertias (checker.workbook.example_v8."
                         "tv_completed types in the values derived from sheet Crank)")
    out = []
    for r in rows:
        cyl = r[ix["cylinder"]]
        if not (isinstance(cyl, str) and "," in cyl):
            out.append(list(r))
            continue
        a, b = (int(c) for c in cyl.split(","))
        for c, k in ((a, link), (b, r[ix["stiffness to next"]])):
            s = list(r)
            s[ix["station"]] = f"{r[ix['station']]} cylinder {c}"
            s[ix["cylinder"]] = c
            s[ix["inertia"]] = r[ix["inertia"]] / 2
            s[ix["absolute damping"]] = r[ix["absolute damping"]] / 2
            s[ix["stiffness to next"]] = k
            s[ix["note"]] = r[ix["note"]] + "; split station"
            out.append(s)
    return {**content, "TVModel": (cols, out)}
