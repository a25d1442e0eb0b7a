"""Dense linear algebra on one thread.

OpenBLAS starts one thread per CPU for every decomposition; on the small and middling
matrices curvefold decomposes (at most a few thousand columns) the threads spend more
time waking and waiting than computing, and far more when other programs share the CPUs
(measured: ``curvefold mechanism`` of a 16-panel vault 4.3 s on one thread, 37–44 s on two
with the machine's two CPUs busy). :func:`one_blas_thread` limits the BLAS libraries of this
process (threadpoolctl) for the extent of a block and restores them after.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import cache, wraps
from typing import Any

__all__ = ["one_blas_thread", "on_one_blas_thread"]


@cache
def _controller() -> Any:
    """The thread pools of the BLAS libraries loaded now (NumPy's among them), found once per process."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


@contextmanager
def one_blas_thread() -> Iterator[None]:
    """Run the block with every BLAS library of this process on one thread.

    Examples
    --------
    >>> import numpy as np
    >>> with one_blas_thread():
    ...     sigma = np.linalg.svd(np.eye(3), compute_uv=False)
    >>> sigma.tolist()
    [1.0, 1.0, 1.0]
    """
    with _controller().limit(limits=1, user_api="blas"):
        yield


def on_one_blas_thread(function: Callable) -> Callable:
    """Decorate ``function`` to run inside :func:`one_blas_thread`.

    Examples
    --------
    >>> import numpy as np
    >>> det = on_one_blas_thread(np.linalg.det)
    >>> det.__name__, round(float(det(2 * np.eye(3))), 6)
    ('det', 8.0)
    """

    @wraps(function)
    def run(*args: Any, **kwargs: Any) -> Any:
        with one_blas_thread():
            return function(*args, **kwargs)

    return run
