"""The paper's "virtual thickness", measured (``virtual_thickness.py``): the vault of thin sheets
against a plain barrel shell of its mass and span and against vaults of thick plywood panels;
the shell model held to 5 q L⁴ / 384 D on a plate strip and to OpenSees shells.

Targets: the vault stiffer than the plain shell of its mass, its buckling factor above the
shell's; the plate strip within 1e-3 of the closed form, OpenSees within 5 %.
"""

from __future__ import annotations

from virtual_thickness import run

__all__ = ["run"]
