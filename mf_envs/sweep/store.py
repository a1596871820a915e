"""The results CSV of a sweep: one row per finished trial, appended atomically, read on resume.

Only the driver writes (Ray tasks return their row). Each row is one `os.write` of one complete
line to a file opened with `O_APPEND`, followed by `fsync`, so an interruption leaves at most a
torn last line; `ResultStore` cuts such a line off before appending again. Floats are written
with `repr` (round-trip exact), so a resumed sweep and a fresh one hold the same numbers.
The header is fixed by the first row written (the same keys for every trial of one env id).

The file is never reached through a symbolic link (one at its name is refused; it is opened with
`O_NOFOLLOW`), the torn line is cut by an atomic rewrite (`_files.write_atomic`), and a file
whose header has no `trial_id` column is refused by name: it is not a sweep's results.
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path
from typing import Any

from mf_envs._files import check_target, open_append, read_regular, write_atomic

MAX_CSV_BYTES = 1 << 30  # 1 GiB: a million trials of a few hundred bytes


class ResultStore:
    """`path` (a CSV): `done_ids()`, `append(row)` and `rows()` (values parsed back)."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        check_target(self.path)
        self._drop_torn_line()
        self._header = self._read_header()

    def _text(self) -> str:
        """The file's text ('' if absent), read as a regular file only."""
        if not os.path.lexists(self.path):
            return ""
        check_target(self.path)
        data = read_regular(self.path, MAX_CSV_BYTES, "out")
        try:
            return data.decode()
        except UnicodeDecodeError:
            raise ValueError(f"out: {str(self.path)!r} is not a sweep's results CSV") from None

    def _drop_torn_line(self) -> None:
        data = self._text()
        if data and not data.endswith("\n"):
            write_atomic(self.path, data[: data.rfind("\n") + 1])

    def _read_header(self) -> list[str] | None:
        text = self._text()
        if not text:
            return None
        header = next(csv.reader(io.StringIO(text)))
        if "trial_id" not in header or len(set(header)) != len(header):
            raise ValueError(
                f"out: {str(self.path)!r} is not a sweep's results CSV (its header has no "
                "trial_id column, or repeats one); move it away or give another --out"
            )
        return header

    def rows(self) -> list[dict[str, Any]]:
        """Every stored row, numbers parsed back to int/float (other cells stay strings)."""
        if self._header is None:
            return []
        reader = csv.DictReader(io.StringIO(self._text(), newline=""))
        rows = []
        for n, r in enumerate(reader, start=2):
            if None in r or None in r.values():  # more or fewer cells than the header
                raise ValueError(
                    f"out: {str(self.path)!r} line {n}: {len(r)} cells do not match the header"
                )
            rows.append({k: _parse(v) for k, v in r.items()})
        return rows

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
        fd = open_append(self.path)
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
