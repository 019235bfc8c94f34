"""The tensioners' running balance (creep theory): where the arms settle under the running span
tensions, the belt's unstretched length that of the installation."""
from __future__ import annotations

import math

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from ...mechanics.layout import compute_layout
from ..geometry.tensioner import moved_to, spring_load, centre, indices, senses


def running(model, rest, torques=None, speed=None):
    """The tensioners' equilibrium under the running loads (creep theory, steady/creep.py; ``torques``
    (N m per pulley) and ``speed`` (belt m/s, signed along the listed order) instead of the model's,
    as creep.steady_state's loads and speed): travel q per
    tensioner such that the spring balances the hub force of the running span tensions (less the
    centrifugal tension, which the wrapped belt carries itself), the belt's unstretched length
    that of the installation. Returns (travel, model with the pulleys there and belt.length set,
    Steady), or None when no steady state exists (gross slip, accelerating drive) or no balance
    lies within the stops."""
    from ..steady.creep import steady_state

    idx = indices(model)
    sense = senses(model)
    lay0 = compute_layout(rest.model)
    L0 = lay0.length / (1 + (rest.tension / model.belt.axial_stiffness) ** (1 / model.belt.axial_exponent))
    T = [model.pulleys[j].tensioner for j in idx]

    def state(qv, with_margins=False):
        m = moved_to(model, {j: centre(model, j, q, s) for j, q, s in zip(idx, qv, sense)}, L0)
        lay = compute_layout(m)
        return m, lay, steady_state(m, lay, loads=torques, speed=speed, with_margins=with_margins)

    def loads(qv):
        try:
            m, lay, st = state(qv)
        except (ModelError, TypeError, ValueError, ZeroDivisionError):   # slack belt, no layout
            raise ValueError("no steady state") from None
        if st.state != "running" or st.gross_slip or not all(math.isfinite(t) for t in st.spans.values()):
            raise ValueError("no steady state")
        hub = np.zeros((len(lay.names), 2))
        for sp in lay.spans:
            u = np.array([math.cos(sp.angle), math.sin(sp.angle)])
            t = st.spans[sp.name] - st.centrifugal
            hub[sp.start] += t * u
            hub[sp.end] -= t * u
        out = []
        for j, q, s, t in zip(idx, qv, sense, T):
            h = 1e-6 if model.pulleys[j].arm is not None else 1e-7
            jac = (np.array(centre(model, j, q + h, s)) - np.array(centre(model, j, q - h, s))) / (2 * h)
            out.append(spring_load(t, q) + float(hub[j] @ jac))
        return np.array(out)

    try:
        if len(idx) == 1:
            # bracket the balance from the rest travel outwards over the stops (the ends may have
            # no steady state: a slack belt)
            seen = {}       # the root finder starts from the bracket's ends, already evaluated by the search

            def f(q):
                if q not in seen:
                    seen[q] = float(loads([q])[0])
                return seen[q]

            lo, hi = T[0].stops
            q0 = float(rest.travel[0])
            f0 = f(q0)
            bracket = None
            # a secant from the rest travel first (the balance is smooth there): a bracket in three
            # solves where the outward search below takes about thirty
            d = 1e-3 * (hi - lo)
            try:
                f1 = f(q0 + d) if q0 + d <= hi else None
                if f1 is not None and f1 != f0:
                    qs = q0 - f0 * d / (f1 - f0)
                    w = max(0.25 * abs(qs - q0), d)
                    a, b = max(lo, qs - w), min(hi, qs + w)
                    if a < b and f(a) * f(b) <= 0:
                        bracket = (a, b)
            except ValueError:
                bracket = None
            for step in (np.geomspace(1e-4, 1.0, 25) * (hi - lo) if bracket is None else ()):
                for q in (q0 + step, q0 - step):
                    if not lo <= q <= hi:
                        continue
                    try:
                        if f(q) * f0 <= 0:
                            bracket = (min(q, q0), max(q, q0))
                    except ValueError:
                        continue
                    if bracket:
                        break
                if bracket:
                    break
            if bracket is None:
                return None
            qv = np.array([find_root(f, *bracket, xtol=1e-10)])
        else:
            # (two or more tensioners only: check's import stays light)
            from scipy.optimize import root

            sol = root(loads, np.array(rest.travel, float), method="hybr")
            if not sol.success:
                return None
            qv = sol.x
    except ValueError:
        return None
    m, lay, st = state(qv, with_margins=True)
    return qv, m, lay, st
