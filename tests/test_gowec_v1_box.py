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
    """The cylinder device (`iswec_class`, the default before the box; axisymmetric: its roll
    block is its pitch block) steps bit for bit as before the roll block, in a head sea and in
    an oblique irregular one (both axes loaded), under a sine torque command."""
    env = gym.make("FloatingGOWEC-v0", device="iswec_class", **kwargs).unwrapped
    env.reset(seed=seed)
    total = 0.0
    for k in range(400):
        _, r, _, _, _ = env.step(np.array([0.6 * math.sin(0.05 * k)], np.float32))
        total += r
    y = np.ascontiguousarray(env.state)
    assert hashlib.sha256(y.tobytes()).hexdigest()[:16] == digest
    assert total.hex() == ret


@pytest.fixture(scope="module")
def box():
    from mf_envs.physics.gowec.hydro.three_dof import ISWEC_BOX_FILE, ThreeDofCoefficients

    return ThreeDofCoefficients.load(ISWEC_BOX_FILE)


def test_box_keel_nodes_carry_both_axes_quadratic_damping(box):
    """The box's keel nodes (`sea.drag_geometry` with its plan) reproduce the flat plate's
    integrals of |y|^3 (pitch about e1, the length along e2: B L^4 / 32) and of |x|^3 (roll:
    L B^4 / 32), so still-water quadratic damping about each body axis is the plate's exactly;
    the side's width faces the wave (B in head seas, L in beam seas)."""
    from mf_envs.physics.gowec.hydro import axes, sea
    from mf_envs.physics.gowec.hydro.axes import pitch_hull

    L, B = axes.plan(box)
    hull = pitch_hull(box)
    for direction, width in ((math.pi / 2, B), (0.0, L)):
        sp = sea.drag_geometry(hull, 1.0, 0.0, direction, (L, B))
        ck = sp[sea.SP_CK : sea.SP_CK + sea.N_KEEL]
        xk, yk = sp[sea.SP_XK : sea.SP_XK + sea.N_KEEL], sp[sea.SP_YK : sea.SP_YK + sea.N_KEEL]
        half = 0.5 * hull.rho  # 1/2 rho C_d, C_d = 1
        assert np.sum(ck) == pytest.approx(half * L * B, rel=1e-14)
        assert np.sum(ck * np.abs(yk) ** 3) == pytest.approx(half * B * L**4 / 32, rel=1e-12)
        assert np.sum(ck * np.abs(xk) ** 3) == pytest.approx(half * L * B**4 / 32, rel=1e-12)
        side = sp[sea.SP_CS : sea.SP_CS + sea.N_SIDE]
        assert np.sum(side) == pytest.approx(half * width * hull.draft, rel=1e-12)
        # the plate's moments of still-water rotations, through the kernel itself (side off)
        sp[sea.SP_CS : sea.SP_CS + sea.N_SIDE] = 0.0
        mx, _, _, _ = sea.drag_loads(0.1, 0.0, 0.0, 0.0, np.zeros(sea.N_LOADS + 2), sp)
        assert mx == pytest.approx(-half * 0.01 * B * L**4 / 32, rel=1e-12)
        _, my, _, _ = sea.drag_loads(0.0, 0.1, 0.0, 0.0, np.zeros(sea.N_LOADS + 2), sp)
        assert my == pytest.approx(-half * 0.01 * L * B**4 / 32, rel=1e-12)


def test_box_wave_moments_by_heading(box):
    """The moments about e1 and e2 (`axes.directional_excitation`) are the heading table's:
    in head seas (direction pi/2) -X5(0) and 0 (the xOz mirror: no roll), in beam seas
    (direction 0, heading -pi/2) 0 (the yOz mirror: no pitch) and X4(-pi/2) = -X4(pi/2);
    between tabulated headings, linear."""
    from mf_envs.physics.gowec.hydro import axes

    w = box.omega[3:20]
    X = box.heading_excitation[3:20]
    head = axes.directional_excitation(box, w, math.pi / 2)
    np.testing.assert_allclose(head[0], -X[:, 0, axes.PITCH], rtol=1e-12)
    assert np.max(np.abs(head[1])) < 1e-9 * np.max(np.abs(head[0]))
    beam = axes.directional_excitation(box, w, 0.0)
    np.testing.assert_allclose(beam[1], -X[:, -1, axes.ROLL], rtol=1e-12)
    assert np.max(np.abs(beam[0])) < 1e-6 * np.max(np.abs(head[0]))
    mid = axes.directional_excitation(box, w, math.pi / 2 + 0.5 * box.headings[1])
    np.testing.assert_allclose(mid[1], 0.5 * (X[:, 0, axes.ROLL] + X[:, 1, axes.ROLL]),
                               rtol=1e-12)  # fmt: skip


def test_box_device_through_make_and_make_vec():
    """`device="iswec_box"` through gym.make and the native vector env: the box's blocks
    (stiffer pitch, 8x softer roll), head seas leave it level in roll, and the vector env's
    rows step as the single env does (tests/test_vector_envs.py checks every step)."""
    env = gym.make("FloatingGOWEC-v0", device="iswec_box", episode_seconds=4.0)
    u = env.unwrapped
    C = u.model.p.stiffness
    assert C[0] == pytest.approx(18.37e6, rel=1e-3) and C[0] / C[1] == pytest.approx(8.41, rel=0.01)
    env.reset(seed=1)
    done, roll = False, 0.0
    while not done:
        _, _, term, trunc, info = env.step(np.array([0.5], np.float32))
        roll = max(roll, abs(info["buoy_roll"]))
        done = term or trunc
    assert not term and roll < 1e-9 and abs(info["buoy_pitch"]) > 1e-3
    vec = gym.make_vec("FloatingGOWEC-v0", num_envs=2, vectorization_mode="vector_entry_point",
                       device="iswec_box", episode_seconds=4.0)  # fmt: skip
    obs, _ = vec.reset(seed=[1, 2])
    single, _ = env.reset(seed=1)
    np.testing.assert_array_equal(obs[0], single)
