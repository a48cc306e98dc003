"""Typed results of the calculation graph: what a node hands to the report and the outputs.

Each graph node (a :func:`checker.evaluation.graph.calculation`) returns named
:class:`~checker.evaluation.graph.
Quantity` arrays (the numbers rules judge) and, beside them, one frozen *detail* object per
quantity family: the curves, inputs and intermediate results a report section or the results
workbook shows (for example the flywheel's angular-speed trace, total inertia and target). The
detail's type is declared on the quantity (:attr:`checker.evaluation.graph.QuantitySpec.detail`)
and the
runner checks it, so a renamed or missing field fails in the check and in the type checker, not
when a PDF is rendered.

Conventions of every detail type:

* frozen dataclasses, keyword-only fields (``@dataclass(frozen=True, kw_only=True)``) that
  derive from :class:`Detail`;
* SI values (the unit in each field's comment or docstring); arrays are NumPy arrays whose
  axes are named in the comment (``(case, speed, angle)``...);
* ``assumptions``: sentences stated in the report's assumptions list (citing their source);
  ``caveats``: limits of validity found in this run (dicts ``{"text", "rules", ...}``, see
  :mod:`checker.results.caveats`).

The detail types of one analysis live in ``checker/results/<analysis>.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True, kw_only=True)
class Detail:
    """Base of every node's detail type: what every node may state besides its numbers."""

    assumptions: tuple[str, ...] = ()
    """Sentences for the report's assumptions list, each citing its source."""
    caveats: tuple[dict[str, Any], ...] = ()
    """Validity limits met in this run (:mod:`checker.results.caveats`)."""


def assumptions_of(q: Any) -> tuple[str, ...]:
    """The assumptions a quantity's detail states (none without a detail)."""
    d = getattr(q, "detail", None)
    return tuple(d.assumptions) if d is not None else ()


def caveats_of(q: Any) -> tuple[dict[str, Any], ...]:
    """The caveats a quantity's detail states (none without a detail)."""
    d = getattr(q, "detail", None)
    return tuple(d.caveats) if d is not None else ()
