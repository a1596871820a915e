"""The SMA inchworm on gripping feet with inertia: the energy-momentum beam of
`mf_envs.physics.beam.dynamics` with the feet's regularised friction as a velocity-dependent load,
to measure what the quasi-static model (`quasistatic.grip_step`, the env's) leaves out.

The feet's z stay on the ground (prescribed, Eq. 100a); their x are free and loaded by the law of
`grip_feet.foot_force` at their velocity v (the same law as the quasi-static increments, where
v = u / h): F(v) = -N [mu_s v / sqrt(v^2 + v_s^2) + phi(g) (mu_grip(s) - mu_s) v / sqrt(v^2 +
v_g^2)], its derivative dF/dv entering the tangent through the scheme's velocity coefficient. The
normal load N of each foot is held at half the body's weight (the quasi-static normal loads of
the symmetric gaits are that to 1e-6). The wires (`quasistatic.sma_advance`) and the feet's
engagement (`friction.grip_response`) are advanced exactly as in the quasi-static step, per time
step of the beam. Python-level (the general `dynamics.time_step`), for comparisons, not in the
env (`gripping_feet` excludes `inertia`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from mf_envs._validate import check_positive
from mf_envs.physics.beam import BeamModel, NewmarkState
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.contact.friction import grip_response
from mf_envs.physics.beam.contact.grip_feet import foot_force
from mf_envs.physics.beam.dynamics import TimeScheme, initial_acceleration, time_step
from mf_envs.physics.inchworm import quasistatic as qs
from mf_envs.physics.inchworm.drive import GRIP_COMMANDS, DrivenInchworm


def run_dynamic(
    driven: DrivenInchworm,
    duty: Callable[[float], np.ndarray],
    dt: float,
    n_steps: int,
    n_sub: int = 10,
    t0: float = 0.0,
    mass_scale: float = 1.0,
) -> np.ndarray:
    """Drive `driven` (an SMA robot on gripping feet, its quasi-static state the start, at rest)
    with duty(t) (n,) held over control steps of dt [s], the head gripping while the wires are
    heated at duty 1 and the tail otherwise (as `open_loop.run_duty_loop`), through n_steps control
    steps of n_sub energy-momentum steps each (`dynamics.time_step`, rho_inf 0.8). t0 [s]: the
    time of the start in the gait (duty is evaluated at t0 + (k + 1) dt). mass_scale scales the
    inertia only (not the weight): 1e-3 gives the quasi-static limit of the same time
    discretisation of the friction law, which isolates the inertia's effect. The driven robot's
    wires, engagement and state are advanced. Returns the feet's x (n_steps + 1, 2) [m] (tail,
    head) at the control steps."""
    sim, wires, gf = driven.sim, driven.wires, driven.grip_feet
    if wires is None or gf is None:
        raise ValueError("driven: needs sma_wires and gripping_feet")
    p = sim.params
    check_positive("mass_scale", mass_scale)
    bp = sim.model.params
    model = BeamModel(replace(bp, mass_per_length=bp.mass_per_length * mass_scale,
                              rotary_inertia=bp.rotary_inertia * mass_scale))  # fmt: skip
    law = gf.law.kernel_args()
    thermal, tt, p_full, k_full, _group = wires.kernel_args()
    xd, zd = driven.foot_x, driven.foot_z
    nd = model.n_dof
    fixed = np.zeros(nd, bool)
    fixed[zd] = True
    normal = 0.5 * p.mass_per_length * p.gravity * p.length
    h = dt / n_sub
    kappa0 = driven._gauss(driven.kappa_ctrl)  # noqa: SLF001 - same package
    d = sim.state.d.copy()
    st = NewmarkState(d, np.zeros(nd), initial_acceleration(model, d, kappa0, sim.f_ext, fixed),
                      sim.state.t)  # fmt: skip
    scheme = TimeScheme("energy_momentum", 0.8)
    g = driven.g.copy()
    feet = np.empty((n_steps + 1, 2))
    feet[0] = sim.x_origin + d[xd]
    ab_v = np.zeros((el.N_BAND, nd))

    def extra(_d, v):
        fx = np.zeros(nd)
        ab_v[:] = 0.0
        for k in range(2):
            f, dfdv = foot_force(float(v[xd[k]]), 1.0, float(g[k]), normal, law)
            fx[xd[k]] = f
            ab_v[el.HALF_BW, xd[k]] = dfdv
        return fx, None, ab_v

    kappa_ctrl = driven.kappa_ctrl.copy()
    g_next, k_next = np.empty(2), np.empty(len(kappa_ctrl))
    for k in range(n_steps):
        u = np.asarray(duty(t0 + (k + 1) * dt), float)
        command = np.array(GRIP_COMMANDS["head" if u[0] == 1.0 else "tail"], float)
        for _j in range(n_sub):
            qs.sma_advance(driven.sma, u, h, thermal, tt, p_full, k_full, k_next)
            grip_response(g, command, h, gf.engage_time, gf.release_time, g_next)
            g[:] = g_next
            k_start, k_end = driven._gauss(kappa_ctrl), driven._gauss(k_next)  # noqa: SLF001
            st = time_step(model, st, h, k_end, sim.f_ext, fixed, sim.settings, extra, k_start,
                           scheme=scheme)  # fmt: skip
            kappa_ctrl = k_next.copy()
        feet[k + 1] = sim.x_origin + st.d[xd]
    driven.kappa_ctrl, driven.g = kappa_ctrl, g.copy()
    sim.state = NewmarkState(st.d, np.zeros(nd), np.zeros(nd), st.t)
    sim.kappa = driven._gauss(kappa_ctrl)  # noqa: SLF001
    return feet
