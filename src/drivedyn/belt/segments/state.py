"""The records a segment run advances, made for a built system (system.BeltSystem): the kernel
State (the placement at rest, prescribed pulleys at their start speed) and Work (outputs, scratch
and the span probes)."""
from __future__ import annotations

import numpy as np

from ..dynamics import _bodies as BK
from . import _kernels as K


def new_state(sysm, x=None, y=None, phi=None) -> BK.State:
    """A kernel State: the placement (or x, y, phi) at rest, prescribed pulleys at their t = 0
    speed. Arrays are fresh copies (the kernels advance them in place)."""
    n, P = sysm.n, sysm.pulleys
    x = np.array(sysm.init.x if x is None else x, dtype=float)
    y = np.array(sysm.init.y if y is None else y, dtype=float)
    phi = np.array(sysm.init.phi if phi is None else phi, dtype=float)
    om = np.array([BK.prescribed_speed(P, j, 0.0) if P.mode[j] == 1 else 0.0 for j in range(P.nk)], dtype=float)
    q = np.array(sysm.rest.travel if sysm.rest is not None else [], dtype=float)
    return BK.State(x=x, y=y, phi=phi, c=np.cos(phi), s=np.sin(phi), vx=np.zeros(n), vy=np.zeros(n),
                   w=np.zeros(n), th=np.zeros(P.nk), om=om, z=np.zeros(n), cx=P.cx.copy(), cy=P.cy.copy(),
                   cvx=np.zeros(P.nk), cvy=np.zeros(P.nk), q=q, qd=np.zeros(len(q)),
                   thm=np.zeros(P.nk), thr=np.zeros(P.nk), omr=np.zeros(P.nk), dcp=np.zeros(P.nk))


def new_work(sysm, state=None) -> BK.Work:
    """A kernel Work record (zeroed); with a state, each span probe starts at the joint nearest
    its midpoint."""
    n, nk = sysm.n, sysm.pulleys.nk
    nspan, ntrack = len(sysm.span_mid), len(sysm.track)
    span_joint = np.zeros(nspan, dtype=np.int64)
    if state is not None:
        hl = sysm.belt.hl
        jx = 0.5 * (state.x - hl * state.c + np.roll(state.x + hl * state.c, 1))
        jy = 0.5 * (state.y - hl * state.s + np.roll(state.y + hl * state.s, 1))
        for q in range(nspan):
            span_joint[q] = int(np.argmin((jx - sysm.span_mid[q, 0]) ** 2 + (jy - sysm.span_mid[q, 1]) ** 2))
    z = np.zeros
    nl = n if sysm.belt.implicit else 0
    nt = n if sysm.contact.teeth else 0
    return BK.Work(fx=z(n), fy=z(n), mz=z(n), jfk=z(n), jdx=z(n), jdy=z(n), jmk=z(n), jmi=z(n),
                  seg_n=z(n), seg_t=z(n), seg_p=z(n),
                  tq_ext=z(nk), tq_belt=z(nk), hubx=z(nk), huby=z(nk), pin=z(nk), diss=z(4),
                  acc_tq_ext=z(nk), acc_tq_belt=z(nk), acc_hubx=z(nk), acc_huby=z(nk), acc_pin=z(nk),
                  acc_span=z((nspan, 2)), acc_track=z((ntrack, 3)), acc_diss=z(6), energy=z(1), probe=z(6),
                  span_geo=np.ascontiguousarray(sysm.span_geo, dtype=float).reshape(nspan, 4),
                  span_joint=span_joint, track=np.ascontiguousarray(sysm.track, dtype=np.int64),
                  lin_d=z((nl, 9)), lin_o=z((nl, 9)), lin_e=z((nl, 9)), lin_dinv=z((nl, 9)), lin_y=z((nl, 9)),
                  lin_x=z((nl, 9)), lin_r=z((nl, 3)), lin_sig=z(nl), lin_gam=z(nl), lin_fk=z(nl), lin_fa=z(nl), lin_far=z(nl), lin_fnx=z(nl), lin_fny=z(nl), lin_geo=z(nl), lin_u=z((nk if nl else 0, nl, 3)), lin_zslot=np.full(nl, -1, dtype=np.int64), lin_zc=z((2 * K.ZMAX if nl else 0, nl, 3)), lin_g=z((nk, nk + 1)), lin_stat=z(4), cand_j=np.full(n, -1, dtype=np.int64), cand_skip=np.zeros(n, dtype=np.int64), lin_st=z(nl), lin_cnt=np.zeros(4, dtype=np.int64), pul_dw=z(nk),
                  tooth_q=z(nt), tooth_qs=z(nt), tooth_j=np.full(nt, -1, dtype=np.int64), tooth_g=np.zeros(nt, dtype=np.int64),
                  tooth_hold=z(nt), tooth_stat=z(8))


def clear_accumulators(W: BK.Work):
    for a in (W.acc_tq_ext, W.acc_tq_belt, W.acc_hubx, W.acc_huby, W.acc_pin, W.acc_span, W.acc_track, W.acc_diss):
        a[...] = 0.0
