"""A synchronous belt in the rotational model (rotational/teeth.py): each grooved wrap a quasi-static
tooth chain, the belt passing its grooves one pitch per groove. Against the quasi-static shear-lag
chain of mechanics/teeth/loadshare.py (solved there by its own Newton iteration) and Gerbert's
closed form for the linear chain, the tooth ratio, the energy balance and the periodic run-up."""
import math
from pathlib import Path

import numpy as np
import pytest

import drivedyn
from drivedyn.mechanics.teeth.loadshare import Chain, solve, teeth_in_mesh

HTD = (Path(__file__).parent / "htd8m-teeth.toml").read_text()


@pytest.fixture(scope="module")
def crawl(tmp_path_factory):
    path = tmp_path_factory.mktemp("rteeth") / "htd.toml"
    path.write_text(HTD)
    model = drivedyn.replace(drivedyn.load(path), {"simulation.model": "rotational"})
    return model, drivedyn.run(model)


def _wrap_loads(res, name):
    """The pulley's tooth loads at the last sample in belt order (first slot after the wrap's gap)."""
    q = res.ds["tooth_load"].sel(toothed_pulley=name).isel(time=-1).values
    start = np.flatnonzero(~np.isfinite(np.roll(q, 1)) & np.isfinite(q))[0]
    n = int(np.isfinite(q).sum())
    return q[[(start + k) % len(q) for k in range(n)]]


def test_tooth_loads_are_the_quasi_static_chains_between_the_runs_span_tensions(crawl):
    """60 rpm under 10 N m: the driven pulley's tooth loads equal loadshare.solve's chain (no play, no
    land friction, teeth unloaded at the rest tension: T_ref = the rest tension, no pitch error) between
    the run's span tensions, tooth by tooth; they fall from the tight side as Gerbert's linear chain,
    by tau_(i-1) - (2 + k_t / k_c) tau_i + tau_(i+1) = 0."""
    model, res = crawl
    assert res.success, res.message
    q = _wrap_loads(res, "driven")
    ten = res.ds["span_tension"].isel(time=-1)
    T_in, T_out = float(ten.sel(span="driver-driven")), float(ten.sel(span="driven-driver"))
    k_t = res.summary["teeth"]["tooth_stiffness"]
    wrap = 2 * math.pi - 2 * math.acos((56.0225 - 28.0113) / 251.5)       # the larger pulley's wrap
    n = teeth_in_mesh(44, wrap)
    assert len(q) == n
    T0 = res.summary["belt"]["pretension"]
    chain = Chain(teeth=n, pitch=8e-3, radius=56.0225e-3, tooth_stiffness=k_t, cord_stiffness=1.0e5,
                  friction=0.0, pitch_error=0.0)
    tight, slack = max(T_in, T_out), min(T_in, T_out)
    ref = solve(chain, tight, slack, T0).tooth_load
    run = q if abs(q[0]) > abs(q[-1]) else q[::-1]
    run = run * np.sign(run[0])
    assert np.max(np.abs(run - ref)) < 1e-6 * np.max(np.abs(ref)), (run, ref)
    # Gerbert's recurrence on every inner tooth (loads A mu^i + B mu^-i, mu + 1 / mu = 2 + k_t / k_c)
    kc = 1.0e5 / 8e-3
    rec = run[:-2] - (2 + k_t / kc) * run[1:-1] + run[2:]
    assert np.max(np.abs(rec)) < 1e-9 * np.max(np.abs(run))
    assert run[0] > 1.5 * run[n // 2]          # the loads fall from the tight side
    # and the teeth carry the span tensions' difference
    assert run.sum() == pytest.approx(tight - slack, rel=1e-9)


def test_no_creep_the_speed_ratio_over_the_window_is_the_tooth_ratio(crawl):
    """The driven pulley turns 22/44 of the driver: held at a steady load until the load step's ringing
    has died away (the spans' damper raised to 20 N s, 1 s), over the last 0.1 s to 1e-9 (measured
    4e-14), where a friction belt's creep at this load takes T / EA = 3e-3; and at the test drive's own
    light damping its angle never leaves the driver's by more than the chains' and spans' stretch."""
    model, res = crawl
    damped = drivedyn.run(drivedyn.replace(model, {"belt.axial_damping": 20.0, "simulation.duration": 1.0,
                                                   "output.steady_window": [0.9, 1.0]}))
    th = damped.ds["angle"].sel(time=slice(0.9, 1.0)).values
    ratio = (th[-1, 1] - th[0, 1]) / (th[-1, 0] - th[0, 0])
    assert abs(ratio - 0.5) < 1e-9, ratio
    lag = np.abs(res.ds["angle"].values[:, 1] * 56.0225e-3 - res.ds["angle"].values[:, 0] * 28.0113e-3)
    T = res.ds["span_tension"].values
    stretch = (T.max() - T.min()) * 0.26 / 1.0e5 + 2 * np.nanmax(np.abs(res.ds["tooth_load"].values)) / \
        res.summary["teeth"]["tooth_stiffness"]
    assert lag.max() < 2 * stretch + 1e-5 * res.ds["angle"].values[-1, 0] * 28e-3


def test_a_pitch_difference_leaves_the_tooth_ratio(crawl):
    """A driven pulley 0.3 % larger than its grooves' pitch radius (within the 0.5 % the model allows): the
    belt still passes one belt pitch per groove, so the speed ratio stays the tooth ratio 22/44 (within
    1e-9), where the radii's ratio would put it 0.3 % off (a friction belt's kinematics)."""
    model, _ = crawl
    r = 56.0225e-3 * 1.003
    bigger = drivedyn.replace(model, {"pulleys.driven.radius": r, "belt.axial_damping": 20.0, "simulation.duration": 1.0,
                                      "output.steady_window": [0.9, 1.0]})
    res = drivedyn.run(bigger)
    th = res.ds["angle"].sel(time=slice(0.9, 1.0)).values
    ratio = (th[-1, 1] - th[0, 1]) / (th[-1, 0] - th[0, 0])
    assert abs(ratio - 0.5) < 1e-9, ratio
    assert abs(28.0113e-3 / r - 0.5) > 1e-3


def test_the_energy_balance_closes_with_the_chains(crawl, tmp_path):
    """Work in = dissipation + energy change within 1e-3 of the work over the window, at a crawl and with
    a crank order that makes the chains work (their energy counted from the rest state)."""
    model, res = crawl
    assert res.summary["power"]["energy_residual_window"] < 1e-3
    excited = drivedyn.replace(model, {"pulleys.driver.speed_orders": [{"order": 2, "angle": 0.01}],
                                       "pulleys.driver.speed_time": [[0.0, 0.0], [0.1, 100.0]]})
    r2 = drivedyn.run(excited)
    assert r2.summary["power"]["energy_residual_window"] < 1e-2
    assert r2.summary["teeth"]["pulleys"]["driven"]["phase_error_orders"][0]["order"] == 2.0


def test_the_cam_drive_runs_up_periodically_with_its_teeth():
    """examples/timing-cam-drive.toml as a periodic run-up 800-6000 rpm in the rotational model: the speeds
    settle (one that does not is said), the run-up tables hold every span, the verdict reads the teeth."""
    model = drivedyn.load(drivedyn.example_path("timing-cam-drive"))
    up = drivedyn.replace(model, {"simulation.model": "rotational", "simulation.runup": "periodic",
                                  "simulation.duration": 1.0, "output.steady_window": None,
                                  "output.runup_bin": 2 * math.pi * 400 / 60,
                                  "pulleys.CRK.speed_time": [[0.0, 800 * math.pi / 30], [1.0, 6000 * math.pi / 30]]})
    res = drivedyn.run(up)
    ru = res.summary["runup"]
    assert ru["method"] == "periodic" and len(ru["speed_rpm"]) >= 12
    # the tensioner's friction damper sticks and slips: a speed whose period does not settle is said
    res_ = np.array(ru["periodic_residual"])
    assert np.mean(res_ <= 1e-4) >= 0.9
    assert (res_.max() <= 1e-4) or any(d.code == "unconverged-periodic" for d in res.diagnostics)
    assert set(ru["span_tension_max"]) == {"CRK-CAM1", "CAM1-CAM2", "CAM2-TEN", "TEN-CRK"}
    crit = res.summary["criteria"]
    assert "jump_margin" in crit and "tooth_jumps" not in crit


def test_the_phase_error_is_judged_against_its_limit(crawl):
    """criteria.phase_error_max judges the largest peak-to-peak transmission error (summary.teeth): a crank
    order makes one; below the run's own it fails, above it passes; without a limit it is not judged."""
    model, _ = crawl
    excited = drivedyn.replace(model, {"pulleys.driver.speed_orders": [{"order": 2, "angle": 0.01}]})
    res = drivedyn.run(excited)
    pp = res.summary["teeth"]["pulleys"]["driven"]["phase_error_pp"]
    assert pp > 1e-4 and "phase_error" not in res.summary["criteria"]
    for limit, ok in ((0.5 * pp, False), (2 * pp, True)):
        r = drivedyn.run(drivedyn.replace(excited, {"criteria.phase_error_max": math.radians(limit)}))
        crit = r.summary["criteria"]["phase_error"]
        assert crit["value"] == pytest.approx(pp) and crit["limit"] == pytest.approx(limit) and crit["pass"] is ok
