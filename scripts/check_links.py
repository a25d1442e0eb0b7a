"""Check every internal link of a built HTML site, offline.

    python check_links.py SITE_DIR

Every ``href`` and ``src`` of every page (the HTML files outside ``_static``, which holds
the theme's assets and templates) that is not an external address (``http:``,
``mailto:``, ``data:`` …) must name a file of the site, and a ``#fragment`` of an HTML page
must be an ``id`` (or ``<a name>``) on that page. Prints each broken link as
``page: link (why)`` and exits 1 if there is one.
"""

from __future__ import annotations

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

#: Attributes that hold a link.
LINK_ATTRIBUTES = frozenset({"href", "src"})


class _Page(HTMLParser):
    """The ids a page defines and the links it holds."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.links: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if value is None:
                continue
            if name == "id" or (tag == "a" and name == "name"):
                self.ids.add(value)
            elif name in LINK_ATTRIBUTES:
                self.links.append(value)


def _parse(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8", errors="replace"))
    return page


def broken_links(site: str | Path) -> list[str]:
    """Every broken internal link of the HTML pages under ``site``, as ``page: link (why)`` lines.

    Parameters
    ----------
    site : path-like
        The built site's root folder.

    Returns
    -------
    list of str
        Empty when every internal link resolves.
    """
    root = Path(site).resolve()
    pages = {
        path: _parse(path)
        for path in sorted(root.rglob("*.html"))
        if "_static" not in path.relative_to(root).parts
    }
    problems = []
    for path, page in pages.items():
        for link in page.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc:
                continue  # an external address: not checked offline
            target = (path.parent / unquote(parts.path)).resolve() if parts.path else path
            where = f"{path.relative_to(root)}: {link}"
            if root not in target.parents and target != root:
                problems.append(f"{where} (outside the site)")
            elif target.is_dir():
                if not (target / "index.html").is_file():
                    problems.append(f"{where} (a folder without index.html)")
            elif not target.is_file():
                problems.append(f"{where} (no such file)")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _parse(target).ids
                if unquote(parts.fragment) not in ids:
                    problems.append(f"{where} (no id {parts.fragment!r} on that page)")
    return problems


if __name__ == "__main__":
    if len(sys.argv) != 2 or not Path(sys.argv[1]).is_dir():
        sys.exit("usage: python check_links.py SITE_DIR")
    found = broken_links(sys.argv[1])
    for line in found:
        print(line)
    print(f"{len(found)} broken internal link(s) in the pages of {sys.argv[1]}")
    sys.exit(1 if found else 0)
