"""The HTML report of an output folder: design, derived quantities, certificate and pictures."""

from __future__ import annotations

import html
import json

import numpy as np

from ..kernel.text import one_line

__all__ = ["plain", "report_html"]

#: Pictures in the report, in this order (others follow alphabetically).
_PICTURE_ORDER = ("vault.png", "folding.gif", "folding-motion.png", "sections.png", "regression-domain.png", "width-proportion.png")


def plain(value):
    """A JSON-ready form of NumPy scalars and arrays (anything else as its text)."""
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return str(value)


def report_html(payload: dict) -> str:
    """A self-contained HTML report: parameters, derived quantities, certificate, pictures."""
    e = html.escape
    rows = "".join(
        f"<tr class={'pass' if c['passed'] else 'fail'}><td>{e(c['name'])}</td><td>{c['value']:.3e}</td>"
        f"<td>{'≥' if c['name'] == 'regression_margin' else '≤'} {c['tolerance']:.3e}</td><td>{e(c['unit'])}</td>"
        f"<td>{'pass' if c['passed'] else 'FAIL'}</td><td>{e(c['meaning'])}</td></tr>"
        for c in payload["certificate"]
    )
    skip = {"certificate", "files", "design", "paper_comparison", "timings", "bounding_box", "curves", "cells", "curve_kinds", "bounding_curves"}
    derived = "".join(
        f"<tr><td>{e(k)}</td><td>{e(f'{v:.10g}' if isinstance(v, float) else str(v))}</td></tr>" for k, v in payload.items() if k not in skip
    )
    design = e(json.dumps(payload.get("design", {}), indent=2, default=plain))
    paper = ""
    if payload.get("paper_comparison"):
        paper = "<h2>The paper's example</h2><table><tr><th>quantity</th><th>paper</th><th>computed</th><th>from the paper's κ0·s0</th><th>note</th></tr>" + "".join(
            f"<tr><td>{e(r['quantity'])}</td><td>{r['paper']}</td><td>{r['computed']:.12g}</td><td>{r['from_paper_kappa0_s0']:.4g}</td><td>{e(r['note'])}</td></tr>"
            for r in payload["paper_comparison"]
        ) + "</table>"
    files = payload.get("files", [])
    shown = sorted((f for f in files if f.endswith((".png", ".gif"))), key=lambda f: (_PICTURE_ORDER.index(f) if f in _PICTURE_ORDER else len(_PICTURE_ORDER), f))
    pictures = "".join(f'<figure><img src="{e(f)}" alt="{e(f)}"><figcaption>{e(f)}</figcaption></figure>' for f in shown)
    links = "".join(f'<li><a href="{e(f)}">{e(f)}</a></li>' for f in files)
    passed = sum(c["passed"] for c in payload["certificate"])
    title = e(one_line(payload.get("title") or payload.get("kind", "curvefold")))
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>curvefold — {title}</title>
<style>
body{{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}}
table{{border-collapse:collapse;margin:1em 0}}td,th{{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}}
tr.pass td:nth-child(5){{color:#070}}tr.fail td{{background:#fee}}
figure{{display:inline-block;margin:.5em;max-width:48%}}img{{max-width:100%;border:1px solid #ddd}}pre{{background:#f6f6f6;padding:1em}}
</style></head><body>
<h1>curvefold — {title}</h1>
<p>Geometric certificate: <b>{passed}/{len(payload['certificate'])}</b> checks pass.</p>
<h2>Pictures</h2>{pictures}
<h2>Derived quantities</h2><table>{derived}</table>
{paper}
<h2>Certificate</h2><table><tr><th>check</th><th>measured</th><th>tolerance</th><th>unit</th><th></th><th>what and why</th></tr>{rows}</table>
<h2>Design</h2><pre>{design}</pre>
<h2>Files</h2><ul>{links}</ul>
</body></html>
"""
