"""Pictures: views of structures and vaults, plots and the HTML report.

matplotlib (the ``plot`` extra) is imported by the modules that draw, when they are first
asked for.
"""

from ..kernel.exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "views": ["plot_vault", "plot_motion_strip", "plot_structure", "plot_crease"],
        "plots": ["plot_regression_domain", "plot_width_proportion", "plot_sections", "plot_singular_values", "save_figure"],
        "scene": ["View", "Scene", "state_scene", "vault_scene"],
        "motion": ["motion_frames", "write_motion_gif"],
        "atlas": ["atlas_figure"],
        "assembly": ["AssemblyPlan", "assembly_plan", "write_assembly"],
        "report": ["report_html"],
    },
)
