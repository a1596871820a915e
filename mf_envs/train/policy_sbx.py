"""SBX's SAC (the JAX SB3, `sbx` extra) in the project's policy format.

Its parameters are flax pytrees: the actor's, the critics' and the target critics'. They are
stored in `policy.safetensors` as flat arrays named `<part>/<path>` (part: `actor`, `qf`,
`qf_target`; path: the pytree keys joined by "/", e.g. `actor/params/Dense_0/kernel`), and put
back into an SBX `SACPolicy` built from `policy.json` (net_arch, n_critics, ...), so loading
runs no code from the file. The policy's activation is SBX's default (ReLU): the format names
torch activations only, so an SBX policy with another is refused when saved.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

PARTS = ("actor", "qf", "qf_target")


def is_sbx(model: Any) -> bool:
    """Whether `model` (an algorithm) is one of SBX's."""
    return type(model).__module__.split(".")[0] == "sbx"


def _trees(policy: Any) -> dict[str, Any]:
    return {
        "actor": policy.actor_state.params,
        "qf": policy.qf_state.params,
        "qf_target": policy.qf_state.target_params,
    }


def sbx_state(policy: Any) -> dict[str, np.ndarray]:
    """The SBX SAC policy's parameters as {"<part>/<path>": array}."""
    from flax.traverse_util import flatten_dict

    return {
        f"{part}/{'/'.join(map(str, key))}": np.ascontiguousarray(np.asarray(value))
        for part, tree in _trees(policy).items()
        for key, value in flatten_dict(tree).items()
    }


def sbx_policy_kwargs(model: Any) -> dict[str, Any]:
    """The policy kwargs an SBX SAC model was built with, for policy.json; ValueError for an
    activation other than the default (the format cannot name a JAX function)."""
    pk = dict(model.policy_kwargs or {})
    if "activation_fn" in pk:
        raise ValueError(
            "policy_kwargs: activation_fn of an SBX policy is not saved; use the default"
        )
    return pk


def rebuild_sbx(obs_space: Any, act_space: Any, kwargs: dict[str, Any], weights: Path) -> Any:
    """The SBX `SACPolicy` of `kwargs` on these spaces holding the arrays of `weights` (a
    safetensors file); ValueError naming the file if it is not one or does not fit."""
    from safetensors.numpy import load_file
    from sbx.sac.policies import SACPolicy

    try:
        state = load_file(weights)
    except Exception as exc:  # noqa: BLE001 - safetensors raises its own SafetensorError
        raise ValueError(f"policy: {weights} is not a safetensors file ({exc})") from exc
    for key, a in state.items():
        if np.issubdtype(a.dtype, np.floating) and not np.isfinite(a).all():
            raise ValueError(f"policy: {weights}: tensor {key!r} holds NaN or inf values")
    import jax

    pol = SACPolicy(obs_space, act_space, lambda _: 0.0, **kwargs)
    pol.build(jax.random.PRNGKey(0), lambda _: 0.0, 0.0)
    put_sbx_state(pol, state, str(weights))
    return pol


def put_sbx_state(policy: Any, state: dict[str, np.ndarray], where: str) -> None:
    """Set the SBX SAC `policy`'s parameters from `sbx_state`'s dict: every array present with
    its shape, none extra (ValueError naming `where` otherwise)."""
    import jax.numpy as jnp
    from flax.traverse_util import flatten_dict, unflatten_dict

    new, seen = {}, set()
    for part, tree in _trees(policy).items():
        flat = {}
        for key, ref in flatten_dict(tree).items():
            name = f"{part}/{'/'.join(map(str, key))}"
            if name not in state or state[name].shape != np.shape(ref):
                raise ValueError(f"policy: weights in {where} do not fit (tensor {name!r})")
            flat[key] = jnp.asarray(state[name], dtype=ref.dtype)
            seen.add(name)
        new[part] = unflatten_dict(flat)
    extra = sorted(set(state) - seen)
    if extra:
        raise ValueError(f"policy: weights in {where} do not fit (unexpected {extra[0]!r})")
    policy.actor_state = policy.actor_state.replace(params=new["actor"])
    policy.qf_state = policy.qf_state.replace(params=new["qf"], target_params=new["qf_target"])
