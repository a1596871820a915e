"""The seed's gaits of the inchworm (Rios 2017 §4.10, Eqs. 101-103) and their run: uniform and
linear kappa#(S, t) in bookkeeping time (period 2 pi), the stress-free chord (an independent
check of the advance per cycle), and `run_gait` driving an `Inchworm` with anchors by Eq. 102.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mf_envs._validate import check_int
from mf_envs.physics.inchworm.model import Inchworm


def seed_uniform_kappa(t: float, kappa0: float) -> float:
    """Eq. 101: kappa#(t) = -kappa0 (1 + cos(t - pi)) / 2 [1/m], bookkeeping period 2 pi."""
    return -0.5 * kappa0 * (1.0 + np.cos(t - np.pi))


def seed_linear_kappa(
    S: np.ndarray, t: float, kappa0: float, length: float, c1: float = 0.2, c2: float = 0.8
) -> np.ndarray:
    """Eq. 103: kappa#(S, t) = -kappa0 (c1 + c2 S/L) (1 + cos(t - pi)) / 2 [1/m]."""
    return -0.5 * kappa0 * (c1 + c2 * np.asarray(S) / length) * (1.0 + np.cos(t - np.pi))


def chord_of_stress_free_shape(
    kappa_fn: Callable[[np.ndarray], np.ndarray], length: float
) -> float:
    """Head-tail distance [m] of the stress-free shape kappa = kappa#(S) with both ends on the
    ground: |int_0^L exp(i K(S)) dS|, K = int kappa#. Without gravity this is the quasi-static
    shape of the sliding simply supported beam, so L - chord at the peak actuation is the
    advance per cycle under Eq. 102 (an independent check of the FE gait)."""
    s = np.linspace(0.0, length, 4001)
    k = kappa_fn(s)
    big_k = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(s))])
    z = np.exp(1j * big_k)
    return float(abs(np.sum(0.5 * (z[1:] + z[:-1]) * np.diff(s))))


@dataclass
class GaitHistory:
    """Time series of a gait run: t [bookkeeping s], x_head, x_tail [m] (n,), anchors (n,),
    centerlines: list of (N, 2) snapshots [m], kappa_sharp: list of (n_el, 4) [1/m]."""

    t: np.ndarray
    x_head: np.ndarray
    x_tail: np.ndarray
    anchors: list[str]
    centerlines: list[np.ndarray]
    kappa_sharp: list[np.ndarray]
    iterations: int


def run_gait(
    sim: Inchworm,
    kappa_fn: Callable[[np.ndarray, float], np.ndarray],
    n_cycles: int = 2,
    steps_per_cycle: int = 40,
) -> GaitHistory:
    """Drive `sim` with kappa#(S_gauss, t) over n_cycles of bookkeeping period 2 pi, anchors by
    Eq. 102; returns the history including the start state."""
    check_int("n_cycles", n_cycles, low=1)
    check_int("steps_per_cycle", steps_per_cycle, low=2)
    ts = [0.0]
    xh, xt, anchors = [sim.x_head], [sim.x_tail], [sim.anchor]
    lines, kaps, iters = [sim.centerline()], [sim.kappa.copy()], 0
    for i in range(1, n_cycles * steps_per_cycle + 1):
        t = 2.0 * np.pi * i / steps_per_cycle
        rep = sim.actuate(kappa_fn(sim.model.gauss_S, t), dt=2.0 * np.pi / steps_per_cycle)
        iters += rep.iterations
        ts.append(t)
        xh.append(sim.x_head)
        xt.append(sim.x_tail)
        anchors.append(sim.anchor)
        lines.append(sim.centerline())
        kaps.append(sim.kappa.copy())
    return GaitHistory(np.array(ts), np.array(xh), np.array(xt), anchors, lines, kaps, iters)
