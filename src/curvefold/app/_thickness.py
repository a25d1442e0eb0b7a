"""Thick panels from the command line: a structure of rigid panels that says what it is made of.

A vault, tube or block of rigid panels (``panels = N``, ``--panels N``) whose design has a
``[material]`` section (any of ``--material``, ``--thickness`` or the material's own values)
is built of thick panels: every panel a solid of the material's ``thickness`` (metres, 1 mm
by default; the model's units are metres) by the offset-panel technique
(:meth:`curvefold.geometry.ThickPanels.offset`: hinges on the zero-thickness creases, each solid
outside its tube, edges bevelled for the fold from flat to the design angle, top faces set
back by at most half the panel's inradius). Where those bevels cannot reach the design angle,
the panels are tapered: their top faces set back by up to :data:`TAPER` of the inradius.
Its output folder then holds (``curvefold vault``, ``tube``, ``block``):

* ``<kind>_solids.stl``: the solids at the design angle, 1:1 in the output units, watertight;
* ``<kind>_solids.3dm``: the solids as closed polysurfaces, in metres (with ``3dm``);
* ``<kind>_solids.step``: the solids as closed B-rep solids (with ``step`` and OpenCascade);
* ``<kind>_cut_list.csv``, ``.json`` and ``.pdf``: every panel's outline, edge lengths, bevels
  and hinges, named by its tube (numbered as in the assembly guide), sheet, strip and place
  along the crease, in the order of assembly (the PDF a printable row per panel);
* ``assembly.pdf`` (the ``guide`` formats): the steps assemble the panels, named by those ids
  in that order, and the cut list follows on its last pages;

and the report, the ``--json`` output (its ``thickness`` key) and the certificate say how far it
folds with thickness beside the zero-thickness motion, its flat stack, its degrees of freedom
and the thickness checks. A smooth structure (``panels = 0``) has no solids: the material's
thickness is then the mechanics' and the crease patterns' (:mod:`curvefold.io._thick_sheet`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..kernel._errors import InputError

if TYPE_CHECKING:  # pragma: no cover
    from ..analysis._certificate import Certificate
    from ..geometry._structure import Structure
    from ..geometry._thick import ThickPanels
    from ._design import Design

__all__ = [
    "TAPER",
    "thick_panels",
    "thickness_payload",
    "thickness_lines",
    "thickness_html",
    "write_thick_files",
]


#: The setback of tapered panels' top faces, as a fraction of the inradius (their bevels: up to
#: atan(0.75 r / t)); the top faces of the paper's vault keep 58 % of their panels' area at
#: t = 1 cm, radius 1 m (measured).
TAPER = 0.75


def thick_panels(structure: Structure, design: Design) -> ThickPanels | None:
    """The thick panels a design builds (module notes): offset panels, or tapered ones where
    those cannot reach the design angle; None for a smooth structure or one with no
    ``[material]``.

    Raises
    ------
    InputError
        One line: a thickness above what the panels allow (their inradius, or the bevels the
        design angle needs), with the value, the limit and what to change.
    """
    if not structure.lattice.rigid or design.material is None:
        return None
    from ..geometry._thick import ThickPanels

    t = design.material.thickness
    try:
        return ThickPanels.offset(structure, t)
    except InputError:
        pass
    try:
        return ThickPanels.offset(structure, t, setback=TAPER)
    except InputError as exc:
        raise InputError(
            f"{design.source}: [material] {exc}, or {_larger(structure, design, t)}",
            parameter="thickness",
        ) from exc


def _larger(structure: Structure, design: Design, thickness: float) -> str:
    """A structure large enough for the thickness, in words: the vault's radius it needs (every
    length of a vault scales with its radius, the thickness limit too), else "a larger one"."""
    from ..geometry._thick import thickness_limit

    vault = getattr(design, "vault", None)
    if vault is None:
        return "a larger structure"
    need = vault.radius * thickness / thickness_limit(structure, setback=TAPER)
    return f"a vault of radius > {need:.3g} (--radius; the limit grows with it)"


def _volumes(thick: ThickPanels) -> np.ndarray:
    """Every solid's volume (F,), by the divergence theorem on its closed triangles."""
    x, tri = thick.triangles()
    a, b, c = (x[tri[:, i]] for i in range(3))
    signed = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    return signed.reshape(len(thick.side), -1).sum(axis=1)


def _material(design: Design) -> tuple[str | None, float | None]:
    """The name of the design's material ("user" for its own values) and its density, kg/m³."""
    from ..mechanics import MATERIALS

    params = design.material
    if params is None:
        return None, None
    if params.material is not None:
        return params.material, MATERIALS[params.material].density
    return "user", params.density


def thickness_payload(thick: ThickPanels, certificate: Certificate, design: Design) -> dict:
    """The ``thickness`` key of the report and ``--json``: the technique, the material, the range
    of motion with thickness beside the zero-thickness one, the flat stack, the bevels, the
    degrees of freedom and the checks (from the certificate's thickness report)."""
    report = certificate.thickness
    assert report is not None  # certified with the thick panels
    labels = thick.labels()
    r = report["range"]
    name, density = _material(design)
    volume = float(_volumes(thick).sum())
    contact = certificate.first_contact
    return {
        "thickness": thick.thickness,
        "unit": "m",
        "technique": thick.technique,
        "setback": thick.setback,
        "material": name,
        "panels": len(labels),
        "volume": volume,
        "mass": None if density is None else volume * density,
        "bevels_max_deg": float(np.degrees(thick.bevels.max())),
        "bevels_for_fold_angles": list(thick.reach),
        "range": {
            "design": r["design"],
            "low": r["low"],
            "high": r["high"],
            "low_contact": None if r["low_pair"] is None else [labels[i] for i in r["low_pair"]],
            "high_contact": None if r["high_pair"] is None else [labels[i] for i in r["high_pair"]],
            "short_of_flat": r["low"],
        },
        # the first contact is sought up to 179° (curvefold.geometry.first_contact)
        "zero_thickness_range": {
            "low": 0.0,
            "high": 179.0 if contact is None else contact,
            "ends_at_contact": contact is not None,
        },
        "stack_height": report["stack_height"],
        "dof": [m["dof"] for m in report["mechanism"]],
        "dof_states": [s for s in report["states"] if s > 0],
        "dof_scope": report["mechanism_scope"] or "every tube",
        "checks": report["checks"],
    }


def thickness_lines(payload: dict) -> list[str]:
    """The thick panels in a few lines of the command's summary."""
    t = payload.get("thickness")
    if t is None:
        return []
    r, z = t["range"], t["zero_thickness_range"]
    what = f"{t['material']} " if t["material"] else ""
    if r["low"] == 0:
        stop, stack = "folds flat", ""
    else:
        touch = " and ".join(r["low_contact"] or [])
        stop = f"stops {r['low']:.4g}° short of flat ({touch} touch)"
        stack = ", were it to fold flat"
    return [
        f"  thick panels       {t['panels']} of {what}{t['thickness'] * 1e3:g} mm, "
        f"{t['technique']}, bevels up to {t['bevels_max_deg']:.3g}°",
        f"  range with t       2α = {r['low']:.4g}° to {r['high']:.4g}° (zero thickness: "
        f"{z['low']:g}° to {z['high']:g}°{'' if z['ends_at_contact'] else ', no contact'}): "
        f"{stop}",
        f"  flat stack         {t['stack_height'] * 1e3:.4g} mm{stack}; DOF "
        f"{', '.join(map(str, sorted(set(t['dof']))))} ({t['dof_scope']})",
    ]


def thickness_html(report_html: str, payload: dict) -> str:
    """The report's page with a section on its thick panels before its certificate (unchanged
    without them)."""
    from html import escape

    t = payload.get("thickness")
    if t is None:
        return report_html
    r, z = t["range"], t["zero_thickness_range"]
    touch = " and ".join(r["low_contact"] or [])
    rows = [
        ("thickness t", f"{t['thickness'] * 1e3:g} mm of {t['material'] or 'the sheet'}"),
        ("technique", t["technique"]),
        ("range of 2α with thickness", f"{r['low']:.4g}° to {r['high']:.4g}°"),
        (
            "range of 2α without",
            f"{z['low']:g}° to {z['high']:g}° "
            + ("(its first contact)" if z["ends_at_contact"] else "(no contact)"),
        ),
        (
            "short of flat by",
            "0° (it folds flat)" if r["low"] == 0 else f"{r['low']:.4g}°, where {touch} touch",
        ),
        ("flat stack", f"{t['stack_height'] * 1e3:.4g} mm"),
        ("bevels up to", f"{t['bevels_max_deg']:.3g}°, cut for 2α = 0° to {r['design']:g}°"),
        ("degrees of freedom", f"{', '.join(map(str, sorted(set(t['dof']))))} ({t['dof_scope']})"),
        ("mass", "" if t["mass"] is None else f"{t['mass']:.4g} kg"),
    ]
    body = "".join(f"<tr><th>{escape(a)}</th><td>{escape(b)}</td></tr>" for a, b in rows)
    section = (
        f"<h2>Thick panels</h2><p>{t['panels']} solids: their cut list with bevels is the CSV, "
        f"JSON and PDF <code>*_cut_list</code> (in the order of assembly, as in the assembly "
        f"guide), the solids <code>*_solids.stl</code> (1:1), "
        f"<code>*_solids.3dm</code> and <code>*_solids.step</code>.</p><table>{body}</table>\n"
    )
    return report_html.replace("<h2>Certificate</h2>", section + "<h2>Certificate</h2>", 1)


def write_thick_files(
    thick: ThickPanels, folder: Path, kind: str, formats: tuple[str, ...], units: str
) -> list[Path]:
    """The solids (STL 1:1 in ``units``; 3dm in metres when ``formats`` has ``3dm``) and the cut
    list (CSV and PDF in ``units``, JSON in metres) into ``folder``."""
    from ..io._solids import (
        write_cut_list,
        write_cut_list_csv,
        write_cut_list_pdf,
        write_thick_3dm,
        write_thick_stl,
    )

    base = folder / kind
    files = [
        write_thick_stl(f"{base}_solids.stl", thick, unit="m", to_unit=units),
        write_cut_list_csv(f"{base}_cut_list.csv", thick, unit="m", to_unit=units),
        write_cut_list(f"{base}_cut_list.json", thick),
        write_cut_list_pdf(f"{base}_cut_list.pdf", thick, unit="m", to_unit=units),
    ]
    if "3dm" in formats:
        files.append(write_thick_3dm(f"{base}_solids.3dm", thick))
    return files
