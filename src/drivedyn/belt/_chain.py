"""The linear solve of the `implicit` belt scheme: the stiff joints of the segment chain treated
implicitly through one cyclic block-tridiagonal system, O(n) per step.

Scheme (derived here; see ``_kernels.step_chunk``): symplectic Euler whose velocity update sees
the joints through a modified mass matrix,

    A dv = h F(x_n, v_n),   A = M + sum over joints G_j^T (h^2/2 k_j + h b_j) G_j   (+ bending),
    x_{n+1} = x_n + h v_{n+1},

G_j the 2 x 6 map from the two segments' velocities (vx, vy, w) to the joint's gap velocity, k_j
the tangent stiffness of its zero-length spring, b_j its damper. For one oscillator (m, k) this
is symplectic Euler with the stiffness k / (1 + h^2 k / 2m): the update matrix has determinant 1
(no numerical damping) and trace 2 - 2 h^2 w^2 / (2 + h^2 w^2) > -2 for every h (no stability
limit); a mode of frequency w is slowed by the relative (h w)^2 / 4, so the modes a user wants
(w h << 1) are kept and the chain's stiff modes (w h >> 1) no longer set the step. Per segment A also carries
(``factor``'s arguments) the contact's normal stiffness and damping (kap n n^T), a stuck
segment's friction anchor along the tangent (kat t t^T) and the joints' geometric (tension)
stiffness on its rotation (geo). The h b_j term
makes each damper backward-Euler. A's extra terms vanish as h -> 0, so a slightly stale A
(segments turned by a few hundredths of a radian since it was factored) costs neither consistency
nor stability: the stiff modes sit at h w_eff = sqrt 2, half the limit 2. They act on the whole
velocity change, though: the contact term kap n n^T would read a segment's turn round its pulley
(its velocity turning inward by h v^2 / r per step) as a normal velocity and push back by
(kap / h) h v^2 / r, twice the normal force at 23.6 m/s; the kernel takes that part out (its
``can``), and the joints' likewise (``_kernels._joint_transport``: a rolling chain's G dv is
-h omega^2 times the chord, not 0), reads a stuck segment's slip along the chord of its step, and
limits the turn per step (simulate.TURN_PER_STEP).

A is symmetric positive definite; segment i couples to i-1 and i+1 through joints i and i+1,
and joint 0 closes the loop (n-1, 0). It is factored by block Gaussian elimination with the last
segment as the border (3 x 3 blocks; fill-in only in the border column), stored as

    dinv[i] = (reduced diagonal block i)^-1,  ymat[i] = dinv[i] O[i+1],  xmat[i] = dinv[i] E[i],

O[i+1] the block (i, i+1), E[i] the border block (i, n-1). The solve is then a forward and a
back sweep of 45 multiply-adds per segment.
"""
import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def _sym_inverse(a, ia, out, io):
    """out[io] = a[ia]^-1 for a symmetric positive definite 3 x 3 (rows of 9, row-major)."""
    a00, a01, a02, a11, a12, a22 = a[ia, 0], a[ia, 1], a[ia, 2], a[ia, 4], a[ia, 5], a[ia, 8]
    c00 = a11 * a22 - a12 * a12
    c01 = a02 * a12 - a01 * a22
    c02 = a01 * a12 - a02 * a11
    c11 = a00 * a22 - a02 * a02
    c12 = a01 * a02 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    inv = 1.0 / (a00 * c00 + a01 * c01 + a02 * c02)
    out[io, 0] = c00 * inv
    out[io, 1] = c01 * inv
    out[io, 2] = c02 * inv
    out[io, 3] = c01 * inv
    out[io, 4] = c11 * inv
    out[io, 5] = c12 * inv
    out[io, 6] = c02 * inv
    out[io, 7] = c12 * inv
    out[io, 8] = c22 * inv


@njit(cache=True, inline="always")
def _mul(a, ia, b, ib, out, io):
    """out[io] = a[ia] b[ib] (3 x 3 blocks, row-major)."""
    for r in range(3):
        for c in range(3):
            out[io, 3 * r + c] = a[ia, 3 * r] * b[ib, c] + a[ia, 3 * r + 1] * b[ib, 3 + c] + a[ia, 3 * r + 2] * b[ib, 6 + c]


@njit(cache=True, inline="always")
def _sub_tmul(a, ia, b, ib, out, io):
    """out[io] -= a[ia]^T b[ib] (3 x 3 blocks, row-major)."""
    for r in range(3):
        for c in range(3):
            out[io, 3 * r + c] -= a[ia, r] * b[ib, c] + a[ia, 3 + r] * b[ib, 3 + c] + a[ia, 6 + r] * b[ib, 6 + c]


@njit(cache=True)
def factor(n, hl, c, s, m, inertia, sig, gam, geo, kap, kat, knx, kny, dmat, omat, emat, dinv, ymat, xmat):
    """Assemble and factor A (see the module doc) at the segment angles (c, s): m, inertia per
    segment (the integrator's, mass-scaled or not); sig[j] = h^2/2 k_j + h b_j per joint (N s/m
    times s: the gap block sig I), gam[j] the same for its bending spring and damper. dmat, omat,
    emat: (n, 9) scratch; dinv, ymat, xmat: (n, 9) the factors (row-major 3 x 3 blocks)."""
    for i in range(n):
        for q in range(9):
            dmat[i, q] = 0.0
            emat[i, q] = 0.0
        # mass, a contact's stiffness and damping along its normal n (kap n n^T) and a stuck
        # segment's anchor along the tangent t = (-n_y, n_x) (kat t t^T)
        nx, ny = knx[i], kny[i]
        dmat[i, 0] = m[i] + kap[i] * nx * nx + kat[i] * ny * ny
        dmat[i, 1] = dmat[i, 3] = (kap[i] - kat[i]) * nx * ny
        dmat[i, 4] = m[i] + kap[i] * ny * ny + kat[i] * nx * nx
        dmat[i, 8] = inertia[i] + geo[i]
    for j in range(n):
        k = j - 1 if j > 0 else n - 1
        i = j
        ax = hl * c[k]
        ay = hl * s[k]
        bx = hl * c[i]
        by = hl * s[i]
        sg = sig[j]
        g = gam[j]
        # gap velocity = P_(-b) u_i - P_a u_k, P_r = [[1, 0, -r_y], [0, 1, r_x]]
        # D_k += sg P_a^T P_a
        dmat[k, 0] += sg
        dmat[k, 2] -= sg * ay
        dmat[k, 4] += sg
        dmat[k, 5] += sg * ax
        dmat[k, 6] -= sg * ay
        dmat[k, 7] += sg * ax
        dmat[k, 8] += sg * hl * hl + g
        # D_i += sg P_(-b)^T P_(-b)
        dmat[i, 0] += sg
        dmat[i, 2] += sg * by
        dmat[i, 4] += sg
        dmat[i, 5] -= sg * bx
        dmat[i, 6] += sg * by
        dmat[i, 7] -= sg * bx
        dmat[i, 8] += sg * hl * hl + g
        # block (k, i) = -sg P_a^T P_(-b), bending -g on (phi_k, phi_i)
        omat[j, 0] = -sg
        omat[j, 1] = 0.0
        omat[j, 2] = -sg * by
        omat[j, 3] = 0.0
        omat[j, 4] = -sg
        omat[j, 5] = sg * bx
        omat[j, 6] = sg * ay
        omat[j, 7] = -sg * ax
        omat[j, 8] = sg * (ay * by + ax * bx) - g
    # border column: block (0, n-1) is the transpose of block (n-1, 0) = omat[0]; block (n-2, n-1) = omat[n-1]
    for r in range(3):
        for q in range(3):
            emat[0, 3 * r + q] += omat[0, 3 * q + r]
            emat[n - 2, 3 * r + q] += omat[n - 1, 3 * r + q]
    last = n - 1
    for i in range(n - 1):
        _sym_inverse(dmat, i, dinv, i)
        _mul(dinv, i, emat, i, xmat, i)
        _sub_tmul(emat, i, xmat, i, dmat, last)
        if i < n - 2:
            _mul(dinv, i, omat, i + 1, ymat, i)
            _sub_tmul(omat, i + 1, ymat, i, dmat, i + 1)
            _sub_tmul(omat, i + 1, xmat, i, emat, i + 1)
    _sym_inverse(dmat, last, dinv, last)


@njit(cache=True, inline="always")
def solve(n, fx, fy, mz, dinv, ymat, xmat, r):
    """Overwrite (fx, fy, mz) with u = A^-1 (fx, fy, mz) from the factors; r: (n, 3) scratch."""
    for i in range(n):
        r[i, 0] = fx[i]
        r[i, 1] = fy[i]
        r[i, 2] = mz[i]
    l0 = r[n - 1, 0]
    l1 = r[n - 1, 1]
    l2 = r[n - 1, 2]
    r0 = r[0, 0]
    r1 = r[0, 1]
    r2 = r[0, 2]
    for i in range(n - 1):
        # the last row collects x^T r_i; the next row y^T r_i
        l0 -= xmat[i, 0] * r0 + xmat[i, 3] * r1 + xmat[i, 6] * r2
        l1 -= xmat[i, 1] * r0 + xmat[i, 4] * r1 + xmat[i, 7] * r2
        l2 -= xmat[i, 2] * r0 + xmat[i, 5] * r1 + xmat[i, 8] * r2
        if i < n - 2:
            q0 = r[i + 1, 0] - (ymat[i, 0] * r0 + ymat[i, 3] * r1 + ymat[i, 6] * r2)
            q1 = r[i + 1, 1] - (ymat[i, 1] * r0 + ymat[i, 4] * r1 + ymat[i, 7] * r2)
            q2 = r[i + 1, 2] - (ymat[i, 2] * r0 + ymat[i, 5] * r1 + ymat[i, 8] * r2)
            r[i + 1, 0] = q0
            r[i + 1, 1] = q1
            r[i + 1, 2] = q2
            r0 = q0
            r1 = q1
            r2 = q2
    d = dinv[n - 1]
    z0 = d[0] * l0 + d[1] * l1 + d[2] * l2
    z1 = d[3] * l0 + d[4] * l1 + d[5] * l2
    z2 = d[6] * l0 + d[7] * l1 + d[8] * l2
    fx[n - 1] = z0
    fy[n - 1] = z1
    mz[n - 1] = z2
    u0 = z0
    u1 = z1
    u2 = z2
    for i in range(n - 2, -1, -1):
        a0 = r[i, 0]
        a1 = r[i, 1]
        a2 = r[i, 2]
        v0 = dinv[i, 0] * a0 + dinv[i, 1] * a1 + dinv[i, 2] * a2 - (xmat[i, 0] * z0 + xmat[i, 1] * z1 + xmat[i, 2] * z2)
        v1 = dinv[i, 3] * a0 + dinv[i, 4] * a1 + dinv[i, 5] * a2 - (xmat[i, 3] * z0 + xmat[i, 4] * z1 + xmat[i, 5] * z2)
        v2 = dinv[i, 6] * a0 + dinv[i, 7] * a1 + dinv[i, 8] * a2 - (xmat[i, 6] * z0 + xmat[i, 7] * z1 + xmat[i, 8] * z2)
        if i < n - 2:
            v0 -= ymat[i, 0] * u0 + ymat[i, 1] * u1 + ymat[i, 2] * u2
            v1 -= ymat[i, 3] * u0 + ymat[i, 4] * u1 + ymat[i, 5] * u2
            v2 -= ymat[i, 6] * u0 + ymat[i, 7] * u1 + ymat[i, 8] * u2
        fx[i] = v0
        fy[i] = v1
        mz[i] = v2
        u0 = v0
        u1 = v1
        u2 = v2


def dense(n, hl, c, s, m, inertia, sig, gam, geo, kap, kat, knx, kny):
    """A as a dense (3n, 3n) matrix (tests: the factor against numpy)."""
    A = np.zeros((3 * n, 3 * n))
    for i in range(n):
        A[3 * i, 3 * i] = A[3 * i + 1, 3 * i + 1] = m[i]
        A[3 * i + 2, 3 * i + 2] = inertia[i] + geo[i]
        nv = np.array([knx[i], kny[i]])
        tv = np.array([-kny[i], knx[i]])
        A[3 * i:3 * i + 2, 3 * i:3 * i + 2] += kap[i] * np.outer(nv, nv) + kat[i] * np.outer(tv, tv)
    for j in range(n):
        k = j - 1 if j > 0 else n - 1
        G = np.zeros((2, 3 * n))
        ax, ay, bx, by = hl * c[k], hl * s[k], hl * c[j], hl * s[j]
        G[:, 3 * k:3 * k + 3] = -np.array([[1, 0, -ay], [0, 1, ax]])
        G[:, 3 * j:3 * j + 3] = np.array([[1, 0, by], [0, 1, -bx]])
        A += sig[j] * G.T @ G
        e = np.zeros(3 * n)
        e[3 * k + 2], e[3 * j + 2] = -1.0, 1.0
        A += gam[j] * np.outer(e, e)
    return A
