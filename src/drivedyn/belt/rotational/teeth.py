"""A synchronous belt in the rotational model: each grooved wrap as a quasi-static tooth chain.

The belt's teeth hold it in the grooves, so the belt passes each grooved pulley at the grooves' rate,
one belt pitch p0 (unstretched) per groove: no creep and no slip, the mean speed ratio is the tooth
ratio by construction. Between the wrap's tangent points the belt is the shear-lag chain of
mechanics/teeth/loadshare.py without play or land friction (the linear case, Gerbert's): the n teeth
in mesh (loadshare.teeth_in_mesh) are springs k_t between the tension member (EA, one pitch p0
between teeth) and their grooves (the pitch p_g = 2 pi r / z apart), its teeth unloaded at the rest
tension (the belt's pitch at rest against the grooves', within the teeth's play, taken by the play);
the end pieces from the tangent points to the first and last tooth are free belt. Massless, it answers the two span tensions at its ends at once: its ends move by

    x_first = ga dT_in + gb dT_out,    x_last = gc dT_in + gd dT_out

(the linear chain's inverse stiffness, with the end pieces' stretch), which lets belt into or out of
the spans (the kernel solves it with the spans' tensions, as the friction belt's cells:
_kernels._cells_couple), and its tooth loads follow from the same solution. What it leaves out
against the segment model (segments/_teeth.py): the teeth's play (a dead band there), their
damping, entry impact and the polygon of the teeth passing; a tooth cannot climb or jump here: the
climb criterion (loadshare eq. 3) is read as a margin from the chain's loads.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...mechanics.teeth.loadshare import teeth_in_mesh


@dataclass(frozen=True)
class Wrap:
    """One grooved wrap's chain (SI)."""

    pulley: int
    z: int                  # grooves
    n: int                  # teeth in mesh
    radius: float
    groove_pitch: float     # p_g = 2 pi r / z
    belt_pitch: float       # p0, unstretched
    end: float              # free belt from a tangent point to the first / last tooth (m)
    X: np.ndarray           # (n, 2): tooth displacements per unit (T_in - Te), (T_out - Te)
    Te: float               # the tension at which the teeth sit unloaded: the rest tension
    k: float                # tooth stiffness
    kc: float               # EA / p0

    def displacements(self, t_in, t_out):
        """(samples, n) belt displacements at the teeth relative to their grooves (belt order positive)."""
        return np.stack([np.asarray(t_in) - self.Te, np.asarray(t_out) - self.Te], axis=-1) @ self.X.T


def chain_energy(ga, gb, gc, gd, T0, t_in, t_out):
    """Energy of a tooth chain (J) held at end tensions t_in, t_out, counted from the rest state (both
    ends at T0): the work of its end tensions over the ends' motions (linear: the mean of each end's
    tension at rest and now). Plain Python: the kernel compiles it inline (_kernels.py)."""
    x0 = ga * (t_in - T0) + gb * (t_out - T0)
    x1 = gc * (t_in - T0) + gd * (t_out - T0)
    return 0.5 * ((t_out + T0) * x1 - (t_in + T0) * x0)


def chains(model, lay, L0, bt, T0) -> list[Wrap]:
    """The grooved wraps' chains; ``bt``: geometry.teeth.BeltTeeth, ``L0`` the unstretched belt (m), ``T0``
    the tension at rest, at which the teeth sit unloaded."""
    EA = float(model.belt.axial_stiffness)
    p0 = L0 / bt.count
    out = []
    for j, q in enumerate(model.pulleys):
        if not q.teeth:
            continue
        r = abs(float(lay.rho[j]))
        pg = 2 * math.pi * r / q.teeth
        n = teeth_in_mesh(q.teeth, float(lay.wrap[j]))
        end = max(0.5 * (r * float(lay.wrap[j]) - (n - 1) * pg), 0.0)
        kc = EA / p0
        K = np.diag(np.full(n, bt.stiffness))
        for i in range(n - 1):
            K[i, i] += kc
            K[i + 1, i + 1] += kc
            K[i, i + 1] -= kc
            K[i + 1, i] -= kc
        f = np.zeros((n, 2))
        f[0, 0] = -1.0          # the arriving span pulls the first tooth back
        f[-1, 1] += 1.0         # the leaving span pulls the last forward
        X = np.linalg.solve(K, f)
        out.append(Wrap(j, int(q.teeth), n, r, pg, p0, end, X, float(T0), float(bt.stiffness), kc))
    return out


def kernel_fields(nk, wraps: list[Wrap], EA) -> dict:
    """The Rot record's per-wrap fields of the chains (zeros on the friction wraps)."""
    g = {name: np.zeros(nk) for name in ("ga", "gb", "gc", "gd")}
    grooved, pr = np.zeros(nk, dtype=np.int64), np.ones(nk)
    for w in wraps:
        j = w.pulley
        grooved[j] = 1
        pr[j] = w.belt_pitch / w.groove_pitch
        g["ga"][j] = w.X[0, 0] - w.end / EA
        g["gb"][j] = w.X[0, 1]
        g["gc"][j] = w.X[-1, 0]
        g["gd"][j] = w.X[-1, 1] + w.end / EA
    return dict(grooved=grooved, pr=pr, **g, chain=bool(wraps))


def loads(w: Wrap, t_in, t_out):
    """(tooth loads (samples, n) N, local tension at each tooth (samples, n) N) of the chain between
    span tensions t_in, t_out (arrays over samples)."""
    t_in, t_out = np.atleast_1d(t_in), np.atleast_1d(t_out)
    x = w.displacements(t_in, t_out)
    bars = w.Te + w.kc * np.diff(x, axis=1)
    left = np.concatenate([t_in[:, None], bars], axis=1)
    right = np.concatenate([bars, t_out[:, None]], axis=1)
    return w.k * x, 0.5 * (left + right)


def add_teeth(ds, summary, model, sysm, sel):
    """The chains' tooth loads per sample into the Dataset (the segment model's variables:
    segments/teeth_outputs.py) and summary["teeth"]: per grooved pulley the largest tooth load, where
    and when, the smallest jump margin, the speed ratio against the tooth ratio and the phase error."""
    from ...core.results import variable
    from ..dynamics.phase import phase_error, phase_rows

    lay, wraps, bt = sysm.layout, sysm.wraps, sysm.belt_teeth
    names = list(lay.names)
    T = ds["span_tension"].values
    ns, nk = T.shape[0], len(names)
    zmax = max(w.z for w in wraps)
    load = np.full((ns, len(wraps), zmax), np.nan)
    margin = np.full((ns, len(wraps)), np.nan)
    torque = np.zeros((ns, len(wraps)))
    m = float(model.belt.mass_per_length)
    om = ds["speed"].values
    for a, w in enumerate(wraps):
        j = w.pulley
        Q, Tl = loads(w, T[:, (j - 1) % nk], T[:, j])
        # the teeth's fixed-frame positions: from the arriving tangent point along the wrap
        sense = 1.0 if lay.rho[j] * lay.orientation > 0 else -1.0
        first = (lay.arc_start[j] + sense * w.end / w.radius) % (2 * math.pi)
        slot = (min(int(first / (2 * math.pi) * w.z), w.z - 1) + int(sense) * np.arange(w.n)) % w.z
        load[:, a, slot] = Q
        torque[:, a] = w.radius * Q.sum(axis=1)
        if bt.climb > 0:
            # hold (T - m v^2) p / R: the wrap's pressure on one pitch, less the belt's centrifugal force
            c = m * (om[:, j] * w.radius) ** 2
            with np.errstate(divide="ignore"):
                mg = np.maximum(Tl - c[:, None], 0.0) * w.groove_pitch / w.radius / (bt.climb * np.abs(Q))
            margin[:, a] = mg.min(axis=1)
    tp = [w.pulley for w in wraps]
    ds["tooth_load"] = variable(load, ("time", "toothed_pulley", "groove_slot"), "N",
                                "load of the tooth in mesh at each groove position (the rotational model's quasi-static "
                                "chain between the interval's span tensions; + against the belt running ahead of its groove)")
    ds["jump_margin"] = variable(margin, ("time", "toothed_pulley"), "1",
                                 "smallest hold (T - m v^2) p / R over outward push Q tan(phi - rho) of the teeth in mesh "
                                 "(below 1 a tooth climbs)")
    ds["teeth_in_mesh"] = variable(np.tile([w.n for w in wraps], (ns, 1)), ("time", "toothed_pulley"), "1", "teeth in mesh")
    ds["grooves"] = variable(np.array([w.z for w in wraps], dtype=np.int64), ("toothed_pulley",), "1", "grooves of the pulley")
    ds["tooth_torque"] = variable(torque, ("time", "toothed_pulley"), "N m", "sum of the tooth loads x their radius")
    ds = ds.assign_coords(toothed_pulley=[names[j] for j in tp], groove_slot=np.arange(zmax))
    th = ds["angle"].values
    pe = phase_error(th, tp, [w.z for w in wraps])
    z0 = wraps[0].z
    ds["phase_error"] = variable(pe, ("time", "toothed_pulley"), "deg",
                                 f"angle of the pulley against its tooth ratio to {names[tp[0]]}, in {names[tp[0]]}'s degrees "
                                 "(transmission error; from its value at the start)")
    out = {**bt.summary(), "play": 0.0, "play_source": "the rotational model's chain has no play",
           "model": "rotational chain", "jumps": None}
    for a, w in enumerate(wraps):
        L = load[sel, a]
        absL = np.abs(np.where(np.isfinite(L), L, 0.0))
        peak = float(absL.max()) if absL.size else 0.0
        i, s = np.unravel_index(np.argmax(absL), absL.shape) if peak else (0, 0)
        mm = margin[sel, a]
        out["pulleys"][names[w.pulley]] = {
            "teeth": w.z, "max_tooth_load": peak, "max_tooth_load_angle": float((s + 0.5) * 360.0 / w.z),
            "max_tooth_load_time": float(ds["time"].values[sel][i]) if peak else float("nan"),
            "teeth_in_mesh": float(w.n),
            "jump_margin_min": float(np.nanmin(mm)) if np.isfinite(mm).any() else math.inf,
            "tooth_torque_mean": float(torque[sel, a].mean()) if sel.any() else float("nan")}
    if len(tp) > 1 and ns > 1:
        turn = th[-1, tp[0]] - th[0, tp[0]]
        for w in wraps[1:]:
            if abs(turn) > 0:
                row = out["pulleys"][names[w.pulley]]
                row["speed_ratio"] = float((th[-1, w.pulley] - th[0, w.pulley]) / turn)
                row["tooth_ratio"] = float(z0 / w.z)
    phase_rows(out["pulleys"], [names[j] for j in tp], th[:, tp[0]], pe, sel)
    summary["teeth"] = out
    return ds
