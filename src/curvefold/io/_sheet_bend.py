"""A thick sheet as its crease patterns draw it (:mod:`curvefold.io._thick_sheet`): its bend, and
the glue tabs and perforation sized to it.

The sizes are the project's rule, stated here (no standard gives them; cutter practice sizes
both with the sheet: a glued lap's width with its thickness, a perforation's ties with the
material they must hold): glue tabs :data:`TAB_PER_T` × t wide, at least :data:`TAB_FLOOR` mm
(the pattern's own tab); perforated creases cut :data:`CUT_PER_T` × t and tied
:data:`TIE_PER_T` × t, the dash and gap asked for as floors. t is drawn at the print scale.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..geometry._bend import K_SOURCES, Bend, bend_for

__all__ = [
    "CUT_PER_T",
    "SEAM_OFFSET",
    "TAB_FLOOR",
    "TAB_PER_T",
    "TIE_PER_T",
    "SheetBend",
    "sheet_bend",
]

#: Glue tab width per sheet thickness; never below :data:`TAB_FLOOR` mm on the page.
TAB_PER_T = 8.0
#: The narrowest glue tab, page mm (the pattern's default tab).
TAB_FLOOR = 6.0
#: A perforated crease's cut and tie lengths per sheet thickness.
CUT_PER_T, TIE_PER_T = 3.0, 1.0
#: How far the lapping ply's seam line moves out, per sheet thickness.
SEAM_OFFSET = 1.0


@dataclass(frozen=True)
class SheetBend:
    """A sheet's bend (thickness, radius, K-factor and its source) and its material's name, as the
    crease patterns draw it."""

    bend: Bend
    material: str

    def tab_width(self, mm_per_unit: float) -> float:
        """Glue tab width on the page (mm) at ``mm_per_unit`` page mm per model unit."""
        return max(TAB_PER_T * self.bend.thickness * mm_per_unit, TAB_FLOOR)

    def perforation(
        self, asked: tuple[float, float] | None, mm_per_unit: float
    ) -> tuple[float, float] | None:
        """(cut, tie) of perforated creases on the page (mm): the asked ones as floors; None
        when none is asked."""
        if asked is None:
            return None
        t = self.bend.thickness * mm_per_unit
        return max(asked[0], CUT_PER_T * t), max(asked[1], TIE_PER_T * t)

    def note(self, mm_per_unit: float) -> str:
        """The legend's statement of what the drawing accounts for."""
        b = self.bend
        t_mm = b.thickness * 1e3  # model units are metres
        k_source = "DIN 6935" if self.material == "aluminium" else "assumed"
        return (
            f"sheet {t_mm:.3g} mm {self.material}: creases inset by the bend (R "
            f"{b.radius * 1e3:.3g} mm, K {b.k:.3g} {k_source}) · sheet A laps its seams, out "
            f"{SEAM_OFFSET * t_mm:.3g} mm · tabs {self.tab_width(mm_per_unit):.3g} mm"
        )


def sheet_bend(material: str | None, thickness: float) -> SheetBend:
    """The bend a design's sheet makes: a named material's (:func:`bend_for`: R = t, K of DIN
    6935 for aluminium, 0.5 assumed for the others), or for the user's own material K = 0.5
    assumed.

    Examples
    --------
    >>> sb = sheet_bend("aluminium", 0.001)
    >>> sb.bend.k, sb.tab_width(1000.0), sb.perforation((2.0, 0.5), 1000.0)
    (0.325, 8.0, (3.0, 1.0))
    >>> sheet_bend(None, 0.002).bend.source
    'no named material: K = 0.5 (the mid-surface) assumed'
    """
    if material is not None and material in K_SOURCES:
        return SheetBend(bend_for(material, thickness), material)
    source = "no named material: K = 0.5 (the mid-surface) assumed"
    return SheetBend(Bend(thickness, thickness, 0.5, source), material or "sheet")
