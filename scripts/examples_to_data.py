"""Dump the example workbooks' content into ``templates/example_<engine>.toml`` and record the
``checker template`` output as the reference digests of ``tests/workbook/data/``.

    python scripts/examples_to_data.py [--check] [--digest-only]

For each example engine (i4, i6, v8) it takes the content that ``checker template --engine E``
writes (:func:`checker.workbook.example.example_content`, ``example_i6.i6_content(damper_ring=
True)``, ``example_v8.v8_content()``; while those were Python literals, this is the
conversion), writes it as TOML (:func:`checker.workbook.example_data.dumps_example`), parses
the TOML back and checks that it gives the same content, types included; it checks that the
variants the tests use (the I6 without its assumed damper ring, the V8 with split stations)
follow from the data file. It then writes the digest of every cell of the ``checker template``
output (:mod:`tests.workbook.template_digest`) to ``tests/workbook/data/template_<E>.json``,
which ``tests/workbook/test_example_data.py`` compares with the output of the data files.

``--check`` writes nothing and exits 1 when a data file or digest would change.
``--digest-only`` leaves the data files alone and records the digests of the current output
(after an intended change of the examples, the schema descriptions or the writer).
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker.workbook import example, example_i6, example_v8  # noqa: E402
from checker.workbook import example_data as ed  # noqa: E402
from tests.workbook.template_digest import workbook_digest  # noqa: E402

DIGEST_DIR = ROOT / "tests" / "workbook" / "data"

TITLES = {
    "i4": "Example I4 gasoline: the engine of Bell, 'Cranktrain Analysis Using ENGDYN and"
          " VALDYN', Ricardo workshop, 2013",
    "i6": "Example I6 truck diesel: the MWM six-cylinder of Mendes, Meirelles, Zampieri, Proc."
          " IMechE Part K 222(2), 2008, with an assumed viscous damper",
    "v8": "Example V8 gasoline: a 90-degree cross-plane V8 from the GM LS1 5.7 L service data",
}
HEADER = """\
{title}.
`checker template --engine {engine}` writes this file as a workbook, cell for cell.
Parameter sheets: [[Sheet]] tables, one per row (parameter, value, unit, note).
Table sheets: [Sheet] columns = [name, unit] pairs, then [[Sheet.rows]] keyed by column
name (a column left out is a blank cell). Notes: the lines of the Notes sheet.
Values marked ASSUMPTION in their note are not in the sources; [about.assumed] lists them.
{derived}
This file is rewritten by scripts; keep explanations in the notes, not in TOML comments."""


def template_content(engine: str) -> dict:
    """The content ``checker template --engine ENGINE`` writes."""
    if engine == "i4":
        return example.example_content()
    if engine == "i6":
        return example_i6.i6_content(damper_ring=True)
    return example_v8.v8_content()


def assumed(engine: str) -> dict:
    mod = {"i4": example, "i6": example_i6, "v8": example_v8}[engine]
    return {k: list(v) for k, v in getattr(mod, "ASSUMED", {}).items()}


DERIVED = {
    "i4": "This example derives no cell.",
    "i6": "Derived cells (Cylinders throw angles, CrankMass, Fatigue oil-hole heights; see\n"
          "checker/workbook/example_derived.py) are rewritten by scripts/make_example_derived.py.",
    "v8": "Derived cells (Cylinders angles and pins, CrankMass, Fatigue web thickness and\n"
          "oil-hole heights; see checker/workbook/example_derived.py) are rewritten by\n"
          "scripts/make_example_derived.py.",
}


def data_text(engine: str) -> str:
    content = template_content(engine)
    text = ed.dumps_example(content, {"title": TITLES[engine], "assumed": assumed(engine)},
                            HEADER.format(title=TITLES[engine], engine=engine,
                                          derived=DERIVED[engine]))
    back = ed.content_from_data(tomllib.loads(text))
    diffs = ed.same_content(content, back, engine)
    if diffs:
        raise SystemExit(f"{engine}: the TOML does not give the content back:\n  "
                         + "\n  ".join(diffs[:20]))
    return text


def check_variants() -> list[str]:
    """The variants the tests use follow from the template content."""
    diffs = ed.same_content(example_i6.i6_content(damper_ring=False),
                            ed.without_tv_role(example_i6.i6_content(damper_ring=True),
                                               "damper ring"), "i6 without damper ring")
    diffs += ed.same_content(example_v8.v8_content(split_stations=True, link=1e13),
                             ed.split_tv_stations(example_v8.v8_content(), 1e13),
                             "v8 split stations")
    return diffs


def digest_text(engine: str) -> str:
    from click.testing import CliRunner

    from checker.cli import main as cli

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / f"{engine}.xlsx"
        r = CliRunner().invoke(cli, ["template", str(p), "--engine", engine])
        if r.exit_code != 0:
            raise SystemExit(f"checker template --engine {engine} failed: {r.output}")
        return dumps_digest(workbook_digest(p))


def dumps_digest(dg: dict) -> str:
    """JSON of a digest, one cell per line (readable diffs)."""
    def j(x):
        return json.dumps(x, ensure_ascii=False)

    lines = ["{", f'"properties": {j(dg["properties"])},', '"sheets": [']
    for i, s in enumerate(dg["sheets"]):
        lines.append("{" + ", ".join(f"{j(k)}: {j(s[k])}" for k in s if k != "cells")
                     + ', "cells": [')
        lines += [j(c) + ("," if n < len(s["cells"]) - 1 else "")
                  for n, c in enumerate(s["cells"])]
        lines.append("]}" + ("," if i < len(dg["sheets"]) - 1 else ""))
    lines += ["]", "}"]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="write nothing; exit 1 on a change")
    ap.add_argument("--digest-only", action="store_true",
                    help="record the digests of the current output, leave the data files")
    args = ap.parse_args(argv)
    outputs: dict[Path, str] = {}
    if not args.digest_only:
        diffs = check_variants()
        if diffs:
            print("variants do not follow from the data:\n  " + "\n  ".join(diffs[:20]))
            return 1
        for engine in ed.ENGINES:
            outputs[ROOT / "templates" / f"example_{engine}.toml"] = data_text(engine)
    for engine in ed.ENGINES:
        outputs[DIGEST_DIR / f"template_{engine}.json"] = digest_text(engine)
    changed = [p for p, t in outputs.items()
               if not p.exists() or p.read_text(encoding="utf-8") != t]
    for p in changed:
        print(("would change " if args.check else "wrote ") + str(p.relative_to(ROOT)))
        if not args.check:
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_text(outputs[p], encoding="utf-8")
    if not changed:
        print("up to date")
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    raise SystemExit(main())
