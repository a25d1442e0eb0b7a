"""What :func:`curvefold.analysis.check_fold` finds: one :class:`FileCheck` per check, gathered in a
:class:`FoldCheck`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

__all__ = ["FileCheck", "FoldCheck"]


@dataclass(frozen=True)
class FileCheck:
    """One check of a FOLD file.

    Attributes
    ----------
    name : str
    status : {"pass", "fail", "not run"}
    value : float or None
        The worst measured value over the elements that can be measured (NaN if none can);
        None when not run, and for ``topology`` and ``edge_kinds``, which list their
        problems in ``where``.
    tolerance : float or None
    unit : str
    where : str
        The frame and the ids of the failing elements (or of the worst one); elements that
        cannot be measured are named apart.
    reason : str
        Why the check did not run, for "not run".
    """

    name: str
    status: str
    value: float | None = None
    tolerance: float | None = None
    unit: str = ""
    where: str = ""
    reason: str = ""

    def to_dict(self) -> dict:
        """The check as strict JSON (a non-finite value is null)."""
        value = None if self.value is None or not math.isfinite(self.value) else self.value
        return {
            "name": self.name,
            "status": self.status,
            "value": value,
            "tolerance": self.tolerance,
            "unit": self.unit,
            "where": self.where,
            "reason": self.reason,
        }


@dataclass(frozen=True)
class FoldCheck:
    """The result of :func:`check_fold`.

    Attributes
    ----------
    frames : int
        Number of folded frames checked.
    checks : tuple of FileCheck
    tolerances : dict
    notes : tuple of str
        What the reader read leniently or left, and why (:attr:`FoldFile.notes`).
    sources : dict of str to str
        How each tolerance the file promises was derived from it
        (:func:`~curvefold.analysis._promises.promised_tolerances`); the others are the
        defaults or were given.
    max_isometry_error : float
        Largest ``|ℓ_folded / ℓ_pattern − 1|`` over all measurable edges and frames (0 when
        that check did not run).
    max_face_planarity_error : float
        Largest fold angle, degrees, across face and ruling-quad diagonals (0 when that
        check did not run).
    max_fold_angle_error : float
        Largest ``|recorded − measured|`` dihedral angle, degrees.
    ok : bool
        Every check that ran passed.
    """

    frames: int
    checks: tuple[FileCheck, ...]
    tolerances: dict
    notes: tuple[str, ...] = ()
    sources: Mapping[str, str] = field(default_factory=dict)

    def _value(self, name: str) -> float:
        check = next(c for c in self.checks if c.name == name)
        return 0.0 if check.value is None else check.value

    @property
    def max_isometry_error(self) -> float:
        return self._value("isometry")

    @property
    def max_face_planarity_error(self) -> float:
        return self._value("face_planarity")

    @property
    def max_fold_angle_error(self) -> float:
        return self._value("fold_angles")

    @property
    def ok(self) -> bool:
        return all(c.status != "fail" for c in self.checks)

    def to_dict(self) -> dict:
        """The result as strict JSON (non-finite numbers are null), as ``curvefold check --json``
        prints it."""

        def finite(x):
            return x if math.isfinite(x) else None

        return {
            "frames": self.frames,
            "max_isometry_error": finite(self.max_isometry_error),
            "max_face_planarity_error": finite(self.max_face_planarity_error),
            "max_fold_angle_error": finite(self.max_fold_angle_error),
            "ok": self.ok,
            "checks": [c.to_dict() for c in self.checks],
            "not_run": [c.name for c in self.checks if c.status == "not run"],
            "notes": list(self.notes),
            "tolerances": self.tolerances,
            "tolerance_sources": dict(self.sources),
        }
