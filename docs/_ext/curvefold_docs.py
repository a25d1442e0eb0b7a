"""Sphinx extension of the curvefold documentation: short names in docstrings resolved, the
packages' public names, and the gallery's figures."""

import importlib
import inspect

#: The packages whose pages list their public names (``__all__``), each on a page of its own under
#: the package's name. The mechanics' page documents its names itself (its modules are private).
PUBLIC_PACKAGES = (
    "curvefold.kernel",
    "curvefold.geometry",
    "curvefold.vault",
    "curvefold.io",
    "curvefold.analysis",
    "curvefold.figures",
    "curvefold.app",
)


def _documented(value) -> bool:
    return inspect.isclass(value) or inspect.isfunction(value)


def public_names(packages) -> dict:
    """Package → the classes and functions of its ``__all__`` (the names its page lists and
    documents)."""
    out = {}
    for name in packages:
        package = importlib.import_module(name)
        out[name] = [item for item in package.__all__ if _documented(getattr(package, item))]
    return out


def skip_reexported(app, what, name, obj, skip, options):
    """Leave off a module's page a class or function its package lists: it is documented under
    the package's name."""
    if what != "module" or not _documented(obj):
        return None
    package = (getattr(obj, "__module__", None) or "").rpartition(".")[0]
    listed = app.config.autosummary_context["public"].get(package, ())
    if name in listed and getattr(importlib.import_module(package), name, None) is obj:
        return True
    return None


def resolve_short_names(app, env, node, contnode):
    """Resolve a docstring's name the way its module's code reads it, else leave it unresolved (a
    warning).

    Docstrings name what their module imports without the package path (``:class:`InputError```),
    a re-export by its package (``curvefold.vault.VaultDesign``), and a dataclass field as an
    attribute of its class (``:attr:`Layout.notes```, documented in the class's Attributes).
    Each is tried in turn by suffix; a name matching more than one object still warns. On the
    page of a package's public name (``curvefold.vault.ArchRoot``) a name is first looked up
    in the module that defines it (``curvefold.vault._arch``), as its docstring was written.
    """
    if node.get("refdomain") != "py" or node.hasattr("refspecific"):
        return None
    py = env.get_domain("py")
    target, kind = node["reftarget"], node["reftype"]
    home = _home(node["refdoc"])
    if (
        home
        and home != node.get("py:module")
        and py.find_obj(env, home, node.get("py:class"), target, kind, 0)
    ):
        # a public name's page: its docstring names what its own module holds
        node["py:module"] = home
        return py.resolve_xref(env, node["refdoc"], app.builder, kind, target, node, contnode)
    parts = target.split(".")
    candidates = [(kind, ".".join(parts[i:])) for i in range(len(parts) - 1)]
    owner = parts[:-1] or [node.get("py:class")]
    if kind == "attr" and owner[-1]:
        candidates.append(("class", ".".join(owner)))
    candidates.append((kind, parts[-1]))
    for role, name in candidates:
        if py.find_obj(env, node.get("py:module"), node.get("py:class"), name, role, 1):
            node["refspecific"] = True
            return py.resolve_xref(env, node["refdoc"], app.builder, role, name, node, contnode)
    return None


def _home(docname: str) -> str | None:
    """The module that defines what a public name's page documents (``curvefold.vault.ArchRoot``:
    ``curvefold.vault._arch``)."""
    package, _, name = docname.rpartition("/")[2].rpartition(".")
    if package not in PUBLIC_PACKAGES:
        return None
    return getattr(getattr(importlib.import_module(package), name, None), "__module__", None)


def curvefold_figures(block, block_vars, gallery_conf):
    """Sphinx-Gallery scraper: save the figures a block made (variables holding a Figure, or a list
    of them).

    curvefold's plots return matplotlib Figures that pyplot does not manage, so the
    matplotlib scraper, which asks pyplot, finds none.
    """
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    saved = block_vars.setdefault("curvefold_saved_figures", [])
    values = block_vars["example_globals"].values()
    found = [
        f
        for v in values
        for f in (v if isinstance(v, (list, tuple)) else [v])
        if isinstance(f, Figure)
    ]
    paths = []
    for figure in found:
        if not any(figure is s for s in saved):
            path = next(block_vars["image_path_iterator"])
            figure.savefig(path, dpi=110)
            saved.append(figure)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])


def setup(app):
    app.connect("missing-reference", resolve_short_names)
    app.connect("autodoc-skip-member", skip_reexported)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
