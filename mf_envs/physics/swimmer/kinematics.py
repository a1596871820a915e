"""Swimming kinematics of a sampled centreline, as fish biologists measure them (docs/eel.md,
"Kinematics against eels"): tail-beat frequency and amplitude, body wavelength and wave speed,
slip and Strouhal number, and Lighthill's elongated-body Froude efficiency.

::

    head (S = L) -------> swimming direction e (the centre of mass's mean path)
      \\__/~~\\__/~~\\__ tail (S = 0): lateral excursion h(S, t) across the mean path

The centreline is sampled at arc lengths S (tail to head) and times t (uniform step). Frame: e
is the direction of the centre of mass's displacement over the record, n = e rotated by +90
degrees; h(S, t) is a point's distance across the straight mean path (the line through the first
centre of mass along e, plus the mean lateral offset). Definitions:

* tail-beat frequency f [Hz]: upward zero crossings of the tail's h (its mean removed), from the
  first to the last (linear interpolation between samples);
* tail amplitude A [m]: half the tail's peak-to-peak excursion, averaged over the beats between
  those crossings (the biologists' amplitude; Strouhal numbers use the peak-to-peak 2 A);
* wave speed V [m/s] and body wavelength lambda = V / f [m]: the phase of h at f at each sample,
  phi(S) = arg sum_t h(S, t) exp(-2 pi i f t), unwrapped along S; its slope by least squares over
  the samples with S <= `fit_fraction` L (the posterior body, where the wave is well formed),
  V = 2 pi f / |dphi/dS| (the wave's speed along the body, in the body's frame);
* swimming speed U [m/s]: centre-of-mass displacement / duration; slip U / V; Strouhal number
  St = f 2 A / U;
* Lighthill's (1960) elongated-body efficiency of a travelling wave, (1 + U / V) / 2, and the
  large-amplitude theory's (Lighthill 1971, Proc. R. Soc. B 179) from the tail's own motion:
  with u = v . t, w = v . n at the tail (t its tangent, pointing to the head), the mean thrust
  T = < m_a (-u w n + w^2 t / 2) . e > (the trailing-edge force of `fluid`) and the energy
  left in the wake per unit time E = < m_a w^2 u / 2 >, eta = U T / (U T + E) (m_a cancels).
  For a small-amplitude wave h = g(x - V t) it is (1 + U / V) / 2 (U T + E is then Lighthill's
  1960 rate of working m_a U < h_t (h_t + U h_x) >).
"""

from __future__ import annotations

import numpy as np

from mf_envs._validate import check_range


def _upward_crossings(t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Times [s] at which y crosses zero upwards (linear interpolation)."""
    i = np.nonzero((y[:-1] < 0.0) & (y[1:] >= 0.0))[0]
    frac = -y[i] / (y[i + 1] - y[i])
    return t[i] + frac * (t[i + 1] - t[i])


def mean_path(com: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """(e, n, U): the unit direction of the centre of mass's displacement com (N, 2) [m], its
    normal (e turned +90 degrees) and the displacement's length (the caller divides by time)."""
    disp = com[-1] - com[0]
    dist = float(np.hypot(*disp))
    if dist <= 0.0:
        raise ValueError("com: the centre of mass did not move")
    e = disp / dist
    return e, np.array([-e[1], e[0]]), dist


def body_kinematics(t: np.ndarray, points: np.ndarray, s: np.ndarray, com: np.ndarray,
                    tail_angle: np.ndarray, tail_velocity: np.ndarray,
                    fit_fraction: float = 0.5) -> dict[str, float]:  # fmt: skip
    """The kinematics (module docstring) of a record: t (N,) [s], uniform; points (N, n, 2)
    [m] the centreline at arc lengths s (n,) [m], tail (s = 0) to head; com (N, 2) [m] the
    centre of mass; tail_angle (N,) [rad] the tail's frame angle (its tangent, pointing to
    the head); tail_velocity (N, 2) [m/s]. Returns f [Hz], A [m], peak_to_peak [m],
    wave_speed V [m/s], wavelength [m], speed U [m/s], slip, strouhal, froude_lighthill
    ((1 + U/V) / 2) and froude_ebt (U T / (U T + E) of the tail's motion)."""
    check_range("fit_fraction", fit_fraction, 0.05, 1.0)
    t = np.asarray(t, float)
    e, n, dist = mean_path(com)
    speed = dist / (t[-1] - t[0])
    lateral = points @ n  # (N, n) across the mean path
    h = lateral - float(np.mean(com @ n))
    tail = h[:, 0] - np.mean(h[:, 0])
    ups = _upward_crossings(t, tail)
    if ups.size < 3:
        raise ValueError("t: the record holds fewer than two tail beats")
    freq = (ups.size - 1) / (ups[-1] - ups[0])
    spans = [np.ptp(tail[(t >= a) & (t < b)]) for a, b in zip(ups[:-1], ups[1:])]
    p2p = float(np.mean(spans))
    inside = (t >= ups[0]) & (t < ups[-1])
    ph = np.exp(-2j * np.pi * freq * t[inside])
    phase = np.unwrap(np.angle((h[inside] - h[inside].mean(axis=0)).T @ ph))
    sel = s <= fit_fraction * (s[-1] - s[0]) + s[0]
    slope = np.polyfit(s[sel], phase[sel], 1)[0]
    wave_speed = 2.0 * np.pi * freq / abs(slope)
    ang = np.asarray(tail_angle)[inside]
    tt = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    nn = np.stack([-tt[:, 1], tt[:, 0]], axis=1)
    vel = np.asarray(tail_velocity)[inside]
    u, w = np.sum(vel * tt, axis=1), np.sum(vel * nn, axis=1)
    thrust = float(np.mean((-u * w) * (nn @ e) + 0.5 * w * w * (tt @ e)))
    wake = float(np.mean(0.5 * w * w * u))
    working = speed * thrust + wake
    return {
        "frequency": float(freq),
        "amplitude": 0.5 * p2p,
        "peak_to_peak": p2p,
        "wave_speed": float(wave_speed),
        "wavelength": float(wave_speed / freq),
        "speed": float(speed),
        "slip": float(speed / wave_speed),
        "strouhal": float(freq * p2p / speed),
        "froude_lighthill": float(0.5 * (1.0 + speed / wave_speed)),
        "froude_ebt": speed * thrust / working if working > 0.0 else 0.0,
    }
