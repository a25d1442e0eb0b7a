"""The ``curvefold`` command line.

Every subcommand prints a short human summary, or with ``--json`` one strict JSON object
on stdout (no NaN or infinity: a non-finite result is an error). Exit statuses: 0 done;
1 a certificate check failed, or a bug (one line asking for a report with the version,
the traceback only with ``--debug``); 2 a user error (one line on stderr: what is wrong,
the allowed range, the value given), including a job over the memory budget
(:mod:`curvefold.app._budget`); 128 + n when stopped by signal n (SIGINT, SIGTERM, SIGHUP),
after removing what the run had started to write; 141 (128 + SIGPIPE), with nothing printed,
when the reader of its output stops early (``curvefold check FILE | head``). Warnings are
shown only with ``--debug``; text a user typed is printed with its control characters
escaped. The output folder is checked before any work and replaced only as
:mod:`curvefold.app._folder` says.

A subcommand per registered kind of design (:mod:`curvefold.app._kinds`), its help the kind's.
The flags of those and of ``load``, their help and their checks are generated from the design
schema (:data:`curvefold.app._design.SCHEMA`): one flag per key, ``--fold-angle`` for
``fold_angle``, ``--no-glue-tabs`` for a key that is true by default. A flag's value is
checked by the key's spec and named as typed (``--page A9: page must be one of …``); a design
made of a file and flags is named by both (``design.toml --samples 10: …``).
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import traceback
import warnings
from collections.abc import Sequence

from ..kernel._threads import blas_loads_on_one_thread

# NumPy is loaded here; a command runs its BLAS on one thread (_run), so OpenBLAS starts none
with blas_loads_on_one_thread():
    from ..kernel._errors import CurvefoldError, InputError
    from ._cli_commands import (
        _certificate_failed,
        _certificate_lines,
        _checked_output,
        _emit,
        _error,
        _load_design,
        cmd_arch,
        cmd_atlas,
        cmd_check,
        cmd_designer,
        cmd_mechanism,
        cmd_reproduce,
        cmd_structure,
    )
    from ._cli_flags import _fit_targets
    from ._cli_parser import LOAD_KIND, build_parser
    from ._folder import Interrupted, raise_if_interrupted, signals_interrupt
    from ._kinds import design_kinds

__all__ = ["build_parser", "main", "run"]
#: The signal a closed pipe would stop a program with (POSIX numbers it 13).
_SIGPIPE = int(getattr(signal, "SIGPIPE", 13))


def cmd_load(args: argparse.Namespace) -> int:
    from ._budget import require_budget
    from ._build import build
    from ._outputs import default_title, write_outputs

    design = _load_design(LOAD_KIND, args, kinds=[k.name for k in design_kinds() if k.loaded])
    target = None if args.out is None else _checked_output(design, args, args.out)
    design = _fit_targets(design, args).with_mechanics()  # the output checked first
    require_budget(design, files=target is not None)
    built = build(design)
    from ._collapse_bar import collapse_progress

    with collapse_progress(not args.json):  # a bar while --nonlinear follows the path
        loaded = built.mechanics
    if loaded is None:  # with_mechanics gave it material and loads
        raise InputError(f"{design.source}: a {design.kind} design is not analysed under load")
    head = {
        "kind": design.kind,
        "title": design.title or default_title(built),
        "design": design.to_dict(),
    }
    # the verdict first: stands or fails, the governing check, its utilisation and combination
    lines = [loaded.verdict.headline(), f"{head['title']}", *loaded.lines()]
    if target is None:
        payload = head | loaded.to_dict()
        failed = False
    else:
        written = write_outputs(built, target, show_progress=not args.json)
        payload = (
            head
            | written.pop("mechanics")
            | {
                "certificate": written["certificate"],
                "files": written["files"],
                "out": str(args.out),
            }
        )
        lines += _certificate_lines(written) + [
            f"  wrote {len(written['files'])} files to {args.out}/ (open {args.out}/report.html)"
        ]
        failed = _certificate_failed(written)
    _emit(args, payload, lines)
    return 1 if failed or not loaded.verdict.stands else 0


def cmd_deploy(args: argparse.Namespace) -> int:
    from ._deploy_command import cmd_deploy as deploy

    return deploy(args, LOAD_KIND)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (see the module doc).

    A :class:`~curvefold.kernel.CurvefoldError` (a user error), an unreadable or
    unwritable file, a missing optional package or running out of memory prints one line
    and returns 2. A signal returns 128 + its number. Any other exception is a bug: one
    line asking for a report, status 1; ``--debug`` adds the traceback and the warnings,
    which are otherwise never printed.
    """
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    with warnings.catch_warnings(record=True) as caught, signals_interrupt():
        warnings.simplefilter("always")
        try:
            status = _run(build_parser(), argv)
            # a signal whose exception Python ignored (raised in a finalizer)
            raise_if_interrupted()
            return status
        except CurvefoldError as err:
            _error(f"error: {err}")
            return 2
        except BrokenPipeError:  # the reader stopped early (``| head``): not an error
            return _reader_gone()
        except OSError as err:
            _error(
                f"error: {err.filename}: {err.strerror}"
                if err.filename and err.strerror
                else f"error: {err}"
            )
            return 2
        except ImportError as err:
            _error(f"error: {err}")
            return 2
        except MemoryError:
            _error(
                "error: out of memory; lower samples, the number of tubes or cells, or the "
                "formats written (see CURVEFOLD_MEMORY_BUDGET in the README)"
            )
            return 2
        except (Interrupted, KeyboardInterrupt) as err:
            signum = err.signum if isinstance(err, Interrupted) else signal.SIGINT
            _error(f"interrupted by {signal.Signals(signum).name}")
            return 128 + int(signum)
        except Exception as err:
            from ..kernel._version import VERSION

            hint = "" if debug else " (rerun with --debug for the traceback)"
            _error(
                f"internal error: {type(err).__name__}: {err}. This is a bug in curvefold "
                f"{VERSION}; please report it with the command you ran{hint}"
            )
            if debug:
                traceback.print_exc()
            return 1
        finally:
            if debug:
                for w in caught:
                    print(
                        warnings.formatwarning(
                            w.message, w.category, w.filename, w.lineno
                        ).rstrip(),
                        file=sys.stderr,
                    )


def _run(parser: argparse.ArgumentParser, argv: Sequence[str] | None) -> int:
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    from ..kernel._threads import one_blas_thread

    # a command's matrices are small: more BLAS threads only wait (kernel.threads); SciPy's
    # own BLAS, loaded by the command, reads the environment then
    with blas_loads_on_one_thread(), one_blas_thread():
        if args.command in {kind.name for kind in design_kinds()}:
            return cmd_structure(args.command, args)
        return {
            "load": cmd_load,
            "deploy": cmd_deploy,
            "arch": cmd_arch,
            "reproduce": cmd_reproduce,
            "check": cmd_check,
            "mechanism": cmd_mechanism,
            "atlas": cmd_atlas,
            "designer": cmd_designer,
        }[args.command](args)


def run() -> None:
    """The ``curvefold`` console script: :func:`main` on the command line's arguments, its status
    as the exit status."""
    status = main()
    try:
        sys.stdout.flush()  # what is still buffered, while a closed reader can be caught
    except BrokenPipeError:
        status = _reader_gone()
    sys.exit(status)


def _reader_gone() -> int:
    """The status of a run whose standard output was closed by its reader: 128 + SIGPIPE, as a
    shell reports a program stopped by it, with nothing printed; what is still buffered is
    dropped, so that Python's own flush at exit does not report the pipe either."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):  # a standard output with no file behind it holds nothing
        pass
    return 128 + _SIGPIPE
