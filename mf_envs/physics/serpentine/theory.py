"""Small-amplitude crawling speed of a travelling curvature wave on a viscous ground (slender body,
inextensible, inertia-free; the resistive-force framework that Hu et al. 2009 use with Coulomb
friction, here with the linear law f = -(c_t v_t t + c_n v_n n) of `friction`).

Derivation (ours). Body along x in [0, L], lateral displacement y = eps Y(s, t), s the arc
length; t = (1, eps Y'), n = (-eps Y', 1); a material point moves with (x_dot, eps Y_dot),
x_dot = O(eps^2). Then v_t = x_dot + eps^2 Y' Y_dot, v_n = eps Y_dot + O(eps^3), and

    f_x = -c_t v_t t_x - c_n v_n n_x = -c_t x_dot + (c_n - c_t) eps^2 Y' Y_dot + O(eps^3),
    f_y = -c_n eps Y_dot + O(eps^2).

No external load: int f_y ds = int s f_y ds = 0 at O(eps), so Y is the imposed shape minus its
L2 projection on the rigid modes {1, s - L/2} (the recoil: lateral drift and yaw), and
int f_x ds = 0 at O(eps^2) gives, averaged over a period (x_dot's periodic part from the
arc-length contraction averages out),

    U = (c_n / c_t - 1) < int_0^L Y' Y_dot ds > / L      (centre-of-mass speed along +x).

For kappa = a sin(k s - w t), Y = -(a / k^2) sin(k s - w t) + rigid modes. On an infinite body
(no recoil) <Y' Y_dot> = -a^2 w / (2 k^3): U = -(c_n / c_t - 1) a^2 w / (2 k^3), the body moves
against the wave. `viscous_wave_speed` evaluates the finite body with its recoil by quadrature.
"""

from __future__ import annotations

import numpy as np

from mf_envs._validate import check_int, check_positive


def viscous_wave_speed(
    length: float,
    wavenumber: float,
    omega: float,
    amplitude: float,
    c_t: float,
    c_n: float,
    n_s: int = 2001,
    n_t: int = 256,
) -> float:
    """Mean centre-of-mass speed along +s [m/s] of kappa = a sin(k s - w t) (module docstring):
    length L [m], wavenumber k [1/m], omega w [rad/s], amplitude a [1/m], c_t, c_n [N s/m^2]."""
    for name, val in (
        ("length", length),
        ("wavenumber", wavenumber),
        ("omega", omega),
        ("c_t", c_t),
        ("c_n", c_n),
    ):
        check_positive(name, val)
    n_s = check_int("n_s", n_s, low=11)
    n_t = check_int("n_t", n_t, low=8)
    s = np.linspace(0.0, length, n_s)
    w_s = np.full(n_s, s[1] - s[0])
    w_s[[0, -1]] *= 0.5  # trapezoid
    wt = np.linspace(0.0, 2 * np.pi, n_t, endpoint=False)  # w t over one period
    phase = wavenumber * s[None, :] - wt[:, None]
    y = -amplitude / wavenumber**2 * np.sin(phase)
    y_dot = amplitude * omega / wavenumber**2 * np.cos(phase)
    y_s = -amplitude / wavenumber * np.cos(phase)
    basis = np.vstack([np.ones(n_s), s - 0.5 * length])  # rigid modes
    gram = basis @ (w_s[:, None] * basis.T)
    coef_dot = np.linalg.solve(gram, basis @ (w_s[:, None] * y_dot.T))  # (2, n_t)
    y_dot = y_dot - coef_dot.T @ basis
    coef = np.linalg.solve(gram, basis @ (w_s[:, None] * y.T))
    y_s = y_s - coef[1][:, None]  # the yaw's slope
    mean = np.mean((y_s * y_dot) @ w_s)
    return float((c_n / c_t - 1.0) * mean / length)
