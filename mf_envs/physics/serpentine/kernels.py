"""Compiled time loop of the serpentine beam: the energy-momentum step of `beam.dynamics` (Simo &
Tarnow 1992; `beam.algorithmic`) with the ground as a configuration- and velocity-dependent
distributed load, solved by Newton with its consistent tangent.

Unknown d = d_{n+1}; v_{n+1} = 2 (d - d_n) / dt - v_n (trapezoidal kinematics). Residual

    R(d) = (2 / dt^2) M (d - d_n - dt v_n) + Pbar(d_n, d) - F_g(d_th, v_th),
    d_th = d_n + th (d - d_n),  v_th = (1 - th) v_n + th v_{n+1},

tangent dR/dd = (2 / dt^2) M + dPbar/dd - th dF_g/dd - (2 th / dt) dF_g/dv. Pbar (the
algorithmic internal force, active curvature kappa# at t_n and t_{n+1}) makes the step conserve
linear and angular momentum and, with F_g = 0 and a constant kappa#, the energy (to the Newton
tolerance). The ground force is evaluated at th in [1/2, 1]:

* th = 1 (default): the ground force at the end of the step. Regularised Coulomb friction is
  stiff in the slip speed (df/dv ~ mu p / v_eps, a relaxation time v_eps / (mu g) ~ 1e-4 s
  with v_eps = 0.1 mm/s), far below any useful step; implicit Euler on it is L-stable, so a
  body that stops slipping stops (no velocity chatter), at a first-order error in a bounded
  force.
* th = 1/2: the midpoint. The ground's discrete work is dt F_g(v_mid) . v_mid <= 0, an exact
  discrete energy balance, but v_{n+1} = 2 v_mid - v_n rings (sign flips) while a point sticks.

Kelvin-Voigt body (`damping` = the retardation time tau [s]): every stress gains the rate term
of a viscoelastic solid, sigma = D (eps - eps# + tau d eps / dt), discretised as the step's
mean strain rate: sigma = D (eps_mid + tau (eps_b - eps_a) / dt) with eps_mid the scheme's
midpoint elastic strain. That is `beam.algorithmic`'s theta-stress at theta = 1/2 + tau / dt,
plus a strain shift that takes the actuation's own rate out of the damper (it acts on the total
curvature rate, in parallel with the active spring: a snapping command is slowed, not
amplified). The step then dissipates exactly (tau / dt) int deps^T D deps dS >= 0 and still
conserves linear momentum; the muscles' work is against the elastic moment only
(`muscle_work`). tau = 0 is the conserving scheme.

Predictor: the constant-velocity d_n + dt v_n, or the start configuration d_n if its residual
(2-norm of R scaled by the dof scales) is below PREDICTOR_RATIO = 0.2 times the former's; the
chosen one's residual and tangent are the first iteration's. The candidate the last step chose
(a hint in the scratch) is formed first with its tangent, the other's residual alone, and its
tangent only if it is chosen after all: the choice costs a residual (the same bits as forming
both in full: the hint orders the work, no result depends on it).
Under smooth motion (a gait) the constant-velocity start is right; after a command's jump the
trapezoidal velocity's stiff components (axial, shear, high bending modes) alternate in sign
from step to step (v_{n+1} = 2 (d_{n+1} - d_n) / dt - v_n), so v_n extrapolates them the wrong
way and d_n is the better start. Measured over 200 control steps of Serpentine-v0's random
actions (seed 0): 18.7 Newton iterations per control step with 82 failed attempts (split
steps) from d_n + dt v_n alone, 13.6 with 17 from d_n alone, which the test picks in 435 of
436 steps; on PyElastica's snake (`benchmarks.speed.snake_elastica`, 10 elements at 10 ms and
6 at 20 ms) d_n alone takes up to 4.6x the iterations, and the test keeps d_n + dt v_n at
every step (a plain smaller-residual choice, ratio 1, took d_n at half the 20 ms steps and
19 % more iterations). Eel-v0: 14.9 iterations per control step and 27 failures from
d_n + dt v_n, 10.6 and none from d_n. The converged step is the same: the predictor only
starts Newton.

Newton safeguards: a correction that reverses the previous one (cosine below -1/2: a friction
point flipping its slip direction every iteration, a 2-cycle on the Coulomb law) is halved and
never accepted as the converged one; no progress over two iterations (stagnation) gives up early.
Converged: a correction below tol, or, in the quadratic phase, the next correction predicted
below tol / 1000 (e_k+1 ~ K e_k^2 with K from the last two corrections).
A step whose Newton fails is retried as 2, 4, ... sub-steps (kappa# linear in time over the
step), at most 2^max_halvings (`stepping`, the loop shared with the swimmer); should every split
fail, the splits again with Newton globalised by a backtracking line search on the residual
(`newton_globalised`). The plain Newton alone failed at the first step on a stiff undamped body
under a slow gait (E = 1e8 Pa, L = 1 m, r = 1 cm, a serpenoid of period 20 s ramped over 20 s,
dt = 50 ms, slip speed 0.1 mm/s): the trapezoidal velocity of its stiff modes rings after the
gait's start (v_n+1 = 2 (d_n+1 - d_n) / dt - v_n), the friction points flip their slip
direction from iterate to iterate and the residual wanders; the line search keeps it falling.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.physics.beam import fused
from mf_envs.physics.beam.element import GAUSS_W, N_GAUSS
from mf_envs.physics.serpentine.friction import ground_point
from mf_envs.physics.serpentine.scratch import (  # noqa: F401 (re-exported)
    MAX_QUAD,
    _scratch,
    make_scratch,
    quad_tables,
)
from mf_envs.physics.serpentine.stepping import (  # noqa: F401 (Body re-exported)
    Body,
    converged,
    correct,
    end_velocity,
    make_stepping,
)

# the predictor d_n replaces d_n + dt v_n when its residual is below this fraction of the
# latter's (module docstring)
PREDICTOR_RATIO = 0.2
# the globalised Newton (`newton_globalised`): halvings of a correction, iterations / max_iter
LINE_HALVINGS, LINE_ITER_FACTOR = 12, 4


@kernel
def _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v, tangent=True):
    """buf[0] = -R(d), ab = dR/dd (module docstring; not with tangent=False, buf[0] the same
    bits) at the iterate d of `Body` body: the
    algorithmic force (`beam.fused.element_internal`, the start's strains in sc's pre) and the
    ground's at (d_th, v_th) element by element, the inertia from sc's cm = (2 / dt^2) M
    (`fused.scale_band`); buf[1] = d - d0 - dt v0, v = v_{n+1}, buf[2:4] = d_th, v_th."""
    quad, le, th = body.quad, body.le, body.th
    cm, pre, e11, ke = sc[15], sc[11], sc[9], sc[12]
    rate = body.damping / dt
    theta_s = 0.5 + rate
    qw, stiff, tab, nzt, npt = quad[1], quad[2], quad[4], quad[5], quad[6]
    p, m_a, law = body.load
    r, x, dth, vth = buf[0], buf[1], buf[2], buf[3]
    db, de, ve, fe = e11[0], e11[1], e11[2], e11[3]
    fused.trapezoid_points(d, d0, v0, dt, th, x, v, dth, vth)
    for i in range(d0.shape[0]):
        r[i] = 0.0
    fused.start_band(cm, x, r, ab, tangent)  # r = -c_a M x, ab = c_a M
    on = law[9] > 0.0  # a ground force (effects on)
    cd, cv = -th, -2.0 * th / dt
    nu_v, c_w = law[7], law[8]
    for e in range(le.shape[0]):
        fused.clear_element(fe, ke)
        fused.gather(d, e, db)
        fused.element_internal(e, db, le[e], k0, k1, qw, stiff, theta_s, rate, tab, pre, fe, ke,
                               tangent)  # fmt: skip
        if on:  # `friction.assemble_ground` at (d_th, v_th), tangent -th dF/dd - 2 th / dt dF/dv
            fused.gather(dth, e, de)
            fused.gather(vth, e, ve)
            for g in range(N_GAUSS):
                nz, npsi = nzt[e, g], npt[e, g]
                w = GAUSS_W[g] * le[e]
                v1 = nz[0] * ve[0] + nz[1] * ve[1] + nz[2] * ve[2] + nz[3] * ve[3]
                v2 = nz[0] * ve[4] + nz[1] * ve[5] + nz[2] * ve[6] + nz[3] * ve[7]
                psi = npsi[0] * de[8] + npsi[1] * de[9] + npsi[2] * de[10]
                w3 = npsi[0] * ve[8] + npsi[1] * ve[9] + npsi[2] * ve[10]
                f1, f2, d11, d12, d21, d22, p1, p2 = ground_point(v1, v2, psi, p, law)
                f1 -= nu_v * m_a * v1
                f2 -= nu_v * m_a * v2
                d11 -= nu_v * m_a
                d22 -= nu_v * m_a
                law_p = (f1, f2, d11, d12, d21, d22, p1, p2)
                fused.point_load(fe, ke, w, nz, npsi, law_p, cd, cv, tangent)
                mc = -c_w * w3
                for i in range(3):
                    fe[8 + i] -= w * npsi[i] * mc
                for i in range(3 if tangent else 0):
                    for j in range(3):
                        ke[8 + i, 8 + j] -= cv * w * c_w * npsi[i] * npsi[j]
        fused.scatter(e, fe, ke, r, ab, tangent)


@numba.njit(cache=True)
def _predict(d0, v0, k0, k1, dt, body, d, v, sc):
    """The start's strains, the inertia band and the predictor of the module docstring into d
    (with its residual and tangent: the first iteration's); returns (buf, ab, buf2, ab2) with
    the chosen start's residual in buf, ab and the other pair free."""
    buf, ab, pre, buf2, ab2, cm = sc[8], sc[10], sc[11], sc[13], sc[14], sc[15]
    u_scale, hint = body.quad[3], sc[16]
    fused.start_strains(d0, body.le, k0, body.quad[4], pre)
    fused.scale_band(body.mass, 2.0 / (dt * dt), cm)
    cv_first = hint[0] > 0.0  # the last step's choice first, with its tangent
    predictor_into(d, d0, v0, dt, cv_first)
    _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v)
    predictor_into(d, d0, v0, dt, not cv_first)
    _residual(d0, v0, d, k0, k1, dt, body, sc, buf2, ab2, v, False)
    n_first, n_other = fused.scaled_norm2(buf[0], u_scale), fused.scaled_norm2(buf2[0], u_scale)
    if start_choice(n_first, n_other, cv_first, hint) == cv_first:
        predictor_into(d, d0, v0, dt, cv_first)
        return buf, ab, buf2, ab2
    _residual(d0, v0, d, k0, k1, dt, body, sc, buf2, ab2, v)  # the other, with its tangent
    return buf2, ab2, buf, ab


@kernel(forceinline=True)
def predictor_into(d, d0, v0, dt, cv):
    """d = d0 + dt v0 (cv) or d0: the predictor's candidates (module docstring)."""
    for i in range(d0.shape[0]):
        d[i] = d0[i] + dt * v0[i] if cv else d0[i]


@kernel(forceinline=True)
def start_choice(n_first, n_other, cv_first, hint):
    """Whether the predictor starts from d0 + dt v0 (module docstring), from the scaled
    squared residual norms of the candidate formed first (d0 + dt v0 if cv_first, else d0) and
    of the other; the choice goes to hint[0] (1.0: d0 + dt v0) for the next step's order."""
    n_start, n_cv = (n_other, n_first) if cv_first else (n_first, n_other)
    use_cv = not (n_start < PREDICTOR_RATIO**2 * n_cv or not np.isfinite(n_cv))
    hint[0] = 1.0 if use_cv else 0.0
    return use_cv


@numba.njit(cache=True)
def newton_globalised(d0, v0, k0, k1, dt, body, d, v, sc):
    """Newton with a backtracking line search: a correction x is taken as lam x with lam = 1,
    1/2, ... down to 1/2^LINE_HALVINGS, the first that lowers the dof-scaled residual norm
    sum (R_i u_i)^2 (Armijo, sufficient decrease 1e-4 lam); converged as the plain Newton, on
    the step taken. Where the plain Newton cycles or diverges (an undamped stiff body whose
    trapezoidal velocity rings on a Coulomb ground, friction points flipping their slip
    direction), this keeps the residual falling. At most LINE_ITER_FACTOR x max_iter
    iterations. Returns the iterations, or minus those spent on failure."""
    work, piv = sc[0], sc[1]
    u_scale, tol, nd = body.quad[3], body.tol, d0.shape[0]
    buf, ab, buf2, ab2 = _predict(d0, v0, k0, k1, dt, body, d, v, sc)
    nrm = fused.scaled_norm2(buf[0], u_scale)
    x = buf[1]
    back1 = np.inf
    for it in range(1, LINE_ITER_FACTOR * body.max_iter + 1):
        if fused.solve(ab, buf[0], work, piv, x) != 0:
            return -it
        lam, accepted = 1.0, False
        trial = buf2[4]  # _residual does not write row 4
        for _ in range(LINE_HALVINGS + 1):
            for i in range(nd):
                trial[i] = d[i] + lam * x[i]
            _residual(d0, v0, trial, k0, k1, dt, body, sc, buf2, ab2, v)
            n2 = fused.scaled_norm2(buf2[0], u_scale)
            if n2 <= (1.0 - 1e-4 * lam) * nrm:
                accepted = True
                break
            lam *= 0.5
        if not accepted or not np.isfinite(n2):
            return -it
        step = 0.0
        for i in range(nd):
            step = max(step, abs(trial[i] - d[i]) / u_scale[i])
            d[i] = trial[i]
        nrm = n2
        buf, buf2, ab, ab2 = buf2, buf, ab2, ab
        x = buf[1]
        if converged(it, step, back1, tol):
            end_velocity(d, d0, v0, dt, v)
            return it
        back1 = step
    return -LINE_ITER_FACTOR * body.max_iter


@numba.njit(cache=True)
def newton_step(d0, v0, k0, k1, dt, body, d, v, sc):
    """One step from (d0, v0) with kappa# k0 -> k1 of `stepping.Body` body on the ground
    (module docstring; body.damping the Kelvin-Voigt retardation time tau [s]). d, v receive
    the result, from the predictor of the module docstring; sc: the `make_scratch` tuple (no
    allocation here). Returns the Newton iterations, or minus the iterations spent on failure
    (no convergence in max_iter, stagnation, a singular or non-finite correction)."""
    work, piv = sc[0], sc[1]
    u_scale, tol = body.quad[3], body.tol
    nd = d0.shape[0]
    buf, ab, _, _ = _predict(d0, v0, k0, k1, dt, body, d, v, sc)  # (module docstring)
    x, prev = buf[1], buf[4]
    back2, back1 = np.inf, np.inf
    for it in range(1, body.max_iter + 1):
        if it > 1:
            _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v)
        if fused.solve(ab, buf[0], work, piv, x) != 0:
            return -it
        halved = False
        if it > 1:
            # a correction that reverses the previous one is a friction point flipping its
            # slip direction every iteration (a 2-cycle of Newton on the Coulomb law): half of
            # it lands between the two states, near zero slip, where the law is smooth
            dot, n_x, n_p = 0.0, 0.0, 0.0
            for i in range(nd):
                dot += x[i] * prev[i]
                n_x += x[i] * x[i]
                n_p += prev[i] * prev[i]
            if dot < -0.5 * np.sqrt(n_x * n_p):
                halved = True
                for i in range(nd):
                    x[i] *= 0.5
        for i in range(nd):
            prev[i] = x[i]
        step = correct(d, x, u_scale)
        if step < 0.0:
            return -it
        if converged(it, step, back1, tol) and not halved:
            end_velocity(d, d0, v0, dt, v)
            return it
        # stagnation (friction states cycling): a correction not below the one two iterations
        # back will not converge within max_iter; give up, the caller splits
        if it >= 5 and step > back2:
            return -it
        back2, back1 = back1, step
    return -body.max_iter


# the step split on Newton failure (with the muscles' work) and the run under a wave gait
advance_linear, run = make_stepping(newton_step, newton_globalised)
