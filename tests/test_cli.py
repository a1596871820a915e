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

COMMANDS = ("demo", "bench", "render", "train", "evaluate", "sweep")


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
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    assert set(COMMANDS) <= set(sub.choices)
    # the description names every command, as the listing below it does
    assert f"Commands: {', '.join(sub.choices)}." in " ".join(out.split())
    for cmd in sub.choices:
        assert f"\n    {cmd} " in out, cmd


def test_version_is_the_installed_distribution(capsys):
    from importlib.metadata import version

    code, out, _ = _run(capsys, ["--version"])
    assert code == 0 and out.strip() == f"mf-envs {version('mf-envs')}"


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
    code, _, err = _run(capsys, ["render", ids[0], "--out", str(tmp_path / "a.mp4")])
    _assert_one_line_error(code, err)
    assert "out" in err


@pytest.mark.parametrize("env_id", available_env_ids())
def test_render_writes_a_gif(capsys, tmp_path, env_id):
    from mf_envs import controllers

    assert controllers.baseline_kinds(env_id)  # every env has its baselines
    path = tmp_path / "gifs" / f"{env_id}.gif"
    path.parent.mkdir()
    code, out, err = _run(capsys, ["render", env_id, "--out", str(path), "--steps", "6"])
    assert code == 0, err
    assert out.strip() == f"wrote {path}"  # the file is named
    with Image.open(path) as im:
        assert im.n_frames >= 2


def test_long_render_records_every_kth_step(capsys, tmp_path, monkeypatch):
    """More steps than MAX_FRAMES: every k-th step is recorded and the GIF frame delay is k
    control steps long, so playback speed is kept."""
    import gymnasium as gym

    import mf_envs.cli.render as rcli

    env_id = "GyroStabilizer-v0"
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

    import mf_envs.cli.render as rcli

    env_id = "GyroStabilizer-v0"

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
        assert "policy" in err or 'pip install "mf-envs[train]"' in err


# ------------------------------------------------------------ outputs, extras, Ctrl-C (issue 12)
def _fake_demo(files: dict[str, str], interrupt: bool = False):
    """A stand-in for `demos.run` that writes `files` into its folder (then maybe Ctrl-C)."""

    def run(out, quick=False, only=None):
        written = []
        for name, text in files.items():
            (out / name).write_text(text)
            written.append(out / name)
        if interrupt:
            raise KeyboardInterrupt
        return written

    return run


def test_ctrl_c_leaves_previous_outputs_intact(capsys, tmp_path, monkeypatch):
    from mf_envs.benchmarks import demos

    out = tmp_path / "demo"
    out.mkdir()
    (out / "a.png").write_text("old a")
    (out / "keep.csv").write_text("old csv")
    monkeypatch.setattr(demos, "run", _fake_demo({"a.png": "new a", "b.png": "new b"}, True))
    code, _, err = _run(capsys, ["demo", "--out", str(out)])
    assert code == 130 and len(err.strip().splitlines()) == 1 and "interrupted" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demo"]  # no temporary folder left
    assert {p.name: p.read_text() for p in out.iterdir()} == {
        "a.png": "old a",
        "keep.csv": "old csv",
    }
    # completed: new files move in, replacing same-named ones; other files stay
    monkeypatch.setattr(demos, "run", _fake_demo({"a.png": "new a", "b.png": "new b"}))
    code, stdout, _ = _run(capsys, ["demo", "--out", str(out)])
    assert code == 0 and str(out) in stdout
    got = {p.name: p.read_text() for p in out.iterdir()}
    assert got == {"a.png": "new a", "b.png": "new b", "keep.csv": "old csv"}


def _read_only_dir(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    if os.access(ro, os.W_OK):  # root ignores permission bits: use a read-only mount
        ro = "/sys/mf_envs_out"
        if os.access("/sys", os.W_OK) and os.path.ismount("/sys") is False:
            pytest.skip("no read-only folder available")
    return str(ro)


def test_render_refuses_a_missing_output_folder(capsys, tmp_path):
    out = tmp_path / "no_such_dir" / "x.gif"
    code, _, err = _run(capsys, ["render", "GOWEC-v0", "--out", str(out), "--steps", "2"])
    _assert_one_line_error(code, err)
    assert "--out" in err and str(out.parent) in err
    assert not out.parent.exists()  # nothing created


def test_render_with_the_deprecated_id_notes_the_new_one(capsys, tmp_path):
    out = tmp_path / "x.gif"
    code, stdout, err = _run(capsys, ["render", "GOWEC-v1", "--out", str(out), "--steps", "2"])
    assert code == 0, err
    notes = [ln for ln in err.splitlines() if "GOWEC-v1" in ln]
    assert notes == [
        "mf-envs render: note: env id 'GOWEC-v1' is deprecated: use 'FloatingGOWEC-v0' "
        "(the same env, renamed)"
    ]
    assert stdout.strip() == f"wrote {out}" and out.is_file()


def test_several_files_are_each_named(capsys, tmp_path, monkeypatch):
    from mf_envs.benchmarks import demos

    monkeypatch.setattr(demos, "run", _fake_demo({"a.png": "a", "b.gif": "b"}))
    code, out, err = _run(capsys, ["demo", "--out", str(tmp_path / "d")])
    assert code == 0, err
    lines = out.strip().splitlines()
    assert lines[0] == "wrote 2 files:"
    assert sorted(ln.strip() for ln in lines[1:]) == [
        str(tmp_path / "d" / "a.png"),
        str(tmp_path / "d" / "b.gif"),
    ]


@pytest.mark.parametrize(
    "argv",
    [
        ["demo", "--out", "FILE"],
        ["bench", "speed", "--out", "FILE"],
        ["bench", "speed", "--out", "FILE/sub"],
        ["demo", "--out", "READONLY/sub"],
        ["render", "GOWEC-v0", "--out", "READONLY/a.gif"],
        ["render", "GOWEC-v0", "--seed", "-1", "--out", "OK/a.gif"],
        ["evaluate", "GOWEC-v0", "--out", "FILE"],
        ["evaluate", "GOWEC-v0", "--seed", "-3"],
        ["evaluate", "Nope-v0"],
        ["train", "Nope-v0", "--out", "OK"],
    ],
    ids=[
        "demo-out-file",
        "bench-out-file",
        "bench-out-under-file",
        "demo-read-only",
        "render-read-only",
        "render-negative-seed",
        "evaluate-out-file",
        "evaluate-negative-seed",
        "evaluate-unknown-env",
        "train-unknown-env",
    ],
)
def test_output_mistakes_are_one_line(capsys, tmp_path, monkeypatch, argv):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a_file").write_text("x")
    subs = {"FILE": str(tmp_path / "a_file"), "OK": str(tmp_path / "ok")}
    if any("READONLY" in a for a in argv):
        subs["READONLY"] = _read_only_dir(tmp_path)
    for key, val in subs.items():
        argv = [a.replace(key, val) for a in argv]
    code, _, err = _run(capsys, argv)
    _assert_one_line_error(code, err)


def test_unknown_policy_kwargs_key_is_one_line(capsys, tmp_path):
    pytest.importorskip(
        "stable_baselines3", reason="needs the train extra: pip install -e '.[train]'"
    )
    cfg = tmp_path / "c.yml"
    cfg.write_text('GOWEC-v0:\n  n_timesteps: 64\n  policy_kwargs: "dict(net_arch=[8], evil=1)"\n')
    code, _, err = _run(capsys, ["train", "GOWEC-v0", "--config", str(cfg), "--out", str(tmp_path)])
    _assert_one_line_error(code, err)
    assert "evil" in err


def test_run_folders_are_not_overwritten_without_force(capsys, tmp_path):
    pytest.importorskip(
        "stable_baselines3", reason="needs the train extra: pip install -e '.[train]'"
    )
    run = tmp_path / "runs" / "GOWEC-v0" / "seed0"
    run.mkdir(parents=True)
    (run / "meta.json").write_text("{}")
    code, _, err = _run(capsys, ["train", "GOWEC-v0", "--out", str(tmp_path / "runs")])
    _assert_one_line_error(code, err)
    assert "--force" in err and (run / "meta.json").read_text() == "{}"
    ev = tmp_path / "eval" / "GOWEC-v0"
    ev.mkdir(parents=True)
    (ev / "evaluate.csv").write_text("old")
    code, _, err = _run(capsys, ["evaluate", "GOWEC-v0", "--out", str(tmp_path / "eval")])
    _assert_one_line_error(code, err)
    assert "--force" in err and (ev / "evaluate.csv").read_text() == "old"


@pytest.mark.parametrize(
    "argv",
    [
        ["train", "GOWEC-v0", "--out", "OUT"],
        ["evaluate", "GOWEC-v0", "--out", "OUT"],
        ["render", "GOWEC-v0", "--policy", "ppo", "--out", "TMP/a.gif", "--steps", "2"],
    ],
    ids=["train", "evaluate", "render-ppo"],
)
def test_missing_train_extra_is_one_line(capsys, tmp_path, monkeypatch, argv):
    for mod in ("stable_baselines3", "torch", "safetensors"):
        monkeypatch.setitem(sys.modules, mod, None)  # `import mod` now fails as if not installed
    argv = [a.replace("OUT", str(tmp_path / "o")).replace("TMP", str(tmp_path)) for a in argv]
    code, _, err = _run(capsys, argv)
    _assert_one_line_error(code, err)
    assert "needs the train extra" in err
    # CPU torch first (a plain `pip install torch` is the CUDA build), then the extra
    cpu = err.index("pip install torch==2.13.0 --index-url https://download.pytorch.org/whl/cpu")
    assert cpu < err.index('pip install "mf-envs[train]"') < err.index('pip install -e ".[train]"')


def test_bench_speed_without_pyelastica_skips_that_case(capsys, tmp_path, monkeypatch):
    from mf_envs.benchmarks.speed import beam_elastica as be

    monkeypatch.setitem(sys.modules, "elastica", None)
    row = {"case": "c", "variant": "v", "steps_per_s": 1.0, "reference": "r"}
    row |= {"reference_steps_per_s": 1.0, "ratio": 1.0}

    def must_not_run(quick):
        raise AssertionError("the PyElastica case ran without PyElastica")

    monkeypatch.setattr(be, "_static", must_not_run)
    monkeypatch.setattr(be, "_inchworm_vs_pendulum", lambda quick: [row])
    monkeypatch.setattr(be, "_step_vs_elements", lambda quick: [])
    out = tmp_path / "speed"
    code, _, err = _run(capsys, ["bench", "speed", "--scene", "beam_elastica", "--out", str(out)])
    assert code == 0, err
    assert sum('pip install "mf-envs[compare]"' in ln for ln in err.splitlines()) == 1
    assert (out / "speed.csv").read_text().count("\n") == 2  # header + the one row


@pytest.mark.slow
def test_first_run_says_once_that_it_compiles(tmp_path):
    """A cold numba cache: one stderr line (however many kernels compile); warm: silent."""
    code = (
        "import numpy as np, mf_envs\n"
        "from mf_envs.frames.kernels import exp_so3\n"
        "exp_so3(np.array([0.1, 0.2, 0.3])); exp_so3(np.array([1e-9, 0.0, 0.0]))\n"
    )
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path), "MPLBACKEND": "Agg"}

    def run():
        r = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300
        )
        assert r.returncode == 0, r.stderr
        return [ln for ln in r.stderr.splitlines() if "compiling the numba kernels" in ln]

    assert len(run()) == 1  # NUMBA_CACHE_DIR (empty) takes precedence over __pycache__
    assert run() == []
