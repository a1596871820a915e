"""Serpentine-v0: a soft snake crawling on anisotropic belly friction (Rios 2017 §4.5 II)."""

from __future__ import annotations

import inspect
import math
from typing import Any

import numpy as np

from mf_envs.envs._beam_robot import BeamRobotMixin
from mf_envs.envs.base import MFEnv
from mf_envs.envs.serpentine import build, render, rows, spec

AVAILABLE_EFFECTS = {
    "friction": "anisotropic Coulomb belly friction (mu, backward_ratio mu, lateral_ratio mu)",
    "viscous_ground": "viscous ground f = -(c_t v_t t + c_n v_n n) (exclusive with friction)",
    "actuator_dynamics": "muscles as a first-order lag of the command (actuator_time_constant)",
}
DEFAULT_EFFECTS = ("friction", "actuator_dynamics")
EPISODE_SECONDS = 20.0  # s, the default episode (400 steps of the default 0.05 s)


class SerpentineEnv(BeamRobotMixin, MFEnv):
    """
    ## Description
    A soft serpentine robot lying on flat ground (Rios 2017 §4.5 II), modelled as a planar
    geometrically exact active C1 beam (`mf_envs.physics.serpentine`) sized like PyElastica's
    continuum snake: L = 0.35 m, radius 0.011 L, E = 1 MPa, rho = 1000 kg/m^3, a Kelvin-Voigt
    elastomer (retardation time 10 ms). Its muscles set the active curvature kappa#(S, t)
    (M3 = EI (kappa - kappa#)), lagging their command; the belly slides on
    anisotropic Coulomb friction (forward mu, backward 1.5 mu, lateral 2 mu, mu from the
    Froude number 0.1 at a 2 s period), stepped by the implicit energy-momentum scheme with the
    friction's consistent tangent. Lateral undulation turns the lateral friction into thrust.
    Goal: crawl along the target direction (+x) with little actuation energy.

    ## Action Space
    `Box(-1, 1, (n_control_points,), float32)`: kappa# = max_curvature * a at the control
    points S_j = j L / (n - 1), tail (S = 0) to head (S = L), linear in S between them. With
    `actuator_dynamics` (default) the muscles' kappa# follows the command as the rate-limited
    first-order lag of `physics.actuators.curvature` (A1: time constant actuator_time_constant,
    rate at most actuator_rate_limit), exactly at the physics steps' ends; without it the
    command moves linearly in time from the previous one to the new one over the step.

    ## Observation Space
    `Box(float32, (2 n + 4,))`, what an on-board robot senses, laid out by
    `mf_envs.envs.serpentine.spec.observation_layout(n)` (the env's `obs_layout`):

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0..n-1 | curvature | measured kappa L at the control points (strain gauges) | +-20 | |
    | n | sin_heading | sin(psi_head - target direction) | +-1 | |
    | n+1 | cos_heading | cos(psi_head - target direction) | +-1 | |
    | n+2..n+3 | velocity | v_com / L along, across the mean axis | +-100 | 0.1 1/s |
    | n+4..2n+3 | curvature_command | muscles' kappa# / max_curvature (the lag's state) | +-1 | |

    psi_head is the frame angle at the head; the mean axis is the mean frame angle.

    ## Rewards
    `reward = progress + effort`, the terms in `info["reward_terms"]`: `progress` = centre-of-
    mass displacement along the target direction in the step / L; `effort` = -effort_weight x
    actuation energy of the step [J] (the muscles' positive work -int M3 dkappa#/dt dS, no
    regeneration; default weight 0.01 / (m_A g L^2): about 0.007 of progress for the
    PyElastica-like serpenoid). Info keys: `spec.INFO_KEYS` (x, y of the centre of mass [m],
    heading [rad], speed [m/s], actuation energy [J] and power [W], time [s]).

    BEAM_START_AND_END(400 = 20 s at 0.05 s)

    ## Arguments
    | Argument | Default | Meaning |
    |---|---|---|
    | length, radius | 0.35, 0.011 L | body length L, section radius [m] (radius <= L / 10) |
    | youngs_modulus, shear_modulus | 1e6, E / 1.5 | E, G [Pa] in [1e3, 1e12] |
    | density | 1000 | rho [kg/m^3] |
    | n_elements | 12 | C1 elements, 2..64 (2 per control interval) |
    | max_curvature | 25 | action scale [1/m], max_curvature L <= 20 |
    | n_control_points | 7 | actuation control points, 2..64 |
    | control_dt, physics_dt | 0.05, 0.003125 | s per step, implicit physics step (< 5 % in speed) |
    | episode_seconds | None | episode length [s]; None: 20 s (10 periods of the reference gait) |
    | max_episode_steps | None | or the episode length in control steps |
    | friction_coefficient | 0.892 | forward Coulomb mu = L / (T^2 g Fr), T = 2 s, Fr = 0.1 |
    | backward_ratio, lateral_ratio | 1.5, 2 | backward, lateral coefficient / mu |
    | slip_speed | 1e-3 | regularisation speed of the friction [m/s] |
    | viscous_tangential, viscous_normal | 2, 4 | c_t, c_n [N s/m^2] with `viscous_ground` |
    | effort_weight | None | [1/J] >= 0; None: 0.01 / (m_A g L^2) |
    | reset_noise_scale | 0.05 | start curvature noise / max_curvature, in [0, 1] |
    | initial_heading_range | pi | start heading drawn in +-this [rad], in [0, pi] |
    | material_damping | 0.01 | Kelvin-Voigt retardation time tau [s] of the body, in [0, 10] |
    | actuator_time_constant | 0.1 | muscle lag [s] with `actuator_dynamics`, in [1e-4, 100] |
    | actuator_rate_limit | 1000 | muscle curvature rate limit [1/(m s)], in [1e-3, 1e6] |
    | effects | friction, actuator_dynamics | viscous_ground for friction; () none of them |
    | preset | None | "pyelastica": PyElastica's continuum snake (`build.PYELASTICA_SCENE`) |

    ## Version History
    * v0: initial release.
    """

    RESET_OPTIONS = spec.RESET_OPTIONS
    robot_build, robot_rows, robot_spec = build, rows, spec  # (`BeamRobotMixin`)
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS
    exclusive_effects = (("friction", "viscous_ground"),)  # one ground law (ValueError)
    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 20}
    target_direction = 0.0  # rad: +x

    def __init__(
        self,
        length: float = build.LENGTH,
        radius: float | None = None,
        youngs_modulus: float = 1e6,
        shear_modulus: float | None = None,
        density: float = 1000.0,
        n_elements: int = 12,
        max_curvature: float = 25.0,
        n_control_points: int = 7,
        control_dt: float = 0.05,
        physics_dt: float = 0.003125,
        episode_seconds: float | None = None,
        friction_coefficient: float = build.MU,
        backward_ratio: float = 1.5,
        lateral_ratio: float = 2.0,
        slip_speed: float = 1e-3,
        viscous_tangential: float = 2.0,
        viscous_normal: float = 4.0,
        effort_weight: float | None = None,
        reset_noise_scale: float = 0.05,
        initial_heading_range: float = math.pi,
        material_damping: float = 0.01,
        actuator_time_constant: float = 0.1,
        actuator_rate_limit: float = 1000.0,
        effects: Any = None,
        preset: str | None = None,
        max_episode_steps: int | None = None,
        render_mode: str | None = None,
    ) -> None:
        kw = {k: v for k, v in locals().items() if k not in ("self", "render_mode", "__class__")}
        kw = build.apply_preset(kw, _DEFAULTS)
        self.preset = preset
        super().__init__(effects=kw["effects"], control_dt=kw["control_dt"],
                         physics_dt=kw["physics_dt"], render_mode=render_mode)  # fmt: skip
        self._make_robot(kw, EPISODE_SECONDS)
        self.cfg = rows.pack(
            self.scene, self.model, self.n_substeps, self.physics_dt, self.target_direction
        )
        self._make_state(self.n_ctrl)
        self._sc = rows.scratch(self.model, self.n_ctrl)

    # ------------------------------------------------------------------ helpers
    def _advance(self, action: np.ndarray, rep: np.ndarray) -> None:
        rows.step_row(self.state[0], self.state[1], self.cmd, action, self.cfg, self._sc,
                      self._body, self._obs, rep)  # fmt: skip

    def _heading(self) -> float:
        return float(self.state[0][-1])  # the head's frame angle

    def _draw(self, line: np.ndarray, text: str) -> np.ndarray:
        return render.draw(line, self._track[-400:], self.target_direction, text)


_DEFAULTS = {k: p.default for k, p in inspect.signature(SerpentineEnv.__init__).parameters.items()}
