"""drivedyn's bracketed root finder (Chandrupatla's method, _roots.py) against functions whose root is
known: within its tolerance, in less than half bisection's evaluations on smooth functions and never
more than bisection's plus the two ends on any of these, and the errors its callers catch."""
import math

import numpy as np
import pytest

from drivedyn.core._roots import find_root


def _cases():
    rng = np.random.default_rng(7)
    for _ in range(300):
        c = rng.uniform(-3, 3, 4)
        root = rng.uniform(-2, 2)
        kind = rng.integers(4)
        if kind == 0:
            f = lambda x, c=c, r=root: (x - r) * (1 + c[0] ** 2 + c[1] ** 2 * (x - r) ** 2)
        elif kind == 1:
            f = lambda x, c=c, r=root: math.expm1(c[0] * (x - r)) + c[1] ** 2 * (x - r) if c[0] else x - r
        elif kind == 2:
            f = lambda x, c=c, r=root: math.atan(5 * (x - r)) + 0.1 * c[2] * math.sin(x - r) ** 2
        else:
            f = lambda x, r=root: np.float64(np.cbrt(x - r))       # not smooth at the root
        a, b = root - rng.uniform(0.1, 3), root + rng.uniform(0.1, 3)
        tols = [{}, {"xtol": 1e-13}, {"xtol": 1e-10, "rtol": 1e-13}, {"xtol": 1e-6, "rtol": 1e-5}][rng.integers(4)]
        yield f, root, a, b, tols, kind


def test_roots_within_the_tolerance_in_fewer_steps_than_bisection():
    smooth_calls, smooth_bisection, roots = 0, 0, 0
    for f, root, a, b, tols, kind in _cases():
        if (f(a) > 0) == (f(b) > 0):      # not bracketed (an exp against a line): the error test below
            continue
        roots += 1
        calls = [0]

        def g(x, f=f, calls=calls):
            calls[0] += 1
            return f(x)

        x = find_root(g, a, b, **tols)
        xtol, rtol = tols.get("xtol", 2e-12), tols.get("rtol", 8.9e-16)
        assert abs(x - root) <= xtol + rtol * abs(root) + 4e-16 * abs(root)
        smallest = 0.0 if a < 0.0 < b else min(abs(a), abs(b))
        bisection = math.ceil(math.log2((b - a) / (xtol + rtol * smallest)))
        assert calls[0] <= bisection + 2              # and the two ends
        if kind != 3:
            smooth_calls += calls[0]
            smooth_bisection += bisection
    assert roots > 250
    assert smooth_calls < 0.5 * smooth_bisection      # superlinear where f is smooth


def test_the_errors_its_callers_catch():
    with pytest.raises(ValueError, match="different signs"):
        find_root(lambda x: x * x + 1, -1.0, 1.0)
    with pytest.raises(ValueError, match="NaN"):
        find_root(lambda x: math.nan if x > 0.5 else x - 0.7, 0.0, 1.0)
    with pytest.raises(RuntimeError, match="converge"):
        find_root(lambda x: x ** 3 - 0.3, 0.0, 1.0, xtol=1e-300, rtol=0.0, maxiter=3)
    assert find_root(lambda x: x, 0.0, 1.0) == 0.0
    assert find_root(lambda x: x - 2.0, 3.0, 1.0) == pytest.approx(2.0, abs=2e-12)      # ends in either order
