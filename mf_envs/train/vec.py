"""Training vector envs: the env's native Gymnasium vector env when it has one, else SB3's.

`make_train_env` first tries `gym.make_vec(env_id, vectorization_mode="vector_entry_point")`.
A native vector env whose autoreset mode is SAME_STEP (or DISABLED, reset through
`reset_mask`) is wrapped in `GymVectorToSB3`, which speaks SB3's `VecEnv` API (auto-reset with
`info["terminal_observation"]` and `info["TimeLimit.truncated"]`). A NEXT_STEP native env cannot
be adapted without corrupting the advantage estimates at episode ends, so it falls back, as does
an env without a vector entry point, to `stable_baselines3.common.env_util.make_vec_env`
(a `DummyVecEnv` of `Monitor`-wrapped envs).

Domain randomisation (`train.randomize.DomainRandomization` as the only wrapper) runs inside the
native vector env when its rows hold every drawn kwarg (`train.randomize.randomized_vector_env`,
bit-identical to the wrapped single envs); otherwise, or with any other wrapper, the wrappers go
on the single envs of a `DummyVecEnv`.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import VecEnv, VecMonitor, VecNormalize

Wrapper = Callable[[gym.Env], gym.Env]


class GymVectorToSB3(VecEnv):
    """SB3 `VecEnv` view of a Gymnasium `VectorEnv` with SAME_STEP or DISABLED autoreset.

    Observations (n_envs, *obs_shape) and actions are passed through unchanged; infos, which
    Gymnasium batches as {key: array, "_key": mask}, are split into one dict per sub-env.
    """

    def __init__(self, venv: gym.vector.VectorEnv) -> None:
        mode = venv.metadata.get("autoreset_mode", AutoresetMode.NEXT_STEP)
        if mode not in (AutoresetMode.SAME_STEP, AutoresetMode.DISABLED):
            raise ValueError(
                f"venv: autoreset mode {mode} cannot be adapted; use SAME_STEP or DISABLED"
            )
        self.venv = venv
        self.autoreset_mode = mode
        super().__init__(venv.num_envs, venv.single_observation_space, venv.single_action_space)
        self._actions: np.ndarray | None = None

    def reset(self) -> np.ndarray:
        seeds = None if all(s is None for s in self._seeds) else [s for s in self._seeds]
        obs, infos = self.venv.reset(seed=seeds)
        self.reset_infos = split_infos(infos, self.num_envs)
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions)

    def step_wait(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[dict[str, Any]]]:
        obs, rew, term, trunc, infos = self.venv.step(self._actions)
        done = np.logical_or(term, trunc)
        if self.autoreset_mode == AutoresetMode.DISABLED and done.any():
            final_obs = obs.copy()
            step_infos = split_infos(infos, self.num_envs)
            obs, reset_infos = self.venv.reset(options={"reset_mask": done})
            for i, ri in enumerate(split_infos(reset_infos, self.num_envs)):
                if done[i]:
                    self.reset_infos[i] = ri
        else:  # SAME_STEP: obs already holds the reset observations
            final_obs = infos.get("final_obs")
            step_infos = split_infos(infos, self.num_envs)
            if done.any():
                finals = split_infos(infos.get("final_info", {}), self.num_envs)
                step_infos = [finals[i] if done[i] else step_infos[i] for i in range(len(done))]
        for i in np.flatnonzero(done):
            step_infos[i]["terminal_observation"] = final_obs[i]
            step_infos[i]["TimeLimit.truncated"] = bool(trunc[i] and not term[i])
        return obs, np.asarray(rew, dtype=np.float32), done, step_infos

    def close(self) -> None:
        self.venv.close()

    def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
        value = getattr(self.venv, attr_name)
        return [value for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
        setattr(self.venv, attr_name, value)

    def env_method(self, method_name: str, *args: Any, indices: Any = None, **kw: Any) -> list[Any]:
        value = getattr(self.venv, method_name)(*args, **kw)
        return [value for _ in self._get_indices(indices)]

    def env_is_wrapped(self, wrapper_class: type, indices: Any = None) -> list[bool]:
        return [False for _ in self._get_indices(indices)]

    def get_images(self) -> Sequence[np.ndarray | None]:
        frames = self.venv.render()
        return list(frames) if frames is not None else [None] * self.num_envs


def split_infos(infos: dict[str, Any], n: int) -> list[dict[str, Any]]:
    """Gymnasium's batched info dict -> one dict per sub-env (masks `_key` respected)."""
    out: list[dict[str, Any]] = [{} for _ in range(n)]
    for key, value in infos.items():
        if key.startswith("_") or key in ("final_obs", "final_info"):
            continue
        mask = infos.get(f"_{key}", np.ones(n, dtype=bool))
        if isinstance(value, dict):
            for i, sub in enumerate(split_infos(value, n)):
                if mask[i]:
                    out[i][key] = sub
            continue
        # 1-D arrays as Python scalars (one C call); rows of an n-D array stay arrays
        values = value.tolist() if isinstance(value, np.ndarray) and value.ndim == 1 else value
        if isinstance(mask, np.ndarray) and mask.all():
            for d, v in zip(out, values, strict=True):
                d[key] = v
            continue
        for i in np.flatnonzero(mask):
            out[i][key] = values[i]
    return out


def native_vector_env(
    env_id: str,
    n_envs: int,
    env_kwargs: dict[str, Any],
    randomize: dict[str, Any] | None = None,
) -> VecEnv | None:
    """The env's own vector env adapted to SB3, or None if it has none / it cannot be adapted;
    `randomize` ({"ranges": ..., "choices": ...}, each optional): with domain randomisation in
    its rows (`train.randomize.randomized_vector_env`), None if its rows cannot hold it."""
    from mf_envs.envs import native_vector_supported
    from mf_envs.train import randomize as rnd

    if gym.spec(env_id).vector_entry_point is None:
        return None
    if not native_vector_supported(env_id, env_kwargs):  # e.g. an inchworm without friction
        print(f"note: the native vector env of {env_id} does not run this scene; DummyVecEnv")
        return None
    if randomize is not None:
        names = rnd.Randomizer(env_id, env_kwargs, **randomize).names
        if not rnd.native_randomization_supported(env_id, names, env_kwargs):
            print(f"note: the rows of {env_id}'s native vector env cannot hold {sorted(names)}"
                  " apart; domain randomisation on DummyVecEnv")  # fmt: skip
            return None
        venv = rnd.randomized_vector_env(
            env_id, n_envs, env_kwargs, autoreset_mode=AutoresetMode.SAME_STEP, **randomize
        )
        return VecMonitor(GymVectorToSB3(venv))
    try:  # ask for SAME_STEP autoreset (SB3's semantics) if the vector env takes the option
        venv = gym.make_vec(
            env_id,
            num_envs=n_envs,
            vectorization_mode="vector_entry_point",
            autoreset_mode=AutoresetMode.SAME_STEP,
            **env_kwargs,
        )
    except TypeError:
        venv = gym.make_vec(
            env_id, num_envs=n_envs, vectorization_mode="vector_entry_point", **env_kwargs
        )
    try:
        return VecMonitor(GymVectorToSB3(venv))
    except ValueError as exc:
        venv.close()
        print(f"note: native vector env of {env_id} not used ({exc}); using DummyVecEnv")
        return None


def make_train_env(
    env_id: str,
    n_envs: int,
    seed: int,
    env_kwargs: dict[str, Any] | None = None,
    wrappers: Sequence[Wrapper] = (),
    normalize: dict[str, Any] | None = None,
    prefer_native: bool = True,
) -> tuple[VecEnv, str]:
    """A seeded SB3 VecEnv for training (VecNormalize on top if `normalize` is a dict).

    Returns the env and a label of the vectorisation used ("native" or "dummy").
    """
    env_kwargs = dict(env_kwargs or {})
    venv, randomize = None, randomization_only(wrappers)
    if prefer_native and (not wrappers or randomize is not None):
        venv = native_vector_env(env_id, n_envs, env_kwargs, randomize)
    kind = "native"
    if venv is None:
        kind = "dummy"
        # wrappers go on the bare gym.make env, below SB3's Monitor (so DomainRandomization
        # may re-make the env it wraps without losing the episode statistics)
        make = functools.partial(_make_wrapped, env_id, tuple(wrappers)) if wrappers else env_id
        venv = make_vec_env(make, n_envs=n_envs, seed=seed, env_kwargs=env_kwargs)
    else:
        venv.seed(seed)
    venv.action_space.seed(seed)
    if normalize is not None:
        venv = VecNormalize(venv, **normalize)
    return venv, kind


def randomization_only(wrappers: Sequence[Wrapper]) -> dict[str, Any] | None:
    """{"ranges": ..., "choices": ...} (the kwargs given) if `wrappers` is exactly one
    `DomainRandomization` (the class, or a `functools.partial` of it with keyword arguments
    only), else None."""
    from mf_envs.train.randomize import DomainRandomization

    if len(wrappers) != 1:
        return None
    (w,) = wrappers
    if w is DomainRandomization:
        return {}
    if isinstance(w, functools.partial) and w.func is DomainRandomization and not w.args:
        if set(w.keywords) <= {"ranges", "choices"}:
            return dict(w.keywords)
    return None


def _make_wrapped(env_id: str, wrappers: tuple[Wrapper, ...], **kwargs: Any) -> gym.Env:
    """`gym.make(env_id, **kwargs)` in `wrappers`; a wrapper refusing its config kwargs (a
    TypeError or assertion in its constructor) is a ValueError naming env_wrapper and it."""
    env = gym.make(env_id, **kwargs)
    for w in wrappers:
        try:
            env = w(env)
        except (TypeError, AssertionError) as exc:
            name = getattr(getattr(w, "func", w), "__name__", repr(w))
            raise ValueError(f"env_wrapper: {name}: {' '.join(str(exc).split())}") from None
    return env
