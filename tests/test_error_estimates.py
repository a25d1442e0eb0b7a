"""Every figure of ``curvefold load`` with its error, estimated against half the elements across.

The estimates (:func:`curvefold.mechanics.figure_errors`, Richardson from k / 2 and k at
the orders of :data:`curvefold.mechanics._convergence.ORDERS`) are measured against a mesh
four times finer; the command prints them beside every figure and says when one is above
5 %.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from _cli import run
from curvefold.kernel import InputError
from curvefold.mechanics import (
    ERROR_TOLERANCE,
    MATERIALS,
    StructureModel,
    analyse_load,
    figure_errors,
)
from curvefold.vault import Vault

EXAMPLES = Path(__file__).parent.parent / "examples"
PP = MATERIALS["polypropylene"]
#: The lines of ``curvefold load`` whose figures depend on the mesh.
MESHED = ("max_displacement", "max_stress", "buckling_factor", "fold_mode_gap", "modes")


def _figures(result) -> dict[str, np.ndarray]:
    return {
        "max_displacement": np.array([result.static.max_displacement]),
        "max_stress": np.array([result.static.max_stress]),
        "buckling_factor": np.array([result.buckling.factor]),
        "fold_mode_gap": np.array([result.modes.fold_mode_gap]),
        "modes": result.modes.eigenvalues[:3],
        "supported_modes": result.supported_eigenvalues[:3],
    }


@pytest.mark.parametrize(
    "design", [dict(tubes=1, samples=41), dict(a=0.3, p_xy=0.75, tubes=3, samples=51)]
)
def test_the_estimates_from_two_and_four_across_bound_the_difference_to_sixteen(design):
    """Polypropylene 1 mm under its own weight, every sample kept (about 3 s each).

    Measured: every estimate is above the figure's difference to k = 16, by 1.05 (the
    tube's largest stress) to 20 times (its buckling factor): the orders assumed are low
    enough to err large, and no more than that.
    """
    one = StructureModel.from_state(
        Vault.from_design(**design).structure.state(), PP, 1e-3, samples="all"
    )
    two, four, sixteen = (analyse_load(one.with_across(k)) for k in (2, 4, 16))
    estimated = figure_errors(two, four)
    at_four, reference = _figures(four), _figures(sixteen)
    for key, value in at_four.items():
        error = np.abs(value - reference[key]) / np.abs(reference[key])
        estimate = np.atleast_1d(estimated[key])[: len(value)]
        assert np.all(estimate > error) and np.all(estimate < 40 * error + 1e-3), (
            key,
            estimate,
            error,
        )


def test_an_estimate_needs_a_coarser_result_first():
    """Swapped results are refused: the estimate would be of the coarser figure."""
    one = StructureModel.from_state(
        Vault.from_design(tubes=1, samples=21).structure.state(), PP, 1e-3
    )
    two, four = analyse_load(one.with_across(2)), analyse_load(one.with_across(4))
    assert figure_errors(two, four)["max_displacement"] > 0
    with pytest.raises(InputError, match=r"finer result must have more elements across, got 2 "):
        figure_errors(four, two)
    with pytest.raises(InputError, match="got 4 against 4"):
        figure_errors(four, four)


def _load(*argv: str) -> tuple[list[str], dict]:
    text = run("load", *argv)
    data = run("load", *argv, "--json")
    assert text.returncode in (0, 1) and data.returncode == text.returncode, text.stderr
    return text.stdout.splitlines(), json.loads(data.stdout)


def _printed(lines: list[str], key: str) -> str:
    return next(line for line in lines if line.startswith(f"  {key} "))


def test_the_tube_example_fails_with_every_figure_s_error():
    """The tube buckles under its own weight (exit 1, stability named first), every figure
    that depends on the mesh printed with ``± x %``, the same as ``--json``'s ``errors``, and
    the figures above 5 % told."""
    lines, d = _load(str(EXAMPLES / "tube.toml"), "--samples", "201")
    assert lines[0].startswith("fails: stability under ULS 1.35 G (buckling factor ")
    assert re.search(r"utilisation [\d.]+ ± [\d.]+ %\)$", lines[0]), lines[0]
    for key in MESHED:
        shown = re.search(r" ± ([\d.]+) %", _printed(lines, key))
        assert shown, key
        largest = float(np.max(d["errors"][key]))
        assert float(shown.group(1)) == pytest.approx(100 * largest, rel=0.05, abs=0.01), key
    for check in d["checks"]:
        assert 0 < check["error"] < 1, check
        assert " ± " in _printed(lines, check["name"])
    worst = max(float(np.max(e)) for e in d["errors"].values())
    assert worst > ERROR_TOLERANCE and any("raise --across (now 4)" in n for n in d["notes"])
    assert any("estimated against 2 across (Richardson)" in n for n in d["notes"])


def test_a_thin_vault_fails_the_stability_check_with_its_error():
    """A vault of three tubes of 0.3 mm polypropylene: buckling factor 3.5 under its own weight
    (exit 1), its error estimated; the same vault 1 mm thick stands."""
    lines, d = _load("--tubes", "3", "--samples", "101", "--thickness", "0.0003")
    assert lines[0].startswith("fails: stability under ULS 1.35 G"), lines[0]
    assert d["verdict"] == "fails" and d["governing"]["name"] == "stability"
    assert 0 < d["governing"]["error"] < 0.5
    lines, d = _load("--tubes", "3", "--samples", "101", "--thickness", "0.001")
    assert lines[0].startswith("stands: stability under ULS 1.35 G"), lines[0]
    # its largest stress is on a support, where the linear model's stress is singular: told
    assert any("largest stress is in an element on the supports" in n for n in d["notes"])


def test_the_paper_s_vault_stands_each_figure_within_five_percent():
    """The paper's vault as shipped (801 samples, polypropylene 1 mm, its own weight): it stands,
    governed by stability, every figure's estimated error below 5 % (measured: 0.5–4 %)."""
    lines, d = _load(str(EXAMPLES / "paper-vault.toml"))
    assert lines[0].startswith("stands: stability under ULS 1.35 G"), lines[0]
    assert d["verdict"] == "stands" and d["governing"]["error"] < ERROR_TOLERANCE
    for key, error in d["errors"].items():
        assert 0 < float(np.max(error)) < ERROR_TOLERANCE, (key, error)
    assert not any("raise --across" in n or "element on the supports" in n for n in d["notes"])


def test_one_element_across_prints_no_estimate_and_says_why():
    """With ``--across 1`` there is no coarser mesh: no ``±``, no ``errors``, and the note that
    a strip cannot bend across its width."""
    lines, d = _load("--tubes", "1", "--samples", "41", "--across", "1")
    assert d["errors"] == {} and all(c["error"] is None for c in d["checks"])
    assert not any(" ± " in line for line in lines)
    assert any("cannot bend across its width" in n for n in d["notes"])


def test_a_coarse_pair_of_meshes_is_told_to_refine():
    """Damaged accuracy: two across against one (a strip that cannot buckle across its width)
    moves the buckling factor by far more than 5 %, and the command says to raise --across."""
    lines, d = _load("--tubes", "3", "--samples", "101", "--across", "2")
    assert d["errors"]["buckling_factor"] > 1
    assert any(
        re.search(r"estimated error of \w+ is [\d.]+ %, above 5 %: raise --across \(now 2\)", n)
        for n in d["notes"]
    ), d["notes"]
