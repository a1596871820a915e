"""Write command outputs into a temporary folder next to the target, move them in when complete.

Used by every `mf-envs` command that writes files (demo, bench, render, train, evaluate), so an
interrupted or failed run (Ctrl-C, an exception) leaves the previous outputs exactly as they were
and never a mix of old and new files. Folder checks raise `ValueError` naming `out`.

No symbolic link the caller did not give is followed: the folders between the output folder
the caller named (`root`) and the target are created one by one and a link among them is
refused (`_files.make_dirs`), and a file moved into place never lands on a link (refused).
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path

from mf_envs._files import check_target, make_dirs


def check_out(target: Path, *, folder: bool = True) -> Path:
    """`target` as an output folder (or file if not `folder`) that can be written: ValueError if
    it is a file where a folder is expected (or the reverse), its nearest existing parent is not
    a writable folder, or (a file) its folder does not exist: a file's folder is not created,
    so a mistyped path is refused instead of growing a tree of folders."""
    target = Path(target)
    if target.exists() and folder and not target.is_dir():
        raise ValueError(f"out: {str(target)!r} is a file, expected a folder")
    if target.exists() and not folder and target.is_dir():
        raise ValueError(f"out: {str(target)!r} is a folder, expected a file path")
    if not folder and not target.parent.exists():
        raise ValueError(f"--out: no folder {str(target.parent)!r}; create it first")
    parent = target.parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise ValueError(f"out: {str(parent)!r} is a file, so {str(target)!r} cannot be created")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise ValueError(f"out: cannot write into {str(parent)!r} (read-only)")
    return target


def _mkdtemp(parent: Path, name: str, root: Path | None = None) -> Path:
    make_dirs(parent if root is None else root, parent)
    try:
        return Path(tempfile.mkdtemp(prefix=f".{name}.tmp-", dir=parent))
    except OSError as exc:
        raise ValueError(f"out: cannot write into {str(parent)!r} ({exc.strerror})") from exc


@contextmanager
def staged_dir(
    target: Path, *, replace: bool = False, force: bool = False, root: Path | None = None
) -> Iterator[Path]:
    """Yield a temporary folder beside `target`; on success move its content into `target`.

    replace=False (demo, bench): each new file replaces the file of the same name in `target`,
    other files stay. replace=True (a run folder of train/evaluate): ValueError if `target`
    exists and is not empty, unless `force`; then the whole folder is swapped. On any exception,
    KeyboardInterrupt included, the temporary folder is deleted and `target` is untouched.
    `root`: the output folder the caller gave, `target` being below it (a run folder
    `OUT/ENV_ID/seedS`); no folder from it down to `target` may be a symbolic link.
    """
    target = Path(target)
    if root is not None:
        make_dirs(root, target.parent)
        if target.is_symlink():
            raise ValueError(f"out: {str(target)!r} is a symbolic link; refused (not followed)")
    target = check_out(target)
    if replace and target.is_dir() and any(target.iterdir()) and not force:
        raise ValueError(f"out: {str(target)!r} already exists; pass --force to replace it")
    tmp = _mkdtemp(target.parent, target.name, root)
    try:
        yield tmp
        if replace:
            _swap(tmp, target)
        else:
            _merge(tmp, target)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _merge(src: Path, dst: Path) -> None:
    """Move the files of `src` into `dst` (its own folders created, a link among them or at a
    file's name refused, before anything is moved)."""
    moves = []
    for path in sorted(src.rglob("*")):
        dest = dst / path.relative_to(src)
        if path.is_dir():
            make_dirs(dst, dest)
        else:
            make_dirs(dst, dest.parent)
            moves.append((path, check_target(dest)))
    for path, dest in moves:
        os.replace(path, dest)


def _swap(src: Path, dst: Path) -> None:
    old = None
    if dst.exists():
        old = Path(tempfile.mkdtemp(prefix=f".{dst.name}.old-", dir=dst.parent))
        os.replace(dst, old / dst.name)
    os.replace(src, dst)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


@contextmanager
def staged_file(target: Path) -> Iterator[Path]:
    """Yield a temporary path beside the file `target` (same suffix); moved onto it on success."""
    target = check_out(Path(target), folder=False)
    tmp = _mkdtemp(target.parent, target.name)
    try:
        path = tmp / target.name
        yield path
        os.replace(path, target)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def moved(paths: Iterable[Path], tmp: Path, target: Path) -> list[Path]:
    """Paths written under `tmp`, as they are after the move into `target`."""
    out = []
    for p in paths:
        p = Path(p)
        out.append(target / p.relative_to(tmp) if p.is_relative_to(tmp) else p)
    return out
