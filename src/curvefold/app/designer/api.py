"""What the designer's server answers, without the web framework: designs from query
parameters, previews, payloads, figures and files.

A request names a kind (``vault``, ``tube``, ``block``, ``crease``) and gives any key of
the design schema as a query parameter (``?a=0.4&tubes=max&fold_angle=60``); a vault also
takes the targets ``span``, ``rise`` and ``p_xz`` (:mod:`curvefold.vault.targets`), which
replace ``radius``, ``a`` and ``p_xy``. A value is read as its key's kind of value needs
(a number, a word, an expression in s, ``cells`` as JSON ``[[0, 0], [0, 1]]``,
``formats`` comma-separated) and checked by the key's :class:`~curvefold.kernel.validate.Spec`,
so the command line, design files and the server refuse the same values with the same
words. A refusal is an :class:`~curvefold.kernel.errors.InputError` whose
:attr:`~curvefold.kernel.errors.CurvefoldError.parameter` names the parameter it is about, if any.

No design is kept per user: everything is a pure function of the request, cached by the
design's content in bounded LRU caches (so two users never see each other's design, and
memory stays flat under load). Previews are built at :data:`PREVIEW_SAMPLES` (the numbers
at the design's own samples); files and the JSON payload at the design's samples.
"""

from __future__ import annotations

import base64
import io
import json
import tempfile
import threading
import zipfile
from collections.abc import Mapping
from functools import lru_cache
from pathlib import Path
from urllib.parse import urlencode

import numpy as np

from ...geometry.structure import drawable
from ...geometry.topology import tube_strips
from ...io.formats import FORMATS, check_kind, default_formats, missing_dependencies
from ...io.tables import COLOURS
from ...kernel.errors import CurvefoldError, InputError
from ...kernel.validate import MAX_TEXT, Spec, from_text, suggest
from ...vault.assembly import DEFAULT_TUBES_CAP
from ...vault.targets import REPLACES, TARGET_SPECS
from ..build import Built, build, fit_vault_targets
from ..design import KINDS, SCHEMA, SECTIONS_OF_KIND, Design, default_design, design_from_dict, kind_specs

__all__ = [
    "PREVIEW_SAMPLES",
    "MAX_VERTICES_SERVED",
    "parameters",
    "schema",
    "request_design",
    "design_query",
    "preview",
    "contact",
    "payload",
    "certificate",
    "domain_svg",
    "pattern_pages",
    "download",
    "design_toml",
    "caches",
]

#: Samples along curve 1 of the 3D preview (odd, so a vault's apex is a sample).
PREVIEW_SAMPLES = 97
#: Segments drawn along each crease in the 3D preview, and cells drawn at most.
PREVIEW_SEGMENTS, PREVIEW_CELLS = 40, 60
#: Fold-angle step between the precomputed states of the 3D preview, degrees.
MOTION_STEP = 5.0
#: Largest fold angle of the preview's states, degrees (where the first-contact search of a vault stops).
MAX_FOLD = 179.0
#: Largest design the server builds, in crease vertices (samples × lattice curves): one request must not
#: take the memory the schema's bound allows a command-line run (25 times more).
MAX_VERTICES_SERVED = 400_000
#: Longest query value read, in characters.
MAX_VALUE = 2 * MAX_TEXT
#: How a request is named in the messages of the design checks (and taken off them again).
SOURCE = "query"
#: Keys a request never sets (the kind is in the path).
_FIXED = ("kind",)
#: The target that sets each parameter a target replaces.
_TARGET_OF = {replaced: target for target, replaced in REPLACES.items()}

#: One heavy job (files, figures, certificate) at a time: they are CPU-bound and share one interpreter.
HEAVY = threading.Lock()


# -- parameters -----------------------------------------------------------------------------------


def parameters(kind: str) -> dict[str, Spec]:
    """Every query parameter of a kind: the schema keys of its sections and ``[output]``, and a vault's targets."""
    if kind not in KINDS:
        raise InputError(f"unknown kind {kind!r} (allowed: {', '.join(KINDS)})")
    specs = kind_specs(kind)
    if kind == "vault":
        specs |= {spec.name: spec for spec in TARGET_SPECS}
    return specs


def _spec_json(spec: Spec, section: str) -> dict:
    return {
        "name": spec.name, "section": section, "kind": spec.kind, "unit": spec.unit, "help": spec.help,
        "describe": spec.describe(), "choices": list(spec.choices), "required": spec.required,
        "default": None if spec.required else _plain(spec.default),
        "range": _interval_json(spec.range), "typical": _interval_json(spec.typical),
    }


def _interval_json(r) -> dict | None:
    return None if r is None else {"lo": _finite(r.lo), "hi": _finite(r.hi), "lo_closed": r.lo_closed, "hi_closed": r.hi_closed}


def _finite(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def _plain(value):
    return [_plain(v) for v in value] if isinstance(value, tuple) else value


@lru_cache(maxsize=1)
def schema() -> dict:
    """The design schema as JSON-ready data: the designer's controls are generated from it.

    Keys: ``kinds`` (kind → its sections), ``sections`` (section → list of specs with name,
    kind, unit, help, choices, default and range; ``""`` is the top level), ``targets``
    (the vault's target specs and the parameter each replaces) and ``formats`` (the
    registry: name, extension, what the file holds, the kinds it is written for).
    """
    return {
        "kinds": {kind: list(SECTIONS_OF_KIND[kind]) for kind in KINDS},
        "sections": {section: [_spec_json(spec, section) for spec in specs.values() if spec.name not in _FIXED]
                     for section, specs in SCHEMA.items()},
        "targets": [_spec_json(spec, "vault") | {"replaces": REPLACES[spec.name]} for spec in TARGET_SPECS],
        "formats": [{"name": f.name, "extension": f.extension, "holds": f.holds, "kinds": list(f.kinds)} for f in FORMATS.values()],
    }


def request_design(kind: str, query: Mapping[str, str] | list[tuple[str, str]]) -> Design:
    """The design a request describes: the kind's defaults with the query over them, targets resolved.

    Parameters
    ----------
    kind : str
    query : mapping or list of (name, text) pairs
        Query parameters as sent; a name given twice is refused.

    Raises
    ------
    InputError
        An unknown parameter, a value the schema refuses, targets out of reach, a design
        the builders refuse or one larger than :data:`MAX_VERTICES_SERVED`; one line.
    """
    specs = parameters(kind)
    items = list(query.items()) if isinstance(query, Mapping) else list(query)
    values: dict = {}
    for name, text in items:
        if name not in specs:
            raise InputError(f"unknown parameter {name!r} for a {kind} (allowed: {', '.join(specs)})" + suggest(name, specs))
        if name in values:
            raise InputError(f"{name} is given twice", parameter=name)
        if len(text) > MAX_VALUE:
            raise InputError(f"{name} is longer than {MAX_VALUE} characters", parameter=name)
        values[name] = from_text(specs[name], text)
    targets = {k: values.pop(k) for k in REPLACES if k in values}
    for target, replaced in REPLACES.items():
        if target in targets and replaced in values:
            raise InputError(f"give {target} or {replaced}, not both ({target} sets {replaced})", parameter=target)
    for group in (values, targets):
        for name, value in group.items():
            if specs[name].kind != "function":  # expressions are checked with the design, on its samples
                group[name] = specs[name].check(value, name)
    try:
        design = default_design(kind).overrides(source=SOURCE, **values)
    except CurvefoldError as err:
        raise _without_source(err) from None
    _check_size(design)
    return _fit(design, targets) if targets else design


def design_query(design: Design) -> list[tuple[str, str]]:
    """The query parameters of a design: ``request_design(design.kind, design_query(design)) == design``.

    Raises
    ------
    InputError
        A function given as a CSV column: the designer takes numbers and expressions in s.
    """
    pairs = []
    for section, values in design.to_dict().items():
        for name, value in (values.items() if isinstance(values, dict) else [(section, values)]):
            if name in _FIXED:
                continue
            if isinstance(value, dict):
                raise InputError(f"[{section}] {name} is a CSV column; the designer takes numbers and expressions in s", parameter=name)
            if isinstance(value, list):
                text = json.dumps(value) if name == "cells" else ",".join(map(str, value))
            else:
                text = str(value).lower() if isinstance(value, bool) else repr(value) if isinstance(value, float) else str(value)
            pairs.append((name, text))
    return pairs


def _fit(design: Design, targets: dict) -> Design:
    """The vault design with the targets' parameters solved (cached: a fit builds about 40 vaults)."""
    return _design(_fitted(_key(design), tuple(sorted(targets.items()))))


@lru_cache(maxsize=64)
def _fitted(design_key: str, targets: tuple) -> str:
    try:
        return _key(fit_vault_targets(_design(design_key), source=SOURCE, **dict(targets)))
    except CurvefoldError as err:  # about a parameter a target replaces: about that target
        raise _without_source(err, _TARGET_OF.get(err.parameter, err.parameter)) from None


def _check_size(design: Design) -> None:
    """Refuse a design with more crease vertices than the server builds (before building it where the count is known)."""
    if design.kind == "vault":
        v = design.vault
        lines = 4 * (DEFAULT_TUBES_CAP if v.tubes == "max" else v.tubes) * v.layers
    elif design.kind == "block":
        lines = 4 * len(design.block.cells)
    else:
        lines = 4
    if design.samples * lines > MAX_VERTICES_SERVED:
        raise InputError(f"samples × crease lines = {design.samples} × {lines} exceeds the {MAX_VERTICES_SERVED} crease vertices "
                         "the designer builds; lower samples (or tubes, layers, cells), or use the command line", parameter="samples")


# -- cached builds ------------------------------------------------------------------------------------


def _key(design: Design) -> str:
    """The design's content as canonical JSON: the cache key, and enough to rebuild it."""
    return json.dumps(design.to_dict(), sort_keys=True)


def _design(key: str) -> Design:
    return design_from_dict(json.loads(key), source=SOURCE)


@lru_cache(maxsize=16)
def _built(key: str) -> Built:
    return build(_design(key))


def _built_of(design: Design, *, samples: int | None = None) -> Built:
    if samples is not None and samples < design.samples:
        design = design.overrides(source=SOURCE, samples=samples)
    try:
        return _built(_key(design))
    except CurvefoldError as err:
        raise _without_source(err) from None


def _without_source(err: CurvefoldError, parameter: str | None = None) -> CurvefoldError:
    """The error of a design check or a builder, its message without the request's name, about
    ``parameter`` (default the error's own)."""
    return type(err)(str(err).removeprefix(f"{SOURCE}: "), parameter=parameter or err.parameter)


def caches() -> dict[str, object]:
    """The server's LRU caches by name (their ``cache_info()`` shows that memory stays bounded)."""
    return {"built": _built, "preview": _preview, "payload": _payload, "fitted": _fitted, "files": _files,
            "domain": _domain, "pattern": _pattern, "contact": _contact}


# -- the preview: numbers and the folding motion -----------------------------------------------------


def _b64(array: np.ndarray, dtype) -> str:
    return base64.b64encode(np.ascontiguousarray(array, dtype=dtype).tobytes()).decode("ascii")


def _mesh(curves: np.ndarray, strips: np.ndarray, kinds: tuple[str, ...]) -> dict:
    """Triangles of the strips and line segments of each crease kind on curves (A, M, k, 3)."""
    k = curves.shape[-2]
    i = np.arange(k - 1)
    a0, b0 = strips[:, :1] * k + i, strips[:, 1:] * k + i
    triangles = np.stack([a0, a0 + 1, b0 + 1, a0, b0 + 1, b0], axis=-1).reshape(-1, 3)
    lines = {}
    for kind in dict.fromkeys(kinds):
        rows = np.flatnonzero(np.asarray(kinds) == kind)[:, None] * k + i
        lines[kind] = _b64(np.stack([rows, rows + 1], axis=-1).reshape(-1, 2), np.uint32)
    ends = np.array([0, k - 1])
    rims = np.stack([strips[:, :1] * k + ends, strips[:, 1:] * k + ends], axis=-1).reshape(-1, 2)
    lines["rim"] = _b64(rims, np.uint32)
    flat = curves.reshape(len(curves), -1, 3)
    return {"states": len(curves), "vertices": flat.shape[1], "positions": _b64(flat, np.float32),
            "triangles": _b64(triangles, np.uint32), "lines": lines}


def _motion(built: Built) -> dict:
    """The folding motion from flat through the design angle to 179° (a vault: :func:`contact`
    then says where it stops) or halfway to 180° (a tube or block): precomputed states the
    browser morphs between."""
    if built.structure is None:  # a single curved fold: its two surfaces, one state
        crease = built.crease
        limits = [float(np.min(w)) for w in crease.regression_limits()]
        widths = tuple(min(0.15 * crease.curve.length, 0.6 * lim) for lim in limits)
        surface = crease.surface("L+R+", width=widths, rulings=2)
        idx = np.unique(np.linspace(0, len(crease.s) - 1, PREVIEW_SEGMENTS + 1).round().astype(int))
        curves = np.stack([surface[0, 0], surface[0, 1], surface[1, 1]])[:, idx][None]
        angle = float(np.degrees(2 * crease.alpha(crease.s[:1])[0]))
        return {"angles": [angle], "design_angle": angle, "end": "the design", "ground": False,
                "lift_off": None, **_mesh(curves, np.array([[0, 1], [0, 2]]), ("fold", "edge", "edge"))}
    structure = built.structure
    design_angle = float(structure.lattice.crease.fold_angle)
    end, reason = (MAX_FOLD, "first contact") if built.vault is not None else (0.5 * (design_angle + 180.0), "halfway to 180°")
    angles = np.unique(np.concatenate([
        np.linspace(0.0, design_angle, int(np.ceil(design_angle / MOTION_STEP)) + 1),
        np.linspace(design_angle, end, int(np.ceil((end - design_angle) / MOTION_STEP)) + 1),
    ]))
    vertices = structure.lattice.fold_points(structure.curves_uv, angles)
    curves, cells, kinds = drawable(structure, vertices, segments=PREVIEW_SEGMENTS, max_cells=PREVIEW_CELLS)
    lift = np.abs(vertices[:, :, [0, -1], 2]).max(axis=(1, 2)) if built.vault is not None else None
    return {"angles": angles.tolist(), "design_angle": design_angle, "end": reason, "ground": built.vault is not None,
            "lift_off": None if lift is None else lift.tolist(), **_mesh(curves, tube_strips(cells), kinds)}


#: The derived numbers shown beside the 3D view, in order.
NUMBERS = ("kappa0_s0", "proportion_change", "p_xz", "span", "rise", "tubes", "max_tubes")


def _numbers(built: Built) -> dict:
    if built.vault is not None:
        summary = built.vault.summary()
        d = built.vault.design
        return {k: summary[k] for k in NUMBERS} | {"a": d.a, "p_xy": d.p_xy, "radius": d.radius}
    if built.structure is not None:
        s = built.structure
        V = s.state().vertices.reshape(-1, 3)
        size = V.max(axis=0) - V.min(axis=0)
        return {"cells": len(s.cells), "lattice_curves": len(s.curves_uv), "size_x": size[0], "size_y": size[1], "size_z": size[2],
                "regression_margin": s.regression_margin}
    c = built.crease
    return {"length": c.curve.length, "fold_angle_start": float(np.degrees(2 * c.alpha(c.s[:1])[0])),
            "fold_angle_end": float(np.degrees(2 * c.alpha(c.s[-1:])[0]))}


@lru_cache(maxsize=64)
def _preview(key: str) -> bytes:
    design = _design(key)
    numbers = _numbers(_built_of(design))
    return json.dumps({
        "kind": design.kind, "design": design.to_dict(), "query": urlencode(design_query(design)), "numbers": numbers,
        "colours": {kind: COLOURS.get(kind, "#3a3a3a") for kind in ("fold", "seam", "junction", "edge", "rim")},
        "motion": _motion(_built_of(design, samples=PREVIEW_SAMPLES)),
    }, default=float).encode()


def preview(design: Design) -> bytes:
    """The designer's answer to a design change, JSON bytes.

    ``design`` (as resolved, targets solved) and its ``query`` (URL-encoded), ``numbers`` (derived quantities at the
    design's samples: a vault's κ0·s0, proportion change, p_xz, span, rise, tubes, max
    tubes, a, p_xy, radius), ``colours`` of the crease kinds and ``motion``: the fold
    angles of the precomputed states (degrees, flat first), the design angle, why the
    range ends, the lift-off of a vault per state (the largest ``|z|`` of its end sections,
    model units; zero at the design angle), and the mesh:
    ``positions`` (states × vertices × 3 float32, base64), ``triangles`` (uint32 triples)
    and ``lines`` per crease kind (uint32 pairs), at :data:`PREVIEW_SAMPLES`.
    """
    return _preview(_key(design))


def contact(design: Design) -> float | None:
    """The first fold angle past the design angle where parts of a vault touch (degrees, on a
    1° grid; :meth:`Vault.first_contact <curvefold.vault.assembly.Vault.first_contact>`), or None
    up to :data:`MAX_FOLD`: where the fold slider stops."""
    if design.kind != "vault":
        raise InputError(f"the first contact is searched for vaults, not for a {design.kind}")
    return _contact(_key(design))


@lru_cache(maxsize=64)
def _contact(key: str) -> float | None:
    return _built_of(_design(key)).vault.first_contact(max_angle=MAX_FOLD)


# -- the payload, certificate and figures -----------------------------------------------------------


@lru_cache(maxsize=16)
def _payload(key: str) -> bytes:
    from ..outputs import structure_payload

    return json.dumps(structure_payload(_built_of(_design(key))), default=float).encode()


def payload(design: Design) -> bytes:
    """``curvefold <kind> --json`` of a design (the same keys and values), JSON bytes."""
    with HEAVY:
        return _payload(_key(design))


def certificate(design: Design) -> list[dict]:
    """The certificate of a design at its samples: one dict per check (name, value, tolerance, passed, …)."""
    return json.loads(payload(design))["certificate"]


def domain_svg(design: Design) -> str:
    """The regression domain of a tube, block or vault with its cells (Eq. 18), as SVG text."""
    if design.kind == "crease":
        raise InputError("a single curved fold has no lattice: the regression domain is drawn for tubes, blocks and vaults")
    return _domain(_key(design))


@lru_cache(maxsize=8)
def _domain(key: str) -> str:
    from ...figures.plots import plot_regression_domain

    structure = _built_of(_design(key), samples=PREVIEW_SAMPLES).structure
    with HEAVY:
        figure = plot_regression_domain(structure.lattice, structure.cells)
        out = io.StringIO()
        figure.savefig(out, format="svg")
    return out.getvalue()


def pattern_pages(design: Design) -> list[str]:
    """The crease-pattern pages as they will be cut (the SVG files a download gives), in page order, at :data:`PREVIEW_SAMPLES`."""
    check_kind(["svg"], design.kind, "crease pattern")
    return list(_pattern(_key(design)))


@lru_cache(maxsize=8)
def _pattern(key: str) -> tuple[str, ...]:
    built = _built_of(_design(key), samples=PREVIEW_SAMPLES)
    with HEAVY, tempfile.TemporaryDirectory(prefix="curvefold-") as tmp:
        return tuple(f.read_text(encoding="utf-8") for f in _write(built, ("svg",), Path(tmp)))  # in page order


# -- files --------------------------------------------------------------------------------------------


def _write(built: Built, formats: tuple[str, ...], folder: Path) -> list[Path]:
    """The files of ``formats`` written by the output folder's jobs (without the report's pictures), in
    the order they are written: a format's pages in page order."""
    from .. import products

    missing = missing_dependencies(formats)
    if missing:
        raise InputError("; ".join(missing))
    files: list[Path] = []
    for label, job in products.jobs(built, formats):
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


@lru_cache(maxsize=4)
def _files(key: str, what: str) -> tuple[str, str, bytes]:
    """(file name, media type, content) of a download: the format's main file, its pages zipped, or the folder zipped."""
    design = _design(key)
    built = _built_of(design)
    with tempfile.TemporaryDirectory(prefix="curvefold-") as tmp:
        root = Path(tmp)
        if what == "zip":
            from ..outputs import write_outputs

            out = root / f"curvefold-{design.kind}"
            write_outputs(built, out, show_progress=False)
            files = sorted(p for p in out.rglob("*") if p.is_file())
            return f"curvefold-{design.kind}.zip", ZIP, _zip([(str(p.relative_to(root)), p) for p in files])
        files = _write(built, (what,), root)
        f = FORMATS[what]
        main = root / f"{design.kind}{f.extension}"
        if main in files:
            return main.name, f.media_type, main.read_bytes()
        same = [p for p in files if p.suffix == f.extension]
        if len(same) == 1:
            return same[0].name, f.media_type, same[0].read_bytes()
        return f"{design.kind}-{what}.zip", ZIP, _zip([(p.name, p) for p in same])


def download(design: Design, what: str) -> tuple[str, str, bytes]:
    """A file of the design at its own samples: (file name, media type, content).

    ``what`` is a format name of the registry (the main file; several pages come zipped),
    ``"zip"`` (the whole output folder, report included) or ``"toml"`` (the design file).

    Raises
    ------
    InputError
        A format the registry does not know, or one not written for the design's kind.
    """
    if what == "toml":
        return f"{design.kind}.toml", TOML, design_toml(design).encode()
    if what != "zip":
        if what not in FORMATS:
            raise InputError(f"unknown file {what!r} (allowed: {', '.join([*default_formats(design.kind), 'zip', 'toml'])})")
        check_kind([what], design.kind, "download")
    with HEAVY:
        return _files(_key(design), what)


def design_toml(design: Design) -> str:
    """The design as a TOML design file: ``curvefold <kind> file.toml`` rebuilds it exactly."""
    import tomli_w

    return tomli_w.dumps(design.to_dict())
