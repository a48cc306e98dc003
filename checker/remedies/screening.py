"""Screening speeds: the root finding of a bearing result at a few of the swept speeds.

A bearing's film thickness and specific load at one speed are computed from that speed alone
(one journal orbit per bearing, load case and speed): checked at a subset of the swept
speeds, a variant has, at those speeds, the values of a check at every speed, bitwise. A rule
judges the worst point over every speed, so its margin over the subset is never below its
margin over every speed. The remedy search of a failing result of such a rule therefore runs
its trial values at the speeds where that result is worst today (:data:`WORST` per item and
load case, with their neighbours), about a tenth of the orbits of a full check; a value that
passes there is checked again at every speed before it is an answer
(:mod:`checker.remedies.solve`), and the search goes on at every speed when it does not pass
there. "No value within the bounds" at the screening speeds holds at every speed (the margin
there is an upper bound).
"""

from __future__ import annotations

from typing import Any

import numpy as np

SPEED_LOCAL = frozenset({
    "bearing.moft_finite", "bearing.moft_short", "bearing.peak_specific_load",
    "bearing.peak_film_pressure", "bearing.peak_film_pressure_short"})
"""Quantities whose value at a speed depends on that speed alone (journal orbits and bearing
loads per speed); a rule on one of them may be screened."""

WORST = 2
"""Speeds per item and load case where the result is worst today (each with its neighbours
in the sweep)."""

MAX_SHARE = 0.5
"""No screening when the screening speeds would be more than this share of the sweep."""


def screenable(rule: Any, nominal: Any) -> bool:
    """True when ``rule`` (a chosen rule of the check ``nominal``) is judged on a
    speed-local quantity computed over the swept speeds."""
    q = nominal.outcome.quantities.get(rule.quantity)
    return (rule.quantity in SPEED_LOCAL and q is not None and "speed" in q.coords
            and "item" in q.coords and rule.check in (">=", ">", "<=", "<"))


def screening_speeds(nominal: Any, results: list[tuple[str, str]]) -> tuple[float, ...] | None:
    """The screening speeds [rad/s] of the results ``(rule, item)`` of ``nominal``: per
    result, item and load case the :data:`WORST` speeds in the rule's direction and their
    neighbours; ``None`` when a result's rule is not :func:`screenable` or the speeds would
    be more than :data:`MAX_SHARE` of the sweep."""
    rules = {r.id: r for r in nominal.rules}
    picked: set[int] = set()
    speeds = None
    for rule_id, item in results:
        rule = rules.get(rule_id)
        if rule is None or not screenable(rule, nominal):
            return None
        q = nominal.outcome.quantities[rule.quantity]
        items = list(q.coords["item"])
        if item not in items:
            return None
        sp = np.asarray(q.coords["speed"], dtype=float)
        speeds = sp if speeds is None else speeds
        if sp.shape != speeds.shape or not np.array_equal(sp, speeds):
            return None
        at = items.index(item)
        v = _rows(np.asarray(q.values, dtype=float), q, at)
        worst = v if rule.check in ("<=", "<") else -v  # larger = worse
        ok = np.isfinite(worst)
        if q.applies is not None:  # points the rule does not judge
            ok &= _rows(np.asarray(q.applies, dtype=bool), q, at)
        worst = np.where(ok, worst, -np.inf)
        for row in worst:
            for k in np.argsort(-row, kind="stable")[:WORST]:
                picked.update(j for j in (k - 1, k, k + 1) if 0 <= j < sp.size)
    if speeds is None or not picked or len(picked) > MAX_SHARE * speeds.size:
        return None
    return tuple(float(speeds[j]) for j in sorted(picked))


def _rows(a: np.ndarray, q: Any, at: int) -> np.ndarray:
    """Item ``at`` of an array over the quantity ``q``'s dims: a row over the speeds per
    point of its other dims (the load cases)."""
    a = np.broadcast_to(a, np.shape(q.values))[at]
    return np.moveaxis(a, list(q.coords).index("speed") - 1, -1).reshape(
        -1, len(q.coords["speed"]))


def in_rpm(speeds: tuple[float, ...]) -> list[float]:
    """Screening speeds [rad/s] in rpm (for what users read)."""
    from ..workbook.units import from_si

    return [float(from_si(x, "rad/s", "rpm")) for x in speeds]


def speeds_text(speeds: tuple[float, ...]) -> str:
    """``1000, 1100, 7000 rpm``."""
    return ", ".join(f"{x:.0f}" for x in in_rpm(speeds)) + " rpm"
