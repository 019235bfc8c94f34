"""Brent's bracketed root finder, step for step as scipy.optimize.brentq takes it (the same
iterates, so the same root to the bit), without importing scipy.optimize: that import was a
quarter of ``drivedyn check``'s wall time, and brentq the only part of it check uses."""
from __future__ import annotations

import math

#: scipy's defaults: xtol, the smallest rtol (4 machine epsilons), iterations
XTOL = 2e-12
RTOL = 4 * 2.220446049250313e-16
MAXITER = 100


def _value(f, x) -> float:
    y = float(f(x))
    if math.isnan(y):
        raise ValueError("The function value is NaN; solver cannot continue")
    return y


def brentq(f, a: float, b: float, xtol: float = XTOL, rtol: float = RTOL, maxiter: int = MAXITER) -> float:
    """A root of f in [a, b] (f(a) and f(b) of opposite signs): within xtol + rtol |x|. Raises
    ValueError as scipy does (no sign change, a NaN, bad tolerances), RuntimeError when it does not
    converge within maxiter iterations."""
    if xtol <= 0:
        raise ValueError(f"xtol too small ({xtol:g} <= 0)")
    if rtol < RTOL:
        raise ValueError(f"rtol too small ({rtol:g} < {RTOL:g})")
    xpre, xcur = float(a), float(b)
    fpre, fcur = _value(f, xpre), _value(f, xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError("f(a) and f(b) must have different signs")
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre          # the bracket's other end
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):             # xcur the better of the two
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:                  # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                             # inverse quadratic
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre = scur = sbis
        else:
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = _value(f, xcur)
    raise RuntimeError(f"Failed to converge after {maxiter} iterations, value is {xcur}")
