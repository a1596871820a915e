"""A policy says what env it was trained on: `meta.json` records every constructor argument and
the env's first observations (`train.provenance`); `load_policy` and `mf-envs evaluate` warn,
naming what differs, when the env they are used on is another."""

from __future__ import annotations

import json
import shutil
import warnings

import pytest

pytest.importorskip("stable_baselines3", reason="needs the train extra: pip install -e '.[train]'")
pytest.importorskip("safetensors", reason="needs the train extra: pip install -e '.[train]'")

from mf_envs.cli import main  # noqa: E402
from mf_envs.train.policy import load_policy, policy_dir  # noqa: E402
from mf_envs.train.provenance import (  # noqa: E402
    PolicyEnvWarning,
    env_differences,
    env_record,
    full_kwargs,
)


def _copy(tmp_path, **meta_changes):
    """The shipped GOWEC-v0 policy copied to tmp_path/pol with `meta.json` fields replaced."""
    folder = tmp_path / "pol"
    shutil.copytree(policy_dir("GOWEC-v0"), folder)
    meta = json.loads((folder / "meta.json").read_text())
    for key, value in meta_changes.items():
        if value is None:
            meta.pop(key)
        else:
            meta[key] = value(meta) if callable(value) else value
    (folder / "meta.json").write_text(json.dumps(meta))
    return folder


def test_full_kwargs_are_the_class_defaults_overlaid_by_the_id_and_the_user():
    base = full_kwargs("GOWEC-v0")
    assert base["wave_period"] == 6.0 and "render_mode" not in base
    assert full_kwargs("GOWEC-v0", {"wave_period": 7.0})["wave_period"] == 7.0
    assert full_kwargs("GyroStabilizer-JONSWAP-v0")["significant_wave_height"] == 0.8


def test_the_record_of_todays_env_shows_no_difference():
    meta = {**env_record("GOWEC-v0"), "hyperparams": {"env_kwargs": {}}}
    assert env_differences(meta, "GOWEC-v0") == []


def test_a_changed_argument_is_named(tmp_path):
    folder = _copy(tmp_path, env_kwargs_full=lambda m: {**m["env_kwargs_full"], "wave_period": 7})
    with pytest.warns(PolicyEnvWarning, match="wave_period: trained with 7, now 6.0"):
        load_policy("GOWEC-v0", folder)


def test_moved_physics_shows_in_the_probe(tmp_path):
    folder = _copy(tmp_path, env_probe=lambda m: [x + 1e-3 for x in m["env_probe"]])
    with pytest.warns(PolicyEnvWarning, match="first observations under the zero action moved"):
        load_policy("GOWEC-v0", folder)


def test_a_policy_without_a_record_is_flagged(tmp_path):
    folder = _copy(tmp_path, env_kwargs_full=None)
    with pytest.warns(PolicyEnvWarning, match="records no env kwargs"):
        load_policy("GOWEC-v0", folder)


def test_the_shipped_policy_matches_todays_env():
    with warnings.catch_warnings():
        warnings.simplefilter("error", PolicyEnvWarning)
        load_policy("GOWEC-v0")


def test_evaluate_prints_the_warning_on_one_line(capsys, tmp_path):
    folder = _copy(tmp_path, env_kwargs_full=lambda m: {**m["env_kwargs_full"], "gamma": 2.0})
    code = main(["evaluate", "GOWEC-v0", "--policy", str(folder), "--episodes", "1",
                 "--out", str(tmp_path / "ev")])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0
    lines = [ln for ln in err.splitlines() if "warning:" in ln]
    assert len(lines) == 1 and "gamma: trained with 2.0, now 3.3" in lines[0]


@pytest.mark.slow
@pytest.mark.parametrize("env_id", sorted(p.name for p in policy_dir("x").parent.iterdir()))
def test_every_shipped_policy_reproduces_its_recorded_evaluation(env_id):
    """A shipped policy's training-time evaluation (its meta.json: the primary metric's mean on
    the evaluation seeds), re-run today on the env it records, gives the same figure (1e-6), so
    the figure the docs quote for it still holds."""
    import numpy as np

    from mf_envs.train.evaluate import episodes

    policy = load_policy(env_id)
    ev = policy.meta["evaluation"]
    per_seed = episodes(env_id, lambda env: policy, ev["seeds"],
                        policy.meta["hyperparams"].get("env_kwargs") or {})  # fmt: skip
    now = np.mean([m[ev["metric"]] for m in per_seed])
    assert now == pytest.approx(ev["ppo"]["mean"], rel=1e-6)
