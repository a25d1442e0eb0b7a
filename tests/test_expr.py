"""Tests of curvefold.kernel._expr: values, broadcasting, refusals, resource limits and fuzzing."""

from __future__ import annotations

import pickle
import re
import tracemalloc

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose, assert_array_equal

from curvefold.kernel import InputError, as_function
from curvefold.kernel._expr import MAX_DEPTH, MAX_LENGTH, MAX_NODES, compile_expression

S = np.linspace(-0.9, 2.7, 37)


# --------------------------------------------------------------------------------------------
# Values against closed forms


@pytest.mark.parametrize(
    ("text", "reference"),
    [
        ("1 + 0.3*sin(s)", lambda s: 1 + 0.3 * np.sin(s)),
        ("0.4 + 0.2*cos(2*pi*s/6)", lambda s: 0.4 + 0.2 * np.cos(2 * np.pi * s / 6)),
        ("s**2 - 3*s + 2", lambda s: s**2 - 3 * s + 2),
        ("2**s", lambda s: 2.0**s),
        ("exp(-s)*tan(s/3)", lambda s: np.exp(-s) * np.tan(s / 3)),
        ("sinh(s) + cosh(s) - tanh(s)", lambda s: np.sinh(s) + np.cosh(s) - np.tanh(s)),
        ("arcsin(s/3) + acos(s/3)", lambda s: np.arcsin(s / 3) + np.arccos(s / 3)),
        ("arctan(s) - atan(2*s)", lambda s: np.arctan(s) - np.arctan(2 * s)),
        ("arctan2(s, 1 - s) + atan2(1, s)", lambda s: np.arctan2(s, 1 - s) + np.arctan2(1, s)),
        ("asin(s/4)", lambda s: np.arcsin(s / 4)),
        ("log(s + 1) + log10(s + 1)", lambda s: np.log(s + 1) + np.log10(s + 1)),
        ("sqrt(abs(s))", lambda s: np.sqrt(np.abs(s))),
        ("min(s, 0.5) + max(s, 0.5)", lambda s: np.minimum(s, 0.5) + np.maximum(s, 0.5)),
        ("clip(s, 0.2, 0.8)", lambda s: np.clip(s, 0.2, 0.8)),
        ("-s + +s - -s", lambda s: -s + s + s),
        ("1/(1 + s*s)", lambda s: 1 / (1 + s * s)),
        ("e**s * pi", lambda s: np.e**s * np.pi),
    ],
)
def test_values_match_numpy(text, reference):
    assert_allclose(compile_expression(text)(S), reference(S), rtol=1e-15, atol=0)


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("1 + 2*3**2", 19.0),
        ("-2**2", -4.0),  # Python precedence: ** binds tighter than unary minus
        ("2**-1", 0.5),
        ("2**3**2", 512.0),  # right-associative
        ("(2**3)**2", 64.0),
        ("7/2", 3.5),  # integers are float64: true division
        ("10**20", 1e20),
        ("1_000 + 0x10", 1016.0),
        ("pi", np.pi),
        ("e", np.e),
        ("2*pi", 2 * np.pi),
        ("clip(5, 0, 1)", 1.0),
        ("clip(5, 2, 1)", 1.0),  # lo > hi: hi wins
        ("max(-1, -2)", -1.0),
    ],
)
def test_constant_values_and_precedence(text, value):
    f = compile_expression(text)
    assert f.constant == value
    assert_array_equal(f(np.zeros(3)), np.full(3, value))


def test_custom_variable():
    f = compile_expression("1 + t**2", variable="t")
    assert_array_equal(f(S), 1 + S**2)
    with pytest.raises(InputError, match=r"tau: unknown name 's' \(allowed: t, pi, e\)"):
        compile_expression("s", variable="t", name="tau")


@pytest.mark.parametrize("variable", ["pi", "e", "sin", "1x", "lambda", "", "a b", 3])
def test_bad_variable_refused(variable):
    with pytest.raises(InputError, match="kappa: variable must be an identifier"):
        compile_expression("1", variable=variable, name="kappa")


# --------------------------------------------------------------------------------------------
# Broadcasting and the returned arrays


@pytest.mark.parametrize("shape", [(), (1,), (5,), (2, 3), (0,)])
def test_constant_broadcasts_to_input_shape(shape):
    out = compile_expression("0.3")(np.ones(shape))
    assert out.shape == shape
    assert out.dtype == np.float64
    assert_array_equal(out, np.full(shape, 0.3))


def test_scalar_and_list_inputs():
    f = compile_expression("s + 1")
    assert f(2).shape == ()
    assert float(f(2)) == 3.0
    assert_array_equal(f([0, 1, 2]), [1.0, 2.0, 3.0])
    assert_array_equal(f(np.arange(3)), [1.0, 2.0, 3.0])  # integer input is read as float


def test_result_never_aliases_input():
    s = np.arange(4.0)
    out = compile_expression("s")(s)
    out[0] = 99.0
    assert s[0] == 0.0
    const = compile_expression("1")(s)
    const[0] = 5.0  # a broadcast constant is a fresh, writable array
    assert_array_equal(compile_expression("1")(s), np.ones(4))


def test_constant_attribute():
    assert compile_expression("2*pi").constant == 2 * np.pi
    assert compile_expression("s - s").constant is None  # depends on s syntactically


def test_non_finite_results_without_warnings():
    # The project runs with warnings as errors, so a RuntimeWarning here would fail the test.
    s = np.array([-1.0, 0.0, 1.0])
    assert_array_equal(compile_expression("1/s")(s), [-1.0, np.inf, 1.0])
    assert_array_equal(compile_expression("log(s)")(s), [np.nan, -np.inf, 0.0])
    assert_array_equal(compile_expression("sqrt(s)")(s), [np.nan, 0.0, 1.0])
    assert compile_expression("exp(1000)").constant == np.inf
    assert_array_equal(compile_expression("s**100 * 1e300")(np.array([1e10])), [np.inf])


def test_expression_value_semantics():
    a, b = compile_expression("sin(s)"), compile_expression("sin(s)")
    assert a == b and hash(a) == hash(b)
    assert a != compile_expression("sin(s) ")
    assert str(a) == "sin(s)"
    assert "sin(s)" in repr(a)
    clone = pickle.loads(pickle.dumps(a))
    assert clone == a
    assert_array_equal(clone(S), a(S))


def test_works_with_as_function():
    f = as_function(compile_expression("s**3"), name="kappa", length=2.0)
    s = np.linspace(0.0, 2.0, 9)
    assert_allclose(f(s), s**3, rtol=1e-15)
    assert_allclose(f.derivative(s), 3 * s**2, rtol=0, atol=1e-9)


def test_doc_example_error_message_is_exact():
    with pytest.raises(InputError) as info:
        compile_expression("s.__class__", name="kappa")
    assert (
        str(info.value) == "kappa: attribute access is not allowed in expressions ('s.__class__')"
    )


# --------------------------------------------------------------------------------------------
# Refusals


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (
            "s.__class__",
            r"kappa: attribute access is not allowed in expressions " r"\('s\.__class__'\)",
        ),
        ("().__class__", r"attribute access is not allowed .*\('\(\)\.__class__'\)"),
        ("__import__('os')", r"kappa: function '__import__' is not allowed \(allowed: sin, cos, "),
        ("open(s)", r"kappa: function 'open' is not allowed \(allowed: sin, cos, tan, "),
        ("x + 1", r"kappa: unknown name 'x' \(allowed: s, pi, e\)"),
        ("tau*s", r"unknown name 'tau' \(allowed: s, pi, e\); .*write 2\*pi"),
        ("s[0]", r"subscripts are not allowed .*\('s\[0\]'\)"),
        ("lambda: 0", r"lambda functions are not allowed"),
        ("[x for x in ()]", r"comprehensions are not allowed"),
        ("(x for x in s)", r"comprehensions are not allowed"),
        ("{x: 1 for x in s}", r"comprehensions are not allowed"),
        ('"a"*9', r"strings are not allowed in expressions \(.\"a\".\)"),
        ("b'a'", r"strings are not allowed"),
        ('f"{s}"', r"f-strings are not allowed"),
        ("(y := 1)", r"assignment expressions \(:=\) are not allowed"),
        ("s < 1", r"comparisons are not allowed in expressions \('s < 1'\)"),
        ("s == s", r"comparisons are not allowed"),
        ("s and 1", r"boolean operators \(and, or\) are not allowed"),
        ("not s", r"operator 'not' is not allowed"),
        ("~s", r"operator '~' is not allowed"),
        ("s if s else 1", r"conditional expressions \(if/else\) are not allowed"),
        ("s % 2", r"operator '%' is not allowed \(allowed: \+ - \* / \*\*\)"),
        ("s // 2", r"operator '//' is not allowed"),
        ("s ^ 2", r"operator '\^' is not allowed .*use \*\* for powers"),
        ("s @ s", r"operator '@' is not allowed"),
        ("s << 1", r"operator '<<' is not allowed"),
        ("[s, 1]", r"lists are not allowed"),
        ("(s, 1)", r"tuples are not allowed"),
        ("{s}", r"sets are not allowed"),
        ("{}", r"dictionaries are not allowed"),
        ("True", r"True is not allowed in expressions \(only numbers\)"),
        ("None", r"None is not allowed"),
        ("...", r"Ellipsis is not allowed"),
        ("1j", r"complex numbers are not allowed"),
        ("sin(x=s)", r"keyword arguments are not allowed in expressions \('sin\(x=s\)'\)"),
        ("sin(**s)", r"keyword arguments are not allowed"),
        ("sin(*s)", r"starred arguments are not allowed in expressions \('\*s'\)"),
        ("sin(s, 1)", r"function 'sin' takes 1 argument, got 2"),
        ("arctan2(s)", r"function 'arctan2' takes 2 arguments, got 1"),
        ("clip(s, 1)", r"function 'clip' takes 3 arguments, got 2"),
        ("min(s, 1, 2)", r"function 'min' takes 2 arguments, got 3"),
        ("sin", r"function 'sin' must be called, e\.g\. sin\(s\)"),
        ("pi(2)", r"'pi' is not a function"),
        ("s(2)", r"'s' is not a function"),
        ("sin(s)(2)", r"only plain function names can be called"),
        ("np.sin(s)", r"only plain function names can be called \('np\.sin\(s\)'\)"),
        ("(yield)", r"'yield' is not allowed"),
        ("await s", r"'await' is not allowed"),
        ("1e999", r"number is too large for float64"),
        ("9" * 400, r"number is too large for float64"),
    ],
)
def test_refused(text, match):
    with pytest.raises(InputError, match=match):
        compile_expression(text, name="kappa")


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("1 + * 2", r"tau: invalid expression: invalid syntax at column 5 in '1 \+ \* 2'"),
        ("sin(s", r"'\(' was never closed at column 4"),
        ("  s +* 1", r"at column 6"),  # leading blanks count in the column
        ("(1 +\n * 2)", r"at line 2, column 2"),
        ("1 +", r"at the end of the expression"),
        ("s\x00", r"tau: invalid character U\+0000 at column 2"),
        ("\ud800", r"invalid character U\+D800 at column 1"),
        ("", r"tau: empty expression"),
        ("   ", r"tau: empty expression"),
    ],
)
def test_syntax_errors_name_the_position(text, match):
    with pytest.raises(InputError, match=match):
        compile_expression(text, name="tau")


@pytest.mark.parametrize("value", [3, 0.5, None, b"s", ["s"]])
def test_non_string_refused(value):
    with pytest.raises(InputError, match="kappa: expected an expression string"):
        compile_expression(value, name="kappa")


# --------------------------------------------------------------------------------------------
# Resource limits


def _refused_quickly(text: str, match: str) -> None:
    # Bounded work, measured without a clock: refusing allocates well under 4 MB (these take
    # at most 0.5 MB), where evaluating 9**9**9 in integers would need 160 MB.
    tracemalloc.start()
    try:
        with pytest.raises(InputError, match=match):
            compile_expression(text, name="kappa")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 4e6


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("9**9**9", r"kappa: constant exponent 3\.8742e\+08 is out of range .*\('9\*\*9\*\*9'\)"),
        ("2**1e6", r"constant exponent 1e\+06 is out of range"),
        ("s**101", r"constant exponent 101 is out of range"),
        ("s**-100.5", r"constant exponent -100\.5 is out of range"),
        ("s**(50 + 51)", r"constant exponent 101 is out of range"),
        ("s**(1e308*10)", r"constant exponent inf is out of range"),
        ("s**sqrt(-1)", r"constant exponent nan is out of range"),
        ("(" * 300 + "s" + ")" * 300, r"too many nested parentheses"),
        ("-" * (MAX_LENGTH - 1) + "s", r"nested too deeply"),
        ("sin(" * 60 + "s" + ")" * 60, r"nested too deeply \(more than 50 levels\)"),
        # a flat sum is one level deep, but 999 terms
        ("1+" * 499 + "1", rf"more than {MAX_NODES} terms"),
        # 20 products of 20 factors: 799 terms at depth ~40.
        ("+".join(["*".join(["s"] * 20)] * 20), rf"more than {MAX_NODES} terms"),
        ("s+" * 5000 + "s", rf"expression is 10001 characters long, the limit is {MAX_LENGTH}"),
    ],
)
def test_resource_limits(text, match):
    _refused_quickly(text, match)


def test_limits_are_inclusive():
    assert_array_equal(compile_expression("s**100")(np.array([1.0])), [1.0])
    assert_array_equal(compile_expression("s**-100")(np.array([1.0])), [1.0])
    assert_array_equal(compile_expression("-" * (MAX_DEPTH - 1) + "s")(S), -S)  # depth exactly 50
    assert compile_expression("1" + " " * (MAX_LENGTH - 1)).constant == 1.0


def test_a_chain_of_operations_is_one_level_deep():
    s = np.linspace(0.5, 2.5, 9)
    flat = "+".join(["s"] * 51) + "-s*2/s"  # 53 operations along the left operands
    assert_allclose(compile_expression(flat)(s), 51 * s - 2, rtol=1e-15)
    # left to right, as Python
    assert_array_equal(compile_expression("2+s*3-1/s**2")(s), 2 + s * 3 - 1 / s**2)
    with pytest.raises(InputError, match="nested too deeply"):
        compile_expression("s+(" * 51 + "s" + ")" * 51)  # a chain on the right operands nests


def test_variable_exponent_is_allowed():
    assert_array_equal(compile_expression("9**s")(np.array([0.0, 2.0])), [1.0, 81.0])


# --------------------------------------------------------------------------------------------
# Fuzzing

_EXPR_ALPHABET = "s0123456789.e+-*/() ,pisncoqrtabxlmg_[]'\"<=\n"


@settings(max_examples=300, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(st.text(max_size=120), st.text(alphabet=_EXPR_ALPHABET, max_size=120)))
def test_random_text_only_raises_input_error(text):
    try:
        f = compile_expression(text, name="kappa")
    except InputError as exc:
        assert str(exc).startswith("kappa: ")
        return
    out = f(S)
    assert out.shape == S.shape and out.dtype == np.float64


# Expression trees: ("var",), ("const", x), ("name", n), ("neg", t), ("bin", op, a, b),
# ("pow", a, k), ("call", f, *args). Text is fully parenthesised; the reference evaluates the
# same tree with NumPy, constants as float64 scalars exactly as the compiler folds them.
_BIN = {"+": np.add, "-": np.subtract, "*": np.multiply, "/": np.true_divide}
_CALLS = {
    "sin": (np.sin, 1),
    "cos": (np.cos, 1),
    "tanh": (np.tanh, 1),
    "exp": (np.exp, 1),
    "sqrt": (np.sqrt, 1),
    "abs": (np.abs, 1),
    "atan": (np.arctan, 1),
    "log": (np.log, 1),
    "arctan2": (np.arctan2, 2),
    "min": (np.minimum, 2),
    "max": (np.maximum, 2),
    "clip": (lambda x, lo, hi: np.minimum(np.maximum(x, lo), hi), 3),
}

_leaves = st.one_of(
    st.just(("var",)),
    st.floats(min_value=0.0, max_value=1e6, allow_nan=False).map(lambda x: ("const", x)),
    st.sampled_from(["pi", "e"]).map(lambda n: ("name", n)),
)


def _extend(children):
    return st.one_of(
        children.map(lambda t: ("neg", t)),
        st.tuples(st.just("bin"), st.sampled_from(sorted(_BIN)), children, children),
        st.tuples(st.just("pow"), children, st.sampled_from([-2.0, -1.0, 0.5, 2.0, 3.0])),
        st.sampled_from(sorted(_CALLS)).flatmap(
            lambda f: st.tuples(st.just("call"), st.just(f), *[children] * _CALLS[f][1])
        ),
    )


_trees = st.recursive(_leaves, _extend, max_leaves=16)


def _text(t) -> str:
    tag = t[0]
    if tag == "var":
        return "s"
    if tag == "const":
        return repr(t[1])
    if tag == "name":
        return t[1]
    if tag == "neg":
        return f"-({_text(t[1])})"
    if tag == "bin":
        return f"({_text(t[2])}) {t[1]} ({_text(t[3])})"
    if tag == "pow":
        return f"({_text(t[1])})**{t[2]!r}"
    return f"{t[1]}({', '.join(_text(a) for a in t[2:])})"


def _reference(t, s):
    tag = t[0]
    if tag == "var":
        return s
    if tag == "const":
        return np.float64(t[1])
    if tag == "name":
        return np.float64({"pi": np.pi, "e": np.e}[t[1]])
    if tag == "neg":
        return np.negative(_reference(t[1], s))
    if tag == "bin":
        return _BIN[t[1]](_reference(t[2], s), _reference(t[3], s))
    if tag == "pow":
        return np.power(_reference(t[1], s), np.float64(t[2]))
    return _CALLS[t[1]][0](*(_reference(a, s) for a in t[2:]))


def _depth(t) -> int:
    return 1 + max((_depth(c) for c in t[1:] if isinstance(c, tuple)), default=0)


@settings(max_examples=200)
@given(_trees)
def test_random_trees_match_numpy_reference(tree):
    text = _text(tree)
    assume(len(text) <= MAX_LENGTH and _depth(tree) <= MAX_DEPTH)
    f = compile_expression(text)
    with np.errstate(all="ignore"):
        expected = np.broadcast_to(_reference(tree, S), S.shape)
    # Same float64 operations in the same order: equal to the last bit (nan == nan here).
    assert_array_equal(f(S), expected)


def test_tree_text_is_parsed_back_exactly():
    tree = (
        "bin",
        "*",
        ("const", 0.1),
        ("call", "clip", ("var",), ("name", "pi"), ("neg", ("const", 2.0))),
    )
    assert _text(tree) == "(0.1) * (clip(s, pi, -(2.0)))"
    assert_array_equal(compile_expression(_text(tree))(S), np.full(S.shape, 0.1 * -2.0))


def test_error_message_is_one_line():
    with pytest.raises(InputError) as info:
        compile_expression("(1 +\n * 2)", name="kappa")
    assert "\n" not in str(info.value).replace("\\n", "")
    assert re.search(r"'\(1 \+\\n \* 2\)'", str(info.value))
