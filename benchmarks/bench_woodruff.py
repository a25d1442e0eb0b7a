"""A creased annulus sector (Woodruff and Filipov 2020): the bar-and-hinge model against
OpenSees shells of the same geometry, linear and to large displacement.

Woodruff and Filipov (2020, Int. J. Solids Struct. 204–205, 114–127) formulate a
bar-and-hinge model for curved-crease origami and study with it a creased annulus sector and
an origami fan. Their figures and the simulation code that accompanies the paper are not
stored anywhere this project can reach (their abstract is), so their numbers are not
compared here; what is reproduced is their example and their kind of study: the sector's
stiffness as the crease is discretised into more segments, against an independent model of
the same sheet, converged in its own mesh.

**Geometry (exact).** A flat annulus sector of radii R₁ < R_c < R₂ and opening Φ, folded
along its circular crease of radius R_c to a fold angle γ: each side is a cone whose apex is
the annulus's centre (its slant distance from the apex is the flat radius ρ, its azimuth
ψ = φ / sin β, β = (π − γ)/2), the inner cone's apex at h = R_c cos β above the crease's
plane, the outer's mirrored below it; the crease is a planar circle of radius R_c sin β.
The two cones are developable and meet along the crease at the fold angle γ everywhere:
an isometric fold of the flat sector (Dias et al. 2012's constant-curvature crease).
Sampled at N + 1 generators, the quads between two generators of a cone are planar
(both generators pass through its apex): the bar-and-hinge model is built on them with
:meth:`BarHingeModel.from_mesh` (``across`` quads on each side of the crease; generators
are rulings, D ℓ / s; the crease a fold of k_c ℓ).

**The shells (independent).** OpenSees ASDShellQ4 (ElasticMembranePlateSection) on the
smooth cones sampled at their own resolution (``--shells``), sharing their nodes within
each side; the crease nodes of the two sides share translations, and a zeroLength element
ties two of their rotations and turns about the crease's tangent with a spring of
k_c times the node's share of the crease. Nothing is taken from curvefold.mechanics but
the material.

**Load.** The generator pair at φ = 0 pinned (every node on it, three translations), a
total load P along the cones' axis on the generators at φ = Φ (shared by length); the
reported displacement is the crease's at φ = Φ along the load. The large-displacement
path: curvefold's :func:`follow_load` against OpenSees co-rotational shells under
displacement control of the same node, the load factors compared at the same
displacements. The crease is locked for the path (k_c = :data:`LOCK` D over the inner
width; one sheet across it in the shells): OpenSees's zeroLength springs keep their axis
fixed in space while the crease turns, and with them the co-rotational shells stiffened
to 0.51 N at 40 mm against the bar-and-hinge model's 0.39 N.

Measured (polypropylene 0.5 mm, radii 0.10, 0.15, 0.20 m, 60° opening, 60° fold; the
record ``docs/guide/woodruff-sector.json``): the linear stiffness converges at second order
in the crease's segments (differences falling by 3.90 from 8 to 16 to 32) and at first order
across (5.8, 2.3, 1.1 % above the shells at 1, 2, 4 across), 1.06 % from the shells' 10.168
N/m (256 × 32; 0.2 % from their 128 × 16). Along the path (128 × 8 against co-rotational
shells 64 × 8) the loads differ by 1.39 % at most at 5 to 30 mm, where the last refinement
of either mesh moved them by 4 to 6 %. About 5 minutes (wall, on a shared machine), most of
it the co-rotational shells.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: A locked crease's stiffness per length, in D over the inner side's width.
LOCK = 1e4


@dataclass(frozen=True)
class Sector:
    """A creased annulus sector: radii (m), opening and fold angle (rad), sheet t (m)."""

    inner: float = 0.10
    crease: float = 0.15
    outer: float = 0.20
    opening: float = np.pi / 3
    fold: float = np.pi / 3
    thickness: float = 5e-4
    material: str = "polypropylene"

    @property
    def beta(self) -> float:
        """The cones' half angle β = (π − γ)/2."""
        return (np.pi - self.fold) / 2

    def point(self, rho: np.ndarray, phi: np.ndarray) -> np.ndarray:
        """The folded position (…, 3) of the flat point at radius ρ and polar angle φ."""
        rho, phi = np.broadcast_arrays(np.asarray(rho, float), np.asarray(phi, float))
        b = self.beta
        h = self.crease * np.cos(b)
        psi = phi / np.sin(b)
        side = np.where(rho <= self.crease, 1.0, -1.0)  # inner cone above, outer below
        return np.stack(
            [
                rho * np.sin(b) * np.cos(psi),
                rho * np.sin(b) * np.sin(psi),
                side * (h - rho * np.cos(b)),
            ],
            axis=-1,
        )

    def radii(self, across: int) -> np.ndarray:
        """The radii of the sample lines: ``across`` intervals on each side of the crease."""
        return np.concatenate(
            [
                np.linspace(self.inner, self.crease, across + 1),
                np.linspace(self.crease, self.outer, across + 1)[1:],
            ]
        )


def sector_mesh(s: Sector, segments: int, across: int = 1):
    """The sector's quads: ``segments`` along the crease, ``across`` on each side; the crease a
    fold, the generators and the lines between the quads' rows rulings."""
    from curvefold import Mesh

    rho = s.radii(across)
    phi = np.linspace(0.0, s.opening, segments + 1)
    R, F = np.meshgrid(rho, phi, indexing="ij")  # (rows, segments + 1)
    x = s.point(R, F).reshape(-1, 3)
    n = segments + 1
    index = np.arange(len(rho) * n).reshape(len(rho), n)
    faces = np.stack(
        [index[:-1, :-1], index[:-1, 1:], index[1:, 1:], index[1:, :-1]], axis=-1
    ).reshape(-1, 4)
    edges, kinds, assignment, angles = [], [], [], []
    degrees = float(np.degrees(s.fold))
    for i in range(len(rho)):  # lines of constant radius
        for j in range(segments):
            edges.append((index[i, j], index[i, j + 1]))
            boundary = i in (0, len(rho) - 1)
            crease = i == across
            kinds.append("boundary" if boundary else "fold" if crease else "ruling")
            assignment.append("B" if boundary else "V" if crease else "F")
            angles.append(degrees if crease else 0.0)
    for j in range(n):  # generators
        for i in range(len(rho) - 1):
            edges.append((index[i, j], index[i + 1, j]))
            boundary = j in (0, segments)
            kinds.append("boundary" if boundary else "ruling")
            assignment.append("B" if boundary else "F")
            angles.append(0.0)
    return Mesh(
        vertices_coords=x,
        edges_vertices=np.array(edges),
        edges_assignment=assignment,
        edges_foldAngle=angles,
        faces_vertices=faces,
        edges_kind=kinds,
        faces_group=np.zeros(len(faces), np.int64),
    )


def _end_loads(rho: np.ndarray) -> np.ndarray:
    """Each sample of an end line's share of a unit load: half the intervals beside it."""
    d = np.diff(rho)
    share = np.zeros(len(rho))
    share[:-1] += d / 2
    share[1:] += d / 2
    return share / share.sum()


def crease_stiffness(s: Sector, locked: bool) -> float:
    """k_c, N·m/rad/m: the material's (D / 1000 t), or :data:`LOCK` D over the inner width."""
    from curvefold.mechanics import MATERIALS

    mat = MATERIALS[s.material]
    if locked:
        return LOCK * mat.bending_stiffness(s.thickness) / (s.crease - s.inner)
    return mat.crease_stiffness(s.thickness)


def bar_hinge(s: Sector, segments: int, across: int = 1, *, locked: bool = False):
    """The bar-and-hinge model, its held DOFs, its unit load (3P,) and the measured DOF."""
    from curvefold.mechanics import MATERIALS, BarHingeModel

    model = BarHingeModel.from_mesh(
        sector_mesh(s, segments, across),
        MATERIALS[s.material],
        s.thickness,
        crease_stiffness=crease_stiffness(s, locked),
    )
    rho = s.radii(across)
    n = segments + 1
    index = np.arange(len(rho) * n).reshape(len(rho), n)
    fixed = np.zeros((len(model.nodes), 3), bool)
    fixed[index[:, 0]] = True
    forces = np.zeros((len(model.nodes), 3))
    forces[index[:, -1], 2] = _end_loads(rho)
    return model, fixed.ravel(), forces.ravel(), 3 * int(index[across, -1]) + 2


def bar_hinge_stiffness(
    s: Sector, segments: int, across: int = 1, *, locked: bool = False
) -> float:
    """P / w: the linear stiffness of the sector under the end load, N/m."""
    import scipy.sparse.linalg as spl

    model, fixed, forces, control = bar_hinge(s, segments, across, locked=locked)
    free = np.flatnonzero(~fixed)
    K = model.stiffness[free][:, free].tocsc()
    u = np.zeros(model.dofs)
    u[free] = spl.spsolve(K, forces[free])
    return 1.0 / u[control]


def shells(s: Sector, along: int, across: int, *, corotational: bool = False, locked: bool = False):
    """Build the OpenSees shell model (module notes); the loaded shell nodes' shares and the
    measured node."""
    import openseespy.opensees as ops

    from curvefold.kernel._arrays import distinct
    from curvefold.mechanics import MATERIALS

    mat = MATERIALS[s.material]
    t = s.thickness
    D = mat.youngs_modulus * t**3 / (12 * (1 - mat.poisson**2))
    k_c = mat.crease_stiffness(t)
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.section("ElasticMembranePlateSection", 1, mat.youngs_modulus, mat.poisson, t, 0.0)
    ops.uniaxialMaterial("Elastic", 1, 1e4 * D)
    phi = np.linspace(0.0, s.opening, along + 1)
    sides = [
        np.linspace(s.inner, s.crease, across + 1),
        np.linspace(s.crease, s.outer, across + 1),
    ]
    tags = []
    tag = 0
    for rho in sides:
        grid = np.zeros((len(rho), len(phi)), np.int64)
        for i, r in enumerate(rho):
            for j, f in enumerate(phi):
                if locked and tags and i == 0:
                    grid[i, j] = tags[0][-1, j]  # one sheet across the crease
                    continue
                tag += 1
                p = s.point(r, f)  # on the crease, both cones' z = 0
                ops.node(tag, *p.tolist())
                grid[i, j] = tag
        tags.append(grid)
    element = 0
    extra = ["-corotational"] if corotational else []
    for grid in tags:
        for i in range(grid.shape[0] - 1):
            for j in range(grid.shape[1] - 1):
                element += 1
                quad = (grid[i, j], grid[i, j + 1], grid[i + 1, j + 1], grid[i + 1, j])
                ops.element("ASDShellQ4", element, *map(int, quad), 1, *extra)
    inner_crease, outer_crease = tags[0][-1], tags[1][0]
    share = np.diff(phi) * s.crease  # flat arc lengths of the crease's segments
    length = np.zeros(len(phi))
    length[:-1] += share / 2
    length[1:] += share / 2
    material = 1
    for j, (a, b) in enumerate(zip(inner_crease, outer_crease, strict=True)):
        if locked:
            break
        ops.equalDOF(int(a), int(b), 1, 2, 3)
        psi = phi[j] / np.sin(s.beta)
        tangent = np.array([-np.sin(psi), np.cos(psi), 0.0])
        radial = np.array([np.cos(psi), np.sin(psi), 0.0])
        material += 1
        ops.uniaxialMaterial("Elastic", material, k_c * length[j])
        element += 1
        ops.element(
            "zeroLength", element, int(a), int(b), "-mat", material, 1, 1,
            "-dir", 4, 5, 6, "-orient", *tangent.tolist(), *radial.tolist(),
        )  # fmt: skip
    for q in distinct(np.concatenate([grid[:, 0] for grid in tags])):
        ops.fix(int(q), 1, 1, 1, 0, 0, 0)
    end = np.concatenate([tags[0][:, -1], tags[1][1:, -1]])
    rho = s.radii(across)
    return end, _end_loads(rho), int(inner_crease[-1])


def shell_stiffness(s: Sector, along: int, across: int, *, locked: bool = False) -> float:
    """P / w of the shell model, linear, N/m."""
    import openseespy.opensees as ops

    end, share, measured = shells(s, along, across, locked=locked)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for q, f in zip(end, share, strict=True):
        ops.load(int(q), 0.0, 0.0, float(f), 0.0, 0.0, 0.0)
    ops.system("UmfPack")
    ops.numberer("RCM")
    ops.constraints("Transformation")
    ops.integrator("LoadControl", 1.0)
    ops.algorithm("Linear")
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees static analysis failed")
    w = ops.nodeDisp(measured, 3)
    ops.wipe()
    return 1.0 / w


def bar_hinge_path(
    s: Sector, segments: int, across: int, displacement: float, *, locked: bool = True
):
    """curvefold's large-displacement path to a displacement w of the measured DOF: (w, P)."""
    from curvefold.mechanics import follow_load

    model, fixed, forces, control = bar_hinge(s, segments, across, locked=locked)
    k = bar_hinge_stiffness(s, segments, across, locked=locked)
    sign = np.sign(displacement)
    path = follow_load(
        model,
        sign * forces,
        fixed,
        steps=400,
        max_factor=1e9,
        first=k * abs(displacement) / 40,
        control=control,
        max_displacement=abs(displacement),
    )
    return path.control_displacement, sign * path.factors


def shell_path(
    s: Sector, along: int, across: int, displacement: float, steps: int = 40, *, locked: bool = True
):
    """OpenSees co-rotational shells under displacement control of the measured node: (w, P)."""
    import openseespy.opensees as ops

    end, share, measured = shells(s, along, across, corotational=True, locked=locked)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for q, f in zip(end, share, strict=True):
        ops.load(int(q), 0.0, 0.0, float(f), 0.0, 0.0, 0.0)
    ops.system("UmfPack")
    ops.numberer("RCM")
    ops.constraints("Transformation")
    ops.test("NormDispIncr", 1e-6 * abs(displacement), 50)
    ops.algorithm("Newton")
    ops.integrator("DisplacementControl", measured, 3, displacement / steps)
    ops.analysis("Static")
    w, load = [0.0], [0.0]
    for _ in range(steps):
        if ops.analyze(1) != 0:
            break  # the states so far are kept
        w.append(ops.nodeDisp(measured, 3))
        load.append(ops.getLoadFactor(1))
    ops.wipe()
    return np.array(w), np.array(load)


#: The linear study: (segments, across) of the bar-and-hinge model; (along, across) of the shells.
SEGMENTS, ACROSS = (4, 8, 16, 32, 64, 128), (1, 2, 4)
SHELLS = ((64, 8), (128, 16), (256, 32))
#: The path: the bar-and-hinge model's mesh, the shells', the end displacement and its steps.
PATH_MODEL, PATH_SHELLS, REACH, PATH_STEPS = (128, 8), (64, 8), 0.03, 6
#: The stated margins: the linear stiffness of the finest bar-and-hinge mesh against the finest
#: shells, and the load of the path at every compared displacement.
LINEAR_MARGIN, PATH_MARGIN = 0.02, 0.02


def run(picture: Path | None = None, record: Path | None = None) -> list:
    """The comparison: tables printed, the picture and the record written; summary rows."""
    from _bench import SummaryRow, markdown_table, verdict

    s = Sector()
    study = {a: [bar_hinge_stiffness(s, n, a) for n in SEGMENTS] for a in ACROSS}
    shell = [shell_stiffness(s, m, a) for m, a in SHELLS]
    finest = shell[-1]
    rows = [
        [f"{n}"] + [f"{study[a][i]:.4f} ({study[a][i] / finest - 1:+.2%})" for a in ACROSS]
        for i, n in enumerate(SEGMENTS)
    ]
    print(markdown_table(["segments N"] + [f"{a} across" for a in ACROSS], rows))
    print(
        markdown_table(
            ["shells (along × across)", "P / w, N/m"],
            [[f"{m} × {a}", f"{k:.4f}"] for (m, a), k in zip(SHELLS, shell, strict=True)],
        )
    )
    w_b, p_b = bar_hinge_path(s, *PATH_MODEL, REACH)
    w_s, p_s = shell_path(s, *PATH_SHELLS, REACH, PATH_STEPS)
    straight = shell_stiffness(s, *PATH_SHELLS, locked=True)  # the path's linear slope
    print(f"crease locked, linear: shells {straight:.4f} N/m")
    ours = np.interp(w_s[1:], w_b, p_b)
    gap = ours / p_s[1:] - 1
    print(
        markdown_table(
            ["w, m", "shells P, N", "bar-and-hinge P, N", "difference"],
            [
                [f"{w:.4f}", f"{p:.5f}", f"{q:.5f}", f"{g:+.2%}"]
                for w, p, q, g in zip(w_s[1:], p_s[1:], ours, gap, strict=True)
            ],
        )
    )
    linear = study[ACROSS[-1]][-1] / finest - 1
    result = {
        "sector": {
            "inner": s.inner, "crease": s.crease, "outer": s.outer, "opening": s.opening,
            "fold": s.fold, "thickness": s.thickness, "material": s.material,
        },
        "segments": list(SEGMENTS),
        "bar_hinge": {str(a): study[a] for a in ACROSS},
        "shells": {f"{m}x{a}": k for (m, a), k in zip(SHELLS, shell, strict=True)},
        "path_bar_hinge": {"w": w_b.tolist(), "P": p_b.tolist()},
        "path_shells": {"w": w_s.tolist(), "P": p_s.tolist()},
        "path_linear": straight,
    }  # fmt: skip
    if record is not None:
        record.write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    if picture is not None:
        draw(result, picture)
    return [
        SummaryRow("woodruff", "sector stiffness: bar-and-hinge against shells",
                   f"{linear:+.2%}", f"≤ {LINEAR_MARGIN:.0%}",
                   verdict(abs(linear) <= LINEAR_MARGIN)),
        SummaryRow("woodruff", "sector path: largest load difference", f"{np.abs(gap).max():.2%}",
                   f"≤ {PATH_MARGIN:.0%}", verdict(np.abs(gap).max() <= PATH_MARGIN)),
    ]  # fmt: skip


def draw(result: dict, picture: Path) -> None:
    """The picture: stiffness against segments, and the two load paths overlaid."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    n = np.array(result["segments"])
    for across, k in result["bar_hinge"].items():
        a.plot(n, k, "o-", label=f"bar and hinge, {across} across")
    finest = list(result["shells"].values())[-1]
    a.axhline(finest, color="k", ls="--", label=f"shells {list(result['shells'])[-1]}")
    a.set_xscale("log", base=2)
    a.set_xlabel("crease segments N")
    a.set_ylabel("P / w, N/m")
    a.set_title("linear stiffness (crease k_c = D / 1000 t)")
    a.legend(fontsize=8)
    wb, pb = result["path_bar_hinge"]["w"], result["path_bar_hinge"]["P"]
    ws, ps = result["path_shells"]["w"], result["path_shells"]["P"]
    b.plot(np.array(wb) * 1e3, pb, "-", label="bar and hinge (follow_load)")
    b.plot(np.array(ws) * 1e3, ps, "s", label="OpenSees co-rotational shells")
    slope = result["path_linear"]
    b.plot(np.array(ws) * 1e3, slope * np.array(ws), ":", color="gray", label="linear (shells)")
    b.set_xlabel("end displacement w, mm")
    b.set_ylabel("end load P, N")
    b.set_title("large displacement (crease locked)")
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(picture, dpi=110)
    plt.close(fig)


def main() -> None:
    from _bench import summary_table

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--picture", type=Path, help="write the picture (PNG) here")
    parser.add_argument("--record", type=Path, help="write the figures (JSON) here")
    args = parser.parse_args()
    print(summary_table(run(args.picture, args.record)))


if __name__ == "__main__":
    sys.exit(main())
