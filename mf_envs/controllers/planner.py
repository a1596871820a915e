"""Sampling planners on the native vector env's rows: the oracle and the causal MPC references.

A `SamplingPlanner` controls ONE env (made with `gym.make`) and plans on K rows of that env's
native vector env (`gym.make_vec(..., vectorization_mode="vector_entry_point")`, the same
kwargs): every `replan` control steps it copies the env's current state into the K rows
(`BatchedVectorEnv.load_env`: physics state, step count and the episode's sea), rolls K
candidate action sequences of `horizon` control steps forward, scores each by the sum of the
env's own reward over the horizon, and applies the best sequence's first `replan` actions.
Search: the cross-entropy method (Rubinstein 1999; as in PETS, Chua et al. 2018): `iterations`
rounds of K Gaussian sequences (clipped to [-1, 1]) around a mean, refitted to the best
`elite` fraction; row 0 is always the mean itself (so K = 1 plays the mean: the warm start, or
`init` at the first step); the mean is warm-started from the last plan shifted by the steps
played, its last action repeated, or with a guiding baseline (`base`) from that baseline's
own continuation, the shifted last plan then being candidate 1. Rollouts stop at the episode's
end (no autoreset enters a score) and a row that fails numerically scores -inf.

What it knows (`causal`):
- oracle (`causal=False`): the episode's whole sea, because each env's sea is a deterministic
  function of its reset seed and `load_env` copies the realisation: the rows' future is the
  env's future exactly (a perfect model, no noise), so the planned return is the one played.
  Not a controller a device could run: it reads the env's state, not the observation.
- causal MPC (`causal=True`): the same rows, but their future sea is replaced at each replan
  by a forecast (`causal_forecast_stabilizer` below: the excitation met up to now, a linear
  autoregressive predictor beyond it; `causal_forecast_floating`: the elevation at the hull
  met up to now and its AR continuation, fitted as a sea): it still reads the env's physical
  state (a perfect state estimate) and the sea's past, but not the sea ahead.

Hand-written (CEM is ten lines; no maintained library plans on an external batched simulator
without a copy of its model), on the env's own kernels: one source of the dynamics.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.envs._rows import SINGLE


class SamplingPlanner:
    """CEM planner over the vector rows of `env`'s id (module doc).

    horizon H (knots of `hold` control steps each: a sequence is H actions, each held `hold`
    steps), samples K (rows), iterations (CEM rounds per replan), elite (fraction refitted),
    replan (knots played per plan, at most H), std (initial sampling std of
    an action in [-1, 1]), init (the first plan's constant action), seed (the sampler's
    generator), causal (module doc), num_threads (the vector env's row blocks), base (a
    baseline kind that guides the search: at each replan a copy of it, in its live state, is
    rolled over the horizon on one more row, and its actions (at each knot's start) are the
    CEM's initial mean and candidate 0, so the plan is never worse than the baseline over
    the horizon; a baseline acting through the drive's settings, as FloatingGOWEC's
    `efficient_pto` (its linear PTO, which `load_env` copies into the rows), guides with its
    zero torque and keeps its drive law under the planner's torque).
    """

    def __init__(
        self,
        env: Any,
        horizon: int = 30,
        samples: int = 128,
        iterations: int = 3,
        elite: float = 0.125,
        replan: int = 2,
        hold: int = 1,
        std: float = 0.5,
        init: float = 0.0,
        seed: int = 0,
        causal: bool = False,
        num_threads: int | None = 1,
        base: str | None = None,
    ) -> None:
        import gymnasium as gym

        from mf_envs._validate import check_int, check_range

        self.env, self._wrapped = env.unwrapped, env
        spec = env.spec if env.spec is not None else self.env.spec
        self.h = check_int("horizon", horizon, 1)
        self.k = check_int("samples", samples, 1)
        self.iterations = check_int("iterations", iterations, 1)
        self.hold = check_int("hold", hold, 1)
        self.replan = min(check_int("replan", replan, 1), self.h)
        self.elite = max(1, round(check_range("elite", elite, 0.0, 1.0) * self.k))
        self.std0 = check_range("std", std, 0.0, 2.0)
        self.init = check_range("init", init, -1.0, 1.0)
        self.seed, self.causal = int(seed), bool(causal)
        kwargs = {k: v for k, v in spec.kwargs.items() if k != "render_mode"}
        self.vec = gym.make_vec(spec.id, num_envs=self.k, vectorization_mode="vector_entry_point",
                                num_threads=num_threads, **kwargs).unwrapped  # fmt: skip
        self.vec.reset(seed=0)
        self.dim = self.env.action_space.shape[0]
        self.forecast = _forecast_of(self.env) if self.causal else None
        self.base = self.guide_env = None
        if base is not None:
            from mf_envs.controllers import make_baseline

            self.base = make_baseline(env, base)
            self.guide_env = gym.make_vec(spec.id, num_envs=1, num_threads=1,
                                          vectorization_mode="vector_entry_point",
                                          **kwargs).unwrapped  # fmt: skip
            self.guide_env.reset(seed=0)
        self.reset()

    def reset(self) -> None:
        if self.base is not None and self.env._last_obs is not None:  # after the env's reset
            self.base.reset()
        self.rng = np.random.default_rng(self.seed)
        self.mean = np.full((self.h, self.dim), self.init)
        self.queue: list[np.ndarray] = []
        self.planned = np.nan  # the last plan's predicted return

    def predict(self, obs: Any, deterministic: bool = True) -> tuple[np.ndarray, None]:
        if not self.queue:
            plan = self._plan()
            self.queue = list(np.repeat(plan[: self.replan], self.hold, axis=0))
            self.mean = np.concatenate([plan[self.replan :],
                                        np.repeat(plan[-1:], self.replan, axis=0)])  # fmt: skip
        if self.base is not None:  # the baseline's state follows the episode (after the plan)
            self.base.predict(obs)
        return self.queue.pop(0).astype(np.float32), None

    def _plan(self) -> np.ndarray:
        """CEM from the env's current state: the best sequence found (H, dim)."""
        left = self.env.max_steps - self._steps()
        h = max(1, min(self.h, -(-left // self.hold)))
        vec = self.vec
        vec.load_env(self.env)
        if self.forecast is not None:
            self.forecast(vec, self.env, h * self.hold)
        start = vec.snapshot()
        mean, std = self.mean[:h].copy(), np.full((h, self.dim), self.std0)
        warm = mean.copy()  # the last plan, shifted: candidate 1 of the first round
        if self.base is not None:
            mean = self._guide(h)
        best, best_ret = mean.copy(), -np.inf
        for it in range(self.iterations):
            noise = self.rng.standard_normal((self.k, h, self.dim))
            seqs = np.clip(mean[None] + std[None] * noise, -1.0, 1.0)
            seqs[0] = np.clip(mean, -1.0, 1.0)
            if it == 0 and self.base is not None and self.k > 1:
                seqs[1] = np.clip(warm, -1.0, 1.0)
            seqs = seqs.astype(np.float32).astype(np.float64)  # the env's float32 actions
            if it:
                vec.restore(start)
            ret = self._returns(seqs)
            order = np.argsort(-ret, kind="stable")
            if ret[order[0]] > best_ret:
                best, best_ret = seqs[order[0]].copy(), float(ret[order[0]])
            top = seqs[order[: self.elite]]
            mean, std = top.mean(axis=0), top.std(axis=0)
        self.planned = best_ret
        if h < self.h:  # the episode's last steps: pad (never played)
            best = np.concatenate([best, np.repeat(best[-1:], self.h - h, axis=0)])
        return best

    def _guide(self, h: int) -> np.ndarray:
        """The baseline's actions (h, dim) over the next h knots from the env's state: a copy of
        it (the env itself not copied) closing its loop on the guide row."""
        import copy

        env, row = self.env, self.guide_env
        keep = (env, self._wrapped, self.vec, row)
        guide = copy.deepcopy(self.base, {id(x): x for x in keep})
        row.load_env(env)
        if self.forecast is not None:  # the causal planner's guide sees the forecast sea too
            self.forecast(row, env, h * self.hold)
        obs = env._last_obs
        out = np.zeros((h, self.dim))
        for j in range(h * self.hold):
            a = np.asarray(guide.predict(obs)[0], dtype=np.float64).reshape(self.dim)
            if j % self.hold == 0:
                out[j // self.hold] = a
            obs, _, term, trunc, _ = row.step(a[None])
            obs = obs[SINGLE]  # the guide's one row
            if term[0] or trunc[0]:
                out[j // self.hold + 1 :] = a
                break
        return out

    def _returns(self, seqs: np.ndarray) -> np.ndarray:
        """Sum of each row's rewards over its sequence (K, h, dim), each action held `hold`
        steps; -inf after a failure."""
        total = np.zeros(self.k)
        alive = np.ones(self.k, dtype=bool)
        for j in range(seqs.shape[1] * self.hold):
            _, r, term, trunc, info = self.vec.step(seqs[:, j // self.hold])
            total += np.where(alive, r, 0.0)
            failed = info.get("numerical_failure", np.zeros(self.k, bool)) & alive
            total[failed] = -np.inf
            alive &= ~(term | trunc)
        return total

    def _steps(self) -> int:
        env = self.env
        return int(env.rows.steps[0]) if hasattr(env, "rows") else int(env._steps)


def _forecast_of(env: Any) -> Any:
    """The causal forecast of the env's module (module doc); ValueError if it has none."""
    from mf_envs.envs.gowec_v1.env import GOWECV1Env
    from mf_envs.envs.gyro_stabilizer.env import GyroStabilizerEnv

    if isinstance(env, GyroStabilizerEnv) and "irregular_waves" in env.effects:
        return causal_forecast_stabilizer
    if isinstance(env, GOWECV1Env) and env.irregular:
        return causal_forecast_floating
    raise ValueError(f"causal: no forecast for {type(env).__name__} in this sea")


# the stabilizer's wave-moment forecast (`causal_forecast_stabilizer`)
AR_DT = 0.2  # s: the predictor's sampling (the sea's peak periods are 3-6 s)
AR_ORDER = 16  # past samples per prediction (3.2 s)
AR_MEMORY = 60.0  # s of past the predictor is fitted on, at each replan
FIT_RIDGE = 1e-3  # the floating forecast's harmonic fit: ridge / mean diagonal of A^T A


def ar_forecast(past: np.ndarray, steps: int, order: int = AR_ORDER) -> np.ndarray:
    """The next `steps` values of the series `past` (n,) by a linear autoregressive predictor of
    `order` fitted by least squares on `past` itself, applied recursively (Fusco & Ringwood
    2010); zeros while the past holds fewer than 3 x order samples."""
    if past.shape[0] < 3 * order:
        return np.zeros(steps)
    X = np.lib.stride_tricks.sliding_window_view(past[:-1], order)
    coef = np.linalg.lstsq(X, past[order:], rcond=None)[0]
    hist = np.concatenate([past[-order:], np.zeros(steps)])
    for j in range(steps):
        hist[order + j] = hist[j : order + j] @ coef
    return hist[order:]


def causal_forecast_stabilizer(vec: Any, env: Any, horizon: int) -> None:
    """GyroStabilizer-v0 in irregular seas: in every row's wave table (roll moment and heave
    force, one sample per `table_dt`), the samples after now are replaced, over the planning
    horizon and one AR_DT beyond it, by `ar_forecast` of each column sampled every AR_DT over
    the last AR_MEMORY seconds up to now: the planner knows the excitation met so far (a
    perfect wave-load estimator) and forecasts the rest. The rows' rollouts never read past
    the forecast window (they stop after `horizon` control steps)."""
    h = env.scene.table_dt
    tab = env.rows.tab[0]
    now = int(env.rows.steps[0]) * env.control_dt
    i_now = int(np.floor(now / h + 1e-9))
    d = max(1, round(AR_DT / h))
    span = int(np.ceil(horizon * env.control_dt / (d * h))) + 1  # forecast samples
    past_idx = np.arange(i_now, max(-1, i_now - round(AR_MEMORY / h)), -d)[::-1]
    fine = np.arange(i_now + 1, min(i_now + d * span + 1, tab.shape[0]))
    if fine.size == 0:
        return
    coarse = i_now + d * np.arange(0, span + 1)
    for col in range(tab.shape[1]):
        past = tab[past_idx, col]
        ahead = np.concatenate([[tab[i_now, col]], ar_forecast(past, span)])
        vec.b.tab[:, fine, col] = np.interp(fine, coarse, ahead)


def causal_forecast_floating(vec: Any, env: Any, horizon: int) -> None:
    """FloatingGOWEC-v0 in irregular seas: every row's sea is replaced by a sea fitted to the
    elevation at the hull, measured up to now and forecast beyond it. The elevation of the last
    AR_MEMORY seconds (sampled every AR_DT, divided by the start-up ramp where it is above 1/2)
    is extended over the planning horizon by `ar_forecast`; the record and its forecast are
    then fitted, by least squares with a small ridge, by a sum of harmonics of the predictor's
    own frequencies (as many as the env's components, at the centres of equal bins over
    [0.3, 3] x the sea's peak frequency: the operator knows the sea state, not the realisation's
    frequencies), and the hull's excitation, drag and translation loads of that sea
    (`FloatingModel.set_sea` on a copy of the env's model) go into every row. The rows' rollouts
    never read past the forecast window."""
    import copy

    from mf_envs.physics.gowec.hydro.sea import ramp
    from mf_envs.physics.waves import WaveField, wavenumber

    wave, dt = env.wave, env.control_dt
    now = env._steps * dt
    t = now - AR_DT * np.arange(round(AR_MEMORY / AR_DT), -1, -1)
    t = t[t >= 0.0]
    tramp = float(env.model.sp[1])
    t = t[np.array([ramp(x, tramp) > 0.5 for x in t], dtype=bool)]
    eta = wave.elevation(t)  # the probe's record (elevation x ramp) / ramp
    n_ahead = int(np.ceil(horizon * dt / AR_DT)) + 1
    ahead = ar_forecast(eta, n_ahead)
    t_all = np.concatenate([t, now + AR_DT * np.arange(1, n_ahead + 1)])
    e_all = np.concatenate([eta, ahead])
    m = wave.omegas.shape[0]
    wp = 2.0 * math.pi / float(env.wave_period)
    edges = np.linspace(0.3 * wp, 3.0 * wp, m + 1)
    om = 0.5 * (edges[1:] + edges[:-1])
    A = np.concatenate([np.cos(np.outer(t_all, om)), np.sin(np.outer(t_all, om))], axis=1)
    AtA = A.T @ A  # t_all holds the forecast's n_ahead >= 2 samples at least
    x = np.linalg.solve(AtA + FIT_RIDGE * np.trace(AtA) / AtA.shape[0] * np.eye(2 * m),
                        A.T @ e_all)  # fmt: skip
    # a cos(-w t + eps) = a cos(eps) cos(w t) + a sin(eps) sin(w t)
    amp, eps = np.hypot(x[:m], x[m:]), np.arctan2(x[m:], x[:m])
    three = env.model.three
    depth = float(three.water_depth) if three is not None else math.inf
    fit = WaveField(amp, om, eps, wavenumber(om, depth), wave.direction, wave.buoy_radius)
    model = getattr(vec, "_forecast_model", None)
    if model is None:
        model = vec._forecast_model = copy.deepcopy(env.model)
    model.set_sea(fit)
    row = (om, amp, eps, model._cp, model._cr, model._dk)
    for key, value in zip(("om", "amp", "eps", "cp", "cr", "dk"), row):
        vec.sea[key][:] = 0.0
        vec.sea[key][:, :m] = value
