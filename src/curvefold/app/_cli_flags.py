"""The command line's flags generated from the design schema, and its argument parser.

One flag per schema key (``--fold-angle`` for ``fold_angle``, ``--no-glue-tabs`` for a key that
is true by default), its help and its check the key's spec; a flag's value is named as typed
(``--page A9: page must be one of …``). The parser's usage errors are one line, exit status 2.
"""

from __future__ import annotations

import argparse
import difflib
import re
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from ..io._formats import FORMATS, default_formats
from ..kernel._errors import InputError
from ..kernel._validate import Spec, from_text
from ._design import OPTIONAL_SECTIONS, SCHEMA, Design, kind_specs
from ._kinds import DesignKind, design_kind

PROG = "curvefold"

#: Values along one axis of the atlas grid.
_GRID_COUNT = Spec("count", "integer", 5, "[1, 200]")


def _grid(flag: str, text: str, spec: Spec) -> np.ndarray:
    """``start:stop:count`` or a comma-separated list of numbers, each checked by ``spec``."""
    where = f"{flag} {text}: {spec.name}"
    parts = text.split(":")
    if len(parts) == 3:
        count = _GRID_COUNT.check(_from_text(_GRID_COUNT, parts[2], flag), f"{flag} {text}: count")
        start, stop = (
            spec.check(_from_text(spec, part, flag), where, shown=part) for part in parts[:2]
        )
        return np.linspace(start, stop, count)
    if len(parts) != 1:
        raise InputError(
            f"{flag}: expected start:stop:count or a comma-separated list of numbers, got {text!r}"
        )
    values = text.split(",")
    _GRID_COUNT.check(len(values), f"{flag} {text}: count")
    return np.array(
        [spec.check(_from_text(spec, part, flag), where, shown=part) for part in values]
    )


class _Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line with exit status 2, which reads
    ``--a -1e-3`` as a value (any number, not only ``-1`` or ``-.5``), and which takes flags
    whole: an abbreviation would change its meaning when a flag is added (``--a`` of ``tube``
    would become ``--across``).

    A command's ``flags(parser)``, if given, adds its arguments when the command is parsed
    or its help shown: the modules their specs come from are imported only for that command.
    """

    def __init__(
        self, *args, flags: Callable[[argparse.ArgumentParser], None] | None = None, **kwargs
    ) -> None:
        super().__init__(*args, **{"allow_abbrev": False, **kwargs})
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
        )
        self._flags = flags

    def _add_flags(self) -> None:
        if self._flags is not None:
            flags, self._flags = self._flags, None
            flags(self)

    def parse_known_args(self, args=None, namespace=None):
        self._add_flags()
        return super().parse_known_args(args, namespace)

    def format_help(self) -> str:
        self._add_flags()
        return super().format_help()

    def parse_args(self, args=None, namespace=None):
        parsed, extras = self.parse_known_args(args, namespace)
        if extras:
            self.error(unrecognized(self, getattr(parsed, "command", None), extras))
        return parsed

    def error(self, message: str) -> None:  # type: ignore[override]
        # the program's own name is the error line's prefix already; a command's is kept
        prefix = "" if " " not in self.prog else f"{self.prog}: "
        raise InputError(f"{prefix}{message}")

    def commands(self) -> dict[str, _Parser]:
        """The parser of every command, by name (none for a command's parser)."""
        return {
            name: command
            for action in self._actions
            if isinstance(action, argparse._SubParsersAction)
            for name, command in action.choices.items()
        }

    def long_flags(self) -> list[str]:
        """Every ``--flag`` this parser takes (a command's own flags added first)."""
        self._add_flags()
        return [flag for flag in self._option_string_actions if flag.startswith("--")]


def unrecognized(parser: _Parser, command: str | None, extras: Sequence[str]) -> str:
    """The usage error of words no flag takes, each unknown flag with the nearest one suggested:
    the command's own spelled alike (``--pxy``: ``--p-xy``), else the commands that take it
    (``--a`` is ``vault``'s), else the command's closest.
    """
    commands = parser.commands()
    own = parser if command is None else commands[command]
    where = PROG if command is None else f"{PROG} {command}"
    hints = [
        hint
        for word in extras
        if word.startswith("--")
        and (hint := _nearest_flag(word.split("=")[0], where, own, commands, command))
    ]
    return f"unrecognized arguments: {' '.join(extras)}" + "".join(f"; {h}" for h in hints)


def _nearest_flag(
    flag: str, where: str, own: _Parser, commands: dict[str, _Parser], command: str | None
) -> str | None:
    def bare(text: str) -> str:
        return text.lstrip("-").replace("-", "").replace("_", "").lower()

    mine = own.long_flags()
    alike = [f for f in mine if bare(f) == bare(flag)]
    if alike:
        return f"did you mean {alike[0]}?"
    others = [
        f"{PROG} {name}"
        for name, other in commands.items()
        if name != command and flag in other.long_flags()
    ]
    if others:
        return f"{flag} is a flag of {_listed(others)}, not of {where}"
    close = difflib.get_close_matches(flag, mine, n=1, cutoff=0.75)
    return f"did you mean {close[0]}?" if close else None


def _listed(names: Sequence[str]) -> str:
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


class _Version(argparse.Action):
    """``--version``: the installed version, read only when asked (the metadata reader is slow to
    import)."""

    def __init__(self, option_strings: Sequence[str], dest: str, **kwargs) -> None:
        super().__init__(
            option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, nargs=0, **kwargs
        )

    def __call__(self, parser, namespace, values, option_string=None) -> None:
        from ..kernel._version import VERSION

        print(f"{parser.prog} {VERSION}")
        parser.exit()


# -- flags generated from the design schema --------------------------------------------------

#: Schema keys with no flag (a list of cells is written in a design file).
_NO_FLAG = ("cells",)


def _flag(spec: Spec) -> str:
    """``--fold-angle`` for ``fold_angle``; ``--no-glue-tabs`` for a key true by default."""
    dashed = spec.name.replace("_", "-")
    return f"--no-{dashed}" if spec.kind == "flag" and spec.default else f"--{dashed}"


def _from_text(spec: Spec, text: str, flag: str | None = None):
    """A flag's text as the value a design file would hold (checked by the spec afterwards);
    a number that does not read as one is refused here, naming the flag."""
    value = from_text(spec, text)
    types = {"real": (int, float), "integer": (int,), "count": (int,)}.get(spec.kind)
    unset = "max" if spec.kind == "count" else None  # a count's other value
    if types and not isinstance(value, types) and value != unset:
        least = "" if spec.range is None else f" ≥ {spec.range.lo:g}"
        form = {
            "real": f"a number ({spec.unit})" if spec.unit else "a number",
            "integer": "a whole number",
            "count": f"a whole number{least} or 'max'",
        }[spec.kind]
        raise InputError(f"{flag or _flag(spec)}: must be {form}, got {text!r}")
    return value


def _flag_value(spec: Spec, text: str):
    """A flag's text as a checked value; a function is checked later, on the design's sample
    grid."""
    value = _from_text(spec, text)
    return (
        value
        if spec.kind == "function"
        else spec.check(value, f"{_flag(spec)} {text}: {spec.name}", shown=text)
    )


def _flag_specs(kind: str) -> dict[str, Spec]:
    """The spec of every design flag of a kind, by argparse destination."""
    return {name: spec for name, spec in kind_specs(kind).items() if name not in _NO_FLAG}


def _formats_help(kind: str) -> str:
    names = default_formats(design_kind(kind).formats_kind)
    if not names:
        return (
            f"no file formats are written for a {kind} design (the report and its pictures "
            "always are)"
        )
    listed = "; ".join(f"{n}: {FORMATS[n].holds}" for n in names)
    return (
        "comma-separated formats to write besides the report and its pictures (default: all): "
        f"{listed}"
    )


def _add_design_flags(p: argparse.ArgumentParser, kind: str) -> None:
    """The design file argument and one flag per schema key of the kind, help from the spec."""
    p.add_argument(
        "design",
        nargs="?",
        type=Path,
        help="a TOML design file (see examples/); flags override its values",
    )
    groups = {"design": p.add_argument_group("design"), "output": p.add_argument_group("output")}
    if OPTIONAL_SECTIONS[kind]:
        groups["load"] = p.add_argument_group(
            "under load",
            "what the structure is made of and "
            "what loads it: with any of these its output folder holds its mechanics (curvefold "
            "load always analyses it); with --panels N, vault, tube and block build the panels "
            "as solids of the thickness (thick panels: their solids, cut list and range)",
        )
    section = {
        spec.name: name
        for name in ("output", *OPTIONAL_SECTIONS[kind])
        for spec in SCHEMA[name].values()
    }
    for name, spec in _flag_specs(kind).items():
        group = groups[{"output": "output", None: "design"}.get(section.get(name), "load")]
        _add_spec_flag(group, name, spec, kind)


def _load_specs(kind: str) -> dict[str, Spec]:
    """The spec of every key of a kind's optional sections (``[material]``, ``[loads]``)."""
    return {key: spec for name in OPTIONAL_SECTIONS[kind] for key, spec in SCHEMA[name].items()}


def _add_spec_flag(group, name: str, spec: Spec, kind: str) -> None:
    """The flag of one schema key, its help and metavar from the spec."""
    if spec.kind == "flag":
        # a spec's help says what the key does when true, the flag what it sets
        text = (
            f"{spec.help}{' by default; this flag turns it off' if spec.default else ''} "
            f"(sets {name} = {str(not spec.default).lower()})"
        )
        group.add_argument(
            _flag(spec),
            dest=name,
            action="store_const",
            const=not spec.default,
            default=None,
            help=text,
        )
    else:
        text = (_formats_help(kind) if spec.kind == "formats" else spec.describe()).replace(
            "%", "%%"
        )
        metavar = {
            "formats": "LIST",
            "page": "PAGE",
            "count": "N|max",
            "choice": "{" + ",".join(spec.choices) + "}",
        }
        group.add_argument(
            _flag(spec), dest=name, metavar=metavar.get(spec.kind, name.upper()), help=text
        )


def _design_flags(
    kind: str, args: argparse.Namespace, specs: dict[str, Spec] | None = None
) -> tuple[dict, list[str]]:
    """The given design flags as checked values, and the words the user typed for them (of
    ``specs`` only when given).

    Raises
    ------
    InputError
        A flag's value, named as typed: ``--page A9: page must be one of …, got A9``.
    """
    values, typed = {}, []
    for name, spec in (_flag_specs(kind) if specs is None else specs).items():
        text = getattr(args, name)
        if text is None:
            continue
        if spec.kind == "flag":
            values[name] = text
            typed.append(_flag(spec))
        else:
            values[name] = _flag_value(spec, text)
            typed.append(f"{_flag(spec)} {text}")
    return values, typed


def _add_target_flags(p: argparse.ArgumentParser, kind: DesignKind) -> None:
    """A kind's targets as flags (a vault's --span, --rise, --p-xz), help and checks from specs."""
    if kind.targets is None:
        return
    g = p.add_argument_group("targets", kind.targets.help)
    for spec in kind.targets.specs():
        g.add_argument(
            _flag(spec),
            dest=spec.name,
            metavar=spec.name.upper(),
            help=spec.describe().replace("%", "%%"),
        )


def _fit_targets(design: Design, args: argparse.Namespace) -> Design:
    """The design with the parameters its kind's target flags replace solved for them."""
    fit = design.design_kind.targets
    specs = {} if fit is None else {spec.name: spec for spec in fit.specs()}
    given = {name: text for name in specs if (text := getattr(args, name, None)) is not None}
    if fit is None or not given:
        return design
    targets = {name: _flag_value(specs[name], text) for name, text in given.items()}
    flags = kind_specs(design.kind)
    for target, replaced in fit.replaces().items():
        if target in targets and getattr(args, replaced, None) is not None:
            raise InputError(
                f"{_flag(specs[target])} sets {replaced}: give {_flag(specs[target])} "
                f"or {_flag(flags[replaced])}, not both"
            )
    return fit.fit(design, source=design.source, **targets)[0]
