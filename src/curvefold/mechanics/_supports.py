"""Supports of a structure's model: which nodes are held and how.

stands on them), or the end sections t = 0 and t = 1 wherever they are (a tube or block
held at both ends, as a bridge), or given nodes; ``"pinned"`` (every translation held) or
``"roller"`` (the vertical held on every supported node; three horizontal restraints,
chosen among them by a pivoted QR to hold the horizontal rigid motions, keep the
structure in place and, being statically determinate, carry no vertical load's reaction).

"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from ..kernel._errors import InputError
from ..kernel._validate import Spec
from ._loadcase import _model, _structure

if TYPE_CHECKING:  # pragma: no cover
    from ._model import BarHingeModel
    from ._structures import StructureModel

__all__ = ["Supports", "SUPPORTS", "SUPPORTED"]

#: How the supported nodes are held.
SUPPORTS = Spec(
    "supports",
    "choice",
    "pinned",
    choices=("pinned", "roller"),
    help="how the supported end sections are held: pinned (every translation) or roller "
    "(the vertical, and three horizontal restraints that only keep the structure "
    "in place)",
    label="supports",
)
#: Which nodes are supported: the feet (end sections on the ground) or both end sections
#: wherever they are.
SUPPORTED = ("feet", "ends")


@dataclass(frozen=True)
class Supports:
    """How the structure is held (module notes).

    Attributes
    ----------
    kind : {"pinned", "roller"}
    nodes : tuple of int or None
        The supported nodes; None: those ``at`` names, of a structure's model.
    at : {"feet", "ends"}
        Without ``nodes``: the feet (the end sections on z = 0, where a vault stands) or
        the ends (every tube's end sections t = 0 and t = 1, wherever they are: a tube or
        block held at both ends).

    Examples
    --------
    >>> Supports("clamped")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: supports must be one of "pinned", "roller", got string
    'clamped'
    """

    kind: Literal["pinned", "roller"] = "pinned"
    nodes: tuple[int, ...] | None = None
    at: Literal["feet", "ends"] = "feet"

    def __post_init__(self) -> None:
        SUPPORTS.check(self.kind)
        Spec("at", "choice", choices=SUPPORTED).check(self.at)
        if self.nodes is not None:
            nodes = np.asarray(self.nodes)
            if nodes.ndim != 1 or not len(nodes) or not np.issubdtype(nodes.dtype, np.integer):
                raise InputError(
                    f"support nodes must be a non-empty list of node indices, got {self.nodes!r}"
                )
            object.__setattr__(self, "nodes", tuple(int(v) for v in nodes))

    def fixed(self, target: StructureModel | BarHingeModel) -> np.ndarray:
        """The held DOFs, shape (P, 3) of bool.

        Raises
        ------
        InputError
            If the structure has no feet (no end section on z = 0) and no nodes are given,
            or a node is out of range.

        Examples
        --------
        >>> import numpy as np
        >>> from curvefold.vault import Vault
        >>> state = Vault.from_design(tubes=1, panels=4, samples=21).structure.state()
        >>> tube = StructureModel.from_state(state, MATERIALS["aluminium"], 1e-3)
        >>> (
        ...     int(Supports().fixed(tube).sum()),
        ...     int(Supports("roller").fixed(tube).sum()),
        ... )  # 8 feet pinned; on rollers, z and 3 more
        (24, 11)
        >>> Supports(nodes=(99,)).fixed(tube)
        Traceback (most recent call last):
        ...
        curvefold.kernel._errors.InputError: support nodes must be in [0, 20), got 99 … 99
        """
        sm = _structure(target)  # a StructureModel, which knows its end sections
        model = _model(target)
        P = len(model.nodes)
        if self.nodes is not None:
            nodes = np.asarray(self.nodes)
            if nodes.min() < 0 or nodes.max() >= P:
                raise InputError(
                    f"support nodes must be in [0, {P}), got {nodes.min()} … {nodes.max()}"
                )
        elif sm is not None:
            nodes = sm.feet if self.at == "feet" else sm.ends
            if not len(nodes):
                low = float(model.nodes[sm.ends, 2].min())
                raise InputError(
                    "no foot: no end section of this structure lies on the ground "
                    f"z = 0 (the lowest end point is at z = {low:.6g} m); place it on the "
                    "ground or give the supported nodes"
                )
        else:
            raise InputError("a model without a structure needs its supported nodes")
        fixed = np.zeros((P, 3), bool)
        if self.kind == "pinned":
            fixed[nodes] = True
            return fixed
        fixed[nodes, 2] = True
        # the horizontal rigid motions (x, y, rotation about z) at the feet's x, y DOFs
        c = model.nodes[nodes, :2] - model.nodes[nodes, :2].mean(axis=0)
        rows = np.zeros((len(nodes), 2, 3))
        rows[:, 0, 0] = rows[:, 1, 1] = 1.0
        rows[:, 0, 2], rows[:, 1, 2] = -c[:, 1], c[:, 0]
        from scipy.linalg import qr

        held = qr(rows.reshape(-1, 3).T, mode="r", pivoting=True)[1][:3]
        fixed[nodes[held // 2], held % 2] = True
        return fixed
