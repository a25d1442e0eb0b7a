"""One interface for every kind of structure: a kind no writer, figure or certificate knows plugs
in.

:class:`Forwarded` is a third kind of lattice: a class of its own (so no ``isinstance`` of
``Lattice`` or ``PanelLattice`` can recognise it) that satisfies
:class:`~curvefold.geometry.StructureLattice` and nothing more. Its geometry is
another lattice's; its answers about its kind (rigid, thinnable, crease degree) are its
own fields. Structures on it are built, sampled, written, checked, drawn and certified by
the code as it is, and each consumer follows the answers, not the type.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from curvefold import Crease, Lattice, SpaceCurve, Structure
from curvefold.analysis import analyse_fold, certify, check_fold
from curvefold.geometry import (
    FoldedCrease,
    FramedCurve,
    PanelLattice,
    StructureLattice,
    choose_sampling,
)
from curvefold.io import FoldOutput, to_fold, write_3d, write_structure_fold


@dataclass(frozen=True)
class Crease1:
    """Crease 1 of the third kind: its own class, the two members of the protocol."""

    curve: FramedCurve
    fold_angle: float


@dataclass(frozen=True, eq=False)
class Forwarded:
    """A third kind of lattice: another lattice's geometry, its own answers about its kind."""

    inner: StructureLattice
    rigid: bool
    thinnable: bool
    crease_degree: int

    @property
    def crease(self) -> Crease1:
        return Crease1(self.inner.crease.curve, self.inner.crease.fold_angle)

    @property
    def s(self):
        return self.inner.s

    @property
    def t(self):
        return self.inner.t

    @property
    def width_left(self):
        return self.inner.width_left

    @property
    def width_right(self):
        return self.inner.width_right

    @property
    def domain(self):
        return self.inner.domain

    @property
    def smooth(self):
        return self.inner.smooth

    def points(self, uv):
        return self.inner.points(uv)

    def check(self, uv, *, name="cells"):
        self.inner.check(uv, name=name)

    def topology(self, cell_curves, faces="triangles", *, keep=None):
        return self.inner.topology(cell_curves, faces, keep=keep)

    def refold(self, fold_angle, *, degrees=True, anchor="start"):
        return replace(self, inner=self.inner.refold(fold_angle, degrees=degrees, anchor=anchor))

    def fold_points(self, uv, fold_angles, *, degrees=True, anchor="start"):
        return self.inner.fold_points(uv, fold_angles, degrees=degrees, anchor=anchor)


@pytest.fixture(scope="module")
def smooth() -> Lattice:
    curve = SpaceCurve.from_curvature(lambda s: 1 + 0.3 * np.sin(s), 0.3, 3.0, samples=121)
    return Lattice.from_crease(Crease.from_curve(curve, fold_angle=90.0), 0.2, 0.15)


@pytest.fixture(scope="module")
def panels(smooth) -> PanelLattice:
    return PanelLattice.from_lattice(smooth, 12)


@pytest.fixture(scope="module")
def boards(panels) -> Structure:
    """A tube of the third kind, rigid, on the panels' geometry."""
    return Structure.tube(Forwarded(panels, rigid=True, thinnable=False, crease_degree=1))


def test_every_kind_satisfies_the_protocols(smooth, panels, boards):
    kinds = (smooth, panels, boards.lattice)
    assert all(isinstance(k, StructureLattice) for k in kinds)
    assert all(isinstance(k.crease, FoldedCrease) for k in kinds)
    assert all(isinstance(k.refold(30.0), StructureLattice) for k in kinds)
    # a lattice short of one member is not one
    assert not isinstance(Crease1(smooth.crease.curve, 90.0), StructureLattice)
    assert not isinstance(smooth.crease.curve, FoldedCrease)


def test_a_third_kind_is_built_sampled_and_written(tmp_path, panels, boards):
    own = Structure.tube(panels)
    for angle in (0.0, 45.0, 90.0):
        assert_array_equal(
            boards.state(angle).mesh().vertices_coords, own.state(angle).mesh().vertices_coords
        )
    sampling = choose_sampling(boards)  # not thinnable: every vertex
    assert [k.tolist() for k in sampling.keep] == [list(range(13))]

    path = write_structure_fold(
        tmp_path / "boards.fold",
        boards,
        fold_angles=[0.0, 45.0, 90.0],
        output=FoldOutput(keep=sampling.keep),
    )
    assert check_fold(path).ok
    # rigid panels, one internal degree of freedom folded
    assert [m.dof for m in analyse_fold(path)][1:] == [1, 1]
    model = to_fold(boards)
    assert model.metadata["samples"] == 13 and model.metadata["tubes"] == 1


def test_a_third_kind_is_drawn_and_certified(boards, panels):
    pytest.importorskip("matplotlib")
    from curvefold.figures import plot_structure

    figure = plot_structure(boards)
    assert "rigid planar panels" in [t.get_text() for t in figure.axes[0].get_legend().get_texts()]

    cert, own = (
        certify(boards.lattice.crease, boards),
        certify(panels.crease, Structure.tube(panels)),
    )
    assert cert.passed, [(c.name, c.status, c.where) for c in cert.checks if not c.passed]
    assert [c.name for c in cert.checks] == [c.name for c in own.checks]
    assert "panel_isometry" in {c.name for c in cert.checks} and cert.mechanism is not None


def test_consumers_follow_the_answers_not_the_type(tmp_path, smooth):
    """The same smooth geometry, told it may not be thinned and that its creases are polylines."""
    plain, told = (
        Structure.tube(smooth),
        Structure.tube(Forwarded(smooth, rigid=False, thinnable=False, crease_degree=1)),
    )
    assert len(choose_sampling(plain, tolerance=1e-2).keep[0]) < 121
    assert len(choose_sampling(told, tolerance=1e-2).keep[0]) == 121

    rhino3dm = pytest.importorskip("rhino3dm")
    degrees = {}
    for name, structure in (("plain", plain), ("told", told)):
        (path,) = write_3d(tmp_path / name, structure, formats=["3dm"])
        model = rhino3dm.File3dm.Read(str(path))
        layers = {layer.Index: layer.Name for layer in model.Layers}
        degrees[name] = {
            o.Geometry.Degree
            for o in model.Objects
            if layers[o.Attributes.LayerIndex] in ("Fold", "Seam")
        }
    assert degrees == {"plain": {3}, "told": {1}}
