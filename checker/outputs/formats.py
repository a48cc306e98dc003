"""Machine and terminal outputs of a check: text, JSON and JUnit XML."""

from __future__ import annotations

import json

from ..api import CheckResult
from ..results.display import item_label

_STATUS = {"pass": "PASS", "fail": "FAIL", "not_evaluated": "NOT EVALUATED",
           "not_applicable": "NOT APPLICABLE"}


def status_label(status: str, severity: str) -> str:
    if status == "fail" and severity == "warning":
        return "WARN"
    return _STATUS[status]


def to_text(res: CheckResult) -> str:
    """One aligned line per rule result (rule, status, item, value, limit, case, margin in
    words), the not-evaluated reasons and limit overrides below their line, the input
    warnings and the caveats (what qualifies the results), then a summary."""
    rows = []
    for r in res.results:
        value = "-" if r.value is None else r.value_text
        notes = []
        if r.status in ("not_evaluated", "not_applicable") or r.internal_error:
            notes.append(r.message)
        if r.override:
            notes.append(r.override)
        rows.append((r.rule, status_label(r.status, r.severity), item_label(r.item), value, r.limit,
                     r.case, r.margin_text, notes))
    w = [max([len(x[i]) for x in rows] + [1]) for i in range(7)]
    lines = []
    for x in rows:
        line = "  ".join(x[i].ljust(w[i]) for i in range(7)).rstrip()
        for n in x[7]:
            line += f"\n{'':{w[0]}}  -> {n}"
        lines.append(line)
    if res.engine.warnings:
        lines.append("")
        lines.append(f"input warnings ({len(res.engine.warnings)}): unusual values, check them")
        lines += [f"  {w}" for w in res.engine.warnings]
    cav = res.caveats
    if cav:
        lines.append("")
        lines.append(f"caveats ({len(cav)}): what qualifies these results")
        lines += [f"  {c['kind']}: {c['text']}" for c in cav]
    lines.append("")
    lines.append(f"{res.engine.name}: {res.summary_text()}"
                 + (f" (modules run: {', '.join(res.outcome.modules_run) or 'none'};"
                    f" skipped: {', '.join(res.outcome.modules_skipped) or 'none'})"))
    return "\n".join(lines) + "\n"


def to_json(res: CheckResult, timings: bool = True) -> str:
    """Stable, deterministic JSON (sorted keys); run times only under ``timings``."""
    return json.dumps(res.to_dict(timings=timings), indent=2, sort_keys=True,
                      ensure_ascii=False) + "\n"


def to_junit(res: CheckResult) -> str:
    """JUnit XML: one test case per rule result (fail -> failure, not evaluated and not
    applicable -> skipped, with the message)."""
    from xml.sax.saxutils import escape, quoteattr  # imports urllib.request: only here

    c = res.counts()
    failing = {id(r) for r in res.failed}
    failures = len(failing)
    skipped = sum(1 for r in res.results if r.status in ("not_evaluated", "not_applicable")
                  and id(r) not in failing)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuites name="checker" tests="{len(res.results)}" failures="{failures}">',
           f'  <testsuite name={quoteattr(res.engine.name)} tests="{len(res.results)}"'
           f' failures="{failures}" skipped="{skipped}">',
           "    <properties>",
           f'      <property name="verdict" value={quoteattr(res.verdict_text)}/>',
           f'      <property name="complete" value="{str(res.complete).lower()}"/>',
           f'      <property name="not_evaluated" value="{c["not_evaluated"]}"/>',
           f'      <property name="not_applicable" value="{c["not_applicable"]}"/>',
           f'      <property name="fail_on" value={quoteattr(res.fail_on)}/>',
           *[f'      <property name="input_warning" value={quoteattr(str(w))}/>'
             for w in res.engine.warnings],
           *[f'      <property name="caveat" value={quoteattr(c["kind"] + ": " + c["text"])}/>'
             for c in res.caveats],
           "    </properties>"]
    for r in res.results:
        name = quoteattr(f"{r.rule} {r.name} [{item_label(r.item)}]")
        out.append(f'    <testcase classname={quoteattr(r.rule.split("-")[0])} name={name}>')
        if id(r) in failing:
            out.append(f"      <failure message={quoteattr(r.message)}>{escape(r.source)}"
                       "</failure>")
        elif r.status == "fail":
            out.append(f"      <system-out>{escape('WARNING: ' + r.message)}</system-out>")
        elif r.status in ("not_evaluated", "not_applicable"):
            out.append(f"      <skipped message={quoteattr(r.message)}/>")
        out.append("    </testcase>")
    out += ["  </testsuite>", "</testsuites>"]
    return "\n".join(out) + "\n"
