"""What it takes to pass: per result and lever, the input value at which the margin is zero.

For every failing result and every passing one within :data:`NEAR` of its limit, each lever
of the lever table that applies to it (:mod:`checker.description.levers`) is moved from today's
value in its allowed direction until the result's margin reaches zero:

* continuous levers: a starting guess from the proportionality of value and input (only a
  guess; 1/8 of the way to the bound without one), then secant steps through the two
  points farthest from today towards the middle of the accepted margin window (the step
  doubled while the margin does not move towards the limit, never beyond the bound) until a
  value passes; the bracket is then refined by inverse quadratic interpolation / regula
  falsi (Illinois variant) until the passing end has a margin in [0, :data:`TOL`] (each step
  a direct evaluation: the answer is always a value that was checked);
* discrete levers (bolt size, number of bolts, oil grade): the first choice beyond today's
  value that passes (one choice per round, the next only while none passes);
* "no value within the bounds" is an answer, with the best margin reached.

Jobs of separable levers (a result depends only on its own row, e.g. the clearance of one
bearing) on different items share one evaluation per step. At each answer the check is run
again with every selected rule whose status can change there: the other results whose status
changes are its side effects.

Failing results of bearing rules (film thickness, specific load: values computed per speed)
are searched at screening speeds, the few speeds where each is worst today
(:mod:`checker.remedies.screening`); a value that passes there is an answer only once the
check at every speed (the side-effect check above) passes it within the window, and the
search goes on at every speed from a value that does not.

Results of one item that need one lever in opposite directions are a conflict, stated with
the levers that do not have it.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from openpyxl.utils import get_column_letter

from ..description.levers import ITEM, Lever, choice_order, row_default, row_needs
from ..evaluation.ruletable import REL_TOL
from ..results.display import CELL_REF, with_unit
from ..workbook.schema import SHEETS
from .screening import screenable, screening_speeds
from .variants import Binding, Evaluator, bind, find

NEAR = 0.10
"""Passing results within this relative margin of their limit get remedies too."""
TOL = 1e-3
"""A remedy value's margin lies in [0, TOL] (relative margin, as the rule table's)."""
MAX_STEPS = 40
FRACTIONS = (0.125, 0.25, 0.5, 1.0)


@dataclass
class Remedy:
    """The answer of one lever for one result."""

    lever: Lever
    where: str  # cells, e.g. Joints!I3
    nominal: Any
    value: Any = None  # lever unit (None: no value within the bounds)
    margin: float | None = None  # at value
    found: bool = False
    reason: str = ""
    best_margin: float | None = None
    side_effects: list[dict] = field(default_factory=list)
    evaluations: int = 0
    direction: int = 0  # +1 the lever rises, -1 it falls

    @property
    def change(self) -> float | None:
        if not self.found or not isinstance(self.value, (int, float)) or not isinstance(
                self.nominal, (int, float)):
            return None
        return float(self.value) - float(self.nominal)

    @property
    def change_pct(self) -> float | None:
        c = self.change
        if c is None or not self.nominal:
            return None
        if self.lever.kind == "temperature":
            return None
        return 100.0 * c / abs(float(self.nominal))

    def value_text(self, v: Any = "__value__") -> str:
        v = self.value if isinstance(v, str) and v == "__value__" else v
        if v is None:
            return "blank"
        if isinstance(v, dict):
            d = v.get("nominal diameter")
            p = v.get("thread pitch")
            if d is not None and p is not None:
                return f"M{d:g}x{p:g}"
            return ", ".join(f"{k} {x:g}" for k, x in v.items())
        if isinstance(v, (int, float)):
            return with_unit(float(v), self.lever.unit)
        return str(v)

    def text(self) -> str:
        """``tightening torque 400 → 376.9 N·m (-23.1 N·m, -5.8 %)``."""
        name = self.lever.name
        if not self.found:
            return f"{name}: {self.reason or 'no value within the bounds'}"
        ch = self.change
        parts = ""
        if ch is not None:
            parts = f" ({'+' if ch >= 0 else ''}{with_unit(ch, self.lever.unit)}"
            pct = self.change_pct
            parts += (f", {'+' if pct >= 0 else '−'}{abs(pct):.1f} %)" if pct is not None
                      else ")")
        return f"{name} {self.value_text(self.nominal)} → {self.value_text()}{parts}"

    def as_dict(self) -> dict:
        def num(x):
            return None if x is None else (float(f"{x:.6g}") if isinstance(x, float) else x)
        return {
            "lever": self.lever.id, "name": self.lever.name, "input": self.where,
            "unit": self.lever.unit, "nominal": num(self.nominal),
            "value": num(self.value) if self.found else None, "found": self.found,
            "change": num(self.change), "change_percent": num(self.change_pct),
            "margin_at_value": num(self.margin), "reason": self.reason or None,
            "best_margin": num(self.best_margin), "side_effects": self.side_effects,
            "text": self.text(),
        }


@dataclass
class ResultRemedies:
    rule: str
    item: str
    status: str
    margin: float | None
    remedies: list[Remedy] = field(default_factory=list)
    conflicts: list[str] = field(default_factory=list)

    def best(self) -> Remedy | None:
        """The smallest relative change among the levers that reach a passing value."""
        ok = [r for r in self.remedies if r.found]
        if not ok:
            return None
        def size(r: Remedy) -> float:
            p = r.change_pct
            if p is not None:
                return abs(p)
            if r.change is not None and r.lever.kind == "temperature" and r.nominal:
                return abs(100.0 * r.change / (float(r.nominal) + 273.15))
            return 1e9  # discrete choices last
        return min(ok, key=size)

    def line(self) -> str:
        """The page-1 line: what it takes to pass (the smallest change) and its effects."""
        if self.status == "pass":
            return ""
        b = self.best()
        if not self.remedies:
            return "What it takes to pass: no design lever is listed for this rule"
        if b is None:
            txt = "no lever of the table passes it within its bounds"
        else:
            txt = b.text()
            eff = [f"{e['rule']} {e['item']} {e['to']}" for e in b.side_effects]
            txt += ("; side effects: " + ", ".join(eff)) if eff else "; no other result changes"
        if self.conflicts:
            txt += (". " + self.conflicts[0].split(" (")[0]
                    + ": see 'What it takes to pass'")
        return "To pass: " + txt

    def as_dict(self) -> dict:
        b = self.best()
        return {"rule": self.rule, "item": self.item, "status": self.status,
                "levers": [r.as_dict() for r in self.remedies],
                "best": b.lever.id if b is not None else None,
                "conflicts": self.conflicts, "what_it_takes": self.line() or None}


# ---------------------------------------------------------------- jobs (one lever, one result)
@dataclass
class _Job:
    res: ResultRemedies
    rule: str
    item: str
    lever: Lever
    binding: Binding
    remedy: Remedy
    sign: int  # +1 lever rises, -1 it falls
    want_pass: bool  # True: find the first passing value (a failing result)
    x0: float | None = None
    xb: float | None = None
    guess: float | None = None
    pts: list[tuple[Any, float | None]] = field(default_factory=list)
    bracket: tuple[tuple[float, float], tuple[float, float]] | None = None  # (bad, good)
    side: int = 0  # Illinois: which end was kept last
    done: bool = False
    queue: list[Any] = field(default_factory=list)
    cands: list[Any] = field(default_factory=list)  # discrete: choices still to try
    twin: _Job | None = None  # the same result and lever in the other direction
    held: list[Any] = field(default_factory=list)  # trial values waiting for the twin
    screen: bool = False  # trial values checked at the screening speeds (screening.py)
    confirm: Any = None  # a value that passes there, being checked at every speed
    full_x: set[str] = field(default_factory=set)  # values checked at every speed (repr)
    full_res: dict[str, tuple] = field(default_factory=dict)  # value -> (items, packed, check)
    tol: float = TOL  # the accepted margin window's width

    @property
    def key(self) -> str:
        return self.item if self.lever.separable else f"__{self.lever.id}"

    def ok(self, m: float | None) -> bool:
        if m is None:
            return False
        return (m >= -REL_TOL) if self.want_pass else (m < -REL_TOL)


def _margin_of(res, rule, item) -> float | None:
    r = find(res, rule, item)
    if r is None or r.status == "not_evaluated" or r.margin is None:
        return None
    return float(r.margin)


def _discrete_candidates(job: _Job) -> list[Any]:
    """The choices a discrete lever tries beyond today's value, nearest first, by the kind of
    its choices: a table of several columns (a bolt size), numbers (a bolt count), texts
    ranked by the lever (oil grades by viscosity), or texts in the order given."""
    lv = job.lever
    today = job.binding.nominal
    choices = list(lv.choices)
    if isinstance(choices[0], dict):
        return _table_candidates(choices, [f.label for f in job.binding.fields], tuple(today),
                                 job.sign)
    if all(isinstance(c, (int, float)) for c in choices):
        return _number_candidates(choices, today[0], job.sign)
    names = [str(c) for c in choices]
    order = choice_order(lv)
    if order is not None:
        return _ranked_candidates(names, today[0], order, job.sign)
    return _listed_candidates(names, today[0], job.sign)


def _table_candidates(choices: list[dict], keys: list[str], now: tuple, sign: int
                      ) -> list[dict]:
    """Choices that are rows of several columns (e.g. an ISO metric bolt's diameter and
    pitch), ranked by their columns ``keys`` in order: those beyond today's row ``now``."""
    def rank(c):
        return tuple(float(c[k]) for k in keys)
    ordered = sorted(choices, key=rank)
    pos = [i for i, c in enumerate(ordered) if rank(c) == now]
    if pos:
        i = pos[0]
    else:
        i = sum(1 for c in ordered if rank(c) < now) - (0 if sign > 0 else 1)
        i = i - 1 if sign > 0 else i + 1
    return ordered[i + 1:] if sign > 0 else ordered[:max(i, 0)][::-1]


def _number_candidates(choices: list[Any], today: Any, sign: int) -> list[float]:
    """Numeric choices (e.g. the number of bolts) beyond today's value; none for a blank."""
    now = float(today) if today is not None else None
    if now is None:
        return []
    vals = sorted(float(c) for c in choices)
    return [v for v in vals if v > now] if sign > 0 else [v for v in vals if v < now][::-1]


def _listed_candidates(names: list[str], today: Any, sign: int) -> list[str]:
    """Text choices in the order given (e.g. property classes, weaker to stronger): those
    after today's (case-insensitive) in the lever's direction; none when today's is not
    listed."""
    now = str(today or "").strip().upper()
    up = [n.upper() for n in names]
    if now not in up:
        return []
    i = up.index(now)
    return names[i + 1:] if sign > 0 else names[:i][::-1]


def _ranked_candidates(names: list[str], today: Any, order, sign: int) -> list[str]:
    """Text choices ranked by ``order`` (e.g. oil grades by their SAE J300 viscosity): those
    strictly beyond today's rank in the lever's direction, nearest first, one per rank (of
    equal ranks the one sharing today's first word, e.g. the winter grade ``5W``, else the
    first listed). Today's value need not be among the choices."""
    try:
        now = order(str(today or ""))
    except ValueError:
        return []
    ranked: dict[Any, list[str]] = {}
    for n in names:
        ranked.setdefault(order(n), []).append(n)
    keys = sorted((k for k in ranked if (k > now if sign > 0 else k < now)),
                  reverse=sign < 0)
    def first_word(text: str) -> str | None:
        m = re.match(r"\s*(?:SAE\s*)?(\d+\s*W)", text, flags=re.IGNORECASE)
        return m.group(1).replace(" ", "").upper() if m else None

    head = first_word(str(today))
    out = []
    for k in keys:
        same = [n for n in ranked[k] if head is not None and first_word(n) == head]
        out.append(same[0] if same else ranked[k][0])
    return out


def _start(job: _Job, value: float | None, limits: list[float] | None, check: str) -> None:
    """The first trial value of a continuous job: the proportional guess (value ~ input^p,
    p = +-1), or 1/8 of the way to the bound when there is none."""
    lv = job.lever
    x0 = job.binding.nominal[0]
    if not isinstance(x0, (int, float)):
        job.done, job.remedy.reason = True, "today's value is blank (no default)"
        return
    x0 = float(x0)
    if lv.limits is not None:
        xb = lv.limits[1] if job.sign > 0 else lv.limits[0]
    else:
        xb = x0 * (lv.bounds[1] if job.sign > 0 else lv.bounds[0])
    if (xb - x0) * job.sign <= 0:
        job.done, job.remedy.reason = True, "today's value is at the lever's bound"
        return
    job.x0, job.xb = x0, xb
    first = x0 + (xb - x0) * FRACTIONS[0]
    # proportional starting guess (value ~ input^p, p = +-1): only a guess, always checked
    if value and limits and lv.kind != "temperature" and x0 != 0 and lv.separable:
        target = min(limits, key=lambda L: abs(L - value))
        up = target > value  # the value must rise
        ratio = target / value if value else None
        if ratio and ratio > 0:
            p = 1.0 if ((job.sign > 0) == up) else -1.0
            g = x0 * ratio ** (1.0 / p)
            if job.want_pass:
                g = x0 + (g - x0) * (1 + 1e-6)  # exact when proportional: just passing
            if (g - x0) * job.sign > 0 and abs(g - x0) < abs(xb - x0):
                job.guess = g
                first = g
    job.queue = [float(f"{first:.10g}")]


def _aim(job: _Job) -> float:
    """The margin aimed at: the middle of the accepted window ([0, TOL] for a failing result,
    [-TOL, 0] for a passing one), so that one interpolation step usually lands in it."""
    return 0.5 * job.tol if job.want_pass else -0.5 * job.tol


def _accept(job: _Job, x: Any, m: float) -> None:
    if job.screen and repr(x) not in job.full_x:
        # passes at the screening speeds: checked at every speed before it is an answer
        job.confirm, job.queue = x, [x]
        return
    job.remedy.value, job.remedy.margin, job.remedy.found = x, m, True
    job.done = True


def _in_window(job: _Job, m: float | None) -> bool:
    if m is None or not job.ok(m):
        return False
    return m <= job.tol if job.want_pass else m >= -job.tol


def _advance(job: _Job, evaluated: list[tuple[Any, float | None]]) -> None:
    """Take the margins of the job's trial values (and points shared by other jobs of the
    same lever) and queue the next one (:func:`_advance_discrete` for a lever of choices,
    :func:`_advance_continuous` for one of numbers)."""
    own = [p for p in evaluated if len(p) == 2]
    # points of other jobs; those checked at the screening speeds only for screened jobs
    shared = [(p[0], p[1]) for p in evaluated if len(p) == 3 and (job.screen
                                                                   or p[2] == "full")]
    if job.done:
        return
    if job.confirm is not None:
        restart = _confirmed(job, own, shared)
        if restart is None:
            return
        own, shared = restart
    if not job.lever.discrete and job.x0 is not None:
        # shared points count only on this job's side of today's value, within its bound
        shared = [(x, m) for x, m in shared if (x - job.x0) * job.sign > 0
                  and abs(x - job.x0) <= abs(job.xb - job.x0) * (1 + 1e-12)]
    if job.queue and not own:
        # the job's own trial values are still to come: keep what others learnt for later
        job.pts += shared
        return
    evaluated = own + shared
    job.pts += evaluated
    job.remedy.evaluations += len(own)
    if job.lever.discrete:
        _advance_discrete(job, evaluated)
    else:
        _advance_continuous(job, evaluated)


def _confirmed(job: _Job, own: list, shared: list) -> tuple[list, list] | None:
    """A value that passed at the screening speeds, checked at every speed (its own check,
    or an equal job's: the four big ends): accepted, or still waiting (None); when it does
    not pass at every speed (the result is worst at a speed outside the screening speeds
    there), the search goes on at every speed from this point: the points to go on with."""
    c = repr(job.confirm)
    at = [p for p in own + shared if repr(p[0]) == c] if c in job.full_x else []
    if not at:
        return None
    x, m = at[0]
    job.confirm = None
    job.remedy.evaluations += len(own)
    if (job.ok(m) if job.lever.discrete else _in_window(job, m)):
        _accept(job, x, m)
        return None
    job.screen = False
    job.pts, job.bracket, job.side = [], None, 0
    return [], [(x, m)]


def _advance_discrete(job: _Job, evaluated: list[tuple[Any, float | None]]) -> None:
    """A lever of choices: the first evaluated choice that passes is the answer, else the
    next choice (one per round), else no standard choice passes."""
    for x, m in evaluated:  # candidates in order, one per round
        if job.ok(m):
            _accept(job, x, m)
            return
    if job.cands:
        job.queue = [job.cands.pop(0)]
        return
    best = [m for _, m in job.pts if m is not None]
    job.remedy.best_margin = max(best) if best else None
    job.remedy.reason = ("no standard choice within the table passes" if job.want_pass
                         else "no choice reaches the limit")
    job.done = True


def _advance_continuous(job: _Job, evaluated: list[tuple[Any, float | None]]) -> None:
    """A lever of numbers: a secant step towards the aimed margin from the two points nearest
    to it until a value passes (doubling the step when the margin does not improve), then
    inverse quadratic interpolation / Illinois regula falsi in the bracket."""
    aim = _aim(job)
    if job.bracket is None:
        if not _bracketed(job, aim):
            return
    elif not _narrowed(job, evaluated, aim):
        return
    _step_in_bracket(job, aim)


def _bracketed(job: _Job, aim: float) -> bool:
    """Walk the points out from today: the first one that passes brackets the root (True);
    one in the accepted window is the answer, and without a passing point the walk goes on
    (:func:`_walk_on`) (False)."""
    prev = (job.x0, job.res.margin)
    walked: list[tuple[float, float]] = []
    for x, m in sorted(job.pts, key=lambda p: abs(p[0] - job.x0)):
        if m is None:  # invalid input there: treat as the end of the range
            break
        if job.ok(m):
            if _in_window(job, m):
                _accept(job, x, m)
                return False
            job.bracket = ((prev[0], prev[1]), (x, m))
            return True
        prev = (x, m)
        walked.append((x, m))
    _walk_on(job, walked, aim)
    return False


def _best_margin(job: _Job) -> float | None:
    """The best margin the walk reached (the largest for a failing result, the smallest for a
    passing one walked towards its limit); None without a valid point."""
    ms = [m for _, m in job.pts if m is not None]
    return (max(ms) if job.want_pass else min(ms)) if ms else None


def _walk_on(job: _Job, walked: list[tuple[float, float]], aim: float) -> None:
    """No value passes yet: none within the bounds when the walk reached the bound or an
    invalid input, else the next step out (:func:`_reach`)."""
    invalid = any(m is None for _, m in job.pts)
    at_bound = any(abs(x - job.xb) <= 1e-12 * max(abs(job.xb), 1.0) for x, _ in walked)
    if invalid or at_bound:
        job.remedy.best_margin = _best_margin(job)
        job.remedy.reason = "no value within the bounds" + (
            f" ({with_unit(job.xb, job.lever.unit)})" if job.xb is not None else "")
        job.done = True
        return
    if job.remedy.evaluations >= MAX_STEPS:
        job.remedy.best_margin = _best_margin(job)
        job.done, job.remedy.reason = True, "root finding did not converge"
        return
    if not walked:
        job.queue = [float(f"{job.x0 + (job.xb - job.x0) * FRACTIONS[0]:.10g}")]
        return
    job.queue = [_reach(job, [(job.x0, job.res.margin)] + walked, aim)]


def _narrowed(job: _Job, evaluated: list[tuple[Any, float | None]], aim: float) -> bool:
    """The bracket narrowed by the points inside it (Illinois: the end kept twice in a row
    has its margin halved towards the aim); False when a point is the answer or the input
    becomes invalid inside the bracket."""
    (xa, ma), (xg, mg) = job.bracket
    for x, m in sorted(evaluated, key=lambda p: abs(p[0] - xg)):
        if not (min(xa, xg) < x < max(xa, xg)):
            continue  # a shared point outside the bracket
        if m is None:
            job.done, job.remedy.reason = True, "the input becomes invalid"
            return False
        if job.ok(m):
            if _in_window(job, m):
                _accept(job, x, m)
                return False
            xg, mg = x, m
            if job.side == 1:
                ma = aim + (ma - aim) / 2.0
            job.side = 1
        else:
            xa, ma = x, m
            if job.side == -1:
                mg = aim + (mg - aim) / 2.0
            job.side = -1
    job.bracket = ((xa, ma), (xg, mg))
    return True


def _step_in_bracket(job: _Job, aim: float) -> None:
    """The next trial value inside the bracket: inverse quadratic interpolation, else regula
    falsi, else bisection; the passing end is the answer when the bracket has closed."""
    if job.remedy.evaluations >= MAX_STEPS:
        job.done, job.remedy.reason = True, "root finding did not converge"
        return
    (xa, ma), (xg, mg) = job.bracket
    lo, hi = sorted((xa, xg))
    w = hi - lo
    x = _iqi(job, lo, hi, aim)
    if x is None:
        if mg == ma:
            x = 0.5 * (xa + xg)
        else:
            x = xg - (mg - aim) * (xg - xa) / (mg - ma)
    if not (lo + 1e-3 * w < x < hi - 1e-3 * w):
        x = 0.5 * (xa + xg)
    if job.want_pass:
        x = x + (xg - xa) * 1e-9  # nudge to the passing side
    x = float(f"{x:.10g}")  # equal jobs (four identical big ends) share their evaluations
    if abs(xg - xa) <= 1e-12 * max(abs(xg), 1.0):
        _accept(job, xg, mg)
        return
    job.queue = [x]


def _reach(job: _Job, walked: list[tuple[float, float]], aim: float) -> float:
    """The next trial value before a passing one is known: the secant through the two
    evaluated points farthest from today (today included) extrapolated to the aimed margin,
    by at most four times the last step; when the margin did not move towards the limit, the
    lever's bound after the first step, twice the distance from today after later ones; never
    beyond the bound."""
    x0, xb = job.x0, job.xb
    (xp, mp), (xl, ml) = walked[-2], walked[-1]
    step = xl - xp
    toward = (ml - mp) * (1.0 if job.want_pass else -1.0) > 0
    if toward and step != 0:
        x = xl + (aim - ml) * step / (ml - mp)
        x = xl + max(min((x - xl) / step, 4.0), 0.25) * step  # within 1/4..4 last steps
    elif len(walked) == 2:
        # the first step moved the margin away from the limit: the bound decides (a value
        # between would pass only where the response turns back)
        x = xb
    else:
        # past a best point (the response turns back): on at twice the distance
        x = xl + 2.0 * (xl - x0 if xl != x0 else (xb - x0) * FRACTIONS[0])
    if (x - xb) * job.sign > 0:
        x = xb
    if job.want_pass and x != xb:
        x = x + (x - xl) * 1e-9  # nudge to the passing side
    return float(f"{x:.10g}")


def _iqi(job: _Job, lo: float, hi: float, aim: float = 0.0) -> float | None:
    """Inverse quadratic interpolation through the three evaluated points nearest to the
    root (x as a quadratic in the margin, at the aimed margin); None when not inside the
    bracket."""
    pts = [(x, m - aim) for x, m in job.pts + [(job.x0, job.res.margin)]
           if m is not None and x is not None and lo <= x <= hi]
    pts = sorted(set(pts), key=lambda p: abs(p[1]))[:3]
    if len(pts) < 3:
        return None
    (x0, f0), (x1, f1), (x2, f2) = pts
    if len({f0, f1, f2}) < 3:
        return None
    x = (x0 * f1 * f2 / ((f0 - f1) * (f0 - f2)) + x1 * f0 * f2 / ((f1 - f0) * (f1 - f2))
         + x2 * f0 * f1 / ((f2 - f0) * (f2 - f1)))
    return x if lo < x < hi and math.isfinite(x) else None


def _mode(job: _Job) -> str:
    """How the job's next trial value is checked: ``confirm`` (a value that passes at the
    screening speeds, at every speed), ``screen`` (at the screening speeds) or ``full``."""
    return "confirm" if job.confirm is not None else "screen" if job.screen else "full"


def _pack(requests: list[tuple[_Job, Any]], pack: bool = True
          ) -> list[list[tuple[_Job, Any]]]:
    """Variants: requests of one separable lever's jobs on different items share one (when
    they are checked the same way, :func:`_mode`); others alone (``pack=False``: every
    request alone, the one-by-one path)."""
    if not pack:
        return [[r] for r in requests]
    variants: list[list[tuple[_Job, Any]]] = []
    keys: list[set[str]] = []
    cells: list[set] = []
    for job, x in requests:
        placed = False
        if job.lever.separable:
            for v, ks, cs in zip(variants, keys, cells):
                # only the same lever's jobs on other items: 'separable' is a property of
                # one lever (a bearing's width leaves the other bearings' films alone, but
                # the flywheel joint's slip depends on the bearings' friction)
                if job.key in ks or (cs & job.binding.cells) or any(
                        j.lever.id != job.lever.id or _mode(j) != _mode(job) for j, _ in v):
                    continue
                v.append((job, x))
                ks.add(job.key)
                cs |= job.binding.cells
                placed = True
                break
        if not placed:
            variants.append([(job, x)])
            keys.append({job.key})
            cells.append(set(job.binding.cells))
    return variants


def _toward(job: _Job) -> bool | None:
    """Did the job's first trial move the margin towards the limit (None: not yet known)?"""
    own = [(x, m) for x, m in job.pts if m is not None
           and (x - job.x0) * job.sign > 0] if job.x0 is not None else []
    if not own or job.res.margin is None:
        return None
    x, m = min(own, key=lambda p: abs(p[0] - job.x0))
    return (m - job.res.margin) * (1.0 if job.want_pass else -1.0) > 0


def _hold_twins(jobs: list[_Job]) -> None:
    """A lever tried in both directions (an 'either' lever, or a passing result): the
    direction whose first trial moved the margin away from the limit waits while the other
    one moved towards it, and is dropped when the other finds a value (the answer is the
    value nearest to today, and a response that first moves away would have to turn back to
    pass); it goes on when the other finds none."""
    for j in jobs:
        t = j.twin
        if t is None or j.done or j.lever.discrete:
            continue
        if j.held and t.done:
            if t.remedy.found:
                j.done, j.held = True, []
                j.remedy.reason = "the other direction passes nearer to today"
            else:
                j.queue, j.held = j.held, []
        elif (j.queue and not t.done and j.bracket is None and _toward(j) is False
              and _toward(t)):
            j.held, j.queue = j.queue, []


def _run(jobs: list[_Job], ev: Evaluator, pack: bool = True, nominal: Any = None,
         speeds: tuple[float, ...] | None = None, screen_rules: frozenset = frozenset()
         ) -> None:
    """Rounds of evaluations until every job is done. Identical variants are evaluated once;
    a variant that moves one lever alone serves every job of that lever (its other results
    are in the same check), so the jobs of a global lever such as the oil temperature share
    their trial values.

    Screened jobs (``speeds``: the screening speeds, :mod:`checker.remedies.screening`) have
    their trial values checked at those speeds when every rule of the variant is in
    ``screen_rules``; a value that passes there is checked at every speed on every rule whose
    status can change (:func:`_judgeable_rules` of ``nominal``), and that check gives its side
    effects."""
    while True:
        _hold_twins(jobs)
        requests = []
        for j in jobs:
            if not j.done and j.queue:
                requests += [(j, x) for x in j.queue]
                j.queue = []
        if not requests:
            return
        _round(jobs, requests, ev, pack, nominal, speeds, screen_rules)


def _round(jobs: list[_Job], requests: list[tuple[_Job, Any]], ev: Evaluator, pack: bool,
           nominal: Any, speeds: tuple[float, ...] | None, screen_rules: frozenset) -> None:
    """One round: the requests packed into variants, each checked on its rules (at the
    screening speeds where it can be), every job given the margins it learnt."""
    requests, invalid = _set_aside_invalid(requests, ev, pack)
    variants = _pack(requests, pack)
    changes, index = _variant_changes(variants)
    active = [j for j in jobs if not j.done]
    sels, screened = _selections(variants, index, changes, active, nominal, speeds,
                                 screen_rules)
    results = _check_by_selection(ev, changes, sels, screened, speeds)
    alone = _checked_alone(ev, variants, index, results)
    got: dict[int, list] = {}
    seen: set[tuple[int, Any]] = set()
    for j, x in invalid:  # not a valid workbook: no margin (as when checked alone)
        if (id(j), repr(x)) not in seen:
            seen.add((id(j), repr(x)))
            got.setdefault(id(j), []).append((x, None))
    for v, k in zip(variants, index):
        _own_margins(v, results[k], alone, not screened[k], got, seen)
        if pack and len(v) == 1 and not v[0][0].lever.discrete:
            _shared_margins(v[0], alone.get((id(v[0][0]), repr(v[0][1])), results[k]),
                            active, sels[k], screened[k], got, seen)
    for j in jobs:
        if id(j) in got:
            _advance(j, got[id(j)])


def _set_aside_invalid(requests: list[tuple[_Job, Any]], ev: Evaluator, pack: bool
                       ) -> tuple[list[tuple[_Job, Any]], list[tuple[_Job, Any]]]:
    """A request whose value alone is not a valid workbook (e.g. a width beyond the journal)
    is not packed with others: it would make their variant invalid too, and each of them
    would have to be checked again alone. Returns (the requests to check, the invalid)."""
    invalid: list[tuple[_Job, Any]] = []
    if not pack:
        return requests, invalid
    per_lever: dict[str, int] = {}
    for j, _ in requests:
        per_lever[j.lever.id] = per_lever.get(j.lever.id, 0) + 1
    for j, x in requests:
        if j.lever.separable and per_lever[j.lever.id] > 1:
            if ev.input_errors(j.binding.changes(x)) is not None:
                invalid.append((j, x))
    bad_ids = {(id(j), repr(x)) for j, x in invalid}
    return [(j, x) for j, x in requests if (id(j), repr(x)) not in bad_ids], invalid


def _variant_changes(variants: list[list[tuple[_Job, Any]]]) -> tuple[list[dict], list[int]]:
    """The cell changes of the distinct variants and, per variant, the index of its changes
    (identical variants checked the same way are evaluated once)."""
    changes: list[dict] = []
    uniq: dict[tuple, int] = {}
    index: list[int] = []
    for v in variants:
        ch: dict = {}
        for j, x in v:
            ch.update(j.binding.changes(x))
        key = (_mode(v[0][0]) == "confirm",) + tuple(sorted(ch.items(), key=repr))
        if key not in uniq:
            uniq[key] = len(changes)
            changes.append(ch)
        index.append(uniq[key])
    return changes, index


def _selections(variants: list[list[tuple[_Job, Any]]], index: list[int], changes: list[dict],
                active: list[_Job], nominal: Any, speeds: tuple[float, ...] | None,
                screen_rules: frozenset) -> tuple[list[frozenset], list[bool]]:
    """Per distinct variant the rules it is checked on and whether at the screening speeds
    only: its own jobs' rules (and those of the other jobs of the same lever, which learn
    from it: a bearing variant does not run the torsion), at the screening speeds when every
    job is screened and every rule screenable; a value being confirmed at every speed on
    every rule whose status can change (its side effects)."""
    sels: list[frozenset] = [frozenset()] * len(changes)
    screened = [True] * len(changes)
    for v, k in zip(variants, index):
        if _mode(v[0][0]) == "confirm":
            sels[k] = frozenset(_judgeable_rules(nominal, [changes[k]]) if nominal
                                is not None else {j.rule for j, _ in v})
            screened[k] = False
            continue
        sel = {j.rule for j, _ in v}
        if len(v) == 1:
            cells = v[0][0].binding.cells
            sel |= {j.rule for j in active if j.binding.cells == cells}
        sels[k] = sels[k] | sel
        screened[k] = screened[k] and all(_mode(j) == "screen" for j, _ in v)
    for k in range(len(changes)):
        screened[k] = bool(speeds) and screened[k] and sels[k] <= screen_rules
    return sels, screened


def _check_by_selection(ev: Evaluator, changes: list[dict], sels: list[frozenset],
                        screened: list[bool], speeds: tuple[float, ...] | None) -> list[Any]:
    """Each variant checked on its own jobs' rules (one group per selection; the groups
    shared among the helper processes): checked on the union of the round's rules, a damper
    variant would also run the fatigue, the flywheel and the joint torques that the torsion
    feeds (the I4: 6 s more in one process)."""
    results: list[Any] = [None] * len(changes)
    how = [(sels[k], screened[k]) for k in range(len(changes))]
    groups = [[k for k in range(len(changes)) if how[k] == h] for h in dict.fromkeys(how)]
    for ks, got in zip(groups, ev.evaluate_groups([
            ([changes[k] for k in ks], sorted(sels[ks[0]]),
             speeds if screened[ks[0]] else None) for ks in groups])):
        for k, r in zip(ks, got):
            results[k] = r
    return results


def _checked_alone(ev: Evaluator, variants: list[list[tuple[_Job, Any]]], index: list[int],
                   results: list[Any]) -> dict[tuple[int, str], Any]:
    """A packed variant that is not a valid workbook (one job's trial value outside a field's
    range): its requests checked alone, so the others' values still count."""
    alone: dict[tuple[int, str], Any] = {}
    bad = [(j, x) for v, k in zip(variants, index) if len(v) > 1
           and not hasattr(results[k], "results") for j, x in v]
    if bad:
        for (j, x), r in zip(bad, ev.evaluate_variants(
                [j.binding.changes(x) for j, x in bad], select=[j.rule for j, _ in bad])):
            alone[(id(j), repr(x))] = r
    return alone


def _own_margins(v: list[tuple[_Job, Any]], res: Any, alone: dict, full: bool,
                 got: dict[int, list], seen: set) -> None:
    """The margins of a variant's own jobs at their trial values (``full``: checked at
    every speed; a value being confirmed keeps its check for its side effects)."""
    for j, x in v:
        r = alone.get((id(j), repr(x)), res)
        if full:
            j.full_x.add(repr(x))
            if _mode(j) == "confirm" and (id(j), repr(x)) not in alone:
                j.full_res[repr(x)] = ({i.item for i, _ in v}, len(v) > 1, r)
        if (id(j), repr(x)) not in seen:
            seen.add((id(j), repr(x)))
            got.setdefault(id(j), []).append((x, _margin_of(r, j.rule, j.item)))


def _shared_margins(request: tuple[_Job, Any], res: Any, active: list[_Job], sel: frozenset,
                    screened: bool, got: dict[int, list], seen: set) -> None:
    """A variant that moves one continuous lever alone: the same lever's other jobs learn
    their margins at its value (those whose rule it was checked on)."""
    j0, x0 = request
    for j in active:
        if j is j0 or j.lever.discrete or j.binding.cells != j0.binding.cells:
            continue
        if (id(j), repr(x0)) in seen or j.rule not in sel:
            continue
        seen.add((id(j), repr(x0)))
        if not screened:
            j.full_x.add(repr(x0))
            if _mode(j0) == "confirm" and _mode(j) == "confirm":
                j.full_res[repr(x0)] = ({j0.item}, False, res)
        got.setdefault(id(j), []).append((x0, _margin_of(res, j.rule, j.item),
                                          "screen" if screened else "full"))


def _side_effects(jobs: list[_Job], ev: Evaluator, nominal, pack: bool = True) -> None:
    """Run the check again at each answer (:func:`_judgeable_rules`): the results whose
    status changes."""
    base = {(r.rule, r.item): r.status for r in nominal.results}
    done = []
    for j in jobs:
        if not j.remedy.found:
            continue
        full = j.full_res.get(repr(j.remedy.value))
        if full is not None and hasattr(full[2], "results"):
            # checked at every speed on these rules when it was confirmed
            j.remedy.side_effects = _effects(j, full[2], full[0], full[1], base)
        else:
            done.append(j)
    # one evaluation per distinct answer (the same cells at the same value)
    uniq: dict[tuple, list[_Job]] = {}
    for j in done:
        ch = j.binding.changes(j.remedy.value)
        uniq.setdefault(tuple(sorted(ch.items(), key=repr)), []).append(j)
    groups = list(uniq.items())
    reqs = [(js[0], js[0].remedy.value) for _, js in groups]
    variants = _pack(reqs, pack)
    changes = []
    for v in variants:
        ch: dict = {}
        for j, x in v:
            ch.update(j.binding.changes(x))
        changes.append(ch)
    # one variant per task: their films were computed in the search (cached), and what is
    # left costs from milliseconds (a joint) to a second (a heat balance of every bearing),
    # so the processes end together only when they share the variants one by one
    results = ev.evaluate_variants(changes, select=_judgeable_rules(nominal, changes),
                                   task_size=1)
    by_first = {id(js[0]): js for _, js in groups}
    for v, res in zip(variants, results):
        if not hasattr(res, "results"):
            continue
        items = {j.item for j, _ in v if j.lever.separable}
        for j0, _ in v:
            for j in by_first[id(j0)]:
                j.remedy.side_effects = _effects(j, res, items, len(v) > 1, base)


def _effects(j: _Job, res: Any, items: set[str], packed: bool, base: dict) -> list[dict]:
    """The results of the check ``res`` at job ``j``'s answer whose status differs from
    ``base`` (nominal statuses), other than its own; in a variant that ``packed`` the answers
    of one separable lever on ``items``, the results of the other items are theirs."""
    eff = []
    for r in res.results:
        if (r.rule, r.item) == (j.rule, j.item):
            continue
        if j.lever.separable and packed and r.item in items and r.item != j.item:
            continue
        was = base.get((r.rule, r.item))
        if was is not None and was != r.status:
            eff.append({"rule": r.rule, "item": r.item, "from": was, "to": r.status,
                        "value": None if r.value is None else float(f"{r.value:.6g}"),
                        "unit": r.unit})
    return eff


def _judgeable_rules(nominal, changes: list[dict]) -> list[str]:
    """The rules whose results can change status in the variants ``changes``: those with
    results at nominal (a rule that applies to no item of this engine, e.g. the
    sputter-lining film guideline without sputter linings, is not applicable in a variant
    either),
    less those whose every result is not evaluated for a workbook limit left blank in cells
    that no variant fills (e.g. the shell supplier's film temperature: not judged at any
    lever value, so its heat balance of every bearing is not solved again for each answer
    of the oil temperature)."""
    moved = {f"{sh}!{get_column_letter(c)}{r}" for ch in changes for sh, r, c in ch}

    def stays_unjudged(r) -> bool:
        if r.status == "not_applicable":  # as before these were listed: no result to judge
            return True
        if r.status != "not_evaluated":
            return False
        for text in r.limit_missing:
            cells = set(CELL_REF.findall(text))
            if cells and not cells & moved:
                return True  # this limit stays missing: the result stays unjudged
        return False

    return sorted({r.rule for r in nominal.results if not stays_unjudged(r)})


def _conflicts(out: list[ResultRemedies]) -> None:
    """One lever on one item needed in opposite directions by failing results."""
    by: dict[tuple[str, str], list[tuple[ResultRemedies, Remedy]]] = {}
    for rr in out:
        if rr.status == "pass":
            continue
        for rm in rr.remedies:
            if rm.found and isinstance(rm.value, (int, float)) and not rm.lever.discrete:
                by.setdefault((rm.lever.id, rm.where), []).append((rr, rm))
    for (lid, _where), lst in by.items():
        lows = [(rm.value, rr) for rr, rm in lst if rm.direction > 0]  # needs >= value
        highs = [(rm.value, rr) for rr, rm in lst if rm.direction < 0]  # needs <= value
        if not lows or not highs:
            continue
        lo = max(lows, key=lambda t: t[0])
        hi = min(highs, key=lambda t: t[0])
        if lo[0] <= hi[0]:
            continue
        lever = lst[0][1].lever
        needs = "; ".join(f"{rr.rule} needs {'≥' if rm.direction > 0 else '≤'}"
                          f" {rm.value_text()}" for rr, rm in lst)
        names = sorted({rr.rule for rr, _ in lst})
        others = []
        for rr, _ in lst:
            can = [f"{rm.lever.name} {rm.value_text()}" for rm in rr.remedies
                   if rm.lever.id != lid and rm.found and not any(
                       e["to"] != "pass" and e["item"] == rr.item for e in rm.side_effects)]
            if can:
                others.append(f"{rr.rule}: {' or '.join(can)}")
        text = (f"Conflict: no {lever.name.lower()} passes {', '.join(names)} together"
                f" ({needs}).")
        text += (f" Levers that can: {'; '.join(others)}." if others
                 else " Change another input (see the lever table).")
        for rr, _ in lst:
            if text not in rr.conflicts:
                rr.conflicts.append(text)


def _row_values(base, lv: Lever, rows, attrs: tuple[str, ...]) -> dict[str, Any] | None:
    """Raw values of the result row's cells ``attrs`` (``{attr: value}``), or None when the
    lever needs none."""
    if not attrs:
        return None
    out: dict[str, Any] = {}
    for a in attrs:
        f = next(x for x in SHEETS[lv.sheet].fields if x.attr == a)
        b = bind(base, lv.sheet, (f,), "", rows, lv.where)
        out[a] = None if isinstance(b, str) else b.nominal[0]
    return out


def find_remedies(nominal, ev: Evaluator, levers: list[Lever], near: float = NEAR,
                  pack: bool = True, info: dict | None = None,
                  bind_lever: Callable[[Lever, str], Any] | None = None,
                  side_effects: bool = True, tol: float = TOL) -> list[ResultRemedies]:
    """Remedies for the failing results of ``nominal`` (a CheckResult) and for the passing
    ones within ``near`` of their limit, by every applicable lever.

    ``pack=False`` evaluates every trial value of every job on its own (the one-by-one path;
    the answers are the same, with more evaluations). ``info`` (a dict) receives
    ``screening_speeds``: the screening speeds [rad/s] used, or None. ``bind_lever(lever,
    item)`` gives the cells a lever moves instead of the workbook's (an object with the
    interface of :class:`Binding`: the sizing loop of ``checker new`` moves layout
    dimensions, :mod:`checker.sizing.loop`); ``side_effects=False`` leaves out the check
    at each answer for the results whose status it changes; ``tol``: the accepted window of
    an answer's margin ([0, tol]; a sizing loop accepts a wider one than :data:`TOL`)."""
    out: list[ResultRemedies] = []
    jobs: list[_Job] = []
    bindings: dict[tuple, Any] = {}
    for r in nominal.results:
        if r.status == "not_evaluated" or r.margin is None or r.internal_error:
            continue
        if r.status == "pass" and not (r.margin < near):
            continue
        rr = ResultRemedies(r.rule, r.item, r.status, r.margin)
        for lv in levers:
            if not lv.applies(r.rule, r.item):
                continue
            b = (_binding(ev, lv, r.item, bindings) if bind_lever is None
                 else bind_lever(lv, r.item))
            if isinstance(b, str):
                continue  # the lever's input is not in this workbook (e.g. another row),
                # or the lever does not apply to the row (e.g. torque on a yield-controlled
                # joint)
            jobs += _lever_jobs(rr, r, lv, b, tol)
        out.append(rr)
    rules = {r.id: r for r in getattr(nominal, "rules", ())}
    screen_rules = frozenset(i for i, r in rules.items() if screenable(r, nominal))
    speeds = _screen(jobs, nominal, screen_rules)
    if info is not None:
        info["screening_speeds"] = speeds
    _run(jobs, ev, pack, nominal, speeds, screen_rules)
    for rr in out:
        rr.remedies = _nearest_direction(rr.remedies)
    kept = {id(rm) for rr in out for rm in rr.remedies}
    if side_effects:
        _side_effects([j for j in jobs if id(j.remedy) in kept], ev, nominal, pack)
    _conflicts(out)
    return out


def _binding(ev: Evaluator, lv: Lever, item: str, bindings: dict[tuple, Any]) -> Any:
    """The cells lever ``lv`` moves for result item ``item`` (a :class:`Binding`), or why it
    has none here (a text); kept in ``bindings`` per lever and row."""
    rows = (item,) if lv.row == ITEM else ((lv.row,) if lv.row else None)
    key = (lv.id, rows)
    if key not in bindings:
        row = _row_values(ev.base, lv, rows, row_needs(lv))
        if row is not None and not lv.holds_for(row):
            bindings[key] = "not for this row (when)"
        else:
            bindings[key] = bind(ev.base, lv.sheet, lv.columns, lv.unit, rows, lv.where,
                                 row_default(lv, row or {}))
    return bindings[key]


def _lever_jobs(rr: ResultRemedies, r: Any, lv: Lever, b: Binding, tol: float = TOL
                ) -> list[_Job]:
    """The jobs of one lever on result ``r``: one per direction it may move (both for a
    passing result, whose margin reaches zero either way; none of a discrete lever there),
    each with its first trial value (:func:`_start_discrete`, :func:`_start`); their remedies
    are added to ``rr``."""
    signs = {"increase": [1], "decrease": [-1], "either": [1, -1]}[lv.direction]
    if r.status == "pass":
        signs = [1, -1]
        if lv.discrete:
            return []
    jobs: list[_Job] = []
    twin = None
    for s in signs:
        rm = Remedy(lv, ", ".join(b.labels), b.nominal[0] if len(b.nominal) == 1
                    else dict(zip([f.label for f in b.fields], b.nominal)), direction=s)
        if lv.discrete and len(b.fields) > 1:
            rm.nominal = {f.label: v for f, v in zip(b.fields, b.nominal)}
        job = _Job(rr, r.rule, r.item, lv, b, rm, s, r.status != "pass", tol=tol)
        if lv.discrete:
            _start_discrete(job)
        else:
            _start(job, r.value, r.limit_values, r.check)
        if twin is not None:
            job.twin, twin.twin = twin, job
        twin = job
        jobs.append(job)
        rr.remedies.append(rm)
    return jobs


def _start_discrete(job: _Job) -> None:
    """The first trial of a lever of choices: the first choice beyond today's, the next ones
    kept for while none passes."""
    cands = _discrete_candidates(job)
    if not cands:
        job.remedy.reason = "no further choice in that direction"
        job.done = True
    job.queue, job.cands = cands[:1], cands[1:]


def _screen(jobs: list[_Job], nominal: Any, screen_rules: frozenset
            ) -> tuple[float, ...] | None:
    """Failing results of bearing rules: their jobs' trial values checked at the screening
    speeds (:mod:`checker.remedies.screening`); the speeds, or None."""
    cand = [j for j in jobs if j.want_pass and not j.done and j.rule in screen_rules]
    speeds = screening_speeds(nominal, sorted({(j.rule, j.item) for j in cand})) if cand \
        else None
    if speeds:
        for j in cand:
            j.screen = True
    return speeds


def _nearest_direction(remedies: list[Remedy]) -> list[Remedy]:
    """Both directions of an 'either' lever: the found one nearest to today is kept (the
    first listed when neither is found)."""
    keep: list[Remedy] = []
    by_lever: dict[str, list[Remedy]] = {}
    for rm in remedies:
        by_lever.setdefault(rm.lever.id, []).append(rm)
    for lst in by_lever.values():
        found = [x for x in lst if x.found]
        if found:
            keep.append(min(found, key=lambda x: abs(x.change or 0.0)
                            if x.change is not None else 0.0))
        else:
            keep.append(lst[0])
    return keep


def is_finite(x) -> bool:
    return x is not None and math.isfinite(x)

