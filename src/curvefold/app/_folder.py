"""The output folder: checked before any work, written beside its target, installed last.

What the command line promises about the folder it writes:

- **Checked first.** :func:`check_output` runs before anything is built. It refuses a
  target that is the current folder or contains it (``.``, ``..``, ``/``), ends in ``.``
  or ``..``, is a file or a symbolic link, holds a file the run reads, or lies in a parent
  that is missing or not writable. An existing folder is replaced only with ``force``, and
  only if curvefold wrote it (it holds the marker file :data:`MARKER`) or it is empty.
- **Nothing partial.** Files are written into a temporary folder beside the target,
  ``.<name>.curvefold-<pid>-<random>`` (the name cut to 200 bytes, so that a name of 255
  bytes is written too), which holds the marker from the start.
- **Never replace what was not checked.** The last step renames the temporary folder onto
  the target with a rename that cannot replace an existing folder (``renameat2`` with
  ``RENAME_NOREPLACE`` on Linux; elsewhere a rename made under a lock on the parent
  folder). A folder being replaced is first moved aside and checked to be the one found at
  the start. If the target appeared or changed meanwhile it is left as it is, the finished
  output is kept beside it as ``<name>.new`` (or ``<name>.new-2``…) and an
  :class:`~curvefold.kernel.InputError` says where.
- **Nothing left behind.** On an error or a signal the temporary folder is removed; the
  last step and the cleanup run with SIGINT, SIGTERM and SIGHUP held back. Temporary
  folders of this naming whose process is gone (killed with SIGKILL, a power cut) are
  removed by the next run that writes beside them.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import json
import os
import re
import secrets
import shutil
import signal
import sys
import tempfile
import threading
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

from ..io._atomic import folder_mode
from ..io._reading import read_bytes
from ..kernel._errors import InputError
from ..kernel._version import VERSION

__all__ = [
    "MARKER",
    "ENDING_SIGNALS",
    "Interrupted",
    "OutputTarget",
    "check_output",
    "output_folder",
    "raise_if_interrupted",
    "rename_noreplace",
    "signals_interrupt",
]

#: The file every output folder holds: curvefold's version and a random id.
MARKER = ".curvefold-output"
#: Temporary folders (and folders moved aside) of a run, with its process id.
_TEMPORARY = re.compile(r"\..+\.curvefold-(\d+)-\w+(\.old)?")
#: The signals that end a run (the command line turns them into a clean stop).
ENDING_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)


#: The ending signal this process received while :func:`signals_interrupt` was active, if any.
_received: list[int] = []


class Interrupted(BaseException):
    """A signal that ends the run (SIGINT, SIGTERM, SIGHUP): raised in the main thread, so
    every ``finally`` runs and the temporary output folder is removed."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


@contextlib.contextmanager
def signals_interrupt() -> Iterator[None]:
    """The first of SIGINT, SIGTERM or SIGHUP raises :class:`Interrupted`; later ones are
    ignored while the run unwinds. Previous handlers are restored afterwards.

    Python ignores an exception raised while it runs a finalizer or a callback, so the
    signal is also remembered: :func:`raise_if_interrupted` raises it again, and
    :func:`output_folder` does before it installs a folder. Such an ignored
    :class:`Interrupted` is not printed (other ignored exceptions are, as before).
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _received.clear()

    def handler(signum, frame):
        if not _received:
            _received.append(signum)
            raise Interrupted(signum)

    previous_hook = sys.unraisablehook

    def unraisable(report):
        if not isinstance(report.exc_value, Interrupted):
            previous_hook(report)

    previous = {signum: signal.signal(signum, handler) for signum in ENDING_SIGNALS}
    sys.unraisablehook = unraisable
    try:
        yield
    finally:
        sys.unraisablehook = previous_hook
        for signum, old in previous.items():
            signal.signal(signum, old)


def raise_if_interrupted() -> None:
    """Raise :class:`Interrupted` if :func:`signals_interrupt` received a signal."""
    if _received:
        raise Interrupted(_received[0])


@dataclass(frozen=True)
class OutputTarget:
    """An output folder checked by :func:`check_output`.

    Attributes
    ----------
    path : Path
        The folder to write.
    replaces : str or None
        None if nothing was there; else the identity of the folder to replace (the id in
        its marker, or ``""`` for an empty folder), verified again before it is replaced.
    """

    path: Path
    replaces: str | None


def check_output(
    path: str | os.PathLike, *, force: bool, inputs: Iterable[str | os.PathLike] = ()
) -> OutputTarget:
    """Check an output folder before any work (see the module doc), and remove stale
    temporary folders beside it.

    Parameters
    ----------
    path : path-like
    force : bool, keyword-only
        Replace an existing folder that curvefold wrote, or an empty one.
    inputs : iterable of path-like, keyword-only
        Files the run reads; none may lie inside the folder.

    Raises
    ------
    InputError
        A target curvefold must not write or replace, with the reason.
    """
    path = Path(path)
    name = f"output folder {path}"
    resolved = path.resolve()
    if path.name in ("", ".", "..") or Path.cwd().resolve().is_relative_to(resolved):
        raise InputError(
            f"{name} is the current folder or contains it; name a new folder, e.g. "
            "--out curvefold-output"
        )
    for file in inputs:
        if Path(file).resolve().is_relative_to(resolved):
            raise InputError(f"{name} holds {file}, which this run reads; choose another folder")
    parent = path.parent
    if not parent.is_dir():
        raise InputError(
            f"cannot write {path}: its parent folder {parent} does not exist or is not a folder"
        )
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"cannot write {path}: its parent folder {parent} is not writable")
    _remove_stale(parent)
    if path.is_symlink():
        raise InputError(
            f"{name} is a symbolic link; curvefold replaces only a folder it wrote; "
            "choose another folder"
        )
    if not path.exists():
        return OutputTarget(path, None)
    if not path.is_dir():
        raise InputError(f"output path {path} exists and is not a folder; choose another folder")
    identity = _identity(path)
    if identity is None:
        raise InputError(
            f"{name} exists and was not written by curvefold (it has no {MARKER} "
            "file and is not empty); choose another folder: --force replaces only a folder "
            "curvefold wrote"
        )
    if not force:
        raise InputError(f"{name} exists; pass --force to replace it")
    return OutputTarget(path, identity)


@contextlib.contextmanager
def output_folder(target: OutputTarget) -> Iterator[Path]:
    """Yield a temporary folder (holding the marker) that becomes ``target.path`` when the
    block succeeds; on any error or signal it is removed.

    Raises
    ------
    InputError
        When the target appeared or changed since it was checked: the finished output is
        kept beside it, and the message names both.
    """
    path = target.path
    tmp = Path(
        tempfile.mkdtemp(prefix=f".{_stem(path.name)}.curvefold-{os.getpid()}-", dir=path.parent)
    )
    try:
        marker = {"curvefold": VERSION, "id": secrets.token_hex(16)}
        (tmp / MARKER).write_text(json.dumps(marker) + "\n", encoding="utf-8")
        yield tmp
        os.chmod(tmp, folder_mode())
        with _signals_held():
            raise_if_interrupted()
            _install(tmp, target)
    finally:
        with _signals_held():  # a second signal must not stop the cleanup
            _remove(tmp)


def _remove(folder: Path, tries: int = 5) -> None:
    """Remove ``folder`` whole. A walk can miss what appears while it runs (a stopped job's
    last file): it walks again until the folder is gone, a few times at most."""
    for _ in range(tries):
        shutil.rmtree(folder, ignore_errors=True)
        if not folder.exists():
            return


def _install(tmp: Path, target: OutputTarget) -> None:
    """Rename ``tmp`` onto the target, replacing only the folder that was checked."""
    path = target.path
    if target.replaces is None:
        try:
            rename_noreplace(tmp, path)
        except FileExistsError:
            _conflict(tmp, path, "appeared while curvefold was running")
        return
    aside = path.with_name(
        f".{_stem(path.name)}.curvefold-{os.getpid()}-{secrets.token_hex(4)}.old"
    )
    try:
        rename_noreplace(path, aside)
    except FileNotFoundError:  # removed meanwhile: nothing to replace
        _install(tmp, OutputTarget(path, None))
        return
    if _identity(aside) != target.replaces:
        rename_noreplace(aside, path)  # not the folder that was checked: put it back
        _conflict(tmp, path, "changed while curvefold was running")
    try:
        rename_noreplace(tmp, path)
    except FileExistsError:
        shutil.rmtree(aside, ignore_errors=True)  # the checked folder, replaced as asked
        _conflict(tmp, path, "appeared while curvefold was running")
    shutil.rmtree(aside, ignore_errors=True)


def _conflict(tmp: Path, path: Path, what: str) -> None:
    """Keep the finished output beside ``path`` under a free name and say so."""
    for n in range(1, 1000):
        kept = path.with_name(f"{_stem(path.name)}.new" + (f"-{n}" if n > 1 else ""))
        try:
            rename_noreplace(tmp, kept)
        except FileExistsError:
            continue
        raise InputError(
            f"output folder {path} {what}; it was left as it is, and the new output is in {kept}"
        )
    raise InputError(
        f"output folder {path} {what}; it was left as it is, and no free name was "
        "found beside it for the new output"
    )


#: Bytes of a folder's name kept in the names made beside it (temporary, aside, ``.new``), so
#: that they stay within the 255 bytes a file name may have.
STEM_BYTES = 200


def _stem(name: str) -> str:
    """``name``, or its first :data:`STEM_BYTES` bytes (whole characters) when longer.

    Examples
    --------
    >>> _stem("vault"), len(_stem("v" * 250)), len(_stem("é" * 150).encode())
    ('vault', 200, 200)
    """
    return name.encode()[:STEM_BYTES].decode(errors="ignore")


def _identity(folder: Path) -> str | None:
    """The id in the folder's marker, ``""`` for an empty folder, None for any other folder."""
    try:
        with os.scandir(folder) as entries:
            if next(entries, None) is None:
                return ""
        marker = json.loads(read_bytes(folder / MARKER, limit=4096, what="marker"))
    except (OSError, ValueError):  # InputError is a ValueError
        return None
    return (
        marker.get("id") if isinstance(marker, dict) and isinstance(marker.get("id"), str) else None
    )


def _remove_stale(parent: Path) -> None:
    """Remove temporary folders of this naming in ``parent`` whose process is gone and that
    hold a marker or nothing."""
    if os.name != "posix":
        return  # no way to ask whether a process id is alive without signalling it
    try:
        entries = list(os.scandir(parent))
    except OSError:
        return
    for entry in entries:
        match = _TEMPORARY.fullmatch(entry.name)
        if (
            match is None
            or int(match.group(1)) == os.getpid()
            or not entry.is_dir(follow_symlinks=False)
        ):
            continue
        if not _alive(int(match.group(1))) and _identity(Path(entry.path)) is not None:
            shutil.rmtree(entry.path, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP are delivered after the block, not inside it."""
    try:
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, ENDING_SIGNALS)
    except (AttributeError, ValueError, OSError):  # no signal masks here (Windows)
        yield
        return
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


# -- a rename that never replaces ---------------------------------------------------------------

_RENAME_NOREPLACE = 1
_AT_FDCWD = -100


def _load_renameat2():
    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2  # glibc ≥ 2.28, musl ≥ 1.2.2
    except (OSError, AttributeError, TypeError):
        return None
    function.argtypes = (
        ctypes.c_int,
        ctypes.c_char_p,
        ctypes.c_int,
        ctypes.c_char_p,
        ctypes.c_uint,
    )
    function.restype = ctypes.c_int
    return function


_renameat2 = _load_renameat2()


def rename_noreplace(source: str | os.PathLike, target: str | os.PathLike) -> None:
    """Rename ``source`` to ``target`` unless ``target`` exists (then FileExistsError).

    Uses ``renameat2(..., RENAME_NOREPLACE)`` where the system has it, which checks and
    renames in one step. Elsewhere (or on a file system without it) the rename is made
    under an exclusive lock on the target's parent folder, after checking that the target
    is absent: runs of curvefold cannot interleave, and a folder another program creates
    in between is never lost (POSIX ``rename`` refuses a non-empty folder; on Windows it
    refuses any existing target).
    """
    if _renameat2 is not None:
        if (
            _renameat2(
                _AT_FDCWD, os.fsencode(source), _AT_FDCWD, os.fsencode(target), _RENAME_NOREPLACE
            )
            == 0
        ):
            return
        code = ctypes.get_errno()
        if code not in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP):
            raise OSError(code, os.strerror(code), os.fspath(source), None, os.fspath(target))
    with _parent_locked(Path(target).parent):
        if os.path.lexists(target):
            raise FileExistsError(errno.EEXIST, os.strerror(errno.EEXIST), os.fspath(target))
        os.rename(source, target)


@contextlib.contextmanager
def _parent_locked(folder: Path) -> Iterator[None]:
    """An exclusive ``flock`` on ``folder`` itself (no lock file is left behind)."""
    try:
        import fcntl
    except ImportError:  # Windows: os.rename never replaces there
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # closing releases the lock
