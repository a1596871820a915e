"""The drawing functions on synthetic states: shape/dtype, non-blank, state-dependent, correct
projection and visibility, clear errors, GIF round trip, headless imports."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from mf_envs.frames import exp_so3, rot_x
from mf_envs.render import (
    HumanWindow,
    draw_gowec,
    draw_inchworm,
    draw_rigid_body,
    draw_ship,
    save_gif,
)
from mf_envs.render.meshes import AXIS_COLORS, box
from mf_envs.render.projection import Camera, clip_polygon, orbit_camera

SIZE = (120, 160)


def _wave(phase: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    s = np.linspace(-30.0, 30.0, 61)
    return s, 1.0 * np.cos(2 * np.pi * s / 25.0 - phase)


def _arch(kappa: float, x0: float = 0.0, length: float = 0.2) -> np.ndarray:
    """A circular arc of curvature kappa (1/m) standing on the ground from x0."""
    S = np.linspace(0.0, length, 41)
    psi = kappa * (length / 2 - S)
    dx, dz = np.cos(psi[:-1]) * np.diff(S), np.sin(psi[:-1]) * np.diff(S)
    return np.column_stack([x0 + np.r_[0, np.cumsum(dx)], np.r_[0, np.cumsum(dz)]])


# scene name -> function of a scalar state parameter q returning a frame
SCENES = {
    "rigid_body": lambda q, **kw: draw_rigid_body(
        R=exp_so3([0.4 + q, -0.3, 0.8]), half_extents=(0.3, 0.15, 0.05), size=SIZE, **kw
    ),
    "ship": lambda q, **kw: draw_ship(
        ship_R=rot_x(0.1 + q), gimbal_angles=(0.4 + 3 * q, -0.4 - 3 * q), size=SIZE, **kw
    ),
    "gowec": lambda q, **kw: draw_gowec(
        buoy_R=rot_x(0.1 + q),
        gimbal_angle=0.3 + 3 * q,
        wave_x=_wave(5 * q)[0],
        wave_z=_wave(5 * q)[1],
        size=SIZE,
        **kw,
    ),
    "inchworm": lambda q, **kw: draw_inchworm(
        centerline=_arch(5.0 + 40 * q, x0=q), x_head=0.2 + q, x_tail=q, size=SIZE, **kw
    ),
}


def _changed_fraction(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.mean(np.any(a != b, axis=-1)))


@pytest.mark.parametrize("scene", SCENES)
def test_frame_is_nonblank_uint8_hw3(scene):
    frame = SCENES[scene](0.0)
    assert frame.dtype == np.uint8 and frame.shape == (*SIZE, 3)
    assert frame.std() > 10.0
    assert len(np.unique(frame.reshape(-1, 3), axis=0)) > 20


@pytest.mark.parametrize("scene", SCENES)
def test_different_states_give_different_frames(scene):
    a, b = SCENES[scene](0.0), SCENES[scene](0.05)
    assert 0.005 < _changed_fraction(a, b) < 0.9
    assert np.array_equal(a, SCENES[scene](0.0)), "drawing must be a pure function"


@pytest.mark.parametrize("scene", SCENES)
def test_text_is_drawn(scene):
    assert _changed_fraction(SCENES[scene](0.0), SCENES[scene](0.0, text="t = 1.0 s")) > 0.003


def test_rotor_angle_is_visible():
    s, z = _wave()
    a = draw_gowec(buoy_R=np.eye(3), gimbal_angle=0.3, rotor_angle=0.0, wave_x=s, wave_z=z)
    b = draw_gowec(buoy_R=np.eye(3), gimbal_angle=0.3, rotor_angle=0.7, wave_x=s, wave_z=z)
    assert _changed_fraction(a, b) > 0.001
    one = draw_ship(ship_R=np.eye(3), gimbal_angles=0.3)
    two = draw_ship(ship_R=np.eye(3), gimbal_angles=(0.3, -0.3))
    assert _changed_fraction(one, two) > 0.005


def test_pinhole_projection_matches_similar_triangles():
    cam = Camera(eye=np.array([0.0, -10.0, 0.0]), target=np.zeros(3), size=(200, 300), fov_deg=40.0)
    focal = 100.0 / np.tan(np.radians(20.0))
    uv, depth = cam.project(np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.5], [1.0, 10.0, 0.5]]))
    np.testing.assert_allclose(uv[0], [150.0, 100.0])
    np.testing.assert_allclose(uv[1], [150.0 + focal / 10, 100.0 - 0.5 * focal / 10])
    np.testing.assert_allclose(uv[2], [150.0 + focal / 20, 100.0 - 0.5 * focal / 20])
    np.testing.assert_allclose(depth, [10.0, 10.0, 20.0])


def _ray_box_face(eye, direction, a):
    """Axis (0, 1, 2) of the box face a ray first hits (slab method), or None; also None when
    the hit is within 6% of a face edge (outlines and anti-aliasing live there)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (-a - eye) / direction, (a - eye) / direction
    tmin, tmax = np.minimum(t1, t2), np.maximum(t1, t2)
    t_in, axis = tmin.max(), int(tmin.argmax())
    if t_in > tmax.min() or t_in <= 0:
        return None
    hit = eye + t_in * direction
    others = [k for k in range(3) if k != axis]
    if np.any(np.abs(hit[others]) > 0.94 * a[others]):
        return None
    return axis


def test_visible_faces_match_a_ray_cast():
    """Painter's order + back-face culling against an independent ray cast: for a grid of
    pixels, the face a ray through the pixel hits first must be the face whose colour (body
    axis: e1 red, e2 green, e3 blue) the pixel shows."""
    size = (240, 320)
    a = np.array([0.3, 0.2, 0.12])
    R = exp_so3([0.5, -0.4, 0.9])
    frame = draw_rigid_body(R=R, half_extents=a, size=size)
    cam = orbit_camera(
        np.array([0, 0, -0.35 * np.linalg.norm(a)]),
        5.6 * np.linalg.norm(a),
        -35.0,
        26.0,
        size,
        fov_deg=32.0,
    )
    r, up, f = cam.basis()
    focal = 0.5 * size[0] / np.tan(np.radians(16.0))
    checked = 0
    for v in range(8, size[0], 8):
        for u in range(8, size[1], 8):
            d = f + (u + 0.5 - size[1] / 2) / focal * r - (v + 0.5 - size[0] / 2) / focal * up
            axis = _ray_box_face(R.T @ cam.eye, R.T @ d, a)  # in body coordinates
            if axis is None:
                continue
            assert int(np.argmax(frame[v, u])) == int(np.argmax(AXIS_COLORS[axis])), (u, v)
            checked += 1
    assert checked > 100


def test_clip_polygon_keeps_the_half_space():
    square = box((1.0, 1.0, 1.0), (200, 0, 0)).polys[0]  # the +x face, z in [-1, 1]
    clipped = clip_polygon(square, np.array([0.0, 0.0, 1.0]), 0.25)
    assert clipped is not None and np.all(clipped[:, 2] >= 0.25 - 1e-12)
    assert np.isclose(np.ptp(clipped[:, 2]), 0.75) and np.isclose(np.ptp(clipped[:, 1]), 2.0)
    assert clip_polygon(square, np.array([0.0, 0.0, 1.0]), 2.0) is None


def test_inchworm_window_follows_the_body_and_ground_ticks_move():
    a = draw_inchworm(centerline=_arch(8.0, 0.0), x_head=0.2, x_tail=0.0, size=SIZE)
    b = draw_inchworm(centerline=_arch(8.0, 0.013), x_head=0.213, x_tail=0.013, size=SIZE)
    h = SIZE[0]
    # the body stays centred (same pixels above the ground), the ground ticks shift
    assert _changed_fraction(a[: int(0.6 * h)], b[: int(0.6 * h)]) < 0.02
    assert _changed_fraction(a[int(0.75 * h) :], b[int(0.75 * h) :]) > 0.005


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: draw_rigid_body(R=np.full((3, 3), np.nan), half_extents=(1, 1, 1)), "R"),
        (lambda: draw_rigid_body(R=np.eye(3), half_extents=(1, -1, 1)), "half_extents"),
        (lambda: draw_rigid_body(R=np.eye(2), half_extents=(1, 1, 1)), "R"),
        (lambda: draw_rigid_body(R=np.eye(3), half_extents=(1, 1, 1), size=(0, 10)), "size"),
        (lambda: draw_ship(ship_R=np.eye(3), gimbal_angles=(0.1, 0.2, 0.3)), "gimbal_angles"),
        (
            lambda: draw_ship(ship_R=np.eye(3), gimbal_angles=(0.1, 0.2), rotor_angles=(1.0,)),
            "rotor_angles",
        ),
        (
            lambda: draw_gowec(buoy_R=np.eye(3), gimbal_angle=np.inf, wave_x=[0, 1], wave_z=[0, 0]),
            "gimbal_angle",
        ),
        (
            lambda: draw_gowec(buoy_R=np.eye(3), gimbal_angle=0, wave_x=[1, 0], wave_z=[0, 0]),
            "wave_x",
        ),
        (
            lambda: draw_gowec(
                buoy_R=np.eye(3),
                gimbal_angle=0,
                wave_x=[0, 1],
                wave_z=[0, 0],
                buoy_plan=(15.0, -8.0),
            ),  # fmt: skip
            "buoy_plan",
        ),
        (lambda: draw_inchworm(centerline=np.zeros((5, 3)), x_head=0, x_tail=0), "centerline"),
        (lambda: draw_inchworm(centerline=np.zeros((5, 2)), x_head=np.nan, x_tail=0), "x_head"),
    ],
)
def test_bad_input_raises_valueerror_naming_it(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_box_hull_is_drawn_to_its_plan():
    """`buoy_plan` draws ISWEC's box instead of the cylinder: a longer hull covers more of the
    frame than a shorter one of the same beam, and both differ from the cylinder of that half
    beam (its gear the same size)."""
    kw = dict(buoy_R=np.eye(3), gimbal_angle=0.3, wave_x=_wave()[0], wave_z=_wave()[1], size=SIZE)
    sky = draw_gowec(**kw, buoy_radius=4.0)[0, 0]
    cyl, short, long = (draw_gowec(**kw, buoy_radius=4.0),
                        draw_gowec(**kw, buoy_plan=(8.0, 8.0)),
                        draw_gowec(**kw, buoy_plan=(15.0, 8.0)))  # fmt: skip

    def hull_pixels(f):
        return int(np.sum(np.all(np.abs(f.astype(int) - (230, 180, 60)) < 60, axis=-1)))

    assert _changed_fraction(cyl, short) > 0 and _changed_fraction(short, long) > 0
    assert hull_pixels(long) > hull_pixels(short) > 0
    assert np.array_equal(sky, long[0, 0])


def test_gif_round_trip(tmp_path):
    frames = [SCENES["rigid_body"](0.02 * i) for i in range(6)]
    path = save_gif(frames, tmp_path / "sub" / "anim.gif", fps=25)
    assert path.is_file()
    with Image.open(path) as im:
        assert im.n_frames == 6 and im.size == (SIZE[1], SIZE[0])
        assert im.info["duration"] == 40 and im.info.get("loop") == 0
        for i, frame in enumerate(frames):
            im.seek(i)
            back = np.asarray(im.convert("RGB"), dtype=float)
            assert np.mean(np.abs(back - frame)) < 4.0  # palette quantisation only


@pytest.mark.parametrize(
    "frames, fps, name",
    [
        ([], 30, "frames"),
        ([np.zeros((8, 8, 3), np.uint8), np.zeros((8, 9, 3), np.uint8)], 30, "frames\\[1\\]"),
        ([np.zeros((8, 8, 3), np.float32)], 30, "frames\\[0\\]"),
        ([np.zeros((8, 8, 3), np.uint8)], 0, "fps"),
    ],
)
def test_save_gif_rejects_bad_input(tmp_path, frames, fps, name):
    with pytest.raises(ValueError, match=name):
        save_gif(frames, tmp_path / "x.gif", fps=fps)


def test_human_window_validates():
    with pytest.raises(ValueError, match="backend"):
        HumanWindow("x", backend="tk")
    win = HumanWindow("x", backend="matplotlib")
    with pytest.raises(ValueError, match="frame"):
        win.show(np.zeros((4, 4), np.uint8))
    win.close()  # closing an unopened window is a no-op


def test_headless_import_and_matplotlib_window_without_display():
    """Importing and drawing never imports pyplot/pygame; the matplotlib window works on a
    non-interactive backend (no display) and closes."""
    code = (
        "import sys, warnings\n"
        "from mf_envs.render import draw_rigid_body, HumanWindow\n"
        "import numpy as np\n"
        "f = draw_rigid_body(R=np.eye(3), half_extents=(1, 1, 1))\n"
        "assert 'matplotlib.pyplot' not in sys.modules and 'pygame' not in sys.modules\n"
        "warnings.simplefilter('ignore')\n"
        "w = HumanWindow('t', backend='matplotlib'); w.show(f); w.show(f); w.close()\n"
        "print('ok')\n"
    )
    env = {"MPLBACKEND": "Agg", "PATH": "/usr/bin:/bin", "HOME": "/tmp"}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"


def test_pygame_window_shows_the_frame_exactly():
    """With the optional `render` extra: the pygame window's surface holds the frame's pixels
    (SDL's dummy video driver, no display)."""
    pytest.importorskip("pygame", reason="needs the render extra: pip install -e '.[render]'")
    code = (
        "import numpy as np, pygame\n"
        "from mf_envs.render import HumanWindow, draw_ship\n"
        "f = draw_ship(ship_R=np.eye(3), gimbal_angles=0.2)\n"
        "w = HumanWindow('t')\n"
        "assert w.backend == 'pygame'\n"
        "w.show(f)\n"
        "shown = pygame.surfarray.array3d(pygame.display.get_surface()).swapaxes(0, 1)\n"
        "assert np.array_equal(shown, f)\n"
        "w.close(); w.close()\n"
        "print('ok')\n"
    )
    env = {**os.environ, "SDL_VIDEODRIVER": "dummy"}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().endswith("ok")


@pytest.mark.parametrize("phi", [0.0, 0.4, -1.2, np.pi / 2])
def test_gyro_spin_axis_follows_the_gimbal_rotation_R2(phi):
    """The rotor spin axis is the gimbal's e3 = R_2(phi) e3 = (sin phi, 0, cos phi) (ch.3
    Eq. 30): the centres of the rotor's marked cap sectors lie on it, at +-half thickness."""
    from mf_envs.render.scenes3d import ROTOR_MARK, gyro_mesh

    mesh = gyro_mesh(phi, 0.3, scale=2.0)
    sectors = [p for p, c in zip(mesh.polys, mesh.colors) if c == ROTOR_MARK]
    axis = np.array([np.sin(phi), 0.0, np.cos(phi)])
    r, half = 1.0, 0.16  # rotor radius r = scale / 2, half thickness 0.16 r
    assert len(sectors) == 4  # two marked quarter sectors per cap
    for p in sectors:
        along = p @ axis
        radial = np.linalg.norm(p - along[:, None] * axis, axis=1)
        assert np.allclose(np.abs(along), half)  # in a cap plane normal to the spin axis
        assert np.isclose(radial.min(), 0.0) and np.allclose(np.sort(radial)[1:], r)
