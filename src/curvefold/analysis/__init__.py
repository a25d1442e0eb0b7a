"""Measurements, the geometric certificate and the check of FOLD files.

The names below are its public surface; :mod:`curvefold.analysis._measure` holds the
measurements the checks are made of.
"""

from ..kernel._exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_certificate": ["Certificate", "Check", "certify", "certify_single_fold"],
        "_checks": ["CHECKS", "CheckSpec"],
        "_foldcheck": ["FoldCheck", "FileCheck", "check_fold"],
        "_fold_mechanism": ["analyse_fold"],
        "_thick_checks": ["hinge_offsets", "thick_mechanism", "thickness_checks"],
        "_mechanism": [
            "Framework",
            "Mechanism",
            "CertifiedMechanism",
            "analyse",
            "certified_mechanism",
            "follow",
        ],
    },
)
