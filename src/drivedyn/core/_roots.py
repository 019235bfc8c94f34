"""A bracketed root finder without scipy.optimize (whose import was a quarter of ``drivedyn
check``'s wall time, and its brentq the only part of it check used): Chandrupatla's method, T. R.
Chandrupatla, "A new hybrid quadratic/bisection algorithm for finding the zero of a nonlinear
function without using derivatives", Advances in Engineering Software 28 (1997) 145-149. Each step
is inverse quadratic interpolation through the bracket's ends and the point last discarded where
that parabola is single-valued over the bracket, else bisection; at least a tolerance from either
end, so the bracket always shrinks."""
from __future__ import annotations

import math

#: the tolerances' defaults (scipy.optimize.brentq's, which the callers were written against)
XTOL = 2e-12
RTOL = 4 * 2.220446049250313e-16


def _value(f, x) -> float:
    y = float(f(x))
    if math.isnan(y):
        raise ValueError("the function value is NaN: the root finder cannot continue")
    return y


def find_root(f, a: float, b: float, xtol: float = XTOL, rtol: float = RTOL, maxiter: int = 200) -> float:
    """A root x of f in [a, b], where f(a) and f(b) have opposite signs, within xtol + rtol |x|. Raises
    ValueError without a sign change or at a NaN, RuntimeError when it does not converge within
    maxiter evaluations (the tolerances below what the floats resolve)."""
    if xtol <= 0 or rtol < 0:
        raise ValueError(f"tolerances must be positive (xtol {xtol:g}, rtol {rtol:g})")
    a, b = float(a), float(b)
    fa, fb = _value(f, a), _value(f, b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        raise ValueError("f(a) and f(b) must have different signs")
    c, fc = a, fa          # the point last discarded: the parabola's third
    t = 0.5                # the next point's place in the bracket, from a toward b
    for _ in range(maxiter):
        x = a + t * (b - a)
        fx = _value(f, x)
        if (fx > 0.0) == (fa > 0.0):
            c, fc = a, fa
        else:
            c, fc, b, fb = b, fb, a, fa
        a, fa = x, fx      # the bracket is [a, b] (either order), a the newest point
        xm, fm = (a, fa) if abs(fa) < abs(fb) else (b, fb)
        tol = 0.5 * (xtol + rtol * abs(xm))
        if fm == 0.0 or abs(b - a) <= 2.0 * tol:
            return xm
        tl = tol / abs(b - a)
        xi = (a - b) / (c - b)
        phi = (fa - fb) / (fc - fb)
        if phi * phi < xi and (1.0 - phi) ** 2 < 1.0 - xi:      # the inverse parabola is monotone here
            t = fa / (fb - fa) * fc / (fb - fc) + (c - a) / (b - a) * fa / (fc - fa) * fb / (fc - fb)
        else:
            t = 0.5
        t = min(1.0 - tl, max(tl, t))
    raise RuntimeError(f"the root finder did not converge in {maxiter} evaluations (bracket [{a!r}, {b!r}])")
