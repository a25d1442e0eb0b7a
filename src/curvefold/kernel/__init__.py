"""The kernel: Lie-group steps, dense output, scalar functions, safe expressions and errors.

Nothing here imports another curvefold package. The names below are its public surface;
the Lie-group and dense-output steps of the integrator stay in their modules
(:mod:`curvefold.kernel._lie`, :mod:`curvefold.kernel._dense`).
"""

from ._exports import lazy_exports as _lazy_exports

# The public names by module, imported when first asked for (kernel.exports).
__all__, __getattr__, __dir__ = _lazy_exports(
    __name__,
    {
        "_errors": [
            "CurvefoldError",
            "InputError",
            "RegressionError",
            "ConvergenceError",
            "InternalError",
        ],
        "_validate": ["Spec", "Interval", "check_integer"],
        "_expr": ["Expression", "compile_expression"],
        "_functions": ["ScalarFunction", "Constant", "Sampled", "UserFunction", "as_function"],
        "_arrays": ["FrozenArrays", "readonly", "frozen"],
        "_threads": ["one_blas_thread"],
    },
)
