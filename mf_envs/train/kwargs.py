"""`policy_kwargs` by a whitelist: the zoo's `"dict(net_arch=[64, 64], activation_fn=nn.Tanh)"`
string, a YAML mapping, or a policy's `policy.json`, parsed without `eval` (docs/design.md,
"nothing loaded from a file executes code").

Allowed: the keys in `POLICY_KEYS`; numbers, booleans, lists/tuples and dicts of those (for
`net_arch`); activation functions by name (`nn.Tanh`, `th.nn.Tanh`, `"Tanh"`) from
`ACTIVATIONS`. Anything else is a `ValueError` naming the offending key or expression.
Hand-written because `ast.literal_eval` does not accept `dict(...)` calls or `nn.Tanh` names.
"""

from __future__ import annotations

import ast
from typing import Any

ACTIVATIONS = (
    "Tanh",
    "ReLU",
    "ELU",
    "LeakyReLU",
    "GELU",
    "SiLU",
    "Sigmoid",
    "Softplus",
    "Identity",
)
POLICY_KEYS = (
    "net_arch",
    "activation_fn",
    "log_std_init",
    "ortho_init",
    "squash_output",
    "full_std",
    "use_expln",
    "share_features_extractor",
    "n_critics",  # SAC, TD3
    "clip_mean",  # SAC
)


def parse_policy_kwargs(text: str | dict[str, Any]) -> dict[str, Any]:
    """policy_kwargs (string or mapping) -> validated dict with `activation_fn` as a NAME.

    Use `resolve_activation` to turn the name into the `torch.nn` class.
    """
    if isinstance(text, str):
        try:
            tree = ast.parse(text, mode="eval").body
        except SyntaxError as exc:
            raise ValueError(f"policy_kwargs: not a dict expression: {text!r}") from exc
        value = _node(tree, "policy_kwargs")
    else:
        value = text
    if not isinstance(value, dict):
        raise ValueError(f"policy_kwargs: must be a dict, got {value!r}")
    return {key: _check_key(key, v) for key, v in value.items()}


def resolve_activation(kwargs: dict[str, Any]) -> dict[str, Any]:
    """A copy of validated kwargs with `activation_fn` the `torch.nn` class of its name."""
    out = dict(kwargs)
    if "activation_fn" in out:
        from torch import nn

        out["activation_fn"] = getattr(nn, out["activation_fn"])
    return out


def activation_name(fn: Any) -> str:
    """`torch.nn.Tanh` (class) or "Tanh" -> "Tanh"; ValueError outside `ACTIVATIONS`."""
    name = fn if isinstance(fn, str) else getattr(fn, "__name__", repr(fn))
    if name not in ACTIVATIONS:
        raise ValueError(f"activation_fn: {name!r} is not one of {ACTIVATIONS}")
    return name


def _check_key(key: Any, value: Any) -> Any:
    if key not in POLICY_KEYS:
        raise ValueError(f"policy_kwargs: unknown key {key!r}; allowed: {', '.join(POLICY_KEYS)}")
    if key == "activation_fn":
        name = value if isinstance(value, str) else getattr(value, "__name__", repr(value))
        return activation_name(name.rpartition(".")[2])
    if key == "net_arch":
        return _check_arch(value)
    if isinstance(value, bool) or (
        isinstance(value, int | float) and key in ("log_std_init", "clip_mean")
    ):
        return value
    if key == "n_critics" and isinstance(value, int) and not isinstance(value, bool) and value > 0:
        return value
    return _bad(key, value)


def _check_arch(value: Any) -> Any:
    if isinstance(value, list | tuple):
        if all(isinstance(n, int) and not isinstance(n, bool) and n > 0 for n in value):
            return [int(n) for n in value]
    if isinstance(value, dict) and set(value) <= {"pi", "vf", "qf"}:  # qf: SAC/TD3 critics
        return {k: _check_arch(v) for k, v in value.items()}
    return _bad("net_arch", value)


def _bad(key: str, value: Any) -> Any:
    raise ValueError(f"policy_kwargs: {key}={value!r} is not allowed")


def _node(node: ast.AST, where: str) -> Any:
    """The value of a whitelisted expression node (no names are looked up, nothing is called)."""
    if isinstance(node, ast.Constant) and isinstance(node.value, int | float | bool | str):
        return node.value
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        v = _node(node.operand, where)
        if isinstance(v, int | float) and not isinstance(v, bool):
            return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.List | ast.Tuple):
        return [_node(e, where) for e in node.elts]
    if isinstance(node, ast.Dict) and all(isinstance(k, ast.Constant) for k in node.keys):
        return {k.value: _node(v, f"{where}.{k.value}") for k, v in zip(node.keys, node.values)}  # type: ignore[union-attr]
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id == "dict"
        and not node.args
        and all(k.arg is not None for k in node.keywords)
    ):
        return {k.arg: _node(k.value, f"{where}.{k.arg}") for k in node.keywords}
    if isinstance(node, ast.Attribute) and ast.unparse(node) in _ACT_EXPR:
        return node.attr
    raise ValueError(
        f"{where}: {ast.unparse(node)!r} is not allowed (numbers, lists, dicts, nn.NAME)"
    )


_ACT_EXPR = {f"{p}{a}" for a in ACTIVATIONS for p in ("nn.", "th.nn.", "torch.nn.")}
