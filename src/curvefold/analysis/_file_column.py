"""The certificate's file column: the checks measured on the FOLD file that ships.

The certificate (:func:`~curvefold.analysis.certify`) measures the internal model, sampled
densely; the files carry fewer samples (:mod:`curvefold.geometry._sampling`). The file column is
:func:`~curvefold.analysis.check_fold` on the FOLD file as written and read back, against the
tolerances the file promises (:func:`~curvefold.analysis._promises.promised_tolerances`), so that
``curvefold check`` on the shipped file gives the same numbers.
"""

from __future__ import annotations

import os
from pathlib import Path

from ._foldcheck import check_fold

__all__ = ["COLUMNS", "file_column"]

#: What each column of the certificate measures, for report.json and the report.
COLUMNS = {
    "model": "the internal model at the design's samples, every check against its error model "
    "(the 'certificate' list)",
    "file": "the FOLD file as written and read back (its frames, at the samples it carries), "
    "against the tolerances the file promises: its recorded mesh tolerance and written "
    "precision; 'curvefold check' on that file gives the same (the 'certificate_file' entry)",
}


def file_column(path: str | os.PathLike) -> dict:
    """The file column of the certificate: :func:`check_fold` of the FOLD file at ``path``.

    Returns
    -------
    dict
        ``file`` (its name), then :meth:`FoldCheck.to_dict
        <curvefold.analysis.FoldCheck.to_dict>` (``ok``, ``checks``, ``tolerances``,
        ``tolerance_sources`` …), as ``curvefold check --json`` prints it.
    """
    return {"file": Path(path).name} | check_fold(path).to_dict()
