"""The paper's domain: arch curves that stand on the ground, vaults and the design atlas."""

from ..kernel._exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_arch": [
            "A_MAX",
            "ArchRoot",
            "GeneralArch",
            "HarmonicTorsion",
            "proportion_change",
            "solve_general_arch",
            "solve_panel_arch",
            "solve_symmetric_arch",
        ],
        "_assembly": ["Vault", "VaultDesign"],
        "_tubes": ["DEFAULT_TUBES_CAP", "MAX_TUBES_SEARCH", "max_tubes"],
        "_atlas": ["Atlas", "AtlasGrid", "Sketch", "evaluate_design"],
        "_sweep": ["run_atlas", "sweep"],
        "_targets": ["TargetFit", "fit_targets"],
        "_paper": ["paper_comparison"],
    },
)
