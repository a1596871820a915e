"""Grouped constructor kwargs: an env takes related kwargs as one dataclass (GOWEC-v0's
`gyro=GOWECParams(...)` and `sea=Sea(...)`), a dict of its fields, or as before one flat kwarg
per field (`rotor_speed=`, `wave_period=`): the flat names stay, as aliases of the fields.

`kwargs_of` turns what was given into the flat kwargs the env's `build` reads (defaults from
the dataclass); `list_aliases` gives the constructor a signature listing the aliases as keyword-only
parameters, so `inspect` (help(), `train.config`, `train.randomize`, `train.provenance`) sees
every kwarg it can pass."""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Callable, Mapping
from typing import Any


@dataclasses.dataclass(frozen=True)
class Group:
    """The kwarg `name` takes a `cls` (a dataclass whose every field has a default), a dict of
    some of its fields, or None (its defaults); `aliases` maps each flat kwarg to its field."""

    name: str
    cls: type
    aliases: Mapping[str, str]

    def defaults(self) -> dict[str, Any]:
        """flat kwarg -> the default of its field."""
        base = self.cls()
        return {alias: getattr(base, field) for alias, field in self.aliases.items()}

    def flatten(self, value: Any, flat: Mapping[str, Any]) -> dict[str, Any]:
        """The flat kwargs of the group given as `value` and of its aliases given in `flat`;
        ValueError naming the group for anything but a `cls`, a dict of its fields, or None, and
        naming the alias for a field given both ways with two values (a registered variant's
        flat kwarg and a user's group, say: neither silently wins)."""
        fields = {f.name for f in dataclasses.fields(self.cls)}
        if value is None:
            value = {}
        if type(value) is self.cls:
            value = {name: getattr(value, name) for name in fields}
        if not isinstance(value, Mapping):
            raise ValueError(
                f"{self.name}: expected a {self.cls.__module__}.{self.cls.__qualname__}, a dict "
                f"of its fields or None, got {value!r}"
            )
        unknown = sorted(set(value) - fields, key=str)
        if unknown:
            raise ValueError(f"{self.name}: unknown fields {unknown}; it takes {sorted(fields)}")
        out = self.defaults()
        for alias, field in self.aliases.items():
            if field in value:
                out[alias] = value[field]
            if alias in flat:
                if field in value and not _same(value[field], flat[alias]):
                    raise ValueError(
                        f"{alias}: given twice, {alias}={flat[alias]!r} and "
                        f"{self.name}.{field}={value[field]!r}; give one"
                    )
                out[alias] = flat[alias]
        return out


def _same(a: Any, b: Any) -> bool:
    """Whether two values of a field agree (an array against anything else: no)."""
    try:
        return bool(a is b or a == b)
    except (TypeError, ValueError):
        return False


def kwargs_of(local_vars: Mapping[str, Any], groups: tuple[Group, ...], owner: str) -> dict:
    """The flat kwargs of a constructor from its `locals()`: its own arguments (not self,
    render_mode, the groups, nor `aliases`, the **kwargs holding the aliases given) and every
    group's flat kwargs (`Group.flatten`); TypeError naming any keyword that is no alias, as
    Python's for `owner`'s call."""
    own = {k: v for k, v in local_vars.items() if k not in ("self", "render_mode", "__class__")}
    flat = own.pop("aliases")
    known = {alias for g in groups for alias in g.aliases}
    unknown = sorted(set(flat) - known)
    if unknown:
        raise TypeError(f"{owner}() got unexpected keyword arguments {unknown}")
    for g in groups:
        own.update(g.flatten(own.pop(g.name), flat))
    return own


def grouped_signature(init: Callable[..., Any], groups: tuple[Group, ...]) -> inspect.Signature:
    """`init`'s signature with its **kwargs replaced by each alias as a keyword-only parameter
    defaulting to its field's default."""
    params = [p for p in inspect.signature(init).parameters.values() if p.kind is not p.VAR_KEYWORD]
    for g in groups:
        for alias, default in g.defaults().items():
            params.append(inspect.Parameter(alias, inspect.Parameter.KEYWORD_ONLY, default=default))
    return inspect.Signature(params)


def list_aliases(cls: type, groups: tuple[Group, ...]) -> None:
    """Set `cls.__init__`'s `__signature__` to `grouped_signature` (what `inspect` reports)."""
    cls.__init__.__signature__ = grouped_signature(cls.__init__, groups)  # type: ignore[misc]
