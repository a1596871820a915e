"""Eel-v0: an anguilliform swimmer on the active beam in still water (Rios 2017 §4.5 I)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.envs._beam_robot import BeamRobotMixin
from mf_envs.envs.base import MFEnv
from mf_envs.envs.eel import build, render, rows, spec
from mf_envs.physics.swimmer.fluid import (
    C_FORM,
    C_NORMAL,
    C_TANGENTIAL,
    RHO_WATER,
    point_forces,
)

AVAILABLE_EFFECTS = {
    "resistive": "Taylor's (1952) quadratic normal and tangential drag of each body element",
    "reactive": "Lighthill's (1960) added mass on the normal velocity and the tail force",
    "form_drag": "the leading end's axial form drag of a gliding fish (docs/eel.md)",
    "muscle_power": "the muscles' positive power capped at fish muscle's power density",
}
DEFAULT_EFFECTS = ("resistive", "reactive", "form_drag", "muscle_power")
EPISODE_SECONDS = 10.0  # s, the default episode (500 steps of the default 0.02 s)


class EelEnv(BeamRobotMixin, MFEnv):
    """
    ## Description
    An anguilliform swimmer (Rios 2017 §4.5 I) sized like the American eels of Tytell & Lauder
    (2004): a planar geometrically exact active C1 beam (`mf_envs.physics.swimmer`), L = 0.2 m,
    a round section of diameter 0.06 L, E = 1 MPa, neutrally buoyant (density 1000 kg/m^3) in
    the horizontal plane of still water. Its muscles set the active curvature kappa#(S, t)
    (M3 = EI (kappa - kappa#)); the water acts through Taylor's (1952) resistive force
    (quadratic cross-flow drag C_N = 1.1 and skin friction C_T = 0.0055) and Lighthill's
    (1960) reactive force (added mass rho pi d^2 / 4 on the normal velocity, the tail force),
    and a form drag on the leading end along its axis (frontal-area coefficient 0.19, from the
    drag of gliding fish; docs/eel.md),
    stepped by the implicit energy-momentum scheme with the added mass in the residual and the
    forces' consistent tangents. Goal: swim along the target direction (+x) with little
    actuation energy.

    ## Action Space
    `Box(-1, 1, (n_control_points,), float32)`: target kappa# = max_curvature * a at the
    control points S_j = j L / (n - 1), tail (S = 0) to head (S = L), linear in S between them.
    The command moves towards the target by at most max_curvature_rate x control_dt per step
    (the muscles' finite rate) and linearly in time over the step. With the effect
    `muscle_power` (default) the step's change is scaled down further where the muscles'
    positive work in the step would exceed max power x control_dt, max power =
    muscle_power_density x muscle_mass_fraction x body mass (22 W/kg x 0.5 x 22.6 g = 0.25 W;
    docs/eel.md).

    With `action_mode="wave"` the action is `Box(-1, 1, (3,), float32)`: the tail's curvature
    amplitude a in [0, max_curvature], the wavelength lambda / L in [0.4, 2] and the frequency f
    in [0.5, 5] Hz (linear maps) of kappa#(S_j, t) = a (0.3 + 0.7 (L - S_j) / L)
    sin(2 pi (L - S_j) / lambda - phi), phi advancing by 2 pi f control_dt per step (phi = 0 at
    reset), the same rate limit and hold.

    ## Observation Space
    `Box(float32, (2 n + 6,))`, laid out by `mf_envs.envs.eel.spec.observation_layout(n)` (the
    env's `obs_layout`):

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0..n-1 | curvature | measured kappa L at the control points | +-20 | |
    | n | sin_heading | sin(mean frame angle - target direction) | +-1 | |
    | n+1 | cos_heading | cos(mean frame angle - target direction) | +-1 | |
    | n+2..n+3 | velocity | v_com / L along, across the mean axis | +-20 | 1/s |
    | n+4 | tail_angle | tail frame angle - mean frame angle (wrapped) | +-3.5 | rad |
    | n+5 | tail_rate | rate of the tail's frame angle | +-20 | 10 rad/s |
    | n+6..2n+5 | curvature_command | kappa# / max_curvature at the step's end | +-1 | |

    ## Rewards
    `reward = progress + effort`, the terms in `info["reward_terms"]`: `progress` = centre-of-
    mass displacement along the target direction in the step / L; `effort` = -effort_weight x
    actuation energy of the step [J] (the muscles' positive work -int M3 dkappa#/dt dS, no
    regeneration; default weight 2e-4 / (m L^2 / s^2), m the body mass). Info keys:
    `spec.INFO_KEYS`.

    BEAM_START_AND_END(500 = 10 s at 0.02 s)

    ## Arguments
    | Argument | Default | Meaning |
    |---|---|---|
    | length, diameter | 0.2, 0.06 L | body length L, diameter d [m] (d <= L / 5) |
    | youngs_modulus, shear_modulus | 1e6, E / 1.5 | E, G [Pa] in [1e3, 1e12] |
    | density, water_density | 1000, 1000 | body, water density [kg/m^3]; body >= 0.25 x water |
    | drag_normal, drag_tangential | 1.1, 0.0055 | Taylor's C_N, C_T (docs/eel.md) |
    | drag_form | 0.19 | form drag coefficient on the frontal area pi d^2 / 4 (docs/eel.md) |
    | n_elements | 6 | C1 elements, 2..64 |
    | max_curvature | 50 | action scale [1/m], max_curvature L <= 20 |
    | max_curvature_rate | 750 | muscle rate limit of the command [1/(m s)] (docs/eel.md) |
    | muscle_power_density | 22 | the muscles' power limit per kg of muscle [W/kg] (docs/eel.md) |
    | muscle_mass_fraction | 0.5 | muscle mass / body mass, in [0.001, 1] |
    | n_control_points | 7 | actuation control points, 2..64 |
    | control_dt, physics_dt | 0.02, 0.01 | s per step, implicit physics step |
    | episode_seconds | None | episode length [s]; None: 10 s |
    | max_episode_steps | None | or the episode length in control steps |
    | effort_weight | None | [1/J] >= 0; None: 2e-4 / (m L^2 / s^2) |
    | reset_noise_scale | 0.05 | start curvature noise / max_curvature, in [0, 1] |
    | initial_heading_range | pi | start heading drawn in +-this [rad], in [0, pi] |
    | numerical_damping | 0.1 | theta_s - 1/2 of the stresses, in [0, 0.5] (0: energy-conserving) |
    | action_mode | "curvature" | or "wave": (amplitude, wavelength, frequency) of the wave |
    | effects | resistive, reactive, form_drag, muscle_power | any subset; () a body in vacuum |

    ## Version History
    * v0: initial release; the form drag (effect `form_drag`) and the muscles' power limit
      (effect `muscle_power`), both on by default, added later, which changes trajectories by
      design.
    """

    RESET_OPTIONS = spec.RESET_OPTIONS
    robot_build, robot_rows, robot_spec = build, rows, spec  # (`BeamRobotMixin`)
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS
    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 50}
    target_direction = 0.0  # rad: +x

    def __init__(
        self,
        length: float = build.LENGTH,
        diameter: float | None = None,
        youngs_modulus: float = 1e6,
        shear_modulus: float | None = None,
        density: float = RHO_WATER,
        water_density: float = RHO_WATER,
        drag_normal: float = C_NORMAL,
        drag_tangential: float = C_TANGENTIAL,
        drag_form: float = C_FORM,
        n_elements: int = 6,
        max_curvature: float = 50.0,
        max_curvature_rate: float = 750.0,
        muscle_power_density: float = build.MUSCLE_POWER_DENSITY,
        muscle_mass_fraction: float = build.MUSCLE_MASS_FRACTION,
        n_control_points: int = 7,
        control_dt: float = 0.02,
        physics_dt: float = 0.01,
        episode_seconds: float | None = None,
        effort_weight: float | None = None,
        reset_noise_scale: float = 0.05,
        initial_heading_range: float = math.pi,
        numerical_damping: float = 0.1,
        action_mode: str = "curvature",
        effects: Any = None,
        max_episode_steps: int | None = None,
        render_mode: str | None = None,
    ) -> None:
        kw = {k: v for k, v in locals().items() if k not in ("self", "render_mode", "__class__")}
        super().__init__(effects=effects, control_dt=control_dt, physics_dt=physics_dt,
                         render_mode=render_mode)  # fmt: skip
        self._make_robot(kw, EPISODE_SECONDS)
        self.cfg = rows.pack(self.scene, self.model, self.n_substeps, self.physics_dt,
                             self.control_dt, self.target_direction)  # fmt: skip
        self._make_state(self.n_ctrl if self.scene.action_mode == "curvature" else 3)
        self.phase = np.zeros(1)  # the wave's phase [rad] (action_mode "wave")
        self._sc = rows.scratch(self.model, self.n_ctrl)

    # ------------------------------------------------------------------ API
    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        self.phase[:] = 0.0
        return super()._start(opts)

    # ------------------------------------------------------------------ helpers
    def _advance(self, action: np.ndarray, rep: np.ndarray) -> None:
        rows.step_row(self.state[0], self.state[1], self.cmd, self.phase, action, self.cfg,
                      self._sc, self._body, self._obs, rep)  # fmt: skip

    def _heading(self) -> float:
        return float(self._body[4])

    def water_forces(self) -> np.ndarray:
        """(n_el * 4, 4) rows (x, y, f_x, f_y) [m, N/m]: Taylor's resistive line force at the
        Gauss points in the present state."""
        out = np.zeros((4 * self.model.n_elements, 4))
        nzt, npt, law = self.cfg.body.load
        point_forces(self.state[0], self.state[1], self.model.le, nzt, npt, law, out)
        return out

    def _draw(self, line: np.ndarray, text: str) -> np.ndarray:
        forces = self.water_forces()
        peak = float(np.max(np.hypot(forces[:, 2], forces[:, 3]))) if forces.size else 0.0
        scale = 0.3 * self.scene.length / peak if peak > 0 and np.isfinite(peak) else 0.0
        return render.draw(line, self._track[-400:], self.target_direction, text, forces, scale)
