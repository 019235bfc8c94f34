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
               ``friction`` only: a new law is a new id there and its parameters here.
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

A step of ``step_chunk`` (its time loop ``_advance``) in stages, each a compiled function (``STAGE``):

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

from ..dynamics._bodies import (FAST, State, _small_solve, _spring_energy, _step_arms, _step_pulleys_on, _torque, external_torque, prescribed_speed, smoothstep, solve_threlfall, threlfall)
from . import _chain
from .records import LAW_ELASTIC_PLASTIC, LAW_THRELFALL, LAWS, Belt, Contact  # noqa: F401


# A stage of the time loop (``_advance``) is a function of its own, compiled once, not inlined into
# the loop as numba IR: numba copies an inlined function's IR at a cost that grows with its size
# times its blocks, and then compiles one giant function (the implicit kernel: 48 s cold against
# 21 s as stages, 2-core AMD EPYC; LLVM inlines the smaller stages, the others are a call per step).
# Compiled as the loop is (no fast-math, numpy's error model, no reference counting: a stage
# allocates nothing), so every number is the same to the bit, the steps as fast, and without the
# wrappers a function called from Python needs (a record's wrapper unboxes each of its arrays:
# 1.6 s of compile for the loop's arguments alone).
STAGE = {"cache": True, "_nrt": False, "error_model": "numpy", "no_cpython_wrapper": True, "no_cfunc_wrapper": True}
STAGE_PY = {**STAGE, "no_cpython_wrapper": False}     # a stage the tests also call from Python


# ---- contact and friction: the one place for the laws (both integrators) -------------------

@njit(cache=True, inline="always")
def normal_force(c1, c2, bc, pmax, p, vn, hm):
    """Normal force of eqs. 9-10 on segment i at penetration p > 0 and normal velocity vn (outward,
    before the contact acts). hm = h/m > 0: the damping implicit in the new normal velocity,
    vn_new = vn + hm N; hm = 0: explicit. Returns (N, delta(p) b); N <= 0 means no contact force."""
    db = smoothstep(p / pmax) * bc
    N = (c1 * p * p + c2 * p - db * vn) / (1.0 + db * hm)
    return N, db


@njit(cache=True, inline="always")
def clipped_power(c1, c2, p, vn):
    """The contact damper's power where it holds the normal force at zero (N = k(p) - db vn <= 0:
    the segment separates faster than the contact pushes): the damper then carries the whole
    elastic force k(p) against the separation speed vn, so the contact's elastic energy is
    dissipated, not returned (without this term it left the energy balance unseen, 1 % of the
    power at 3000 rpm on examples/fead-runup.toml's drive, where segments leave the tensioner's
    moving pulley)."""
    return (c1 * p * p + c2 * p) * vn if vn > 0.0 else 0.0


@njit(cache=True, inline="always")
def contact_energy(Ct, i, p):
    """Potential of the elastic part of eq. 9 at penetration p > 0 (J)."""
    return Ct.c1[i] * p * p * p / 3.0 + Ct.c2[i] * p * p / 2.0


@njit(cache=True, inline="always")
def friction(mu, law, dv, dmax, N, wslip, hm, h, z, i):
    """Friction force T on segment i (along the tangent Z x n) under normal force N, for the slip
    wslip of the pulley surface relative to the segment before friction acts. Implicit in the new
    slip with hm = h/m > 0, explicit with hm = 0. Updates z[i] (elastic-plastic state).
    Returns (T, slip after), so that T * slip is the friction power."""
    muN = mu * N
    if law == LAW_THRELFALL:
        sl = solve_threlfall(wslip, hm * muN, dv)
        T = muN * threlfall(sl, dv)
    else:
        T, sl, z[i] = _bristle(muN, dmax, wslip, z[i], h, hm)
    return T, sl


@njit(cache=True, inline="always")
def _bristle(muN, dmax, wslip, z, h, hm):
    """The elastic-plastic law (``friction``): T = K z with K = mu N / dmax, z_new = z + h slip_new,
    clipped at the displacement limit; branch-free so that a loop of it vectorises. Returns (T,
    slip after, z_new)."""
    K = muN / dmax
    zn = min(max((z + h * wslip) / (1.0 + h * hm * K), -dmax), dmax)
    T = K * zn
    return T, wslip - hm * T, zn


@njit(cache=True, inline="always")
def contact(Ct, i, rx, ry, d2, r, vx, vy, om, hm, h, z):
    """Segment i inside the contact radius r of a pulley (d2 = |rx, ry|^2 < r^2, (rx, ry) from the
    pulley centre to the segment centre), segment velocity (vx, vy), pulley speed om: normal force
    and friction (eqs. 4-17). Returns (p, N, T, nx, ny, contact damping power, friction power);
    N <= 0: no force (the segment leaves faster than the contact pushes)."""
    dist = math.sqrt(d2)
    inv = 1.0 / dist
    nx = rx * inv
    ny = ry * inv
    p = r - dist
    vn = vx * nx + vy * ny
    N, db = normal_force(Ct.c1[i], Ct.c2[i], Ct.bc[i], Ct.pmax, p, vn, hm)
    if N <= 0.0:
        return p, N, 0.0, nx, ny, clipped_power(Ct.c1[i], Ct.c2[i], p, vn), 0.0
    vn_new = vn + hm * N
    # tangent tau = Z x n; slip of the pulley surface relative to the segment
    vt = vx * -ny + vy * nx
    T, sl = friction(Ct.mu[i], Ct.law, Ct.dv, Ct.dmax, N, om * (dist if Ct.centre else r) - vt, hm, h, z, i)
    return p, N, T, nx, ny, db * vn_new * vn_new, T * sl


# ---- belt joints (eqs. 18-21) ---------------------------------------------------------------

@njit(cache=True, inline="always", fastmath=FAST)
def _joint(i, k, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m, inv_i,
           jfk, jdx, jdy, jmk, jmi):
    """Joint i between segment k (+ end) and segment i (- end): stores its gap vector (jdx, jdy),
    jfk (force vector = jfk * d, on k; minus that on i) and its moments on k and on i (arms and
    bending). Returns the power of its axial and bending dampers."""
    ax = hl * c[k]
    ay = hl * s[k]
    bx = hl * c[i]
    by = hl * s[i]
    dx = (x[i] - bx) - (x[k] + ax)
    dy = (y[i] - by) - (y[k] + ay)
    dvx = (vx[i] + w[i] * by) - (vx[k] - w[k] * ay)
    dvy = (vy[i] - w[i] * bx) - (vy[k] + w[k] * ax)
    dd = dx * dx + dy * dy
    num = dx * dvx + dy * dvy                     # Delta_l * dDelta_l/dt
    # damper force per unit gap, b (dDelta_l/dt) / Delta_l, with the implicit factor
    # 1 / (1 + h b w_eff) folded into the one division (num = 0 when the gap closes)
    hb = h * bax[i]
    cak = ax * dy - ay * dx
    cbi = bx * dy - by * dx
    den = dd * (1.0 + hb * (inv_m[k] + inv_m[i])) + hb * (cak * cak * inv_i[k] + cbi * cbi * inv_i[i])
    fd = bax[i] * num / max(den, 1e-300)
    if linear:
        fk = kax[i] + fd
    else:
        fk = kax[i] * dd ** (0.5 * (eax - 1.0)) + fd
    Fx = fk * dx
    Fy = fk * dy
    dphi = phi[i] - phi[k]
    if eb == 1.0:
        M = kb[i] * dphi
    else:
        M = kb[i] * math.copysign(abs(dphi) ** eb, dphi)
    dw = w[i] - w[k]
    M += bb[i] * dw
    jfk[i] = fk
    jdx[i] = dx
    jdy[i] = dy
    jmk[i] = ax * Fy - ay * Fx + M        # on k: arm (+a) x F, plus the bending moment
    jmi[i] = bx * Fy - by * Fx - M        # on i: arm (-b) x (-F) = b x F, minus it
    return fd * num, bb[i] * dw * dw


@njit(**STAGE_PY)
def _joint_forces(n, eax, eb, hl, turn, linear, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, fx, fy, mz, jfk, jdx,
                  jdy, h, inv_m, inv_i, jmk, jmi):
    """``joint_forces`` on plain arrays: the compiled loop sees arrays, not records, so that it
    vectorises. A stage (``STAGE``): compiled with reference counting, as a separate function
    it made the step 30-45 % slower (4.0-4.5 against 2.95-3.05 us per step, AMD EPYC)."""
    # two passes without scattered writes (so that the loops vectorise): the joints, then each
    # segment sums its two joints. Joint 0 closes the loop, where phi jumps by the total turn.
    pax, pb = _joint(0, n - 1, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m, inv_i,
                     jfk, jdx, jdy, jmk, jmi)
    if eb == 1.0:
        Mt = kb[0] * turn
    else:
        d0 = phi[0] - phi[n - 1]
        Mt = kb[0] * (math.copysign(abs(d0 + turn) ** eb, d0 + turn) - math.copysign(abs(d0) ** eb, d0))
    jmk[0] += Mt
    jmi[0] -= Mt
    if linear and eb == 1.0:
        # linear joints, written out here (``_joint`` less its dampers' power): with the power
        # summed in this loop, or ``_joint`` inlined into it, it compiled scalar; so it vectorises
        # (333 joints, with the power loop and the sums below: 3.2 against 6.3 us, 2-core AMD EPYC)
        for i in range(1, n):
            k = i - 1
            ax = hl * c[k]
            ay = hl * s[k]
            bx = hl * c[i]
            by = hl * s[i]
            dx = (x[i] - bx) - (x[k] + ax)
            dy = (y[i] - by) - (y[k] + ay)
            dvx = (vx[i] + w[i] * by) - (vx[k] - w[k] * ay)
            dvy = (vy[i] - w[i] * bx) - (vy[k] + w[k] * ax)
            hb = h * bax[i]
            cak = ax * dy - ay * dx
            cbi = bx * dy - by * dx
            den = ((dx * dx + dy * dy) * (1.0 + hb * (inv_m[k] + inv_m[i]))
                   + hb * (cak * cak * inv_i[k] + cbi * cbi * inv_i[i]))
            fk = kax[i] + bax[i] * (dx * dvx + dy * dvy) / max(den, 1e-300)
            Fx = fk * dx
            Fy = fk * dy
            M = kb[i] * (phi[i] - phi[k]) + bb[i] * (w[i] - w[k])
            jfk[i] = fk
            jdx[i] = dx
            jdy[i] = dy
            jmk[i] = ax * Fy - ay * Fx + M
            jmi[i] = bx * Fy - by * Fx - M
        # the dampers' power, b (d|d|/dt)^2 / (implicit factor) and bb (dw)^2, from the stored gaps
        for i in range(1, n):
            k = i - 1
            dvx = (vx[i] + w[i] * hl * s[i]) - (vx[k] - w[k] * hl * s[k])
            dvy = (vy[i] - w[i] * hl * c[i]) - (vy[k] + w[k] * hl * c[k])
            pax += (jfk[i] - kax[i]) * (jdx[i] * dvx + jdy[i] * dvy)
            dw = w[i] - w[k]
            pb += bb[i] * dw * dw
    else:
        for i in range(1, n):
            a, b = _joint(i, i - 1, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m,
                          inv_i, jfk, jdx, jdy, jmk, jmi)
            pax += a
            pb += b
    for i in range(n - 1):
        fx[i] = jfk[i + 1] * jdx[i + 1] - jfk[i] * jdx[i]
        fy[i] = jfk[i + 1] * jdy[i + 1] - jfk[i] * jdy[i]
        mz[i] = jmi[i] + jmk[i + 1]
    fx[n - 1] = jfk[0] * jdx[0] - jfk[n - 1] * jdx[n - 1]
    fy[n - 1] = jfk[0] * jdy[0] - jfk[n - 1] * jdy[n - 1]
    mz[n - 1] = jmi[n - 1] + jmk[0]
    return pax, pb


def joint_forces(B, S, W, h):
    """``_joint_forces_of`` called from Python: through the plain arrays, whose compiled wrapper is
    cheap (a record's unboxes each of its arrays: 0.9 s of a first run's compile)."""
    return _joint_forces(B.n, B.eax, B.eb, B.hl, B.turn, B.linear, S.x, S.y, S.c, S.s, S.vx, S.vy, S.w, S.phi,
                         B.kax, B.bax, B.kb, B.bb, W.fx, W.fy, W.mz, W.jfk, W.jdx, W.jdy, h, B.inv_m, B.inv_i,
                         W.jmk, W.jmi)


@njit(cache=True, inline="always")
def _joint_forces_of(B, S, W, h):
    """Elastic + damping forces of all joints into W.fx, W.fy, W.mz (overwritten).

    Stores per joint the gap vector (jdx, jdy) and jfk with force vector = jfk * d (tension
    = jfk |d|), and the moments on both segments (jmk, jmi). Returns (dissipated power in axial
    dampers, in bending dampers).

    With h > 0 the axial damper is integrated implicitly for its own joint: its force
    b v_n / (1 + h b w_eff), w_eff the inverse effective mass of the two segment ends along the
    gap (translation and rotation). The damper acts along the gap vector (eq. 18), which at low
    tension need not be along the belt, and then damps the segments' stiff rotation; explicitly
    that limits the step below the elastic limit, implicitly it does not. h = 0 gives eq. 18 as
    written (used by RKF45).
    """
    return _joint_forces(B.n, B.eax, B.eb, B.hl, B.turn, B.linear, S.x, S.y, S.c, S.s, S.vx, S.vy, S.w, S.phi,
                         B.kax, B.bax, B.kb, B.bb, W.fx, W.fy, W.mz, W.jfk, W.jdx, W.jdy, h, B.inv_m, B.inv_i,
                         W.jmk, W.jmi)


def static_forces(B, Ct, P, S, W):
    """Generalised forces -dE/dq of the belt at rest (S with zero velocities, so that no damper
    acts): joints, contact normal force (the integrators' ``normal_force``), gravity, into W.fx,
    W.fy, W.mz (used by equilibrium.relax). Through the plain arrays, as ``joint_forces`` (the
    records' compiled wrapper and flattened arguments: 3.7 s of a first run's compile)."""
    joint_forces(B, S, W, 0.0)
    _static_contacts(B.n, P.nk, B.m, B.g, S.x, S.y, S.cx, S.cy, P.r, Ct.c1, Ct.c2, Ct.bc, Ct.pmax, W.fx, W.fy)


@njit(cache=True, no_cfunc_wrapper=True)
def _static_contacts(n, nk, m, g, x, y, pcx, pcy, pr, c1, c2, bc, pmax, fx, fy):
    """``static_forces``' contact normal forces and gravity, added to fx, fy."""
    for i in range(n):
        for j in range(nk):
            rx = x[i] - pcx[j]
            ry = y[i] - pcy[j]
            d2 = rx * rx + ry * ry
            if d2 >= pr[j] * pr[j]:
                continue
            dist = math.sqrt(d2)
            N, _ = normal_force(c1[i], c2[i], bc[i], pmax, pr[j] - dist, 0.0, 0.0)
            fx[i] += N * rx / dist
            fy[i] += N * ry / dist
        fy[i] -= m[i] * g


# ---- tensioners ------------------------------------------------------------------------------


# ---- semi-implicit and implicit integrators ---------------------------------------------------

# the implicit scheme refactors its chain matrix once the fastest segment has turned this far
# (rad): the explicit forces are exact, the implicit terms act along the factored directions
# (see _chain.py), so a stuck segment's friction tilts by up to this angle. Loaded accessory drive
# at its default step, slips against the reference: free idler +0.027 points at 0.05 rad, +0.003
# at 0.02, -0.005 at 0.01; 1-2 % more factorisations on the 5PK (0.019 against 0.012 per step)
REFACTOR_ANGLE = 0.02
# segments whose stick-slip state differs from the factored one within a step (CMAX), and
# segments whose columns A_f^-1 [e_x e_y] are cached between factorisations (ZMAX)
CMAX = 8
ZMAX = 8
# the anchor slope, x mu N / Delta_v: the secant of the Threlfall law to its saturation, so an
# anchor lets go where the law saturates (its tangent at zero, 1.5, flickered and drifted at 20 us)
ANCHOR = 1.0
# the implicit scheme's limiter of the segments' alternating rotation in free spans. Under tension
# T a segment of a free span rotating against its neighbours is held by T l alone (the joints do
# not stretch): omega^2 = 12 T / (m l), 6 kHz for 4.5 mm segments at 300 N, undamped (no bending
# damping by default) and resolved only marginally at the implicit scheme's 20-40 us, where segment
# transport can pump it: segments of the free spans spinning within milliseconds (the accessory
# drive at 337 segments halved its step four times, to 2.2 us). Where a free segment's rotation rate
# departs from its neighbours' mean by more than SPIN_LIMIT x the fastest pulley's speed (which
# ordinary running stays well below), a damper on the second difference of the rates (zero for a
# rigid turn and a uniformly changing one) gives that mode the damping ratio SPIN_ZETA; explicit,
# stable while zeta h omega < 1. Below the limit the model runs undamped, as the reference does.
SPIN_ZETA = 0.2
SPIN_LIMIT = 3.0
# passes of the stick-slip active set per step (each a small dense solve): anchors let go in any
# of them, sliding segments are anchored in all but the last; one more pass takes the last changes in
PASSES = 6


@njit(cache=True, inline="always")
def _move(i, h, vxs, vys, x, y, vx, vy, w, phi, c, s):
    """Segment i takes its new velocity (vxs, vys) and moves over the step (``_turn``)."""
    vx[i] = vxs
    vy[i] = vys
    x[i] += h * vxs
    y[i] += h * vys
    _turn(i, h, w, phi, c, s)


@njit(cache=True, inline="always")
def _turn(i, h, w, phi, c, s):
    """Segment i's angle turns by a = h w over the step, (c, s) rotated exactly to round-off
    (series to a^5; |a| < 2e-2 here)."""
    a = h * w[i]
    phi[i] += a
    a2 = a * a
    ca = 1.0 - 0.5 * a2 * (1.0 - a2 / 12.0)
    sa = a * (1.0 - a2 / 6.0 * (1.0 - a2 / 20.0))
    cn = c[i] * ca - s[i] * sa
    s[i] = s[i] * ca + c[i] * sa
    c[i] = cn


# a free segment's contact test is skipped for at most this many steps (see _contact_candidate)
SKIP_MAX = 64


@njit(cache=True, inline="always")
def _contact_candidate(i, nk, x, y, pcx, pcy, pr, cand_j, cand_skip, hvb):
    """The pulley whose circle holds segment i's centre, or -1, and the centre's offset from it
    (rx, ry) and its square d2 (zeros for -1); pulleys do not overlap, so at most one. Not every
    pulley is tested every step: a segment on a pulley is tested against that one first; a free
    segment, once tested against all, is not tested again for as many steps as it needs to cross
    its clearance to the nearest pulley at the speed bound hvb / h (twice the fastest segment and
    pulley centre, plus 1 m/s; at most SKIP_MAX steps)."""
    j0 = cand_j[i]
    if j0 >= 0:
        rx = x[i] - pcx[j0]
        ry = y[i] - pcy[j0]
        d2 = rx * rx + ry * ry
        if d2 < pr[j0] * pr[j0]:
            return j0, rx, ry, d2
    elif cand_skip[i] > 0:
        cand_skip[i] -= 1
        return -1, 0.0, 0.0, 0.0
    gmin = 1e300
    for j in range(nk):
        rx = x[i] - pcx[j]
        ry = y[i] - pcy[j]
        d2 = rx * rx + ry * ry
        if d2 < pr[j] * pr[j]:
            cand_j[i] = j
            return j, rx, ry, d2
        gmin = min(gmin, math.sqrt(d2) - pr[j])
    cand_j[i] = -1
    cand_skip[i] = min(SKIP_MAX, int(gmin / hvb))
    return -1, 0.0, 0.0, 0.0


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _refactor(n, h, hl, eax, eb, linear, kax, bax, kb, bb, c, s, w, phi, jfk, jdx, jdy, turn, m, ieff, sig, gam,
              geo, kap, kat, knx, kny, dmat, omat, emat, dinv, ymat, xmat):
    """Factor the chain matrix at the current angles (joint tangent stiffnesses at the current
    gaps); returns the number of steps it serves (turning of the fastest segment, REFACTOR_ANGLE).
    geo: scratch (n), the joints' geometric stiffness on the segments' rotation: the force F of a
    joint turning the arm a of a segment end stiffens that rotation by F . a (the tension's
    T l / 2 per end, which sets the segment-scale transverse waves, h < l / sqrt(T / rho),
    explicitly); taken only where positive so that A stays positive definite."""
    wmax = 0.0
    for i in range(n):
        geo[i] = 0.0
    for i in range(n):
        k = i - 1 if i > 0 else n - 1
        ga = jfk[i] * (jdx[i] * hl * c[k] + jdy[i] * hl * s[k])
        gb = jfk[i] * (jdx[i] * hl * c[i] + jdy[i] * hl * s[i])
        geo[k] += 0.5 * h * h * max(ga, 0.0)
        geo[i] += 0.5 * h * h * max(gb, 0.0)
        kt = kax[i]
        if not linear:   # tangent of kax |d|^e (its larger, radial-direction value)
            kt = kax[i] * max(eax, 1.0) * math.sqrt(jdx[i] * jdx[i] + jdy[i] * jdy[i]) ** (eax - 1.0)
        sig[i] = 0.5 * h * h * kt + h * bax[i]
        kbt = kb[i]
        if eb != 1.0:
            dphi = phi[i] - phi[k] + (turn if i == 0 else 0.0)
            kbt = kb[i] * eb * max(abs(dphi), 1e-6) ** (eb - 1.0)
        gam[i] = 0.5 * h * h * kbt + h * bb[i]
        wmax = max(wmax, abs(w[i]))
    _chain.factor(n, hl, c, s, m, ieff, sig, gam, geo, kap, kat, knx, kny, dmat, omat, emat, dinv, ymat, xmat)
    return max(1, min(1000, int(REFACTOR_ANGLE / (h * wmax + 1e-300))))


@njit(**STAGE_PY)
def _joint_transport(n, h, hl, linear, eax, kax, bax, c, s, w, jdx, jdy, fx, fy, mz):
    """Stage (implicit scheme): the joints' share of A acting on the gap's acceleration, not on its
    linear part alone. A's joint term sig G^T G reads the velocity change G dv of a joint's two
    ends, whose true gap acceleration also holds the ends' centripetal terms w_i^2 b + w_k^2 a. A
    chain rolling round a pulley keeps its gaps, yet G dv = -h w^2 (chord): read alone, every
    joint on a wrap pushed its segments apart by sig w^2 l, (h w)^2 EA / 2 (52 N at 0.024 rad per
    step on the 6PK belt: the implicit scheme's loss of accuracy at a large turn per step). Here
    the centripetal part joins the right-hand side, so that A acts on the deviation from rolling:
    the force -sig G^T q, q = w_i^2 b + w_k^2 a."""
    for j in range(n):
        k = j - 1 if j > 0 else n - 1
        kt = kax[j]
        if not linear:
            kt = kax[j] * max(eax, 1.0) * math.sqrt(jdx[j] * jdx[j] + jdy[j] * jdy[j]) ** (eax - 1.0)
        sig = 0.5 * h * h * kt + h * bax[j]
        ax = hl * c[k]
        ay = hl * s[k]
        bx = hl * c[j]
        by = hl * s[j]
        wi2 = w[j] * w[j]
        wk2 = w[k] * w[k]
        gx = -sig * (wi2 * bx + wk2 * ax)
        gy = -sig * (wi2 * by + wk2 * ay)
        fx[j] += gx
        fy[j] += gy
        mz[j] += by * gx - bx * gy
        fx[k] -= gx
        fy[k] -= gy
        mz[k] += ay * gx - ax * gy


@njit(**STAGE)
def _velocity_change(n, nk, nC, ipl, dom, qv, cseg, zslot, lin_u, zc, yx, yy, yz, fx, fy, mz):
    """Stage (implicit scheme, chain solve): the step's acceleration (fx, fy, mz) = A_f^-1 F from the
    base solve y, the implicit pulleys' speed changes dom over their columns U_k (lin_u) and the
    active set's force corrections qv over their cached columns Z_c (zc)."""
    for i in range(n):
        fx[i] = yx[i]
        fy[i] = yy[i]
        mz[i] = yz[i]
    for kk in range(nk):
        if ipl[kk]:
            dk = dom[kk]
            for i in range(n):
                fx[i] += dk * lin_u[kk, i, 0]
                fy[i] += dk * lin_u[kk, i, 1]
                mz[i] += dk * lin_u[kk, i, 2]
    for d in range(nC):
        sd = 2 * zslot[cseg[d]]
        p0 = qv[2 * d]
        p1 = qv[2 * d + 1]
        for i in range(n):
            fx[i] += p0 * zc[sd, i, 0] + p1 * zc[sd + 1, i, 0]
            fy[i] += p0 * zc[sd, i, 1] + p1 * zc[sd + 1, i, 1]
            mz[i] += p0 * zc[sd, i, 2] + p1 * zc[sd + 1, i, 2]


@njit(**STAGE)
def _accumulate(h, hl, x, y, c, s, vx, vy, jfk, jdx, jdy, seg_n, seg_t, span_geo, span_joint, track_seg, acc_span,
                acc_track, acc_diss, pax, pb, pcd, pfr, diss_cl):
    """Stage: the step's share of the accumulators: mid-span tension and belt speed (following the
    joint nearest each span's midpoint as the belt moves), tracked segments, dissipation."""
    n = x.shape[0]
    nspan = span_geo.shape[0]
    ntrack = track_seg.shape[0]
    # mid-span tension: follow the joint nearest each span's midpoint as the belt moves
    for q in range(nspan):
        best = span_joint[q]
        bestd = 1e300
        for dk in range(-2, 3):
            jj = span_joint[q] + dk
            if jj < 0:
                jj += n
            elif jj >= n:
                jj -= n
            kk = jj - 1 if jj > 0 else n - 1
            px = 0.5 * (x[jj] - hl * c[jj] + x[kk] + hl * c[kk]) - span_geo[q, 0]
            py = 0.5 * (y[jj] - hl * s[jj] + y[kk] + hl * s[kk]) - span_geo[q, 1]
            dd = px * px + py * py
            if dd < bestd:
                bestd = dd
                best = jj
        span_joint[q] = best
        acc_span[q, 0] += h * jfk[best] * math.sqrt(jdx[best] * jdx[best] + jdy[best] * jdy[best])
        kb_ = best - 1 if best > 0 else n - 1
        acc_span[q, 1] += h * 0.5 * ((vx[best] + vx[kb_]) * span_geo[q, 2] + (vy[best] + vy[kb_]) * span_geo[q, 3])
    for q in range(ntrack):
        i = track_seg[q]
        jn = i + 1 if i < n - 1 else 0       # the joint after segment i
        acc_track[q, 0] += h * jfk[jn] * math.sqrt(jdx[jn] * jdx[jn] + jdy[jn] * jdy[jn])
        acc_track[q, 1] += h * seg_n[i]
        acc_track[q, 2] += h * seg_t[i]
    acc_diss[0] += h * pax
    acc_diss[1] += h * pb
    acc_diss[2] += h * pcd
    acc_diss[3] += h * pfr
    acc_diss[5] += diss_cl


# the implicit scheme's per-segment scratch within a chunk: float columns of ``sc`` (n, NSC) ...
(C_NX, C_NY,        # contact normal
 C_P, C_R,          # penetration, distance from the pulley's centre (friction's arm)
 C_N, C_KAP,        # normal force, A's contact coefficient
 C_CA, C_T, C_TB,   # anchor slope now (N s/m; 0: sliding), sliding friction now and in F_base
 C_CAN,             # centripetal acceleration v_t^2 / r (see _base_solve)
 C_TMX, C_TMY,      # the chord's tangent t_m (see _contacts)
 C_VPX, C_VPY,      # the rolling prediction vp
 C_AK, C_ATX, C_ATY, C_ATR,  # the anchor as the last pass solved it: slope, direction, arm
 C_F0X, C_F0Y, C_F0Z,   # F_base: the step's forces with every segment in its factored state
 C_T0, C_T0B,       # an anchor's explicit force now and in F_base (elastic-plastic: K z; Threlfall: 0)
 C_DB, C_VN, C_HCN,  # contact damping rate delta(p) b, the normal velocity it was read at, h v_t^2 / r
 NSC) = range(27)
# ... and int columns of ``si`` (n, NSI): the pulley it touches (-1: none), the list of segments in
# contact, a segment's place in the active set C (-1: none), the list of segments to join C
(I_J, I_LIST, I_SLOT, I_PEND, NSI) = range(5)


@njit(**STAGE)
def _spin_damper(n, h, hl, spin_lim, ieff, w, jfk, jdx, jdy, seg_n, spd, cs, mz, pb):
    """Stage (implicit scheme): SPIN_ZETA's damper on segments whose neighbours two either side were
    free at the last step, where their rate departs from the neighbours' by spin_lim (SPIN_LIMIT).
    Adds its moments to mz; returns pb less its power."""
    for i in range(n):
        free = True
        for dk in range(-2, 3):
            kk = i + dk
            if kk < 0:
                kk += n
            elif kk >= n:
                kk -= n
            free = free and seg_n[kk] == 0.0
        im = i - 1 if i > 0 else n - 1
        ip = i + 1 if i < n - 1 else 0
        spd[i] = w[im] - 2.0 * w[i] + w[ip] if free else 0.0
        # the mode's stiffness T l (T the mean force of the segment's two joints) and its
        # modified inertia I + h^2/2 T l; the alternating pattern sees 16 x the coefficient
        ka = 0.5 * (jfk[i] * math.sqrt(jdx[i] * jdx[i] + jdy[i] * jdy[i])
                    + jfk[ip] * math.sqrt(jdx[ip] * jdx[ip] + jdy[ip] * jdy[ip])) * 2.0 * hl
        ka = max(ka, 0.0)
        on = free and abs(spd[i]) > spin_lim
        cs[i] = 2.0 * SPIN_ZETA * math.sqrt(ka * (ieff[i] + 0.5 * h * h * ka)) / 16.0 if on else 0.0
    for i in range(n):
        im = i - 1 if i > 0 else n - 1
        ip = i + 1 if i < n - 1 else 0
        ms = -(cs[im] * spd[im] - 2.0 * cs[i] * spd[i] + cs[ip] * spd[ip])
        mz[i] += ms
        pb -= ms * w[i]
    return pb


@njit(**STAGE)
def _contacts(n, nk, h, hvb, g, m, c1, c2, bc, pmax, centre, x, y, vx, vy, pcx, pcy, pvx, pvy, pr, cand_j, cand_skip,
              stk, z, fy, si, sc):
    """Stage (implicit scheme), gravity and contact: per segment the pulley it touches, its normal
    and penetration, its normal force (``normal_force`` at the explicit normal velocity) and A's
    contact coefficient, and the chord it rolls along. Returns (segments in contact, listed in
    si[:, I_LIST]; contact damping power)."""
    nc = 0
    pcd = 0.0
    for i in range(n):
        fy[i] -= m[i] * g
        si[i, I_J] = -1
        j, rx, ry, d2 = _contact_candidate(i, nk, x, y, pcx, pcy, pr, cand_j, cand_skip, hvb)
        if j >= 0:      # pulleys do not overlap: one contact per segment
            dist = math.sqrt(d2)
            nx = rx / dist
            ny = ry / dist
            p = pr[j] - dist
            rvx = vx[i] - pvx[j]
            rvy = vy[i] - pvy[j]
            # the normal velocity at the middle of the last step's chord: a segment rolling
            # round the pulley arrives along a chord that leaves the circle's normal by half
            # its turn, which read at the end point is a separating v_t^2 h / 2 r (at 0.03 rad
            # per step it took nearly all the damping's share of the normal force)
            vt_ = -rvx * ny + rvy * nx
            vn = rvx * nx + rvy * ny - 0.5 * h * vt_ * vt_ / dist
            N, db = normal_force(c1[i], c2[i], bc[i], pmax, p, vn, 0.0)
            si[i, I_J] = j
            sc[i, C_NX] = nx
            sc[i, C_NY] = ny
            sc[i, C_P] = p
            sc[i, C_R] = dist if centre else pr[j]
            sc[i, C_KAP] = 0.5 * h * h * (c2[i] + 2.0 * c1[i] * p) + h * db
            if N < 0.0:
                N = 0.0
            sc[i, C_N] = N
            # the damping's power is counted at the solved velocity (_update_implicit)
            sc[i, C_DB] = db if N > 0.0 else 0.0
            sc[i, C_VN] = vn
            sc[i, C_HCN] = h * vt_ * vt_ / dist
            if N <= 0.0:
                pcd += clipped_power(c1[i], c2[i], p, vn)
            # slip is read along the chord of the step (t_m: the tangent turned by half
            # the segment's turn round the pulley, h v_t / 2 dist), the direction of a
            # rolling segment's new velocity, whose difference from any other tangent
            # t is read off the rolling prediction vp (rv turned by the whole turn):
            # slip = om r - v_new . t - vp . (t_m - t). Read along the current tangent, a
            # rolling segment's new velocity shows a slip of v (h Omega)^2 / 8, 0.75 mm/s
            # at 0.016 rad per step: against a friction law of 1e-5 m/s the anchors let go.
            ps = 0.5 * h * vt_ / dist
            cps = math.cos(ps)
            sps = math.sin(ps)
            sc[i, C_TMX] = -ny * cps - nx * sps
            sc[i, C_TMY] = -ny * sps + nx * cps
            c2s = cps * cps - sps * sps
            s2s = 2.0 * sps * cps
            sc[i, C_VPX] = rvx * c2s - rvy * s2s
            sc[i, C_VPY] = rvx * s2s + rvy * c2s
        if si[i, I_J] < 0:
            stk[i] = 0.0
            z[i] = 0.0
        else:
            si[nc, I_LIST] = i
            nc += 1
    return nc, pcd


@njit(cache=True, inline="always")
def _anchor(law, mu, N, dv, dmax, h, z):
    """A stuck segment's anchor in the implicit scheme: its slope in A and its explicit force.
    Threlfall: the law's secant ANCHOR mu N / Delta_v, no force; elastic-plastic: the bristle
    T = K (z + h slip), K = mu N / Delta_max, as ``friction`` integrates it: slope h K, force K z."""
    if law == LAW_ELASTIC_PLASTIC:
        K = mu * N / dmax
        return h * K, K * z
    return ANCHOR * mu * N / dv, 0.0


@njit(cache=True, inline="always")
def _pressed(j, sc, i):
    """Whether segment i (on pulley j, -1 for none) is pressed onto its pulley (explicit normal
    force N > 0): the contact set the chain matrix A holds (``_factored_state``, ``_friction``)."""
    return j >= 0 and sc[i, C_N] > 0.0


@njit(**STAGE)
def _friction(n, h, Ct, om, stk, z, fkap, fx, fy, mz, si, sc):
    """Stage (implicit scheme), friction: by its state at the last step, a contact segment is
    anchored to the pulley surface (in A) or slides with mu N against its slip (explicit); the
    contact forces join the step's forces, kept as F_base. The anchor: ``_anchor`` (its explicit
    force in C_T0); an elastic-plastic bristle short of Delta_max is elastic (anchored), one at it
    slides until its slip turns.
    Returns whether the contact set (segments pressed onto a pulley: explicit normal force N > 0)
    differs from the one A was factored with."""
    mu, law, dv, dmax = Ct.mu, Ct.law, Ct.dv, Ct.dmax
    cchg = False
    for i in range(n):
        j = si[i, I_J]
        sc[i, C_T] = 0.0
        sc[i, C_T0] = 0.0
        sc[i, C_CA] = 0.0
        sc[i, C_AK] = 0.0
        if j >= 0:
            N = sc[i, C_N]
            if N > 0.0:
                if stk[i] > 0.0 or (law == LAW_ELASTIC_PLASTIC and abs(z[i]) < dmax):
                    sc[i, C_CA], sc[i, C_T0] = _anchor(law, mu[i], N, dv, dmax, h, z[i])
                else:
                    sl = om[j] * sc[i, C_R] - (sc[i, C_VPX] * sc[i, C_TMX] + sc[i, C_VPY] * sc[i, C_TMY])
                    sc[i, C_T] = math.copysign(mu[i] * N, sl)
            ft = sc[i, C_T] + sc[i, C_T0]
            fx[i] += N * sc[i, C_NX] - ft * sc[i, C_NY]
            fy[i] += N * sc[i, C_NY] + ft * sc[i, C_NX]
        if _pressed(j, sc, i) != (fkap[i] > 0.0):
            cchg = True
        sc[i, C_F0X] = fx[i]
        sc[i, C_F0Y] = fy[i]
        sc[i, C_F0Z] = mz[i]
    return cchg


@njit(**STAGE)
def _factored_state(n, h, si, sc, fkap, fnx, fny, fca, far, kat, zslot):
    """Stage (implicit scheme): the contact and friction state A is about to be factored with
    (contact coefficients, normals, anchor slopes and arms); empties the cache of columns."""
    # A holds a segment's contact only while the contact pushes (N > 0). A segment that leaves
    # faster than the contact pushes (N <= 0: eq. 10 clips the force at zero, no adhesion) kept
    # A's contact damping h delta b, a damper that pulled it back and dissipated energy no loss term
    # counted: fead-runup's drive held at 3000 rpm without orders, 333 segments, lost 63 W unseen at
    # 11.4 us (efficiency 0.959; semi-implicit 0.965) and 13 W with this rule (0.968)
    for i in range(n):
        fkap[i] = sc[i, C_KAP] if _pressed(si[i, I_J], sc, i) else 0.0
        fnx[i] = sc[i, C_NX]
        fny[i] = sc[i, C_NY]
        fca[i] = sc[i, C_CA]
        far[i] = sc[i, C_R]
        kat[i] = h * sc[i, C_CA]
        zslot[i] = -1


@njit(**STAGE)
def _pulley_columns(n, nk, nc, far, fca, fnx, fny, si, ipl, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r, lin_u, lin_g):
    """Stage (implicit scheme, after a factorisation): each implicit pulley's anchors
    g_k = sum fca r tau_f (r: each anchor's factored arm) and their columns U_k = A_f^-1 g_k
    (lin_u); lin_g holds G[j, k] = g_j . U_k and, in column nk, R_j = sum fca r^2."""
    for jj in range(nk):
        for kk in range(nk + 1):
            lin_g[jj, kk] = 0.0
    for jj in range(nk):
        if not ipl[jj]:
            continue
        for i in range(n):
            if fca[i] > 0.0 and si[i, I_J] == jj:
                ux[i] = fca[i] * far[i] * -fny[i]
                uy[i] = fca[i] * far[i] * fnx[i]
                lin_g[jj, nk] += fca[i] * far[i] * far[i]
            else:
                ux[i] = 0.0
                uy[i] = 0.0
            uz[i] = 0.0
        _chain.solve(n, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r)
        for i in range(n):
            lin_u[jj, i, 0] = ux[i]
            lin_u[jj, i, 1] = uy[i]
            lin_u[jj, i, 2] = uz[i]
    for q in range(nc):
        i = si[q, I_LIST]
        jj = si[i, I_J]
        if fca[i] > 0.0 and ipl[jj]:
            gx = fca[i] * far[i] * -fny[i]
            gy = fca[i] * far[i] * fnx[i]
            for kk in range(nk):
                if ipl[kk]:
                    lin_g[jj, kk] += gx * lin_u[kk, i, 0] + gy * lin_u[kk, i, 1]


@njit(**STAGE)
def _base_solve(n, nk, nc, nC, vx, vy, om, pvx, pvy, pr, fkap, fnx, fny, fca, far, si, cseg, sc, yx, yy, yz, s0,
                gyv, ipl, lin_dinv, lin_y, lin_x, lin_r):
    """Stage (implicit scheme, chain solve): y = A_f^-1 F_base, F_base the forces with every contact
    segment in its factored state (anchored along its factored tangent with its factored slope
    and arm, or sliding with its friction now), and per pulley the base friction torque s0 and
    g_j . y.
    Empties C (nC members before); lists in si[:, I_PEND] the segments whose state differs from
    the factored one. Returns their number."""
    for p in range(nC):
        si[cseg[p], I_SLOT] = -1
    npend = 0
    for i in range(n):
        yx[i] = sc[i, C_F0X]
        yy[i] = sc[i, C_F0Y]
        yz[i] = sc[i, C_F0Z]
    for jj in range(nk):
        s0[jj] = 0.0
        gyv[jj] = 0.0
    for q in range(nc):
        i = si[q, I_LIST]
        j = si[i, I_J]
        cT = sc[i, C_T]
        sc[i, C_TB] = cT
        sc[i, C_T0B] = sc[i, C_T0]
        s0[j] += sc[i, C_T0] * sc[i, C_R]
        if fkap[i] > 0.0:
            # the contact term of A, fkap fn fn^T, would read a segment's turn round the pulley
            # (its velocity turning inward by h v_t^2 / r) as an inward normal velocity change
            # and push back by fkap v_t^2 / r (outward; 90 N per segment at 23.6 m/s on a 75 mm
            # crank at 38.5 us, twice its normal force): taken out here, so that A's contact
            # term acts on the deviation from rolling round the pulley
            tvx = vx[i] - pvx[j]
            tvy = vy[i] - pvy[j]
            vt = -tvx * fny[i] + tvy * fnx[i]
            can = vt * vt / (pr[j] - sc[i, C_P])
            sc[i, C_CAN] = can
            yx[i] -= fkap[i] * can * fnx[i]
            yy[i] -= fkap[i] * can * fny[i]
        else:
            sc[i, C_CAN] = 0.0
        if fca[i] > 0.0:
            tx = -fny[i]
            ty = fnx[i]
            sl = (om[j] * far[i] - (vx[i] - pvx[j]) * tx - (vy[i] - pvy[j]) * ty
                  - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
            yx[i] += fca[i] * sl * tx + cT * sc[i, C_NY]
            yy[i] += fca[i] * sl * ty - cT * sc[i, C_NX]
            s0[j] += fca[i] * sl * far[i]
        else:
            s0[j] += cT * sc[i, C_R]
        if (fca[i] > 0.0) != (sc[i, C_CA] > 0.0):
            si[npend, I_PEND] = i
            npend += 1
    _chain.solve(n, yx, yy, yz, lin_dinv, lin_y, lin_x, lin_r)
    for q in range(nc):
        i = si[q, I_LIST]
        j = si[i, I_J]
        if fca[i] > 0.0 and ipl[j]:
            gyv[j] += fca[i] * far[i] * (-fny[i] * yx[i] + fnx[i] * yy[i])
    return npend


@njit(**STAGE)
def _join(n, nC, npend, si, cseg, zslot, zc, lin_cnt, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r):
    """Stage (implicit scheme, active set): the segments in si[:, I_PEND] join C, their columns
    Z = A_f^-1 [e_x e_y] solved unless cached. Returns (members, whether C or the cache is full:
    then the caller refactors)."""
    zcap = zc.shape[0] // 2
    for a in range(npend):
        i = si[a, I_PEND]
        if si[i, I_SLOT] >= 0:
            continue
        if nC == CMAX or (zslot[i] < 0 and lin_cnt[2] == zcap):
            return nC, True
        if zslot[i] < 0:
            sl_ = lin_cnt[2]
            lin_cnt[2] += 1
            zslot[i] = sl_
            for col in range(2):
                for r in range(n):
                    ux[r] = 0.0
                    uy[r] = 0.0
                    uz[r] = 0.0
                if col == 0:
                    ux[i] = 1.0
                else:
                    uy[i] = 1.0
                _chain.solve(n, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r)
                for r in range(n):
                    zc[2 * sl_ + col, r, 0] = ux[r]
                    zc[2 * sl_ + col, r, 1] = uy[r]
                    zc[2 * sl_ + col, r, 2] = uz[r]
        cseg[nC] = i
        si[i, I_SLOT] = nC
        nC += 1
    return nC, False


@njit(**STAGE)
def _corrections(nC, vx, vy, om, pvx, pvy, fnx, fny, fca, far, si, sc, cseg, cpar):
    """Stage (implicit scheme, active set): each member's force correction (its state now less its
    factored state), affine in its velocity change and its pulley's: phi_c = a + B dv_c + e dw_j,
    and its torque on the pulley's belt side alpha + beta . dv_c + gamma dw_j (the friction times
    its arm), into cpar (a0, a1, b00, b01, b11, e0, e1, alpha, beta0, beta1, gamma)."""
    for p in range(nC):
        i = cseg[p]
        j = si[i, I_J]
        ctx = -sc[i, C_NY]
        cty = sc[i, C_NX]
        a0 = 0.0
        a1 = 0.0
        b00 = 0.0
        b01 = 0.0
        b11 = 0.0
        e0 = 0.0
        e1 = 0.0
        al = 0.0
        be0 = 0.0
        be1 = 0.0
        ga = 0.0
        # an anchor's explicit force (elastic-plastic K z) now less the one in F_base
        dT0 = sc[i, C_T0] - sc[i, C_T0B]
        a0 += dT0 * ctx
        a1 += dT0 * cty
        al += dT0 * sc[i, C_R]
        for side in range(2):
            # + its state now (anchor along the current tangent, or its sliding friction),
            # - its factored state (anchor along the factored tangent, or its friction in F_base)
            if side == 0:
                sg, kp, tx, ty, Tsl, ar = 1.0, sc[i, C_CA], ctx, cty, sc[i, C_T], sc[i, C_R]
            else:
                sg, kp, tx, ty, Tsl = -1.0, fca[i], -fny[i], fnx[i], sc[i, C_TB]
                ar = far[i] if kp > 0.0 else sc[i, C_R]
            if kp > 0.0:
                sl = (om[j] * ar - (vx[i] - pvx[j]) * tx - (vy[i] - pvy[j]) * ty
                      - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
                a0 += sg * kp * sl * tx
                a1 += sg * kp * sl * ty
                b00 -= sg * kp * tx * tx
                b01 -= sg * kp * tx * ty
                b11 -= sg * kp * ty * ty
                e0 += sg * kp * ar * tx
                e1 += sg * kp * ar * ty
                al += sg * kp * sl * ar
                be0 -= sg * kp * tx * ar
                be1 -= sg * kp * ty * ar
                ga += sg * kp * ar * ar
            else:
                a0 += sg * Tsl * ctx
                a1 += sg * Tsl * cty
                al += sg * Tsl * ar
        cpar[p, 0] = a0
        cpar[p, 1] = a1
        cpar[p, 2] = b00
        cpar[p, 3] = b01
        cpar[p, 4] = b11
        cpar[p, 5] = e0
        cpar[p, 6] = e1
        cpar[p, 7] = al
        cpar[p, 8] = be0
        cpar[p, 9] = be1
        cpar[p, 10] = ga


@njit(**STAGE)
def _small_system(h, nk, nC, pinv_i, mext, zslot, zc, lin_u, lin_g, si, cseg, cpar, qm, qv, yx, yy, s0, gyv,
                  ipl, dom, lin_cnt):
    """Stage (implicit scheme, active set): the members' force corrections and the implicit
    pulleys' speed changes from the dense (2 nC + nk) system: rows 2p, 2p + 1 for member p, row
    2 nC + j for pulley j (its torque balance over the step, applied torque mext). Solved into
    qv; the speed changes into dom."""
    msz = 2 * nC + nk
    for r in range(msz):
        qv[r] = 0.0
        for q in range(msz):
            qm[r, q] = 0.0
    for p in range(nC):
        i = cseg[p]
        j = si[i, I_J]
        b00 = cpar[p, 2]
        b01 = cpar[p, 3]
        b11 = cpar[p, 4]
        r0 = 2 * p
        qm[r0, r0] = 1.0
        qm[r0 + 1, r0 + 1] = 1.0
        for d in range(nC):
            sd = 2 * zslot[cseg[d]]
            for col in range(2):
                z0 = zc[sd + col, i, 0]
                z1 = zc[sd + col, i, 1]
                qm[r0, 2 * d + col] -= h * (b00 * z0 + b01 * z1)
                qm[r0 + 1, 2 * d + col] -= h * (b01 * z0 + b11 * z1)
        for kk in range(nk):
            if ipl[kk]:
                u0 = lin_u[kk, i, 0]
                u1 = lin_u[kk, i, 1]
                qm[r0, 2 * nC + kk] -= h * (b00 * u0 + b01 * u1)
                qm[r0 + 1, 2 * nC + kk] -= h * (b01 * u0 + b11 * u1)
        qm[r0, 2 * nC + j] -= cpar[p, 5]
        qm[r0 + 1, 2 * nC + j] -= cpar[p, 6]
        qv[r0] = cpar[p, 0] + h * (b00 * yx[i] + b01 * yy[i])
        qv[r0 + 1] = cpar[p, 1] + h * (b01 * yx[i] + b11 * yy[i])
    for jj in range(nk):
        r0 = 2 * nC + jj
        if not ipl[jj]:
            qm[r0, r0] = 1.0
            continue
        qm[r0, r0] += 1.0 / pinv_i[jj] + h * lin_g[jj, nk]
        for kk in range(nk):
            qm[r0, 2 * nC + kk] -= h * h * lin_g[jj, kk]
        for d in range(nC):
            qm[r0, 2 * d] -= h * h * lin_u[jj, cseg[d], 0]
            qm[r0, 2 * d + 1] -= h * h * lin_u[jj, cseg[d], 1]
        qv[r0] = h * mext[jj] - h * s0[jj] + h * h * gyv[jj]
        for p in range(nC):
            i = cseg[p]
            if si[i, I_J] != jj:
                continue
            be0 = cpar[p, 8]
            be1 = cpar[p, 9]
            qm[r0, r0] += h * cpar[p, 10]
            for kk in range(nk):
                if ipl[kk]:
                    qm[r0, 2 * nC + kk] += h * h * (be0 * lin_u[kk, i, 0] + be1 * lin_u[kk, i, 1])
            for d in range(nC):
                sd = 2 * zslot[cseg[d]]
                for col in range(2):
                    qm[r0, 2 * d + col] += h * h * (be0 * zc[sd + col, i, 0] + be1 * zc[sd + col, i, 1])
            qv[r0] -= h * (cpar[p, 7] + h * (be0 * yx[i] + be1 * yy[i]))
    _small_solve(msz, qm, qv)
    for jj in range(nk):
        dom[jj] = qv[2 * nC + jj]
    lin_cnt[3] += 1


@njit(**STAGE)
def _check(h, nk, nc, nC, npend, npass, Ct, vx, vy, om, pvx, pvy, fnx, fny, fca, far, stk, z, zslot,
           zc, lin_u, lin_stat, si, sc, cseg, yx, yy, qv, dom, ipl):
    """Stage (implicit scheme, active set): every contact segment at the velocity pass npass
    solved. An anchor whose force would exceed mu N lets go (slides with mu N this step) in any
    of the PASSES, a sliding segment whose slip the step would turn sticks in all but the last.
    Changed segments not in C join si[:, I_PEND]. Returns (whether any changed, their number)."""
    mu, law, dv, dmax = Ct.mu, Ct.law, Ct.dv, Ct.dmax
    changed = False
    for q in range(nc):
        i = si[q, I_LIST]
        N = sc[i, C_N]
        if N <= 0.0:
            continue
        j = si[i, I_J]
        ax_ = yx[i]
        ay_ = yy[i]
        for kk in range(nk):
            if ipl[kk]:
                ax_ += dom[kk] * lin_u[kk, i, 0]
                ay_ += dom[kk] * lin_u[kk, i, 1]
        for d in range(nC):
            sd = 2 * zslot[cseg[d]]
            ax_ += qv[2 * d] * zc[sd, i, 0] + qv[2 * d + 1] * zc[sd + 1, i, 0]
            ay_ += qv[2 * d] * zc[sd, i, 1] + qv[2 * d + 1] * zc[sd + 1, i, 1]
        rvx = vx[i] + h * ax_ - pvx[j]
        rvy = vy[i] + h * ay_ - pvy[j]
        nx = sc[i, C_NX]
        ny = sc[i, C_NY]
        if sc[i, C_CA] > 0.0:
            if si[i, I_SLOT] >= 0:
                kp = sc[i, C_CA]
                tx = -ny
                ty = nx
                ar = sc[i, C_R]
            else:
                kp = fca[i]
                tx = -fny[i]
                ty = fnx[i]
                ar = far[i]
            T = sc[i, C_T0] + kp * ((om[j] + dom[j]) * ar - rvx * tx - rvy * ty
                                    - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
            sc[i, C_AK] = kp           # the anchor as this pass solved it (the update reads it)
            sc[i, C_ATX] = tx
            sc[i, C_ATY] = ty
            sc[i, C_ATR] = ar
            if abs(T) > mu[i] * N and npass < PASSES:
                # lets go: slides this step with mu N
                Ts = math.copysign(mu[i] * N, T)
                sc[i, C_AK] = 0.0
                sc[i, C_CA] = 0.0
                stk[i] = 0.0
                sc[i, C_T] = Ts
                dT = Ts - sc[i, C_T0]
                sc[i, C_T0] = 0.0
                sc[i, C_F0X] += dT * -ny
                sc[i, C_F0Y] += dT * nx
                changed = True
                lin_stat[0] += 1
                if si[i, I_SLOT] < 0:
                    si[npend, I_PEND] = i
                    npend += 1
        elif sc[i, C_T] != 0.0 and npass < PASSES - 1:
            cT = sc[i, C_T]
            sl = (om[j] + dom[j]) * sc[i, C_R] - rvx * sc[i, C_TMX] - rvy * sc[i, C_TMY]
            if sl * cT < 0.0:
                # a sliding segment whose slip the step would turn: it sticks (elastic-plastic:
                # its bristle held at z, its force K z)
                ca, T0 = _anchor(law, mu[i], N, dv, dmax, h, z[i])
                sc[i, C_CA] = ca
                sc[i, C_F0X] += (T0 - cT) * -ny
                sc[i, C_F0Y] += (T0 - cT) * nx
                sc[i, C_T] = 0.0
                sc[i, C_T0] = T0
                stk[i] = 1.0
                changed = True
                lin_stat[1] += 1
                if si[i, I_SLOT] < 0:
                    si[npend, I_PEND] = i
                    npend += 1
    return changed, npend


@njit(**STAGE)
def _update_implicit(n, h, Ct, x, y, phi, c, s, vx, vy, w, om, pvx, pvy, fx, fy, mz, seg_n, seg_t,
                     seg_p, stk, z, fkap, fnx, fny, si, sc, dom, tq_belt, hub):
    """Stage (implicit scheme): each segment takes its velocity change (fx, fy, mz from
    ``_velocity_change``) and moves; its friction at the solved velocities (an anchor's force,
    or mu N sliding), the friction power, belt torques and hub forces (hub: rows x, y), the normal
    force the step applied (N and A's contact term), and its stick-slip state for the next step.
    Returns the friction power and the contact damping's: its force -delta b (v_n + dv_n), the
    part in A only where A holds the contact, times the solved normal velocity v_n + dv_n (dv_n:
    the velocity change along n less a rolling segment's turn, h v_t^2 / r, as A reads it)."""
    mu, law, dv, dmax = Ct.mu, Ct.law, Ct.dv, Ct.dmax
    pfr = 0.0
    pcd = 0.0
    for i in range(n):
        vxs = vx[i] + h * fx[i]
        vys = vy[i] + h * fy[i]
        w[i] += h * mz[i]
        j = si[i, I_J]
        if j >= 0:
            N = sc[i, C_N]
            if N > 0.0:
                # the normal velocity change less the turn of a rolling segment's velocity
                dvn = h * (sc[i, C_NX] * fx[i] + sc[i, C_NY] * fy[i]) + sc[i, C_HCN]
                pcd += sc[i, C_DB] * (sc[i, C_VN] + (dvn if fkap[i] > 0.0 else 0.0)) * (sc[i, C_VN] + dvn)
            T = sc[i, C_T]
            nx = sc[i, C_NX]
            ny = sc[i, C_NY]
            ak = sc[i, C_AK]
            if ak > 0.0:
                tx = sc[i, C_ATX]
                ty = sc[i, C_ATY]
                ar = sc[i, C_ATR]
            else:
                tx = -ny
                ty = nx
                ar = sc[i, C_R]
            if N > 0.0:
                sl = ((om[j] + dom[j]) * ar - (vxs - pvx[j]) * tx - (vys - pvy[j]) * ty
                      - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
                if ak > 0.0:
                    T = sc[i, C_T0] + ak * sl        # the anchor's force at the solved velocities
                pfr += T * sl
                if law == LAW_ELASTIC_PLASTIC:
                    # the bristle's new state, T = K z; at Delta_max it slides on, until its slip turns
                    muN = mu[i] * N
                    dm = dmax * T / muN if muN > 0.0 else 0.0
                    if ak > 0.0 and abs(dm) < dmax:
                        z[i] = dm
                        stk[i] = 1.0
                    elif muN == 0.0:    # no grip (mu = 0): no bristle
                        z[i] = 0.0
                        stk[i] = 0.0
                    else:
                        z[i] = math.copysign(dmax, T)
                        stk[i] = 1.0 if sl * T < 0.0 else 0.0
                elif ak == 0.0:
                    # a sliding segment whose slip reached the band or turned sticks next step
                    stk[i] = 1.0 if (abs(sl) < dv or sl * T < 0.0) else 0.0
                tq_belt[j] -= ar * T
            else:
                stk[i] = 0.0
            # the normal force the step applied: N and A's contact term (see _base_solve)
            N -= fkap[i] * (fnx[i] * fx[i] + fny[i] * fy[i] + sc[i, C_CAN])
            hub[0, j] -= N * nx + T * tx
            hub[1, j] -= N * ny + T * ty
            seg_n[i] = N
            seg_t[i] = T
            seg_p[i] = sc[i, C_P]
        else:
            seg_n[i] = 0.0
            seg_t[i] = 0.0
            seg_p[i] = 0.0
        _move(i, h, vxs, vys, x, y, vx, vy, w, phi, c, s)
    return pfr, pcd


# the semi-implicit contact stage's per-segment rows of ``sq`` (Q_*, n): its contact pulley's
# offset (x, y, squared length), that pulley's centre velocity, radius and speed (a segment without
# one gets a stand-in that gives p = 0: no force), 1 in contact; the normal force, the unit normal,
# friction's arm, the slip before friction, the friction force; the contact damping's and friction's power
(Q_RX, Q_RY, Q_D2, Q_PVX, Q_PVY, Q_R, Q_OM, Q_ON, Q_N, Q_NX, Q_NY, Q_ARM, Q_WS, Q_T, Q_PC, Q_PF, NQ) = range(17)


@njit(**STAGE)
def _contacts_semi(n, nk, h, hg, hvb, hm_, hi_, fx, fy, mz, Ct, S, pr, cand_j, cand_skip, seg_n, seg_t, seg_p, sj, sq,
                   tq_belt, hubx, huby):
    """Stage (semi-implicit scheme): each segment's contact and friction at its new velocity under
    the joints and gravity, implicit in it (the contact damping and the regularised friction:
    ``normal_force``, ``friction``, the pulley's speed frozen over the step); then the move. Adds
    to the pulleys' belt torques and hub forces; returns the contact damping's and friction's power.

    In passes over the segments so that the arithmetic vectorises: the contact test (branches and
    a pulley index) and the sums (into the pulleys, and the powers: ``_advance`` is not compiled
    with fast-math, so a sum in a loop keeps it scalar) are loops of their own; between them every
    segment does the same arithmetic, a segment off the pulleys on a stand-in that gives no force.
    Written per segment with its branches, the stage compiled scalar: fead-runup's drive at 333
    segments stepped in 8.6-8.7 us, in 7.3-7.6 us with the passes (2-core AMD EPYC, alternating
    runs)."""
    c1, c2, bc, mu, pmax, law, dv, dmax, centre = Ct
    x, y, phi, c, s, vx, vy, w, om, z = S.x, S.y, S.phi, S.c, S.s, S.vx, S.vy, S.w, S.om, S.z
    pcx, pcy, pvx, pvy = S.cx, S.cy, S.cvx, S.cvy
    qrx = sq[Q_RX]
    qry = sq[Q_RY]
    qd2 = sq[Q_D2]
    qpvx = sq[Q_PVX]
    qpvy = sq[Q_PVY]
    qr = sq[Q_R]
    qom = sq[Q_OM]
    qon = sq[Q_ON]
    qn = sq[Q_N]
    qnx = sq[Q_NX]
    qny = sq[Q_NY]
    qarm = sq[Q_ARM]
    qws = sq[Q_WS]
    qt = sq[Q_T]
    qpc = sq[Q_PC]
    qpf = sq[Q_PF]
    for i in range(n):          # the contact test
        j, rx, ry, d2 = _contact_candidate(i, nk, x, y, pcx, pcy, pr, cand_j, cand_skip, hvb)
        sj[i] = j
        if j >= 0:
            qrx[i] = rx
            qry[i] = ry
            qd2[i] = d2
            qpvx[i] = pvx[j]
            qpvy[i] = pvy[j]
            qr[i] = pr[j]
            qom[i] = om[j]
            qon[i] = 1.0
        else:
            qrx[i] = 1.0        # the stand-in: p = 0, no force
            qry[i] = 0.0
            qd2[i] = 1.0
            qpvx[i] = 0.0
            qpvy[i] = 0.0
            qr[i] = 1.0
            qom[i] = 0.0
            qon[i] = 0.0
    for i in range(n):          # the normal force, implicit in the contact damping
        hm = hm_[i]
        dist = math.sqrt(qd2[i])
        inv = 1.0 / dist
        nx = qrx[i] * inv
        ny = qry[i] * inv
        p = qr[i] - dist
        # velocities relative to the pulley centre (a tensioner moves it)
        rvx = vx[i] + hm * fx[i] - qpvx[i]
        rvy = vy[i] + hm * fy[i] - hg - qpvy[i]
        vn = rvx * nx + rvy * ny
        N, db = normal_force(c1[i], c2[i], bc[i], pmax, p, vn, hm)
        Np = max(N, 0.0)
        vn_new = vn + hm * Np
        qpc[i] = db * vn_new * vn_new if N > 0.0 else clipped_power(c1[i], c2[i], p, vn)
        arm = dist if centre else qr[i]
        qn[i] = Np
        qnx[i] = nx
        qny[i] = ny
        qarm[i] = arm
        # slip of the pulley surface relative to the segment, along tau = Z x n = (-ny, nx)
        qws[i] = qom[i] * arm - (rvx * -ny + rvy * nx)
        seg_p[i] = p
    if law == LAW_ELASTIC_PLASTIC:
        for i in range(n):      # friction: ``friction``'s bristle, every segment (N = 0: no force)
            T, sl, zn = _bristle(mu[i] * qn[i], dmax, qws[i], z[i], h, hm_[i])
            z[i] = zn if qn[i] > 0.0 else z[i] * qon[i]
            qt[i] = T
            qpf[i] = T * sl
    else:
        for i in range(n):
            T = 0.0
            sl = 0.0
            if qn[i] > 0.0:
                T, sl = friction(mu[i], law, dv, dmax, qn[i], qws[i], hm_[i], h, z, i)
            elif qon[i] == 0.0:
                z[i] = 0.0
            qt[i] = T
            qpf[i] = T * sl
    for i in range(n):          # the force N n + T tau acts; the move
        hm = hm_[i]
        N = qn[i]
        T = qt[i]
        fcx = N * qnx[i] - T * qny[i]
        fcy = N * qny[i] + T * qnx[i]
        qrx[i] = fcx
        qry[i] = fcy
        seg_n[i] = N
        seg_t[i] = T
        vxs = vx[i] + hm * (fx[i] + fcx)
        vys = vy[i] + hm * (fy[i] + fcy) - hg
        vx[i] = vxs
        vy[i] = vys
        x[i] += h * vxs
        y[i] += h * vys
    for i in range(n):          # the turn (a loop of its own: one loop writing all twelve arrays compiled scalar)
        w[i] += hi_[i] * mz[i]
        _turn(i, h, w, phi, c, s)
    # the belt's torque and force on its pulleys, summed along each run of segments on one pulley
    # (not into the pulley's entry per segment: a chain through memory); the powers' sums
    pcd = 0.0
    pfr = 0.0
    jr = -1
    tq = 0.0
    hx = 0.0
    hy = 0.0
    for i in range(n):
        pcd += qpc[i]
        pfr += qpf[i]
        j = sj[i]
        if j != jr:
            if jr >= 0:
                tq_belt[jr] -= tq
                hubx[jr] -= hx
                huby[jr] -= hy
            jr = j
            tq = 0.0
            hx = 0.0
            hy = 0.0
        tq += qarm[i] * qt[i]
        hx += qrx[i]
        hy += qry[i]
    if jr >= 0:
        tq_belt[jr] -= tq
        hubx[jr] -= hx
        huby[jr] -= hy
    return pcd, pfr


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


# a pulley's speed joins the implicit scheme's chain solve where its stuck belt would turn it
# faster than an explicit step can follow: h^2 S / I above this (the explicit limit is 4)
PULLEY_IMPLICIT = 0.5


@njit(cache=True, inline="always")
def _implicit_pulleys(h, B, Ct, P, S, ipl):
    """Which dynamic pulleys (no clutch) the implicit scheme solves with the chain. Under
    Threlfall's law all: a stuck segment's anchor is a stiff viscous slope (mu N / Delta_v), which
    an explicit pulley would not follow. Under the elastic-plastic law the anchors are the
    bristles, a spring K = mu N / Delta_max each: the pulley's rotation on them has
    S = sum K r^2 (N m per rad, from each contact segment's elastic normal force now), and an
    explicit pulley is stable for h^2 S / I < 4; it stays explicit below PULLEY_IMPLICIT, where it
    spares the step a chain solve per pulley and factorisation (fead-runup's drive held with its
    orders, 333 segments, 0.016 rad per step on the alternator: 1.2-1.3x faster at 1000 and 5000
    rpm, 1.5-1.6x at 3000, bands within 1 % of the implicit pulleys'; benchmarks/bench_fead_schemes.py)."""
    nk = P.nk
    for j in range(nk):
        ipl[j] = False
        if P.mode[j] != 0 or P.cl_kind[j] != 0:
            continue
        if Ct.law != LAW_ELASTIC_PLASTIC:
            ipl[j] = True
            continue
        stiff = 0.0
        for i in range(B.n):
            rx = S.x[i] - S.cx[j]
            ry = S.y[i] - S.cy[j]
            d2 = rx * rx + ry * ry
            if d2 < P.r[j] * P.r[j]:
                p = P.r[j] - math.sqrt(d2)
                arm = math.sqrt(d2) if Ct.centre else P.r[j]
                stiff += Ct.mu[i] * (Ct.c1[i] * p * p + Ct.c2[i] * p) / Ct.dmax * arm * arm
        ipl[j] = h * h * stiff * P.inv_i[j] > PULLEY_IMPLICIT
    return ipl


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


@njit(cache=True, inline="always")
def _probe(n, nk, S, P, W):
    """The run's health for the caller (simulate._healthy) in one pass, 0.5 us against 50 us for
    the same checks in numpy per output sample: a sum that is finite only if every coordinate and
    speed is, the largest squared segment speed, pulley surface speed, penetration, segment
    turning rate and pulley speed."""
    x, y, vx, vy, w, om, pr, seg_p = S.x, S.y, S.vx, S.vy, S.w, S.om, P.r, W.seg_p
    fin = 0.0
    v2m = 0.0
    pm = 0.0
    wm_ = 0.0
    wc = 0.0
    for i in range(n):
        fin += x[i] + y[i] + vx[i] + vy[i] + w[i]
        v2m = max(v2m, vx[i] * vx[i] + vy[i] * vy[i])
        pm = max(pm, seg_p[i])
        wm_ = max(wm_, abs(w[i]))
    sm = 0.0
    for j in range(nk):
        fin += om[j]
        sm = max(sm, abs(om[j]) * pr[j])
        wc = max(wc, abs(om[j]))
    W.probe[0] = fin
    W.probe[1] = v2m
    W.probe[2] = sm
    W.probe[3] = pm
    W.probe[4] = wm_
    W.probe[5] = wc


def energy(B, Ct, P, A, S):
    """Kinetic + potential energy (J): belt, dynamic pulleys, joints, bending, contact, gravity.
    The segments' rotational inertia is the one the integrator uses (times B.iscale). Called from
    Python through the arrays (``_energy``), whose compiled wrapper is cheap (the records' was
    most of 4.5 s of a first run's compile)."""
    return _energy(B.n, B.eax, B.eb, B.hl, B.turn, B.g, B.iscale, B.m, B.inertia, B.kax, B.kb, S.x, S.y, S.phi, S.c,
                   S.s, S.vx, S.vy, S.w, Ct, P.nk, S.cx, S.cy, P.r, P.mode, P.inertia, S.om, P.cl_kind, P.cl_ir, P.cl_k,
                   S.omr, S.dcp, A.na, A.inertia, A.tab_off, A.tab_x, A.tab_y, A.preload, A.rate, A.qmin, A.qmax,
                   A.kstop, S.q, S.qd)


@njit(cache=True, inline="always")
def _energy_of(B, Ct, P, A, S):
    """``energy`` in a kernel: the same stage, for the same argument types (compiled once)."""
    return _energy(B.n, B.eax, B.eb, B.hl, B.turn, B.g, B.iscale, B.m, B.inertia, B.kax, B.kb, S.x, S.y, S.phi, S.c,
                   S.s, S.vx, S.vy, S.w, Ct, P.nk, S.cx, S.cy, P.r, P.mode, P.inertia, S.om, P.cl_kind, P.cl_ir, P.cl_k,
                   S.omr, S.dcp, A.na, A.inertia, A.tab_off, A.tab_x, A.tab_y, A.preload, A.rate, A.qmin, A.qmax,
                   A.kstop, S.q, S.qd)


@njit(cache=True, no_cfunc_wrapper=True)
def _energy(n, eax, eb, hl, turn, g, iscale, m, inertia, kax, kb, x, y, phi, c, s, vx, vy, w, Ct, nk, pcx, pcy, pr,
            pmode, pinertia, om, cl_kind, cl_ir, cl_k, omr, dcp, na, a_inertia, tab_off, tab_x, tab_y, preload, rate,
            qmin, qmax, kstop, q, qd):
    """``energy`` on the arrays it reads: the time loop calls it with these alone (the records
    passed whole flattened to 670 arguments)."""
    E = 0.0
    for i in range(n):
        E += 0.5 * m[i] * (vx[i] * vx[i] + vy[i] * vy[i]) + 0.5 * (inertia[i] * iscale) * w[i] * w[i] \
            + m[i] * g * y[i]
        k = i - 1 if i > 0 else n - 1
        dx = (x[i] - hl * c[i]) - (x[k] + hl * c[k])
        dy = (y[i] - hl * s[i]) - (y[k] + hl * s[k])
        dl = math.sqrt(dx * dx + dy * dy)
        E += kax[i] * dl ** (eax + 1.0) / (eax + 1.0)
        dphi = phi[i] - phi[k]
        if i == 0:
            dphi += turn
        E += kb[i] * abs(dphi) ** (eb + 1.0) / (eb + 1.0)
        for j in range(nk):
            rx = x[i] - pcx[j]
            ry = y[i] - pcy[j]
            p = pr[j] - math.sqrt(rx * rx + ry * ry)
            if p > 0.0:
                E += contact_energy(Ct, i, p)
    for j in range(nk):
        if pmode[j] == 0:
            E += 0.5 * pinertia[j] * om[j] * om[j]
    for j in range(nk):   # accessory rotors behind clutches, decoupler springs
        if cl_kind[j] > 0:
            E += 0.5 * cl_ir[j] * omr[j] * omr[j] + 0.5 * cl_k[j] * dcp[j] * dcp[j]
    for a in range(na):   # arm or slider: kinetic (pulley mass included), spring and stops
        E += 0.5 * a_inertia[a] * qd[a] * qd[a] + _spring_energy(a, q[a], tab_off, tab_x, tab_y, preload, rate, qmin,
                                                                 qmax, kstop)
    return E


# ---- explicit right-hand side and RKF45 -----------------------------------------------------

@njit(cache=True, no_cfunc_wrapper=True)
def rhs(t, yv, dy, B, Ct, P, W, z):
    """Explicit right-hand side of the seed's equations of motion (eqs. 21-22) for RKF45.

    State y = [x(n), y(n), phi(n), th(nk), vx(n), vy(n), w(n), om(nk)]. Contact damping and
    friction at the current velocities (``contact`` with hm = 0). Fills W: joint forces, seg_n,
    seg_t, tq_ext, tq_belt, hubx, huby, pin (per pulley) and diss (dissipation rates).
    """
    n = B.n
    nk = P.nk
    x = yv[0:n]
    y = yv[n:2 * n]
    phi = yv[2 * n:3 * n]
    th = yv[3 * n:3 * n + nk]
    o = 3 * n + nk
    vx = yv[o:o + n]
    vy = yv[o + n:o + 2 * n]
    w = yv[o + 2 * n:o + 3 * n]
    om = yv[o + 3 * n:o + 3 * n + nk].copy()
    for j in range(nk):
        if P.mode[j] == 1:
            om[j] = prescribed_speed(P, j, t)
    e0 = np.zeros(0)
    S = State(x, y, phi, np.cos(phi), np.sin(phi), vx, vy, w, th, om, z, P.cx, P.cy, np.zeros(nk), np.zeros(nk), e0, e0,
              np.zeros(nk), np.zeros(nk), np.zeros(nk), np.zeros(nk))
    pax, pb = _joint_forces_of(B, S, W, 0.0)
    pcd = 0.0
    pfr = 0.0
    for j in range(nk):
        W.tq_belt[j] = 0.0
        W.hubx[j] = 0.0
        W.huby[j] = 0.0
    for i in range(n):
        ax = W.fx[i]
        ay = W.fy[i] - B.m[i] * B.g
        Ntot = 0.0
        Ttot = 0.0
        for j in range(nk):
            rx = x[i] - P.cx[j]
            ry = y[i] - P.cy[j]
            d2 = rx * rx + ry * ry
            if d2 >= P.r[j] * P.r[j]:
                continue
            p, N, T, nx, ny, pc, pf = contact(Ct, i, rx, ry, d2, P.r[j], vx[i], vy[i], om[j], 0.0, 0.0, z)
            if N <= 0.0:
                continue
            pcd += pc
            pfr += pf
            ax += N * nx + T * -ny
            ay += N * ny + T * nx
            Ntot += N
            Ttot += T
            W.tq_belt[j] -= P.r[j] * T
            W.hubx[j] -= N * nx + T * -ny
            W.huby[j] -= N * ny + T * nx
        W.seg_n[i] = Ntot
        W.seg_t[i] = Ttot
        dy[i] = vx[i]
        dy[n + i] = vy[i]
        dy[2 * n + i] = w[i]
        dy[o + i] = ax / B.m[i]
        dy[o + n + i] = ay / B.m[i]
        dy[o + 2 * n + i] = W.mz[i] / (B.inertia[i] * B.iscale)
    W.diss[0] = pax
    W.diss[1] = pb
    W.diss[2] = pcd
    W.diss[3] = pfr
    for j in range(nk):
        dy[3 * n + j] = om[j]
        if P.mode[j] == 1:
            dy[o + 3 * n + j] = 0.0
            W.tq_ext[j] = 0.0
            W.pin[j] = -W.tq_belt[j] * om[j]
        else:
            M = external_torque(P, j, t, th[j], om[j])
            W.tq_ext[j] = M
            W.pin[j] = M * om[j]
            dy[o + 3 * n + j] = (M + W.tq_belt[j]) * P.inv_i[j]


# Runge-Kutta-Fehlberg 4(5) tableau (Fehlberg 1969), the seed's integrator
_C = np.array([0.0, 0.25, 3 / 8, 12 / 13, 1.0, 0.5])
_A = np.array([[0, 0, 0, 0, 0],
               [1 / 4, 0, 0, 0, 0],
               [3 / 32, 9 / 32, 0, 0, 0],
               [1932 / 2197, -7200 / 2197, 7296 / 2197, 0, 0],
               [439 / 216, -8, 3680 / 513, -845 / 4104, 0],
               [-8 / 27, 2, -3544 / 2565, 1859 / 4104, -11 / 40]])
_B4 = np.array([25 / 216, 0, 1408 / 2565, 2197 / 4104, -1 / 5, 0])
_B5 = np.array([16 / 135, 0, 6656 / 12825, 28561 / 56430, -9 / 50, 2 / 55])


@njit(cache=True, no_cfunc_wrapper=True)
def rkf45_chunk(t, t_end, h, yv, rtol, atol, max_steps, B, Ct, P, W, Wst, z):
    """Adaptive RKF45 from t to t_end (advancing with the 4th-order solution, error from the
    embedded 5th). The first stage writes W, the others the scratch Wst; W's accumulators get
    the h-weighted stage-1 outputs (acc_tq_ext, acc_tq_belt, acc_hubx, acc_huby, acc_pin,
    acc_diss). Returns (t, h, accepted steps, rejected steps); t < t_end means max_steps was hit."""
    N = yv.shape[0]
    nk = P.nk
    K = np.zeros((6, N))
    yt = np.zeros(N)
    acc = 0
    rej = 0
    while t < t_end and acc + rej < max_steps:
        if t + h > t_end:
            h = t_end - t
        rhs(t, yv, K[0], B, Ct, P, W, z)
        for st in range(1, 6):
            for q in range(N):
                v = yv[q]
                for r in range(st):
                    v += h * _A[st, r] * K[r, q]
                yt[q] = v
            rhs(t + _C[st] * h, yt, K[st], B, Ct, P, Wst, z)
        err = 0.0
        for q in range(N):
            y4 = yv[q]
            e5 = 0.0
            for r in range(6):
                y4 += h * _B4[r] * K[r, q]
                e5 += h * (_B5[r] - _B4[r]) * K[r, q]
            yt[q] = y4
            sc = atol + rtol * abs(yv[q])
            e = abs(e5) / sc
            if e > err:
                err = e
        if err <= 1.0 or not np.isfinite(err):
            if not np.isfinite(err):
                return t, h, acc, rej
            for q in range(4):
                W.acc_diss[q] += h * W.diss[q]
            for j in range(nk):
                W.acc_tq_ext[j] += h * W.tq_ext[j]
                W.acc_tq_belt[j] += h * W.tq_belt[j]
                W.acc_hubx[j] += h * W.hubx[j]
                W.acc_huby[j] += h * W.huby[j]
                W.acc_pin[j] += h * W.pin[j]
            for q in range(N):
                yv[q] = yt[q]
            t += h
            acc += 1
            fac = 5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)
        else:
            rej += 1
            fac = max(0.1, 0.9 * err ** -0.25)
        h *= fac
        if h < 1e-15:
            return t, h, acc, rej
    return t, h, acc, rej
