"""FloatingGOWEC-v0 as a native batched vector env: N floating buoys stepped in one compiled call.

`gym.make_vec("FloatingGOWEC-v0", num_envs=N, vectorization_mode="vector_entry_point",
**kwargs)` builds it; `kwargs` are those of `gym.make("FloatingGOWEC-v0", ...)` plus
`autoreset_mode` (default NEXT_STEP).
Trajectories are identical, bit for bit, to `SyncVectorEnv` over N single `GOWECV1Env`s with the
same seeds (`tests/test_vector_envs.py`): seeded resets, resets with options and resets in
irregular seas go through a template single env (its state and sea are copied into the row), the
others are compiled (below); steps through `observe.step_rows`, which calls the single env's own
step kernel (`step_row`) and observation (`observe_one`) for every row. See
`mf_envs.envs._vector`.

Compiled resets (regular seas): `GOWECV1Env.reset()` without options draws two doubles, the wave
phase U(0, 2 pi) and the gimbal angle U(-0.1, 0.1), and the phase enters only the row's sea
(eps and the excitation coefficients). Autoresets and seedless resets without options therefore
skip the template env: the doubles are pre-drawn from each row's generator
(`mf_envs.envs._predraw`), the coefficients come from the single env's own
`floating.excitation_coefficients` (per row, the same arrays), and one numba call (`reset_rows`)
writes the state, the reset infos' values and the observations. Irregular seas (a new sea of
many draws per reset) keep the template path.

Domain randomisation (`randomize_rows`, `mf_envs.envs._drawn_rows`): the rows hold their sea
(components, excitation and drag coefficients) and their reward scale (1 / (P_ref control_dt),
P_ref from the row's wave), so the declared wave_period, peak_period, wave_amplitude and the
choice of significant_wave_height (None: a regular wave of one component; else a JONSWAP sea of
n_components) differ between rows. Rows of fewer components are padded with zero-amplitude
ones (amplitude, frequency, phase and coefficients 0) after their own: every sum over the
components then adds exact zeros after the row's own terms (a sum started at +0.0 is never
-0.0, so x + 0.0 == x bit for bit) and the rows stay bit-identical to the single env
(tests/test_randomize_vector.py).

Measured (N = 1024, random actions every step, autoresets, 2-core machine, medians of five 3 s
runs): 0.41M env-steps/s on one thread, 0.68M on two (runs 0.57-0.74M on this shared
machine). The kernel is `step_row` (a `mf_envs._jit.kernel`, as the row loop) at ~2.2 us per
row: 16 RK4 stages of ~140 ns; most of the rest is the Python around the resets (under random
actions some row resets in three steps of four).
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

from mf_envs.envs._predraw import PredrawnResets
from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gowec_v1 import spec
from mf_envs.envs.gowec_v1.env import GOWECV1Env
from mf_envs.envs.gowec_v1.rows import observe_one, step_rows
from mf_envs.physics.gowec.hydro.batch import (
    INFO_SLOTS,
    N_VALS,
    RATES,
    V_ELEVATION,
    V_ENERGY,
    state_values,
)
from mf_envs.physics.gowec.hydro.sea import (
    N_LOADS,
    drag_velocity_coefficients,
    excitation_coefficients,
    translation_loads,
)

_SCALAR_SLOTS = INFO_SLOTS  # info key -> step_row value slot (physics.gowec.hydro.batch)
_FAILURE_KEYS = ("power", "reward_terms", "overspeed", "stroke_end", "survival",
                 "numerical_failure")  # fmt: skip
PHASE0, GIMBAL0 = (0.0, 2.0 * math.pi), (-0.1, 0.1)  # GOWECV1Env.reset's U(low, high) draws


@numba.njit(cache=True)
def reset_rows(idx, gimbal, Y, steps, shared, tail, sea, vals, view, obs, supervisor):
    """GOWECV1Env.reset() (no options) for the rows idx whose sea = (om, cp, cr, dk, amp, eps)
    is in place (as `rows.step_rows`'): the state at rest with the gimbal angle gimbal[j] (rad)
    and the supervisor's timer at supervisor = (its state index, the timer s), steps = 0, the
    reset info's value slots (`step_row`'s layout, at t = 0 with tau = 0) and the float32
    observations (view = (lo, hi, preview))."""
    om, cp, cr, dk, amp, eps = sea
    lo, hi, preview = view
    sup, timer = supervisor
    for j in range(idx.shape[0]):
        i = idx[j]
        y = Y[i]
        y[:] = 0.0
        y[2] = gimbal[j]
        y[sup] = timer
        steps[i] = 0
        v = vals[i]
        v[:] = 0.0
        state_values(0.0, y, 0.0, (*shared, om[i], cp[i], cr[i], dk[i], *tail), amp[i], eps[i],
                     v)  # fmt: skip
        observe_one(y, 0.0, amp[i], om[i], eps[i], tail[0][1], preview, lo, hi, obs[i],
                    v[V_ELEVATION])  # fmt: skip


class GOWECV1VectorEnv(PredrawnResets, BatchedVectorEnv):
    """N independent `FloatingGOWEC-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 8) float32 (`spec.OBS`), actions (N, 1) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does with the single env's keys (`spec.INFO_KEYS`).
    """

    single_env_cls = GOWECV1Env
    DRAWS_PER_RESET = 2  # wave phase, gimbal angle
    # held per row (the sea's arrays, padded; the reward scale): `randomize_rows`
    ROW_KWARGS = frozenset(
        ("wave_amplitude", "wave_period", "peak_period", "significant_wave_height")
    )

    def _shared(self, env: Any) -> tuple[Any, ...]:
        """The step's template scalars and the model's arrays other than the sea
        (`_step_batch`: `model._args()` but its sea entries 9..12, and the drag geometry
        sp = a[13] through what sets it at `set_sea`)."""
        a, m = env.model._args(), env.model
        return (*super()._shared(env), a[:9], a[14:], m.drag_coefficient, m.sp[1],
                env.wave_direction, env.physics_dt, env.n_substeps, env.max_generator_torque,
                env.rotor_loss_power(), env.preview_times, env.max_gimbal_rate,
                env.gimbal_stroke())  # fmt: skip

    def _alloc(self, n: int) -> None:
        env = self.template
        # the template's sea now, as a reset sets it: the step reads its drag geometry (sp),
        # and under `randomize_rows` the template itself is never reset
        env.model.set_sea(env.wave)
        m = env.n_components if env.irregular else 1
        self.Y = np.zeros((n, env.state.shape[0]))
        self.sea = {key: np.zeros((n, m)) for key in ("om", "amp", "eps")}
        self.sea.update(cp=np.zeros((n, m), complex), cr=np.zeros((n, m), complex))
        self.sea["dk"] = np.zeros((n, m, N_LOADS), complex)  # drag nodes' water, surge, heave
        self._steps = np.zeros(n, dtype=np.int64)
        self._escale = np.full(n, env.energy_scale)  # each row's 1 / (P_ref control_dt)
        self._vals = np.zeros((n, N_VALS))
        self._fresh = np.zeros((n, env.observation_space.shape[0]), dtype=np.float32)
        self._ok = np.ones(n, dtype=bool)
        self._lo = self.single_observation_space.low.astype(np.float32)
        self._hi = self.single_observation_space.high.astype(np.float32)
        self._predraw_alloc(n, not env.irregular)
        if not env.irregular:  # the hull's excitation at the regular wave's frequency
            self._X = env.model.wave_excitation(env.wave.omegas, env.wave.direction)

    def _load(self, i: int) -> None:
        env, sea = self.template, self.sea
        self.Y[i] = env.state
        m = env.model
        row = (m._om, env.wave.amplitudes, env.wave.phases, m._cp, m._cr, m._dk)
        k = m._om.shape[0]
        if k > sea["om"].shape[1]:  # a randomised row's larger sea: every row padded to it
            for key in sea:
                wide = np.zeros((self.num_envs, k, *sea[key].shape[2:]), sea[key].dtype)
                wide[:, : sea[key].shape[1]] = sea[key]
                sea[key] = wide
        for key, value in zip(("om", "amp", "eps", "cp", "cr", "dk"), row):
            sea[key][i] = 0.0  # zero-amplitude components after the row's own (module doc)
            sea[key][i, :k] = value
        self._escale[i] = env.energy_scale
        self._steps[i] = 0

    def _state_arrays(self) -> dict[str, np.ndarray]:
        """The rows' arrays a step reads or writes (`snapshot`): state, sea, counters."""
        arrays = {f"sea_{k}": a for k, a in self.sea.items()}
        arrays.update(Y=self.Y, steps=self._steps, escale=self._escale, vals=self._vals,
                      fresh=self._fresh, ok=self._ok)  # fmt: skip
        return arrays

    def _load_live(self, i: int, env: Any) -> None:
        """`_load`, the episode's step count (the sea's clock is steps x control_dt) and the
        env's flywheel speed and linear PTO gains (`GOWECV1Env.set_rotor_speed`, `set_pto`;
        the template's, shared by all rows)."""
        super()._load_live(i, env)
        self._steps[i] = env._steps
        if env.model.psid != self.template.model.psid:
            self.template.set_rotor_speed(env.model.psid)
        pto = env.model.p.pto
        if (pto[0], pto[1]) != tuple(self.template.model.p.pto[:2]):
            self.template.set_pto(float(pto[0]), float(pto[1]))

    def _batch_reset(self, idx: np.ndarray) -> dict[str, Any] | None:
        env, sea, draws, ptr = self.template, self.sea, self._draws, self._ptr
        if sea["om"].shape[1] != env.wave.omegas.shape[0] or not self._predrawn(idx):
            return None  # (padded seas, after randomised rows: the template path)
        gimbal = np.empty(idx.shape[0])
        for j, i in enumerate(idx.tolist()):
            p = int(ptr[i])
            phase = PHASE0[0] + (PHASE0[1] - PHASE0[0]) * float(draws[i, p])
            gimbal[j] = GIMBAL0[0] + (GIMBAL0[1] - GIMBAL0[0]) * float(draws[i, p + 1])
            ptr[i] = p + 2
            eps = np.array([phase])  # as waves.regular_wave and model.set_sea
            sea["cp"][i], sea["cr"][i] = excitation_coefficients(
                self._X, env.wave.amplitudes, eps, env.wave.direction
            )
            sea["eps"][i] = eps
            dk = drag_velocity_coefficients(
                env.model.sp, env.hull, sea["om"][i], env.wave.amplitudes, eps
            )
            if env.model.translating:
                translation_loads(dk, env.model.three, sea["om"][i], env.wave.amplitudes, eps)
            sea["dk"][i] = dk
        a = env.model._args()
        supervisor = (env.model.survival_index(), env.survival_at_reset())
        reset_rows(
            idx, gimbal, self.Y, self._steps, a[:9], a[13:], self._sea_rows(), self._vals,
            (self._lo, self._hi, env.preview_times), self._obs, supervisor,
        )  # fmt: skip
        return self._reset_infos(idx)

    def _sea_rows(self) -> tuple:
        """The rows' sea as the kernels take it (`rows.step_rows`): (om, cp, cr, dk, amp, eps)."""
        return tuple(self.sea[k] for k in ("om", "cp", "cr", "dk", "amp", "eps"))

    def _reset_infos(self, idx: np.ndarray) -> dict[str, Any]:
        """The batched reset infos of rows idx (GOWECV1Env.reset's keys, dtypes and values)."""
        n = self.num_envs
        mask = np.zeros(n, dtype=bool)
        mask[idx] = True
        v = np.zeros((n, N_VALS))
        v[idx] = self._vals[idx]
        info: dict[str, Any] = {key: v[:, j].copy() for key, j in _SCALAR_SLOTS.items()}
        info["buoy_rate"] = v[:, RATES].copy()
        info["time"] = np.zeros(n)
        info["numerical_failure"] = np.zeros(n, dtype=bool)
        info["reward_terms"] = {"net_electrical_energy": np.zeros(n), "_net_electrical_energy":
                                mask.copy(), "shutdown_loss": np.zeros(n),
                                "_shutdown_loss": mask.copy()}  # fmt: skip
        info["overspeed"], info["stroke_end"] = np.zeros(n, bool), np.zeros(n, bool)
        info["survival"] = self.Y[:, self.template.model.survival_index()] > 0.0
        for key in list(info):
            if not key.startswith("_"):
                info[f"_{key}"] = mask.copy()
        return info

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics, sea, counters, values, observations,
        pre-drawn resets)."""
        arrays = [self.Y, *self.sea.values(), self._steps, self._vals, self._fresh, self._obs]
        return int(sum(a.nbytes for a in arrays)) + self._ok.nbytes + self._draws.nbytes

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        env, dtc = self.template, self.template.control_dt
        tau = actions[:, 0] * env.max_generator_torque
        t0 = self._steps * dtc
        self._steps[active] += 1
        t1 = self._steps * dtc
        ok = self._ok
        ok[~active] = True
        a = env.model._args()
        shared = a[:9]
        obs = self._fresh
        clock = (env.physics_dt, env.n_substeps, dtc, env.rotor_loss_power())
        self.blocks.run(
            step_rows, active, t0, t1, self.Y, tau, clock, shared, a[13:], self._sea_rows(),
            (self._vals, ok, obs), (self._lo, self._hi, env.preview_times),
        )  # fmt: skip
        v, Y = self._vals, self.Y
        reward = v[:, V_ENERGY] * self._escale
        vt = v.T.copy()  # one copy; the info columns are its rows (fresh every step)
        info: dict[str, Any] = {key: vt[j] for key, j in _SCALAR_SLOTS.items()}
        info["buoy_rate"] = v[:, RATES].copy()
        info["time"] = t1.copy()
        over = np.abs(Y[:, 5]) > env.max_gimbal_rate
        out = np.abs(Y[:, 2]) > env.gimbal_stroke()
        shut = np.where(over | out, -env.shutdown_energy(self._steps) * self._escale, 0.0)
        info["reward_terms"] = {"net_electrical_energy": reward.copy(), "shutdown_loss": shut}
        reward = reward + shut
        info["overspeed"], info["stroke_end"] = over, out
        info["survival"] = Y[:, env.model.survival_index()] > 0.0
        finite = ok & np.isfinite(reward)  # MFEnv._finish_step: finite obs and reward
        info["numerical_failure"] = ~finite
        masks = np.ones((len(spec.INFO_KEYS) + 1, self.num_envs), dtype=bool)
        info["reward_terms"]["_net_electrical_energy"] = masks[-1]
        info["reward_terms"]["_shutdown_loss"] = masks[-1]
        for j, key in enumerate(spec.INFO_KEYS):
            info[f"_{key}"] = masks[j]
        term = over | out
        bad = ~finite & active
        if bad.any():  # last finite obs, reward 0, terminated
            obs[bad] = self._obs[bad]
            reward[bad], term[bad] = 0.0, True
            gone = ~ok & active  # the physics failed: only the failure keys, zeroed
            info["power"][gone], info["reward_terms"]["net_electrical_energy"][gone] = 0.0, 0.0
            info["reward_terms"]["shutdown_loss"][gone] = 0.0
            over[gone], out[gone], info["survival"][gone] = False, False, False
            for key in set(spec.INFO_KEYS) - set(_FAILURE_KEYS):
                info[f"_{key}"][gone] = False
        return obs, reward, term, self._steps >= env.max_steps, info
