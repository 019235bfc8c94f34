"""Rotational natural frequencies and mode shapes of a belt drive, linearised about its steady state.

Discrete rotational model (Hwang, Mote & Lee, J. Mech. Des. 116 (1994); Beikmann, Perkins & Ulsoy,
J. Vib. Acoust. 118 (1996)): the DOFs are the rotations of the pulleys that are free to turn (a
pulley with a prescribed speed is held); span k from pulley a to pulley b in belt order is a
spring EA / L_k on its stretch rho_b theta_b - rho_a theta_a (signed radii: a pulley turning with
the belt feeds belt into the span it leaves and draws it from the span it enters). The springs are
the spans' only (wraps held by adhesion); tension enters through the span lengths only.
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


def modes(model, layout: Layout | None = None) -> Modes:
    lay = layout or compute_layout(model)
    free = [j for j, p in enumerate(model.pulleys) if not p.speed_time]
    K = stiffness(lay, model.belt.axial_stiffness)[np.ix_(free, free)]
    J = np.diag([model.pulleys[j].inertia for j in free])
    names = tuple(lay.names[j] for j in free)
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
