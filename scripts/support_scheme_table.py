"""Print the support-scheme comparison of docs/crank-beam.md for a workbook with sheet Crank.

Run: ``.venv/bin/python scripts/support_scheme_table.py engine.xlsx [stiffness N/mm]``

Checks the workbook three times (Engine 'Main bearing supports' = determinate, continuous beam
on rigid supports, continuous beam on elastic supports of the given stiffness) and prints, as
Markdown: the peak main-bearing loads, the fillet bending ratios (with Cummins 2002 Fig. 1's
80 % / 87 % beside them), the mains' thinnest film and every verdict that changes.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
import openpyxl

from checker import api

SCHEMES = ("determinate", "continuous beam, rigid supports", "continuous beam, elastic supports")


def _variant(src: Path, folder: Path, scheme: str, k: float) -> Path:
    wb = openpyxl.load_workbook(src)
    ws = wb["Engine"]
    for label, value, unit in (("Main bearing supports", scheme, "-"),
                               ("Main bearing support stiffness",
                                k if scheme.endswith("elastic supports") else None, "N/mm")):
        row = next((r for r in range(1, ws.max_row + 1) if ws.cell(r, 1).value == label),
                   ws.max_row + 1)
        ws.cell(row, 1, label)
        ws.cell(row, 2, value)
        ws.cell(row, 3, unit if value is not None else None)
    out = folder / f"{scheme.replace(',', '').replace(' ', '_')}.xlsx"
    wb.save(out)
    return out


def main(path: str, k: float = 1e6) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        res = {s: api.check(_variant(Path(path), Path(tmp), s, k)) for s in SCHEMES}
        print(f"Main-bearing supports of elastic scheme: {k:g} N/mm each.\n")
        bl = {s: r.outcome.quantities["loads.bearing_load"] for s, r in res.items()}
        names = bl[SCHEMES[0]].coords["item"]
        mains = [i for i, n in enumerate(names) if bl[SCHEMES[0]].item_attrs[n]["type"] == "main"]
        print("| main | case | determinate [kN] | rigid [kN] | elastic [kN] |")
        print("|---|---|---|---|---|")
        for i in mains:
            for ci, c in enumerate(bl[SCHEMES[0]].coords["case"]):
                v = [np.nanmax(bl[s].values[i, ci]) / 1e3 for s in SCHEMES]
                print(f"| {names[i]} | {c} load | " + " | ".join(f"{x:.2f}" for x in v) + " |")
        print("\n| fillet | rigid supports | elastic supports |")
        print("|---|---|---|")
        qr = res[SCHEMES[1]].outcome.quantities["fatigue.fillet_bending_ratio"]
        qe = res[SCHEMES[2]].outcome.quantities["fatigue.fillet_bending_ratio"]
        for n, a, b in zip(qr.coords["item"], qr.values, qe.values, strict=True):
            print(f"| {n} | {a:.3f} | {b:.3f} |")
        for label, part in (("pin fillets", "pin fillet"), ("main fillets", "main fillet")):
            sel = [j for j, n in enumerate(qr.coords["item"]) if part in n]
            print(f"\n{label}: rigid {qr.values[sel].min():.3f}..{qr.values[sel].max():.3f}"
                  f" (mean {qr.values[sel].mean():.3f}), elastic {qe.values[sel].min():.3f}.."
                  f"{qe.values[sel].max():.3f} (mean {qe.values[sel].mean():.3f});"
                  " Cummins 2002 Fig. 1: 0.80 rigid, 0.87 elastic")
        print("\n| rule | main | case | determinate | rigid | elastic |")
        print("|---|---|---|---|---|---|")
        for k, r0 in enumerate(res[SCHEMES[0]].results):
            if not (r0.rule.startswith(("BRG-003", "BRG-004", "BRG-001"))
                    and r0.item.startswith("M")):
                continue
            cells = []
            for s in SCHEMES:
                r = res[s].results[k]
                cells.append(f"{r.value_text} {r.status.replace('_', ' ')}")
            print(f"| {r0.rule} | {r0.item} | {r0.case.split(',')[0]} | " + " | ".join(cells)
                  + " |")
        print("\nVerdicts that change against the determinate scheme:\n")
        for s in SCHEMES[1:]:
            ch = api.compare_schemes(res[s])
            print(f"- {s}: " + ("none" if not ch else "; ".join(
                f"{c['rule']} {c['item']} {c['determinate']} -> {c['continuous']}"
                f" ({c['determinate_value']:.3g} -> {c['continuous_value']:.3g})" for c in ch)))


if __name__ == "__main__":
    main(sys.argv[1], *(float(x) for x in sys.argv[2:3]))
