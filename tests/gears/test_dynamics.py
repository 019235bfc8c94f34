"""Dynamics against closed forms, the seed's published K_v, and convergence in the step."""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.gears.train.system import assemble

from .conftest import pair_model, seed_model

RB1, RB2 = 0.02625 * math.cos(math.radians(20)), 0.07125 * math.cos(math.radians(20))


def test_two_inertia_natural_frequency_closed_form(quiet):
    """f = sqrt(k (1/m1 + 1/m2)) / 2 pi with m_i = J_i / r_bi^2: eigenvalues and free vibration."""
    k = 449.9e6
    m1, m2 = 1.47e-4 / RB1 ** 2, 7.81e-3 / RB2 ** 2
    f_exact = math.sqrt(k * (1 / m1 + 1 / m2)) / (2 * math.pi)
    m = pair_model(**{"meshes.0.stiffness": {"model": "constant", "mean": k}, "meshes.0.damping_ratio": 0.0,
                      "simulation.start": "rest", "simulation.duration": 0.01, "simulation.step": 1e-6})
    assert assemble(m).modes()[0][0] == pytest.approx(f_exact, rel=1e-9)
    r = drivedyn.run(m)
    f = r.ds.mesh_force.sel(mesh="m").values
    t = r.ds.time.values
    up = np.flatnonzero((f[:-1] < f.mean()) & (f[1:] >= f.mean()))     # upward mean crossings
    f_sim = (len(up) - 1) / (t[up[-1]] - t[up[0]])
    assert f_sim == pytest.approx(f_exact, rel=2e-3)
    # undamped step load from rest: the force swings between 0 and twice the nominal
    assert r.summary["meshes"]["m"]["kv"] == pytest.approx(2.0, abs=0.01)


def test_kv_tends_to_1_at_low_speed_with_smooth_engagement(quiet):
    m = pair_model(**{"drive.speed": 3.0, "meshes.0.stiffness": {"model": "cai", "mean": 449.9e6, "engagement": 0.2},
                      "simulation.duration": 0.24, "simulation.step": 1e-5})
    assert drivedyn.run(m).summary["meshes"]["m"]["kv"] == pytest.approx(1.0, abs=0.01)


def test_low_speed_kv_of_a_stiffness_jump_closed_form(quiet):
    """Cai's pair enters at 0.55 K: at eps = 1.5 the mesh stiffness jumps from 0.95 K to 1.5 K, the
    deflection cannot follow at once, so even quasi-statically F_max / F = 1.5/0.95 = 1.5789 (why K_v
    does not tend to 1 with a discontinuous stiffness); half a free period later the force swings to
    F_min / F = 1 - 0.5789 exp(-zeta pi / sqrt(1 - zeta^2)) = 0.4390 at zeta = 0.01."""
    m = pair_model(**{"drive.speed": 3.0, "simulation.duration": 0.24, "simulation.step": 1e-6,
                      "meshes.0.damping_ratio": 0.01})
    s = drivedyn.run(m).summary["meshes"]["m"]
    assert s["kv"] == pytest.approx(1.5 / 0.95, rel=0.01)
    zeta = 0.01
    assert s["force_min"] / s["force_nominal"] == pytest.approx(
        1 - (1.5 / 0.95 - 1) * math.exp(-zeta * math.pi / math.sqrt(1 - zeta ** 2)), rel=0.01)


def test_seed_kv(quiet):
    """Seed 003 eqs. 16-17: K_v = 1.626 (mesh 1-2) and 1.647 (1-3), seed data, in-phase meshes."""
    r = drivedyn.run(seed_model())                               # the seed's step, 5e-6 s
    for mesh in ("m12", "m13"):
        assert r.summary["meshes"][mesh]["kv"] == pytest.approx(1.636, abs=0.03)
        assert r.summary["meshes"][mesh]["force_nominal"] == pytest.approx(1001.27, rel=2e-4)
        assert r.summary["meshes"][mesh]["load_share"] == pytest.approx(0.5, abs=1e-3)
    fine = drivedyn.run(seed_model(**{"simulation.step": 1.25e-6}))
    assert fine.summary["meshes"]["m12"]["kv"] == pytest.approx(1.626, abs=0.02)
    assert r.summary["natural_frequencies_hz"] == sorted(r.summary["natural_frequencies_hz"])


def test_convergence_in_step_and_methods_agree(quiet):
    kv = [drivedyn.run(seed_model(**{"simulation.step": h})).summary["meshes"]["m12"]["kv"]
          for h in (5e-6, 2.5e-6, 1.25e-6, 6.25e-7)]
    d = np.abs(np.diff(kv))
    assert d[1] < 0.5 * d[0] and d[2] < 0.5 * d[1]              # successive differences shrink
    assert d[2] < 2e-3
    ad = drivedyn.run(seed_model(**{"simulation.method": "dopri5", "simulation.rtol": 1e-9}))
    assert ad.summary["meshes"]["m12"]["kv"] == pytest.approx(kv[-1], rel=5e-3)


def test_counter_phase_meshes_report_separation(quiet):
    """Gears 180 deg apart on a 21-tooth pinion: meshes half a period apart excite the anti-phase mode."""
    m = seed_model(**{"meshes.m13.position_angle": math.pi})
    assert assemble(m).phase[1] == pytest.approx(0.5)
    r = drivedyn.run(m)
    assert "tooth-separation" in [d.code for d in r.diagnostics]
    assert min(v["force_min"] for v in r.summary["meshes"].values()) < 0
    ms = seed_model(**{"meshes.m13.position_angle": math.pi, "meshes.m12.separation": True,
                       "meshes.m13.separation": True, "meshes.m12.backlash": 1e-4, "meshes.m13.backlash": 1e-4})
    rs = drivedyn.run(ms)
    assert "tooth-separation" not in [d.code for d in rs.diagnostics]
    assert min(v["force_min"] for v in rs.summary["meshes"].values()) >= 0


def test_sweep_and_iso_beside_it(quiet):
    m = seed_model(**{"sweep.enabled": True, "sweep.count": 12, "sweep.settle": 0.01,
                      "sweep.speed_min": 5.0, "sweep.speed_max": 60.0})
    r = drivedyn.run(m)
    kv = r.ds.kv_sweep.values
    iso = r.ds.kv_iso_sweep.values
    assert kv.shape == (12, 2) and np.all(kv >= 1.0)
    assert np.all(np.diff(iso[:, 0]) > 0)                       # subcritical: K_v = 1 + N K grows with speed
    assert "sweep" in r.summary and r.summary["sweep"]["count"] == 12
