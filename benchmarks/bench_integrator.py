"""SpaceCurve.from_curvature against scipy's solve_ivp (DOP853) and a compiled Magnus-6 loop.

Curve: κ = 1 + 0.5 sin s, τ = 0.3 cos 2s, L = 20, start frame the identity at the origin.
The contenders produce the same thing, the position and the frame T, N, B (12 unknowns)
at N + 1 uniform samples, N = 1e3 … 1e6 (N + 1 so that the grids nest and one reference
serves them all):

- ours: ``SpaceCurve.from_curvature(kappa, tau, L, samples=N + 1)``;
- solve_ivp: DOP853, rtol = atol = 1e-12, ``t_eval`` = the same samples;
- compiled: ``magnus6.c``, built now with the machine's C compiler (``_compiled.py``): κ and τ
  evaluated by NumPy at the three Gauss nodes of every sample interval, then one Magnus-6
  step per interval in a C loop (quaternion and position, normalised every step);
- write floor: allocating the output (12 doubles per sample: 96 MB at N = 1e6) and writing
  it once, what no integrator can go below.

Times are CPU seconds of this process (steadier than wall time on a shared machine),
best of k interleaved rounds.

Errors are measured against two references that share no code:

- fine: our integrator at 8× finer sampling than the largest N (every grid is a subset);
- DOP853: solve_ivp at rtol = atol = 1e-14 (scipy raises rtol to 100 ε ≈ 2.2e-14) at the
  1001 samples every grid contains.

Their mutual agreement is printed; a contender's error is the larger of its errors against
the two (the fine one at every sample, the DOP853 one at the common samples).

Targets: error ≤ 1e-12 at every N; ≥ 3× faster than solve_ivp at every N; within 2× of
the compiled loop from N = 1e4.
"""

from __future__ import annotations

import math
import os
import warnings

import numpy as np
from _bench import (
    CPU,
    SummaryRow,
    best_of_interleaved,
    choose_repeats,
    markdown_table,
    ms,
    summary_table,
    timed,
    verdict,
)
from _compiled import CompiledMagnus6
from scipy.integrate import solve_ivp

from curvefold import SpaceCurve

LENGTH = 20.0
N_VALUES = (10**3, 10**4, 10**5, 10**6)
REFINE = 8
COMMON = 1000  # intervals of the grid every N contains
ERROR_TARGET = 1e-12
SPEEDUP = 3.0  # ivp / ours at every N
COMPILED_FROM, COMPILED_WITHIN = 10**4, 2.0  # ours / compiled from this N
BUDGET_PER_N = 12.0  # seconds of timing rounds per N


def kappa(s: np.ndarray) -> np.ndarray:
    return 1.0 + 0.5 * np.sin(s)


def tau(s: np.ndarray) -> np.ndarray:
    return 0.3 * np.cos(2.0 * s)


def frenet_rhs(s: float, y: np.ndarray) -> np.ndarray:
    """y = (x, T, N, B): x' = T, T' = κN, N' = −κT + τB, B' = −τN."""
    k, t = 1.0 + 0.5 * math.sin(s), 0.3 * math.cos(2.0 * s)
    T, N, B = y[3:6], y[6:9], y[9:12]
    return np.concatenate([T, k * N, -k * T + t * B, -t * N])


Y0 = np.concatenate([np.zeros(3), np.eye(3).ravel()])  # x = 0, T = e1, N = e2, B = e3


def ours(samples: int) -> tuple[np.ndarray, np.ndarray]:
    c = SpaceCurve.from_curvature(kappa, tau, LENGTH, samples=samples)
    return c.points, c.frames


def ivp(s: np.ndarray, tol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*rtol.*too small.*")
        sol = solve_ivp(
            frenet_rhs, (0.0, LENGTH), Y0, method="DOP853", rtol=tol, atol=tol, t_eval=s
        )
    if not sol.success:
        raise RuntimeError(f"solve_ivp failed: {sol.message}")
    return ivp_arrays(sol.y)


def ivp_arrays(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """solve_ivp's (12, n) output as points (n, 3) and frames (n, 3, 3) with columns T, N, B."""
    return y[:3].T, np.swapaxes(y[3:].T.reshape(-1, 3, 3), -1, -2)


def write_floor(samples: int) -> tuple[np.ndarray, np.ndarray]:
    """The output's arrays, allocated and written once."""
    points, frames = np.empty((samples, 3)), np.empty((samples, 3, 3))
    points.fill(1.0)
    frames.fill(1.0)
    return points, frames


def max_errors(
    result: tuple[np.ndarray, np.ndarray], reference: tuple[np.ndarray, np.ndarray]
) -> tuple[float, float]:
    """Largest absolute error in the positions and in the frame entries."""
    return float(np.abs(result[0] - reference[0]).max()), float(
        np.abs(result[1] - reference[1]).max()
    )


def orthonormality_error(frames: np.ndarray) -> float:
    """max |FᵀF − I| over all frames."""
    return float(np.abs(np.swapaxes(frames, -1, -2) @ frames - np.eye(3)).max())


def run() -> list[SummaryRow]:
    n_max = max(N_VALUES)
    compiled = CompiledMagnus6()
    print(
        f"Frenet integrator: κ = 1 + 0.5 sin s, τ = 0.3 cos 2s, L = {LENGTH:g}; samples = N + "
        f"1; compiled reference: {compiled.command}"
    )
    t_fine, fine = timed(lambda: ours(REFINE * n_max + 1))
    s_common = np.linspace(0.0, LENGTH, COMMON + 1)
    t_ref, ref_ivp = timed(lambda: ivp(s_common, tol=1e-14))
    stride = REFINE * n_max // COMMON
    agreement = max_errors((fine[0][::stride], fine[1][::stride]), ref_ivp)
    print(
        f"references: fine = ours at {REFINE * n_max + 1:,} samples ({t_fine:.1f} s); DOP853 at "
        f"rtol = atol = 1e-14 (SciPy raises rtol to 2.2e-14) at {COMMON + 1} samples "
        f"({t_ref:.2f} s)"
    )
    print(
        f"mutual agreement of the references: positions {agreement[0]:.2e}, frames "
        f"{agreement[1]:.2e}\n"
    )

    rows, error_rows, summary, frames_1e6 = [], [], [], None
    worst = (0.0, 0.0)
    names = ("ours", "ivp", "compiled")
    for n in N_VALUES:
        label = f"1e{round(math.log10(n))}"
        s = np.linspace(0.0, LENGTH, n + 1)
        contenders = {
            "ours": lambda n=n: ours(n + 1),
            "ivp": lambda s=s: ivp(s),
            "compiled": lambda n=n: compiled(kappa, tau, LENGTH, n + 1),
            "floor": lambda n=n: write_floor(n + 1),
        }
        warm, _ = best_of_interleaved(contenders, 1, clock=CPU)
        k = choose_repeats(sum(warm.values()), BUDGET_PER_N)
        best, results = best_of_interleaved(contenders, k, clock=CPU)
        step = REFINE * n_max // n
        ref_fine = (fine[0][::step], fine[1][::step])
        common = n // COMMON
        err, split = {}, {}
        for name in names:
            res = results[name]
            e_fine = max_errors(res, ref_fine)
            e_ivp = max_errors((res[0][::common], res[1][::common]), ref_ivp)
            err[name] = (max(e_fine[0], e_ivp[0]), max(e_fine[1], e_ivp[1]))
            split[name] = (e_fine, e_ivp)
        error_rows.append(
            (label,) + tuple(f"{a:.1e} / {b:.1e}" for name in names for a, b in split[name])
        )
        vs_ivp, vs_compiled = best["ivp"] / best["ours"], best["ours"] / best["compiled"]
        ivp_ok = vs_ivp >= SPEEDUP
        compiled_ok = None if n < COMPILED_FROM else vs_compiled <= COMPILED_WITHIN
        err_ok = max(err["ours"]) <= ERROR_TARGET
        rows.append(
            (
                label,
                k,
                ms(best["ours"]),
                ms(best["ivp"]),
                ms(best["compiled"]),
                ms(best["floor"]),
                f"{vs_ivp:.2f} {verdict(ivp_ok)}",
                f"{vs_compiled:.2f}" + ("" if compiled_ok is None else f" {verdict(compiled_ok)}"),
                f"{best['ours'] / best['floor']:.1f}",
                f"{err['ours'][0]:.1e}, {err['ours'][1]:.1e}",
                f"{err['ivp'][0]:.1e}, {err['ivp'][1]:.1e}",
                f"{err['compiled'][0]:.1e}, {err['compiled'][1]:.1e}",
                verdict(err_ok),
            )
        )
        summary.append(
            SummaryRow(
                "integrator",
                f"N = {label}: from_curvature vs solve_ivp (DOP853, rtol 1e-12) and a compiled "
                "Magnus-6 loop",
                f"{ms(best['ours'])} ms vs {ms(best['ivp'])} ms ({vs_ivp:.1f}×) and "
                f"{ms(best['compiled'])} ms ({vs_compiled:.2f}× its time)",
                f"≥ {SPEEDUP:g}×"
                + ("" if compiled_ok is None else f"; ≤ {COMPILED_WITHIN:g}× compiled"),
                verdict(ivp_ok and compiled_ok is not False),
            )
        )
        worst = (max(worst[0], err["ours"][0]), max(worst[1], err["ours"][1]))
        if n == n_max:
            frames_1e6 = {name: results[name][1] for name in names}
            floor_1e6 = (best["ours"], best["floor"])
        del results
    compiled.close()
    headers = [
        "N",
        "k",
        "ours [ms]",
        "solve_ivp [ms]",
        "compiled [ms]",
        "write floor [ms]",
        f"ivp/ours (≥ {SPEEDUP:g})",
        f"ours/compiled (≤ {COMPILED_WITHIN:g} from 1e{round(math.log10(COMPILED_FROM))})",
        "ours/floor",
        "ours err (pos, frame)",
        "ivp err",
        "compiled err",
        f"ours err ≤ {ERROR_TARGET:g}",
    ]
    print(
        f"CPU seconds, best of k interleaved rounds; load average {os.getloadavg()[0]:.1f} on "
        f"{os.cpu_count()} CPUs"
    )
    print(markdown_table(headers, rows))
    print(
        "\nerrors split by reference, position / frame (the table above shows the larger of "
        "the two):"
    )
    print(
        markdown_table(
            ["N"] + [f"{name} vs {ref}" for name in names for ref in ("fine", "DOP853")], error_rows
        )
    )
    orth = {name: orthonormality_error(f) for name, f in frames_1e6.items()}
    print(
        f"\nframe orthonormality max|FᵀF − I| at N = 1e{round(math.log10(n_max))}: "
        + ", ".join(f"{name} {orth[name]:.1e}" for name in names)
    )
    ok = max(worst) <= ERROR_TARGET
    summary.append(
        SummaryRow(
            "integrator",
            "max error over all N (pos, frame)",
            f"{worst[0]:.1e}, {worst[1]:.1e}",
            f"≤ {ERROR_TARGET:g}",
            verdict(ok),
        )
    )
    summary.append(
        SummaryRow(
            "integrator",
            f"N = 1e6 against writing its {12 * 8 * (n_max + 1) / 1e6:.0f} MB once",
            f"{ms(floor_1e6[0])} ms vs {ms(floor_1e6[1])} ms ({floor_1e6[0] / floor_1e6[1]:.1f}×)",
            "—",
            "—",
        )
    )
    summary.append(
        SummaryRow(
            "integrator",
            "orthonormality at N = 1e6",
            f"{orth['ours']:.1e} (solve_ivp {orth['ivp']:.1e}, compiled {orth['compiled']:.1e})",
            "—",
            "—",
        )
    )
    summary.append(
        SummaryRow(
            "integrator",
            "reference agreement (pos, frame)",
            f"{agreement[0]:.1e}, {agreement[1]:.1e}",
            "—",
            "—",
        )
    )
    return summary


def main() -> None:
    print("\n" + summary_table(run()))


if __name__ == "__main__":
    main()
