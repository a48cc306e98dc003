"""Derived against published: each example's crank model from its geometry (sheet Crank) beside
the torsional model its source publishes (typed in TVModel, which wins in the check).

    python scripts/crank_derived_vs_published.py [--markdown]

For the I4 (Bell, Ricardo 2013) and the I6 (Mendes et al. 2008): per cylinder station the
published inertia and the derived one (throw + con-rod rotating share + reciprocating mean),
per crank element the published and the derived stiffness (where the throw stiffness model is
installed), and the first two natural frequencies of the published model and of the model with
every derivable value derived (blank cells in TVModel). Prints the table of
docs/crank-geometry.md.
"""

from __future__ import annotations

import argparse
import copy
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from checker import api  # noqa: E402
from checker.workbook.example import write_workbook  # noqa: E402
from checker.workbook.example_data import load_example  # noqa: E402


def _derived_content(content: dict, stiffness: bool = True) -> dict:
    """TVModel with every cylinder inertia (and crank stiffness) blank: derived."""
    out = copy.deepcopy(content)
    cols, rows = out["TVModel"]
    names = [n for n, _ in cols]
    ji, ki = names.index("inertia"), names.index("stiffness to next")
    roles = [r[names.index("role")] for r in rows]
    ends = {r[0]: r[1] for r in out.get("CrankEnds", [])}
    nose = ends.get("Crank nose diameter") is not None
    flange = ends.get("Flywheel flange diameter") is not None
    for i, r in enumerate(rows):
        nxt = roles[i + 1] if i + 1 < len(rows) else None
        if r[names.index("role")] == "cylinder":
            r[ji] = None
            if stiffness and (nxt == "cylinder" or (nxt == "flywheel" and flange)):
                r[ki] = None
        if stiffness and r[names.index("role")] == "crank nose" and nxt == "cylinder" and nose:
            r[ki] = None
    return out


def _run(content: dict, folder: Path, name: str):
    p = folder / name
    write_workbook(p, content)
    return api.check(p, select=["TV-"])


def compare(engine: str, folder: Path) -> dict:
    content = load_example(engine)
    published = _run(content, folder, f"{engine}-published.xlsx")
    inertia_only = _run(_derived_content(content, stiffness=False), folder,
                        f"{engine}-inertia.xlsx")
    try:
        derived = _run(_derived_content(content), folder, f"{engine}-derived.xlsx")
    except Exception as exc:  # stiffness not derivable without the throw stiffness model
        derived = None
        why = str(exc).splitlines()[0]
    e = published.engine
    model = {(m.item, m.attr): m for m in e.crank_model}
    rows = []
    for s in e.tv_model:
        for attr in ("inertia", "stiffness"):
            m = model.get((s.station, attr))
            if m is None or m.derived is None:
                continue
            rows.append((s.station, attr, getattr(s, attr), m.derived,
                         m.derived / getattr(s, attr) - 1.0))
    f_pub = published.outcome.quantities["tv.natural_frequency"].values[:2]
    f_der = (derived.outcome.quantities["tv.natural_frequency"].values[:2]
             if derived is not None else None)
    f_in = inertia_only.outcome.quantities["tv.natural_frequency"].values[:2]
    return {"rows": rows, "f_pub": f_pub, "f_der": f_der, "f_in": f_in,
            "why": "" if derived is not None else why,
            "stiffness_method": (published.outcome.quantities["crank.throw_stiffness"]
                                 .detail.stiffness_method)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--markdown", action="store_true")
    ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        for engine in ("i4", "i6"):
            r = compare(engine, Path(tmp))
            print(f"\n{engine.upper()}")
            print("| station | value | published | derived | difference |")
            print("|---|---|---|---|---|")
            for st, attr, pub, der, d in r["rows"]:
                unit = "kg m^2" if attr == "inertia" else "N m/rad"
                print(f"| {st} | {attr} [{unit}] | {pub:.5g} | {der:.5g} | {d * 100:+.0f} % |")
            for k in range(2):
                pub, der = r["f_pub"][k], r["f_in"][k]
                print(f"| model, derived inertias only | natural frequency {k + 1} [Hz] |"
                      f" {pub:.4g} | {der:.4g} | {(der / pub - 1) * 100:+.0f} % |")
            if r["f_der"] is not None:
                for k in range(2):
                    pub, der = r["f_pub"][k], r["f_der"][k]
                    print(f"| model | natural frequency {k + 1} [Hz] | {pub:.4g} | {der:.4g} |"
                          f" {(der / pub - 1) * 100:+.0f} % |")
            else:
                print(f"(natural frequencies of the derived model: not available: {r['why']})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
