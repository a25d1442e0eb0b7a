"""The names :mod:`curvefold.kernel` loads on first use, for type checkers and editors."""

from ._arrays import FrozenArrays as FrozenArrays
from ._arrays import frozen as frozen
from ._arrays import readonly as readonly
from ._errors import ConvergenceError as ConvergenceError
from ._errors import CurvefoldError as CurvefoldError
from ._errors import InputError as InputError
from ._errors import InternalError as InternalError
from ._errors import RegressionError as RegressionError
from ._expr import Expression as Expression
from ._expr import compile_expression as compile_expression
from ._functions import Constant as Constant
from ._functions import Sampled as Sampled
from ._functions import ScalarFunction as ScalarFunction
from ._functions import UserFunction as UserFunction
from ._functions import as_function as as_function
from ._threads import one_blas_thread as one_blas_thread
from ._validate import Interval as Interval
from ._validate import Spec as Spec
from ._validate import check_integer as check_integer

__all__ = [
    "CurvefoldError",
    "InputError",
    "RegressionError",
    "ConvergenceError",
    "InternalError",
    "Spec",
    "Interval",
    "check_integer",
    "Expression",
    "compile_expression",
    "ScalarFunction",
    "Constant",
    "Sampled",
    "UserFunction",
    "as_function",
    "FrozenArrays",
    "readonly",
    "frozen",
    "one_blas_thread",
]
