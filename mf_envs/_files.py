"""Reading config files and naming output files safely.

- `load_yaml`: `yaml.safe_load` (no Python tags, nothing executed) of a file of at most
  `MAX_YAML_BYTES` that expands to at most `MAX_YAML_NODES` values: a 1.5 KB "billion laughs"
  file of nested aliases expands to gigabytes when walked, so its composed graph (aliases still
  shared) is measured before anything is built, and it is refused in milliseconds.
- `safe_name`: a name that becomes part of a file name (a sweep's `name`, a plot metric, an env id
  used as a folder) must be one plain path component: no separator, no `..`, no leading dot.
- `inside`: the resolved path must stay inside the output folder it was given.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import yaml

MAX_YAML_BYTES = 1 << 20  # 1 MiB: the shipped configs are a few KB
MAX_YAML_NODES = 100_000  # values once aliases are expanded; the shipped configs have < 1,000
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.+=,-]{0,127}")


def _expanded_size(node: yaml.Node, what: str, memo: dict[int, int], path: set[int]) -> int:
    """Nodes in `node` once every alias is expanded (the composed graph shares them)."""
    key = id(node)
    if key in memo:
        return memo[key]
    if key in path:
        raise ValueError(f"{what}: a YAML alias refers to itself (an endless document); refused")
    n = 1
    if isinstance(node, (yaml.SequenceNode, yaml.MappingNode)):
        path.add(key)
        items = node.value if isinstance(node, yaml.SequenceNode) else sum(node.value, ())
        for child in items:
            n += _expanded_size(child, what, memo, path)
            if n > MAX_YAML_NODES:
                break
        path.discard(key)
    memo[key] = n
    return n


def load_yaml(path: str | Path, what: str = "config") -> Any:
    """The YAML document in `path`, read safely (see the module docstring); ValueError naming
    `what` for a missing, oversized, malformed or alias-bomb file."""
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{what}: no such file {str(p)!r}")
    size = p.stat().st_size
    if size > MAX_YAML_BYTES:
        raise ValueError(f"{what}: {p} is {size} bytes, more than {MAX_YAML_BYTES}")
    try:
        text = p.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{what}: cannot read {p} ({exc})") from exc
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        n = _expanded_size(node, what, {}, set())
        if n > MAX_YAML_NODES:
            raise ValueError(
                f"{what}: {p} expands to more than {MAX_YAML_NODES} YAML nodes (aliases of "
                "aliases: an alias bomb); refused"
            )
        return loader.construct_document(node)
    except yaml.YAMLError as exc:
        raise ValueError(f"{what}: {p} is not valid YAML ({' '.join(str(exc).split())})") from exc
    finally:
        loader.dispose()


def safe_name(field: str, value: Any) -> str:
    """`value` as one plain file-name component (letters, digits, `_ . + = , -`, not starting
    with a dot, at most 128 characters); ValueError naming `field` otherwise (`..`, `/`, `\\`)."""
    if not isinstance(value, str) or not _NAME.fullmatch(value) or ".." in value:
        raise ValueError(
            f"{field}: {value!r} cannot name a file: use letters, digits and _ . + = , - only "
            "(no path separator, no '..', not starting with a dot)"
        )
    return value


def inside(folder: str | Path, path: str | Path, field: str) -> Path:
    """`path` resolved; ValueError naming `field` unless it lies inside `folder` (resolved)."""
    root = Path(folder).resolve()
    p = Path(path).resolve()
    if p != root and root not in p.parents:
        raise ValueError(f"{field}: {str(path)!r} would be written outside {str(root)!r}")
    return p
