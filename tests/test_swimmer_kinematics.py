"""The kinematics analysis (mf_envs.physics.swimmer.kinematics) against a prescribed travelling
wave whose frequency, amplitude, wave speed, slip, Strouhal number and Lighthill efficiency are
known in closed form."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics.swimmer.kinematics import body_kinematics


def _record(envelope_ratio, heading=0.6, length=0.2, freq=2.5, wavelength=0.16, speed=0.28,
            a0=0.02, dt=0.002, seconds=4.0):  # fmt: skip
    """h(S, t) = a(S) sin(2 pi (L - S) / lambda - 2 pi f t) on a body gliding along `heading` at
    `speed`; a(S) = a0 (r + (1 - r) (L - S) / L), r = envelope_ratio (1: uniform)."""
    t = np.arange(0.0, seconds, dt)
    s = np.linspace(0.0, length, 13)
    e = np.array([np.cos(heading), np.sin(heading)])
    n = np.array([-e[1], e[0]])
    r = envelope_ratio
    amp = a0 * (r + (1 - r) * (length - s) / length)
    k, w = 2 * np.pi / wavelength, 2 * np.pi * freq
    arg = k * (length - s)[None, :] - w * t[:, None]
    h = amp * np.sin(arg)
    along = speed * t[:, None] + (s - length / 2)[None, :]
    points = along[..., None] * e + h[..., None] * n
    com = (speed * t)[:, None] * e
    dh_ds = -(a0 * (1 - r) / length) * np.sin(arg) - amp * k * np.cos(arg)
    tail_angle = heading + np.arctan(dh_ds[:, 0])
    tail_v = speed * e + (-amp[0] * w * np.cos(arg[:, 0]))[:, None] * n
    return t, points, s, com, tail_angle, tail_v


@pytest.mark.parametrize("envelope_ratio", [1.0, 0.3])
def test_kinematics_of_a_prescribed_travelling_wave(envelope_ratio):
    """f, A, V = f lambda, U, slip U / V, St = 2 A f / U and (1 + U/V) / 2 to 1e-3."""
    freq, wavelength, speed, a0 = 2.5, 0.16, 0.28, 0.02
    got = body_kinematics(*_record(envelope_ratio))
    v = freq * wavelength
    assert got["frequency"] == pytest.approx(freq, rel=1e-3)
    assert got["amplitude"] == pytest.approx(a0, rel=1e-3)
    assert got["wave_speed"] == pytest.approx(v, rel=1e-3)
    assert got["wavelength"] == pytest.approx(wavelength, rel=1e-3)
    assert got["speed"] == pytest.approx(speed, rel=1e-9)
    assert got["slip"] == pytest.approx(speed / v, rel=1e-3)
    assert got["strouhal"] == pytest.approx(2 * a0 * freq / speed, rel=1e-3)
    assert got["froude_lighthill"] == pytest.approx(0.5 * (1 + speed / v), rel=1e-3)


@pytest.mark.parametrize("a0, tol", [(0.002, 1e-2), (0.0005, 1e-3)])
def test_large_amplitude_efficiency_tends_to_lighthills_small_amplitude_one(a0, tol):
    """U T / (U T + E) of the tail's motion (Lighthill 1971) tends to (1 + U/V) / 2 as the
    wave's slope k a falls (0.079 and 0.020 here: errors of order (k a)^2)."""
    got = body_kinematics(*_record(1.0, a0=a0))
    assert got["froude_ebt"] == pytest.approx(0.5 * (1 + 0.28 / 0.4), rel=tol)


def test_a_record_without_two_beats_is_refused_by_name():
    t, points, s, com, ang, vel = _record(1.0, seconds=0.5)
    with pytest.raises(ValueError, match="^t:"):
        body_kinematics(t, points, s, com, ang, vel)
