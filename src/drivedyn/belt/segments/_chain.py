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
limits the turn per step (system.TURN_PER_STEP).

A is symmetric positive definite; segment i couples to i-1 and i+1 through joints i and i+1,
and joint 0 closes the loop (n-1, 0). It is factored by block Gaussian elimination with the last
segment as the border (3 x 3 blocks; fill-in only in the border column), stored as

    dinv[i] = (reduced diagonal block i)^-1,  ymat[i] = dinv[i] O[i+1],  xmat[i] = dinv[i] E[i],

O[i+1] the block (i, i+1), E[i] the border block (i, n-1). The solve is then a forward and a
back sweep of 45 multiply-adds per segment.
"""
import numpy as np
from numba import njit


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
    _eliminate(n, dmat, omat, emat, dinv, ymat, xmat)


@njit(cache=True, inline="always")
def _eliminate(n, dmat, omat, emat, dinv, ymat, xmat):
    """The block elimination of ``factor``, its running blocks in scalars: row i's reduced diagonal
    D (symmetric), its border block E and the last row's diagonal L (symmetric), so that each row
    reads its assembled blocks once and writes its three factors once (the whole factorisation,
    333 segments: 75 ns per segment, against 96 with 3 x 3 helpers working in the arrays)."""
    last = n - 1
    d00, d01, d02, d11, d12, d22 = dmat[0, 0], dmat[0, 1], dmat[0, 2], dmat[0, 4], dmat[0, 5], dmat[0, 8]
    e00, e01, e02, e10, e11, e12, e20, e21, e22 = (emat[0, 0], emat[0, 1], emat[0, 2], emat[0, 3], emat[0, 4],
                                                   emat[0, 5], emat[0, 6], emat[0, 7], emat[0, 8])
    l00, l01, l02, l11, l12, l22 = (dmat[last, 0], dmat[last, 1], dmat[last, 2], dmat[last, 4], dmat[last, 5],
                                    dmat[last, 8])
    for i in range(n - 1):
        # P = D^-1 (symmetric), by cofactors
        c00 = d11 * d22 - d12 * d12
        c01 = d02 * d12 - d01 * d22
        c02 = d01 * d12 - d02 * d11
        inv = 1.0 / (d00 * c00 + d01 * c01 + d02 * c02)
        p00 = c00 * inv
        p01 = c01 * inv
        p02 = c02 * inv
        p11 = (d00 * d22 - d02 * d02) * inv
        p12 = (d01 * d02 - d00 * d12) * inv
        p22 = (d00 * d11 - d01 * d01) * inv
        dinv[i, 0] = p00
        dinv[i, 1] = p01
        dinv[i, 2] = p02
        dinv[i, 3] = p01
        dinv[i, 4] = p11
        dinv[i, 5] = p12
        dinv[i, 6] = p02
        dinv[i, 7] = p12
        dinv[i, 8] = p22
        # X = P E
        x00 = p00 * e00 + p01 * e10 + p02 * e20
        x01 = p00 * e01 + p01 * e11 + p02 * e21
        x02 = p00 * e02 + p01 * e12 + p02 * e22
        x10 = p01 * e00 + p11 * e10 + p12 * e20
        x11 = p01 * e01 + p11 * e11 + p12 * e21
        x12 = p01 * e02 + p11 * e12 + p12 * e22
        x20 = p02 * e00 + p12 * e10 + p22 * e20
        x21 = p02 * e01 + p12 * e11 + p22 * e21
        x22 = p02 * e02 + p12 * e12 + p22 * e22
        xmat[i, 0] = x00
        xmat[i, 1] = x01
        xmat[i, 2] = x02
        xmat[i, 3] = x10
        xmat[i, 4] = x11
        xmat[i, 5] = x12
        xmat[i, 6] = x20
        xmat[i, 7] = x21
        xmat[i, 8] = x22
        # L -= E^T X (symmetric)
        l00 -= e00 * x00 + e10 * x10 + e20 * x20
        l01 -= e00 * x01 + e10 * x11 + e20 * x21
        l02 -= e00 * x02 + e10 * x12 + e20 * x22
        l11 -= e01 * x01 + e11 * x11 + e21 * x21
        l12 -= e01 * x02 + e11 * x12 + e21 * x22
        l22 -= e02 * x02 + e12 * x12 + e22 * x22
        if i < n - 2:
            j = i + 1
            o00, o01, o02, o10, o11, o12, o20, o21, o22 = (omat[j, 0], omat[j, 1], omat[j, 2], omat[j, 3], omat[j, 4],
                                                           omat[j, 5], omat[j, 6], omat[j, 7], omat[j, 8])
            # Y = P O
            y00 = p00 * o00 + p01 * o10 + p02 * o20
            y01 = p00 * o01 + p01 * o11 + p02 * o21
            y02 = p00 * o02 + p01 * o12 + p02 * o22
            y10 = p01 * o00 + p11 * o10 + p12 * o20
            y11 = p01 * o01 + p11 * o11 + p12 * o21
            y12 = p01 * o02 + p11 * o12 + p12 * o22
            y20 = p02 * o00 + p12 * o10 + p22 * o20
            y21 = p02 * o01 + p12 * o11 + p22 * o21
            y22 = p02 * o02 + p12 * o12 + p22 * o22
            ymat[i, 0] = y00
            ymat[i, 1] = y01
            ymat[i, 2] = y02
            ymat[i, 3] = y10
            ymat[i, 4] = y11
            ymat[i, 5] = y12
            ymat[i, 6] = y20
            ymat[i, 7] = y21
            ymat[i, 8] = y22
            # the next row: D = D_j - O^T Y (symmetric), E = E_j - O^T X (E no longer needed)
            d00 = dmat[j, 0] - (o00 * y00 + o10 * y10 + o20 * y20)
            d01 = dmat[j, 1] - (o00 * y01 + o10 * y11 + o20 * y21)
            d02 = dmat[j, 2] - (o00 * y02 + o10 * y12 + o20 * y22)
            d11 = dmat[j, 4] - (o01 * y01 + o11 * y11 + o21 * y21)
            d12 = dmat[j, 5] - (o01 * y02 + o11 * y12 + o21 * y22)
            d22 = dmat[j, 8] - (o02 * y02 + o12 * y12 + o22 * y22)
            e00 = emat[j, 0] - (o00 * x00 + o10 * x10 + o20 * x20)
            e01 = emat[j, 1] - (o00 * x01 + o10 * x11 + o20 * x21)
            e02 = emat[j, 2] - (o00 * x02 + o10 * x12 + o20 * x22)
            e10 = emat[j, 3] - (o01 * x00 + o11 * x10 + o21 * x20)
            e11 = emat[j, 4] - (o01 * x01 + o11 * x11 + o21 * x21)
            e12 = emat[j, 5] - (o01 * x02 + o11 * x12 + o21 * x22)
            e20 = emat[j, 6] - (o02 * x00 + o12 * x10 + o22 * x20)
            e21 = emat[j, 7] - (o02 * x01 + o12 * x11 + o22 * x21)
            e22 = emat[j, 8] - (o02 * x02 + o12 * x12 + o22 * x22)
    c00 = l11 * l22 - l12 * l12
    c01 = l02 * l12 - l01 * l22
    c02 = l01 * l12 - l02 * l11
    inv = 1.0 / (l00 * c00 + l01 * c01 + l02 * c02)
    dinv[last, 0] = c00 * inv
    dinv[last, 1] = c01 * inv
    dinv[last, 2] = c02 * inv
    dinv[last, 3] = c01 * inv
    dinv[last, 4] = (l00 * l22 - l02 * l02) * inv
    dinv[last, 5] = (l01 * l02 - l00 * l12) * inv
    dinv[last, 6] = c02 * inv
    dinv[last, 7] = (l01 * l02 - l00 * l12) * inv
    dinv[last, 8] = (l00 * l11 - l01 * l01) * inv


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
