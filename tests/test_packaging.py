"""The package as others cite and reuse it: one version everywhere (pyproject, `__version__`,
CITATION.cff, CHANGELOG), a valid-looking citation of the package and of the dissertation, an
MIT LICENSE, a docs page for every env id, a wheel that carries `py.typed`, and the README and
docs/api.md naming every baseline controller."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import yaml

import mf_envs
from mf_envs.envs import ENV_SPECS

ROOT = Path(__file__).resolve().parent.parent
DISSERTATION = "Dynamic modeling and analysis of gyroscopic multibody systems and flexible robots"


def _pyproject() -> dict:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        tomllib = pytest.importorskip("tomli")
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


def test_one_version_everywhere():
    version = _pyproject()["project"]["version"]
    assert mf_envs.__version__ == version
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert str(cff["version"]) == version
    changelog = (ROOT / "CHANGELOG.md").read_text()
    assert "## [Unreleased]" in changelog
    assert f"## [{version}]" in changelog


def test_citation_cites_the_package_and_the_dissertation():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software"
    assert {"message", "title", "authors"} <= set(cff) and cff["license"] == "MIT"
    (thesis,) = [r for r in cff["references"] if r["type"] == "thesis"]
    assert thesis["title"] == DISSERTATION and thesis["year"] == 2017
    assert thesis["authors"] == [{"family-names": "Rios", "given-names": "Oscar"}]
    assert "San Diego" in thesis["institution"]["name"]
    assert DISSERTATION in (ROOT / "README.md").read_text()  # the README's Citing agrees


def test_license_is_mit_as_pyproject_says():
    assert _pyproject()["project"]["license"] == {"text": "MIT"}
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License") and "the mf_envs authors" in text


def test_docs_nav_has_a_page_for_every_env_id():
    nav = yaml.safe_load((ROOT / "mkdocs.yml").read_text())["nav"]
    (envs,) = [item["Environments"] for item in nav if "Environments" in item]
    pages = {next(iter(p.values())) for p in envs}
    assert pages == {f"envs/{env_id}.md" for env_id in ENV_SPECS}


def test_wheel_carries_py_typed_and_the_license(tmp_path):
    pytest.importorskip("build", reason="needs the release extra: pip install -e '.[release]'")
    out = subprocess.run(
        [sys.executable, "-m", "build", "--wheel", "--outdir", str(tmp_path), str(ROOT)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    (wheel,) = tmp_path.glob("mf_envs-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert "mf_envs/py.typed" in names
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    assert not [n for n in names if "__pycache__" in n or n.endswith((".nbi", ".nbc"))]


@pytest.mark.parametrize("env_id", list(ENV_SPECS))
def test_readme_and_api_list_every_baseline(env_id):
    """The README's env table names each env's default baseline, and docs/api.md's env table and
    its baseline list name every registered kind, the default first (the stabilizer's "rate"
    was once missing from both)."""
    from mf_envs import controllers

    kinds = controllers.baseline_kinds(env_id)
    readme = (ROOT / "README.md").read_text().splitlines()
    row = next(ln for ln in readme if ln.startswith(f"| `{env_id}` | "))
    assert f"| `{kinds[0]}` |" in row
    api_lines = (ROOT / "docs" / "api.md").read_text().splitlines()
    row = next(ln for ln in api_lines if ln.startswith(f"| `{env_id}` | ") and ln.count(" | ") >= 6)
    baselines = row.rstrip(" |").rsplit(" | ", 1)[1]
    assert baselines.startswith(f'`"{kinds[0]}"`')  # the default first
    assert [k for k in kinds if f'`"{k}"`' not in baselines] == []
    api = (ROOT / "docs" / "api.md").read_text()
    section = api[api.index("## Baseline controllers") :]
    (item,) = [p for p in section.split("\n- ") if p.startswith(f"`{env_id}`:")]
    assert [k for k in kinds if f'`"{k}"`' not in item] == []
