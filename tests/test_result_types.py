"""Typed results (issue 24): every quantity a check computes carries a detail of the type its
spec declares (:attr:`checker.evaluation.graph.QuantitySpec.detail`), every detail type is a frozen,
keyword-only subclass of :class:`checker.results.Detail`, and a wrong detail is refused when
the quantity is made (not when a PDF is rendered)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from checker import api
from checker.evaluation import graph
from checker.results import Detail
from tests.helpers import example_path


@pytest.fixture(scope="module")
def i4(tmp_path_factory):
    return api.check(example_path(tmp_path_factory.mktemp("i4")))


def test_declared_detail_types_are_frozen_details():
    import checker.modules  # noqa: F401  (registers the quantities)

    for spec in graph.QUANTITIES.values():
        if spec.detail is None:
            continue
        assert issubclass(spec.detail, Detail), spec.name
        params = spec.detail.__dataclass_params__
        assert params.frozen, f"{spec.detail.__name__} of {spec.name} is not frozen"


def test_every_computed_detail_has_its_declared_type(i4):
    for name, q in i4.outcome.quantities.items():
        if q.spec.detail is not None and q.detail is not None:
            assert isinstance(q.detail, q.spec.detail), name
        if q.spec.detail is None:
            assert q.detail is None, name


def test_a_wrong_detail_is_refused():
    @dataclasses.dataclass(frozen=True, kw_only=True)
    class A(Detail):
        x: float

    @dataclasses.dataclass(frozen=True, kw_only=True)
    class B(Detail):
        y: float

    spec = graph.QuantitySpec("test.a", "", ("item",), "a test quantity", detail=A)
    graph.Quantity(spec, np.zeros(1), {"item": ["x"]}, detail=A(x=1.0))
    with pytest.raises(TypeError, match="declares A"):
        graph.Quantity(spec, np.zeros(1), {"item": ["x"]}, detail=B(y=1.0))
    bare = graph.QuantitySpec("test.b", "", ("item",), "no detail")
    with pytest.raises(TypeError, match="declares none"):
        graph.Quantity(bare, np.zeros(1), {"item": ["x"]}, detail=A(x=1.0))
    with pytest.raises(dataclasses.FrozenInstanceError):
        A(x=1.0).x = 2.0  # type: ignore[misc]
