"""A bracketed root finder without scipy.optimize (whose import was a quarter of ``drivedyn
check``'s wall time, and its brentq the only part of it check used): the ITP method of Oliveira &
Takahashi, "An Enhancement of the Bisection Method Average Performance Preserving Minmax
Optimality", ACM Trans. Math. Softw. 47 (2020) 5: regula falsi, truncated toward the midpoint and
projected into bisection's minmax interval, so it converges superlinearly on smooth functions and
never takes more steps than bisection plus one."""
from __future__ import annotations

import math

#: the tolerances' defaults (scipy.optimize.brentq's) and the paper's suggested kappa_2, n_0
XTOL = 2e-12
RTOL = 4 * 2.220446049250313e-16
KAPPA2 = 2.0
N0 = 1


def _value(f, x) -> float:
    y = float(f(x))
    if math.isnan(y):
        raise ValueError("the function value is NaN: the root finder cannot continue")
    return y


def _half_tolerance(a, b, xtol, rtol) -> float:
    """Half of xtol + rtol |x| for the smallest |x| in [a, b]."""
    return 0.5 * (xtol + rtol * (0.0 if a < 0.0 < b else min(abs(a), abs(b))))


def find_root(f, a: float, b: float, xtol: float = XTOL, rtol: float = RTOL, maxiter: int = 200) -> float:
    """A root x of f in [a, b], where f(a) and f(b) have opposite signs, within xtol + rtol |x|. Raises ValueError without a sign change or at a NaN, RuntimeError when
    it does not converge within maxiter evaluations (the tolerances below what the floats resolve)."""
    if xtol <= 0 or rtol < 0:
        raise ValueError(f"tolerances must be positive (xtol {xtol:g}, rtol {rtol:g})")
    a, b = float(a), float(b)
    if a > b:
        a, b = b, a
    fa, fb = _value(f, a), _value(f, b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        raise ValueError("f(a) and f(b) must have different signs")
    eps = _half_tolerance(a, b, xtol, rtol)
    n_max = max(0, math.ceil(math.log2((b - a) / (2.0 * eps)))) + N0
    kappa1 = 0.2 / (b - a)
    for j in range(maxiter):
        if b - a <= 2.0 * _half_tolerance(a, b, xtol, rtol):
            return 0.5 * (a + b)
        half = 0.5 * (a + b)
        r = eps * 2.0 ** (n_max - j) - 0.5 * (b - a)
        delta = kappa1 * (b - a) ** KAPPA2
        xf = (b * fa - a * fb) / (fa - fb)            # regula falsi
        sigma = 1.0 if half >= xf else -1.0
        xt = xf + sigma * delta if delta <= abs(half - xf) else half      # truncated toward the midpoint
        x = xt if abs(xt - half) <= r else half - sigma * r               # projected into the minmax interval
        if not a < x < b:                                                 # rounding at the bracket's ends
            x = half
        y = _value(f, x)
        if y == 0.0:
            return x
        if (y > 0.0) == (fa > 0.0):
            a, fa = x, y
        else:
            b, fb = x, y
    raise RuntimeError(f"the root finder did not converge in {maxiter} evaluations (bracket [{a!r}, {b!r}])")
