"""Compiled kernels of the belt-drive model (Kubas, seed 000). Contract:

- Kernels take named parameter groups (``typing.NamedTuple`` records of float64 arrays, int64
  index arrays and scalars; no other Python objects), all in SI units, index base 0; nothing is
  compiled at import (``@njit(cache=True)`` without signatures). Numba compiles one version per
  record layout, so a group's field types must not change between calls (floats stay float,
  counts int, flags bool).
- The groups (built once per model by ``system.build``; ``State`` and ``Work`` once per run by
  ``state.new_state`` / ``state.new_work``):

  ``Belt``     the chain of n rigid segments: counts, masses m (kg), inertias (kg m^2) and their
               reciprocals, joint element constants per joint (kax = c_L, bax = b_L, kb = c_B,
               bb = b_B, per element, see system.build), exponents e_L, e_B, half-length hl (m),
               total turn of the path (rad, closes the bending of joint 0), gravity g (m/s^2),
               rotation mass-scaling factor iscale (1 = none).
  ``Contact``  the contact and friction laws, per segment: c1 (N/m^2), c2 (N/m), b (N s/m),
               mu; the damping ramp depth p_max (m), the friction law id (LAW_*), Threlfall's
               Delta_v (m/s), the elastic-plastic Delta_max (m). Read by ``normal_force`` and
               ``friction`` only: a new law is a new id there and its parameters here. Also the
               teeth (``_teeth.py``) and the non-circular pulleys' curve tables (``_curves.py``:
               the semi-implicit scheme's contact, the static contact, the energy).
  ``Pulleys``  nk pulleys: centres (m), contact radii (m), inertias and reciprocals, mode
               (0 dynamic, 1 prescribed speed), applied torque (constant, viscous, tables over
               time and speed, harmonics of the angle) and prescribed-speed tables (flattened,
               see ``tables``).
  ``State``    what the integrators advance: segment x, y, phi (unwrapped), c = cos phi,
               s = sin phi, vx, vy, w; pulley th, om; z the elastic-plastic friction state (m).
  ``Work``     outputs and scratch: joint forces and per-segment contact results, per-pulley
               instantaneous loads, accumulators (h-weighted sums, the caller divides by the
               interval), and the probes (span midpoints followed, tracked segments).

- Belt state: segment i is joined to i-1 by joint i; joint 0 closes the loop between n-1 and 0.
- Notation (seed): joint force F = c_L * Delta_l^e_L + b_L * dDelta_l/dt along the gap vector d
  from the end of segment i-1 to the start of segment i (eqs. 18, 20); bending moment
  M = c_B (dphi)^e_B + b_B dw (eq. 19); contact N = c1 p^2 + c2 p + delta(p) b pdot (eqs. 9-10);
  friction T = mu(v_T) N (eqs. 11-17, Threlfall's law: cubic step from -mu to +mu over |v| < dv).
- Eq. (12), v_kj = theta'_j x r_hat_ji, has a unit vector where a radius belongs; two readings
  (``friction.radius``, ``Contact.centre``), each with slip om_j a - v_t and moment -a T on the
  pulley, so that friction power is exactly T * slip (eq. 22 has the same unit vector):
  "contact" (the default), a = r_j: the belt's centre line runs at the pulley surface's speed, the
  thin belt of classical creep theory; a stuck segment centred at r_j - p then orbits a little
  faster than its pulley, and stuck belt at different depths drifts apart at EA / (r^2 k').
  "centre", a = |r_ji| = r_j - p: stuck belt turns with its pulley, its speed follows its depth
  (a V-belt's pitch radius shrinks as it sinks into the groove), and a belt landing on a wrap
  must also shorten by p / r as it sinks. In both a landing segment reaches the contact radius
  before the tangent point and crosses it at an angle to the pulley's tangent, so with Threlfall's
  law the belt slides where it lands (docs/belt-drive.md, "Friction's radius").
- Contact and friction are written once (``contact``: geometry, ``normal_force``, ``friction``)
  for both integrators: with hm = h / m > 0 they are the implicit updates of the semi-implicit
  scheme, with hm = 0 the explicit forces of the seed's equations (RKF45 right-hand side).

Scheme ``step_chunk``: symplectic (semi-implicit) Euler. Elastic and bending forces and gravity
explicit; each joint's axial damper implicit for that joint (see ``joint_forces``); for each
segment in contact, the contact damping and the regularised friction are solved implicitly in the
segment's new velocity (a scalar monotone equation per contact, pulley speeds frozen during the
step), which makes the stiff friction law (slope mu N / dv) unconditionally stable; the step is
limited only by the elastic chain, h < 2 / sqrt(12 k / m) (``system.stability_limit``).

Scheme ``implicit`` (same function, ``Belt.implicit``; the default wherever it integrates
the drive, ``model.integrator``): the joints (stiffness, dampers, tension stiffness), the contact
normal stiffness and damping and the stuck segments' friction through one cyclic block-tridiagonal
matrix (``_chain.py``: symplectic Euler with a modified mass, no stability limit from the chain);
stick and slip by an active set solved in a small space over the factored matrix; pulleys implicit
with the segments they anchor. Agrees with the semi-implicit scheme at about ten times its step
(docs/belt-drive.md, tests/belt/test_implicit.py).

A step of ``step_chunk`` (its time loop ``_advance``) in stages, each a compiled function (``STAGE``) in a file of
its own by what it holds (this file keeps the records' contract, the loop and its scratch):
``_laws.py`` contact and friction laws; ``_joints.py`` the joints; ``_motion.py`` a segment's move
and its candidate pulley; ``_semi.py`` the semi-implicit contact stage; ``_implicit_contacts.py`` and
``_active_set.py`` the implicit scheme's contacts and its linear algebra; ``_outputs.py`` accumulators,
probe and energy; ``_explicit.py`` the RKF45 right-hand side. The stages:

  both schemes    ``_joint_forces``      the joints' elastic and damping forces and moments
  semi-implicit   ``_contacts_semi``     per segment, at its new velocity under the joints and
                                         gravity: contact and friction implicit in it
                                         (``normal_force``, ``friction``); then the move
  implicit        ``_joint_transport``   the joints' centripetal term (A acts on the deviation
                                         from rolling)
                  ``_spin_damper``       free segments rotating against their neighbours
                  ``_contacts``          gravity; contact (``normal_force``), the chord rolled along
                  ``_friction``          anchors (stuck) and sliding friction; F_base
                  ``_factored_state``, ``_refactor``, ``_pulley_columns``
                                         the chain matrix and the pulleys' columns, when needed
                  ``_base_solve``        y = A_f^-1 F_base
                  ``_join``, ``_corrections``, ``_small_system``, ``_check``
                                         the stick-slip active set, pass by pass
                  ``_velocity_change``   dv from y, the pulleys' and the members' columns
                  ``_update_implicit``   friction at the solved velocities, hub loads, the move
  both schemes    ``_step_pulleys``      pulleys, engine orders, clutches and decouplers
                  ``_step_arms``         tensioners (they move their pulleys' centres)
                  ``_accumulate``        the step's share of the output accumulators

``_advance`` and its stages are compiled without numba's reference counting (they allocate nothing;
``scratch`` makes their scratch, ``Scratch``, once per run): an array a stage takes, or a record's
field it reads, otherwise costs an atomic reference-count pair per call, half of a semi-implicit
step (measured).
"""
import math
from typing import NamedTuple

import numpy as np
from numba import njit

from ..dynamics._bodies import (FAST, State, _small_solve, _spring_energy, _step_arms, _step_pulleys_on, _torque, external_torque, prescribed_speed, smoothstep, solve_threlfall, threlfall)  # noqa: F401
from . import _chain  # noqa: F401
from .records import LAW_ELASTIC_PLASTIC, LAW_THRELFALL, LAWS, STAGE, STAGE_PY, Belt, Contact  # noqa: F401
from ._laws import (normal_force, clipped_power, contact_energy, friction, _bristle, contact)  # noqa: F401
from ._joints import (_joint, _joint_forces, joint_forces, _joint_forces_of, static_forces, _static_contacts)  # noqa: F401
from ._motion import (_move, _turn, SKIP_MAX, _contact_candidate)  # noqa: F401
from ._implicit_contacts import (ANCHOR, SPIN_ZETA, SPIN_LIMIT, _spin_damper, _contacts, _anchor, _pressed, _friction, _update_implicit, NSC, NSI)  # noqa: F401
from ._active_set import (REFACTOR_ANGLE, CMAX, ZMAX, PASSES, _refactor, _joint_transport, _velocity_change, _factored_state, _pulley_columns, _base_solve, _join, _corrections, _small_system, _check, PULLEY_IMPLICIT, _implicit_pulleys)  # noqa: F401
from ._semi import (NQ, _contacts_semi)  # noqa: F401
from ._outputs import (_accumulate, _probe, energy, _energy_of, _energy)  # noqa: F401
from ._teeth import _teeth  # noqa: F401
from ._explicit import (rhs, _C, _A, _B4, _B5, rkf45_chunk)  # noqa: F401




class Scratch(NamedTuple):
    """What a call of ``step_chunk`` works in, allocated by it for ``_advance`` (which allocates
    nothing). Per segment: the implicit scheme's columns C_* (sc) and I_* (si), the spin damper's
    second differences and coefficients (spd, cs), A's anchor terms (kat), the base solve y and a
    column being solved (u) (sized 0 for the semi-implicit scheme); copies of 1 / m, 1 / I and the
    joints' moments (jmk, jmi), h / m, h / I and the scaled inertia. The active set C: its members,
    their corrections and the small system. Per pulley: the base friction sum s0, g_j . y, the
    speed change dom, the applied torque, whether the chain solve integrates it (ipl), the belt's
    torque and its force (hub: rows x, y). The semi-implicit contact stage's contact pulley per segment
    and its rows Q_* (sj, sq; sized 0 for the implicit scheme)."""
    sc: np.ndarray
    si: np.ndarray
    spd: np.ndarray
    cs: np.ndarray
    kat: np.ndarray
    yx: np.ndarray
    yy: np.ndarray
    yz: np.ndarray
    ux: np.ndarray
    uy: np.ndarray
    uz: np.ndarray
    inv_m: np.ndarray
    inv_i: np.ndarray
    jmk: np.ndarray
    jmi: np.ndarray
    hm: np.ndarray
    hi: np.ndarray
    ieff: np.ndarray
    cseg: np.ndarray
    cpar: np.ndarray
    qm: np.ndarray
    qv: np.ndarray
    s0: np.ndarray
    gyv: np.ndarray
    dom: np.ndarray
    mext: np.ndarray
    ipl: np.ndarray
    tq_belt: np.ndarray
    hub: np.ndarray
    wsave: np.ndarray
    sj: np.ndarray
    sq: np.ndarray


def step_chunk(nsteps, t, h, B, Ct, P, A, S, W, lin=None, X=None):
    """Advance ``nsteps`` steps from time t (semi-implicit Euler, or the implicit scheme with
    ``lin`` = True and ``B.implicit``); returns the new time. X: the run's ``scratch`` (made here
    when not given).

    Accumulates into W (added h * value, the caller divides by the interval): acc_tq_ext[j]
    applied torque, acc_tq_belt[j] belt torque on the pulley, acc_hubx/y[j] belt force on the
    pulley, acc_pin[j] power into the system through pulley j, acc_span[q, 0:2] mid-span tension
    and belt speed along the span, acc_track[q, 0:3] element force / normal force / friction force
    (along the segment) of tracked segments, acc_diss[0:5] dissipation in axial dampers, bending
    dampers, contact damping, friction, tensioners, clutches. Tensioners (A) move their pulleys' centres
    in S (cx, cy, cvx, cvy); contact and friction act on the velocity relative to the centre.
    The stages of a step: see the module's doc.
    """
    if B.implicit != (lin is not None):
        raise ValueError("step_chunk: lin must be given for the implicit scheme only")
    return _advance(nsteps, t, h, B, Ct, P, A, S, W, *scheme(B), scratch(B, P) if X is None else X)


def scheme(B):
    """``_advance``'s arguments (lin, semi) for this belt's scheme: None for the scheme not run.
    numba drops a branch on ``arg is not None`` at compile time only where arg is None, so the
    kernel of each scheme is compiled without the other's stages (implicit: 21 against 48 s of
    compile with the semi-implicit stages and every stage inlined, 2-core AMD EPYC)."""
    return (True, None) if B.implicit else (None, True)


def scratch(B, P):
    """The ``Scratch`` of a run of this belt (``_advance`` allocates nothing); one serves every chunk."""
    n, nk = B.n, P.nk
    ni = n if B.implicit else 0
    nci = CMAX if B.implicit else 0
    msz = 2 * nci + nk if B.implicit else 0
    f = np.zeros
    return Scratch(f((ni, NSC)), np.full((ni, NSI), -1, dtype=np.int64), f(ni), f(ni), f(ni), f(ni), f(ni), f(ni),
                   f(ni), f(ni), f(ni), f(n), f(n), f(n), f(n), f(n), f(n), f(n), np.zeros(nci, dtype=np.int64),
                   f((nci, 11)), f((msz, msz)), f(msz), f(nk), f(nk), f(nk), f(nk), np.zeros(nk, dtype=np.bool_),
                   f(nk), f((2, nk)), f(nk), np.zeros(n - ni, dtype=np.int64), f((NQ, n - ni)))


# the stages of ``_bodies`` that the rotational model's loop inlines, compiled as stages here from
# their own code: a stage that called them inlined copied their IR first (numba's inlining, 1.3 s
# of the pulleys' 2.5 s compile); ``_step_pulleys_on`` takes the arrays of S and W it reads, not
# the records (see ``_advance``)
_pulleys_stage = njit(**STAGE)(_step_pulleys_on.py_func)
_arms_stage = njit(**STAGE)(_step_arms.py_func)
_torque_stage = njit(**STAGE)(_torque.py_func)


# Compiled without numba's reference counting (_nrt=False: it allocates nothing, ``scratch``
# makes its scratch once per run): each array a stage takes, or a record's field it reads, in the
# time loop otherwise costs an atomic reference-count pair, which was half of the semi-implicit
# step (6.3 against 3.4 us at 150 segments, measured with numba's atomicity switched off)
# and with numpy's error model: a float division by zero gives inf or nan (which the health probe
# reports as a state that ran away) rather than a test and a raise per division, which kept the
# stages' loops from vectorising
@njit(cache=True, _nrt=False, error_model="numpy", no_cfunc_wrapper=True)
def _advance(nsteps, t, h, B, Ct, P, A, S, W, lin, semi, X):
    """The time loop of ``step_chunk``, in stages (the module's doc)."""
    # the records' arrays read where they are used (S.x, X.sc), not taken out into local names:
    # numba gives each local array a stack slot that LLVM's SROA then splits, 1.3 s of this
    # function's compile (5.7 -> 4.3 s without its Python wrapper); the loads are the same
    n, nk, hl, g, eax, eb, linear, turn = B.n, P.nk, B.hl, B.g, B.eax, B.eb, B.linear, B.turn
    na = A.na
    hubx = X.hub[0]
    huby = X.hub[1]
    # the scratch as step_chunk allocated it per chunk before it served a whole run (the active
    # set, for one, starts empty), and the chunk's constants (the step h can change between chunks)
    for a in (X.sc, X.cpar, X.qm, X.hub, X.sq):
        a[...] = 0.0
    for b in (X.spd, X.cs, X.kat, X.yx, X.yy, X.yz, X.ux, X.uy, X.uz, X.jmk, X.jmi, X.qv, X.s0, X.gyv, X.dom, X.mext,
              X.tq_belt, X.wsave):
        b[...] = 0.0
    X.si[...] = -1
    X.cseg[...] = 0
    X.sj[...] = 0
    for i in range(n):
        X.inv_m[i] = B.inv_m[i]
        X.inv_i[i] = B.inv_i[i]
        X.ieff[i] = B.inertia[i] * B.iscale   # the segments' rotational inertia as integrated (see system.py)
        X.hm[i] = h * B.inv_m[i]
        X.hi[i] = h / X.ieff[i]
    for j in range(nk):
        X.ipl[j] = False
    if lin is not None:
        _implicit_pulleys(h, B, Ct, P, S, X.ipl)
    hj = 0.0 if B.implicit else h       # the implicit scheme's dampers are in the chain matrix
    nC = np.int64(0)                  # members of the active set C (int64 throughout: one signature of its stages)
    # the spin damper acts above this second difference of the rates (the alternating pattern
    # of amplitude W has a second difference of 4 W)
    spin_lim = 0.0
    for j in range(nk):
        spin_lim = max(spin_lim, abs(S.om[j]))
    spin_lim = 4.0 * SPIN_LIMIT * max(spin_lim, 10.0)
    hg = h * g
    # contact candidates (_contact_candidate): the speed bound of this chunk, per step
    vmax = 0.0
    for i in range(n):
        vmax = max(vmax, S.vx[i] * S.vx[i] + S.vy[i] * S.vy[i])
    pvmax = 0.0
    for j in range(nk):
        pvmax = max(pvmax, S.cvx[j] * S.cvx[j] + S.cvy[j] * S.cvy[j])
    hvb = h * (2.0 * math.sqrt(vmax) + 2.0 * math.sqrt(pvmax) + 1.0)
    for _ in range(nsteps):
        pax, pb = _joint_forces(n, eax, eb, hl, turn, linear, S.x, S.y, S.c, S.s, S.vx, S.vy, S.w, S.phi, B.kax, B.bax,
                                B.kb, B.bb, W.fx, W.fy, W.mz, W.jfk, W.jdx, W.jdy, hj, X.inv_m, X.inv_i, X.jmk, X.jmi)
        pcd = 0.0
        pfr = 0.0
        for j in range(nk):
            X.tq_belt[j] = 0.0
            hubx[j] = 0.0
            huby[j] = 0.0
        if lin is not None:
            # Every force through the chain matrix, dv = h A^-1 F (see _chain.py). Contact normal
            # forces explicit at (x_n, v_n), their stiffness and damping in A. Friction: a
            # sliding segment carries mu N against its slip (explicit, saturated); a stuck one is
            # anchored to the pulley surface in A (Threlfall: the law's secant slope mu N / dv;
            # elastic-plastic: its bristle, slope h K, K z explicit; the pulley's speed change
            # solved with the chain or, outside it, extrapolated), its friction the anchor's force. An anchor
            # whose force would exceed mu N lets go and the step is solved again (active set).
            # A pulley outside the chain solve (prescribed, behind a clutch, or explicit:
            # _implicit_pulleys) turns after the belt; the belt is solved against its speed at
            # the step's end, extrapolated by its last change (restored for _step_pulleys).
            # Against its speed at the start, the coupling lags by a step: fead-runup's drive
            # held at 1000 rpm at 19.2 us read span minima 5 % off with it, within 0.5 % of the
            # implicit pulleys' result with the extrapolation.
            for j in range(nk):
                if not X.ipl[j]:
                    X.wsave[j] = S.om[j]
                    S.om[j] += W.pul_dw[j]
            _joint_transport(n, h, hl, linear, eax, B.kax, B.bax, S.c, S.s, S.w, W.jdx, W.jdy, W.fx, W.fy, W.mz)
            pb = _spin_damper(n, h, hl, spin_lim, X.ieff, S.w, W.jfk, W.jdx, W.jdy, W.seg_n, X.spd, X.cs, W.mz, pb)
            nc, pcd = _contacts(n, nk, h, hvb, g, B.m, Ct.c1, Ct.c2, Ct.bc, Ct.pmax, Ct.centre, S.x, S.y, S.vx,
                                S.vy, S.cx, S.cy, S.cvx, S.cvy, P.r, W.cand_j, W.cand_skip, W.lin_st, S.z, W.fy,
                                X.si, X.sc)
            cchg = _friction(n, h, Ct, S.om, W.lin_st, S.z, W.lin_fk, W.fx, W.fy, W.mz, X.si, X.sc)
            for j in range(nk):
                if X.ipl[j]:
                    X.mext[j] = _torque_stage(j, t, S.th[j], S.om[j], P.tq_const, P.tq_visc, P.tq_drag, P.w_drag,
                                              P.tq_quad, P.tq_pow, P.w_cut, P.tt_off, P.tt_x, P.tt_y, P.ts_off, P.ts_x,
                                              P.ts_y, P.hm_off, P.hm_order, P.hm_amp, P.hm_phase)
            # The step's linear system, its stick-slip active set solved in a small space (CMAX,
            # ZMAX above). One banded solve per step gives y = A_f^-1 F_base (_base_solve). A
            # segment whose state differs from the factored one (set C) adds a force correction
            # phi_c at its centre, a pulley its speed change dw_k: dv = h (y + sum_k dw_k U_k +
            # sum_c Z_c phi_c), U_k = A_f^-1 g_k and Z_c = A_f^-1 [e_x e_y]_c cached. phi and dw
            # solve a dense (2 |C| + nk) system; each pass checks every contact segment (anchors
            # letting go, slips turning) at O(|C| + nk) each; a segment that changes joins C. The
            # chain matrix is refactored at the current state when the contact set changes, the
            # segments have turned (REFACTOR_ANGLE), or C outgrows its cache.
            need = W.lin_cnt[0] <= 0 or cchg
            base = True
            npass = np.int64(0)
            npend = np.int64(0)
            while True:
                if need:
                    _factored_state(n, h, X.si, X.sc, W.lin_fk, W.lin_fnx, W.lin_fny, W.lin_fa, W.lin_far, X.kat,
                                    W.lin_zslot)
                    W.lin_cnt[2] = 0
                    W.lin_cnt[0] = _refactor(n, h, hl, eax, eb, linear, B.kax, B.bax, B.kb, B.bb, S.c, S.s, S.w, S.phi,
                                             W.jfk, W.jdx, W.jdy, turn, B.m, X.ieff, W.lin_sig, W.lin_gam, W.lin_geo,
                                             W.lin_fk, X.kat, W.lin_fnx, W.lin_fny, W.lin_d, W.lin_o, W.lin_e,
                                             W.lin_dinv, W.lin_y, W.lin_x)
                    W.lin_cnt[1] += 1
                    _pulley_columns(n, nk, nc, W.lin_far, W.lin_fa, W.lin_fnx, W.lin_fny, X.si, X.ipl, X.ux, X.uy,
                                    X.uz, W.lin_dinv, W.lin_y, W.lin_x, W.lin_r, W.lin_u, W.lin_g)
                    need = False
                    base = True
                if base:
                    npend = _base_solve(n, nk, nc, nC, S.vx, S.vy, S.om, S.cvx, S.cvy, P.r, W.lin_fk, W.lin_fnx,
                                        W.lin_fny, W.lin_fa, W.lin_far, X.si, X.cseg, X.sc, X.yx, X.yy, X.yz, X.s0,
                                        X.gyv, X.ipl, W.lin_dinv, W.lin_y, W.lin_x, W.lin_r)
                    nC = 0
                    base = False
                nC, over = _join(n, nC, npend, X.si, X.cseg, W.lin_zslot, W.lin_zc, W.lin_cnt, X.ux, X.uy, X.uz,
                                 W.lin_dinv, W.lin_y, W.lin_x, W.lin_r)
                npend = np.int64(0)         # (not the literal 0: _check compiled for one signature, tail.py)
                if over:
                    need = True
                    continue
                _corrections(nC, S.vx, S.vy, S.om, S.cvx, S.cvy, W.lin_fnx, W.lin_fny, W.lin_fa, W.lin_far, X.si, X.sc,
                             X.cseg, X.cpar)
                _small_system(h, nk, nC, P.inv_i, X.mext, W.lin_zslot, W.lin_zc, W.lin_u, W.lin_g, X.si, X.cseg,
                              X.cpar, X.qm, X.qv, X.yx, X.yy, X.s0, X.gyv, X.ipl, X.dom, W.lin_cnt)
                changed, npend = _check(h, nk, nc, nC, npend, npass, Ct, S.vx, S.vy, S.om, S.cvx, S.cvy, W.lin_fnx,
                                        W.lin_fny, W.lin_fa, W.lin_far, W.lin_st, S.z, W.lin_zslot, W.lin_zc, W.lin_u,
                                        W.lin_stat, X.si, X.sc, X.cseg, X.yx, X.yy, X.qv, X.dom, X.ipl)
                npass += 1
                if not changed:
                    break
            _velocity_change(n, nk, nC, X.ipl, X.dom, X.qv, X.cseg, W.lin_zslot, W.lin_u, W.lin_zc, X.yx, X.yy, X.yz,
                             W.fx, W.fy, W.mz)
            W.lin_cnt[0] -= 1
            pfr, pcd_ = _update_implicit(n, h, Ct, S.x, S.y, S.phi, S.c, S.s, S.vx, S.vy, S.w, S.om, S.cvx, S.cvy,
                                         W.fx, W.fy, W.mz, W.seg_n, W.seg_t, W.seg_p, W.lin_st, S.z, W.lin_fk,
                                         W.lin_fnx, W.lin_fny, X.si, X.sc, X.dom, X.tq_belt, X.hub)
            pcd += pcd_
            for j in range(nk):
                if not X.ipl[j]:
                    S.om[j] = X.wsave[j]
        if semi is not None:
            if Ct.teeth:
                _teeth(n, nk, t, Ct, S, P.r, W.fx, W.fy, W.jfk, W.jdx, W.jdy, W.tooth_q, W.tooth_qs, W.tooth_j, W.tooth_g,
                       W.tooth_hold, W.tooth_stat, X.tq_belt, hubx, huby)
            pcd, pfr = _contacts_semi(n, nk, h, hg, hvb, X.hm, X.hi, W.fx, W.fy, W.mz, Ct, S, P.r, W.cand_j,
                                      W.cand_skip, W.seg_n, W.seg_t, W.seg_p, X.sj, X.sq, X.tq_belt, hubx, huby)
        # pulleys, then tensioners, under this step's belt torques and hub forces
        for j in range(nk):
            W.pul_dw[j] = S.om[j]
        diss_cl = _pulleys_stage(t, h, X.tq_belt, hubx, huby, P, S.th, S.om, S.thm, S.thr, S.omr, S.dcp, W.acc_pin,
                                 W.acc_tq_ext, W.acc_tq_belt, W.acc_hubx, W.acc_huby)
        for j in range(nk):
            W.pul_dw[j] = S.om[j] - W.pul_dw[j]
        if na > 0:     # tensioners, under this step's hub forces; they move the centres
            W.acc_diss[4] += h * _arms_stage(na, A.pulley, A.kind, A.par, A.tab_off, A.tab_x, A.tab_y, S.q, S.qd, S.cx,
                                             S.cy, S.cvx, S.cvy, hubx, huby, h)
        _accumulate(h, hl, S.x, S.y, S.c, S.s, S.vx, S.vy, W.jfk, W.jdx, W.jdy, W.seg_n, W.seg_t, W.span_geo,
                    W.span_joint, W.track, W.acc_span, W.acc_track, W.acc_diss, pax, pb, pcd, pfr, diss_cl)
        t += h
    for j in range(nk):
        W.tq_belt[j] = X.tq_belt[j]
        W.hubx[j] = hubx[j]
        W.huby[j] = huby[j]
    W.energy[0] = _energy_of(B, Ct, P, A, S)   # here, not by a second call from Python (12 us per call)
    _probe(n, nk, S, P, W)
    return t
