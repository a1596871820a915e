"""Reading config files and naming output files safely.

- `load_yaml`: `yaml.safe_load` (no Python tags, nothing executed) of a file of at most
  `MAX_YAML_BYTES` that expands to at most `MAX_YAML_NODES` values: a 1.5 KB "billion laughs"
  file of nested aliases expands to gigabytes when walked, so its composed graph (aliases still
  shared) is measured before anything is built, and it is refused in milliseconds.
- `safe_name`: a name that becomes part of a file name (a sweep's `name`, a plot metric, an env id
  used as a folder) must be one plain path component: no separator, no `..`, no leading dot.
- `inside`: the resolved path must stay inside the output folder it was given.
- `read_regular`: the bytes of a regular file (a FIFO, a device or a folder is refused without
  blocking on it), bounded in size; `check_depth`: JSON nesting bounded before it is parsed.
- `check_npz`: every member header of an `.npz` archive checked (dtype, shape, bytes) before
  `np.load` allocates an array of the shape it declares.
- Writing under an output folder the caller gave never follows a symbolic link the caller did
  not give: `make_dirs` creates the folders below it one by one and refuses a link among them,
  `atomic_path`/`write_atomic` write a temporary file in the same folder and `os.replace` it
  onto the target (a link or a non-regular file there is refused), so an interrupted write
  leaves the old file or the new one; `open_append` opens with `O_NOFOLLOW | O_APPEND`.
"""

from __future__ import annotations

import math
import os
import re
import stat
import tempfile
import zipfile
import zlib
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import yaml

MAX_YAML_BYTES = 1 << 20  # 1 MiB: the shipped configs are a few KB
MAX_YAML_NODES = 100_000  # values once aliases are expanded; the shipped configs have < 1,000
MAX_DEPTH = 64  # nesting of a YAML or JSON document; the shipped files nest < 6 deep
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
    `what` for a missing, oversized, too deeply nested, malformed or alias-bomb file."""
    p = Path(path)
    if not p.exists():
        raise ValueError(f"{what}: no such file {str(p)!r}")
    try:
        text = read_regular(p, MAX_YAML_BYTES, what).decode()
    except UnicodeDecodeError as exc:
        raise ValueError(f"{what}: cannot read {p} ({exc})") from exc
    loader = yaml.SafeLoader(text)
    try:
        _yaml_depth(text, p, what)  # PyYAML composes recursively: 3,000 levels overflow it
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


def _yaml_depth(text: str, p: Path, what: str) -> None:
    """ValueError naming `p` if the document nests deeper than MAX_DEPTH (the parser's events
    are produced without recursion, so this is safe where composing is not)."""
    depth = 0
    for event in yaml.parse(text, Loader=yaml.SafeLoader):
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            if depth > MAX_DEPTH:
                raise ValueError(f"{what}: {p} nests deeper than {MAX_DEPTH} levels; refused")
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1


_JSON_STRING = re.compile(rb'"(?:[^"\\]|\\.)*"', re.S)


def check_depth(data: bytes, where: str, limit: int = MAX_DEPTH) -> None:
    """ValueError naming `where` if the JSON text `data` nests deeper than `limit` (measured
    on the brackets outside strings, before the recursive parser sees it)."""
    b = np.frombuffer(_JSON_STRING.sub(b"", data), dtype=np.uint8)
    steps = np.isin(b, (ord("["), ord("{"))).astype(np.int64)
    steps -= np.isin(b, (ord("]"), ord("}")))
    if steps.size and int(np.cumsum(steps).max()) > limit:
        raise ValueError(f"{where} nests deeper than {limit} levels; refused")


MAX_NPZ_MEMBERS = 64


def check_npz(path: str | Path, max_bytes: int) -> None:
    """ValueError (or zipfile.BadZipFile) unless `path` is a zip of at most MAX_NPZ_MEMBERS
    `.npy` members whose headers declare a plain numeric dtype (no objects: nothing unpickled)
    and at most `max_bytes` of data each; only the headers are read. The caller names the
    file (the hull loaders: ValueError naming it)."""
    fmt = np.lib.format
    with zipfile.ZipFile(path) as z:
        members = z.infolist()
        if len(members) > MAX_NPZ_MEMBERS:
            raise ValueError(f"{len(members)} members, more than {MAX_NPZ_MEMBERS}")
        for info in members:
            name = info.filename
            if not name.endswith(".npy"):
                raise ValueError(f"member {name!r} is not an .npy array")
            with z.open(info) as fh:
                version = fmt.read_magic(fh)
                if version == (1, 0):
                    shape, _, dtype = fmt.read_array_header_1_0(fh, max_header_size=10_000)
                elif version == (2, 0):
                    shape, _, dtype = fmt.read_array_header_2_0(fh, max_header_size=10_000)
                else:
                    raise ValueError(f"member {name!r}: unsupported .npy version {version}")
            if dtype.hasobject or dtype.kind not in "biuf":
                raise ValueError(f"member {name!r}: dtype {dtype} is not a real number type")
            nbytes = math.prod(shape) * dtype.itemsize
            if nbytes > max_bytes:
                raise ValueError(
                    f"member {name!r}: its header declares shape {shape} ({nbytes} bytes), "
                    f"more than {max_bytes}"
                )


def read_npz(path: str | Path, max_bytes: int, read: Any, what: str, field: str = "hull") -> Any:
    """read(z) of the `.npz` archive at `path` (`check_npz` first, then opened without
    pickles). A missing file, a bad archive or read's KeyError/ValueError/TypeError become a
    ValueError naming `field`, the file and `what` it should have been."""
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{field}: file {str(p)!r} not found")
    try:
        check_npz(p, max_bytes)  # headers first: a declared (1e12,) is refused
        z = np.load(p, allow_pickle=False)
        if not isinstance(z, np.lib.npyio.NpzFile):
            raise ValueError("an .npy array, not an .npz archive of named arrays")
        with z:
            return read(z)
    except (KeyError, OSError, ValueError, TypeError, EOFError, zipfile.BadZipFile,
            zlib.error) as exc:  # fmt: skip
        raise ValueError(f"{field}: file {str(p)!r} is not {what} ({exc})") from exc


def npz_array(z: Any, key: str, ndim: int) -> Any:
    """Array `key` of an open archive as float64 with `ndim` dimensions (a float when 0)."""
    if key not in z.files:
        raise KeyError(f"no array {key!r}")
    a = np.asarray(z[key])
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{key}: expected real numbers, got dtype {a.dtype}")
    if a.ndim != ndim:
        raise ValueError(f"{key}: expected {ndim} dimensions, got shape {a.shape}")
    return float(a) if ndim == 0 else a.astype(np.float64)


def read_regular(path: str | Path, max_bytes: int, what: str) -> bytes:
    """The bytes of the regular file `path` (links to one are followed), at most `max_bytes`;
    ValueError naming `what` and the file for a FIFO, device or folder (opened without
    blocking, never read), an oversized or unreadable file."""
    p = Path(path)
    try:
        fd = os.open(p, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise ValueError(f"{what}: cannot read {p} ({exc.strerror})") from exc
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{what}: {p} is not a regular file")
        if st.st_size > max_bytes:
            raise ValueError(f"{what}: {p} is {st.st_size} bytes, more than {max_bytes}")
        with os.fdopen(fd, "rb", closefd=False) as fh:
            data = fh.read(max_bytes + 1)
    except OSError as exc:
        raise ValueError(f"{what}: cannot read {p} ({exc.strerror})") from exc
    finally:
        os.close(fd)
    if len(data) > max_bytes:
        raise ValueError(f"{what}: {p} is more than {max_bytes} bytes")
    return data


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


def _is_link(p: Path) -> bool:
    try:
        return stat.S_ISLNK(os.lstat(p).st_mode)
    except OSError:
        return False


def make_dirs(root: str | Path, folder: str | Path, field: str = "out") -> Path:
    """Create `folder` and its missing parents below `root` (the folder the caller gave, which
    may itself be a link), one at a time: ValueError naming `field` and the path if one of
    them is a symbolic link or a file. `root` is created with its parents if missing."""
    root, folder = Path(root), Path(folder)
    rel = folder.relative_to(root)
    try:
        root.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValueError(f"{field}: cannot create {str(root)!r} ({exc.strerror})") from exc
    p = root
    for part in rel.parts:
        p = p / part
        if _is_link(p):
            raise ValueError(f"{field}: {str(p)!r} is a symbolic link; refused (not followed)")
        try:
            p.mkdir()
        except FileExistsError:
            if not p.is_dir():
                raise ValueError(f"{field}: {str(p)!r} is a file, expected a folder") from None
        except OSError as exc:
            raise ValueError(f"{field}: cannot create {str(p)!r} ({exc.strerror})") from exc
    return folder


def check_target(path: str | Path, field: str = "out") -> Path:
    """`path` as a file to be (re)placed: ValueError naming `field` if it is a symbolic link or
    exists as anything but a regular file."""
    p = Path(path)
    try:
        mode = os.lstat(p).st_mode
    except FileNotFoundError:
        return p
    if stat.S_ISLNK(mode):
        raise ValueError(f"{field}: {str(p)!r} is a symbolic link; refused (not followed)")
    if not stat.S_ISREG(mode):
        raise ValueError(f"{field}: {str(p)!r} exists and is not a regular file")
    return p


@contextmanager
def atomic_path(path: str | Path, field: str = "out") -> Iterator[Path]:
    """Yield a new temporary path in `path`'s folder (same suffix, created by this process);
    write it, and on success it is moved onto `path` with `os.replace`. `path` must not be a
    symbolic link or a non-regular file (`check_target`); on any exception the temporary file
    is removed and `path` is left as it was."""
    p = check_target(path, field)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.tmp-", suffix=p.suffix, dir=p.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        check_target(p, field)
        os.replace(tmp, p)
    finally:
        if os.path.lexists(tmp):
            os.unlink(tmp)


def save_figure(fig: Any, path: str | Path, dpi: int = 110, **savefig_kw: Any) -> Path:
    """Write matplotlib figure `fig` to `path` through `atomic_path` (its folder created; a
    link or non-regular file at `path` refused; the format from the suffix, png without one)
    and close it, whatever happened; returns the path."""
    import matplotlib.pyplot as plt

    p = Path(path)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(p) as tmp:
            fig.savefig(tmp, dpi=dpi, format=p.suffix.lstrip(".") or "png", **savefig_kw)
    finally:
        plt.close(fig)
    return p


def write_atomic(path: str | Path, data: str | bytes, field: str = "out") -> Path:
    """Write `data` to `path` through `atomic_path` (fsync'ed before the rename)."""
    raw = data.encode() if isinstance(data, str) else data
    with atomic_path(path, field) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(raw)
            fh.flush()
            os.fsync(fh.fileno())
    return Path(path)


def open_append(path: str | Path, field: str = "out") -> int:
    """A write descriptor of the regular file `path` opened with `O_APPEND | O_NOFOLLOW`
    (created if missing); ValueError naming `field` for a link or a non-regular file."""
    p = check_target(path, field)
    flags = os.O_WRONLY | os.O_APPEND | os.O_CREAT | os.O_NOFOLLOW | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(p, flags | os.O_NONBLOCK, 0o644)
    except OSError as exc:
        raise ValueError(f"{field}: cannot write {str(p)!r} ({exc.strerror})") from exc
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise ValueError(f"{field}: {str(p)!r} exists and is not a regular file")
    return fd
