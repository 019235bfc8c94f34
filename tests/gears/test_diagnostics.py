"""Gear-train diagnostics against theory no one tuned: the RK4 stability bound, Mathieu's principal
parametric resonance, mode decay times; and the run contract (solver record, partial results)."""
import math
import subprocess
import sys

import numpy as np
import pytest

import drivedyn
from drivedyn.gears import simulate
from drivedyn.gears.train.checks import DECAY_TIMES, floquet_growth, rk4_step_limit
from drivedyn.gears.train.system import assemble

from .conftest import EXAMPLE, pair_model, seed_model

SOLVER_KEYS = {"method", "steps", "rejected_steps", "rhs_evaluations", "last_step", "wall_time", "simulated_time",
               "status"}


def codes(r):
    return [d.code for d in r.diagnostics]


def test_rk4_limit_is_2_sqrt_2_for_an_undamped_mode():
    """|R(iy)|^2 = 1 - y^6/72 + y^8/576 <= 1 iff y <= 2 sqrt 2: the limit h omega for a constant,
    undamped mesh is 2 sqrt 2 with omega = sqrt(k (1/m1 + 1/m2)) from the two inertias."""
    k = 449.9e6
    rb1, rb2 = 0.02625 * math.cos(math.radians(20)), 0.07125 * math.cos(math.radians(20))
    w = math.sqrt(k * (rb1 ** 2 / 1.47e-4 + rb2 ** 2 / 7.81e-3))
    s = assemble(pair_model(**{"meshes.0.stiffness": {"model": "constant", "mean": k}, "meshes.0.damping_ratio": 0.0}))
    h, w_max = rk4_step_limit(s)
    assert w_max == pytest.approx(w, rel=1e-6)
    assert h * w == pytest.approx(2 * math.sqrt(2), rel=1e-6)


def test_step_too_large_is_one_line_before_integrating(tmp_path):
    text = EXAMPLE.read_text().replace('step = "5e-6 s"', 'step = "2e-4 s"')
    model = tmp_path / "big-step.toml"
    model.write_text(text)
    out = tmp_path / "out"
    p = subprocess.run([sys.executable, "-m", "drivedyn.front.cli", "run", str(model), "-o", str(out), "-q"],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr and len(p.stderr.strip().splitlines()) == 1
    assert "simulation.step" in p.stderr and "step-too-large" in p.stderr
    assert not (out / "results.nc").exists()


def test_stiffness_lookup_survives_nan():
    s = assemble(seed_model())
    k = simulate.stiffness_at(s, np.array([[np.nan, 0.1], [0.0, np.inf]]))
    assert np.isnan(k[0, 0]) and np.isnan(k[1, 1]) and np.all(np.isfinite(k[[0, 1], [1, 0]]))


def _mathieu_pair(zeta):
    """One pair with the rectangular stiffness wave, run at mesh frequency = 2 f_n (principal
    parametric resonance of x'' + 2 zeta w x' + w^2 (1 + eps cos W t) x = 0)."""
    base = pair_model(**{"meshes.0.stiffness": {"model": "rectangular"}, "meshes.0.damping_ratio": zeta})
    s = assemble(base)
    f_n = s.modes()[0][0]
    speed = 2 * f_n * 2 * math.pi / 21                         # mesh frequency z1 omega / 2 pi = 2 f_n
    m = pair_model(**{"meshes.0.stiffness": {"model": "rectangular"}, "meshes.0.damping_ratio": zeta,
                      "drive.speed": speed, "simulation.duration": 0.002, "simulation.step": 1e-6})
    k = s.ktab()[0]
    eps = 2 * np.abs(np.fft.rfft(k)[1]) / len(k) / k.mean()     # first harmonic of k / mean, from the table
    return m, eps, 2 * math.pi * f_n


def test_kv_unstable_at_the_principal_parametric_resonance(quiet):
    """First-order Mathieu theory (e.g. Nayfeh & Mook, Nonlinear Oscillations, 5.4): at W = 2 w the
    solution grows when eps / 4 > zeta, at sigma = w (eps / 4 - zeta)."""
    m, eps, w = _mathieu_pair(0.01)
    assert eps / 4 > 3 * 0.01                                  # well inside the tongue
    r = drivedyn.run(m)
    assert "kv-unstable" in codes(r) and r.status == "warning"
    sigma = r.summary["floquet_growth_rate"]
    assert sigma == pytest.approx(w * (eps / 4 - 0.01), rel=0.25)
    # the simulated force amplitude grows at that rate too (not only the Floquet number)
    f = r.ds.mesh_force.values[:, 0]
    t = r.ds.time.values
    # 0.5-1 ms against 1-1.5 ms: growth dominates, speed swings have not yet detuned the mesh
    q3, q4 = (t > 0.0005) & (t <= 0.001), (t > 0.001) & (t <= 0.0015)
    measured = math.log(np.ptp(f[q4]) / np.ptp(f[q3])) / 0.0005
    assert measured == pytest.approx(sigma, rel=0.3)


def test_no_kv_unstable_when_damping_closes_the_tongue(quiet):
    m, eps, w = _mathieu_pair(0.2)
    assert 0.2 > 2 * eps / 4                                    # damping well above the tongue's threshold
    r = drivedyn.run(m)
    assert "kv-unstable" not in codes(r)
    assert r.summary["floquet_growth_rate"] == pytest.approx(w * (eps / 4 - 0.2), rel=0.25)   # same formula, < 0


def test_stable_pair_runs_clean(quiet):
    r = drivedyn.run(pair_model(**{"simulation.duration": 0.02}))
    assert r.status == "success", [d.line() for d in r.diagnostics]
    assert r.summary["floquet_growth_rate"] < 0


def test_seed_example_is_unstable_in_the_anti_phase_mode(quiet):
    """At 1450 rpm the linear model is unstable in the anti-phase mode (Floquet); exact symmetry
    keeps the example's run clean of it, a 0.001 deg clocking error grows at the Floquet rate."""
    sigma = floquet_growth(assemble(seed_model()), [seed_model().drive.speed], 5e-6)[0]
    assert sigma > 20
    r = drivedyn.run(seed_model(**{"meshes.m13.position_angle": math.radians(120.001),
                                   "simulation.duration": 0.1, "simulation.steady_window": None}))
    d = r.ds.mesh_force.values[:, 0] - r.ds.mesh_force.values[:, 1]       # the anti-phase part
    t = r.ds.time.values
    a1 = np.abs(d[(t > 0.04) & (t <= 0.06)]).max()
    a2 = np.abs(d[(t > 0.08) & (t <= 0.1)]).max()
    assert math.log(a2 / a1) / 0.04 == pytest.approx(sigma, rel=0.2)
    assert "kv-unstable" in codes(r)


def test_window_not_steady_on_the_old_window_not_on_the_example(quiet):
    """Counter-phase meshes excite the anti-phase mode, tau = 1/(zeta omega) from its modal damping:
    the seed's window 24-44 ms starts 0.7 tau into the run; the example's 150-200 ms, 4.3 tau."""
    anti = {"meshes.m13.position_angle": math.pi}
    s = assemble(seed_model(**anti))
    f, _, z = s.modes()
    tau = 1 / (z[0] * 2 * math.pi * f[0])
    old = drivedyn.run(seed_model(**anti, **{"simulation.duration": 0.05, "simulation.steady_window": [0.024, 0.044]}))
    assert "window-not-steady" in codes(old)
    assert old.summary["window_decay_times"] == pytest.approx(0.024 / tau, rel=1e-6)
    assert 0.024 / tau < DECAY_TIMES
    new = drivedyn.run(seed_model(**anti))
    assert new.summary["steady_window"] == pytest.approx([0.15, 0.2])
    assert new.summary["window_decay_times"] == pytest.approx(0.15 / tau, rel=1e-6)
    assert 0.15 / tau > DECAY_TIMES
    assert not any(d.quantity == "window_decay_times" for d in new.diagnostics)
    example = drivedyn.run(seed_model())
    assert "window-not-steady" not in codes(example) and "tooth-separation" not in codes(example)


def test_counter_phase_linear_meshes_report_tooth_separation(quiet):
    r = drivedyn.run(seed_model(**{"meshes.m13.position_angle": math.pi}))
    sep = [d for d in r.diagnostics if d.code == "tooth-separation"]
    assert sep and all(d.value < 0 == d.limit for d in sep) and "separation = true" in sep[0].text
    assert "warnings" not in r.summary


@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_solver_record_and_chunks_change_nothing(quiet, monkeypatch, method):
    m = pair_model(**{"simulation.method": method, "simulation.duration": 0.01})
    whole = drivedyn.run(m)
    rec = whole.summary["solver"]
    assert SOLVER_KEYS <= set(rec) and rec["method"] == method and rec["status"] == "success"
    assert rec["simulated_time"] == pytest.approx(0.01) and rec["rhs_evaluations"] >= 4 * rec["steps"]
    monkeypatch.setattr(simulate, "CHUNK_SECONDS", 1e-5)       # many small chunks
    calls = []
    chunked = drivedyn.run(m, progress=lambda f, t="": calls.append(f))
    assert len(calls) > 5
    assert chunked.summary["meshes"]["m"]["kv"] == whole.summary["meshes"]["m"]["kv"]
    assert chunked.summary["solver"]["steps"] == rec["steps"]


@pytest.mark.parametrize("exc", [drivedyn.core.errors.Stopped("case_timeout 1 s"), KeyboardInterrupt()])
@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_stop_keeps_partial_results(quiet, monkeypatch, exc, method):
    monkeypatch.setattr(simulate, "CHUNK_SECONDS", 1e-5)
    seen = []

    def progress(frac, info=""):
        seen.append(frac)
        if len(seen) == 4:
            raise exc

    with pytest.raises(drivedyn.SolverError) as err:
        drivedyn.run(pair_model(**{"simulation.method": method, "simulation.duration": 0.02}), progress=progress)
    part = err.value.partial
    assert part is not None and not part.success and part.status == "failed"
    rec = part.summary["solver"]
    assert rec["status"] == "failed" and 0 < rec["simulated_time"] < 0.02 and rec["steps"] > 0
    t = part.ds.time.values
    done = t <= rec["simulated_time"] * (1 - 1e-9)
    assert np.all(np.isfinite(part.ds.mesh_force.values[done])) and done.sum() > 2
    assert "stopped" in part.message


def test_sweep_marks_unstable_speeds_by_floquet(quiet):
    m = seed_model(**{"sweep.enabled": True, "sweep.count": 12, "sweep.settle": 0.01, "sweep.speed_min": 1400.0,
                      "sweep.speed_max": 1680.0, "simulation.duration": 0.01})
    r = drivedyn.run(m)
    s = assemble(m)
    sigma = floquet_growth(s, r.ds.sweep_speed.values, 5e-6)
    bad = r.ds.sweep_unstable.values[:, 0]
    assert bad.any() and np.array_equal(bad, sigma > 0)
    d = [x for x in r.diagnostics if x.code == "kv-unstable" and "sweep" in x.text]
    assert len(d) == 1 and "rpm" in d[0].text and d[0].value == pytest.approx(sigma.max())
    assert r.summary["sweep"]["meshes"]["m12"]["unstable_speeds"]
    assert r.units["sweep.meshes.m12.kv_max"] == "1" and r.units["meshes.m12.force_max"] == "N"
    # the reported maximum is over the speeds where the model holds only; the largest over every speed
    # (here in the unstable band) is kept beside it under its own name
    sm = r.summary["sweep"]["meshes"]["m12"]
    kv = r.ds.kv_sweep.values[:, 0]
    ok = ~bad & (r.ds.kv_min_sweep.values[:, 0] >= 0)
    assert sm["kv_max"] == pytest.approx(kv[ok].max()) and sm["kv_max_all_speeds"] == pytest.approx(np.nanmax(kv))
    assert sm["kv_max_all_speeds"] > sm["kv_max"]
    assert r.units["sweep.meshes.m12.speed_at_kv_max_all_speeds"] == "rad/s"


def test_plots_are_marked(quiet, tmp_path, monkeypatch):
    from drivedyn.core import plotting
    from drivedyn.gears.plots import plot_all

    marked = []
    monkeypatch.setattr(plotting, "mark_status", lambda fig, result: marked.append(result.status))
    r = drivedyn.run(seed_model(**{"meshes.m13.position_angle": math.pi, "simulation.duration": 0.02}))
    files = plot_all(r, tmp_path, workers=1)      # here, where the patch above holds
    assert len(marked) == len(files) and set(marked) == {"warning"}
