"""The joint-force kernel against a plain NumPy transcription of the seed's eqs. 18-21, and the
balance laws any internal force system must satisfy (zero net force and net moment)."""
import numpy as np
import pytest

import drivedyn
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.segments.state import new_state, new_work
from drivedyn.belt.segments.system import build


def reference_joint_forces(x, y, phi, vx, vy, w, l, k, b, kb, bb, turn):
    """Eqs. 18-21 for linear elements, written directly: gap vector from the end of segment i-1
    to the start of segment i; force c_L |d| + b_L d|d|/dt along d; bending c_B (phi_i - phi_i-1)."""
    n = len(x)
    e = np.stack([np.cos(phi), np.sin(phi)], 1)
    P = np.stack([x, y], 1)
    V = np.stack([vx, vy], 1)
    perp = np.stack([-e[:, 1], e[:, 0]], 1)
    end_plus, end_minus = P + l / 2 * e, P - l / 2 * e
    v_plus = V + (w * l / 2)[:, None] * perp
    v_minus = V - (w * l / 2)[:, None] * perp
    F = np.zeros((n, 2))
    M = np.zeros(n)
    for i in range(n):
        km = i - 1
        d = end_minus[i] - end_plus[km]
        dv = v_minus[i] - v_plus[km]
        L = np.linalg.norm(d)
        f = (k * L + b * (d @ dv) / L) * d / L          # on segment i-1, toward i
        arm_k, arm_i = l / 2 * e[km], -l / 2 * e[i]
        F[km] += f
        F[i] -= f
        M[km] += arm_k[0] * f[1] - arm_k[1] * f[0]
        M[i] += arm_i[0] * (-f[1]) - arm_i[1] * (-f[0])
        dphi = phi[i] - phi[km] + (turn if i == 0 else 0.0)
        Mb = kb * dphi + bb * (w[i] - w[km])
        M[i] -= Mb
        M[km] += Mb
    return F, M


@pytest.fixture(scope="module")
def perturbed():
    m = drivedyn.load(drivedyn.example_path("belt-5pk"))
    m = drivedyn.replace(m, {"belt.segments": 60, "output.segments": [0], "belt.bending_damping": 1e-6})
    S = build(m)
    rng = np.random.default_rng(7)
    n = S.n
    x = S.init.x + rng.normal(0, 2e-5, n)
    y = S.init.y + rng.normal(0, 2e-5, n)
    phi = S.init.phi + rng.normal(0, 1e-3, n)
    vx, vy, w = rng.normal(0, 0.5, n), rng.normal(0, 0.5, n), rng.normal(0, 20, n)
    return S, x, y, phi, vx, vy, w


def kernel(S, x, y, phi, vx, vy, w):
    st = new_state(S, x, y, phi)
    st = st._replace(vx=vx, vy=vy, w=w)
    W = new_work(S)
    K.joint_forces(S.belt, st, W, 0.0)
    return W.fx, W.fy, W.mz


def test_joint_forces_match_the_equations(perturbed):
    S, x, y, phi, vx, vy, w = perturbed
    fx, fy, mz = kernel(S, x, y, phi, vx, vy, w)
    B = S.belt
    F, M = reference_joint_forces(x, y, phi, vx, vy, w, S.init.seg_length, B.kax[0], B.bax[0],
                                  B.kb[0], B.bb[0], S.init.turn)
    scale = np.max(np.abs(F))
    np.testing.assert_allclose(fx, F[:, 0], atol=1e-9 * scale)
    np.testing.assert_allclose(fy, F[:, 1], atol=1e-9 * scale)
    np.testing.assert_allclose(mz, M, atol=1e-9 * scale * S.init.seg_length)


def test_internal_forces_have_no_resultant(perturbed):
    """Action and reaction: the belt's own forces sum to zero and have no moment (angular momentum)."""
    S, x, y, phi, vx, vy, w = perturbed
    fx, fy, mz = kernel(S, x, y, phi, vx, vy, w)
    scale = np.max(np.abs(fx))
    assert abs(fx.sum()) < 1e-9 * scale and abs(fy.sum()) < 1e-9 * scale
    assert abs(np.sum(x * fy - y * fx + mz)) < 1e-9 * scale * 0.5
