"""The stability chart in the (F0, V) plane (seed fig. 3): divergence, tongues, Floquet map.

``chart_variables`` returns the arrays of one grid as ``xarray`` variables keyed by name, with a
``suffix`` so that the full chart and the zoomed tongue can live in one Dataset.
"""
from __future__ import annotations

import numpy as np

from ...core.results import variable
from .floquet import floquet_chart, hill_parameters, multipliers
from .mathieu import exact_boundaries, first_order_boundaries, speed_band, tongue_centre_speed
from .quantities import critical_speed

UNSTABLE = 1.0 + 1e-6   # |lambda| above this is growth (RK4 keeps undamped |lambda| within ~1e-7 of 1)

REGION_STABLE, REGION_DIVERGENCE, REGION_PARAMETRIC = 0, 1, 2


def chart_variables(F0, V, setup, harm, tongues: int, floquet: bool, steps: int, suffix: str = ""):
    """Variables of one (F0, V) grid: critical speed, exact and first-order tongues, Floquet map."""
    sp, args = setup.span, (setup.teeth, setup.pitch, setup.convention)
    P, S = f"pretension{suffix}", f"speed{suffix}"
    out = {"critical_speed" + suffix: variable(critical_speed(F0, sp), (P,), "m/s", "critical speed V_cr(F0)")}
    lo, hi = [], []
    for n in range(1, tongues + 1):
        a, b = exact_boundaries(V, n, sp, harm.f1, *args)
        lo.append(a)
        hi.append(b)
    T = f"tongue{suffix}"
    out["tongue_low" + suffix] = variable(np.array(lo), (T, S), "N", "exact (Mathieu) tongue: lower pretension")
    out["tongue_high" + suffix] = variable(np.array(hi), (T, S), "N", "exact (Mathieu) tongue: upper pretension")
    a, b = first_order_boundaries(V, sp, harm.f1, *args)
    out["first_order_low" + suffix] = variable(a, (S,), "N", "first-order (seed) principal tongue: lower pretension")
    out["first_order_high" + suffix] = variable(b, (S,), "N", "first-order (seed) principal tongue: upper pretension")
    diverged = V[None, :] >= critical_speed(F0, sp)[:, None]
    region = np.where(diverged, REGION_DIVERGENCE, REGION_STABLE)
    if floquet:
        rho, trace = floquet_chart(F0, V, sp, harm.f1, harm.shape(), *args, steps_per_oscillation=steps)
        out["floquet_multiplier" + suffix] = variable(rho, (P, S), "1", "largest Floquet multiplier modulus (full Phi)")
        region = np.where(~diverged & (rho > UNSTABLE), REGION_PARAMETRIC, region)
    else:  # fall back on the exact tongues for the region map
        inside = np.zeros(diverged.shape, bool)
        for a, b in zip(lo, hi):
            inside |= (F0[:, None] > a[None, :]) & (F0[:, None] < b[None, :])
        region = np.where(~diverged & inside, REGION_PARAMETRIC, region)
    out["region" + suffix] = variable(region.astype(np.int8), (P, S), "1",
                                      "0 stable, 1 divergence (V > V_cr), 2 parametric resonance")
    coords = {P: variable(F0, (P,), "N", "pretension F0"), S: variable(V, (S,), "m/s", "belt speed V"),
              T: variable(np.arange(1, tongues + 1), (T,), "1", "tongue order n (omega ~ 2 Omega / n)")}
    return out, coords


def tongue_curves(F0_max, setup, harm, tongues: int, points: int = 600):
    """Exact and first-order boundaries on a fine speed axis covering the tongues up to F0_max.

    The chart's own speed grid is too coarse for the thin low-speed tongues (seed fig. 3a).
    """
    sp, args = setup.span, (setup.teeth, setup.pitch, setup.convention)
    vtop = 1.25 * float(tongue_centre_speed(F0_max, 1, sp, *args))
    V = np.linspace(vtop / points, vtop, points)
    lo, hi = zip(*(exact_boundaries(V, n, sp, harm.f1, *args) for n in range(1, tongues + 1)))
    a, b = first_order_boundaries(V, sp, harm.f1, *args)
    S = "speed_tongues"
    data = {
        "tongue_low_fine": variable(np.array(lo), ("tongue", S), "N", "exact tongue, lower pretension (fine speed axis)"),
        "tongue_high_fine": variable(np.array(hi), ("tongue", S), "N", "exact tongue, upper pretension (fine speed axis)"),
        "first_order_low_fine": variable(a, (S,), "N", "first-order tongue, lower pretension (fine speed axis)"),
        "first_order_high_fine": variable(b, (S,), "N", "first-order tongue, upper pretension (fine speed axis)"),
    }
    return data, {S: variable(V, (S,), "m/s", "belt speed on the tongues' axis")}


def zoom_ranges(model, setup, harm):
    """Default zoom window (seed fig. 3b): F0 within +- 6 F1 of the model's, V around the tongue."""
    z = model.chart.zoom
    F0 = setup.pretension
    width = max(6.0 * harm.f1, 0.05 * F0)
    pr = z.pretension if z.pretension is not None else (max(F0 - width, 0.0), F0 + width)
    if z.speed is not None:
        return pr, z.speed
    args = (setup.teeth, setup.pitch, setup.convention)
    v0, v1 = (float(tongue_centre_speed(f, 1, setup.span, *args)) for f in pr)
    pad = 0.15 * (v1 - v0) + 0.01 * v1
    return pr, (max(v0 - pad, 0.0), v1 + pad)


def floquet_band(F0, band, setup, harm, steps: int):
    """[v_low, v_high] of the principal tongue at F0 from Floquet with the full Phi (and damping).

    Scans a window around the exact band and refines the edges by bisection; None if the span is
    stable across the window (damping can close the tongue).
    """
    from scipy import optimize

    sp, args = setup.span, (setup.teeth, setup.pitch, setup.convention)
    a, b = harm.shape()

    def rho(v):
        al, be, ga = hill_parameters(F0, np.atleast_1d(v), sp, harm.f1, *args)
        return multipliers(al, be, ga, a, b, steps)[2]

    v0, v1 = band
    pad = 0.5 * (v1 - v0)
    grid = np.linspace(v0 - pad, v1 + pad, 201)
    unstable = rho(grid) > UNSTABLE
    if not unstable.any():
        return None
    i0, i1 = np.argmax(unstable), len(unstable) - 1 - np.argmax(unstable[::-1])
    if i0 == 0 or i1 == len(grid) - 1:
        return None  # not enclosed in the window: not this tongue
    g = lambda v: float(rho(v)[0]) - UNSTABLE  # noqa: E731
    lo = optimize.brentq(g, grid[i0 - 1], grid[i0], xtol=1e-10)
    hi = optimize.brentq(g, grid[i1], grid[i1 + 1], xtol=1e-10)
    return [float(lo), float(hi)]


def bands(setup, harm, tongues: int):
    """Speed bands at the model's pretension: exact tongues 1..tongues and first order."""
    args = (setup.teeth, setup.pitch, setup.convention)
    exact = [speed_band(setup.pretension, n, setup.span, harm.f1, *args) for n in range(1, tongues + 1)]
    first = speed_band(setup.pretension, 1, setup.span, harm.f1, *args, method="first-order")
    return exact, first
