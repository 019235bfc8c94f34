"""Rotational natural frequencies and mode shapes of a belt drive, linearised about its steady state.

Discrete rotational model (Hwang, Mote & Lee, J. Mech. Des. 116 (1994); Beikmann, Perkins & Ulsoy,
J. Vib. Acoust. 118 (1996)): the DOFs are the rotations of the pulleys that are free to turn (a
pulley with a prescribed speed is held); span k from pulley a to pulley b in belt order is a
spring EA / L_k on its stretch rho_b theta_b - rho_a theta_a (signed radii: a pulley turning with
the belt feeds belt into the span it leaves and draws it from the span it enters). The springs are
the spans' only (wraps held by adhesion); tension enters through the span lengths only.
A tensioner (arm or slider) adds its travel q as a DOF (inertia about the pivot, or mass): the
spans next to its pulley stretch by g_k q (g_k = d L_k / d q from the layout), its spring adds
its rate and the belt tension T the path's curvature T d^2 L / dq^2 (Beikmann et al.).
Eigenproblem K phi = omega^2 J phi.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from .layout import Layout, compute_layout


@dataclass
class Modes:
    dofs: tuple               # names of the free pulleys
    frequencies_hz: list      # elastic modes, ascending (rigid-body modes left out)
    shapes: list              # per mode: {pulley: rotation, largest |value| = 1}
    participation: list       # per mode: {pulley: share of the modal kinetic energy}
    rigid_modes: int          # zero-frequency modes (the drive turning as one body)


def stiffness(layout: Layout, EA: float) -> np.ndarray:
    """Rotational stiffness matrix (N m/rad) of all pulleys."""
    nk = len(layout.names)
    K = np.zeros((nk, nk))
    for sp in layout.spans:
        g = np.zeros(nk)
        g[sp.end] += layout.rho[sp.end]
        g[sp.start] -= layout.rho[sp.start]
        K += (EA / sp.length) * np.outer(g, g)
    return K


def _moved(model, j, q):
    """The layout with tensioner pulley j moved by travel q (rad about the pivot, or m along the
    slide) from where the model has it."""
    from .tensioner import centre, with_centres

    return compute_layout(with_centres(model, {j: centre(model, j, q, 1.0)}))


def _tensioner_rows(model, lay, tension):
    """Per tensioner: name, inertia, span-stretch gradient g (per span) and stiffness rate + T L''."""
    out = []
    for j, p in enumerate(model.pulleys):
        t = p.tensioner
        if t is None:
            continue
        h = 1e-5 if p.arm is not None else 1e-6
        lp, lm = _moved(model, j, h), _moved(model, j, -h)
        g = np.array([(a.length - b.length) / (2 * h) for a, b in zip(lp.spans, lm.spans)])
        curv = (lp.length - 2 * lay.length + lm.length) / h ** 2
        inertia = t.inertia if p.arm is not None else t.mass
        out.append((f"{p.name}.{'arm' if p.arm is not None else 'slider'}", inertia, g, t.rate + tension * curv))
    return out


def modes(model, layout: Layout | None = None) -> Modes:
    lay = layout or compute_layout(model)
    free = [j for j, p in enumerate(model.pulleys) if not p.speed_time]
    K = stiffness(lay, model.belt.axial_stiffness)[np.ix_(free, free)]
    J = np.diag([model.pulleys[j].inertia for j in free])
    names = tuple(lay.names[j] for j in free)
    rows = _tensioner_rows(model, lay, model.belt.pretension or 0.0)
    if rows and free:
        # tensioner DOFs: span stretches rho_b theta_b - rho_a theta_a + g_k q
        nf, na = len(free), len(rows)
        G = np.zeros((len(lay.spans), nf + na))
        for k, sp in enumerate(lay.spans):
            for jj, sgn in ((sp.end, 1.0), (sp.start, -1.0)):
                if jj in free:
                    G[k, free.index(jj)] += sgn * lay.rho[jj]
            for a, (_, _, g, _) in enumerate(rows):
                G[k, nf + a] = g[k]
        EA = model.belt.axial_stiffness
        K = sum((EA / sp.length) * np.outer(G[k], G[k]) for k, sp in enumerate(lay.spans))
        for a, (_, _, _, kq) in enumerate(rows):
            K[nf + a, nf + a] += kq
        J = np.diag([model.pulleys[j].inertia for j in free] + [r[1] for r in rows])
        names = names + tuple(r[0] for r in rows)
    if not free:
        return Modes((), [], [], [], 0)
    w2, vec = eigh(K, J)
    scale = float(np.max(np.abs(w2))) or 1.0
    rigid = int(np.sum(w2 < 1e-9 * scale))
    freqs, shapes, parts = [], [], []
    for k in range(rigid, len(w2)):
        phi = vec[:, k] / vec[np.argmax(np.abs(vec[:, k])), k]
        e = np.diag(J) * phi ** 2
        freqs.append(math.sqrt(max(w2[k], 0.0)) / (2 * math.pi))
        shapes.append({n: float(x) for n, x in zip(names, phi)})
        parts.append({n: float(x) for n, x in zip(names, e / e.sum())})
    return Modes(names, freqs, shapes, parts, rigid)
