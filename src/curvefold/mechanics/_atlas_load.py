"""The mechanics columns of the design atlas: every vault of a grid under load, on a coarse model.

An :class:`AtlasLoad` says what every design of an atlas is made of, what loads it and how
coarse its model is; :meth:`AtlasLoad.measure` gives one built vault's columns
(:data:`LOAD_FIELDS`): the buckling factor, the governing check and its utilisation, the
deflection and its share of the span, the mass and whether the vault stands. It runs
:func:`~curvefold.mechanics.analyse_load` and :func:`~curvefold.mechanics.assess` on the
design rebuilt at :attr:`AtlasLoad.samples` samples with the tubes the atlas built, so a
design's columns are what ``curvefold load`` prints for the same design at those samples
(``--samples``) and elements across (``--across``). The sweep hands an ``AtlasLoad`` to its
workers (:mod:`curvefold.vault._sweep`), which keeps the vault layer free of the mechanics.

**Accuracy** (docs: the atlas guide; ``benchmarks/bench_atlas.py --load``). At the default
41 samples and one element across, a design costs 0.03–0.9 CPU-s (1 to 24 tubes), and on
five designs of the default grid its figures are those of the same model at 161 samples
within 2.1 % (buckling factor), 1.5 % (deflection) and 0.1 % (mass). That model is stiffer
than the structure: against four elements across at 81 samples its deflection is 15–34 %
low and its buckling factor 12–54 times high (a strip one element wide cannot buckle across
its width). The atlas ranks designs and finds the light ones; a design picked from it is
checked with ``curvefold load --across 4``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, ClassVar

from ..kernel._errors import CurvefoldError
from ..kernel._validate import Spec
from ._loadcase import G
from ._loads import Loads
from ._materials import THICKNESS, Material
from ._verdict import Criteria

if TYPE_CHECKING:  # pragma: no cover
    from ..vault._assembly import Vault

__all__ = ["AtlasLoad", "LOAD_FIELDS", "LOAD_SAMPLES"]

#: The mechanics columns of an atlas, in CSV order: the buckling factor under the characteristic
#: load (``curvefold load``'s ``buckling_factor``; empty when the load only stiffens the vault),
#: the governing check's utilisation and name, the largest deflection under the SLS combination
#: (m) and over the span, the mass (kg), whether every check passes, and why a built design has no
#: mechanics (the model refused it). Empty cells for a design that is not built.
LOAD_FIELDS = (
    "buckling_factor",
    "utilisation",
    "governing",
    "deflection",
    "deflection_span",
    "mass",
    "stands",
    "load_error",
)

#: Samples along each crease of the model of every design of an atlas.
LOAD_SAMPLES = Spec(
    "load_samples",
    "integer",
    41,
    "[21, 801]",
    help="samples along each crease of the model every design of the atlas is analysed on "
    "(made odd; fewer than 41 let some designs buckle between their samples)",
    why="801 is curvefold load's default",
)


@dataclass(frozen=True)
class AtlasLoad:
    """What every vault of an atlas is made of and loaded by, and the model it is analysed on.

    Attributes
    ----------
    material : Material
    thickness : float
        m.
    loads : Loads
        The characteristic load cases (default self-weight).
    supports : {"pinned", "roller"}
        How the feet are held.
    criteria : Criteria
        What the verdict asks.
    crease_stiffness : float or None
        N·m/rad/m (None: the material's).
    across : int
        Elements across each ruling strip.
    samples : int
        Samples along each crease of the model (``LOAD_SAMPLES``, made odd).

    Examples
    --------
    >>> from curvefold.vault import Vault
    >>> from curvefold.mechanics import MATERIALS
    >>> load = AtlasLoad(MATERIALS["polypropylene"], 1e-3, samples=21)
    >>> columns = load.measure(Vault.from_design(samples=41, tubes=2))
    >>> columns["stands"], columns["governing"], round(columns["mass"], 4)
    (True, 'stability', 1.5939)
    """

    material: Material
    thickness: float = THICKNESS.default
    loads: Loads = field(default_factory=Loads)
    supports: str = "pinned"
    criteria: Criteria = field(default_factory=Criteria)
    crease_stiffness: float | None = None
    across: int = 1
    samples: int = LOAD_SAMPLES.default

    fields: ClassVar[tuple[str, ...]] = LOAD_FIELDS

    def __post_init__(self) -> None:
        from ._across import ACROSS
        from ._supports import SUPPORTS

        THICKNESS.check(self.thickness)
        SUPPORTS.check(self.supports)
        ACROSS.check(self.across)
        object.__setattr__(self, "samples", LOAD_SAMPLES.check(self.samples) | 1)

    def measure(self, vault: Vault) -> dict[str, Any]:
        """The columns of ``LOAD_FIELDS`` of one built vault, as plain Python values.

        The vault is built again at :attr:`samples` with the tubes it has; a design that cannot
        be built so or that the model refuses (a :class:`~curvefold.kernel.CurvefoldError`:
        past regression at those samples, a mechanism on its supports, no load) gets empty
        cells and the reason in ``load_error``.

        Examples
        --------
        >>> from curvefold.vault import Vault
        >>> from curvefold.mechanics import MATERIALS, Loads
        >>> vault = Vault.from_design(samples=41, tubes=1)
        >>> columns = AtlasLoad(MATERIALS["aluminium"], 1e-3, samples=21).measure(vault)
        >>> columns["governing"], round(columns["mass"], 4), columns["load_error"]
        ('deflection', 2.3768, None)
        >>> AtlasLoad(MATERIALS["aluminium"], 1e-3, Loads(())).measure(vault)[
        ...     "load_error"
        ... ]  # doctest: +ELLIPSIS
        'InputError: ...'
        """
        from ..kernel._threads import one_blas_thread
        from ..vault._assembly import Vault
        from ._analysis import analyse_load
        from ._supports import Supports
        from ._verdict import assess, span_length

        try:
            coarse = (
                vault
                if vault.design.samples == self.samples
                else Vault.from_design(replace(vault.design, samples=self.samples))
            )
            with one_blas_thread():  # a worker of another cluster may run more
                result = analyse_load(
                    coarse.structure,
                    self.material,
                    self.thickness,
                    self.loads,
                    Supports(self.supports, at="feet"),  # type: ignore[arg-type]
                    crease_stiffness=self.crease_stiffness,
                    across=self.across,
                )
                verdict = assess(result, self.criteria)
        except CurvefoldError as err:
            return self.empty() | {"load_error": f"{type(err).__name__}: {err}"}
        governing = verdict.governing
        deflection = next(c for c in verdict.checks if c.name == "deflection").value
        factor = result.buckling.factor
        return {
            "buckling_factor": None if math.isinf(factor) else float(factor),
            "utilisation": float(governing.utilisation),
            "governing": governing.name,
            "deflection": float(deflection),
            "deflection_span": float(deflection / span_length(result.structure, result.supports)),
            "mass": float(result.total_weight / G),
            "stands": bool(verdict.stands),
            "load_error": None,
        }

    def empty(self) -> dict[str, Any]:
        """The columns of a design with no mechanics: every cell empty.

        Examples
        --------
        >>> from curvefold.mechanics import MATERIALS
        >>> set(AtlasLoad(MATERIALS["aluminium"]).empty().values())
        {None}
        """
        return dict.fromkeys(LOAD_FIELDS)

    def notes(self) -> list[str]:
        """What a reader of the columns must know: how far the model is from the structure.

        Examples
        --------
        >>> from curvefold.mechanics import MATERIALS
        >>> AtlasLoad(MATERIALS["aluminium"], across=2).notes()[0].split(";")[0]
        'the mechanics columns are the model at 41 samples and 2 elements across each strip'
        """
        head = (
            f"the mechanics columns are the model at {self.samples} samples and "
            + ("one element" if self.across == 1 else f"{self.across} elements")
            + " across each strip"
        )
        if self.across > 1:
            return [
                f"{head}; check the vault you pick with curvefold load --across {2 * self.across}"
            ]
        return [
            f"{head}: against four elements across, its deflection was 15–34 % low and its "
            "buckling factor 12–54 times high on five designs of the default grid, so a vault "
            "marked as standing may buckle; check the one you pick with curvefold load --across 4"
        ]

    def to_dict(self) -> dict[str, Any]:
        """What the atlas's JSON header says of the mechanics: material, thickness, loads,
        supports, criteria and the model.

        Examples
        --------
        >>> from curvefold.mechanics import MATERIALS
        >>> d = AtlasLoad(MATERIALS["aluminium"], 2e-3).to_dict()
        >>> d["material"], d["thickness"], d["loads"], d["samples"], d["across"]
        ('aluminium', 0.002, 'self-weight', 41, 1)
        """
        c = self.criteria
        return {
            "material": self.material.name,
            "thickness": self.thickness,
            "loads": self.loads.describe(),
            "supports": self.supports,
            "crease_stiffness": self.crease_stiffness,
            "criteria": {
                "gamma_g": c.gamma_g,
                "gamma_q": c.gamma_q,
                "gamma_m": c.gamma_m,
                "buckling_safety": c.buckling_safety,
                "deflection_limit": c.deflection_limit,
            },
            "samples": self.samples,
            "across": self.across,
        }
