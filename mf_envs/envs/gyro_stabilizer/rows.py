"""GyroStabilizer-v0's compiled step: the observation kernel `observe` shared by the single env and
the native vector env's rows (`step_rows`, `reset_rows`), so both give the same bits, and the
packing of a `build.Scene` into the ship kernels' parameter vector (`pack`) and irregular-sea
table (`irregular_table`)."""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.envs.gyro_stabilizer import spec
from mf_envs.envs.gyro_stabilizer.build import Scene
from mf_envs.frames.steppers import rk4_work, rkmk4_rwork
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.batch import alloc_batch
from mf_envs.physics.ship.layout import Slot
from mf_envs.physics.ship.model import WaveLoad, pack_params
from mf_envs.physics.ship.seas import (
    G,
    excitation_table,
    jonswap_sea,
    regular_heave_force,
    regular_roll_moment,
    sinc,
)

OBS = spec.OBS
_HIGH = tuple(float(v) for v in OBS.high())  # in the observation's units
_SCALE = tuple(float(v) for v in OBS.scales())
_TWO_PI = 2.0 * math.pi


@kernel
def observe(roll, y, R, out):
    """The observation (OBS order, each value / its field's scale) of ship state y (N_STATE,),
    attitude R (3, 3) and its roll angle (rad) into the float32 row `out`, clipped to the
    bounds; returns False (out untouched)
    if the state is not finite (the failure contract)."""
    for i in range(y.shape[0]):
        if not math.isfinite(y[i]):
            return False
    for i in range(3):
        for j in range(3):
            if not math.isfinite(R[i, j]):
                return False
    v = y[3] + math.pi  # wrapped: v % 2 pi - pi, whose fmod is v itself on [0, 2 pi)
    phi = (v if 0.0 <= v < _TWO_PI else v % _TWO_PI) - math.pi
    vals = (roll, y[0], y[1], y[2], phi, y[4])
    for i in range(6):
        out[i] = min(max(vals[i] / _SCALE[i], -_HIGH[i]), _HIGH[i])
    return True


# info columns written by step_rows / reset_rows: spec.INFO_KEYS up to drive_energy, then the
# two reward terms and the time (named, from the spec's keys)
COLS = spec.INFO_KEYS[: spec.INFO_KEYS.index("drive_energy") + 1]
C_ENERGY = COLS.index("drive_energy")
C_RROLL, C_REFFORT, C_TIME = len(COLS), len(COLS) + 1, len(COLS) + 2
N_COLS = len(COLS) + 3
ROLL0, RATE0, PHASE0 = (-0.05, 0.05), (-0.02, 0.02), (0.0, 2.0 * math.pi)  # reset's U(lo, hi)


@numba.njit(cache=True, inline="always")
def _info_row(c, roll, y, out, energy):
    """Info columns (COLS order) of one row: roll, body rates, gimbal angle/rate, moments,
    drive torque/power, mount moment, rotor power, the step's drive energy (`spec.step_info`)."""
    c[0] = roll
    for j in range(5):
        c[1 + j] = y[j]
    for j in range(K.N_OUT):
        c[6 + j] = out[j]
    c[C_ENERGY] = energy


Rows = namedtuple("Rows", "t y R P tab out u dt n_sub steps last obs cols ok reward")
Rows.__doc__ = """The arrays of N stepped rows (the single env is a batch of one, row 0): t (N,) s;
y (N, N_STATE), R (N, 3, 3), P (N, N_PARAMS), tab (N, L, 2), out (N, N_OUT) as
`physics.ship.batch.alloc_batch`; u (N,) rad/s the precession command; dt (N,) s and n_sub (N,)
int64 each row's physics step and substeps; steps (N,) int64; last (N, 6) float32 the last
returned observations; obs (N, 6) float32 the new ones; cols (N_COLS, N) info columns, reward
terms and time; ok (N,) False on a numerical failure; reward (N,)."""
Task = namedtuple("Task", "roll_scale effort_weight control_dt")
Task.__doc__ = "The reward's scales (`spec.reward_terms`) and the control step (s) of a scene."


def alloc_rows(n: int, table_shape: tuple[int, int], dt: float, n_sub: int) -> Rows:
    """Zeroed `Rows` of n rows (R = identity), each with physics step dt and n_sub substeps."""
    b = alloc_batch(n, K.N_STATE, K.N_PARAMS, table_shape)
    return Rows(
        b["t"], b["y"], b["R"], b["P"], b["tab"], b["out"], np.zeros(n), np.full(n, dt),
        np.full(n, n_sub, dtype=np.int64), np.zeros(n, dtype=np.int64),
        np.zeros((n, OBS.size), dtype=np.float32), np.zeros((n, OBS.size), dtype=np.float32),
        np.zeros((N_COLS, n)), np.ones(n, dtype=bool), np.zeros(n),
    )  # fmt: skip


def info_of(cols: np.ndarray) -> dict:
    """The info dict of info columns (N_COLS,) (floats) or (N_COLS, N) (arrays, copied):
    `spec.INFO_KEYS` up to drive_energy, time and the reward terms."""
    vals = [float(v) for v in cols] if cols.ndim == 1 else list(cols.copy())
    info = dict(zip(COLS, vals))
    info["time"] = vals[C_TIME]
    info["reward_terms"] = {"roll": vals[C_RROLL], "effort": vals[C_REFFORT]}
    return info


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, b, task):
    """One control step of the active rows lo <= i < hi of `Rows` b (GyroStabilizerEnv.step is
    row 0 of a batch of one; the GIL is released, so threads can step disjoint blocks of rows at
    once): advances each row by its command b.u, writes b.obs, b.cols, b.ok (False on a numerical
    failure: the step then scores 0 and keeps the last observation) and b.reward. This task's
    scratch is allocated here; the rows are stepped by `_rows`."""
    work, Rwork = rk4_work(b.y.shape[1]), rkmk4_rwork()
    ob, c = np.empty(b.obs.shape[1], dtype=b.obs.dtype), np.empty(N_COLS)
    _rows(lo, hi, active, b, task, work, Rwork, ob, c)


@kernel
def _rows(lo, hi, active, b, task, work, Rwork, ob, c):
    """The row loop of `step_rows` on the batch arrays in place (a `mf_envs._jit.kernel`: its
    row views cost no reference counts, so threads share the arrays freely): each active row
    by the ship's step (`advance_with`) and `_row_tail`; work, Rwork: the stepper's
    scratch, ob (6,) float32 and c (N_COLS,) one row's observation and info columns."""
    for i in range(lo, hi):
        if not active[i]:
            continue
        e0 = b.y[i, K.E_STATE]
        b.t[i] = K.advance_with(b.t[i], b.y[i], b.R[i], b.u[i], b.dt[i], b.n_sub[i], b.P[i],
                                b.tab[i], b.out[i], work, Rwork)  # fmt: skip
        _row_tail(i, e0, b, task, ob, c)


@kernel(forceinline=True)
def _row_tail(i, e0, b, task, ob, c):
    """Row i after its physics step (drive energy e0 in J before it): its step count,
    observation, reward terms and info columns (`step_rows`)."""
    yi, Ri, oi = b.y[i], b.R[i], b.out[i]
    b.steps[i] += 1
    roll = K.roll_of(Ri)
    ok = observe(roll, yi, Ri, ob)
    if not ok:  # the last finite observation stays (and is scored)
        for k in range(ob.shape[0]):
            ob[k] = b.last[i, k]
    energy = yi[K.E_STATE] - e0
    q = roll / task.roll_scale  # the true roll (float64), whatever the observation shows
    c[C_RROLL], c[C_REFFORT] = -(q * q), -task.effort_weight * energy
    rew = c[C_RROLL] + c[C_REFFORT]
    _info_row(c, roll, yi, oi, energy)
    c[C_TIME] = b.steps[i] * task.control_dt
    b.ok[i] = ok and math.isfinite(rew)
    if not b.ok[i]:  # MFEnv._finish_step: last finite obs, reward 0, terminated
        for k in range(ob.shape[0]):
            ob[k] = b.last[i, k]
        rew = 0.0
    b.reward[i] = rew
    for k in range(ob.shape[0]):
        b.obs[i, k] = ob[k]
    for k in range(c.shape[0]):
        b.cols[k, i] = c[k]


@numba.njit(cache=True)
def reset_row(i, roll, rate, gimbal, b):
    """Row i of `Rows` b at its start (GyroStabilizerEnv.reset, the vector env's `reset_rows`):
    roll angle (rad; R = rot_x(roll)), roll rate (rad/s), gimbal angle (rad), t = 0, the rest of
    y zero; the moments and drive output at t = 0 (out), the observation (b.obs and b.last) and
    the info columns (b.cols[:, i], zero reward terms)."""
    b.y[i, :] = 0.0
    b.y[i, 0] = rate
    b.y[i, 3] = gimbal
    c, s = math.cos(roll), math.sin(roll)
    Ri, yi, oi, Pi = b.R[i], b.y[i], b.out[i], b.P[i]
    Ri[0, 0], Ri[0, 1], Ri[0, 2] = 1.0, 0.0, 0.0
    Ri[1, 0], Ri[1, 1], Ri[1, 2] = 0.0, c, -s
    Ri[2, 0], Ri[2, 1], Ri[2, 2] = 0.0, s, c
    b.t[i], b.steps[i] = 0.0, 0
    oi[0] = 0.0
    oi[1] = K.external_moment(0.0, yi, Ri, Pi, b.tab[i])[3]
    oi[2], oi[3] = K.drive_output(0.0, yi, Ri, 0.0, Pi, math.nan, math.nan)
    oi[4] = K.mount_moment(yi, oi[2], Pi)
    oi[5] = Pi[Slot.PROTOR]
    roll0 = K.roll_of(Ri)
    observe(roll0, yi, Ri, b.obs[i])
    b.last[i, :] = b.obs[i]
    c0 = np.empty(N_COLS)
    _info_row(c0, roll0, yi, oi, 0.0)
    c0[C_RROLL], c0[C_REFFORT], c0[C_TIME] = 0.0, 0.0, 0.0
    b.cols[:, i] = c0


@numba.njit(cache=True)
def reset_rows(idx, draws, ptr, p_sign, b):
    """The vector env's resets (regular seas, no options) of the rows idx from pre-drawn
    doubles: draws (N, 3 K) next_double()s of each row's generator, ptr (N,) the next unused one.
    roll ~ U(ROLL0), roll rate ~ U(RATE0), the wave phase ~ U(PHASE0) into P[WPHASE] (times
    p_sign; 0: the scene has no regular wave), then `reset_row` with the gimbal at 0."""
    for j in range(idx.shape[0]):
        i = idx[j]
        p = ptr[i]
        roll = ROLL0[0] + (ROLL0[1] - ROLL0[0]) * draws[i, p]
        rate = RATE0[0] + (RATE0[1] - RATE0[0]) * draws[i, p + 1]
        phase = PHASE0[0] + (PHASE0[1] - PHASE0[0]) * draws[i, p + 2]
        ptr[i] = p + 3
        if p_sign != 0.0:
            b.P[i, Slot.WPHASE] = phase if p_sign > 0.0 else -phase
        reset_row(i, roll, rate, 0.0, b)


def pack(scene: Scene, phase: float) -> np.ndarray:
    """The packed physics parameters of the scene, its regular wave at `phase` (rad) met at the
    ship's heading and speed (`physics.ship.seas.regular_roll_moment`)."""
    hull = scene.hull
    m0, we = regular_roll_moment(
        scene.wave_moment_amplitude, scene.wave_period, scene.heading, scene.ship_speed, hull.length
    )
    period = 2.0 * math.pi / max(abs(we), 1e-12)
    phase = phase if we >= 0.0 else -phase  # cos(-w t + p) = cos(w t - p)
    k = (2.0 * math.pi / scene.wave_period) ** 2 / G
    gain = float(sinc(0.5 * k * hull.length * math.cos(scene.heading)))  # heave: length mean
    try:
        heave = regular_heave_force(
            scene.wave_moment_amplitude,
            scene.wave_period,
            hull.roll_stiffness,
            hull.heave_stiffness,
            scene.effective_slope,
        )
    except ZeroDivisionError:
        heave = math.inf
    if not math.isfinite(heave * gain):
        raise ValueError(
            "roll_stiffness, wave_period: the wave of this roll moment would have an infinite "
            f"heave force (C44 = {hull.roll_stiffness:g} N m/rad is too small)"
        )
    wave = WaveLoad(m0, period, phase, heave * gain)
    return pack_params(
        scene.ship,
        scene.gyro,
        scene.n_gyros,
        scene.effects,
        scene.drive,
        wave,
        scene.form,
        scene.table_dt,
        hull.gz_cubic,
        scene.coupling,
        scene.ship_speed,
        scene.units,
        scene.rotor_power,
    )


def irregular_table(scene: Scene, rng: np.random.Generator, seconds: float) -> np.ndarray:
    """A new JONSWAP sea (long- or short-crested, `physics.ship.seas`) met at the ship's heading
    and speed, drawn from `rng`: the (N, 2) roll-moment / heave-force table over `seconds`."""
    hull = scene.hull
    sea = jonswap_sea(
        scene.significant_wave_height,
        scene.wave_period,
        scene.heading,
        rng,
        64,
        scene.wave_spreading,
    )
    return excitation_table(
        sea,
        scene.ship_speed,
        hull.roll_stiffness,
        hull.heave_stiffness,
        hull.length,
        hull.beam,
        seconds + 1.0,
        scene.table_dt,
        scene.effective_slope,
    )
