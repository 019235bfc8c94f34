"""A tensioner's damping as built: a mechanical tensioner's friction that grows with its spring's load
(``friction_share``, with ``friction_asymmetry``) and a hydraulic tensioner's damping that differs in and
out (``damping_away``). The tensioner stage (dynamics/_bodies.py ``_step_arms``, which both dynamic models
step) against references derived here:

- an imposed sinusoidal travel q0 + A sin(w t): the energy per cycle of viscous damping c is pi c w A^2,
  of damping c_in one way and c_out the other pi w A^2 (c_in + c_out) / 2 (each half cycle half of the
  symmetric loop's); of friction f0 + s Q(q) (into the belt, x a away) on a linear spring Q = P - k q it
  is 2 A (1 + a) (f0 + s Q(q0)) (the loop's area: each sweep integrates the friction, linear in q, over
  the stroke 2 A);
- a free decay on the spring with such friction falls linearly: between turning points, the spring's
  energy lost equals the friction's work, which gives the sum of two turning points from the equilibrium
  S = 2 a (f0 + s Q_e) / (k (1 + a s)) moving away from the belt and -2 (f0 + s Q_e) / (k (1 - s)) moving
  into it (Q_e the spring load at equilibrium; s = 0, a = 1: Coulomb's 4 f0 / k per cycle);
- a symmetric force on a damper stiffer one way pumps the mean travel: over a periodic motion the mean
  of m q'' is 0, so k <q - q_e> = (c_away - c_in) <|q'|> / 2, into the belt when the damper resists
  moving away more (the hydraulic tensioner's check valve); and the mean travel against a solve_ivp
  integration of the same equation written here;
- both models' energy balance with the new damping booked in the tensioner's mechanism.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

import drivedyn
from drivedyn.belt.dynamics import _bodies as BK
from drivedyn.belt.dynamics.bodies import arms_record
from drivedyn.belt.dynamics.checks import ENERGY_LIMIT
from drivedyn.core.errors import ModelError
from drivedyn.core.model import from_dict, to_dict
from drivedyn.mechanics.layout import compute_layout

MASS, RATE, PRELOAD = 0.5, 5000.0, 340.0     # the slider: kg, N/m, N


def accessory(slider=None, arm=None, **top):
    """The seed's accessory drive with its idler (pulley 3) on a slider or an arm."""
    d = to_dict(drivedyn.load(drivedyn.example_path("belt-accessory")))
    d["pulleys"][0].pop("torque_time", None)
    d["belt"]["segments"] = 110
    if slider is not None:
        d["pulleys"][3]["slider"] = {"direction": [1.0, 0.0], "mass": MASS, "preload": PRELOAD, "rate": RATE,
                                     **slider}
    if arm is not None:
        d["pulleys"][3]["arm"] = {"pivot": ["-0.020 m", "-0.200 m"], "inertia": "1.5e-3 kg*m^2",
                                  "preload": "24 N*m", "rate": "20 N*m/rad", **arm}
    d.update(top)
    return from_dict(d)


@njit
def _arms_step(na, pulley, kind, par, tab_off, tab_x, tab_y, q, qd, cx, cy, cvx, cvy, hx, hy, h):
    """The kernels' tensioner stage in a function of the test's own: the stage is inlined where the models
    call it, some of them compiled without numba's reference counting, and called from Python as it is
    after one of those compiles (the test suite's order) it crashed the process."""
    return BK._step_arms(na, pulley, kind, par, tab_off, tab_x, tab_y, q, qd, cx, cy, cvx, cvy, hx, hy, h)


class Stage:
    """The tensioner stage alone on the model's record, its hub force given per step: the pulley's
    force along the slide (N, + into the belt)."""

    def __init__(self, model):
        self.A = A = arms_record(model)
        nk = len(model.pulleys)
        self.j = int(A.pulley[0])
        self.q, self.qd = np.zeros(1), np.zeros(1)
        self.c = [np.zeros(nk) for _ in range(4)]
        self.hx, self.hy = np.zeros(nk), np.zeros(nk)

    def step(self, F, h):
        A, j = self.A, self.j
        self.hx[j] = F * A.par[0, BK.ARM_DX]
        self.hy[j] = F * A.par[0, BK.ARM_DY]
        return _arms_step(A.na, A.pulley, A.kind, A.par, A.tab_off, A.tab_x, A.tab_y, self.q, self.qd,
                          *self.c, self.hx, self.hy, h)


def imposed_cycle_energy(model, q0, amp, freq, cycles=3, steps=8000):
    """Energy the tensioner dissipates over the last two of ``cycles`` periods of an imposed travel
    q0 + amp sin(w t): the slider held on it by a stiff spring and damper (their own work is not the
    tensioner's)."""
    w = 2 * math.pi * freq
    h = 1.0 / freq / steps
    K = 1e8
    C = 0.5 * math.sqrt(K * MASS)
    st = Stage(model)
    st.q[0], st.qd[0] = q0, amp * w
    E = 0.0
    for n in range(cycles * steps):
        t = n * h
        q_imp, v_imp = q0 + amp * math.sin(w * t), amp * w * math.cos(w * t)
        # the spring's and preload's load is the tensioner's own: the holder cancels it by its stiffness
        F = K * (q_imp - st.q[0]) + C * (v_imp - st.qd[0])
        P = st.step(F, h)
        if n >= steps:
            E += h * P
    return E / (cycles - 1), w


@pytest.mark.parametrize("c_in, c_away", [(150.0, 150.0), (20.0, 400.0)])
def test_viscous_loop_energy_per_cycle(c_in, c_away):
    m = accessory(slider={"damping": c_in, "damping_away": c_away})
    amp = 2e-3
    E, w = imposed_cycle_energy(m, 0.0, amp, 20.0)
    ref = math.pi * w * amp ** 2 * 0.5 * (c_in + c_away)
    assert E == pytest.approx(ref, rel=1e-3), (E, ref)


@pytest.mark.parametrize("f0, share, asym", [(5.0, 0.0, 1.0), (0.0, 0.05, 1.0), (2.0, 0.04, 2.5)])
def test_friction_loop_energy_per_cycle(f0, share, asym):
    m = accessory(slider={"friction": f0, "friction_share": share, "friction_asymmetry": asym})
    q0, amp = 3e-3, 2e-3
    E, _ = imposed_cycle_energy(m, q0, amp, 20.0)
    ref = 2 * amp * (1 + asym) * (f0 + share * (PRELOAD - RATE * q0))
    # Threlfall's regularisation over friction_speed (1e-3 m/s) near the turning points (peak speed 0.25 m/s)
    assert E == pytest.approx(ref, rel=1e-3), (E, ref)


def turning_points(model, x0, hub, duration, h=1e-5):
    """Travel at each turning point of a free decay from rest at x0 under a constant hub force."""
    st = Stage(model)
    st.q[0] = x0
    out = [x0]
    prev = 0.0
    for _ in range(int(duration / h)):
        st.step(hub, h)
        v = st.qd[0]
        if v * prev < 0.0:
            out.append(st.q[0])
        if v != 0.0:
            prev = v
    return np.array(out)


@pytest.mark.parametrize("f0, share, asym", [(2.0, 0.0, 1.0), (2.0, 0.0, 1.5), (0.5, 0.008, 2.0)])
def test_free_decay_falls_linearly(f0, share, asym):
    m = accessory(slider={"friction": f0, "friction_share": share, "friction_asymmetry": asym,
                          "friction_speed": "1e-4 m/s", "stops": ["-0.05 m", "0.05 m"]})
    q_e = 0.004                              # the equilibrium: spring load Q_e = P - k q_e balances the hub
    Q_e = PRELOAD - RATE * q_e
    x0 = 0.020
    tp = turning_points(m, q_e + x0, -Q_e, 0.4) - q_e
    # the sums of successive turning points (closed form in the module's docstring)
    away = 2 * asym * (f0 + share * Q_e) / (RATE * (1 + asym * share))
    into = -2 * (f0 + share * Q_e) / (RATE * (1 - share))
    n = 6
    assert len(tp) > n + 1 and np.all(np.abs(tp[:n]) > 2 * max(away, -into)), tp   # still moving
    sums = tp[:n] + tp[1:n + 1]
    ref = np.array([away if k % 2 == 0 else into for k in range(n)])    # from x0 > 0 it moves away first
    assert np.allclose(sums, ref, rtol=1e-3, atol=0), (sums, ref)
    if share == 0.0 and asym == 1.0:
        assert tp[0] - tp[2] == pytest.approx(4 * f0 / RATE, rel=1e-3)    # Coulomb's decrement per cycle


def _asym_ode_mean(c_in, c_away, F1, w, t_end, t_avg):
    """Mean travel from the equilibrium over [t_end - t_avg, t_end] of m x'' + c(x') x' + k x = F1 sin(w t)
    (c = c_in moving into the belt, c_away away from it), by scipy."""
    from scipy.integrate import solve_ivp

    def f(t, y):
        c = c_in if y[1] >= 0 else c_away
        return [y[1], (F1 * math.sin(w * t) - c * y[1] - RATE * y[0]) / MASS]

    t = np.linspace(t_end - t_avg, t_end, 4001)
    sol = solve_ivp(f, (0.0, t_end), [0.0, 0.0], t_eval=t, rtol=1e-9, atol=1e-12, max_step=2e-4)
    return float(np.trapezoid(sol.y[0], t) / t_avg)


def test_hydraulic_tensioner_pumps_into_the_belt():
    c_in, c_away, F1, freq = 5.0, 200.0, 50.0, 30.0
    m = accessory(slider={"damping": c_in, "damping_away": c_away})
    st = Stage(m)
    w, h = 2 * math.pi * freq, 1e-5
    t_end, t_avg = 0.5, 0.2                 # the last 6 periods, after the mean's drift (c / k ~ 0.02 s)
    n_end, n_avg = round(t_end / h), round(t_avg / h)
    xs, vs = [], []
    for n in range(n_end):
        st.step(-PRELOAD + F1 * math.sin(w * (n + 1) * h), h)   # the spring's equilibrium at q = 0
        if n >= n_end - n_avg:
            xs.append(st.q[0])
            vs.append(st.qd[0])
    x_mean, v_abs = float(np.mean(xs)), float(np.mean(np.abs(vs)))
    # the mean force balance of a periodic motion, and the direction: into the belt
    assert x_mean > 0.0
    assert x_mean == pytest.approx((c_away - c_in) * v_abs / (2 * RATE), rel=1e-3)
    assert x_mean == pytest.approx(_asym_ode_mean(c_in, c_away, F1, w, t_end, t_avg), rel=2e-3)
    # swapped, the damper pumps the travel out of the belt by as much
    st2 = Stage(accessory(slider={"damping": c_away, "damping_away": c_in}))
    x2 = []
    for n in range(n_end):
        st2.step(-PRELOAD + F1 * math.sin(w * (n + 1) * h), h)
        if n >= n_end - n_avg:
            x2.append(st2.q[0])
    assert float(np.mean(x2)) == pytest.approx(-x_mean, rel=0.02)


def test_the_record_carries_the_keys():
    A = arms_record(accessory(slider={"damping": 3.0}))
    assert A.par[0, BK.ARM_VISC_AWAY] == 3.0 and A.par[0, BK.ARM_FSHARE] == 0.0     # none: damping both ways
    A = arms_record(accessory(arm={"damping": 0.01, "damping_away": "0.2 N*m*s/rad", "friction_share": 0.2}))
    assert A.par[0, BK.ARM_VISC] == 0.01 and A.par[0, BK.ARM_VISC_AWAY] == 0.2 and A.par[0, BK.ARM_FSHARE] == 0.2


def _loaded_run(method, arm):
    """The accessory drive loaded by the crank, its order-2 harmonic swinging the arm on: the window's
    tensioner dissipation and energy residual (J), and the run."""
    d = to_dict(accessory(arm=arm))
    d["simulation"] = {"duration": 0.2, "model": method}
    d["output"] = {"interval": "1 ms", "frames": 2, "segments": [0], "steady_window": [0.1, 0.2]}
    d["pulleys"][0]["torque_time"] = [[0, 0], [0.1, -15.0]]
    d["pulleys"][0]["harmonics"] = [{"order": 2, "amplitude": "3 N*m"}]
    d["pulleys"][2]["viscous_torque"] = 0.5
    r = drivedyn.run(from_dict(d))
    t = r.ds["time"].values
    D = r.ds["dissipated"].sel(mechanism="tensioner").values
    R = r.ds["energy_residual"].values
    i0, i1 = np.nonzero(t > 0.1)[0][[0, -1]]
    return D[i1] - D[i0], R[i1] - R[i0], r


@pytest.mark.parametrize("method", ["segments", "rotational"])
def test_energy_balance_with_the_tensioners_damping_as_built(method):
    arm = {"damping": "0.01 N*m*s/rad", "damping_away": "0.2 N*m*s/rad", "friction": "0.1 N*m",
           "friction_share": 0.15, "friction_asymmetry": 2.0}
    D, R, r = _loaded_run(method, arm)
    t = r.summary["tensioners"]["idler"]
    assert t["travel_max"] - t["travel_min"] > 1e-4 and D > 0
    assert r.summary["power"]["energy_residual_window"] < ENERGY_LIMIT      # the models' limit (dynamics/checks.py)
    if method == "segments":
        # what the window's balance leaves is far below what the tensioner took, and so over the whole run
        assert abs(R) < 0.01 * D, (D, R)
        resid = abs(float(r.ds["energy_residual"].values[-1]))
        assert resid < 0.01 * float(r.ds["work_in"].values[-1]), (resid, float(r.ds["work_in"].values[-1]))
    else:
        # the rotational model's own residual (its wraps' friction, 2 1/2 times the tensioner's dissipation
        # here, measured) is the same as without the tensioner's damping: the tensioner's is all booked
        _, R0, _ = _loaded_run(method, {})
        assert abs(R - R0) < 0.2 * D, (D, R, R0)


@pytest.mark.parametrize("change, words", [
    ({"friction_share": 1.0}, "friction_share"),
    ({"friction_share": -0.1}, "friction_share"),
    ({"damping_away": "-1 N*m*s/rad"}, "damping_away"),
])
def test_bad_damping_input_is_one_line(change, words):
    d = to_dict(accessory(arm={}))
    d["pulleys"][3]["arm"].update(change)
    with pytest.raises(ModelError) as e:
        from_dict(d)
    msg = str(e.value)
    assert "\n" not in msg and words in msg, msg


def test_an_eccentric_arm_balances_the_spans_moment_about_its_pivot():
    """An eccentric tensioner (a timing drive's: its pivot inside its pulley, 6 mm off the idler's centre)
    at rest: its spring torque equals the moment of the span tensions about the pivot (the balance
    tests/belt/test_tensioner.py checks on a long arm)."""
    pivot = (-0.020, -0.136)                      # the idler's centre (-20, -130) mm, radius 31 mm
    d = to_dict(accessory(arm={}))
    d["pulleys"][3]["arm"].update({"pivot": [pivot[0], pivot[1]], "preload": "1.6 N*m", "rate": "2 N*m/rad"})
    d["simulation"] = {"duration": 0.05}
    d["output"] = {"interval": "1 ms", "frames": 2, "segments": [0]}
    m = from_dict(d)
    r = drivedyn.run(m)
    t = r.summary["tensioners"]["idler"]
    assert t["travel_max"] - t["travel_min"] < 1e-8 and np.abs(r.ds["speed"].values).max() < 1e-5   # at rest
    psi = t["arm_angle_mean"]
    c = (pivot[0] + 0.006 * math.cos(psi), pivot[1] + 0.006 * math.sin(psi))
    pulleys = [p.model_copy(update={"center": c}) if k == 3 else p for k, p in enumerate(m.pulleys)]
    lay = compute_layout(m.model_copy(update={"pulleys": pulleys}))
    F = np.zeros(2)
    for sp in lay.spans:
        u = np.array([math.cos(sp.angle), math.sin(sp.angle)])
        T = r.summary["spans"][sp.name]["tension_mean"]
        F += T * u if sp.start == 3 else 0.0      # the leaving span pulls the pulley along it
        F -= T * u if sp.end == 3 else 0.0        # the arriving span pulls it back
    M = (c[0] - pivot[0]) * F[1] - (c[1] - pivot[1]) * F[0]
    spring = 1.6 - 2.0 * t["travel_mean"]
    assert abs(t["travel_mean"]) < 0.5 and abs(abs(M) - spring) < 0.01 * spring, (M, spring, t["travel_mean"])


def test_a_stop_is_stable_at_steps_its_explicit_spring_could_not_take():
    """The stops' spring is implicit in the tensioner stage: a slider pressed onto its stop (1e6 N/m on
    0.5 kg, 1414 rad/s) at a step 5x the explicit scheme's bound 2 / omega comes to rest at the static
    penetration and stays there."""
    kstop, qmax = 1e6, 0.01
    m = accessory(slider={"damping": 5.0, "stops": ["-0.05 m", f"{qmax} m"], "stop_stiffness": f"{kstop} N/m"})
    st = Stage(m)
    h = 5 * 2 / math.sqrt(kstop / MASS)
    F = 400.0                                        # with the spring's load, onto the upper stop
    q_ref = (F + PRELOAD + kstop * qmax) / (kstop + RATE)       # F + P - k q = k_stop (q - q_max)
    st.q[0] = qmax + 1e-4
    for _ in range(4000):
        st.step(F, h)
        assert abs(st.q[0] - q_ref) < 1e-3, st.q[0]     # bounded: the explicit stop diverged here
    assert st.q[0] == pytest.approx(q_ref, abs=1e-9) and abs(st.qd[0]) < 1e-9, (st.q[0], q_ref)


@pytest.mark.parametrize("h_omega", [0.02, 0.3, 1.0, 5.0, 50.0])
def test_a_bounce_on_the_stop_books_what_it_takes(h_omega):
    """A free slider (no spring, no damping) thrown onto its undamped stop at 1 m/s. At a step that
    resolves the stop (h omega < 1/2) the explicit stop gives back what it took to O((h omega)^2) of
    the impact's energy; at a longer one (backward Euler) the slider still comes back, and what the
    stage books as dissipated is what the rebound lacks, to round-off."""
    kstop, qmax, v0 = 1e6, 0.01, 1.0
    m = accessory(slider={"preload": "1e-9 N", "rate": "1e-9 N/m", "stops": ["-0.05 m", f"{qmax} m"],
                          "stop_stiffness": f"{kstop} N/m", "stop_damping": "1e-9 N*s/m"})
    st = Stage(m)
    h = h_omega / math.sqrt(kstop / MASS)
    st.q[0], st.qd[0] = 0.0, v0
    D = 0.0
    for _ in range(int(0.03 / h) + 10):
        D += h * st.step(0.0, h)
        if st.q[0] < qmax and st.qd[0] < 0:          # off the stop, on its way back
            break
    assert st.qd[0] < 0, "the slider did not come back off its stop"
    K1 = 0.5 * MASS * st.qd[0] ** 2
    K0 = 0.5 * MASS * v0 ** 2
    if h_omega < 0.5:
        assert abs(K1 - K0) < h_omega ** 2 * K0 and abs(D) < 1e-9 * K0, (K1, D, K0)
    else:
        assert K1 + D == pytest.approx(K0, rel=1e-9) and D > 0, (K1, D, K0)
