"""The belt drive at rest as the continuum holds it: the unstretched belt length installed
(``belt.length``, or what the drawn path holds at the pretension with the belt sunk into each wrap)
and the tensioners' travel and the uniform belt tension at rest (virtual work). The rotational model
starts from it and the modes are taken about it."""
from __future__ import annotations

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from . import tensioner as TN
from ...mechanics.layout import Layout, compute_layout
from .placement import penetration


def installed_length(model, lay: Layout) -> float:
    """Unstretched belt length: ``belt.length``, or what the drawn path holds at the pretension with
    the belt sunk into each wrap by its static depth (as creep.drive_of)."""
    b = model.belt
    return float(b.length) if b.length is not None else belt_content(model, lay, b.pretension)


def belt_content(model, lay: Layout, T: float) -> float:
    """Unstretched belt the path of ``lay`` holds at a uniform tension T at rest (a synchronous belt's
    pitch line runs on a grooved pulley's pitch radius: it sinks into the smooth ones only)."""
    EA = model.belt.axial_stiffness
    smooth = np.array([not p.teeth for p in model.pulleys], dtype=float)
    sunk = float(np.sum(smooth * lay.wrap * penetration(T / np.abs(lay.rho), model.contact.stiffness_quadratic,
                                                model.contact.stiffness_linear)))
    return (lay.length - sunk) / (1 + T / EA)


def tension_at(model, lay: Layout, L0: float) -> float:
    """Uniform tension at rest at which the path of ``lay`` holds L0 (0 when it is slack)."""
    f = lambda T: belt_content(model, lay, T) - L0
    if f(0.0) <= 0:
        return 0.0
    hi = 1.0
    while f(hi) > 0:
        hi *= 2
        if hi > 1e3 * model.belt.axial_stiffness:
            raise ModelError("no belt tension holds this installation (belt length?)", field="belt")
    return find_root(f, 0.0, hi, xtol=1e-10, rtol=1e-13)


def rest_state(model, L0: float, drawn: Layout | None = None, sense=None):
    """Tensioners' travel and the belt's uniform tension at rest (virtual work: spring load plus
    the hub force's component along the pulley's travel vanish), and the layout there. ``drawn``
    and ``sense`` (tensioner.senses), when the caller has them, are not derived again."""
    idx = TN.indices(model)
    if not idx:
        lay = drawn or compute_layout(model)
        return np.zeros(0), tension_at(model, lay, L0), lay
    sense = TN.senses(model) if sense is None else sense

    def at(qv):
        m = TN.with_centres(model, {j: TN.centre(model, j, q, s) for j, q, s in zip(idx, qv, sense)})
        return compute_layout(m)

    def loads(qv):
        lay = at(qv)
        return TN.generalised_loads(model, idx, sense, qv, lay.hub_load_static(tension_at(model, lay, L0)))

    ts = [model.pulleys[j].tensioner for j in idx]
    if len(idx) == 1:
        lo, hi = ts[0].stops
        f = lambda q: float(loads([q])[0])
        if f(lo) < 0 or f(hi) > 0:
            raise ModelError(f"pulley {model.pulleys[idx[0]].name!r}: no static equilibrium of the tensioner between "
                             "its stops (spring against belt tension)", field=f"pulleys.{idx[0]}.tensioner")
        qv = np.array([find_root(f, lo, hi, xtol=1e-13)])
    else:
        # (two or more tensioners only: check's import stays light)
        from scipy.optimize import root

        sol = root(loads, np.zeros(len(idx)), method="hybr")
        if not sol.success:
            raise ModelError(f"no static equilibrium of the tensioners found ({sol.message})", field="pulleys")
        qv = sol.x
    lay = at(qv)
    return qv, tension_at(model, lay, L0), lay
