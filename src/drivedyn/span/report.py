"""``check`` for span-stability models: the span quantities, bands and frequencies as text."""
from __future__ import annotations

import numpy as np

from .analysis import measurement_summary, operating_point, point_floquet, require_stable_speed, tooth_force_harmonics
from ..mechanics.span.chart import bands
from ..mechanics.span.frequencies import span_frequencies
from .source import resolve


def _band(b):
    return f"{b[0]:.5g} .. {b[1]:.5g} m/s" if b else "none"


def _excitation(op, st) -> str:
    """The excitation line: no period at V = 0 (no teeth pass), no ratio above V_cr (no Omega)."""
    mu = "none (diverged)" if op["mu"] is None else f"{op['mu']:.4g}"
    head = f"  excitation      mu = {mu}, pitch {1e3 * st.pitch:.4g} mm, "
    w = op["excitation_frequency"]
    if w <= 0:
        return head + "none at V = 0 (no teeth pass: no tension fluctuation)"
    ratio = "" if op["frequency_ratio"] is None else f" (omega/Omega = {op['frequency_ratio']:.4g})"
    return head + f"{st.convention} period {1e3 * 2 * np.pi / w:.4g} ms, omega = {w:.4g} rad/s{ratio}"


def report(model) -> str:
    """Human-readable report of what is known without the chart (no Floquet map)."""
    st = resolve(model)
    # a measurement no tension can explain is the user's mistake: refuse it before the Floquet map
    meas = measurement_summary(model, st) if model.measurement is not None else None
    harm = tooth_force_harmonics(model, st)
    op = operating_point(st, harm)
    if model.response is not None:
        require_stable_speed(op, "[response]")
    sp = st.span
    exact, first = bands(st, harm, model.chart.tongues)
    f = None if op["omega"] is None else span_frequencies(st.pretension, sp.mass_per_length, sp.length,
                                                          sp.bending_stiffness, st.speed, 3)
    lines = [
        f"span-stability: {model.name or '(unnamed)'}",
        f"  span            l = {sp.length:.4g} m ({sp.source}), rhoA = {sp.mass_per_length:.4g} kg/m, "
        f"EI = {sp.bending_stiffness:.4g} N m^2, zeta = {sp.damping_ratio:.3g}",
        f"  operation       F0 = {st.pretension:.4g} N, V = {st.speed:.4g} m/s",
        f"  Euler load      F* = {op['euler_load']:.4g} N",
        f"  critical speed  V_cr = {op['v_critical']:.4g} m/s (divergence above)",
        (f"  loaded freq.    Omega = {op['omega']:.4g} rad/s ({op['natural_frequency_hz']:.4g} Hz)" if op["omega"]
         else f"  loaded freq.    none: V = {st.speed:.4g} m/s is above V_cr, the span DIVERGES"),
        f"  tooth force     mean {harm.mean:.4g} N, F1 = {harm.f1:.4g} N, "
        f"c2..c4 = {', '.join(f'{c:.3g}' for c in harm.amplitudes[1:4])} N",
        _excitation(op, st),
        f"  principal band  exact {_band(exact[0])}; first order (seed) {_band(first)}",
    ]
    for n, b in enumerate(exact[1:], start=2):
        lines.append(f"  tongue n = {n}    {_band(b)}")
    inside = bool(exact[0] and exact[0][0] <= st.speed <= exact[0][1])
    pf = point_floquet(st, harm, model.chart.steps_per_oscillation)
    lines.append(f"  at the model's speed: {'INSIDE the principal resonance band' if inside else 'outside the principal band'}; "
                 f"Floquet |lambda| = {pf['floquet_multiplier']:.6g}, growth rate {pf['growth_rate']:.4g} 1/s")
    lines.append("  span frequencies (Hz, modes 1-3):" + (" none (diverged)" if f is None else ""))
    for k, v in (f or {}).items():
        lines.append(f"    {k:14s} " + "  ".join(f"{x:8.4g}" for x in np.atleast_1d(v)))
    if meas is not None:
        m = meas
        lines.append(f"  measurement     {m['frequency']:.4g} Hz (mode {m['mode']}, V = {m['speed']:.3g} m/s) -> "
                     f"T = {m['tension']:.4g} +- {m['uncertainty']:.3g} N (string formula {m['tension_string']:.4g} N, "
                     f"bending {m['bending_correction']:+.3g} N, speed {m['speed_correction']:+.3g} N)")
    return "\n".join(lines)
