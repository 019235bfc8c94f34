"""The kernel records of the bodies both dynamic models move (dynamics/_bodies.py), built from the
model: the pulleys with their loads, orders and clutches, and the tensioners; and the sense each
pulley runs in."""
from __future__ import annotations

import math

import numpy as np

from ...core.tables import flatten
from ..geometry.tensioner import indices, senses
from . import _bodies as BK


def arms_record(model, sense=None) -> BK.Arms:
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
                  kstop=f([t.stop_stiffness for t in T]), cstop=f([t.stop_damping for t in T]),
                  visc_away=f([t.damping if t.damping_away is None else t.damping_away for t in T]),
                  fshare=f([t.friction_share for t in T]))
    par = np.ascontiguousarray(np.column_stack([fields[k] for k in BK.ARM_FIELDS]).reshape(len(idx), BK.ARM_NPAR))
    return BK.Arms(na=len(idx), pulley=np.array(idx, dtype=np.int64), kind=np.array(kind, dtype=np.int64),
                  tab_off=off, tab_x=tx, tab_y=ty, par=par, **fields)


def pulleys_record(P, senses=None) -> BK.Pulleys:
    """The Pulleys record; ``senses``: +-1 per pulley, its running sense (clutches need it)."""
    f = lambda vals: np.array(vals, dtype=float)
    tt_off, tt_x, tt_y = flatten([p.torque_time for p in P])
    ts_off, ts_x, ts_y = flatten([p.torque_speed for p in P])
    sp_off, sp_x, sp_y = flatten([p.speed_time for p in P])
    hm_off = np.zeros(len(P) + 1, dtype=np.int64)
    so_off = np.zeros(len(P) + 1, dtype=np.int64)
    for j, p in enumerate(P):
        hm_off[j + 1] = hm_off[j] + len(p.load_harmonics)
        so_off[j + 1] = so_off[j] + len(p.speed_orders)
    hs = [hh for p in P for hh in p.load_harmonics]     # a torque_angle table's among them (model.Pulley)
    so = [o for p in P for o in p.speed_orders]
    senses = np.ones(len(P)) if senses is None else senses
    cl = [p.clutch for p in P]
    return BK.Pulleys(
        nk=len(P), cx=f([p.center[0] for p in P]), cy=f([p.center[1] for p in P]),
        r=f([p.radius for p in P]),
        inertia=f([p.inertia for p in P]), inv_i=f([1.0 / p.inertia for p in P]),
        mode=np.array([1 if p.speed_time is not None else 0 for p in P], dtype=np.int64),
        tq_const=f([p.constant_torque for p in P]), tq_visc=f([p.viscous_torque for p in P]),
        tt_off=tt_off, tt_x=tt_x, tt_y=tt_y, ts_off=ts_off, ts_x=ts_x, ts_y=ts_y,
        hm_off=hm_off, hm_order=f([hh.order for hh in hs]),
        hm_amp=f([hh.amplitude for hh in hs]), hm_phase=f([hh.phase for hh in hs]),
        sp_off=sp_off, sp_x=sp_x, sp_y=sp_y,
        tq_drag=f([p.drag for p in P]), w_drag=f([p.drag_speed for p in P]),
        tq_quad=f([p.quadratic_torque for p in P]), tq_pow=f([p.power / p.efficiency for p in P]),
        w_cut=f([p.cut_in_speed for p in P]),
        so_off=so_off, so_order=f([o.order for o in so]), so_amp=f([o.amplitude for o in so]),
        so_ang=f([o.angle for o in so]), so_phase=f([o.phase for o in so]),
        cl_kind=np.array([0 if c is None else (1 if c.type == "one-way" else 2) for c in cl], dtype=np.int64),
        cl_ir=f([1.0 if c is None else c.inertia for c in cl]), cl_k=f([0.0 if c is None else c.rate for c in cl]),
        cl_c=f([0.0 if c is None else c.damping for c in cl]),
        cl_s=f([1.0 if c is None else ({"ccw": 1.0, "cw": -1.0}[c.sense] if c.sense else senses[j])
                for j, c in enumerate(cl)]))


def running_senses(model, layout) -> np.ndarray:
    """+-1 per pulley: the sense it turns in when the drive runs as its driver turns it (the
    prescribed-speed pulley by its mean speed, else the pulley with the largest applied torque).
    Pulleys whose signed radius has the driver's sign turn with it."""
    P = model.pulleys
    drv, sd = None, 1.0
    for j, p in enumerate(P):
        if p.speed_time is not None:
            w = max((r[1] for r in p.speed_time), key=abs)
            drv, sd = j, math.copysign(1.0, w) if w else 1.0
            break
    if drv is None:
        peak = [max([abs(p.torque)] + [abs(r[1]) for r in (p.torque_time or [])]) for p in P]
        drv = int(np.argmax(peak))
        p = P[drv]
        tq = p.torque if abs(p.torque) == peak[drv] else max((r[1] for r in (p.torque_time or [[0, 1.0]])), key=abs)
        sd = math.copysign(1.0, tq) if tq else 1.0
    rho = np.sign(layout.rho)
    return sd * rho * rho[drv]
