"""The design file an output folder holds: ``design.toml``, the exact design that rebuilds it.

``curvefold <kind> design.toml`` builds the same structure again: every value as built, a
vault's ``tubes = "max"`` resolved to the number built, a CSV table named by its absolute path.
The TOML is written here (a design holds strings, numbers, booleans, lists and tables), so that
writing it needs no package beyond those the command line needs.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

from ._build import Built, BuiltVault
from ._design import Design

__all__ = ["DESIGN_FILE", "built_design", "design_toml"]

#: The name of the design file in every output folder.
DESIGN_FILE = "design.toml"

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def built_design(built: Built) -> Design:
    """The design as built: a vault's ``tubes = "max"`` replaced by the number of tubes built."""
    design = built.design
    if isinstance(built, BuiltVault) and design.to_dict()["vault"].get("tubes") == "max":
        return design.overrides(source=design.source, tubes=int(built.vault.summary()["tubes"]))
    return design


def design_toml(design: Design) -> str:
    """The design as a TOML design file that :func:`curvefold.app.load_design` reads back equal.

    Examples
    --------
    >>> from curvefold.app._design import design_from_dict, parse_design
    >>> design = design_from_dict({"kind": "tube", "curve": {"kappa": "1 + 0.1*s"}})
    >>> print(design_toml(design).splitlines()[0])
    kind = "tube"
    >>> parse_design(design_toml(design)) == design
    True
    """
    folder = Path.cwd() if design.base_dir is None else Path(design.base_dir)
    data = _absolute_tables(design.to_dict(), folder)
    top = [f"{_key(k)} = {_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    tables = [
        f"\n[{_key(k)}]\n" + "".join(f"{_key(n)} = {_value(x)}\n" for n, x in v.items())
        for k, v in data.items()
        if isinstance(v, dict)
    ]
    return "\n".join(top) + "\n" + "".join(tables)


def _absolute_tables(value: Any, folder: Path) -> Any:
    """The design's data with every CSV table's path made absolute (the folder is elsewhere)."""
    if isinstance(value, dict):
        if set(value) == {"csv", "column"}:
            return {"csv": str((folder / value["csv"]).resolve()), "column": value["column"]}
        return {k: _absolute_tables(v, folder) for k, v in value.items()}
    if isinstance(value, list):
        return [_absolute_tables(v, folder) for v in value]
    return value


def _key(name: str) -> str:
    return name if _BARE_KEY.match(name) else _string(name)


def _string(text: str) -> str:
    """A TOML basic string: quotes, backslashes and control characters escaped."""
    escaped = "".join(
        "\\" + c if c in '"\\' else f"\\u{ord(c):04x}" if ord(c) < 0x20 or ord(c) == 0x7F else c
        for c in text
    )
    return f'"{escaped}"'


def _value(value: Any) -> str:
    """A TOML value: a float written so that it reads back the same number."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        text = repr(value)
        return text if any(c in text for c in ".en") else f"{text}.0"
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"a design file holds no {type(value).__name__}: {value!r}")
