"""The results CSV of a sweep: one row per finished trial, appended atomically, read on resume.

Only the driver writes (Ray tasks return their row). Each row is one `os.write` of one complete
line to a file opened with `O_APPEND`, followed by `fsync`, so an interruption leaves at most a
torn last line; `ResultStore` cuts such a line off before appending again. Floats are written
with `repr` (round-trip exact), so a resumed sweep and a fresh one hold the same numbers.
The header is fixed by the first row written (the same keys for every trial of one env id).
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path
from typing import Any


class ResultStore:
    """`path` (a CSV): `done_ids()`, `append(row)` and `rows()` (values parsed back)."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._drop_torn_line()
        self._header = self._read_header()

    def _drop_torn_line(self) -> None:
        if not self.path.exists():
            return
        data = self.path.read_bytes()
        if data and not data.endswith(b"\n"):
            with self.path.open("r+b") as fh:
                fh.truncate(data.rfind(b"\n") + 1)

    def _read_header(self) -> list[str] | None:
        if not self.path.exists() or self.path.stat().st_size == 0:
            return None
        with self.path.open(newline="") as fh:
            return next(csv.reader(fh))

    def rows(self) -> list[dict[str, Any]]:
        """Every stored row, numbers parsed back to int/float (other cells stay strings)."""
        if self._header is None:
            return []
        with self.path.open(newline="") as fh:
            return [{k: _parse(v) for k, v in r.items()} for r in csv.DictReader(fh)]

    def by_id(self, drop: tuple[str, ...] = ("wall_s",)) -> dict[str, dict[str, Any]]:
        """{trial id: row without the `drop` columns} (by default without the wall time)."""
        return {
            str(r["trial_id"]): {k: v for k, v in r.items() if k not in drop} for r in self.rows()
        }

    def done_ids(self) -> set[str]:
        return {str(r["trial_id"]) for r in self.rows()}

    def append(self, row: dict[str, Any], first: tuple[str, ...] = ()) -> None:
        """Append `row`; the first row also writes the header (`first` columns, then sorted)."""
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        if self._header is None:
            self._header = [*first, *sorted(set(row) - set(first))]
            writer.writerow(self._header)
        writer.writerow([_format(row.get(k, "")) for k in self._header])
        fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            os.write(fd, buf.getvalue().encode())
            os.fsync(fd)
        finally:
            os.close(fd)


def _format(v: Any) -> Any:
    return repr(v) if isinstance(v, float) else v


def _parse(text: str) -> Any:
    for cast in (int, float):
        try:
            return cast(text)
        except ValueError:
            pass
    return text
