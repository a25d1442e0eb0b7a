"""The kinds curvefold ships (vault, tube, block, crease), registered in the registry of
:mod:`curvefold.app._kinds`.

The package imports this module first (``curvefold/app/__init__.py``), so every module of the
application finds the built-in kinds registered. Each kind names its builder in
:mod:`curvefold.app._build` by string, loaded when first called: this module is imported by no
module of the application, so the builders (which import the registry) are not in a cycle with it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..kernel._errors import InputError
from ..kernel._validate import Spec
from ..vault._tubes import DEFAULT_TUBES_CAP
from ._kinds import (
    BLOCK,
    CREASE,
    CURVE,
    LOAD_SECTIONS,
    TUBE,
    VAULT,
    BlockParams,
    CurveParams,
    DesignKind,
    Targets,
    VaultParams,
    register_kind,
)

#: A :class:`curvefold.app._design.Design`, named in words as in :mod:`curvefold.app._kinds`.
Design = Any

__all__: list[str] = []


def _vault_strips(design: Design) -> int:
    v = design.params(VaultParams)
    tubes = DEFAULT_TUBES_CAP if v.tubes == "max" else v.tubes
    return 4 * tubes * v.layers


def _check_alpha(values: dict, given: Mapping[str, Any], source: str) -> None:
    """With ``alpha`` given, β_R follows from Eq. (3): refuse ``beta_right`` and set
    ``fold_angle`` to 2α(0)."""
    import numpy as np

    checked, table = values["crease"], given.get("crease", {})
    alpha = checked["alpha"]
    if alpha is None:
        return
    if table.get("beta_right") is not None:
        raise InputError(
            f"{source}: [crease] give beta_right or alpha, not both "
            "(with alpha, beta_right follows from Eq. (3))",
            parameter="beta_right",
        )
    twice = float(2 * np.asarray(alpha(np.zeros(1)) if callable(alpha) else alpha, float).flat[0])
    if table.get("fold_angle") is not None and not math.isclose(
        checked["fold_angle"], twice, rel_tol=1e-12
    ):
        raise InputError(
            f"{source}: [crease] fold_angle must equal 2 alpha(0) = {twice:.12g} degrees "
            f"or be left out, got {checked['fold_angle']!r}",
            parameter="fold_angle",
        )
    checked["beta_right"], checked["fold_angle"] = None, twice


def _crease_alternatives(data: dict, given: set[str]) -> None:
    """A [crease]'s ``alpha`` and ``beta_right`` are alternatives: the one given drops the other
    (with ``alpha``, its ``fold_angle`` too, which then follows from it), unless both are given."""
    crease = data.get("crease")
    if crease is None:
        return
    if "alpha" in given:
        for key in ("beta_right", "fold_angle"):
            if key not in given:
                crease.pop(key, None)
    elif "beta_right" in given:
        crease.pop("alpha", None)


def _vault_targets() -> tuple[tuple[Spec, ...], Mapping[str, str]]:
    from ..vault._targets import REPLACES, TARGET_SPECS

    return tuple(TARGET_SPECS), REPLACES


def _curve_panels(design: Design) -> int:
    return design.params(CurveParams).panels


register_kind(
    DesignKind(
        "vault",
        (VAULT,),
        "curvefold.app._build:build_vault",
        _vault_strips,
        lambda values: math.pi * values["vault"]["radius"],
        help="the composite deployable vault (the main job)",
        description="Build a vault of tubed arches stacked along the lattice diagonal, "
        "standing on z = 0 at the design fold angle, and write its files, pictures and report.",
        optional=LOAD_SECTIONS,
        panels=lambda design: design.params(VaultParams).panels,
        lower=f'[vault] tubes or layers (tubes = "max" counts as {DEFAULT_TUBES_CAP})',
        grounded=True,
        targets=Targets(
            _vault_targets,
            "curvefold.app._build:fit_vault_targets",
            help="design the vault from what it must measure; each target replaces a "
            "parameter (span the radius, rise with span a, p_xz p_xy); tubes must then be a number",
        ),
    )
)
register_kind(
    DesignKind(
        "tube",
        (CURVE, TUBE),
        "curvefold.app._build:build_tube",
        lambda design: 4,
        lambda values: values["curve"]["length"],
        help="a single tube around curve 1",
        description='Build a single tube around curve 1 from a design file (kind = "tube") '
        "or the defaults, and write its files and report.",
        optional=LOAD_SECTIONS,
        panels=_curve_panels,
    )
)
register_kind(
    DesignKind(
        "block",
        (CURVE, BLOCK),
        "curvefold.app._build:build_block",
        lambda design: 4 * len(design.params(BlockParams).cells),
        lambda values: values["curve"]["length"],
        help="a cellular block of lattice cells",
        description='Build a cellular block of lattice cells from a design file (kind = "block") '
        "or the defaults, and write its files and report.",
        optional=LOAD_SECTIONS,
        panels=_curve_panels,
        lower="[block] cells",
    )
)
register_kind(
    DesignKind(
        "crease",
        (CREASE,),
        "curvefold.app._build:build_crease",
        lambda design: 2,
        lambda values: values["crease"]["length"],
        help="a single curved fold from its crease pattern",
        description="Fold a single curved crease from its crease pattern (kappa_2d, ruling "
        "angles, start fold angle or alpha(s)): the paper's Fig. 08.",
        check=_check_alpha,
        alternatives=_crease_alternatives,
        structure=False,
    )
)
