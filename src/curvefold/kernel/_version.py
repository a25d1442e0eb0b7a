"""The version of curvefold: set here once (``pyproject.toml`` reads it when the package is built).

A constant, so that naming the version (``curvefold.__version__``, the files' creator) imports
nothing: the package metadata reader, ``importlib.metadata``, costs a job process about
0.05 CPU-s to import.
"""

__all__ = ["VERSION"]

VERSION = "0.1.0"
