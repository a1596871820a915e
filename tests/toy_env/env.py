"""ToyOscillator-v0: a mass on a spring and a damper, pushed by a bounded force."""

from __future__ import annotations

import numpy as np
from gymnasium import spaces
from scipy.linalg import expm

from mf_envs._validate import check_range, positive_scalar
from mf_envs.envs._spec import Field, ObsLayout
from mf_envs.envs.base import MFEnv

OBS = ObsLayout(
    Field("position", "m", 10.0, "position x of the mass"),
    Field("velocity", "m/s", 100.0, "velocity x'"),
)
AVAILABLE_EFFECTS = {"damping": "viscous damper c x' (off: c = 0)"}
DEFAULT_EFFECTS = ("damping",)
MAX_START = 1.0  # m, |x| and |x'| a reset option may set


class ToyOscillatorEnv(MFEnv):
    """
    ## Description
    A mass m on a spring k and a damper c, m x'' + c x' + k x = F, with the force F held over
    each control step (zero-order hold) and integrated exactly by the matrix exponential.

    ## Action Space
    `Box(-1, 1, (1,), float32)`: force F / max_force.

    ## Observation Space
    `Box(float32, (2,))`, laid out by `OBS`:

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0 | position | position x of the mass | +-10 | m |
    | 1 | velocity | velocity x' | +-100 | m/s |

    ## Rewards
    `position`: -(x / 0.1 m)^2 dt; `effort`: -0.01 (F / max_force)^2 dt.

    ## Starting State
    x and x' uniform in +-0.1 (m, m/s); options `position`, `velocity` set them (|.| <= 1).

    ## Episode End
    Truncated after `episode_seconds` (default 5 s: the spec's max_episode_steps, 100) or
    `max_episode_steps`; terminated on a numerical failure.

    ## Arguments
    mass (kg), stiffness (N/m), damping (N s/m), max_force (N), control_dt (s),
    episode_seconds (s), max_episode_steps, effects, render_mode.

    ## Version History
    v0: the example of docs/adding_an_env.md.
    """

    RESET_OPTIONS = ("position", "velocity")

    def __init__(self, mass=1.0, stiffness=40.0, damping=2.0, max_force=5.0, control_dt=0.05,
                 episode_seconds=None, max_episode_steps=None, effects=None,
                 render_mode=None):  # fmt: skip
        super().__init__(effects=effects, available_effects=AVAILABLE_EFFECTS,
                         default_effects=DEFAULT_EFFECTS, control_dt=control_dt,
                         physics_dt=control_dt, render_mode=render_mode)  # fmt: skip
        self.mass = positive_scalar("mass", mass)
        self.stiffness = positive_scalar("stiffness", stiffness)
        self.damping = check_range("damping", damping, 0.0, None)
        self.max_force = positive_scalar("max_force", max_force)
        # the length and gym.make's TimeLimit agree, or ValueError (MFEnv._episode_length)
        self.max_steps, self.episode_seconds = self._seconds_episode(
            episode_seconds, max_episode_steps, 5.0
        )
        c = self.damping if "damping" in self.effects else 0.0
        a = np.array([[0.0, 1.0], [-self.stiffness / self.mass, -c / self.mass]])
        big = np.zeros((3, 3))
        big[:2, :2], big[1, 2] = a, 1.0 / self.mass
        step = expm(big * self.control_dt)  # exact zero-order-hold discretisation
        self._phi, self._gamma = step[:2, :2], step[:2, 2]
        self.obs_layout = OBS
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        high = OBS.high()
        self.observation_space = spaces.Box(-high, high, dtype=np.float32)
        self.state = np.zeros(2)

    def _check_reset_options(self, opts):  # MFEnv.reset: checked before any draw
        return {k: check_range(k, v, -MAX_START, MAX_START) for k, v in opts.items()}

    def _start(self, opts):  # MFEnv.reset: after seeding, with the step counter at 0
        self.state = self.np_random.uniform(-0.1, 0.1, 2)
        for k, v in opts.items():
            self.state[OBS.index(k)] = v
        return self.state.copy(), self._info(0.0)

    def step(self, action):
        u = self._scalar_action(action)
        self.state = self._phi @ self.state + self._gamma * (u * self.max_force)
        self._steps += 1
        dt = self.control_dt
        terms = {"position": -((self.state[0] / 0.1) ** 2) * dt, "effort": -0.01 * u * u * dt}
        info = self._info(u * self.max_force)
        info["reward_terms"] = terms
        return self._finish_step(self.state.copy(), sum(terms.values()), False,
                                 self._steps >= self.max_steps, info,
                                 bool(np.all(np.isfinite(self.state))))  # fmt: skip

    def _info(self, force):
        x, v = self.state
        return {"position": float(x), "velocity": float(v), "force": float(force),
                "time": self._steps * self.control_dt}  # fmt: skip

    def _draw_frame(self):
        frame = np.full((64, 128, 3), 255, dtype=np.uint8)
        col = int(np.clip(64 + 300 * self.state[0], 4, 123))
        frame[24:40, col - 4 : col + 4] = (200, 40, 40)
        frame[31:33, 0:col] = (60, 60, 60)
        return frame
