"""The report's own text: quantities by name with units, the mesh resolution, files described."""

from __future__ import annotations

import html
import re

from curvefold.analysis._checks import TITLES
from curvefold.app import default_design
from curvefold.app._build import build
from curvefold.app._outputs import parameter_rows, structure_payload
from curvefold.app._products import resolution
from curvefold.figures._report import QUANTITIES, describe_file, report_html


def _section(page: str, title: str) -> str:
    return page.split(f"<h2>{title}</h2>", 1)[1].split("<h2>", 1)[0]


def test_derived_quantities_read_as_names_and_units_not_python():
    built = build(default_design("vault").overrides(samples=201))
    payload = (
        structure_payload(built)
        | resolution(built)
        | {"files": ["vault-pattern-p10.svg", "vault-pattern-p2.svg", "vault.obj"]}
    )
    page = report_html(payload | {"parameters": parameter_rows(built.design)})
    derived = _section(page, "Derived quantities")
    # lengths in metres
    assert (
        "κ0·s0, the root of the arch condition (Eq. 20)" in derived
        and "<td class=unit>m</td>" in derived
    )
    # names only as symbols beside their words
    for title in ("Certificate", "The paper's example", "Design"):
        shown = re.sub(r"<code>.*?</code>|<pre>.*?</pre>", "", _section(page, title), flags=re.S)
        assert not re.search(r">(eq\d+|[a-z0-9]+_[a-z0-9_]+)<", shown), title
    smooth = [
        words for words in TITLES.values() if not re.search("panel|degree of freedom|rank", words)
    ]
    assert all(html.escape(words) in page for words in smooth)
    assert "torsion amplitude" in _section(page, "Design") and "× radius" in _section(
        page, "Design"
    )
    assert not re.search(r">[a-z0-9]+_[a-z0-9_]+<", derived)  # no snake_case key shown as a name
    # no Python list, no 16-digit number
    assert "[" not in derived and not re.search(r"\d{11,}", derived)
    assert "×" in derived and "→" in derived  # the footprint and the bounding box, read as such
    assert [
        key for key in QUANTITIES if key in payload
    ] and "samples along each crease, in the files" in _section(page, "Meshes of the files")
    files = _section(page, "Files")
    assert files.index("vault-pattern-p2.svg") < files.index("vault-pattern-p10.svg")
    assert describe_file("vault.obj") in files and "Y up" in describe_file("vault.obj")
    assert describe_file("sheets/tube-1-sheet-A.fold").endswith("(loads in Origami Simulator)")


def _check(name: str, status: str) -> dict:
    """A check of ``check --json`` (as the file column holds it)."""
    return {
        "name": name,
        "status": status,
        "value": 1e-9,
        "tolerance": 1e-6,
        "unit": "",
        "where": "",
        "reason": "" if status != "not run" else "nothing to check",
    }


def test_the_summary_counts_the_checks_of_the_model_and_of_the_file_as_written():
    built = build(default_design("vault").overrides(samples=201))
    payload = structure_payload(built) | {"files": []}
    shipped = {
        "file": "vault.fold",
        "ok": True,
        "checks": [
            _check("isometry", "pass"),
            _check("fold_angles", "pass"),
            _check("welds", "not run"),
        ],
    }

    def summary(extra: dict) -> str:
        page = report_html(payload | extra)
        return re.sub(r"\s+", " ", page.split("<p>Geometric certificate:", 1)[1].split("</p>")[0])

    passed = sum(c["passed"] for c in payload["certificate"])
    model = f"<b>{passed}/{len(payload['certificate'])}</b> checks pass on the model"
    assert summary({}).startswith(f" {model}. Lengths")  # no file written: no file column
    assert f"{model}; on the FOLD file as written, <b>2/2</b>." in summary(
        {"certificate_file": shipped}
    )  # what did not run is not counted
    failed = {
        **shipped,
        "checks": [{**shipped["checks"][0], "status": "fail"}, *shipped["checks"][1:]],
    }
    assert "on the FOLD file as written, <b>1/2</b>." in summary({"certificate_file": failed})
