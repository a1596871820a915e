"""Layering (docs/design.md): frames and physics import no Gymnasium, SB3 or python-control."""

import subprocess
import sys


def test_physics_imports_no_rl_or_control():
    code = (
        "import sys, pkgutil, importlib, mf_envs.frames, mf_envs.physics as P\n"
        "for m in pkgutil.iter_modules(P.__path__):\n"
        "    importlib.import_module('mf_envs.physics.' + m.name)\n"
        "rl = ('gymnasium', 'stable_baselines3', 'control', 'torch')\n"
        "bad = [m for m in rl if m in sys.modules]\n"
        "print(','.join(bad))\n"
    )
    # importing mf_envs.physics imports mf_envs/__init__ (which registers envs with gymnasium);
    # check the physics modules through a path that bypasses it
    code = "import sys, types\n" + _bypass() + code
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"physics layer imports: {out.stdout.strip()}"


def _bypass() -> str:
    # a bare namespace package for `mf_envs` so that its __init__ (env registration) is skipped
    return (
        "import importlib.util, pathlib\n"
        "spec = importlib.util.find_spec('mf_envs')\n"
        "pkg = types.ModuleType('mf_envs'); pkg.__path__ = list(spec.submodule_search_locations)\n"
        "sys.modules['mf_envs'] = pkg\n"
    )
