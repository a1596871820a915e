"""Nothing loaded from a file runs code or writes outside the folder it was given (docs/design.md).

Each payload carries a marker file that must stay absent: training configs (wrapper imports,
Python YAML tags, policy_kwargs and normalize strings), sweep configs (names and metrics that
point outside the output folder, huge counts, alias bombs), policy folders (pickles renamed,
malformed JSON, bad statistics) and hull files. Where a payload is refused, the test also lists
the tree around the output folder to show that nothing was written beside it.
"""

from __future__ import annotations

import json
import os
import pickle
import zipfile
from pathlib import Path

import numpy as np
import pytest

from mf_envs.cli import main
from mf_envs.sweep.config import load_config
from mf_envs.train.config import WRAPPERS, load_hyperparams, wrapper_class


def tree(root: Path) -> set[str]:
    """Every file and folder below `root` (relative paths)."""
    return {str(p.relative_to(root)) for p in root.rglob("*")}


class _Touch:
    """A pickle payload: unpickling it creates `path`."""

    def __init__(self, path: Path) -> None:
        self.path = str(path)

    def __reduce__(self):
        return (os.system, (f"touch {self.path}",))


# ---------------------------------------------------------------------- training configs
def test_env_wrapper_payload_never_runs(tmp_path, capsys):
    """The reviewer's payload: a wrapper path naming a callable that runs a shell command."""
    marker = tmp_path / "MARKER"
    cfg = tmp_path / "evil.yml"
    cfg.write_text(
        "GOWEC-v0:\n  n_timesteps: 100\n"
        f'  env_wrapper: [{{pydoc.pipepager: {{cmd: "touch {marker}"}}}}]\n'
    )
    with pytest.raises(ValueError, match="env_wrapper"):
        load_hyperparams("GOWEC-v0", cfg)
    before = tree(tmp_path)
    assert main(["train", "GOWEC-v0", "--config", str(cfg), "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "env_wrapper" in err[0]
    assert not marker.exists()
    assert tree(tmp_path) == before  # nothing written, not even the run folder
    # the payload is real: the callable it names does run a command when called
    import pydoc

    pydoc.pipepager("", cmd=f"touch {marker}")
    assert marker.exists()


@pytest.mark.parametrize(
    "entry",
    [
        "env_wrapper: os.system",
        "env_wrapper: builtins.eval",
        "env_wrapper: {subprocess.call: {args: [touch, MARKER]}}",
        "env_wrapper: gymnasium.wrappers.TransformObservation",  # takes a callable
        "policy_kwargs: \"dict(activation_fn=__import__('os').system('touch MARKER'))\"",
        "normalize: \"__import__('os').system('touch MARKER')\"",
        'n_envs: !!python/object/apply:os.system ["touch MARKER"]',
    ],
)
def test_config_payloads_are_refused(tmp_path, monkeypatch, entry):
    monkeypatch.chdir(tmp_path)
    cfg = tmp_path / "evil.yml"
    cfg.write_text(f"GOWEC-v0:\n  n_timesteps: 100\n  {entry}\n")
    with pytest.raises(ValueError):
        load_hyperparams("GOWEC-v0", cfg)
    assert not (tmp_path / "MARKER").exists()


def test_only_whitelisted_wrappers_resolve():
    for name in WRAPPERS:
        assert callable(wrapper_class(name))
    with pytest.raises(ValueError, match="env_wrapper"):
        wrapper_class("mf_envs.train.config.wrapper_class")


# ---------------------------------------------------------------------- sweep configs
SWEEP = """env_id: GOWEC-v0
seeds: [0]
controllers: [baseline]
env_kwargs: {{episode_seconds: 1.0}}
{extra}
"""


@pytest.mark.parametrize(
    "extra",
    [
        "name: ../../escape_rel",
        "name: /tmp/escape_abs",
        "name: a/b",
        "name: ..",
        "name: .hidden",
        "plot: {metric: ../../escape_png}",
    ],
)
def test_sweep_names_cannot_leave_the_output_folder(tmp_path, monkeypatch, capsys, extra):
    work = tmp_path / "a" / "b" / "work"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    cfg = work / "evil.yml"
    cfg.write_text(SWEEP.format(extra=extra))
    with pytest.raises(ValueError, match="name|metric"):
        load_config(cfg)
    before = tree(tmp_path)
    for out in ([], ["--out", str(work / "out")]):
        assert main(["sweep", str(cfg), "--serial", "--no-progress", *out]) == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 2
    assert tree(tmp_path) == before
    assert not Path("/tmp/escape_abs").exists()


def test_a_sweep_writes_only_inside_its_output_folder(tmp_path, monkeypatch):
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    cfg = work / "ok.yml"
    cfg.write_text(SWEEP.format(extra="name: fine_name"))
    before = tree(tmp_path)
    assert main(["sweep", str(cfg), "--serial", "--no-progress", "--out", "out"]) == 0
    new = tree(tmp_path) - before
    assert new and all(p == "work/out" or p.startswith("work/out/") for p in new), new
    assert {"work/out/trials.csv"} <= new and any(p.endswith(".png") for p in new)


def test_alias_bomb_and_huge_counts_are_refused(tmp_path):
    bomb = 'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n'
    for prev, name in zip("abcdefgh", "bcdefghi"):
        bomb += f"{name}: &{name} [" + ",".join([f"*{prev}"] * 9) + "]\n"
    p = tmp_path / "bomb.yml"
    p.write_text(bomb)
    assert len(bomb) < 1500
    with pytest.raises(ValueError, match="alias bomb"):
        load_config(p)
    with pytest.raises(ValueError, match="alias bomb"):
        load_hyperparams("GOWEC-v0", p)
    p.write_text("a: &x [1, *x]\n")
    with pytest.raises(ValueError, match="refers to itself"):
        load_config(p)
    p.write_text(SWEEP.format(extra="").replace("[0]", "{start: 0, count: 2000000000}"))
    with pytest.raises(ValueError, match="seeds"):
        load_config(p)
    grid = "grid: {" + ", ".join(f"p{i}: [{', '.join(['1.0'] * 40)}]" for i in range(5)) + "}"
    p.write_text(SWEEP.format(extra=grid))
    with pytest.raises(ValueError, match="grid"):
        load_config(p)
    p.write_text(SWEEP.format(extra="mode: random\nsamples: 1000000000\nrandom: {}"))
    with pytest.raises(ValueError, match="samples"):
        load_config(p)
    p.write_bytes(b"#" * (2 << 20))
    with pytest.raises(ValueError, match="bytes"):
        load_config(p)


def test_unknown_controller_param_is_one_line(tmp_path, capsys):
    cfg = tmp_path / "c.yml"
    cfg.write_text(
        SWEEP.format(extra="name: c").replace(
            "controllers: [baseline]", "controllers: [{kind: baseline, params: {bogus: 1}}]"
        )
    )
    assert main(["sweep", str(cfg), "--serial", "--no-progress", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bogus" in err[0], err


# ---------------------------------------------------------------------- policies and ship
def test_ship_refuses_an_env_id_that_leaves_the_policy_folder(tmp_path, capsys):
    from mf_envs.train import ship

    run = tmp_path / "run"
    run.mkdir()
    (run / "meta.json").write_text(json.dumps({"env_id": "../../../../X", "evaluation": {}}))
    (run / "policy.json").write_text("{}")
    before = tree(tmp_path)
    assert ship.main([str(run), "--force"]) == 2
    assert "env_id" in capsys.readouterr().err
    assert tree(tmp_path) == before
    from mf_envs.train.trainer import ship_run

    with pytest.raises(ValueError, match="env_id"):
        ship_run(run, root=tmp_path / "policies")
    assert not (tmp_path / "policies").exists()


def _policy_folder(tmp_path: Path) -> Path:
    """A well-formed policy folder of a 2-obs, 1-action MLP (weights written by safetensors)."""
    pytest.importorskip("stable_baselines3", reason="needs the train extra")
    from gymnasium.spaces import Box
    from safetensors.torch import save_file
    from stable_baselines3.common.policies import ActorCriticPolicy

    from mf_envs.train.policy import FORMAT

    folder = tmp_path / "pol"
    folder.mkdir()
    box = {"shape": [2], "low": [-1.0, -1.0], "high": [1.0, 1.0]}
    act = {"shape": [1], "low": [-1.0], "high": [1.0]}
    desc = {
        "format": FORMAT,
        "algo": "PPO",
        "policy": "MlpPolicy",
        "observation_space": box,
        "action_space": act,
        "policy_kwargs": {"net_arch": [4]},
        "use_sde": False,
    }
    (folder / "policy.json").write_text(json.dumps(desc))
    pol = ActorCriticPolicy(
        Box(-1, 1, (2,), np.float32), Box(-1, 1, (1,), np.float32), lambda _: 0.0, net_arch=[4]
    )
    save_file(
        {k: v.contiguous() for k, v in pol.state_dict().items()}, folder / "policy.safetensors"
    )
    norm = {"mean": [0.0, 0.0], "var": [1.0, 1.0], "epsilon": 1e-8, "clip_obs": 10.0}
    (folder / "obs_normalization.json").write_text(json.dumps(norm))
    (folder / "meta.json").write_text(json.dumps({"env_id": "Pendulum-v1"}))
    return folder


def _edit(folder: Path, name: str, fn) -> None:
    p = folder / name
    p.write_text(json.dumps(fn(json.loads(p.read_text()))))


BAD_POLICY_FILES = {
    "meta.json holds a list": ("meta.json", lambda d: []),
    "meta env_id escapes": ("meta.json", lambda d: {"env_id": "../x"}),
    "no action_space": (
        "policy.json",
        lambda d: {k: v for k, v in d.items() if k != "action_space"},
    ),
    "low of wrong length": (
        "policy.json",
        lambda d: {**d, "observation_space": {**d["observation_space"], "low": [0.0]}},
    ),
    "nan bound": (
        "policy.json",
        lambda d: {**d, "action_space": {**d["action_space"], "high": ["nan"]}},
    ),
    "no mean": ("obs_normalization.json", lambda d: {k: v for k, v in d.items() if k != "mean"}),
    "mean too short": ("obs_normalization.json", lambda d: {**d, "mean": [0.0]}),
    "var negative": ("obs_normalization.json", lambda d: {**d, "var": [1.0, -1.0]}),
    "var a string": ("obs_normalization.json", lambda d: {**d, "var": ["a", "b"]}),
    "clip zero": ("obs_normalization.json", lambda d: {**d, "clip_obs": 0.0}),
}


@pytest.mark.parametrize("case", list(BAD_POLICY_FILES))
def test_bad_policy_files_fail_at_load_naming_the_file(tmp_path, case):
    from mf_envs.train import load_policy

    folder = _policy_folder(tmp_path)
    load_policy("Pendulum-v1", folder)  # the well-formed folder loads
    name, fn = BAD_POLICY_FILES[case]
    _edit(folder, name, fn)
    with pytest.raises(ValueError, match=name.replace(".", r"\.")):
        load_policy("Pendulum-v1", folder)


def test_policy_payloads_never_run(tmp_path, capsys):
    from mf_envs.train import load_policy

    folder = _policy_folder(tmp_path)
    marker = tmp_path / "PWNED"
    # a pickle and a torch.save file named .safetensors
    import torch

    for writer in (
        lambda p: p.write_bytes(pickle.dumps(_Touch(marker))),
        lambda p: torch.save({"x": _Touch(marker)}, p),
    ):
        writer(folder / "policy.safetensors")
        with pytest.raises(ValueError, match="policy.safetensors"):
            load_policy("Pendulum-v1", folder)
        args = ["evaluate", "Pendulum-v1", "--policy", str(folder), "--out", str(tmp_path / "e")]
        assert main(args) == 2
        assert len(capsys.readouterr().err.strip().splitlines()) == 1
    (folder / "policy.json").write_text("{not json")
    with pytest.raises(ValueError, match="policy.json"):
        load_policy("Pendulum-v1", folder)
    assert not marker.exists()
    pickle.loads(pickle.dumps(_Touch(marker)))  # the payload is real
    assert marker.exists()


# ---------------------------------------------------------------------- hull files
def test_hull_payloads_and_malformed_files(tmp_path):
    from mf_envs.physics.gowec.hydro import load_hull

    hull = load_hull()
    good = tmp_path / "good.npz"
    hull.save(good)
    marker = tmp_path / "PWNED"
    with np.load(good) as z:
        arrays = {k: z[k] for k in z.files}
    cases = {
        "npy named npz": lambda p: np.save(open(p, "wb"), np.arange(5.0)),
        "object array": lambda p: np.savez(
            p, **{**arrays, "stiffness": np.array([_Touch(marker)])}
        ),
        "array for a scalar": lambda p: np.savez(p, **{**arrays, "stiffness": np.ones(3)}),
        "truncated zip": lambda p: p.write_bytes(good.read_bytes()[:300]),
        "not a zip": lambda p: p.write_bytes(b"PK\x03\x04garbage"),
        "1e308 stiffness": lambda p: np.savez(p, **{**arrays, "stiffness": np.array(1e308)}),
        "string array": lambda p: np.savez(p, **{**arrays, "omega": np.array(["a"] * 5)}),
        "pickle": lambda p: p.write_bytes(pickle.dumps(_Touch(marker))),
    }
    for label, write in cases.items():
        p = tmp_path / f"{label.replace(' ', '_')}.npz"
        write(p)
        with pytest.raises(ValueError, match=p.name) as info:
            load_hull(p)
        assert type(info.value) is ValueError, label
    assert not marker.exists()


def test_gowec_v1_hull_file_kwarg_is_checked_at_make(tmp_path):
    import gymnasium as gym

    p = tmp_path / "bad.npz"
    with zipfile.ZipFile(p, "w") as z:
        z.writestr("x.txt", "not an array")
    with pytest.raises(ValueError, match="bad.npz"):
        gym.make("FloatingGOWEC-v0", hull=str(p))
