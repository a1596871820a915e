"""Inchworm-v0: an active C1-beam inchworm crawling by its actuation curvature (Rios 2017 §4.10)."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_choice, check_int, check_range
from mf_envs.envs._spec import check_options
from mf_envs.envs.base import MFEnv
from mf_envs.envs.inchworm import spec
from mf_envs.physics.beam import NewtonDivergence
from mf_envs.physics.inchworm import INCHWORM_EFFECTS, Inchworm, InchwormParams, kappa_at_gauss
from mf_envs.physics.terrain import SOILS

DEFAULT_EFFECTS = ("gravity", "shear_deformation", "anchor_switching")
CURVATURE_OBS_LIMIT = spec.CURVATURE_OBS_LIMIT
REACTION_OBS_LIMIT = spec.REACTION_OBS_LIMIT
# what a diverging solve raises: a failed step ends the episode (numerical_failure)
SOLVER_ERRORS = (NewtonDivergence, np.linalg.LinAlgError, FloatingPointError, OverflowError)
MAX_INCREMENTS = 200  # increments (or Newmark steps) of a full-range step: a step stays fast


class InchwormEnv(MFEnv):
    """
    ## Description
    A slender soft robot (the seed's SMA/PDMS inchworm, §4.10) modelled as a planar geometrically
    exact active beam with three-node C1 elements (Eqs. 68-83). The agent sets the actuation
    curvature kappa#(S) (the pre-curvature of the active law M3 = EI (kappa - kappa#), Eq. 53);
    the body's shape follows from equilibrium (quasi-static by default, as in the seed; Newmark
    dynamics with the `inertia` effect). Both ends rest on the ground (z = 0, sliding simple
    supports, Eq. 100); with `anchor_switching` the agent chooses which foot grips (its x is
    held, Eq. 102). With `terrain` the body instead rests on Bekker/Janosi soil (Eqs. 56-57):
    no kinematic supports, and the anchor choice gives the gripping half of the body the soil's
    shear strength while the other half slides (slick foot), so the grip comes out of the
    contact law (`terrain` implies the weight). Curling with the head anchored pulls the tail
    forward; uncurling with the tail anchored pushes the head forward. Goal: crawl forward
    (+x) with little actuation effort.

    ## Action Space
    `Box(-1, 1, (n_control_points + 1,), float32)` with `anchor_switching`, else
    `(n_control_points,)`:

    kappa# = -max_curvature (a + 1) / 2, i.e. in [-max_curvature, 0] (the body humps up).

    | Num | Action | Scaling |
    |-----|--------|---------|
    | 0..n-1 | kappa# at control points S = 0 .. L (tail to head), linear between | [1/m] |
    | n | anchor choice | a > 0: head grips, a <= 0: tail grips |

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
    any distance); `effort` = -effort_weight * mean((Delta kappa# / max_curvature)^2) over the
    control points. Info keys: `spec.INFO_KEYS` (`time` = steps x control_dt).

    ## Starting State
    Straight body at rest, tail at x = 0, head gripping, with a small random initial actuation
    kappa# = -max_curvature * U(0, reset_noise_scale) per control point, settled to equilibrium.
    `reset(options={"kappa": (n,) [1/m] within +-max_curvature, "x_tail": m, |.| <= 1e6})`
    overrides; any other key or value raises ValueError naming it (and draws nothing).

    ## Episode End
    Truncation after `episode_seconds` (default 40 s = 400 steps of 0.1 s; or give
    `max_episode_steps`). Termination when Newton-Raphson fails even after step halving
    (info["numerical_failure"] = True); render() then draws the last finite state.
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
    | effort_weight | 0.05 | weight of the effort term, >= 0 |
    | increment_factor | 4.0 | increments up to factor * 2h/L^2 (seed: 1; same equilibria) |
    |  |  | at most 200 increments (or Newmark steps) per step |
    | reset_noise_scale | 0.05 | initial actuation noise, in [0, 1] |
    | soil | "dry_sand" | soil preset for `terrain` (Wong 2008 Table 2.3 values) |
    | effects | gravity, shear_deformation, anchor_switching | also: inertia, terrain |

    ## Version History
    * v0: initial release (kinematic anchoring of Eq. 102; quasi-static by default).
    """

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 10}

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
        effort_weight: float = 0.05,
        increment_factor: float = 4.0,
        reset_noise_scale: float = 0.05,
        soil: str = "dry_sand",
        episode_seconds: float | None = None,
        render_mode: str | None = None,
    ) -> None:
        super().__init__(
            effects=effects,
            available_effects=INCHWORM_EFFECTS,
            default_effects=DEFAULT_EFFECTS,
            control_dt=control_dt,
            physics_dt=physics_dt,
            render_mode=render_mode,
        )
        self.params = self._params(
            length, width, height, youngs_modulus, shear_modulus, mass_per_length, n_elements
        )
        L = self.params.length
        self.max_curvature = check_range("max_curvature", max_curvature, 1e-9)
        if self.max_curvature * L > CURVATURE_OBS_LIMIT:
            raise ValueError(
                f"max_curvature: max_curvature * length must be <= {CURVATURE_OBS_LIMIT:g} (the "
                f"curvature observation bound), got {self.max_curvature:g} 1/m x {L:g} m"
            )
        self.effort_weight = check_range("effort_weight", effort_weight, 0.0, 1e6)
        self.reset_noise_scale = check_range("reset_noise_scale", reset_noise_scale, 0.0, 1.0)
        increment_factor = check_range("increment_factor", increment_factor, 1e-3, 1e6)
        if self.max_curvature / (increment_factor * self.params.max_dkappa) > MAX_INCREMENTS:
            raise ValueError(
                f"increment_factor: a full-range step (max_curvature {self.max_curvature:g} 1/m) "
                f"would take more than {MAX_INCREMENTS} increments of "
                f"increment_factor * 2 height / length^2; raise increment_factor"
            )
        if "inertia" in self.effects and self.n_substeps > MAX_INCREMENTS:
            raise ValueError(
                f"physics_dt: with `inertia` a step takes control_dt / physics_dt Newmark steps, "
                f"at most {MAX_INCREMENTS}; got {self.n_substeps}"
            )
        self.n_ctrl = check_int("n_control_points", n_control_points, low=2, high=64)
        if episode_seconds is not None and max_episode_steps is not None:
            raise ValueError("episode_seconds: give episode_seconds or max_episode_steps, not both")
        if episode_seconds is None:
            steps = 400 if max_episode_steps is None else max_episode_steps
            self.max_episode_steps = check_int("max_episode_steps", steps, 1, 10**7)
        else:
            self.max_episode_steps = self._episode_steps(episode_seconds)
        self.episode_seconds = self.max_episode_steps * self.control_dt
        check_choice("soil", soil, tuple(SOILS))
        try:
            self.sim = Inchworm(
                self.params, self.effects, increment_factor=increment_factor, soil=soil
            )
        except SOLVER_ERRORS as exc:
            raise ValueError(
                "length, youngs_modulus, mass_per_length, height: the body finds no static "
                f"equilibrium under its own weight ({exc}); stiffen or shorten it"
            ) from None
        self.S_ctrl = np.linspace(0.0, L, self.n_ctrl)
        self.switching = "anchor_switching" in self.effects
        n_act = self.n_ctrl + (1 if self.switching else 0)
        self.action_space = spaces.Box(-1.0, 1.0, (n_act,), np.float32)
        self.obs_layout = spec.observation_layout(self.n_ctrl)
        hi = self.obs_layout.high()
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self._weight = self.params.mass_per_length * self.params.gravity * L
        self._kappa_ctrl = np.zeros(self.n_ctrl)
        self._steps = 0
        self._frame_state: dict[str, Any] | None = None  # last finite state, for render()

    @staticmethod
    def _params(length, width, height, youngs, shear, mass, n_elements) -> InchwormParams:
        """The beam parameters from the public arguments (errors name them)."""
        L = check_range("length", length, 0.01, 10.0)
        h = check_range("height", height, 1e-4, 1.0)
        if h > L / 5:
            raise ValueError(f"height: must be <= length / 5 (a slender beam), got {height!r}")
        m = check_range("mass_per_length", mass, 1e-6, 1e4)
        return dataclasses.replace(
            InchwormParams(),
            length=L,
            width=check_range("width", width, 1e-4, 1.0),
            height=h,
            youngs_modulus=check_range("youngs_modulus", youngs, 1e3, 1e13),
            shear_modulus=check_range("shear_modulus", shear, 1e3, 1e13),
            mass_per_length=m,
            rotary_inertia=m * h**2 / 12.0,
            n_elements=check_int("n_elements", n_elements, low=1, high=64),
        )

    # ------------------------------------------------------------------ API
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a = self._validate_action(action)
        kappa_new = -self.max_curvature * 0.5 * (a[: self.n_ctrl] + 1.0)
        anchor = None
        if self.switching:
            anchor = "head" if a[-1] > 0.0 else "tail"
        tail_old, kappa_old = spec.tail_position(self.sim), self._kappa_ctrl
        ok, report = True, None
        try:
            report = self.sim.actuate(
                kappa_at_gauss(self.S_ctrl, kappa_new, self.sim.model.gauss_S),
                dt=self.control_dt,
                anchor=anchor,
                min_increments=self.n_substeps if "inertia" in self.effects else 1,
            )
            self._kappa_ctrl = kappa_new
        except SOLVER_ERRORS:
            ok = False
        self._steps += 1
        rate = (kappa_new - kappa_old) / self.max_curvature
        terms = spec.reward_terms(
            tail_old, spec.tail_position(self.sim), self.params.length, rate, self.effort_weight
        )
        obs = self._observe() if ok else np.full(self.observation_space.shape, np.nan)
        info = self._get_info(terms, report)
        if ok:
            self._remember_frame(info)
        truncated = self._steps >= self.max_episode_steps
        reward = terms["progress"] + terms["effort"]
        return self._finish_step(obs, reward, False, truncated, info, ok)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        opts = check_options(options, spec.RESET_OPTIONS)  # all checks before any draw
        x_tail = check_range("x_tail", opts.get("x_tail", 0.0), -spec.MAX_X_TAIL, spec.MAX_X_TAIL)
        kappa = None
        if "kappa" in opts:
            kappa = np.asarray(opts["kappa"])
            if kappa.shape != (self.n_ctrl,) or kappa.dtype.kind not in "iuf":
                raise ValueError(f"kappa: expected {self.n_ctrl} numbers, got {opts['kappa']!r}")
            kappa = kappa.astype(float)
            if not np.all(np.isfinite(kappa)) or np.any(np.abs(kappa) > self.max_curvature):
                raise ValueError("kappa: must be finite and within +-max_curvature")
        super().reset(seed=seed)
        noise = self.np_random.uniform(0.0, self.reset_noise_scale, self.n_ctrl)
        kappa = -self.max_curvature * noise if kappa is None else kappa
        try:
            self.sim.reset(x_tail=x_tail)
            self.sim.actuate(
                kappa_at_gauss(self.S_ctrl, kappa, self.sim.model.gauss_S), anchor="head"
            )
        except SOLVER_ERRORS:
            raise ValueError(
                "kappa, reset_noise_scale, max_curvature: no equilibrium for this initial "
                "actuation; use a smaller one"
            ) from None
        self._kappa_ctrl = kappa
        self._steps = 0
        info = self._get_info({"progress": 0.0, "effort": 0.0}, None)
        self._frame_state = None
        self._remember_frame(info)
        return self._finish_reset(self._observe()), info

    # ------------------------------------------------------------------ helpers
    def _observe(self) -> np.ndarray:
        return spec.observe(
            self.sim, self.S_ctrl, self._kappa_ctrl, self.max_curvature, self._weight
        )

    def _get_info(self, terms: dict[str, float], report: Any) -> dict[str, Any]:
        sim = self.sim
        info: dict[str, Any] = {
            "x_head": sim.x_head,
            "x_tail": sim.x_tail,
            "centerline": sim.centerline(),
            "anchor": sim.anchor,
            "kappa_sharp": self._kappa_ctrl.copy(),
            "elastic_energy": sim.elastic_energy(),
            "newton_iterations": 0 if report is None else report.iterations,
            "increments": 0 if report is None else report.increments,
            "time": self._steps * self.control_dt,
        }
        info["reward_terms"] = terms  # the convention shared by every env: terms sum to reward
        return info

    # ------------------------------------------------------------------ rendering
    def _remember_frame(self, info: dict[str, Any]) -> None:
        """Keep the drawable state if it is finite (after a numerical failure the physics state
        may be NaN; render() then shows the last finite one)."""
        keys = ("centerline", "x_head", "x_tail")
        if all(np.all(np.isfinite(info[k])) for k in keys):
            self._frame_state = {k: info[k] for k in (*keys, "anchor")}
            self._frame_state["step"] = self._steps

    def _draw_frame(self) -> np.ndarray:
        from mf_envs.render import draw_inchworm

        if self._frame_state is None:  # before the first reset: the constructed state
            sim = self.sim
            info = {"centerline": sim.centerline(), "x_head": sim.x_head, "x_tail": sim.x_tail}
            self._remember_frame({**info, "anchor": sim.anchor})
        fs = self._frame_state
        note = "" if fs["step"] == self._steps else "  (last finite state)"
        return draw_inchworm(
            centerline=fs["centerline"],
            x_head=fs["x_head"],
            x_tail=fs["x_tail"],
            text=f"step {fs['step']}  tail x = {fs['x_tail']:+.3f} m  grip: {fs['anchor']}{note}",
        )
