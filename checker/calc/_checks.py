"""Input checks shared by the calculation functions (messages name the argument)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def finite(name: str, value: ArrayLike) -> np.ndarray:
    """``value`` as a float array; ValueError if any element is NaN or infinite."""
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite (no NaN/inf), got {value!r}")
    return arr


def positive(name: str, value: ArrayLike) -> np.ndarray:
    """``value`` as a finite float array with every element > 0."""
    arr = finite(name, value)
    if np.any(arr <= 0.0):
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return arr


def non_negative(name: str, value: ArrayLike) -> np.ndarray:
    """``value`` as a finite float array with every element >= 0."""
    arr = finite(name, value)
    if np.any(arr < 0.0):
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return arr
