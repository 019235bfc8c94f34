"""Model -> plain arrays for the kernels (the only place that knows both worlds)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _kernels as K
from .initial import InitialState, initial_state
from .layout import Layout, compute_layout


@dataclass
class BeltSystem:
    model: object
    layout: Layout
    init: InitialState
    ip: np.ndarray
    fp: np.ndarray
    seg: dict          # per-segment arrays: m, inertia, mu, kax, bax, kb, bb, c1, c2, bc
    pul: dict          # per-pulley arrays: pcx, pcy, pr, pinv_i, pmode, pinertia + excitation tables
    span_mid: np.ndarray
    track: np.ndarray
    step: float        # time step (s) of the semi-implicit scheme
    step_limit: float  # stability estimate 2 / omega_max (s)

    @property
    def n(self):
        return int(self.ip[K.I_N])


def _offsets(tables):
    off = np.zeros(len(tables) + 1, dtype=np.int64)
    xs, ys = [], []
    for j, rows in enumerate(tables):
        rows = rows or []
        off[j + 1] = off[j] + len(rows)
        xs += [r[0] for r in rows]
        ys += [r[1] for r in rows]
    return off, np.array(xs, float), np.array(ys, float)


def build(model) -> BeltSystem:
    layout = compute_layout(model)
    init = initial_state(model, layout)
    belt, n, nk = model.belt, model.belt.segments, len(model.pulleys)
    l = init.seg_length
    e = belt.axial_exponent
    ones = np.ones(n)
    m = belt.mass_per_length * l * ones
    seg = dict(
        m=m,
        inertia=m * l * l / 12.0,                                    # eq. 2
        mu=model.friction.coefficient * ones,
        kax=belt.axial_stiffness / l ** e * ones,                     # F = EA (g / l)^e
        bax=belt.axial_damping / l * ones,
        kb=belt.bending_stiffness / l * ones,
        bb=belt.bending_damping / l * ones,
        c1=model.contact.stiffness_quadratic * l * ones,
        c2=model.contact.stiffness_linear * l * ones,
        bc=model.contact.damping * l * ones,
    )
    # friction zones by arc length of the segment centre measured from the start of segment 0
    s_mid = (np.arange(n) + 0.5) * (l * (1 + (init.tension / belt.axial_stiffness) ** (1 / e)))
    for zone in model.friction.zones:
        seg["mu"][(s_mid >= zone.start) & (s_mid < zone.end)] = zone.coefficient

    P = model.pulleys
    tt_off, tt_x, tt_y = _offsets([p.torque_time for p in P])
    ts_off, ts_x, ts_y = _offsets([p.torque_speed for p in P])
    sp_off, sp_x, sp_y = _offsets([p.speed_time for p in P])
    hm_off = np.zeros(nk + 1, dtype=np.int64)
    for j, p in enumerate(P):
        hm_off[j + 1] = hm_off[j] + len(p.harmonics)
    hs = [hh for p in P for hh in p.harmonics]
    pul = dict(
        pcx=np.array([p.center[0] for p in P]), pcy=np.array([p.center[1] for p in P]),
        pr=np.array([p.radius for p in P]),
        pinertia=np.array([p.inertia for p in P]), pinv_i=np.array([1.0 / p.inertia for p in P]),
        pmode=np.array([1 if p.speed_time is not None else 0 for p in P], dtype=np.int64),
        tq_const=np.array([p.torque for p in P]), tq_visc=np.array([p.viscous_torque for p in P]),
        tt_off=tt_off, tt_x=tt_x, tt_y=tt_y, ts_off=ts_off, ts_x=ts_x, ts_y=ts_y,
        hm_off=hm_off, hm_order=np.array([hh.order for hh in hs], float),
        hm_amp=np.array([hh.amplitude for hh in hs], float), hm_phase=np.array([hh.phase for hh in hs], float),
        sp_off=sp_off, sp_x=sp_x, sp_y=sp_y,
    )
    span_mid = np.array([sp.midpoint for sp in layout.spans])
    track = np.array(model.output.segments, dtype=np.int64)
    ip = np.zeros(7, dtype=np.int64)
    ip[K.I_N], ip[K.I_NK] = n, nk
    ip[K.I_LAW] = 0 if model.friction.law == "threlfall" else 1
    ip[K.I_NSPAN], ip[K.I_NTRACK] = len(layout.spans), len(track)
    ip[K.I_LINEAR] = 1 if e == 1.0 else 0
    fp = np.zeros(8)
    fp[K.F_EAX], fp[K.F_EB] = e, belt.bending_exponent
    fp[K.F_PMAX], fp[K.F_DV], fp[K.F_DMAX] = model.contact.damping_depth, model.friction.velocity_threshold, model.friction.displacement_limit
    fp[K.F_G], fp[K.F_TURN], fp[K.F_HL] = model.gravity, init.turn, 0.5 * l

    limit = stability_limit(model, init, seg)
    step = model.simulation.step if model.simulation.step is not None else 0.85 * limit
    return BeltSystem(model, layout, init, ip, fp, seg, pul, span_mid, track, step, limit)


def stability_limit(model, init, seg) -> float:
    """Largest stable step of the explicit part: 2/omega for the stiffest chain mode.

    The zero-length joint spring is isotropic, so a segment's rotation is held by stiffness k at
    both ends: the alternating rotation mode has omega^2 = 12 k / m; the axial zig-zag mode
    omega^2 = 4 k / m with damping rate 4 b / m (symplectic Euler with damping:
    h < 2/omega (sqrt(1 + zeta^2) - zeta)).
    """
    e = model.belt.axial_exponent
    m = float(seg["m"][0])
    k = float(seg["kax"][0])
    if e != 1.0:  # tangent stiffness at the pretension
        g = init.seg_length * (init.tension / model.belt.axial_stiffness) ** (1 / e)
        k = e * k * g ** (e - 1)
    kb = float(seg["kb"][0]) * max(model.belt.bending_exponent, 1.0)
    w_rot = math.sqrt(12 * (k + 4 * kb / init.seg_length ** 2) / m)
    w_ax = math.sqrt(4 * k / m)
    zeta = 4 * float(seg["bax"][0]) / m / (2 * w_ax)
    h_ax = 2 / w_ax * (math.sqrt(1 + zeta ** 2) - zeta)
    # contact normal stiffness at twice the static penetration (explicit part)
    p = 2 * float(np.max(init.penetration))
    kc = 2 * float(seg["c1"][0]) * p + float(seg["c2"][0])
    h_c = 2 / math.sqrt(kc / m)
    return min(2 / w_rot, h_ax, h_c)
