"""Inchworm-v0 as a native batched vector env: N worms on friction feet in one compiled call.

`gym.make_vec("Inchworm-v0", num_envs=N, vectorization_mode="vector_entry_point", **kwargs)`
builds it; `kwargs` are those of `gym.make("Inchworm-v0", ...)` plus `autoreset_mode` (default
NEXT_STEP) and `num_threads` (blocks of rows stepped at once on threads, default: one per
CPU; a row's arithmetic does not depend on it). The scene must include `friction` (the default
scene; the quasi-static friction step is what is compiled); other effect sets raise ValueError
naming `effects` (use `vectorization_mode="sync"` for them).

Trajectories are identical, bit for bit, to `SyncVectorEnv` over N single `InchwormEnv`s with
the same seeds (`tests/test_vector_envs.py`): resets go through a template single env whose
state is copied into the row; steps through `envs.inchworm.rows.step_rows`, which runs the
single env's own compiled step (`quasistatic.drive_step`) and observation for every row.
See `mf_envs.envs._vector`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.inchworm.env import InchwormEnv
from mf_envs.envs.inchworm.rows import step_rows
from mf_envs.physics.beam.contact import stick_slip as ss

CENTERLINE_PER_ELEMENT = 8  # points per element of info["centerline"] (Inchworm.centerline)


class InchwormVectorEnv(BatchedVectorEnv):
    """N independent `Inchworm-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 2 n + 6) float32, actions (N, n [+ 1]) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does with the single env's keys (`spec.INFO_KEYS`)."""

    single_env_cls = InchwormEnv
    row_cost = "heavy"  # ~1 ms per row: one block per CPU from N = 2

    @classmethod
    def supports(cls, **env_kwargs: Any) -> bool:
        """Only the friction scene (the default effects include it) is compiled."""
        from mf_envs.effects import resolve_effects
        from mf_envs.envs.inchworm.env import AVAILABLE_EFFECTS, DEFAULT_EFFECTS

        effects = resolve_effects(env_kwargs.get("effects"), AVAILABLE_EFFECTS, DEFAULT_EFFECTS)
        return "friction" in effects

    def _alloc(self, n: int) -> None:
        env = self.template
        if "friction" not in env.effects:
            raise ValueError(
                "effects: the native Inchworm-v0 vector env runs the friction scene (the "
                f"compiled quasi-static step); got {sorted(env.effects)}; use "
                "vectorization_mode='sync' for other scenes"
            )
        driven, model = env.driven, env.sim.model
        nd, nc, ne = model.n_dof, env.n_ctrl, model.n_elements
        self._state = (
            np.zeros((n, nd)), np.zeros(n), np.zeros((n, nc)), np.zeros((n, nc)),
            np.zeros((n, 2)), np.zeros((n, 2), np.int64), np.zeros((n, nc)), np.ones(n, bool),
        )  # fmt: skip
        sc = driven.feet.scratch
        self._work = tuple(np.zeros((n, *a.shape), a.dtype) for a in sc)
        xis = np.linspace(0.0, 1.0, CENTERLINE_PER_ELEMENT + 1)[:-1]
        scales = (env.params.length, env.max_curvature, env.scene.weight)
        self._cfg = (
            env.switching, env.max_curvature, env.control_dt, 1, *driven.kernel_args(),
            env.obs_geometry, scales, xis,
        )  # fmt: skip
        n_pts = CENTERLINE_PER_ELEMENT * ne + 1
        self._out = (
            np.zeros(n, np.int64), np.zeros((n, ss.N_REPORT)), np.zeros((n, 2)),
            np.zeros((n, 2 * nc + 6), np.float32), np.zeros(n), np.zeros((n, n_pts, 2)),
            np.zeros((n, ne, 4)),
        )  # fmt: skip
        self._steps = np.zeros(n, np.int64)
        self._lo = self.single_observation_space.low
        self._hi = self.single_observation_space.high

    def _load(self, i: int) -> None:
        env = self.template
        sim, driven = env.sim, env.driven
        d, xo, lag, kc, g, slip, cmd, head = self._state
        d[i], xo[i] = sim.state.d, sim.x_origin
        lag[i] = driven.lag.kappa if driven.lag is not None else driven.kappa_ctrl
        kc[i], g[i], slip[i] = driven.kappa_ctrl, driven.feet.g, driven.feet.slipping
        cmd[i], head[i] = env.kappa_command, sim.anchor == "head"
        self._steps[i] = 0

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics, scratch, outputs, observations)."""
        arrays = [*self._state, *self._work, *self._out, self._steps, self._obs]
        return int(sum(a.nbytes for a in arrays))

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        env = self.template
        status, rep, before, obs, energy_el, line, _ = self._out
        status[~active] = ss.OK
        self.blocks.run(step_rows, active, actions, self._state, self._work, self._cfg, self._out)
        self._steps[active] += 1
        d, xo, _, kc, g, _, cmd, head = self._state
        ok = status == ss.OK
        eff = env.driven.meter.efficiency
        energy = np.where(ok, rep[:, ss.REP_POS] / eff, 0.0)
        advance = (d[:, 0] - before[:, 1]) + (xo - before[:, 0])
        progress = advance / env.params.length
        effort = -env.effort_weight * energy
        reward = progress + effort
        nd = d.shape[1]
        info: dict[str, Any] = {
            "x_head": xo + d[:, nd - 5],
            "x_tail": xo + d[:, 0],
            "centerline": line.copy(),
            "anchor": np.array(["head" if h else "tail" for h in head], dtype=object),
            "kappa_sharp": kc.copy(),
            "kappa_command": cmd.copy(),
            "actuation_power": np.where(ok, rep[:, ss.REP_NET] / env.control_dt, 0.0),
            "actuation_energy": energy,
            "grip": g.copy(),
            "foot_slip": np.where(ok[:, None], rep[:, ss.REP_SLIP : ss.REP_SLIP + 2], 0.0),
            "elastic_energy": energy_el.copy(),
            "newton_iterations": np.where(ok, rep[:, ss.REP_ITER], 0).astype(np.int64),
            "increments": np.where(ok, rep[:, ss.REP_INC], 0).astype(np.int64),
            "time": self._steps * env.control_dt,
            "reward_terms": {"progress": progress, "effort": effort},
        }
        finite = ok & np.isfinite(obs).all(axis=1) & np.isfinite(reward)
        info["numerical_failure"] = ~finite
        for key in list(info):
            info[f"_{key}"] = np.ones(self.num_envs, bool)
        info["reward_terms"].update(_progress=np.ones_like(ok), _effort=np.ones_like(ok))
        obs_out = np.clip(obs, self._lo, self._hi)
        term = ~finite & active
        obs_out[term] = self._obs[term]  # last finite obs, reward 0, terminated
        reward[term] = 0.0
        trunc = self._steps >= env.max_steps
        return obs_out, reward, term, trunc, info
