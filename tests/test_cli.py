"""`mf-envs` command line: help lists every command; user mistakes give exit status 2 and one
line on stderr (no traceback); `mf-envs render` writes a GIF for every registered env."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from PIL import Image

from mf_envs.cli import build_parser, main
from mf_envs.envs import available_env_ids

COMMANDS = ("demo", "bench", "render", "train", "evaluate")


def _run(capsys, argv: list[str]) -> tuple[int, str, str]:
    """main(argv) in-process: (exit status, stdout, stderr); argparse exits are caught."""
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 1
    out = capsys.readouterr()
    return code, out.out, out.err


def _assert_one_line_error(code: int, err: str) -> None:
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    assert code == 2, (code, err)
    assert "Traceback" not in err
    assert len(lines) == 1, f"expected one line on stderr, got {len(lines)}:\n{err}"


def test_help_lists_every_command(capsys):
    code, out, _ = _run(capsys, ["--help"])
    assert code == 0
    for cmd in COMMANDS:
        assert cmd in out, cmd
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    assert set(COMMANDS) <= set(sub.choices)


@pytest.mark.parametrize(
    "argv",
    [
        ["render", "Nope-v0", "--out", "x.gif"],
        ["bench", "speed", "--scene", "no_such_scene", "--out", "OUT"],
        ["bench", "nope", "--out", "OUT"],
    ],
    ids=["unknown-env-id", "unknown-scene", "unknown-bench-kind"],
)
def test_user_mistakes_give_one_line_and_status_2(capsys, tmp_path, argv):
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in argv]
    code, _, err = _run(capsys, argv)
    _assert_one_line_error(code, err)


def test_unknown_env_id_names_the_known_ids(capsys):
    code, _, err = _run(capsys, ["render", "Nope-v0", "--out", "x.gif"])
    assert code == 2 and "Nope-v0" in err and "GOWEC-v0" in err


def test_user_mistake_in_a_subprocess():
    """The installed entry point behaves the same way (status 2, one line, no traceback)."""
    out = subprocess.run(
        [sys.executable, "-m", "mf_envs.cli", "render", "Nope-v0", "--out", "x.gif"],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    _assert_one_line_error(out.returncode, out.stderr)
    assert "env_id" in out.stderr


@pytest.mark.parametrize("env_id", available_env_ids())
@pytest.mark.parametrize(
    "extra, name",
    [
        (["--policy", "nonsense"], "policy"),
        (["--policy", "baseline:no_such_kind"], "kind|policy"),
        (["--steps", "0"], "steps"),
    ],
)
def test_render_user_mistakes(capsys, tmp_path, env_id, extra, name):
    code, _, err = _run(capsys, ["render", env_id, "--out", str(tmp_path / "a.gif"), *extra])
    _assert_one_line_error(code, err)
    assert any(n in err for n in name.split("|")), err


def test_render_needs_a_gif_path(capsys, tmp_path):
    ids = available_env_ids()
    if not ids:
        pytest.skip("no env module has landed yet")
    code, _, err = _run(capsys, ["render", ids[0], "--out", str(tmp_path / "a.mp4")])
    _assert_one_line_error(code, err)
    assert "out" in err


@pytest.mark.parametrize("env_id", available_env_ids())
def test_render_writes_a_gif(capsys, tmp_path, env_id):
    from mf_envs import controllers

    try:
        controllers.baseline_kinds(env_id)
    except ModuleNotFoundError:
        pytest.skip(f"{env_id}: its baseline controllers have not landed yet")
    path = tmp_path / "gifs" / f"{env_id}.gif"
    code, out, err = _run(capsys, ["render", env_id, "--out", str(path), "--steps", "6"])
    assert code == 0, err
    assert str(path.parent) in out  # the output folder is named
    with Image.open(path) as im:
        assert im.n_frames >= 2


def test_long_render_records_every_kth_step(capsys, tmp_path, monkeypatch):
    """More steps than MAX_FRAMES: every k-th step is recorded and the GIF frame delay is k
    control steps long, so playback speed is kept."""
    import gymnasium as gym

    import mf_envs.render.cli as rcli

    env_id = "GyroStabilizer-v0"
    if env_id not in available_env_ids():
        pytest.skip(f"{env_id} has not landed")
    monkeypatch.setattr(rcli, "MAX_FRAMES", 3)
    path = tmp_path / "long.gif"
    code, _, err = _run(capsys, ["render", env_id, "--out", str(path), "--steps", "9"])
    assert code == 0, err
    env = gym.make(env_id)
    fps = env.metadata["render_fps"]
    env.close()
    with Image.open(path) as im:
        assert im.n_frames == 4  # reset + steps 3, 6, 9
        assert im.info["duration"] == round(100 / (fps / 3)) * 10


def test_render_keeps_the_frames_before_a_numerical_failure(capsys, tmp_path, monkeypatch):
    """An episode ended by a numerical failure still gives its GIF (the non-finite state is
    not drawn) and says so."""
    import numpy as np

    import mf_envs.render.cli as rcli

    env_id = "GyroStabilizer-v0"
    if env_id not in available_env_ids():
        pytest.skip(f"{env_id} has not landed")

    class PoisoningPolicy:  # zero action; makes the physics state NaN before the 4th step
        def __init__(self, env):
            self.env, self.calls = env, 0

        def predict(self, obs, deterministic=True):
            self.calls += 1
            if self.calls == 4:
                self.env.unwrapped._y.fill(np.nan)
            return np.zeros(self.env.action_space.shape, np.float32), None

    monkeypatch.setattr(rcli, "make_policy", lambda env, env_id, policy: PoisoningPolicy(env))
    path = tmp_path / "fail.gif"
    code, _, err = _run(capsys, ["render", env_id, "--out", str(path), "--steps", "10"])
    assert code == 0, err
    assert "numerical failure at step 4" in err
    with Image.open(path) as im:
        assert im.n_frames == 4  # reset + steps 1..3


@pytest.mark.parametrize("env_id", available_env_ids())
def test_render_ppo_policy_renders_or_says_why(capsys, tmp_path, env_id):
    """`--policy ppo`: the shipped policy drives the env, or (none shipped / extras missing)
    one clear line and status 2, never a traceback."""
    path = tmp_path / "ppo.gif"
    code, _, err = _run(
        capsys, ["render", env_id, "--policy", "ppo", "--out", str(path), "--steps", "3"]
    )
    if code == 0:
        with Image.open(path) as im:
            assert im.n_frames == 4
    else:
        _assert_one_line_error(code, err)
        assert "policy" in err
