"""MERLIN's published Miura-ori examples under GNU Octave against curvefold's path following on the
same model.

MERLIN (Liu and Paulino 2017, the code of their Proc. R. Soc. A paper) is public MATLAB
code; it is not part of curvefold. Give its folder (the one holding ``PathAnalysis.m``) with
``--merlin DIR`` or ``CURVEFOLD_MERLIN``; ``octave-cli`` must be on the path. For each
example, ``merlin/merlin_case.m`` builds the structure with MERLIN's own functions
(``ConfigMiura``, ``PrepareData``) and follows it with MERLIN's ``PathAnalysis`` (MGDCM,
its bars Ogden's law, its springs linear within their limits), then saves the model it
assembled and its load path. curvefold builds a :class:`BarHingeModel` of the same nodes,
bars (EA/L = C0 A / L), hinges (k = k_p L, MERLIN's ``EnhancedLinear`` within its limits)
and supports, and follows the same load with :func:`follow_load` from the same first load
factor, to the same control displacement.

The examples: a 5 × 5 Miura-ori sheet bent by two point loads (bending), one pulled
along its length (folding), and one whose vertex is pushed through (bistable, a
snap-through with a snap-back in the pushed displacement; its springs stiffen outside
[45°, 315°] in MERLIN's convention, which its folds, within 69° of flat, never reach).

At every state of MERLIN's path, curvefold's load factor at the same control displacement
(its equilibrium there, solved with the control DOF held, started from MERLIN's state so
that the branch is MERLIN's) is compared with MERLIN's, relative to the largest load factor
of the path. Holding the displacement is singular where the path turns back in it: a
state there is counted, not compared. The two differ by (a) the bars' law, Ogden's
(α = 5, 1) against St Venant–Kirchhoff, equal to second order in the strain; (b) MERLIN's
tolerance (a displacement correction below 1e-6). Measured: folding (strains below 1e-4)
4e-10 at most; bistable 1.2e-6 in the median, 1.7e-4 next to a turning point of the
displacement (one state at it); bending 5e-9 in the median, growing
with the largest bar strain to 1.5e-5 at 1.8 % and 2.1e-3 at 7.3 % (its last state): the
laws' difference. To tell, :func:`ogden_residual` puts MERLIN's states into curvefold's
model with Ogden's bars: bending's are in equilibrium to 4.7e-7 of the load (2.2e-3 with
curvefold's own bars), folding's to 7.7e-5 (MERLIN stops at a correction of 1e-6 m, which
its bars of EA/L = 5e4 N/m turn into that residual).

Targets (issue 46): curves within 1 %; curvefold at least 10× faster than MERLIN under
Octave (CPU seconds of the path following alone, each in its own process, one BLAS thread).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from _bench import SummaryRow, markdown_table, verdict  # noqa: E402

HERE = Path(__file__).resolve().parent
CASES = ("bending", "folding", "bistable")
AGREEMENT = 0.01
SPEEDUP = 10.0


def merlin_path(merlin: Path, case: str, out: Path) -> dict:
    """Run MERLIN's example under Octave; the saved model and path, as arrays."""
    import scipy.io

    command = f"merlin_case('{merlin}', '{case}', '{out}')"
    subprocess.run(
        ["octave-cli", "--no-gui", "--eval", command],
        cwd=HERE / "merlin",
        check=True,
        capture_output=True,
    )
    return {k: v for k, v in scipy.io.loadmat(out).items() if not k.startswith("__")}


def curvefold_path(data: dict, first_scale: float = 1.0):
    """The same model and load with curvefold; the model, path and CPU seconds."""
    from curvefold.mechanics import BarHingeModel, follow_load

    nodes = data["nodes"]
    lengths = data["lengths"].ravel()
    hinges = np.concatenate([data["bend"], data["fold"]]).astype(np.int64) - 1
    stiffness = np.concatenate([data["kpb"].ravel(), data["kpf"].ravel()]) * lengths[: len(hinges)]
    model = BarHingeModel(
        nodes,
        data["bars"].astype(np.int64) - 1,
        float(data["C0"].item()) * data["area"].ravel() / lengths,
        hinges,
        stiffness,
        np.ones(len(nodes)),
    )
    fixed = np.zeros(model.dofs, bool)
    fixed[data["fixed"].astype(np.int64).ravel() - 1] = True
    control = int(data["control"].item()) - 1
    t0 = time.process_time()
    path = follow_load(
        model,
        data["F"].ravel(),
        fixed,
        steps=5000,
        max_factor=1e9,
        first=first_scale * float(data["blam"].item()),
        control=control,
        max_displacement=float(np.abs(data["U_his"][control]).max()),
    )
    return model, path, time.process_time() - t0


def at_control(model, forces, fixed, control: int, states: np.ndarray, factors: np.ndarray):
    """curvefold's load factor at the control displacement of each of MERLIN's states: its
    equilibrium there (Newton's method on (u, λ) with the control DOF held, to 1e-10 of the
    load; no interpolation), started from MERLIN's state itself (u (3P, n), λ (n,)), so that
    where the path turns back in displacement (a snap-back) the branch is MERLIN's. NaN where
    Newton's method does not converge (at a turning point of the displacement, where holding
    it is singular)."""
    import scipy.sparse.linalg as spl

    from curvefold.mechanics._nonlinear import internal_forces, tangent

    free = np.flatnonzero(~fixed)
    F = forces[free]
    c = int(np.flatnonzero(free == control)[0])
    scale = np.abs(states[control]).max() or 1.0
    out = []
    for u, lam in zip(states.T.copy(), factors, strict=True):
        target = u[control]
        for _ in range(30):
            r = lam * F - internal_forces(model, u)[free]
            if abs(u[control] - target) < 1e-12 * scale and np.linalg.norm(r) < 1e-10 * max(
                np.linalg.norm(lam * F), np.linalg.norm(F)
            ):
                break
            lu = spl.splu(tangent(model, u)[free][:, free].tocsc())
            ur, uf = lu.solve(r), lu.solve(F)
            step = (target - u[control] - ur[c]) / uf[c]
            u[free] += ur + step * uf
            lam += step
            if np.abs(ur + step * uf).max() < 1e-12 * scale:
                break  # a correction at rounding (stiff bars round the residual above 1e-10)
        else:
            lam = np.nan
        out.append(lam)
    return np.array(out)


def compare(data: dict, model) -> np.ndarray:
    """|λ_curvefold − λ_MERLIN| / max |λ_MERLIN| at every state of MERLIN's path."""
    control = int(data["control"].item()) - 1
    fixed = np.zeros(model.dofs, bool)
    fixed[data["fixed"].astype(np.int64).ravel() - 1] = True
    lam = data["LF_his"].ravel()
    ours = at_control(model, data["F"].ravel(), fixed, control, data["U_his"], lam)
    return np.abs(ours - lam) / np.abs(lam).max()


def ogden_residual(data: dict, model) -> np.ndarray:
    """How far MERLIN's states are from equilibrium in curvefold's model with MERLIN's own bar
    law: ‖λ f − f_int(u)‖ / ‖λ f‖ on the free DOFs at every state, the hinges curvefold's and
    the bars Ogden's (α = 5, 1; second Piola–Kirchhoff stress
    C0 (p³ − p⁻¹) / 4 at the stretch p). Rounding and MERLIN's tolerance only, if the two
    codes' hinges and bars are the same elements."""
    from dataclasses import replace

    from curvefold.mechanics._nonlinear import elongations, internal_forces

    hinges = replace(model, bar_stiffness=np.zeros(len(model.bars)))
    L = data["lengths"].ravel()
    area, c0 = data["area"].ravel(), float(data["C0"].item())
    free = np.flatnonzero(~np.isin(np.arange(model.dofs), data["fixed"].astype(int).ravel() - 1))
    F = data["F"].ravel()
    out = []
    for u, lam in zip(data["U_his"].T, data["LF_his"].ravel(), strict=True):
        stretch = np.sqrt(2 * elongations(model, u) / L + 1)
        force = area * c0 / 4 * (stretch**3 - 1 / stretch)  # A times the PK2 stress
        x = model.nodes + u.reshape(-1, 3)
        d = (x[model.bars[:, 1]] - x[model.bars[:, 0]]) * (force / L)[:, None]
        f = internal_forces(hinges, u).reshape(-1, 3)
        np.add.at(f, model.bars[:, 1], d)
        np.add.at(f, model.bars[:, 0], -d)
        r = (lam * F - f.ravel())[free]
        out.append(np.linalg.norm(r) / np.linalg.norm(lam * F[free]))
    return np.array(out)


def run(merlin: Path | None = None, picture: Path | None = None) -> list[SummaryRow]:
    merlin = merlin or (
        Path(os.environ["CURVEFOLD_MERLIN"]) if "CURVEFOLD_MERLIN" in os.environ else None
    )
    if (
        shutil.which("octave-cli") is None
        or merlin is None
        or not (merlin / "PathAnalysis.m").exists()
    ):
        why = (
            "octave-cli is not installed"
            if shutil.which("octave-cli") is None
            else ("MERLIN's folder was not given (--merlin DIR or CURVEFOLD_MERLIN)")
        )
        print(f"merlin: skipped, {why}")
        return [SummaryRow("merlin", "comparison", "skipped", why, "skipped")]
    rows, summary, curves = [], [], {}
    with tempfile.TemporaryDirectory() as tmp:
        for case in CASES:
            data = merlin_path(merlin, case, Path(tmp) / f"{case}.mat")
            model, path, cpu = curvefold_path(data)
            error = compare(data, model)
            control = int(data["control"].item()) - 1
            curves[case] = (
                (data["U_his"][control], data["LF_his"].ravel()),
                (path.displacements.reshape(len(path.factors), -1)[:, control], path.factors),
                float(np.nanmax(error)),
            )
            theirs = float(data["cpu"].item())
            rows.append(
                [
                    f"Miura {case}",
                    f"{model.dofs}",
                    f"{len(data['LF_his'].ravel())}, {len(path.factors) - 1}",
                    f"{np.nanmax(error):.2e} (state {int(np.nanargmax(error)) + 1})"
                    + (
                        f"; {np.isnan(error).sum()} at a turning point"
                        if np.isnan(error).any()
                        else ""
                    ),
                    f"{np.nanmedian(error):.1e}",
                    f"{ogden_residual(data, model).max():.1e}",
                    f"{theirs:.2f}",
                    f"{cpu:.2f}",
                    f"{theirs / cpu:.1f}×",
                ]
            )
            summary += [
                SummaryRow("merlin", f"Miura {case}: largest difference", f"{np.nanmax(error):.1e}",
                           f"≤ {AGREEMENT:.0%}", verdict(np.nanmax(error) <= AGREEMENT)),
                SummaryRow("merlin", f"Miura {case}: speed-up", f"{theirs / cpu:.1f}×",
                           f"≥ {SPEEDUP:.0f}×", verdict(theirs / cpu >= SPEEDUP)),
            ]  # fmt: skip
    if picture is not None:
        draw(curves, picture)
    print(
        markdown_table(
            [
                "example",
                "DOFs",
                "states (MERLIN, ours)",
                "largest difference of λ",
                "median",
                "MERLIN's states, Ogden bars: residual",
                "MERLIN CPU-s",
                "ours CPU-s",
                "speed-up",
            ],
            rows,
        )
    )
    return summary


def draw(curves: dict, picture: Path) -> None:
    """The overlaid curves: MERLIN's states as dots on curvefold's path, one panel a case."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(curves), figsize=(4 * len(curves), 3.6))
    for ax, (case, (theirs, ours, error)) in zip(np.atleast_1d(axes), curves.items(), strict=True):
        ax.plot(np.abs(ours[0]), ours[1], "-", lw=1.5, label="curvefold (follow_load)")
        ax.plot(np.abs(theirs[0]), theirs[1], "o", ms=3, mfc="none",
                label="MERLIN under Octave")  # fmt: skip
        ax.set_title(f"Miura {case}: largest difference {error:.1e}", fontsize=9)
        ax.set_xlabel("|control displacement| (MERLIN's length unit)")
        ax.set_ylabel("load factor λ")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(picture, dpi=110)
    plt.close(fig)


def main() -> None:
    from _bench import summary_table

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--merlin", type=Path, help="the folder of MERLIN's code")
    parser.add_argument("--picture", type=Path, help="write the overlaid curves (PNG) here")
    args = parser.parse_args()
    print(summary_table(run(args.merlin, args.picture)))


if __name__ == "__main__":
    sys.exit(main())
