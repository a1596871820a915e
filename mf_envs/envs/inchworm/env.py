"""Inchworm-v0: an active C1-beam inchworm crawling by its actuation curvature (Rios 2017 §4.10)."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_range
from mf_envs.envs._spec import check_curvature_option
from mf_envs.envs.base import MFEnv
from mf_envs.envs.inchworm import build, render, spec
from mf_envs.physics.beam import NewtonDivergence
from mf_envs.physics.beam.contact.feet import NoQuasiStaticEquilibrium
from mf_envs.physics.inchworm import INCHWORM_EFFECTS
from mf_envs.physics.inchworm.drive import DRIVE_EFFECTS, make_driven

# the seed's scene (§4.10): kinematic anchors (Eq. 102), kappa# as commanded, quasi-static
SEED_SCENE_EFFECTS = ("gravity", "shear_deformation", "anchor_switching")
AVAILABLE_EFFECTS = {**INCHWORM_EFFECTS, **DRIVE_EFFECTS}
DEFAULT_EFFECTS = (*SEED_SCENE_EFFECTS, "actuator_dynamics", "friction")
CURVATURE_OBS_LIMIT = spec.CURVATURE_OBS_LIMIT
REACTION_OBS_LIMIT = spec.REACTION_OBS_LIMIT
# what a diverging solve raises: a failed step ends the episode (numerical_failure)
SOLVER_ERRORS = (NewtonDivergence, NoQuasiStaticEquilibrium, np.linalg.LinAlgError)
SOLVER_ERRORS += (FloatingPointError, OverflowError)


class InchwormEnv(MFEnv):
    """
    ## Description
    A slender soft robot (the seed's SMA/PDMS inchworm, §4.10) modelled as a planar geometrically
    exact active beam with three-node C1 elements (Eqs. 68-83). The agent sets the actuation
    curvature kappa#(S) (the pre-curvature of the active law M3 = EI (kappa - kappa#), Eq. 53);
    the body's shape follows from equilibrium (quasi-static by default, as in the seed; Newmark
    dynamics with the `inertia` effect). Both ends rest on the ground (z = 0, Eq. 100); with
    `anchor_switching` the agent chooses which foot grips. By default (issue 16) the command
    reaches the beam through the actuators' own dynamics (`actuator_dynamics`: a first-order
    lag tau with a rate limit on kappa#, SMA-wire defaults, `mf_envs.physics.actuators.curvature`)
    and the feet hold by anisotropic Coulomb friction with engage/release dynamics (`friction`,
    `mf_envs.physics.beam.contact.feet`): a foot slips when the pull exceeds mu N. Without them
    (`SEED_SCENE_EFFECTS`, the seed's scene) kappa# is as commanded and the gripping foot's x is
    held kinematically (Eq. 102). With `terrain` the body instead rests on Bekker/Janosi soil
    (Eqs. 56-57):
    no kinematic supports, and the anchor choice gives the gripping half of the body the soil's
    shear strength while the other half slides (slick foot), so the grip comes out of the
    contact law (`terrain` implies the weight). Curling with the head anchored pulls the tail
    forward; uncurling with the tail anchored pushes the head forward. Goal: crawl forward
    (+x) with little actuation energy.

    Control step and actuator bandwidth: the default control_dt = 0.1 s is a third of the
    actuator time constant (0.3 s; corner frequency 1 / (2 pi tau) = 0.53 Hz, the control rate
    is 19x that), and in one step kappa# moves at most actuator_rate_limit x dt = 1.3 1/m,
    10 % of its range: a bang-bang policy cannot sweep the range in one step.

    ## Action Space
    `Box(-1, 1, (n_control_points + 1,), float32)` with `anchor_switching`, else
    `(n_control_points,)`:

    kappa# = -max_curvature (a + 1) / 2, i.e. in [-max_curvature, 0] (the body humps up).

    | Num | Action | Scaling |
    |-----|--------|---------|
    | 0..n-1 | commanded kappa# at control points S = 0 .. L, linear between | [1/m] |
    | n | anchor / grip choice | a > 0: head grips, a <= 0: tail grips (with `friction`: the |
    |   |   | other foot releases; without switching both feet grip) |

    ## Observation Space
    `Box(float32, (2 n + 6,))`, what an on-board robot can sense, laid out by
    `mf_envs.envs.inchworm.spec.observation_layout(n)` (the env's `obs_layout`; read slots by
    name: `obs_layout.slice("curvature")`, `obs_layout.index("grip")`):

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0..n-1 | curvature | measured kappa L at the control points (strain gauges) | +-20 | |
    | n..2n-1 | curvature_command | commanded kappa# / max_curvature | +-1 | |
    | 2n | tail_angle | frame angle psi at the tail (foot IMU) | +-2 pi | rad |
    | 2n+1 | head_angle | frame angle psi at the head (foot IMU) | +-2 pi | rad |
    | 2n+2 | head_tail_distance | (x_head - x_tail) / L | +-1.5 | |
    | 2n+3 | grip | gripping foot: +1 head, -1 tail | +-1 | |
    | 2n+4 | tail_reaction | ground reaction at the tail (`terrain`: half) / weight | +-20 | |
    | 2n+5 | head_reaction | ground reaction at the head / weight | +-20 | |

    ## Rewards
    `reward = progress + effort`, the terms in `info["reward_terms"]`:
    `progress` = tail advance this step / L (computed in the body's local coordinates, exact at
    any distance); `effort` = -effort_weight * actuation energy of the step [J] (the positive
    work of P = -int M3 d kappa#/dt dS, no regeneration; default weight 1 / (m_A g L * L), so the
    reward is (dx - E / weight) / L). Info keys: `spec.INFO_KEYS` (`time` = steps x control_dt;
    `kappa_sharp` = realised actuation curvature at the control points [1/m], `actuation_power`
    = mean mechanical actuation power of the step [W], `actuation_energy` [J], `grip` = the
    feet's engagement (tail, head) in [0, 1], `foot_slip` (tail, head) [m]).

    ## Starting State
    Straight body at rest, tail at x = 0, head gripping, with a small random initial actuation
    kappa# = -max_curvature * U(0, reset_noise_scale) per control point, settled to equilibrium.
    `reset(options={"kappa": (n,) [1/m] within +-max_curvature, "x_tail": m, |.| <= 1e6})`
    overrides; any other key or value raises ValueError naming it (and draws nothing).

    ## Episode End
    Truncation after `episode_seconds` (default 40 s = 400 steps of 0.1 s; or give
    `max_episode_steps`). Termination when Newton-Raphson fails even after step halving
    (info["numerical_failure"] = True), or when both feet would slip at once (no quasi-static
    equilibrium: the body would accelerate); render() then draws the last finite state.
    The physics is translation invariant to round-off at any distance crawled (local
    coordinates re-centred on the tail, see `mf_envs.physics.inchworm`).

    ## Arguments
    | Argument | Default | Meaning |
    |----------|---------|---------|
    | length | 0.3 | body length L [m] in [0.01, 10] |
    | width, height | 0.02, 0.01 | cross-section b, h [m] in [1e-4, 1], h <= L / 5 |
    | youngs_modulus, shear_modulus | 2.4e9, 0.96e9 | E, G [Pa] in [1e3, 1e13] |
    | mass_per_length | 0.278 | m_A [kg/m] in [1e-6, 1e4] (J_3C from m_A h^2 / 12) |
    | n_elements | 12 | C1 elements, 1..64 |
    | max_curvature | 13.0 | largest abs(kappa#) [1/m] (the seed's kappa0#), <= 20 / L |
    | n_control_points | 3 | actuation control points, 2..64 |
    | control_dt, physics_dt | 0.1, 0.1 | s per step; Newmark step with `inertia` |
    | episode_seconds | None | episode length [s]; None: max_episode_steps steps |
    | max_episode_steps | 400 | 10 seed gait cycles (when episode_seconds is None) |
    | effort_weight | None | weight of the effort term [1/J], >= 0; None: 1 / (m_A g L^2) |
    | actuator_time_constant | 0.3 | tau [s] of the actuator lag (SMA wire, see actuators) |
    | actuator_rate_limit | 13.0 | largest abs(d kappa#/dt) [1/(m s)] |
    | grip_time_constant | 0.2 | engage/release time constant of the feet [s] |
    | friction_coefficients | None | dict grip_forward, grip_backward, slide_forward, |
    |  |  | slide_backward (defaults 0.6, 1.0, 0.1, 0.15) or 4 numbers in that order |
    | increment_factor | 4.0 | increments up to factor * 2h/L^2 (seed: 1; same equilibria) |
    |  |  | at most 200 increments (or Newmark steps) per step |
    | reset_noise_scale | 0.05 | initial actuation noise, in [0, 1] |
    | soil | "dry_sand" | soil preset for `terrain` (Wong 2008 Table 2.3 values) |
    | effects | gravity, shear_deformation, anchor_switching, | also: inertia, terrain |
    |  | actuator_dynamics, friction | (friction excludes both) |

    ## Version History
    * v0: initial release (kinematic anchoring of Eq. 102; quasi-static by default); issue 16:
      actuator dynamics, friction feet and the energy effort term by default.
    """

    RESET_OPTIONS = spec.RESET_OPTIONS  # the keys reset(options=...) takes
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 10}
    exclusive_effects = (("friction", "inertia"), ("friction", "terrain"))  # ValueError

    def __init__(
        self,
        length: float = 0.3,
        width: float = 0.02,
        height: float = 0.01,
        youngs_modulus: float = 2.4e9,
        shear_modulus: float = 0.96e9,
        mass_per_length: float = 0.278,
        n_elements: int = 12,
        max_curvature: float = 13.0,
        effects: Any = None,
        n_control_points: int = 3,
        control_dt: float = 0.1,
        physics_dt: float = 0.1,
        max_episode_steps: int | None = None,
        effort_weight: float | None = None,
        increment_factor: float = 4.0,
        reset_noise_scale: float = 0.05,
        soil: str = "dry_sand",
        episode_seconds: float | None = None,
        actuator_time_constant: float = build.SMA_TIME_CONSTANT,
        actuator_rate_limit: float = build.SMA_RATE_LIMIT,
        grip_time_constant: float = build.GRIP_TIME_CONSTANT,
        friction_coefficients: Any = None,
        render_mode: str | None = None,
    ) -> None:
        kw = {k: v for k, v in locals().items() if k not in ("self", "render_mode", "__class__")}
        super().__init__(effects=effects, control_dt=control_dt, physics_dt=physics_dt,
                         render_mode=render_mode)  # fmt: skip
        self._set_scene(build.build(kw, self.effects, self.n_substeps))  # kwargs as physics params
        self.max_steps = build.episode_steps(
            max_episode_steps, episode_seconds, self._episode_steps
        )
        self.episode_seconds = self.max_steps * self.control_dt
        self.actuator = self.actuator_params if "actuator_dynamics" in self.effects else None
        self._drive = build.drive_kwargs(self.scene, self.effects)
        try:
            self.driven = make_driven(**self._drive)
        except SOLVER_ERRORS as exc:
            raise ValueError(
                "length, youngs_modulus, mass_per_length, height: the body finds no static "
                f"equilibrium under its own weight ({exc}); stiffen or shorten it"
            ) from None
        self.sim = self.driven.sim
        self.S_ctrl = self.driven.S_ctrl
        self.obs_geometry = spec.observe_geometry(self.sim, self.S_ctrl)
        self.switching = "anchor_switching" in self.effects
        n_act = self.n_ctrl + (1 if self.switching else 0)
        self.action_space = spaces.Box(-1.0, 1.0, (n_act,), np.float32)
        self.obs_layout = spec.observation_layout(self.n_ctrl)
        hi = self.obs_layout.high()
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self.kappa_command = np.zeros(self.n_ctrl)
        self._steps = 0
        self._frame_state: dict[str, Any] | None = None  # last finite state, for render()

    def drive_config(self) -> tuple:
        """Hashable configuration of the physics (make_driven's arguments, control_dt,
        max_curvature): what an open-loop gait tuner needs to rebuild this robot."""
        cfg = dict(self._drive, control_dt=self.control_dt, max_curvature=self.max_curvature)
        return tuple(cfg.items())

    # ------------------------------------------------------------------ API
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a = self._validate_action(action)
        kappa_new = -self.max_curvature * 0.5 * (a[: self.n_ctrl] + 1.0)
        anchor = None
        if self.switching:
            anchor = "head" if a[-1] > 0.0 else "tail"
        tail_old = spec.tail_position(self.sim)
        ok, report = True, None
        try:
            n_min = self.n_substeps if "inertia" in self.effects else 1
            report = self.driven.step(kappa_new, anchor, self.control_dt, n_min)
            self.kappa_command = kappa_new
        except SOLVER_ERRORS:
            ok = False
        self._steps += 1
        energy = 0.0 if report is None else report.energy
        terms = spec.reward_terms(
            tail_old, spec.tail_position(self.sim), self.params.length, energy, self.effort_weight
        )
        obs = self._observe() if ok else np.full(self.observation_space.shape, np.nan)
        info = self._get_info(terms, report)
        if ok:
            self._remember_frame(info)
        truncated = self._steps >= self.max_steps
        reward = terms["progress"] + terms["effort"]
        return self._finish_step(obs, reward, False, truncated, info, ok)

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        x_tail = check_range("x_tail", opts.get("x_tail", 0.0), -spec.MAX_X_TAIL, spec.MAX_X_TAIL)
        kappa = None
        if "kappa" in opts:
            kappa = check_curvature_option(opts["kappa"], self.n_ctrl, self.max_curvature)
        return {"x_tail": x_tail, "kappa": kappa}

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        x_tail, kappa = opts["x_tail"], opts["kappa"]
        noise = self.np_random.uniform(0.0, self.reset_noise_scale, self.n_ctrl)
        drawn, kappa = kappa is None, -self.max_curvature * noise if kappa is None else kappa
        for _ in range(8 if drawn else 1):  # a drawn start without equilibrium is halved
            try:
                self.driven.reset(kappa, x_tail=x_tail)
                break
            except SOLVER_ERRORS:
                kappa = 0.5 * kappa
        else:
            if not drawn:
                raise ValueError("kappa: no equilibrium for this initial actuation")
            kappa = np.zeros(self.n_ctrl)  # the flat body is always an equilibrium
            self.driven.reset(kappa, x_tail=x_tail)
        self.kappa_command = kappa
        info = self._get_info({"progress": 0.0, "effort": 0.0}, None)
        self._frame_state = None
        self._remember_frame(info)
        return self._observe(), info

    # ------------------------------------------------------------------ helpers
    def _observe(self) -> np.ndarray:
        args = (self.obs_geometry, self.kappa_command, self.max_curvature, self.scene.weight)
        return spec.observe(self.sim, *args)

    def _get_info(self, terms: dict[str, float], report: Any) -> dict[str, Any]:
        sim = self.sim
        info: dict[str, Any] = {
            "x_head": sim.x_head,
            "x_tail": sim.x_tail,
            "centerline": sim.centerline(),
            "anchor": sim.anchor,
            "kappa_sharp": self.driven.kappa_ctrl.copy(),
            "kappa_command": self.kappa_command.copy(),
            "actuation_power": 0.0 if report is None else report.net_work / self.control_dt,
            "actuation_energy": 0.0 if report is None else report.energy,
            "grip": self.driven.grip.copy(),
            "foot_slip": np.zeros(2) if report is None else report.slip.copy(),
            "elastic_energy": sim.elastic_energy(),
            "newton_iterations": 0 if report is None else report.iterations,
            "increments": 0 if report is None else report.increments,
            "time": self._steps * self.control_dt,
        }
        info["reward_terms"] = terms  # the convention shared by every env: terms sum to reward
        return info

    # ------------------------------------------------------------------ rendering
    def _remember_frame(self, info: dict[str, Any]) -> None:
        """Keep the drawable state if it is finite (`render.frame_state`)."""
        fs = render.frame_state(info, self._steps)
        if fs is not None:
            self._frame_state = fs

    def _draw_frame(self) -> np.ndarray:
        if self._frame_state is None:  # before the first reset: the constructed state
            self._remember_frame(render.sim_state(self.sim))
        return render.draw(self._frame_state, self._steps)
