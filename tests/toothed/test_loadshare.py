"""Load sharing on a pulley and the jump torque (issue 15): closed forms, balances, limits,
convergence in the land discretisation, the exit path against the profiles' flank angles, and
bad input refused with one line."""
import json

import numpy as np
import pytest

import drivedyn
from drivedyn.front.cli import main
from drivedyn.mechanics.teeth.loadshare import Chain, climb_factor, flank_angle, jump_torque, solve, span_tensions, teeth_in_mesh, tooth_stiffness_per_width

from .conftest import DEG, make_pair


def _chain(**kw):
    base = dict(teeth=12, pitch=9.525e-3, radius=0.03, tooth_stiffness=2e5, cord_stiffness=1.5e5)
    return Chain(**{**base, **kw})


def _shear_lag(n, lam, tau0, taun):
    """Tooth loads of the linear chain from its recurrence tau_(i-1) - (2 + lam) tau_i + tau_(i+1) = 0
    (tau_i = T_i - T_ref, lam = k_t / k_c): tau_i = A r^i + B r^-i with r the root < 1 of
    r^2 - (2 + lam) r + 1 = 0, A and B from tau_0 and tau_n; Q_i = tau_(i-1) - tau_i."""
    r = np.min(np.roots([1.0, -(2.0 + lam), 1.0]).real)
    A, B = np.linalg.solve([[1.0, 1.0], [r ** n, r ** -n]], [tau0, taun])
    i = np.arange(n + 1)
    tau = A * r ** i + B * r ** -i
    return tau[:-1] - tau[1:], r


@pytest.mark.parametrize("n, kt, T1, T2, Tref", [(12, 2e5, 500.0, 100.0, 300.0), (5, 3e6, 800.0, 20.0, 100.0),
                                                 (30, 5e4, 260.0, 140.0, 200.0)])
def test_linear_chain_matches_the_closed_form(n, kt, T1, T2, Tref):
    ch = _chain(teeth=n, tooth_stiffness=kt)
    q, _ = _shear_lag(n, kt / (ch.cord_stiffness / ch.pitch), T1 - Tref, T2 - Tref)
    sh = solve(ch, T1, T2, Tref)
    assert np.allclose(sh.tooth_load, q, rtol=1e-9, atol=1e-9 * T1)


def test_a_belt_sinking_into_its_support_softens_the_cord_as_the_moving_polygon_says():
    """eq. 4: a cord sunk by delta = T / (R k_r) spans p / (R - delta) of the pulley per pitch, so
    that on the pitch circle a pitch is p R / (R - delta): the recurrence's k_c is p over the pitch's
    growth per newton there, d/dT (p R / (R - T / (R k_r))) at T_ref (first order in delta / R, which
    is 4e-5 here), in series with the cord's p / EA."""
    R, k_r, Tref = 0.03, 2e8, 300.0
    ch = _chain(radial_stiffness=k_r)
    sink = ch.pitch * R / (R * k_r) / R ** 2       # d/dT of p R / (R - T / (R k_r)) at delta << R
    k_c = 1.0 / (ch.pitch / ch.cord_stiffness + sink) * ch.pitch
    q, _ = _shear_lag(12, ch.tooth_stiffness / (k_c / ch.pitch), 500.0 - Tref, 100.0 - Tref)
    sh = solve(ch, 500.0, 100.0, Tref)
    assert np.allclose(sh.tooth_load, q, rtol=1e-9, atol=1e-9 * 500.0)
    rigid = solve(_chain(), 500.0, 100.0, Tref)
    assert sh.tooth_load[0] > rigid.tooth_load[0] * 1.05   # a softer cord loads the entry tooth more


def test_load_decays_geometrically_from_the_entry_tooth():
    # slack end at the reference tension: only the tight end loads its teeth, Q_(i+1) / Q_i -> r
    ch = _chain(teeth=40, tooth_stiffness=1e6)
    sh = solve(ch, 400.0, 200.0, 200.0)
    _, r = _shear_lag(40, ch.tooth_stiffness * ch.pitch / ch.cord_stiffness, 200.0, 0.0)
    ratios = sh.tooth_load[1:10] / sh.tooth_load[:9]
    assert np.allclose(ratios, r, rtol=1e-6)
    assert 0 < r < 1 and sh.tooth_load[0] == sh.tooth_load.max()


@pytest.mark.parametrize("kw", [{}, {"friction": 0.3, "land_nodes": 6}, {"clearance": 2e-4},
                                {"pitch_error": 5e-5, "clearance": 1e-4, "friction": 0.2}])
def test_tooth_loads_and_land_friction_sum_to_the_tension_difference(kw):
    sh = solve(_chain(**kw), 520.0, 80.0, 300.0)
    total = sh.tooth_load.sum() + sh.land_friction.sum()
    assert total == pytest.approx(440.0, rel=1e-9)
    if not kw.get("friction"):
        assert sh.tooth_load.sum() == pytest.approx(440.0, rel=1e-9)
    else:
        assert sh.land_friction.sum() > 0      # the lands carry part of it


def test_rigid_teeth_first_tooth_takes_all():
    # rigid teeth: the cord between teeth stays at T_ref; tooth 1 takes T1 - T_ref, tooth n T_ref - T2
    sh = solve(_chain(tooth_stiffness=1e13), 500.0, 100.0, 300.0)
    assert sh.tooth_load[0] == pytest.approx(200.0, rel=1e-5)
    assert sh.tooth_load[-1] == pytest.approx(200.0, rel=1e-5)
    assert np.all(np.abs(sh.tooth_load[1:-1]) < 1e-3)
    sh = solve(_chain(tooth_stiffness=1e13), 500.0, 100.0, 100.0)  # pitch matched at the slack tension
    assert sh.tooth_load[0] == pytest.approx(400.0, rel=1e-5) and sh.tooth_load[1:].sum() < 1e-3


def test_rigid_cord_shares_equally():
    sh = solve(_chain(cord_stiffness=1e14), 500.0, 100.0, 300.0)
    assert np.allclose(sh.tooth_load, 400.0 / 12, rtol=1e-6)


def test_uniform_play_does_not_change_the_sharing():
    # without pitch error every tooth crosses the same play: the cord strains are unchanged
    a = solve(_chain(friction=0.2, land_nodes=4), 500.0, 100.0, 300.0)
    b = solve(_chain(friction=0.2, land_nodes=4, clearance=1.7e-4), 500.0, 100.0, 300.0)
    assert np.allclose(a.tooth_load, b.tooth_load, rtol=1e-6)


def test_pitch_error_with_play_unloads_the_slack_end():
    # a belt longer than the grooves (e > 0) bears on the tight-side teeth; with a play larger than
    # the accumulated error the slack-side teeth float free
    sh = solve(_chain(pitch_error=1.1e-4, clearance=1.1e-3), 500.0, 100.0, 300.0)
    assert sh.tooth_load[0] == sh.tooth_load.max()
    assert np.all(np.abs(sh.tooth_load[-4:]) < 1e-3)


def test_land_friction_converges_with_the_land_discretisation():
    loads = {m: solve(_chain(friction=0.4, land_nodes=m, land_share=0.6), 600.0, 50.0, 300.0).tooth_load
             for m in (1, 2, 4, 8, 16, 64)}
    ref = loads[64]
    err = [np.max(np.abs(loads[m] - ref)) for m in (1, 2, 4, 8, 16)]
    assert all(b < a for a, b in zip(err, err[1:]))
    assert err[-1] < 0.3 * err[-2] and err[-1] < 1e-3 * ref.max()   # about second order (midpoints)


def test_jump_torque_of_one_tooth_is_the_wedge_balance():
    # one tooth: Q = T1 - T2 = M / R, T_local = T0, so (3) gives M = T0 p / tan(phi - rho)
    ch = _chain(teeth=1)
    f = climb_factor(20 * DEG, 0.1)
    assert jump_torque(ch, 300.0, f) == pytest.approx(300.0 * ch.pitch / f, rel=1e-5)
    assert jump_torque(ch, 300.0, climb_factor(20 * DEG, 0.5)) is None   # self-locking: rho > phi


def test_jump_torque_grows_with_installation_tension_and_ends_where_the_slack_side_does():
    ch = _chain(teeth=10)
    f = climb_factor(20 * DEG, 0.0)
    m = [jump_torque(ch, t, f) for t in (100.0, 200.0, 400.0)]
    assert m[0] < m[1] < m[2]
    assert all(x <= 2 * t * ch.radius * (1 + 1e-6) for x, t in zip(m, (100.0, 200.0, 400.0)))
    assert span_tensions(m[1], 200.0, ch.radius)[1] >= 0


@pytest.mark.parametrize("profile, z, groove_half_angle", [("L", 20, 20), ("T10", 20, 25), ("XL", 20, 25)])
def test_exit_path_follows_the_straight_flank(profile, z, groove_half_angle):
    # a straight-flanked tooth in a straight-flanked groove at least as open slides out along the
    # groove flank: the exit path's slope is the groove's half-angle (ISO 5294 / DIN 7721-2 tables)
    phi = flank_angle(make_pair(profile, z=z))
    assert np.degrees(phi) == pytest.approx(groove_half_angle, abs=0.05)


@pytest.mark.parametrize("profile, z", [("HTD9.525", 19), ("HTD8M", 22), ("HTD8M", 44), ("L", 20), ("T10", 20)])
def test_exit_path_by_rays_is_conservative_advancements(profile, z):
    """The exit path as check finds it (the first contact of the translated polygons, vertex against
    edge) against conservative advancement to 1e-9 m (the slow reference, 20-40 x its cost): the same
    free lifts, the path within 2e-8 m (measured 1.1e-8 m: the reference's 1e-9 m gap along the flank
    normal), the flank angle within 2e-5 rad and the play within 2e-8 m."""
    from drivedyn.mechanics.teeth.loadshare import exit_path

    pair = make_pair(profile, z=z, tol=2e-7)
    ref, fast = exit_path(pair, method="advance"), exit_path(pair)
    assert np.array_equal(np.isfinite(ref[1]), np.isfinite(fast[1]))
    on = np.isfinite(ref[1])
    assert np.max(np.abs(ref[1][on] - fast[1][on])) < 2e-8
    assert flank_angle(pair, path=fast) == pytest.approx(flank_angle(pair, path=ref), abs=2e-5)
    assert fast[1][0] == pytest.approx(ref[1][0], abs=2e-8)


def test_tooth_stiffness_scales_with_shape_not_size():
    a = tooth_stiffness_per_width(make_pair("HTD8M").tooth, 1.0)
    b = tooth_stiffness_per_width(make_pair("HTD9.525", z=24).tooth, 1.0)
    assert a == pytest.approx(b, rel=1e-5)
    assert teeth_in_mesh(20, np.pi) == 10 and teeth_in_mesh(7, 0.1) == 1


def test_load_example_runs_and_writes_results(tmp_path):
    code = main(["run", str(drivedyn.example_path("mesh-load-l")), "-o", str(tmp_path), "-q"])
    assert code == 0
    doc = json.loads((tmp_path / "summary.json").read_text())
    ld = doc["load"]
    assert doc["status"] == "success" and not doc["diagnostics"]        # 5 N m is below the jump torque
    assert sum(ld["tooth_loads_N"]) + ld["land_friction_N"] == pytest.approx(ld["tight_tension_N"] - ld["slack_tension_N"])
    assert doc["units"]["load.jump_torque_N_m"] == "N*m" and doc["units"]["load.tooth_loads_N"] == "N"
    assert 5.0 < ld["jump_torque_N_m"] < 2 * 200.0 * 30.3e-3
    assert (tmp_path / "mesh-load.png").stat().st_size > 10_000
    assert "mesh-load.png" in (tmp_path / "report.html").read_text()


def test_tooth_jump_diagnostic_fires_above_the_jump_torque(tmp_path):
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("mesh-load-l")),
                         {"load.torque": 15.0, "load.tensions": [200.0], "mesh.angles": 21})
    r = drivedyn.run(m)
    assert r.status == "warning" and [d.code for d in r.diagnostics] == ["tooth-jump"]
    d = r.diagnostics[0]
    assert d.value == 15.0 and d.limit == pytest.approx(r.summary["load"]["jump_torque_N_m"]) and d.limit < 15.0


BAD = [
    ({"cord_stiffness": None}, "load.cord_stiffness"),                 # L: no source gives EA
    ({"tooth_stiffness": "8 N/mm/mm"}, "tooth_stiffness"),              # both tooth data given
    ({"width": "-25 mm"}, "load.width"),
    ({"land_nodes": 0}, "load.land_nodes"),
    ({"friction": -0.1}, "load.friction"),
    ({"tensions": ["100 N"] * 51}, "load.tensions"),
    ({"installation_tension": "1e6 N"}, "load.installation_tension"),
    ({"pitch_error": "6 mm"}, "load.pitch_error"),
    ({"torque": "3 kg"}, "load.torque"),
]


@pytest.mark.parametrize("change, field", BAD)
def test_bad_load_input_is_one_line_exit_2(tmp_path, capsys, change, field):
    import tomllib

    import tomli_w

    data = tomllib.loads(drivedyn.example_path("mesh-load-l").read_text())
    for k, v in change.items():
        if v is None:
            data["load"].pop(k)
        else:
            data["load"][k] = v
    path = tmp_path / "m.toml"
    path.write_bytes(tomli_w.dumps(data).encode())
    code = main(["check", str(path)])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and field in err, err


def test_mixed_pair_at_equal_pitch_concentrates_the_load():
    # L belt on the HTD groove scaled to 9.525 mm: PLD 0.817 vs 0.381 mm makes the belt 0.114 mm per
    # tooth longer than the groove spacing (z = 24) and the groove leaves 1.1 mm of play: the load
    # gathers on the tight-side teeth, against near-equal sharing on the matched L pair
    base = drivedyn.load(drivedyn.example_path("mesh-load-l"))
    out = {}
    for pulley in ("L", "HTD9.525"):
        m = drivedyn.replace(base, {"pulley.profile": pulley, "pulley.teeth": 24, "load.tensions": [200.0],
                                    "mesh.angles": 21})
        out[pulley] = drivedyn.run(m).summary["load"]
    assert out["HTD9.525"]["pitch_error_mm"] == pytest.approx(2 * np.pi * (0.686 * 9.525 / 8 - 0.381) / 24, rel=1e-6)
    assert out["HTD9.525"]["first_tooth_share"] > 3 * out["L"]["first_tooth_share"]
    assert out["HTD9.525"]["seated_play_mm"] > 5 * out["L"]["seated_play_mm"]
    assert out["L"]["seated_play_mm"] == pytest.approx(0.172, abs=2e-3)   # mesh-l: 0.172 mm horizontal per flank
