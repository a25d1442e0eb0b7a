"""Pictures: views of structures and vaults, plots and the HTML report.

matplotlib (the ``plot`` extra) is imported by the modules that draw, when they are first
asked for. Importing the package registers the writer of the assembly guide, which it draws,
in io's registry of file formats (:func:`curvefold.io._formats.register_writer`).
"""

from ..io._formats import register_writer as _register_writer
from ..kernel._exports import lazy_exports as _lazy_exports

_register_writer("assembly", "curvefold.figures._assembly:write_assembly")

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_views": ["plot_vault", "plot_motion_strip", "plot_structure", "plot_crease"],
        "_plots": [
            "plot_regression_domain",
            "plot_width_proportion",
            "plot_sections",
            "plot_singular_values",
            "save_figure",
        ],
        "_scene": ["View", "Scene", "state_scene", "vault_scene"],
        "_motion": ["motion_frames", "write_motion_gif"],
        "_atlas": ["atlas_figure"],
        "_assembly": ["AssemblyPlan", "assembly_plan", "write_assembly"],
        "_report": ["report_html"],
    },
)
