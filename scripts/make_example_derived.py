"""Recompute the derived cells of the example data files ``templates/example_<engine>.toml``.

    python scripts/make_example_derived.py [--check]

Throw angles, counterweight phasing, crank masses and oil-hole heights follow from other
cells of the same file (:mod:`checker.workbook.example_derived` says which and how); after an
edit of those cells (spacing, journal sizes, firing order, rod masses...) this script writes
the derived cells again. ``--check`` writes nothing and exits 1 when a file would change
(``tests/workbook/test_example_derived.py`` checks the same).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker.workbook import example_data as ed  # noqa: E402
from checker.workbook import example_derived as dv  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="write nothing; exit 1 on a change")
    args = ap.parse_args(argv)
    changed = []
    for engine in dv.DERIVED:
        path = ed.example_file(engine)
        text = ed.rewrite_example(engine, dv.derived_cells(engine, ed.load_example(engine)))
        if text != path.read_text(encoding="utf-8"):
            changed.append(path)
            if not args.check:
                path.write_text(text, encoding="utf-8")
            print(("would change " if args.check else "wrote ") + str(path))
    if not changed:
        print("up to date")
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    raise SystemExit(main())
