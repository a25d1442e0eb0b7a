"""The paper's domain: arch curves that stand on the ground, vaults and the design atlas."""

from .arch import A_MAX, ArchRoot, proportion_change, solve_general_arch, solve_symmetric_arch
from .assembly import DEFAULT_TUBES_CAP, MAX_TUBES_SEARCH, Vault, VaultDesign, max_tubes

__all__ = [
    "A_MAX",
    "ArchRoot",
    "DEFAULT_TUBES_CAP",
    "MAX_TUBES_SEARCH",
    "Vault",
    "VaultDesign",
    "max_tubes",
    "proportion_change",
    "solve_general_arch",
    "solve_symmetric_arch",
]
