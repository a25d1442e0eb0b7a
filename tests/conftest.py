"""Hypothesis profiles.

By default property tests are derandomized: every run, on every machine, tries the same
examples (no example database either), so the suite passes or fails the same way on a
fresh clone. To look for new failures locally, draw fresh random examples on each run:

    HYPOTHESIS_PROFILE=explore .venv/bin/python -m pytest tests/test_properties.py

and pin every failing example it prints with ``@example(...)``. No profile has a
wall-clock deadline: a busy machine must not fail a test.
"""

import os

# One BLAS thread, set before NumPy loads its BLAS (nothing imports NumPy before this file):
# the same rounding on every run, and no oversubscription of small dense factorisations
# (the mechanism tests' SVDs run ten times slower with two threads on a busy two-core machine).
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

from hypothesis import settings  # noqa: E402

settings.register_profile("deterministic", derandomize=True, database=None, deadline=None)
settings.register_profile("explore", deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))
