"""Samples of a function read from a column of a CSV file a design names.

A design file's function-valued key may read ``{csv = "file.csv", column = "kappa"}``: the
samples of that column, uniformly spaced over the curve's length. :func:`table_path`
resolves the file inside the design file's folder (never outside it); :func:`read_column`
reads it within bounds (:data:`MAX_CSV_BYTES`, :data:`MAX_CSV_LINE`, :data:`MAX_CSV_ROWS`,
regular files only: :mod:`curvefold.io._reading`), requires every field to be a number and
distinct headers, and checks an ``s`` column, when there is one, against the uniform grid.
Blank lines and lines starting with ``#`` are skipped. Every refusal names the file, the
line and what is wrong.

Examples
--------
>>> import shutil, tempfile
>>> folder = Path(tempfile.mkdtemp())
>>> _ = (folder / "k.csv").write_text("s,kappa\\n0,1\\n1,1.5\\n# a comment\\n2,2\\n")
>>> values, lines = read_column(
...     table_path("k.csv", "kappa", folder), "kappa", length=2.0, label="k.csv"
... )
>>> values.tolist(), lines
([1.0, 1.5, 2.0], [2, 3, 5])
>>> read_column(folder / "k.csv", "kappa", length=4.0, label="k.csv")
Traceback (most recent call last):
...
curvefold.kernel._errors.InputError: k.csv: the s column must run from 0 to length 4, got 0 to 2
>>> table_path("../k.csv", "kappa", folder)
Traceback (most recent call last):
...
curvefold.kernel._errors.InputError: kappa: csv path must be relative to the design file's folder
and stay inside it, got '../k.csv'
>>> shutil.rmtree(folder)
"""

from __future__ import annotations

import csv
import io
from pathlib import Path, PurePosixPath, PureWindowsPath

import numpy as np

from ..kernel._errors import InputError
from ._reading import read_bytes

__all__ = ["MAX_CSV_BYTES", "MAX_CSV_LINE", "MAX_CSV_ROWS", "table_path", "read_column"]

#: Largest CSV file read, in bytes.
MAX_CSV_BYTES = 64 << 20
#: Longest CSV line read, in characters (with the row and column bounds, a CSV costs at most
#: a few times its size to read).
MAX_CSV_LINE = 10_000
#: Most data rows of a CSV file.
MAX_CSV_ROWS = 200_000


def read_column(
    file: Path, column: str, *, length: float, label: str
) -> tuple[np.ndarray, list[int]]:
    """The samples (M,) of ``column`` of the CSV ``file``, M ≥ 2, and the line number of each.

    The samples lie on the uniform grid over [0, ``length``]; an ``s`` column, if the file
    has one, must be that grid (to print rounding).

    Parameters
    ----------
    file : Path
        A file :func:`table_path` resolved.
    column : str
        The header of the column.
    length : float, keyword-only
        The length the samples span, model units.
    label : str, keyword-only
        How messages name the file (``design.toml: [curve] kappa (k.csv)``).

    Raises
    ------
    InputError
        The file cannot be read within the bounds, is not UTF-8, is malformed or empty, a
        field is not a number, the column is missing or short, or the ``s`` column is not
        the grid; the message starts with ``label``.
    """
    data = read_bytes(file, limit=MAX_CSV_BYTES, what="CSV file", name=label)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(
            f"{label}: CSV file is not UTF-8 text (bad byte at offset {exc.start})"
        ) from None
    lines, values, s = _parse_csv(text, label, column)
    if values.size < 2:
        raise InputError(f"{label}: column {column!r} needs at least 2 samples, got {values.size}")
    if s is not None:
        _check_grid(s, np.linspace(0.0, length, values.size), lines, label, length)
    return values, lines


def table_path(raw: str, where: str, base_dir: Path) -> Path:
    """The CSV file ``raw`` (as the design file writes it) inside ``base_dir``; absolute paths and
    escapes are refused.

    Raises
    ------
    InputError
        An absolute path, one leading outside ``base_dir`` (``..``, a link) or a file that
        does not exist; the message starts with ``where``.
    """
    posix = PurePosixPath(raw.replace("\\", "/"))
    if posix.is_absolute() or PureWindowsPath(raw).anchor or ".." in posix.parts:
        raise InputError(
            f"{where}: csv path must be relative to the design file's folder and stay inside it, "
            f"got {raw!r}"
        )
    base = base_dir.resolve()
    file = (base / posix).resolve()
    if not file.is_relative_to(base):
        raise InputError(f"{where}: csv path {raw!r} leads outside the design file's folder")
    if not file.is_file():
        raise InputError(f"{where}: csv file {raw!r} not found next to the design file")
    return file


def _parse_csv(
    text: str, label: str, column: str
) -> tuple[list[int], np.ndarray, np.ndarray | None]:
    """Line number of every data row, the samples of ``column`` and those of the ``s``
    column (None without one).

    Blank lines and lines starting with ``#`` are skipped. Every field must be a number;
    only the two columns are kept. Bounded: lines of at most :data:`MAX_CSV_LINE`
    characters, at most :data:`MAX_CSV_ROWS` data rows, distinct headers.
    """

    def bounded(lines):
        for number, line in enumerate(lines, 1):
            if len(line) > MAX_CSV_LINE:
                raise InputError(f"{label}: line {number} is longer than {MAX_CSV_LINE} characters")
            yield line

    header: list[str] | None = None
    wanted: list[int] = []
    rows: list[list[float]] = []
    lines: list[int] = []
    reader = csv.reader(bounded(io.StringIO(text)), strict=True)
    try:
        for row in reader:
            if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
                continue
            if header is None:
                header = [h.strip() for h in row]
                wanted = _columns(header, column, label)
                continue
            if len(row) != len(header):
                raise InputError(
                    f"{label}: line {reader.line_num} has {len(row)} fields, the "
                    f"header has {len(header)}"
                )
            if len(rows) == MAX_CSV_ROWS:
                raise InputError(
                    f"{label}: more than {MAX_CSV_ROWS} data rows (at line {reader.line_num})"
                )
            try:
                numbers = [float(x) for x in row]
            except ValueError:
                bad = next(x for x in row if not _is_float(x))
                raise InputError(
                    f"{label}: line {reader.line_num}: {bad.strip()!r} is not a number"
                ) from None
            rows.append([numbers[j] for j in wanted])
            lines.append(reader.line_num)
    except csv.Error as exc:
        raise InputError(f"{label}: malformed CSV at line {reader.line_num}: {exc}") from None
    if header is None:
        raise InputError(f"{label}: CSV file is empty (expected a header row and samples)")
    data = np.array(rows, dtype=float).reshape(len(rows), len(wanted))
    values = np.ascontiguousarray(data[:, 0])
    return lines, values, (np.ascontiguousarray(data[:, 1]) if len(wanted) == 2 else None)


def _columns(header: list[str], column: str, label: str) -> list[int]:
    """Indices of ``column`` and of ``s`` (if present) in a header with distinct names."""
    seen: dict[str, int] = {}
    for j, name in enumerate(header):
        if name in seen:
            raise InputError(
                f"{label}: column {name!r} appears twice in the header (fields "
                f"{seen[name] + 1} and {j + 1})"
            )
        seen[name] = j
    if column not in seen:
        raise InputError(f"{label}: no column {column!r} (columns: {', '.join(map(repr, header))})")
    return [seen[column]] + ([seen["s"]] if "s" in seen and column != "s" else [])


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _check_grid(
    s: np.ndarray, grid: np.ndarray, lines: list[int], label: str, length: float
) -> None:
    """The ``s`` column must be the uniform grid over [0, length] (to print rounding)."""
    h = length / (grid.size - 1)
    tol = max(1e-3 * h, 1e-6 * length)
    with np.errstate(invalid="ignore"):
        off = np.flatnonzero(~(np.abs(s - grid) <= tol))
    if off.size and (off[0] == 0 or off[-1] == grid.size - 1):
        raise InputError(
            f"{label}: the s column must run from 0 to length {length:g}, got {s[0]:.6g} to "
            f"{s[-1]:.6g}"
        )
    if off.size:
        i = int(off[0])
        raise InputError(
            f"{label}: the s column must be uniformly spaced over [0, {length:g}]: at line "
            f"{lines[i]} s = {s[i]:.6g}, expected {grid[i]:.6g} ({grid.size} samples, "
            f"spacing {h:.6g})"
        )
