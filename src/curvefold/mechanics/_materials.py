"""Sheet materials: a small named table with its sources, the user's own values, and their checks.

Every value is SI (Pa, kg/m³). The table's entries give where their numbers come from;
paperboard has no single source (grades, moisture and direction change it by a factor of
two), so its values are typical and marked as such. A user's material is checked with
the specs below (:class:`curvefold.kernel.Spec`), so a design file, a flag and
the Python API refuse the same values with the same words.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from ..kernel._validate import Interval, Spec

__all__ = [
    "Material",
    "MATERIALS",
    "MATERIAL",
    "MATERIAL_SPECS",
    "THICKNESS",
    "CREASE_STIFFNESS",
    "UNCODED_FACTOR",
    "material",
    "check_thickness",
]

#: The checks of a user's material (design-file keys and keyword arguments alike).
MATERIAL_SPECS: tuple[Spec, ...] = (
    Spec(
        "youngs_modulus",
        "real",
        None,
        Interval.parse("[1e3, 1e13]"),
        "Pa",
        help="Young's modulus E of the sheet",
        why="from the softest gels to beyond diamond's 1.2e12 Pa",
        typical=Interval.parse("[1e8, 2e11]"),
        label="Young's modulus E",
    ),
    Spec(
        "poisson",
        "real",
        None,
        Interval.parse("(-1, 0.5)"),
        help="Poisson's ratio ν of the sheet",
        why="an isotropic solid is stable only there",
        typical=Interval.parse("[0, 0.49]"),
        label="Poisson's ratio ν",
    ),
    Spec(
        "density",
        "real",
        None,
        Interval.parse("[1, 1e5]"),
        "kg/m³",
        help="density of the sheet",
        why="from aerogels to beyond osmium's 22,590 kg/m³",
        typical=Interval.parse("[100, 8000]"),
        label="density",
    ),
    Spec(
        "strength",
        "real",
        None,
        Interval.parse("[1e3, 1e12]"),
        "Pa",
        help="strength the stresses are measured against (yield or tensile)",
        why="up to beyond graphene's 1.3e11 Pa",
        typical=Interval.parse("[1e6, 5e8]"),
        label="strength",
    ),
)
#: The sheet's thickness t.
THICKNESS = Spec(
    "thickness",
    "real",
    1e-3,
    Interval.parse("(0, 1)"),
    "m",
    help="sheet thickness t",
    why="a sheet, not a block",
    typical=Interval.parse("[1e-4, 5e-3]"),
    label="sheet thickness t",
)
#: The creases' rotational stiffness per length k_c (default: the material's, see
#: :meth:`Material.crease_stiffness`).
CREASE_STIFFNESS = Spec(
    "crease_stiffness",
    "real",
    None,
    Interval.parse("(0, inf)"),
    "N·m/rad/m",
    help="rotational stiffness of the creases per length",
    why="a crease of no stiffness leaves the folding motion free",
    typical=Interval.parse("[1e-3, 10]"),
    label="crease stiffness k_c",
)
_SPEC = MappingProxyType({s.name: s for s in MATERIAL_SPECS})

#: The partial factor γ_M of a material no design code covers, and why.
UNCODED_FACTOR = 1.5
UNCODED_SOURCE = (
    "no Eurocode covers this material: 1.5 is this library's cautious choice, not a code value; "
    "give your own (gamma_m)"
)

#: Length scale of the default crease stiffness k_c = D / L*, as a multiple of the thickness.
CREASE_LENGTH_SCALE = 1000.0


def check_thickness(thickness: float, where: str = "thickness") -> float:
    """The thickness in metres, or :class:`~curvefold.kernel.InputError` (:data:`THICKNESS`)."""
    return THICKNESS.check(thickness, where)


@dataclass(frozen=True)
class Material:
    """An isotropic, linearly elastic sheet material.

    Build a user's with :meth:`from_values` (checked); the named ones are :data:`MATERIALS`.

    Attributes
    ----------
    name : str
    youngs_modulus : float
        E, Pa.
    poisson : float
        ν, in (−1, 0.5).
    density : float
        ρ, kg/m³.
    strength : float or None
        The stress the utilisation is measured against (yield for metals and polymers,
        tensile strength for board), Pa; None when not known (no utilisation then).
    source : str
        Where the numbers come from.
    partial_factor : float
        γ_M: the design strength is ``strength / partial_factor`` (EN 1990 §6.3.3).
    partial_factor_source : str
        Where γ_M comes from.

    Examples
    --------
    >>> steel = Material("steel", 200e9, 0.3, 7850.0, 250e6)
    >>> steel.name, steel.source, round(steel.bending_stiffness(1e-3), 6)
    ('steel', 'given by the user', 18.315018)
    """

    name: str
    youngs_modulus: float
    poisson: float
    density: float
    strength: float | None
    source: str = "given by the user"
    partial_factor: float = UNCODED_FACTOR
    partial_factor_source: str = UNCODED_SOURCE

    @classmethod
    def from_values(
        cls,
        youngs_modulus: float,
        poisson: float,
        density: float,
        strength: float | None = None,
        *,
        name: str = "user",
        where: str = "",
    ) -> Material:
        """A user's material, every value checked against :data:`MATERIAL_SPECS`.

        Parameters
        ----------
        youngs_modulus, poisson, density : float
            E (Pa), ν and ρ (kg/m³).
        strength : float, optional
            Pa; without it the stresses are not measured against a strength.
        name : str, keyword-only
        where : str, keyword-only
            Prefix of the parameters' names in messages (``"design.toml: [material] "``).

        Raises
        ------
        InputError
            One line naming the value, its range and what was given.

        Examples
        --------
        >>> Material.from_values(2e9, 0.3, 1200.0, 40e6).name
        'user'
        >>> Material.from_values(2e9, 0.5, 1200.0, 40e6)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: poisson must be in (-1, 0.5) (an isotropic solid is
        stable only there), got 0.5
        """
        values = {
            "youngs_modulus": youngs_modulus,
            "poisson": poisson,
            "density": density,
            "strength": strength,
        }
        checked: dict[str, Any] = {
            k: None if v is None and k == "strength" else _SPEC[k].check(v, f"{where}{k}")
            for k, v in values.items()
        }
        return cls(name, **checked)

    def bending_stiffness(self, thickness: float) -> float:
        """D = E t³ / 12(1 − ν²), the sheet's bending stiffness, N·m.

        Examples
        --------
        >>> round(Material.from_values(12e9, 0.0, 1000.0, 1e6).bending_stiffness(0.01), 6)
        1000.0
        """
        t = check_thickness(thickness)
        return self.youngs_modulus * t**3 / (12.0 * (1.0 - self.poisson**2))

    def crease_stiffness(self, thickness: float) -> float:
        """The default crease stiffness per length, k_c = D / L* with L* = 1000 t, N·m/rad/m.

        A crease is a line where the sheet was weakened to fold: Lechenault, Thiria and
        Adda-Bedia (2014, Phys. Rev. Lett. 112, 244301) measured a crease's stiffness as
        the sheet's D over a length L* that depends on how the crease was made: a scored line
        that keeps half the thickness over a thickness's width gives L* ≈ 8 t, a living
        hinge of a third of the thickness over three thicknesses L* ≈ 80 t, a tape or
        piano hinge far more. L* = 1000 t is this library's default, not a measured value:
        give the crease stiffness of your own creases where it matters (the fold-mode gap
        and the first mode's shape depend on it).

        Examples
        --------
        >>> round(MATERIALS["aluminium"].crease_stiffness(1e-3), 6)
        6.443347
        >>> MATERIALS["aluminium"].crease_stiffness(0.0)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: thickness must be in (0, 1) m (a sheet, not a block),
        got 0.0
        """
        return self.bending_stiffness(thickness) / (
            CREASE_LENGTH_SCALE * check_thickness(thickness)
        )


#: Named sheet materials, with their sources.
MATERIALS: MappingProxyType[str, Material] = MappingProxyType(
    {
        m.name: m
        for m in (
            Material(
                "polypropylene",
                1.3e9,
                0.42,
                905.0,
                31e6,
                "homopolymer sheet: E 1.14–1.55 GPa (ASTM D638), tensile yield 31–37 MPa, density "
                "0.90–0.91 g/cm³, from Modern Plastics Encyclopedia 99; ν 0.40–0.45 is typical "
                "(no single source); the lower ends are taken",
            ),
            Material(
                "paperboard",
                4.0e9,
                0.3,
                700.0,
                25e6,
                "typical folding boxboard in its machine direction (no single source): E 2–7 "
                "GPa, ν 0.2–0.4, density 600–900 kg/m³, tensile strength 20–50 MPa; the "
                "cross direction is 2–3 times softer: measure your board",
                partial_factor=1.3,
                partial_factor_source="no Eurocode covers board: EN 1995-1-1 Table 2.3's γ_M = "
                "1.3 for fibreboards, the nearest wood-based panel",
            ),
            Material(
                "aluminium",
                68.9e9,
                0.33,
                2700.0,
                276e6,
                "6061-T6 sheet: E 68.9 GPa, ν 0.33, density 2.70 g/cm³, tensile yield 276 MPa, "
                "typical values of the Aluminum Association as given in the ASM/MatWeb data "
                "sheet 'Aluminum 6061-T6; 6061-T651'",
                partial_factor=1.1,
                partial_factor_source="EN 1999-1-1 §6.1.3: γ_M1 = 1.10 (resistance of "
                "cross-sections)",
            ),
            Material(
                "plywood",
                4.0e9,
                0.3,
                680.0,
                30e6,
                "birch plywood to EN 636 of bending classes F40/30 E60/40 (along/across the face "
                "grain; EN 12369-2:2011 gives f_m,k 40/30 MPa, mean E 6.0/4.0 GPa): the across "
                "values taken for an isotropic sheet; density 680 kg/m³ typical of birch (EN "
                "12369-2 covers 350–750); ν 0.3 typical (no single source)",
                partial_factor=1.2,
                partial_factor_source="EN 1995-1-1 Table 2.3: γ_M = 1.2 for plywood",
            ),
        )
    }
)


def material(name: str) -> Material:
    """The named material of :data:`MATERIALS`.

    Examples
    --------
    >>> material("aluminium").youngs_modulus
    68900000000.0
    >>> material("steel")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: material must be one of "polypropylene", "paperboard",
    "aluminium", "plywood", got string 'steel'
    """
    return MATERIALS[MATERIAL.check(name)]


#: The name of a material of :data:`MATERIALS` (design files and flags; no default: the user's own
#: values, or the caller's choice).
MATERIAL = Spec(
    "material",
    "choice",
    None,
    choices=tuple(MATERIALS),
    help="a named sheet material (E, ν, density and strength from its source)",
    label="sheet material",
)
