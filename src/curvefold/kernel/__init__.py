"""The kernel: Lie-group steps, dense output, scalar functions, safe expressions and errors.

Nothing here imports another curvefold package.
"""
