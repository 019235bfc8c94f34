"""Span quantities of the seed (Belyaev, seed 002, eqs. 4-6): F*, Omega, mu, V_cr, forcing gain.

Notation (SI): l span length, m = rhoA mass per metre, EI bending stiffness, F0 static tension,
V belt speed, F1 first-harmonic amplitude of the tension fluctuation.

The effective tension ``N = F0 + F* - V^2 m`` appears everywhere: the span diverges when N <= 0.
All functions broadcast over numpy arrays.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.errors import ModelError


@dataclass(frozen=True)
class SpanProperties:
    """A resolved span (SI floats).

    Attributes
    ----------
    length : float
        Free span length l (m).
    mass_per_length : float
        rhoA (kg/m).
    bending_stiffness : float
        EI (N m^2).
    damping_ratio : float
        Modal damping ratio zeta of the first mode (-).
    source : str
        Where the length came from ("model" or "<belt file>:<span name>").
    """

    length: float
    mass_per_length: float
    bending_stiffness: float
    damping_ratio: float = 0.0
    source: str = "model"

    @property
    def euler_load(self) -> float:
        """F* = pi^2 EI / l^2 (N), seed eq. 5."""
        return euler_load(self.bending_stiffness, self.length)


def euler_load(EI, l):
    """Euler load of the pinned span, F* = pi^2 EI / l^2 (seed, after eq. 5)."""
    return np.pi ** 2 * EI / l ** 2


def effective_tension(F0, V, sp: SpanProperties):
    """N = F0 + F* - V^2 rhoA (N): the stiffness of eq. 4 times l^2 / pi^2."""
    return F0 + sp.euler_load - np.asarray(V) ** 2 * sp.mass_per_length


def natural_frequency(F0, V, sp: SpanProperties):
    """Loaded natural frequency Omega = (pi/l) sqrt(N / rhoA) (rad/s), seed eq. 5.

    NaN where the span has diverged (N <= 0).
    """
    N = effective_tension(F0, V, sp)
    with np.errstate(invalid="ignore"):
        return np.where(N > 0, np.pi / sp.length * np.sqrt(np.maximum(N, 0.0) / sp.mass_per_length), np.nan)


def excitation_coefficient(F0, V, F1, sp: SpanProperties):
    """mu = F1 / (2 N) (-), seed eq. 5; NaN where N <= 0."""
    N = effective_tension(F0, V, sp)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(N > 0, F1 / (2.0 * N), np.nan)


def critical_speed(F0, sp: SpanProperties):
    """V_cr = sqrt((F0 + F*) / rhoA) (m/s): divergence above it (seed, after eq. 6)."""
    return np.sqrt((np.asarray(F0) + sp.euler_load) / sp.mass_per_length)


def moment_rate_gain(V, sp: SpanProperties):
    """Gain G of dM/dt in eq. 4: q'' + ... = G dM/dt, G = 4 l V (12 - pi^2) / (3 EI pi^3) (1/(N s)).

    Eq. 4 of the seed has pi^3; its eq. 5 prints pi^2, a misprint (our Galerkin integral of
    the static correction gives pi^3). Its eq. 3 also lacks a 1/l in the static term for the
    boundary condition EI y'' = -M to hold; eq. 4 is consistent with the corrected eq. 3.
    """
    if sp.bending_stiffness <= 0:
        raise ModelError("must be > 0 for the moment-forced response (eq. 4 divides by EI)",
                         field="span.bending_stiffness")
    return 4.0 * sp.length * np.asarray(V) * (12.0 - np.pi ** 2) / (3.0 * sp.bending_stiffness * np.pi ** 3)


def excitation_frequency(V, teeth: int, pitch: float, convention: str = "tooth-passing"):
    """Circular frequency omega (rad/s) of the tension fluctuation at belt speed V.

    ``"tooth-passing"``: period p / V with p = 2 pi r / z the tooth pitch (physical).
    ``"seed"``: the seed's printed T = pi r / (V z), half the tooth-passing period.
    """
    omega = 2.0 * np.pi * np.asarray(V, dtype=float) / pitch
    return 2.0 * omega if convention == "seed" else omega
