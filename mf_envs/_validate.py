"""Input validation shared by parameter dataclasses and envs: clear ValueErrors naming the field."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np


def check_finite(name: str, value: Any) -> np.ndarray:
    """Return `value` as a float64 array; ValueError naming `name` if any entry is NaN/inf."""
    if type(value) is float:  # fast path for scalars (reset hot path)
        if not math.isfinite(value):
            raise ValueError(f"{name}: must be finite, got {value!r}")
        return np.float64(value)
    if type(value) is int:  # an int beyond float64's range (10**400) is not finite as a float
        if not -_MAX_FLOAT <= value <= _MAX_FLOAT:
            raise ValueError(f"{name}: must be finite (|x| < 1.8e308), got {_short(value)}")
        return np.float64(value)
    _reject_non_numbers(name, value)
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ValueError(
            f"{name}: expected a real number or array of real numbers, got {_short(value)}"
        ) from exc
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: must be finite, got {_short(value)}")
    return arr


_MAX_FLOAT = float(np.finfo(np.float64).max)


def _short(value: Any) -> str:
    """`repr(value)`, cut to 80 characters (a 400-digit integer or a long list stays readable)."""
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:60]}... ({len(text)} characters)"


def _reject_non_numbers(name: str, value: Any) -> None:
    """ValueError naming `name` for bools, strings (also numeric ones) and containers of them:
    numpy would silently read True as 1.0 and "3" as 3.0."""
    items = value if isinstance(value, (list, tuple)) else (value,)
    for v in items:
        if isinstance(v, (list, tuple)):
            _reject_non_numbers(name, v)
        elif isinstance(v, (bool, np.bool_, str, bytes, complex, np.complexfloating, dict)):
            raise ValueError(f"{name}: expected a real number, got {_short(value)}")
        elif v is None:
            raise ValueError(f"{name}: expected a real number, got {_short(value)}")
    if isinstance(value, np.ndarray) and value.dtype.kind not in "iuf":
        raise ValueError(f"{name}: expected a real numeric array, got dtype {value.dtype}")


def check_range(
    name: str, value: Any, low: float | None = None, high: float | None = None
) -> float:
    """A finite real number (bools, strings, arrays rejected) in [low, high]; returns a float."""
    arr = check_finite(name, value)
    if arr.ndim != 0:
        raise ValueError(f"{name}: expected a number, got shape {arr.shape}")
    x = float(arr)
    if (low is not None and x < low) or (high is not None and x > high):
        lo = "-inf" if low is None else f"{low:g}"
        hi = "inf" if high is None else f"{high:g}"
        raise ValueError(f"{name}: must be in [{lo}, {hi}], got {value!r}")
    return x


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


def check_fields(obj: Any, label: str = "{}", **kinds: Iterable[str]) -> None:
    """Validate a parameter dataclass's fields by table, in the order given: each keyword is a
    check (`finite`, `positive`, `nonnegative`) and names the fields it applies to, e.g.
    `check_fields(self, positive=("mass", "length"), finite=("phase",))`. A field is named in
    the ValueError as `label.format(field)` (its public parameter, e.g.
    "friction_coefficients['{}']")."""
    for kind, names in kinds.items():
        check = _FIELD_CHECKS.get(kind)
        if check is None:
            raise TypeError(f"check_fields: unknown check {kind!r} (one of {tuple(_FIELD_CHECKS)})")
        for name in names:
            check(label.format(name), getattr(obj, name))


def check_shape(name: str, value: Any, shape: tuple[int, ...]) -> np.ndarray:
    """Finite float64 array of exactly `shape`."""
    arr = check_finite(name, value)
    if arr.shape != shape:
        raise ValueError(f"{name}: expected shape {shape}, got {arr.shape}")
    return arr


def check_int(name: str, value: Any, low: int | None = None, high: int | None = None) -> int:
    """An integer (bools rejected) within [low, high] when given."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        if type(value) is float and math.isfinite(value) and value.is_integer():
            value = int(value)
        else:
            raise ValueError(f"{name}: expected an integer, got {value!r}")
    value = int(value)
    if low is not None and value < low:
        raise ValueError(f"{name}: must be >= {low}, got {value}")
    if high is not None and value > high:
        raise ValueError(f"{name}: must be <= {high}, got {value}")
    return value


def arg_int(low: int, high: int) -> Any:
    """An argparse `type`: a whole number in [low, high]; otherwise argparse's one-line usage
    error (exit status 2) naming the option and the range, never an OverflowError later."""
    import argparse

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"must be in [{low}, {high}], got {_short(text)}")
        return value

    parse.__name__ = "int"  # argparse's messages name the type
    return parse


def check_choice(name: str, value: Any, choices: Iterable[Any]) -> Any:
    """`value` must be one of `choices`."""
    choices = tuple(choices)
    # an array, list or dict is never a choice (`in` would compare it elementwise or fail)
    if not isinstance(value, (str, int, float, type(None))) or value not in choices:
        raise ValueError(f"{name}: must be one of {choices}, got {value!r}")
    return value


def as_action(name: str, action: Any, shape: tuple[int, ...]) -> np.ndarray:
    """`action` as a finite float64 array of exactly `shape` (a single number is also taken
    for shape (1,)); ValueError naming `name` and the expected shape for strings, bools,
    objects, complex numbers, NaN/inf and any other shape, also one of the same size ((N, 1)
    for (N,), a flat (rows * N,) for (rows, N)): numpy would silently read "0.5" as 0.5 and
    True as 1.0, and a reshape would hide a caller's mix-up of rows and columns."""
    try:
        raw = np.asarray(action)
    except (TypeError, ValueError, OverflowError) as exc:  # ragged lists, odd objects
        raise ValueError(
            f"{name}: expected real numbers of shape {shape}, got {_short(action)}"
        ) from exc
    if raw.dtype.kind not in "iuf":
        raise ValueError(
            f"{name}: expected real numbers of shape {shape}, got {_short(action)} "
            f"(dtype {raw.dtype})"
        )
    if raw.shape != shape and not (raw.ndim == 0 and shape == (1,)):
        raise ValueError(f"{name}: expected shape {shape}, got shape {raw.shape}")
    a = raw.astype(np.float64).reshape(shape)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: must be finite, got {_short(action)}")
    return a


def finite_scalar(name: str, value: Any) -> float:
    """A finite real number (not an array, string or bool) as a float; ValueError naming `name`."""
    return _scalar(name, check_finite(name, value))


def positive_scalar(name: str, value: Any) -> float:
    """A finite real number > 0 as a float; ValueError naming `name`."""
    return _scalar(name, check_positive(name, value))


def nonnegative_scalar(name: str, value: Any) -> float:
    """A finite real number >= 0 as a float; ValueError naming `name`."""
    return _scalar(name, check_nonnegative(name, value))


def _scalar(name: str, arr: np.ndarray) -> float:
    if np.ndim(arr) != 0:
        raise ValueError(f"{name}: expected a number, got an array of shape {np.shape(arr)}")
    return float(arr)


_FIELD_CHECKS = {
    "finite": check_finite,
    "positive": check_positive,
    "nonnegative": check_nonnegative,
}
