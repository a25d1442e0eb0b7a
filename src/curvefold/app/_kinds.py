"""Kinds of design: one object per kind, registered in one place.

A kind of design (``vault``, ``tube``, ``block``, ``crease``) is a :class:`DesignKind`: the
sections of a design file it reads (their specs and the frozen values they become), how a
design of it is built, what it costs (the strips the memory budget counts), where its
output folder goes, which file formats it writes and how the command line describes it.
:func:`register_kind` adds one, as :mod:`curvefold.io._formats` registers file formats; the
design schema (:mod:`curvefold.app._design`), the command line (:mod:`curvefold.app.cli`),
the budget (:mod:`curvefold.app._budget`) and the designer's API read the registry, so a new
kind touches no other file::

    register_kind(
        DesignKind(
            "ring",
            (RING,),
            build_ring,
            strips=lambda design: 4,
            crease_length=lambda values: values["ring"]["length"],
            help="a tube on a circle",
            description="Build a tube on a circle.",
        )
    )

What only some kinds have is theirs: a vault's targets (:class:`Targets`), which replace
some of its parameters, and the arch root a build at other samples shares
(:meth:`DesignKind.build`'s second argument).

This module holds the registry and the built-in kinds' sections; the built-in kinds are
registered by :mod:`curvefold.app._standard_kinds`, which the package imports first. A
built-in kind names its builder (``"module:function"``, as the formats name their writers),
imported when first called, so the command line starts without the geometry, and the
builders' module (which imports this one) sits above the registry, not in a cycle with it.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Literal

from ..geometry._panel_pattern import PANELS
from ..kernel._errors import InputError
from ..kernel._validate import Spec
from ..vault._assembly import LENGTHS, LENGTHS_WHY, VAULT_SPECS
from ._design_functions import FunctionValue

#: A :class:`curvefold.app._design.Design` and a :class:`curvefold.app._build.Built`, named in
#: words: both modules import this one, which sits below them.
Design = Any
Built = Any

__all__ = [
    "Section",
    "Targets",
    "DesignKind",
    "register_kind",
    "deregister_kind",
    "design_kind",
    "design_kinds",
    "registry_version",
    "VaultParams",
    "CurveParams",
    "TubeParams",
    "BlockParams",
    "CreaseParams",
    "LOAD_SECTIONS",
    "SHARED_SECTIONS",
]

#: The optional sections of a kind that can stand under load: what it is made of and what loads it.
LOAD_SECTIONS = ("material", "loads")
#: Sections every kind shares (the top level, ``[output]`` and :data:`LOAD_SECTIONS`), which no
#: kind's own section may be named.
SHARED_SECTIONS = ("", "output", *LOAD_SECTIONS)


@dataclass(frozen=True)
class Section:
    """One section of a design file: its name, the spec of every key in file order, and the
    frozen dataclass its checked values become (its fields are the keys)."""

    name: str
    specs: Mapping[str, Spec]
    params: type

    @classmethod
    def of(cls, name: str, params: type, *specs: Spec) -> Section:
        """A section from its specs, in file order."""
        return cls(name, MappingProxyType({spec.name: spec for spec in specs}), params)


@dataclass(frozen=True)
class Targets:
    """What a design of a kind may be asked to measure instead of giving some of its parameters
    (a vault's span, rise and p_xz).

    Attributes
    ----------
    load : callable
        ``load() -> (specs, replaces)``: the targets' specs and the parameter each replaces,
        imported when asked.
    fit_with : callable or str
        ``fit(design, source=..., **targets) -> (design, note)``: the design with the replaced
        parameters solved for the targets, and what the fit chose for the user (or ""); or its
        qualified name ``"module:function"``, imported when first called.
    help : str
        What they are, for the command line's help.
    """

    load: Callable[[], tuple[tuple[Spec, ...], Mapping[str, str]]]
    fit_with: str | Callable[..., tuple[Design, str]]
    help: str = ""

    def fit(
        self, design: Design, *, source: str | None = None, **targets: float
    ) -> tuple[Design, str]:
        """The design with the parameters the targets replace solved for them, and a note
        (or "")."""
        return _load(self.fit_with)(design, source=source, **targets)

    def specs(self) -> tuple[Spec, ...]:
        return self.load()[0]

    def replaces(self) -> Mapping[str, str]:
        """Target name -> the parameter it replaces."""
        return self.load()[1]


def _no_panels(design: Design) -> int:
    return 0


def _load(function: str | Callable) -> Callable:
    """A function, or the function a qualified name ``"module:function"`` names (imported now)."""
    if callable(function):
        return function
    import importlib

    module, _, name = function.partition(":")
    return getattr(importlib.import_module(module), name)


@dataclass(frozen=True)
class DesignKind:
    """A kind of design: its sections, how it builds, what it costs, how it is described.

    Attributes
    ----------
    name : str
        What a design file's ``kind`` and the command line's subcommand say.
    sections : tuple of Section
        The sections it reads besides ``[output]``, in file order.
    builder : callable or str
        ``builder(design, like) -> Built`` (:meth:`build`), or its qualified name
        ``"module:function"``, imported when first called.
    strips : callable
        ``strips(design) -> int``: strips of the structure it builds, which the memory budget
        counts (four per cell; a single crease has two surfaces).
    crease_length : callable
        ``crease_length(values) -> float``: the length of crease 1 in model units from the
        checked values of its sections (by section name), which the output's scale is checked with.
    help, description : str
        The command line's one-line help and its subcommand's description.
    optional : tuple of str
        Sections read only when a design has them (:data:`LOAD_SECTIONS`: it can stand under load).
    panels : callable
        ``panels(design) -> int``: rigid panels along each crease (0: smooth); the budget counts
        their vertices.
    check : callable or None
        ``check(values, given, source)``: checks across the keys of its checked sections
        (``values``, by section; completed in place), ``given`` the design's raw data.
    alternatives : callable or None
        ``alternatives(data, given)``: drops from a design's data (by section) the keys that the
        keys ``given`` (by flags, to override) replace.
    lower : str
        What besides samples lowers its memory (``"[block] cells"``), or "".
    structure : bool
        Whether it builds a structure of strips (a lattice, sheets, a regression domain); a
        single curved fold does not.
    grounded : bool
        Whether it stands on its feet on the ground (a vault): held there under load, and its
        fold stops at its first contact.
    targets : Targets or None
        What it may be designed from besides its parameters.
    formats_as : str
        The kind whose file formats it writes (``curvefold.io.FileFormat.kinds``); default
        its own name.
    """

    name: str
    sections: tuple[Section, ...]
    builder: str | Callable[[Design, Built | None], Built]
    strips: Callable[[Design], int]
    crease_length: Callable[[Mapping[str, Mapping[str, Any]]], float]
    help: str
    description: str
    optional: tuple[str, ...] = ()
    panels: Callable[[Design], int] = _no_panels
    check: Callable[[dict, Mapping[str, Any], str], None] | None = None
    alternatives: Callable[[dict, set[str]], None] | None = None
    lower: str = ""
    structure: bool = True
    grounded: bool = False
    targets: Targets | None = None
    formats_as: str = ""

    def build(self, design: Design, like: Built | None = None) -> Built:
        """Build a design of this kind; ``like`` is None or the same design built at other samples,
        whose solved parts (a vault's arch root) the build may reuse."""
        return _load(self.builder)(design, like)

    @property
    def default_out(self) -> str:
        """The output folder written unless told: ``curvefold-<name>``."""
        return f"curvefold-{self.name}"

    @property
    def formats_kind(self) -> str:
        """The kind of design its file formats are written for."""
        return self.formats_as or self.name

    @property
    def section_names(self) -> tuple[str, ...]:
        return tuple(section.name for section in self.sections)

    @property
    def loaded(self) -> bool:
        """Whether it can stand under load (``curvefold load``, ``[material]`` and ``[loads]``)."""
        return bool(self.optional)


_KINDS: dict[str, DesignKind] = {}
_version = [0]


def register_kind(kind: DesignKind) -> DesignKind:
    """Add a kind of design to the registry (after those there); returns it.

    Raises
    ------
    InputError
        A kind of that name is registered, one of its sections is named as a shared one
        (:data:`SHARED_SECTIONS`) or as another kind's with other specs, or an optional
        section is none of :data:`LOAD_SECTIONS`.
    """
    if kind.name in _KINDS:
        raise InputError(f"kind {kind.name!r} is registered already")
    shared = [s.name for s in kind.sections if s.name in SHARED_SECTIONS]
    if shared:
        raise InputError(
            f"kind {kind.name!r}: section [{shared[0]}] is every kind's; "
            "name its own sections otherwise"
        )
    unknown = [name for name in kind.optional if name not in LOAD_SECTIONS]
    if unknown:
        raise InputError(
            f"kind {kind.name!r}: optional section [{unknown[0]}] "
            f"must be one of {', '.join(LOAD_SECTIONS)}"
        )
    for section in kind.sections:
        for other in _KINDS.values():
            theirs = {s.name: s for s in other.sections}.get(section.name)
            if theirs is not None and theirs != section:
                raise InputError(
                    f"section [{section.name}] of kind {kind.name!r} "
                    f"differs from kind {other.name!r}'s"
                )
    _KINDS[kind.name] = kind
    _version[0] += 1
    return kind


def deregister_kind(name: str) -> None:
    """Remove a kind of design from the registry (one a test registered)."""
    design_kind(name)
    del _KINDS[name]
    _version[0] += 1


def registry_version() -> int:
    """A number that changes whenever a kind is registered or removed (what caches of the
    registry are keyed by)."""
    return _version[0]


def design_kinds() -> tuple[DesignKind, ...]:
    """Every registered kind, in registration order."""
    return tuple(_KINDS.values())


def design_kind(name: object, where: str = "") -> DesignKind:
    """The registered kind of this name.

    Raises
    ------
    InputError
        An unknown kind, in one line: ``unknown kind 'dome' (allowed: vault, tube, block, crease)``.

    Examples
    --------
    >>> vault = design_kind("vault")
    >>> vault.default_out, vault.section_names, vault.grounded, design_kind("crease").structure
    ('curvefold-vault', ('vault',), True, False)
    """
    found = _KINDS.get(name) if isinstance(name, str) else None
    if found is None:
        raise InputError(f"{where}unknown kind {name!r} (allowed: {', '.join(_KINDS)})")
    return found


# --------------------------------------------------------------------------------------------
# The built-in kinds: their sections


_ANGLE = "(0, 180)"


def _fold_angle(default: float, help: str) -> Spec:
    return Spec("fold_angle", "real", default, _ANGLE, "degrees", help=help, label="fold angle")


def _width(side: str, default: float) -> Spec:
    return Spec(
        f"width_{side}",
        "real",
        default,
        "(0, inf)",
        "model units",
        help=f"width w_{side[0].upper()}(0) on the {side}, at s = 0",
        label=f"width on the {side}",
    )


@dataclass(frozen=True)
class VaultParams:
    """``[vault]``: a composite deployable vault (see :data:`~curvefold.app._design.SCHEMA`
    for ranges and units)."""

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


VAULT = Section.of("vault", VaultParams, *VAULT_SPECS)
CURVE = Section.of(
    "curve",
    CurveParams,
    Spec(
        "kappa",
        "function",
        1.0,
        "(0, inf)",
        "per model unit",
        help="curvature of curve 1 as a function of s",
        label="curvature",
    ),
    Spec(
        "tau",
        "function",
        0.2,
        "(-inf, inf)",
        "per model unit",
        help="torsion of curve 1 as a function of s",
        label="torsion",
    ),
    Spec(
        "length",
        "real",
        6.0,
        LENGTHS,
        "model units",
        help="arc length of curve 1",
        why=LENGTHS_WHY,
        label="length of curve 1",
    ),
    _fold_angle(90.0, "fold angle 2 alpha at which kappa and tau are given"),
    PANELS,
)
TUBE = Section.of("tube", TubeParams, _width("left", 0.3), _width("right", 0.3))
BLOCK = Section.of(
    "block",
    BlockParams,
    _width("left", 0.2),
    _width("right", 0.2),
    Spec(
        "cells",
        "cells",
        ((0, 0), (0, 1), (1, 1)),
        "[-1000, 1000]",
        help="lattice cells [i, j]",
        label="cells",
    ),
)
CREASE = Section.of(
    "crease",
    CreaseParams,
    Spec(
        "kappa_2d",
        "function",
        0.5,
        "(0, inf)",
        "per model unit",
        help="curvature of the crease in the flat pattern",
        label="curvature in the flat pattern",
    ),
    Spec(
        "beta_left",
        "function",
        90.0,
        _ANGLE,
        "degrees",
        help="ruling angle on the left",
        label="ruling angle on the left",
    ),
    Spec(
        "beta_right",
        "function",
        90.0,
        _ANGLE,
        "degrees",
        help="ruling angle on the right (not with alpha)",
        label="ruling angle on the right",
    ),
    _fold_angle(60.0, "fold angle 2 alpha(0) at the start of the crease"),
    Spec(
        "length",
        "real",
        3.0,
        LENGTHS,
        "model units",
        help="arc length of the crease",
        why=LENGTHS_WHY,
        label="crease length",
    ),
    Spec(
        "alpha",
        "function",
        None,
        "(0, 90)",
        "degrees",
        help="alpha(s), half the fold angle along the crease; beta_right then follows from Eq. (3)",
        label="half fold angle",
    ),
    *(
        Spec(
            f"width_{side}",
            "real",
            None,
            "(0, inf)",
            "model units",
            help=f"width of the {side} strip from the crease's tangent lines, in the files "
            "(default: 15% of the length, within 60% of the regression limit)",
            label=f"{side} strip width",
        )
        for side in ("left", "right")
    ),
)
