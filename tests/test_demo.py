"""`mf-envs demo`, the README's first command: the real demo runs to its end and writes every
file it names (no stand-in), and the CLI tells a bug from a user mistake."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from mf_envs.cli import main


def _written(stdout: str) -> list[str]:
    """The files named by the CLI's closing `wrote N files:` block."""
    lines = stdout.splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith("wrote "))
    return [ln.strip() for ln in lines[start + 1 :] if ln.startswith("  ")]


@pytest.mark.slow
def test_the_real_quick_demo_writes_every_file_it_names(tmp_path):
    """`mf-envs demo --quick` in a new process: exit 0, every named file a readable, non-blank
    picture or GIF, one picture at least per demo module."""
    from mf_envs.benchmarks import demos
    from mf_envs.benchmarks._registry import discover

    env = {**os.environ, "MPLBACKEND": "Agg"}
    res = subprocess.run(
        [sys.executable, "-m", "mf_envs.cli", "demo", "--quick", "--out", "out"],
        cwd=tmp_path, capture_output=True, text=True, env=env, timeout=1800,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr[-3000:]
    files = _written(res.stdout)
    assert len(files) >= len(discover(demos.__name__))
    for name in files:
        path = tmp_path / name
        assert path.parent == tmp_path / "out" and path.stat().st_size > 0, name
        with Image.open(path) as im:
            pixels = np.asarray(im.convert("L"))
        assert pixels.std() > 1.0, f"{name} is blank"


def _raise(exc: Exception):
    def run(out, quick=False, only=None):
        raise exc

    return run


def test_a_bug_in_the_demo_is_not_reported_as_the_users_mistake(capsys, monkeypatch):
    """A ValueError from inside numpy (the reduction over an empty array the floating GOWEC's
    demo once hit) is a bug: traceback, one line saying so, status 1, not the 2 of a mistake."""
    from mf_envs.benchmarks import demos

    def run(out, quick=False, only=None):
        return [Path(str(np.zeros(0).max()))]

    monkeypatch.setattr(demos, "run", run)
    code = main(["demo", "--out", "unused"])
    err = capsys.readouterr().err
    assert code == 1
    assert "Traceback" in err and "zero-size array" in err
    assert err.strip().splitlines()[-1].startswith("mf-envs demo: internal error")


def test_a_validation_error_of_the_library_stays_a_one_line_mistake(capsys, tmp_path):
    """A ValueError that the package raises on purpose (a baseline kind the env does not have)
    is the user's: one line naming the parameter, status 2."""
    code = main(["render", "GOWEC-v0", "--out", str(tmp_path / "a.gif"),
                 "--policy", "baseline:no_such_kind"])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert "kind" in err and "no_such_kind" in err


def test_an_unexpected_exception_is_a_bug_with_its_traceback(capsys, monkeypatch):
    from mf_envs.benchmarks import demos

    monkeypatch.setattr(demos, "run", _raise(KeyError("trial_id")))
    code = main(["demo", "--out", "unused"])
    err = capsys.readouterr().err
    assert code == 1 and "Traceback" in err and "KeyError" in err
