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

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from types import MappingProxyType
from typing import Any, Literal

import numpy as np

from ..geometry._panel_pattern import PANELS
from ..io._formats import OUTPUT_SPECS, check_scale, default_formats
from ..io._reading import read_bytes
from ..kernel._errors import InputError
from ..kernel._expr import Expression
from ..kernel._functions import ScalarFunction, as_function
from ..kernel._validate import REQUIRED, Spec, describe, suggest
from ..mechanics import LoadCase
from ..vault._assembly import LENGTHS, LENGTHS_WHY, VAULT_SPECS
from ._design_functions import Context, FunctionValue, TableColumn, check_function
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

KINDS = ("vault", "tube", "block", "crease")
#: Sections each kind reads besides ``[output]``.
SECTIONS_OF_KIND: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"vault": ("vault",), "tube": ("curve", "tube"), "block": ("curve", "block"), "crease": ("crease",)}
)
#: Sections a kind reads only when a design has them: what it is made of and what loads it.
OPTIONAL_SECTIONS: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"vault": ("material", "loads"), "tube": ("material", "loads"), "block": ("material", "loads"), "crease": ()}
)

#: Largest design file read, in bytes.
MAX_DESIGN_BYTES = 1 << 20


# --------------------------------------------------------------------------------------------
# The schema: the specs of every section, composed from their owners


_ANGLE = "(0, 180)"


def _fold_angle(default: float, help: str) -> Spec:
    return Spec("fold_angle", "real", default, _ANGLE, "degrees", help=help, label="fold angle")


def _width(side: str, default: float) -> Spec:
    return Spec(f"width_{side}", "real", default, "(0, inf)", "model units", help=f"width w_{side[0].upper()}(0) on the {side}, at s = 0",
                label=f"width on the {side}")


def _section(*specs: Spec) -> Mapping[str, Spec]:
    return MappingProxyType({spec.name: spec for spec in specs})


#: Every section ("" is the top level) and the specs of its keys, in file order. The
#: ``[vault]`` specs are :data:`curvefold.vault._assembly.VAULT_SPECS`, the ``[output]``
#: specs :data:`curvefold.io._formats.OUTPUT_SPECS`.
SCHEMA: Mapping[str, Mapping[str, Spec]] = MappingProxyType({
    "": _section(
        Spec("kind", "choice", REQUIRED, choices=KINDS, help="what to build", label="structure"),
        Spec("samples", "integer", 801, "[9, 200000]", help="samples along curve 1",
             why="the certificate's differences need 9; memory is budgeted besides", label="samples along each crease"),
        Spec("title", "text", "", help="free text for reports", label="title"),
    ),
    "vault": _section(*VAULT_SPECS),
    "curve": _section(
        Spec("kappa", "function", 1.0, "(0, inf)", "per model unit", help="curvature of curve 1 as a function of s", label="curvature"),
        Spec("tau", "function", 0.2, "(-inf, inf)", "per model unit", help="torsion of curve 1 as a function of s", label="torsion"),
        Spec("length", "real", 6.0, LENGTHS, "model units", help="arc length of curve 1", why=LENGTHS_WHY, label="length of curve 1"),
        _fold_angle(90.0, "fold angle 2 alpha at which kappa and tau are given"),
        PANELS,
    ),
    "tube": _section(_width("left", 0.3), _width("right", 0.3)),
    "block": _section(
        _width("left", 0.2),
        _width("right", 0.2),
        Spec("cells", "cells", ((0, 0), (0, 1), (1, 1)), "[-1000, 1000]", help="lattice cells [i, j]", label="cells"),
    ),
    "crease": _section(
        Spec("kappa_2d", "function", 0.5, "(0, inf)", "per model unit", help="curvature of the crease in the flat pattern", label="curvature in the flat pattern"),
        Spec("beta_left", "function", 90.0, _ANGLE, "degrees", help="ruling angle on the left", label="ruling angle on the left"),
        Spec("beta_right", "function", 90.0, _ANGLE, "degrees", help="ruling angle on the right (not with alpha)", label="ruling angle on the right"),
        _fold_angle(60.0, "fold angle 2 alpha(0) at the start of the crease"),
        Spec("length", "real", 3.0, LENGTHS, "model units", help="arc length of the crease", why=LENGTHS_WHY, label="crease length"),
        Spec("alpha", "function", None, "(0, 90)", "degrees",
             help="alpha(s), half the fold angle along the crease; beta_right then follows from Eq. (3)", label="half fold angle"),
        *(Spec(f"width_{side}", "real", None, "(0, inf)", "model units",
               help=f"width of the {side} strip from the crease's tangent lines, in the files (default: 15% of the length, "
                    "within 60% of the regression limit)", label=f"{side} strip width") for side in ("left", "right")),
    ),
    "output": _section(*OUTPUT_SPECS),
    "material": _section(*MATERIAL_SECTION),
    "loads": _section(*LOADS_SECTION),
})

_SECTIONS = tuple(name for name in SCHEMA if name)
#: Keys of a section that hold a list of tables, checked apart: ``[[loads.case]]``
#: (:func:`check_cases`).
_LISTED: Mapping[str, tuple[str, ...]] = MappingProxyType({"loads": ("case",)})


# --------------------------------------------------------------------------------------------
# Validated values




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
    panels: int = 0


@dataclass(frozen=True)
class CurveParams:
    """``[curve]``: curve 1 of a tube or block, with κ and τ given at ``fold_angle``, and the
    number of rigid planar panels along it (0: the smooth structure)."""

    kappa: FunctionValue
    tau: FunctionValue
    length: float
    fold_angle: float
    panels: int = 0


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
    """``[crease]``: a single curved fold from its crease pattern (angles in degrees).

    Either ``beta_right`` is given and α(s) follows from Eq. (3) integrated from
    ``fold_angle``, or ``alpha`` is given (``beta_right`` is then None and
    ``fold_angle`` = 2α(0)) and β_R follows from Eq. (3). The strips' widths are those of
    its files (None: as :func:`curvefold.geometry._single_fold.default_widths` chooses).
    """

    kappa_2d: FunctionValue
    beta_left: FunctionValue
    beta_right: FunctionValue | None
    fold_angle: float
    length: float
    alpha: FunctionValue | None
    width_left: float | None = None
    width_right: float | None = None


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


_PARAM_TYPES: Mapping[str, type] = MappingProxyType({
    "vault": VaultParams,
    "curve": CurveParams,
    "tube": TubeParams,
    "block": BlockParams,
    "crease": CreaseParams,
    "output": OutputParams,
    "material": MaterialParams,
    "loads": LoadParams,
})


@dataclass(frozen=True)
class Design:
    """A validated design: what to build, with every default filled in.

    Build it with :func:`load_design`, :func:`parse_design`, :func:`design_from_dict` or
    :func:`default_design`; derive variants with :meth:`overrides`. Only the sections of
    ``kind`` (see :data:`SECTIONS_OF_KIND`) and ``output`` are set, and its optional ones
    (:data:`OPTIONAL_SECTIONS`) when given; the others are None.

    Parameters
    ----------
    kind : {"vault", "tube", "block", "crease"}
    samples : int
        Samples along curve 1.
    title : str
    output : OutputParams
    vault, curve, tube, block, crease, material, loads : section parameters or None
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
    material: MaterialParams | None = None
    loads: LoadParams | None = None
    source: str = field(default="<defaults>", compare=False)
    base_dir: Path | None = field(default=None, compare=False, repr=False)

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
            data = {"kind": kind, "samples": data["samples"], "title": data["title"], "output": data["output"]}
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
                    f"{source}: unknown option {flag!r} for kind {kind!r} (allowed: {', '.join(allowed)})"
                    + suggest(key, allowed)
                )
        return design_from_dict(data, source=source, base_dir=self.base_dir)

    @property
    def mechanics(self) -> bool:
        """Whether the design says what it is made of or what loads it: its output folders then hold its mechanics."""
        return self.material is not None or self.loads is not None

    def with_mechanics(self) -> Design:
        """This design with its ``[material]`` and ``[loads]`` as given or at their defaults (``curvefold load``).

        Raises
        ------
        InputError
            For a single curved fold, which has no end sections to hold.
        """
        if not OPTIONAL_SECTIONS[self.kind]:
            raise InputError(f"{self.source}: a single curved fold has no end sections to hold: load a tube, block or vault")
        return self.overrides(source=self.source, material={}, loads={})

    def tables(self) -> tuple[Path, ...]:
        """The CSV files the design reads, each once."""
        sections = [getattr(self, section) for section in SECTIONS_OF_KIND[self.kind]]
        values = [getattr(params, f.name) for params in sections for f in fields(params)]
        return tuple(dict.fromkeys(self.base_dir / v.path for v in values if isinstance(v, TableColumn)))

    def function(self, key: str) -> ScalarFunction:
        """A function-valued key (e.g. ``"kappa"``) as a :class:`ScalarFunction` of arc length.

        Values are in the design file's units: angles stay in degrees.
        """
        section = next((s for s in SECTIONS_OF_KIND[self.kind] if key in SCHEMA[s] and SCHEMA[s][key].kind == "function"), None)
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


def _alternatives(data: dict, flags: Mapping[str, Any]) -> None:
    """A [crease]'s ``alpha`` and ``beta_right`` are alternatives, and a named material and one's own values: the one the
    flags set drops the other from the design's data (with ``alpha``, its ``fold_angle`` too, which then follows from
    it), unless the flags set both."""
    given = {k.replace("-", "_") for k, v in flags.items() if v is not None and not isinstance(v, Mapping)}
    given |= {key for value in flags.values() if isinstance(value, Mapping) for key in value}  # a section's keys
    material_alternatives(data, given)
    crease = data.get("crease")
    if crease is None:
        return
    if "alpha" in given:
        for key in ("beta_right", "fold_angle"):
            if key not in given:
                crease.pop(key, None)
    elif "beta_right" in given:
        crease.pop("alpha", None)


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
    curvefold.kernel._errors.InputError: design.toml: [vault] fold_angle must be in (0, 180) degrees, got 180.0
    """
    if not isinstance(text, str):
        raise InputError(f"{source}: expected TOML text, got {type(text).__name__}")
    if len(text) > MAX_DESIGN_BYTES:
        raise InputError(f"{source}: design text is longer than {MAX_DESIGN_BYTES} characters")
    import tomllib  # here: its regular expressions are compiled on import

    try:
        data = tomllib.loads(text.removeprefix("\ufeff"))  # a byte-order mark, which some editors write, is not TOML
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
    if "kind" not in data:
        kinds = ", ".join(f'"{k}"' for k in KINDS)
        raise InputError(f"{source}: missing required key 'kind' (one of {kinds})")
    kind = top["kind"].check(data["kind"], f"{source}: kind")
    used = (*SECTIONS_OF_KIND[kind], *(s for s in OPTIONAL_SECTIONS[kind] if s in data))
    for key, value in data.items():
        if key in _SECTIONS:
            if not isinstance(value, Mapping):
                raise InputError(f"{source}: {key} must be a table ([{key}] section), got {describe(value)}")
            if key != "output" and key not in used:
                users = " or ".join(repr(k) for k in KINDS if key in (*SECTIONS_OF_KIND[k], *OPTIONAL_SECTIONS[k]))
                raise InputError(
                    f"{source}: section [{key}] is used by kind {users}, not by kind {kind!r}; "
                    "remove it or change kind"
                )
        elif key not in top:
            what = f"section [{key}]" if isinstance(value, Mapping) else f"key {key!r}"
            raise InputError(
                f"{source}: unknown {what} (allowed keys: {', '.join(top)}; sections: {', '.join(_SECTIONS)})"
                + suggest(key, (*top, *_SECTIONS))
            )
    head = _check_section("", data, Context(source, folder, 0), skip=_SECTIONS)
    ctx = Context(source, folder, head["samples"])
    checked = {s: _check_section(s, data.get(s, {}), ctx, skip=_LISTED.get(s, ()))
               for s in (*used, "output")}
    if checked["output"]["formats"] is None:
        checked["output"]["formats"] = default_formats(kind)
    if kind == "crease":
        _check_alpha(checked["crease"], data.get("crease", {}), source)
    if "material" in checked:
        check_material(checked["material"], f"{source}: [material] ")
    if "loads" in checked:
        listed = data["loads"].get("case")
        checked["loads"]["case"] = check_cases(listed, f"{source}: [[loads.case]] ")
    out = checked["output"]
    check_scale(out["scale"], out["units"], _crease_length(kind, checked), f"{source}: [output] scale")
    params = {s: _PARAM_TYPES[s](**values) for s, values in checked.items()}
    return Design(
        kind=kind, samples=head["samples"], title=head["title"], source=source, base_dir=folder.resolve(), **params
    )


def _crease_length(kind: str, checked: dict) -> float:
    """The length of a design's crease 1 in model units (a vault's at least π × radius: its κ0·s0 is above π)."""
    if kind == "vault":
        return math.pi * checked["vault"]["radius"]
    return checked["crease" if kind == "crease" else "curve"]["length"]


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



def _check_section(section: str, table: Mapping[str, Any], ctx: Context, skip: tuple[str, ...] = ()) -> dict:
    """Validate one section against the schema; fill defaults. Function keys go last (they
    need the section's length)."""
    specs = SCHEMA[section]
    prefix = f"{ctx.source}: " if section == "" else f"{ctx.source}: [{section}] "
    for key in table:
        if key not in specs and key not in skip:
            raise InputError(f"{prefix}unknown key {key!r} (allowed: {', '.join(specs)})" + suggest(key, specs))
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


def _check_alpha(values: dict, table: Mapping[str, Any], source: str) -> None:
    """With ``alpha`` given, β_R follows from Eq. (3): refuse ``beta_right`` and set ``fold_angle`` to 2α(0)."""
    alpha = values["alpha"]
    if alpha is None:
        return
    if table.get("beta_right") is not None:
        raise InputError(f"{source}: [crease] give beta_right or alpha, not both (with alpha, beta_right follows from Eq. (3))",
                         parameter="beta_right")
    twice = float(2 * np.asarray(alpha(np.zeros(1)) if callable(alpha) else alpha, float).flat[0])
    if table.get("fold_angle") is not None and not math.isclose(values["fold_angle"], twice, rel_tol=1e-12):
        raise InputError(
            f"{source}: [crease] fold_angle must equal 2 alpha(0) = {twice:.12g} degrees or be left out, got {values['fold_angle']!r}",
            parameter="fold_angle",
        )
    values["beta_right"], values["fold_angle"] = None, twice
