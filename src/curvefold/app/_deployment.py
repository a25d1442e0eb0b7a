"""A design's deployment: its built structure folded under its own weight in the design's
material (``curvefold deploy`` and the designer's deploy button run the same)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..mechanics import Deployment, Material
    from ._loading import MaterialParams

__all__ = ["deploy_design"]


def deploy_design(
    structure: Any, params: MaterialParams, **options: Any
) -> tuple[Deployment, str | None, Material]:
    """The deployment of a built structure in its design's material (``MaterialParams``), the
    reason it stopped short of the design angle (None if it did not: a path that stops keeps
    its states) and the material."""
    from ..mechanics import MATERIALS
    from ..mechanics._deploy import DeployError, deploy
    from ._loading import _sheet

    material = _sheet(params) if params.material is None else MATERIALS[params.material]
    try:
        found = deploy(
            structure,
            material,
            params.thickness,
            crease_stiffness=params.crease_stiffness,
            **options,
        )
    except DeployError as err:
        return err.deployment, str(err), material
    return found, None, material
