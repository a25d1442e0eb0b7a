"""Bounded reading of the files a user names: regular files only, up to a size limit.

A path on the command line or in a design file may name anything: a FIFO (reading it
blocks until someone writes), a device (``/dev/zero`` never ends), a kernel file
(``/proc/kmsg`` blocks, and reading it consumes the log) or a file of many gigabytes.
:func:`read_bytes` opens without blocking, checks the open file itself (so nothing can
be swapped in between a check and the read), refuses anything but a regular file of at
most ``limit`` bytes, and reads no more than the size the file reports: a kernel file
that reports 0 bytes reads as empty, a file that grows meanwhile is read as it was.
"""

from __future__ import annotations

import os
import stat

from ..kernel._errors import InputError

__all__ = ["read_bytes"]

_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a FIFO"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def read_bytes(path: str | os.PathLike, *, limit: int, what: str, name: str | None = None) -> bytes:
    """The content of the regular file ``path``, at most ``limit`` bytes.

    Parameters
    ----------
    path : path-like
    limit : int, keyword-only
        Largest size accepted, in bytes.
    what : str, keyword-only
        What the file should be, for messages (``"design file"``).
    name : str, optional, keyword-only
        How messages name the file; default the path as given.

    Raises
    ------
    InputError
        The path cannot be opened, is not a regular file or is larger than ``limit``;
        the message starts with ``name``.
    """
    where = os.fspath(path) if name is None else name
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    except OSError as exc:
        raise InputError(f"{where}: cannot read {what}: {exc.strerror or exc}") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            kind = next(
                (name for test, name in _KINDS if test(info.st_mode)), "another kind of file"
            )
            raise InputError(f"{where}: cannot read {what}: it is {kind}, not a regular file")
        if info.st_size > limit:
            raise InputError(
                f"{where}: {what} is {info.st_size} bytes, more than the limit of {limit} bytes"
            )
        chunks, left = [], info.st_size
        while left > 0:
            chunk = os.read(fd, min(left, 1 << 24))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)
    except OSError as exc:
        raise InputError(f"{where}: cannot read {what}: {exc.strerror or exc}") from None
    finally:
        os.close(fd)
