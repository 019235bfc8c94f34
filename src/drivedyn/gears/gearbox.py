"""A gearbox of stages in series: a planetary stage whose output member drives a gear train (parallel
pairs) through a torsional shaft, as wind-turbine and industrial gearboxes are built.

The whole train's modes: the stage's model (torsional, planetary.matrices, or lateral-torsional,
planetary_lateral.matrices, the fixed member on its support) and the train's torsional model
(train.System.coupling, mean mesh stiffnesses) joined by the shaft, whose energy is
1/2 k (theta_out - theta_g)^2: theta_out the stage's output member (u / r in the lateral model),
theta_g the train gear on that shaft (its angle positive in its own direction of rotation, which
the shaft gives it from the output member). Each mode is attributed by its kinetic energy: the share
in the stage's coordinates.
"""
from __future__ import annotations

import math

import numpy as np

from . import planetary as tors
from .planetary_lateral import MEMBERS


def stage_matrices(spec):
    """(M, K, names, output coordinate vector) of the stage with its fixed member held (or on its
    support stiffness); the last is the row g with theta_out = g . q."""
    lat = spec.lateral
    hold = lat.support_stiffness if lat is not None and lat.support_stiffness is not None else "fixed"
    st = tors.stage_of(spec, support={spec.fixed: hold})
    output = next(m for m in MEMBERS if m not in (spec.fixed, spec.input))
    if lat is None:
        M, K, names = tors.matrices(st)
        g = np.zeros(len(names))
        g[names.index(output)] = 1.0
        return M, K, names, g, "torsional"
    from . import planetary_lateral as pl

    ls = tors.lateral_stage(spec, st, {spec.fixed: hold})
    M, K, names = pl.matrices(ls)
    g = np.zeros(len(names))
    g[names.index(f"{output}.u")] = 1.0 / ls.radius(output)
    return M, K, names, g, "lateral-torsional"


def modes(model, sys_) -> dict:
    """Natural frequencies (Hz, rigid-body mode removed) of the stage and the train joined by the
    output shaft, and each mode's kinetic-energy share in the stage."""
    from scipy.linalg import eigh

    spec = model.planetary
    Ms, Ks, names, g_out, kind = stage_matrices(spec)
    Kt, _, Mt = sys_.coupling()
    ns, nt = len(names), sys_.n
    M = np.zeros((ns + nt, ns + nt))
    K = np.zeros_like(M)
    M[:ns, :ns], K[:ns, :ns] = Ms, Ks
    M[ns:, ns:], K[ns:, ns:] = Mt, Kt
    g = np.zeros(ns + nt)
    g[:ns] = g_out
    g[ns + sys_.names.index(spec.output_gear)] = -1.0
    K += spec.output_shaft_stiffness * np.outer(g, g)
    w2, V = eigh(K, M)
    keep = w2 > 1e-9 * max(abs(w2).max(), 1.0)
    f = np.sqrt(w2[keep]) / (2 * math.pi)
    V = V[:, keep]
    ke = (M @ V) * V                                  # kinetic energy per coordinate and mode (mass-normalised: sums to 1)
    share = ke[:ns].sum(axis=0)
    return {"model": kind, "output_gear": spec.output_gear, "natural_frequencies_hz": [float(x) for x in f],
            "stage_energy_share": [float(x) for x in share],
            "coordinates": [*(f"planetary.{n}" for n in names), *sys_.names]}


def output_torque(spec) -> float:
    """Torque (N m) the stage delivers at its output member: the input torque times the speed ratio
    input / output (no losses)."""
    st = tors.stage_of(spec)
    output = next(m for m in MEMBERS if m not in (spec.fixed, spec.input))
    return spec.torque * abs(tors._speed_ratio(st, spec.input, output))
