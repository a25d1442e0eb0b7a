"""Sphinx configuration of the curvefold documentation (built by scripts/docs.sh).

The site builds offline: no intersphinx, MathJax served from the site itself (copied from
npm into ``_vendor/`` by scripts/docs.sh), every cross-reference resolved (nitpicky), the
gallery's examples and the tutorial notebook executed.
"""

import sys
from importlib.metadata import version as _version
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))  # curvefold_docs: short names and the gallery's figures

from curvefold_docs import PUBLIC_PACKAGES, public_names  # noqa: E402

project = "curvefold"
author = "curvefold developers"
copyright = "2026, curvefold developers"
release = _version("curvefold")  # one source: the installed package's metadata
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "curvefold_docs",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "myst_nb",
]

# The gallery also writes each example as a notebook and a script: only its pages are sources.
exclude_patterns = [
    "_build",
    "_vendor",
    "node_modules",
    "jupyter_execute",
    "auto_examples/*.ipynb",
    "auto_examples/*.py",
    "auto_examples/*.zip",
    "auto_examples/*.md5",
    "auto_examples/*.codeobj.json",
]
templates_path = ["_templates"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"

# Every reference must resolve; names outside curvefold are not linked (no intersphinx: the
# build needs no network). Built-in and third-party names are listed here once.
nitpicky = True
nitpick_ignore_regex = [
    (
        r"py:.*",
        r"(numpy|np|scipy|matplotlib|PIL|pathlib|os|abc|ast|collections|typing|types|enum|io|dask|distributed|fastapi|rhino3dm|argparse|concurrent|contextlib|dataclasses|json|logging|threading|socket)\..*",
    ),
    (r"py:mod", r"(ast|abc|numpy|scipy|matplotlib|dask|fastapi|rhino3dm|ezdxf|trimesh|pygltflib)"),
    (
        r"py:class",
        r"(str|int|float|bool|bytes|dict|list|tuple|set|frozenset|object|callable|None|Any|Path|Figure|Axes|Image|ndarray|Mapping|Sequence|Iterable|Iterator|Callable|Collection|PathLike|Literal|MappingProxyType|ArrayLike|Enum|IntEnum|ValueError|RuntimeError|Exception|NamedTuple|TextIO|BinaryIO|Self)",
    ),
]

# numpydoc: parameter types are text (shapes and units read as written); classes are linked from the
# prose.
numpydoc_show_class_members = False
numpydoc_xref_param_type = False
numpydoc_class_members_toctree = False

autosummary_generate = True
# The module tree is documented whole (every module a page, so that docstrings may name any
# object by its module): autosummary does not follow __all__, which would drop the modules
# a package does not list. Each package's page lists its public names instead, the classes
# and functions of its __all__, each documented on its own page under the package's name
# (curvefold.geometry.Crease); its module's page leaves it out (curvefold_docs).
autosummary_ignore_module_all = True
autosummary_context = {"public": public_names(PUBLIC_PACKAGES)}
autodoc_default_options = {"members": True, "show-inheritance": True, "ignore-module-all": True}
autodoc_typehints = "none"
autodoc_member_order = "bysource"
# Source links for what each module defines (a lock object must not send viewcode to _thread).
viewcode_follow_imported_members = False

# MathJax from the site itself (npm's mathjax, copied by scripts/docs.sh).
html_static_path = ["_vendor"]
mathjax_path = "mathjax/tex-chtml.js"

# MyST: $…$ and $$…$$ maths, ::: fences; the notebook runs at every build.
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
nb_execution_mode = "force"
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples" / "gallery"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "matplotlib_animations": False,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "image_scrapers": ("curvefold_docs.curvefold_figures",),
    "reset_modules": ("matplotlib",),
}

html_theme = "pydata_sphinx_theme"
html_title = f"curvefold {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 5,
    "secondary_sidebar_items": ["page-toc"],
}
# Pages without sub-pages need no section navigation: the text gets the width.
html_sidebars = {
    page: [] for page in ("index", "install", "tutorial", "rhino", "errata", "changelog", "citing")
}
html_show_sourcelink = False
html_copy_source = False
