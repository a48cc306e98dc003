"""Even firing orders of in-line four-stroke engines, 1 to 16 cylinders (``checker new``).

The usual orders of 1-6 and 8 cylinders are tabled (:data:`INLINE_FIRING`); the others are
derived by the classical balance argument for multi-cylinder engines (each crank throw a
rotating and a reciprocating force, the free moments the vector sums of those forces times
their distances from the crank's centre: Taylor, C. F., "The Internal-Combustion Engine in
Theory and Practice", vol. 2, rev. ed., MIT Press, 1985, ch. 8):

* even-firing means the cylinders fire 720/n deg apart; a cylinder's throw angle is minus its
  firing angle (mod 360 deg), so a firing order fixes the crank;
* an even count ``n = 2 m`` gets a mirror-symmetric crank (cylinders k and n + 1 - k on the
  same pin angle, firing 360 deg apart): every free moment cancels by the symmetry and the
  free forces of orders below m cancel (the m pin angles are 360/m apart). The first half's
  arrangement is the one with the smallest first-order moment of the half crank about its
  centre (the internal couple the middle main bearing carries), then the smallest
  second-order one; which cylinder of a pair fires first alternates the firings between the
  crank's front and rear halves as far as the pins allow;
* an odd count has every throw at its own angle and cannot cancel its moments: the order
  with the smallest first-order free moment, then the smallest second-order one, searched
  over every order up to 9 cylinders and by pairwise exchanges from several starts above
  (not proven the smallest there).

Ties go to the lexicographically first order. Derived for 3 and 5 cylinders, the orders are
the tabled ones; for 4, 6 and 8, cranks with the tabled ones' free forces and moments (zero
moments, the same pin angles; tests).
"""

from __future__ import annotations

import itertools

import numpy as np

__all__ = ["INLINE_FIRING", "MAX_CYLINDERS", "inline_firing_order", "derived_firing_order",
           "throw_angles"]

INLINE_FIRING = {1: [1], 2: [1, 2], 3: [1, 2, 3], 4: [1, 3, 4, 2], 5: [1, 2, 4, 5, 3],
                 6: [1, 5, 3, 6, 2, 4], 8: [1, 6, 2, 5, 8, 3, 7, 4]}
"""Usual in-line firing orders (even firing, 720/n apart); the throw angles follow."""

MAX_CYLINDERS = 16
"""Largest in-line count with a firing order (tabled or derived)."""

EXHAUSTIVE = 9
"""Odd counts up to this are searched over every order."""

_DIGITS = 9  # moments compared to 1e-9 (of a unit throw force times the cylinder pitch)


def throw_angles(order: list[int] | tuple[int, ...]) -> np.ndarray:
    """Throw angles [deg] of cylinders 1..n for an even-firing ``order``: minus the firing
    angle (k 720/n for the k-th cylinder to fire), mod 360."""
    n = len(order)
    fire = np.empty(n)
    fire[np.asarray(order) - 1] = np.arange(n) * 720.0 / n
    return (-fire) % 360.0


def _moments(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First- and second-order free moments (..., n) throw angles [deg] -> (...), per unit
    force and cylinder pitch, about the middle of the row."""
    n = theta.shape[-1]
    z = np.arange(n) - (n - 1) / 2.0
    t = np.radians(theta)
    return (np.round(np.abs((z * np.exp(1j * t)).sum(-1)), _DIGITS),
            np.round(np.abs((z * np.exp(2j * t)).sum(-1)), _DIGITS))


def _orders_throws(orders: np.ndarray) -> np.ndarray:
    """(K, n) firing orders -> (K, n) throw angles [deg]."""
    k, n = orders.shape
    fire = np.empty(orders.shape)
    np.put_along_axis(fire, orders - 1, np.broadcast_to(np.arange(n) * 720.0 / n, (k, n)),
                      axis=1)
    return (-fire) % 360.0


def _best(orders: np.ndarray, *keys: np.ndarray) -> list[int]:
    """The order with the smallest keys, ties to the lexicographically first order."""
    cols = [orders[:, j] for j in range(orders.shape[1] - 1, -1, -1)]
    i = np.lexsort(cols + [k for k in reversed(keys)])[0]
    return [int(c) for c in orders[i]]


def _odd(n: int) -> list[int]:
    if n <= EXHAUSTIVE:
        orders = np.array([(1, *p) for p in itertools.permutations(range(2, n + 1))])
        m1, m2 = _moments(_orders_throws(orders))
        return _best(orders, m1, m2)
    best: tuple | None = None
    for q in range(1, n):  # starts: cylinders in the steps q (mod n)
        start = [1 + (k * q) % n for k in range(n)]
        if len(set(start)) < n:
            continue
        cur = _exchange(start)
        if best is None or cur < best:
            best = cur
    return list(best[2])


def _key(order: list[int]) -> tuple:
    m1, m2 = _moments(throw_angles(order)[None, :])
    return (float(m1[0]), float(m2[0]), tuple(order))


def _exchange(order: list[int]) -> tuple:
    """Pairwise exchanges of two cylinders in the order (the first kept) while the key
    falls, the best exchange each pass."""
    cur = _key(order)
    n = len(order)
    while True:
        cands = []
        for i, j in itertools.combinations(range(1, n), 2):
            o = list(cur[2])
            o[i], o[j] = o[j], o[i]
            cands.append(o)
        orders = np.array(cands)
        m1, m2 = _moments(_orders_throws(orders))
        o = _best(orders, m1, m2)
        k = _key(o)
        if k >= cur:
            return cur
        cur = k


def _even(n: int) -> list[int]:
    m = n // 2
    step = 360.0 / m
    pins = np.array([(0, *p) for p in itertools.permutations(range(1, m))]) * step
    h1, h2 = _moments(pins)  # the half crank, cylinders 1..m
    cols = [pins[:, j] for j in range(m - 1, -1, -1)]
    half = pins[np.lexsort(cols + [h2, h1])[0]]
    rows = []
    for pick in itertools.product((0, 1), repeat=m - 1):  # which of a pair fires first
        fire = np.empty(n)
        fire[0], fire[n - 1] = 0.0, 360.0
        for k in range(1, m):
            f0 = (-half[k]) % 360.0
            a, b = (k, n - 1 - k) if pick[k - 1] == 0 else (n - 1 - k, k)
            fire[a], fire[b] = f0, f0 + 360.0
        rows.append(np.argsort(fire, kind="stable") + 1)
    orders = np.array(rows)
    front = orders <= m
    alternations = (front != np.roll(front, -1, axis=1)).sum(1)
    return _best(orders, -alternations)


def derived_firing_order(n: int) -> list[int]:
    """The derived even firing order of an in-line ``n``-cylinder four-stroke engine (module
    docstring: the rule and its source)."""
    if not 1 <= n <= MAX_CYLINDERS:
        raise ValueError(f"cylinders must be 1..{MAX_CYLINDERS}, got {n}")
    if n <= 2:
        return list(range(1, n + 1))
    return _odd(n) if n % 2 else _even(n)


def inline_firing_order(n: int) -> tuple[list[int], bool]:
    """``(order, tabled)``: the usual order where tabled (:data:`INLINE_FIRING`), else the
    derived one (:func:`derived_firing_order`)."""
    if n in INLINE_FIRING:
        return list(INLINE_FIRING[n]), True
    return derived_firing_order(n), False
