"""Compiled scalar step of a shape-memory-alloy (SMA) wire group (`actuators.sma`): lumped
Joule heating and convective cooling solved exactly over a step, the martensite fraction xi on
Liang-Rogers cosine branches with reversal memory, latent heat of the transformation by an
energy-exact implicit correction. Scalar functions of floats (numba `kernel`s: no arrays, no
allocation); `sma` documents the model and holds the parameters.

Per unit length of one wire (A = pi d^2 / 4, perimeter p = pi d; temperatures in degC, their
differences in K):

    rho c A dT/dt = I^2 R' - h p (T - T_amb)   (sensible heat, latent heat apart)       (S1)

is linear in T for a held current I: T(t) = T_inf + (T0 - T_inf) exp(-t / tau) with
tau = rho c A / (h p) = rho c d / (4 h) and T_inf = T_amb + I^2 R' / (h p); the heat convected
over the step is the exact integral of h p (T - T_amb) along it (`thermal_exact`).
"""

from __future__ import annotations

import math

from mf_envs._jit import kernel

HEATING, COOLING = 1.0, -1.0  # branch direction codes of the hysteresis state


@kernel(forceinline=True)
def thermal_exact(t0, power, hp, cap, t_amb, dt):
    """Exact solution of (S1) over dt [s] from t0 [degC] with Joule power `power` [W/m], film
    conductance hp = h p [W/(m K)] and heat capacity cap = rho c A [J/(m K)] per length:
    returns (T1 [degC], heat convected [J/m])."""
    tau = cap / hp
    t_inf = t_amb + power / hp
    decay = math.exp(-dt / tau)
    t1 = t_inf + (t0 - t_inf) * decay
    q_conv = hp * ((t_inf - t_amb) * dt + (t0 - t_inf) * tau * (1.0 - decay))
    return t1, q_conv


@kernel(forceinline=True)
def austenite_branch(t, a_s, a_f):
    """Liang-Rogers heating shape f_A(T) = (cos(pi (T - As) / (Af - As)) + 1) / 2: 1 at and
    below As, 0 at and above Af (the martensite left of a full heating from xi = 1)."""
    if t <= a_s:
        return 1.0
    if t >= a_f:
        return 0.0
    return 0.5 * (math.cos(math.pi * (t - a_s) / (a_f - a_s)) + 1.0)


@kernel(forceinline=True)
def martensite_branch(t, m_f, m_s):
    """Liang-Rogers cooling shape g_M(T) = (1 - cos(pi (T - Mf) / (Ms - Mf))) / 2: 1 at and
    above Ms, 0 at and below Mf (the austenite left of a full cooling from xi = 0)."""
    if t >= m_s:
        return 1.0
    if t <= m_f:
        return 0.0
    return 0.5 * (1.0 - math.cos(math.pi * (t - m_f) / (m_s - m_f)))


@kernel(forceinline=True)
def fraction_on_branch(t, direction, t_r, xi_r, a_s, a_f, m_s, m_f):
    """Martensite fraction at T on the branch that left the reversal point (t_r, xi_r) in
    `direction` (HEATING or COOLING): the Liang-Rogers (1990) cosine law, scaled so that it
    starts at xi_r (heating: xi = xi_r f_A(T) / f_A(t_r); cooling: xi = 1 - (1 - xi_r)
    g_M(T) / g_M(t_r)); it is Liang-Rogers' own law when the reversal lies outside the
    transformation band (below As, above Ms). Always in [0, 1], monotone in T."""
    if direction > 0.0:
        f_r = austenite_branch(t_r, a_s, a_f)
        if f_r <= 0.0:
            return 0.0
        return min(max(xi_r * austenite_branch(t, a_s, a_f) / f_r, 0.0), 1.0)
    g_r = martensite_branch(t_r, m_f, m_s)
    if g_r <= 0.0:
        return 1.0
    return min(max(1.0 - (1.0 - xi_r) * martensite_branch(t, m_f, m_s) / g_r, 0.0), 1.0)


@kernel
def latent_correction(t0, t1s, xi0, direction, t_r, xi_r, a_s, a_f, m_s, m_f, lat):
    """The temperature T1 in [min(t0, t1s), max(t0, t1s)] where the sensible-heat end point t1s
    gives up (heating) or receives (cooling) the latent heat of the transformation it drives:
    T1 = t1s - lat (xi0 - xi(T1)), lat = L / c [K], xi on the present branch. The left side
    minus the right is monotone in T1, so bisection with secant steps finds the root (to
    1e-13 K, at most 200 iterations). Returns (T1, xi(T1))."""
    lo, hi = min(t0, t1s), max(t0, t1s)
    g_lo = lo - t1s + lat * (xi0 - fraction_on_branch(lo, direction, t_r, xi_r, a_s, a_f, m_s, m_f))
    g_hi = hi - t1s + lat * (xi0 - fraction_on_branch(hi, direction, t_r, xi_r, a_s, a_f, m_s, m_f))
    if g_lo >= 0.0:
        return lo, fraction_on_branch(lo, direction, t_r, xi_r, a_s, a_f, m_s, m_f)
    if g_hi <= 0.0:
        return hi, fraction_on_branch(hi, direction, t_r, xi_r, a_s, a_f, m_s, m_f)
    t = hi
    for k in range(200):
        t = lo - g_lo * (hi - lo) / (g_hi - g_lo)  # secant (regula falsi) point
        if not lo < t < hi or (k % 3) == 2:  # every third step (and out of range): bisect
            t = 0.5 * (lo + hi)
        g = t - t1s + lat * (xi0 - fraction_on_branch(t, direction, t_r, xi_r, a_s, a_f, m_s, m_f))
        if g == 0.0 or hi - lo < 1e-13:
            break
        if g < 0.0:
            lo, g_lo = t, g
        else:
            hi, g_hi = t, g
    return t, fraction_on_branch(t, direction, t_r, xi_r, a_s, a_f, m_s, m_f)


@kernel
def sma_step(t0, xi0, direction, t_r, xi_r, power, hp, cap, t_amb, dt, alloy, lat):
    """One step of a wire under the held Joule power `power` [W/m] (S1 exact; then xi on its
    branch; latent heat lat = L / c [K] by `latent_correction`, 0 for none). A step that moves T
    against the branch direction starts a new branch at (t0, xi0). Returns (T1, xi1, direction,
    t_r, xi_r, q_conv [J/m]); the energy per length balances exactly:
    power dt = cap (T1 - t0) + cap lat (xi0 - xi1) + q_conv."""
    a_s, a_f, m_s, m_f = alloy  # the transformation temperatures [C]
    t1s, q_conv = thermal_exact(t0, power, hp, cap, t_amb, dt)
    if t1s != t0:
        new_dir = HEATING if t1s > t0 else COOLING
        if new_dir != direction:
            direction, t_r, xi_r = new_dir, t0, xi0
    if lat > 0.0:
        t1, xi1 = latent_correction(t0, t1s, xi0, direction, t_r, xi_r, a_s, a_f, m_s, m_f, lat)
    else:
        t1 = t1s
        xi1 = fraction_on_branch(t1, direction, t_r, xi_r, a_s, a_f, m_s, m_f)
    return t1, xi1, direction, t_r, xi_r, q_conv


@kernel
def contraction_time(power, hp, cap, t_amb, dt, a_s, a_f, m_s, m_f, lat, done, t_max):
    """The maker's heating test: from rest at t_amb (martensite, xi = 1) under the held power
    [W/m], the time [s] until the wire has contracted (xi <= 1 - done), located by linear
    interpolation of xi inside the crossing step; inf if not within t_max [s]. Also returns the
    temperature [degC] then."""
    t, xi, direction, t_r, xi_r = t_amb, 1.0, COOLING, t_amb, 1.0
    time = 0.0
    while time < t_max:
        xi_old = xi
        t, xi, direction, t_r, xi_r, _q = sma_step(
            t, xi, direction, t_r, xi_r, power, hp, cap, t_amb, dt, (a_s, a_f, m_s, m_f), lat
        )
        time += dt
        if xi <= 1.0 - done:
            return time - dt * (xi - (1.0 - done)) / (xi - xi_old), t
    return math.inf, t


@kernel
def relaxation_time(t0, xi0, hp, cap, t_amb, dt, a_s, a_f, m_s, m_f, lat, done, t_max):
    """The maker's cooling test: from a contracted wire (t0 [degC], xi0, last heated) with the
    current off, the time [s] until it has relaxed (xi >= done), interpolated as above; inf if
    not within t_max [s]."""
    t, xi, direction, t_r, xi_r = t0, xi0, HEATING, t0, xi0
    time = 0.0
    while time < t_max:
        xi_old = xi
        t, xi, direction, t_r, xi_r, _q = sma_step(
            t, xi, direction, t_r, xi_r, 0.0, hp, cap, t_amb, dt, (a_s, a_f, m_s, m_f), lat
        )
        time += dt
        if xi >= done:
            return time - dt * (xi - done) / (xi - xi_old)
    return math.inf
