"""The paper's "virtual thickness", measured: its vault of thin sheets against a plain barrel shell
of the same mass and span, and against thick-panel versions of the vault.

- the vault: ``curvefold load --across 4 --json`` as a user runs it (the paper's design,
  polypropylene 1 mm): its weight, deflection under its own weight, the linear buckling
  factor of its own weight, and again with ``--no-self-weight --point-load P`` for the
  deflection under a point load at the apex; its stiffness is P over that deflection;
- thick-panel vaults: ``curvefold load --panels 16 --material plywood --thickness T
  --across 4`` for a few T, the same figures;
- a plain shell: a cylinder whose directrix is the vault's middle crease curve seen along the
  vault's depth (its span and rise), extruded over the vault's depth, pinned along its feet,
  free at its ends, of the vault's material and of the thickness that gives it the vault's
  mass; modelled by the project's bar-and-hinge model on a quad mesh (every inner edge a
  bending hinge, every quad a membrane and a twist hinge), converged over three meshes
  (Richardson's estimate of the error of the finest), and checked against OpenSees shells
  (ASDShellQ4) on the finest mesh and, on a plate strip, against 5 q L⁴ / 384 D;
- the equivalent thickness: the plain shell's thickness whose point-load stiffness is the
  vault's (found by root finding on log t).

``python benchmarks/virtual_thickness.py [--json FILE] [--markdown FILE]`` prints the table and
writes the figures (``docs/guide/virtual-thickness.json`` records a run, quoted in
``docs/guide/thickness.md``); ``run()`` gives run_all.py its summary rows. About 2 CPU-minutes.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
G = 9.80665
#: The point load at the apex, N (the analysis is linear: the stiffness does not depend on it).
POINT = 10.0
#: Plywood thicknesses of the thick-panel vaults, m (0.01 needs tapered panels).
PLYWOOD = (0.004, 0.008, 0.01)
#: Shell meshes: quads along the arch × across the depth, each twice the last.
MESHES = ((48, 12), (96, 24), (192, 48))


# -- the vaults, as ``curvefold load`` builds them ---------------------------------------------
def load_json(args: list[str]) -> dict:
    """``curvefold load ARGS --json`` in a child process, as a user runs it."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    out = subprocess.run(
        [sys.executable, "-m", "curvefold", "load", *args, "--json"],
        capture_output=True,
        text=True,
        check=False,
        env=env,
    )
    if out.returncode not in (0, 1):
        raise RuntimeError(out.stderr)
    return json.loads(out.stdout)


def vault_figures(args: list[str]) -> dict:
    """Mass, deflections, stiffness and buckling factor of ``curvefold load ARGS``."""
    weight = load_json(args)
    point = load_json([*args, "--no-self-weight", "--point-load", str(POINT)])
    return figures(
        mass=weight["total_weight"] / G,
        deflection=weight["max_displacement"],
        point_deflection=point["max_displacement"],
        buckling=weight["buckling_factor"],
        error=max(weight["errors"]["max_displacement"], point["errors"]["max_displacement"]),
    )


def figures(
    mass: float, deflection: float, point_deflection: float, buckling: float, error: float
) -> dict:
    """One row's figures: stiffness = POINT / point deflection, and per kilogram."""
    stiffness = POINT / point_deflection
    return {
        "mass": mass,
        "deflection": deflection,
        "point_deflection": point_deflection,
        "stiffness": stiffness,
        "stiffness_per_mass": stiffness / mass,
        "buckling_factor": buckling,
        "error": error,
    }


# -- the plain shell ---------------------------------------------------------------------------
def arch(samples: int = 801) -> tuple[np.ndarray, float]:
    """The vault's arch: its middle crease curve seen along its depth ((N, 2): y from its first
    foot, z), and its depth (the extent of its feet along x)."""
    from curvefold.vault import Vault

    x = np.asarray(Vault.from_design(samples=samples).structure.state().vertices)
    middle = x[len(x) // 2]
    profile = np.column_stack([middle[:, 1] - middle[0, 1], middle[:, 2]])
    feet = x[:, 0, 0]
    return profile, float(feet.max() - feet.min())


def arch_size(profile: np.ndarray) -> tuple[float, float, float]:
    """Span (between the feet), rise and length of an arch profile."""
    length = float(np.linalg.norm(np.diff(profile, axis=0), axis=1).sum())
    return float(profile[-1, 0] - profile[0, 0]), float(profile[:, 1].max()), length


def barrel(profile: np.ndarray, depth: float, along: int, across: int):
    """A quad mesh of the cylinder of directrix ``profile`` (y, z) extruded along x over
    ``depth``: ``along`` quads along the arch (equal arc lengths) × ``across`` over the depth.
    Inner edges bend (kind ``ruling``); the rim is ``boundary``."""
    from curvefold import Mesh

    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(profile, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], along + 1)
    yz = np.column_stack([np.interp(t, s, profile[:, 0]), np.interp(t, s, profile[:, 1])])
    yz[:, 1] = np.where(np.abs(yz[:, 1]) < 1e-12, 0.0, yz[:, 1])
    xs = np.linspace(0.0, depth, across + 1)
    node = np.arange((along + 1) * (across + 1)).reshape(along + 1, across + 1)
    coords = np.array([[x, y, z] for (y, z) in yz for x in xs])
    faces = np.array(
        [
            [node[i, j], node[i + 1, j], node[i + 1, j + 1], node[i, j + 1]]
            for i in range(along)
            for j in range(across)
        ]
    )
    edges, kinds = [], []
    for i in range(along + 1):
        for j in range(across + 1):
            if i < along:
                edges.append([node[i, j], node[i + 1, j]])
                kinds.append("boundary" if j in (0, across) else "ruling")
            if j < across:
                edges.append([node[i, j], node[i, j + 1]])
                kinds.append("boundary" if i in (0, along) else "ruling")
    return Mesh(
        vertices_coords=coords,
        edges_vertices=np.array(edges),
        edges_assignment=["B" if k == "boundary" else "F" for k in kinds],
        edges_foldAngle=[0.0] * len(edges),
        faces_vertices=faces,
        edges_kind=kinds,
        faces_group=[0] * len(faces),
    )


def shell_response(mesh, material, thickness: float, *, point_at=None) -> dict:
    """The bar-and-hinge model of a plain sheet pinned where z = 0: mass, deflection under its
    own weight, buckling factor of its own weight, deflection under POINT at the node nearest
    ``point_at`` (default the highest node nearest the middle of the depth)."""
    from curvefold.mechanics import BarHingeModel, buckling, static_response

    model = BarHingeModel.from_mesh(mesh, material, thickness, crease_stiffness=0.0)
    x = model.nodes
    fixed = np.repeat((np.abs(x[:, 2]) <= 1e-9 * model.size)[:, None], 3, axis=1)
    weight = np.zeros_like(x)
    weight[:, 2] = -model.masses * G
    result, factor = static_response(model, weight, fixed)
    if point_at is None:
        top = x[:, 2] >= x[:, 2].max() - 1e-9 * model.size
        middle = 0.5 * (x[:, 0].min() + x[:, 0].max())
        candidates = np.flatnonzero(top)
        where = int(candidates[np.argmin(np.abs(x[candidates, 0] - middle))])
    else:
        where = int(np.argmin(np.linalg.norm(x - np.asarray(point_at), axis=1)))
    point = np.zeros_like(x)
    point[where, 2] = -POINT
    at_point, _ = static_response(model, point, fixed, factor=factor)
    return {
        "mass": float(model.masses.sum()),
        "deflection": result.max_displacement,
        "point_deflection": at_point.max_displacement,
        "buckling_factor": buckling(model, result, factor).factor,
        "node": where,
    }


def richardson(values) -> tuple[float, float, float]:
    """The limit of a figure on three meshes each twice as fine (h, h/2, h/4), its observed
    order p (held to [1, 4]) and the relative error of the finest mesh's figure."""
    f1, f2, f3 = (float(v) for v in values)
    ratio = abs(f1 - f2) / max(abs(f2 - f3), 1e-300)
    order = float(np.clip(np.log2(ratio), 1.0, 4.0)) if ratio > 0 else 4.0
    limit = f3 + (f3 - f2) / (2.0**order - 1.0)
    return limit, order, abs(f3 - limit) / abs(limit)


def converged_shell(profile, depth, material, thickness, meshes=MESHES) -> dict:
    """The plain shell on each mesh, each figure's Richardson limit, order and the finest mesh's
    error."""
    runs = [shell_response(barrel(profile, depth, *m), material, thickness) for m in meshes]
    out: dict = {"meshes": [list(m) for m in meshes], "runs": runs, "errors": {}, "orders": {}}
    for key in ("deflection", "point_deflection", "buckling_factor"):
        _, order, error = richardson([r[key] for r in runs])
        out["errors"][key], out["orders"][key] = error, order
    out["figures"] = figures(
        mass=runs[-1]["mass"],
        deflection=runs[-1]["deflection"],
        point_deflection=runs[-1]["point_deflection"],
        buckling=runs[-1]["buckling_factor"],
        error=max(out["errors"].values()),
    )
    return out


def equivalent_thickness(profile, depth, material, stiffness: float, mesh) -> float:
    """The plain shell's thickness whose point-load stiffness is ``stiffness`` (N/m)."""
    from scipy.optimize import brentq

    sheet = barrel(profile, depth, *mesh)

    def gap(log_t: float) -> float:
        r = shell_response(sheet, material, float(np.exp(log_t)))
        return float(np.log(POINT / r["point_deflection"]) - np.log(stiffness))

    return float(np.exp(brentq(gap, np.log(1e-5), np.log(0.2), xtol=1e-6)))


def plate_strip(
    material, thickness: float, span: float, depth: float, along: int, across: int
) -> tuple[float, float]:
    """A flat strip pinned on its edges y = 0 and y = span under its own weight: the bar-and-
    hinge deflection at mid-span and the closed form 5 q L⁴ / 384 D (q its weight per area)."""
    profile = np.column_stack([np.linspace(0.0, span, 3), np.zeros(3)])
    mesh = barrel(profile, depth, along, across)
    q = material.density * thickness * G
    closed = 5.0 * q * span**4 / (384.0 * material.bending_stiffness(thickness))
    return shell_response_flat(mesh, material, thickness), closed


def shell_response_flat(mesh, material, thickness: float) -> float:
    """Mid-span deflection of a flat sheet in z = 0 pinned on its edges y = min and y = max under
    its own weight (downward, −z)."""
    from curvefold.mechanics import BarHingeModel, static_response

    model = BarHingeModel.from_mesh(mesh, material, thickness, crease_stiffness=0.0)
    x = model.nodes
    tol = 1e-9 * model.size
    edge = (np.abs(x[:, 1] - x[:, 1].min()) <= tol) | (np.abs(x[:, 1] - x[:, 1].max()) <= tol)
    fixed = np.repeat(edge[:, None], 3, axis=1)
    weight = np.zeros_like(x)
    weight[:, 2] = -model.masses * G
    result, _ = static_response(model, weight, fixed)
    return float(-result.displacements[:, 2].min())


# -- OpenSees shells of the same mesh ----------------------------------------------------------
def opensees_barrel(mesh, material, thickness: float, node: int) -> tuple[float, float]:
    """Max deflection of ASDShellQ4 shells on ``mesh`` (pinned where z = 0) under their own
    weight (lumped a quarter of each element's to its corners) and under POINT at ``node``."""
    import openseespy.opensees as ops

    x = np.asarray(mesh.vertices_coords)
    faces = np.asarray(mesh.faces_vertices)
    size = float(np.ptp(x, axis=0).max())
    out = []
    for case in ("weight", "point"):
        ops.wipe()
        ops.model("basic", "-ndm", 3, "-ndf", 6)
        ops.section(
            "ElasticMembranePlateSection",
            1,
            material.youngs_modulus,
            material.poisson,
            thickness,
            material.density,
        )
        for i, p in enumerate(x):
            ops.node(i + 1, *p.tolist())
            if abs(p[2]) <= 1e-9 * size:
                ops.fix(i + 1, 1, 1, 1, 0, 0, 0)
        load = np.zeros(len(x))
        for e, f in enumerate(faces):
            ops.element("ASDShellQ4", e + 1, *(f + 1).tolist(), 1)
            p = x[f]
            area = 0.5 * np.linalg.norm(
                np.cross(p[2] - p[0], p[3] - p[1])
            )  # a planar or near-planar quad's area
            load[f] += material.density * thickness * area * G / 4.0
        if case == "point":
            load[:] = 0.0
            load[node] = POINT
        ops.timeSeries("Linear", 1)
        ops.pattern("Plain", 1, 1)
        for i, w in enumerate(load):
            if w:
                ops.load(i + 1, 0.0, 0.0, -w, 0.0, 0.0, 0.0)
        ops.system("UmfPack")
        ops.numberer("RCM")
        ops.constraints("Plain")
        ops.integrator("LoadControl", 1.0)
        ops.algorithm("Linear")
        ops.analysis("Static")
        if ops.analyze(1) != 0:
            raise RuntimeError("OpenSees static analysis failed")
        u = np.array([ops.nodeDisp(i + 1)[:3] for i in range(len(x))])
        out.append(float(np.linalg.norm(u, axis=1).max()))
    ops.wipe()
    return out[0], out[1]


# -- the comparison ----------------------------------------------------------------------------
def measure(
    plywood=PLYWOOD, meshes=MESHES, extra=("--across", "4"), *, thin_panels=True, opensees=True
) -> dict:
    """Every row's figures, the shell's convergence and checks, JSON-ready; ``extra``, the
    arguments of every ``curvefold load`` (a reduced case: fewer samples, fewer across);
    ``thin_panels``, a row for the panel vault of the thin sheet too."""
    from curvefold.mechanics import MATERIALS

    pp = MATERIALS["polypropylene"]
    vault = vault_figures(list(extra))
    profile, depth = arch()
    span, rise, length = arch_size(profile)
    t_mass = vault["mass"] / (pp.density * length * depth)
    shell = converged_shell(profile, depth, pp, t_mass, meshes)
    t_stiff = equivalent_thickness(profile, depth, pp, vault["stiffness"], meshes[-1])
    stiff = converged_shell(profile, depth, pp, t_stiff, meshes)
    rows = [
        {"structure": "the paper's vault of thin sheets", "sheet": "polypropylene 1 mm", **vault},
        {
            "structure": "plain barrel shell, the vault's mass",
            "sheet": f"polypropylene {t_mass * 1e3:.2f} mm",
            **shell["figures"],
        },
        {
            "structure": "plain barrel shell, the vault's stiffness",
            "sheet": f"polypropylene {t_stiff * 1e3:.1f} mm",
            **stiff["figures"],
        },
    ]
    thin = [("polypropylene", 0.001)] if thin_panels else []
    for name, t in thin + [("plywood", t) for t in plywood]:
        args = ["--panels", "16", "--material", name, "--thickness", str(t), *extra]
        rows.append(
            {
                "structure": "the vault of 16 panels per crease",
                "sheet": f"{name} {t * 1e3:g} mm",
                **vault_figures(args),
            }
        )
    panels = rows[3 + len(thin) :]
    out = {
        "point_load": POINT,
        "arch": {"span": span, "rise": rise, "length": length, "depth": depth},
        "mass_thickness": t_mass,
        "stiffness_thickness": t_stiff,
        # a plain shell bending: λ ∝ t², so the thickness of the vault's buckling factor
        "buckling_thickness": t_mass
        * np.sqrt(vault["buckling_factor"] / rows[1]["buckling_factor"]),
        # stiffness ∝ t^n: the plain shell between its two thicknesses, the plywood panel vaults
        "shell_exponent": exponent(rows[1], rows[2], t_mass, t_stiff),
        "panel_exponent": exponent(panels[0], panels[-1], plywood[0], plywood[-1]),
        "rows": rows,
        "shell_convergence": {k: shell[k] for k in ("meshes", "errors", "orders")},
        "stiff_shell_convergence": {k: stiff[k] for k in ("meshes", "errors", "orders")},
        "plate_strip": dict(
            zip(
                ("deflection", "closed_form"),
                plate_strip(pp, t_mass, span, depth, meshes[-1][0], meshes[-1][1]),
            )
        ),
    }
    if opensees:
        node = shell["runs"][-2]["node"]
        theirs = opensees_barrel(barrel(profile, depth, *meshes[-2]), pp, t_mass, node)
        ours = shell["runs"][-2]
        out["opensees"] = {
            "mesh": list(meshes[-2]),
            "deflection": [ours["deflection"], theirs[0]],
            "point_deflection": [ours["point_deflection"], theirs[1]],
        }
    return out


def exponent(a: dict, b: dict, ta: float, tb: float) -> float:
    """n in stiffness ∝ tⁿ between two rows of thicknesses ta and tb."""
    return float(np.log(b["stiffness"] / a["stiffness"]) / np.log(tb / ta))


def table(result: dict) -> str:
    """The Markdown table of :func:`measure`'s rows."""
    from _bench import markdown_table

    cells = [
        [
            r["structure"],
            r["sheet"],
            f"{r['mass']:.2f}",
            f"{r['deflection'] * 1e3:.3g}",
            f"{r['stiffness'] / 1e3:.3g}",
            f"{r['stiffness_per_mass'] / 1e3:.3g}",
            f"{r['buckling_factor']:.3g}",
            f"{r['error']:.1%}",
        ]
        for r in result["rows"]
    ]
    return markdown_table(
        [
            "structure",
            "sheet",
            "mass (kg)",
            "deflection, own weight (mm)",
            f"stiffness, {result['point_load']:g} N at the apex (kN/m)",
            "stiffness per mass (kN/m/kg)",
            "buckling factor, own weight",
            "error (deflections)",
        ],
        cells,
    )


def run() -> list:
    """The figures, printed, and run_all.py's summary rows."""
    from _bench import SummaryRow, verdict

    result = measure()
    print(table(result))
    rows = result["rows"]
    vault, shell = rows[0], rows[1]
    ratio = vault["stiffness"] / shell["stiffness"]
    ordered = vault["buckling_factor"] > shell["buckling_factor"]
    strip = result["plate_strip"]
    strip_error = abs(strip["deflection"] / strip["closed_form"] - 1)
    o = result["opensees"]
    apart = max(abs(a / b - 1) for a, b in (o["deflection"], o["point_deflection"]))
    return [
        SummaryRow(
            "virtual_thickness",
            "vault vs plain shell of its mass: stiffness",
            f"{ratio:.0f}× (equivalent shell {result['stiffness_thickness'] * 1e3:.1f} mm)",
            "> 1, buckling factor above the shell's",
            verdict(ratio > 1 and ordered),
        ),
        SummaryRow(
            "virtual_thickness",
            "shell model: plate strip vs 5qL⁴/384D; OpenSees",
            f"{strip_error:.1e}; {apart:.1%}",
            "≤ 1e-3; ≤ 5 %",
            verdict(strip_error <= 1e-3 and apart <= 0.05),
        ),
    ]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, help="write the figures as JSON here")
    parser.add_argument("--markdown", type=Path, help="write the table as Markdown here")
    args = parser.parse_args(argv)
    result = measure()
    text = table(result)
    print(text)
    print(json.dumps({k: v for k, v in result.items() if k != "rows"}, indent=1))
    if args.json:
        args.json.write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    if args.markdown:
        args.markdown.write_text(text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
