"""Tables of flat records (dicts with the same keys) written as CSV or JSON while they come.

Each writer is a context manager that yields ``write(record)``: a record goes to disk when
it is written (CSV files are line-buffered), so a table of any length takes no memory to
write. The file appears at its path, complete, when the block ends without an error (it
is written beside it and renamed, see :mod:`curvefold.io._atomic`); on an error nothing
is left.

Values are None, booleans, integers, floats or strings. Floats are written with ``repr``
in CSV and JSON alike, so they read back exactly.

Examples
--------
>>> import json, tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> with json_records(folder / "t.json", {"format": "demo"}, ("x", "ok")) as write:
...     write({"x": 0.1, "ok": True})
...     write({"x": None, "ok": False})
>>> json.loads((folder / "t.json").read_text())
{'format': 'demo', 'records': [{'x': 0.1, 'ok': True}, {'x': None, 'ok': False}]}
>>> with csv_records(folder / "t.csv", ("x", "ok")) as write:
...     write({"x": 0.1, "ok": True})
>>> (folder / "t.csv").read_text()
'x,ok\\n0.1,True\\n'
"""

from __future__ import annotations

import contextlib
import csv
import json
import math
import os
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any

from ..kernel._errors import InputError
from ._atomic import atomic_path

__all__ = ["csv_records", "json_records"]

Write = Callable[[Mapping[str, Any]], None]


@contextlib.contextmanager
def csv_records(path: str | os.PathLike, fields: Sequence[str]) -> Iterator[Write]:
    """Write records as the rows of a CSV file with the columns ``fields``.

    None is an empty cell, a boolean ``True``/``False``, a float its ``repr``.
    """
    with atomic_path(path) as tmp, open(tmp, "w", buffering=1, newline="", encoding="utf-8") as f:
        rows = csv.writer(f, lineterminator="\n")
        rows.writerow(fields)

        def write(record: Mapping[str, Any]) -> None:
            rows.writerow(
                [
                    ""
                    if record[k] is None
                    else repr(record[k])
                    if isinstance(record[k], float)
                    else record[k]
                    for k in fields
                ]
            )

        yield write


@contextlib.contextmanager
def json_records(
    path: str | os.PathLike, header: Mapping[str, Any], fields: Sequence[str]
) -> Iterator[Write]:
    """Write ``{**header, "records": [...]}`` as a JSON file, one record (keys ``fields``) a line.

    A float that is not finite is written as null (JSON has no NaN).
    """
    if "records" in header:
        raise InputError(f"header must not have a 'records' key, got keys {list(header)}")
    document = json.dumps({**header, "records": []}, indent=1, ensure_ascii=False, allow_nan=False)
    opening = document[: document.rindex("[]") + 1]  # up to the records' "["
    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8") as f:
        f.write(opening)
        separator = "\n  "

        def write(record: Mapping[str, Any]) -> None:
            nonlocal separator
            f.write(
                separator
                + json.dumps(
                    {k: _json_value(record[k]) for k in fields}, ensure_ascii=False, allow_nan=False
                )
            )
            separator = ",\n  "

        yield write
        f.write("\n ]\n}\n")


def _json_value(value: Any) -> Any:
    return None if isinstance(value, float) and not math.isfinite(value) else value
