"""Design files: what to build, in TOML, validated against one declarative schema.

A design file names the kind of structure and its parameters::

    kind = "vault"
    samples = 801

    [vault]
    a = 0.3
    p_xy = 0.75
    fold_angle = 90.0

    [output]
    units = "mm"
    formats = ["svg", "fold"]

A vault, tube or block may also say what it is made of and what loads it, in the optional
sections ``[material]`` and ``[loads]`` (:data:`OPTIONAL_SECTIONS`, :mod:`curvefold.app._loading`).

:data:`SCHEMA` holds the :class:`~curvefold.kernel.Spec` of every section and key
(kind of value, unit, allowed range, default and meaning), composed from the parameters'
owners: ``[vault]`` from :data:`curvefold.vault._assembly.VAULT_SPECS`, ``[output]`` from
:data:`curvefold.io._formats.OUTPUT_SPECS`, the rest declared here. The command-line flags
are generated from it (:mod:`curvefold.app.cli`). The loader checks a file against it once
and returns a frozen :class:`Design` with every default filled in. Unknown sections and
keys, wrong types, values out of range and sections that belong to another kind are
refused with an :class:`~curvefold.kernel.InputError` that names the file, the
section, the key, the requirement and the value received.

Function-valued keys (``kappa``, ``tau``, ``kappa_2d``, ``beta_left``, ``beta_right``,
``alpha``) take a number, an expression in ``s`` (:func:`curvefold.kernel.compile_expression`)
or a CSV column ``{csv = "file.csv", column = "kappa"}`` read from the design file's folder.
Their values are checked on the sample grid too, so ``kappa = "sin(s)"`` fails at load time
with the arc length where κ stops being positive.

A ``[crease]`` gives either ``beta_right`` (α(s) then follows from Eq. (3), integrated from
``fold_angle``) or ``alpha`` (β_R then follows from Eq. (3); ``fold_angle`` is 2α(0) and may
be left out), never both.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from types import MappingProxyType
from typing import Any, TypeVar

from ..io._formats import OUTPUT_SPECS, check_scale, default_formats
from ..io._reading import read_bytes
from ..kernel._errors import InputError
from ..kernel._expr import Expression
from ..kernel._functions import ScalarFunction, as_function
from ..kernel._validate import REQUIRED, Spec, describe, suggest
from ..mechanics import LoadCase
from ._design_functions import Context, TableColumn, check_function
from ._kinds import (
    BlockParams,
    CreaseParams,
    CurveParams,
    DesignKind,
    TubeParams,
    VaultParams,
    design_kind,
    design_kinds,
    registry_version,
)
from ._loading import (
    LOADS_SECTION,
    MATERIAL_SECTION,
    LoadParams,
    MaterialParams,
    check_cases,
    check_material,
    material_alternatives,
)

__all__ = [
    "Design",
    "VaultParams",
    "CurveParams",
    "TubeParams",
    "BlockParams",
    "CreaseParams",
    "OutputParams",
    "TableColumn",
    "SCHEMA",
    "KINDS",
    "SECTIONS_OF_KIND",
    "OPTIONAL_SECTIONS",
    "load_design",
    "parse_design",
    "design_from_dict",
    "default_design",
    "kind_specs",
]

#: Largest design file read, in bytes.
MAX_DESIGN_BYTES = 1 << 20

_P = TypeVar("_P")

#: The kinds curvefold itself registers (:mod:`curvefold.app._kinds`);
#: :func:`~curvefold.app._kinds.design_kinds` gives them with any registered since.
KINDS = tuple(kind.name for kind in design_kinds())


class _ByKind(Mapping[str, tuple[str, ...]]):
    """Kind name -> the names of some of its sections, read from the registry of kinds when
    asked."""

    def __init__(self, read: Callable[[DesignKind], tuple[str, ...]]) -> None:
        self._read = read

    def __getitem__(self, kind: str) -> tuple[str, ...]:
        found = {k.name: k for k in design_kinds()}.get(kind)
        if found is None:
            raise KeyError(kind)
        return self._read(found)

    def __iter__(self) -> Iterator[str]:
        return iter([k.name for k in design_kinds()])

    def __len__(self) -> int:
        return len(design_kinds())


#: Sections each kind reads besides ``[output]``
#: (:attr:`DesignKind.sections <curvefold.app._kinds.DesignKind.sections>`).
SECTIONS_OF_KIND: Mapping[str, tuple[str, ...]] = _ByKind(lambda kind: kind.section_names)
#: Sections a kind reads only when a design has them: what it is made of and what loads it.
OPTIONAL_SECTIONS: Mapping[str, tuple[str, ...]] = _ByKind(lambda kind: kind.optional)


# --------------------------------------------------------------------------------------------
# The schema: the specs of every section, composed from their owners


def _section(*specs: Spec) -> Mapping[str, Spec]:
    return MappingProxyType({spec.name: spec for spec in specs})


#: The sections every kind may read: ``[output]`` (:data:`curvefold.io._formats.OUTPUT_SPECS`),
#: ``[material]`` and ``[loads]`` (:mod:`curvefold.app._loading`).
_COMMON = {
    "output": _section(*OUTPUT_SPECS),
    "material": _section(*MATERIAL_SECTION),
    "loads": _section(*LOADS_SECTION),
}

#: Keys of a section that hold a list of tables, checked apart: ``[[loads.case]]``
#: (:func:`check_cases`).
_LISTED: Mapping[str, tuple[str, ...]] = MappingProxyType({"loads": ("case",)})


def _top(kinds: tuple[str, ...]) -> Mapping[str, Spec]:
    return _section(
        Spec("kind", "choice", REQUIRED, choices=kinds, help="what to build", label="structure"),
        Spec(
            "samples",
            "integer",
            801,
            "[9, 200000]",
            help="samples along curve 1",
            why="the certificate's differences need 9; memory is budgeted besides",
            label="samples along each crease",
        ),
        Spec("title", "text", "", help="free text for reports", label="title"),
    )


class _Schema(Mapping[str, Mapping[str, Spec]]):
    """Every section ("" is the top level) and the specs of its keys, in file order: the top level,
    the sections of the registered kinds (:mod:`curvefold.app._kinds`), then ``[output]``,
    ``[material]`` and ``[loads]``. Read from the registry when asked, so a kind registered later
    is in it."""

    def __init__(self) -> None:
        self._cache: tuple[int, Mapping[str, Mapping[str, Spec]]] | None = None

    def _sections(self) -> Mapping[str, Mapping[str, Spec]]:
        version = registry_version()
        if self._cache is None or self._cache[0] != version:
            kinds = design_kinds()
            sections: dict[str, Mapping[str, Spec]] = {"": _top(tuple(k.name for k in kinds))}
            for kind in kinds:
                sections |= {section.name: section.specs for section in kind.sections}
            self._cache = (version, MappingProxyType(sections | _COMMON))
        return self._cache[1]

    def __getitem__(self, section: str) -> Mapping[str, Spec]:
        return self._sections()[section]

    def __iter__(self) -> Iterator[str]:
        return iter(self._sections())

    def __len__(self) -> int:
        return len(self._sections())


#: Every section ("" is the top level) and the specs of its keys, in file order: the ``[vault]``
#: specs are :data:`curvefold.vault._assembly.VAULT_SPECS`, the ``[output]`` specs
#: :data:`curvefold.io._formats.OUTPUT_SPECS`, each kind's those it registers with
#: (:class:`curvefold.app._kinds.DesignKind`).
SCHEMA: Mapping[str, Mapping[str, Spec]] = _Schema()


def _section_names() -> tuple[str, ...]:
    """Every section name but the top level's."""
    return tuple(name for name in SCHEMA if name)


def _params_type(section: str) -> type:
    """The frozen dataclass a section's checked values become."""
    common = {"output": OutputParams, "material": MaterialParams, "loads": LoadParams}
    if section in common:
        return common[section]
    return next(s.params for kind in design_kinds() for s in kind.sections if s.name == section)


# --------------------------------------------------------------------------------------------
# Validated values


@dataclass(frozen=True)
class OutputParams:
    """``[output]``: units, scale, page, how the crease patterns are cut, and file formats."""

    units: str
    scale: float | None
    page: str | tuple[float, float]
    glue_tabs: bool
    rulings: bool
    cutter: str
    perforation: float | None
    perforation_gap: float
    kerf: float
    formats: tuple[str, ...]


@dataclass(frozen=True)
class Design:
    """A validated design: what to build, with every default filled in.

    Build it with :func:`load_design`, :func:`parse_design`, :func:`design_from_dict` or
    :func:`default_design`; derive variants with :meth:`overrides`. It holds the sections of
    its kind (:data:`SECTIONS_OF_KIND`), read by :meth:`params` (``design.params(VaultParams)``)
    or by name (``design.vault``: None for a section of another kind), ``output``, and its
    optional ones (:data:`OPTIONAL_SECTIONS`) when given, else None.

    Parameters
    ----------
    kind : str
        A registered kind (:func:`curvefold.app._kinds.design_kinds`): ``"vault"``,
        ``"tube"``, ``"block"``, ``"crease"``.
    samples : int
        Samples along curve 1.
    title : str
    output : OutputParams
    sections : tuple of (str, params)
        The kind's sections by name, in file order.
    material, loads : section parameters or None
    source : str
        Where the design came from (a file name), used in messages.
    base_dir : Path or None
        Folder CSV paths are relative to.
    """

    kind: str
    samples: int
    title: str
    output: OutputParams
    sections: tuple[tuple[str, Any], ...] = ()
    material: MaterialParams | None = None
    loads: LoadParams | None = None
    source: str = field(default="<defaults>", compare=False)
    base_dir: Path | None = field(default=None, compare=False, repr=False)

    def __getattr__(self, name: str) -> Any:
        """A section by name (``design.vault``): its values, or None for a section of
        another kind."""
        if name.startswith("_") or "sections" not in self.__dict__:
            raise AttributeError(name)
        found = dict(self.__dict__["sections"])
        if name in found:
            return found[name]
        if name in _section_names():
            return None
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    @property
    def design_kind(self) -> DesignKind:
        """The registered kind of this design."""
        return design_kind(self.kind)

    def params(self, section: type[_P]) -> _P:
        """The values of the section of this design's kind that are a ``section``
        (``design.params(VaultParams)``).

        Raises
        ------
        InputError
            The design's kind has no such section.
        """
        for _, values in self.sections:
            if isinstance(values, section):
                return values
        raise InputError(f"{self.source}: a {self.kind} design has no {section.__name__}")

    def to_dict(self) -> dict[str, Any]:
        """The design as plain data in TOML form: expressions as their text, CSV columns as
        ``{"csv": ..., "column": ...}``, tuples as lists; absent optional keys left out.

        ``design_from_dict(d.to_dict(), base_dir=d.base_dir) == d``.
        """
        out: dict[str, Any] = {"kind": self.kind, "samples": self.samples, "title": self.title}
        for section in (*SECTIONS_OF_KIND[self.kind], "output", *OPTIONAL_SECTIONS[self.kind]):
            params = getattr(self, section)
            if params is None:
                continue
            values = {f.name: _plain(getattr(params, f.name)) for f in fields(params)}
            out[section] = {k: v for k, v in values.items() if v is not None}
        return out

    def overrides(self, *, source: str | None = None, **flags: Any) -> Design:
        """A new design with the non-None ``flags`` replacing file values, validated anew.

        Flags are key names without their section (``a=0.4``, ``samples=1601``,
        ``fold_angle=60.0``, ``formats=["svg"]``); within one kind every key name is unique.
        A section name with a mapping (``vault={"a": 0.4}``) sets several keys. Changing
        ``kind`` drops the old kind's sections and starts from the new kind's defaults.
        ``source`` names the result in messages (default: this design's source
        ``"(with overrides)"``).

        Raises
        ------
        InputError
            An unknown flag, or a value the schema refuses.
        """
        data = self.to_dict()
        source = source or f"{self.source} (with overrides)"
        kind = flags.pop("kind", None)
        if kind is not None and kind != self.kind:
            kind = SCHEMA[""]["kind"].check(kind, f"{source}: kind")
            data = {
                "kind": kind,
                "samples": data["samples"],
                "title": data["title"],
                "output": data["output"],
            }
        kind = data["kind"]
        allowed = _flag_sections(kind)
        _alternatives(data, flags)
        for flag, value in flags.items():
            if value is None:
                continue
            key = flag.replace("-", "_")
            if key in allowed.values() and isinstance(value, Mapping):
                data.setdefault(key, {}).update(value)
            elif key in allowed:
                section = allowed[key]
                target = data if section == "" else data.setdefault(section, {})
                target[key] = value
            else:
                raise InputError(
                    f"{source}: unknown option {flag!r} for kind {kind!r} (allowed: "
                    f"{', '.join(allowed)})" + suggest(key, allowed)
                )
        return design_from_dict(data, source=source, base_dir=self.base_dir)

    @property
    def mechanics(self) -> bool:
        """Whether the design says what it is made of or what loads it: its output folders then
        hold its mechanics."""
        return self.material is not None or self.loads is not None

    def with_mechanics(self) -> Design:
        """This design with its ``[material]`` and ``[loads]`` as given or at their defaults
        (``curvefold load``).

        Raises
        ------
        InputError
            For a single curved fold, which has no end sections to hold.
        """
        if not self.design_kind.loaded:
            *others, last = sorted(
                (k.name for k in design_kinds() if k.loaded), key=lambda k: design_kind(k).grounded
            )
            what = (
                "a single curved fold"
                if not self.design_kind.structure
                else f"a {self.kind} design"
            )
            raise InputError(
                f"{self.source}: {what} has no end sections to hold: "
                f"load a {', '.join(others)} or {last}"
            )
        return self.overrides(source=self.source, material={}, loads={})

    def tables(self) -> tuple[Path, ...]:
        """The CSV files the design reads, each once."""
        values = [getattr(params, f.name) for _, params in self.sections for f in fields(params)]
        folder = Path.cwd() if self.base_dir is None else self.base_dir
        return tuple(dict.fromkeys(folder / v.path for v in values if isinstance(v, TableColumn)))

    def function(self, key: str) -> ScalarFunction:
        """A function-valued key (e.g. ``"kappa"``) as a :class:`ScalarFunction` of arc length.

        Values are in the design file's units: angles stay in degrees.
        """
        section = next(
            (
                s
                for s in SECTIONS_OF_KIND[self.kind]
                if key in SCHEMA[s] and SCHEMA[s][key].kind == "function"
            ),
            None,
        )
        if section is None:
            raise InputError(f"{key!r} is not a function-valued key of kind {self.kind!r}")
        params = dict(self.sections)[section]
        value = getattr(params, key)
        if value is None:
            raise InputError(f"[{section}] {key} is not set in {self.source}")
        if isinstance(value, TableColumn):
            value = value.values
        elif isinstance(value, Expression) and value.constant is not None:
            value = value.constant  # exact derivative for constants
        return as_function(value, name=f"[{section}] {key}", length=params.length)


def _alternatives(data: dict, flags: Mapping[str, Any]) -> None:
    """A named material and one's own values are alternatives, and keys of a kind's sections
    (:attr:`DesignKind.alternatives <curvefold.app._kinds.DesignKind.alternatives>`: a
    [crease]'s ``alpha`` and ``beta_right``): the one the flags set drops the other from the
    design's data, unless the flags set both."""
    given = {
        k.replace("-", "_")
        for k, v in flags.items()
        if v is not None and not isinstance(v, Mapping)
    }
    # a section's keys
    given |= {key for value in flags.values() if isinstance(value, Mapping) for key in value}
    material_alternatives(data, given)
    kind = design_kind(data["kind"])
    if kind.alternatives is not None:
        kind.alternatives(data, given)


def _flag_sections(kind: str) -> dict[str, str]:
    """Key name -> section ("" for top level) of every key a design of ``kind`` accepts."""
    out: dict[str, str] = {}
    for section in ("", *SECTIONS_OF_KIND[kind], "output", *OPTIONAL_SECTIONS[kind]):
        for key in SCHEMA[section]:
            if key != "kind":
                out[key] = section
    return out


def kind_specs(kind: str) -> dict[str, Spec]:
    """The spec of every key a design of ``kind`` accepts besides ``kind``, by key name (unique
    within a kind): the top level, the kind's sections and ``[output]``."""
    return {key: SCHEMA[section][key] for key, section in _flag_sections(kind).items()}


def _plain(value: Any) -> Any:
    if isinstance(value, LoadCase):
        return value.to_dict()
    if isinstance(value, Expression):
        return value.text
    if isinstance(value, TableColumn):
        return {"csv": value.path, "column": value.column}
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    return value


# --------------------------------------------------------------------------------------------
# Loading


def load_design(path: str | os.PathLike) -> Design:
    """Read and validate a TOML design file.

    Parameters
    ----------
    path : str or path-like
        The design file: a regular file of UTF-8 text (a byte-order mark is skipped), at
        most :data:`MAX_DESIGN_BYTES`. CSV tables it refers to are read from its folder.

    Returns
    -------
    Design

    Raises
    ------
    InputError
        The file cannot be read, is not valid TOML or does not match :data:`SCHEMA`; the
        message starts with ``path``.
    """
    source = os.fspath(path)
    file = Path(path)
    raw = read_bytes(file, limit=MAX_DESIGN_BYTES, what="design file", name=source)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(
            f"{source}: design file is not UTF-8 text (bad byte at offset {exc.start})"
        ) from None
    return parse_design(text, source=source, base_dir=file.parent)


def parse_design(
    text: str, *, source: str = "<string>", base_dir: str | os.PathLike | None = None
) -> Design:
    """Validate a design given as TOML text.

    Parameters
    ----------
    text : str
        TOML text.
    source : str, optional
        Name used at the start of error messages.
    base_dir : str or path-like, optional
        Folder CSV tables are read from; default the current working directory.

    Returns
    -------
    Design

    Examples
    --------
    >>> d = parse_design('kind = "vault"\\n[vault]\\na = 0.4')
    >>> d.vault.a, d.vault.fold_angle, d.output.units
    (0.4, 90.0, 'mm')
    >>> parse_design('kind = "vault"\\n[vault]\\nfold_angle = 180.0', source="design.toml")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: design.toml: [vault] fold_angle must be in (0, 180)
    degrees, got 180.0
    """
    if not isinstance(text, str):
        raise InputError(f"{source}: expected TOML text, got {type(text).__name__}")
    if len(text) > MAX_DESIGN_BYTES:
        raise InputError(f"{source}: design text is longer than {MAX_DESIGN_BYTES} characters")
    import tomllib  # here: its regular expressions are compiled on import

    try:
        # a byte-order mark, which some editors write, is not TOML
        data = tomllib.loads(text.removeprefix("\ufeff"))
    except (RecursionError, MemoryError):
        raise InputError(f"{source}: invalid TOML: nested too deeply") from None
    except ValueError as exc:  # TOMLDecodeError, and integers past Python's digit limit
        raise InputError(f"{source}: invalid TOML: {exc}") from None
    return design_from_dict(data, source=source, base_dir=base_dir)


def design_from_dict(
    data: Mapping[str, Any], *, source: str = "<dict>", base_dir: str | os.PathLike | None = None
) -> Design:
    """Validate a design given as plain data (a parsed TOML or JSON document).

    Parameters
    ----------
    data : mapping
        Top-level keys and one mapping per section, as in a design file.
    source : str, optional
        Name used at the start of error messages.
    base_dir : str or path-like, optional
        Folder CSV tables are read from; default the current working directory.

    Returns
    -------
    Design
    """
    if not isinstance(data, Mapping):
        raise InputError(f"{source}: a design must be a table, got {describe(data)}")
    folder = Path.cwd() if base_dir is None else Path(base_dir)
    top = SCHEMA[""]
    names = _section_names()
    if "kind" not in data:
        kinds = ", ".join(f'"{k.name}"' for k in design_kinds())
        raise InputError(f"{source}: missing required key 'kind' (one of {kinds})")
    kind = top["kind"].check(data["kind"], f"{source}: kind")
    registered = design_kind(kind)
    used = (*registered.section_names, *(s for s in registered.optional if s in data))
    for key, value in data.items():
        if key in names:
            if not isinstance(value, Mapping):
                raise InputError(
                    f"{source}: {key} must be a table ([{key}] section), got {describe(value)}"
                )
            if key != "output" and key not in used:
                users = " or ".join(
                    repr(k.name) for k in design_kinds() if key in (*k.section_names, *k.optional)
                )
                raise InputError(
                    f"{source}: section [{key}] is used by kind {users}, not by kind {kind!r}; "
                    "remove it or change kind"
                )
        elif key not in top:
            what = f"section [{key}]" if isinstance(value, Mapping) else f"key {key!r}"
            raise InputError(
                f"{source}: unknown {what} (allowed keys: {', '.join(top)}; "
                f"sections: {', '.join(names)})" + suggest(key, (*top, *names))
            )
    head = _check_section("", data, Context(source, folder, 0), skip=names)
    ctx = Context(source, folder, head["samples"])
    checked = {
        s: _check_section(s, data.get(s, {}), ctx, skip=_LISTED.get(s, ()))
        for s in (*used, "output")
    }
    if checked["output"]["formats"] is None:
        checked["output"]["formats"] = default_formats(registered.formats_kind)
    if registered.check is not None:
        registered.check(checked, data, source)
    if "material" in checked:
        check_material(checked["material"], f"{source}: [material] ")
    if "loads" in checked:
        listed = data["loads"].get("case")
        checked["loads"]["case"] = check_cases(listed, f"{source}: [[loads.case]] ")
    out = checked["output"]
    # crease 1's length in model units (a vault's at least π × radius: its κ0·s0 is above π)
    check_scale(
        out["scale"], out["units"], registered.crease_length(checked), f"{source}: [output] scale"
    )
    params = {s: _params_type(s)(**values) for s, values in checked.items()}
    optional = {s: params.pop(s) for s in registered.optional if s in params}
    return Design(
        kind=kind,
        samples=head["samples"],
        title=head["title"],
        output=params.pop("output"),
        sections=tuple((s, params[s]) for s in registered.section_names),
        source=source,
        base_dir=folder.resolve(),
        **optional,
    )


def default_design(kind: str) -> Design:
    """The built-in design of ``kind``: every key at its default (see :data:`SCHEMA`).

    Examples
    --------
    >>> default_design("vault").vault.tubes
    'max'
    """
    return design_from_dict({"kind": kind}, source="<defaults>")


# --------------------------------------------------------------------------------------------
# Checking


def _check_section(
    section: str, table: Mapping[str, Any], ctx: Context, skip: tuple[str, ...] = ()
) -> dict:
    """Validate one section against the schema; fill defaults. Function keys go last (they
    need the section's length)."""
    specs = SCHEMA[section]
    prefix = f"{ctx.source}: " if section == "" else f"{ctx.source}: [{section}] "
    for key in table:
        if key not in specs and key not in skip:
            raise InputError(
                f"{prefix}unknown key {key!r} (allowed: {', '.join(specs)})" + suggest(key, specs)
            )
    out: dict[str, Any] = {}
    for key in sorted(specs, key=lambda k: specs[k].kind == "function"):
        spec = specs[key]
        value = table.get(key)  # an explicit None (JSON null) means the default
        if value is None and spec.required:
            raise InputError(f"{prefix}missing required key {key!r}", parameter=key)
        if value is None:
            value = spec.default
        if value is None:
            out[key] = None
        elif spec.kind == "function":
            out[key] = check_function(spec, value, section, ctx, out["length"])
        else:
            out[key] = spec.check(value, f"{prefix}{key}")
    return {key: out[key] for key in specs}
