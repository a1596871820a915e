"""Named observation layouts: the one declaration of what each observation slot is.

Every env's `spec.py` declares its observation as an `ObsLayout` of `Field`s (name, size, unit,
bound, meaning). The env builds its `observation_space` from it (`layout.high(...)`), the
docstring's Observation table is checked against `layout.table()` (tests/test_env_api.py),
and controllers and tests address slots by name (`layout.index("roll")`,
`layout.slice("curvature")`), never by a literal position.

A bound is a number or the name of an env argument that sets it (e.g. "max_gimbal_rate"); the
numbers are supplied by `high(**values)`. All bounds are symmetric: the field lies in [-b, b].

A field's `scale` (default 1) is the fixed unit the observation is given in: the slot holds the
physical value / scale, so that a learner sees O(1) numbers without running normalisation (the
bound is stated in physical units; the slot's bound is bound / scale). Controllers read
physical values with `physical(obs)`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Field:
    """One named observation quantity: `size` consecutive float32 slots holding value / `scale`,
    the value within +-`bound` (in `unit`)."""

    name: str
    unit: str
    bound: float | str
    doc: str
    size: int = 1
    scale: float = 1.0


class ObsLayout:
    """An ordered tuple of `Field`s with name lookups (the observation's single declaration)."""

    def __init__(self, *fields: Field) -> None:
        self.fields = tuple(fields)
        self._start: dict[str, int] = {}
        n = 0
        for f in self.fields:
            if f.name in self._start:
                raise ValueError(f"fields: duplicate name {f.name!r}")
            self._start[f.name] = n
            n += f.size
        self.size = n

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.fields)

    def __len__(self) -> int:
        return self.size

    def field(self, name: str) -> Field:
        """The field called `name` (KeyError listing the names otherwise)."""
        if name not in self._start:
            raise KeyError(f"{name!r} is not an observation field; fields: {self.names}")
        return self.fields[self.names.index(name)]

    def index(self, name: str) -> int:
        """Slot of the scalar field `name`."""
        if self.field(name).size != 1:
            raise KeyError(f"{name!r} has {self.field(name).size} slots: use slice()")
        return self._start[name]

    def slice(self, name: str) -> slice:
        """Slots of the field `name` (any size)."""
        start = self._start[self.field(name).name]
        return slice(start, start + self.field(name).size)

    def high(self, values: Mapping[str, float] | None = None) -> np.ndarray:
        """Upper bounds (size,) float32; named bounds are looked up in `values`."""
        values = values or {}
        out = np.empty(self.size, dtype=np.float32)
        for f in self.fields:
            bound = values[f.bound] if isinstance(f.bound, str) else f.bound
            out[self.slice(f.name)] = bound / f.scale
        return out

    def scales(self) -> np.ndarray:
        """Each slot's scale (size,) float64: physical value = slot x scale."""
        out = np.empty(self.size)
        for f in self.fields:
            out[self.slice(f.name)] = f.scale
        return out

    def physical(self, obs: Any) -> np.ndarray:
        """The observation (..., size) in physical units (float64): slot x its field's scale."""
        return np.asarray(obs, dtype=np.float64) * self.scales()

    def unpack(self, obs: Any) -> dict[str, Any]:
        """{name: physical value} of one observation (scalars as float, vectors as arrays)."""
        obs = self.physical(obs)
        return {
            f.name: float(obs[self._start[f.name]]) if f.size == 1 else obs[self.slice(f.name)]
            for f in self.fields
        }

    def table(self) -> str:
        """The docstring's Observation Space table (markdown, one row per field; a scaled
        field's bound and unit are the slot's: +-bound / scale in units of scale x unit)."""
        rows = ["| Num | Name | Observation | Bound | Unit |", "|---|---|---|---|---|"]
        for f in self.fields:
            s = self.slice(f.name)
            num = str(s.start) if f.size == 1 else f"{s.start}..{s.stop - 1}"
            if isinstance(f.bound, str):  # the slot's bound and unit (the unit x its scale)
                bound = f.bound if f.scale == 1.0 else f"{f.bound} / {f.scale:g}"
            else:
                bound = f"{f.bound / f.scale:g}"
            unit = f.unit if f.scale == 1.0 else f"{f.scale:g} {f.unit}"
            rows.append(f"| {num} | {f.name} | {f.doc} | +-{bound} | {unit} |")
        return "\n".join(rows)


def check_options(options: Mapping[str, Any] | None, known: tuple[str, ...]) -> dict[str, Any]:
    """`reset(options=...)` as a dict; ValueError naming every unknown key and the known ones."""
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise ValueError(f"options: expected a dict or None, got {type(options).__name__}")
    bad = sorted(str(k) for k in options if k not in known)
    if bad:
        raise ValueError(f"options: unknown key(s) {bad}; known: {', '.join(known)}")
    return dict(options)


def check_curvature_option(value: Any, n: int, max_curvature: float) -> np.ndarray:
    """A `kappa` reset option of a beam robot: n finite numbers within +-max_curvature (1/m), as
    float64; ValueError naming `kappa` otherwise."""
    kappa = np.asarray(value)
    if kappa.shape != (n,) or kappa.dtype.kind not in "iuf":
        raise ValueError(f"kappa: expected {n} numbers, got {value!r}")
    kappa = kappa.astype(float)
    if not np.all(np.isfinite(kappa)) or np.any(np.abs(kappa) > max_curvature):
        raise ValueError("kappa: must be finite and within +-max_curvature")
    return kappa
