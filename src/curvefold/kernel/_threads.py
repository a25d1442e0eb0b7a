"""Dense linear algebra on one thread.

OpenBLAS starts one thread per CPU for every decomposition; on the small and middling
matrices curvefold decomposes (at most a few thousand columns) the threads spend more
time waking and waiting than computing, and far more when other programs share the CPUs
(measured: ``curvefold mechanism`` of a 16-panel vault 4.3 s on one thread, 37–44 s on two
with the machine's two CPUs busy). :func:`one_blas_thread` limits the BLAS libraries of this
process (threadpoolctl) for the extent of a block and restores them after.

OpenBLAS also starts its threads when it is loaded, and each spins for about a tenth of a
CPU-second before it sleeps, whatever comes (measured: ``import numpy`` alone 0.20-0.26
CPU-s with two threads, 0.12-0.14 with one). A program that runs its BLAS on one thread
loads NumPy in :func:`blas_loads_on_one_thread`, and no thread is started.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import cache, wraps
from typing import Any

__all__ = ["one_blas_thread", "on_one_blas_thread", "blas_loads_on_one_thread"]

#: The variables the BLAS libraries NumPy and SciPy may bring read for their thread count when
#: loaded.
BLAS_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


@cache
def _controller() -> Any:
    """The thread pools of the BLAS libraries loaded now (NumPy's among them), found once per
    process."""
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


@contextmanager
def blas_loads_on_one_thread() -> Iterator[None]:
    """A BLAS library loaded in the block (NumPy's, by its first import) starts on one thread.

    Each of :data:`BLAS_THREAD_VARIABLES` that is not set is ``1`` while the block runs, and
    the environment is as before afterwards (the processes started later inherit nothing).
    A library loaded before the block keeps its threads; :func:`one_blas_thread` can give
    a library loaded here more threads afterwards (threadpoolctl).

    Examples
    --------
    >>> import os
    >>> before = dict(os.environ)
    >>> with blas_loads_on_one_thread():
    ...     os.environ["OPENBLAS_NUM_THREADS"]
    '1'
    >>> dict(os.environ) == before
    True
    """
    unset = [name for name in BLAS_THREAD_VARIABLES if name not in os.environ]
    os.environ.update(dict.fromkeys(unset, "1"))
    try:
        yield
    finally:
        for name in unset:
            os.environ.pop(name, None)
