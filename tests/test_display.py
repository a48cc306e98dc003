"""Distances to limits in words: percent limits in percentage points, a zero value against an
upper limit as the value and the limit (checker/results/display.py)."""

from __future__ import annotations

import pytest

from checker.results import display


@pytest.mark.parametrize(("check", "value", "limit", "margin", "passed", "unit", "words"), [
    # the crank-nose bolt preload of Bell 2013: 79.51 % of proof against 70..75 %
    ("between", 79.51, [70, 75], -0.0601, False, "%", "4.51 points above the range"),
    ("between", 72.0, [70, 75], 0.0286, True, "%", "within the range (2 points from its nearer"
                                                   " end)"),
    ("between", 65.0, [70, 75], -0.0714, False, "%", "5 points below the range"),
    ("<=", 14.77, [10], -0.477, False, "%", "4.77 points above the limit"),
    ("<=", 6.31, [10], 0.369, True, "%", "3.69 points below the limit"),
    (">=", 1.0, [2], -0.5, False, "%", "1 point below the minimum"),
    # a free force of zero (an inline 4's first order) against a 500 N limit
    ("<=", 0.0, [500], 1.0, True, "N", "0 N (limit 500 N)"),
    ("<=", 1e-12, [0.5], 1.0, True, "kN", "0 kN (limit 0.5 kN)"),
    ("<=", 0.0, [5], 1.0, True, "%", "0 % (limit 5 %)"),
    # without a percent unit: relative wording as before
    ("<=", 554.5, [500], -0.109, False, "MPa", "limit exceeded by 11 %"),
    ("<=", 0.5728, [0.5], -0.1456, False, "MPa", "limit exceeded by 15 %"),
])
def test_margin_words_points_and_zero(check, value, limit, margin, passed, unit, words):
    assert display.margin_words(check, value, limit, margin, passed, unit) == words
