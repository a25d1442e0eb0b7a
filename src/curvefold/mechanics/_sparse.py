"""Sparse matrices of a bar-and-hinge model assembled from its elements' rows and blocks.

An element on m nodes owns the 3m unknowns of its nodes, node by node (x, y, z): a row per
element (compatibility, hinge rotation) or an element matrix summed into the global one.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["dof_index", "rows_matrix", "assemble"]


def dof_index(elements: np.ndarray) -> np.ndarray:
    """The DOFs of elements' nodes (N, m), node by node, shape (N, 3m)."""
    return (3 * elements[:, :, None] + np.arange(3)).reshape(len(elements), 3 * elements.shape[1])


def rows_matrix(rows: np.ndarray, elements: np.ndarray, dofs: int) -> sp.csr_matrix:
    """A sparse matrix with one row per element from its rows (N, m, 3) on its nodes (N, m)."""
    N = len(elements)
    index = dof_index(elements)
    return sp.csr_matrix(
        (
            rows.reshape(N, index.shape[1]).ravel(),
            (np.repeat(np.arange(N), index.shape[1]), index.ravel()),
        ),
        shape=(N, dofs),
    )


def assemble(blocks: np.ndarray, elements: np.ndarray, dofs: int) -> sp.csr_matrix:
    """Σ of element matrices (N, 3m, 3m) on their nodes (N, m), shape (dofs, dofs)."""
    index = dof_index(elements)
    m = index.shape[1]
    rows = np.repeat(index, m, axis=1).ravel()
    cols = np.tile(index, (1, m)).ravel()
    return sp.csr_matrix((blocks.reshape(-1), (rows, cols)), shape=(dofs, dofs))
