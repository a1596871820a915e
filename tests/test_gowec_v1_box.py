"""FloatingGOWEC-v0 with ISWEC's box hull (`device="iswec_box"`): the separate roll block of the
floating model, and the cylinder device's trajectories unchanged by it."""

import hashlib
import math

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the envs)

# (kwargs, seed) -> (sha256 of the state after 400 steps, first 16 hex digits; the return's
# float.hex()), recorded on the cylinder device before the roll block existed (main 39baa2a)
CYLINDER_TRAJECTORIES = [
    ({}, 3, "a67d59d7927ee211", "-0x1.70446f466f1dap+4"),
    (dict(significant_wave_height=2.0, peak_period=6.0, wave_direction=1.0), 5,
     "92721baf10a10106", "-0x1.0d6f968119805p+5"),
]  # fmt: skip


@pytest.mark.parametrize("kwargs, seed, digest, ret", CYLINDER_TRAJECTORIES)
def test_cylinder_device_is_bit_identical(kwargs, seed, digest, ret):
    """The default device (`iswec_class`, axisymmetric: its roll block is its pitch block) steps
    bit for bit as before the roll block, in a head sea and in an oblique irregular one (both
    axes loaded), under a sine torque command."""
    env = gym.make("FloatingGOWEC-v0", **kwargs).unwrapped
    env.reset(seed=seed)
    total = 0.0
    for k in range(400):
        _, r, _, _, _ = env.step(np.array([0.6 * math.sin(0.05 * k)], np.float32))
        total += r
    y = np.ascontiguousarray(env.state)
    assert hashlib.sha256(y.tobytes()).hexdigest()[:16] == digest
    assert total.hex() == ret
