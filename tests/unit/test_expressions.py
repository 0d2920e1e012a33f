"""The expression grammar of initial fields (pmpmsph/config/expressions.py): values against
NumPy to 1e-15, Python's precedence, every whitelisted function, and every refusal."""
import math

import numpy as np
import pytest

from pmpmsph.config.expressions import FUNCTIONS, MAX_NODES, UNARY, parse

RNG = np.random.default_rng(7)
# points in (0.1, 0.9)^3: inside the domain of every function (arcsin, log, sqrt)
X3 = 0.1 + 0.8 * RNG.random((257, 3))
X2 = X3[:, :2]
x, y, z = X3.T


def ev(text, pts=X2, dim=None):
    return parse(text, dim or pts.shape[1]).evaluate(pts)


def close(a, b):
    np.testing.assert_allclose(a, np.broadcast_to(b, a.shape), rtol=1e-15, atol=1e-300)


@pytest.mark.parametrize("name", sorted(UNARY))
def test_every_function_of_one_argument(name):
    ref = {"abs": np.abs}.get(name, getattr(np, name))
    close(ev(f"{name}(0.5 * x + 0.3 * y)"), ref(0.5 * x + 0.3 * y))


def test_functions_of_several_arguments():
    close(ev("atan2(y - 0.5, x - 0.5)"), np.arctan2(y - 0.5, x - 0.5))
    close(ev("min(x, y)"), np.minimum(x, y))
    close(ev("max(x, y, 0.5)"), np.maximum(np.maximum(x, y), 0.5))
    close(ev("min(x, y, z, 0.4)", X3), np.minimum(np.minimum(np.minimum(x, y), z), 0.4))
    close(ev("where(x < 0.5, 1, -y)"), np.where(x < 0.5, 1.0, -y))
    assert set(FUNCTIONS) == set(UNARY) | {"atan2", "min", "max", "where"}


def test_values_of_the_issue_examples():
    close(ev("0.8 * y"), 0.8 * y)
    close(ev("-sin(pi*x)*cos(pi*y)"), -np.sin(np.pi * x) * np.cos(np.pi * y))
    close(ev("cos(pi*x)*sin(pi*y)"), np.cos(np.pi * x) * np.sin(np.pi * y))
    close(ev("-1000*9.81*(0.5 - y)"), -1000 * 9.81 * (0.5 - y))
    close(ev("sqrt(x**2 + y**2 + z**2)", X3), np.sqrt(x**2 + y**2 + z**2))


def test_precedence_and_associativity_are_pythons():
    close(ev("1 + 2 * 3"), 7.0)
    close(ev("(1 + 2) * 3"), 9.0)
    close(ev("2 ** 3 ** 2"), 512.0)          # right-associative
    close(ev("-2 ** 2"), -4.0)               # ** binds tighter than unary minus
    close(ev("-x ** 2"), -(x**2))
    close(ev("2 ** -1"), 0.5)
    close(ev("x - y - 1"), (x - y) - 1)      # left-associative
    close(ev("x / y / 2"), (x / y) / 2)
    close(ev("+x - -y"), x + y)
    close(ev("8 / 2 * 4"), 16.0)             # not 1: / and * left to right
    close(ev("((((x))))"), x)
    close(ev("(" * 150 + "x" + ")" * 150), x)  # parentheses make no tree nodes


def test_constants_and_numbers():
    close(ev("pi"), math.pi)
    close(ev("e"), math.e)
    close(ev("2.5e-3 * x + 1_000"), 2.5e-3 * x + 1000)
    close(ev("3"), 3.0)
    assert ev("0").dtype == np.float64 and ev("0").shape == (len(X2),)


def test_conditions():
    close(ev("where(0.3 < x < 0.6, 1, 0)"), ((0.3 < x) & (x < 0.6)).astype(float))
    close(ev("where(x < 0.5 and y > 0.5, 2, 3)"), np.where((x < 0.5) & (y > 0.5), 2.0, 3.0))
    close(ev("where(x < 0.2 or not y <= 0.5, 1, 0)"), ((x < 0.2) | (y > 0.5)).astype(float))
    close(ev("where(x == x, 1, 0) + where(x != x, 1, 0)"), 1.0)
    close(ev("where(x >= 0.5, x, 0)"), np.where(x >= 0.5, x, 0.0))


def test_dimensions_select_the_names():
    close(ev("x", X3[:, :1]), x)
    close(ev("z", X3), z)
    with pytest.raises(ValueError, match="unknown name 'y'; allowed: x, pi, e"):
        parse("y", 1)
    with pytest.raises(ValueError, match="unknown name 'z'; allowed: x, y, pi, e"):
        parse("z", 2)


def test_non_finite_values_come_back_without_warnings():
    with np.errstate(all="raise"):  # the evaluator silences them itself
        v = ev("log(x - 0.5)")
    assert np.isnan(v[x < 0.5]).all() and np.isfinite(v[x > 0.5]).all()
    assert np.isinf(ev("1 / (x - x)")).all()
    assert np.isinf(ev("10.0 ** 400")).all()


REFUSED = [
    ("q * 2", "unknown name 'q'; allowed: x, y, pi, e"),
    ("open(x)", "function 'open' is not allowed"),
    ("__import__('os')", "function '__import__' is not allowed"),
    ("x.real", "attribute access"),
    ("x[0]", "indexing"),
    ("lambda: 1", "lambda is not allowed"),
    ("1 if x else 2", "use where"),
    ("x % 2", "'%' is not allowed"),
    ("x // 2", "'//' is not allowed"),
    ("x ^ 2", "use \\*\\* for a power"),
    ("~x", "'~' is not allowed"),
    ("'a'", "'a' is not a number"),
    ("True", "True is not a number"),
    ("1j", "1j is not a number"),
    ("x < 1", "belongs in the first argument of where"),
    ("where(x, 1, 0)", "the first argument of where must be a comparison"),
    ("where(x is y, 1, 0)", "'is' is not allowed"),
    ("where(x in y, 1, 0)", "'in' is not allowed"),
    ("not x", "'not' belongs in the condition"),
    ("sin", "'sin' is a function: call it"),
    ("sin(x, y)", "sin\\(\\) takes 1 argument, got 2"),
    ("atan2(x)", "atan2\\(\\) takes 2 arguments, got 1"),
    ("max(x)", "max\\(\\) takes 2 or more arguments, got 1"),
    ("sin(x=1)", "no keyword arguments"),
    ("max(*x)", "'\\*' unpacking"),
    ("np.sin(x)", "only the listed functions may be called"),
    ("(x := 2)", "':=' is not allowed"),
    ("x, y", "a tuple"),
    ("[x]", "a list"),
    ("f'{x}'", "an f-string"),
    ("x +", "syntax error at the end"),
    ("x = 1", "syntax error at column 3 near '= 1'"),
    ("sin(x", "syntax error"),
    ("x = 1", "syntax error"),
    ("import os", "syntax error"),
    ("", "empty expression"),
    ("   ", "empty expression"),
    ("1" * 400, "too large for a float"),
    ("x\0", "syntax error"),
    ("+".join(["x"] * (MAX_NODES + 5)), "too long"),
    ("-(" * 70 + "x" + ")" * 70, "too long: at most 400 terms nested 60 deep"),
    ("(" * 300 + "x" + ")" * 300, "nested parentheses|nested too deep"),
    ("-" * 5000 + "x", "characters"),
]


@pytest.mark.parametrize("text,reason", REFUSED, ids=[r[0][:20] for r in REFUSED])
def test_refusals(text, reason):
    with pytest.raises(ValueError, match=reason):
        parse(text, 2)


def test_not_a_string():
    with pytest.raises(ValueError, match="expected a number or an expression string"):
        parse(["x"], 2)
