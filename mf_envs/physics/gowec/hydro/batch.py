"""Compiled per-step quantities of the floating GOWEC and their batch over rows (GOWEC-v1).

`step_row` is one control step of one buoy: `floating.rk4_steps` (Rios 2017 ch. 3, the Cummins
equation with the gyro's B-matrix coupling, `floating` module doc) plus what the env reports at
the end of the step: PTO powers from the integrated energies, the excitation moment, the gyro's
moment on the hull (`_gyro_pitch`, the compiled twin of `floating.gyro_moment`) and the wave
elevation (Eq. 89 at the origin). The single env (`envs.gowec_v1.rows.step_one`) calls it for
its one row and the native vector env (`envs.gowec_v1.rows.step_rows`) for each of its N rows,
so the two agree bit for bit. Arrays float64, SI units.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.frames.kernels import sincos_near
from mf_envs.physics.gowec.hydro.floating import N_ENERGY, energy_index, mechanics, rk4_steps_into
from mf_envs.physics.gowec.hydro.gimbal import supervise
from mf_envs.physics.gowec.hydro.sea import ramp, sea_inputs

# step_row's value slots (its docstring), by name: the one layout the env and the vector env read
(
    V_POWER, V_POWER_MECH, V_PITCH, V_ROLL, V_PITCH_RATE, V_ROLL_RATE, V_EXCITATION, V_GYRO,
    V_GIMBAL, V_GIMBAL_RATE, V_ELEVATION, V_ENERGY,
) = range(12)  # fmt: skip
N_VALS = 12
# info key -> value slot (buoy_rate is the pair V_PITCH_RATE, V_ROLL_RATE)
INFO_SLOTS = {
    "power": V_POWER, "power_mechanical": V_POWER_MECH, "buoy_pitch": V_PITCH,
    "buoy_roll": V_ROLL, "excitation_moment": V_EXCITATION, "gyro_moment": V_GYRO,
    "gimbal_angle": V_GIMBAL, "gimbal_rate": V_GIMBAL_RATE, "wave_elevation": V_ELEVATION,
}  # fmt: skip
RATES = slice(V_PITCH_RATE, V_ROLL_RATE + 1)


@numba.njit(cache=True)
def elevation(t, amp, om, eps):
    """eta (m) at the origin at time t (s): sum a_i cos(-w_i t + eps_i) (Eq. 89)."""
    eta = 0.0
    for i in range(amp.shape[0]):
        eta += amp[i] * math.cos(-om[i] * t + eps[i])
    return eta


@numba.njit(cache=True)
def step_work(n_state, n_components):
    """`step_row`'s temporaries for a state of n_state and a sea of n_components: the RK4 stage
    slopes and stage state (5, n_state), the end state (n_state,) and the components' phasors
    (4, n_components) (`floating.rk4_steps_into`), as one flat buffer (one array: cheap to pass
    from Python; `step_row` carves it)."""
    return np.zeros(6 * n_state + 4 * n_components)


@kernel(forceinline=True)
def state_values_into(t, y, tau, args, amp, eps, vals, inp, near=None):
    """Slots V_PITCH..V_ELEVATION of `step_row`'s values (its docstring) at (t, y) with the PTO
    command tau: the buoy and gimbal state, the excitation moment, the gyro moment
    (`_gyro_pitch`) and the elevation, for the sea (args, amp, eps) whose loads at t are inp
    (`floating.sea_inputs`); near: the angles of `floating._mass_terms` (None: libm)."""
    vals[V_PITCH], vals[V_ROLL], vals[V_PITCH_RATE], vals[V_ROLL_RATE] = y[0], y[1], y[3], y[4]
    vals[V_EXCITATION] = inp[0]
    vals[V_GYRO] = _gyro_pitch(mechanics(t, y, tau, args, inp, near))
    vals[V_GIMBAL], vals[V_GIMBAL_RATE] = y[2], y[5]
    vals[V_ELEVATION] = elevation(t, amp, args[9], eps) * ramp(t, args[13][1])


@numba.njit(cache=True)
def state_values(t, y, tau, args, amp, eps, vals):
    """`state_values_into` with the sea's loads at t, callable from Python and from the vector
    env's resets (the reset info)."""
    inp = sea_inputs(t, args[9], args[10], args[11], args[12], args[13])
    state_values_into(t, y, tau, args, amp, eps, vals, inp)


@kernel(forceinline=True)
def _gyro_pitch(mech):
    """Moment (N m) of the gyro units on the hull about the pitch axis e1 from
    `floating.mechanics`' result at a state: minus the theta row of the gyro's
    B^T (J B u' + J B' u + w x h) (as `floating.gyro_moment`), i.e. row 0 of the gyro's mass
    matrix (M* less the hull's; its only entry is (0, 0)) times u', plus the gyro's velocity
    terms."""
    ud, m = mech[0], mech[1]
    return -((m[0] - m[11]) * ud[0] + m[7])


@kernel
def step_row(t0, t1, y, tau, clock, args, amp, eps, vals, w):
    """One control step from (t0, y) to t1 = t0 + dtc (s) with the PTO command tau (N m) held
    over n RK4 substeps of dt, clock = (dt, n, dtc, loss) (w = `step_work`; the new state y1 is
    written into its entries 5 n_state..6 n_state, `end_state(w, n_state)`). Returns ok: False
    if y1 is not finite (then `vals` is untouched); else vals (N_VALS,) = (net electrical power
    W, mechanical power W, pitch rad, roll rad, pitch rate rad/s, roll rate rad/s, excitation
    moment N m, gyro moment N m, gimbal angle rad, gimbal rate rad/s, elevation m, net
    electrical energy J), the powers from the integrated PTO energies over dtc, `loss` (W) the
    rotor loss subtracted.
    A `mf_envs._jit.kernel` (no reference counting; it returns no array)."""
    m, nc = y.shape[0], args[9].shape[0]
    work, ph, y1 = step_views(w, m, nc)
    return step_row_into(t0, t1, y, tau, clock, args, amp, eps, vals, work, ph, y1)[0]


@numba.njit(cache=True, inline="always")  # returns views: not a kernel (`mf_envs._jit`)
def step_views(w, m, nc):
    """`step_work` w carved for `step_row_into`: the RK4 scratch (5, m), the phasors (4, nc)
    and the end state (m,) (a row loop carves once: each reshape is a call into numba's C
    helper)."""
    work = w[: 5 * m].reshape((5, m))
    return work, w[6 * m : 6 * m + 4 * nc].reshape((4, nc)), w[5 * m : 6 * m]


@kernel
def step_row_into(t0, t1, y, tau, clock, args, amp, eps, vals, work, ph, y1):
    """`step_row` on the carved buffer (`step_views`), the new state into y1; returns (ok, the
    end state's (rho, cos rho, sin rho, phi, cos phi, sin phi)), the angles' sin/cos near the
    last substep's start (`floating._mass_terms`' near; NaNs if not ok), for the observation."""
    dt, n, dtc, loss = clock
    m = y.shape[0]
    k = energy_index(args)
    for i in range(m):  # element-wise: a slice copy may allocate (no runtime here)
        y1[i] = y[i]
    inp = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # the sea at t1 (below)
    near = (math.nan, math.nan, math.nan, math.nan, math.nan, math.nan)  # the last substep's
    try:  # a zero pivot of the 3 x 3 solve raises ZeroDivisionError (numba's float division)
        inp, near = rk4_steps_into(t0, y1, tau, dt, n, args, work, ph)
    except Exception:  # noqa: BLE001
        y1[0] = np.nan
    nan = math.nan
    for i in range(m):
        if not math.isfinite(y1[i]):
            return False, (nan, nan, nan, nan, nan, nan)
    y1[k + N_ENERGY] = supervise(y1[k + N_ENERGY], y1[0], y1[1], y1[2], dtc, args[8])
    p_el = (y1[k + 4] - y[k + 4]) / dtc - loss
    vals[V_POWER], vals[V_POWER_MECH] = p_el, (y1[k + 3] - y[k + 3]) / dtc
    cr, sr = sincos_near(y1[1], near[0], near[1], near[2])
    cp, sp = sincos_near(y1[2], near[3], near[4], near[5])
    end = (y1[1], cr, sr, y1[2], cp, sp)
    state_values_into(t1, y1, tau, args, amp, eps, vals, inp, end)
    vals[V_ENERGY] = p_el * dtc
    return True, end


@numba.njit(cache=True, inline="always")
def end_state(w, m):
    """The state y1 that `step_row` wrote into its work buffer w, for a state of m entries."""
    return w[5 * m : 6 * m]
