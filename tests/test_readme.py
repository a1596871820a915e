"""The README is a front door that cannot go stale: at most 250 lines, its Python examples print
what it says they print, its table is the one its results file generates, every picture it shows
exists, and (slow) the results file is what the measuring command measures today."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _examples() -> list[tuple[str, str]]:
    """(code, expected stdout) of each ```python block followed by 'prints' and a ```text block."""
    pat = re.compile(r"```python\n(.*?)```\s*\n+prints\s*\n+```text\n(.*?)```", re.S)
    return pat.findall(README)


def test_the_readme_is_at_most_250_lines():
    assert len(README.splitlines()) <= 250


def test_the_readme_has_its_two_quickstart_commands():
    block = README.split("## Quickstart", 1)[1].split("```bash\n", 1)[1].split("```", 1)[0]
    lines = [ln for ln in block.splitlines() if ln.strip()]
    assert lines == ["pip install -e . && mf-envs demo",
                     'pip install -e ".[dev]" && python -m pytest -n 2']  # fmt: skip


@pytest.mark.parametrize("code, expected", _examples() or [("", "")])
def test_each_example_prints_what_the_readme_says(tmp_path, code, expected):
    assert code, "the README has no example with its printed output"
    env = {**os.environ, "MPLBACKEND": "Agg"}
    res = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600, env=env)  # fmt: skip
    assert res.returncode == 0, res.stderr[-2000:]
    assert res.stdout == expected


def test_the_env_table_is_generated_from_its_results_file():
    from mf_envs.benchmarks import headline

    result = json.loads((ROOT / headline.RESULTS).read_text())
    refs_file = ROOT / headline.REFERENCES  # the oracle's headroom, where measured
    refs = json.loads(refs_file.read_text()) if refs_file.is_file() else None
    assert headline.splice(README, headline.table(result, refs)) == README
    assert {r["env_id"] for r in result["rows"]} == {row.env_id for row in headline.ROWS}


def test_every_registered_env_and_headline_id_is_in_the_table():
    from mf_envs.benchmarks import headline
    from mf_envs.envs import available_env_ids, task_ids

    assert set(available_env_ids()) | set(task_ids("headline")) <= {
        row.env_id for row in headline.ROWS
    }


def test_every_picture_and_local_link_of_the_readme_exists():
    targets = re.findall(r'src="([^"]+)"', README) + re.findall(r"\]\(([^)#]+)\)", README)
    local = [t for t in targets if not t.startswith("http")]
    assert local
    missing = [t for t in local if not (ROOT / t).exists()]
    assert not missing, missing


def test_no_page_or_module_names_an_issue_number():
    pat = re.compile(r"\bissues? ?#?\d+|\bissue-?\d+", re.I)
    hits = []
    for folder in ("mf_envs", "docs"):
        for path in (ROOT / folder).rglob("*"):
            if path.suffix in {".py", ".md", ".yml", ".json"} and path.is_file():
                for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                    if pat.search(line):
                        hits.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()[:80]}")
    assert not hits, "\n".join(hits[:20])


@pytest.mark.slow
def test_the_results_file_is_what_the_command_measures_today():
    """Every row of docs/results/headline.json re-measured: the same baseline, the same score on
    every seed (to 1e-9 relative; the episodes are deterministic)."""
    from mf_envs.benchmarks import headline

    result = json.loads((ROOT / headline.RESULTS).read_text())
    for row, stored in zip(headline.ROWS, result["rows"], strict=True):
        now = headline.measure(row, tuple(stored["seeds"]))
        assert now["baseline"] == stored["baseline"], row.env_id
        np.testing.assert_allclose(now["scores"], stored["scores"], rtol=1e-9, err_msg=row.env_id)
