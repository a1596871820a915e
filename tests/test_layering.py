"""Layering (docs/design.md): frames and physics import no Gymnasium, SB3 or python-control, and
no module imports from a layer above its own."""

import ast
import subprocess
import sys
from pathlib import Path


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


# ---------------------------------------------------------------------- imports point down
# frames < physics < envs < controllers < train < sweep, benchmarks < cli (docs/design.md).
# Shared helpers (`mf_envs._*`, `effects`) sit below everything; `render` draws (it is used by the
# envs and imports only physics-level code); `cli` holds every command that ties layers together.
RANK = {
    "frames": 1, "physics": 2, "render": 2, "envs": 3, "controllers": 4, "train": 5,
    "sweep": 6, "benchmarks": 6, "cli": 7,
}  # fmt: skip
PACKAGE = Path(__file__).resolve().parents[1] / "mf_envs"


def _rank(module: str) -> int | None:
    parts = module.split(".")
    if parts[0] != "mf_envs" or len(parts) == 1:
        return None
    return 0 if parts[1].startswith("_") or parts[1] == "effects" else RANK.get(parts[1])


def upward_imports(root: Path = PACKAGE) -> list[str]:
    """Every import (also inside functions) of a higher layer from a lower one under `root`."""
    bad = []
    for f in sorted(root.rglob("*.py")):
        rel = f.relative_to(root.parent).with_suffix("")
        module = ".".join(rel.parts[:-1] if rel.name == "__init__" else rel.parts)
        mine = _rank(module)
        if mine is None:
            continue
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [node.module, *(f"{node.module}.{a.name}" for a in node.names)]
            else:
                continue
            for name in names:
                theirs = _rank(name)
                if theirs is not None and theirs > mine:
                    bad.append(f"{f.relative_to(root.parent)}:{node.lineno} imports {name}")
    return bad


def test_imports_point_down():
    assert upward_imports() == []


def test_the_layer_check_finds_an_upward_import(tmp_path):
    """The check above can fail: frames importing physics and a physics module importing the
    envs (inside a function) are reported."""
    pkg = tmp_path / "mf_envs"
    (pkg / "physics").mkdir(parents=True)
    (pkg / "physics" / "bad.py").write_text("def f():\n    from mf_envs.envs import base\n")
    (pkg / "frames.py").write_text("import mf_envs.physics\n")
    assert upward_imports(pkg) == [
        "mf_envs/frames.py:1 imports mf_envs.physics",
        "mf_envs/physics/bad.py:2 imports mf_envs.envs",
        "mf_envs/physics/bad.py:2 imports mf_envs.envs.base",
    ]
