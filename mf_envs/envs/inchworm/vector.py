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

Domain randomisation (`randomize_rows`, `mf_envs.envs._drawn_rows`): each row holds its
compiled configuration (`_cfg_of`: stiffness, weight loads, actuation, the feet's friction
coefficients or the grip law; `_row_held`), its effort weight, its mass per length and its
feet's coefficients (the quasi-static error's), so youngs_modulus, shear_modulus,
mass_per_length and friction_coefficients differ between rows; the randomised rows are stepped
one by one with their own (`DrawnRows._run_rows_of`).
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import numpy as np

from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.inchworm import spec
from mf_envs.envs.inchworm.env import InchwormEnv
from mf_envs.envs.inchworm.rows import step_rows, step_rows_grip
from mf_envs.physics.beam.contact import grip_feet as gf
from mf_envs.physics.beam.contact import stick_slip as ss
from mf_envs.physics.inchworm import quasistatic as qs

CENTERLINE_PER_ELEMENT = 8  # points per element of info["centerline"] (Inchworm.centerline)


class InchwormVectorEnv(BatchedVectorEnv):
    """N independent `Inchworm-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 2 n + 6) float32, actions (N, n [+ 1]) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does with the single env's keys (`spec.INFO_KEYS`)."""

    single_env_cls = InchwormEnv
    row_cost = "heavy"  # ~1 ms per row: one block per CPU from N = 2
    # held per row (its `_cfg_of`, effort weight, mass per length, `_mu_of`): `randomize_rows`
    ROW_KWARGS = frozenset(
        ("youngs_modulus", "shear_modulus", "mass_per_length", "friction_coefficients")
    )

    def _row_held(self, env: Any) -> Any:
        return self._cfg_of(env)

    def _shared(self, env: Any) -> tuple[Any, ...]:
        """The step's template values (`_step_batch`, `_step_grip`, `_finish`; the feet's
        friction is each row's: `_cfg_of`, `_mu_of`)."""
        d = env.driven
        return (*super()._shared(env), env.n_ctrl, env.sma, env.switching, env.params.length,
                d.meter.efficiency, env.scene.ambient, env.sim.model.n_dof)  # fmt: skip

    def _mu_of(self, env: Any) -> np.ndarray:
        """What the quasi-static error reads of the single env `env`'s feet: the Coulomb feet's
        coefficients (4,) (`spec.holding_capacity`), on gripping feet the grip law's
        `kernel_args` (7,) (`spec.grip_capacity`)."""
        if self._grip:
            return env.driven.grip_feet.law.kernel_args()
        return env.driven.feet.params.coefficients

    def _law_rows(self) -> SimpleNamespace:
        """The rows' grip laws as column views (N, 1) of `_mu` (`spec.grip_capacity`; the
        layout of `GripLaw.kernel_args`)."""
        m = self._mu
        names = ("threshold", "width", "mu_slide", "grip_forward", "grip_backward")
        return SimpleNamespace(**{k: m[:, j : j + 1] for j, k in enumerate(names)})

    def _cfg_of(self, env: Any) -> tuple:
        """The compiled configuration of `rows.step_rows` (`step_rows_grip` on gripping feet)
        for the single env `env`."""
        xis = np.linspace(0.0, 1.0, CENTERLINE_PER_ELEMENT + 1)[:-1]
        if not self._grip:
            scales = (env.params.length, env.max_curvature, env.scene.weight)
            return (env.switching, env.max_curvature, env.control_dt, 1,
                    *env.driven.kernel_args(), env.obs_geometry, scales, xis)  # fmt: skip
        sma = env.sma
        scales = (env.params.length, 1.0 if sma else env.max_curvature, env.scene.weight)
        tobs = (0.0, 1.0, 1.0)
        if sma:
            w = env.scene.wires.params
            tobs = (w.ambient, w.alloy.austenite_finish - w.ambient,
                    spec.WIRE_TEMPERATURE_OBS_LIMIT)  # fmt: skip
        return (env.switching, env.max_curvature, env.control_dt, 1,
                *env.driven.grip_kernel_args(), env.obs_geometry, scales, xis, sma,
                tobs)  # fmt: skip

    @classmethod
    def supports(cls, **env_kwargs: Any) -> bool:
        """Only the scenes on friction or gripping feet (the default) are compiled."""
        from mf_envs.effects import resolve_effects
        from mf_envs.envs.inchworm.env import AVAILABLE_EFFECTS, DEFAULT_EFFECTS

        effects = resolve_effects(env_kwargs.get("effects"), AVAILABLE_EFFECTS, DEFAULT_EFFECTS)
        return bool({"friction", "gripping_feet"} & effects)

    def _alloc(self, n: int) -> None:
        env = self.template
        self._grip = "gripping_feet" in env.effects
        if "friction" not in env.effects and not self._grip:
            raise ValueError(
                "effects: the native Inchworm-v0 vector env runs the scenes on friction or "
                f"gripping feet (the compiled quasi-static steps); got {sorted(env.effects)}; "
                "use vectorization_mode='sync' for other scenes"
            )
        self._foot_dx = np.zeros((n, 2))
        self._duty = np.zeros((n, env.n_ctrl))  # the friction scene's (the kernel has none)
        self._effort = np.full(n, env.effort_weight)  # each row's effort weight
        self._mu = np.tile(self._mu_of(env), (n, 1))  # each row's feet (`_mu_of`, `_load`)
        self._law = self._law_rows() if self._grip else None  # views: `_load` updates them
        # each row's mass per length (N, 1), for `spec.quasi_static_error`
        self._qs = SimpleNamespace(mass_per_length=np.full((n, 1), env.params.mass_per_length),
                                   length=env.params.length)  # fmt: skip
        driven, model = env.driven, env.sim.model
        nd, nc, ne = model.n_dof, env.n_ctrl, model.n_elements
        z = np.zeros
        if self._grip:  # feet (N, 4), SMA state (N, 5, n), ..., duty (N, n)
            feet, extra = (z((n, 4)), z((n, 5, nc))), (z((n, nc)),)
            sc, n_rep, n_before = driven.grip_scratch, qs.N_GRIP_REPORT, 3
        else:  # engagement (N, 2), slipping (N, 2)
            feet, extra = (z((n, 2)), z((n, 2), np.int64)), ()
            sc, n_rep, n_before = driven.feet.scratch, ss.N_REPORT, 2
        self._state = (z((n, nd)), z(n), z((n, nc)), z((n, nc)), *feet, z((n, nc)),
                       np.ones(n, bool), *extra)  # fmt: skip
        self._work = tuple(z((n, *a.shape), a.dtype) for a in sc)
        self._cfg = self._cfg_of(env)
        n_pts = CENTERLINE_PER_ELEMENT * ne + 1
        self._out = (
            z(n, np.int64), z((n, n_rep)), z((n, n_before)), z((n, 2 * nc + 6), np.float32),
            z(n), z((n, n_pts, 2)), z((n, ne, 4)),
        )  # fmt: skip
        self._steps = np.zeros(n, np.int64)

    def _load(self, i: int) -> None:
        env = self.template
        sim, driven = env.sim, env.driven
        self._foot_dx[i] = 0.0
        self._effort[i], self._qs.mass_per_length[i] = env.effort_weight, env.params.mass_per_length
        self._mu[i] = self._mu_of(env)
        if self._grip:
            d, xo, lag, kc, ft, sma, cmd, head, duty = self._state
            d[i], xo[i] = sim.state.d, sim.x_origin
            lag[i] = driven.lag.kappa if driven.lag is not None else driven.kappa_ctrl
            kc[i] = driven.kappa_ctrl
            ft[i, :2], ft[i, 2:] = driven.g, driven.v_feet
            sma[i] = driven.sma if driven.sma is not None else 0.0
            cmd[i], head[i], duty[i] = env.kappa_command, sim.anchor == "head", env.duty
            self._steps[i] = 0
            return
        self._duty[i] = env.duty
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
        status, rep = self._out[0], self._out[1]
        status[~active] = ss.OK  # = gf.OK
        d, xo = self._state[0], self._state[1]
        nd = d.shape[1]
        feet_old = np.stack([xo + d[:, 0], xo + d[:, nd - 5]], axis=1)
        kernel = step_rows_grip if self._grip else step_rows
        self._run_rows_of(kernel, 4, active, actions, self._state, self._work, self._cfg,
                          self._out)  # fmt: skip
        self._steps[active] += 1
        ok = status == ss.OK
        if self._grip:
            return self._step_grip(ok, active, feet_old)
        upd = ok & active
        self._duty[upd] = 0.5 * (actions[upd, : env.n_ctrl] + 1.0)
        energy = np.where(ok, rep[:, ss.REP_POS] / env.driven.meter.efficiency, 0.0)
        grip = self._state[4]
        slip = rep[:, ss.REP_SLIP : ss.REP_SLIP + 2]
        info = self._step_info(ok, energy, rep[:, ss.REP_NET], grip, slip, rep[:, ss.REP_ITER],
                               rep[:, ss.REP_INC])  # fmt: skip
        mu4 = self._mu.T[:, :, None]  # (4, N, 1): each row's coefficients
        normal = rep[:, ss.REP_N : ss.REP_N + 2]
        limit = spec.holding_capacity(mu4, grip, rep[:, ss.REP_GX : ss.REP_GX + 2], normal)
        mech = np.where(ok, rep[:, ss.REP_POS], 0.0)
        return self._finish(info, np.zeros(self.num_envs), mech, None, feet_old, limit, ok,
                            active)  # fmt: skip

    def _step_grip(self, ok: np.ndarray, active: np.ndarray, feet_old: np.ndarray) -> tuple:
        """`_step_batch`'s end on gripping feet (`rows.step_rows_grip`)."""
        env, rep = self.template, self._out[1]
        ft, sma = self._state[4], self._state[5]
        if env.sma:
            energy = np.where(ok, rep[:, qs.REP_ELEC], 0.0)
        else:
            energy = np.where(ok, rep[:, qs.REP_A2POS] / env.driven.meter.efficiency, 0.0)
        info = self._step_info(ok, energy, rep[:, qs.REP_A2NET], ft[:, :2],
                               rep[:, gf.REP_SLIP : gf.REP_SLIP + 2], rep[:, gf.REP_ITER],
                               rep[:, qs.REP_SUBSTEPS])  # fmt: skip
        normal = rep[:, gf.REP_N : gf.REP_N + 2]
        limit = spec.grip_capacity(self._law, ft[:, :2], normal)
        temperature = sma[:, 0, :].copy() if env.sma else None
        electrical = energy if env.sma else np.zeros(self.num_envs)
        mechanical = np.where(ok, rep[:, qs.REP_WIRE], 0.0)
        return self._finish(info, electrical, mechanical, temperature, feet_old, limit, ok,
                            active)  # fmt: skip

    def _step_info(self, ok, energy, net, grip, slip, its, incs) -> dict[str, Any]:
        """The info keys both feet share (`spec.INFO_KEYS`; ok (N,) the rows that stepped):
        energy (N,) J the actuation energy, net the actuators' net work [J], grip (N, 2),
        slip (N, 2) m, its and incs the Newton iterations and increments of each row."""
        env = self.template
        d, xo, kc, cmd, head = (self._state[k] for k in (0, 1, 3, 6, 7))
        nd = d.shape[1]
        return {
            "x_head": xo + d[:, nd - 5],
            "x_tail": xo + d[:, 0],
            "centerline": self._out[5].copy(),
            "anchor": np.array(["head" if h else "tail" for h in head], dtype=object),
            "kappa_sharp": kc.copy(),
            "kappa_command": cmd.copy(),
            "actuation_power": np.where(ok, net / env.control_dt, 0.0),
            "actuation_energy": energy,
            "grip": grip.copy(),
            "foot_slip": np.where(ok[:, None], slip, 0.0),
            "elastic_energy": self._out[4].copy(),
            "newton_iterations": np.where(ok, its, 0).astype(np.int64),
            "increments": np.where(ok, incs, 0).astype(np.int64),
            "time": self._steps * env.control_dt,
        }

    def _finish(self, info, electrical, mechanical, temperature, feet_old, limit, ok,
                active) -> tuple[Any, ...]:  # fmt: skip
        """The step's rewards, the SMA robot's info keys (`spec.INFO_KEYS`), the reward terms
        and the failure contract."""
        env, n = self.template, self.num_envs
        d, xo, before = self._state[0], self._state[1], self._out[2]
        advance = (d[:, 0] - before[:, 1]) + (xo - before[:, 0])
        progress = advance / env.params.length
        effort = -self._effort * info["actuation_energy"]
        reward = progress + effort
        info["electrical_energy"] = electrical
        info["mechanical_work"] = mechanical
        if temperature is None:
            temperature = np.full((n, env.n_ctrl), env.scene.ambient)
        info["wire_temperature"] = temperature
        info["duty"] = self._state[8].copy() if self._grip else self._duty.copy()
        feet_new = np.stack([info["x_tail"], info["x_head"]], axis=1)
        dx = np.where(ok[:, None], feet_new - feet_old, 0.0)
        qse = spec.quasi_static_error(dx, self._foot_dx, env.control_dt, self._qs, limit)
        info["quasi_static_error"] = np.where(ok, qse, 0.0)
        self._foot_dx = np.where(active[:, None], dx, self._foot_dx)
        info["reward_terms"] = {"progress": progress, "effort": effort}
        obs = self._out[3]
        finite = ok & np.isfinite(obs).all(axis=1) & np.isfinite(reward)
        return self._close_rows(obs, reward, finite, active, info, env.max_steps)
