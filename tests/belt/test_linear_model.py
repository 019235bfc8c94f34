"""The drive's linear model (belt/steady/modes.py ``linear_model``) with the crank as a DOF: a two-pulley
drive driven by its crank's motion is a base-excited oscillator, written here from the belt's
energies (belt stuck to both wraps, equal radii R, centres L apart):

- stiffness: two spans EA / L, one stretched and the other shortened by R (theta_d - theta_c):
  k = 2 EA R^2 / L on the driven pulley, -k between it and the crank;
- mass: each span's belt moves along itself at R theta' of the point it leaves and of the point it
  reaches, velocity linear in between (m L / 6 [[2, 1], [1, 2]]); the driven pulley carries its
  half wrap (m pi R) at R. Driven: J + m pi R^3 + 2 m L R^2 / 3; crank-driven coupling m L R^2 / 3;

so the driven pulley's rotation over the crank's is (k + W^2 m L R^2 / 3) / (k - W^2 J_eff)."""
import math

import numpy as np
import pytest

from drivedyn.belt.steady.modes import linear_model, modes
from drivedyn.core.model import from_dict

EA, MASS, R, L, J = 1.5e5, 0.1, 0.05, 0.4, 2e-3


def drive():
    return from_dict({
        "kind": "belt-drive",
        "belt": {"mass_per_length": MASS, "axial_stiffness": EA, "pretension": 400.0},
        "contact": {"stiffness_linear": 1e12, "stiffness_quadratic": 0.0},
        "friction": {"law": "threlfall", "coefficient": 1.0},       # adhesion: the closed form above
        "pulleys": [{"name": "crank", "center": [0, 0], "radius": R, "speed_time": [[0, 0], [1, 50]]},
                    {"name": "driven", "center": [L, 0], "radius": R, "inertia": J}]})


@pytest.mark.parametrize("ratio", [0.6, 1.6])
def test_forced_by_the_crank(ratio):
    m = drive()
    lin = linear_model(m, held_as_dofs=True)
    assert lin.dofs == ("crank", "driven")
    k = 2 * EA * R * R / L
    m_c = MASS * L * R * R / 3
    J_eff = J + MASS * math.pi * R ** 3 + 2 * MASS * L * R * R / 3
    W = ratio * math.sqrt(k / J_eff)
    D = lin.K - W * W * lin.M
    H = -D[1, 0] / D[1, 1]
    assert H == pytest.approx((k + W * W * m_c) / (k - W * W * J_eff), rel=1e-6)
    # the span tensions from the stretch map: +- EA / L * R (theta_d - theta_c)
    dT = lin.span_stiffness * (lin.G @ np.array([1.0, H]))
    assert dT[0] == pytest.approx(-dT[1], rel=1e-12)
    assert abs(dT[0]) == pytest.approx(EA / L * R * abs(H - 1.0), rel=1e-9)


def test_held_crank_is_modes_own_model():
    m = drive()
    held, free = linear_model(m), linear_model(m, held_as_dofs=True)
    assert held.dofs == ("driven",)
    assert held.K[0, 0] == pytest.approx(free.K[1, 1]) and held.M[0, 0] == pytest.approx(free.M[1, 1])
    assert modes(m).frequencies_hz[0] == pytest.approx(math.sqrt(held.K[0, 0] / held.M[0, 0]) / (2 * math.pi))


def test_slack_wraps_are_condensed_not_a_singular_matrix():
    """Every span slack (a periodic run-up of fead-runup with friction.coefficient = 1e-6 ends with
    zero mean tensions): no wrap grips, and the belt sliding round all pulleys at once is stiffened by
    nothing. The wraps' condensation failed with a singular matrix in the Campbell painter after the
    run had finished, and no report was written; the sliding carries no force, so it condenses."""
    import drivedyn
    from drivedyn.belt.steady.modes import drive_modes

    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")), {"friction.coefficient": 1e-6})
    slack = drive_modes(m, tensions=np.zeros(6))
    assert len(slack.frequencies_hz) >= 1 and np.all(np.isfinite(slack.frequencies_hz))
    # a small grip: its wrap's sliding stiffness kb L, the lowest mode's frequency as sqrt(mu)
    f = [drive_modes(drivedyn.replace(m, {"friction.coefficient": mu})).frequencies_hz[0] for mu in (1e-6, 1e-8)]
    assert f[1] == pytest.approx(0.1 * f[0], rel=1e-3)
