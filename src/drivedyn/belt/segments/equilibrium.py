"""Static equilibrium of the discrete belt: the state a drive at rest keeps.

The placement (geometry/placement.py) puts chord ends on the path; it is not an equilibrium of the rigid-
segment chain (point contacts at the segment centres, joints at the chord ends): up to tens of
newtons of residual force per segment, and the chain's potential energy depends on its phase
along the path (period one segment, the chain's cogging). Started there, a free drive falls into
the nearest cogging well and swings in it (about 1.7 rad/s at 100 segments for the 5PK drive).

At rest friction is zero (both laws give no force at zero slip and zero elastic displacement)
and the pulleys' angles do not enter the energy, so the static equilibrium is a minimum of the
belt's potential energy (joints, bending, contact, gravity: ``_kernels.energy``, whose gradient
is ``_kernels.static_forces``) over the 3 n segment coordinates. Newton's method with an energy
line search finds it; the Hessian is the central difference of the forces, banded (a segment
couples only to its two neighbours), so a few coloured sweeps of force evaluations build it. Forces in equilibrium vanish to round-off, so the
semi-implicit step leaves the state exactly in place.
"""
from __future__ import annotations

import numpy as np

from . import _kernels as K
from .state import new_state, new_work

#: converged when every residual force is below this share of the pretension (and moments below
#: it times the segment length)
FORCE_TOL = 1e-9
#: Newton iterations: each moves a segment by at most a tenth of its length, so finer chains need
#: more (the accessory drive with a tensioner arm: 120 at 337 segments, where 60 left it unrelaxed
#: and the idler drifted at 0.1 rad/s from rest)
MAX_ITER = 400


def _state(sysm, q):
    """Kernel State at rest in configuration q (n, 3: x, y, phi)."""

    return new_state(sysm, *(np.ascontiguousarray(q[:, k]) for k in range(3)))


def forces(sysm, q: np.ndarray) -> np.ndarray:
    """Static generalised forces -dE/dq (n, 3: fx, fy, moment) at zero velocity, q = (x, y, phi)."""

    S = _state(sysm, q)
    W = new_work(sysm)
    B, C, P, _ = sysm.groups
    K.static_forces(B, C, P, S, W)
    return np.stack([W.fx, W.fy, W.mz], axis=1)


def potential(sysm, q: np.ndarray) -> float:
    """Potential energy (J) of the belt at rest in configuration q (the pulleys at rest add none)."""
    B, C, P, A = sysm.groups
    S = _state(sysm, q)
    S.om[:] = 0.0
    S.qd[:] = 0.0
    return float(K.energy(B, C, P, A, S))


def _hessian(sysm, q, scale):
    """Banded Hessian by central differences of the forces, perturbing segments three apart at once
    (their neighbourhoods i-1..i+1 do not overlap; the n mod 3 last segments get their own sweeps)."""
    from scipy import sparse

    n = sysm.n
    color = np.arange(n) % 3
    if n % 3:
        color[n - n % 3:] = 3 + np.arange(n % 3)
    rows, cols, vals = [], [], []
    for col in range(int(color.max()) + 1):
        segs = np.nonzero(color == col)[0]
        nb = np.stack([(segs - 1) % n, segs, (segs + 1) % n], axis=1)        # (m, 3) neighbours
        for d in range(3):
            eps = 1e-7 * scale[d]
            qp, qm = q.copy(), q.copy()
            qp[segs, d] += eps
            qm[segs, d] -= eps
            dg = (forces(sysm, qm) - forces(sysm, qp)) / (2 * eps)       # d(grad E)/dq
            for e in range(3):
                rows.append((3 * nb + e).ravel())
                cols.append(np.repeat(3 * segs + d, 3))
                vals.append(dg[nb, e].ravel())
    H = sparse.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * n, 3 * n))
    return 0.5 * (H + H.T)


def relax(sysm, x, y, phi):
    """Static equilibrium nearest the placement (x, y, phi): returns (x, y, phi, residual force
    share, iterations), or None when Newton does not converge (the placement is then kept)."""
    # (scipy.sparse imported here: check builds the system without settling it)
    from scipy import sparse
    from scipy.sparse.linalg import spsolve

    l, T0 = sysm.init.seg_length, sysm.init.tension
    scale = np.array([l, l, 1.0])
    q = np.stack([x, y, phi], axis=1).astype(float)
    E = potential(sysm, q)
    for it in range(MAX_ITER):
        F = forces(sysm, q)
        res = max(float(np.abs(F[:, :2]).max()), float(np.abs(F[:, 2]).max()) / l) / T0
        if not np.isfinite(res):
            return None
        if res < FORCE_TOL:
            return q[:, 0].copy(), q[:, 1].copy(), q[:, 2].copy(), res, it
        g = -F.ravel()
        H = _hessian(sysm, q, scale)
        # Newton; where the Hessian is not positive (a segment at the kink of the contact law,
        # p = 0, or near a cogging maximum) shift it towards its diagonal until the step descends
        D = sparse.diags(np.abs(H.diagonal()) + 1e-300)
        tau = 0.0
        for _ in range(12):
            dq = spsolve((H + tau * D).tocsc(), -g).reshape(-1, 3)
            slope = float(g @ dq.ravel())
            if np.all(np.isfinite(dq)) and slope < 0:
                break
            tau = 1e-6 if tau == 0.0 else 10 * tau
        else:
            return None
        # at most a tenth of a segment per step: the chain must not jump wells or lose contact
        a = min(1.0, 0.1 * l / max(float(np.abs(dq[:, :2]).max()), 1e-300))
        while True:
            qn = q + a * dq
            En = potential(sysm, qn)
            if En <= E + 1e-4 * a * slope or En - E <= 1e-13 * abs(E) or a < 1e-8:   # (round-off level)
                break
            a *= 0.5
        q, E = qn, En
    return None
