"""MkDocs hook (`mkdocs.yml`, `hooks:`): pages generated at build time, so they cannot go stale.

- `index.md`: the README, its `docs/` links made relative to the docs folder; `changelog.md`:
  CHANGELOG.md; `CITATION.cff` and `LICENSE` copied as they are (the README links to them).
- `envs/<ENV_ID>.md`: one page per registered env id (`mf_envs.envs.ENV_SPECS`), rendered by
  mkdocstrings from the env class's docstring (its Gymnasium-style page: description, spaces,
  rewards, starting state, episode end, arguments), then its native vector env's docstring.
"""

from __future__ import annotations

import re
from pathlib import Path

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parent.parent


def env_pages() -> dict[str, str]:
    """`envs/<ENV_ID>.md` -> Markdown, for every env id with its mkdocstrings blocks."""
    from mf_envs.envs import ALIASES, ENV_SPECS, VECTOR_SPECS

    pages = {}
    for env_id, entry in ENV_SPECS.items():
        old = [a for a, new in ALIASES.items() if new == env_id]
        lines = [
            f"# {env_id}",
            "",
            f'`gymnasium.make("{env_id}", **kwargs)` after `import mf_envs`; the keyword '
            "arguments are those of the class below.",
        ]
        if old:
            ids = ", ".join(f"`{a}`" for a in old)
            lines += ["", f"Deprecated id: {ids} (makes this env and warns, naming `{env_id}`)."]
        lines += ["", f"::: {entry.replace(':', '.')}", "    options:", "      members: false"]
        vec = VECTOR_SPECS.get(env_id)
        if vec is not None:
            lines += [
                "",
                "## Native vector env",
                "",
                f'`gymnasium.make_vec("{env_id}", num_envs=N, '
                'vectorization_mode="vector_entry_point", **kwargs)`:',
                "",
                f"::: {vec.replace(':', '.')}",
                "    options:",
                "      members: false",
                "      heading_level: 3",
            ]
        pages[f"envs/{env_id}.md"] = "\n".join(lines) + "\n"
    return pages


def readme_page() -> str:
    """The README as the site's home page (links into `docs/` made relative to it)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    text = re.sub(r"\]\(docs/", "](", text)
    text = text.replace("](CHANGELOG.md)", "](changelog.md)")
    return re.sub(r'src="docs/', 'src="', text)


def _root_file(name: str) -> str:
    return (ROOT / name).read_text(encoding="utf-8")


def on_files(files: Files, config: MkDocsConfig) -> Files:
    """Add the generated pages to the site's files."""
    generated = {
        "index.md": readme_page(),
        "changelog.md": _root_file("CHANGELOG.md"),
        "CITATION.cff": _root_file("CITATION.cff"),
        "LICENSE": _root_file("LICENSE"),
        **env_pages(),
    }
    for path, content in generated.items():
        files.append(File.generated(config, path, content=content))
    return files
