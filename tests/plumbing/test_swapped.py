"""checker.plumbing.swapped: an attribute replaced inside the block and restored after it."""

import types

import pytest

from checker.plumbing import swapped


def test_replaced_inside_and_restored_after_also_on_an_error():
    obj = types.SimpleNamespace(level=9)
    with swapped.attribute(obj, "level", 6):
        assert obj.level == 6
    assert obj.level == 9
    with pytest.raises(RuntimeError), swapped.attribute(obj, "level", 1):
        raise RuntimeError("inside")
    assert obj.level == 9
