"""The HTML report of an output folder: design, derived quantities, certificate and pictures."""

from __future__ import annotations

import html
import json

import numpy as np

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


def _number(x: float | None, prefix: str = "") -> str:
    return "—" if x is None else f"{prefix}{x:.3g}" if prefix else f"{x:.2e}"


def _certificate_row(c: dict) -> str:
    e = html.escape
    kind = "pass" if c["passed"] else "fail" if c["status"] == "fail" else "unresolved"
    needed = f"<br><small>use ≥ {c['samples_needed']} samples</small>" if c["samples_needed"] else ""
    return (f"<tr class='{kind} head'><td><b>{e(c['name'])}</b></td><td class=status>{e(c['status'])}{needed}</td>"
            f"<td class=num>{_number(c['value'])}</td><td class=num>{_number(c['tolerance'])}</td>"
            f"<td class=num>{_number(c['margin'], '×')}</td><td>{e(c['unit'])}</td><td>{e(c['where'])}</td></tr>"
            f"<tr class='{kind} about'><td colspan=7>{e(c['measures'])}<br><small>Error model: {e(c['model'])}</small></td></tr>")


def _certificate_table(payload: dict) -> str:
    """The certificate: per check its status, value, tolerance, margin, where, what it measures and its error model."""
    e = html.escape
    rows = "".join(_certificate_row(c) for c in payload["certificate"])
    head = ("<tr><th>check</th><th>status</th><th>measured</th><th>tolerance</th><th>margin</th><th>unit</th>"
            "<th>worst frame and place</th></tr>")
    frames = payload.get("certificate_frames") or {}
    angles = frames.get("fold_angles") or []
    motion = ""
    if angles:
        listed = ", ".join(f"{a:g}°" for a in angles)
        motion = f"<p>Certified as built and in the frames 2α = {e(listed)}."
        if frames.get("holds_up_to") is not None:
            motion += (f" Every check passes up to 2α = {frames['holds_up_to']:g}° at {frames['samples']} samples (past it the error "
                       "of the folded state, growing as κ = κ_2D / cos α, outgrows a cap).")
        else:
            motion += f" At {frames['samples']} samples not every check passes in every frame (see below)."
        motion += "</p>"
    return f"{motion}<table class=certificate>{head}{rows}</table>"


def report_html(payload: dict) -> str:
    """A self-contained HTML report: parameters, derived quantities, certificate, pictures."""
    e = html.escape
    certificate = _certificate_table(payload)
    skip = {"certificate", "certificate_frames", "files", "design", "paper_comparison", "timings", "bounding_box", "curves", "cells", "curve_kinds", "bounding_curves"}
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
    title = e(payload.get("title") or payload.get("kind", "curvefold"))
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>curvefold — {title}</title>
<style>
body{{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}}
table{{border-collapse:collapse;margin:1em 0}}td,th{{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}}
.num{{white-space:nowrap;text-align:right;font-variant-numeric:tabular-nums}}td.status{{white-space:nowrap}}
tr.pass td.status{{color:#070}}tr.fail td{{background:#fee}}tr.unresolved td{{background:#fff6dd}}
table.certificate{{width:100%}}table.certificate small{{color:#555}}table.certificate td:nth-child(7){{min-width:14em}}
table.certificate tr.head td{{border-bottom:none}}table.certificate tr.about td{{border-top:none;font-size:.9em;padding-bottom:.6em}}
figure{{display:inline-block;margin:.5em;max-width:48%}}img{{max-width:100%;border:1px solid #ddd}}pre{{background:#f6f6f6;padding:1em}}
</style></head><body>
<h1>curvefold — {title}</h1>
<p>Geometric certificate: <b>{passed}/{len(payload['certificate'])}</b> checks pass.</p>
<h2>Pictures</h2>{pictures}
<h2>Derived quantities</h2><table>{derived}</table>
{paper}
<h2>Certificate</h2>{certificate}
<h2>Design</h2><pre>{design}</pre>
<h2>Files</h2><ul>{links}</ul>
</body></html>
"""
