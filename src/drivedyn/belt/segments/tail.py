"""The time loop's stages with arguments of the types ``_kernels._advance`` calls them with, in the
loop's order. On a first run the two processes share them: this one compiles the last stages from the
last back (``compile_back``) while the second process (ahead.py) compiles them from the first on
(``compile_forward``); each claims a stage before it compiles it, so that none compiles twice (a
cache entry is written only when a compile ends: both compiled ``_joint_forces`` and ``_join``, 1 s
each, when they met on the cache alone). The second process then compiles the loop itself, which
loads its stages from numba's cache. A stage compiled for other types would compile twice (here, and
again in the loop): every call below mirrors one in ``_advance`` (tests/belt/test_first_use.py checks
that each stage ends up with one signature). ``_joint_forces`` and ``_energy`` are not listed: the
belt's settling compiles them first, here."""
from __future__ import annotations

import contextlib
import os
import time

import numpy as np

from . import _kernels as K
from .ahead import cached

F = 0.0                  # a float the loop computes (a power, a time)
I = np.int64(0)          # an int64 it computes (counts, indices)
TRUE = True              # a flag


def head(h, B, Ct, P, A, S, W, X):
    """[(stage, args)] of the implicit loop's stages between the joint forces and ``stages``."""
    if not B.implicit:
        return []
    n, hl, linear, eax = B.n, B.hl, B.linear, B.eax
    return [
        (K._joint_transport, (n, h, hl, linear, eax, B.kax, B.bax, S.c, S.s, S.w, W.jdx, W.jdy, W.fx, W.fy, W.mz)),
        (K._spin_damper, (n, h, hl, F, X.ieff, S.w, W.jfk, W.jdx, W.jdy, W.seg_n, X.spd, X.cs, W.mz, F)),
        (K._contacts, (n, P.nk, h, F, B.g, B.m, Ct.c1, Ct.c2, Ct.bc, Ct.pmax, Ct.centre, S.x, S.y, S.vx, S.vy, S.cx,
                       S.cy, S.cvx, S.cvy, P.r, W.cand_j, W.cand_skip, W.lin_st, S.z, W.fy, X.si, X.sc)),
        (K._friction, (n, h, Ct, S.om, W.lin_st, S.z, W.lin_fk, W.fx, W.fy, W.mz, X.si, X.sc)),
    ]


def stages(h, B, Ct, P, A, S, W, X):
    """[(stage, args)] of the loop's stages after the contacts, in the loop's order."""
    hubx, huby = X.hub[0], X.hub[1]
    out = []
    if B.implicit:
        out += [
            (K._torque_stage, (I, F, F, F, P.tq_const, P.tq_visc, P.tq_drag, P.w_drag, P.tq_quad, P.tq_pow, P.w_cut,
                               P.tt_off, P.tt_x, P.tt_y, P.ts_off, P.ts_x, P.ts_y, P.hm_off, P.hm_order, P.hm_amp,
                               P.hm_phase)),
            (K._factored_state, (B.n, h, X.si, X.sc, W.lin_fk, W.lin_fnx, W.lin_fny, W.lin_fa, W.lin_far, X.kat,
                                 W.lin_zslot)),
            (K._refactor, (B.n, h, B.hl, B.eax, B.eb, B.linear, B.kax, B.bax, B.kb, B.bb, S.c, S.s, S.w, S.phi, W.jfk,
                           W.jdx, W.jdy, B.turn, B.m, X.ieff, W.lin_sig, W.lin_gam, W.lin_geo, W.lin_fk, X.kat,
                           W.lin_fnx, W.lin_fny, W.lin_d, W.lin_o, W.lin_e, W.lin_dinv, W.lin_y, W.lin_x)),
            (K._pulley_columns, (B.n, P.nk, I, W.lin_far, W.lin_fa, W.lin_fnx, W.lin_fny, X.si, X.ipl, X.ux, X.uy, X.uz,
                                 W.lin_dinv, W.lin_y, W.lin_x, W.lin_r, W.lin_u, W.lin_g)),
            (K._base_solve, (B.n, P.nk, I, I, S.vx, S.vy, S.om, S.cvx, S.cvy, P.r, W.lin_fk, W.lin_fnx, W.lin_fny,
                             W.lin_fa, W.lin_far, X.si, X.cseg, X.sc, X.yx, X.yy, X.yz, X.s0, X.gyv, X.ipl, W.lin_dinv,
                             W.lin_y, W.lin_x, W.lin_r)),
            (K._join, (B.n, I, I, X.si, X.cseg, W.lin_zslot, W.lin_zc, W.lin_cnt, X.ux, X.uy, X.uz, W.lin_dinv, W.lin_y,
                       W.lin_x, W.lin_r)),
            (K._corrections, (I, S.vx, S.vy, S.om, S.cvx, S.cvy, W.lin_fnx, W.lin_fny, W.lin_fa, W.lin_far, X.si, X.sc,
                              X.cseg, X.cpar)),
            (K._small_system, (h, P.nk, I, P.inv_i, X.mext, W.lin_zslot, W.lin_zc, W.lin_u, W.lin_g, X.si, X.cseg,
                               X.cpar, X.qm, X.qv, X.yx, X.yy, X.s0, X.gyv, X.ipl, X.dom, W.lin_cnt)),
            (K._check, (h, P.nk, I, I, I, I, Ct, S.vx, S.vy, S.om, S.cvx, S.cvy, W.lin_fnx, W.lin_fny, W.lin_fa,
                        W.lin_far, W.lin_st, S.z, W.lin_zslot, W.lin_zc, W.lin_u, W.lin_stat, X.si, X.sc, X.cseg, X.yx,
                        X.yy, X.qv, X.dom, X.ipl)),
            (K._velocity_change, (B.n, P.nk, I, X.ipl, X.dom, X.qv, X.cseg, W.lin_zslot, W.lin_u, W.lin_zc, X.yx, X.yy,
                                  X.yz, W.fx, W.fy, W.mz)),
            (K._update_implicit, (B.n, h, Ct, S.x, S.y, S.phi, S.c, S.s, S.vx, S.vy, S.w, S.om, S.cvx, S.cvy, W.fx, W.fy,
                                  W.mz, W.seg_n, W.seg_t, W.seg_p, W.lin_st, S.z, W.lin_fk, W.lin_fnx, W.lin_fny, X.si,
                                  X.sc, X.dom, X.tq_belt, X.hub)),
        ]
    else:
        out.append((K._contacts_semi, (B.n, P.nk, h, F, F, X.hm, X.hi, W.fx, W.fy, W.mz, Ct, S, P.r, W.cand_j,
                                       W.cand_skip, W.seg_n, W.seg_t, W.seg_p, X.sj, X.sq, X.tq_belt, hubx, huby)))
    out += [
        (K._pulleys_stage, (F, h, X.tq_belt, hubx, huby, P, S.th, S.om, S.thm, S.thr, S.omr, S.dcp, W.acc_pin,
                            W.acc_tq_ext, W.acc_tq_belt, W.acc_hubx, W.acc_huby)),
        (K._arms_stage, (A.na, A.pulley, A.kind, A.par, A.tab_off, A.tab_x, A.tab_y, S.q, S.qd, S.cx, S.cy, S.cvx,
                         S.cvy, hubx, huby, h)),
        (K._accumulate, (h, B.hl, S.x, S.y, S.c, S.s, S.vx, S.vy, W.jfk, W.jdx, W.jdy, W.seg_n, W.seg_t, W.span_geo,
                         W.span_joint, W.track, W.acc_span, W.acc_track, W.acc_diss, F, F, F, F, F)),
    ]
    return out


def signature(stage, args):
    return tuple(stage.typeof_pyval(a) for a in args)


def claim(claims, stage) -> bool:
    """Whether this process takes ``stage`` (the other has not): a file created in ``claims``, a
    directory the two processes share; None: no other process, every stage is this one's."""
    if claims is None:
        return True
    try:
        os.close(os.open(os.path.join(claims, stage.py_func.__name__), os.O_CREAT | os.O_EXCL | os.O_WRONLY))
        return True
    except FileExistsError:
        return False


def compile_back(jobs, busy, claims=None) -> list:
    """Compile the stages of ``jobs`` (``stages``) from the last back, while ``busy()`` (the second
    process still compiling), until one is compiled, cached or claimed already: the second process
    got there first (it compiles them from the first on). Returns the names of those compiled here."""
    done = []
    taken = None
    try:
        for stage, args in reversed(jobs):
            sig = signature(stage, args)
            if not busy() or cached(stage, sig) or not claim(claims, stage):
                break
            taken = stage
            stage.compile(sig)
            taken = None
            done.append(stage.py_func.__name__)
    except Exception:  # noqa: BLE001  (numba's internals moved: the loop compiles what is left itself)
        if claims is not None and taken is not None:     # given back: the second process stops waiting on it
            with contextlib.suppress(OSError):
                os.remove(os.path.join(claims, taken.py_func.__name__))
    return done


def compile_forward(args, claims, patience=60.0) -> list:
    """In the second process, before the loop (``_advance`` with ``args``): its stages from the
    first on until one is claimed (this process compiles the rest back from the last); then wait,
    up to ``patience`` seconds, until the other's are in the cache, so that the loop loads them."""
    h, records, X = args[2], args[3:9], args[-1]
    jobs = [(stage, signature(stage, a)) for stage, a in head(h, *records, X) + stages(h, *records, X)]
    done = []
    for stage, sig in jobs:
        if cached(stage, sig):
            continue
        if not claim(claims, stage):
            break
        stage.compile(sig)
        done.append(stage.py_func.__name__)
    # (a stage this process did not take is the other's while its claim stands: given back, the loop
    # compiles it)
    theirs = [(stage, sig) for stage, sig in jobs if stage.py_func.__name__ not in done]
    end = time.monotonic() + patience
    while time.monotonic() < end and any(not cached(stage, sig) and os.path.exists(
            os.path.join(claims, stage.py_func.__name__)) for stage, sig in theirs):
        time.sleep(0.02)
    return done
