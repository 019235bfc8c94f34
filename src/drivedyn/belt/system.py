"""Model -> plain arrays for the kernels (the only place that knows both worlds)."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from . import _kernels as K
from .equilibrium import relax
from .initial import InitialState, initial_state
from ..tables import flatten
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
    span_geo: np.ndarray  # per span: midpoint x, y and unit direction x, y (belt order)
    track: np.ndarray
    step: float        # time step (s) of the semi-implicit scheme
    step_limit: float  # stability estimate 2 / omega_max (s)

    @property
    def n(self):
        return int(self.ip[K.I_N])


def build(model, settle: bool = True) -> BeltSystem:
    """The kernels' arrays for ``model``. ``settle``: start the belt from its static equilibrium
    (equilibrium.relax, 0.2-1.5 s); ``check`` needs only the placement's tension and penetration."""
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
    s_mid = (np.arange(n) + 0.5) * (l + init.gap)
    for zone in model.friction.zones:
        seg["mu"][(s_mid >= zone.start) & (s_mid < zone.end)] = zone.coefficient

    P = model.pulleys
    tt_off, tt_x, tt_y = flatten([p.torque_time for p in P])
    ts_off, ts_x, ts_y = flatten([p.torque_speed for p in P])
    sp_off, sp_x, sp_y = flatten([p.speed_time for p in P])
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
    span_geo = np.array([[*sp.midpoint, math.cos(sp.angle), math.sin(sp.angle)] for sp in layout.spans])
    track = np.array(model.output.segments, dtype=np.int64)
    ip = np.zeros(7, dtype=np.int64)
    ip[K.I_N], ip[K.I_NK] = n, nk
    ip[K.I_LAW] = 0 if model.friction.law == "threlfall" else 1
    ip[K.I_NSPAN], ip[K.I_NTRACK] = len(layout.spans), len(track)
    ip[K.I_LINEAR] = 1 if e == 1.0 else 0
    fp = np.zeros(9)
    fp[K.F_EAX], fp[K.F_EB] = e, belt.bending_exponent
    fp[K.F_PMAX], fp[K.F_DV], fp[K.F_DMAX] = damping_depth(model, init), model.friction.velocity_threshold, model.friction.displacement_limit
    fp[K.F_G], fp[K.F_TURN], fp[K.F_HL] = model.gravity, init.turn, 0.5 * l

    scaled = model.simulation.method == "semi-implicit" and model.simulation.rotation_scaling
    limit = stability_limit(model, init, seg, scaled)
    step = model.simulation.step if model.simulation.step is not None else 0.85 * limit
    if not model.simulation.duration / step < MAX_STEPS:
        raise ModelError(f"the stable step is only {limit:.3g} s ({model.simulation.duration / step:.3g} steps for "
                         f"{model.simulation.duration:g} s, over the {MAX_STEPS:.0e} allowed): check the belt's "
                         "stiffness and damping values and the contact stiffness", field="simulation")
    fp[K.F_ISCALE] = ROTATION_SCALE if scaled else 1.0
    sysm = BeltSystem(model, layout, init, ip, fp, seg, pul, span_mid, span_geo, track, step, limit)
    # start from the chain's static equilibrium, so that a drive at rest stays at rest
    eq = relax(sysm, init.x, init.y, init.phi) if settle else None
    if eq is not None:
        x, y, phi, res, _ = eq
        sysm.init = dataclasses.replace(init, x=x, y=y, phi=phi, residual=res)
    return sysm


def damping_depth(model, init) -> float:
    """p_max of the contact damping ramp: the model's, else the smallest static penetration at the
    pretension (the segments pressed as at rest on the largest pulley get the full damping)."""
    if model.contact.damping_depth is not None:
        return float(model.contact.damping_depth)
    return float(np.min(init.penetration))


# Selective mass scaling of the segments' rotation: I = m l^2/12 -> 3.3 I = 1.1 m l^2/4, just above
# the m l^2/4 that takes the alternating rotation mode (omega^2 = 12 k/m) below the zig-zag modes
# (4 k/m): the step grows by about 1.5. Opt-in (simulation.rotation_scaling): at 1 m/s belt speed it
# changes span forces by < 0.5 % and slip by < 1e-4, but at 11 m/s it raises the contact losses
# where segments land on a pulley by a third.
ROTATION_SCALE = 3.3
# more steps than this (days of computing at microseconds per step) means an input error
MAX_STEPS = 1e11


def effective_inertia(sysm) -> np.ndarray:
    """Rotational inertia of the segments as the integrator sees it (mass-scaled or not); the
    energy balance uses it, since that is the energy the scheme conserves."""
    return sysm.seg["inertia"] * float(sysm.fp[K.F_ISCALE])


def _tangent_k(model, init, seg):
    e = model.belt.axial_exponent
    k = float(seg["kax"][0])
    if e != 1.0:  # tangent stiffness at the pretension
        k = e * k * init.gap ** (e - 1)
    return k


def stability_limit(model, init, seg, scaled=False) -> float:
    """Largest stable step of the explicit part: 2/omega for the stiffest chain mode.

    The zero-length joint spring is isotropic. Bloch analysis of the straight chain gives, for the
    transverse/rotation branch, omega^2 = 2k [(1 - cos q)/m + (1 + cos q) (l/2)^2 / I]: the
    alternating rotation mode (q = 0) at 12 k / m, and once the rotation is mass-scaled to
    I >= m l^2 / 4 (``scaled``) the zig-zag modes (q = pi) at 4 k / m, raised by the contact
    stiffness k_c. The axial dampers (rate 4 b / m in the zig-zag mode, reduced by the per-joint
    implicit factor 1 / (1 + 2 h b / m)) lower the symplectic-Euler limit to
    2/omega (sqrt(1 + zeta^2) - zeta); solved for h by fixed-point iteration.
    """
    m = float(seg["m"][0])
    k = _tangent_k(model, init, seg)
    p = 2 * float(np.max(init.penetration))          # contact stiffness at twice the static penetration
    kc = 2 * float(seg["c1"][0]) * p + float(seg["c2"][0])
    kb = float(seg["kb"][0]) * max(model.belt.bending_exponent, 1.0)
    inertia = float(seg["inertia"][0])
    # the tension adds T l/2 per joint to a segment's rotational stiffness (arms turning in the
    # force); negligible at usual strains, not at tens of per cent: take twice the pretension
    k_rot = k + 4 * kb / init.seg_length ** 2 + 4 * init.tension / init.seg_length
    w_zig = math.sqrt((4 * k + kc) / m)
    if scaled:   # the scaled rotation branch, which at high tension may top the zig-zag modes
        w_zig = max(w_zig, math.sqrt(12 * k_rot / (ROTATION_SCALE * m)))
    b = float(seg["bax"][0])
    h = 2 / w_zig
    for _ in range(50):
        gamma = 4 * b / m / (1 + 2 * h * b / m)
        zeta = gamma / (2 * w_zig)
        h = 2 / w_zig / (math.sqrt(1 + zeta ** 2) + zeta)  # = sqrt(1 + z^2) - z without cancellation
    limits = [h]
    if not scaled:
        w_rot = math.sqrt(12 * k_rot / m)
        zeta = 4 * float(seg["bb"][0]) / inertia / (2 * w_rot)
        limits.append(2 / w_rot / (math.sqrt(1 + zeta ** 2) + zeta))
    elif float(seg["bb"][0]) > 0:   # explicit bending dampers, on the unscaled (conservative) inertia
        limits.append(inertia / (2 * float(seg["bb"][0])))
    return min(limits)
