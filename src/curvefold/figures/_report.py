"""The HTML report of an output folder: design, derived quantities, the structure under load,
certificate and pictures.

One self-contained page that reads on a phone (390 px) as on a desktop: pictures in a
grid (wide figures across it; on a phone each at :data:`PHONE_DENSITY` picture pixels per
screen pixel in a frame of its own, so that its text stays readable, and full size on a tap), tables
that become one card per row on a phone rather than scroll sideways, every quantity and check in
words with its symbol and unit, and every file with what it holds.
"""

from __future__ import annotations

import html
import json
import re
from pathlib import Path

import numpy as np

from ..analysis._checks import TITLES
from ..kernel._json_text import plain
from ..kernel._text import one_line
from ..mechanics import error_text

__all__ = [
    "plain",
    "report_html",
    "QUANTITIES",
    "MECHANICS_QUANTITIES",
    "UNITS_SHOWN",
    "describe_file",
    "natural_key",
]

#: Pictures in the report, in this order (others follow alphabetically).
_PICTURE_ORDER = (
    "vault.png",
    "folding.gif",
    "folding-motion.png",
    "sections.png",
    "singular-values.png",
    "regression-domain.png",
    "width-proportion.png",
)
#: Pictures shown across the whole width (small multiples).
_WIDE = ("sections.png",)
#: Pictures the section of a structure under load shows (not among the others).
_MECHANICS_PICTURES = ("deflection.png", "modes.png")

#: Lengths: the model unit is the metre of the 3D files (:data:`curvefold.io._tables.UNITS`).
_UNIT = "m"
#: How the report and the designer name the schema's units.
UNITS_SHOWN = {
    "model units": _UNIT,
    "per model unit": f"1/{_UNIT}",
    "output units per model unit": f"print units per {_UNIT}",
    "degrees": "°",
}
#: Picture pixels per CSS pixel on a phone: the figures' 7 pt text (14.6 px at 150 dpi) shows at 9.7
#: px.
PHONE_DENSITY = 1.5
#: Name and unit of every derived quantity of a payload, in the order shown.
QUANTITIES = {
    "kappa0_s0": ("κ0·s0, the root of the arch condition (Eq. 20)", ""),
    "s0": ("arc length s0 of the arch curve", _UNIT),
    "proportion_change": ("proportion change w_R(s0/2) / w_R(0), predicted", ""),
    "proportion_change_measured": ("proportion change, measured on the built creases", ""),
    "p_xy_measured": ("section proportion at the feet w_R/w_L, measured", ""),
    "p_xz": ("section proportion at the apex p_xz", ""),
    "tubes": ("tubes", ""),
    "max_tubes": ("most tubes before regression", ""),
    "span": ("span, foot to foot", _UNIT),
    "rise": ("rise above the ground", _UNIT),
    "footprint": ("footprint, x × y", _UNIT),
    "bounding_box": ("bounding box, min → max (x, y, z)", _UNIT),
    "slope_xy_deg": ("section slope at the feet (xy plane)", "°"),
    "slope_zx_deg": ("section slope at the apex (zx plane)", "°"),
    "regression_margin": (
        "smallest speed factor over the creases (Eq. 17; > 0 is free of regression)",
        "",
    ),
    "ground_error": ("largest height of an end section above the ground", _UNIT),
    "cells": ("cells (i, j)", ""),
    "curves": ("lattice curves (u, v)", ""),
    "length": ("crease length", _UNIT),
    "fold_angle_start_deg": ("fold angle 2α at the start", "°"),
    "fold_angle_end_deg": ("fold angle 2α at the end", "°"),
}
#: Name and unit of every entry of the mesh resolution (``payload["mesh"]``).
MESH_QUANTITIES = {
    "samples_computed": ("samples along each crease, computed", ""),
    "mesh_samples_per_crease": (
        "samples along each crease, in the files' meshes (fewest, most)",
        "",
    ),
    "mesh_tolerance": ("accuracy asked (relative)", ""),
    "mesh_deviation": ("largest distance of the exact creases from the meshes' polylines", _UNIT),
    "mesh_deviation_relative": ("the same, over the structure's size", ""),
    "mesh_stretch": ("largest relative change of an edge length, folded against flat", ""),
    "mesh_bend_deg": ("largest fold across a ruling quad's diagonal", "°"),
    "mesh_bend_bound_deg": ("… allowed", "°"),
    "mesh_smallest_angle_deg": ("smallest triangle corner", "°"),
    "mesh_angle_bound_deg": ("… wanted", "°"),
}
#: What the files of an output folder hold, by name pattern (first match wins).
_FILES = (
    (
        r"^sheets/.*\.fold$",
        "one developed sheet, flat with its target fold angles (loads in Origami Simulator)",
    ),
    (
        r"^design\.toml$",
        "the design file that builds this folder again (curvefold <kind> design.toml)",
    ),
    (r"^report\.json$", "everything on this page, for programs"),
    (r"^report\.html$", "this page"),
    (
        r"-pattern(-p\d+)?\.svg$",
        "crease pattern page, mm at 1:1, one layer per line kind, scale bar and legend",
    ),
    (r"\.png$", "picture in this report"),
)


def natural_key(name: str) -> tuple:
    """Sort key that orders the numbers in a name by value: p2 before p10.

    Examples
    --------
    >>> sorted(["p10.svg", "p2.svg", "p1.svg"], key=natural_key)
    ['p1.svg', 'p2.svg', 'p10.svg']
    """
    return tuple(
        (0, int(part), "") if part.isdigit() else (1, 0, part)
        for part in re.split(r"(\d+)", name)
        if part
    )


def describe_file(name: str) -> str:
    """What a file of an output folder holds, for the report's file list."""
    from ..io._formats import FORMATS

    for pattern, text in _FILES:
        if re.search(pattern, name):
            return text
    own = [f for f in FORMATS.values() if f.stem is not None]  # a file name of its own first
    named = next((f.holds for f in own if f.path(Path(name).stem).as_posix() == name), None)
    if named is not None:
        return named
    suffix = name[name.rfind(".") :]
    return next((f.holds for f in FORMATS.values() if f.extension == suffix and f.stem is None), "")


def _number(value) -> str:
    """A value as people read it: 6 significant digits, lists as (a, b, c)."""
    if isinstance(value, bool) or isinstance(value, (int, np.integer)):
        return str(value)
    if isinstance(value, float):
        return f"{value:.6g}" if value == 0 or 1e-3 <= abs(value) < 1e6 else f"{value:.3e}"
    if isinstance(value, (list, tuple)):
        if (
            len(value) == 2
            and all(isinstance(v, (list, tuple)) for v in value)
            and len(value[0]) == 3
        ):
            return f"{_number(value[0])} → {_number(value[1])}"
        if len(value) > 12:
            return ", ".join(_number(v) for v in value[:12]) + f", … ({len(value)} in all)"
        return "(" + ", ".join(_number(v) for v in value) + ")"
    return str(value)


def _rows(values: dict, names: dict) -> str:
    e = html.escape
    out = []
    for key, (label, unit) in names.items():
        if key in values:
            value = values[key]
            shown = " × ".join(_number(v) for v in value) if key == "footprint" else _number(value)
            out.append(
                f'<tr><td>{e(label)}</td><td class="num">{e(shown)}</td><td '
                f"class=unit>{e(unit)}</td></tr>"
            )
    return "".join(out)


def _cells(labels: tuple[str, ...], cells: list[str], attrs: tuple[str, ...] = ()) -> str:
    """A row whose cells carry their column's label (a phone shows each row as a card: label,
    value)."""
    attrs = attrs or ("",) * len(cells)
    return "".join(
        f'<td data-label="{html.escape(label)}"{a}>{cell}</td>'
        for label, cell, a in zip(labels, cells, attrs)
    )


def _parameters_table(payload: dict) -> str:
    """The design's parameters in words with their symbols and units, or its raw form when the
    payload has no words."""
    e = html.escape
    raw = e(json.dumps(payload.get("design", {}), indent=2, default=plain))
    rows = payload.get("parameters")
    if not rows:
        return f"<pre>{raw}</pre>"
    columns, attrs = ("parameter", "symbol", "value", "unit"), ("", "", " class=num", "")
    body = "".join(
        "<tr>"
        + _cells(
            columns,
            [e(r["label"]), f"<code>{e(r['name'])}</code>", e(_number(r["value"])), e(r["unit"])],
            attrs,
        )
        + "</tr>"
        for r in rows
    )
    head = "<tr><th>parameter</th><th>symbol</th><th>value</th><th>unit</th></tr>"
    text = payload.get("design_toml")
    design_file = (
        ""
        if text is None
        else "<details><summary><code>design.toml</code>, the design file in this folder: "
        f"<code>curvefold {e(str(payload.get('kind', '')))} design.toml</code> builds it "
        f"again</summary><pre>{e(text)}</pre></details>"
    )
    return f"<table class=cards>{head}{body}</table>{design_file}"


def _sci(x: float | None, prefix: str = "") -> str:
    """A certificate figure: 3 digits, or "—" when there is none."""
    return "—" if x is None else f"{prefix}{x:.3g}" if prefix else f"{x:.2e}"


_CERTIFICATE_COLUMNS = (
    "check",
    "status",
    "measured",
    "tolerance",
    "margin",
    "unit",
    "worst frame and place",
)


def _certificate_row(c: dict) -> str:
    e = html.escape
    kind = "pass" if c["passed"] else "fail" if c["status"] == "fail" else "unresolved"
    needed = (
        f"<br><small>use ≥ {c['samples_needed']} samples</small>" if c["samples_needed"] else ""
    )
    title = f"<b>{e(TITLES.get(c['name'], c['name']))}</b><br><code>{e(c['name'])}</code>"
    cells = [
        title,
        f"{e(c['status'])}{needed}",
        _sci(c["value"]),
        _sci(c["tolerance"]),
        _sci(c["margin"], "×"),
        e(c["unit"]),
        e(c["where"]),
    ]
    classes = ("", " class=status", " class=num", " class=num", " class=num", "", "")
    return (
        f"<tr class='{kind} head'>{_cells(_CERTIFICATE_COLUMNS, cells, classes)}</tr>"
        f"<tr class='{kind} about'><td colspan=7 data-label='what it measures'>"
        f"{e(c['measures'])}<br><small>Error model: {e(c['model'])}</small></td></tr>"
    )


def _certificate_table(payload: dict) -> str:
    """The certificate: per check its status, value, tolerance, margin, where, what it measures
    and its error model."""
    e = html.escape
    rows = "".join(_certificate_row(c) for c in payload["certificate"])
    head = "<tr>" + "".join(f"<th>{name}</th>" for name in _CERTIFICATE_COLUMNS) + "</tr>"
    frames = payload.get("certificate_frames") or {}
    angles = frames.get("fold_angles") or []
    motion = ""
    contact = frames.get("first_contact")
    ends = (
        ""
        if contact is None
        else (
            f"The folding motion runs from flat to 2α = {contact:g}°, "
            "where the structure first touches itself (the first contact): its files hold the "
            "frames before it. "
        )
    )
    if angles:
        listed = ", ".join(f"{a:g}°" for a in angles)
        motion = f"<p>{ends}Certified as built and in the frames 2α = {e(listed)}."
        panels = bool(payload.get("mechanism"))
        if frames.get("holds_up_to") is not None and panels:
            motion += (
                f" Every check passes up to 2α = {frames['holds_up_to']:g}° (rigid "
                "panels: their residuals are rounding at any angle; the search ends within "
                "1.5° of 180°)."
            )
        elif frames.get("holds_up_to") is not None:
            motion += (
                f" Every check passes up to 2α = {frames['holds_up_to']:g}° at "
                f"{frames['samples']} samples (past it the error of the folded state, growing "
                "as κ = κ_2D / cos α, outgrows a cap)."
            )
        else:
            motion += (
                " Not every check passes in every frame (see below)."
                if panels
                else (
                    f" At {frames['samples']} samples not every check passes in every frame "
                    "(see below)."
                )
            )
        motion += (
            " The crease checks measure the smooth crease the panels sample.</p>"
            if panels
            else "</p>"
        )
    model = (
        "<p>The model column: the internal model at the design's samples.</p>"
        if payload.get("certificate_file")
        else ""
    )
    table = f"{motion}{model}<table class='certificate cards'>{head}{rows}</table>"
    return table + _certificate_file_table(payload.get("certificate_file"))


_FILE_COLUMNS = ("check", "status", "measured", "tolerance", "unit", "worst frame and place")


def _certificate_file_table(shipped: dict | None) -> str:
    """The certificate's file column: the checks of the FOLD file as written, with how each
    tolerance follows from what the file promises ("" when no FOLD file was written)."""
    if not shipped:
        return ""
    e = html.escape
    head = "<tr>" + "".join(f"<th>{name}</th>" for name in _FILE_COLUMNS) + "</tr>"
    rows = "".join(
        f"<tr class='{c['status'] if c['status'] in ('pass', 'fail') else ''}'>"
        + _cells(
            _FILE_COLUMNS,
            [
                f"<code>{e(c['name'])}</code>",
                e(c["status"]) + (f"<br><small>{e(c['reason'])}</small>" if c["reason"] else ""),
                _sci(c["value"]),
                _sci(c["tolerance"]),
                e(c["unit"]),
                e(c["where"]),
            ],
        )
        + "</tr>"
        for c in shipped["checks"]
    )
    sources = "".join(
        f"<li><code>{e(name)}</code>: {e(how)}</li>"
        for name, how in shipped.get("tolerance_sources", {}).items()
    )
    return (
        f"<h3>The file column: {e(shipped['file'])} as written</h3><p>Measured on the FOLD "
        "file that ships (its frames, read back, at the samples it carries), against the "
        "tolerances it promises; <code>curvefold check</code> on the file gives the same.</p>"
        f"<table class='certificate cards'>{head}{rows}</table>"
        + (f"<ul>{sources}</ul>" if sources else "")
    )


def _mechanism_table(mechanism: dict) -> str:
    """A panel structure's degrees of freedom at each analysed state, with its smallest singular
    values."""
    e = html.escape
    scope = f" of {e(mechanism['scope'])} (the dense SVD is bounded)" if mechanism["scope"] else ""
    head = (
        "<tr><th>state</th><th>internal DOF</th><th>nullity</th><th>smallest singular values "
        "/ σ_max</th><th>gap</th><th>clearance</th><th>residual</th></tr>"
    )
    rows = ""
    columns = (
        "state",
        "internal DOF",
        "nullity",
        "smallest singular values / σ_max",
        "gap",
        "clearance",
        "residual",
    )
    for m in mechanism["states"]:
        smallest = ", ".join(f"{v / m['sigma_max']:.1e}" for v in m["smallest_singular_values"][:9])
        cells = [
            e(m["label"]),
            str(m["dof"]),
            str(m["nullity"]),
            f"{smallest}, …",
            "∞" if m["gap"] is None else _sci(m["gap"]),
            _sci(m["clearance"]),
            _sci(m["residual"]),
        ]
        classes = ("", " class=num", " class=num", "", " class=num", " class=num", " class=num")
        rows += f"<tr>{_cells(columns, cells, classes)}</tr>"
    return (
        "<h2>Mechanism</h2><p>Degrees of freedom of the rigid panels" + scope + ": the "
        "first-order motions are the null space of the Jacobian of every edge length, both "
        "diagonals and the planarity of every panel, seams and bonds welded; six of them move "
        "the whole rigidly. A singular value counts as null at or below 1e-9 σ_max. The flat "
        "state's extra ones lift the flat sheets at first order only.</p><table "
        f"class=cards>{head}{rows}</table>"
    )


#: Name and unit of every figure of a structure under load (``payload["mechanics"]``), in the order
#: shown.
MECHANICS_QUANTITIES = {
    "total_weight": ("total weight", "N"),
    "applied_load": ("applied load, sum [x, y, z]", "N"),
    "reactions": ("support reactions, sum [x, y, z] (they carry the load)", "N"),
    "equilibrium_error": (
        "|Σ reactions + Σ loads| over the forces summed (rounding when they balance)",
        "",
    ),
    "max_displacement": ("largest displacement", "m"),
    "max_stress": (
        "largest stress at the sheet's faces (membrane von Mises plus bending, an upper bound)",
        "Pa",
    ),
    "utilisation": ("stress over strength: the largest stress over the material's strength", ""),
    "buckling_factor": ("linear buckling factor: the load times this buckles the structure", ""),
    "fold_mode_gap": (
        "fold-mode gap λ₂/λ₁: how much stiffer the next free mode is than the folding",
        "",
    ),
    "soft_modes": (
        "soft modes: motions that stretch no bar, rigid motions aside (the folding is one)",
        "",
    ),
    "fold_mode_correlation": (
        "correlation of the first free mode with the rigid folding motion",
        "",
    ),
    "fold_span_correlation": (
        "correlation of the rigid folding motion with the span of the free modes found",
        "",
    ),
    "nodes": ("nodes of the bar-and-hinge model", ""),
    "samples": ("samples along each crease the model keeps", ""),
}


def _balanced(forces: list[float], load: float) -> list[float]:
    """Forces with what is below 1e-9 of the load (the rounding of forces that balance it) shown as
    0.

    >>> _balanced([1.1e-12, -3e-7, 70.7], 70.7)
    [0.0, -3e-07, 70.7]
    """
    return [0.0 if abs(f) <= 1e-9 * load else f for f in forces]


def _mechanics_section(m: dict, files: list[str]) -> str:
    """The structure under load: what it is made of and what loads it, the deflected shape, the
    numbers and the first modes."""
    e = html.escape
    sheet = m["sheet"]
    strength = (
        "no strength given"
        if sheet["strength"] is None
        else f"strength {sheet['strength'] / 1e6:.4g} MPa"
    )
    loads = m["loads"]
    what = loads["described"]  # each load case in words (curvefold.mechanics.LoadCase.describe)
    held = (
        "its feet (the end sections on the ground)"
        if m["supported"] == "feet"
        else "both end sections of every tube (t = 0 and t = 1)"
    )
    intro = (
        f"<p>{e(m['material'])} {_number(m['thickness'] * 1e3)} mm thick (E "
        f"{sheet['youngs_modulus'] / 1e9:.4g} GPa, ν {_number(sheet['poisson'])}, density "
        f"{_number(sheet['density'])} kg/m³, {e(strength)}; {e(sheet['source'])}), creases of "
        f"{_number(m['crease_stiffness'])} N·m/rad/m, under {e(' and '.join(what))}, held at "
        f"{e(held)}, {e(m['supports'])}. The bar-and-hinge model of the structure at its "
        "design angle, linear; SI units, z up.</p>"
    )
    shown = m | {  # each figure with its estimated error
        key: f"{_number(m[key])}{error_text(error)}"
        for key, error in m.get("errors", {}).items()
        if isinstance(m.get(key), float) and error is not None
    }
    if m["buckling_factor"] is None:
        shown["buckling_factor"] = "none (the load only stiffens it)"
    if m["utilisation"] is None:
        shown["utilisation"] = "unknown (no strength)"
    if not m["buckling_resolved"]:
        shown["buckling_factor"] = f"{shown['buckling_factor']}: not resolved (see below)"
    load = max(abs(v) for v in m["applied_load"])
    shown["reactions"] = _balanced(m["reactions"], load)
    rows = _rows(shown, MECHANICS_QUANTITIES)
    ends = "".join(
        f"<tr><td>reactions at {e(end)}, [x, y, z]</td><td "
        f"class=num>{e(_number(_balanced(r, load)))}</td><td class=unit>N</td></tr>"
        for end, r in m["reactions_by_end"].items()
    )
    picture = lambda name, alt, wide="": (
        f'<figure{wide}><a href="{name}"><img src="{name}" '
        f'srcset="{name} {PHONE_DENSITY:g}x" '  # noqa: E731
        f'alt="{e(alt)}"></a><figcaption>{e(alt)}</figcaption></figure>'
        if name in files
        else ""
    )
    columns = ("mode", "λ = ω²", "frequency", "λ / λ₁", "stretching share")
    lam = m["modes"]
    modes = "".join(
        "<tr>"
        + _cells(
            columns,
            [str(k + 1), _number(v), _number(f), _number(v / lam[0]), f"{s:.1%}"],
            ("", " class=num", " class=num", " class=num", " class=num"),
        )
        + "</tr>"
        for k, (v, f, s) in enumerate(zip(lam, m["frequencies"], m["stretching"]))
    )
    notes = "".join(f"<p><small>{e(one_line(n))}.</small></p>" for n in m["notes"])
    return (
        f"<h2>Under load: will it stand?</h2>{_verdict_html(m)}{intro}<table>{rows}{ends}</table>"
        f"{notes}<div "
        "class=pictures>"
        + picture(
            "deflection.png",
            f"the deflected shape, displacement × {m['deflection_scale']:g}, coloured by its size",
        )
        + "</div><h3>The first free modes</h3><p>Of the structure without supports, its "
        "rigid motions removed (the first is its folding motion); with the share of "
        "each one's energy that stretches the sheet.</p>" + "<table "
        f"class=cards><tr>{''.join(f'<th>{e(c)}</th>' for c in columns)}</tr>{modes}</table><div "
        "class=pictures>"
        + picture(
            "modes.png",
            f"the first free modes, largest displacement {m['mode_amplitude']:g} m",
            " class=wide",
        )
        + "</div>"
    )


def _verdict_html(m: dict) -> str:
    """The answer, then every check and the load and reactions of every combination."""
    if "checks" not in m:
        return ""
    e = html.escape
    columns = ("check", "combination", "value", "limit", "utilisation", "")
    units = {"Pa": (1e-6, " MPa"), "m": (1e3, " mm"), "": (1.0, "")}

    def shown(value: float | None, unit: str) -> str:
        scale, suffix = units.get(unit, (1.0, f" {unit}"))
        return "none" if value is None else f"{_number(value * scale)}{suffix}"

    checks = "".join(
        "<tr>"
        + _cells(
            columns,
            [
                e(c["name"]),
                e(c["combination"]),
                shown(c["value"], c["unit"]),
                f"{shown(c['limit'], c['unit'])} ({e(c['basis'])})",
                f"{c['utilisation']:.3g}{error_text(c.get('error'))}",
                "ok" if c["passed"] else "<strong>fails</strong>",
            ],
            ("", "", " class=num", "", " class=num", ""),
        )
        + "</tr>"
        for c in m["checks"]
    )
    size = lambda c: max(abs(v) for v in c["applied_load"])  # noqa: E731
    combos = "".join(
        f"<tr><td>{e(c['name'])}</td><td class=num>"
        f"{e(_number(_balanced(c['applied_load'], size(c))))}</td><td class=num>"
        f"{e(_number(_balanced(c['reactions'], size(c))))}</td></tr>"
        for c in m["combinations"]
    )
    answer = "It stands" if m["verdict"] == "stands" else "It fails"
    return (
        f"<p class=verdict><strong>{answer}</strong>: {e(m['verdict_text'].split(': ', 1)[1])}."
        "</p><table class=cards><tr>"
        + "".join(f"<th>{e(c)}</th>" for c in columns)
        + f"</tr>{checks}</table><table class=cards><tr><th>combination</th><th>applied load "
        f"[x, y, z], N</th><th>reactions [x, y, z], N</th></tr>{combos}</table>"
    )


def report_html(payload: dict) -> str:
    """A self-contained HTML report: parameters, derived quantities, certificate, pictures."""
    e = html.escape
    certificate = _certificate_table(payload)
    derived = _rows(payload, QUANTITIES)
    mesh = ""
    if payload.get("mesh"):
        mesh = (
            "<h2>Meshes of the files</h2><p>The 3D, FOLD and crease-pattern files keep, "
            "tube by tube, the fewest samples that stay within the accuracy asked; "
            f"measured:</p><table>{_rows(payload['mesh'], MESH_QUANTITIES)}</table>"
        )
    mechanism = _mechanism_table(payload["mechanism"]) if payload.get("mechanism") else ""
    design = _parameters_table(payload)
    paper = ""
    if payload.get("paper_comparison"):
        columns = ("quantity", "paper", "computed", "from the paper's κ0·s0", "note")
        rows = [
            [
                e(QUANTITIES.get(r["quantity"], (r["quantity"],))[0]),
                str(r["paper"]),
                f"{r['computed']:.12g}",
                f"{r['from_paper_kappa0_s0']:.4g}",
                e(r["note"]),
            ]
            for r in payload["paper_comparison"]
        ]
        paper = (
            "<h2>The paper's example</h2><table class=cards><tr>"
            + "".join(f"<th>{e(c)}</th>" for c in columns)
            + "</tr>"
            + "".join(f"<tr>{_cells(columns, cells)}</tr>" for cells in rows)
            + "</table>"
        )
    files = sorted(payload.get("files", []), key=natural_key)
    under_load = _mechanics_section(payload["mechanics"], files) if payload.get("mechanics") else ""
    shown = sorted(
        (
            f
            for f in files
            if f.endswith((".png", ".gif")) and not (under_load and f in _MECHANICS_PICTURES)
        ),
        key=lambda f: (_PICTURE_ORDER.index(f) if f in _PICTURE_ORDER else len(_PICTURE_ORDER), f),
    )
    pictures = "".join(
        f'<figure{" class=wide" if f in _WIDE else ""}><a href="{e(f)}"><img src="{e(f)}" '
        f'srcset="{e(f)} {PHONE_DENSITY:g}x" '
        f'alt="{e(f)}"></a><figcaption>{e(f)}</figcaption></figure>'
        for f in shown
    )
    links = "".join(
        f'<tr><td><a href="{e(f)}">{e(f)}</a></td><td>{e(describe_file(f))}</td></tr>'
        for f in files
    )
    notes = "".join(f"<p>{e(one_line(note))}</p>" for note in payload.get("notes", []))
    passed = sum(c["passed"] for c in payload["certificate"])
    shipped = payload.get("certificate_file") or {"checks": []}
    ran = [c["status"] for c in shipped["checks"] if c["status"] != "not run"]
    on_file = f"; on the FOLD file as written, <b>{ran.count('pass')}/{len(ran)}</b>" * bool(ran)
    title = e(one_line(payload.get("title") or payload.get("kind", "curvefold")))
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>curvefold — {title}</title>
<style>
body{{font-family:system-ui,sans-serif;max-width:1100px;margin:1.5em auto;padding:0 1em;
color:#222;line-height:1.4}}
h1{{font-size:1.5em;overflow-wrap:anywhere}}
table{{border-collapse:collapse;margin:1em 0;display:block;overflow-x:auto;max-width:100%}}
td,th{{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}}
.num{{white-space:nowrap;text-align:right;font-variant-numeric:tabular-nums}}td.status,td.unit{{white-space:nowrap}}
tr.pass td.status{{color:#070}}tr.fail td{{background:#fee}}tr.unresolved td{{background:#fff6dd}}
table.certificate small{{color:#555}}table.certificate td:nth-child(7){{min-width:14em}}
table.certificate tr.head td{{border-bottom:none}}
table.certificate tr.about td{{border-top:none;font-size:.9em;padding-bottom:.6em}}
.pictures{{display:grid;grid-template-columns:repeat(auto-fill,minmax(min(100%,420px),1fr));gap:1em}}
figure{{margin:0}}figure.wide{{grid-column:1/-1}}
img{{width:100%;height:auto;border:1px solid #ddd}}figcaption{{font-size:.85em;color:#555}}
pre{{background:#f6f6f6;padding:1em;overflow-x:auto}}code{{font-size:.9em;color:#555}}
td{{overflow-wrap:anywhere}}
@media (max-width:600px){{
 body{{margin:.8em auto;padding:0 .6em}}
 table{{display:table;width:100%}}td.num{{white-space:normal}}
 table.cards,table.cards tbody,table.cards tr,table.cards td{{display:block;width:100%;
  box-sizing:border-box}}
 table.cards{{overflow:visible}}table.cards tr:first-child:has(th){{display:none}}
 table.cards tr{{border:1px solid #ccc;margin:0 0 .6em;padding:.2em 0}}
 table.cards tr.about{{margin-top:-.6em;border-top:none}}
 table.cards td{{border:none;padding:.15em .6em;text-align:left;white-space:normal}}
 table.cards td[data-label]::before{{content:attr(data-label) ": ";color:#666;font-size:.85em}}
 table.certificate tr.about td::before{{content:none}}
 table.certificate td:nth-child(7){{min-width:0}}
 .pictures{{display:block}}figure{{overflow-x:auto;margin:0 0 1em}}
 figure img{{width:auto;max-width:none}}
}}
</style></head><body>
<h1>curvefold — {title}</h1>
<p>Geometric certificate: <b>{passed}/{len(payload["certificate"])}</b> checks pass on the
model{on_file}. Lengths are in metres (the model unit, as in the 3D files); crease patterns are
in millimetres at their print scale. On a phone, slide a picture sideways or tap it for its full
size.</p>
<h2>Pictures</h2>{notes}<div class="pictures">{pictures}</div>
<h2>Derived quantities</h2><table>{derived}</table>
{under_load}
{mesh}
{paper}
<h2>Certificate</h2>{certificate}
{mechanism}
<h2>Design</h2>{design}
<h2>Files</h2><table>{links}</table>
</body></html>
"""
