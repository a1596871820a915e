"""The RL benchmark's tasks: per id its scene, budgets, baselines, test conditions and score.

Test conditions (docs/benchmark.md, "Test conditions"): a test seed s in `TEST_SEEDS`
(20000-20019, never used by training: training envs use the run's seed and the rows after it,
its evaluation checks seed + 10000) sets the episode's start (`reset(seed=s)`) and draws its
scene:
- the marine ids (`GyroStabilizer-JONSWAP-v0`, `FloatingGOWEC-JONSWAP-v0`): a new irregular-sea
  realisation of the id's spectrum per seed (the env draws it from `reset(seed=s)`);
- the soft robots (`SCENE_DRAWN`): the declared randomisation ranges of the env
  (`EnvDeclaration.randomize`: friction, body stiffness and mass, fluid drag), one draw per test
  seed from its own generator (`test_kwargs`), made as `train.randomize.DomainRandomization`
  draws them (`Randomizer.sample`). Training runs on the nominal scene (the shipped configs),
  or on draws in the same ranges from the training seeds with DomainRandomization.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

TEST_SEEDS = tuple(range(20_000, 20_020))
SCENE_DRAWN = ("Inchworm-v0", "Serpentine-v0", "Eel-v0")
CONDITION_STREAM = 45_001  # the test scene's generator: default_rng([seed, CONDITION_STREAM])
MARINE_BUDGETS = {"ppo": (1_000_000, 10_000_000), "sbx_sac": (1_000_000,)}
SOFT_BUDGETS = {"ppo": (1_000_000,)}


@dataclass(frozen=True)
class Task:
    """A benchmark task on a registered id (its scene: the id's spec kwargs plus `env_kwargs`):
    budgets (algorithm -> env-steps per run), baselines, and the score with its ceiling.

    Score per test episode: with `reference_kwargs`, 1 - metric / metric of the same seed in
    the reference scene (the stabilizer: rotor off); with `ceiling_scaled`, metric / the id's
    ceiling for the episode's scene (`EnvDeclaration.ceiling`, e.g. a sea's power bound); else
    the metric itself (the soft robots' speed, m/s)."""

    name: str
    env_id: str
    env_kwargs: dict[str, Any]
    eval_seconds: float | None  # None: the id's own episode
    budgets: dict[str, tuple[int, ...]]
    baselines: tuple[str, ...]
    ceiling: float
    ceiling_note: str
    score_name: str
    reference_kwargs: Callable[[dict[str, Any]], dict[str, Any]] | None = field(repr=False)
    metric: str | None = None  # the episode metric scored (None: the env's primary metric)
    ceiling_scaled: bool = False


def rotor_off(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The stabilizer's reference scene: the same sea with the rotor off."""
    return {**kwargs, "effects": tuple(e for e in kwargs["effects"] if e != "gyroscopic")}


def _stabilizer_irregular() -> Task:
    """GyroStabilizer-JONSWAP-v0: its scene's kwargs (the episode length is the protocol's,
    `eval_seconds`) and its ceiling."""
    from mf_envs.envs import declaration

    env_id = "GyroStabilizer-JONSWAP-v0"
    decl = declaration(env_id)
    kw = {k: v for k, v in decl.kwargs.items() if k != "episode_seconds"}
    return Task(
        name="stabilizer_irregular",
        env_id=env_id,
        env_kwargs=kw,
        eval_seconds=120.0,
        budgets=MARINE_BUDGETS,
        baselines=("zero", "random", *_classical(env_id)),
        ceiling=float(decl.ceiling.value),
        ceiling_note="RMS roll reduction 1 (no roll left); no causal bound computed",
        score_name="rms_roll_reduction",
        reference_kwargs=rotor_off,
    )


def _stabilizer_resonance() -> Task:
    """The default scene (regular beam wave at the roll resonance): the easy task; a test seed
    sets only the wave's phase and the start, so its 20 episodes are nearly one."""
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    irregular = _stabilizer_irregular()
    return replace(irregular, name="stabilizer_resonance", env_id="GyroStabilizer-v0",
                   env_kwargs={"effects": tuple(DEFAULT_EFFECTS)},
                   baselines=("zero", "random", *_classical("GyroStabilizer-v0")),
                   ceiling=1.0)  # fmt: skip


def _gowec_irregular() -> Task:
    """FloatingGOWEC-JONSWAP-v0: mean net electrical power over the episode's second half as a
    fraction of the id's ceiling for that episode's sea (`gowec_v1.task.net_power_ceiling`)."""
    return Task(
        name="gowec_irregular",
        env_id="FloatingGOWEC-JONSWAP-v0",
        env_kwargs={},
        eval_seconds=120.0,
        budgets=MARINE_BUDGETS,
        baselines=("zero", "random", *_classical("FloatingGOWEC-JONSWAP-v0")),
        ceiling=1.0,
        ceiling_note="net power / the sea's `net_power_ceiling` (loss-inclusive, loose)",
        score_name="net_power_of_ceiling",
        reference_kwargs=None,
        metric="net_power",
        ceiling_scaled=True,
    )


def _gowec_regular() -> Task:
    """FloatingGOWEC-v0's default regular sea (a = 1 m, T = 6 s): the GOWEC's easy task, scored
    as `gowec_irregular` (a test seed sets only the wave's phase)."""
    return replace(_gowec_irregular(), name="gowec_regular", env_id="FloatingGOWEC-v0")


def _soft(env_id: str, name: str) -> Callable[[], Task]:
    """A soft robot's task: its speed (m/s) on the id's own episode, scene drawn per seed."""

    def make() -> Task:
        return Task(name=name, env_id=env_id, env_kwargs={}, eval_seconds=None,
                    budgets=SOFT_BUDGETS, baselines=("zero", "random", *_classical(env_id)),
                    ceiling=math.nan, ceiling_note="no ceiling derived", score_name="speed_m_s",
                    reference_kwargs=None, metric="speed")  # fmt: skip

    return make


def _classical(env_id: str) -> tuple[str, ...]:
    from mf_envs.controllers import baseline_kinds

    return tuple(baseline_kinds(env_id))


TASKS: dict[str, Callable[[], Task]] = {
    "stabilizer_irregular": _stabilizer_irregular,
    "stabilizer_resonance": _stabilizer_resonance,
    "gowec_irregular": _gowec_irregular,
    "gowec_regular": _gowec_regular,
    "inchworm": _soft("Inchworm-v0", "inchworm"),
    "serpentine": _soft("Serpentine-v0", "serpentine"),
    "eel": _soft("Eel-v0", "eel"),
}
# the headline ids' tasks (`mf-envs bench rl --all`)
HEADLINE = {
    "GyroStabilizer-JONSWAP-v0": "stabilizer_irregular",
    "FloatingGOWEC-JONSWAP-v0": "gowec_irregular",
    "Inchworm-v0": "inchworm",
    "Serpentine-v0": "serpentine",
    "Eel-v0": "eel",
}


def test_kwargs(task: Task, seed: int) -> dict[str, Any]:
    """The env kwargs of test seed `seed` (module docstring): the task's scene, its episode
    length, and for `SCENE_DRAWN` ids a draw of the declared randomisation ranges."""
    kw = dict(task.env_kwargs)
    if task.eval_seconds is not None:  # gym.make without its TimeLimit: episode_seconds ends it
        kw.update(episode_seconds=task.eval_seconds, max_episode_steps=-1)
    if task.env_id in SCENE_DRAWN:
        from mf_envs.train.randomize import Randomizer

        draw = Randomizer(task.env_id, kw).sample(np.random.default_rng([seed, CONDITION_STREAM]))
        kw.update(draw)
    return kw


# ------------------------------------------------------------------------------- evaluation
class RandomAction:
    """Uniform random actions from a seeded generator (one per episode)."""

    def __init__(self, space: Any, seed: int) -> None:
        self.space, self.rng = space, np.random.default_rng(seed)

    def reset(self) -> None:
        return None

    def predict(self, obs: Any, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return self.rng.uniform(self.space.low, self.space.high).astype(self.space.dtype), None


class ZeroAction(RandomAction):
    def predict(self, obs: Any, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.zeros(self.space.shape, self.space.dtype), None


def episode(task: Task, kwargs: dict[str, Any], kind: Any, seed: int, run: Any = None) -> dict:
    """The metrics of one test episode of `kind` (a baseline, "random", "zero", a factory
    `kind(env) -> controller` (a reference, `benchmarks.references`), or the policy in folder
    `run`) in the scene `kwargs` from `reset(seed=seed)` (`evaluate.run_episode`: its metrics,
    "return" included), plus "ceiling": the id's ceiling for that scene (nan without)."""
    import gymnasium as gym

    from mf_envs.controllers import make_baseline
    from mf_envs.envs import declaration
    from mf_envs.train.evaluate import run_episode
    from mf_envs.train.policy import load_policy

    env = gym.make(task.env_id, **kwargs)
    try:
        if run is not None:
            ctrl: Any = load_policy(task.env_id, run)
        elif callable(kind):
            ctrl = kind(env)
        elif kind in ("random", "zero"):
            ctrl = (RandomAction if kind == "random" else ZeroAction)(env.action_space, seed)
        else:
            ctrl = make_baseline(env, kind)
        m = dict(run_episode(task.env_id, env, ctrl, seed))
        if task.metric == "speed" and "speed" not in m:  # the inchworm: advance per step
            from mf_envs.benchmarks.headline import inchworm_speed

            m["speed"] = inchworm_speed(env, m)
        ceiling = declaration(task.env_id).ceiling
        m["ceiling"] = math.nan if ceiling is None else float(ceiling.of(env))
        return m
    finally:
        env.close()


def score_episode(task: Task, m: dict[str, float], kw: dict[str, Any], seed: int) -> float:
    """The task's score of one episode's metrics `m` (scene `kw`, seed `seed`; `Task`)."""
    from mf_envs.train.evaluate import primary_metric

    value = float(m[task.metric or primary_metric(task.env_id).name])
    if task.reference_kwargs is not None:
        return 1.0 - value / _reference(task, task.reference_kwargs(kw), seed)
    return value / m["ceiling"] if task.ceiling_scaled else value


def _reference(task: Task, kw: dict[str, Any], seed: int) -> float:
    """The scored metric of the zero action in the reference scene `kw` (cached per scene)."""
    from mf_envs.train.evaluate import primary_metric

    key = (task.env_id, repr(sorted(kw.items())), seed)
    if key not in _REFERENCE:
        m = episode(task, kw, "zero", seed)
        _REFERENCE[key] = float(m[task.metric or primary_metric(task.env_id).name])
    return _REFERENCE[key]


_REFERENCE: dict[tuple[str, str, int], float] = {}


def test_episodes(
    task: Task, kind: Any, run: Any = None, seeds: tuple[int, ...] = TEST_SEEDS
) -> tuple[np.ndarray, np.ndarray]:
    """(score, episode return) of `kind` (as `episode`'s) on each test seed's condition
    (`test_kwargs`)."""
    scores, returns = [], []
    for s in seeds:
        kw = test_kwargs(task, s)
        m = episode(task, kw, kind, s, run)
        scores.append(score_episode(task, m, kw, s))
        returns.append(float(m["return"]))
    return np.array(scores), np.array(returns)


def episode_scores(
    task: Task, kind: str, run: Any = None, seeds: tuple[int, ...] = TEST_SEEDS
) -> np.ndarray:
    """The task's score of `kind` on each test seed (`test_episodes`)."""
    return test_episodes(task, kind, run, seeds)[0]
