"""Tensioners (pivoted arm, slider): their kernel record and the static equilibrium of belt and
tensioners at installation.

Each tensioner carries one pulley on one coordinate q, the travel from the drawn position
(the pulley's ``center``), positive into the belt: the sense that lengthens the belt path, found
from the layout. With tensioners the belt's unstretched length, not a tension, is what is
installed: ``belt.length`` when given, else the length that has ``belt.pretension`` on the drawn
layout. At rest the tension is uniform, T(q) from the path length L(q) and that length, and
each tensioner balances its spring against the belt's hub force projected on d centre / dq:

    Q_spring(q) + F_hub(T(q), q) . dc/dq = 0      (one equation per tensioner)

solved first with the continuum tension (EA strain^e of the path), then corrected with the
discrete placement's tension (initial.initial_state), which the dynamic model starts from.
References: Beikmann, Perkins & Ulsoy, J. Vib. Acoust. 118 (1996) 406-413 (static equilibrium of
a belt drive with a dynamic tensioner); design note fead.md.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, root

from ..errors import ModelError
from ..tables import flatten, table
from . import _kernels as K
from .initial import initial_state
from .layout import compute_layout


@dataclass
class Equilibrium:
    """Static equilibrium of belt and tensioners (at rest)."""
    model: object          # the model with the tensioner pulleys at their equilibrium centres, belt.length set
    travel: np.ndarray     # q per tensioner (rad or m)
    tension: float         # belt tension at rest (N), discrete placement
    spring: np.ndarray     # spring load per tensioner at q (N m or N)
    hub: np.ndarray        # hub load magnitude per tensioner pulley (N)
    angle: np.ndarray      # arm angle psi (rad, counter-clockwise from x); nan for sliders
    stiffness: np.ndarray  # d(load)/d(travel) (na, na): the tensioners' stiffness against the belt
    residual: float = float("nan")   # largest load left on a tensioner after refine / its spring load


def indices(model) -> list[int]:
    return [j for j, p in enumerate(model.pulleys) if p.tensioner is not None]


def with_centres(model, centres: dict):
    """The model with the pulleys j in ``centres`` moved there (not validated: data only)."""
    pulleys = [p.model_copy(update={"center": tuple(centres[j])}) if j in centres else p
               for j, p in enumerate(model.pulleys)]
    return model.model_copy(update={"pulleys": pulleys})


def _moved(model, centres: dict, length: float):
    belt = model.belt.model_copy(update={"pretension": None, "length": float(length)})
    return with_centres(model, centres).model_copy(update={"belt": belt})


def arms_record(model, sense=None) -> K.Arms:
    """The kernel record of the model's tensioners (an empty record without). ``sense``: the
    +-1 per tensioner that points into the belt (``senses``)."""
    idx = indices(model)
    if sense is None:
        sense = senses(model) if idx else []
    T = [model.pulleys[j].tensioner for j in idx]
    f = lambda vals: np.array(vals, dtype=float)
    off, tx, ty = flatten([t.spring_table for t in T])
    kind, px, py, L, psi0, sgn, dx, dy, inertia = [], [], [], [], [], [], [], [], []
    for j, t, s in zip(idx, T, sense):
        c = model.pulleys[j].center
        if model.pulleys[j].arm is not None:
            kind.append(0)
            px.append(t.pivot[0])
            py.append(t.pivot[1])
            L.append(math.hypot(c[0] - t.pivot[0], c[1] - t.pivot[1]))
            psi0.append(math.atan2(c[1] - t.pivot[1], c[0] - t.pivot[0]))
            sgn.append(float(s))
            dx.append(0.0)
            dy.append(0.0)
            inertia.append(t.inertia)
        else:
            n = math.hypot(*t.direction)
            kind.append(1)
            px.append(c[0])
            py.append(c[1])
            L.append(0.0)
            psi0.append(0.0)
            sgn.append(1.0)
            dx.append(s * t.direction[0] / n)
            dy.append(s * t.direction[1] / n)
            inertia.append(t.mass)
    fields = dict(px=f(px), py=f(py), length=f(L), psi0=f(psi0), sgn=f(sgn), dx=f(dx), dy=f(dy),
                  inertia=f(inertia), preload=f([t.preload for t in T]), rate=f([t.rate for t in T]),
                  visc=f([t.damping for t in T]), fric=f([t.friction for t in T]),
                  asym=f([t.friction_asymmetry for t in T]), fv=f([t.friction_speed for t in T]),
                  qmin=f([t.stops[0] for t in T]), qmax=f([t.stops[1] for t in T]),
                  kstop=f([t.stop_stiffness for t in T]), cstop=f([t.stop_damping for t in T]))
    par = np.ascontiguousarray(np.column_stack([fields[k] for k in K.ARM_FIELDS]).reshape(len(idx), K.ARM_NPAR))
    return K.Arms(na=len(idx), pulley=np.array(idx, dtype=np.int64), kind=np.array(kind, dtype=np.int64),
                  tab_off=off, tab_x=tx, tab_y=ty, par=par, **fields)


def centre(model, j, q, s):
    """Centre of tensioner pulley j at travel q, sense s (before the record exists)."""
    p = model.pulleys[j]
    c = p.center
    if p.arm is not None:
        pv = p.arm.pivot
        L = math.hypot(c[0] - pv[0], c[1] - pv[1])
        psi = math.atan2(c[1] - pv[1], c[0] - pv[0]) + s * q
        return (pv[0] + L * math.cos(psi), pv[1] + L * math.sin(psi))
    d = np.array(p.slider.direction, float)
    d = s * d / np.linalg.norm(d)
    return (c[0] + q * d[0], c[1] + q * d[1])


def _path_length(model, centres: dict) -> float:
    return compute_layout(with_centres(model, centres)).length


def senses(model) -> list[float]:
    """+1 or -1 per tensioner: the sense of q that lengthens the belt path (pushes into the belt)."""
    out = []
    for j in indices(model):
        p = model.pulleys[j]
        arm = p.arm is not None
        eps = 1e-4 if arm else 1e-5       # rad, m
        try:
            dL = (_path_length(model, {j: centre(model, j, eps, 1.0)})
                  - _path_length(model, {j: centre(model, j, -eps, 1.0)})) / (2 * eps)
        except ModelError:
            dL = 0.0
        # the path must lengthen by at least 1e-3 of the travel at the pulley centre
        reach = math.hypot(p.center[0] - p.arm.pivot[0], p.center[1] - p.arm.pivot[1]) if arm else 1.0
        if not abs(dL) > 1e-3 * reach:
            what = "arm" if arm else "slider"
            raise ModelError(f"pulley {p.name!r}: moving the {what} does not change the belt's path (it moves the "
                             "pulley along the belt); it cannot tension it", field=f"pulleys.{j}.{what}")
        out.append(math.copysign(1.0, dL))
    return out


def _spring(t, q: float) -> float:
    """Spring load at travel q (the kernel's law without the stops: tables.table, extrapolated)."""
    if t.spring_table:
        rows = np.asarray(t.spring_table, dtype=float)
        return float(table(rows[:, 0], rows[:, 1], 0, len(rows), float(q), True))
    return t.preload - t.rate * q


def generalised_loads(model, idx, sense, qv, hub) -> np.ndarray:
    """Load on each tensioner's travel at travel qv (virtual work): its spring plus the belt's hub
    force ``hub`` (per pulley) projected on the pulley centre's motion per unit travel."""
    out = []
    for j, q, s in zip(idx, qv, sense):
        h = 1e-6 if model.pulleys[j].arm is not None else 1e-7
        c1, c0 = np.array(centre(model, j, q + h, s)), np.array(centre(model, j, q - h, s))
        out.append(_spring(model.pulleys[j].tensioner, q) + float(hub[j] @ ((c1 - c0) / (2 * h))))
    return np.array(out)


def equilibrium(model) -> Equilibrium:
    """Static equilibrium of the belt and the model's tensioners (ModelError when none exists
    within the stops, naming the tensioner and why)."""
    from .resolution import resolved

    model = resolved(model)
    idx = indices(model)
    sense = senses(model)
    belt = model.belt
    EA, e, n = belt.axial_stiffness, belt.axial_exponent, belt.segments
    if belt.length is not None:       # installed by length: the drawn layout may leave it slack
        L0_chain = L_eff = belt.length
        T_drawn = EA * max(compute_layout(model).length / L_eff - 1, 0.0) ** e
    else:
        init0 = initial_state(model, compute_layout(model))
        L0_chain = init0.seg_length * n                  # the installed (unstretched) chain length
        # continuum calibration: the discrete chain at the drawn layout has init0.tension on path L(0)
        L_eff = compute_layout(model).length / (1 + (init0.tension / EA) ** (1 / e))
        T_drawn = init0.tension

    def centres(qv):
        return {j: centre(model, j, q, s) for j, q, s in zip(idx, qv, sense)}

    def loads(qv, tension):
        """Generalised load on each tensioner (spring + belt) at travel qv under a uniform tension."""
        m = _moved(model, centres(qv), L0_chain)
        lay = compute_layout(m)
        return generalised_loads(model, idx, sense, qv, lay.hub_load_static(tension(m, lay)))

    def t_cont(m, lay):
        strain = lay.length / L_eff - 1
        return EA * max(strain, 0.0) ** e

    T = [model.pulleys[j].tensioner for j in idx]
    qmin = np.array([t.stops[0] for t in T])
    qmax = np.array([t.stops[1] for t in T])
    if len(idx) == 1:
        f = lambda q: float(loads([q], t_cont)[0])
        lo, hi = f(qmin[0]), f(qmax[0])
        if lo < 0:
            _no_equilibrium(model, idx[0], qmin[0], "the belt pushes the tensioner onto its stop: the spring cannot "
                            f"hold the belt tension ({T_drawn:.4g} N at the drawn position)")
        if hi > 0:
            slack = t_cont(None, compute_layout(_moved(model, centres([qmax[0]]), L0_chain))) <= 0
            _no_equilibrium(model, idx[0], qmax[0], "the belt is slack at the stop: the tensioner cannot reach it"
                            if slack else "the spring pushes the tensioner onto its stop into the belt")
        qv = np.array([brentq(f, qmin[0], qmax[0], xtol=1e-12)])
    else:
        sol = root(lambda qv: loads(qv, t_cont), np.zeros(len(idx)), method="hybr")
        qv = sol.x
        if not sol.success:
            raise ModelError(f"no static equilibrium of the tensioners found ({sol.message})", field="pulleys")
    T_rest = t_cont(None, compute_layout(_moved(model, centres(qv), L0_chain)))
    if len(idx) == 1 and T_rest < 0.05 * T_drawn:
        _no_equilibrium(model, idx[0], qv[0], f"the spring cannot hold the belt tension: it balances the belt "
                        f"at {T_rest:.3g} N, against {T_drawn:.4g} N at the drawn position")
    # the discrete placement's tension: Newton steps on q with the continuum's Jacobian
    t_disc = lambda m, lay: initial_state(m, lay).tension
    J = _jacobian(lambda v: loads(v, t_cont), qv)
    scale = np.array([max(abs(t.preload), abs(t.rate) * 0.01, 1e-3) for t in T])
    for _ in range(4):
        r = loads(qv, t_disc)
        if np.all(np.abs(r) < 1e-9 * scale):
            break
        qv = qv - np.linalg.solve(J, r)
    for a, j in enumerate(idx):
        if not qmin[a] <= qv[a] <= qmax[a]:
            _no_equilibrium(model, j, qv[a], "the equilibrium lies beyond the stops")
    moved = _moved(model, centres(qv), L0_chain)
    lay = compute_layout(moved)
    init = initial_state(moved, lay)
    hub = lay.hub_load_static(init.tension)
    angle = np.array([_arm_angle(model, j, q, s) for j, q, s in zip(idx, qv, sense)])
    return Equilibrium(moved, qv, init.tension, np.array([_spring(t, q) for t, q in zip(T, qv)]),
                       np.array([float(np.hypot(*hub[j])) for j in idx]), angle, J)


def hub_at_rest(sysm, x, y, cx, cy) -> np.ndarray:
    """Force (nk, 2) of the belt at rest (x, y segment centres) on each pulley: minus the contact
    normal forces of eq. 9 (no velocity, no friction at rest)."""
    C, P = sysm.contact, sysm.pulleys
    out = np.zeros((P.nk, 2))
    for j in range(P.nk):
        rx, ry = x - cx[j], y - cy[j]
        d = np.hypot(rx, ry)
        p = P.r[j] - d
        on = p > 0
        N = C.c1[on] * p[on] ** 2 + C.c2[on] * p[on]
        out[j] = -np.array([np.sum(N * rx[on] / d[on]), np.sum(N * ry[on] / d[on])])
    return out


def loads_at_rest(sysm, x, y, q) -> np.ndarray:
    """Generalised load (spring + belt) on each tensioner with the discrete belt at rest."""
    A = sysm.arms
    cx, cy = sysm.pulleys.cx.copy(), sysm.pulleys.cy.copy()
    jac = []
    for a in range(A.na):
        c = K.arm_centre(A, a, q[a])
        cx[A.pulley[a]], cy[A.pulley[a]] = c[0], c[1]
        jac.append(c[2:])
    hub = hub_at_rest(sysm, x, y, cx, cy)
    spring = [_spring(sysm.model.pulleys[A.pulley[a]].tensioner, q[a]) for a in range(A.na)]
    return np.array([spring[a] + hub[A.pulley[a]] @ jac[a] for a in range(A.na)])


def _arm_angle(model, j, q, s) -> float:
    p = model.pulleys[j]
    if p.arm is None:
        return float("nan")
    c, pv = p.center, p.arm.pivot
    return math.atan2(c[1] - pv[1], c[0] - pv[0]) + s * q


def _jacobian(f, x, h=1e-7):
    f0 = f(x)
    J = np.empty((len(f0), len(x)))
    for k in range(len(x)):
        xp = x.copy()
        xp[k] += h
        J[:, k] = (f(xp) - f0) / h
    return J


def _no_equilibrium(model, j, q, why):
    p = model.pulleys[j]
    what, unit = ("arm", "rad") if p.arm is not None else ("slider", "m")
    raise ModelError(f"tensioner on pulley {p.name!r}: no usable static equilibrium within the stops "
                     f"[{p.tensioner.stops[0]:.4g}, {p.tensioner.stops[1]:.4g}] {unit} ({why}; travel {q:.4g} {unit})",
                     field=f"pulleys.{j}.{what}")


def running(model, rest):
    """The tensioners' equilibrium under the running loads (creep theory, steady.py): travel q per
    tensioner such that the spring balances the hub force of the running span tensions (less the
    centrifugal tension, which the wrapped belt carries itself), the belt's unstretched length
    that of the installation. Returns (travel, model with the pulleys there and belt.length set,
    Steady), or None when no steady state exists (gross slip, accelerating drive) or no balance
    lies within the stops."""
    from .steady import steady_state

    idx = indices(model)
    sense = senses(model)
    lay0 = compute_layout(rest.model)
    L0 = lay0.length / (1 + (rest.tension / model.belt.axial_stiffness) ** (1 / model.belt.axial_exponent))
    T = [model.pulleys[j].tensioner for j in idx]

    def state(qv, with_margins=False):
        m = _moved(model, {j: centre(model, j, q, s) for j, q, s in zip(idx, qv, sense)}, L0)
        lay = compute_layout(m)
        return m, lay, steady_state(m, lay, with_margins=with_margins)

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
            out.append(_spring(t, q) + float(hub[j] @ jac))
        return np.array(out)

    try:
        if len(idx) == 1:
            # bracket the balance from the rest travel outwards over the stops (the ends may have
            # no steady state: a slack belt)
            f = lambda q: float(loads([q])[0])
            lo, hi = T[0].stops
            q0 = float(rest.travel[0])
            f0 = f(q0)
            bracket = None
            for step in np.geomspace(1e-4, 1.0, 25) * (hi - lo):
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
            qv = np.array([brentq(f, *bracket, xtol=1e-10)])
        else:
            sol = root(loads, np.array(rest.travel, float), method="hybr")
            if not sol.success:
                return None
            qv = sol.x
    except ValueError:
        return None
    m, lay, st = state(qv, with_margins=True)
    return qv, m, lay, st
