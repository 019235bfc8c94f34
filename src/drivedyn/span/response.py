"""Time response of the span's modal coordinate (seed eq. 4) to the end-moment rate.

    q'' + 2 zeta Omega q' + Omega^2 (1 + 2 mu Phi(omega t)) q = G dM/dt,
    G = 4 l V (12 - pi^2) / (3 EI pi^3),     M(t) = M1 Phi(omega t)

The seed leaves M(t) open; here the end moment fluctuates with the same tooth-passing shape as
the tension, with amplitude ``response.moment_amplitude`` (a constant part does not force q).
Mid-span deflection equals q: the static correction of eq. 3 vanishes at x = l/2.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..core.errors import SolverError
from ..mechanics.span.quantities import excitation_frequency, moment_rate_gain, natural_frequency


def modal_response(setup, harm, duration: float, moment_amplitude: float, q0: float, points: int):
    """(t, q) over ``duration`` at the model's F0 and V; DOP853 with rtol 1e-8.

    Raises SolverError if the integration fails.
    """
    sp = setup.span
    F0, V = setup.pretension, setup.speed
    Om = float(natural_frequency(F0, V, sp))
    w = float(excitation_frequency(V, setup.teeth, setup.pitch, setup.convention))
    two_mu_om2 = (np.pi / sp.length) ** 2 * harm.f1 / sp.mass_per_length   # 2 mu Omega^2 = k^2 F1 / rhoA
    a, b = harm.shape()
    k = np.arange(1, len(a) + 1)
    gain = float(moment_rate_gain(V, sp)) * moment_amplitude * w if moment_amplitude > 0 else 0.0

    def rhs(t, y):
        x = k * w * t
        c, s = np.cos(x), np.sin(x)
        phi = a @ c + b @ s
        dphi = (-a * k) @ s + (b * k) @ c            # dPhi / d(omega t)
        acc = -2 * sp.damping_ratio * Om * y[1] - (Om * Om + two_mu_om2 * phi) * y[0] + gain * dphi
        return [y[1], acc]

    t = np.linspace(0.0, duration, points)
    max_step = 2 * np.pi / max(Om, w * len(a)) / 2   # never step over the fastest of mode and harmonics
    sol = solve_ivp(rhs, (0.0, duration), [q0, 0.0], method="DOP853", t_eval=t, rtol=1e-8, atol=1e-12,
                    max_step=max_step)
    if not sol.success:
        raise SolverError(f"modal response failed at t = {sol.t[-1]:.4g} s: {sol.message}")
    return sol.t, sol.y[0]
