"""The bar-and-hinge model of a curvefold structure at a fold angle: the adapter from a State.

A structure's state holds every distinct lattice curve at every sample
(``State.vertices``, (M, n, 3)); its mesh (``State.mesh``) gives each tube its own copy of
its curves. The model's nodes are the distinct (curve, sample) points, so the two sheets
of a tube, welded along their seams, and neighbouring tubes, sharing a crease, share
their nodes (as :mod:`curvefold.analysis._mechanism` welds them); every tube keeps its own
crease hinges on them. Nodes are numbered sample by sample (node = sample · M + curve for
the points in use), which keeps the stiffness matrix in a band two samples wide.

A single curved fold (the paper's Fig. 08: crease 1 between its two strips) is one sheet
of a tube: ``sheets=(0,)`` keeps sheet A of tube 1, strips 4-1 and 1-2.

**Samples.** A model keeps, by default, every sample within :data:`END_SHARE` of the
samples of either end and every k-th sample in between (:func:`model_samples`): the end
sections are where a structure is supported, where its stresses concentrate and where a
local buckling mode of the sheet lives, which needs the finest sampling the structure
has; in between, :data:`MIDDLE_SAMPLES` spacings already resolve the response and the free
modes (measured: the paper's vault built on 801 samples and modelled on 261 of them
gives the same deflection, eigenvalues and buckling factor as on all 801, to 3e-4, in a
third of the time). With elements across the strips (k ≥ 2) the sheet's local modes are
held across its width, not by the spacing along it: a model keeps every second of those
samples (the paper's vault at k = 2 and 3 on 131 samples: every figure within 0.6 % of
261 samples, the buckling factor 0.5 % lower, in 40 % of the time and memory). Every
tube keeps the same samples, so seams and shared creases still share their nodes; a
structure of rigid panels keeps every vertex.

**Across.** ``across = k`` cuts every ruling strip or panel into k elements across its width
(:func:`cut_across`): the nodes inside a strip lie on its rulings, between two nodes of the
curves. They have no curve (``node_curve`` −1); ``node_ends`` and ``node_weight`` say where
they are, ``(1 − w) x_a + w x_b``, and every field of the curves' points that the model
carries onto its nodes (the folding motion) is taken there linearly.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..geometry._mesh import Mesh
from ..geometry._structure import State
from ..kernel._arrays import FrozenArrays, distinct, readonly
from ..kernel._errors import InputError
from ..kernel._validate import check_integer
from ._across import check_across, cut_across
from ._materials import CREASE_STIFFNESS, Material, check_thickness
from ._model import BarHingeModel

__all__ = [
    "StructureModel",
    "FOLD_STEP",
    "END_SHARE",
    "MIDDLE_SAMPLES",
    "MAX_STIFFNESS_RATIO",
    "model_samples",
    "check_conditioning",
]

#: Step of the central difference of the folding motion, degrees (its error ~1e-9 relative).
FOLD_STEP = 1e-3
#: Share of the samples at either end that a model keeps one by one (module notes).
END_SHARE = 0.05
#: Spacings a model keeps at least between its ends (module notes).
MIDDLE_SAMPLES = 200


def model_samples(n: int, across: int = 1) -> np.ndarray:
    """The samples of n that a structure's model keeps by default (module notes), ascending.

    With one element ``across`` each strip: every sample within ⌈e (n − 1)⌉ of either
    end, every s-th in between with s = ⌊(n − 1) / m⌋ (at least 1), and the middle sample
    (a vault's apex); e is ``END_SHARE`` = 0.05, m ``MIDDLE_SAMPLES`` = 200. With more:
    every second of those near the ends and m / 2 spacings between (module notes), the
    ends themselves always kept.

    Examples
    --------
    >>> len(model_samples(801)), model_samples(801)[[0, 40, 41, 42, -1]].tolist()
    (261, [0, 40, 44, 48, 800])
    >>> len(model_samples(801, 4)), model_samples(801, 4)[[0, 1, 20, 21, -2, -1]].tolist()
    (131, [0, 2, 40, 48, 798, 800])
    >>> model_samples(9).tolist() == list(range(9))
    True
    """
    n = check_integer(n, "samples", "[2, inf)")
    coarse = 1 if check_across(across) == 1 else 2
    i = np.arange(n)
    end = math.ceil(END_SHARE * (n - 1))
    stride = max(1, (n - 1) // (MIDDLE_SAMPLES // coarse))
    near = ((i <= end) | (i >= n - 1 - end)) & ((i % coarse == 0) | (i == n - 1))
    keep = near | (i % stride == 0) | (i == (n - 1) // 2)
    return i[keep]


@dataclass(frozen=True, eq=False)
class StructureModel(FrozenArrays):
    """A curvefold structure's bar-and-hinge model at one fold angle. Build it with
    :meth:`from_state`.

    Attributes
    ----------
    model : BarHingeModel
        In metres: the structure's model units are taken as metres (a vault's size is set
        by its radius 1/κ₀).
    state : State
    node_curve, node_sample : (P,) ndarray of int
        The lattice curve (row of ``structure.curves_uv``) and sample of every node; −1 for
        the curve of a node inside a strip.
    crease_stiffness : float
        k_c used for the creases, N·m/rad/m.
    material : Material
    across : int
        Elements across each strip or panel (module notes).
    node_ends : (P, 2) ndarray of int, optional
        The two nodes on curves that every node lies between (a node on a curve: itself
        twice; default every node on a curve).
    node_weight : (P,) ndarray, optional
        w of every node, at ``(1 − w) x_a + w x_b`` of its ends (default 0).

    Examples
    --------
    >>> import numpy as np
    >>> from curvefold.vault import Vault
    >>> tube = StructureModel.from_state(
    ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
    ...     MATERIALS["aluminium"],
    ...     1e-3,
    ... )
    >>> (
    ...     tube.model.nodes.shape,
    ...     round(tube.crease_stiffness, 6),
    ...     tube.material.name,
    ... )  # 4 curves × 5 vertices
    ((20, 3), 6.443347, 'aluminium')
    """

    model: BarHingeModel
    state: State
    node_curve: np.ndarray
    node_sample: np.ndarray
    crease_stiffness: float
    material: Material
    across: int = 1
    node_ends: np.ndarray | None = None
    node_weight: np.ndarray | None = None

    def __post_init__(self) -> None:
        P = len(self.node_curve)
        if self.node_ends is None:
            object.__setattr__(self, "node_ends", np.repeat(np.arange(P)[:, None], 2, axis=1))
        if self.node_weight is None:
            object.__setattr__(self, "node_weight", np.zeros(P))
        super().__post_init__()

    @classmethod
    def from_state(
        cls,
        state: State,
        material: Material,
        thickness: float,
        *,
        crease_stiffness: float | None = None,
        sheets: Sequence[int] | None = None,
        samples: str | Sequence[int] = "graded",
        across: int = 1,
    ) -> StructureModel:
        """The model of a structure's state (module notes).

        Parameters
        ----------
        state : State
        material : Material
        thickness : float
            t, m.
        crease_stiffness : float, optional, keyword-only
            k_c, N·m/rad/m; default the material's (:meth:`Material.crease_stiffness`).
        sheets : sequence of int, optional, keyword-only
            Only these sheets of the structure's topology (0 = tube 1 sheet A); default all.
        samples : {"graded", "all"} or sequence of int, keyword-only
            The samples the model keeps: :func:`model_samples` of its ``across``
            (``"graded"``), every one,
            or these (ascending, the first and last included). A structure of rigid panels
            keeps every vertex.
        across : int, keyword-only
            Elements across each ruling strip or panel, in [1, 64] (module notes).

        Examples
        --------
        >>> from curvefold import SpaceCurve, Crease, Lattice, Structure
        >>> from curvefold.mechanics import MATERIALS
        >>> lat = Lattice.from_crease(
        ...     Crease.from_curve(SpaceCurve.from_curvature(1.0, 0.2, 2.0, samples=9)), 0.1, 0.1
        ... )
        >>> tube = StructureModel.from_state(
        ...     Structure.tube(lat).state(), MATERIALS["aluminium"], 1e-3
        ... )
        >>> (
        ...     len(tube.model.nodes),
        ...     len(
        ...         StructureModel.from_state(
        ...             Structure.tube(lat).state(), MATERIALS["aluminium"], 1e-3, sheets=(0,)
        ...         ).model.nodes
        ...     ),
        ... )
        (36, 27)
        """
        t = check_thickness(thickness)
        k = check_across(across)
        k_c = (
            material.crease_stiffness(t)
            if crease_stiffness is None
            else CREASE_STIFFNESS.check(crease_stiffness)
        )
        structure = state.structure
        keep = _kept(samples, state.vertices.shape[1], k) if structure.lattice.thinnable else None
        # a quad per ruling quad or panel
        topology = structure.topology(
            "quads", keep=None if keep is None else [keep] * len(structure.cell_curves)
        )
        mesh = topology.mesh(state.vertices)
        if sheets is not None:
            mesh, kept = _sheets(mesh, topology, sheets)
        else:
            kept = np.arange(len(topology.vertex_curve))
        M = len(structure.curves_uv)
        curve, sample = topology.vertex_curve[kept], topology.vertex_sample[kept]
        mesh, ends, weight = cut_across(mesh, curve, k)
        # the points of the curves once, those inside strips each their own: sample by sample
        inner = np.arange(len(ends)) - len(curve)
        width = M + max(int(inner.max(initial=-1)) + 1, 0)
        key = sample[ends[:, 0]] * width + np.where(inner < 0, curve[ends[:, 0]], M + inner)
        points, weld = np.unique(key, return_inverse=True)
        model = BarHingeModel.from_mesh(mesh, material, t, crease_stiffness=k_c, weld=weld)
        check_conditioning(model, material, k_c)
        node_ends = np.zeros((len(points), 2), np.int64)
        node_weight = np.zeros(len(points))
        node_ends[weld], node_weight[weld] = weld[ends], weight
        node_curve = np.where(points % width < M, points % width, -1)
        return cls(
            model,
            state,
            node_curve,
            points // width,
            float(k_c),
            material,
            k,
            node_ends,
            node_weight,
        )

    def with_across(self, across: int) -> StructureModel:
        """The model of the same state, material, creases and samples with ``across`` elements
        across each strip.

        Examples
        --------
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> finer = tube.with_across(3)
        >>> finer.across, len(finer.model.nodes) - len(tube.model.nodes)  # 2 on 4 × 21 rulings
        (3, 168)
        """
        return StructureModel.from_state(
            self.state,
            self.material,
            self.model.thickness,
            crease_stiffness=self.crease_stiffness,
            samples=self.samples.tolist(),
            across=across,
        )

    # -- where the nodes are ---------------------------------------------------------------------
    @cached_property
    def feet(self) -> np.ndarray:
        """Nodes of the end sections (first and last samples) on the ground z = 0 (to 1e-9 of the
        size), ascending."""
        n = self.state.vertices.shape[1]
        ends = np.isin(self.node_sample, (0, n - 1))
        ground = np.abs(self.model.nodes[:, 2]) <= 1e-9 * max(self.model.size, 1e-300)
        return readonly(np.flatnonzero(ends & ground))

    @cached_property
    def ends(self) -> np.ndarray:
        """Nodes of the end sections (first and last samples), wherever they are, ascending."""
        n = self.state.vertices.shape[1]
        return readonly(np.flatnonzero(np.isin(self.node_sample, (0, n - 1))))

    def end_sections(self) -> np.ndarray:
        """The end sections of every tube as node quadruples, corners 1–4, shape (2K, 4): t = 0 then
        t = 1 of each tube.

        Raises
        ------
        InputError
            For a model of single sheets (a sheet's end is two rulings, not a section).

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> tube.end_sections().tolist()
        [[0, 1, 3, 2], [16, 17, 19, 18]]
        """
        index = {
            (c, s): p
            for p, (c, s) in enumerate(zip(self.node_curve.tolist(), self.node_sample.tolist()))
        }
        n = self.state.vertices.shape[1]
        try:
            return np.array(
                [
                    [index[(int(c), s)] for c in cell]
                    for cell in self.state.structure.cell_curves
                    for s in (0, n - 1)
                ]
            )
        except KeyError:
            raise InputError(
                "end sections need whole tubes; this model holds single sheets"
            ) from None

    @cached_property
    def samples(self) -> np.ndarray:
        """The samples the model keeps, ascending (every one, or :func:`model_samples`)."""
        return readonly(distinct(self.node_sample))

    def field(self, values: np.ndarray) -> np.ndarray:
        """Nodal values (P, ...) laid out as the state's curves, shape (M, n, ...); NaN where no
        node is.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> z = tube.field(tube.model.nodes[:, 2])
        >>> z.shape, bool(np.allclose(z, tube.state.vertices[..., 2]))
        ((4, 5), True)
        """
        values = np.asarray(values, float)
        M, n = self.state.vertices.shape[:2]
        out = np.full((M, n) + values.shape[1:], np.nan)
        on = self.node_curve >= 0
        out[self.node_curve[on], self.node_sample[on]] = values[on]
        return out

    def interpolate(self, values: np.ndarray) -> np.ndarray:
        """Nodal values (P, ...) on every sample of the state's curves, shape (M, n, ...).

        Linear in t between the samples the model keeps; NaN on curves it has no node on
        (single sheets).

        Examples
        --------
        A field linear in t comes back exactly on every sample; a constant one stays constant:

        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> from curvefold.mechanics import MATERIALS
        >>> sm = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, samples=41).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ...     samples=[0, 10, 20, 30, 40],
        ... )
        >>> on_curves = sm.interpolate(np.ones(len(sm.model.nodes)))
        >>> on_curves.shape[1], bool(np.allclose(on_curves[~np.isnan(on_curves)], 1.0))
        (41, True)
        """
        F = self.field(values)
        kept, n = self.samples, F.shape[1]
        i = np.arange(n)
        j = np.clip(np.searchsorted(kept, i, side="right") - 1, 0, len(kept) - 2)
        lo, hi = kept[j], kept[j + 1]
        w = ((i - lo) / (hi - lo)).reshape((1, n) + (1,) * (F.ndim - 2))
        return F[:, lo] * (1 - w) + F[:, hi] * w

    def sample_correlation(self, values: np.ndarray) -> float:
        """How a nodal field (P, 3) varies from one kept sample to the next where it is largest, in
        [−1, 1].

        ``Σ v(s_i) · v(s_i+1) / Σ ½ (|v(s_i)|² + |v(s_i+1)|²)`` over the consecutive samples
        of the curve that holds the field's largest value: 1 for a field that is the same at
        neighbouring samples, −1 for one that alternates from each sample to the next, a
        pattern at the scale of the samples themselves, which they do not resolve (a field
        elsewhere on the structure does not hide it).

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> from curvefold.mechanics import MATERIALS
        >>> sm = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> sign = (-1.0) ** sm.node_sample[:, None]
        >>> (
        ...     round(sm.sample_correlation(np.ones((len(sm.node_sample), 3))), 12),
        ...     round(sm.sample_correlation(sign * [0, 0, 1]), 12),
        ... )
        (1.0, -1.0)
        """
        values = np.asarray(values, float)
        size = np.where(
            self.node_curve >= 0, np.linalg.norm(values.reshape(len(values), -1), axis=1), -1
        )
        F = self.field(values)[self.node_curve[np.argmax(size)], self.samples]
        a, b = F[:-1], F[1:]
        scale = 0.5 * float(np.sum(a * a) + np.sum(b * b))
        return float(np.sum(a * b) / scale) if scale > 0 else 1.0

    def fold_velocity(self) -> np.ndarray:
        """d x / d(2α) of every node along the rigid folding motion, m/rad, shape (P, 3).

        The kinematics' own motion (``fold_points`` at 2α ± 0.001°, central
        difference), up to a rigid motion.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> tube = StructureModel.from_state(
        ...     Vault.from_design(tubes=1, panels=4, samples=21).structure.state(),
        ...     MATERIALS["aluminium"],
        ...     1e-3,
        ... )
        >>> velocity = tube.fold_velocity()
        >>> velocity.shape, float(np.abs(velocity[0]).max())  # node 0, on the anchored foot, stays
        ((20, 3), 0.0)
        """
        lattice = self.state.lattice
        angle = float(lattice.crease.fold_angle)
        h = min(FOLD_STEP, 0.5 * angle, 0.5 * (180.0 - angle)) if angle > 0 else FOLD_STEP
        lo, hi = max(angle - h, 0.0), angle + h
        X = lattice.fold_points(self.state.structure.curves_uv, np.array([lo, hi]))
        velocity = (X[1] - X[0]) / np.radians(hi - lo)
        a, b = np.asarray(self.node_ends).T
        w = np.asarray(self.node_weight)[:, None]
        return readonly(
            (1 - w) * velocity[self.node_curve[a], self.node_sample[a]]
            + w * velocity[self.node_curve[b], self.node_sample[b]]
        )


#: The largest ratio of two stiffnesses of one model that its solves resolve (module notes):
#: the free eigenvalues of a tube lose every digit past 1e12 (measured: thickness 1e-8 m,
#: ratio 5e13).
MAX_STIFFNESS_RATIO = 1e11


def check_conditioning(model: BarHingeModel, material: Material, crease_stiffness: float) -> None:
    """Refuse a model whose stiffnesses differ by more than :data:`MAX_STIFFNESS_RATIO`: the
    sheet's stretching against its bending over an element (E t ℓ² / D = 12 (1 − ν²) ℓ² / t²),
    and the creases against the sheet's bending (k_c ℓ / D), ℓ the median edge.

    Raises
    ------
    InputError
        Naming the thickness or the crease stiffness, the ratio and the value that fits.

    Examples
    --------
    >>> from curvefold.mechanics import MATERIALS
    >>> from curvefold.vault import Vault
    >>> state = Vault.from_design(tubes=1, samples=21).structure.state()
    >>> StructureModel.from_state(state, MATERIALS["aluminium"], 1e-9)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: thickness 1e-09 m is too thin for elements of 0.1... m:
    the sheet stretches ... times harder than it bends there, beyond the 1e+11 the solvers
    resolve; give at least ... m
    """
    if not len(model.bars) or model.thickness <= 0:
        return
    x = np.asarray(model.nodes)[np.asarray(model.bars)]
    edge = float(np.quantile(np.linalg.norm(x[:, 1] - x[:, 0], axis=1), 0.5))
    t, nu = model.thickness, material.poisson
    D = material.bending_stiffness(t)
    # (ℓ / t)² rather than ℓ² / t²: t² of a thickness below 1e-162 m is 0
    stretching = 12 * (1 - nu * nu) * min(edge / t, 1e150) ** 2
    if stretching > MAX_STIFFNESS_RATIO:
        least = edge * math.sqrt(12 * (1 - nu * nu) / MAX_STIFFNESS_RATIO)
        raise InputError(
            f"thickness {t:g} m is too thin for elements of {edge:.3g} m: the sheet stretches "
            f"{'over ' * (edge / t > 1e150)}{stretching:.2g} times harder than it bends there, "
            "beyond the "
            f"{MAX_STIFFNESS_RATIO:g} the solvers resolve; give at least {least:.2g} m",
            parameter="thickness",
        )
    creases = crease_stiffness * edge / D
    if creases > MAX_STIFFNESS_RATIO:
        raise InputError(
            f"crease_stiffness {crease_stiffness:g} N·m/rad/m is {creases:.2g} times the sheet's "
            f"bending stiffness over an element ({D / edge:.3g} N·m/rad/m), beyond the "
            f"{MAX_STIFFNESS_RATIO:g} the solvers resolve; give at most "
            f"{MAX_STIFFNESS_RATIO * D / edge:.2g} N·m/rad/m",
            parameter="crease_stiffness",
        )


def _kept(samples: str | Sequence[int], n: int, across: int) -> np.ndarray:
    """The samples of n a model keeps (:meth:`StructureModel.from_state`'s ``samples``)."""
    if isinstance(samples, str):
        if samples not in ("graded", "all"):
            raise InputError(f"samples must be 'graded', 'all' or sample indices, got {samples!r}")
        return model_samples(n, across) if samples == "graded" else np.arange(n)
    keep = np.asarray(samples)
    if (
        keep.ndim != 1
        or len(keep) < 2
        or not np.issubdtype(keep.dtype, np.integer)
        or keep[0] != 0
        or keep[-1] != n - 1
        or (np.diff(keep) <= 0).any()
    ):
        raise InputError(
            f"samples must be ascending sample indices from 0 to {n - 1}, got "
            f"{np.asarray(samples).tolist()!r}"[:300]
        )
    return keep


def _sheets(mesh: Mesh, topology, sheets: Sequence[int]) -> tuple[Mesh, np.ndarray]:
    """The mesh of some sheets of a topology, renumbered, and the topology vertices it keeps."""
    count = len(topology.sheets)
    picks = list(sheets)
    if not picks or any(
        isinstance(s, bool) or not isinstance(s, (int, np.integer)) or not 0 <= s < count
        for s in picks
    ):
        raise InputError(
            f"sheets must be indices in [0, {count}) of the structure's sheets, got "
            f"{list(sheets)!r}"
        )
    faces = distinct(np.concatenate([topology.sheets[s].faces for s in picks]))
    edges = distinct(np.concatenate([topology.sheets[s].edges for s in picks]))
    used = distinct(mesh.faces_vertices[faces])
    remap = np.full(len(mesh.vertices_coords), -1)
    remap[used] = np.arange(len(used))
    sub = Mesh(
        vertices_coords=mesh.vertices_coords[used],
        edges_vertices=remap[mesh.edges_vertices[edges]],
        edges_assignment=mesh.edges_assignment[edges],
        edges_foldAngle=mesh.edges_foldAngle[edges],
        faces_vertices=remap[mesh.faces_vertices[faces]],
        edges_kind=mesh.edges_kind[edges],
        faces_group=mesh.faces_group[faces],
    )
    return sub, used
