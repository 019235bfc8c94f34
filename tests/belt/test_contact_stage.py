"""The semi-implicit scheme's contact stage (``_kernels._contacts_semi``, written in passes so that
it vectorises) against the contact and friction laws applied segment by segment in plain Python:
every segment's new velocity and position, normal and friction force, penetration and bristle
state, each pulley's belt torque and hub force, and the contact damping's and friction's power."""
import math

import numpy as np
import pytest
from numba import njit

import drivedyn
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.segments.state import new_state, new_work
from drivedyn.belt.segments.system import build


@njit(error_model="numpy")
def _stage(h, hg, hvb, hm, hi, W, Ct, S, pr, sj, sq, tq, hx, hy):
    return K._contacts_semi(S.x.shape[0], pr.shape[0], h, hg, hvb, hm, hi, W.fx, W.fy, W.mz, Ct, S, pr, W.cand_j,
                            W.cand_skip, W.seg_n, W.seg_t, W.seg_p, sj, sq, tq, hx, hy)


def _reference(h, g, hm, hi, W, Ct, S, P):
    """The stage, one segment at a time: the pulley whose circle holds the segment's centre, the
    normal force of eqs. 9-10 implicit in its damping (``normal_force``), friction implicit in the
    slip (elastic-plastic: T = K z clipped at mu N; Threlfall: ``friction``), then the move."""
    n, nk = S.x.shape[0], P.r.shape[0]
    out = {k: np.zeros(n) for k in ("vx", "vy", "x", "y", "w", "phi", "N", "T", "p", "z")}
    tq, hx, hy = np.zeros(nk), np.zeros(nk), np.zeros(nk)
    pcd = pfr = 0.0
    for i in range(n):
        vxs = S.vx[i] + hm[i] * W.fx[i]
        vys = S.vy[i] + hm[i] * W.fy[i] - h * g
        z = S.z[i]
        N = T = p = 0.0
        hit = [j for j in range(nk) if (S.x[i] - S.cx[j]) ** 2 + (S.y[i] - S.cy[j]) ** 2 < P.r[j] ** 2]
        if hit:
            j = hit[0]
            rx, ry = S.x[i] - S.cx[j], S.y[i] - S.cy[j]
            dist = math.hypot(rx, ry)
            nx, ny = rx / dist, ry / dist
            p = P.r[j] - dist
            rvx, rvy = vxs - S.cvx[j], vys - S.cvy[j]
            vn = rvx * nx + rvy * ny
            Nf, db = K.normal_force(Ct.c1[i], Ct.c2[i], Ct.bc[i], Ct.pmax, p, vn, hm[i])
            if Nf <= 0.0:
                pcd += (Ct.c1[i] * p * p + Ct.c2[i] * p) * max(vn, 0.0)
            else:
                N = Nf
                pcd += db * (vn + hm[i] * N) ** 2
                arm = dist if Ct.centre else P.r[j]
                ws = S.om[j] * arm - (-rvx * ny + rvy * nx)
                if Ct.law == K.LAW_ELASTIC_PLASTIC:
                    muN = Ct.mu[i] * N
                    k = muN / Ct.dmax
                    z = (z + h * ws) / (1.0 + h * hm[i] * k)
                    T = k * z
                    if abs(T) > muN:
                        T, z = math.copysign(muN, T), math.copysign(Ct.dmax, T)
                    sl = ws - hm[i] * T
                else:
                    zz = np.array([z])
                    T, sl = K.friction(Ct.mu[i], Ct.law, Ct.dv, Ct.dmax, N, ws, hm[i], h, zz, 0)
                pfr += T * sl
                fcx, fcy = N * nx - T * ny, N * ny + T * nx
                vxs += hm[i] * fcx
                vys += hm[i] * fcy
                tq[j] -= arm * T
                hx[j] -= fcx
                hy[j] -= fcy
        else:
            z = 0.0
        w = S.w[i] + hi[i] * W.mz[i]
        out["vx"][i], out["vy"][i], out["w"][i] = vxs, vys, w
        out["x"][i], out["y"][i], out["phi"][i] = S.x[i] + h * vxs, S.y[i] + h * vys, S.phi[i] + h * w
        out["N"][i], out["T"][i], out["p"][i], out["z"][i] = N, T, p, z
    return out, tq, hx, hy, pcd, pfr


@pytest.mark.parametrize("law", ["elastic-plastic", "threlfall"])
def test_contact_stage_matches_the_laws_segment_by_segment(law):
    # fead-runup's drive (six pulleys, a tensioner moving its pulley) after 4000 steps from rest,
    # its joint forces and pulley speeds disturbed: segments on and off the pulleys, sticking and
    # sliding, some leaving
    # (the state from a run under the elastic-plastic law, the stage under the law tested: the
    # semi-implicit scheme is not stable at this step under Threlfall's stiff viscous slope)
    base = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")),
                            {"belt.segments": 150, "simulation.method": "semi-implicit"})
    sysm = build(drivedyn.replace(base, {"friction.law": "elastic-plastic"}))
    B, Ct, P, A = sysm.groups
    S, h = new_state(sysm), 5e-6
    W = new_work(sysm, S)
    K.step_chunk(4000, 0.0, h, B, Ct, P, A, S, W)
    Ct = build(drivedyn.replace(base, {"friction.law": law})).groups[1]
    n, nk = B.n, P.nk
    rng = np.random.default_rng(1)
    W.fx[:] *= rng.uniform(0.9, 1.1, n)          # the last step's joint forces, disturbed
    W.fy[:] *= rng.uniform(0.9, 1.1, n)
    W.mz[:] *= rng.uniform(0.9, 1.1, n)
    S.om[:] += rng.normal(0.0, 20.0, nk)
    S.z[:] = rng.uniform(-1.5, 1.5, n) * Ct.dmax
    # every third segment on a pulley leaves it at 0.5 m/s (the contact then holds no force)
    for i in np.flatnonzero(W.seg_n > 0.0)[::3]:
        j = int(np.argmin(np.hypot(S.x[i] - S.cx, S.y[i] - S.cy) - P.r))
        rx, ry = S.x[i] - S.cx[j], S.y[i] - S.cy[j]
        S.vx[i] += 0.5 * rx / math.hypot(rx, ry)
        S.vy[i] += 0.5 * ry / math.hypot(rx, ry)
    W.cand_j[:] = -1                             # every segment tested against every pulley
    W.cand_skip[:] = 0
    hm, hi = h * B.inv_m, h / (B.inertia * B.iscale)
    ref, tq, hx, hy, pcd, pfr = _reference(h, B.g, hm, hi, W, Ct, S, P)
    on = ref["N"] > 0.0
    assert 10 < np.count_nonzero(on) < np.count_nonzero(ref["p"] > 0.0) < n
    if law == "elastic-plastic":            # both sliding (at the bound) and sticking segments
        held = np.abs(ref["z"][on]) == Ct.dmax
        assert 0 < np.count_nonzero(held) < np.count_nonzero(on)
    sj, sq = np.zeros(n, dtype=np.int64), np.zeros((K.NQ, n))
    tq_, hx_, hy_ = np.zeros(nk), np.zeros(nk), np.zeros(nk)
    phi0 = S.phi.copy()
    pcd_, pfr_ = _stage(h, h * B.g, 1.0, hm, hi, W, Ct, S, P.r, sj, sq, tq_, hx_, hy_)
    got = {"vx": S.vx, "vy": S.vy, "x": S.x, "y": S.y, "w": S.w, "phi": S.phi, "N": W.seg_n, "T": W.seg_t,
           "p": W.seg_p, "z": S.z}
    for k, v in ref.items():
        scale = max(np.max(np.abs(v)), 1e-12)
        np.testing.assert_allclose(got[k], v, rtol=0, atol=1e-10 * scale, err_msg=k)
    # the turn keeps (cos, sin) on the unit circle at the new angle
    np.testing.assert_allclose(S.c, np.cos(phi0 + h * ref["w"]), atol=1e-12)
    np.testing.assert_allclose(S.s, np.sin(phi0 + h * ref["w"]), atol=1e-12)
    scale = max(np.max(np.abs(hx)), np.max(np.abs(hy)))
    np.testing.assert_allclose(hx_, hx, atol=1e-10 * scale)
    np.testing.assert_allclose(hy_, hy, atol=1e-10 * scale)
    np.testing.assert_allclose(tq_, tq, atol=1e-10 * np.max(np.abs(tq)))
    assert pcd_ == pytest.approx(pcd, rel=1e-9) and pfr_ == pytest.approx(pfr, rel=1e-9)
