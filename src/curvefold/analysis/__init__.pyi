"""The names :mod:`curvefold.analysis` loads on first use, for type checkers and editors."""

from ._certificate import Certificate as Certificate
from ._certificate import Check as Check
from ._certificate import certify as certify
from ._certificate import certify_single_fold as certify_single_fold
from ._checks import CHECKS as CHECKS
from ._checks import CheckSpec as CheckSpec
from ._fold_mechanism import analyse_fold as analyse_fold
from ._foldcheck import FileCheck as FileCheck
from ._foldcheck import FoldCheck as FoldCheck
from ._foldcheck import check_fold as check_fold
from ._mechanism import CertifiedMechanism as CertifiedMechanism
from ._mechanism import Framework as Framework
from ._mechanism import Mechanism as Mechanism
from ._mechanism import analyse as analyse
from ._mechanism import certified_mechanism as certified_mechanism
from ._mechanism import follow as follow
from ._thick_checks import hinge_offsets as hinge_offsets
from ._thick_checks import thick_mechanism as thick_mechanism
from ._thick_checks import thickness_checks as thickness_checks

__all__ = [
    "Certificate",
    "Check",
    "certify",
    "certify_single_fold",
    "CHECKS",
    "CheckSpec",
    "FoldCheck",
    "FileCheck",
    "check_fold",
    "analyse_fold",
    "Framework",
    "Mechanism",
    "CertifiedMechanism",
    "analyse",
    "certified_mechanism",
    "follow",
    "hinge_offsets",
    "thick_mechanism",
    "thickness_checks",
]
