"""Text a user typed, made safe for the place it goes.

A title, a path or a column name travels into files other programs read (OBJ comments,
glTF, 3DM, FOLD, HTML) and onto the terminal. Control characters there act instead of
showing: a newline in an OBJ comment starts a new statement (``v 999 999 999``), an
escape sequence recolours or rewrites the terminal, a bidirectional override reorders
what is shown.

- :func:`control_characters` finds them (the validators refuse them in design values);
- :func:`one_line` is the form files get: the same text on one line, each run of control
  characters and line breaks a single space;
- :func:`for_terminal` is the form printed: each control character shown as its escape
  (``\\n``, ``\\x1b``), so what was typed stays visible and nothing acts on the terminal.

Formats with their own syntax escape on top of :func:`one_line` (HTML and XML escapes,
JSON strings).
"""

from __future__ import annotations

import re

__all__ = ["CONTROL", "control_characters", "one_line", "for_terminal"]

#: C0 and C1 control characters, DEL, the line and paragraph separators and the
#: bidirectional embeddings, overrides and isolates (U+202A–U+202E, U+2066–U+2069).
CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069]")


def control_characters(text: str) -> list[int]:
    """Indices of the control characters in ``text`` (see :data:`CONTROL`).

    Examples
    --------
    >>> control_characters("vault\\nv 1 2 3")
    [5]
    """
    return [m.start() for m in CONTROL.finditer(text)]


def one_line(text: str) -> str:
    """``text`` on one line with no control characters: each run of them (and of spaces
    around them) becomes one space, and the ends are stripped.

    Examples
    --------
    >>> one_line("vault\\r\\nv 999 999 999\\x1b[2J ")
    'vault v 999 999 999 [2J'
    """
    return re.sub(rf"\s*(?:{CONTROL.pattern}\s*)+", " ", str(text)).strip()


def for_terminal(text: str) -> str:
    """``text`` with every control character written as its Python escape.

    Examples
    --------
    >>> print(for_terminal("out\\ndir\\x1b[31m"))
    out\\ndir\\x1b[31m
    """
    return CONTROL.sub(lambda m: repr(m.group())[1:-1], str(text))
