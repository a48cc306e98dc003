"""checker.plumbing.frame_stack: a call below a large frame gives what the plain call gives, and a
recursion going up and down inside it no longer maps fresh memory at every turn."""

import resource
import sys

import pytest

from checker.plumbing import frame_stack


def _depth(n: int) -> int:
    return 0 if n == 0 else _depth(n - 1) + 1


def _oscillate(turns: int) -> int:
    """A recursion 30-250 frames deep, up and down ``turns`` times (a layout's pattern)."""
    return sum(_depth(d) for _ in range(turns) for d in (30, 250, 90, 180))


def test_same_value_and_arguments_as_the_plain_call():
    assert frame_stack.call(divmod, 17, 5) == (3, 2)
    assert frame_stack.call(sorted, [3, 1, 2], reverse=True) == [3, 2, 1]
    assert frame_stack.call(_oscillate, 3) == _oscillate(3)


def test_errors_pass_through_unchanged():
    with pytest.raises(ValueError, match="invalid literal"):
        frame_stack.call(int, "not a number")
    with pytest.raises(RecursionError):  # the recursion limit still holds below the frame
        frame_stack.call(_depth, 10 * sys.getrecursionlimit())
    with pytest.raises(SystemExit):
        frame_stack.call(sys.exit, 3)


@pytest.mark.skipif(frame_stack._OUTER is None, reason="no chunked frame stack here")
def test_recursion_below_the_large_frame_touches_no_fresh_pages():
    """5000 turns of a recursion whose depth crosses many 16 KiB chunk boundaries: as a plain
    call, every crossing maps a fresh chunk (a page fault or more each); below the large
    frame the chunk stays mapped."""
    def faults_during(fn, *args):
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        fn(*args)
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before

    frame_stack.call(_oscillate, 5)  # anything the first calls touch
    inside = faults_during(frame_stack.call, _oscillate, 5000)
    assert inside < 200
    plain = faults_during(_oscillate, 5000)
    assert plain > 5000, "the plain call did not map chunks: the test shows nothing here"
