"""The rotational model of a belt drive (``simulation.model = "rotational"``): one unknown per
pulley, clutch rotor and tensioner, the spans as axial springs, the wraps with creep and a
friction limit. It reads the same model file and gives the same summary, time series, run-up
tables and plots as the segment model, in milliseconds per simulated second.

Formulation (after Hwang, Perkins & Ulsoy, J. Vib. Acoust. 116 (1994) 8-15, rotational response
and slip prediction of serpentine belt drives; creep as Kong & Parker, J. Appl. Mech. 72 (2005)
25-34; stated in full in docs/belt-drive.md, "The rotational model"):

- Span k (from pulley k to k+1 in belt order) holds an unstretched belt length u_k on its straight
  length L_k(q) (q: the tensioners' travel, exact layouts): strain e_k = L_k / u_k - 1, tension
  T_k = EA e_k + b de_k/dt (b = belt.axial_damping), zero when slack.
- Wrap j holds W_j. The belt arrives in adhesion: it moves with the pulley surface (rho_j omega_j)
  at the strain of the span it comes from, so the flux into the wrap is rho_j omega_j / (1 + e_in).
  With Threlfall's law (no pre-sliding) the wrap's content relaxes to its steady value (creep theory:
  adhesion arc, then a slip arc with T - m v^2 ~ exp(mu phi), the belt sunk into the groove by its
  contact pressure; steady/creep.py) over one passage time r theta / |v|, and the flux out is the
  flux in less the content's change; with the elastic-plastic law the wrap's cells below.
  Belt is conserved: sum u + sum W = L0 at every step.
- With the elastic-plastic friction law (the default) each wrap's belt is held in cells along its arc
  (at most CELL_LENGTH long) that the rim carries: each cell keeps its belt's tension and bristle
  deflection, fresh belt enters with the arriving span's tension and unloaded bristles. Each step the
  wraps' ends meet the span tensions: the cells' nodes, joined by the belt (EA_w, with its sinking)
  and held to the rim by their bristles (mu (T - m v^2) / (r Delta_max) per length; none for a
  bristle at Delta_max pushed on outward: it slides), give way where the spans pull, solved with the
  spans' tensions; the belt they let out moves into the spans. Creep, the slip arc, pre-sliding and
  its hysteresis follow from the cells (the segment model's friction law along a continuum); the
  cells conserve the belt exactly (the shift's outflow from the content it moved, the stretch's and
  the arc's changes booked to the spans).
- A tensioner moving the tangent points rolls belt from a span onto its pulleys (adhesion): the
  stretch of a span per unit travel is then the projection of the pulley centre's motion on the
  span (modes.py), the same gradient as ``check``'s modes.
- Gross slip: where a wrap's tension ratio (T_tight - m v^2) / (T_slack - m v^2) would exceed
  e^(mu theta), belt slides through the whole wrap from the slack to the tight span until the ratio
  is at the limit (Coulomb's law on the wrap, a return map each step): the pulley's torque is capped
  by the friction limit and its speed decouples from the belt's.
- Pulley j: J_j omega_j' = rho_j (T_out - T_in) + its loads; the hub carries the spans' pull less
  the belt's centrifugal force on the wrap; the tensioner arm the hub force on its pulley. Pulleys,
  clutches, speed orders and tensioners advance in the segment model's own stages (_kernels.py).
- The belt's mass: its centrifugal tension in the wraps (above) and, lumped, its inertia: each
  wrap's belt on its pulley and a third of each adjoining span's (the diagonal of a span's
  consistent mass), on the pulley's rotation and on a tensioner's travel.

- A synchronous belt (``[belt.teeth]``): the grooved wraps are quasi-static tooth chains, the belt
  passing one pitch per groove (teeth.py); a grooved pitch curve carries the belt past its tangent
  points by their arc positions and pulls on its effective radii (curves.py). So does a smooth one,
  its wrap's belt stuck to the rim carried past the two tangent points at their own rates.

Not in it: the spans' transverse motion (flap: belt/steady/flap.py), the belt's own axial waves (the
spans are massless springs) and polygon effects (none: it is the continuum).
"""
from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ...core.errors import ModelError, SolverError, Stopped, stop_reason
from ..dynamics import _bodies as BK
from ..dynamics.bodies import arms_record, pulleys_record, running_senses
from ..dynamics.frequencies import add_flap_and_modes
from . import _kernels as RK
from . import curves as CV
from . import teeth as TT
from ..geometry import tensioner as TN
from ...mechanics.layout import Layout, compute_layout
from ..steady.modes import rolled_on
from ..geometry.drive import resolve
from ..geometry.placement import penetration

#: grid of a tensioner's geometry table (travel steps over its stop-to-stop range, plus margins): the
#: cubic tables' error falls as the step^4; fead-runup's held extremes and arm travel at 31 points are
#: within 1e-6 of 121 points' (61: 1e-7), each point a layout (0.3 ms)
TABLE_POINTS = 31
#: the step resolves the fastest mode: h omega_max at most this (symplectic Euler: frequency error
#: (h omega)^2 / 24, 1.5 % at 0.6; stable to 2). An accuracy rule: fead-runup's periodic run-up
#: tables at 0.6 are as close to the step-converged ones as the first-order belt stage's at 0.3
STEP_OMEGA = 0.6
#: Gauss-Seidel passes of the gross-slip return map over the wraps
SLIP_PASSES = 4
#: the wraps' belt (elastic-plastic law) in cells of at most this length (m), at least CELLS_MIN per
#: wrap: against 3 mm cells, fead-runup's drive held at 1875 and 4375 rpm (orders 2 and 4) moves its
#: span tension extremes by at most 2.2 %, its slips by 0.0013 points and the arm's travel range by
#: 0.9 %; 4 mm cost 1.4x the solve of 6 mm, 8 mm moved the extremes by 2 % more
CELL_LENGTH = 6e-3
CELLS_MIN = 4


@dataclass
class RotSystem:
    model: object          # the drawn model
    layout: Layout         # at the tensioners' rest travel
    R: RK.Rot
    P: BK.Pulleys           # belt mass lumped on the inertias
    A: BK.Arms
    rest_travel: np.ndarray
    rest_tension: float
    L0: float              # unstretched belt length (m)
    step: float
    omega_max: float       # bound on the fastest mode (rad/s)
    wraps: list = ()       # a synchronous belt's grooved wraps (teeth.Wrap)
    belt_teeth: object = None
    curves: object = None  # non-circular pulleys (curves.Curves)


def rolling_radii(model, lay: Layout, tension: float) -> np.ndarray:
    """Per pulley: belt speed over pulley speed at rest, the radius slip is read against: the
    contact radius, or with friction.radius = "centre" the belt's centre line's, less the depth of
    the pressure tension / r (placement.penetration)."""
    r = np.abs(lay.rho)
    if model.friction.radius != "centre":
        return r
    return r - penetration(tension / r, model.contact.stiffness_quadratic, model.contact.stiffness_linear)


def _tables(model, rest_lay: Layout, idx, sense, rest_q):
    """Geometry tables per tensioner over its travel (the others at rest): changes from rest of
    span lengths, rolled-on belt, span directions and wraps."""
    ns, nk = len(rest_lay.spans), len(rest_lay.names)
    na = len(idx)
    L_r = np.array([sp.length for sp in rest_lay.spans])
    d_r = np.array([[math.cos(sp.angle), math.sin(sp.angle)] for sp in rest_lay.spans])
    shape = (na, TABLE_POINTS, ns)
    tL, t0, t1, tdx, tdy = (np.zeros(shape) for _ in range(5))
    tw = np.zeros((na, TABLE_POINTS, nk))
    q0, dq = np.zeros(na), np.zeros(na)
    centres_rest = {j: TN.centre(model, j, q, s) for j, q, s in zip(idx, rest_q, sense)}
    for a, (j, s) in enumerate(zip(idx, sense)):
        lo, hi = model.pulleys[j].tensioner.stops
        margin = 0.15 * (hi - lo)
        dq[a] = (hi - lo + 2 * margin) / (TABLE_POINTS - 1)
        i0 = int(round((rest_q[a] - (lo - margin)) / dq[a]))       # rest travel on a grid point
        q0[a] = rest_q[a] - i0 * dq[a]
        last = None
        for i in range(TABLE_POINTS):
            q = q0[a] + i * dq[a]
            c = dict(centres_rest)
            c[j] = TN.centre(model, j, q, s)
            try:
                lay = compute_layout(TN.with_centres(model, c))
            except ModelError:
                lay = None
            if lay is None:       # beyond where the layout exists: held at the last valid one
                if last is None:
                    continue
                tL[a, i], t0[a, i], t1[a, i], tdx[a, i], tdy[a, i], tw[a, i] = last
                continue
            a0, a1 = rolled_on(rest_lay, lay)
            d = np.array([[math.cos(sp.angle), math.sin(sp.angle)] for sp in lay.spans])
            row = (np.array([sp.length for sp in lay.spans]) - L_r, a0, a1, d[:, 0] - d_r[:, 0], d[:, 1] - d_r[:, 1],
                   lay.wrap - rest_lay.wrap)
            tL[a, i], t0[a, i], t1[a, i], tdx[a, i], tdy[a, i], tw[a, i] = row
            if last is None and i > 0:      # fill the invalid start
                for i2 in range(i):
                    tL[a, i2], t0[a, i2], t1[a, i2], tdx[a, i2], tdy[a, i2], tw[a, i2] = row
            last = row
    return q0, dq, tL, t0, t1, tdx, tdy, tw


def build(drive) -> RotSystem:
    """The rotational model's system of ``drive`` (geometry.drive.Drive; a model is resolved first):
    about the continuum's rest state (``drive.rest``)."""
    drive = resolve(drive)
    model, drawn, L0 = drive.model, drive.layout, drive.installed_length
    idx, sense = list(drive.tensioners), list(drive.senses)
    belt = model.belt
    rest_q, T_rest, lay = drive.rest
    curves = CV.tables(model, lay)      # non-circular pulleys (None: all circles)
    if curves is not None:
        T_rest = CV.rest_tension(model, curves, L0)
    if not T_rest > 0:
        raise ModelError("the belt is slack at rest: belt.length too long or no pretension", field="belt")
    q0, dq, tL, t0, t1, tdx, tdy, tw = _tables(model, lay, idx, sense, rest_q) if idx else (
        np.zeros(0), np.ones(0), *(np.zeros((0, 4, len(lay.spans))) for _ in range(5)), np.zeros((0, 4, len(lay.names))))
    wraps, bt = [], None
    if belt.teeth is not None:
        from ..geometry.teeth import belt_teeth

        bt = belt_teeth(model, lay.length)
        wraps = TT.chains(model, lay, L0, bt, T_rest)
    R = RK.Rot(nk=len(lay.names), rho=lay.rho.astype(float), EA=float(belt.axial_stiffness),
               bax=float(belt.axial_damping), m=float(belt.mass_per_length),
               mu=np.full(len(lay.names), float(model.friction.coefficient)),
               c1=float(model.contact.stiffness_quadratic), c2=float(model.contact.stiffness_linear),
               centre=model.friction.radius == "centre",
               # (a synchronous belt's smooth wraps relax to their creep state: the cells hold none of its teeth)
               dmax=float(model.friction.displacement_limit) if model.friction.law == "elastic-plastic" and not wraps
               else 0.0,
               L=np.array([sp.length for sp in lay.spans]),
               dx=np.array([math.cos(sp.angle) for sp in lay.spans]), dy=np.array([math.sin(sp.angle) for sp in lay.spans]),
               wrap=lay.wrap.astype(float), q0=q0, dq=dq, tL=tL, t0=t0, t1=t1, tdx=tdx, tdy=tdy, tw=tw,
               ncell=np.array([max(CELLS_MIN, math.ceil(abs(r) * w / CELL_LENGTH)) for r, w in zip(lay.rho, lay.wrap)],
                              dtype=np.int64),
               p0=np.array([0.0 if model.friction.radius == "centre" else
                            float(penetration(T_rest / abs(r), model.contact.stiffness_quadratic, model.contact.stiffness_linear))
                            for r in lay.rho]),
               **TT.kernel_fields(len(lay.names), wraps, float(belt.axial_stiffness)), trest=float(T_rest),
               **CV.kernel_fields(curves, len(lay.names), len(lay.spans)))
    P = pulleys_record(model.pulleys, running_senses(model, drawn))
    A = arms_record(model, sense)
    # the belt's mass, lumped: each wrap's belt and a third of each adjoining span's
    nk = R.nk
    m = belt.mass_per_length
    carried = np.array([abs(R.rho[j]) * R.wrap[j] + (R.L[j] + R.L[(j - 1) % nk]) / 3 for j in range(nk)]) * m
    inertia = P.inertia + carried * R.rho ** 2
    P = P._replace(cx=lay.centers[:, 0].copy(), cy=lay.centers[:, 1].copy(), inertia=inertia, inv_i=1.0 / inertia)
    if A.na:
        par = A.par.copy()
        add = np.zeros(A.na)
        for a in range(A.na):
            _, _, jx, jy = BK.arm_centre(A, a, float(rest_q[a]))
            add[a] = carried[A.pulley[a]] * (jx * jx + jy * jy)
        par[:, BK.ARM_IN] += add
        A = A._replace(par=par, inertia=A.inertia + add)
    w_max = _omega_bound(R, P, A, rest_q, T_rest)
    h = STEP_OMEGA / w_max
    return RotSystem(model, lay, R, P, A, rest_q, T_rest, L0, h, w_max, wraps, bt, curves)


def _omega_bound(R, P, A, rest_q, T) -> float:
    """An upper bound of the fastest mode (rad/s): for each DOF, twice its diagonal stiffness over
    its inertia (Gershgorin: the span springs couple neighbours with off-diagonal terms no larger
    than the diagonal ones). The arms' stops are left out: their spring is implicit in the arm
    stage (``_step_arms``), stable at any step."""
    nk = R.nk
    kspan = R.EA / R.L
    w2 = 0.0
    for j in range(nk):
        kr = (kspan[j] + kspan[(j - 1) % nk]) * R.rho[j] ** 2
        if P.mode[j] == 0:
            w2 = max(w2, 2 * kr / P.inertia[j])
        if P.cl_kind[j] == 2:     # the decoupler's spring between pulley and rotor
            ired = P.inertia[j] * P.cl_ir[j] / (P.inertia[j] + P.cl_ir[j])
            w2 = max(w2, P.cl_k[j] / ired)
    for a in range(A.na):
        j = A.pulley[a]
        _, _, jx, jy = BK.arm_centre(A, a, float(rest_q[a]))
        g2 = jx * jx + jy * jy
        ka = (kspan[j] + kspan[(j - 1) % nk]) * g2 * 2 + A.par[a, BK.ARM_RATE]
        w2 = max(w2, 2 * ka / A.par[a, BK.ARM_IN])
    return math.sqrt(w2)


# --- the run -----------------------------------------------------------------------------------

class _Rest:
    """The tensioners at rest, as the summary reports them (tensioner.Equilibrium's fields)."""

    def __init__(self, sysm: RotSystem):
        A, q = sysm.A, sysm.rest_travel
        self.travel = q
        self.tension = sysm.rest_tension
        self.angle = np.array([A.psi0[a] + A.sgn[a] * q[a] if A.kind[a] == 0 else np.nan for a in range(A.na)])
        self.spring = np.array([TN.spring_load(sysm.model.pulleys[A.pulley[a]].tensioner, q[a]) for a in range(A.na)])


class _Init:
    """What the shared summary and diagnostics read of an initial state: the rest tension and, for
    the steadiness test's speed floor, a length the belt must pass in a window (1 mm)."""

    def __init__(self, tension):
        self.tension = tension
        self.seg_length = 1e-3
        self.residual = 0.0


class _View:
    """The rotational system seen through the segment model's system interface (dynamics/outputs.run_summary,
    diagnose): layout, pulleys, arms, rest state; the continuum rolls on ``rolling_radii``."""

    def __init__(self, sysm: RotSystem):
        self.model, self.layout, self.pulleys, self.arms = sysm.model, sysm.layout, sysm.P, sysm.A
        self.rest = _Rest(sysm) if sysm.A.na else None
        self.init = _Init(sysm.rest_tension)
        self.rolling_radius = rolling_radii(sysm.model, sysm.layout, sysm.rest_tension)
        self.n = 0


def new_states(sysm: RotSystem):
    """Kernel states at rest: pulleys still (a prescribed one at its t = 0 speed), tensioners at
    their rest travel, every span and wrap holding the belt of the rest tension."""
    P, R, A = sysm.P, sysm.R, sysm.A
    nk, z = R.nk, np.zeros
    om = np.array([BK.prescribed_speed(P, j, 0.0) if P.mode[j] == 1 else 0.0 for j in range(nk)])
    e = z(0)
    S = BK.State(x=e, y=e, phi=e, c=e, s=e, vx=e, vy=e, w=e, th=z(nk), om=om, z=e, cx=P.cx.copy(), cy=P.cy.copy(),
                cvx=z(nk), cvy=z(nk), q=sysm.rest_travel.astype(float).copy(), qd=z(A.na), thm=z(nk), thr=z(nk),
                omr=z(nk), dcp=z(nk))
    W = BK.Work(fx=e, fy=e, mz=e, jfk=e, jdx=e, jdy=e, jmk=e, jmi=e, seg_n=e, seg_t=e, seg_p=e,
               tq_ext=z(nk), tq_belt=z(nk), hubx=z(nk), huby=z(nk), pin=z(nk), diss=z(4),
               acc_tq_ext=z(nk), acc_tq_belt=z(nk), acc_hubx=z(nk), acc_huby=z(nk), acc_pin=z(nk),
               acc_span=z((0, 2)), acc_track=z((0, 3)), acc_diss=z(6), energy=z(1), probe=z(6),
               span_geo=z((0, 4)), span_joint=np.zeros(0, np.int64), track=np.zeros(0, np.int64),
               lin_d=z((0, 9)), lin_o=z((0, 9)), lin_e=z((0, 9)), lin_dinv=z((0, 9)), lin_y=z((0, 9)),
               lin_x=z((0, 9)), lin_r=z((0, 3)), lin_sig=e, lin_gam=e, lin_fk=e, lin_fa=e, lin_far=e, lin_fnx=e, lin_fny=e,
               lin_geo=e, lin_u=z((0, 0, 3)), lin_zslot=np.zeros(0, np.int64), lin_zc=z((0, 0, 3)), lin_g=z((nk, nk + 1)),
               lin_stat=z(4), cand_j=np.zeros(0, np.int64), cand_skip=np.zeros(0, np.int64), lin_st=e,
               lin_cnt=np.zeros(4, np.int64), pul_dw=z(nk), tooth_q=e, tooth_qs=e, tooth_j=np.zeros(0, np.int64),
               tooth_g=np.zeros(0, np.int64), tooth_hold=e, tooth_stat=z(8))
    T = sysm.rest_tension
    EA = R.EA
    c1, c2 = R.c1, R.c2
    nc = int(R.ncell.max())
    # the cells' content per unit arc summed (_kernels._content; the centrifugal tension 0 at rest)
    wsum = np.array([R.ncell[j] * RK._content(T, 0.0, abs(R.rho[j]), R.p0[j], EA, c1, c2) for j in range(nk)])
    if R.dmax > 0.0:        # the wraps' belt is their cells'
        Wc = wsum * np.abs(R.rho) * R.wrap / R.ncell
    else:
        Wc = np.array([RK.wrap_content(abs(R.rho[j]), R.wrap[j], T, T, 0.0, R.mu[j], EA, c1, c2) for j in range(nk)])
    for w in sysm.wraps:        # the grooved wraps: the belt on the pitch line at the rest tension
        Wc[w.pulley] = w.radius * R.wrap[w.pulley] / (1 + T / EA)
    span0 = R.L
    if sysm.curves is not None:     # the path on the curves at their rest angles
        span0 = sysm.curves.spans0
        for w in sysm.wraps:
            Wc[w.pulley] = sysm.curves.arcs0[w.pulley] / (1 + T / EA)
        grooved = {w.pulley for w in sysm.wraps}
        for j in sysm.curves.pulleys:       # a smooth curve's belt as a circle's, on its arc
            if j in grooved:
                continue
            arc, wrap = sysm.curves.arcs0[j], sysm.curves.base.wrap[j]
            wsum[j] = R.ncell[j] * RK._content(T, 0.0, arc / wrap, R.p0[j], EA, c1, c2)
            Wc[j] = (wsum[j] * arc / R.ncell[j] if R.dmax > 0.0 else
                     RK.wrap_content(arc / wrap, wrap, T, T, 0.0, R.mu[j], EA, c1, c2))
    RS = RK.RotState(u=span0 / (1 + T / EA), W=Wc, ud=z(nk), vs=z(nk), t0=z(nk), t1=z(nk), Tp=np.full(nk, T), ed=z(nk),
                     eb=z(nk), zc=z((nk, nc)), Tc=np.full((nk, nc), T), dz=z((nk, nc)), wsum=wsum,
                     cw0=np.full(nk, T), cw1=np.full(nk, T))
    RW = RK.RotWork(L=z(nk), Ld=z(nk), t0=z(nk), t1=z(nk), dx=z(nk), dy=z(nk), wrap=z(nk), T=z(nk), Tm=z(nk), wm=z(nk), a=z(nk), b=z(nk),
                    tq=z(nk), hubx=z(nk), huby=z(nk), slip=z(nk), acc_T=z(nk), acc_v=z(nk), acc_slip=z(nk),
                    acc_gross=z(nk), acc_diss=z(6), bm=z((nk, nk)), bv=z(nk), ex=z(nk),
                    Xc=z((nk, nc)), Yc=z((nk, nc)), Kc=z((nk, nc)), Fc=z((nk, nc)), cp=z(nc), ca=z(nk), cb=z(nk), cc=z(nk),
                    cd=z(nk), eb0=z(nk),
                    Tw0=z(nk), Tw1=z(nk), ew=z(nk), off=z(nk), m0=z(nk), m1=z(nk), rin=np.abs(R.rho), rout=np.abs(R.rho),
                    thb=z(nk), aw=np.abs(R.rho) * R.wrap, rr=np.abs(R.rho))
    return S, W, RS, RW


def planned(model, sysm) -> tuple[int, int]:
    """(samples, steps per sample) of a run of ``model`` on its system ``sysm`` (``build``)."""
    sim, out = model.simulation, model.output
    nsamples = max(1, int(round(sim.duration / out.interval)))
    return nsamples, max(1, int(math.ceil(sim.duration / nsamples / (sim.step or sysm.step))))


def run(drive, progress=None):
    """Integrate ``drive`` (geometry.drive.Drive, or a model) with the rotational model."""
    from ...core.limits import steps_problem

    drive = resolve(drive)
    model = drive.model
    sysm = build(drive)
    sim = model.simulation
    nsamples, steps = planned(model, sysm)
    interval = sim.duration / nsamples
    h = interval / steps
    problem = steps_problem(steps * nsamples, "simulation.duration", "a shorter duration")
    if problem:
        raise ModelError(problem, field="simulation.duration")
    S, W, RS, RW = new_states(sysm)
    nk, na = sysm.R.nk, sysm.A.na
    z = np.zeros
    o = dict(t=z(nsamples), th=z((nsamples, nk)), om=z((nsamples, nk)), tq=z((nsamples, nk)), tb=z((nsamples, nk)),
             hx=z((nsamples, nk)), hy=z((nsamples, nk)), pin=z((nsamples, nk)), T=z((nsamples, nk)), v=z((nsamples, nk)),
             slip=z((nsamples, nk)), gross=z((nsamples, nk)), q=z((nsamples, na)), qd=z((nsamples, na)),
             omr=z((nsamples, nk)), E=z(nsamples), work=z(nsamples), diss=z((nsamples, 6)))
    E0 = RK.energy(sysm.R, sysm.P, sysm.A, S, RS, RW)
    wall0 = _time.perf_counter()
    t, k, failure = 0.0, 0, ""
    chunk = max(1, nsamples // 50)
    try:
        while k < nsamples:
            k1 = min(nsamples, k + chunk)
            t = RK.run_samples(k, k1, steps, t, h, sysm.R, sysm.P, sysm.A, S, W, RS, RW, SLIP_PASSES, True, *o.values())
            if not (np.all(np.isfinite(o["om"][k1 - 1])) and np.all(np.isfinite(o["T"][k1 - 1]))):
                bad = int(np.argmax(~np.isfinite(o["om"][k:k1]).any(axis=1) | ~np.isfinite(o["T"][k:k1]).any(axis=1)))
                k += bad
                failure = f"diverged at t = {o['t'][k]:.6g} s (a state is not finite)"
                break
            k = k1
            if progress is not None:
                progress(k / nsamples, f"t = {t:.3f} s")
    except (Stopped, KeyboardInterrupt) as exc:
        failure = f"stopped: {stop_reason(exc)}"
    except ZeroDivisionError:      # a state ran away inside a chunk: keep the whole chunks before it
        failure = f"diverged after t = {o['t'][k - 1] if k else 0.0:.6g} s (a division by zero in the step: a state ran away)"
    wall = _time.perf_counter() - wall0
    o["E"] -= E0
    o["t"][:k] = (np.arange(k) + 1) * interval      # exact sample times
    result = _assemble(model, sysm, o, k, steps * k, h, wall, failure)
    add_flap_and_modes(model, result)       # the estimate reads them (_absorbs); the verdict too
    extremes_estimate(result, TIMING_SHARE if sysm.wraps else TIME_SHARE, teeth=bool(sysm.wraps))
    if failure:
        raise SolverError(failure + f" (results kept up to t = {o['t'][k - 1] if k else 0.0:.6g} s)", partial=result)
    return result


def _assemble(model, sysm: RotSystem, o, ns, nsteps, h, wall, failure, runup_model=None, window=None):
    import xarray as xr

    from ...core.model import dumps
    from ...core.results import Result, unit_map, variable
    from ...core.window import in_window, steady_window
    from ..dynamics.outputs import ROTATIONAL_UNITS, UNITS, clutch_variables, friction_law, run_summary, tensioner_variables

    lay = sysm.layout
    names, spans = list(lay.names), [sp.name for sp in lay.spans]
    hub = np.hypot(o["hx"][:ns], o["hy"][:ns])
    E, Wk, D = o["E"][:ns], o["work"][:ns], o["diss"][:ns]
    ds = xr.Dataset(
        {
            "angle": variable(o["th"][:ns], ("time", "pulley"), "rad", "pulley angle (counter-clockwise positive)"),
            "speed": variable(o["om"][:ns], ("time", "pulley"), "rad/s", "pulley angular speed (counter-clockwise positive)"),
            "torque_applied": variable(o["tq"][:ns], ("time", "pulley"), "N m", "applied torque, interval mean"),
            "torque_belt": variable(o["tb"][:ns], ("time", "pulley"), "N m", "torque of the belt on the pulley, interval mean"),
            "hub_force_x": variable(o["hx"][:ns], ("time", "pulley"), "N", "belt force on the pulley, x, interval mean"),
            "hub_force_y": variable(o["hy"][:ns], ("time", "pulley"), "N", "belt force on the pulley, y, interval mean"),
            "hub_load": variable(hub, ("time", "pulley"), "N", "hub load magnitude"),
            "power_in": variable(o["pin"][:ns], ("time", "pulley"), "W", "power into the belt system through the pulley"),
            "span_tension": variable(o["T"][:ns], ("time", "span"), "N", "span tension, interval mean"),
            "span_speed": variable(o["v"][:ns], ("time", "span"), "m/s", "belt speed along the span (belt order positive)"),
            "wrap_sliding_speed": variable(o["slip"][:ns], ("time", "pulley"), "m/s",
                                           "belt sliding through the whole wrap (gross slip), belt order positive"),
            "gross_slip_share": variable(o["gross"][:ns], ("time", "pulley"), "1",
                                         "share of the interval the wrap slid as a whole (tension ratio at e^(mu theta))"),
            "energy_change": variable(E, ("time",), "J", "mechanical energy minus its initial value"),
            "work_in": variable(Wk, ("time",), "J", "cumulative work done on the system by the pulleys"),
            "dissipated": variable(D, ("time", "mechanism"), "J", "cumulative dissipated energy"),
            "energy_residual": variable(Wk - D.sum(axis=1) - E, ("time",), "J", "work in - dissipated - energy change (integration error)"),
            "pulley_x": variable(lay.centers[:, 0].copy(), ("pulley",), "m", "pulley centre x (a tensioner's: at rest)"),
            "pulley_y": variable(lay.centers[:, 1].copy(), ("pulley",), "m", "pulley centre y (a tensioner's: at rest)"),
            "pulley_radius": variable([p.radius for p in model.pulleys], ("pulley",), "m", "contact radius"),
            "pulley_rolling_radius": variable(rolling_radii(model, lay, sysm.rest_tension), ("pulley",), "m",
                                              "belt speed over pulley speed at rest (friction.radius)"),
        },
        coords={"time": o["t"][:ns], "pulley": names, "span": spans,
                "mechanism": ["axial_damping", "bending_damping", "contact_damping", "friction", "tensioner", "clutch"]},
        attrs={"model_toml": dumps(model), "title": model.name or "belt drive", "belt_model": "rotational"},
    )
    view = _View(sysm)
    rec = SimpleNamespace(q=o["q"], qd=o["qd"], omr=o["omr"], tq_ext=o["tq"])     # the recorder fields they read
    tensioner_variables(ds, model, view, rec, ns)
    clutch_variables(ds, model, view, rec, ns, float(ds["time"].values[0]) if ns else 1.0)
    ds["time"].attrs["units"] = "s"
    t = ds["time"].values
    t_end = float(t[-1]) if ns else 0.0
    window = window or steady_window(model.output.steady_window, model.simulation.duration)
    sel = in_window(t, window)
    if not np.any(sel):
        window = steady_window(None, t_end)
        sel = in_window(t, window)
    solver = {"method": "rotational", "steps": int(nsteps), "rejected_steps": 0, "rhs_evaluations": int(nsteps),
              "last_step": float(h), "wall_time": float(wall), "simulated_time": t_end,
              "status": "failed" if failure else "success", "step": float(h),
              "stability_limit": float(2 / sysm.omega_max),
              "real_time_factor": float(t_end / wall) if wall > 0 else float("nan")}
    disc = {"model": "rotational", "step": float(h), "fastest_mode_bound_hz": sysm.omega_max / (2 * math.pi),
            # symplectic Euler's frequency error (h omega)^2 / 24 at the bound of the fastest mode
            "step_frequency_error": float((h * sysm.omega_max) ** 2 / 24)}
    summary = run_summary(model, view, ds, solver, sel, window, disc)
    summary["belt"] = {"pretension": float(sysm.rest_tension), "path_length": float(lay.length),
                       "unstretched_length": float(sysm.L0), "model": "rotational", **friction_law(model)}
    gross = ds["gross_slip_share"].values[sel] if np.any(sel) else np.zeros((0, len(names)))
    for j, nm in enumerate(names):
        p = summary["pulleys"][nm]
        p["sliding_share"] = float(gross[:, j].mean()) if len(gross) else float("nan")
    if sysm.wraps:
        ds = TT.add_teeth(ds, summary, model, sysm, sel)
    ds.attrs["steady_window"] = [float(window[0]), float(window[1])]
    ds.attrs["animation"] = 0
    if ns:
        from ..dynamics.runup import add_runup

        summary.update(add_runup(ds, runup_model or model, model.output.runup_bin, up_only=runup_model is not None))
    result = Result("belt-drive", ds, summary, success=not failure, message=failure)
    if ns:
        _checks(result, model, view, sel)
    result.units = unit_map(result.summary, {**UNITS, **ROTATIONAL_UNITS})
    return result


#: ... for a synchronous belt (teeth.py's chains): against the segment model at two segments per tooth on
#: examples/timing-cam-drive.toml held at 1500-4000 rpm (benchmarks/bench_timing_rotational.py), its
#: extremes sat within 0.05-0.8 of the rotational half band on most spans, 1.9-2.1 on the short crank-cam
#: span at 1500-2000 rpm and 2.54 on CAM1-CAM2 at 3000 rpm; with the tensioner held fixed (no damper) at
#: its first mode (3000 rpm) the chains, without the teeth's play and the lands' friction, ring to slack
#: spans where the segment model's stay above 97 N (1.3-1.7 of the band): with a margin
TIMING_SHARE = 3.0

#: a wrap that slides as a whole for more than this share of the window is in gross slip
GROSS_SHARE = 0.02

#: How far the rotational model's span tension extremes may sit from the segment model's, as a share
#: of the tension's half band (max - min) / 2 in the rotational run: the largest seen against the segment
#: model at twice its "auto" segments (benchmarks/bench_rotational_agreement.py) were 0.50 on
#: examples/fead-runup.toml's drive held at 1000-5000 rpm, 0.55 over every bin of its run-up, 0.80 for
#: its periodic run-up (against the segment model's ramp, whose bins cross the modes in passing; above
#: 3625 rpm, where wraps slide grossly, the sweep's continuation and a start from rest can find different
#: responses; 1.36 before the periodic solution carried the sweep's inertia torques), and 0.60 on the
#: three-pulley drive of tests/belt/test_rotational.py (2000 rpm, 2nd order on the alternator's mode):
#: these, with the same margin (1.36). Means (within 1-2 %) are not affected.
TIME_SHARE = 0.75
PERIODIC_SHARE = 1.1
#: ... on a span at a tensioner's pulley whose flap frequency (its first or second, at the run's speed)
#: lies within FLAP_NEAR of one of the drive's modes: the arm's swing moves the span across, and its flap
#: modes, which the rotational model lacks, take that mode's energy as a tuned absorber would: the
#: segment model's one peak is two, and between and beside them the bands differ by up to 2.8x. The
#: three-pulley drive of tests/belt/test_rotational.py swept with its 6th order across its arm's mode
#: (200 Hz; its arm spans' 2nd flap modes at 204-207 Hz, 3 % off; 1800-2300 rpm, 50 rpm apart) needed
#: 1.13 (2150 rpm: half bands 28.5 against 55.8 N); examples/fead-ag0868.toml's first duty row (a flap
#: frequency 18 % off a mode) 0.44, within the other spans' 0.75. The segment model's spans damp their
#: flap little (benchmarks/bench_flap_decay.py: damping ratios below 0.005), so the split stays sharp.
ARM_SPAN_SHARE = 1.5
FLAP_NEAR = 0.1
#: ... and there the arm's travel range may be this factor off (either way): the same sweep read 3.19
#: against 0.83 mrad at 2050 rpm, 1.79 against 3.15 at 2150 (fead-runup held: within 13 %)
ARM_TRAVEL_FACTOR = 4.0
#: How far its slips (against the crank) and the arm's travel range may sit from the segment model's,
#: the largest seen on fead-runup's drive (benchmarks/bench_rotational_agreement.py) with a margin:
#: slips 0.037 points held and 0.033 in the run-up's bins where no wrap slides as a whole, 0.105 where
#: one does (4375 rpm held: the rotational model's wraps slide, the segment model's do not; 0.146 on the
#: three-pulley drive of tests/belt/test_rotational.py at 2000 rpm); the arm's travel range 12.6 % held,
#: 24.2 % over the run-up's bins (periodic 22.8 %), 24 % on the three-pulley drive
SLIP_ABSOLUTE = 4e-4
SLIP_ABSOLUTE_GROSS = 2e-3
ARM_TRAVEL_RELATIVE = 0.3
#: an estimate above this share of the extreme itself makes the run a warning
EXTREMES_LIMIT = 0.05


def _absorbs(summary, span, where) -> bool:
    """Whether ``span`` (at ``where``: "<rpm> rpm" or the steady window) may take a drive mode's energy
    by its flap: it ends at a tensioner's pulley, and its first or second flap frequency at that speed
    lies within FLAP_NEAR of one of the drive's modes (summary.flap, summary.modes)."""
    arms = set(summary.get("tensioners", {}))
    if not any(end in arms for end in span.split("-")):       # span names: "<from>-<to>"
        return False
    flap, modes = summary.get("flap", {}), summary.get("modes", {}).get("frequencies_hz", [])
    f = flap.get("spans", {}).get(span)
    if not f or not modes:
        return True            # nothing to tell: the cautious share
    speeds = flap.get("speed_rpm", [])
    k = 0
    if where.endswith(" rpm") and len(speeds) > 1:
        rpm = float(where.split()[0])
        k = int(np.argmin([abs(abs(x) - rpm) for x in speeds]))
    return any(abs(f[key][k] - fm) <= FLAP_NEAR * fm for key in ("f1", "f2") if key in f for fm in modes)


def extremes_estimate(result, share, teeth=False):
    """summary.discretisation.estimate for the rotational model: each span tension extreme's
    uncertainty against the segment model, share x its half band (ARM_SPAN_SHARE at least where a
    span's flap may take a drive mode's energy: _absorbs), and the ``model-accuracy`` diagnostic
    where the largest is above EXTREMES_LIMIT of the extreme (a bin of a run-up, or the steady
    window)."""
    s = result.summary
    ru = s.get("runup")
    if ru and ru.get("span_tension_min"):
        rows = [(sp, f"{rpm:.0f} rpm", lo, hi) for sp in ru["span_tension_min"]
                for rpm, lo, hi in zip(ru["speed_rpm"], ru["span_tension_min"][sp], ru["span_tension_max"][sp])]
    else:
        rows = [(sp, "the steady window", v["tension_min"], v["tension_max"]) for sp, v in s.get("spans", {}).items()
                if "tension_min" in v]
    worst = None
    absorbing = set()
    for sp, where, lo, hi in rows:
        if not (np.isfinite(lo) and np.isfinite(hi)) or lo <= 0.0:
            continue
        takes = _absorbs(s, sp, where)
        if takes:
            absorbing.add(sp)
        u = (max(share, ARM_SPAN_SHARE) if takes else share) * 0.5 * (hi - lo)
        if worst is None or u / lo > worst[0]:
            worst = (u / lo, sp, where, lo, u)
    est = {"method": f"{share:g} x each span tension's half band (max - min) / 2, {max(share, ARM_SPAN_SHARE):g} on a "
                     f"span at a tensioner's pulley whose flap frequency lies within {100 * FLAP_NEAR:g} % of a mode of the "
                     "drive: at least the largest deviation of the rotational model's extremes "
                     "from the segment model's (twice its \"auto\" segments) measured on examples/fead-runup.toml's drive "
                     "(benchmarks/bench_rotational_agreement.py) and a three-pulley drive swept across its arm's mode "
                     "(tests/belt/test_rotational.py); the means are within 2 %", "share_of_half_band": share,
           "share_of_half_band_at_a_tensioner": max(share, ARM_SPAN_SHARE)}
    if worst is not None:
        est.update(tension_extreme_relative_largest=worst[0], where=f"{worst[1]} at {worst[2]}")
    if absorbing:
        est.update(arm_travel_range_factor=ARM_TRAVEL_FACTOR, spans_taking_a_mode=sorted(absorbing))
    gross = any(d.code == "gross-slip" for d in getattr(result, "diagnostics", []))
    est["slip_absolute"] = SLIP_ABSOLUTE_GROSS if gross else SLIP_ABSOLUTE
    if s.get("tensioners"):
        est["arm_travel_range_relative"] = ARM_TRAVEL_RELATIVE
    s.setdefault("discretisation", {})["estimate"] = est
    result.units.update({"discretisation.estimate.share_of_half_band": "1", "discretisation.estimate.where": "",
                         "discretisation.estimate.share_of_half_band_at_a_tensioner": "1",
                         "discretisation.estimate.arm_travel_range_factor": "1",
                         "discretisation.estimate.spans_taking_a_mode": "",
                         "discretisation.estimate.slip_absolute": "1",
                         "discretisation.estimate.arm_travel_range_relative": "1",
                         "discretisation.estimate.tension_extreme_relative_largest": "1"})
    if worst is not None and worst[0] > EXTREMES_LIMIT:
        rel, sp, where, lo, u = worst
        result.diagnose("model-accuracy", f"rotational model: span {sp}'s minimum {lo:.0f} N at {where} may be off by "
                        f"+-{u:.0f} N ({100 * rel:.0f} %) against the segment model (it lacks the spans' flap, which "
                        "takes energy from the drive's modes, and the belt's axial waves"
                        + ("; its tooth chains lack the teeth's play and the lands' friction, which damp a timing "
                           "drive's resonance" if teeth else "") + ")"
                        + (f"; its arm travel range may be {ARM_TRAVEL_FACTOR:g} times off where {', '.join(sorted(absorbing))} "
                           "may take a mode by its flap" if absorbing else "")
                        + f"; its slips may be off by {100 * est['slip_absolute']:.2g} points"
                        + (f", its arm travel range by {100 * ARM_TRAVEL_RELATIVE:.0f} %"
                           if "arm_travel_range_relative" in est and not absorbing else "")
                        + "; confirm the bands with simulation.model = \"segments\"",
                        "discretisation.estimate.tension_extreme_relative_largest", rel, EXTREMES_LIMIT, "1")


def _checks(result, model, view, sel):
    """The rotational model's diagnostics: gross slip from the wraps' return map, and the segment
    model's window, energy, slip-margin, run-up-slip and load checks."""
    from ..dynamics import checks as D
    from ..dynamics.loadcheck import check_loads

    if not np.any(sel) or result.ds.sizes.get("time", 0) < 3:
        return
    ru = result.summary.get("runup")
    if ru and "gross_slip_share" in ru:
        # a run-up bin by bin: its steady window is one part of the sweep (a periodic run-up's, its
        # last speed: the crank's sliding at 3625-4625 rpm went unsaid)
        rpm = np.array(ru["speed_rpm"])
        for nm, shares in ru["gross_slip_share"].items():
            g = np.array(shares)
            bad = g > GROSS_SHARE
            if np.any(bad) and D.excited(model):
                result.diagnose("gross-slip", f"pulley {nm}'s belt slides over its whole wrap up to {100 * g.max():.0f} % "
                                f"of a bin at {rpm[bad].min():.0f}-{rpm[bad].max():.0f} rpm in the run-up (tension ratio at "
                                "e^(mu theta)); more pretension or less load",
                                f"runup.gross_slip_share.{nm}", float(g.max()), GROSS_SHARE, "1")
    else:
        for nm, p in result.summary["pulleys"].items():
            share = p.get("sliding_share", 0.0)
            if share > GROSS_SHARE and D.excited(model):
                result.diagnose("gross-slip", f"pulley {nm}'s belt slides over its whole wrap {100 * share:.0f} % of the "
                                "steady window (tension ratio at e^(mu theta)); more pretension or less load",
                                f"pulleys.{nm}.sliding_share", share, GROSS_SHARE, "1")
    D.steady_drift(result, model, view, sel)
    D.energy_balance(result, model, sel)
    D.slip_margin(result, model, view, sel)
    D.runup_slip(result)
    check_loads(result, model, sel)
