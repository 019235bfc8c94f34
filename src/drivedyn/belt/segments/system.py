"""Model -> plain arrays for the kernels (the only place that knows both worlds).

The kernels (numba) are imported where a system is built or settled, not with this module: check
places the chain and states its step (``placed``) without them."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...core.errors import ModelError
from .records import LAWS, Belt, Contact
from ..geometry.placement import InitialState, check_length, initial_state
from ...mechanics.layout import Layout, compute_layout
from ..geometry import tensioner
from ..model import integrator
from ..geometry.drive import resolve

if TYPE_CHECKING:
    from ..dynamics import _bodies as BK


@dataclass
class BeltSystem:
    model: object
    layout: Layout
    init: InitialState
    belt: Belt
    contact: Contact
    pulleys: BK.Pulleys
    arms: BK.Arms       # tensioners (na = 0 without)
    span_mid: np.ndarray
    span_geo: np.ndarray  # per span: midpoint x, y and unit direction x, y (belt order)
    track: np.ndarray
    step: float        # time step (s) of the semi-implicit scheme
    step_limit: float  # stability estimate 2 / omega_max (s)
    rest: object = None  # tensioner.Equilibrium of belt and tensioners at rest (None without)

    @property
    def n(self):
        return self.belt.n

    @property
    def rolling_radius(self) -> np.ndarray:
        """Per pulley: belt speed over pulley speed of the discrete chain rolling with no load (its
        own kinematics). A stuck segment rides on the circle r_c = r - p0 it is pressed to and moves
        at the pulley's speed at the friction's radius a (``friction.radius``: a = r, "contact";
        a = r_c, "centre", turning with the pulley); one pitch l + g passes per angle
        2 asin(l / 2 R_e) + 2 asin(g / 2 R_e), its chord ends on R_e = sqrt(r_c^2 + l^2 / 4)
        (geometry/placement.py): a (1 + l^2 / (12 r_c^2)) to first order. Speed ratios against it are free of
        the polygon effect, which is no slip."""
        init = self.init
        l, g = init.seg_length, init.gap
        r = np.array([p.radius for p in self.model.pulleys])
        rc = r - init.penetration
        Re = np.sqrt(rc ** 2 + l * l / 4)
        pitch_angle = 2 * np.arcsin(np.minimum(l / (2 * Re), 1.0)) + 2 * np.arcsin(np.minimum(g / (2 * Re), 1.0))
        arm = rc if self.model.friction.radius == "centre" else r
        return (l + g) * arm / (rc * pitch_angle)

    @property
    def groups(self):
        """(Belt, Contact, Pulleys, Arms): the constant arguments of every kernel, in kernel order."""
        return self.belt, self.contact, self.pulleys, self.arms


#: evaluations of the chain per rkf45 step (Fehlberg's 4(5) pair): what its step costs against the
#: single-evaluation schemes' steps the steps limit counts
RKF45_STAGES = 6


def rkf45_step(model, tension: float) -> float | None:
    """rkf45's stable step (s) under the friction law, or None (no friction or no tension).

    Explicit: a sticking segment's friction force mu N v / velocity_threshold is a damper of rate
    mu N / dv on its mass m = rho l, with N = T l / r on a pulley of radius r; explicit Runge-Kutta
    schemes are stable for h < ~2.8 m / (mu N / dv) = 2.8 rho r dv / (mu T) (the real-axis stability
    limit of RK4/5, Hairer & Wanner, Solving ODEs II, IV.2). On examples/belt-5pk.toml it is about
    1.3e-10 s (the run's own step control went to 7e-11 s)."""
    mu = max([model.friction.coefficient] + [z.coefficient for z in model.friction.zones])
    r = min(p.radius for p in model.pulleys)
    if not (mu > 0 and tension > 0):
        return None
    return 2.8 * model.belt.mass_per_length * r * model.friction.velocity_threshold / (mu * tension)


#: steps rkf45 takes within one output interval before it gives up (``build`` refuses a model whose
#: friction law needs more)
MAX_STEPS_PER_SAMPLE = 2_000_000


#: the settled belt's tension may differ from the one asked for by this share before the chain is
#: placed again with a corrected tension
SETTLE_TOL = 1e-3


def build(drive, settle: bool = True, before_settle=None) -> BeltSystem:
    """The kernels' arrays for ``drive`` (geometry.drive.Drive; a model is resolved first).
    ``settle``: start the belt from its static equilibrium (equilibrium.relax, 0.2-1.5 s);
    ``check`` needs only the placement and the step (``placed``, without the kernels). With tensioners, the belt is
    placed on the path of their static equilibrium (``drive.equilibrium``, tensioner.py).

    Without tensioners, the belt's tension means the continuum's, at any segment count: a
    ``belt.length`` gives the tension creep theory gives that installed length at rest (steady/creep.py,
    the belt's depth in the grooves included), and the chain is placed so that it settles to the
    pretension (the settled chain carries up to a few percent less than its placement: chord sag
    and the segments' seating; one corrected placement takes that out). ``belt.segments = "auto"``
    is resolved first (geometry/segment_count.py). ``before_settle(sysm)`` is called with each
    system built, before its belt is settled (a run compiles its time loop ahead meanwhile)."""
    drive = resolve(drive)
    model = drive.resolved
    first, target = _to_place(drive)
    sysm = _build(first, drive, settle, before_settle)
    if target is None:
        return sysm
    if settle and abs(settled_tension(sysm) / target - 1) > SETTLE_TOL:
        sysm = _build(_with_pretension(model, target * target / settled_tension(sysm)), drive, settle,
                      before_settle)
    if settle:
        sysm.init = dataclasses.replace(sysm.init, tension=settled_tension(sysm))
    return sysm


def _to_place(drive):
    """The model ``build`` places the chain of (``drive.resolved``, or at the tension of its belt
    length without tensioners) and that target tension (None with tensioners)."""
    model = drive.resolved
    if drive.tensioners:
        return model, None
    target = model.belt.pretension
    placed = model
    if target is None and model.belt.teeth is not None:
        # a toothed belt's length is its teeth x pitch, which its chain carries one pitch per tooth on
        # the grooved pulleys (geometry/teeth.py: chain_radius)
        check_length(model, drive.layout)
        return model, None          # placed at its length (segments of pitch / nodes_per_tooth); the tension follows
    if target is None:
        from ..steady.creep import drive_of, tensions

        check_length(model, drive.layout)
        T = tensions(drive_of(model, drive.layout), np.zeros(len(model.pulleys)), 0.0, True)
        if T is None:
            raise ModelError(f"belt too long to be tensioned: unstretched length {model.belt.length:.4f} m",
                             field="belt.length")
        target = float(np.mean(T))
        placed = _with_pretension(model, target)
    return placed, target


@dataclass
class Placed:
    """The chain as ``build(drive, settle=False)`` places it, with its step, before the kernels'
    pulley and arm records: what check reports of the segment model."""
    model: object        # drive.resolved
    layout: Layout
    init: InitialState
    belt: Belt
    contact: Contact
    step: float
    step_limit: float
    rest: object = None

    @property
    def n(self):
        return self.belt.n


def placed(drive) -> Placed:
    """``build(drive, settle=False)`` up to the kernels' records, which need numba (check)."""
    drive = resolve(drive)
    return _place(_to_place(drive)[0], drive)


def _with_pretension(model, tension):
    return model.model_copy(update={"belt": model.belt.model_copy(update={"pretension": float(tension), "length": None})})


def settled_tension(sysm) -> float:
    """Mean element force of the belt as placed (N)."""
    from . import _kernels as K
    from .state import new_state, new_work

    init = sysm.init
    S, W = new_state(sysm, init.x, init.y, init.phi), new_work(sysm)
    K.joint_forces(sysm.belt, S, W, 0.0)
    return float(np.mean(W.jfk * np.hypot(W.jdx, W.jdy)))


def _build(model, drive, settle: bool, before_settle=None) -> BeltSystem:
    """The system of ``model`` (the belt placed by its pretension or length; the pulleys as
    drawn); ``drive.resolved``, the user's model, is what the system reports."""
    from ..dynamics.bodies import arms_record, pulleys_record, running_senses
    from .equilibrium import relax

    pl = _place(model, drive)
    drawn, layout, init, rest = pl.model, pl.layout, pl.init, pl.rest
    if rest is not None:
        model = rest.model            # centres at the equilibrium, as placed
    P = pulleys_record(model.pulleys, running_senses(model, layout))
    if model.belt.teeth is not None:
        # the chain carries its teeth at the grooves' spacing riding at these contact radii; placed on the
        # pitch circles, it settles onto them (equilibrium.relax) with the belt's tension (geometry/teeth.py),
        # lifted by the contact's static penetration at the installation tension: the catalogue's pitch
        # circle is where the cord runs as installed. Along the wrap the chain sinks more or less with the
        # local tension, as a belt on its radial support does (mechanics/teeth/loadshare.py, eq. 4).
        from ..geometry.teeth import chain_radius, installed_tension, sinking

        T_in = installed_tension(model, layout, init.tension)
        for j, q in enumerate(model.pulleys):
            if q.teeth:
                P.r[j] = chain_radius(q.radius, model) + sinking(model.contact, T_in / q.radius)[0]
    # the pulleys' contact as the kernels read it: the radii above, the non-circular ones' curves (_curves.py)
    from ._curves import tables as curve_tables

    contact = pl.contact._replace(**curve_tables(model, P.r))
    A = arms_record(drawn, drive.senses)   # travel measured from the drawn centres
    span_mid = np.array([sp.midpoint for sp in layout.spans])
    span_geo = np.array([[*sp.midpoint, math.cos(sp.angle), math.sin(sp.angle)] for sp in layout.spans])
    track = np.array(model.output.segments, dtype=np.int64)
    sysm = BeltSystem(drawn, layout, init, pl.belt, contact, P, A, span_mid, span_geo, track, pl.step,
                      pl.step_limit, rest)
    if before_settle is not None:
        before_settle(sysm)
    # start from the chain's static equilibrium, so that a drive at rest stays at rest
    eq = relax(sysm, init.x, init.y, init.phi) if settle else None
    if eq is not None:
        x, y, phi, res, _ = eq
        if rest is not None:
            x, y, phi = _settle_tensioners(sysm, x, y, phi)
        sysm.init = dataclasses.replace(init, x=x, y=y, phi=phi, residual=res)
    if sysm.contact.teeth:
        sysm.contact = sysm.contact._replace(gphase=groove_phases(sysm.contact, sysm.pulleys, sysm.init.x, sysm.init.y))
    return sysm


#: a tooth engages its groove within this share of the pitch outside the pitch circle (segments/_teeth.py):
#: 0.02 p is 0.19 mm at 9.525 mm, reached 0.3-0.4 pitch before the tangent point on a 19-30 tooth pulley
TOOTH_BAND = 0.02


def _with_teeth(model, layout, B, C):
    """The contact record with the belt's teeth (geometry/teeth.py): a tooth on every
    ``nodes_per_tooth``-th segment, the grooves per pulley; the groove phases follow the placed belt
    (``groove_phases``)."""
    from ..geometry.teeth import belt_teeth

    bt = belt_teeth(model, layout.length)
    nk = len(model.pulleys)
    if bt is None:
        return C
    tk = np.zeros(B.n)
    tk[::bt.nodes] = bt.stiffness
    tc = np.where(tk > 0, 2.0 * bt.damping_ratio * np.sqrt(tk * B.m), 0.0)
    gz = np.array([q.teeth or 0 for q in model.pulleys], dtype=np.int64)
    return C._replace(tk=tk, tc=tc, tplay=float(bt.play), tclimb=float(bt.climb), tpitch=float(bt.pitch),
                      tband=float(TOOTH_BAND * bt.pitch), gz=gz, gphase=np.zeros(nk), teeth=True)


def groove_phases(C, P, x, y) -> np.ndarray:
    """Per grooved pulley, the angle of its groove 0 (pulley at theta = 0) that seats the placed belt's
    teeth in mesh best: the circular mean of their angles over the groove spacing, so that a belt
    whose pitch fits the grooves starts with every tooth centred."""
    from ._curves import penetrations, table_values

    ph = np.zeros(len(C.gz))
    teeth = np.flatnonzero(C.tk > 0)
    for j, z in enumerate(C.gz):
        if z == 0:
            continue
        dx, dy = x[teeth] - P.cx[j], y[teeth] - P.cy[j]
        a = int(C.ccur[j])
        if a >= 0:      # a curve: the arc positions of the teeth's feet on it (m, _curves.py), one groove pitch apart
            p = penetrations(C, P, j, dx, dy)[0]
            on = p > -C.tband
            if not on.any():
                continue
            phi = np.arctan2(dy[on], dx[on])
            d = np.hypot(dx[on], dy[on])
            rc, drc = table_values(C.crad, a, phi)
            rp = table_values(C.cpr, a, phi)[0]
            s_ = table_values(C.carc, a, phi)[0] + C.cper[a] * phi + (d - rp) * drc / rc
            sp = 2 * math.pi * C.cper[a] / z
            ph[j] = float(np.angle(np.mean(np.exp(2j * math.pi * s_ / sp)))) * sp / (2 * math.pi)
            continue
        on = dx * dx + dy * dy < (P.r[j] + C.tband) ** 2
        if not on.any():
            continue
        a = np.arctan2(dy[on], dx[on])
        ph[j] = float(np.angle(np.mean(np.exp(1j * z * a)))) / z
    return ph


def _place(model, drive) -> Placed:
    """``_build`` up to the kernels' records: the chain placed, its constants and its step, with
    the refusals of a step that cannot run."""
    drawn = drive.resolved
    rest = drive.equilibrium
    layout = drive.layout
    if rest is not None:
        rest = dataclasses.replace(rest)     # _build's settling refines this system's copy
        model = rest.model            # centres at the equilibrium, belt.length installed
        layout = compute_layout(model)
    _one_belt_speed(model, layout)
    init = initial_state(model, layout)
    belt, n = model.belt, model.belt.segments
    l = init.seg_length
    e = belt.axial_exponent
    ones = np.ones(n)
    m = belt.mass_per_length * l * ones
    inertia = m * l * l / 12.0                                      # eq. 2
    scaled = integrator(model) == "semi-implicit" and rotation_scaled(model)
    B = Belt(
        n=int(n), m=m, inertia=inertia, inv_m=1.0 / m, inv_i=1.0 / inertia,
        kax=belt.axial_stiffness / l ** e * ones,                     # F = EA (g / l)^e
        bax=belt.axial_damping / l * ones,
        kb=belt.bending_stiffness / l * ones,
        bb=max(belt.bending_damping / l, grid_damping(belt, init)) * ones,   # or the grid mode's (GRID_ZETA)
        eax=float(e), eb=float(belt.bending_exponent), linear=bool(e == 1.0), hl=float(0.5 * l),
        turn=float(init.turn), g=float(model.gravity), iscale=float(ROTATION_SCALE if scaled else 1.0),
        implicit=integrator(model) == "implicit")
    mu = model.friction.coefficient * ones
    # friction zones by arc length of the segment centre measured from the start of segment 0
    s_mid = (np.arange(n) + 0.5) * (l + init.gap)
    for zone in model.friction.zones:
        mu[(s_mid >= zone.start) & (s_mid < zone.end)] = zone.coefficient
    C = Contact(
        c1=model.contact.stiffness_quadratic * l * ones,
        c2=model.contact.stiffness_linear * l * ones,
        bc=model.contact.damping * l * ones,
        mu=mu, pmax=damping_depth(model, init), law=int(LAWS[model.friction.law]),
        dv=float(model.friction.velocity_threshold), dmax=float(model.friction.displacement_limit),
        centre=model.friction.radius == "centre",
        ccur=np.full(len(model.pulleys), -1, dtype=np.int64), creach=np.array([q.radius for q in model.pulleys]))
    C = _with_teeth(model, layout, B, C)
    limit = stability_limit(model, init, B, C, scaled)
    if B.implicit:
        limit = implicit_step(model, init, B, C)
        step = model.simulation.step if model.simulation.step is not None else limit
    else:
        step = model.simulation.step if model.simulation.step is not None else 0.85 * limit
    from ...core.limits import max_steps

    steps = model.simulation.duration / min(step, model.output.interval)
    if integrator(model) == "rkf45":
        h_f = rkf45_step(model, init.tension)
        if h_f is not None:
            # each rkf45 step is six evaluations of the whole chain (and its rejected attempts more):
            # counted as six steps of the limit, which is set by the single-evaluation schemes' steps
            cost = RKF45_STAGES * model.simulation.duration / h_f
            if cost > max_steps():
                raise ModelError(f"rkf45 is explicit: the friction law's slope (mu N / velocity_threshold) limits its "
                                 f"step to about {h_f:.2g} s, {model.simulation.duration / h_f:.2g} steps of "
                                 f"{RKF45_STAGES} stages each ({cost:.2g} counted) for "
                                 f"{model.simulation.duration:g} s, more than the {max_steps():.3g} a run may take: use "
                                 "the implicit or semi-implicit scheme, or a larger friction.velocity_threshold "
                                 "(or set DRIVEDYN_MAX_STEPS)", field="simulation.method")
            # and each stage evaluates every segment: its cost in time is steps x stages x segments
            from ...core.limits import evaluations_problem

            problem = evaluations_problem(cost * n, f"rkf45 is explicit: the friction law's slope (mu N / "
                                          f"velocity_threshold) limits its step to about {h_f:.2g} s, "
                                          f"{model.simulation.duration / h_f:.2g} steps of {RKF45_STAGES} stages "
                                          f"of {n} segments for {model.simulation.duration:g} s",
                                          "use the implicit or semi-implicit scheme, a larger "
                                          "friction.velocity_threshold or a shorter simulation.duration")
            if problem:
                raise ModelError(problem, field="simulation.method")
            per_sample = min(model.output.interval, model.simulation.duration) / h_f
            if per_sample > MAX_STEPS_PER_SAMPLE:
                # (else it ran for minutes, at 0 % on the progress line, before it gave up)
                raise ModelError(f"rkf45 is explicit: the friction law's slope (mu N / velocity_threshold) limits its "
                                 f"step to about {h_f:.2g} s, {per_sample:.2g} steps per output interval of "
                                 f"{model.output.interval:g} s, more than the {MAX_STEPS_PER_SAMPLE:.3g} it takes "
                                 "before it gives up: use the implicit or semi-implicit scheme, or a larger "
                                 "friction.velocity_threshold", field="simulation.method")
    if not steps <= max_steps():
        raise ModelError(f"{steps:.3g} integration steps of {step:.3g} s (stable step {limit:.3g} s) for "
                         f"{model.simulation.duration:g} s, more than the {max_steps():.3g} a run may take: a shorter "
                         "duration, or check the belt's stiffness and damping values and the contact stiffness "
                         "(or set DRIVEDYN_MAX_STEPS)", field="simulation")
    return Placed(drawn, layout, init, B, C, step, limit, rest)


#: prescribed speeds whose belt speeds differ by more than this share cannot all hold without gross
#: slip (creep is below 2 % on any drive the belt model applies to)
SPEED_MISMATCH = 0.05


def _one_belt_speed(model, layout) -> None:
    """Two pulleys with prescribed speeds set the belt speed twice: refuse them (one line) unless
    they agree, at every row of their tables, within creep; otherwise the belt slides on one of
    them and check would report a steady state that cannot exist."""
    presc = [j for j, p in enumerate(model.pulleys) if p.speed_time is not None]
    if len(presc) < 2:
        return
    a = presc[0]
    for b in presc[1:]:
        times = sorted({r[0] for j in (a, b) for r in model.pulleys[j].speed_time})
        for t in times:
            va, vb = (np.interp(t, *np.array(model.pulleys[j].speed_time).T) * layout.rho[j] for j in (a, b))
            if abs(va - vb) > SPEED_MISMATCH * max(abs(va), abs(vb)) and max(abs(va), abs(vb)) > 0:
                pa, pb = model.pulleys[a].name, model.pulleys[b].name
                raise ModelError(f"pulleys {pa!r} and {pb!r} both have a prescribed speed (speed_time) and at "
                                 f"t = {t:g} s they move the belt at {va:.4g} and {vb:.4g} m/s (signed along the "
                                 "loop): the belt would slide on one of them; prescribe one and load the other",
                                 field=f"pulleys[{b}].speed_time")


def _settle_tensioners(sysm, x, y, phi):
    """Move the tensioners until their spring balances the discrete belt's hub force at rest
    (the placement's uniform tension is off by the chain's discretisation), relaxing the belt
    after each move: Newton on the travel with the stiffness of the continuum equilibrium."""
    from ..dynamics import _bodies as BK
    from .equilibrium import relax

    rest, A = sysm.rest, sysm.arms
    scale = max(float(np.max(np.abs(rest.spring))), 1e-9)
    for _ in range(6):
        R = loads_at_rest(sysm, x, y, rest.travel)
        rest.residual = float(np.max(np.abs(R))) / scale
        if rest.residual < 1e-8:
            break
        rest.travel = rest.travel - np.linalg.solve(rest.stiffness, R)
        cx, cy = sysm.pulleys.cx.copy(), sysm.pulleys.cy.copy()
        for a in range(A.na):
            cx[A.pulley[a]], cy[A.pulley[a]] = BK.arm_centre(A, a, rest.travel[a])[:2]
        sysm.pulleys = sysm.pulleys._replace(cx=cx, cy=cy)
        eq = relax(sysm, x, y, phi)
        if eq is None:
            break
        x, y, phi = eq[:3]
    # what check and the summary report: the discrete belt's equilibrium
    A = sysm.arms
    cx, cy = sysm.pulleys.cx, sysm.pulleys.cy
    hub = hub_at_rest(sysm, x, y, cx, cy)
    rest.hub = np.array([float(np.hypot(*hub[A.pulley[a]])) for a in range(A.na)])
    rest.spring = np.array([tensioner.spring_load(sysm.model.pulleys[A.pulley[a]].tensioner, rest.travel[a]) for a in range(A.na)])
    rest.angle = np.array([A.psi0[a] + A.sgn[a] * rest.travel[a] if A.kind[a] == 0 else np.nan for a in range(A.na)])
    sysm.init = dataclasses.replace(sysm.init, x=x, y=y, phi=phi)
    rest.tension = settled_tension(sysm)
    return x, y, phi


def damping_depth(model, init) -> float:
    """p_max of the contact damping ramp: the model's, else the smallest static penetration at the
    pretension (the segments pressed as at rest on the largest pulley get the full damping)."""
    if model.contact.damping_depth is not None:
        return float(model.contact.damping_depth)
    return float(np.min(init.penetration))


# Selective mass scaling of the segments' rotation: I = m l^2/12 -> 3.3 I = 1.1 m l^2/4, just above
# the m l^2/4 that takes the alternating rotation mode (omega^2 = 12 k/m) below the zig-zag modes
# (4 k/m): the step grows by 1.27 on examples/fead-runup.toml's drive, 1.5 on the 5PK
# (simulation.rotation_scaling; by default with the elastic-plastic law only). What it changes is
# the landings: a segment landing on a pulley stops turning relative to it, and the scaled inertia
# raises that turn's energy, I (v/r)^2 / 2, by 3.3 (the landing's whole energy by about 1.6). Where
# the chord sag is resolved (resolution.py) that leaves the losses and the modes as they were
# (fead-runup's drive held at 3000 / 5000 rpm with its orders, 666 segments: contact-damping loss
# 101.3 against 101.9 W, 178.5 against 178.9 W; a two-pulley drive's torsional mode at 24 m/s within
# 0.3 %), but not a tensioner arm's dry friction, which the stronger landing kicks on its pulley
# dither: the alternator-tensioner span's minimum 260-264 N at 666-930 segments scaled against 253 N
# unscaled and 247-248 N at 2664 (3000 rpm; with the arm held, scaled and unscaled agree to 1 N).
# Not the default with Threlfall's law for that; the elastic-plastic law's pre-sliding takes the
# kicks up (rotation_scaled). At a coarse count the landings dominate: the accessory drive at 11 m/s
# lost 33 against 24 W in contact and friction.
ROTATION_SCALE = 3.3


# The chain's grid-scale rotation mode: neighbouring segments turning against each other strain no
# joint (their shared ends move together); only the bending springs (4 k_b) and the tension's arms
# (T l) hold it, omega^2 = (T l + 4 k_b) / I, about 1e5 rad/s for 2.25 mm segments at 400 N. A
# continuous belt has no such mode, and without bending damping (the default) nothing damps it:
# the landings on the pulleys pump it to alternating rates of +-300-600 rad/s in every free span
# (examples/fead-runup.toml's drive held at 3000 rpm), which shortens the chain and reads as
# tension, and at the implicit scheme's large steps grows until a run blows up (666 segments at
# 18.5 us) or reads high: the 5PK held at 800 rad/s at 424 segments, span means 1.2-2.8 % high at
# 8.6-17 us against the semi-implicit scheme, the error the old 0.003 rad-per-step rule kept out.
# A bending damper per joint of c = zeta sqrt(K I) / 2 gives the mode the damping ratio GRID_ZETA;
# at 0.05 the same runs agree within 0.06 % at 8.6-17 us (Threlfall's law; 0.3 % at 25 us) and the
# 666-segment run runs through at 17.9 us (tests/belt/test_grid_mode.py). c scales as l^2 (l^3 per belt length), so a flap mode is not touched (damping ratio
# ~1e-5 on a 100 mm span) and the loss it adds where the belt bends onto and off a pulley falls as
# l^2: 8.6 W in the bending dampers at 333 segments on that drive, 1.7 W more in all (the contact
# damping takes 7 W less). A belt.bending_damping above it replaces it.
GRID_ZETA = 0.05


def grid_damping(belt, init) -> float:
    """The bending damper per joint (N m s/rad) that gives the chain's grid-scale rotation mode
    the damping ratio GRID_ZETA: c = zeta sqrt(K I) / 2, K = T0 l + 4 k_b at the pretension."""
    l = init.seg_length
    inertia = belt.mass_per_length * l ** 3 / 12.0
    k = max(init.tension, 0.0) * l + 4.0 * belt.bending_stiffness / l * max(belt.bending_exponent, 1.0)
    return 0.5 * GRID_ZETA * math.sqrt(k * inertia)


def rotation_scaled(model) -> bool:
    """Whether the semi-implicit scheme scales the segments' rotation: ``simulation.rotation_scaling``,
    where None (the default) scales with the elastic-plastic friction law. With it the bristles take
    up the stronger landings: examples/fead-runup.toml's drive held with its orders, scaled against
    1332 segments unscaled, span minima within 1.6 / 2.5 / 1.2 %, maxima 0.7 / 0.5 / 1.7 %, slips
    0.014 / 0.011 / 0.004 points at 1000 / 3000 / 5000 rpm (333 / 330 / 330 segments;
    benchmarks/bench_fead_defaults.py), where Threlfall's law scaled reads the alternator-tensioner
    span's minimum 5 % high (below)."""
    rs = model.simulation.rotation_scaling
    return bool(rs) if rs is not None else model.friction.law == "elastic-plastic"


def effective_inertia(sysm) -> np.ndarray:
    """Rotational inertia of the segments as the integrator sees it (mass-scaled or not); the
    energy balance uses it, since that is the energy the scheme conserves."""
    return sysm.belt.inertia * sysm.belt.iscale


def _tangent_k(model, init, B):
    e = model.belt.axial_exponent
    k = float(B.kax[0])
    if e != 1.0:  # tangent stiffness at the pretension
        k = e * k * init.gap ** (e - 1)
    return k


# largest default step of the implicit scheme (s), measured: the 5PK, loaded accessory and
# verification drives agree with the semi-implicit reference at 20-40 us; at 100 us the
# verification drive (softer contact) slips grossly, at 150 us the 5PK diverges
IMPLICIT_STEP_MAX = 40e-6


def implicit_step(model, init, B, C) -> float:
    """Default step of the implicit scheme (s): the contact normal mode of a segment on its pulley
    resolved, h omega_c = 2 with omega_c^2 = k_c / m, k_c the contact stiffness at twice the static
    penetration (as in ``stability_limit``), and at most IMPLICIT_STEP_MAX, even where the
    semi-implicit limit is larger: the verification drive (heavy, soft belt; explicit limit 74 us)
    runs into gross slip at 62.5 us (slip 12.5 %) and agrees with the converged reference at
    38.5 us. The chain's stiff modes no longer limit it (5PK: 35 us against 3.1 us)."""
    m = float(B.m[0])
    p = 2 * float(np.max(init.penetration))
    kc = 2 * float(C.c1[0]) * p + float(C.c2[0])
    return min(2 / math.sqrt(kc / m), IMPLICIT_STEP_MAX)


def stability_limit(model, init, B, C, scaled=False) -> float:
    """Largest stable step of the explicit part: 2/omega for the stiffest chain mode.

    The zero-length joint spring is isotropic. Bloch analysis of the straight chain gives, for the
    transverse/rotation branch, omega^2 = 2k [(1 - cos q)/m + (1 + cos q) (l/2)^2 / I]: the
    alternating rotation mode (q = 0) at 12 k / m, and once the rotation is mass-scaled to
    I >= m l^2 / 4 (``scaled``) the zig-zag modes (q = pi) at 4 k / m, raised by the contact
    stiffness k_c. The axial dampers (rate 4 b / m in the zig-zag mode, reduced by the per-joint
    implicit factor 1 / (1 + 2 h b / m)) lower the symplectic-Euler limit to
    2/omega (sqrt(1 + zeta^2) - zeta); solved for h by fixed-point iteration.
    """
    m = float(B.m[0])
    k = _tangent_k(model, init, B)
    p = 2 * float(np.max(init.penetration))          # contact stiffness at twice the static penetration
    kc = 2 * float(C.c1[0]) * p + float(C.c2[0])
    if C.teeth:
        kc += float(np.max(C.tk))          # a tooth's spring acts on its segment beside the contact's
    kb = float(B.kb[0]) * max(model.belt.bending_exponent, 1.0)
    inertia = float(B.inertia[0])
    # the tension adds T l/2 per joint to a segment's rotational stiffness (arms turning in the
    # force); negligible at usual strains, not at tens of per cent: take twice the pretension
    k_rot = k + 4 * kb / init.seg_length ** 2 + 4 * init.tension / init.seg_length
    w_zig = math.sqrt((4 * k + kc) / m)
    if scaled:   # the scaled rotation branch, which at high tension may top the zig-zag modes
        w_zig = max(w_zig, math.sqrt(12 * k_rot / (ROTATION_SCALE * m)))
    b = float(B.bax[0])
    h = 2 / w_zig
    for _ in range(50):
        gamma = 4 * b / m / (1 + 2 * h * b / m)
        zeta = gamma / (2 * w_zig)
        h = 2 / w_zig / (math.sqrt(1 + zeta ** 2) + zeta)  # = sqrt(1 + z^2) - z without cancellation
    limits = [h]
    if not scaled:
        w_rot = math.sqrt(12 * k_rot / m)
        zeta = 4 * float(B.bb[0]) / inertia / (2 * w_rot)
        limits.append(2 / w_rot / (math.sqrt(1 + zeta ** 2) + zeta))
    elif float(B.bb[0]) > 0:   # explicit bending dampers, on the unscaled (conservative) inertia
        limits.append(inertia / (2 * float(B.bb[0])))
    return min(limits)


def hub_at_rest(sysm, x, y, cx, cy) -> np.ndarray:
    """Force (nk, 2) of the belt at rest (x, y segment centres) on each pulley: minus the contact
    normal forces of eq. 9 (no velocity, no friction at rest)."""
    C, P = sysm.contact, sysm.pulleys
    from ._curves import penetrations

    out = np.zeros((P.nk, 2))
    for j in range(P.nk):
        p, nx, ny = penetrations(C, P, j, x - cx[j], y - cy[j])
        on = p > 0
        N = C.c1[on] * p[on] ** 2 + C.c2[on] * p[on]
        out[j] = -np.array([np.sum(N * nx[on]), np.sum(N * ny[on])])
    return out


def loads_at_rest(sysm, x, y, q) -> np.ndarray:
    """Generalised load (spring + belt) on each tensioner with the discrete belt at rest."""
    from ..dynamics import _bodies as BK

    A = sysm.arms
    cx, cy = sysm.pulleys.cx.copy(), sysm.pulleys.cy.copy()
    jac = []
    for a in range(A.na):
        c = BK.arm_centre(A, a, q[a])
        cx[A.pulley[a]], cy[A.pulley[a]] = c[0], c[1]
        jac.append(c[2:])
    hub = hub_at_rest(sysm, x, y, cx, cy)
    spring = [tensioner.spring_load(sysm.model.pulleys[A.pulley[a]].tensioner, q[a]) for a in range(A.na)]
    return np.array([spring[a] + hub[A.pulley[a]] @ jac[a] for a in range(A.na)])


# the implicit scheme's accuracy rule, per friction law: a segment rolling on a pulley turns at
# most this far per step (rad), measured by the fastest pulley's speed. It was 0.003 while the
# chain's grid-scale rotation mode ran undamped (system.GRID_ZETA): at larger turns the steps
# pumped that mode and the 5PK held at 800 rad/s read 1.2-4.9 % high. With the mode damped,
# against the semi-implicit scheme at the same segments: the 5PK at 800 rad/s (424 segments)
# within 0.04 % (elastic-plastic) and 0.3 % (Threlfall) at 0.020 rad per step, 0.2 % and 1 % at
# 0.028 (Threlfall's then misses 4 % of the energy); examples/fead-runup.toml's drive held with
# its orders (333 segments, elastic-plastic) within 1.5 % at 5000 rpm and 0.012-0.035 rad and
# within 1 % of the 4x-refined run at 3000 rpm and 0.032 rad, but at 0.056 rad (5000 rpm, 40 us) it
# ran away and the step control halved the step. Under Threlfall's law the same drive at 3000 rpm
# (330 segments) read the alternator-tensioner span's minimum 3.6 % high at 0.019 rad per step,
# 0.4 % at 0.0096 (tests/belt/test_implicit.py).
TURN_PER_STEP = {"elastic-plastic": 0.02, "threlfall": 0.01}
