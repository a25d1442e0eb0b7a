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

:data:`SCHEMA` lists every section and key with its type, unit, allowed range, default and
meaning; the loader checks a file against it once and returns a frozen :class:`Design` with
every default filled in. Unknown sections and keys, wrong types, values out of range and
sections that belong to another kind are refused with an :class:`~curvefold.kernel.errors.InputError`
that names the file, the section, the key, the requirement and the value received.

Function-valued keys (``kappa``, ``tau``, ``kappa_2d``, ``beta_left``, ``beta_right``,
``alpha``) take a number, an expression in ``s`` (:func:`curvefold.kernel.expr.compile_expression`)
or a CSV column ``{csv = "file.csv", column = "kappa"}`` read from the design file's folder.
Their values are checked on the sample grid too, so ``kappa = "sin(s)"`` fails at load time
with the arc length where κ stops being positive.
"""

from __future__ import annotations

import csv
import difflib
import io
import math
import os
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path, PurePosixPath, PureWindowsPath
from types import MappingProxyType
from typing import Any, Literal

import numpy as np

from ..geometry.curve import MAX_SAMPLES
from ..kernel.errors import InputError
from ..kernel.expr import Expression, compile_expression
from ..kernel.functions import ScalarFunction, as_function

__all__ = [
    "Design",
    "VaultParams",
    "CurveParams",
    "TubeParams",
    "BlockParams",
    "CreaseParams",
    "OutputParams",
    "TableColumn",
    "KeySpec",
    "Interval",
    "SCHEMA",
    "KINDS",
    "SECTIONS_OF_KIND",
    "FORMATS",
    "PAGES",
    "load_design",
    "parse_design",
    "design_from_dict",
    "default_design",
]

KINDS = ("vault", "tube", "block", "crease")
#: Sections each kind reads besides ``[output]``.
SECTIONS_OF_KIND: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"vault": ("vault",), "tube": ("curve", "tube"), "block": ("curve", "block"), "crease": ("crease",)}
)
FORMATS = ("svg", "dxf", "pdf", "fold", "glb", "obj", "3dm", "stl", "ply", "gif")
#: Named page sizes, (width, height) in millimetres.
PAGES: Mapping[str, tuple[float, float]] = MappingProxyType(
    {"A4": (210.0, 297.0), "A3": (297.0, 420.0), "Letter": (215.9, 279.4)}
)

#: Largest design file read, in bytes.
MAX_DESIGN_BYTES = 1 << 20
#: Largest CSV file read, in bytes.
MAX_CSV_BYTES = 64 << 20
#: Bound on samples × crease lines (vertices of all lattice curves): about 1 GB with meshes.
MAX_VERTICES = MAX_SAMPLES

_REQUIRED = "<required>"


# --------------------------------------------------------------------------------------------
# The schema


@dataclass(frozen=True)
class Interval:
    """A real interval with open or closed ends, written like ``"(0, 180)"`` or ``"[3, inf)"``."""

    lo: float
    hi: float
    lo_closed: bool
    hi_closed: bool

    @classmethod
    def parse(cls, text: str) -> Interval:
        """Read interval notation: ``"[0, 3)"``, ``"(0, inf)"``, ``"(-inf, inf)"``."""
        lo, hi = (float(x) for x in text[1:-1].split(","))
        return cls(lo, hi, text[0] == "[", text[-1] == "]")

    def __contains__(self, x: float) -> bool:
        above = self.lo <= x if self.lo_closed else self.lo < x
        below = x <= self.hi if self.hi_closed else x < self.hi
        return above and below

    def __str__(self) -> str:
        if self.hi == math.inf and self.lo == -math.inf:
            return "finite"
        if self.hi == math.inf:
            return f"{'>=' if self.lo_closed else '>'} {_fmt(self.lo)}"
        left, right = "[" if self.lo_closed else "(", "]" if self.hi_closed else ")"
        return f"in {left}{_fmt(self.lo)}, {_fmt(self.hi)}{right}"


@dataclass(frozen=True)
class KeySpec:
    """One key of the schema.

    Parameters
    ----------
    type : str
        ``"float"``, ``"int"``, ``"tubes"`` (integer or ``"max"``), ``"choice"``, ``"text"``,
        ``"bool"``, ``"function"`` (number, expression or CSV column), ``"page"``,
        ``"formats"`` or ``"cells"``.
    default : object
        Value used when the key is absent; ``None`` means the key is optional with no value.
        Required keys have no default.
    range : Interval or None
        Allowed values (for functions: allowed values of the function).
    unit : str
        Unit shown in messages and help.
    choices : tuple of str
        Allowed strings for ``"choice"``, ``"page"`` and ``"formats"``.
    doc : str
        One-line meaning, for help texts.
    note : str
        Why the range is what it is, shown in messages (e.g. ``"memory bound"``).
    """

    type: str
    default: Any
    range: Interval | None = None
    unit: str = ""
    choices: tuple[str, ...] = ()
    doc: str = ""
    note: str = ""

    @property
    def required(self) -> bool:
        return isinstance(self.default, str) and self.default == _REQUIRED


def _key(
    type_: str, default: Any, range_: str | None = None, unit: str = "", *, choices=(), doc: str = "", note: str = ""
) -> KeySpec:
    return KeySpec(type_, default, None if range_ is None else Interval.parse(range_), unit, tuple(choices), doc, note)


_POSITIVE = "(0, inf)"
_ANGLE = "(0, 180)"

#: Every section ("" is the top level) and its keys, in file order.
SCHEMA: Mapping[str, Mapping[str, KeySpec]] = MappingProxyType({
    "": MappingProxyType({
        "kind": _key("choice", _REQUIRED, choices=KINDS, doc="what to build"),
        "samples": _key("int", 801, "[3, 200000]", doc="samples along curve 1", note="memory bound"),
        "title": _key("text", "", doc="free text for reports"),
    }),
    "vault": MappingProxyType({
        "a": _key("float", 0.3, "[0, 3)", doc="torsion amplitude: tau = a kappa0 sin(2 pi s / s0)"),
        "p_xy": _key("float", 0.75, "(0, 100]", doc="width ratio w_R(0) / w_L(0)"),
        "width": _key("float", 0.08, "(0, 10]", doc="w_L(0) kappa0, dimensionless"),
        "tubes": _key("tubes", "max", "[1, 1000]", doc='number of tubes, or "max"'),
        "fold_angle": _key("float", 90.0, _ANGLE, "degrees", doc="design fold angle 2 alpha"),
        "radius": _key("float", 1.0, _POSITIVE, "model units", doc="1 / kappa0"),
        "layers": _key("int", 1, "[1, 50]", doc="number of stacked bands"),
        "direction": _key("choice", "+", choices=("+", "-"), doc="stacking direction along the lattice diagonal"),
    }),
    "curve": MappingProxyType({
        "kappa": _key("function", 1.0, _POSITIVE, "per model unit", doc="curvature of curve 1 as a function of s"),
        "tau": _key("function", 0.2, "(-inf, inf)", "per model unit", doc="torsion of curve 1 as a function of s"),
        "length": _key("float", 6.0, _POSITIVE, "model units", doc="arc length of curve 1"),
        "fold_angle": _key("float", 90.0, _ANGLE, "degrees", doc="fold angle 2 alpha at which kappa, tau are given"),
    }),
    "tube": MappingProxyType({
        "width_left": _key("float", 0.3, _POSITIVE, "model units", doc="w_L(0)"),
        "width_right": _key("float", 0.3, _POSITIVE, "model units", doc="w_R(0)"),
    }),
    "block": MappingProxyType({
        "width_left": _key("float", 0.2, _POSITIVE, "model units", doc="w_L(0)"),
        "width_right": _key("float", 0.2, _POSITIVE, "model units", doc="w_R(0)"),
        "cells": _key("cells", [[0, 0], [0, 1], [1, 1]], "[-1000, 1000]", doc="lattice cells [i, j]"),
    }),
    "crease": MappingProxyType({
        "kappa_2d": _key("function", 0.5, "(-inf, inf)", "per model unit", doc="planar curvature of the crease"),
        "beta_left": _key("function", 90.0, _ANGLE, "degrees", doc="ruling angle on the left"),
        "beta_right": _key("function", 90.0, _ANGLE, "degrees", doc="ruling angle on the right"),
        "fold_angle": _key("float", 60.0, _ANGLE, "degrees", doc="initial fold angle 2 alpha(0)"),
        "length": _key("float", 3.0, _POSITIVE, "model units", doc="arc length of the crease"),
        "alpha": _key("function", None, "(0, 90)", "degrees", doc="optional alpha(s), half the fold angle"),
    }),
    "output": MappingProxyType({
        "units": _key("choice", "mm", choices=("mm", "cm", "m", "in", "unit"), doc="output length unit"),
        "scale": _key("float", None, _POSITIVE, "output units per model unit", doc="model units to output units (default: fit the largest sheet to the page)"),
        "page": _key("page", "A4", "(0, 10000]", "mm", choices=tuple(PAGES), doc="page name or [width, height]"),
        "glue_tabs": _key("bool", True, doc="draw glue tabs on the sheets"),
        "rulings": _key("bool", False, doc="draw the rulings on the crease patterns (for scoring or engraving)"),
        "formats": _key("formats", list(FORMATS), choices=FORMATS, doc="files to write (default: all)"),
    }),
})

_SECTIONS = tuple(name for name in SCHEMA if name)


# --------------------------------------------------------------------------------------------
# Validated values


@dataclass(frozen=True, eq=False)
class TableColumn:
    """Samples of a function read from a CSV column, uniformly spaced over ``[0, length]``.

    ``np.asarray(column)`` gives the samples, so :func:`curvefold.kernel.functions.as_function`
    accepts it directly.

    Parameters
    ----------
    path : str
        The path as written in the design file, relative to its folder.
    column : str
        Header of the column.
    values : (M,) ndarray
        The samples, read-only, M ≥ 2.
    """

    path: str
    column: str
    values: np.ndarray = field(repr=False)

    def __array__(self, dtype=None, copy=None) -> np.ndarray:
        if copy:
            return np.array(self.values, dtype=dtype)
        return np.asarray(self.values, dtype=dtype)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TableColumn):
            return NotImplemented
        return (self.path, self.column) == (other.path, other.column) and np.array_equal(self.values, other.values)

    def __hash__(self) -> int:
        return hash((self.path, self.column, self.values.size))


FunctionValue = float | Expression | TableColumn


@dataclass(frozen=True)
class VaultParams:
    """``[vault]``: a composite deployable vault (see :data:`SCHEMA` for ranges and units)."""

    a: float
    p_xy: float
    width: float
    tubes: int | Literal["max"]
    fold_angle: float
    radius: float
    layers: int
    direction: Literal["+", "-"]


@dataclass(frozen=True)
class CurveParams:
    """``[curve]``: curve 1 of a tube or block, with κ and τ given at ``fold_angle``."""

    kappa: FunctionValue
    tau: FunctionValue
    length: float
    fold_angle: float


@dataclass(frozen=True)
class TubeParams:
    """``[tube]``: the widths of a single tube at s = 0."""

    width_left: float
    width_right: float


@dataclass(frozen=True)
class BlockParams:
    """``[block]``: a cellular block, the widths at s = 0 and the lattice cells it uses."""

    width_left: float
    width_right: float
    cells: tuple[tuple[int, int], ...]


@dataclass(frozen=True)
class CreaseParams:
    """``[crease]``: a single curved fold from its crease pattern (angles in degrees)."""

    kappa_2d: FunctionValue
    beta_left: FunctionValue
    beta_right: FunctionValue
    fold_angle: float
    length: float
    alpha: FunctionValue | None


@dataclass(frozen=True)
class OutputParams:
    """``[output]``: units, scale, page and file formats."""

    units: str
    scale: float | None
    page: str | tuple[float, float]
    glue_tabs: bool
    rulings: bool
    formats: tuple[str, ...]


_PARAM_TYPES: Mapping[str, type] = MappingProxyType({
    "vault": VaultParams,
    "curve": CurveParams,
    "tube": TubeParams,
    "block": BlockParams,
    "crease": CreaseParams,
    "output": OutputParams,
})


@dataclass(frozen=True)
class Design:
    """A validated design: what to build, with every default filled in.

    Build it with :func:`load_design`, :func:`parse_design`, :func:`design_from_dict` or
    :func:`default_design`; derive variants with :meth:`overrides`. Only the sections of
    ``kind`` (see :data:`SECTIONS_OF_KIND`) and ``output`` are set; the others are None.

    Parameters
    ----------
    kind : {"vault", "tube", "block", "crease"}
    samples : int
        Samples along curve 1.
    title : str
    output : OutputParams
    vault, curve, tube, block, crease : section parameters or None
    source : str
        Where the design came from (a file name), used in messages.
    base_dir : Path or None
        Folder CSV paths are relative to.
    """

    kind: str
    samples: int
    title: str
    output: OutputParams
    vault: VaultParams | None = None
    curve: CurveParams | None = None
    tube: TubeParams | None = None
    block: BlockParams | None = None
    crease: CreaseParams | None = None
    source: str = field(default="<defaults>", compare=False)
    base_dir: Path | None = field(default=None, compare=False, repr=False)

    def to_dict(self) -> dict[str, Any]:
        """The design as plain data in TOML form: expressions as their text, CSV columns as
        ``{"csv": ..., "column": ...}``, tuples as lists; absent optional keys left out.

        ``design_from_dict(d.to_dict(), base_dir=d.base_dir) == d``.
        """
        out: dict[str, Any] = {"kind": self.kind, "samples": self.samples, "title": self.title}
        for section in (*SECTIONS_OF_KIND[self.kind], "output"):
            params = getattr(self, section)
            values = {f.name: _plain(getattr(params, f.name)) for f in fields(params)}
            out[section] = {k: v for k, v in values.items() if v is not None}
        return out

    def overrides(self, **flags: Any) -> Design:
        """A new design with the non-None ``flags`` replacing file values, validated anew.

        Flags are key names without their section (``a=0.4``, ``samples=1601``,
        ``fold_angle=60.0``, ``formats=["svg"]``); within one kind every key name is unique.
        A section name with a mapping (``vault={"a": 0.4}``) sets several keys. Changing
        ``kind`` drops the old kind's sections and starts from the new kind's defaults.

        Raises
        ------
        InputError
            An unknown flag, or a value the schema refuses.
        """
        data = self.to_dict()
        source = f"{self.source} (with overrides)"
        kind = flags.pop("kind", None)
        if kind is not None and kind != self.kind:
            kind = _check_choice(SCHEMA[""]["kind"], kind, f"{source}: kind")
            data = {"kind": kind, "samples": data["samples"], "title": data["title"], "output": data["output"]}
        kind = data["kind"]
        allowed = _flag_sections(kind)
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
                    f"{source}: unknown option {flag!r} for kind {kind!r} (allowed: {', '.join(allowed)})"
                    + _suggest(key, allowed)
                )
        return design_from_dict(data, source=source, base_dir=self.base_dir)

    def function(self, key: str) -> ScalarFunction:
        """A function-valued key (e.g. ``"kappa"``) as a :class:`ScalarFunction` of arc length.

        Values are in the design file's units: angles stay in degrees.
        """
        section = next((s for s in SECTIONS_OF_KIND[self.kind] if SCHEMA[s].get(key, _NOSPEC).type == "function"), None)
        if section is None:
            raise InputError(f"{key!r} is not a function-valued key of kind {self.kind!r}")
        params = getattr(self, section)
        value = getattr(params, key)
        if value is None:
            raise InputError(f"[{section}] {key} is not set in {self.source}")
        if isinstance(value, TableColumn):
            value = value.values
        elif isinstance(value, Expression) and value.constant is not None:
            value = value.constant  # exact derivative for constants
        return as_function(value, name=f"[{section}] {key}", length=params.length)


_NOSPEC = KeySpec("none", None)


def _flag_sections(kind: str) -> dict[str, str]:
    """Key name -> section ("" for top level) of every key a design of ``kind`` accepts."""
    out: dict[str, str] = {}
    for section in ("", *SECTIONS_OF_KIND[kind], "output"):
        for key in SCHEMA[section]:
            if key != "kind":
                out[key] = section
    return out


def _plain(value: Any) -> Any:
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
        The design file (UTF-8, at most :data:`MAX_DESIGN_BYTES`). CSV tables it refers to
        are read from its folder.

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
    try:
        if not file.is_file():
            raise InputError(f"{source}: design file not found (or not a regular file)")
        if file.stat().st_size > MAX_DESIGN_BYTES:
            raise InputError(f"{source}: design file is larger than {MAX_DESIGN_BYTES} bytes")
        raw = file.read_bytes()
    except OSError as exc:
        raise InputError(f"{source}: cannot read design file: {exc.strerror or exc}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{source}: design file is not UTF-8 text (bad byte at offset {exc.start})") from None
    return parse_design(text, source=source, base_dir=file.parent)


def parse_design(text: str, *, source: str = "<string>", base_dir: str | os.PathLike | None = None) -> Design:
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
    curvefold.kernel.errors.InputError: design.toml: [vault] fold_angle must be in (0, 180) degrees, got 180.0
    """
    if not isinstance(text, str):
        raise InputError(f"{source}: expected TOML text, got {type(text).__name__}")
    if len(text) > MAX_DESIGN_BYTES:
        raise InputError(f"{source}: design text is longer than {MAX_DESIGN_BYTES} characters")
    try:
        data = tomllib.loads(text)
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
        raise InputError(f"{source}: a design must be a table, got {_describe(data)}")
    folder = Path.cwd() if base_dir is None else Path(base_dir)
    top = SCHEMA[""]
    if "kind" not in data:
        raise InputError(f"{source}: missing required key 'kind' (one of {_choices(KINDS)})")
    kind = _check_choice(top["kind"], data["kind"], f"{source}: kind")
    used = SECTIONS_OF_KIND[kind]
    for key, value in data.items():
        if key in _SECTIONS:
            if not isinstance(value, Mapping):
                raise InputError(f"{source}: {key} must be a table ([{key}] section), got {_describe(value)}")
            if key != "output" and key not in used:
                users = " or ".join(repr(k) for k in KINDS if key in SECTIONS_OF_KIND[k])
                raise InputError(
                    f"{source}: section [{key}] is used by kind {users}, not by kind {kind!r}; "
                    "remove it or change kind"
                )
        elif key not in top:
            what = f"section [{key}]" if isinstance(value, Mapping) else f"key {key!r}"
            raise InputError(
                f"{source}: unknown {what} (allowed keys: {', '.join(top)}; sections: {', '.join(_SECTIONS)})"
                + _suggest(key, (*top, *_SECTIONS))
            )
    head = _check_section("", data, _Context(source, folder, 0), skip=_SECTIONS)
    ctx = _Context(source, folder, head["samples"])
    params = {s: _PARAM_TYPES[s](**_check_section(s, data.get(s, {}), ctx)) for s in (*used, "output")}
    design = Design(
        kind=kind, samples=head["samples"], title=head["title"], source=source, base_dir=folder.resolve(), **params
    )
    _check_budget(design)
    return design


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


@dataclass(frozen=True)
class _Context:
    source: str
    base_dir: Path
    samples: int


def _check_section(section: str, table: Mapping[str, Any], ctx: _Context, skip: tuple[str, ...] = ()) -> dict:
    """Validate one section against the schema; fill defaults. Function keys go last (they
    need the section's length)."""
    specs = SCHEMA[section]
    prefix = f"{ctx.source}: " if section == "" else f"{ctx.source}: [{section}] "
    for key in table:
        if key not in specs and key not in skip:
            raise InputError(f"{prefix}unknown key {key!r} (allowed: {', '.join(specs)})" + _suggest(key, specs))
    out: dict[str, Any] = {}
    order = sorted(specs, key=lambda k: specs[k].type == "function")
    for key in order:
        spec = specs[key]
        value = table.get(key)  # an explicit None (JSON null) means the default
        if value is None and spec.required:
            raise InputError(f"{prefix}missing required key {key!r}")
        if value is None:
            value = spec.default
        if value is None:
            out[key] = None
        elif spec.type == "function":
            out[key] = _check_function(spec, value, section, key, ctx, out["length"])
        else:
            out[key] = _CHECKERS[spec.type](spec, value, f"{prefix}{key}")
    return {key: out[key] for key in specs}


def _check_budget(design: Design) -> None:
    if design.kind == "vault" and design.vault.tubes != "max":
        lines, what = 4 * design.vault.tubes * design.vault.layers, "[vault] tubes or layers"
    elif design.kind == "block":
        lines, what = 4 * len(design.block.cells), "[block] cells"
    else:
        return
    if design.samples * lines > MAX_VERTICES:
        raise InputError(
            f"{design.source}: samples × crease lines = {design.samples} × {lines} = {design.samples * lines} "
            f"exceeds {MAX_VERTICES} (memory bound, about 1 GB); lower samples or {what}"
        )


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def _to_float(value: Any, where: str) -> float:
    try:
        return float(value)
    except OverflowError:
        raise InputError(f"{where} is too large, got an integer of {int(value).bit_length()} bits") from None


def _range_text(spec: KeySpec) -> str:
    """E.g. ``in (0, 180) degrees`` or ``in [3, 200000] (memory bound)``."""
    text = f"{spec.range} {spec.unit}" if spec.unit else str(spec.range)
    return f"{text} ({spec.note})" if spec.note else text


def _check_float(spec: KeySpec, value: Any, where: str) -> float:
    if not _is_number(value):
        unit = f" ({spec.unit})" if spec.unit else ""
        raise InputError(f"{where} must be a number{unit}, got {_describe(value)}")
    x = _to_float(value, where)
    if not math.isfinite(x):
        raise InputError(f"{where} must be a finite number, got {x}")
    if x not in spec.range:
        raise InputError(f"{where} must be {_range_text(spec)}, got {x!r}")
    return x


def _check_int(spec: KeySpec, value: Any, where: str) -> int:
    if not _is_number(value) or not isinstance(value, (int, np.integer)) or value not in spec.range:
        raise InputError(f"{where} must be an integer {_range_text(spec)}, got {_describe(value)}")
    return int(value)


def _check_tubes(spec: KeySpec, value: Any, where: str) -> int | str:
    if isinstance(value, str) and value == "max":
        return value
    if not _is_number(value) or not isinstance(value, (int, np.integer)) or value not in spec.range:
        raise InputError(f'{where} must be an integer {_range_text(spec)} or "max", got {_describe(value)}')
    return int(value)


def _check_choice(spec: KeySpec, value: Any, where: str) -> str:
    if not isinstance(value, str) or value not in spec.choices:
        raise InputError(f"{where} must be one of {_choices(spec.choices)}, got {_describe(value)}")
    return value


def _check_text(spec: KeySpec, value: Any, where: str) -> str:
    if not isinstance(value, str) or len(value) > 1000:
        raise InputError(f"{where} must be a string of at most 1000 characters, got {_describe(value)}")
    return value


def _check_bool(spec: KeySpec, value: Any, where: str) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{where} must be true or false, got {_describe(value)}")
    return bool(value)


def _check_page(spec: KeySpec, value: Any, where: str) -> str | tuple[float, float]:
    if isinstance(value, str) and value in spec.choices:
        return value
    if isinstance(value, (list, tuple)) and len(value) == 2:
        width, height = (_check_float(spec, v, f"{where} {name}") for v, name in zip(value, ("width", "height"), strict=True))
        return width, height
    names = _choices(spec.choices)
    raise InputError(f"{where} must be one of {names} or [width, height] in mm, got {_describe(value)}")


def _check_formats(spec: KeySpec, value: Any, where: str) -> tuple[str, ...]:
    if not isinstance(value, (list, tuple)):
        names = ", ".join(spec.choices)
        raise InputError(f"{where} must be an array of format names ({names}), got {_describe(value)}")
    for item in value:
        if not isinstance(item, str) or item not in spec.choices:
            raise InputError(f"{where}: unknown format {_describe(item)} (allowed: {', '.join(spec.choices)})")
    return tuple(dict.fromkeys(value))


def _check_cells(spec: KeySpec, value: Any, where: str) -> tuple[tuple[int, int], ...]:
    if not isinstance(value, (list, tuple)) or not 1 <= len(value) <= 10_000:
        raise InputError(f"{where} must be an array of 1 to 10000 [i, j] pairs, got {_describe(value)}")
    seen: dict[tuple[int, int], int] = {}
    for n, cell in enumerate(value):
        ok = isinstance(cell, (list, tuple)) and len(cell) == 2
        ok = ok and all(_is_number(x) and isinstance(x, (int, np.integer)) and x in spec.range for x in cell)
        if not ok:
            raise InputError(f"{where}[{n}] must be a pair [i, j] of integers {spec.range}, got {_describe(cell)}")
        pair = (int(cell[0]), int(cell[1]))
        if pair in seen:
            raise InputError(f"{where}[{n}] repeats cell {list(pair)} (first at index {seen[pair]})")
        seen[pair] = n
    return tuple(seen)


_CHECKERS: Mapping[str, Callable[[KeySpec, Any, str], Any]] = MappingProxyType({
    "float": _check_float,
    "int": _check_int,
    "tubes": _check_tubes,
    "choice": _check_choice,
    "text": _check_text,
    "bool": _check_bool,
    "page": _check_page,
    "formats": _check_formats,
    "cells": _check_cells,
})


def _check_function(spec: KeySpec, value: Any, section: str, key: str, ctx: _Context, length: float) -> FunctionValue:
    where = f"{ctx.source}: [{section}] {key}"
    if _is_number(value):
        return _check_float(spec, value, where)
    if isinstance(value, str):
        try:
            expression = compile_expression(value, name=f"[{section}] {key}")
        except InputError as exc:
            raise InputError(f"{ctx.source}: {exc}") from None
        grid = np.linspace(0.0, length, ctx.samples)
        _check_samples(spec, expression(grid), grid, where, lambda i: f"at s = {grid[i]:.6g}")
        return expression
    if isinstance(value, Mapping):
        return _read_table(spec, value, key, where, ctx, length)
    raise InputError(
        f"{where} must be a number, an expression in s or a table {{csv = ..., column = ...}}, got {_describe(value)}"
    )


def _check_samples(
    spec: KeySpec, values: np.ndarray, grid: np.ndarray, where: str, at: Callable[[int], str]
) -> None:
    """Raise naming the first sample that is not finite or not in the key's range."""
    with np.errstate(invalid="ignore"):
        inside = np.isfinite(values)
        r = spec.range
        inside &= (values >= r.lo) if r.lo_closed else (values > r.lo)
        inside &= (values <= r.hi) if r.hi_closed else (values < r.hi)
    bad = np.flatnonzero(~inside)
    if bad.size:
        i = int(bad[0])
        need = "finite" if str(r) == "finite" else f"finite and {_range_text(spec)}"
        raise InputError(f"{where} must be {need}; {at(i)} it is {values[i]:.6g}")


def _read_table(
    spec: KeySpec, table: Mapping[str, Any], key: str, where: str, ctx: _Context, length: float
) -> TableColumn:
    for k in table:
        if k not in ("csv", "column"):
            raise InputError(f"{where}: unknown key {k!r} in CSV table (allowed: csv, column)")
    raw, column = table.get("csv"), table.get("column", key)
    if not isinstance(raw, str) or not raw.strip():
        raise InputError(f"{where}: csv must be a file name relative to the design file, got {_describe(raw)}")
    if not isinstance(column, str):
        raise InputError(f"{where}: column must be a column header, got {_describe(column)}")
    file = _safe_path(raw, where, ctx.base_dir)
    label = f"{where} ({raw})"
    try:
        if file.stat().st_size > MAX_CSV_BYTES:
            raise InputError(f"{label}: CSV file is larger than {MAX_CSV_BYTES} bytes")
        text = file.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise InputError(f"{label}: cannot read CSV file: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        raise InputError(f"{label}: CSV file is not UTF-8 text (bad byte at offset {exc.start})") from None
    header, lines, columns = _parse_csv(text, label)
    if column not in header:
        raise InputError(f"{label}: no column {column!r} (columns: {', '.join(map(repr, header))})")
    values = columns[header.index(column)]
    if values.size < 2:
        raise InputError(f"{label}: column {column!r} needs at least 2 samples, got {values.size}")
    if values.size > MAX_SAMPLES:
        raise InputError(f"{label}: column {column!r} has more than {MAX_SAMPLES} samples")
    grid = np.linspace(0.0, length, values.size)
    if "s" in header:
        _check_grid(columns[header.index("s")], grid, lines, label, length)

    def at(i: int) -> str:
        return f"at line {lines[i]} (s = {grid[i]:.6g})"

    _check_samples(spec, values, grid, f"{label} column {column!r}", at)
    values.flags.writeable = False
    return TableColumn(raw, column, values)


def _safe_path(raw: str, where: str, base_dir: Path) -> Path:
    """Resolve a CSV path inside ``base_dir``; refuse absolute paths and escapes."""
    posix = PurePosixPath(raw.replace("\\", "/"))
    if posix.is_absolute() or PureWindowsPath(raw).anchor or ".." in posix.parts:
        raise InputError(
            f"{where}: csv path must be relative to the design file's folder and stay inside it, got {raw!r}"
        )
    base = base_dir.resolve()
    file = (base / posix).resolve()
    if not file.is_relative_to(base):
        raise InputError(f"{where}: csv path {raw!r} leads outside the design file's folder")
    if not file.is_file():
        raise InputError(f"{where}: csv file {raw!r} not found next to the design file")
    return file


def _parse_csv(text: str, label: str) -> tuple[list[str], list[int], list[np.ndarray]]:
    """Header, line number of every data row, and one float array per column.

    Blank lines and lines starting with ``#`` are skipped.
    """
    header: list[str] | None = None
    rows: list[list[float]] = []
    lines: list[int] = []
    reader = csv.reader(io.StringIO(text), strict=True)
    try:
        for row in reader:
            if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
                continue
            if header is None:
                header = [h.strip() for h in row]
                continue
            if len(row) != len(header):
                raise InputError(f"{label}: line {reader.line_num} has {len(row)} fields, the header has {len(header)}")
            try:
                rows.append([float(x) for x in row])
            except ValueError:
                bad = next(x for x in row if not _is_float(x))
                raise InputError(f"{label}: line {reader.line_num}: {bad.strip()!r} is not a number") from None
            lines.append(reader.line_num)
    except csv.Error as exc:
        raise InputError(f"{label}: malformed CSV at line {reader.line_num}: {exc}") from None
    if header is None:
        raise InputError(f"{label}: CSV file is empty (expected a header row and samples)")
    data = np.array(rows, dtype=float).reshape(len(rows), len(header))
    return header, lines, [np.ascontiguousarray(data[:, j]) for j in range(len(header))]


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _check_grid(s: np.ndarray, grid: np.ndarray, lines: list[int], label: str, length: float) -> None:
    """The ``s`` column must be the uniform grid over [0, length] (to print rounding)."""
    h = length / (grid.size - 1)
    tol = max(1e-3 * h, 1e-6 * length)
    with np.errstate(invalid="ignore"):
        off = np.flatnonzero(~(np.abs(s - grid) <= tol))
    if off.size and (off[0] == 0 or off[-1] == grid.size - 1):
        raise InputError(
            f"{label}: the s column must run from 0 to length {length:g}, got {s[0]:.6g} to {s[-1]:.6g}"
        )
    if off.size:
        i = int(off[0])
        raise InputError(
            f"{label}: the s column must be uniformly spaced over [0, {length:g}]: at line {lines[i]} "
            f"s = {s[i]:.6g}, expected {grid[i]:.6g} ({grid.size} samples, spacing {h:.6g})"
        )


# --------------------------------------------------------------------------------------------
# Messages


def _fmt(x: float) -> str:
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return str(int(x)) if x == int(x) else repr(x)


def _choices(choices: tuple[str, ...]) -> str:
    return ", ".join(f'"{c}"' for c in choices)


_TOML_TYPES = ((bool, "boolean"), (str, "string"), (int, "integer"), (float, "float"), (Mapping, "table"))


def _describe(value: Any) -> str:
    """TOML type name and a short repr, e.g. ``string '90'``."""
    try:
        text = repr(value)
    except ValueError:  # an integer past Python's digit limit
        text = "<too many digits>"
    if len(text) > 60:
        text = text[:57] + "..."
    if _is_number(value) and not isinstance(value, bool):
        return text
    for kind, name in _TOML_TYPES:
        if isinstance(value, kind):
            return f"{name} {text}"
    if isinstance(value, (list, tuple)):
        return f"array {text}"
    return f"{type(value).__name__} {text}"


def _suggest(key: Any, options) -> str:
    if not isinstance(key, str):
        return ""
    close = difflib.get_close_matches(key, list(options), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""
