"""Tensioners (pivoted arm, slider) on the seed's accessory drive: static equilibrium against the
moment of the span tensions about the pivot, the arm's small free oscillation against a linear
belt-arm model written here, energy balance with tensioner damping and friction, bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.dynamics import _bodies as BK
from drivedyn.mechanics.layout import compute_layout
from drivedyn.belt.segments.state import new_state, new_work
from drivedyn.belt.segments.system import build
from drivedyn.core.errors import ModelError
from drivedyn.core.model import from_dict, to_dict

PIVOT = (-0.020, -0.200)     # below the idler (-20, -130) mm: a 70 mm arm pointing up


def accessory(arm=None, slider=None, **sim):
    """The seed's accessory drive (4 pulleys, idler on the back of the belt) with its idler on a
    tensioner, no crank torque (at rest) unless sim says otherwise."""
    d = to_dict(drivedyn.load(drivedyn.example_path("belt-accessory")))
    d["pulleys"][0].pop("torque_time", None)
    # the count these tests were written and measured at (the example's "auto" takes 337)
    d["belt"]["segments"] = 110
    if arm is not None:
        spring = {} if "spring_table" in arm else {"preload": "24 N*m", "rate": "20 N*m/rad"}   # the table is the spring
        d["pulleys"][3]["arm"] = {"pivot": [f"{PIVOT[0]} m", f"{PIVOT[1]} m"], "inertia": "1.5e-3 kg*m^2",
                                  **spring, **arm}
    if slider is not None:
        d["pulleys"][3]["slider"] = {"direction": [1.0, 0.0], "mass": "0.5 kg", "preload": "340 N", **slider}
    d["simulation"] = {"duration": 0.05, **sim.pop("simulation", {})}
    d["output"] = {"interval": "1 ms", "frames": 2, "segments": [0], **sim.pop("output", {})}
    for k, v in sim.items():
        d[k] = v
    return from_dict(d)


def _moment_of_spans(model, r, name="idler"):
    """Hub force of the two spans at the idler from their tensions in the run and the layout at
    the arm's angle, and its moment about the pivot (N m) and the idler centre."""
    j = [p.name for p in model.pulleys].index(name)
    psi = r.summary["tensioners"][name]["arm_angle_mean"]
    L = math.hypot(model.pulleys[j].center[0] - PIVOT[0], model.pulleys[j].center[1] - PIVOT[1])
    c = (PIVOT[0] + L * math.cos(psi), PIVOT[1] + L * math.sin(psi))
    pulleys = [p.model_copy(update={"center": c}) if k == j else p for k, p in enumerate(model.pulleys)]
    lay = compute_layout(model.model_copy(update={"pulleys": pulleys}))
    F = np.zeros(2)
    for sp in lay.spans:
        u = np.array([math.cos(sp.angle), math.sin(sp.angle)])
        T = r.summary["spans"][sp.name]["tension_mean"]
        if sp.start == j:
            F += T * u           # the leaving span pulls the pulley along it
        if sp.end == j:
            F -= T * u           # the arriving span pulls it back
    return (c[0] - PIVOT[0]) * F[1] - (c[1] - PIVOT[1]) * F[0], c


def test_arm_static_equilibrium_against_span_moments():
    m = accessory(arm={})
    r = drivedyn.run(m)
    assert {d.code for d in r.diagnostics} <= {"coarse-discretisation"}, r.message     # 2 segments on the idler, on purpose
    t = r.summary["tensioners"]["idler"]
    # at rest nothing moves: the equilibrium is exact for the discrete model
    assert t["travel_max"] - t["travel_min"] < 1e-8
    assert np.abs(r.ds["speed"].values).max() < 1e-5
    M, _ = _moment_of_spans(m, r)
    spring = 24.0 - 20.0 * t["travel_mean"]
    # the spring torque (into the belt) balances the moment of the span tensions about the pivot,
    # to the discretisation (2 segments of 9.9 mm on the idler's 36 degree wrap: -0.65 %; 220
    # segments: -0.02 %; 440: +0.27 %, measured)
    assert abs(abs(M) - spring) < 0.01 * spring, (M, spring)
    assert t["rest_spring_torque"] == pytest.approx(spring, rel=1e-9)
    d = to_dict(accessory(arm={}, simulation={"duration": 0.005}))
    d["belt"]["segments"] = 220
    m2 = from_dict(d)
    r2 = drivedyn.run(m2)
    M2, _ = _moment_of_spans(m2, r2)
    spring2 = 24.0 - 20.0 * r2.summary["tensioners"]["idler"]["travel_mean"]
    assert abs(abs(M2) - spring2) < 0.003 * spring2, (M2, spring2)
    # a stiffer preload pushes further into the belt and raises the tension
    r3 = drivedyn.run(accessory(arm={"preload": "30 N*m"}, simulation={"duration": 0.005}))
    t2 = r3.summary["tensioners"]["idler"]
    assert t2["travel_mean"] > t["travel_mean"] and t2["rest_tension"] > t["rest_tension"]


def test_arm_free_oscillation_against_linear_model():
    # heavy arm (0.01 kg m^2), other pulleys practically held (inertia 1e3), a light idler: the
    # arm swings against the belt between alternator and crankshaft: k = rate + EA g^2 / L_s
    # + T L'' (g = dL/dq, L_s the belt length between the held pulleys over the idler)
    # The contact is made 10 times stiffer than the example's: its compliance in series with the
    # belt (about 3.6e6 N/m radially at the idler against the belt's 2.1e5) would lower the
    # frequency by 2.8 % and is not in the linear model.
    d = to_dict(accessory(arm={"inertia": "0.01 kg*m^2"}))
    for p in d["pulleys"]:
        p["inertia"] = 1e3 if p["name"] != "idler" else 1e-6
    d["contact"]["stiffness_linear"] = 10 * float(d["contact"]["stiffness_linear"])
    d["contact"]["stiffness_quadratic"] = 10 * float(d["contact"]["stiffness_quadratic"])
    m = from_dict(d)
    sysm = build(m)
    S, W = new_state(sysm), new_work(sysm)
    S.qd[0] = 0.02                                   # rad/s: a small kick
    h = sysm.step
    nsub = max(1, int(2e-5 / h))
    qs, ts, t = [], [], 0.0
    for _ in range(2500):                            # 50 ms
        t = K.step_chunk(nsub, t, h, *sysm.groups, S, W)
        qs.append(S.q[0] - sysm.rest.travel[0])
        ts.append(t)
    qs, ts = np.array(qs), np.array(ts)
    up = np.nonzero((qs[:-1] < 0) & (qs[1:] >= 0))[0]
    tc = ts[up] - qs[up] * (ts[up + 1] - ts[up]) / (qs[up + 1] - qs[up])
    f_sim = (len(tc) - 1) / (tc[-1] - tc[0])

    # the linear model: path length L(q) from the layout, tension T and EA
    j, q0 = 3, sysm.rest.travel[0]
    A = sysm.arms

    def path(q):
        c = BK.arm_centre(A, 0, q)[:2]
        pulleys = [p.model_copy(update={"center": c}) if k == j else p for k, p in enumerate(m.pulleys)]
        return compute_layout(m.model_copy(update={"pulleys": pulleys}))

    dq = 1e-4
    g = (path(q0 + dq).length - path(q0 - dq).length) / (2 * dq)
    Lpp = (path(q0 + dq).length - 2 * path(q0).length + path(q0 - dq).length) / dq ** 2
    lay = path(q0)
    names = [sp.name for sp in lay.spans]
    L_s = lay.spans[names.index("alternator-idler")].length + lay.spans[names.index("idler-crankshaft")].length \
        + lay.radii[j] * lay.wrap[j]
    T = sysm.rest.tension
    k = 20.0 + m.belt.axial_stiffness * g * g / L_s + T * Lpp
    f_lin = math.sqrt(k / 0.01) / (2 * math.pi)
    assert f_sim == pytest.approx(f_lin, rel=0.03), (f_sim, f_lin)
    # the drive's linearised modes (modes.py, with the arm as a DOF) hold the belt to the wraps: the
    # free idler turns, the wrap on it does not stretch (L1 + L2 in place of L_s). The run, kicked
    # by 0.02 rad/s, slides at micro-slip speeds inside the friction law's regularisation, so its
    # wrap stretches too: the two bound the mode (5 % apart here)
    from drivedyn.belt.steady.modes import modes
    md = modes(m)
    f_mode = min(md.frequencies_hz, key=lambda f: abs(f - f_sim))
    k_held = 20.0 + m.belt.axial_stiffness * g * g / (L_s - lay.radii[j] * lay.wrap[j]) + T * Lpp
    assert f_mode == pytest.approx(math.sqrt(k_held / 0.01) / (2 * math.pi), rel=0.01), md.frequencies_hz
    assert f_sim < f_mode < 1.07 * f_sim
    k_arm = max(range(len(md.frequencies_hz)), key=lambda k: md.participation[k].get("idler.arm", 0))
    assert md.frequencies_hz[k_arm] == f_mode


def test_energy_balance_with_tensioner_damping_and_friction():
    m = accessory(arm={"damping": "0.05 N*m*s/rad", "friction": "0.5 N*m", "friction_asymmetry": 3.0},
                  simulation={"duration": 0.2},
                  output={"interval": "1 ms", "frames": 2, "steady_window": [0.1, 0.2]})
    d = to_dict(m)
    d["pulleys"][0]["torque_time"] = [[0, 0], [0.1, -15.0]]   # the crank loads the drive: the arm swings
    d["pulleys"][2]["viscous_torque"] = 0.5
    r = drivedyn.run(from_dict(d))
    D = r.ds["dissipated"].sel(mechanism="tensioner").values
    t = r.summary["tensioners"]["idler"]
    assert t["travel_max"] - t["travel_min"] > 1e-4          # the arm moved
    assert D[-1] > 0                                         # and its damping took energy
    resid = abs(float(r.ds["energy_residual"].values[-1]))
    assert resid < 0.01 * float(r.ds["work_in"].values[-1]), (resid, float(r.ds["work_in"].values[-1]))


def test_slider_equilibrium_and_fixed_force():
    # a fixed-force slider (rate 0) along x: the spans' hub force along x equals the force
    m = accessory(slider={"preload": "340 N"})
    r = drivedyn.run(m)
    assert {d.code for d in r.diagnostics} <= {"coarse-discretisation"}, r.message
    t = r.summary["tensioners"]["idler"]
    assert t["slide_max"] - t["slide_min"] < 1e-9
    j = 3
    hx = float(r.ds["hub_force_x"].isel(pulley=j).values[-1])
    assert abs(hx) == pytest.approx(340.0, rel=0.005)


@pytest.mark.parametrize("change, words", [
    ({"arm": {"pivot": ["-20 mm", "-130 mm"]}}, "pivot lies at the pulley's centre"),
    ({"arm": {"preload": "1 N*m", "rate": "0 N*m/rad"}}, "spring cannot hold the belt"),
    ({"arm": {"stops": ["-0.001 rad", "0.5 rad"], "preload": "20 N*m"}}, "stop"),
    ({"arm": {"damping": "-1 N*m*s/rad"}}, "damping"),
    ({"belt_length": 1.2, "arm": {"stops": ["-0.1 rad", "0.05 rad"]}}, "slack"),
])
def test_bad_tensioner_input_is_one_line(change, words):
    d = to_dict(accessory(arm={}))
    arm = d["pulleys"][3]["arm"]
    arm.update(change.get("arm", {}))
    if "belt_length" in change:
        d["belt"].pop("pretension")
        d["belt"]["length"] = change["belt_length"]
    with pytest.raises(ModelError) as e:
        build(from_dict(d))
    msg = str(e.value)
    assert "\n" not in msg and words in msg, msg


def test_spring_table_matches_preload_and_rate_and_keeps_energy():
    # the table of the linear spring gives the same equilibrium (to 1e-10 rad: the belt's moment on the
    # arm comes from the rest tension, itself a root found to 1e-10 N, so the two equilibria's roots sit
    # a few 1e-12 rad apart); a stiffening table keeps the energy balance (its potential is the table's
    # exact integral) while the arm swings
    lin = build(accessory(arm={}), settle=False).rest
    tab = build(accessory(arm={"spring_table": [["-0.5 rad", "34 N*m"], ["0.5 rad", "14 N*m"]]}), settle=False).rest
    assert tab.travel[0] == pytest.approx(lin.travel[0], abs=1e-10)
    m = accessory(arm={"spring_table": [[-0.5, 40.0], [-0.01, 24.4], [0.0, 24.0], [0.01, 23.2], [0.5, 0.0]],
                       "damping": "0.02 N*m*s/rad"}, simulation={"duration": 0.2})
    d = to_dict(m)
    d["pulleys"][0]["torque_time"] = [[0, 0], [0.1, -15.0]]
    d["pulleys"][2]["viscous_torque"] = 0.5
    r = drivedyn.run(from_dict(d))
    t = r.summary["tensioners"]["idler"]
    assert t["travel_max"] - t["travel_min"] > 1e-4
    resid = abs(float(r.ds["energy_residual"].values[-1]))
    assert resid < 0.01 * float(r.ds["work_in"].values[-1])


def test_running_equilibrium_of_a_fixed_force_slider():
    # creep theory with the tensioner free to move: a fixed-force slider (rate 0) pushing along its
    # pulley's bisector holds the spans beside it at T - m v^2 = F / (2 sin(wrap / 2)), whatever
    # the loads; at rest it holds them at F / (2 sin(wrap / 2)) too (closed form, checked here)
    from drivedyn.belt.statics import check_data
    from drivedyn.belt.geometry.tensioner import equilibrium
    from drivedyn.belt.steady.running import running

    d = to_dict(drivedyn.load(drivedyn.example_path("belt-accessory-loaded")))
    lay = compute_layout(from_dict(d))
    hub = lay.hub_load_static(1.0)[3]
    d["pulleys"][3]["slider"] = {"direction": [float(-hub[0]), float(-hub[1])], "mass": "0.3 kg", "preload": "300 N"}
    m = from_dict(d)
    rest = equilibrium(m)
    q, m_run, lay_run, st = running(m, rest)
    j = 3
    wrap = lay_run.wrap[j]
    names = [sp.name for sp in lay_run.spans]
    t_in, t_out = st.spans[names[j - 1]], st.spans[names[j]]
    c = st.centrifugal
    assert st.state == "running" and c > 0
    assert t_in - c == pytest.approx(300 / (2 * math.sin(wrap / 2)), rel=1e-4)
    assert t_out - c == pytest.approx(300 / (2 * math.sin(wrap / 2)), rel=1e-4)
    wrap0 = compute_layout(rest.model).wrap[j]
    assert rest.tension == pytest.approx(300 / (2 * math.sin(wrap0 / 2)), rel=0.01)   # discrete belt at rest
    data = check_data(m)
    assert data["tensioners"]["idler"]["running_travel"] == pytest.approx(q[0])
    assert "running equilibrium" in " ".join(data["steady"]["notes"])


def test_at_rest_at_the_default_resolution():
    """At "auto" (337 segments) the belt and arm start at their static equilibrium: nothing moves
    (the relaxation needed 120 Newton steps there; with 60 it stopped short and the idler drifted
    at 0.1 rad/s)."""
    d = to_dict(accessory(arm={}))
    d["belt"]["segments"] = "auto"
    r = drivedyn.run(from_dict(d))
    assert r.status == "success", [x.text for x in r.diagnostics]
    t = r.summary["tensioners"]["idler"]
    assert t["travel_max"] - t["travel_min"] < 1e-8
    assert np.abs(r.ds["speed"].values).max() < 1e-5
