"""Which computed points the rules judge, for the report's tables and plots.

The single source is :attr:`checker.evaluation.graph.Quantity.applies` (the quantity's own mask,
e.g. the
resonant peaks of a TV amplitude, combined with the operating envelope by
:func:`checker.api._apply_envelope`) with ``q.applies_text`` as the reason. The report
never decides by itself which points count: these helpers only *locate* the judged worst point
(the point the rule result names: the same mask, the same direction, the first of equal values)
and mark the points that are computed but not judged.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..api import CheckResult

NOT_JUDGED_CSS = "not-judged"
"""CSS class of a table row that shows a computed point the rules do not judge."""
SHADE = {"color": "0.55", "alpha": 0.18, "linewidth": 0, "zorder": 0}
"""Style of the speed ranges that are computed but not judged."""
SHADE_LABEL = "not judged"


@dataclass(frozen=True)
class Point:
    """One point of a quantity: its full index into ``q.values``, value (SI), judged or not."""

    index: tuple[int, ...]
    value: float
    judged: bool


def mask(q) -> np.ndarray:
    """Boolean mask of the points the rules judge, shaped like ``q.values``."""
    if q.applies is None:
        return np.ones(q.values.shape, dtype=bool)
    return np.broadcast_to(np.asarray(q.applies, dtype=bool), q.values.shape)


def reason(q) -> str:
    """Why points of ``q`` are not judged (the quantity's own text)."""
    return str(q.applies_text or "not judged by the rules")


def direction(res: CheckResult, quantity: str, default: str = "max") -> str:
    """``"max"`` when larger values are worse for the rules on ``quantity`` (``<``, ``<=``),
    ``"min"`` when smaller values are (``>``, ``>=``); ``default`` without such a rule."""
    for r in list(res.rules) + list(res.table.rules):
        if r.quantity == quantity:
            if r.check in ("<", "<="):
                return "max"
            if r.check in (">", ">="):
                return "min"
    return default


def rule_ids(res: CheckResult, quantity: str, item: str | None = None,
             case: str | None = None) -> list[str]:
    """Ids of the selected rules with a result on ``quantity`` for ``item`` (any item when
    None), kept to those whose case filter admits ``case``."""
    rules = {r.id: r for r in res.rules if r.quantity == quantity}
    out: list[str] = []
    for rr in res.results:
        r = rules.get(rr.rule)
        if r is None or rr.status not in ("pass", "fail"):
            continue
        if item is not None and rr.item not in (item, "all"):
            continue
        if case is not None and "case" in r.where and case not in r.where["case"]:
            continue
        if rr.rule not in out:
            out.append(rr.rule)
    return out


def worst(q, lead: tuple = (), how: str = "max") -> tuple[Point | None, Point | None]:
    """The judged worst point of ``q.values[lead]`` and, when a point that is not judged is
    worse still, that point (else None). ``lead`` indexes the leading dims with ints or
    ``slice(None)`` (searched too); ``how`` is ``"max"`` or ``"min"``. Of equal values the
    first in C order wins, as in the rule evaluation."""
    lead = tuple(lead)
    v = np.asarray(q.values[lead], dtype=float)
    m = mask(q)[lead]
    sign = 1.0 if how == "max" else -1.0
    ok = np.isfinite(v)
    score = np.where(ok, sign * v, -np.inf)

    def full(k: tuple) -> tuple[int, ...]:
        it = iter(int(x) for x in k)
        head = tuple(next(it) if isinstance(x, slice) else int(x) for x in lead)
        return head + tuple(it)

    judged = unjudged = None
    if (m & ok).any():
        k = np.unravel_index(int(np.argmax(np.where(m, score, -np.inf))), v.shape)
        judged = Point(full(k), float(v[k]), True)
    if (~m & ok).any():
        k = np.unravel_index(int(np.argmax(np.where(~m, score, -np.inf))), v.shape)
        if judged is None or score[k] > sign * judged.value:
            unjudged = Point(full(k), float(v[k]), False)
    return judged, unjudged


def judged_text(res: CheckResult, q, p: Point, item: str | None = None,
                case: str | None = None) -> str:
    """The 'judged' cell of a table row: the rules that judge the point, or why not."""
    if not p.judged:
        return "not judged: " + reason(q)
    ids = rule_ids(res, q.name, item, case)
    if ids:
        return ", ".join(ids)
    ne = [rr.rule for rr in res.results if rr.status == "not_evaluated"
          and any(r.id == rr.rule and r.quantity == q.name for r in res.rules)
          and (item is None or rr.item in (item, "all"))]
    return ("not judged: no limit given for " + ", ".join(dict.fromkeys(ne))) if ne \
        else "no rule on it"


def row_css(p: Point | None) -> str:
    return NOT_JUDGED_CSS if p is not None and not p.judged else ""


def runs(judged_1d: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges ``(first, last)`` of the runs of points that are not judged."""
    j = np.asarray(judged_1d, dtype=bool)
    out = []
    k = 0
    while k < j.size:
        if j[k]:
            k += 1
            continue
        a = k
        while k < j.size and not j[k]:
            k += 1
        out.append((a, k - 1))
    return out


def shade(ax, x, judged_1d: np.ndarray, label: str | None = SHADE_LABEL) -> bool:
    """Shade the x ranges of the points that are not judged (half a step beyond each end
    point); returns whether anything was shaded. ``label`` goes to the legend once."""
    x = np.asarray(x, dtype=float)
    if x.size < 2:
        return False
    done = False
    for a, b in runs(judged_1d):
        lo = x[a] - 0.5 * (x[a] - x[a - 1] if a > 0 else x[1] - x[0])
        hi = x[b] + 0.5 * (x[b + 1] - x[b] if b + 1 < x.size else x[-1] - x[-2])
        ax.axvspan(lo, hi, **SHADE, label=None if done else label)
        done = True
    return done


def shade_caption(reasons: list[str]) -> str:
    """Caption text for shaded ranges (empty when nothing was shaded)."""
    r = [x for x in dict.fromkeys(reasons) if x]
    return (" Grey: computed but not judged by the rules (" + "; ".join(r) + ").") if r else ""


def missing_reasons(q, lead: tuple[int, ...]) -> list[str]:
    """Reasons of the missing entries of ``q`` at or below the leading index ``lead``."""
    out: list[str] = []
    for key, reasons in q.missing.items():
        n = min(len(key), len(lead))
        if tuple(key[:n]) == tuple(lead[:n]):
            out += [r for r in reasons if r not in out]
    return out


def point_label(q, index: tuple[int, ...]) -> str:
    """Legend suffix for a plotted point: empty when judged, else ' (not judged)'."""
    return "" if mask(q)[index] else " (not judged)"


def line(ax, x, y, judged_1d: np.ndarray, **kw) -> None:
    """Plot ``y(x)``: solid where judged, faint and dotted where computed but not judged (the
    ``label`` goes to the judged part)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    j = np.asarray(judged_1d, dtype=bool)
    if j.all():
        ax.plot(x, y, **kw)
        return
    (ln,) = ax.plot(x, np.where(j, y, np.nan), **kw)
    # the not-judged parts, joined to their judged neighbours
    near = ~j | np.r_[~j[1:], False] | np.r_[False, ~j[:-1]]
    faint = {k: v for k, v in kw.items() if k not in ("label", "ls", "linestyle", "alpha")}
    faint.setdefault("color", ln.get_color())
    ax.plot(x, np.where(near, y, np.nan), ls=":", alpha=0.5, **faint)
