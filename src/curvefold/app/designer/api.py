"""What the designer's server answers, without the web framework: requests read into designs,
their certificates, figures and files.

A request names a kind (``vault``, ``tube``, ``block``, ``crease``) and gives any key of
the design schema as a query parameter (``?a=0.4&tubes=max&fold_angle=60``); a vault also
takes the targets ``span``, ``rise`` and ``p_xz`` (:mod:`curvefold.vault._targets`), which
replace ``radius``, ``a`` and ``p_xy``. A value is read as its key's kind of value needs
(a number, a word, an expression in s, ``cells`` as JSON ``[[0, 0], [0, 1]]``,
``formats`` comma-separated) and checked by the key's :class:`~curvefold.kernel.Spec`,
so the command line, design files and the server refuse the same values with the same
words. A refusal is an :class:`~curvefold.kernel.InputError` whose
:attr:`~curvefold.kernel.CurvefoldError.parameter` names the parameter it is about, if any.

:func:`read_request` only reads and checks (quick, in the server); everything that builds
runs in worker processes (:mod:`curvefold.app.designer.jobs`). No design is kept per
user: everything is a pure function of the request, cached by the design's content in
small LRU caches of the worker (so two users never see each other's design).
"""

from __future__ import annotations

import io
import json
import re
import tempfile
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ...analysis._checks import TITLES
from ...figures._report import MECHANICS_QUANTITIES, UNITS_SHOWN
from ...io._formats import (
    FORMATS,
    check_kind,
    default_formats,
    formats_left_out,
    missing_dependencies,
)
from ...kernel._errors import CurvefoldError, InputError
from ...kernel._json_text import strict_json
from ...kernel._validate import MAX_TEXT, Spec, from_text, suggest
from .._build import Built, BuiltStructure, BuiltVault, build
from .._design import SCHEMA, Design, default_design, design_from_dict, kind_specs
from .._kinds import DesignKind, design_kind, design_kinds, registry_version
from .curves import collapse_curve

__all__ = [
    "Request",
    "PREVIEW_SAMPLES",
    "COARSE_SAMPLES",
    "STATE",
    "parameters",
    "schema",
    "read_request",
    "resolve",
    "request_design",
    "design_query",
    "built",
    "payload",
    "certificate",
    "mechanics",
    "domain_svg",
    "pattern_pages",
    "download",
    "design_toml",
    "caches",
]

#: Samples along curve 1 of the regression domain's picture (odd, so a vault's apex is a sample; the
#: 3D preview has its own, :data:`curvefold.app.designer.preview.MOTION_SAMPLES`).
PREVIEW_SAMPLES = 97
#: Samples of the coarse certificate and crease pattern that answer first after a change.
COARSE_SAMPLES = 49
#: Longest query value read, in characters.
MAX_VALUE = 2 * MAX_TEXT
#: How a request is named in the messages of the design checks (and taken off them again).
SOURCE = "query"
#: Keys a request never sets (the kind is in the path).
_FIXED = ("kind",)
#: The fold angle of the state a downloaded file holds (a query parameter of the files only).
STATE = Spec(
    "state",
    "real",
    None,
    "[0, 180)",
    "degrees",
    help="fold angle 2 alpha of the state the files hold; default the design angle",
    label="fold angle of the files",
)


# -- parameters -----------------------------------------------------------------------------------


def parameters(kind: str) -> dict[str, Spec]:
    """Every query parameter of a kind: the schema keys of its sections and ``[output]``, and
    its targets (:attr:`DesignKind.targets <curvefold.app._kinds.DesignKind.targets>`: a
    vault's)."""
    specs = kind_specs(design_kind(kind).name)
    return specs | {spec.name: spec for spec in _target_specs(kind)}


def _target_specs(kind: str) -> tuple[Spec, ...]:
    targets = design_kind(kind).targets
    return () if targets is None else targets.specs()


def _replaces(kind: str) -> dict[str, str]:
    """Target -> the parameter it replaces, for a kind's targets."""
    targets = design_kind(kind).targets
    return {} if targets is None else dict(targets.replaces())


#: The designer's words for a control where the command line's label is too terse.
_LABELS = {"nonlinear": "follow to collapse (large displacements)"}


def _spec_json(spec: Spec, section: str) -> dict:
    return {
        "name": spec.name,
        "label": _LABELS.get(spec.name, spec.label),
        "section": section,
        "kind": spec.kind,
        "unit": spec.unit,
        "help": spec.help,
        "describe": spec.describe(),
        "choices": list(spec.choices),
        "required": spec.required,
        "default": None if spec.required else _plain(spec.default),
        "range": _interval_json(spec.range),
        "typical": _interval_json(spec.typical),
    }


def _interval_json(r) -> dict | None:
    return (
        None
        if r is None
        else {
            "lo": _finite(r.lo),
            "hi": _finite(r.hi),
            "lo_closed": r.lo_closed,
            "hi_closed": r.hi_closed,
        }
    )


def _finite(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def _plain(value):
    return [_plain(v) for v in value] if isinstance(value, tuple) else value


def schema() -> dict:
    """The design schema as JSON-ready data: the designer's controls are generated from it.

    Keys: ``kinds`` (kind → its sections, its optional ones last: ``material`` and ``loads``),
    ``optional`` (kind → its optional sections), ``grounded`` (the kinds that stand on the
    ground: a vault, whose fold stops at its first contact), ``sections`` (section → list of
    specs with name, label, kind, unit, help, choices, default and range; ``""`` is the top
    level), ``targets`` (the kinds' target specs, a vault's, each with its ``design_kind`` and
    the parameter it replaces; its ``kind`` is its value's, as every spec's), ``formats`` (the
    registry: name, extension, what the file holds, the kinds it is written for), ``state`` (the
    spec of the files' fold angle) and ``units`` (how the page names the schema's units,
    :data:`curvefold.figures._report.UNITS_SHOWN`). Read from the registry of
    kinds (:mod:`curvefold.app._kinds`), once for each state of it.
    """
    return _schema(registry_version())


def _kind_targets(kind: DesignKind) -> list[dict]:
    if kind.targets is None:
        return []
    replaces = kind.targets.replaces()
    return [
        _spec_json(spec, kind.name) | {"design_kind": kind.name, "replaces": replaces[spec.name]}
        for spec in kind.targets.specs()
    ]


@lru_cache(maxsize=1)
def _schema(version: int) -> dict:
    kinds = design_kinds()
    return {
        "kinds": {kind.name: [*kind.section_names, *kind.optional] for kind in kinds},
        "optional": {kind.name: list(kind.optional) for kind in kinds},
        "grounded": [kind.name for kind in kinds if kind.grounded],
        "sections": {
            section: [
                _spec_json(spec, section) for spec in specs.values() if spec.name not in _FIXED
            ]
            for section, specs in SCHEMA.items()
        },
        "targets": [target for kind in kinds for target in _kind_targets(kind)],
        "formats": [
            {
                "name": f.name,
                "title": f.title,
                "extension": f.extension,
                "holds": f.holds,
                "kinds": list(f.kinds),
            }
            for f in FORMATS.values()
            if not f.optional  # written for some builds only: it comes in the folder's zip
        ],
        "state": _spec_json(STATE, ""),
        "units": UNITS_SHOWN,
    }


@dataclass(frozen=True)
class Request:
    """A request read and checked: the design it gives (targets not yet solved) and its targets.

    Attributes
    ----------
    design : Design
        The kind's defaults with the query over them.
    targets : tuple of (str, float)
        ``span``, ``rise``, ``p_xz`` as given, sorted; empty for none.
    """

    design: Design
    targets: tuple[tuple[str, float], ...] = ()

    @property
    def key(self) -> str:
        """The design's content as canonical JSON: what a worker rebuilds it from."""
        return _key(self.design)


def read_request(
    kind: str, query: Mapping[str, str] | list[tuple[str, str]], *, extra: tuple[Spec, ...] = ()
) -> tuple[Request, dict]:
    """Read and check the query of a request, without building anything.

    Parameters
    ----------
    kind : str
    query : mapping or list of (name, text) pairs
        Query parameters as sent; a name given twice is refused.
    extra : tuple of Spec, keyword-only
        Parameters of the route besides the design's (:data:`STATE` for files).

    Returns
    -------
    request : Request
    extras : dict
        The values of ``extra`` given, checked.

    Raises
    ------
    InputError
        An unknown parameter or a value the schema refuses; one line.
    """
    specs = parameters(kind) | {spec.name: spec for spec in extra}
    items = list(query.items()) if isinstance(query, Mapping) else list(query)
    values: dict = {}
    for name, text in items:
        if name not in specs:
            raise InputError(
                f"unknown parameter {name!r} for a {kind} (allowed: "
                f"{', '.join(specs)})" + suggest(name, specs)
            )
        if name in values:
            raise InputError(f"{name} is given twice", parameter=name)
        if len(text) > MAX_VALUE:
            raise InputError(f"{name} is longer than {MAX_VALUE} characters", parameter=name)
        values[name] = from_text(specs[name], text)
    replaces = _replaces(kind)
    targets = {k: values.pop(k) for k in replaces if k in values}
    extras = {spec.name: values.pop(spec.name) for spec in extra if spec.name in values}
    for target, replaced in replaces.items():
        if target in targets and replaced in values:
            raise InputError(
                f"give {target} or {replaced}, not both ({target} sets {replaced})",
                parameter=target,
            )
    for group in (values, targets, extras):
        for name, value in group.items():
            # expressions are checked with the design, on its samples
            if specs[name].kind != "function":
                group[name] = specs[name].check(value, name)
    try:
        design = default_design(kind).overrides(source=SOURCE, **values)
    except CurvefoldError as err:
        raise _without_source(err) from None
    return Request(design, tuple(sorted(targets.items()))), extras


def resolve(key: str, targets: tuple[tuple[str, float], ...] = ()) -> tuple[Design, str]:
    """The design of a request with its targets solved (cached: a fit builds about 40 vaults and
    certifies the one it returns), and what the fit chose for the user (or "")."""
    if not targets:
        return _design(key), ""
    resolved, note = _fitted(key, targets)
    return _design(resolved), note


@lru_cache(maxsize=16)
def _fitted(design_key: str, targets: tuple) -> tuple[str, str]:
    given = _design(design_key)
    fit = given.design_kind.targets
    if fit is None:
        raise InputError(f"a {given.kind} has no targets")
    try:
        design, note = fit.fit(given, source=SOURCE, **dict(targets))
    except CurvefoldError as err:  # about a parameter a target replaces: about that target
        target_of = {replaced: target for target, replaced in fit.replaces().items()}
        parameter = None if err.parameter is None else target_of.get(err.parameter, err.parameter)
        raise _without_source(err, parameter) from None
    return _key(design), note


def request_design(kind: str, query: Mapping[str, str] | list[tuple[str, str]]) -> Design:
    """The design a request describes, targets solved (:func:`read_request`, then
    :func:`resolve`)."""
    request, _ = read_request(kind, query)
    return resolve(request.key, request.targets)[0]


def design_query(design: Design) -> list[tuple[str, str]]:
    """The query parameters of a design: ``request_design(design.kind, design_query(design)) ==
    design``.

    Raises
    ------
    InputError
        A function given as a CSV column: the designer takes numbers and expressions in s.
    """
    pairs = []
    for section, values in design.to_dict().items():
        for name, value in values.items() if isinstance(values, dict) else [(section, values)]:
            if name in _FIXED:
                continue
            if isinstance(value, dict):
                raise InputError(
                    f"[{section}] {name} is a CSV column; the designer takes "
                    "numbers and expressions in s",
                    parameter=name,
                )
            if isinstance(value, list):
                text = json.dumps(value) if name == "cells" else ",".join(map(str, value))
            else:
                text = (
                    str(value).lower()
                    if isinstance(value, bool)
                    else repr(value)
                    if isinstance(value, float)
                    else str(value)
                )
            pairs.append((name, text))
    return pairs


# -- cached builds
# ------------------------------------------------------------------------------------


def _key(design: Design) -> str:
    """The design's content as canonical JSON: the cache key, and enough to rebuild it."""
    return json.dumps(design.to_dict(), sort_keys=True)


@lru_cache(maxsize=32)
def _design(key: str) -> Design:
    """The design a key holds (a frozen value, so one is shared: a request reads it about five
    times)."""
    return design_from_dict(json.loads(key), source=SOURCE)


@lru_cache(maxsize=4)
def _built(key: str, like: Built | None = None) -> Built:
    return build(_design(key), like=like)


def built(design: Design, *, samples: int | None = None) -> Built:
    """The design built (cached), at fewer ``samples`` if given: then the design is first built at
    its own samples, so that what its samples refuse (regression between coarse samples) is
    refused, never drawn, and what the build solves (a vault's arch root) is solved once for
    both."""
    try:
        if samples is not None and samples < design.samples:
            full = _built(_key(design))
            coarse = design.overrides(source=SOURCE, samples=samples)
            return _built(_key(coarse), full)
        return _built(_key(design))
    except CurvefoldError as err:
        raise _without_source(err) from None


def _without_source(err: CurvefoldError, parameter: str | None = None) -> CurvefoldError:
    """The error of a design check or a builder, its message without the request's name, about
    ``parameter`` (default the error's own)."""
    return type(err)(str(err).removeprefix(f"{SOURCE}: "), parameter=parameter or err.parameter)


def caches() -> dict[str, object]:
    """This module's LRU caches by name (their ``cache_info()`` shows that memory stays bounded;
    see also :func:`curvefold.app.designer.preview.caches`)."""
    return {
        "design": _design,
        "built": _built,
        "fitted": _fitted,
        "payload": _payload,
        "mechanics": _mechanics,
        "files": _files,
        "domain": _domain,
        "pattern": _pattern,
    }


# -- the payload, certificate and figures
# -----------------------------------------------------------


@lru_cache(maxsize=4)
def _payload(key: str) -> bytes:
    from .._outputs import structure_payload

    return strict_json(structure_payload(built(_design(key)))).encode()


def payload(design: Design) -> bytes:
    """``curvefold <kind> --json`` of a design (the same keys and values), JSON bytes."""
    return _payload(_key(design))


def certificate(design: Design, *, coarse: bool = False) -> dict:
    """The certificate of a design at its samples in every frame of its files, or, with ``coarse``,
    at :data:`COARSE_SAMPLES` as built, flat and at the design angle only (a quarter of the work).

    Returns
    -------
    dict
        ``samples``, ``coarse``, ``fold_angles`` (the frames certified, degrees),
        ``holds_up_to`` (degrees or None) and ``checks``: one dict per check (name, title in
        words, value, tolerance, status, passed, …).
    """
    if coarse and design.samples > COARSE_SAMPLES:
        from ...analysis._certificate import certify

        found = built(design, samples=COARSE_SAMPLES)
        structure = found.structure if isinstance(found, BuiltStructure) else None
        cert = certify(
            found.crease, structure, found.vault if isinstance(found, BuiltVault) else None
        )
        checks, frames = (
            [c.to_dict() for c in cert.checks],
            {
                "samples": cert.samples,
                "holds_up_to": cert.holds_up_to,
                "fold_angles": list(cert.fold_angles),
            },
        )
    else:
        coarse, found = False, json.loads(payload(design))
        checks, frames = found["certificate"], found.get("certificate_frames") or {}
    return {
        "samples": frames.get("samples") or design.samples,
        "coarse": coarse,
        "fold_angles": frames.get("fold_angles", []),
        "holds_up_to": frames.get("holds_up_to"),
        "checks": [c | {"title": TITLES.get(c["name"], c["name"])} for c in checks],
    }


#: The figures of a design under load the designer shows, in this order (the report shows them all).
MECHANICS_SHOWN = (
    "total_weight",
    "reactions",
    "max_displacement",
    "max_stress",
    "utilisation",
    "buckling_factor",
    "fold_mode_gap",
    "soft_modes",
)


#: The figures under load whose report words lead with notation: a plain name, the symbol after.
_MECHANICS_PLAIN = {"fold_mode_gap": "fold-mode gap (λ₂/λ₁)"}


def mechanics(design: Design) -> dict:
    """The design under load, as ``curvefold load --json`` gives it (its material and loads, or
    their defaults).

    Returns
    -------
    dict
        ``numbers``: :meth:`curvefold.app._loading.Loaded.to_dict`; ``labels``: each figure
        of :data:`MECHANICS_SHOWN` as ``[words, unit, explanation]``, the report's words
        (:data:`curvefold.figures._report.MECHANICS_QUANTITIES`) up to their explanation;
        ``collapse_curve`` when followed to collapse (:func:`.curves.collapse_curve`).
    """
    return json.loads(_mechanics(_key(design.with_mechanics())))


@lru_cache(maxsize=4)
def _mechanics(key: str) -> bytes:
    loaded = built(_design(key)).mechanics
    if loaded is None:
        raise InputError("the design has no material or loads to analyse")
    numbers = loaded.to_dict()
    labels = {
        k: [
            _MECHANICS_PLAIN.get(k)
            or re.split(r": | \(", MECHANICS_QUANTITIES[k][0], maxsplit=1)[0],
            MECHANICS_QUANTITIES[k][1],
            MECHANICS_QUANTITIES[k][0],
        ]
        for k in MECHANICS_SHOWN
    }
    found = {"numbers": numbers, "labels": labels}
    if loaded.collapse is not None:  # the page draws it
        found["collapse_curve"] = collapse_curve(loaded.collapse)
    return strict_json(found).encode()


def domain_svg(design: Design) -> str:
    """The regression domain of a tube, block or vault with its cells (Eq. 18), as SVG text."""
    if not design.design_kind.structure:
        raise InputError(
            "a single curved fold has no lattice: the regression domain is drawn "
            "for tubes, blocks and vaults"
        )
    return _domain(_key(design))


def built_structure(design: Design, *, samples: int | None = None) -> BuiltStructure:
    """:func:`built` of a design whose kind builds a structure of strips
    (:attr:`DesignKind.structure <curvefold.app._kinds.DesignKind.structure>`, checked by the
    caller)."""
    found = built(design, samples=samples)
    if not isinstance(found, BuiltStructure):
        raise InputError(f"a {design.kind} design builds no structure of strips")
    return found


@lru_cache(maxsize=4)
def _domain(key: str) -> str:
    from ...figures._plots import plot_regression_domain

    structure = built_structure(_design(key), samples=PREVIEW_SAMPLES).structure
    figure = plot_regression_domain(structure.lattice, structure.cells)
    out = io.StringIO()
    figure.savefig(out, format="svg")
    return out.getvalue()


def pattern_pages(design: Design) -> list[str]:
    """The crease-pattern pages as they will be cut (the SVG files a download gives), in page
    order, at the design's samples."""
    check_kind(["svg"], design.design_kind.formats_kind, "crease pattern")
    return list(_pattern(_key(design)))


@lru_cache(maxsize=4)
def _pattern(key: str) -> tuple[str, ...]:
    with tempfile.TemporaryDirectory(prefix="curvefold-") as tmp:
        # in page order
        return tuple(
            f.read_text(encoding="utf-8") for f in _write(built(_design(key)), ("svg",), Path(tmp))
        )


# -- files
# --------------------------------------------------------------------------------------------


def _write(
    built: Built, formats: tuple[str, ...], folder: Path, state: float | None = None
) -> list[Path]:
    """The files of ``formats`` written by the output folder's jobs (without the report's
    pictures), in the order they are written: a format's pages in page order."""
    from .. import _products as products

    missing = missing_dependencies(formats)
    if missing:
        raise InputError("; ".join(missing))
    files: list[Path] = []
    for label, job in products.jobs(built, formats, fold_angle=state):
        if label != "pictures":
            files += [Path(f) for f in job(folder)]
    return files


#: Media types of the two downloads that are no format of the registry (which gives the others').
ZIP, TOML = "application/zip", "application/toml"


def _zip(files: list[tuple[str, Path]]) -> bytes:
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        for name, path in files:
            z.write(path, name)
    return out.getvalue()


@lru_cache(maxsize=2)
def _files(key: str, what: str, state: float | None) -> tuple[str, str, bytes]:
    """(file name, media type, content) of a download: the format's main file, its pages zipped,
    or the folder zipped."""
    design = _design(key)
    found = built(design)
    with tempfile.TemporaryDirectory(prefix="curvefold-") as tmp:
        root = Path(tmp)
        if what == "zip":
            from .._folder import check_output
            from .._outputs import write_outputs

            out = root / f"curvefold-{design.kind}"
            # the pool is the parallelism
            write_outputs(
                found,
                check_output(out, force=False),
                show_progress=False,
                fold_angle=state,
                workers=1,
            )
            # not the folder's marker
            files = sorted(p for p in out.rglob("*") if p.is_file() and not p.name.startswith("."))
            return (
                f"curvefold-{design.kind}.zip",
                ZIP,
                _zip([(str(p.relative_to(root)), p) for p in files]),
            )
        files = _write(found, (what,), root, state)
        f = FORMATS[what]
        main = root / f"{design.kind}{f.extension}"
        if main in files:
            return main.name, f.media_type, main.read_bytes()
        same = [p for p in files if p.suffix == f.extension]
        if not same:  # an optional format of another build (the STEP of thick panels)
            raise InputError(
                f"format {what!r}: this design writes no {f.holds.split(':')[0]}"
                + "".join(f"; {n}" for n in formats_left_out((what,)))
            )
        if len(same) == 1:
            return same[0].name, f.media_type, same[0].read_bytes()
        return f"{design.kind}-{what}.zip", ZIP, _zip([(p.name, p) for p in same])


def check_download(design: Design, what: str) -> None:
    """Refuse a file the registry does not know, or one not written for the design's kind (before
    any work)."""
    if what in ("zip", "toml"):
        return
    if what not in FORMATS:
        allowed = [*default_formats(design.design_kind.formats_kind), "zip", "toml"]
        raise InputError(f"unknown file {what!r} (allowed: {', '.join(allowed)})")
    check_kind([what], design.design_kind.formats_kind, "download")


def download(design: Design, what: str, *, state: float | None = None) -> tuple[str, str, bytes]:
    """A file of the design at its own samples: (file name, media type, content).

    ``what`` is a format name of the registry (the main file; several pages come zipped),
    ``"zip"`` (the whole output folder, report included) or ``"toml"`` (the design file).
    ``state`` is the fold angle 2α of the folded state the FOLD and 3D files hold (degrees;
    default the design angle); the crease patterns are flat whatever it is.

    Raises
    ------
    InputError
        A format the registry does not know, or one not written for the design's kind.
    """
    check_download(design, what)
    if what == "toml":
        return f"{design.kind}.toml", TOML, design_toml(design).encode()
    return _files(_key(design), what, state)


def design_toml(design: Design) -> str:
    """The design as a TOML design file: ``curvefold <kind> file.toml`` rebuilds it exactly."""
    import tomli_w

    return tomli_w.dumps(design.to_dict())
