"""Generate ``docs/examples.md`` from its template with the numbers of a fresh check of the
example engines.

    python scripts/make_examples_doc.py [--check]

The page quotes the examples' results (counts, rule values, natural frequencies...). Each such
number is written in the template (``scripts/examples_doc_template.md``) as a placeholder
``{{ expression | format }}``, evaluated against a fresh ``checker check`` of the example
(``i4``, ``i6``, ``v8``, ``genset``, ``marine``: :class:`Example`), e.g.
``{{ v8.mode(1) | .0f }}`` for the V8's first natural frequency in Hz or
``{{ i4.value("TV-001") | .3f }}`` for a rule's value in its unit.
After a change that moves the examples' results, run this script and read the diff: the text
around the numbers may need a new word. ``--check`` writes nothing and exits 1 when a number
of the committed page is off (``tests/test_examples_doc.py`` checks the same, with the
tolerance of the printed digits).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

TEMPLATE = ROOT / "scripts" / "examples_doc_template.md"
OUT = ROOT / "docs" / "examples.md"
ENGINES = ("i4", "i6", "v8", "genset", "marine")
PLACEHOLDER = re.compile(r"\{\{(.+?)\}\}", re.S)
NUMBER = r"[-+]?\d[\d,]*(?:\.\d+)?"


class Example:
    """A fresh check of one example engine, as the template reads it: ``count(status)``,
    ``value(rule, item)`` (the result's value in the rule's unit), ``rpm(rule, item)`` and
    ``order(rule, item)`` (the speed and order of the result's worst case), ``values(rule,
    *items)`` (the values of a rule's results), ``mode(k)`` (natural frequency k [Hz]) and
    ``q(name, **labels)`` (a quantity's SI value, :meth:`q`)."""

    def __init__(self, engine: str):
        self.engine = engine
        self.res = _check(engine)

    def count(self, status: str) -> int:
        return int(self.res.counts()[status])

    def result(self, rule: str, item: str = "all"):
        got = [r for r in self.res.results if r.rule == rule and r.item == item]
        if len(got) != 1:
            raise KeyError(f"{self.engine}: {len(got)} results of {rule} on item {item!r}")
        return got[0]

    def value(self, rule: str, item: str = "all") -> float:
        v = self.result(rule, item).value
        if v is None:
            raise KeyError(f"{self.engine}: {rule} {item} has no value")
        return float(v)

    def values(self, rule: str, *items: str) -> list[float]:
        return [float(r.value) for r in self.res.results
                if r.rule == rule and r.value is not None and (not items or r.item in items)]

    def rpm(self, rule: str, item: str = "all") -> int:
        m = re.search(r"(\d+) rpm", self.result(rule, item).case)
        if m is None:
            raise KeyError(f"{self.engine}: {rule} {item} has no speed")
        return int(m.group(1))

    def order(self, rule: str, item: str = "all") -> float:
        m = re.search(r"order ([\d.]+)", self.result(rule, item).case)
        if m is None:
            raise KeyError(f"{self.engine}: {rule} {item} names no order")
        return float(m.group(1))

    def mode(self, k: int) -> float:
        return self.q("tv.natural_frequency", mode=f"mode {k}")

    def number(self, status: str, *rules: str) -> int:
        """How many results of these rules have the status."""
        return sum(1 for r in self.res.results if r.rule in rules and r.status == status)

    def speeds(self) -> int:
        """The number of speeds of the check's grid."""
        return len(self.res.outcome.quantities["tv.nose_amplitude"].coords["speed"])

    def total(self, name: str, rpm: float, **labels: str) -> float:
        """A quantity's SI values summed over its items at one speed of the grid [rpm]."""
        import numpy as np

        q = self.res.outcome.quantities[name]
        speeds = [round(float(w) * 30.0 / math.pi) for w in q.coords["speed"]]
        labels = {**labels, "speed": speeds.index(round(rpm))}
        idx = tuple(labels[d] if d == "speed" else
                    [str(c) for c in q.coords[d]].index(str(labels[d])) if d in labels
                    else slice(None) for d in q.spec.dims)
        return float(np.sum(np.asarray(q.values, dtype=float)[idx]))

    def q(self, name: str, reduce: str = "max", **labels: str) -> float:
        """A quantity's SI value at the coordinate labels given (``item="M1"``), the largest
        (``reduce="min"``: smallest) over the axes not given."""
        import numpy as np

        q = self.res.outcome.quantities[name]
        v = np.asarray(q.values, dtype=float)
        idx = tuple([str(c) for c in q.coords[d]].index(str(labels[d])) if d in labels
                    else slice(None) for d in q.spec.dims)
        sub = v[idx]
        return float(np.nanmin(sub) if reduce == "min" else np.nanmax(sub))


def _check(engine: str):
    from checker import api
    from checker.workbook.example import example_content, write_workbook
    from checker.workbook.example_classes import genset_content, marine_content
    from checker.workbook.example_i6 import i6_content
    from checker.workbook.example_v8 import v8_content

    content = {"i4": example_content, "i6": lambda: i6_content(damper_ring=True),
               "v8": v8_content, "genset": genset_content,
               "marine": marine_content}[engine]()  # as `checker template --engine` writes them
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / f"{engine}.xlsx"
        write_workbook(p, content)
        return api.check(str(p))


@dataclass(frozen=True)
class Quoted:
    """One number the page quotes: its expression, format and the value of a fresh check."""

    expression: str
    format: str
    value: Any

    @property
    def text(self) -> str:
        return format(self.value, self.format)


def _split(body: str) -> tuple[str, str]:
    expr, _, fmt = body.rpartition("|") if "|" in body else (body, "", "")
    return expr.strip(), fmt.strip()


_BUILTINS = {"min": min, "max": max, "abs": abs, "round": round, "len": len, "range": range}
"""What a placeholder's expression may call besides the examples."""


def quoted(template: str, examples: dict[str, Example] | None = None) -> list[Quoted]:
    """Every placeholder of the template with its value."""
    examples = examples if examples is not None else {e: Example(e) for e in ENGINES}
    out = []
    for m in PLACEHOLDER.finditer(template):
        expr, fmt = _split(m.group(1))
        value = eval(expr, {"__builtins__": _BUILTINS, **examples})
        out.append(Quoted(expr, fmt, value))
    return out


def render(template: str, numbers: list[Quoted]) -> str:
    it = iter(numbers)
    return PLACEHOLDER.sub(lambda _m: next(it).text, template)


def read_numbers(template: str, page: str) -> list[str] | None:
    """The numbers the page prints where the template has placeholders (None: the page's
    text differs from the template's around them)."""
    parts = PLACEHOLDER.split(template)
    pattern = "".join(re.escape(p) if k % 2 == 0 else f"({NUMBER})"
                      for k, p in enumerate(parts))
    m = re.fullmatch(pattern, page, re.S)
    return None if m is None else list(m.groups())


def _first_difference(template: str, page: str) -> str:
    """Where the page's text first departs from the template's: the template's text there."""
    parts = PLACEHOLDER.split(template)
    pattern = ""
    for k, p in enumerate(parts):
        pattern += re.escape(p) if k % 2 == 0 else f"({NUMBER})"
        if re.match(pattern, page, re.S) is None:
            return f" at: {p.strip()[:80]!r}" if k % 2 == 0 else f" at {{{{{p.strip()}}}}}"
    return " after its last number"


def tolerance(printed: str, fmt: str) -> float:
    """One unit in the last printed digit (rounding on another machine cannot cross it);
    whole numbers (counts) exact."""
    if fmt.endswith("d") or fmt == "":
        return 0.0
    digits = printed.split(".", 1)[1] if "." in printed else ""
    return 10.0 ** -len(digits)


def differences(template: str, page: str, numbers: list[Quoted]) -> list[str]:
    """What is off in the page: text not the template's, or numbers beyond their printed
    precision."""
    printed = read_numbers(template, page)
    if printed is None:
        return [f"the page's text differs from the template{_first_difference(template, page)}"]
    out = []
    for s, n in zip(printed, numbers):
        got = float(s.replace(",", ""))
        want = float(n.value)
        if not math.isfinite(want) or abs(got - want) > tolerance(s, n.format) * (1 + 1e-9):
            out.append(f"{{{{ {n.expression} }}}}: the page says {s}, a fresh check gives"
                       f" {n.text}")
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="write nothing; exit 1 if stale")
    args = ap.parse_args()
    template = TEMPLATE.read_text(encoding="utf-8")
    numbers = quoted(template)
    if args.check:
        off = differences(template, OUT.read_text(encoding="utf-8"), numbers)
        for line in off:
            print(line)
        return 1 if off else 0
    OUT.write_text(render(template, numbers), encoding="utf-8")
    print(f"wrote {OUT.relative_to(ROOT)} ({len(numbers)} numbers)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
