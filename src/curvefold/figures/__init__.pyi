"""The names :mod:`curvefold.figures` loads on first use, for type checkers and editors."""

from ._assembly import AssemblyPlan as AssemblyPlan
from ._assembly import assembly_plan as assembly_plan
from ._assembly import write_assembly as write_assembly
from ._atlas import atlas_figure as atlas_figure
from ._motion import motion_frames as motion_frames
from ._motion import write_motion_gif as write_motion_gif
from ._plots import plot_regression_domain as plot_regression_domain
from ._plots import plot_sections as plot_sections
from ._plots import plot_singular_values as plot_singular_values
from ._plots import plot_width_proportion as plot_width_proportion
from ._plots import save_figure as save_figure
from ._report import report_html as report_html
from ._scene import Scene as Scene
from ._scene import View as View
from ._scene import state_scene as state_scene
from ._scene import vault_scene as vault_scene
from ._views import plot_crease as plot_crease
from ._views import plot_motion_strip as plot_motion_strip
from ._views import plot_structure as plot_structure
from ._views import plot_vault as plot_vault

__all__ = [
    "plot_vault",
    "plot_motion_strip",
    "plot_structure",
    "plot_crease",
    "plot_regression_domain",
    "plot_width_proportion",
    "plot_sections",
    "plot_singular_values",
    "save_figure",
    "View",
    "Scene",
    "state_scene",
    "vault_scene",
    "motion_frames",
    "write_motion_gif",
    "atlas_figure",
    "AssemblyPlan",
    "assembly_plan",
    "write_assembly",
    "report_html",
]
