"""Crank types and firing (issue 47, item 4): the most even firing the crank type allows, the
intervals checked against classical firing theory (Taylor 1985, vol. 2, ch. 8), by hand."""

from __future__ import annotations

import math

import pytest

from checker.sizing.crank_types import NoArrangement, arrange, intervals


def _arr(n, layout, bank, ctype=None, order=None):
    return arrange(n, layout, math.radians(bank), ctype, order)


def test_inline_orders_are_even():
    for n, order in ((3, "1-2-3"), (4, "1-3-4-2"), (5, "1-2-4-5-3"), (6, "1-5-3-6-2-4")):
        a = _arr(n, "inline", 0)
        assert a.firing_order == order and a.even
        assert sorted(a.intervals) == [720.0 / n] * n


def test_v6_60_shared_pins_is_as_even_as_it_can_be():
    a = _arr(6, "V", 60)
    # with pins 120 deg apart and a 60 deg bank, every TDC is a multiple of 60 deg (mod 360):
    # the best split of six TDCs over 720 deg leaves one 180 and one 60 interval
    assert max(a.intervals) == 180.0 and min(a.intervals) == 60.0
    assert sorted(a.intervals) == [60.0, 120.0, 120.0, 120.0, 120.0, 180.0]
    assert not a.even and "does not allow even firing" in a.note


def test_v6_split_pins_fire_every_120_deg():
    for bank, split in ((60, 60.0), (90, 30.0)):
        a = _arr(6, "V", bank, "split pins")
        assert a.even and a.intervals == [120.0] * 6
        # partners of a pair: pins (720/n - bank) apart (60 deg V6: 60, 90 deg V6: 30)
        d = (a.throw_angle[0] - a.throw_angle[1]) % 360.0
        assert min(d, 360.0 - d) == pytest.approx(split)
        assert len(set(a.cyl_throw)) == 6


def test_v8_cross_and_flat_plane_fire_every_90_deg():
    c = _arr(8, "V", 90, "cross-plane")
    f = _arr(8, "V", 90, "flat-plane")
    assert c.throw_angle == [0.0, 90.0, 270.0, 180.0] and c.intervals == [90.0] * 8
    assert f.throw_angle == [0.0, 180.0, 180.0, 0.0] and f.intervals == [90.0] * 8
    # flat plane: the banks alternate at every firing (each bank an in-line four)
    order = [int(x) for x in f.firing_order.split("-")]
    assert all((order[i] % 2) != (order[(i + 1) % 8] % 2) for i in range(8))


def test_v12_and_v16_never_fire_cylinders_together():
    assert _arr(12, "V", 60).intervals == [60.0] * 12
    assert _arr(16, "V", 45).intervals == [45.0] * 16
    v16 = _arr(16, "V", 90)  # I8 pins at a 90 deg bank: pairs coincide, never four at once
    fire = sorted(f % 720.0 for f in v16.cyl_firing)
    assert max(sum(abs(x - y) < 1e-6 for y in fire) for x in fire) <= 2


def test_twins():
    t = _arr(2, "inline", 0, "270 deg")
    assert sorted(t.intervals) == [270.0, 450.0] and t.throw_angle == [0.0, 90.0]
    assert sorted(_arr(2, "inline", 0, "180 deg").intervals) == [180.0, 540.0]
    assert _arr(2, "inline", 0, "360 deg").intervals == [360.0, 360.0]
    assert sorted(_arr(2, "V", 90).intervals) == [270.0, 450.0]  # one pin, 90 deg V


def test_firing_order_of_the_brief():
    assert _arr(8, "V", 90, "cross-plane", "1-8-4-3-6-5-7-2").firing_order == "1-8-4-3-6-5-7-2"
    a = _arr(4, "inline", 0, None, "1-2-4-3")
    assert a.firing_order == "1-2-4-3" and a.intervals == [180.0] * 4
    with pytest.raises(NoArrangement, match="cannot be fired"):
        _arr(8, "V", 90, "cross-plane", "1-2-3-4-5-6-7-8")
    with pytest.raises(NoArrangement, match="each cylinder 1..4 once"):
        _arr(4, "inline", 0, None, "1-2-3")


def test_intervals_wrap_the_cycle():
    assert list(intervals([0.0, 270.0])) == [270.0, 450.0]
