"""A small shared base for the mf_envs environments.

Owns what every env does the same way: action validation and scaling from [-1, 1], the control
step as an integer number of physics substeps, effect resolution, and the numerical-failure
contract (a state that goes non-finite ends the episode with info["numerical_failure"] = True;
the observation returned is the last finite one, the reward 0). Physics lives in
`mf_envs.physics`; subclasses only wire it to spaces, rewards and rendering.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Mapping
from typing import Any

import gymnasium as gym
import numpy as np

from mf_envs._validate import as_action, check_int, check_range
from mf_envs.effects import resolve_effects
from mf_envs.envs._spec import check_options

MIN_DT = 1e-6  # s, smallest control or physics step
MAX_CONTROL_DT = 60.0  # s, largest control step
MAX_SUBSTEPS = 10_000  # physics substeps per control step (a step must stay fast)
MAX_EPISODE_STEPS = 10_000_000  # control steps per episode
# what step() returns: observation, reward, terminated, truncated, info
StepResult = tuple[np.ndarray, float, bool, bool, dict[str, Any]]


def episode_steps_arg(value: Any) -> int | None:
    """`max_episode_steps` as given to an env or a native vector env: None (not given), else an
    integer in [1, MAX_EPISODE_STEPS]; ValueError naming it otherwise (a float, even 100.0, or a
    bool is refused)."""
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"max_episode_steps: expected an integer, got {value!r}")
    return check_int("max_episode_steps", value, 1, MAX_EPISODE_STEPS)


def _field_names(scene: Any) -> frozenset[str]:
    return frozenset(f.name for f in dataclasses.fields(scene))


class MFEnv(gym.Env):
    """Base class: subclasses set `action_space`/`observation_space` and call the helpers."""

    metadata: dict[str, Any] = {"render_modes": ["rgb_array", "human"], "render_fps": 30}
    AVAILABLE_EFFECTS: Mapping[str, str] = {}  # a subclass's effects: name -> meaning
    DEFAULT_EFFECTS: tuple[str, ...] = ()

    def __init__(
        self,
        *,
        effects: str | Iterable[str] | None,
        control_dt: float,
        physics_dt: float,
        render_mode: str | None = None,
        available_effects: Mapping[str, str] | None = None,
        default_effects: Iterable[str] | None = None,
    ) -> None:
        """`available_effects`, `default_effects`: the class's `AVAILABLE_EFFECTS` and
        `DEFAULT_EFFECTS` unless given."""
        if available_effects is None:
            available_effects = type(self).AVAILABLE_EFFECTS
        if default_effects is None:
            default_effects = type(self).DEFAULT_EFFECTS
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode: must be one of {self.metadata['render_modes']} or None, "
                f"got {render_mode!r}"
            )
        self.render_mode = render_mode
        self.effects = resolve_effects(effects, available_effects, default_effects)
        self.available_effects = tuple(sorted(available_effects))  # every effect it can switch
        control_dt = check_range("control_dt", control_dt, MIN_DT, MAX_CONTROL_DT)
        physics_dt = check_range("physics_dt", physics_dt, MIN_DT, None)
        # integer substeps; physics_dt is shrunk so that n * physics_dt == control_dt exactly
        n_substeps = max(1, math.ceil(control_dt / physics_dt - 1e-9))
        if n_substeps > MAX_SUBSTEPS:
            raise ValueError(
                f"physics_dt: control_dt / physics_dt = {n_substeps} substeps per step exceeds "
                f"{MAX_SUBSTEPS}; raise physics_dt (>= {control_dt / MAX_SUBSTEPS:.3g} s) or "
                "lower control_dt"
            )
        self.n_substeps = n_substeps
        self.control_dt = control_dt
        self.physics_dt = self.control_dt / self.n_substeps
        self._last_obs: np.ndarray | None = None
        self._window: Any = None  # mf_envs.render.HumanWindow, opened by the first human render

    def _episode_steps(self, episode_seconds: Any) -> int:
        """Control steps in `episode_seconds` (s): ceil(episode_seconds / control_dt), >= 1."""
        seconds = check_range("episode_seconds", episode_seconds, MIN_DT, None)
        ratio = seconds / self.control_dt  # may overflow to inf (1e308 s): refused below
        if not ratio <= MAX_EPISODE_STEPS:
            raise ValueError(
                f"episode_seconds: {seconds:g} s is {ratio:.3g} control steps, more than "
                f"{MAX_EPISODE_STEPS}; shorten the episode or raise control_dt"
            )
        return max(1, math.ceil(ratio - 1e-9))

    def _episode_length(
        self, max_episode_steps: Any, own: tuple[str, Any, int] | None, default: int
    ) -> int:
        """Control steps per episode, the env's own (it truncates itself; no TimeLimit is
        registered): `max_episode_steps` given (`episode_steps_arg`) sets it; `own` = (argument,
        value, its steps) is the env's own length argument given (`episode_seconds`,
        `n_periods`), which must then give the same steps (ValueError naming both); else
        `default`, the default episode at these kwargs."""
        steps = episode_steps_arg(max_episode_steps)
        if own is None:
            return default if steps is None else steps
        name, value, n = own
        if steps is not None and n != steps:
            raise ValueError(
                f"max_episode_steps: {name}={value!r} is {n} control steps but "
                f"max_episode_steps={steps}; give one of them, or both agreeing"
            )
        return n

    def _own_seconds(self, episode_seconds: Any) -> tuple[str, Any, int] | None:
        """`_episode_length`'s `own` for an `episode_seconds` given (None: not given)."""
        if episode_seconds is None:
            return None
        return ("episode_seconds", episode_seconds, self._episode_steps(episode_seconds))

    def _seconds_episode(
        self, episode_seconds: Any, max_episode_steps: Any, default_seconds: float
    ) -> tuple[int, float]:
        """(control steps, seconds) of an episode given in seconds (`episode_seconds`; None:
        `default_seconds`) or in steps (`max_episode_steps`), by `_episode_length`; the seconds
        are those given, the default's, or steps x control_dt."""
        own = self._own_seconds(episode_seconds)
        default = self._episode_steps(default_seconds)
        steps = self._episode_length(max_episode_steps, own, default)
        if own is not None:
            return steps, float(episode_seconds)
        return steps, float(default_seconds) if steps == default else steps * self.control_dt

    def _set_scene(self, scene: Any) -> None:
        """Keep the env's physical parameters, its `build.Scene` (a frozen dataclass), as
        `self.scene`; its fields read as the env's attributes (`env.wave_period`), set once here
        from the frozen scene. (No `__getattr__` forwarding: a class with one loses CPython's
        specialised attribute reads, ~15 % of a fast env's step.)"""
        self.scene = scene
        for name in _field_names(scene):
            self.__dict__[name] = getattr(scene, name)

    @property
    def max_episode_steps(self) -> int:
        """Control steps per episode, `max_steps`: the constructor's `max_episode_steps`, else
        ceil(episode_seconds / control_dt) (`_episode_steps`; GOWEC-v0: n_periods x
        steps_per_period), else the default episode's (`_episode_length`)."""
        return self.max_steps

    @property
    def dt(self) -> float:
        """Control interval in seconds (one `step`)."""
        return self.control_dt

    # ------------------------------------------------------------------ rendering
    def render(self) -> np.ndarray | None:
        """rgb_array: the frame (H, W, 3) uint8 from the subclass's `_draw_frame()`; human: show
        it in one window (opened on first use; `close()` closes it); None without render_mode."""
        if self.render_mode is None:
            return None
        frame = self._draw_frame()
        if self.render_mode == "human":
            from mf_envs.render import HumanWindow

            if self._window is None:
                name = self.spec.id if self.spec is not None else type(self).__name__
                self._window = HumanWindow(name)
            self._window.show(frame)
            return None
        return frame

    def _draw_frame(self) -> np.ndarray:
        """The current frame, uint8 (H, W, 3); each env draws its system with mf_envs.render."""
        raise TypeError(f"{type(self).__name__} does not define _draw_frame()")

    def close(self) -> None:
        if self._window is not None:
            self._window.close()
            self._window = None

    # ------------------------------------------------------------------ actions
    def _validate_action(self, action: Any) -> np.ndarray:
        """float64 copy of `action` clipped to [-1, 1]; NaN/inf, strings, bools and a wrong size
        raise ValueError naming `action` (documented)."""
        return np.clip(as_action("action", action, self.action_space.shape), -1.0, 1.0)

    def _scalar_action(self, action: Any) -> float:
        """The one action of a Box(-1, 1, (1,)) env as a float in [-1, 1]: the contract of
        `_validate_action` without its array overhead (the per-step hot path)."""
        if isinstance(action, np.ndarray) and action.shape == (1,) and action.dtype.kind == "f":
            u = float(action[0])
            if not math.isfinite(u):
                raise ValueError(f"action: must be finite, got {action!r}")
            return -1.0 if u < -1.0 else (1.0 if u > 1.0 else u)
        return float(self._validate_action(action)[0])

    # ------------------------------------------------------------------ reset
    RESET_OPTIONS: tuple[str, ...] = ()  # the keys reset(options=...) takes

    def reset(
        self, *, seed: int | None = None, options: Mapping[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Every env's reset: the options checked (unknown keys, then each value by the
        subclass's `_check_reset_options`) before any draw, so a refused reset leaves the
        generator untouched; then seeding, the step counter at 0, the subclass's `_start(opts)`
        (the start drawn from `self.np_random`; returns (observation, info)), and the
        observation clipped to its bounds (`_finish_reset`)."""
        opts = self._check_reset_options(check_options(options, self.RESET_OPTIONS))
        super().reset(seed=seed)
        self._steps = 0
        obs, info = self._start(opts)
        return self._finish_reset(obs), info

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        """The reset options' values, validated (ValueError naming the key); no draws."""
        return opts

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        """Draw and set the start state (from `self.np_random`, honouring `opts`); return the
        observation and the reset info."""
        raise TypeError(f"{type(self).__name__} does not define _start()")

    # ------------------------------------------------------------------ numerics
    def _step_ok(self, obs: np.ndarray, reward: float, terminated: bool, truncated: bool,
                 info: dict[str, Any]) -> StepResult:  # fmt: skip
        """The end of a healthy step whose observation the env's kernel already checked finite
        and clipped to the bounds: `_finish_step`'s contract without repeating its checks."""
        info["numerical_failure"] = False
        self._last_obs = obs
        return obs, reward, terminated, truncated, info

    def _finish_step(self, obs: np.ndarray, reward: float, terminated: bool, truncated: bool,
                     info: dict[str, Any], state_ok: bool) -> StepResult:  # fmt: skip
        """Apply the numerical-failure contract and remember the last finite observation."""
        obs = np.asarray(obs, dtype=np.float32)
        ok = bool(state_ok) and bool(np.all(np.isfinite(obs))) and bool(np.isfinite(reward))
        info["numerical_failure"] = not ok
        if not ok:
            obs = (
                self._last_obs.copy()
                if self._last_obs is not None
                else np.zeros(self.observation_space.shape, dtype=np.float32)
            )
            return obs, 0.0, True, truncated, info
        obs = np.clip(obs, self.observation_space.low, self.observation_space.high)
        self._last_obs = obs
        return obs, float(reward), bool(terminated), bool(truncated), info

    def _finish_reset(self, obs: np.ndarray) -> np.ndarray:
        obs = np.asarray(obs, dtype=np.float32)
        obs = np.clip(obs, self.observation_space.low, self.observation_space.high)
        self._last_obs = obs
        return obs
