"""The construction, reset, control step, step info, centreline and frame shared by the planar
beam robots on a distributed load (`Serpentine-v0` on the ground, `Eel-v0` in water). Each env
provides its modules (`robot_build`, `robot_rows`, `robot_spec`), its compiled row step
(`_advance`), its heading (`_heading`) and its drawing (`_draw`); the rows report into `rep`
by the slots below (`envs.serpentine.rows`, `envs.eel.rows`)."""

from __future__ import annotations

import math
from abc import ABCMeta, abstractmethod
from types import ModuleType
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_range
from mf_envs.envs._beam_rows import (
    N_REPORT,
    REP_ENERGY,
    REP_ITER,
    REP_NET,
    REP_OK,
    REP_X0,
    REP_Y0,
)
from mf_envs.envs._spec import check_curvature_option
from mf_envs.envs.serpentine import spec
from mf_envs.envs.serpentine.build import initial_dofs
from mf_envs.physics.beam.solver import BeamModel

MAX_HEADING = 4 * math.pi  # rad, |heading| of a reset option


_START_AND_END = """## Starting State
    At rest, curvature kappa0 = max_curvature x U(-reset_noise_scale, reset_noise_scale) at the
    control points (linear between) and commanded alike (an equilibrium), mean frame angle
    U(-initial_heading_range, initial_heading_range), centre of mass at the origin.
    `reset(options={"heading": rad (|.| <= 4 pi), "kappa": (n,) 1/m within +-max_curvature})`
    overrides; any other key or value raises ValueError naming it (and draws nothing).

    ## Episode End
    Truncation after `episode_seconds` or `max_episode_steps` (default DEFAULT;
    docs/api.md, "Episode length"). Termination on numerical failure (Newton fails even
    after 2^6 step halvings, or a non-finite state): info["numerical_failure"] = True.
"""


def beam_doc(doc: str | None) -> str:
    """A beam robot's class docstring with its `BEAM_START_AND_END(<default episode>)` line
    replaced by the Starting State and Episode End sections they share."""
    head, sep, rest = (doc or "").partition("BEAM_START_AND_END(")
    if not sep:
        return doc or ""
    default, _, tail = rest.partition(")\n")
    return head + _START_AND_END.replace("DEFAULT", default) + tail


def step_terms(body, rep, target_direction, length, effort_weight) -> tuple[Any, dict]:
    """The centre of mass's advance along the target direction in a step [m] and the reward
    terms (`progress` = advance / L, `effort` = -effort_weight x the actuation energy [J]) of
    one row (body (5,), rep (N_REPORT,)) or of a batch (body (N, 5), rep (N, N_REPORT)): the
    single env's and the vector env's one definition."""
    c, s = math.cos(target_direction), math.sin(target_direction)
    along = c * (body[..., 0] - rep[..., REP_X0]) + s * (body[..., 1] - rep[..., REP_Y0])
    energy = rep[..., REP_ENERGY]
    return along, {"progress": along / length, "effort": -effort_weight * energy}


class BeamRobotMixin(metaclass=ABCMeta):
    """`step`, reset, `_info`, `centerline` and `_draw_frame` of a beam robot (put before
    `MFEnv`); an env that lacks one of the three hooks below cannot be instantiated
    (TypeError). `robot_build`, `robot_rows`, `robot_spec`: the env's own `build`, `rows` and
    `spec` modules."""

    robot_build: ModuleType
    robot_rows: ModuleType
    robot_spec: ModuleType

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.__doc__ = beam_doc(cls.__doc__)  # the shared Starting State and Episode End

    def _make_robot(self, kw: dict[str, Any], episode_default: float) -> None:
        """The start of the constructor (after `MFEnv.__init__`): the scene from the kwargs
        `kw` (`build.build`), the episode length (`episode_default` s unless given) and the
        beam model."""
        self._set_scene(self.robot_build.build(kw, self.effects))
        steps, _ = self._seconds_episode(
            kw["episode_seconds"], kw["max_episode_steps"], episode_default
        )
        self.max_steps, self.episode_seconds = steps, steps * self.control_dt
        self.model = BeamModel(self.scene.params)

    def _make_state(self, n_actions: int) -> None:
        """The spaces (`n_actions` actions in [-1, 1]), the state (d, v) of the straight beam,
        the command and the row buffers."""
        n, nd = self.n_ctrl, self.model.n_dof
        self.action_space = spaces.Box(-1.0, 1.0, (n_actions,), np.float32)
        self.obs_layout = self.robot_spec.observation_layout(n)
        hi = self.obs_layout.high()
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self.state = np.zeros((2, nd))  # (d, v): beam dofs [m, rad] and their rates
        self.state[0] = self.model.straight()
        self.cmd = np.zeros(n)  # commanded kappa# at the control points [1/m]
        self._body, self._rep = np.zeros(5), np.zeros(N_REPORT)
        self._obs = np.zeros(self.obs_layout.size, np.float32)
        self._steps = 0
        self._track: list[tuple[float, float]] = []

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        heading = None
        if "heading" in opts:
            heading = check_range("heading", opts["heading"], -MAX_HEADING, MAX_HEADING)
        kappa = None
        if "kappa" in opts:
            kappa = check_curvature_option(opts["kappa"], self.n_ctrl, self.max_curvature)
        return {"heading": heading, "kappa": kappa}

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        heading, kappa = opts["heading"], opts["kappa"]
        rng, sc = self.np_random, self.scene
        drawn_heading = rng.uniform(-sc.initial_heading_range, sc.initial_heading_range)
        noise = rng.uniform(-1.0, 1.0, self.n_ctrl) * sc.reset_noise_scale * self.max_curvature
        heading = drawn_heading if heading is None else heading
        kappa = noise if kappa is None else kappa
        self.state[0] = initial_dofs(sc.params, kappa, heading)
        self.state[1] = 0.0
        self.cmd[:] = kappa
        self.robot_rows.observe_row(
            self.state[0], self.state[1], self.cmd, self.cfg, self._body, self._obs
        )
        self._track = [(self._body[0], self._body[1])]
        info = self._info(0.0, 0.0, 0, {"progress": 0.0, "effort": 0.0})
        return self._obs.copy(), info

    @abstractmethod
    def _advance(self, action: np.ndarray, rep: np.ndarray) -> None:
        """One control step of the robot's compiled row with the validated action, reporting
        into rep by the REP_* slots."""

    @abstractmethod
    def _heading(self) -> float:
        """The body's heading (rad)."""

    @abstractmethod
    def _draw(self, line: np.ndarray, text: str) -> np.ndarray:
        """The rgb frame of the centreline `line` (N, 2) with the caption `text`."""

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a = self._validate_action(action)
        rep = self._rep
        self._advance(a, rep)
        self._steps += 1
        ok = rep[REP_OK] > 0.0 and bool(np.isfinite(self.state).all())
        along, terms = step_terms(self._body, rep, self.target_direction, self.scene.length,
                                  self.effort_weight)  # fmt: skip
        along, terms = float(along), {k: float(v) for k, v in terms.items()}
        energy = float(rep[REP_ENERGY])
        info = self._info(along / self.control_dt, energy, int(rep[REP_ITER]), terms)
        info["actuation_net_work"] = float(rep[REP_NET])
        if ok:
            self._track.append((self._body[0], self._body[1]))
        reward = terms["progress"] + terms["effort"]
        trunc = self._steps >= self.max_steps
        return self._finish_step(self._obs.copy(), reward, False, trunc, info, ok)

    def _info(self, speed: float, energy: float, its: int, terms: dict) -> dict[str, Any]:
        return spec.step_info(
            float(self._body[0]), float(self._body[1]), self._heading(), float(speed),
            self.cmd.copy(), energy, 0.0, self.control_dt, its,
            self._steps * self.control_dt, terms,
        )  # fmt: skip

    def centerline(self, per_element: int = 8) -> np.ndarray:
        """(N, 2) points of the body's centreline [m], tail to head."""
        return self.model.centerline(self.state[0], per_element)

    def _draw_frame(self) -> np.ndarray:
        line = self.centerline()
        if not np.isfinite(line).all():  # after a numerical failure: the last finite track
            line = np.array([self._track[-1], self._track[-1]]) + [[0.0, 0.0], [1e-9, 0.0]]
        x, y = self._track[-1] if self._track else (0.0, 0.0)
        text = f"t = {self._steps * self.control_dt:.2f} s  com ({x:+.3f}, {y:+.3f}) m"
        return self._draw(line, text)
