"""Geometry: curves, creases, lattices, structures, their folded states, meshes and sheets.

Pure NumPy on top of :mod:`curvefold.kernel`.
"""
