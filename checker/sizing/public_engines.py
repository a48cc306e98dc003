"""Public engines the first-layout rules are measured against (never tuned on): bore, stroke,
rated power and speed, and the main journal, crank-pin and rod length that their service data
publish (None where the page found does not give it).

Each row names where its crank dimensions are published (the manufacturers' service manuals
as reproduced by public repair-manual sites); bore, stroke and rating are the commonly
quoted figures of the engine. :func:`scatter` sizes each from its brief (``checker new``'s
open-loop layout, the default peak pressure and lining of the fuel) and tables the errors
(docs/new-engine.md).
"""

from __future__ import annotations

import statistics
from dataclasses import dataclass


@dataclass(frozen=True)
class PublicEngine:
    name: str
    brief: dict
    main: float | None  # mm
    pin: float | None  # mm
    rod: float | None  # mm, centre to centre
    source: str


def _b(cyl: int, bore: float, stroke: float, kw: float, rpm: float, fuel: str = "gasoline",
       bank: float | None = None, **kw_: str) -> dict:
    d = {"cylinders": cyl, "bore": f"{bore} mm", "stroke": f"{stroke} mm",
         "rated_power": f"{kw} kW", "rated_speed": f"{rpm} rpm", "fuel": fuel, **kw_}
    if bank is not None:
        d.update(layout="V", bank_angle=f"{bank} deg")
    return d


ENGINES: tuple[PublicEngine, ...] = (
    PublicEngine("Toyota 2AZ-FE I4 2.4 l", _b(4, 88.5, 96.0, 119, 5600), 55.0, 48.0, None,
                 "Toyota service data (2006 Highlander L4-2.4L, Crankshaft specifications)"),
    PublicEngine("Volvo B5244S I5 2.4 l", _b(5, 83.0, 90.0, 125, 5900), 65.0, 50.0, 147.0,
                 "Volvo service data (2001 S60 2.4, Crankshaft specifications)"),
    PublicEngine("Ford 2.0 SOHC I4 (Tracer)", _b(4, 84.8, 88.0, 82, 5000), None, None, 131.9,
                 "Ford service data (1997 Tracer 2.0L SOHC, Connecting Rod)"),
    PublicEngine("GM 3.5 V6 60 deg (LX9)", _b(6, 94.0, 84.0, 150, 5600, bank=60,
                                               crank_type="split pins"), 67.25, 57.13, 150.0,
                 "GM service data (2005 Saturn Relay V6-3.5L, System Specifications)"),
    PublicEngine("Ford 4.0 SOHC V6 60 deg", _b(6, 100.4, 84.4, 157, 5250, bank=60), 57.0, 54.0,
                 146.0, "Ford service data (2004 Explorer Sport Trac and Mountaineer V6-4.0L)"),
    PublicEngine("Ford 3.0 Duratec V6 60 deg", _b(6, 89.0, 79.5, 149, 5900, bank=60), 62.98,
                 49.98, None, "Ford service data (2005 Sable V6-3.0L DOHC, Crankshaft)"),
    PublicEngine("Ford 2.5 Duratec V6 60 deg", _b(6, 82.4, 79.5, 127, 6250, bank=60), None,
                 None, 138.2, "Ford service data (1999 Mystique V6-2.5L DOHC, Connecting Rod)"),
    PublicEngine("Lexus 2GR-FSE V6 60 deg", _b(6, 94.0, 83.0, 226, 6400, bank=60), 61.0, 53.0,
                 None, "Toyota service data (2008 GS 350 2GR-FSE, Crankshaft)"),
    PublicEngine("Ford 3.8 V6 90 deg (Essex)", _b(6, 96.8, 86.0, 144, 5500, bank=90,
                                                   crank_type="split pins"), 63.99, 58.69,
                 154.7, "Ford service data (2001 Mustang V6-3.8L, Crankshaft and Connecting"
                 " Rod)"),
    PublicEngine("Ford 4.6 2V V8", _b(8, 90.2, 90.0, 168, 4800, bank=90), None, None, 150.7,
                 "Ford service data (2006 E-250 V8-4.6L, Connecting Rod)"),
    PublicEngine("Ford 5.4 3V V8", _b(8, 90.2, 105.8, 224, 5000, bank=90), 67.49, 52.99, 169.1,
                 "Ford service data (2004 Navigator 5.4L DOHC; 2008 F-150 5.4L Connecting Rod)"),
    PublicEngine("Dodge 4.7 V8", _b(8, 93.0, 86.5, 175, 4800, bank=90), 63.5, 51.0, None,
                 "Chrysler service data (2005 Durango V8-4.7L, System Specifications)"),
    PublicEngine("Cadillac Northstar 4.4 V8", _b(8, 91.0, 84.0, 330, 6400, bank=90), None,
                 53.96, 151.0, "GM service data (2008 XLR V8-4.4L SC, Specifications)"),
    PublicEngine("Ford 6.8 V10", _b(10, 90.2, 105.8, 228, 4750, bank=90), 67.49, 52.99, None,
                 "Ford service data (2007 F-450 V10-6.8L, General Specifications)"),
    PublicEngine("Ford 7.3 V8 diesel", _b(8, 104.4, 106.2, 157, 3000, "diesel", bank=90),
                 79.24, 63.46, None, "Ford service data (1998 Econoline V8-7.3L DSL,"
                 " Crankshaft)"),
    PublicEngine("Cummins 5.9 I6 diesel", _b(6, 102.0, 120.0, 175, 2700, "diesel"), 83.0,
                 69.0, None, "Dodge Ram service manual (1996 and 2001, 5.9L diesel)"),
    PublicEngine("Cummins 6.7 I6 diesel", _b(6, 107.0, 124.0, 261, 3000, "diesel"), 83.0,
                 69.0, None, "Dodge Ram service data (2009 RAM 3500 L6-6.7L DSL)"),
    PublicEngine("Jeep 4.0 I6 (Power Tech)", _b(6, 98.4, 87.4, 142, 4600), 63.495, 53.2, 155.6,
                 "Jeep service data (Power Tech 4.0 I6 engine manual, Crankshaft and"
                 " Connecting Rods)"),
    PublicEngine("Chrysler 5.7 Hemi V8", _b(8, 99.5, 90.9, 257, 5400, bank=90), 65.0, 54.0,
                 None, "Chrysler service data (2007 Jeep WK 5.7L; Ram 1500 V8-5.7L,"
                 " Connecting Rod)"),
    PublicEngine("GM 6.0 V8 (LQ9)", _b(8, 101.6, 92.0, 257, 5200, bank=90), 65.0, 53.33, None,
                 "GM service data (2005 Sierra Denali V8-6.0L; 2009 Sierra 2500 V8-6.0L L76)"),
    PublicEngine("Toyota 1MZ-FE V6 60 deg", _b(6, 87.5, 83.0, 149, 5200, bank=60), 60.99,
                 53.0, None, "Toyota 1MZ-FE engine repair manual (Cylinder Block)"),
    PublicEngine("Lexus 2UR-FSE V8", _b(8, 94.0, 89.5, 290, 6400, bank=90), 66.99, 52.99, None,
                 "Toyota service data (2008 LS 600h V8-5.0L 2UR-FSE, System Specifications)"),
    PublicEngine("Toyota 22R-E I4", _b(4, 92.0, 89.0, 85, 4800), 59.99, 52.99, None,
                 "Toyota 22R-E engine repair manual (Cylinder Block)"),
    PublicEngine("Ford 3.0 Vulcan V6 60 deg", _b(6, 88.9, 79.8, 112, 5000, bank=60), 63.99,
                 53.99, None, "Ford service data (1998 Ranger V6-3.0L, Crankshaft)"),
    PublicEngine("GM Ecotec 2.2 I4 (L61)", _b(4, 86.0, 94.6, 104, 5600), 56.0, 49.01, None,
                 "GM service data (Ecotec 2.2L unit repair, Engine Mechanical Specifications)"),
    PublicEngine("Honda J32A3 V6 60 deg", _b(6, 89.0, 86.0, 192, 6200, bank=60), 71.99, 54.99,
                 None, "Honda service data (2008 Acura TL V6-3.2L, General Specifications)"),
    PublicEngine("Chrysler 3.5 SOHC V6 60 deg", _b(6, 96.0, 81.0, 186, 6400, bank=60), 64.0,
                 57.99, None, "Chrysler service data (2004 Pacifica V6-3.5L, System"
                 " Specifications)"),
    PublicEngine("Kia 1.8 DOHC I4", _b(4, 81.0, 87.0, 93, 6000), 54.95, 44.95, None,
                 "Kia service data (2000 Spectra GSX L4-1.8L, System Specifications)"),
    PublicEngine("Saturn 1.9 DOHC I4", _b(4, 82.0, 90.0, 92, 5600), 57.0, 47.0, None,
                 "Saturn service manual (1998 SL2, Crankshaft specifications)"),
    PublicEngine("Ford 2.3 Duratec I4", _b(4, 87.5, 94.0, 114, 5800), 51.99, 49.99, 154.8,
                 "Ford service data (2005 Mariner L4-2.3L, System Specifications)"),
    PublicEngine("GM 3.1 V6 60 deg (LG8)", _b(6, 89.0, 84.0, 130, 5200, bank=60), 67.25, 50.77,
                 None, "GM service data (Lumina 3.1L overhaul data; 2003 Century 3.1L)"),
    PublicEngine("Ford 4.6 4V V8 (Marauder)", _b(8, 90.2, 90.0, 225, 5750, bank=90), 67.49,
                 52.99, 150.7, "Ford service data (2003 Marauder V8-4.6L DOHC, Crankshaft;"
                 " 1999 Mustang GT 4.6L, Connecting Rod)"),
    PublicEngine("Cadillac Northstar 4.6 V8 (LD8)", _b(8, 93.0, 84.0, 205, 5600, bank=90),
                 64.36, 53.96, None, "GM service data (2008 DTS V8-4.6L LD8, Engine"
                 " Mechanical Specifications)"),
    PublicEngine("Ford 6.0 V8 diesel", _b(8, 95.0, 105.0, 242, 3300, "diesel", bank=90), 81.0,
                 69.0, None, "Ford service data (2005 F-250 Super Duty V8-6.0L DSL, System"
                 " Specifications)"),
    PublicEngine("Caterpillar 3208 V8 diesel", _b(8, 114.3, 127.0, 157, 2800, "diesel",
                                                  bank=90), 88.89, 69.84, None,
                 "Caterpillar service data (3208 industrial and marine engines, Crankshaft)"),
    PublicEngine("Isuzu 4JJ1 I4 diesel", _b(4, 95.4, 104.9, 120, 3600, "diesel"), 69.92,
                 52.92, None, "Isuzu workshop manual (2007 KB P190 4JJ1, Crankshaft)"),
    PublicEngine("Perkins 854F-E34T I4 diesel", _b(4, 99.0, 110.0, 100, 2200, "diesel"), None,
                 71.98, None, "Perkins specifications UENR0622 (854F-E34T, Connecting Rod"
                 " Bearing Journal)"),
)


def scatter(iterate: bool = False) -> tuple[list[dict], dict[str, dict[str, float]]]:
    """Size each public engine (open loop; with ``iterate`` as ``checker new`` does, its
    sizing loop included) and compare; rows and per-quantity statistics (median and largest
    |error| in %). With the loop each row also holds the results failed after it."""
    from .brief import parse_brief
    from .loop import sized
    from .new_engine import layout

    rows = []
    errs: dict[str, list[float]] = {"main": [], "pin": [], "rod": []}
    for e in ENGINES:
        b = parse_brief(dict(e.brief), e.name)
        s = sized(b) if iterate else None
        lay = s.layout if s is not None else layout(b)
        got = {"main": lay.dj * 1e3, "pin": lay.dp * 1e3, "rod": lay.rod_len * 1e3}
        row = {"engine": e.name, "source": e.source}
        if s is not None:
            row["failed"] = (s.loop.failed_before, s.loop.failed_after,
                             sorted({t.split()[0] for t in s.loop.stop}))
        for k, real in (("main", e.main), ("pin", e.pin), ("rod", e.rod)):
            row[k] = (real, got[k], None if real is None else 100.0 * (got[k] / real - 1.0))
            if real is not None:
                errs[k].append(abs(row[k][2]))
        rows.append(row)
    stats = {k: {"n": len(v), "median": statistics.median(v), "max": max(v)}
             for k, v in errs.items()}
    return rows, stats


def markdown(iterate: bool = False) -> str:
    """The scatter tables of docs/new-engine.md (open loop; with ``iterate`` the layouts of
    ``checker new`` with its loop, and what each leaves failing)."""
    rows, stats = scatter(iterate)
    if iterate:
        out = ["| engine | main journal real / sized (error) | crank pin | rod length |"
               " failed results, first layout -> after the loop | rules still failing |",
               "|---|---|---|---|---|---|"]
    else:
        out = ["| engine | main journal real / sized (error) | crank pin | rod length |"
               " source |", "|---|---|---|---|---|"]

    def cell(v: tuple) -> str:
        real, got, err = v
        return "n/a" if real is None else f"{real:g} / {got:.1f} mm ({err:+.1f} %)"

    for r in rows:
        tail = (f"{r['failed'][0]} -> {r['failed'][1]} | {', '.join(r['failed'][2]) or '-'}"
                if iterate else r["source"])
        out.append(f"| {r['engine']} | {cell(r['main'])} | {cell(r['pin'])} | {cell(r['rod'])}"
                   f" | {tail} |")
    out.append("")
    out.append("| quantity | engines | median abs. error | largest abs. error |")
    out.append("|---|---|---|---|")
    for k, name in (("main", "main journal diameter"), ("pin", "crank-pin diameter"),
                    ("rod", "rod length")):
        s = stats[k]
        out.append(f"| {name} | {s['n']} | {s['median']:.1f} % | {s['max']:.1f} % |")
    return "\n".join(out)


if __name__ == "__main__":
    import sys

    print(markdown(iterate="--loop" in sys.argv[1:]))
