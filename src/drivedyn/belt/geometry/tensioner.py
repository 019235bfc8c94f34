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
discrete placement's tension (placement.initial_state), which the dynamic model starts from.
References: Beikmann, Perkins & Ulsoy, J. Vib. Acoust. 118 (1996) 406-413 (static equilibrium of
a belt drive with a dynamic tensioner); design note fead.md.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from ...core.tables import table
from .placement import initial_state
from ...mechanics.layout import compute_layout


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


def moved_to(model, centres: dict, length: float):
    belt = model.belt.model_copy(update={"pretension": None, "length": float(length)})
    return with_centres(model, centres).model_copy(update={"belt": belt})


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


def spring_load(t, q: float) -> float:
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
        out.append(spring_load(model.pulleys[j].tensioner, q) + float(hub[j] @ ((c1 - c0) / (2 * h))))
    return np.array(out)


def equilibrium(model, drawn=None, sense=None) -> Equilibrium:
    """Static equilibrium of the belt and the model's tensioners (ModelError when none exists
    within the stops, naming the tensioner and why). ``drawn`` (the drawn layout) and ``sense``
    (``senses``), when the caller has them (drive.Drive), are not derived again."""
    from .segment_count import resolved

    model = resolved(model)
    idx = indices(model)
    sense = senses(model) if sense is None else sense
    drawn = drawn or compute_layout(model)
    belt = model.belt
    EA, e, n = belt.axial_stiffness, belt.axial_exponent, belt.segments
    dL = _curves_length(model, drawn)
    if belt.length is not None:       # installed by length: the drawn layout may leave it slack
        L0_chain = L_eff = belt.length
        T_drawn = EA * max((drawn.length + dL) / L_eff - 1, 0.0) ** e
    else:
        init0 = initial_state(model, drawn)
        L0_chain = init0.seg_length * n                  # the installed (unstretched) chain length
        # continuum calibration: the discrete chain at the drawn layout has init0.tension on path L(0)
        L_eff = (drawn.length + dL) / (1 + (init0.tension / EA) ** (1 / e))
        T_drawn = init0.tension

    def centres(qv):
        return {j: centre(model, j, q, s) for j, q, s in zip(idx, qv, sense)}

    def layout_at(m, qv):
        try:
            return compute_layout(m)
        except ModelError as exc:
            # the drawn layout passed: at this travel (a stop, or on the way to it) the tensioner takes
            # the belt off its loop, and the fault is the tensioner's travel, not the belt order
            _off_the_loop(model, idx, qv, str(exc).split(": ", 1)[-1])

    def loads(qv, tension):
        """Generalised load on each tensioner (spring + belt) at travel qv under a uniform tension."""
        m = moved_to(model, centres(qv), L0_chain)
        lay = layout_at(m, qv)
        return generalised_loads(model, idx, sense, qv, lay.hub_load_static(tension(m, lay)))

    def t_cont(m, lay):
        strain = (lay.length + dL) / L_eff - 1
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
            slack = t_cont(None, compute_layout(moved_to(model, centres([qmax[0]]), L0_chain))) <= 0
            _no_equilibrium(model, idx[0], qmax[0], "the belt is slack at the stop: the tensioner cannot reach it"
                            if slack else "the spring pushes the tensioner onto its stop into the belt")
        qv = np.array([find_root(f, qmin[0], qmax[0], xtol=1e-12)])
    else:
        # (two or more tensioners only: check's import stays light)
        from scipy.optimize import root

        sol = root(lambda qv: loads(qv, t_cont), np.zeros(len(idx)), method="hybr")
        qv = sol.x
        if not sol.success:
            raise ModelError(f"no static equilibrium of the tensioners found ({sol.message})", field="pulleys")
    T_rest = t_cont(None, compute_layout(moved_to(model, centres(qv), L0_chain)))
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
    moved = moved_to(model, centres(qv), L0_chain)
    lay = compute_layout(moved)
    init = initial_state(moved, lay)
    hub = lay.hub_load_static(init.tension)
    angle = np.array([arm_angle(model, j, q, s) for j, q, s in zip(idx, qv, sense)])
    return Equilibrium(moved, qv, init.tension, np.array([spring_load(t, q) for t, q in zip(T, qv)]),
                       np.array([float(np.hypot(*hub[j])) for j in idx]), angle, J)


def _curves_length(model, drawn) -> float:
    """What the pulleys' pitch curves (at their rest angles) add to the circles' path length at the drawn
    centres (m; 0 without curves): the continuum equilibrium takes it as constant over the tensioners'
    travel (its change with the travel is of second order), the discrete placement walks the curves."""
    if not any(p.pitch_curve is not None for p in model.pulleys):
        return 0.0
    from ...mechanics.curve_layout import layout_at as curve_layout

    ps = model.pulleys
    cl = curve_layout([p.name for p in ps], drawn.centers, [p.curve for p in ps], [p.side for p in ps],
                      orientation=drawn.orientation)
    return float(cl.length - drawn.length)


def arm_angle(model, j, q, s) -> float:
    """Arm angle (rad, counter-clockwise from x) of tensioner pulley j at travel q, sense s; nan for a slider."""
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


def _off_the_loop(model, idx, qv, why):
    """A tensioner travel (within the stops) at which the belt no longer makes its loop: one line
    naming the tensioner, the travel and its stops (for an arm with supplier data, the free arm and
    the load stop they come from)."""
    parts = []
    for j, q in zip(idx, qv):
        p = model.pulleys[j]
        t = p.tensioner
        if p.arm is not None:
            text = (f"{p.name!r} at {math.degrees(q):.4g} deg from the drawn arm (stops {math.degrees(t.stops[0]):.4g} / "
                    f"{math.degrees(t.stops[1]):.4g} deg")
            if p.arm.free_angle is not None:
                stop = p.arm.load_stop if p.arm.load_stop is not None else t.stops[1] - t.stops[0]
                text += (f": the free arm {math.degrees(t.stops[1]):.4g} deg into the belt, the load stop "
                         f"{math.degrees(stop):.4g} deg from it")
            parts.append(text + ")")
        else:
            parts.append(f"{p.name!r} at {q * 1e3:.4g} mm from its drawn place (stops {t.stops[0] * 1e3:.4g} / "
                         f"{t.stops[1] * 1e3:.4g} mm)")
    j = idx[0]
    what = "arm" if model.pulleys[j].arm is not None else "slider"
    raise ModelError(f"the tensioner {', '.join(parts)} takes the belt off its loop ({why}): its stops must lie "
                     "where the belt still wraps the pulleys", field=f"pulleys.{j}.{what}.stops")


def _no_equilibrium(model, j, q, why):
    p = model.pulleys[j]
    what, unit = ("arm", "rad") if p.arm is not None else ("slider", "m")
    raise ModelError(f"tensioner on pulley {p.name!r}: no usable static equilibrium within the stops "
                     f"[{p.tensioner.stops[0]:.4g}, {p.tensioner.stops[1]:.4g}] {unit} ({why}; travel {q:.4g} {unit})",
                     field=f"pulleys.{j}.{what}")


