"""The ``[load]`` section of a toothed-mesh model: its chain, checks, the run's numbers and arrays.

The chain (loadshare.Chain) is built from the resolved pair: belt pitch-line radius R_b, groove
spacing on it, the pair's pitch error (PLD or pitch mismatch) plus ``load.pitch_error``, the land
share from the groove width, teeth in mesh from the wrap, and the stiffnesses (per width x width).
"""
from __future__ import annotations

import numpy as np

from ..mechanics.teeth import catalogue
from ..mechanics.teeth.loadshare import Chain, climb_factor, exit_path, flank_angle, jump_margin, jump_torque, land_share, solve, span_tensions, teeth_in_mesh, tooth_stiffness_per_width

MAX_NODES = 5000     # nodes of one chain: each jump torque is ~30 solves of it, per tension
MAX_STRAIN = 0.1     # tensions beyond 10 % cord strain are outside a linear-elastic cord


def stiffnesses(model, pair):
    """(tooth spring per width N/m^2, its source, EA per width N/m, its source)."""
    ld = model.load
    if ld.tooth_stiffness is not None:
        kt, kt_src = ld.tooth_stiffness, "load.tooth_stiffness"
    else:
        kt = tooth_stiffness_per_width(pair.tooth, ld.tooth_modulus)
        kt_src = "from the tooth shape and load.tooth_modulus (cantilever, bending + shear)"
    if ld.cord_stiffness is not None:
        return kt, kt_src, ld.cord_stiffness, "load.cord_stiffness"
    found = catalogue.cord_stiffness(model.belt.profile) if model.belt.profile else None
    if found is None:
        raise ValueError(f"load.cord_stiffness: no source gives the cord stiffness of belt "
                         f"{model.belt.profile or 'custom'!s}; give EA per width (e.g. '6000 N/mm')")
    return kt, kt_src, found[0], found[1]


def chain_of(model, pair, clearance=0.0) -> Chain:
    """The load-sharing chain of a model with a ``[load]`` section."""
    ld = model.load
    kt, _, ea, _ = stiffnesses(model, pair)
    spacing = 2 * np.pi * pair.belt_radius / pair.teeth
    return Chain(teeth=teeth_in_mesh(pair.teeth, ld.wrap), pitch=spacing, radius=pair.belt_radius,
                 tooth_stiffness=kt * ld.width, cord_stiffness=ea * ld.width, land_share=land_share(pair),
                 friction=ld.friction, pitch_error=pair.pitch_error + ld.pitch_error,
                 land_nodes=ld.land_nodes, slip_scale=ld.slip_scale, clearance=clearance)


def tensions_of(model):
    """Installation tensions of the jump-torque curve (N)."""
    ld = model.load
    return list(ld.tensions) or [f * ld.installation_tension for f in (0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0)]


def check_load(model, pair) -> None:
    """Checks that need the pair; ValueError with one line naming the field."""
    ld = model.load
    ch = chain_of(model, pair)
    if pair.teeth * ld.wrap / (2 * np.pi) + 1e-9 < 1:
        raise ValueError(f"load.wrap: {np.degrees(ld.wrap):.4g} deg holds no whole tooth of the {pair.teeth}-tooth "
                         f"pulley (one tooth spans {360 / pair.teeth:.4g} deg): no tooth would carry the load")
    if ld.clearance is not None and ld.clearance >= ch.pitch / 2:
        raise ValueError(f"load.clearance: {ld.clearance * 1e3:.4g} mm of sideways play is at least half the groove "
                         f"spacing {ch.pitch * 1e3:.4g} mm: the tooth would sit in the next groove")
    nodes = ch.teeth + (ch.teeth - 1) * (ch.land_nodes if ch.friction > 0 else 0)
    if nodes > MAX_NODES:
        raise ValueError(f"load: {ch.teeth} teeth in mesh x {ch.land_nodes} land_nodes make {nodes} nodes, "
                         f"more than {MAX_NODES}; lower load.land_nodes or load.wrap")
    if abs(ch.pitch_error) >= ch.pitch / 2:
        raise ValueError(f"load.pitch_error: the total pitch error {ch.pitch_error * 1e3:.4g} mm is more than "
                         f"half the groove spacing {ch.pitch * 1e3:.4g} mm")
    ea = ch.cord_stiffness
    for name, t in [("installation_tension", ld.installation_tension)] + \
                   [(f"tensions[{k}]", t) for k, t in enumerate(ld.tensions)]:
        if t > MAX_STRAIN * ea:
            raise ValueError(f"load.{name}: {t:.4g} N stretches the cord (EA {ea:.4g} N) by more than "
                             f"{MAX_STRAIN:.0%}; the linear cord model does not apply")
    T1, _ = span_tensions(ld.torque, ld.installation_tension, ch.radius)
    if T1 > MAX_STRAIN * ea:
        raise ValueError(f"load.torque: {ld.torque:.4g} N m gives a tight-side tension {T1:.4g} N that stretches "
                         f"the cord (EA {ea:.4g} N) by more than {MAX_STRAIN:.0%}")


def run_load(model, pair, progress=None):
    """(data variables, coordinates, summary, diagnostics as (code, text, quantity, value, limit, unit)).
    A load sharing that does not converge (extreme stiffness ratios) is a failed solve, one line."""
    try:
        return _run_load(model, pair, progress)
    except RuntimeError as exc:
        from ..core.errors import SolverError

        ch = chain_of(model, pair)
        raise SolverError(f"{exc}: tooth stiffness {ch.tooth_stiffness:.3g} N/m against cord stiffness "
                          f"{ch.cord_stiffness:.3g} N (check load.tooth_stiffness or tooth_modulus and "
                          "cord_stiffness)") from None


def _run_load(model, pair, progress=None):
    from ..core.results import variable

    ld = model.load
    path = exit_path(pair)
    play = float(path[1][0]) if np.isfinite(path[1][0]) else 0.0
    ch = chain_of(model, pair, ld.clearance if ld.clearance is not None else play)
    kt, kt_src, ea, ea_src = stiffnesses(model, pair)
    phi = ld.flank_angle if ld.flank_angle is not None else flank_angle(pair, path=path)
    factor = climb_factor(phi, ld.friction)
    T0 = ld.installation_tension
    T1, T2 = span_tensions(ld.torque, T0, ch.radius)
    sh = solve(ch, T1, T2, T0)
    margin = jump_margin(sh, ch, factor)
    m_jump = jump_torque(ch, T0, factor)
    first = None
    if m_jump is not None:
        a, b = span_tensions(m_jump, T0, ch.radius)
        first = int(np.argmax(jump_margin(solve(ch, a, b, T0), ch, factor))) + 1
    curve = []
    tens = tensions_of(model)
    for k, t in enumerate(tens):
        curve.append(jump_torque(ch, t, factor))
        if progress:
            progress(0.75 + 0.2 * (k + 1) / len(tens), f"jump torque at {t:.4g} N")
    teeth = np.arange(1, ch.teeth + 1)
    # tension along the wrap: T1 at the tight end, each element, T2 at the slack end
    s_wrap = np.concatenate([[sh.s[0]], sh.element_s, [sh.s[-1]]]) if len(sh.s) > 1 else np.array([0.0, 0.0])
    T_wrap = np.concatenate([[T1], sh.element_T, [T2]])
    data = {
        "tooth_load": variable(sh.tooth_load, ("load_tooth",), "N", "load on each tooth in mesh (tooth 1: tight side)"),
        "tooth_tension": variable(sh.tooth_tension, ("load_tooth",), "N", "mean belt tension at each tooth"),
        "jump_margin": variable(margin, ("load_tooth",), "N",
                                "outward push Q tan(phi - rho) minus hold T p / R (> 0: the tooth climbs)"),
        "wrap_tension": variable(T_wrap, ("wrap_point",), "N", "tension of the cord along the wrap"),
        "jump_torque": variable(np.array([np.nan if c is None else c for c in curve]), ("jump_tension",), "N*m",
                                "torque at which a tooth starts to climb out of its groove"),
    }
    coords = {"load_tooth": ("load_tooth", teeth),
              "wrap_position": variable(s_wrap, ("wrap_point",), "m", "position along the wrap from tooth 1"),
              "jump_tension": variable(np.array(tens), ("jump_tension",), "N", "installation tension")}
    summary = {
        "width_mm": 1e3 * ld.width, "installation_tension_N": T0, "torque_N_m": ld.torque,
        "tight_tension_N": T1, "slack_tension_N": T2, "teeth_in_mesh": ch.teeth,
        "tooth_loads_N": sh.tooth_load.tolist(), "max_tooth_load_N": float(sh.tooth_load.max()),
        "most_loaded_tooth": int(np.argmax(sh.tooth_load)) + 1,
        "first_tooth_share": float(sh.tooth_load[0] / (T1 - T2)) if T1 > T2 else None,
        "land_friction_N": float(sh.land_friction.sum()),
        "tooth_stiffness_N_per_m": kt * ld.width, "tooth_stiffness_source": kt_src,
        "cord_stiffness_N": ea * ld.width, "cord_stiffness_source": ea_src,
        "land_share": ch.land_share, "pitch_error_mm": 1e3 * ch.pitch_error,
        "flank_angle_deg": float(np.degrees(phi)), "friction": ld.friction,
        "clearance_mm": 1e3 * ch.clearance, "seated_play_mm": 1e3 * play,
        "jump_torque_N_m": m_jump, "first_tooth_to_climb": first,
        "jump_curve": {"installation_tension_N": tens, "jump_torque_N_m": curve},
        "newton_iterations": sh.iterations,
    }
    diags = []
    if m_jump is not None and ld.torque >= m_jump:
        diags.append(("tooth-jump", f"the torque {ld.torque:.4g} N m is at or above the jump torque {m_jump:.4g} N m "
                      f"at {T0:.4g} N installation tension: tooth {first} climbs out of its groove (ratchets)",
                      "torque", ld.torque, m_jump, "N*m"))
    attrs = {"load_torque": ld.torque, "load_T0": T0, "load_jump_torque": np.nan if m_jump is None else m_jump,
             "load_pitch": ch.pitch, "load_climb_factor": factor}
    return data, coords, summary, diags, attrs
