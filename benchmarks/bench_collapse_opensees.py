"""The paper's vault to collapse against OpenSees co-rotational shells.

``python benchmarks/bench_collapse_opensees.py [--samples N] [--across K] [--steps S]
[--plot PNG]``: the paper's vault (``examples/paper-vault.toml``, polypropylene 1 mm, its own
weight, the feet pinned) on N samples with K elements across each strip: curvefold's collapse
path (:func:`curvefold.mechanics.collapse`, ULS 1.35 G, span / 300 in the first buckling mode)
and the same structure in OpenSees (``tests/_opensees.py``: ASDShellQ4 co-rotational, K shells
across each ruling quad, on the same nodes, the same imperfect shape, the same weight × 1.35),
followed by displacement control of curvefold's control DOF in S steps to 1.2 times the
displacement curvefold's path reached, or until Newton's method fails even on an eighth of a
step (the shells' limit, or past it).

The defaults, 41 samples and one across (1,148 nodes, 20 steps), are a mesh whose shells fit in
ten minutes here (160 CPU-s; 81 samples would take about twice, not run); the verdict's mesh
(801 samples, 4 across) has 80 times the shells' elements, hours of CPU.

Printed: both curves, λ at the same control displacement and the amplification w / (λ w_lin)
at the same λ (the shells' curve interpolated), the largest λ of each and the CPU seconds of
each; ``--plot`` draws the two curves over each other. The figures of the docs' table
(docs/guide/nonlinear.md) and the mesh they were run on are stated there.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from _bench import SummaryRow, markdown_table, verdict  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
G = 9.80665
SAMPLES, ACROSS, STEPS = 41, 1, 20


def curvefold_path(samples: int, across: int):
    """curvefold's collapse of the paper's vault, the structure, its linear control displacement
    per unit λ about the imperfect shape, the load's factor on the weight, CPU s."""
    from curvefold.app import parse_design
    from curvefold.app._build import build_vault
    from curvefold.mechanics import analyse_load, assess, collapse
    from curvefold.mechanics._collapse import governing_combination
    from curvefold.mechanics._response import static_response

    design = parse_design((ROOT / "examples" / "paper-vault.toml").read_text())
    structure = build_vault(design.overrides(samples=samples)).structure
    t0 = time.process_time()
    result = analyse_load(structure, "polypropylene", 1e-3, across=across)
    verdict_ = assess(result)
    found = collapse(result, verdict_)
    cpu = time.process_time() - t0
    _, forces = governing_combination(result, verdict_)
    model = result.structure.model
    factor = float(-forces[:, 2].sum() / (model.masses.sum() * G))
    imperfect = replace(model, nodes=model.nodes + found.shape)
    static, _ = static_response(imperfect, forces, result.supports.fixed(result.structure))
    linear = float(static.displacements.reshape(-1)[found.path.control])
    return found, result.structure, linear, factor, cpu


def shells_path(sm, found, factor: float, across: int, steps: int):
    """The shells' path (λ, w, w_lin per λ) and its CPU s."""
    sys.path.insert(0, str(ROOT / "tests"))
    import _opensees

    reach = 1.2 * float(np.abs(found.path.control_displacement).max())
    sign = np.sign(found.path.control_displacement[-1]) or -1.0
    t0 = time.process_time()
    out = _opensees.load_path(
        sm,
        (across, 1),
        shift=found.shape,
        factor=factor,
        control=found.path.control,
        increment=sign * reach / steps,
        steps=steps,
    )
    return out, time.process_time() - t0


def compare(found, linear: float, theirs) -> list[list[str]]:
    """Rows: curvefold's λ and w, the shells' λ at that w, the amplification of each at λ."""
    lam_s, w_s, linear_s = theirs
    rows = []
    for lam, w in zip(found.path.factors[1:], found.path.control_displacement[1:], strict=True):
        inside = abs(w) <= np.abs(w_s).max()
        at_w = float(np.interp(abs(w), np.abs(w_s), lam_s)) if inside else float("nan")
        amp = w / (lam * linear)
        amp_s = float(np.interp(lam, lam_s[1:], w_s[1:] / (lam_s[1:] * linear_s)))
        amp_s = amp_s if lam <= lam_s.max() else float("nan")
        rows.append(
            [
                f"{lam:.4g}",
                f"{1e3 * w:.3g}",
                f"{at_w:.4g}",
                f"{lam / at_w - 1:+.2%}",
                f"{amp:.4f}",
                f"{amp_s:.4f}",
                f"{amp / amp_s - 1:+.2%}",
            ]
        )
    return rows


def plot(path: Path, found, theirs, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lam_s, w_s, _ = theirs
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(-1e3 * found.path.control_displacement, found.path.factors, "o-", label="curvefold")
    ax.plot(-1e3 * w_s, lam_s, "s--", label="OpenSees co-rotational shells")
    ax.axhline(found.linear_factor, color="grey", ls=":", label="linear buckling factor")
    ax.set_xlabel("control node's displacement downwards (mm)")
    ax.set_ylabel("load factor on ULS 1.35 G")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(
    samples: int = SAMPLES, across: int = ACROSS, steps: int = STEPS, png: Path | None = None
) -> list[SummaryRow]:
    found, sm, linear, factor, ours_cpu = curvefold_path(samples, across)
    theirs, shells_cpu = shells_path(sm, found, factor, across, steps)
    lam_s, w_s, linear_s = theirs
    print(f"paper's vault, {samples} samples, {across} across, {len(sm.model.nodes)} nodes")
    print(f"curvefold: {found.text()}")
    print(
        f"linear control displacement per λ: curvefold {1e3 * linear:.5g} mm, shells "
        f"{1e3 * linear_s:.5g} mm ({linear_s / linear - 1:+.2%})"
    )
    print(
        markdown_table(
            ["λ", "w (mm)", "shells' λ at w", "difference", "amp.", "shells' amp.", "difference"],
            compare(found, linear, theirs),
        )
    )
    print(
        markdown_table(
            ["", "largest λ", "at w (mm)", "CPU s"],
            [
                [
                    "curvefold",
                    f"{found.path.factors.max():.4g}",
                    f"{1e3 * found.path.control_displacement[found.at_collapse]:.3g}",
                    f"{ours_cpu:.0f}",
                ],
                [
                    "OpenSees shells",
                    f"{lam_s.max():.4g}",
                    f"{1e3 * w_s[int(np.argmax(lam_s))]:.3g}",
                    f"{shells_cpu:.0f}",
                ],
            ],
        )
    )
    print(
        "shells' path (λ, w mm):",
        " ".join(f"({a:.4g}, {1e3 * b:.3g})" for a, b in zip(lam_s, w_s, strict=True)),
    )
    if png is not None:
        plot(png, found, theirs, f"paper's vault, {samples} samples, {across} across")
    return [
        SummaryRow(
            "collapse_opensees",
            f"paper's vault ({samples} samples, {across} across): largest λ, curvefold / shells",
            f"{found.path.factors.max():.4g} / {lam_s.max():.4g}",
            "reported",
            verdict(True),
        ),
        SummaryRow(
            "collapse_opensees",
            "linear control displacement, shells over curvefold − 1",
            f"{linear_s / linear - 1:+.2%}",
            "reported",
            verdict(True),
        ),
    ]


def main() -> None:
    from _bench import summary_table

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=SAMPLES)
    parser.add_argument("--across", type=int, default=ACROSS)
    parser.add_argument("--steps", type=int, default=STEPS)
    parser.add_argument("--plot", type=Path, default=None)
    args = parser.parse_args()
    print(summary_table(run(args.samples, args.across, args.steps, args.plot)))


if __name__ == "__main__":
    main()
