"""`policy_kwargs` by a whitelist: the zoo's `"dict(net_arch=[64, 64], activation_fn=nn.Tanh)"`
string, a YAML mapping, or a policy's `policy.json`, parsed without `eval` (docs/design.md,
"nothing loaded from a file executes code").

Allowed: the keys in `POLICY_KEYS`; numbers, booleans, lists/tuples and dicts of those (for
`net_arch`: at most `MAX_LAYERS` layers of at most `MAX_UNITS` units, checked before any
network is allocated); activation functions by name (`nn.Tanh`, `th.nn.Tanh`, `"Tanh"`) from
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
MAX_LAYERS = 16  # hidden layers of one net_arch list
MAX_UNITS = 4096  # units of one hidden layer (the shipped configs use 64 to 400)
MAX_WEIGHTS = 16_000_000  # weights of one policy's networks (64 MB of float32)
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
        arch = _check_arch(value)
        check_arch_size(arch)
        return arch
    if isinstance(value, bool) or (
        isinstance(value, int | float) and key in ("log_std_init", "clip_mean")
    ):
        return value
    if key == "n_critics" and isinstance(value, int) and not isinstance(value, bool) and value > 0:
        return value
    return _bad(key, value)


def arch_weights(arch: Any, n_in: int = 1, n_out: int = 1) -> int:
    """Weights (matrix entries) of the MLPs a checked `net_arch` describes between `n_in`
    inputs and `n_out` outputs: a list counts once per network (actor, critic), a dict once per
    list."""
    lists = list(arch.values()) if isinstance(arch, dict) else [arch, arch]
    total = 0
    for units in lists:
        sizes = [n_in, *units, n_out]
        total += sum(a * b for a, b in zip(sizes, sizes[1:]))
    return total


def check_arch_size(arch: Any, n_in: int = 1, n_out: int = 1, where: str = "policy_kwargs") -> None:
    """ValueError naming `where` if `arch_weights` exceeds MAX_WEIGHTS (before allocating)."""
    n = arch_weights(arch, n_in, n_out)
    if n > MAX_WEIGHTS:
        raise ValueError(f"{where}: net_arch needs {n} weights, more than {MAX_WEIGHTS}")


def _check_arch(value: Any) -> Any:
    if isinstance(value, list | tuple) and len(value) <= MAX_LAYERS:
        if all(isinstance(n, int) and not isinstance(n, bool) and n > 0 for n in value):
            if all(n <= MAX_UNITS for n in value):
                return [int(n) for n in value]
            raise ValueError(
                f"policy_kwargs: net_arch={value!r}: a layer has more than {MAX_UNITS} units"
            )
    if isinstance(value, dict) and set(value) <= {"pi", "vf", "qf"}:  # qf: SAC/TD3 critics
        return {k: _check_arch(v) for k, v in value.items()}
    if isinstance(value, list | tuple) and len(value) > MAX_LAYERS:
        raise ValueError(f"policy_kwargs: net_arch has more than {MAX_LAYERS} layers")
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
