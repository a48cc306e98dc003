"""checker new (issue 43, item 7): a brief file's errors at file:line with key, expected and
found, exit code 2, no traceback (a binary file ended in an internal UnicodeDecodeError; a
refused cylinder count named neither key nor file); an even firing order for every in-line
count the brief accepts (1-16; in-line 7 was refused while the limit said 1-16).

Independent reference for the firing orders: the free forces and moments of the throws
summed here by order (Taylor 1985, vol. 2, ch. 8: each throw's force of order k along its
throw angle times k; the moment about the middle of the row), and for in-line 7 every one of
its 720 orders searched here."""

from __future__ import annotations

import itertools
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from checker import api
from checker.sizing import firing
from checker.sizing.brief import key_lines, parse_brief
from checker.sizing.new_engine import layout

BASE = 'bore = "80 mm"\nstroke = "80 mm"\nrated_power = "50 kW"\nrated_speed = "6000 rpm"\n'


def _new(tmp_path: Path, name: str, data: str | bytes) -> subprocess.CompletedProcess:
    brief = tmp_path / f"{name}.toml"
    if isinstance(data, bytes):
        brief.write_bytes(data)
    else:
        brief.write_text(data)
    # the open-loop layout (the brief and the firing orders; the loop has its own tests)
    return subprocess.run([sys.executable, "-m", "checker", "new", str(tmp_path / f"{name}.xlsx"),
                           "--brief", str(brief), "--no-iterate"], capture_output=True, text=True)


def _refused(r: subprocess.CompletedProcess, tmp_path: Path, name: str) -> str:
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr
    assert not (tmp_path / f"{name}.xlsx").exists()
    return r.stderr


def _free(theta_deg, order: int) -> tuple[float, float]:
    """|free force| and |free moment| of order ``order`` of unit throws at ``theta_deg``
    (cylinder pitch 1, moment about the middle of the row)."""
    t = np.radians(np.asarray(theta_deg, dtype=float))
    z = np.arange(t.size) - (t.size - 1) / 2
    ph = np.exp(1j * order * t)
    return abs(ph.sum()), abs((z * ph).sum())


@pytest.mark.parametrize("n", range(1, 17))
def test_every_inline_count_has_an_even_firing_order(n):
    order, tabled = firing.inline_firing_order(n)
    assert tabled == (n in (1, 2, 3, 4, 5, 6, 8))
    assert sorted(order) == list(range(1, n + 1)) and order[0] == 1
    th = firing.throw_angles(order)
    # each cylinder fires 720/n after the one before: throw = -firing angle (mod 360)
    fire = np.arange(n) * 720.0 / n
    np.testing.assert_allclose(th[np.array(order) - 1], (-fire) % 360.0, atol=1e-9)
    if n % 2 == 0:
        # mirror-symmetric crank: every free moment of orders 1 and 2 cancels, and the free
        # forces of orders below n/2
        np.testing.assert_allclose(th, th[::-1], atol=1e-9)
        for k in (1, 2):
            assert _free(th, k)[1] < 1e-9
        for k in range(1, n // 2):
            assert _free(th, k)[0] < 1e-9
    elif n >= 3:
        assert len(set(np.round(th, 6))) == n  # every throw at its own angle
        assert _free(th, 1)[0] < 1e-9 and _free(th, 2)[0] < 1e-9


def test_derived_orders_of_three_and_five_are_the_usual_ones():
    assert firing.derived_firing_order(3) == firing.INLINE_FIRING[3]
    assert firing.derived_firing_order(5) == firing.INLINE_FIRING[5]
    for n in (4, 6, 8):  # the same pin angles (a crank of the tabled balance)
        d = firing.throw_angles(firing.derived_firing_order(n))
        t = firing.throw_angles(firing.INLINE_FIRING[n])
        assert sorted(np.round(d, 6)) == sorted(np.round(t, 6))


def test_inline_seven_has_the_smallest_first_order_moment_of_all_720_orders():
    best = min(_free(firing.throw_angles((1, *p)), 1)[1]
               for p in itertools.permutations(range(2, 8)))
    got = firing.throw_angles(firing.derived_firing_order(7))
    assert _free(got, 1)[1] == pytest.approx(best, abs=1e-9)
    assert _free(got, 1)[1] < 0.1  # against 3.0 for the order 1-2-...-7


@pytest.mark.parametrize("n", (11, 13, 15))
def test_large_odd_counts_well_below_the_plain_order(n):
    got = _free(firing.throw_angles(firing.derived_firing_order(n)), 1)[1]
    plain = _free(firing.throw_angles(list(range(1, n + 1))), 1)[1]
    assert got < 0.1 * plain


def test_inline_seven_brief_writes_a_workbook_that_checks(tmp_path):
    r = _new(tmp_path, "i7", "cylinders = 7\n" + BASE)
    assert r.returncode == 0, r.stderr
    res = api.check(str(tmp_path / "i7.xlsx"), select=["BAL"])
    assert len(res.engine.cylinders) == 7
    lay = layout(parse_brief({"cylinders": 7, "bore": "80 mm", "stroke": "80 mm",
                              "rated_power": "50 kW", "rated_speed": "6000 rpm"}))
    assert lay.firing_order == "1-5-2-4-6-3-7"
    assert "a derived in-line firing order" in lay.firing_note
    assert "even firing every 102.857 deg" in lay.firing_note


def test_v14_takes_the_pins_of_an_inline_seven(tmp_path):
    b = parse_brief({"cylinders": 14, "layout": "V", "bore": "80 mm", "stroke": "80 mm",
                     "rated_power": "300 kW", "rated_speed": "6000 rpm"})
    lay = layout(b)
    assert "pins as an in-line 7" in lay.firing_note
    assert "even firing every" in lay.firing_note


def test_binary_brief_is_an_error_at_its_line(tmp_path):
    err = _refused(_new(tmp_path, "bin", b"cylinders = 4\n\x89PNG\r\n\x1a\n\x00\xff\xfe"),
                   tmp_path, "bin")
    assert "bin.toml:2: expected a text file (TOML, UTF-8)" in err
    assert "found the byte 0x89" in err


def test_toml_syntax_error_at_its_line(tmp_path):
    err = _refused(_new(tmp_path, "syn", "cylinders = 4\nbore = 86 mm\n" + BASE[15:]),
                   tmp_path, "syn")
    assert "syn.toml:2: expected TOML lines key = value" in err and "'bore = 86 mm'" in err


def test_refused_cylinder_count_names_file_line_and_key(tmp_path):
    text = 'name = "x"\n\ncylinders = 17\n' + BASE
    err = _refused(_new(tmp_path, "b17", text), tmp_path, "b17")
    assert "b17.toml:3: cylinders: no rule of checker new has data for 17 (covered: 1 to 16;" \
        in err
    err = _refused(_new(tmp_path, "v7", 'cylinders = 7\nlayout = "V"\n' + BASE), tmp_path, "v7")
    assert "v7.toml:1: cylinders: a V engine needs an even number of cylinders" in err
    assert "found 7" in err


def test_every_key_error_at_its_line(tmp_path):
    err = _refused(_new(tmp_path, "bad", 'cylinders = 0\n"bore" = 86\nlayot = "V"\n'
                                         'rated_speed = "6000 rpm"\n'), tmp_path, "bad")
    for text in ("bad.toml:1: cylinders: expected a whole number > 0",
                 "bad.toml:2: bore: expected a number with its unit",
                 "bad.toml:3: layot: unknown key", "bad.toml: stroke: required"):
        assert text in err, (text, err)


def test_key_lines():
    assert key_lines('# c\ncylinders = 4\n  "bore" = "1 mm"\nx.y = 1\n[t]\nz = 2\n') == {
        "cylinders": 2, "bore": 3, "x": 4}
