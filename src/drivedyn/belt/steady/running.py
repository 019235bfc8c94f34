"""The tensioners' running balance (creep theory): where the arms settle under the running span
tensions, the belt's unstretched length that of the installation.

The installed length is the rest state's, measured as creep theory measures a running belt (each
span's length over 1 + T/EA plus the wraps' belt sunk into the groove by the contact law,
geometry/rest.py), so that with no load and no speed the balance is the rest state itself (its
travel and tension: tests/belt/test_running_balance.py)."""
from __future__ import annotations

import math

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from ...mechanics.layout import compute_layout
from ..geometry.tensioner import moved_to, spring_load, centre, indices, senses


def running(model, rest, torques=None, speed=None):
    """The tensioners' equilibrium under the running loads (running_balance), or None where there is
    none (running_balance says why)."""
    return running_balance(model, rest, torques, speed)[0]


def running_balance(model, rest, torques=None, speed=None):
    """The tensioners' equilibrium under the running loads (creep theory, steady/creep.py; ``torques``
    (N m per pulley) and ``speed`` (belt m/s, signed along the listed order) instead of the model's,
    as creep.steady_state's loads and speed): travel q per
    tensioner such that the spring balances the hub force of the running span tensions (less the
    centrifugal tension, which the wrapped belt carries itself), the belt's unstretched length
    that of the installation. Returns ((travel, model with the pulleys there and belt.length set,
    Steady), "") or (None, why) when no steady state exists at any arm position (gross slip, a slack
    span, an accelerating drive) or the balance lies beyond a stop (the arm rests on it).

    Under load the tight spans stretch and the arm moves into the belt to take the length up: on a
    stiff belt with a soft spring, far from its rest travel, where the belt at the rest travel
    may not even hold the loads (it slips there). The search therefore walks out from the rest
    travel to both stops and brackets the balance between two arm positions that both run."""
    from ..geometry.rest import belt_content
    from .creep import steady_state

    idx = indices(model)
    sense = senses(model)
    # the unstretched belt the rest layout holds at the rest tension, as creep theory counts it
    L0 = belt_content(model, compute_layout(rest.model), rest.tension)
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
        if st.state not in ("running", "at rest") or st.gross_slip or not all(math.isfinite(t) for t in st.spans.values()):
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

    if len(idx) == 1:
        qv, why = _single(loads, T[0].stops, float(rest.travel[0]), state)
        if qv is None:
            return None, why
    else:
        # (two or more tensioners only: check's import stays light)
        from scipy.optimize import root

        try:
            sol = root(loads, np.array(rest.travel, float), method="hybr")
        except ValueError:
            return None, "no running balance of the tensioners: no steady state near their rest travel"
        if not sol.success:
            return None, f"no running balance of the tensioners found ({sol.message})"
        qv = sol.x
    m, lay, st = state(qv, with_margins=True)
    return (qv, m, lay, st), ""


def _single(loads, stops, q0, state):
    """The one tensioner's running balance: (travel, "") or (None, why). The load on the arm
    (spring + belt) is sampled outwards from the rest travel to both stops; the balance is the sign
    change nearest the rest travel between two samples that both have a steady state."""
    lo, hi = stops
    q0 = min(max(q0, lo), hi)
    seen = {}

    def f(q):                      # the load on the arm, None where the drive has no steady state
        if q not in seen:
            try:
                seen[q] = float(loads([q])[0])
            except ValueError:
                seen[q] = None
        return seen[q]

    def ok(a, b):
        fa, fb = f(a), f(b)
        return fa is not None and fb is not None and fa * fb <= 0

    bracket = None
    f0 = f(q0)
    # a secant from the rest travel first (the balance is smooth there): a bracket in three
    # solves where the outward search below takes about thirty
    d = 1e-3 * (hi - lo)
    f1 = f(q0 + d) if f0 is not None and q0 + d <= hi else None
    if f1 is not None and f1 != f0:
        qs = q0 - f0 * d / (f1 - f0)
        w = max(0.25 * abs(qs - q0), d)
        a, b = max(lo, qs - w), min(hi, qs + w)
        if a < b and ok(a, b):
            bracket = (a, b)
    if bracket is None:
        prev, done = {1: q0, -1: q0}, set()
        for step in np.geomspace(1e-4, 1.0, 25) * (hi - lo):
            for side in (1, -1):
                if side in done:
                    continue
                q = min(max(q0 + side * step, lo), hi)
                if q == prev[side]:          # at the stop already
                    done.add(side)
                    continue
                if ok(prev[side], q):
                    bracket = (min(q, prev[side]), max(q, prev[side]))
                    break
                prev[side] = q
            if bracket:
                break
    if bracket is None:
        return None, _why_none(seen, q0, lo, hi, state)
    return np.array([find_root(lambda q: f(q), *bracket, xtol=1e-10)]), ""


def _why_none(seen, q0, lo, hi, state):
    """Why no balance was bracketed, from the samples (arm travel -> load on the arm or None)."""
    run = {q: v for q, v in seen.items() if v is not None}
    if not run:
        # no arm position runs: name the pulley that slips (or the slack span) at the rest travel
        q = q0
        try:
            st = state([q])[2]
            what = (f"pulley {st.gross_slip} slips over its whole wrap" if st.gross_slip
                    else "a span would go slack (T below m v^2)")
        except (ModelError, TypeError, ValueError, ZeroDivisionError):
            what = "the belt is slack"
        return f"no steady state at any arm position between its stops: {what}"
    # the load on the arm at the sample nearest each stop: the side the balance lies beyond
    near = run[min(run, key=lambda q: abs(q - lo))] if all(v < 0 for v in run.values()) else None
    if near is not None:
        return (f"the running span tensions push the arm onto its stop away from the belt (the spring "
                f"{-near:.3g} N m short of holding them there)")
    far = run[min(run, key=lambda q: abs(q - hi))]
    return (f"the spring swings the arm onto its stop into the belt (the running tensions {far:.3g} N m short of "
            "holding it off)")
