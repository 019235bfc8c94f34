"""What is known without simulating: layout, belt length, wraps, static tensions, hub loads,
span frequencies, the capstan limit and the step the integrator will use."""
from __future__ import annotations

import math

import numpy as np



def span_frequencies(tension, mass_per_length, length, bending_stiffness=0.0, speed=0.0, modes=3):
    """Transverse natural frequencies (Hz) of a span.

    Taut string (Wickert & Mote 1990, axially moving): f_n = n/(2L) c (1 - v^2/c^2), c = sqrt(T/m');
    a pinned-pinned bending correction multiplies by sqrt(1 + (n pi / L)^2 EI / T) (beam under tension).
    """
    c = math.sqrt(tension / mass_per_length)
    out = []
    for k in range(1, modes + 1):
        f = k / (2 * length) * c * (1 - (speed / c) ** 2)
        f *= math.sqrt(1 + (k * math.pi / length) ** 2 * bending_stiffness / tension)
        out.append(f)
    return out


def capstan_torque(tension, radius, wrap, mu):
    """Largest torque a pulley transmits before gross slip (Euler-Eytelwein, T1/T2 = e^(mu theta)),
    with T1 + T2 = 2 T0 (constant belt length): M = 2 T0 r (e - 1)/(e + 1)."""
    return 2 * tension * radius * math.tanh(mu * wrap / 2)  # = (e - 1)/(e + 1), no overflow


def report(model) -> str:
    from .system import build

    sysm = build(model)
    lay = sysm.layout
    T0 = sysm.init.tension
    belt = model.belt
    lines = [f"belt drive: {model.name or '(unnamed)'}",
             f"loop: {'counter-clockwise' if lay.orientation > 0 else 'clockwise'} in the listed order; "
             f"path length {lay.length * 1e3:.2f} mm at the contact radii",
             f"belt: unstretched length {sysm.init.seg_length * belt.segments * 1e3:.2f} mm, pretension {T0:.1f} N "
             f"(strain {T0 / belt.axial_stiffness * 100:.3f} %), {belt.segments} segments of {sysm.init.seg_length * 1e3:.3f} mm",
             "", f"{'pulley':14s} {'x mm':>9s} {'y mm':>9s} {'r mm':>7s} {'side':>6s} {'wrap deg':>9s} {'hub load N':>11s} "
             f"{'hub dir deg':>11s} {'penetr. mm':>10s} {'capstan N m':>11s}"]
    hub = lay.hub_load_static(T0)
    mu = model.friction.coefficient
    for j, p in enumerate(model.pulleys):
        H = hub[j]
        lines.append(f"{p.name:14s} {p.center[0] * 1e3:9.2f} {p.center[1] * 1e3:9.2f} {p.radius * 1e3:7.2f} {p.side:>6s} "
                     f"{math.degrees(lay.wrap[j]):9.2f} {np.hypot(*H):11.1f} {math.degrees(math.atan2(H[1], H[0])):11.1f} "
                     f"{sysm.init.penetration[j] * 1e3:10.4f} {capstan_torque(T0, p.radius, lay.wrap[j], mu):11.2f}")
    lines += ["", f"{'span':28s} {'length mm':>10s} {'tension N':>10s} {'f1 Hz':>8s} {'f2 Hz':>8s} {'f3 Hz':>8s}"]
    for sp in lay.spans:
        f = span_frequencies(T0, belt.mass_per_length, sp.length, belt.bending_stiffness)
        lines.append(f"{sp.name:28s} {sp.length * 1e3:10.2f} {T0:10.1f} {f[0]:8.1f} {f[1]:8.1f} {f[2]:8.1f}")
    lines += ["", "static: no load, no gravity sag; span frequencies of the belt at rest (taut string with bending).",
              f"integration: {model.simulation.method}, step {sysm.step * 1e6:.3f} us (stability limit "
              f"{sysm.step_limit * 1e6:.3f} us), {model.simulation.duration / sysm.step:.3g} steps for "
              f"{model.simulation.duration:g} s"]
    return "\n".join(lines)
