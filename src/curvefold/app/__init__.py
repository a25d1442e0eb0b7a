"""The application layer: design files, the command line and the output folder.

The names below are its public surface: a design read or made, built, and written out, and the
registry of kinds of design a new kind registers with (:func:`register_kind`).
"""

from ..kernel._exports import lazy_exports as _lazy_exports
from ..kernel._threads import blas_loads_on_one_thread as _blas_loads_on_one_thread

# The built-in kinds are registered before any use. Their sections load NumPy: the application
# (the command line, the designer) loads it with one BLAS thread (kernel._threads), as its small
# problems run fastest that way; a library loaded before keeps its threads.
with _blas_loads_on_one_thread():
    from . import _standard_kinds  # noqa: F401

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_design": ["Design", "load_design", "parse_design", "design_from_dict", "default_design"],
        "_build": ["Built", "BuiltStructure", "BuiltVault", "BuiltCrease", "vault_design"],
        "_kinds": [
            "DesignKind",
            "Section",
            "Targets",
            "register_kind",
            "deregister_kind",
            "design_kind",
            "design_kinds",
        ],
        "_outputs": ["write_outputs", "write_atlas", "structure_payload"],
        "cli": ["main"],
    },
)
