"""The deployment's keys (``curvefold deploy``'s flags), apart from its solver: the command line
reads them without loading SciPy."""

from __future__ import annotations

from ..kernel._validate import Spec

__all__ = ["DEPLOY_SUPPORTS", "REST_ANGLE", "START", "STEP"]

DEPLOY_SUPPORTS = Spec(
    "supports",
    "choice",
    "feet",
    choices=("feet", "foot"),
    help="how the structure is held while it folds: feet (both end sections carried along "
    "the folding motion) or foot (the first end section alone, the far end free)",
    label="supports while deploying",
)
STEP = Spec(
    "step",
    "real",
    1.0,
    "[0.05, 10]",
    "degrees",
    help="step of the fold angle 2α along the deployment",
    why="finer steps resolve nothing more; coarser ones lose the warm start",
    label="deployment step",
)
REST_ANGLE = Spec(
    "rest_angle",
    "real",
    None,
    "(0, 180)",
    "degrees",
    help="fold angle 2α at which the creases are at rest (default the design angle)",
    why="a crease creased flat or through would have no angle to rest at",
    label="creases' rest angle",
)
START = Spec(
    "start",
    "real",
    10.0,
    "(0, 180)",
    "degrees",
    help="fold angle 2α of the first state of the deployment",
    why="the flat state is degenerate (module notes)",
    label="deployment start",
)
