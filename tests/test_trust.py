"""Outputs never follow a planted link, documents and headers are bounded before they are read,
and every refusal is one line naming the key, file or parameter the user gave.

Each case plants its payload (a symbolic link to a victim file outside the output folder, a
deeply nested document, a huge array header, a FIFO, a silent address) and asserts both the
exact name in the error and that the victim is unchanged.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from mf_envs.cli import main

SWEEP = """env_id: GOWEC-v0
seeds: [0]
controllers: [baseline]
env_kwargs: {episode_seconds: 1.0}
"""
VICTIM = "line1\nline2 without a newline"


def _victim(tmp_path: Path) -> Path:
    v = tmp_path / "victim.txt"
    v.write_text(VICTIM)
    return v


def _planted(tmp_path: Path, folder: str, name: str) -> tuple[Path, Path]:
    """(victim file outside, `tmp_path/folder`) with `folder/name` a link to the victim."""
    victim = _victim(tmp_path)
    out = tmp_path / folder
    out.mkdir()
    (out / name).symlink_to(victim)
    return victim, out


def _one_line(capsys) -> str:
    """The one line on stderr (the first run's numba-compile notice aside)."""
    lines = capsys.readouterr().err.strip().splitlines()
    err = [ln for ln in lines if "compiling the numba kernels" not in ln]
    assert len(err) == 1, err
    return err[0]


# ---------------------------------------------------------------------- planted links
def test_sweep_refuses_a_planted_trials_csv_link(tmp_path, capsys):
    victim, out = _planted(tmp_path, "out", "trials.csv")
    cfg = tmp_path / "cfg.yml"
    cfg.write_text(SWEEP)
    args = ["sweep", str(cfg), "--serial", "--no-progress", "--out", str(out)]
    assert main(args) == 2
    line = _one_line(capsys)
    assert "trials.csv" in line and "symbolic link" in line
    assert victim.read_text() == VICTIM
    # a planted link at a picture's name is refused too (after the trials ran)
    (out / "trials.csv").unlink()
    (out / "cfg_power_ratio.png").symlink_to(victim)
    assert main(args) == 2
    assert "cfg_power_ratio.png" in _one_line(capsys)
    assert victim.read_text() == VICTIM


def test_sweep_names_a_malformed_or_special_trials_csv(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    cfg = tmp_path / "cfg.yml"
    cfg.write_text(SWEEP)
    args = ["sweep", str(cfg), "--serial", "--no-progress", "--out", str(out)]
    (out / "trials.csv").write_text("a,b\n1,2\n")
    assert main(args) == 2
    line = _one_line(capsys)
    assert "trials.csv" in line and "trial_id" in line
    assert (out / "trials.csv").read_text() == "a,b\n1,2\n"
    (out / "trials.csv").unlink()
    os.mkfifo(out / "trials.csv")  # never opened for reading (no hang)
    assert main(args) == 2
    assert "not a regular file" in _one_line(capsys)


def test_store_cuts_a_torn_line_atomically(tmp_path):
    from mf_envs.sweep.store import ResultStore

    p = tmp_path / "trials.csv"
    p.write_text("trial_id,x\nabc,1\ndef,")
    store = ResultStore(p)
    assert p.read_text() == "trial_id,x\nabc,1\n"
    store.append({"trial_id": "ghi", "x": 2.5})
    assert store.done_ids() == {"abc", "ghi"}
    assert [q.name for q in tmp_path.iterdir()] == ["trials.csv"]  # no temporary left


def test_train_refuses_a_planted_run_folder_link(tmp_path, capsys):
    pytest.importorskip("stable_baselines3", reason="needs the train extra")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    runs = tmp_path / "runs"
    runs.mkdir()
    (runs / "GOWEC-v0").symlink_to(elsewhere)
    args = ["train", "GOWEC-v0", "--timesteps", "64", "--out", str(runs)]
    assert main(args) == 2
    line = _one_line(capsys)
    assert "runs/GOWEC-v0" in line and "symbolic link" in line
    assert list(elsewhere.iterdir()) == []


def test_staged_outputs_refuse_links_inside_the_folder(tmp_path):
    from mf_envs._staging import staged_dir

    victim, out = _planted(tmp_path, "out", "table.csv")
    with pytest.raises(ValueError, match="table.csv.*symbolic link"):
        with staged_dir(out) as tmp:
            (tmp / "table.csv").write_text("new")
            (tmp / "other.csv").write_text("new")
    assert victim.read_text() == VICTIM
    assert not (out / "other.csv").exists()  # nothing moved: refused before the first move
    (out / "sub").symlink_to(tmp_path)
    with pytest.raises(ValueError, match="sub.*symbolic link"):
        with staged_dir(out) as tmp:
            (tmp / "sub").mkdir()
            (tmp / "sub" / "victim.txt").write_text("new")
    assert victim.read_text() == VICTIM


def test_policy_files_are_not_written_through_links(tmp_path):
    from mf_envs.train.policy import write_meta

    victim, folder = _planted(tmp_path, "pol", "meta.json")
    with pytest.raises(ValueError, match="meta.json.*symbolic link"):
        write_meta(folder, {"env_id": "GOWEC-v0"})
    assert victim.read_text() == VICTIM
    (folder / "meta.json").unlink()
    write_meta(folder, {"env_id": "GOWEC-v0"})
    assert json.loads((folder / "meta.json").read_text()) == {"env_id": "GOWEC-v0"}
    assert sorted(q.name for q in folder.iterdir()) == ["meta.json"]


def test_a_gif_is_not_written_through_a_link(tmp_path):
    import numpy as np

    from mf_envs.render import save_gif

    victim = _victim(tmp_path)
    (tmp_path / "o.gif").symlink_to(victim)
    with pytest.raises(ValueError, match="o.gif.*symbolic link"):
        save_gif([np.zeros((4, 4, 3), np.uint8)], tmp_path / "o.gif")
    assert victim.read_text() == VICTIM


# ---------------------------------------------------------------------- policy folders
def _deep(n: int) -> str:
    return "[" * n + "]" * n


@pytest.mark.parametrize(
    ("name", "payload", "match"),
    [
        ("policy.json", lambda d: '{"a": ' + _deep(100_000) + "}", "nests deeper"),
        ("meta.json", lambda d: '{"a": ' + _deep(100_000) + "}", "nests deeper"),
        ("obs_normalization.json", lambda d: _deep(100_000), "nests deeper"),
        ("policy.json", lambda d: json.dumps({**d, "algo": ["PPO"]}), "algo"),
        (
            "policy.json",
            lambda d: json.dumps({**d, "policy_kwargs": {"net_arch": [1_000_000, 1_000_000]}}),
            "net_arch",
        ),
        (
            "policy.json",
            lambda d: json.dumps({**d, "policy_kwargs": {"net_arch": [4096] * 16}}),
            "net_arch needs",
        ),
    ],
)
def test_policy_documents_are_bounded_before_parsing(tmp_path, name, payload, match):
    from test_security import _policy_folder

    from mf_envs.train import load_policy

    folder = _policy_folder(tmp_path)
    p = folder / name
    p.write_text(payload(json.loads(p.read_text())))
    with pytest.raises(ValueError, match=match) as info:
        load_policy("Pendulum-v1", folder)
    assert name in str(info.value)


def test_policy_fifo_and_nan_weights_are_named(tmp_path):
    import threading

    pytest.importorskip("safetensors", reason="needs the train extra: pip install -e '.[train]'")
    pytest.importorskip("torch", reason="needs the train extra: pip install -e '.[train]'")

    from safetensors.torch import load_file, save_file
    from test_security import _policy_folder

    from mf_envs.train import load_policy

    folder = _policy_folder(tmp_path)
    norm = folder / "obs_normalization.json"
    norm.unlink()
    os.mkfifo(norm)
    # were the FIFO opened for reading, this writer would unblock it; the test must not hang
    timer = threading.Timer(10.0, lambda: open(norm, "w").close())
    timer.start()
    try:
        with pytest.raises(ValueError, match="obs_normalization.json.*not a regular file"):
            load_policy("Pendulum-v1", folder)
    finally:
        timer.cancel()
    norm.unlink()
    weights = folder / "policy.safetensors"
    state = load_file(weights)
    key = sorted(state)[0]
    state[key] = state[key].clone().fill_(float("nan"))
    save_file(state, weights)
    with pytest.raises(ValueError, match=f"policy.safetensors: tensor '{key}' holds NaN"):
        load_policy("Pendulum-v1", folder)


# ---------------------------------------------------------------------- hull files
def test_a_hull_member_declaring_a_huge_shape_is_refused_from_its_header(tmp_path):
    import io
    import zipfile

    import gymnasium as gym
    import numpy as np

    from mf_envs.physics.gowec.hydro import load_hull

    good = tmp_path / "good.npz"
    load_hull().save(good)
    evil = tmp_path / "evil.npz"
    with zipfile.ZipFile(good) as src, zipfile.ZipFile(evil, "w") as dst:
        for info in src.infolist():
            data = src.read(info)
            if info.filename == "omega.npy":
                buf = io.BytesIO()
                header = {"descr": "<f8", "fortran_order": False, "shape": (10**12,)}
                np.lib.format.write_array_header_1_0(buf, header)
                data = buf.getvalue() + b"\0" * 4096
            dst.writestr(info.filename, data)
    assert evil.stat().st_size < 10_000
    for make in (lambda: load_hull(evil), lambda: gym.make("FloatingGOWEC-v0", hull=str(evil))):
        with pytest.raises(ValueError, match=r"evil\.npz.*omega\.npy.*\(1000000000000,\)") as info:
            make()
        assert type(info.value) is ValueError


# ---------------------------------------------------------------------- configs
BAD_TRAIN_ENTRIES = {
    'normalize: "{"': "normalize",
    "normalize: {norm_obs: true, bogus: 1}": "normalize: unknown key 'bogus'",
    "learning_rate: [1, 2]": "learning_rate",
    "learning_rate: lin_abc": "learning_rate",
    "gamma: abc": "gamma",
    "gamma: .nan": "gamma",
    "n_steps: 0": "n_steps",
    "tensorboard_log: /tmp/elsewhere": "tensorboard_log",
    "env_kwargs: {bogus: 1}": "env_kwargs: 'bogus'",
    "n_envs: !!float 1e8": "n_envs",
    'policy_kwargs: "dict(net_arch=[1000000000])"': "net_arch",
    "env_wrapper: [{gymnasium.wrappers.TimeLimit: {bogus: 1}}]": "unknown argument 'bogus'",
    "clip_range: -1": "clip_range",
    "batch_size: 1.5": "batch_size",
    "policy: CnnPolicy": "policy",
    "not_a_key: 1": "'not_a_key'",
    "ent_coef: auto": "ent_coef",
}


@pytest.mark.parametrize("entry", list(BAD_TRAIN_ENTRIES))
def test_train_config_is_checked_in_one_pass_naming_the_key(tmp_path, capsys, entry):
    if entry == "ent_coef: auto":  # PPO refuses SAC's 'auto' once it knows the algorithm class
        pytest.importorskip("stable_baselines3", reason="needs the train extra")
    cfg = tmp_path / "bad.yml"
    cfg.write_text(f"GOWEC-v0:\n  n_timesteps: 64\n  {entry}\n")
    before = sorted(tmp_path.rglob("*"))
    assert main(["train", "GOWEC-v0", "--config", str(cfg), "--out", str(tmp_path / "r")]) == 2
    assert BAD_TRAIN_ENTRIES[entry] in _one_line(capsys)
    assert sorted(tmp_path.rglob("*")) == before  # refused before any folder is made


@pytest.mark.parametrize(
    "text",
    [
        "GOWEC-v0:\n  env_kwargs: " + "[" * 3000 + "]" * 3000 + "\n",
        "- " * 3000 + "1\n",
        "{a: " * 3000 + "1" + "}" * 3000 + "\n",
    ],
)
def test_deep_yaml_is_refused_by_the_loader(tmp_path, text):
    from mf_envs.sweep.config import load_config
    from mf_envs.train.config import load_hyperparams

    p = tmp_path / "deep.yml"
    p.write_text(text)
    for load in (load_config, lambda q: load_hyperparams("GOWEC-v0", q)):
        with pytest.raises(ValueError, match=r"deep\.yml nests deeper than 64"):
            load(p)


# ---------------------------------------------------------------------- CLI bounds, Ray
@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["render", "GOWEC-v0", "--out", "o.gif", "--steps", "100000000000000000000"], "--steps"),
        (["render", "GOWEC-v0", "--out", "o.gif", "--seed", "99999999999999999999"], "--seed"),
        (["train", "GOWEC-v0", "--timesteps", "1" + "0" * 30], "--timesteps"),
        (["train", "GOWEC-v0", "--eval-episodes", "100000000"], "--eval-episodes"),
        (["evaluate", "GOWEC-v0", "--episodes", "1e9"], "--episodes"),
        (["sweep", "x.yml", "--num-cpus", "100000000000"], "--num-cpus"),
    ],
)
def test_cli_counts_are_bounded(tmp_path, monkeypatch, capsys, argv, option):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2
    line = _one_line(capsys)
    assert f"argument {option}:" in line
    assert list(tmp_path.iterdir()) == []


def test_a_silent_ray_address_fails_fast_naming_it(tmp_path, capsys):
    import time

    from mf_envs._ray import probe_address

    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"address: no Ray cluster answers at '127\.0\.0\.1:1'"):
        probe_address("127.0.0.1:1", timeout=1.0)
    with pytest.raises(ValueError, match="address: expected HOST:PORT"):
        probe_address("127.0.0.1")
    assert time.perf_counter() - t0 < 5.0
    pytest.importorskip("ray", reason="needs the ray extra")
    cfg = tmp_path / "cfg.yml"
    cfg.write_text(SWEEP)
    out = tmp_path / "out"
    argv = ["sweep", str(cfg), "--address", "127.0.0.1:1", "--out", str(out), "--no-progress"]
    t0 = time.perf_counter()
    assert main(argv) == 2
    assert "'127.0.0.1:1'" in _one_line(capsys)
    assert time.perf_counter() - t0 < 30.0 and not out.exists()


def test_ray_usage_stats_are_off_unless_turned_on(monkeypatch):
    from mf_envs._ray import quiet_usage_stats

    monkeypatch.delenv("RAY_USAGE_STATS_ENABLED", raising=False)
    quiet_usage_stats()
    assert os.environ["RAY_USAGE_STATS_ENABLED"] == "0"
    monkeypatch.setenv("RAY_USAGE_STATS_ENABLED", "1")
    quiet_usage_stats()
    assert os.environ["RAY_USAGE_STATS_ENABLED"] == "1"


# ---------------------------------------------------------------------- envs name what was given
def test_errors_name_the_parameter_the_user_passed():
    import gymnasium as gym

    import mf_envs  # noqa: F401

    with pytest.raises(ValueError, match=r"^control_dt: must be >= 2e-06"):
        gym.make("GyroStabilizer-v0", control_dt=1e-6)
    with pytest.raises(ValueError, match="shear_modulus"):
        gym.make("Inchworm-v0", shear_modulus=3.96e9)


@pytest.mark.parametrize("env_id", ["GOWEC-v0", "Inchworm-v0"])
def test_a_fractional_max_episode_steps_is_refused_by_name_everywhere(env_id):
    """`max_episode_steps=100.0`: the env and its native vector env refuse it with a ValueError
    naming it; `gym.make` keeps the argument for its own TimeLimit (the env never sees it), whose
    TypeError names it too. None of them runs with it."""
    import gymnasium as gym

    import mf_envs  # noqa: F401

    with pytest.raises(TypeError, match="max_episode_steps"):
        gym.make(env_id, max_episode_steps=100.0)
    with pytest.raises(ValueError, match=r"^max_episode_steps: expected an integer, got 100\.0"):
        gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point",
                     max_episode_steps=100.0)  # fmt: skip
    assert gym.make(env_id, max_episode_steps=100).spec.max_episode_steps == 100


def test_vector_reset_options_and_action_shapes_are_named():
    import gymnasium as gym
    import numpy as np

    import mf_envs  # noqa: F401

    envs = gym.make_vec("GOWEC-v0", num_envs=2, vectorization_mode="vector_entry_point")
    for bad in (1, "abc", [("a", 1)]):
        with pytest.raises(ValueError, match=r"^options: expected a dict or None"):
            envs.reset(options=bad)
    envs.reset(seed=0)
    n = envs.single_action_space.shape[0]
    with pytest.raises(ValueError, match=rf"^actions: expected shape \(2, {n}\), got shape \(2,\)"):
        envs.step(np.zeros(2 * n))
    envs.step(np.zeros((2, n)))
    envs.close()
    env = gym.make("GOWEC-v0")
    env.reset(seed=0)
    with pytest.raises(
        ValueError, match=rf"^action: expected shape \({n},\), got shape \({n}, 1\)"
    ):
        env.step(np.zeros((n, 1)))
    env.step(np.zeros(n))
    env.close()


@pytest.mark.parametrize(
    ("extra", "key"),
    [
        ({"mode": "random", "samples": 2, "random": {"x": {"low": "a", "high": 1}}}, "random.x"),
        ({"mode": "random", "samples": 2, "sampler_seed": -1, "random": {}}, "sampler_seed"),
        ({"plot": {"log": "yes"}}, "plot.log"),
        ({"mode": "random", "samples": 2, "random": {"x": {"choices": []}}}, "random.x"),
    ],
)
def test_sweep_config_values_are_named(extra, key):
    from mf_envs.sweep.config import parse_config

    base = {"env_id": "GOWEC-v0", "seeds": [0], "controllers": ["baseline"]}
    with pytest.raises(ValueError, match=rf"^config: {key}:"):
        parse_config({**base, **extra})


@pytest.mark.parametrize(
    ("overrides", "key"),
    [
        ({"lr": [1, 2]}, "lr"),
        ({"fcnet_hiddens": [10**9]}, "fcnet_hiddens"),
        ({"num_envs_per_env_runner": 1e8}, "num_envs_per_env_runner"),
        ({"env_kwargs": "x"}, "env_kwargs"),
    ],
)
def test_rllib_settings_are_checked_naming_the_key(overrides, key):
    from mf_envs.train.rllib import ppo_settings

    with pytest.raises(ValueError, match=rf"^config: GOWEC-v0: {key} must be"):
        ppo_settings("GOWEC-v0", overrides)


def test_a_whitelisted_wrapper_refusing_its_kwargs_is_named():
    import functools

    pytest.importorskip("stable_baselines3", reason="needs the train extra")

    from gymnasium.wrappers import TimeLimit

    from mf_envs.train.vec import _make_wrapped

    bad = functools.partial(TimeLimit, max_episode_steps="abc")
    with pytest.raises(ValueError, match=r"^env_wrapper: TimeLimit: .*max_episode_steps"):
        _make_wrapped("GOWEC-v0", (bad,))
