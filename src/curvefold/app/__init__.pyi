"""The names :mod:`curvefold.app` loads on first use, for type checkers and editors."""

from ._build import Built as Built
from ._build import BuiltCrease as BuiltCrease
from ._build import BuiltStructure as BuiltStructure
from ._build import BuiltVault as BuiltVault
from ._build import vault_design as vault_design
from ._design import Design as Design
from ._design import default_design as default_design
from ._design import design_from_dict as design_from_dict
from ._design import load_design as load_design
from ._design import parse_design as parse_design
from ._kinds import DesignKind as DesignKind
from ._kinds import Section as Section
from ._kinds import Targets as Targets
from ._kinds import deregister_kind as deregister_kind
from ._kinds import design_kind as design_kind
from ._kinds import design_kinds as design_kinds
from ._kinds import register_kind as register_kind
from ._outputs import structure_payload as structure_payload
from ._outputs import write_atlas as write_atlas
from ._outputs import write_outputs as write_outputs
from .cli import main as main

__all__ = [
    "Design",
    "load_design",
    "parse_design",
    "design_from_dict",
    "default_design",
    "Built",
    "BuiltStructure",
    "BuiltVault",
    "BuiltCrease",
    "vault_design",
    "DesignKind",
    "Section",
    "Targets",
    "register_kind",
    "deregister_kind",
    "design_kind",
    "design_kinds",
    "write_outputs",
    "write_atlas",
    "structure_payload",
    "main",
]
