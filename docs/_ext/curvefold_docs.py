"""Sphinx extension of the curvefold documentation: short names in docstrings resolved, and the gallery's figures."""


def resolve_short_names(app, env, node, contnode):
    """Resolve a docstring's name the way its module's code reads it, else leave it unresolved (a warning).

    Docstrings name what their module imports without the package path (``:class:`InputError```),
    a re-export by its package (``curvefold.vault.VaultDesign``), and a dataclass field as an
    attribute of its class (``:attr:`Layout.notes```, documented in the class's Attributes).
    Each is tried in turn by suffix; a name matching more than one object still warns.
    """
    if node.get("refdomain") != "py" or node.hasattr("refspecific"):
        return None
    py = env.get_domain("py")
    target, kind = node["reftarget"], node["reftype"]
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


def curvefold_figures(block, block_vars, gallery_conf):
    """Sphinx-Gallery scraper: save the figures a block made (variables holding a Figure, or a list of them).

    curvefold's plots return matplotlib Figures that pyplot does not manage, so the
    matplotlib scraper, which asks pyplot, finds none.
    """
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    saved = block_vars.setdefault("curvefold_saved_figures", [])
    values = block_vars["example_globals"].values()
    found = [f for v in values for f in (v if isinstance(v, (list, tuple)) else [v]) if isinstance(f, Figure)]
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
    return {"parallel_read_safe": True, "parallel_write_safe": True}
