"""What a synchronous belt's run records of its teeth, and its summary: the load on every tooth in
mesh through time (a map per pulley over the groove positions), the margin to a tooth climbing out
(jump), the jumps, the teeth in mesh, and the balance of the tooth loads against the belt torque.

A groove position is the pulley's fixed-frame angle cut into its groove count (slot k covers
[k, k + 1) x 360 / z deg counter-clockwise from +x): a tooth in mesh is counted in the slot of its
groove's centre, so each sample fills the wrap's slots, one tooth each, and leaves the others empty
(NaN)."""
from __future__ import annotations

import math

import numpy as np

from ..dynamics.phase import phase_error, phase_rows


class TeethRecorder:
    """Per sample: tooth loads by slot, the smallest jump margin and the teeth in mesh per pulley, jumps so far."""

    def __init__(self, ns, sysm):
        C = sysm.contact
        self.z = np.asarray(C.gz)
        self.nk = len(self.z)
        zmax = int(self.z.max())
        self.load = np.full((ns, self.nk, zmax), np.nan)
        self.margin = np.full((ns, self.nk), np.nan)
        self.in_mesh = np.zeros((ns, self.nk), dtype=np.int64)
        self.jumps = np.zeros(ns)
        self.climbs = np.zeros(ns)             # tooth-steps at the climb limit so far
        self.first_climb = None
        self.last_jump = np.full((ns, 2), np.nan)
        self.belt_torque = np.zeros((ns, self.nk))     # sum of Q d of the teeth, instantaneous
        self.climb = float(C.tclimb)
        self.teeth = np.flatnonzero(np.asarray(C.tk) > 0)
        self.gphase = np.asarray(C.gphase, dtype=float).copy()
        for j, a in enumerate(np.asarray(C.ccur)):
            if a >= 0:      # a pitch curve's groove phase is an arc (m, segments/_curves.py): as a mean angle
                self.gphase[j] /= C.cper[a]

    def sample(self, k, S, W):
        i = self.teeth
        j = W.tooth_j[i]
        on = j >= 0
        i, j = i[on], j[on]
        q = W.tooth_q[i]
        # the slot of the tooth's groove (its centre th + phase + g 2 pi / z): the tooth's own angle, its
        # groove's +- its deflection, would put two neighbours in one slot and leave a hole beside them
        # where the grooves sit at the slots' edges
        z = self.z[j]
        slot = (np.floor((S.th[j] + self.gphase[j]) * z / (2 * math.pi)).astype(np.int64) + W.tooth_g[i]) % z
        self.load[k, j, slot] = q
        np.add.at(self.in_mesh[k], j, 1)
        d = np.hypot(S.x[i] - S.cx[j], S.y[i] - S.cy[j])
        np.add.at(self.belt_torque[k], j, q * d)
        if self.climb > 0:
            # against the spring's load before the climb limit: below 1 while a tooth climbs
            with np.errstate(divide="ignore"):
                m = W.tooth_hold[i] / (self.climb * np.abs(W.tooth_qs[i]))
            for jj in np.unique(j):
                self.margin[k, jj] = float(np.min(m[j == jj]))
        self.jumps[k] = W.tooth_stat[1]
        self.climbs[k] = W.tooth_stat[4]
        self.first_climb = (float(W.tooth_stat[5]), int(W.tooth_stat[6])) if W.tooth_stat[4] > 0 else None
        self.last_jump[k] = W.tooth_stat[2:4] if W.tooth_stat[1] > 0 else np.nan


def variables(ds, rec: TeethRecorder, ns, sysm):
    """The teeth's variables in the run's Dataset."""
    from ...core.results import variable

    names = list(sysm.layout.names)
    tp = [j for j in range(rec.nk) if rec.z[j] > 0]
    ds["tooth_load"] = variable(rec.load[:ns][:, tp], ("time", "toothed_pulley", "groove_slot"), "N",
                                "load of the tooth in mesh at each groove position (slot k: the pulley's fixed-frame "
                                "angle k x 360 / z deg from +x; + against the belt running ahead of its groove)")
    ds["jump_margin"] = variable(rec.margin[:ns][:, tp], ("time", "toothed_pulley"), "1",
                                 "smallest hold T p / R over outward push Q tan(phi - rho) of the teeth in mesh "
                                 "(below 1 a tooth climbs)")
    ds["teeth_in_mesh"] = variable(rec.in_mesh[:ns][:, tp], ("time", "toothed_pulley"), "1", "teeth in mesh")
    ds["grooves"] = variable(rec.z[tp].astype(np.int64), ("toothed_pulley",), "1", "grooves of the pulley")
    ds["tooth_jumps"] = variable(rec.jumps[:ns], ("time",), "1", "teeth that changed groove so far (jumps)")
    ds["tooth_torque"] = variable(rec.belt_torque[:ns][:, tp], ("time", "toothed_pulley"), "N m",
                                  "sum of the tooth loads x their radius, at the sample")
    ds = ds.assign_coords(toothed_pulley=[names[j] for j in tp], groove_slot=np.arange(rec.load.shape[2]))
    # transmission (phase) error of each grooved pulley against the first (the crank), in the first's degrees
    th = ds["angle"].values
    a = tp[0]
    pe = phase_error(th, tp, rec.z[tp])
    ds["phase_error"] = variable(pe, ("time", "toothed_pulley"), "deg",
                                 f"angle of the pulley against its tooth ratio to {names[a]}, in {names[a]}'s degrees "
                                 "(transmission error; from its value at the start)")
    return ds


def summary(ds, rec: TeethRecorder, sel, sysm, model) -> dict:
    """Per toothed pulley over the steady window: the largest tooth load and where, the mean teeth in
    mesh, the smallest jump margin; the jumps (count, last time and pulley); the speed ratios."""
    from ..geometry.teeth import belt_teeth

    bt = belt_teeth(model, sysm.layout.length)
    names = list(sysm.layout.names)
    out = bt.summary()
    th = ds["angle"].values
    for m, name in enumerate(ds["toothed_pulley"].values.tolist()):
        j = names.index(name)
        L = ds["tooth_load"].values[:, m, :]
        Lw = L[sel]
        peak = float(np.nanmax(np.abs(Lw))) if np.isfinite(Lw).any() else 0.0
        where = np.unravel_index(np.nanargmax(np.abs(np.where(np.isfinite(Lw), Lw, 0.0))), Lw.shape) if peak else (0, 0)
        z = int(rec.z[j])
        margin = ds["jump_margin"].values[sel, m]
        mm = float(np.nanmin(margin)) if np.isfinite(margin).any() else math.inf
        out["pulleys"][name] = {
            "teeth": z, "max_tooth_load": peak,
            "max_tooth_load_angle": float((where[1] + 0.5) * 360.0 / z),
            "max_tooth_load_time": float(ds["time"].values[sel][where[0]]) if peak else float("nan"),
            "teeth_in_mesh": float(ds["teeth_in_mesh"].values[sel, m].mean()),
            "jump_margin_min": mm,
            "tooth_torque_mean": float(ds["tooth_torque"].values[sel, m].mean()),
        }
    # the mean speed ratio of each toothed pulley to the first, against the tooth ratio
    tp = [names.index(n) for n in ds["toothed_pulley"].values.tolist()]
    if len(tp) > 1 and len(th) > 1:
        a = tp[0]
        turn = th[-1, a] - th[0, a]
        for j in tp[1:]:
            if abs(turn) > 0:
                out["pulleys"][names[j]]["speed_ratio"] = float((th[-1, j] - th[0, j]) / turn)
                out["pulleys"][names[j]]["tooth_ratio"] = float(rec.z[a] / rec.z[j])
    # phase error over the steady window: peak to peak and its largest orders of the first pulley's turn
    phase_rows(out["pulleys"], ds["toothed_pulley"].values.tolist(), ds["angle"].values[:, tp[0]] if len(tp) else th[:, 0],
               ds["phase_error"].values, sel)
    jumps = int(ds["tooth_jumps"].values[-1]) if ds.sizes["time"] else 0
    out["jumps"] = jumps
    out["climbing_steps"] = int(rec.climbs[ds.sizes["time"] - 1]) if ds.sizes["time"] else 0
    if rec.first_climb is not None:
        out["first_climb_time"], out["first_climb_pulley"] = rec.first_climb[0], names[rec.first_climb[1]]
    if jumps:
        t_last, j_last = rec.last_jump[ds.sizes["time"] - 1]
        out["last_jump_time"] = float(t_last)
        out["last_jump_pulley"] = names[int(j_last)]
        first = int(np.argmax(ds["tooth_jumps"].values > 0))
        out["first_jump_time"] = float(ds["time"].values[first])
    return out
