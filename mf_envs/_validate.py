"""Input validation shared by parameter dataclasses and envs: clear ValueErrors naming the field."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np


def check_finite(name: str, value: Any) -> np.ndarray:
    """Return `value` as a float64 array; ValueError naming `name` if any entry is NaN/inf."""
    if type(value) is float or type(value) is int:  # fast path for scalars (reset hot path)
        if not math.isfinite(value):
            raise ValueError(f"{name}: must be finite, got {value!r}")
        return np.float64(value)
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name}: expected a number or array of numbers, got {value!r}") from exc
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: must be finite, got {value!r}")
    return arr


def check_positive(name: str, value: Any) -> np.ndarray:
    """Finite and > 0 (every entry); returns a float64 array."""
    arr = check_finite(name, value)
    if not (bool(arr > 0) if arr.ndim == 0 else np.all(arr > 0)):
        raise ValueError(f"{name}: must be > 0, got {value!r}")
    return arr


def check_nonnegative(name: str, value: Any) -> np.ndarray:
    """Finite and >= 0 (every entry); returns a float64 array."""
    arr = check_finite(name, value)
    if not (bool(arr >= 0) if arr.ndim == 0 else np.all(arr >= 0)):
        raise ValueError(f"{name}: must be >= 0, got {value!r}")
    return arr


def check_shape(name: str, value: Any, shape: tuple[int, ...]) -> np.ndarray:
    """Finite float64 array of exactly `shape`."""
    arr = check_finite(name, value)
    if arr.shape != shape:
        raise ValueError(f"{name}: expected shape {shape}, got {arr.shape}")
    return arr


def check_int(name: str, value: Any, low: int | None = None, high: int | None = None) -> int:
    """An integer (bools rejected) within [low, high] when given."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        else:
            raise ValueError(f"{name}: expected an integer, got {value!r}")
    value = int(value)
    if low is not None and value < low:
        raise ValueError(f"{name}: must be >= {low}, got {value}")
    if high is not None and value > high:
        raise ValueError(f"{name}: must be <= {high}, got {value}")
    return value


def check_choice(name: str, value: Any, choices: Iterable[Any]) -> Any:
    """`value` must be one of `choices`."""
    choices = tuple(choices)
    if value not in choices:
        raise ValueError(f"{name}: must be one of {choices}, got {value!r}")
    return value
