"""Rotational natural frequencies and mode shapes of a belt drive, linearised about its steady state.

Discrete model in the spirit of Hwang, Mote & Lee (J. Mech. Des. 116, 1994) and Beikmann, Perkins
& Ulsoy (J. Vib. Acoust. 118, 1996): the DOFs are the rotations of the pulleys that are free to turn
(a pulley with a prescribed speed is held), the travel q of each tensioner (arm angle about its
pivot, or slide) and, with a decoupler, its rotor's rotation.

The belt sticks to the wraps and rolls on the pulleys without slip (with the elastic-plastic
friction law, the wraps' bristles give: ``_wrap_compliance``). A pulley turning by theta feeds
its signed radius times theta into the span it leaves; a tensioner moving by q changes a span's
straight length and turns its tangent points round the pulleys, and the belt that rolls on or off
there (rho times the turn) is taken from or given to the span. The stretch is then, to first order,
the projection of the tensioner centre's motion on the span direction (not the change of the
straight length: with adhesion the belt does not slide round the neighbouring pulleys). Span k is a
spring EA / L_k at tension T_k on its stretch e_k; its energy's Hessian is

    K_k = (EA / L_k) grad(e_k) grad(e_k)^T + T_k Hess(e_k),

where e_k is linear in the rotations and Hess(e_k), the geometric stiffness of the prestressed span
in the tensioners' travel, comes from exact layouts (for a uniform tension T it sums to
T d^2 L_path / dq^2). The tensioner adds its spring rate, a decoupler its torsion spring.

The belt's mass is included: each span as a bar whose velocity varies linearly between its two
points (consistent mass m L / 6 [[2, 1], [1, 2]] on the points' velocities), each wrap as mass
carried rigidly by its pulley. A one-way clutch's rotor is in the modes twice: locked (rotor
inertia added to its pulley: the clutch transmits) and free (overrunning: the pulley alone).
Eigenproblem K phi = omega^2 M phi.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._wraps import wrap_axial_stiffness
from ...mechanics.layout import Layout, compute_layout

#: points per wrap for its mass (the wrap is an arc carried rigidly by its pulley)
WRAP_POINTS = 24


@dataclass
class Modes:
    dofs: tuple               # names of the DOFs (free pulleys, "<tensioner>.arm" / ".slider", "<pulley>.rotor")
    frequencies_hz: list      # elastic modes, ascending (rigid-body modes left out); clutches locked
    shapes: list              # per mode: {dof: value, largest |value| = 1}
    participation: list       # per mode: {dof: share of the modal kinetic energy}
    rigid_modes: int          # zero-frequency modes (the drive turning as one body)
    free_rotor_hz: list = field(default_factory=list)   # with one-way clutches overrunning (rotors free); [] without


def stiffness(layout: Layout, EA: float) -> np.ndarray:
    """Rotational stiffness matrix (N m/rad) of all pulleys held by their spans alone (no tensioner)."""
    nk = len(layout.names)
    K = np.zeros((nk, nk))
    for sp in layout.spans:
        g = np.zeros(nk)
        g[sp.end] += layout.rho[sp.end]
        g[sp.start] -= layout.rho[sp.start]
        K += (EA / sp.length) * np.outer(g, g)
    return K


def _tensioner_kinematics(model, j, q0):
    """Centre velocity dc/dq and acceleration d^2c/dq^2 of tensioner pulley j (exact: a circle
    about the pivot, or a straight slide), and the spring's rate -d(load)/dq at travel q0 from
    the drawn position."""
    from ..geometry.tensioner import spring_load

    p = model.pulleys[j]
    t = p.tensioner
    c = np.asarray(p.center, float)
    h = 1e-5 if p.arm is not None else 1e-6
    rate = -(spring_load(t, q0 + h) - spring_load(t, q0 - h)) / (2 * h)
    if p.arm is not None:
        r = c - np.asarray(p.arm.pivot, float)
        return np.array([-r[1], r[0]]), -r, rate, t.inertia          # d/dq of pivot + R(q) r
    d = np.asarray(p.slider.direction, float)
    return d / np.linalg.norm(d), np.zeros(2), rate, t.mass


def rolled_on(lay0: Layout, lay: Layout):
    """Per span: the belt rolled onto its start and its end pulley as their tangent points moved
    round them from lay0 to lay (rolling without slip: rho times the tangent point's turn, signed
    so that the two plus the change of the straight length are the span's stretch)."""
    t0, t1 = np.empty(len(lay.spans)), np.empty(len(lay.spans))
    for k, (s0, s1) in enumerate(zip(lay0.spans, lay.spans)):
        for out, j, p0, p1, sgn in ((t0, s1.start, s0.p0, s1.p0, 1.0), (t1, s1.end, s0.p1, s1.p1, -1.0)):
            a0 = math.atan2(p0[1] - lay0.centers[j][1], p0[0] - lay0.centers[j][0])
            a1 = math.atan2(p1[1] - lay.centers[j][1], p1[0] - lay.centers[j][0])
            out[k] = sgn * lay.rho[j] * math.remainder(a1 - a0, 2 * math.pi)
    return t0, t1


def stretch_of(lay0: Layout, lay: Layout) -> np.ndarray:
    """Stretch of each span from layout lay0 to lay (pulleys not turning): the change of its straight
    length, less the belt that rolls onto its two pulleys as its tangent points move round them
    (``rolled_on``)."""
    t0, t1 = rolled_on(lay0, lay)
    return np.array([s1.length - s0.length for s0, s1 in zip(lay0.spans, lay.spans)]) + t0 + t1


def _stretch_derivatives(model, lay, tens, h=None):
    """Gradient g (spans, tensioners) and Hessians H (spans, tensioners, tensioners) of the span
    stretches in the tensioners' travel, by central differences of exact layouts."""
    from ..geometry.tensioner import centre, with_centres

    na = len(tens)
    steps = np.array([1e-4 if model.pulleys[j].arm is not None else 5e-6 for j in tens]) if h is None else h

    def e(dq):
        moved = {j: centre(model, j, float(q), 1.0) for j, q in zip(tens, dq)}
        return stretch_of(lay, compute_layout(with_centres(model, moved)))

    g = np.zeros((len(lay.spans), na))
    H = np.zeros((len(lay.spans), na, na))
    for a in range(na):
        da = np.zeros(na)
        da[a] = steps[a]
        ep, em = e(da), e(-da)
        g[:, a] = (ep - em) / (2 * steps[a])
        H[:, a, a] = (ep + em) / steps[a] ** 2          # e(0) = 0
        for b in range(a):
            db = np.zeros(na)
            db[b] = steps[b]
            H[:, a, b] = H[:, b, a] = (e(da + db) - e(da - db) - e(db - da) + e(-da - db)) / (4 * steps[a] * steps[b])
    return g, H


@dataclass
class Linear:
    """The drive's linear model about its steady state (belt stuck to every wrap)."""
    dofs: tuple               # names, as Modes.dofs
    K: np.ndarray             # stiffness (n, n)
    M: np.ndarray             # mass, one-way clutches overrunning (rotors free)
    M_locked: np.ndarray      # mass, one-way clutches transmitting (rotors on their pulleys)
    G: np.ndarray             # (spans, n): span stretch per unit DOF (m per rad or per travel unit)
    span_stiffness: np.ndarray  # EA / L per span (N/m)


def modes(model, layout: Layout | None = None, tensions=None, travel=None) -> Modes:
    """Modes of ``model`` about the layout it draws (give a tensioned drive at its equilibrium:
    tensioner.equilibrium(model).model). ``tensions``: per span (N), default the pretension;
    ``travel``: per tensioner, its travel from the drawn position (for a spring table's slope)."""
    lin = linear_model(model, layout, tensions, travel)
    if lin is None:
        return Modes((), [], [], [], 0)
    out = _eigen(lin.K, lin.M_locked, lin.dofs)
    if lin.M_locked is not lin.M:
        out.free_rotor_hz = _eigen(lin.K, lin.M, lin.dofs).frequencies_hz
    return out


def linear_model(model, layout: Layout | None = None, tensions=None, travel=None, held_as_dofs=False):
    """K, M and the span stretch map of the drive (arguments as ``modes``); ``held_as_dofs``: the
    pulleys with a prescribed speed are DOFs too (in pulley order with the free ones), for a forced
    response to their motion. None when nothing is free to move."""
    lay = layout or compute_layout(model)
    pulleys = model.pulleys
    nk = len(pulleys)
    belt = model.belt
    EA, mass = belt.axial_stiffness, belt.mass_per_length
    T = np.full(len(lay.spans), float(belt.pretension or 0.0)) if tensions is None else np.asarray(tensions, float)
    # --- the DOFs and each pulley's point kinematics: dP/dx (2 x ndof) and d2P (ndof x ndof x 2) ---
    free = [j for j, p in enumerate(pulleys) if held_as_dofs or not p.speed_time]
    names = [lay.names[j] for j in free]
    col = {("rot", j): a for a, j in enumerate(free)}
    tens = [j for j, p in enumerate(pulleys) if p.tensioner is not None]
    kin = {}
    for a, j in enumerate(tens):
        p = pulleys[j]
        col[("ten", j)] = len(names)
        names.append(f"{p.name}.{'arm' if p.arm is not None else 'slider'}")
        kin[j] = _tensioner_kinematics(model, j, 0.0 if travel is None else float(travel[a]))
    rotors = [j for j in free if pulleys[j].clutch is not None and pulleys[j].clutch.type == "decoupler"]
    for j in rotors:
        col[("rotor", j)] = len(names)
        names.append(f"{pulleys[j].name}.rotor")
    n = len(names)
    if not free and not tens:
        return None

    def point(j, pt):
        """Velocity Jacobian (2, n) of the belt's material point pt on pulley j."""
        r = np.asarray(pt, float) - lay.centers[j]
        Jp = np.zeros((2, n))
        if ("rot", j) in col:
            Jp[:, col[("rot", j)]] = (-r[1], r[0])
        if ("ten", j) in col:
            Jp[:, col[("ten", j)]] += kin[j][0]
        return Jp

    # stretch of each span: linear in the rotations (rho_b theta_b - rho_a theta_a), and in the
    # tensioners' travel a function the layout gives exactly (stretch_of)
    G = np.zeros((len(lay.spans), n))
    for k, sp in enumerate(lay.spans):
        for jj, sgn in ((sp.end, 1.0), (sp.start, -1.0)):
            if ("rot", jj) in col:
                G[k, col[("rot", jj)]] += sgn * lay.rho[jj]
    K, M = np.zeros((n, n)), np.zeros((n, n))
    if tens:
        cols = [col[("ten", j)] for j in tens]
        g, H = _stretch_derivatives(model, lay, tens)
        G[:, cols] = g
        K[np.ix_(cols, cols)] += np.einsum("k,kab->ab", T, H)
    for k, sp in enumerate(lay.spans):
        K += (EA / sp.length) * np.outer(G[k], G[k])
        Ja, Jb = point(sp.start, sp.p0), point(sp.end, sp.p1)
        M += mass * sp.length / 6 * (2 * Ja.T @ Ja + Ja.T @ Jb + Jb.T @ Ja + 2 * Jb.T @ Jb)
    if model.friction.law == "elastic-plastic":
        dK, G = _wrap_compliance(model, lay, T, G)
        K += dK
    for j in range(nk):
        # the wrap's belt, carried by pulley j
        a0, sweep = lay.arc_start[j], lay.wrap[j] * math.copysign(1.0, lay.rho[j])
        dm = mass * lay.radii[j] * lay.wrap[j] / WRAP_POINTS
        for s in (np.arange(WRAP_POINTS) + 0.5) / WRAP_POINTS:
            ang = a0 + sweep * s
            Jp = point(j, lay.centers[j] + lay.radii[j] * np.array([math.cos(ang), math.sin(ang)]))
            M += dm * Jp.T @ Jp
    for j in free:
        a = col[("rot", j)]
        M[a, a] += pulleys[j].inertia
    for j in tens:
        b = col[("ten", j)]
        K[b, b] += kin[j][2]
        M[b, b] += kin[j][3]
    for j in rotors:
        a, r = col[("rot", j)], col[("rotor", j)]
        k_c = pulleys[j].clutch.rate
        K[np.ix_([a, r], [a, r])] += k_c * np.array([[1.0, -1.0], [-1.0, 1.0]])
        M[r, r] += pulleys[j].clutch.inertia
    K = 0.5 * (K + K.T)
    one_way = [j for j in free if pulleys[j].clutch is not None and pulleys[j].clutch.type == "one-way"]
    locked = M.copy() if one_way else M
    for j in one_way:
        a = col[("rot", j)]
        locked[a, a] += pulleys[j].clutch.inertia
    return Linear(tuple(names), K, M, locked, G, np.array([EA / sp.length for sp in lay.spans]))


def _wrap_compliance(model, lay, T, G):
    """The wraps' compliance under the elastic-plastic friction law: every stuck bit of belt is held
    to its pulley by a bristle of stiffness mu N / Delta_max, per unit length k' = mu T / (r
    Delta_max) at tension T, so the belt on a wrap moves against the rim where the spans pull it.
    Along the wrap its displacement u relative to the rim obeys EA_w u'' = k' u (a shear lag of length
    1 / beta, beta^2 = k' / EA_w; EA_w the wrap's axial stiffness with the belt's sinking into the
    rim, ``rotational/_kernels.wrap_axial_stiffness``), whose two ends, u_in where the belt arrives and
    u_out where it leaves, then carry the energy EA_w beta / 2 [(u_in^2 + u_out^2) coth(beta L) - 2
    u_in u_out csch(beta L)] (L = r x wrap). A span's stretch gains u_in of its end pulley less
    u_out of its start pulley. These massless displacements are condensed out. Linearised at rest:
    every bristle elastic (a loaded wrap's sliding arc has none, which this leaves out). Returns the
    stiffness to add to the adhesion model's and the span stretch map with the wraps' displacements
    condensed."""
    nk = len(lay.names)
    EA, mu, dmax = model.belt.axial_stiffness, model.friction.coefficient, model.friction.displacement_limit
    c1, c2 = float(model.contact.stiffness_quadratic), float(model.contact.stiffness_linear)
    H = np.zeros((len(lay.spans), 2 * nk))          # columns 2 j: u_in on pulley j, 2 j + 1: u_out
    Kww = np.zeros((2 * nk, 2 * nk))
    t_wrap = np.zeros(nk)
    for k, sp in enumerate(lay.spans):
        H[k, 2 * sp.end] += 1.0
        H[k, 2 * sp.start + 1] -= 1.0
        t_wrap[sp.end] += 0.5 * T[k]
        t_wrap[sp.start] += 0.5 * T[k]
    for j in range(nk):
        r = float(lay.radii[j])
        L = r * float(lay.wrap[j])
        kb = mu * max(t_wrap[j], 0.0) / (r * dmax)
        if kb <= 0.0 or L <= 0.0:          # no grip: the belt's ends slide freely
            continue
        ew = wrap_axial_stiffness(EA, c1, c2, max(t_wrap[j], 0.0) / r, r)
        b = math.sqrt(kb / ew)
        x = b * L
        # the energy in the wrap's two motions: (u_in + u_out) / 2, the belt sliding along the whole
        # wrap against its bristles (stiffness 2 EA_w beta tanh(beta L / 2), kb L at a short or
        # lightly held wrap), and u_in - u_out, its stretch (EA_w beta coth(beta L / 2) / 2, EA_w / L
        # there). Written so, no term cancels: coth - csch of a small beta L (a small mu or a
        # slack wrap) lost every digit of the sliding stiffness
        slide, stretch = math.tanh(0.5 * x), 1.0 / math.tanh(0.5 * x)
        Kww[2 * j:2 * j + 2, 2 * j:2 * j + 2] += 0.5 * ew * b * (slide * np.array([[1.0, 1.0], [1.0, 1.0]])
                                                                 + stretch * np.array([[1.0, -1.0], [-1.0, 1.0]]))
    ks = np.array([EA / sp.length for sp in lay.spans])
    Kxw = (G * ks[:, None]).T @ H
    Kww += (H * ks[:, None]).T @ H
    try:
        C = np.linalg.solve(Kww, Kxw.T)              # u = -C x
    except np.linalg.LinAlgError:
        # no wrap grips (every span slack: each wrap's ends slide freely): the belt sliding round
        # all pulleys at once stretches no span and is stiffened by nothing. Kxw carries no force
        # into that motion (H maps it to zero stretch), so the least-squares solution is the
        # condensation's exact one (it was a singular-matrix traceback after a finished run)
        C = np.linalg.lstsq(Kww, Kxw.T, rcond=None)[0]
    return -Kxw @ C, G - H @ C


def _generalised_eigh(K, M):
    """K v = w2 M v for symmetric K and positive definite M, as LAPACK's sygv reduces it (M = L L^T,
    the standard problem of L^-1 K L^-T): in numpy, so that ``drivedyn check`` does not import
    scipy.linalg for a ten-by-ten problem (0.2-0.4 s of its 0.6-1.7 s). Vectors M-orthonormal."""
    Linv = np.linalg.inv(np.linalg.cholesky(M))
    A = Linv @ K @ Linv.T
    w2, y = np.linalg.eigh(0.5 * (A + A.T))
    return w2, Linv.T @ y


def _eigen(K, M, names) -> Modes:
    w2, vec = _generalised_eigh(K, M)
    scale = float(np.max(np.abs(w2))) or 1.0
    rigid = int(np.sum(w2 < 1e-9 * scale))
    freqs, shapes, parts = [], [], []
    for k in range(rigid, len(w2)):
        phi = vec[:, k] / vec[np.argmax(np.abs(vec[:, k])), k]
        e = phi * (M @ phi)
        freqs.append(math.sqrt(max(w2[k], 0.0)) / (2 * math.pi))
        shapes.append({n: float(x) for n, x in zip(names, phi)})
        parts.append({n: float(x) for n, x in zip(names, e / e.sum())})
    return Modes(names, freqs, shapes, parts, rigid)


def drive_modes(model, tensions=None) -> Modes:
    """Modes of a drive as built: a tensioned drive about the static equilibrium of the continuous
    belt and its tensioners (rest.rest_state, the rotational model's rest state), at that rest
    tension unless span ``tensions`` are given."""
    built, travel = _as_built(model)
    return modes(built, tensions=tensions, travel=travel)


def crank_free_modes(model, tensions=None) -> Modes:
    """Modes of a drive as built with its prescribed-speed pulleys (the crank) free on their
    inertias: the supplier's "system resonance" is the first (the rigid turning of the whole drive
    is left out). The crank's ``inertia`` must be the engine's, as the supplier takes it."""
    lin = drive_linear_model(model, tensions, held_as_dofs=True)
    return _eigen(lin.K, lin.M_locked, lin.dofs) if lin is not None else Modes((), [], [], [], 0)


def drive_linear_model(model, tensions=None, held_as_dofs=False):
    """``linear_model`` of a drive as built (as ``drive_modes``)."""
    built, travel = _as_built(model)
    return linear_model(built, tensions=tensions, travel=travel, held_as_dofs=held_as_dofs)


def _as_built(model):
    """The drive with its tensioners at the rest equilibrium (its pretension the rest tension) and
    their travel; the drawn drive and None without tensioners. ``model``: a model or its
    geometry.drive.Drive."""
    from ..geometry import tensioner
    from ..geometry.drive import resolve

    drive = resolve(model)
    model = drive.model
    if not drive.tensioners:
        return model, None
    travel, T, _ = drive.rest
    moved = tensioner.with_centres(model, {j: tensioner.centre(model, j, q, s)
                                           for j, q, s in zip(drive.tensioners, travel, drive.senses)})
    belt = moved.belt.model_copy(update={"pretension": float(T), "length": None})
    return moved.model_copy(update={"belt": belt}), travel
