"""Crank type and firing order of a first layout: the most even firing the crank type allows.

A four-stroke cylinder fires at its compression TDC; with the crank's throw angles and the bank
angles fixed, each cylinder reaches TDC at one crank angle (mod 360 deg) and fires there or 360
deg later (which of the two is the camshaft's choice). :func:`arrange` searches those choices
(and, for V engines on shared pins, the usual pin arrangements) for the most even firing:
the smallest largest interval, then the largest smallest interval, then the most alternation
between the banks, then the lowest cylinder numbers first. Classical balancing and firing
theory (Taylor, C. F., The Internal-Combustion Engine in Theory and Practice, Vol. 2, rev. ed.,
MIT Press, 1985, ch. 8).

Conventions (those of the Cylinders sheet): throw angle = -firing angle (mod 360) on an in-line
engine; on a V engine a cylinder of bank angle ``b`` on a pin at throw angle ``t`` reaches TDC
at ``(b - b_1) - t`` (mod 360), ``b_1`` the bank of cylinder 1.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from .firing import inline_firing_order

CRANK_TYPES = ("shared pins", "split pins", "flat-plane", "cross-plane", "180 deg", "270 deg",
               "360 deg")


class NoArrangement(ValueError):
    """The crank type, bank angle or firing order cannot be arranged (the message says why)."""


@dataclass(frozen=True)
class Arrangement:
    """Throws and firing of a layout."""

    throw_angle: list[float]  # deg, per throw (crank pin)
    cyl_throw: list[int]  # per cylinder, 1-based
    cyl_bank: list[float]  # deg
    cyl_firing: list[float]  # deg
    firing_order: str
    note: str
    crank_type: str
    intervals: list[float]  # deg, in firing order
    even: bool


def intervals(firing: list[float]) -> np.ndarray:
    """Firing intervals [deg] over the 720-deg cycle, in firing order (wrapping)."""
    f = np.sort(np.mod(np.asarray(firing, float), 720.0))
    return np.diff(np.append(f, f[0] + 720.0))


def _order(firing: list[float]) -> list[int]:
    return sorted(range(len(firing)), key=lambda c: (round(firing[c] % 720.0, 6), c))


def _score(firing: list[float], banks: list[float]) -> tuple:
    gaps = intervals(firing)
    order = _order(firing)
    n = len(order)
    alt = sum(banks[order[i]] != banks[order[(i + 1) % n]] for i in range(n))
    return (round(float(gaps.max()), 6), -round(float(gaps.min()), 6),
            round(float(np.sum((gaps - 720.0 / n) ** 2)), 3), -alt, tuple(order))


def _inline_pins(k: int) -> list[float]:
    order = inline_firing_order(k)[0]
    f = [0.0] * k
    for j, c in enumerate(order):
        f[c - 1] = j * 720.0 / k
    return [(-x) % 360.0 for x in f]


def _parse_order(text: str | None, n: int) -> list[int] | None:
    if text is None:
        return None
    parts = [p for p in str(text).replace(",", "-").replace(" ", "-").split("-") if p]
    try:
        order = [int(p) for p in parts]
    except ValueError:
        raise NoArrangement(f"firing_order: expected the cylinders 1..{n} separated by '-',"
                            f" e.g. 1-3-4-2; found {text!r}") from None
    if sorted(order) != list(range(1, n + 1)):
        raise NoArrangement(f"firing_order: expected each cylinder 1..{n} once; found {text!r}")
    return order


def _matches(firing: list[float], order: list[int] | None) -> bool:
    if order is None:
        return True
    got = [c + 1 for c in _order(firing)]
    k = got.index(order[0])
    return got[k:] + got[:k] == order


def _best_choice(tdc: list[float], banks: list[float], order: list[int] | None
                 ) -> tuple[tuple, list[float]] | None:
    """Over every choice of firing at TDC or 360 deg later (cylinder 1 at its TDC): the best
    firing, or None when ``order`` cannot be met. The choices are screened together (largest
    and smallest interval, spread); the few best are ranked in full."""
    n = len(tdc)
    picks = np.array(list(itertools.product((0.0, 360.0), repeat=n - 1))).reshape(-1, n - 1)
    fire = np.mod(np.asarray(tdc, float)[None, :] + np.hstack(
        [np.zeros((len(picks), 1)), picks]), 720.0)
    srt = np.sort(fire, axis=1)
    gaps = np.diff(np.hstack([srt, srt[:, :1] + 720.0]), axis=1)
    if order is None:  # largest interval, most cylinders firing together, smallest interval
        together = (np.abs(fire[:, :, None] - fire[:, None, :]) < 1e-6).sum(axis=(1, 2))
        key = np.round(gaps.max(axis=1), 6) * 1e9 + together * 1e6 \
            - np.round(gaps.min(axis=1), 6) * 1e3 \
            + np.round(np.sum((gaps - 720.0 / n) ** 2, axis=1), 3) * 1e-3
        rows = np.flatnonzero(key <= key.min() + 1e-9)[:512]  # ties: ranked in full
    else:
        rows = np.arange(len(picks))
    best: tuple[tuple, list[float]] | None = None
    for r in rows:
        firing = [float(x) for x in fire[r]]
        if not _matches(firing, order):
            continue
        k = _score(firing, banks)
        if best is None or k < best[0]:
            best = (k, firing)
    return best


def arrange(cylinders: int, layout: str, bank_angle: float, crank_type: str | None,
            firing_order: str | None = None) -> Arrangement:
    """Throws and firing of the layout (module docstring); ``bank_angle`` in rad."""
    n = cylinders
    order = _parse_order(firing_order, n)
    alpha = math.degrees(bank_angle)
    if layout == "inline":
        return _inline(n, crank_type, order)
    banks = [alpha / 2 if c % 2 == 0 else -alpha / 2 for c in range(n)]  # odd cylinders left
    half = n // 2
    ctype = crank_type or "shared pins"
    if ctype == "split pins":
        return _split(n, alpha, banks, order)
    if ctype in ("180 deg", "270 deg", "360 deg"):
        ctype = "shared pins"  # a V-twin on one pin: its interval follows from the bank angle
    if ctype == "cross-plane":
        options = [("cross-plane crank (pins 0/90/270/180 deg)", [0.0, 90.0, 270.0, 180.0])]
    elif ctype == "flat-plane":
        options = [("flat-plane crank (pins 0/180/180/0 deg)", [0.0, 180.0, 180.0, 0.0])]
    elif half == 4:
        options = [("cross-plane crank (pins 0/90/270/180 deg)", [0.0, 90.0, 270.0, 180.0])]
        ctype = "cross-plane"
    else:
        pins = _inline_pins(half)
        options = [(f"pins as an in-line {half}", pins)]
        if half >= 3:
            options.append((f"pins as an in-line {half}, mirrored",
                            [(-p) % 360.0 for p in pins]))
    cyl_pin = [c // 2 + 1 for c in range(n)]
    best: tuple | None = None
    for how, pins in options:
        tdc = [((banks[c] - banks[0]) - pins[cyl_pin[c] - 1]) % 360.0 for c in range(n)]
        got = _best_choice(tdc, banks, order)
        if got is not None and (best is None or got[0] < best[0]):
            best = (got[0], got[1], how, pins)
    if best is None:
        raise NoArrangement(f"firing_order: {firing_order} cannot be fired by a V{n} at"
                            f" {alpha:g} deg on {ctype} (each cylinder fires at its TDC or"
                            " 360 deg later); leave it out for the most even order")
    _key, firing, how, pins = best
    note = (f"V{n}, {alpha:g} deg bank angle, two rods per pin ({ctype}), {how}; each"
            " cylinder fires at its TDC or 360 deg later, chosen for the most even firing"
            + ("" if order is None else " in the brief's firing order"))
    return _done(list(pins), cyl_pin, banks, firing, note, ctype)


def _inline(n: int, crank_type: str | None, order: list[int] | None) -> Arrangement:
    banks = [0.0] * n
    if n == 2 and crank_type in ("180 deg", "270 deg", "360 deg"):
        step = float(crank_type.split()[0])
        firing = [0.0, step]
        if order == [2, 1]:
            firing = [step, 0.0]
        throws = [(-f) % 360.0 for f in firing]
        return _done(throws, [1, 2], banks, firing, f"in-line twin, {crank_type} crank: throws"
                     f" {throws[0]:g}/{throws[1]:g} deg, firing {step:g} deg apart", crank_type)
    if crank_type not in (None, "shared pins") and n != 2:
        raise NoArrangement(f"crank_type: {crank_type!r} is for V engines (or twins); an"
                            f" in-line {n} has one throw per cylinder")
    how = "the brief's in-line firing order"
    if order is None:
        order, tabled = inline_firing_order(n)
        how = ("the usual in-line firing order" if tabled else "a derived in-line firing order"
               " (the smallest free moments, Taylor 1985 vol. 2 ch. 8)")
    step = 720.0 / n
    firing = [0.0] * n
    for k, c in enumerate(order):
        firing[c - 1] = k * step
    throws = [(-f) % 360.0 for f in firing]
    return _done(throws, list(range(1, n + 1)), banks, firing,
                 f"{how}, firing every {step:g} deg; throw angle = -firing angle (mod 360)",
                 "in-line")


def _split(n: int, alpha: float, banks: list[float], order: list[int] | None) -> Arrangement:
    """Split pins: each cylinder its own pin, offset within a pair so that the firing is even
    (V6: pair partners 720/n apart; 60-degree V6: 60 deg split, 90-degree V6: 30 deg)."""
    half = n // 2
    step = 720.0 / n
    if order is None:
        pair_order = inline_firing_order(half)[0]
        # pairs fire as an in-line of half the cylinders; each partner an odd number of
        # intervals after its mate, the one that makes the split between the pins smallest

        def split(m: int) -> float:
            return abs((banks[1] - banks[0] - m * step + 180.0) % 360.0 - 180.0)

        m = min(range(1, n, 2), key=lambda k: (round(split(k), 6), k))
        firing = [0.0] * n
        for k, p in enumerate(pair_order):
            firing[2 * p - 2] = k * 2 * step
            firing[2 * p - 1] = k * 2 * step + m * step
    else:
        firing = [0.0] * n
        for k, c in enumerate(order):
            firing[c - 1] = k * step
    throws = [((banks[c] - banks[0]) - firing[c]) % 360.0 for c in range(n)]
    note = (f"V{n}, {alpha:g} deg bank angle, split pins (one rod per pin, each pin offset for"
            f" even firing every {step:g} deg)")
    return _done(throws, list(range(1, n + 1)), banks, firing, note, "split pins")


def _done(throws: list[float], cyl_throw: list[int], banks: list[float], firing: list[float],
          note: str, ctype: str) -> Arrangement:
    n = len(firing)
    firing = [f % 720.0 for f in firing]
    gaps = intervals(firing)
    even = bool(np.allclose(gaps, 720.0 / n))
    text = "/".join(f"{g:g}" for g in gaps)
    note += ("; even firing every " + f"{720.0 / n:g} deg" if even else
             f"; the crank type does not allow even firing (intervals {text} deg)")
    order = "-".join(str(c + 1) for c in _order(firing))
    return Arrangement([round(t % 360.0, 6) for t in throws], cyl_throw, banks,
                       [round(f, 6) for f in firing], order, note, ctype,
                       [float(g) for g in gaps], even)
