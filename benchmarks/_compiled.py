"""The compiled reference of the integrator benchmark: ``magnus6.c`` built with the machine's C
compiler.

It is built at benchmark time into a temporary folder (``cc -O3 -march=native``) and
loaded with ctypes; it is a reference to time against, never part of curvefold.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from curvefold.kernel._lie import GAUSS3_NODES

SOURCE = Path(__file__).with_name("magnus6.c")
FLAGS = ("-O3", "-march=native", "-shared", "-fPIC")


def compiler() -> str | None:
    """The C compiler to build with ($CC, else cc), or None when there is none."""
    name = os.environ.get("CC", "cc")
    return shutil.which(name)


class CompiledMagnus6:
    """``frenet_magnus6`` of ``magnus6.c``, built and loaded.

    Call it as ``(kappa, tau, length, samples) -> (points, frames)`` with vectorised
    callables: κ and τ are evaluated by NumPy at the Gauss nodes of every step, the
    steps run in C.
    """

    def __init__(self) -> None:
        cc = compiler()
        if cc is None:
            raise RuntimeError("no C compiler (cc or $CC) to build the compiled reference")
        self._folder = tempfile.TemporaryDirectory()
        library = Path(self._folder.name) / "magnus6.so"
        subprocess.run([cc, *FLAGS, "-o", str(library), str(SOURCE), "-lm"], check=True)
        self._lib = ctypes.CDLL(str(library))
        pointer = np.ctypeslib.ndpointer(np.float64, flags="C_CONTIGUOUS")
        self._lib.frenet_magnus6.argtypes = [
            ctypes.c_long,
            ctypes.c_double,
            pointer,
            pointer,
            pointer,
            pointer,
        ]
        self._lib.frenet_magnus6.restype = None
        self.command = " ".join([Path(cc).name, *FLAGS])

    def __call__(self, kappa, tau, length: float, samples: int) -> tuple[np.ndarray, np.ndarray]:
        h = length / (samples - 1)
        nodes = np.arange(samples - 1)[:, None] * h + GAUSS3_NODES * h  # (n - 1, 3)
        k, t = np.ascontiguousarray(kappa(nodes), float), np.ascontiguousarray(tau(nodes), float)
        points, frames = np.empty((samples, 3)), np.empty((samples, 3, 3))
        self._lib.frenet_magnus6(samples, h, k, t, points, frames)
        return points, frames

    def close(self) -> None:
        self._folder.cleanup()
