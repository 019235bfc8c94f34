"""Belt-drive dynamics against classical belt mechanics and conservation laws.

References: torque balance T1 - T2 = M/r and hub load = vector sum of span tensions (statics);
Euler-Eytelwein capstan limit T1/T2 = exp(mu theta); creep slip (T1 - T2)/EA (Reynolds 1847,
Johnson, Contact Mechanics, sec. 8.4); taut-string span frequency f1 = sqrt(T/m')/(2L);
energy conservation of the undamped, frictionless model; convergence in step and segments.
Each reference runs under both belt schemes, the semi-implicit reference and the implicit one
(issue 14), except the segment convergence and the mass scaling, which concern the first.
"""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.segments.simulate import _Recorder  # noqa: F401  (internal, used for the energy test)
from drivedyn.belt.segments.state import new_state, new_work
from drivedyn.belt.segments.system import build

from .conftest import seed_5pk

R = 0.027


def kinematic(model_factory, load, **kw):
    """Driver at -40 rad/s (ramped in 50 ms), driven loaded by a viscous torque equal to ``load`` at
    40 rad/s (a viscous load, like the seed's, damps the drive's torsional mode); 1.1 m/s belt speed
    renews the belt on the arcs every 0.08 s, so the creep pattern settles within the run."""
    args = dict(pulleys__0__speed_time=[[0, 0], [0.05, -40.0]],
                pulleys__1__viscous_torque=load / 40.0, pulleys__1__inertia=2e-3)
    args.update(kw)
    return model_factory(**args)


SCHEMES = ["semi-implicit", "implicit"]


@pytest.fixture(scope="module", params=SCHEMES)
def loaded(model_factory, request):
    m = kinematic(model_factory, 5.0, simulation__duration=0.4, output__steady_window=[0.2, 0.4],
                  simulation__method=request.param)
    return m, drivedyn.run(m)


def test_tension_difference_is_torque_over_radius(loaded):
    _, r = loaded
    s = r.summary["spans"]
    tight, slack = s["driver-driven"]["tension_mean"], s["driven-driver"]["tension_mean"]
    assert tight - slack == pytest.approx(5.0 / R, rel=0.03)
    # 180 degree wraps: hub load = T1 + T2 along the centre line
    assert r.summary["pulleys"]["driven"]["hub_load"] == pytest.approx(tight + slack, rel=0.01)


def test_creep_on_each_pulley_follows_the_tensions(loaded):
    """Belt speeds in the spans obey mass conservation, v ~ 1 + T/EA (Reynolds' creep): the belt
    leaves the driver slower and the driven pulley faster than it arrived."""
    _, r = loaded
    s = r.summary
    T1, T2 = s["spans"]["driver-driven"]["tension_mean"], s["spans"]["driven-driver"]["tension_mean"]
    expect = (T1 - T2) / (1.52e5 + T1)
    assert s["pulleys"]["driver"]["creep"] == pytest.approx(expect, rel=0.2)
    assert s["pulleys"]["driven"]["creep"] == pytest.approx(-expect * (1.52e5 + T1) / (1.52e5 + T2), rel=0.2)
    # belt speed = driver surface speed, up to the chordal action of the rigid 12 mm segments,
    # which ride on the pulley like a chain, at about sqrt(r^2 + l^2/4) (+2 % here)
    v = s["spans"]["driver-driven"]["speed_mean"]
    assert 1.0 < abs(v) / (40 * 0.027) < 1.025


@pytest.mark.parametrize("method", SCHEMES)
def test_creep_slip_matches_tension_difference_over_EA(model_factory, method):
    # a softer belt makes the creep large enough to measure: (T1 - T2)/EA = 185 / 2e4 = 0.93 %
    m = kinematic(model_factory, 5.0, belt__axial_stiffness=2e4, simulation__duration=0.4,
                  output__steady_window=[0.2, 0.4], simulation__method=method)
    r = drivedyn.run(m)
    s = r.summary["spans"]
    creep = (s["driver-driven"]["tension_mean"] - s["driven-driver"]["tension_mean"]) / 2e4
    assert r.summary["pulleys"]["driven"]["slip"] == pytest.approx(creep, rel=0.15)


@pytest.mark.parametrize("method", SCHEMES)
@pytest.mark.parametrize("factor, slipping", [(0.8, False), (1.25, True)])
def test_gross_slip_at_the_capstan_limit(model_factory, factor, slipping, method):
    mu, T0 = 0.3, 300.0
    M_crit = 2 * T0 * R * math.tanh(mu * math.pi / 2)   # T1/T2 = e^(mu pi), T1 + T2 = 2 T0
    m = kinematic(model_factory, factor * M_crit, friction__coefficient=mu, belt__pretension=T0,
                  simulation__duration=0.35, output__steady_window=[0.25, 0.35], simulation__method=method)
    slip = drivedyn.run(m).summary["pulleys"]["driven"]["slip"]
    if slipping:   # the viscous load slows the driven pulley until it asks for M_crit: slip ~ 1 - 1/1.25
        assert slip > 0.12
    else:
        assert 0 < slip < 0.02


def _free_vibration(model, steps, nsamp):
    """Give the upper span a transverse velocity V sin(pi s / L) and integrate with the kernel.

    Returns the system, sample times, mid-span y and the energies at the samples."""
    sysm = build(model)
    S = new_state(sysm)
    x, y, vy = S.x, S.y, S.vy
    upper = (y > 0.02) & (x > 0.0) & (x < 0.515)
    vy[upper] = 0.5 * np.sin(np.pi * x[upper] / 0.515)
    W = new_work(sysm)
    lin = True if sysm.belt.implicit else None
    mid = int(np.argmin(np.abs(x - 0.2575) + 10 * ~upper))

    def energy():
        return K.energy(*sysm.groups, S)

    E0, ts, ys, Es = energy(), [], [], []
    t = 0.0
    for _ in range(nsamp):
        t = K.step_chunk(steps, t, sysm.step, *sysm.groups, S, W, lin)
        ts.append(t)
        ys.append(y[mid])
        Es.append(energy() - E0)
    return np.array(ts), np.array(ys), np.array(Es)


@pytest.mark.parametrize("method", SCHEMES)
def test_span_frequency_is_the_string_frequency(model_factory, method):
    # held pulleys (prescribed zero speed), no gravity: the upper span swings in its first mode
    m = model_factory(belt__segments=150, pulleys__0__speed_time=[[0, 0]], pulleys__1__speed_time=[[0, 0]],
                      simulation__method=method)
    steps = 40 if method == "semi-implicit" else 4      # samples every ~0.12 ms
    t, y, _ = _free_vibration(m, steps, 600)
    y = y - y.mean()
    up = np.nonzero((y[:-1] < 0) & (y[1:] >= 0))[0]
    f = (len(up) - 1) / (t[up[-1]] - t[up[0]])
    f_string = math.sqrt(550 / 0.096) / (2 * 0.515)       # 73.5 Hz
    assert f == pytest.approx(f_string, rel=0.02)


@pytest.mark.parametrize("method, law", [(s, "threlfall") for s in SCHEMES] + [("implicit", "elastic-plastic")])
def test_energy_is_conserved_without_damping_and_friction(model_factory, method, law):
    m = model_factory(friction__coefficient=0.0, belt__axial_damping=0.0, contact__damping=0.0, belt__segments=150,
                      simulation__method=method, friction__law=law)
    ke0 = 0.5 * 0.096 * 0.515 * 0.5 ** 2 / 2          # kinetic energy of the initial sine velocity
    steps = 40 if method == "semi-implicit" else 4
    _, _, E = _free_vibration(m, steps, 600)
    # symplectic Euler: a bounded energy error (from the stiff modes near the step limit), no drift
    assert np.max(np.abs(E)) < 0.1 * ke0
    assert abs(E[-100:].mean() - E[:100].mean()) < 0.01 * ke0
    # and the error is first order in the step
    h = build(m).step
    _, _, E2 = _free_vibration(drivedyn.replace(m, {"simulation.step": h / 2}), 2 * steps, 600)
    assert np.max(np.abs(E2)) < 0.65 * np.max(np.abs(E))


def test_energy_balance_closes(loaded):
    _, r = loaded
    p = r.summary["power"]
    assert p["energy_residual_relative"] < 1e-3
    assert p["input"] > p["output"] > 0.95 * p["input"]


def test_converged_in_step(loaded):
    m, r = loaded
    r2 = drivedyn.run(drivedyn.replace(m, {"simulation.step": r.summary["solver"]["step"] / 2}))
    for sp in ("driver-driven", "driven-driver"):
        assert r2.summary["spans"][sp]["tension_mean"] == pytest.approx(r.summary["spans"][sp]["tension_mean"], rel=5e-3)
    # the window lies within the belt's first passage round the loop (1.1 s at 1.1 m/s), where the
    # slip still drifts (0.164-0.186 % in 0.2-0.4 s, 0.197-0.201 % in 0.4-0.8 s); there the implicit
    # scheme at its default step (h omega_c = 2 on the contact mode) lags its half step by 0.017
    # points (0.022 with the chord-read anchors), the semi-implicit one by 0.0003. Later windows
    # agree within 0.004 points, but their tension means wander by 0.8 % with the belt's pattern.
    tol = 2e-4 if m.simulation.method == "semi-implicit" else 2.5e-4
    assert r2.summary["pulleys"]["driven"]["slip"] == pytest.approx(r.summary["pulleys"]["driven"]["slip"], abs=tol)


def test_converged_in_segments(loaded):
    # the transmitted tension difference and the slip converge as the belt is refined; the mean
    # tension level of the spans shifts by a few per cent with n (noted in the README)
    m, r = loaded
    runs = {n: drivedyn.run(drivedyn.replace(m, {"belt.segments": n})).summary for n in (50, 300)}
    runs[100] = r.summary
    dT = {n: s["spans"]["driver-driven"]["tension_mean"] - s["spans"]["driven-driver"]["tension_mean"]
          for n, s in runs.items()}
    assert abs(dT[100] - dT[300]) < 0.02 * dT[300]
    assert abs(dT[50] - dT[300]) > abs(dT[100] - dT[300])
    assert runs[300]["pulleys"]["driven"]["slip"] == pytest.approx(dT[300] / 1.52e5, rel=0.25)


def test_rotation_mass_scaling_at_low_belt_speed(loaded):
    """Semi-implicit scheme, opt-in: scaling the segments' rotational inertia by 3.3 lets the step grow from the
    rotation-mode limit to the zig-zag limit. At this belt speed (1.1 m/s) the drive's response
    must not change by more than 0.5 % (at 11 m/s, in the accessory drive, the contact losses do:
    hence off by default)."""
    m, r0 = loaded
    if m.simulation.method != "semi-implicit":
        pytest.skip("the implicit scheme's step is not set by the rotation modes")
    r = drivedyn.run(drivedyn.replace(m, {"simulation.rotation_scaling": True}))
    assert r.summary["solver"]["step"] > 1.4 * r0.summary["solver"]["step"]
    for sp in ("driver-driven", "driven-driver"):
        assert r.summary["spans"][sp]["tension_mean"] == pytest.approx(r0.summary["spans"][sp]["tension_mean"], rel=5e-3)
    # slip within 0.03 points (measured 0.006 with the belt placed at 585 N, 0.024 settled at the
    # continuum's 602 N: the scaled rotation shifts the seating of the 12 mm segments)
    assert r.summary["pulleys"]["driven"]["slip"] == pytest.approx(r0.summary["pulleys"]["driven"]["slip"], abs=3e-4)


def test_rkf45_agrees_with_semi_implicit(model_factory):
    m = kinematic(model_factory, 3.0, friction__velocity_threshold=5e-2, simulation__duration=0.04, belt__segments=60,
                  simulation__method="semi-implicit")
    a = drivedyn.run(m)
    b = drivedyn.run(drivedyn.replace(m, {"simulation.method": "rkf45"}))
    assert b.summary["solver"]["method"] == "rkf45"
    sa, sb = a.ds["speed"].values[:, 1], b.ds["speed"].values[:, 1]
    assert np.max(np.abs(sa - sb)) < 0.01 * np.max(np.abs(sa))


@pytest.mark.slow
def test_seed_5pk_case():
    """Kubas (seed 000) sec. 4: slip just under 1.5 %, slack ~250 N, tight ~780 N, speed ~ -22 rad/s
    (the model as described has too few losses for -22: a lossless drive with this load law settles
    at -25.1 rad/s, see README), at the seed's 150 segments; the example's "auto" count (424) reads
    279 / 834 N, which steady creep theory confirms (tests/belt/test_steady.py), and the run at 150
    says its error is not known."""
    r = drivedyn.run(seed_5pk())
    assert {d.code for d in r.diagnostics} == {"coarse-discretisation"}
    s = r.summary
    assert 0 < s["pulleys"]["driven"]["slip"] < 0.015
    assert s["spans"]["driver-driven"]["tension_mean"] == pytest.approx(780, rel=0.06)
    assert s["spans"]["driven-driver"]["tension_mean"] == pytest.approx(250, rel=0.1)
    assert -26 < s["pulleys"]["driver"]["speed_mean"] < -22


def test_runaway_driver_in_gross_slip_stays_stable():
    """Drive torque above the capstan limit at low pretension: the driver runs away while the slack
    span nearly unloads (its gaps then point anywhere, so the axial dampers act on the segments'
    rotation). Regression: the explicit damper blew up here; the implicit one does not."""
    base = drivedyn.load(drivedyn.example_path("belt-5pk"))
    m = drivedyn.replace(base, {"belt.pretension": 200.0, "simulation.duration": 0.4, "output.frames": 2,
                                "pulleys.driver.torque_time": [[0, 0], [0.3, -20.0]],
                                "pulleys.driven.torque_speed": [[-25.13, 20.0], [25.13, -20.0]]})
    r = drivedyn.run(m)
    w = r.ds["speed"].values
    assert w[-1, 0] < -50 and w[-1, 1] > -20          # the driver runs away, the driven is left behind
    # gross slip at 1 m/s dissipates ~90 % of the input; the balance still closes to a few 1e-3
    assert r.summary["power"]["energy_residual_relative"] < 3e-3
