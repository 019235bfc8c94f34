"""drivedyn's brentq takes scipy.optimize.brentq's steps: the same root to the bit, the same errors."""
import math

import numpy as np
import pytest
from scipy import optimize

from drivedyn._brent import brentq


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
            f = lambda x, r=root: np.float64(np.cbrt(x - r))
        a, b = root - rng.uniform(0.1, 3), root + rng.uniform(0.1, 3)
        tols = [{}, {"xtol": 1e-13}, {"xtol": 1e-10, "rtol": 1e-13}, {"xtol": 1e-6, "rtol": 1e-5}][rng.integers(4)]
        yield f, a, b, tols


def _outcome(solve, f, a, b, tols):
    try:
        return solve(f, a, b, **tols)
    except ValueError as exc:
        return str(exc)


def test_the_same_root_as_scipy_to_the_bit():
    roots = 0
    for f, a, b, tols in _cases():
        mine = _outcome(brentq, f, a, b, tols)
        assert mine == _outcome(optimize.brentq, f, a, b, tols)
        roots += isinstance(mine, float)
    assert roots > 250


def test_the_same_errors_as_scipy():
    with pytest.raises(ValueError, match="different signs"):
        brentq(lambda x: x * x + 1, -1.0, 1.0)
    with pytest.raises(ValueError, match="NaN"):
        brentq(lambda x: math.nan if x > 0.5 else x - 0.7, 0.0, 1.0)
    for solve in (brentq, optimize.brentq):
        with pytest.raises(RuntimeError, match="converge"):
            solve(lambda x: x ** 3 - 0.3, 0.0, 1.0, xtol=1e-300, maxiter=3)
    assert brentq(lambda x: x, 0.0, 1.0) == 0.0 == optimize.brentq(lambda x: x, 0.0, 1.0)
